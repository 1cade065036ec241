"""FS701 cut cycle, length mode (Cutting Mode 1): spec §2.3, worked examples §7 (E2..E7, E19, E25).

Decision numbers (C1..C23) refer to the Decisions list in axisline/devices/fs701/cutter.py.
"""

from __future__ import annotations

import pytest

from axisline.devices.fs701.cutter import (
    ControlState,
    CutKind,
    CutState,
    CutterSettings,
    FS701Error,
    S_RAMP_PEAK_FACTOR,
    s_ramp_limits,
)
from axisline.motion.profiles import plan_velocity, State

from .test_cutter_rig import CutterRig, Tool, demo_settings


def mm_settings(**kw) -> CutterSettings:
    """LU = 1 mm, 1 increment per mm on both encoders (the manual's examples)."""
    base = dict(
        cutting_length=1000,
        pulses_line_1000=4000,
        pulses_cut_1000=4000,
        acceleration_1=5000,
        acceleration_2=8000,
        deceleration_1=5000,
        deceleration_2=8000,
        max_line_speed=100000,
        p_gain=3000,
        cut_window=8,
        home_window=5,
        return_speed=3.0,
    )
    base.update(kw)
    return CutterSettings(**base)


def running_rig(settings: CutterSettings, speed: float, **kw) -> CutterRig:
    rig = CutterRig(settings, line_speed=speed, **kw)
    rig.enable()
    rig.start()
    return rig


# ---------------------------------------------------------------- settings and scaling


def test_settings_use_the_manual_names_units_and_defaults():
    s = CutterSettings()
    # §11 table defaults (Deceleration 1 and Printm. per Length from the text: shifted table rows)
    assert (s.cutting_length, s.test_cut_length, s.virtual_line_speed) == (1000, 1000, 10000)
    assert (s.pulses_line_1000, s.pulses_cut_1000, s.acceleration_1, s.acceleration_2) == (1000, 1000, 1000, 1000)
    assert (s.ramp_form, s.sync_rate, s.return_speed, s.edge_sense, s.synchron_time) == (0, 0.0, 1.0, 0, 1)
    assert (s.cut_window, s.sync_samples, s.tool_width, s.cutting_mode, s.photocell_cut) == (50, 1, 0, 1, 1000)
    assert (s.deceleration_1, s.deceleration_2, s.printm_per_length) == (1000, 1000, 1)
    assert (s.p_gain, s.i_time, s.max_correction, s.max_line_speed, s.sampling_time) == (1000, 0.0, 9999, 100000, 1)
    assert (s.home_window, s.minimum_position, s.maximum_position, s.alarm_position) == (100, -999999, 999999, 999999)
    assert s.ana_out_gain_2 == 10.0 and s.ana_out_offset_2 == 0


def test_from_parameters_by_name_with_text_aliases_and_raw_gain():
    class Params:
        cutting_length = 2500
        rel_return_speed = 2.5  # the text name of "Return Speed"
        sync_mode = 1  # the text name of "Freeze Mode"
        ana_out_gain_2 = 1016  # raw register: 10.16 V

    s = CutterSettings.from_parameters(Params())
    assert s.cutting_length == 2500 and s.return_speed == 2.5 and s.freeze_mode == 1
    assert s.ana_out_gain_2 == pytest.approx(10.16)
    s2 = CutterSettings.from_parameters({"tool_width": 3, "pulses_line_1000": 2000}, cutting_length=7)
    assert (s2.tool_width, s2.pulses_line_1000, s2.cutting_length) == (3, 2000, 7)


def test_lu_count_conversions_follow_pulses_per_1000_lu_c20():
    s = CutterSettings(pulses_line_1000=4096, pulses_cut_1000=2000, mode_counter_1=2, mode_counter_2=1)
    assert s.line_counts_per_lu == pytest.approx(4.096)
    assert s.lu_to_line_counts(1000) == pytest.approx(4096)
    assert s.cut_counts_to_lu(2000) == pytest.approx(1000)
    assert s.line_lines_per_lu == pytest.approx(4.096 / 4)  # x4: four counts per line
    assert s.cut_lines_per_lu == pytest.approx(2.0 / 2)


def test_e12_ratio_rule_error_05():
    """E12 (§2.3): beyond 16:1 / 1:16 is Error 05; 16:1 itself is allowed."""
    assert CutterSettings(pulses_line_1000=17000, pulses_cut_1000=1000).ratio_error
    assert not CutterSettings(pulses_line_1000=16000, pulses_cut_1000=1000).ratio_error
    assert CutterSettings(pulses_line_1000=1000, pulses_cut_1000=16001).ratio_error
    rig = CutterRig(mm_settings(pulses_line_1000=17000, pulses_cut_1000=1000))
    rig.enable()
    assert rig.cutter.error_active(FS701Error.VALUE_RANGE) and rig.cutter.outputs.error
    rig.cutter.inputs.clear_error = True
    rig.run(0.002)
    assert rig.cutter.error_active(FS701Error.VALUE_RANGE)  # comes back: cause not eliminated


# ---------------------------------------------------------------- ramps and anticipation (E2, E3)


def test_e2_ramp_time_and_anticipation_distance():
    """E2 (§4.3.1): 5000 mm/s^2 reaches 300 m/min in 1 s, 30 m/min in 100 ms; anticipation v^2/2a."""
    for form in (0, 1):  # the S-ramp lasts as long as the linear one (C1)
        rig = CutterRig(mm_settings(ramp_form=form))
        c = rig.cutter
        assert c.anticipation(30000 / 60) == pytest.approx(25.0)
        assert c.anticipation(300000 / 60) == pytest.approx(2500.0)
        prof, tau_a, s_sync, dm = c._approach_geometry(500.0)
        assert tau_a == pytest.approx(0.100, abs=1e-9)
        assert s_sync == pytest.approx(25.0)
        prof, tau_a, *_ = c._approach_geometry(5000.0)
        assert tau_a == pytest.approx(1.0, abs=1e-9)


def test_e2_simulated_approach_lasts_v_over_a_and_starts_at_the_anticipation_point():
    s = mm_settings(ramp_form=1)
    rig = running_rig(s, 500.0)  # 30 m/min
    c = rig.cutter
    assert rig.run_until(lambda r: r.cutter.cut_state is CutState.ACCELERATION, 5.0)
    start_cycle, start_len = rig.cycle, c.length_counter / s.line_counts_per_lu
    assert start_len == pytest.approx(1000 - 25, abs=0.6)  # L - v^2/2a
    assert rig.run_until(lambda r: r.cutter.cut_state is not CutState.ACCELERATION, 1.0)
    assert (rig.cycle - start_cycle) * rig.period == pytest.approx(0.100, abs=0.0021)


def test_e3_s_ramp_peak_acceleration_is_1_25_times_the_setting():
    """E3 (§4.3.1): S-ramp, Acceleration 1000 -> peak 1250, ramp duration unchanged (C1)."""
    shape, lim = s_ramp_limits(True, 1000.0, 800.0)
    prof = plan_velocity(shape, State(0.0, 0.0, 0.0), 800.0, lim)
    peak = max(abs(prof.sample(k * prof.duration / 400)[2]) for k in range(401))
    assert peak == pytest.approx(S_RAMP_PEAK_FACTOR * 1000.0, rel=1e-9)
    assert prof.duration == pytest.approx(0.8, rel=1e-12)
    shape, lim = s_ramp_limits(False, 1000.0, 800.0)
    lin = plan_velocity(shape, State(0.0, 0.0, 0.0), 800.0, lim)
    assert lin.duration == pytest.approx(0.8) and lin.target.p == pytest.approx(prof.target.p)
    # in the running cutter: the set-point acceleration of the approach peaks at 1.25 x Acc1.
    # The line is the virtual master at 48 m/min: the approach's set-point acceleration also
    # carries the line's acceleration (zero here, and exact from the virtual master; an
    # encoder's estimate would add its count noise)
    s = mm_settings(acceleration_1=1000, ramp_form=0, virtual_line_speed=48000, ramp_vir_master=0)
    rig = CutterRig(s, encoder_line=False)
    rig.cutter.inputs.select_vir_master = True
    rig.cutter.inputs.run_virt_master = True
    rig.enable()
    rig.start()
    peak = 0.0
    for _ in range(3000):
        rig.step()
        if rig.cutter.cut_state is CutState.ACCELERATION:
            peak = max(peak, abs(rig.cutter.set_point[2]))
    assert peak == pytest.approx(1250.0, rel=0.02)


# ---------------------------------------------------------------- synchronisation (E5, E6, E7, C5)


def test_cut_lands_on_target_at_constant_speed():
    """Pieces measured on the simulated material: within one carriage increment (spec §2.3.2)."""
    rig = running_rig(demo_settings(), 10000.0)  # 60 m/min, 1 m pieces
    rig.run(6.0)
    pieces = rig.pieces()
    assert len(pieces) >= 4 and rig.cutter.errors == 0
    for p in pieces:
        assert p.target_length == 10000.0
        assert abs(p.error_counts) <= 1.0


def test_e5_sync_rate_changes_the_synchronous_speed_not_the_cutting_length():
    s = mm_settings(sync_rate=1.0)
    rig = running_rig(s, 1000.0)
    speeds = []
    for _ in range(4500):
        rig.step()
        if rig.cutter.cut_state is CutState.READY_TO_CUT:
            speeds.append(rig.cutter.set_point[1])
    assert speeds and all(v == pytest.approx(1010.0, rel=1e-9) for v in speeds)
    targets = [c.target_mc for c in rig.cutter.cut_log]
    assert len(targets) >= 3
    assert all(b - a == 1000 * s.pulses_line_1000 for a, b in zip(targets, targets[1:]))


def test_e6_ready_to_cut_rises_synchron_time_after_sync_speed():
    for st in (1, 25):
        rig = running_rig(mm_settings(synchron_time=st, cut_window=99), 500.0)
        assert rig.run_until(lambda r: r.cutter.cut_state is CutState.SYNCHRONOUS, 5.0)
        c_sync = rig.cycle
        assert rig.run_until(lambda r: r.cutter.outputs.ready_to_cut, 1.0)
        # the tick of cycle (rig.cycle - 1) switched it on
        assert (rig.cycle - 1 - (c_sync - 1)) * rig.period * 1000 >= st - 1e-9
        assert (rig.cycle - 1 - (c_sync - 1)) * rig.period * 1000 <= st + 1.0 + 1e-9


def test_e7_sync_samples_filter_the_cut_window():
    """E7: Sync Samples 5 and a carriage leaving the window every 3rd cycle: never Ready to Cut."""

    def wobble(rig, c):
        if c % 3 == 0:
            rig.cutter.loop.position_error = 100.0  # outside the window this cycle

    for samples, expect in ((5, False), (2, True)):
        rig = running_rig(mm_settings(sync_samples=samples), 500.0)
        rig.hooks.append(wobble)
        rig.run(3.0)
        assert (len(rig.cutter.cut_log) > 0) is expect


def test_cut_window_is_in_carriage_increments_c5():
    """C5: |position error| must be <= Cut Window (increments) before Ready to Cut."""

    def hold_error(rig, c):
        rig.cutter.loop.position_error = 9.0  # increments (2.25 LU at 4 increments/LU)

    rig = running_rig(mm_settings(cut_window=8), 500.0)
    rig.hooks.append(hold_error)
    rig.run(3.0)
    assert rig.cutter.cut_log == [] and rig.cutter.cut_state is CutState.SYNCHRONOUS
    rig = running_rig(mm_settings(cut_window=9), 500.0)
    rig.hooks.append(hold_error)
    rig.run(3.0)
    assert rig.cutter.cut_log


def test_cut_completed_edge_sense_falling():
    s = mm_settings(edge_sense=1)
    rig = running_rig(s, 1000.0)
    rig.cutter.inputs.cut_completed = True  # idle HIGH: the falling edge counts
    rig.run(4.0)
    assert len(rig.cutter.cut_log) >= 3 and rig.cutter.errors == 0


def test_ready_to_cut_stays_until_cut_completed_and_alarm_position_warns():
    """No Cut completed: the carriage keeps following; Alarm at the Alarm Position, no stop (§4.1.1)."""
    s = mm_settings(alarm_position=300)
    rig = running_rig(s, 500.0, tool=Tool(enabled=False))
    rig.run(4.0)
    c = rig.cutter
    assert c.outputs.ready_to_cut and c.cut_state is CutState.READY_TO_CUT
    assert c.outputs.alarm and c.errors == 0
    assert rig.drive.velocity == pytest.approx(500.0, rel=0.02)
    rig.cutter.inputs.cut_completed = True
    rig.run(0.01)
    assert not c.outputs.ready_to_cut and c.cut_state in (CutState.DECELERATION, CutState.RETURN)


def test_ready_to_cut_linked_to_cut_completed_for_commissioning():
    """§7.5: Ready to cut wired to Cut completed (Edge Sense 0): return after Synchron Time."""
    s = mm_settings(synchron_time=50)
    rig = running_rig(s, 1000.0, tool=Tool(enabled=False))
    rig.hooks.append(lambda r, c: setattr(r.cutter.inputs, "cut_completed", r.cutter.outputs.ready_to_cut))
    rig.run(5.0)
    assert len(rig.cutter.cut_log) >= 4 and rig.cutter.errors == 0


# ---------------------------------------------------------------- return (E4, C4) and home window


def test_e4_return_speed_limits():
    """E4: Rel 2.00 at 10000 LU/min -> at most 20000 LU/min; Abs 15000 -> 15000 whatever the line."""
    # 10000 LU/min is 667 increments/s: a 100 ms Sampling Time measures it to 1.5 %
    rig = running_rig(mm_settings(return_speed=2.0, sampling_time=100), 10000 / 60)
    rig.run(0.2)
    assert rig.cutter._v_return_max() * 60 == pytest.approx(20000, rel=0.02)
    rig = running_rig(mm_settings(return_speed=2.0, abs_return_speed=15000, sampling_time=100), 10000 / 60)
    rig.run(0.2)
    assert rig.cutter._v_return_max() * 60 == pytest.approx(15000)
    rig = running_rig(mm_settings(return_speed=2.0, abs_return_speed=15000, sampling_time=100), 50000 / 60)
    rig.run(0.2)
    assert rig.cutter._v_return_max() * 60 == pytest.approx(15000)


def test_return_speed_is_only_as_fast_as_needed():
    """C4: a long piece returns slowly; a short one at the limit (Rel. Return Speed x line)."""
    long = running_rig(mm_settings(cutting_length=6000, return_speed=3.0), 1000.0)
    long.run(8.0)
    assert long.cutter.cut_log and long.cutter.errors == 0
    v_long = long.cutter.return_speed_used
    short = running_rig(mm_settings(cutting_length=1500, return_speed=3.0), 1000.0)
    short.run(4.0)
    assert short.cutter.errors == 0
    v_short = short.cutter.return_speed_used
    assert v_long < 0.5 * v_short
    assert v_short <= 3.0 * 60000 * 1.0001


def test_home_output_follows_the_home_window():
    s = mm_settings(home_window=5)
    rig = running_rig(s, 1000.0)
    seen_out = seen_in = False
    for _ in range(3000):
        seen = rig.axis.actual_position  # what the tick of this cycle sees (encoder, last loop)
        rig.step()
        off = abs(seen - rig.cutter.home_position)
        assert rig.cutter.outputs.home is (off <= 5)
        seen_out |= off > 5
        seen_in |= off <= 5
    assert seen_out and seen_in


# ---------------------------------------------------------------- Error 02 (C3, E19)


def test_e19_one_metre_at_60_m_min_with_a_one_second_cut_is_not_possible():
    """E19 (§10): 1 m pieces at 60 m/min with a saw needing 1 s: Error 02 on the 2nd cut."""
    s = mm_settings(cutting_length=1000, acceleration_1=5000, deceleration_1=5000)
    rig = running_rig(s, 1000.0, tool=Tool(blade_delay=0.5, cut_time=1.0))
    c = rig.cutter
    assert rig.run_until(lambda r: len(r.cutter.cut_log) == 1, 2.0)
    ok = rig.run_until(lambda r: r.cutter.error_active(FS701Error.CUT_NOT_POSSIBLE), 3.0)
    assert ok and c.outputs.error and len(c.cut_log) == 1
    assert c.control_state is ControlState.ERROR
    # the carriage never starts forward again: it finishes the cycle and stands at home
    rig.run(3.0)
    assert len(c.cut_log) == 1 and c.cut_state is CutState.HOME
    assert abs(rig.drive.position - c.home_position) < s.home_window and abs(rig.drive.velocity) < 1.0


def test_error_02_is_checked_before_moving_and_clear_error_resumes():
    s = mm_settings(cutting_length=1000)
    rig = running_rig(s, 1000.0, tool=Tool(blade_delay=0.5, cut_time=1.0))
    rig.run_until(lambda r: r.cutter.errors != 0, 5.0)
    c = rig.cutter
    assert c.errors == 1 << FS701Error.CUT_NOT_POSSIBLE
    assert c.cut_state in (CutState.DECELERATION, CutState.RETURN, CutState.HOME)
    rig.run(2.0)
    rig.tool.blade_delay, rig.tool.cut_time = 0.02, 0.05  # the cause removed (faster tool)
    c.inputs.clear_error = True
    rig.run(0.002)
    c.inputs.clear_error = False
    assert c.errors == 0
    n = len(c.cut_log)
    rig.run(4.0)
    assert c.errors == 0 and len(c.cut_log) >= n + 3
    kinds = [x.kind for x in c.cut_log[n:]]
    assert kinds[0] is CutKind.LATE and all(k is CutKind.NORMAL for k in kinds[1:])  # C9


# ---------------------------------------------------------------- counters (E25), immediate cut, test length


def test_e25_decrement_batch_counter():
    s = mm_settings(batch_counter=243, waste_counter=9)
    rig = CutterRig(s)
    rig.enable()
    rig.cutter.inputs.decr_batch_cou = True
    rig.run(0.002)
    assert (rig.cutter.batch_counter, rig.cutter.waste_counter) == (242, 10)
    rig.run(0.01)  # static HIGH: one edge, one decrement
    assert (rig.cutter.batch_counter, rig.cutter.waste_counter) == (242, 10)
    rig.cutter.inputs.reset_batch_cou = True
    rig.run(0.002)
    assert rig.cutter.batch_counter == 0


def test_batch_counts_normal_cuts_waste_counts_immediate_and_test_cuts():
    rig = running_rig(mm_settings(), 500.0)
    rig.run(7.0)
    c = rig.cutter
    assert c.batch_counter == len(c.cut_log) >= 3 and c.waste_counter == 0


def test_immediate_cut_in_stop_re_references_the_grid_c7():
    s = mm_settings()
    rig = CutterRig(s, line_speed=500.0)
    rig.enable()
    rig.run(0.5)
    c = rig.cutter
    c.inputs.immediate_cut = True
    rig.run(1.0)
    c.inputs.immediate_cut = False
    assert len(c.cut_log) == 1 and c.cut_log[0].kind is CutKind.IMMEDIATE and c.waste_counter == 1
    assert c.batch_counter == 0
    rig.run(0.5)
    c.inputs.start_stop = True  # Start after the immediate cut: first piece = Cutting Length (C10)
    rig.run(5.0)
    pieces = rig.pieces()
    assert len(pieces) >= 3
    assert pieces[0].kind == "NORMAL" and abs(pieces[0].error_lu) < 0.5
    assert c.batch_counter == len(c.cut_log) - 1


def test_immediate_cut_in_automatic_cuts_at_once_then_preset_length():
    s = mm_settings(cutting_length=3000)
    rig = running_rig(s, 1000.0)
    rig.run(0.8)
    c = rig.cutter
    c.inputs.immediate_cut = True
    rig.run(0.01)
    c.inputs.immediate_cut = False
    assert c.cut_state is CutState.ACCELERATION and c.current_cut.kind is CutKind.IMMEDIATE
    rig.run(0.5)
    assert c.cut_log and c.cut_log[0].kind is CutKind.IMMEDIATE
    rig.run(7.0)
    pieces = rig.pieces()
    assert [p.kind for p in pieces[:2]] == ["NORMAL", "NORMAL"]
    assert all(abs(p.error_lu) < 0.5 for p in pieces)


def test_cut_test_length_pulse_gives_one_test_piece_c8():
    s = mm_settings(cutting_length=1500, test_cut_length=700)
    rig = running_rig(s, 600.0)
    c = rig.cutter
    assert rig.run_until(lambda r: len(r.cutter.cut_log) == 1, 5.0)
    c.inputs.cut_test_length = True  # a short pulse while the first cycle runs
    rig.run(0.01)
    c.inputs.cut_test_length = False
    rig.run(8.0)
    kinds = [p.kind for p in rig.pieces()]
    lengths = [p.target_length for p in rig.pieces()]
    assert kinds[:3] == ["TEST", "NORMAL", "NORMAL"] and lengths[:3] == [700.0, 1500.0, 1500.0]
    assert all(abs(p.error_lu) < 0.5 for p in rig.pieces())
    assert c.waste_counter == 1


def test_tool_width_spaces_the_targets_c6():
    s = mm_settings(cutting_length=1000, tool_width=5)
    rig = running_rig(s, 500.0)
    rig.run(8.0)
    t = [x.target_mc for x in rig.cutter.cut_log]
    assert all(b - a == 1005 * s.pulses_line_1000 for a, b in zip(t, t[1:]))
    assert all(abs(p.error_lu) < 0.5 for p in rig.pieces())  # pieces of L (kerf removed)


# ---------------------------------------------------------------- start, stop, enable (C9..C12)


def test_late_first_cut_is_waste_c9():
    """Start with more than a piece counted in Stop: the first cut is made at once (waste)."""
    s = mm_settings(cutting_length=1000)
    rig = CutterRig(s, line_speed=500.0)
    rig.enable()
    rig.run(2.5)  # 1250 mm counted in Stop
    rig.start()
    rig.run(0.05)
    c = rig.cutter
    assert c.cut_state is not CutState.HOME and c.current_cut.kind is CutKind.LATE
    rig.run(5.0)
    assert c.waste_counter == 1 and all(p.kind == "NORMAL" for p in rig.pieces())
    assert all(abs(p.error_lu) < 0.5 for p in rig.pieces())


def test_set_length_counter_presets_the_first_piece_once_c10():
    s = mm_settings(cutting_length=1000, set_length_cou_lu=400)
    rig = CutterRig(s, line_speed=500.0)
    rig.enable()
    rig.start()
    rig.run(0.002)
    c = rig.cutter
    assert c.length_counter == pytest.approx(400 * s.line_counts_per_lu, abs=2)
    assert s.set_length_cou_lu == 0 and s.set_length_cou_ps == 0 and c.set_length_counter_consumed
    assert rig.run_until(lambda r: r.cutter.cut_state is CutState.ACCELERATION, 3.0)
    assert rig.time == pytest.approx((600 - 25) / 500.0 + 0.012, abs=0.01)
    # Ps wins when both are set (C10)
    s2 = mm_settings(set_length_cou_ps=800, set_length_cou_lu=400)
    rig2 = CutterRig(s2, line_speed=500.0)
    rig2.enable()
    rig2.start()
    rig2.run(0.002)
    assert rig2.cutter.length_counter == pytest.approx(800, abs=2)


def test_stop_during_cycle_completes_it_c11():
    rig = running_rig(mm_settings(), 500.0)
    c = rig.cutter
    assert rig.run_until(lambda r: r.cutter.cut_state is CutState.ACCELERATION, 3.0)
    c.inputs.start_stop = False
    rig.run(2.0)
    assert len(c.cut_log) == 1 and c.cut_state is CutState.HOME
    rig.run(3.0)
    assert len(c.cut_log) == 1 and c.control_state is ControlState.STOP


def test_control_enable_off_switches_the_output_off_and_clears_errors_c12():
    s = mm_settings(pulses_line_1000=17000, pulses_cut_1000=1000, batch_counter=5)
    rig = CutterRig(s, line_speed=500.0)
    rig.enable()
    c = rig.cutter
    assert c.errors
    s.pulses_line_1000 = 4000
    s.pulses_cut_1000 = 4000
    c.inputs.control_enable = False
    rig.run(0.01)
    assert c.errors == 0 and rig.volts == 0.0 and not rig.axis.powered
    assert c.control_state is ControlState.DISABLED and c.length_counter == 0
    assert c.batch_counter == 5


def test_settings_fill_from_the_fs701_parameter_set_by_name():
    """The lead fills CutterSettings from the register side's ParameterSet (same attribute names)."""
    params = pytest.importorskip("axisline.devices.fs701.parameters")
    ps = params.ParameterSet()
    assert CutterSettings.from_parameters(ps) == CutterSettings()  # same names, units, defaults
    ps.cutting_length = 2500
    ps.sync_rate = 1.5
    ps.ana_out_gain_2 = 10.16
    s = CutterSettings.from_parameters(ps)
    assert (s.cutting_length, s.sync_rate, s.ana_out_gain_2) == (2500, 1.5, pytest.approx(10.16))


def test_e1_length_units_of_0_1_mm():
    """E1 (§4.2): LU = 0.1 mm: Cutting Length 1000 gives 100.0 mm pieces (demo line: 20 incr/mm)."""
    s = demo_settings(cutting_length=1000, acceleration_1=20000, deceleration_1=20000)
    rig = running_rig(s, 1000.0)  # 6 m/min
    rig.run(4.0)
    pieces = rig.pieces()
    assert len(pieces) >= 2
    assert all(abs(p.actual_length * 0.1 - 100.0) <= 0.05 for p in pieces)  # mm


def test_immediate_cut_at_line_standstill_is_synchronous_at_once_c19():
    rig = CutterRig(mm_settings(), line_speed=0.0)
    rig.enable()
    c = rig.cutter
    c.inputs.immediate_cut = True
    rig.run(0.005)
    assert c.outputs.ready_to_cut and abs(rig.drive.position) < 0.1
    c.inputs.cut_completed = True
    rig.run(0.05)
    assert c.cut_state is CutState.HOME and c.waste_counter == 1


def test_state_codes_and_process_values():
    rig = running_rig(mm_settings(), 1000.0)
    rig.run(0.01)
    c = rig.cutter
    pv = c.process_values()
    assert pv[29] == ControlState.AUTOMATIC and pv[30] == CutState.HOME
    assert pv[2] == pytest.approx(60000, rel=0.01) and pv[1] == pytest.approx(4000, rel=0.01)
    assert rig.run_until(lambda r: r.cutter.cut_state is CutState.DECELERATION, 3.0)
    pv = c.process_values()
    assert pv[30] == CutState.DECELERATION and pv[14] == 1
    assert pv[12] <= pv[13] and max(abs(pv[12]), abs(pv[13])) <= 3 * c.settings.cut_window  # #12/#13 during the cut
    assert pv[8] > 0 and pv[10] == pytest.approx(1000 * 4)  # travel, cut length in increments
    assert c.outputs.bits() & 1  # Ready (bit 0)


def test_start_takes_the_home_position_where_the_carriage_stands():
    """§4.3.3: the home for the cuts is where the carriage is when Start/Stop goes HIGH."""
    s = mm_settings(jog_speed_forw=50)
    rig = CutterRig(s, line_speed=1000.0)
    rig.enable()
    c = rig.cutter
    c.inputs.jog_forward = True
    rig.run(0.4)
    c.inputs.jog_forward = False
    rig.run(0.5)
    home = c.set_point[0]
    assert home > 100.0
    rig.start()
    rig.run(3.0)
    assert c.home_position == pytest.approx(home) and len(c.cut_log) >= 2
    assert all(abs(p.error_lu) < 0.5 for p in rig.pieces())
    rig.run_until(lambda r: r.cutter.cut_state is CutState.HOME, 2.0)
    assert abs(rig.drive.position - home) < s.home_window
