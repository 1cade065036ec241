"""One CAN bus as the controller sees it: canopen's Network, the SYNC of each cycle, axisline's heartbeat.

All CiA 402 axes whose [axis.drive] names the same interface and channel share one bus. Each
cycle every drive on it writes its RPDOs in its ACTUATE task; when the last of them has, the
bus sends one SYNC and waits for every drive's TPDOs (see DriveMember.await_tpdos), so the
actual values are in before the next cycle's INPUTS.

Decisions
1. Issue 20 "SYNC every cycle": the SYNC goes out at the end of the cycle's ACTUATE stage, after
   every drive's RPDO, and the controller waits for the drives' TPDOs before the cycle ends
   (up to response_timeout). A drive takes the target at the SYNC and reports the position it
   reaches; the next cycle's position loop reads it, one cycle of transport as with the
   embedded plant (the drive is stepped by the same T). The simulated drive's trace therefore
   agrees with the embedded plant's (tests/drives/test_positioning.py).
2. A drive that leaves a SYNC unanswered is waited for response_timeout; after three such SYNCs
   in a row, or its heartbeat timeout, it is lost (adapter.py, decision 3) and not waited for
   again: a dead node stalls the cycle at most three times response_timeout, once
   (tests/drives/test_faults.py::test_heartbeat_loss_stops_the_others).
"""

from __future__ import annotations

import atexit
import weakref
from typing import Any, Protocol

import can
import canopen

from ..configerrors import ConfigError

__all__ = ["CanBus", "DriveError", "open_network"]


class DriveError(ConfigError):
    """A drive that cannot be brought up: printed like a bad machine file (what, value, why)."""


class DriveMember(Protocol):
    def before_sync(self) -> None: ...

    def await_tpdos(self) -> None: ...

    def close(self) -> None: ...


def open_network(interface: str, channel: str, bitrate: int, where: str) -> canopen.Network:
    """canopen's Network connected to the bus, or a DriveError naming interface and channel."""
    network = canopen.Network()
    # the receive thread looks up this often when the bus is idle: leaving the bus waits for it
    network.NOTIFIER_CYCLE = 0.05
    try:
        network.connect(interface=interface, channel=channel, bitrate=bitrate)
    except (can.CanError, OSError, ValueError, ImportError, NotImplementedError) as e:
        raise DriveError(where, [
            f"CAN interface = {interface!r}, channel = {channel!r}, bitrate = {bitrate}: cannot open the bus ({e})"
        ]) from None
    return network


class CanBus:
    """The controller's side of one CAN bus."""

    def __init__(self, interface: str, channel: str, bitrate: int, *, controller_id: int, where: str) -> None:
        self.interface = interface
        self.channel = channel
        self.bitrate = bitrate
        self.controller_id = controller_id
        self.network = open_network(interface, channel, bitrate, where)
        self.members: list[Any] = []
        self.simulated: list[Any] = []  # simulated drives on this (virtual) bus, closed with it
        self._stepped = 0
        self._heartbeat: Any = None
        self.closed = False
        _OPEN.add(self)

    @property
    def key(self) -> tuple[str, str]:
        return (self.interface, self.channel)

    @property
    def name(self) -> str:
        return f"{self.interface}:{self.channel}"

    def start_heartbeat(self, period_ms: int) -> None:
        """axisline's own heartbeat (NMT state OPERATIONAL), which the drives' consumers watch."""
        if self._heartbeat is None:
            self._heartbeat = self.network.send_periodic(0x700 + self.controller_id, [0x05], period_ms / 1000.0)

    def stop_heartbeat(self) -> None:
        """The controller "goes away" for the drives: their heartbeat consumers will quick-stop them."""
        if self._heartbeat is not None:
            self._heartbeat.stop()
            self._heartbeat = None

    def stepped(self) -> None:
        """A member has written this cycle's RPDOs; after the last one, SYNC and collect."""
        self._stepped += 1
        if self._stepped >= len(self.members):
            self._stepped = 0
            self.sync()

    def sync(self) -> None:
        for m in self.members:
            m.before_sync()
        self.network.sync.transmit()
        for m in self.members:
            m.await_tpdos()

    def close(self) -> None:
        """Leave the bus: members first (their quick stop), then the heartbeat and the network."""
        if self.closed:
            return
        self.closed = True
        for m in self.members:
            m.close()
        self.stop_heartbeat()
        try:
            self.network.disconnect()
        except (can.CanError, OSError):  # a bus already gone: nothing left to release
            pass
        for sim in self.simulated:
            sim.close()
        _OPEN.discard(self)


_OPEN: "weakref.WeakSet[CanBus]" = weakref.WeakSet()


@atexit.register
def _close_all() -> None:
    """At exit the buses are left in order (drives told to quick-stop, threads ended)."""
    for bus in list(_OPEN):
        bus.close()
