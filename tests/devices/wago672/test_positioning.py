"""Single positioning through the process image, as a PLC drives it (manual §3.11.1.4; wago.md §2.1-2.3, §7.4, §9.12)."""

from __future__ import annotations

import pytest

from axisline.devices.wago672.bits import Bit
from axisline.devices.wago672.image import C1, C2, S1, S2
from axisline.motion.axis import AxisState

from .rig import ON, Rig

V20000 = 20000 * 80 / 40  # microsteps/s at the default prescaler 40


def test_exchange_of_wago_md_9_12():
    r = Rig()
    r.c1 = ON
    r.step()
    assert (r.s1, r.s2) == (0x03, 0x04)
    r.c1 = ON | C1.M_Positioning
    r.step()
    assert r.s1 == 0x0B
    r.positioning(20000, 3000, 65065)
    assert r.data == bytes([0x20, 0x4E, 0xB8, 0x0B, 0x29, 0xFE, 0x00])
    r.c1 = ON | C1.M_Positioning | C1.Start
    r.step()
    assert r.s1 == 0x0F and r.s2 == 0x12  # Start_ACK; Busy, Direction positive
    r.c1 = ON | C1.M_Positioning
    r.step()
    assert r.s1 == 0x0B  # Start_ACK follows Start
    r.until(lambda: r.has(S2.On_Speed), 2000)
    assert r.s2 == 0x1A and r.velocity == 20000
    r.until(lambda: r.has(S2.On_Target), 5000)
    assert r.s2 == 0x05 and r.inp.data[4:7] == bytes([0x29, 0xFE, 0x00]) and r.position == 65065
    assert r.dev.outputs == (True, False)  # DO1 = On_Target, DO2 = Error
    r.step(2)
    assert r.axis.state is AxisState.STANDSTILL and r.axis.command_position == 65065


def test_busy_from_start_to_target_and_on_target_cleared_at_once():
    r = Rig()
    r.enable()
    r.select(C1.M_Positioning)
    r.move(10000, 10000, 3000)
    assert not r.has(S2.Busy) and r.has(S2.StandStill)
    r.positioning(10000, 10000, -1000)
    r.c1 |= C1.Start
    r.step()
    assert not r.has(S2.On_Target) and r.has(S2.Busy)
    r.c1 &= ~C1.Start
    r.until(lambda: r.has(S2.On_Target))
    assert r.position == -1000 and r.inp.data[4:7] == bytes([0x18, 0xFC, 0xFF])


def test_on_the_fly_new_target_with_constant_acceleration_is_taken_at_once():
    r = Rig()
    r.enable()
    r.select(C1.M_Positioning)
    r.positioning(10000, 5000, 100000)
    r.start()
    r.step(100)  # still accelerating (a = 125000 microsteps/s^2 up to 20000 microsteps/s)
    v_before = r.dev.velocity_steps
    assert 10000 < v_before < 20000
    r.positioning(2000, 5000, 8000)  # 4000 microsteps/s, a nearer target
    r.record = True
    r.start()
    vs = [v for _, _, v in r.trace]
    assert max(vs) < v_before, "the new, lower speed is taken during the ramp"
    r.until(lambda: r.has(S2.On_Target), 10000)
    assert r.position == 8000
    assert min(v for _, _, v in r.trace) >= 0.0, "no stop on the way: on-the-fly"


def test_on_the_fly_with_linear_ramps_waits_for_constant_speed():
    # Acceleration_Modes 0x11: linear rise (AccType 1) and linear fall (DecType 1), jerk time 300 ms
    r = Rig(Acceleration_Modes=0x11)
    r.enable()
    r.select(C1.M_Positioning)
    r.positioning(10000, 5000, 100000)
    r.start()
    r.step(50)
    assert r.dev._state().a > 0.0
    r.positioning(5000, 5000, 25000)
    r.record = True
    r.start()
    assert r.has(S2.Busy) and not r.has(S2.On_Target)
    r.until(lambda: r.has(S2.On_Target), 10000)
    vs = [v for _, _, v in r.trace]
    # the old ramp ran on to its constant speed (20000) before the new set point was taken
    assert max(vs) == pytest.approx(V20000 / 2, rel=1e-9)
    assert r.position == 25000
    assert min(vs) >= 0.0


def test_start_with_invalid_velocity_or_acceleration_is_an_error():
    for velocity, acceleration, code in ((0, 100, 1117), (25001, 100, 1117), (-5, 100, 1117), (100, 0, 1121), (100, -1, 1121)):
        r = Rig()
        r.enable()
        r.select(C1.M_Positioning)
        r.positioning(velocity, acceleration, 1000)
        r.c1 |= C1.Start
        r.step()
        assert r.error == code and r.has(S2.Error)
        assert not r.has(S1.Ready) and not r.has(S1.Start_ACK)
        assert not r.axis.powered


def test_velocity_above_speed_limit_turns_the_drive_off():
    r = Rig(Speed_Limit=8000)
    r.enable()
    r.select(C1.M_Positioning)
    r.positioning(9000, 100, 1000)
    r.c1 |= C1.Start
    r.step()
    assert r.error == 1212


def test_precalc_latches_the_setpoints_of_its_edge():
    r = Rig()
    r.enable()
    r.select(C1.M_Positioning)
    r.positioning(10000, 10000, 4000)
    r.c2 = C2.PreCalc
    r.step()
    assert r.has(S2.PreCalc_ACK)
    r.positioning(10000, 10000, 9999)  # ignored while PreCalc is 1
    r.move(1, 1, 1)  # also ignored: the start uses the latched set points
    assert r.position == 4000
    r.c2 = 0
    r.step()
    assert not r.has(S2.PreCalc_ACK)


def test_user_units_pos_mult_and_div():
    # wago.md §9.4: Pos_Mult 25, Pos_Div 3: 12 mm are 100 microsteps
    r = Rig(Pos_Mult=25, Pos_Div=3)
    r.enable()
    r.select(C1.M_Positioning)
    r.move(5000, 5000, 12)
    assert r.dev.position_steps == 100 and r.position == 12


def test_acceleration_type_linear_ramp_lasts_v_over_a_plus_jerk_time():
    # AccType 1, AccParam 0: "the period for acceleration increase is Acceleration_RampUp_Param" (300 ms)
    r = Rig(Acceleration_Modes=0x11)
    r.enable()
    r.select(C1.M_Positioning)
    r.positioning(10000, 2000, 200000)  # 20000 microsteps/s, a = 50000 microsteps/s^2
    r.record = True
    r.start()
    r.until(lambda: r.dev.velocity_steps == pytest.approx(V20000 / 2, abs=1e-6), 3000)
    t_ramp = len(r.trace) / 1000.0
    assert t_ramp == pytest.approx(20000 / 50000 + 0.300, abs=0.002)


def test_acceleration_parameter_as_ramp_time():
    # AccType 2 (sin^2), AccParam 1: Acceleration_RampUp_Param is the ramp time (250 ms)
    r = Rig(Acceleration_Modes=0x26 | 0x40, Acceleration_RampUp_Param=250, Acceleration_RampDown_Param=250)
    r.enable()
    r.select(C1.M_Positioning)
    r.positioning(10000, 2000, 12000)
    r.record = True
    r.start()
    r.until(lambda: r.dev.velocity_steps == pytest.approx(V20000 / 2, abs=1e-6), 3000)
    assert len(r.trace) == pytest.approx(250, abs=1)
    r.until(lambda: r.has(S2.On_Target), 20000)
    assert r.position == 12000
    vs = [v for _, _, v in r.trace]
    braking = len(vs) - max(i for i, v in enumerate(vs) if v == pytest.approx(V20000 / 2, abs=1e-6)) - 1
    assert braking == pytest.approx(250, abs=2), "the deceleration lasts Acceleration_RampDown_Param too"


def test_separate_ramp_types_for_acceleration_and_deceleration():
    # AccType linear, DecType constant: two ramp laws in one move (chained kernel ramps)
    r = Rig(Acceleration_Modes=0x01, Acceleration_RampUp=1000, Acceleration_RampDown=4000)
    r.enable()
    r.select(C1.M_Positioning)
    r.record = True
    r.move(10000, 1000, 50000, limit=20000)
    assert r.position == 50000
    p = [x for _, x, _ in r.trace]
    v = [x for _, _, x in r.trace]
    assert max(p) == pytest.approx(50000, abs=1e-6), "no overshoot"
    # the deceleration phase has constant deceleration (second differences constant)
    acc = [(v[i + 1] - v[i]) * 1000 for i in range(len(v) - 1)]
    braking = [a for a in acc if a < -1.0]
    assert braking and max(braking) == pytest.approx(min(braking), rel=0.05)


def test_setup_speed_active_limits_the_speed():
    r = Rig(SetupSpeed=2000)
    r.dev.bits.write(Bit.SetupSpeed_Active, True)  # Ptr_SetupSpeed_Active = MZERO: writable
    r.enable()
    r.select(C1.M_Positioning)
    r.record = True
    r.move(20000, 32767, 4000)
    assert max(v for _, _, v in r.trace) == pytest.approx(2000 * 80 / 40)
    assert r.dev.bits.read(Bit.SetupSpeed_Active_ACK)


def test_brake_released_before_the_move_and_applied_before_the_target():
    # §3.11.4: the Break bit is set at the start; the move waits Braketime_Turn_On; the bit drops
    # Braketime_Turn_Off before the target is reached
    r = Rig(Braketime_Turn_On=20, Braketime_Turn_Off=30)
    r.enable()
    r.select(C1.M_Positioning)
    assert not r.dev.bits.read(Bit.Break)
    r.positioning(10000, 10000, 5000)
    r.c1 |= C1.Start
    r.step()
    assert r.dev.bits.read(Bit.Break) and r.has(S2.Busy)
    assert r.dev.velocity_steps == 0.0
    r.c1 &= ~C1.Start
    waited = r.until(lambda: r.dev.velocity_steps != 0.0, 100)
    assert waited == pytest.approx(20, abs=1)
    r.until(lambda: not r.dev.bits.read(Bit.Break), 5000)
    remaining = r.until(lambda: r.has(S2.On_Target), 5000)
    assert remaining == pytest.approx(30, abs=1)
    # the next move starts at once when the brake is still released? it was applied: wait again
    r.positioning(10000, 10000, 0)
    r.c1 |= C1.Start
    r.step()
    r.c1 &= ~C1.Start
    assert r.until(lambda: r.dev.velocity_steps != 0.0, 100) == pytest.approx(20, abs=1)
