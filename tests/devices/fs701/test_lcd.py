"""The MC720 LCD model (lcd.py), spec §5.4 / manual §8.2, worked example E23."""

from __future__ import annotations

import pytest

from axisline.devices.fs701.lcd import (
    COMMENT_CHARS,
    OPERAND_MAX,
    VALUES_PER_WINDOW,
    VARIABLES,
    WINDOWS,
    LcdError,
    LcdValue,
    LcdWindow,
    Mc720Lcd,
    format_value,
    keypad_may_edit,
    scale,
)
from axisline.devices.fs701.registers import RegisterMap


def test_e23_four_windows_two_values_16_char_comments_32_variables_5_decade_operands():
    """E23 (§8.2) LCD: 4 windows (0-3), 2 values each, 16-char comments, 32 variables 00-31,
    5-decade operands."""
    assert (WINDOWS, VALUES_PER_WINDOW, COMMENT_CHARS, VARIABLES, OPERAND_MAX) == (4, 2, 16, 32, 99_999)
    lcd = Mc720Lcd()
    assert len(lcd.windows) == 4 and all(len(w.values) == 2 for w in lcd.windows)
    # windows 0..3; F2 cycles 0 -> 1 -> 2 -> 3 -> 0
    assert [lcd.f2() for _ in range(4)] == [1, 2, 3, 0]
    assert lcd.previous_window() == 3 and lcd.next_window() == 0
    for bad_window in (-1, 4):
        with pytest.raises(LcdError):
            lcd.define(bad_window, 0, LcdValue())
    with pytest.raises(LcdError):
        lcd.define(0, 2, LcdValue())
    with pytest.raises(LcdError):
        LcdWindow((LcdValue(),))
    # comments: 16 characters, not 17
    LcdValue("x" * 16)
    with pytest.raises(LcdError):
        LcdValue("x" * 17)
    # variables 00..31
    LcdValue(variable=0), LcdValue(variable=31)
    for bad in (-1, 32):
        with pytest.raises(LcdError):
            LcdValue(variable=bad)
    # 5-decade operands
    LcdValue(x_operand=99_999, div_operand=99_999, plus_operand=-99_999)
    for kw in ({"x_operand": 100_000}, {"div_operand": 100_000}, {"div_operand": 0}, {"plus_operand": 100_000}):
        with pytest.raises(LcdError):
            LcdValue(**kw)


def test_e23_windows_show_the_process_values_of_the_register_map():
    regs = RegisterMap()
    regs.status.set_process_value(2, 60_000)  # #2 Line Speed, LU/min (mm/min)
    regs.status.set_process_value(3, -7)  # #3 Position Error
    regs.params.set("batch_counter", 243)  # #14 reads the counter 0x0170
    lcd = Mc720Lcd()
    lcd.define(0, 0, LcdValue("Line m/min", variable=2, decimal_point=1, x_operand=1, div_operand=100))
    lcd.define(0, 1, LcdValue("Pos. Error", variable=3))
    lcd.define(1, 0, LcdValue("Batch", variable=14))
    # the §8.2 screenshot's window 0 on an FS701: Nr. 26 / 25 are unused, they show 0.0
    lcd.define(3, 0, LcdValue("actual Speed", variable=26, decimal_point=1))
    lcd.define(3, 1, LcdValue("Tension Value", variable=25, decimal_point=1))
    assert lcd.render(regs) == [("Line m/min", "60.0"), ("Pos. Error", "-7")]
    lcd.f2()
    assert lcd.render(regs)[0] == ("Batch", "243")
    assert lcd.render(regs, 3) == [("actual Speed", "0.0"), ("Tension Value", "0.0")]


def test_e23_scaling_multiplies_divides_then_adds():
    assert scale(1000, 3, 7, 5) == 3000 // 7 + 5 == 433
    assert scale(-1000, 3, 7, 0) == -428  # truncation toward zero
    assert scale(12345) == 12345
    assert format_value(12345, 1) == "1234.5"
    assert format_value(-5, 2) == "-0.05"
    assert format_value(7, 0) == "7"
    assert LcdValue(decimal_point=3, x_operand=2, plus_operand=-1).text(500) == "0.999"


def test_keypad_edits_only_in_stop_at_standstill():
    assert keypad_may_edit(start_stop=False, immediate_cut=False, jog=False, carriage_standstill=True)
    assert not keypad_may_edit(start_stop=True, immediate_cut=False, jog=False, carriage_standstill=True)
    assert not keypad_may_edit(start_stop=False, immediate_cut=True, jog=False, carriage_standstill=True)
    assert not keypad_may_edit(start_stop=False, immediate_cut=False, jog=True, carriage_standstill=True)
    assert not keypad_may_edit(start_stop=False, immediate_cut=False, jog=False, carriage_standstill=False)
