"""Issue 16, plots and reports: what a new user reads off the figures.

* the knife's acceleration (and jerk) is the cam law's, not the count noise of the master;
* the line speed of a flying cutoff is shown in m/min, the unit the devices think in;
* the print-mark cycle plot shows one whole cut cycle.
"""

from __future__ import annotations

import math
import tomllib
from pathlib import Path

import numpy as np
import pytest

from axisline.config import parse_machine
from axisline.machine import Machine
from axisline.motion.cam import PointTable
from axisline.motion.master_observer import MasterObserver
from axisline.motion.segments import SegmentCam

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


def build(path: Path, **machine) -> Machine:
    data = tomllib.loads(path.read_text())
    data["machine"].update(machine)
    return Machine(parse_machine(data, str(path)), source=str(path))


# --------------------------------------------------------------------------- 1. acceleration


def test_master_observer_follows_a_ramp_of_whole_increments_without_their_noise():
    # a master accelerating at 2000 increments/s^2, counted in whole increments per 1 ms:
    # the per-cycle difference of the counted speed jumps by 1 increment/ms per cycle (1e6/s^2)
    period, acc = 0.001, 2000.0
    obs = MasterObserver(period)
    counted, last = 0, 0
    accelerations, speeds = [], []
    for n in range(1, 3001):
        t = n * period
        counted = math.floor(0.5 * acc * t * t + 100.0 * t)
        obs.update(counted - last)
        last = counted
        accelerations.append(obs.acceleration)
        speeds.append(obs.velocity - (100.0 + acc * t))
    settled = np.array(accelerations[1000:])
    assert abs(settled.mean() - acc) < 0.02 * acc  # type 3: no steady error on a ramp
    assert np.abs(settled - acc).max() < 0.25 * acc  # against +-1e6 of a double difference
    speed_error = np.array(speeds[1000:])  # increments/s at 2100 ... 6100 increments/s
    assert abs(speed_error.mean()) < 1.0 and np.abs(speed_error).max() < 10.0  # no lag on the ramp


def test_master_observer_takes_a_start_from_standstill_at_once():
    # a test master that jumps from rest to 2 increments per 1 ms and stops again at once
    obs = MasterObserver(0.001)
    obs.update(0)
    for _ in range(10):
        obs.update(2)
        assert obs.velocity == 2000.0 and obs.acceleration == 0.0
    obs.update(0)
    assert obs.velocity == 0.0 and obs.acceleration == 0.0
    # a wheel leaving standstill one increment at a time is tracked, not snapped
    obs = MasterObserver(0.001)
    for delta in (0, 1, 0, 0, 1, 0, 1):
        obs.update(delta)
    assert 0.0 < obs.velocity < 1000.0


def test_master_observer_rejects_a_bandwidth_the_cycle_cannot_carry():
    with pytest.raises(ValueError, match="bandwidth"):
        MasterObserver(0.001, bandwidth=1000.0)
    with pytest.raises(ValueError, match="period"):
        MasterObserver(0.0)


def test_point_table_set_point_acceleration_is_the_laws_acceleration():
    # a parabola s = x^2 / 2 sampled at 101 points: s'' = 1 everywhere inside; the same
    # table with its set points quantised to 2^-23 of the slave cycle (COMPAX words) keeps it
    x = np.linspace(0.0, 10.0, 101)
    table = PointTable(list(x), list(0.5 * x * x))
    inside = [table.set_point_acceleration(v) for v in np.linspace(1.0, 9.0, 57)]
    assert np.allclose(inside, 1.0, atol=1e-9)
    st = 360.0
    q = PointTable.from_fractions(PointTable(list(x), list(0.5 * x * x * st / 50.0)).fractions(st), 10.0, st)
    quantised = np.array([q.set_point_acceleration(v) for v in np.linspace(1.0, 9.0, 57)])
    assert np.abs(quantised - st / 50.0).max() < 0.01 * st / 50.0
    # eval keeps the exact interpolation: 0 inside the intervals
    assert table.eval(5.05)[2] == 0.0


def _knife_law_bound(data: dict) -> float:
    """max |s''| vm^2 + max |s'| |am| of the example's knife curve and web profile."""
    curve = data["device"]["curves"][0]
    cam = SegmentCam(curve["segments"], master_period=curve["master_period"], periodic=True)
    x = np.linspace(0.0, curve["master_period"], 3001)
    _, ds, dds, _ = cam.eval_array(x)
    profile = data["material"]["profile"]
    vm = max(p["speed"] for p in profile)
    am = max(p["acceleration"] for p in profile)
    return float(np.abs(dds).max() * vm * vm + np.abs(ds).max() * am)


def test_compax_knife_acceleration_is_the_cam_law_not_count_noise():
    path = EXAMPLES / "cam_packaging.toml"
    data = tomllib.loads(path.read_text())
    m = build(path, duration=4.0)
    m.run(4.0)
    d = m.trace.data()
    a = d["knife.command_acceleration"]
    bound = _knife_law_bound(data)
    # the measuring wheel moves 0.05 mm per increment: a double difference per 1 ms gave
    # +-7e4 deg/s^2 here (issue 16); the cam law allows a few thousand
    assert 1000.0 < bound < 10000.0
    assert np.abs(a).max() < 1.2 * bound
    # and it is the law's shape: the set point's velocity changes as its acceleration says
    t, v = d["t"], d["knife.command_velocity"]
    busy = (t > 1.0) & (t < 4.0)
    dv = np.interp(t[busy] + 0.05, t, v) - np.interp(t[busy] - 0.05, t, v)
    assert np.abs(dv / 0.1 - a[busy]).mean() < 0.1 * bound
    # the jerk, the change of that acceleration, stays within the law's order of magnitude
    assert np.abs(d["knife.command_jerk"]).max() < 50.0 * bound


class _Counter:
    counts = 0


def test_cam_follower_on_a_wheel_has_the_laws_acceleration():
    # a cam slave on an encoder master of 20 counts/mm that ramps to 600 mm/s at 2000 mm/s^2;
    # the cam a point table of s = 10 sin(2 pi x / 300) mm, 301 points
    from axisline.motion.camsync import CamFollower
    from axisline.motion.master import EncoderMaster

    period = 0.001
    enc = _Counter()
    master = EncoderMaster(enc, 20.0, period)
    x = np.linspace(0.0, 300.0, 301)
    k = 2.0 * math.pi / 300.0
    cam = CamFollower(master, PointTable(list(x), list(10.0 * np.sin(k * x))))
    errors, peak = [], 0.0
    for n in range(1, 1201):
        t = n * period
        pos = 1000.0 * t * t if t < 0.3 else 90.0 + 600.0 * (t - 0.3)
        vel, acc = (2000.0 * t, 2000.0) if t < 0.3 else (600.0, 0.0)
        enc.counts = math.floor(20.0 * pos)
        _, _, a = cam.sample(n)
        law = -10.0 * k * k * math.sin(k * pos) * vel * vel + 10.0 * k * math.cos(k * pos) * acc
        peak = max(peak, abs(law))
        if t > 0.5:  # after the observer has settled on the ramp's end
            errors.append(a - law)
    # the law's peak is 10 k^2 600^2 = 1579 mm/s^2; a difference of the counted speed gave
    # 1 count/ms^2 = 50 000 mm/s^2 times s' (up to 0.21)
    assert 1500.0 < peak < 1700.0
    assert np.abs(errors).max() < 0.1 * peak


def test_knife_trace_is_still_deterministic():
    path = EXAMPLES / "cam_packaging.toml"
    runs = []
    for _ in range(2):
        m = build(path, duration=1.0)
        m.run(1.0)
        runs.append(m.trace.data())
    for key in ("knife.command_acceleration", "knife.command_position"):
        assert np.array_equal(runs[0][key], runs[1][key])


# --------------------------------------------------------------------------- 2. line speed


def test_line_speed_unit_is_metres_per_minute_for_metric_lengths():
    from axisline.report.cuts import line_speed_unit

    assert line_speed_unit("mm") == (1e-3, "m/min")
    assert line_speed_unit("m") == (1.0, "m/min")
    assert line_speed_unit("in") == (pytest.approx(1.0 / 12.0), "ft/min")
    assert line_speed_unit("LU") == (1.0, "LU/min")  # a unit it does not know stays per minute


def test_cut_table_shows_the_line_speed_in_m_per_min():
    from axisline.report.cuts import cut_table_markdown

    cut = dict(index=2, time=1.5, kind="NORMAL", target_length=800.0, actual_length=800.02, error_lu=0.02,
               error_counts=0.4, line_speed=60000.0, line_speed_measured=59940.0, following_error=0.5,
               constant_speed=True)
    table = cut_table_markdown([cut], "mm", "FS701 line speed")
    head, _, row = table.splitlines()
    assert "line speed [m/min]" in head and "FS701 line speed [m/min]" in head and "mm/min" not in head
    cells = [c.strip() for c in row.strip("|").split("|")]
    assert cells[7:9] == ["60.00", "59.94"]  # 60000 mm/min = 60 m/min


# --------------------------------------------------------------------------- 3. the cycle plot


@pytest.fixture(scope="module")
def printmark_run(tmp_path_factory):
    """The print-mark example for 6 s (a few cut cycles), its trace and the FS701's figures."""
    from axisline.devices.fs701.report import write_plots

    m = build(EXAMPLES / "flying_shear_printmark.toml", duration=6.0)
    m.run(6.0)
    d = m.device.summary()
    out = tmp_path_factory.mktemp("printmark")
    paths = write_plots(d, m.trace.data(), out)
    return d, m.trace.data(), paths


def test_print_mark_cycle_window_spans_synchronisation_cut_and_return(printmark_run):
    from axisline.devices.fs701.report import cycle_window

    d, data, _ = printmark_run
    car = d["carriage"]
    s0, r, f, e0 = cycle_window(data, car)
    t, v, p = data["t"], data[f"{car}.command_velocity"], data[f"{car}.command_position"]
    assert s0 < r < f < e0
    # it starts with the carriage still at its start position, before it accelerates to the line
    home = p[s0]
    assert v[s0] == 0.0
    start_moving = s0 + int(np.flatnonzero(v[s0:] > 0.0)[0])
    assert start_moving < r
    # it ends with the carriage back there, after the return stroke (the set point moved back)
    assert (v[f:e0] < 0.0).any()
    assert v[e0] == 0.0 and abs(p[e0] - home) < 0.5
    # the cut of this cycle lies inside
    assert any(t[r] <= c["time"] <= t[e0] for c in d["cuts"])


def test_print_mark_cycle_plot_and_line_speed_figure_are_written(printmark_run):
    _, _, paths = printmark_run
    names = {p.name for p in paths}
    assert {"fs701_cycle.png", "fs701_line_speed.png"} <= names
