"""COMPAX auxiliary functions and the special outputs O13...O16 (compax.md §2.12, §2.18; §7 X7, X20, X22;
Appendix B p38_all_aux_enabled, aux_valences, bx_decode_examples)."""

from __future__ import annotations

import pytest

from axisline.devices.compax import CompaxError
from axisline.devices.compax.camop import CamState, analog_volts

from .test_camop_rig import FULL, Curve, Rig, line

# §25 sample curve: aux functions "digital;analogue 0;analogue 1" of the 11 set points
MANUAL_AUX = ["1;10;246", "3;20;236", "7;30;226", "15;40;216", "31;50;206", "63;60;196", "127;70;186",
              "255;80;176", "254;90;166", "252;100;156", "248;110;146"]


def manual_curve(**kw) -> Curve:
    triples = [tuple(int(x) for x in t.split(";")) for t in MANUAL_AUX]
    return line(aux_digital=[t[0] for t in triples], aux_analog=[(t[1], t[2]) for t in triples], **kw)


def running(p38=16320, p37=0, i15=True, speed=0, curve=None, **params) -> Rig:
    rig = Rig({1: curve or manual_curve()}, P38=p38, P37=p37, **params)
    rig.inputs["I15"] = i15
    rig.op.setc(1)
    rig.op.setm(0.0)
    rig.start_master(0)
    rig.op.loop(0)
    rig.inputs["I13"] = True
    rig.step()
    rig.speed = speed
    return rig


def outputs(rig: Rig) -> dict[int, bool]:
    return {n: rig.op.output(n) for n in range(7, 15)}


def test_manual_curve_at_180_sets_o7_to_o12():
    # §7 X20: "at m = 180 slave = 180, O-byte 63 (O7...O12 = 1) => with P38 = 16320, I15 = 1:
    # O7-O12 on, O13/O14 off; analogue ch0 interpolates 10 -> 110 across points"
    rig = running(speed=4)
    rig.step(45)  # master 180
    assert rig.p == pytest.approx(180.0)
    assert outputs(rig) == {7: True, 8: True, 9: True, 10: True, 11: True, 12: True, 13: False, 14: False}
    assert rig.op.aux_byte == 63
    assert rig.op.analog(0) == pytest.approx(60.0) and rig.op.analog(1) == pytest.approx(-60.0)
    rig.step(4)  # master 196: between set points 5 (180) and 6 (216)
    assert rig.op.analog(0) == pytest.approx(60.0 + 10 * 16 / 36)
    assert rig.op.aux_byte == 63  # the bits of the last set point passed


def test_p38_16320_i15_1_byte_0b10000001():
    # §7 X7: "P38=16320, I15=1, set point aux byte 0b10000001 => O7=1, O14=1 (if P33=0), O8-O13=0.
    # With I15=0 and P37=64 => O7=1, others 0."
    curve = line(n=2, aux_digital=[0b10000001, 0b10000001])
    rig = running(curve=curve, speed=1)
    rig.step(3)
    assert outputs(rig) == {7: True, 8: False, 9: False, 10: False, 11: False, 12: False, 13: False, 14: True}
    rig2 = running(curve=curve, speed=1, i15=False, p37=64)
    rig2.step(3)
    assert outputs(rig2) == {7: True, 8: False, 9: False, 10: False, 11: False, 12: False, 13: False, 14: False}


def test_valences_and_the_mask():
    # Appendix B aux_valences: O7 = 64 ... O14 = 8192; only the outputs enabled by P38 change
    rig = Rig({1: manual_curve()}, P38=64 + 1024)  # O7 and O11
    rig.op.set_output(8, True)  # OUTPUT beyond cam operation, independent of the mask
    rig.op.setc(1)
    rig.start_master(0)
    rig.inputs["I15"] = True
    rig.op.loop(0)
    rig.inputs["I13"] = True
    rig.step()
    rig.speed = 4
    rig.step(45)  # byte 63: O7...O12, but only O7 and O11 are enabled
    assert outputs(rig) == {7: True, 8: True, 9: False, 10: False, 11: True, 12: False, 13: False, 14: False}


def test_i15_0_after_loop_the_outputs_take_the_reset_value():
    # §2.12 "I15="0": ... After "LOOP" the outputs O7 to O14 remain at the reset value indicated by P37."
    rig = Rig({1: manual_curve()}, P38=16320, P37=128 + 8192)
    rig.op.setc(1)
    rig.op.loop(0)
    assert rig.op.aux_byte == 0b10000010  # O8 and O14 right at LOOP
    rig.inputs["I13"] = True
    rig.start_master(4)
    rig.step(45)
    assert rig.op.aux_byte == 0b10000010
    rig.inputs["I15"] = True  # enabled during cam operation: the set points' bits
    rig.step()
    assert rig.op.aux_byte == 63


def test_outputs_freeze_when_leaving_synchronous_operation():
    # §2.12 "When leaving the synchronous operation: by I13="0", ... by STOP ... the outputs will
    # remain at the status which has been indicated last."
    rig = running(speed=4)
    rig.step(45)
    rig.inputs["I13"] = False
    rig.step()
    assert rig.op.state is CamState.READY
    rig.step(30)
    assert rig.op.aux_byte == 63
    rig.inputs["I13"] = True
    rig.step(30)
    assert rig.op.aux_byte != 63  # influenced again at the next cam operation
    rig.op.stop()
    byte = rig.op.aux_byte
    rig.step(40)
    assert rig.op.aux_byte == byte


def test_o14_is_the_label_error_while_label_synchronisation_is_on():
    # §2.12 "If the label synchronization is switched on (P33≠0) O14 is engaged, with the signal
    # "label error"." The aux function does not drive it.
    curve = line(n=2, aux_digital=[0xFF, 0xFF])
    rig = running(curve=curve, speed=1, P33=1)
    rig.step(3)
    assert rig.op.aux_byte & 0x7F == 0x7F
    assert rig.op.output(14) is False  # not set by the aux function


def test_output_command_rules():
    # §2.12 "O13 and O14 cannot be reached by OUTPUT"; during cam operation only the aux functions
    rig = Rig()
    with pytest.raises(CompaxError):
        rig.op.set_output(13, True)
    with pytest.raises(CompaxError):
        rig.op.set_output(14, True)
    rig.op.set_output(12, True)
    assert rig.op.output(12)
    rig.op.setc(1)
    rig.op.loop(0)
    with pytest.raises(CompaxError):
        rig.op.set_output(7, True)


@pytest.mark.parametrize(
    "raw, digital, an0_v, an1_v",
    [("128;0;0", 0b10000000, 0.0, 0.0), ("255;127;255", 0xFF, 10.0, -0.078), ("1;1;128", 1, 0.078, -10.0)],
)
def test_aux_decode_examples(raw, digital, an0_v, an1_v):
    # §7 X22 / Appendix B bx_decode_examples (P73 = P74 = 100)
    d, a0, a1 = (int(x) for x in raw.split(";"))
    curve = Curve(set_points=[0.0, FULL], aux_digital=[d, d], aux_analog=[(a0, a1), (a0, a1)])
    rig = running(curve=curve, speed=1)
    rig.step(2)
    assert rig.op.aux_byte == digital
    assert analog_volts(rig.op.analog(0)) == pytest.approx(an0_v, abs=0.08)
    assert analog_volts(rig.op.analog(1)) == pytest.approx(an1_v, abs=0.001 if an1_v != -10.0 else 1e-9)
    assert analog_volts(rig.op.analog(1), gain=10) == pytest.approx(an1_v / 10, abs=0.001)


def test_analogue_channels_are_prepared_independent_of_i15_and_of_the_cam_operation():
    # §2.12 "The analogue auxiliary functions are always prepared independently from I15!"
    rig = Rig({1: manual_curve()})
    rig.op.setc(1)
    rig.op.setm(50.0)
    assert rig.op.analog(0) == pytest.approx(60.0)


def test_o16_is_set_only_while_synchronous():
    # §2.18 O16 "Synchronous operation": not during the coupling movement
    rig = Rig({1: line(coupling=0.1, synchronous=0.6)}, P34=1)
    rig.op.setc(1)
    rig.start_master(2)
    rig.op.loop(0)
    rig.inputs["I13"] = True
    rig.until(lambda: rig.op.state is CamState.COUPLING)
    assert not rig.op.output(16)
    rig.until(lambda: rig.op.state is CamState.SYNC)
    assert rig.op.output(16)


def test_o15_tracking_warning_follows_p79():
    # §2.18 O15 (low active): "O15="1": the tracking error is smaller than the tracking zone given
    # by P79 ... actualized at each movement." (decision D13: every cycle)
    rig = Rig({1: line()}, P79=0.5, plant_lag=True)
    rig.step()
    assert rig.op.output(15)
    rig.op.setc(1)
    rig.start_master(0)
    rig.op.loop(0)
    rig.inputs["I13"] = True
    rig.step()
    rig.speed = 5  # 5000 deg/s: the lagging drive falls behind by more than 0.5
    rig.step(20)
    assert abs(rig.axis.following_error) > 0.5 and not rig.op.output(15)
    rig.speed = 0
    rig.step(2000)
    assert abs(rig.axis.following_error) < 0.5 and rig.op.output(15)


@pytest.mark.parametrize("gain, full_scale_rpm", [(1.0, 20000.0), (10.0, 2000.0), (100.0, 200.0)])
def test_da_monitor_master_speed_scaling(gain, full_scale_rpm):
    # §7 X8: signal 24 "20000 min-1 ≙ 10V" at gain 1; P71 = 10: 2000 min-1; P71 = 100: 200 min-1
    rig = running(speed=6)  # 6 increments/ms, M_T* = 360: 1000 master cycles per minute at P35 = 1
    rig.params[35] = full_scale_rpm / 2 / 1000
    rig.step(3)
    assert rig.op.status(41) == pytest.approx(full_scale_rpm / 2)
    assert rig.op.da_monitor(24, gain) == pytest.approx(5.0)


@pytest.mark.parametrize("gain, volts", [(1.0, 0.1), (10.0, 1.0), (100.0, 10.0)])
def test_da_monitor_master_and_slave_position(gain, volts):
    # §7 X8: signal 22 "M_T ≙ 100mV" at gain 1, 1 V (P71 = 10), 10 V (P71 = 100); signal 23 likewise S_T
    rig = running(speed=4)
    rig.step(45)  # half the master cycle, half the slave cycle
    assert rig.op.da_monitor(22, gain) == pytest.approx(volts / 2)
    assert rig.op.da_monitor(23, gain) == pytest.approx(volts / 2)
    assert rig.op.da_monitor(20, 100.0) == pytest.approx(60 * 10 / 128)
