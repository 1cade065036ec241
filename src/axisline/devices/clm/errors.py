"""The CLM1.4's own error codes, and the one error type every CLM parser raises.

Two numbering schemes, kept apart because the manual keeps them apart (errata §1.7):

* fault codes (chapter 11, Fig. 11-2; spec §7.2) are **hex**, two digits: ``0A`` "Invalid Prg
  Cmd", ``32`` "Variable Value", ``38`` "Logic Prg. Error". The display, Status 53, the polling
  reply ``:snn`` and B018 show them.
* serial transmission errors (Status 01, spec §8.5) are **decimal**: ``04`` "RS Checksum Error",
  ``12`` "Block # too large" (sent as 0x0C over Profibus). axisline writes them ``X01:nn`` (the
  status number they arrive in, then the number) wherever both kinds can appear in one list,
  so that fault 02 (invalid parameter) and Status 01 error 02 (format) cannot be confused.

`ClmError` carries the code, the CLM's text and where the fault is (an instruction number, a
parameter, a Logic Task instruction, a variable): the same three things the CLM shows (F1 key:
``NC Instr : 0110``, ``LT Instr :``, ``Variable : 0620``; Status 60).
"""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["FAULTS", "SERIAL_ERRORS", "ClmError", "Finding", "axis_fault", "serial_code"]

# Fig. 11-2 (L8540-8760) with the B018 long names where the display text is missing (spec §7.2).
FAULTS: dict[str, str] = {
    "00": "no error",
    "01": "no error (Parameter mode)",
    "02": "INVALID Parameter",
    "03": "EMERGENCY STOP",
    "04": "Battery is low",
    "05": "Parameters lost",
    "06": "Program lost",
    "07": "Division by zero",
    "08": "Invalid Mode",
    "0A": "Invalid Prg Cmd",
    "0B": "JSR Nesting",
    "0C": "RTS Nesting",
    "0D": "BCD Input error",
    "0E": "Invalid Block #",
    "10": "System Failure",
    "11": "System Failure (cycle overrun)",
    "12": "IDS Break-Error",
    "13": "IDS Checksum Err",
    "14": "IDS Char Format",
    "15": "IDS data string too long",
    "16": "Axis No. false",
    "17": "Hardw. Axis 3 & 4",
    "18": "wrong CLM hardware",
    "19": "CLM +/- 15 Volts",
    "1A": "REP Command",
    "1B": "SAC Command",
    "1D": "Command I/O",
    "1E": "VCC Command",
    "1F": "Var. No. illegal",
    "30": "Inc. Enc. 5 faulty",
    "31": "Write Sys.-Var.",
    "32": "Variable Value",
    "33": "Fieldbus",
    "34": "Fieldbus Init",
    "35": "Missing EOS Cmd",
    "36": "Not Homeposition",
    "37": "Fieldbus Timeout",
    "38": "Logic Prg. Error",
    "39": "Logic Prg. Lost",
    "3A": "Index Length",
    "3B": "Rapid Stop",
    "3C": "Max Stroke Limit",
    "3D": "I/O-No. illegal",
}
for _axis in range(4):
    FAULTS[f"{0x2C + _axis:02X}"] = f"Inc. Enc. {_axis + 1} faulty"

# Axis faults: base 0x40 / 0x70 / 0xA0 / 0xD0 for axes 1-4 plus the offset (spec §7.2).
_AXIS_BASE = (0x40, 0x70, 0xA0, 0xD0)
_AXIS_FAULTS = {
    0x00: "Drive {x} not ready",
    0x01: "Feed Angle Loss {x}",
    0x02: "Drive Runaway A{x}",
    0x03: "Excess Pos Lag {x}",
    0x04: "Abs. Enc. Error {x}",
    0x05: "Abs. Range Error {x}",
    0x06: "Min Travel Lmt {x}",
    0x07: "Max Travel Lmt {x}",
    0x08: "Axis {x} not Homed",
    0x09: "Cam too short {x}",
    0x0A: "No marker pulse {x}",
    0x0B: "Mrkr Pulse Pos A{x}",
    0x0C: "Encoder Fault A{x}",  # axes 1 and 2 only
    0x0D: "Max. Override A{x}",
    0x0E: "A{x} not enabled",
    0x0F: "Marker high A{x}",
    0x10: "Target Pos < Lim {x}",
    0x11: "Target Pos > Lim {x}",
    0x12: "HOM Command A{x}",
}
for _axis, _base in enumerate(_AXIS_BASE, start=1):
    for _offset, _text in _AXIS_FAULTS.items():
        if _offset == 0x0C and _axis > 2:
            continue
        FAULTS[f"{_base + _offset:02X}"] = _text.format(x=_axis)

# Status 01 (spec §8.5): decimal numbers, texts exactly as the CLM sends them (20 characters).
SERIAL_ERRORS: dict[int, str] = {
    1: "RS Block # Wrong",
    2: "RS Format Error",
    3: "RS Block Data Error",
    4: "RS Checksum Error",
    5: "Invalid Mode",
    6: "Wrong RS Param #",
    7: "Param. # too large",
    8: "Wrong RS Status #",
    9: "Status # illegal",
    10: "M-Wheel Param Error",
    11: "Invalid Param Block",
    12: "Block # too large",
    13: "Invalid Prg Command",
    16: "Value too large",
    18: "Not accepted",
    23: "Wrong Variable #",
    25: "Invalid Operand",
}


def serial_code(number: int) -> str:
    """The printed form of a Status 01 error: ``X01:04``."""
    return f"X01:{number:02d}"


def axis_fault(offset: int, axis: int) -> str:
    """The hex code of an axis fault: ``axis_fault(0x08, 2)`` -> ``'78'`` (Axis 2 not Homed)."""
    return f"{_AXIS_BASE[axis - 1] + offset:02X}"


class ClmError(ValueError):
    """A CLM input refused with the CLM's own code.

    ``code`` is a fault code (``'0A'``, ``'32'``) or a Status 01 error (``'X01:04'``);
    ``detail`` says what exactly was wrong (field, value, allowed range); ``where`` is the
    place (``'N0102'``, ``'A123'``, ``'LT0007'``, ``'V620'``) when the parser knows it.
    """

    def __init__(self, code: str, detail: str, where: str | None = None) -> None:
        self.code = code
        self.detail = detail
        self.where = where
        self.out_of_range = False  # a well-formed number outside its field's range
        super().__init__(self.message)

    @property
    def text(self) -> str:
        """The CLM's own text for the code."""
        if self.code.startswith("X01:"):
            return SERIAL_ERRORS.get(int(self.code[4:]), "")
        return FAULTS.get(self.code, "")

    @property
    def message(self) -> str:
        head = f"{self.where} " if self.where else ""
        return f"{head}{self.code} {self.text}: {self.detail}" if self.text else f"{head}{self.code} {self.detail}"

    def at(self, where: str) -> ClmError:
        """The same error placed at `where` (a parser that knows the line adds it)."""
        if self.where is None:
            self.where = where
            self.args = (self.message,)
        return self


@dataclass(frozen=True)
class Finding:
    """One line of `axisline clm check`: where, the CLM code, the text; errors and warnings."""

    where: str
    code: str
    text: str
    severity: str = "error"  # "error" | "warning"
    source: str = ""  # file:line the finding comes from

    @classmethod
    def of(cls, error: ClmError, where: str | None = None, severity: str = "error", source: str = "") -> Finding:
        text = f"{error.text}: {error.detail}" if error.text else error.detail
        return cls(error.where or where or "-", error.code, text, severity, source)

    @property
    def is_error(self) -> bool:
        return self.severity == "error"

    def __str__(self) -> str:
        mark = "" if self.is_error else " (warning)"
        at = f" [{self.source}]" if self.source else ""
        return f"{self.where} {self.code} {self.text}{mark}{at}"
