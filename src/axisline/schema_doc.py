"""The machine-file reference (docs/machine-file.md), generated from the schema itself.

The pydantic models are the single source of truth for every key's type, default,
allowed range and meaning; this renders them as tables so the documentation cannot
drift from the code (a test compares the committed file with a fresh rendering).
"""

from __future__ import annotations

import typing
from typing import Any

from pydantic import BaseModel
from pydantic_core import PydanticUndefined

from .configerrors import allowed_range


def _type_name(annotation: Any) -> str:
    origin = typing.get_origin(annotation)
    args = typing.get_args(annotation)
    if origin is typing.Literal:
        return " \\| ".join(repr(a) for a in args)
    if origin is typing.Annotated:
        return _type_name(args[0])
    if origin in (typing.Union, getattr(__import__("types"), "UnionType", None)):
        return " or ".join(_type_name(a) for a in args if a is not type(None)) + (" (optional)" if type(None) in args else "")
    if origin is list:
        return f"list of {_type_name(args[0])}" if args else "list"
    if isinstance(annotation, type):
        return annotation.__name__ if not issubclass(annotation, BaseModel) else f"table ({annotation.__name__})"
    return str(annotation)


def _default(info) -> str:
    if info.default is PydanticUndefined:
        return "required" if info.default_factory is None else "(table)"
    if info.default is None:
        return "none"
    return repr(info.default)


def model_table(model: type[BaseModel]) -> list[str]:
    rows = ["| key | type | default | allowed | meaning |", "|---|---|---|---|---|"]
    for name, info in model.model_fields.items():
        rng = allowed_range(info)
        desc = (info.description or "").replace("|", "\\|").replace("\n", " ")
        rows.append(f"| `{name}` | {_type_name(info.annotation)} | {_default(info)} | {rng} | {desc} |")
    return rows


def render() -> str:
    from .config import AxisEntry, MachineSection, MarkEntry, RealtimeConfig, ServoEntry, StepperEntry, SwitchEntry, TraceConfig
    from .drives.config import Cia402Entry
    from .plant.config import ServoDriveConfig
    from .job import JobConfig, JobStep
    from .plant.config import ActuatorConfig, DigitalIOConfig, EncoderConfig, MaterialConfig, MeasuringWheelConfig, SpeedChangeConfig
    from .config import MAX_FILE_BYTES
    from .job import REQUIRED
    from .sync_setup import MAX_CSV_BYTES, CamEntry, MasterEntry, SegmentEntry

    sections = [
        ("[machine]", MachineSection, "The machine as a whole."),
        ("[[axis]]", AxisEntry, "One table per axis: the axis parameters (PLCopen axis, profile, position loop)."),
        ("[axis.drive] type = \"servo\"", ServoEntry, "Servo amplifier with a velocity loop (simulated)."),
        ("[axis.drive] type = \"stepper\"", StepperEntry, "Stepper motor with a microstepping driver (simulated)."),
        ("[axis.drive] type = \"cia402\"", Cia402Entry, "A CiA 402 servo drive over CANopen in Cyclic Synchronous Position mode (docs/drives.md)."),
        ("[axis.drive.simulated]", ServoDriveConfig, "With interface = \"virtual\": the servo model of the simulated CiA 402 drive (the [axis.encoder] is its motor encoder)."),
        ("[axis.encoder]", EncoderConfig, "Incremental encoder on the motor; without it the actual position is the drive's."),
        ("[[axis.switches]]", SwitchEntry, "Reference and limit switches on the axis, read as `<axis>.<name>`."),
        ("[material]", MaterialConfig, "The material line (web, strip) and its speed profile."),
        ("[[material.profile]]", SpeedChangeConfig, "A speed change of the material line."),
        ("[[marks]]", MarkEntry, "A print-mark sensor reading marks printed on the material."),
        ("[io]", DigitalIOConfig, "Named digital inputs and outputs; an input named like a switch follows it."),
        ("[[actuator]]", ActuatorConfig, "A cylinder (press ram, clamp) on an [io] output with end switches on [io] inputs."),
        ("[[master]]", MasterEntry, "A master that slaves follow (gear_in, gear_in_pos, cam_in job steps)."),
        ("[master.wheel]", MeasuringWheelConfig, "kind = \"wheel\": a measuring wheel rolling on the material."),
        ("[[cam]]", CamEntry, "A cam curve over one master cycle (`segments` rows: master_end, slave_end, law)."),
        ("[[cam]] segments = [...]", SegmentEntry, "One segment of a cam of motion laws; the last one ends at master_period."),
        ("[job]", JobConfig, "The scripted main job."),
        ("[[job.steps]]", JobStep, "One step: an axis command with its arguments, and/or a dwell. A command needs "
         + "; ".join(f"{c}: {', '.join(a)}" for c, a in REQUIRED.items()) + "."),
        ("[trace]", TraceConfig, "The scope: what is recorded each cycle."),
        ("[realtime]", RealtimeConfig, "Soft real-time measures of `axisline serve` (docs/serve.md); a simulated run ignores them."),
    ]
    out = [
        "# The machine file",
        "",
        "Generated from the schema by `axisline schema` (do not edit by hand; `tests/test_schema_doc.py`",
        "fails when this file and the code disagree). A key not listed in its table, a value of the",
        "wrong type or outside its range is refused with a message naming the key, the value and the",
        "allowed range. A machine file is UTF-8 text of at most "
        f"{MAX_FILE_BYTES >> 20} MiB (a cam's CSV file at most {MAX_CSV_BYTES >> 20} MiB).",
        "",
    ]
    for title, model, text in sections:
        out += [f"## {title}", "", text, ""] + model_table(model) + [""]
    return "\n".join(out)
