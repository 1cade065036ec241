"""COMPAX XX70 status values (compax.md §0.1, §2.19; manual §2, §20, §21, §25).

    from axisline.devices.compax.status import StatusValues, STATUS, format_status
    status = StatusValues()              # the cam operation fills it every cycle
    status[44] = per_mille(126.0, 360.0) # S44 = 350 ‰
    status.read(13, params)              # S13 = the optimizing indicator P233 selects
    format_status(status[48])            # "-8388608.000": 8 digits before, 3 behind the comma

`STATUS` is the table: number, meaning, unit, and how the value is computed. The cam
operation (``camop``) writes the values, the ASCII interface reads them ("S44<cr>").
The small pure functions here (`per_mille`, `label_reference`, `loop_counter_value`,
`s42_wrap`) are the "how computed" of the table, so both sides agree on them.

Decisions (spec line -> choice, why)
------------------------------------
1. §0.1 [CONFLICT] / ambiguity 3: the overview (§2) gives S44, S45, S50, S51, S52 in %,
   §20 and §14.5 in ‰. ‰ (per mille) is used: §20 is the status chapter, and §14.6.1's
   "SETM x with x = S50/10 ('/10' because x is given in % and S50 in ‰)" only works
   in ‰. SETM itself takes %.
2. §0.1 vs §20, S2: "In cam operation: Variable of last LOOP command; otherwise: Set point"
   and "the total number of curve travels (m)" say the same in cam operation: S2 = m of
   the last LOOP. Outside cam operation S2 is the standard set point (filled by camop).
3. §20 S42 "increments will be reset when there is an overflow; value range ±8 000 000"
   [AMBIGUOUS]: the counter restarts from 0 when it would leave ±8 000 000, i.e. the
   shown value is the count's remainder (sign kept) modulo 8 000 000 (`s42_wrap`).
4. §20 "Format of the status values: 8 digits in front of the comma, 3 digits behind";
   "If there is an overflow 3 strokes will appear": `format_status` prints 3 decimals
   and "---" beyond ±99 999 999.999.
5. §21 S13/S14 show the optimizing indicator selected by P233/P234 (31 function pointer,
   32 normalized correction factor 0 ... 1000 ‰, 33 cycle counter, 37 encoder frequency
   channel 4): the cam operation fills `StatusValues.indicators`; `read(13, params)`
   picks the one P233 selects (0 when it has none).
6. §25 S30 "last error" (how a host checks a cam-memory transfer): the number of the last
   error (`CompaxError.code`), 0 when there was none; the ASCII endpoint sets it.
7. §14.2 label reference: M_ref = M_M - |P32| with cycles "added until the result lies in
   the value range 0 ... M_T" - taken as [0, M_T) (a reference at M_T is the one at 0);
   the slave form S_ref = (S_M - P32) + S_T of §14.6.1 is the same formula.
"""

from __future__ import annotations

import math
from collections.abc import Iterator, Mapping
from dataclasses import dataclass
from typing import Any

from axisline.devices.compax import E_UNKNOWN, E_VALUE, CompaxError, UnknownNumberError

__all__ = [
    "LOOP_ENDLESS",
    "S42_RANGE",
    "STATUS",
    "StatusSpec",
    "StatusValues",
    "format_status",
    "label_reference",
    "loop_counter_value",
    "per_mille",
    "s42_wrap",
]

#: S48 during "LOOP 0" (cyclic travel): -8388608 = -2^23 (§20).
LOOP_ENDLESS = -8_388_608
#: S42 value range ±8 000 000 increments (§20).
S42_RANGE = 8_000_000
_STATUS_LIMIT = 100_000_000  # 8 digits before the comma


@dataclass(frozen=True, slots=True)
class StatusSpec:
    number: int
    meaning: str
    unit: str
    computed: str
    source: str


STATUS: dict[int, StatusSpec] = {
    s.number: s
    for s in (
        StatusSpec(1, "Actual position", "units (P90)",
                   "actual slave position; in reset mode folded back each curve cycle (§15.3.4)", "§15.3.4"),
        StatusSpec(2, "In cam operation: m of the last LOOP command (total number of curve travels); otherwise "
                      "the set point", "-", "m of the last LOOP m (decision 2)", "§2, §20"),
        StatusSpec(13, "Optimizing indicator selected by P233", "per indicator",
                   "indicators[P233]: 31 function pointer, 32 normalized correction factor (0 ... 1000 ‰), "
                   "33 cycle counter, 37 encoder frequency channel 4 (incr./ms)", "§21"),
        StatusSpec(14, "Optimizing indicator selected by P234", "per indicator", "indicators[P234]", "§21"),
        StatusSpec(30, "Last error", "-", "number of the last error, 0 if none (decision 6)", "§25"),
        StatusSpec(41, "Master rotation speed", "min⁻¹", "master speed in revolutions of the master encoder per "
                   "minute (internal time base: simulated, §16)", "§20"),
        StatusSpec(42, "Master position in increments of the encoder module (4x evaluation)", "increments",
                   "counted increments, reset on overflow of ±8 000 000 (s42_wrap)", "§20"),
        StatusSpec(43, "Number of the activated curve", "-", "n of the last SETC n", "§20"),
        StatusSpec(44, "Master position in the master cycle", "‰", "per_mille(master position, M_T)", "§20"),
        StatusSpec(45, "Internal slave set position of the curve in the slave cycle", "‰",
                   "1000 · interpolated curve fraction F (of S_T)", "§20"),
        StatusSpec(46, "Sign of master speed", "-", "0: positive (or standstill), 1: negative", "§20"),
        StatusSpec(47, "Slave set position from set point interpolation", "units (P90)",
                   "F·S_T·P36 plus the open-curve offset", "§20"),
        StatusSpec(48, "Loop counter of LOOP m (counts down from m to 0)", "-",
                   "loop_counter_value(m) at LOOP, -1 per synchronous cycle; LOOP 0: -8388608", "§9, §20"),
        StatusSpec(49, "Physical position target for POSR", "units (P90)", "target of the last POSR / POSR CAM",
                   "§20"),
        StatusSpec(50, "Internal label set position M_ref (S_ref)", "‰",
                   "per_mille(label_reference(M_M or S_M, P32, cycle), cycle)", "§14.2, §20"),
        StatusSpec(51, "Internal actual value of the label", "‰", "S44 (S45 slave related) at the label edge",
                   "§14.5, §20"),
        StatusSpec(52, "Label correction", "‰", "S51 - S50, unlimited by P180", "§14.5, §14.6, §20"),
    )
}


def _spec(number: Any) -> StatusSpec:
    if isinstance(number, bool) or not isinstance(number, int) or number not in STATUS:
        raise UnknownNumberError(
            f"status S{number} is not modelled; known: {', '.join(f'S{n}' for n in STATUS)}",
            code=E_UNKNOWN, field="status", value=number, allowed=", ".join(f"S{n}" for n in STATUS))
    return STATUS[number]


class StatusValues(Mapping[int, float]):
    """The status values by number; the cam operation writes, the interface reads.

    ``status[44] = 350.0``; ``status[44]``; ``indicators`` holds the optimizing indicators
    by their P233/P234 number. Values start at 0.
    """

    def __init__(self) -> None:
        self._values: dict[int, float] = {n: 0.0 for n in STATUS}
        self.indicators: dict[int, float] = {}

    def __getitem__(self, number: int) -> float:
        _spec(number)
        return self._values[number]

    def __setitem__(self, number: int, value: float) -> None:
        _spec(number)
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
            raise CompaxError(f"S{number} = {value!r} must be a finite number", code=E_VALUE, field=f"S{number}",
                              value=value)
        self._values[number] = value

    def __iter__(self) -> Iterator[int]:
        return iter(self._values)

    def __len__(self) -> int:
        return len(self._values)

    def read(self, number: int, parameters: Any = None) -> float:
        """S-value ``number``; S13 / S14 resolve P233 / P234 through ``parameters`` (valid values)."""
        _spec(number)
        if number in (13, 14) and parameters is not None:
            selector = parameters.valid[233 if number == 13 else 234]
            return float(self.indicators.get(int(selector), 0.0))
        return self._values[number]

    def __repr__(self) -> str:
        shown = ", ".join(f"S{n}={v:g}" for n, v in self._values.items() if v)
        return f"StatusValues({shown})"


def format_status(value: float) -> str:
    """The device's status format: 3 decimals, at most 8 digits before the comma, else "---"."""
    v = float(value)
    if not math.isfinite(v) or abs(round(v, 3)) >= _STATUS_LIMIT:
        return "---"
    text = f"{v:.3f}"
    return "0.000" if text == "-0.000" else text


def per_mille(position: float, cycle: float) -> float:
    """1000 · (position mod cycle) / cycle: S44 from the master position, S50 from M_ref, ..."""
    if not (math.isfinite(cycle) and cycle > 0):
        raise CompaxError(f"cycle {cycle!r} must be a finite number > 0", code=E_VALUE, field="cycle", value=cycle)
    r = math.fmod(position, cycle)
    if r < 0:
        r += cycle
        if r >= cycle:
            r = 0.0
    return 1000.0 * r / cycle


def label_reference(label_set_point: float, p32: float, cycle: float) -> float:
    """M_ref = M_M - |P32| (or S_ref = S_M - |P32|), cycles added into 0 <= ref < cycle (§14.2)."""
    if not (math.isfinite(cycle) and cycle > 0):
        raise CompaxError(f"cycle {cycle!r} must be a finite number > 0", code=E_VALUE, field="cycle", value=cycle)
    ref = label_set_point - abs(p32)
    ref = math.fmod(ref, cycle)
    if ref < 0:
        ref += cycle
        if ref >= cycle:
            ref = 0.0
    return ref


def loop_counter_value(m: int) -> int:
    """S48 right after LOOP m: m, or -8388608 for LOOP 0 (endless); m in 0 ... 65000 (§9)."""
    if isinstance(m, bool) or not isinstance(m, int) or not 0 <= m <= 65000:
        raise CompaxError(f"LOOP {m!r} out of range; allowed is an integer 0 ... 65000", code=E_VALUE,
                          field="LOOP m", value=m, allowed="0 ... 65000")
    return LOOP_ENDLESS if m == 0 else m


def s42_wrap(increments: int) -> int:
    """S42 from an unbounded increment count: restarts at 0 on overflow of ±8 000 000 (decision 3)."""
    if isinstance(increments, bool) or not isinstance(increments, int):
        raise CompaxError(f"increment count {increments!r} must be an int", code=E_VALUE, field="S42",
                          value=increments)
    remainder = abs(increments) % S42_RANGE
    return -remainder if increments < 0 else remainder
