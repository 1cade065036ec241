"""The `axisline` command: exit codes, outputs, serve's clean stop."""

import json
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest
from typer.testing import CliRunner

from axisline.cli import app
from axisline.kernel import Trace

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
runner = CliRunner()

BAD_AXIS = """
[machine]
cycle_us = 1000
[[axis]]
name = "x"
unit = "mm"
counts_per_unit = 1000.0
v_max = -5.0
a_max = 100.0
following_error_limit = 1.0
"""

LAGGING = """
[machine]
duration = 5.0
[[axis]]
name = "x"
unit = "mm"
counts_per_unit = 1000.0
v_max = 100.0
a_max = 1000.0
kv = 1.0
velocity_feed_forward = 0.0
following_error_limit = 0.2
[[job.steps]]
axis = "x"
command = "power"
on = true
[[job.steps]]
axis = "x"
command = "move_absolute"
position = 50.0
"""


def test_run_writes_json_trace_csv_and_plots(tmp_path):
    res = runner.invoke(
        app,
        ["run", str(EXAMPLES / "positioning.toml"), "--json", str(tmp_path / "r.json"), "--trace", str(tmp_path / "t.npz"), "--plot", str(tmp_path / "p"), "--quiet"],
    )
    assert res.exit_code == 0, res.output
    s = json.loads((tmp_path / "r.json").read_text())
    assert s["completed"] is True and s["faults"] == []
    assert set(s["axes"]) == {"x", "r"}
    assert s["axes"]["x"]["max_following_error"] > 0
    assert s["cycles"] * s["cycle_us"] / 1e6 == pytest.approx(s["simulated_s"])
    rec = Trace.load_npz(tmp_path / "t.npz")
    assert rec.units["x.command_position"] == "mm"
    assert (tmp_path / "t.csv").read_text().splitlines()[0].startswith("t")
    assert sorted(p.name for p in (tmp_path / "p").iterdir()) == ["axis_r.png", "axis_x.png"]
    assert (tmp_path / "p" / "axis_x.png").read_bytes()[:4] == b"\x89PNG"


def test_run_duration_and_seed_options(tmp_path):
    res = runner.invoke(app, ["run", str(EXAMPLES / "positioning.toml"), "--duration", "0.5", "--seed", "9", "--json", str(tmp_path / "r.json"), "--quiet"])
    s = json.loads((tmp_path / "r.json").read_text())
    assert s["seed"] == 9 and s["cycles"] == 500
    # a duration asked for is a complete run, even though the job is still moving
    assert res.exit_code == 0 and s["completed"] is True
    assert s["job"]["finished"] is False


def test_job_that_outlasts_the_files_duration_is_a_fault(tmp_path):
    f = tmp_path / "short.toml"
    f.write_text((EXAMPLES / "positioning.toml").read_text().replace("duration = 20.0", "duration = 1.0"))
    res = runner.invoke(app, ["run", str(f), "--quiet", "--json", str(tmp_path / "r.json")])
    s = json.loads((tmp_path / "r.json").read_text())
    assert res.exit_code == 1 and any("job not finished" in x for x in s["faults"])


def test_bad_machine_file_exits_2_naming_the_key(tmp_path):
    f = tmp_path / "bad.toml"
    f.write_text(BAD_AXIS)
    for cmd in ("run", "check"):
        res = runner.invoke(app, [cmd, str(f)])
        assert res.exit_code == 2
        assert "axis[0].v_max = -5.0" in res.output and "> 0" in res.output


def test_runtime_fault_exits_1(tmp_path):
    f = tmp_path / "lag.toml"
    f.write_text(LAGGING)
    res = runner.invoke(app, ["run", str(f), "--quiet", "--json", str(tmp_path / "r.json")])
    assert res.exit_code == 1
    s = json.loads((tmp_path / "r.json").read_text())
    assert any("following error" in x for x in s["faults"])


def test_check_and_plot(tmp_path):
    res = runner.invoke(app, ["check", str(EXAMPLES / "positioning.toml")])
    assert res.exit_code == 0 and "OK" in res.output
    runner.invoke(app, ["run", str(EXAMPLES / "positioning.toml"), "--duration", "0.3", "--trace", str(tmp_path / "t.npz"), "--quiet"])
    res = runner.invoke(app, ["plot", str(tmp_path / "t.npz"), "--out", str(tmp_path / "plots")])
    assert res.exit_code == 0
    assert {p.name for p in (tmp_path / "plots").iterdir()} == {"axis_x.png", "axis_r.png"}


def test_serve_rejects_an_endpoint_the_machine_does_not_offer():
    res = runner.invoke(app, ["serve", str(EXAMPLES / "positioning.toml"), "--modbus", "127.0.0.1:1502"])
    assert res.exit_code == 2 and "--modbus" in res.output


def _axisline() -> list[str]:
    return [sys.executable, "-m", "axisline.cli"]


@pytest.mark.parametrize("sig", [signal.SIGTERM, signal.SIGINT])
def test_serve_stops_cleanly_on_a_signal(sig):
    proc = subprocess.Popen(
        [*_axisline(), "serve", str(EXAMPLES / "positioning.toml")],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
    )
    try:
        assert proc.stdout.readline().strip() == "ready"
        time.sleep(1.5)  # the job is moving both axes on the wall clock by now
        proc.send_signal(sig)
        out, err = proc.communicate(timeout=60)
    finally:
        if proc.poll() is None:
            proc.kill()
    assert proc.returncode == 0, err
    assert "stopped" in out
    assert "axes at rest" in err


def test_report_folder_holds_report_summary_trace_and_plots(tmp_path):
    res = runner.invoke(app, ["run", str(EXAMPLES / "positioning.toml"), "--report", str(tmp_path / "rep"), "--quiet"])
    assert res.exit_code == 0
    names = {p.name for p in (tmp_path / "rep").iterdir()}
    assert {"report.md", "summary.json", "trace.npz", "trace.csv", "axis_x.png", "axis_r.png"} <= names
    md = (tmp_path / "rep" / "report.md").read_text()
    assert "**completed**" in md and "![axis_x](axis_x.png)" in md
    assert "| x | STANDSTILL |" in md


def test_a_longer_duration_on_the_command_line_is_recorded_whole(tmp_path):
    # the scope is sized from the duration: --duration beyond the file's must not truncate it
    f = tmp_path / "short.toml"
    f.write_text((EXAMPLES / "positioning.toml").read_text().replace("duration = 20.0", "duration = 1.0").replace("capacity = 30000", "capacity = 100000"))
    res = runner.invoke(app, ["run", str(f), "--duration", "3.0", "--trace", str(tmp_path / "t.npz"), "--quiet"])
    assert res.exit_code == 0
    rec = Trace.load_npz(tmp_path / "t.npz")
    assert len(rec.data()["t"]) == 3000 and not rec.overflowed


def test_cam_check_reports_maxima_and_the_largest_master_speed(tmp_path):
    res = runner.invoke(app, ["cam", str(EXAMPLES / "cam_sync.toml"), "cut", "--master-speed", "450", "--axis", "knife", "--plot", str(tmp_path / "c.png")])
    assert res.exit_code == 0, res.output
    # modified sine: cv = 1.76 -> 360 deg over 120 mm at 450 mm/s peaks at 1.76 * 3 * 450
    assert "2375" in res.output and "largest master speed" in res.output
    assert (tmp_path / "c.png").read_bytes()[:4] == b"\x89PNG"
    res = runner.invoke(app, ["cam", str(EXAMPLES / "cam_sync.toml"), "cut", "--master-speed", "2000", "--axis", "knife"])
    assert res.exit_code == 1 and "NO" in res.output
    res = runner.invoke(app, ["cam", str(EXAMPLES / "cam_sync.toml"), "nope", "--master-speed", "1"])
    assert res.exit_code == 2


def test_fs701_envelope_command_says_one_metre_at_60_m_min_with_a_1_s_cut_is_not_feasible(tmp_path):
    # manual §10 (fs701.md §5.6): 1 m at 60 m/min with a 1 s cut is not feasible
    params = EXAMPLES / "params" / "fs701_params.toml"
    res = runner.invoke(app, ["fs701", "envelope", str(params), "--cut-time", "1.0", "--speeds", "60000", "--png", str(tmp_path / "e.png")])
    assert res.exit_code == 0, res.output
    row = next(line for line in res.output.splitlines() if line.strip().startswith("60000"))
    assert " NO " in row
    assert (tmp_path / "e.png").read_bytes()[:4] == b"\x89PNG"
