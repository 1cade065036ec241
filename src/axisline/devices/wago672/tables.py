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

from axisline.devices.wago672.config_table import ConfigValueError
from axisline.devices.wago672.table_store import (
    _RAM_KINDS,
    EEPROM_WRITE_MS,
    INVALID_POSITION,
    MAX_DATA_SETS,
    PASSWORD_FACTORY,
    PASSWORD_USER,
    RUN_COMMANDS,
    TRC,
    Storage,
    Table,
    TableKind,
    TableStatus,
    _reply,
    _s32,
    _status,
    byte_sum,
)
from axisline.devices.wago672.table_transfer import TableTransfers

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


class TableManager(TableTransfers):
    """RAM1/RAM2/EEPROM tables of one module (see the module docstring): the table commands,
    configuration data sets and the position table, over `TableTransfers` and `TableStore`."""

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
