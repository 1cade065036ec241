"""`axisline sweep SWEEP.toml [--out DIR] [--workers N] [--scheduler tcp://HOST:8786]`: the command body.

Exit codes: 0 every case ran (a case that ended on a runtime fault, e.g. an infeasible cut,
is a result); 1 some cases failed (their errors are in results.csv and report.md; a re-run
runs them again) or the sweep was interrupted (a re-run resumes); 2 a bad sweep file, base
machine file, parameter key or value, option, or an unreachable scheduler: before any case runs.

The lead registers it in cli.py (`app.command("sweep")(sweep)`); the defaults below are the
typer options.

Decisions
1. (issue: "--workers N", "--scheduler") `--workers 0` runs the cases in this process without
   Dask (for a debugger, and the reference the Dask runs are compared with); `--workers` with
   `--scheduler` is refused (exit 2): the cluster's own workers run the cases. Test:
   test_sweep_run.py::test_cli_exit_codes_and_summary_line.
2. (issue: the sweep command) the default output folder is out/sweeps/<sweep file stem> in the
   working directory, as `make demo` writes to out/. Test: test_sweep_run.py::test_default_out_folder.
"""

from __future__ import annotations

import re
from pathlib import Path
from typing import Optional

import typer
from rich.console import Console
from rich.markup import escape

__all__ = ["sweep", "MAX_WORKERS"]

MAX_WORKERS = 1024
_ADDRESS = re.compile(r"^(tcp|tls|ucx|inproc)://\S+$")


def _refuse(console: Console, option: str, value: object, why: str) -> typer.Exit:
    console.print(f"[red]{option}[/red] = {escape(repr(value))}: {escape(why)}", highlight=False)
    return typer.Exit(2)


def sweep(
    sweep_file: Path = typer.Argument(..., help="sweep file (TOML): base machine file, [parameters], collect, feasible, [report]"),
    out: Optional[Path] = typer.Option(None, "--out", help="results folder (default: out/sweeps/<sweep file name>); a re-run into it resumes"),
    workers: Optional[int] = typer.Option(None, "--workers", help="Dask LocalCluster worker processes (default: this machine's cores; 0: in this process, without Dask)"),
    scheduler: Optional[str] = typer.Option(None, "--scheduler", help="an existing Dask cluster's scheduler, tcp://HOST:8786 (its workers need axisline and the files the machine file names)"),
) -> None:
    """Run a machine over a grid of parameters (Dask): results.csv/.parquet, report.md, plots."""
    from axisline.kernel.atomic import unwritable_reason

    from .engine import prepare, run_sweep
    from .spec import SweepError

    console = Console(stderr=True)
    stdout = Console()
    if workers is not None and not 0 <= workers <= MAX_WORKERS:
        raise _refuse(console, "--workers", workers, f"allowed: 0 .. {MAX_WORKERS} (0: in this process)")
    if scheduler is not None:
        if workers is not None:
            raise _refuse(console, "--workers", workers, "not with --scheduler: the cluster's own workers run the cases")
        if not _ADDRESS.match(scheduler):
            raise _refuse(console, "--scheduler", scheduler, "expected a Dask scheduler address such as tcp://HOST:8786")
    out = out if out is not None else Path("out") / "sweeps" / sweep_file.stem
    reason = unwritable_reason(out / "report.md")
    if reason is not None:
        raise _refuse(console, "--out", str(out), f"cannot be written ({reason})")
    try:
        prepared = prepare(sweep_file)
    except SweepError as e:
        console.print(f"[red]bad sweep file[/red] {escape(e.source)}:", highlight=False)
        for p in e.problems:
            console.print(f"  - {p}", markup=False, highlight=False, soft_wrap=True)
        raise typer.Exit(2) from None
    try:
        outcome = run_sweep(sweep_file, out, workers=workers, scheduler=scheduler, console=console, prepared=prepared)
    except SweepError as e:
        console.print(f"[red]sweep stopped[/red] {escape(e.source)}:", highlight=False)
        for p in e.problems:
            console.print(f"  - {p}", markup=False, highlight=False, soft_wrap=True)
        raise typer.Exit(2) from None
    except KeyboardInterrupt:
        console.print(f"interrupted: the finished cases are kept in {escape(str(out / 'journal'))}; run the same command to resume")
        raise typer.Exit(1) from None
    except OSError as e:  # an unreachable scheduler, a full disk
        if scheduler is not None and outcome_missing(e):
            raise _refuse(console, "--scheduler", scheduler, f"cannot reach the Dask scheduler ({e}); the finished cases "
                          f"are kept in {out / 'journal'}") from None
        console.print(f"[red]sweep failed[/red]: {escape(str(e))}; the finished cases are kept in {escape(str(out / 'journal'))}",
                      highlight=False)
        raise typer.Exit(1) from None
    rate = outcome.ran / outcome.wall_s if outcome.wall_s > 0 else 0.0
    stdout.print(
        f"sweep {prepared.spec.sweep.name}: {outcome.total} cases ({outcome.ok} completed, {outcome.fault} fault, "
        f"{outcome.failed} failed); ran {outcome.ran}, {outcome.skipped} already done; {outcome.wall_s:.1f} s, {rate:.1f} cases/s",
        markup=False, highlight=False, soft_wrap=True)
    for f in outcome.files:
        stdout.print(str(f), markup=False, highlight=False, soft_wrap=True)
    raise typer.Exit(1 if outcome.failed else 0)


def outcome_missing(e: OSError) -> bool:
    """A connection error (the scheduler is not there) rather than a failure during the run."""
    return isinstance(e, (ConnectionError, TimeoutError)) or "connect" in str(e).lower() or "timed out" in str(e).lower()
