"""CLM1.4: every CLM example at its NC cycle (reference: real time)."""

from __future__ import annotations

import time
from pathlib import Path

from axisline.machine import Machine

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


def _best_of_three(path: Path) -> tuple[float, object, Machine]:
    runs = []
    for _ in range(3):  # the best of three: the machine is shared with whatever else runs
        m = Machine.from_file(path)
        t0 = time.perf_counter()
        result = m.run()
        runs.append((time.perf_counter() - t0, result, m))
    return min(runs, key=lambda r: r[0])


def bench_clm() -> None:
    print("clm: every CLM example (NC tasks, Logic Task, axis loop, plant) at its B010 NC cycle")
    for path in sorted(EXAMPLES.glob("*_clm.toml")):
        wall, result, m = _best_of_three(path)
        print(f"  {path.stem:24s} {result.cycles:6d} cycles of {m.period * 1e3:g} ms: "  # type: ignore[attr-defined]
              f"{result.simulated_s / wall:6.1f}x real time ({wall / result.cycles * 1e6:5.1f} us per cycle)")  # type: ignore[attr-defined]


if __name__ == "__main__":
    bench_clm()
