"""The COMPAX XX70 cam memory: 5460 addresses of 24 bits (compax.md §2.21, §6; manual §25).

    from axisline.devices.compax.cammemory import CamMemory
    mem = CamMemory()                    # delivery state: curve 1 = straight line, gradient 1
    mem.write("F", 6, 0.1234567)         # set point 1 (F format, fraction of S_T)
    mem.read("F", 6)                     # 0.12345671... (the stored 24-bit value)
    mem.write("B", 7, (1, 10, 246))      # aux function of set point 1: digital; analogue 0; analogue 1
    mem.vf()                             # declare valid: the cam operation now sees the change
    mem.save("cam.json"); CamMemory.load("cam.json")

Organisation (§25 "Organization of the Cam Memory")
---------------------------------------------------
* address 1: number of curves (I0001); addresses 2 ... 5: reserved for status information;
* set point k (1-based, over the whole memory): position F(4 + 2k) at the even addresses
  from 6, auxiliary function B(5 + 2k) at the odd addresses from 7;
* control block of curve c (1-based): 20 addresses downward from 5460 - 20·(c - 1), field
  i at that base minus i (`CONTROL_BLOCK`, the table of §25): curve 1 is I5460 ... F5441,
  curve 2 I5440 ... F5421.
* set points and control blocks must not overlap: highest set point L and C curves need
  2·L + 20·C <= 5455 (`check_capacity`).

Formats (§25 "Number formats", compax.md §6.2)
----------------------------------------------
* I: 24-bit integer, two's complement: -8 388 608 ... 8 388 607 (1024 -> 00 04 00).
* F: 24-bit fraction, Fx = Ix / 2^23, -1 <= Fx < 1 (0.99999999 -> 7F FF FF,
  -0.00000001 -> FF FF FF). Encoding and decoding are `axisline.motion.cam`'s
  `encode_fraction` / `decode_fraction` (floor, as the manual's table requires).
* B: three 8-bit numbers "digital;analogue 0;analogue 1", each an 8-bit two's complement
  (0 ... 255, or -128 ... -1 for the upper half), stored MSB = analogue 1, middle =
  analogue 0, LSB = digital outputs (128;0;0 -> 00 00 80, 1;1;128 -> 80 01 01).

The memory holds raw words; the format letter says how a value is converted ("The
argument must be of the corresponding format", read as: the value must be of the format
its letter names). Any format may be read from any address.

Written and valid (RESETF, VF)
------------------------------
Writes go to the memory (the Zero-Power-RAM, `words()`); the cam operation works with the
valid copy (`words(valid=True)`, the DSP's), which only VF updates: "After having changed
the cam memory it must be declared as valid by VF." The memory keeps a table of modified
addresses, 20 entries at most; VF transfers only those, or the whole memory when the table
is full or empty ("If, at the time of the VF command, there is no modification in the cam
memory, the entire VF (ca. 0.5s) is executed"). RESETF sets the whole memory to 0.

Every write is all-or-nothing: a bad address or a value that does not fit raises
`CompaxError` (E102 address, E103 value, E104 reserved) and the memory is unchanged.
`write_words` writes many addresses at once, validating all of them first.

Decisions (spec line -> choice, why)
------------------------------------
1. §0 "With curve 1 COMPAX contains a straight line with gradient 1. The remaining curve
   parameters are 0." [GAP: no cycle lengths given]: I0001 = 1; curve 1 with
   M_T = S_T = 360 (the manual's example cycle and the default P98) and two set points
   0 and 0.9999999 (= S_T), i.e. slave = master; all other words 0.
2. §6.2 I format [GAP: signedness]: two's complement like F and B (S48's -8388608 = -2^23
   is the same range), so -8 388 608 ... 8 388 607.
3. §25 "The 5 addresses below are reserved for status informations" + "Under address 1
   ... the number of curves": addresses 2 ... 5 are read-only (E104); address 1 takes the
   I format only, 0 ... 100 (max. 100 curves, §9 SETC).
4. "The argument must be of the corresponding format" (see above): the value must match
   its format letter; addresses carry no fixed format (the boundary between set points
   and control blocks moves with the number of curves), except address 1.
5. §25 modified-address table [GAP: what counts as a modification]: every write access
   enters its address (distinct addresses; the device cannot be assumed to compare). The
   21st distinct address fills the table: the next VF transfers the whole memory.
6. [GAP] RESETF clears the memory; like any change it needs VF to reach the valid copy
   (the next VF is a full one). Durations: RESETF 1 s, full VF 0.5 s (the manual's
   "up to"); an accelerated VF takes 0.5 s · entries / 5460 (the same rate per word).
7. [GAP] persistence: the Zero-Power-RAM is what survives a power cut, so `save` writes
   the memory (not the valid copy, not the table); `load` is a power-on: the valid copy is
   the whole stored memory, the table empty.
8. B values: 0 ... 255 or -128 ... -1 per byte (both notations of an 8-bit two's
   complement; the manual writes 255 and 128); read back as 0 ... 255.
"""

from __future__ import annotations

import json
import os
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from enum import Enum
from typing import Any

from axisline.devices.compax import E_ADDRESS, E_CAPACITY, E_RESERVED, E_VALUE, CompaxError
from axisline.kernel.atomic import atomic_write_text
from axisline.motion.cam import FRACTION_ONE, decode_fraction, encode_fraction

__all__ = [
    "BLOCK_SIZE",
    "CAPACITY",
    "CONTROL_BLOCK",
    "DELIVERY_CYCLE",
    "FIRST_SET_POINT_ADDRESS",
    "FULL_SCALE",
    "MAX_CURVES",
    "MAX_POINTS_PER_CURVE",
    "RESERVED_ADDRESSES",
    "SIZE",
    "BlockField",
    "CamMemory",
    "Fmt",
    "VfResult",
    "aux_address",
    "block_address",
    "block_base",
    "check_capacity",
    "decode_bytes",
    "decode_int",
    "encode_bytes",
    "encode_int",
    "format_fraction",
    "fraction_value",
    "fraction_word",
    "set_point_address",
]

SIZE = 5460
FIRST_SET_POINT_ADDRESS = 6
BLOCK_SIZE = 20
#: Addresses 6 ... 5460 hold set points, aux functions and control blocks.
CAPACITY = SIZE - FIRST_SET_POINT_ADDRESS + 1  # 5455
MAX_CURVES = 100  # §9 SETC: "max. 100 curves with 2 set points each"
MAX_POINTS_PER_CURVE = 2500  # §3: "a sequence of up to 2500 set points"
RESERVED_ADDRESSES = range(2, 6)
#: The largest F word; it stands for the full cycle (S_T, or M_T for master-related fields).
FULL_SCALE = FRACTION_ONE - 1  # 0x7FFFFF
DELIVERY_CYCLE = 360

_WORD = 0xFFFFFF
_INT_MIN, _INT_MAX = -(1 << 23), (1 << 23) - 1
RESETF_DURATION_S = 1.0
VF_FULL_DURATION_S = 0.5
MODIFIED_TABLE_SIZE = 20



MAX_MEMORY_FILE_BYTES = 4 << 20  # a saved memory (5460 values as JSON) is about 33 kB

class Fmt(str, Enum):
    """Number format letter of an address access (§25)."""

    I = "I"  # noqa: E741 - the manual's letter
    F = "F"
    B = "B"


@dataclass(frozen=True, slots=True)
class BlockField:
    """One field of a control block: address = block base - offset."""

    offset: int
    fmt: Fmt
    significance: str
    attr: str | None  # CurveRecord attribute (None: part of a compound value or unused)
    ref: str  # "M": fraction of M_T, "S": fraction of S_T, "M/S": of the label cycle, "": none


#: The control-block table of §25 ("Storage of Curve Number 1"), offsets 0 ... 15; 16 ... 19 are unused.
CONTROL_BLOCK: tuple[BlockField, ...] = (
    BlockField(0, Fmt.I, "Master cycle integer", None, ""),
    BlockField(1, Fmt.F, "Master cycle fractional", None, ""),
    BlockField(2, Fmt.I, "Number of 1st set point", "first_point", ""),
    BlockField(3, Fmt.I, "Number of last set point", "last_point", ""),
    BlockField(4, Fmt.I, "Slave cycle integer", None, ""),
    BlockField(5, Fmt.F, "Slave cycle fractional", None, ""),
    BlockField(6, Fmt.F, "Coupling position", "coupling", "M"),
    BlockField(7, Fmt.F, "Synchronous position", "synchronous", "M"),
    BlockField(8, Fmt.F, "Decoupling position", "decoupling", "M"),
    BlockField(9, Fmt.F, "Brake position", "braking", "M"),
    BlockField(10, Fmt.F, "Standstill position", "standstill", "S"),
    BlockField(11, Fmt.F, "---", None, ""),
    BlockField(12, Fmt.F, "Label set position", "label_set_point", "M/S"),
    BlockField(13, Fmt.F, "Label window", "label_window", "M/S"),
    BlockField(14, Fmt.F, "Correction starting", "correction_enable", "M"),
    BlockField(15, Fmt.F, "Correction end", "correction_disable", "M"),
)


# ---------------------------------------------------------------------------------------
# addresses


def _index(value: Any, name: str, lo: int, hi: int | None = None) -> int:
    if isinstance(value, bool) or not isinstance(value, int) or value < lo or (hi is not None and value > hi):
        allowed = f"an integer {lo} ... {hi}" if hi is not None else f"an integer >= {lo}"
        raise CompaxError(f"{name} {value!r} out of range; allowed is {allowed}", code=E_ADDRESS, field=name,
                          value=value, allowed=allowed)
    return value


def set_point_address(k: int) -> int:
    """Address of set point k (1-based): F(4 + 2k); set point 1 is F0006."""
    return 4 + 2 * _index(k, "set point number", 1, (SIZE - 4) // 2)


def aux_address(k: int) -> int:
    """Address of the auxiliary function of set point k (1-based): B(5 + 2k); B0007 for k = 1."""
    return 5 + 2 * _index(k, "set point number", 1, (SIZE - 5) // 2)


def block_base(curve: int) -> int:
    """First (highest) address of curve c's control block: 5460 - 20·(c - 1)."""
    return SIZE - BLOCK_SIZE * (_index(curve, "curve number", 1, MAX_CURVES) - 1)


def block_address(curve: int, offset: int) -> int:
    """Address of field ``offset`` (0 ... 19, see `CONTROL_BLOCK`) of curve c's control block."""
    return block_base(curve) - _index(offset, "control block field", 0, BLOCK_SIZE - 1)


def check_capacity(highest_point: int, curves: int) -> None:
    """Set points 1 ... L and C control blocks fit without overlap: 2·L + 20·C <= 5455 (§2.21)."""
    used = 2 * highest_point + BLOCK_SIZE * curves
    if used > CAPACITY or curves > MAX_CURVES:
        raise CompaxError(
            f"cam memory capacity exceeded: {highest_point} set points and {curves} curves need "
            f"2·{highest_point} + 20·{curves} = {used} addresses; allowed is 2·N_points + 20·N_curves <= {CAPACITY} "
            f"and at most {MAX_CURVES} curves (set point addresses 6 ... {5 + 2 * highest_point} would overlap "
            f"the control blocks from {SIZE - BLOCK_SIZE * curves + 1})",
            code=E_CAPACITY, field="capacity", value=used, allowed=f"<= {CAPACITY}")


# ---------------------------------------------------------------------------------------
# word formats


def encode_int(value: Any) -> int:
    """I format: a signed integer as its 24-bit two's complement word (1024 -> 0x000400)."""
    if isinstance(value, bool) or not isinstance(value, int):
        if isinstance(value, float) and value.is_integer():
            value = int(value)
        else:
            raise CompaxError(f"I value {value!r} is not an integer; allowed is {_INT_MIN} ... {_INT_MAX}",
                              code=E_VALUE, field="I", value=value, allowed=f"{_INT_MIN} ... {_INT_MAX}")
    if not _INT_MIN <= value <= _INT_MAX:
        raise CompaxError(f"I value {value} does not fit 24 bits; allowed is {_INT_MIN} ... {_INT_MAX}",
                          code=E_VALUE, field="I", value=value, allowed=f"{_INT_MIN} ... {_INT_MAX}")
    return value & _WORD


def decode_int(word: int) -> int:
    """I format: the signed value of a 24-bit word."""
    return word - (1 << 24) if word & 0x800000 else word


def encode_bytes(value: Iterable[Any]) -> int:
    """B format: (digital, analogue 0, analogue 1) -> word with digital in the LSB (§25)."""
    try:
        parts = tuple(value)
    except TypeError:
        parts = (value,)
    if len(parts) != 3:
        raise CompaxError(f"B value {value!r} must be three numbers 'digital;analogue 0;analogue 1'",
                          code=E_VALUE, field="B", value=value, allowed="3 numbers, each -128 ... 255")
    word = 0
    for i, (name, byte) in enumerate(zip(("digital", "analogue 0", "analogue 1"), parts)):
        if isinstance(byte, bool) or not isinstance(byte, int) or not -128 <= byte <= 255:
            raise CompaxError(f"B value {name} = {byte!r} does not fit 8 bits; allowed is -128 ... 255",
                              code=E_VALUE, field=f"B {name}", value=byte, allowed="-128 ... 255")
        word |= (byte & 0xFF) << (8 * i)
    return word


def decode_bytes(word: int) -> tuple[int, int, int]:
    """B format: (digital, analogue 0, analogue 1) as unsigned bytes 0 ... 255."""
    return word & 0xFF, (word >> 8) & 0xFF, (word >> 16) & 0xFF


# A value this close (in LSBs) to a multiple of 2^-23 is that multiple: undoes float error
# in computed fractions (s / S_T) without touching any decimal of up to 8 places, whose
# distance from the grid is at least 2.56e-6 LSB.
_SNAP = 1e-6


def fraction_word(value: Any, *, full_scale_is_one: bool = False) -> int:
    """F format word of a fraction, via motion.cam's `encode_fraction` (floor).

    With ``full_scale_is_one`` the value 1.0 (the full cycle) is stored as 0x7FFFFF, the
    inverse of ``decode_fraction(..., full_scale_is_one=True)``; otherwise 1.0 does not fit
    (the largest fraction is 0.9999999).
    """
    if isinstance(value, bool):
        raise CompaxError(f"F value {value!r} is not a number", code=E_VALUE, field="F", value=value)
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise CompaxError(f"F value {value!r} is not a number; allowed is -1 <= value < 1", code=E_VALUE,
                          field="F", value=value, allowed="-1 <= value < 1") from None
    scaled = v * FRACTION_ONE
    if scaled == scaled and abs(scaled) != float("inf"):
        nearest = round(scaled)
        if nearest != scaled and abs(scaled - nearest) <= _SNAP:
            v = nearest / FRACTION_ONE
    if full_scale_is_one and v == 1.0:
        return FULL_SCALE
    try:
        return encode_fraction(v)
    except ValueError:
        allowed = "-1 <= value <= 1 (1 = the full cycle)" if full_scale_is_one else "-1 <= value < 1 (max. 0.9999999)"
        raise CompaxError(f"F value {value!r} does not fit the 24-bit fraction format; allowed is {allowed}",
                          code=E_VALUE, field="F", value=value, allowed=allowed) from None


def fraction_value(word: int, *, full_scale_is_one: bool = False) -> float:
    """The value of an F word (`decode_fraction`); 0x7FFFFF is 1.0 with ``full_scale_is_one``."""
    return decode_fraction(word, full_scale_is_one=full_scale_is_one)


def _trailing_zeros(q: int) -> int:
    if q == 0:
        return 99
    n = 0
    while q % 10 == 0:
        q //= 10
        n += 1
    return n


def format_fraction(word: int) -> str:
    """The read-back text of an F word: "F6<cr>" -> "F0006=0.1234567" (§25), 7 decimals.

    The word stands for every value v with floor(v·2^23) = w, an interval 2^-23
    (1.19e-7) wide that holds one or two 7-decimal numbers. Printed is one of them, so
    writing the text back stores the same word: the one with the fewest decimals, and of
    two 7-decimal ones the one farther from 0. A value written with up to 6 decimals
    therefore reads back exactly (".1" as 0.1000000, not 0.0999999), and 0.1234567, the
    manual's example, reads back as 0.1234567.
    """
    w = decode_int(word)
    low = -((-w * 10**7) // FRACTION_ONE)  # ceil(w·10^7 / 2^23), exact integer arithmetic
    high = -((-(w + 1) * 10**7) // FRACTION_ONE) - 1  # last q with q/10^7 < (w+1)/2^23
    q = max(range(low, high + 1), key=lambda c: (_trailing_zeros(c), abs(c)))
    sign = "-" if q < 0 else ""
    q = abs(q)
    return f"{sign}{q // 10**7}.{q % 10**7:07d}"


# ---------------------------------------------------------------------------------------
# the memory


@dataclass(frozen=True, slots=True)
class VfResult:
    """What a VF did: the whole memory (``full``) or the listed addresses, and how long it takes."""

    full: bool
    addresses: tuple[int, ...]
    duration_s: float


def _address(address: Any) -> int:
    if isinstance(address, bool) or not isinstance(address, int) or not 1 <= address <= SIZE:
        raise CompaxError(f"address {address!r} out of range; allowed is 1 ... {SIZE}", code=E_ADDRESS,
                          field="address", value=address, allowed=f"1 ... {SIZE}")
    return address


def _fmt(fmt: Any) -> Fmt:
    try:
        return Fmt(fmt.upper() if isinstance(fmt, str) else fmt)
    except ValueError:
        raise CompaxError(f"format {fmt!r} unknown; allowed is I, F or B", code=E_VALUE, field="format",
                          value=fmt, allowed="I, F, B") from None


def _check_word(address: int, word: int, shown: Any = None) -> None:
    """Rules that depend on the address: reserved status addresses, the number of curves."""
    if address in RESERVED_ADDRESSES:
        raise CompaxError(f"address {address} is reserved for status information (2 ... 5) and cannot be written",
                          code=E_RESERVED, field="address", value=address, allowed="1, 6 ... 5460")
    if address == 1 and not 0 <= decode_int(word) <= MAX_CURVES:
        raise CompaxError(
            f"I0001 (number of curves) = {decode_int(word) if shown is None else shown} out of range; "
            f"allowed is 0 ... {MAX_CURVES}",
            code=E_VALUE, field="I0001", value=decode_int(word), allowed=f"0 ... {MAX_CURVES}")


class CamMemory:
    """The cam memory with its valid copy and the modified-address table (see the module doc)."""

    def __init__(self, *, delivery: bool = True) -> None:
        self._ram = [0] * (SIZE + 1)  # index 0 unused: addresses are 1-based
        if delivery:
            self._delivery_state()
        self._valid = list(self._ram)
        #: numbers the states of the valid copy: changed by every VF (only VF changes it), so a
        #: reader may keep what it derived from a curve until this number changes
        self.valid_version = 0
        self._modified: list[int] = []
        self._overflow = False

    @classmethod
    def blank(cls) -> CamMemory:
        """All 5460 words 0 (the state after RESETF and VF)."""
        return cls(delivery=False)

    def _delivery_state(self) -> None:
        ram = self._ram
        ram[1] = 1
        base = block_base(1)
        ram[base] = DELIVERY_CYCLE  # master cycle integer
        ram[base - 2] = 1  # first set point
        ram[base - 3] = 2  # last set point
        ram[base - 4] = DELIVERY_CYCLE  # slave cycle integer
        ram[set_point_address(1)] = 0
        ram[set_point_address(2)] = FULL_SCALE  # 0.9999999 = S_T: gradient S_T / M_T = 1

    # -- reading -----------------------------------------------------------------------------

    def word(self, address: int, *, valid: bool = False) -> int:
        """The raw 24-bit word (memory, or the valid copy with ``valid=True``)."""
        return (self._valid if valid else self._ram)[_address(address)]

    def read(self, fmt: str | Fmt, address: int, *, valid: bool = False) -> int | float | tuple[int, int, int]:
        """The value at ``address`` in format I (int), F (float Ix/2^23) or B (3 unsigned bytes)."""
        f = _fmt(fmt)
        word = self.word(address, valid=valid)
        if f is Fmt.I:
            return decode_int(word)
        if f is Fmt.F:
            return fraction_value(word)
        return decode_bytes(word)

    def words(self, *, valid: bool = False) -> tuple[int, ...]:
        """All words, addresses 1 ... 5460 (index 0 is address 1)."""
        return tuple((self._valid if valid else self._ram)[1:])

    def curve_count(self, *, valid: bool = False) -> int:
        """I0001, the number of curves."""
        return decode_int(self.word(1, valid=valid))

    def curve(self, number: int, *, valid: bool = True) -> Any:
        """`curves.read_curve(self, number)`: the CurveRecord SETC would select (E17 if absent)."""
        from axisline.devices.compax.curves import read_curve  # curves builds on this module

        return read_curve(self, number, valid=valid)

    @property
    def modified(self) -> tuple[int, ...]:
        """The modified-address table (at most 20 distinct addresses, in write order)."""
        return tuple(self._modified)

    @property
    def modified_overflow(self) -> bool:
        """True when more than 20 addresses changed: the next VF transfers the whole memory."""
        return self._overflow

    # -- writing -----------------------------------------------------------------------------

    def encode(self, fmt: str | Fmt, address: int, value: Any) -> int:
        """The word ``value`` becomes at ``address`` in ``fmt``; raises CompaxError if it cannot be written."""
        f = _fmt(fmt)
        address = _address(address)
        if address == 1 and f is not Fmt.I:
            raise CompaxError(f"address 1 (number of curves) takes the I format, got {f.value}", code=E_VALUE,
                              field="I0001", value=value, allowed="I0001 = 0 ... 100")
        try:
            if f is Fmt.I:
                word = encode_int(value)
            elif f is Fmt.F:
                word = fraction_word(value)
            else:
                word = encode_bytes(value)
        except CompaxError as exc:
            raise CompaxError(f"{f.value}{address:04d}: {exc}", code=exc.code, field=f"{f.value}{address:04d}",
                              value=value, allowed=exc.allowed) from None
        _check_word(address, word, value)
        return word

    def write(self, fmt: str | Fmt, address: int, value: Any) -> None:
        """Write one value; on any error the memory is unchanged."""
        word = self.encode(fmt, address, value)
        self._store(address, word)

    def write_words(self, words: Mapping[int, int]) -> None:
        """Write raw words at many addresses, all or nothing (every address and word checked first)."""
        checked: list[tuple[int, int]] = []
        for address, word in words.items():
            address = _address(address)
            if isinstance(word, bool) or not isinstance(word, int) or not 0 <= word <= _WORD:
                raise CompaxError(f"word {word!r} at address {address} does not fit 24 bits (0 ... 0xFFFFFF)",
                                  code=E_VALUE, field=f"address {address}", value=word, allowed="0 ... 0xFFFFFF")
            _check_word(address, word)
            checked.append((address, word))
        for address, word in checked:
            self._store(address, word)

    def _store(self, address: int, word: int) -> None:
        self._ram[address] = word
        if self._overflow or address in self._modified:
            return
        if len(self._modified) >= MODIFIED_TABLE_SIZE:
            self._overflow = True
            self._modified.clear()
        else:
            self._modified.append(address)

    def resetf(self) -> float:
        """RESETF: the whole memory to 0 (needs VF to become valid). Returns the duration, 1 s."""
        self._ram = [0] * (SIZE + 1)
        self._modified.clear()
        self._overflow = True
        return RESETF_DURATION_S

    def vf(self) -> VfResult:
        """VF: declare the memory valid - the modified addresses, or all of it (see the module doc)."""
        if self._overflow or not self._modified:
            self._valid = list(self._ram)
            result = VfResult(True, (), VF_FULL_DURATION_S)
        else:
            for address in self._modified:
                self._valid[address] = self._ram[address]
            n = len(self._modified)
            result = VfResult(False, tuple(self._modified), VF_FULL_DURATION_S * n / SIZE)
        self._modified.clear()
        self._overflow = False
        self.valid_version += 1
        return result

    @property
    def dirty(self) -> bool:
        """True when the memory differs from its valid copy (a VF is outstanding)."""
        return self._ram != self._valid

    def copy(self) -> CamMemory:
        other = CamMemory.__new__(CamMemory)
        other._ram = list(self._ram)
        other._valid = list(self._valid)
        other.valid_version = self.valid_version
        other._modified = list(self._modified)
        other._overflow = self._overflow
        return other

    def restore(self, snapshot: CamMemory) -> None:
        """Put back the memory and modified table of ``snapshot`` (a `copy()`): undoes a line
        whose data could not be stored. The valid copy stays: only VF changes it."""
        self._ram = list(snapshot._ram)
        self._modified = list(snapshot._modified)
        self._overflow = snapshot._overflow

    # -- persistence -------------------------------------------------------------------------

    _FILE_FORMAT = "axisline-compax-cam-memory"

    def document(self) -> dict[str, Any]:
        """The memory (the Zero-Power-RAM) as the file's JSON document (others may add keys)."""
        return {"format": self._FILE_FORMAT, "version": 1, "size": SIZE,
                "words": "".join(f"{w:06X}" for w in self._ram[1:])}

    def save(self, path: str | os.PathLike[str]) -> None:
        """Write the memory to ``path`` atomically: a failed save keeps the old file."""
        atomic_write_text(path, json.dumps(self.document()) + "\n")

    @classmethod
    def load(cls, path: str | os.PathLike[str]) -> CamMemory:
        """Power on with a saved memory: everything valid, the modified table empty."""
        name = os.fspath(path)
        from axisline.configerrors import read_text

        try:  # the size is checked before the file is read
            document = json.loads(read_text(path, MAX_MEMORY_FILE_BYTES))
        except json.JSONDecodeError as exc:
            raise CompaxError(f"{name}: not a cam memory file ({exc})", field="file", value=name) from None
        except (ValueError, RecursionError) as exc:  # too large, not UTF-8, nested too deep
            raise CompaxError(f"{name}: not a cam memory file ({exc})", field="file", value=name) from None
        if not isinstance(document, dict) or document.get("format") != cls._FILE_FORMAT:
            raise CompaxError(f"{name}: not a cam memory file (format must be {cls._FILE_FORMAT!r})",
                              field="format", value=name)
        if document.get("version") != 1 or document.get("size") != SIZE:
            raise CompaxError(
                f"{name}: version {document.get('version')!r} / size {document.get('size')!r} not supported "
                f"(version 1, size {SIZE})", field="version", value=document.get("version"))
        text = document.get("words")
        if not isinstance(text, str) or len(text) != 6 * SIZE:
            raise CompaxError(f"{name}: 'words' must hold {SIZE} words of 6 hex digits", field="words",
                              value=None if not isinstance(text, str) else len(text))
        try:
            words = [int(text[i : i + 6], 16) for i in range(0, len(text), 6)]
        except ValueError:
            raise CompaxError(f"{name}: 'words' holds a character that is not a hex digit", field="words",
                              value=name) from None
        if not 0 <= decode_int(words[0]) <= MAX_CURVES:
            raise CompaxError(f"{name}: I0001 = {decode_int(words[0])} out of range 0 ... {MAX_CURVES}",
                              field="I0001", value=decode_int(words[0]))
        memory = cls.__new__(cls)
        memory._ram = [0, *words]
        memory._valid = list(memory._ram)
        memory.valid_version = 0
        memory._modified = []
        memory._overflow = False
        return memory

    def __repr__(self) -> str:
        return (f"CamMemory({self.curve_count()} curves, modified={len(self._modified)}"
                f"{' (full)' if self._overflow else ''}, dirty={self.dirty})")
