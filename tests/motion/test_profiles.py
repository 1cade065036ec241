"""Profiles: exactness, limits, continuity, time-optimality against Ruckig, WAGO variants."""

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from axisline.motion.profiles import SHAPES, Limits, State, plan, plan_velocity
from axisline.motion.profiles import _end_of  # the state the segments really reach

ruckig = pytest.importorskip("ruckig")

REL = 1e-9


def ruckig_duration(start: State, target: State, lim: Limits) -> float:
    inp = ruckig.InputParameter(1)
    inp.current_position = [start.p]
    inp.current_velocity = [start.v]
    inp.current_acceleration = [start.a]
    inp.target_position = [target.p]
    inp.target_velocity = [target.v]
    inp.target_acceleration = [0.0]
    inp.max_velocity = [lim.v]
    inp.max_acceleration = [lim.a]
    inp.max_jerk = [lim.j]
    traj = ruckig.Trajectory(1)
    res = ruckig.Ruckig(1).calculate(inp, traj)
    assert res in (ruckig.Result.Working, ruckig.Result.Finished)
    return traj.duration


def segment_end(prof):
    segs = list(zip(prof._kind, prof._tau, prof._p, prof._v, prof._a, prof._j))
    return _end_of(segs, prof.start)


def dense_samples(prof, n=400):
    """Sample uniformly and at both sides of every segment joint."""
    ts = list(np.linspace(0.0, prof.duration, n))
    for t0, tau in zip(prof._t0, prof._tau):
        for t in (t0, t0 + tau * 0.5, t0 + tau * (1 - 1e-12)):
            ts.append(t)
    return np.array([prof.sample(t) for t in sorted(ts)])


def assert_reaches(prof, target: State, scale: float) -> None:
    end = segment_end(prof)
    tol = REL * max(1.0, scale)
    assert abs(end.p - target.p) <= tol, (end, target)
    assert abs(end.v - target.v) <= tol, (end, target)
    if not prof.shape.startswith("trapezoid"):  # a trapezoid drops its acceleration in a step
        assert abs(end.a) <= tol * 10, (end, target)
    p, v, a, _ = prof.sample(prof.duration)
    assert (p, v, a) == (target.p, target.v, 0.0)


def assert_within(prof, lim: Limits, shape: str) -> None:
    s = dense_samples(prof)
    d = lim.a if lim.d is None else lim.d
    assert np.all(np.abs(s[:, 1]) <= lim.v * (1 + REL) + 1e-12)
    assert np.all(np.abs(s[:, 2]) <= max(lim.a, d) * (1 + REL) + 1e-12)
    if shape in ("jerk", "sin2") and lim.j is not None:
        assert np.all(np.abs(s[:, 3]) <= lim.j * (1 + REL) + 1e-12)


# -- the example and closed forms -------------------------------------------------


def test_public_api_example_reaches_target_with_closed_form_duration():
    prof = plan("jerk", State(p=0.0, v=0.0, a=0.0), State(p=10.0, v=0.0), Limits(v=1.0, a=2.0, d=2.0, j=10.0))
    # rest to rest with both limits reached: T = D/v + v/a + a/j
    assert prof.duration == pytest.approx(10.0 + 0.5 + 0.2, rel=1e-12)
    assert_reaches(prof, State(10.0, 0.0), 10.0)
    p, v, a, j = prof.sample(0.1)  # first jerk phase: p = j t^3 / 6
    assert (p, v, a, j) == pytest.approx((10 * 0.1**3 / 6, 10 * 0.1**2 / 2, 1.0, 10.0), rel=1e-12)


def test_trapezoid_with_separate_acceleration_and_deceleration():
    lim = Limits(v=1.0, a=1.0, d=2.0)
    prof = plan("trapezoid", State(), State(10.0), lim)
    # accelerate v/a = 1 s (0.5 m), brake v/d = 0.5 s (0.25 m), cruise 9.25 m
    assert prof.duration == pytest.approx(1.0 + 9.25 + 0.5, rel=1e-12)
    assert prof.sample(0.5)[2] == 1.0
    assert prof.sample(prof.duration - 0.25)[2] == -2.0
    assert_reaches(prof, State(10.0), 10.0)


def test_short_move_does_not_reach_speed():
    prof = plan("trapezoid", State(), State(1.0), Limits(v=10.0, a=1.0))
    assert prof.duration == pytest.approx(2.0, rel=1e-12)  # triangle: 2*sqrt(D/a)
    assert max(prof.sample(t)[1] for t in np.linspace(0, 2, 201)) == pytest.approx(1.0, rel=1e-9)


def test_sin2_ramp_follows_sin_squared_and_keeps_peak_jerk():
    lim = Limits(v=1.0, a=2.0, j=10.0)
    prof = plan("sin2", State(), State(10.0), lim)
    tj = math.pi / 2 * 2.0 / 10.0  # rise time of a sin² ramp with peak jerk j
    for f in (0.25, 0.5, 0.75):
        assert prof.sample(f * tj)[2] == pytest.approx(2.0 * math.sin(math.pi * f / 2) ** 2, rel=1e-12)
    assert prof.sample(tj / 2)[3] == pytest.approx(10.0, rel=1e-12)
    assert_reaches(prof, State(10.0), 10.0)
    assert_within(prof, lim, "sin2")
    # same mean acceleration as the linear ramp: rest-to-rest time = D/v + v/a + tj
    assert prof.duration == pytest.approx(10.0 + 0.5 + tj, rel=1e-12)


def test_ramp_time_gives_the_equivalent_jerk():
    a = plan("jerk", State(), State(5.0), Limits(v=1.0, a=2.0, ramp_time=0.2))
    b = plan("jerk", State(), State(5.0), Limits(v=1.0, a=2.0, j=10.0))
    assert a.duration == pytest.approx(b.duration, rel=1e-12)


# -- WAGO time / path variants (wago.md §2.7) ----------------------------------------------


@pytest.mark.parametrize("base", ["trapezoid", "jerk", "sin2"])
def test_wago_time_variant_ramps_last_the_given_time(base):
    lim = Limits(v=2.0, a=1.0, up_time=0.5, down_time=0.25)
    prof = plan(f"{base}/time", State(), State(10.0), lim)
    assert prof.sample(0.5)[1] == pytest.approx(2.0, rel=1e-12)
    assert prof.sample(0.5)[2] == pytest.approx(0.0, abs=1e-12)
    # ramp distances (v0+v1)/2*T: 0.5 and 0.25 m, cruise 9.25 m at 2 m/s
    assert prof.duration == pytest.approx(0.5 + 9.25 / 2.0 + 0.25, rel=1e-12)
    assert_reaches(prof, State(10.0), 10.0)
    if base != "trapezoid":
        # bell: peak acceleration 2*dv/T in the middle of the ramp
        assert prof.sample(0.25)[2] == pytest.approx(2 * 2.0 / 0.5, rel=1e-12)


def test_wago_time_variant_short_move_keeps_ramp_times():
    prof = plan("jerk/time", State(), State(0.5), Limits(v=2.0, a=1.0, up_time=0.5, down_time=0.5))
    assert prof.duration == pytest.approx(1.0, rel=1e-12)
    assert prof.sample(0.5)[1] == pytest.approx(1.0, rel=1e-12)  # peak speed reduced
    assert_reaches(prof, State(0.5), 1.0)


def test_wago_path_variant_ramp_covers_the_given_path():
    prof = plan("sin2/path", State(), State(10.0), Limits(v=2.0, a=1.0, up_path=1.0, down_path=0.5))
    t_up = 2 * 1.0 / 2.0  # T = 2S/(v0+v1)
    p, v, a, _ = prof.sample(t_up)
    assert (p, v) == pytest.approx((1.0, 2.0), rel=1e-12)
    assert_reaches(prof, State(10.0), 10.0)


def test_time_variants_need_zero_start_acceleration():
    with pytest.raises(ValueError, match="State.a"):
        plan("jerk/time", State(a=0.5), State(1.0), Limits(v=1.0, a=1.0, up_time=1.0, down_time=1.0))
    with pytest.raises(ValueError, match="Limits.up_time"):
        plan("jerk/time", State(), State(1.0), Limits(v=1.0, a=1.0))


# -- bad input ---------------------------------------------------------------------------


@pytest.mark.parametrize(
    "lim, field",
    [
        (Limits(v=0.0, a=1.0, j=1.0), "Limits.v"),
        (Limits(v=1.0, a=-1.0, j=1.0), "Limits.a"),
        (Limits(v=1.0, a=1.0, d=0.0, j=1.0), "Limits.d"),
        (Limits(v=1.0, a=1.0, j=0.0), "Limits.j"),
        (Limits(v=1.0, a=1.0, j=float("nan")), "Limits.j"),
        (Limits(v=1.0, a=1.0), "Limits.j"),
    ],
)
def test_impossible_limits_raise_naming_the_field(lim, field):
    with pytest.raises(ValueError, match=field.replace(".", r"\.")):
        plan("jerk", State(), State(1.0), lim)


def test_bad_states_and_shape_raise_naming_the_field():
    lim = Limits(v=1.0, a=1.0, j=1.0)
    with pytest.raises(ValueError, match=r"start\.p"):
        plan("jerk", State(p=float("nan")), State(1.0), lim)
    with pytest.raises(ValueError, match=r"target\.v"):
        plan("jerk", State(), State(1.0, v=2.0), lim)
    with pytest.raises(ValueError, match="shape"):
        plan("cubic", State(), State(1.0), lim)


# -- properties over random requests -------------------------------------------------------

finite = dict(allow_nan=False, allow_infinity=False)


@st.composite
def requests(draw, moving=True, target_velocity=True):
    vmax = draw(st.floats(0.05, 5.0, **finite))
    amax = draw(st.floats(0.05, 20.0, **finite))
    jmax = draw(st.floats(0.2, 200.0, **finite))
    v0 = draw(st.floats(-vmax, vmax, **finite)) if moving else 0.0
    a0 = draw(st.floats(-amax, amax, **finite)) if moving else 0.0
    # a start state inside the limits: braking to a = 0 keeps |v| <= v_max
    assume(abs(v0 + a0 * abs(a0) / (2 * jmax)) <= vmax)
    p0 = draw(st.floats(-10.0, 10.0, **finite))
    pf = draw(st.floats(-10.0, 10.0, **finite))
    vf = draw(st.floats(-vmax, vmax, **finite)) if target_velocity else 0.0
    return State(p0, v0, a0), State(pf, vf), Limits(v=vmax, a=amax, d=amax, j=jmax)


def inside_for_shape(start: State, lim: Limits, shape: str) -> bool:
    """A sin² ramp takes pi/2 longer than a linear one for the same peak jerk, so
    bringing a to 0 adds pi/2 more velocity: the start is inside only if that fits."""
    k = {"trapezoid": 0.0, "jerk": 1.0, "sin2": math.pi / 2}[shape]
    return abs(start.v + k * start.a * abs(start.a) / (2 * lim.j)) <= lim.v


def _same_duration_as_ruckig(req):
    start, target, lim = req
    prof = plan("jerk", start, target, lim)
    ref = ruckig_duration(start, target, lim)
    assert_reaches(prof, target, max(abs(target.p), abs(start.p), 1.0))
    assert_within(prof, lim, "jerk")
    if prof.duration < ref * (1 - 1e-6):
        # Faster than Ruckig and verified above (exact target, limits kept): this happens
        # where Ruckig's profile check rejects a boundary case (a start exactly at the
        # velocity limit with a denormal acceleration) and falls back to a slower profile.
        return
    if abs(prof.duration - ref) > 1e-6 * ref:
        # Ruckig accepts a profile within its own 1e-8 position precision, which for
        # motions that small allows a time error of the order (6e-8/j)^(1/3).
        size = max(abs(target.p - start.p), abs(start.v), abs(target.v), abs(start.a) ** 2 / lim.j)
        assert size < 1e-6, (prof.duration, ref)
        assert abs(prof.duration - ref) <= 4 * (6e-8 / lim.j) ** (1 / 3), (prof.duration, ref)


@settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.filter_too_much])
@given(requests(moving=False, target_velocity=False))
def test_rest_to_rest_is_as_fast_as_ruckig(req):
    _same_duration_as_ruckig(req)


@settings(max_examples=400, deadline=None, suppress_health_check=[HealthCheck.filter_too_much])
@given(requests(moving=True, target_velocity=False))
def test_moving_start_to_rest_is_as_fast_as_ruckig(req):
    _same_duration_as_ruckig(req)


@settings(max_examples=400, deadline=None, suppress_health_check=[HealthCheck.filter_too_much])
@given(requests(moving=True, target_velocity=True))
def test_moving_start_to_target_velocity_is_as_fast_as_ruckig(req):
    _same_duration_as_ruckig(req)


def test_overshooting_start_reverses_and_matches_ruckig():
    # moving fast toward a target just ahead: it must pass it and come back
    start, target, lim = State(0.0, 1.0, 0.5), State(0.05, 0.0), Limits(v=1.2, a=1.0, d=1.0, j=5.0)
    prof = plan("jerk", start, target, lim)
    assert max(prof.sample(t)[0] for t in np.linspace(0, prof.duration, 500)) > 0.3
    assert prof.duration == pytest.approx(ruckig_duration(start, target, lim), rel=1e-6)


def test_a_root_search_across_infeasible_parameters_finds_the_profile():
    """Found by hypothesis: from a = v = 1e-12 to the same p and v, the end error has a sign
    change between two grid points with no profile in between: not a root, and no crash."""
    start, target, lim = State(1e-12, 1e-12, 1e-12), State(1e-12, 1e-12, 0.0), Limits(v=1.0, a=1.0, d=1.0, j=1.0)
    _same_duration_as_ruckig((start, target, lim))


def test_a_start_one_ulp_below_the_velocity_limit_finds_the_loop_back():
    """Found by hypothesis: at p = 0 one ulp below v_max, reaching p = 0 at v_max needs a loop
    backwards whose peak is exactly v_max: the root sits on the end of the search interval,
    within rounding of zero but with no sign change to bracket it."""
    start, target, lim = State(0.0, 0.49999999999999994, 0.0), State(0.0, 0.5), Limits(v=0.5, a=0.05, d=0.05, j=8.0)
    _same_duration_as_ruckig((start, target, lim))
    assert plan("jerk", start, target, lim).duration > 40.0


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.filter_too_much])
@given(requests(moving=True, target_velocity=True), st.sampled_from(["trapezoid", "jerk", "sin2"]), st.floats(0.3, 3.0))
def test_every_shape_reaches_the_target_within_limits(req, shape, d_ratio):
    start, target, lim = req
    lim = Limits(v=lim.v, a=lim.a, d=lim.a * d_ratio, j=lim.j)
    if shape == "trapezoid":
        start = State(start.p, start.v, 0.0)
    assume(inside_for_shape(start, lim, shape))
    prof = plan(shape, start, target, lim)
    assert_reaches(prof, target, max(abs(target.p), abs(start.p), 1.0))
    assert_within(prof, lim, shape)


@settings(max_examples=100, deadline=None)
@given(requests(moving=True, target_velocity=True), st.sampled_from(["jerk", "sin2"]))
def test_position_and_velocity_are_continuous_at_every_joint(req, shape):
    start, target, lim = req
    prof = plan(shape, start, target, lim)
    for t0 in prof._t0[1:]:
        eps = 1e-9 * max(prof.duration, 1.0)
        before, after = prof.sample(t0 - eps), prof.sample(t0)
        # over eps the state may move by its derivative times eps, no more (no jumps)
        assert after[0] == pytest.approx(before[0], abs=2 * lim.v * eps + 1e-9 * max(1.0, abs(before[0])))
        assert after[1] == pytest.approx(before[1], abs=2 * lim.a * eps + 1e-9 * lim.v)
        assert after[2] == pytest.approx(before[2], abs=2 * lim.j * eps + 1e-9 * lim.a)  # C2 for shaped ramps


@settings(max_examples=100, deadline=None)
@given(requests(moving=True, target_velocity=True), st.sampled_from(["trapezoid", "jerk", "sin2"]))
def test_velocity_profile_reaches_and_keeps_the_velocity(req, shape):
    start, target, lim = req
    if shape == "trapezoid":
        start = State(start.p, start.v, 0.0)
    assume(inside_for_shape(start, lim, shape))
    prof = plan_velocity(shape, start, target.v, lim)
    end = segment_end(prof)
    assert end.v == pytest.approx(target.v, abs=1e-9 * max(1.0, lim.v))
    if shape != "trapezoid":
        assert end.a == pytest.approx(0.0, abs=1e-9 * max(1.0, lim.a))
    p1, v1, a1, _ = prof.sample(prof.duration + 2.0)
    assert v1 == target.v and a1 == 0.0
    assert p1 == pytest.approx(end.p + 2.0 * target.v, abs=1e-9 * max(1.0, abs(end.p)))
    assert_within(prof, lim, shape)


def test_start_above_the_speed_limit_brakes_back_inside_then_arrives():
    # e.g. a speed override lowered while moving: v0 = 2 with v_max = 1
    lim = Limits(v=1.0, a=2.0, j=20.0)
    prof = plan("jerk", State(0.0, 2.0, 0.0), State(20.0), lim)
    s = dense_samples(prof)
    t_in = next(t for t in np.linspace(0, prof.duration, 2000) if prof.sample(t)[1] <= 1.0 + 1e-9)
    assert all(prof.sample(t)[1] <= 1.0 + 1e-9 for t in np.linspace(t_in, prof.duration, 500))
    assert np.all(np.abs(s[:, 2]) <= 2.0 * (1 + REL))
    assert_reaches(prof, State(20.0), 20.0)


def test_shapes_listed():
    assert set(SHAPES) >= {"trapezoid", "jerk", "sin2", "jerk/time", "sin2/path", "trapezoid/time"}


def test_sin2_replan_in_the_middle_of_a_ramp_keeps_the_speed_limit():
    # an on-the-fly target change while a sin² ramp-up is about to reach v_max
    lim = Limits(v=100.0, a=1000.0, j=20000.0)
    first = plan("sin2", State(), State(500.0), lim)
    t_mid = next(t for t in np.arange(0.0, first.duration, 1e-3) if first.sample(t)[1] > 90.0)
    p, v, a, _ = first.sample(t_mid)
    assert a > 100.0  # still accelerating
    again = plan("sin2", State(p, v, a), State(800.0), lim)
    s = dense_samples(again, 2000)
    assert np.all(np.abs(s[:, 1]) <= 100.0 * (1 + REL))
    assert np.all(np.abs(s[:, 3]) <= 20000.0 * (1 + REL))
    assert_reaches(again, State(800.0), 800.0)
