"""FS701 report plots: one cut cycle and the length-error histogram (the issue's plots)."""

from __future__ import annotations

import numpy as np

from axisline.devices.fs701.report import cycle_window, write_plots

from .test_cutter import mm_settings, running_rig
from .test_cutter_rig import Tool


def _trace():
    rig = running_rig(mm_settings(), 1000.0, tool=Tool(blade_delay=0.02, cut_time=0.1))
    c = rig.cutter
    rows = []
    for _ in range(4000):
        rig.step()
        rows.append((rig.time, rig.material.velocity, c.line_speed, rig.axis.command_position, rig.drive.position,
                     rig.axis.command_velocity, rig.drive.velocity, c.position_error, int(c.cut_state),
                     c.outputs.ready_to_cut, c.inputs.cut_completed))
    a = list(zip(*rows))
    names = ["t", "material.speed", "fs701.line_speed", "car.command_position", "car.actual_position",
             "car.command_velocity", "car.actual_velocity", "fs701.position_error", "fs701.cut_state",
             "fs701.ready_to_cut", "fs701.cut_completed"]
    return {n: np.asarray(v) for n, v in zip(names, a)}, len(c.cut_log)


def _summary(n: int):
    rng = np.random.default_rng(1)
    cuts = [dict(index=i + 1, time=0.5 + i, line_speed=60000.0, error_counts=float(rng.normal(0, 2)),
                 constant_speed=True, mark_offset_counts=None) for i in range(n)]
    return {"length_unit": "mm", "cuts": cuts, "carriage": "car", "counts_per_lu": {"carriage": 4.0, "line": 4.0},
            "tolerance": {"constant_speed_counts": 7.0, "ramp_counts": 14.0, "mark_counts": 7.0}}


def test_cycle_window_finds_ready_to_cut_and_the_return_home():
    data, ncuts = _trace()
    assert ncuts >= 3
    s0, r, f, e0 = cycle_window(data)
    assert s0 < r < f < e0
    assert data["fs701.ready_to_cut"][r] and not data["fs701.ready_to_cut"][r - 1]
    assert 1 in data["fs701.cut_state"][f : e0 + 1]  # home again (HOME = 1) inside the window
    assert 0.09 < data["t"][f] - data["t"][r] < 0.13  # the tool's cut time


def test_cycle_plot_and_error_histogram_pngs_are_written(tmp_path):
    data, _ = _trace()
    paths = write_plots(_summary(30), data, tmp_path)
    names = {p.name for p in paths}
    assert {"fs701_cycle.png", "fs701_error_histogram.png"} <= names
    for p in paths:
        assert p.exists() and p.stat().st_size > 1000


def test_no_cycle_plot_without_the_ready_to_cut_channel(tmp_path):
    data, _ = _trace()
    del data["fs701.ready_to_cut"]
    names = {p.name for p in write_plots(_summary(5), data, tmp_path)}
    assert "fs701_cycle.png" not in names and "fs701_error_histogram.png" in names
