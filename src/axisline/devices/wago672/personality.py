"""WAGO 750-672 stepper modules behind a Modbus TCP coupler, as a machine personality.

    [machine]
    cycle_us = 1000                 # the 750-672 runs a 1 ms TICK
    personality = "wago672"

    [device]
    watchdog_ms = 100               # the coupler's fieldbus watchdog (0: off, for hand tools)

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

`[[device.plc]]` (optional): a scripted PLC for `axisline run` - steps that set and clear
control bits, write set points and wait for status bits of the process image (plc.py). It is
the stand-in for the PLC that `serve` gets from the network: `serve` does not run it (one
master on the image). With a script the run ends when the script is done (`finished`), and
the summary's headline says what the PLC did.

Each cycle (LOGIC stage, before the axes sample their set points in SETPOINTS) the coupler
exchanges the process images with the modules and runs their 1 ms ticks (coupler.py). The
Modbus endpoint is the coupler: docs/wago672-modbus.md has the register map.
"""

from __future__ import annotations

import sys
from functools import partial
from pathlib import Path
from typing import Annotated, Any, Literal

from pydantic import BaseModel, ConfigDict, Field, StringConstraints, field_validator

from axisline.configerrors import ConfigError, FilePath
from axisline.devices.base import Personality
from axisline.devices.wago672.config_table import ConfigTable, ConfigValueError
from axisline.devices.wago672.coupler import MAX_MODULES, Coupler
from axisline.devices.wago672.device import Wago672
from axisline.devices.wago672.image import MODE_NAMES, OFFSET_C1, OFFSET_C2, InputImage
from axisline.devices.wago672.mailbox import attach
from axisline.devices.wago672.plc import PlcStep
from axisline.devices.wago672.plcscript import PlcScript, error_text
from axisline.devices.wago672.runreport import headline, report_section
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
    watchdog_ms: int = Field(
        100, ge=0, le=60000,
        description="fieldbus watchdog, ms: no write for longer stops the motors; 0 switches it off (hand tools); else 10 .. 60000",
    )
    plc: list[PlcStep] = Field(
        default_factory=list, max_length=10000,
        description="a scripted PLC for `axisline run`: steps on the process image (not run by serve)",
    )

    @field_validator("watchdog_ms")
    @classmethod
    def _watchdog(cls, v: int) -> int:
        if 0 < v < 10:
            raise ValueError(f"{v} ms is shorter than a Modbus request round trip: give 0 (off) or 10 .. 60000")
        return v


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
        for k, plc_step in enumerate(config.plc):
            if plc_step.module >= len(config.modules):
                problems.append(
                    f"device.plc[{k}].module = {plc_step.module} ({plc_step.label(k)}): no such module "
                    f"(allowed: 0 .. {len(config.modules) - 1}, the device.modules tables)"
                )
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
            on_expiry=self._watchdog_expired,
        )
        #: where console lines go (the watchdog's expiry, the script not run by serve)
        self.notify = _stderr
        self.script: PlcScript | None = None
        if config.plc:
            if _wall_clock(machine):  # `serve`: the network's PLC is the only master (plc.py, decision 3)
                self.notify(f"wago672: the [[device.plc]] script ({len(config.plc)} steps) is not run by serve: "
                            "the Modbus client is the PLC")
            else:
                self.script = PlcScript(config.plc, self.coupler, machine.period,
                                        error_text=lambda n: error_text(self.modules[n].device))
        self._failure_reported = False
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
        script = self.script
        if script is not None:  # the PLC's cycle: read the last inputs, write the outputs
            script.tick(cycle)
            if script.failed is not None and not self._failure_reported:
                self._failure_reported = True
                self.machine.faults.append(f"t={cycle * self.machine.period:.3f} s wago672: {script.failed}")
        self.coupler.tick(cycle)
        if self._outputs:
            io = self.machine.io
            for dev, name, io_name in self._outputs:
                io.write(io_name, dev.outputs[0 if name == "Output1" else 1])

    def _watchdog_expired(self, cycle: int, ticks: int) -> None:
        axes = ", ".join(f"module {m.index} (axis {m.axis})" for m in self.modules)
        self.notify(
            f"wago672: fieldbus watchdog expired at t={cycle * self.machine.period:.3f} s: no write for "
            f"{ticks * self.machine.period * 1000:.0f} ms (watchdog_ms = {self.coupler.watchdog_ms}); {axes} "
            f"{'brakes' if len(self.modules) == 1 else 'brake'} with the STOP ramp, then its outputs are 0; "
            "the next write re-arms it ([device] watchdog_ms = 0: off)"
        )

    @property
    def finished(self) -> bool | None:  # type: ignore[override]  # (Personality: a plain attribute)
        """The PLC script: None without one, else whether it is done (or failed)."""
        return None if self.script is None else self.script.done

    def trace_channels(self) -> dict[str, tuple[Any, str, type]]:
        """Each module's status bytes S1, S2 (as the PLC reads them) and the PLC script's step."""
        out: dict[str, tuple[Any, str, type]] = {}
        for m in self.modules:
            for name, offset in (("S1", OFFSET_C1), ("S2", OFFSET_C2)):
                out[f"wago672.m{m.index}.{name}"] = (partial(_status_byte, self.coupler, m.index, offset), "", int)
        if self.script is not None:
            out["wago672.plc_step"] = (partial(_plc_step, self.script), "", int)
        return out

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
        out: dict[str, Any] = {"coupler": self.coupler.summary(), "modules": modules}
        for entry, m in zip(modules, self.modules):
            unit = self.machine.units[m.axis]
            entry["axis_position"] = unit.axis.actual_position
            entry["unit"] = unit.config.unit
        s = self.script
        out["plc"] = None if s is None else {
            "steps": len(s.steps), "done": s.steps_done, "failed": s.failed, "failure": s.failure, "log": list(s.log),
        }
        out["plc_configured"] = len(self.config.plc)
        out["headline"] = headline(out)
        return out

    def report_markdown(self, device_summary: dict[str, Any], plots: list[Path]) -> str:
        return report_section(device_summary)


def _status_byte(coupler: Coupler, module: int, offset: int) -> int:
    return coupler.inputs(module)[offset]


def _plc_step(script: PlcScript) -> int:
    """The step running, 1-based; 0 once the script is done or failed."""
    return 0 if script.done else script.index + 1


def _stderr(line: str) -> None:
    print(line, file=sys.stderr, flush=True)


def _wall_clock(machine: Any) -> bool:
    """Runs on the wall clock (`axisline serve`), not the simulated one (`run`, tests)."""
    from axisline.kernel.clock import WallClock

    return isinstance(getattr(machine, "clock", None), WallClock)
