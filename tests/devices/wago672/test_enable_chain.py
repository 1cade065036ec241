"""Enable / Ready / Stop chain and the selection and ending of modes (manual §3.7.2, §3.11.1.1-3.11.1.3)."""

from __future__ import annotations

from axisline.devices.wago672.image import C1, C2, C3, S1, S2, S3
from axisline.motion.axis import AxisState

from .rig import ON, Rig


def test_power_on_reset_bit_until_reset_quit():
    r = Rig()
    r.step()
    assert r.has(S3.Reset) and r.has(S3.Input1)
    r.c3 = C3.Reset_Quit
    r.step()
    assert not r.has(S3.Reset)
    r.c3 = 0
    r.step()
    assert not r.has(S3.Reset)


def test_enable_gives_ready_and_stop2_n_with_di1_gives_stop_n_ack():
    r = Rig()
    r.c1 = C1.Enable
    r.step()
    assert r.has(S1.Ready) and not r.has(S1.Stop_N_ACK)
    assert r.axis.powered and r.axis.state is AxisState.STANDSTILL
    r.c1 = ON
    r.step()
    assert r.s1 == 0x03 and r.s2 == S2.StandStill  # wago.md §9.12 step 1
    # DI1 is Stop1_N by default: without it Stop_N_ACK stays 0 (wago.md §9.9)
    r.inputs["Input1"] = False
    r.step()
    assert r.has(S1.Ready) and not r.has(S1.Stop_N_ACK) and not r.has(S3.Input1)


def test_mode_selection_needs_stop_n_ack_and_is_acknowledged():
    r = Rig()
    r.inputs["Input1"] = False
    r.c1 = ON | C1.M_Positioning
    r.step(3)
    assert r.s1 & 0xF8 == 0, "selection is delayed until Stop_N_ACK"
    r.inputs["Input1"] = True
    r.step()
    assert r.has(S1.M_Positioning_ACK) and r.inp.command_ack == 1


def test_sequence_of_fig_3_11_1_1_mode_1_ends_mode_2_starts():
    r = Rig(Acceleration_Stop_Fast=1000)
    r.enable()
    r.select(C1.M_Positioning)
    r.positioning(10000, 5000, 40000)
    r.start()
    r.step(100)
    assert r.has(S2.Busy)
    # (7) mode 1 ended while moving: braked with Acceleration_Stop_Fast, ACK until standstill
    r.c1 = ON
    r.step()
    assert r.has(S1.M_Positioning_ACK)
    n = r.until(lambda: not r.has(S1.M_Positioning_ACK), 2000)
    assert r.has(S2.StandStill) and not r.has(S2.On_Target)
    assert n > 1
    # (9) (10) mode 2 selected and accepted
    r.select(C1.M_Reference)


def test_another_mode_bit_while_a_mode_is_active_has_no_function():
    r = Rig()
    r.enable()
    r.select(C1.M_Positioning)
    r.c1 |= C1.M_Jog
    r.step(3)
    assert r.s1 & 0xF8 == S1.M_Positioning_ACK and r.error == 0


def test_two_mode_bits_at_selection_are_error_1354():
    r = Rig()
    r.enable()
    r.c1 = ON | C1.M_Reference | C1.M_Jog
    r.step()
    assert r.error == 1354 and r.has(S2.Error) and not r.has(S1.Ready)


def test_start_without_a_mode_is_error_1351():
    r = Rig()
    r.enable()
    r.c1 |= C1.Start
    r.step()
    assert r.error == 1351 and not r.has(S1.Start_ACK)


def test_stop2_n_brakes_with_acceleration_stop_fast_and_ends_the_mode_at_standstill():
    r = Rig(Acceleration_Stop_Fast=2000)  # 2000 * 1000 / 40 = 50000 microsteps/s^2
    r.enable()
    r.select(C1.M_Positioning)
    r.positioning(10000, 32767, 100000)  # 20000 microsteps/s
    r.start()
    r.until(lambda: r.has(S2.On_Speed), 500)
    r.c1 &= ~C1.Stop2_N
    r.step()
    assert r.has(S1.Stop_N_ACK), "Stop_N_ACK stays 1 while the drive is braked"
    assert r.has(S1.M_Positioning_ACK)
    n = r.until(lambda: r.has(S2.StandStill))
    assert abs(n - 20000 / 50000 * 1000) <= 2  # v / a = 0.4 s
    r.step()
    assert not r.has(S1.Stop_N_ACK) and r.s1 & 0xF8 == 0
    assert not r.has(S2.On_Target) and not r.has(S2.Busy)
    assert r.axis.powered, "Stop2_N keeps the motor energised"
    assert r.dev.current_phase.name == "STANDSTILL"


def test_di1_stop1_n_stops_like_stop2_n():
    r = Rig()
    r.enable()
    r.select(C1.M_Positioning)
    r.positioning(5000, 32767, 50000)
    r.start()
    r.step(50)
    r.inputs["Input1"] = False
    r.step()
    assert r.has(S1.Stop_N_ACK) and r.dev.current_phase.name == "STOP"
    r.until(lambda: not r.has(S1.Stop_N_ACK), 2000)
    assert r.has(S2.StandStill)


def test_stop_ramp_runs_at_current_ratio_stop_and_rest_at_the_standstill_ratio():
    # decision D25 (drive.py): Current_Ratio_Stop while the STOP ramp brakes, the standstill
    # ratio once at rest, also with Stop2_N still 0 (150 % at rest would trip the thermal model)
    r = Rig(Current_Ratio_Stop=120, Current_Ratio_StandStill=20, Current_Ratio_Drive=60)
    r.enable()
    r.select(C1.M_Positioning)
    r.positioning(5000, 32767, 50000)
    r.start()
    r.until(lambda: r.has(S2.On_Speed), 500)
    assert r.dev.current_ratio == 60 and r.dev.current_phase.name == "DRIVE"
    r.c1 &= ~C1.Stop2_N
    r.step()
    assert r.dev.current_ratio == 120 and r.dev.current_phase.name == "STOP"
    r.until(lambda: r.has(S2.StandStill))
    assert r.dev.current_ratio == 20 and r.dev.current_phase.name == "STANDSTILL"
    assert r.dev.phase_current == 5.0 * 20 / 100  # Current 50 (0.1 A) at 20 %


def test_enable_off_coasts_ready_and_ack_drop_at_once():
    r = Rig()
    r.enable()
    r.select(C1.M_Positioning)
    r.positioning(10000, 32767, 100000)
    r.start()
    r.step(100)
    r.c1 = C1.Stop2_N | C1.M_Positioning
    r.step()
    assert r.s1 == 0 and not r.has(S2.Busy)
    assert r.axis.state is AxisState.DISABLED and not r.axis.powered
    p = r.dev.position_steps
    r.step(10)
    assert r.dev.position_steps == p, "the pulse output stops at once (no ramp)"


def test_freq_range_sel_is_taken_only_while_enable_is_0():
    r = Rig()
    r.c2 = C2.Freq_Range_Sel_0  # '01' -> prescaler 80
    r.step()
    assert r.dev.scaling.prescaler == 80
    r.enable()
    r.c2 = C2.Freq_Range_Sel_0 | C2.Freq_Range_Sel_1
    r.step()
    assert r.dev.scaling.prescaler == 80
    r.c1 = 0
    r.step()
    assert r.dev.scaling.prescaler == 4
