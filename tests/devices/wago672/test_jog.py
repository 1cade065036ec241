"""JogMode and SteppingMode (manual §3.11.1.6, §3.11.3; wago.md §2.5, §7.6; decisions D2-D4 in device.py)."""

from __future__ import annotations

import pytest

from axisline.devices.wago672.bits import Bit
from axisline.devices.wago672.image import C1, C3, S1, S2

from .rig import Rig

SETUP = 3000 * 80 / 40  # SetupSpeed 3000 -> 6000 microsteps/s; SetupAcceleration 1000 -> 25000 microsteps/s^2


def jog_rig(**values) -> Rig:
    r = Rig(**values)
    r.enable()
    r.select(C1.M_Jog)
    return r


def test_jog_input3_runs_positive_at_setup_speed_and_release_ramps_down():
    r = jog_rig()
    r.inputs["Input3"] = True  # Jog_Pos (DI3)
    r.step()
    assert r.has(S2.Busy) and not r.has(S2.On_Target)
    n = r.until(lambda: r.has(S2.On_Speed), 1000)
    assert n == pytest.approx(SETUP / 25000 * 1000, abs=2)
    assert r.velocity == 3000 and r.has(S2.Direction)
    r.inputs["Input3"] = False
    n = r.until(lambda: r.has(S2.StandStill), 1000)
    assert n == pytest.approx(SETUP / 25000 * 1000, abs=2), "release ramps down with SetupAcceleration"
    assert not r.has(S2.Busy) and not r.has(S2.On_Target)


def test_jog_by_direction_bits_and_both_directions_turn_the_drive_off():
    r = jog_rig()
    r.c3 = C3.Direction_Neg
    r.until(lambda: r.has(S2.On_Speed), 1000)
    assert r.dev.velocity_steps < 0
    r.c3 = C3.Direction_Neg | C3.Direction_Pos  # "locked against each other"
    r.until(lambda: r.has(S2.StandStill), 1000)
    r.step(20)
    assert r.dev.velocity_steps == 0.0 and r.error == 0
    r.c3 = C3.Direction_Pos  # still held: must be released first
    r.step(20)
    assert r.dev.velocity_steps == 0.0
    r.c3 = 0
    r.step()
    r.c3 = C3.Direction_Pos
    r.until(lambda: r.dev.velocity_steps > 0, 10)


def test_start_in_jog_mode_is_ignored():
    # D2, wago.md §2.5 [CONFLICT] "Start bit in JogMode": no Start_ACK, no error, no motion
    r = jog_rig()
    r.c1 |= C1.Start
    r.step(5)
    assert not r.has(S1.Start_ACK) and r.error == 0 and r.dev.velocity_steps == 0.0
    r.c1 &= ~C1.Start
    r.inputs["Input4"] = True
    r.until(lambda: r.dev.velocity_steps < 0, 5)


def test_setup_speed_zero_jogs_at_speed_1():
    r = jog_rig(SetupSpeed=0)
    r.inputs["Input3"] = True
    r.until(lambda: r.has(S2.On_Speed), 100)
    assert r.dev.velocity_steps == pytest.approx(1 * 80 / 40)


def test_limit_switch_stops_jog_and_only_the_way_back_is_allowed():
    r = jog_rig()
    r.inputs["Input5"] = lambda: r.x >= 1000  # positive limit switch
    r.inputs["Input3"] = True
    r.until(lambda: r.has(S2.StandStill) and r.x > 900, 3000)
    assert r.dev.bits.read(Bit.Err_Range) and r.error == 0
    r.inputs["Input3"] = False
    r.step()
    r.inputs["Input3"] = True  # toward the switch again: no motion
    r.step(20)
    assert r.dev.velocity_steps == 0.0
    r.inputs["Input3"] = False
    r.inputs["Input4"] = True  # away from it
    r.until(lambda: r.dev.velocity_steps < 0, 5)
    # leaving the limit switch the drive stops again (§3.11.3.1), then runs freely after a new press
    r.until(lambda: r.has(S2.StandStill), 3000)
    assert r.x < 1000
    r.step(10)
    assert r.dev.velocity_steps == 0.0
    r.inputs["Input4"] = False
    r.step()
    r.inputs["Input4"] = True
    r.until(lambda: r.x < 0, 3000)


def test_software_limits_stop_jog_and_a_repeated_jog_goes_outside():
    r = jog_rig(Drive_Range_Pos=1000)
    r.inputs["Input3"] = True
    r.until(lambda: r.has(S2.StandStill) and r.x > 1000, 3000)
    assert r.dev.bits.read(Bit.Err_Range_Pos) and r.error == 0
    stopped = r.x
    r.step(10)
    assert r.x == stopped, "held until the jog key is pressed again"
    r.inputs["Input3"] = False
    r.step()
    r.inputs["Input3"] = True  # a repeated JOG command: outside the range
    r.until(lambda: r.x > stopped + 500, 2000)
    r.inputs["Input3"] = False
    r.until(lambda: r.has(S2.StandStill), 2000)
    r.inputs["Input4"] = True
    r.until(lambda: r.x < 900, 3000)
    assert not r.dev.bits.read(Bit.Err_Range_Pos), "back inside the range"


def test_stepping_mode_timeout_ends_the_run():
    r = jog_rig()
    r.dev.stepping_timeout_ms = 100
    r.inputs["Input3"] = True
    r.step(100)
    assert r.dev.velocity_steps > 0
    r.until(lambda: r.has(S2.StandStill), 1000)
    r.step(50)
    assert r.dev.velocity_steps == 0.0, "a new press is needed"
