"""What the 750-672 watches and reports each tick (a part of `device.Wago672`; manual §3.11.3,
§4.5): the limit switches and software limits, the end of a motion, the flags it implies
(On_Target, Busy, On_Speed, Direction, Err_Range ...), and its own source bits of the bit
field, from which the status bytes are linked.

Decisions ([AMBIGUOUS]/[CONFLICT]/[RECONSTRUCTED] points of wago.md; the manual wins):
* D9 Software limits (wago.md §2.13 [AMBIGUOUS]/[RECONSTRUCTED]): watched in single positioning,
  speed control, run program and mailbox moves, never in referencing; jog as the manual says. A
  move may be started toward a target beyond a limit; crossing the limit brakes with
  Acceleration_Stop_Fast and sets Err_Range_Pos/_Neg (manual §3.11.3.2: brought to standstill
  after the violation, no error code named). Outside the range a start that would go further out
  is refused: no motion, no error, Err_Range stays set, Start_ACK is given, Busy 0, On_Target 0.
  The Err_Range bits clear when the position is back inside the range (and, for a reference
  start refused at a limit switch, when the switch is left). Drive_Range_* and Reference_Offset
  are position units (user); Rotary_Axis_Period and CAM9 are microsteps (wago.md §6.2).
* D10 Hardware limit switches: a switch in the direction of travel brakes with
  Acceleration_Stop_Fast. A start in positioning, speed, program or mailbox mode while a limit
  switch is active is 1931 PARTMODL_LIMITSWITCH, except after a reference run to that limit switch
  (special mode, moving away).
* D12 On_Target in speed control (§4.6 TargetWindowSpeed vs. S2 table "no function" [CONFLICT]):
  set when the commanded speed has been reached (as TargetWindowSpeed and SPEED describe); Busy
  is 1 until then. On_Speed/On_Target compare |v - v_set| <= TargetWindowSpeed.
* D13 StandStill = the frequency output is 0 (bit table §4.5). Direction is 1 while moving positive
  and reads 0 at standstill ("valid only when StandStill is 0"; wago.md §9.12 shows S2 = 0x05 at target).

Tests: D9, D10 test_limits_and_rotary.py; D12 test_speed.py; D13
test_positioning.py::test_exchange_of_wago_md_9_12.
"""

from __future__ import annotations

import math
from typing import Any

from axisline.devices.wago672.bits import SPREAD
from axisline.devices.wago672.errors import WagoError, blink_signal, err_flag
from axisline.devices.wago672.image import MODE_IDLE, MODE_JOG, S0
from axisline.devices.wago672.modes import MODE_BITS
from axisline.devices.wago672.trajectory import Feed
from axisline.devices.wago672.units import Scaling

__all__ = ["Watches"]

_S0_MBX = int(S0.MBX)
_S0_ERR = int(S0.ERR)


class Watches:
    """Mixed into `Wago672` (its state: the set point, the motion running, the flags ...)."""

    config: Any
    scaling: Scaling
    feed: Feed
    bits: Any
    errors: Any
    program: Any
    mode: int
    busy: bool
    on_target: bool
    on_speed: bool
    reference_ok: bool
    precalc_ack: bool
    reset_flag: bool
    err_range_pos: bool
    err_range_neg: bool
    velocity_target: int
    cam_pattern: Any
    _sp: tuple[float, float, float, float]
    _motion: str | None
    _stopping: bool
    _pending: Any
    _target: float | None
    _v_set: float
    _ready: bool
    _stop_n_ack: bool
    _start_ack: bool
    _mode_exit: bool
    _direction: bool
    _mbx_on: bool
    _error_since: int
    _ref: Any
    _range_block: int
    _ls_special: int
    _ls_left: int | None
    _jog_dir: int
    _jog_block: bool
    _jog_ls: int
    _jog_outside: bool

    def _user_position(self) -> float | None:
        """Position in user units for the software limits (None: limits not in force)."""
        p = self.feed.state(self._c_plan())[0]  # the last set point (as `_state`)
        period = self.rotary_period()
        if period:
            c = self.config.values
            if not (c["Drive_Range_Neg"] >= 0 or c["Drive_Range_Pos"] < self.scaling.position_float(period)):
                return None  # rotary axis: "otherwise unrestricted"
            p = p % period
        return self.scaling.position_float(p)

    def _check_limit_switch(self, direction: int) -> None:
        """1931 for a start while a limit switch is active, except leaving it in special mode (D10)."""
        s = self._sig
        for active, side in ((s.get("ls_pos", False), 1), (s.get("ls_neg", False), -1)):
            if active and not (self._ls_special == side and direction == -side):
                raise WagoError(1931, f"{'LimitSwitch_Pos' if side > 0 else 'LimitSwitch_Neg'} is active")

    def _refused_by_range(self, direction: int) -> bool:
        """Outside the software limits only moves back into the range are accepted (D9)."""
        u = self._user_position()
        if u is None or direction == 0:
            return False
        c = self.config.values
        if u > c["Drive_Range_Pos"] and direction > 0:
            self.err_range_pos = True
            return True
        if u < c["Drive_Range_Neg"] and direction < 0:
            self.err_range_neg = True
            return True
        return False

    def _watch_limits(self, s: dict[str, bool], cycle: int) -> None:
        v = self.feed.state(self._c_plan())[1]  # the last set point's velocity (as `_state`)
        # special mode after a reference run to a limit switch ends 100 ms after leaving it
        if self._ls_special:
            on = s["ls_pos"] if self._ls_special > 0 else s["ls_neg"]
            if on:
                self._ls_left = None
            elif self._ls_left is None:
                self._ls_left = cycle
            elif cycle - self._ls_left >= 100:
                self._ls_special = 0
        if self._range_block and not (s["ls_pos"] if self._range_block > 0 else s["ls_neg"]):
            self._range_block = 0
        if self._motion == "reference" or (self._ref is not None and self._ref.active):
            return  # the reference run handles limit switches; software limits are off
        jog = self.mode == MODE_JOG and self._motion == "jog"
        # hardware limit switches: brake when moving toward an active one
        if (v > 0.0 and s["ls_pos"]) or (v < 0.0 and s["ls_neg"]):
            if not self._stopping:
                self._stop_fast("jog" if jog else "stop")
                if jog:
                    self._jog_dir = 0
                    self._jog_block = True
            return
        if jog and self._jog_ls and not self._stopping:
            # JogMode: leaving the limit switch the drive started on brakes again (§3.11.3.1)
            if not (s["ls_pos"] if self._jog_ls > 0 else s["ls_neg"]):
                self._jog_ls = 0
                self._stop_fast("jog")
                self._jog_dir = 0
                self._jog_block = True
                return
        # software limits
        u = self._user_position()
        if u is None:
            return
        c = self.config.values
        out_pos = u > c["Drive_Range_Pos"]
        out_neg = u < c["Drive_Range_Neg"]
        if not (out_pos and v > 0.0) and not (out_neg and v < 0.0):
            if jog and not (out_pos or out_neg):
                self._jog_outside = False  # back inside: the limits are in force again
            return
        if jog and self._jog_outside:
            return  # jogging outside the range after a repeated JOG command
        if out_pos:
            self.err_range_pos = True
        else:
            self.err_range_neg = True
        if not self._stopping:
            self._stop_fast("jog" if jog else "stop")
            if jog:
                self._jog_dir = 0
                self._jog_block = True

    # ================================================================== end of motions, flags
    def _finish_motions(self, cycle: int, stop_ok: bool) -> None:
        kind = self._motion
        ended = self.feed.ended(cycle)
        v = self._sp[1]
        if kind == "position" and ended and self._pending is None:
            window = self.scaling.distance(self.config.values["TargetWindowPosition"]) if self.config.values["TargetWindowPosition"] else 0
            self.on_target = self._target is not None and abs(self._sp[0] - self._target) <= abs(window) + 1e-6
            self.busy = False
            self._motion = None
            self.velocity_target = 0  # SET_VELOCITY_TARGET is for the next positioning only
        elif kind == "speed" and ended and self._pending is None:
            self.busy = False
            self.on_target = True  # D12
            if v == 0.0:
                self._motion = None
        elif kind in ("stop", "jog") and ended and v == 0.0:
            self._motion = None
            self._stopping = False
            if self._ref is None or not self._ref.active:
                self.busy = False if kind == "stop" or self.mode == MODE_JOG else self.busy
        elif kind == "reference" and ended and v == 0.0 and (self._ref is None or not self._ref.active):
            self._motion = None
            self._stopping = False
        if self._motion is None and self._stopping:
            self._stopping = False
        if self._mode_exit and self.feed.ended(cycle) and v == 0.0:
            self.mode = MODE_IDLE
            self._mode_exit = False
            self._motion = None
        if self._stop_n_ack and not stop_ok and ended and v == 0.0:
            self._stop_n_ack = False
            if self.mode != MODE_IDLE:
                self.mode = MODE_IDLE
                self._mode_exit = False
                self.busy = False
        if self._ready and not stop_ok and not self._stop_n_ack and self.mode != MODE_IDLE:
            self.mode = MODE_IDLE
            self._mode_exit = False

    def _update_flags(self, s: dict[str, bool]) -> None:
        p, v, a, _ = self._sp
        self._direction = v > 0.0  # D13: 1 moving positive; 0 otherwise (valid when moving)
        window = self.config.values["TargetWindowSpeed"]
        if self._motion in ("position", "speed", "jog", "reference") and self._pending is None:
            actual = self.scaling.velocity_float(v)
            if self._motion != "speed":
                actual = abs(actual)  # positioning, jog, referencing: the speed, either direction
            self.on_speed = abs(actual - self._v_set) <= window and (v != 0.0 or self._v_set == 0)
        else:
            self.on_speed = False
        if self.mode == MODE_JOG:
            self.busy = self._motion == "jog" and v != 0.0
            self.on_target = False
        u = self._user_position()
        c = self.config.values
        if u is None or c["Drive_Range_Neg"] <= u:
            if self._range_block >= 0:
                self.err_range_neg = False
        if u is None or u <= c["Drive_Range_Pos"]:
            if self._range_block <= 0:
                self.err_range_pos = False
        if self._range_block > 0:
            self.err_range_pos = True
        elif self._range_block < 0:
            self.err_range_neg = True

    # ================================================================== bits out, S0
    def _write_sources(self, s: dict[str, bool], cycle: int) -> None:
        """The device's own source bits (§4.5), written into the bit field in runs of adjacent
        bits (bits.py: each 0 or 1)."""
        f = self.bits.field
        p, v, a, _ = self._sp
        errors = self.errors
        mode = self.mode
        program = self.program
        f[0x04:0x06] = bytes((
            1 if self.reset_flag else 0,  # Reset
            1 if errors.warning else 0,  # Warning
        ))
        f[0x08:0x13] = bytes((
            1 if self.on_target else 0,  # On_Target
            1 if self.busy else 0,  # Busy
            v == 0.0,  # StandStill
            1 if self.on_speed else 0,  # On_Speed
            1 if self._direction else 0,  # Direction
            1 if self.reference_ok else 0,  # Reference_OK
            1 if self.precalc_ack else 0,  # PreCalc_ACK
            1 if errors.error else 0,  # Error
            1 if self._ready else 0,  # Ready
            1 if self._stop_n_ack else 0,  # Stop_N_ACK
            1 if self._start_ack else 0,  # Start_ACK
        ))
        f[0x13:0x18] = SPREAD[MODE_BITS.get(mode, 0) if mode else 0][0:5]  # Command_ACK_1 .. 5
        moving = v != 0.0
        f[0x18:0x1E] = bytes((
            1 if self.brake else 0,  # Break
            1 if errors.code and blink_signal(errors.code, cycle - self._error_since) else 0,  # ERR_Code
            1 if s["setup_active"] else 0,  # SetupSpeed_Active_ACK
            1 if program is not None and program.running else 0,  # Program_Running
            moving and a * v > 0.0,  # Ramp_Up
            moving and a * v < 0.0,  # Ramp_Down
        ))
        f[0x28:0x2B] = bytes((
            1 if self.err_range_neg else 0,  # Err_Range_Neg
            1 if self.err_range_pos else 0,  # Err_Range_Pos
            1 if self.err_range_neg or self.err_range_pos or s["ls_pos"] or s["ls_neg"] else 0,  # Err_Range
        ))
        steps = int(math.floor(p + 0.5))
        c = self.config.values
        period9 = c["Camshaft_Ch9_Period"]
        f[0x2F] = period9 > 0 and (steps - c["Camshaft_Ch9_Start"]) % period9 < c["Camshaft_Ch9_Pulsewidth"]  # CAM9
        pattern = self.cam_pattern(p) if self.cam_pattern is not None else 0
        f[0x38:0x40] = SPREAD[pattern & 0xFF]  # CAM1 .. CAM8

    def _s0(self, s: dict[str, bool]) -> int:
        c = self.config.values
        v = _S0_MBX if self._mbx_on else 0
        if err_flag(c["ErrorNotificationMode"], c["WarningNotificationMode"], bool(self.errors.error), bool(self.errors.warning), s["error_quit"]):
            v |= _S0_ERR
        return v
