"""COMPAX curves: CurveRecord from / to the cam memory, point tables, CSV, motion laws (compax.md §2.7, §2.21)."""

from __future__ import annotations

import math

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from axisline.devices.compax import E_CAPACITY, E_CURVE_NOT_PRESENT, E_VALUE, CompaxError
from axisline.devices.compax.cammemory import (
    FULL_SCALE,
    CamMemory,
    aux_address,
    block_address,
    set_point_address,
)
from axisline.devices.compax.curves import (
    AuxFunction,
    CurveRecord,
    curve_from_cam,
    curve_from_csv,
    curve_from_table,
    curve_to_csv,
    next_free_point,
    read_curve,
    store_cam,
    write_curve,
)
from axisline.motion.cam import PointTable
from axisline.motion.segments import SegmentCam

SET_POINTS = [0, .1, .2, .3, .4, .5, .6, .7, .8, .9, .9999999]
AUX = [(1, 10, 246), (3, 20, 236), (7, 30, 226), (15, 40, 216), (31, 50, 206), (63, 60, 196), (127, 70, 186),
       (255, 80, 176), (254, 90, 166), (252, 100, 156), (248, 110, 146)]
BLOCK = {"coupling": .1, "synchronous": .6, "decoupling": .2, "braking": .7, "standstill": -.1,
         "label_set_point": .5, "label_window": .05, "correction_enable": .1, "correction_disable": .9}
BLOCK_VALUES = [.1, .6, .2, .7, -.1, 0, .5, .05, .1, .9]  # F5454 ... F5445 / F5434 ... F5425


def manual_example_memory() -> CamMemory:
    """§25's two example curves, written address by address as a host would (X20)."""
    mem = CamMemory.blank()
    mem.write("I", 1, 2)
    for curve, base, first in ((1, 5460, 1), (2, 5440, 12)):
        mem.write("I", base, 360)
        mem.write("F", base - 1, 0.0)
        mem.write("I", base - 2, first)
        mem.write("I", base - 3, first + 10)
        mem.write("I", base - 4, 360)
        mem.write("F", base - 5, 0.0)
        for i, value in enumerate(BLOCK_VALUES):
            mem.write("F", base - 6 - i, value)
        for i, (value, aux) in enumerate(zip(SET_POINTS, AUX)):
            mem.write("F", set_point_address(first + i), value)
            mem.write("B", aux_address(first + i), aux)
    mem.vf()
    return mem


# -- the manual's example (X20) -----------------------------------------------------------------


def test_x20_manual_example_curves_read_as_records():
    mem = manual_example_memory()
    # curve 1: I5460 ... F5441, set points F0006 ... F0026; curve 2: I5440 ... F5421, F0028 ... F0048
    for number, first, last in ((1, 1, 11), (2, 12, 22)):
        rec = read_curve(mem, number)
        assert (rec.number, rec.master_cycle, rec.slave_cycle) == (number, 360.0, 360.0)
        assert (rec.first_point, rec.last_point) == (first, last)
        assert rec.set_points[0] == 0.0 and rec.set_points[-1] == 1.0  # .9999999 = S_T
        assert rec.set_points == pytest.approx([float(v) for v in SET_POINTS[:-1]] + [1.0], abs=2**-23)
        assert list(zip(rec.aux_digital, [a if a < 128 else a - 256 for a in rec.aux_analog0])) == [
            (d, a0) for d, a0, _ in AUX]
        assert rec.aux(1) == AuxFunction(3, 20, 236 - 256)
        for name, value in BLOCK.items():
            assert getattr(rec, name) == pytest.approx(value, abs=2**-23), name
        assert rec.open and not rec.closed


def test_x20_curve_is_m_for_mt_st_360():
    # "curve(m) = m (gradient 1) for M_T = S_T = 360; at m = 180 slave = 180"
    rec = read_curve(manual_example_memory(), 1)
    table = rec.to_point_table()
    assert isinstance(table, PointTable) and table.equidistant_step == 36.0
    assert table.eval(180.0)[0] == 180.0
    assert table.eval(360.0)[0] == 360.0  # 0.9999999 is exactly S_T
    for m in (0.0, 17.3, 123.4, 359.9):
        assert table.eval(m)[0] == pytest.approx(m, abs=360 * 2**-23)


def test_x20_aux_at_180_is_63_and_analogue_0_interpolates_10_to_110():
    rec = read_curve(manual_example_memory(), 1)
    aux = rec.aux_at(180.0)
    assert aux.digital == 63
    outputs = aux.outputs()
    assert all(outputs[f"O{k}"] for k in range(7, 13)) and not outputs["O13"] and not outputs["O14"]
    assert rec.aux_at(179.9).digital == 31 and rec.aux_at(0.0).digital == 1 and rec.aux_at(360.0).digital == 248
    ch0 = rec.analog_table(0)
    assert ch0.eval(0.0)[0] == 10 and ch0.eval(180.0)[0] == 60 and ch0.eval(360.0)[0] == 110
    assert ch0.eval(18.0)[0] == pytest.approx(15.0)


@pytest.mark.parametrize(
    ("text", "bits", "an0", "an1"),
    [("128;0;0", "10000000", 0.0, 0.0), ("255;127;255", "11111111", 10.0, -0.078),
     ("1;1;128", "00000001", 0.078, -10.0)],
)
def test_x22_aux_decode_examples(text, bits, an0, an1):
    # §25 "B7=128;0;0: O14 = 1, O13 ... O7 = 0 ..."; decision 7: 1 LSB = 10 V / 128 at P73 = 100
    aux = AuxFunction.parse(text)
    outputs = aux.outputs()
    assert "".join("1" if outputs[f"O{k}"] else "0" for k in range(14, 6, -1)) == bits
    assert aux.volts(0) == pytest.approx(an0, abs=0.08) and aux.volts(1) == pytest.approx(an1, abs=0.001)
    assert AuxFunction.from_word(aux.word()) == aux


def test_x22_analogue_scaling_exact_values_and_gain():
    assert AuxFunction(0, 127, 1).volts(0) == 127 * 10 / 128  # 9.92 V ("10V")
    assert AuxFunction(0, 1, 0).volts(0) == 0.078125
    assert AuxFunction(0, -128, 0).volts(0) == -10.0
    assert AuxFunction(0, -128, 0).volts(0, gain=10) == -1.0  # P71 = 10: 100 % = 1 V
    with pytest.raises(CompaxError):
        AuxFunction(0, 0, 0).volts(2)
    with pytest.raises(CompaxError):
        AuxFunction.parse("1;x;3")


# -- delivery state and E17 ---------------------------------------------------------------------


def test_delivery_state_curve_1_is_gradient_1():
    rec = read_curve(CamMemory(), 1)
    assert (rec.master_cycle, rec.slave_cycle, rec.set_points) == (360.0, 360.0, [0.0, 1.0])
    table = rec.to_point_table()
    assert table.eval(123.4)[:2] == (123.4, 1.0)
    assert all(getattr(rec, name) == 0.0 for name in BLOCK)


@pytest.mark.parametrize("number", [0, 2, 3, -1, 1.0, "1", True, None])
def test_e17_for_a_non_existent_curve(number):
    with pytest.raises(CompaxError) as info:
        read_curve(CamMemory(), number)
    assert info.value.code == E_CURVE_NOT_PRESENT and "not present" in str(info.value)


def test_e17_after_resetf_and_vf():
    mem = CamMemory()
    mem.resetf()
    read_curve(mem, 1)  # still valid until VF
    mem.vf()
    with pytest.raises(CompaxError) as info:
        read_curve(mem, 1)
    assert info.value.code == E_CURVE_NOT_PRESENT


@pytest.mark.parametrize(
    ("words", "reason"),
    [({0: 0}, "M_T"), ({0: 0xFFFFFF}, "M_T"), ({2: 0}, "set points"), ({3: 1}, "set points"),
     ({3: 2600}, "set points"), ({2: 300, 3: 2720}, "reach")],
)
def test_e17_for_a_control_block_that_describes_no_curve(words, reason):
    # decision 4
    mem = CamMemory()
    mem.write_words({block_address(1, offset): word for offset, word in words.items()})
    mem.vf()
    with pytest.raises(CompaxError, match=reason) as info:
        read_curve(mem, 1)
    assert info.value.code == E_CURVE_NOT_PRESENT


def test_memory_curve_method_is_read_curve_of_the_valid_copy():
    mem = CamMemory()
    assert mem.curve(1) == read_curve(mem, 1)
    write_curve(mem, CurveRecord(number=2, master_cycle=100, slave_cycle=50, set_points=[0, 1]))
    with pytest.raises(CompaxError):
        mem.curve(2)
    assert mem.curve(2, valid=False).master_cycle == 100


# -- open / closed, point tables ----------------------------------------------------------------


def test_open_and_closed_curves():
    # §8.1: closed - start and end positions of the slave identical; open - not identical
    closed = CurveRecord(number=1, master_cycle=360, slave_cycle=100, set_points=[0, 0.5, 1.0, 0.5, 0])
    open_ = CurveRecord(number=1, master_cycle=360, slave_cycle=100, set_points=[0, 0.5, 1.0])
    assert closed.closed and not closed.open
    assert open_.open and open_.to_point_table().cycle_offset == 100.0
    assert closed.to_point_table().eval(180.0)[0] == 100.0


def test_to_point_table_is_equidistant_over_mt_with_slave_fraction_times_st():
    # §2.7.2 [DERIVED]: point k at k·M_T/(N-1), slave = F_k·S_T
    rec = CurveRecord(number=1, master_cycle=200, slave_cycle=-40, set_points=[0, 0.25, -0.5, 1.0])
    table = rec.to_point_table()
    assert list(table.master) == pytest.approx([0, 200 / 3, 400 / 3, 200])
    assert list(table.slave) == [0.0, -10.0, 20.0, -40.0]
    assert table.fractions(-40) == rec.set_point_words()


def test_decision_1_standstill_equal_st_is_representable():
    # §8.2.1 exception S_0 = S_T: stored as 0x7FFFFF and read back as exactly 1.0
    mem = CamMemory()
    write_curve(mem, CurveRecord(number=2, master_cycle=360, slave_cycle=360, set_points=[0, 1.0], standstill=1.0))
    assert mem.word(block_address(2, 10)) == FULL_SCALE
    mem.vf()
    assert read_curve(mem, 2).standstill == 1.0


# -- writing ------------------------------------------------------------------------------------


def example_record(number: int = 2, **changes) -> CurveRecord:
    fields = dict(number=number, master_cycle=360.0, slave_cycle=360.0, set_points=list(SET_POINTS),
                  aux_digital=[a[0] for a in AUX], aux_analog0=[a[1] for a in AUX],
                  aux_analog1=[a[2] - 256 if a[2] > 127 else a[2] for a in AUX], **BLOCK)
    fields.update(changes)
    return CurveRecord(**fields)


def test_write_then_read_reproduces_the_manual_example_words():
    mem = CamMemory.blank()
    write_curve(mem, example_record(1))
    write_curve(mem, example_record(2))
    mem.vf()
    expected = manual_example_memory()
    assert mem.words(valid=True) == expected.words(valid=True)
    assert read_curve(mem, 2).first_point == 12 and read_curve(mem, 2).last_point == 22


def test_write_new_curve_increments_i0001_and_allocates_first_fit():
    mem = CamMemory()  # delivery: curve 1 uses set points 1, 2
    rec = write_curve(mem, example_record(2))
    assert (rec.first_point, rec.last_point) == (3, 13)
    assert mem.curve_count() == 2 and mem.curve_count(valid=True) == 1
    assert next_free_point(mem, 5) == 14
    mem.vf()
    assert read_curve(mem, 2).set_points[-1] == 1.0


def test_replacing_a_curve_reuses_its_place_or_moves_to_the_first_free_one():
    mem = CamMemory()
    write_curve(mem, example_record(2))  # 3 ... 13
    write_curve(mem, example_record(3))  # 14 ... 24
    smaller = write_curve(mem, CurveRecord(number=2, master_cycle=100, slave_cycle=10, set_points=[0, 0.5, 1.0]))
    assert (smaller.first_point, smaller.last_point) == (3, 5)
    bigger = write_curve(mem, CurveRecord(number=2, master_cycle=100, slave_cycle=10, set_points=[0.0] * 15))
    assert (bigger.first_point, bigger.last_point) == (25, 39)
    assert mem.curve_count() == 3


def test_overlap_with_another_curve_is_refused_and_nothing_written():
    mem = CamMemory()
    write_curve(mem, example_record(2))  # 3 ... 13
    before = mem.words()
    with pytest.raises(CompaxError, match="overlap curve 2") as info:
        write_curve(mem, example_record(3, first_point=10))
    assert info.value.code == E_CAPACITY
    assert mem.words() == before


def test_capacity_is_checked_before_writing():
    # §2.21: 2·L + 20·C <= 5455
    mem = CamMemory.blank()
    write_curve(mem, CurveRecord(number=1, master_cycle=1, slave_cycle=1, set_points=[0.0] * 2500))
    before = mem.words()
    with pytest.raises(CompaxError) as info:
        write_curve(mem, CurveRecord(number=2, master_cycle=1, slave_cycle=1, set_points=[0.0] * 300))
    assert info.value.code == E_CAPACITY and "5455" in str(info.value)
    assert mem.words() == before
    write_curve(mem, CurveRecord(number=2, master_cycle=1, slave_cycle=1, set_points=[0.0] * 200))  # 5400+40


def test_curve_numbers_are_consecutive():
    mem = CamMemory()
    with pytest.raises(CompaxError, match="next new curve is 2"):
        write_curve(mem, example_record(3))


@pytest.mark.parametrize(
    ("changes", "field"),
    [
        ({"label_window": 0.31}, "label_window"),  # "Restriction: M_f <= 0,3 * M_T"
        ({"coupling": 0.7, "synchronous": 0.6}, "coupling"),  # "Condition: M_E < M_S"
        ({"decoupling": 0.8, "braking": 0.7}, "decoupling"),  # "Condition: M_A < M_B"
        ({"standstill": 1.5}, "standstill"),  # "Value range: ±S_T"
        ({"coupling": -0.1}, "coupling"),
        ({"correction_disable": 1.2}, "correction_disable"),
        ({"set_points": [0.0, 1.5]}, "set_points[1]"),
        ({"set_points": [0.0]}, "set_points"),
        ({"set_points": [0.0] * 2501}, "set_points"),
        ({"aux_digital": [256] + [0] * 10}, "aux_digital[0]"),
        ({"aux_analog0": [128] + [0] * 10}, "aux_analog0[0]"),
        ({"aux_digital": [0] * 3}, "aux_digital"),
        ({"master_cycle": 0.0}, "master_cycle"),
        ({"master_cycle": float("nan")}, "curve 2 master_cycle (M_T)"),
        ({"slave_cycle": 2.0**24}, "slave_cycle"),
        ({"number": 0}, "number"),
        ({"number": 101}, "number"),
        ({"first_point": 1, "last_point": 5}, "last_point"),
        ({"first_point": 0}, "first_point"),
    ],
)
def test_field_checks_name_the_field_and_write_nothing(changes, field):
    mem = CamMemory()
    before = mem.words()
    with pytest.raises(CompaxError) as info:
        write_curve(mem, example_record(changes.pop("number", 2), **changes))
    assert info.value.field == field and info.value.code == E_VALUE
    assert mem.words() == before and mem.modified == ()


def test_write_leaves_field_11_and_the_unused_addresses_alone():
    mem = CamMemory()
    mem.write_words({block_address(2, 11): 0x123456, block_address(2, 19): 0x654321})
    write_curve(mem, example_record(2))
    assert mem.word(block_address(2, 11)) == 0x123456 and mem.word(block_address(2, 19)) == 0x654321


def test_master_and_slave_cycles_with_fractions():
    # decision 6: I = floor(x), F = x - I
    mem = CamMemory()
    write_curve(mem, CurveRecord(number=2, master_cycle=360.5, slave_cycle=-300.25, set_points=[0, -1.0]))
    assert mem.read("I", 5440) == 360 and mem.read("F", 5439) == 0.5
    assert mem.read("I", 5436) == -301 and mem.read("F", 5435) == 0.75
    mem.vf()
    rec = read_curve(mem, 2)
    assert (rec.master_cycle, rec.slave_cycle) == (360.5, -300.25)


@settings(max_examples=40)
@given(
    st.lists(st.integers(min_value=-(1 << 23), max_value=(1 << 23) - 1), min_size=2, max_size=30),
    st.floats(min_value=0.001, max_value=1e6, allow_nan=False),
    st.floats(min_value=-1e6, max_value=1e6, allow_nan=False),
)
def test_write_read_round_trip_keeps_every_word(raw_points, master_cycle, slave_cycle):
    points = [k / (1 << 23) for k in raw_points]
    mem = CamMemory()
    rec = write_curve(mem, CurveRecord(number=2, master_cycle=master_cycle, slave_cycle=slave_cycle,
                                       set_points=points, coupling=0.25, synchronous=0.5))
    mem.vf()
    back = read_curve(mem, 2)
    assert back.set_point_words() == rec.set_point_words()
    assert back.master_cycle == pytest.approx(master_cycle, abs=2**-23)
    assert back.slave_cycle == pytest.approx(slave_cycle, abs=2**-23)
    assert (back.coupling, back.synchronous) == (0.25, 0.5)


# -- building curves: tables, motion laws, CSV --------------------------------------------------


def test_curve_from_equidistant_table_default_slave_cycle_is_max_curve_value():
    # decision 8: "The slave cycle always corresponds to the max. curve value"
    table = PointTable.equidistant([0.0, 30.0, 120.0, 90.0], 300.0)
    rec = curve_from_table(table, 2, coupling=0.1)
    assert rec.slave_cycle == 120.0 and rec.set_points == [0.0, 0.25, 1.0, 0.75] and rec.coupling == 0.1
    assert rec.to_point_table().eval(200.0)[0] == 120.0
    with pytest.raises(CompaxError, match="outside"):
        curve_from_table(table, 2, slave_cycle=100.0)
    with pytest.raises(CompaxError, match="unknown curve field"):
        curve_from_table(table, 2, couplng=0.1)


def test_curve_from_non_equidistant_table_needs_points():
    table = PointTable([0.0, 10.0, 100.0], [0.0, 50.0, 100.0])
    with pytest.raises(CompaxError, match="points=N"):
        curve_from_table(table, 2)
    rec = curve_from_table(table, 2, points=11)
    assert rec.n_points == 11 and rec.set_points[1] == 0.5 and rec.set_points[-1] == 1.0


def test_curve_from_segment_cam_samples_equidistant_set_points():
    cam = SegmentCam([(90.0, 0.0, "dwell"), (180.0, 50.0, "cycloidal"), (270.0, 50.0, "dwell"),
                      (360.0, 0.0, "modified_sine")], start=0.0)
    rec = curve_from_cam(cam, 2, 361, coupling=0.05, synchronous=0.2)
    assert rec.n_points == 361 and rec.master_cycle == 360.0 and rec.slave_cycle == 50.0
    assert rec.closed
    table = rec.to_point_table()
    for x in (0.0, 45.0, 135.0, 180.0, 225.0, 300.0, 359.0):
        assert table.eval(x)[0] == pytest.approx(cam.eval(x)[0], abs=1e-5)
    mem = CamMemory()
    stored = store_cam(mem, cam, 2, 361, synchronous=0.2)
    assert (stored.first_point, stored.last_point) == (3, 363)
    mem.vf()
    assert read_curve(mem, 2).to_point_table().eval(135.0)[0] == pytest.approx(cam.eval(135.0)[0], abs=1e-5)


def test_open_feed_cam_ends_exactly_on_the_full_slave_cycle():
    cam = SegmentCam([(120.0, 40.0, "poly345"), (360.0, 100.0, "constant_velocity")], start=0.0)
    rec = curve_from_cam(cam, 2, 50)
    assert rec.slave_cycle == 100.0 and rec.set_points[-1] == 1.0
    assert rec.set_point_words()[-1] == FULL_SCALE and rec.open
    assert rec.to_point_table().cycle_offset == 100.0
    with pytest.raises(CompaxError, match="points"):
        curve_from_cam(cam, 2, 1)
    with pytest.raises(CompaxError, match="slave_cycle"):
        curve_from_cam(SegmentCam([(360.0, 0.0, "dwell")]), 2, 5)


def test_csv_export_and_import_round_trip(tmp_path):
    rec = example_record(2)
    path = tmp_path / "curve.csv"
    curve_to_csv(rec, path)
    assert path.read_text().splitlines()[0] == "master,slave"
    back = curve_from_csv(path, 2, slave_cycle=360.0)
    assert back.set_point_words() == rec.set_point_words()
    assert back.master_cycle == 360.0
    auto = curve_from_csv(path, 3)  # S_T = max |slave| = 360
    assert auto.slave_cycle == 360.0 and auto.set_point_words() == rec.set_point_words()


def test_csv_import_errors(tmp_path):
    path = tmp_path / "bad.csv"
    path.write_text("master,slave\n0,0\n10,5\n100,10\n")
    with pytest.raises(CompaxError, match="equidistant"):
        curve_from_csv(path, 2)
    resampled = curve_from_csv(path, 2, points=3)  # master 0, 50, 100: slave 0, 5 + 5·40/90, 10
    assert resampled.slave_cycle == 10.0
    assert resampled.set_points == pytest.approx([0.0, (5 + 5 * 40 / 90) / 10, 1.0])
    path.write_text("master,slave\n0,0\n10,abc\n")
    with pytest.raises(ValueError, match="line 3"):
        curve_from_csv(path, 2)


def test_x20_second_curve_addresses():
    mem = manual_example_memory()
    assert [mem.read("I", a) for a in (5440, 5438, 5437, 5436)] == [360, 12, 22, 360]
    assert mem.read("F", 28) == 0.0 and mem.read("B", 49) == (248, 110, 146)
    assert math.isclose(mem.read("F", 5430), -0.1, abs_tol=2**-23)
