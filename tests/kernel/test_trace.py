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


# --- the row block (issue 18): samples reach the columns a block at a time ---------------------


def reference_data(capacity: int, mode: str, decimation: int, cycles: range) -> dict[str, list]:
    """What the scope must hold: the newest (ring) or first (linear) samples, by hand."""
    taken = [c for i, c in enumerate(cycles) if i % decimation == 0]
    kept = taken[-capacity:] if mode == "ring" else taken[:capacity]
    return {"cycle": kept, "x": [c * 1.5 for c in kept]}


@pytest.mark.parametrize(("capacity", "mode", "decimation", "n"), [
    (1000, "linear", 1, 700),  # several blocks, a part block at the end
    (300, "linear", 1, 700),  # full in the middle of a block
    (300, "ring", 1, 700),  # wraps in the middle of a block
    (100, "ring", 3, 1000),  # a block larger than the ring
    (1, "ring", 1, 5),
    (257, "ring", 2, 3000),
])
def test_reads_mid_block_see_every_sample_recorded(capacity: int, mode: str, decimation: int, n: int) -> None:
    trace = Trace(capacity, decimation=decimation, mode=mode)  # type: ignore[arg-type]
    signal = Signal()
    trace.add_channel("x", signal)
    for cycle in range(n):
        signal.value = cycle * 1.5
        trace.record(cycle)
        if cycle % 97 == 0 or cycle == n - 1:  # reads at odd places inside blocks
            want = reference_data(capacity, mode, decimation, range(cycle + 1))
            data = trace.data()
            assert data["cycle"].tolist() == want["cycle"]
            assert data["x"].tolist() == want["x"]
            assert data["t"].tolist() == [c / 1000 for c in want["cycle"]]
            assert len(trace) == len(want["cycle"])


def test_ring_wraps_inside_a_block() -> None:
    trace = Trace(10, mode="ring")
    signal = Signal()
    trace.add_channel("x", signal)
    fill(trace, range(27), signal)  # the block of 10 wraps; 27 samples: the 3rd ring pass
    assert trace.data()["cycle"].tolist() == list(range(17, 27))
    assert trace.stored == 27
    assert trace.overflowed


def test_several_channels_from_one_getter_keep_their_kinds_and_order() -> None:
    trace = Trace(600, period_us=500)
    state = {"v": 0.0, "n": 0, "on": False}
    trace.add_channel("first", lambda: state["v"] * 2)
    trace.add_channels(
        ["speed", "counts", "ready"],
        lambda: (state["v"], state["n"], state["on"]),
        units=["mm/s", "inc", ""],
        kinds=[float, int, bool],
    )
    trace.add_channel("last", lambda: state["n"], kind=int)
    for cycle in range(520):
        state.update(v=math.sin(cycle) * 1e3, n=2**40 + cycle, on=cycle % 3 == 0)
        trace.record(cycle)
    data = trace.data()
    assert list(data) == ["t", "cycle", "first", "speed", "counts", "ready", "last"]
    cycles = range(520)
    assert data["speed"].tolist() == [math.sin(c) * 1e3 for c in cycles]
    assert data["first"].tolist() == [math.sin(c) * 1e3 * 2 for c in cycles]
    assert data["counts"].tolist() == [2**40 + c for c in cycles]  # int64: no float rounding
    assert data["counts"].dtype == np.int64 and data["ready"].dtype == np.bool_
    assert data["ready"].tolist() == [c % 3 == 0 for c in cycles]
    assert data["last"].tolist() == [2**40 + c for c in cycles]
    assert trace.units["counts"] == "inc" and trace.kind("ready") == "bool"


# values of every type a getter may return, for each kind of channel
ODD_VALUES = {
    float: [1.25, -0.0, math.inf, -math.inf, 7, True, np.float32(0.1), np.float64(2.5), np.int64(-3), None,
            2**70, 1e-310],
    int: [5, -(2**63), 2**63 - 1, True, np.int64(9), np.int32(-4), 2.7, -2.7, np.float64(3.9), np.bool_(True)],
    bool: [True, False, 0, 2, 0.0, 0.5, math.nan, np.bool_(False), np.float64(0.0), np.int64(-1), "", "x", None],
}


@pytest.mark.parametrize("kind", [float, int, bool])
@pytest.mark.parametrize("grouped", [False, True])
def test_block_stores_what_numpy_assignment_stores(kind: type, grouped: bool) -> None:
    values = ODD_VALUES[kind]
    expected = np.zeros(len(values), dtype={float: np.float64, int: np.int64, bool: np.bool_}[kind])
    for i, v in enumerate(values):
        expected[i] = v  # numpy's own conversion: what the scope stored before blocks
    trace = Trace(len(values) + 1)
    current: list = [None]
    if grouped:
        trace.add_channels(["a", "b"], lambda: (current[0], 1.0), kinds=[kind, float])
    else:
        trace.add_channel("a", lambda: current[0], kind=kind)
    for cycle, v in enumerate(values):
        current[0] = v
        trace.record(cycle)
    got = trace.data()["a"]
    assert got.dtype == expected.dtype
    assert got.tobytes() == expected.tobytes()  # bit for bit (-0.0, inf, nan included)


def test_a_value_numpy_refuses_raises_in_its_cycle_and_is_not_stored() -> None:
    trace = Trace(10)
    current: list = [1]
    trace.add_channel("n", lambda: current[0], kind=int)
    trace.record(0)
    current[0] = math.nan  # numpy: cannot convert float NaN to integer
    with pytest.raises(ValueError):
        trace.record(1)
    current[0] = 3
    trace.record(2)
    assert trace.data()["n"].tolist() == [1, 3]
    assert trace.data()["cycle"].tolist() == [0, 2]


def test_a_getter_that_raises_stores_no_part_of_the_sample() -> None:
    trace = Trace(10)
    current: list = [0.0, False]

    def row() -> tuple:
        if current[1]:
            raise RuntimeError("sensor gone")
        return (current[0], current[0] + 1)

    trace.add_channels(["a", "b"], row)
    trace.record(0)
    current[1] = True
    with pytest.raises(RuntimeError, match="sensor gone"):
        trace.record(1)
    current[:] = [5.0, False]
    trace.record(2)
    data = trace.data()
    assert data["cycle"].tolist() == [0, 2] and data["b"].tolist() == [1.0, 6.0]


def test_a_getter_returning_the_wrong_count_is_named() -> None:
    trace = Trace(10)
    trace.add_channels(["a", "b", "c"], lambda: (1.0, 2.0))
    with pytest.raises(ValueError, match=r"a, b, c.*2 values for 3 channels"):
        trace.record(0)
    assert len(trace) == 0
    single = Trace(10)
    single.add_channels(["a", "b"], lambda: 1.0)  # not a sequence
    with pytest.raises(ValueError, match=r"a, b: the getter returned 1.0 for 2 channels"):
        single.record(0)


@pytest.mark.parametrize(("args", "match"), [
    ((["a", "a"], lambda: (1, 2)), "already exists"),
    ((["a", "t"], lambda: (1, 2)), "already exists"),
    (([], lambda: ()), "no channel names"),
    ((["a", "b"], "not callable"), "callable"),
])
def test_bad_channel_groups_are_refused_and_add_nothing(args: tuple, match: str) -> None:
    trace = Trace(4)
    with pytest.raises((ValueError, TypeError), match=match):
        trace.add_channels(*args)
    with pytest.raises(ValueError, match="kind"):
        trace.add_channels(["p", "q"], lambda: (1, 2), kinds=[float, str])
    with pytest.raises(ValueError, match="2 names but 1 units"):
        trace.add_channels(["p", "q"], lambda: (1, 2), units=["mm"])
    assert trace.channels == ()
    trace.add_channels(["a", "b"], lambda: (1.0, 2.0))  # the names are still free
    assert trace.channels == ("a", "b")


# --- samples since n (the HMI's live scope) -----------------------------------------------------


def test_since_returns_the_samples_from_n_on() -> None:
    trace = Trace(1000)
    signal = Signal()
    trace.add_channel("x", signal)
    trace.add_channel("y", lambda: -signal.value)
    fill(trace, range(300), signal)
    first, columns = trace.since(290, ["x"])
    assert first == 290
    assert list(columns) == ["t", "cycle", "x"]
    assert columns["cycle"].tolist() == list(range(290, 300))
    assert columns["x"].tolist() == [c * 1.5 for c in range(290, 300)]
    assert trace.since(300)[1]["y"].tolist() == []  # nothing new yet
    fill(trace, range(300, 303), signal)  # inside a block: flushed by the read
    first, columns = trace.since(300)
    assert (first, columns["y"].tolist()) == (300, [-450.0, -451.5, -453.0])
    columns["x"][:] = 0.0  # a copy, not the live buffer
    assert trace.since(300)[1]["x"].tolist() == [450.0, 451.5, 453.0]


def test_since_starts_at_the_oldest_held_and_keeps_the_newest_limit() -> None:
    trace = Trace(50, mode="ring")
    signal = Signal()
    trace.add_channel("x", signal)
    fill(trace, range(120), signal)
    assert trace.stored == 120
    first, columns = trace.since(10)  # 10..69 were overwritten
    assert first == 70 and columns["cycle"].tolist() == list(range(70, 120))
    first, columns = trace.since(80, limit=5)
    assert first == 115 and columns["cycle"].tolist() == list(range(115, 120))


@pytest.mark.parametrize(("args", "match"), [
    ((-1,), "first sample"),
    ((0, ["nope"]), "unknown channel 'nope'"),
    ((0, None, 0), "limit"),
])
def test_since_refuses_bad_requests(args: tuple, match: str) -> None:
    trace = Trace(5)
    trace.add_channel("x", Signal())
    with pytest.raises(ValueError, match=match):
        trace.since(*args)
