"""Run programs: command encoding, the interpreter, Start_Instruction_Counter, the move command
manager, autostart (manual §3.10.5, §3.11.1.7, §4.3; wago.md §3.9, §5.6 - §5.8, §9.10)."""

from __future__ import annotations

import pytest

from axisline.devices.wago672.bits import Bit
from axisline.devices.wago672.config_table import ConfigTable
from axisline.devices.wago672.image import C1, S1, S2, S3, ProgramSetpoints
from axisline.devices.wago672.mailbox import MbxOpcode as Op
from axisline.devices.wago672.mailbox import attach
from axisline.devices.wago672.program import Cmd, Line, encode_program
from axisline.devices.wago672.tables import TableKind, byte_sum

from .rig import Rig
from .test_mailbox import Mbx, module

# wago.md §9.10 (manual §3.11.1.7.3), the rows as printed: opcode, Data LSB, Data, Data MSB
EXAMPLE = [
    bytes([0x25, 0x20, 0x4E, 0x00]),
    bytes([0x22, 0xB8, 0x0B, 0x00]),
    bytes([0x71, 0x30, 0x01, 0x00]),
    bytes([0x02, 0x20, 0xFE, 0x00]),
    bytes([0x71, 0x30, 0x00, 0x00]),
    bytes([0x02, 0x00, 0x00, 0x00]),
    bytes([0xF5, 0x02, 0x00, 0x00]),
    bytes([0x70, 0xD0, 0x07, 0x00]),
]


def load(m: Mbx, lines: list[Line], location: int = 1) -> None:
    _, status, rcs, rc, _ = m.download(location, TableKind.PROGRAM, encode_program(lines))
    assert status == 0 and rcs == [0] * len(lines) and rc == 0
    if location != 1:
        assert m(Op.TABLE_START, location, 1)[0] == 0


def run(r: Rig, address: int = 0, ack: bool = True) -> None:
    """Select the Run program mode (mailbox image off) and start at `address` (ack: wait for
    Start_ACK; a program that fails in its first tick loses Ready and gives none)."""
    r.c0 = 0
    r.data = ProgramSetpoints(address).encode()
    if not r.has(S1.M_Program_ACK):
        r.select(C1.M_Program)
    if ack:
        r.start()
    else:
        r.c1 |= C1.Start
        r.step()
        r.c1 &= ~C1.Start


def program(r: Rig):
    return r.dev.mailbox.program


def test_run_command_encodings():
    # wago.md §9.10 rows: 0x004E20 = 20000, 0x000BB8 = 3000 (SEL 0), bit 0x30 = Input1, 0x00FE20 = 65056
    decoded = [Line.decode(b) for b in EXAMPLE]
    assert decoded == [
        Line(Cmd.SET_VELOCITY, 20000), Line(Cmd.SET_ACC, 3000, 0), Line(Cmd.WAIT_TEST_BIT, Bit.Input1, 1),
        Line(Cmd.MOVE, 65056), Line(Cmd.WAIT_TEST_BIT, Bit.Input1, 0), Line(Cmd.MOVE, 0), Line(Cmd.GOTO, 2),
        Line(Cmd.WAIT_TIME, 2000),
    ]
    assert encode_program(decoded) == EXAMPLE
    assert byte_sum(EXAMPLE) == 0x61B  # wago.md §9.10 [DERIVED] checksum of the download
    assert Line(Cmd.MOVE, -1000).encode() == bytes([0x02, 0x18, 0xFC, 0xFF])  # wago.md §9.12: 0xFFFC18
    assert Line(Cmd.VAR_SET, 3, -1).encode() == bytes([0x50, 3, 0xFF, 0xFF])
    assert Line(Cmd.GOTO_IF, 300, Bit.UserBit_0).encode() == bytes([0xF6, 0x2C, 0x01, 0x98])
    assert Line(Cmd.START_REFERENCING, 0, 0, 0b110).encode() == bytes([0x20, 0, 0, 6])
    assert Line(Cmd.SPEED, -2000).encode() == bytes([0x10, 0x30, 0xF8, 0x00])
    assert Line(Cmd.WAIT_TIME, 16777215).encode() == bytes([0x70, 0xFF, 0xFF, 0xFF])
    assert Line.decode(bytes([0xFF, 0, 0, 0])) == Line(Cmd.PROG_END_FF)
    for cmd in Cmd:
        line = Line(cmd)
        assert Line.decode(line.encode()) == line
    with pytest.raises(ValueError):
        Line(0x30)
    with pytest.raises(ValueError):
        Line(Cmd.MOVE, 8388608)
    with pytest.raises(ValueError):
        Line(Cmd.WAIT_TIME, -1)


def test_run_program_example_of_the_manual():
    # wago.md §9.10: velocity 20000, acceleration 3000; wait for Input1 = 1, move to 65056 (P3: the
    # printed bytes), wait for Input1 = 0, move to 0, go to line 2 (P1: 0-based). Input1 is Stop1_N by
    # default: Stop1_N is linked to ONE so that Input1 is free for the program.
    r, m = module(mailbox_mode=False, Ptr_Stop1_N=Bit.ONE)
    r.inputs["Input1"] = False
    _, status, rcs, rc, end = m.download(1, TableKind.PROGRAM, EXAMPLE)
    assert (status, rcs, rc, end) == (0, [0] * 8, 0, bytes([0x1B, 0x06, 0, 0]))
    assert m(Op.TABLE_GET_ACTIVE, 1)[1][0] == 1  # RAM1 activated by DLD_END
    run(r)
    assert r.has(S1.M_Program_ACK) and r.dev.bits.read(Bit.Program_Running) and r.dev.leds()["C"]
    r.step(5)
    assert r.inp.program().counter == 2 and r.dev.velocity == 20000 and (r.dev.acc_up, r.dev.acc_down) == (3000, 3000)
    assert r.dev.standstill
    r.inputs["Input1"] = True
    r.step(3)
    assert r.has(S2.Busy) and r.inp.program().counter == 4
    r.inputs["Input1"] = False  # line 5 (MOVE 0) waits until the move to 65056 has ended
    r.step(3)
    assert r.inp.program().counter == 5
    r.until(lambda: r.dev.actual_position == 65056, 5000)
    r.until(lambda: r.inp.program().counter == 6, 5)  # MOVE 0 started
    r.step()
    assert r.has(S2.Busy) and r.inp.program().counter == 2  # GOTO 2: waiting for Input1 again
    r.until(lambda: r.has(S2.On_Target), 5000)
    assert r.dev.actual_position == 0 and r.inp.program().counter == 2 and r.error == 0
    assert r.dev.state_variable(41) == 2 and r.dev.state_variable(40) == Cmd.WAIT_TEST_BIT


def test_wait_time_and_wr_bit():
    r, m = module(mailbox_mode=False)
    load(m, [Line(Cmd.WAIT_TIME, 50), Line(Cmd.WR_BIT, Bit.UserBit_0, 1), Line(Cmd.WAIT_TIME, 0),
             Line(Cmd.WR_BIT, Bit.UserBit_0 + 1, 7), Line(Cmd.PROG_STOP)])
    run(r, ack=False)  # the Start edge and the first lines in one tick
    start = r.cycle
    r.until(lambda: r.dev.bits.read(Bit.UserBit_0), 100)
    assert r.cycle - start == 50  # P8: WAIT_TIME n lets the next line run n ticks later
    r.step()
    assert r.dev.bits.read(Bit.UserBit_0 + 1) and not program(r).running and r.error == 0
    assert not r.dev.bits.read(Bit.Program_Running)


def test_labels_and_conditional_jumps_with_a_counter():
    # a loop of three MOVE_REL 100 counted down in FILT1 (math); each MOVE_REL waits for the last one
    r, m = module(mailbox_mode=False, Filter1_Function=7)
    load(m, [
        Line(Cmd.SET_VELOCITY, 1000),
        Line(Cmd.VAR_SET, 1, 3),
        Line(Cmd.LABEL, 7),
        Line(Cmd.MOVE_REL, 100),
        Line(Cmd.VAR_DEC, 1, 1),
        Line(Cmd.GOTO_LABEL_IF, 7, Bit.FILT1),
        Line(Cmd.GOTO_IF_NOT, 8, Bit.FILT1),
        Line(Cmd.PROG_STOP, 1),  # not reached
        Line(Cmd.LABEL, 9),
        Line(Cmd.LABEL, 7),  # a second label 7: the lowest one is valid (P2)
        Line(Cmd.WAIT_TEST_BIT, Bit.On_Target, 1),
        Line(Cmd.PROG_STOP, 0),
    ])
    run(r)
    r.until(lambda: not program(r).running, 5000)
    assert r.error == 0 and r.dev.actual_position == 300 and r.dev.mailbox.filters.value(1) == 0


def test_a_missing_label_and_jumps_out_of_the_table():
    r, m = module(mailbox_mode=False)
    load(m, [Line(Cmd.GOTO_LABEL, 5)])
    run(r, ack=False)
    assert r.error == 1322 and not program(r).running
    for lines, code in (([Line(Cmd.GOTO, 400)], 1323), ([Line(Cmd.GOTO_IF, 500, Bit.ONE)], 1323),
                        ([Line(Cmd.NOP), Line(Cmd.PROG_END)], 1319)):
        r, m = module(mailbox_mode=False)
        load(m, lines)
        run(r, ack=False)
        r.step(2)
        assert r.error == code


def test_start_without_a_program_and_beyond_the_table():
    r, m = module(mailbox_mode=False)
    r.c0 = 0
    r.select(C1.M_Program)
    r.c1 |= C1.Start
    r.step(2)
    assert r.error == 1352
    r, m = module(mailbox_mode=False)
    load(m, [Line(Cmd.NOP)])
    r.c0 = 0
    r.data = ProgramSetpoints(400).encode()
    r.select(C1.M_Program)
    r.c1 |= C1.Start
    r.step(2)
    assert r.error == 1323


def test_prog_end_and_prog_stop():
    # P5: PROG_STOP 0 ends without error (output stage on); 1..8 -> 1311..1318; 9 -> 1321; PROG_END -> 1319
    r, m = module(mailbox_mode=False, Acceleration_Stop_Fast=3000)
    load(m, [Line(Cmd.SPEED_IMMEDIATE, 2000), Line(Cmd.WAIT_TIME, 100), Line(Cmd.PROG_STOP, 0)])
    run(r)
    r.step(102)
    assert not program(r).running and r.error == 0 and r.dev.stopping  # braked with STOP_FAST
    r.until(lambda: r.has(S2.StandStill), 2000)
    assert r.has(S1.Ready)
    for message, code in ((1, 1311), (3, 1313), (7, 1317), (8, 1318), (9, 1321)):
        r, m = module(mailbox_mode=False)
        load(m, [Line(Cmd.PROG_STOP, message)])
        run(r, ack=False)
        assert r.error == code and not program(r).running and not r.has(S1.Ready)
    r, m = module(mailbox_mode=False)
    load(m, [Line(Cmd.NOP)])  # line 1 is blank: PROG_END
    run(r, ack=False)
    assert r.error == 1319


def test_an_endless_goto_loop_runs_16_lines_a_tick():
    # P4
    r, m = module(mailbox_mode=False, Filter4_Function=7)
    load(m, [Line(Cmd.VAR_INC, 4, 1), Line(Cmd.GOTO, 0)])
    run(r)
    filters = r.dev.mailbox.filters
    before = filters.value(4)
    r.step()
    assert filters.value(4) - before == 8
    assert r.has(S1.Ready)


def test_program_errors_end_the_program():
    r, m = module(mailbox_mode=False)
    load(m, [Line(Cmd.WR_BIT, Bit.OUT1, 1)])
    run(r, ack=False)
    assert r.error == 1242 and not program(r).running and not r.dev.bits.read(Bit.Program_Running)
    r, m = module(mailbox_mode=False)
    load(m, [Line(Cmd.VAR_DIV, 1, 1, 1)])
    run(r, ack=False)
    assert r.error == 1248


def test_start_edge_restarts_at_the_new_address():
    # P6: Start during a running program: braked, restarted at the address in D2..D3
    r, m = module(mailbox_mode=False, Acceleration_Stop_Fast=20000)
    load(m, [Line(Cmd.SET_VELOCITY, 2000), Line(Cmd.MOVE, 200000), Line(Cmd.WAIT_TIME, 100000),
             Line(Cmd.NOP), Line(Cmd.NOP),
             Line(Cmd.MOVE, -3000), Line(Cmd.WAIT_TEST_BIT, Bit.On_Target, 1), Line(Cmd.PROG_STOP)])
    run(r)
    r.step(300)
    assert r.has(S2.Busy) and r.inp.program().counter == 2
    r.data = ProgramSetpoints(5).encode()
    r.c1 |= C1.Start
    r.step()
    assert r.has(S1.Start_ACK) and r.dev.stopping and r.inp.program().counter == 5
    r.c1 &= ~C1.Start
    r.until(lambda: not program(r).running, 10000)
    assert r.dev.actual_position == -3000 and r.error == 0


def test_a_stop_ramp_is_not_interrupted_by_the_program():
    # P7: crossing Drive_Range_Pos brakes with Acceleration_Stop_Fast (device D9); the program's
    # MOVE_IMMEDIATE back waits for standstill instead of interrupting the braking
    r, m = module(mailbox_mode=False, Drive_Range_Pos=20000, Acceleration_Stop_Fast=1000)
    load(m, [Line(Cmd.SET_VELOCITY, 3000), Line(Cmd.MOVE, 100000), Line(Cmd.WAIT_TEST_BIT, Bit.Err_Range_Pos, 1),
             Line(Cmd.MOVE_IMMEDIATE, 0), Line(Cmd.WAIT_TEST_BIT, Bit.On_Target, 1), Line(Cmd.PROG_STOP)])
    run(r)
    r.until(lambda: r.dev.bits.read(Bit.Err_Range_Pos), 20000)
    r.step()  # the program sees the bit in its next tick
    braking = 0
    while r.dev.stopping:
        assert r.inp.program().counter == 3 and r.dev.velocity_steps >= 0
        braking += 1
        r.step()
    assert braking > 10
    r.until(lambda: not program(r).running, 20000)
    assert r.dev.actual_position == 0 and r.error == 0


def test_a_move_the_drive_refuses_is_1115():
    # P7: outside the software limits a move further out is refused without an error code (D9)
    r, m = module(mailbox_mode=False, Drive_Range_Pos=1000)
    load(m, [Line(Cmd.SET_ACTUALPOSITION, 2000), Line(Cmd.MOVE, 3000)])
    run(r, ack=False)
    r.step(2)
    assert r.error == 1115 and not program(r).running


def test_table_stop_ends_the_program_and_brakes():
    r, m = module(mailbox_mode=False, Acceleration_Stop_Fast=3000)
    load(m, [Line(Cmd.SPEED_IMMEDIATE, 2000), Line(Cmd.WAIT_TIME, 100000)])
    run(r)
    r.step(200)
    m.r.c0 = 0x20  # the mailbox beside the Run program mode
    assert m(Op.TABLE_START, 2, 1)[0] == 0x31  # not while the program runs (T6)
    assert m(Op.TABLE_STOP) == (0, bytes(4))
    assert not program(r).running and r.dev.stopping
    r.until(lambda: r.has(S2.StandStill), 5000)
    assert r.error == 0 and m(Op.TABLE_GET_ACTIVE, 1)[1][0] == 1  # the table stays active
    assert m(Op.TABLE_STOP) == (0, bytes(4))  # nothing to end


def test_leaving_the_mode_stops_the_program():
    r, m = module(mailbox_mode=False)
    load(m, [Line(Cmd.WAIT_TIME, 100000)])
    run(r)
    r.step(3)
    assert program(r).running
    r.c1 &= ~C1.M_Program
    r.step(2)
    assert not program(r).running and not r.has(S1.M_Program_ACK)


# ---------------------------------------------------------------- autostart (wago.md §5.7)


def autostart_module(tmp_path, lines: list[Line] | None, **values) -> tuple[Rig, Mbx]:
    """A module whose EEPROM holds `lines` and a configuration with Program_Autostart."""
    path = tmp_path / "auto.eeprom.json"
    path.unlink(missing_ok=True)
    cfg = ConfigTable()
    cfg.update({"HwSwConfig": 0x80, "Freq_Div": 10, **values})
    r = Rig(cfg)
    mbx = attach(r.dev, path)
    m = Mbx(r)
    if lines is not None:
        load(m, lines)
        assert m(Op.TABLE_COPY, 1, 1, 0)[0] == 0
    assert m.u32(Op.CONFIG_SAVE, 1)[0] == 0  # the configuration with Program_Autostart
    mbx.tables.flush()
    cfg2 = ConfigTable()
    r2 = Rig(cfg2)
    attach(r2.dev, path)  # the power-on: configuration (HwSwConfig bit 7) and program from the EEPROM
    return r2, Mbx(r2)


def test_autostart_runs_the_eeprom_program_once_after_reset(tmp_path):
    r, m = autostart_module(tmp_path, [Line(Cmd.WR_BIT, Bit.UserBit_0, 1), Line(Cmd.SET_VELOCITY, 1000),
                                       Line(Cmd.MOVE, 500), Line(Cmd.WAIT_TEST_BIT, Bit.On_Target, 1),
                                       Line(Cmd.PROG_STOP)])
    r.step(3)
    assert not program(r).running  # not before Ready and Stop_N_ACK
    r.c1 = C1.Enable | C1.Stop2_N
    r.until(lambda: program(r).running, 5)
    r.step()
    assert r.has(S3.Reset) and r.s1 & 0xF8 == 0 and r.dev.bits.read(Bit.Program_Running)
    r.until(lambda: not program(r).running, 5000)
    assert r.dev.actual_position == 500 and r.dev.bits.read(Bit.UserBit_0) and r.error == 0
    r.step(50)
    assert not program(r).running  # "started only one time after each reset"


def test_autostart_ends_with_reset_quit(tmp_path):
    r, m = autostart_module(tmp_path, [Line(Cmd.SPEED_IMMEDIATE, 1000), Line(Cmd.WAIT_TIME, 100000)],
                            Acceleration_Stop_Fast=5000)
    r.c1 = C1.Enable | C1.Stop2_N
    r.step(100)
    assert program(r).running and not r.dev.standstill
    r.c3 = 0x80  # Reset_Quit: "can be ended by canceling Reset"
    r.step(2)
    assert not program(r).running and r.dev.stopping
    r.until(lambda: r.dev.standstill, 2000)
    assert r.error == 0


def test_autostart_cancelled_by_reset_quit_before_ready(tmp_path):
    r, m = autostart_module(tmp_path, [Line(Cmd.WAIT_TIME, 100000)])
    r.c3 = 0x80
    r.step(2)
    r.c1 = C1.Enable | C1.Stop2_N
    r.step(5)
    assert not program(r).running and r.error == 0


def test_autostart_without_a_program_in_the_eeprom_is_1142(tmp_path):
    r, m = autostart_module(tmp_path, None)
    r.c1 = C1.Enable | C1.Stop2_N
    r.step(3)
    assert r.error == 1142


def test_autostart_adopted_by_the_program_mode_and_ended_by_another_mode(tmp_path):
    r, m = autostart_module(tmp_path, [Line(Cmd.WAIT_TIME, 100000)])
    r.c1 = C1.Enable | C1.Stop2_N
    r.until(lambda: program(r).running, 5)
    r.select(C1.M_Program)
    r.step(3)
    assert program(r).running and not program(r).autostarted and r.inp.program().counter == 0
    r.c1 = C1.Enable | C1.Stop2_N
    r.step(3)
    assert not program(r).running
    r, m = autostart_module(tmp_path, [Line(Cmd.WAIT_TIME, 100000)])
    r.c1 = C1.Enable | C1.Stop2_N
    r.until(lambda: program(r).running, 5)
    r.select(C1.M_Positioning)
    r.step()
    assert not program(r).running
