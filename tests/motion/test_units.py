"""User units <-> counts."""

from __future__ import annotations

import pytest
from hypothesis import given
from hypothesis import strategies as st

from axisline.motion.units import Scale, from_counts, to_counts


def test_nearest_rounds_halves_away_from_zero_symmetrically() -> None:
    assert to_counts(0.0005, 1000.0) == 1
    assert to_counts(-0.0005, 1000.0) == -1
    assert to_counts(0.00049, 1000.0) == 0
    assert to_counts(2.5, 1.0) == 3 and to_counts(-2.5, 1.0) == -3


def test_floor_gives_the_count_a_decimal_value_lies_on() -> None:
    assert 2.3 * 100 < 230  # float: 229.99999999999997
    assert to_counts(2.3, 100.0, rounding="floor") == 230
    assert to_counts(2.3049, 100.0, rounding="floor") == 230
    assert to_counts(-0.001, 100.0, rounding="floor") == -1


def test_from_counts_scales_back() -> None:
    assert from_counts(12345, 1000.0) == pytest.approx(12.345)
    assert Scale(4096 / 360.0).from_counts(4096) == pytest.approx(360.0)


@pytest.mark.parametrize(
    "call",
    [
        lambda: to_counts(1.0, 0.0),
        lambda: to_counts(float("nan"), 10.0),
        lambda: to_counts(1.0, 10.0, rounding="up"),  # type: ignore[arg-type]
        lambda: from_counts(1.5, 10.0),  # type: ignore[arg-type]
        lambda: Scale(-1.0),
    ],
)
def test_invalid_inputs_raise_value_error(call) -> None:
    with pytest.raises(ValueError):
        call()


@given(st.floats(-1e6, 1e6), st.sampled_from([1.0, 1000.0, 4096 / 360.0, 2500.0 / 3.0]))
def test_round_trip_is_within_half_a_count(x: float, scale: float) -> None:
    s = Scale(scale)
    assert abs(s.from_counts(s.to_counts(x)) - x) <= 0.5 / scale * (1 + 1e-9)
    assert s.to_counts(-x) == -s.to_counts(x)
