"""Plant parameters as pydantic models: every field typed, ranged and explained.

Lengths are in the axis's user units (mm in the examples), times in seconds. Models are strict:
an unknown key, a value of the wrong type (a string for a number, a float for an integer) or a
value outside its range raises ``pydantic.ValidationError`` naming the field. Each model's
``build`` creates the runtime object; random features take the machine's seeded
``numpy.random.Generator``.
"""

from __future__ import annotations

from typing import Annotated, Literal

import numpy as np
from pydantic import BaseModel, ConfigDict, Field, StringConstraints, model_validator

from .actuators import Cylinder
from .drives import ServoDrive, StepperDrive
from .encoder import IncrementalEncoder, MeasuringWheel
from .io import AnalogIO, DigitalIO
from .material import MaterialLine, SlipContact, SpeedChange
from .sensors import LimitSwitch, PositionSwitch, PrintMarks, PrintMarkSensor, ReferenceSwitch

__all__ = [
    "AnalogIOConfig",
    "DigitalIOConfig",
    "EncoderConfig",
    "MaterialConfig",
    "MeasuringWheelConfig",
    "PrintMarkConfig",
    "ServoDriveConfig",
    "SlipConfig",
    "SpeedChangeConfig",
    "StepperDriveConfig",
    "SwitchConfig",
]

_POSITION_LIMIT = 1e9  # user units; far beyond any machine, but keeps numbers finite
_SPEED_LIMIT = 1e6  # user units/s

Position = Annotated[
    float,
    Field(ge=-_POSITION_LIMIT, le=_POSITION_LIMIT, description="Position in user units."),
]
IOName = Annotated[str, StringConstraints(min_length=1, max_length=64, pattern=r"^[A-Za-z0-9_.\-]+$")]


class PlantModel(BaseModel):
    """Base of the plant models: strict, no unknown keys, no infinities or NaN."""

    model_config = ConfigDict(
        extra="forbid", strict=True, allow_inf_nan=False, validate_assignment=True
    )


class ServoDriveConfig(PlantModel):
    """Servo amplifier and motor with a closed velocity loop (see :class:`ServoDrive`)."""

    model_config = ConfigDict(extra="forbid")

    loop: Literal["first_order", "second_order"] = Field(
        "first_order",
        description="Velocity loop model: first-order lag, or second-order (frequency, damping).",
    )
    time_constant: float = Field(
        0.002, gt=0.0, le=1.0, description="First-order velocity loop time constant, s."
    )
    natural_frequency: float = Field(
        600.0, gt=0.0, le=100_000.0, description="Second-order loop natural frequency, rad/s."
    )
    damping: float = Field(0.7, gt=0.0, le=10.0, description="Second-order loop damping ratio.")
    velocity_per_volt: float = Field(
        100.0, gt=0.0, le=_SPEED_LIMIT, description="Velocity per volt of analog command, units/s/V."
    )
    max_velocity: float | None = Field(
        None, gt=0.0, le=_SPEED_LIMIT, description="Motor speed limit, units/s (none: unlimited)."
    )
    max_acceleration: float | None = Field(
        None, gt=0.0, le=1e9, description="Drive acceleration limit, units/s^2 (none: unlimited)."
    )
    coast_time_constant: float = Field(
        0.1, ge=0.0, le=100.0, description="Coast-down time constant when disabled, s (0: stops)."
    )
    offset_volts: float = Field(
        0.0, ge=-10.0, le=10.0, description="Offset of the analog input, V (commissioning)."
    )
    drift_volts_per_second: float = Field(
        0.0, ge=-1.0, le=1.0, description="Drift of the analog input offset, V/s."
    )
    gain_factor: float = Field(
        1.0, ge=0.5, le=1.5, description="Gain error factor on velocity_per_volt (1 = exact)."
    )
    position: Position = Field(0.0, description="Initial motor position, user units.")

    def build(self) -> ServoDrive:
        return ServoDrive(**self.model_dump())


class StepperDriveConfig(PlantModel):
    """Stepper motor with a microstepping driver (see :class:`StepperDrive`)."""

    model_config = ConfigDict(extra="forbid")

    steps_per_unit: float = Field(
        200.0, gt=0.0, le=1e7, description="Full steps per user unit (e.g. 200/rev over the lead)."
    )
    microsteps: int = Field(64, ge=1, le=256, description="Microsteps per full step.")
    max_step_frequency: float = Field(
        200_000.0, gt=0.0, le=10_000_000.0, description="Most step pulses per second, Hz."
    )
    position_microsteps: int = Field(
        0, ge=-(2**53), le=2**53, description="Initial rotor position, microsteps."
    )

    def build(self) -> StepperDrive:
        return StepperDrive(**self.model_dump())


class EncoderConfig(PlantModel):
    """Incremental encoder on a drive or other position source."""

    model_config = ConfigDict(extra="forbid")

    lines_per_unit: float = Field(
        250.0, gt=0.0, le=1e9, description="Encoder lines per user unit."
    )
    multiplier: Literal[1, 2, 4] = Field(4, description="Edge evaluation: counts per line.")
    index_every_units: float | None = Field(
        None, gt=0.0, le=_POSITION_LIMIT, description="Index pulse spacing, user units (none: no index)."
    )
    index_offset: Position = Field(0.0, description="Position of index pulse 0, user units.")
    counter_bits: int | None = Field(
        None, ge=8, le=64, description="Counter width in bits (none: never wraps)."
    )
    direction: Literal[1, -1] = Field(1, description="Counting direction (-1: mounted mirrored).")

    def build(self, source: object) -> IncrementalEncoder:
        return IncrementalEncoder(source, **self.model_dump())


class MeasuringWheelConfig(PlantModel):
    """Measuring wheel with an encoder, rolling on the material with slip."""

    model_config = ConfigDict(extra="forbid")

    lines_per_revolution: int = Field(
        1000, ge=1, le=10_000_000, description="Encoder lines per wheel revolution."
    )
    circumference: float = Field(
        200.0, gt=0.0, le=100_000.0, description="Wheel circumference, user units (index once per turn)."
    )
    multiplier: Literal[1, 2, 4] = Field(4, description="Edge evaluation: counts per line.")
    slip: float = Field(
        0.0, ge=0.0, le=0.5, description="Mean slip: the wheel sees material travel * (1 - slip)."
    )
    slip_jitter: float = Field(
        0.0, ge=0.0, le=0.05, description="Standard deviation of the slip along the travel."
    )
    jitter_length: float = Field(
        10.0, gt=0.0, le=_POSITION_LIMIT, description="Travel over which one slip value holds, user units."
    )
    counter_bits: int | None = Field(
        None, ge=8, le=64, description="Counter width in bits (none: never wraps)."
    )
    direction: Literal[1, -1] = Field(1, description="Counting direction.")

    def build(self, material: object, rng: np.random.Generator | None = None) -> MeasuringWheel:
        return MeasuringWheel(
            material,
            self.lines_per_revolution / self.circumference,
            self.multiplier,
            slip=self.slip,
            slip_jitter=self.slip_jitter,
            jitter_length=self.jitter_length,
            rng=rng,
            circumference=self.circumference,
            counter_bits=self.counter_bits,
            direction=self.direction,
        )


class SlipConfig(PlantModel):
    """Slipping contact: material pulled by a feed roll (or any surface-driven follower)."""

    model_config = ConfigDict(extra="forbid")

    slip: float = Field(0.0, ge=0.0, le=0.5, description="Mean slip: follows travel * (1 - slip).")
    slip_jitter: float = Field(
        0.0, ge=0.0, le=0.05, description="Standard deviation of the slip along the travel."
    )
    jitter_length: float = Field(
        10.0, gt=0.0, le=_POSITION_LIMIT, description="Travel over which one slip value holds, user units."
    )

    def build(self, source: object, rng: np.random.Generator | None = None) -> SlipContact:
        return SlipContact(source, rng=rng, **self.model_dump())


class SpeedChangeConfig(PlantModel):
    """One entry of a material speed profile."""

    model_config = ConfigDict(extra="forbid")

    time: float = Field(ge=0.0, le=1e7, description="When the change starts, s.")
    speed: float = Field(ge=-_SPEED_LIMIT, le=_SPEED_LIMIT, description="New line speed, units/s.")
    acceleration: float = Field(
        gt=0.0, le=1e9, description="Ramp acceleration (magnitude), units/s^2."
    )


class MaterialConfig(PlantModel):
    """Material line (web, strip, profile) and its speed profile."""

    model_config = ConfigDict(extra="forbid")

    unit: str | None = Field(
        None, min_length=1, max_length=16, description="Length unit of the line (none: the first axis' unit)."
    )
    speed: float = Field(
        0.0, ge=-_SPEED_LIMIT, le=_SPEED_LIMIT, description="Initial line speed, units/s."
    )
    position: Position = Field(0.0, description="Initial material position, user units.")
    profile: list[SpeedChangeConfig] = Field(
        default_factory=list, max_length=10_000, description="Speed changes over time, applied in time order."
    )

    def build(self) -> MaterialLine:
        profile = [SpeedChange(c.time, c.speed, c.acceleration) for c in self.profile]
        return MaterialLine(profile, speed=self.speed, position=self.position)


class PrintMarkConfig(PlantModel):
    """Print marks on the material and the sensor that sees them."""

    model_config = ConfigDict(extra="forbid")

    sensor_position: Position = Field(0.0, description="Sensor position along the line, user units.")
    width: float = Field(5.0, gt=0.0, le=100_000.0, description="Mark length along the material.")
    pitch: float | None = Field(
        500.0, gt=0.0, le=_POSITION_LIMIT, description="Distance between marks, user units."
    )
    first: Position = Field(0.0, description="Position of the first mark on the material.")
    jitter: float = Field(
        0.0, ge=0.0, le=100_000.0, description="Printing jitter, standard deviation, user units."
    )
    missing_probability: float = Field(
        0.0, ge=0.0, le=1.0, description="Probability that a mark is missing."
    )
    count: int | None = Field(None, ge=0, le=10**9, description="Number of marks (none: endless).")
    positions: list[Position] | None = Field(
        None, max_length=1_000_000, description="Explicit mark positions instead of a pitch."
    )
    invert: bool = Field(False, description="Output 0 while a mark is under the sensor.")

    @model_validator(mode="after")
    def _layout(self) -> PrintMarkConfig:
        if self.positions is not None:
            if "pitch" in self.model_fields_set and self.pitch is not None:
                raise ValueError("give either pitch or positions, not both")
            # the rule of PrintMarks: checked here, so a file that would fail to build is refused
            ordered = sorted(self.positions)
            for a, b in zip(ordered, ordered[1:]):
                if b - a <= self.width:
                    raise ValueError(
                        f"positions: the marks at {a!r} and {b!r} overlap (width {self.width!r}; "
                        "allowed: marks more than a width apart)"
                    )
        elif self.pitch is None:
            raise ValueError("give pitch or positions")
        elif self.width + 6.0 * self.jitter >= self.pitch:
            raise ValueError(
                f"width + 6 * jitter ({self.width + 6.0 * self.jitter}) must be less than "
                f"pitch ({self.pitch}), or marks overlap"
            )
        return self

    def build(self, material: object, rng: np.random.Generator | None = None) -> PrintMarkSensor:
        if self.positions is not None:
            marks = PrintMarks(width=self.width, positions=self.positions)
        else:
            marks = PrintMarks(
                width=self.width,
                pitch=self.pitch,
                first=self.first,
                jitter=self.jitter,
                missing_probability=self.missing_probability,
                count=self.count,
                rng=rng if (self.jitter > 0.0 or self.missing_probability > 0.0) else None,
            )
        return PrintMarkSensor(
            material, marks, sensor_position=self.sensor_position, invert=self.invert
        )


class SwitchConfig(PlantModel):
    """Reference (home) cam or limit switch on an axis."""

    model_config = ConfigDict(extra="forbid")

    kind: Literal["reference", "limit"] = Field(
        "reference", description="reference: a cam of `width`; limit: actuated beyond `position`."
    )
    position: Position = Field(0.0, description="Switching position, user units.")
    width: float = Field(
        10.0, gt=0.0, le=_POSITION_LIMIT, description="Cam length of a reference switch, user units."
    )
    direction: Literal[1, -1] = Field(
        1, description="Limit switch side: +1 actuated above position, -1 below."
    )
    hysteresis: float = Field(
        0.0, ge=0.0, le=100_000.0, description="Extra travel before the switch releases, user units."
    )
    invert: bool = Field(False, description="Normally closed contact: output 0 when actuated.")

    def build(self, source: object) -> PositionSwitch:
        if self.kind == "reference":
            return ReferenceSwitch(
                source, self.position, self.width, hysteresis=self.hysteresis, invert=self.invert
            )
        return LimitSwitch(
            source, self.position, self.direction, hysteresis=self.hysteresis, invert=self.invert
        )


class DigitalIOConfig(PlantModel):
    """Names of the digital inputs and outputs."""

    model_config = ConfigDict(extra="forbid")

    inputs: list[IOName] = Field(default_factory=list, max_length=4096, description="Input names.")
    outputs: list[IOName] = Field(default_factory=list, max_length=4096, description="Output names.")

    @model_validator(mode="after")
    def _unique(self) -> DigitalIOConfig:
        _check_unique(self.inputs + self.outputs)
        return self

    def build(self) -> DigitalIO:
        return DigitalIO(self.inputs, self.outputs)


class AnalogIOConfig(PlantModel):
    """Analog channels in volts."""

    model_config = ConfigDict(extra="forbid")

    inputs: list[IOName] = Field(default_factory=list, max_length=256, description="Input names.")
    outputs: list[IOName] = Field(default_factory=list, max_length=256, description="Output names.")
    limit: float = Field(10.0, gt=0.0, le=10.0, description="Range +-limit, V.")
    input_bits: int | None = Field(
        None, ge=8, le=24, description="Input converter resolution, bits (none: exact)."
    )
    output_bits: int | None = Field(
        None, ge=8, le=24, description="Output converter resolution, bits (none: exact)."
    )

    @model_validator(mode="after")
    def _unique(self) -> AnalogIOConfig:
        _check_unique(self.inputs + self.outputs)
        return self

    def build(self) -> AnalogIO:
        return AnalogIO(
            self.inputs,
            self.outputs,
            limit=self.limit,
            input_bits=self.input_bits,
            output_bits=self.output_bits,
        )


def _check_unique(names: list[str]) -> None:
    seen: set[str] = set()
    for name in names:
        if name in seen:
            raise ValueError(f"I/O name {name!r} is used twice")
        seen.add(name)


class ActuatorConfig(PlantModel):
    """A cylinder on a valve output, with end switches (a press ram, a clamp): `Cylinder`."""

    name: IOName = Field(description="Name of the actuator (for messages).")
    valve: IOName = Field(description="The [io] output that drives it: on = extend.")
    retracted: IOName | None = Field(None, description="[io] input closed while it is retracted (at home).")
    extended: IOName | None = Field(None, description="[io] input closed while it is fully extended.")
    extend_time: float = Field(gt=0.0, le=3600.0, description="Travel from retracted to extended, s.")
    retract_time: float = Field(gt=0.0, le=3600.0, description="Travel from extended to retracted, s.")

    def build(self) -> Cylinder:
        return Cylinder(self.extend_time, self.retract_time)

