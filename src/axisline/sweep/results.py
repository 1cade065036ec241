"""The results table: one row per case (results.csv, results.parquet) and one file per per-row
table (cuts.csv, cuts.parquet: one row per cut of every case).

Columns of results: case (its number in the grid order), key (the resume key), the parameters
(named by their dotted keys), machine.seed (with machine_seed = "per_case"), status (ok, fault,
failed), error, the collected fields (by their dotted names), feasible (with conditions).
Per-row tables: case, row, the parameters, the fields (named after the table, as collected).

A column's type is its values': bool, int64, float64 (ints among floats become floats), else
text; a list or table value is JSON text. Missing values are empty cells in the CSV and nulls
in Parquet. Floats are written with repr (the shortest exact form), so two runs that computed
the same numbers write the same bytes.
"""

from __future__ import annotations

import csv
import io
import json
import math
from pathlib import Path
from typing import Any

from axisline.kernel import atomic_write_bytes, atomic_write_text

from .spec import SweepFile, holds, parse_condition

__all__ = ["Table", "results_table", "row_tables", "feasible_of", "write_table"]


class Table:
    """Columns of equal length, by name, in order."""

    def __init__(self) -> None:
        self.columns: dict[str, list[Any]] = {}

    def __len__(self) -> int:
        return len(next(iter(self.columns.values()), []))

    def rows(self) -> list[dict[str, Any]]:
        names = list(self.columns)
        return [dict(zip(names, vals)) for vals in zip(*self.columns.values())]


def feasible_of(spec: SweepFile, r: dict[str, Any]) -> bool | None:
    """All conditions hold (None: no conditions, or the case failed: unknown)."""
    if not spec.sweep.feasible or r.get("status") == "failed":
        return None
    values = r.get("values", {})
    return all(holds(values.get(f), op, v) for f, op, v in map(parse_condition, spec.sweep.feasible))


def _params(case: Any) -> dict[str, Any]:
    out = {k: v for k, v in case.overrides}
    if case.seed is not None:
        out["machine.seed"] = case.seed
    return out


def results_table(spec: SweepFile, cases: list[Any], results: list[dict[str, Any]]) -> Table:
    t = Table()
    scalar = [f for f in spec.sweep.collect if not _per_row(f, results)]
    names = ["case", "key", *[k for k, _ in cases[0].overrides]] if cases else ["case", "key"]
    if cases and cases[0].seed is not None:
        names.append("machine.seed")
    names += ["status", "error", *scalar]
    if spec.sweep.feasible:
        names.append("feasible")
    t.columns = {n: [] for n in names}
    for case, r in zip(cases, results):
        row = {"case": case.index, "key": case.key, **_params(case), "status": r.get("status"), "error": r.get("error")}
        values = r.get("values", {})
        row.update({f: values.get(f) for f in scalar})
        row["feasible"] = feasible_of(spec, r)
        for n in names:
            t.columns[n].append(row.get(n))
    return t


def _per_row(field: str, results: list[dict[str, Any]]) -> bool:
    """A field that some case stored in a per-row table (and none as a value)."""
    for r in results:
        if field in r.get("values", {}):
            return False
        for table in r.get("tables") or {}:
            if field.startswith(table + "."):
                return True
    return False


def row_tables(cases: list[Any], results: list[dict[str, Any]]) -> dict[str, Table]:
    """Per table path: case, row, the parameters, the table's fields (as collected)."""
    columns: dict[str, list[str]] = {}
    for r in results:
        for table, rows in (r.get("tables") or {}).items():
            cols = columns.setdefault(table, [])
            for row in rows:
                cols += [c for c in row if c not in cols]
    out: dict[str, Table] = {}
    for table, cols in columns.items():
        t = Table()
        pnames = list(_params(cases[0])) if cases else []
        names = ["case", "row", *pnames, *[f"{table}.{c}" for c in cols]]
        t.columns = {n: [] for n in names}
        for case, r in zip(cases, results):
            params = _params(case)
            for i, row in enumerate((r.get("tables") or {}).get(table, [])):
                full = {"case": case.index, "row": i, **params, **{f"{table}.{c}": row.get(c) for c in cols}}
                for n in names:
                    t.columns[n].append(full.get(n))
        out[table] = t
    return out


def _kind(values: list[Any]) -> str:
    present = [v for v in values if v is not None]
    if present and all(isinstance(v, bool) for v in present):
        return "bool"
    if present and all(isinstance(v, int) and not isinstance(v, bool) for v in present):
        return "int"
    if present and all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in present):
        return "float"
    return "text"


def _text(v: Any) -> str | None:
    if v is None or isinstance(v, str):
        return v
    return json.dumps(v, separators=(",", ":"), allow_nan=True)


def _csv_cell(v: Any, kind: str) -> str:
    if v is None:
        return ""
    if kind == "bool":
        return "true" if v else "false"
    if kind == "float":
        x = float(v)
        return repr(x) if math.isfinite(x) else ("nan" if math.isnan(x) else ("inf" if x > 0 else "-inf"))
    if kind == "int":
        return str(v)
    return _text(v) or ""


def csv_text(table: Table) -> str:
    kinds = {n: _kind(v) for n, v in table.columns.items()}
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(table.columns)
    for row in zip(*table.columns.values()):
        w.writerow(_csv_cell(v, kinds[n]) for n, v in zip(table.columns, row))
    return buf.getvalue()


def parquet_bytes(table: Table) -> bytes:
    import pyarrow as pa
    import pyarrow.parquet as pq

    arrays = {}
    for n, values in table.columns.items():
        kind = _kind(values)
        if kind == "bool":
            arrays[n] = pa.array(values, type=pa.bool_())
        elif kind == "int":
            arrays[n] = pa.array(values, type=pa.int64())
        elif kind == "float":
            arrays[n] = pa.array([None if v is None else float(v) for v in values], type=pa.float64())
        else:
            arrays[n] = pa.array([_text(v) for v in values], type=pa.string())
    sink = pa.BufferOutputStream()
    pq.write_table(pa.table(arrays), sink)
    return sink.getvalue().to_pybytes()


def write_table(table: Table, stem: Path) -> list[Path]:
    """STEM.csv and STEM.parquet, each written atomically."""
    stem.parent.mkdir(parents=True, exist_ok=True)
    c, p = stem.with_name(stem.name + ".csv"), stem.with_name(stem.name + ".parquet")
    atomic_write_text(c, csv_text(table))
    atomic_write_bytes(p, parquet_bytes(table))
    return [c, p]
