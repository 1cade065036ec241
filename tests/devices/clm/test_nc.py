"""The NC tasks running the manual's programs (chapter 5 and §7.5), without a plant."""

from __future__ import annotations

import pytest

from .clmrig import Rig
from .manual_examples import PROGRAM_LISTINGS


def listing(name: str) -> str:
    import re

    text = next(e["text"] for e in PROGRAM_LISTINGS if e["name"] == name)
    return "\n".join(line for line in text.split("\n") if re.match(r"\s*\d{4}\s", line))


def test_bac_count_following_the_event_positions_10_times():
    """L1546-1553: 'Positioning is executed 10 times, and then the program waits for a new start signal.'"""
    rig = Rig(listing("bac_example_a"))
    rig.run(2)
    rig.start()
    rig.run(6000)  # 10 x (WAI 1 s = 500 cycles of 2 ms, PSI, BAC)
    assert len(rig.axes[1].moves) == 10
    assert not rig.rt.modes.running and rig.rt.tasks[0].pc == 0  # JST 0000: waits for Start
    rig.start()
    rig.run(6000)
    assert len(rig.axes[1].moves) == 20  # the count was back at 0


def test_bac_count_prior_to_the_event_positions_9_times():
    """L1555-1563: 'Positioning is executed 9 times'."""
    rig = Rig(listing("bac_example_b"))
    rig.run(2)
    rig.start()
    rig.run(6000)
    assert len(rig.axes[1].moves) == 9


def test_cou_example_sets_q1_00_4_after_ten_positionings():
    """L1739-1751: 'Positioning is executed ten times. Then, output Q1.00.4 is set and the system
    waits for a new start signal.'"""
    rig = Rig(listing("cou_example"))
    rig.run(2)
    rig.start()
    rig.run(300)  # each part: PSI (3 cycles) + WAI 1 s (500 cycles at 2 ms) ...
    assert rig.bit("Q1.00.4") == 0
    rig.run(6000)
    assert len(rig.axes[1].moves) == 10 and rig.bit("Q1.00.4") == 1
    assert not rig.rt.modes.running and rig.rt.tasks[0].pc == 1


def test_wai_counts_cycles():
    """Decision C-WAI: WAI 00.010 at 2 ms holds its task 5 cycles."""
    rig = Rig("0000 WAI 00.010\n0001 AEA Q1.00.0 1\n0002 JST 0000\n")
    rig.run(1)
    rig.start()  # cycle of the start: WAI reached
    for _ in range(4):
        rig.run()
        assert rig.bit("Q1.00.0") == 0
    rig.run()  # the 5th cycle ends the wait, AEA runs in the next
    rig.run()
    assert rig.bit("Q1.00.0") == 1


def test_four_txt_in_one_cycle():
    """L2756: up to 4 consecutive TXT commands run in one cycle (decision C-TXT)."""
    program = "".join(f"{n:04d} TXT 0 LINE{n}\n" for n in range(5)) + "0005 JST 0000\n"
    rig = Rig(program)
    rig.run(1)
    rig.start()
    assert [t.strip() for t in rig.rt.text_lines] == ["LINE0", "LINE1", "LINE2", "LINE3"]
    assert rig.rt.tasks[0].pc == 4
    rig.run()
    assert rig.rt.text_lines[0].strip() == "LINE4"


def test_a_bit_written_by_task_1_is_seen_by_task_4_in_the_same_cycle():
    """L3472: 'An output set in Task 1 is processed in Task 4 as a set output.'"""
    program = "0000 AEA M2.00.0 1\n0001 JST 0000\n0500 BCE 0502 M2.00.0 1\n0501 JMP 0500\n0502 AEA M2.00.1 1\n0503 JMP 0503\n"
    rig = Rig(program, params={"B012": "0500 0000"})
    rig.run(1)
    rig.start()  # task 1 writes M2.00.0, task 4 reads it in the same cycle and jumps
    assert rig.rt.tasks[3].pc == 502
    program_late = "0000 BCE 0002 M2.00.1 1\n0001 JMP 0000\n0002 JST 0002\n0500 AEA M2.00.1 1\n0501 JMP 0501\n"
    rig = Rig(program_late, params={"B012": "0500 0000"})
    rig.run(1)
    rig.start()  # task 4 writes after task 1 has read: task 1 sees it a cycle later
    assert rig.rt.tasks[0].pc == 1


def test_jsr_rts_and_stack_depth():
    rig = Rig("0000 JSR 0010\n0001 JST 0000\n0010 JSR 0010\n")
    rig.run(1)
    rig.start()
    rig.run(200)
    assert rig.fault == "0B"  # the 128th JSR
    rig = Rig("0000 RTS\n")
    rig.run(1)
    rig.start()
    assert rig.fault == "0C"


def test_running_past_2999_is_0e():
    rig = Rig("2998 NOP\n")
    rig.rt.memory.program.store(__import__("axisline.devices.clm.program", fromlist=["x"]).parse_listing_line("0000 JMP 2998"))
    rig.run(1)
    rig.start()
    rig.run(5)
    assert rig.fault == "0E"


def test_bic_worked_examples():
    """L1588-1620: M2.03.2..0, M2.02.7..0 = 0 1 1 | 0 1 1 0 1 0 1 1 (binary) and 1 0 1 | 0 1 1 0 0 1 1 1 (BCD)."""
    cases = [
        ("0b01101101011", "BIC 0500 11 M2.02.4 5 0", 742),
        ("0b01101101011", "BIC 0300 02 M2.02.2 8 0", 736),
        ("0b10101100111", "BIC 0500 11 M2.02.4 5 1", 676),
        ("0b10101100111", "BIC 0300 02 M2.02.2 8 1", 418),
    ]
    for bits, instruction, target in cases:
        rig = Rig(f"0000 {instruction}\n")
        value = int(bits, 2)
        rig.set("M2.02", value & 0xFF)
        rig.set("M2.03", value >> 8)
        rig.run(1)
        rig.start()
        assert rig.rt.tasks[0].pc == target, instruction


def test_cio_example():
    """L1687-1700: 'CIO I1.01.0 M2.02.0 5' copies I1.01.0-4 (inputs 1 0 1 0 1 0 1 1) -> markers 0000 1011."""
    rig = Rig("0000 CIO I1.01.0 M2.02.0 5\n0001 JST 0001\n")
    rig.set("I1.01", 0b10101011)
    rig.run(1)
    rig.start()
    assert rig.rt.image.get(__import__("axisline.devices.clm.operands", fromlist=["x"]).parse_operand("M2.02", bit=False)) == 0b00001011


@pytest.mark.parametrize(("mask", "before", "after"), [("21002210", 0b00000000, 0b01000010), ("21110002", 0b11111111, 0b11110001)])
def test_ape_examples(mask, before, after):
    """L1520-1534: APE M2.02 21002210 sets bits 1, 6, clears 0, 4, 5; 21110002 sets 4, 5, 6, clears 1, 2, 3."""
    rig = Rig(f"0000 APE M2.02 {mask}\n0001 JST 0001\n")
    rig.set("M2.02", before)
    rig.run(1)
    rig.start()
    from axisline.devices.clm.operands import parse_operand

    got = rig.rt.image.get(parse_operand("M2.02", bit=False))
    changed = {0, 4, 5, 1, 6} if mask == "21002210" else {1, 2, 3, 4, 5, 6}
    assert all(((got >> b) & 1) == ((after >> b) & 1) for b in changed)
    assert all(((got >> b) & 1) == ((before >> b) & 1) for b in set(range(8)) - changed)


def test_bio_example_does_not_jump():
    """L1645-1653: BIO 0123 M2.02 Q1.00 11110000 with bytes 11100010 / 11000010: no jump."""
    rig = Rig("0032 BIO 0123 M2.02 Q1.00 11110000\n")
    rig.rt.memory.program.store(__import__("axisline.devices.clm.program", fromlist=["x"]).parse_listing_line("0000 JMP 0032"))
    rig.set("M2.02", 0b11100010)
    rig.set("Q1.00", 0b11000010)
    rig.run(1)
    rig.start()
    rig.run()
    assert rig.rt.tasks[0].pc == 33


def test_cvt_bcd_fig_5_8():
    """Fig. 5-8 (L1853-1885): V600 = -87654321.654321 -> M2.00..M2.07 = 21 43 65 21 43 65 87 FF."""
    rig = Rig("0000 CVT V600 M2.00 0 0\n0001 CVT V601 M2.00 0 1\n0002 JST 0002\n")
    rig.rt.memory.variables.write(600, -87654321654321)
    rig.run(1)
    rig.start()
    from axisline.devices.clm.operands import Operand

    assert [rig.rt.image.get(Operand("M", 2, i)) for i in range(8)] == [0x21, 0x43, 0x65, 0x21, 0x43, 0x65, 0x87, 0xFF]
    rig.run()
    assert rig.rt.memory.variables[601] == -87654321654321


def test_cvt_binary_round_trip():
    rig = Rig("0000 CVT V600 M2.00 1 0\n0001 CVT V601 M2.00 1 1\n0002 JST 0002\n")
    rig.rt.memory.variables.write(600, -12345678_901234)
    rig.run(1)
    rig.start()
    rig.run()
    assert rig.rt.memory.variables[601] == -12345678_901234


def test_mat():
    """L2173-2182 (decision C-MAT): + - * / on variables, /0 is fault 07."""
    rig = Rig("0000 MAT V700 = V601 * V602\n0001 MAT V701 = V700 / +00000003.000000\n0002 MAT V702 = V601 - V600\n0003 JST 0003\n")
    v = rig.rt.memory.variables
    v.write(600, 1_500_000)
    v.write(601, 2_500_000)
    v.write(602, -4_000_000)
    rig.run(1)
    rig.start()
    rig.run(5)  # two cycles a MAT
    assert (v[700], v[701], v[702]) == (-10_000_000, -3_333_333, 1_000_000)
    rig = Rig("0000 MAT V700 = V601 / V602\n")
    rig.run(1)
    rig.start()
    assert rig.fault == "07"


def test_cid():
    rig = Rig("0000 CID V600 0 +00012.500\n0001 CID V600 1 +00001.250\n0002 CID V600 2 +00000.750\n0003 JST 0003\n")
    rig.run(1)
    rig.start()
    rig.run(3)
    assert rig.var(600) == 13.0


def test_variable_fit_fault_32_at_run_time():
    """§5.6 (L1333-1337): 'POI 1 +V602 V603' -> error 32 (V602 too large)."""
    rig = Rig("0000 POI 1 +V602 V601\n")
    rig.rt.memory.variables.write(602, 1_234_567_123_456)
    rig.rt.memory.variables.write(601, 999_999_900)
    rig.run(1)
    rig.start()
    assert rig.fault == "32"
    assert rig.rt.modes.fault_error.where == "N0000"


def test_set_of_an_axis_position_is_31_once_the_axis_is_homed():
    """L2590: V047, V048 and Vx00 can be SET only while the axis is not homed."""
    rig = Rig("0000 SET V100 = +00000012.500000\n0001 JST 0001\n")
    rig.run(1)
    rig.start()
    assert rig.fault is None and rig.axes[1].actual_position == 12.5
    rig = Rig("0000 SET V100 = +00000012.500000\n")
    rig.axes[1].homed = True
    rig.run(1)
    rig.start()
    assert rig.fault == "31"


def test_cou_target_in_a_variable_mirrors_the_count():
    """L1770: target in V600 -> the actual count in V601."""
    rig = Rig("0000 COU +00000 Q1.00.0 V600\n0001 JST 0000\n")
    rig.rt.memory.variables.write(600, 5_000_000)
    rig.run(1)
    for expected in (1, 2, 3, 4, 0):
        rig.start()
        rig.run(2)
        assert rig.var(601) == expected
    assert rig.bit("Q1.00.0") == 1


def test_nc_write_to_a_logic_task_output_has_no_effect():
    """L5723 (decision C-LT-OWNED): an output the Logic Task writes is not the NC's any more."""
    rig = Rig("0000 AEA Q1.00.0 1\n0001 AEA Q1.00.1 1\n0002 JST 0002\n", logic={0: "LD M4.00.0", 1: "ST Q1.00.0", 2: "END"})
    rig.run(1)
    rig.start()
    rig.run(5)
    assert rig.bit("Q1.00.1") == 1 and rig.bit("Q1.00.0") == 0


def test_jtk_sends_another_task_elsewhere():
    """L2083-2101: 'JTK 0100 2' in Task 1 -> Task 2 continues at 0100; in its own task it is a JMP."""
    program = ("0000 WAI 00.010\n0001 JTK 0300 2\n0002 JTK 0005 1\n0005 JST 0005\n"
               "0200 JMP 0200\n0300 AEA M2.00.0 1\n0301 JMP 0301\n")
    rig = Rig(program, params={"B011": "0200 0000 0"})
    rig.run()
    rig.start()
    rig.run(8)
    assert rig.bit("M2.00.0") == 1 and rig.rt.tasks[1].pc == 301
    assert rig.rt.tasks[0].pc == 5


def test_cst_drops_subroutine_levels():
    """L1818-1842: 'CST t l': l = 1..9 corrects the stack by l levels, 0 clears it; then an RTS
    returns across several levels (and after CST x 0 it is an RTS nesting error)."""
    program = "0000 JSR 0010\n0001 JST 0001\n0010 JSR 0020\n0020 JSR 0030\n0030 CST 1 2\n0031 RTS\n"
    rig = Rig(program)
    rig.run()
    rig.start()
    rig.run(6)
    assert rig.rt.tasks[0].pc == 1 and rig.fault is None  # straight back to the main program
    rig = Rig("0000 JSR 0010\n0010 CST 1 0\n0011 RTS\n")
    rig.run()
    rig.start()
    rig.run(3)
    assert rig.fault == "0C"


def _corrected(name: str) -> str:
    """The manual's Task 2/3 listings write APE with a bit operand ('APE Q1.01.0 ...'); APE takes a
    byte (L1504-1536), so Q1.01 is meant; and 'I1.00.00' (L3466) is I1.00.0."""
    return listing(name).replace("APE\tQ1.01.0", "APE\tQ1.01").replace("I1.00.00", "I1.00.0")


def test_task_2_example_sets_q1_00_7_after_10_cycles():
    """§7.5 Task 2 (L3428-3443, B011 = 0200 0000 0): 'COU +00000 Q1.00.7 000010' after 10 loops."""
    rig = Rig("0000 JMP 0000\n" + _corrected("task2_example"), params={"B011": "0200 0000 0"})
    rig.set("I1.00.0", 1)
    rig.run()
    rig.start()
    rig.run(round(9 * 3.3 / 0.002))
    assert rig.bit("Q1.00.7") == 0
    for _ in range(round(1.5 * 3.3 / 0.002)):
        rig.run()
        if rig.bit("Q1.00.7"):
            break
    assert rig.bit("Q1.00.7") == 1 and len(rig.axes[1].moves) == 10


def test_task_3_example_runs_in_manual_from_power_on():
    """§7.5 Task 3 (L3455-3469, B011 = 0000 0800 0): started at power-up, also in Manual: after
    I1.00.0 the outputs are cleared, Q1.01.0 comes after 2 s, then Q1.01.1 pulses 100 ms."""
    rig = Rig(_corrected("task3_example"), params={"B011": "0000 0800 0"}, mode="manual")
    rig.set("Q1.01", 0xFF)
    rig.set("I1.00.0", 1)
    rig.run(3)
    assert rig.bit("Q1.01.0") == 0 and rig.bit("Q1.01.7") == 0  # APE Q1.01 00000000
    rig.run(1000)  # WAI 02.000
    seen = []
    for _ in range(80):
        rig.run()
        seen.append((rig.bit("Q1.01.0"), rig.bit("Q1.01.1")))
    assert (0, 1) in seen  # Q1.01.0 back to 0, Q1.01.1 on for the 100 ms pulse
    assert not rig.rt.modes.running  # tasks 1, 2, 4, 5 do not run in Manual


def test_mat_takes_two_cycles_and_the_unit_is_shared():
    """Decision C-MAT (L2176-2180): a MAT's result is there and its task goes on one cycle after it
    is reached; a second task's MAT in the same cycle waits for the calculating unit."""
    program = ("0000 MAT V700 = V600 + +00000001.000000\n0001 AEA M2.00.0 1\n0002 JMP 0002\n"
               "0500 MAT V701 = V600 + +00000002.000000\n0501 AEA M2.00.1 1\n0502 JMP 0502\n")
    rig = Rig(program, params={"B012": "0500 0000"})
    rig.run()
    rig.start()  # cycle 1: task 1 takes the unit, task 4 waits
    v = rig.rt.memory.variables
    assert (v[700], v[701]) == (0, 0)
    rig.run()  # cycle 2: task 1 stores; task 4 takes the unit
    assert (v[700], v[701]) == (1_000_000, 0)
    rig.run()  # cycle 3: task 1 AEA; task 4 stores
    assert v[701] == 2_000_000 and rig.bit("M2.00.0") == 1 and rig.bit("M2.00.1") == 0
    rig.run()
    assert rig.bit("M2.00.1") == 1
