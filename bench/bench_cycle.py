"""Cycle cost: one axis in a move, and a 4-axis machine against real time at T = 1 ms."""

from __future__ import annotations

import statistics
import time

from axisline.config import parse_machine
from axisline.machine import Machine


def _machine(n_axes: int, trace: bool) -> Machine:
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
        "trace": {"enabled": trace, "capacity": 70000},
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
