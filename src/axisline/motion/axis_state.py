"""An axis in layers, by what the code does (axis.py's docstring describes the whole axis):

    AxisBase (this file)    the state, its read-outs, and the rules a command passes: the state
                            gate, the command values and limits, planning, the command queue,
                            the software-limit watch of a velocity command
      <- AxisCycle          faults, and the set point and position loop of each cycle
                            (axis_cycle.py: the hot path)
      <- Axis               the PLCopen commands users call (axis.py)

Every attribute is declared here and set in `Axis.__init__`. A layer calls only what it or a
lower layer defines (the homing procedures get the `Axis` itself).
"""

from __future__ import annotations

import math
from collections import deque
from typing import Literal

from axisline.motion.axis_config import AxisConfig, SyncSource
from axisline.motion.homing import HomingProcedure
from axisline.motion.motion_command import (
    _POSITION_KINDS,
    _VELOCITY_KINDS,
    AxisState,
    BufferMode,
    Direction,
    ErrorId,
    MotionCommand,
    _Rejected,
)
from axisline.motion.profiles import Limits, Profile, State, plan, plan_velocity
from axisline.motion.units import Scale

__all__ = ["AxisBase"]

# ramp duration factor per shape (profiles.py: a ramp lasts k * |da| / j)
_RAMP_K = {"trapezoid": 0.0, "jerk": 1.0, "sin2": math.pi / 2.0}


def _number(name: str, x: object) -> float:
    if isinstance(x, bool) or not isinstance(x, (int, float)) or not math.isfinite(x):
        raise _Rejected(ErrorId.INVALID_PARAMETER, f"{name} must be a finite number, got {x!r}")
    return float(x)



class AxisBase:
    """An axis' state, read-outs and the rules its commands pass (see the module docstring)."""

    # ---- configuration, resolved once (Axis.__init__)
    config: AxisConfig
    name: str
    unit: str
    period: float
    scale: Scale
    _v_max: float
    _a_max: float
    _d_max: float
    _j_max: float | None
    _shape: Literal["trapezoid", "jerk", "sin2"]
    _e_dec: float
    _jog_v: float
    _jog_a: float
    _window: float
    _fe_limit: float
    _kv: float
    _ff: float
    _modulo: float | None
    _limits_on: bool
    _low: float
    _high: float
    # ---- state
    _state: AxisState
    _powered: bool
    _error_id: int
    _error_text: str
    warning: str  # last software-limit stop, for the HMI; cleared by the next accepted motion
    homed: bool
    # ---- set point of the last cycle (axis frame, unwrapped)
    _p: float
    _v: float
    _a: float
    _j: float
    _cycle: int | None  # last cycle passed to update_setpoint
    # ---- trajectory being sampled: a profile (started at cycle _c0, shifted by _shift) or a sync source
    _profile: Profile | None
    _c0: int | None  # None: bind to the cycle before the first update_setpoint
    _shift: float
    _ended: bool
    _sync: SyncSource | None
    _sync_first: bool
    _watch: bool  # software-limit watch of a velocity command
    _watch_cmd: MotionCommand | None
    # ---- commands
    _active: MotionCommand | None
    _queue: deque[MotionCommand]
    _stop_held: bool
    _reset_cmd: MotionCommand | None
    _homing: HomingProcedure | None
    _homing_started: bool
    _last_target: float | None  # target of the last position command (move_additive)
    # ---- actual values (axis frame)
    _offset: float  # axis frame = plant frame + offset
    _actual: float
    _actual_v: float
    _have_actual: bool
    _fe: float

    # ------------------------------------------------------------------ read-outs

    @property
    def state(self) -> AxisState:
        return self._state

    @property
    def powered(self) -> bool:
        return self._powered

    @property
    def error_id(self) -> int:
        return self._error_id

    @property
    def error_text(self) -> str:
        return self._error_text

    @property
    def command_position(self) -> float:
        """Set point of the last cycle (unwrapped)."""
        return self._p

    @property
    def command_velocity(self) -> float:
        return self._v

    @property
    def command_acceleration(self) -> float:
        return self._a

    @property
    def command_jerk(self) -> float:
        return self._j

    @property
    def actual_position(self) -> float:
        """Actual position in the axis frame (unwrapped)."""
        return self._actual

    @property
    def actual_velocity(self) -> float:
        return self._actual_v

    @property
    def following_error(self) -> float:
        """Set point - actual position of the last position_loop."""
        return self._fe

    @property
    def position(self) -> float:
        """Actual position as users read it: wrapped into [0, modulo_period) on a modulo axis."""
        return self.wrap(self._actual)

    @property
    def position_offset(self) -> float:
        """Axis frame = plant frame + this (changed by set_position and homing)."""
        return self._offset

    @property
    def in_position(self) -> bool:
        """At rest (no motion left) and |following error| within in_position_window."""
        return (
            self._powered
            and (self._profile is None or self._ended)
            and self._sync is None
            and self._v == 0.0
            and abs(self._fe) <= self._window
        )

    @property
    def motion_ended(self) -> bool:
        """The running profile has reached its end (or none runs)."""
        return self._sync is None and (self._profile is None or self._ended)

    @property
    def active_command(self) -> MotionCommand | None:
        return self._active

    def wrap(self, position: float) -> float:
        """Wrap into [0, modulo_period) on a modulo axis; identity on a linear axis."""
        m = self._modulo
        if m is None:
            return position
        r = position % m
        return 0.0 if r >= m else r  # -1e-17 % 360 == 360.0

    # ------------------------------------------------------------------ state rules

    def _gate(self) -> None:
        """Reject a motion command in a state that does not accept one."""
        s = self._state
        if s is AxisState.DISABLED:
            raise _Rejected(ErrorId.AXIS_DISABLED, f"axis {self.name} is disabled (power off)")
        if s is AxisState.ERROR_STOP:
            raise _Rejected(ErrorId.AXIS_ERROR_STOP, f"axis {self.name} is in error stop ({self._error_text}); reset first")
        if s is AxisState.STOPPING:
            raise _Rejected(ErrorId.AXIS_STOPPING, f"axis {self.name} is stopping; release the stop first")
        if s is AxisState.HOMING:
            raise _Rejected(ErrorId.AXIS_HOMING, f"axis {self.name} is homing; only stop is accepted")

    def _abort_all(self) -> None:
        """The active command, the buffered ones, homing and sync lose the axis."""
        if self._active is not None:
            self._active._abort()
            self._active = None
        while self._queue:
            self._queue.popleft()._abort()
        self._homing = None
        self._sync = None
        self._watch = False
        self._watch_cmd = None

    def _run(self, profile: Profile, state: AxisState, cmd: MotionCommand | None) -> None:
        """Sample `profile` from the last cycle on (a command between cycles starts there)."""
        self._profile = profile
        self._c0 = self._cycle
        self._shift = 0.0
        self._ended = False
        self._sync = None
        self._state = state
        self._active = cmd
        if cmd is not None:
            cmd.busy = cmd.active = True

    def _start_state(self) -> State:
        return State(self._p, self._v, self._a)

    def _hold(self) -> None:
        """No trajectory: the set point stays where it is, at rest."""
        self._profile = None
        self._sync = None
        self._ended = False
        self._v = self._a = self._j = 0.0

    # ------------------------------------------------------------------ command values

    def _dynamics(
        self,
        cmd: MotionCommand,
        velocity: float | None,
        acceleration: float | None,
        deceleration: float | None,
        jerk: float | None,
    ) -> None:
        """Limits of a command: None -> config; above the config -> clamped (cmd.clamped)."""

        def pick(name: str, x: float | None, limit: float | None) -> float | None:
            if x is None:
                return limit
            x = _number(name, x)
            if x <= 0.0:
                raise _Rejected(ErrorId.INVALID_PARAMETER, f"{name} must be > 0, got {x:g}")
            if limit is not None and x > limit:
                cmd.clamped = True
                return limit
            return x

        v = pick("velocity", velocity, self._v_max)
        a = pick("acceleration", acceleration, self._a_max)
        d = pick("deceleration", deceleration, self._d_max)
        j = pick("jerk", jerk, self._j_max)
        shape = self._shape
        if jerk is not None and shape == "trapezoid":
            shape = "jerk"
        assert v is not None and a is not None and d is not None
        cmd._shape = shape
        cmd._limits = Limits(v=v, a=a, d=d, j=j if shape != "trapezoid" else None)

    def _brake_limits(self, deceleration: float | None, cmd: MotionCommand, ceiling: float) -> None:
        """Limits of a braking command (halt, stop): deceleration for both ramps."""
        if deceleration is None:
            d = self._d_max
        else:
            d = _number("deceleration", deceleration)
            if d <= 0.0:
                raise _Rejected(ErrorId.INVALID_PARAMETER, f"deceleration must be > 0, got {d:g}")
            if d > ceiling:
                cmd.clamped = True
                d = ceiling
        cmd._shape = self._shape
        cmd._limits = Limits(v=self._v_max, a=d, d=d, j=self._j_max if self._shape != "trapezoid" else None)

    def _check_limits(self, target: float) -> None:
        if not self._limits_on:
            return
        u = self.unit
        if target > self._high:
            raise _Rejected(
                ErrorId.SW_LIMIT_HIGH,
                f"target {target:g} {u} is above the software limit high {self._high:g} {u}",
            )
        if target < self._low:
            raise _Rejected(
                ErrorId.SW_LIMIT_LOW,
                f"target {target:g} {u} is below the software limit low {self._low:g} {u}",
            )

    def _modulo_target(self, position: float, direction: Direction) -> float:
        """Unwrapped target for an absolute position on a modulo axis."""
        m = self._modulo
        assert m is not None
        p0 = self._p
        base = math.floor(p0 / m) * m
        cur = p0 - base
        diff = position - cur
        if direction is Direction.CURRENT:
            direction = (
                Direction.POSITIVE if self._v > 0.0 else Direction.NEGATIVE if self._v < 0.0 else Direction.SHORTEST
            )
        if direction is Direction.POSITIVE:
            turn = 0.0 if diff >= 0.0 else m
        elif direction is Direction.NEGATIVE:
            turn = 0.0 if diff <= 0.0 else -m
        elif diff > m / 2.0:
            turn = -m
        elif diff <= -m / 2.0:  # a half turn either way: positive
            turn = m
        else:
            turn = 0.0
        return base + turn + position

    def _target_of(self, cmd: MotionCommand) -> float:
        """Resolve the position target of a position command from the current set point."""
        if cmd.kind == "move_absolute":
            if self._modulo is not None:
                return self._modulo_target(cmd._value, cmd._direction)
            return cmd._value
        if cmd.kind == "move_relative":
            return self._p + cmd._value
        base = self._last_target if self._last_target is not None else self._p
        return base + cmd._value

    def _prepare(self, cmd: MotionCommand) -> Profile:
        """Plan a command from the current set point (raises _Rejected)."""
        assert cmd._limits is not None
        start = self._start_state()
        try:
            if cmd.kind in _POSITION_KINDS:
                target = self._target_of(cmd)
                self._check_limits(target)
                cmd.target = target
                return plan(cmd._shape, start, State(target, 0.0), cmd._limits)
            if cmd.kind in _VELOCITY_KINDS:
                v = cmd._value
                if self._limits_on and ((v > 0.0 and self._p >= self._high) or (v < 0.0 and self._p <= self._low)):
                    high = v > 0.0
                    raise _Rejected(
                        ErrorId.SW_LIMIT_HIGH if high else ErrorId.SW_LIMIT_LOW,
                        f"set point {self._p:g} {self.unit} is at the software limit "
                        f"{'high' if high else 'low'} {self._high if high else self._low:g} {self.unit}",
                    )
                return plan_velocity(cmd._shape, start, v, cmd._limits)
            return plan_velocity(cmd._shape, start, 0.0, cmd._limits)  # halt, stop
        except ValueError as e:
            raise _Rejected(ErrorId.INVALID_PARAMETER, str(e)) from None

    def _state_for(self, cmd: MotionCommand) -> AxisState:
        if cmd.kind in _VELOCITY_KINDS:
            return AxisState.CONTINUOUS_MOTION
        if cmd.kind == "stop":
            return AxisState.STOPPING
        return AxisState.DISCRETE_MOTION

    def _begin(self, cmd: MotionCommand, profile: Profile) -> None:
        """cmd takes the axis with its planned profile."""
        self._run(profile, self._state_for(cmd), cmd)
        self.warning = ""
        if cmd.kind in _POSITION_KINDS:
            self._last_target = cmd.target
        else:
            self._last_target = None
        if cmd.kind in _VELOCITY_KINDS and self._limits_on:
            self._watch = True
            self._watch_cmd = cmd
            self._watch_limits(self.period)  # the first new set point, one cycle after the start
        else:
            self._watch = False
            self._watch_cmd = None

    def _submit(self, cmd: MotionCommand) -> MotionCommand:
        """Gate, then buffer or start (aborting) a prepared motion command."""
        try:
            self._gate()
            if cmd.kind == "move_absolute":
                # reject an absolute target outside the limits now, even if buffered
                self._check_limits(cmd._value)
            if cmd.buffer_mode is BufferMode.BUFFERED and self._state is not AxisState.STANDSTILL:
                cmd.busy = True
                self._queue.append(cmd)
                return cmd
            profile = self._prepare(cmd)
        except _Rejected as r:
            return cmd._fail(r.error_id, r.text)
        self._abort_all()
        self._begin(cmd, profile)
        return cmd

    def _start_next(self) -> bool:
        """Start the first buffered command that can be planned; True if one started."""
        while self._queue:
            cmd = self._queue.popleft()
            try:
                profile = self._prepare(cmd)
            except _Rejected as r:
                cmd._fail(r.error_id, r.text)
                continue
            if self._active is not None:
                self._active._abort()  # a velocity command handing over at in_velocity
                self._active = None
            self._begin(cmd, profile)
            return True
        return False

    # ------------------------------------------------------------------ software limits of a velocity command

    def _watch_limits(self, t_next: float) -> None:
        """Velocity command: brake to the software limit when the next set point could not stop before it.

        t_next: profile time of the next cycle. The check one cycle ahead keeps the current
        set point (checked in the cycle before) a state from which the stop still fits.
        """
        profile = self._profile
        if profile is None:
            return
        p, v, a, _ = profile.sample(t_next)
        p += self._shift
        if v > 0.0:
            if self._high - p < self._stop_distance(v, a):
                self._limit_stop(True)
        elif v < 0.0:
            if p - self._low < self._stop_distance(-v, -a):
                self._limit_stop(False)

    def _stop_distance(self, v: float, a: float) -> float:
        """Upper bound of the distance to stop from speed v >= 0 with acceleration a (same frame).

        Ramp a -> -d, brake at d, ramp -d -> 0, all at the peak speed the first ramp can
        reach, plus one cycle of travel. Only needs to be safe: braking a little early
        costs nothing, since the stop is planned as a move that ends at the limit.
        """
        cmd = self._watch_cmd
        assert cmd is not None and cmd._limits is not None
        lim = cmd._limits
        d = lim.d if lim.d is not None else lim.a
        k = _RAMP_K[cmd._shape]
        if k == 0.0 or lim.j is None:
            return v * self.period + v * v / (2.0 * d)
        j = lim.j
        up = a if a > 0.0 else 0.0
        v_peak = v + k * up * up / (2.0 * j)
        ramps = k * (max(a + d, 0.0) + d) / j
        return v_peak * (ramps + self.period) + v_peak * v_peak / (2.0 * d)

    def _limit_stop(self, high: bool) -> None:
        """Replan the watched velocity command as a move that stops exactly at the limit."""
        cmd = self._watch_cmd
        assert cmd is not None and cmd._limits is not None
        lim = cmd._limits
        limit = self._high if high else self._low
        side = 1.0 if high else -1.0
        goal = cmd._value
        v_lim = abs(goal) if goal * side > 0.0 else abs(self._v)
        v_lim = max(v_lim, 1e-9)
        brake = Limits(v=v_lim, a=lim.a, d=lim.d, j=lim.j)
        try:
            profile = plan(cmd._shape, self._start_state(), State(limit, 0.0), brake)
        except ValueError:  # pragma: no cover - plan always finds a move to rest
            profile = plan_velocity(cmd._shape, self._start_state(), 0.0, Limits(v=self._v_max, a=self._e_dec, d=self._e_dec, j=lim.j))
        text = f"software limit {'high' if high else 'low'} {limit:g} {self.unit} reached: stopped at the limit"
        self._watch = False
        self._watch_cmd = None
        cmd._fail(ErrorId.SW_LIMIT_HIGH if high else ErrorId.SW_LIMIT_LOW, text)
        self._active = None
        while self._queue:
            self._queue.popleft()._abort()
        self._last_target = None
        self._run(profile, AxisState.DISCRETE_MOTION, None)
        self.warning = text


# Compiled, the public names get this source's docstrings and annotations back (help(),
# inspect.signature); in plain Python this does nothing. See axisline/_docs.py.
from axisline._docs import document as _document  # noqa: E402

_document(globals())
