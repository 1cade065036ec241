"""Servo and stepper drive models: the behaviour the position loop relies on."""

from __future__ import annotations

import math

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from axisline.plant import Drive, ServoDrive, StepperDrive

TAU = 0.01


def run_servo(dt: float, until: float, **kwargs) -> list[tuple[float, float, float]]:
    """(time, position, velocity) after every step of a 100 units/s step command."""
    drive = ServoDrive(enabled=True, **kwargs)
    drive.command_velocity(100.0)
    out = []
    for n in range(1, round(until / dt) + 1):
        drive.step(dt)
        out.append((n * dt, drive.position, drive.velocity))
    return out


def test_first_order_step_response_is_the_analytic_curve():
    for t, x, v in run_servo(0.001, 0.05, time_constant=TAU)[4::5]:
        assert v == pytest.approx(100.0 * (1.0 - math.exp(-t / TAU)), abs=1e-9)
        assert x == pytest.approx(100.0 * (t - TAU * (1.0 - math.exp(-t / TAU))), abs=1e-9)


def test_first_order_response_does_not_depend_on_the_cycle_period():
    coarse = run_servo(0.001, 0.04, time_constant=TAU)
    fine = run_servo(0.00025, 0.04, time_constant=TAU)[3::4]
    assert len(coarse) == len(fine)
    for (t1, x1, v1), (t2, x2, v2) in zip(coarse, fine):
        assert t1 == pytest.approx(t2)
        assert x1 == pytest.approx(x2, abs=1e-10)
        assert v1 == pytest.approx(v2, abs=1e-10)


def test_second_order_response_does_not_depend_on_the_cycle_period_even_when_ramping():
    kwargs = dict(loop="second_order", natural_frequency=300.0, damping=0.4, max_acceleration=4000.0)
    coarse = run_servo(0.002, 0.06, **kwargs)
    fine = run_servo(0.00025, 0.06, **kwargs)[7::8]
    for (_, x1, v1), (_, x2, v2) in zip(coarse, fine):
        assert x1 == pytest.approx(x2, abs=1e-9)
        assert v1 == pytest.approx(v2, abs=1e-9)


def test_second_order_settles_on_the_command_with_its_damped_overshoot():
    wn, zeta = 300.0, 0.4
    samples = run_servo(0.0005, 0.2, loop="second_order", natural_frequency=wn, damping=zeta)
    peak = max(v for _, _, v in samples)
    overshoot = math.exp(-zeta * math.pi / math.sqrt(1.0 - zeta * zeta))
    assert peak == pytest.approx(100.0 * (1.0 + overshoot), rel=1e-3)
    assert samples[-1][2] == pytest.approx(100.0, abs=1e-6)


def test_acceleration_limit_ramps_the_first_order_loop_and_is_never_exceeded():
    drive = ServoDrive(enabled=True, time_constant=0.005, max_acceleration=2000.0, max_velocity=50.0)
    drive.command_velocity(80.0)  # above the speed limit too
    for _ in range(200):
        drive.step(0.001)
        assert abs(drive.acceleration) <= 2000.0 + 1e-9
        assert drive.velocity <= 50.0 + 1e-9
    assert drive.velocity == pytest.approx(50.0, abs=1e-6)


def test_analog_command_is_clamped_at_plus_minus_10_volts():
    drive = ServoDrive(enabled=True, velocity_per_volt=20.0, time_constant=0.001)
    assert drive.command_voltage(12.5) == 10.0
    assert drive.saturated
    assert drive.commanded_velocity == 200.0
    assert drive.command_voltage(-30.0) == -10.0
    assert drive.commanded_velocity == -200.0
    assert drive.command_voltage(4.0) == 4.0
    assert not drive.saturated
    for _ in range(100):
        drive.step(0.001)
    assert drive.velocity == pytest.approx(80.0, abs=1e-9)


def test_analog_offset_drift_and_gain_error_reach_the_motor():
    drive = ServoDrive(
        enabled=True, velocity_per_volt=10.0, offset_volts=0.05, gain_factor=1.1,
        drift_volts_per_second=0.01,
    )
    drive.command_voltage(0.0)
    assert drive.commanded_velocity == pytest.approx(10.0 * 1.1 * 0.05)
    for _ in range(1000):
        drive.step(0.001)
    assert drive.commanded_velocity == pytest.approx(10.0 * 1.1 * (0.05 + 0.01 * 1.0))
    drive.command_velocity(3.0)  # the digital path is ideal
    assert drive.commanded_velocity == 3.0


def test_disabled_servo_ignores_the_command_and_coasts_down_exponentially():
    drive = ServoDrive(enabled=True, time_constant=0.001, coast_time_constant=0.05)
    drive.command_velocity(100.0)
    for _ in range(50):
        drive.step(0.001)
    v0, x0 = drive.velocity, drive.position
    drive.enable(False)
    for _ in range(100):
        drive.step(0.001)
    assert drive.velocity == pytest.approx(v0 * math.exp(-0.1 / 0.05), rel=1e-12)
    assert drive.position == pytest.approx(x0 + v0 * 0.05 * (1 - math.exp(-0.1 / 0.05)), rel=1e-12)


def test_disabled_servo_with_zero_coast_time_stops_at_once():
    drive = ServoDrive(enabled=True, coast_time_constant=0.0)
    drive.command_velocity(10.0)
    drive.step(0.001)
    drive.enable(False)
    x = drive.position
    drive.step(0.001)
    assert (drive.velocity, drive.position) == (0.0, x)


def test_servo_position_inside_the_cycle_is_exact():
    drive = ServoDrive(enabled=True, time_constant=TAU)
    drive.command_velocity(100.0)
    drive.step(0.004)
    for f in (0.25, 0.5, 0.9):
        t = f * 0.004
        assert drive.position_at(f) == pytest.approx(100 * (t - TAU * (1 - math.exp(-t / TAU))))
    ((fraction, direction),) = drive.crossings(drive.position_at(0.3))
    assert fraction == pytest.approx(0.3, abs=1e-12) and direction == 1


def test_stepper_follows_the_commanded_microsteps():
    stepper = StepperDrive(steps_per_unit=40.0, microsteps=16, max_step_frequency=4e6, enabled=True)
    assert stepper.command_position(2.5) == 2.5 * 40 * 16
    stepper.step(0.001)
    assert stepper.position_microsteps == 1600
    assert stepper.position == 2.5
    assert stepper.position_steps == 100.0
    assert stepper.velocity == pytest.approx(2500.0)
    stepper.command_microsteps(1590)
    stepper.step(0.001)
    assert stepper.position_microsteps == 1590


def test_stepper_respects_its_maximum_step_frequency():
    stepper = StepperDrive(steps_per_unit=1.0, microsteps=1, max_step_frequency=2500.0, enabled=True)
    stepper.command_microsteps(100)
    counts = []
    for _ in range(16):  # 0.25 ms cycles: 0.625 pulses each
        stepper.step(0.00025)
        counts.append(stepper.position_microsteps)
    assert counts[-1] == 10  # 2500 Hz * 4 ms
    assert all(b - a in (0, 1) for a, b in zip([0] + counts, counts))


@settings(max_examples=40, deadline=None)
@given(
    targets=st.lists(st.integers(-5000, 5000), min_size=1, max_size=30),
    dt=st.sampled_from([0.00025, 0.001, 0.004]),
    freq=st.floats(100.0, 1e6),
)
def test_stepper_never_outruns_its_pulse_input(targets, dt, freq):
    stepper = StepperDrive(steps_per_unit=1.0, microsteps=8, max_step_frequency=freq, enabled=True)
    elapsed, pulses = 0.0, 0
    for target in targets:
        stepper.command_microsteps(target)
        before = stepper.position_microsteps
        stepper.step(dt)
        elapsed += dt
        moved = stepper.position_microsteps - before
        pulses += abs(moved)
        # never past the target, never faster than the input allows (over the whole run)
        assert abs(target - stepper.position_microsteps) <= abs(target - before)
        assert pulses <= freq * elapsed + 1e-6


def test_disabled_stepper_loses_the_pulses_sent_meanwhile():
    stepper = StepperDrive(steps_per_unit=1.0, microsteps=1, enabled=False)
    stepper.command_microsteps(50)
    stepper.step(0.001)
    assert stepper.position_microsteps == 0
    stepper.enable(True)
    stepper.command_microsteps(60)
    stepper.step(0.001)
    assert stepper.position_microsteps == 10


def test_both_drives_present_the_same_interface():
    for drive in (ServoDrive(), StepperDrive(steps_per_unit=1.0)):
        assert isinstance(drive, Drive)
        drive.enable(True)
        drive.step(0.001)
        assert isinstance(drive.position + drive.velocity + drive.acceleration, float)
