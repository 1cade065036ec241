"""WAGO 750-672 stepper modules behind a Modbus TCP coupler, as a machine personality.

    [machine]
    cycle_us = 1000                 # the 750-672 runs a 1 ms TICK
    personality = "wago672"

    [device]
    watchdog_ms = 100               # the coupler's fieldbus watchdog

    [[device.modules]]              # one table per module, in K-bus order
    axis = "x"                      # a stepper axis of this machine file
    inputs = { Input1 = true, Input2 = "x.ref", Input5 = "x.limit_pos", Input6 = "x.limit_neg" }
    config = { SetupSpeed = 5000 }  # the module's FACTORY_DEFAULT configuration values
    outputs = { Output1 = "in_position" }   # optional: DO1/DO2 to io outputs
    eeprom = "x.eeprom.json"        # optional: the module's EEPROM image (relative to this file)

Wiring of Input1 .. Input6 (DI1 .. DI6 of the module; by default Stop1_N, the reference
switch, Jog_Pos, Jog_Neg, LimitSwitch_Pos, LimitSwitch_Neg): `true`/`false` (a constant level,
e.g. the Stop1_N circuit closed), the name of a switch of the machine file ("<axis>.<switch>")
or print-mark sensor, or the name of an [io] input. An input not wired reads 0, as an open
input does: without `Input1 = true` (or a closed stop circuit) the axis cannot be started.

Configuration: `config` sets values of the configuration table by the manual's names; they are
this module's FACTORY_DEFAULT, so they hold at power-on unless a user data set was saved into
the module's EEPROM (CONFIG_SAVE), as on a real module, and CONFIG_RESTORE brings them back.
Mailbox, table manager, run programs, filters and data recorder are plugged into each module
(`mailbox.attach`); with `eeprom` the EEPROM (saved configuration, tables) is a JSON file that
survives a restart - the module writes it when it stores, `persist()` completes pending writes.

The module's axis: a stepper drive with 64 microsteps per full step (the 750-672 has a fixed
64-fold microstepping) and `counts_per_unit` = the drive's microsteps per unit (the module
counts microsteps: its positions are microsteps unless Pos_Mult/Pos_Div scale them). The axis
belongs to the module: job steps must not command it.

Each cycle (LOGIC stage, before the axes sample their set points in SETPOINTS) the coupler
exchanges the process images with the modules and runs their 1 ms ticks (coupler.py). The
Modbus endpoint is the coupler: docs/wago672-modbus.md has the register map.
"""

from __future__ import annotations

from pathlib import Path
from typing import Annotated, Any, Literal

from pydantic import BaseModel, ConfigDict, Field, StringConstraints

from axisline.configerrors import ConfigError, FilePath
from axisline.devices.base import Personality
from axisline.devices.wago672.config_table import ConfigTable, ConfigValueError
from axisline.devices.wago672.coupler import MAX_MODULES, Coupler
from axisline.devices.wago672.device import Wago672
from axisline.devices.wago672.image import MODE_NAMES, InputImage
from axisline.devices.wago672.mailbox import attach
from axisline.kernel.atomic import unwritable_reason

__all__ = ["ModuleEntry", "Wago672Config", "Wago672Personality"]

InputName = Literal["Input1", "Input2", "Input3", "Input4", "Input5", "Input6"]
OutputName = Literal["Output1", "Output2"]
Signal = Annotated[str, StringConstraints(min_length=1, max_length=130, pattern=r"^[A-Za-z0-9_.\-]+$")]
MICROSTEPS = 64  # the 750-672's microstepping (manual §3: 64 microsteps per full step)


class ModuleEntry(BaseModel):
    """One 750-672 on the coupler."""

    model_config = ConfigDict(extra="forbid")

    axis: str = Field(min_length=1, max_length=64, description="the stepper axis this module drives")
    inputs: dict[InputName, bool | Signal] = Field(
        default_factory=dict,
        description="Input1..Input6: true/false, a switch '<axis>.<name>', a sensor or an [io] input; unwired: 0",
    )
    outputs: dict[OutputName, Signal] = Field(default_factory=dict, description="Output1/Output2 (DO1/DO2) to [io] outputs")
    config: dict[str, int] = Field(
        default_factory=dict, description="configuration-table values by the manual's names (e.g. SetupSpeed = 5000): the FACTORY_DEFAULT"
    )
    eeprom: FilePath = Field(
        None, min_length=1, max_length=4096,
        description="EEPROM image file (JSON, relative to the machine file); none: the EEPROM lasts as long as the run",
    )


class Wago672Config(BaseModel):
    """The [device] table of personality "wago672"."""

    model_config = ConfigDict(extra="forbid")

    modules: list[ModuleEntry] = Field(min_length=1, max_length=MAX_MODULES, description="the 750-672 modules in K-bus order")
    watchdog_ms: int = Field(100, ge=10, le=60000, description="fieldbus watchdog: no write for longer stops the motors")


class _Module:
    """A configured module: the device, its axis name and its wiring."""

    def __init__(self, index: int, axis: str, device: Wago672, wiring: dict[str, Any], outputs: dict[str, str], mailbox: Any) -> None:
        self.index = index
        self.axis = axis
        self.device = device
        self.wiring = wiring
        self.outputs = outputs
        self.mailbox = mailbox  # mailbox.Mailbox: tables, program, filters, recorder


class Wago672Personality(Personality):
    """WAGO Modbus TCP coupler with 750-672 stepper modules (see the module docstring)."""

    name = "wago672"
    Config = Wago672Config
    endpoints = ("modbus",)

    def __init__(self, machine: Any, config: Wago672Config) -> None:
        super().__init__(machine, config)
        source = getattr(machine, "source", "") or "<machine>"
        problems: list[str] = []
        mc = machine.config
        if mc.machine.cycle_us != 1000:
            problems.append(f"machine.cycle_us = {mc.machine.cycle_us}: the 750-672 runs a 1 ms TICK (allowed: 1000)")
        if mc.machine.logic_every != 1:
            problems.append(f"machine.logic_every = {mc.machine.logic_every}: the 750-672 ticks every cycle (allowed: 1)")
        signals = sorted(set(machine.sensors) | set(mc.io.inputs))
        used: dict[str, int] = {}
        eeproms: dict[Path, int] = {}
        self.modules: list[_Module] = []
        for i, entry in enumerate(config.modules):
            where = f"device.modules[{i}]"
            unit = machine.units.get(entry.axis)
            if unit is None:
                problems.append(f"{where}.axis = {entry.axis!r}: no such axis (axes: {', '.join(machine.units) or 'none'})")
            else:
                problems.extend(self._check_axis(where, entry.axis, unit))
                if entry.axis in used:
                    problems.append(f"{where}.axis = {entry.axis!r}: already driven by device.modules[{used[entry.axis]}]")
                used[entry.axis] = i
            for name, value in entry.inputs.items():
                if isinstance(value, str) and value not in signals:
                    problems.append(
                        f"{where}.inputs.{name} = {value!r}: no such switch, sensor or io input "
                        f"(known: {', '.join(signals) or 'none'}; or true/false)"
                    )
            for name, value in entry.outputs.items():
                if value not in mc.io.outputs:
                    problems.append(f"{where}.outputs.{name} = {value!r}: no such io output (outputs: {', '.join(mc.io.outputs) or 'none'})")
            try:
                table = ConfigTable(defaults=entry.config)
                table.validate()
            except KeyError as e:
                problems.append(f"{where}.config: {e.args[0]}")
            except ConfigValueError as e:
                problems.append(f"{where}.config: {e}")
            eeprom = None
            if entry.eeprom is not None:
                eeprom = Path(entry.eeprom)
                if not eeprom.is_absolute() and getattr(machine, "source", ""):
                    eeprom = Path(machine.source).parent / eeprom
                reason = unwritable_reason(eeprom)
                if reason is not None:  # the module writes it whenever it stores: refuse it now, not at run time
                    problems.append(f"{where}.eeprom = {entry.eeprom!r}: {eeprom} {reason}")
                if eeprom in eeproms:
                    problems.append(f"{where}.eeprom = {entry.eeprom!r}: also the EEPROM of device.modules[{eeproms[eeprom]}]")
                eeproms.setdefault(eeprom, i)
            if problems or unit is None:
                continue  # build nothing once something is wrong: the ConfigError below names it all
            wiring = {name: self._signal(value) for name, value in entry.inputs.items()}
            device = Wago672(unit.axis, wiring, table)
            try:
                mbx = attach(device, eeprom)  # the power-on: configuration and tables from the EEPROM
            except ValueError as e:
                problems.append(f"{where}.eeprom = {entry.eeprom!r}: {e}")
                continue
            self.modules.append(_Module(i, entry.axis, device, wiring, dict(entry.outputs), mbx))
        for k, step in enumerate(mc.job.steps):
            if step.command is not None and step.axis in used:
                problems.append(f"job.steps[{k}].axis = {step.axis!r}: the axis is driven by the 750-672 of device.modules[{used[step.axis]}]")
        if problems:
            raise ConfigError(source, problems)
        self.coupler = Coupler(
            [m.device for m in self.modules],
            config.watchdog_ms,
            tick_s=machine.period,
            writes_allowed=lambda: self.network_writes,
        )
        self._outputs = tuple((m.device, name, io_name) for m in self.modules for name, io_name in m.outputs.items())

    @staticmethod
    def _check_axis(where: str, name: str, unit: Any) -> list[str]:
        drive = unit.config.drive
        if getattr(drive, "type", None) != "stepper":
            return [f"{where}.axis = {name!r}: axis {name!r} has a {getattr(drive, 'type', '?')} drive; the 750-672 drives a stepper"]
        out = []
        if drive.microsteps != MICROSTEPS:
            out.append(f"axis {name!r}: drive.microsteps = {drive.microsteps}: the 750-672 makes {MICROSTEPS} microsteps per full step (allowed: {MICROSTEPS})")
        per_unit = drive.steps_per_unit * drive.microsteps
        if abs(unit.config.counts_per_unit - per_unit) > 1e-9 * per_unit:
            out.append(
                f"axis {name!r}: counts_per_unit = {unit.config.counts_per_unit:g}: the 750-672 counts microsteps, "
                f"so it must be drive.steps_per_unit * drive.microsteps = {per_unit:g}"
            )
        return out

    def _signal(self, value: bool | str) -> Any:
        """A wired input: a constant, or a function reading a sensor or an io input."""
        return self.machine.signal(value)

    # ------------------------------------------------------------------ Personality

    def tick(self, cycle: int) -> None:
        self.coupler.tick(cycle)
        if self._outputs:
            io = self.machine.io
            for dev, name, io_name in self._outputs:
                io.write(io_name, dev.outputs[0 if name == "Output1" else 1])

    def register_endpoint(self) -> Coupler:
        return self.coupler

    def device(self, module: int = 0) -> Wago672:
        """The Wago672 of module `module` (K-bus order)."""
        return self.modules[module].device

    def stop(self) -> bool:
        """Shutdown: the modules brake with their own stop ramp (Acceleration_Stop_Fast), as on a
        watchdog expiry, so each module's set point stays the axis' set point."""
        self.coupler.stop_modules()
        return True

    def persist(self) -> list[Path]:
        """Complete the EEPROM writes still pending; returns the EEPROM image files."""
        files: list[Path] = []
        for m in self.modules:
            tables = m.mailbox.tables
            tables.flush()
            if tables.path is not None and tables.path.exists():
                files.append(tables.path)
        return files

    def store_paths(self) -> list[Path]:
        return [m.mailbox.tables.path for m in self.modules if m.mailbox.tables.path is not None]

    def summary(self) -> dict[str, Any]:
        modules = []
        for m in self.modules:
            dev = m.device
            image = InputImage.from_bytes(self.coupler.inputs(m.index))
            modules.append({
                "module": m.index,
                "axis": m.axis,
                "mode": MODE_NAMES.get(dev.mode, str(dev.mode)),
                "ready": dev.ready,
                "error": dev.errors.error,
                "warning": dev.errors.warning,
                "position": dev.actual_position,
                "velocity": dev.actual_velocity,
                "on_target": dev.on_target,
                "busy": dev.busy,
                "reference_ok": dev.reference_ok,
                "status": {"S0": image.s0, "S1": image.s1, "S2": image.s2, "S3": image.s3},
            })
        return {"coupler": self.coupler.summary(), "modules": modules}
