"""The Rexroth CLM1.4 as a machine personality (docs/clm.md).

    [machine]
    cycle_us = 2000                    # the CLM's NC cycle: B010 (0.0 = 2 ms for 1-2 axes, 3 / 4 ms for 3 / 4)
    personality = "clm"

    [device]
    axes = ["feed"]                    # CLM axes 1, 2, ... = these machine axes (servos, +-10 V)
    program = "clm/roll_feed.prg"      # the CLM's files (either form, see docs/clm.md)
    parameters = "clm/roll_feed.par"
    logic = "clm/roll_feed.lt"
    variables = "clm/roll_feed.var"
    memory_file = "roll_feed.clm.json" # the battery-buffered memory: loaded at start when present
    start_at = 0.05                    # press Start this long after power-on (simulation)
    report_output = "Q1.00.0"          # the report records the feed error at each rising edge
    [device.inputs]                    # CLM inputs: true/false, an [io] input, a switch or sensor
    "I1.00.0" = "press_top"
    [device.outputs]                   # CLM outputs to [io] outputs
    "Q1.00.0" = "press_valve"
    [device.analog_inputs]             # AE1..AE4 in volts (the override potentiometer, §7.3)
    AE1 = 5.0
    [device.decade_switch]             # an IDS01 on X6 (B002 function 1): V015-V018 (decade_switch.py)
    model = "IDS01.1-2"
    length = 123.45
    velocity = 50

Each NC cycle (`tick`, every machine cycle): the outputs the CLM set in the previous cycle go to
the [io] outputs ("Hardware outputs are set at the beginning of the following cycle", L1437),
the wired inputs are read into the CLM's image, and the runtime runs one cycle (`runtime`).
Without wiring, the system inputs are those of a machine ready to run: Automatic selected,
E-Stop and Immediate Stop closed, the configured axes enabled. Before the runtime's step the
devices on the CLM's own connectors are read: master encoder 1 (`master_encoder`), the IDS01
decade switch (`decade_switch`, which reports its faults 12-15 through the mode machine's fault
path) and the analog inputs through B017's averaging (`analog`: the override, V007-V010 and
Status 45/49 read the same value).

The retained memory (program, parameters, Logic Task, V600-V999, counters, M3, M6.00-19) is
written to `memory_file` whenever it changes, at the end of the NC cycle that changed it, so a
kill -9 loses nothing the CLM had executed or acknowledged; at the next start it is loaded in
place of the files.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Annotated, Any, Callable

from pydantic import BaseModel, ConfigDict, Field, StringConstraints

from axisline.configerrors import ConfigError, FilePath
from axisline.devices.base import Personality
from axisline.kernel.atomic import unwritable_reason
from axisline.plant.io import AnalogIO

from .analog import ClmAnalogInputs
from .decade_switch import DecadeSwitch, DecadeSwitchConfig, IdsReceiver, config_problems
from .errors import Finding
from .files import read_file
from .image import ProcessImage
from .memory import ClmMemory, RetainedStore
from .operands import Operand, parse_operand
from .runtime import ClmRuntime

__all__ = ["ClmConfig", "ClmPersonality"]

Name = Annotated[str, StringConstraints(min_length=1, max_length=64, pattern=r"^[A-Za-z0-9_\-]+$")]
Signal = Annotated[str, StringConstraints(min_length=1, max_length=130, pattern=r"^[A-Za-z0-9_.\-]+$")]
InputName = Annotated[str, StringConstraints(pattern=r"^I[0-2]\.\d\d\.\d$")]
AnalogName = Annotated[str, StringConstraints(pattern=r"^AE[1-4]$")]
ANALOG_INPUTS = ("AE1", "AE2", "AE3", "AE4")
OutputName = Annotated[str, StringConstraints(pattern=r"^Q[0-2]\.\d\d\.\d$")]

_AUTO_CYCLE_MS = {1: 2.0, 2: 2.0, 3: 3.0, 4: 4.0}  # B010 = 0.0 (spec §1.4)
_READY = {"I0.00.1": True, "I0.00.2": True, "I0.00.4": True}  # Automatic, E-Stop and Immediate Stop closed
_ENABLE = {1: "I0.00.5", 2: "I0.00.6", 3: "I0.02.0", 4: "I0.02.3"}
START = "I0.00.3"


class ClmConfig(BaseModel):
    """The [device] table of personality "clm"."""

    model_config = ConfigDict(extra="forbid")

    axes: list[Name] = Field(min_length=1, max_length=4, description="machine axes that are CLM axes 1, 2, 3, 4 (servos with an encoder)")
    program: FilePath = Field(None, min_length=1, max_length=4096, description="program file (telegrams or listing), relative to the machine file")
    parameters: FilePath = Field(None, min_length=1, max_length=4096, description="parameter file (none: the defaults)")
    logic: FilePath = Field(None, min_length=1, max_length=4096, description="Logic Task file (none: END at 0000)")
    variables: FilePath = Field(None, min_length=1, max_length=4096, description="variables file (V600-V999)")
    memory_file: FilePath = Field(
        None, min_length=1, max_length=4096,
        description="the battery-buffered memory (JSON): loaded at start when present instead of the files, written when it changes",
    )
    inputs: dict[InputName, bool | Signal] = Field(
        default_factory=dict,
        description="CLM inputs (I0.00.0 ... I1.10.7): true/false, an [io] input, a switch or a print-mark sensor; "
        "unwired: Automatic, E-Stop and Immediate Stop closed, the configured axes enabled, the rest 0",
    )
    outputs: dict[OutputName, Signal] = Field(default_factory=dict, description="CLM outputs (Q0.00.0 ... Q2.05.7) to [io] outputs")
    analog_inputs: dict[AnalogName, Annotated[float, Field(ge=-10.0, le=10.0)]] = Field(
        default_factory=dict,
        description="analog inputs AE1..AE4 in volts, read through the 12-bit converter and B017's averaging (analog.py) by the "
        "B017/VEO override (0-10 V = 0-100 %), V007-V010 and Status 45/49; unset: 0 V",
    )
    master_encoder_1: Name | None = Field(
        None, description="a [[master]] of kind 'wheel' whose encoder is the CLM's master encoder 1 (X1; C000-C003, master_encoder.py); none: not connected"
    )
    master_encoder_2: Name | None = Field(
        None, description="a [[master]] of kind 'wheel' whose encoder is the CLM's master encoder 2 (C004-C007; axis 2's measuring wheel, master_encoder.py); none: not connected"
    )
    decade_switch: DecadeSwitchConfig | None = Field(
        None,
        description="an IDS01 decade switch on X6, read when B002 selects it (function digit 1): V015-V018, "
        "faults 12-15 in Automatic (decade_switch.py); none: nothing connected",
    )
    start_at: float | None = Field(None, ge=0.0, le=1e6, description="press Start this many seconds after power-on (none: only the wired input or !START)")
    stop_after_cuts: int | None = Field(
        None, ge=1, le=1_000_000,
        description="flying cutoff (A100 mode 5): the run is complete after this many cuts (the report_output's rising "
        "edges); the cutoff program itself never stops (JST is forbidden, L3944); none: machine.duration ends it",
    )
    test_speed_steps: int | None = Field(
        None, ge=0, le=32,
        description="flying cutoff in test mode (A100's test digit): the material speed key pressed this many times when the "
        "cutoff first runs: the internal clock runs at steps/32 x A106 in Automatic (cutoff.py decision 11); none: 0",
    )
    report_output: OutputName | None = Field(
        None, description="the CLM output whose rising edge the report records (the press signal): the position error of axis 1 then"
    )


class ClmPersonality(Personality):
    """The CLM1.4 on the simulated plant (see the module docstring)."""

    name = "clm"
    Config = ClmConfig
    endpoints = ("serial-tcp", "modbus")

    def __init__(self, machine: Any, config: ClmConfig) -> None:
        super().__init__(machine, config)
        self.source = getattr(machine, "source", "") or "<machine>"
        self.base_dir = Path(machine.source).parent if getattr(machine, "source", "") else Path.cwd()
        problems: list[str] = []
        mc = machine.config
        for i, name in enumerate(config.axes):
            if name not in machine.units:
                problems.append(f"device.axes[{i}] = {name!r}: no such axis (axes: {', '.join(machine.units) or 'none'})")
        if mc.machine.logic_every != 1:
            problems.append(f"machine.logic_every = {mc.machine.logic_every}: the CLM runs every NC cycle (allowed: 1)")
        for k, step in enumerate(mc.job.steps):
            if step.command is not None and step.axis in config.axes:
                problems.append(f"job.steps[{k}].axis = {step.axis!r}: the axis is the CLM's (device.axes); its program commands it")
        self.memory = ClmMemory()
        self.memory_path = self._path(config.memory_file)
        if self.memory_path is not None:
            reason = unwritable_reason(self.memory_path)
            if reason is not None:
                problems.append(f"device.memory_file = {config.memory_file!r}: {self.memory_path} {reason}")
        self.store = RetainedStore(self.memory_path) if self.memory_path is not None else None
        self._load(config, problems)
        self._inputs = self._wire_inputs(config, problems)
        self._outputs = self._wire_outputs(config, problems)
        # where each wired bit lives in the image, found once: the inputs wired to true / false
        # as masks per byte (one write a byte a cycle), the others as (byte, bit, source)
        constant: dict[int, list[int]] = {}
        self._input_places: list[tuple[int, int, Callable[[], bool]]] = []
        for op, source in self._inputs:
            at, shift, _ = ProcessImage.locate(op)
            if source.__class__ is bool:
                masks = constant.setdefault(at, [0xFF, 0])  # [bits kept, bits set]
                masks[0] &= ~(1 << shift)
                masks[1] |= int(source) << shift  # type: ignore[arg-type]
            else:
                self._input_places.append((at, 1 << shift, source))  # type: ignore[arg-type]
        self._constant_inputs = [(at, keep, on) for at, (keep, on) in sorted(constant.items())]
        self._output_places = [(ProcessImage.locate(op), name) for op, name in self._outputs]
        self._check_cycle(problems)
        me_masters: dict[int, Any] = {}  # master encoder 1 / 2 -> its wheel master
        kinds = {m.name: m.kind for m in mc.master}
        for number, name in ((1, config.master_encoder_1), (2, config.master_encoder_2)):
            if name is None:
                continue
            if kinds.get(name) != "wheel":
                have = ", ".join(n for n, k in kinds.items() if k == "wheel") or "none"
                problems.append(f"device.master_encoder_{number} = {name!r}: no [[master]] of kind 'wheel' of that name (wheels: {have})")
            else:
                me_masters[number] = machine.masters[name]
        if config.master_encoder_1 is not None and config.master_encoder_1 == config.master_encoder_2:
            problems.append(f"device.master_encoder_2 = {config.master_encoder_2!r}: that wheel is master encoder 1 already (one wheel, one encoder input)")
        if config.decade_switch is not None:
            problems += config_problems(config.decade_switch)
        if problems:
            raise ConfigError(self.source, problems)
        from .axis import ClmAxis

        cycle_s = float(machine.period)
        axes = {n: ClmAxis(n, machine, name, self.memory.parameters, self.memory.image, cycle_s) for n, name in enumerate(config.axes, start=1)}
        for clm_axis in axes.values():  # a slave finds its master axis (slave.py)
            clm_axis.peers = axes
        self.rt = ClmRuntime(self.memory, axes, cycle_s)
        self.rt.on_move = self._moved
        from .master_encoder import MasterEncoder

        # master encoder n is the measuring wheel of axis n (it attaches itself, master_encoder.py)
        encoders = {n: MasterEncoder(master, self.rt, n) for n, master in me_masters.items()}
        self.rt.master_encoder = encoders.get(1)
        self.rt.master_encoder_2 = encoders.get(2)
        self._master_encoders = tuple(encoders.values())
        self._wire_marks(config)
        self.analog = AnalogIO(ANALOG_INPUTS)  # AE1..AE4 (a test or the operator may set_input them)
        for name, volts in config.analog_inputs.items():
            self.analog.set_input(name, volts)
        # the firmware's reading of them (12 bits, B017 averaging): override, V007-V010, Status 45/49
        self.analog_inputs = ClmAnalogInputs(self.analog)
        self.rt.analog = self.analog_inputs  # (status.py and the runtime's V007-V010 read it)
        cycle_us = round(cycle_s * 1e6)
        switch = None if config.decade_switch is None else DecadeSwitch(config.decade_switch, cycle_us)
        self.ids = IdsReceiver(self.rt, switch, cycle_us)
        self._mode_seen: str | None = None
        self._start_cycle = None if config.start_at is None else math.ceil(config.start_at / cycle_s - 1e-9)
        self._report = None if config.report_output is None else parse_operand(config.report_output, bit=True)
        self._report_place = None if self._report is None else ProcessImage.locate(self._report)
        self._report_previous = 0
        at, shift, _ = ProcessImage.locate(_START)
        self._start_bit = (at, 1 << shift)
        self.records: list[dict[str, Any]] = []
        self._targets: dict[int, float] = {}
        self._ever_ran = False
        self.store_error: str | None = None
        self.profibus: Any = None  # the Profibus DP image once served (register_endpoint, profibus.py)
        self.meter: Any = None  # cutreport.CutMeter of a flying cutoff (axis 1 in Ax00 mode 5)
        self._was_running = False

    # -- construction ----------------------------------------------------------------------

    def _path(self, name: str | None) -> Path | None:
        if name is None:
            return None
        p = Path(name)
        return p if p.is_absolute() else self.base_dir / p

    def _load(self, config: ClmConfig, problems: list[str]) -> None:
        """The retained memory when present, else the files; a file with an error is refused whole."""
        if self.store is not None and self.store.exists():
            try:
                self.store.load(self.memory)
            except ValueError as e:
                problems.append(f"device.memory_file = {config.memory_file!r}: {e}")
            return
        for key, kind in (("program", "program"), ("parameters", "parameters"), ("logic", "logic"), ("variables", "variables")):
            name = getattr(config, key)
            path = self._path(name)
            if path is None:
                continue
            loaded = read_file(path, kind)
            errors = [f for f in loaded.findings if f.is_error]
            if errors:
                problems += [f"device.{key} = {name!r}: {_finding(f)}" for f in errors[:10]]
                continue
            if kind == "program":
                self.memory.program = loaded.data  # type: ignore[assignment]
            elif kind == "parameters":
                self.memory.parameters = loaded.data  # type: ignore[assignment]
            elif kind == "logic":
                self.memory.logic = loaded.data  # type: ignore[assignment]
            else:
                for n, v in loaded.data.items():  # type: ignore[union-attr]
                    self.memory.variables.write(n, v, by="serial")

    def _wire_inputs(self, config: ClmConfig, problems: list[str]) -> list[tuple[Operand, Callable[[], bool] | bool]]:
        wiring: dict[str, bool | str] = dict(_READY)
        for n in range(1, len(config.axes) + 1):
            wiring[_ENABLE[n]] = True
        wiring.update(config.inputs)
        out: list[tuple[Operand, Callable[[], bool] | bool]] = []
        for name, value in sorted(wiring.items()):
            try:
                op = parse_operand(name, bit=True)
            except ValueError as e:
                problems.append(f"device.inputs.{name}: {e}")
                continue
            try:
                out.append((op, value if isinstance(value, bool) else self.machine.signal(value)))
            except ValueError as e:  # ConfigError from machine.signal too
                problems.append(f"device.inputs.{name} = {value!r}: {'; '.join(getattr(e, 'problems', [str(e)]))}")
        return out

    def _wire_marks(self, config: ClmConfig) -> None:
        """The raster inputs wired to a print-mark sensor latch at its sub-cycle edges
        (registration.py)."""
        sensors = getattr(self.machine, "sensors", {})
        for name, value in config.inputs.items():
            if isinstance(value, str) and value in sensors and name in ("I0.01.7", "I0.01.4"):
                op = parse_operand(name, bit=True)
                self.rt.registration.raster_sensors[(op.source, op.byte, op.bit)] = sensors[value].device

    def _wire_outputs(self, config: ClmConfig, problems: list[str]) -> list[tuple[Operand, str]]:
        out = []
        for name, io_name in sorted(config.outputs.items()):
            try:
                op = parse_operand(name, bit=True)
            except ValueError as e:
                problems.append(f"device.outputs.{name}: {e}")
                continue
            if io_name not in self.machine.config.io.outputs:
                problems.append(f"device.outputs.{name} = {io_name!r}: no such io output (outputs: {', '.join(self.machine.config.io.outputs) or 'none'})")
                continue
            out.append((op, io_name))
        return out

    def _check_cycle(self, problems: list[str]) -> None:
        """machine.cycle_us must be the CLM's NC cycle, B010 (issue 12; spec §1.4)."""
        b010 = float(self.memory.parameters.get("B010")["cycle_time"])
        axes = max(len(self.config.axes), max(self.memory.parameters.enabled_axes(), default=1))  # type: ignore[attr-defined]
        ms = b010 if b010 else _AUTO_CYCLE_MS[min(4, axes)]
        cycle_us = self.machine.config.machine.cycle_us
        if abs(cycle_us - ms * 1000) > 0.5:
            problems.append(
                f"machine.cycle_us = {cycle_us}: the CLM's NC cycle is {ms:g} ms (B010 = {b010:g}"
                + (f", 0.0 = automatic for {axes} axes" if not b010 else "") + f"): set cycle_us = {round(ms * 1000)}"
            )

    # -- the cycle ---------------------------------------------------------------------------

    def tick(self, cycle: int) -> None:
        image = self.memory.image
        data = image.data
        io = self.machine.io
        for (at, shift, _), name in self._output_places:  # last cycle's outputs reach the hardware now
            io.write(name, bool(data[at] >> shift & 1))
        if self._report_place is not None:  # the press gets its signal now: record the feed there
            at, shift, _ = self._report_place
            now = data[at] >> shift & 1
            if now and not self._report_previous:
                if self.meter is not None and self.rt.cutoff is not None:
                    self.meter.cut(cycle)  # a flying cutoff: the piece measured on the material
                else:
                    self._record(cycle)
            self._report_previous = now
        for at, keep, on in self._constant_inputs:  # the wired inputs into the image
            data[at] = data[at] & keep | on
        for at, bit, source in self._input_places:
            data[at] = data[at] | bit if source() else data[at] & ~bit
        if self._start_cycle is not None:
            at, bit = self._start_bit
            data[at] = data[at] | bit if cycle == self._start_cycle else data[at] & ~bit
        mode = self.rt.modes.mode
        if mode != self._mode_seen:  # B017's averaging is taken on leaving Parameter mode
            if self._mode_seen in (None, "parameter", "power-on") and mode != "parameter":
                self.analog_inputs.configure(self.memory.parameters)
            self._mode_seen = mode
        analog = self.analog_inputs
        velocity = self.rt.velocity
        if analog.window > 1:  # (averaging; else nothing per cycle unless an override reads, analog.py decision 3)
            analog.tick()
        if velocity.needs_analog:
            velocity.analog_volts[:] = analog.all_volts()
        for encoder in self._master_encoders:  # (nothing per cycle without a master encoder)
            encoder.sample(cycle)
        self.ids.tick(cycle)  # the IDS01 on X6 (a fault 12-15 stops the tasks before they run)
        if self.profibus is not None:  # the DP control word as system inputs, the watchdog (profibus.py)
            self.profibus.cycle(self.rt.step)
        else:
            self.rt.step()
        running = self.rt.modes.running
        self._ever_ran = self._ever_ran or running
        if self.rt.cutoff is not None:  # (cutreport.py: the first piece counts from the start)
            if self.meter is None:
                from .cutreport import CutMeter

                self.meter = CutMeter(self)
                for _ in range(self.config.test_speed_steps or 0):  # test mode's key (cutoff.py 11)
                    self.rt.cutoff.test_key("up")
            if running and not self._was_running:
                self.meter.started()
        self._was_running = running
        if self.store is not None:
            try:
                self.store.save(self.memory)
                self.store_error = None
            except OSError as e:  # the CLM keeps running; the error is reported, not a traceback
                self.store_error = f"{self.store.path}: {e.strerror or e}"

    def _moved(self, axis: Any, task: Any) -> None:
        self._targets[axis.number] = float(axis.target)

    def _record(self, cycle: int) -> None:
        axis = self.rt.axes.get(1)
        if axis is None:
            return
        target = self._targets.get(1, float(axis.target if axis.target is not None else axis.command_position))
        actual = axis.actual_position
        iut = getattr(axis, "iut", None)
        if iut is not None:  # a rotary table: the station within the revolution (0..IUT)
            wrapped = target % float(iut)
            actual, target = wrapped + (actual - target), wrapped
        counts = getattr(self.machine.units[self.config.axes[0]].encoder, "counts_per_unit", None)
        self.records.append({
            "feed": len(self.records) + 1,
            "time_s": round(cycle * self.machine.period, 6),
            "target": target,
            "actual": actual,
            "error": actual - target,
            "error_counts": None if counts is None else round((actual - target) * counts, 3),
        })

    @property
    def finished(self) -> bool:  # type: ignore[override]
        """The program ran and has stopped (JST, a fault): a batch is done; a flying cutoff has
        made its stop_after_cuts cuts."""
        n = self.config.stop_after_cuts
        if n is not None and self.meter is not None and len(self.meter.records) >= n:
            return True
        return self._ever_ran and not self.rt.modes.running

    # -- persistence and reporting -------------------------------------------------------------

    def stop(self) -> bool:
        """Shutdown (`serve`'s Ctrl-C, SIGTERM): what the CLM's Immediate Stop does, also in the
        flying cutoff, where the input itself has no function (L3929): tasks 1, 2, 4, 5 stop
        where they are, every axis brakes with its current deceleration (a slave ramps its
        following down). The machine then runs cycles until they are at rest. The kernel
        axes' own stop ramp instead brakes the set point harder than the CLM's loop model
        expects and trips Drive Runaway (fault 42) in the middle of a feed."""
        self.rt.modes.immediate_stop(programmed=True)
        return True

    def limited_axes(self) -> set[str]:
        """The CLM accounts for the travel of its axes: a linear one (Ax00 type 1) by Ax03/Ax04
        once referenced, a rotary one or a table is endless (axis.py decision 15)."""
        return set(self.config.axes)

    def byte_endpoint(self) -> Any:
        """The X6 serial protocol (`serial`) on this CLM's runtime, for `serve --serial-tcp /
        --serial-pty`: each connection takes its own session; writes need `network_writes`; an
        acknowledged write is in the memory file before its reply."""
        from .serial import ClmSerialEndpoint

        store = None if self.store is None else (lambda: self.store.save(self.memory))  # type: ignore[union-attr]
        return ClmSerialEndpoint(self.rt, lambda: self.network_writes, store=store)

    def register_endpoint(self) -> Any:
        """The Profibus DP image (`profibus`) as Modbus TCP registers, for `serve --modbus`
        (docs/clm-profibus.md): writes need `network_writes`; a write over the service channel
        is in the memory file before its reply."""
        from .profibus import ClmProfibus

        if self.profibus is None:
            store = None if self.store is None else (lambda: self.store.save(self.memory))  # type: ignore[union-attr]
            self.profibus = ClmProfibus(self.rt, lambda: self.network_writes, store=store)
        return self.profibus

    def store_paths(self) -> list[Path]:
        return [self.memory_path] if self.memory_path is not None else []

    def persist(self) -> list[Path]:
        if self.store is None:
            return []
        self.store.save(self.memory, force=True)
        return [self.store.path]

    def summary(self) -> dict[str, Any]:
        modes = self.rt.modes
        errors = [abs(r["error"]) for r in self.records]
        fault = modes.fault_error
        products = self.rt.registration.products
        cuts = [] if self.meter is None else self.meter.records
        cutoff = self.rt.cutoff
        cut_errors = [abs(c["error_counts"]) for c in cuts if c["error_counts"] is not None]
        return {
            "headline": (
                f"CLM: {modes.mode}"
                + ("" if cuts else f", {len(self.records)} feed(s) recorded")
                + (f", largest error {max(errors):.4f}" if errors else "")
                + (f", {len(products)} product(s) registered, largest correction {max(abs(r['correction']) for r in products):.3f}" if products else "")
                + (f", {len(cuts)} cut(s), largest length error {max(cut_errors):.2f} increments" if cut_errors else "")
                + (f", fault {fault.code} {fault.text}" if fault is not None else "")
            ),
            "mode": modes.mode,
            "fault": None if fault is None else {"code": fault.code, "text": fault.text, "where": fault.where, "detail": fault.detail},
            "tasks": [{"task": t.number, "instruction": t.pc, "running": t.running} for t in self.rt.tasks],
            "counters": {f"{n:04d}": c for n, c in sorted(self.memory.program.counters.items())},
            "feeds": self.records,
            "max_abs_error": max(errors) if errors else None,
            "store_error": self.store_error,
            "registration": self.rt.registration.products,
            "decade_switch": self._ids_summary(),
            "cuts": cuts,  # the flying cutoff's pieces (cutreport.py; the FS701's keys)
            "length_unit": self.machine.axis(self.config.axes[0]).config.unit,
            "cutoff": None if cutoff is None else {"material_length": float(cutoff.material_length),
                                                   "product_length": float(cutoff.product_length), "state": cutoff.state},
            "profibus": None if self.profibus is None else self.profibus.summary(),
        }

    def json_fields(self, device_summary: dict[str, Any]) -> dict[str, Any]:
        """`run --json` of a flying cutoff: "cuts" and "summary" in the FS701's names (report.cuts)."""
        if not device_summary.get("cuts"):
            return {}
        from axisline.report.cuts import job_json

        return job_json(device_summary)

    def plots(self, out_dir: str | Path, data: dict | None, units: dict | None = None) -> list[Path]:
        from .cutreport import write_plots

        return write_plots(self.summary(), out_dir)

    def _ids_summary(self) -> dict[str, Any] | None:
        ids = self.ids
        if ids.switch is None and not ids.enabled:
            return None
        return {"read": ids.enabled, "telegrams": ids.telegrams, "errors": dict(sorted(ids.errors.items())),
                "length": None if ids.switch is None else ids.switch.length,
                "velocity": None if ids.switch is None else ids.switch.velocity}

    def report_markdown(self, device_summary: dict[str, Any], plots: list[Path]) -> str:
        lines = ["## CLM1.4", "", f"Mode at the end: {device_summary['mode']}."]
        fault = device_summary.get("fault")
        if fault:
            lines.append(f"Fault {fault['code']} {fault['text']} at {fault['where'] or '-'}: {fault['detail']}")
        feeds = device_summary.get("feeds") or []
        if feeds:
            lines += ["", "Position error of axis 1 when the press signal came:", "",
                      "| feed | time s | target | actual | error | error (counts) |", "|---|---|---|---|---|---|"]
            lines += [f"| {r['feed']} | {r['time_s']:.3f} | {r['target']:.4f} | {r['actual']:.4f} | {r['error']:+.4f} | {r['error_counts']} |" for r in feeds]
        products = device_summary.get("registration") or []
        if products:  # SRP (registration.py): what a user checks on a print-registered feed
            lines += ["", "Registration (SRP) per product: mark latched, measured distance to the end position, "
                      "correction of the next feed:", "", "| product | mark | measured | correction |", "|---|---|---|---|"]
            lines += [f"| {r['product']} | {r['mark']:.3f} | {r['measured']:.3f} | {r['correction']:+.3f} |" for r in products]
        ids = device_summary.get("decade_switch")
        if ids:  # the IDS01 (decade_switch.py): what came over the link, what went wrong on it
            errors = ", ".join(f"{code}: {n}" for code, n in ids["errors"].items()) or "none"
            lines += ["", f"IDS01 decade switch on X6 ({'read' if ids['read'] else 'not read: B002 selects a data interface'}): "
                      f"{ids['telegrams']} good telegram(s), errors {errors}."]
        from .cutreport import report_section

        lines += report_section(device_summary, plots)
        return "\n".join(lines) + "\n"

    def trace_channels(self) -> dict[str, tuple[Callable[[], Any], str, type]]:
        out: dict[str, tuple[Callable[[], Any], str, type]] = {
            "clm.task1": (lambda: self.rt.tasks[0].pc, "", int),
            "clm.running": (lambda: self.rt.modes.running, "", bool),
        }
        for n, axis in self.rt.axes.items():
            out[f"clm.axis{n}.lag"] = (lambda a=axis: a.lag, "IU", float)
        return out


_START = parse_operand(START, bit=True)


def _finding(f: Finding) -> str:
    return str(f)[:300]
