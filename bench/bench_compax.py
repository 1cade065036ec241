"""COMPAX cam slave: one cycle with a 2500-point curve, with and without label correction."""

from __future__ import annotations

import statistics
import tempfile
import time
from pathlib import Path

from axisline.machine import Machine

EXAMPLE = Path(__file__).resolve().parent.parent / "examples" / "cam_packaging.toml"


def _machine(label: bool) -> Machine:
    text = EXAMPLE.read_text(encoding="utf-8").replace("points = 301 ", "points = 2500 ")
    if not label:
        text = text.replace("P33 = 1,", "P33 = 0,")
    text = text.replace("decimation = 2", "enabled = false")  # the scope is measured elsewhere
    tmp = Path(tempfile.mkdtemp()) / "cam_packaging.toml"
    tmp.write_text(text, encoding="utf-8")
    (tmp.parent / "curves").mkdir()
    (tmp.parent / "curves" / "sealing_jaw.csv").write_text(
        (EXAMPLE.parent / "curves" / "sealing_jaw.csv").read_text(encoding="utf-8"), encoding="utf-8")
    return Machine.from_file(tmp)


def bench_compax() -> None:
    print("compax: cam slave on a 2500-point curve (whole machine cycle: plant, wheel master, cam, loop)")
    for label in (False, True):
        m = _machine(label)
        m.scheduler.run(2000)  # coupled, labels seen: steady operation
        costs = []
        for _ in range(3000):
            t0 = time.perf_counter_ns()
            m.scheduler.run_cycle()
            costs.append(time.perf_counter_ns() - t0)
        med = statistics.median(costs) / 1e3
        what = "with label correction   " if label else "without label correction"
        print(f"  {what} {med:7.1f} us per cycle   ({1000.0 / med:6.1f}x real time at T = 1 ms)")
