"""Master sources for gears, cams and sync: where a slave reads its master from.

Every master is updated once per kernel cycle, before the slaves sample it:

    master.update(cycle)          # SETPOINTS stage, before the slaves' update_setpoint
    master.position, master.velocity, master.acceleration    # master user units, s
    master.counts, master.counts_per_unit                    # integer position for gears

`update` is idempotent per cycle (a second call with the same cycle does nothing), so each
gear may call it from its own `sample` and several slaves can share one master. Time is
exact: a master that generates its own motion samples its profile at (cycle - c0) * period.

`position` is unbounded (unwrapped). `counts` is the integer position the electronic gear
works with (gear.py: slave counts = master counts * numerator // denominator, exactly):

  * count-based masters (EncoderMaster) report the counts they read;
  * masters without counts of their own (AxisMaster, VirtualMaster, TimeBase) quantise
    their position at `counts_per_unit`, by default the fine fixed resolution
    FINE_COUNTS_PER_UNIT (10**9 counts per master unit: 1 nm on a mm master). Pass the
    resolution of the drive you emulate (e.g. the FS701 virtual master's encoder) to gear
    integer ratios against it. Positions up to about 10**6 units stay exact in float64.

Implementations:
  AxisMaster     another axis' set point ("command") or actual position ("actual")
  EncoderMaster  an encoder's counts (counter wrap handled), velocity by a window
                 (FS701 "Sampling Time") or first-order filter
  VirtualMaster  a master running at a commanded velocity with ramps (plan_velocity)
  TimeBase       COMPAX internal time base: position = speed * t, speed changes ramp
                 linearly over a fixed ramp time (P39: an absolute time for any change)
"""

from __future__ import annotations

import math
from abc import ABC, abstractmethod
from typing import Any, Literal

from mypy_extensions import mypyc_attr

from axisline.motion.profiles import Limits, Profile, State, plan_velocity

__all__ = [
    "FINE_COUNTS_PER_UNIT",
    "Master",
    "AxisMaster",
    "EncoderMaster",
    "VirtualMaster",
    "TimeBase",
]

FINE_COUNTS_PER_UNIT = 1_000_000_000
"""Resolution of masters without counts of their own (counts per master unit)."""

# a velocity limit that never binds: virtual masters ramp with acceleration and jerk only
_NO_SPEED_LIMIT = 1e15


def _period(period: float) -> float:
    if isinstance(period, bool) or not isinstance(period, (int, float)) or not (math.isfinite(period) and period > 0):
        raise ValueError(f"period must be a number of seconds > 0, got {period!r}")
    return float(period)


def _positive(name: str, x: float) -> float:
    if isinstance(x, bool) or not isinstance(x, (int, float)) or not (math.isfinite(x) and x > 0):
        raise ValueError(f"{name} must be a finite number > 0, got {x!r}")
    return float(x)


def _finite(name: str, x: float) -> float:
    if isinstance(x, bool) or not isinstance(x, (int, float)) or not math.isfinite(x):
        raise ValueError(f"{name} must be a finite number, got {x!r}")
    return float(x)


def _quantise(position: float, counts_per_unit: float) -> int:
    # nearest count, halves up: symmetric enough for a fine resolution, and one rounding
    return math.floor(position * counts_per_unit + 0.5)


# (compiled: the tests' and the devices' own masters may subclass it)
@mypyc_attr(allow_interpreted_subclasses=True)
class Master(ABC):
    """A master source; see the module docstring.

    Subclasses implement `_update(cycle)` and set `_p`, `_v`, `_a` and `_counts`.
    """

    def __init__(self, counts_per_unit: float) -> None:
        self.counts_per_unit = _positive("counts_per_unit", counts_per_unit)
        self._cycle: int | None = None
        self._p = 0.0
        self._v = 0.0
        self._a = 0.0
        self._counts = 0

    def update(self, cycle: int) -> None:
        """Read or generate the master of `cycle`; once per cycle (repeated calls are ignored)."""
        if cycle == self._cycle:
            return
        self._update(cycle)
        self._cycle = cycle

    @abstractmethod
    def _update(self, cycle: int) -> None: ...

    @property
    def cycle(self) -> int | None:
        """Last cycle passed to `update` (None before the first)."""
        return self._cycle

    @property
    def position(self) -> float:
        """Master position, master user units, unwrapped."""
        return self._p

    @property
    def velocity(self) -> float:
        return self._v

    @property
    def acceleration(self) -> float:
        return self._a

    @property
    def counts(self) -> int:
        """Integer master position (see the module docstring)."""
        return self._counts

    def __repr__(self) -> str:
        return f"{type(self).__name__}(p={self._p:.6g}, v={self._v:.6g}, counts={self._counts})"


# ------------------------------------------------------------------------ axis


class AxisMaster(Master):
    """Another axis as master: its set point (use="command") or its actual position ("actual").

    The set point is exact (position, velocity and acceleration of the master's profile).
    The actual position comes from the axis' last position loop; its velocity is the
    axis' actual velocity and the acceleration its difference per cycle.

    Order: update the master axis' set point before the slaves sample this master (a gear
    that samples first sees the master's previous cycle: one cycle of lag).
    """

    def __init__(
        self,
        axis: Any,
        use: Literal["command", "actual"] = "command",
        *,
        counts_per_unit: float = FINE_COUNTS_PER_UNIT,
    ) -> None:
        if use not in ("command", "actual"):
            raise ValueError(f"use must be 'command' or 'actual', got {use!r}")
        super().__init__(counts_per_unit)
        self.axis = axis
        self.use = use
        self._period = _period(axis.period)
        self._read()
        self._a = 0.0 if use == "actual" else self._a

    def _read(self) -> None:
        ax = self.axis
        if self.use == "command":
            self._p = ax.command_position
            self._v = ax.command_velocity
            self._a = ax.command_acceleration
        else:
            self._p = ax.actual_position
            self._v = ax.actual_velocity
        self._counts = _quantise(self._p, self.counts_per_unit)

    def _update(self, cycle: int) -> None:
        v_before = self._v
        self._read()
        if self.use == "actual":
            n = 1 if self._cycle is None else cycle - self._cycle
            self._a = (self._v - v_before) / (max(n, 1) * self._period)


# ------------------------------------------------------------------------ encoder


class EncoderMaster(Master):
    """An encoder as master (line encoder, measuring wheel).

    encoder: an IncrementalEncoder, or any object with an integer `counts`. A counter that
    wraps is unwrapped with the encoder's `delta(new, old)`, or, for objects without one,
    with `counter_bits`. The counter must not move more than half its range per cycle.

    counts_per_unit: encoder counts per master unit. multiplier: integer factor on the
    counts handed to gears (-1: the encoder counts backwards; 4: express the counts in
    finer steps); the master's `counts_per_unit` is counts_per_unit * |multiplier|, so the
    position does not depend on it except for the sign.

    Velocity (the feed-forward of the slaves):
      * "window" (FS701 "Sampling Time"): counts moved over the last N cycles / (N*T),
        N = round(sampling_time / period) >= 1 (a ring of N+1 preallocated entries).
        At constant speed this is the exact mean speed once the window is full (N+1
        updates); on a ramp it lags by N*T/2 (v = v_true - a*N*T/2). Acceleration: the
        change of that velocity over the same window (exact on a ramp after 2N+1 updates).
      * "first_order": v += alpha * (counts of this cycle / T - v), alpha = 1 - exp(-T/tau).
        On a ramp of acceleration a the estimate lags by a * (T/(exp(T/tau) - 1) + T/2)
        (about a * tau): the filter lag plus half a cycle of the count difference.
        Acceleration: the change of the filtered velocity per cycle.
      Before a second update both are 0.
    """

    def __init__(
        self,
        encoder: Any,
        counts_per_unit: float,
        period: float,
        *,
        multiplier: int = 1,
        velocity_filter: Literal["window", "first_order"] = "window",
        sampling_time: float | None = None,
        time_constant: float | None = None,
        counter_bits: int | None = None,
    ) -> None:
        if isinstance(multiplier, bool) or not isinstance(multiplier, int) or multiplier == 0:
            raise ValueError(f"multiplier must be a non-zero integer, got {multiplier!r}")
        cpu = _positive("counts_per_unit", counts_per_unit)
        super().__init__(cpu * abs(multiplier))
        self.period = _period(period)
        self.encoder = encoder
        self.multiplier = multiplier
        if velocity_filter not in ("window", "first_order"):
            raise ValueError(f"velocity_filter must be 'window' or 'first_order', got {velocity_filter!r}")
        self.velocity_filter = velocity_filter
        if counter_bits is not None and (
            isinstance(counter_bits, bool) or not isinstance(counter_bits, int) or not 1 <= counter_bits <= 64
        ):
            raise ValueError(f"counter_bits must be an integer in 1..64, got {counter_bits!r}")
        self._modulus = 1 << counter_bits if counter_bits is not None else 0
        delta = getattr(encoder, "delta", None)
        self._delta = delta if callable(delta) else self._plain_delta

        if velocity_filter == "window":
            st = self.period if sampling_time is None else _positive("sampling_time", sampling_time)
            self.window_cycles = max(1, round(st / self.period))
            self.time_constant = None
        else:
            if time_constant is None:
                raise ValueError("velocity_filter 'first_order' needs time_constant (seconds)")
            self.time_constant = _positive("time_constant", time_constant)
            self.window_cycles = 1
        self._alpha1 = 1.0 - math.exp(-self.period / self.time_constant) if self.time_constant else 1.0

        n = self.window_cycles + 1
        self._ring_cycle = [0] * n
        self._ring_counts = [0] * n
        self._ring_v = [0.0] * n
        self._head = -1
        self._fill = 0

        self._raw = self._read_raw()
        self._counts = self._raw * multiplier
        self._p = self._counts / self.counts_per_unit

    def _read_raw(self) -> int:
        raw = self.encoder.counts
        if isinstance(raw, bool) or not hasattr(raw, "__index__"):
            raise TypeError(f"encoder.counts must be an integer, got {raw!r}")
        return int(raw)

    def _plain_delta(self, new: int, old: int) -> int:
        d = new - old
        m = self._modulus
        if m:
            d %= m
            if d >= m // 2:
                d -= m
        return d

    def _update(self, cycle: int) -> None:
        raw = self._read_raw()
        d = self._delta(raw, self._raw) * self.multiplier
        self._raw = raw
        counts = self._counts + d
        self._counts = counts
        cpu = self.counts_per_unit
        self._p = counts / cpu
        if self.velocity_filter == "window":
            ring_cycle = self._ring_cycle
            n = len(ring_cycle)
            i = (self._head + 1) % n
            self._head = i
            fill = self._fill
            if fill < n:
                fill += 1
                self._fill = fill
            ring_cycle[i] = cycle
            ring_counts = self._ring_counts
            ring_counts[i] = counts
            if fill > 1:
                j = (i - fill + 1) % n  # oldest entry: N cycles back once the ring is full
                dt = (cycle - ring_cycle[j]) * self.period
                v = (counts - ring_counts[j]) / (cpu * dt)
                self._a = (v - self._ring_v[j]) / dt
                self._v = v
            self._ring_v[i] = self._v
        else:
            previous = self._cycle
            if previous is None:
                return
            steps = cycle - previous
            dt = steps * self.period
            alpha = self._alpha1 if steps == 1 else 1.0 - math.exp(-dt / self.time_constant)  # type: ignore[operator]
            v_raw = d / (cpu * dt)
            v_new = self._v + alpha * (v_raw - self._v)
            self._a = (v_new - self._v) / dt
            self._v = v_new


# ------------------------------------------------------------------------ virtual master


class VirtualMaster(Master):
    """A master that runs at a commanded velocity with ramps (FS701 virtual master axis).

    `set_velocity(v)` replans on the fly from the state of the last update with
    plan_velocity (shape "jerk" when a jerk is given, else "trapezoid"; or `shape`).
    The position is the profile's, sampled at exact times: no integration error.
    `counts` quantises it at `counts_per_unit` (the resolution integer gears count in).
    A velocity set before the first update ramps from the cycle before that update.
    """

    def __init__(
        self,
        period: float,
        velocity: float = 0.0,
        *,
        acceleration: float,
        deceleration: float | None = None,
        jerk: float | None = None,
        shape: Literal["trapezoid", "jerk", "sin2"] | None = None,
        position: float = 0.0,
        counts_per_unit: float = FINE_COUNTS_PER_UNIT,
    ) -> None:
        super().__init__(counts_per_unit)
        self.period = _period(period)
        self.acceleration_limit = _positive("acceleration", acceleration)
        self.deceleration_limit = self.acceleration_limit if deceleration is None else _positive("deceleration", deceleration)
        self.jerk_limit = None if jerk is None else _positive("jerk", jerk)
        if shape is None:
            shape = "jerk" if jerk is not None else "trapezoid"
        if shape not in ("trapezoid", "jerk", "sin2"):
            raise ValueError(f"shape must be 'trapezoid', 'jerk' or 'sin2', got {shape!r}")
        if shape != "trapezoid" and jerk is None:
            raise ValueError(f"shape {shape!r} needs a jerk")
        self.shape = shape
        self._p = _finite("position", position)
        self._counts = _quantise(self._p, self.counts_per_unit)
        self._target = 0.0
        self._profile: Profile | None = None
        self._c0: int | None = None
        self.set_velocity(velocity)

    @property
    def target_velocity(self) -> float:
        return self._target

    @property
    def in_velocity(self) -> bool:
        """The commanded velocity is reached (the ramp has ended)."""
        return self._v == self._target and self._a == 0.0

    def set_velocity(self, velocity: float) -> None:
        """Ramp to `velocity` (sign = direction) from the state of the last update."""
        v = _finite("velocity", velocity)
        lim = Limits(
            v=_NO_SPEED_LIMIT,
            a=self.acceleration_limit,
            d=self.deceleration_limit,
            j=self.jerk_limit if self.shape != "trapezoid" else None,
        )
        self._target = v
        self._profile = plan_velocity(self.shape, State(self._p, self._v, self._a), v, lim)
        self._c0 = self._cycle  # None: bind to the cycle before the first update

    def stop(self) -> None:
        self.set_velocity(0.0)

    def _update(self, cycle: int) -> None:
        profile = self._profile
        assert profile is not None
        if self._c0 is None:
            self._c0 = cycle - 1
        p, v, a, _ = profile.sample((cycle - self._c0) * self.period)
        self._p, self._v, self._a = p, v, a
        self._counts = _quantise(p, self.counts_per_unit)


# ------------------------------------------------------------------------ internal time base


class TimeBase(Master):
    """Internal time base (COMPAX P30 = 1): position = speed * t.

    A speed change ramps linearly over `ramp_time` seconds whatever its size (COMPAX P39
    "is an absolute time; depending on the target speed, the gradient ... varies"); 0 is a
    step. A change during a ramp starts a new ramp from the speed reached. The position
    is the closed-form integral at exact times.
    """

    def __init__(
        self,
        period: float,
        speed: float = 0.0,
        *,
        ramp_time: float = 0.0,
        position: float = 0.0,
        counts_per_unit: float = FINE_COUNTS_PER_UNIT,
    ) -> None:
        super().__init__(counts_per_unit)
        self.period = _period(period)
        self.ramp_time = self._ramp(ramp_time)
        self._p = _finite("position", position)
        self._counts = _quantise(self._p, self.counts_per_unit)
        # segment: from cycle _c0 at (_p0, _v0) ramp to _v1 over _tr seconds, then constant
        self._p0 = self._p
        self._v0 = 0.0
        self._v1 = 0.0
        self._tr = 0.0
        self._c0: int | None = None
        self.set_speed(speed, ramp_time=0.0)  # the initial speed holds from the start
        self._v = self._v1

    @staticmethod
    def _ramp(ramp_time: float) -> float:
        if isinstance(ramp_time, bool) or not isinstance(ramp_time, (int, float)) or not (
            math.isfinite(ramp_time) and ramp_time >= 0
        ):
            raise ValueError(f"ramp_time must be a number of seconds >= 0, got {ramp_time!r}")
        return float(ramp_time)

    @property
    def speed(self) -> float:
        """Target speed (the speed after the ramp)."""
        return self._v1

    def set_speed(self, speed: float, ramp_time: float | None = None) -> None:
        """Change the speed, ramping from the last update's state over ramp_time (None: the default)."""
        s = _finite("speed", speed)
        self._p0 = self._p
        self._v0 = self._v
        self._v1 = s
        self._tr = self.ramp_time if ramp_time is None else self._ramp(ramp_time)
        if self._tr == 0.0:
            self._v0 = s
        self._c0 = self._cycle

    def _update(self, cycle: int) -> None:
        if self._c0 is None:
            self._c0 = cycle - 1
        t = (cycle - self._c0) * self.period
        tr, v0, v1 = self._tr, self._v0, self._v1
        if t < tr:
            a = (v1 - v0) / tr
            self._p = self._p0 + t * (v0 + 0.5 * a * t)
            self._v = v0 + a * t
            self._a = a
        else:
            self._p = self._p0 + 0.5 * (v0 + v1) * tr + v1 * (t - tr)
            self._v = v1
            self._a = 0.0
        self._counts = _quantise(self._p, self.counts_per_unit)
