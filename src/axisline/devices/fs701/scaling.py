"""FS701 arithmetic on parameter values: length units and encoder scaling, the virtual
master, jog, adjust and return speeds, the print-mark buffer (manual §4.2, §4.3; spec §2.1).
parameters.py re-exports every name.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

from .parameter_table import ParameterError

if TYPE_CHECKING:
    from .parameters import ParameterSet


# --------------------------------------------------------------------------------------------
# length units and encoder scaling (§4.2, §4.3.1, §4.3.7; spec §2.1)

COUNTER_MULTIPLIERS: dict[int, int] = {0: 1, 1: 2, 2: 4}  # "Mode Counter": 0 = x1, 1 = x2, 2 = x4


def counter_multiplier(mode: int) -> int:
    """Edges counted per encoder period for a "Mode Counter" setting (0 -> 1, 1 -> 2, 2 -> 4)."""
    try:
        return COUNTER_MULTIPLIERS[mode]
    except KeyError:
        raise ParameterError(f"Mode Counter {mode!r} is not 0 (x1), 1 (x2) or 2 (x4)") from None


def counts_per_lu(pulses_per_1000: int | float) -> float:
    """Counted increments per length unit: Pulses .. / 1000 divided by 1000 (§4.3.1)."""
    return pulses_per_1000 / 1000.0


def line_counts_per_lu(params: ParameterSet) -> float:
    """kL: line encoder increments per LU."""
    return counts_per_lu(params.get_raw("pulses_line_1000"))


def carriage_counts_per_lu(params: ParameterSet) -> float:
    """kC: carriage encoder increments per LU."""
    return counts_per_lu(params.get_raw("pulses_cut_1000"))


def lu_to_line_counts(lu: float, params: ParameterSet) -> float:
    return lu * params.get_raw("pulses_line_1000") / 1000.0


def line_counts_to_lu(counts: float, params: ParameterSet) -> float:
    return counts * 1000.0 / params.get_raw("pulses_line_1000")


def lu_to_carriage_counts(lu: float, params: ParameterSet) -> float:
    return lu * params.get_raw("pulses_cut_1000") / 1000.0


def carriage_counts_to_lu(counts: float, params: ParameterSet) -> float:
    return counts * 1000.0 / params.get_raw("pulses_cut_1000")


def pulses_per_1000_lu(ppr: int, multiplier: int, lu_per_revolution: float) -> float:
    """The "Pulses .. / 1000" setting of an encoder: ppr x multiplier edges per revolution,
    `lu_per_revolution` LU of travel per revolution (e.g. a measuring wheel's circumference).
    Round the result to an integer for the register; the rounding error is a cutting error
    proportional to the length (§9 "Is the synchronous ratio correct?").
    """
    if ppr <= 0 or lu_per_revolution <= 0:
        raise ParameterError(f"ppr ({ppr}) and LU per revolution ({lu_per_revolution}) must be positive")
    if multiplier not in (1, 2, 4):
        raise ParameterError(f"multiplier {multiplier!r} is not 1, 2 or 4")
    return ppr * multiplier * 1000.0 / lu_per_revolution


def lu_to_physical(lu: float, lu_size: float) -> float:
    """A length in LU expressed in the physical unit one LU stands for (§4.2: with
    LU = 0.1 mm, 1000 LU are 100.0 mm)."""
    return lu * lu_size


def line_speed_to_count_rate(speed_lu_min: float, pulses_per_1000: int | float) -> float:
    """Counted increments per second at a speed in LU/min."""
    return speed_lu_min / 60.0 * pulses_per_1000 / 1000.0


def count_rate_to_line_speed(count_rate: float, pulses_per_1000: int | float) -> float:
    """LU/min from counted increments per second (process value "Line Speed" from "Master Freq.")."""
    return count_rate * 60.0 * 1000.0 / pulses_per_1000


def encoder_signal_frequency(speed_lu_min: float, pulses_per_1000: int | float, mode_counter: int) -> float:
    """Signal frequency (Hz) on the encoder input: counted rate / x1,x2,x4 multiplier."""
    return line_speed_to_count_rate(speed_lu_min, pulses_per_1000) / counter_multiplier(mode_counter)


def sync_ratio(params: ParameterSet) -> float:
    """Carriage increments per line increment in the synchronous phase:
    kC / kL x (1 + Sync Rate / 100) (spec §2.1 [DERIVED]; the Sync Rate changes the synchronous
    speed only, never the cutting length)."""
    return (
        params.get_raw("pulses_cut_1000") / params.get_raw("pulses_line_1000") * (1.0 + params.sync_rate / 100.0)
    )


class RatioClass:
    """Classes of the line : carriage pulse ratio (§2.3)."""

    ACCEPTABLE = "acceptable"  # 5:1 .. 1:5
    MISMATCHED = "mismatched"  # beyond 5:1 up to 16:1 (and 1:5 .. 1:16): works, not recommended
    NOT_ALLOWED = "not allowed"  # beyond 16:1 / 1:16 -> Error 05


def encoder_ratio_class(pulses_line_1000: int, pulses_cut_1000: int) -> str:
    """Classify Pulses Line/1000 : Pulses Cut/1000 (exact integer comparisons)."""
    hi, lo = max(pulses_line_1000, pulses_cut_1000), min(pulses_line_1000, pulses_cut_1000)
    if lo <= 0:
        return RatioClass.NOT_ALLOWED
    if hi > 16 * lo:
        return RatioClass.NOT_ALLOWED
    if hi > 5 * lo:
        return RatioClass.MISMATCHED
    return RatioClass.ACCEPTABLE


def ratio_raises_error_05(pulses_line_1000: int, pulses_cut_1000: int) -> bool:
    """Error 05 "Val. Range exceed": the ratio is beyond 16:1 or 1:16 (§2.3, §6)."""
    return encoder_ratio_class(pulses_line_1000, pulses_cut_1000) == RatioClass.NOT_ALLOWED


MAX_INPUT_FREQUENCY_HZ = 400_000.0  # §2.3 "must not exceed the maximum level of 400 kHz"
MIN_MASTER_FREQUENCY_HZ = 1_000.0  # §2.3 "at least about 1 kHz" at maximum line speed


@dataclass(frozen=True, slots=True)
class Finding:
    """One result of the encoder rules: severity "error" (Error 05), "warning" or "advice"."""

    severity: str
    rule: str
    message: str


@dataclass(frozen=True, slots=True)
class EncoderCheck:
    ratio: float  # pulses line / pulses cut
    ratio_class: str
    error_05: bool
    master_count_rate_hz: float  # counted line increments per second at Max. Line Speed
    master_signal_hz: float
    carriage_signal_hz: float  # carriage encoder at Max. Line Speed (synchronous)
    findings: tuple[Finding, ...]

    @property
    def ok(self) -> bool:
        return not any(f.severity in ("error", "warning") for f in self.findings)


def check_encoder_rules(params: ParameterSet) -> EncoderCheck:
    """The encoder rules of §2.3 for a parameter set.

    Error 05 (ratio beyond 16:1 / 1:16); warnings: an input above 400 kHz at Max. Line Speed,
    a master count rate below ~1 kHz at Max. Line Speed; advice: ratio outside 5:1 .. 1:5.
    """
    pl, pc = params.get_raw("pulses_line_1000"), params.get_raw("pulses_cut_1000")
    vmax = params.get_raw("max_line_speed")
    cls = encoder_ratio_class(pl, pc)
    count_rate = line_speed_to_count_rate(vmax, pl)
    f_master = encoder_signal_frequency(vmax, pl, params.mode_counter_1)
    f_carriage = encoder_signal_frequency(vmax, pc, params.mode_counter_2)
    findings: list[Finding] = []
    if cls == RatioClass.NOT_ALLOWED:
        findings.append(
            Finding("error", "ratio", f"Error 05: Pulses Line/1000 : Pulses Cut/1000 = {pl}:{pc} is beyond 16:1 / 1:16 (§2.3, §6)")
        )
    elif cls == RatioClass.MISMATCHED:
        findings.append(
            Finding("advice", "ratio", f"ratio {pl}:{pc} is outside the acceptable 5:1 .. 1:5; consider x1/x2/x4 (§2.3)")
        )
    for label, f in (("master", f_master), ("carriage", f_carriage)):
        if f > MAX_INPUT_FREQUENCY_HZ:
            findings.append(
                Finding("warning", "max_frequency", f"{label} encoder signal {f:.0f} Hz at Max. Line Speed exceeds 400 kHz (§2.3)")
            )
    if count_rate < MIN_MASTER_FREQUENCY_HZ:
        findings.append(
            Finding("warning", "min_frequency", f"master count rate {count_rate:.1f} Hz at Max. Line Speed is below about 1 kHz (§2.3)")
        )
    return EncoderCheck(pl / pc, cls, cls == RatioClass.NOT_ALLOWED, count_rate, f_master, f_carriage, tuple(findings))


# --------------------------------------------------------------------------------------------
# virtual master (§4.2, §4.3.1, §4.3.7)

VIRTUAL_SPEED_STEPS = 2048  # "Internal resolution = 1/2048 of Max Line Speed"


def virtual_speed_quantum(max_line_speed: int) -> float:
    """The virtual master's speed resolution in LU/min: Max. Line Speed / 2048."""
    return max_line_speed / VIRTUAL_SPEED_STEPS


def virtual_speed_steps(virtual_line_speed: int, max_line_speed: int) -> int:
    """Internal speed steps (0..2048): the setting limited to Max. Line Speed, truncated."""
    if max_line_speed <= 0:
        raise ParameterError(f"Max. Line Speed {max_line_speed!r} must be positive")
    v = min(max(virtual_line_speed, 0), max_line_speed)
    return v * VIRTUAL_SPEED_STEPS // max_line_speed


def effective_virtual_line_speed(virtual_line_speed: int, max_line_speed: int) -> float:
    """Speed the virtual master really runs (LU/min): steps x Max. Line Speed / 2048."""
    return virtual_speed_steps(virtual_line_speed, max_line_speed) * max_line_speed / VIRTUAL_SPEED_STEPS


def virtual_master_count_rate(params: ParameterSet) -> float:
    """Signed increments per second the virtual master generates at its set speed
    ("Dir. Frequency": 1 = forward, 0 = reverse)."""
    v = effective_virtual_line_speed(params.get_raw("virtual_line_speed"), params.get_raw("max_line_speed"))
    rate = line_speed_to_count_rate(v, params.get_raw("pulses_line_1000"))
    return rate if params.dir_frequency == 1 else -rate


def virtual_master_acceleration(params: ParameterSet) -> float:
    """LU/s² of the virtual master ramp: Max. Line Speed in "Ramp Vir. Master" seconds
    (inf for 0 s = step)."""
    t = params.get_raw("ramp_vir_master")
    vmax = params.get_raw("max_line_speed") / 60.0
    return math.inf if t == 0 else vmax / t


# --------------------------------------------------------------------------------------------
# jog, adjust, return speed, print-mark buffer


def jog_speed(params: ParameterSet, forward: bool = True) -> float:
    """Jog speed in LU/min: Jog Speed % of Max. Line Speed (§4.3.3)."""
    pct = params.jog_speed_forw if forward else params.jog_speed_rev
    return pct / 100.0 * params.get_raw("max_line_speed")


def jog_acceleration(params: ParameterSet, forward: bool = True, up: bool = True) -> float:
    """Jog acceleration (up) or deceleration (down) in LU/s²: the ramp time is for a change
    between standstill and Max. Line Speed (§4.3.3); inf for 0 s."""
    if forward:
        t = params.jog_ramp_up_forw if up else params.jog_ramp_dw_forw
    else:
        t = params.jog_ramp_up_rev if up else params.jog_ramp_dw_rev
    vmax = params.get_raw("max_line_speed") / 60.0
    return math.inf if t == 0 else vmax / t


def adjust_default_speed(max_line_speed: int) -> float:
    """Default "Vir. Master Speed" of the Adjust program: 10 % of Max. Line Speed (§7.1)."""
    return max_line_speed * 0.10


def max_return_speed(params: ParameterSet, line_speed_lu_min: float) -> float:
    """Upper limit of the return speed (LU/min): Abs. Return Speed when not 0, else
    Rel. Return Speed x actual line speed (§4.3.1)."""
    absolute = params.get_raw("abs_return_speed")
    if absolute:
        return float(absolute)
    return params.return_speed * abs(line_speed_lu_min)


PRINTMARK_BUFFER_SIZE = 64  # cutting positions (§4.3.1, §4.3.5)


def max_printmarks_between_sensor_and_carriage(additional_cuts: int) -> int:
    """64 cutting positions shared by each mark and its additional cuts: 64, 32, 21, 16 (§4.3.5)."""
    if additional_cuts not in (0, 1, 2, 3):
        raise ParameterError(f"Additional Cuts {additional_cuts!r} is outside 0..3")
    return PRINTMARK_BUFFER_SIZE // (additional_cuts + 1)
