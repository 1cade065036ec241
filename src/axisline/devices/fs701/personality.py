"""The motrona FS701 (flying shear / saw) as a machine personality: a cut-to-length line.

    [machine]
    personality = "fs701"
    logic_every = 1                  # the FS701 closes its loop every cycle (1 ms)

    [device]
    carriage = "carriage"            # servo axis, [axis.drive] command = "analog", [axis.encoder]
    line = "wheel"                   # [[master]] of kind "wheel" / "axis_encoder", or "virtual"
    parameter_file = "params/fs701_params.toml"   # a parameter set (paramfile.py), relative to this file
    commissioning = true             # run the Adjust program (offset, gain) before the first cycle
    batch = 20                       # cut 20 pieces, then stop (0: cut until the run ends)

    [device.parameters]              # overrides by snake_case name, engineering units
    cutting_length = 1000

    [device.inputs]                  # FS701 input functions (or terminals In1..In16)
    control_enable = "job"           # true/false, "job" (the batch), "shear" (the tool's
    start_stop = "job"               # Cut completed), a sensor or an [io] input
    cut_completed = "shear"

    [device.shear]                   # the simulated tool: blade and Cut completed timing
    blade_delay = 0.02

What runs where (the machine's cycle, machine.py):

    INPUTS          the line encoder (measuring wheel / axis encoder) and the carriage encoder
    LOGIC           Fs701Personality.tick: parameter writes from the network -> the cutter's
                    settings; terminal levels -> hardware command word -> All Commands (OR of
                    hardware, serial, CAN: registers.py) -> cutter inputs; print-mark edges;
                    Cutter.tick (the cut cycle, cutter.py); the shear and the cut measurement;
                    the batch job (line.py); counters back into the registers
    SETPOINTS       the carriage axis samples the cutter (its SyncSource)
    POSITION_LOOP   the FS701's PI loop with feed-forward (loop.py) replaces the axis' Kv loop
                    (Machine.drive_by): carriage encoder counts / Pulses Cut -> Ana-Out 2 volts
    ACTUATE         the carriage drive gets the volts on its analogue input (with its offset and
                    gain errors), the material moves, the print-mark sensor sees the marks

Endpoints: `byte_endpoint()` is the Drivecom protocol (drivecom.py) over the live register map
(registers.py: parameters, process values, command and status words, wired to the cutter);
`register_endpoint()` the same registers as Modbus holding registers (docs/fs701-serial.md).
Writes (parameters, serial command bits) are refused - NAK, Modbus exception - unless the
operator enabled them (`network_writes`, `serve --allow-writes`).

Decisions:
 D1 The FS701's length unit (LU) is the machine file's length unit: the carriage axis, the
    material and the masters are written in it (mm in the examples). The encoders must match the
    parameter set: Pulses Line / 1000 and Pulses Cut / 1000 within 2 % of the plant encoders'
    increments per 1000 LU, and Mode Counter 1/2 equal to their x1/x2/x4 evaluation; a
    mismatch is a configuration error (a real unit would simply cut wrong lengths).
 D2 The carriage's actual position is read as the FS701 reads it: carriage encoder increments
    (Dir. Counter 2 sign) / (Pulses Cut / 1000 / 1000); the axis' own scaling is not used.
 D3 Parameters written over the network act from the next cycle, except Pulses Line / 1000,
    Pulses Cut / 1000, Dir. Counter 1 / 2 and Sampling Time: they scale the encoders, so they
    take effect at the next Control Enable OFF (the cut cycle is then rebuilt, counters and
    Zero kept). Batch / Waste Counter written over the network set the cutter's counters.
 D4 The Adjust program (§7: direction check, offset, gain) runs before the first cycle with the
    carriage disconnected from the line, on the carriage's plant drive; the carriage is then put
    back at its start position. Its results (Ana-Out Offset 2, Gain 2) go into the parameter set
    and the EEPROM image. At runtime the serial / bus command bits 30 "Adjust Program" and 31
    "Test Program" (manual §4.1.1 "Control Enable must be OFF"; registers.py refuses the
    write while Control Enable is ON, or while the other program's bit is set) start, on their
    rising edge in All Commands, the Adjust program (direction check, Ana-Out Offset 2, Gain 2:
    new values into the parameter set, not the EEPROM until "Store to EEProm") or the Test
    program (the §7.4 "Cycle": TEST_PROGRAM_CYCLES up/down ramps at the adjust speed; process
    value #31 "Test Counter" = the cycles completed, reset when it is entered). Each runs to its
    end within that cycle on the carriage's plant drive (simulated time of the procedure is
    not added to the machine's clock); the carriage is then back where it stood, unpowered.
    Holding the bit does not repeat it; clear and set it again. A rising edge with Control
    Enable ON (only possible from the CAN word) is logged as refused in `programs`.
    The Adjust card's Vir. Master Speed and Ramp Time are [device.adjust] speed and ramp_time
    (`adjust_steps`, and the Test program's cycle); with acceleration_feed_forward = "auto" the Adjust program also measures
    the feed-forward's lead (loop.py L10), kept in the cutter's settings (it is not an FS701
    register); a number is used as given, 0 is the FS701's loop.
    Tests: test_feed_forward.py::test_the_adjust_speed_is_the_one_configured,
    test_auto_without_commissioning_stays_off_until_the_adjust_program_runs,
    test_programs.py::test_serial_adjust_program_tunes_offset_and_gain_at_runtime.
 D5 Process values and status words are refreshed from the cutter when a protocol reads them
    (at a cycle boundary), not every cycle.
 D6 persist() (serve's shutdown) writes the live parameter set, counters and I/O assignment to
    `save_parameters` (atomically); "Store to EEProm" (command bit 29) writes the EEPROM image
    there at once, before the write that set the bit is acknowledged (a kill -9 after the ACK
    keeps it, as the EEPROM keeps it through a power cut). A file that cannot be written is
    refused by the check, and at run time the store is refused (NAK, Modbus exception 4; from a
    hardware input a run fault) with the EEPROM image left as it was. Parameters written over
    the interfaces without a store stay in RAM, as on the unit. Without `save_parameters`
    nothing is written.
 D7 FS701 errors (02 cut not possible, 03 limit, 04 print-mark buffer, 05 encoder ratio) are run
    faults (exit 1), and so is a piece out of its tolerance unless `tolerance_fault = false`.
"""

from __future__ import annotations

import math
from dataclasses import fields
from functools import partial
from operator import attrgetter
from pathlib import Path
from typing import Any, Callable

from mypy_extensions import mypyc_attr

from axisline.configerrors import ConfigError
from axisline.devices.base import Personality
from axisline.kernel.atomic import unwritable_reason

from .cut_states import _WASTE
from .cutter import CutKind, Cutter, CutState, CutterInputs, CutterSettings
from .cutter_state import CutInfo
from .drivecom import DrivecomEndpoint, DrivecomSession
from .io_assign import (
    HW_INPUTS,
    HW_OUTPUTS,
    INPUT_FUNCTIONS,
    OUTPUT_SIGNALS,
    PRINT_MARK_INPUT,
    IOAssignment,
    IOAssignmentError,
    input_function,
    output_signal,
)
from .config import DEFAULT_INPUTS, Fs701Config, ShearConfig
from .line import BatchJob, CommissioningReport, CutMeasurement, CutMeter, Shear, batch_statistics
from .loop import cycle_test, direction_check, tune_gain, tune_lead, tune_offset
from .parameters import ParameterError, ParameterSet, parameter
from .paramfile import ParamFileError, load_parameter_file, save_parameters
from .modbus_map import modbus_read, modbus_write, ModbusError
from .registers import CommandRefusedError, RegisterError, RegisterMap
from .status import COUNTER_MIRRORS, ERRORS, PROCESS_BASE, ClearReason, StatusImage

__all__ = ["Fs701Config", "ShearConfig", "Fs701Personality", "DEFAULT_INPUTS"]

#: parameters that scale the encoders: applied at the next Control Enable OFF (D3)
DEFERRED = ("pulses_line_1000", "pulses_cut_1000", "dir_counter_1", "dir_counter_2", "sampling_time")
SCALE_TOLERANCE = 0.02  # D1
_INT32 = (-(2**31), 2**31 - 1)
_INPUT_FIELD = {"select_virmaster": "select_vir_master"}  # io_assign attr -> CutterInputs field
_CUTTER_INPUTS = {f.name for f in fields(CutterInputs)}
_BIT_CE = 1 << 0  # Control Enable
_BIT_ADJUST = 1 << 30  # Adjust Program (serial / bus only)
_BIT_TEST = 1 << 31  # Test Program (serial / bus only)
TEST_PROGRAM_CYCLES = 2  # up/down cycles the Test program runs per start (#31 Test Counter)


def adjust_steps(config: Fs701Config) -> tuple[tuple[str, Callable[..., Any]], ...]:
    """D4: the Adjust program's steps at the [device.adjust] speed and ramp; with
    acceleration_feed_forward = "auto" also the feed-forward lead (loop.py L10)."""
    a = config.adjust
    steps: list[tuple[str, Callable[..., Any]]] = [
        ("direction", partial(direction_check, speed_lu_min=a.speed, ramp_time=a.ramp_time)),
        ("offset", tune_offset),
        ("gain", partial(tune_gain, speed_lu_min=a.speed, ramp_time=a.ramp_time)),
    ]
    if config.acceleration_feed_forward == "auto":
        steps.append(("lead", partial(tune_lead, speed_lu_min=a.speed)))
    return tuple(steps)


class _DrivecomPort:
    """The Drivecom endpoint, with the status image refreshed before each chunk (D5)."""

    def __init__(self, device: "Fs701Personality") -> None:
        self.device = device
        self.endpoint = DrivecomEndpoint(device.registers, address=None, writes_allowed=partial(getattr, device, "network_writes"))

    def feed(self, data: bytes) -> bytes:
        self.device.refresh_status()
        return self.endpoint.feed(data)

    def session(self) -> "_DrivecomSession":
        """One connection's telegram framing on this unit (serial_tcp: one per client)."""
        return _DrivecomSession(self.device, self.endpoint.session())


class _DrivecomSession:
    """A connection's Drivecom session, with the status image refreshed before each chunk (D5)."""

    def __init__(self, device: "Fs701Personality", framing: DrivecomSession) -> None:
        self.device = device
        self.framing = framing

    def feed(self, data: bytes) -> bytes:
        self.device.refresh_status()
        return self.framing.feed(data)


class _ModbusPort:
    """The register map as Modbus holding (and input) registers; refusals as RegisterRefused."""

    def __init__(self, device: "Fs701Personality") -> None:
        self.device = device

    @property
    def network_writes(self) -> bool:
        return self.device.network_writes

    def read_registers(self, kind: str, address: int, count: int) -> list[int]:
        from axisline.fieldbus.modbus import RegisterRefused

        if kind not in ("holding", "input"):
            raise RegisterRefused(f"register kind {kind!r} is not served")
        self.device.refresh_status()
        try:
            return modbus_read(self.device.registers, address, count)
        except ModbusError as e:  # the register map's own exception code: 2, 3 or 4
            raise RegisterRefused(str(e), e.exception_code) from None

    def write_registers(self, address: int, values: list[int]) -> None:
        from axisline.fieldbus.modbus import RegisterRefused

        if not self.device.network_writes:
            raise RegisterRefused("writes from the network are not enabled (serve --allow-writes)")
        try:
            modbus_write(self.device.registers, address, values)
        except ModbusError as e:  # e.g. 4 when "Store to EEProm" cannot be written
            raise RegisterRefused(str(e), e.exception_code) from None


# a Python class also when compiled: it subclasses Personality, which stays interpreted
@mypyc_attr(native_class=False)
class Fs701Personality(Personality):
    """The FS701 on a simulated cut-to-length line (see the module docstring)."""

    name = "fs701"
    Config = Fs701Config
    endpoints = ("serial-tcp", "modbus")

    def __init__(self, machine: Any, config: Fs701Config) -> None:
        super().__init__(machine, config)
        self.source = getattr(machine, "source", "") or "<machine>"
        self.base_dir = Path(machine.source).parent if getattr(machine, "source", "") else Path.cwd()
        problems: list[str] = []
        mc = machine.config
        self.period = machine.period
        if mc.machine.logic_every != 1:
            problems.append(f"machine.logic_every = {mc.machine.logic_every}: the FS701 closes its loop every cycle (allowed: 1)")

        # ---- parameters: file, then overrides
        params = ParameterSet()
        io = IOAssignment.default()
        n_before = len(problems)
        if config.parameter_file is not None:
            path = self._path(config.parameter_file)
            try:
                loaded = load_parameter_file(path)
            except ParamFileError as e:
                problems += [f"device.parameter_file = {config.parameter_file!r}: {p}" for p in e.problems] or [
                    f"device.parameter_file = {config.parameter_file!r}: {e}"
                ]
            else:
                params = loaded.params
                if loaded.io is not None:
                    io = loaded.io
        for key, value in config.parameters.items():
            try:
                params.set(key, value)
            except ParameterError as e:
                problems.append(f"device.parameters.{key} = {value!r}: {e}")
        self.params = params
        self._check_scales = len(problems) == n_before  # (a set that did not load says nothing)
        if config.save_parameters is not None:
            save_path = self._path(config.save_parameters)
            reason = unwritable_reason(save_path)
            if reason is not None:  # Store to EEProm writes it at run time: refuse it now
                problems.append(f"device.save_parameters = {config.save_parameters!r}: {save_path} {reason}")

        # ---- the carriage (Encoder 2, Ana-Out 2)
        unit = machine.units.get(config.carriage)
        if unit is None:
            problems.append(f"device.carriage = {config.carriage!r}: no such axis (axes: {', '.join(machine.units) or 'none'})")
        else:
            problems += self._check_carriage(unit)
        self.unit = unit

        # ---- the line (Encoder 1)
        self._line_encoder: Any = None
        self._line_entry = None
        if config.line != "virtual":
            entry = next((m for m in mc.master if m.name == config.line), None)
            if entry is None or entry.kind not in ("wheel", "axis_encoder"):
                known = [m.name for m in mc.master if m.kind in ("wheel", "axis_encoder")]
                what = "no such master" if entry is None else f"master of kind {entry.kind!r}"
                problems.append(
                    f"device.line = {config.line!r}: {what}; the line encoder is a [[master]] of kind 'wheel' or 'axis_encoder' "
                    f"(here: {', '.join(known) or 'none'}) or 'virtual'"
                )
            else:
                self._line_entry = entry
                self._line_encoder = machine.masters[entry.name].encoder
                if unit is not None and entry.kind == "axis_encoder" and entry.axis == config.carriage:
                    problems.append(f"device.line = {config.line!r}: the line encoder cannot be the carriage's own encoder")
                problems += self._check_scale("line", self._line_encoder, "pulses_line_1000", "mode_counter_1")

        # ---- print marks (In15)
        self.mark_sensor = None
        if config.printmark_sensor is not None:
            names = [m.name for m in mc.marks]
            if config.printmark_sensor not in names:
                problems.append(
                    f"device.printmark_sensor = {config.printmark_sensor!r}: no such print-mark sensor ([[marks]]: {', '.join(names) or 'none'})"
                )
            else:
                self.mark_sensor = machine.sensors[config.printmark_sensor]
        if params.cutting_mode in (2, 3) and config.printmark_sensor is None:
            problems.append(f"device: cutting_mode = {params.cutting_mode} cuts to print marks: name the sensor in device.printmark_sensor")
        if config.line == "virtual" and config.printmark_sensor is not None:
            problems.append("device.printmark_sensor: print marks need the material's line encoder (device.line), not the virtual master")

        # ---- wiring, job
        self.job: BatchJob | None = None
        uses_job = any(v == "job" for v in config.inputs.values())
        if uses_job:
            self.job = BatchJob(config.batch, self.period, start_delay=config.start_delay)
        self.shear = Shear(self.period, blade_delay=config.shear.blade_delay, cut_time=config.shear.cut_time, pulse=config.shear.pulse)
        self._const_levels = 0
        self._dynamic: list[tuple[int, Callable[[], bool]]] = []
        problems += self._wire_inputs(io, mc)
        self._outputs: list[tuple[int, str]] = []  # (output word mask, io output)
        problems += self._wire_outputs(io, mc)
        if config.batch > 0 and config.inputs.get("start_stop") != "job":
            problems.append("device.batch: a batch needs the job to switch Start/Stop (device.inputs.start_stop = \"job\")")
        for k, step in enumerate(mc.job.steps):
            if step.command is not None and step.axis == config.carriage:
                problems.append(f"job.steps[{k}].axis = {step.axis!r}: the carriage is driven by the FS701 (device.carriage)")
        if problems:
            raise ConfigError(self.source, problems)

        # ---- the unit: registers, cut cycle, loop
        self.registers = RegisterMap(params, StatusImage(), io)
        self.settings = CutterSettings.from_parameters(params)
        self._car_encoder = unit.encoder
        lead = config.acceleration_feed_forward
        self.settings.acc_feed_forward = 0.0 if lead == "auto" else float(lead)
        self._adjust_steps = adjust_steps(config)
        self.commissioning = CommissioningReport()
        if config.commissioning:
            self._commission()
        self.registers.store_to_eeprom()  # the commissioned set is the unit's EEPROM (manual §7: store)
        self.registers.on_store.append(self._stored)
        self._synced = params.copy()
        self._params_obj: Any = None
        self._params_seen = -1
        self._pending_rebuild = False
        self.cutter: Cutter = self._build_cutter(None)
        machine.drive_by(config.carriage, self._control, volts=True)

        # ---- measurement and bookkeeping
        material = machine.material
        entry = self._line_entry
        if entry is not None and entry.kind == "axis_encoder":
            feed = machine.units[entry.axis]  # the roll that pulls the strip: its surface travel
            probe: Callable[[], tuple[float, float, float]] = partial(_feed_probe, feed)
            self.measured_on = f"feed axis {entry.axis!r} (plant)"
        elif material is not None and entry is not None:
            probe = partial(_material_probe, material)
            self.measured_on = "material"
        else:
            probe = self._virtual_probe
            self.measured_on = "virtual master"
        # (no closures in this class: partials and bound methods, see _feed_probe)
        self.meter = CutMeter(
            probe,
            partial(getattr, unit.drive, "position"),
            counts_per_lu=self._cut_counts_per_lu,
            tool_width=self._tool_width,
            tolerance=config.tolerance,
            ramp_tolerance=config.ramp_tolerance,
            mark_tolerance=config.mark_tolerance,
            marks=self._mark_offset if self.mark_sensor is not None else None,
        )
        self._cut_info: CutInfo | None = None  # the cut whose blade is on its way
        self._last_edge: Any = None
        self._errors_seen = 0
        self.errors_raised: list[dict[str, Any]] = []
        self._batch_seen = self.cutter.batch_counter
        self._waste_seen = self.cutter.waste_counter
        self._hw_levels = -1
        self._hw_word = 0
        self._input_masks = tuple(
            (f.mask, _INPUT_FIELD.get(f.attr, f.attr)) for f in INPUT_FUNCTIONS if _INPUT_FIELD.get(f.attr, f.attr) in _CUTTER_INPUTS
        )
        #: All Commands word -> {cutter input field: level} (tick: one dict update per cycle)
        self._input_values: dict[int, dict[str, bool]] = {}
        self._pm_inverted = PRINT_MARK_INPUT in io.inverted_inputs
        self._program_word = 0  # All Commands bits 30/31 seen last cycle (D4)
        #: runtime Adjust / Test programs started by command bits 30/31 (D4)
        self.programs: list[dict[str, Any]] = []

    # ------------------------------------------------------------------ construction helpers

    def _path(self, name: str) -> Path:
        p = Path(name)
        return p if p.is_absolute() else self.base_dir / p

    def _check_carriage(self, unit: Any) -> list[str]:
        name = self.config.carriage
        drive = unit.config.drive
        out = []
        if getattr(drive, "type", None) != "servo":
            out.append(f"device.carriage = {name!r}: axis {name!r} has a {getattr(drive, 'type', '?')} drive; the FS701 drives a servo through Ana-Out 2 (+-10 V)")
        elif drive.command != "analog":
            out.append(f"device.carriage = {name!r}: set [axis.drive] command = \"analog\" (the FS701 commands the carriage with +-10 V on Ana-Out 2)")
        if unit.encoder is None:
            out.append(f"device.carriage = {name!r}: the carriage needs an [axis.encoder] (the FS701 reads it on Encoder 2)")
        else:
            out += self._check_scale("carriage", unit.encoder, "pulses_cut_1000", "mode_counter_2")
        if unit.config.kind != "linear":
            out.append(f"device.carriage = {name!r}: the carriage is a linear axis")
        return out

    def _check_scale(self, what: str, encoder: Any, pulses: str, mode: str) -> list[str]:
        """D1: the parameter set must describe the plant encoder."""
        p = self.params
        out: list[str] = []
        if not self._check_scales:
            return out
        have = encoder.counts_per_unit * 1000.0  # increments per 1000 LU
        want = float(p.get(pulses))
        if abs(want - have) > SCALE_TOLERANCE * have:
            out.append(
                f"device: {pulses} = {want:g}, but the {what} encoder counts {have:g} increments per 1000 LU "
                f"(lines x {encoder.multiplier}); set {pulses} = {round(have)} in the parameter set"
            )
        mult = {0: 1, 1: 2, 2: 4}.get(int(p.get(mode)))
        if mult != encoder.multiplier:
            out.append(
                f"device: {mode} = {p.get(mode)} (x{mult}), but the {what} encoder is evaluated x{encoder.multiplier}; "
                f"set {mode} = {({1: 0, 2: 1, 4: 2})[encoder.multiplier]}"
            )
        return out

    def _signal(self, key: str, value: bool | str, mc: Any) -> tuple[Callable[[], bool] | None, bool, str | None]:
        """(getter or None for a constant, the constant, problem)."""
        if isinstance(value, bool):
            return None, value, None
        if value == "job":
            if key not in ("control_enable", "start_stop"):
                return None, False, f"device.inputs.{key} = 'job': the batch job switches only control_enable and start_stop"
            # (partial of a builtin: a C call, read every cycle)
            return partial(getattr, self.job, key), False, None
        if value == "shear":
            return partial(getattr, self.shear, "level"), False, None
        sensor = self.machine.sensors.get(value)
        if sensor is not None:
            return partial(getattr, sensor, "state"), False, None
        if value in mc.io.inputs:
            return partial(self.machine.io.read, value), False, None
        known = sorted(set(self.machine.sensors) | set(mc.io.inputs))
        return None, False, (
            f"device.inputs.{key} = {value!r}: no such sensor or io input (known: {', '.join(known) or 'none'}; "
            f"or true/false, 'job', 'shear')"
        )

    def _wire_inputs(self, io: IOAssignment, mc: Any) -> list[str]:
        problems: list[str] = []
        owner: dict[int, str] = {}
        for key, value in self.config.inputs.items():
            if key.startswith("In") and key[2:].isdigit():
                t = int(key[2:])
                if not 1 <= t <= HW_INPUTS:
                    problems.append(f"device.inputs.{key}: no such terminal (In1..In{HW_INPUTS})")
                    continue
                terminals = [t]
            else:
                try:
                    f = input_function(key)
                except IOAssignmentError:
                    known = ", ".join(f.attr for f in INPUT_FUNCTIONS if f.in_use and f.assignable and f.attr != "print_mark")
                    problems.append(f"device.inputs.{key}: no such FS701 input function (known: {known}; or In1..In{HW_INPUTS})")
                    continue
                if f.attr == "print_mark":
                    problems.append("device.inputs.print_mark: the Print Mark input (In15) is the sensor named in device.printmark_sensor")
                    continue
                terminals = sorted(io.inputs_of(f.attr))
                if not terminals:
                    problems.append(f"device.inputs.{key}: the I/O assignment puts {f.name!r} on no hardware input (assign it in the parameter file's [io])")
                    continue
            getter, const, problem = self._signal(key, value, mc)
            if problem:
                problems.append(problem)
                continue
            for t in terminals:
                if t == PRINT_MARK_INPUT and self.config.printmark_sensor is not None:
                    problems.append(f"device.inputs.{key}: terminal In{t} carries the print-mark sensor")
                    continue
                if t in owner:
                    problems.append(f"device.inputs.{key}: terminal In{t} is already wired by device.inputs.{owner[t]}")
                    continue
                owner[t] = key
                if getter is None:
                    if const:
                        self._const_levels |= 1 << (t - 1)
                else:
                    self._dynamic.append((1 << (t - 1), getter))
        if self.config.printmark_sensor is not None and self.config.printmark_sensor in self.machine.sensors:
            sensor = self.machine.sensors[self.config.printmark_sensor]
            self._dynamic.append((1 << (PRINT_MARK_INPUT - 1), partial(getattr, sensor, "state")))
        return problems

    def _wire_outputs(self, io: IOAssignment, mc: Any) -> list[str]:
        problems: list[str] = []
        for key, target in self.config.outputs.items():
            if target not in mc.io.outputs:
                problems.append(f"device.outputs.{key} = {target!r}: no such io output (outputs: {', '.join(mc.io.outputs) or 'none'})")
                continue
            if key.startswith("Out") and key[3:].isdigit():
                t = int(key[3:])
                if not 1 <= t <= HW_OUTPUTS:
                    problems.append(f"device.outputs.{key}: no such terminal (Out1..Out{HW_OUTPUTS})")
                    continue
                self._outputs.append((-t, target))  # a terminal: resolved from the hardware levels
                continue
            try:
                s = output_signal(key)
            except IOAssignmentError:
                known = ", ".join(s.attr for s in OUTPUT_SIGNALS if s.in_use)
                problems.append(f"device.outputs.{key}: no such FS701 output signal (known: {known}; or Out1..Out{HW_OUTPUTS})")
                continue
            self._outputs.append((s.mask, target))
        return problems

    def _build_cutter(self, old: Cutter | None) -> Cutter:
        s = self.settings
        if old is not None:
            s.batch_counter, s.waste_counter = old.batch_counter, old.waste_counter
        c = Cutter(self.unit.axis, s, line=self._line_encoder, period=self.period)
        if old is not None:
            c.zero = old.zero
            c.test_counter = old.test_counter
        c.on_cut = self._on_ready
        return c

    def _carriage_counts(self) -> int:
        sign = 1 if self.settings.dir_counter_2 == 1 else -1
        return sign * self._car_encoder.counts_unwrapped

    def _commission(self) -> None:
        """D4: the Adjust program on the disconnected carriage, then the carriage back home."""
        rep = self.commissioning
        rep.ran = True
        steps, ok = self._run_on_carriage(self._adjust_steps)
        rep.steps += steps
        rep.ok = ok
        if not ok:
            self.machine.faults.append(f"fs701 commissioning: {steps[-1]['message']}")

    def _run_on_carriage(self, steps: tuple[tuple[str, Callable[..., Any]], ...]) -> tuple[list[dict[str, Any]], bool]:
        """Run Adjust / Test procedures (loop.py) on the carriage's plant drive, then put the
        carriage back where it stood, unpowered (Control Enable is OFF). Returns the step
        records and whether all passed; Ana-Out Offset 2 / Gain 2 go into the parameter set."""
        s = self.settings
        drive = self.unit.drive
        start = drive.position
        enc = self._car_encoder
        counts = partial(_signed_sample, 1 if s.dir_counter_2 == 1 else -1, enc)
        out: list[dict[str, Any]] = []
        ok = True
        for name, fn in steps:
            r = fn(s, self.period, drive, counts)
            out.append({"step": name, "ok": r.ok, "message": r.message, "iterations": r.iterations})
            if not r.ok or (name == "direction" and r.dir_counter_2 != s.dir_counter_2):
                ok = False
                break
        drive.command_voltage(0.0)
        drive.reset(start)
        drive.enable(False)
        enc.sample()
        self.unit.actual_position = drive.position
        self.params.set("ana_out_offset_2", int(s.ana_out_offset_2))
        self.params.set("ana_out_gain_2", round(float(s.ana_out_gain_2), 2))
        return out, ok

    def _service_programs(self, cycle: int, word: int) -> None:
        """D4: serial / bus command bits 30 "Adjust Program" and 31 "Test Program" (rising edge
        of All Commands, Control Enable OFF) run the Adjust program / the cycle test now."""
        rising = word & ~self._program_word
        self._program_word = word
        if not rising & (_BIT_ADJUST | _BIT_TEST):
            return
        t = round(cycle * self.period, 6)
        if word & _BIT_CE:  # the registers refuse the serial write; a CAN word is not checked there
            self.programs.append({"t": t, "program": "refused", "ok": False,
                                  "steps": [], "message": "Adjust/Test Program needs Control Enable OFF"})
            return
        if rising & _BIT_ADJUST and not word & _BIT_TEST:
            steps, ok = self._run_on_carriage(self._adjust_steps)
            self.programs.append({"t": t, "program": "adjust", "ok": ok, "steps": steps})
        elif rising & _BIT_TEST and not word & _BIT_ADJUST:
            self.cutter.test_counter = 0  # entering the Test program resets #31 (status.py)
            steps, ok = self._run_on_carriage((("cycle", self._cycle_test),))
            self.cutter.test_counter = int(steps[-1]["iterations"]) if ok else 0
            self.programs.append({"t": t, "program": "test", "ok": ok, "steps": steps})

    def _cycle_test(self, s: Any, period: float, drive: Any, counts: Callable[[], int]) -> Any:
        a = self.config.adjust  # the Test program's "Cycle" runs at the Adjust card's speed and ramp
        return cycle_test(s, period, drive, counts, speed_lu_min=a.speed, ramp_time=a.ramp_time, cycles=TEST_PROGRAM_CYCLES)

    # ------------------------------------------------------------------ the loop (POSITION_LOOP)

    def _control(self, actual_position: float, drive_velocity: float) -> float:
        """D2: Ana-Out 2 volts from the FS701's own view of the carriage encoder."""
        return self.cutter.position_loop(self._carriage_counts() / self.settings.cut_counts_per_lu)

    # ------------------------------------------------------------------ per cycle (LOGIC)

    def tick(self, cycle: int) -> None:
        c = self.cutter
        params = self.params
        # parameter writes since the last cycle: the set's write counter first, the (full)
        # comparison only when something was written
        if params.version != self._params_seen or params is not self._params_obj:
            self._params_obj = params
            self._params_seen = params.version
            if params != self._synced:
                self._apply_parameters()
        if self._pending_rebuild and not c.inputs.control_enable:
            self._rebuild()
            c = self.cutter
        # inputs: terminals -> hardware word -> All Commands (OR with serial / CAN)
        levels = self._const_levels
        for mask, get in self._dynamic:
            if get():
                levels |= mask
        if levels != self._hw_levels:
            self._hw_levels = levels
            self._hw_word = self.registers.io.hardware_command_word(levels)
        reg = self.registers
        hw = self._hw_word
        # the register service reacts to edges of All Commands only: skipped when neither the
        # hardware word nor All Commands changed since its last call
        if reg.needs_service(hw):
            try:
                reg.set_hardware_commands(hw)
            except RegisterError as e:  # Store to EEProm from an input failed: no reply carries it
                self.machine.faults.append(f"t={cycle * self.period:.4f} s fs701: {e}")
        word = reg.status.all_commands
        if word & (_BIT_ADJUST | _BIT_TEST) or self._program_word:
            self._service_programs(cycle, word)
        # the cutter's inputs from All Commands: one precomputed field table per word seen
        values = self._input_values.get(word)
        if values is None:
            if len(self._input_values) > 1024:
                self._input_values.clear()
            values = self._input_values[word] = {name: bool(word & mask) for mask, name in self._input_masks}
        c.inputs.__dict__.update(values)
        if self.mark_sensor is not None:
            self._feed_marks(c)
        c.tick(cycle)
        # the tool and the measurement
        if self.shear.step(cycle, c.outputs.ready_to_cut, self.settings.edge_sense):
            self._measure(cycle)
        job = self.job
        if job is not None and not job.done:
            job.step(cycle, self._carriage_parked)
        # the unit's registers follow the cutter
        if c.batch_counter != self._batch_seen or c.waste_counter != self._waste_seen:
            self._store_counters()
        if c.set_length_counter_consumed:
            c.set_length_counter_consumed = False
            for name in ("set_length_cou_ps", "set_length_cou_lu"):
                params.set_raw(name, 0)
                self._synced.set_raw(name, 0)
        if c.errors != self._errors_seen:
            self._new_errors(cycle, c.errors)
        if self._outputs:
            self._write_outputs()

    def _carriage_parked(self) -> bool:
        """The batch job's Stop waits for this: carriage home and settled, no cycle, blade idle."""
        c = self.cutter
        return (
            c.outputs.home
            and abs(self.unit.drive.velocity) <= 1e-3 * self.settings.v_max_line
            and not (c.cut_state not in (CutState.HOME, CutState.IDLE) or self.shear.busy)
        )

    def _virtual_probe(self) -> tuple[float, float, float]:
        m = self.cutter.master
        return m.position, m.velocity, 0.0

    def _cut_counts_per_lu(self) -> float:
        return self.settings.cut_counts_per_lu

    def _tool_width(self) -> float:
        return float(self.settings.tool_width)

    def _feed_marks(self, c: Cutter) -> None:
        """Print-mark edges of the cycle just simulated, in order, to the cutter (In15)."""
        sensor = self.mark_sensor
        assert sensor is not None  # (called only with a print-mark sensor)
        edges = sensor.edges
        if not edges or edges[-1] is self._last_edge:
            return
        new: list[Any] = []
        for e in reversed(edges):
            if e is self._last_edge:
                break
            new.append(e)
        self._last_edge = edges[-1]
        inv = self._pm_inverted
        new.reverse()  # (oldest first; `for e in reversed(new)` trips mypyc)
        for e in new:
            c.print_mark_edge(e._replace(rising=not e.rising) if inv else e)

    def _on_ready(self, info: CutInfo) -> None:
        """The cutter reached Ready to Cut (cutter.on_cut): the blade is on its way."""
        self._cut_info = info
        if self.job is not None:
            self.job.count(info.kind in _WASTE)

    def _measure(self, cycle: int) -> None:
        c = self.cutter
        info = self._cut_info
        kind = info.kind.name if info is not None else "UNKNOWN"
        target = None if info is None or info.kind in _WASTE else float(info.piece_length)
        rec = self.meter.cut(
            cycle * self.period,
            kind=kind,
            target_length=target,
            line_speed_measured=c.line_speed,
            following_error=c.position_error,
            at_mark=info is None or info.kind is not CutKind.ADDITIONAL,  # line.py M5
            # #12/#13, kept by the cutter from Ready to Cut on: the error over the cut window
            max_pos_error=max(abs(c.min_pos_error), abs(c.max_pos_error), abs(c.position_error)),
        )
        if rec.in_tolerance is False and self.config.tolerance_fault:
            what = (
                f"mark offset {rec.mark_offset_counts:+.2f}" if rec.mark_offset_counts is not None else f"length error {rec.error_counts:+.2f}"
            )
            self.machine.faults.append(
                f"t={rec.time:.4f} s fs701: cut {rec.index}: {what} increments beyond the tolerance of +-{rec.tolerance:g}"
            )

    def json_fields(self, device_summary: dict[str, Any]) -> dict[str, Any]:
        """`run --json`: "cuts" and "summary" in the names of the issue (jsonout.py)."""
        from .jsonout import job_json

        return job_json(device_summary)

    def _mark_offset(self, point: float) -> float | None:
        """M4: cut point - the nearest mark's active edge on the material."""
        sensor = self.mark_sensor
        assert sensor is not None  # (print-mark mode only)
        marks = sensor.device.marks
        edge = marks.width if self.settings.printmark_edge == 1 else 0.0
        best = None
        for k in marks.indices_near(point - edge - marks.width - 1.0, point - edge + marks.width + 1.0):
            m = marks.leading_edge(k)
            if m is None:
                continue
            off = point - (m + edge)
            if best is None or abs(off) < abs(best):
                best = off
        if best is None and marks.pitch is not None:  # far from any mark: look a pitch around
            for k in marks.indices_near(point - marks.pitch, point + marks.pitch):
                m = marks.leading_edge(k)
                if m is not None:
                    off = point - (m + edge)
                    if best is None or abs(off) < abs(best):
                        best = off
        return best

    def _new_errors(self, cycle: int, errors: int) -> None:
        new = errors & ~self._errors_seen
        self._errors_seen = errors
        for n in range(6):
            if new >> n & 1:
                text = ERRORS[n].message
                self.errors_raised.append({"t": round(cycle * self.period, 6), "error": n, "text": text})
                self.machine.faults.append(f"t={cycle * self.period:.4f} s fs701: {text}")

    def _write_outputs(self) -> None:
        word = self.cutter.outputs.bits()  # bit 7 "Error" included
        hw = None
        io = self.machine.io
        for mask, target in self._outputs:
            if mask < 0:  # a terminal Out1..Out8: the OR of the signals assigned to it
                if hw is None:
                    hw = self.registers.io.hardware_output_levels(word)
                io.write(target, bool(hw >> (-mask - 1) & 1))
            else:
                io.write(target, bool(word & mask))

    # ------------------------------------------------------------------ parameters <-> cutter

    def _apply_parameters(self) -> None:
        """Parameters written over the network (or by a test) since the last cycle (D3)."""
        s = self.settings
        c = self.cutter
        for d in self._synced.diff(self.params):
            attr = d.parameter.attr
            if attr == "batch_counter":
                c.batch_counter = int(d.theirs)
                self._batch_seen = c.batch_counter
            elif attr == "waste_counter":
                c.waste_counter = int(d.theirs)
                self._waste_seen = c.waste_counter
            elif attr in DEFERRED:
                self._pending_rebuild = True
            elif hasattr(s, attr):
                setattr(s, attr, d.theirs)
        self._synced = self.params.copy()

    def _rebuild(self) -> None:
        s = self.settings
        for attr in DEFERRED:
            setattr(s, attr, self.params.get(attr))
        self.cutter = self._build_cutter(self.cutter)
        self._pending_rebuild = False

    def _store_counters(self) -> None:
        c = self.cutter
        for name, value in (("batch_counter", c.batch_counter), ("waste_counter", c.waste_counter)):
            p = parameter(name)
            raw = min(max(int(value), p.minimum), p.maximum)
            self.params.set_raw(name, raw)
            self._synced.set_raw(name, raw)
        self._batch_seen, self._waste_seen = c.batch_counter, c.waste_counter

    def refresh_status(self) -> None:
        """D5: process values, output word and error word from the cutter (at a cycle boundary)."""
        c = self.cutter
        st = self.registers.status
        values: dict[str | int, int] = {}
        lo, hi = _INT32
        for n, v in c.process_values().items():
            code = PROCESS_BASE + n
            if code in COUNTER_MIRRORS:
                continue
            x = float(v)
            values[code] = 0 if not math.isfinite(x) else min(max(int(round(x)), lo), hi)
        st.update_process_values(values)
        st.set_outputs(c.outputs.bits())
        want = c.errors
        st.set_error_cause(5, self.settings.ratio_error)
        if st.error_status & ~want:
            st.clear_errors(ClearReason.CLEAR_ERROR)
        for n in range(6):
            if want >> n & 1 and not st.error_status >> n & 1:
                st.raise_error(n)
        self._store_counters()

    # ------------------------------------------------------------------ endpoints, persistence

    def byte_endpoint(self) -> _DrivecomPort:
        return _DrivecomPort(self)

    def register_endpoint(self) -> _ModbusPort:
        return _ModbusPort(self)

    def _stored(self, image: Any) -> None:
        """"Store to EEProm" (bit 29): the EEPROM image goes to the parameter file at once (D6)."""
        if self.config.save_parameters is not None:
            path = self._path(self.config.save_parameters)
            try:
                save_parameters(path, image.params, image.io, comment="FS701 EEPROM image (Store to EEProm)")
            except OSError as e:
                # refused like any register write (NAK, Modbus exception 4): the EEPROM keeps the old set
                raise CommandRefusedError(0x091D, f"Store to EEProm: {path} cannot be written: {e.strerror or e}") from None

    def store_paths(self) -> list[Path]:
        return [self._path(self.config.save_parameters)] if self.config.save_parameters is not None else []

    def persist(self) -> list[Path]:
        if self.config.save_parameters is None:
            return []
        self.refresh_status()
        path = self._path(self.config.save_parameters)
        return [save_parameters(path, self.params, self.registers.io, comment="FS701 parameter set (axisline shutdown)")]

    # ------------------------------------------------------------------ the run's end, the report

    @property
    def finished(self) -> bool | None:  # type: ignore[override]  # (Personality: a plain attribute)
        """The batch job: None without one (or with batch = 0), else whether it is done."""
        if self.job is None or self.config.batch == 0:
            return None
        return self.job.done

    def trace_channels(self) -> dict[str, tuple[Callable[[], Any], str, type]]:
        lu = self.unit.config.unit
        return {
            # the cutter of now (a parameter change may rebuild it): dotted paths, read in C
            "fs701.line_speed": (partial(attrgetter("cutter.line_speed"), self), f"{lu}/min", float),
            "fs701.position_error": (partial(attrgetter("cutter.position_error"), self), "incr", float),
            "fs701.ana_out_2": (partial(getattr, self.unit, "command_volts"), "V", float),
            "fs701.cut_state": (partial(attrgetter("cutter.cut_state"), self), "", int),
            "fs701.ready_to_cut": (partial(attrgetter("cutter.outputs.ready_to_cut"), self), "", bool),
            "fs701.cut_completed": (partial(attrgetter("cutter.inputs.cut_completed"), self), "", bool),
        }

    @property
    def cuts(self) -> list[CutMeasurement]:
        return self.meter.records

    def summary(self) -> dict[str, Any]:
        self.refresh_status()
        c = self.cutter
        s = self.settings
        stats = batch_statistics(self.meter.records)
        lu = self.unit.config.unit
        out = {
            "personality": "fs701",
            "length_unit": lu,
            "carriage": self.config.carriage,
            "line": self.config.line,
            "measured_on": self.measured_on,
            "cutting_mode": s.cutting_mode,
            "cutting_length": s.cutting_length,
            "counts_per_lu": {"line": s.line_counts_per_lu, "carriage": s.cut_counts_per_lu},
            "tolerance": {
                "constant_speed_counts": self.config.tolerance,
                "ramp_counts": self.config.ramp_tolerance,
                "mark_counts": self.config.mark_tolerance,
                "constant_speed_lu": self.config.tolerance / s.cut_counts_per_lu,
                "ramp_lu": self.config.ramp_tolerance / s.cut_counts_per_lu,
            },
            "batch": {
                "size": self.config.batch,
                "state": self.job.state if self.job is not None else "no job",
                "counted": self.job.counted if self.job is not None else None,
                **stats,
            },
            "errors_raised": list(self.errors_raised),
            "errors_active": self.registers.errors_text(),
            "counters": {"batch": c.batch_counter, "waste": c.waste_counter},
            "commissioning": {"ran": self.commissioning.ran, "ok": self.commissioning.ok, "steps": self.commissioning.steps,
                              "ana_out_offset_2": s.ana_out_offset_2, "ana_out_gain_2": s.ana_out_gain_2,
                              "acc_feed_forward_ms": s.acc_feed_forward},
            "job_events": list(self.job.events) if self.job is not None else [],
            "parameters_changed": {d.parameter.attr: d.theirs for d in self.params.changed_from_defaults()},
            "state": {"control": c.control_state.name, "cut": c.cut_state.name, "outputs_on": self.registers.status.snapshot()["outputs_on"]},
            "cuts": [r.as_dict() for r in self.meter.records],
        }
        out["headline"] = _headline(out)
        return out

    def plots(self, out_dir: str | Path, data: dict | None, units: dict | None = None) -> list[Path]:
        from .report import write_plots

        return write_plots(self.summary(), data, out_dir)

    def report_markdown(self, device_summary: dict[str, Any], plots: list[Path]) -> str:
        from .report import report_section

        return report_section(device_summary, plots)


# Readings for the meter, the Adjust routines and the scope: module functions behind partials,
# not closures (mypyc cannot compile closures in methods of a class that stays a Python class).


def _feed_probe(feed: Any) -> tuple[float, float, float]:
    return feed.drive.position, feed.drive.velocity, feed.axis.command_acceleration


def _material_probe(material: Any) -> tuple[float, float, float]:
    return material.position, material.velocity, material.acceleration


def _signed_sample(sign: int, encoder: Any) -> int:
    return sign * encoder.sample()


def _headline(d: dict[str, Any]) -> str:
    b = d["batch"]
    lu = d["length_unit"]
    parts = [f"fs701: {b['cuts']} cuts, {b['pieces']} pieces measured on the {d['measured_on']}"]
    if b["max_abs_error_counts"] is not None:
        parts.append(f"max length error {b['max_abs_error_counts']:.2f} increments ({b['max_abs_error_lu']:.4f} {lu})")
    if b["max_abs_mark_offset_counts"] is not None:
        parts.append(f"max mark offset {b['max_abs_mark_offset_counts']:.2f} increments")
    parts.append(f"{b['in_tolerance']}/{b['checked']} in tolerance")
    parts.append(f"FS701 errors: {', '.join(e['text'] for e in d['errors_raised']) or 'none'}")
    return "; ".join(parts)
