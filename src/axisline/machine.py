"""The Machine: a machine file turned into axes, plant, scheduler, job and scope.

One cycle (period T) runs the stages of kernel.scheduler in order:

    INPUTS         encoder counts -> actual position of each axis
    LOGIC          the job (and, later, a device personality)
    SETPOINTS      each axis samples its profile / sync source
    POSITION_LOOP  each axis: Kv, feed-forward, following-error monitoring
    ACTUATE        drive commands, then the plant advances by T
    RECORD         the scope

The same code runs on the simulated clock (`run`, as fast as possible, exact time)
and on the wall clock (`serve`, soft real time).
"""

from __future__ import annotations

import math
import time
import zlib
from collections import deque
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable, cast

import numpy as np

from .config import AxisEntry, MachineConfig, device_config, load_machine_file, parse_machine
from .configerrors import ConfigError
from .job import JobRunner
from .kernel import Clock, Scheduler, SimulatedClock, Stage, Trace
from .motion.axis import Axis, AxisConfig, AxisState, BufferMode, Direction
from .motion.camsync import CamFollower, CamState
from .motion.gear import Gear
from .motion.gear_in_position import GearInPos
from .motion.homing import DirectHoming, SwitchHoming
from .scope_channels import make_trace
from .sync_setup import SyncHandle, build_cam, build_master
from .actuation import actuator
from .plant.drives import ServoDrive, StepperDrive
from .plant.encoder import IncrementalEncoder

_ERROR_STOP = AxisState.ERROR_STOP
_DISABLED = AxisState.DISABLED
# states in which an axis is not producing motion
_IDLE = {AxisState.STANDSTILL, AxisState.DISABLED, AxisState.ERROR_STOP}


@dataclass
class AxisUnit:
    """An axis with its drive and (optional) encoder: the controller and the plant side."""

    axis: Axis
    drive: Any
    encoder: Any
    config: AxisEntry
    actual_position: float = 0.0
    velocity_output: float = 0.0
    max_following_error: float = 0.0
    max_speed: float = 0.0
    #: a device's own position controller in place of the axis' Kv loop (Machine.drive_by):
    #: called in POSITION_LOOP with (actual position, drive velocity), returns the drive command
    controller: Callable[[float, float], float] | None = None
    #: the controller's output is volts on the analog input (else a velocity, units/s)
    controller_volts: bool = False
    command_volts: float = 0.0
    #: the controller's counting direction of the encoder and polarity of its command
    #: (Machine.set_directions): -1 turns a miswired encoder or command output round
    feedback_sign: float = 1.0
    output_sign: float = 1.0
    #: what a commissioning engineer must see (Machine.warnings): cycles whose command the drive
    #: could not follow (+-10 V or its speed limit), the largest speed asked, the travel range
    over_cycles: int = 0
    peak_request: float = 0.0
    first_over_cycle: int = -1
    travel_low: float = math.inf
    reach: float = math.inf  # the fastest the drive goes (its speed limit, or +-10 V on the analog input)
    travel_high: float = -math.inf
    # the plant's own servo and encoder, typed (None: another kind, e.g. a drive on CANopen):
    # compiled code calls them without an attribute lookup or a boxed float on the way
    servo: ServoDrive | None = field(default=None, init=False, repr=False)
    plant_encoder: IncrementalEncoder | None = field(default=None, init=False, repr=False)

    def __post_init__(self) -> None:
        self._unit_per_count = 1.0 / self.encoder.counts_per_unit if self.encoder is not None else 0.0
        self.servo = self.drive if isinstance(self.drive, ServoDrive) else None
        self.plant_encoder = self.encoder if isinstance(self.encoder, IncrementalEncoder) else None

    def sample(self, cycle: int) -> None:
        enc = self.plant_encoder
        if enc is not None:
            x = self.actual_position = enc.sample() * self._unit_per_count * self.feedback_sign
        elif self.encoder is not None:
            x = self.actual_position = self.encoder.sample() * self._unit_per_count * self.feedback_sign
        else:
            x = self.actual_position = self.drive.position * self.feedback_sign
        if x < self.travel_low:
            self.travel_low = x
        if x > self.travel_high:
            self.travel_high = x

    def note_over(self, cycle: int, requested: float) -> None:
        """A cycle whose command the drive cannot follow (`requested` units/s)."""
        self.over_cycles += 1
        if self.first_over_cycle < 0:
            self.first_over_cycle = cycle
        if abs(requested) > abs(self.peak_request):
            self.peak_request = requested

    def loop(self, cycle: int) -> None:
        drive = self.drive
        servo = self.servo
        v = servo.velocity if servo is not None else drive.velocity
        ctl = self.controller
        v = v * self.feedback_sign  # the drive's velocity as the controller's encoder sees it
        sign = self.output_sign
        if ctl is None:
            self.velocity_output = self.axis.position_loop(self.actual_position, v) * sign
        elif self.controller_volts:
            self.command_volts = u = ctl(self.actual_position, v) * sign
            self.velocity_output = u * drive.velocity_per_volt  # nominal: the scope's "output"
        else:
            self.velocity_output = ctl(self.actual_position, v) * sign
        fe = self.axis.following_error
        peak = self.max_following_error
        if fe > peak or -fe > peak:
            self.max_following_error = abs(fe)
        peak = self.max_speed
        if v > peak or -v > peak:
            self.max_speed = abs(v)


@dataclass
class Sensor:
    """A plant sensor with sub-cycle edges (switch or print-mark sensor) and its recent edges."""

    name: str
    device: Any
    edges: deque = field(default_factory=lambda: deque(maxlen=1024))

    def sample(self, t_start: float, dt: float) -> None:
        for e in self.device.sample(t_start, dt):
            self.edges.append(e)  # Edge is an immutable tuple: safe to keep

    @property
    def state(self) -> bool:
        return self.device.state


@dataclass
class RunResult:
    cycles: int
    simulated_s: float
    wall_s: float
    completed: bool
    faults: list[str] = field(default_factory=list)


class Machine:
    """Everything a machine file describes, wired into one cycle."""

    def __init__(self, config: MachineConfig, *, seed: int | None = None, clock: Clock | None = None, source: str = "") -> None:
        self.config = config
        self.source = source
        self.seed = config.machine.seed if seed is None else seed
        period_us = config.machine.cycle_us
        self.clock = clock if clock is not None else SimulatedClock(period_us)
        self.period = self.clock.period
        self.scheduler = Scheduler(self.clock)
        self.commands = self.scheduler.commands
        self.units: dict[str, AxisUnit] = {}
        self.sensors: dict[str, Sensor] = {}  # "<axis>.<switch>" and print-mark sensors
        self.faults: list[str] = []
        # axes that are masters get their set point first, so their slaves see this cycle's
        master_axes = {m.axis for m in config.master if m.kind == "axis"}
        for entry in sorted(config.axis, key=lambda a: a.name not in master_axes):
            self._add_axis(entry)
        self.material = config.material.build() if config.material is not None else None
        for mark in config.marks:  # marks on the material line, or on a strip a feed roll moves
            carrier = self.units[mark.carrier].drive if mark.carrier is not None else self.material
            self.sensors[mark.name] = Sensor(mark.name, mark.build(carrier, self.child_rng(f"marks:{mark.name}")))
        self._add_sync(config)
        self.io = config.io.build()  # before the personality, which may wire its inputs to it
        self.device = None  # the personality (devices/base.py), if the machine file names one
        dev_cfg = device_config(config, source or "<machine>")
        if dev_cfg is not None:
            from .devices import base

            self.device = base.load(config.machine.personality)(self, dev_cfg)
            self.scheduler.add_task("device", self.device.tick, Stage.LOGIC, every=config.machine.logic_every)
        self._io_followers = tuple((n, self.sensors[n]) for n in config.io.inputs if n in self.sensors)
        self.actuators = tuple((a, a.build()) for a in config.actuator)
        self._io_used = bool(self.io.inputs or self.io.outputs)
        if self._io_used:  # the first cycle sees the inputs' power-on levels, not an empty image
            self.io.sample()
        if self.material is not None or self.sensors or config.io.inputs or config.io.outputs:
            self.scheduler.add_task("plant", self._plant_step, Stage.ACTUATE)
        self._axes = tuple((n, u.axis) for n, u in self.units.items())
        self._reported: dict[str, str] = {}
        self.job = JobRunner(config.job, self.period, self._issue)
        self.scheduler.add_task("job", self.job.tick, Stage.LOGIC, every=config.machine.logic_every)
        self.scheduler.add_task("faults", self._watch_faults, Stage.RECORD)
        self.trace: Trace | None = None
        if config.trace.enabled:
            self.trace = make_trace(self)  # scope_channels.py: the channels and their getters
            self.scheduler.add_task("scope", self.trace.record, Stage.RECORD)

    # -- construction ---------------------------------------------------------------

    def child_rng(self, name: str) -> np.random.Generator:
        """A random stream of its own for each named source: adding one leaves the others alone."""
        return np.random.default_rng([self.seed, zlib.crc32(name.encode())])

    def _add_sync(self, config: MachineConfig) -> None:
        """Masters and cams of the machine file (sync_setup.py)."""
        base = Path(self.source).parent if self.source else Path.cwd()
        self.cams = {c.name: build_cam(c, base) for c in config.cam}
        self.masters = {}
        wheels = []
        for entry in config.master:
            master, wheel = build_master(entry, self)
            self.masters[entry.name] = master
            if wheel is not None:
                wheels.append(wheel)
        self._followers: dict[str, CamFollower] = {}
        if wheels:
            sample = tuple(w.sample for w in wheels)

            def sample_wheels(cycle: int) -> None:
                for f in sample:
                    f()

            self.scheduler.add_task("wheels", sample_wheels, Stage.INPUTS)
        if self.masters:
            updates = tuple(m.update for m in self.masters.values())

            # after the axes: slaves update their master themselves (once per cycle); this
            # keeps masters without a slave current for the scope
            def update_masters(cycle: int) -> None:
                for f in updates:
                    f(cycle)

            # a single master's update is the whole task: run it without the loop around it
            task = updates[0] if len(updates) == 1 else update_masters
            self.scheduler.add_task("masters", task, Stage.SETPOINTS)

    @classmethod
    def from_file(
        cls, path: str | Path, *, seed: int | None = None, clock: Clock | None = None, duration: float | None = None
    ) -> "Machine":
        """Build from a machine file; `duration` overrides machine.duration (it sizes the scope)."""
        config = load_machine_file(path)
        if duration is not None:
            data = config.model_dump()
            data["machine"]["duration"] = duration
            config = parse_machine(data, f"{path} (with --duration {duration:g})")
        return cls(config, seed=seed, clock=clock, source=str(path))

    def _add_axis(self, entry: AxisEntry) -> None:
        # the axis sees only its own parameters, not the plant tables beside them
        axis_cfg = entry.model_dump(include=set(AxisConfig.model_fields))
        axis = Axis(AxisConfig.model_validate(axis_cfg), self.period)
        if entry.drive.type == "cia402":  # a drive on CANopen (drives/): its counts come over the bus
            from .drives import attach

            drive, encoder = attach(self, entry, axis), None
        else:
            drive = entry.drive.build()
            encoder = entry.encoder.build(drive) if entry.encoder is not None else None
        unit = AxisUnit(axis, drive, encoder, entry)
        unit.actual_position = drive.position
        # a disabled axis' set point follows the actual position: seed it with the plant's
        # initial one, so an axis enabled in the first cycle is not pulled to 0
        axis.position_loop(drive.position, 0.0)
        name = entry.name
        for sw in entry.switches:
            self.sensors[f"{name}.{sw.name}"] = Sensor(f"{name}.{sw.name}", sw.build(drive))
        self.units[name] = unit
        s = self.scheduler
        s.add_task(f"{name}.inputs", unit.sample, Stage.INPUTS)
        s.add_task(f"{name}.setpoint", axis.update_setpoint, Stage.SETPOINTS)
        s.add_task(f"{name}.loop", unit.loop, Stage.POSITION_LOOP)
        s.add_task(f"{name}.actuate", actuator(unit, self.period), Stage.ACTUATE)

    def drive_by(self, axis: str, controller: Callable[[float, float], float], *, volts: bool = True) -> None:
        """Let a device's own position controller drive `axis` instead of the axis' Kv loop.

        `controller(actual_position, drive_velocity)` runs in POSITION_LOOP in place of
        `Axis.position_loop` (it should call that itself for the axis' bookkeeping: following
        error, actual position) and returns the drive command: volts for a servo's analogue
        input (`volts=True`: an analog servo gets them with its offset, drift and gain errors, a
        digital one their nominal velocity), else a velocity in units/s. Steppers have no loop.
        """
        unit = self.units[axis]
        if isinstance(unit.drive, StepperDrive):
            raise ValueError(f"axis {axis!r}: a stepper drive has no position loop to replace")
        if unit.config.drive.type == "cia402":
            raise ValueError(f"axis {axis!r}: a CiA 402 drive in CSP closes its own position loop; a device's loop cannot replace it")
        unit.controller = controller
        unit.controller_volts = bool(volts)

    def set_directions(self, axis: str, *, feedback: int = 1, output: int = 1) -> None:
        """The controller's view of `axis`' wiring: `feedback = -1` counts the encoder the other
        way, `output = -1` turns the command's polarity (a drive direction parameter, the CLM's
        Ax21). Both -1 reverse the axis' direction of motion on an unchanged plant."""
        for name, value in (("feedback", feedback), ("output", output)):
            if value not in (1, -1):
                raise ValueError(f"{name} direction is +1 or -1, not {value}")
        unit = self.units[axis]
        if isinstance(unit.drive, StepperDrive) and (feedback, output) != (1, 1):
            raise ValueError(f"axis {axis!r}: a stepper drive follows its steps; it has no feedback or command polarity to turn")
        if unit.config.drive.type == "cia402" and (feedback, output) != (1, 1):
            raise ValueError(f"axis {axis!r}: a CiA 402 drive's directions are its own parameters (0x607E polarity), set in the drive")
        unit.feedback_sign = float(feedback)
        unit.output_sign = float(output)

    def _plant_step(self, cycle: int) -> None:
        """The rest of the plant after the drives moved: material, then every sensor's edges."""
        dt = self.period
        if self.material is not None:
            self.material.step(dt)
        sensors = self.sensors
        if sensors:  # (t_start serves only the sensors)
            t_start = cycle * self.clock.period_us / 1e6
            for sensor in sensors.values():
                sensor.sample(t_start, dt)
        for name, sensor in self._io_followers:
            self.io.set_input(name, sensor.state)
        io = self.io
        for entry, cylinder in self.actuators:  # the outputs the controller wrote this cycle move them
            cylinder.step(dt, io.output(entry.valve))
            if entry.retracted is not None:
                io.set_input(entry.retracted, cylinder.retracted)
            if entry.extended is not None:
                io.set_input(entry.extended, cylinder.extended)
        if self._io_used:  # an image without inputs and outputs samples nothing
            self.io.sample()

    def signal(self, wiring: bool | str) -> bool | Callable[[], bool]:
        """A device input as the machine file wires it: a constant, or a function reading a
        switch/sensor ("x.ref", "marks") or a digital input of the I/O image, by name."""
        if isinstance(wiring, bool):
            return wiring
        sensor = self.sensors.get(wiring)
        if sensor is not None:
            return lambda: sensor.state
        if wiring in self.config.io.inputs:
            io = self.io
            return lambda: io.read(wiring)
        raise ConfigError(self.source or "<machine>", [
            f"input wiring {wiring!r}: no such switch, sensor or io input "
            f"(switches/sensors: {', '.join(self.sensors) or 'none'}; io inputs: {', '.join(self.config.io.inputs) or 'none'})"
        ])

    # -- commands -----------------------------------------------------------------------

    def axis(self, name: str) -> Axis:
        return self.units[name].axis

    @property
    def axes(self) -> dict[str, Axis]:
        return {n: u.axis for n, u in self.units.items()}

    def _issue(self, axis: str | None, command: str, kwargs: dict[str, Any]) -> Any:
        """Give an axis command from inside the cycle (job, personality); `axis` is None for
        a master command (set_master_velocity)."""
        if command in _SYNC_COMMANDS:
            try:
                return self._sync_command(axis, command, kwargs)
            except ValueError as e:  # an infeasible or bad request: the step fails, the cycle goes on
                return _Failed(str(e))
        assert axis is not None  # (every command but set_master_velocity names its axis)
        ax = self.units[axis].axis
        if command == "home":
            return ax.home(self._homing(axis, kwargs))
        return getattr(ax, command)(**_axis_kwargs(command, kwargs))

    def _sync_command(self, axis: str | None, command: str, kw: dict[str, Any]) -> Any:
        """Couplings of the job (gear, cam) and master commands."""
        if command == "set_master_velocity":
            master: Any = self.masters[kw["master"]]  # a virtual master or a time base
            if hasattr(master, "set_velocity"):
                master.set_velocity(kw["velocity"])
                return SyncHandle(None, lambda: master.in_velocity)
            master.set_speed(kw["velocity"])
            return SyncHandle(None, lambda: True)
        assert axis is not None  # (every command but set_master_velocity names its axis)
        ax = self.units[axis].axis
        if command == "gear_in":
            gear = Gear(self.masters[kw["master"]], ax, kw["numerator"], kw["denominator"])
            return SyncHandle(gear.gear_in(), lambda: gear.in_gear)
        if command == "gear_in_pos":
            master = self.masters[kw["master"]]
            # plan the approach for the speed the master is heading for: a master still ramping
            # up then only makes the slave slower than planned, never faster
            nominal = max(abs(master.velocity), abs(getattr(master, "target_velocity", 0.0)))
            gear = GearInPos(
                master, ax, kw["numerator"], kw["denominator"],
                master_sync_position=kw["master_sync_position"], slave_sync_position=kw["slave_sync_position"],
                master_velocity=nominal or None,
            )
            return SyncHandle(gear.gear_in(), lambda: gear.in_gear)
        if command == "cam_in":
            follower = CamFollower(self.masters[kw["master"]], self.cams[kw["cam"]], master_offset=kw.get("master_offset", 0.0))
            follower.couple(ax.command_position, kw.get("coupling"), kw.get("synchronous"))
            self._followers[axis] = follower
            return SyncHandle(ax.start_sync(follower), lambda: follower.synchronous)
        if command == "cam_out":
            coupled = self._followers.get(axis)
            if coupled is None or ax.state is not AxisState.SYNCHRONIZED_MOTION:
                raise ValueError(f"cam_out: axis {axis!r} follows no cam")
            coupled.decouple(kw["decoupling"], kw["braking"], kw["standstill"])
            return SyncHandle(ax.active_command, lambda: coupled.state is CamState.DECOUPLED)
        # sync_out: leave the master; the axis halts with its ramp
        return ax.end_sync(kw.get("deceleration"))

    def _homing(self, axis: str, kw: dict[str, Any]):
        """A homing procedure from job-step words (method = direct | switch)."""
        position = kw.get("position", 0.0)
        if kw.get("method", "direct") == "direct":
            return DirectHoming(position)
        sensor = self.sensors[f"{axis}.{kw['switch']}"]
        cfg = self.units[axis].axis.config
        direction = kw.get("direction", -1)
        return SwitchHoming(
            lambda: sensor.state,
            velocity=cast(float, kw.get("velocity", cfg.jog_velocity)),
            direction=-1 if direction in (-1, "negative") else 1,
            position=position,
            acceleration=kw.get("acceleration"),
            max_distance=kw.get("max_distance"),
        )

    def submit(self, axis: str | None, command: str, **kwargs: Any):
        """Give an axis command from outside (CLI, fieldbus, HMI): applied at the next cycle boundary."""
        return self.commands.submit(self._issue, axis, command, kwargs)

    # -- running ------------------------------------------------------------------------

    def _watch_faults(self, cycle: int) -> None:
        for name, ax in self._axes:
            if ax.state is _ERROR_STOP:
                text = f"axis {name}: error {ax.error_id}: {ax.error_text}"
                if self._reported.get(name) != text:
                    self._reported[name] = text
                    self.faults.append(f"t={cycle * self.period:.4f} s {text}")
            elif name in self._reported:
                del self._reported[name]  # reset: a later fault is reported again
        if self.job.failed and f"job: {self.job.failed}" not in self.faults:
            self.faults.append(f"job: {self.job.failed}")

    def at_rest(self) -> bool:
        """Every set point at rest and every motor settled (the loop has pulled in the lag)."""
        return all(
            u.axis.state in _IDLE
            and u.axis.command_velocity == 0.0
            and abs(u.drive.velocity) <= 1e-4 * u.config.v_max
            for u in self.units.values()
        )

    def device_finished(self) -> bool | None:
        """The personality's own job (a batch): None if it runs none, else whether it is done."""
        if self.device is None:
            return None
        done = getattr(self.device, "finished", None)
        return None if done is None else bool(done)

    def run(self, duration: float | None = None, progress: Callable[[float], None] | None = None, until_job_done: bool = True) -> RunResult:
        """Simulate: run until the job (and the personality's own job, if it runs one) is done
        and every axis is at rest, or `duration` seconds."""
        limit = self.config.machine.duration if duration is None else duration
        cycles = max(1, round(limit / self.period))
        start_cycle = self.clock.cycle
        t0 = time.perf_counter()
        every = max(1, cycles // 200)
        completed = False
        s = self.scheduler
        device_job = self.device_finished() is not None
        has_job = bool(self.config.job.steps) or device_job
        for i in range(cycles):
            s.run_cycle()
            if (
                until_job_done
                and has_job
                and self.job.finished
                and (not device_job or self.device_finished())
                and self.at_rest()
            ):
                completed = True
                break
            if progress is not None and i % every == 0:
                progress((i + 1) / cycles)
        else:
            # A duration asked for explicitly is a complete run; the file's own limit
            # reached with the job still running is a timeout.
            device_done = not device_job or bool(self.device_finished())
            completed = duration is not None or not has_job or (self.job.finished and device_done)
            if not completed:
                what = "job" if not self.job.finished else f"{self.config.machine.personality} job"
                self.faults.append(f"{what} not finished within machine.duration = {limit:g} s")
        if progress is not None:
            progress(1.0)
        n = self.clock.cycle - start_cycle
        return RunResult(n, n * self.period, time.perf_counter() - t0, completed and not self.faults and not self.job.failed, list(self.faults))

    def stop_all(self, max_seconds: float = 30.0) -> bool:
        """Stop every moving axis with its stop ramp; True when all came to rest.

        A personality that drives its axes itself stops them with its own ramps (its stop()),
        so it stays consistent with them; otherwise the axes get a stop command."""
        if self.device is None or not self.device.stop():
            for u in self.units.values():
                if u.axis.state not in _IDLE:
                    u.axis.stop()
        ok = self.scheduler.run_until(self.at_rest_after_stop, max(1, round(max_seconds / self.period)))
        for u in self.units.values():
            if u.axis.state is AxisState.STOPPING:
                u.axis.stop_release()
        self.scheduler.run_cycle()
        return ok

    def at_rest_after_stop(self) -> bool:
        return all(u.axis.command_velocity == 0.0 and u.axis.command_acceleration == 0.0 for u in self.units.values())

    def persist(self) -> list[Path]:
        """Save what must survive a restart (parameters, programs, curves): the personality's."""
        return self.device.persist() if self.device is not None else []

    # -- reporting ----------------------------------------------------------------------

    def warnings(self) -> list[str]:
        """What a commissioning engineer must see after a run (report/summary.py)."""
        from .report.summary import run_warnings

        return run_warnings(self)

    def summary(self, result: RunResult) -> dict[str, Any]:
        """The run summary (JSON, the console table, report.md): report/summary.py."""
        from .report.summary import run_summary

        return run_summary(self, result)


_SYNC_COMMANDS = ("gear_in", "gear_in_pos", "cam_in", "cam_out", "sync_out", "set_master_velocity")


class _Failed:
    """Handle of a command refused before it reached an axis (for example an infeasible gear-in-position)."""

    done = False
    aborted = False
    error = True
    error_id = -1

    def __init__(self, text: str) -> None:
        self.error_text = text


def _axis_kwargs(command: str, kwargs: dict[str, Any]) -> dict[str, Any]:
    """Machine-file words ("buffered", "shortest") -> the axis API's enums."""
    out = dict(kwargs)
    if isinstance(out.get("buffer_mode"), str):
        out["buffer_mode"] = BufferMode[out["buffer_mode"].upper()]
    if command == "move_absolute" and isinstance(out.get("direction"), str):
        out["direction"] = Direction[out["direction"].upper()]
    return out


# Compiled, the public names get this source's docstrings and annotations back (help(),
# inspect.signature); in plain Python this does nothing. See axisline/_docs.py.
from axisline._docs import document as _document  # noqa: E402

# hot: the scheduler's per-cycle tasks (bound methods taken from the class), left compiled-only
_document(globals(), hot={"AxisUnit": ("sample", "loop")})
