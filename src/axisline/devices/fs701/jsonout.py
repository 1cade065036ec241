"""The FS701 job's JSON in the names the issue fixes (`axisline run --json`).

    {"cuts": [{"target_lu", "actual_lu", "error_lu", "error_counts",
               "line_speed_lu_min", "max_pos_error_counts", ...}],
     "summary": {"count", "mean_error_lu", "max_abs_error_counts", "cuts_per_minute", ...}}

They sit at the top level of the run summary beside the machine's own keys; the full
per-cut measurement (material point, tolerance, mark offsets, ...) stays under "device".
The names are shared with the CLM1.4's flying cutoff: the code is `axisline.report.cuts`.
"""

from __future__ import annotations

from axisline.report.cuts import job_json

__all__ = ["job_json"]
