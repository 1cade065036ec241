"""COMPAX curves in the cam memory: `CurveRecord` (compax.md §2.7, §2.21; manual §8, §25).

    from axisline.devices.compax.cammemory import CamMemory
    from axisline.devices.compax.curves import CurveRecord, read_curve, write_curve, store_cam
    mem = CamMemory()
    rec = CurveRecord(number=2, master_cycle=360.0, slave_cycle=360.0,
                      set_points=[0.0, 0.5, 1.0], coupling=0.1, synchronous=0.6)
    rec = write_curve(mem, rec)          # placed at the first free set points; needs VF
    mem.vf()
    table = read_curve(mem, 2).to_point_table()   # motion.cam.PointTable, slave in units

A curve is its control block (20 addresses downward from 5460 - 20·(n - 1)) and its set
points (F at 4 + 2k) with their auxiliary functions (B at 5 + 2k), k = first_point ...
last_point. `CurveRecord` fields (the cam operation codes against these names):

=====================  ====================================================  ==========
field                  meaning (manual symbol)                               stored as
=====================  ====================================================  ==========
number                 curve number n (1-based, SETC n)                      position
master_cycle           M_T, master units                                     I + F
slave_cycle            S_T, slave units                                      I + F
first_point            number of the 1st set point                           I
last_point             number of the last set point                          I
set_points             slave values, fractions of S_T (1.0 = S_T)            F each
aux_digital            digital aux function per set point (bit 0 = O7)       B (LSB)
aux_analog0/1          analogue aux functions per set point, -128 ... 127    B (mid / MSB)
coupling               M_E, fraction of M_T                                  F
synchronous            M_S, fraction of M_T                                  F
decoupling             M_A, fraction of M_T                                  F
braking                M_B, fraction of M_T                                  F
standstill             S_0, fraction of S_T (-1 ... 1; 1.0 = S_T exception)  F
label_set_point        M_M or S_M, fraction of M_T or S_T                    F
label_window           M_f (half width), fraction of M_T or S_T, <= 0.3      F
correction_enable      M_k1, fraction of M_T                                 F
correction_disable     M_k2, fraction of M_T                                 F
=====================  ====================================================  ==========

Set point k (0-based within the curve) lies at master position k·M_T/(N - 1), N the
number of set points; between set points the slave is interpolated linearly
(`to_point_table`). A curve is *closed* when its first and last set point are equal
(the slave returns to its start), otherwise *open* (§2.7.1).

Decisions (spec line -> choice, why)
------------------------------------
1. §2.7.2 [DERIVED] / ambiguity 2: set points are equidistant over M_T (N - 1 intervals)
   and the largest F word 0x7FFFFF stands for exactly 1.0 (S_T, or M_T for master
   fields): `set_points[i] == 1.0` <-> 0x7FFFFF, so an open curve 0 ... 0.9999999 moves
   exactly S_T per cycle ("This value then corresponds to the slave-cycle", §25), and the
   exception S_0 = S_T (§8.2.1) is representable.
2. §6.1 [CONFLICT] / ambiguity 9 "Master-cycle of curve 0 ... I5460" / "Slave-cycle of
   1st curve: I5436": curves are numbered from 1 as in the storage tables and SETC n
   ("the nth curve"); I5436 is the slave cycle of curve 2.
3. §2.21 capacity [DERIVED]: 2·L + 20·C <= 5455 (L the highest set point used, C the
   number of curves); a curve has 2 ... 2500 set points (§3 "up to 2500 set points"; two
   are needed to interpolate), there are at most 100 curves (§9). Set point ranges of
   different curves must not overlap (a write would change the other curve).
4. E17 "Curve not present" (§22) for a number outside 1 ... I0001 and for a curve whose
   control block cannot describe a curve (M_T <= 0, set point numbers out of order or
   overlapping the control blocks) - SETC cannot select it either way.
5. Field ranges checked on write (reading takes what the memory holds, so a curve a host
   wrote word by word can always be inspected): M_E, M_S, M_A, M_B, M_M, M_k1, M_k2 in
   0 ... 1 of their cycle; S_0 in -1 ... 1 ("Value range: ±S_T"); M_f <= 0.3
   ("Restriction: M_f <= 0,3 * M_T"); M_E <= M_S and M_A <= M_B ("Condition: M_E < M_S",
   "M_A < M_B" when they differ). M_E's "0 or >= the master change in 1 ms" depends on
   the speed and is left to the cam operation.
6. M_T and S_T are split into integer and fraction as I = floor(x), F = x - I, so F is
   always 0 ... 1; reading adds whatever the two words hold. M_T must be > 0; S_T may be
   any value (the slave may move backwards).
7. Analogue aux values (§2.12 [DERIVED]): 8-bit two's complement, 1 LSB = 10 V / 128 at
   gain 100 (P71/P72 = 100: 127 -> 9.92 V "10V", 1 -> 0.078 V, 128 -> -10 V).
8. Sampling a CamCurve or CSV: the default slave cycle is the largest |slave value|
   ("The slave cycle always corresponds to the max. curve value", §8.2); a CSV that is
   not equidistant must be resampled (``points=N``), since COMPAX set points are.
9. `write_curve` writes the control block fields 0 ... 10 and 12 ... 15, the set points,
   the aux functions and (for a new curve) I0001 in one all-or-nothing write; field 11
   ("---") and the unused 16 ... 19 are left as they are.
"""

from __future__ import annotations

import math
import os
from collections.abc import Sequence
from dataclasses import dataclass, field, fields, replace
from typing import Any

import numpy as np

from axisline.devices.compax import E_CAPACITY, E_CURVE_NOT_PRESENT, E_VALUE, CompaxError
from axisline.devices.compax.cammemory import (
    CONTROL_BLOCK,
    MAX_CURVES,
    MAX_POINTS_PER_CURVE,
    CamMemory,
    aux_address,
    block_address,
    check_capacity,
    decode_bytes,
    decode_int,
    encode_bytes,
    encode_int,
    fraction_value,
    fraction_word,
    set_point_address,
)
from axisline.motion.cam import PointTable
from axisline.motion.curve import CamCurve

__all__ = [
    "AuxFunction",
    "CurveRecord",
    "curve_from_cam",
    "curve_from_csv",
    "curve_from_table",
    "curve_to_csv",
    "next_free_point",
    "read_curve",
    "store_cam",
    "write_curve",
]

#: CurveRecord attribute -> (control block offset, allowed range, what it is a fraction of)
_FRACTION_FIELDS: dict[str, tuple[int, float, float, str]] = {
    "coupling": (6, 0.0, 1.0, "M_T"),
    "synchronous": (7, 0.0, 1.0, "M_T"),
    "decoupling": (8, 0.0, 1.0, "M_T"),
    "braking": (9, 0.0, 1.0, "M_T"),
    "standstill": (10, -1.0, 1.0, "S_T"),
    "label_set_point": (12, 0.0, 1.0, "M_T or S_T"),
    "label_window": (13, 0.0, 0.3, "M_T or S_T"),
    "correction_enable": (14, 0.0, 1.0, "M_T"),
    "correction_disable": (15, 0.0, 1.0, "M_T"),
}
_SYMBOL = {
    "coupling": "M_E", "synchronous": "M_S", "decoupling": "M_A", "braking": "M_B", "standstill": "S_0",
    "label_set_point": "M_M/S_M", "label_window": "M_f", "correction_enable": "M_k1",
    "correction_disable": "M_k2",
}
assert all(CONTROL_BLOCK[off].attr == name for name, (off, *_r) in _FRACTION_FIELDS.items())


def _signed8(byte: int) -> int:
    return byte - 256 if byte >= 128 else byte


@dataclass(frozen=True, slots=True)
class AuxFunction:
    """One B word: digital outputs O7 ... O14 (bit 0 = O7) and two analogue values (§25)."""

    digital: int
    analog0: int  # -128 ... 127
    analog1: int

    @classmethod
    def from_word(cls, word: int) -> AuxFunction:
        d, a0, a1 = decode_bytes(word)
        return cls(d, _signed8(a0), _signed8(a1))

    @classmethod
    def parse(cls, text: str) -> AuxFunction:
        """From the manual's notation "digital;analogue 0;analogue 1", e.g. "255;127;255"."""
        parts = text.split(";")
        try:
            values = tuple(int(p) for p in parts)
        except ValueError:
            raise CompaxError(f"aux function {text!r}: expected 'digital;analogue 0;analogue 1'", code=E_VALUE,
                              field="B", value=text) from None
        return cls.from_word(encode_bytes(values))

    def word(self) -> int:
        return encode_bytes((self.digital, self.analog0, self.analog1))

    def outputs(self) -> dict[str, bool]:
        """O7 ... O14 as the digital byte sets them (valence O7 = bit 0 ... O14 = bit 7)."""
        return {f"O{7 + b}": bool(self.digital >> b & 1) for b in range(8)}

    def volts(self, channel: int, gain: float = 100.0) -> float:
        """Analogue channel 0 or 1 in volts: value · 10 V / 128 · gain / 100 (decision 7)."""
        if channel not in (0, 1):
            raise CompaxError(f"analogue channel {channel!r} unknown; allowed 0 or 1", field="channel",
                              value=channel, allowed="0, 1")
        value = self.analog0 if channel == 0 else self.analog1
        return value * 10.0 / 128.0 * float(gain) / 100.0


@dataclass(kw_only=True)
class CurveRecord:
    """One curve: control block, set points and aux functions (see the module doc)."""

    number: int
    master_cycle: float
    slave_cycle: float
    first_point: int | None = None
    last_point: int | None = None
    set_points: list[float]
    aux_digital: list[int] = field(default_factory=list)
    aux_analog0: list[int] = field(default_factory=list)
    aux_analog1: list[int] = field(default_factory=list)
    coupling: float = 0.0
    synchronous: float = 0.0
    decoupling: float = 0.0
    braking: float = 0.0
    standstill: float = 0.0
    label_set_point: float = 0.0
    label_window: float = 0.0
    correction_enable: float = 0.0
    correction_disable: float = 0.0

    def __post_init__(self) -> None:
        self.set_points = [float(v) for v in self.set_points]
        n = len(self.set_points)
        for name in ("aux_digital", "aux_analog0", "aux_analog1"):
            values = list(getattr(self, name))
            setattr(self, name, values if values else [0] * n)  # empty: all aux functions 0

    # -- derived -----------------------------------------------------------------------------

    @property
    def n_points(self) -> int:
        return len(self.set_points)

    def set_point_words(self) -> list[int]:
        """The set points as F words (1.0 -> 0x7FFFFF)."""
        words = []
        for i, v in enumerate(self.set_points):
            try:
                words.append(fraction_word(v, full_scale_is_one=True))
            except CompaxError as exc:
                raise CompaxError(f"curve {self.number} set point {i}: {exc}", code=E_VALUE,
                                  field=f"set_points[{i}]", value=v, allowed=exc.allowed) from None
        return words

    @property
    def open(self) -> bool:
        """Open curve: the slave's start and end positions differ (§8.1)."""
        words = self.set_point_words()
        return words[0] != words[-1]

    @property
    def closed(self) -> bool:
        return not self.open

    def to_point_table(self) -> PointTable:
        """The curve as a linear point table: N set points equidistant over M_T, slave = F·S_T."""
        return PointTable.from_fractions(self.set_point_words(), self.master_cycle, self.slave_cycle,
                                         max_points=MAX_POINTS_PER_CURVE)

    def aux(self, index: int) -> AuxFunction:
        """The aux function of set point ``index`` (0-based within the curve)."""
        return AuxFunction(self.aux_digital[index], self.aux_analog0[index], self.aux_analog1[index])

    def aux_at(self, x: float) -> AuxFunction:
        """The aux function in force at master position x: that of the last set point passed (§13.1)."""
        n = self.n_points
        step = self.master_cycle / (n - 1)
        if x <= 0:
            i = 0
        else:
            i = min(int(x / step), n - 1)
            if (i + 1) * step <= x and i < n - 1:  # rounding in x / step
                i += 1
        return self.aux(i)

    def analog_table(self, channel: int) -> PointTable:
        """Analogue aux channel 0 or 1 over the master cycle, linearly interpolated (§13.2), in LSB."""
        if channel not in (0, 1):
            raise CompaxError(f"analogue channel {channel!r} unknown; allowed 0 or 1", field="channel",
                              value=channel, allowed="0, 1")
        values = self.aux_analog0 if channel == 0 else self.aux_analog1
        return PointTable.equidistant([float(v) for v in values], self.master_cycle,
                                      max_points=MAX_POINTS_PER_CURVE)

    # -- checks --------------------------------------------------------------------------------

    def validate(self) -> None:
        """Raise CompaxError naming the first field that cannot be stored (decision 5)."""
        n = self.number
        if isinstance(n, bool) or not isinstance(n, int) or not 1 <= n <= MAX_CURVES:
            raise CompaxError(f"curve number {n!r} out of range; allowed is 1 ... {MAX_CURVES}", code=E_VALUE,
                              field="number", value=n, allowed=f"1 ... {MAX_CURVES}")
        where = f"curve {n}"
        mt = _finite(self.master_cycle, f"{where} master_cycle (M_T)")
        if mt <= 0:
            raise CompaxError(f"{where} master_cycle (M_T) = {self.master_cycle!r} must be > 0", code=E_VALUE,
                              field="master_cycle", value=self.master_cycle, allowed="> 0")
        for name in ("master_cycle", "slave_cycle"):
            value = _finite(getattr(self, name), f"{where} {name}")
            if not -(1 << 23) <= math.floor(value) <= (1 << 23) - 1:
                raise CompaxError(f"{where} {name} = {value!r} does not fit the I format (-8388608 ... 8388607)",
                                  code=E_VALUE, field=name, value=value, allowed="-8388608 ... 8388607")
        count = self.n_points
        if not 2 <= count <= MAX_POINTS_PER_CURVE:
            raise CompaxError(f"{where} has {count} set points; allowed is 2 ... {MAX_POINTS_PER_CURVE}",
                              code=E_VALUE, field="set_points", value=count, allowed=f"2 ... {MAX_POINTS_PER_CURVE}")
        for i, v in enumerate(self.set_points):
            if not (math.isfinite(v) and -1.0 <= v <= 1.0):
                raise CompaxError(f"{where} set_points[{i}] = {v!r} out of range; allowed is -1 ... 1 (fraction of S_T)",
                                  code=E_VALUE, field=f"set_points[{i}]", value=v, allowed="-1 ... 1")
        for name, lo, hi in (("aux_digital", 0, 255), ("aux_analog0", -128, 127), ("aux_analog1", -128, 127)):
            values = getattr(self, name)
            if len(values) != count:
                raise CompaxError(f"{where} {name} has {len(values)} values; one per set point ({count}) is needed",
                                  code=E_VALUE, field=name, value=len(values), allowed=str(count))
            for i, v in enumerate(values):
                if isinstance(v, bool) or not isinstance(v, (int, np.integer)) or not lo <= v <= hi:
                    raise CompaxError(f"{where} {name}[{i}] = {v!r} out of range; allowed is an integer {lo} ... {hi}",
                                      code=E_VALUE, field=f"{name}[{i}]", value=v, allowed=f"{lo} ... {hi}")
        for name, (_off, lo, hi, of) in _FRACTION_FIELDS.items():
            v = _finite(getattr(self, name), f"{where} {name}")
            if not lo <= v <= hi:
                raise CompaxError(
                    f"{where} {name} ({_SYMBOL[name]}) = {v!r} out of range; allowed is {lo} ... {hi} (fraction of {of})",
                    code=E_VALUE, field=name, value=v, allowed=f"{lo} ... {hi}")
        if self.coupling > self.synchronous:
            raise CompaxError(
                f"{where} coupling M_E = {self.coupling} > synchronous M_S = {self.synchronous}; "
                "allowed is M_E = M_S or M_E < M_S (§11.1.1)",
                code=E_VALUE, field="coupling", value=self.coupling, allowed="<= synchronous")
        if self.decoupling > self.braking:
            raise CompaxError(
                f"{where} decoupling M_A = {self.decoupling} > braking M_B = {self.braking}; "
                "allowed is M_A = M_B or M_A < M_B (§11.2.1)",
                code=E_VALUE, field="decoupling", value=self.decoupling, allowed="<= braking")
        if self.first_point is not None:
            if isinstance(self.first_point, bool) or not isinstance(self.first_point, int) or self.first_point < 1:
                raise CompaxError(f"{where} first_point = {self.first_point!r}; allowed is an integer >= 1",
                                  code=E_VALUE, field="first_point", value=self.first_point, allowed=">= 1")
            if self.last_point is not None and self.last_point != self.first_point + count - 1:
                raise CompaxError(
                    f"{where} last_point = {self.last_point!r} does not match first_point {self.first_point} "
                    f"and {count} set points (must be {self.first_point + count - 1})",
                    code=E_VALUE, field="last_point", value=self.last_point,
                    allowed=str(self.first_point + count - 1))
        elif self.last_point is not None:
            raise CompaxError(f"{where} last_point given without first_point", code=E_VALUE, field="last_point",
                              value=self.last_point, allowed="None when first_point is None")
        self.set_point_words()  # every value encodable


def _finite(value: Any, name: str) -> float:
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise CompaxError(f"{name} = {value!r} is not a number", code=E_VALUE, field=name, value=value) from None
    if not math.isfinite(v):
        raise CompaxError(f"{name} = {value!r} must be a finite number", code=E_VALUE, field=name, value=value)
    return v


# ---------------------------------------------------------------------------------------
# memory access


def _cycle(memory: CamMemory, curve: int, offset: int, valid: bool) -> float:
    integer = decode_int(memory.word(block_address(curve, offset), valid=valid))
    fraction = fraction_value(memory.word(block_address(curve, offset + 1), valid=valid))
    return integer + fraction


def _split_cycle(value: float) -> tuple[int, int]:
    integer = math.floor(value)
    try:
        fraction = fraction_word(value - integer)
    except CompaxError:  # value - floor(value) rounded up to 1.0 (a tiny negative value)
        integer, fraction = integer + 1, 0
    return encode_int(integer), fraction


def _not_present(number: Any, reason: str) -> CompaxError:
    return CompaxError(f"curve {number!r} not present: {reason}", code=E_CURVE_NOT_PRESENT,
                       field="curve", value=number)


def _raw_range(memory: CamMemory, curve: int, valid: bool) -> tuple[int, int]:
    first = decode_int(memory.word(block_address(curve, 2), valid=valid))
    last = decode_int(memory.word(block_address(curve, 3), valid=valid))
    return first, last


def read_curve(memory: CamMemory, number: int, *, valid: bool = True) -> CurveRecord:
    """Curve ``number`` from the valid copy (what SETC sees) or, ``valid=False``, the memory.

    E17 (`CompaxError`, code 17) when the curve does not exist or its control block cannot
    describe a curve (decision 4).
    """
    count = memory.curve_count(valid=valid)
    if isinstance(number, bool) or not isinstance(number, int) or not 1 <= number <= count:
        held = f"1 ... {count}" if count else "none"
        raise _not_present(number, f"the cam memory holds {count} curves ({held})")
    master_cycle = _cycle(memory, number, 0, valid)
    slave_cycle = _cycle(memory, number, 4, valid)
    first, last = _raw_range(memory, number, valid)
    if not master_cycle > 0:
        raise _not_present(number, f"its master cycle is M_T = {master_cycle} (must be > 0)")
    if not (1 <= first < last and last - first + 1 <= MAX_POINTS_PER_CURVE):
        raise _not_present(number, f"its set points are {first} ... {last} (need 1 <= first < last, at most "
                                   f"{MAX_POINTS_PER_CURVE} set points)")
    try:
        check_capacity(last, count)
    except CompaxError:
        raise _not_present(number, f"its set points reach {last}, which overlap the control blocks of "
                                   f"{count} curves (2·{last} + 20·{count} > 5455)") from None
    words = [memory.word(set_point_address(k), valid=valid) for k in range(first, last + 1)]
    aux = [decode_bytes(memory.word(aux_address(k), valid=valid)) for k in range(first, last + 1)]
    values = {
        name: fraction_value(memory.word(block_address(number, off), valid=valid), full_scale_is_one=True)
        for name, (off, *_r) in _FRACTION_FIELDS.items()
    }
    return CurveRecord(
        number=number,
        master_cycle=master_cycle,
        slave_cycle=slave_cycle,
        first_point=first,
        last_point=last,
        set_points=[fraction_value(w, full_scale_is_one=True) for w in words],
        aux_digital=[d for d, _a0, _a1 in aux],
        aux_analog0=[_signed8(a0) for _d, a0, _a1 in aux],
        aux_analog1=[_signed8(a1) for _d, _a0, a1 in aux],
        **values,
    )


def _other_ranges(memory: CamMemory, number: int, count: int) -> dict[int, tuple[int, int]]:
    """Set point ranges of the other curves in the memory (plausible ones only)."""
    ranges = {}
    for curve in range(1, count + 1):
        if curve == number:
            continue
        first, last = _raw_range(memory, curve, valid=False)
        if 1 <= first <= last:
            ranges[curve] = (first, last)
    return ranges


def next_free_point(memory: CamMemory, points: int = 2, *, exclude: int | None = None) -> int:
    """The first set point number where ``points`` consecutive set points are unused (first fit)."""
    count = memory.curve_count()
    ranges = sorted(_other_ranges(memory, exclude if exclude is not None else 0, count).values())
    start = 1
    for first, last in ranges:
        if start + points - 1 < first:
            break
        start = max(start, last + 1)
    return start


def write_curve(memory: CamMemory, record: CurveRecord) -> CurveRecord:
    """Store ``record`` in the memory (all or nothing); returns it with first/last_point set.

    Curve ``number`` may replace an existing curve or be the next new one (I0001 + 1).
    Without ``first_point`` the set points go to the first free place (the curve's own
    old place if it fits). Capacity, overlap with other curves and every field are checked
    before anything is written. The change needs VF to become valid.
    """
    record.validate()
    number = record.number
    count = memory.curve_count()
    if number > count + 1:
        raise CompaxError(
            f"curve {number} cannot be written: the memory holds {count} curves, so the next new curve is "
            f"{count + 1} (curve numbers are consecutive)",
            code=E_VALUE, field="number", value=number, allowed=f"1 ... {count + 1}")
    new_count = max(count, number)
    points = record.n_points
    others = _other_ranges(memory, number, count)
    first = record.first_point
    if first is None:
        first = next_free_point(memory, points, exclude=number)
    last = first + points - 1
    for curve, (f, l) in sorted(others.items()):
        if first <= l and f <= last:
            raise CompaxError(
                f"curve {number}: set points {first} ... {last} overlap curve {curve}'s set points {f} ... {l}",
                code=E_CAPACITY, field="first_point", value=first, allowed="a range no other curve uses")
    highest = max([last, *(l for _f, l in others.values())])
    check_capacity(highest, new_count)

    words: dict[int, int] = {}
    mt_int, mt_frac = _split_cycle(record.master_cycle)
    st_int, st_frac = _split_cycle(record.slave_cycle)
    words[block_address(number, 0)] = mt_int
    words[block_address(number, 1)] = mt_frac
    words[block_address(number, 2)] = encode_int(first)
    words[block_address(number, 3)] = encode_int(last)
    words[block_address(number, 4)] = st_int
    words[block_address(number, 5)] = st_frac
    for name, (off, *_r) in _FRACTION_FIELDS.items():
        words[block_address(number, off)] = fraction_word(getattr(record, name), full_scale_is_one=True)
    for i, word in enumerate(record.set_point_words()):
        k = first + i
        words[set_point_address(k)] = word
        words[aux_address(k)] = encode_bytes((record.aux_digital[i], record.aux_analog0[i], record.aux_analog1[i]))
    if new_count != count:
        words[1] = encode_int(new_count)
    memory.write_words(words)
    return replace(record, first_point=first, last_point=last)


# ---------------------------------------------------------------------------------------
# building curves from tables, motion laws and CSV


def _block_kwargs(kwargs: dict[str, Any]) -> dict[str, Any]:
    allowed = {f.name for f in fields(CurveRecord)} - {"number", "master_cycle", "slave_cycle", "set_points"}
    unknown = set(kwargs) - allowed
    if unknown:
        raise CompaxError(f"unknown curve field(s) {sorted(unknown)}; allowed: {sorted(allowed)}", field="field",
                          value=sorted(unknown))
    return kwargs


def _fractions(slave: Sequence[float], slave_cycle: float | None) -> tuple[float, list[float]]:
    values = [float(s) for s in slave]
    if slave_cycle is None:
        slave_cycle = max(abs(s) for s in values)
        if slave_cycle == 0:
            raise CompaxError("all slave values are 0: give slave_cycle (S_T) explicitly", code=E_VALUE,
                              field="slave_cycle", value=0.0, allowed="!= 0")
    st = _finite(slave_cycle, "slave_cycle")
    if st == 0:
        raise CompaxError("slave_cycle (S_T) = 0 cannot scale slave values", code=E_VALUE, field="slave_cycle",
                          value=st, allowed="!= 0")
    fractions = []
    for i, s in enumerate(values):
        f = s / st
        if not -1.0 <= f <= 1.0:
            if abs(f) <= 1.0 + 1e-12:  # float error at the full cycle
                f = math.copysign(1.0, f)
            else:
                raise CompaxError(
                    f"set point {i}: slave value {s!r} is outside ±S_T = ±{abs(st)} (fraction {f!r}; allowed -1 ... 1)",
                    code=E_VALUE, field=f"set_points[{i}]", value=s, allowed=f"-{abs(st)} ... {abs(st)}")
        fractions.append(f)
    return st, fractions


def curve_from_table(
    table: PointTable,
    number: int,
    *,
    slave_cycle: float | None = None,
    points: int | None = None,
    **block: Any,
) -> CurveRecord:
    """A curve from a point table (slave in units). Equidistant tables are taken as they are;
    others need ``points`` (resampled at N equidistant master positions)."""
    if points is None:
        if table.equidistant_step is None:
            raise CompaxError(
                "the table's master positions are not equidistant; COMPAX set points are: pass points=N to resample",
                code=E_VALUE, field="master", value=None, allowed="equidistant master positions")
        slave = list(table.slave)
    else:
        slave = list(_sample(table, points))
    st, fractions = _fractions(slave, slave_cycle)
    return CurveRecord(number=number, master_cycle=float(table.master_period), slave_cycle=st,
                       set_points=fractions, **_block_kwargs(block))


def _sample(curve: CamCurve, points: int) -> np.ndarray:
    if isinstance(points, bool) or not isinstance(points, int) or not 2 <= points <= MAX_POINTS_PER_CURVE:
        raise CompaxError(f"points = {points!r} out of range; allowed is 2 ... {MAX_POINTS_PER_CURVE}", code=E_VALUE,
                          field="points", value=points, allowed=f"2 ... {MAX_POINTS_PER_CURVE}")
    period = float(curve.master_period)
    x = np.array([period * k / (points - 1) for k in range(points)])
    x[-1] = period
    s, _ds, _dds, _ddds = curve.eval_array(x)
    return np.asarray(s, dtype=float)


def curve_from_cam(
    cam: CamCurve,
    number: int,
    points: int,
    *,
    slave_cycle: float | None = None,
    **block: Any,
) -> CurveRecord:
    """Sample any CamCurve (a motion.segments.SegmentCam, a spline, ...) at ``points``
    equidistant master positions over its cycle: set point k = s(k·M_T/(N-1)) / S_T."""
    slave = _sample(cam, points)
    st, fractions = _fractions(slave, slave_cycle)
    return CurveRecord(number=number, master_cycle=float(cam.master_period), slave_cycle=st,
                       set_points=fractions, **_block_kwargs(block))


def store_cam(memory: CamMemory, cam: CamCurve, number: int, points: int, *,
              slave_cycle: float | None = None, **block: Any) -> CurveRecord:
    """`curve_from_cam` and `write_curve` in one (the memory then needs VF)."""
    return write_curve(memory, curve_from_cam(cam, number, points, slave_cycle=slave_cycle, **block))


def curve_from_csv(
    path: str | os.PathLike[str],
    number: int,
    *,
    slave_cycle: float | None = None,
    points: int | None = None,
    **block: Any,
) -> CurveRecord:
    """A curve from a ``master,slave`` CSV (motion.cam format; rejected rows name their line)."""
    table = PointTable.from_csv(path)
    return curve_from_table(table, number, slave_cycle=slave_cycle, points=points, **block)


def curve_to_csv(record: CurveRecord, path: str | os.PathLike[str]) -> None:
    """Write the curve's points as ``master,slave`` CSV (units; atomic)."""
    record.to_point_table().to_csv(path)
