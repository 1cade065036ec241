"""A planned profile as data: State, Limits, the segment list and O(1) sampling.

    prof.duration, prof.sample(t) -> (p, v, a, j)

Every profile is a short list of segments. A segment is either a polynomial with
constant jerk or a sin² acceleration ramp; sampling finds the segment with a
bisection over at most ~10 start times and evaluates a closed form, so it is O(1)
and builds no containers. The planners (motion.profiles, motion.uddu) write the
segments through a `Segments` builder, one call per segment, straight into the
lists the profile samples (no tuple per segment).
"""

from __future__ import annotations

import math
from bisect import bisect_right
from dataclasses import dataclass
from typing import Final

__all__ = ["State", "Limits", "Profile"]

# Final: compiled code reads them as constants, not from the module dict
SIN2_C: Final = 0.25 - 1.0 / (math.pi * math.pi)  # position coefficient of a sin² ramp
LINEAR: Final = 0  # segment kinds
SIN2: Final = 1


@dataclass(frozen=True, slots=True)
class State:
    """Kinematic state: position, velocity, acceleration (user units, seconds)."""

    p: float = 0.0
    v: float = 0.0
    a: float = 0.0


@dataclass(frozen=True, slots=True)
class Limits:
    """Motion limits.

    v: maximum speed; a: acceleration; d: deceleration (None: same as a);
    j: jerk (shapes "jerk" and "sin2"; for sin² the peak jerk);
    ramp_time: alternative to j, time for the acceleration to rise from 0 to a
    (WAGO Acceleration_RampUp_Param with AccParam 0): j = a / ramp_time;
    up_time/down_time, up_path/down_path: the WAGO time/path variants.
    """

    v: float
    a: float
    d: float | None = None
    j: float | None = None
    ramp_time: float | None = None
    up_time: float | None = None
    down_time: float | None = None
    up_path: float | None = None
    down_path: float | None = None


class Segments:
    """The segments of a profile being planned, in the lists Profile samples.

    add(kind, dur, p, v, a, x): x is the jerk of a linear segment or the acceleration
    change of a sin² ramp. Segments of no duration are dropped; the last one added (kept
    or not) stays readable as `end()` (the state it reaches), as planners chain on it.
    """

    t0: list[float]
    p: list[float]
    v: list[float]
    a: list[float]
    j: list[float]
    tau: list[float]
    kind: list[int]
    t: float
    added: int  # add() calls, dropped segments included
    last: tuple[int, float, float, float, float, float]

    def __init__(self) -> None:
        self.t0, self.p, self.v, self.a, self.j, self.tau, self.kind = [], [], [], [], [], [], []
        self.t = 0.0
        self.added = 0
        self.last = (LINEAR, 0.0, 0.0, 0.0, 0.0, 0.0)

    def add(self, kind: int, dur: float, p: float, v: float, a: float, x: float) -> None:
        self.added += 1
        self.last = (kind, dur, p, v, a, x)
        if dur <= 0.0:
            return
        if kind == SIN2 and dur < 1e-9:
            # pi/dur would overflow the sin² closed form; over a nanosecond a linear
            # ramp with the same acceleration change is the same curve to rounding
            kind, x = LINEAR, x / dur
        self.t0.append(self.t)
        self.p.append(p)
        self.v.append(v)
        self.a.append(a)
        self.j.append(x)
        self.tau.append(dur)
        self.kind.append(kind)
        self.t += dur

    def end(self, s: State) -> State:
        """State at the end of the last segment added; `s` when none was."""
        if self.added == 0:
            return s
        kind, dur, p, v, a, x = self.last
        return seg_end(kind, dur, p, v, a, x)


class Profile:
    """A planned trajectory; sample(t) -> (p, v, a, j).

    Before t = 0 it holds the start state; from `duration` on it continues at the
    final velocity with a = 0 (a velocity profile keeps running, a position profile
    that ends at rest stays at its target).
    """

    __slots__ = ("duration", "start", "target", "shape", "_t0", "_p", "_v", "_a", "_j", "_tau", "_kind")

    def __init__(self, shape: str, start: State, target: State, segments: list[tuple] | Segments) -> None:
        """segments: a Segments builder, or (kind, duration, p, v, a, x) tuples."""
        self.shape = shape
        self.start = start
        self.target = target
        if isinstance(segments, Segments):
            segs = segments
        else:
            segs = Segments()
            for kind, dur, p, v, a, x in segments:
                segs.add(kind, dur, p, v, a, x)
        self._t0: list[float] = segs.t0
        self._p: list[float] = segs.p
        self._v: list[float] = segs.v
        self._a: list[float] = segs.a
        self._j: list[float] = segs.j
        self._tau: list[float] = segs.tau
        self._kind: list[int] = segs.kind
        self.duration = segs.t

    @property
    def segments(self) -> int:
        return len(self._t0)

    def sample(self, t: float) -> tuple[float, float, float, float]:
        """State at time t (seconds from the start of the profile)."""
        if t >= self.duration:
            tg = self.target
            return (tg.p + tg.v * (t - self.duration), tg.v, 0.0, 0.0)
        if t <= 0.0:
            s = self.start
            return (s.p + s.v * t, s.v, s.a, 0.0) if t < 0.0 else (s.p, s.v, s.a, 0.0)
        i = bisect_right(self._t0, t) - 1
        dt = t - self._t0[i]
        p, v, a, x = self._p[i], self._v[i], self._a[i], self._j[i]
        if self._kind[i] == LINEAR:
            return (
                p + dt * (v + dt * (a / 2.0 + dt * x / 6.0)),
                v + dt * (a + dt * x / 2.0),
                a + dt * x,
                x,
            )
        tau = self._tau[i]
        w = math.pi / tau
        sn, c = math.sin(w * dt), math.cos(w * dt)
        return (
            p + v * dt + a * dt * dt / 2.0 + x / 2.0 * (dt * dt / 2.0 + (c - 1.0) / (w * w)),
            v + a * dt + x / 2.0 * (dt - sn / w),
            a + x / 2.0 * (1.0 - c),
            x / 2.0 * w * sn,
        )

    def sample_many(self, ts):
        """Vectorised sampling for plots and reports (allocates; not for the cycle)."""
        import numpy as np

        out = np.empty((len(ts), 4))
        for k, t in enumerate(ts):
            out[k] = self.sample(float(t))
        return out

    def __repr__(self) -> str:
        return f"Profile({self.shape!r}, duration={self.duration:.6g}, segments={self.segments})"


def seg_end(kind: int, dur: float, p: float, v: float, a: float, x: float) -> State:
    """State at the end of one segment (x: jerk, or the acceleration change of a sin² ramp)."""
    if kind == LINEAR:
        return State(p + dur * (v + dur * (a / 2.0 + dur * x / 6.0)), v + dur * (a + dur * x / 2.0), a + dur * x)
    return State(p + v * dur + a * dur * dur / 2.0 + x * SIN2_C * dur * dur, v + a * dur + x / 2.0 * dur, a + x)


# Compiled, the public names get this source's docstrings and annotations back (help(),
# inspect.signature); in plain Python this does nothing. See axisline/_docs.py.
from axisline._docs import document as _document  # noqa: E402

# hot: called every cycle from interpreted code (devices), left compiled-only (no wrapper)
_document(globals(), hot={"Profile": ("sample",)})
