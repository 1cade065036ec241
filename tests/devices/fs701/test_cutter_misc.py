"""FS701 cut cycle: gap function, jog / zero / software limits, monitoring outputs, virtual master
(spec §2.6..§2.8, §2.13, §2.15..§2.18; E8, E9, E21, E22; decisions C13..C16, C18, C21, C22)."""

from __future__ import annotations

import math

import pytest

from axisline.devices.fs701.cutter import CutState, CutterSettings, FS701Error

from .test_cutter_rig import CutterRig, SpeedChange, Tool


def mm(**kw) -> CutterSettings:
    base = dict(
        cutting_length=1000,
        pulses_line_1000=4000,
        pulses_cut_1000=4000,
        acceleration_1=5000,
        deceleration_1=5000,
        acceleration_2=8000,
        deceleration_2=8000,
        max_line_speed=100000,
        p_gain=3000,
        cut_window=8,
        home_window=5,
        return_speed=3.0,
    )
    base.update(kw)
    return CutterSettings(**base)


# ---------------------------------------------------------------- gap (C15, C16)


def gap_tool(rig: CutterRig, c: int, state: dict) -> None:
    """Start Gap 20 ms after Ready to Cut; Cut completed when the gap is completed."""
    cut = rig.cutter
    if cut.outputs.ready_to_cut and state.get("rtc") is None:
        state["rtc"] = c
    if state.get("rtc") is not None and c - state["rtc"] == 20:
        cut.inputs.start_gap = True
    if cut.outputs.gap_completed and not state.get("done"):
        state["done"] = True
        cut.inputs.cut_completed = True
    if not cut.outputs.ready_to_cut and state.get("done"):
        cut.inputs.start_gap = False
        cut.inputs.cut_completed = False
        state.clear()


def test_gap_moves_the_carriage_gap_length_ahead_of_the_material_c16():
    s = mm(gap_length=30, gap_time=100)
    rig = CutterRig(s, line_speed=1000.0, tool=Tool(enabled=False))
    st: dict = {}
    rig.hooks.append(lambda r, c: gap_tool(r, c, st))
    rig.enable()
    rig.start()
    assert rig.run_until(lambda r: r.cutter.cut_state is CutState.GAP, 3.0)
    c = rig.cutter
    x0 = c.set_point[0] - c.master.position  # carriage - material before the gap
    v_peak = 0.0
    while c.cut_state is CutState.GAP:
        rig.step()
        v_peak = max(v_peak, c.set_point[1] - c.master.velocity)
    assert c.cut_state is CutState.GAP_COMPLETED and c.outputs.gap_completed and c.outputs.ready_to_cut
    # Gap Time after Start Gap the carriage is Gap Length further ahead, synchronous again
    assert v_peak == pytest.approx(2 * 30 / 0.1, rel=0.02)
    assert c.set_point[0] - c.master.position == pytest.approx(x0 + 30.0, abs=0.3)
    assert c.set_point[1] == pytest.approx(c.master.velocity)
    rig.run(3.0)
    assert len(c.cut_log) >= 2 and c.errors == 0


def test_cut_completed_during_the_gap_waits_for_its_end_c15():
    s = mm(gap_length=30, gap_time=200)
    rig = CutterRig(s, line_speed=1000.0, tool=Tool(enabled=False))
    rig.enable()
    rig.start()
    c = rig.cutter
    assert rig.run_until(lambda r: r.cutter.outputs.ready_to_cut, 3.0)
    c.inputs.start_gap = True
    rig.run(0.05)
    assert c.cut_state is CutState.GAP
    c.inputs.cut_completed = True  # early
    rig.run(0.1)
    assert c.cut_state is CutState.GAP and c.outputs.ready_to_cut and not c.outputs.gap_completed
    assert rig.run_until(lambda r: r.cutter.cut_state in (CutState.DECELERATION, CutState.RETURN), 0.2)
    assert rig.cycle * rig.period > 0  # returned only after the gap


def test_gap_is_unused_with_gap_length_0():
    rig = CutterRig(mm(gap_length=0), line_speed=1000.0, tool=Tool(enabled=False))
    rig.enable()
    rig.start()
    assert rig.run_until(lambda r: r.cutter.outputs.ready_to_cut, 3.0)
    rig.cutter.inputs.start_gap = True
    rig.run(0.3)
    assert rig.cutter.cut_state is CutState.READY_TO_CUT


# ---------------------------------------------------------------- jog, zero, limits (E8, E22, C13, C14)


def test_e22_jog_speed_and_ramp():
    """E22: Jog Speed Forw. 10 % of 100000 LU/min, ramp 1 s -> 10000 LU/min reached in 0.1 s."""
    s = CutterSettings(max_line_speed=100000, jog_speed_forw=10, jog_ramp_up_forw=1)
    v, a, d = s.jog(True, 0.001)
    assert v * 60 == pytest.approx(10000) and a == pytest.approx(1666.6667, rel=1e-4)
    rig = CutterRig(mm())
    rig.enable()
    rig.cutter.inputs.jog_forward = True
    rig.run(0.1)
    assert rig.cutter.set_point[1] == pytest.approx(10000 / 60, rel=1e-6)
    rig.run(0.05)
    assert rig.cutter.cut_state is CutState.JOG
    # ramp 0 s: a one-cycle step (C14)
    s0 = CutterSettings(max_line_speed=100000, jog_ramp_up_rev=0)
    assert s0.jog(False, 0.001)[1] == pytest.approx(100000 / 60 / 0.001)


def test_e8_jog_stops_at_the_software_limits_in_stop():
    """E8 (§4.3.3): Min -20, Max +2500, Alarm 2000; Stop: jog stops at +2500 and at -20."""
    s = mm(minimum_position=-20, maximum_position=2500, alarm_position=2000, jog_speed_forw=100, jog_speed_rev=100)
    rig = CutterRig(s)
    rig.enable()
    c = rig.cutter
    c.inputs.jog_forward = True
    rig.run(2.5)
    assert c.set_point[0] == pytest.approx(2500.0) and c.set_point[1] == 0.0
    assert not c.outputs.alarm and c.errors == 0  # Alarm is for automatic operation
    c.inputs.jog_forward = False
    rig.run(0.3)
    assert c.home_position == pytest.approx(2500.0)  # the new home after a jog
    c.inputs.jog_reverse = True
    rig.run(3.0)
    assert c.set_point[0] == pytest.approx(-20.0)
    c.inputs.jog_reverse = False
    rig.run(0.3)
    assert c.cut_state is CutState.HOME and c.errors == 0


def test_e8_automatic_alarm_at_alarm_position_and_no_max_limit():
    """E8: Start/Stop HIGH: Alarm HIGH beyond 2000, no error, the carriage runs on beyond 2500."""
    s = mm(minimum_position=-20, maximum_position=2500, alarm_position=2000, cutting_length=500)
    rig = CutterRig(s, line_speed=1000.0, tool=Tool(enabled=False))
    rig.enable()
    rig.start()
    c = rig.cutter
    assert rig.run_until(lambda r: r.cutter.carriage_abs_pos / s.cut_counts_per_lu >= 2000.5, 5.0)
    assert c.outputs.alarm and c.errors == 0
    rig.run(1.0)
    assert c.carriage_abs_pos / s.cut_counts_per_lu > 2600 and c.errors == 0 and c.outputs.alarm


def test_e8_automatic_min_position_is_error_03():
    s = mm(minimum_position=-20)
    rig = CutterRig(s, line_speed=0.0)
    rig.enable()
    rig.start()
    rig.run(0.05)
    c = rig.cutter
    assert c.errors == 0
    rig.drive.velocity_error = 2000.0  # a load pushes the carriage back
    rig.run_until(lambda r: r.cutter.errors != 0, 0.5)
    assert c.error_active(FS701Error.LIMIT_SWITCH) and c.outputs.error


def test_set_zero_position_holds_the_counter_and_lifts_the_limits_c13():
    s = mm(minimum_position=-20, maximum_position=100, jog_speed_forw=100)
    rig = CutterRig(s)
    rig.enable()
    c = rig.cutter
    c.inputs.set_zero_pos = True
    c.inputs.jog_forward = True
    rig.run(0.5)
    assert c.set_point[0] > 150.0  # beyond Max: the counter is held at zero
    assert abs(c.carriage_abs_pos) <= 40  # (one cycle of travel behind)
    c.inputs.jog_forward = False
    rig.run(0.5)
    c.inputs.set_zero_pos = False
    rig.run(0.01)
    z = c.zero
    assert abs(c.carriage_abs_pos) <= 1 and z == pytest.approx(rig.axis.actual_position, abs=0.5)
    c.inputs.jog_forward = True
    rig.run(0.5)
    assert c.set_point[0] == pytest.approx(z + 100.0)  # Max now refers to the new Zero


# ---------------------------------------------------------------- monitoring outputs


def test_e9_length_pulses_one_per_length_per_pulse_duty_1_to_1_c21():
    """E9 (§4.3.4): 1000 mm per pulse, 10000 mm of line -> 10 pulses, high 500 / low 500."""
    s = mm(length_per_pulse=1000)
    rig = CutterRig(s, line_speed=2000.0)
    rig.enable()
    rises = 0
    high = 0
    prev = rig.cutter.outputs.length_pulses
    for _ in range(5000):  # 10000 mm at 2000 mm/s
        rig.step()
        o = rig.cutter.outputs.length_pulses
        if o and not prev:
            rises += 1
        high += o
        prev = o
    assert rises == 10
    assert high == pytest.approx(2500, abs=3)  # half of the time


def test_master_reverse_output_c22():
    s = mm(master_rev_limit=50)
    prof = [SpeedChange(0.0, 1000.0), SpeedChange(0.2, -500.0), SpeedChange(0.35, 500.0)]
    rig = CutterRig(s, line=prof)
    rig.enable()
    c = rig.cutter
    seen = False
    for _ in range(350):
        rig.step()
        seen |= c.outputs.master_reverse
    assert seen and c.outputs.master_reverse  # 75 LU back > 50
    rig.run(0.2)  # forward again past the peak
    assert not c.outputs.master_reverse
    # Clear Error resets it as well
    prof2 = [SpeedChange(0.0, -1000.0)]
    rig2 = CutterRig(s, line=prof2)
    rig2.enable()
    rig2.run(0.1)
    assert rig2.cutter.outputs.master_reverse
    rig2.cutter.inputs.clear_error = True
    rig2.run(0.001)
    assert not rig2.cutter.outputs.master_reverse
    rig3 = CutterRig(mm(master_rev_limit=0), line=prof2)
    rig3.enable()
    rig3.run(0.3)
    assert not rig3.cutter.outputs.master_reverse  # 0 disables


def test_motion_detection_outputs():
    s = mm(zero_speed_master=30000, zero_speed_vir_ma=5000, virtual_line_speed=6000, ramp_vir_master=0, sampling_time=20)
    rig = CutterRig(s, line_speed=400.0)  # 24000 LU/min
    rig.enable()
    assert not rig.cutter.outputs.master_in_motion
    rig.material.set_speed(600.0)  # 36000 LU/min
    rig.run(0.03)
    assert rig.cutter.outputs.master_in_motion
    assert not rig.cutter.outputs.vir_m_in_motion
    rig.cutter.inputs.run_virt_master = True
    rig.run(0.01)
    assert rig.cutter.outputs.vir_m_in_motion


# ---------------------------------------------------------------- virtual master (C18, E21)


def test_e21_virtual_line_speed_resolution():
    s = CutterSettings(max_line_speed=204800, virtual_line_speed=1050)
    assert s.virtual_speed_effective() == 1000.0  # floor to the 1/2048 step (C18)
    s.virtual_line_speed = 300000  # limited to Max. Line Speed
    assert s.virtual_speed_effective() == 204800.0


def test_virtual_master_runs_the_cut_cycle_without_material():
    """§7.5: Select Virtual Master in Stop, Run Virt. Master; the carriage cuts at the virtual line."""
    s = mm(virtual_line_speed=60000, ramp_vir_master=1, cutting_length=1000)
    rig = CutterRig(s, line_speed=0.0)
    rig.enable()
    c = rig.cutter
    c.inputs.select_vir_master = True
    c.inputs.run_virt_master = True
    rig.run(0.8)
    assert c.line_speed == pytest.approx(s.virtual_speed_effective(), rel=1e-9)  # 59960.9 (1/2048 steps)
    c.inputs.immediate_cut = True
    rig.run(0.5)
    c.inputs.immediate_cut = False
    assert len(c.cut_log) == 1
    c.inputs.start_stop = True
    c.inputs.select_vir_master = False  # ignored in Start
    rig.run(4.0)
    assert len(c.cut_log) >= 4 and c.errors == 0 and c.master.use_virtual
    c.inputs.run_virt_master = False
    rig.run(2.0)
    assert c.line_speed == 0.0


@pytest.mark.parametrize("standstill", [0.0, 0.3, 1.7])
def test_the_virtual_master_ramps_from_the_cycle_it_is_started_after_any_standstill(standstill):
    """A stopped virtual master is not re-sampled every cycle; started again, its ramp begins
    at that cycle: the travel after Run Virt. Master does not depend on how long it stood."""
    s = mm(virtual_line_speed=60000, ramp_vir_master=1)
    rig = CutterRig(s, line_speed=0.0)
    c = rig.cutter
    c.inputs.select_vir_master = True
    rig.run(0.05 + standstill)
    assert c.master.velocity == 0.0
    start = c.master.position
    c.inputs.run_virt_master = True
    rig.run(0.5)
    v = s.virtual_speed_effective() / 60.0
    a = s.v_max_line / s.ramp_vir_master
    expected = 0.5 * a * 0.5**2 if a * 0.5 < v else v * 0.5 - v * v / (2 * a)
    assert c.master.position - start == pytest.approx(expected, abs=2.0 / s.line_counts_per_lu)
    c.inputs.run_virt_master = False  # and stopped, then started again
    rig.run(1.5)
    assert c.master.velocity == 0.0
    again = c.master.position
    c.inputs.run_virt_master = True
    rig.run(0.5)
    assert c.master.position - again == pytest.approx(expected, abs=2.0 / s.line_counts_per_lu)


def test_select_virtual_master_switch_keeps_the_length_counter():
    s = mm(virtual_line_speed=30000, ramp_vir_master=0)
    rig = CutterRig(s, line_speed=500.0)
    rig.enable()
    rig.run(0.2)
    c = rig.cutter
    n0 = c.length_counter
    c.inputs.select_vir_master = True
    rig.run(0.001)
    assert c.length_counter == pytest.approx(n0, abs=4)  # no jump when the source changes
    rig.run(0.2)
    assert c.length_counter == pytest.approx(n0, abs=4)  # virtual master stands (not running)
    assert not math.isnan(c.line_speed)
