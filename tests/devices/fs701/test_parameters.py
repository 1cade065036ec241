"""FS701 parameters: the §11 register list as data, ParameterSet, scaling rules (manual §4, spec fs701.md §3, §7)."""

from __future__ import annotations

import copy
import math
import pickle
from decimal import Decimal

import pytest
from hypothesis import given
from hypothesis import strategies as st

from axisline.devices.fs701.parameters import (
    BLOCKS,
    PARAMETERS,
    PARAMETERS_BY_CODE,
    ParameterError,
    ParameterRangeError,
    ParameterSet,
    RatioClass,
    UnknownParameterError,
    adjust_default_speed,
    carriage_counts_to_lu,
    check_encoder_rules,
    count_rate_to_line_speed,
    counter_multiplier,
    effective_virtual_line_speed,
    encoder_ratio_class,
    jog_acceleration,
    jog_speed,
    line_counts_to_lu,
    line_speed_to_count_rate,
    lu_to_carriage_counts,
    lu_to_line_counts,
    lu_to_physical,
    max_printmarks_between_sensor_and_carriage,
    max_return_speed,
    parameter,
    parameter_table_markdown,
    pulses_per_1000_lu,
    ratio_raises_error_05,
    snake_case,
    sync_ratio,
    virtual_master_acceleration,
    virtual_master_count_rate,
    virtual_speed_quantum,
    virtual_speed_steps,
)

# The attribute names the cut cycle uses (one line per block, §11 order).
EXPECTED_ATTRS = {
    "general": "cutting_length test_cut_length virtual_line_speed",
    "basic_settings": (
        "pulses_line_1000 pulses_cut_1000 acceleration_1 acceleration_2 ramp_form sync_rate return_speed "
        "edge_sense synchron_time cut_window sync_samples tool_width cutting_mode photocell_cut gap_length gap_time "
        "ramp_vir_master set_length_cou_ps set_length_cou_lu printmark_edge virt_printmarks deceleration_1 "
        "deceleration_2 printmark_offset photocell_delay printm_per_length printmark_window missing_printmarks "
        "abs_return_speed freeze_mode"
    ),
    "control_loop": "p_gain i_time max_correction max_line_speed sampling_time",
    "jog_home_ref": (
        "home_window minimum_position maximum_position alarm_position jog_speed_forw jog_ramp_up_forw "
        "jog_ramp_dw_forw jog_speed_rev jog_ramp_up_rev jog_ramp_dw_rev"
    ),
    "monitoring": "zero_speed_master zero_speed_vir_ma led_function length_per_pulse master_rev_limit batch_counter waste_counter",
    "additional_cuts": "additional_cuts add_cut_1_length add_cut_2_length add_cut_3_length",
    "communication": (
        "can_unit_address can_baud_rate can_config can_tx_par can_rx_par ser_unit_address ser_baud_rate ser_data_format"
    ),
    "set_up": (
        "mode_counter_1 dir_counter_1 mode_counter_2 dir_counter_2 mode_counter_3 dir_counter_3 mode_counter_4 "
        "dir_counter_4 ana_out_offset_1 ana_out_gain_1 ana_out_offset_2 ana_out_gain_2 ana_out_offset_3 "
        "ana_out_gain_3 ana_out_offset_4 ana_out_gain_4 ana_in_1_offset ana_in_1_gain ana_in_2_offset ana_in_2_gain "
        "ana_in_3_offset ana_in_3_gain ana_in_4_offset ana_in_4_gain index_output frequency_output dir_frequency "
        "frequency_select index_1_select index_2_select index_3_select index_4_select"
    ),
}


# ---- the data ----------------------------------------------------------------------------------


def test_every_block_has_the_manual_parameters_in_section_11_order():
    for key, names in EXPECTED_ATTRS.items():
        assert [p.attr for p in PARAMETERS if p.block == key] == names.split(), key
    assert len(PARAMETERS) == sum(len(v.split()) for v in EXPECTED_ATTRS.values()) == 99


def test_codes_are_unique_and_inside_their_block():
    assert len(PARAMETERS_BY_CODE) == len(PARAMETERS)
    for p in PARAMETERS:
        assert p.code in BLOCKS[p.block].codes, p.name


def test_attribute_is_the_snake_case_of_the_manual_name_or_a_documented_rename():
    for p in PARAMETERS:
        assert p.attr == snake_case(p.name), p.name
    # the text's names are aliases
    assert parameter("rel_return_speed").attr == "return_speed" and parameter("sync_mode").attr == "freeze_mode"
    assert snake_case("+/- Sync Rate") == "sync_rate"
    assert snake_case("Pulses Line / 1000") == "pulses_line_1000"
    assert snake_case("Photocell -> Cut") == "photocell_cut"


def test_every_default_lies_in_its_range():
    for p in PARAMETERS:
        assert p.minimum <= p.default <= p.maximum, p.name
        p.check_raw(p.default)


def test_section_11_values_as_decided():
    p = parameter
    # shifted rows 0x0111..0x0115 (fs701.md §3.4 table error): ranges from the text
    assert (p("set_length_cou_ps").minimum, p("set_length_cou_ps").maximum) == (0, 999_999_999)
    assert (p("set_length_cou_lu").maximum, p("printmark_edge").maximum) == (999_999, 1)
    assert (p("deceleration_1").minimum, p("deceleration_1").maximum, p("deceleration_1").default) == (1, 99_999, 1000)
    assert (p("printm_per_length").minimum, p("printm_per_length").default) == (1, 1)
    # conflicts
    assert p("cut_window").unit == "Incr." and p("max_correction").unit == "mV"
    assert p("photocell_delay").decimals == 1 and p("photocell_delay").maximum_value == 500.0
    assert p("ana_out_gain_2").default_value == 10.0 and p("ana_out_gain_2").maximum_value == 320.0
    assert p("sampling_time").maximum == 1000 and p("gap_time").minimum == 10
    assert (p("sync_rate").minimum_value, p("sync_rate").maximum_value) == (-9.99, 9.99)
    assert (p("return_speed").minimum_value, p("return_speed").default_value) == (0.01, 1.0)
    assert p("i_time").maximum_value == 9.999
    assert p("batch_counter").maximum == 9_999_999_999
    # table ranges where the text differs (module docstring)
    assert (p("jog_speed_forw").minimum, p("jog_ramp_up_forw").minimum, p("length_per_pulse").maximum) == (1, 0, 50_000)
    assert (p("minimum_position").maximum, p("maximum_position").minimum) == (0, 0)
    assert (p("ramp_form").minimum, p("ramp_form").maximum, p("can_baud_rate").maximum) == (0, 15, 7)
    assert p("dir_counter_1").default == 1 and p("ana_in_1_gain").default_value == 10.0
    # defaults of §3.9 / §7 E13: serial address 11, 9600 baud, 7E1
    d = ParameterSet()
    assert (d.ser_unit_address, d.ser_baud_rate, d.ser_data_format) == (11, 2, 0)
    assert parameter("ser_baud_rate").choices[2] == "9600 bit/s" and parameter("ser_data_format").choices[0] == "7E1"


# ---- get / set -----------------------------------------------------------------------------------


def test_get_and_set_by_attribute_alias_manual_name_and_code():
    s = ParameterSet()
    s.sync_rate = 1.5
    assert s.get(0x0105) == 1.5 and s.get_raw("sync_rate") == 150
    assert s.get("+/- Sync Rate") == s.get("Sync Rate") == s["sync_rate"] == 1.5
    s.set(0x0000, 2500)
    assert s.cutting_length == 2500 and s.get("Cutting Length") == 2500
    s.rel_return_speed = 2  # alias of return_speed ("Rel. Return Speed" in the text)
    assert s.return_speed == 2.0 and s.get_raw(0x0106) == 200
    s.sync_mode = 1  # alias of freeze_mode ("Sync Mode" in the text)
    assert s.freeze_mode == 1
    s.set_raw("photocell_delay", 125)
    assert s.photocell_delay == 12.5
    s["i_time"] = "0.030"  # §7.5 "I-Time to e.g. 30" read as 0.030 s
    assert s.get_raw("i_time") == 30


def test_unknown_names_and_codes_are_named_in_the_error():
    s = ParameterSet()
    with pytest.raises(UnknownParameterError, match="0x0003"):
        s.get(0x0003)
    with pytest.raises(UnknownParameterError, match="cuting_length"):
        s.set("cuting_length", 1)
    with pytest.raises(AttributeError):
        _ = s.cuting_length
    with pytest.raises(AttributeError):
        s.cuting_length = 5
    assert "sync_rate" in s and 0x0105 in s and "nonsense" not in s


def test_range_error_names_field_value_and_range():
    s = ParameterSet()
    with pytest.raises(ParameterRangeError) as info:
        s.sync_rate = 10.0
    msg = str(info.value)
    assert "+/- Sync Rate" in msg and "sync_rate" in msg and "0x0105" in msg and "10.0" in msg and "-9.99..9.99" in msg
    assert info.value.minimum == -9.99 and info.value.maximum == 9.99
    assert s.sync_rate == 0.0
    with pytest.raises(ParameterRangeError, match="1..999999"):
        s.cutting_length = 0
    with pytest.raises(ParameterRangeError, match="resolution 0.01"):
        s.sync_rate = 1.005
    with pytest.raises(ParameterRangeError, match="resolution 0.01"):
        s.set("sync_rate", "1.005")
    with pytest.raises(ParameterRangeError, match="bool"):
        s.edge_sense = True
    with pytest.raises(ParameterRangeError, match="finite"):
        s.sync_rate = math.nan
    with pytest.raises(ParameterRangeError, match="not a number"):
        s.sync_rate = "fast"
    s.sync_rate = 0.1 + 0.2  # binary noise within 1e-6 of a step is accepted
    assert s.get_raw("sync_rate") == 30
    s.sync_rate = Decimal("-9.99")
    assert s.get_raw("sync_rate") == -999


@given(st.sampled_from(PARAMETERS), st.integers(min_value=-(10**11), max_value=10**11))
def test_out_of_range_raw_values_are_refused_and_change_nothing(p, raw):
    s = ParameterSet()
    before = s.get_raw(p)
    ok = p.minimum <= raw <= p.maximum and not (p.forbid_zero_digit and "0" in str(raw))
    if ok:
        s.set_raw(p, raw)
        assert s.get_raw(p) == raw
        assert s.get(p.attr) == p.from_raw(raw)
    else:
        with pytest.raises(ParameterRangeError):
            s.set_raw(p, raw)
        assert s.get_raw(p) == before


@given(st.sampled_from(PARAMETERS), st.data())
def test_engineering_values_round_trip(p, data):
    raw = data.draw(st.integers(min_value=p.minimum, max_value=p.maximum))
    if p.forbid_zero_digit and "0" in str(raw):
        return
    s = ParameterSet()
    s.set(p.attr, p.from_raw(raw))
    assert s.get_raw(p.attr) == raw
    s.set(p.code, p.format_value(raw))  # the text form with its decimal point
    assert s.get_raw(p.code) == raw


def test_update_is_all_or_nothing():
    s = ParameterSet()
    with pytest.raises(ParameterRangeError, match="tool_width"):
        s.update({"cutting_length": 2000, "tool_width": 1000})
    assert s.cutting_length == 1000
    s.update({"cutting_length": 2000, 0x010B: 5})
    assert (s.cutting_length, s.tool_width) == (2000, 5)
    with pytest.raises(UnknownParameterError):
        s.update({"cutting_length": 3000, "nope": 1})
    assert s.cutting_length == 2000


def test_serial_address_without_zero_digit_fs701_md_7_e13():
    s = ParameterSet()
    for bad in (1, 10, 20, 30, 90, 100):
        with pytest.raises(ParameterRangeError):
            s.ser_unit_address = bad
    for good in (*range(11, 20), *range(21, 30), 99):
        s.ser_unit_address = good
        assert s.ser_unit_address == good


def test_diff_copy_reset_and_defaults():
    a, b = ParameterSet(), ParameterSet()
    assert a == b and a.diff(b) == []
    b.sync_rate, b.cutting_length = -1.25, 1500
    d = a.diff(b)
    assert [x.name for x in d] == ["cutting_length", "sync_rate"]
    assert (d[1].ours, d[1].theirs) == (0.0, -1.25)
    assert "0x0105" in str(d[1]) and "-1.25" in str(d[1])
    c = b.copy()
    assert c == b and c is not b
    c.reset("sync_rate")
    assert c.sync_rate == 0.0 and b.sync_rate == -1.25
    c.reset()
    assert c == ParameterSet.defaults()
    assert "cutting_length=1500" in repr(b)
    assert list(b)[:2] == ["cutting_length", "test_cut_length"] and len(b) == len(PARAMETERS)
    assert b.block("general") == {"cutting_length": 1500, "test_cut_length": 1000, "virtual_line_speed": 10000}
    assert ParameterSet({"cutting_length": 7}).cutting_length == 7
    assert copy.deepcopy(b) == b and pickle.loads(pickle.dumps(b)) == b
    assert len({parameter("sync_rate"), parameter(0x0105)}) == 1  # hashable
    assert ParameterSet.from_raw({"sync_rate": 5}).sync_rate == 0.05
    assert "| 0x0105 | +/- Sync Rate | `sync_rate` |" in parameter_table_markdown()


# ---- scaling (spec fs701.md §2.1, §4) ---------------------------------------------------------


def test_lu_example_fs701_md_7_e1():
    # "when you chose to set the length with a 0.1 mm resolution, 1000 LUs will represent a length of 100.0 mm"
    assert lu_to_physical(1000, 0.1) == pytest.approx(100.0)


def test_encoder_scaling_and_multiplier():
    s = ParameterSet({"pulses_line_1000": 4096, "pulses_cut_1000": 2000})
    assert lu_to_line_counts(1000, s) == 4096 and line_counts_to_lu(4096, s) == 1000
    assert lu_to_carriage_counts(500, s) == 1000 and carriage_counts_to_lu(1000, s) == 500
    assert [counter_multiplier(m) for m in (0, 1, 2)] == [1, 2, 4]
    with pytest.raises(ParameterError):
        counter_multiplier(3)
    # a 1024-ppr encoder counted x4 on a wheel of 500 mm circumference, LU = 1 mm -> 8192 pulses / 1000 LU
    assert pulses_per_1000_lu(1024, 4, 500) == 8192
    with pytest.raises(ParameterError):
        pulses_per_1000_lu(1024, 3, 500)
    # 120 000 LU/min at 10 increments / LU = 20 000 increments/s, and back
    assert line_speed_to_count_rate(120_000, 10_000) == pytest.approx(20_000)
    assert count_rate_to_line_speed(20_000, 10_000) == pytest.approx(120_000)


def test_sync_rate_changes_speed_ratio_only_fs701_md_7_e5():
    s = ParameterSet({"pulses_line_1000": 2000, "pulses_cut_1000": 1000, "sync_rate": 1.0})
    assert sync_ratio(s) == pytest.approx(0.5 * 1.01)


@pytest.mark.parametrize(
    "line, cut, cls",
    [
        (1000, 1000, RatioClass.ACCEPTABLE),
        (5000, 1000, RatioClass.ACCEPTABLE),
        (5001, 1000, RatioClass.MISMATCHED),
        (16000, 1000, RatioClass.MISMATCHED),
        (17000, 1000, RatioClass.NOT_ALLOWED),
        (16001, 1000, RatioClass.NOT_ALLOWED),
        (1000, 16000, RatioClass.MISMATCHED),
        (1000, 16001, RatioClass.NOT_ALLOWED),
    ],
)
def test_ratio_rule_fs701_md_7_e12(line, cut, cls):
    # "Acceptable ratios are in the range of 5:1 ... 1:1 ... 1:5. Mismatching beyond 1:16 and 16:1 are not allowed"
    assert encoder_ratio_class(line, cut) == cls
    assert ratio_raises_error_05(line, cut) == (cls == RatioClass.NOT_ALLOWED)
    s = ParameterSet({"pulses_line_1000": line, "pulses_cut_1000": cut})  # stored: the unit shows Error 05
    assert check_encoder_rules(s).error_05 == (cls == RatioClass.NOT_ALLOWED)


def test_frequency_rules_fs701_md_7_e12():
    # factory set: 100 000 LU/min at 1 incr/LU = 1667 Hz: fine
    assert check_encoder_rules(ParameterSet()).ok
    slow = check_encoder_rules(ParameterSet({"max_line_speed": 50_000}))  # 833 Hz < ~1 kHz
    assert [f.rule for f in slow.findings] == ["min_frequency"] and not slow.error_05
    # 9 999 999 LU/min at 4 incr/LU counted x1 = 666 666 Hz > 400 kHz on both inputs
    fast = ParameterSet({"max_line_speed": 9_999_999, "pulses_line_1000": 4000, "pulses_cut_1000": 4000})
    check = check_encoder_rules(fast)
    assert [f.rule for f in check.findings] == ["max_frequency", "max_frequency"] and not check.error_05
    fast.mode_counter_1 = fast.mode_counter_2 = 2  # x4: the signal is a quarter of the count rate
    assert check_encoder_rules(fast).ok
    mism = check_encoder_rules(ParameterSet({"pulses_line_1000": 8000}))
    assert [(f.severity, f.rule) for f in mism.findings] == [("advice", "ratio")] and mism.ok


def test_virtual_speed_quantisation_fs701_md_7_e21():
    # "Internal resolution = 1/2048 of Max Line Speed": 204 800 / 2048 = 100 LU/min; 1050 -> 1000 (truncated)
    assert virtual_speed_quantum(204_800) == 100
    assert effective_virtual_line_speed(1050, 204_800) == 1000
    assert effective_virtual_line_speed(1099, 204_800) == 1000
    assert effective_virtual_line_speed(1100, 204_800) == 1100
    # "the setting is limited to the value of register Max. Line Speed"
    assert effective_virtual_line_speed(9_999_999, 204_800) == 204_800
    assert virtual_speed_steps(9_999_999, 204_800) == 2048
    s = ParameterSet({"virtual_line_speed": 500_000})  # stored although above Max. Line Speed
    assert s.virtual_line_speed == 500_000


def test_virtual_speed_truncation_matches_adjust_screenshot_fs701_md_7_e26():
    # §7.1 screenshot: virtual master 120 000 LU/min, frequency 19 988 Hz (plausibility: Max 200 000, 10 incr/LU)
    s = ParameterSet({"virtual_line_speed": 120_000, "max_line_speed": 200_000, "pulses_line_1000": 10_000})
    assert effective_virtual_line_speed(120_000, 200_000) == 119_921.875
    assert abs(virtual_master_count_rate(s) - 19_988) < 2
    rounded = round(120_000 * 2048 / 200_000) * 200_000 / 2048 / 60 * 10  # round-to-nearest would give 20 003 Hz
    assert abs(rounded - 19_988) > 10
    s.dir_frequency = 0
    assert virtual_master_count_rate(s) < 0


def test_virtual_master_and_jog_ramps_fs701_md_7_e22():
    s = ParameterSet()  # Max. Line Speed 100 000, Jog Speed Forw. 10 %, Jog Ramp Up 1 s
    assert jog_speed(s) == 10_000 and jog_speed(s, forward=False) == 10_000
    a = jog_acceleration(s)
    assert a == pytest.approx(100_000 / 60)
    assert (10_000 / 60) / a == pytest.approx(0.1)  # 10 000 LU/min reached in 0.1 s
    s.jog_ramp_dw_rev = 0
    assert jog_acceleration(s, forward=False, up=False) == math.inf
    assert virtual_master_acceleration(s) == pytest.approx(100_000 / 60)
    s.ramp_vir_master = 0
    assert virtual_master_acceleration(s) == math.inf


def test_adjust_default_speed_fs701_md_7_e15():
    assert adjust_default_speed(100_000) == 10_000


def test_return_speed_limit_fs701_md_7_e4():
    s = ParameterSet({"return_speed": 2.0})
    assert max_return_speed(s, 10_000) == 20_000
    s.abs_return_speed = 15_000
    assert max_return_speed(s, 10_000) == 15_000 and max_return_speed(s, 50_000) == 15_000


def test_printmark_capacity_fs701_md_7_e10():
    assert [max_printmarks_between_sensor_and_carriage(n) for n in range(4)] == [64, 32, 21, 16]
    with pytest.raises(ParameterError):
        max_printmarks_between_sensor_and_carriage(4)
