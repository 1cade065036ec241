"""The files a run leaves behind: summary JSON, the trace (npz + csv), plots, report.md.

`axisline run` writes them after a simulated run and `axisline serve` when it stops (its
trace is the scope ring: the newest samples)."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

__all__ = ["write_outputs"]


def write_outputs(m: Any, result: Any, *, json_out: Path | None = None, trace_out: Path | None = None,
                  plot_dir: Path | None = None, report_dir: Path | None = None) -> dict[str, Any]:
    """Write what was asked for; returns the run summary (with the files' names in it)."""
    summary = m.summary(result)
    if m.device is not None:  # e.g. the FS701's "cuts" and "summary" in the issue's names
        summary.update(m.device.json_fields(summary.get("device") or {}))
    if report_dir is not None:
        json_out = json_out or report_dir / "summary.json"
        trace_out = trace_out or report_dir / "trace.npz"
        plot_dir = plot_dir or report_dir
    if trace_out is not None and m.trace is not None:
        trace_out.parent.mkdir(parents=True, exist_ok=True)
        m.trace.save_npz(trace_out)
        m.trace.save_csv(trace_out.with_suffix(".csv"))
        summary["trace"]["file"] = str(trace_out)
    device_plots: list[Path] = []
    if plot_dir is not None and m.trace is not None:
        from .plots import plot_trace

        files = plot_trace(m.trace.data(), m.trace.units, plot_dir, title=m.config.machine.name)
        summary["plots"] = [str(f) for f in files]
    if plot_dir is not None and m.device is not None:  # a personality's own figures
        device_plots = m.device.plots(plot_dir, m.trace.data() if m.trace is not None else None)
        summary["plots"] = [str(f) for f in device_plots] + summary.get("plots", [])
    if report_dir is not None:
        from .markdown import write_report

        generic = [Path(p) for p in summary.get("plots", []) if Path(p) not in device_plots]
        path = write_report(summary, report_dir, generic)
        if m.device is not None and summary.get("device"):
            _insert_device_section(path, m.device.report_markdown(summary["device"], device_plots))
        summary["report"] = str(path)
    if json_out is not None:
        from ..kernel import atomic_write_text

        json_out.parent.mkdir(parents=True, exist_ok=True)
        atomic_write_text(json_out, json.dumps(summary, indent=2) + "\n")
    return summary


def _insert_device_section(path: Path, section: str) -> None:
    """Put a personality's report section (Markdown) before the generic plots of report.md."""
    from ..kernel import atomic_write_text

    text = path.read_text(encoding="utf-8")
    at = text.find("\n## Plots\n")
    text = text + "\n" + section if at < 0 else text[: at + 1] + section + "\n" + text[at + 1 :]
    atomic_write_text(path, text)


