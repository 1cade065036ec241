"""Sensors that switch at positions: print-mark sensors over the material and axis switches.

Each sensor is sampled once after every plant step with the cycle's start time and period, and
returns the edges of that cycle in time order, each with its exact sub-cycle moment. Edges are
found from the source's exact motion (see :mod:`.kinematics`), so a capture does not depend on
the cycle period. The returned list is reused: copy it to keep it past the next sample.

Decisions
1. (issue 18, the sensors' per-cycle cost) A switch or print-mark sensor computes crossings only
   of the thresholds inside the cycle's position range (``cycle_bounds``): a threshold outside it
   cannot be crossed, as the side of a threshold changes only between positions on both sides of
   it, so the edges and their sub-cycle moments are those of solving every threshold. A switch
   works out once which thresholds can change its state (finite ones; the leave-thresholds only
   with hysteresis). Checked by tests/plant/test_sensors.py (edge moments of switches and marks)
   and by every example's trace staying bit-identical.
"""

from __future__ import annotations

import bisect
import math
from collections.abc import Iterable
from typing import NamedTuple

import numpy as np

from .kinematics import cycle_bounds, cycle_crossings

__all__ = ["Edge", "LimitSwitch", "PositionSwitch", "PrintMarkSensor", "PrintMarks", "ReferenceSwitch"]


class Edge(NamedTuple):
    """A sensor output edge inside a cycle."""

    time: float
    """Absolute time in seconds."""
    fraction: float
    """When in the cycle, 0 (start) .. 1 (end)."""
    rising: bool
    """Output level after the edge (after any inversion)."""
    position: float
    """Source position at the edge (material position for marks, axis position for switches)."""
    mark: int = -1
    """Index of the print mark that caused it; -1 for switches."""


class PrintMarks:
    """Marks printed on the material, each ``width`` long.

    A mark at ``m`` has its leading edge ``m`` behind the material's reference point, so it
    reaches a sensor at line position ``S`` when the material position is ``S + m``, and
    leaves it at ``S + m + width``.

    Either give ``positions`` (explicit, any order), or a ``pitch``: mark ``k`` (k = 0, 1, ...,
    up to ``count`` marks) sits at ``first + k * pitch`` plus a printing jitter (normal, standard
    deviation ``jitter``, clipped at 3 sigma), and is missing with ``missing_probability``. The
    random draws come from ``rng`` in mark order, so the same seed prints the same marks.
    """

    _BATCH = 256

    def __init__(
        self,
        *,
        width: float,
        pitch: float | None = None,
        first: float = 0.0,
        jitter: float = 0.0,
        missing_probability: float = 0.0,
        count: int | None = None,
        positions: Iterable[float] | None = None,
        rng: np.random.Generator | None = None,
    ) -> None:
        if not width > 0.0:
            raise ValueError("width must be > 0")
        if (pitch is None) == (positions is None):
            raise ValueError("give either pitch or positions")
        self.width = float(width)
        self.pitch = pitch
        self.first = float(first)
        self.jitter = float(jitter)
        self.missing_probability = float(missing_probability)
        self.count = count
        self._rng = rng
        self._explicit: list[float] | None = None
        if positions is not None:
            self._explicit = sorted(float(p) for p in positions)
            for a, b in zip(self._explicit, self._explicit[1:]):
                if b - a <= self.width:
                    raise ValueError(f"marks at {a} and {b} overlap (width {self.width})")
            self.count = len(self._explicit)
        else:
            assert pitch is not None
            if not pitch > 0.0:
                raise ValueError("pitch must be > 0")
            if self.width + 6.0 * self.jitter >= pitch:
                raise ValueError("width + 6 * jitter must be less than the pitch (marks overlap)")
            if (self.jitter > 0.0 or self.missing_probability > 0.0) and rng is None:
                raise ValueError("jitter or missing marks need a numpy Generator (rng)")
        self._offsets: list[float] = []  # drawn jitter per mark
        self._present: list[bool] = []

    def _draw(self) -> None:
        rng = self._rng
        assert rng is not None
        # Both draws happen for every mark, so switching one feature on does not shift the other.
        jitter = np.clip(rng.standard_normal(self._BATCH), -3.0, 3.0) * self.jitter
        present = rng.random(self._BATCH) >= self.missing_probability
        self._offsets.extend(jitter.tolist())
        self._present.extend(present.tolist())

    def leading_edge(self, k: int) -> float | None:
        """Position of mark ``k`` on the material, or None if it is missing or out of range."""
        if k < 0 or (self.count is not None and k >= self.count):
            return None
        if self._explicit is not None:
            return self._explicit[k]
        pitch = self.pitch
        assert pitch is not None
        nominal = self.first + k * pitch
        if self._rng is None:
            return nominal
        while k >= len(self._offsets):
            self._draw()
        if not self._present[k]:
            return None
        return nominal + self._offsets[k]

    def indices_near(self, lo: float, hi: float) -> range:
        """Marks that may overlap the material stretch ``[lo, hi]``."""
        if self._explicit is not None:
            start = bisect.bisect_left(self._explicit, lo - self.width)
            stop = bisect.bisect_right(self._explicit, hi)
            return range(start, stop)
        pitch = self.pitch
        assert pitch is not None
        margin = 3.0 * self.jitter
        start = max(0, math.floor((lo - self.width - margin - self.first) / pitch))
        stop = math.floor((hi + margin - self.first) / pitch) + 1
        if self.count is not None:
            stop = min(stop, self.count)
        return range(start, max(start, stop))


class PrintMarkSensor:
    """A print-mark (contrast) sensor fixed at ``sensor_position`` along the line.

    Its output is 1 while a mark is under it (``invert`` for the opposite polarity). ``material``
    is the material's position source: a :class:`~.material.MaterialLine`, or a
    :class:`~.material.SlipContact` for material pulled by a roll.
    """

    def __init__(
        self,
        material: object,
        marks: PrintMarks,
        *,
        sensor_position: float = 0.0,
        invert: bool = False,
    ) -> None:
        self.material = material
        self.marks = marks
        self.sensor_position = float(sensor_position)
        self.invert = bool(invert)
        self.edges: list[Edge] = []
        self._previous = float(material.position)  # type: ignore[attr-defined]
        self.covered = self._covered_at(self._previous)

    def _covered_at(self, p: float) -> bool:
        s = self.sensor_position
        for k in self.marks.indices_near(p - s, p - s):
            m = self.marks.leading_edge(k)
            if m is not None and (p >= s + m) and not (p >= s + m + self.marks.width):
                return True
        return False

    @property
    def state(self) -> bool:
        """Sensor output at the end of the last cycle."""
        return self.covered != self.invert

    def sample(self, t_start: float, dt: float) -> list[Edge]:
        """Edges during the cycle ``[t_start, t_start + dt]`` just simulated."""
        edges = self.edges
        edges.clear()
        source = self.material
        previous = self._previous
        s = self.sensor_position
        width = self.marks.width
        lo, hi = cycle_bounds(source, previous)
        events: list[tuple[float, int, int, int, float]] = []
        covered_marks = 0
        for k in self.marks.indices_near(lo - s, hi - s):
            m = self.marks.leading_edge(k)
            if m is None:
                continue
            arrive, leave = s + m, s + m + width
            if previous >= arrive and not previous >= leave:
                covered_marks += 1
            # A threshold outside the cycle's position range is never crossed in it.
            if lo <= arrive <= hi:
                for fraction, direction in cycle_crossings(source, previous, arrive):
                    events.append((fraction, k, 0, direction, arrive))
            if lo <= leave <= hi:
                for fraction, direction in cycle_crossings(source, previous, leave):
                    events.append((fraction, k, 1, direction, leave))
        # Start from the state the cycle's start position implies, so rounding in a mapped
        # source (a slipping roll) can never leave the output out of step with the material.
        self.covered = covered_marks > 0
        if events:
            events.sort()
            # Each threshold's crossing moves the material to its other side; a mark covers the
            # sensor between its two thresholds. Marks never overlap, so one at a time.
            for fraction, k, which, direction, x in events:
                entering = (direction > 0) == (which == 0)
                covered_marks += 1 if entering else -1
                covered = covered_marks > 0
                if covered != self.covered:
                    self.covered = covered
                    edges.append(
                        Edge(t_start + fraction * dt, fraction, covered != self.invert, x, k)
                    )
        self._previous = float(source.position)  # type: ignore[attr-defined]
        return edges


class PositionSwitch:
    """A switch actuated while an axis is in ``[low, high)`` (either end may be infinite).

    With ``hysteresis`` the switch, once actuated, releases only outside
    ``[low - hysteresis, high + hysteresis)``, as a mechanical or inductive switch does.
    Its output is 1 while actuated; ``invert`` models a normally closed contact.
    """

    def __init__(
        self,
        source: object,
        *,
        low: float = -math.inf,
        high: float = math.inf,
        hysteresis: float = 0.0,
        invert: bool = False,
    ) -> None:
        if not low < high:
            raise ValueError("low must be below high")
        if hysteresis < 0.0:
            raise ValueError("hysteresis must be >= 0")
        self.source = source
        self.low = float(low)
        self.high = float(high)
        self.hysteresis = float(hysteresis)
        self.invert = bool(invert)
        self.edges: list[Edge] = []
        self._previous = float(source.position)  # type: ignore[attr-defined]
        p = self._previous
        self.active = self.low <= p < self.high
        # Thresholds that can change the state: 0 enter-low, 1 enter-high, 2 leave-low,
        # 3 leave-high (a side is "position >= threshold"; infinite ones never change).
        h = self.hysteresis
        self._thresholds: tuple[float, float, float, float] = (self.low, self.high, self.low - h, self.high + h)
        # The thresholds that can change the state, worked out once: the infinite ones never
        # do, and without hysteresis the leave-thresholds are the enter ones (Decision 1).
        self._watched: tuple[tuple[int, float], ...] = tuple(
            (i, x) for i, x in enumerate(self._thresholds) if math.isfinite(x) and (i < 2 or h > 0.0)
        )

    @property
    def state(self) -> bool:
        """Switch output at the end of the last cycle."""
        return self.active != self.invert

    def sample(self, t_start: float, dt: float) -> list[Edge]:
        """Edges during the cycle ``[t_start, t_start + dt]`` just simulated."""
        edges = self.edges
        edges.clear()
        source = self.source
        previous = self._previous
        lo, hi = cycle_bounds(source, previous)
        events: list[tuple[float, int, int]] = []
        for i, x in self._watched:
            # A threshold outside the cycle's position range is never crossed in it: most
            # cycles a switch is far from its axis and computes no crossing at all.
            if lo <= x <= hi:
                for fraction, direction in cycle_crossings(source, previous, x):
                    events.append((fraction, i, direction))
        if events:
            sides = [previous >= x for x in self._thresholds]
            events.sort()
            h0 = self.hysteresis == 0.0
            for fraction, i, direction in events:
                sides[i] = direction > 0
                if h0:
                    sides[i + 2 if i < 2 else i - 2] = sides[i]
                if not self.active:
                    changed = sides[0] and not sides[1]
                else:
                    changed = not sides[2] or sides[3]
                if changed:
                    self.active = not self.active
                    edges.append(
                        Edge(t_start + fraction * dt, fraction, self.state, self._thresholds[i])
                    )
        self._previous = float(source.position)  # type: ignore[attr-defined]
        return edges


class ReferenceSwitch(PositionSwitch):
    """Reference (home) switch: a cam ``width`` long starting at ``position``."""

    def __init__(
        self,
        source: object,
        position: float,
        width: float,
        *,
        hysteresis: float = 0.0,
        invert: bool = False,
    ) -> None:
        if not width > 0.0:
            raise ValueError("width must be > 0")
        super().__init__(
            source, low=position, high=position + width, hysteresis=hysteresis, invert=invert
        )


class LimitSwitch(PositionSwitch):
    """Limit switch at ``position``: actuated beyond it in ``direction`` (+1 above, -1 below)."""

    def __init__(
        self,
        source: object,
        position: float,
        direction: int = 1,
        *,
        hysteresis: float = 0.0,
        invert: bool = False,
    ) -> None:
        if direction not in (1, -1):
            raise ValueError("direction must be +1 or -1")
        low, high = (position, math.inf) if direction == 1 else (-math.inf, position)
        super().__init__(source, low=low, high=high, hysteresis=hysteresis, invert=invert)
