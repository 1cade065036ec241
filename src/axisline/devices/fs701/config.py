"""The `[device]` table of an FS701 machine file (pydantic models).

Apart from the personality's run-time code (personality.py, which re-exports them): the
schema is read by `axisline schema` and the checks, the personality by the cycle, and a
module that mypyc compiles (compiled_modules.txt) cannot define pydantic models.
"""

from __future__ import annotations

from typing import Annotated, Any, Literal

from pydantic import BaseModel, ConfigDict, Field, StringConstraints, field_validator

from axisline.configerrors import FilePath

from .loop import LEAD_MAX_MS
from .parameters import ParameterSet

__all__ = ["AdjustConfig", "DEFAULT_INPUTS", "Fs701Config", "ShearConfig", "Signal"]

Signal = Annotated[str, StringConstraints(min_length=1, max_length=130, pattern=r"^[A-Za-z0-9_.\-]+$")]

DEFAULT_INPUTS: dict[str, bool | str] = {"control_enable": "job", "start_stop": "job", "cut_completed": "shear"}
"""The demo wiring: the batch job switches Control Enable and Start/Stop, the shear answers."""


class ShearConfig(BaseModel):
    """The simulated cutting tool on the carriage (line.py: Shear)."""

    model_config = ConfigDict(extra="forbid")

    blade_delay: float = Field(0.02, ge=0.0, le=10.0, description="s from Ready to Cut until the blade passes the material (the cut instant)")
    cut_time: float = Field(0.06, gt=0.0, le=60.0, description="s from Ready to Cut until the tool signals Cut completed")
    pulse: float = Field(0.02, gt=0.0, le=10.0, description="s the Cut completed signal lasts")


class AdjustConfig(BaseModel):
    """The Adjust program's own settings (the PC software's "Adjust Carriage" card, §7.1)."""

    model_config = ConfigDict(extra="forbid")

    speed: int | None = Field(
        None, ge=1, le=9_999_999,
        description="LU/min, the card's Vir. Master Speed; none: 10 % of Max. Line Speed (the manual's default). "
        "Ana-Out Gain 2 is tuned at this speed: near the line's working speed it is right where the cuts are made",
    )
    ramp_time: float = Field(1.0, ge=0.0, le=99.0, description="s from 0 to Max. Line Speed in the Adjust runs (0: at once)")


class Fs701Config(BaseModel):
    """The [device] table of personality "fs701"."""

    model_config = ConfigDict(extra="forbid")

    carriage: str = Field(
        min_length=1, max_length=64,
        description="the carriage axis: a servo drive with command = 'analog' (Ana-Out 2) and an [axis.encoder] (Encoder 2)",
    )
    line: str = Field(
        "virtual", min_length=1, max_length=64,
        description="the line encoder (Encoder 1): a [[master]] of kind 'wheel' or 'axis_encoder', or 'virtual' (only the FS701's virtual master)",
    )
    printmark_sensor: str | None = Field(
        None, min_length=1, max_length=64, description="the print-mark sensor (a [[marks]] name) on In15, for Cutting Mode 2/3"
    )
    parameter_file: FilePath = Field(
        None, min_length=1, max_length=4096, description="FS701 parameter set file (TOML, paramfile.py), relative to the machine file"
    )
    parameters: dict[str, int | float] = Field(
        default_factory=dict, description="parameter values by snake_case name in engineering units (after the file), e.g. cutting_length = 1000"
    )
    save_parameters: FilePath = Field(
        None, min_length=1, max_length=4096,
        description="persist() and 'Store to EEProm' write the parameter set here (relative to the machine file); none: never written",
    )
    inputs: dict[str, bool | Signal] = Field(
        default_factory=lambda: dict(DEFAULT_INPUTS),
        description="input functions (control_enable, start_stop, cut_completed, ...) or terminals In1..In16: true/false, "
        "'job' (the batch job), 'shear' (the tool's Cut completed), a sensor or an [io] input; replaces the default wiring",
    )
    outputs: dict[str, Signal] = Field(
        default_factory=dict, description="output signals (ready_to_cut, home, error, ...) or terminals Out1..Out8 to [io] outputs"
    )
    commissioning: bool = Field(True, description="run the Adjust program (direction check, Ana-Out Offset 2 and Gain 2) before the first cycle")
    adjust: AdjustConfig = Field(default_factory=AdjustConfig, description="the Adjust program's speed and ramp")
    acceleration_feed_forward: float | Literal["auto"] = Field(
        0.0,
        description="ms: the set point's acceleration x this lead is added to the feed-forward (axisline, not an FS701 "
        "register; loop.py L10). 0: the FS701's loop (feed-forward + P + I). 'auto': the Adjust program measures it "
        "(commissioning = true, or the serial Adjust Program); 0 until it has run",
    )
    batch: int = Field(0, ge=0, le=10_000_000, description="pieces to cut (Batch Counter cuts) before the job stops the cutter; 0: no end")
    start_delay: float = Field(0.02, gt=0.0, le=60.0, description="s from Control Enable to Start in the batch job")
    shear: ShearConfig = Field(default_factory=ShearConfig, description="the simulated cutting tool")
    tolerance: float = Field(1.0, gt=0.0, le=1e6, description="length tolerance, carriage increments, for pieces cut at constant line speed")
    ramp_tolerance: float = Field(2.0, gt=0.0, le=1e6, description="length tolerance, carriage increments, for pieces with a cut during a speed change")
    mark_tolerance: float = Field(2.0, gt=0.0, le=1e6, description="print-mark cuts: largest offset to the mark, carriage increments")
    tolerance_fault: bool = Field(True, description="a piece out of tolerance is a run fault (exit 1)")

    @field_validator("acceleration_feed_forward")
    @classmethod
    def _lead_range(cls, v: float | str) -> float | str:
        if isinstance(v, (int, float)) and not 0.0 <= v <= LEAD_MAX_MS:
            raise ValueError(f"acceleration_feed_forward = {v} ms: allowed 0 .. {LEAD_MAX_MS:g} ms, or 'auto'")
        return v

    @field_validator("parameters")
    @classmethod
    def _known_parameters(cls, v: dict[str, Any]) -> dict[str, Any]:
        bad = [k for k in v if k not in ParameterSet()]
        if bad:
            raise ValueError(f"unknown FS701 parameter(s) {', '.join(map(repr, bad))} (snake_case names of the manual's §11, e.g. cutting_length)")
        return v
