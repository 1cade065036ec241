"""The ACTUATE stage of each axis: what the controller hands its drive every cycle.

    s.add_task(f"{name}.actuate", actuator(unit, period), Stage.ACTUATE)   # machine.py

The plant's servo commanded by velocity, the common case, gets a closure with the servo typed
(`servo_actuator`): compiled (compiled_modules.txt), its calls are direct, with no attribute
lookup and no boxed float on the way; every other drive (analog input, stepper, a drive on
CANopen) goes through the generic one.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import TYPE_CHECKING

from .motion.axis import AxisState
from .plant.drives import ANALOG_LIMIT_VOLTS, ServoDrive, StepperDrive

if TYPE_CHECKING:
    from .machine import AxisUnit

__all__ = ["actuator", "servo_actuator"]

_DISABLED = AxisState.DISABLED


def actuator(unit: AxisUnit, period: float) -> Callable[[int], None]:
    """The ACTUATE task of an axis: the command to its drive (velocity, volts or the set point
    itself) and the drive's step over one period; the cycles it could not follow are noted."""
    axis, drive, dt = unit.axis, unit.drive, period
    step = drive.step
    stepper = isinstance(drive, StepperDrive)
    # the drive takes the set point itself: a stepper's pulses, a CiA 402 drive in CSP
    positioned = stepper or unit.config.drive.type == "cia402"
    analog = not positioned and unit.config.drive.command == "analog"
    volts_per_velocity = 1.0 / drive.velocity_per_volt if analog else 0.0
    velocity_per_volt = drive.velocity_per_volt if analog else 0.0
    top = math.inf if stepper else drive.max_velocity
    reach = min(top, ANALOG_LIMIT_VOLTS * velocity_per_volt) if analog else top
    unit.reach = reach

    if isinstance(drive, ServoDrive) and not analog and not positioned:
        return servo_actuator(unit, drive, period)

    def actuate(cycle: int) -> None:
        if (axis.state is not _DISABLED) is not drive.enabled:
            drive.enable(not drive.enabled)  # the amplifier follows the axis' power
        if analog:
            # the classic +-10 V interface: the amplifier's offset, drift and gain errors
            # apply; a device's analogue output (Machine.drive_by) or the axis' loop output
            u = unit.command_volts if unit.controller_volts else unit.velocity_output * volts_per_velocity
            drive.command_voltage(u)
            asked = u * velocity_per_volt  # nominal units/s
            # at or beyond +-10 V (a controller clips its own output there) or the speed limit
            if drive.saturated or u >= ANALOG_LIMIT_VOLTS or u <= -ANALOG_LIMIT_VOLTS or asked > reach or asked < -reach:
                unit.note_over(cycle, asked)
        elif positioned:
            # the drive follows the set point: a stepper's pulses (open loop), a CiA 402 drive's target
            drive.command_position(axis.command_position - axis.position_offset)  # axis -> plant frame
        else:
            v = unit.velocity_output
            drive.command_velocity(v)
            if v > drive.max_velocity or v < -drive.max_velocity:
                unit.note_over(cycle, v)
        step(dt)

    return actuate


def servo_actuator(unit: AxisUnit, servo: ServoDrive, period: float) -> Callable[[int], None]:
    """`actuator` for the plant's servo commanded by velocity (the common case), with the
    servo typed: compiled, its calls are direct. Same steps as the generic actuator."""
    axis, dt = unit.axis, period

    def actuate(cycle: int) -> None:
        if (axis.state is not _DISABLED) is not servo.enabled:
            servo.enable(not servo.enabled)  # the amplifier follows the axis' power
        v = unit.velocity_output
        servo.command_velocity(v)
        if v > servo.max_velocity or v < -servo.max_velocity:
            unit.note_over(cycle, v)
        servo.step(dt)

    return actuate
