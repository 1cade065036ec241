"""COMPAX XX70 value-range rules and parameter helpers (compax.md §2.20, §4.5.3, §13.1, §24):
the scaled master and slave cycles and their 4 000 000 increment limit, the drift-free
conditions, the travel range, the P35 ramp error, the P37/P38 aux masks and the label sensor
distance. `parameters` re-exports them.

Decisions (numbered as in parameters.py, whose parameters they concern):

1. §2.5 / §4 formula 3 [CONFLICT] "P93 = 0 (Increments)" / "P93 = 1 (mm) or 3 (degree)" in
   the value-range formulas: read P90 (units); P93 is the operating mode and has no value
   0. `scaled_slave_cycle` takes P90.
6. §2.20 [CONFLICT] "P36 = S_T* = whole number" (P36 range ±1000): P36 keeps its table
   range; `drift_free_problems` does not ask for P36 = S_T* (implausible, cf. the gear
   example of §24 itself, which uses P36 = 1). "P83 = P93 = 2^n" there is read as
   P83 = P98 = 2^n as in its own example (P83 = P98 = 1024); only P83 = 2^a is checked.
"""

from __future__ import annotations

import math
from fractions import Fraction

from axisline.devices.compax import E_VALUE, CompaxError

__all__ = [
    "AUX_VALENCES",
    "MAX_SCALED_CYCLE",
    "aux_mask",
    "check_label_sensor_distance",
    "check_master_cycle_range",
    "check_slave_cycle_range",
    "drift_free_problems",
    "max_travel_revolutions",
    "p35_ramp_error_percent",
    "scaled_master_cycle",
    "scaled_slave_cycle",
]

#: Largest scaled master / slave cycle in increments (§4.5.3, §24).
MAX_SCALED_CYCLE = 4_000_000

#: P37 / P38 valence of each digital auxiliary output (§13.1.1, §13.1.2): O7 = 2^6 ... O14 = 2^13.
AUX_VALENCES: dict[str, int] = {f"O{k}": 1 << (k - 1) for k in range(7, 15)}
_AUX_BITS = sum(AUX_VALENCES.values())  # 16320: "O7...O14 to be enabled by P38=16320"

# ---------------------------------------------------------------------------------------
# value-range rules and helpers


def _positive(name: str, value: float) -> float:
    value = float(value)
    if not (math.isfinite(value) and value > 0):
        raise CompaxError(f"{name} = {value!r} must be a finite number > 0", code=E_VALUE, field=name, value=value,
                          allowed="> 0")
    return value


def scaled_master_cycle(master_cycle: float, p143: float, p98: float) -> float:
    """M_T* = M_T · 4 · P143 / P98: the master cycle in encoder increments (§4.5.3, §24)."""
    _positive("P98", p98)
    return float(Fraction(master_cycle) * 4 * Fraction(p143) / Fraction(p98))


def check_master_cycle_range(master_cycle: float, p143: float, p98: float) -> float:
    """The scaled master cycle, or CompaxError if M_T·4·P143/P98 > 4 000 000 (§4.5.3)."""
    _positive("M_T", master_cycle)
    scaled = scaled_master_cycle(master_cycle, p143, p98)
    if scaled > MAX_SCALED_CYCLE:
        raise CompaxError(
            f"scaled master cycle M_T·4·P143/P98 = {scaled:.3f} exceeds 4 000 000 increments "
            f"(M_T = {master_cycle}, P143 = {p143}, P98 = {p98}; §4.5.3)",
            code=E_VALUE, field="M_T·4·P143/P98", value=scaled, allowed="<= 4 000 000")
    return scaled


def scaled_slave_cycle(slave_cycle: float, p83: float, p90: int) -> float | None:
    """S_T* in increments: S_T·2^16/P83 (P90 = 0) or S_T·2^16/(P83·0.001) (P90 = 1 or 3).

    None for P90 = 2 (inch): the manual gives no rule (decision 1: the formulas' "P93" is P90).
    """
    _positive("P83", p83)
    if p90 == 0:
        return float(abs(Fraction(slave_cycle)) * 2**16 / Fraction(p83))
    if p90 in (1, 3):
        return float(abs(Fraction(slave_cycle)) * 2**16 / (Fraction(p83) * Fraction(1, 1000)))
    if p90 == 2:
        return None
    raise CompaxError(f"P90 = {p90!r} out of range; allowed is one of 0, 1, 2, 3", code=E_VALUE, field="P90",
                      value=p90, allowed="0, 1, 2, 3")


def check_slave_cycle_range(slave_cycle: float, p83: float, p90: int) -> float | None:
    """S_T*, or CompaxError if it exceeds 4 000 000 (§4.5.3)."""
    scaled = scaled_slave_cycle(slave_cycle, p83, p90)
    if scaled is not None and scaled > MAX_SCALED_CYCLE:
        formula = "S_T·2^16/P83" if p90 == 0 else "S_T·2^16/(P83·0.001)"
        raise CompaxError(
            f"scaled slave cycle {formula} = {scaled:.3f} exceeds 4 000 000 (S_T = {slave_cycle}, P83 = {p83}, "
            f"P90 = {p90}; §4.5.3)",
            code=E_VALUE, field=formula, value=scaled, allowed="<= 4 000 000")
    return scaled


def drift_free_problems(
    *,
    master_cycle: float,
    slave_cycle: float,
    p143: float,
    p98: float,
    p83: float,
    p90: int,
    p80: int = 16,
    p35: float = 1.0,
    p21: float = 1.0,
    open_curve: bool = True,
) -> list[str]:
    """The conditions of §24 (Annex 1) a configuration breaks; [] means drift-free.

    Pass exact values (ints or Fractions, or decimal strings via Fraction) - the
    conditions are about whole numbers. Closed curves need no slave condition (§24:
    "Closed curves are always drift-free"). See decision 6 for P36 and "P83 = P93".
    """
    problems: list[str] = []
    if p80 != 16:
        problems.append(f"P80 = {p80}: drift-free operation needs the universal drive (P80 = 16)")
    if p90 == 2:
        problems.append("P90 = 2 (inch): drift-free operation needs increments, mm or degree")
    if Fraction(p35) != 1:
        problems.append(f"P35 = {p35}: the 1st condition requires P35 = 1")
    if Fraction(p21) != 1:
        problems.append(f"P21 = {p21}: the slave channel requires P21 = 1")
    m_star = Fraction(master_cycle) * 4 * Fraction(p143) / Fraction(p98)
    if m_star.denominator != 1 or m_star > MAX_SCALED_CYCLE:
        problems.append(f"1st condition: M_T* = M_T·4·P143/P98 = {float(m_star)} must be a whole number <= 4 000 000")
    if open_curve and p90 in (0, 1, 3):
        if p90 == 0:
            s_star = abs(Fraction(slave_cycle)) * 2**16 / Fraction(p83)
        else:
            s_star = abs(Fraction(slave_cycle)) * 2**16 / (Fraction(p83) / 1000)
        if s_star.denominator != 1 or s_star > MAX_SCALED_CYCLE:
            problems.append(f"2nd condition: S_T* = {float(s_star)} must be a whole number <= 4 000 000")
        if p90 == 0:
            p83_int = Fraction(p83)
            if p83_int.denominator != 1 or p83_int <= 0 or int(p83_int) & (int(p83_int) - 1):
                problems.append(f"3rd condition: P83 = {p83} must be 2^a at 'Increments'")
        else:
            ratio = Fraction(p83) / (1000 * abs(Fraction(slave_cycle)))
            if ratio <= 0 or not _is_power_of_two(ratio):
                problems.append(f"3rd condition: P83 = {p83} must be 1000·S_T·2^b at 'mm' or 'Degree'")
    return problems


def _is_power_of_two(x: Fraction) -> bool:
    n, d = x.numerator, x.denominator
    return n > 0 and (n & (n - 1)) == 0 and (d & (d - 1)) == 0 and (n == 1 or d == 1)


def max_travel_revolutions(p83: int) -> int:
    """Max. travel in motor revolutions at the unit 'Increments': floor(4 000 000 / P83) (§4.2.2)."""
    if isinstance(p83, bool) or not isinstance(p83, int) or p83 <= 0:
        raise CompaxError(f"P83 = {p83!r} must be a positive integer", code=E_VALUE, field="P83", value=p83)
    return 4_000_000 // p83


def p35_ramp_error_percent(p179: float) -> float:
    """Upper bound of the P35 ramp time error: F < 100 % · 2^-23 · P179 (§18)."""
    return 100.0 * float(p179) / 2**23


def aux_mask(*outputs: str) -> int:
    """P37 / P38 value for the given outputs, e.g. aux_mask("O7", "O14") = 8256 (§13.1)."""
    total = 0
    for name in outputs:
        if name not in AUX_VALENCES:
            raise CompaxError(f"output {name!r} is no digital auxiliary function; allowed: O7 ... O14",
                              code=E_VALUE, field="output", value=name, allowed="O7 ... O14")
        total |= AUX_VALENCES[name]
    return total


def check_label_sensor_distance(p32: float, cycle: float) -> None:
    """P32 must lie in 0 ... 10 · the allocated cycle (M_T or S_T) (§23)."""
    limit = 10 * abs(float(cycle))
    if not (math.isfinite(float(p32)) and 0 <= float(p32) <= limit):
        raise CompaxError(f"P32 = {p32!r} out of range; allowed is 0 ... 10 · cycle = {limit}",
                          code=E_VALUE, field="P32", value=p32, allowed=f"0 ... {limit}")
