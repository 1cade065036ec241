"""Cam tables: point tables, splines, scaling, COMPAX fractions, checks, plots, CSV.

Sources: compax.md §2.7 (curves, equidistant set points), §2.20 (drift-free open curves),
§6.2 / Appendix B (24-bit fraction vectors), §7 X20 (cam memory example).
"""

from __future__ import annotations

import math
import os
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from axisline.motion.cam import (
    FRACTION_ONE,
    CamCheck,
    ModuloMaster,
    PointTable,
    ScaledCurve,
    SplineTable,
    check,
    decode_fraction,
    encode_fraction,
    plot_cam,
)

# ---------------------------------------------------------------------------------------
# linear point tables


def _kinked_table(**kwargs) -> PointTable:
    # rise, dwell, return: three slopes (2, 0, -1) so a wrong interval shows
    return PointTable([0.0, 1.0, 3.0, 6.0], [0.0, 2.0, 2.0, -1.0], **kwargs)


def test_linear_table_is_exact_at_its_points() -> None:
    table = _kinked_table()
    for m, s in zip(table.master, table.slave):
        assert table.eval(m)[0] == s


def test_linear_table_interpolates_between_points_with_the_interval_slope() -> None:
    table = _kinked_table()
    assert table.eval(0.5) == (1.0, 2.0, 0.0, 0.0)
    assert table.eval(2.0) == (2.0, 0.0, 0.0, 0.0)
    assert table.eval(4.5) == (0.5, -1.0, 0.0, 0.0)
    # at a point the slope of the interval that starts there
    assert table.eval(1.0)[1] == 0.0
    assert table.eval(3.0)[1] == -1.0
    # the cycle end belongs to the last interval
    assert table.eval(6.0) == (-1.0, -1.0, 0.0, 0.0)


def test_eval_array_agrees_with_eval() -> None:
    table = _kinked_table()
    x = np.linspace(0.0, 6.0, 61)
    arrays = table.eval_array(x)
    for k, xi in enumerate(x):
        assert tuple(float(a[k]) for a in arrays) == table.eval(float(xi))


def test_equidistant_lookup_equals_bisection() -> None:
    # The O(1) index (int(x / step)) must pick the same interval as bisection everywhere,
    # including exactly at points and a hair either side, where rounding would bite.
    slave = [math.sin(0.37 * k) * 10.0 for k in range(101)]
    fast = PointTable.equidistant(slave, master_period=7.3)
    general = PointTable(list(fast.master), slave, equidistant=False)
    assert fast.equidistant_step == pytest.approx(7.3 / 100)
    assert general.equidistant_step is None
    xs = list(np.linspace(0.0, 7.3, 3001))
    for m in fast.master:
        xs += [m, math.nextafter(m, -math.inf), math.nextafter(m, math.inf)]
    for x in xs:
        x = min(max(x, 0.0), 7.3)
        assert fast.eval(x) == general.eval(x)
        assert fast.last_point_passed(x) == general.last_point_passed(x)


@pytest.mark.parametrize("equidistant", [True, False])
def test_eval_with_acceleration_is_eval_and_set_point_acceleration_in_one_search(equidistant: bool) -> None:
    # what a cam follower reads every cycle (COMPAX: position, gradient and the set points'
    # acceleration) must be exactly the three separate evaluations, at the points, a hair either
    # side, between them, at the cycle end and beyond the table on both sides
    slave = [math.sin(0.37 * k) * 10.0 + 0.2 * k for k in range(41)]
    table = PointTable.equidistant(slave, master_period=3.6)
    if not equidistant:
        table = PointTable(list(table.master), slave, equidistant=False)
    xs = list(np.linspace(-0.5, 4.0, 901))
    for m in table.master:
        xs += [m, math.nextafter(m, -math.inf), math.nextafter(m, math.inf)]
    for x in xs:
        s, ds, dds = table.eval_with_acceleration(x)
        assert (s, ds) == table.eval(x)[:2]
        assert dds == table.set_point_acceleration(x)


def test_equally_spaced_points_are_recognised_whatever_the_constructor() -> None:
    # a CSV or hand-built COMPAX table gets the O(1) lookup too
    table = PointTable([0.0, 90.0, 180.0, 270.0, 360.0], [0.0, 1.0, 0.0, 1.0, 0.0])
    assert table.equidistant_step == 90.0
    assert PointTable([0.0, 1.0, 3.0], [0.0, 1.0, 2.0]).equidistant_step is None
    with pytest.raises(ValueError, match="not equally spaced"):
        PointTable([0.0, 1.0, 3.0], [0.0, 1.0, 2.0], equidistant=True)


def test_a_compax_sized_table_of_2500_set_points_and_a_larger_one() -> None:
    # compax.md §2.7.2: "The 2500 addresses of the cam memory"; tables from a PC may be finer
    for n in (2500, 20000):
        slave = [float(k % 7) for k in range(n)]
        table = PointTable.equidistant(slave, master_period=360.0)
        step = 360.0 / (n - 1)
        assert table.equidistant_step == pytest.approx(step)
        for k in (0, 1, n // 2, n - 2, n - 1):
            assert table.eval(table.master[k])[0] == slave[k]
        mid = table.eval((n // 2 + 0.5) * step)
        assert mid[0] == pytest.approx((slave[n // 2] + slave[n // 2 + 1]) / 2)


def test_open_table_continues_with_its_slave_offset_per_master_cycle() -> None:
    # compax.md §2.7.1: an open curve ends elsewhere than it starts; the slave keeps moving
    feed = PointTable([0.0, 180.0, 360.0], [0.0, 40.0, 100.0])
    assert not feed.closed and feed.cycle_offset == 100.0
    assert feed.at(360.0 + 180.0)[0] == 140.0
    assert feed.at(3 * 360.0 + 90.0)[0] == pytest.approx(320.0)
    assert feed.at(-180.0)[0] == -60.0  # a master running backwards walks the slave back
    closed = PointTable([0.0, 180.0, 360.0], [5.0, 40.0, 5.0])
    assert closed.closed and closed.at(-180.0)[0] == 40.0


_points = st.lists(st.floats(-1e3, 1e3), min_size=2, max_size=8)


@given(_points, st.lists(st.floats(0.01, 100.0), min_size=7, max_size=7))
def test_cycle_end_value_is_exactly_the_last_point(slave: list[float], steps: list[float]) -> None:
    # The slave travel per cycle of an open curve must be exactly last - first: any rounding
    # here would add up over millions of cycles (compax.md §2.20, drift-free operation).
    master = [0.0]
    for h in steps[: len(slave) - 1]:
        master.append(master[-1] + h)
    for curve in (PointTable(master, slave), SplineTable(master, slave, periodic=True)):
        assert curve.eval(curve.master_period)[0] == slave[-1]
        assert curve.cycle_offset == slave[-1] - slave[0]


# ---------------------------------------------------------------------------------------
# COMPAX 24-bit fractions (compax.md §6.2 item 3, Appendix B "fractional_24bit")

FRACTION_VECTORS = [
    (0.99999999, 0x7FFFFF),
    (0.5, 0x400000),
    (0.0, 0x000000),
    (-1.0, 0x800000),
    (-0.5, 0xC00000),
    (-0.00000001, 0xFFFFFF),
]


@pytest.mark.parametrize(("value", "word"), FRACTION_VECTORS)
def test_fraction_encoding_matches_the_manuals_table(value: float, word: int) -> None:
    assert encode_fraction(value) == word
    # reading back: "1. Conversion into an integer value. 2. Fx = Ix / 2^23"
    assert decode_fraction(word) == pytest.approx(value, abs=1.0 / FRACTION_ONE)
    assert encode_fraction(decode_fraction(word)) == word


@given(st.integers(0, 0xFFFFFF))
def test_every_24_bit_word_round_trips(word: int) -> None:
    assert encode_fraction(decode_fraction(word)) == word


@pytest.mark.parametrize("value", [1.0, -1.0000001, float("nan"), 2.0])
def test_fractions_outside_minus_one_to_one_are_rejected(value: float) -> None:
    with pytest.raises(ValueError, match="-1 <= value < 1"):
        encode_fraction(value)


def test_cam_memory_example_curve_is_the_straight_line_and_drift_free() -> None:
    # compax.md §7 X20: M_T = S_T = 360, set points 0, .1, ..., .9, .9999999 ⇒ curve(m) = m
    words = [encode_fraction(v) for v in (0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 0.9999999)]
    assert words[-1] == 0x7FFFFF
    curve = PointTable.from_fractions(words, master_cycle=360.0, slave_cycle=360.0)
    assert curve.equidistant_step == 36.0
    assert curve.eval(180.0)[0] == 180.0  # "at m = 180 slave = 180"
    assert curve.eval(36.0)[0] == pytest.approx(36.0, abs=360.0 / FRACTION_ONE)
    # 0x7FFFFF is the full slave cycle, so a million cycles move the slave exactly S_T each
    # (compax.md §2.20: the last set point 0.999999 keeps open curves drift-free)
    assert curve.cycle_offset == 360.0
    assert curve.at(1_000_000 * 360.0 + 180.0)[0] == 1_000_000 * 360.0 + 180.0
    assert curve.fractions(360.0) == words


def test_from_fractions_names_a_bad_word() -> None:
    with pytest.raises(ValueError, match=r"set point 2: .*0x1000000.*0 \.\.\. 0xFFFFFF"):
        PointTable.from_fractions([0, 0x100000, 0x1000000], 360.0, 360.0)


# ---------------------------------------------------------------------------------------
# splines


def _one_sided(curve: SplineTable, x: float) -> tuple[np.ndarray, np.ndarray]:
    eps = 1e-7 * curve.master_period
    return np.array(curve.at(x - eps)), np.array(curve.at(x + eps))


def _assert_c2_at(curve: SplineTable, x: float) -> None:
    left, right = _one_sided(curve, x)
    scale = max(1.0, float(np.max(np.abs(curve.slave))))
    # s, ds, dds agree from both sides; ddds may jump (cubic pieces)
    assert left[:3] == pytest.approx(right[:3], abs=1e-5 * scale)


@pytest.mark.parametrize("periodic", [False, True])
def test_spline_passes_through_its_points_and_is_c2_at_the_knots(periodic: bool) -> None:
    master = [0.0, 40.0, 100.0, 170.0, 250.0, 300.0, 360.0]
    slave = [0.0, 12.0, 30.0, 25.0, 8.0, 3.0, 0.0]
    spline = SplineTable(master, slave, periodic=periodic)
    for m, s in zip(master, slave):
        assert spline.eval(m)[0] == pytest.approx(s, abs=1e-12)
    for m in master[1:-1]:
        _assert_c2_at(spline, m)


def test_natural_spline_has_no_acceleration_at_its_ends() -> None:
    spline = SplineTable([0.0, 1.0, 2.5, 4.0], [0.0, 1.0, 0.0, 2.0], periodic=False)
    assert spline.eval(0.0)[2] == pytest.approx(0.0, abs=1e-12)
    assert spline.eval(4.0)[2] == pytest.approx(0.0, abs=1e-12)


def test_clamped_spline_starts_and_ends_with_the_given_gradients() -> None:
    # e.g. a rise between two dwells: gradient 0 at both ends
    spline = SplineTable([0.0, 1.0, 2.5, 4.0], [0.0, 1.0, 3.0, 4.0], periodic=False, end_slopes=(0.0, 0.0))
    assert spline.eval(0.0)[1] == pytest.approx(0.0, abs=1e-12)
    assert spline.eval(4.0)[1] == pytest.approx(0.0, abs=1e-12)
    _assert_c2_at(spline, 1.0)


@pytest.mark.parametrize("n", [3, 4, 9, 200])  # 3 points: dense solve; more: cyclic Thomas
def test_periodic_spline_wraps_c2_into_the_next_cycle(n: int) -> None:
    master = list(np.linspace(0.0, 360.0, n))
    slave = [10.0 * math.sin(math.radians(m)) + 3.0 * math.cos(math.radians(2 * m)) for m in master]
    slave[-1] = slave[0]  # closed
    spline = SplineTable(master, slave, periodic=True)
    assert spline.closed
    _assert_c2_at(spline, 360.0)
    _assert_c2_at(spline, -360.0)
    for m in master[1:-1]:
        _assert_c2_at(spline, m)


def test_open_periodic_spline_continues_smoothly_with_its_offset() -> None:
    # a feed: the slave gains 40 per cycle; velocity and acceleration continue across the wrap
    spline = SplineTable([0.0, 90.0, 200.0, 360.0], [0.0, 10.0, 30.0, 40.0], periodic=True)
    assert spline.cycle_offset == 40.0
    _assert_c2_at(spline, 360.0)
    assert spline.at(360.0)[0] == 40.0


def test_spline_through_a_sine_reproduces_it() -> None:
    n = 2500
    xs = np.linspace(0.0, 360.0, n)
    spline = SplineTable.equidistant(np.sin(np.radians(xs)), 360.0, periodic=True)
    k = math.pi / 180.0
    for x in (0.0, 12.345, 90.0, 271.1):
        s, ds, dds, ddds = spline.eval(x)
        assert s == pytest.approx(math.sin(k * x), abs=1e-10)
        assert ds == pytest.approx(k * math.cos(k * x), abs=1e-8)
        assert dds == pytest.approx(-k * k * math.sin(k * x), abs=1e-7)


def test_spline_end_conditions_are_validated() -> None:
    with pytest.raises(ValueError, match="end_slopes"):
        SplineTable([0.0, 1.0, 2.0], [0.0, 1.0, 0.0], periodic=True, end_slopes=(0.0, 0.0))


# ---------------------------------------------------------------------------------------
# scaling


def test_scaled_curve_scales_positions_and_derivatives() -> None:
    inner = SplineTable([0.0, 1.0, 2.0, 4.0], [0.0, 2.0, 1.0, 3.0], periodic=False)
    scaled = ScaledCurve(inner, master_scale=2.5, slave_scale=-3.0, slave_offset=7.0)
    assert scaled.master_period == 10.0
    for x in (0.0, 1.3, 4.9, 7.7, 10.0):
        s, ds, dds, ddds = inner.eval(x / 2.5)
        got = scaled.eval(x)
        assert got[0] == pytest.approx(-3.0 * s + 7.0)
        assert got[1] == pytest.approx(-3.0 * ds / 2.5)
        assert got[2] == pytest.approx(-3.0 * dds / 2.5**2)
        assert got[3] == pytest.approx(-3.0 * ddds / 2.5**3)
    # the chain rule also by finite differences (independent of the formula above)
    h = 1e-5
    x = 3.3
    assert scaled.eval(x)[1] == pytest.approx((scaled.eval(x + h)[0] - scaled.eval(x - h)[0]) / (2 * h), rel=1e-6)
    assert scaled.cycle_offset == pytest.approx(-3.0 * inner.cycle_offset)


def test_scaled_open_curve_keeps_an_exact_offset_per_cycle() -> None:
    # P36 scales the slave (compax.md §4 [DERIVED]); the end value is taken exactly from the
    # inner curve, so the offset does not pick up rounding of x / master_scale
    feed = PointTable([0.0, 0.1, 1.0], [0.0, 0.3, 1.0])
    scaled = ScaledCurve(feed, master_scale=3.0, slave_scale=360.0)
    assert scaled.cycle_offset == 360.0
    assert scaled.at(3.0 * 1000)[0] == 360.0 * 1000


def test_scaled_curve_rejects_a_zero_master_scale() -> None:
    with pytest.raises(ValueError, match="master_scale"):
        ScaledCurve(_kinked_table(), master_scale=0.0)


# ---------------------------------------------------------------------------------------
# master cycles


def test_modulo_master_splits_negative_positions_into_cycle_and_position() -> None:
    mm = ModuloMaster(360.0)
    assert mm.split(-90.0) == (-1, 270.0)
    assert mm.split(-360.0) == (-1, 0.0)
    assert mm.split(725.0) == (2, 5.0)
    assert ModuloMaster(4096).split(-1) == (-1, 4095)  # encoder counts: exact integers


@given(st.integers(-(10**12), 10**12), st.integers(1, 10**6))
def test_modulo_master_is_exact_for_counts(x: int, period: int) -> None:
    k, r = ModuloMaster(period).split(x)
    assert k * period + r == x and 0 <= r < period


@given(st.floats(-1e9, 1e9), st.sampled_from([360.0, 0.1, 7.3, 1e-3]))
def test_modulo_master_position_is_always_inside_the_cycle(x: float, period: float) -> None:
    k, r = ModuloMaster(period).split(x)
    assert 0.0 <= r < period
    assert k * period + r == pytest.approx(x, abs=1e-9 * max(1.0, abs(x)))


# ---------------------------------------------------------------------------------------
# cam editor check


def test_check_of_a_straight_line() -> None:
    # gradient 2 at master speed 3: slave velocity 6, no acceleration or jerk
    line = PointTable([0.0, 10.0], [0.0, 20.0])
    result = check(line, master_speed=3.0)
    assert isinstance(result, CamCheck)
    assert (result.max_velocity, result.max_acceleration, result.max_jerk) == (6.0, 0.0, 0.0)
    assert result.within_limits and result.max_master_speed == math.inf
    assert check(line, 3.0, v_max=6.0).within_limits  # exactly at the limit is allowed
    slow = check(line, 3.0, v_max=5.0)
    assert slow.velocity_exceeded and not slow.within_limits
    assert slow.max_master_speed == 2.5
    # a master accelerating at 4 adds ds·am = 8 slave acceleration
    assert check(line, 3.0, master_acceleration=4.0).max_acceleration == 8.0


def _sine_spline(amplitude: float = 5.0) -> SplineTable:
    master = np.linspace(0.0, 360.0, 73)
    return SplineTable(master, amplitude * np.sin(np.radians(master)), periodic=True)


def test_check_of_a_sine_cam_gives_the_analytic_maxima() -> None:
    # s = A sin(k x), k = 2π/360: v = A k vm, a = A k² vm², j = A k³ vm³ at constant master speed
    a_, k, vm = 5.0, math.pi / 180.0, 720.0
    result = check(_sine_spline(a_), master_speed=vm)
    assert result.max_velocity == pytest.approx(a_ * k * vm, rel=1e-4)
    assert result.max_acceleration == pytest.approx(a_ * k**2 * vm**2, rel=1e-3)
    assert result.max_jerk == pytest.approx(a_ * k**3 * vm**3, rel=1e-2)
    # where: velocity peaks where the sine crosses zero, acceleration at its crests
    assert min(abs(result.max_velocity_at - p) for p in (0.0, 180.0, 360.0)) < 1.0
    assert min(abs(result.max_acceleration_at - p) for p in (90.0, 270.0)) < 1.0


def test_largest_master_speed_is_set_by_the_tightest_limit() -> None:
    a_, k = 5.0, math.pi / 180.0
    cam = _sine_spline(a_)
    limits = dict(v_max=100.0, a_max=200.0, j_max=300.0)
    expected = min(100.0 / (a_ * k), math.sqrt(200.0 / (a_ * k * k)), (300.0 / (a_ * k**3)) ** (1 / 3))
    result = check(cam, 100.0, **limits)
    assert result.max_master_speed == pytest.approx(expected, rel=1e-3)
    assert check(cam, result.max_master_speed, **limits).within_limits
    assert not check(cam, 1.01 * result.max_master_speed, **limits).within_limits


def _lopsided_spline() -> SplineTable:
    # fast rise, slow return: velocity and acceleration are not symmetric, so a sign slip
    # between ds·am and dds·vm² shows
    master = [0.0, 40.0, 100.0, 170.0, 250.0, 300.0, 360.0]
    return SplineTable(master, [0.0, 1.0, 4.0, 5.0, 2.5, 0.3, 0.0], periodic=True)


@pytest.mark.parametrize("master_acceleration", [-3000.0, 3000.0])
@pytest.mark.parametrize("limits", [{"a_max": 300.0}, {"j_max": 2000.0}, {"j_max": 50.0}])
@pytest.mark.parametrize("make_cam", [_sine_spline, _lopsided_spline])
def test_largest_master_speed_with_an_accelerating_master(master_acceleration: float, limits: dict, make_cam) -> None:
    # a = dds·vm² + ds·am and j = ddds·vm³ + 3·dds·vm·am: the limit speed is where the first
    # limit is reached; just below it the cam is within limits, just above it is not
    cam = make_cam()
    speed = check(cam, 1.0, master_acceleration, **limits).max_master_speed
    assert 0.0 < speed < math.inf
    assert check(cam, 0.999 * speed, master_acceleration, **limits).within_limits
    assert not check(cam, 1.001 * speed, master_acceleration, **limits).within_limits


def test_no_master_speed_helps_when_the_master_acceleration_alone_breaks_the_limit() -> None:
    # ds·am = 5·(π/180)·5000 ≈ 436 > 150 already at standstill of the master
    result = check(_sine_spline(), 0.0, 5000.0, a_max=150.0)
    assert result.max_master_speed == 0.0 and result.acceleration_exceeded


def test_check_rejects_a_zero_limit() -> None:
    with pytest.raises(ValueError, match="a_max"):
        check(_kinked_table(), 1.0, a_max=0.0)


# ---------------------------------------------------------------------------------------
# plot


def test_plot_writes_a_png(tmp_path: Path) -> None:
    path = tmp_path / "cam.png"
    plot_cam(_sine_spline(), master_speed=360.0, path=path)
    data = path.read_bytes()
    assert data.startswith(b"\x89PNG\r\n\x1a\n") and len(data) > 5000
    assert sorted(os.listdir(tmp_path)) == ["cam.png"]  # no temporary file left behind


def test_plot_draws_the_axis_limits_and_units(tmp_path: Path) -> None:
    """Issue 16: the cam plot shows the slave axis' limits (dashed, +-) on the velocity,
    acceleration and jerk panels, and the slave's unit on every panel."""
    panels = plot_cam(_sine_spline(), master_speed=360.0, path=tmp_path / "cam.png",
                      limits={"v_max": 500.0, "a_max": 2e4, "j_max": None}, unit="mm")
    assert [limit for _, limit in panels] == [None, 500.0, 2e4, None]
    assert all("[mm" in label for label, _ in panels)


# ---------------------------------------------------------------------------------------
# CSV


def test_csv_round_trip_is_exact(tmp_path: Path) -> None:
    table = PointTable([0.0, 0.1, 1 / 3, 2.0], [1e-300, -0.7, 2 / 3, 123456.789])
    path = tmp_path / "curve.csv"
    table.to_csv(path)
    assert path.read_text().splitlines()[0] == "master,slave"
    back = PointTable.from_csv(path)
    assert back.master == table.master and back.slave == table.slave
    spline = SplineTable.from_csv(path, periodic=False)
    assert spline.master == table.master


def test_csv_save_keeps_the_old_file_when_writing_fails(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    # a crash during a save must not leave half a curve on disk
    path = tmp_path / "curve.csv"
    _kinked_table().to_csv(path)
    before = path.read_text()

    def broken_replace(src, dst):  # the rename never happens
        raise OSError("power cut")

    monkeypatch.setattr(os, "replace", broken_replace)
    with pytest.raises(OSError, match="power cut"):
        PointTable([0.0, 1.0], [5.0, 6.0]).to_csv(path)
    monkeypatch.undo()
    assert path.read_text() == before
    assert sorted(os.listdir(tmp_path)) == ["curve.csv"]


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        ("master,slave\n0,0\n2,1\n2,3\n", r"line 4, field 'master': 2\.0 .*strictly increasing"),
        ("master,slave\n0,0\n1,nan\n", r"line 3, field 'slave': 'nan' .*finite"),
        ("master,slave\n0,0\n", r"at least 2 points, got 1"),
        ("master,slave\n0,0\n1,1\n2,2\n3,3\n", r"line 5: more than max_points=3"),
        ("x,y\n0,0\n1,1\n", r"line 1: header must be 'master,slave'"),
        ("master,slave\n0,0\n1,1,1\n", r"line 3: expected 2 fields"),
        ("master,slave\n0,0\n1,abc\n", r"line 3, field 'slave': 'abc' is not a number"),
        ("master,slave\n5,0\n10,1\n", r"line 2, field 'master': 5\.0 .*first master position must be 0"),
        ("", r"empty file"),
    ],
)
def test_csv_bad_input_names_the_row_field_and_value(tmp_path: Path, text: str, expected: str) -> None:
    path = tmp_path / "bad.csv"
    path.write_text(text)
    with pytest.raises(ValueError, match=expected):
        PointTable.from_csv(path, max_points=3)


def test_constructor_rejects_mismatched_lengths_and_unknown_interpolation() -> None:
    with pytest.raises(ValueError, match="one slave value per master position"):
        PointTable([0.0, 1.0, 2.0], [0.0, 1.0])
    with pytest.raises(ValueError, match="'linear'"):
        PointTable([0.0, 1.0], [0.0, 1.0], interpolation="cubic")  # type: ignore[arg-type]
