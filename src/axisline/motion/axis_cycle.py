"""What an axis does every cycle: the set point (`update_setpoint`) and the position loop
(`position_loop`), faults, a reset completing at rest, and the steps of a homing procedure.
The middle layer of `Axis` (axis_state.py lists the layers); this is the hot path.
"""

from __future__ import annotations

from axisline.motion.axis_state import AxisBase
from axisline.motion.homing import HomingError
from axisline.motion.motion_command import AxisState, ErrorId
from axisline.motion.profiles import Limits, Profile, plan_velocity

__all__ = ["AxisCycle"]


class AxisCycle(AxisBase):
    """An axis' cycle (see the module docstring); `Axis` is the one to use."""

    def _do_reset(self) -> None:
        self._error_id = 0
        self._error_text = ""
        if self._have_actual:
            self._p = self._actual
        self._fe = 0.0
        self._hold()
        self._state = AxisState.STANDSTILL if self._powered else AxisState.DISABLED
        if self._reset_cmd is not None:
            self._reset_cmd._finish()
            self._reset_cmd = None

    def fault(self, error_id: int = ErrorId.DRIVE_FAULT, text: str = "drive fault") -> None:
        """An axis error: ERROR_STOP with this reason, braking with error_deceleration.

        A second fault while in ERROR_STOP keeps the first reason (it is the cause)."""
        if self._state is AxisState.ERROR_STOP:
            return
        self._error_id = int(error_id)
        self._error_text = text
        self._abort_all()
        self._stop_held = False
        self._last_target = None
        if self._powered:
            lim = Limits(
                v=self._v_max, a=self._e_dec, d=self._e_dec, j=self._j_max if self._shape != "trapezoid" else None
            )
            self._run(plan_velocity(self._shape, self._start_state(), 0.0, lim), AxisState.ERROR_STOP, None)
        else:
            self._hold()
            self._state = AxisState.ERROR_STOP

    def _homing_profile(self, profile: Profile) -> None:
        self._profile = profile
        self._c0 = self._cycle
        self._shift = 0.0
        self._ended = False

    def _homing_step(self) -> None:
        procedure = self._homing
        assert procedure is not None
        try:
            if not self._homing_started:
                self._homing_started = True
                procedure.start(self)  # type: ignore[arg-type]  # an Axis (the homing helpers are there)
            finished = procedure.step(self)  # type: ignore[arg-type]
            if finished and not (self.motion_ended and self._v == 0.0):
                raise HomingError(f"{procedure!r} finished while the axis was moving")
        except HomingError as e:
            self.fault(ErrorId.HOMING_FAILED, f"homing failed: {e}")
            return
        if finished:
            self._homing = None
            self._hold()
            self._state = AxisState.STANDSTILL
            self.homed = True
            if self._active is not None:
                self._active._finish()
                self._active = None

    # ------------------------------------------------------------------ per cycle (hot path)

    def update_setpoint(self, cycle: int) -> None:
        """Set point of `cycle`: sample the profile or sync source, finish and chain commands."""
        if not self._powered:
            # drive off: the set point follows the axis, so power-on starts without a jump
            self._cycle = cycle
            self._p = self._actual
            self._v = self._a = self._j = 0.0
            return
        if self._homing is not None:
            self._homing_step()  # before sampling: sees last cycle's set point with this cycle's inputs
        self._cycle = cycle
        sync = self._sync
        profile = self._profile
        if sync is not None:
            p, v, a = sync.sample(cycle)
            self._j = 0.0 if self._sync_first else (a - self._a) / self.period
            self._sync_first = False
            self._p = p + self._shift
            self._v = v
            self._a = a
            if self._limits_on and not self._low <= self._p <= self._high:
                high = self._p > self._high
                self.fault(
                    ErrorId.SW_LIMIT_HIGH if high else ErrorId.SW_LIMIT_LOW,
                    f"synchronized set point {self._p:g} {self.unit} beyond the software limit "
                    f"{'high' if high else 'low'} {self._high if high else self._low:g} {self.unit}",
                )
            return
        if profile is None:
            self._v = self._a = self._j = 0.0
            return
        c0 = self._c0
        if c0 is None:
            c0 = self._c0 = cycle - 1  # a command issued before the first cycle
        t = (cycle - c0) * self.period
        p, self._v, self._a, self._j = profile.sample(t)
        self._p = p + self._shift
        if not self._ended and t >= profile.duration:
            self._ended = True
            self._profile_ended()
        elif self._queue and self._state is AxisState.CONTINUOUS_MOTION and self._ended:
            self._start_next()  # buffered behind a velocity command that is already in velocity
        if self._watch:  # (a command started above re-based _c0 on this cycle)
            self._watch_limits((cycle + 1 - (cycle if self._c0 is None else self._c0)) * self.period)

    def _profile_ended(self) -> None:
        """The profile reached its end in this cycle."""
        s = self._state
        cmd = self._active
        if s is AxisState.DISCRETE_MOTION:
            if cmd is not None:
                cmd._finish()
                self._active = None
            if not self._start_next():
                self._hold()
                self._state = AxisState.STANDSTILL
        elif s is AxisState.CONTINUOUS_MOTION:
            if cmd is not None:
                cmd.in_velocity = True
            self._start_next()
        elif s is AxisState.STOPPING:
            if cmd is not None:
                cmd._finish()
                self._active = None
            if not self._stop_held:
                self._hold()
                self._state = AxisState.STANDSTILL
        elif s is AxisState.ERROR_STOP:
            if self._reset_cmd is not None:
                self._do_reset()

    def position_loop(self, actual_position: float, actual_velocity: float | None = None) -> float:
        """Velocity command of this cycle: feed-forward * set-point velocity + kv * following error.

        actual_position: continuous (unwrapped) actual position in user units, plant frame
        (an open-loop stepper passes its command). Trips ERROR_STOP when the following error
        exceeds its limit while powered.
        """
        actual = actual_position + self._offset
        if actual_velocity is None:
            self._actual_v = (actual - self._actual) / self.period if self._have_actual else 0.0
        else:
            self._actual_v = actual_velocity
        self._actual = actual
        self._have_actual = True
        if not self._powered:
            self._p = actual
            self._v = self._a = self._j = 0.0
            self._fe = 0.0
            return 0.0
        fe = self._p - actual
        self._fe = fe
        if (fe > self._fe_limit or fe < -self._fe_limit) and self._state is not AxisState.ERROR_STOP:
            u = self.unit
            self.fault(
                ErrorId.FOLLOWING_ERROR, f"following error {fe:.4g} {u} exceeds limit {self._fe_limit:g} {u}"
            )
        return self._ff * self._v + self._kv * fe

# Compiled, the public names get this source's docstrings and annotations back (help(),
# inspect.signature); in plain Python this does nothing. See axisline/_docs.py.
from axisline._docs import document as _document  # noqa: E402

# hot: called every cycle from interpreted code (devices), left compiled-only (no wrapper)
_document(globals(), hot={"AxisCycle": ("update_setpoint", "position_loop")})
