"""Cam motion laws: end values, continuity, symmetry, characteristic values, transitions.

Textbook characteristic values (cv = max|v|, ca = max|a|, cj = max|j| of the normalised law)
come from
  [VDI] VDI 2143 Blatt 1 (1980), "Bewegungsgesetze für Kurvengetriebe", Kennwerte table;
  [NORTON] R. L. Norton, "Design of Machinery", chapter "Cam design", table of factors for
           peak velocity and acceleration of cam functions.
Both round to 3-4 digits; where the law has a closed form the value is also given exactly
(derived in the comment) and tested to 1e-9.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from axisline.motion.laws import LAWS, dwell, evaluate, return_, rise, transition

PI = math.pi
ALL = sorted(LAWS)

# law: (cv, ca, cj or None, source). cj None: the textbook gives none or an infinite one.
TEXTBOOK = {
    "constant_velocity": (1.0, 0.0, 0.0, "[NORTON]: s = u, cv = 1; a is 0 inside (impulses at ends)"),
    "simple_harmonic": (1.571, 4.935, None, "[VDI], [NORTON] harmonic: 1.571 / 4.935 (pi/2, pi^2/2)"),
    "cycloidal": (2.0, 6.283, 39.48, "[VDI], [NORTON] cycloid: 2 / 6.283 (2 pi) / 39.48 (4 pi^2)"),
    "modified_sine": (1.760, 5.528, 69.47, "[VDI], [NORTON] modified sine: 1.760 / 5.528 / 69.47"),
    "modified_trapezoid": (2.0, 4.888, 61.43, "[VDI], [NORTON] modified trapezoid: 2.000 / 4.888 / 61.43"),
    "poly345": (1.875, 5.7735, 60.0, "[VDI], [NORTON] 3-4-5 polynomial: 1.875 / 5.77 / 60"),
    "poly4567": (2.1875, 7.5132, 52.5, "[VDI], [NORTON] 4-5-6-7 polynomial: 2.188 / 7.51 / 52.5"),
}

# exact closed forms, derived from each law's definition
EXACT = {
    "simple_harmonic": (PI / 2, PI**2 / 2, PI**3 / 2),  # s = (1 - cos pi u)/2; cj: finite part
    "cycloidal": (2.0, 2 * PI, 4 * PI**2),  # s = u - sin(2 pi u)/(2 pi)
    # a = A sin(4 pi u) first, A = 4 pi^2/(4 + pi) from s(1) = 1; v(1/2) = 4 pi/(4 + pi); j(0) = 4 pi A
    "modified_sine": (4 * PI / (4 + PI), 4 * PI**2 / (4 + PI), 16 * PI**3 / (4 + PI)),
    # s(1/2) = A (1/(8 pi) + 1/16) = 1/2 gives A = 8 pi/(pi + 2); v(1/2) = A (1/4 + 1/(2 pi)) = 2
    "modified_trapezoid": (2.0, 8 * PI / (PI + 2), 32 * PI**2 / (PI + 2)),
    # v = 30 u^2 (1-u)^2 -> 30/16; a extreme at u = 1/2 - sqrt(3)/6 -> 10/sqrt(3); j(0) = 60
    "poly345": (1.875, 10 / math.sqrt(3), 60.0),
    # v = 140 u^3 (1-u)^3 -> 140/64; j(1/2) = -52.5; ca at u = 1/2 -/+ sqrt(5)/10 (a' = j = 0)
    "poly4567": (140 / 64, None, 52.5),
}


def dense_u(law, n: int = 20001) -> np.ndarray:
    """Uniform samples plus the law's joints, so piece changes are always sampled."""
    return np.unique(np.concatenate([np.linspace(0.0, 1.0, n), np.asarray(law.joints, dtype=float)]))


@pytest.mark.parametrize("name", ALL)
def test_rise_goes_from_0_to_1(name: str) -> None:
    s0, *_ = evaluate(name, 0.0)
    s1, *_ = evaluate(name, 1.0)
    assert s0 == pytest.approx(0.0, abs=1e-14)
    assert s1 == pytest.approx(1.0, abs=1e-14)


@pytest.mark.parametrize("name", ALL)
def test_derivatives_match_finite_differences(name: str) -> None:
    """v, a, j are the derivatives of s, v, a: a wrong sign or factor in any closed form
    shows up here."""
    h = 1e-5
    u = np.linspace(h, 1.0 - h, 4001)
    # central differences inside each piece; at a joint the two sides use different closed
    # forms, but the law is C2 there, so the O(h^2) error bound still holds
    sp, vp, ap, _ = evaluate(name, u + h)
    sm, vm, am, _ = evaluate(name, u - h)
    s, v, a, j = evaluate(name, u)
    law = LAWS[name]
    scale = max(law.cv, law.ca, law.cj, 1.0)
    np.testing.assert_allclose((sp - sm) / (2 * h), v, atol=1e-6 * scale)
    np.testing.assert_allclose((vp - vm) / (2 * h), a, atol=1e-6 * scale)
    np.testing.assert_allclose((ap - am) / (2 * h), j, atol=1e-4 * scale)


@pytest.mark.parametrize("name", ALL)
def test_no_jumps_in_s_v_a_at_joints(name: str) -> None:
    law = LAWS[name]
    # one-sided values at each internal joint: the previous piece just before, the next at it
    for uj in law.joints:
        left = law.eval(np.nextafter(uj, 0.0))
        right = law.eval(uj)
        for k, what in enumerate("sva"):
            assert right[k] == pytest.approx(left[k], abs=1e-9 * max(1.0, law.cj)), (name, uj, what)


@pytest.mark.parametrize("name", ALL)
def test_dense_sampling_has_no_steps(name: str) -> None:
    """Between neighbouring samples s, v, a change by at most (max derivative) * du."""
    law = LAWS[name]
    u = dense_u(law)
    du = np.diff(u).max()
    s, v, a, _ = law.eval(u)
    assert np.abs(np.diff(s)).max() <= law.cv * du * 1.001 + 1e-15
    assert np.abs(np.diff(v)).max() <= law.ca * du * 1.001 + 1e-15
    assert np.abs(np.diff(a)).max() <= law.cj * du * 1.001 + 1e-15


@pytest.mark.parametrize("name", ALL)
def test_symmetric_laws_are_point_symmetric(name: str) -> None:
    # all seven standard rises are point-symmetric about (0.5, 0.5):
    # s(1-u) = 1 - s(u), so v is even, a odd and j even about u = 0.5
    u = np.linspace(0.0, 1.0, 1001)
    s, v, a, j = evaluate(name, u)
    sr, vr, ar, jr = evaluate(name, 1.0 - u)
    np.testing.assert_allclose(sr, 1.0 - s, atol=1e-12)
    np.testing.assert_allclose(vr, v, atol=1e-11)
    np.testing.assert_allclose(ar, -a, atol=1e-9)
    np.testing.assert_allclose(jr, j, atol=1e-7)


@pytest.mark.parametrize("name", ALL)
def test_characteristic_values_match_textbook(name: str) -> None:
    law = LAWS[name]
    cv, ca, cj, source = TEXTBOOK[name]
    assert law.cv == pytest.approx(cv, rel=1e-3, abs=1e-12), source
    assert law.ca == pytest.approx(ca, rel=1e-3, abs=1e-12), source
    if cj is not None:
        assert law.cj == pytest.approx(cj, rel=1e-3, abs=1e-12), source


@pytest.mark.parametrize("name", sorted(EXACT))
def test_characteristic_values_match_closed_forms(name: str) -> None:
    law = LAWS[name]
    for got, want in zip((law.cv, law.ca, law.cj), EXACT[name]):
        if want is not None:
            assert got == pytest.approx(want, rel=1e-9)


@pytest.mark.parametrize("name", ALL)
def test_characteristic_values_bound_dense_samples(name: str) -> None:
    """cv, ca, cj are the maxima: never below a dense sample, and attained at u_cv, u_ca, u_cj."""
    law = LAWS[name]
    _, v, a, j = law.eval(dense_u(law))
    for c, samples in ((law.cv, v), (law.ca, a), (law.cj, j)):
        assert np.abs(samples).max() <= c * (1 + 1e-12) + 1e-12
        assert np.abs(samples).max() >= c * (1 - 1e-6) - 1e-12


def test_infinite_textbook_values_are_documented() -> None:
    # joined to dwells, simple harmonic steps in acceleration and constant velocity in velocity;
    # the characteristic values are those of the finite part, and the notes must say so
    assert "infinite" in LAWS["simple_harmonic"].notes
    assert "jerk" in LAWS["simple_harmonic"].notes
    assert "infinite" in LAWS["constant_velocity"].notes
    assert LAWS["simple_harmonic"].eval(0.0)[2] == pytest.approx(PI**2 / 2)
    assert LAWS["constant_velocity"].ca == 0.0


def test_floats_in_floats_out_and_arrays_agree() -> None:
    u = np.array([0.0, 0.1, 0.125, 0.3, 0.5, 0.875, 0.99, 1.0])
    for name in ALL:
        arr = evaluate(name, u)
        assert all(isinstance(x, np.ndarray) and x.shape == u.shape for x in arr)
        for i, ui in enumerate(u):
            one = evaluate(name, float(ui))
            assert all(isinstance(x, float) for x in one)
            assert one == pytest.approx(tuple(x[i] for x in arr), abs=1e-12)
    # shapes are kept (a grid of u for plots)
    assert evaluate("cycloidal", np.zeros((3, 2)))[0].shape == (3, 2)


def test_unknown_law_name_is_rejected_with_the_allowed_names() -> None:
    with pytest.raises(ValueError, match="cycloid.*allowed.*cycloidal"):
        evaluate("cycloid", 0.5)


def test_law_object_interface() -> None:
    law = LAWS["cycloidal"]
    assert law.name == "cycloidal"
    assert law.eval(0.25) == pytest.approx((0.25 - 1 / (2 * PI), 1.0, 2 * PI, 0.0), abs=1e-12)


def test_dwell_rise_return() -> None:
    u = np.linspace(0.0, 1.0, 101)
    assert all(np.all(x == 0.0) for x in dwell().eval(u))
    assert rise("poly345") is LAWS["poly345"]
    for name in ALL:
        ret = return_(name)
        s, v, a, j = ret.eval(u)
        sr, vr, ar, jr = rise(name).eval(u)
        np.testing.assert_allclose(s, 1.0 - sr, atol=1e-12)
        np.testing.assert_allclose(v, -vr, atol=1e-12)
        np.testing.assert_allclose(a, -ar, atol=1e-9)
        assert ret.eval(0.0)[0] == pytest.approx(1.0) and ret.eval(1.0)[0] == pytest.approx(0.0, abs=1e-14)
        assert (ret.cv, ret.ca) == pytest.approx((LAWS[name].cv, LAWS[name].ca))
    with pytest.raises(ValueError, match="allowed"):
        return_("nope")


finite = st.floats(min_value=-20.0, max_value=20.0, allow_nan=False)


@given(finite, finite, finite, finite)
def test_transition_meets_its_six_boundary_conditions(v0: float, a0: float, v1: float, a1: float) -> None:
    law = transition(v0, a0, v1, a1)
    s, v, a, _ = law.eval(0.0)
    assert (s, v, a) == pytest.approx((0.0, v0, a0), abs=1e-12)
    s, v, a, _ = law.eval(1.0)
    assert (s, v, a) == pytest.approx((1.0, v1, a1), abs=1e-11)


def test_transition_special_cases_are_the_known_laws() -> None:
    # rest to rest is the 3-4-5 polynomial (so its characteristic values are too)
    t = transition(0.0, 0.0, 0.0, 0.0)
    u = np.linspace(0.0, 1.0, 51)
    np.testing.assert_allclose(t.eval(u)[0], evaluate("poly345", u)[0], atol=1e-14)
    assert (t.cv, t.ca, t.cj) == pytest.approx((LAWS["poly345"].cv, LAWS["poly345"].ca, 60.0))
    # velocity 1 to velocity 1 with no acceleration is the constant-velocity law s = u
    np.testing.assert_allclose(transition(1.0, 0.0, 1.0, 0.0).eval(u)[0], u, atol=1e-14)


def test_transition_rejects_non_finite_boundary_values() -> None:
    with pytest.raises(ValueError, match="a1"):
        transition(0.0, 0.0, 0.0, math.inf)
