"""Filters, timers and counters FILT1..FILT8 and bit linking through them (manual §3.10.4,
§3.10.4.3, §4.3.4.2; wago.md §5.1 - §5.5, §9.9, §9.13)."""

from __future__ import annotations

import pytest

from axisline.devices.wago672.bits import Bit
from axisline.devices.wago672.errors import WagoError
from axisline.devices.wago672.filters import FilterFunction as F
from axisline.devices.wago672.filters import VarOpcode as V
from axisline.devices.wago672.filters import wrap32
from axisline.devices.wago672.image import S1
from axisline.devices.wago672.mailbox import MbxOpcode as Op
from axisline.devices.wago672.program import Cmd

from .test_mailbox import module


def filt(r, n: int) -> bool:
    return r.dev.bits.read(Bit.FILT1 + n - 1)


def setup(**values):
    """A module with FILT1 fed by Input3 unless told otherwise."""
    values.setdefault("Ptr_FILT1", Bit.Input3)
    r, m = module(mailbox_mode=False, **values)
    r.inputs["Input3"] = False
    r.step()
    return r, m


def trace(r, n: int, ticks: int) -> list[bool]:
    out = []
    for _ in range(ticks):
        r.step()
        out.append(filt(r, n))
    return out


def ones(seq: list[bool]) -> tuple[int, int] | None:
    """(first index, count) of the ones in seq (they must be one block)."""
    idx = [i for i, v in enumerate(seq) if v]
    if not idx:
        return None
    assert idx == list(range(idx[0], idx[-1] + 1)), "one block of ones expected"
    return idx[0], len(idx)


def test_no_filter_and_inversion_are_undelayed():
    r, m = setup(Filter2_Function=F.INVERSION, Ptr_FILT2=Bit.Input3)
    assert not filt(r, 1) and filt(r, 2)
    r.inputs["Input3"] = True
    r.step()
    assert filt(r, 1) and not filt(r, 2)
    assert not filt(r, 3)  # default: Ptr_FILT3 = ZERO, function 0


def test_start_edge_filter():
    # "After a reset, the filter is in wait state as long as the input is active. The output supplies 0."
    r, m = setup(Filter1_Function=F.START_EDGE)
    r.inputs["Input3"] = True
    r.dev.warm_start()
    r.step(3)
    assert not filt(r, 1)
    r.inputs["Input3"] = False
    r.step()
    r.inputs["Input3"] = True
    r.step()
    assert filt(r, 1)  # operating mode: the input passes unchanged
    r.inputs["Input3"] = False
    r.step()
    assert not filt(r, 1)


def test_timings_of_the_manual_figures():
    # F5, figures 3.10.4-4 .. -8 (500 ms): change first seen in tick k
    r, m = setup(Filter1_Function=F.LOW_PASS, Filter1_Time=500)
    r.inputs["Input3"] = True
    seq = trace(r, 1, 600)
    assert ones(seq) == (500, 100)  # the new state after 500 ms of constancy
    r.inputs["Input3"] = False
    seq = trace(r, 1, 300)
    r.inputs["Input3"] = True  # a 300 ms pulse of 0 does not get through
    seq += trace(r, 1, 300)
    assert all(seq)

    r, m = setup(Filter1_Function=F.PULSE_EXTENSION, Filter1_Time=500)
    r.inputs["Input3"] = True
    seq = trace(r, 1, 100)
    r.inputs["Input3"] = False
    seq += trace(r, 1, 600)
    assert ones(seq) == (0, 600)  # 100 ms pulse + 500 ms after the 1 -> 0 edge
    r.inputs["Input3"] = True  # retriggerable
    seq = trace(r, 1, 10)
    r.inputs["Input3"] = False
    seq += trace(r, 1, 300)
    r.inputs["Input3"] = True
    seq += trace(r, 1, 10)
    r.inputs["Input3"] = False
    seq += trace(r, 1, 600)
    assert ones(seq) == (0, 820)

    r, m = setup(Filter1_Function=F.MONOFLOP, Filter1_Time=500)
    r.inputs["Input3"] = True  # short pulse (Fig. 3.10.4-6)
    seq = trace(r, 1, 20)
    r.inputs["Input3"] = False
    seq += trace(r, 1, 100)
    r.inputs["Input3"] = True  # not retriggerable
    seq += trace(r, 1, 20)
    r.inputs["Input3"] = False
    seq += trace(r, 1, 500)
    assert ones(seq) == (0, 500)
    r.inputs["Input3"] = True  # long pulse (Fig. 3.10.4-7): 500 ms as well
    seq = trace(r, 1, 900)
    assert ones(seq) == (0, 500)

    r, m = setup(Filter1_Function=F.PULSE_DELAY, Filter1_Time=500)
    r.inputs["Input3"] = True
    seq = trace(r, 1, 700)
    r.inputs["Input3"] = False
    seq += trace(r, 1, 10)
    assert ones(seq) == (500, 200)  # set 500 ms after the edge, reset with the input


def test_pulse_delay_is_an_on_delay():
    # F2: an input that drops before the time never sets the output
    r, m = setup(Filter1_Function=F.PULSE_DELAY, Filter1_Time=500)
    r.inputs["Input3"] = True
    seq = trace(r, 1, 400)
    r.inputs["Input3"] = False
    seq += trace(r, 1, 400)
    assert not any(seq)


def test_filters_in_series_example():
    # Fig. 3.10.4-9: monoflop 500 ms -> inversion -> second monoflop 100 ms
    r, m = setup(Filter1_Function=F.MONOFLOP, Filter1_Time=500, Ptr_FILT2=Bit.FILT1, Filter2_Function=F.INVERSION,
                 Ptr_FILT3=Bit.FILT1 + 1, Filter3_Function=F.MONOFLOP, Filter3_Time=100)
    r.inputs["Input3"] = True
    seq1, seq2, seq3 = [], [], []
    for _ in range(800):
        r.step()
        seq1.append(filt(r, 1))
        seq2.append(filt(r, 2))
        seq3.append(filt(r, 3))
    assert ones(seq1) == (0, 500)
    assert ones([not v for v in seq2]) == (0, 500)
    assert ones(seq3) == (500, 100)


def test_counters():
    # F3: output = variable != 0; "stop" variants halt at 0
    r, m = setup(Filter1_Function=F.COUNTER_UP, Ptr_FILT2=Bit.Input3, Filter2_Function=F.COUNTER_UP_TO_ZERO,
                 Ptr_FILT3=Bit.Input3, Filter3_Function=F.COUNTER_DOWN, Ptr_FILT4=Bit.Input3,
                 Filter4_Function=F.COUNTER_DOWN_TO_ZERO)
    fb = r.dev.mailbox.filters
    fb.set_value(2, -3)
    fb.set_value(4, 2)
    assert not filt(r, 1) and filt(r, 2) and filt(r, 4)
    for _ in range(5):
        r.inputs["Input3"] = True
        r.step(2)
        r.inputs["Input3"] = False
        r.step(2)
    assert [fb.value(n) for n in (1, 2, 3, 4)] == [5, 0, -5, 0]
    assert [filt(r, n) for n in (1, 2, 3, 4)] == [True, False, True, False]
    # at most one edge per 1 ms tick: a signal toggling every tick counts every second tick
    for i in range(10):
        r.inputs["Input3"] = i % 2 == 0
        r.step()
    assert fb.value(1) == 10


def test_an_input_active_at_reset_is_no_edge():
    # F4
    r, m = setup(Filter1_Function=F.COUNTER_UP, Ptr_FILT2=Bit.Input3, Filter2_Function=F.MONOFLOP, Filter2_Time=50)
    r.inputs["Input3"] = True
    r.dev.warm_start()
    r.step(3)
    assert r.dev.mailbox.filters.value(1) == 0 and not filt(r, 2)


def test_var_arithmetic_in_32_bit():
    # F1: signed 32 bit, wrapping; 16-bit immediates sign-extended; division truncates toward zero
    r, m = setup(**{f"Filter{n}_Function": F.MATH for n in range(1, 9)})
    fb = r.dev.mailbox.filters
    ex = fb.execute
    ex(V.VAR_SET, (1, 0xFF, 0xFF))
    assert fb.value(1) == -1 and filt(r, 1)
    ex(V.VAR_INC, (1, 8, 0))
    ex(V.VAR_DEC, (1, 2, 0))
    assert fb.value(1) == 5
    ex(V.VAR_SET, (2, 0x00, 0x80))  # -32768
    ex(V.VAR_ADD, (3, 1, 2))  # FILT3 := FILT2 + FILT1
    assert fb.value(3) == -32763
    ex(V.VAR_SUB, (4, 1, 2))  # FILT4 := FILT1 (minuend) - FILT2 (subtrahend)
    assert fb.value(4) == 32773
    ex(V.VAR_SET, (5, 7, 0))
    ex(V.VAR_SET, (6, 0xFE, 0xFF))  # -2
    ex(V.VAR_DIV, (7, 5, 6))  # 7 / -2 = -3
    assert fb.value(7) == -3
    ex(V.VAR_MUL, (8, 2, 2))  # (-32768)^2 = 2^30
    ex(V.VAR_MUL, (8, 8, 6))  # 2^30 * -2 = -2^31
    ex(V.VAR_MUL, (8, 8, 6))  # 2^32: wraps to 0
    assert fb.value(8) == 0 and not filt(r, 8)
    ex(V.VAR_COPY, (8, 4, 0))
    assert fb.value(8) == 32773
    assert wrap32(0x80000000) == -0x80000000 and wrap32(-0x80000001) == 0x7FFFFFFF
    ex(V.VAR_SET, (8, 0, 0))
    for opcode, data, code in ((V.VAR_DIV, (1, 5, 8), 1251), (V.VAR_ADD, (9, 1, 1), 1247), (V.VAR_ADD, (1, 9, 1), 1247),
                               (V.VAR_INC, (0, 1, 0), 1247)):
        with pytest.raises(WagoError) as exc:
            ex(opcode, data)
        assert exc.value.code == code
    assert fb.value(1) == 5  # unchanged by the failed commands


def test_var_commands_need_math_or_a_counter():
    r, m = setup(Filter1_Function=F.LOW_PASS, Filter2_Function=F.COUNTER_DOWN)
    fb = r.dev.mailbox.filters
    with pytest.raises(WagoError) as exc:
        fb.execute(V.VAR_SET, (1, 1, 0))
    assert exc.value.code == 1248
    fb.execute(V.VAR_SET, (2, 1, 0))
    fb.execute(V.VAR_COPY, (2, 1, 0))  # F6: any filter may be read
    assert fb.value(2) == 0
    with pytest.raises(WagoError) as exc:
        fb.execute(V.VAR_COPY, (0, 2, 0))
    assert exc.value.code == 1247


def test_var_commands_through_the_mailbox_and_program_and_divide_by_zero():
    r, m = module(Filter1_Function=F.MATH, Filter2_Function=F.MATH)
    assert m.drive(Cmd.VAR_SET, 1, 100, 0) == 0
    assert m.drive(Cmd.VAR_DIV, 1, 1, 2) == 0x01 and r.error == 1251  # FILT2 = 0
    assert r.dev.mailbox.filters.value(1) == 100


def test_state_variables_91_to_98():
    # F6: DIAG_RD_VAR 91..98
    r, m = setup(Filter1_Function=F.PULSE_DELAY, Filter1_Time=1000, Filter4_Function=F.MATH, Ptr_FILT2=Bit.ONE)
    r.dev.mailbox.filters.set_value(4, -7)
    assert m(Op.DIAG_RD_VAR, 94) == (0, (-7 & 0xFFFFFFFF).to_bytes(4, "little"))
    assert m(Op.DIAG_RD_VAR, 92)[1][0] == 1  # FILT2 (function 0) passes ONE
    r.inputs["Input3"] = True
    r.step(100)
    assert 95 <= int.from_bytes(m(Op.DIAG_RD_VAR, 91)[1], "little") <= 105  # running time [ms]


def test_a_filter_linked_to_mzero_counts_wr_bit_edges():
    # a FILT bit linked to MZERO takes the value written with WR_BIT as its input
    r, m = module(Ptr_FILT1=Bit.MZERO, Filter1_Function=F.COUNTER_UP)
    for _ in range(3):
        assert m.drive(Cmd.WR_BIT, Bit.FILT1, 1) == 0
        assert m.drive(Cmd.WR_BIT, Bit.FILT1, 0) == 0
    assert r.dev.mailbox.filters.value(1) == 3 and filt(r, 1)


def test_changing_the_function_resets_the_filter():
    r, m = setup(Filter1_Function=F.COUNTER_UP)
    fb = r.dev.mailbox.filters
    fb.set_value(1, 42)
    r.dev.config["Filter1_Function"] = F.MATH
    r.step()
    assert fb.value(1) == 0 and not filt(r, 1)


def test_a_low_pass_debounces_a_limit_switch():
    # bit linking through a filter: LimitSwitch_Pos <- FILT1 (low pass 5 ms) <- Input5
    r, m = module(Ptr_FILT1=Bit.Input5, Filter1_Function=F.LOW_PASS, Filter1_Time=5, Ptr_LimitSwitch_Pos=Bit.FILT1)
    r.inputs["Input5"] = True
    r.step(3)
    assert not r.dev.bits.read(Bit.LimitSwitch_Pos)
    r.inputs["Input5"] = False
    r.step(10)
    r.inputs["Input5"] = True
    r.step(6)
    assert r.dev.bits.read(Bit.LimitSwitch_Pos)


def test_mzero_and_mone_bits_after_a_warm_start():
    # wago.md §5.3: a bit linked to MONE is set after a reset, one linked to MZERO cleared
    r, m = module(Ptr_UserBit_0=Bit.MONE)
    assert r.dev.bits.read(Bit.UserBit_0) and not r.dev.bits.read(Bit.UserBit_0 + 1)
    m.drive(Cmd.WR_BIT, Bit.UserBit_0, 0)
    m.drive(Cmd.WR_BIT, Bit.UserBit_0 + 1, 1)
    assert not r.dev.bits.read(Bit.UserBit_0) and r.dev.bits.read(Bit.UserBit_0 + 1)
    r.dev.warm_start()
    assert r.dev.bits.read(Bit.UserBit_0) and not r.dev.bits.read(Bit.UserBit_0 + 1)


def test_error_set_through_a_user_bit():
    # Error_Set linked to a user bit: a run program or the mailbox can raise 1358
    r, m = module(Reserved_221=Bit.UserBit_0)  # Ptr of Error_Set (0xDD), "Reserved_221" in §4.6
    assert m.drive(Cmd.WR_BIT, Bit.UserBit_0, 1) == 0
    r.step()
    assert r.error == 1358 and not r.has(S1.Ready)
    assert m.drive(Cmd.WR_BIT, Bit.UserBit_0, 0) == 0x23  # no mode any more


def test_too_deep_links_read_zero_and_raise_1245_without_stopping_the_module():
    # "Too many nesting levels will yield an ambiguous result and the error ERR_LINK_NESTING"
    r, m = module(mailbox_mode=False)
    r.dev.config.update({"Ptr_KBUS_ST3_6": 0x98, "Ptr_UserBit_0": 0x99, "Ptr_UserBit_1": 0x9A,
                         "Ptr_UserBit_2": 0x9B, "Ptr_UserBit_3": 0x9C})
    r.step()
    assert r.error == 1245 and r.s3 & 0x40 == 0
    r.dev.config["Ptr_UserBit_2"] = Bit.ONE
    m(Op.DIAG_QUIT_ERROR)
    r.step(2)
    assert r.error == 0 and r.s3 & 0x40
