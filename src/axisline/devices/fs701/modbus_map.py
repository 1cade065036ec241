"""The FS701's Modbus holding registers (registers.py describes the register map): each
parameter or status register at its 0-based address, 32-bit values as two words high word
first (a few 64-bit ones as four), reads and writes through the `RegisterMap`.
"""

from __future__ import annotations

import bisect
from collections.abc import Callable, Iterable
from dataclasses import dataclass

from .registers import REGISTERS, CommandRefusedError, ReadOnlyRegisterError, RegisterError, RegisterMap, UnknownRegisterError

__all__ = ["MODBUS_WIDE_BASE", "ModbusEntry", "MODBUS_MAP", "modbus_entry", "ModbusError", "encode_words", "decode_words", "modbus_read", "modbus_write", "ModbusImage", "modbus_table_markdown"]


MODBUS_WIDE_BASE = 0x1800
_WIDE_CODES = (0x0170, 0x0171, 0x080E, 0x080F)


@dataclass(frozen=True, slots=True)
class ModbusEntry:
    address: int  # first holding register (0-based protocol address)
    words: int  # 2 (32 bit) or 4 (64 bit), high word first
    code: int  # serial code
    name: str
    attr: str
    signed: bool
    decimals: int
    writable: bool

    @property
    def end(self) -> int:
        return self.address + self.words


def _build_modbus() -> tuple[ModbusEntry, ...]:
    out = []
    for r in REGISTERS:
        if r.code in _WIDE_CODES:
            address, words = MODBUS_WIDE_BASE + 4 * _WIDE_CODES.index(r.code), 4
        else:
            address, words = 2 * r.code, 2
        out.append(ModbusEntry(address, words, r.code, r.name, r.attr, r.signed, r.decimals, r.writable))
    out.sort(key=lambda e: e.address)
    return tuple(out)


MODBUS_MAP: tuple[ModbusEntry, ...] = _build_modbus()
_MB_STARTS = [e.address for e in MODBUS_MAP]
_MB_BY_CODE = {e.code: e for e in MODBUS_MAP}


class ModbusError(RegisterError):
    """exception_code: 2 illegal data address, 3 illegal data value, 4 refused by the device."""

    def __init__(self, exception_code: int, message: str, code: int | None = None) -> None:
        self.exception_code = exception_code
        super().__init__(code, message)


def modbus_entry(address: int) -> ModbusEntry:
    """The entry holding a register address; ModbusError(2) if unmapped."""
    i = bisect.bisect_right(_MB_STARTS, address) - 1
    if i >= 0 and MODBUS_MAP[i].address <= address < MODBUS_MAP[i].end:
        return MODBUS_MAP[i]
    raise ModbusError(2, f"Modbus holding register {address} (0x{address:04X}) is not mapped")


def modbus_entry_of_code(code: int) -> ModbusEntry:
    try:
        return _MB_BY_CODE[code]
    except KeyError:
        raise UnknownRegisterError(code, f"no FS701 register at serial code 0x{code:04X}") from None


def encode_words(value: int, words: int, signed: bool = True) -> list[int]:
    """A value as `words` 16-bit registers, high word first (two's complement if signed)."""
    bits = 16 * words
    if signed:
        if not -(1 << (bits - 1)) <= value < 1 << (bits - 1):
            raise ValueError(f"{value} does not fit {bits} signed bits")
        value &= (1 << bits) - 1
    elif not 0 <= value < 1 << bits:
        raise ValueError(f"{value} does not fit {bits} unsigned bits")
    return [(value >> (16 * (words - 1 - i))) & 0xFFFF for i in range(words)]


def decode_words(regs: Iterable[int], signed: bool = True) -> int:
    value = 0
    n = 0
    for w in regs:
        value = value << 16 | (w & 0xFFFF)
        n += 1
    if signed and value >= 1 << (16 * n - 1):
        value -= 1 << (16 * n)
    return value


def modbus_read(regmap: RegisterMap, address: int, count: int) -> list[int]:
    """`count` holding registers from `address`; every address must be mapped."""
    if not 1 <= count <= 125:
        raise ModbusError(3, f"register count {count} is outside 1..125")
    out: list[int] = []
    addr = address
    while addr < address + count:
        e = modbus_entry(addr)
        words = encode_words(regmap.read(e.code), e.words, e.signed)
        take = min(e.end, address + count) - addr
        start = addr - e.address
        out.extend(words[start : start + take])
        addr += take
    return out


def modbus_write(regmap: RegisterMap, address: int, values: list[int]) -> None:
    """Write whole entries from `address`; all are checked before any is written."""
    if not 1 <= len(values) <= 123:
        raise ModbusError(3, f"register count {len(values)} is outside 1..123")
    for v in values:
        if isinstance(v, bool) or not isinstance(v, int) or not 0 <= v <= 0xFFFF:
            raise ModbusError(3, f"register value {v!r} is not 0..65535")
    staged: list[tuple[int, int]] = []
    addr, i = address, 0
    while i < len(values):
        e = modbus_entry(addr)
        if e.address != addr or i + e.words > len(values):
            raise ModbusError(
                3, f"write at 0x{addr:04X} must cover the whole {16 * e.words}-bit entry 0x{e.address:04X}..0x{e.end - 1:04X} ({e.name})"
            )
        staged.append((e.code, decode_words(values[i : i + e.words], e.signed)))
        addr += e.words
        i += e.words
    # one handler: compiled, a name bound in several `except ... as` clauses keeps the first
    # clause's type
    try:
        regmap.write_many(staged)
    except RegisterError as exc:
        exception = 2 if isinstance(exc, ReadOnlyRegisterError) else 4 if isinstance(exc, CommandRefusedError) else 3
        raise ModbusError(exception, str(exc), exc.code) from None


class ModbusImage:
    """The register image for a Modbus server (fieldbus/); `writes_allowed` may be a callable."""

    def __init__(self, regmap: RegisterMap, writes_allowed: bool | Callable[[], bool] = True) -> None:
        self.regmap = regmap
        self.writes_allowed = writes_allowed

    def read_registers(self, kind: str, address: int, count: int) -> list[int]:
        if kind not in ("holding", "input"):
            raise ModbusError(1, f"register kind {kind!r} is not served (holding, input)")
        return modbus_read(self.regmap, address, count)

    def write_registers(self, address: int, values: list[int]) -> None:
        allowed = self.writes_allowed() if callable(self.writes_allowed) else self.writes_allowed
        if not allowed:
            raise ModbusError(4, "writes from the network are not enabled")
        modbus_write(self.regmap, address, values)


# --------------------------------------------------------------------------------------------
# documentation


def modbus_table_markdown() -> str:
    lines = [
        "| Holding register | Words | Type | Serial code | Name | Decimals | R/W |",
        "|---|---|---|---|---|---|---|",
    ]
    for e in MODBUS_MAP:
        t = f"{'int' if e.signed else 'uint'}{16 * e.words}"
        lines.append(
            f"| {e.address} (0x{e.address:04X}) | {e.words} | {t}, high word first | 0x{e.code:04X} | {e.name} | "
            f"{e.decimals} | {'RW' if e.writable else 'R'} |"
        )
    return "\n".join(lines) + "\n"
