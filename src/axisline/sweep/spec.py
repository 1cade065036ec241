"""The sweep file (TOML): which machine, which parameters over which values, what to collect.

    [sweep]
    name = "..."                      shown in the report
    base = "line.toml"                the machine file every case starts from (relative to this file)
    duration = 5.0                    simulated seconds per case (default: the machine file's)
    seed = 1                          the sweep's seed: random draws and per-case machine seeds
    machine_seed = "file"             "file": machine.seed of the base file; "per_case": one from each case's values
    collect = ["completed", "summary.max_abs_error_lu", "cuts.error_lu"]
    feasible = ["completed == true", "summary.count >= 2"]

    [parameters]                      dotted machine-file keys, in quotes; the cases are their product
    "axis.carriage.kv" = [20, 30, 40]                                    a list
    "material.profile[0].speed" = { start = 250, stop = 1500, step = 250 }   a range (stop included)
    "device.parameters.cutting_length" = { start = 50, stop = 2000, num = 40, scale = "log", round = 0 }
    "axis.carriage.drive.time_constant" = { random = "uniform", low = 0.002, high = 0.006, count = 8 }

    [report]
    heatmap = { x = "material.profile[0].speed", y = "device.parameters.cutting_length", metric = "summary.max_abs_error_lu" }
    line = { x = "material.profile[0].speed", metric = "summary.cuts_per_minute" }
    boundary = "envelope.min_length_lu"

An unknown key, a wrong type or a value out of range is a SweepError whose lines name the key,
the value and the allowed range (the same wording as the machine file's, configerrors.explain).

Decisions
1. (issue: "any field of the personality's JSON summary") `wall_s` and `realtime_factor` are
   refused in `collect`: they measure the computer, and the results must be identical on any
   engine and worker count. Test: test_sweep_file.py::test_wall_clock_fields_are_refused.
2. (issue: "random draws") a random parameter is a dimension of `count` draws; draw j comes
   from its own generator seeded with (sweep seed, the key, j), so a larger count keeps the
   earlier draws (a grown sweep resumes) and no engine sees another order. Test:
   test_cases.py::test_random_draws_are_stable_and_seeded.
3. (issue: "per-case deterministic seeds") machine_seed = "per_case" gives each case a plant
   seed from the sweep seed and the case's own values (not its position in the grid), so
   adding a value to a list leaves the other cases' seeds and results alone. Test:
   test_cases.py::test_per_case_seeds_follow_the_values.
"""

from __future__ import annotations

import math
import re
import tomllib
from pathlib import Path
from typing import Annotated, Any, Literal, Union

from pydantic import BaseModel, ConfigDict, Discriminator, Field, Tag, ValidationError, field_validator, model_validator

from axisline.configerrors import ConfigError, explain, read_text, shown

__all__ = ["SweepError", "SweepFile", "load_sweep_file", "parse_condition", "MAX_CASES", "WALL_CLOCK_FIELDS"]

#: the sweep file is a page of settings; large value lists belong in ranges
MAX_FILE_BYTES = 1 << 20
#: the product of all parameters; the tables are assembled in memory (about 2 kB a case)
MAX_CASES = 2_000_000
#: values of one parameter
MAX_VALUES = 1_000_000
#: fields of the run summary that are the computer's, not the case's (decision 1)
WALL_CLOCK_FIELDS = ("wall_s", "realtime_factor")

#: a machine-file key: parts separated by dots, each part a key or a name, with [index] suffixes
KEY_RE = re.compile(r"^[A-Za-z_][\w\-]*(\[\d+\])*(\.[A-Za-z0-9_][\w\-]*(\[\d+\])*)*$")
#: a result field: the same shape (summary keys, axes by name, per-cut tables)
FIELD_RE = KEY_RE
_CONDITION_RE = re.compile(r"^\s*([A-Za-z_][\w\-.\[\]]*)\s*(==|!=|<=|>=|<|>)\s*(.+?)\s*$")

Scalar = Union[bool, int, float, str]


class SweepError(ConfigError):
    """A sweep file that cannot be used; `problems` lists one line per bad key."""


class _Strict(BaseModel):
    model_config = ConfigDict(extra="forbid")


class RangeParameter(_Strict):
    """start .. stop (stop included) by `step`, or `num` values spaced linearly or geometrically."""

    start: int | float = Field(description="first value")
    stop: int | float = Field(description="last value (included when the step lands on it)")
    step: int | float | None = Field(None, description="distance between values (with start, stop)")
    num: int | None = Field(None, ge=1, le=MAX_VALUES, description="number of values (instead of step)")
    scale: Literal["linear", "log"] = Field("linear", description="log: geometric spacing (num only; start, stop > 0)")
    round: int | None = Field(None, ge=0, le=12, description="decimals to round to; 0: whole numbers (ints)")

    @model_validator(mode="after")
    def _one_spacing(self) -> "RangeParameter":
        if (self.step is None) == (self.num is None):
            raise ValueError("give either step or num")
        if self.step is not None:
            if not self.step > 0 or not math.isfinite(self.step):
                raise ValueError(f"step = {self.step}: must be > 0")
            if self.stop < self.start:
                raise ValueError(f"stop = {self.stop} < start = {self.start}: a range with a step runs upwards")
            n = math.floor((self.stop - self.start) / self.step * (1 + 1e-12)) + 1
            if n > MAX_VALUES:
                raise ValueError(f"{n} values (allowed: at most {MAX_VALUES})")
            if self.scale == "log":
                raise ValueError("scale = 'log' needs num, not step")
        if self.scale == "log" and not (self.start > 0 and self.stop > 0):
            raise ValueError("scale = 'log' needs start > 0 and stop > 0")
        return self


class RandomParameter(_Strict):
    """`count` random draws (decision 2)."""

    random: Literal["uniform", "loguniform", "normal", "integers"] = Field(description="the distribution")
    count: int = Field(ge=1, le=MAX_VALUES, description="number of draws")
    low: float | None = Field(None, description="uniform, loguniform, integers: lowest value")
    high: float | None = Field(None, description="uniform, loguniform: highest value; integers: highest value (included)")
    mean: float | None = Field(None, description="normal: mean")
    std: float | None = Field(None, ge=0.0, description="normal: standard deviation")
    round: int | None = Field(None, ge=0, le=12, description="decimals to round to; 0: whole numbers (ints)")

    @model_validator(mode="after")
    def _needs(self) -> "RandomParameter":
        need = ("mean", "std") if self.random == "normal" else ("low", "high")
        missing = [k for k in need if getattr(self, k) is None]
        if missing:
            raise ValueError(f"random = {self.random!r} needs {' and '.join(missing)}")
        if self.random != "normal" and not self.low <= self.high:  # type: ignore[operator]
            raise ValueError(f"low = {self.low} > high = {self.high}")
        if self.random == "loguniform" and not self.low > 0:  # type: ignore[operator]
            raise ValueError("random = 'loguniform' needs low > 0")
        return self


def _parameter_kind(v: Any) -> str | None:
    """A list, a range ({start, stop, ...}) or random draws ({random = ..., ...})."""
    if isinstance(v, (list, tuple)):
        return "list"
    if isinstance(v, dict):
        return "random" if "random" in v else "range"
    if isinstance(v, (RangeParameter, RandomParameter)):
        return "random" if isinstance(v, RandomParameter) else "range"
    return None


Parameter = Annotated[
    Union[
        Annotated[Annotated[list[Scalar], Field(min_length=1, max_length=MAX_VALUES)], Tag("list")],
        Annotated[RangeParameter, Tag("range")],
        Annotated[RandomParameter, Tag("random")],
    ],
    Discriminator(_parameter_kind, custom_error_type="parameter_form",
                  custom_error_message="a list of values, a range {start, stop, step | num} or random draws {random, count, ...}"),
]


class SweepSection(_Strict):
    name: str = Field("sweep", min_length=1, max_length=200, description="shown in the report")
    base: str = Field(min_length=1, max_length=4096, description="the machine file every case starts from, relative to the sweep file")
    duration: float | None = Field(None, gt=0.0, le=7 * 86400.0, description="simulated seconds per case; none: the machine file's machine.duration")
    seed: int = Field(0, ge=0, le=2**63 - 1, description="the sweep's seed: random draws and per-case machine seeds")
    machine_seed: Literal["file", "per_case"] = Field(
        "file", description="file: every case runs with the base file's machine.seed; per_case: a seed from the sweep seed and the case's values"
    )
    stop_on_fault: bool = Field(
        True, description="end a case at its first runtime fault (its summary is as at that moment); false: run on to the duration, as `axisline run` does"
    )
    collect: list[Annotated[str, Field(min_length=1, max_length=200, pattern=FIELD_RE.pattern)]] = Field(
        default_factory=lambda: ["completed"], min_length=1, max_length=200,
        description="result fields: dotted keys of the run summary (`axisline run --json`); a key through a list "
        "without an index (cuts.error_lu) is a per-row field of that table",
    )
    feasible: list[Annotated[str, Field(min_length=1, max_length=300)]] = Field(
        default_factory=list, max_length=50,
        description="conditions 'FIELD OP VALUE' (OP: == != < <= > >=, VALUE in TOML: 2, 0.5, true, \"text\", []) that all hold in a feasible case",
    )

    @field_validator("collect")
    @classmethod
    def _collect(cls, v: list[str]) -> list[str]:
        for f in v:
            if f.split(".")[0].split("[")[0] in WALL_CLOCK_FIELDS:
                raise ValueError(f"{f!r} is the computer's wall-clock time, not a result of the case (results must be identical on any engine)")
        if len(set(v)) != len(v):
            raise ValueError("a field is listed twice")
        return v

    @field_validator("feasible")
    @classmethod
    def _conditions(cls, v: list[str]) -> list[str]:
        for c in v:
            parse_condition(c)
        return v


class HeatmapSpec(_Strict):
    x: str = Field(description="a parameter key (columns)")
    y: str = Field(description="a parameter key (rows)")
    metric: str = Field(description="a collected field (colour)")


class LineSpec(_Strict):
    x: str = Field(description="a parameter key")
    metric: str = Field(description="a collected field")


class ReportSection(_Strict):
    heatmap: HeatmapSpec | None = Field(None, description="a metric over two parameters, the feasible region marked")
    line: LineSpec | None = Field(None, description="a metric over one parameter (one line per value of another)")
    boundary: str | None = Field(
        None, description="a collected field giving, per heatmap x, the computed y where the feasible region starts "
        "(e.g. envelope.min_length_lu): drawn on the heatmap and compared with the simulated boundary"
    )


class SweepFile(_Strict):
    sweep: SweepSection
    parameters: dict[Annotated[str, Field(min_length=1, max_length=200)], Parameter] = Field(
        min_length=1, max_length=32, description="dotted machine-file keys and their values"
    )
    report: ReportSection = Field(default_factory=ReportSection)

    @field_validator("parameters")
    @classmethod
    def _keys(cls, v: dict[str, Any]) -> dict[str, Any]:
        for k in v:
            if not KEY_RE.match(k):
                raise ValueError(f"{k!r} is not a dotted machine-file key (like axis.carriage.kv or material.profile[0].speed)")
        return v

    @model_validator(mode="after")
    def _report_names(self) -> "SweepFile":
        keys = list(self.parameters)
        fields = list(self.sweep.collect)
        checks: list[tuple[str, str, list[str], str]] = []
        if self.report.heatmap is not None:
            h = self.report.heatmap
            checks += [("report.heatmap.x", h.x, keys, "parameters"), ("report.heatmap.y", h.y, keys, "parameters"),
                       ("report.heatmap.metric", h.metric, fields, "sweep.collect")]
        if self.report.line is not None:
            checks += [("report.line.x", self.report.line.x, keys, "parameters"),
                       ("report.line.metric", self.report.line.metric, fields, "sweep.collect")]
        if self.report.boundary is not None:
            checks.append(("report.boundary", self.report.boundary, fields, "sweep.collect"))
            if self.report.heatmap is None:
                raise ValueError("report.boundary is drawn on the heatmap: give report.heatmap")
        for where, name, known, table in checks:
            if name not in known:
                raise ValueError(f"{where} = {name!r}: not in {table} ({', '.join(map(repr, known))})")
        for c in self.sweep.feasible:
            field, _, _ = parse_condition(c)
            if field not in fields:
                raise ValueError(f"sweep.feasible: {c!r}: the field {field!r} is not in sweep.collect")
        if "machine.seed" in self.parameters and self.sweep.machine_seed == "per_case":
            raise ValueError("machine.seed is a parameter: sweep.machine_seed = 'per_case' would replace it (use 'file')")
        n = 1
        for p in self.parameters.values():
            n *= len(p) if isinstance(p, list) else (p.count if isinstance(p, RandomParameter) else 1)
        if n > MAX_CASES:
            raise ValueError(f"{n} cases (allowed: at most {MAX_CASES})")
        return self


def parse_condition(text: str) -> tuple[str, str, Any]:
    """'summary.count >= 2' -> ("summary.count", ">=", 2); ValueError naming what is wrong."""
    m = _CONDITION_RE.match(text)
    if m is None:
        raise ValueError(f"{text!r}: expected FIELD OP VALUE with OP one of == != < <= > >=")
    field, op, literal = m.groups()
    try:
        value = tomllib.loads(f"v = {literal}")["v"]
    except tomllib.TOMLDecodeError:
        raise ValueError(f"{text!r}: the value {literal!r} is not a TOML value (2, 0.5, true, \"text\", [])") from None
    if op in ("<", "<=", ">", ">=") and not (isinstance(value, (int, float)) and not isinstance(value, bool)):
        raise ValueError(f"{text!r}: {op} compares numbers")
    return field, op, value


def holds(value: Any, op: str, expected: Any) -> bool:
    """The condition on one case's value; a missing value (None) holds no order comparison."""
    if op == "==":
        return value == expected
    if op == "!=":
        return value != expected
    if not isinstance(value, (int, float)) or isinstance(value, bool) or value is None:
        return False
    return {"<": value < expected, "<=": value <= expected, ">": value > expected, ">=": value >= expected}[op]


def load_sweep_file(path: str | Path) -> SweepFile:
    """Read and check a sweep file (the machine-file keys are checked against the base later)."""
    p = Path(path)
    try:
        text = read_text(p, MAX_FILE_BYTES)
    except ValueError as e:
        raise SweepError(str(p), [f"sweep file: {e}"]) from None
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as e:
        raise SweepError(str(p), [f"TOML syntax: {e}"]) from None
    except RecursionError:
        raise SweepError(str(p), ["TOML: arrays or inline tables nested too deeply"]) from None
    if "sweep" not in data and {"machine", "axis", "device"} & set(data):
        raise SweepError(str(p), ["this is a machine file; a sweep file names it: [sweep] base = \"MACHINE.toml\", "
                                  "and the keys to vary in [parameters] (docs/sweep.md)"])
    try:
        return SweepFile.model_validate(data)
    except ValidationError as err:
        e = explain(err, SweepFile, str(p), data)
        raise SweepError(e.source, e.problems) from None


def base_path(spec: SweepFile, sweep_file: str | Path) -> Path:
    """The base machine file, relative to the sweep file."""
    b = Path(spec.sweep.base)
    return (b if b.is_absolute() else Path(sweep_file).parent / b).resolve()


def describe(p: Any) -> str:
    """A parameter's values in a line of the report."""
    if isinstance(p, list):
        return ", ".join(shown(v) for v in p[:8]) + (f", ... ({len(p)} values)" if len(p) > 8 else "")
    if isinstance(p, RangeParameter):
        spacing = f"step {p.step:g}" if p.step is not None else f"{p.num} values, {p.scale}"
        return f"{p.start:g} .. {p.stop:g}, {spacing}"
    return f"{p.count} draws, {p.random}"
