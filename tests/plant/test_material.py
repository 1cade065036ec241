"""Material line: speed profile integrated exactly, positions inside a cycle, slipping contacts."""

from __future__ import annotations

import math

import numpy as np
import pytest

from axisline.plant import MaterialLine, SlipContact, SpeedChange

PERIODS = [0.00025, 0.001, 0.004, 0.01]


def analytic_position(t: float) -> float:
    """Profile below: 0.5 units/s, from 0.0123 s ramp to 2.0 at 5 units/s^2 (0.3 s),
    from 1.0 s ramp to -0.5 at 10 units/s^2 (0.25 s)."""
    p = 0.5 * min(t, 0.0123)
    if t > 0.0123:
        r = min(t - 0.0123, 0.3)
        p += 0.5 * r + 2.5 * r * r
    if t > 0.3123:
        p += 2.0 * (min(t, 1.0) - 0.3123)
    if t > 1.0:
        r = min(t - 1.0, 0.25)
        p += 2.0 * r - 5.0 * r * r
    if t > 1.25:
        p += -0.5 * (t - 1.25)
    return p


def profile_line() -> MaterialLine:
    return MaterialLine([SpeedChange(0.0123, 2.0, 5.0), SpeedChange(1.0, -0.5, 10.0)], speed=0.5)


@pytest.mark.parametrize("dt", PERIODS)
def test_position_after_ramps_equals_the_analytic_value(dt):
    line = profile_line()
    steps = round(1.5 / dt)
    for n in range(1, steps + 1):
        line.step(dt)
        if n % round(0.05 / dt) == 0:
            assert line.position == pytest.approx(analytic_position(n * dt), abs=1e-12)
    assert line.time == pytest.approx(1.5, abs=1e-15)
    assert line.velocity == -0.5
    assert line.acceleration == 0.0


def test_position_inside_a_cycle_with_a_ramp_starting_mid_cycle():
    line = profile_line()
    line.step(0.01)
    line.step(0.01)  # the ramp starts at 0.0123 s, 23 % into this cycle
    for f in (0.1, 0.23, 0.5, 0.99):
        t = 0.01 + f * 0.01
        assert line.position_at(f) == pytest.approx(analytic_position(t), abs=1e-14)
    assert line.velocity_at(0.5) == pytest.approx(0.5 + 5.0 * (0.015 - 0.0123))


def test_set_speed_takes_effect_from_the_next_step():
    line = MaterialLine(speed=1.0)
    line.step(0.001)
    line.set_speed(3.0, 100.0)
    for _ in range(30):
        line.step(0.001)
    # 20 ms ramp from 1 to 3, then 10 ms at 3
    assert line.position == pytest.approx(0.001 + 0.02 * 1.0 + 0.5 * 100 * 0.02**2 + 0.01 * 3.0)
    line.set_speed(0.0)  # infinite acceleration: stops at once
    assert line.velocity == 0.0


def test_crossings_are_solved_exactly_while_accelerating_and_reversing():
    line = MaterialLine([SpeedChange(0.0, -1.0, 100.0)], speed=1.0)  # turns at 10 ms
    line.step(0.02)
    lo, hi = line.position_bounds()
    assert hi == pytest.approx(0.005)  # turning point
    assert lo == pytest.approx(0.0)
    t1 = (1.0 - math.sqrt(1.0 - 4.0 * 50.0 * 0.004)) / 100.0  # t - 50 t^2 = 0.004
    (up, down) = line.crossings(0.004)
    assert up == (pytest.approx(t1 / 0.02, abs=1e-12), 1)
    assert down == (pytest.approx((0.02 - t1) / 0.02, abs=1e-12), -1)
    assert line.crossings(0.006) == ()


def test_slip_contact_sees_travel_times_one_minus_slip():
    line = MaterialLine(speed=2.0, position=5.0)
    wheel = SlipContact(line, slip=0.02)
    for _ in range(100):
        line.step(0.001)
    assert wheel.position == pytest.approx(0.2 * 0.98)
    assert wheel.velocity == pytest.approx(2.0 * 0.98)
    wheel.set_slip(0.0)  # no jump, then no slip
    line.step(0.001)
    assert wheel.position == pytest.approx(0.2 * 0.98 + 0.002)
    ((fraction, direction),) = wheel.crossings(0.2 * 0.98 + 0.0005)
    assert (fraction, direction) == (pytest.approx(0.25), 1)


def test_slip_jitter_is_seeded_and_independent_of_the_cycle_period():
    def wheel_after(seed: int, dt: float) -> float:
        line = MaterialLine(speed=1.0)
        wheel = SlipContact(line, slip=0.01, slip_jitter=0.005, jitter_length=0.01,
                            rng=np.random.default_rng(seed))
        for _ in range(round(0.5 / dt)):
            line.step(dt)
            wheel.position  # sampled every cycle, as the machine does
        return wheel.position

    a = wheel_after(7, 0.001)
    assert a == wheel_after(7, 0.001)
    assert a == pytest.approx(wheel_after(7, 0.00025), abs=1e-12)
    assert a != wheel_after(8, 0.001)
    assert a == pytest.approx(0.5 * 0.99, abs=0.005)
