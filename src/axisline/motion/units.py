"""User units <-> encoder counts for one axis.

The kernel computes in float64 user units (mm, deg, ...); devices count in integers
(encoder counts, print-mark captures, WAGO position registers). `counts_per_unit` is the
axis scale from its machine file (AxisConfig.counts_per_unit).

Rounding (docs/decisions.md): `to_counts` rounds to the *nearest* count with halves away
from zero. That is symmetric about zero (a move of -x gives exactly minus the counts of +x)
and does not depend on the sign the way truncation does. An encoder, by contrast, only
reports a count once its edge has been passed; the plant quantises with
``rounding="floor"``. Floor tolerates 1e-9 counts of float error, so that a decimal user
value that lies exactly on a count (2.3 mm at 100 counts/mm = 229.99999999999997) gives
that count (230) and not the one below.
"""

from __future__ import annotations

import math
from typing import Literal

__all__ = ["Scale", "to_counts", "from_counts"]

Rounding = Literal["nearest", "floor"]

# float error tolerated by floor rounding, in counts (see the module docstring)
_FLOOR_TOLERANCE = 1e-9


def _check_scale(counts_per_unit: float) -> float:
    if isinstance(counts_per_unit, bool) or not isinstance(counts_per_unit, (int, float)):
        raise ValueError(f"counts_per_unit must be a number > 0, got {counts_per_unit!r}")
    if not math.isfinite(counts_per_unit) or counts_per_unit <= 0.0:
        raise ValueError(f"counts_per_unit must be a finite number > 0, got {counts_per_unit!r}")
    return float(counts_per_unit)


def to_counts(value: float, counts_per_unit: float, rounding: Rounding = "nearest") -> int:
    """User units -> integer counts (nearest, halves away from zero; or floor)."""
    scale = _check_scale(counts_per_unit)
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise ValueError(f"value must be a finite number of user units, got {value!r}")
    x = float(value) * scale
    if rounding == "nearest":
        return int(math.copysign(math.floor(abs(x) + 0.5), x))
    if rounding == "floor":
        return math.floor(x + _FLOOR_TOLERANCE)
    raise ValueError(f"rounding must be 'nearest' or 'floor', got {rounding!r}")


def from_counts(counts: int, counts_per_unit: float) -> float:
    """Integer counts -> user units."""
    scale = _check_scale(counts_per_unit)
    if isinstance(counts, bool) or not hasattr(counts, "__index__"):
        raise ValueError(f"counts must be an integer, got {counts!r}")
    return int(counts) / scale


class Scale:
    """The scale of one axis: `to_counts` / `from_counts` with its counts_per_unit."""

    __slots__ = ("counts_per_unit",)

    def __init__(self, counts_per_unit: float) -> None:
        self.counts_per_unit = _check_scale(counts_per_unit)

    def to_counts(self, value: float, rounding: Rounding = "nearest") -> int:
        return to_counts(value, self.counts_per_unit, rounding)

    def from_counts(self, counts: int) -> float:
        return from_counts(counts, self.counts_per_unit)

    def __repr__(self) -> str:
        return f"Scale(counts_per_unit={self.counts_per_unit!r})"
