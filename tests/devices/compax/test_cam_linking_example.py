"""examples/cam_linking.toml: the supplement's §15.2 program example 2 (L1474-1484) from a program
file, on a measuring-wheel master, with `axisline run --report` (issue 19)."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

from axisline.cli import app

EXAMPLE = Path(__file__).resolve().parents[3] / "examples" / "cam_linking.toml"
S_T = {1: 420.0, 2: 300.0, 3: 360.0}


@pytest.fixture(scope="module")
def report(tmp_path_factory):
    out = tmp_path_factory.mktemp("cam_linking")
    res = CliRunner().invoke(app, ["run", str(EXAMPLE), "--report", str(out / "report"), "--json", str(out / "s.json")])
    return res, out


def test_runs_with_report_and_the_printed_curve_order(report):
    res, out = report
    assert res.exit_code == 0, res.output
    summary = json.loads((out / "s.json").read_text())
    program = summary["device"]["program_memory"]
    assert program["sets"] == 11 and program["state"] == "running" and not program["errors"]
    events = program["curves"]
    # N006 LOOP 1, N008 LOOP 2, N010 LOOP 1, N011 SETC 1 / N012 GOTO 6: 1, 2 (x2), 3, 1, 2 (x2), 3, ...
    assert [(e["curve"], e["loop"]) for e in events[:7]] == [(1, 1), (2, 2), (3, 1), (1, 1), (2, 2), (3, 1), (1, 1)]
    # normal mode: every curve starts at the end value of the last one (S47 less the new curve's
    # value at S44: gradient 1 at the curve start, M_T = 360 mm)
    end = 0.0
    for previous, e in zip(events, events[1:]):
        end += S_T[previous["curve"]] * (2 if previous["loop"] == 2 else 1)
        assert e["set_point"] - 0.360 * e["S44"] == pytest.approx(end, abs=1e-3)
    text = (out / "report" / "report.md").read_text()
    assert "## COMPAX program" in text and "| transfer | 2 | 2 |" in text


def test_no_speed_jump_at_the_transfers(report):
    # L1548-1550: "The gradients on the end of a curve and on the start of the next curve must
    # coincide; otherwise jumps in speed occur": all three curves have gradient 1 at their borders,
    # so around every transfer the belt runs at the line's speed (the set point's speed averaged
    # over 20 ms: a single 1 ms step is one encoder count, 50 mm/s)
    res, out = report
    summary = json.loads((out / "s.json").read_text())
    trace = np.load(out / "report" / "trace.npz")
    t, p, line = trace["t"], trace["belt.command_position"], trace["material.speed"]
    for e in summary["device"]["program_memory"]["curves"][1:]:
        k = int(np.searchsorted(t, e["t"]))
        for a, b in ((k - 10, k), (k, k + 10)):  # 20 ms before and after (decimation 2)
            speed = (p[b] - p[a]) / (t[b] - t[a])
            assert speed == pytest.approx(line[a:b + 1].mean(), abs=6.0), (e, a, b)
    # a curve's own speed change is far larger than that: the middle of curve 1 runs 4/3 faster
    assert np.abs(trace["belt.command_velocity"] - line).max() > 150.0
