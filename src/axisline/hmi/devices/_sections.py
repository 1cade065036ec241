"""The pieces of a device view: sections as plain JSON, built the same way for every personality.

A device view is ``{"title": str, "sections": [section, ...]}``; the HMI page renders each
section by its ``type`` without knowing the device:

    parameters   rows of name, label, value, unit, min, max, writable (a write names the row)
    table        columns and rows of cells
    bits         words, each with its bits (bit, name, set)
    plot         series of x / y points with axis labels
    diagnostics  rows of code, text, active (the page offers acknowledge)
    text         lines (a display as the device shows it)

Everything here returns plain lists, dicts, str, int, float, bool and None: a value that is
not finite becomes None (strict JSON has no NaN), Decimal and Fraction become float, an enum
its value, anything else its text. Views run between two cycles, so the builders bound what
they copy: `MAX_ROWS` table rows, `MAX_POINTS` points per plot series; and what changes
only when someone writes (a parameter table of 400 fields) is built again only then (`cached`).
"""

from __future__ import annotations

import math
import weakref
from decimal import Decimal
from enum import Enum
from fractions import Fraction
from typing import Any, Callable, Iterable, Mapping, Sequence

__all__ = [
    "MAX_POINTS",
    "MAX_ROWS",
    "bits",
    "cached",
    "clean",
    "cut_table",
    "diagnostics",
    "downsample",
    "number",
    "parameters",
    "plot",
    "row",
    "table",
    "text",
    "word",
]

#: points of one plot series (a curve of up to 5460 set points is thinned to this)
MAX_POINTS = 500
#: rows of a table (the newest are kept: the last 50 cuts)
MAX_ROWS = 50


def clean(value: Any) -> Any:
    """`value` as plain JSON (see the module docstring)."""
    if value is None or isinstance(value, (bool, str, int)):
        return value
    if isinstance(value, float):
        return value if math.isfinite(value) else None
    if isinstance(value, (Decimal, Fraction)):
        return clean(float(value))
    if isinstance(value, Enum):
        return clean(value.value)
    if isinstance(value, Mapping):
        return {str(k): clean(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [clean(v) for v in value]
    item = getattr(value, "item", None)  # numpy scalars
    if callable(item):
        try:
            return clean(item())
        except (TypeError, ValueError):
            pass
    return str(value)


def number(value: Any) -> int | float | None:
    """A number for a cell: int stays int, a float that is not finite is None."""
    v = clean(value)
    if isinstance(v, bool) or not isinstance(v, (int, float)):
        return None
    return v


def row(name: str, label: str, value: Any, unit: str = "", minimum: Any = None, maximum: Any = None,
        writable: bool = False, **extra: Any) -> dict[str, Any]:
    """One row of a parameters section; `extra` keys (e.g. "allowed", "note") ride along."""
    out = {"name": name, "label": label, "value": clean(value), "unit": unit, "min": clean(minimum),
           "max": clean(maximum), "writable": bool(writable)}
    out.update({k: clean(v) for k, v in extra.items()})
    return out


def parameters(title: str, rows: list[dict[str, Any]]) -> dict[str, Any]:
    return {"type": "parameters", "title": title, "rows": rows}


def table(title: str, columns: Sequence[str], rows: Iterable[Sequence[Any]], *, newest: int = MAX_ROWS) -> dict[str, Any]:
    """A table of at most `newest` rows: the last ones (a live table shows the present)."""
    kept = list(rows)[-newest:] if newest else list(rows)
    return {"type": "table", "title": title, "columns": list(columns), "rows": [[clean(c) for c in r] for r in kept]}


def word(name: str, value: int, names: Mapping[int, str] | Sequence[str], width: int | None = None) -> dict[str, Any]:
    """A status or control word and its bits: `names` by bit number (a sequence: bit 0 first).
    Bits without a name are left out unless `width` asks for all of them ("bit n")."""
    named = dict(enumerate(names)) if not isinstance(names, Mapping) else dict(names)
    numbers = range(width) if width is not None else sorted(named)
    value = int(value)
    return {"name": name, "value": value,
            "bits": [{"bit": n, "name": named.get(n, f"bit {n}"), "set": bool(value >> n & 1)} for n in numbers]}


def bits(title: str, words: list[dict[str, Any]]) -> dict[str, Any]:
    return {"type": "bits", "title": title, "words": words}


def downsample(xs: Sequence[float], ys: Sequence[float], limit: int = MAX_POINTS) -> tuple[list[Any], list[Any]]:
    """At most `limit` points, evenly picked, the first and the last always kept (a cam's
    start and end values are what an engineer checks)."""
    n = min(len(xs), len(ys))
    if n <= limit:
        idx: Iterable[int] = range(n)
    else:
        idx = sorted({round(k * (n - 1) / (limit - 1)) for k in range(limit)})
    picked = list(idx)
    return [clean(xs[i]) for i in picked], [clean(ys[i]) for i in picked]


def plot(title: str, x_label: str, y_label: str, series: list[tuple[str, Sequence[float], Sequence[float]]]) -> dict[str, Any]:
    out = []
    for name, xs, ys in series:
        x, y = downsample(xs, ys)
        out.append({"name": name, "x": x, "y": y})
    return {"type": "plot", "title": title, "x_label": x_label, "y_label": y_label, "series": out}


def diagnostics(title: str, rows: list[tuple[Any, str, bool]]) -> dict[str, Any]:
    return {"type": "diagnostics", "title": title,
            "rows": [{"code": clean(code), "text": str(text), "active": bool(active)} for code, text, active in rows]}


def text(title: str, lines: Iterable[str]) -> dict[str, Any]:
    return {"type": "text", "title": title, "lines": [str(line) for line in lines]}


def cut_table(title: str, cuts: Sequence[Mapping[str, Any]], length_unit: str) -> dict[str, Any]:
    """The cut table of a flying shear or cutoff (the shared cut records, report/cuts.py),
    the newest `MAX_ROWS` cuts, with the report's columns and its line-speed unit."""
    from axisline.report.cuts import line_speed_unit

    k, speed_unit = line_speed_unit(length_unit)
    lu = length_unit
    columns = ["cut", "t [s]", "kind", f"target [{lu}]", f"actual [{lu}]", f"error [{lu}]", "error [incr]",
               f"line speed [{speed_unit}]", "position error [incr]", "tolerance [incr]", "ok"]
    rows = []
    for c in list(cuts)[-MAX_ROWS:]:
        speed = number(c.get("line_speed"))
        rows.append([c.get("index"), number(c.get("time")), c.get("kind"), number(c.get("target_length")),
                     number(c.get("actual_length")), number(c.get("error_lu")), number(c.get("error_counts")),
                     None if speed is None else speed * k, number(c.get("following_error")),
                     number(c.get("tolerance")), c.get("in_tolerance")])
    return table(title, columns, rows)


_CACHE: "weakref.WeakKeyDictionary[Any, dict[str, tuple[Any, Any]]]" = weakref.WeakKeyDictionary()


def cached(owner: Any, what: str, key: Any, build: Callable[[], Any]) -> Any:
    """`build()`, or what it gave for `owner` last time when `key` is the same (a parameter
    set's identity and write counter): the parameter tables are rebuilt only after a write,
    not at every poll of the page. Callers must not change what they get."""
    try:
        entries = _CACHE.setdefault(owner, {})
    except TypeError:  # (an owner without weak references: no cache)
        return build()
    hit = entries.get(what)
    if hit is not None and hit[0] == key:
        return hit[1]
    value = build()
    entries[what] = (key, value)
    return value
