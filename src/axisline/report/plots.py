"""Plots of a recorded trace: position, velocity, acceleration, jerk, following error per axis."""

from __future__ import annotations

from pathlib import Path
from typing import Mapping

import numpy as np

# channel suffixes recorded per axis by the Machine (see machine.py: Machine.add_axis_channels)
_ROWS = (
    ("position", ("command_position", "actual_position")),
    ("velocity", ("command_velocity", "actual_velocity")),
    ("acceleration", ("command_acceleration",)),
    ("jerk", ("command_jerk",)),
    ("following error", ("following_error",)),
)


def axes_in(data: Mapping[str, np.ndarray]) -> list[str]:
    """Axis names that have traced channels ("x.command_position" -> "x")."""
    names = []
    for key in data:
        head, _, tail = key.rpartition(".")
        if head and tail == "command_position" and head not in names:
            names.append(head)
    return names


def axis_panels(data: Mapping[str, np.ndarray], units: Mapping[str, str], axis: str) -> list[tuple[str, list[str], str]]:
    """The panels of `axis`' plot: (label, channels, unit), only those the scope recorded (an
    FS701 trace has no jerk: no empty panel); the unit is the channels' own."""
    out = []
    for label, suffixes in _ROWS:
        keys = [f"{axis}.{sfx}" for sfx in suffixes if f"{axis}.{sfx}" in data]
        if keys:
            unit = next((units[k] for k in keys if units.get(k)), "")
            out.append((label, keys, unit))
    return out


def plot_trace(data: Mapping[str, np.ndarray], units: Mapping[str, str], out_dir: str | Path, title: str = "") -> list[Path]:
    """Write one PNG per axis into out_dir; returns the files written."""
    import matplotlib

    matplotlib.use("Agg")  # no screen needed, and no GUI toolkit import
    import matplotlib.pyplot as plt

    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    t = np.asarray(data["t"])
    written = []
    for axis in axes_in(data):
        panels = axis_panels(data, units, axis)
        fig, rows = plt.subplots(len(panels), 1, sharex=True, figsize=(9, 2.0 * len(panels) + 0.6),
                                 constrained_layout=True, squeeze=False)
        rows = rows[:, 0]
        for ax, (label, keys, unit) in zip(rows, panels):
            for key in keys:
                ax.plot(t, data[key], label=key.rpartition(".")[2].replace("_", " "), linewidth=1.0)
            ax.set_ylabel(f"{label}\n[{unit}]" if unit else label)
            ax.grid(True, alpha=0.3)
            if len(ax.get_lines()) > 1:
                ax.legend(loc="upper right", fontsize=8)
        rows[-1].set_xlabel("time [s]")
        fig.suptitle(f"{title} axis {axis}".strip())
        path = out / f"axis_{axis}.png"
        fig.savefig(path, dpi=90)
        plt.close(fig)
        written.append(path)
    return written
