"""Cam tables: point tables, cubic splines, scaled curves, and the cam editor's checks.

    from axisline.motion.cam import PointTable, SplineTable, ScaledCurve, check, plot_cam
    table = PointTable.equidistant([0.0, 10.0, 30.0, 60.0, 90.0, 100.0], master_period=360.0)
    s, ds, dds, ddds = table.eval(90.0)          # hot path: O(1), builds no containers
    report = check(table, master_speed=720.0, v_max=500.0)

Every table implements `axisline.motion.curve.CamCurve`: `eval(x)` over one master cycle
0 <= x <= master_period, `at(x)` for any master position (open curves add their slave
travel per cycle).

Point tables (`PointTable`)
---------------------------
Master positions strictly increasing, the first 0 and the last the master cycle. Between
points the slave moves linearly, so ds is constant per interval and the higher derivatives
are 0 inside the intervals (the velocity steps at a point; the curve's acceleration there
is an impulse this model does not report). At a point the derivatives are those of the
interval that starts there. Equidistant tables (COMPAX set points, compax.md §2.7.2
[DERIVED]: point k at k·M_T/(N−1)) find their interval in O(1) from int(x / step);
other tables bisect (O(log n)). An equidistant table is recognised whatever constructor
built it.

COMPAX set points are 24-bit fractions of the slave cycle (compax.md §6.2 item 3,
formula 14: Fx = Ix / 2²³, two's complement, sign bit then 2⁻¹ … 2⁻²³); `encode_fraction`
and `decode_fraction` convert, `PointTable.from_fractions` builds the curve. The largest
fraction 0x7FFFFF (0.99999988) stands for the full slave cycle (compax.md §2.7.2: "last set
point of open monotone curves must be 0.9999999 (= S_T)", §4 [DERIVED] "treat F=0x7FFFFF
as exactly 1.0"), so an open curve from 0 to 0x7FFFFF moves exactly S_T per cycle and
does not drift (§2.20).

Splines (`SplineTable`)
-----------------------
A cubic spline through the points, C2 (position, velocity and acceleration continuous),
evaluated from its piecewise polynomial with analytic derivatives. End conditions:

* ``periodic=True``: ds and dds at the cycle end equal those at the start, so the curve
  continues C2 into the next cycle. For a closed curve s wraps too; an open curve (last
  slave value != first) continues with its slave offset per cycle - the usual choice for a
  feed that repeats.
* ``periodic=False``: "natural" (dds = 0 at both ends) unless ``end_slopes=(ds0, ds1)``
  is given ("clamped": the slave gradients at the start and end are prescribed, e.g. 0 for
  a rest at both ends, or the neighbouring curve's gradient when curves are linked).
  Natural is the default because it needs no extra numbers and adds no acceleration at
  the ends.

Scaling (`ScaledCurve`)
-----------------------
``master_scale`` stretches the master cycle (the scaled curve covers master_scale × the
original cycle), ``slave_scale`` multiplies the slave values (COMPAX P36, "slave set point
= P36 · s_curve", compax.md §4 [DERIVED]), ``slave_offset`` is added. COMPAX P35 multiplies
the master *position* in the master channel (compax.md §1.3); the same curve seen through
P35 is ``ScaledCurve(curve, master_scale=1 / P35)`` for P35 > 0.

Checks and plots
----------------
`check` samples one master cycle at a constant master speed (plus the points where the
extremes of a table can lie), converts to time units with the rules of `curve.py`
(v = ds·vm, a = dds·vm² + ds·am, j = ddds·vm³ + 3·dds·vm·am) and compares with slave
limits; `plot_cam` draws position, velocity, acceleration and jerk to a PNG. A curve may
offer ``check_points() -> ndarray`` (master positions where its derivative extremes can
lie: knots, interior maxima of ds); `check` samples those too, so a table's extremes are
found exactly. Curves without it are checked on the grid alone.

CSV
---
``master,slave`` header, one point per line, numbers written with Python's shortest
round-trip repr so a save/load round trip is exact. Saving is atomic
(`axisline.kernel.atomic`). Reading rejects, with the line, the field, the value and what
is allowed: a wrong header, a row without exactly two fields, a value that is not a finite
number, a master position that does not increase, a first master position other than 0,
fewer than 2 points, more than ``max_points`` points.

Modules
-------
camtable.py (point tables, scaling, fractions, the modulo master, CSV), spline.py (splines),
camcheck.py (check and plot); this module gathers them.
"""

from __future__ import annotations

from axisline.motion.camcheck import CamCheck, check, plot_cam
from axisline.motion.camtable import (
    DEFAULT_MAX_POINTS,
    FRACTION_ONE,
    ModuloMaster,
    PointTable,
    ScaledCurve,
    decode_fraction,
    encode_fraction,
)
from axisline.motion.spline import SplineTable

__all__ = [
    "DEFAULT_MAX_POINTS",
    "FRACTION_ONE",
    "CamCheck",
    "ModuloMaster",
    "PointTable",
    "ScaledCurve",
    "SplineTable",
    "check",
    "decode_fraction",
    "encode_fraction",
    "plot_cam",
]
