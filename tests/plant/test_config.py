"""Plant configuration: typed, ranged, no unknown keys; builds the runtime objects."""

from __future__ import annotations

import numpy as np
import pytest
from pydantic import ValidationError

from axisline.plant import (
    AnalogIOConfig,
    DigitalIOConfig,
    EncoderConfig,
    IncrementalEncoder,
    LimitSwitch,
    MaterialConfig,
    MeasuringWheelConfig,
    PrintMarkConfig,
    ReferenceSwitch,
    ServoDrive,
    ServoDriveConfig,
    StepperDrive,
    StepperDriveConfig,
    SwitchConfig,
)

MODELS = [
    ServoDriveConfig, StepperDriveConfig, EncoderConfig, MeasuringWheelConfig, MaterialConfig,
    PrintMarkConfig, SwitchConfig, DigitalIOConfig, AnalogIOConfig,
]


@pytest.mark.parametrize("model", MODELS)
def test_every_field_is_described_and_unknown_keys_are_refused(model):
    for name, field in model.model_fields.items():
        assert field.description, f"{model.__name__}.{name} has no description"
    with pytest.raises(ValidationError, match="extra"):
        model.model_validate({"no_such_key": 1})


@pytest.mark.parametrize(
    ("model", "data", "field"),
    [
        (ServoDriveConfig, {"time_constant": 0.0}, "time_constant"),
        (ServoDriveConfig, {"time_constant": "fast"}, "time_constant"),
        (ServoDriveConfig, {"loop": "third_order"}, "loop"),
        (ServoDriveConfig, {"offset_volts": 11.0}, "offset_volts"),
        (ServoDriveConfig, {"damping": float("nan")}, "damping"),
        (StepperDriveConfig, {"microsteps": 64.0}, "microsteps"),
        (StepperDriveConfig, {"microsteps": 512}, "microsteps"),
        (EncoderConfig, {"multiplier": 3}, "multiplier"),
        (EncoderConfig, {"counter_bits": 4}, "counter_bits"),
        (MaterialConfig, {"profile": [{"time": 1.0, "speed": 2.0, "acceleration": -1.0}]},
         "profile.0.acceleration"),
        (PrintMarkConfig, {"missing_probability": 1.5}, "missing_probability"),
        (MeasuringWheelConfig, {"slip": 0.9}, "slip"),
        (DigitalIOConfig, {"inputs": ["ok", ""]}, "inputs.1"),
    ],
)
def test_wrong_type_or_range_names_the_field(model, data, field):
    with pytest.raises(ValidationError) as info:
        model.model_validate(data)
    assert field in {".".join(map(str, e["loc"])) for e in info.value.errors()}


def test_cross_field_rules():
    with pytest.raises(ValidationError, match="overlap"):
        PrintMarkConfig.model_validate({"pitch": 10.0, "width": 5.0, "jitter": 1.0})
    with pytest.raises(ValidationError, match="either pitch or positions"):
        PrintMarkConfig.model_validate({"pitch": 10.0, "positions": [1.0]})
    with pytest.raises(ValidationError, match="twice"):
        DigitalIOConfig.model_validate({"inputs": ["a"], "outputs": ["a"]})


def test_defaults_validate_and_build_runtime_objects():
    rng = np.random.default_rng(1)
    servo = ServoDriveConfig.model_validate({"loop": "second_order", "max_velocity": 500}).build()
    assert isinstance(servo, ServoDrive) and servo.loop == "second_order"
    assert servo.max_velocity == 500.0
    assert isinstance(StepperDriveConfig().build(), StepperDrive)
    encoder = EncoderConfig(lines_per_unit=100.0, multiplier=2).build(servo)
    assert isinstance(encoder, IncrementalEncoder) and encoder.counts_per_unit == 200.0
    line = MaterialConfig.model_validate(
        {"speed": 1.0, "profile": [{"time": 0.5, "speed": 2.0, "acceleration": 10.0}]}
    ).build()
    assert line.profile[0].speed == 2.0
    wheel = MeasuringWheelConfig(slip=0.01, slip_jitter=0.001).build(line, rng)
    assert wheel.lines_per_unit == 1000 / 200.0
    sensor = PrintMarkConfig(jitter=1.0).build(line, rng)
    assert sensor.marks.pitch == 500.0
    assert PrintMarkConfig(positions=[30.0, 10.0]).build(line).marks.leading_edge(0) == 10.0
    assert isinstance(SwitchConfig().build(servo), ReferenceSwitch)
    assert isinstance(SwitchConfig(kind="limit", direction=-1).build(servo), LimitSwitch)
    io = DigitalIOConfig(inputs=["I1.01.0"], outputs=["Q1.01.0"]).build()
    assert io.inputs == ("I1.01.0",)
    assert AnalogIOConfig(outputs=["axis1"]).build().write("axis1", 20.0) == 10.0
