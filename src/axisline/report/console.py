"""The run summary on the console (`axisline run`): the axes' table and the result lines.

The job line is printed when the machine file has a job. A personality that drives the
machine itself (an FS701 batch, a CLM program) has no job steps: then its own summary line
(the device summary's `headline`) says what happened, in the device's words, and a
"job: finished, 0 round(s), 0 command(s)" would say nothing. A personality without such a
line is still named, with where its summary is.
"""

from __future__ import annotations

from rich.console import Console
from rich.markup import escape
from rich.table import Table

from .markdown import _fmt

__all__ = ["print_summary"]


def print_summary(s: dict, job_steps: int, personality: str | None, out: Console) -> None:
    """The run's table and result lines. The job line only when the machine file has a job:
    a personality that drives the machine itself (an FS701 batch, a CLM program) says what
    happened in its own summary line, and "0 round(s), 0 command(s)" would say nothing."""
    t = Table(title=f"{escape(s['machine'])}: {s['simulated_s']:.3f} s simulated in {s['wall_s']:.2f} s ({s['realtime_factor']:.0f}x real time)")
    for col in ("axis", "state", "position", "max following error", "max speed"):
        t.add_column(col)
    for name, a in s["axes"].items():
        u, res = a["unit"], a.get("resolution")
        t.add_row(name, a["state"], _fmt(a["position"], u, res), _fmt(a["max_following_error"], u, res), _fmt(a["max_speed"], f"{u}/s", res))
    out.print(t)
    for warning in s.get("warnings") or ():
        out.print(f"[yellow]warning:[/yellow] {escape(warning)}")
    job = s["job"]
    device = s.get("device")
    if job_steps or job.get("failed"):
        state = f"failed: {job['failed']}" if job.get("failed") else "finished" if job["finished"] else "not finished"
        out.print(f"job: {state}, {job['rounds']} round(s), {len(job['events'])} command(s)", markup=False)
    elif personality is None:
        out.print("job: none (the machine file has no [[job.steps]])", markup=False)
    if device and device.get("headline"):  # a personality's one-line result (e.g. the FS701's batch)
        out.print(device["headline"], markup=False, soft_wrap=True)  # one line, for grep
    elif personality is not None and not job_steps:
        out.print(f"{personality}: the personality drove the machine (no job steps); its summary is in --json and --report",
                  markup=False, soft_wrap=True)
    for f in s["faults"]:
        out.print(f"[red]fault[/red] {escape(f)}", markup=True)
    out.print("[green]completed[/green]" if s["completed"] else "[red]not completed[/red]")
