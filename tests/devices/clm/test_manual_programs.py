"""Every program listing printed in the manual reads (tests/devices/clm/manual_examples.py, with lines).

The few lines the manual itself prints wrongly are refused with the CLM's code, each named
here with the reason (the entry's note in manual_examples says more).
"""

from __future__ import annotations

import re

import pytest

from axisline.devices.clm.check import check_program
from axisline.devices.clm.errors import ClmError
from axisline.devices.clm.files import read_program_text
from axisline.devices.clm.program import parse_listing_line

from .manual_examples import PROGRAM_LISTINGS

# (listing, instruction) -> code: printing defects of the manual
DEFECTS = {
    ("acc_fig5_3", 2): "0A",  # L1419 'AKN M2.00.0' without its state digit
    ("txt_status63", 0): "0A",  # L2761-2785: the text printed as spaced glyphs with '_' (lost blanks)
    ("txt_status63", 1): "0A",
    ("txt_status53", 0): "0A",
    ("txt_status53", 1): "0A",
    ("txt_status53", 2): "0A",
    ("vcc_mode1_fig5_32", 5): "0A",  # L2856: an empty row
    ("task2_example", 203): "1D",  # L3437-3441: APE needs a byte operand, printed 'Q1.01.0'
    ("task2_example", 205): "1D",
    ("task2_example", 207): "1D",
    ("task3_example", 801): "1D",
    ("task3_example", 804): "1D",  # L3466 'I1.00.00'
}

_NUMBERED = re.compile(r"\s*(\d{4})\s")


def _lines():
    for entry in PROGRAM_LISTINGS:
        for line in entry["text"].split("\n"):
            m = _NUMBERED.match(line)
            if m:
                yield pytest.param(entry["name"], int(m.group(1)), line, id=f"{entry['name']}-{m.group(1)}")


@pytest.mark.parametrize(("name", "number", "line"), list(_lines()))
def test_manual_listing_line(name, number, line):
    code = DEFECTS.get((name, number))
    if code is None:
        ins = parse_listing_line(line)
        assert ins.number == number
        assert parse_listing_line(ins.listing()) == ins
    else:
        with pytest.raises(ClmError) as e:
            parse_listing_line(line)
        assert e.value.code == code


def _listing(name: str) -> str:
    """The instruction lines of a listing (the manual's heading rows such as 'Product 1' dropped)."""
    text = next(e["text"] for e in PROGRAM_LISTINGS if e["name"] == name)
    return "\n".join(line for line in text.split("\n") if _NUMBERED.match(line))


def test_fig_7_20_flying_cutoff_program_is_clean():
    """Fig. 7-20 (L3900-3921): 100 pieces of 1000, 200 of 2000; the cutoff program ends with EOS, RTS."""
    program, findings = read_program_text(_listing("flying_cutoff_fig7_20"))
    assert findings == []
    assert [i.mnemonic for i in program.written()][-2:] == ["EOS", "RTS"]
    assert [f for f in check_program(program, cutoff_axis1=True) if f.is_error] == []


def test_fig_7_20_without_eos_is_error_35():
    text = "\n".join(line for line in _listing("flying_cutoff_fig7_20").split("\n") if "EOS" not in line)
    program, _ = read_program_text(text)
    assert [f.code for f in check_program(program) if f.is_error] == ["35"]


def test_bac_examples_are_clean_programs():
    """L1548-1561: both BAC examples end in a jump, so nothing runs off into NOPs."""
    for name in ("bac_example_a", "bac_example_b", "cou_example"):
        program, findings = read_program_text(_listing(name))
        assert findings == [] and check_program(program) == [], name


def test_rep_directly_after_srm_for_the_same_axis_is_allowed_for_another_axis_1a():
    """L2361-2365 place REP right after SRM (decision C-REP); error 1A when the axes differ (L8484-8486)."""
    program, _ = read_program_text(_listing("rep_example_2") + "\n0032 JMP 0030\n")
    assert [f.code for f in check_program(program) if f.is_error] == []
    program, _ = read_program_text("0030 SRM 1 +000000.000 +050 I1.01.0\n0031 REP 0900 2 000500.000\n0032 JMP 0030\n")
    assert [f.code for f in check_program(program) if f.is_error] == ["1A"]


def test_raster_input_of_the_other_axis_is_1d():
    """Raster 1 (I0.01.7) serves axis 1, Raster 2 (I0.01.4) axis 2 (L2625)."""
    program, _ = read_program_text("0000 SRM 2 +000000.000 +500 I0.01.7\n0001 SRM 2 +000000.000 +500 I0.01.4\n0002 JMP 0000\n")
    assert [(f.where, f.code) for f in check_program(program) if f.is_error] == [("N0000", "1D")]
