"""The 750-672's output stage and its axis (a part of `device.Wago672`): Ready lost, the power of
the axis and the hand-over of the set point (the axis' sync source), running a profile, the STOP
ramp and STOP_NO_RAMP, the latched scaling and the ramp laws, the motor current and the brake.

    self._run(profile, "position", up, down)   # from the last set point (brake delay D23)
    self._stop_fast()                          # brake with Acceleration_Stop_Fast (D19)
    self._sync_axis(cycle)                     # the axis follows the feed while it moves

Decisions ([AMBIGUOUS]/[CONFLICT]/[RECONSTRUCTED] points of wago.md; the manual wins):
* D15 Freq_Range_Sel/Acc_Range_Sel and the scaling factors are latched while Enable = 0 (§3.7.2:
  "accepted only when Enable is set to 0"); a configuration change takes effect at the next
  Enable. Freq_Range_Sel value = C2 & 3 with C2.0 as LSB (wago.md §3.4 [AMBIGUOUS], §3.7.2 reading).
* D19 STOP ramps (Stop1_N/Stop2_N, mode exit, limit switches, STOP_FAST) use constant deceleration
  Acceleration_Stop_Fast; 0 uses the deceleration of the running motion. STOP_NO_RAMP holds the
  set point where it is (frequency 0 at once) with the output stage on.
* D23 The brake bit (Break, bit 24) is set when a motion starts; if it was not set, the motion
  starts Braketime_Turn_On ms later; it drops Braketime_Turn_Off ms before a position move ends
  (at standstill otherwise). §3.11.4 naming (wago.md §2.11 [CONFLICT]).
* D25 Current_Ratio_Stop applies while a STOP ramp brakes; at standstill (also with Stop2_N = 0) the
  standstill ratio holds the motor - 150 % at rest would trip the 10 s overcurrent model.
* D26 Drive_Direction (HwSwConfig bit 2) inverts the sign of the set point handed to the axis only;
  logical positions, limit switches and software limits keep their directions (wago.md §4.3).

Tests: D15 test_enable_chain.py::test_freq_range_sel_is_taken_only_while_enable_is_0; D19
test_enable_chain.py::test_stop2_n_brakes_with_acceleration_stop_fast_and_ends_the_mode_at_standstill; D23
test_positioning.py::test_brake_released_before_the_move_and_applied_before_the_target; D25
test_enable_chain.py::test_stop_ramp_runs_at_current_ratio_stop_and_rest_at_the_standstill_ratio; D26
test_limits_and_rotary.py::test_drive_direction_inverts_the_motor_not_the_logical_position.
"""

from __future__ import annotations

from collections.abc import Callable

from axisline.devices.wago672.errors import ErrorClass, WagoError, error_class
from axisline.devices.wago672.image import MODE_IDLE
from axisline.devices.wago672.thermal import CurrentPhase, phase_current
from axisline.devices.wago672.trajectory import ACC_INTERNAL_MAX, Ramp, plan_stop, ramp_from_mode
from axisline.devices.wago672.units import Scaling, acc_multiplier, freq_prescaler
from axisline.motion.axis import AxisState
from axisline.motion.profiles import State
from axisline.devices.wago672.state import DeviceState

__all__ = ["TICK", "Drive"]

TICK = 0.001  # the module's scan interval: one TICK = 1 ms (§3.10.6.1.1)


class Drive(DeviceState):
    """The output stage and the axis: the lowest layer of `Wago672` (state.py)."""

    def _lose_ready(self) -> None:
        """Ready 1 -> 0: speed 0 at once, mode ACK cleared at once (§3.11.1.2)."""
        self._no_ramp(stopped=True)
        self.mode = MODE_IDLE
        self._mode_exit = False
        self._stop_n_ack = False
        self._start_ack = False
        self.busy = False
        self.on_speed = False
        self._ref = None
        self._jog_dir = 0
        self._precalc, self.precalc_ack = None, False
        if self.program is not None and self.program.running:
            self.program.stop(self)  # type: ignore[arg-type]  # a layer of Wago672

    def _axis_steps(self) -> float:
        return self.axis.command_position * self._k * self._dir_sign

    def _axis_power(self, on: bool) -> None:
        ax = self.axis
        if on and not ax.powered:
            if ax.state is AxisState.ERROR_STOP:
                ax.reset()
            ax.power(True)
            self.feed.hold(self._axis_steps())
            self._sync_cmd = None
        elif not on and ax.powered:
            ax.power(False)
            self._sync_cmd = None

    def _engaged(self) -> bool:
        cmd = self._sync_cmd
        return cmd is not None and cmd.active and self.axis.state is AxisState.SYNCHRONIZED_MOTION

    def _sync_axis(self, cycle: int) -> None:
        """Hand the feed to the axis while it moves; release it (STANDSTILL) at rest."""
        if not self._stage_on or not self.axis.powered:
            return
        ax = self.axis
        moving = not (
            self.feed.ended(cycle - 1)
            and self.feed.state(cycle - 1)[1] == 0.0
            and self._sp[1] == 0.0
            and ax.command_velocity == 0.0
            and ax.command_acceleration == 0.0
        )
        engaged = self._engaged()
        if moving and not engaged:
            if self.axis.state in (AxisState.STANDSTILL, AxisState.DISCRETE_MOTION, AxisState.CONTINUOUS_MOTION):
                cmd = self.axis.start_sync(self.feed)
                self._sync_cmd = cmd if not cmd.error else None
                if cmd.error:
                    self._raise(1811, f"axis {self.axis.name} refused the set point: {cmd.error_text}")
        elif not moving and engaged:
            self.axis.end_sync()
            self._sync_cmd = None

    def _state(self) -> State:
        """The set point a plan starts from (the last cycle's)."""
        p, v, a, _ = self.feed.state(self._c_plan())
        return State(p, v, a)

    def _at_rest(self) -> bool:
        c = self._c_plan()
        return self.feed.ended(c) and self.feed.state(c)[1] == 0.0

    def _run(self, profile, kind: str, up: Ramp | None = None, down: Ramp | None = None) -> None:
        """Start `profile` from the last set point (brake delay D23 when starting from rest)."""
        c0 = self._c_plan()
        delay = 0
        if not self._brake_auto and self._at_rest():
            delay = self.config.values["Braketime_Turn_On"]
        self._brake_auto = True
        self.feed.run(profile, c0 + delay)
        self._motion = kind
        self._stopping = kind == "stop"
        self._cur_up = up or Ramp("trapezoid", 1.0)
        self._cur_down = down or self._cur_up

    def _stop_fast(self, kind: str = "stop") -> None:
        """STOP_FAST: brake with Acceleration_Stop_Fast (0: the running deceleration) (D19)."""
        self._pending = None
        st = self._state()
        if st.v == 0.0 and self.feed.ended(self._c_plan()):
            return
        value = self.config.values["Acceleration_Stop_Fast"]
        try:
            decel = self.scaling.accel(value, "Acceleration_Stop_Fast") if value else self._cur_down.accel
        except WagoError as e:
            self._raise(e.code, e.text)
            return
        keep = self._motion if kind == "keep" else kind
        self._run(plan_stop(st, decel), keep or "stop", Ramp("trapezoid", decel))
        self._stopping = True
        self._last_target = None

    def _no_ramp(self, stopped: bool = False) -> None:
        """STOP_NO_RAMP: frequency 0 at once; the set point stays where it is."""
        self.feed.hold(self._state().p if self._stage_on or stopped else self._axis_steps())
        self._pending = None
        self._motion = None
        self._stopping = False
        self._last_target = None
        self._brake_auto = False

    def _set_actual(self, steps: float) -> None:
        """ActualPosition := steps at standstill (the logical zero is moved)."""
        if self._engaged():
            self.axis.end_sync()
            self._sync_cmd = None
        p = self._state().p
        delta = steps - p
        self.axis.set_position(delta / self._k * self._dir_sign, relative=True)
        self.feed.hold(steps)
        self._sp = (steps, 0.0, 0.0, 0.0)
        self._last_target = None
        self._target = None

    # ================================================================== scaling and ramps
    def _latch_scaling(self) -> None:
        """Prescaler, acceleration factor and scaling factors, taken while Enable = 0 (D15)."""
        c = self.config.values
        out = self._out
        sig = self._sig
        if sig.known:
            fsel = int(sig.freq_sel_0) | int(sig.freq_sel_1) << 1
            asel = int(sig.acc_sel_0) | int(sig.acc_sel_1) << 1
        else:
            fsel, asel = out.c2 & 3, (out.c2 >> 2) & 3
        try:
            self.scaling = Scaling(
                prescaler=freq_prescaler(fsel, c["Freq_Div"]),
                multiplier=acc_multiplier(asel, c["Acc_Fact"]),
                pos_mult=c["Pos_Mult"], pos_div=c["Pos_Div"],
                speed_mult=c["Speed_Mult"], speed_div=c["Speed_Div"],
                acc_mult=c["Acc_Mult"], acc_div=c["Acc_Div"],
            )
        except WagoError as e:
            self._raise(e.code, e.text)
        self._dir_sign = -1.0 if c["HwSwConfig"] & 0x04 else 1.0
        self.feed.steps_per_unit = self._k * self._dir_sign

    def _ramps(self, acc_up: int, acc_down: int, v_f: float) -> tuple[Ramp, Ramp]:
        """Ramp laws of a positioning or speed command from the acceleration settings."""
        sc = self.scaling
        m = self.acc_mode
        a_up = sc.accel(acc_up, "Acceleration (ramp-up)")
        a_dn = sc.accel(acc_down, "Acceleration (ramp-down)")
        ramps = []
        for phase, typ, par, a, raw in (("Acc", m & 3, (m >> 2) & 3, a_up, self.param_up), ("Dec", (m >> 4) & 3, (m >> 6) & 3, a_dn, self.param_down)):
            steps = abs(sc.distance(raw)) if par == 2 else None
            r = ramp_from_mode(typ, par, a, raw, steps, phase)
            # a ramp time/path that needs more acceleration than the module can make
            peak = None
            if r.time is not None:
                peak = 2.0 * abs(v_f) / r.time
            elif r.path is not None:
                peak = v_f * v_f / r.path
            if peak is not None and peak > ACC_INTERNAL_MAX:
                code = 1556 if r.path is not None else (1554 if phase == "Acc" else 1555)
                raise WagoError(code, f"{phase} ramp {'path' if r.path is not None else 'time'} {raw}: {peak:.0f} microsteps/s^2 exceeds {ACC_INTERNAL_MAX:.0f}")
            ramps.append(r)
        return ramps[0], ramps[1]

    def _defer(self, new_needs_rest: bool) -> bool:
        """Must a new set point wait for v = const? (D8)"""
        st = self._state()
        if st.a == 0.0:
            return False
        if new_needs_rest:
            return True
        accelerating = st.a * st.v > 0.0 or st.v == 0.0
        return (self._cur_up if accelerating else self._cur_down).smooth

    def _start_or_defer(self, go: Callable[[], None], new_needs_rest: bool) -> None:
        """Start a new set point now, or keep it until v = const (D8: `_defer`)."""
        if self._defer(new_needs_rest):
            self._pending = go
        else:
            self._pending = None
            go()

    def _overloaded(self) -> bool:
        """The cause of 1413: the thermal model has not cooled back to 0 (D22)."""
        return self._overcurrent.load > 0.0

    def _current_and_brake(self, cycle: int) -> None:
        p, v, a, _ = self._sp
        c = self.config.values
        # the phase and its configured ratio (Enum members are not hashed here: a dict keyed
        # by them costs a Python-level __hash__ per lookup)
        if not self._stage_on:
            phase, name = CurrentPhase.OFF, ""
        elif self._stopping and v != 0.0:
            phase, name = CurrentPhase.STOP, "Current_Ratio_Stop"
        elif v == 0.0:
            phase, name = CurrentPhase.STANDSTILL, "Current_Ratio_StandStill"
        elif a * v > 0.0:
            phase, name = CurrentPhase.RAMP_UP, "Current_Ratio_RampUp"
        elif a * v < 0.0:
            phase, name = CurrentPhase.RAMP_DOWN, "Current_Ratio_RampDown"
        else:
            phase, name = CurrentPhase.DRIVE, "Current_Ratio_Drive"
        self.current_phase = phase
        if phase is CurrentPhase.OFF:
            ratio = 0
        else:
            # a SET_CURRENT value wins over the configuration's (not for the STOP ramp)
            ratio = self._ratio_set.get(phase, -1) if self._ratio_set and phase is not CurrentPhase.STOP else -1
            if ratio < 0:
                ratio = c[name]
        self.current_ratio = ratio
        self.phase_current = phase_current(c["Current"], ratio)
        if self._overcurrent.step(self.phase_current, TICK):
            self._raise(1413, f"overcurrent {self.phase_current:g} A for too long (thermal model)",
                        cause=self._overloaded)
        # automatic brake bit (D23)
        if self._brake_auto:
            if self.feed.ended(cycle) and v == 0.0:
                self._brake_auto = False
            elif self._motion == "position" and self.feed.profile is not None and self._pending is None:
                remaining = self.feed.profile.duration - self.feed.t(cycle)
                if remaining * 1000.0 <= c["Braketime_Turn_Off"] and remaining < self.feed.profile.duration:
                    self._brake_auto = False


    @property
    def brake(self) -> bool:
        """The Break bit: 1 brake vented (released)."""
        return self._brake_auto or self._sig.brake_manual

    def _raise(self, code: int, text: str = "", cause: Callable[[], bool] | None = None) -> None:
        """Raise a device error or warning. An error switches the output stage off at once."""
        if not self.errors.raise_code(code, text, cause=cause):
            return
        if error_class(code) is ErrorClass.WARNING:
            return
        self._error_since = self._cycle or 0
        if self._ready:
            self._lose_ready()
        self._ready = False
        self._stage_on = False
        self._axis_power(False)
        self.current_phase = CurrentPhase.OFF  # the output stage is off: no current from now on
        self.phase_current = 0.0
        self.current_ratio = 0
