"""A run report a person reads: summary, per-axis table, faults, job events, plots."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any


def decimals(resolution: float | None) -> int:
    """Decimal places that show one count of `resolution` (and one digit below it)."""
    if not resolution or resolution <= 0.0 or not math.isfinite(resolution):
        return 6
    return max(0, min(9, math.ceil(-math.log10(resolution) - 1e-9) + 1))


def _fmt(x: Any, unit: str = "", resolution: float | None = None) -> str:
    """A number rounded to what it means: to a tenth of a count when the axis' resolution is
    known (no 2.7e-12 deg of rounding noise), else 6 significant digits."""
    if isinstance(x, float):
        if resolution is not None:
            d = decimals(resolution)
            text = f"{x:.{d}f}"
            if float(text) == 0.0:
                text = "0"  # (no "-0.0000")
            return f"{text} {unit}".strip()
        return f"{x:.6g} {unit}".strip()
    return f"{x} {unit}".strip()


def write_report(summary: dict[str, Any], out_dir: str | Path, plots: list[Path]) -> Path:
    """Write report.md into out_dir (the plots are expected in the same folder)."""
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    s = summary
    lines = [
        f"# {s['machine']}",
        "",
        f"- machine file: `{s['file']}`, seed {s['seed']}, cycle {s['cycle_us']} µs",
        f"- simulated {s['simulated_s']:.4f} s ({s['cycles']} cycles) in {s['wall_s']:.3f} s wall clock "
        f"({s['realtime_factor']:.0f}x real time)",
        f"- result: **{'completed' if s['completed'] else 'NOT completed'}**",
        "",
        "## Axes",
        "",
        "| axis | state | position | following error | max following error | max speed | error |",
        "|---|---|---|---|---|---|---|",
    ]
    for name, a in s["axes"].items():
        u, res = a["unit"], a.get("resolution")
        err = f"{a['error_id']}: {a['error_text']}" if a["error_id"] else ""
        lines.append(
            f"| {name} | {a['state']} | {_fmt(a['position'], u, res)} | {_fmt(a['following_error'], u, res)} | "
            f"{_fmt(a['max_following_error'], u, res)} | {_fmt(a['max_speed'], u + '/s', res)} | {err} |"
        )
    lines += ["", "## Faults", ""]
    lines += [f"- {f}" for f in s["faults"]] or ["none"]
    if s.get("warnings"):  # what a commissioning engineer must see (Machine.warnings)
        lines += ["", "## Warnings", ""]
        lines += [f"- {w}" for w in s["warnings"]]
    job = s["job"]
    if job.get("steps", 1) or job["events"] or job.get("failed"):
        lines += ["", "## Job", "", f"{'finished' if job['finished'] else 'not finished'}, {job['rounds']} round(s)", ""]
    elif s.get("device") is not None:  # the personality drove the machine: its section says what happened
        lines += ["", "## Job", "", "none: the device drove the machine (its section below)", ""]
    if job["events"]:
        lines += ["| t [s] | step | command |", "|---|---|---|"]
        lines += [f"| {e['t']:.4f} | {e['step']} | {e['text']} |" for e in job["events"]]
    if plots:
        lines += ["", "## Plots", ""]
        lines += [f"![{p.stem}]({p.name})" for p in plots]
    path = out / "report.md"
    from ..kernel import atomic_write_text

    atomic_write_text(path, "\n".join(lines) + "\n")
    return path
