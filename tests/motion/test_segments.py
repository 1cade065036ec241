"""Cams built from motion-law segments: joints, wrap, open cams, auto transitions, validation."""

from __future__ import annotations

import math

import numpy as np
import pytest

from axisline.motion.curve import CamCurve
from axisline.motion.laws import LAWS
from axisline.motion.segments import Segment, SegmentCam, segments_from_table


def left_and_right(cam: SegmentCam, x: float) -> tuple[tuple[float, ...], tuple[float, ...]]:
    """The cam just before a joint (previous segment at u ~ 1) and at it (next segment)."""
    return cam.eval(float(np.nextafter(x, -math.inf))), cam.eval(x)


def assert_c2_at(cam: SegmentCam, x: float, rel: float = 1e-9) -> None:
    (s_l, v_l, a_l, _), (s_r, v_r, a_r, _) = left_and_right(cam, x)
    scale_s = max(1.0, abs(s_l))
    assert s_r == pytest.approx(s_l, abs=rel * scale_s), f"s jumps at x = {x}"
    assert v_r == pytest.approx(v_l, abs=rel * max(1.0, abs(v_l))), f"ds/dx jumps at x = {x}"
    assert a_r == pytest.approx(a_l, abs=rel * max(1.0, abs(a_l))), f"d2s/dx2 jumps at x = {x}"


def assert_wraps_c2(cam: SegmentCam) -> None:
    """End of the cycle joins the start of the next one in value (with offset), velocity, accel."""
    s_end, v_end, a_end, _ = cam.eval(cam.master_period)
    s_0, v_0, a_0, _ = cam.eval(0.0)
    assert s_end == pytest.approx(s_0 + cam.cycle_offset, abs=1e-9)
    assert v_end == pytest.approx(v_0, abs=1e-9)
    assert a_end == pytest.approx(a_0, abs=1e-9)


def joints(cam: SegmentCam) -> list[float]:
    return [seg.master_end for seg in cam.segments[:-1]]


def test_dwell_rise_dwell_return_with_cycloidal_is_c2() -> None:
    cam = SegmentCam([(90.0, 0.0, "dwell"), (180.0, 50.0, "cycloidal"),
                      (270.0, 50.0, "dwell"), (360.0, 0.0, "cycloidal")], start=0.0)
    assert isinstance(cam, CamCurve)
    assert cam.master_period == 360.0 and cam.closed
    for x in joints(cam):
        assert_c2_at(cam, x)
    assert_wraps_c2(cam)
    # the rise is the law scaled by stroke h = 50 over master length L = 90
    s, v, a, j = cam.eval(135.0)
    law = LAWS["cycloidal"]
    assert s == pytest.approx(25.0)
    assert v == pytest.approx(law.cv * 50.0 / 90.0)
    _, v_ret, _, _ = cam.eval(315.0)  # the return draws the same law downwards
    assert v_ret == pytest.approx(-law.cv * 50.0 / 90.0)
    x = np.linspace(90.0, 180.0, 2001)
    assert np.abs(cam.eval_array(x)[2]).max() == pytest.approx(law.ca * 50.0 / 90.0**2, rel=1e-5)


def test_simple_harmonic_keeps_its_acceleration_step_next_to_a_dwell() -> None:
    # C2 only where the laws allow: the harmonic rise starts with a = h/L^2 * pi^2/2
    cam = SegmentCam([(100.0, 0.0, "dwell"), (200.0, 10.0, "simple_harmonic"), (300.0, 0.0, "poly345")])
    (_, v_l, a_l, _), (_, v_r, a_r, _) = left_and_right(cam, 100.0)
    assert v_r == pytest.approx(v_l, abs=1e-12)
    assert a_l == 0.0 and a_r == pytest.approx(10.0 / 100.0**2 * math.pi**2 / 2)


def test_constant_velocity_between_auto_segments_is_c2() -> None:
    # dwell, auto ramp-up, constant velocity, auto ramp-down back to the start, dwell
    cam = SegmentCam([(60.0, 0.0, "dwell"), (120.0, 20.0, "auto"), (240.0, 140.0, "constant_velocity"),
                      (300.0, 160.0, "auto"), (330.0, 160.0, "dwell"), (360.0, 0.0, "auto")])
    for x in joints(cam):
        assert_c2_at(cam, x)
    assert_wraps_c2(cam)
    # the constant-velocity segment really is ds/dx = stroke/length, d2s/dx2 = 0 throughout
    x = np.linspace(120.0, 240.0, 501, endpoint=False)  # at 240 the next segment takes over
    _, v, a, j = cam.eval_array(x)
    np.testing.assert_allclose(v, 120.0 / 120.0, atol=1e-12)
    assert np.all(a == 0.0) and np.all(j == 0.0)
    # and its "auto" neighbours meet that velocity
    assert cam.boundary[1][2] == pytest.approx(1.0) and cam.boundary[3][0] == pytest.approx(1.0)


def test_runs_of_auto_segments_are_c2_and_even_c4() -> None:
    # between two auto segments nothing fixes v and a: they are chosen so d3 and d4 are
    # continuous as well (a quintic spline through the points)
    cam = SegmentCam([(50.0, 0.0, "dwell"), (80.0, 10.0, "auto"), (140.0, 4.0, "auto"),
                      (200.0, 30.0, "auto"), (360.0, 0.0, "poly4567")])
    for x in joints(cam):
        assert_c2_at(cam, x)
    for x in (80.0, 140.0):
        (_, _, _, j_l), (_, _, _, j_r) = left_and_right(cam, x)
        assert j_r == pytest.approx(j_l, rel=1e-8, abs=1e-12)
    # the points themselves are hit
    for seg in cam.segments:
        assert cam.eval(seg.master_end)[0] == pytest.approx(seg.slave_end, abs=1e-10)


def test_auto_run_reproduces_a_quintic_through_its_points() -> None:
    """The matched run of auto segments is the unique quintic spline with its end conditions,
    so points taken from one quintic (a 3-4-5 rise from rest to rest, stroke 30 over 200)
    must give that quintic back everywhere, at uneven spacing."""
    stroke, length = 30.0, 200.0
    ends = [17.0, 60.0, 75.0, 140.0, 200.0]
    poly = LAWS["poly345"]
    rows = [(x, stroke * poly.eval(x / length)[0], "auto") for x in ends]
    cam = SegmentCam(rows, periodic=False)  # a single pass starts and ends at rest, as 3-4-5 does
    x = np.linspace(0.0, length, 801)
    s, v, a, j = cam.eval_array(x)
    ps, pv, pa, pj = poly.eval(x / length)
    np.testing.assert_allclose(s, stroke * ps, atol=1e-9)
    np.testing.assert_allclose(v, stroke / length * pv, atol=1e-11)
    np.testing.assert_allclose(a, stroke / length**2 * pa, atol=1e-12)
    np.testing.assert_allclose(j, stroke / length**3 * pj, atol=1e-13)


def test_all_auto_cam_is_a_periodic_spline() -> None:
    cam = SegmentCam([(100.0, 5.0, "auto"), (200.0, -3.0, "auto"), (360.0, 0.0, "auto")], start=0.0)
    for x in joints(cam):
        assert_c2_at(cam, x)
    assert_wraps_c2(cam)
    assert cam.eval(360.0)[3] == pytest.approx(cam.eval(0.0)[3], rel=1e-8)


def test_open_cam_has_its_cycle_offset_and_repeats_with_it() -> None:
    # a feed of 25 per master cycle (COMPAX reset mode): auto ramp, constant feed, auto back into it
    cam = SegmentCam([(90.0, 20.0, "auto"), (270.0, 30.0, "constant_velocity"), (360.0, 35.0, "auto")],
                     start=10.0)
    assert not cam.closed
    assert cam.start == 10.0 and cam.cycle_offset == 25.0
    for x in (0.0, 33.3, 200.0, 359.0):
        s, v, a, _ = cam.at(x)
        s2, v2, a2, _ = cam.at(x + 2 * 360.0)
        assert s2 == pytest.approx(s + 50.0)
        assert (v2, a2) == pytest.approx((v, a), abs=1e-12)
    for x in joints(cam):
        assert_c2_at(cam, x)
    assert_wraps_c2(cam)


def test_single_pass_cam_starts_and_ends_at_rest() -> None:
    cam = SegmentCam([(100.0, 40.0, "auto"), (200.0, 60.0, "auto")], periodic=False)
    for x in (0.0, 200.0):
        _, v, a, _ = cam.eval(x)
        assert v == pytest.approx(0.0, abs=1e-12) and a == pytest.approx(0.0, abs=1e-12)
    assert_c2_at(cam, 100.0)


def test_derivatives_are_derivatives_of_the_position() -> None:
    cam = SegmentCam([(40.0, 0.0, "dwell"), (100.0, 12.0, "modified_sine"), (150.0, 20.0, "auto"),
                      (220.0, 30.0, "constant_velocity"), (300.0, 5.0, "auto"),
                      (360.0, 0.0, "modified_trapezoid")])
    h = 1e-4
    # stay away from joints, where jerk may step, so central differences are valid
    edges = [0.0] + [seg.master_end for seg in cam.segments]
    x = np.concatenate([np.linspace(a + 1e-2, b - 1e-2, 200) for a, b in zip(edges, edges[1:])])
    sp, vp, ap, _ = cam.eval_array(x + h)
    sm, vm, am, _ = cam.eval_array(x - h)
    s, v, a, j = cam.eval_array(x)
    np.testing.assert_allclose((sp - sm) / (2 * h), v, atol=1e-6)
    np.testing.assert_allclose((vp - vm) / (2 * h), a, atol=1e-7)
    np.testing.assert_allclose((ap - am) / (2 * h), j, atol=1e-8)


def test_eval_and_eval_array_agree() -> None:
    cam = SegmentCam([(30.0, 0.0, "dwell"), (90.0, 8.0, "poly345"), (150.0, 8.0, "auto"),
                      (200.0, 15.0, "constant_velocity"), (360.0, 0.0, "auto")], start=0.0)
    x = np.concatenate([np.linspace(0.0, 360.0, 997), [0.0, 30.0, 90.0, 150.0, 200.0, 360.0]])
    arr = np.array(cam.eval_array(x))
    one = np.array([cam.eval(float(xi)) for xi in x]).T
    np.testing.assert_allclose(arr, one, rtol=1e-13, atol=1e-13)
    assert cam.eval_array(np.zeros((2, 3)))[0].shape == (2, 3)


def test_table_rows_as_dicts_tuples_and_csv_text() -> None:
    rows = [
        {"master_end": "90", "slave_end": "0", "law": "dwell"},
        ("180", " 50.5 ", "Cycloidal"),  # CSV cells are text; law names ignore case
        Segment(360.0, 0.0, "auto"),
    ]
    segs = segments_from_table(rows)
    assert segs == [Segment(90.0, 0.0, "dwell"), Segment(180.0, 50.5, "cycloidal"), Segment(360.0, 0.0, "auto")]
    cam = SegmentCam.from_table(rows)
    assert cam.eval(180.0)[0] == pytest.approx(50.5)


@pytest.mark.parametrize(
    "rows, kwargs, pattern",
    [
        ([(90.0, 0.0, "dwell"), (80.0, 5.0, "cycloidal"), (360.0, 0.0, "auto")], {},
         r"segment 1: master_end = 80\.0 must be greater than the previous master_end 90\.0"),
        ([(0.0, 0.0, "dwell"), (360.0, 1.0, "auto")], {}, r"segment 0: master_end = 0\.0 must be greater"),
        ([(90.0, 0.0, "dwell"), (360.0, 1.0, "cycloid")], {},
         r"segment 1: law = 'cycloid' is not known; allowed: .*cycloidal.*dwell.*auto"),
        ([(90.0, math.nan, "auto"), (360.0, 1.0, "auto")], {}, r"segment 0: slave_end = nan must be a finite"),
        ([(90.0, 0.0, "dwell"), ("x", 1.0, "auto")], {}, r"segment 1: master_end = 'x' must be a finite"),
        ([(90.0, 3.0, "dwell"), (360.0, 0.0, "auto")], {},
         r"segment 0: slave_end = 3\.0 must equal the segment's start 0\.0 for law 'dwell'"),
        ([(90.0, 0.0, "dwell"), (350.0, 0.0, "auto")], {"master_period": 360.0},
         r"segment 1: master_end = 350\.0 must equal master_period = 360\.0"),
        ([{"master_end": 90.0, "slave": 1.0, "law": "auto"}], {},
         r"segment 0: unknown field\(s\) slave; allowed: master_end, slave_end, law"),
        ([{"master_end": 90.0, "law": "auto"}], {}, r"segment 0: missing field\(s\) slave_end"),
        ([(90.0, 0.0)], {}, r"segment 0: row = .* must be"),
        ([], {}, r"at least one segment"),
    ],
)
def test_validation_names_segment_field_value_and_what_is_allowed(rows, kwargs, pattern) -> None:
    with pytest.raises(ValueError, match=pattern):
        SegmentCam(rows, **kwargs)


def test_master_period_given_and_matching_is_accepted() -> None:
    cam = SegmentCam([(0.5, 1.0, "poly345"), (1.0, 0.0, "poly345")], master_period=1.0)
    assert cam.master_period == 1.0 and cam.closed
