"""Sweeps: many simulations of one machine over parameter grids, on Dask (issue 21).

    axisline sweep SWEEP.toml [--out DIR] [--workers N] [--scheduler tcp://HOST:8786]

    spec.py      the sweep file (pydantic): base machine, parameters, collect, feasible, report
    keys.py      dotted machine-file keys (axis.carriage.kv, material.profile[0].speed) into the data
    cases.py     the grid: values of each parameter, cases with keys and seeds
    worker.py    one case: config, run, the collected fields (what a Dask worker runs)
    fs701.py     fields computed beside a run (the FS701's cut envelope)
    journal.py   results as they come, for resume
    engine.py    checks before anything runs, Dask LocalCluster / a cluster / this process, progress
    results.py   results.csv / .parquet and the per-row tables (cuts.csv)
    report.py    report.md, heatmap.png, line.png, the simulated vs computed boundary
    cli.py       the `axisline sweep` command body
    bench.py     cases/s with 1 and 2 workers, scheduling overhead per case

docs/sweep.md is the user's guide.
"""

from .engine import SweepOutcome, prepare, run_sweep
from .spec import SweepError, SweepFile, load_sweep_file

__all__ = ["SweepOutcome", "SweepError", "SweepFile", "load_sweep_file", "prepare", "run_sweep"]
