"""The mailbox: toggle handshake, every opcode's request/reply layout, mailbox move mode
(manual §3.7.4, §3.8, §4.2, §4.3; wago.md §3.7 - §3.9, §7.9, §7.10, §9.12).

`Mbx` is the PLC side used by the other test files of the second engineer's parts too.
"""

from __future__ import annotations

from axisline.devices.wago672.bits import Bit
from axisline.devices.wago672.errors import WagoError
from axisline.devices.wago672.image import C0, C1, S0, S1, S2, S3
from axisline.devices.wago672.mailbox import MbxOpcode as Op
from axisline.devices.wago672.mailbox import attach, build_request
from axisline.devices.wago672.program import Cmd
from axisline.devices.wago672.tables import byte_sum

from .rig import Rig


class Mbx:
    """The PLC side of the mailbox: one request per call, waiting for the mirrored toggle."""

    def __init__(self, rig: Rig) -> None:
        self.r = rig
        self.t = 0
        rig.c0 |= C0.MBX

    def __call__(self, opcode: int, *params: int, limit: int = 3) -> tuple[int, bytes]:
        self.t ^= 1
        r = self.r
        r.data = build_request(opcode, self.t, *params) + b"\x00"
        want = 0x80 if self.t else 0
        r.until(lambda: r.has(S0.MBX) and r.inp.mailbox_reply[0] == opcode and r.inp.mailbox_reply[1] & 0x80 == want, limit)
        reply = r.inp.mailbox_reply
        return reply[1] & 0x7F, bytes(reply[2:6])

    def drive(self, cmd: int, *data: int) -> int:
        """DRIVE_COMMAND; returns the return code."""
        return self(Op.DRIVE_COMMAND, cmd, *data)[0]

    def u32(self, opcode: int, value: int) -> tuple[int, bytes]:
        return self(opcode, *(value & 0xFFFFFFFF).to_bytes(4, "little"))

    def download(self, location: int, kind: int, blocks: list[bytes], transfer: int = 0, checksum: int | None = None,
                 count: int | None = None) -> tuple[int, int, list[int], int, bytes]:
        """DLD_START, DLD_CONT per block, DLD_END: (start rc, start status, DLD_CONT rcs, end rc, end reply)."""
        n = len(blocks) // 2 if transfer in (2, 3) and kind in (1, 2) else len(blocks)
        n = n if count is None else count
        rc0, rep0 = self(Op.DLD_START, location, kind, n & 0xFF, transfer << 4 | n >> 8)
        rcs = [self(Op.DLD_CONT, *b)[0] for b in blocks]
        rc1, rep1 = self.u32(Op.DLD_END, byte_sum(blocks) if checksum is None else checksum)
        return rc0, rep0[0], rcs, rc1, rep1

    def upload(self, location: int, kind: int, count: int, transfer: int = 3) -> tuple[int, list[bytes], bytes]:
        rc, rep = self(Op.DLD_START, location, kind, count & 0xFF, transfer << 4 | count >> 8)
        if rc:
            return rc, [], b""
        blocks = []
        per = 2 if transfer == 3 and kind in (1, 2) else 1
        for _ in range(count * per):
            rc, data = self(Op.DLD_CONT)
            assert rc == 0
            blocks.append(data)
        rc, end = self(Op.DLD_END)
        return rc, blocks, end


def d24(value: int) -> tuple[int, int, int]:
    return tuple((value & 0xFFFFFF).to_bytes(3, "little"))  # type: ignore[return-value]


def module(eeprom=None, mailbox_mode: bool = True, **values) -> tuple[Rig, Mbx]:
    """A rig with the mailbox, tables, programs, filters and recorder attached; enabled."""
    values.setdefault("Freq_Div", 10)  # 8 microsteps/s per speed unit: short tests
    r = Rig(**values)
    attach(r.dev, eeprom)
    m = Mbx(r)
    r.enable()
    if mailbox_mode:
        r.select(C1.M_DriveByMbx)
    return r, m


# ---------------------------------------------------------------- handshake


def test_toggle_handshake_executes_a_request_once_and_mirrors_the_toggle():
    r, m = module()
    mbx = r.dev.mailbox
    before = mbx.executed
    rc, _ = m(Op.IDLE)
    assert rc == 0 and mbx.executed == before + 1
    r.step(5)  # the same opcode and toggle: nothing new is executed
    assert mbx.executed == before + 1
    # "data is also accepted if an opcode is specified which differing from the previous one"
    r.data = build_request(Op.DIAG_RD_BIT, m.t, Bit.Input1) + b"\x00"
    r.step()
    assert mbx.executed == before + 2 and r.inp.mailbox_reply[:3] == bytes([Op.DIAG_RD_BIT, 0x80 if m.t else 0, 1])
    # switching the mailbox off and on does not execute the request again (M1)
    r.c0 = 0
    r.step(2)
    assert not r.has(S0.MBX)
    r.c0 = C0.MBX
    r.step(2)
    assert r.has(S0.MBX) and mbx.executed == before + 2


def test_toggle_handshake_first_request_after_power_on():
    # M1: after power-on the last opcode is IDLE with toggle 0: IDLE with toggle 0 does nothing,
    # any other opcode (or toggle 1) is executed
    r = Rig()
    attach(r.dev)
    r.c0 = C0.MBX
    r.data = build_request(Op.IDLE, 0) + b"\x00"
    r.step()
    assert r.dev.mailbox.executed == 0 and r.has(S0.MBX)
    r.data = build_request(Op.DIAG_RD_VAR, 0, 9) + b"\x00"
    r.step()
    assert r.dev.mailbox.executed == 1 and r.inp.mailbox_reply == bytes([Op.DIAG_RD_VAR, 0x00, 8, 0, 0, 0])


def test_mailbox_move_exchange_of_wago_md_9_12():
    # wago.md §9.12 "Mailbox MOVE": C0 = 0x20, MB0 = 0x40, MB1 = 0x80, MB2 = 0x02, MB3..5 = 29 FE 00,
    # C1 = 0x83 -> S0 = 0x20, MB0 = 0x40, MB1 = 0x80, MB2 = 0x02, S1 = 0x83; a second MOVE before
    # On_Target -> MB1 = 0x00 | 0x12 after toggling back
    r = Rig(Freq_Div=10)
    attach(r.dev)
    r.c0 = C0.MBX
    r.c1 = 0x83
    r.step(3)
    assert r.s1 == 0x83
    out = bytes([0x20, 0, 0x40, 0x80, 0x02, 0x29, 0xFE, 0x00, 0, 0, 0, 0x83])
    r.data = out[2:9]
    assert r.out().to_bytes() == out
    r.step()
    raw = r.inp.to_bytes()
    assert raw[0] == 0x20 and raw[2:5] == bytes([0x40, 0x80, 0x02]) and raw[11] == 0x83
    assert raw[5:8] == bytes([0x29, 0xFE, 0x00])  # M3: Data 1..3 echoed
    r.data = bytes([0x40, 0x00, 0x02, 0x00, 0x00, 0x00, 0x00])
    r.step()
    assert r.inp.mailbox_reply[1] == 0x12
    r.until(lambda: r.has(S2.On_Target), 20000)
    assert r.dev.actual_position == 65065


def test_undefined_opcodes_are_unknown_commands():
    r, m = module()
    for opcode in (0x01, 0x3F, 0x47, 0x4B, 0x55, 0x5B, 0x60, 0xFF):
        assert m(opcode)[0] == 0x13
    assert r.error == 0  # M2: no device error


# ---------------------------------------------------------------- DRIVE_COMMAND and mailbox move mode


def test_drive_command_needs_the_mailbox_move_mode():
    r, m = module(mailbox_mode=False)
    assert m.drive(Cmd.SET_VELOCITY, 0x10, 0x27) == 0x23
    assert m.drive(Cmd.WR_BIT, Bit.UserBit_0, 1) == 0x23
    assert m.drive(Cmd.VAR_SET, 1, 5, 0) == 0x23
    r.select(C1.M_Positioning)
    assert m.drive(Cmd.MOVE, *d24(100)) == 0x23
    assert r.error == 0


def test_every_move_command_through_the_mailbox():
    # §4.3.4.1: the setting commands, MOVE/MOVE_IMMEDIATE/MOVE_REL, SPEED/SPEED_IMMEDIATE,
    # STOP_FAST/STOP_NO_RAMP, SET_ACTUALPOSITION(_ZERO), SET_CURRENT, START_REFERENCING
    r, m = module(Acceleration_Stop_Fast=30000)
    dev = r.dev
    assert m.drive(Cmd.SET_ACC_MODE, 0x00) == 0
    assert m.drive(Cmd.SET_ACC, 0xFF, 0x7F, 0) == 0 and dev.acc_up == dev.acc_down == 32767
    assert m.drive(Cmd.SET_ACC, 0x10, 0x27, 2) == 0 and (dev.acc_up, dev.acc_down) == (32767, 10000)
    assert m.drive(Cmd.SET_ACC_PARAM_UP, *d24(500)) == 0 and dev.param_up == 500
    assert m.drive(Cmd.SET_ACC_PARAM_DOWN, *d24(600)) == 0 and dev.param_down == 600
    assert m.drive(Cmd.SET_VELOCITY, 0x10, 0x27) == 0 and dev.velocity == 10000
    assert m.drive(Cmd.SET_VELOCITY_TARGET, 0, 0) == 0
    assert m.drive(Cmd.SET_CURRENT, 80, 0b0100) == 0
    assert m.drive(Cmd.MOVE, *d24(20000)) == 0
    r.step(5)
    assert m.drive(Cmd.MOVE, *d24(0)) == 0x12  # not accepted while the move runs
    assert m.drive(Cmd.MOVE_IMMEDIATE, *d24(30000)) == 0  # interrupts
    r.until(lambda: r.has(S2.On_Target), 20000)
    assert dev.actual_position == 30000
    assert m.drive(Cmd.MOVE_REL, *d24(-5000)) == 0
    r.until(lambda: r.has(S2.On_Target), 20000)
    assert dev.actual_position == 25000
    assert m.drive(Cmd.SPEED, *d24(-3000)[:2]) == 0
    r.until(lambda: r.has(S2.On_Target), 20000)
    assert dev.actual_velocity == -3000
    assert m.drive(Cmd.SPEED_IMMEDIATE, 0xB8, 0x0B) == 0  # +3000 at once
    r.step(3)
    assert m.drive(Cmd.STOP_FAST) == 0
    r.until(lambda: r.has(S2.StandStill), 20000)
    assert m.drive(Cmd.SET_ACTUALPOSITION, *d24(-1000)) == 0 and dev.actual_position == -1000
    assert m.drive(Cmd.SET_ACTUALPOSITION_ZERO) == 0 and dev.actual_position == 0
    assert m.drive(Cmd.SPEED_IMMEDIATE, 0xB8, 0x0B) == 0
    r.step(20)
    assert m.drive(Cmd.STOP_NO_RAMP) == 0
    r.step()
    assert r.has(S2.StandStill)
    r.inputs["Input6"] = lambda: r.x <= -3000  # the negative limit switch
    assert m.drive(Cmd.START_REFERENCING, 0, 0, 0b001) == 0  # SWT 1 limit switch, STD 0: negative
    r.step()
    assert r.has(S2.Busy) and not r.has(S2.Reference_OK)
    r.until(lambda: r.has(S2.Reference_OK), 20000)
    assert r.error == 0 and not r.has(S2.On_Target)


def test_unknown_and_750_673_move_commands():
    r, m = module()
    assert m.drive(Cmd.TORQ, 0x10, 0x00, 50) == 0x13 and r.error == 1114  # wago.md §3.9 [RECONSTRUCTED]
    m(Op.DIAG_QUIT_ERROR)
    r.step()
    assert r.error == 0
    r.select(C1.M_DriveByMbx)
    assert m.drive(0x30) == 0x13 and r.error == 1112


def test_var_and_wr_bit_through_drive_command():
    r, m = module(Filter3_Function=7)
    dev = r.dev
    assert m.drive(Cmd.WR_BIT, Bit.UserBit_0, 1) == 0 and dev.bits.read(Bit.UserBit_0)
    assert m.drive(Cmd.WR_BIT, Bit.UserBit_0, 0) == 0 and not dev.bits.read(Bit.UserBit_0)
    assert m.drive(Cmd.VAR_SET, 3, 0xFF, 0xFF) == 0 and r.dev.mailbox.filters.value(3) == -1
    assert m.drive(Cmd.NOP) == 0
    for cmd in (Cmd.WAIT_TIME, Cmd.WAIT_TEST_BIT, Cmd.GOTO, Cmd.LABEL, Cmd.PROG_STOP, Cmd.PROG_END):
        assert m.drive(cmd) == 0x12  # M4: table processing only
    assert r.error == 0
    assert m.drive(Cmd.WR_BIT, Bit.OUT1, 1) == 0x01 and r.error == 1242  # wago.md §9.9
    m(Op.DIAG_QUIT_ERROR)
    r.step()
    r.select(C1.M_DriveByMbx)
    assert m.drive(Cmd.WR_BIT, Bit.On_Target, 1) == 0x01 and r.error == 1243  # a source bit
    m(Op.DIAG_QUIT_ERROR)
    r.step()
    r.select(C1.M_DriveByMbx)
    assert m.drive(Cmd.VAR_SET, 1, 5, 0) == 0x01 and r.error == 1248  # FILT1 has function 0
    m(Op.DIAG_QUIT_ERROR)
    r.step()
    r.select(C1.M_DriveByMbx)
    assert m.drive(Cmd.VAR_INC, 9, 1, 0) == 0x01 and r.error == 1247


# ---------------------------------------------------------------- diagnosis


def test_diag_rd_error_and_quit():
    r, m = module()
    r.dev.raise_error(1413, "test: overcurrent")
    r.step()
    assert not r.has(S1.Ready)
    assert m(Op.DIAG_RD_ERROR) == (0, bytes([0x85, 0x05, 0, 0]))  # wago.md §9.12: 1413 = 0x0585
    assert m(Op.DIAG_QUIT_ERROR)[0] == 0
    r.step()
    assert r.error == 0 and r.has(S1.Ready)
    assert m(Op.DIAG_RD_ERROR) == (0, bytes(4))


def test_diag_quit_error_of_a_2xxx_error_warm_starts_once():
    r, m = module()
    r.c3 = 0x80  # Reset_Quit
    r.step(2)
    r.c3 = 0
    r.step()
    assert not r.has(S3.Reset)
    r.dev.raise_error(2821, "test")
    executed = r.dev.mailbox.executed
    m(Op.DIAG_QUIT_ERROR)
    r.step(5)
    assert r.dev.mailbox.executed == executed + 1  # M1: not executed again after the warm start
    assert r.has(S3.Reset) and r.error == 0 and r.has(S0.MBX)


def test_diag_rd_var_and_rd_bit():
    r, m = module()
    r.inputs["Input1"] = True
    assert m(Op.DIAG_RD_BIT, 0x30) == (0, bytes([1, 0, 0, 0]))  # wago.md §9.12
    assert m(Op.DIAG_RD_BIT, Bit.Stop1_N) == (0, bytes([1, 0, 0, 0]))  # wago.md §9.9
    assert m.u32(Op.DIAG_RD_VAR, 0x1030) == (0, bytes([1, 0, 0, 0]))  # M5: 32-bit number
    assert m(Op.DIAG_RD_VAR, 9) == (0, bytes([8, 0, 0, 0]))  # hardware version 750-672
    assert m(Op.DIAG_RD_VAR, 15) == (0, bytes([4, 0, 0, 0]))
    assert m.u32(Op.DIAG_RD_VAR, 0x40000000) == (0, bytes(4))
    m.drive(Cmd.SET_ACTUALPOSITION, *d24(-1000))
    assert m(Op.DIAG_RD_VAR, 1) == (0, (-1000 & 0xFFFFFFFF).to_bytes(4, "little"))
    assert m(Op.DIAG_QUERY_STORAGE) == (0, bytes(4))


def test_diag_rd_bit_of_a_too_deep_link_raises_1245():
    r, m = module(mailbox_mode=False)
    r.dev.config.update({"Ptr_OUT1": 0x98, "Ptr_UserBit_0": 0x99, "Ptr_UserBit_1": 0x9A, "Ptr_UserBit_2": 0x9B, "Ptr_UserBit_3": 0x9C})
    rc, rep = m(Op.DIAG_RD_BIT, Bit.OUT1)
    assert rc == 0 and rep[0] == 0 and r.error == 1245


# ---------------------------------------------------------------- configuration access


def test_config_access_example_of_wago_md_9_12():
    # Freq_Div := 80 with Enable = 0: CONFIG_SET_PTR 04 00 02, CONFIG_WR 50 00, CONFIG_RD 04 00 02 -> 50 00
    r = Rig()
    attach(r.dev)
    m = Mbx(r)
    assert m(Op.CONFIG_SET_PTR, 0x04, 0x00, 0x02) == (0, bytes(4))
    assert m(Op.CONFIG_WR, 0x50, 0x00, 0xAA, 0xBB) == (0, bytes(4))  # MB4/MB5 ignored
    assert m(Op.CONFIG_RD, 0x04, 0x00, 2) == (0, bytes([0x50, 0, 0, 0]))
    assert r.dev.config["Freq_Div"] == 80 and r.dev.config.read_bytes(6, 2) == (1000).to_bytes(2, "little")
    r.step()
    assert r.dev.scaling.prescaler == 80  # latched while Enable = 0


def test_config_access_errors():
    r, m = module(mailbox_mode=False)
    assert m(Op.CONFIG_WR, 1, 2, 3, 4)[0] == 0x23  # no pointer yet
    assert m(Op.CONFIG_SET_PTR, 0x00, 0x02, 2)[0] == 0x23  # 512 + 2 > 512
    assert r.error == 0
    assert m(Op.CONFIG_SET_PTR, 40, 0, 2)[0] == 0  # Speed, 1 .. 25000
    assert m(Op.CONFIG_WR, 0, 0)[0] == 0x23 and r.dev.config["Speed"] == 3000  # M6: out of range
    assert m(Op.CONFIG_WR, 0x88, 0x13)[0] == 0 and r.dev.config["Speed"] == 5000
    assert m(Op.CONFIG_RD, 40, 0, 0) == (0, bytes(4))  # invalid size: 0
    assert m(Op.CONFIG_RD, 0xFF, 0x01, 4) == (0, bytes(4))
    assert m(Op.CONFIG_SET_PTR, 40, 0, 5)[0] == 0x23 and r.error == 1161


def test_relinking_through_the_mailbox_jog_direction_example():
    # §3.10.4 example (wago.md §5.2 [RECONSTRUCTED] complete solution): Input2 as the jog direction,
    # "1" = positive: Ptr_Direction_Pos := Input2, Ptr_FILT1 := Input2, Filter1_Function := 1
    # (inversion), Ptr_Direction_Neg := FILT1, Ptr_Set_Reference := ZERO
    r, m = module(mailbox_mode=False, SetupSpeed=1000, SetupAcceleration=30000)
    for address, value in ((186, 0x31), (168, 0x31), (224, 1), (187, 0xA8), (188, 0x00)):
        assert m(Op.CONFIG_SET_PTR, address, 0, 1)[0] == 0
        assert m(Op.CONFIG_WR, value)[0] == 0
    bits = r.dev.bits
    r.inputs["Input2"] = False
    r.step()
    assert bits.read(Bit.Direction_Neg) and not bits.read(Bit.Direction_Pos) and not bits.read(Bit.Set_Reference)
    r.select(C1.M_Jog)
    r.step(100)
    assert r.dev.velocity_steps < 0
    r.inputs["Input2"] = True
    r.step(300)
    assert r.dev.velocity_steps > 0 and bits.read(Bit.Direction_Pos) and not bits.read(Bit.Direction_Neg)


def test_writes_of_the_bit_table_raise_their_codes():
    r, m = module()
    t = r.dev.bits
    for n, code in ((Bit.On_Target, 1243), (0xE0, 1243), (Bit.Enable, 1242)):
        try:
            t.write(n, True)
        except WagoError as e:
            assert e.code == code
        else:  # pragma: no cover
            raise AssertionError(n)
