"""The cam editor's check and plot of a cam curve: `check` (peak speed, acceleration and jerk
at a master speed against slave limits, `CamCheck`) and `plot_cam`. `axisline.motion.cam` is
the place to import them from; its docstring describes them.
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass

import numpy as np

from axisline.kernel.atomic import atomic_open
from axisline.motion.curve import CamCurve

__all__ = ["CamCheck", "check", "plot_cam"]

# ---------------------------------------------------------------------------------------
# cam editor check and plot


@dataclass(frozen=True, slots=True)
class CamCheck:
    """Slave motion over one master cycle at a constant master speed (time units).

    ``max_*`` are absolute values; ``*_at`` the master position (within the cycle) where
    they occur. ``*_exceeded`` is False when no limit was given. ``max_master_speed`` is the
    largest |master speed| up to which every given limit holds (at the same master
    acceleration); ``inf`` when no limit binds.
    """

    master_speed: float
    master_acceleration: float
    max_velocity: float
    max_velocity_at: float
    max_acceleration: float
    max_acceleration_at: float
    max_jerk: float
    max_jerk_at: float
    v_max: float | None
    a_max: float | None
    j_max: float | None
    velocity_exceeded: bool
    acceleration_exceeded: bool
    jerk_exceeded: bool
    max_master_speed: float

    @property
    def within_limits(self) -> bool:
        return not (self.velocity_exceeded or self.acceleration_exceeded or self.jerk_exceeded)


# A limit counts as exceeded only beyond this relative margin, so that running exactly at
# `max_master_speed` (computed in floating point) passes.
_LIMIT_MARGIN = 1e-9


def _check_limit(name: str, value: float | None) -> float | None:
    if value is None:
        return None
    value = float(value)
    if not (math.isfinite(value) and value > 0):
        raise ValueError(f"{name} {value!r} not allowed: a limit must be a finite number > 0 (or None)")
    return value


def _sample_positions(curve: CamCurve, n: int) -> np.ndarray:
    period = curve.master_period
    grid = np.linspace(0.0, period, n)
    extra = getattr(curve, "check_points", None)
    if extra is not None:
        points = np.asarray(extra(), dtype=float)
        points = points[(points >= 0.0) & (points <= period)]
        grid = np.concatenate([grid, points])
    return np.unique(grid)


def _first_speed_over_jerk(ddds: np.ndarray, dds: np.ndarray, am: float, j_max: float) -> float:
    """Smallest w > 0 with |ddds·w³ + 3·dds·am·w| = j_max over all samples (inf if none)."""
    p = ddds
    q = 3.0 * dds * am
    best = math.inf
    linear = (p == 0.0) & (q != 0.0)
    if np.any(linear):
        best = min(best, float(np.min(j_max / np.abs(q[linear]))))
    cubic = p != 0.0
    if not np.any(cubic):
        return best
    if am == 0.0:
        return min(best, float(np.min(np.cbrt(j_max / np.abs(p[cubic])))))
    pc, qc = p[cubic], q[cubic]
    roots = []
    for sign in (1.0, -1.0):
        # w³ + (q/p)·w − sign·j/p = 0 as a batch of companion matrices
        comp = np.zeros((pc.size, 3, 3))
        comp[:, 0, 1] = -qc / pc
        comp[:, 0, 2] = sign * j_max / pc
        comp[:, 1, 0] = 1.0
        comp[:, 2, 1] = 1.0
        roots.append(np.linalg.eigvals(comp))
    r = np.concatenate(roots, axis=1)
    real = np.abs(r.imag) <= 1e-9 * np.maximum(1.0, np.abs(r.real))
    positive = real & (r.real > 0.0)
    if np.any(positive):
        best = min(best, float(np.min(r.real[positive])))
    return best


def check(
    curve: CamCurve,
    master_speed: float,
    master_acceleration: float = 0.0,
    n: int = 2001,
    *,
    v_max: float | None = None,
    a_max: float | None = None,
    j_max: float | None = None,
) -> CamCheck:
    """What the slave does over one master cycle at ``master_speed`` (master units / s).

    Samples ``n`` equally spaced master positions plus the curve's ``check_points()`` (the
    knots of a table and, for a spline, the interior extremes of ds), so the extremes of a
    table are found exactly, and those of other curves to the sampling resolution.
    """
    vm = float(master_speed)
    am = float(master_acceleration)
    if not (math.isfinite(vm) and math.isfinite(am)):
        raise ValueError(f"master speed {master_speed!r} / acceleration {master_acceleration!r} must be finite")
    if n < 2:
        raise ValueError(f"n {n!r} not allowed: sample at least 2 master positions")
    v_lim = _check_limit("v_max", v_max)
    a_lim = _check_limit("a_max", a_max)
    j_lim = _check_limit("j_max", j_max)

    x = _sample_positions(curve, n)
    _, ds, dds, ddds = (np.asarray(arr, dtype=float) for arr in curve.eval_array(x))
    v = np.abs(ds * vm)
    a = np.abs(dds * vm * vm + ds * am)
    j = np.abs(ddds * vm**3 + 3.0 * dds * vm * am)
    iv, ia, ij = int(np.argmax(v)), int(np.argmax(a)), int(np.argmax(j))

    def exceeded(peak: float, limit: float | None) -> bool:
        return limit is not None and peak > limit * (1.0 + _LIMIT_MARGIN)

    speed = math.inf
    if v_lim is not None:
        peak = float(np.max(np.abs(ds)))
        if peak > 0.0:
            speed = min(speed, v_lim / peak)
    if a_lim is not None:
        base = ds * am
        if np.any(np.abs(base) > a_lim):
            speed = 0.0  # the master acceleration alone breaks the limit
        else:
            with np.errstate(divide="ignore", invalid="ignore"):
                w2 = np.where(dds > 0.0, (a_lim - base) / dds, np.where(dds < 0.0, (a_lim + base) / -dds, np.inf))
            speed = min(speed, float(np.sqrt(np.min(w2))))
    if j_lim is not None:
        speed = min(speed, _first_speed_over_jerk(ddds, dds, am, j_lim))

    return CamCheck(
        master_speed=vm,
        master_acceleration=am,
        max_velocity=float(v[iv]),
        max_velocity_at=float(x[iv]),
        max_acceleration=float(a[ia]),
        max_acceleration_at=float(x[ia]),
        max_jerk=float(j[ij]),
        max_jerk_at=float(x[ij]),
        v_max=v_lim,
        a_max=a_lim,
        j_max=j_lim,
        velocity_exceeded=exceeded(float(v[iv]), v_lim),
        acceleration_exceeded=exceeded(float(a[ia]), a_lim),
        jerk_exceeded=exceeded(float(j[ij]), j_lim),
        max_master_speed=speed,
    )


def plot_cam(
    curve: CamCurve,
    master_speed: float,
    path: str | os.PathLike[str],
    *,
    n: int = 1001,
    title: str | None = None,
    jerk: bool = True,
    limits: dict[str, float | None] | None = None,
    unit: str = "",
) -> list[tuple[str, float | None]]:
    """Slave position, velocity, acceleration (and jerk) over one master cycle, as a PNG.

    Velocity and the rest are in time units at the constant ``master_speed``; ``limits``
    (``v_max``, ``a_max``, ``j_max`` of the slave axis) are drawn as dashed lines at +-limit on
    their panels, ``unit`` (the slave's) labels the axes; returns the panels drawn as (label,
    limit). Drawn with
    matplotlib's Agg canvas directly (no pyplot, no global backend switch); the file is
    written atomically.
    """
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    vm = float(master_speed)
    x = _sample_positions(curve, n)
    s, ds, dds, ddds = (np.asarray(arr, dtype=float) for arr in curve.eval_array(x))
    u = unit or "units"
    lim = limits or {}
    rows: list[tuple[str, np.ndarray, float | None]] = [
        (f"slave position\n[{u}]", s, None),
        (f"slave velocity\n[{u}/s]", ds * vm, lim.get("v_max")),
        (f"slave acceleration\n[{u}/s²]", dds * vm * vm, lim.get("a_max")),
    ]
    if jerk:
        rows.append((f"slave jerk\n[{u}/s³]", ddds * vm**3, lim.get("j_max")))
    fig = Figure(figsize=(8.0, 2.2 * len(rows) + 0.6))
    FigureCanvasAgg(fig)
    axes = fig.subplots(len(rows), 1, sharex=True)
    for ax, (label, values, limit) in zip(np.atleast_1d(axes), rows):
        # step-like curves (a linear table's velocity) read best as drawn lines between samples
        ax.plot(x, values, linewidth=1.2)
        if limit is not None:  # the axis' limit, both signs: where the cam asks too much
            for sign in (1.0, -1.0):
                ax.axhline(sign * limit, color="tab:red", linestyle="--", linewidth=0.9,
                           label="axis limit" if sign > 0 else None)
            ax.legend(loc="upper right", fontsize=7)
        ax.set_ylabel(label)
        ax.grid(True, alpha=0.3)
    np.atleast_1d(axes)[-1].set_xlabel("master position")
    fig.suptitle(title or f"{curve!r} at master speed {vm:g}/s", fontsize=9)
    fig.tight_layout()
    with atomic_open(path, "wb") as file:
        fig.savefig(file, format="png", dpi=100)
    return [(label, limit) for label, _, limit in rows]
