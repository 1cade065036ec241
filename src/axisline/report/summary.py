"""The run summary a person and a program read after `Machine.run`: the machine, the result,
the job, every axis (with its resolution, so reports round to what a position means), the
device's own part, and the warnings a commissioning engineer must see.

    summary = run_summary(machine, result)     # = machine.summary(result)
    warnings = run_warnings(machine)           # = machine.warnings()

Kept out of machine.py (compiled, per-cycle code): this runs once per run.
"""

from __future__ import annotations

import math
from typing import Any

__all__ = ["run_summary", "run_warnings"]


def run_warnings(machine: Any) -> list[str]:
    """What a commissioning engineer must see after a run: a drive asked for more than it can
    do (the +-10 V command saturated, or beyond its speed limit), and linear axes with no
    stroke limit, with the travel they made (axes the device accounts for are left out)."""
    out = []
    limited = machine.device.limited_axes() if machine.device is not None else set()
    period = machine.period
    for name, u in machine.units.items():
        unit = u.config.unit
        if u.over_cycles:
            asked = (f"asked {u.peak_request:.6g} {unit}/s of a drive that reaches {u.reach:.6g} {unit}/s"
                     if abs(u.peak_request) > u.reach * (1.0 + 1e-9) else
                     f"held at the +-10 V limit ({u.peak_request:.6g} {unit}/s nominal): the loop wanted more than the drive gives")
            out.append(
                f"axis {name!r}: the drive command saturated in {u.over_cycles} cycle(s) ({u.over_cycles * period:.3f} s, "
                f"first at t = {u.first_over_cycle * period:.3f} s): {asked}; max following error "
                f"{u.max_following_error:.4g} {unit}"
            )
        travel = None if name in limited else _travel_warning(name, u)
        if travel is not None:
            out.append(travel)
    return out


def _travel_warning(name: str, u: Any) -> str | None:
    """A linear axis without a stroke limit (no software limits, no limit switch): its travel."""
    c = u.config
    if c.kind != "linear" or c.sw_limits_enabled or any(sw.kind == "limit" for sw in c.switches):
        return None
    if not u.travel_high >= u.travel_low:
        return None
    return (f"axis {name!r} travelled {u.travel_low:.6g} .. {u.travel_high:.6g} {c.unit} with no stroke limit "
            f"(sw_limits_enabled = false, no limit switch): check that the mechanics allow it")


def run_summary(machine: Any, result: Any) -> dict[str, Any]:
    """The run summary of `machine` after `result` (see the module docstring)."""
    m = machine
    axes = {}
    for name, u in m.units.items():
        ax = u.axis
        axes[name] = {
            "state": ax.state.name,
            "command_position": ax.command_position,
            "actual_position": ax.actual_position,
            "position": ax.position,
            "following_error": ax.following_error,
            "max_following_error": u.max_following_error,
            "max_speed": u.max_speed,
            "unit": u.config.unit,
            "resolution": 1.0 / u.config.counts_per_unit,  # one count: what a position means
            "error_id": ax.error_id,
            "error_text": ax.error_text,
        }
    return {
        "machine": m.config.machine.name,
        "file": m.source,
        "seed": m.seed,
        "cycle_us": m.clock.period_us,
        "cycles": result.cycles,
        "simulated_s": result.simulated_s,
        "wall_s": result.wall_s,
        "realtime_factor": (result.simulated_s / result.wall_s) if result.wall_s > 0 else math.inf,
        "completed": result.completed,
        "faults": result.faults,
        "job": {
            "steps": len(m.config.job.steps),
            "finished": m.job.finished,
            "failed": m.job.failed,
            "rounds": m.job.round,
            "events": [{"t": e.t, "step": e.step + 1, "text": e.text} for e in m.job.events],
        },
        "axes": axes,
        "warnings": run_warnings(m),
        "trace": {"samples": len(m.trace), "channels": list(m.trace.channels)} if m.trace else None,
        "device": m.device.summary() if m.device is not None else None,
    }
