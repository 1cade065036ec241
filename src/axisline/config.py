"""The machine file (TOML): every field typed, ranged and explained.

    [machine]            name, cycle period, seed, run duration
    [[axis]]             one table per axis: the axis parameters (motion.axis.AxisConfig)
      [axis.drive]       type = "servo" | "stepper" and the drive model's parameters, or
                         "cia402": a CiA 402 drive on CANopen (drives/config.py)
      [axis.encoder]     optional: an incremental encoder on the motor (counts -> actual position)
      [[axis.switches]]  optional: reference and limit switches on the axis (name, kind, position ...)
    [material]           optional: the material line (web, strip) with its speed profile and slip
    [[marks]]            optional: print-mark sensors on the material
    [io]                 optional: named digital inputs and outputs
    [[master]], [[cam]]  optional: masters and cams the job couples axes to (sync_setup.py)
    [job]                the scripted main job: repeat, [[job.steps]]
    [trace]              the scope: capacity, decimation, channels

An unknown key, a wrong type or an out-of-range value is a ConfigError whose lines
name the key, the value and the allowed range. The file and the files it names (cam CSVs)
are read and checked whole when it is loaded, within size limits checked before any work:
`check` then refuses everything `run` would.
"""

from __future__ import annotations

import re
import tomllib
from pathlib import Path
from typing import Annotated, Any, Literal, Union

from pydantic import BaseModel, ConfigDict, Field, ValidationError, field_validator, model_validator

from .configerrors import ConfigError, explain, read_text, shown
from .drives.config import Cia402Entry
from .job import JobConfig
from .kernel.clock import MAX_PERIOD_US, MIN_PERIOD_US
from .motion.axis import AxisConfig
from .sync_setup import CamEntry, MasterEntry, load_cam_csv
from .plant.config import (
    ActuatorConfig,
    DigitalIOConfig,
    EncoderConfig,
    MaterialConfig,
    PrintMarkConfig,
    ServoDriveConfig,
    StepperDriveConfig,
    SwitchConfig,
)

Name = Annotated[str, Field(min_length=1, max_length=64, pattern=r"^[A-Za-z0-9_\-]+$")]

#: a machine file is a page of settings (the examples are below 10 kB; large tables go in CSV
#: files): the limit keeps a wrong or hostile file from costing seconds and memory to refuse
MAX_FILE_BYTES = 1 << 20
#: parts of one dotted key (a.b.c = 1); tomllib takes time and memory quadratic in this
MAX_KEY_PARTS = 16


class _Strict(BaseModel):
    model_config = ConfigDict(extra="forbid")


class MachineSection(_Strict):
    name: str = Field("axisline machine", min_length=1, max_length=200, description="shown in reports")
    cycle_us: int = Field(1000, ge=MIN_PERIOD_US, le=MAX_PERIOD_US, description="cycle period T in microseconds")
    seed: int = Field(0, ge=0, le=2**63 - 1, description="seed of the simulated plant's randomness")
    duration: float = Field(10.0, gt=0.0, le=7 * 86400.0, description="longest simulated run, seconds")
    logic_every: int = Field(
        1, ge=1, le=1000, description="the logic task (job, device logic) runs every n-th cycle, e.g. 4 as the CLM's"
    )
    personality: str = Field("none", max_length=64, description="device personality: none, or a registered device (its [device] table configures it)")


class ServoEntry(ServoDriveConfig):
    type: Literal["servo"] = "servo"
    command: Literal["digital", "analog"] = Field(
        "digital",
        description="digital: ideal velocity set point; analog: the +-10 V path with its offset, drift and gain errors",
    )

    def build(self):
        return ServoDriveConfig.model_validate(self.model_dump(exclude={"type", "command"})).build()


class StepperEntry(StepperDriveConfig):
    type: Literal["stepper"] = "stepper"

    def build(self):
        return StepperDriveConfig.model_validate(self.model_dump(exclude={"type"})).build()


# a CiA 402 drive on CANopen (drives/): the axis sees the same drive interface
DriveEntry = Annotated[Union[ServoEntry, StepperEntry, Cia402Entry], Field(discriminator="type")]


class SwitchEntry(SwitchConfig):
    name: Name = Field(description="switch name, e.g. ref or limit_pos; read as '<axis>.<name>'")


class AxisEntry(AxisConfig):
    """An axis with the drive, encoder and switches of the simulated plant behind it."""

    drive: DriveEntry = Field(default_factory=ServoEntry, description="the drive model")
    encoder: EncoderConfig | None = Field(None, description="incremental encoder; none: actual = drive position")
    switches: list[SwitchEntry] = Field(default_factory=list, max_length=16, description="switches on this axis")


class MarkEntry(PrintMarkConfig):
    name: Name = Field("marks", description="sensor name; its edges are read as '<name>'")
    carrier: Name | None = Field(
        None, description="an axis whose drive moves the marked strip past the sensor (a feed roll); none: the [material] line"
    )


class TraceConfig(_Strict):
    enabled: bool = True
    capacity: int = Field(
        200_000, ge=1, le=50_000_000,
        description="samples kept per channel (a linear trace allocates no more than machine.duration fills)",
    )
    decimation: int = Field(1, ge=1, le=10_000, description="record every n-th cycle")
    mode: Literal["linear", "ring"] = Field("linear", description="linear: stop when full; ring: keep the newest")
    channels: list[Annotated[str, Field(min_length=1, max_length=128)]] | Literal["all"] = Field(
        "all", max_length=4096, description="axis.signal names, or all"
    )

    @field_validator("channels")
    @classmethod
    def _unique(cls, channels: list[str] | str) -> list[str] | str:
        if channels != "all":
            seen: set[str] = set()
            for c in channels:
                if c in seen:  # the scope records each signal once (a second column would be a copy)
                    raise ValueError(f"{c!r} is listed twice")
                seen.add(c)
        return channels


class RealtimeConfig(_Strict):
    """Soft real-time measures for `axisline serve` (a simulated `run` never waits for the clock)."""

    gc: Literal["python", "idle"] = Field(
        "python",
        description="python: the interpreter collects garbage when it likes, inside a cycle too; idle: objects made at start are frozen, "
        "automatic collection is off, and `serve` collects in the idle time between cycles",
    )
    cpus: list[Annotated[int, Field(ge=0, le=4095)]] = Field(
        default_factory=list, max_length=64,
        description="CPUs the cycle process may run on (empty: any); the endpoint process then runs on the others",
    )
    fifo_priority: int = Field(
        0, ge=0, le=99,
        description="SCHED_FIFO priority of the cycle process, 1..99 (0: the normal scheduler); where not permitted, serve says so and runs on",
    )
    busy_wait_us: int = Field(
        0, ge=0, le=10_000,
        description="spin instead of sleeping for this long before each deadline (the OS wakes sleepers late); at most the period",
    )
    overrun_us: int | None = Field(
        None, ge=1, le=10_000_000,
        description="a cycle starting later than this after its deadline is an overrun (none: one period)",
    )
    on_overrun: Literal["log", "stop"] = Field(
        "log", description="log: count and log overruns; stop: also stop every axis with its stop ramp",
    )


class MachineConfig(_Strict):
    machine: MachineSection = Field(default_factory=MachineSection)
    axis: list[AxisEntry] = Field(default_factory=list, max_length=64)
    material: MaterialConfig | None = Field(None, description="the material line, if the machine has one")
    marks: list[MarkEntry] = Field(default_factory=list, max_length=16, description="print-mark sensors on the material")
    io: DigitalIOConfig = Field(default_factory=DigitalIOConfig, description="named digital inputs and outputs")
    actuator: list[ActuatorConfig] = Field(
        default_factory=list, max_length=64, description="cylinders on [io] outputs with end switches on [io] inputs (a press ram, a clamp)"
    )
    master: list[MasterEntry] = Field(default_factory=list, max_length=16, description="masters slaves can follow")
    device: dict[str, Any] = Field(default_factory=dict, description="the personality's own table, validated by it")
    cam: list[CamEntry] = Field(default_factory=list, max_length=64, description="cam curves")
    job: JobConfig = Field(default_factory=JobConfig)
    trace: TraceConfig = Field(default_factory=TraceConfig)
    realtime: RealtimeConfig = Field(default_factory=RealtimeConfig, description="soft real-time measures of `axisline serve`")

    @model_validator(mode="after")
    def _cross_checks(self) -> "MachineConfig":
        if self.realtime.busy_wait_us > self.machine.cycle_us:
            raise ValueError(f"realtime.busy_wait_us = {self.realtime.busy_wait_us} is longer than the cycle "
                             f"(machine.cycle_us = {self.machine.cycle_us}); allowed is 0..{self.machine.cycle_us}")
        names = [a.name for a in self.axis]
        for n in names:
            if names.count(n) > 1:
                raise ValueError(f"axis name {n!r} is used twice")
        switches = [f"{a.name}.{sw.name}" for a in self.axis for sw in a.switches]
        for n in switches:
            if switches.count(n) > 1:
                raise ValueError(f"switch name {n!r} is used twice")
        for i, mark in enumerate(self.marks):
            if mark.carrier is None and self.material is None:
                raise ValueError(f"marks[{i}]: a print-mark sensor reads marks from the [material] line or from a carrier axis; give one")
            if mark.carrier is not None and mark.carrier not in names:
                raise ValueError(f"marks[{i}].carrier = {mark.carrier!r}: no such axis (axes: {', '.join(names) or 'none'})")
        marks = [m.name for m in self.marks]
        for n in marks:
            if marks.count(n) > 1:
                raise ValueError(f"marks name {n!r} is used twice")
        masters = [m.name for m in self.master]
        cams = [c.name for c in self.cam]
        for kind, seen in (("master", masters), ("cam", cams)):
            for n in seen:
                if seen.count(n) > 1:
                    raise ValueError(f"{kind} name {n!r} is used twice")
        for i, act in enumerate(self.actuator):
            if act.valve not in self.io.outputs:
                raise ValueError(f"actuator[{i}].valve = {act.valve!r}: not an [io] output (outputs: {', '.join(self.io.outputs) or 'none'})")
            for key in ("retracted", "extended"):
                switch = getattr(act, key)
                if switch is not None and switch not in self.io.inputs:
                    raise ValueError(f"actuator[{i}].{key} = {switch!r}: not an [io] input (inputs: {', '.join(self.io.inputs) or 'none'})")
        for m in self.master:
            if m.axis is not None and m.axis not in names:
                raise ValueError(f"master {m.name!r}: axis = {m.axis!r}: no such axis (axes: {', '.join(names) or 'none'})")
            if m.kind == "axis_encoder" and next(a for a in self.axis if a.name == m.axis).encoder is None:
                raise ValueError(f"master {m.name!r}: axis {m.axis!r} has no [axis.encoder]")
            if m.carrier is not None and m.carrier not in names:
                raise ValueError(f"master {m.name!r}: carrier = {m.carrier!r}: no such axis (axes: {', '.join(names) or 'none'})")
            if m.kind == "wheel" and self.material is None and m.carrier is None:
                raise ValueError(f"master {m.name!r}: a measuring wheel needs a [material] line")
        for i, step in enumerate(self.job.steps):
            if step.command in ("gear_in", "gear_in_pos", "cam_in", "set_master_velocity") and step.master not in masters:
                raise ValueError(f"job.steps[{i}].master = {step.master!r}: no such master (masters: {', '.join(masters) or 'none'})")
            if step.command == "cam_in" and step.cam not in cams:
                raise ValueError(f"job.steps[{i}].cam = {step.cam!r}: no such cam (cams: {', '.join(cams) or 'none'})")
            if step.command in ("gear_in", "gear_in_pos") and (step.numerator is None or step.denominator is None):
                raise ValueError(f"job.steps[{i}]: {step.command} needs numerator and denominator")
            if step.command == "set_master_velocity":
                if step.velocity is None:
                    raise ValueError(f"job.steps[{i}]: set_master_velocity needs velocity")
                continue
            if step.command is not None and step.axis not in names:
                raise ValueError(f"job.steps[{i}].axis = {step.axis!r}: no such axis (axes: {', '.join(names) or 'none'})")
            if step.command == "home" and step.method == "switch" and f"{step.axis}.{step.switch}" not in switches:
                raise ValueError(
                    f"job.steps[{i}].switch = {step.switch!r}: axis {step.axis!r} has no such switch "
                    f"(switches: {', '.join(switches) or 'none'})"
                )
            if step.command is None and step.dwell is None:
                raise ValueError(f"job.steps[{i}]: a step needs a command or a dwell")
            try:
                step.arguments()
            except ValueError as e:
                raise ValueError(f"job.steps[{i}]: {e}") from None
        return self


def parse_machine(data: dict, source: str = "<machine>") -> MachineConfig:
    try:
        config = MachineConfig.model_validate(data)
    except ValidationError as err:
        raise explain(err, MachineConfig, source, data) from None
    device_config(config, source)  # the personality's table is checked with the rest of the file
    return config


def device_config(config: MachineConfig, source: str = "<machine>"):
    """The validated [device] table of the machine's personality (None without one)."""
    from .devices import base

    name = config.machine.personality
    if name == "none":
        if config.device:
            raise ConfigError(source, ["device: a [device] table needs machine.personality"])
        return None
    try:
        cls = base.load(name)
    except ValueError as e:
        raise ConfigError(source, [f"machine.personality = {shown(name)}: {e}"]) from None
    try:
        return cls.Config.model_validate(config.device)
    except ValidationError as err:
        inner = explain(err, cls.Config, source, config.device)
        raise ConfigError(source, [f"device.{p}" for p in inner.problems]) from None


# TOML strings and comments: their dots belong to no key. Every alternative matches in one
# pass, an unterminated string too (to the end of its line or of the text: the file is
# invalid then, and tomllib says so), so the scan stays linear on any input.
_TOML_TEXT = re.compile(
    r'"""(?:[^\\]|\\.)*?(?:"""|\Z)'  # multi-line basic string
    r"|'''.*?(?:'''|\Z)"  # multi-line literal string
    r'|"(?:[^"\\\n]|\\.)*+"?'  # basic string
    r"|'[^'\n]*+'?"  # literal string
    r"|#[^\n]*+",  # comment
    re.S,
)
# a dotted key (bare or quoted parts; strings are "" by then) of more than MAX_KEY_PARTS parts;
# possessive, and starting only where a part starts, so that it is linear too
_LONG_KEY = re.compile(r'(?<![\w"-])(?:[\w-]++|"")(?:[ \t]*+\.[ \t]*+(?:[\w-]++|"")){%d,}' % MAX_KEY_PARTS)


def _blank(m: re.Match[str]) -> str:
    """A string becomes "" and a comment nothing, line breaks kept (line numbers stay the file's)."""
    text = m.group()
    return ('""' if text[0] in "\"'" else "") + "\n" * text.count("\n")


def _toml_limits(text: str) -> str | None:
    """What in the text's shape would make tomllib itself slow (None: nothing)."""
    bare = _TOML_TEXT.sub(_blank, text)
    long_key = _LONG_KEY.search(bare)
    if long_key is not None:
        line = bare.count("\n", 0, long_key.start()) + 1
        return f"line {line}: a dotted key of more than {MAX_KEY_PARTS} parts (allowed: at most {MAX_KEY_PARTS})"
    return None


def load_machine_file(path: str | Path) -> MachineConfig:
    """Read, parse and check a machine file and the files it names (cam CSVs)."""
    p = Path(path)
    try:
        text = read_text(p, MAX_FILE_BYTES)
    except ValueError as e:
        raise ConfigError(str(p), [f"machine file: {e}"]) from None
    too_big = _toml_limits(text)
    if too_big is not None:
        raise ConfigError(str(p), [too_big])
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as e:
        raise ConfigError(str(p), [f"TOML syntax: {e}"]) from None
    except RecursionError:  # arrays or inline tables nested hundreds deep
        raise ConfigError(str(p), ["TOML: arrays or inline tables nested too deeply"]) from None
    config = parse_machine(data, str(p))
    problems = []
    for i, cam in enumerate(config.cam):
        if cam.csv is not None:
            try:
                load_cam_csv(cam, p.parent)
            except ValueError as e:
                problems.append(f"cam[{i}].csv = {shown(cam.csv)}: {e}")
    if problems:
        raise ConfigError(str(p), problems)
    return config
