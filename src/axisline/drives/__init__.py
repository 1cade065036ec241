"""Real drives: CiA 402 servo drives over CANopen, interchangeable with the simulated plant (issue 20).

An axis whose machine file says `[axis.drive] type = "cia402"` gets, instead of the plant's
drive model, a CANopen drive behind the same drive interface (set point in, actual position
and state out); the axis, its profiles, gears, cams and the personalities above it do not
change. canopen and python-can do all of the protocol; this package holds no CAN code of its own.

    config      the [axis.drive] table (no CAN imports: checking a file needs no bus)
    cia402      controlword / statusword / error-code words both sides use
    bus         one CAN bus: canopen's Network, the SYNC of each cycle, axisline's heartbeat
    adapter     one drive: PDOs each cycle, the CiA 402 state machine, faults -> the axis
    wiring      the one call machine.py makes for such an axis
    simulated   a CiA 402 drive (canopen LocalNode) around the plant's servo, for the virtual bus
    scan        `axisline drives scan`: the nodes on a bus with identity and state
    cli         the `drives` sub-command
    bench       cost of a CANopen axis per cycle
    eds/        the generic CiA 402 EDS shipped with axisline

docs/drives.md tells how to wire a real drive.
"""

from __future__ import annotations

from typing import Any

__all__ = ["attach", "close_drives"]


def attach(machine: Any, entry: Any, axis: Any) -> Any:
    """The started CANopen drive of a cia402 axis (drives/wiring.py); imports canopen on first use."""
    from .wiring import attach as _attach

    return _attach(machine, entry, axis)


def close_drives(machine: Any) -> None:
    """Leave the machine's CAN buses (drives quick-stopped, receive threads ended)."""
    from .wiring import close_drives as _close

    _close(machine)
