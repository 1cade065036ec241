"""report.py: the boundary comparison and the heatmap's cells, on results made up for the test."""

from __future__ import annotations

from dataclasses import dataclass

import pytest

from axisline.sweep.report import boundary_rows, heatmap, line_plot
from axisline.sweep.spec import SweepFile


@dataclass
class C:
    overrides: tuple


def _spec(extra: dict | None = None) -> SweepFile:
    params = {"v": [1.0, 2.0], "L": [80.0, 96.0, 104.0, 120.0]}
    params.update(extra or {})
    return SweepFile.model_validate({
        "sweep": {"base": "m.toml", "collect": ["ok", "m", "c"], "feasible": ["ok == true"]},
        "parameters": params,
        "report": {"heatmap": {"x": "v", "y": "L", "metric": "m"}, "line": {"x": "L", "metric": "m"}, "boundary": "c"},
    })


def _case(v, L, ok, m=1.0, c=100.0, **more):
    return C((("v", v), ("L", L), *more.items())), {"status": "ok" if ok else "fault", "values": {"ok": ok, "m": m, "c": c}}


def test_boundary_rows_bracket_and_deviation():
    spec = _spec()
    made = [_case(1.0, L, L >= 100) for L in (80.0, 96.0, 104.0, 120.0)]  # agrees: switches at 100
    made += [_case(2.0, L, L >= 120, c=100.0) for L in (80.0, 96.0, 104.0, 120.0)]  # 104 is infeasible: 4 % off
    cases, results = zip(*made)
    rows = {r["x"]: r for r in boundary_rows(spec, list(cases), list(results))}
    assert rows[1.0] == {"x": 1.0, "computed": 100.0, "simulated_low": 96.0, "simulated_high": 104.0, "deviation": 0.0,
                         "agree": True, "cases": 4}
    assert rows[2.0]["simulated_low"] == 104.0 and rows[2.0]["simulated_high"] == 120.0
    assert rows[2.0]["deviation"] == pytest.approx(0.04) and rows[2.0]["agree"] is True
    late = [_case(1.0, L, L >= 120) for L in (80.0, 96.0, 104.0, 120.0)] + [_case(1.0, 110.0, False)]
    cases, results = zip(*late)
    (row,) = boundary_rows(spec, list(cases), list(results))
    assert row["deviation"] == pytest.approx(0.10) and row["agree"] is False


def test_failed_cases_say_nothing_about_the_boundary():
    spec = _spec()
    made = [_case(1.0, 80.0, False), _case(1.0, 120.0, True)]
    failed = C((("v", 1.0), ("L", 104.0))), {"status": "failed", "values": {}}
    cases, results = zip(*made, failed)
    (row,) = boundary_rows(spec, list(cases), list(results))
    assert (row["simulated_low"], row["simulated_high"], row["cases"]) == (80.0, 120.0, 2)


def test_heatmap_cells_average_the_other_parameters(tmp_path, monkeypatch):
    """report.py decision 1: a cell is the mean of its cases, feasible only if all of them are."""
    import matplotlib.axes

    spec = _spec({"k": [1, 2]})
    made = [_case(1.0, 80.0, True, m=1.0, k=1), _case(1.0, 80.0, False, m=3.0, k=2),
            _case(2.0, 80.0, True, m=5.0, k=1), _case(2.0, 80.0, True, m=5.0, k=2)]
    cases, results = zip(*made)
    seen = {}
    real = matplotlib.axes.Axes.pcolormesh

    def spy(self, *args, **kw):
        seen.setdefault("grids", []).append(args[2])
        return real(self, *args, **kw)

    monkeypatch.setattr(matplotlib.axes.Axes, "pcolormesh", spy)
    path = heatmap(spec, list(cases), list(results), tmp_path / "h.png")
    assert path.stat().st_size > 1000
    import numpy as np

    metric, infeasible = [g for g in seen["grids"] if isinstance(g, np.ma.MaskedArray)][:2]  # (the colour bar's is not)
    assert metric.tolist() == [[2.0, 5.0]]  # the mean of 1 and 3; of 5 and 5
    assert np.ma.getmaskarray(infeasible).tolist() == [[False, True]]  # cell (1.0, 80): one case infeasible
    assert line_plot(spec, list(cases), list(results), tmp_path / "l.png").stat().st_size > 1000
