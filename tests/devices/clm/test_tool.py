"""`axisline clm check | convert | checksum` on files, as a maintainer uses them."""

from __future__ import annotations

from pathlib import Path

import pytest
from typer.testing import CliRunner

from axisline.cli import app

EXAMPLES = Path(__file__).resolve().parents[3] / "examples" / "clm"
runner = CliRunner()


def clm(*args: str):
    result = runner.invoke(app, ["clm", *map(str, args)])
    assert result.exception is None or isinstance(result.exception, SystemExit), result.exception
    assert "Traceback" not in result.output
    return result


def _examples(suffix: str) -> list[Path]:
    return sorted(EXAMPLES.glob(f"*{suffix}"))


def test_every_example_program_checks_clean_with_its_files():
    programs = _examples(".prg")
    assert programs
    for prg in programs:
        args = [prg]
        for option, suffix in (("--params", ".par"), ("--logic", ".lt"), ("--variables", ".var")):
            if prg.with_suffix(suffix).exists():
                args += [option, prg.with_suffix(suffix)]
        r = clm("check", *args)
        assert r.exit_code == 0, r.output
        assert "clean" in r.output


def test_broken_program_names_the_line_and_the_code(tmp_path):
    bad = tmp_path / "bad.prg"
    bad.write_text("0000 POI 1 +000100.000 999\n0001 POI 7 +000100.000 999\n0002 FOO 1\n0003 JMP 0000\n")
    r = clm("check", bad)
    assert r.exit_code == 2
    assert "N0001 16 Axis No. false" in r.output and "bad.prg:2" in r.output
    assert "N0002 0A Invalid Prg Cmd" in r.output and "bad.prg:3" in r.output


def test_broken_transfer_file_reports_status_01_errors(tmp_path):
    bad = tmp_path / "bad.txt"
    bad.write_text("#_N0101_AEA_Q1.00.3_1_$C1\r\n#_N3000_NOP__$5D\r\n")
    r = clm("check", bad)
    assert r.exit_code == 2
    assert "X01:04 RS Checksum Error" in r.output and "X01:12" in r.output


def test_warnings_only_exit_1(tmp_path):
    warn = tmp_path / "w.prg"
    warn.write_text("0000 JMP 0100\n")  # jumps where nothing is written
    r = clm("check", warn)
    assert r.exit_code == 1, r.output
    assert "(warning)" in r.output


def test_unreadable_or_binary_input_is_a_finding_not_a_traceback(tmp_path):
    binary = tmp_path / "b.prg"
    binary.write_bytes(b"\x00\xff\xfe garbage \x81\n0000 NOP\n")
    assert clm("check", binary).exit_code == 2
    assert clm("check", tmp_path / "missing.prg").exit_code == 2
    assert clm("check", tmp_path).exit_code == 2  # a directory


def test_convert_listing_to_transfer_and_back(tmp_path):
    src = EXAMPLES / "roll_feed.prg"
    transfer = tmp_path / "roll_feed.txt"
    r = clm("convert", src, transfer, "--to", "transfer")
    assert r.exit_code == 0, r.output
    raw = transfer.read_bytes()
    assert raw.endswith(b"\r\n") and b"\r\n" in raw and raw.isascii()
    assert raw.splitlines()[0].startswith(b"# N0000 CLC 0007 $")
    back = tmp_path / "back.prg"
    assert clm("convert", transfer, back, "--to", "listing").exit_code == 0
    assert clm("check", back).exit_code == 0
    lines = [line.split("  - ")[0] for line in src.read_text().splitlines() if line[:1].isdigit()]
    assert [" ".join(line.split()) for line in lines] == back.read_text().splitlines()


def test_convert_refuses_a_file_with_errors_and_keeps_the_old_target(tmp_path):
    bad = tmp_path / "bad.prg"
    bad.write_text("0000 POI 1 +000100.000 999\n0001 XYZ\n")
    target = tmp_path / "out.txt"
    target.write_text("old")
    r = clm("convert", bad, target, "--to", "transfer")
    assert r.exit_code == 2 and "not written" in r.output
    assert target.read_text() == "old"


@pytest.mark.parametrize(
    ("telegram", "out", "code"),
    [
        ("#_N0101_AEA_Q1.00.3_1_", "C0", 0),
        ("#_N0101_AEA_Q1.00.3_1_$C0", "$C0 is right", 0),
        ("# K B000 0 0 0 0$8E", "$8E is wrong", 1),  # L6591 as printed (errata §3.4)
        ("# K B000 0 0 0$8E", "$8E is right", 0),
    ],
)
def test_checksum_command(telegram, out, code):
    r = clm("checksum", telegram)
    assert r.exit_code == code and out in r.output


def test_broken_logic_task_names_the_lt_instruction_and_38(tmp_path):
    prg = EXAMPLES / "roll_feed.prg"
    lt = tmp_path / "bad.lt"
    lt.write_text("0000 LD I1.00.0\n0001 AND( I1.00.2\n0002 ST M5.00.0\n0003 END\n")  # '(' never closed
    r = clm("check", prg, "--logic", lt)
    assert r.exit_code == 2
    assert "LT0001 38 Logic Prg. Error" in r.output
    lt.write_text("0000 LD I1.00.0\n0001 ST M2.00.0\n0002 END\n")  # M2 is the NC's
    r = clm("check", prg, "--logic", lt)
    assert r.exit_code == 2 and "LT0001 38" in r.output and "bad.lt:2" in r.output


def test_broken_variables_file(tmp_path):
    var = tmp_path / "bad.var"
    var.write_text("V600 +250.000\nV100 +1\nV601 12a\n")
    r = clm("check", EXAMPLES / "roll_feed.prg", "--variables", var)
    assert r.exit_code == 2
    assert "V100 X01:23 Wrong Variable #" in r.output and "X01:18" in r.output


def test_variable_that_does_not_fit_its_field_is_a_32_warning(tmp_path):
    var = tmp_path / "big.var"
    var.write_text("V600 +1234567.0\nV601 +999\nV602 +20\n")  # a feed length beyond 6.3 digits
    r = clm("check", EXAMPLES / "roll_feed.prg", "--variables", var)
    assert r.exit_code == 1
    assert "N0003 32 Variable Value" in r.output and "too large" in r.output


def test_parameters_decide_axes_and_cutoff_rules(tmp_path):
    prg = tmp_path / "p.prg"
    prg.write_text("0000 POI 2 +000010.000 999\n0001 LML 1 001000.000\n0002 EOS\n0003 JMP 0000\n")
    r = clm("check", prg, "--params", EXAMPLES / "roll_feed.par")
    assert r.exit_code == 2
    assert "N0000 7E A2 not enabled" in r.output  # B000 enables axis 1 only (axis fault base 0x70)
    assert "N0001 0A" in r.output and "flying cutoff" in r.output  # A100 mode is not 5


def test_broken_parameter_file_names_the_parameter(tmp_path):
    par = tmp_path / "bad.par"
    par.write_text((EXAMPLES / "roll_feed.par").read_text().replace("A106 000500.000", "A106 0005x0.000"))
    r = clm("check", EXAMPLES / "roll_feed.prg", "--params", par)
    assert r.exit_code == 2
    assert "A106 02" in r.output and "bad.par:" in r.output
    assert r.output.count("A106 02") == 1  # reported once


@pytest.mark.parametrize(("name", "kind"), [("roll_feed.par", "parameters"), ("roll_feed.lt", "logic"), ("roll_feed.var", "variables")])
def test_convert_every_kind_round_trips(tmp_path, name, kind):
    from axisline.devices.clm.files import read_file

    transfer, back = tmp_path / "t.txt", tmp_path / name
    assert clm("convert", EXAMPLES / name, transfer, "--to", "transfer").exit_code == 0
    assert all(line.endswith(b"\r\n") and b"$" in line for line in transfer.read_bytes().splitlines(keepends=True))
    assert clm("convert", transfer, back, "--to", "listing").exit_code == 0
    original, again = read_file(EXAMPLES / name), read_file(back)
    assert (original.kind, again.kind) == (kind, kind)
    assert original.ok and again.ok and original.data == again.data
