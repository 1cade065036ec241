"""COMPAX cam memory: formats, addresses, RESETF / VF, persistence (compax.md §2.21, §6; manual §25)."""

from __future__ import annotations

import json
import os

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from axisline.devices.compax import E_ADDRESS, E_CAPACITY, E_RESERVED, E_VALUE, CompaxError
from axisline.devices.compax import cammemory as cm
from axisline.devices.compax.cammemory import (
    CONTROL_BLOCK,
    FULL_SCALE,
    SIZE,
    CamMemory,
    Fmt,
    aux_address,
    block_address,
    block_base,
    check_capacity,
    decode_bytes,
    decode_int,
    encode_bytes,
    encode_int,
    format_fraction,
    fraction_value,
    fraction_word,
    set_point_address,
)
from axisline.motion.cam import decode_fraction, encode_fraction

# The manual's example curve 1 control block (§25 "Storage of Curve Number 1"; X20).
CURVE1_BLOCK = [
    ("I", 5460, 360), ("F", 5459, 0.0), ("I", 5458, 1), ("I", 5457, 11), ("I", 5456, 360), ("F", 5455, 0.0),
    ("F", 5454, 0.1), ("F", 5453, 0.6), ("F", 5452, 0.2), ("F", 5451, 0.7), ("F", 5450, -0.1), ("F", 5449, 0.0),
    ("F", 5448, 0.5), ("F", 5447, 0.05), ("F", 5446, 0.1), ("F", 5445, 0.9),
]
SET_POINTS = [0, .1, .2, .3, .4, .5, .6, .7, .8, .9, .9999999]
AUX = [(1, 10, 246), (3, 20, 236), (7, 30, 226), (15, 40, 216), (31, 50, 206), (63, 60, 196), (127, 70, 186),
       (255, 80, 176), (254, 90, 166), (252, 100, 156), (248, 110, 146)]


def hexbytes(word: int) -> str:
    return " ".join(f"{b:02X}" for b in word.to_bytes(3, "big"))


# -- number formats (§25, X21, Appendix B) ------------------------------------------------------


@pytest.mark.parametrize(
    ("value", "cells"),
    [("0.99999999", "7F FF FF"), ("0.5", "40 00 00"), ("0", "00 00 00"), ("-1", "80 00 00"),
     ("-0.5", "C0 00 00"), ("-0.00000001", "FF FF FF")],
)
def test_x21_fractional_24bit_vectors(value, cells):
    assert hexbytes(fraction_word(float(value))) == cells
    # the same conversion as motion.cam's (reused, not duplicated)
    assert fraction_word(float(value)) == encode_fraction(float(value))
    mem = CamMemory()
    mem.write("F", 6, float(value))
    assert hexbytes(mem.word(6)) == cells


def test_fx_reading_is_ix_over_2_pow_23():
    # "1. Conversion into an integer value. 2. Fx = Ix / 2^23"
    assert fraction_value(0x7FFFFF) == 8388607 / 2**23
    assert fraction_value(0xC00000) == -0.5 == decode_fraction(0xC00000)
    assert fraction_value(0x7FFFFF, full_scale_is_one=True) == 1.0


@pytest.mark.parametrize(("value", "cells"), [(1024, "00 04 00"), (512, "00 02 00"), (0, "00 00 00")])
def test_x21_integer_24bit_vectors(value, cells):
    assert hexbytes(encode_int(value)) == cells
    mem = CamMemory()
    mem.write("I", 5460, value)
    assert hexbytes(mem.word(5460)) == cells and mem.read("I", 5460) == value


@pytest.mark.parametrize(
    ("value", "cells"), [((128, 0, 0), "00 00 80"), ((255, 127, 255), "FF 7F FF"), ((1, 1, 128), "80 01 01")]
)
def test_x21_bx_3x8bit_vectors(value, cells):
    # MSB = analogue channel 1, middle = analogue channel 0, LSB = digital outputs
    assert hexbytes(encode_bytes(value)) == cells
    mem = CamMemory()
    mem.write("B", 7, value)
    assert hexbytes(mem.word(7)) == cells and mem.read("B", 7) == value


def test_decision_2_i_format_is_signed_24bit():
    assert encode_int(-1) == 0xFFFFFF and decode_int(0xFFFFFF) == -1
    assert decode_int(encode_int(-8388608)) == -8388608 and decode_int(encode_int(8388607)) == 8388607
    for bad in (8388608, -8388609, 1.5, "1", True):
        with pytest.raises(CompaxError):
            encode_int(bad)


def test_decision_8_b_bytes_accept_both_twos_complement_notations():
    assert encode_bytes((-128, -1, 0)) == encode_bytes((128, 255, 0))
    assert decode_bytes(encode_bytes((-1, 5, -128))) == (255, 5, 128)
    for bad in ((256, 0, 0), (0, -129, 0), (1, 2), (1, 2, 3, 4), (1.5, 0, 0)):
        with pytest.raises(CompaxError):
            encode_bytes(bad)


def test_format_fraction_read_back_text():
    # §25: "F0006=0.1234567"; 7 decimals; writing the text back stores the same word
    assert format_fraction(fraction_word(0.1234567)) == "0.1234567"
    assert format_fraction(0) == "0.0000000"
    assert format_fraction(FULL_SCALE) == "0.9999999"
    assert format_fraction(0x800000) == "-1.0000000"
    assert format_fraction(0xFFFFFF) == "-0.0000001"
    assert format_fraction(fraction_word(0.1)) == "0.1000000"  # not 0.0999999
    assert format_fraction(fraction_word(-0.1)) == "-0.1000000"
    assert format_fraction(fraction_word(0.05)) == "0.0500000"


@settings(max_examples=300)
@given(st.integers(min_value=0, max_value=0xFFFFFF))
def test_format_fraction_round_trips_every_word(word):
    assert fraction_word(float(format_fraction(word))) == word


@settings(max_examples=300)
@given(st.integers(min_value=-10**6, max_value=10**6 - 1))
def test_values_with_six_decimals_read_back_exactly(k):
    text = f"{k / 10**6:.6f}"
    assert float(format_fraction(fraction_word(float(text)))) == float(text)


def test_fraction_word_full_scale_and_float_error():
    assert fraction_word(1.0, full_scale_is_one=True) == FULL_SCALE
    with pytest.raises(CompaxError, match="0.9999999"):
        fraction_word(1.0)
    # s / S_T computed in floats lands on the grid, not one LSB below
    assert fraction_word((0.3 * 360) / 360) == fraction_word(0.3)
    word = fraction_word(0.1)
    assert fraction_word(fraction_value(word) * 7 / 7) == word
    for bad in (1.5, -1.0000001, float("nan"), "x", True):
        with pytest.raises(CompaxError):
            fraction_word(bad)


# -- addresses ----------------------------------------------------------------------------------


def test_address_formulas():
    # §25 / compax.md §2.21 [DERIVED]: set point k at F(4+2k), aux at B(5+2k); blocks 20 downward from 5460
    assert [set_point_address(k) for k in (1, 2, 10, 11, 12, 22)] == [6, 8, 24, 26, 28, 48]
    assert [aux_address(k) for k in (1, 2, 10, 11, 12, 22)] == [7, 9, 25, 27, 29, 49]
    assert block_base(1) == 5460 and block_base(2) == 5440 and block_base(100) == 5460 - 20 * 99
    assert block_address(1, 15) == 5445 and block_address(1, 19) == 5441 and block_address(2, 19) == 5421
    with pytest.raises(CompaxError):
        set_point_address(0)
    with pytest.raises(CompaxError):
        block_base(101)
    with pytest.raises(CompaxError):
        block_address(1, 20)


def test_decision_curve_numbering_i5436_is_slave_cycle_of_curve_2():
    # §6.1 [CONFLICT] "Slave-cycle of 1st curve: I5436": curves are 1-based; I5436 belongs to curve 2
    assert block_address(2, 4) == 5436 and CONTROL_BLOCK[4].significance == "Slave cycle integer"
    assert block_address(1, 0) == 5460 and CONTROL_BLOCK[0].significance == "Master cycle integer"


def test_control_block_layout_is_the_manuals_table():
    layout = [(f.offset, f.fmt.value, f.significance, f.ref) for f in CONTROL_BLOCK]
    assert layout == [
        (0, "I", "Master cycle integer", ""), (1, "F", "Master cycle fractional", ""),
        (2, "I", "Number of 1st set point", ""), (3, "I", "Number of last set point", ""),
        (4, "I", "Slave cycle integer", ""), (5, "F", "Slave cycle fractional", ""),
        (6, "F", "Coupling position", "M"), (7, "F", "Synchronous position", "M"),
        (8, "F", "Decoupling position", "M"), (9, "F", "Brake position", "M"),
        (10, "F", "Standstill position", "S"), (11, "F", "---", ""), (12, "F", "Label set position", "M/S"),
        (13, "F", "Label window", "M/S"), (14, "F", "Correction starting", "M"), (15, "F", "Correction end", "M"),
    ]


def test_x20_curve1_control_block_example_values():
    mem = CamMemory()
    for fmt, address, value in CURVE1_BLOCK:
        mem.write(fmt, address, value)
    for k, (value, aux) in enumerate(zip(SET_POINTS, AUX), start=1):
        mem.write("F", set_point_address(k), value)
        mem.write("B", aux_address(k), aux)
    for fmt, address, value in CURVE1_BLOCK:
        got = mem.read(fmt, address)
        if fmt == "F":
            assert abs(got - value) < 2**-23 and format_fraction(mem.word(address)) == f"{value:.7f}"
        else:
            assert got == value
    assert mem.read("F", 26) == 8388607 / 2**23 and format_fraction(mem.word(26)) == "0.9999999"
    assert mem.read("B", 7) == (1, 10, 246) and mem.read("B", 27) == (248, 110, 146)
    assert mem.read("B", 17) == (63, 60, 196)


def test_capacity_rule():
    # 2·N_points + 20·N_curves <= 5455 (addresses 6 ... 5460 hold both regions)
    check_capacity(2717, 1)  # 5434 + 20 = 5454
    check_capacity(2500, 22)  # "2500 set points"
    check_capacity(200, 100)  # "max. 100 curves with 2 set points each"
    with pytest.raises(CompaxError) as info:
        check_capacity(2718, 1)
    assert info.value.code == E_CAPACITY and "5455" in str(info.value)
    with pytest.raises(CompaxError):
        check_capacity(2, 101)


# -- delivery state -----------------------------------------------------------------------------


def test_delivery_state_curve_1_straight_line_gradient_1():
    # §0: "With curve 1 COMPAX contains a straight line with gradient 1. The remaining curve parameters are 0."
    mem = CamMemory()
    assert mem.curve_count() == 1 and mem.curve_count(valid=True) == 1
    assert mem.read("I", 5460) == 360 and mem.read("I", 5456) == 360  # decision 1: M_T = S_T = 360
    assert (mem.read("I", 5458), mem.read("I", 5457)) == (1, 2)
    assert mem.word(6) == 0 and mem.word(8) == FULL_SCALE
    assert all(mem.word(a) == 0 for a in range(5441, 5456) if a != 5456)
    assert not mem.dirty and mem.modified == ()
    blank = CamMemory.blank()
    assert set(blank.words()) == {0} and set(blank.words(valid=True)) == {0}


# -- errors leave the memory unchanged ----------------------------------------------------------


@pytest.mark.parametrize(
    ("fmt", "address", "value", "code"),
    [
        ("F", 0, 0.5, E_ADDRESS), ("F", 5461, 0.5, E_ADDRESS), ("I", -1, 1, E_ADDRESS), ("F", 6.0, 0.5, E_ADDRESS),
        ("F", 6, 1.0, E_VALUE), ("F", 6, -1.5, E_VALUE), ("I", 5460, 2**23, E_VALUE), ("I", 5460, 3.5, E_VALUE),
        ("B", 7, (256, 0, 0), E_VALUE), ("B", 7, (1, 2), E_VALUE), ("F", 3, 0.5, E_RESERVED),
        ("I", 5, 0, E_RESERVED), ("I", 1, 101, E_VALUE), ("F", 1, 0.5, E_VALUE), ("Q", 6, 0, E_VALUE),
    ],
)
def test_bad_writes_raise_the_devices_error_and_change_nothing(fmt, address, value, code):
    mem = CamMemory()
    before = mem.words()
    with pytest.raises(CompaxError) as info:
        mem.write(fmt, address, value)
    assert info.value.code == code
    text = str(info.value)
    assert str(address).split(".")[0] in text or str(value) in text or repr(fmt) in text  # names what was wrong
    assert mem.words() == before and mem.modified == ()


def test_reading_out_of_range_addresses():
    mem = CamMemory()
    for address in (0, 5461):
        with pytest.raises(CompaxError) as info:
            mem.read("F", address)
        assert info.value.code == E_ADDRESS and "1 ... 5460" in str(info.value)
    assert mem.read("I", 3) == 0  # reserved addresses can be read


def test_write_words_is_all_or_nothing():
    mem = CamMemory()
    before = mem.words()
    with pytest.raises(CompaxError):
        mem.write_words({10: 5, 12: 6, 5461: 1})
    with pytest.raises(CompaxError):
        mem.write_words({10: 5, 12: 1 << 24})
    with pytest.raises(CompaxError):
        mem.write_words({10: 5, 4: 0})
    assert mem.words() == before
    mem.write_words({10: 5, 12: 6})
    assert (mem.word(10), mem.word(12)) == (5, 6)


def test_any_format_may_be_read_from_any_address():
    # decision 4: the value must match its letter; addresses carry no fixed format
    mem = CamMemory()
    mem.write("I", 6, -8388608)
    assert mem.read("F", 6) == -1.0 and mem.read("B", 6) == (0, 0, 128)
    assert mem.read(Fmt.I, 6) == -8388608


# -- RESETF and VF ------------------------------------------------------------------------------


def test_writes_take_effect_only_after_vf():
    mem = CamMemory()
    mem.write("F", 10, 0.25)
    assert mem.read("F", 10) == 0.25 and mem.read("F", 10, valid=True) == 0.0 and mem.dirty
    result = mem.vf()
    assert result.full is False and result.addresses == (10,) and result.duration_s < 0.5
    assert mem.read("F", 10, valid=True) == 0.25 and not mem.dirty and mem.modified == ()


def test_modified_address_table_of_20_entries():
    mem = CamMemory()
    for k in range(20):
        mem.write("F", 100 + 2 * k, 0.5)
    mem.write("F", 100, 0.25)  # the same address again: still 20 entries
    assert len(mem.modified) == 20 and not mem.modified_overflow
    result = mem.vf()
    assert not result.full and len(result.addresses) == 20
    for k in range(21):
        mem.write("F", 100 + 2 * k, 0.125)
    assert mem.modified_overflow  # table full: the whole memory is transmitted
    result = mem.vf()
    assert result.full and result.duration_s == 0.5
    assert mem.words(valid=True) == mem.words()


def test_decision_5_every_write_access_enters_the_table():
    mem = CamMemory()
    mem.write("F", 6, 0.0)  # the value it already holds
    assert mem.modified == (6,) and not mem.dirty
    assert mem.vf().addresses == (6,)


def test_vf_without_modification_is_a_full_vf():
    # "If, at the time of the VF command, there is no modification in the cam memory, the entire VF (ca. 0.5s) is executed."
    result = CamMemory().vf()
    assert result.full and result.duration_s == 0.5


def test_resetf_clears_everything_and_needs_vf():
    mem = CamMemory()
    assert mem.resetf() == 1.0
    assert set(mem.words()) == {0} and mem.curve_count() == 0
    assert mem.curve_count(valid=True) == 1  # decision 6: not valid before VF
    assert mem.vf().full
    assert set(mem.words(valid=True)) == {0}


# -- persistence --------------------------------------------------------------------------------


def test_save_and_load_round_trip(tmp_path):
    mem = CamMemory()
    mem.write("F", 6, 0.1234567)
    mem.write("B", 7, (1, 10, 246))
    mem.write("I", 5440, -5)
    path = tmp_path / "cam.json"
    mem.save(path)
    loaded = CamMemory.load(path)
    assert loaded.words() == mem.words()
    # decision 7: power-on makes everything valid, the table is empty
    assert loaded.words(valid=True) == mem.words() and loaded.modified == () and not loaded.dirty
    assert json.loads(path.read_text())["format"] == "axisline-compax-cam-memory"


def test_failed_save_keeps_the_old_file(tmp_path, monkeypatch):
    path = tmp_path / "cam.json"
    CamMemory().save(path)
    old = path.read_bytes()
    mem = CamMemory.blank()

    def broken_fsync(fd):
        raise OSError("disk full")

    monkeypatch.setattr(os, "fsync", broken_fsync)
    with pytest.raises(OSError):
        mem.save(path)
    monkeypatch.undo()
    assert path.read_bytes() == old
    assert sorted(p.name for p in tmp_path.iterdir()) == ["cam.json"]  # no temporary file left
    assert CamMemory.load(path).curve_count() == 1


@pytest.mark.parametrize(
    "content",
    [
        "not json",
        json.dumps({"format": "other", "version": 1, "size": SIZE, "words": "0" * 6 * SIZE}),
        json.dumps({"format": "axisline-compax-cam-memory", "version": 2, "size": SIZE, "words": "0" * 6 * SIZE}),
        json.dumps({"format": "axisline-compax-cam-memory", "version": 1, "size": SIZE, "words": "0" * 60}),
        json.dumps({"format": "axisline-compax-cam-memory", "version": 1, "size": SIZE,
                    "words": "G" + "0" * (6 * SIZE - 1)}),
        json.dumps({"format": "axisline-compax-cam-memory", "version": 1, "size": SIZE,
                    "words": "0000FF" + "0" * (6 * SIZE - 6)}),
    ],
)
def test_load_rejects_bad_files(tmp_path, content):
    path = tmp_path / "bad.json"
    path.write_text(content)
    with pytest.raises(CompaxError):
        CamMemory.load(path)


def test_copy_is_independent():
    mem = CamMemory()
    other = mem.copy()
    other.write("F", 6, 0.5)
    assert mem.word(6) == 0 and other.word(6) == 0x400000 and other.modified == (6,)
    assert cm.MAX_CURVES == 100 and cm.MAX_POINTS_PER_CURVE == 2500
