"""Run report of the COMPAX personality: one record per master cycle, its JSON and plots, and
the curve plot of `axisline compax plot`.

    from axisline.devices.compax.report import CycleLog, write_report, plot_curve
    log = CycleLog(period=0.001)             # the personality feeds it every 1 ms cycle
    write_report(log.records, "out/run")     # compax_cycles.json + compax_label.png
    plot_curve("cam.json", 1, 600.0, "curve1.png")   # a curve of a saved cam memory

Records (`CycleRecord`, one per master cycle = one curve cycle of the master chain, counted
from the first master-cycle wrap after the start; the cycle in which the master started is
record 0 and may be partial):

=======================  =================================================================
field                    meaning
=======================  =================================================================
cycle                    index of the master cycle (0, 1, ...)
t_start, t_end           when it began and ended, s (simulated time of the 1 ms cycles)
curve                    S43, the curve in use at the end of the cycle
state                    cam state at the end of the cycle (camop.CamState value)
label                    S51 of the label accepted in this cycle, ‰ of the cycle (None: no label)
error_before             S52 of that label: its error before the correction, ‰
error_after              S52 of the next label accepted: the error left after the
                         correction (None until that label has been seen), ‰
error_before_units,      the same in master units (master related) or slave units
error_after_units        (slave related): ‰ · cycle / 1000
labels                   number of labels accepted in the cycle
label_ok                 O14 at the end of the cycle (False: a label was missing)
correction               correction applied during the cycle, ‰ (sign of the deviation)
tracking_error_max       largest |following error| of the slave during the cycle, slave units
o15_events, o16_events   [time s, value] of every change of O15 / O16 during the cycle
synchronous              O16 at the end of the cycle
=======================  =================================================================

"Label error after correction" is the error of the next label: in master related label
synchronisation a label's deviation is corrected before the next label arrives, so the next
label's S52 is what the correction left (one cycle of slip, printing jitter and the 100 µs
sampling of I14).
"""

from __future__ import annotations

import json
import math
import os
from collections import deque
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any, Iterable

import numpy as np

__all__ = [
    "CycleLog",
    "CycleRecord",
    "MAX_EVENTS_PER_CYCLE",
    "MAX_RECORDS",
    "converged_after",
    "curve_kinematics",
    "load_curve",
    "plot_curve",
    "plot_cycles",
    "write_report",
]

#: records kept (the newest); a long `serve` session does not grow without bound
MAX_RECORDS = 100_000
#: O15 / O16 changes kept per master cycle (a chattering O15 keeps its first ones)
MAX_EVENTS_PER_CYCLE = 1000


@dataclass
class CycleRecord:
    """One master cycle; see the module docstring."""

    cycle: int
    t_start: float
    t_end: float | None = None
    curve: int = 0
    state: str = ""
    label: float | None = None
    error_before: float | None = None
    error_after: float | None = None
    error_before_units: float | None = None
    error_after_units: float | None = None
    labels: int = 0
    label_ok: bool = False
    correction: float = 0.0
    tracking_error_max: float = 0.0
    o15_events: list[list[Any]] = field(default_factory=list)
    o16_events: list[list[Any]] = field(default_factory=list)
    synchronous: bool = False

    def as_dict(self) -> dict[str, Any]:
        return asdict(self)


class CycleLog:
    """Collects `CycleRecord`s from the per-cycle calls of the personality.

    Per 1 ms cycle: `label(...)` for every label accepted, `outputs(t, o15, o16)`,
    `tracking(fe)`, `correction(per_mille)`, then `wrap(t, ...)` for every master-cycle
    wrap (closes the current record and opens the next).
    """

    def __init__(self, maxlen: int = MAX_RECORDS) -> None:
        self.records: deque[CycleRecord] = deque(maxlen=maxlen)
        self.current: CycleRecord | None = None
        self._waiting: CycleRecord | None = None  # the last record with a label and no error_after yet
        self._o15: bool | None = None
        self._o16: bool | None = None

    def _open(self, t: float) -> CycleRecord:
        if self.current is None:
            self.current = CycleRecord(cycle=0, t_start=t)
        return self.current

    def start(self, t: float) -> None:
        """Open record 0 (the master started counting)."""
        self._open(t)

    def label(self, t: float, s51: float, s52: float, cycle_length: float) -> None:
        """A label was accepted: S51, S52 in ‰; cycle_length: master (or slave) cycle in units."""
        rec = self._open(t)
        units = s52 * cycle_length / 1000.0
        waiting = self._waiting
        if waiting is not None and waiting is not rec:
            waiting.error_after = s52
            waiting.error_after_units = units
        if rec.labels == 0:
            rec.label = s51
            rec.error_before = s52
            rec.error_before_units = units
            self._waiting = rec
        rec.labels += 1

    def outputs(self, t: float, o15: bool, o16: bool) -> None:
        rec = self.current
        if o15 != self._o15:
            self._o15 = o15
            if rec is not None and len(rec.o15_events) < MAX_EVENTS_PER_CYCLE:
                rec.o15_events.append([t, o15])
        if o16 != self._o16:
            self._o16 = o16
            if rec is not None and len(rec.o16_events) < MAX_EVENTS_PER_CYCLE:
                rec.o16_events.append([t, o16])

    def tracking(self, following_error: float) -> None:
        rec = self.current
        if rec is not None:
            fe = abs(following_error)
            if fe > rec.tracking_error_max:
                rec.tracking_error_max = fe

    def correction(self, per_mille: float) -> None:
        rec = self.current
        if rec is not None and per_mille:
            rec.correction += per_mille

    def wrap(self, t: float, *, curve: int, state: str, label_ok: bool, synchronous: bool) -> None:
        """The master cycle ended at t: close the record, open the next."""
        rec = self._open(t)
        rec.t_end = t
        rec.curve = curve
        rec.state = state
        rec.label_ok = label_ok
        rec.synchronous = synchronous
        self.records.append(rec)
        self.current = CycleRecord(cycle=rec.cycle + 1, t_start=t)

    def as_list(self) -> list[dict[str, Any]]:
        return [r.as_dict() for r in self.records]


def converged_after(records: Iterable[CycleRecord | dict[str, Any]], tolerance: float) -> int | None:
    """Index (cycle) of the first record from which every label error before correction stays
    within ±tolerance ‰ (records without a label are skipped); None if it never does."""
    found: int | None = None
    for r in records:
        d = r if isinstance(r, dict) else r.as_dict()
        e = d.get("error_before")
        if e is None:
            continue
        if abs(e) <= tolerance:
            if found is None:
                found = d["cycle"]
        else:
            found = None
    return found


# ---------------------------------------------------------------------------------------
# report files


def plot_cycles(records: Iterable[CycleRecord | dict[str, Any]], path: str | os.PathLike[str], *,
                title: str = "COMPAX label synchronisation", window: float | None = None,
                tracking_limit: float | None = None) -> Path:
    """PNG: label error before / after correction (‰) and the slave's largest tracking error per
    master cycle. ``window``: the label window ±M_f in ‰ (drawn as a band); ``tracking_limit``:
    P79 (O15's limit), drawn as a line."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    from axisline.kernel import atomic_open

    rows = [r if isinstance(r, dict) else r.as_dict() for r in records]
    n = np.array([r["cycle"] for r in rows], dtype=float)

    def column(key: str) -> np.ndarray:
        return np.array([math.nan if r.get(key) is None else float(r[key]) for r in rows], dtype=float)

    fig = Figure(figsize=(9.0, 7.0))
    FigureCanvasAgg(fig)
    ax1, ax2, ax3 = fig.subplots(3, 1, sharex=True)
    if window:
        ax1.axhspan(-window, window, color="tab:green", alpha=0.08, label=f"label window ±{window:.4g} ‰")
    ax1.plot(n, column("error_before"), "o-", label="before correction (S52)", linewidth=1.2, markersize=4)
    ax1.plot(n, column("error_after"), "s--", label="after correction (next label)", linewidth=1.0, markersize=3)
    ax1.axhline(0.0, color="k", linewidth=0.6)
    ax1.set_ylabel("label error [‰]")
    ax1.grid(True, alpha=0.3)
    ax1.legend(loc="best", fontsize=8)
    ax2.bar(n, column("correction"), width=0.6, color="tab:purple", alpha=0.7)
    ax2.set_ylabel("correction\napplied [‰]")
    ax2.grid(True, alpha=0.3)
    ax3.plot(n, column("tracking_error_max"), "d-", color="tab:red", linewidth=1.0, markersize=3,
             label="max |tracking error|")
    if tracking_limit is not None:
        ax3.axhline(tracking_limit, color="tab:orange", linestyle=":", label=f"P79 = {tracking_limit:g} (O15)")
    ax3.set_ylabel("tracking error\n[slave units]")
    ax3.set_xlabel("master cycle")
    ax3.grid(True, alpha=0.3)
    ax3.legend(loc="best", fontsize=8)
    fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    out = Path(path)
    out.parent.mkdir(parents=True, exist_ok=True)
    with atomic_open(out, "wb") as f:
        fig.savefig(f, format="png", dpi=90)
    return out


def write_report(records: Iterable[CycleRecord | dict[str, Any]], out_dir: str | os.PathLike[str], *,
                 status: dict[str, Any] | None = None, title: str = "COMPAX label synchronisation",
                 window: float | None = None, tracking_limit: float | None = None) -> list[Path]:
    """Write ``compax_cycles.json`` (the records, plus the status values given) and
    ``compax_label.png`` into out_dir; returns the files written."""
    from axisline.kernel import atomic_write_text

    rows = [r if isinstance(r, dict) else r.as_dict() for r in records]
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    doc = {"cycles": rows}
    if status is not None:
        doc["status"] = status
    js = out / "compax_cycles.json"
    atomic_write_text(js, json.dumps(doc, indent=1, default=_json_default) + "\n")
    png = plot_cycles(rows, out / "compax_label.png", title=title, window=window, tracking_limit=tracking_limit)
    return [js, png]


def _json_default(value: Any) -> Any:
    if isinstance(value, (np.floating, np.integer)):
        return value.item()
    if isinstance(value, Path):
        return str(value)
    raise TypeError(f"not JSON serialisable: {value!r}")


# ---------------------------------------------------------------------------------------
# curve plot (axisline compax plot)


def load_curve(source: Any, number: int = 1) -> Any:
    """A `curves.CurveRecord` from a CamMemory, a CurveRecord, a saved cam memory (.json) or a
    ``master,slave`` CSV (taken as curve ``number``; non-equidistant points are resampled at
    the number of rows)."""
    from axisline.devices.compax.cammemory import CamMemory
    from axisline.devices.compax.curves import CurveRecord, curve_from_csv, read_curve

    if isinstance(source, CurveRecord):
        return source
    if isinstance(source, CamMemory):
        return read_curve(source, number, valid=False)
    path = Path(os.fspath(source))
    if path.suffix.lower() == ".csv":
        from axisline.motion.cam import PointTable

        table = PointTable.from_csv(path)
        points = None if table.equidistant_step is not None else len(table.master)
        return curve_from_csv(path, number, points=points)
    return read_curve(CamMemory.load(path), number, valid=False)


def curve_kinematics(record: Any, master_speed: float, *, p36: float = 1.0) -> dict[str, np.ndarray]:
    """The curve as COMPAX runs it at a constant master speed (master units/s): set points
    equidistant over M_T, linear interpolation (compax.md §2.7.2). Returns arrays

    * ``master``, ``slave``: the set points (slave = P36 · S_T · F),
    * ``velocity``: the slave speed on each interval between set points (constant there),
      at the interval's middle ``velocity_at``,
    * ``acceleration``: the mean acceleration between neighbouring intervals (the speed
      step at a set point spread over one interval's time), at the set points
      ``acceleration_at`` (the interpolated curve itself has its speed steps there).
    """
    pts = np.asarray(record.set_points, dtype=float)
    n = len(pts)
    mt = float(record.master_cycle)
    master = np.linspace(0.0, mt, n)
    slave = pts * float(record.slave_cycle) * float(p36)
    dx = mt / (n - 1)
    vm = float(master_speed)
    slope = np.diff(slave) / dx  # slave units per master unit
    velocity = slope * vm
    dt = dx / abs(vm) if vm else math.inf
    if len(velocity) > 1:
        # an open curve repeats: the speed step at the cycle end joins the last interval to the first
        acc_inner = np.diff(velocity) / dt
        closing = (velocity[0] - velocity[-1]) / dt
        acceleration = np.concatenate(([closing], acc_inner, [closing]))
    else:
        acceleration = np.zeros(2)
    return {
        "master": master,
        "slave": slave,
        "velocity_at": master[:-1] + dx / 2.0,
        "velocity": velocity,
        "acceleration_at": master,
        "acceleration": acceleration,
    }


def plot_curve(source: Any, curve_number: int, master_speed: float, path: str | os.PathLike[str], *,
               p36: float = 1.0, title: str | None = None) -> Path:
    """PNG of curve ``curve_number`` of ``source`` (a CamMemory, a saved cam memory file .json,
    a CurveRecord or a master,slave CSV): slave position, velocity and acceleration over one
    master cycle at ``master_speed`` (master units/s), as the cam controller interpolates it.
    The velocity and acceleration peaks are written into the panel titles."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    from axisline.kernel import atomic_open

    record = load_curve(source, curve_number)
    k = curve_kinematics(record, master_speed, p36=p36)
    fig = Figure(figsize=(8.0, 7.2))
    FigureCanvasAgg(fig)
    ax1, ax2, ax3 = fig.subplots(3, 1, sharex=True)
    ax1.plot(k["master"], k["slave"], linewidth=1.2, marker="." if len(k["master"]) <= 60 else None)
    ax1.set_ylabel("slave position")
    ax1.grid(True, alpha=0.3)
    v = k["velocity"]
    # constant speed on each interval: drawn as steps between the set points
    ax2.step(k["master"], np.append(v, v[-1]), where="post", linewidth=1.2, color="tab:orange")
    ax2.set_ylabel("slave velocity /s")
    ax2.set_title(f"max |v| = {np.max(np.abs(v)):.6g}/s", fontsize=8, loc="right")
    ax2.grid(True, alpha=0.3)
    a = k["acceleration"]
    ax3.plot(k["acceleration_at"], a, linewidth=1.0, color="tab:red")
    ax3.set_ylabel("slave acceleration /s²\n(mean between set points)")
    ax3.set_title(f"max |a| = {np.max(np.abs(a)):.6g}/s²", fontsize=8, loc="right")
    ax3.set_xlabel("master position")
    ax3.grid(True, alpha=0.3)
    kind = "open" if record.open else "closed"
    fig.suptitle(title or (f"curve {curve_number}: M_T = {record.master_cycle:g}, S_T = {record.slave_cycle:g}, "
                           f"{record.n_points} set points ({kind}), master speed {float(master_speed):g}/s"),
                 fontsize=9)
    fig.tight_layout()
    out = Path(path)
    out.parent.mkdir(parents=True, exist_ok=True)
    with atomic_open(out, "wb") as f:
        fig.savefig(f, format="png", dpi=100)
    return out
