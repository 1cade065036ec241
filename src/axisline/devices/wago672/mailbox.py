"""The mailbox of the 750-672: the toggle handshake and every opcode (manual §3.7.4, §3.8, §4.2,
§4.3; wago.md §3.7 .. §3.9, §7.9, §7.10).

    mbx = attach(dev, eeprom="x.eeprom.json")   # filters, tables, run programs, recorder, mailbox
    PLC: C0.5 = 1 -> S0.5 = 1, bytes 2..7 carry MB0..MB5:
         MB0 opcode, MB1 Control_Mbx (bit 7 toggle), MB2..MB5 request parameters
         reply MB0 opcode, MB1 Status_Mbx (bit 7 toggle | return code), MB2..MB5 reply

A request is executed when its toggle bit differs from the toggle of the last reply, or when
its opcode differs from the previous request's ("data is also accepted if an opcode is
specified which differing from the previous one"); the reply mirrors the toggle ("done").

Opcodes (reply MB2..MB5 in brackets):
    0x00 IDLE                 no task
    0x40 DRIVE_COMMAND        MB2 move command, MB3..MB5 Data 1..3 (command and data echoed);
                              only in the mode "Run commands via mailbox" (C1.7, else 0x23)
    0x41 DLD_START            location, table type, count LSB, transfer<<4 | count MSB
                              [status, -, number of data sets, EEPROM version]
    0x42 DLD_CONT             4 data bytes [4 data bytes (upload data / download echo)]
    0x43 DLD_END              checksum [checksum of the stored data]
    0x44 TABLE_ERASE          location, type [status]
    0x45 TABLE_COPY           type (5: status query), source, target [status]
    0x46 TABLE_START          location (0: none), type [status]
    0x48 TABLE_STOP           - [status = return code of the internal STOP_FAST]
    0x49 DIAG_RD_ERROR        - [error code LSB, MSB, extra information LSB, MSB]
    0x4A DIAG_QUIT_ERROR      - (as an Error_Quit edge)
    0x4C DIAG_RD_VAR          variable number (32 bit) [value, 32 bit]
    0x4D DIAG_RD_BIT          bit number [0 / 1]
    0x4E DIAG_QUERY_STORAGE   - [0 stored, 1..255 storing in progress]
    0x4F TABLE_GET_ACTIVE     type [0 none / 1 RAM1 / 2 RAM2; type 4: 1 user set, 2 factory]
    0x50 CONFIG_SET_PTR       address LSB, MSB, number of bytes 1..4
    0x51 CONFIG_WR            data (the number of bytes set by CONFIG_SET_PTR)
    0x52 CONFIG_RD            address LSB, MSB, number of bytes [data]
    0x53 CONFIG_SAVE          password 0x0001 (user) / 0xE17E (FACTORY_DEFAULT), 32 bit
    0x54 CONFIG_RESTORE       restore 1 (user) / 2 (factory), warm start 0 / 1
    0x5C POS_TABLE_CREATE     location, number of elements, initialization [status]
    0x5D POS_TABLE_SET_PTR    index [status]
    0x5E POS_TABLE_WR         value (32 bit) [status]
    0x5F POS_TABLE_TEACH      target (0..49, 0xFF/0xFE/0xFD), measurement 0/1 [status]

Return codes (Status_Mbx bits 0..6): 0x00 OK, 0x01 general error, 0x11 still executing, 0x12
not accepted, 0x13 unknown command, 0x23 access denied, 0x30 table used/active, 0x31 general
error (tables, configuration), 0x32 invalid table, 0x33 copying still active, 0x34 EEPROM
copying aborted, 0x35 target not empty, 0x37 table/index does not exist, 0x38 data corrupt,
0x3A invalid number of elements.

Decisions ([AMBIGUOUS]/[CONFLICT]/[RECONSTRUCTED] points of wago.md §3.7 .. §3.9; the manual wins):
* M1 Handshake state (wago.md §3.7 [RECONSTRUCTED]): after power-on the last opcode is IDLE and
  the last toggle 0, so the first request with toggle 1 - or any opcode but IDLE - is executed.
  The state survives switching the mailbox off and on and a warm start (CONFIG_RESTORE, a
  configuration download, DIAG_QUIT_ERROR of a 2xxx error): the request that caused the warm
  start is not executed again; its reply is shown once the mailbox image is back. Test:
  test_mailbox::test_toggle_handshake_*.
* M2 Undefined opcodes (0x01..0x3F, 0x47, 0x4B, 0x55..0x5B, 0x60..0xFF; wago.md §3.8
  [RECONSTRUCTED] "0x01/0x31"): return code 0x13 "Unknown command", no device error (the
  manual's code for an unknown command; an undefined opcode must not stop the drive). Test:
  test_mailbox::test_undefined_opcodes_are_unknown_commands.
* M3 DRIVE_COMMAND reply: MB2..MB5 echo command and Data 1..3 (the DRIVE_COMMAND table of
  §4.2.4.2.1 lists them; the sub-command tables call them reserved). Test:
  test_mailbox::test_mailbox_move_exchange_of_wago_md_9_12.
* M4 Commands of the run-program table in mailbox move mode (§3.10.5 "The table commands and
  auxiliary commands are required exclusively for the Run program mode", yet VAR_* "can be
  transferred in the mode Mailbox Move command" and bits linked to MZERO/MONE "can be freely set
  ... via mailbox commands"): VAR_*, WR_BIT and NOP are executed; WAIT_TIME, WAIT_TEST_BIT,
  GOTO*, LABEL, PROG_STOP and PROG_END need table processing and are answered 0x12 without an
  error. Outside the mailbox move mode all DRIVE_COMMANDs are 0x23. An error of a VAR_*/WR_BIT
  command (1242, 1243, 1247, 1248, 1251) is raised and answered 0x01. Test:
  test_mailbox::test_var_and_wr_bit_through_drive_command.
* M5 DIAG_RD_VAR variable number (wago.md §3.8.13 [AMBIGUOUS], §10.3 item 14): 32 bit, MB2 = LSB
  .. MB5 = MSB (the bit range 0x1000.. needs more than MB2). 0x1000 + n is bit n (0x1100: 0);
  direct RAM / periphery reads (0x40000000.., 0xE0000000.., 0xFFE00000..) return 0 [HW]. Test:
  test_mailbox::test_diag_rd_var_and_rd_bit.
* M6 CONFIG_SET_PTR (wago.md §3.8.16/17): a number of bytes outside 1..4 is 0x23 and error 1161
  CONFIG_WRITE_SIZE (its description is exactly this case); an address range outside 0..511 is
  0x23. The pointer does not auto-increment [RECONSTRUCTED]; it is forgotten at a warm start.
  CONFIG_WR without a pointer or with a value outside the entry's range is 0x23 and changes
  nothing (no device error: the table never holds an invalid value); CONFIG_RD with an invalid
  number of bytes or address returns 0 with 0x00. Test: test_mailbox::test_config_access_*.
* M7 DIAG_QUIT_ERROR acknowledges like an Error_Quit edge (device.quit_errors: 1xxx cleared
  unless the cause persists, 2xxx warm start). DIAG_RD_ERROR reports the error, else the warning
  (the device's error memory). Test: test_mailbox::test_diag_rd_error_and_quit.
"""

from __future__ import annotations

import os
from enum import IntEnum
from typing import TYPE_CHECKING

from axisline.devices.wago672.config_table import TABLE_SIZE, ConfigValueError
from axisline.devices.wago672.device import RC
from axisline.devices.wago672.errors import WagoError
from axisline.devices.wago672.filters import FilterBank, VarOpcode
from axisline.devices.wago672.image import MODE_MAILBOX
from axisline.devices.wago672.program import Cmd, ProgramEngine
from axisline.devices.wago672.recorder import DataRecorder
from axisline.devices.wago672.tables import EEPROM_WRITE_MS, TRC, TableManager

if TYPE_CHECKING:
    from axisline.devices.wago672.device import Wago672

__all__ = ["MbxOpcode", "Mailbox", "attach", "build_request", "TOGGLE"]

TOGGLE = 0x80


class MbxOpcode(IntEnum):
    """Mailbox opcodes (§4.2.2)."""

    IDLE = 0x00
    DRIVE_COMMAND = 0x40
    DLD_START = 0x41
    DLD_CONT = 0x42
    DLD_END = 0x43
    TABLE_ERASE = 0x44
    TABLE_COPY = 0x45
    TABLE_START = 0x46
    TABLE_STOP = 0x48
    DIAG_RD_ERROR = 0x49
    DIAG_QUIT_ERROR = 0x4A
    DIAG_RD_VAR = 0x4C
    DIAG_RD_BIT = 0x4D
    DIAG_QUERY_STORAGE = 0x4E
    TABLE_GET_ACTIVE = 0x4F
    CONFIG_SET_PTR = 0x50
    CONFIG_WR = 0x51
    CONFIG_RD = 0x52
    CONFIG_SAVE = 0x53
    CONFIG_RESTORE = 0x54
    POS_TABLE_CREATE = 0x5C
    POS_TABLE_SET_PTR = 0x5D
    POS_TABLE_WR = 0x5E
    POS_TABLE_TEACH = 0x5F


# run-program commands that need table processing (M4)
_TABLE_ONLY = frozenset({
    Cmd.WAIT_TIME, Cmd.WAIT_TEST_BIT, Cmd.GOTO, Cmd.GOTO_IF, Cmd.GOTO_IF_NOT, Cmd.GOTO_LABEL,
    Cmd.GOTO_LABEL_IF, Cmd.GOTO_LABEL_IF_NOT, Cmd.LABEL, Cmd.PROG_STOP, Cmd.PROG_END, Cmd.PROG_END_FF,
})
_VAR = frozenset(int(v) for v in VarOpcode)


def build_request(opcode: int, toggle: int, *params: int) -> bytes:
    """MB0..MB5 of a request: opcode, Control_Mbx (toggle 0/1 or 0x80), up to 4 parameter bytes."""
    if len(params) > 4:
        raise ValueError(f"a mailbox request has 4 parameter bytes (MB2..MB5), got {len(params)}")
    t = TOGGLE if toggle else 0
    return bytes([opcode & 0xFF, t]) + bytes(p & 0xFF for p in params).ljust(4, b"\x00")


def _u32(p: bytes) -> int:
    return int.from_bytes(p[0:4], "little")


def _r(rc: int, payload: bytes | int = b"") -> tuple[int, bytes]:
    if isinstance(payload, int):
        payload = bytes([payload & 0xFF])
    return rc, bytes(payload).ljust(4, b"\x00")[:4]


class Mailbox:
    """The mailbox engine (device.py's MailboxHandler); see the module docstring."""

    def __init__(
        self,
        device: Wago672,
        tables: TableManager,
        program: ProgramEngine,
        filters: FilterBank,
        recorder: DataRecorder,
    ) -> None:
        self.device = device
        self.tables = tables
        self.program = program
        self.filters = filters
        self.recorder = recorder
        self._opcode = 0x00
        self._toggle = 0
        self._reply = bytes(6)
        self._ptr: tuple[int, int] | None = None  # CONFIG_SET_PTR (address, size)
        self.executed = 0  # requests executed (diagnostics)

    # ---- the handshake
    def exchange(self, request: bytes, device: Wago672) -> bytes:
        req = bytes(request).ljust(6, b"\x00")
        opcode, toggle = req[0], req[1] & TOGGLE
        if toggle != self._toggle or opcode != self._opcode:
            self._opcode, self._toggle = opcode, toggle
            self.executed += 1
            rc, payload = self.execute(opcode, req[2:6])
            self._reply = bytes([opcode, toggle | (rc & 0x7F)]) + payload
        return self._reply

    def on_warm_start(self, device: Wago672) -> None:
        """Warm start: the volatile parts lose their state (the handshake state is kept, M1)."""
        self.tables.warm_start()
        self.filters.reset()
        self.recorder.reset()
        self.program.reset()
        self._ptr = None

    # ---- the opcodes
    def execute(self, opcode: int, p: bytes) -> tuple[int, bytes]:
        """Execute one request (MB2..MB5 = p); returns (return code, MB2..MB5 of the reply)."""
        p = bytes(p).ljust(4, b"\x00")
        t = self.tables
        dev = self.device
        op = opcode
        if op == MbxOpcode.IDLE:
            return _r(RC.OK)
        if op == MbxOpcode.DRIVE_COMMAND:
            return self._drive_command(p)
        if op == MbxOpcode.DLD_START:
            return t.dld_start(p[0], p[1], p[2] | (p[3] & 0x0F) << 8, p[3] >> 4)
        if op == MbxOpcode.DLD_CONT:
            return t.dld_cont(p)
        if op == MbxOpcode.DLD_END:
            return t.dld_end(_u32(p))
        if op == MbxOpcode.TABLE_ERASE:
            return t.table_erase(p[0], p[1])
        if op == MbxOpcode.TABLE_COPY:
            return t.table_copy(p[0], p[1], p[2])
        if op == MbxOpcode.TABLE_START:
            return t.table_start(p[0], p[1])
        if op == MbxOpcode.TABLE_STOP:
            rc, status = self.program.table_stop()
            return _r(rc, status)
        if op == MbxOpcode.TABLE_GET_ACTIVE:
            return t.table_get_active(p[0])
        if op == MbxOpcode.DIAG_RD_ERROR:
            e = dev.errors
            return _r(RC.OK, (e.code & 0xFFFF).to_bytes(2, "little") + (e.extra & 0xFFFF).to_bytes(2, "little"))
        if op == MbxOpcode.DIAG_QUIT_ERROR:
            dev.quit_errors()
            return _r(RC.OK)
        if op == MbxOpcode.DIAG_RD_VAR:
            n = _u32(p)
            value = dev.state_variable(n) if n <= 0x10FF else 0
            return _r(RC.OK, (int(value) & 0xFFFFFFFF).to_bytes(4, "little"))
        if op == MbxOpcode.DIAG_RD_BIT:
            try:
                return _r(RC.OK, int(dev.bits.read(p[0])))
            except WagoError as e:
                dev.raise_error(e.code, e.text)
                return _r(RC.OK, 0)
        if op == MbxOpcode.DIAG_QUERY_STORAGE:
            return t.query_storage()
        if op == MbxOpcode.CONFIG_SET_PTR:
            return self._config_set_ptr(p[0] | p[1] << 8, p[2])
        if op == MbxOpcode.CONFIG_WR:
            return self._config_wr(p)
        if op == MbxOpcode.CONFIG_RD:
            return self._config_rd(p[0] | p[1] << 8, p[2])
        if op == MbxOpcode.CONFIG_SAVE:
            return t.config_save(_u32(p))
        if op == MbxOpcode.CONFIG_RESTORE:
            return t.config_restore(p[0], p[1])
        if op == MbxOpcode.POS_TABLE_CREATE:
            return t.pos_create(p[0], p[1], p[2])
        if op == MbxOpcode.POS_TABLE_SET_PTR:
            return t.pos_set_ptr(p[0])
        if op == MbxOpcode.POS_TABLE_WR:
            return t.pos_write(_u32(p))
        if op == MbxOpcode.POS_TABLE_TEACH:
            return t.pos_teach(p[0], p[1])
        return _r(RC.UNKNOWN_COMMAND)  # M2

    def _drive_command(self, p: bytes) -> tuple[int, bytes]:
        dev = self.device
        cmd, data = p[0], p[1:4]
        echo = bytes(p)
        if cmd in _VAR or cmd in _TABLE_ONLY or cmd in (Cmd.WR_BIT, Cmd.NOP):
            if dev.mode != MODE_MAILBOX or not dev.ready:
                return RC.ACCESS_DENIED, echo
            if cmd in _TABLE_ONLY:
                return RC.NOT_ACCEPTED, echo
            try:
                if cmd in _VAR:
                    self.filters.execute(cmd, data)
                elif cmd == Cmd.WR_BIT:
                    dev.bits.write(data[0], bool(data[1]))
            except WagoError as e:
                dev.raise_error(e.code, e.text)
                return RC.GENERAL_ERROR, echo
            return RC.OK, echo
        return dev.drive_command(cmd, data, source="mailbox"), echo

    def _config_set_ptr(self, address: int, size: int) -> tuple[int, bytes]:
        if not 1 <= size <= 4:
            self.device.raise_error(1161, f"CONFIG_SET_PTR: {size} bytes - an element has 1 .. 4 bytes")
            return _r(TRC.ACCESS_DENIED)
        if address + size > TABLE_SIZE:
            return _r(TRC.ACCESS_DENIED)
        self._ptr = (address, size)
        return _r(TRC.OK)

    def _config_wr(self, p: bytes) -> tuple[int, bytes]:
        if self._ptr is None:
            return _r(TRC.ACCESS_DENIED)
        address, size = self._ptr
        try:
            self.device.config.write_bytes(address, p[:size])
        except (ConfigValueError, KeyError):
            return _r(TRC.ACCESS_DENIED)
        return _r(TRC.OK)

    def _config_rd(self, address: int, size: int) -> tuple[int, bytes]:
        if not 1 <= size <= 4 or address + size > TABLE_SIZE:
            return _r(TRC.OK)
        return _r(TRC.OK, self.device.config.read_bytes(address, size))


def attach(
    device: Wago672,
    eeprom: str | os.PathLike[str] | None = None,
    *,
    eeprom_write_ms: int = EEPROM_WRITE_MS,
) -> Mailbox:
    """Plug the filters, table manager, run-program interpreter, data recorder and mailbox into
    `device` and power it on with the EEPROM image `eeprom` (a JSON file; None: an EEPROM that
    lives as long as the object). Returns the mailbox engine, which is also `device.mailbox`;
    its `tables`, `program`, `filters` and `recorder` are the parts."""
    filters = FilterBank(device)
    tables = TableManager(device, eeprom, filters, eeprom_write_ms=eeprom_write_ms)
    program = ProgramEngine(device, tables, filters)
    recorder = DataRecorder(device, tables)
    mbx = Mailbox(device, tables, program, filters, recorder)
    device.mailbox = mbx
    device.on_warm_start = mbx.on_warm_start
    device.warm_start()  # the power-on: configuration and tables from the EEPROM
    return mbx
