"""The [device] table of personality "compax" (docs/compax.md "The machine file").

`CompaxConfig` is the table, `CurveEntry` one of its ``[[device.curves]]``. The values are
checked when the machine file is read: a wrong key is named with its value and what is
allowed. The personality (personality.py) builds the device from them; without P98 / P143 it
takes them from the master encoder (`derive_master_scaling`).

The start-up list (``startup``) holds what a host sends at power on: lines of the ASCII
interface (``SETC 1``, ``P31=2``, ``F6=0.5``, ``N001: SETC 1``, ``START``, ...) and
``WAIT ms``; the program sets themselves (GOTO, IF, END) belong to the program memory
(``program_file``, program.py).
"""

from __future__ import annotations

import math
import re
from typing import Annotated, Any, Literal

from pydantic import AfterValidator, BaseModel, ConfigDict, Field, StringConstraints, field_validator, model_validator

from axisline.configerrors import FilePath
from axisline.devices.compax import CompaxError
from axisline.devices.compax.ascii import MAX_LINE
from axisline.devices.compax.cammemory import MAX_CURVES, MAX_POINTS_PER_CURVE
from axisline.devices.compax.parameters import PARAMETERS, Parameters

__all__ = ["CompaxConfig", "CurveEntry", "InputName", "OutputName", "ProgramLine", "derive_master_scaling"]

Signal = Annotated[str, StringConstraints(min_length=1, max_length=130, pattern=r"^[A-Za-z0-9_.\-]+$")]
Name = Annotated[str, StringConstraints(min_length=1, max_length=64, pattern=r"^[A-Za-z0-9_\-]+$")]
InputName = Literal["I1", "I2", "I3", "I4", "I5", "I6", "I7", "I8", "I9", "I10", "I11", "I12", "I13", "I14", "I15", "I16"]
OutputName = Literal["O1", "O2", "O3", "O4", "O5", "O6", "O7", "O8", "O9", "O10", "O11", "O12", "O13", "O14", "O15", "O16"]

# lines of the start-up list (spaces removed, upper case): the ASCII interface's and WAIT ms
_PROGRAM_LINES = tuple(
    re.compile(p)
    for p in (
        r"[IFB]\d+(=.+)?",
        r"P\d+(=.+)?",
        r"S\d+",
        r"RESETF|VF|VP|VC|RESETP|SETS|SS|POSRCAM|PR|POSAHOME|START|STOP|BREAK",
        r"(SETC|SC|SETM|SM|LOOP|LP).+",
        r"(POSA|POSR|SPEED|ACCEL)[+-.\d]+|OUTPUTO\d+=\d+",
        r"N\d+(:.*|[A-Z].*)?",
        r"WAIT\d+(\.\d*)?",
    )
)

# ---------------------------------------------------------------------------------------
# configuration


def _program_line(line: str) -> str:
    key = "".join(line.split()).upper()
    if not any(p.fullmatch(key) for p in _PROGRAM_LINES):
        raise ValueError(
            "not a line of the ASCII interface (SETC n, SETM x, SETS, POSR CAM, LOOP m, F/I/B<address>=value, "
            "P<n>=value, VP, VC, VF, RESETF, RESETP, POSA x, POSR x, OUTPUT On=x, N<n>: set, START, STOP, "
            "BREAK) or WAIT ms"
        )
    return line


ProgramLine = Annotated[str, StringConstraints(min_length=1, max_length=MAX_LINE), AfterValidator(_program_line)]


class CurveEntry(BaseModel):
    """One curve written into a new cam memory: from a CSV file, motion-law segments or a [[cam]]."""

    model_config = ConfigDict(extra="forbid")

    number: int = Field(ge=1, le=MAX_CURVES, description="curve number n (SETC n); curves are numbered 1, 2, ... without gaps")
    csv: FilePath = Field(
        None, min_length=1, max_length=4096,
        description="a master,slave CSV (slave in units), relative to the machine file; equidistant, or give points to resample",
    )
    segments: list[dict[str, Any]] | None = Field(
        None, max_length=1000, description="motion-law segments (master_end, slave_end, law) as in [[cam]]; needs master_period and points"
    )
    cam: Name | None = Field(None, description="the name of a [[cam]] of the machine file; needs points")
    master_period: float | None = Field(None, gt=0.0, le=8_388_607.0, description="segments: the master cycle M_T, master units")
    start: float = Field(0.0, ge=-1e9, le=1e9, description="segments: slave position at master 0")
    points: int | None = Field(
        None, ge=2, le=MAX_POINTS_PER_CURVE, description="set points to sample (equidistant over M_T); a CSV is resampled when given"
    )
    slave_cycle: float | None = Field(
        None, ge=-8_388_607.0, le=8_388_607.0, description="S_T, slave units (none: the largest |slave value| of the curve)"
    )
    coupling: float = Field(0.0, ge=0.0, le=1.0, description="M_E, coupling position, fraction of M_T")
    synchronous: float = Field(0.0, ge=0.0, le=1.0, description="M_S, synchronous position, fraction of M_T")
    decoupling: float = Field(0.0, ge=0.0, le=1.0, description="M_A, decoupling position, fraction of M_T")
    braking: float = Field(0.0, ge=0.0, le=1.0, description="M_B, braking position, fraction of M_T")
    standstill: float = Field(0.0, ge=-1.0, le=1.0, description="S_0, standstill position, fraction of S_T")
    label_set_point: float = Field(0.0, ge=0.0, le=1.0, description="M_M (S_M), label set point, fraction of M_T (S_T)")
    label_window: float = Field(0.0, ge=0.0, le=0.3, description="M_f, half width of the label window, fraction of M_T (S_T)")
    correction_enable: float = Field(0.0, ge=0.0, le=1.0, description="M_k1, corrections from this master position, fraction of M_T")
    correction_disable: float = Field(0.0, ge=0.0, le=1.0, description="M_k2, corrections up to this master position, fraction of M_T")

    @model_validator(mode="after")
    def _source(self) -> "CurveEntry":
        given = [k for k in ("csv", "segments", "cam") if getattr(self, k) is not None]
        if len(given) != 1:
            raise ValueError(f"curve {self.number}: give exactly one of csv, segments, cam (given: {', '.join(given) or 'none'})")
        if self.segments is not None and (self.master_period is None or self.points is None):
            raise ValueError(f"curve {self.number}: segments need master_period and points")
        if self.cam is not None and self.points is None:
            raise ValueError(f"curve {self.number}: cam = {self.cam!r} needs points (the set points to sample)")
        if self.slave_cycle == 0.0:
            raise ValueError(f"curve {self.number}: slave_cycle = 0 cannot scale the curve")
        return self

    def block(self) -> dict[str, float]:
        names = ("coupling", "synchronous", "decoupling", "braking", "standstill", "label_set_point",
                 "label_window", "correction_enable", "correction_disable")
        return {n: getattr(self, n) for n in names}


class CompaxConfig(BaseModel):
    """The [device] table of personality "compax"."""

    model_config = ConfigDict(extra="forbid")

    slave: Name = Field(description="the machine axis COMPAX drives as its slave (job steps must not command it)")
    master: Name = Field(
        "internal",
        description="master encoder: a [[master]] name (wheel, axis_encoder, ...), an axis with an [axis.encoder], or internal (time base)",
    )
    memory_file: FilePath = Field(
        None, min_length=1, max_length=4096,
        description="cam memory file (JSON, relative to the machine file): loaded at start if present, saved by persist(); none: not kept",
    )
    parameter_file: FilePath = Field(
        None, min_length=1, max_length=4096,
        description="parameter file (JSON): loaded at start if present instead of device.parameters, saved by persist()",
    )
    program_file: FilePath = Field(
        None, min_length=1, max_length=4096,
        description="program sets 'N001: SETC 1' (text, relative to the machine file; # or ; starts a comment): "
                    "loaded into the program memory unless the memory_file already holds a program",
    )
    curves: list[CurveEntry] = Field(
        default_factory=list, max_length=MAX_CURVES, description="curves for a new cam memory (ignored when memory_file exists)"
    )
    parameters: dict[str, int | float] = Field(
        default_factory=dict, description="parameter values by number (P33 = 1): written, then VC and VP"
    )
    inputs: dict[InputName, bool | Signal] = Field(
        default_factory=dict,
        description="I1...I16: true/false, a switch '<axis>.<name>', a print-mark sensor or an [io] input; I12 defaults to true, the rest to false",
    )
    outputs: dict[OutputName, Signal] = Field(default_factory=dict, description="O1...O16 to [io] outputs")
    startup: list[ProgramLine] = Field(
        default_factory=list, max_length=1000,
        description="start-up list: ASCII-interface lines (SETC 1, SETM 0, LOOP 0, P31=2, VP, START, ...) and WAIT ms, sent in order at start",
    )
    label_tolerance: float = Field(
        10.0, gt=0.0, le=500.0, description="label error (per mille of the cycle) the report counts as converged"
    )
    trace: bool = Field(True, description="offer the compax.* scope channels (trace.channels = all, or by name)")

    @field_validator("parameters")
    @classmethod
    def _parameters(cls, value: dict[str, int | float]) -> dict[str, int | float]:
        probe = Parameters()
        problems = []
        for key, v in value.items():
            m = re.fullmatch(r"[Pp]?(\d+)", key.strip())
            if m is None or int(m[1]) not in PARAMETERS:
                problems.append(f"{key} = {v!r}: not a parameter of the device (e.g. P33)")
                continue
            try:
                probe[int(m[1])] = v
            except CompaxError as e:
                problems.append(str(e))
        if problems:
            raise ValueError("; ".join(problems))
        return value

    def parameter_values(self) -> dict[int, int | float]:
        return {int(re.fullmatch(r"[Pp]?(\d+)", k.strip())[1]): v for k, v in self.parameters.items()}  # type: ignore[index]


def derive_master_scaling(counts_per_unit: float, *, preferred_p98: float | None = None) -> tuple[float, int] | None:
    """(P98, P143) so that 4·P143/P98 = counts_per_unit (the master encoder's increments per
    master unit, §4.5): the preferred P98 (a wheel's circumference) first, then round values.
    None when no P143 of 128 ... 2 000 000 fits exactly."""
    c = float(counts_per_unit)
    if not (math.isfinite(c) and c > 0):
        return None
    candidates: list[float] = [preferred_p98] if preferred_p98 else []
    candidates += [1, 2, 3, 4, 5, 6, 8, 9, 10, 12, 15, 16, 18, 20, 24, 25, 30, 32, 36, 40, 45, 48, 50, 60, 64, 72,
                   75, 80, 90, 96, 100, 120, 125, 128, 144, 150, 160, 180, 200, 240, 250, 256, 300, 360, 400, 500,
                   512, 600, 720, 750, 1000, 1024, 2000, 2048, 3600, 4096, 5000, 10000]
    for p98 in candidates:
        p143 = c * p98 / 4.0
        r = round(p143)
        if abs(p143 - r) <= 1e-9 * max(1.0, p143) and 128 <= r <= 2_000_000 and 0 < p98 <= 4_000_000:
            return float(p98), int(r)
    return None
