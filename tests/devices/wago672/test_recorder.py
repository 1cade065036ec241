"""The data recorder: trigger, Trace_Armed/Trace_Stored, sampling, upload through the table
manager (manual §3.13.2, §4.5, §4.6 addresses 264 - 272, 222, 223; wago.md §8.5)."""

from __future__ import annotations

from axisline.devices.wago672.bits import Bit
from axisline.devices.wago672.mailbox import MbxOpcode as Op
from axisline.devices.wago672.program import Cmd
from axisline.devices.wago672.recorder import TRACE_SAMPLES
from axisline.devices.wago672.tables import TableKind, byte_sum

from .test_mailbox import d24, module


def stored(r) -> bool:
    return r.dev.bits.read(Bit.Trace_Stored)


def test_a_move_triggers_a_recording_of_position_and_frequency():
    # defaults: TRACE_TRIGGER <- Busy, Trace_Armed <- MONE, TraceVar1 = 1 (position), TraceVar2 = 2
    # (frequency), every 1 ms
    r, m = module()
    rec = r.dev.mailbox.recorder
    assert not stored(r) and not rec.recording
    m.drive(Cmd.SET_VELOCITY, 0xE8, 0x03)  # 1000
    assert m.drive(Cmd.SET_ACC, 0xFF, 0x7F, 0) == 0
    assert m.drive(Cmd.MOVE, *d24(2000)) == 0
    r.step()
    assert rec.recording and not stored(r)
    r.until(lambda: stored(r), 600)
    s = rec.samples
    assert len(s) == TRACE_SAMPLES and not rec.recording
    positions = [p for p, _ in s]
    assert positions == sorted(positions) and positions[-1] == 2000
    assert max(v for _, v in s) == 1000 and s[0][1] >= 0
    assert m(Op.DIAG_RD_BIT, Bit.Trace_Stored)[1][0] == 1


def test_sampling_period_and_variables():
    # R2: TraceMsecCycleTime = 3 ms, a bit as variable (0x1000 + n), sampled from the trigger tick on
    r, m = module(TraceMsecCycleTime=3, TraceVar1=0, TraceVar2=0x1000 + Bit.Busy)
    m.drive(Cmd.SET_VELOCITY, 0xE8, 0x03)
    m.drive(Cmd.MOVE, *d24(500))
    r.until(lambda: stored(r), 2000)
    s = r.dev.mailbox.recorder.samples
    times = [t for t, _ in s]
    assert all(b - a == 3 for a, b in zip(times, times[1:]))
    assert s[0][1] == 1 and s[-1][1] == 0  # Busy at the trigger, idle at the end


def test_upload_through_the_table_manager():
    # R1: DLD_START (1, 5, 1000, 32-bit upload), var1[i], var2[i] interleaved, DLD_END returns the sum
    r, m = module(TraceVar1=1, TraceVar2=0)
    m.drive(Cmd.SET_VELOCITY, 0xE8, 0x03)
    m.drive(Cmd.MOVE, *d24(-200))
    r.until(lambda: stored(r), 600)
    s = r.dev.mailbox.recorder.samples
    rc, blocks, end = m.upload(1, TableKind.TRACE, 1000)
    assert rc == 0 and len(blocks) == 1000
    values = [int.from_bytes(b, "little", signed=True) for b in blocks]
    assert values[0::2] == [p for p, _ in s] and values[1::2] == [t for _, t in s]
    assert values[-2] == -200
    assert end == byte_sum(blocks).to_bytes(4, "little")
    assert m(Op.DLD_START, 0, 5, 0xE8, 0x13)[0] == 0  # location 0 = RAM1 (T13), 24-bit upload accepted
    assert m(Op.DLD_CONT)[1] == blocks[0]
    assert m(Op.TABLE_COPY, 5, 1, 0)[0] == 0  # type 5 is the copy status query: the trace cannot be copied


def test_no_upload_without_a_stored_data_set():
    # R3
    r, m = module()
    assert m(Op.DLD_START, 1, 5, 0xE8, 0x33) == (0x31, bytes([1, 0, 0, 4]))
    m.drive(Cmd.SPEED, 0x64, 0x00)
    r.step(10)
    assert r.dev.mailbox.recorder.recording
    assert m(Op.DLD_START, 1, 5, 0xE8, 0x33)[0] == 0x31


def test_trace_armed_0_keeps_the_data_set_and_a_new_start_clears_trace_stored():
    r, m = module()
    rec = r.dev.mailbox.recorder
    m.drive(Cmd.SET_VELOCITY, 0xE8, 0x03)
    m.drive(Cmd.MOVE, *d24(100))
    r.until(lambda: stored(r), 600)
    first = rec.samples
    assert m.drive(Cmd.WR_BIT, Bit.Trace_Armed, 0) == 0  # Trace_Armed is linked to MONE
    m.drive(Cmd.MOVE, *d24(0))
    r.step(600)
    assert stored(r) and rec.samples == first
    assert m.drive(Cmd.WR_BIT, Bit.Trace_Armed, 1) == 0
    m.drive(Cmd.MOVE, *d24(200))
    r.step(2)
    assert rec.recording and not stored(r)  # "cleared at each new start"
    r.until(lambda: stored(r), 600)
    assert rec.samples != first


def test_remote_trigger_with_wr_bit_and_a_trigger_during_a_recording_is_ignored():
    # §3.13.2: "The trigger bits must be linked to the MONE internal bit for this."
    r, m = module(Ptr_Trace_Trigger=Bit.MZERO, TraceMsecCycleTime=2)
    rec = r.dev.mailbox.recorder
    r.step(5)
    assert not rec.recording
    assert m.drive(Cmd.WR_BIT, Bit.TRACE_TRIGGER, 1) == 0
    r.step()
    start = r.cycle
    assert rec.recording
    m.drive(Cmd.WR_BIT, Bit.TRACE_TRIGGER, 0)
    r.step(100)
    m.drive(Cmd.WR_BIT, Bit.TRACE_TRIGGER, 1)  # ignored: the recording goes on
    r.until(lambda: stored(r), 1200)
    assert r.cycle - start >= 2 * (TRACE_SAMPLES - 1) - 2


def test_a_warm_start_clears_the_data_set():
    r, m = module()
    m.drive(Cmd.SET_VELOCITY, 0xE8, 0x03)
    m.drive(Cmd.MOVE, *d24(100))
    r.until(lambda: stored(r), 600)
    r.dev.warm_start()
    r.step()
    assert not stored(r) and r.dev.mailbox.recorder.samples == []


def test_a_trigger_already_set_at_reset_is_no_edge():
    # R4: TRACE_TRIGGER linked to ONE: no recording after a reset
    r, m = module(Ptr_Trace_Trigger=Bit.ONE)
    r.step(5)
    assert not r.dev.mailbox.recorder.recording and not stored(r)
