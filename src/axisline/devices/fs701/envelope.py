"""FS701 cut envelope: which cutting lengths can be cut at which line speed (manual §10).

Manual §10: "Flying shears have physical limitations with respect to short cutting length at
high line speeds ... When we would need to cut pieces of 1 meter length at a line speed of 60
meters/minute, this means we must execute one cut every second. If our saw blade would take one
full second to perform the cut, it is easy to understand that this cannot work". motrona sells a
PC tool for this judgement (not documented); this module is our equivalent, computed with the
cut cycle exactly as cutter.py plans it (spec §2.3, §4):

    V line speed (LU/s), R = 1 + Sync Rate/100, v_s = R V
    forward ramp       tau_a = v_s / Acceleration 1        carriage travel v_s tau_a / 2
                       (the S-ramp has the same duration and travel, peak 1.25 x the setting)
    synchronous        t_sync = Synchron Time + cut time (Ready to Cut -> Cut completed)
    forward brake      t_d = v_s / Deceleration 1          travel v_s t_d / 2
    travel             x = v_s tau_a / 2 + v_s t_sync + v_s t_d / 2   (from home)
    return             the cutter's own return profile (Acceleration 2 / Deceleration 2, S or
                       linear) over x at the maximum return speed (Abs. Return Speed, or Rel.
                       Return Speed x V, never below the reverse jog speed)
    cycle              T = tau_a + t_sync + t_d + t_return

Consecutive approach starts are (L + Tool Width) / V apart, and the cutter raises Error 02
when a start point comes before the carriage is home (C3), so a length L is possible iff
T <= (L + Tool Width) / V:   L_min(V) = V T - Tool Width. The travel x does not depend on L;
it must stay inside Maximum Position - home (the configured stroke; the FS701 does not stop at
Maximum Position in automatic operation, manual §4.3.3, so this is a mechanical check).

Not included: the Gap motion (Start Gap), the Cut Window settling (Sync Samples cycles) and the
control-cycle quantisation (a few ms): keep a small margin.

Reuse: the ramp geometry (`approach_geometry`), the return speed limit (`v_return_max`) and
the return profile (`return_profile`) are the cutter's own functions, so a change of the cut
cycle changes the envelope too.

CLI (wired by cli.py): `axisline fs701 envelope PARAMS [--png OUT] [--cut-time S] [--speeds A,B,..]`
-> `envelope_command(params_file, out_png, cut_time, speeds)`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Iterable, NamedTuple

from axisline.motion.profiles import State

from .cut_settings import CutterSettings, approach_geometry, return_profile, v_return_max

__all__ = ["EnvelopePoint", "CycleBudget", "cycle_budget", "envelope", "feasible", "plot_envelope", "envelope_command"]


class EnvelopePoint(NamedTuple):
    line_speed: float  # LU/min
    min_length: float  # LU (inf: no length, the travel exceeds the stroke)
    travel: float  # LU, forward carriage excursion from home
    limiting_factor: str


@dataclass(frozen=True)
class CycleBudget:
    """The time budget of one cut cycle at one line speed (s, LU, LU/s)."""

    line_speed: float  # LU/s
    t_acc: float
    t_sync: float
    t_dec: float
    t_return: float
    travel: float
    v_return: float
    stroke: float  # Maximum Position - home

    @property
    def t_cycle(self) -> float:
        return self.t_acc + self.t_sync + self.t_dec + self.t_return

    @property
    def travel_ok(self) -> bool:
        return self.travel <= self.stroke + 1e-9

    @property
    def limiting_factor(self) -> str:
        if not self.travel_ok:
            return "travel (Maximum Position)"
        parts = {
            "acceleration (Acceleration 1)": self.t_acc,
            "synchronous / cut time": self.t_sync,
            "deceleration (Deceleration 1)": self.t_dec,
            "return (return speed, Acc./Dec. 2)": self.t_return,
        }
        return max(parts, key=parts.get)  # type: ignore[arg-type]


def _settings(settings: Any) -> CutterSettings:
    return settings if isinstance(settings, CutterSettings) else CutterSettings.from_parameters(settings)


def cycle_budget(settings: Any, line_speed: float, cut_time: float = 0.0, home: float = 0.0) -> CycleBudget:
    """The cut cycle at `line_speed` (LU/min); `cut_time` s from Ready to Cut to Cut completed;
    `home` the home position relative to Zero (LU)."""
    s = _settings(settings)
    V = max(float(line_speed), 0.0) / 60.0
    stroke = float(s.maximum_position) - home
    if V <= 0.0:
        return CycleBudget(0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, stroke)
    _, tau_a, s_sync, _ = approach_geometry(s, V)
    vs = s.sync_ratio * V
    t_sync = s.synchron_time / 1000.0 + max(float(cut_time), 0.0)
    t_dec = vs / max(float(s.deceleration_1), 1.0)
    travel = s_sync + vs * t_sync + 0.5 * vs * t_dec
    v_r = v_return_max(s, V)
    ret = return_profile(s, State(travel, 0.0, 0.0), 0.0, v_r)
    t_ret = 0.0 if ret is None else ret.duration
    return CycleBudget(V, tau_a, t_sync, t_dec, t_ret, travel, v_r, stroke)


def _min_length(b: CycleBudget, s: CutterSettings) -> float:
    if b.line_speed <= 0.0:
        return 0.0
    if not b.travel_ok:
        return math.inf
    return max(b.line_speed * b.t_cycle - s.tool_width, 0.0)


def default_speeds(settings: Any, n: int = 20) -> list[float]:
    s = _settings(settings)
    return [s.max_line_speed * (i + 1) / n for i in range(n)]


def envelope(settings: Any, speeds: Iterable[float] | None = None, cut_time: float = 0.0,
             home: float = 0.0) -> list[EnvelopePoint]:
    """(line speed LU/min, shortest length LU, carriage travel LU, limiting factor) per speed."""
    s = _settings(settings)
    out = []
    for v in (default_speeds(s) if speeds is None else speeds):
        b = cycle_budget(s, v, cut_time, home)
        factor = "line stands" if b.line_speed <= 0.0 else b.limiting_factor
        out.append(EnvelopePoint(float(v), _min_length(b, s), b.travel, factor))
    return out


def feasible(settings: Any, length: float, line_speed: float, cut_time: float = 0.0,
             home: float = 0.0) -> tuple[bool, str]:
    """Can pieces of `length` LU be cut at `line_speed` LU/min? (ok, reason)."""
    s = _settings(settings)
    b = cycle_budget(s, line_speed, cut_time, home)
    if b.line_speed <= 0.0:
        return True, "line stands: no cycle-time limit"
    if not b.travel_ok:
        return False, (f"carriage travel {b.travel:.1f} LU exceeds the stroke {b.stroke:.1f} LU "
                       f"(Maximum Position)")
    period = (float(length) + s.tool_width) / b.line_speed
    detail = (f"cycle {b.t_cycle:.3f} s = accel {b.t_acc:.3f} + sync/cut {b.t_sync:.3f} + decel "
              f"{b.t_dec:.3f} + return {b.t_return:.3f} (at {b.v_return * 60:.0f} LU/min); one piece "
              f"passes in {period:.3f} s; travel {b.travel:.1f} LU")
    if b.t_cycle <= period:
        return True, "feasible: " + detail
    return False, (f"not feasible (Error 02, limited by {b.limiting_factor}; shortest length "
                   f"{_min_length(b, s):.1f} LU): " + detail)


def plot_envelope(settings: Any, path: str | Path, speeds: Iterable[float] | None = None,
                  lengths: Iterable[tuple[float, float]] | None = None, cut_time: float = 0.0) -> Path:
    """Shortest cut length over line speed, the feasible region shaded; `lengths`: optional
    (line speed LU/min, length LU) points to mark (green feasible, red not)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    s = _settings(settings)
    if speeds is None:
        speeds = [s.max_line_speed * i / 100 for i in range(1, 101)]
    pts = envelope(s, speeds, cut_time)
    v = [p.line_speed for p in pts]
    lmin = [p.min_length for p in pts]
    finite = [x for x in lmin if math.isfinite(x)]
    pts_l = list(lengths or [])
    top = max(finite + [pl for _, pl in pts_l] + [float(s.cutting_length), 1.0]) * 1.3
    lplot = [x if math.isfinite(x) else top for x in lmin]
    fig, ax = plt.subplots(figsize=(9, 5), constrained_layout=True)
    ax.fill_between(v, lplot, top, color="tab:green", alpha=0.2, label="feasible")
    ax.fill_between(v, 0, lplot, color="tab:red", alpha=0.08, label="Error 02 / travel")
    ax.plot(v, lplot, color="tab:green", linewidth=1.5, label="shortest cut length")
    for ls, ll in pts_l:
        ok, _ = feasible(s, ll, ls, cut_time)
        ax.plot([ls], [ll], "o" if ok else "x", color="tab:green" if ok else "tab:red", markersize=8)
    ax.set_xlim(0, max(v) if v else 1)
    ax.set_ylim(0, top)
    ax.set_xlabel("line speed [LU/min]")
    ax.set_ylabel("cut length [LU]")
    ax.grid(True, alpha=0.3)
    ax.legend(loc="upper left", fontsize=8)
    ax.set_title(f"FS701 cut envelope (cut time {cut_time:g} s, Synchron Time {s.synchron_time} ms)")
    out = Path(path)
    out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out, dpi=90)
    plt.close(fig)
    return out


def _parse_speeds(text: str) -> list[float]:
    return [float(x) for x in text.replace(";", ",").split(",") if x.strip()]


def envelope_command(params_file: Path, out_png: Path | None = None, cut_time: float | None = None,
                     speeds: str | None = None) -> int:
    """`axisline fs701 envelope PARAMS`: prints the envelope table; 0 ok, 2 bad input."""
    from .paramfile import ParamFileError, load_parameters

    try:
        params = load_parameters(params_file)
    except ParamFileError as exc:
        print(f"error: {exc}")
        return 2
    try:
        sp = _parse_speeds(speeds) if speeds else None
    except ValueError:
        print(f"error: --speeds must be comma separated numbers (LU/min), got {speeds!r}")
        return 2
    s = _settings(params)
    ct = float(cut_time or 0.0)
    pts = envelope(s, sp, ct)
    print(f"FS701 cut envelope: {params_file} (cut time {ct:g} s, Synchron Time {s.synchron_time} ms, "
          f"{'S' if s.s_ramps else 'linear'} ramps)")
    head = f"L={s.cutting_length}"
    print(f"{'line speed LU/min':>18} {'min length LU':>14} {'travel LU':>11} {head:>9}  limiting factor")
    for p in pts:
        ml = "-" if not math.isfinite(p.min_length) else f"{p.min_length:.1f}"
        ok = "ok" if feasible(s, s.cutting_length, p.line_speed, ct)[0] else "NO"
        print(f"{p.line_speed:>18.0f} {ml:>14} {p.travel:>11.1f} {ok:>9}  {p.limiting_factor}")
    if out_png is not None:
        print(f"plot: {plot_envelope(s, out_png, sp, cut_time=ct)}")
    return 0
