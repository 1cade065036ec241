"""COMPAX status values S1, S2, S13/S14, S30, S41 ... S52 (compax.md §2.19; manual §20, §21)."""

from __future__ import annotations

import pytest

from axisline.devices.compax import E_UNKNOWN, CompaxError, UnknownNumberError
from axisline.devices.compax.parameters import Parameters
from axisline.devices.compax.status import (
    LOOP_ENDLESS,
    S42_RANGE,
    STATUS,
    StatusValues,
    format_status,
    label_reference,
    loop_counter_value,
    per_mille,
    s42_wrap,
)


def test_table_holds_the_status_values_with_units():
    assert sorted(STATUS) == [1, 2, 13, 14, 30, *range(41, 53)]
    assert STATUS[41].unit == "min⁻¹" and STATUS[42].unit == "increments"
    assert all(STATUS[n].meaning and STATUS[n].computed for n in STATUS)


def test_decision_1_per_mille_not_percent():
    # §0.1 [CONFLICT]: overview says %, §20 says ‰ -> ‰ for S44, S45, S50, S51, S52
    assert {n: STATUS[n].unit for n in (44, 45, 50, 51, 52)} == {n: "‰" for n in (44, 45, 50, 51, 52)}


def test_x5_setm_35_gives_s44_350_per_mille():
    # "SETC 2 / SETM 35": master position := 0.35·M_T (M_T = 360 -> 126); S44 = 350 ‰
    assert per_mille(0.35 * 360, 360) == pytest.approx(350.0)
    assert per_mille(360 + 126, 360) == pytest.approx(350.0)
    assert per_mille(-90, 360) == 750.0
    with pytest.raises(CompaxError):
        per_mille(1, 0)


def test_x12_master_related_label_reference_and_setm():
    # M_M = 0.5·M_T, P32 = 0.7·M_T -> M_ref = 0.5 - 0.7 + 1 = 0.8·M_T -> S50 = 800 ‰ -> SETM 80
    mref = label_reference(0.5 * 360, 0.7 * 360, 360)
    assert mref == pytest.approx(288.0)
    s50 = per_mille(mref, 360)
    assert s50 == pytest.approx(800.0) and s50 / 10 == pytest.approx(80.0)


def test_x13_slave_related_label_reference():
    # S_ref = (S_M - P32) + S_T = 240 for S_T = 360, S_M = 180, P32 = 300; X = S_act - S_ref = 100 - 240 = -140
    sref = label_reference(180, 300, 360)
    assert sref == 240.0 and 100 - sref == -140.0
    assert label_reference(10, 0, 360) == 10.0 and label_reference(0, 360, 360) == 0.0  # decision 7: [0, cycle)
    assert label_reference(100, 1000, 360) == 180.0  # several cycles added


def test_x24_loop_0_and_s48():
    # "At a cyclical travel with LOOP 0 S48 = -8388608" (-2^23); LOOP range 0 ... 65000
    assert LOOP_ENDLESS == -8388608 == -(2**23)
    assert loop_counter_value(0) == -8388608 and loop_counter_value(10) == 10
    assert loop_counter_value(65000) == 65000
    for bad in (-1, 65001, 1.0, True):
        with pytest.raises(CompaxError):
            loop_counter_value(bad)


def test_x24_decision_3_s42_range_and_reset_on_overflow():
    assert S42_RANGE == 8_000_000
    assert [s42_wrap(v) for v in (0, 7_999_999, 8_000_000, 8_000_001, -8_000_001, 24_000_005)] == [
        0, 7_999_999, 0, 1, -1, 5]
    with pytest.raises(CompaxError):
        s42_wrap(1.5)


def test_decision_4_status_format_8_3_digits_and_overflow_strokes():
    assert format_status(350) == "350.000"
    assert format_status(-8388608) == "-8388608.000"
    assert format_status(99_999_999.999) == "99999999.999"
    assert format_status(100_000_000) == "---"
    assert format_status(-0.0001) == "0.000"
    assert format_status(float("nan")) == "---"


def test_status_values_container():
    status = StatusValues()
    assert status[44] == 0.0 and len(status) == len(STATUS)
    status[44] = 350.0
    status[48] = LOOP_ENDLESS
    assert status[44] == 350.0 and status.read(48) == -8388608
    with pytest.raises(UnknownNumberError) as info:
        status[40]
    assert info.value.code == E_UNKNOWN
    assert 40 not in status and 44 in status
    for bad in (float("inf"), "1", True):
        with pytest.raises(CompaxError):
            status[44] = bad


def test_decision_5_s13_s14_show_the_indicator_p233_p234_select():
    # §21: 32 "normalized correction factor" runs from 0 to 1000 per mil; 33 cycle counter
    params = Parameters()
    status = StatusValues()
    status.indicators[32] = 500.0
    status.indicators[33] = 7.0
    assert status.read(13, params) == 0.0  # P233 = 0 selects nothing here
    params[233] = 32
    params[234] = 33
    params.make_valid("VP")
    assert status.read(13, params) == 500.0 and status.read(14, params) == 7.0
