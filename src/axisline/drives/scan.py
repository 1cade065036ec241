"""`axisline drives scan`: which CANopen nodes are on a bus, with identity and state.

canopen's NodeScanner asks every node id (an SDO read of 0x1000) and notes who answers, and any
node heard meanwhile (heartbeat, EMCY, PDO); each found node is then read by SDO: device type,
identity (0x1018), device name (0x1008), the CiA 402 statusword (0x6041, drives only) and its
NMT state from its heartbeat, if it sends one.
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from pathlib import Path

import canopen
from canopen.sdo import SdoAbortedError, SdoCommunicationError

from .bus import open_network
from .cia402 import state_of
from .config import GENERIC_EDS

__all__ = ["NodeInfo", "scan"]


@dataclass
class NodeInfo:
    node_id: int
    device_type: int | None = None
    vendor_id: int | None = None
    product_code: int | None = None
    revision: int | None = None
    serial: int | None = None
    name: str = ""
    nmt_state: str = "?"
    drive_state: str = ""  # CiA 402 state, drives only

    @property
    def profile(self) -> str:
        if self.device_type is None:
            return "?"
        return f"CiA {self.device_type & 0xFFFF}"

    def row(self) -> list[str]:
        def h(x: int | None) -> str:
            return "?" if x is None else f"0x{x:08X}"

        return [str(self.node_id), self.name or "?", self.profile, h(self.vendor_id), h(self.product_code),
                h(self.revision), h(self.serial), self.nmt_state, self.drive_state or "-"]


HEADER = ["node", "name", "profile", "vendor", "product", "revision", "serial", "NMT", "CiA 402 state"]


def _read(node: canopen.RemoteNode, index: int, sub: int | None = None) -> int | None:
    try:
        var = node.sdo[index] if sub is None else node.sdo[index][sub]
        return int(var.raw)
    except (SdoCommunicationError, SdoAbortedError, KeyError, ValueError):
        return None


def scan(interface: str, channel: str, bitrate: int = 1_000_000, *, wait: float = 0.5, timeout: float = 0.2,
         limit: int = 127, eds: Path = GENERIC_EDS) -> list[NodeInfo]:
    """The nodes that answer on the bus, by node id (`wait` s for answers after the search)."""
    network = open_network(interface, channel, bitrate, f"{interface}:{channel}")
    try:
        network.scanner.search(limit)
        time.sleep(wait)  # (the answers come in on the receive thread)
        found = sorted(set(network.scanner.nodes))
        out = []
        for node_id in found:
            node = canopen.RemoteNode(node_id, str(eds))
            network.add_node(node)
            node.sdo.RESPONSE_TIMEOUT = timeout
            node.sdo.MAX_RETRIES = 1  # one try (canopen counts tries; 0 would retry forever)
            info = NodeInfo(node_id)
            info.device_type = _read(node, 0x1000)
            info.vendor_id = _read(node, 0x1018, 1)
            info.product_code = _read(node, 0x1018, 2)
            info.revision = _read(node, 0x1018, 3)
            info.serial = _read(node, 0x1018, 4)
            try:
                info.name = str(node.sdo[0x1008].raw)
            except (SdoCommunicationError, SdoAbortedError, KeyError, ValueError, UnicodeDecodeError):
                info.name = ""
            if info.device_type is not None and info.device_type & 0xFFFF == 402:
                sw = _read(node, 0x6041)
                info.drive_state = "?" if sw is None else f"{state_of(sw)} (0x{sw:04X})"
            if node.nmt.timestamp is not None:
                info.nmt_state = node.nmt.state
            out.append(info)
        return out
    finally:
        network.disconnect()
