"""Fields the sweep computes beside a case's run: for an FS701, the computed cut envelope.

    computed_fields(machine)  ->  {"envelope": {...}} for personality "fs701", {} otherwise

The envelope is `axisline fs701 envelope`'s (devices/fs701/envelope.py) for the case's own
parameter set and shear, at the case's line speed: so the report can put the simulated
feasible region (no Error 02) beside the computed one, case by case.

    envelope.line_speed_lu_min   the line's top speed: the largest of material.speed and the
                                 material.profile speeds, x 60 (LU = the material's unit)
    envelope.cut_time_s          device.shear.cut_time (Ready to Cut -> Cut completed)
    envelope.min_length_lu       the shortest length at that speed (None: the travel exceeds the stroke)
    envelope.travel_lu           the carriage's forward travel
    envelope.limiting_factor     what limits the cycle
    envelope.feasible            the case's Cutting Length at that speed (feasible())

Decisions
1. (issue: "the report puts the simulated feasible region beside `axisline fs701 envelope`'s
   computed one") the line speed of the comparison is the material line's top speed (its
   profile's largest): the envelope is a constant-speed judgement, and the sweep's example
   runs the line at one speed. A virtual line (no [material]) has no envelope fields. Test:
   test_fs701_envelope.py::test_simulated_boundary_agrees_with_the_envelope.
"""

from __future__ import annotations

import math
from typing import Any

__all__ = ["computed_fields"]


def computed_fields(machine: Any) -> dict[str, Any]:
    if machine.device is None or machine.config.machine.personality != "fs701" or machine.config.material is None:
        return {}
    from axisline.devices.fs701.envelope import envelope, feasible

    mat = machine.config.material
    top = max([abs(mat.speed)] + [abs(p.speed) for p in mat.profile])
    v = top * 60.0
    settings = machine.device.settings
    cut_time = float(machine.device.config.shear.cut_time)
    pt = envelope(settings, [v], cut_time)[0]
    ok, _ = feasible(settings, settings.cutting_length, v, cut_time)
    return {"envelope": {
        "line_speed_lu_min": v,
        "cut_time_s": cut_time,
        "min_length_lu": pt.min_length if math.isfinite(pt.min_length) else None,
        "travel_lu": pt.travel,
        "limiting_factor": pt.limiting_factor,
        "feasible": bool(ok),
    }}
