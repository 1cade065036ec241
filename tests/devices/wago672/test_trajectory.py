"""Ramp laws of Acceleration_Modes on the kernel profile generator (wago.md §2.7; trajectory.py)."""

from __future__ import annotations

import math

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from axisline.devices.wago672.errors import WagoError
from axisline.devices.wago672.trajectory import Chain, needs_constant_speed, plan_move, plan_speed, ramp_from_mode
from axisline.motion.profiles import State


def test_mode_fields_map_to_kernel_shapes():
    assert ramp_from_mode(0, 0, 1000.0, 300).shape == "trapezoid"
    lin = ramp_from_mode(1, 0, 1000.0, 300)
    assert lin.shape == "jerk" and lin.jerk == pytest.approx(1000.0 / 0.3)
    sin2 = ramp_from_mode(2, 0, 1000.0, 300)
    assert sin2.shape == "sin2" and sin2.jerk == pytest.approx(math.pi / 2 * 1000.0 / 0.3)  # rise lasts 300 ms
    assert ramp_from_mode(1, 1, 1000.0, 250).shape == "jerk/time" and ramp_from_mode(1, 1, 1000.0, 250).time == 0.25
    assert ramp_from_mode(2, 2, 1000.0, 77, 154.0).shape == "sin2/path" and ramp_from_mode(2, 2, 1000.0, 77, 154.0).path == 154.0
    for bad in ((3, 0), (0, 3)):
        with pytest.raises(WagoError) as exc:
            ramp_from_mode(*bad, 1000.0, 300)
        assert exc.value.code == 1557
    with pytest.raises(WagoError) as exc:
        ramp_from_mode(1, 0, 1000.0, 0)  # a jerk time of 0
    assert exc.value.code == 1557


def test_sin2_rise_lasts_the_jerk_time():
    r = ramp_from_mode(2, 0, 1000.0, 200)
    prof = plan_speed(State(0.0, 0.0, 0.0), 1000.0, r, r)  # 1000/s at 1000/s^2: 1 s plus the jerk time
    assert prof.duration == pytest.approx(1.0 + 0.2, abs=1e-9)


_RAMPS = st.tuples(st.integers(0, 2), st.integers(0, 2), st.integers(500, 50000), st.integers(20, 400))


@settings(max_examples=60, deadline=None)
@given(up=_RAMPS, down=_RAMPS, target=st.floats(-50000, 50000), v0=st.floats(-8000, 8000), vmax=st.floats(500, 20000))
def test_every_mix_of_ramp_laws_arrives_exactly_at_rest(up, down, target, v0, vmax):
    ru = ramp_from_mode(up[0], up[1], float(up[2]), up[3], float(up[3]), "Acc")
    rd = ramp_from_mode(down[0], down[1], float(down[2]), down[3], float(down[3]), "Dec")
    start = State(0.0, v0, 0.0)
    prof = plan_move(start, target, vmax, ru, rd)
    p, v, a, _ = prof.sample(prof.duration)
    assert p == pytest.approx(target, abs=1e-6 * max(1.0, abs(target)))
    assert v == pytest.approx(0.0, abs=1e-6) and a == 0.0
    peak = max(abs(prof.sample(prof.duration * k / 200)[1]) for k in range(201))
    assert peak <= max(vmax, abs(v0)) * (1 + 1e-9) + 1e-9
    if isinstance(prof, Chain):
        assert needs_constant_speed(ru, rd)
