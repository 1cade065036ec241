"""The operating modes of the 750-672 (a part of `device.Wago672`; manual §3.11.1, wago.md §2, §7):
selecting and leaving a mode, the Start handshake, single positioning, speed control, PreCalc,
referencing (the module's side of referencing.py's reference run) and JogMode.

    C1 = Enable | Stop2_N | M_Positioning  -> M_Positioning_ACK (S1.3), Busy 0
    set points in D0..D6, Start 0 -> 1     -> Start_ACK, Busy; On_Target at the target

Decisions ([AMBIGUOUS]/[CONFLICT]/[RECONSTRUCTED] points of wago.md; the manual wins):
* D1 Speed control selection (wago.md §3.3 [CONFLICT/AMBIGUOUS]): the manual selects it with
  "Command[]=3" (§3.7.2 C1 table, §3.11.1.11: "selected by selecting the Command[]=3 operating
  image"), i.e. C1.3 and C1.4 together; Command_Ack reports 3 (S1.3 + S1.4). The spec's
  Application_Selector variant is not documented for the 672 (addr 3 allows only 1). Any other
  combination of mode bits at selection is 1354 OPC_MULTIMODE_1.
* D2 Start in JogMode (wago.md §2.5 [CONFLICT], spec line "Start bit in JogMode: [CONFLICT] C1/Start
  description ... Recommendation: JogMode runs without Start"): JogMode runs without Start; a
  Start edge is ignored - no Start_ACK ("Start_ACK: No effect. Handshake not performed", S1 in
  §3.11.1.6.1) and no error (an error would switch the output stage off under a PLC that
  follows the sequence diagram Fig. 3.11.1-15). Test: test_jog::test_start_in_jog_mode_is_ignored.
* D3 Jog control (wago.md §2.5 [CONFLICT]): positive while Jog_Pos (Input3) or Direction_Pos,
  negative while Jog_Neg (Input4) or Direction_Neg; both -> the drive brakes (Acceleration_
  Stop_Fast) and waits for both to be released. Release ramps down with SetupAcceleration.
  Jog and reference runs use constant acceleration (SetupAcceleration is "the acceleration").
* D4 SteppingMode timeout (wago.md §2.5 [AMBIGUOUS], no process-image location): the attribute
  `stepping_timeout_ms` (0 = unlimited JogMode); a jog press ends after it, a new press is needed.
* D5 On_Target in referencing (wago.md §2.4 [CONFLICT]): set when a reference run started from the
  process image has set the reference point (S2 table §3.11.1.5.1, bit table); not set after
  START_REFERENCING (§4.3.4.1.13). Reference_OK and Busy = 0 mark the end in both.
* D6 Reference_Mode bits (wago.md §2.4 [CONFLICT]): bit 0 switch/limit switch, bit 1 edge (§4.6);
  START_REFERENCING's DIR is read when SWT = 0 (the §3.11.1.5.3 tables), not SWT = 1.
* D7 Reference run motion: see referencing.py ([RECONSTRUCTED], as wago.md §2.4 proposes). Both
  Direction bits set: the drive "is deactivated" - no run, no error, Start_ACK given. No direction
  bit: 1431 PROT_REF_DIR.
* D8 On-the-fly with linear/sin^2 ramps (wago.md §2.3 [RECONSTRUCTED], manual note §3.11.1.4): a new
  set point that arrives while the acceleration is not 0 in a linear/sin^2 phase, or that needs a
  ramp time/path plan (which starts from a = 0, docs/decisions.md K3), waits until v = const
  (a = 0: a cruise or the end of the move), then the move is replanned. Busy is 1 and On_Target 0
  from the Start edge on. With constant acceleration the new set point is taken at once.
* D11 Rotary axis (wago.md §2.6 [AMBIGUOUS]): actual value in [0, P); absolute targets in [0, P)
  else 1123; from standstill the shorter way (half a turn: positive); when moving, the first
  equivalent target ahead of the stopping point (no reversal). Speed control wraps with
  Rotary_Axis_Period, or 100000 microsteps when it is 0 (wago.md §2.6 reading of "a value of
  100000 is assumed").
* D14 Start with an error pending is simply refused by Ready = 0; Start while Error_Quit is set is
  1361; Start without a mode is 1351; Start while a mode is being left is ignored.
* D20 Speed_Limit: a commanded velocity above it is error 1212 CTRLOUT_F_FREF (the drive is turned
  off) [RECONSTRUCTED code]. Velocity 0/over 25000/negative in positioning: 1117; acceleration
  0/negative: 1121 [RECONSTRUCTED codes, wago.md §3.6.1].

Tests (tests/devices/wago672): D1 test_speed.py; D2-D4 test_jog.py (test_start_in_jog_mode_is_ignored,
test_jog_by_direction_bits_and_both_directions_turn_the_drive_off, test_stepping_mode_timeout_ends_the_run);
D5-D7 test_referencing.py, test_drive_command.py::test_start_referencing_does_not_set_on_target; D8
test_positioning.py::test_on_the_fly_with_linear_ramps_waits_for_constant_speed; D11
test_limits_and_rotary.py; D14 test_errors.py; D20
test_positioning.py::test_velocity_above_speed_limit_turns_the_drive_off.
"""

from __future__ import annotations

import math
from collections.abc import Callable

from axisline.devices.wago672.errors import WagoError
from axisline.devices.wago672.image import (
    MODE_BITS,
    MODE_IDLE,
    MODE_JOG,
    MODE_MAILBOX,
    MODE_POSITIONING,
    MODE_PROGRAM,
    MODE_REFERENCING,
    MODE_SPEED,
    PositioningSetpoints,
    ProgramSetpoints,
    SpeedSetpoints,
)
from axisline.devices.wago672.referencing import RefPhase, RefRun
from axisline.devices.wago672.trajectory import Ramp, needs_constant_speed, plan_move, plan_speed
from axisline.motion.profiles import Limits, State, plan_velocity
from axisline.devices.wago672.watches import Watches
from axisline.devices.wago672.signals import Signals

__all__ = ["MODE_BITS", "Modes"]



class Modes(Watches):
    """The operating modes: a layer of `Wago672` over `Watches` (state.py)."""

    # ================================================================== mode selection
    def _select_mode(self, s: Signals) -> None:
        requested = int(s.cmd1) | int(s.cmd2) << 1 | int(s.cmd3) << 2 | int(s.cmd4) << 3 | int(s.cmd5) << 4
        if self.mode != MODE_IDLE:
            bits = MODE_BITS[self.mode]
            still = (requested & bits) == bits
            if not still or not self._stop_n_ack:
                if not self._mode_exit:
                    self._leave_mode()
                if self._at_rest():
                    self.mode = MODE_IDLE
                    self._mode_exit = False
                    self._motion = None
            return
        if requested == 0:
            self._bad_selection = 0
            return
        if not (self._ready and self._stop_n_ack and not self._start_ack and not s.start):
            return  # selection waits until the module is ready for it (§3.11.1.1)
        if requested not in MODE_BITS:
            if requested != self._bad_selection:
                self._bad_selection = requested
                self._raise(1354, f"mode bits C1 = {requested << 3:#04x} select more than one mode")
            return
        self.mode = requested
        self._bad_selection = 0
        self.on_target = False
        self.busy = False
        self.on_speed = False
        self._start_ack = False
        self._source = "pi"
        self._jog_dir = 0
        self._jog_block = False
        self._last_target = None

    def _leave_mode(self) -> None:
        """Mode bit cleared (or Stop_N_ACK lost): brake, end the mode's task."""
        self._mode_exit = True
        self._pending = None
        self._ref = None
        self._jog_dir = 0
        if self.program is not None and self.program.running:
            self.program.stop(self)  # type: ignore[arg-type]  # a layer of Wago672
        if not self._at_rest() and not self._stopping:
            self._stop_fast()
        self.on_target = False
        self.busy = False

    # ================================================================== Start
    def _on_start(self, s: Signals) -> None:
        if s.error_quit:
            self._raise(1361, "Start while Error_Quit is set")
            return
        if not self._ready:
            return
        if self.mode == MODE_IDLE:
            if self._bad_selection == 0:
                self._raise(1351, "Start without an active mode")
            return
        if self._mode_exit:
            return  # D14
        mode = self.mode
        if mode in (MODE_JOG, MODE_MAILBOX):
            return  # D2: no handshake, no error
        if not s.stop2_n or not s.stop1_n:
            return
        self._source = "pi"
        ok = True
        try:
            if mode == MODE_POSITIONING:
                if s.precalc and self._precalc is not None:
                    ok = self._start_precalc()
                else:
                    sp = PositioningSetpoints.decode(self._out.data)
                    ok = self._pi_position(sp.velocity, sp.acceleration, sp.target)
            elif mode == MODE_SPEED:
                if s.precalc and self._precalc is not None:
                    ok = self._start_precalc()
                else:
                    ssp = SpeedSetpoints.decode(self._out.data)
                    ok = self._pi_speed(ssp.velocity, ssp.acceleration)
            elif mode == MODE_REFERENCING:
                ok = self._pi_reference(s)
            elif mode == MODE_PROGRAM:
                if self.program is None:
                    raise WagoError(1352, "no run program is available (no table manager)")
                self._pending = None
                if not self._at_rest():
                    self._stop_fast()
                self.program.start(ProgramSetpoints.decode(self._out.data).start_counter, self)  # type: ignore[arg-type]  # a layer of Wago672
                self._source = "program"
        except WagoError as e:
            self._raise(e.code, e.text)
            return
        self._start_ack = self._ready and ok is not None

    # ---- single positioning
    def _pi_position(self, velocity: int, acceleration: int, target: int) -> bool:
        if not 1 <= velocity <= 25000:
            raise WagoError(1117, f"Velocity = {velocity} is outside 1 .. 25000")
        if not 1 <= acceleration <= 32767:
            raise WagoError(1121, f"Acceleration = {acceleration} is outside 1 .. 32767")
        return self._move(self._absolute_target(target), velocity, acceleration, acceleration)

    def _absolute_target(self, position: int) -> float:
        """User target -> unwrapped microsteps (rotary: [0, P) and the direction rule, D11)."""
        steps = self.scaling.steps(position, "Target position")
        period = self.config.values["Rotary_Axis_Period"]
        if not period:
            return float(steps)
        if not 0 <= steps < period:
            raise WagoError(1123, f"Target position {position} ({steps} microsteps) is outside the rotary axis range 0 .. {period - 1}")
        st = self._state()
        base = math.floor(st.p / period) * period
        cur = st.p - base
        if st.v == 0.0:
            diff = steps - cur
            if diff > period / 2.0:
                diff -= period
            elif diff <= -period / 2.0:
                diff += period
            return st.p + diff
        # moving: the first equivalent target at or beyond the stopping point (no reversal)
        a = self._cur_down.accel if self._cur_down.accel > 1.0 else 1.0
        stop_at = st.p + math.copysign(st.v * st.v / (2.0 * a), st.v)
        k = math.ceil((stop_at - steps - base) / period) if st.v > 0 else math.floor((stop_at - steps - base) / period)
        return base + steps + k * period

    def _move(self, target: float, velocity: int, acc_up: int, acc_down: int, v_end: int = 0) -> bool:
        """Start (or retarget) a positioning move [target microsteps]; False if refused (D9)."""
        c = self.config.values
        if velocity > c["Speed_Limit"]:
            raise WagoError(1212, f"Velocity = {velocity} is above Speed_Limit = {c['Speed_Limit']}")
        if self._sig.setup_active:
            velocity = min(velocity, max(c["SetupSpeed"], 1))
        f = self.scaling.frequency(velocity)
        st = self._state()
        direction = 1 if target > st.p else -1 if target < st.p else 0
        self._check_limit_switch(direction)
        if self._refused_by_range(direction):
            self.busy = False
            self.on_target = False
            return False
        up, down = self._ramps(acc_up, acc_down, f)
        f_end = math.copysign(self.scaling.frequency(v_end), direction) if v_end else 0.0
        self._target = target
        self._last_target = target
        self._v_set = velocity
        self._v_set_f = f
        self.on_target = False
        self.busy = True

        def go() -> None:
            self._run(plan_move(self._state(), target, f, up, down, f_end), "position", up, down)

        self._start_or_defer(go, needs_constant_speed(up, down))
        return True

    # ---- speed control
    def _pi_speed(self, velocity: int, acceleration: int) -> bool:
        if not -25000 <= velocity <= 25000:
            raise WagoError(1117, f"Velocity = {velocity} is outside -25000 .. 25000")
        if not 1 <= acceleration <= 32767:
            raise WagoError(1121, f"Acceleration = {acceleration} is outside 1 .. 32767")
        return self._speed(velocity, acceleration, acceleration)

    def _speed(self, velocity: int, acc_up: int, acc_down: int) -> bool:
        c = self.config.values
        if abs(velocity) > c["Speed_Limit"]:
            raise WagoError(1212, f"Velocity = {velocity} is above Speed_Limit = {c['Speed_Limit']}")
        f = self.scaling.frequency(velocity)
        direction = 1 if f > 0 else -1 if f < 0 else 0
        self._check_limit_switch(direction)
        if self._refused_by_range(direction):
            self.busy = False
            self.on_target = False
            return False
        up, down = self._ramps(acc_up, acc_down, f)
        self._target = None
        self._last_target = None
        self._v_set = velocity
        self._v_set_f = f
        self.on_target = False
        self.busy = True

        def go() -> None:
            self._run(plan_speed(self._state(), f, up, down), "speed", up, down)

        self._start_or_defer(go, needs_constant_speed(up, down))
        return True

    def _guard(self, action: Callable[[], None]) -> None:
        try:
            action()
        except WagoError as e:
            self._raise(e.code, e.text)

    # ---- PreCalc (§3.7.2 C2.6)
    def _precalc_step(self, s: Signals, edge: bool) -> None:
        if not s.precalc:
            self._precalc, self.precalc_ack = None, False
            return
        if not edge:
            return
        data = self._out.data
        if self.mode == MODE_POSITIONING:
            sp = PositioningSetpoints.decode(data)
            self._precalc = {"kind": "position", "v": sp.velocity, "a": sp.acceleration, "target": sp.target}
        else:
            sp2 = SpeedSetpoints.decode(data)
            self._precalc = {"kind": "speed", "v": sp2.velocity, "a": sp2.acceleration}
        # "If the starting speed is zero, a movement sequence will be calculated in advance"
        if self._at_rest():
            try:
                self._validate_precalc()
                self.precalc_ack = True
            except WagoError as e:
                self._precalc = None
                self._raise(e.code, e.text)
        else:
            self.precalc_ack = False

    def _validate_precalc(self) -> None:
        pc = self._precalc
        assert pc is not None
        if pc["kind"] == "position":
            if not 1 <= pc["v"] <= 25000:
                raise WagoError(1117, f"Velocity = {pc['v']} is outside 1 .. 25000")
            if not 1 <= pc["a"] <= 32767:
                raise WagoError(1121, f"Acceleration = {pc['a']} is outside 1 .. 32767")
            pc["steps"] = self._absolute_target(pc["target"])
            f = self.scaling.frequency(pc["v"])
            up, down = self._ramps(pc["a"], pc["a"], f)
            pc["profile"] = plan_move(self._state(), pc["steps"], f, up, down)
            pc["from"] = self._state().p
            pc["ramps"] = (up, down)

    def _start_precalc(self) -> bool:
        """Start with PreCalc_ACK: the latched set points (the precalculated profile if the
        drive is still where it was calculated)."""
        pc = self._precalc
        assert pc is not None
        if pc["kind"] == "speed":
            return self._pi_speed(pc["v"], pc["a"])
        st = self._state()
        if "profile" in pc and st.v == 0.0 and pc["from"] == st.p and self._at_rest():
            direction = 1 if pc["steps"] > st.p else -1 if pc["steps"] < st.p else 0
            self._check_limit_switch(direction)
            if self._refused_by_range(direction):
                return False
            self._target = self._last_target = pc["steps"]
            self._v_set = pc["v"]
            self._v_set_f = self.scaling.frequency(pc["v"])
            self.on_target = False
            self.busy = True
            up, down = pc["ramps"]
            self._run(pc["profile"], "position", up, down)
            return True
        return self._pi_position(pc["v"], pc["a"], pc["target"])

    # ---- referencing
    def _pi_reference(self, s: Signals) -> bool:
        pos, neg = s.dir_pos, s.dir_neg
        if pos and neg:
            # "The drive is deactivated when the bit Direction_Neg is set at the same time" (D7)
            self._ref = None
            if not self._at_rest():
                self._stop_fast()
            self.busy = False
            return True
        if not pos and not neg:
            raise WagoError(1431, "reference run without direction: set Direction_Pos or Direction_Neg")
        mode = self.config.values["Reference_Mode"]
        self._mailbox_reference = False
        return self._start_reference(1 if pos else -1, bool(mode & 1), 1 if mode & 2 else -1, s)

    def _start_reference(self, direction: int, to_limit: bool, edge: int, s: Signals) -> bool:
        """Begin a reference run; False if it cannot start at a limit switch."""
        c = self.config.values
        if c["SetupSpeed"] == 0:
            raise WagoError(1453, "SetupSpeed = 0: a reference run needs a speed")
        f = abs(self.scaling.frequency(c["SetupSpeed"], "SetupSpeed"))
        if c["SetupAcceleration"] == 0:
            raise WagoError(1121, "SetupAcceleration = 0: a reference run needs an acceleration")
        a = self.scaling.accel(c["SetupAcceleration"], "SetupAcceleration")
        self._pending = None
        self.reference_ok = False
        self.on_target = False
        self._target = None
        self._last_target = None
        self._ref_pending_shift = 0.0
        run = RefRun(self, direction, to_limit, edge, f, a)
        self._ref = run
        if not run.start(s.set_reference, s.ls_pos, s.ls_neg):
            if run.phase is RefPhase.BLOCKED:
                # at the limit switch of the start direction: no motion, Err_Range (no error)
                self._range_block = direction
                if direction > 0:
                    self.err_range_pos = True
                else:
                    self.err_range_neg = True
            self._ref = None
            self.busy = False
            return False
        self.busy = True
        self._v_set = c["SetupSpeed"]
        self._v_set_f = f
        return True

    # RefDrive protocol (referencing.py)
    def ref_velocity(self, velocity: float, acceleration: float) -> None:
        st = self._state()
        lim = Limits(v=max(abs(velocity), abs(st.v), 1.0), a=acceleration, d=acceleration)
        r = Ramp("trapezoid", acceleration)
        self._run(plan_velocity("trapezoid", st, velocity, lim), "reference", r, r)
        self._stopping = False

    def ref_stop_fast(self) -> None:
        self._stop_fast("reference")

    def ref_state(self) -> State:
        return self._state()

    def ref_at_rest(self) -> bool:
        return self._at_rest()

    def ref_edge(self, edge_position: float) -> None:
        """The reference edge: the reported position is the reference value from now on."""
        try:
            ref = self.scaling.steps(self.config.values["Reference_Offset"], "Reference_Offset")
        except WagoError:
            return
        self._ref_pending_shift = ref - edge_position

    def ref_finish(self, edge_position: float, on_limit_switch: int) -> None:
        """At rest after the edge: ActualPosition = Reference_Offset + braking distance."""
        try:
            ref = self.scaling.steps(self.config.values["Reference_Offset"], "Reference_Offset")
        except WagoError as e:
            self._raise(e.code, e.text)
            return
        p = self._state().p
        self._set_actual(ref + (p - edge_position))
        self._ref_pending_shift = 0.0
        self.reference_ok = True
        self.busy = False
        self._motion = None
        self.on_target = self.reference_on_target and not self._mailbox_reference
        if on_limit_switch:
            self._ls_special = on_limit_switch
            self._ls_left = None
        self._ref = None

    def ref_fail(self, code: int, text: str) -> None:
        self._ref = None
        self.busy = False
        self._raise(code, text)

    # ================================================================== jog
    def _jog_step(self, s: Signals, cycle: int) -> None:
        pos = s.jog_pos or s.dir_pos
        neg = s.jog_neg or s.dir_neg
        c = self.config.values
        want = 0 if pos == neg else (1 if pos else -1)
        if pos and neg:
            if self._jog_dir != 0 or not self._at_rest():
                self._stop_fast("jog")
            self._jog_dir = 0
            self._jog_block = True  # "the drive is turned off" until both are released
            return
        if want == 0:
            self._jog_block = False
            if self._jog_dir != 0:
                self._jog_dir = 0
                self._jog_velocity(0.0)
            return
        if self._jog_block:
            return
        if self._jog_dir == want:
            if self.stepping_timeout_ms and cycle - self._jog_started >= self.stepping_timeout_ms:
                self._jog_dir = 0
                self._jog_block = True
                self._jog_velocity(0.0)
            return
        # a new press: not toward an active limit switch
        if (want > 0 and s.ls_pos) or (want < 0 and s.ls_neg):
            return
        u = self._user_position()
        self._jog_outside = u is not None and not (c["Drive_Range_Neg"] <= u <= c["Drive_Range_Pos"])
        self._jog_ls = 1 if s.ls_pos else -1 if s.ls_neg else 0
        self._jog_dir = want
        self._jog_started = cycle
        speed = max(c["SetupSpeed"], 1)  # "If the setup speed is parameterized as zero ... speed 1"
        try:
            self._jog_velocity(want * abs(self.scaling.frequency(speed, "SetupSpeed")))
        except WagoError as e:
            self._raise(e.code, e.text)
            return
        self._v_set = speed
        self.busy = True

    def _jog_velocity(self, velocity: float) -> None:
        c = self.config.values
        if c["SetupAcceleration"] == 0:
            self._raise(1121, "SetupAcceleration = 0: jog needs an acceleration")
            return
        a = self.scaling.accel(c["SetupAcceleration"], "SetupAcceleration")
        st = self._state()
        lim = Limits(v=max(abs(velocity), abs(st.v), 1.0), a=a, d=a)
        r = Ramp("trapezoid", a)
        self._run(plan_velocity("trapezoid", st, velocity, lim), "jog", r, r)
        self._stopping = False
