"""Flying shear line (examples/flying_shear.toml, FS701 personality) against real time at T = 1 ms.

The machine is built (the FS701's Adjust program commissions the carriage in the constructor),
the batch is started and the line brought up to speed; then only the running line is timed:
cutting 1 m pieces at 60/48 m/min, scope on and off. Reference: real time (1.0).

Cut accuracy (issue 4's quality bars, deterministic figures): the three FS701 examples run to
the end of their batch; per run the largest length error of pieces whose two cuts fell at one
constant line speed, of the other pieces (a cut during a speed change), and of the cuts to
their print marks, in carriage increments; the ramps example also with the FS701's own loop
(acceleration_feed_forward = 0) for comparison.
"""

from __future__ import annotations

import statistics
import time
from pathlib import Path

from axisline.config import load_machine_file, parse_machine
from axisline.machine import Machine

EXAMPLE = Path(__file__).resolve().parent.parent / "examples" / "flying_shear.toml"
WARMUP = 2.0      # s simulated before timing: Control Enable, Start, line at speed, first cuts
TIMED = 10.0      # s simulated and timed (the line runs 2..12 s: speed change at 9 s included)


def _machine(trace: bool) -> Machine:
    config = load_machine_file(EXAMPLE)
    data = config.model_dump()
    data["trace"]["enabled"] = trace
    return Machine(parse_machine(data, str(EXAMPLE)), source=str(EXAMPLE))


def _running(trace: bool) -> Machine:
    m = _machine(trace)  # commissioning done in the constructor
    m.scheduler.run(round(WARMUP / m.period))
    return m


def bytecodes_per_cycle(cycles: int = 1000) -> float:
    """Python bytecode instructions the running line executes per cycle (every task, scope off),
    counted with sys.settrace over one cut period: a cost figure that, unlike the wall clock,
    is the same on every machine and every run (C calls such as math.floor count as one)."""
    from bench_examples import count_bytecodes

    return count_bytecodes(_running(False), cycles)


def bench_fs701(runs: int = 5) -> None:
    print("fs701: flying shear line (examples/flying_shear.toml), running line after commissioning, T = 1 ms")
    for trace in (False, True):
        factors = []
        costs = []
        for _ in range(runs):
            m = _running(trace)
            n = round(TIMED / m.period)
            s = m.scheduler
            t0 = time.perf_counter()
            s.run(n)
            wall = time.perf_counter() - t0
            factors.append(TIMED / wall)
            costs.append(wall / n * 1e6)
        print(f"  scope {'on ' if trace else 'off'}: {statistics.median(factors):7.1f}x real time, "
              f"{statistics.median(costs):6.1f} us per cycle "
              f"(median of {runs} runs of {TIMED:g} s simulated; min {min(factors):.1f}x, max {max(factors):.1f}x)")
    print(f"  Python bytecodes per cycle (deterministic, scope off): {bytecodes_per_cycle():.0f}")


_RAMPS = EXAMPLE.parent / "flying_shear_ramps.toml"
# the print-mark example on the ramps example's line, with its feed-forward and Sampling Time
_MARKS_ON_RAMPS = {
    "material": "ramps",
    "device": {"acceleration_feed_forward": "auto", "batch": 30, "tolerance_fault": False},
    "device.parameters": {"sampling_time": 8},
    "machine": {"duration": 45.0},
}
ACCURACY_RUNS = (
    ("flying_shear.toml", {}, "0.25 m/s² ramps, FS701 loop"),
    ("flying_shear_printmark.toml", {}, "print marks, FS701 loop"),
    ("flying_shear_ramps.toml", {}, "1 m/s² ramps, acceleration feed-forward"),
    ("flying_shear_ramps.toml", {"device": {"acceleration_feed_forward": 0.0, "tolerance_fault": False}}, "1 m/s² ramps, FS701 loop"),
    ("flying_shear_printmark.toml", _MARKS_ON_RAMPS, "print marks, 1 m/s² ramps, feed-forward"),
)


def accuracy_machine(name: str, patch: dict) -> Machine:
    """An example with `patch`: {"table": {key: value}} merged in ("device.parameters" for the
    nested table; "material": "ramps" takes the ramps example's strip)."""
    path = EXAMPLE.parent / name
    data = load_machine_file(path).model_dump()
    data["trace"]["enabled"] = False
    for table, values in patch.items():
        if values == "ramps":
            data[table] = load_machine_file(_RAMPS).model_dump()[table]
            continue
        target = data
        for part in table.split("."):
            target = target[part]
        target.update(values)
    return Machine(parse_machine(data, str(path)), source=str(path))


def _worst(values: list[float]) -> str:
    return f"{max(map(abs, values)):5.2f}" if values else "    -"


def cut_accuracy() -> None:
    print("fs701 cut accuracy, carriage increments (max |error|; deterministic):")
    print("  example                       line                                      constant  ramps  marks")
    for name, patch, what in ACCURACY_RUNS:
        m = accuracy_machine(name, patch)
        m.run()
        cuts = m.device.cuts
        constant = [c.error_counts for c in cuts if c.error_counts is not None and c.constant_speed]
        ramps = [c.error_counts for c in cuts if c.error_counts is not None and not c.constant_speed]
        marks = [c.mark_offset_counts for c in cuts if c.mark_offset_counts is not None]
        print(f"  {name:29s} {what:41s} {_worst(constant)}    {_worst(ramps)}  {_worst(marks)}")


if __name__ == "__main__":
    bench_fs701()
    cut_accuracy()
