"""CLM1.4 homing options 1-5 (manual §7.9, L3694-3803; Ax23-Ax25, L4688-4754) as kernel
homing procedures on the encoder's index pulse (the marker) and the home switch cam.

    proc = ClmHoming(option=1, cam=lambda: image.get(home_switch), marker=EncoderMarker(unit),
                     direction=-1, v1=100.0, accel=5000.0, increment=10/4096, cycle_s=0.002,
                     revolution=10.0, offset=Fraction(0), on_reference=loop.resync)
    kernel_axis.home(proc)                 # HOMING; ClmAxis.tick polls proc.error / completion

The procedure runs in the kernel axis' HOMING state (`motion.homing`): each cycle it sees the
set point of the previous cycle next to this cycle's inputs (the cam through the CLM's process
image, the marker through the encoder's index pulse of the last plant step). Speeds (legend of
Fig. 7-17, L3730-3738): V1 = Ax24 per mille of Ax06, V2 = V1 / 4, V3 = 10 increments per NC
cycle, V4 = 1 increment per NC cycle; an increment is Ax01 (x Y/X) / (Ax19 pulses x 4).

A failure raises `ClmHomingError` with the axis fault offset (0x09 cam too short, 0x0A no
marker pulse, 0x0B marker pulse position, 0x0F marker high); the kernel axis goes to
ERROR_STOP and `ClmAxis.tick` reports the CLM fault (49/4A/4B/4F for axis 1).

Decisions (spec line -> choice, why)
------------------------------------
1. Option 1 sequence (L3742-3746, errata §3.9) -> V1 in the Ax24 direction d to the cam; on the
   cam: reverse, leave it at V2 (the actual position where the cam input drops is the cam
   switching point E); reverse, back onto the cam at V3; markers before E are not evaluated
   (the home must not depend on the braking distance); the first marker after E is M; reverse,
   V4 to M, stop; the reference makes M = -Ax25. Test:
   tests/devices/clm/test_homing.py::test_option_1_sequence_speeds_and_reference.
2. Cam-marker distance (L3752-3756, "X = > 1/16 and < 15/16 Feed Constant" L3738) -> X = (M - E)
   x d; X <= 1/16 or >= 15/16 of an encoder revolution -> 4B. Test: test_marker_too_close_to_the_cam_is_4b.
3. "No marker pulse within one encoder revolution" (L3766) -> more than one revolution past E
   at V3 without a marker -> 4A. Test: test_no_marker_is_4a.
4. "Marker high" (errata §3.9; 4F) -> the marker input reads active in the first cycle of the
   V3 search (the axis at rest) or in two consecutive V3 cycles (a marker is about one
   increment wide, V3 passes 10 a cycle). Test: test_stuck_marker_is_4f.
5. "Cam too short" (49) -> the cam input drops while the axis moves in the search direction on
   the cam (braking from V1 through the cam, or passing the whole cam at V3 without a marker
   after E). Test: test_cam_too_short_is_49.
6. Homing offset sign (errata §1 "the homing offset sign", §3.9 "the reference gets -Ax25";
   L3556 "+00010.000 ... the zero point is defined at 10 degrees") -> the marker (option 2) or
   the switch edge (options 3/4) gets the coordinate -Ax25, so the zero point lies Ax25 from it.
   Test: test_option_1_sequence_speeds_and_reference.
7. Option 2 (L3775-3779) "a positioning move in the same direction ... to a position 1/32
   revolution before the second marker" (its speed not given) -> continues at V3 to one
   revolution - 1/32 past the first marker, then V4 onto the second. Test: test_option_2_marker_only.
8. Options 3/4 (L3787-3795) -> V1 in direction d until the rising edge of the switch (option 4
   first leaves a switch it stands on, against d); the actual position at the edge cycle gets
   -Ax25 and the axis brakes to rest behind it. Test: test_option_3_and_4_switch_edge.
9. Option 5, passive homing (L3797-3803; Ax24 type 4, flying cutoff only, L4741) -> no
   procedure runs (HOM is 52): while the axis is not homed and its drive is enabled, the cycle
   in which the home switch drops while the set point moves forward (Jog Forward in Manual, the
   synchronized carriage in Automatic) or rises while it moves in reverse (Jog Reverse, Manual
   only: L3799 names Manual; the reverse case starts *off* the switch as §7.9 says, not "located
   at" it as the Ax24 text has it, spec §12.3 item 10) makes the actual position -Ax25 (as options 3/4: Ax25 is negative
   in flying cutoff, L4754, so the zero point lies |Ax25| behind the switch edge) and sets the
   Homed output. Once homed, passing the switch again changes nothing (a carriage re-referenced
   at every return would shift its cut positions mid-run); the reference is lost as for every
   option (Lag / Runaway, Parameter mode). Test: tests/devices/clm/test_homing.py::
   test_option_5_passive_homing_on_the_switch_edges.
"""

from __future__ import annotations

from collections.abc import Callable
from fractions import Fraction
from typing import Any

from axisline.motion.homing import HomingAxis, HomingError, HomingProcedure

__all__ = ["ClmHoming", "ClmHomingError", "EncoderMarker"]

CAM_TOO_SHORT, NO_MARKER, MARKER_POSITION, MARKER_HIGH = 0x09, 0x0A, 0x0B, 0x0F


class ClmHomingError(HomingError):
    def __init__(self, offset: int, text: str) -> None:
        super().__init__(text)
        self.offset = offset


class EncoderMarker:
    """The marker input of a CLM axis: the plant encoder's index pulse, in the axis frame.

    ``active()``: an index pulse passed during the last plant step; ``position()``: where, to
    the increment as the CLM counts it (axis frame = plant + position offset)."""

    def __init__(self, unit: Any) -> None:
        self.unit = unit

    def active(self) -> bool:
        enc = self.unit.encoder
        return enc is not None and enc.index_every_units is not None and enc.index_pulses > 0

    def arm(self) -> None:
        """Latch the next index pulse (its position is only kept when armed)."""
        enc = self.unit.encoder
        if enc is not None:
            enc.arm_index()

    def position(self) -> float:
        """The latched marker to the increment, axis frame; the latch is armed again."""
        enc = self.unit.encoder
        x = enc.index_position
        enc.arm_index()
        return enc.counts_at(x) / enc.counts_per_unit * self.unit.feedback_sign + self.unit.axis.position_offset


class ClmHoming(HomingProcedure):
    """Homing options 1-4 (Ax24 type digits 0-3); see the module docstring."""

    (_TO_CAM, _CAM_BRAKE, _LEAVE, _LEAVE_BRAKE, _SEARCH, _SEARCH_BRAKE, _APPROACH, _FINAL_BRAKE,
     _EDGE_LEAVE, _EDGE_LEAVE_BRAKE, _EDGE_SEARCH, _DONE) = range(12)

    def __init__(self, *, option: int, cam: Callable[[], bool], marker: Any, direction: int, v1: float,
                 accel: float, increment: float, cycle_s: float, revolution: float, offset: Fraction,
                 kernel_axis: Any, on_reference: Callable[[], None] | None = None) -> None:
        if option not in (1, 2, 3, 4):
            raise ValueError(f"homing option 1-4, not {option}")
        self.option = option
        self.cam = cam
        self.marker = marker
        self.d = 1 if direction >= 0 else -1
        self.v1 = float(v1)
        self.accel = float(accel)
        self.v3 = 10 * increment / cycle_s
        self.v4 = increment / cycle_s
        self.increment = float(increment)
        self.revolution = float(revolution)
        self.offset = offset
        self.kernel_axis = kernel_axis
        self.on_reference = on_reference
        self.phase = self._DONE
        self.phases: list[tuple[str, float]] = []  # (phase name, commanded velocity): what a test checks
        self.edge: float | None = None  # E: the cam switching point (actual position)
        self.mark: float | None = None  # M: the marker (or switch edge) position
        self.error: ClmHomingError | None = None
        self._cam_was = False
        self._marker_was = False
        self._first_search_cycle = False
        self._passed_edge = False
        self._goal: float | None = None

    # -- helpers ---------------------------------------------------------------------------

    def _run(self, axis: HomingAxis, phase: int, name: str, velocity: float) -> None:
        self.phase = phase
        self.phases.append((name, velocity))
        axis.homing_move_velocity(velocity, self.accel)

    def _halt(self, axis: HomingAxis, phase: int) -> None:
        self.phase = phase
        axis.homing_halt(self.accel)

    def _fail(self, offset: int, text: str) -> None:
        self.error = ClmHomingError(offset, text)
        raise self.error

    @property
    def _actual(self) -> float:
        return float(self.kernel_axis.actual_position)

    # -- the procedure ---------------------------------------------------------------------

    def start(self, axis: HomingAxis) -> None:
        self.phases.clear()
        self.edge = self.mark = None
        self.error = None
        cam = bool(self.cam())
        self._cam_was = cam
        d = self.d
        if self.option == 1:
            if cam:  # 3.) on the cam at the start: leave it at V2 (L3746)
                self._run(axis, self._LEAVE, "leave cam at V2", -d * self.v1 / 4)
            else:  # 1.) to the cam at V1 (L3742)
                self._run(axis, self._TO_CAM, "to cam at V1", d * self.v1)
        elif self.option == 2:
            self._start_search(axis)
        elif self.option == 4 and cam:  # first off the switch (L3793)
            self._run(axis, self._EDGE_LEAVE, "leave switch at V1", -d * self.v1)
        else:
            self._run(axis, self._EDGE_SEARCH, "to switch at V1", d * self.v1)

    def _start_search(self, axis: HomingAxis) -> None:
        self._first_search_cycle = True
        self._marker_was = False
        self._passed_edge = self.option == 2 or self.edge is None
        self._origin = self._actual
        arm = getattr(self.marker, "arm", None)
        if arm is not None:
            arm()
        self._run(axis, self._SEARCH, "marker search at V3", self.d * self.v3)

    def step(self, axis: HomingAxis) -> bool:
        cam = bool(self.cam())
        rising = cam and not self._cam_was
        falling = self._cam_was and not cam
        self._cam_was = cam
        d, p = self.d, self.phase
        if p == self._TO_CAM:
            if cam:
                self._halt(axis, self._CAM_BRAKE)
        elif p == self._CAM_BRAKE:
            if falling:
                self._fail(CAM_TOO_SHORT, "the home switch cam dropped while braking onto it from V1 (L3762)")
            if axis.motion_ended:
                self._run(axis, self._LEAVE, "leave cam at V2", -d * self.v1 / 4)
        elif p == self._LEAVE:
            if not cam:
                self.edge = self._actual
                self._halt(axis, self._LEAVE_BRAKE)
        elif p == self._LEAVE_BRAKE:
            if axis.motion_ended:
                self._start_search(axis)
        elif p == self._SEARCH:
            self._search(axis, cam, falling)
        elif p == self._SEARCH_BRAKE:
            if axis.motion_ended:
                self._run(axis, self._APPROACH, "onto marker at V4", -d * self.v4)
        elif p == self._APPROACH:
            assert self.mark is not None
            if (axis.command_position - self.mark) * d <= self.increment / 2:
                self._halt(axis, self._FINAL_BRAKE)
        elif p == self._FINAL_BRAKE:
            if axis.motion_ended:
                return self._reference(axis)
        elif p == self._EDGE_LEAVE:
            if not cam:
                self._halt(axis, self._EDGE_LEAVE_BRAKE)
        elif p == self._EDGE_LEAVE_BRAKE:
            if axis.motion_ended:
                self._cam_was = bool(self.cam())
                self._run(axis, self._EDGE_SEARCH, "to switch at V1", d * self.v1)
        elif p == self._EDGE_SEARCH:
            if rising:
                self.mark = self._actual
                self._halt(axis, self._FINAL_BRAKE)
        return self.phase == self._DONE

    def _search(self, axis: HomingAxis, cam: bool, falling: bool) -> None:
        """V3 in the search direction until the first marker after E (decisions 1-5, 7)."""
        d = self.d
        marker = bool(self.marker.active())
        if marker and (self._first_search_cycle or self._marker_was):
            self._fail(MARKER_HIGH, "the marker pulse input is continuously active (4F)")
        self._first_search_cycle = False
        self._marker_was = marker
        if self.option == 1:
            if not self._passed_edge:
                if cam:
                    self._passed_edge = True
                return  # markers before the cam switching point are not evaluated
            if falling:
                self._fail(CAM_TOO_SHORT, "the cam ended during the marker search (L3762)")
            assert self.edge is not None
            travelled = (self._actual - self.edge) * d
            if marker:
                m = self.marker.position()
                x = (m - self.edge) * d / self.revolution
                if not (Fraction(1, 16) < x < Fraction(15, 16)):
                    self._fail(MARKER_POSITION, f"the marker is {x:.4f} revolution from the cam switching point; "
                               "allowed 1/16..15/16: shift the home switch by 1/3 of the feed constant (L3752-3756)")
                self.mark = m
                self._halt(axis, self._SEARCH_BRAKE)
            elif travelled > self.revolution + 10 * self.increment:
                self._fail(NO_MARKER, "no marker pulse within one encoder revolution of the cam (L3766)")
            return
        # option 2: the first marker, then to 1/32 revolution before the second, then V4
        travelled = (self._actual - self._origin) * d
        if self.mark is None:
            if marker:
                self.mark = self.marker.position()
                self._goal = self.mark + d * self.revolution * (1 - 1 / 32)
            elif travelled > self.revolution + 10 * self.increment:
                self._fail(NO_MARKER, "no marker pulse within one encoder revolution (L3766)")
        elif self._goal is not None and (axis.command_position - self._goal) * d >= 0:
            self._goal = None
            self.phases.append(("second marker at V4", d * self.v4))
            axis.homing_move_velocity(d * self.v4, self.accel)
            self._first_search_cycle = False
        elif self._goal is None and marker:
            self.mark = self.marker.position()
            self._halt(axis, self._SEARCH_BRAKE)
            self.phase = self._FINAL_BRAKE  # V4 is within one increment: no way back

    def _reference(self, axis: HomingAxis) -> bool:
        """The marker (or edge) becomes -Ax25 (decision 6)."""
        assert self.mark is not None
        axis.homing_set_position(float(-self.offset) - self.mark, relative=True)
        if self.on_reference is not None:
            self.on_reference()
        self.phase = self._DONE
        return True

    def __repr__(self) -> str:
        return f"ClmHoming(option={self.option}, direction={self.d:+d}, v1={self.v1:g})"
