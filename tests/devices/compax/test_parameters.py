"""COMPAX cam parameters: table, ranges, written / armed / valid (compax.md §3; manual §23)."""

from __future__ import annotations

from fractions import Fraction

import pytest

from axisline.devices.compax import E_UNKNOWN, E_VALUE, CompaxError, UnknownNumberError
from axisline.devices.compax.masterchain import DEFAULTS, valid_values
from axisline.devices.compax.parameters import (
    AUX_VALENCES,
    EVENTS,
    PARAMETERS,
    Parameters,
    Validity,
    aux_mask,
    check_label_sensor_distance,
    check_master_cycle_range,
    check_slave_cycle_range,
    drift_free_problems,
    max_travel_revolutions,
    p35_ramp_error_percent,
    scaled_master_cycle,
    scaled_slave_cycle,
)

# -- the table -------------------------------------------------------------------------------

SPEC_NUMBERS = (
    # §3.1 cam parameters, §3.2 drive, §3.3 encoder, §3.4 HEDA, §3.5 referenced
    30, 31, 32, 33, 34, 35, 36, 37, 38, 39, 68, 79, 90, 93, 179, 180, 210,
    80, 82, 83, 84, 85, 88, 143, 144, 98,
    18, 184, 188, 243, 245, 246, 247, 248, 249, 250,
    1, 6, 11, 12, 13, 21, *range(40, 50), 71, 72, 73, 74, 76, 77, 212, 215, 233, 234,
)


def test_every_parameter_the_spec_lists_is_in_the_table():
    missing = [n for n in SPEC_NUMBERS if n not in PARAMETERS]
    assert missing == []


def test_table_rows_carry_the_manuals_numbers():
    # §23: min / default / max / valid from
    assert (PARAMETERS[35].minimum, PARAMETERS[35].default, PARAMETERS[35].maximum) == (-1000, 1, 1000)
    assert PARAMETERS[35].decimals == 6 and PARAMETERS[36].decimals == 6
    assert (PARAMETERS[39].minimum, PARAMETERS[39].maximum, PARAMETERS[39].unit) == (0, 4_000_000, "ms")
    assert (PARAMETERS[68].maximum, PARAMETERS[68].unit) == (550, "%")
    assert (PARAMETERS[98].minimum, PARAMETERS[98].default, PARAMETERS[98].maximum) == (0, 360, 4_000_000)
    assert (PARAMETERS[143].minimum, PARAMETERS[143].default, PARAMETERS[143].maximum) == (128, 4096, 2_000_000)
    assert PARAMETERS[79].default == 1
    assert PARAMETERS[93].default == 3  # "The operation mode Reset mode is a default setting"
    assert PARAMETERS[31].allowed == (0, 1, 2, 3, 4, 5, 9)
    assert PARAMETERS[80].allowed == (2, 4, 8, 16, 32)
    assert PARAMETERS[90].allowed == (0, 1, 2, 3)
    assert PARAMETERS[184].allowed == (0, 40, 42, 43, 44, 45, 46)
    assert PARAMETERS[188].allowed == (0, 40, 42, 43, 140)
    assert (PARAMETERS[247].default, PARAMETERS[248].default, PARAMETERS[249].default) == (5, 15, 10)
    valid = {n: PARAMETERS[n].valid_from for n in (30, 34, 36, 32, 33, 90, 93, 98, 143, 210, 245)}
    assert valid == {
        30: Validity.VP, 34: Validity.VP_SETC, 36: Validity.VP_CURVE_ZERO, 32: Validity.VP_CYCLE_END,
        33: Validity.VP_NEXT_CURVE, 90: Validity.VC, 93: Validity.IMMEDIATE, 98: Validity.VC,
        143: Validity.VC, 210: Validity.IMMEDIATE, 245: Validity.IMMEDIATE,
    }


def test_every_default_is_accepted_by_its_own_range():
    params = Parameters()
    for number, spec in PARAMETERS.items():
        params[number] = spec.default  # raises if a default were outside its range
        assert params.written[number] == spec.default


def test_soft_limits_off_values_appendix_b():
    # §4.4 / Appendix B soft_limits_off; permissible P11 1 ... 4e6, P12 -1 ... -4e6 (X3)
    params = Parameters()
    assert (params[11], params[12]) == (4_000_000, -4_000_000)
    params[11] = 1
    params[12] = -1
    for number, bad in ((11, 0), (11, 4_000_001), (12, 0), (12, -4_000_001)):
        with pytest.raises(CompaxError):
            params[number] = bad


def test_aux_valences_and_p38_all_enabled_appendix_b():
    # §13.1.1: O7 = 2^6 = 64 ... O14 = 2^13 = 8192; "O7...O14 to be enabled by P38=16320" (X7)
    assert AUX_VALENCES == {"O7": 64, "O8": 128, "O9": 256, "O10": 512, "O11": 1024, "O12": 2048,
                            "O13": 4096, "O14": 8192}
    assert aux_mask(*AUX_VALENCES) == 16320
    params = Parameters()
    params[38] = 16320
    params[37] = aux_mask("O7")
    assert params.written[37] == 64
    for bad in (1, 32, 16384, 16321, -64):
        with pytest.raises(CompaxError, match="valences"):
            params[38] = bad
    with pytest.raises(CompaxError):
        aux_mask("O6")


# -- get / set -------------------------------------------------------------------------------


def test_get_set_with_int_keys_and_errors_that_name_field_value_and_range():
    params = Parameters()
    params[31] = 2
    assert params.written[31] == 2
    with pytest.raises(CompaxError) as info:
        params[31] = 6
    err = info.value
    assert err.code == E_VALUE and err.field == "P31" and err.value == 6
    assert "P31" in str(err) and "6" in str(err) and "0, 1, 2, 3, 4, 5, 9" in str(err)
    assert params.written[31] == 2  # unchanged
    with pytest.raises(CompaxError, match=r"-1000\.000000 \.\.\. 1000\.000000"):
        params[35] = 1000.5
    for bad in ("abc", float("nan"), float("inf"), True, None):
        with pytest.raises(CompaxError):
            params[35] = bad
    with pytest.raises(CompaxError):
        params[31] = 2.5  # integer parameter


def test_unknown_numbers_are_compax_errors_and_key_errors():
    params = Parameters()
    with pytest.raises(UnknownNumberError) as info:
        params[7]
    assert info.value.code == E_UNKNOWN
    with pytest.raises(KeyError):
        params[7] = 1
    with pytest.raises(CompaxError):
        params["31"]
    assert 7 not in params and 31 in params


def test_values_are_stored_at_the_parameter_resolution():
    # decision 16
    params = Parameters()
    params[35] = 1.23456789
    assert params.written[35] == 1.234568
    params[31] = 2.0
    assert params.written[31] == 2 and isinstance(params.written[31], int)
    assert params.format(35) == "1.234568" and params.format(31) == "2" and params.format(31, valid=True) == "0"


# -- written / armed / valid -----------------------------------------------------------------


def test_vp_parameter_becomes_valid_with_vp():
    params = Parameters()
    params[31] = 2
    assert params[31] == 0 and params.valid[31] == 0 and params.pending() == {31: "written"}
    assert params.make_valid("VP") == [31]
    assert params[31] == 2 and params.pending() == {}


def test_immediate_parameters_p93_and_p210():
    # §23 "immediately"; §15.1 "Any modifications to P210 are effective immediately (without VP)"
    params = Parameters()
    params[93] = 1
    params[210] = 1
    assert (params[93], params[210]) == (1, 1) and params.pending() == {}


def test_valid_values_is_the_live_table_the_cycle_reads():
    # the cam operation reads params.valid_values[n] every 1 ms (no number check per read): it must
    # show exactly the valid values, through writes, VP, RESETP, restore, and stay the same dict
    params = Parameters()
    table = params.valid_values
    assert all(table[n] == params[n] for n in PARAMETERS)
    params[93] = 1  # immediately valid
    params[35] = 2.5  # valid with VP
    assert table[93] == 1 and table[35] == 1.0
    params.make_valid("VP")
    assert table[35] == 2.5
    snap = params.snapshot()
    params[35] = 3.0
    params.make_valid("VP")
    params.restore(snap)
    assert params.valid_values is table and table[35] == 2.5
    params.resetp()
    assert params.valid_values is table and table[35] == 1.0 and table[93] == PARAMETERS[93].default
    assert snap.valid_values is not table and snap.valid_values[35] == 2.5


def test_the_cycle_reads_a_parameter_mapping_with_the_manuals_defaults():
    # a parameter object without a table of valid values (a test rig's dict) is read through
    # params[n], missing numbers as the manual's defaults (masterchain.DEFAULTS)
    params = {35: 2.0}
    table = valid_values(params)
    assert table[35] == 2.0 and table[98] == DEFAULTS[98] and table[188] == 0
    params[35] = 3.0
    assert table[35] == 3.0
    assert valid_values(Parameters()) is not None and isinstance(valid_values(Parameters()), dict)


def test_vc_parameters_need_vc_not_vp():
    # decision 13
    params = Parameters()
    params[98] = 720
    params[143] = 1024
    params.make_valid("VP")
    assert params[98] == 360 and params.pending() == {98: "written", 143: "written"}
    assert params.make_valid("VC") == [98, 143]
    assert (params[98], params[143]) == (720, 1024)


def test_p34_valid_with_vp_and_setc():
    params = Parameters()
    params[34] = 1
    params.make_valid("VP")
    assert params[34] == 0 and params.pending() == {34: "armed"}
    assert params.make_valid("cycle_end") == []
    assert params.make_valid("SETC") == [34] and params[34] == 1


def test_p36_valid_at_next_curve_zero_point_or_setc_footnote_5():
    params = Parameters()
    params[36] = 2
    params.make_valid("SETC")
    assert params[36] == 1  # not yet VP'd
    params.make_valid("VP")
    assert params[36] == 1
    params.make_valid("curve_zero")
    assert params[36] == 2
    params[36] = 3
    params.make_valid("VP")
    params.make_valid("SETC")
    assert params[36] == 3


def test_p33_next_curve_and_triggered_variant():
    # §15.3.2 overview: 0...2 "acceptance triggered with LOOP"; 10...12 "with 1st LOOP or at the end of the current cycle"
    params = Parameters()
    params[33] = 1
    params.make_valid("VP")
    params.make_valid("cycle_end")
    assert params[33] == 0
    params.make_valid("LOOP")
    assert params[33] == 1
    params[33] = 12
    params.make_valid("VP")
    params.make_valid("cycle_end")
    assert params[33] == 12
    params[33] = 10  # decision 7: 10 allowed
    params.make_valid("VP")
    params.make_valid("LOOP")
    assert params[33] == 10


def test_p32_at_the_end_of_the_current_cycle_or_loop():
    params = Parameters()
    params[32] = 12.5
    params.make_valid("VP")
    assert params[32] == 0
    params.make_valid("cycle_end")
    assert params[32] == 12.5
    params[32] = 20
    params.make_valid("VP")
    params.make_valid("LOOP")
    assert params[32] == 20


def test_p35_triggered_transfer_only_when_synchronous():
    # §17: P30 10...19: P35 only transferred at curve end; "only done in synchronous mode ...
    # Otherwise P35 is always transferred immediately" (decision 12)
    params = Parameters()
    params[35] = 2
    params.make_valid("VP")
    assert params[35] == 2  # P30 = 0: always transferred
    params[30] = 10
    params.make_valid("VP")
    params.synchronous = True
    params[35] = 3
    params.make_valid("VP")
    assert params[35] == 2 and params.pending() == {35: "armed"}
    params.make_valid("cycle_end")
    assert params[35] == 3
    params[35] = 4
    params.make_valid("VP")
    assert params[35] == 3
    params.synchronous = False  # leaving synchronous operation: transferred at once
    assert params[35] == 4
    params[35] = 5
    params.make_valid("VP")
    assert params[35] == 5


def test_cycle_end_and_curve_zero_are_the_same_event():
    # decision 11
    for event in ("cycle_end", "curve_zero"):
        params = Parameters()
        params[36] = 2
        params[32] = 1
        params.make_valid("VP")
        assert params.make_valid(event) == [32, 36]


def test_accept_alias_takes_the_cam_operations_event_names():
    params = Parameters()
    params[36] = 2
    params.accept("vp")
    assert params.accept("CYCLE") == [36]
    with pytest.raises(CompaxError, match="event"):
        params.make_valid("VQ")
    assert set(EVENTS) == {"VP", "VC", "SETC", "LOOP", "curve_zero", "cycle_end"}


def test_new_write_while_armed_keeps_the_armed_value_until_its_trigger():
    params = Parameters()
    params[36] = 2
    params.make_valid("VP")
    params[36] = 5  # written, not yet VP'd
    params.make_valid("SETC")
    assert params[36] == 2 and params.written[36] == 5 and params.pending() == {36: "written"}


def test_vp_checks_p79_below_p13_and_changes_nothing_when_it_fails():
    params = Parameters()
    params[79] = 50  # > P13 default 10
    params[31] = 2
    with pytest.raises(CompaxError, match="P79 = 50.0 must be smaller than P13") as info:
        params.make_valid("VP")
    assert info.value.field == "P79"
    assert params[31] == 0 and params[79] == 1 and params.pending() == {31: "written", 79: "written"}
    params[13] = 100
    params.make_valid("VP")
    assert params[79] == 50 and params[31] == 2


def test_vp_checks_the_heda_rules():
    # §6: P243 bit 0 / bit 1 need P250 = 1; P245 = P246 = 0 in those modes
    params = Parameters()
    params[243] = 1
    with pytest.raises(CompaxError, match="P250"):
        params.make_valid("VP")
    params[250] = 1
    params[245] = 3
    with pytest.raises(CompaxError, match="P245"):
        params.make_valid("VP")
    params[245] = 0
    params.make_valid("VP")
    assert params[243] == 1


def test_vc_checks_roller_feed_ranges():
    # §4.3: roller feed P83 30 ... 3000 mm, restriction P83/P85 <= 300 mm
    params = Parameters()
    params[80] = 32
    params[83] = 600
    with pytest.raises(CompaxError, match="P83/P85"):
        params.make_valid("VC")
    assert params[80] == 16  # nothing valid
    params[85] = 2
    params.make_valid("VC")
    assert (params[80], params[83], params[85]) == (32, 600, 2)
    params[83] = 3001
    with pytest.raises(CompaxError, match="30 ... 3000"):
        params.make_valid("VC")


def test_vc_checks_increments_resolution_2_to_the_n():
    # §4.2.2 "P83 = 2^n with n = 4, 5, 6, ...16"
    params = Parameters()
    params[90] = 0
    params[83] = 1000
    with pytest.raises(CompaxError, match="2\\^n"):
        params.make_valid("VC")
    for good in (16, 1024, 65536):
        params[83] = good
        params.make_valid("VC")
        assert params[83] == good
    params[83] = 131072
    with pytest.raises(CompaxError):
        params.make_valid("VC")


def test_resetp_restores_defaults_written_and_valid():
    # decision 14
    params = Parameters()
    params[31] = 2
    params[36] = 2
    params.make_valid("VP")
    params[98] = 100
    params.resetp()
    assert params[31] == 0 and params[36] == 1 and params.written[98] == 360 and params.pending() == {}


# -- decisions on [CONFLICT] / [GAP] points --------------------------------------------------


def test_decision_2_p82_table_max_70000():
    params = Parameters()
    params[82] = 70_000
    params[82] = 7001  # above the text's 7000 but within the table's range
    with pytest.raises(CompaxError, match="70000"):
        params[82] = 70_001


def test_decision_3_p179_table_max_4_million_not_2_pow_23():
    params = Parameters()
    params[179] = 4_000_000
    with pytest.raises(CompaxError, match="4000000"):
        params[179] = 2**23


def test_decisions_4_5_p180_default_100_after_resetp_no_maximum():
    params = Parameters()
    assert params[180] == 100
    params[180] = 250  # ">100": initial correction unlimited
    with pytest.raises(CompaxError):
        params[180] = -1


def test_decision_6_p36_keeps_its_range_and_drift_free_check_ignores_p36_st_star():
    params = Parameters()
    with pytest.raises(CompaxError):
        params[36] = 16523  # "P36 = S_T*" would need this; the table allows ±1000
    assert drift_free_problems(master_cycle=11872, slave_cycle=16523, p143=4096, p98=1024, p83=1024, p90=0) == []


def test_decision_8_p32_minimum_zero_and_upper_limit_against_the_cycle():
    params = Parameters()
    with pytest.raises(CompaxError):
        params[32] = -1
    check_label_sensor_distance(3600, 360)
    with pytest.raises(CompaxError, match="10"):
        check_label_sensor_distance(3600.5, 360)


def test_decision_9_p31_meanings_are_those_of_section_19_1():
    meanings = dict(PARAMETERS[31].meanings)
    assert "after one master cycle, not when I16='1'" in meanings[3]
    assert "further SETC n independent of I16" in meanings[4]
    assert "independent of I16" in meanings[5] and "HEDA" in meanings[9]


def test_decision_10_da_quantities_0_to_18_and_20_to_24():
    params = Parameters()
    for good in (0, 18, 20, 24):
        params[73] = good
    params[76] = 22.0000001  # quantity 22 (S_T), gain factor 1
    params[77] = 18.1
    for number, bad in ((73, 19), (74, 25), (76, 19.5), (77, 25)):
        with pytest.raises(CompaxError):
            params[number] = bad


def test_decision_15_gap_defaults():
    params = Parameters()
    assert (params[80], params[90], params[144], params[13]) == (16, 1, 4, 10)
    assert params[21] == 1


# -- value ranges and worked examples --------------------------------------------------------


def test_x4_default_master_reference_16384_increments():
    # §7 X4 / Appendix B master_increments_default: P143 4096, P98 360, M_T 360 -> 16384 <= 4e6
    assert scaled_master_cycle(360, 4096, 360) == 16384
    assert check_master_cycle_range(360, 4096, 360) == 16384


def test_scaled_master_cycle_rule_and_its_error():
    # §4.5.3: M_T·4·P143/P98 <= 4 000 000
    assert check_master_cycle_range(4_000_000 / 4 / 4096 * 360, 4096, 360) == 4_000_000
    with pytest.raises(CompaxError) as info:
        check_master_cycle_range(100_000, 4096, 360)
    assert "exceeds 4 000 000" in str(info.value) and "M_T = 100000" in str(info.value)
    assert info.value.code == E_VALUE
    with pytest.raises(CompaxError, match="P98"):
        check_master_cycle_range(360, 4096, 0)
    with pytest.raises(CompaxError, match="M_T"):
        check_master_cycle_range(0, 4096, 360)


def test_decision_1_slave_cycle_rule_uses_p90():
    # §4.5.3 [CONFLICT] "P93 = 0 (Increments)" read as P90
    assert scaled_slave_cycle(360, 1024, 0) == 360 * 2**16 / 1024
    assert scaled_slave_cycle(360, 1024, 3) == 360 * 2**16 / 1.024
    assert scaled_slave_cycle(360, 1024, 2) is None  # inch: no rule
    check_slave_cycle_range(360, 1024, 0)
    with pytest.raises(CompaxError, match="S_T"):
        check_slave_cycle_range(360, 1024, 1)  # 23 040 000 > 4e6


def test_x2_max_travel_table_appendix_b():
    table = {16: 250000, 32: 125000, 64: 62500, 128: 31250, 256: 15625, 512: 7812, 1024: 3906, 2048: 1953,
             4096: 976, 8192: 488, 16384: 244, 32768: 122, 65536: 61}
    assert {p83: max_travel_revolutions(p83) for p83 in table} == table


def test_x18_p179_accuracy_appendix_b():
    # "P179 = 1000ms -> F < 0.012%": 100·2^-23·1000 = 0.01192
    assert p35_ramp_error_percent(1000) == pytest.approx(0.01192, abs=1e-5)
    assert p35_ramp_error_percent(1000) < 0.012


def test_x19_drift_free_gear_example_appendix_b():
    i_m = Fraction(20, 63) * Fraction(26, 64) * Fraction(6, 53)
    i_s = Fraction(20, 82) * Fraction(8, 33) * Fraction(11, 62)
    assert float(i_m) == pytest.approx(0.014600179, abs=1e-9)
    assert float(i_s) == pytest.approx(0.010490427, abs=1e-9)
    assert i_m / i_s == Fraction(16523, 11872)  # S_T*/M_T*
    # P35 = P36 = 1; P83 = P98 = 1024; P90 = 0; curve (0,0) - (11872, 16523)
    assert drift_free_problems(master_cycle=11872, slave_cycle=16523, p143=1024, p98=1024, p83=1024, p90=0) == []
    problems = drift_free_problems(master_cycle=11872, slave_cycle=16523, p143=1000, p98=360, p83=1000, p90=0,
                                   p35=2)
    assert any("1st condition" in p for p in problems)
    assert any("3rd condition" in p for p in problems)
    assert any("P35" in p for p in problems)
    assert drift_free_problems(master_cycle=360, slave_cycle=360, p143=4096, p98=360, p83=360_000, p90=3) == []
    assert any("inch" in p for p in drift_free_problems(master_cycle=360, slave_cycle=1, p143=4096, p98=360,
                                                          p83=1, p90=2))
