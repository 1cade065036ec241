"""CLM1.4 parameters: columns, checks on leaving Parameter mode, files (manual ch. 8, Figs. 9-14..9-16)."""

from __future__ import annotations

from decimal import Decimal

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from axisline.devices.clm.errors import FAULTS, SERIAL_ERRORS, ClmError
from axisline.devices.clm.operands import Operand
from axisline.devices.clm.parameters import (
    MIN_MAX,
    PARAMETERS,
    ParameterSet,
    check_id,
    format_data,
    parse_data,
    read_parameter_text,
)
from axisline.devices.clm.telegram import checksum

# Figs. 9-14..9-16 exactly as printed (L6591-6670): `# _K_` is '#', the station blank, 'K', a blank;
# every other `_` is a blank (spec §0, §8.4).
MANUAL_TABLE = {
    6591: "# _K_B000_0_0_0_0$8E", 6592: "# _K_B001_0_0_0_0$DD", 6593: "# _K_B002_019200_0_1_8_1$E4",
    6594: "# _K_B003_0_1_00_0_000_000$A8", 6595: "# _K_B004_000000_0_0_0_0_0$F8", 6596: "# _K_B005_0_0_00_0_000_000$A7",
    6597: "# _K_B006_$59", 6598: "# _K_B007_$58", 6599: "# _K_B008_0_0_0_0_0_02$B3", 6600: "# _K_B009_$56",
    6601: "# _K_B010_0.0$CF", 6602: "# _K_B011_0000_0000_0$6B", 6603: "# _K_B012_1000_2000$B7", 6604: "# _K_B013_$5B",
    6605: "# _K_B014_00.00.0_0_0000$DB", 6606: "# _K_B015_00.00.0_0_0_0000$8A", 6607: "# _K_B016_0000$97",
    6608: "# _K_B017_0_0_0_0_0_0_0$95", 6609: "# _K_B018_0_0001000$B3", 6610: "# _K_B019_2_FF0000_00_00$B4",
    6615: "# _K_A100_1_0_0_0_0$EC", 6616: "# _K_A101_0010.00000$7D", 6617: "# _K_A102_0000_0000$BB",
    6618: "# _K_A103_-111111.111$46", 6619: "# _K_A104_+100000.000$4F", 6620: "# _K_A105_000000.000_0$2A",
    6621: "# _K_A106_000100.000$78", 6622: "# _K_A107_000100.000$77", 6623: "# _K_A108_000010$35",
    6624: "# _K_A109_000_000$15", 6625: "# _K_A110_0.000$6F", 6626: "# _K_A111_01.00_0$1D",
    6627: "# _K_A112_03000_10.0$88", 6628: "# _K_A113_$5B", 6629: "# _K_A114_0_010_00.00.0$0B",
    6630: "# _K_A115_00.00.0_00.00.0$9E", 6631: "# _K_A116_00_00_00.00.0$0A", 6632: "# _K_A117_0000.000$D7",
    6633: "# _K_A118_$56", 6634: "# _K_A119_01024_1024$75", 6635: "# _K_A120_0_0_00_1$0B", 6636: "# _K_A121_0_0_0$8B",
    6637: "# _K_A122_00_+000000.000$CF", 6638: "# _K_A123_ 1.00.0_ 1.00.1$6A", 6639: "# _K_A124_Q1.00.0_-100_0$BA",
    6640: "# _K_A125_-00000.000$7B", 6641: "# _K_A126_$57", 6642: "# _K_A127_Q1.00.2_0010.000$44",
    6643: "# _K_A128_00.00.0_0000.000$68", 6644: "# _K_A129_00.00.0_1.0_0000$76", 6645: "# _K_A130_00.00.0_00.00.0$A1",
    6646: "# _K_A131_00.00.0$0E", 6647: "# _K_A132_00.00.0_00.00.0$9F", 6648: "# _K_A133_00.00.0_00.00.0$9E",
    6649: "# _K_A134_00.00.0_0100_0$D8", 6650: "# _K_A135_00.00.0_00000$F8", 6651: "# _K_A136_00.00.0_0000$28",
    6652: "# _K_A137_00000_0000$83", 6653: "# _K_A138_00.00.0_0_0$66", 6654: "# _K_A139_00.00.0_00.00.0$98",
    6655: "# _K_A140_0.00_000_000$3B", 6656: "# _K_A141_00.00$6B", 6657: "# _K_A142_0000.00_00.00.0$9C",
    6662: "# _K_C000_01250_0000$84", 6663: "# _K_C001_0_0_00_0_0_0$6B", 6664: "# _K_C002_0020.00000$7A",
    6665: "# _K_C003_+00000.000$80", 6666: "# _K_C004_01250_0000$80", 6667: "# _K_C005_0_0_00_0_0_0$67",
    6668: "# _K_C006_0000.00000$78", 6669: "# _K_C007_+00000.000$7C", 6670: "# _K_C008_00.00.0_000$58",
}

# Errata §3.4: the six samples that fail their checksum as printed, as they verify.
CORRECTED = {
    "B000": "0 0 0",
    "B001": "0 0",
    "B004": "000000 0 0 0 0",
    "B008": "0 0 0 0 02",
    "B017": "0 0 0 0 0 0",
    "A123": "I1.00.0 I1.00.1",
}


def _telegram(printed: str) -> tuple[str, str, str, str]:
    """(text before $, id, data, checksum) of a printed sample."""
    text, _, hh = printed.replace("# _K_", "# K ", 1).replace("_", " ").partition("$")
    pid, _, data = text[4:].partition(" ")
    return text, pid, data, hh


def test_the_table_has_every_id_of_the_manual():
    """L4150-4156: B000-B019, A100-A142 .. A400-A442, C000-C008, in the manual's block order."""
    ids = list(PARAMETERS)
    assert len(ids) == 20 + 4 * 43 + 9
    assert ids[:3] == ["B000", "B001", "B002"] and ids[20] == "A100" and ids[62] == "A142" and ids[63] == "A200"
    assert ids[-1] == "C008"
    assert PARAMETERS["A301"].row is PARAMETERS["A101"].row  # one axis table, four axes


@pytest.mark.parametrize("line", sorted(MANUAL_TABLE))
def test_manual_sample_reproduced(line):
    """Every sample of Figs. 9-14..9-16 comes back byte for byte with its printed checksum."""
    text, pid, data, hh = _telegram(MANUAL_TABLE[line])
    if pid in CORRECTED:
        data = CORRECTED[pid]
        text = f"# K {pid} {data}"
    assert format_data(pid, parse_data(pid, data)) == data
    params = ParameterSet()
    params.set(pid, data)
    telegram = params.telegrams()[list(PARAMETERS).index(pid)]
    assert telegram == f"{text}${hh}", f"L{line}"
    assert checksum(text) == hh


@pytest.mark.parametrize("pid", sorted(CORRECTED))
def test_printed_misprint_refused_with_x01_04(pid):
    """Errata §3.4: as printed (L6591, L6592, L6595, L6599, L6608, L6638) the checksum is wrong."""
    printed = next(p for p in MANUAL_TABLE.values() if f"_K_{pid}_" in p)
    _, findings = read_parameter_text(printed.replace("# _K_", "#_K_"), "fig9")
    assert [(f.where, f.code) for f in findings] == [(pid, "X01:04")]
    assert "RS Checksum Error" in findings[0].text and findings[0].source == "fig9:1"


@pytest.mark.parametrize("pid", sorted(CORRECTED))
def test_corrected_misprint_accepted(pid):
    printed = next(p for p in MANUAL_TABLE.values() if f"_K_{pid}_" in p)
    hh = printed.rpartition("$")[2]
    line = f"#_K_{pid}_{CORRECTED[pid].replace(' ', '_')}${hh}"
    params, findings = read_parameter_text(line)
    assert findings == []
    assert params.data(pid) == CORRECTED[pid]


def test_whole_corrected_table_reads_clean_in_both_notations():
    lines = []
    for printed in MANUAL_TABLE.values():
        text, pid, data, hh = _telegram(printed)
        if pid in CORRECTED:
            text = f"# K {pid} {CORRECTED[pid]}"
        lines.append(f"{text}${hh}")
    params, findings = read_parameter_text("\r\n".join(lines))
    assert findings == []
    assert params.get("B012").data == "1000 2000" and params.get("A124").data == "Q1.00.0 -100 0"
    underscored, findings = read_parameter_text("\n".join(line.replace(" ", "_") for line in lines))
    assert findings == [] and underscored == params


def test_defaults():
    """Decision 9: the corrected samples, B008 address 00 (L7519), B012/B018 off, no I/O assigned."""
    params = ParameterSet()
    assert params.check() == []
    assert params.data("B008") == "0 0 0 0 00"
    assert params.data("B012") == "0000 0000"
    assert params.data("B018") == "0 0000000"
    assert params.data("A123") == "00.00.0 00.00.0" and params.data("A423") == "00.00.0 00.00.0"
    assert params.data("A124") == "00.00.0 -100 0"
    assert params.data("A127") == "00.00.0 0010.000"
    assert params.data("B010") == "0.0"  # "The default setting for Parameter B010 is 0.0" (L5119)
    assert params.data("A101") == "0010.00000" and params.data("C006") == "0000.00000"
    assert params.enabled_axes() == (1,)
    params.set("A106", "000400.000")
    params.reset()  # !sCSETPA
    assert params == ParameterSet()


def test_min_max_table_is_fig_8_15():
    """L5680-5693, with Ax05's blank row."""
    assert MIN_MAX["Ax01"][2:] == (Decimal("0.0100"), Decimal("5000.00000"))
    assert MIN_MAX["Ax08"][2:] == (Decimal(1), Decimal(999999))
    assert MIN_MAX["Ax05"][2:] == (None, None)
    assert set(MIN_MAX) == {"Ax01", "Ax05", "Ax06", "Ax07", "Ax08", "Ax10", "Ax11", "Ax12", "Ax19", "C000", "C002", "C004", "C006"}


def _with(**data: str) -> ParameterSet:
    params = ParameterSet()
    for pid, value in data.items():
        params.set(pid, value)
    return params


def _findings(params: ParameterSet) -> list[tuple[str, str]]:
    return [(f.where, f.code) for f in params.check()]


@pytest.mark.parametrize(
    ("pid", "data", "field", "value", "allowed"),
    [
        ("A101", "0000.00500", "feed_constant", "0000.00500", "0.0100..5000.00000"),  # L4250, L5681
        ("A106", "000000.099", "maximum_velocity", "000000.099", "0.100..50000.000"),  # L4374
        ("A108", "000000", "acceleration", "000000", "1..999999"),  # L4400
        ("A110", "1.025", "jerk_constant", "1.025", "0.000..1.024"),  # L4425
        ("A111", "25.00 0", "kv_factor", "25.00", "0.01..20.00"),  # L4463
        ("A112", "03000 00.4", "command_voltage", "00.4", "0.5..10.0"),  # L4477
        ("A112", "10000 10.0", "max_encoder_speed", "10000", "1..9999"),  # L4478
        ("A114", "0 000 00.00.0", "window_percent", "000", "1..100"),  # L4508
        ("A114", "4 010 00.00.0", "monitoring_mode", "4", "0, 1, 2, 3"),  # L4510-4516
        ("A124", "00.00.0 -100 5", "homing_type", "5", "0, 1, 2, 3, 4"),  # L4712-4720
        ("B002", "012345 0 1 8 1", "baud_rate", "012345", "0, 300, 600"),  # L6313-6327
        ("B002", "019200 0 1 9 1", "data_bits", "9", "7, 8"),  # L6256
        ("B003", "4 1 00 0 000 000", "handshake_checksum", "4", "0, 1, 2, 3"),  # L6349-6353
        ("B003", "0 1 33 0 000 000", "station_number", "33", "0..32"),  # L6343
        ("B010", "2.2", "cycle_time", "2.2", "0.0, 1.0, 1.1"),  # L5097-5111
        ("B011", "3000 0000 0", "task_2_start", "3000", "0..2999"),  # L6818
        ("B017", "0 7 0 0 0 0", "override_axis_1", "7", "0, 1, 2, 3, 4, 5, 6"),  # L5239-5245
        ("B018", "7 0000000", "fault_code_output", "7", "0, 1, 2, 3, 4, 5, 6"),  # L5269-5281
        ("B018", "0 0003000", "clear_q1_03", "3", "0, 1, 2"),  # L5289-5293
    ],
)
def test_range_error_names_field_value_and_range(pid, data, field, value, allowed):
    params, findings = read_parameter_text(f"; a machine\n{pid} {data}\n", "m.par")
    assert [(f.where, f.code) for f in findings] == [(pid, "02")]
    text = findings[0].text
    assert text.startswith("INVALID Parameter: ") and f"{field} = {value}" in text and f"allowed {allowed}" in text
    assert findings[0].source == "m.par:2"


def test_a_file_with_errors_still_returns_the_good_lines():
    params, findings = read_parameter_text("A106 000200.000\nA111 25.00 0\nA107 XYZ\n")
    assert params.data("A106") == "000200.000"  # good line applied
    assert params.data("A107") == "000100.000"  # bad line: the default stays
    assert [(f.where, f.code) for f in findings] == [("A107", "02"), ("A111", "02")]


def test_every_bad_line_reported():
    text = "\n".join([
        "# a comment line",
        "B000 0 0 0 ; axes 2-4 off",
        "",
        "Z100 1",  # unknown block -> X01:11
        "#_K_B001_0_0$DE",  # wrong checksum
        "A101 0010.00000",
        "A101 0020.00000",  # twice: warning, later kept
        "! K A106 000100.000$" + checksum("! K A106 000100.000"),  # '!' for '#'
        "A103 -111111.111 5",  # too many fields
        "!garbage",
    ])
    params, findings = read_parameter_text(text, "x.par")
    got = [(f.where, f.code, f.severity, f.source) for f in findings]
    assert got == [
        ("line 4", "X01:11", "error", "x.par:4"),
        ("B001", "X01:04", "error", "x.par:5"),
        ("A101", "02", "warning", "x.par:7"),
        ("A103", "02", "error", "x.par:9"),
        ("line 10", "X01:02", "error", "x.par:10"),
    ]
    assert params.data("A101") == "0020.00000"


@pytest.mark.parametrize(
    ("token", "code"),
    [("Z100", "X01:11"), ("b000", "X01:11"), ("A500", "X01:11"), ("B0X1", "X01:06"), ("B0001", "X01:06"), ("B020", "X01:07"), ("A143", "X01:07"), ("C009", "X01:07")],
)
def test_unknown_ids(token, code):
    """Decision 14 (spec §8.5, L6812-6817): block -> 11, number not decimal -> 06, too large -> 07."""
    with pytest.raises(ClmError) as e:
        check_id(token)
    assert e.value.code == code
    _, findings = read_parameter_text(f"{token} 0")
    assert [f.code for f in findings] == [code]


def test_parse_tolerance():
    """Decision 15: one or two blanks, a tab, short leading digits, ',' for '.'; printing is exact."""
    assert parse_data("B002", "019200  0 1  8 1").data == "019200 0 1 8 1"
    assert parse_data("A101", "10,5").data == "0010.50000"
    assert parse_data("A124", "Q1.00.0 +5 0").data == "Q1.00.0 +005 0"
    params, findings = read_parameter_text("A119\t01024\t0256\n")  # as the manual prints it, L3531
    assert findings == [] and params.data("A119") == "01024 0256"
    for pid, data, why in [
        ("B002", "019200 0 1   8 1", "3 blanks"),
        ("A103", "111111.111", "needs its sign"),
        ("A101", "+0010.00000", "takes no sign"),
        ("A101", "00010.00000", "at most 4 digits"),
        ("A101", "0010.000001", "at most 5 decimals"),
        ("A108", "100.5", "a whole number"),
        ("A124", "Q1.00.0 100 0", "expected + or -"),
        ("A123", "1.00.0 I1.00.1", "needs I, Q or M"),
        ("A123", "I1.00.8 I1.00.1", "does not exist"),
        ("B018", "0 000100", "clear_q1_06 is missing"),
        ("B006", "0", "reserved and takes no data"),
        ("B019", "2 FG0000 00 00", "hex digits"),
    ]:
        with pytest.raises(ClmError) as e:
            parse_data(pid, data)
        assert e.value.code == "02" and e.value.where == pid and why in e.value.detail, (pid, data, e.value.detail)


def test_reserved_parameters_take_no_data():
    """Decision 8: reserved ids are empty (`# K B006 $59`), lost fields are kept but not checked."""
    for pid in ("B006", "B007", "B009", "B013", "A113", "A218", "A326", "A426"):
        assert PARAMETERS[pid].fields == () and ParameterSet().data(pid) == ""
    params = _with(B011="0200 0000 7", B019="9 ABCDEF 12 FF", A121="9 9 9", A122="99 -123456.789", A100="1 9 0 0 0")
    assert params.check() == []
    assert params.listing().splitlines()[11] == "B011 0200 0000 7"


def test_negative_zero_round_trip():
    value = parse_data("A125", "-00000.000")
    assert value["homing_offset"] == 0 and value["homing_offset"].is_signed()
    assert value.data == "-00000.000" and parse_data("A125", "+00000.000").data == "+00000.000"


def test_param_value_fields_by_name():
    value = parse_data("A124", "M2.02.0 +100 0")  # L2018
    assert value["homed_output"] == Operand("M", 2, 2, 0)
    assert value.as_dict() == {"homed_output": Operand("M", 2, 2, 0), "search_direction": "+", "search_velocity": 100, "homing_type": 0}
    assert value.replace(search_direction="-", homing_type=3).data == "M2.02.0 -100 3"
    assert value.replace(homed_output="00.00.0").data == "00.00.0 +100 0"
    with pytest.raises(ClmError):
        value.replace(search_velocity=1000)
    with pytest.raises(ClmError):
        format_data("A124", (Operand("M", 2, 2, 0), "+", 100))


def test_round_trip_listing_and_telegrams(tmp_path):
    params = _with(B000="1 0 0", A101="0014.06250", A125="-00010.500", A124="Q1.00.0 +250 0", B019="2 0A0000 00 00", A211="02.50 0")
    listing = params.listing()
    again, findings = read_parameter_text(listing)
    assert findings == [] and again == params and again.listing() == listing
    back, findings = read_parameter_text("\n".join(params.telegrams(station=10)))  # RS485 station A
    assert findings == [] and back == params
    assert params.telegrams()[0] == "# K B000 1 0 0$" + checksum("# K B000 1 0 0")
    params.save(tmp_path / "m.par")
    params.save(tmp_path / "m.tel", telegrams=True)
    assert (tmp_path / "m.par").read_text() == listing
    raw = (tmp_path / "m.tel").read_bytes()
    assert raw.startswith(b"# K B000 1 0 0$") and raw.count(b"\r\n") == len(PARAMETERS)
    assert read_parameter_text(raw.decode("ascii"))[0] == params


def test_b000_enables_axes_left_to_right():
    """Decision 4: ``B000 1 0 1`` enables axes 2 and 4 (L5012; L6039 'activated using B000')."""
    assert _with(B000="1 0 1").enabled_axes() == (1, 2, 4)
    assert _with(B000="0 1 0").enabled_axes() == (1, 3)


def test_hardware_axes_3_4():
    """Decision 13, error 17 (L8461): only when the caller says the expansion is missing."""
    params = _with(B000="0 1 0")
    assert params.check() == []
    assert [(f.where, f.code) for f in params.check(axes_fitted=2)] == [("B000", "17")]
    assert _with(B000="1 0 0").check(axes_fitted=2) == []


def test_ax00_layout_and_combinations():
    """Decision 3: ``master reserved test_mode mode motion_type``; combinations per axis L4202-4226."""
    value = parse_data("A100", "1 0 0 0 0")  # L6615
    assert (value["master"], value["mode"], value["motion_type"]) == (1, 0, 0)
    assert _with(A100="5 0 0 2 1").axis_mode(1) == 2
    assert _findings(_with(A100="5 0 0 2 1")) == []  # axis 1 slave of master encoder 1 (L4205)
    assert _findings(_with(A100="1 0 0 2 1")) == [("A100", "02")]  # axis 1 cannot follow axis 1
    assert _findings(_with(A100="0 0 0 1 1")) == [("A100", "02")]  # axis 1 is never synchronous (L4204-4207)
    assert _findings(_with(B000="1 0 0", A200="1 0 0 1 1")) == []  # axis 2 synchronous to axis 1 (L4209)
    assert _findings(_with(B000="1 0 0", A200="1 0 0 5 1")) == [("A200", "02")]  # flying cutoff is axis 1's (L4207)
    assert _findings(_with(B000="0 0 1", A400="3 0 0 2 1")) == []  # axis 4 follows axis 3 (L4225)
    assert _findings(_with(B000="0 1 0", A300="3 0 0 2 1")) == [("A300", "02")]  # axis 3 cannot follow axis 3
    assert _findings(_with(B000="0 1 0", A300="0 0 0 3 1")) == [("A300", "02")]  # no measuring wheel on axis 3


def test_b008_layout():
    """Decision 6: the display example ``1 1 0 1 05`` (L5064) is valid; operating mode 0 or 3."""
    value = parse_data("B008", "1 1 0 1 05")
    assert (value["process_data_format"], value["operating_mode"], value["slave_address"]) == (1, 0, 5)
    assert _findings(_with(B008="1 1 0 1 05")) == []
    assert _findings(_with(B008="2 0 3 1 89")) == []
    assert _findings(_with(B008="0 0 1 0 02")) == [("B008", "02")]


def test_encoder_type_ranges():
    """Decision 7 and 11: Ax19 and Ax20 per encoder type (L4637-4659, Fig. 8-15 L5689)."""
    assert _findings(_with(A119="00099 0000")) == [("A119", "02")]  # incremental: 100..10000
    assert _findings(_with(A119="10000 9999")) == []  # revolutions undefined for incremental (L4637)
    multi = {"A120": "0 2 24 1"}
    assert _findings(_with(**multi, A119="04096 4096")) == []  # 24 bits: 0001..4096 (L4638)
    assert _findings(_with(**multi, A119="04096 4097")) == [("A119", "02")]
    assert _findings(_with(A120="0 2 21 1", A119="01024 0513")) == [("A119", "02")]  # 21 bits: ..0512 (L4641)
    assert _findings(_with(**multi, A119="08192 0001")) == [("A119", "02")]  # 00016..04096 (L4649)
    assert _findings(_with(A120="0 2 20 1", A119="01024 0001")) == [("A120", "02")]  # multi-turn 21-24 bits (L4657)
    single = {"A120": "0 1 16 1"}
    assert _findings(_with(**single, A119="00012 0004")) == []  # 12 + 4 bits <= 16 (L4659)
    assert _findings(_with(**single, A119="00012 0005")) == [("A119", "02")]
    assert _findings(_with(**single, A119="00022 0000")) == [("A119", "02")]  # 00007..00021 (L4650)
    assert _findings(_with(A120="0 1 22 1", A119="00012 0000")) == [("A120", "02")]  # single-turn 12-21 (L4656)
    assert _findings(_with(A120="0 4 00 1")) == [("A120", "02")]


def test_interface_fields_unused_when_off():
    """Decision 5: baud 000000 (L6327) or IDS01 (L5028) leave the rest and B003/B005 unchecked."""
    assert _findings(_with(B004="000000 0 0 0 0", B005="9 9 99 9 999 999")) == []  # the sample's X8 (L6595)
    assert _findings(_with(B004="009600 0 0 8 1", B005="9 0 00 0 000 000")) == [("B005", "02")]
    assert _findings(_with(B002="000000 0 7 0 0", B003="7 0 00 0 000 000")) == []
    assert _findings(_with(B002="000000 1 7 0 0", B003="7 0 00 0 000 000")) == []
    assert _findings(_with(B002="019200 0 3 8 1")) == [("B002", "02")]


def test_unused_parameters_not_checked():
    """Errata §3.4 / decision 10: the sample's A102 0000 0000 and C006 0000.00000 pass while unused."""
    gear = {"A102": "0000 0000"}
    assert _findings(_with(**gear)) == []  # rotary axis: Ax02 unused (L4278)
    assert _findings(_with(**gear, A100="1 0 0 0 2")) == [("A102", "02")] * 2  # rotary table, incremental: X and Y
    assert _findings(_with(**gear, A100="1 0 0 0 2", A120="0 2 24 1", A119="01024 0001")) == []  # absolute encoder
    assert _findings(_with(A111="50.00 0", A206="999999.999")) == [("A111", "02")]  # axis 2 disabled
    assert _findings(_with(B000="1 0 0", A206="999999.999")) == [("A206", "02")]
    assert _findings(_with(C006="0000.00000")) == []
    assert _findings(_with(B000="1 0 0", A200="0 0 0 3 0")) == [("C006", "02")]  # axis 2 measuring wheel (L4228)
    assert _findings(_with(C002="0000.00000", C000="00000 0000")) == []  # master encoder 1 unused
    assert _findings(_with(C002="0000.00000", A100="5 0 0 2 0", A111="01.00 1")) == [("C002", "02")]  # axis 1 slave
    assert _findings(_with(A103="+000001.000")) == []  # rotary axis: travel limits unused (L2518)
    assert _findings(_with(A104="-000001.000", A100="1 0 0 0 1")) == [("A104", "02")]  # linear: always positive (L4338)
    assert _findings(_with(A105="999999.999 7")) == []  # Ax05 only for the rotary table (L4350)
    assert _findings(_with(A105="999999.999 1", A100="1 0 0 0 2", A102="0001 0001")) == [("A105", "02")]
    assert _findings(_with(A116="99 99 00.00.0", A136="00.00.0 9999")) == []  # measuring wheel / cutoff only
    assert _findings(_with(B014="00.00.0 0 9999", B015="00.00.0 9 9 9999")) == []  # vectors without input
    assert _findings(_with(B015="I1.01.0 9 0 0900")) == [("B015", "02")]


def test_rotary_table_example_accepts_vmax_equal():
    """L3607-3649: A101 = 3600/256 = 14.0625, A112 = 4800 RPM -> A106 at most 1125 IU/s (errata §3.4)."""
    table = dict(A100="1 0 0 0 2", A120="0 2 24 1", A119="01024 0256", A101="0014.06250", A112="04800 10.0", A105="003600.000 1")
    assert _findings(_with(**table, A106="001125.000", A125="+03600.000")) == []
    assert _findings(_with(**table, A106="001125.001")) == [("A106", "02")]
    assert _findings(_with(**table, A125="+03600.001")) == [("A125", "02")]  # IUT = 14.0625 x 256 (L3545, L3552)


# The interaction checks: each one failing, then passing, with the manual's line.
INTERACTIONS = [
    # Ax06 <= RPM/60 x Ax01: 3000/60 x 10 = 500 (L4363-4372)
    ("L4363-4372", {"A106": "000500.001"}, {"A106": "000500.000"}, "A106"),
    # Ax07 <= Ax06 (L4388)
    ("L4388", {"A107": "000100.001"}, {"A107": "000099.999"}, "A107"),
    # rotary table, incremental: feed constant Ax01 x Y/X, 360 IU/table rev, 590:1 -> 3000/60 x 360/590 = 30.508 (L3581-3589)
    ("L3581", {"A100": "1 0 0 0 2", "A101": "0360.00000", "A102": "0590 0001", "A106": "000030.509", "A107": "000010.000"},
     {"A100": "1 0 0 0 2", "A101": "0360.00000", "A102": "0590 0001", "A106": "000030.508", "A107": "000010.000"}, "A106"),
    # Ax02 X >= Y (L3565-3567)
    ("L3565-3567", {"A100": "1 0 0 0 2", "A102": "0002 0005"}, {"A100": "1 0 0 0 2", "A102": "0005 0002"}, "A102"),
    # Ax25 <= IUT, incremental rotary table: IUT = Ax01 (L3593)
    ("L3593", {"A100": "1 0 0 0 2", "A102": "0001 0001", "A125": "-00010.001"}, {"A100": "1 0 0 0 2", "A102": "0001 0001", "A125": "-00010.000"}, "A125"),
    # Ax03 negative with an incremental encoder (L4302), positive with an absolute one (L4309)
    ("L4302", {"A100": "1 0 0 0 1", "A103": "+000001.000"}, {"A100": "1 0 0 0 1", "A103": "-000001.000"}, "A103"),
    ("L4309", {"A100": "1 0 0 0 1", "A120": "0 2 24 1", "A119": "04096 0001", "A103": "-000001.000"},
     {"A100": "1 0 0 0 1", "A120": "0 2 24 1", "A119": "04096 0001", "A103": "+000001.000"}, "A103"),
    # feedforward only for slave / synchronous / flying cutoff (L4457)
    ("L4457", {"A111": "01.00 1"}, {"A111": "01.00 1", "A100": "5 0 0 2 0"}, "A111"),
    # homing Option 5 only for flying cutoff (L4741)
    ("L4741", {"A124": "00.00.0 +100 4"}, {"A124": "00.00.0 +100 3"}, "A124"),
]

CUTOFF = {"A100": "0 0 0 5 1", "A111": "01.00 1"}
CUTOFF_RULES = [
    ("L3933", "A109", "100 000", "000 000"),
    ("L3935", "A110", "0.008", "0.000"),
    ("L3936", "A115", "00.00.0 I1.00.1", "00.00.0 00.00.0"),
    ("L3937", "A130", "I1.00.2 00.00.0", "00.00.0 Q1.00.2"),
    ("L3938", "A132", "Q1.00.3 00.00.0", "00.00.0 00.00.0"),
    ("L3939", "B015", "I1.01.0 0 0 0900", "00.00.0 0 0 0900"),
    ("L3940", "B016", "2000", "0000"),
    ("L3941", "B017", "0 1 0 0 0 0", "0 0 1 0 0 0"),
    ("L4739", "A124", "00.00.0 +100 1", "00.00.0 +100 4"),
    ("L4754", "A125", "+00000.001", "-00005.000"),
]
INTERACTIONS += [(line, {**CUTOFF, pid: bad}, {**CUTOFF, pid: good}, pid) for line, pid, bad, good in CUTOFF_RULES]


@pytest.mark.parametrize(("line", "failing", "passing", "pid"), INTERACTIONS, ids=[f"{i[0]}-{i[3]}" for i in INTERACTIONS])
def test_interaction(line, failing, passing, pid):
    findings = _with(**failing).check()
    assert [(f.where, f.code) for f in findings] == [(pid, "02")], [str(f) for f in findings]
    assert line in findings[0].text
    assert _with(**passing).check() == []


def test_one_wrong_value_is_reported_once():
    """A106 out of range is not also reported against Vmax or by A107 <= A106."""
    assert _findings(_with(A106="060000.000")) == [("A106", "02")]


def test_used_helpers_for_the_program_checker():
    params = _with(A100="0 0 0 5 1")
    assert params.axis_mode(1) == 5 and params.flying_cutoff() and params.master_encoder_1_used()
    assert params.used("A133") and not params.used("A233") and params.used("C008")
    assert not ParameterSet().used("A133") and not ParameterSet().used("B019")


def _is_clm_code(code: str) -> bool:
    if code.startswith("X01:"):
        return code[4:].isdigit() and int(code[4:]) in SERIAL_ERRORS
    return code in FAULTS


_LINE_PARTS = st.sampled_from(["#", "!", "_", " ", "K", "B0", "A1", "A4", "C0", "00", "19", "42", "0", "1", "9", ".", ",", "+", "-",
                               "$", "8E", "I1.00.0", "Q1.06.2", "00.00.0", ";", "\t", "\x00", "é", "#_K_", "FF", "2999", "\r"])
_LINES = st.lists(_LINE_PARTS, max_size=14).map("".join)


@settings(max_examples=400, deadline=None)
@given(st.one_of(st.text(max_size=300), st.lists(_LINES, max_size=12).map("\n".join)))
def test_reading_never_raises_and_every_finding_has_a_clm_code(text):
    params, findings = read_parameter_text(text, "fuzz")
    assert isinstance(params, ParameterSet)
    for finding in findings:
        assert _is_clm_code(finding.code), finding
    params.listing()
    params.telegrams()


@settings(max_examples=200, deadline=None)
@given(st.data())
def test_any_value_of_the_right_form_round_trips(data):
    pid = data.draw(st.sampled_from(sorted(PARAMETERS)))
    parts = []
    for f in PARAMETERS[pid].fields:
        if f.kind == "operand":
            token = data.draw(st.sampled_from(["00.00.0", "I1.00.0", "Q1.06.2", "M2.19.7", "M6.39.7"]))
        elif f.kind == "sign":
            token = data.draw(st.sampled_from("+-"))
        elif f.kind == "hex":
            token = data.draw(st.text("0123456789ABCDEF", min_size=f.int_digits, max_size=f.int_digits))
        else:
            token = data.draw(st.text("0123456789", min_size=f.int_digits, max_size=f.int_digits))
            if f.decimals:
                token += "." + data.draw(st.text("0123456789", min_size=f.decimals, max_size=f.decimals))
            if f.signed:
                token = data.draw(st.sampled_from("+-")) + token
        parts.append(token if not parts or f.glued else " " + token)
    text = "".join(parts)
    assert parse_data(pid, text).data == text
    params, findings = read_parameter_text(f"{pid} {text}")
    assert all(f.code in ("02", "17") for f in findings)  # only range and fit findings
    assert params.data(pid) == text
