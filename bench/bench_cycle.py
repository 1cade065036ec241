"""Cycle cost: one axis in a move, and a 4-axis machine against real time at T = 1 ms; the
scope's cost per axis and a 16-axis machine with it (issue 18). `python bench/bench_cycle.py
scope` runs the scope part alone."""

from __future__ import annotations

import statistics
import time

from axisline.config import parse_machine
from axisline.machine import Machine


def _machine(n_axes: int, trace: bool, mode: str = "linear", capacity: int = 70000) -> Machine:
    axes = []
    steps = []
    for i in range(n_axes):
        name = f"a{i}"
        axes.append({
            "name": name, "unit": "mm", "counts_per_unit": 2000.0, "v_max": 500.0, "a_max": 5000.0,
            "d_max": 5000.0, "j_max": 100000.0, "shape": "jerk", "kv": 40.0, "following_error_limit": 5.0,
            "drive": {"type": "servo", "time_constant": 0.002},
            "encoder": {"lines_per_unit": 500.0, "multiplier": 4},
        })
        steps.append({"axis": name, "command": "power", "on": True})
    for i in range(n_axes):
        steps.append({"axis": f"a{i}", "command": "move_absolute", "position": 1000.0 + 10 * i, "wait": "none"})
    steps.append({"dwell": 30.0})
    data = {
        "machine": {"name": "bench", "cycle_us": 1000, "duration": 60.0},
        "axis": axes,
        "job": {"steps": steps},
        "trace": {"enabled": trace, "capacity": capacity, "mode": mode},
    }
    return Machine(parse_machine(data, "bench"))


def bench_cycle() -> None:
    # one axis in a move: median cost of a cycle (all stages, plant included)
    m = _machine(1, trace=False)
    m.scheduler.run(20)  # power on, move started
    costs = []
    for _ in range(2000):
        t0 = time.perf_counter_ns()
        m.scheduler.run_cycle()
        costs.append(time.perf_counter_ns() - t0)
    med = statistics.median(costs) / 1e3
    print("cycle: one axis in a move (servo + encoder + position loop, all stages)")
    print(f"  cost of one cycle, median {med:8.1f} us   ({1000.0 / med:6.1f} cycles per 1 ms period)")

    # 4 axes at T = 1 ms: simulated seconds per wall-clock second (reference: real time = 1.0)
    # the reference is real time: simulated seconds per wall-clock second (median of 5 runs)
    for trace in (False, True):
        factors = []
        for _ in range(5):
            m = _machine(4, trace=trace)
            sim = 10.0
            t0 = time.perf_counter()
            m.scheduler.run(round(sim / m.period))
            factors.append(sim / (time.perf_counter() - t0))
        print(f"  4 axes, T = 1 ms, scope {'on ' if trace else 'off'}: {statistics.median(factors):7.1f}x real time "
              f"(median of 5 runs of 10 s simulated; min {min(factors):.1f}x, max {max(factors):.1f}x)")
    bench_scope()


def _scope_record_us(n_axes: int, samples: int = 20000) -> float:
    """Cost of the scope alone: microseconds per `Trace.record` of an n-axis machine (11
    channels per axis), the block copies into the columns included (a ring never stops)."""
    m = _machine(n_axes, trace=True, mode="ring", capacity=4096)  # a ring never stops recording
    m.scheduler.run(20)  # power on, moves started: the values the scope reads are live ones
    assert m.trace is not None
    record = m.trace.record
    t0 = time.perf_counter_ns()
    for cycle in range(samples):
        record(cycle)
    return (time.perf_counter_ns() - t0) / 1e3 / samples


def bench_scope() -> None:
    # bar (issue 18): <= 0.5 us per axis per cycle with 11 channels; 16 axes, scope on, >= 100x
    per_axis = [_scope_record_us(16) / 16 for _ in range(5)]
    n_channels = len(_machine(1, trace=True).trace.channels)
    print(f"scope: {n_channels} channels per axis, 16 axes (bar <= 0.5 us per axis per cycle)")
    print(f"  cost per axis per cycle, median {statistics.median(per_axis):6.3f} us "
          f"(of 5 runs of 20000 samples; min {min(per_axis):.3f}, max {max(per_axis):.3f})")
    factors: dict[bool, list[float]] = {False: [], True: []}
    for _ in range(3):  # interleaved: both see the same load of the machine
        for trace in (False, True):
            m = _machine(16, trace=trace)
            sim = 5.0
            t0 = time.perf_counter()
            m.scheduler.run(round(sim / m.period))
            factors[trace].append(sim / (time.perf_counter() - t0))
    for trace in (False, True):
        print(f"  16 axes, T = 1 ms, scope {'on ' if trace else 'off'}: {statistics.median(factors[trace]):7.1f}x real time "
              f"(median of 3 runs of 5 s simulated; bar >= 100x with the scope on)")


if __name__ == "__main__":
    import sys

    if sys.argv[1:] == ["scope"]:
        bench_scope()
    else:
        bench_cycle()
