"""The Parker COMPAX XX70 cam controller as a machine personality (docs/compax.md).

    [machine]
    cycle_us = 1000                    # COMPAX works in 1 ms cycles (I14 polled every 100 µs)
    personality = "compax"

    [device]
    slave = "knife"                    # the machine axis COMPAX drives (its power stage: I12)
    master = "wheel"                   # a [[master]] (wheel, axis_encoder, ...), an axis with an
                                       # encoder, or "internal" (the internal time base, P30 = 1)
    memory_file = "knife.cam.json"     # the cam memory (and program sets): loaded at start if present
    program_file = "knife.prg"         # program sets "N001: SETC 1" for a new program memory
    parameters = { P33 = 1, P32 = 450.0, P180 = 10 }          # written, then VC and VP
    inputs = { I13 = true, I14 = "labels", I16 = true }       # I1 ... I16 wiring
    outputs = { O16 = "knife_sync" }                          # O1 ... O16 to [io] outputs
    startup = ["SETC 1", "SETM 0", "LOOP 0"]                  # sent at start, as a host would ("START")

    [[device.curves]]                  # written into a new cam memory (not when the file exists)
    number = 1
    master_period = 300.0              # from motion laws (SegmentCam), a [[cam]] or a CSV file
    segments = [ { master_end = 30.0, slave_end = 43.2, law = "constant_velocity" }, ... ]
    points = 301
    label_set_point = 0.25             # curve parameters: fractions of M_T (S_T)
    label_window = 0.1

What happens each 1 ms cycle (`tick`, LOGIC stage, before the slave samples its set point;
after the start-up list, `devicecycle.DeviceCycle`): the start-up list advances (a line waits
while the slave is positioning, while a LOOP is active unless P210 = 1, and a LOOP / POSR CAM /
POSA / POSR waits for the power stage), the program memory's interpreter runs one set
(`programrun.ProgramRun`: started by START, over the interface or in the start-up list; its
errors are faults of the run), the label sensor's sub-cycle edges of the last plant step go to
the label synchronisation (I14 wired to a print-mark sensor or switch; an io input or a
constant is read as a level), I16 wired to a sensor latches the master encoder at its rising
edge (interpolated in the cycle), the cam operation runs (`camop.CamOperation.tick`), and O1
... O16 are written to the io outputs wired to them (in the cycle one of them changes: nothing
else writes those outputs). A `report.CycleLog` keeps one record per master cycle (label error
before / after correction, correction, tracking error, O15 / O16 changes):
`summary()["cycles"]`, and `write_report(dir)` writes them as JSON with a plot.

The slave belongs to COMPAX: job steps must not command it; its power follows I12 (wired
to true unless given). The master encoder's scaling P98 / P143 is derived from the master
(`derive_master_scaling`) unless device.parameters sets them.

The ASCII interface (`byte_endpoint`, `axisline serve --serial-tcp / --serial-pty`) is
`endpoint.CompaxEndpoint` on this device's cam memory, program memory, parameters, cam
operation and live status values. Reads (F/I/B<address>, P<n>, S<n>) are always answered; every write (memory,
parameters, VF, VP, RESETF, SETC, LOOP, ...) is refused with the device's error reply
(``!E104`` for memory and parameters, ``!E107`` for commands) unless the operator enabled
network writes (``serve --allow-writes``); a refused or wrong line changes nothing.

What the interface acknowledges is stored, as the device keeps its Zero-Power-RAM and
parameters through a power cut: a line that changes the cam memory (F/I/B<address>=...,
RESETF), a program set (N<n>: ..., kept in the memory file) or the written parameters (P<n>=..., RESETP) is saved to memory_file /
parameter_file (atomic write, fsync, rename) before its reply goes out, so a kill -9 right
after the reply keeps it. A save that fails is undone and answered ``!E108`` (S30 = 108).
Both files must be writable when the machine file is checked, and a save's temporary file
left by a kill is removed at the next `serve` (`store_paths`).

Scope channels come from `trace_channels()` (the machine adds them with its own: all of them
with trace.channels = "all", or those named): compax.S44, S45, S52 (per mille), O14 ... O16,
state, A0 / A1 (V). The label records come from the public `LabelSync.on_label` hook and
`LabelSync.corrected` (label.py).

Decisions (each has a test in tests/devices/compax/test_personality.py):

* P1 The two analogue aux channels (compax.md §2.1 "Additionally there can be put out 2 analogue
  signals within +/- 10V", §2.12 "The analogue auxiliary functions are always prepared
  independently from I15", §7 X22 "volt = signed_byte·10/128"): the machine has no analogue
  I/O image ([io] is digital), so they are not wired to machine outputs; they are exposed as
  the scope channels compax.A0 / compax.A1 and in `summary()["analog"]`, in volts at the X22
  scaling (gain 100: 127 ≙ 9.92 V, -128 ≙ -10 V), 0 V without a selected curve or without
  analogue aux values. Test: test_analog_aux_channels_in_the_scope_and_the_summary.
* P2 The io outputs wired to O1 ... O16 (issue 18: "skip work nothing reads") are written in the
  cycle the device's output image changes, not every cycle: device.outputs makes them the
  device's (no job step or other device writes them; the HMI forces, which is a layer above the
  written value), so the io image is the same. Test:
  test_startup_program_waits_for_the_power_stage_then_couples_and_sets_the_outputs.
"""

from __future__ import annotations

import math
import re
from pathlib import Path
from typing import Any, Callable

from axisline.configerrors import ConfigError
from axisline.devices.base import Personality
from axisline.devices.compax import CompaxError
from axisline.devices.compax.cammemory import CamMemory
from axisline.devices.compax.camop import CamOperation, CamState, analog_volts
from axisline.devices.compax.curves import (
    CurveRecord,
    curve_from_cam,
    curve_from_table,
    curve_to_csv,
    read_curve,
    write_curve,
)
from axisline.devices.compax.config import CompaxConfig, CurveEntry, derive_master_scaling
from axisline.devices.compax.devicecycle import DeviceCycle
from axisline.devices.compax.endpoint import (
    CompaxEndpoint,
    LiveStatus,
    ProgramInterface,
    load_parameters,
    save_parameters,
    save_store,
    stored_program,
)
from axisline.devices.compax.label import LabelSync
from axisline.devices.compax.masterchain import param
from axisline.devices.compax.parameters import Parameters
from axisline.devices.compax.program import ProgramMemory, read_program_file
from axisline.devices.compax.programrun import ProgramRun
from axisline.devices.compax.report import CycleLog, converged_after, write_report
from axisline.kernel.atomic import unwritable_reason
from axisline.motion.axis import AxisState

__all__ = [
    "CompaxConfig",
    "CompaxEndpoint",
    "CompaxPersonality",
    "CurveEntry",
    "derive_master_scaling",
    "load_parameters",
    "save_parameters",
]


_STATUS_NUMBERS = (1, 2, 13, 14, 30, 41, 42, 43, 44, 45, 46, 47, 48, 49, 50, 51, 52)
_STATE_CODE = {s: i for i, s in enumerate(CamState)}
_MOVING = (AxisState.DISCRETE_MOTION, AxisState.CONTINUOUS_MOTION, AxisState.HOMING, AxisState.STOPPING)
_MOTION = re.compile(r"LOOP|LP|POSRCAM|PR|POSA|POSR")


# ---------------------------------------------------------------------------------------
# the personality


class CompaxPersonality(Personality):
    """COMPAX XX70 cam controller on a machine axis (see the module docstring)."""

    name = "compax"
    Config = CompaxConfig
    endpoints = ("serial-tcp",)

    def __init__(self, machine: Any, config: CompaxConfig) -> None:
        super().__init__(machine, config)
        self.source = getattr(machine, "source", "") or "<machine>"
        self.base_dir = Path(machine.source).parent if getattr(machine, "source", "") else Path.cwd()
        self.period = float(machine.period)
        problems: list[str] = []
        mc = machine.config
        if mc.machine.cycle_us != 1000:
            problems.append(f"machine.cycle_us = {mc.machine.cycle_us}: COMPAX works in 1 ms cycles (allowed: 1000)")
        if mc.machine.logic_every != 1:
            problems.append(f"machine.logic_every = {mc.machine.logic_every}: COMPAX runs its cam operation every cycle (allowed: 1)")
        unit = machine.units.get(config.slave)
        if unit is None:
            problems.append(f"device.slave = {config.slave!r}: no such axis (axes: {', '.join(machine.units) or 'none'})")
        for k, step in enumerate(mc.job.steps):
            if step.command is not None and step.axis == config.slave:
                problems.append(f"job.steps[{k}].axis = {step.axis!r}: the axis is the COMPAX slave (device.slave); "
                                "command it through the device (startup, ASCII interface)")
        self.encoder, counts_per_unit, preferred_p98 = self._master(config, unit, problems)
        signals = sorted(set(machine.sensors) | set(mc.io.inputs))
        for name, value in config.inputs.items():
            if isinstance(value, str) and value not in signals:
                problems.append(f"device.inputs.{name} = {value!r}: no such switch, sensor or io input "
                                f"(known: {', '.join(signals) or 'none'}; or true/false)")
        for name, value in config.outputs.items():
            if value not in mc.io.outputs:
                problems.append(f"device.outputs.{name} = {value!r}: no such io output (outputs: {', '.join(mc.io.outputs) or 'none'})")
        self.memory_path = self._path(config.memory_file)
        self.parameter_path = self._path(config.parameter_file)
        for key, name, path in (("memory_file", config.memory_file, self.memory_path),
                                ("parameter_file", config.parameter_file, self.parameter_path)):
            reason = unwritable_reason(path) if path is not None else None
            if reason is not None:  # persist() and every stored line write it: refuse it now, not at run time
                problems.append(f"device.{key} = {name!r}: {path} {reason}")
        if self.memory_path is not None and self.memory_path == self.parameter_path:
            problems.append(f"device.parameter_file = {config.parameter_file!r}: the same file as device.memory_file "
                            "(each save would overwrite the other)")
        self.memory = self._memory(config, problems)
        self.program_memory = self._program(config, problems)
        self.params = self._parameters(config, counts_per_unit, preferred_p98, problems)
        if problems:
            raise ConfigError(self.source, problems)
        assert unit is not None and self.params is not None and self.memory is not None
        self.unit = unit
        self.axis = unit.axis
        self.label = LabelSync()
        wiring: dict[str, Any] = {"I12": True}
        wiring.update({name: self._signal(value) for name, value in config.inputs.items()})
        self.wiring = wiring
        self.op = CamOperation(self.axis, self.params, self.memory, encoder=self.encoder, inputs=wiring, label=self.label)
        self.status = LiveStatus(self.op)
        self.run = ProgramRun(self.program_memory, self.op, self.params, on_error=self._program_error)
        self._programs = ProgramInterface(self.program_memory, self.run)
        self._local = CompaxEndpoint(self.memory, self.params, self.op, self.status, lambda: True,
                                     program=self._programs)
        self._i14 = self._sensor(config.inputs.get("I14"))
        self._i16 = self._sensor(config.inputs.get("I16"))
        self.program = list(config.startup)
        self.pc = 0  # next line of the start-up program
        self._wait_until: int | None = None
        self.program_errors: list[dict[str, Any]] = []
        self.log = CycleLog()
        self._first = True
        outputs = tuple((int(name[1:]), io_name) for name, io_name in config.outputs.items())
        self.device_cycle = DeviceCycle(self.op, self.run, self.log, self.label, self.period,
                                        i14=self._i14, i16=self._i16, encoder=self.encoder, io=machine.io,
                                        outputs=outputs, status=self.status)
        self.label.on_label = lambda s51, s52: self.device_cycle.accepted.append((s51, s52))

    # ------------------------------------------------------------------ construction

    def _path(self, name: str | None) -> Path | None:
        if name is None:
            return None
        p = Path(name)
        return p if p.is_absolute() else self.base_dir / p

    def _master(self, config: CompaxConfig, slave_unit: Any, problems: list[str]) -> tuple[Any, float | None, float | None]:
        """The master encoder (an object with integer counts), its counts per master unit and a
        preferred P98 (a wheel's circumference)."""
        machine = self.machine
        name = config.master
        if name == "internal":
            return None, None, None
        entries = {m.name: m for m in machine.config.master}
        if name in machine.masters:
            entry, master = entries[name], machine.masters[name]
            if entry.kind == "wheel":
                w = entry.wheel
                return master.encoder, w.lines_per_revolution * w.multiplier / w.circumference, w.circumference
            if entry.kind == "axis_encoder":
                if entry.axis == config.slave:
                    problems.append(f"device.master = {name!r}: the master cannot be the slave's own encoder")
                return master.encoder, master.encoder.counts_per_unit, None
            # virtual, time_base, axis: their integer position (read once per cycle, one cycle behind)
            return master, master.counts_per_unit, None
        unit = machine.units.get(name)
        if unit is not None:
            if unit.encoder is None:
                problems.append(f"device.master = {name!r}: axis {name!r} has no [axis.encoder] to count the master")
                return None, None, None
            if name == config.slave:
                problems.append(f"device.master = {name!r}: the master cannot be the slave's own encoder")
            return unit.encoder, unit.encoder.counts_per_unit, None
        problems.append(f"device.master = {name!r}: no such master or axis with an encoder "
                        f"(masters: {', '.join(machine.masters) or 'none'}; axes: {', '.join(machine.units) or 'none'}; or internal)")
        return None, None, None

    def _memory(self, config: CompaxConfig, problems: list[str]) -> CamMemory | None:
        """The cam memory: the saved file (power on), else the delivery state plus the configured curves."""
        path = self.memory_path
        if path is not None and path.exists() and not path.is_dir():  # a directory: named by the path check
            try:
                return CamMemory.load(path)
            except (CompaxError, OSError) as e:
                problems.append(f"device.memory_file = {config.memory_file!r}: {e}")
                return None
        memory = CamMemory()
        for i, entry in sorted(enumerate(config.curves), key=lambda x: x[1].number):
            try:
                write_curve(memory, self._curve(entry))
            except (CompaxError, ValueError, OSError) as e:
                problems.append(f"device.curves[{i}] (curve {entry.number}): {e}")
        memory.vf()
        return memory

    def _program(self, config: CompaxConfig, problems: list[str]) -> ProgramMemory:
        """The program memory: the sets kept in the memory file (power on), else program_file
        (endpoint.py decision 3)."""
        program = ProgramMemory()
        lines, source = None, ""
        path = self.memory_path
        try:
            if path is not None and path.exists() and not path.is_dir():
                source = f"device.memory_file = {config.memory_file!r}"
                lines = stored_program(path)
            if lines is None and config.program_file is not None:
                source = f"device.program_file = {config.program_file!r}"
                lines = read_program_file(self._path(config.program_file))
            if lines is not None:
                program.replace(lines, source=source)
        except CompaxError as e:
            problems.append(str(e) if str(e).startswith(source) else f"{source}: {e}")
        except (OSError, ValueError) as e:
            problems.append(f"{source}: {e}")
        return program

    def _curve(self, entry: CurveEntry) -> CurveRecord:
        from axisline.motion.cam import PointTable
        from axisline.motion.segments import SegmentCam

        block = entry.block()
        if entry.csv is not None:
            path = self._path(entry.csv)
            assert path is not None
            table = PointTable.from_csv(path)
            return curve_from_table(table, entry.number, slave_cycle=entry.slave_cycle, points=entry.points, **block)
        if entry.segments is not None:
            cam = SegmentCam(entry.segments, start=entry.start, master_period=entry.master_period, periodic=True)
        else:
            cams = getattr(self.machine, "cams", {})
            if entry.cam not in cams:
                raise ValueError(f"cam = {entry.cam!r}: no such [[cam]] (cams: {', '.join(cams) or 'none'})")
            cam = cams[entry.cam]
        assert entry.points is not None
        return curve_from_cam(cam, entry.number, entry.points, slave_cycle=entry.slave_cycle, **block)

    def _parameters(self, config: CompaxConfig, counts_per_unit: float | None, preferred_p98: float | None,
                    problems: list[str]) -> Parameters | None:
        path = self.parameter_path
        if path is not None and path.exists() and not path.is_dir():  # a directory: named by the path check
            try:
                return load_parameters(path)
            except (CompaxError, OSError) as e:
                problems.append(f"device.parameter_file = {config.parameter_file!r}: {e}")
                return None
        params = Parameters()
        values = config.parameter_values()
        for n, v in values.items():
            params[n] = v  # checked by the config model already
        if config.master == "internal":
            if 30 not in values:
                params[30] = 1
            elif int(values[30]) % 10 != 1:
                problems.append(f"device.parameters: P30 = {values[30]} selects the encoder, but device.master = 'internal' "
                                "(the internal time base is P30 = 1 or 11)")
        elif counts_per_unit is not None and 98 not in values and 143 not in values:
            scaling = derive_master_scaling(counts_per_unit, preferred_p98=preferred_p98)
            if scaling is None:
                problems.append(f"device.master = {config.master!r}: its encoder counts {counts_per_unit:g} increments per "
                                "master unit; set P98 and P143 in device.parameters so that 4*P143/P98 equals it")
            else:
                params[98], params[143] = scaling
        try:
            params.make_valid("VC")
            params.make_valid("VP")
        except CompaxError as e:
            problems.append(f"device.parameters: {e}")
        return params

    def _signal(self, value: bool | str) -> Any:
        """A wired input: a constant, or a function reading a sensor or an io input."""
        return self.machine.signal(value)

    def _sensor(self, value: bool | str | None) -> Any:
        if isinstance(value, str):
            return self.machine.sensors.get(value)
        return None

    # ------------------------------------------------------------------ per cycle

    def trace_channels(self) -> dict[str, tuple[Callable[[], Any], str, type]]:
        """compax.* scope channels (device.trace = false: none); the machine adds them when the
        scope records all channels, or those named in trace.channels."""
        if not self.config.trace:
            return {}
        op, label = self.op, self.label
        return {
            "compax.S44": (lambda: op.chain.s44, "per mille", float),
            "compax.S45": (lambda: op._s45, "per mille", float),
            "compax.S52": (lambda: label.s52, "per mille", float),
            "compax.O14": (lambda: op.output(14), "", bool),
            "compax.O15": (lambda: op.output(15), "", bool),
            "compax.O16": (lambda: op.output(16), "", bool),
            "compax.state": (lambda: _STATE_CODE[op.state], "", int),
            "compax.A0": (lambda: self.analog_volts(0), "V", float),
            "compax.A1": (lambda: self.analog_volts(1), "V", float),
        }

    def analog_volts(self, channel: int) -> float:
        """Analogue aux channel 0 / 1 (the curve's analogue aux function at the master position,
        interpolated, independent of I15) in volts: signed byte · 10 V / 128 (P1 in docs/compax.md)."""
        return analog_volts(self.op.analog(channel))

    def tick(self, cycle: int) -> None:
        if self._first:
            self._first = False
            self.log.start(cycle * self.period)
        if self.pc < len(self.program):
            self._run_program(cycle)
        self.device_cycle.tick(cycle)  # the program memory, the cam operation, the log, the outputs

    # ------------------------------------------------------------------ start-up program

    def _busy(self, key: str) -> bool:
        """The program waits: a LOOP is active (P210 = 0), the slave is positioning, or a
        LOOP / POSR CAM needs the power stage (I12) that is still off."""
        op, ax = self.op, self.axis
        parallel = int(param(self.params, 210)) == 1
        if not parallel and (op.loop_active or ax.state in _MOVING):
            return True
        if _MOTION.match(key) and not op.loop_active and ax.state in (AxisState.DISABLED, AxisState.ERROR_STOP, *_MOVING):
            return True
        return False

    def _run_program(self, cycle: int) -> None:
        program = self.program
        while self.pc < len(program):
            line = program[self.pc]
            key = "".join(line.split()).upper()
            if key.startswith("WAIT"):
                if self._wait_until is None:
                    ms = float(key[4:])
                    self._wait_until = cycle + max(0, math.ceil(ms / 1000.0 / self.period - 1e-9))
                if cycle < self._wait_until:
                    return
                self._wait_until = None
                self.pc += 1
                continue
            if self._busy(key):
                return
            reply = self._local.execute(line)
            if reply.startswith(b"!E"):
                text = reply.decode("ascii", "replace").removesuffix("\r\n>")
                self.program_errors.append({"line": self.pc + 1, "text": line, "reply": text, "t": cycle * self.period})
                self.machine.faults.append(f"t={cycle * self.period:.4f} s device: start-up line {self.pc + 1} {line!r}: {text}")
                self.pc = len(program)  # a program stops at an error
                return
            self.pc += 1

    # ------------------------------------------------------------------ Personality API

    def byte_endpoint(self) -> CompaxEndpoint:
        """The ASCII interface (memory, parameters and status are this device's; each
        connection takes its own line buffer with `.session()`). Writes need `network_writes`."""
        return CompaxEndpoint(self.memory, self.params, self.op, self.status, lambda: self.network_writes,
                              store=self._store_line, program=self._programs)

    def _program_error(self, record: dict[str, Any]) -> None:
        """A program set answered with an error: S30, and a fault of the run (programrun decision 5)."""
        self.status[30] = record["code"]
        where = f"program set {record['text']!r}" if record["text"] else "program"
        self.machine.faults.append(f"t={record['t']:.4f} s device: {where}: !E{record['code']} {record['message']}")

    def _store_line(self, memory_before: CamMemory, params_before: Parameters,
                    program_before: ProgramMemory | None = None) -> None:
        """Save what one interface line changed, before its reply (see the module docstring)."""
        program_changed = program_before is not None and program_before != self.program_memory
        if self.memory_path is not None and (self.memory.words() != memory_before.words() or program_changed):
            self.memory_path.parent.mkdir(parents=True, exist_ok=True)
            save_store(self.memory_path, self.memory, self.program_memory)
        if self.parameter_path is not None and dict(self.params.written) != dict(params_before.written):
            self.parameter_path.parent.mkdir(parents=True, exist_ok=True)
            save_parameters(self.params, self.parameter_path)

    def stop(self) -> bool:
        """Shutdown: the start-up list and the program stop, the slave brakes on its ramp (STOP)."""
        self.pc = len(self.program)
        self.run.stop()
        return True

    def store_paths(self) -> list[Path]:
        return [p for p in (self.memory_path, self.parameter_path) if p is not None]

    def persist(self) -> list[Path]:
        """Save the cam memory (and the parameters, with parameter_file) atomically."""
        files = []
        if self.memory_path is not None:
            self.memory_path.parent.mkdir(parents=True, exist_ok=True)
            save_store(self.memory_path, self.memory, self.program_memory)
            files.append(self.memory_path)
        if self.parameter_path is not None:
            self.parameter_path.parent.mkdir(parents=True, exist_ok=True)
            save_parameters(self.params, self.parameter_path)
            files.append(self.parameter_path)
        return files

    def curve(self, number: int, *, valid: bool = True) -> CurveRecord:
        """Curve `number` of the cam memory (the valid copy, what SETC selects)."""
        return read_curve(self.memory, number, valid=valid)

    def export_curve(self, number: int, path: str | Path) -> Path:
        """Write curve `number` (the memory as written) as a master,slave CSV."""
        curve_to_csv(read_curve(self.memory, number, valid=False), path)
        return Path(path)

    def status_values(self) -> dict[str, float]:
        return {f"S{n}": float(self.status.read(n)) for n in _STATUS_NUMBERS}

    def summary(self) -> dict[str, Any]:
        op = self.op
        records = self.log.as_list()
        labelled = [r for r in records if r["error_before"] is not None]
        tol = self.config.label_tolerance
        return {
            "slave": self.config.slave,
            "master": self.config.master,
            "state": op.state.value,
            "curve": int(op.status(43)) if op.curve is not None else None,
            "loop_active": op.loop_active,
            "outputs": {f"O{n}": op.output(n) for n in range(7, 17)},
            "analog": {"A0": self.analog_volts(0), "A1": self.analog_volts(1)},  # volts (P1)
            "status": self.status_values(),
            "program": {
                "lines": len(self.program),
                "next_line": self.pc + 1 if self.pc < len(self.program) else None,
                "done": self.pc >= len(self.program) and not self.program_errors,
                "errors": list(self.program_errors),
            },
            "program_memory": self.run.summary(),  # the sets N001 ... and their interpreter
            "label": {
                "mode": {0: "off", 1: "master related", 2: "slave related"}.get(self.label.mode, str(self.label.mode)),
                "cycles_with_label": len(labelled),
                "tolerance_per_mille": tol,
                "converged_from_cycle": converged_after(records, tol) if labelled else None,
                "last_error_per_mille": labelled[-1]["error_before"] if labelled else None,
            },
            "cycles": records,
        }

    def plots(self, out_dir: str | Path, data: dict | None, units: dict | None = None) -> list[Path]:
        """`run --plot/--report`: the label plot (and compax_cycles.json beside it)."""
        return [f for f in self.write_report(out_dir) if f.suffix == ".png"]

    def report_markdown(self, device_summary: dict[str, Any], plots: list[Path]) -> str:
        label = device_summary.get("label", {})
        program = self.run.report_lines()
        if program and label.get("mode") == "off" and not label.get("cycles_with_label"):
            return "\n".join(program) + "\n"  # a program without labels: no label section
        lines = program + ["## COMPAX label synchronisation", "",
                 f"- label synchronisation: {label.get('mode')}, {label.get('cycles_with_label')} master cycles with a label",
                 f"- converged (|error| <= {label.get('tolerance_per_mille')} ‰) from master cycle {label.get('converged_from_cycle')}",
                 f"- last label error: {_per_mille(label.get('last_error_per_mille'))} ‰", "",
                 "Per master cycle (label value, error before and after correction, tracking error, O15/O16): `compax_cycles.json`.", ""]
        lines += [f"![{p.stem}]({p.name})" for p in plots]
        return "\n".join(lines) + "\n"

    def write_report(self, out_dir: str | Path) -> list[Path]:
        """compax_cycles.json and compax_label.png into out_dir (for `axisline run --report`)."""
        curve = self.op.curve
        window = 1000.0 * min(curve.label_window, 0.3) if curve is not None and curve.label_window else None
        title = f"{self.machine.config.machine.name} (COMPAX, slave {self.config.slave})"
        return write_report(self.log.records, out_dir, status=self.status_values(), title=title, window=window,
                            tracking_limit=float(param(self.params, 79)))


def _per_mille(x: Any) -> str:
    """A label error in ‰ to a tenth, like the tolerance beside it (not 16 digits of noise)."""
    return "-" if x is None else f"{x:.1f}"
