"""Motion within one cycle: the shared vocabulary of plant sources and the sensors that watch them.

A *position source* is anything with a float ``position`` (user units) at the end of the last
plant step. A *traced* source also answers where it was during that step:

- ``crossings(x)`` lists the moments in the last cycle at which the position crossed ``x``, as
  ``(fraction, direction)`` pairs: ``fraction`` in [0, 1] of the cycle, ``direction`` +1 when the
  position rose to or above ``x`` and -1 when it fell below ``x``.
- ``position_bounds()`` gives the lowest and highest position reached during the last cycle.

Crossings follow one rule everywhere: a threshold ``x`` is "reached" when ``position >= x``.
A crossing is reported exactly when that side changes between the ends of a monotonic piece of
the motion, and only its time is found by solving the motion equation. So the edges reported
over many cycles always agree with the positions at the cycle boundaries: no edge is lost or
doubled when the motion starts, stops or reverses right on a threshold.

Sources without ``crossings`` are interpolated linearly between their positions at the last
two samples (exact for constant velocity).
"""

from __future__ import annotations

import math

from .interfaces import Crossing, PositionSource, TracedSource

__all__ = [
    "Crossing",
    "NO_CROSSINGS",
    "PositionSource",
    "TracedSource",
    "bisect_crossing",
    "cycle_bounds",
    "cycle_crossings",
    "linear_crossing",
    "quadratic_root",
]

NO_CROSSINGS: tuple[Crossing, ...] = ()


def linear_crossing(p0: float, p1: float, x: float) -> tuple[Crossing, ...]:
    """Crossing of ``x`` by a straight move from ``p0`` to ``p1`` over the cycle."""
    above0 = p0 >= x
    if above0 == (p1 >= x):
        return NO_CROSSINGS
    fraction = (x - p0) / (p1 - p0)
    # Rounding may push the fraction a hair outside the cycle; the side change is what counts.
    fraction = min(1.0, max(0.0, fraction))
    return ((fraction, -1 if above0 else 1),)


def quadratic_root(p0: float, v0: float, a: float, x: float, lo: float, hi: float) -> float:
    """Time ``t`` in [lo, hi] with ``p0 + v0*t + a*t*t/2 == x`` on a monotonic piece.

    The caller has established that the position crosses ``x`` between ``lo`` and ``hi``;
    this picks the root in that interval with the cancellation-free quadratic formula.
    """
    c = p0 - x
    if a == 0.0:
        t = -c / v0 if v0 != 0.0 else lo
    else:
        disc = v0 * v0 - 2.0 * a * c
        # A crossing exists, so a negative discriminant is rounding of a double root.
        sq = math.sqrt(disc) if disc > 0.0 else 0.0
        q = -0.5 * (v0 + math.copysign(sq, v0))
        r1 = q / (0.5 * a)
        r2 = c / q if q != 0.0 else r1
        mid = 0.5 * (lo + hi)
        t = r1 if abs(r1 - mid) <= abs(r2 - mid) else r2
    return min(hi, max(lo, t))


def cycle_crossings(source: object, previous: float, x: float) -> tuple[Crossing, ...]:
    """Crossings of ``x`` by ``source`` during the last cycle.

    ``previous`` is the source's position at the previous sample; it is used only when the
    source does not trace its own motion.
    """
    crossings = getattr(source, "crossings", None)
    if crossings is not None:
        return crossings(x)
    return linear_crossing(previous, source.position, x)  # type: ignore[attr-defined]


def cycle_bounds(source: object, previous: float) -> tuple[float, float]:
    """Lowest and highest position of ``source`` during the last cycle."""
    bounds = getattr(source, "position_bounds", None)
    if bounds is not None:
        return bounds()
    p1 = source.position  # type: ignore[attr-defined]
    return (previous, p1) if previous <= p1 else (p1, previous)


def bisect_crossing(position_at, fa: float, fb: float, pa: float, x: float) -> float:
    """Fraction in [fa, fb] where a monotonic ``position_at(fraction)`` reaches ``x``.

    ``pa`` is the position at ``fa``; the side of ``x`` differs at ``fb``. Bisection to the
    last bit of the fraction: slower than a closed form but exact for any smooth motion.
    """
    below_a = pa < x
    for _ in range(64):
        fm = 0.5 * (fa + fb)
        if fm <= fa or fm >= fb:
            break
        if (position_at(fm) < x) == below_a:
            fa = fm
        else:
            fb = fm
    return fb
