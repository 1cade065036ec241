"""Running a sweep: check everything, then the cases on Dask (or in this process), then the tables.

    outcome = run_sweep(sweep_file, out, workers=None, scheduler=None, console=None)

1. The sweep file and its base machine file are read and checked; every parameter key is
   placed in the base and each of its values (all of a short list; first, smallest and largest
   of a long one) is checked by the machine-file model and the personality, as `axisline check`
   does: a bad key or value is a SweepError naming it, before any case runs (exit 2).
2. The journal (journal.py) gives the cases that already have a result; the others run.
3. Engine: `scheduler` = "tcp://host:8786": that Dask cluster; else a Dask LocalCluster of
   `workers` processes (default: this machine's cores) with one thread each (the simulation is
   Python: a process per core); `workers` = 0: in this process, without Dask. The base
   machine's data goes to the workers once (scatter, broadcast); at most IN_FLIGHT_PER_WORKER
   cases per worker wait in the cluster (the worker count looked at every WINDOW_CHECK_S), so
   a sweep of millions of cases needs no memory for millions of futures.
4. Results (results.py, report.py) are written from the journal in case order: the same files
   whatever engine ran the cases, and in whatever order they finished.

Decisions
1. (issue: "a rich progress bar with cases done, failed and the rate") the bar shows on a
   terminal only (as `axisline run`'s); elsewhere one line at the end says the same. Tests:
   test_sweep_run.py::test_progress_bar_on_a_terminal, ::test_cli_exit_codes_and_summary_line.
2. (issue: "a bad key (exit 2 naming the key before anything runs)") a result field in
   `collect` that the run summary does not have is found in the first case that completes:
   the sweep stops there, exit 2 naming the field and the keys that are there. Test:
   test_sweep_run.py::test_unknown_collect_field_stops_the_sweep.
"""

from __future__ import annotations

import logging
import os
import time
import tomllib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable, Iterator

from axisline.configerrors import ConfigError, read_text

from .cases import Case, Grid
from .journal import Journal, is_result
from .keys import KeyPathError, set_key
from .spec import SweepError, SweepFile, base_path, load_sweep_file
from .worker import case_config, run_case

__all__ = ["run_sweep", "SweepOutcome", "prepare", "Prepared", "IN_FLIGHT_PER_WORKER"]

IN_FLIGHT_PER_WORKER = 8
#: seconds between looks at the cluster's worker count (an adaptive cluster grows and shrinks)
WINDOW_CHECK_S = 5.0


@dataclass
class Prepared:
    spec: SweepFile
    sweep_file: Path
    base_file: Path
    base: dict[str, Any]
    grid: Grid
    explicit_duration: float | None  # passed to Machine.run (None: the file's, as `axisline run`)

    def options(self) -> dict[str, Any]:
        s = self.spec.sweep
        return {"duration": self.explicit_duration, "collect": list(s.collect), "stop_on_fault": s.stop_on_fault}


@dataclass
class SweepOutcome:
    total: int
    ran: int
    skipped: int
    ok: int
    fault: int
    failed: int
    wall_s: float
    results: list[dict[str, Any]] = field(default_factory=list)  # in case order
    files: list[Path] = field(default_factory=list)


def prepare(sweep_file: Path) -> Prepared:
    """Read and check the sweep file, the base machine file and every parameter (step 1)."""
    from axisline.config import load_machine_file

    spec = load_sweep_file(sweep_file)
    base_file = base_path(spec, sweep_file)
    try:
        base_config = load_machine_file(base_file)
        text = read_text(base_file, 1 << 20)
    except ConfigError as e:
        raise SweepError(str(sweep_file), [f"sweep.base = {spec.sweep.base!r}: {p}" for p in e.problems]) from None
    except ValueError as e:
        raise SweepError(str(sweep_file), [f"sweep.base = {spec.sweep.base!r}: {e}"]) from None
    base = tomllib.loads(text)
    try:
        grid = Grid(spec, text, base_config.machine.duration)
    except ValueError as e:  # a value twice in a parameter
        raise SweepError(str(sweep_file), [str(e)]) from None
    problems: list[str] = []
    source = str(base_file)
    for key, values in grid.check_values().items():
        try:
            set_key(_copy(base), key, values[0])
        except KeyPathError as e:
            problems.append(f"parameters.{key!r}: {str(e).removeprefix(key + ': ')}")
            continue
        for v in values:  # this key alone on the base: a problem is this key's
            why = _refusal(base, source, [(key, v)], None)
            if why:
                problems += [f"parameters.{key!r} = {v!r}: {p}" for p in why]
                break  # one value says it; the others of this key would repeat it
    if not problems:  # together (a per-case seed too): the first case
        first = next(grid.cases())
        shown = ", ".join(f"{k} = {v!r}" for k, v in first.overrides)
        problems += [f"the first case ({shown}): {p}" for p in _refusal(base, source, first.overrides, first.seed)]
    if problems:
        raise SweepError(str(sweep_file), problems)
    return Prepared(spec, Path(sweep_file), base_file, base, grid, spec.sweep.duration)


def _refusal(base: dict[str, Any], source: str, overrides: Any, seed: int | None) -> list[str]:
    """Why a machine with these values cannot be built ([]: it can), as `axisline check` says it."""
    from axisline.machine import Machine

    try:
        Machine(case_config(base, source, overrides, seed), source=source)
    except ConfigError as e:
        return list(e.problems)
    except Exception as e:  # noqa: BLE001 - a personality's own refusal, named rather than a traceback
        return [f"{type(e).__name__}: {e}"]
    return []


def _copy(d: dict[str, Any]) -> dict[str, Any]:
    import copy

    return copy.deepcopy(d)


class _Progress:
    """The rich bar (on a terminal) with done, failed and the rate (decision 1)."""

    def __init__(self, console: Any, total: int, skipped: int) -> None:
        self.console = console
        self.total, self.done, self.failed, self.faults = total, skipped, 0, 0
        self.skipped = skipped
        self.t0 = time.monotonic()
        self.bar = None
        if console is not None and console.is_terminal:
            from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn, TimeRemainingColumn

            self.bar = Progress(TextColumn("[bold]sweep"), BarColumn(), MofNCompleteColumn(),
                                TextColumn("failed [red]{task.fields[failed]}[/red]"), TextColumn("fault {task.fields[faults]}"),
                                TextColumn("{task.fields[rate]} cases/s"), TimeElapsedColumn(), TimeRemainingColumn(),
                                console=console, transient=False)
            self.bar.start()
            self.task = self.bar.add_task("sweep", total=total, completed=skipped, failed=0, faults=0, rate="-")

    def rate(self) -> float:
        dt = time.monotonic() - self.t0
        return (self.done - self.skipped) / dt if dt > 0 else 0.0

    def update(self, status: str) -> None:
        self.done += 1
        self.failed += status == "failed"
        self.faults += status == "fault"
        if self.bar is not None:
            self.bar.update(self.task, completed=self.done, failed=self.failed, faults=self.faults, rate=f"{self.rate():.1f}")

    def close(self) -> None:
        if self.bar is not None:
            self.bar.stop()


def _check_fields(result: dict[str, Any], spec: SweepFile, sweep_file: Path) -> None:
    if result.get("status") == "ok" and result.get("unknown"):
        problems = [f"sweep.collect: {f!r} is not in the run summary ({why})" for f, why in result["unknown"].items()]
        raise SweepError(str(sweep_file), problems)


def _local(prep: Prepared, todo: list[Case]) -> Iterator[dict[str, Any]]:
    options = prep.options()
    for case in todo:
        yield run_case(prep.base, str(prep.base_file), case.index, case.key, case.overrides, case.seed, options)


def _client(workers: int | None, scheduler: str | None, processes: bool):
    from dask.distributed import Client, LocalCluster

    if scheduler is not None:
        return Client(scheduler, timeout="10s"), None
    n = workers if workers is not None else (len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count() or 1)
    cluster = LocalCluster(n_workers=n, threads_per_worker=1, processes=processes, dashboard_address=None,
                           silence_logs=logging.ERROR)
    return Client(cluster), cluster


def _dask(prep: Prepared, todo: list[Case], workers: int | None, scheduler: str | None, processes: bool) -> Iterator[dict[str, Any]]:
    from dask.distributed import as_completed

    client, cluster = _client(workers, scheduler, processes)
    try:
        def window() -> int:  # cases waiting in the cluster: a few per worker, workers that join included
            return IN_FLIGHT_PER_WORKER * max(1, len(client.nthreads()))

        size, sized = window(), time.monotonic()
        base = client.scatter(prep.base, broadcast=True)
        options = prep.options()
        source = str(prep.base_file)
        pending = iter(todo)
        by_future: dict[Any, Case] = {}

        def submit() -> Any | None:
            case = next(pending, None)
            if case is None:
                return None
            fut = client.submit(run_case, base, source, case.index, case.key, case.overrides, case.seed,
                                options, key=f"axisline-case-{case.key}", pure=False, retries=0)
            by_future[fut] = case
            return fut

        first = [f for f in (submit() for _ in range(size)) if f is not None]
        queue = as_completed(first)
        for fut in queue:
            case = by_future.pop(fut)
            try:
                result = fut.result()
            except Exception as e:  # noqa: BLE001 - the worker died or the task could not run
                result = {"case": case.index, "key": case.key, "status": "failed", "values": {}, "tables": {}, "unknown": {},
                          "error": f"{type(e).__name__}: {e}"[:500]}
            if time.monotonic() - sized > WINDOW_CHECK_S:
                size, sized = window(), time.monotonic()
            while len(by_future) < size:
                nxt = submit()
                if nxt is None:
                    break
                queue.add(nxt)
            yield result
    finally:
        client.close()
        if cluster is not None:
            cluster.close()


def run_sweep(sweep_file: Path, out: Path, workers: int | None = None, scheduler: str | None = None,
              console: Any = None, processes: bool = True, prepared: Prepared | None = None,
              on_result: Callable[[dict[str, Any]], None] | None = None) -> SweepOutcome:
    """Run (or resume) a sweep into `out`; SweepError (exit 2) before anything runs."""
    from .report import write_outputs

    t0 = time.monotonic()
    prep = prepared or prepare(sweep_file)
    spec = prep.spec
    journal = Journal(out)
    stored = journal.load()
    cases = list(prep.grid.cases())
    done = {c.key for c in cases if c.key in stored and is_result(stored[c.key], spec.sweep.collect)}
    todo = [c for c in cases if c.key not in done]
    progress = _Progress(console, len(cases), len(cases) - len(todo))
    checked = False
    try:
        if todo:
            results = _local(prep, todo) if workers == 0 and scheduler is None else _dask(prep, todo, workers, scheduler, processes)
            try:
                for r in results:
                    if not checked and r.get("status") == "ok":
                        _check_fields(r, spec, prep.sweep_file)
                        checked = True
                    stored[r["key"]] = r
                    journal.add(r)
                    progress.update(r["status"])
                    if on_result is not None:
                        on_result(r)
            finally:
                close = getattr(results, "close", None)
                if close is not None:
                    close()
    finally:
        journal.flush()
        progress.close()
    journal.compact()
    ordered = [stored[c.key] for c in cases]
    counts = {s: sum(1 for r in ordered if r.get("status") == s) for s in ("ok", "fault", "failed")}
    outcome = SweepOutcome(len(cases), len(todo), len(cases) - len(todo), counts["ok"], counts["fault"], counts["failed"],
                           time.monotonic() - t0, ordered)
    outcome.files = write_outputs(prep, cases, ordered, out)
    return outcome
