"""The table manager of the 750-672 (manual §3.9, §4.2.4.3 .. §4.2.4.7; wago.md §3.8, §3.10).

    tables = TableManager(dev, eeprom="module.eeprom.json")   # mailbox.attach() does this
    rc, reply = tables.dld_start(1, TableKind.CAMSHAFT, 8, transfer=0)
    rc, reply = tables.dld_cont(bytes([0x84, 0xE0, 0x2E, 0x00]))  # ... one per entry
    rc, reply = tables.dld_end(0xB0D)
    rc, reply = tables.table_start(1, TableKind.CAMSHAFT)

Table kinds: 1 run program (400 lines: command + 24/32-bit data), 2 camshaft (50 entries:
bit sample CAM8..CAM1 + position [microsteps]), 3 position table (50 positions [position
units]), 4 configuration data set (128 x 32 bit = the 512-byte configuration), 5 data recorder
(upload only, recorder.py). Storage: 0 EEPROM, 1 RAM1, 2 RAM2; configuration and recorder live
in RAM1 only. A RAM table is blank, valid or invalid (during or after a faulted download, or
erased); one table of each kind is active (TABLE_START; a run program downloaded to RAM1 is
activated by DLD_END when no other program table is active). The active camshaft drives CAM1
.. CAM8 (`device.cam_pattern`, with `camswitch.CamTable`), the active position table serves
MOVE_TABLE* (`device.position_table`; SRC 1 reads the variables FILT1..8 of filters.py).

Every operation of the mailbox returns (return code, MB2..MB5 of the reply); the codes are the
manual's (`TRC`). Downloads: DLD_START -> one DLD_CONT per data set (compressed 24-bit) or two
(expanded 32-bit: command/sample, then 32-bit data/position) or one 32-bit value (position
table, configuration) -> DLD_END with the checksum, the plain sum of every byte of every
DLD_CONT (the camshaft example of §3.11.1.9 sums to 0xB0D). Uploads (transfer 1/3) return the
data in DLD_CONT replies and their sum in the DLD_END reply.

The EEPROM holds one table of each kind plus the user and the FACTORY_DEFAULT configuration
data sets. Writing it (TABLE_COPY to 0, TABLE_ERASE 0, CONFIG_SAVE, configuration download)
runs in the background for `eeprom_write_ms` (DIAG_QUERY_STORAGE, LED A at 10 Hz) and then
persists the EEPROM to `eeprom` (a JSON file written with axisline.kernel.atomic). At a warm
start (and at `mailbox.attach`, the power-on) RAM tables are lost, the EEPROM tables are copied
to RAM1 and RAM2 and activated in RAM1, and the configuration is loaded from the EEPROM user
data set (else the FACTORY_DEFAULT one).

Decisions ([AMBIGUOUS]/[CONFLICT]/[RECONSTRUCTED] points of wago.md §3.8, §3.10; the manual wins):
* T1 DLD_START MB5 (wago.md §3.8.3 [AMBIGUOUS], §10.3 item 13): bits 7..4 = Transfer, bits 3..0
  = bits 11..8 of the number of data sets. The reply's MB4 "Number of data sets" is one byte:
  the number accepted modulo 256; MB5 is the EEPROM version number (ConfVersion 4). Test:
  test_tables::test_dld_start_mb5_split.
* T2 Configuration version (wago.md §3.8.3 "EEPROM version number is expected in byte 5"
  [AMBIGUOUS]): the ConfVersion byte (address 2) inside the downloaded data set must be the known
  version 4, else the data set is rejected at DLD_END (0x31). Test:
  test_tables::test_configuration_download_with_a_wrong_version_is_rejected.
* T3 Checksum (wago.md §3.8.5, §9.11): the sum of all DLD_CONT bytes modulo 2**32 (0xB0D for
  the manual's camshaft example, 0x61B for the run-program example). Test:
  test_tables::test_camshaft_example_of_the_manual.
* T4 Table size (wago.md §3.8.3 [RECONSTRUCTED]): a download always yields the full table (400
  lines, 50 cam entries, 50 positions); entries past the downloaded count keep the default
  assignment (PROG_END, invalid position 0x80000000, 0). POS_TABLE_CREATE makes a table of the
  given number of elements; an index past it is 0x37 in the mailbox and 1332
  TBL_INDEX_OUT_OF_RANGE in MOVE_TABLE*. Test: test_tables::test_position_table_download_and_default_assignment,
  test_tables::test_position_table_create_write_and_move_table.
* T5 Expanded 32-bit run-program data: Data 1..3 of a line are the lower 24 bits; the upper
  byte must be 0x00 or 0xFF, else DLD_CONT answers 0x38 (the line cannot be a run command). A
  command byte that is no run command or a camshaft position not above the previous one (unused
  entries 0x80000000 aside) is 0x38 too; the download goes on but the table cannot become
  valid ("The data that has been transmitted will not be corrected"). Test:
  test_tables::test_invalid_commands_and_descending_cams_make_the_table_invalid,
  test_tables::test_expanded_program_download_runs.
* T6 "Active" (wago.md §3.10, DLD_START/TABLE_START text): a table is active from TABLE_START
  (or the automatic activation) until another table of its kind or "0 No table" is started.
  Downloading into the active run-program table is 0x30 Table being used; the active camshaft
  and position tables may be overwritten: the new content takes effect at a successful DLD_END
  (until then the old content works); a faulted download leaves the table invalid and no longer
  active. TABLE_START of a run program while a program runs is 0x31. TABLE_STOP (program.py)
  ends the processing and keeps the table active. Test: test_tables::test_activation_rules.
* T7 Empty (wago.md §3.10 "The target table must be empty"): a copy target is empty unless it is
  valid, i.e. blank, erased (TABLE_ERASE sets the status to invalid) or faulted. Copying into an
  active table, from an invalid table, from the EEPROM or from/to a table in transfer is 0x31.
  Test: test_tables::test_copy_rules.
* T8 Start-up copy (wago.md §3.10 [CONFLICT], §10.3 item 29): EEPROM tables go to RAM1 and RAM2,
  RAM1 is activated. Test: test_tables::test_eeprom_tables_survive_a_restart_in_ram1_and_ram2.
* T9 EEPROM write time [RECONSTRUCTED]: 200 ms per job (EEPROM_WRITE_MS), jobs queued;
  DIAG_QUERY_STORAGE reports the number of pending jobs (1..255) or 0; TABLE_COPY type 5 reports
  0x33 while a copy is pending, 0x34 if the last one failed (file not writable: also error 1334
  TBL_COPY_FAILED). A warm start first completes the pending jobs. Test:
  test_tables::test_storage_runs_in_the_background.
* T10 Configuration data sets (wago.md §3.8.19/20, §7.1): without an EEPROM file the module's
  configuration at power-on is its saved user data set. CONFIG_SAVE 0x0001 saves the RAM
  configuration as user data set, 0xE17E as FACTORY_DEFAULT (used by CONFIG_RESTORE 2 and when
  no user set exists), any other password is 0x31 and error 1162 CONFIG_WRONGPASSWORD; a data
  set that breaks a rule between values (1162 current password, 1817 supply limits) is 0x31
  with that error. CONFIG_RESTORE warm start 0 overwrites the EEPROM user set with the chosen
  set and warm starts; warm start 1 loads it into RAM only and raises 2821 CFG_FACTORY_LOAD, whose
  acknowledgement warm starts with the saved user set. TABLE_ERASE of the configuration in the
  EEPROM deletes the user set (the FACTORY_DEFAULT can only be overwritten); the RAM
  configuration is always active (0x30). TABLE_GET_ACTIVE 4: 1 user set, 2 factory default.
  Test: test_tables::test_config_save_and_restore.
* T11 Position table access (wago.md §3.9 [RECONSTRUCTED]): MOVE_TABLE* without an active valid
  position table or at an entry 0x80000000 is 1333 TBL_INVALID, past the table 1332. SRC = 1:
  the entry number 1..8 selects FILT1..8 (1247 otherwise). Test:
  test_tables::test_position_table_create_write_and_move_table, test_tables::test_move_table_without_a_position_table_is_1333.
* T12 Teach (wago.md §3.8.24 [RECONSTRUCTED]): stored value = actual position [position units]
  for measurement 0, actual position - zero point (set with target 0xFD, 0 after a reset) for
  measurement 1; targets 0xFF/0xFE write Drive_Range_Neg/_Pos in RAM the same way. A reserved
  target or measurement, an index past the active table or no active table: 0x37, status 1.
  POS_TABLE_WR writes at the index of the last POS_TABLE_SET_PTR (no auto-increment); the
  index is forgotten when another position table is activated. Test: test_tables::test_teach.
* T13 Storage location 0 for the configuration and the recorder (DLD_START table types 4, 5: the
  manual's "0:" row has no text): 0 and 1 both mean RAM1. Test:
  test_tables::test_configuration_download_with_a_wrong_version_is_rejected,
  test_recorder::test_upload_through_the_table_manager.
* T14 Uploads: a table that is not valid cannot be uploaded (0x31); the data recorder needs a
  stored data set (Trace_Stored). Program lines and cam entries upload in the format asked for:
  compressed as 24 bits, expanded as the 32-bit value stored (a compressed download stores the
  24 bits sign-extended); the trace and position/configuration values as one 32-bit value per
  DLD_CONT (transfer 1 or 3). Test: test_tables::test_expanded_download_and_uploads_in_both_formats,
  test_tables::test_expanded_program_download_runs.
* T15 Camshaft positions (wago.md §2.10): CAM1..CAM8 compare the actual value in microsteps
  rounded to the nearest step (as CAM9) - on a rotary axis taken into 0 .. Rotary_Axis_Period - with the
  table (camswitch.CamTable: below the first entry the first sample, at and above the last the
  last one). An active camshaft keeps working in every mode; after a reset only a table from the
  EEPROM is active. Test: test_tables::test_camshaft_example_of_the_manual,
  test_tables::test_cam_positions_on_a_rotary_axis_are_taken_into_the_period.
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

from axisline.devices.wago672.config_table import CONF_VERSION, TABLE_SIZE, ConfigValueError
from axisline.devices.wago672.errors import WagoError
from axisline.configerrors import read_text
from axisline.kernel.atomic import atomic_write_text
from axisline.motion.camswitch import CamTable

if TYPE_CHECKING:
    from axisline.devices.wago672.device import Wago672
    from axisline.devices.wago672.filters import FilterBank

__all__ = [
    "TableKind",
    "Storage",
    "TableStatus",
    "TRC",
    "Table",
    "TableManager",
    "MAX_DATA_SETS",
    "INVALID_POSITION",
    "RUN_COMMANDS",
    "EEPROM_WRITE_MS",
    "byte_sum",
]

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


class TableManager:
    """RAM1/RAM2/EEPROM tables of one module (see the module docstring)."""

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

    # ================================================================== download / upload

    def dld_start(self, location: int, kind: int, count: int, transfer: int) -> tuple[int, bytes]:
        """DLD_START: MB2 location, MB3 kind, count 0..4095, transfer 0..3 (T1)."""
        if self._transfer is not None and not self._transfer.upload:
            self._abort_transfer()
        self._transfer = None

        def refuse(rc: int = TRC.FAULT) -> tuple[int, bytes]:
            return _reply(rc, 1, 0, 0, CONF_VERSION)

        try:
            kind = TableKind(kind)
        except ValueError:
            return refuse()
        if transfer not in (0, 1, 2, 3):
            return refuse()
        upload = transfer in (1, 3)
        wide = transfer in (2, 3)
        if kind in (TableKind.CONFIG, TableKind.TRACE):
            if location not in (0, 1):
                return refuse()
            location = 1
        elif location not in (1, 2):
            return refuse()
        if not 1 <= count <= MAX_DATA_SETS[kind]:
            return refuse()
        if kind in (TableKind.POSITION, TableKind.CONFIG) and not wide:
            return refuse()  # "Only 32-bit data exists for the position tables and the configuration"
        if kind == TableKind.TRACE and not upload:
            return refuse()
        if kind == TableKind.CONFIG and not upload and count != MAX_DATA_SETS[kind]:
            return refuse()  # "A complete table, with 128 data values, 32 bit each, is always expected"
        tr = _Transfer(kind, location, count, upload, wide)
        if upload:
            blocks = self._upload_blocks(kind, location, count, wide)
            if blocks is None:
                return refuse()
            tr.blocks = blocks
        else:
            if kind == TableKind.PROGRAM and self.active[kind] == location:
                return refuse(TRC.TABLE_USED)
            if kind in _RAM_KINDS:
                tr.table = Table.default(kind, TableStatus.INVALID)
                if self.active.get(kind) != location:
                    self.ram[(kind, location)] = Table.default(kind, TableStatus.INVALID)
            else:
                tr.raw = bytearray()
        self._transfer = tr
        return _reply(TRC.OK, 0, 0, count & 0xFF, CONF_VERSION)

    def _upload_blocks(self, kind: TableKind, location: int, count: int, wide: bool) -> list[bytes] | None:
        if kind == TableKind.TRACE:
            data = self.trace_source() if self.trace_source is not None else None
            if not data or count > len(data):
                return None
            return [(v & 0xFFFFFFFF).to_bytes(4, "little") for v in data[:count]]
        if kind == TableKind.CONFIG:
            raw = self.device.config.to_bytes()
            return [raw[4 * i : 4 * i + 4] for i in range(count)]
        t = self.ram[(kind, location)]
        if not t.valid or count > t.size:
            return None
        blocks: list[bytes] = []
        for e in t.entries[:count]:
            if kind == TableKind.POSITION:
                blocks.append((e & 0xFFFFFFFF).to_bytes(4, "little"))
                continue
            head, value = e  # (command | sample, data | position)
            if wide:
                blocks.append(bytes([head, 0, 0, 0]))
                blocks.append((value & 0xFFFFFFFF).to_bytes(4, "little"))
            else:
                blocks.append(bytes([head]) + (value & 0xFFFFFF).to_bytes(3, "little"))
        return blocks

    def _abort_transfer(self) -> None:
        """A previous, incomplete download is cancelled and becomes invalid."""
        tr = self._transfer
        self._transfer = None
        if tr is None or tr.upload or tr.kind not in _RAM_KINDS:
            return
        self._invalidate(tr.kind, tr.location, tr.table)

    def _invalidate(self, kind: TableKind, location: int, content: Table | None) -> None:
        t = content.copy() if content is not None else Table.default(kind)
        t.status = TableStatus.INVALID
        self.ram[(kind, location)] = t
        if self.active.get(kind) == location:
            self._activate(kind, 0)

    def dld_cont(self, data: bytes) -> tuple[int, bytes]:
        """DLD_CONT: one 4-byte block (download) or the next 4 bytes of an upload."""
        d = bytes(data).ljust(4, b"\x00")[:4]
        tr = self._transfer
        if tr is None:
            return _reply(TRC.FAULT)
        if tr.upload:
            if tr.done >= len(tr.blocks):
                return _reply(TRC.FAULT)
            block = tr.blocks[tr.done]
            tr.done += 1
            tr.checksum = (tr.checksum + sum(block)) & 0xFFFFFFFF
            return TRC.OK, block
        if tr.done >= tr.count:
            return _reply(TRC.FAULT)
        tr.checksum = (tr.checksum + sum(d)) & 0xFFFFFFFF
        bad = False
        if tr.kind == TableKind.CONFIG:
            tr.raw += d
            tr.done += 1
        elif tr.kind == TableKind.POSITION:
            value = _s32(int.from_bytes(d, "little"))  # 0x80000000: an entry without position
            assert tr.table is not None
            tr.table.entries[tr.done] = value
            tr.done += 1
        else:
            if tr.wide and tr.half is None:
                tr.half = d[0]  # step n.1: command / bit sample, MB3..MB5 ignored
                return _reply(TRC.OK, *d)
            if tr.wide:
                head = tr.half
                assert head is not None
                tr.half = None
                value = _s32(int.from_bytes(d, "little"))
                if tr.kind == TableKind.PROGRAM and d[3] not in (0x00, 0xFF):
                    bad = True  # T5
            else:
                head = d[0]
                value = _s24(int.from_bytes(d[1:4], "little"))
            assert tr.table is not None
            if tr.kind == TableKind.PROGRAM:
                bad = bad or head not in RUN_COMMANDS
                tr.table.entries[tr.done] = (head, value)
            else:
                if value != INVALID_POSITION:
                    if tr.last_position is not None and value <= tr.last_position:
                        bad = True
                    tr.last_position = value
                tr.table.entries[tr.done] = (head, value)
            tr.done += 1
        if bad:
            tr.corrupt = True
            return _reply(TRC.CORRUPT, *d)
        return _reply(TRC.OK, *d)

    def dld_end(self, checksum: int) -> tuple[int, bytes]:
        """DLD_END: compare the checksum, validate (or not) the table; configuration: EEPROM, warm start."""
        tr = self._transfer
        self._transfer = None
        if tr is None:
            return _reply(TRC.FAULT)
        stored = tr.checksum.to_bytes(4, "little")
        if tr.upload:
            return TRC.OK, stored
        ok = not tr.corrupt and tr.done == tr.count and tr.half is None and (checksum & 0xFFFFFFFF) == tr.checksum
        if tr.kind == TableKind.CONFIG:
            return self._config_download(bytes(tr.raw), ok, stored)
        assert tr.table is not None
        if not ok:
            self._invalidate(tr.kind, tr.location, tr.table)
            return TRC.FAULT, stored
        table = tr.table
        table.status = TableStatus.VALID
        self.ram[(tr.kind, tr.location)] = table
        if self.active.get(tr.kind) == tr.location:
            self._activate(tr.kind, tr.location)  # an active camshaft/position table: new content now
        elif tr.kind == TableKind.PROGRAM and tr.location == Storage.RAM1 and not self.active[tr.kind]:
            self._activate(tr.kind, 1)  # "automatically activated (only when no other table is active)"
        return TRC.OK, stored

    def _config_download(self, data: bytes, ok: bool, stored: bytes) -> tuple[int, bytes]:
        rc = TRC.FAULT
        if ok and len(data) == TABLE_SIZE:
            probe = self.device.config.copy()
            try:
                probe.load_bytes(data)  # T2: ConfVersion, ranges, rules
            except ConfigValueError:
                pass
            else:
                self.config_user = probe.to_bytes()
                self._job(lambda: None)  # saved; the warm start completes the write
                rc = TRC.OK
        self.device.warm_start()  # "with a subsequent warm start (even if the transfer was faulted)"
        return rc, stored

    # ================================================================== table management

    def table_erase(self, location: int, kind: int) -> tuple[int, bytes]:
        try:
            kind = TableKind(kind)
        except ValueError:
            return _status(TRC.FAULT)
        if location not in (0, 1, 2) or kind == TableKind.TRACE:
            return _status(TRC.FAULT)
        if kind == TableKind.CONFIG:
            if location == Storage.RAM1:
                return _status(TRC.TABLE_USED)
            if location == Storage.RAM2:
                return _status(TRC.FAULT)
            self._job(self._erase_user_config)
            return _status(TRC.OK)
        if self._in_transfer(kind, location):
            return _status(TRC.FAULT)
        if location == Storage.EEPROM:
            self._job(lambda: self.eeprom.pop(kind, None))
            return _status(TRC.OK)
        if self.active[kind] == location:
            return _status(TRC.TABLE_USED)
        self.ram[(kind, location)] = Table.default(kind, TableStatus.INVALID)
        return _status(TRC.OK)

    def _erase_user_config(self) -> None:
        self.config_user = None

    def table_copy(self, kind: int, source: int, target: int) -> tuple[int, bytes]:
        if kind == 5:  # status query for a previous copy
            if any(job[2] for job in self._jobs):
                return _status(TRC.COPY_ACTIVE)
            return _status(TRC.COPY_ABORTED if self.copy_aborted else TRC.OK)
        try:
            kind = TableKind(kind)
        except ValueError:
            return _status(TRC.FAULT)
        if kind not in _RAM_KINDS or source not in (1, 2) or target not in (0, 1, 2) or source == target:
            return _status(TRC.FAULT)
        if self._in_transfer(kind, source) or self._in_transfer(kind, target):
            return _status(TRC.FAULT)
        src = self.ram[(kind, source)]
        if not src.valid:
            return _status(TRC.FAULT)
        snapshot = src.copy()
        if target == Storage.EEPROM:
            if any(job[2] for job in self._jobs):
                return _status(TRC.COPY_ACTIVE)
            stored = self.eeprom.get(kind)
            if stored is not None and stored.valid:
                return _status(TRC.NOT_EMPTY)

            def store() -> None:
                self.eeprom[kind] = snapshot

            self._job(store, copy=True)
            return _status(TRC.OK)
        if self.active[kind] == target:
            return _status(TRC.FAULT)
        if self.ram[(kind, target)].valid:
            return _status(TRC.NOT_EMPTY)
        self.ram[(kind, target)] = snapshot
        return _status(TRC.OK)

    def table_start(self, location: int, kind: int) -> tuple[int, bytes]:
        try:
            kind = TableKind(kind)
        except ValueError:
            return _status(TRC.FAULT)
        if kind not in _RAM_KINDS or location not in (0, 1, 2):
            return _status(TRC.FAULT)
        if kind == TableKind.PROGRAM and self._program_running():
            return _status(TRC.FAULT)
        if location and (not self.ram[(kind, location)].valid or self._in_transfer(kind, location)):
            return _status(TRC.FAULT)
        self._activate(kind, location)
        return _status(TRC.OK)

    def table_get_active(self, kind: int) -> tuple[int, bytes]:
        if kind in (1, 2, 3):
            return _reply(TRC.OK, self.active[TableKind(kind)])
        if kind == TableKind.CONFIG:
            return _reply(TRC.OK, self.config_source)
        return _reply(TRC.FAULT, 0)

    def query_storage(self) -> tuple[int, bytes]:
        return _reply(TRC.OK, self.storage_busy())

    # ================================================================== configuration data sets

    def config_save(self, password: int) -> tuple[int, bytes]:
        cfg = self.device.config
        if password not in (PASSWORD_USER, PASSWORD_FACTORY):
            self.device.raise_error(1162, f"CONFIG_SAVE password {password:#x}: 0x0001 (user data set) or 0xE17E (FACTORY_DEFAULT)")
            return _reply(TRC.FAULT)
        try:
            cfg.validate()
        except ConfigValueError as e:
            if e.code is not None:
                self.device.raise_error(e.code, str(e))
            return _reply(TRC.FAULT)
        data = cfg.to_bytes()
        if password == PASSWORD_USER:
            def store() -> None:
                self.config_user = data
        else:
            def store() -> None:
                self.config_factory = data
        self._job(store)
        return _reply(TRC.OK)

    def _factory(self) -> bytes:
        return self.config_factory if self.config_factory is not None else self.device.config.factory_bytes()

    def config_restore(self, restore: int, warm: int) -> tuple[int, bytes]:
        if restore not in (1, 2) or warm not in (0, 1):
            return _reply(TRC.FAULT)
        if restore == 1:
            if self.config_user is None:
                return _reply(TRC.FAULT)
            data = self.config_user
        else:
            data = self._factory()
        if warm == 0:
            self.flush()
            self.config_user = data
            try:
                self._write_eeprom()
            except OSError as e:
                self.device.raise_error(1334, f"EEPROM image {self.path} cannot be written: {e}")
            self.device.warm_start()
            return _reply(TRC.OK)
        try:
            self.device.config.load_bytes(data)
        except ConfigValueError:
            return _reply(TRC.FAULT)
        self.config_source = 1 if restore == 1 else 2
        self.device.raise_error(2821, "CONFIG_RESTORE without warm start: the data set is loaded to RAM only")
        return _reply(TRC.OK)

    # ================================================================== position table

    def pos_create(self, location: int, count: int, init: int) -> tuple[int, bytes]:
        if location not in (1, 2) or init not in (0, 1) or self._in_transfer(TableKind.POSITION, location):
            return _status(TRC.INVALID_TABLE)
        if not 1 <= count <= MAX_DATA_SETS[TableKind.POSITION]:
            return _status(TRC.BAD_COUNT)
        old = self.ram[(TableKind.POSITION, location)]
        if init == 1 and old.valid:
            if count <= old.size:
                return _status(TRC.BAD_COUNT)  # "executed only when the new size is larger"
            entries = old.entries + [INVALID_POSITION] * (count - old.size)
        else:
            entries = [INVALID_POSITION] * count
        self.ram[(TableKind.POSITION, location)] = Table(TableKind.POSITION, TableStatus.VALID, entries)
        if self.active[TableKind.POSITION] == location:
            self._activate(TableKind.POSITION, location)
        return _status(TRC.OK)

    def pos_set_ptr(self, index: int) -> tuple[int, bytes]:
        t = self.active_table(TableKind.POSITION)
        if t is None or not 0 <= index < min(t.size, 50):
            return _status(TRC.NO_TABLE)
        self._pos_index = index
        return _status(TRC.OK)

    def pos_write(self, value: int) -> tuple[int, bytes]:
        t = self.active_table(TableKind.POSITION)
        if t is None or self._pos_index is None or self._pos_index >= t.size:
            return _status(TRC.NO_TABLE)
        t.entries[self._pos_index] = _s32(value)
        return _status(TRC.OK)

    def pos_teach(self, target: int, measurement: int) -> tuple[int, bytes]:
        if measurement not in (0, 1):
            return _status(TRC.NO_TABLE)
        actual = self.device.actual_position
        if target == 0xFD:
            self._zero_point = actual
            return _status(TRC.OK)
        value = actual - self._zero_point if measurement == 1 else actual
        if target in (0xFE, 0xFF):
            name = "Drive_Range_Pos" if target == 0xFE else "Drive_Range_Neg"
            try:
                self.device.config[name] = value
            except ConfigValueError:
                return _status(TRC.NO_TABLE)
            return _status(TRC.OK)
        t = self.active_table(TableKind.POSITION)
        if t is None or not 0 <= target < min(t.size, 50):
            return _status(TRC.NO_TABLE)
        t.entries[target] = value
        return _status(TRC.OK)
