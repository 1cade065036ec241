"""The queue of marks between the sensor and the tool (registration.py describes the whole).
"""

from __future__ import annotations

import math
from enum import IntEnum
from typing import NamedTuple

import numpy as np

from axisline.motion.registration_common import _check_finite, _check_positive, _is_count

__all__ = ["MarkKind", "MarkQueue", "QueuedMark"]


class MarkKind(IntEnum):
    REAL = 0
    """Captured at the sensor."""
    VIRTUAL = 1
    """Filled in at start for the stretch between sensor and tool nobody has seen."""
    SUBSTITUTE = 2
    """Stands for a mark that was missing from its window."""


class QueuedMark(NamedTuple):
    position: float
    """Mark position as captured at the sensor (master/material coordinates)."""
    due: float
    """Tool position at which it is due: ``position + distance``."""
    kind: MarkKind


class MarkQueue:
    """Marks between the sensor and the tool, first in, first out.

    ``capacity`` marks fit (a preallocated ring buffer). ``distance`` is the sensor-to-tool
    distance: a mark captured at ``position`` is due when the tool position reaches
    ``position + distance`` (0 if the positions pushed are already at the tool).

    A mark that does not fit sets :attr:`overflow` (latched until :meth:`clear_overflow` or
    :meth:`reset`) and counts in :attr:`overflows`; :meth:`push` returns False. Marks already
    queued are never overwritten.

    ``marks_per_product``: only every n-th real (or substitute) mark starts a product and is
    queued, beginning with the first after a reset; the others are counted and skipped.
    """

    __slots__ = (
        "capacity",
        "distance",
        "marks_per_product",
        "_positions",
        "_kinds",
        "_read",
        "_count",
        "_seen",
        "overflow",
        "overflows",
        "skipped",
    )

    def __init__(
        self, capacity: int = 64, *, distance: float = 0.0, marks_per_product: int = 1
    ) -> None:
        if not _is_count(capacity, 1):
            raise ValueError("capacity must be an integer >= 1")
        if not _is_count(marks_per_product, 1):
            raise ValueError("marks_per_product must be an integer >= 1")
        self.capacity = capacity
        self.distance = _check_finite("distance", distance)
        self.marks_per_product = marks_per_product
        self._positions = np.zeros(capacity, dtype=np.float64)
        self._kinds = np.zeros(capacity, dtype=np.int8)
        self.reset()

    def reset(self) -> None:
        """Empty the queue, restart the marks-per-product count, clear the overflow."""
        self._read = 0
        self._count = 0
        self._seen = 0
        self.overflow = False
        self.overflows = 0
        self.skipped = 0

    def clear_overflow(self) -> None:
        self.overflow = False

    def __len__(self) -> int:
        return self._count

    @property
    def full(self) -> bool:
        return self._count == self.capacity

    @property
    def read_index(self) -> int:
        """Ring-buffer slot of the oldest mark."""
        return self._read

    @property
    def write_index(self) -> int:
        """Ring-buffer slot the next mark goes to."""
        return (self._read + self._count) % self.capacity

    def push(self, position: float, kind: MarkKind = MarkKind.REAL) -> bool:
        """Queue a mark captured at ``position``. Returns True if queued; False if skipped
        (marks per product) or if the queue is full (then :attr:`overflow` is set)."""
        if kind is not MarkKind.VIRTUAL:
            # virtual marks are spaced a product apart already; real ones are counted
            n = self._seen
            self._seen = n + 1
            if n % self.marks_per_product:
                self.skipped += 1
                return False
        if self._count == self.capacity:
            self.overflow = True
            self.overflows += 1
            return False
        slot = (self._read + self._count) % self.capacity
        self._positions[slot] = position
        self._kinds[slot] = kind
        self._count += 1
        return True

    def fill_virtual(self, position: float, spacing: float) -> int:
        """Line start at master ``position``: empty the queue and fill the stretch between
        sensor and tool with virtual marks ``spacing`` apart, as if they had passed the sensor
        at ``position - k * spacing`` (k = n .. 1, n = floor(distance / spacing)), so the
        tool works from the first one instead of waiting for the first real mark. Returns n."""
        spacing = _check_positive("spacing", spacing)
        self.reset()
        n = math.floor(self.distance / spacing + 1e-9)
        for k in range(n, 0, -1):
            self.push(position - k * spacing, MarkKind.VIRTUAL)
        return n

    def _head(self) -> int:
        if not self._count:
            raise IndexError("the mark queue is empty")
        return self._read

    @property
    def head_position(self) -> float:
        return float(self._positions[self._head()])

    @property
    def head_due(self) -> float:
        """Tool position at which the oldest mark is due."""
        return float(self._positions[self._head()]) + self.distance

    @property
    def head_kind(self) -> MarkKind:
        return MarkKind(int(self._kinds[self._head()]))

    def is_due(self, tool_position: float) -> bool:
        """The oldest mark has reached the tool at ``tool_position``."""
        return self._count > 0 and tool_position >= float(self._positions[self._read]) + self.distance

    def pop(self) -> QueuedMark:
        """Remove and return the oldest mark."""
        slot = self._head()
        position = float(self._positions[slot])
        mark = QueuedMark(position, position + self.distance, MarkKind(int(self._kinds[slot])))
        self._read = (slot + 1) % self.capacity
        self._count -= 1
        return mark

    def pop_due(self, tool_position: float) -> QueuedMark | None:
        """The oldest mark if it is due at ``tool_position``, else None."""
        return self.pop() if self.is_due(tool_position) else None

    def marks(self) -> list[QueuedMark]:
        """Snapshot, oldest first (for display; allocates)."""
        out = []
        for i in range(self._count):
            slot = (self._read + i) % self.capacity
            p = float(self._positions[slot])
            out.append(QueuedMark(p, p + self.distance, MarkKind(int(self._kinds[slot]))))
        return out
