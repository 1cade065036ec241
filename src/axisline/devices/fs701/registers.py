"""FS701 register map: parameters, process values, commands, outputs and status words by serial code.

Source: manual §11 (the register lists), §4.1 (command inputs from the PC), §4.2..§4.4 (register
cards: "Read", "Transmit Single", "Transmit All", "Store EEPROM"); spec fs701.md §3.13, §2.20, §6.

Address map (serial codes, spec §3.13)::

    0x0000-0x001F  General parameters (3 used, the rest "(Parameter nn)": read 0, accept only 0)
    0x0100-0x011F  Basic Settings
    0x0120-0x013F  Control Loop
    0x0140-0x015F  Jog / Home / Ref
    0x0160-0x017F  Monitoring (Batch / Waste Counter at 0x0170 / 0x0171)
    0x0180-0x019F  Additional Cuts
    0x02C0-0x02DF  Communication ("(Block 15 8)".. reserved)
    0x02E0-0x02FF  Set-Up
    0x0800-0x081F  Process data, read only
    0x0900-0x091F  Single commands: bit n of "Serial Commands" (0x090E does not exist: Print Mark)
    0x0A00-0x0A1F  Single outputs: bit n of "Output Status", read only
    0x0B00-0x0B05  Hardware / Serial / CAN / All Commands, Output Status, Error Status
                   (only 0x0B01 "Serial Commands" is writable over the serial link)

`RegisterMap` reads and writes by code, as raw integers (`read`/`write`), engineering values
(`read_value`/`write_value`) or the text the unit sends (`read_text`/`write_text`). Every write
is checked first and then stored, so a refused write changes nothing. `display_text` gives the
OS5.1 screen form ("+0.00", "001000", "-000100").

Value text on the serial link ("as the unit sends it"): the raw register value in decimal, a
"-" for negative values, no "+", no leading zeros, no decimal point: the decimals are implied
by the register ("+/- Sync Rate" 1.50 % is sent as "150", "I Time" 0.030 s as "30"). A write
may give the value the same way, with an optional "+" and leading zeros, or with the decimal
point and exactly the register's number of decimals ("1.50" for Sync Rate).

EEPROM (§2.20, §4.1.1 "Store to EEProm"): the rising edge of command bit 29 (from any source:
hardware, serial or CAN, the OR) copies all parameters - counters included - and the I/O
assignment to the EEPROM image (`RegisterMap.eeprom`); `power_cycle()` restores it. Counters
therefore lose what they counted since the last store ("Counter will not automatically be saved
to the EEPROM upon power-down!").

Modbus holding registers (`MODBUS_MAP`; served later by fieldbus/, no sockets here)::

    address = 2 x serial code, 2 registers (32 bit), two's complement for signed registers,
              high word first ("big-endian word order"), raw value with the register's implied
              decimals (Sync Rate 1.50 % = 150), exactly as on the serial link;
    exception: Batch Counter 0x0170, Waste Counter 0x0171 and their read-only copies 0x080E,
              0x080F count up to 9 999 999 999 (34 bits): 4 registers (64 bit, high word
              first) at 0x1800, 0x1804, 0x1808, 0x180C; their 2 x code slots are not mapped.

Reads may start and end anywhere inside mapped entries; writes must cover whole entries (a
32-bit value is never half written); an unmapped address is Modbus exception 2, a refused
value exception 3 (`ModbusError.exception_code`).

Decisions (spec line -> choice -> why):

* spec §6 "Parameter values are decimal with fixed implied decimals per register": the wire
  value is the raw integer (see above); a decimal point is accepted on writes only with the
  register's exact number of decimals, so "1" for Sync Rate is never mistaken for 1.00 %.
* spec §2.20 EEPROM: see above; the store is edge-triggered on All Commands bit 29 (a level
  held HIGH stores once); `service()` detects the edge and is called after every serial
  command write and by the device once per cycle after it updated the hardware/CAN words.
* spec §2.2 / §6 error clearing from the register side: `service()` also applies the rising
  edge of "Clear Error" and the falling edge of "Control Enable" to the status image (the
  device may do the same; clearing is idempotent).
* "Adjust Program" / "Test Program" (bits 30/31) "Control Enable must be OFF": a write that
  sets either while Control Enable is ON (All Commands bit 0), or that sets one while the other
  is active, is refused (CommandRefusedError; NAK on the serial link).
* Reading a single command 0x0900+n returns the *serial* command bit (the "RS" column of the
  I/O card); the effective state is in 0x0B03.
* Reserved registers inside the described blocks ("(Parameter nn)", "(Block 15 nn)",
  "(Command nn)", "(Output nn)", process values #11, #25..#28) exist: they read 0; reserved
  parameters accept only 0 (their §11 range is 0..0); unused commands store their bit, which has
  no effect. Codes outside the blocks (e.g. 0x01A0..0x02BF, 0x090E, 0x0B06) are unknown.
* Process values #14/#15 (Read Batch/Waste Count) are read from 0x0170/0x0171.
* The I/O assignment has no serial codes; `set_io_assignment` changes it and writes it to the
  EEPROM image at once, as the IO Definition card does when it is left (§4.1.3).
* Display form: digits = digits of the larger range limit, sign shown for signed registers
  and for Maximum/Alarm Position (the §4.3.3 screenshot shows "+010000", "+009000"),
  process values as sign + 7 digits ("+0000000", §4.4 screenshot).
"""

from __future__ import annotations

import re
from collections.abc import Callable, Iterable
from dataclasses import dataclass
from typing import Any, Final

from .io_assign import (
    COMMAND_BASE,
    INPUT_FUNCTIONS,
    OUTPUT_BASE,
    OUTPUT_SIGNALS,
    SERIAL_COMMAND_MASK,
    EdgeDetector,
    Edges,
    IOAssignment,
)
from .parameters import BLOCKS, PARAMETERS_BY_CODE, Parameter, ParameterError, ParameterSet
from .status import (
    COUNTER_MIRRORS,
    ERRORS,
    PROCESS_VALUES,
    STATUS_WORDS,
    ClearReason,
    StatusImage,
)

__all__ = [
    "RegisterKind",
    "Register",
    "REGISTERS",
    "REGISTERS_BY_CODE",
    "register",
    "RegisterError",
    "UnknownRegisterError",
    "ReadOnlyRegisterError",
    "RegisterRangeError",
    "RegisterFormatError",
    "CommandRefusedError",
    "format_wire",
    "parse_wire",
    "format_display",
    "parse_display",
    "EepromImage",
    "RegisterMap",
    "register_table_markdown",
]

INT32_MIN, INT32_MAX = -(2**31), 2**31 - 1
MAX_TEXT = 16  # longest value text accepted (sign + 10 digits + point + slack)


class RegisterKind:
    PARAMETER: Final = "parameter"
    RESERVED: Final = "reserved"
    PROCESS: Final = "process value"
    COMMAND: Final = "command"
    OUTPUT: Final = "output"
    STATUS: Final = "status word"


@dataclass(frozen=True, slots=True)
class Register:
    code: int
    name: str
    attr: str
    kind: str
    writable: bool
    minimum: int  # raw
    maximum: int  # raw
    decimals: int = 0
    unit: str = ""
    description: str = ""
    display_digits: int = 0  # digits on the OS5.1 screen (0: from the range)
    display_sign: bool = False

    @property
    def signed(self) -> bool:
        return self.minimum < 0

    @property
    def parameter(self) -> Parameter | None:
        return PARAMETERS_BY_CODE.get(self.code) if self.kind == RegisterKind.PARAMETER else None


def _build() -> tuple[Register, ...]:
    regs: list[Register] = []
    # parameter blocks, every one of the 32 codes
    for block in BLOCKS.values():
        for i, code in enumerate(block.codes):
            p = PARAMETERS_BY_CODE.get(code)
            if p is not None:
                regs.append(
                    Register(code, p.name, p.attr, RegisterKind.PARAMETER, True, p.minimum, p.maximum, p.decimals,
                             p.unit, p.description, display_sign=p.signed or code in (0x0142, 0x0143))
                )  # fmt: skip
            else:
                name = f"(Block 15 {i})" if block.key == "communication" else f"(Parameter {i:02d})"
                regs.append(
                    Register(code, name, f"{block.key}_reserved_{i:02d}", RegisterKind.RESERVED, True, 0, 0, 0, "",
                             "Not in use (§11 range 0..0).")
                )  # fmt: skip
    for pv in PROCESS_VALUES:
        lo, hi = (0, 9_999_999_999) if pv.code in COUNTER_MIRRORS else (INT32_MIN, INT32_MAX)
        regs.append(
            Register(pv.code, pv.name, pv.attr, RegisterKind.PROCESS, False, lo, hi, 0, pv.unit, pv.explanation,
                     display_digits=7, display_sign=True)
        )  # fmt: skip
    for f in INPUT_FUNCTIONS:
        if f.code is not None:
            regs.append(Register(f.code, f.name, f.attr, RegisterKind.COMMAND, True, 0, 1, 0, "", f.description))
    for s in OUTPUT_SIGNALS:
        regs.append(Register(s.code, s.name, s.attr, RegisterKind.OUTPUT, False, 0, 1, 0, "", s.description))
    for w in STATUS_WORDS:
        hi = 0xFFFF if w.bits == "errors" else 0xFFFF_FFFF
        regs.append(Register(w.code, w.name, w.attr, RegisterKind.STATUS, w.serial_writable, 0, hi, 0, "", w.description))
    regs.sort(key=lambda r: r.code)
    return tuple(regs)


REGISTERS: tuple[Register, ...] = _build()
REGISTERS_BY_CODE: dict[int, Register] = {r.code: r for r in REGISTERS}


# --------------------------------------------------------------------------------------------
# errors


class RegisterError(Exception):
    """A register access the FS701 refuses (the serial link answers NAK)."""

    def __init__(self, code: int | None, message: str) -> None:
        self.code = code
        super().__init__(message)


class UnknownRegisterError(RegisterError, LookupError):
    pass


class ReadOnlyRegisterError(RegisterError):
    pass


class RegisterRangeError(RegisterError, ValueError):
    pass


class RegisterFormatError(RegisterError, ValueError):
    pass


class CommandRefusedError(RegisterError):
    pass


def register(code: int) -> Register:
    if isinstance(code, bool) or not isinstance(code, int):
        raise UnknownRegisterError(None, f"register code must be an int, got {code!r}")
    try:
        return REGISTERS_BY_CODE[code]
    except KeyError:
        raise UnknownRegisterError(code, f"no FS701 register at serial code 0x{code:04X} ({code})") from None


def _range_text(reg: Register) -> str:
    return f"{format_wire(reg, reg.minimum)}..{format_wire(reg, reg.maximum)} (raw)"


def _check_range(reg: Register, raw: object) -> int:
    if isinstance(raw, bool) or not isinstance(raw, int):
        raise RegisterFormatError(reg.code, f"{reg.name} (0x{reg.code:04X}): value {raw!r} is not an integer raw value")
    p = reg.parameter
    if p is not None:
        try:
            p.check_raw(raw)
        except ParameterError as exc:
            raise RegisterRangeError(reg.code, str(exc)) from None
        return raw
    if not reg.minimum <= raw <= reg.maximum:
        raise RegisterRangeError(
            reg.code, f"{reg.name} (0x{reg.code:04X}): value {raw} is outside the allowed range {_range_text(reg)}"
        )
    return raw


# --------------------------------------------------------------------------------------------
# value text

_WIRE = re.compile(r"[+-]?[0-9]+(?:\.[0-9]+)?")


def format_wire(reg: Register | int, raw: int) -> str:
    """The value text the unit sends: raw decimal, "-" if negative, no leading zeros."""
    return str(int(raw))


def parse_wire(reg: Register | int, text: str) -> int:
    """Raw value of a value text (see module doc). Raises RegisterFormatError."""
    r = reg if isinstance(reg, Register) else register(reg)
    if not isinstance(text, str) or len(text) > MAX_TEXT or not _WIRE.fullmatch(text):
        raise RegisterFormatError(r.code, f"{r.name} (0x{r.code:04X}): {text!r} is not a value text (digits, optional sign)")
    if "." in text:
        decimals = len(text.split(".", 1)[1])
        if decimals != r.decimals:
            raise RegisterFormatError(
                r.code,
                f"{r.name} (0x{r.code:04X}): {text!r} has {decimals} decimals; the register has {r.decimals}"
                + (" (send the raw integer)" if r.decimals == 0 else ""),
            )
        text = text.replace(".", "")
    return int(text)


def format_display(reg: Register | int, raw: int) -> str:
    """The value as the OS5.1 register card shows it ("+0.00", "001000", "-000100", "010.17")."""
    r = reg if isinstance(reg, Register) else register(reg)
    digits = r.display_digits or max(len(str(abs(r.minimum))), len(str(abs(r.maximum))), r.decimals + 1)
    body = f"{abs(raw):0{digits}d}"
    if r.decimals:
        body = f"{body[: -r.decimals]}.{body[-r.decimals :]}"
    if r.display_sign or r.signed:
        return ("-" if raw < 0 else "+") + body
    return ("-" if raw < 0 else "") + body


def parse_display(reg: Register | int, text: str) -> int:
    """Raw value of a display form (inverse of format_display; leading zeros and "+" allowed)."""
    r = reg if isinstance(reg, Register) else register(reg)
    return parse_wire(r, text.strip())


# --------------------------------------------------------------------------------------------
# the register map


@dataclass
class EepromImage:
    """What "Store to EEProm" saves: all parameters (counters included) and the I/O assignment."""

    params: ParameterSet
    io: IOAssignment


_BIT_CE = 1 << 0  # Control Enable
_BIT_CLEAR = 1 << 7  # Clear Error
_BIT_STORE = 1 << 29  # Store to EEProm
_BIT_ADJUST = 1 << 30
_BIT_TEST = 1 << 31


class RegisterMap:
    """All registers of one FS701 over its ParameterSet, StatusImage and IOAssignment."""

    def __init__(
        self,
        params: ParameterSet | None = None,
        status: StatusImage | None = None,
        io: IOAssignment | None = None,
    ) -> None:
        self.params = params if params is not None else ParameterSet()
        self.status = status if status is not None else StatusImage()
        self.io = io if io is not None else IOAssignment.default()
        self.eeprom = EepromImage(self.params.copy(), self.io.copy())
        self.store_count = 0
        #: called with the EepromImage after every store (the device persists it)
        self.on_store: list[Callable[[EepromImage], None]] = []
        self._edges = EdgeDetector(self.status.all_commands)

    # ---- lookup ---------------------------------------------------------------------------
    @staticmethod
    def register(code: int) -> Register:
        return register(code)

    def __contains__(self, code: object) -> bool:
        return code in REGISTERS_BY_CODE

    # ---- reads ----------------------------------------------------------------------------
    def read(self, code: int) -> int:
        """Raw value of a register."""
        reg = register(code)
        kind = reg.kind
        if kind == RegisterKind.PARAMETER:
            return self.params.get_raw(code)
        if kind == RegisterKind.RESERVED:
            return 0
        if kind == RegisterKind.PROCESS:
            mirror = COUNTER_MIRRORS.get(code)
            return self.params.get_raw(mirror) if mirror is not None else self.status.process_value(code)
        if kind == RegisterKind.COMMAND:
            return self.status.serial_commands >> (code - COMMAND_BASE) & 1
        if kind == RegisterKind.OUTPUT:
            return self.status.output_status >> (code - OUTPUT_BASE) & 1
        return self.status.word(code)

    def read_value(self, code: int) -> int | float:
        """Engineering value (decimals applied)."""
        reg = register(code)
        raw = self.read(code)
        return raw if reg.decimals == 0 else raw / 10**reg.decimals

    def read_text(self, code: int) -> str:
        """The value text the unit sends for a read request."""
        return format_wire(register(code), self.read(code))

    def display_text(self, code: int) -> str:
        return format_display(register(code), self.read(code))

    # ---- writes ---------------------------------------------------------------------------
    # (raw values typed `object`: a value of the wrong type gets RegisterFormatError, also
    # when this module is compiled, where an `int` argument would be a TypeError at the call)
    def check_write(self, code: int, raw: object) -> Register:
        """Raise the error a write would raise; changes nothing."""
        return self._checked(code, raw)[0]

    def _checked(self, code: int, raw: object) -> tuple[Register, int]:
        """The register and the raw value a write would store, or the error it would raise."""
        reg = register(code)
        if not reg.writable:
            raise ReadOnlyRegisterError(code, f"{reg.name} (0x{code:04X}) is read only")
        value = _check_range(reg, raw)
        if reg.kind == RegisterKind.COMMAND:
            self._check_serial_word(self._with_bit(code - COMMAND_BASE, value), reg)
        elif reg.kind == RegisterKind.STATUS:
            self._check_serial_word(value, reg)
        return reg, value

    def write(self, code: int, raw: object) -> None:
        """Write a raw value; refused writes raise and change nothing."""
        reg, value = self._checked(code, raw)
        if reg.kind == RegisterKind.PARAMETER:
            self.params.set_raw(code, value)
        elif reg.kind == RegisterKind.COMMAND:
            self.status.serial_commands = self._with_bit(code - COMMAND_BASE, value)
            self.service()
        elif reg.kind == RegisterKind.STATUS:  # 0x0B01
            self.status.serial_commands = value
            self.service()
        # reserved parameters: 0 accepted, nothing stored

    def write_value(self, code: int, value: Any) -> None:
        """Write an engineering value (1.5 for Sync Rate 1.50 %)."""
        reg = register(code)
        p = reg.parameter
        if p is not None:
            try:
                raw = p.to_raw(value)
            except ParameterError as exc:
                raise RegisterRangeError(code, str(exc)) from None
        else:
            raw = value
        self.write(code, raw)

    def write_text(self, code: int, text: str) -> None:
        """Write a value text (serial link)."""
        reg = register(code)
        if not reg.writable:
            raise ReadOnlyRegisterError(code, f"{reg.name} (0x{code:04X}) is read only")
        self.write(code, parse_wire(reg, text))

    def write_many(self, values: Iterable[tuple[int, object]]) -> None:
        """Write several raw values ("Transmit All", a Modbus FC16) as one: the state they
        produce together is checked before any is stored, so a refused write changes nothing.

        Command bits (0x0900 + n) and Serial Commands (0x0B01) are folded into the one word
        they produce, and that word is checked (Adjust/Test Program need Control Enable OFF
        and exclude each other): checked one by one, an Adjust bit written before a refused
        Test bit was already set, and the Adjust program started. Parameters are stored first,
        then the word, with one service() for its edges (a Store to EEProm in the same write
        stores the new parameters)."""
        probe_params = self.params.copy()
        params: list[tuple[int, int]] = []
        word = self.status.serial_commands
        word_reg: Register | None = None  # the last register that changed the word (for errors)
        for code, raw in values:
            reg = register(code)
            if not reg.writable:
                raise ReadOnlyRegisterError(code, f"{reg.name} (0x{code:04X}) is read only")
            value = _check_range(reg, raw)
            if reg.kind == RegisterKind.PARAMETER:
                probe_params.set_raw(code, value)
                params.append((code, value))
            elif reg.kind == RegisterKind.COMMAND:
                bit = 1 << (code - COMMAND_BASE)
                word = word | bit if value else word & ~bit
                word_reg = reg
            elif reg.kind == RegisterKind.STATUS:  # 0x0B01
                word = value
                word_reg = reg
            # reserved parameters: 0 accepted, nothing stored
        if word_reg is not None:
            self._check_serial_word(word, word_reg)
        for code, value in params:
            self.params.set_raw(code, value)
        if word_reg is not None:
            self.status.serial_commands = word
            self.service()

    def _with_bit(self, bit: int, on: int) -> int:
        word = self.status.serial_commands
        return word | (1 << bit) if on else word & ~(1 << bit)

    def _check_serial_word(self, word: int, reg: Register) -> None:
        if word & ~SERIAL_COMMAND_MASK:
            raise RegisterRangeError(reg.code, f"{reg.name} (0x{reg.code:04X}): bit 14 (Print Mark) has no serial command")
        new = word & ~self.status.serial_commands & (_BIT_ADJUST | _BIT_TEST)
        if not new:
            return
        others = self.status.hardware_commands | self.status.can_commands | word
        if others & _BIT_CE:
            raise CommandRefusedError(reg.code, f"{reg.name} (0x{reg.code:04X}): Adjust/Test Program needs Control Enable OFF")
        if others & _BIT_ADJUST and others & _BIT_TEST:
            raise CommandRefusedError(reg.code, f"{reg.name} (0x{reg.code:04X}): Adjust and Test Program cannot run together")

    # ---- device side ----------------------------------------------------------------------
    def needs_service(self, hardware_word: int) -> bool:
        """Whether `set_hardware_commands(hardware_word)` would see anything new: the hardware
        word or All Commands changed since the last service (the cycle asks every 1 ms)."""
        st = self.status
        if st.hardware_commands != hardware_word:
            return True
        return (hardware_word | st.serial_commands | st.can_commands) != self._edges.last

    def set_hardware_commands(self, word: object) -> Edges:
        """The device's hardware command word (0x0B00, from IOAssignment.hardware_command_word)."""
        if isinstance(word, bool) or not isinstance(word, int) or not 0 <= word <= 0xFFFF_FFFF:
            raise RegisterRangeError(0x0B00, f"Hardware Commands {word!r} is not a 32-bit word")
        self.status.hardware_commands = word
        return self.service()

    def set_can_commands(self, word: object) -> Edges:
        if isinstance(word, bool) or not isinstance(word, int) or not 0 <= word <= 0xFFFF_FFFF:
            raise RegisterRangeError(0x0B02, f"CAN Commands {word!r} is not a 32-bit word")
        self.status.can_commands = word
        return self.service()

    def service(self) -> Edges:
        """Register-side reactions to edges of All Commands since the last call:
        Store to EEProm (rising), Clear Error (rising), Control Enable (falling)."""
        edges = self._edges.update(self.status.all_commands)
        if edges.rising & _BIT_CLEAR:
            self.status.clear_errors(ClearReason.CLEAR_ERROR)
        if edges.falling & _BIT_CE:
            self.status.clear_errors(ClearReason.CONTROL_ENABLE_OFF)
        if edges.rising & _BIT_STORE:  # last: a store that fails raises, the other edges are applied
            self.store_to_eeprom()
        return edges

    def set_io_assignment(self, io: IOAssignment) -> None:
        """A new I/O assignment, stored to the EEPROM at once: "The input/output assignment is
        stored to EEPROM when leaving this register card" (§4.1.3); parameters are not stored."""
        self.io.assign(io)
        self.eeprom = EepromImage(self.eeprom.params, self.io.copy())

    def store_to_eeprom(self) -> None:
        """Copy parameters and I/O assignment to the EEPROM image; `on_store` persists it. A
        callback that raises (the file cannot be written) leaves the previous image."""
        previous = self.eeprom
        self.eeprom = EepromImage(self.params.copy(), self.io.copy())
        try:
            for callback in self.on_store:
                callback(self.eeprom)
        except BaseException:
            self.eeprom = previous
            raise
        self.store_count += 1

    def power_cycle(self) -> None:
        """Power off/on: parameters and I/O assignment from the EEPROM, status reset."""
        self.params.assign(self.eeprom.params)
        self.io.assign(self.eeprom.io)
        self.status.power_cycle()
        self._edges.reset(self.status.all_commands)

    # ---- views ----------------------------------------------------------------------------
    def dump(self, kinds: Iterable[str] = (RegisterKind.PARAMETER,)) -> dict[int, int]:
        """{code: raw} of the registers of the given kinds."""
        wanted = set(kinds)
        return {r.code: self.read(r.code) for r in REGISTERS if r.kind in wanted}

    def errors_text(self) -> list[str]:
        return [ERRORS[n].message for n in range(6) if self.status.error_status >> n & 1]


def register_table_markdown() -> str:
    lines = ["| Code | Name | Kind | R/W | Range (raw) | Decimals | Unit |", "|---|---|---|---|---|---|---|"]
    for r in REGISTERS:
        lines.append(
            f"| 0x{r.code:04X} | {r.name} | {r.kind} | {'RW' if r.writable else 'R'} | {r.minimum}..{r.maximum} | "
            f"{r.decimals} | {r.unit} |"
        )
    return "\n".join(lines) + "\n"
