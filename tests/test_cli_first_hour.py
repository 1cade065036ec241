"""What a new user meets first in the `axisline` command (issue 16, "The first hour", CLI):
--version, -h on every command, flags shown as flags, help texts printed as written,
`run --json -`, `plot` of either trace file, `compax plot` inputs, config errors that name
the axis and suggest the key meant, and a run summary in the device's words."""

import json
import re
import tomllib
from importlib.metadata import version
from pathlib import Path

import pytest
import typer
from pydantic import ValidationError
from typer.testing import CliRunner

from axisline.cli import app
from axisline.config import MachineConfig
from axisline.configerrors import closest_key, explain
from axisline.devices.fs701.report import report_section

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
runner = CliRunner()


def _commands(group=None, path=()):
    """Every command path of the CLI: (), ("run",), ("fs701",), ("fs701", "envelope"), ..."""
    group = group or typer.main.get_command(app)
    yield path, group
    for name, sub in getattr(group, "commands", {}).items():
        yield from _commands(sub, (*path, name))


COMMANDS = list(_commands())


def _flat(text: str) -> str:
    return " ".join(text.split())


# -- --version, -h, flags, help texts ------------------------------------------------------


def test_version_prints_the_installed_version():
    res = runner.invoke(app, ["--version"])
    assert res.exit_code == 0, res.output
    assert res.stdout.strip() == f"axisline {version('axisline')}"


@pytest.mark.parametrize("path", [p for p, _ in COMMANDS], ids=lambda p: " ".join(p) or "axisline")
def test_every_command_takes_h_and_help(path):
    short = runner.invoke(app, [*path, "-h"])
    long = runner.invoke(app, [*path, "--help"])
    assert short.exit_code == 0 and long.exit_code == 0, short.output
    assert short.stdout == long.stdout
    assert short.stdout.startswith("Usage: ")
    assert "-h, --help" in short.stdout


def test_boolean_flags_are_shown_as_flags():
    flags = 0
    for path, cmd in COMMANDS:
        text = runner.invoke(app, [*path, "--help"]).stdout
        assert "<bool>" not in text, (path, text)
        for p in cmd.params:
            if getattr(p, "is_flag", False) and p.opts[0] != "--version":
                flags += 1
                line = next(line for line in text.splitlines() if line.strip().startswith(p.opts[0]))
                assert line.split()[1] != "<bool>"
    assert flags >= 3  # run --quiet, serve --serial-pty/--allow-writes, clm display --once


_BRACKETED = re.compile(r"\[\[?[^\[\]]+\]\]?")


def test_no_help_text_loses_its_brackets():
    # `[[cam]]` in a help text was printed as "[]" by rich markup; every bracketed word of
    # every command's and parameter's help must reach the screen as written
    checked = []
    for path, cmd in COMMANDS:
        shown = _flat(runner.invoke(app, [*path, "--help"]).stdout)
        texts = [cmd.help or ""] + [getattr(p, "help", None) or "" for p in cmd.params]
        for text in texts:
            for token in _BRACKETED.findall(text):
                assert token in shown, (path, token)
                checked.append(token)
    assert "[[cam]]" in checked  # (the scan found what it is there for)


# -- run --json - ----------------------------------------------------------------------------


def test_json_dash_writes_only_the_json_to_standard_output(tmp_path):
    res = runner.invoke(app, ["run", str(EXAMPLES / "positioning.toml"), "--duration", "0.2", "--quiet", "--json", "-",
                              "--report", str(tmp_path / "rep")])
    assert res.exit_code == 0, res.output
    s = json.loads(res.stdout)  # nothing but the JSON
    assert s["cycles"] == 200 and set(s["axes"]) == {"x", "r"}
    assert "two-axis positioning demo" in res.stderr  # the table went to standard error
    assert not (tmp_path / "-").exists()
    assert json.loads((tmp_path / "rep" / "summary.json").read_text())["cycles"] == 200


# -- axisline plot -------------------------------------------------------------------------


def test_plot_draws_the_csv_trace_as_the_npz(tmp_path):
    res = runner.invoke(app, ["run", str(EXAMPLES / "positioning.toml"), "--duration", "0.3", "--trace", str(tmp_path / "t.npz"), "--quiet"])
    assert res.exit_code == 0
    for name in ("t.npz", "t.csv"):
        res = runner.invoke(app, ["plot", str(tmp_path / name), "--out", str(tmp_path / name.replace(".", "_"))])
        assert res.exit_code == 0, res.output
        assert {p.name for p in (tmp_path / name.replace(".", "_")).iterdir()} == {"axis_x.png", "axis_r.png"}


def test_plot_of_a_report_folder_draws_its_trace(tmp_path):
    runner.invoke(app, ["run", str(EXAMPLES / "positioning.toml"), "--duration", "0.2", "--report", str(tmp_path / "rep"), "--quiet"])
    res = runner.invoke(app, ["plot", str(tmp_path / "rep"), "--out", str(tmp_path / "p")])
    assert res.exit_code == 0, res.output
    assert {p.name for p in (tmp_path / "p").iterdir()} == {"axis_x.png", "axis_r.png"}


def test_csv_trace_keeps_values_and_units(tmp_path):
    from axisline.kernel import Trace
    from axisline.report.tracefile import load_trace

    runner.invoke(app, ["run", str(EXAMPLES / "positioning.toml"), "--duration", "0.3", "--trace", str(tmp_path / "t.npz"), "--quiet"])
    a, b = Trace.load_npz(tmp_path / "t.npz"), load_trace(tmp_path / "t.csv")
    assert b.units == a.units and b.period_us == a.period_us
    da, db = a.data(), b.data()
    assert list(db) == list(da)
    for name in da:
        assert (db[name] == da[name].astype(float)).all(), name  # repr of a float round-trips


@pytest.mark.parametrize("what", ["cam_csv", "machine_file", "png", "bad_cell", "not_a_trace_zip"])
def test_plot_says_what_it_reads(tmp_path, what):
    f = {
        "cam_csv": EXAMPLES / "curves" / "sealing_jaw.csv",
        "machine_file": EXAMPLES / "positioning.toml",
        "png": tmp_path / "x.png",
        "bad_cell": tmp_path / "t.csv",
        "not_a_trace_zip": tmp_path / "t.npz",
    }[what]
    if what == "png":
        f.write_bytes(b"\x89PNG\r\n\x1a\n\xff\xfe\x00")
    elif what == "bad_cell":
        f.write_text("t[s],cycle,x.command_position[mm]\n0.0,0,1.0\n0.001,1,oops\n")
    elif what == "not_a_trace_zip":
        import zipfile

        with zipfile.ZipFile(f, "w") as z:
            z.writestr("a.npy", b"nothing")
    res = runner.invoke(app, ["plot", str(f), "--out", str(tmp_path / "p")])
    assert res.exception is None or isinstance(res.exception, SystemExit), repr(res.exception)  # no traceback
    text = _flat(res.output)
    assert res.exit_code == 2, text
    assert "pickle" not in text
    if what == "bad_cell":
        assert "line 3, column x.command_position: 'oops' is not a number" in text
    else:
        assert "axisline run --trace FILE" in text and "FILE.csv" in text


# -- axisline compax plot --------------------------------------------------------------------


def test_compax_plot_of_a_csv_takes_the_curve_number_in_range(tmp_path):
    csv = str(EXAMPLES / "curves" / "sealing_jaw.csv")
    res = runner.invoke(app, ["compax", "plot", csv, "2", "--master-speed", "600", "--out", str(tmp_path / "c.png")])
    assert res.exit_code == 0, res.output
    assert (tmp_path / "c.png").read_bytes()[:4] == b"\x89PNG"
    for bad in ("0", "101"):
        res = runner.invoke(app, ["compax", "plot", "--master-speed", "600", "--out", str(tmp_path / "d.png"), csv, "--", bad])
        assert res.exit_code == 2 and "1 ... 100" in _flat(res.output), res.output
    assert not (tmp_path / "d.png").exists()


def test_compax_plot_of_a_machine_file_says_what_to_give(tmp_path):
    res = runner.invoke(app, ["compax", "plot", str(EXAMPLES / "cam_packaging.toml"), "2", "--master-speed", "600",
                              "--out", str(tmp_path / "c.png")])
    text = _flat(res.output)
    assert res.exception is None or isinstance(res.exception, SystemExit), repr(res.exception)  # no traceback
    assert "machine file" in text and "cam memory" in text
    assert "curve 2:" in text and "sealing_jaw.csv" in text  # the CSV the machine file names
    assert "Expecting value" not in text


# -- config errors: the axis by its name, the key meant ------------------------------------


AXIS = {"name": "x", "unit": "mm", "counts_per_unit": 1000.0, "v_max": 100.0, "a_max": 1000.0, "following_error_limit": 1.0}


def _problems(data) -> list[str]:
    with pytest.raises(ValidationError) as e:
        MachineConfig.model_validate(data)
    return explain(e.value, MachineConfig, "m.toml", data).problems


def test_a_config_error_names_the_axis_and_the_switch_by_name():
    y = dict(AXIS, name="feed", v_max=-1.0, switches=[{"name": "ref", "kind": "reference", "position": "a"}])
    p = _problems({"axis": [dict(AXIS), y]})
    assert "axis[1].v_max = -1.0 (axis 'feed'): " in p[0] and "> 0" in p[0]
    assert p[1].startswith("axis[1].switches[0].position = 'a' (axis 'feed', switch 'ref'): ")


def test_a_misspelt_key_gets_the_closest_key_suggested():
    p = _problems({"axis": [dict(AXIS, vmax=3.0)]})
    assert p == [p[0]] and p[0].startswith("axis[0].vmax: unknown key (axis 'x'); did you mean v_max? (known keys here: name, ")
    assert closest_key("V_MAX", ["v_max", "a_max"]) == "v_max"
    assert closest_key("colour", ["v_max", "a_max"]) is None  # nothing close: no guess


def test_a_cross_check_of_an_axis_names_it_after_the_message():
    # "axis[0]: <message>" stays as it was (scripts and tests match it); the name follows
    (p,) = _problems({"axis": [dict(AXIS, sw_limits_enabled=True, sw_limit_low=5.0, sw_limit_high=1.0)]})
    assert p.startswith("axis[0]: sw_limit_low = 5") and p.endswith(" (in axis 'x')")


def test_without_the_input_the_lines_are_as_before():
    data = {"axis": [dict(AXIS, v_max=-1.0)]}
    with pytest.raises(ValidationError) as e:
        MachineConfig.model_validate(data)
    (p,) = explain(e.value, MachineConfig, "m.toml").problems
    assert p.startswith("axis[0].v_max = -1.0: ")


def test_a_typo_in_the_machine_file_gets_a_suggestion_from_check(tmp_path):
    f = tmp_path / "m.toml"
    f.write_text((EXAMPLES / "positioning.toml").read_text().replace("a_max =", "amax =", 1))
    assert tomllib.loads(f.read_text())["axis"][0]["amax"]
    res = runner.invoke(app, ["check", str(f)])
    assert res.exit_code == 2 and "axis[0].amax: unknown key" in _flat(res.output)
    assert "did you mean a_max?" in _flat(res.output)


# -- the run summary in the device's words ------------------------------------------------


def test_a_personality_that_drives_the_machine_speaks_instead_of_an_empty_job(tmp_path):
    res = runner.invoke(app, ["run", str(EXAMPLES / "flying_shear.toml"), "--quiet", "--duration", "6"])
    assert res.exit_code == 0, res.output
    assert "job:" not in res.stdout  # no "0 round(s), 0 command(s)" for a batch of cuts
    headline = next(line for line in res.stdout.splitlines() if line.startswith("fs701: "))
    assert re.match(r"fs701: 3 cuts, 2 pieces measured", headline), headline  # one line, not wrapped


def test_a_personality_without_a_summary_line_is_still_named(tmp_path):
    res = runner.invoke(app, ["run", str(EXAMPLES / "cam_packaging.toml"), "--quiet", "--duration", "0.2"])
    assert res.exit_code == 0, res.output
    assert "job:" not in res.stdout and "compax: the personality drove the machine" in res.stdout


def test_a_machine_file_job_still_gets_its_job_line():
    res = runner.invoke(app, ["run", str(EXAMPLES / "positioning.toml"), "--quiet", "--duration", "0.2"])
    assert "job: not finished, 0 round(s), 4 command(s)" in res.stdout


def test_a_machine_without_job_or_personality_says_so(tmp_path):
    f = tmp_path / "idle.toml"
    f.write_text("[machine]\nduration = 0.1\n[[axis]]\nname = \"x\"\nunit = \"mm\"\ncounts_per_unit = 1000.0\n"
                 "v_max = 10.0\na_max = 100.0\nfollowing_error_limit = 1.0\n")
    res = runner.invoke(app, ["run", str(f), "--quiet"])
    assert "job: none (the machine file has no [[job.steps]])" in res.stdout


def test_the_report_explains_why_the_first_cut_has_no_piece(tmp_path):
    res = runner.invoke(app, ["run", str(EXAMPLES / "flying_shear.toml"), "--quiet", "--duration", "6", "--report", str(tmp_path / "r")])
    assert res.exit_code == 0
    md = (tmp_path / "r" / "report.md").read_text()
    cuts = md[md.index("### Cuts"):]
    assert "Cut 1 has no piece length: a piece is the material between two cuts" in cuts
    assert re.search(r"^\| 1 \| [0-9.]+ \| NORMAL \| - \| - \|", cuts, re.M)  # the row it explains
    # a first cut with a length needs no explanation
    d = json.loads((tmp_path / "r" / "summary.json").read_text())["device"]
    d["cuts"][0]["actual_length"] = 1000.0
    assert "has no piece length" not in report_section(d)


def test_check_names_the_axis_by_its_name(tmp_path):
    f = tmp_path / "m.toml"
    f.write_text((EXAMPLES / "positioning.toml").read_text().replace("a_max =", "amax =", 1))
    res = runner.invoke(app, ["check", str(f)])
    assert res.exit_code == 2
    assert "axis[0].amax: unknown key (axis 'x'); did you mean a_max?" in res.output


def test_check_names_what_drives_the_machine():
    """Issue 16: `check` of a device-driven example says which personality drives it, not
    "job of 0 steps"; a file with a job keeps its step count."""
    res = runner.invoke(app, ["check", str(EXAMPLES / "wago_stepper.toml")])
    assert res.exit_code == 0 and "driven by the wago672 personality" in " ".join(res.output.split())
    res = runner.invoke(app, ["check", str(EXAMPLES / "positioning.toml")])
    assert res.exit_code == 0 and "job of 10 steps" in " ".join(res.output.split())
