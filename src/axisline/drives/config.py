"""`[axis.drive] type = "cia402"`: a CiA 402 servo drive on CANopen, as the machine file gives it.

Everything above the drive (the axis, its profiles, gears, cams, personalities) reads the same
[[axis]] table as with the simulated plant; only [axis.drive] changes. The axis' own
`counts_per_unit` is the drive's position scaling (increments of 0x6064 / 0x607A per user unit).

This module imports no CAN code: loading and checking a machine file does not need a bus.

Decisions
1. Issue 20 "interface: virtual for tests": python-can's virtual bus exists only inside the
   process, so no drive but a simulated one can be on it: `interface = "virtual"` needs
   [axis.drive.simulated], and a simulated drive needs the virtual bus; `check` refuses both
   mistakes instead of `run` waiting for a drive that cannot answer
   (tests/drives/test_config.py::test_the_virtual_bus_needs_the_simulated_drive).
2. The defaults: 1 Mbit/s, heartbeat 100 ms judged lost after 500 ms (CiA 301 leaves both to the
   integrator; five periods ride out a busy host), axisline's own heartbeat under node id 127
   (the highest, the one integrators leave free for a master) watched by the drive for 500 ms,
   and 0.5 s for any answer (tests/drives/test_pdo_mapping.py::
   test_the_generic_eds_mapping_on_the_controller_and_on_the_drive).
3. Issue 20 "homing done by the drive or by axisline": by the drive means at start, before the
   first cycle, when homing_method is given (the drive's homing mode 6, started by SDO,
   awaited for homing_timeout); the cycle then runs in CSP on the drive's home frame. Homing
   by axisline is the axis' home job step, unchanged (tests/drives/test_homing.py).
"""

from __future__ import annotations

from pathlib import Path
from typing import Literal

from pydantic import BaseModel, ConfigDict, Field, field_validator, model_validator

from ..plant.config import ServoDriveConfig

__all__ = ["Cia402Entry", "BITRATES", "GENERIC_EDS"]

#: the generic CiA 402 EDS shipped with axisline (drives/eds/)
GENERIC_EDS = Path(__file__).resolve().parent / "eds" / "cia402_generic.eds"

#: CiA 301's bit rates (bit/s)
BITRATES = (10_000, 20_000, 50_000, 125_000, 250_000, 500_000, 800_000, 1_000_000)


class Cia402Entry(BaseModel):
    """A CiA 402 servo drive in Cyclic Synchronous Position mode over CANopen."""

    model_config = ConfigDict(extra="forbid")

    type: Literal["cia402"] = "cia402"
    interface: str = Field(
        "virtual", min_length=1, max_length=32, pattern=r"^[a-z0-9_]+$",
        description="python-can interface: virtual (simulation, tests), socketcan, pcan, kvaser, ...",
    )
    channel: str = Field(
        "axisline", min_length=1, max_length=64, pattern=r"^[A-Za-z0-9_.:/\-]+$",
        description="bus channel: can0 for socketcan, any name for virtual; axes on one channel share one bus",
    )
    bitrate: int = Field(1_000_000, description=f"bit rate, bit/s: one of {', '.join(str(b) for b in BITRATES)}")
    node_id: int = Field(1, ge=1, le=127, description="the drive's CANopen node id")
    eds: str | None = Field(
        None, min_length=1, max_length=1024,
        description="the drive's EDS file (relative to the machine file); none: the generic CiA 402 EDS shipped with axisline",
    )
    mode: Literal["csp"] = Field("csp", description="operating mode: csp (Cyclic Synchronous Position, target every SYNC)")
    jog: Literal["csp", "pv"] = Field(
        "csp", description="jog in csp (the axis' ramp, position every cycle) or pv (Profile Velocity: the drive's velocity loop)"
    )
    heartbeat_ms: int = Field(100, ge=10, le=10_000, description="the drive's heartbeat period (0x1017), ms")
    heartbeat_timeout_ms: int = Field(
        500, ge=20, le=60_000, description="no heartbeat for this long: the drive is lost (its axis faults, the others stop), ms"
    )
    controller_id: int = Field(
        127, ge=1, le=127, description="node id under which axisline sends its own heartbeat (the drive's consumer watches it)"
    )
    controller_timeout_ms: int = Field(
        500, ge=20, le=60_000,
        description="the drive's heartbeat consumer time (0x1016): no controller heartbeat for this long and the drive quick-stops, ms",
    )
    response_timeout: float = Field(
        0.5, gt=0.0, le=10.0, description="longest wait for an answer: SDO at start, the TPDOs after each SYNC, s"
    )
    quick_stop_deceleration: float | None = Field(
        None, gt=0.0, le=1e9,
        description="the drive's quick stop deceleration (0x6085), units/s^2; none: the axis' error_deceleration",
    )
    homing_method: int | None = Field(
        None, ge=-128, le=127,
        description="home by the drive at start with this CiA 402 homing method (0x6098; 35 or 37: here); none: no homing by the drive",
    )
    home_offset: float = Field(0.0, ge=-1e9, le=1e9, description="the drive's home offset (0x607C), user units")
    homing_timeout: float = Field(30.0, gt=0.0, le=600.0, description="longest homing by the drive at start, s")
    simulated: ServoDriveConfig | None = Field(
        None,
        description="interface virtual only: start a simulated CiA 402 drive on the bus wrapping this servo model "
        "(the [axis.encoder] is its motor encoder)",
    )

    @field_validator("bitrate")
    @classmethod
    def _bitrate(cls, value: int) -> int:
        if value not in BITRATES:
            raise ValueError(f"{value} is not a CANopen bit rate (allowed: {', '.join(str(b) for b in BITRATES)})")
        return value

    @model_validator(mode="after")
    def _checks(self) -> "Cia402Entry":
        if self.simulated is not None and self.interface != "virtual":
            raise ValueError(f"simulated: a simulated drive runs on the virtual bus only (interface = {self.interface!r})")
        if self.simulated is None and self.interface == "virtual":
            # python-can's virtual bus exists inside this process only: no real drive is on it
            raise ValueError(
                "interface = 'virtual' is python-can's in-process bus, where only a simulated drive can be: "
                "give [axis.drive.simulated], or a real interface (socketcan, pcan, ...)"
            )
        if self.heartbeat_timeout_ms <= self.heartbeat_ms:
            raise ValueError(
                f"heartbeat_timeout_ms = {self.heartbeat_timeout_ms} must exceed heartbeat_ms = {self.heartbeat_ms} "
                "(one heartbeat period late is not a lost drive)"
            )
        if self.controller_id == self.node_id:
            raise ValueError(f"controller_id = {self.controller_id} is the drive's node_id; give axisline a node id of its own")
        return self

    @property
    def bus_key(self) -> tuple[str, str]:
        """Axes with the same interface and channel share one bus (one SYNC per cycle)."""
        return (self.interface, self.channel)

    def eds_path(self, base: Path) -> Path:
        """The EDS file: the machine file's own, relative to its folder, or the generic one."""
        if self.eds is None:
            return GENERIC_EDS
        p = Path(self.eds)
        return p if p.is_absolute() else base / p
