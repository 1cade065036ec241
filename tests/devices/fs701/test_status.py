"""FS701 process values, status words, errors 00..05, LEDs (manual §4.4, §5, §6, §11; spec fs701.md §3.11, §3.12, §5)."""

from __future__ import annotations

import pytest

from axisline.devices.fs701.status import (
    ERRORS,
    PROCESS_VALUES,
    STATUS_WORDS,
    ClearReason,
    LedScale,
    StatusError,
    StatusImage,
    led_pattern,
    process_value,
)


def test_process_values_of_section_11():
    assert [v.code for v in PROCESS_VALUES] == list(range(0x0800, 0x0820))
    named = [v.name for v in PROCESS_VALUES if not v.reserved]
    assert named == [
        "Length Counter", "Master Frequency", "Line Speed", "Position Error", "Feed Forw. Value", "Correction Value",
        "Integral Value", "Carriage Cut Pos", "Car. travel dist.", "Carriage Abs.Pos", "Act. Cut Length",
        "Min. Pos. Error", "Max. Pos. Error", "Read Batch Count", "Read Waste Count", "Length Cou. Sheet",
        "Prm. Delay Length", "Printm. Pos. Cou.", "Miss. Printm. Cou.", "Printmark Status", "Virt. Printmarks",
        "Ptr. Write Printm.", "Ptr. Read Printm.", "Printmark Buffer", "Control State", "Cut State", "Test Counter",
    ]  # fmt: skip
    assert [v.number for v in PROCESS_VALUES if v.reserved] == [11, 25, 26, 27, 28]
    assert process_value("position_error").code == 0x0803 == process_value(3).code == process_value(0x0803).code
    assert [w.code for w in STATUS_WORDS] == list(range(0x0B00, 0x0B06))


def test_error_table_and_behaviour_of_section_6():
    assert [(n, e.bit, e.name) for n, e in ERRORS.items()] == [
        (0, 0, "DPRAM Error"), (1, 1, "Power Low"), (2, 2, "Cut not possible"), (3, 3, "Limit switch"),
        (4, 4, "Printmark buffer"), (5, 5, "Value Range Exceed"),
    ]  # fmt: skip
    assert not ERRORS[0].stops_machine and ERRORS[0].severity == "display"
    assert all(ERRORS[n].stops_machine and ERRORS[n].sets_error_output for n in range(1, 6))
    assert ERRORS[0].cleared_by == {ClearReason.POWER_CYCLE} and ERRORS[1].self_clearing


def test_error_00_is_display_only_and_clears_only_by_power_cycle():
    s = StatusImage()
    s.raise_error(0)
    assert s.error_status == 1 and not s.error_output and not s.stop_requested
    for reason in (ClearReason.CLEAR_ERROR, ClearReason.CONTROL_ENABLE_OFF, ClearReason.RESET_BUTTON):
        assert s.clear_errors(reason) == [] and s.error_status == 1
    assert s.leds(0, hardware_outputs=0b1, time_s=0.7) == (True, False, False, False, False, False)  # no flashing
    s.power_cycle()
    assert s.error_status == 0


def test_error_01_clears_itself_and_returns_while_the_voltage_is_low():
    s = StatusImage()
    s.set_error_cause(1, True)
    assert s.error_output and s.stop_requested
    assert s.clear_errors() == [] and s.error_status == 2  # "immediately return to the error state"
    s.set_error_cause(1, False)
    assert s.error_status == 0 and not s.output("error")


def test_event_errors_clear_and_persistent_causes_return():
    s = StatusImage()
    s.raise_error(2)
    s.raise_error(4)
    assert s.error_messages() == ["Error 02: Cut not possible", "Error 04: Printmark Buffer"]
    assert s.output_status == 1 << 7
    assert s.clear_errors(ClearReason.CONTROL_ENABLE_OFF) == [2, 4] and s.output_status == 0
    s.set_error_cause(5, True)  # encoder ratio beyond 16:1
    s.clear_errors()
    assert s.error_status == 1 << 5
    s.set_error_cause(5, False)  # parameters corrected: latched until cleared
    assert s.error_status == 1 << 5
    assert s.clear_errors(ClearReason.RESET_BUTTON) == [5]
    with pytest.raises(StatusError):
        s.raise_error(6)
    with pytest.raises(StatusError):
        s.clear_errors("shout")


def test_error_output_bit_is_owned_by_the_error_logic():
    s = StatusImage()
    s.set_outputs(0xFF)
    assert s.output_status == 0x7F
    s.raise_error(3)
    assert s.output_status == 0xFF and s.output("error")
    s.set_output("home", False)
    assert not s.output("home")


def test_process_values_are_checked():
    s = StatusImage()
    s.set_process_value("line_speed", 123_456)
    assert s.process_value(0x0802) == 123_456
    with pytest.raises(StatusError, match="32-bit"):
        s.set_process_value("length_counter", 2**31)
    with pytest.raises(StatusError, match="0x0170"):
        s.set_process_value("read_batch_count", 5)
    with pytest.raises(StatusError, match="reserved"):
        s.set_process_value(0x080B, 5)
    with pytest.raises(StatusError):
        s.set_process_value("nonsense", 1)
    with pytest.raises(StatusError):
        s.update_process_values({"line_speed": 1, "position_error": 1.5})
    assert s.process_value("line_speed") == 123_456  # all or nothing
    s.update_process_values({"line_speed": 1, "position_error": -3})
    assert (s.process_value("line_speed"), s.process_value("position_error")) == (1, -3)


def test_command_words_are_ored():
    s = StatusImage()
    s.hardware_commands = 0b001
    s.serial_commands = 0b010
    s.can_commands = 0b100
    assert s.all_commands == 0b111 and s.word(0x0B03) == 0b111 and s.command(2)
    with pytest.raises(StatusError):
        s.serial_commands = 1 << 14


def test_leds_fs701_md_7_e20():
    # LED Function 0: outputs Out1..Out6 left to right
    assert led_pattern(0, hardware_outputs=0b10_0101) == (True, False, True, False, False, True)
    # LED Function 1: centre for 0, right for lag (+), left for lead (-)
    bar = {e: led_pattern(1, position_error=e).index(True) for e in (-100, -32, -9, -8, -1, 1, 8, 9, 32, 33)}
    assert bar == {-100: 0, -32: 1, -9: 1, -8: 2, -1: 2, 1: 3, 8: 3, 9: 4, 32: 4, 33: 5}
    assert led_pattern(1, position_error=0) == (False, False, True, True, False, False)
    # an error: all flash at about 1 Hz, whatever LED Function says
    assert led_pattern(1, flashing=True, time_s=0.25) == (True,) * 6
    assert led_pattern(0, flashing=True, time_s=0.75) == (False,) * 6
    assert led_pattern(0, flashing=True, time_s=1.25) == (True,) * 6
    s = StatusImage()
    s.set_process_value("position_error", 20)
    assert s.leds(1) == (False, False, False, False, True, False)
    s.raise_error(2)
    assert s.leds(1, time_s=0.1) == (True,) * 6
    assert led_pattern(1, position_error=3, scale=LedScale(2, 4)).index(True) == 4
    with pytest.raises(StatusError):
        LedScale(5, 5)
    with pytest.raises(StatusError):
        led_pattern(2)


def test_snapshot():
    s = StatusImage()
    s.set_output("ready", True)
    snap = s.snapshot()
    assert snap["outputs_on"] == ["ready"] and "value_11" not in snap["process"]  # type: ignore[operator]
