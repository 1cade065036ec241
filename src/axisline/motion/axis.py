"""One axis: PLCopen single-axis state machine, set-point generation and position loop.

All four personalities drive the same `Axis`. Per kernel cycle the machine calls

    axis.update_setpoint(cycle)                       # stage 3: set point of this cycle
    v_cmd = axis.position_loop(actual_position)       # stage 4: Kv + feed-forward -> drive

and in between cycles (from the command queue) the PLCopen-like commands
(`move_absolute`, `move_velocity`, `halt`, `stop`, ...), which return a `MotionCommand`
handle with the function-block outputs (busy, active, done, aborted, error, ...).

Time is exact: a profile started at cycle c0 is sampled at (cycle - c0) * period. A command
issued between cycles starts from the set point of the last cycle, at that cycle, so the
first new set point appears at the next `update_setpoint` and nothing jumps.

State machine (PLCopen Motion Control Part 1, "FB state diagram"), as read here:
  * power on: DISABLED -> STANDSTILL. Power off: any state -> DISABLED, except ERROR_STOP,
    which the standard leaves only through MC_Reset (its note: "MC_Power.Enable = FALSE
    and there is no error in the axis" -> Disabled). So power off in ERROR_STOP keeps
    ERROR_STOP with the drive off, and reset then goes to DISABLED; reset while powered
    goes to STANDSTILL.
  * a fault (following error, drive fault, failed homing) -> ERROR_STOP from any state,
    braking with error_deceleration; the first reason is kept until reset. Reset while
    the error ramp still runs completes when the axis is at rest.
  * motion commands are rejected (handle: error, error_id; axis state unchanged) in
    DISABLED, ERROR_STOP and STOPPING (also a second stop: CODESYS SM3 reads it the same
    way), and in HOMING (only stop leaves HOMING early). `home` needs STANDSTILL.
  * STOPPING is left to STANDSTILL only when the stop ramp has ended AND the stop command
    is no longer held (`stop_release()`, MC_Stop.Execute = FALSE).
  * halt: DISCRETE_MOTION until at rest, then STANDSTILL; any motion command may
    interrupt it.

Command values: None takes the config's limit; a velocity, acceleration, deceleration or
jerk above the config's limit is clamped to it (the config is the machine's mechanical
limit; drives such as the CLM do the same) and the handle's `clamped` flag says so;
non-positive or non-finite values are rejected. A `jerk` on an axis whose shape is
"trapezoid" makes that move jerk limited (PLCopen's Jerk input).

Software limits (linear axes): a position target outside them is rejected naming limit
and value. A velocity move or jog is watched every cycle: when the set point one cycle
ahead could no longer stop before the limit, the axis replans a stop exactly at the limit
(DISCRETE_MOTION, then STANDSTILL), and the command reports error SW_LIMIT_* (`warning`
keeps the text). A position move that is replanned on the fly while moving fast toward a
nearby target may overshoot that target (time-optimal profile); targets are checked,
overshoots are not. Homing ignores the limits (see homing.py).

Frames: `command_position` and `actual_position` are unwrapped user units in the axis
frame. The plant reports positions in its own frame; `set_position` and homing shift the
axis frame by `position_offset` (axis = plant + offset), so a drive that wants a position
command gets `command_position - position_offset`. A modulo axis keeps the unwrapped set
point (continuous across the wrap); `position` and `wrap()` give [0, modulo_period).

The class is built in layers by what the code does: axis_state.py (state, rules, planning),
axis_cycle.py (the cycle), this file (the commands); axis_state.py says more.
"""

from __future__ import annotations

import math
from collections import deque
from typing import cast

from axisline.motion.axis_config import AxisConfig, SyncSource
from axisline.motion.axis_cycle import AxisCycle
from axisline.motion.axis_state import _number
from axisline.motion.homing import HomingError, HomingProcedure
from axisline.motion.motion_command import (
    AxisState,
    BufferMode,
    Direction,
    ErrorId,
    MotionCommand,
    _Rejected,
)
from axisline.motion.profiles import Limits, Profile, plan_velocity
from axisline.motion.units import Scale

__all__ = [
    "AxisState",
    "AxisConfig",
    "Axis",
    "MotionCommand",
    "BufferMode",
    "Direction",
    "ErrorId",
    "SyncSource",
]


class Axis(AxisCycle):
    """One axis; see the module docstring. `period`: kernel cycle in seconds."""

    def __init__(self, config: AxisConfig, period: float) -> None:
        if isinstance(period, bool) or not isinstance(period, (int, float)) or not (
            math.isfinite(period) and period > 0.0
        ):
            raise ValueError(f"period must be a number of seconds > 0, got {period!r}")
        self.config = config
        self.name = config.name
        self.unit = config.unit
        self.period = float(period)
        self.scale = Scale(config.counts_per_unit)
        c = config
        # limits resolved once (model_construct'ed configs may still hold None)
        self._v_max = c.v_max
        self._a_max = c.a_max
        self._d_max = c.d_max if c.d_max is not None else c.a_max
        self._j_max = c.j_max
        self._shape = c.shape if c.shape is not None else ("jerk" if c.j_max is not None else "trapezoid")
        self._e_dec = c.error_deceleration if c.error_deceleration is not None else self._d_max
        self._jog_v = c.jog_velocity if c.jog_velocity is not None else c.v_max / 10.0
        self._jog_a = c.jog_acceleration if c.jog_acceleration is not None else c.a_max
        self._window = c.in_position_window if c.in_position_window is not None else c.following_error_limit / 10.0
        self._fe_limit = c.following_error_limit
        self._kv = c.kv
        self._ff = c.velocity_feed_forward
        self._modulo = c.modulo_period if c.kind == "modulo" else None
        self._limits_on = c.sw_limits_enabled and self._modulo is None
        self._low = c.sw_limit_low
        self._high = c.sw_limit_high

        self._state = AxisState.DISABLED
        self._powered = False
        self._error_id = 0
        self._error_text = ""
        self.warning = ""  # last software-limit stop, for the HMI; cleared by the next accepted motion
        self.homed = False

        # set point of the last cycle (axis frame, unwrapped)
        self._p = 0.0
        self._v = 0.0
        self._a = 0.0
        self._j = 0.0
        self._cycle: int | None = None  # last cycle passed to update_setpoint

        # trajectory being sampled: a profile (started at cycle _c0, shifted by _shift) or a sync source
        self._profile: Profile | None = None
        self._c0: int | None = None  # None: bind to the cycle before the first update_setpoint
        self._shift = 0.0
        self._ended = False
        self._sync: SyncSource | None = None
        self._sync_first = False
        self._watch = False  # software-limit watch of a velocity command
        self._watch_cmd: MotionCommand | None = None

        # commands
        self._active: MotionCommand | None = None
        self._queue: deque[MotionCommand] = deque()
        self._stop_held = False
        self._reset_cmd: MotionCommand | None = None
        self._homing: HomingProcedure | None = None
        self._homing_started = False
        self._last_target: float | None = None  # target of the last position command (move_additive)

        # actual values (axis frame)
        self._offset = 0.0  # axis frame = plant frame + offset
        self._actual = 0.0
        self._actual_v = 0.0
        self._have_actual = False
        self._fe = 0.0

    # ------------------------------------------------------------------ commands

    def power(self, on: bool) -> MotionCommand:
        """Enable (DISABLED -> STANDSTILL) or disable the drive (-> DISABLED, not from ERROR_STOP)."""
        cmd = MotionCommand("power")
        if on:
            self._powered = True
            if self._state is AxisState.DISABLED:
                # start from where the axis stands, so the loop does not pull it anywhere
                if self._have_actual:
                    self._p = self._actual
                self._hold()
                self._state = AxisState.STANDSTILL
        else:
            self._powered = False
            self._abort_all()
            self._hold()
            self._stop_held = False
            if self._reset_cmd is not None:
                self._do_reset()  # the error ramp is moot without power: reset completes now
            if self._state is not AxisState.ERROR_STOP:
                self._state = AxisState.DISABLED
        cmd._finish()
        return cmd

    def move_absolute(
        self,
        position: float,
        velocity: float | None = None,
        acceleration: float | None = None,
        deceleration: float | None = None,
        jerk: float | None = None,
        buffer_mode: BufferMode = BufferMode.ABORTING,
        direction: Direction = Direction.SHORTEST,
    ) -> MotionCommand:
        """Move to `position` (modulo: in [0, period), reached in `direction`)."""
        cmd = MotionCommand("move_absolute", buffer_mode)
        try:
            cmd._value = _number("position", position)
            if self._modulo is not None and not 0.0 <= cmd._value < self._modulo:
                raise _Rejected(
                    ErrorId.INVALID_PARAMETER,
                    f"position {cmd._value:g} {self.unit} is outside the modulo range [0, {self._modulo:g})",
                )
            if not isinstance(cast(object, direction), Direction):  # (typed, but callers are not checked)
                raise _Rejected(ErrorId.INVALID_PARAMETER, f"direction must be a Direction, got {direction!r}")
            cmd._direction = direction
            self._dynamics(cmd, velocity, acceleration, deceleration, jerk)
        except _Rejected as r:
            return cmd._fail(r.error_id, r.text)
        return self._submit(cmd)

    def move_relative(
        self,
        distance: float,
        velocity: float | None = None,
        acceleration: float | None = None,
        deceleration: float | None = None,
        jerk: float | None = None,
        buffer_mode: BufferMode = BufferMode.ABORTING,
    ) -> MotionCommand:
        """Move by `distance` from the set point at the start of the command."""
        return self._distance_move("move_relative", distance, velocity, acceleration, deceleration, jerk, buffer_mode)

    def move_additive(
        self,
        distance: float,
        velocity: float | None = None,
        acceleration: float | None = None,
        deceleration: float | None = None,
        jerk: float | None = None,
        buffer_mode: BufferMode = BufferMode.ABORTING,
    ) -> MotionCommand:
        """Move to the target of the last position command + `distance` (no such target: relative)."""
        return self._distance_move("move_additive", distance, velocity, acceleration, deceleration, jerk, buffer_mode)

    def _distance_move(
        self,
        kind: str,
        distance: float,
        velocity: float | None,
        acceleration: float | None,
        deceleration: float | None,
        jerk: float | None,
        buffer_mode: BufferMode,
    ) -> MotionCommand:
        cmd = MotionCommand(kind, buffer_mode)
        try:
            cmd._value = _number("distance", distance)
            self._dynamics(cmd, velocity, acceleration, deceleration, jerk)
        except _Rejected as r:
            return cmd._fail(r.error_id, r.text)
        return self._submit(cmd)

    def move_velocity(
        self,
        velocity: float,
        acceleration: float | None = None,
        deceleration: float | None = None,
        jerk: float | None = None,
        buffer_mode: BufferMode = BufferMode.ABORTING,
    ) -> MotionCommand:
        """Run at `velocity` (sign = direction) until another command; in_velocity when reached."""
        cmd = MotionCommand("move_velocity", buffer_mode)
        try:
            v = _number("velocity", velocity)
            if abs(v) > self._v_max:
                cmd.clamped = True
                v = math.copysign(self._v_max, v)
            cmd._value = v
            self._dynamics(cmd, None, acceleration, deceleration, jerk)
        except _Rejected as r:
            return cmd._fail(r.error_id, r.text)
        return self._submit(cmd)

    def jog(self, direction: int) -> MotionCommand:
        """+1/-1: run at jog velocity; 0: end the jog with a halt (the jog handle is done at rest)."""
        if direction not in (-1, 0, 1) or isinstance(direction, bool):
            return MotionCommand("jog")._fail(ErrorId.INVALID_PARAMETER, f"jog direction must be -1, 0 or +1, got {direction!r}")
        active = self._active
        if direction == 0:
            if active is not None and active.kind == "jog" and not active._ending:
                try:
                    profile = self._prepare_halt(active)
                except _Rejected as r:  # pragma: no cover - a halt always plans
                    return active._fail(r.error_id, r.text)
                active._ending = True
                active.in_velocity = False
                self._watch = False
                self._watch_cmd = None
                self._run(profile, AxisState.DISCRETE_MOTION, active)
                return active
            cmd = MotionCommand("jog")
            cmd._finish()  # no jog to end: nothing to do (a released jog key must not halt a program)
            return cmd
        cmd = MotionCommand("jog")
        cmd._value = direction * self._jog_v
        cmd._shape = self._shape
        cmd._limits = Limits(
            v=self._v_max, a=self._jog_a, d=self._jog_a, j=self._j_max if self._shape != "trapezoid" else None
        )
        return self._submit(cmd)

    def _prepare_halt(self, cmd: MotionCommand) -> Profile:
        assert cmd._limits is not None
        lim = cmd._limits
        brake = Limits(v=self._v_max, a=lim.d if lim.d is not None else lim.a, d=lim.d, j=lim.j)
        try:
            return plan_velocity(cmd._shape, self._start_state(), 0.0, brake)
        except ValueError as e:  # pragma: no cover
            raise _Rejected(ErrorId.INVALID_PARAMETER, str(e)) from None

    def halt(self, deceleration: float | None = None) -> MotionCommand:
        """Brake to rest (DISCRETE_MOTION, then STANDSTILL and done); interruptible."""
        cmd = MotionCommand("halt")
        try:
            self._gate()
            self._brake_limits(deceleration, cmd, self._d_max)
            profile = self._prepare(cmd)
        except _Rejected as r:
            return cmd._fail(r.error_id, r.text)
        self._abort_all()
        self._begin(cmd, profile)
        return cmd

    def stop(self, deceleration: float | None = None) -> MotionCommand:
        """Brake to rest and hold STOPPING until `stop_release()`; aborts everything, homing too.

        The deceleration may exceed d_max up to error_deceleration (a stop may brake harder).
        """
        cmd = MotionCommand("stop")
        try:
            if self._state is not AxisState.HOMING:
                self._gate()
            self._brake_limits(deceleration, cmd, max(self._d_max, self._e_dec))
            profile = self._prepare(cmd)
        except _Rejected as r:
            return cmd._fail(r.error_id, r.text)
        self._abort_all()
        self._begin(cmd, profile)
        self._stop_held = True
        return cmd

    def stop_release(self) -> None:
        """The stop command is no longer held (MC_Stop.Execute = FALSE)."""
        self._stop_held = False
        if self._state is AxisState.STOPPING and self._ended:
            self._hold()
            self._state = AxisState.STANDSTILL

    def set_position(self, position: float, relative: bool = False) -> MotionCommand:
        """Shift the reference without motion: the set point becomes `position` (or moves by it);
        the actual position moves by the same amount, so the following error is unchanged."""
        cmd = MotionCommand("set_position")
        try:
            if self._state is AxisState.HOMING:
                raise _Rejected(ErrorId.AXIS_HOMING, f"axis {self.name} is homing; the procedure sets the position")
            self._set_position(_number("position", position), relative)
        except _Rejected as r:
            return cmd._fail(r.error_id, r.text)
        cmd._finish()
        return cmd

    def _set_position(self, position: float, relative: bool) -> None:
        if relative:
            delta = position
        elif self._modulo is not None:
            if not 0.0 <= position < self._modulo:
                raise _Rejected(
                    ErrorId.INVALID_PARAMETER,
                    f"position {position:g} {self.unit} is outside the modulo range [0, {self._modulo:g})",
                )
            delta = position - self.wrap(self._p)
        else:
            delta = position - self._p
        self._p += delta
        self._shift += delta
        self._offset += delta
        self._actual += delta
        if self._last_target is not None:
            self._last_target += delta

    def reset(self) -> MotionCommand:
        """Leave ERROR_STOP (to STANDSTILL if powered, else DISABLED) once the error ramp has ended.

        The set point is taken from the actual position, so a trip with a large following
        error does not make the axis lurch when it is enabled again. No effect in other states.
        """
        if self._reset_cmd is not None:
            return self._reset_cmd  # already waiting for the error ramp
        cmd = MotionCommand("reset")
        if self._state is AxisState.ERROR_STOP:
            if self._powered and self._profile is not None and not self._ended:
                cmd.busy = True
                self._reset_cmd = cmd
                return cmd
            self._reset_cmd = cmd
            self._do_reset()
        else:
            cmd._finish()
        return cmd

    def home(self, procedure: HomingProcedure) -> MotionCommand:
        """Run a homing procedure (homing.py) in HOMING; from STANDSTILL only."""
        cmd = MotionCommand("home")
        try:
            self._gate()
            if self._state is not AxisState.STANDSTILL:
                raise _Rejected(ErrorId.INVALID_STATE, f"homing needs standstill; axis {self.name} is in {self._state.value}")
            if not isinstance(cast(object, procedure), HomingProcedure):  # (typed, but callers are not checked)
                raise _Rejected(ErrorId.INVALID_PARAMETER, f"procedure must be a HomingProcedure, got {procedure!r}")
        except _Rejected as r:
            return cmd._fail(r.error_id, r.text)
        self._abort_all()
        self._hold()
        self._homing = procedure
        self._homing_started = False
        self._active = cmd
        cmd.busy = cmd.active = True
        self._state = AxisState.HOMING
        self._last_target = None
        self.homed = False
        return cmd

    def start_sync(self, source: SyncSource) -> MotionCommand:
        """Follow `source.sample(cycle) -> (p, v, a)` from the next cycle (SYNCHRONIZED_MOTION).

        The source owns the coupling (a gear or cam engages smoothly from the axis state)."""
        cmd = MotionCommand("sync")
        try:
            self._gate()
            if not callable(getattr(source, "sample", None)):
                raise _Rejected(ErrorId.INVALID_PARAMETER, f"source must have sample(cycle), got {source!r}")
        except _Rejected as r:
            return cmd._fail(r.error_id, r.text)
        self._abort_all()
        self._profile = None
        self._ended = False
        self._shift = 0.0
        self._sync = source
        self._sync_first = True
        self._active = cmd
        cmd.busy = cmd.active = True
        cmd.in_velocity = True  # in sync: the source is followed from the first cycle
        self._state = AxisState.SYNCHRONIZED_MOTION
        self._last_target = None
        self.warning = ""
        return cmd

    def end_sync(self, deceleration: float | None = None) -> MotionCommand:
        """Leave synchronized motion: the sync command is done, the axis halts (returned handle)."""
        cmd = MotionCommand("halt")
        if self._state is not AxisState.SYNCHRONIZED_MOTION:
            return cmd._fail(ErrorId.INVALID_STATE, f"axis {self.name} is not synchronized")
        try:
            self._brake_limits(deceleration, cmd, self._d_max)
            profile = self._prepare(cmd)
        except _Rejected as r:
            return cmd._fail(r.error_id, r.text)
        if self._active is not None:
            self._active._finish()
            self._active.in_velocity = False
            self._active = None
        self._abort_all()
        self._begin(cmd, profile)
        return cmd

    # ------------------------------------------------------------------ homing helpers (HomingAxis)

    def homing_move_velocity(self, velocity: float, acceleration: float | None = None) -> None:
        v = max(-self._v_max, min(self._v_max, float(velocity)))
        a = self._a_max if acceleration is None else min(float(acceleration), self._a_max)
        d = self._d_max if acceleration is None else min(float(acceleration), self._d_max)
        lim = Limits(v=self._v_max, a=a, d=d, j=self._j_max if self._shape != "trapezoid" else None)
        self._homing_profile(plan_velocity(self._shape, self._start_state(), v, lim))

    def homing_halt(self, deceleration: float | None = None) -> None:
        d = self._d_max if deceleration is None else min(float(deceleration), self._d_max)
        lim = Limits(v=self._v_max, a=d, d=d, j=self._j_max if self._shape != "trapezoid" else None)
        self._homing_profile(plan_velocity(self._shape, self._start_state(), 0.0, lim))

    def homing_set_position(self, position: float, relative: bool = False) -> None:
        try:
            self._set_position(float(position), relative)
        except _Rejected as r:
            raise HomingError(r.text) from None

    def __repr__(self) -> str:
        return (
            f"Axis({self.name!r}, {self._state.value}, p={self._p:.6g} {self.unit}, v={self._v:.6g}, "
            f"fe={self._fe:.3g})"
        )


# Compiled, the public names get this source's docstrings and annotations back (help(),
# inspect.signature); in plain Python this does nothing. See axisline/_docs.py.
from axisline._docs import document as _document  # noqa: E402

_document(globals())
