"""`make bench`: sweep throughput, cases per second with 1 and 2 Dask workers, and the
scheduling overhead per case.

    figures = bench_sweep()        # prints a table, returns the figures (a dict)

The sweep is the FS701 envelope example's machine (examples/sweeps/fs701_line.toml) over
4 line speeds x 10 cut lengths (40 cases, about 0.1 s of computing each, feasible and Error 02
cases alike), run into a fresh folder each time (no resume): in this process without Dask
(the reference), then on a LocalCluster of 1 and of 2 worker processes; the checks before the
run (engine.prepare) are made once and timed on their own. The overhead per case is what Dask
adds to a case on 1 worker: (run time - cluster start - the cases' own time) / cases, the
cluster start (with the imports of a worker's first case) measured on its own (the run
time includes writing the tables). Figures, not pass/fail (a shared machine makes
them vary).
"""

from __future__ import annotations

import logging
import tempfile
import time
from pathlib import Path
from typing import Any

__all__ = ["bench_sweep"]

EXAMPLES = Path(__file__).resolve().parents[3] / "examples" / "sweeps"

_SWEEP = """
[sweep]
name = "bench: FS701 line speed x cut length"
base = "{base}"
collect = ["completed", "summary.max_abs_error_counts", "envelope.min_length_lu"]
feasible = ["completed == true"]

[parameters]
"material.profile[0].speed" = [500, 750, 1000, 1250]
"device.parameters.cutting_length" = {{ start = 150, stop = 1500, num = 10, scale = "log", round = 0 }}
"""


def _imports() -> int:
    """What a worker imports for its first case (the machine, the FS701): part of the start."""
    import axisline.devices.fs701.personality  # noqa: F401
    import axisline.machine  # noqa: F401
    import axisline.sweep.worker  # noqa: F401

    return 1


def _cluster_start(n: int) -> float:
    from dask.distributed import Client, LocalCluster

    t0 = time.perf_counter()
    with LocalCluster(n_workers=n, threads_per_worker=1, processes=True, dashboard_address=None,
                      silence_logs=logging.ERROR) as cluster, Client(cluster) as client:
        client.submit(_imports, pure=False).result()
        return time.perf_counter() - t0


def bench_sweep(base: Path | None = None, out: Any = print) -> dict[str, float]:
    from .engine import prepare, run_sweep

    base = base or EXAMPLES / "fs701_line.toml"
    figures: dict[str, float] = {}
    with tempfile.TemporaryDirectory(prefix="axisline-bench-sweep-") as tmp:
        f = Path(tmp) / "bench.toml"
        f.write_text(_SWEEP.format(base=base), encoding="utf-8")
        runs = {}
        t0 = time.perf_counter()
        prepared = prepare(f)  # the checks before anything runs: once, not timed with the runs
        figures["check_s"] = time.perf_counter() - t0
        for label, workers in (("in this process", 0), ("1 worker", 1), ("2 workers", 2)):
            t0 = time.perf_counter()
            outcome = run_sweep(f, Path(tmp) / f"out{workers}", workers=workers, prepared=prepared)
            wall = time.perf_counter() - t0
            own = sum(r.get("wall_s", 0.0) for r in outcome.results)
            runs[label] = (outcome.total, wall, own)
            figures[f"cases_per_s_{workers}"] = outcome.total / wall
        start = _cluster_start(1)
        n, wall1, own1 = runs["1 worker"]
        figures["cluster_start_s"] = start
        figures["overhead_per_case_ms"] = 1e3 * max(wall1 - start - own1, 0.0) / n
    out("sweep (Dask): 40 cases of examples/sweeps/fs701_line.toml, results and report written")
    for label, (n, wall, own) in runs.items():
        out(f"  {label:<16} {n / wall:7.1f} cases/s   ({wall:6.2f} s; the cases' own time {own:6.2f} s)")
    out(f"  checks before the run {figures['check_s']:.2f} s; LocalCluster start and imports (1 worker) {figures['cluster_start_s']:.2f} s; "
        f"scheduling overhead per case {figures['overhead_per_case_ms']:.1f} ms")
    return figures


if __name__ == "__main__":  # pragma: no cover
    bench_sweep()
