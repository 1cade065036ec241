"""The table manager: download/upload, checksum, RAM1/RAM2/EEPROM, copy/erase/activate, camshaft
and position tables, teach, configuration data sets (manual §3.9, §3.11.1.9, §3.11.1.10,
§4.2.4.3 - §4.2.4.7; wago.md §3.8, §3.10, §9.11)."""

from __future__ import annotations

import json

from axisline.devices.wago672.bits import Bit
from axisline.devices.wago672.image import C1, S2, S3
from axisline.devices.wago672.mailbox import MbxOpcode as Op
from axisline.devices.wago672.program import Cmd, Line
from axisline.devices.wago672.tables import INVALID_POSITION, TableKind, TableStatus, byte_sum

from .rig import Rig
from .test_mailbox import Mbx, d24, module

# wago.md §9.11 (manual §3.11.1.9): MB2 bit sample, MB3..MB5 position (LSB first)
CAM_EXAMPLE = [
    bytes([0x84, 0xE0, 0x2E, 0x00]),
    bytes([0x44, 0xC0, 0x5D, 0x00]),
    bytes([0x22, 0x80, 0xBB, 0x00]),
    bytes([0x12, 0x00, 0x77, 0x01]),
    bytes([0x08, 0xC0, 0xD4, 0x01]),
    bytes([0x44, 0x40, 0x90, 0x02]),
    bytes([0x42, 0xC0, 0xB0, 0x07]),
    bytes([0x41, 0xA0, 0xDF, 0x07]),
]


def cams(r: Rig) -> int:
    return sum(1 << i for i in range(8) if r.dev.bits.read(Bit.CAM1 + i))


def set_position(m: Mbx, value: int) -> None:
    assert m.drive(Cmd.SET_ACTUALPOSITION, *d24(value)) == 0
    m.r.step()


def test_camshaft_example_of_the_manual():
    # wago.md §9.11: eight entries, checksum 0xB0D, DLD_START (1, 2, 8, 0), TABLE_START (1, 2)
    assert byte_sum(CAM_EXAMPLE) == 0xB0D
    r, m = module()
    rc0, status, rcs, rc1, end = m.download(1, TableKind.CAMSHAFT, CAM_EXAMPLE, checksum=0xB0D)
    assert (rc0, status, rcs, rc1, end) == (0, 0, [0] * 8, 0, bytes([0x0D, 0x0B, 0, 0]))
    assert cams(r) == 0  # downloaded, not yet active
    assert m(Op.TABLE_START, 1, 2) == (0, bytes(4))
    assert m(Op.TABLE_GET_ACTIVE, 2) == (0, bytes([1, 0, 0, 0]))
    for position, pattern in ((0, 0x84), (11999, 0x84), (12000, 0x84), (23999, 0x84), (24000, 0x44), (48000, 0x22),
                              (100000, 0x12), (119999, 0x12), (120000, 0x08), (168000, 0x44), (504000, 0x42),
                              (515999, 0x42), (516000, 0x41), (8000000, 0x41), (-5000, 0x84)):
        set_position(m, position)
        assert cams(r) == pattern, position
    set_position(m, 100000)  # "pos 100000 -> CAM5 = 1, CAM2 = 1, others 0"
    assert m(Op.DIAG_RD_BIT, Bit.CAM5)[1][0] == 1 and m(Op.DIAG_RD_BIT, Bit.CAM2)[1][0] == 1
    assert m(Op.DIAG_RD_BIT, Bit.CAM3)[1][0] == 0


def test_cam_bits_follow_a_move_and_can_drive_an_output():
    cfg = {"Ptr_OUT1": Bit.CAM3}  # CAM3 on DO1 (the CAM bits are sources)
    r, m = module(**cfg)
    m.download(1, TableKind.CAMSHAFT, CAM_EXAMPLE)
    m(Op.TABLE_START, 1, 2)
    m.drive(Cmd.SET_VELOCITY, 0xA8, 0x61)  # 25000
    m.drive(Cmd.SET_ACC, 0xFF, 0x7F, 0)
    seen = set()
    assert m.drive(Cmd.MOVE, *d24(60000)) == 0
    while not r.has(S2.On_Target):
        r.step()
        seen.add((cams(r), r.dev.outputs[0]))
    assert seen == {(0x84, True), (0x44, True), (0x22, False)}


def test_cam_positions_on_a_rotary_axis_are_taken_into_the_period():
    # T15: CAM1..8 compare the actual value (0 .. Rotary_Axis_Period)
    r, m = module(Rotary_Axis_Period=30000)
    m.download(1, TableKind.CAMSHAFT, CAM_EXAMPLE[:2])
    m(Op.TABLE_START, 1, 2)
    tables = r.dev.mailbox.tables
    assert tables.cam_pattern(25000.0) == 0x44 and tables.cam_pattern(55000.0) == 0x44 and tables.cam_pattern(31000.0) == 0x84


def test_dld_start_mb5_split():
    # T1: MB5 bits 7..4 transfer, 3..0 count bits 11..8; reply MB4 count LSB, MB5 EEPROM version 4
    r, m = module()
    assert m(Op.DLD_START, 2, 1, 0x90, 0x01) == (0, bytes([0, 0, 0x90, 4]))  # 400 lines, compressed
    assert m(Op.DLD_START, 2, 1, 0x91, 0x01) == (0x31, bytes([1, 0, 0, 4]))  # 401 lines
    assert m(Op.DLD_START, 2, 1, 0x90, 0x21) == (0, bytes([0, 0, 0x90, 4]))  # expanded 32 bit
    assert m(Op.DLD_START, 2, 1, 0x00, 0x00)[0] == 0x31  # no data
    assert m(Op.DLD_START, 3, 1, 1, 0)[0] == 0x31  # location 3
    assert m(Op.DLD_START, 1, 3, 5, 0x00)[0] == 0x31  # position table: 32 bit only
    assert m(Op.DLD_START, 1, 4, 100, 0x20)[0] == 0x31  # configuration: 128 values always
    assert m(Op.DLD_START, 1, 5, 10, 0x00)[0] == 0x31  # trace: upload only
    assert m(Op.DLD_START, 1, 6, 10, 0x00)[0] == 0x31
    assert m(Op.DLD_START, 1, 1, 1, 0x40)[0] == 0x31  # transfer 4 reserved
    # wago.md §9.13 maximum numbers of data sets: program 400, camshaft 50, positions 50, trace 1000
    assert m(Op.DLD_START, 1, 2, 50, 0x00)[0] == 0 and m(Op.DLD_START, 1, 2, 51, 0x00)[0] == 0x31
    assert m(Op.DLD_START, 1, 3, 50, 0x20)[0] == 0 and m(Op.DLD_START, 1, 3, 51, 0x20)[0] == 0x31
    assert m(Op.DLD_START, 1, 5, 0xE9, 0x33)[0] == 0x31  # 1001 trace values
    assert m(Op.DLD_START, 1, 4, 128, 0x20)[0] == 0  # 128 configuration values


def test_dld_cont_and_dld_end_without_a_transfer():
    r, m = module()
    assert m(Op.DLD_CONT, 1, 2, 3, 4)[0] == 0x31
    assert m(Op.DLD_END)[0] == 0x31
    assert m(Op.DLD_START, 1, 2, 1, 0)[0] == 0
    assert m(Op.DLD_CONT, 0x01, 0x10, 0, 0)[0] == 0
    assert m(Op.DLD_CONT, 0x02, 0x20, 0, 0)[0] == 0x31  # "all data have already been transferred"
    assert m.u32(Op.DLD_END, 0x11)[0] == 0


def test_invalid_commands_and_descending_cams_make_the_table_invalid():
    # T5: DLD_CONT answers 0x38, the download goes on, DLD_END cannot validate the table
    r, m = module()
    tables = r.dev.mailbox.tables
    blocks = [CAM_EXAMPLE[1], CAM_EXAMPLE[0], CAM_EXAMPLE[2]]
    _, status, rcs, rc1, _ = m.download(1, TableKind.CAMSHAFT, blocks)
    assert status == 0 and rcs == [0, 0x38, 0] and rc1 == 0x31
    assert tables.table(TableKind.CAMSHAFT, 1).status is TableStatus.INVALID
    assert m(Op.TABLE_START, 1, 2) == (0x31, bytes([1, 0, 0, 0]))
    program = [Line(Cmd.NOP).encode(), bytes([0x30, 0, 0, 0]), Line(Cmd.PROG_STOP).encode()]
    _, _, rcs, rc1, _ = m.download(2, TableKind.PROGRAM, program)
    assert rcs == [0, 0x38, 0] and rc1 == 0x31
    wide = [bytes([Cmd.MOVE, 0, 0, 0]), (0x12345678).to_bytes(4, "little")]  # upper byte 0x12: no 24-bit datum
    _, _, rcs, rc1, _ = m.download(2, TableKind.PROGRAM, wide, transfer=2)
    assert rcs == [0, 0x38] and rc1 == 0x31
    # an unused position (0x80000000) is no error in a download; MOVE_TABLE to it is 1333
    _, _, rcs, rc1, _ = m.download(1, TableKind.POSITION, [(0x80000000).to_bytes(4, "little")], transfer=2)
    assert rcs == [0] and rc1 == 0


def test_a_wrong_checksum_leaves_the_table_invalid():
    r, m = module()
    _, _, rcs, rc1, end = m.download(1, TableKind.CAMSHAFT, CAM_EXAMPLE, checksum=0xB0C)
    assert rcs == [0] * 8 and rc1 == 0x31 and end == bytes([0x0D, 0x0B, 0, 0])  # the stored data's sum
    assert m(Op.TABLE_START, 1, 2)[0] == 0x31
    # an incomplete download is invalid too; a new DLD_START cancels the old one
    assert m(Op.DLD_START, 2, 2, 3, 0)[0] == 0
    m(Op.DLD_CONT, *CAM_EXAMPLE[0])
    assert m(Op.DLD_START, 1, 2, 8, 0)[0] == 0
    tables = r.dev.mailbox.tables
    assert tables.table(TableKind.CAMSHAFT, 2).status is TableStatus.INVALID
    for b in CAM_EXAMPLE[:7]:
        m(Op.DLD_CONT, *b)
    assert m.u32(Op.DLD_END, byte_sum(CAM_EXAMPLE[:7]))[0] == 0x31  # 7 of 8


def test_expanded_download_and_uploads_in_both_formats():
    r, m = module()
    wide = []
    for b in CAM_EXAMPLE:
        wide += [bytes([b[0], 0xAA, 0xBB, 0xCC]), b[1:] + b"\x00"]  # step n.1 MB3..MB5 ignored
    _, status, rcs, rc1, _ = m.download(2, TableKind.CAMSHAFT, wide, transfer=2)
    assert status == 0 and rcs == [0] * 16 and rc1 == 0
    rc, blocks, end = m.upload(2, TableKind.CAMSHAFT, 8, transfer=1)
    assert rc == 0 and blocks == CAM_EXAMPLE and end == bytes([0x0D, 0x0B, 0, 0])
    rc, blocks, end = m.upload(2, TableKind.CAMSHAFT, 8, transfer=3)
    assert rc == 0 and blocks[0] == bytes([0x84, 0, 0, 0]) and blocks[1] == bytes([0xE0, 0x2E, 0, 0])
    assert m(Op.DLD_START, 1, 2, 8, 0x10)[0] == 0x31  # RAM1 holds no valid table (T14)


def test_expanded_program_download_runs():
    # transfer 2: per line a DLD_CONT with the command, then one with the 32-bit data (T5: upper
    # byte 0x00 / 0xFF); the upload in the compressed format gives the lines of Line.encode()
    r, m = module()
    lines = [Line(Cmd.SET_VELOCITY, 5000), Line(Cmd.MOVE, -1000), Line(Cmd.WAIT_TIME, 16777215)]
    wide = []
    for line in lines:
        raw = line.encode()
        value = int.from_bytes(raw[1:], "little", signed=line.cmd == Cmd.MOVE)
        wide += [bytes([line.cmd, 0, 0, 0]), (value & 0xFFFFFFFF).to_bytes(4, "little")]
    _, status, rcs, rc1, _ = m.download(1, TableKind.PROGRAM, wide, transfer=2)
    assert status == 0 and rcs == [0] * 6 and rc1 == 0
    rc, blocks, _ = m.upload(1, TableKind.PROGRAM, 3, transfer=1)
    assert blocks == [line.encode() for line in lines]
    rc, blocks, _ = m.upload(1, TableKind.PROGRAM, 3, transfer=3)
    assert blocks == wide
    assert r.dev.mailbox.tables.active_table(TableKind.PROGRAM).line(1) == (Cmd.MOVE, bytes([0x18, 0xFC, 0xFF]))


def test_activation_rules():
    # T6: a program in RAM1 is activated by DLD_END when no program table is active; downloading into
    # the active program table is 0x30; the active camshaft may be overwritten
    r, m = module()
    tables = r.dev.mailbox.tables
    prog = [Line(Cmd.NOP).encode(), Line(Cmd.PROG_STOP).encode()]
    assert m.download(2, TableKind.PROGRAM, prog)[3] == 0
    assert m(Op.TABLE_GET_ACTIVE, 1)[1][0] == 0  # RAM2: not activated automatically
    assert m.download(1, TableKind.PROGRAM, prog)[3] == 0
    assert m(Op.TABLE_GET_ACTIVE, 1)[1][0] == 1
    assert m(Op.DLD_START, 1, 1, 2, 0) == (0x30, bytes([1, 0, 0, 4]))
    assert m(Op.TABLE_ERASE, 1, 1) == (0x30, bytes([1, 0, 0, 0]))
    assert m(Op.TABLE_START, 2, 1) == (0, bytes(4)) and m(Op.TABLE_GET_ACTIVE, 1)[1][0] == 2
    assert m(Op.TABLE_ERASE, 1, 1) == (0, bytes(4))
    assert tables.table(TableKind.PROGRAM, 1).status is TableStatus.INVALID
    assert m(Op.TABLE_START, 0, 1)[0] == 0 and m(Op.TABLE_GET_ACTIVE, 1)[1][0] == 0
    assert m(Op.TABLE_GET_ACTIVE, 0)[0] == 0x31 and m(Op.TABLE_START, 1, 4)[0] == 0x31
    # camshaft overwritten while active: the old content until DLD_END, then the new one at once
    m.download(1, TableKind.CAMSHAFT, CAM_EXAMPLE)
    m(Op.TABLE_START, 1, 2)
    set_position(m, 30000)
    assert cams(r) == 0x44
    assert m(Op.DLD_START, 1, 2, 1, 0)[0] == 0
    assert m(Op.DLD_CONT, 0x03, 0, 0, 0)[0] == 0
    r.step()
    assert cams(r) == 0x44
    assert m.u32(Op.DLD_END, 3)[0] == 0
    r.step()
    assert cams(r) == 0x03 and m(Op.TABLE_GET_ACTIVE, 2)[1][0] == 1
    # a faulted overwrite: invalid and no longer active
    m.download(1, TableKind.CAMSHAFT, CAM_EXAMPLE, checksum=1)
    r.step()
    assert cams(r) == 0 and m(Op.TABLE_GET_ACTIVE, 2)[1][0] == 0


def test_copy_rules():
    # T7 and manual §4.2.4.4.2
    r, m = module()
    m.download(1, TableKind.CAMSHAFT, CAM_EXAMPLE)
    assert m(Op.TABLE_COPY, 2, 1, 2) == (0, bytes(4))  # RAM1 -> RAM2 (blank)
    assert m(Op.TABLE_COPY, 2, 1, 2) == (0x35, bytes([1, 0, 0, 0]))  # target not empty
    assert m(Op.TABLE_COPY, 2, 1, 1)[0] == 0x31  # target = source
    assert m(Op.TABLE_COPY, 2, 0, 1)[0] == 0x31  # not out of the EEPROM
    assert m(Op.TABLE_COPY, 4, 1, 2)[0] == 0x31  # not the configuration
    assert m(Op.TABLE_COPY, 1, 1, 2)[0] == 0x31  # RAM1 holds no valid program
    m(Op.TABLE_START, 2, 2)
    assert m(Op.TABLE_ERASE, 2, 2)[0] == 0x30
    m(Op.TABLE_START, 0, 2)
    assert m(Op.TABLE_ERASE, 2, 2)[0] == 0 and m(Op.TABLE_COPY, 2, 1, 2)[0] == 0  # erased = empty
    rc, blocks, _ = m.upload(2, TableKind.CAMSHAFT, 8, transfer=1)
    assert blocks == CAM_EXAMPLE
    m(Op.TABLE_START, 2, 2)
    m(Op.TABLE_ERASE, 1, 2)
    assert m(Op.TABLE_COPY, 2, 1, 2)[0] == 0x31  # from an erased table, to the active table
    assert m(Op.DLD_START, 1, 2, 8, 0)[0] == 0
    assert m(Op.TABLE_COPY, 2, 1, 0)[0] == 0x31  # the source is in transfer
    assert m(Op.TABLE_COPY, 5, 0, 0) == (0, bytes(4))  # no copy pending


def test_storage_runs_in_the_background(tmp_path):
    # T9: TABLE_COPY RAM -> EEPROM, DIAG_QUERY_STORAGE, TABLE_COPY 5, LED A at 10 Hz, then the file
    path = tmp_path / "module.eeprom.json"
    r, m = module(path)
    m.download(1, TableKind.CAMSHAFT, CAM_EXAMPLE)
    assert m(Op.TABLE_COPY, 2, 1, 0) == (0, bytes(4))
    assert m(Op.DIAG_QUERY_STORAGE)[1][0] == 1
    assert m(Op.TABLE_COPY, 5, 0, 0)[0] == 0x33
    assert m(Op.TABLE_COPY, 2, 1, 0)[0] == 0x33
    assert not path.exists()
    led = set()
    for _ in range(120):
        r.step()
        led.add(r.dev.leds()["A"])
    assert led == {True, False}
    r.until(lambda: m(Op.DIAG_QUERY_STORAGE)[1][0] == 0, 100)
    assert m(Op.TABLE_COPY, 5, 0, 0)[0] == 0 and path.exists()
    assert json.loads(path.read_text())["tables"]["2"]["entries"][0] == [0x84, 12000]
    assert m(Op.TABLE_COPY, 2, 1, 0)[0] == 0x35  # the EEPROM table must be erased first
    assert m(Op.TABLE_ERASE, 0, 2)[0] == 0
    r.step(250)
    assert m(Op.TABLE_COPY, 2, 1, 0)[0] == 0


def test_eeprom_tables_survive_a_restart_in_ram1_and_ram2(tmp_path):
    # T8: after power-on the EEPROM tables are in RAM1 and RAM2, RAM1 active; RAM tables are lost
    path = tmp_path / "module.eeprom.json"
    r, m = module(path)
    prog = [Line(Cmd.SET_VELOCITY, 1000).encode(), Line(Cmd.PROG_STOP).encode()]
    m.download(1, TableKind.PROGRAM, prog)
    m.download(1, TableKind.CAMSHAFT, CAM_EXAMPLE)
    m(Op.TABLE_COPY, 1, 1, 0)
    r.step(250)
    m(Op.TABLE_COPY, 2, 1, 0)
    r.step(250)
    m(Op.POS_TABLE_CREATE, 2, 5, 0)  # RAM only
    r.dev.mailbox.tables.flush()
    r2, m2 = module(path)
    for kind in (1, 2):
        assert m2(Op.TABLE_GET_ACTIVE, kind)[1][0] == 1
        t1, t2 = (r2.dev.mailbox.tables.table(TableKind(kind), loc) for loc in (1, 2))
        assert t1.valid and t2.valid and t1.entries == t2.entries
    assert m2(Op.TABLE_GET_ACTIVE, 3)[1][0] == 0
    assert not r2.dev.mailbox.tables.table(TableKind.POSITION, 2).valid
    rc, blocks, _ = m2.upload(2, TableKind.PROGRAM, 2, transfer=1)
    assert blocks == prog
    # a warm start (acknowledging a 2xxx error) does the same
    m2(Op.POS_TABLE_CREATE, 1, 5, 0)
    r2.dev.raise_error(2821, "test")
    m2(Op.DIAG_QUIT_ERROR)
    r2.step()
    assert r2.has(S3.Reset) and not r2.dev.mailbox.tables.table(TableKind.POSITION, 1).valid
    assert m2(Op.TABLE_GET_ACTIVE, 2)[1][0] == 1


def test_an_unreadable_eeprom_image_is_refused(tmp_path):
    path = tmp_path / "bad.json"
    path.write_text("{not json")
    try:
        module(path)
    except ValueError as e:
        assert "bad.json" in str(e)
    else:  # pragma: no cover
        raise AssertionError("no error")


# ---------------------------------------------------------------- position table


def test_position_table_create_write_and_move_table():
    r, m = module(Filter2_Function=7)
    tables = r.dev.mailbox.tables
    assert m(Op.POS_TABLE_CREATE, 1, 51, 0) == (0x3A, bytes([1, 0, 0, 0]))  # wago.md §9.13
    assert m(Op.POS_TABLE_CREATE, 3, 5, 0)[0] == 0x32
    assert m(Op.POS_TABLE_SET_PTR, 0)[0] == 0x37  # no active table
    assert m(Op.POS_TABLE_CREATE, 1, 5, 0) == (0, bytes(4))
    assert tables.table(TableKind.POSITION, 1).entries == [INVALID_POSITION] * 5
    assert m(Op.TABLE_START, 1, 3)[0] == 0
    assert m(Op.POS_TABLE_SET_PTR, 5)[0] == 0x37  # T4: past the 5 elements
    assert m(Op.POS_TABLE_WR, 1, 2, 3, 4)[0] == 0x37  # no index set
    assert m(Op.POS_TABLE_SET_PTR, 2) == (0, bytes(4))
    assert m.u32(Op.POS_TABLE_WR, 5000) == (0, bytes(4))
    assert m.u32(Op.POS_TABLE_WR, 6000)[0] == 0  # no auto-increment: entry 2 again
    m(Op.POS_TABLE_SET_PTR, 3)
    m.u32(Op.POS_TABLE_WR, -2000)
    assert tables.table(TableKind.POSITION, 1).entries[:4] == [INVALID_POSITION, INVALID_POSITION, 6000, -2000]
    # expand: the entries are kept; only to a larger size
    assert m(Op.POS_TABLE_CREATE, 1, 8, 1)[0] == 0
    assert tables.table(TableKind.POSITION, 1).entries[2:] == [6000, -2000] + [INVALID_POSITION] * 4
    assert m(Op.POS_TABLE_CREATE, 1, 8, 1)[0] == 0x3A
    # MOVE_TABLE (0x04), _IMMEDIATE (0x05), _REL (0x08) with SRC 0 and SRC 1 (FILTn, T11)
    m.drive(Cmd.SET_VELOCITY, 0x10, 0x27)
    assert m.drive(Cmd.MOVE_TABLE, 2, 0) == 0
    r.until(lambda: r.has(S2.On_Target), 5000)
    assert r.dev.actual_position == 6000
    assert m.drive(Cmd.MOVE_TABLE_REL, 3, 0) == 0
    r.until(lambda: r.has(S2.On_Target), 5000)
    assert r.dev.actual_position == 4000
    assert m.drive(Cmd.VAR_SET, 2, *(-300 & 0xFFFF).to_bytes(2, "little")) == 0
    assert m.drive(Cmd.MOVE_TABLE_IMMEDIATE, 2, 1) == 0
    r.until(lambda: r.has(S2.On_Target), 5000)
    assert r.dev.actual_position == -300
    assert m.drive(Cmd.MOVE_TABLE, 0, 0) == 0x01 and r.error == 1333  # entry 0x80000000
    m(Op.DIAG_QUIT_ERROR)
    r.step()
    r.select(C1.M_DriveByMbx)
    assert m.drive(Cmd.MOVE_TABLE, 9, 0) == 0x01 and r.error == 1332  # past the table
    m(Op.DIAG_QUIT_ERROR)
    r.step()
    r.select(C1.M_DriveByMbx)
    assert m.drive(Cmd.MOVE_TABLE, 9, 1) == 0x01 and r.error == 1247  # FILT9


def test_position_table_download_and_default_assignment():
    # 32-bit values only; the entries after the downloaded ones are 0 (the default assignment, T4)
    r, m = module()
    values = [1000, -1000, 8388607]
    blocks = [(v & 0xFFFFFFFF).to_bytes(4, "little") for v in values]
    assert m.download(2, TableKind.POSITION, blocks, transfer=2)[3] == 0
    t = r.dev.mailbox.tables.table(TableKind.POSITION, 2)
    assert t.entries[:3] == values and t.entries[3:] == [0] * 47
    assert m(Op.TABLE_START, 2, 3)[0] == 0 and m(Op.POS_TABLE_SET_PTR, 49)[0] == 0
    rc, up, _ = m.upload(2, TableKind.POSITION, 3, transfer=3)
    assert up == blocks


def test_move_table_without_a_position_table_is_1333():
    r, m = module()
    assert m.drive(Cmd.MOVE_TABLE, 0, 0) == 0x01 and r.error == 1333


def test_teach():
    # T12: absolute, zero point 0xFD, relative, Drive_Range_Neg/Pos (0xFF/0xFE)
    r, m = module()
    m(Op.POS_TABLE_CREATE, 1, 10, 0)
    m(Op.TABLE_START, 1, 3)
    set_position(m, 1234)
    assert m(Op.POS_TABLE_TEACH, 0, 0) == (0, bytes(4))
    assert m(Op.POS_TABLE_TEACH, 0xFD, 0)[0] == 0  # zero point of the relative measurement
    set_position(m, 2000)
    assert m(Op.POS_TABLE_TEACH, 1, 1)[0] == 0
    assert m(Op.POS_TABLE_TEACH, 2, 0)[0] == 0
    assert r.dev.mailbox.tables.table(TableKind.POSITION, 1).entries[:3] == [1234, 766, 2000]
    assert m(Op.POS_TABLE_TEACH, 0xFE, 0)[0] == 0 and r.dev.config["Drive_Range_Pos"] == 2000
    set_position(m, -50)
    assert m(Op.POS_TABLE_TEACH, 0xFF, 0)[0] == 0 and r.dev.config["Drive_Range_Neg"] == -50
    assert m(Op.POS_TABLE_TEACH, 10, 0) == (0x37, bytes([1, 0, 0, 0]))  # past the 10 elements
    assert m(Op.POS_TABLE_TEACH, 50, 0)[0] == 0x37
    assert m(Op.POS_TABLE_TEACH, 1, 2)[0] == 0x37


# ---------------------------------------------------------------- configuration data sets


def quit_reset(r: Rig) -> None:
    r.c3 |= 0x80
    r.step(2)
    r.c3 &= ~0x80
    r.step()


def config_write(m: Mbx, address: int, value: int, size: int = 2) -> None:
    assert m(Op.CONFIG_SET_PTR, address & 0xFF, address >> 8, size)[0] == 0
    assert m(Op.CONFIG_WR, *(value & 0xFFFFFFFF).to_bytes(4, "little"))[0] == 0


def test_config_save_and_restore(tmp_path):
    # T10: save (0x0001 user, 0xE17E factory, else 1162), restore with and without warm start
    path = tmp_path / "module.eeprom.json"
    r, m = module(path, mailbox_mode=False)
    cfg = r.dev.config
    assert m(Op.TABLE_GET_ACTIVE, 4) == (0, bytes([1, 0, 0, 0]))  # the user data set
    config_write(m, 40, 5000)  # Speed
    assert m.u32(Op.CONFIG_SAVE, 0x0001) == (0, bytes(4))
    assert m(Op.DIAG_QUERY_STORAGE)[1][0] == 1
    r.step(250)
    assert m(Op.DIAG_QUERY_STORAGE)[1][0] == 0
    config_write(m, 40, 6000)
    assert cfg["Speed"] == 6000
    assert m(Op.CONFIG_RESTORE, 1, 0) == (0, bytes(4))  # last saved user set, warm start
    r.step(2)
    assert cfg["Speed"] == 5000 and r.has(S3.Reset) and r.dev.velocity == 5000
    # factory default into RAM only: 2821, its acknowledgement restores the saved user set
    quit_reset(r)
    assert m(Op.CONFIG_RESTORE, 2, 1)[0] == 0
    assert cfg["Speed"] == 3000 and r.error == 2821 and m(Op.TABLE_GET_ACTIVE, 4)[1][0] == 2
    m(Op.DIAG_QUIT_ERROR)
    r.step(2)
    assert r.error == 0 and cfg["Speed"] == 5000 and r.has(S3.Reset) and m(Op.TABLE_GET_ACTIVE, 4)[1][0] == 1
    # a wrong password: 0x31 and 1162
    assert m.u32(Op.CONFIG_SAVE, 0x1234)[0] == 0x31 and r.error == 1162
    m(Op.DIAG_QUIT_ERROR)
    # a FACTORY_DEFAULT data set of our own, then "user data set overwritten with FACTORY_DEFAULT"
    config_write(m, 40, 7000)
    assert m.u32(Op.CONFIG_SAVE, 0xE17E)[0] == 0
    r.step(250)
    config_write(m, 40, 1234)
    assert m(Op.CONFIG_RESTORE, 2, 0)[0] == 0
    r.step(2)
    assert cfg["Speed"] == 7000
    # the user set deleted from the EEPROM: the next warm start loads FACTORY_DEFAULT
    assert m(Op.TABLE_ERASE, 1, 4)[0] == 0x30 and m(Op.TABLE_ERASE, 2, 4)[0] == 0x31
    assert m(Op.TABLE_ERASE, 0, 4)[0] == 0
    r.step(250)
    assert m(Op.CONFIG_RESTORE, 1, 0)[0] == 0x31  # no user set left
    r.dev.warm_start()
    assert cfg["Speed"] == 7000 and m(Op.TABLE_GET_ACTIVE, 4)[1][0] == 2
    saved = json.loads(path.read_text())
    assert saved["config_user"] is None and saved["config_factory"] is not None


def test_configuration_download_and_upload():
    # wago.md §7.10: DLD_START (1, 4, 128, 32 bit), 128 x DLD_CONT, DLD_END -> EEPROM, warm start
    r, m = module(mailbox_mode=False)
    quit_reset(r)
    rc, blocks, _ = m.upload(1, TableKind.CONFIG, 128, transfer=3)
    assert rc == 0 and b"".join(blocks) == r.dev.config.to_bytes()
    data = bytearray(b"".join(blocks))
    data[40:42] = (4321).to_bytes(2, "little")
    new = [bytes(data[i : i + 4]) for i in range(0, 512, 4)]
    _, status, rcs, rc1, _ = m.download(1, TableKind.CONFIG, new, transfer=2)
    assert status == 0 and rcs == [0] * 128 and rc1 == 0
    r.step(2)
    assert r.dev.config["Speed"] == 4321 and r.has(S3.Reset)
    assert r.dev.mailbox.tables.config_user == bytes(data)
    # T2: a data set of another ConfVersion is rejected - and the warm start happens anyway
    quit_reset(r)
    data[2] = 3
    data[40:42] = (1111).to_bytes(2, "little")
    bad = [bytes(data[i : i + 4]) for i in range(0, 512, 4)]
    assert m.download(1, TableKind.CONFIG, bad, transfer=2)[3] == 0x31
    r.step(2)
    assert r.dev.config["Speed"] == 4321 and r.has(S3.Reset)


def test_configuration_download_with_a_wrong_version_is_rejected():
    r, m = module(mailbox_mode=False)
    data = bytearray(r.dev.config.to_bytes())
    data[2] = 5
    blocks = [bytes(data[i : i + 4]) for i in range(0, 512, 4)]
    assert m.download(0, TableKind.CONFIG, blocks, transfer=2)[3] == 0x31  # location 0 = RAM1 (T13)
    assert r.dev.config["ConfVersion"] == 4
