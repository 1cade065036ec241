"""Print-mark sensor and axis switches: edges with exact sub-cycle timestamps."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from axisline.plant import (
    LimitSwitch,
    MaterialLine,
    PrintMarks,
    PrintMarkSensor,
    ReferenceSwitch,
    ServoDrive,
    SlipContact,
    SpeedChange,
)

PERIODS = [0.00025, 0.001, 0.004, 0.01]
V0, ACCEL = 0.5, 3.0  # the line accelerates for the whole test run
SENSOR, FIRST, PITCH, WIDTH = 0.2, 0.05, 0.1, 0.01


def run_marks(sensor: PrintMarkSensor, line: MaterialLine, dt: float, until: float) -> list:
    edges = []
    for n in range(round(until / dt)):
        line.step(dt)
        edges.extend(sensor.sample(n * dt, dt))
    return edges


def crossing_time(x: float) -> float:
    return (-V0 + math.sqrt(V0 * V0 + 2.0 * ACCEL * x)) / ACCEL


@pytest.mark.parametrize("dt", PERIODS)
def test_mark_edges_match_the_analytic_crossing_time_while_accelerating(dt):
    line = MaterialLine([SpeedChange(0.0, 50.0, ACCEL)], speed=V0)
    marks = PrintMarks(width=WIDTH, pitch=PITCH, first=FIRST)
    sensor = PrintMarkSensor(line, marks, sensor_position=SENSOR)
    edges = run_marks(sensor, line, dt, 1.0)
    assert len(edges) == 2 * 18  # P(1 s) = 2.0: marks 0..17 reach 0.25 + 0.1 k and leave
    for i, edge in enumerate(edges):
        k, rising = divmod(i, 2)[0], i % 2 == 0
        x = SENSOR + FIRST + k * PITCH + (0.0 if rising else WIDTH)
        assert edge.mark == k and edge.rising == rising and edge.position == pytest.approx(x)
        assert edge.time == pytest.approx(crossing_time(x), abs=1e-9)
        assert 0.0 <= edge.fraction <= 1.0
        assert edge.time == pytest.approx(math.floor(edge.time / dt) * dt + edge.fraction * dt, abs=1e-12)


def test_mark_edge_after_a_ramp_ending_mid_cycle():
    line = MaterialLine([SpeedChange(0.0, 1.0, 10.0)], speed=0.0)  # ramp ends at 0.1 s
    sensor = PrintMarkSensor(line, PrintMarks(width=0.01, positions=[0.1]), sensor_position=0.0)
    edges = run_marks(sensor, line, 0.004, 0.3)  # 0.1 s lies inside cycle 25
    # 0.05 travelled in the ramp, then 0.05 at 1 units/s
    assert [e.time for e in edges] == [pytest.approx(0.15, abs=1e-12), pytest.approx(0.16, abs=1e-12)]


def test_sensor_inverts_and_reports_state():
    line = MaterialLine(speed=1.0)
    sensor = PrintMarkSensor(line, PrintMarks(width=0.01, positions=[0.005]), invert=True)
    assert sensor.state  # no mark: output high
    line.step(0.01)
    (fall,) = sensor.sample(0.0, 0.01)
    assert not fall.rising and not sensor.state and sensor.covered


def jittered_edges(seed: int, dt: float = 0.001, missing: float = 0.0) -> list[float]:
    line = MaterialLine(speed=2.0)
    marks = PrintMarks(width=0.005, pitch=0.1, jitter=0.002, missing_probability=missing,
                       rng=np.random.default_rng(seed))
    sensor = PrintMarkSensor(line, marks, sensor_position=0.3)
    return [e.time for e in run_marks(sensor, line, dt, 2.0) if e.rising]


def test_seeded_jitter_is_reproducible_and_differs_with_another_seed():
    a = jittered_edges(11)
    assert a == jittered_edges(11)
    assert a != jittered_edges(12)
    nominal = [(0.3 + 0.1 * k) / 2.0 for k in range(len(a))]
    assert max(abs(t - n) for t, n in zip(a, nominal)) <= 3 * 0.002 / 2.0
    assert max(abs(t - n) for t, n in zip(a, nominal)) > 0.0


def test_jittered_marks_do_not_depend_on_the_cycle_period():
    assert jittered_edges(5, 0.00025) == pytest.approx(jittered_edges(5, 0.004), abs=1e-12)


def test_missing_marks_are_seeded():
    all_marks = jittered_edges(2)
    some = jittered_edges(2, missing=0.3)
    assert len(some) < len(all_marks)
    assert some == jittered_edges(2, missing=0.3)
    assert set(some) <= set(all_marks)  # the same marks, some left out


def test_marks_seen_by_material_pulled_through_a_slipping_roll():
    roll = MaterialLine(speed=1.0)  # stands in for the feed roll's surface
    material = SlipContact(roll, slip=0.2)
    sensor = PrintMarkSensor(material, PrintMarks(width=0.01, positions=[0.4]))
    edges = run_marks(sensor, roll, 0.001, 1.0)
    assert edges[0].time == pytest.approx(0.4 / 0.8, abs=1e-12)


def servo_position(t: float, v: float = 100.0, tau: float = 0.01) -> float:
    return v * (t - tau * (1.0 - math.exp(-t / tau)))


def solve(f, x: float, lo: float, hi: float) -> float:
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if f(mid) < x else (lo, mid)
    return 0.5 * (lo + hi)


@pytest.mark.parametrize("dt", PERIODS)
def test_reference_switch_edges_are_exact_on_an_accelerating_servo(dt):
    drive = ServoDrive(enabled=True, time_constant=0.01)
    drive.command_velocity(100.0)
    switch = ReferenceSwitch(drive, position=0.5, width=1.0)
    edges = []
    for n in range(round(0.06 / dt)):
        drive.step(dt)
        edges.extend(switch.sample(n * dt, dt))
    assert [e.rising for e in edges] == [True, False]
    assert edges[0].time == pytest.approx(solve(servo_position, 0.5, 0.0, 0.1), abs=1e-9)
    assert edges[1].time == pytest.approx(solve(servo_position, 1.5, 0.0, 0.1), abs=1e-9)


def test_limit_switch_hysteresis_and_normally_closed_contact():
    line = MaterialLine([SpeedChange(0.1, -1.0)], speed=1.0)  # forward 0.1 then back
    switch = LimitSwitch(line, 0.08, direction=1, hysteresis=0.01, invert=True)
    assert switch.state  # NC contact closed while not actuated
    edges = []
    for n in range(200):
        line.step(0.001)
        edges.extend(switch.sample(n * 0.001, 0.001))
    assert [(e.rising, e.position) for e in edges] == [(False, 0.08), (True, 0.07)]
    assert edges[0].time == pytest.approx(0.08, abs=1e-12)
    assert edges[1].time == pytest.approx(0.13, abs=1e-12)


@settings(max_examples=60, deadline=None)
@given(
    speeds=st.lists(st.floats(-2.0, 2.0), min_size=1, max_size=8),
    accel=st.floats(1.0, 500.0),
    dt=st.sampled_from(PERIODS),
    hysteresis=st.sampled_from([0.0, 0.002]),
)
def test_switch_state_always_agrees_with_its_edges_and_position(speeds, accel, dt, hysteresis):
    # Random back-and-forth motion: every edge toggles the state; the state ends where the
    # position says, whatever the motion did inside the cycles.
    profile = [SpeedChange(0.013 * i, v, accel) for i, v in enumerate(speeds)]
    line = MaterialLine(profile)
    switch = ReferenceSwitch(line, position=0.003, width=0.004, hysteresis=hysteresis)
    marks = PrintMarkSensor(line, PrintMarks(width=0.003, pitch=0.01, first=-0.05))
    state, covered = switch.active, marks.covered
    for n in range(round(0.15 / dt)):
        line.step(dt)
        for edge in switch.sample(n * dt, dt):
            assert edge.rising != state
            state = edge.rising
        for edge in marks.sample(n * dt, dt):
            assert edge.rising != covered
            covered = edge.rising
        assert state == switch.active
        p = line.position
        if hysteresis == 0.0:
            assert state == (0.003 <= p < 0.007)
        # (a position exactly on a mark edge is decided by rounding: check only clear cases)
        bounds = [b for k in range(100) for b in (0.01 * k - 0.05, 0.01 * k - 0.047)]
        if min(abs(p - b) for b in bounds) > 1e-12:
            assert covered == any(0.01 * k - 0.05 <= p < 0.01 * k - 0.047 for k in range(100))


class _Pointer:
    """A bare position source (no traced motion): sensors interpolate it linearly."""

    def __init__(self, position: float) -> None:
        self.position = position


def test_switch_threshold_on_the_cycle_end_gives_one_edge_each_way():
    # Sensors solve only the thresholds inside the cycle's position range (sensors.py
    # Decision 1): a threshold exactly on the range's end must still give its edge, once.
    source = _Pointer(0.0)
    switch = ReferenceSwitch(source, position=0.5, width=1.0)
    seen = []
    for n, p in enumerate([0.25, 0.5, 0.5, 0.4, 0.5, 2.0]):
        source.position = p
        seen.append([(e.rising, e.fraction, e.position) for e in switch.sample(n * 0.001, 0.001)])
    assert seen == [[], [(True, 1.0, 0.5)], [], [(False, 0.0, 0.5)], [(True, 1.0, 0.5)], [(False, 2.0 / 3.0, 1.5)]]
    assert not switch.state


def test_mark_thresholds_on_the_cycle_ends_give_one_edge_each_way():
    source = _Pointer(0.0)
    sensor = PrintMarkSensor(source, PrintMarks(width=0.1, positions=[0.3]), sensor_position=0.2)
    seen = []
    for n, p in enumerate([0.5, 0.6, 0.6, 0.7, 0.8]):  # the mark covers the sensor in [0.5, 0.6)
        source.position = p
        seen.append([(e.rising, e.fraction, e.position, e.mark) for e in sensor.sample(n * 0.001, 0.001)])
    assert seen == [[(True, 1.0, 0.5, 0)], [(False, 1.0, 0.6, 0)], [], [], []]
    assert not sensor.state
