"""The MC720 operator terminal's LCD: display windows over the FS701's process values.

Source: manual §8 "MC720 operator terminal", §8.2 "Display of actual process values"; spec
fs701.md §5.4 and worked example E23 ("4 windows (0-3), 2 values each, 16-char comments,
32 variables 00-31, 5-decade operands"). No GUI: `Mc720Lcd` holds the "LCD Definitions" the
PC software transmits (4 windows x 2 values: comment text, Variable Nr., Decimal point,
xOperand, /Operand, +Operand), the window shown (key F2 cycles them) and renders a window's two
lines from a register map (`RegisterMap.read(0x0800 + Variable Nr.)`, the same process values
the serial link reads; #14/#15 come from the counters 0x0170/0x0171).

    lcd = Mc720Lcd()
    lcd.define(0, 0, LcdValue("actual Speed", variable=2, decimal_point=1))
    lcd.f2()                       # next window
    lcd.render(registers)          # [("actual Speed", "6000.0"), ...] of the window shown

Decisions (spec line -> choice -> why):

* spec §5.4 "[DERIVED] displayed = value x xOp / /Op + +Op (order of operations unspecified)":
  multiply, then divide, then add, in integers: value x xOp is exact, the division truncates
  toward zero (a fixed-point controller's integer division), +Op is added to the scaled value.
  Tests: test_e23_scaling_multiplies_divides_then_adds.
* "5-decade operands": xOperand 0..99999, /Operand 1..99999 (0 would divide by zero),
  +Operand -99999..99999 (an offset may have either sign; the dialog shows 0). Out-of-range
  definitions are refused (LcdError) like an out-of-range parameter.
* "Decimal point: Defines the position where a decimal point should appear on the LCD
  display (0=no decimal point)": the number of digits right of the point, 0..6 (process values
  have 7 digits and a sign, spec §3.11), leading "0." / "-0.0" as needed.
* "max. 16 characters for each text comment": longer comments are refused, not cut; printable
  ASCII only (an LCD character set).
* The definitions are not part of the parameter set / EEPROM image here (the manual gives them
  no serial codes: "click to Transmit to store your definitions to the controller"); the
  unused values #11, #25..#28 may be selected and show 0 (status.py), as in the §8.2
  screenshot example (Nr. 26 and 25) on an FS701.
* spec §5.4 "The keyboard of MC720 allows parameter changes only in the Stop state with the
  carriage in standstill (Start/Stop input LOW, no immediate cut, no Jog)": `keypad_may_edit`.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Protocol

__all__ = [
    "WINDOWS",
    "VALUES_PER_WINDOW",
    "COMMENT_CHARS",
    "VARIABLES",
    "OPERAND_MAX",
    "DECIMALS_MAX",
    "LcdError",
    "LcdValue",
    "LcdWindow",
    "Mc720Lcd",
    "scale",
    "format_value",
    "keypad_may_edit",
]

WINDOWS = 4  # windows 0..3
VALUES_PER_WINDOW = 2
COMMENT_CHARS = 16
VARIABLES = 32  # Variable Nr. 00..31 = process values 0x0800..0x081F
OPERAND_MAX = 99_999  # 5 decades
DECIMALS_MAX = 6
PROCESS_BASE = 0x0800


class LcdError(ValueError):
    """An LCD definition outside the terminal's ranges."""


class _Registers(Protocol):
    def read(self, code: int) -> int: ...


@dataclass(frozen=True, slots=True)
class LcdValue:
    """One value of a window: its comment and the "Variable n" box of the dialog."""

    comment: str = ""
    variable: int = 0
    decimal_point: int = 0
    x_operand: int = 1
    div_operand: int = 1
    plus_operand: int = 0

    def __post_init__(self) -> None:
        if not isinstance(self.comment, str) or len(self.comment) > COMMENT_CHARS:
            raise LcdError(f"comment {self.comment!r}: at most {COMMENT_CHARS} characters")
        if any(not (32 <= ord(ch) < 127) for ch in self.comment):
            raise LcdError(f"comment {self.comment!r}: printable ASCII only")
        _int_in("Variable Nr.", self.variable, 0, VARIABLES - 1)
        _int_in("Decimal point", self.decimal_point, 0, DECIMALS_MAX)
        _int_in("xOperand", self.x_operand, 0, OPERAND_MAX)
        _int_in("/Operand", self.div_operand, 1, OPERAND_MAX)
        _int_in("+Operand", self.plus_operand, -OPERAND_MAX, OPERAND_MAX)

    @property
    def code(self) -> int:
        """The process value's serial code."""
        return PROCESS_BASE + self.variable

    def text(self, raw: int) -> str:
        return format_value(scale(raw, self.x_operand, self.div_operand, self.plus_operand), self.decimal_point)


@dataclass(frozen=True, slots=True)
class LcdWindow:
    values: tuple[LcdValue, ...] = field(default_factory=lambda: (LcdValue(), LcdValue()))

    def __post_init__(self) -> None:
        if len(self.values) != VALUES_PER_WINDOW:
            raise LcdError(f"a window shows {VALUES_PER_WINDOW} values, not {len(self.values)}")


class Mc720Lcd:
    """The four LCD windows of an MC720 and the one shown."""

    def __init__(self) -> None:
        self.windows: list[LcdWindow] = [LcdWindow() for _ in range(WINDOWS)]
        self.shown = 0

    def define(self, window: int, slot: int, value: LcdValue) -> None:
        """Set value `slot` (0/1: "Variable 1"/"Variable 2") of `window` (0..3)."""
        _int_in("window", window, 0, WINDOWS - 1)
        _int_in("value", slot, 0, VALUES_PER_WINDOW - 1)
        vals = list(self.windows[window].values)
        vals[slot] = value
        self.windows[window] = LcdWindow(tuple(vals))

    def f2(self) -> int:
        """Key F2: "Cycle from one window to next" (3 -> 0)."""
        self.shown = (self.shown + 1) % WINDOWS
        return self.shown

    def next_window(self) -> int:
        return self.f2()

    def previous_window(self) -> int:
        self.shown = (self.shown - 1) % WINDOWS
        return self.shown

    def render(self, registers: _Registers, window: int | None = None) -> list[tuple[str, str]]:
        """(comment, value text) of the window shown (or `window`), read from `registers`."""
        w = self.shown if window is None else window
        _int_in("window", w, 0, WINDOWS - 1)
        return [(v.comment, v.text(registers.read(v.code))) for v in self.windows[w].values]


def scale(raw: int, x_operand: int = 1, div_operand: int = 1, plus_operand: int = 0) -> int:
    """raw x xOp / /Op + +Op: multiply, divide (truncating toward zero), add."""
    p = int(raw) * x_operand
    q = abs(p) // div_operand
    return (q if p >= 0 else -q) + plus_operand


def format_value(value: int, decimal_point: int = 0) -> str:
    """The integer with `decimal_point` digits right of the point (0: none)."""
    if decimal_point == 0:
        return str(value)
    sign = "-" if value < 0 else ""
    digits = str(abs(value)).rjust(decimal_point + 1, "0")
    return f"{sign}{digits[:-decimal_point]}.{digits[-decimal_point:]}"


def keypad_may_edit(*, start_stop: bool, immediate_cut: bool, jog: bool, carriage_standstill: bool) -> bool:
    """§8: keypad parameter changes only in Stop with the carriage at standstill."""
    return not start_stop and not immediate_cut and not jog and carriage_standstill


def _int_in(name: str, v: object, lo: int, hi: int) -> None:
    if isinstance(v, bool) or not isinstance(v, int) or not lo <= v <= hi:
        raise LcdError(f"{name} {v!r}: allowed {lo}..{hi}")
