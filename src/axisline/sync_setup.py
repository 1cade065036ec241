"""Masters and cams in the machine file, and the job commands that couple axes to them.

    [[master]]   a master the slaves follow: virtual (velocity with ramps), time_base,
                 axis (another axis' set point or actual), wheel (a measuring wheel on the
                 material line, or with ``carrier`` on material a feed roll moves) or
                 axis_encoder (the encoder of an axis)
    [[cam]]      a cam curve: a point table, a C2 spline or segments of motion laws

Job steps then couple axes: gear_in, gear_in_pos, cam_in, cam_out, sync_out, and change a
virtual master's speed with set_master_velocity. The motion library does the work
(motion.master, motion.gear, motion.cam, motion.segments, motion.camsync); this module
only turns machine-file words into its objects.
"""

from __future__ import annotations

import csv
import io
from pathlib import Path
from typing import Annotated, Any, Literal

from pydantic import BaseModel, BeforeValidator, ConfigDict, Field, PrivateAttr, model_validator

from .configerrors import ConfigError, FilePath, read_text, shown
from .motion.cam import DEFAULT_MAX_POINTS, PointTable, SplineTable
from .motion.curve import CamCurve
from .motion.master import AxisMaster, EncoderMaster, Master, TimeBase, VirtualMaster
from .motion.segments import SEGMENT_LAWS, SegmentCam
from .plant.config import MeasuringWheelConfig, SlipConfig

Name = Annotated[str, Field(min_length=1, max_length=64, pattern=r"^[A-Za-z0-9_\-]+$")]

#: a cam CSV holds at most DEFAULT_MAX_POINTS lines of two numbers: far below this size
MAX_CSV_BYTES = 8 << 20


class MasterEntry(BaseModel):
    """One master (see the module docstring for the kinds)."""

    model_config = ConfigDict(extra="forbid", allow_inf_nan=False)

    name: Name = Field(description="master name, used by the job's coupling steps")
    kind: Literal["virtual", "time_base", "axis", "wheel", "axis_encoder"] = Field(description="what moves the master")
    velocity: float = Field(0.0, ge=-1e7, le=1e7, description="virtual / time_base: speed at start, units/s")
    acceleration: float | None = Field(None, gt=0.0, le=1e9, description="virtual: acceleration and deceleration")
    jerk: float | None = Field(None, gt=0.0, le=1e12, description="virtual: jerk (none: constant acceleration)")
    ramp_time: float = Field(0.0, ge=0.0, le=3600.0, description="time_base: time of every speed change, s")
    axis: str | None = Field(None, max_length=64, description="axis / axis_encoder: the axis")
    use: Literal["command", "actual"] = Field("command", description="axis: follow its set point or its actual position")
    wheel: MeasuringWheelConfig | None = Field(None, description="wheel: the measuring wheel on the material")
    carrier: Name | None = Field(
        None, description="wheel: an axis whose drive moves the material under the wheel (a feed roll); none: the [material] line"
    )
    carrier_slip: SlipConfig | None = Field(
        None, description="wheel with a carrier: how the material slips on the feed roll (seeded); none: it does not slip"
    )
    unit: str | None = Field(
        None, min_length=1, max_length=16,
        description="the master's length unit (none: its axis' for axis masters, the material's for a wheel, 'units' otherwise)",
    )
    velocity_filter: Literal["window", "first_order"] = Field("window", description="encoder masters: speed estimate")
    sampling_time: float | None = Field(None, gt=0.0, le=10.0, description="encoder masters: window length, s")
    time_constant: float | None = Field(None, gt=0.0, le=10.0, description="encoder masters: first-order filter, s")
    counts_per_unit: float | None = Field(
        None, gt=0.0, le=1e12, description="virtual / time_base / axis: resolution the gears count in (none: 1e9)"
    )

    @model_validator(mode="after")
    def _needs(self) -> "MasterEntry":
        if self.kind == "virtual" and self.acceleration is None:
            raise ValueError(f"master {self.name!r}: a virtual master needs an acceleration")
        if self.kind in ("axis", "axis_encoder") and self.axis is None:
            raise ValueError(f"master {self.name!r}: kind {self.kind!r} needs axis = the axis it follows")
        if self.kind == "wheel" and self.wheel is None:
            raise ValueError(f"master {self.name!r}: kind 'wheel' needs a [master.wheel] table")
        if self.carrier is not None and self.kind != "wheel":
            raise ValueError(f"master {self.name!r}: carrier = {self.carrier!r} is for a master of kind 'wheel' (this one is {self.kind!r})")
        if self.carrier_slip is not None and self.carrier is None:
            raise ValueError(f"master {self.name!r}: carrier_slip needs carrier = the axis whose feed roll moves the material")
        if self.velocity_filter == "first_order" and self.time_constant is None and self.kind in ("wheel", "axis_encoder"):
            raise ValueError(f"master {self.name!r}: velocity_filter 'first_order' needs time_constant")
        return self


def _law_word(value: Any) -> Any:
    # the motion library reads law names case-insensitively ("Cycloidal"); so does the file
    return value.strip().lower() if isinstance(value, str) else value


class SegmentEntry(BaseModel):
    """One segment of a cam of motion laws (motion.segments): from the previous segment's end
    (master 0 and `start` for the first) to (master_end, slave_end), along `law`."""

    model_config = ConfigDict(extra="forbid", allow_inf_nan=False)

    master_end: float = Field(gt=0.0, le=1e9, description="master position where the segment ends")
    slave_end: float = Field(ge=-1e9, le=1e9, description="slave position there")
    law: Annotated[Literal[SEGMENT_LAWS], BeforeValidator(_law_word)] = Field(  # type: ignore[valid-type]
        description="motion law (dwell: the slave rests; auto: C2 transition between its neighbours)"
    )


class CamEntry(BaseModel):
    """One cam curve over a master cycle."""

    model_config = ConfigDict(extra="forbid", allow_inf_nan=False)

    name: Name = Field(description="cam name, used by cam_in steps")
    master_period: float = Field(gt=0.0, le=1e9, description="master cycle length, master units")
    kind: Literal["table", "spline", "segments"] = Field("table", description="linear point table, C2 spline, or motion laws")
    points: list[tuple[float, float]] | None = Field(
        None, max_length=DEFAULT_MAX_POINTS, description="table / spline: (master, slave) pairs"
    )
    csv: FilePath = Field(None, min_length=1, max_length=4096, description="table / spline: a CSV file (header master,slave), relative to the machine file")
    segments: list[SegmentEntry] | None = Field(None, max_length=1000, description="segments: master_end, slave_end, law")
    start: float = Field(0.0, ge=-1e9, le=1e9, description="segments: slave position at master 0")
    periodic: bool = Field(True, description="spline / segments: the curve repeats C2 across the cycle")
    # the curve, once built: a curve given inline is built while the file is checked (so a
    # curve the motion library refuses is a bad machine file), a CSV one when it is loaded
    _curve: CamCurve | None = PrivateAttr(None)

    @model_validator(mode="after")
    def _source(self) -> "CamEntry":
        given = [k for k in ("points", "csv", "segments") if getattr(self, k) is not None]
        wanted = "segments" if self.kind == "segments" else "points or csv"
        if len(given) != 1 or (self.kind == "segments") != (given[0] == "segments"):
            raise ValueError(f"cam {self.name!r} of kind {self.kind!r} needs exactly one of: {wanted} (given: {', '.join(given) or 'none'})")
        if self.csv is None:
            self._curve = _curve(self, None)
        return self


def _curve(entry: CamEntry, rows: list[tuple[float, float]] | None) -> CamCurve:
    """The motion library's curve; its ValueError names the segment or point, the value and
    what is allowed, and is put under the cam's name here."""
    try:
        if entry.segments is not None:
            return SegmentCam(
                [s.model_dump() for s in entry.segments],
                start=entry.start, master_period=entry.master_period, periodic=entry.periodic,
            )
        points = rows if rows is not None else entry.points or []
        master = [p[0] for p in points]
        slave = [p[1] for p in points]
        if not master or master[-1] != entry.master_period:
            last = master[-1] if master else None
            raise ValueError(f"the last master point {last!r} must equal master_period {entry.master_period!r}")
        if entry.kind == "spline":
            return SplineTable(master, slave, entry.periodic)
        return PointTable(master, slave)
    except ValueError as e:
        raise ValueError(f"cam {entry.name!r}: {e}") from None


def load_cam_csv(entry: CamEntry, base_dir: Path) -> CamCurve:
    """Read the cam's CSV (header master,slave; further columns are ignored) and build its
    curve; ValueError with a one-line reason naming the line."""
    assert entry.csv is not None
    text = read_text(base_dir / entry.csv, MAX_CSV_BYTES)
    rows: list[tuple[float, float]] = []
    reader = csv.DictReader(io.StringIO(text, newline=""))
    try:
        header = reader.fieldnames
        if header is None or not {"master", "slave"} <= set(header):
            raise ValueError(f"expected a header master,slave (got {shown(', '.join(header or [])) if header else 'nothing'})")
        for r in reader:
            if len(rows) >= DEFAULT_MAX_POINTS:
                raise ValueError(f"line {reader.line_num}: more than {DEFAULT_MAX_POINTS} points (allowed: at most {DEFAULT_MAX_POINTS})")
            try:
                rows.append((float(r["master"]), float(r["slave"])))
            except (TypeError, ValueError):
                raise ValueError(
                    f"line {reader.line_num}: master = {shown(r['master'])}, slave = {shown(r['slave'])}: expected two numbers"
                ) from None
    except csv.Error as e:  # e.g. a NUL character in the text
        raise ValueError(f"line {reader.line_num}: not CSV: {e}") from None
    entry._curve = _curve(entry, rows)
    return entry._curve


def build_cam(entry: CamEntry, base_dir: Path) -> CamCurve:
    """The cam's curve: built when the machine file was checked, else now."""
    if entry._curve is not None:
        return entry._curve
    if entry.csv is not None:
        return load_cam_csv(entry, base_dir)
    return _curve(entry, None)


def build_master(entry: MasterEntry, machine: Any) -> tuple[Master, Any]:
    """The master and, for a wheel, the encoder the machine must sample each cycle."""
    period = machine.period
    cpu = {} if entry.counts_per_unit is None else {"counts_per_unit": entry.counts_per_unit}
    filt = {"velocity_filter": entry.velocity_filter, "sampling_time": entry.sampling_time, "time_constant": entry.time_constant}
    if entry.kind == "virtual":
        return VirtualMaster(period, entry.velocity, acceleration=entry.acceleration, jerk=entry.jerk, **cpu), None
    if entry.kind == "time_base":
        return TimeBase(period, entry.velocity, ramp_time=entry.ramp_time, **cpu), None
    if entry.kind == "axis":
        return AxisMaster(machine.units[entry.axis].axis, use=entry.use, **cpu), None
    if entry.kind == "axis_encoder":
        enc = machine.units[entry.axis].encoder
        return EncoderMaster(enc, enc.counts_per_unit, period, **filt), None
    wheel = entry.wheel.build(_wheel_material(entry, machine), machine.child_rng(f"master:{entry.name}"))
    return EncoderMaster(wheel, wheel.counts_per_unit, period, **filt), wheel


def _wheel_material(entry: MasterEntry, machine: Any) -> Any:
    """What the wheel rolls on: the [material] line, or material the carrier axis' feed roll
    pulls with its slip (a SlipContact on the roll's drive, seeded by the master's name)."""
    if entry.carrier is None:
        return machine.material
    unit = machine.units.get(entry.carrier)
    if unit is None:
        axes = ", ".join(machine.units) or "none"
        raise ConfigError(getattr(machine, "source", "") or "<machine>", [f"master {entry.name!r}: carrier = {entry.carrier!r}: no such axis (axes: {axes})"])
    slip = entry.carrier_slip if entry.carrier_slip is not None else SlipConfig()
    return slip.build(unit.drive, machine.child_rng(f"master:{entry.name}:carrier"))


class SyncHandle:
    """What a job waits on for a coupling: done once the slave is synchronous (or decoupled)."""

    def __init__(self, command: Any, ready: Any) -> None:
        self.command, self._ready = command, ready

    @property
    def done(self) -> bool:
        return not self.error and bool(self._ready())

    @property
    def error(self) -> bool:
        return bool(getattr(self.command, "error", False))

    @property
    def error_id(self) -> int:
        return getattr(self.command, "error_id", 0)

    @property
    def error_text(self) -> str:
        return getattr(self.command, "error_text", "")

    aborted = False
