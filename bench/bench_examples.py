"""Every example machine in examples/ (issue 18's table): microseconds per cycle, the real-time
factor at the example's own cycle period, and the Python bytecodes per cycle.

Each example runs its whole job (`Machine.run`, as `axisline run` does, with the scope channels
its file asks for), best of three runs: the wall clock is shared with whatever else the machine
runs. The bytecode count (sys.settrace, opcode events, over the first 1000 cycles of a fresh
machine) is deterministic: the same on every computer and every run, so it shows a change of
cost that the timings' noise would hide. C calls (numpy, math) count as one instruction.

Bar (issue 18): every example >= 100x real time, but for the bus-bound ones: a machine with a
CiA 402 drive runs its SYNC and PDOs through python-can's virtual bus to a simulated drive in
threads (drives/bench.py, decision 1); it is printed, marked, and not held to the bar.
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

from axisline.machine import Machine

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
BAR = 100.0


def example_files() -> list[Path]:
    return sorted(EXAMPLES.glob("*.toml"))


def _close(m: Machine) -> None:
    if any(a.drive.type == "cia402" for a in m.config.axis):
        from axisline.drives import close_drives

        close_drives(m)


def count_bytecodes(m: Machine, cycles: int) -> float:
    """Python bytecode instructions per cycle over `cycles` cycles of `m` (sys.settrace)."""
    count = 0

    def tracer(frame, event, arg):  # noqa: ANN001 - sys.settrace signature
        nonlocal count
        if event == "call":
            frame.f_trace_opcodes = True
        elif event == "opcode":
            count += 1
        return tracer

    sys.settrace(tracer)
    try:
        m.scheduler.run(cycles)
    finally:
        sys.settrace(None)
    return count / cycles


def bytecodes_per_cycle(path: Path, cycles: int = 1000) -> float:
    m = Machine.from_file(path)
    try:
        return count_bytecodes(m, cycles)
    finally:
        _close(m)


def timed(path: Path, runs: int = 3) -> tuple[float, float, int]:
    """(us per cycle, real-time factor, cycles) of the best of `runs` whole runs."""
    best = None
    for _ in range(runs):
        m = Machine.from_file(path)
        t0 = time.perf_counter()
        result = m.run()
        wall = time.perf_counter() - t0
        _close(m)
        if best is None or wall < best[0]:
            best = (wall, result.cycles, result.simulated_s)
    wall, cycles, simulated = best
    return wall / cycles * 1e6, simulated / wall, cycles


def bench_examples(only: list[str] | None = None) -> None:
    print(f"examples: every machine in examples/ running its job with its scope (best of 3 runs; bar >= {BAR:g}x real time)")
    print(f"  {'example':28s} {'cycle':>7s} {'us/cycle':>9s} {'real time':>10s} {'bytecodes/cycle':>16s}")
    below = []
    for path in example_files():
        if only and path.stem not in only:
            continue
        try:
            us, factor, cycles = timed(path)
            codes = bytecodes_per_cycle(path)
        except Exception as e:  # an example that cannot run here (a CAN bus the machine lacks): say so
            print(f"  {path.stem:28s} not run: {type(e).__name__}: {e}")
            continue
        m = Machine.from_file(path)
        period_ms = m.period * 1e3
        bus_bound = any(a.drive.type == "cia402" for a in m.config.axis)
        _close(m)
        mark = "  bus-bound (CANopen virtual bus; not held to the bar)" if bus_bound else "" if factor >= BAR else "  < bar"
        if factor < BAR and not bus_bound:
            below.append(path.stem)
        print(f"  {path.stem:28s} {period_ms:5g} ms {us:9.1f} {factor:9.1f}x {codes:16.0f}{mark}")
    print(f"  below {BAR:g}x: {', '.join(below) if below else 'none'}")


if __name__ == "__main__":
    bench_examples(sys.argv[1:] or None)
