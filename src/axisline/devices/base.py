"""Device personalities: how a device (FS701, COMPAX, CLM, WAGO 750-672) plugs into a Machine.

A personality is a class registered under a name (python-can's interface registry is the
model: one interface, many back ends, imported only when used). The machine file names it
in `[machine] personality = "fs701"` and configures it in its own `[device]` table, which
the personality validates with its pydantic model. The Machine then

    - builds it after the axes and the plant: `Personality(machine, config)`,
    - runs `tick(cycle)` in the LOGIC stage every `logic_every` cycles,
    - asks it for its protocol endpoints when `axisline serve` names them,
    - calls `persist()` on shutdown and `summary()` for the run report.

Rules of the house: a personality reads inputs and writes set points and outputs through
the kernel (axes, the I/O image, masters); it never integrates physics and never opens a
socket. Protocol code (fieldbus/) maps bytes to the personality's typed API, at cycle
boundaries through the machine's command queue.
"""

from __future__ import annotations

import importlib
from abc import ABC, abstractmethod
from pathlib import Path
from typing import Any, ClassVar, Protocol

from pydantic import BaseModel, ConfigDict

from ..kernel.requests import note_write_gate

# name -> "module:Class", imported on first use so a machine only loads its own device
PERSONALITIES: dict[str, str] = {}


def register(name: str, target: str) -> None:
    """Register a personality class by import path ("axisline.devices.fs701.device:Fs701")."""
    PERSONALITIES[name] = target


def load(name: str) -> type["Personality"]:
    try:
        target = PERSONALITIES[name]
    except KeyError:
        raise ValueError(f"unknown personality {name!r} (known: {', '.join(sorted(PERSONALITIES)) or 'none'})") from None
    module, _, cls = target.partition(":")
    return getattr(importlib.import_module(module), cls)


class ByteSession(Protocol):
    """One connection's side of a byte-stream protocol: its receive buffer and parser state."""

    def feed(self, data: bytes) -> bytes: ...


class ByteEndpoint(Protocol):
    """A byte-stream protocol (serial register access, ASCII interface): bytes in, reply bytes out.

    `session()` is called once per connection (TCP client, the pty), outside the cycle: it
    only makes parser state, so that a request one client leaves half-sent can never run
    into another client's bytes. Its `feed` runs at cycle boundaries; `feed` here is the
    endpoint's own session, for in-process callers."""

    def session(self) -> ByteSession: ...

    def feed(self, data: bytes) -> bytes: ...


class RegisterEndpoint(Protocol):
    """A register image served over Modbus TCP (16-bit registers)."""

    def read_registers(self, kind: str, address: int, count: int) -> list[int]: ...

    def write_registers(self, address: int, values: list[int]) -> None: ...


class NoDeviceConfig(BaseModel):
    model_config = ConfigDict(extra="forbid")


class Personality(ABC):
    """Base of the device personalities."""

    name: ClassVar[str]
    Config: ClassVar[type[BaseModel]] = NoDeviceConfig
    #: protocol endpoints it can serve: "serial-tcp" (byte stream), "modbus" (registers), "http"
    endpoints: ClassVar[tuple[str, ...]] = ()

    def __init__(self, machine: Any, config: BaseModel) -> None:
        self.machine = machine
        self.config = config
        #: the operator's explicit enable for writes from the network (`serve --allow-writes`);
        #: endpoints refuse writes (with the protocol's own refusal) while it is False
        self._network_writes = False

    @property
    def network_writes(self) -> bool:
        """The operator's write enable. Endpoints read it exactly when they decide on a write,
        so reading it also tells `serve`'s audit that the request is a write (kernel/requests.py)."""
        note_write_gate()
        return self._network_writes

    @network_writes.setter
    def network_writes(self, value: bool) -> None:
        self._network_writes = bool(value)

    @abstractmethod
    def tick(self, cycle: int) -> None:
        """Device logic of one logic cycle (LOGIC stage)."""

    def byte_endpoint(self) -> ByteEndpoint:
        raise NotImplementedError(f"{self.name} offers no byte-stream protocol")

    def register_endpoint(self) -> RegisterEndpoint:
        raise NotImplementedError(f"{self.name} offers no register image")

    def limited_axes(self) -> set[str]:
        """Machine axes whose travel the device accounts for: it limits them itself (its own
        travel limits) or knows them endless (a feed roll, a rotary axis); the run's "no stroke
        limit" warning leaves them out."""
        return set()

    def stop(self) -> bool:
        """Shutdown (Ctrl-C, SIGTERM): stop the device's motion with its own stop ramps.

        Return True if the device takes care of it (the machine then runs cycles until the
        axes are at rest), False to let the machine stop the axes directly.
        """
        return False

    def persist(self) -> list[Path]:
        """Save what must survive a restart (atomically); returns the files written."""
        return []

    def store_paths(self) -> list[Path]:
        """The files the device keeps its stored data in (`serve` removes the temporary files
        that interrupted saves left beside them before it starts)."""
        return []

    # -- reporting (axisline run) ---------------------------------------------------------

    #: None: the device runs no job of its own; else True once its job (a batch) is done,
    #: which the simulated run waits for like the machine file's job
    finished: bool | None = None

    def summary(self) -> dict[str, Any]:
        """The device's part of the run summary (JSON); `headline` is printed by `run`."""
        return {}

    def json_fields(self, device_summary: dict[str, Any]) -> dict[str, Any]:
        """Keys the device adds at the top level of `run --json` (beside "device")."""
        return {}

    def trace_channels(self) -> dict[str, tuple[Any, str, type]]:
        """Extra scope channels: name -> (getter, unit, float|int|bool)."""
        return {}

    def plots(self, out_dir: str | Path, data: dict | None, units: dict | None = None) -> list[Path]:
        """The device's own figures for `run --plot/--report` (files written)."""
        return []

    def report_markdown(self, device_summary: dict[str, Any], plots: list[Path]) -> str:
        """The device's section of report.md."""
        return ""


register("wago672", "axisline.devices.wago672.personality:Wago672Personality")
register("compax", "axisline.devices.compax.personality:CompaxPersonality")
register("fs701", "axisline.devices.fs701.personality:Fs701Personality")
register("clm", "axisline.devices.clm.personality:ClmPersonality")
