"""The sweep's report: results tables, report.md and the plots (heatmap, line), from the results
in case order, so every file is the same whatever engine ran the cases and in whatever order.

    files = write_outputs(prepared, cases, results, out)
    rows = boundary_rows(spec, cases, results)    # simulated vs computed feasible boundary, per x

The boundary comparison (report.boundary, e.g. the FS701's computed shortest cut length):
at each heatmap x, a case is expected feasible when its y is at or above the computed
boundary c. A case on the wrong side contradicts it; `deviation` is the farthest contradicting
case's distance from c relative to c (0: none contradicts), and the two agree within 5 % when
no case more than 5 % away from c contradicts it. The simulated boundary is the bracket
between the largest infeasible y and the smallest y from which every case is feasible.

Decisions
1. (issue: "a heatmap of a chosen metric over two parameters") with more parameters than the
   two, a cell shows the mean of its cases' metric, and it is feasible only when all its cases
   are (the title says how many cases a cell holds). Test:
   test_report.py::test_heatmap_cells_average_the_other_parameters.
2. (brief: results identical whatever the engine) report.md holds no wall-clock figure and no
   count of this run's skipped cases: the console prints those. Test:
   test_sweep_run.py::test_dask_and_single_process_give_identical_files.
"""

from __future__ import annotations

import json
import math
from collections import defaultdict
from pathlib import Path
from typing import Any

from axisline.kernel import atomic_write_text

from .results import feasible_of, results_table, row_tables, write_table
from .spec import RandomParameter, RangeParameter, SweepFile, describe

__all__ = ["write_outputs", "boundary_rows", "AGREEMENT"]

#: the simulated and the computed boundary agree when no case farther than this contradicts
AGREEMENT = 0.05
_ROWS_SHOWN = 100
_FAILED_SHOWN = 50


def _number(v: Any) -> float | None:
    if isinstance(v, bool) or not isinstance(v, (int, float)):
        return None
    return float(v) if math.isfinite(v) else None


def _param(case: Any, key: str) -> Any:
    return dict(case.overrides).get(key)


def boundary_rows(spec: SweepFile, cases: list[Any], results: list[dict[str, Any]]) -> list[dict[str, Any]]:
    """Per heatmap x: computed boundary, simulated bracket, deviation, agree (module docstring)."""
    h, field = spec.report.heatmap, spec.report.boundary
    if h is None or field is None:
        return []
    by_x: dict[Any, list[tuple[float, bool, float | None]]] = defaultdict(list)
    for case, r in zip(cases, results):
        ok = feasible_of(spec, r)
        y = _number(_param(case, h.y))
        if ok is None or y is None:
            continue
        by_x[_param(case, h.x)].append((y, ok, _number(r.get("values", {}).get(field))))
    out = []
    for x in sorted(by_x, key=lambda v: (_number(v) is None, _number(v) or 0.0, str(v))):
        pts = by_x[x]
        known = [c for _, _, c in pts if c is not None]
        c = sum(known) / len(known) if known else None
        cells: dict[float, bool] = {}
        for y, ok, _ in pts:
            cells[y] = cells.get(y, True) and ok
        ys = sorted(cells)
        high = None
        for y in reversed(ys):  # the smallest y from which every case is feasible
            if not cells[y]:
                break
            high = y
        low = max((y for y in ys if not cells[y] and (high is None or y < high)), default=None)
        deviation = None
        if c is not None and c > 0:
            wrong = [abs(y - c) / c for y in ys if (y >= c) != cells[y]]
            deviation = max(wrong, default=0.0)
        out.append({"x": x, "computed": c, "simulated_low": low, "simulated_high": high, "deviation": deviation,
                    "agree": None if deviation is None else deviation <= AGREEMENT, "cases": len(pts)})
    return out


def _log_scale(spec: SweepFile, key: str) -> bool:
    p = spec.parameters.get(key)
    return (isinstance(p, RangeParameter) and p.scale == "log") or (isinstance(p, RandomParameter) and p.random == "loguniform")


def _edges(values: list[float], log: bool) -> list[float]:
    if len(values) == 1:
        v = values[0]
        return [v * 0.9, v * 1.1] if log and v > 0 else [v - 0.5, v + 0.5]
    f = (lambda a, b: math.sqrt(a * b)) if log else (lambda a, b: (a + b) / 2)
    mids = [f(a, b) for a, b in zip(values, values[1:])]
    first = values[0] ** 2 / mids[0] if log else 2 * values[0] - mids[0]
    last = values[-1] ** 2 / mids[-1] if log else 2 * values[-1] - mids[-1]
    return [first, *mids, last]


def _axis_values(cases: list[Any], key: str) -> list[Any]:
    vals = list(dict.fromkeys(_param(c, key) for c in cases))
    if all(_number(v) is not None for v in vals):
        return sorted(vals, key=float)
    return vals


def heatmap(spec: SweepFile, cases: list[Any], results: list[dict[str, Any]], path: Path) -> Path | None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    h = spec.report.heatmap
    assert h is not None
    xs, ys = _axis_values(cases, h.x), _axis_values(cases, h.y)
    if not xs or not ys:
        return None
    xi, yi = {v: i for i, v in enumerate(xs)}, {v: i for i, v in enumerate(ys)}
    total = np.zeros((len(ys), len(xs)))
    count = np.zeros((len(ys), len(xs)))
    feasible = np.ones((len(ys), len(xs)), dtype=bool)
    known = np.zeros((len(ys), len(xs)), dtype=bool)
    per_cell = defaultdict(int)
    for case, r in zip(cases, results):
        i, j = yi[_param(case, h.y)], xi[_param(case, h.x)]
        per_cell[(i, j)] += 1
        m = _number(r.get("values", {}).get(h.metric))
        if m is not None:
            total[i, j] += m
            count[i, j] += 1
        ok = feasible_of(spec, r)
        if ok is not None:
            known[i, j] = True
            feasible[i, j] &= ok
    grid = np.where(count > 0, total / np.maximum(count, 1), np.nan)
    numeric = all(_number(v) is not None for v in xs + ys)
    if numeric:
        xe = _edges([float(v) for v in xs], _log_scale(spec, h.x))
        ye = _edges([float(v) for v in ys], _log_scale(spec, h.y))
    else:
        xe, ye = list(np.arange(len(xs) + 1) - 0.5), list(np.arange(len(ys) + 1) - 0.5)
    fig, ax = plt.subplots(figsize=(9, 6), constrained_layout=True)
    mesh = ax.pcolormesh(xe, ye, np.ma.masked_invalid(grid), cmap="viridis", shading="flat")
    fig.colorbar(mesh, ax=ax, label=h.metric)
    if spec.sweep.feasible:
        bad = np.where(known & ~feasible, 1.0, np.nan)
        ax.pcolor(xe, ye, np.ma.masked_invalid(bad), hatch="xx", alpha=0.0, edgecolor="tab:red", linewidth=0.0)
        ax.pcolormesh(xe, ye, np.ma.masked_invalid(bad), cmap="Greys", vmin=0.0, vmax=2.5, alpha=0.55, shading="flat")
        ax.plot([], [], "s", color="0.6", label="not feasible (simulated)")
    rows = boundary_rows(spec, cases, results)
    if rows and numeric:
        bx = [float(r["x"]) for r in rows if r["computed"] is not None]
        by = [r["computed"] for r in rows if r["computed"] is not None]
        ax.plot(bx, by, "k--o", linewidth=1.5, markersize=4, label=f"computed boundary ({spec.report.boundary})")
        sx = [float(r["x"]) for r in rows if r["simulated_high"] is not None]
        sy = [r["simulated_high"] for r in rows if r["simulated_high"] is not None]
        ax.plot(sx, sy, "^", color="white", markeredgecolor="black", markersize=6, label="simulated: feasible from here")
    if _log_scale(spec, h.x) and numeric:
        ax.set_xscale("log")
    if _log_scale(spec, h.y) and numeric:
        ax.set_yscale("log")
    if not numeric:
        ax.set_xticks(range(len(xs)), [str(v) for v in xs])
        ax.set_yticks(range(len(ys)), [str(v) for v in ys])
    ax.set_xlabel(h.x)
    ax.set_ylabel(h.y)
    most = max(per_cell.values(), default=1)
    ax.set_title(f"{spec.sweep.name}\n{h.metric}" + (f" (mean of {most} cases a cell)" if most > 1 else ""), fontsize=10)
    if ax.get_legend_handles_labels()[0]:
        ax.legend(loc="upper left", fontsize=8, framealpha=0.85)
    fig.savefig(path, dpi=90)
    plt.close(fig)
    return path


def line_plot(spec: SweepFile, cases: list[Any], results: list[dict[str, Any]], path: Path) -> Path | None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    ln = spec.report.line
    assert ln is not None
    others = [k for k in spec.parameters if k != ln.x]
    group = next((k for k in others if len(_axis_values(cases, k)) <= 12), None)
    series: dict[Any, list[tuple[Any, float | None, bool | None]]] = defaultdict(list)
    for case, r in zip(cases, results):
        g = _param(case, group) if group is not None else None
        series[g].append((_param(case, ln.x), _number(r.get("values", {}).get(ln.metric)), feasible_of(spec, r)))
    fig, ax = plt.subplots(figsize=(9, 5), constrained_layout=True)
    numeric = all(_number(v) is not None for v in _axis_values(cases, ln.x))
    for g, pts in series.items():
        pts = sorted(pts, key=lambda p: float(p[0]) if numeric else 0.0)
        xs = [p[0] for p in pts]
        label = f"{group} = {g}" if group is not None else None
        (line,) = ax.plot(xs, [math.nan if p[1] is None else p[1] for p in pts], "-", linewidth=1.2, label=label)
        good = [(x, y) for x, y, ok in pts if y is not None and ok is not False]
        bad = [(x, y) for x, y, ok in pts if y is not None and ok is False]
        if good:
            ax.plot(*zip(*good), "o", color=line.get_color(), markersize=4)
        if bad:
            ax.plot(*zip(*bad), "x", color="tab:red", markersize=7)
        blank = [x for x, y, ok in pts if y is None and ok is False]  # no value (e.g. no piece cut): on the axis
        if blank:
            ax.plot(blank, [0.02] * len(blank), "x", color="tab:red", markersize=7, transform=ax.get_xaxis_transform())
    if spec.sweep.feasible:
        ax.plot([], [], "x", color="tab:red", label="not feasible (on the axis: no value)")
    if _log_scale(spec, ln.x) and numeric:
        ax.set_xscale("log")
    ax.set_xlabel(ln.x)
    ax.set_ylabel(ln.metric)
    ax.grid(True, alpha=0.3)
    ax.set_title(spec.sweep.name, fontsize=10)
    if ax.get_legend_handles_labels()[0]:
        ax.legend(loc="best", fontsize=8)
    fig.savefig(path, dpi=90)
    plt.close(fig)
    return path


def _cell(v: Any) -> str:
    if v is None:
        return "-"
    if isinstance(v, bool):
        return "yes" if v else "no"
    if isinstance(v, float):
        return f"{v:.6g}"
    text = json.dumps(v, separators=(",", ":")) if isinstance(v, (list, dict)) else str(v).replace("|", "\\|").replace("\n", " ")
    return text if len(text) <= 120 else text[:117] + "..."


def _table(head: list[str], rows: list[list[Any]]) -> list[str]:
    return ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)] + ["| " + " | ".join(_cell(c) for c in r) + " |" for r in rows]


def markdown(prep: Any, cases: list[Any], results: list[dict[str, Any]], files: list[Path], plots: list[Path]) -> str:
    spec: SweepFile = prep.spec
    s = spec.sweep
    n = len(results)
    status = {k: sum(1 for r in results if r.get("status") == k) for k in ("ok", "fault", "failed")}
    out = [f"# Sweep: {spec.sweep.name}", "",
           f"Sweep file `{prep.sweep_file.name}`, base machine file `{s.base}`; "
           f"{'duration ' + format(s.duration, 'g') + ' s' if s.duration is not None else 'the machine file duration'} per case; "
           f"machine seed: {'per case (sweep seed ' + str(s.seed) + ')' if s.machine_seed == 'per_case' else 'the base file'}.", "",
           f"**{n} cases**: {status['ok']} completed, {status['fault']} ended on a runtime fault, {status['failed']} failed.", ""]
    out += ["## Parameters", ""] + _table(["key", "values"], [[f"`{k}`", describe(p)] for k, p in spec.parameters.items()]) + [""]
    if s.feasible:
        nf = sum(1 for r in results if feasible_of(spec, r))
        out += ["## Feasible", "", "A case is feasible when " + " and ".join(f"`{c}`" for c in s.feasible) + f": {nf} of {n}.", ""]
    rows = boundary_rows(spec, cases, results)
    if rows:
        h = spec.report.heatmap
        assert h is not None
        agree = all(r["agree"] for r in rows if r["agree"] is not None)
        out += ["## Simulated and computed feasible region", "",
                f"At each `{h.x}`: the computed boundary `{spec.report.boundary}`, the simulated one (between the largest "
                f"infeasible and the smallest feasible `{h.y}`), and the farthest case that contradicts the computed one "
                f"(relative to it). They agree within {AGREEMENT:.0%} when no case farther than that contradicts it: "
                f"**{'they agree' if agree else 'they do not agree'}**.", ""]
        out += _table([h.x, "computed", "simulated: infeasible up to", "feasible from", "deviation", f"within {AGREEMENT:.0%}"],
                      [[r["x"], r["computed"], r["simulated_low"], r["simulated_high"],
                        None if r["deviation"] is None else f"{r['deviation']:.1%}", r["agree"]] for r in rows]) + [""]
    if plots:
        out += ["## Plots", ""] + [f"![{p.stem}]({p.name})" for p in plots] + [""]
    failed = [(c, r) for c, r in zip(cases, results) if r.get("status") == "failed"]
    if failed:
        out += ["## Failed cases", ""] + _table(["case", *spec.parameters, "error"],
                                                 [[c.index, *[v for _, v in c.overrides], r.get("error")] for c, r in failed[:_FAILED_SHOWN]])
        if len(failed) > _FAILED_SHOWN:
            out.append(f"... and {len(failed) - _FAILED_SHOWN} more (results.csv, status = failed)")
        out.append("")
    table = results_table(spec, cases, results)
    shown = [k for k in table.columns if k not in ("key", "error")]
    out += ["## Results", "", f"The first {min(n, _ROWS_SHOWN)} of {n} cases (all of them, with the errors: "
            + ", ".join(f"`{f.name}`" for f in files) + ")", ""]
    out += _table(shown, [[row[k] for k in shown] for row in table.rows()[:_ROWS_SHOWN]]) + [""]
    return "\n".join(out)


def write_outputs(prep: Any, cases: list[Any], results: list[dict[str, Any]], out: Path) -> list[Path]:
    """results.csv/.parquet, a table per per-row field group, the plots and report.md."""
    spec: SweepFile = prep.spec
    out.mkdir(parents=True, exist_ok=True)
    files = write_table(results_table(spec, cases, results), out / "results")
    for name, table in row_tables(cases, results).items():
        files += write_table(table, out / name)
    plots = []
    if spec.report.heatmap is not None:
        p = heatmap(spec, cases, results, out / "heatmap.png")
        plots += [p] if p is not None else []
    if spec.report.line is not None:
        p = line_plot(spec, cases, results, out / "line.png")
        plots += [p] if p is not None else []
    report = out / "report.md"
    atomic_write_text(report, markdown(prep, cases, results, files, plots))
    return files + plots + [report]
