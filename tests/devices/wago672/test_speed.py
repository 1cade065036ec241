"""Speed control (manual §3.11.1.11; wago.md §2.9, §7.8; decisions D1, D11, D12 in device.py)."""

from __future__ import annotations

import pytest

from axisline.devices.wago672.bits import Bit
from axisline.devices.wago672.image import C1, S2

from .rig import Rig

SPEED_MODE = C1.M_Positioning | C1.M_Program  # "Command[]=3"


def speed_rig(**values) -> Rig:
    r = Rig(**values)
    r.enable()
    r.select(SPEED_MODE)
    assert r.inp.command_ack == 3
    return r


def test_speed_control_runs_up_busy_until_reached_then_on_speed():
    r = speed_rig()
    r.speed(5000, 2000)  # 10000 microsteps/s, 50000 microsteps/s^2
    r.start()
    assert r.has(S2.Busy) and not r.has(S2.On_Target)
    n = r.until(lambda: not r.has(S2.Busy), 2000)
    assert n == pytest.approx(200, abs=3)
    assert r.has(S2.On_Speed) and r.has(S2.On_Target) and r.velocity == 5000
    p = r.dev.position_steps
    r.step(100)
    assert r.dev.position_steps == pytest.approx(p + 1000), "keeps running at the speed"


def test_speed_change_on_the_fly_and_reversal():
    r = speed_rig()
    r.speed(5000, 5000)
    r.start()
    r.until(lambda: r.has(S2.On_Speed), 2000)
    r.speed(-2000, 5000)
    r.start()
    assert r.has(S2.Busy)
    r.until(lambda: r.has(S2.On_Speed), 2000)
    assert r.velocity == -2000 and not r.has(S2.Direction)
    r.speed(0, 5000)
    r.start()
    r.until(lambda: r.has(S2.StandStill), 2000)
    assert not r.has(S2.Busy)


def test_position_wraps_with_the_implicit_period_100000():
    r = speed_rig(Freq_Div=4)  # f = 20 * v: 25000 -> 500000 microsteps/s
    r.speed(25000, 32767)
    r.start()
    positions = []
    for _ in range(300):
        r.step()
        positions.append(r.position)
    assert max(positions) < 100000 and min(positions) >= 0
    assert any(b < a for a, b in zip(positions, positions[1:])), "the actual value wrapped"
    assert r.error == 0


def test_speed_control_with_rotary_axis_period():
    r = speed_rig(Rotary_Axis_Period=5000)
    r.speed(10000, 32767)
    r.start()
    r.step(500)
    assert 0 <= r.position < 5000 and r.dev.position_steps > 5000


def test_limit_switch_in_speed_control_brakes():
    r = speed_rig()
    r.inputs["Input5"] = lambda: r.x >= 2000
    r.speed(5000, 5000)
    r.start()
    r.until(lambda: r.has(S2.StandStill), 3000)
    assert r.x >= 2000 and r.dev.bits.read(Bit.Err_Range) and r.error == 0


def test_velocity_out_of_range_is_1117():
    r = speed_rig()
    r.speed(-25001, 100)
    r.c1 |= C1.Start
    r.step()
    assert r.error == 1117
