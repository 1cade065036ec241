"""One case: the base machine with the case's values, run as `axisline run` runs it, and the
collected fields of its summary. This is the function the Dask workers execute.

    config = case_config(base, source, overrides, seed)       # ConfigError naming the key
    result = run_case(base, source, index, key, overrides, seed, duration, collect)

`base` is the base machine file's data as TOML read it; `source` its path (files it names,
such as an FS701 parameter file, are read relative to it, on the worker). The summary is the
one of `axisline run --json`: the machine's, plus the personality's `json_fields` (the FS701's
"cuts" and "summary"), plus computed fields the sweep adds (fs701.py: "envelope").

A collected field is a dotted path into that summary (`summary.max_abs_error_lu`,
`axes.carriage.max_following_error`, `cuts[2].error_lu`); a path through a list without an
index (`cuts.error_lu`) is a per-row field of that table (one row per cut).

The result is plain data (JSON types): status "ok" (the run completed), "fault" (it ended on a
runtime fault, e.g. Error 02: a result, the case is infeasible) or "failed" (it raised: the
error is recorded and the sweep goes on). The trace is off in every case (the sweep reads the
summary, and a scope costs memory per case).

Decisions
1. (issue: "a failing case is recorded with its error and does not stop the sweep") a case
   ends at its first runtime fault by default (sweep.stop_on_fault = true): what follows a
   fault (an FS701 after Error 02 stands until the duration is over) changes no verdict and
   would cost most of a sweep's time in its infeasible corner. The check runs at the run's
   progress points (every 1/200 of the duration), so the summary is the one of that cycle on
   every engine; `stop_on_fault = false` runs on as `axisline run` does. Test:
   test_fs701_envelope.py::test_a_case_ends_at_its_first_fault_unless_told_otherwise.
2. (issue: "any field of the personality's JSON summary") the summary is built exactly as
   `axisline run --json` builds it (Machine.summary + the personality's json_fields), so a
   field a user reads in one run's JSON is the field the sweep collects. Test:
   test_sweep_run.py::test_single_process_results.
"""

from __future__ import annotations

import copy
import time
import traceback
from typing import Any

from axisline.configerrors import ConfigError

from .keys import KeyPathError, set_key

__all__ = ["case_config", "run_case", "extract", "plain"]

#: an error text in the table stays a line
ERROR_CHARS = 500


def plain(v: Any) -> Any:
    """JSON types only (numpy scalars -> Python numbers, tuples -> lists)."""
    if isinstance(v, dict):
        return {str(k): plain(x) for k, x in v.items()}
    if isinstance(v, (list, tuple)):
        return [plain(x) for x in v]
    if v is None or isinstance(v, (bool, int, float, str)):
        return v
    item = getattr(v, "item", None)
    if callable(item):
        return plain(item())
    return str(v)


def case_config(base: dict[str, Any], source: str, overrides: Any, seed: int | None):
    """The validated MachineConfig of a case (ConfigError naming the bad key)."""
    from axisline.config import parse_machine

    data = copy.deepcopy(base)
    for key, value in overrides:
        try:
            set_key(data, key, value)
        except KeyPathError as e:
            raise ConfigError(source, [f"parameters.{key!r}: {str(e).removeprefix(key + ': ')}"]) from None
    if seed is not None:
        set_key(data, "machine.seed", seed)
    trace = data.get("trace")
    data["trace"] = {"enabled": False} if not isinstance(trace, dict) else {**trace, "enabled": False}
    return parse_machine(data, source)


def _missing(node: Any, done: str) -> str:
    if isinstance(node, dict):
        return f"{done or 'the summary'} has {', '.join(list(node)[:40]) or 'no keys'}"
    if isinstance(node, list):
        return f"{done} is a list of {len(node)}"
    return f"{done} is a value"


def _resolve(node: Any, parts: list[Any], done: str) -> tuple[bool, Any, str]:
    """(found, value, why not) for a path without a per-row list."""
    for part in parts:
        if isinstance(part, int):
            if isinstance(node, list) and 0 <= part < len(node):
                node = node[part]
            else:
                return False, None, _missing(node, done)
        elif isinstance(node, dict) and part in node:
            node = node[part]
        else:
            return False, None, _missing(node, done)
        done = f"{done}[{part}]" if isinstance(part, int) else (f"{done}.{part}" if done else part)
    return True, node, ""


def extract(summary: dict[str, Any], collect: list[str]) -> tuple[dict[str, Any], dict[str, list[dict[str, Any]]], dict[str, str]]:
    """(values by field, per-row tables by table path, unknown fields with what is there)."""
    from .keys import parse_key

    values: dict[str, Any] = {}
    tables: dict[str, list[dict[str, Any]]] = {}
    unknown: dict[str, str] = {}
    for field in collect:
        parts = parse_key(field)
        node: Any = summary
        done = ""
        for i, part in enumerate(parts):
            if isinstance(node, list) and not isinstance(part, int):  # a per-row field of this table
                rest = parts[i:]
                rows = tables.setdefault(done, [{} for _ in node])
                column = ".".join(str(p) for p in rest)
                any_found = not node
                for row, entry in zip(rows, node):
                    found, value, _ = _resolve(entry, rest, "")
                    row[column] = plain(value)
                    any_found = any_found or found
                if not any_found:
                    unknown[field] = f"no row of {done} has {column} ({_missing(node[0], done + '[0]')})"
                break
            found, node, why = _resolve(node, [part], done)
            if not found:
                unknown[field] = why
                values[field] = None
                break
            done = f"{done}[{part}]" if isinstance(part, int) else (f"{done}.{part}" if done else str(part))
        else:
            values[field] = plain(node)
    return values, tables, unknown


def _error_text(e: BaseException) -> str:
    if isinstance(e, ConfigError):
        text = "bad machine file: " + "; ".join(e.problems)
    else:
        where = traceback.extract_tb(e.__traceback__)[-1:] if e.__traceback__ else []
        at = f" (at {where[0].filename.rsplit('/', 1)[-1]}:{where[0].lineno})" if where else ""
        text = f"{type(e).__name__}: {e}{at}"
    return text if len(text) <= ERROR_CHARS else text[: ERROR_CHARS - 3] + "..."


class _Stopped(Exception):
    """The case's first runtime fault: the run ends there (stop_on_fault)."""


def _run(m: Any, duration: float | None, stop_on_fault: bool) -> Any:
    """Machine.run, ended at the first runtime fault when `stop_on_fault` (the check runs at the
    run's progress points, every 1/200 of the duration: the same cycles on every engine)."""
    if not stop_on_fault:
        return m.run(duration)
    from axisline.machine import RunResult

    start, t0 = m.clock.cycle, time.perf_counter()

    def watch(_fraction: float) -> None:
        if m.faults:
            raise _Stopped

    try:
        return m.run(duration, progress=watch)
    except _Stopped:
        n = m.clock.cycle - start
        return RunResult(n, n * m.period, time.perf_counter() - t0, False, list(m.faults))


def run_case(base: dict[str, Any], source: str, index: int, key: str, overrides: Any, seed: int | None,
             options: dict[str, Any]) -> dict[str, Any]:
    """Run one case; never raises (a failure is a result with status "failed").

    options: duration (None: the file's, as `axisline run` without --duration), collect (the
    fields), stop_on_fault (end the run at its first runtime fault)."""
    duration, collect = options.get("duration"), options["collect"]
    t0 = time.perf_counter()
    out: dict[str, Any] = {"case": index, "key": key, "status": "failed", "error": None, "values": {}, "tables": {}, "unknown": {}}
    try:
        from axisline.machine import Machine

        from .fs701 import computed_fields

        config = case_config(base, source, overrides, seed)
        m = Machine(config, source=source)
        extra = computed_fields(m)
        result = _run(m, duration, bool(options.get("stop_on_fault", True)))
        summary = m.summary(result)
        if m.device is not None:
            summary.update(m.device.json_fields(summary.get("device") or {}))
        summary.update(extra)
        values, tables, unknown = extract(summary, collect)
        out.update(values=values, tables=tables, unknown=unknown)
        out["status"] = "ok" if result.completed else "fault"
        if not result.completed:
            why = result.faults[0] if result.faults else "the job failed"
            out["error"] = why if len(why) <= ERROR_CHARS else why[: ERROR_CHARS - 3] + "..."
    except Exception as e:  # noqa: BLE001 - a case's failure is recorded, the sweep goes on
        out["error"] = _error_text(e)
    out["wall_s"] = time.perf_counter() - t0  # the journal's, never the table's (spec.py decision 1)
    return out
