"""`make bench`: the cost of a CANopen axis per cycle, and how many fit in a 1 ms cycle.

Each axis is a CiA 402 drive in CSP on python-can's virtual bus with a simulated drive behind
it, all in this process: the figure is the controller's work (RPDOs, SYNC, waiting for and
decoding the TPDOs, the axis) plus the simulated drives' (their receive threads, the servo
model). A real bus moves the drives' work out of the process and adds the wire time, which
is printed beside it: the frames of one axis per cycle at the bus' bit rate.

Timings are printed, never asserted. bench/run.py calls `bench_cia402()`.

Decisions (issue point -> choice, why):

1. Issue 18 "every example in examples/ at >= 100x real time" against issue 20's
   `examples/positioning_cia402.toml` -> that example is bus-bound and outside the bar; the
   examples table (bench/bench_examples.py) prints it with its figure, marked "bus-bound". It
   exists to run the real protocol path: every cycle's SYNC, RPDOs and TPDOs go through
   canopen and python-can's virtual bus to a simulated drive answering in its own threads
   (about 125 us a cycle, 8x real time). On a real bus the same machine runs at real time by
   definition (the drive is real), and the embedded-plant twin of the same line,
   examples/positioning.toml, is in the bar (260x). Test: the bench table marks it.
"""

from __future__ import annotations

import statistics
import time

__all__ = ["bench_cia402", "wire_us_per_axis"]

# CAN 2.0A data frame: 47 bits of frame around 8 bits per data byte; bit stuffing adds up to
# one bit in five of the 34 + 8n stuffed bits (worst case)
_FRAME_BITS = 47


def _frame_bits(data_bytes: int) -> float:
    return _FRAME_BITS + 8 * data_bytes + (34 + 8 * data_bytes - 1) / 4


def wire_us_per_axis(bitrate: int = 1_000_000) -> float:
    """Bus time of one CSP axis per cycle with the generic EDS' PDOs (RPDO 7 + 8, TPDO 7 + 8 bytes), us."""
    return sum(_frame_bits(n) for n in (7, 8, 7, 8)) / bitrate * 1e6


def _machine(n_axes: int, channel: str):
    from ..config import parse_machine
    from ..machine import Machine

    axes, steps = [], []
    for i in range(n_axes):
        name = f"a{i}"
        axes.append({
            "name": name, "unit": "mm", "counts_per_unit": 2000.0, "v_max": 500.0, "a_max": 5000.0,
            "d_max": 5000.0, "j_max": 100000.0, "shape": "jerk", "kv": 40.0, "following_error_limit": 5.0,
            "drive": {"type": "cia402", "interface": "virtual", "channel": channel, "node_id": i + 1,
                      "simulated": {"time_constant": 0.002}},
            "encoder": {"lines_per_unit": 500.0, "multiplier": 4},
        })
        steps.append({"axis": name, "command": "power", "on": True})
    for i in range(n_axes):
        steps.append({"axis": f"a{i}", "command": "move_absolute", "position": 1000.0 + 10 * i, "wait": "none"})
    steps.append({"dwell": 30.0})
    data = {
        "machine": {"name": "bench cia402", "cycle_us": 1000, "duration": 60.0},
        "axis": axes, "job": {"steps": steps}, "trace": {"enabled": False},
    }
    return Machine(parse_machine(data, "bench"))


def cycle_cost_us(n_axes: int, cycles: int = 1000) -> float:
    """Median cost of one machine cycle with `n_axes` CANopen axes in a move, us."""
    from . import close_drives

    m = _machine(n_axes, f"bench-{n_axes}-{time.monotonic_ns()}")
    try:
        m.scheduler.run(20)  # powered, moving
        costs = []
        for _ in range(cycles):
            t0 = time.perf_counter_ns()
            m.scheduler.run_cycle()
            costs.append(time.perf_counter_ns() - t0)
    finally:
        close_drives(m)
    return statistics.median(costs) / 1e3


def bench_cia402(counts: tuple[int, ...] = (1, 2, 4, 8), cycles: int = 1000) -> dict[str, float]:
    """Print and return: us per cycle of one axis, of n axes, and how many fit in 1 ms (measured)."""
    print("cia402: CANopen axes in CSP on the virtual bus (simulated drives in the same process)")
    costs = {n: cycle_cost_us(n, cycles) for n in counts}
    for n, c in costs.items():
        print(f"  {n} {'axes' if n > 1 else 'axis'}: median {c:8.1f} us per cycle")
    fit = max((n for n, c in costs.items() if c <= 1000.0), default=0)
    wire = wire_us_per_axis()
    lean = sum(_frame_bits(n) for n in (6, 6))  # controlword + target, statusword + position: us at 1 Mbit/s
    sync = _frame_bits(0)
    print(f"  one CANopen axis: {costs[counts[0]]:.1f} us per cycle; axes measured to fit in a 1 ms cycle here: {fit}")
    print(f"  on a 1 Mbit/s wire: {wire:.0f} us of bus time per axis with the generic EDS' four PDOs "
          f"({int((1000.0 - sync) // wire)} axis per 1 ms), {lean:.0f} us with two 6-byte PDOs ({int((1000.0 - sync) // lean)} axes)")
    return {"one_axis_us": costs[counts[0]], "axes_per_ms": float(fit), "wire_us_per_axis": wire}


if __name__ == "__main__":
    bench_cia402()
