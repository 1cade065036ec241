"""Read a saved scope trace for `axisline plot`: the .npz or the .csv that `run --trace` writes.

`axisline run --trace FILE` (and `--report DIR`: DIR/trace.npz) writes the trace twice:
FILE as npz (arrays, units, period) and FILE with the suffix .csv beside it, whose header
cells are `name[unit]` (kernel/trace.py, Recording.save_csv). A user may hold either, so
`load_trace` takes both, told apart by content, not by name (an npz is a zip file: it starts
with "PK"). Anything else is refused with a message that says what is read, instead of
numpy's "Cannot load file containing pickled data" for a text file.
"""

from __future__ import annotations

import csv
import io
import os
import zipfile
from pathlib import Path

import numpy as np

from axisline.kernel import Trace
from axisline.kernel.trace import Recording

__all__ = ["load_trace", "ACCEPTED"]

#: what `axisline plot` says it reads when a file is none of it
ACCEPTED = "a trace written by `axisline run --trace FILE`: FILE (npz) or the FILE.csv beside it"

_ZIP_MAGIC = b"PK\x03\x04"


def load_trace(path: str | os.PathLike[str]) -> Recording:
    """The recording in an npz or csv trace file. Raises ValueError with a one-line reason
    (OSError for a file that cannot be opened)."""
    p = Path(path)
    with open(p, "rb") as f:
        head = f.read(4)
    if head == _ZIP_MAGIC:
        try:
            return Trace.load_npz(p)
        except (KeyError, ValueError, OSError, EOFError, zipfile.BadZipFile) as e:
            raise ValueError(f"a zip/npz file, but not an axisline trace ({e}); expected {ACCEPTED}") from None
    return _load_csv(p)


def _split_header(cell: str) -> tuple[str, str]:
    """'x.command_velocity[mm/s]' -> ('x.command_velocity', 'mm/s'); 'cycle' -> ('cycle', '')."""
    cell = cell.strip()
    at = cell.find("[")
    if at > 0 and cell.endswith("]"):
        return cell[:at], cell[at + 1 : -1]
    return cell, ""


def _load_csv(path: Path) -> Recording:
    try:
        with open(path, encoding="utf-8", newline="") as f:
            header_line = f.readline()
            rest = f.read()
    except UnicodeDecodeError:
        raise ValueError(f"neither an npz nor a text (CSV) file; expected {ACCEPTED}") from None
    header = next(csv.reader([header_line]), [])
    names_units = [_split_header(c) for c in header]
    names = [n for n, _ in names_units]
    if names[:2] != ["t", "cycle"]:
        shown = ",".join(header[:4])
        shown = shown if len(shown) <= 60 else shown[:57] + "..."
        raise ValueError(f"a CSV whose header starts {shown!r}, not 't[s],cycle,...'; expected {ACCEPTED}")
    if len(set(names)) != len(names):
        raise ValueError("the CSV header names a column twice")
    try:
        table = np.loadtxt(io.StringIO(rest), delimiter=",", dtype=float, ndmin=2) if rest.strip() else np.zeros((0, len(names)))
    except ValueError:
        raise ValueError(_bad_cell(rest, names)) from None
    if table.shape[1] != len(names):
        raise ValueError(f"the rows have {table.shape[1]} cells, the header {len(names)}")
    columns = {n: table[:, i].copy() for i, n in enumerate(names)}
    columns["cycle"] = columns["cycle"].astype(np.int64)
    t, cycle = columns["t"], columns["cycle"]
    # the period is not in the CSV: from the first two samples (t = cycle * period)
    period_us = round((t[1] - t[0]) / (cycle[1] - cycle[0]) * 1e6) if len(t) > 1 and cycle[1] != cycle[0] else 1000
    units = dict(names_units)  # "" for a channel without a unit, as the npz has it
    return Recording(columns, units, max(1, period_us))


def _bad_cell(rest: str, names: list[str]) -> str:
    """Where the CSV body fails (slow path, only after numpy refused it): line and column."""
    for line_no, row in enumerate(csv.reader(io.StringIO(rest)), start=2):
        if not row:
            continue
        if len(row) != len(names):
            return f"line {line_no} has {len(row)} cells, the header {len(names)}"
        for name, cell in zip(names, row):
            try:
                float(cell)
            except ValueError:
                return f"line {line_no}, column {name}: {cell[:40]!r} is not a number"
    return "the CSV body is not a table of numbers"
