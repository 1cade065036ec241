"""Parker COMPAX XX70 cam controller personality (spec: the project's COMPAX functional specification, docs/compax.md).

Modules (import them directly; this package file only holds the shared error type so that
every module, and the cam operation in ``camop``, raise the same thing):

* ``parameters`` - the cam parameters P30 ... P250 as data, `Parameters` with written /
  armed / valid values and the VP / VC / SETC / LOOP / cycle-end acceptance rules.
* ``cammemory``  - the 5460-word cam memory (formats I, F, B), RESETF, VF with the
  modified-address table, atomic save / load.
* ``curves``     - `CurveRecord`: one curve read from / written to the cam memory, its
  point table, CSV and motion-law import.
* ``ascii``      - the RS232/RS485 ASCII interface (`AsciiEndpoint.feed(bytes) -> bytes`).
* ``status``     - the status values S1, S2, S13/S14, S30, S41 ... S52.
* ``program``    - the program memory: sets N001 ... N250, their commands and grammar.
* ``programrun`` - the interpreter that runs the sets on the cam operation (P210, START/STOP/BREAK).
* ``endpoint``   - the device side of the interface (write enable, storing before the reply,
  the program lines) and the stored files; ``config`` - the [device] table;
  ``preparedcurve`` - a curve made ready for the cam operation; ``camop`` - the cam operation.

Errors
------
Every bad input raises `CompaxError` (a ``ValueError``). ``code`` is the device's error
number where the manual names one (E17 "Curve not present", ...). The supplement numbers
no error for a malformed interface line, an address out of range or a value that does not
fit; those carry axisline's own numbers 101 ... 108 (`INTERFACE_ERRORS`), chosen above the
device's E1 ... E99 so they can never be mistaken for a device error number.
"""

from __future__ import annotations

from typing import Any

__all__ = [
    "CompaxError",
    "UnknownNumberError",
    "DEVICE_ERRORS",
    "INTERFACE_ERRORS",
    "E_TRACKING",
    "E_CURVE_NOT_PRESENT",
    "E_POSITION_INVALID",
    "E_SYNTAX",
    "E_ADDRESS",
    "E_VALUE",
    "E_RESERVED",
    "E_UNKNOWN",
    "E_CAPACITY",
    "E_NOT_AVAILABLE",
    "E_STORE",
]

#: Error numbers the manual names (compax.md §5.1).
E_TRACKING = 10
E_CURVE_NOT_PRESENT = 17
E_POSITION_INVALID = 25

DEVICE_ERRORS: dict[int, str] = {
    10: "Tracking error",
    17: "Curve not present",  # §22: previous meaning "Selected set number not present" retained
    25: "Position invalid",
    65: "E65 (standard meaning not given in the supplement)",
    76: "HEDA synchronization interrupted",
    77: "HEDA transmission error",
    78: "HEDA transmission error",
}

#: axisline's numbers for errors the supplement does not number (see the module doc).
E_SYNTAX = 101
E_ADDRESS = 102
E_VALUE = 103
E_RESERVED = 104
E_UNKNOWN = 105
E_CAPACITY = 106
E_NOT_AVAILABLE = 107
E_STORE = 108

INTERFACE_ERRORS: dict[int, str] = {
    E_SYNTAX: "malformed line",
    E_ADDRESS: "address out of range",
    E_VALUE: "value does not fit",
    E_RESERVED: "address or parameter cannot be written",
    E_UNKNOWN: "unknown parameter or status number",
    E_CAPACITY: "cam memory capacity exceeded",
    E_NOT_AVAILABLE: "command not available",
    E_STORE: "data could not be stored (the line changed nothing)",
}


class CompaxError(ValueError):
    """A COMPAX error: the message names the field, the value and what is allowed.

    ``code``: the error number (device E-number or axisline interface number, see the
    module doc); ``field``, ``value``, ``allowed``: what was wrong, for programs.
    """

    def __init__(
        self,
        message: str,
        *,
        code: int | None = None,
        field: str | None = None,
        value: Any = None,
        allowed: str | None = None,
    ) -> None:
        super().__init__(message)
        self.code = code
        self.field = field
        self.value = value
        self.allowed = allowed

    @property
    def label(self) -> str:
        """``E17`` style label of the error number ('' without one)."""
        return f"E{self.code}" if self.code is not None else ""


class UnknownNumberError(CompaxError, KeyError):
    """A parameter or status number the device does not have (E105); also a KeyError, so
    mapping-style lookups (``n in params``, ``dict.get``-like helpers) treat it as missing."""

    __str__ = ValueError.__str__
