"""The CLM telegram codec: checksum, framing, station byte (manual §9.2, L6380-6540)."""

from __future__ import annotations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from axisline.devices.clm.errors import ClmError
from axisline.devices.clm.telegram import checksum, emit, parse_telegram, station_char, station_number


def test_checksum_worked_example_1_from_the_sum_table():
    """Fig. 9-12 (L6474-6516): '#_N0000_POI_1____+123456.789_123_' sums to 0x636 -> 06 + 36 = 3C -> C4."""
    text = "# N0000 POI 1    +123456.789 123 "
    assert sum(text.encode()) == 0x636
    assert checksum(text) == "C4"


def test_checksum_worked_example_2_station_5():
    """Fig. 9-12 (L6520-6522): '#5N0123_NOP__' sums to 0x2B9 -> 02 + B9 = BB -> 45."""
    assert sum(b"#5N0123 NOP  ") == 0x2B9
    assert checksum("#5N0123 NOP  ") == "45"


@pytest.mark.parametrize(
    ("text", "hh"),
    [
        ("# N0101 AEA Q1.00.3 1 ", "C0"),  # L6536: verifies only with the trailing blank (errata §1.8)
        ("# N0102 BPA 0123 M2.02      21112212 ", "32"),  # L6537: six blanks before the mask
        ("# K B002 019200 0 1 8 1", "E4"),  # L6600: parameters carry no blank before $
        ("# K B006 ", "59"),  # empty parameter data
    ],
)
def test_printed_checksums(text, hh):
    assert checksum(text) == hh
    assert parse_telegram(f"{text}${hh}\r\n").checksum == hh


def test_bpa_with_five_blanks_does_not_verify():
    """Errata §1.8: the printed BPA telegram verifies with 6 blanks, not the 5 of the text (-> 52)."""
    assert checksum("# N0102 BPA 0123 M2.02     21112212 ") == "52"
    with pytest.raises(ClmError) as e:
        parse_telegram("# N0102 BPA 0123 M2.02     21112212 $32")
    assert e.value.code == "X01:04"


def test_frame_parts_and_emit_round_trip():
    t = parse_telegram("#AN0000 NOP  $" + checksum("#AN0000 NOP  "))
    assert (t.control, t.station, t.kind, t.body) == ("#", 10, "N", "0000 NOP  ")
    assert t.emit() == "#AN0000 NOP  $" + checksum("#AN0000 NOP  ") + "\r\n"
    reply = parse_telegram("X 05  CLM $" + checksum("X 05  CLM "))
    assert (reply.control, reply.kind, reply.body) == ("X", "", "05  CLM ")


def test_stations():
    """RS232 a blank; RS485 1-9, A=10 ... W=32 (L6394-6400)."""
    assert station_char(0) == " " and station_char(10) == "A" and station_char(32) == "W"
    assert [station_number(c) for c in " 9AFW"] == [0, 9, 10, 15, 32]
    with pytest.raises(ClmError) as e:
        station_number("Z")
    assert e.value.code == "X01:02"
    with pytest.raises(ValueError):
        station_char(33)


def test_lower_case_checksum_and_missing_checksum():
    assert parse_telegram("# N0101 AEA Q1.00.3 1 $c0").checksum == "C0"
    assert parse_telegram("# N0101 AEA Q1.00.3 1 ").checksum is None
    with pytest.raises(ClmError) as e:
        parse_telegram("# N0101 AEA Q1.00.3 1 ", require_checksum=True)
    assert e.value.code == "X01:04"


@pytest.mark.parametrize("line", ["", "x", "N0000 NOP", "#", "# Z0000", "# N0000 NOP $1", "# N0000 NOP $GG", "# N0\x00 $00", "# N0000 NOPé"])
def test_malformed_telegrams_are_format_errors(line):
    with pytest.raises(ClmError) as e:
        parse_telegram(line)
    assert e.value.code == "X01:02"


@settings(max_examples=400, deadline=None)
@given(st.one_of(st.text(max_size=80), st.binary(max_size=80), st.from_regex(r"[#?!:XVP][ 1-9A-W][NKXPV][ -~]{0,40}(\$[0-9A-F]{2})?", fullmatch=True)))
def test_fuzz_parse_raises_only_clm_errors_with_a_code(line):
    try:
        t = parse_telegram(line)
    except ClmError as e:
        assert e.code.startswith("X01:")
        return
    if t.checksum is not None:  # anything accepted with a checksum re-emits to the same bytes
        text = line.decode() if isinstance(line, bytes) else line
        assert t.emit().rstrip("\r\n").upper() == text.rstrip("\r\n").upper()


@given(st.text(alphabet=st.characters(min_codepoint=32, max_codepoint=126, blacklist_characters="$"), max_size=40), st.integers(0, 32))
def test_emit_then_parse_verifies(body, station):
    line = emit("#", station, "N", body)
    assert parse_telegram(line, require_checksum=True).body == body


def _manual_telegrams():
    from .manual_examples import TELEGRAMS

    return [pytest.param(t, id=t["name"]) for t in TELEGRAMS]


@pytest.mark.parametrize("t", _manual_telegrams())
def test_every_checksummed_telegram_of_the_manual(t):
    """manual_examples.TELEGRAMS (lines in each entry): the printed form verifies or is refused
    with X01:04, and the corrected form (sum table / errata §1.8) verifies."""
    printed = f"{t['text']}${t['checksum']}"
    if t["verifies"]:
        assert parse_telegram(printed).checksum == t["checksum"]
    else:
        with pytest.raises(ClmError) as e:
            parse_telegram(printed)
        assert e.value.code == "X01:04"
        assert parse_telegram(f"{t['corrected']}${t['checksum']}").checksum == t["checksum"]
