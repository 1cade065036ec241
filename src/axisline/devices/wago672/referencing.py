"""Reference runs of the 750-672 (manual §3.11.1.5, §3.11.3.1; wago.md §2.4).

The manual gives the rules in words and the motions only as missing figures (Fig. 3.11.1-4 ..
-14). The rules held strictly:

* the run goes at SetupSpeed (addr 44) with SetupAcceleration (addr 62); SetupSpeed 0 is 1453;
* a start at the limit switch of the start direction does not move (cyclic image: Err_Range_Pos
  or _Neg is set, no error; mailbox START_REFERENCING: return code 0x23);
* a start on the reference switch first moves the other way until the switch is free;
* a limit switch before the reference switch reverses the search; a second one ends the run
  with an error (1451 REF_SWITCH_NOT_FOUND); both limit switches at once: 1452;
* the reference value Reference_Offset (addr 108, position units) is taken at the edge; the
  edge is always approached from the same end;
* software limit switches are not watched during the run.

[RECONSTRUCTED] motion (wago.md §2.4, as proposed there): the edge E (Reference_Mode bit 1 /
START_REFERENCING DIR: 1 positive end, 0 negative end) is latched when the drive *leaves* the
reference switch moving in direction E. If the switch was entered moving in E the drive runs
through it, otherwise it ramps down, turns and crosses it in direction E. After the edge it
brakes with SetupAcceleration; the actual position is the reference value at the edge plus the
braking distance. A reference run to a limit switch latches at the switch's rising edge, brakes
with Acceleration_Stop_Fast and stays on the switch, in the "special mode" of §3.11.3.1 (the
drive may then leave it in any mode; the mode ends 100 ms after it has left the switch). A limit
switch of the other direction during a limit-switch run, or any limit switch in the direction of
travel once the reference switch has been found, is 1455 ERROR_REF_LIM_SWITCH_NOT_EXPECTED.
"""

from __future__ import annotations

from enum import Enum
from typing import Protocol

from axisline.motion.profiles import State

__all__ = ["RefPhase", "RefRun", "RefDrive"]


class RefPhase(Enum):
    FREE = "leave the reference switch"
    SEARCH = "search"
    TURN = "brake at a limit switch and turn"
    APPROACH = "approach the edge"
    BRAKE = "brake after the edge"
    DONE = "done"
    FAILED = "failed"
    BLOCKED = "blocked at a limit switch"


class RefDrive(Protocol):
    """What a reference run may ask of the module (all speeds/positions in microsteps)."""

    def ref_velocity(self, velocity: float, acceleration: float) -> None: ...
    def ref_stop_fast(self) -> None: ...
    def ref_state(self) -> State: ...
    def ref_at_rest(self) -> bool: ...
    def ref_edge(self, edge_position: float) -> None: ...
    def ref_finish(self, edge_position: float, on_limit_switch: int) -> None: ...
    def ref_fail(self, code: int, text: str) -> None: ...


class RefRun:
    """One reference run. direction D: +1/-1 (start direction, or which limit switch);
    to_limit_switch: Reference_Mode bit 0 / SWT; edge E: +1 positive end, -1 negative end."""

    def __init__(self, drive: RefDrive, direction: int, to_limit_switch: bool, edge: int, speed: float, acceleration: float) -> None:
        self.drive = drive
        self.direction = direction
        self.to_limit_switch = to_limit_switch
        self.edge = edge
        self.speed = speed
        self.acceleration = acceleration
        self.phase = RefPhase.SEARCH
        self._dir = direction  # current search direction
        self._reversed = False
        self._prev_ref = False
        self._prev_ls = (False, False)
        self._edge_p = 0.0

    @property
    def active(self) -> bool:
        return self.phase not in (RefPhase.DONE, RefPhase.FAILED, RefPhase.BLOCKED)

    def _limit(self, d: int, lsp: bool, lsn: bool) -> bool:
        return lsp if d > 0 else lsn

    def start(self, ref: bool, lsp: bool, lsn: bool) -> bool:
        """Begin the run; False if it cannot move (at the limit switch of the start direction)."""
        if lsp and lsn:
            self.phase = RefPhase.FAILED
            self.drive.ref_fail(1452, "both limit switches are active at the start of the reference run")
            return False
        if self._limit(self.direction, lsp, lsn):
            self.phase = RefPhase.BLOCKED
            return False
        self._prev_ref = ref
        self._prev_ls = (lsp, lsn)
        if not self.to_limit_switch and ref:
            self.phase = RefPhase.FREE  # on the switch: free it first, against the start direction
            self.drive.ref_velocity(-self.direction * self.speed, self.acceleration)
        else:
            self.phase = RefPhase.SEARCH
            self.drive.ref_velocity(self.direction * self.speed, self.acceleration)
        return True

    def step(self, ref: bool, lsp: bool, lsn: bool) -> None:
        """One tick with this tick's switch states (they show the set point of the last tick)."""
        d = self.drive
        if lsp and lsn and self.active and self.phase is not RefPhase.BRAKE:
            self._fail(1452, "both limit switches are active during the reference run")
            return
        rising = ref and not self._prev_ref
        falling = self._prev_ref and not ref
        self._prev_ref = ref
        ls_rising = (lsp and not self._prev_ls[0], lsn and not self._prev_ls[1])
        self._prev_ls = (lsp, lsn)
        st = d.ref_state()
        moving = 1 if st.v > 0.0 else -1 if st.v < 0.0 else 0
        if self.phase is RefPhase.FREE:
            if self._limit(-self.direction, lsp, lsn):
                self._fail(1451, "limit switch reached while freeing the reference switch")
            elif not ref:
                self.phase = RefPhase.SEARCH
                d.ref_velocity(self.direction * self.speed, self.acceleration)
        elif self.phase is RefPhase.SEARCH:
            if self.to_limit_switch:
                if ls_rising[0 if self.direction < 0 else 1]:
                    self._fail(1455, "the limit switch of the other direction became active")
                elif self._limit(self.direction, lsp, lsn):
                    self._edge_p = st.p
                    d.ref_edge(st.p)
                    self.phase = RefPhase.BRAKE
                    d.ref_stop_fast()
            elif rising or (ref and moving == self._dir):
                self.phase = RefPhase.APPROACH
                if self._dir != self.edge:  # entered against E: turn and cross it in direction E
                    d.ref_velocity(self.edge * self.speed, self.acceleration)
            elif self._limit(self._dir, lsp, lsn):
                if self._reversed:
                    self._fail(1451, "reference switch not found between the limit switches")
                else:
                    self.phase = RefPhase.TURN
                    d.ref_stop_fast()
        elif self.phase is RefPhase.TURN:
            if d.ref_at_rest():
                self._dir = -self._dir
                self._reversed = True
                self.phase = RefPhase.SEARCH
                d.ref_velocity(self._dir * self.speed, self.acceleration)
        elif self.phase is RefPhase.APPROACH:
            if moving != 0 and self._limit(moving, lsp, lsn):
                self._fail(1455, "limit switch reached while approaching the reference edge")
            elif falling and moving == self.edge:
                self._edge_p = st.p  # the set point the plant followed when the edge was seen
                d.ref_edge(st.p)
                self.phase = RefPhase.BRAKE
                d.ref_velocity(0.0, self.acceleration)
        elif self.phase is RefPhase.BRAKE:
            if d.ref_at_rest():
                self.phase = RefPhase.DONE
                d.ref_finish(self._edge_p, self.direction if self.to_limit_switch else 0)

    def _fail(self, code: int, text: str) -> None:
        self.phase = RefPhase.FAILED
        self.drive.ref_fail(code, text)

    def __repr__(self) -> str:
        kind = "limit switch" if self.to_limit_switch else f"reference switch, edge {self.edge:+d}"
        return f"RefRun({kind}, direction {self.direction:+d}, {self.phase.name})"
