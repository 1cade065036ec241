"""The simulated plant: drives, encoders, material, sensors and I/O the controller works on.

Everything is deterministic: no wall clock, randomness only from a seeded numpy Generator passed
in, exact integration wherever a closed-form solution exists. The plant never knows which
personality drives it.

One cycle of the machine, as the plant sees it::

    drive.step(dt); material.step(dt)             # physics over the cycle just ended
    encoder.sample(); sensor.sample(t_start, dt)  # inputs with sub-cycle event times
    io.sample()                                   # input image for the controller
    ... controller ...
    drive.command_voltage(u) / command_velocity(v) / command_microsteps(n)
"""

from .config import (
    AnalogIOConfig,
    DigitalIOConfig,
    EncoderConfig,
    MaterialConfig,
    MeasuringWheelConfig,
    PrintMarkConfig,
    ServoDriveConfig,
    SlipConfig,
    SpeedChangeConfig,
    StepperDriveConfig,
    SwitchConfig,
)
from .drives import ANALOG_LIMIT_VOLTS, Drive, ServoDrive, StepperDrive
from .encoder import IncrementalEncoder, MeasuringWheel
from .io import AnalogIO, DigitalIO
from .kinematics import Crossing, PositionSource, TracedSource
from .material import MaterialLine, SlipContact, SpeedChange
from .sensors import Edge, LimitSwitch, PositionSwitch, PrintMarks, PrintMarkSensor, ReferenceSwitch

__all__ = [
    "ANALOG_LIMIT_VOLTS",
    "AnalogIO",
    "AnalogIOConfig",
    "Crossing",
    "DigitalIO",
    "DigitalIOConfig",
    "Drive",
    "Edge",
    "EncoderConfig",
    "IncrementalEncoder",
    "LimitSwitch",
    "MaterialConfig",
    "MaterialLine",
    "MeasuringWheel",
    "MeasuringWheelConfig",
    "PositionSource",
    "PositionSwitch",
    "PrintMarkConfig",
    "PrintMarkSensor",
    "PrintMarks",
    "ReferenceSwitch",
    "ServoDrive",
    "ServoDriveConfig",
    "SlipConfig",
    "SlipContact",
    "SpeedChange",
    "SpeedChangeConfig",
    "StepperDrive",
    "StepperDriveConfig",
    "SwitchConfig",
    "TracedSource",
]
