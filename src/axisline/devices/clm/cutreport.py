"""The flying cutoff's cuts measured on the simulated material, for the run report and `run
--json` (the FS701's names and table: axisline.report.cuts).

    meter = CutMeter(personality)      # the personality makes it for a flying cutoff machine
    meter.started()                    # the program started: the first piece counts from here
    meter.cut(cycle)                   # the punch signal (device.report_output) rose
    meter.records                      # one dict per cut (axisline.report.cuts keys)

A cut is taken at the rising edge of the output the machine file names as ``report_output`` (the
punch signal). The point cut has the material coordinate ``material position - carriage
position`` (both the plant's, at the same instant: the end of the cycle before the one in which
the CLM's output reaches the hardware); a piece is the difference of two such points less the
A141 tool width. The first piece of a run counts from the point under the tool when the program
started (cutoff.py decision 3), so every piece is measured. Without a [material] the wheel master
(master encoder 1) is the material.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

__all__ = ["CutMeter", "report_section", "write_plots"]


class CutMeter:
    def __init__(self, personality: Any) -> None:
        self.device = personality
        machine = personality.machine
        self.machine = machine
        self.unit = machine.units[personality.config.axes[0]]
        encoder = getattr(self.unit, "encoder", None)
        self.counts_per_unit = float(getattr(encoder, "counts_per_unit", None) or machine.axis(personality.config.axes[0]).config.counts_per_unit)
        self.records: list[dict[str, Any]] = []
        self._point: float | None = None
        self._speed: tuple[float, float] | None = None  # (velocity, acceleration) at the previous cut

    def _material(self) -> tuple[float, float, float]:
        mat = getattr(self.machine, "material", None)
        if mat is not None:
            return float(mat.position), float(mat.velocity), float(getattr(mat, "acceleration", 0.0))
        me = self.device.rt.master_encoder
        master = me.master if me is not None else None
        if master is None:
            return math.nan, math.nan, math.nan
        return float(master.position), float(master.velocity), float(master.acceleration)

    def _point_now(self) -> float:
        return self._material()[0] - float(self.unit.drive.position)

    def started(self) -> None:
        self._point = self._point_now()
        self._speed = None

    def cut(self, cycle: int) -> None:
        rt = self.device.rt
        cutoff = rt.cutoff
        if cutoff is None:
            return
        position, velocity, acceleration = self._material()
        point = position - float(self.unit.drive.position)
        width = float(cutoff.tool_width)
        target = float(cutoff.programmed) if cutoff.programmed is not None else math.nan
        actual = point - self._point - width if self._point is not None else math.nan
        err = actual - target
        k = self.counts_per_unit
        axis = rt.axes[1]
        me = rt.master_encoder
        before = self._speed
        constant = before is not None and acceleration == 0.0 and before[1] == 0.0 and before[0] == velocity
        self.records.append({
            "index": len(self.records) + 1,
            "time": round(cycle * float(self.machine.period), 6),
            "kind": "LML",
            "target_length": None if math.isnan(target) else target,
            "actual_length": None if math.isnan(actual) else actual,
            "error_lu": None if math.isnan(err) else err,
            "error_counts": None if math.isnan(err) else err * k,
            "line_speed": velocity * 60.0,
            "line_speed_measured": None if me is None else float(me.velocity) * 60.0,
            "following_error": float(axis.lag) * k,
            "max_pos_error_counts": float(cutoff.max_lag) * k,
            "constant_speed": constant,
            "tolerance": None,
            "in_tolerance": None,
            "material_point": point,
        })
        self._point = point
        self._speed = (velocity, acceleration)


def report_section(d: dict[str, Any], plots: list[Path]) -> list[str]:
    """The flying cutoff's lines of the CLM section of report.md."""
    from axisline.report.cuts import cut_table_markdown

    cuts = d.get("cuts") or []
    if not cuts:
        return []
    lu = d.get("length_unit", "IU")
    errs = [abs(c["error_counts"]) for c in cuts if c.get("error_counts") is not None]
    const = [abs(c["error_counts"]) for c in cuts if c.get("error_counts") is not None and c.get("constant_speed")]
    lines = ["", "### Flying cutoff: every cut measured on the material", "",
             f"{len(cuts)} cut(s); largest length error {max(errs):.2f} carriage increments" if errs else f"{len(cuts)} cut(s)"]
    if const:
        lines[-1] += f", {max(const):.2f} at constant line speed"
    lines += ["", cut_table_markdown(cuts, lu, "CLM line speed (V011)", tolerance=False)]
    lines += [f"![{Path(p).stem}]({Path(p).name})" for p in plots if Path(p).name.startswith("clm_")]
    return lines


def write_plots(d: dict[str, Any], out_dir: str | Path) -> list[Path]:
    """clm_length_error.png and clm_error_histogram.png (the FS701's figures, report.cuts)."""
    cuts = d.get("cuts") or []
    if not cuts:
        return []
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from axisline.report.cuts import error_histogram_figure, finish_cut_axes, length_error_figure

    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    written = []
    fig, ax = plt.subplots(figsize=(9, 4), constrained_layout=True)
    length_error_figure(plt, ax, cuts)
    finish_cut_axes(ax)
    ax.set_title("CLM flying cutoff: length error of every piece")
    path = out / "clm_length_error.png"
    fig.savefig(path, dpi=90)
    plt.close(fig)
    written.append(path)
    hist = error_histogram_figure(plt, cuts, out / "clm_error_histogram.png")
    if hist is not None:
        written.append(hist)
    return written
