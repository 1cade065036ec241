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

from axisline.devices.wago672.bits import SPREAD
from axisline.devices.wago672.errors import WagoError, blink_signal, err_flag
from axisline.devices.wago672.image import MODE_BITS, MODE_IDLE, MODE_JOG, S0
from axisline.devices.wago672.drive import Drive
from axisline.devices.wago672.signals import Signals

__all__ = ["Watches"]

_S0_MBX = int(S0.MBX)
_S0_ERR = int(S0.ERR)


class Watches(Drive):
    """What the module watches each tick: a layer of `Wago672` over `Drive` (state.py)."""

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
        for active, side in ((s.ls_pos, 1), (s.ls_neg, -1)):
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

    def _watch_limits(self, s: Signals, cycle: int) -> None:
        v = self.feed.state(self._c_plan())[1]  # the last set point's velocity (as `_state`)
        # special mode after a reference run to a limit switch ends 100 ms after leaving it
        if self._ls_special:
            on = s.ls_pos if self._ls_special > 0 else s.ls_neg
            if on:
                self._ls_left = None
            elif self._ls_left is None:
                self._ls_left = cycle
            elif cycle - self._ls_left >= 100:
                self._ls_special = 0
        if self._range_block and not (s.ls_pos if self._range_block > 0 else s.ls_neg):
            self._range_block = 0
        if self._motion == "reference" or (self._ref is not None and self._ref.active):
            return  # the reference run handles limit switches; software limits are off
        jog = self.mode == MODE_JOG and self._motion == "jog"
        # hardware limit switches: brake when moving toward an active one
        if (v > 0.0 and s.ls_pos) or (v < 0.0 and s.ls_neg):
            if not self._stopping:
                self._stop_fast("jog" if jog else "stop")
                if jog:
                    self._jog_dir = 0
                    self._jog_block = True
            return
        if jog and self._jog_ls and not self._stopping:
            # JogMode: leaving the limit switch the drive started on brakes again (§3.11.3.1)
            if not (s.ls_pos if self._jog_ls > 0 else s.ls_neg):
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

    def _update_flags(self, s: Signals) -> None:
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
    def _write_sources(self, s: Signals, cycle: int) -> None:
        """The device's own source bits (§4.5), written into the bit field (bits.py: each 0 or
        1) when one of them changed since the last tick, or when someone else wrote a source bit
        (`BitTable.sources_touched`); most ticks nothing changes and nothing is written."""
        p, v, a, _ = self._sp
        errors = self.errors
        mode = self.mode
        program = self.program
        code = errors.code
        moving = v != 0.0
        steps = int(math.floor(p + 0.5))
        c = self.config.values
        period9: int = c["Camshaft_Ch9_Period"]
        cam9 = period9 > 0 and (steps - c["Camshaft_Ch9_Start"]) % period9 < c["Camshaft_Ch9_Pulsewidth"]
        pattern = (self.cam_pattern(p) if self.cam_pattern is not None else 0) & 0xFF
        # every bit below, packed: the word that decides whether the field needs writing
        word = (
            (1 if self.reset_flag else 0)  # 0x04 Reset
            | (2 if errors.warning else 0)  # 0x05 Warning
            | (4 if self.on_target else 0)  # 0x08 On_Target
            | (8 if self.busy else 0)  # 0x09 Busy
            | (0 if moving else 16)  # 0x0A StandStill
            | (32 if self.on_speed else 0)  # 0x0B On_Speed
            | (64 if self._direction else 0)  # 0x0C Direction
            | (128 if self.reference_ok else 0)  # 0x0D Reference_OK
            | (256 if self.precalc_ack else 0)  # 0x0E PreCalc_ACK
            | (512 if errors.error else 0)  # 0x0F Error
            | (1024 if self._ready else 0)  # 0x10 Ready
            | (2048 if self._stop_n_ack else 0)  # 0x11 Stop_N_ACK
            | (4096 if self._start_ack else 0)  # 0x12 Start_ACK
            | ((MODE_BITS.get(mode, 0) if mode else 0) & 0x1F) << 13  # 0x13 .. 0x17 Command_ACK_1 .. 5
            | (1 << 18 if self.brake else 0)  # 0x18 Break
            | (1 << 19 if code and blink_signal(code, cycle - self._error_since) else 0)  # 0x19 ERR_Code
            | (1 << 20 if s.setup_active else 0)  # 0x1A SetupSpeed_Active_ACK
            | (1 << 21 if program is not None and program.running else 0)  # 0x1B Program_Running
            | (1 << 22 if moving and a * v > 0.0 else 0)  # 0x1C Ramp_Up
            | (1 << 23 if moving and a * v < 0.0 else 0)  # 0x1D Ramp_Down
            | (1 << 24 if self.err_range_neg else 0)  # 0x28 Err_Range_Neg
            | (1 << 25 if self.err_range_pos else 0)  # 0x29 Err_Range_Pos
            | (1 << 26 if self.err_range_neg or self.err_range_pos or s.ls_pos or s.ls_neg else 0)  # 0x2A Err_Range
            | (1 << 27 if cam9 else 0)  # 0x2F CAM9
            | pattern << 28  # 0x38 .. 0x3F CAM1 .. CAM8
        )
        bits = self.bits
        if word == self._sources_word and not bits.sources_touched:
            return
        self._sources_word = word
        bits.sources_touched = False
        f = bits.field
        f[0x04:0x06] = SPREAD[word & 0x03][0:2]
        f[0x08:0x10] = SPREAD[(word >> 2) & 0xFF]
        f[0x10:0x18] = SPREAD[(word >> 10) & 0xFF]
        f[0x18:0x1E] = SPREAD[(word >> 18) & 0x3F][0:6]
        f[0x28:0x2B] = SPREAD[(word >> 24) & 0x07][0:3]
        f[0x2F] = (word >> 27) & 1
        f[0x38:0x40] = SPREAD[pattern]

    def _s0(self, s: Signals) -> int:
        c = self.config.values
        v = _S0_MBX if self._mbx_on else 0
        if err_flag(c["ErrorNotificationMode"], c["WarningNotificationMode"], bool(self.errors.error), bool(self.errors.warning), s.error_quit):
            v |= _S0_ERR
        return v
