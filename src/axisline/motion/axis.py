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
"""

from __future__ import annotations

import math
from collections import deque
from enum import Enum, IntEnum
from typing import Literal, cast

from axisline.motion.axis_config import AxisConfig, SyncSource
from axisline.motion.homing import HomingError, HomingProcedure
from axisline.motion.profiles import Limits, Profile, State, plan, plan_velocity
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


class AxisState(Enum):
    """PLCopen single-axis states."""

    DISABLED = "Disabled"
    STANDSTILL = "Standstill"
    HOMING = "Homing"
    DISCRETE_MOTION = "DiscreteMotion"
    CONTINUOUS_MOTION = "ContinuousMotion"
    SYNCHRONIZED_MOTION = "SynchronizedMotion"
    STOPPING = "Stopping"
    ERROR_STOP = "ErrorStop"


class BufferMode(Enum):
    """ABORTING replans at once from the current set point; BUFFERED waits (FIFO)."""

    ABORTING = "Aborting"
    BUFFERED = "Buffered"


class Direction(Enum):
    """Direction of an absolute move on a modulo axis (ignored on linear axes)."""

    SHORTEST = "Shortest"
    POSITIVE = "Positive"
    NEGATIVE = "Negative"
    CURRENT = "Current"  # the direction the axis moves in now; at rest: shortest


class ErrorId(IntEnum):
    """Error ids of commands and of the axis (PLCopen leaves the numbers to the vendor)."""

    NONE = 0
    AXIS_DISABLED = 0x10  # motion command while DISABLED
    AXIS_ERROR_STOP = 0x11  # motion command while ERROR_STOP
    AXIS_STOPPING = 0x12  # motion command while STOPPING
    AXIS_HOMING = 0x13  # command not allowed while HOMING
    INVALID_STATE = 0x14  # e.g. home while moving, end_sync without sync
    INVALID_PARAMETER = 0x20
    SW_LIMIT_LOW = 0x30
    SW_LIMIT_HIGH = 0x31
    FOLLOWING_ERROR = 0x40
    DRIVE_FAULT = 0x41  # default of Axis.fault()
    HOMING_FAILED = 0x42


# ------------------------------------------------------------------------ command handle

_POSITION_KINDS = ("move_absolute", "move_relative", "move_additive")
_VELOCITY_KINDS = ("move_velocity", "jog")


class MotionCommand:
    """Handle of one command with the PLCopen function-block outputs.

    busy: accepted and not finished; active: has control of the axis; done: finished
    normally; aborted (command_aborted): taken over by another command, a stop, a fault or
    power off; error/error_id/error_text: rejected or failed; in_velocity: a velocity
    command (or jog) runs at its velocity; clamped: a value was clamped to the config.
    """

    __slots__ = (
        "kind", "buffer_mode", "busy", "active", "done", "aborted", "error", "error_id",
        "error_text", "in_velocity", "clamped", "target", "_value", "_direction", "_limits",
        "_shape", "_ending",
    )  # fmt: skip

    def __init__(self, kind: str, buffer_mode: BufferMode = BufferMode.ABORTING) -> None:
        self.kind = kind
        self.buffer_mode = buffer_mode
        self.busy = False
        self.active = False
        self.done = False
        self.aborted = False
        self.error = False
        self.error_id = 0
        self.error_text = ""
        self.in_velocity = False
        self.clamped = False
        self.target: float | None = None  # resolved position target (axis frame) once started
        self._value = 0.0  # position, distance or velocity as commanded
        self._direction = Direction.SHORTEST
        self._limits: Limits | None = None
        self._shape = "trapezoid"
        self._ending = False  # a jog that is braking after jog(0)

    @property
    def command_aborted(self) -> bool:
        return self.aborted

    def _fail(self, error_id: int, text: str) -> MotionCommand:
        self.busy = self.active = self.in_velocity = False
        self.error = True
        self.error_id = int(error_id)
        self.error_text = text
        return self

    def _finish(self) -> None:
        self.busy = self.active = False
        self.done = True

    def _abort(self) -> None:
        if self.busy:
            self.busy = self.active = self.in_velocity = False
            self.aborted = True

    def __repr__(self) -> str:
        flags = [n for n in ("busy", "active", "done", "aborted", "error", "in_velocity") if getattr(self, n)]
        err = f", error_id={self.error_id:#x}, {self.error_text!r}" if self.error else ""
        return f"MotionCommand({self.kind}, {'|'.join(flags) or 'idle'}{err})"


class _Rejected(Exception):
    def __init__(self, error_id: int, text: str) -> None:
        super().__init__(text)
        self.error_id = error_id
        self.text = text


# ------------------------------------------------------------------------ the axis

# ramp duration factor per shape (profiles.py: a ramp lasts k * |da| / j)
_RAMP_K = {"trapezoid": 0.0, "jerk": 1.0, "sin2": math.pi / 2.0}


def _number(name: str, x: object) -> float:
    if isinstance(x, bool) or not isinstance(x, (int, float)) or not math.isfinite(x):
        raise _Rejected(ErrorId.INVALID_PARAMETER, f"{name} must be a finite number, got {x!r}")
    return float(x)


class Axis:
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
                procedure.start(self)
            finished = procedure.step(self)
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

    def __repr__(self) -> str:
        return (
            f"Axis({self.name!r}, {self._state.value}, p={self._p:.6g} {self.unit}, v={self._v:.6g}, "
            f"fe={self._fe:.3g})"
        )


# Compiled, the public names get this source's docstrings and annotations back (help(),
# inspect.signature); in plain Python this does nothing. See axisline/_docs.py.
from axisline._docs import document as _document  # noqa: E402

# hot: called every cycle from interpreted code (devices), left compiled-only (no wrapper)
_document(globals(), hot={"Axis": ("update_setpoint", "position_loop")})
