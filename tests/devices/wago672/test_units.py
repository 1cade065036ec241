"""Scaling, number ranges and units: every worked example of wago.md §6 / §9.1-9.6 (manual §3.10.1, §3.10.6, §4.1)."""

from __future__ import annotations

import math

import pytest

from axisline.devices.wago672.errors import WagoError
from axisline.devices.wago672.thermal import OvercurrentModel, phase_current, t_cool, t_off
from axisline.devices.wago672.units import (
    Scaling,
    acc_multiplier,
    acceleration,
    f_max,
    freq_prescaler,
    full_steps,
    mechanical_speed,
    mechanical_speed_direct,
    pulse_frequency,
    rotary_speed_limit,
    rotor_angle,
    rpm,
    step_angle,
    time_to_f_max,
    to_internal,
    to_user,
)


def test_9_1_frequency_prescaler_table():
    """wago.md §9.1 (manual §3.10.1.1): Freq_Range_Sel -> Freq_Prescaler -> f_p,max."""
    assert freq_prescaler(0, 0) == 200 and f_max(200) == 10_000
    assert freq_prescaler(0, 40) == 40 and f_max(40) == 50_000
    assert freq_prescaler(0, 4) == 4 and f_max(4) == 500_000
    assert (freq_prescaler(1, 40), f_max(80)) == (80, 25_000)
    assert (freq_prescaler(2, 40), f_max(20)) == (20, 100_000)
    assert (freq_prescaler(3, 40), f_max(4)) == (4, 500_000)
    # f_p,max = 25000 * 80 / Freq_Prescaler
    for sel, fp in ((0, 200), (1, 80), (2, 20), (3, 4)):
        assert pulse_frequency(25000, freq_prescaler(sel, 0)) == pytest.approx(f_max(fp))


def test_9_1_prescaler_80_gives_velocity_in_hz_and_7812_hz_full_step():
    """wago.md §9.1: "pulse frequency in [Hz] ... Freq_Prescaler = 80"; 500 kHz / 64 = 7812.5 Hz full step."""
    for v in (1, 333, 25000):
        assert pulse_frequency(v, 80) == v
    assert math.floor(f_max(4) / 64) == 7812


def test_9_2_acceleration_factor_table_and_periods():
    """wago.md §9.2 (manual §3.10.1.2): Acc_Multiplier and T to f_max at 32767 = 25000*80/(32767*Acc_Multiplier)."""
    assert acc_multiplier(0, 0) == 8 and time_to_f_max(8) == pytest.approx(7.6296, abs=1e-4)  # "7600 ms"
    assert acc_multiplier(1, 0) == 80 and time_to_f_max(80) == pytest.approx(0.7630, abs=1e-4)  # "760 ms"
    assert acc_multiplier(2, 0) == 800 and time_to_f_max(800) == pytest.approx(0.07630, abs=1e-5)  # "76 ms"
    # '11': 7.6 ms (the manual's "0.2 ms" in §3.10.1.2 is the misprint wago.md §9.2 shows)
    assert acc_multiplier(3, 0) == 8000 and time_to_f_max(8000) == pytest.approx(0.00763, abs=1e-5)
    assert acc_multiplier(0, 1000) == 1000 and time_to_f_max(1000) == pytest.approx(0.0610, abs=1e-4)
    # the period is independent of the prescaler: f_max / a
    for fp in (4, 40, 80, 200):
        assert f_max(fp) / acceleration(32767, fp, 80) == pytest.approx(time_to_f_max(80))


def test_9_2_acceleration_in_hz_per_s_when_multiplier_equals_prescaler_and_default_values():
    """wago.md §9.2: a = Acceleration * Acc_Multiplier / Freq_Prescaler; §4.6 defaults give 25000 and 6000."""
    assert acceleration(1234, 80, 80) == 1234
    assert acceleration(1000, 40, 1000) == 25000  # Acceleration_RampUp 1000 -> 25000 microsteps/s^2
    assert pulse_frequency(3000, 40) == 6000  # Speed 3000 -> 6000 microsteps/s
    assert pulse_frequency(3000, 200) == 1200  # with the alternative default Freq_Div 200


def test_9_3_speed_and_mechanical_rotation():
    """wago.md §9.3 (manual §3.10.6.1.4, §4.1.2): v = 25000 at prescaler 80, p = 50."""
    f_p = pulse_frequency(25000, 80)
    assert f_p == 25000
    assert mechanical_speed(f_p, 50) == pytest.approx(1.953125)
    assert mechanical_speed_direct(25000, 80, 50) == pytest.approx(1.953125)  # 3.2, not the misprinted 3,3
    assert 25000 / (50 * 3.3 * 80) == pytest.approx(1.894, abs=1e-3)  # what 3,3 would give
    assert rpm(mechanical_speed(f_p)) == pytest.approx(117.1875)


def test_9_3_rotor_angle_and_motor_geometry():
    """wago.md §9.3 (manual §3.10.6.1.2, §4.1.1): phi = 360 * s / (64 N); alpha 1.8 -> N 200, p 50."""
    assert rotor_angle(12800, 200) == pytest.approx(360.0)
    assert rotor_angle(3200, 200) == pytest.approx(90.0)
    assert rotor_angle(64, 200) == pytest.approx(1.8)
    assert full_steps(1.8) == pytest.approx(200)
    assert step_angle(50) == pytest.approx(1.8)


def test_9_4_position_scaling_micrometres_and_millimetres():
    """wago.md §9.4 (manual §3.10.6.2.1): a microstep is 0.12 mm; um with 1/120, mm with 25/3."""
    um = Scaling(pos_mult=1, pos_div=120)
    assert um.steps(1200) == 10 and um.steps(120) == 1 and um.position(10) == 1200
    mm = Scaling(pos_mult=25, pos_div=3)
    assert mm.steps(3) == 25 and mm.steps(12) == 100 and mm.position(100) == 12


def test_6_2_truncation_toward_zero_and_range_errors():
    """wago.md §6.2: integer arithmetic, truncation toward zero; 1511..1517 outside the ranges."""
    assert to_internal(-7, 1, 2) == -3 and to_internal(7, 1, 2) == 3 and to_user(-5, 2, 1) == -2
    with pytest.raises(WagoError) as exc:
        Scaling(pos_mult=2).steps(5_000_000)
    assert exc.value.code == 1511
    with pytest.raises(WagoError) as exc:
        Scaling(pos_div=2).position(8_000_000)
    assert exc.value.code == 1512
    with pytest.raises(WagoError) as exc:
        Scaling(speed_mult=2).frequency(20000)
    assert exc.value.code == 1513
    with pytest.raises(WagoError) as exc:
        Scaling(acc_mult=4).accel(10000)
    assert exc.value.code == 1515
    with pytest.raises(WagoError) as exc:
        to_internal(1, 1, 0)
    assert exc.value.code == 1517


def test_9_5_rotary_speed_restriction():
    """wago.md §9.5 (manual §3.11.1.8): v <= (Speed_Div/Speed_Mult)(Freq_Div/80) 10^3 p."""
    assert rotary_speed_limit(10, 80) == pytest.approx(10000)
    assert rotary_speed_limit(12800, 80) == pytest.approx(12_800_000)
    # i.e. f_p <= 1000 * p: no more than one period per 1 ms tick
    assert pulse_frequency(rotary_speed_limit(10, 80), 80) == pytest.approx(1000 * 10)


def test_9_6_thermal_model_times():
    """wago.md §9.6 (manual §4.1.4.3): t_off = 5 A/(I - 5 A) * 5 s; t_cool = 4 (I - 5)/(5 - I_re) t_OV."""
    assert t_off(7.5) == pytest.approx(10.0) and t_off(6.0) == pytest.approx(25.0) and t_off(5.5) == pytest.approx(50.0)
    assert t_cool(7.5, 2.5, 10.0) == pytest.approx(40.0)
    assert t_cool(6.0, 1.65, 10.0) == pytest.approx(11.94, abs=0.01)
    # the default currents: 5.0 A rated, standstill 33 % -> 1.65 A, stop 150 % -> 7.5 A (wago.md §2.8)
    assert phase_current(50, 33) == pytest.approx(1.65) and phase_current(50, 150) == pytest.approx(7.5)


@pytest.mark.parametrize("current, seconds", [(7.5, 10.0), (6.0, 25.0), (5.5, 50.0)])
def test_9_6_integrator_trips_after_t_off_and_cools_in_t_cool(current, seconds):
    m = OvercurrentModel()
    dt = 0.001
    n = 0
    while not m.step(current, dt):
        n += 1
    assert n * dt == pytest.approx(seconds, abs=2e-3)
    assert m.state_variable == 255
    # cooling at I_re = 2.5 A for t_cool brings the model back to its original state
    m2 = OvercurrentModel()
    for _ in range(5000):
        m2.step(current, dt)
    cool = t_cool(current, 2.5, 5.0)
    for _ in range(int(round(cool / dt)) - 2):
        m2.step(2.5, dt)
    assert m2.load > 0.0
    for _ in range(4):
        m2.step(2.5, dt)
    assert m2.load == 0.0
