"""FS701 position loop and Adjust procedures (loop.py, decisions L1..L9; spec §2.4, §2.5, §5.3, E14..E17)."""

from __future__ import annotations

import pytest

from axisline.devices.fs701.cutter import CutterSettings, CutState
from axisline.devices.fs701.loop import (
    DAC_LIMIT_VOLTS,
    PositionLoop,
    cycle_test,
    direction_check,
    tune_gain,
    tune_offset,
)
from axisline.plant import IncrementalEncoder, ServoDrive

from .test_cutter_rig import CutterRig, demo_settings


def settings(**kw) -> CutterSettings:
    base = dict(pulses_cut_1000=2000, max_line_speed=600000, ana_out_gain_2=10.0, p_gain=1000)
    base.update(kw)
    return CutterSettings(**base)


def test_feed_forward_scaling_l1():
    """100 % feed-forward (Max. Line Speed) = Ana-Out Gain volts."""
    s = settings(ana_out_gain_2=8.0)
    loop = PositionLoop(s, 0.001, dac=False)
    assert loop.update(0.0, 10000.0, 0.0) == pytest.approx(8.0)  # 600000 LU/min = 10000 LU/s
    assert loop.update(0.0, 2500.0, 0.0) == pytest.approx(2.0)
    assert loop.feed_forward_value == pytest.approx(2.0)
    # the Adjust screenshot (§7.1): 120000 LU/min with 10.16 V gives 1.51 V at Max. Line Speed ~807000
    s2 = settings(ana_out_gain_2=10.16, max_line_speed=807000)
    assert PositionLoop(s2, 0.001, dac=False).update(0.0, 2000.0, 0.0) == pytest.approx(1.51, abs=0.005)


def test_a_setting_written_while_running_takes_effect_at_the_next_update():
    """Parameters written over the interface change the running loop: its constants (gain
    volts, Kv, offset, Max. Correction) follow every write of the settings."""
    s = settings(ana_out_gain_2=8.0, p_gain=1000)
    loop = PositionLoop(s, 0.001, dac=False)
    assert loop.update(0.0, 10000.0, 0.0) == pytest.approx(8.0)
    s.ana_out_gain_2 = 9.0
    assert s.v_max_line == pytest.approx(10000.0)
    assert loop.update(0.0, 10000.0, 0.0) == pytest.approx(9.0)
    s.max_line_speed = 1200000  # 20000 LU/s: the same speed is now half of the scale
    assert s.v_max_line == pytest.approx(20000.0)
    assert loop.update(0.0, 10000.0, 0.0) == pytest.approx(4.5)
    before = loop.update(1.0, 0.0, 0.0)
    s.p_gain = 2000
    assert loop.update(1.0, 0.0, 0.0) == pytest.approx(2.0 * before)
    s.pulses_cut_1000 = 4000
    assert s.cut_counts_per_lu == 4.0 and not s.ratio_error
    loop.update(1.0, 0.0, 0.0)
    assert loop.position_error == pytest.approx(4.0)  # 1 LU = 4 increments now


def test_p_gain_scaling_l2():
    """P-Gain/100 = Kv (1/s) with a matched gain: 1 LU of error asks for P/100 LU/s more."""
    s = settings(p_gain=2500)
    loop = PositionLoop(s, 0.001, dac=False)
    u = loop.update(1.0, 0.0, 0.0)  # 1 LU = 2 increments behind
    assert loop.position_error == pytest.approx(2.0)
    assert u == pytest.approx(loop.feed_forward(25.0))
    assert loop.kv(s.v_max_line / s.ana_out_gain_2) == pytest.approx(25.0)


def test_max_correction_limits_and_flags_l3():
    s = settings(p_gain=1000, max_correction=500)  # mV
    loop = PositionLoop(s, 0.001, dac=False)
    u = loop.update(1000.0, 0.0, 0.0)
    assert u == pytest.approx(0.5) and loop.at_max_correction
    assert loop.position_error == pytest.approx(2000.0)  # the error record goes on
    u = loop.update(-1000.0, 0.0, 0.0)
    assert u == pytest.approx(-0.5)
    loop.update(0.0, 0.0, 0.0)
    assert not loop.at_max_correction


def test_integral_doubles_a_constant_error_after_i_time_l4_and_is_clamped():
    s = settings(p_gain=1000, i_time=0.1, max_correction=9999)
    loop = PositionLoop(s, 0.001, dac=False)
    for _ in range(100):
        loop.update(0.01, 0.0, 0.0)
    assert loop.integral_value == pytest.approx(loop.correction_value, rel=1e-9)
    s.max_correction = 1  # 1 mV
    for _ in range(5000):
        loop.update(10.0, 0.0, 0.0)
    assert abs(loop.integral_value) <= 0.001 + 1e-12
    s.i_time = 0.0
    loop.update(0.0, 0.0, 0.0)
    assert loop.integral_value == 0.0


def test_e14_offset_is_a_fraction_of_full_scale_l5():
    """E14: Offset +2047 with gain 10.00 V and zero demand -> +10 V."""
    s = settings(ana_out_offset_2=2047)
    assert PositionLoop(s, 0.001).update(0.0, 0.0, 0.0) == pytest.approx(10.0)
    s.ana_out_offset_2 = -1024
    s.ana_out_gain_2 = 5.0
    assert PositionLoop(s, 0.001, dac=False).update(0.0, 0.0, 0.0) == pytest.approx(-1024 / 2047 * 5.0)


def test_output_is_clamped_to_10_volts_and_quantised_l8():
    s = settings()
    loop = PositionLoop(s, 0.001)
    assert loop.update(0.0, 30000.0, 0.0) == DAC_LIMIT_VOLTS and loop.saturated
    assert loop.update(0.0, -30000.0, 0.0) == -DAC_LIMIT_VOLTS
    u = loop.update(0.0, 1234.567, 0.0)
    step = 10.0 / 2048
    assert abs(u / step - round(u / step)) < 1e-9


def test_reset_diff_counter_opens_the_loop_l7():
    s = settings(i_time=0.05)
    loop = PositionLoop(s, 0.001, dac=False)
    u = loop.update(5.0, 100.0, 0.0, reset=True)
    assert loop.position_error == 0.0 and u == pytest.approx(loop.feed_forward(100.0))
    # released: the counter starts from zero (no jump), later errors count again
    u = loop.update(5.0, 100.0, 0.0)
    assert loop.position_error == 0.0 and u == pytest.approx(loop.feed_forward(100.0))
    loop.update(6.0, 100.0, 0.0)
    assert loop.position_error == pytest.approx(2.0)


def test_sync_mode_freezes_or_drops_the_correction_l6():
    s = settings(freeze_mode=2)
    loop = PositionLoop(s, 0.001, dac=False)
    loop.update(1.0, 0.0, 0.0)
    frozen = loop.correction_value
    u = loop.update(50.0, 0.0, 0.0, sync_mode=True)
    assert u == pytest.approx(frozen)
    s.freeze_mode = 1
    loop2 = PositionLoop(s, 0.001, dac=False)
    assert loop2.update(50.0, 100.0, 0.0, sync_mode=True) == pytest.approx(loop2.feed_forward(100.0))
    s.freeze_mode = 0
    assert loop2.update(50.0, 0.0, 0.0, sync_mode=True) == pytest.approx(loop2.p_volts_per_increment() * 100.0)


def test_cutter_applies_reset_diff_counter_and_sync_mode_inputs():
    rig = CutterRig(demo_settings(freeze_mode=1), line_speed=10000.0)
    rig.enable()
    rig.start()
    rig.cutter.inputs.sync_mode_enable = True
    seen = False
    for _ in range(2000):
        rig.step()
        if rig.cutter.cut_state is CutState.READY_TO_CUT:
            seen = True
            assert rig.cutter.loop.correction_value == 0.0
    assert seen
    rig.cutter.inputs.reset_diff_cou = True
    rig.run(0.01)
    assert rig.cutter.position_error == 0.0


# ---------------------------------------------------------------- Adjust program (§7)


def adjust_plant(s: CutterSettings, **drive):
    kw = dict(time_constant=0.003, velocity_per_volt=s.v_max_line / 10.0)
    kw.update(drive)
    d = ServoDrive(**kw)
    enc = IncrementalEncoder(d, s.cut_lines_per_lu, s.cut_multiplier)
    return d, (lambda: enc.sample())


def test_e15_adjust_speed_defaults_to_10_percent_of_max_line_speed():
    from axisline.devices.fs701.loop import _adjust_speed

    s = CutterSettings(max_line_speed=100000)
    assert _adjust_speed(s, None) == 10000
    assert s.p_gain == 1000 and s.ana_out_gain_2 == 10.0  # §7.1 starts: gain 1000 = 10.00 V


def test_e16_gain_tuning_centres_the_differential_counter():
    """E16 (§7.3): after tuning Ana-Out Gain 2 the counter swings within +-8 increments."""
    s = demo_settings()
    for factor in (0.9, 1.1):
        s.ana_out_gain_2 = 10.0
        drive, counts = adjust_plant(s, gain_factor=factor)
        r = tune_gain(s, 0.001, drive, counts)
        assert r.ok and max(abs(r.differential_min), abs(r.differential_max)) <= 8.0
        assert r.ana_out_gain_2 == pytest.approx(10.0 / factor, rel=0.01)
        assert s.ana_out_gain_2 == r.ana_out_gain_2 and s.i_time == 0.0


def test_offset_tuning_finds_the_drive_offset():
    s = demo_settings()
    drive, counts = adjust_plant(s, offset_volts=0.05)
    r = tune_offset(s, 0.001, drive, counts)
    assert r.ok and r.ana_out_offset_2 == pytest.approx(-0.05 / 10.0 * 2047, abs=2)


def test_direction_check_finds_polarity_and_counter_direction():
    s = demo_settings()
    drive, counts = adjust_plant(s)
    r = direction_check(s, 0.001, drive, counts)
    assert r.ok and r.carriage_forward and r.dir_counter_2 == s.dir_counter_2
    # counter wired backwards: the check says to toggle Dir. Counter 2
    d2 = ServoDrive(time_constant=0.003, velocity_per_volt=s.v_max_line / 10.0)
    enc = IncrementalEncoder(d2, s.cut_lines_per_lu, s.cut_multiplier, direction=-1)
    r = direction_check(s, 0.001, d2, lambda: enc.sample())
    assert r.ok and r.dir_counter_2 == 1 - s.dir_counter_2
    # analogue polarity reversed: the carriage moves backward
    d3, c3 = adjust_plant(s, gain_factor=-1.0)
    r = direction_check(s, 0.001, d3, c3)
    assert not r.ok and not r.carriage_forward


def test_cycle_test_reports_the_differential_counter_e17():
    s = demo_settings()
    drive, counts = adjust_plant(s)
    r = cycle_test(s, 0.001, drive, counts, cycles=2)
    assert r.ok and max(abs(r.differential_min), abs(r.differential_max)) <= 30.0
    slow, counts2 = adjust_plant(s, time_constant=0.05)  # a sluggish drive: larger swings
    r2 = cycle_test(s, 0.001, slow, counts2, cycles=2)
    assert max(abs(r2.differential_min), abs(r2.differential_max)) > max(abs(r.differential_min), abs(r.differential_max))
