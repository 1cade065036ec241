"""The bit field placeholder: default links, relinking, MZERO/MONE bits (manual §3.10.4, §4.5; wago.md §5, §9.9)."""

from __future__ import annotations

import pytest

from axisline.devices.wago672.bits import Bit, BitTable
from axisline.devices.wago672.config_table import ConfigTable
from axisline.devices.wago672.errors import WagoError
from axisline.devices.wago672.image import C1, S1, S3

from .rig import ON, Rig


def test_bit_numbers_of_the_bit_table():
    assert (Bit.On_Target, Bit.Busy, Bit.Error, Bit.Ready, Bit.Stop_N_ACK) == (0x08, 0x09, 0x0F, 0x10, 0x11)
    assert (Bit.Input1, Bit.CAM1, Bit.CAM9, Bit.Err_Range) == (0x30, 0x38, 0x2F, 0x2A)
    assert (Bit.Enable, Bit.Stop1_N, Bit.Set_Reference, Bit.Jog_Pos, Bit.OUT1) == (0xB0, 0xC2, 0xBC, 0xCA, 0xA0)


def test_default_links_stop1_n_follows_input1_and_dia_rd_bit():
    # wago.md §9.9: with defaults DI1 = 0 -> Stop_N_ACK = 0 even if C1.1 = 1; bit 0xC2 reads DI1
    r = Rig()
    r.c1 = ON
    r.inputs["Input1"] = False
    r.step()
    assert not r.has(S1.Stop_N_ACK) and not r.dev.bits.read(Bit.Stop1_N)
    r.inputs["Input1"] = True
    r.step()
    assert r.has(S1.Stop_N_ACK) and r.dev.bits.read(Bit.Stop1_N) and r.dev.state_variable(0x1000 + 0xC2) == 1


def test_relinking_stop1_n_to_one_frees_input1():
    cfg = ConfigTable()
    cfg.set("Ptr_Stop1_N", Bit.ONE)
    r = Rig(cfg)
    r.inputs["Input1"] = False
    r.c1 = ON
    r.step()
    assert r.has(S1.Stop_N_ACK) and not r.has(S3.Input1)


def test_status_bits_follow_their_pointers():
    cfg = ConfigTable()
    cfg.set("Ptr_KBUS_ST1_0", Bit.Input3)  # S1.0 now shows DI3 instead of Ready
    r = Rig(cfg)
    r.c1 = C1.Enable
    r.step()
    assert not r.has(S1.Ready)
    r.inputs["Input3"] = True
    r.step()
    assert r.has(S1.Ready)


def test_only_bits_linked_to_mzero_or_mone_are_writable():
    # wago.md §9.9: WR_BIT(0x98, 1) succeeds (user bit on MZERO), WR_BIT(0xA0 OUT1, 1) fails with 1242
    t = BitTable(ConfigTable())
    assert not t.read(Bit.UserBit_0)
    t.write(Bit.UserBit_0, True)
    assert t.read(Bit.UserBit_0)
    with pytest.raises(WagoError) as exc:
        t.write(Bit.OUT1, True)
    assert exc.value.code == 1242
    with pytest.raises(WagoError) as exc:
        t.read(256)
    assert exc.value.code == 1241
    assert t.read(Bit.Trace_Armed), "Trace_Armed is linked to MONE: 1 after reset"


def test_nesting_deeper_than_four_levels_is_1245():
    cfg = ConfigTable()
    # Enable <- UserBit_0 <- UserBit_1 <- UserBit_2 <- UserBit_3 <- UserBit_4 (5 targets)
    cfg.update({"Ptr_Enable": 0x98, "Ptr_UserBit_0": 0x99, "Ptr_UserBit_1": 0x9A, "Ptr_UserBit_2": 0x9B, "Ptr_UserBit_3": 0x9C})
    t = BitTable(cfg)
    with pytest.raises(WagoError) as exc:
        t.read(Bit.Enable)
    assert exc.value.code == 1245
    cfg.set("Ptr_UserBit_2", Bit.ONE)  # 3 targets, then ONE
    assert t.read(Bit.Enable)


def test_the_device_reports_a_too_deep_link_as_an_error():
    cfg = ConfigTable()
    cfg.update({"Ptr_Start": 0x98, "Ptr_UserBit_0": 0x99, "Ptr_UserBit_1": 0x9A, "Ptr_UserBit_2": 0x9B, "Ptr_UserBit_3": 0x9C})
    r = Rig(cfg)
    r.step()
    assert r.error == 1245


def test_input2_as_stop2_n_by_relinking():
    # "Input2 = Stop2_N or as configured": Ptr_Stop2_N (177) := Input2 (0x31), the reference switch moved away
    cfg = ConfigTable()
    cfg.update({"Ptr_Stop2_N": Bit.Input2, "Ptr_Set_Reference": Bit.ZERO})
    r = Rig(cfg)
    r.c1 = C1.Enable  # C1.1 no longer matters
    r.step()
    assert not r.has(S1.Stop_N_ACK)
    r.inputs["Input2"] = True
    r.step()
    assert r.has(S1.Stop_N_ACK)


def test_the_tick_rewrites_its_own_source_bits_after_a_foreign_write():
    # the tick writes its source bits only when they change (watches._write_sources); a write
    # by someone else (set_source) must not survive the next tick
    r = Rig()
    r.c1 = ON
    r.step(3)
    assert r.has(S1.Ready)
    r.dev.bits.set_source(Bit.Ready, False)
    assert not r.dev.bits.read(Bit.Ready)
    r.step()
    assert r.dev.bits.read(Bit.Ready) and r.has(S1.Ready)
