"""The scope's channels of a machine: what each name reads, and the Trace wired to them.

Every axis offers eleven signals ("<axis>.command_position" ... "<axis>.enabled", in the
order of `AXIS_SIGNALS`); the plant its material line, sensors, I/O image and masters; a
personality its own (`trace_channels()`). The machine file's ``[trace] channels`` picks from
them in any order; "all" takes every one, axes first.

Cost (issue 18): the scope samples up to dozens of channels per cycle. The axis signals are
read by one compiled call for each run of consecutive axis channels in the file's order
(`AxisReads.read`, given to `Trace.add_channels`): "all" on a 16-axis machine is one call
for 176 values, not 176 calls. The plant's and the personality's channels keep a getter each
(attrgetter/partial, C calls).

Decisions:

1. Issue 18 "one getter per axis": a run of axis channels may span several axes and any
   subset of their signals; the trace's columns keep exactly the file's order (a run ends
   where a plant or device channel comes between), so the saved files are unchanged.
   Test: tests/test_scope_channels.py::test_channels_keep_the_file_order_and_values.
"""

from __future__ import annotations

from functools import partial
from operator import attrgetter
from typing import TYPE_CHECKING, Any, Callable, Final

from .configerrors import ConfigError
from .kernel import Trace
from .motion.axis import Axis, AxisState
from .plant.drives import ServoDrive, StepperDrive

if TYPE_CHECKING:
    from .machine import AxisUnit, Machine, Sensor

__all__ = ["AXIS_SIGNALS", "AxisReads", "make_trace", "plant_channels"]

Channel = tuple[Callable[[], Any], str, type]  # getter, unit, float|int|bool

# an axis' signals as "all" lists them: name, unit ("{u}": the axis' unit), kind; the index
# is the signal's number in AxisReads
AXIS_SIGNALS: Final = (
    ("command_position", "{u}", float),
    ("actual_position", "{u}", float),  # axis frame
    ("command_velocity", "{u}/s", float),
    ("actual_velocity", "{u}/s", float),  # the drive's
    ("command_acceleration", "{u}/s^2", float),
    ("actual_acceleration", "{u}/s^2", float),
    ("command_jerk", "{u}/s^3", float),
    ("following_error", "{u}", float),
    ("velocity_output", "{u}/s", float),
    ("state", "", int),  # 0 = DISABLED ... in AxisState's order
    ("enabled", "", bool),  # the drive's
)
_SIGNAL_NUMBER: Final = {name: i for i, (name, _, _) in enumerate(AXIS_SIGNALS)}
_STATE_CODE: Final = {s: i for i, s in enumerate(AxisState)}
_ALL: Final = list(range(len(AXIS_SIGNALS)))


class AxisReads:
    """The values of axis signals for the scope, many channels in one call (`read`).

    `reads`: (axis unit, signal number in `AXIS_SIGNALS`) pairs, in the channels' order.
    """

    def __init__(self, reads: list[tuple[AxisUnit, int]]) -> None:
        groups: list[_AxisGroup] = []
        for unit, signal in reads:  # consecutive signals of one axis: one group
            if not groups or groups[-1].unit is not unit:
                groups.append(_AxisGroup(unit))
            groups[-1].signals.append(signal)
        for group in groups:
            group.full = group.signals == _ALL
        self._groups = groups
        # the values, written in place each cycle (the trace packs them at once): no list
        # to grow and free per cycle
        self._out: list[Any] = [0.0] * len(reads)

    def read(self) -> list[Any]:
        """The values, in the channels' order (the same list each call, rewritten)."""
        out = self._out
        k = 0
        for group in self._groups:
            if group.full:
                group.read_all(out, k)
                k += 11
            else:
                k = group.read_some(out, k)
        return out


class _AxisGroup:
    """Signals of one axis: all eleven in order (`read_all`, straight-line code), or some."""

    def __init__(self, unit: AxisUnit) -> None:
        self.unit = unit
        self.axis: Axis = unit.axis
        drive = unit.drive
        self.drive: Any = drive
        # the simulated drives are compiled classes: their fields are read directly, any
        # other drive (CiA 402) by attribute lookup
        self.servo: ServoDrive | None = drive if isinstance(drive, ServoDrive) else None
        self.stepper: StepperDrive | None = drive if isinstance(drive, StepperDrive) else None
        self.signals: list[int] = []
        self.full = False
        # the state code is looked up when the state changes, not every cycle (an enum's
        # hash is a Python call)
        self._state: AxisState | None = None
        self._code = 0

    def state_code(self) -> int:
        state = self.axis.state
        if state is not self._state:
            self._state = state
            self._code = _STATE_CODE[state]
        return self._code

    def read_all(self, out: list[Any], k: int) -> None:
        """The eleven signals into out[k:k + 11]."""
        ax = self.axis
        out[k] = ax.command_position
        out[k + 1] = ax.actual_position
        out[k + 2] = ax.command_velocity
        out[k + 4] = ax.command_acceleration
        out[k + 6] = ax.command_jerk
        out[k + 7] = ax.following_error
        out[k + 8] = self.unit.velocity_output
        out[k + 9] = self.state_code()
        servo = self.servo
        stepper = self.stepper
        if servo is not None:
            out[k + 3] = servo.velocity
            out[k + 5] = servo.acceleration
            out[k + 10] = servo.enabled
        elif stepper is not None:
            out[k + 3] = stepper.velocity
            out[k + 5] = stepper.acceleration
            out[k + 10] = stepper.enabled
        else:
            drive = self.drive
            out[k + 3] = drive.velocity
            out[k + 5] = drive.acceleration
            out[k + 10] = drive.enabled

    def read_some(self, out: list[Any], k: int) -> int:
        """The group's signals into out from k on; returns the index after them."""
        ax = self.axis
        drive = self.drive  # (read only for the signals asked: not every drive has them all)
        for s in self.signals:
            if s == 0:
                out[k] = ax.command_position
            elif s == 1:
                out[k] = ax.actual_position
            elif s == 2:
                out[k] = ax.command_velocity
            elif s == 3:
                out[k] = drive.velocity
            elif s == 4:
                out[k] = ax.command_acceleration
            elif s == 5:
                out[k] = drive.acceleration
            elif s == 6:
                out[k] = ax.command_jerk
            elif s == 7:
                out[k] = ax.following_error
            elif s == 8:
                out[k] = self.unit.velocity_output
            elif s == 9:
                out[k] = self.state_code()
            else:
                out[k] = drive.enabled
            k += 1
        return k


def _getter(obj: Any, name: str) -> Callable[[], Any]:
    return partial(attrgetter(name), obj)


def _sensor_level(sensor: Sensor) -> bool:
    return bool(sensor.state)


def plant_channels(machine: Machine) -> dict[str, Channel]:
    """The material line's, the sensors', the I/O image's and the masters' channels."""
    config = machine.config
    out: dict[str, Channel] = {}
    axis_units = {a.name: a.unit for a in config.axis}
    first = next(iter(axis_units.values()), "units")
    line_unit = first
    if config.material is not None and config.material.unit is not None:
        line_unit = config.material.unit
    if machine.material is not None:
        mat = machine.material
        out["material.position"] = (lambda: mat.position, line_unit, float)
        out["material.speed"] = (lambda: mat.velocity, f"{line_unit}/s", float)
    for name, sensor in machine.sensors.items():
        out[f"{name}.state"] = (partial(_sensor_level, sensor), "", bool)
    for name in config.io.inputs:
        out[f"io.{name}"] = (partial(machine.io.read, name), "", bool)
    for name in config.io.outputs:
        out[f"io.{name}"] = (partial(machine.io.output, name), "", bool)
    entries = {m.name: m for m in config.master}
    for name, master in machine.masters.items():
        entry = entries.get(name)
        unit = "units"
        if entry is not None:
            if entry.unit is not None:
                unit = entry.unit
            elif entry.axis is not None:
                unit = axis_units.get(entry.axis, unit)
            elif entry.kind == "wheel":
                unit = axis_units.get(entry.carrier, line_unit) if entry.carrier is not None else line_unit
        out[f"{name}.position"] = (_getter(master, "position"), unit, float)
        out[f"{name}.velocity"] = (_getter(master, "velocity"), f"{unit}/s", float)
    return out


def make_trace(machine: Machine) -> Trace:
    """The scope of the machine file's [trace] table, its channels wired (decision 1)."""
    config = machine.config
    tc = config.trace
    capacity = tc.capacity
    if tc.mode == "linear":  # never allocate more than the longest run can fill
        capacity = min(capacity, round(config.machine.duration / machine.period) // tc.decimation + 1)
    trace = Trace(capacity, decimation=tc.decimation, mode=tc.mode, period_us=machine.clock.period_us)
    # every channel: name -> (unit, kind); its values come from an axis' signal or a getter
    available: dict[str, tuple[str, type]] = {}
    signals: dict[str, tuple[AxisUnit, int]] = {}
    getters: dict[str, Callable[[], Any]] = {}
    for name, u in machine.units.items():
        for number, (signal, unit, kind) in enumerate(AXIS_SIGNALS):
            channel = f"{name}.{signal}"
            available[channel] = (unit.format(u=u.config.unit), kind)
            signals[channel] = (u, number)
    others = plant_channels(machine)
    device_channels = getattr(machine.device, "trace_channels", None)
    if device_channels is not None:  # a personality's own signals ("fs701.line_speed", ...)
        others.update(device_channels())
    for channel, (getter, unit, kind) in others.items():
        available[channel] = (unit, kind)
        getters[channel] = getter
    wanted = list(available) if tc.channels == "all" else tc.channels
    unknown = [c for c in wanted if c not in available]
    if unknown:
        raise ConfigError(machine.source or "<machine>", [
            f"trace.channels: unknown channel {c!r} (available: {', '.join(available)})" for c in unknown
        ])
    run: list[str] = []  # consecutive axis channels: one AxisReads

    def end_run() -> None:
        if run:
            reads = AxisReads([signals[c] for c in run])
            trace.add_channels(run, reads.read, [available[c][0] for c in run], [available[c][1] for c in run])
            run.clear()

    for c in wanted:
        if c in signals:
            run.append(c)
        else:
            end_run()
            unit, kind = available[c]
            trace.add_channel(c, getters[c], unit=unit, kind=kind)
    end_run()
    return trace


# Compiled, the public names get this source's docstrings and annotations back (help(),
# inspect.signature); in plain Python this does nothing. See axisline/_docs.py.
from axisline._docs import document as _document  # noqa: E402

# hot: the scope's per-cycle call (a bound method handed to Trace), left compiled-only
_document(globals(), hot={"AxisReads": ("read",)})
