"""Limitation of the moving range and the rotary axis (manual §3.11.3, §3.11.1.8; wago.md §2.6, §2.13; D9-D11)."""

from __future__ import annotations

import pytest

from axisline.devices.wago672.bits import Bit
from axisline.devices.wago672.device import Opcode, RC
from axisline.devices.wago672.image import C1, S1, S2

from .rig import Rig


def pos_rig(**values) -> Rig:
    r = Rig(**values)
    r.enable()
    r.select(C1.M_Positioning)
    return r


def test_crossing_a_software_limit_brakes_and_sets_err_range_pos():
    r = pos_rig(Drive_Range_Pos=5000, Acceleration_Stop_Fast=2000)
    r.positioning(10000, 32767, 20000)
    r.start()
    r.until(lambda: r.has(S2.StandStill), 5000)
    assert 5000 < r.position < 20000 and not r.has(S2.On_Target)
    assert r.dev.bits.read(Bit.Err_Range_Pos) and r.dev.bits.read(Bit.Err_Range) and r.error == 0
    assert not r.has(S2.Busy)
    # further out is refused (no motion, no error); back into the range is accepted
    here = r.position
    r.positioning(10000, 32767, 30000)
    r.start()
    r.step(50)
    assert r.position == here and r.error == 0 and not r.has(S2.Busy)
    r.move(10000, 32767, 1000)
    assert r.position == 1000 and not r.dev.bits.read(Bit.Err_Range_Pos)


def test_software_limit_negative():
    r = pos_rig(Drive_Range_Neg=-2000)
    r.positioning(10000, 32767, -9000)
    r.start()
    r.until(lambda: r.has(S2.StandStill), 5000)
    assert r.position < -2000 and r.dev.bits.read(Bit.Err_Range_Neg)


def test_hardware_limit_switch_brakes_a_positioning_move():
    r = pos_rig(Acceleration_Stop_Fast=1000)
    r.inputs["Input5"] = lambda: r.x >= 3000
    r.positioning(10000, 32767, 20000)
    r.start()
    r.until(lambda: r.has(S2.StandStill), 5000)
    assert r.x >= 3000 and r.position < 20000 and r.error == 0 and not r.has(S2.On_Target)
    # the drive can only be started in jog or referencing at a limit switch
    r.positioning(10000, 32767, 0)
    r.c1 |= C1.Start
    r.step()
    assert r.error == 1931


def test_rotary_axis_actual_value_wraps_and_targets_go_the_short_way():
    # wago.md §9.5: P = 12800 (one turn of a 200-step motor)
    r = pos_rig(Rotary_Axis_Period=12800)
    r.move(10000, 32767, 12000)  # from 0 the short way is -800
    assert r.position == 12000 and r.dev.position_steps == -800
    r.record = True
    r.move(10000, 32767, 400)  # from 12000: +1200 across 0, not -11600
    assert r.position == 400
    assert all(v >= 0.0 for _, _, v in r.trace)
    assert r.dev.position_steps == 400


def test_rotary_axis_absolute_target_outside_the_period_is_1123():
    r = pos_rig(Rotary_Axis_Period=12800)
    r.positioning(10000, 32767, 12800)
    r.c1 |= C1.Start
    r.step()
    assert r.error == 1123


def test_rotary_axis_relative_moves_over_several_turns():
    # wago.md §9.5: MOVE_REL +25600 from 0 -> two turns, actual 0; MOVE_REL -100 from 0 -> 12700
    r = Rig(Rotary_Axis_Period=12800, Freq_Div=4)
    r.c0 = 0x20  # mailbox on: move commands via mailbox need C1.7
    r.enable()
    r.select(C1.M_DriveByMbx)
    dev = r.dev
    assert dev.drive_command(Opcode.SET_VELOCITY, (0x10, 0x27, 0)) == RC.OK  # 10000
    assert dev.drive_command(Opcode.MOVE_REL, (25600).to_bytes(3, "little")) == RC.OK
    r.until(lambda: r.has(S2.On_Target), 5000)
    assert dev.actual_position == 0 and dev.position_steps == 25600
    assert dev.drive_command(Opcode.MOVE_REL, (-100).to_bytes(3, "little", signed=True)) == RC.OK
    r.until(lambda: r.has(S2.On_Target), 5000)
    assert dev.actual_position == 12700


def test_rotary_axis_without_software_limits_when_the_range_covers_the_period():
    # "Limited to Drive_Range_* when Drive_Range_Neg >= 0 or Drive_Range_Pos < P, otherwise unrestricted"
    r = pos_rig(Rotary_Axis_Period=12800)
    r.move(10000, 32767, 6000)
    assert not r.dev.bits.read(Bit.Err_Range)
    r = pos_rig(Rotary_Axis_Period=12800, Drive_Range_Neg=0, Drive_Range_Pos=5000)
    r.positioning(10000, 32767, 6000)
    r.start()
    r.until(lambda: r.has(S2.StandStill), 5000)
    assert r.dev.bits.read(Bit.Err_Range_Pos) and not r.has(S2.On_Target)


def test_set_actual_pos_takes_reference_offset_at_standstill_only():
    r = pos_rig(Reference_Offset=777)
    r.move(10000, 32767, 5000)
    from axisline.devices.wago672.image import C3

    r.c3 = C3.SetActual_Pos
    r.step(20)  # "must be set for a minimum of 20 ms"
    r.c3 = 0
    r.step()
    assert r.position == 777 and r.x == 5000
    r.positioning(10000, 32767, 20000)
    r.start()
    r.step(10)
    before = r.position
    r.c3 = C3.SetActual_Pos  # while moving: "the actual value remains unchanged and no error"
    r.step()
    assert r.position > before and r.error == 0
    r.c3 = 0
    r.until(lambda: r.has(S2.On_Target), 5000)
    assert r.position == 20000
    assert r.has(S1.Ready)


@pytest.mark.parametrize("cpu", [1.0, 64.0])
def test_axis_units_are_microsteps_over_counts_per_unit(cpu):
    r = Rig(counts_per_unit=cpu)
    r.enable()
    r.select(C1.M_Positioning)
    r.move(10000, 32767, 6400)
    assert r.axis.command_position == pytest.approx(6400 / cpu) and r.position == 6400


def test_drive_direction_inverts_the_motor_not_the_logical_position():
    # HwSwConfig bit 2 Drive_Direction: "rotary direction is inverted" (wago.md §4.3 [RECONSTRUCTED])
    r = Rig(HwSwConfig=0x04)
    r.enable()
    r.select(C1.M_Positioning)
    r.move(10000, 32767, 3000)
    assert r.position == 3000 and r.axis.command_position == -3000
