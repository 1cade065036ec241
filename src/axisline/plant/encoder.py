"""Incremental encoders: quantised counts, x1/x2/x4 evaluation, index pulse latch, wrap-around.

Counting convention: the count is ``floor(direction * position * lines_per_unit * multiplier)``.
Floor is what a counter does: it changes when an edge is passed, and edge ``n`` sits at
``n / (lines_per_unit * multiplier)``, so a position exactly on an edge shows the count reached by
passing it forwards. Positions within 1e-9 count below an edge count as on it, so decimal
positions such as 0.7 mm give the count they name despite binary floating point.
"""

from __future__ import annotations

import math

import numpy as np

from .kinematics import cycle_bounds, cycle_crossings
from .material import SlipContact

__all__ = ["IncrementalEncoder", "MeasuringWheel"]

_EDGE_TOLERANCE = 1e-9  # counts


class IncrementalEncoder:
    """Incremental (quadrature) encoder reading the position of ``source``.

    ``lines_per_unit`` lines per user unit, evaluated x1, x2 or x4 (``multiplier`` counts per
    line). ``direction=-1`` counts the other way (encoder mounted mirrored). With
    ``counter_bits`` the count wraps like a hardware counter of that width and is reported
    unsigned in ``0 .. 2**bits - 1``; use :meth:`delta` for signed differences.

    With ``index_every_units`` an index pulse sits at ``index_offset + k * index_every_units``
    (source positions). :meth:`arm_index` arms the latch; the first index passed afterwards
    latches ``index_count`` (the count at the index position), ``index_position`` and
    ``index_fraction`` (when in the cycle it passed, 0..1, exact for plant sources).

    Call :meth:`sample` once after every plant step.
    """

    def __init__(
        self,
        source: object,
        lines_per_unit: float,
        multiplier: int = 4,
        index_every_units: float | None = None,
        counter_bits: int | None = None,
        direction: int = 1,
        index_offset: float = 0.0,
    ) -> None:
        if multiplier not in (1, 2, 4):
            raise ValueError(f"multiplier must be 1, 2 or 4, got {multiplier!r}")
        if direction not in (1, -1):
            raise ValueError(f"direction must be +1 or -1, got {direction!r}")
        if not lines_per_unit > 0.0:
            raise ValueError("lines_per_unit must be > 0")
        if index_every_units is not None and not index_every_units > 0.0:
            raise ValueError("index_every_units must be > 0")
        if counter_bits is not None and not 1 <= counter_bits <= 64:
            raise ValueError("counter_bits must be in 1..64")
        self.source = source
        self.lines_per_unit = float(lines_per_unit)
        self.multiplier = int(multiplier)
        self.direction = int(direction)
        self.index_every_units = index_every_units
        self.index_offset = float(index_offset)
        self.counter_bits = counter_bits
        self._modulus = 1 << counter_bits if counter_bits is not None else 0
        self._previous = float(source.position)  # type: ignore[attr-defined]
        self.counts_unwrapped = self.counts_at(self._previous)
        self.counts = self._wrap(self.counts_unwrapped)
        self.index_armed = False
        self.index_latched = False
        self.index_count = 0
        self.index_position = 0.0
        self.index_fraction = 0.0
        self.index_pulses = 0
        """Index pulses passed during the last cycle."""

    @property
    def counts_per_unit(self) -> float:
        return self.lines_per_unit * self.multiplier

    def counts_at(self, position: float) -> int:
        """Unwrapped count the encoder shows at ``position``."""
        value = self.direction * position * self.lines_per_unit * self.multiplier
        return math.floor(value + _EDGE_TOLERANCE)

    def _wrap(self, counts: int) -> int:
        return counts % self._modulus if self._modulus else counts

    def delta(self, new: int, old: int) -> int:
        """Signed count difference ``new - old``, correct across one counter wrap."""
        d = new - old
        if self._modulus:
            d %= self._modulus
            if d >= self._modulus // 2:
                d -= self._modulus
        return d

    def arm_index(self) -> None:
        """Latch the next index pulse (clears the previous latch)."""
        self.index_armed = True
        self.index_latched = False

    def sample(self) -> int:
        """Read the counter after a plant step; also watch for index pulses in that step."""
        previous = self._previous
        position = float(self.source.position)  # type: ignore[attr-defined]
        self.index_pulses = 0
        every = self.index_every_units
        if every is not None:
            lo, hi = cycle_bounds(self.source, previous)
            offset = self.index_offset
            first = math.ceil((lo - offset) / every)
            last = math.floor((hi - offset) / every)
            if first <= last:  # (else no index position within the cycle's travel: no pulse)
                self._watch_index(previous, first, last)
        self._previous = position
        self.counts_unwrapped = counts = self.counts_at(position)
        self.counts = counts = self._wrap(counts)
        return counts

    def _watch_index(self, previous: float, first: int, last: int) -> None:
        """Count the index pulses ``first..last`` passed in the cycle; latch the first if armed."""
        every = self.index_every_units
        assert every is not None
        best_fraction = math.inf
        best_x = 0.0
        for k in range(first, last + 1):
            x = self.index_offset + k * every
            for fraction, _ in cycle_crossings(self.source, previous, x):
                self.index_pulses += 1
                if fraction < best_fraction:
                    best_fraction, best_x = fraction, x
        if self.index_armed and self.index_pulses:
            self.index_armed = False
            self.index_latched = True
            self.index_fraction = best_fraction
            self.index_position = best_x
            self.index_count = self._wrap(self.counts_at(best_x))


class MeasuringWheel(IncrementalEncoder):
    """Encoder on a wheel rolling on the material: sees ``material travel * (1 - slip)``.

    ``circumference`` (user units) sets one index pulse per revolution. The wheel is a
    :class:`SlipContact`, so slip may carry seeded jitter along the travel and may be changed
    at run time with ``wheel.contact.set_slip``.
    """

    def __init__(
        self,
        material: object,
        lines_per_unit: float,
        multiplier: int = 4,
        *,
        slip: float = 0.0,
        slip_jitter: float = 0.0,
        jitter_length: float = 0.1,
        rng: np.random.Generator | None = None,
        circumference: float | None = None,
        counter_bits: int | None = None,
        direction: int = 1,
    ) -> None:
        self.contact = SlipContact(
            material, slip=slip, slip_jitter=slip_jitter, jitter_length=jitter_length, rng=rng
        )
        super().__init__(
            self.contact,
            lines_per_unit,
            multiplier,
            index_every_units=circumference,
            counter_bits=counter_bits,
            direction=direction,
        )

    @property
    def wheel_position(self) -> float:
        """Length the wheel has rolled off, user units."""
        return self.contact.position
