"""Trace / scope: preallocated channels, linear and ring modes, decimation, npz/csv files."""

from __future__ import annotations

import csv
import math
import os
from pathlib import Path

import numpy as np
import pytest

from axisline.kernel import Recording, Scheduler, SimulatedClock, Stage, Trace


class Signal:
    """A value that changes per cycle, as a getter would read it from an axis."""

    def __init__(self) -> None:
        self.value: float | int | bool = 0

    def __call__(self) -> float | int | bool:
        return self.value


def fill(trace: Trace, cycles: range, signal: Signal | None = None) -> None:
    for cycle in cycles:
        if signal is not None:
            signal.value = cycle * 1.5
        trace.record(cycle)


def test_channels_are_stored_with_their_dtypes() -> None:
    trace = Trace(10, period_us=500)
    position, count, enabled = Signal(), Signal(), Signal()
    trace.add_channel("position", position, unit="mm")
    trace.add_channel("counts", count, unit="inc", kind=int)
    trace.add_channel("enabled", enabled, kind=bool)
    for cycle in range(3):
        position.value, count.value, enabled.value = cycle / 3, 2**40 + cycle, cycle == 1
        trace.record(cycle)
    data = trace.data()
    assert list(data) == ["t", "cycle", "position", "counts", "enabled"]
    assert data["position"].dtype == np.float64
    assert data["counts"].dtype == np.int64
    assert data["enabled"].dtype == np.bool_
    assert data["cycle"].dtype == np.int64
    assert data["t"].dtype == np.float64
    assert data["position"].tolist() == [0.0, 1 / 3, 2 / 3]
    assert data["counts"].tolist() == [2**40, 2**40 + 1, 2**40 + 2]  # no float rounding
    assert data["enabled"].tolist() == [False, True, False]
    assert data["t"].tolist() == [0.0, 0.0005, 0.001]
    assert trace.units == {"t": "s", "cycle": "", "position": "mm", "counts": "inc", "enabled": ""}
    assert trace.kind("counts") == "int"


def test_time_is_exact_cycle_times_period() -> None:
    trace = Trace(400, period_us=1000)
    trace.add_channel("x", Signal())
    fill(trace, range(400))
    assert trace.data()["t"][300] == 0.3  # not 0.3000000000000002 from accumulation


def test_linear_mode_stops_when_full_and_flags_overflow() -> None:
    trace = Trace(5)
    signal = Signal()
    trace.add_channel("x", signal)
    fill(trace, range(5), signal)
    assert len(trace) == 5
    assert not trace.overflowed  # full is not overflowed: nothing lost yet
    assert trace.record(5) is False
    fill(trace, range(6, 9), signal)
    assert trace.overflowed
    data = trace.data()
    assert data["cycle"].tolist() == [0, 1, 2, 3, 4]
    assert data["x"].tolist() == [0.0, 1.5, 3.0, 4.5, 6.0]


def test_ring_mode_keeps_newest_samples_in_time_order() -> None:
    trace = Trace(5, mode="ring")
    signal = Signal()
    trace.add_channel("x", signal)
    fill(trace, range(4), signal)
    assert trace.data()["cycle"].tolist() == [0, 1, 2, 3]
    assert not trace.overflowed
    fill(trace, range(4, 12), signal)
    data = trace.data()
    assert len(trace) == 5
    assert trace.overflowed
    assert data["cycle"].tolist() == [7, 8, 9, 10, 11]
    assert data["x"].tolist() == [c * 1.5 for c in range(7, 12)]
    assert data["t"].tolist() == [c / 1000 for c in range(7, 12)]


def test_decimation_keeps_one_sample_in_n_starting_with_the_first() -> None:
    trace = Trace(100, decimation=4)
    signal = Signal()
    trace.add_channel("x", signal)
    stored = [trace.record(cycle) for cycle in range(10, 20)]
    assert stored == [c % 4 == 2 for c in range(10, 20)]
    assert trace.data()["cycle"].tolist() == [10, 14, 18]


def test_data_returns_copies() -> None:
    trace = Trace(4)
    trace.add_channel("x", Signal())
    fill(trace, range(3))
    first = trace.data()
    first["x"][:] = 99.0
    first["cycle"][:] = -1
    again = trace.data()
    assert again["x"].tolist() == [0.0, 0.0, 0.0]
    assert again["cycle"].tolist() == [0, 1, 2]


def test_clear_rearms_the_scope() -> None:
    trace = Trace(2)
    trace.add_channel("x", Signal())
    fill(trace, range(5))
    assert trace.overflowed
    trace.clear()
    assert len(trace) == 0 and not trace.overflowed
    fill(trace, range(10, 11))
    assert trace.data()["cycle"].tolist() == [10]


def test_channels_must_be_declared_before_recording() -> None:
    trace = Trace(4)
    trace.add_channel("x", Signal())
    trace.record(0)
    with pytest.raises(RuntimeError, match="before"):
        trace.add_channel("y", Signal())


@pytest.mark.parametrize("name", ["t", "cycle", "x", "", "__meta__"])
def test_channel_names_must_be_new_and_not_reserved(name: str) -> None:
    trace = Trace(4)
    trace.add_channel("x", Signal())
    with pytest.raises(ValueError):
        trace.add_channel(name, Signal())


def test_channel_kind_must_be_float_int_or_bool() -> None:
    with pytest.raises(ValueError, match="kind"):
        Trace(4).add_channel("x", Signal(), kind=str)


@pytest.mark.parametrize(
    "kwargs",
    [
        {"capacity": 0},
        {"capacity": 10, "decimation": 0},
        {"capacity": 10, "mode": "circular"},
        {"capacity": 10, "period_us": 100},
        {"capacity": 2.5},
    ],
)
def test_bad_trace_settings_are_refused(kwargs: dict) -> None:
    with pytest.raises(ValueError):
        Trace(**kwargs)


def make_trace(period_us: int = 2000) -> tuple[Trace, Signal, Signal, Signal]:
    trace = Trace(8, mode="ring", period_us=period_us)
    speed, counts, mark = Signal(), Signal(), Signal()
    trace.add_channel("speed", speed, unit="mm/s")
    trace.add_channel("counts", counts, unit="inc", kind=int)
    trace.add_channel("mark", mark, kind=bool)
    for cycle in range(11):
        speed.value = math.sin(cycle * 0.1) * 1e3
        counts.value = -(cycle**3)
        mark.value = cycle % 3 == 0
        trace.record(cycle)
    return trace, speed, counts, mark


def test_npz_round_trip_keeps_data_units_and_period(tmp_path: Path) -> None:
    trace, *_ = make_trace()
    path = tmp_path / "scope.npz"
    trace.save_npz(path)

    loaded = Trace.load_npz(path)
    assert isinstance(loaded, Recording)
    original = trace.data()
    data = loaded.data()
    assert list(data) == list(original)
    for name in original:
        assert data[name].dtype == original[name].dtype
        assert np.array_equal(data[name], original[name])
    assert loaded.units == trace.units
    assert loaded.period_us == 2000
    assert loaded.channels == ("speed", "counts", "mark")
    assert loaded.overflowed is True
    assert len(loaded) == 8

    # Plain numpy reads the file too (no pickle needed).
    with np.load(path, allow_pickle=False) as npz:
        assert np.array_equal(npz["speed"], original["speed"])


def test_loaded_recording_can_be_saved_again(tmp_path: Path) -> None:
    trace, *_ = make_trace()
    trace.save_npz(tmp_path / "a.npz")
    Trace.load_npz(tmp_path / "a.npz").save_npz(tmp_path / "b.npz")
    assert (tmp_path / "a.npz").read_bytes() == (tmp_path / "b.npz").read_bytes()


def test_load_refuses_foreign_npz(tmp_path: Path) -> None:
    np.savez(tmp_path / "other.npz", x=np.arange(3))
    with pytest.raises(ValueError, match="not an axisline trace"):
        Trace.load_npz(tmp_path / "other.npz")


def test_csv_has_unit_header_and_exact_values(tmp_path: Path) -> None:
    trace, *_ = make_trace()
    path = tmp_path / "scope.csv"
    trace.save_csv(path)
    with open(path, newline="", encoding="utf-8") as file:
        rows = list(csv.reader(file))
    assert rows[0] == ["t[s]", "cycle", "speed[mm/s]", "counts[inc]", "mark"]
    assert len(rows) == 1 + 8
    data = trace.data()
    assert [float(row[0]) for row in rows[1:]] == data["t"].tolist()
    assert [int(row[1]) for row in rows[1:]] == data["cycle"].tolist()
    assert [float(row[2]) for row in rows[1:]] == data["speed"].tolist()  # repr round-trips
    assert [int(row[3]) for row in rows[1:]] == data["counts"].tolist()
    assert [row[4] for row in rows[1:]] == ["1" if m else "0" for m in data["mark"]]


def simulate(path: Path) -> dict[str, np.ndarray]:
    """A small closed loop through the scheduler: deterministic simulation end to end."""
    clock = SimulatedClock(250)
    sched = Scheduler(clock)
    state = {"target": 0.0, "position": 0.0, "velocity": 0.0, "counts": 0, "in_pos": False}

    def setpoints(cycle: int) -> None:
        state["target"] = 10.0 * math.sin(2 * math.pi * 3.0 * clock.now)

    def position_loop(cycle: int) -> None:
        state["velocity"] = 150.0 * (state["target"] - state["position"])

    def actuate(cycle: int) -> None:
        state["position"] += state["velocity"] * clock.period
        state["counts"] = round(state["position"] * 4096)
        state["in_pos"] = abs(state["target"] - state["position"]) < 0.05

    trace = Trace(1000, decimation=3, mode="ring", period_us=clock.period_us)
    trace.add_channel("position", lambda: state["position"], unit="mm")
    trace.add_channel("velocity", lambda: state["velocity"], unit="mm/s")
    trace.add_channel("counts", lambda: state["counts"], unit="inc", kind=int)
    trace.add_channel("in_position", lambda: state["in_pos"], kind=bool)
    sched.add_task("setpoints", setpoints, Stage.SETPOINTS)
    sched.add_task("kv", position_loop, Stage.POSITION_LOOP)
    sched.add_task("drive", actuate, Stage.ACTUATE)
    sched.add_task("scope", trace.record, Stage.RECORD)
    sched.commands.submit_at(1200, state.__setitem__, "position", 3.0)  # scripted disturbance
    sched.run(4000)
    trace.save_npz(path)
    return trace.data()


def test_identical_runs_give_bit_identical_npz(tmp_path: Path) -> None:
    first = simulate(tmp_path / "run1.npz")
    second = simulate(tmp_path / "run2.npz")
    assert first["counts"].any() and first["in_position"].any() and not first["in_position"].all()
    loaded1 = Trace.load_npz(tmp_path / "run1.npz").data()
    loaded2 = Trace.load_npz(tmp_path / "run2.npz").data()
    for name in first:
        assert first[name].tobytes() == second[name].tobytes()
        assert np.array_equal(loaded1[name].view(np.uint8), loaded2[name].view(np.uint8))
    # The whole file is reproducible too, so a checksum can guard a simulation.
    assert (tmp_path / "run1.npz").read_bytes() == (tmp_path / "run2.npz").read_bytes()


def test_failed_save_leaves_previous_file_intact(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    trace, *_ = make_trace()
    path = tmp_path / "scope.npz"
    trace.save_npz(path)
    good = path.read_bytes()

    def disk_full(fd: int) -> None:
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(os, "fsync", disk_full)
    trace.record(99)
    with pytest.raises(OSError, match="No space"):
        trace.save_npz(path)
    assert path.read_bytes() == good
    assert sorted(p.name for p in tmp_path.iterdir()) == ["scope.npz"]
