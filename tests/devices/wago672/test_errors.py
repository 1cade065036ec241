"""Errors and warnings: table, error memory, Error_Quit, S0.ERR, LEDs (manual §3.12, §4.4; wago.md §8, §1.7)."""

from __future__ import annotations

import pytest

from axisline.devices.wago672.bits import Bit
from axisline.devices.wago672.errors import (
    ERRORS,
    ErrorClass,
    ErrorMemory,
    blink_sequence,
    blink_signal,
    err_flag,
    error_class,
)
from axisline.devices.wago672.image import C1, C2, C3, S0, S1, S2, S3
from axisline.motion.axis import AxisState

from .rig import Rig


def test_error_table_holds_the_manual_codes_with_their_classes():
    assert ERRORS[1413].name == "PARTMODL_CURRENT_TIME"
    assert ERRORS[1431].name == "PROT_REF_DIR" and ERRORS[1931].name == "PARTMODL_LIMITSWITCH"
    assert ERRORS[1115].name == "CI_COMMAND_DENIED" and ERRORS[1123].name == "CI_ROTARY_AXIS_PERIOD_SETPOINT"
    assert error_class(1413) is ErrorClass.ACKNOWLEDGE and error_class(2821) is ErrorClass.WARM_START
    assert error_class(3112) is ErrorClass.FATAL and error_class(5893) is ErrorClass.WARNING
    assert all(code in ERRORS for code in (1112, 1117, 1121, 1351, 1354, 1358, 1361, 1451, 1452, 1453, 1454, 1455, 1511, 1517, 1557, 1815, 1816, 1894, 2821, 5887))
    assert len(ERRORS) >= 224


def test_error_memory_keeps_the_first_error_and_the_cause_decides_the_acknowledge():
    m = ErrorMemory()
    present = [True]
    assert m.raise_code(1358, cause=lambda: present[0])
    assert not m.raise_code(1117)  # one error code only
    assert m.error == 1358
    m.acknowledge()
    assert m.error == 1358, "the cause is still there: the error is set again"
    present[0] = False
    m.acknowledge()
    assert m.error == 0
    m.raise_code(5893)
    assert m.warning == 5893 and m.error == 0 and m.code == 5893
    m.raise_code(3112)
    assert not m.acknowledge() and m.error == 3112
    m.clear()
    m.raise_code(2821)
    assert m.acknowledge(), "a 2xxx error asks for a warm start"


def test_err_flag_follows_the_notification_modes_and_error_quit():
    assert not err_flag(0x06, 0x18, True, True, False), "default: ERR not enabled"
    assert err_flag(0x07, 0x18, True, False, False)
    assert not err_flag(0x07, 0x18, False, True, False)
    assert err_flag(0x06, 0x19, False, True, False)
    assert not err_flag(0x07, 0x19, True, True, True), "not while Error_Quit is set"


def test_blink_code_of_1413():
    # wago.md §9.12: 10 Hz burst, then 1 blink, pause, 4 blinks, pause, 1 blink, pause, 3 blinks
    seq = blink_sequence(1413)
    burst = seq[:20]
    assert all(d == 50 for _, d in burst) and [lvl for lvl, _ in burst[:2]] == [True, False]
    digits, count = [], 0
    for level, d in seq[21:]:
        if level:
            count += 1
        elif d == 1000:
            digits.append(count)
            count = 0
    assert digits == [1, 4, 1, 3]
    assert blink_signal(1413, 0) and not blink_signal(1413, 50) and not blink_signal(0, 0)


def test_error_set_raises_1358_output_stage_off_and_error_quit_after_the_cause():
    r = Rig()
    r.enable()
    r.select(C1.M_Positioning)
    r.positioning(10000, 32767, 50000)
    r.start()
    r.step(50)
    r.dev.config.set(221, Bit.ONE)  # Error_Set linked to ONE: the error is present
    r.step()
    assert r.error == 1358 and r.has(S2.Error) and r.dev.outputs == (False, True)
    assert not r.has(S1.Ready) and r.s1 & 0xF8 == 0, "Ready and the mode ACK drop at once"
    assert r.axis.state is AxisState.DISABLED
    r.c2 = C2.Error_Quit
    r.step()
    assert r.error == 1358, "cause still present: error set again"
    r.c2 = 0
    r.dev.config.set(221, Bit.ZERO)
    r.step()
    r.c2 = C2.Error_Quit
    r.step()
    assert r.error == 0 and r.has(S1.Ready) and r.axis.powered
    r.c2 = 0
    r.step()
    assert r.has(S1.M_Positioning_ACK), "the mode bit still set: selected again"


def test_start_while_error_quit_is_set_is_1361():
    r = Rig()
    r.enable()
    r.select(C1.M_Positioning)
    r.c2 = C2.Error_Quit
    r.c1 |= C1.Start
    r.step()
    assert r.error == 1361


def test_s0_err_when_enabled_by_error_notification_mode():
    r = Rig(ErrorNotificationMode=0x07)
    r.enable()
    r.c1 |= C1.Start  # no mode: 1351
    r.step()
    assert r.error == 1351 and r.has(S0.ERR)
    r.c2 = C2.Error_Quit
    r.step()
    assert not r.has(S0.ERR) and r.error == 0


def test_output_stage_temperature_error_or_warning():
    r = Rig()
    r.enable()
    r.dev.environment["stage_temperature"] = 75.0  # above Warn_Treshold_Temperature 70.0 degC
    r.step()
    assert r.error == 1894, "ErrorNotificationMode bit 1 (default): as an error"
    r = Rig(ErrorNotificationMode=0x04, WarningNotificationMode=0x1A)
    r.enable()
    r.dev.environment["stage_temperature"] = 75.0
    r.step()
    assert r.error == 0 and r.dev.errors.warning == 5893 and r.has(S3.Warning) and r.has(S1.Ready)
    r.dev.environment["stage_temperature"] = 60.0
    r.c2 = C2.Error_Quit
    r.step()
    assert not r.has(S3.Warning)


def test_dc_link_voltage_outside_the_limits():
    r = Rig()
    r.enable()
    r.dev.environment["dc_link_voltage"] = 12.0
    r.step()
    assert r.error == 1816
    r = Rig()
    r.dev.environment["dc_link_voltage"] = 81.0
    r.step()
    assert r.error == 1815


def test_boost_current_at_standstill_trips_1413_after_10_s():
    # Current_Ratio_StandStill 150 % of 5.0 A = 7.5 A: the thermal model allows 10 s (wago.md §9.6)
    r = Rig(Current_Ratio_StandStill=150)
    r.enable()
    assert r.dev.phase_current == pytest.approx(7.5)
    n = r.until(lambda: r.error != 0, 10100)
    assert r.error == 1413 and n == pytest.approx(10000, abs=3)
    assert r.dev.state_variable(21) == 255 and not r.axis.powered and r.dev.phase_current == 0.0
    r.c2 = C2.Error_Quit
    r.step()
    assert r.error == 1413, "the model must cool down first"
    r.c2 = 0
    r.step(100)
    assert r.dev.state_variable(21) < 255


def test_warm_start_error_is_acknowledged_by_a_warm_start():
    r = Rig()
    r.enable()
    r.c3 = C3.Reset_Quit
    r.step()
    r.c3 = 0
    r.dev.raise_error(2821, "CONFIG_RESTORE without warm start")
    r.step()
    assert r.error == 2821 and not r.has(S3.Reset)
    r.c2 = C2.Error_Quit
    r.step()
    assert r.error == 0 and r.has(S3.Reset) and r.has(S1.Ready)


def test_leds():
    r = Rig()
    r.enable()
    leds = r.dev.leds()
    assert leds["D"] and leds["I"] and not leds["A"] and not leds["B"]
    r.select(C1.M_Positioning)
    r.positioning(10000, 32767, 5000)
    r.start()
    assert r.dev.leds()["B"], "LED B = Busy"
    r.dev.raise_error(1117)
    r.step()
    assert r.dev.leds()["A"] and r.dev.leds()["H"]
