"""What the registration parts share (registration.py describes them): the cycle arithmetic
(`wrap`, `phase`, `expected_at_sensor`), the option names and the argument checks.
"""

from __future__ import annotations

import math
from typing import Literal

__all__ = ["Side", "Startup", "Substitute", "expected_at_sensor", "phase", "wrap"]


Side = Literal["master", "slave"]
Startup = Literal["window", "first", "until_inside"]
Substitute = Literal["expected", "extrapolate"]

# A fraction this far outside 0..1 is rounding of an edge on the cycle boundary, not an error.
_FRACTION_TOLERANCE = 1e-9


def _check_positive(name: str, value: float) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise ValueError(f"{name} must be a number > 0, got {value!r}")
    if not (math.isfinite(value) and value > 0.0):
        raise ValueError(f"{name} must be a finite number > 0, got {value!r}")
    return float(value)


def _check_finite(name: str, value: float) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise ValueError(f"{name} must be a finite number, got {value!r}")
    return float(value)


def _is_count(value: object, minimum: int) -> bool:
    return isinstance(value, int) and not isinstance(value, bool) and value >= minimum


def _check_limit(name: str, value: float | None) -> float:
    """A magnitude limit: None means unlimited (stored as inf)."""
    if value is None:
        return math.inf
    value = _check_finite(name, value)
    if value <= 0.0:
        raise ValueError(f"{name} must be > 0 (or None for no limit), got {value!r}")
    return value


def wrap(distance: float, cycle: float) -> float:
    """``distance`` wrapped into ``(-cycle/2, cycle/2]``: the shortest way round a cycle.

    The upper end is closed so that a mark exactly half a cycle away has one deviation, not two.
    """
    r = math.fmod(distance, cycle)  # exact, sign of ``distance``, |r| < cycle
    half = 0.5 * cycle
    if r > half:
        r -= cycle
    elif r <= -half:
        r += cycle
    return r


def phase(position: float, cycle: float) -> float:
    """``position`` reduced into ``[0, cycle)``."""
    r = math.fmod(position, cycle)
    if r < 0.0:
        r += cycle
        if r >= cycle:  # -1e-20 + cycle rounds to cycle
            r = 0.0
    return r


def expected_at_sensor(processing_point: float, sensor_to_tool: float, cycle: float) -> float:
    """Where in the cycle a mark must pass the sensor so that it meets the tool at
    ``processing_point``: ``processing_point - sensor_to_tool`` reduced into ``[0, cycle)``.

    The sensor sits ``sensor_to_tool`` (in the units of the cycle) upstream of the tool, so the
    mark passes it that much earlier.
    """
    return phase(processing_point - sensor_to_tool, _check_positive("cycle", cycle))
