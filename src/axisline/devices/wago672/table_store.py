"""The tables of a 750-672 module and where they are kept (tables.py describes them and
lists the decisions): the table types, the RAM and EEPROM store with its file and write
jobs, and the lookups the device makes each tick (position table, camshaft).

    TableStore (this file) <- TableTransfers (table_transfer.py) <- TableManager (tables.py)
"""

from __future__ import annotations

import json
import math
import os
from collections.abc import Callable
from dataclasses import dataclass, field
from enum import Enum, IntEnum
from pathlib import Path
from typing import TYPE_CHECKING, Any

from axisline.devices.wago672.config_table import ConfigValueError
from axisline.devices.wago672.errors import WagoError
from axisline.configerrors import read_text
from axisline.kernel.atomic import atomic_write_text
from axisline.motion.camswitch import CamTable

if TYPE_CHECKING:
    from axisline.devices.wago672.device import Wago672
    from axisline.devices.wago672.filters import FilterBank


__all__ = ["TableStore", "Table", "TableKind", "Storage", "TableStatus", "TRC", "MAX_DATA_SETS", "INVALID_POSITION", "RUN_COMMANDS", "EEPROM_WRITE_MS", "byte_sum"]

EEPROM_WRITE_MS = 200  # T9
INVALID_POSITION = -0x80000000  # 0x80000000: unused camshaft entry / uninitialised position
PASSWORD_USER = 0x0001
PASSWORD_FACTORY = 0xE17E
_EEPROM_FORMAT = "axisline-wago672-eeprom"


class TableKind(IntEnum):
    PROGRAM = 1
    CAMSHAFT = 2
    POSITION = 3
    CONFIG = 4
    TRACE = 5


class Storage(IntEnum):
    EEPROM = 0
    RAM1 = 1
    RAM2 = 2


class TableStatus(Enum):
    BLANK = "blank"
    VALID = "valid"
    INVALID = "invalid"


class TRC:
    """Mailbox return codes of the table, diagnosis and configuration commands (§4.2)."""

    OK = 0x00
    GENERAL_ERROR = 0x01
    ACCESS_DENIED = 0x23
    TABLE_USED = 0x30
    FAULT = 0x31
    INVALID_TABLE = 0x32
    COPY_ACTIVE = 0x33
    COPY_ABORTED = 0x34
    NOT_EMPTY = 0x35
    NO_TABLE = 0x37
    CORRUPT = 0x38
    BAD_COUNT = 0x3A


MAX_DATA_SETS = {TableKind.PROGRAM: 400, TableKind.CAMSHAFT: 50, TableKind.POSITION: 50, TableKind.CONFIG: 128, TableKind.TRACE: 1000}

# every command of the run-program table (§4.3): a line with another command byte is invalid
RUN_COMMANDS = frozenset(
    [0x00, 0x02, 0x03, 0x04, 0x05, 0x06, 0x08, 0x10, 0x11, 0x18, 0x19, 0x1C, 0x1D, 0x20, 0x21, 0x22, 0x23, 0x24, 0x25,
     0x2B, 0x2E, 0x2F, 0x39]
    + list(range(0x50, 0x58))
    + [0x70, 0x71, 0x78, 0xF0, 0xF1, 0xF5, 0xF6, 0xF7, 0xF8, 0xF9, 0xFA, 0xFB, 0xFF]
)

_RAM_KINDS = (TableKind.PROGRAM, TableKind.CAMSHAFT, TableKind.POSITION)


def byte_sum(blocks) -> int:
    """The DLD checksum: the sum of every byte of every 4-byte block, modulo 2**32 (T3)."""
    return sum(sum(bytes(b)) for b in blocks) & 0xFFFFFFFF


def _s32(value: int) -> int:
    value &= 0xFFFFFFFF
    return value - 0x100000000 if value & 0x80000000 else value


def _s24(value: int) -> int:
    value &= 0xFFFFFF
    return value - 0x1000000 if value & 0x800000 else value


@dataclass
class Table:
    """One table: run program lines (command, 32-bit data), cam entries (sample, position) or
    positions; `size` = number of elements."""

    kind: TableKind
    status: TableStatus = TableStatus.BLANK
    entries: list[Any] = field(default_factory=list)

    @classmethod
    def default(cls, kind: TableKind, status: TableStatus = TableStatus.BLANK, size: int | None = None) -> Table:
        n = MAX_DATA_SETS[kind] if size is None else size
        if kind == TableKind.PROGRAM:
            entries: list[Any] = [(0x00, 0)] * n
        elif kind == TableKind.CAMSHAFT:
            entries = [(0, INVALID_POSITION)] * n
        else:
            entries = [0] * n
        return cls(kind, status, entries)

    @property
    def size(self) -> int:
        return len(self.entries)

    @property
    def valid(self) -> bool:
        return self.status is TableStatus.VALID

    def copy(self) -> Table:
        return Table(self.kind, self.status, list(self.entries))

    def line(self, index: int) -> tuple[int, bytes]:
        """Run program line `index`: (command, Data 1..3)."""
        cmd, data = self.entries[index]
        return cmd, (data & 0xFFFFFF).to_bytes(3, "little")

    def cam_table(self) -> CamTable:
        return CamTable.from_device([(pos, sample) for sample, pos in self.entries])

    def to_json(self) -> dict[str, Any]:
        return {"kind": int(self.kind), "entries": [list(e) if isinstance(e, tuple) else e for e in self.entries]}

    @classmethod
    def from_json(cls, obj: dict[str, Any]) -> Table:
        kind = TableKind(obj["kind"])
        raw = obj["entries"]
        if not isinstance(raw, list) or len(raw) > MAX_DATA_SETS[kind]:
            raise ValueError(f"table {kind.name}: bad entries")
        if kind in (TableKind.PROGRAM, TableKind.CAMSHAFT):
            entries: list[Any] = [(int(a), int(b)) for a, b in raw]
        else:
            entries = [int(v) for v in raw]
        return cls(kind, TableStatus.VALID, entries)


@dataclass
class _Transfer:
    kind: TableKind
    location: int
    count: int
    upload: bool
    wide: bool  # 32-bit transfer
    table: Table | None = None  # download staging
    blocks: list[bytes] = field(default_factory=list)  # upload data
    done: int = 0  # data sets transferred
    half: int | None = None  # expanded format: the command/sample of the data set in progress
    checksum: int = 0
    corrupt: bool = False
    last_position: int | None = None
    raw: bytearray = field(default_factory=bytearray)  # configuration data set


def _reply(rc: int, *payload: int) -> tuple[int, bytes]:
    return rc, bytes(payload).ljust(4, b"\x00")[:4]


def _status(rc: int) -> tuple[int, bytes]:
    """A reply whose MB2 is the status: 0 done, 1 aborted."""
    return _reply(rc, 0 if rc == TRC.OK else 1)


class TableStore:
    """The tables of one module and where they are kept: RAM1/RAM2, the EEPROM (its file and
    write jobs), the active tables and the lookups the device makes (tables.py describes it)."""

    def __init__(
        self,
        device: Wago672,
        eeprom: str | os.PathLike[str] | None = None,
        filters: FilterBank | None = None,
        *,
        eeprom_write_ms: int = EEPROM_WRITE_MS,
    ) -> None:
        self.device = device
        self.filters = filters
        self.path = Path(eeprom) if eeprom is not None else None
        self.eeprom_write_ms = eeprom_write_ms
        self.trace_source: Callable[[], list[int] | None] | None = None  # recorder.py
        # EEPROM image
        self.eeprom: dict[TableKind, Table] = {}
        self.config_user: bytes | None = device.config.to_bytes()  # T10
        self.config_factory: bytes | None = None
        if self.path is not None and self.path.exists():
            self._read_eeprom()
        # RAM
        self.ram: dict[tuple[TableKind, int], Table] = {}
        self.active: dict[TableKind, int] = {}
        self.config_source = 1
        self._cams: CamTable | None = None
        self._transfer: _Transfer | None = None
        self._jobs: list[list[Any]] = []  # [remaining ms, action, is_copy]
        self.copy_aborted = False
        self._pos_index: int | None = None
        self._zero_point = 0
        self._clear_ram()
        device.position_table = self.position
        device.cam_pattern = self.cam_pattern
        device.tick_hooks.append(self.tick)

    # ================================================================== EEPROM file

    def _read_eeprom(self) -> None:
        assert self.path is not None
        try:
            obj = json.loads(read_text(self.path, 16 << 20))  # size checked before reading
            if obj.get("format") != _EEPROM_FORMAT or obj.get("version") != 1:
                raise ValueError("not an axisline 750-672 EEPROM image")
            tables = {TableKind(int(k)): Table.from_json(v) for k, v in obj.get("tables", {}).items()}
            user = bytes.fromhex(obj["config_user"]) if obj.get("config_user") else None
            factory = bytes.fromhex(obj["config_factory"]) if obj.get("config_factory") else None
        except (OSError, ValueError, KeyError, TypeError, AttributeError, RecursionError) as e:  # not the JSON object we wrote
            raise ValueError(f"EEPROM image {self.path} cannot be read: {e}") from None
        self.eeprom = tables
        self.config_user = user
        self.config_factory = factory

    def _write_eeprom(self) -> None:
        if self.path is None:
            return
        obj = {
            "format": _EEPROM_FORMAT,
            "version": 1,
            "tables": {str(int(k)): t.to_json() for k, t in sorted(self.eeprom.items())},
            "config_user": self.config_user.hex() if self.config_user is not None else None,
            "config_factory": self.config_factory.hex() if self.config_factory is not None else None,
        }
        self.path.parent.mkdir(parents=True, exist_ok=True)  # as `axisline check` takes missing ones for writable
        atomic_write_text(self.path, json.dumps(obj, indent=1) + "\n")

    def _job(self, action: Callable[[], None], copy: bool = False) -> None:
        self._jobs.append([max(1, int(self.eeprom_write_ms)), action, copy])
        self.device.eeprom_writing = True

    def _finish_job(self, job: list[Any]) -> None:
        try:
            job[1]()
            self._write_eeprom()
            if job[2]:
                self.copy_aborted = False
        except OSError as e:
            if job[2]:
                self.copy_aborted = True
            self.device.raise_error(1334, f"EEPROM image {self.path} cannot be written: {e}")

    def flush(self) -> None:
        """Complete every pending EEPROM job now (warm start, shutdown)."""
        while self._jobs:
            self._finish_job(self._jobs.pop(0))
        self.device.eeprom_writing = False

    def storage_busy(self) -> int:
        return min(len(self._jobs), 255)

    def tick(self, cycle: int) -> None:
        if self._jobs:
            job = self._jobs[0]
            job[0] -= 1
            if job[0] <= 0:
                self._finish_job(self._jobs.pop(0))
            self.device.eeprom_writing = bool(self._jobs)

    # ================================================================== reset

    def _clear_ram(self) -> None:
        self.ram = {(k, loc): Table.default(k) for k in _RAM_KINDS for loc in (1, 2)}
        self.active = {k: 0 for k in _RAM_KINDS}
        self._cams = None
        self._transfer = None
        self._pos_index = None
        self._zero_point = 0

    def warm_start(self) -> None:
        """Reset: RAM tables lost, EEPROM tables to RAM1 and RAM2 (RAM1 active), configuration
        from the EEPROM user data set (else FACTORY_DEFAULT)."""
        self.flush()
        self._clear_ram()
        for kind, table in self.eeprom.items():
            if kind in _RAM_KINDS and table.valid:
                self.ram[(kind, 1)] = table.copy()
                self.ram[(kind, 2)] = table.copy()
                self._activate(kind, 1)
        cfg = self.device.config
        for data, source in ((self.config_user, 1), (self.config_factory, 2), (cfg.factory_bytes(), 2)):
            if data is None:
                continue
            try:
                cfg.load_bytes(data)
            except ConfigValueError:
                continue
            self.config_source = source
            break

    # ================================================================== lookups for the device

    def table(self, kind: TableKind, location: int) -> Table:
        """The table of `kind` at `location` (0 EEPROM: a blank table if none is stored)."""
        if location == Storage.EEPROM:
            return self.eeprom.get(kind) or Table.default(kind)
        return self.ram[(kind, location)]

    def active_table(self, kind: TableKind) -> Table | None:
        loc = self.active.get(kind, 0)
        if not loc:
            return None
        t = self.ram[(kind, loc)]
        return t if t.valid else None

    def _activate(self, kind: TableKind, location: int) -> None:
        self.active[kind] = location
        if kind == TableKind.CAMSHAFT:
            t = self.active_table(kind)
            self._cams = t.cam_table() if t is not None else None
        elif kind == TableKind.POSITION:
            self._pos_index = None

    def position(self, index: int, src: int) -> int:
        """MOVE_TABLE* target/distance: position table entry `index` (SRC 0) or FILTindex (SRC 1) (T11)."""
        if src:
            if self.filters is None:
                raise WagoError(1247, f"variable FILT{index}: no filters")
            return self.filters.value(index)
        t = self.active_table(TableKind.POSITION)
        if t is None:
            raise WagoError(1333, f"position table entry {index}: no valid position table is active")
        if index >= t.size:
            raise WagoError(1332, f"position table entry {index} is outside the active table (0 .. {t.size - 1})")
        value = t.entries[index]
        if value == INVALID_POSITION:
            raise WagoError(1333, f"position table entry {index} holds no position (0x80000000)")
        return value

    def cam_pattern(self, position: float) -> int:
        """CAM1..CAM8 sample at a set point [microsteps] (T15)."""
        cams = self._cams
        if cams is None:
            return 0
        steps = math.floor(position + 0.5)  # as CAM9 (device.py)
        period = self.device.config["Rotary_Axis_Period"]
        if period:
            steps %= period
        return cams.sample_at(steps)

    def eeprom_program(self) -> Table | None:
        t = self.eeprom.get(TableKind.PROGRAM)
        return t if t is not None and t.valid else None

    def _program_running(self) -> bool:
        p = self.device.program
        return bool(p is not None and p.running)

    def _in_transfer(self, kind: TableKind, location: int) -> bool:
        t = self._transfer
        return t is not None and t.kind == kind and t.location == location
