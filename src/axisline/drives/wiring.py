"""Wiring a CiA 402 axis into the machine: bus, simulated drive (virtual bus), adapter, supervision.

`attach(machine, entry, axis)` is the one call machine.py makes for an axis whose
[axis.drive] type is "cia402"; it returns the drive the machine actuates like any other.

Decisions
1. One controller per bus and process: the axes of one machine on the same interface and
   channel share one canopen Network (one SYNC a cycle, one heartbeat); a machine built later
   in the same process on that bus (a finished `run` whose bus stayed open, a file loaded
   again) first closes the earlier one, so two controllers never answer for the same node
   (tests/test_machine_file_faults.py runs the example many times in one process).
2. A start that fails (no answer, a refused EDS) closes the bus it opened: no receive thread or
   heartbeat outlives the error (tests/drives/test_faults.py::test_a_refused_start_leaves_no_bus_open).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from ..configerrors import ConfigError
from ..kernel import Stage
from ..motion.axis import AxisState
from .adapter import Cia402Drive
from .bus import _OPEN, CanBus
from .config import Cia402Entry

__all__ = ["attach", "close_drives", "simulated_drive"]

_IDLE = (AxisState.STANDSTILL, AxisState.DISABLED, AxisState.ERROR_STOP)


def attach(machine: Any, entry: Any, axis: Any) -> Cia402Drive:
    """The CANopen drive of `entry` (an AxisEntry with a Cia402Entry drive), started."""
    cfg: Cia402Entry = entry.drive
    source = machine.source or "<machine>"
    where = f"{source}: axis {entry.name!r}"
    base = Path(machine.source).parent if machine.source else Path.cwd()
    eds = cfg.eds_path(base)
    if not eds.is_file():
        raise ConfigError(source, [f"axis {entry.name!r}: drive.eds = {str(cfg.eds)!r}: no such file ({eds})"])
    bus = None
    for name, unit in machine.units.items():
        other = unit.drive
        if isinstance(other, Cia402Drive) and other.bus.key == cfg.bus_key:
            if other.node_id == cfg.node_id:
                raise ConfigError(source, [
                    f"axis {entry.name!r}: drive.node_id = {cfg.node_id} is axis {name!r}'s drive on {other.bus.name} already (one node id per drive)"
                ])
            if cfg.node_id == other.bus.controller_id or other.node_id == cfg.controller_id:
                raise ConfigError(source, [f"axis {entry.name!r}: drive.node_id = {cfg.node_id} is the controller's id on {other.bus.name}"])
            bus = other.bus
    counts = entry.counts_per_unit
    if bus is None:
        # one controller per bus: an earlier machine of this process on it is left first
        # (a finished `run`, a machine file loaded again); its simulated drives go with it
        for stale in [b for b in list(_OPEN) if b.key == cfg.bus_key]:
            stale.close()
        bus = CanBus(cfg.interface, cfg.channel, cfg.bitrate, controller_id=cfg.controller_id, where=where)
    try:
        if cfg.simulated is not None:
            bus.simulated.append(simulated_drive(entry, eds))
        drive = Cia402Drive(cfg, bus, axis, counts_per_unit=counts, eds=str(eds), where=where)
        bus.members.append(drive)
        drive.start(machine.clock.period_us)
        bus.start_heartbeat(min(100, max(10, cfg.controller_timeout_ms // 3)))
    except BaseException:
        if not any(isinstance(u.drive, Cia402Drive) and u.drive.bus is bus for u in machine.units.values()):
            bus.close()  # nobody else uses it: leave no threads behind a refused start
        raise

    def lost(drive: Cia402Drive, text: str) -> None:
        """A drive is gone: every other axis stops with its own stop ramp."""
        for name, unit in machine.units.items():
            ax = unit.axis
            if unit.drive is not drive and ax.state not in _IDLE:
                ax.stop()
                ax.stop_release()  # back to Standstill once at rest
        machine.faults.append(f"t={machine.clock.cycle * machine.period:.4f} s {text}")

    drive.on_lost = lost
    machine.scheduler.add_task(f"{entry.name}.drive", drive.watch, Stage.INPUTS)
    return drive


def simulated_drive(entry: Any, eds: Path) -> Any:
    """The simulated CiA 402 drive of an axis entry: its servo, its encoder, the axis' loop gains."""
    from ..plant.config import EncoderConfig
    from .simulated import SimulatedDrive

    cfg: Cia402Entry = entry.drive
    assert cfg.simulated is not None
    servo = cfg.simulated.build()
    if entry.encoder is not None:
        encoder = entry.encoder.build(servo)
        if abs(encoder.counts_per_unit - entry.counts_per_unit) > 1e-9 * entry.counts_per_unit:
            raise ConfigError("<machine>", [
                f"axis {entry.name!r}: [axis.encoder] counts {encoder.counts_per_unit:g} per unit but counts_per_unit = "
                f"{entry.counts_per_unit:g}: a CiA 402 drive reports its encoder's increments (make them equal)"
            ])
    else:
        encoder = EncoderConfig(lines_per_unit=entry.counts_per_unit / 4.0, multiplier=4).build(servo)
    return SimulatedDrive(
        cfg.node_id, servo, encoder, kv=entry.kv, feed_forward=entry.velocity_feed_forward,
        interface=cfg.interface, channel=cfg.channel, bitrate=cfg.bitrate, eds=eds,
    )


def close_drives(machine: Any) -> None:
    """Leave every CAN bus of the machine (drives quick-stopped, threads ended)."""
    for unit in machine.units.values():
        if isinstance(unit.drive, Cia402Drive):
            unit.drive.bus.close()
