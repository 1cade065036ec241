"""Per-cut results of a flying cutoff, shared by the personalities that cut on the fly (the
FS701 flying shear, the CLM1.4 flying cutoff): the `run --json` names, the cut table and the
length-error figures.

A cut record is a dict with the keys the FS701's `CutRecord.as_dict()` has:

    index, time [s], kind, target_length, actual_length, error_lu (LU), error_counts
    (carriage encoder increments), line_speed (LU/min, the material's), line_speed_measured
    (LU/min, the controller's own measurement), following_error (carriage increments at the
    cut), max_pos_error_counts (optional: over the synchronous phase), constant_speed (bool),
    tolerance (increments or None), in_tolerance (bool or None), mark_offset(_counts) (optional)

`actual_length` is None (or nan) for a cut without a piece (the first cut of an FS701 run).

    job_json(device_summary)                       # {"cuts": [...], "summary": {...}} for run --json
    line_speed_unit(length_unit)                   # (factor from LU/min, "m/min") for tables and figures
    cut_table_markdown(cuts, length_unit, ...)     # the Markdown table of report.md
    length_error_figure(cuts, ..., path)           # bar chart of every piece's error
    error_histogram_figure(cuts, ..., path)        # histogram of the errors
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any, Iterable, Mapping

__all__ = ["job_json", "line_speed_unit", "cut_table_markdown", "length_error_figure", "error_histogram_figure", "finish_cut_axes", "cell"]

# a line's speed is read in m/min on the machine (FS701 register 0x0B08 is LU/min, the CLM's
# V011 and line speed parameters are per minute): the length units that convert to metres
_METRES_PER_UNIT = {"mm": 1e-3, "cm": 1e-2, "dm": 1e-1, "m": 1.0}
_FEET_PER_UNIT = {"in": 1.0 / 12.0, "inch": 1.0 / 12.0, "ft": 1.0}


def line_speed_unit(length_unit: str) -> tuple[float, str]:
    """(factor, unit) to show a line speed given in length units per minute: m/min for metric
    lengths, ft/min for inches and feet, else the length unit per minute (factor 1)."""
    if length_unit in _METRES_PER_UNIT:
        return _METRES_PER_UNIT[length_unit], "m/min"
    if length_unit in _FEET_PER_UNIT:
        return _FEET_PER_UNIT[length_unit], "ft/min"
    return 1.0, f"{length_unit}/min"


def _num(x: Any) -> float | None:
    return None if x is None or (isinstance(x, float) and not math.isfinite(x)) else x


def job_json(device: Mapping[str, Any]) -> dict[str, Any]:
    """Top-level "cuts" and "summary" of `run --json` from a personality's summary() with "cuts"."""
    cuts = []
    for c in device.get("cuts", []):
        pos_err = c.get("max_pos_error_counts")
        if pos_err is None and c.get("following_error") is not None:
            pos_err = abs(c["following_error"])  # no window record: the error at the cut
        cuts.append({
            "index": c.get("index"),
            "time_s": c.get("time"),
            "kind": c.get("kind"),
            "target_lu": _num(c.get("target_length")),
            "actual_lu": _num(c.get("actual_length")),
            "error_lu": _num(c.get("error_lu")),
            "error_counts": _num(c.get("error_counts")),
            "line_speed_lu_min": _num(c.get("line_speed")),
            "max_pos_error_counts": _num(pos_err),
            "in_tolerance": c.get("in_tolerance"),
        })
    measured = [c for c in cuts if c["error_lu"] is not None]
    times = [c["time_s"] for c in cuts if c["time_s"] is not None]
    span = (times[-1] - times[0]) if len(times) > 1 else 0.0
    batch = device.get("batch", {})
    summary = {
        "count": len(measured),
        "cuts": len(cuts),
        "mean_error_lu": (sum(c["error_lu"] for c in measured) / len(measured)) if measured else None,
        "max_abs_error_lu": max((abs(c["error_lu"]) for c in measured), default=None),
        "max_abs_error_counts": max((abs(c["error_counts"]) for c in measured), default=None),
        "std_error_lu": batch.get("std_error_lu"),
        "cuts_per_minute": (60.0 * (len(times) - 1) / span) if span > 0 else None,
        "in_tolerance": batch.get("in_tolerance"),
        "errors_raised": device.get("errors_raised", []),
    }
    return {"cuts": cuts, "summary": summary}


def cell(x: Any, fmt: str = ".3f", none: str = "-") -> str:
    """A report cell: `none` for a missing (or NaN) value, yes/no for a flag, `fmt` for a float."""
    if x is None or (isinstance(x, float) and math.isnan(x)):
        return none
    if isinstance(x, bool):
        return "yes" if x else "no"
    if isinstance(x, float):
        return format(x, fmt)
    return str(x)


def cut_table_markdown(cuts: Iterable[Mapping[str, Any]], length_unit: str, measured_speed: str = "measured line speed",
                       tolerance: bool = True) -> str:
    """One row per cut: target, actual, errors, line speed, position error (and tolerance)."""
    cuts = list(cuts)
    lu = length_unit
    k, speed_unit = line_speed_unit(lu)
    speed_fmt = ".2f" if k < 1.0 else ".0f"  # m/min to the cm/min; LU/min as the device shows them
    marks = any(c.get("mark_offset") is not None for c in cuts)
    head = [
        "cut", "t [s]", "kind", f"target [{lu}]", f"actual [{lu}]", f"error [{lu}]", "error [incr]",
        f"line speed [{speed_unit}]", f"{measured_speed} [{speed_unit}]", "position error [incr]", "constant speed",
    ]
    if marks:
        head += [f"mark offset [{lu}]", "mark offset [incr]"]
    if tolerance:
        head += ["tolerance [incr]", "ok"]
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for c in cuts:
        row = [
            str(c["index"]), cell(c["time"], ".3f"), str(c["kind"]), cell(c["target_length"], ".2f"), cell(c["actual_length"], ".3f"),
            cell(c["error_lu"], "+.4f"), cell(c["error_counts"], "+.2f"), cell(_scaled(c.get("line_speed"), k), speed_fmt),
            cell(_scaled(c.get("line_speed_measured"), k), speed_fmt), cell(c.get("following_error"), "+.2f"), cell(c.get("constant_speed")),
        ]
        if marks:
            row += [cell(c.get("mark_offset"), "+.4f"), cell(c.get("mark_offset_counts"), "+.2f")]
        if tolerance:
            ok = c.get("in_tolerance")
            row += [cell(c.get("tolerance"), "g"), "-" if ok is None else ("yes" if ok else "**NO**")]
        lines.append("| " + " | ".join(row) + " |")
    return "\n".join(lines) + "\n"


def _scaled(x: Any, k: float) -> Any:
    return x * k if isinstance(x, (int, float)) and not isinstance(x, bool) else x


def length_error_figure(plt: Any, ax: Any, cuts: list[Mapping[str, Any]], *, width: float = 0.8, shift: float = 0.0,
                        tolerances: Iterable[tuple[float, str, str]] = ()) -> None:
    """Bars of every piece's length error (increments) on `ax`: constant line speed green, a cut
    in a speed change orange; `tolerances`: (increments, line style, label) drawn at +-."""
    pieces = [c for c in cuts if c.get("error_counts") is not None and not _nan(c["error_counts"])]
    const = [c for c in pieces if c.get("constant_speed")]
    ramp = [c for c in pieces if not c.get("constant_speed")]
    ax.bar([c["index"] + shift for c in const], [c["error_counts"] for c in const], width=width, color="tab:green",
           label="length error, constant line speed")
    ax.bar([c["index"] + shift for c in ramp], [c["error_counts"] for c in ramp], width=width, color="tab:orange",
           label="length error, cut in a speed change")
    for v, style, label in tolerances:
        ax.axhline(v, color="tab:red", linestyle=style, linewidth=1, label=label)
        ax.axhline(-v, color="tab:red", linestyle=style, linewidth=1)
    ax.set_ylabel("length error [carriage increments]")


def _nan(x: Any) -> bool:
    return isinstance(x, float) and math.isnan(x)


def error_histogram_figure(plt: Any, cuts: list[Mapping[str, Any]], path: Path, tolerance: float | None = None) -> Path | None:
    """Histogram of the length errors (increments); None when no piece was measured."""
    import numpy as np

    errs = [c["error_counts"] for c in cuts if c.get("error_counts") is not None and not _nan(c["error_counts"])]
    if not errs:
        return None
    fig, ax = plt.subplots(figsize=(7, 4), constrained_layout=True)
    n_bins = max(5, min(40, int(np.sqrt(len(errs))) * 2))
    ax.hist(errs, bins=n_bins, color="tab:green", edgecolor="black", linewidth=0.5)
    if tolerance is not None:
        ax.axvline(tolerance, color="tab:red", linestyle="--", linewidth=1, label="tolerance (constant speed)")
        ax.axvline(-tolerance, color="tab:red", linestyle="--", linewidth=1)
        ax.legend(loc="upper right", fontsize=8)
    ax.set_xlabel("length error [carriage increments]")
    ax.set_ylabel("pieces")
    ax.grid(True, alpha=0.3)
    ax.set_title(f"length errors of {len(errs)} pieces: mean {np.mean(errs):.2f}, std {np.std(errs):.2f} increments")
    fig.savefig(path, dpi=90)
    plt.close(fig)
    return path


def finish_cut_axes(ax: Any) -> None:
    """The dress every per-cut figure shares: the zero line, whole cut numbers, grid, legend."""
    from matplotlib.ticker import MaxNLocator

    ax.axhline(0.0, color="black", linewidth=0.5)
    ax.xaxis.set_major_locator(MaxNLocator(integer=True))
    ax.set_xlabel("cut")
    ax.grid(True, alpha=0.3)
    if ax.get_legend_handles_labels()[0]:
        ax.legend(loc="upper right", fontsize=8)
