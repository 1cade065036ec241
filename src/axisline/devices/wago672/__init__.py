"""WAGO 750-672 stepper controller personality (manual: WAGO-I/O-SYSTEM 750, 750-672, V1.0.5; spec: wago.md).

    from axisline.devices.wago672 import Wago672, ConfigTable
    dev = Wago672(axis, inputs={"Input1": True})

Modules: image (12-byte process image), config_table (512-byte configuration), units (scaling),
errors (error table, error memory, LED blink code), bits (bit field seam), trajectory (ramp
types on the kernel's profile generator), referencing (reference runs), thermal (current phases,
overcurrent model), device (the module: power-on, process image, the tick, errors) with its
parts modes (mode selection, Start, positioning, speed control, PreCalc, referencing, jog),
commands (DRIVE_COMMAND and run-program move commands), watches (limits, end of motions, flags,
source bits), drive (output stage, axis hand-over, STOP ramps, scaling, current, brake,
errors), state (the state they share, and why the parts are a chain of layers), signals (the
consumed signals of a tick), opcodes (move-command opcodes, mailbox return codes) and
seams (mailbox, run program, position table, input wiring); their docstrings list the decisions
taken on the spec's [AMBIGUOUS]/[CONFLICT]/[RECONSTRUCTED] points (D1 .. D26). Around the
module: coupler (Modbus register map, watchdog), personality (the machine file's [device]),
plc and plcscript (the [[device.plc]] steps that stand in for the PLC in `axisline run`, and
their runner), runreport (the
run's headline and report section), client (the PLC side over Modbus).
"""

from axisline.devices.wago672.bits import Bit, BitTable
from axisline.devices.wago672.config_table import ConfigTable, ConfigValueError
from axisline.devices.wago672.device import RC, MailboxHandler, NoMailbox, Opcode, RunProgram, Wago672
from axisline.devices.wago672.errors import ERRORS, ErrorMemory, WagoError
from axisline.devices.wago672.image import InputImage, OutputImage

__all__ = [
    "Wago672",
    "ConfigTable",
    "ConfigValueError",
    "Bit",
    "BitTable",
    "ERRORS",
    "ErrorMemory",
    "WagoError",
    "InputImage",
    "OutputImage",
    "Opcode",
    "RC",
    "MailboxHandler",
    "NoMailbox",
    "RunProgram",
]
