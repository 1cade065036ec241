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
        fig, rows = plt.subplots(len(_ROWS), 1, sharex=True, figsize=(9, 10), constrained_layout=True)
        for ax, (label, suffixes) in zip(rows, _ROWS):
            unit = ""
            for suffix in suffixes:
                key = f"{axis}.{suffix}"
                if key in data:
                    ax.plot(t, data[key], label=suffix.replace("_", " "), linewidth=1.0)
                    unit = units.get(key, unit)
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
