"""The scripted job of a machine file: a sequence of axis commands, dwells and waits.

It runs in the LOGIC stage, so every command it gives takes effect at a cycle
boundary exactly as a command from a fieldbus would, and a run is reproducible to
the cycle. A step either waits for its command to be done ("done"), or lets the
next step start in the following cycle ("none", for moves on several axes at once).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Literal

from pydantic import BaseModel, ConfigDict, Field

# axis commands a job step may give, with the keyword arguments each takes
COMMANDS: dict[str, tuple[str, ...]] = {
    "power": ("on",),
    "move_absolute": ("position", "velocity", "acceleration", "deceleration", "jerk", "buffer_mode", "direction"),
    "move_relative": ("distance", "velocity", "acceleration", "deceleration", "jerk", "buffer_mode"),
    "move_additive": ("distance", "velocity", "acceleration", "deceleration", "jerk", "buffer_mode"),
    "move_velocity": ("velocity", "acceleration", "deceleration", "jerk", "buffer_mode"),
    "halt": ("deceleration",),
    "stop": ("deceleration",),
    "stop_release": (),
    "set_position": ("position", "relative"),
    "jog": ("direction",),
    "reset": (),
    "home": ("method", "position", "velocity", "direction", "switch", "acceleration", "max_distance"),
    # couplings (sync_setup.py)
    "gear_in": ("master", "numerator", "denominator"),
    "gear_in_pos": ("master", "numerator", "denominator", "master_sync_position", "slave_sync_position"),
    "cam_in": ("master", "cam", "coupling", "synchronous", "master_offset"),
    "cam_out": ("decoupling", "braking", "standstill"),
    "sync_out": ("deceleration",),
    "set_master_velocity": ("master", "velocity"),  # a step with master = ..., no axis
}

# commands given to a master rather than an axis
MASTER_COMMANDS = ("set_master_velocity",)

# the arguments a command cannot do without (the axis API has no default for them): a step
# without one is a bad machine file, found by `check`, not a crash in the middle of `run`
REQUIRED: dict[str, tuple[str, ...]] = {
    "power": ("on",),
    "move_absolute": ("position",),
    "move_relative": ("distance",),
    "move_additive": ("distance",),
    "move_velocity": ("velocity",),
    "set_position": ("position",),
    "jog": ("direction",),
    "gear_in": ("master", "numerator", "denominator"),
    "gear_in_pos": ("master", "numerator", "denominator", "master_sync_position", "slave_sync_position"),
    "cam_in": ("master", "cam"),
    "cam_out": ("decoupling", "braking", "standstill"),
    "set_master_velocity": ("master", "velocity"),
}

# `direction` means a different thing to each command that takes it
DIRECTIONS: dict[str, tuple[Any, ...]] = {
    "move_absolute": ("shortest", "positive", "negative", "current"),  # the way to the target (modulo axes)
    "jog": (-1, 0, 1),  # the jog key pressed
    "home": (-1, 1, "negative", "positive"),  # the search direction
}

# positions, distances, velocities and master positions of a step: finite (the model refuses
# NaN and infinities) and within the range every other length of the machine file keeps to
_SPAN = 1e9


_ARGUMENTS = ("master", "on", "position", "distance", "velocity", "acceleration", "deceleration", "jerk", "buffer_mode",
              "direction", "relative", "method", "switch", "max_distance", "numerator", "denominator",
              "master_sync_position", "slave_sync_position", "cam", "coupling", "synchronous", "master_offset",
              "decoupling", "braking", "standstill")


class JobStep(BaseModel):
    """One step: an axis command, or a dwell when `dwell` is given without a command."""

    model_config = ConfigDict(extra="forbid", allow_inf_nan=False)

    axis: str | None = Field(None, max_length=64, description="axis the command goes to")
    command: Literal[tuple(COMMANDS)] | None = Field(None, description="axis command")  # type: ignore[valid-type]
    wait: Literal["done", "none"] = Field("done", description="wait for the command to be done before the next step")
    dwell: float | None = Field(None, ge=0.0, le=86400.0, description="seconds to wait (after the command, if any)")
    on: bool | None = None
    position: float | None = Field(None, ge=-_SPAN, le=_SPAN)
    distance: float | None = Field(None, ge=-_SPAN, le=_SPAN)
    velocity: float | None = Field(None, ge=-_SPAN, le=_SPAN)
    acceleration: float | None = Field(None, gt=0.0, le=1e12)
    deceleration: float | None = Field(None, gt=0.0, le=1e12)
    jerk: float | None = Field(None, gt=0.0, le=1e15)
    buffer_mode: Literal["aborting", "buffered"] | None = None
    direction: Literal["shortest", "positive", "negative", "current", -1, 0, 1] | None = None
    relative: bool | None = None
    method: Literal["direct", "switch"] | None = Field(None, description="homing: set the position here, or search a switch")
    switch: str | None = Field(None, max_length=64, description="homing: the axis' switch to search")
    max_distance: float | None = Field(None, gt=0.0, le=_SPAN, description="homing: give up after this search distance")
    master: str | None = Field(None, max_length=64, description="couplings: the master (set_master_velocity: the master addressed)")
    numerator: int | None = Field(None, ge=-(2**62), le=2**62, description="gear: slave counts ...")
    denominator: int | None = Field(None, ge=1, le=2**62, description="gear: ... per master counts")
    master_sync_position: float | None = Field(None, ge=-_SPAN, le=_SPAN, description="gear_in_pos: master position of synchronism")
    slave_sync_position: float | None = Field(None, ge=-_SPAN, le=_SPAN, description="gear_in_pos: slave position at that master position")
    cam: str | None = Field(None, max_length=64, description="cam_in: the cam")
    coupling: float | None = Field(None, ge=-_SPAN, le=_SPAN, description="cam_in: coupling position M_E in the master cycle")
    synchronous: float | None = Field(None, ge=-_SPAN, le=_SPAN, description="cam_in: synchronous position M_S in the master cycle")
    master_offset: float | None = Field(None, ge=-_SPAN, le=_SPAN, description="cam_in: master position of curve position 0")
    decoupling: float | None = Field(None, ge=-_SPAN, le=_SPAN, description="cam_out: decoupling position M_A in the master cycle")
    braking: float | None = Field(None, ge=-_SPAN, le=_SPAN, description="cam_out: braking position M_B in the master cycle")
    standstill: float | None = Field(None, ge=-_SPAN, le=_SPAN, description="cam_out: standstill position S_0 of the slave")

    def arguments(self) -> dict[str, Any]:
        """Keyword arguments for the axis command (only those given)."""
        allowed = COMMANDS[self.command] if self.command else ()
        given = {k: getattr(self, k) for k in allowed if getattr(self, k) is not None}
        extra = [
            k
            for k in _ARGUMENTS
            if getattr(self, k) is not None and k not in allowed
        ]
        if extra:
            raise ValueError(f"job step {self.command!r} does not take {', '.join(extra)} (takes: {', '.join(allowed) or 'nothing'})")
        if "direction" in given and given["direction"] not in DIRECTIONS[self.command or ""]:
            allowed_directions = ", ".join(repr(d) for d in DIRECTIONS[self.command or ""])
            raise ValueError(f"{self.command} direction = {given['direction']!r} (allowed: {allowed_directions})")
        missing = [k for k in REQUIRED.get(self.command or "", ()) if k not in given]
        if missing:
            raise ValueError(f"{self.command} needs {', '.join(missing)} (takes: {', '.join(allowed)})")
        return given


class JobConfig(BaseModel):
    model_config = ConfigDict(extra="forbid")

    repeat: int = Field(1, ge=1, le=1_000_000, description="how many times the steps run")
    steps: list[JobStep] = Field(default_factory=list, max_length=10_000)


@dataclass
class JobEvent:
    t: float
    step: int
    text: str


@dataclass
class JobRunner:
    """Executes a JobConfig against the machine's axes, one decision per cycle."""

    config: JobConfig
    period: float
    issue: Any  # callable(axis, command, kwargs) -> handle; the machine's command path
    index: int = 0
    round: int = 0
    finished: bool = False
    failed: str | None = None
    events: list[JobEvent] = field(default_factory=list)
    _started: bool = False
    _handle: Any = None
    _dwell_until: int | None = None

    def __post_init__(self) -> None:
        if not self.config.steps:
            self.finished = True

    def _fail(self, cycle: int, text: str) -> None:
        self.failed = f"step {self.index + 1}: {text}"
        self.events.append(JobEvent(cycle * self.period, self.index, self.failed))
        self.finished = True

    @staticmethod
    def _label(step: JobStep) -> str:
        return f"{step.axis or step.master}.{step.command}"

    def tick(self, cycle: int) -> None:
        """Advance the job; at most one new command per cycle."""
        if self.finished:
            return
        step = self.config.steps[self.index]
        if not self._started:
            self._started = True
            if step.command is not None:
                h = self.issue(step.axis, step.command, step.arguments())
                self.events.append(JobEvent(cycle * self.period, self.index, f"{self._label(step)}"))
                if getattr(h, "error", False):  # rejected at once
                    self._fail(cycle, f"{self._label(step)}: error {h.error_id}: {h.error_text}")
                    return
                self._handle = h if step.wait == "done" else None
        h = self._handle
        if h is not None:
            if getattr(h, "error", False):
                self._fail(cycle, f"{self._label(step)}: error {h.error_id}: {h.error_text}")
                return
            if getattr(h, "aborted", False):
                self._fail(cycle, f"{self._label(step)} was aborted")
                return
            # a velocity command is "done" for the job once it runs at its velocity
            if not (getattr(h, "done", False) or getattr(h, "in_velocity", False)):
                return
            self._handle = None
        if step.dwell:
            if self._dwell_until is None:
                self._dwell_until = cycle + round(step.dwell / self.period)
            if cycle < self._dwell_until:
                return
        self._started = False
        self._dwell_until = None
        self.index += 1
        if self.index >= len(self.config.steps):
            self.round += 1
            self.index = 0
            if self.round >= self.config.repeat:
                self.finished = True
