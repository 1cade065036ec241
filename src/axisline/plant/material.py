"""Material moving through the line (web, strip, profile) and slipping contacts with it.

:class:`MaterialLine` is material whose line speed follows a speed profile. Between events the
acceleration is constant, so the position is integrated exactly, and any moment inside a cycle
(for example a print mark reaching a sensor) is found by solving the motion's quadratic.

:class:`SlipContact` is a wheel or roll in frictional contact with a moving surface: a
measuring wheel on the material, or material pulled by a driven feed roll. It follows the
surface's travel scaled by ``1 - slip``.
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from typing import NamedTuple

import numpy as np

from .kinematics import NO_CROSSINGS, Crossing, quadratic_root

__all__ = ["MaterialLine", "SlipContact", "SpeedChange"]


class SpeedChange(NamedTuple):
    """From ``time`` (s) on, ramp the line speed to ``speed`` (units/s) at ``acceleration``.

    ``acceleration`` is a magnitude in units/s^2; ``math.inf`` changes the speed at once.
    """

    time: float
    speed: float
    acceleration: float = math.inf


def _turning_point(segment: tuple[float, float, float, float, float]) -> float | None:
    """Time at which a segment (offset, duration, p0, v0, a) turns round strictly inside it,
    or None: then the segment is monotonic."""
    _, h, _, v0, a = segment
    if a != 0.0:
        t_turn = -v0 / a
        if 0.0 < t_turn < h:
            return t_turn
    return None


class MaterialLine:
    """Material running at a line speed that follows a speed profile.

    The profile is a list of :class:`SpeedChange`; :meth:`set_speed` changes the speed at run
    time, from the start of the next step. A newer change supersedes a ramp in progress, and the
    ramp always starts from the actual speed.

    Time is the integer number of steps times the period (never accumulated), so it equals the
    kernel's cycle time; a change of period restarts the count from the current time.
    """

    def __init__(
        self,
        profile: Iterable[SpeedChange | tuple[float, float, float]] = (),
        *,
        speed: float = 0.0,
        position: float = 0.0,
    ) -> None:
        changes = [SpeedChange(*change) for change in profile]
        for change in changes:
            if not change.acceleration > 0.0:
                raise ValueError(f"speed change acceleration must be > 0, got {change}")
        # Stable sort: changes given for the same time apply in the order written.
        self._profile = sorted(changes, key=lambda change: change.time)
        self._next = 0
        self.position = float(position)
        self.velocity = float(speed)
        self.acceleration = 0.0
        self.target_speed = float(speed)
        self._ramp = math.inf
        self._t_base = 0.0
        self._steps = 0
        self._dt = 0.0
        self._t_next = self._profile[0].time if self._profile else math.inf  # next change due
        self.cycle_start_time = 0.0
        self.cycle_start_position = self.position
        # Constant-acceleration segments of the last cycle: (offset (s), duration, p0, v0, a).
        self._segs: list[tuple[float, float, float, float, float]] = []
        self._bounds_valid = False
        self._lo = self._hi = self.position

    @property
    def time(self) -> float:
        """Time in seconds at the end of the last step."""
        return self._t_base + self._steps * self._dt

    @property
    def profile(self) -> tuple[SpeedChange, ...]:
        return tuple(self._profile)

    def set_speed(self, speed: float, acceleration: float = math.inf) -> None:
        """Ramp to ``speed`` at ``acceleration`` (magnitude) from now on."""
        if not acceleration > 0.0:
            raise ValueError(f"acceleration must be > 0, got {acceleration!r}")
        self.target_speed = float(speed)
        self._ramp = float(acceleration)
        if self._ramp == math.inf:
            self.velocity = self.target_speed
        self.acceleration = self._current_acceleration()

    def _current_acceleration(self) -> float:
        if self.velocity == self.target_speed:
            return 0.0
        return math.copysign(self._ramp, self.target_speed - self.velocity)

    def _apply_due(self, t: float) -> float:
        """Apply the profile changes due at ``t``; return the time of the next one (inf: none)."""
        profile = self._profile
        while self._next < len(profile) and profile[self._next].time <= t:
            change = profile[self._next]
            self._next += 1
            self.set_speed(change.speed, change.acceleration)
        self._t_next = profile[self._next].time if self._next < len(profile) else math.inf
        return self._t_next

    def step(self, dt: float) -> None:
        """Advance one cycle of ``dt`` seconds, applying the profile changes that fall in it."""
        t0 = self._t_base + self._steps * self._dt  # self.time, inline (per cycle)
        if dt != self._dt:
            self._t_base, self._steps, self._dt = t0, 0, dt
        self._steps += 1
        t_end = self._t_base + self._steps * self._dt
        self.cycle_start_time = t0
        self.cycle_start_position = p = self.position
        self._bounds_valid = False
        self._segs = segs = []
        t = t0
        # the next change's time, inf when none is left: "t_next <= t" and "t_next - t < h"
        # are then false, as the profile-length checks they stand for
        t_next = self._t_next
        while True:
            if t_next <= t:
                t_next = self._apply_due(t)
            if t >= t_end:
                break
            v = self.velocity
            target = self.target_speed
            h = t_end - t
            reaches_end = True
            if t_next - t < h:
                h = t_next - t
                reaches_end = False
            a = 0.0 if v == target else math.copysign(self._ramp, target - v)  # _current_acceleration
            ramp_ends = False
            if a != 0.0:
                t_ramp = abs(target - v) / self._ramp
                if t_ramp <= h:
                    h = t_ramp
                    ramp_ends = True
                    reaches_end = t_ramp == t_end - t
            segs.append((t - t0, h, p, v, a))
            p += v * h + 0.5 * a * h * h
            # A ramp ends exactly on its target speed, not on a rounded sum.
            self.velocity = target if ramp_ends else v + a * h
            t = t_end if reaches_end else t + h
        self.position = p
        self.acceleration = self._current_acceleration()

    # -- motion inside the last cycle ----------------------------------------------------------

    def _segment(self, fraction: float) -> tuple[tuple[float, float, float, float, float], float]:
        t = fraction * self._dt
        segs = self._segs
        i = len(segs) - 1
        while i > 0 and segs[i][0] > t:
            i -= 1
        return segs[i], t - segs[i][0]

    def position_at(self, fraction: float) -> float:
        """Exact position at ``fraction`` (0..1) of the last cycle."""
        if not self._segs or fraction >= 1.0:
            return self.position
        (_, _, p0, v0, a), tau = self._segment(fraction)
        return p0 + v0 * tau + 0.5 * a * tau * tau

    def velocity_at(self, fraction: float) -> float:
        """Exact line speed at ``fraction`` (0..1) of the last cycle."""
        if not self._segs or fraction >= 1.0:
            return self.velocity
        (_, _, _, v0, a), tau = self._segment(fraction)
        return v0 + a * tau

    def _pieces(self, i: int) -> tuple[tuple[float, float, float, float], ...]:
        """Monotonic pieces (t_a, t_b, p_a, p_b) of segment ``i``: split at a turning point."""
        segs = self._segs
        _, h, p0, v0, a = segs[i]
        p_end = segs[i + 1][2] if i + 1 < len(segs) else self.position
        t_turn = _turning_point(segs[i])
        if t_turn is not None:
            p_turn = p0 + v0 * t_turn + 0.5 * a * t_turn * t_turn
            return ((0.0, t_turn, p0, p_turn), (t_turn, h, p_turn, p_end))
        return ((0.0, h, p0, p_end),)

    def position_bounds(self) -> tuple[float, float]:
        """Lowest and highest position during the last cycle."""
        if not self._bounds_valid:
            segs = self._segs
            lo = hi = self.position
            if len(segs) == 1 and _turning_point(segs[0]) is None:
                # the usual cycle, one monotonic segment, is one piece from p0 to position:
                # the min/max below, written as comparisons
                p0 = segs[0][2]
                lo = p0 if p0 < lo else lo
                hi = p0 if p0 > hi else hi
            else:
                for i in range(len(segs)):
                    for _, _, pa, pb in self._pieces(i):
                        lo, hi = min(lo, pa, pb), max(hi, pa, pb)
            self._lo, self._hi = lo, hi
            self._bounds_valid = True
        return self._lo, self._hi

    def crossings(self, x: float) -> tuple[Crossing, ...]:
        """Moments in the last cycle the material position crossed ``x``, solved exactly."""
        lo, hi = self.position_bounds()
        if x <= lo or x > hi:
            return NO_CROSSINGS
        events: list[Crossing] = []
        for i, (off, _, p0, v0, a) in enumerate(self._segs):
            for ta, tb, pa, pb in self._pieces(i):
                if (pa >= x) != (pb >= x):
                    tau = quadratic_root(p0, v0, a, x, ta, tb)
                    events.append(((off + tau) / self._dt, 1 if pb >= x else -1))
        return tuple(events)


class SlipContact:
    """A wheel or roll following a moving surface's travel, less its slip.

    Over a travel ``s`` of the surface (``source.position`` since construction) the contact
    turns by ``(1 - slip) * s``: a measuring wheel that sees ``material_position * (1 - slip)``,
    or material pulled by a feed roll (source: the roll's drive) that lags the roll.

    Optional slip jitter varies the slip along the travel: every ``jitter_length`` of surface
    travel holds its own slip, ``slip + jitter`` with the jitter drawn from ``rng`` (normal,
    standard deviation ``slip_jitter``, clipped at 3 sigma). Because the jitter depends on where
    the surface is, not on when it is sampled, the contact's position does not depend on the
    cycle period, and the same seed gives the same wheel on every run.

    The source must trace its motion (``crossings``/``position_bounds``, as every plant source
    does); the contact answers the same questions by mapping them onto the source.
    """

    _BATCH = 256

    def __init__(
        self,
        source: object,
        *,
        slip: float = 0.0,
        slip_jitter: float = 0.0,
        jitter_length: float = 0.1,
        rng: np.random.Generator | None = None,
        position: float = 0.0,
    ) -> None:
        if not (hasattr(source, "crossings") and hasattr(source, "position_bounds")):
            raise TypeError("SlipContact needs a source with crossings() and position_bounds()")
        if not 0.0 <= slip + 3.0 * slip_jitter < 1.0 or slip_jitter < 0.0:
            raise ValueError("slip + 3 * slip_jitter must lie in [0, 1) and slip_jitter >= 0")
        if slip_jitter > 0.0 and rng is None:
            raise ValueError("slip_jitter needs a numpy Generator (rng)")
        if not jitter_length > 0.0:
            raise ValueError("jitter_length must be > 0")
        self.source = source
        self._origin = float(source.position)  # type: ignore[attr-defined]
        self._slip = float(slip)
        self._scale = 1.0 - self._slip  # the contact's travel per surface travel, without jitter
        self._sigma = float(slip_jitter)
        self._cell = float(jitter_length)
        self._w_base = float(position)
        self._s_base = 0.0
        # Jitter per travel cell; forward and backward cells come from separate streams so the
        # cells do not depend on the order in which the travel reaches them.
        self._rng_fwd = rng
        self._rng_back = rng.spawn(1)[0] if (rng is not None and slip_jitter > 0.0) else None
        self._jit_fwd: list[float] = []
        self._cum_fwd: list[float] = [0.0]
        self._jit_back: list[float] = []
        self._cum_back: list[float] = [0.0]

    @property
    def slip(self) -> float:
        return self._slip

    def set_slip(self, slip: float) -> None:
        """Change the mean slip from here on (the contact's position does not jump)."""
        if not 0.0 <= slip + 3.0 * self._sigma < 1.0:
            raise ValueError("slip + 3 * slip_jitter must lie in [0, 1)")
        s = self._travel(self.source.position)  # type: ignore[attr-defined]
        self._w_base = self._wheel(s)
        self._s_base = s
        self._slip = float(slip)
        self._scale = 1.0 - self._slip

    # -- travel <-> contact position -----------------------------------------------------------

    def _travel(self, source_position: float) -> float:
        return source_position - self._origin

    def _draw(self, rng: np.random.Generator, jit: list[float], cum: list[float]) -> None:
        values = (self._sigma * np.clip(rng.standard_normal(self._BATCH), -3.0, 3.0)).tolist()
        for value in values:
            jit.append(value)
            cum.append(cum[-1] + value * self._cell)

    def _cell_jitter(self, k: int) -> float:
        """Jitter of travel cell ``k`` (covering ``[k, k+1) * jitter_length``)."""
        if self._sigma == 0.0:
            return 0.0
        if k >= 0:
            while k >= len(self._jit_fwd):
                self._draw(self._rng_fwd, self._jit_fwd, self._cum_fwd)  # type: ignore[arg-type]
            return self._jit_fwd[k]
        m = -k - 1
        while m >= len(self._jit_back):
            self._draw(self._rng_back, self._jit_back, self._cum_back)  # type: ignore[arg-type]
        return self._jit_back[m]

    def _jitter_integral(self, s: float) -> float:
        """Integral of the slip jitter over the travel from 0 to ``s``."""
        if self._sigma == 0.0:
            return 0.0
        k = math.floor(s / self._cell)
        j = self._cell_jitter(k)  # also makes sure the cumulative lists reach cell k
        start = self._cum_fwd[k] if k >= 0 else -self._cum_back[-k]
        return start + j * (s - k * self._cell)

    def _wheel(self, s: float) -> float:
        if self._sigma == 0.0:  # no jitter: both integrals are 0.0 (x - (0.0 - 0.0) is x)
            return self._w_base + self._scale * (s - self._s_base)
        return (
            self._w_base
            + self._scale * (s - self._s_base)
            - (self._jitter_integral(s) - self._jitter_integral(self._s_base))
        )

    def _travel_for(self, w: float) -> float:
        """Travel at which the contact reaches ``w`` (the contact's motion is strictly increasing
        in the travel, so this is unique); deterministic, so a threshold maps to the same travel
        in every cycle."""
        guess = self._s_base + (w - self._w_base) / self._scale
        if self._sigma == 0.0:
            return guess
        L = self._cell
        k = math.floor(guess / L)
        while self._wheel(k * L) > w:
            k -= 1
        while self._wheel((k + 1) * L) <= w:
            k += 1
        return k * L + (w - self._wheel(k * L)) / (self._scale - self._cell_jitter(k))

    # -- position source -----------------------------------------------------------------------

    @property
    def position(self) -> float:
        """Contact position in user units (e.g. the measuring wheel's rolled-off length)."""
        return self._wheel(self.source.position - self._origin)  # type: ignore[attr-defined]  # _travel, inline

    @property
    def velocity(self) -> float:
        s = self._travel(self.source.position)  # type: ignore[attr-defined]
        k = math.floor(s / self._cell)
        return self.source.velocity * (self._scale - self._cell_jitter(k))  # type: ignore[attr-defined]

    def position_bounds(self) -> tuple[float, float]:
        lo, hi = self.source.position_bounds()  # type: ignore[attr-defined]
        origin = self._origin  # (_travel, inline)
        return self._wheel(lo - origin), self._wheel(hi - origin)

    def crossings(self, x: float) -> tuple[Crossing, ...]:
        return self.source.crossings(self._origin + self._travel_for(x))  # type: ignore[attr-defined]
