"""The FS701 job's JSON in the names the issue fixes (`axisline run --json`).

    {"cuts": [{"target_lu", "actual_lu", "error_lu", "error_counts",
               "line_speed_lu_min", "max_pos_error_counts", ...}],
     "summary": {"count", "mean_error_lu", "max_abs_error_counts", "cuts_per_minute", ...}}

They sit at the top level of the run summary beside the machine's own keys; the full
per-cut measurement (material point, tolerance, mark offsets, ...) stays under "device".
"""

from __future__ import annotations

import math
from typing import Any


def _num(x: Any) -> float | None:
    return None if x is None or (isinstance(x, float) and not math.isfinite(x)) else x


def job_json(device: dict[str, Any]) -> dict[str, Any]:
    """Top-level "cuts" and "summary" from the FS701 personality's summary()."""
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
