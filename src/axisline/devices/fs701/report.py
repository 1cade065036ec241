"""The FS701 part of a run report: the per-cut table, the batch summary and its plots.

`report_section(device_summary, plots)` is the Markdown the run report (`axisline run --report
DIR`) gets for an FS701 machine; `write_plots(device_summary, trace_data, out_dir)` draws

    fs701_length_error.png   length error of every piece (carriage increments) against the
                             tolerances; print-mark cuts: the offset to the mark
    fs701_line_speed.png     line speed in m/min (the material's and the FS701's measurement)
                             with the cut instants
    fs701_carriage.png       carriage position and velocity (set point and actual) against the
                             line speed, and the FS701's position error with the Cut Window
    fs701_cycle.png          one whole cut cycle (the last complete one in the trace: from the
                             start of the synchronisation over the cut to the end of the return):
                             line and carriage speed (m/min), carriage position, position
                             error; Ready to Cut -> Cut completed shaded, the cut and the print
                             marks at the sensor marked (needs fs701.ready_to_cut; the
                             carriage's command_velocity or fs701.cut_state find the ends)
    fs701_error_histogram.png  histogram of the length errors (carriage increments)

The plots that need the scope use its channels (material.speed, <carriage>.command_position,
<carriage>.actual_position, <carriage>.command_velocity, <carriage>.actual_velocity,
fs701.line_speed, fs701.position_error); missing channels are left out of the figure.
`device_summary` is Fs701Personality.summary() (also the "device" entry of `run --json`).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any, Mapping

import numpy as np

from axisline.report.cuts import cut_table_markdown as shared_cut_table
from axisline.report.cuts import cell as _f
from axisline.report.cuts import error_histogram_figure, finish_cut_axes, length_error_figure, line_speed_unit

__all__ = ["report_section", "write_plots", "cut_table_markdown"]


def cut_table_markdown(d: Mapping[str, Any]) -> str:
    """One row per cut: target, actual, errors, line speed, position error, tolerance (the
    table shared with the CLM's flying cutoff, axisline.report.cuts)."""
    return shared_cut_table(d["cuts"], d["length_unit"], "FS701 line speed")


def _errors_text(errors: list[dict[str, Any]]) -> str:
    return "; ".join(f"{e['text']} at {e['t']:.3f} s" for e in errors) or "none"


def report_section(d: Mapping[str, Any], plots: list[Path] | None = None) -> str:
    """The FS701 section of report.md."""
    lu = d["length_unit"]
    b = d["batch"]
    tol = d["tolerance"]
    lines = [
        "## Flying shear (FS701)",
        "",
        f"{d['headline']}",
        "",
        f"- carriage axis `{d['carriage']}`, line encoder `{d['line']}`; pieces measured on the {d['measured_on']} "
        f"(material point = material travel - carriage position at the blade's passage)",
        f"- cutting mode {d['cutting_mode']}, cutting length {d['cutting_length']} {lu}; "
        f"{d['counts_per_lu']['line']:g} line / {d['counts_per_lu']['carriage']:g} carriage increments per {lu}",
        f"- tolerance: ±{tol['constant_speed_counts']:g} carriage increments (±{tol['constant_speed_lu']:.4g} {lu}) at constant "
        f"line speed, ±{tol['ramp_counts']:g} (±{tol['ramp_lu']:.4g} {lu}) with a cut in a speed change",
        f"- batch: {b['size'] or 'no end'} ({b['state']}); FS701 Batch Counter {d['counters']['batch']}, Waste Counter {d['counters']['waste']}",
        "",
        "| | value |",
        "|---|---|",
        f"| cuts | {b['cuts']} |",
        f"| pieces measured | {b['pieces']} ({b['pieces_constant_speed']} at constant speed, {b['pieces_ramps']} with a ramp) |",
        f"| max abs length error | {_f(b['max_abs_error_counts'], '.3f')} incr ({_f(b['max_abs_error_lu'], '.4f')} {lu}) |",
        f"| mean length error | {_f(b['mean_error_counts'], '+.3f')} incr ({_f(b['mean_error_lu'], '+.4f')} {lu}) |",
        f"| std of the length error | {_f(b['std_error_counts'], '.3f')} incr ({_f(b['std_error_lu'], '.4f')} {lu}) |",
        f"| max abs error at constant speed / in ramps | {_f(b['max_abs_error_counts_constant_speed'], '.3f')} / "
        f"{_f(b['max_abs_error_counts_ramps'], '.3f')} incr |",
    ]
    if b["max_abs_mark_offset_counts"] is not None:
        lines.append(
            f"| print marks: max abs / mean / std offset | {_f(b['max_abs_mark_offset_counts'], '.3f')} / "
            f"{_f(b['mean_mark_offset_counts'], '+.3f')} / {_f(b['std_mark_offset_counts'], '.3f')} incr |"
        )
    lines += [
        f"| in tolerance | {b['in_tolerance']} of {b['checked']} |",
        f"| out of tolerance | {', '.join(map(str, b['out_of_tolerance'])) or 'none'} |",
        f"| FS701 errors raised | {_errors_text(d['errors_raised'])} |",
        "",
    ]
    com = d["commissioning"]
    if com["ran"]:
        lines += ["### Commissioning (Adjust program, manual §7)", ""]
        lines += [f"- {s['step']}: {'ok' if s['ok'] else 'FAILED'}: {s['message']}" for s in com["steps"]]
        lead = com.get("acc_feed_forward_ms") or 0.0
        lines += [f"- set: Ana-Out Offset 2 = {com['ana_out_offset_2']}, Ana-Out Gain 2 = {com['ana_out_gain_2']:.2f} V"
                  + (f", acceleration feed-forward {lead:.1f} ms" if lead else ""), ""]
    if d["job_events"]:
        lines += ["### Batch job", "", "| t [s] | event |", "|---|---|"]
        lines += [f"| {e['t']:.3f} | {e['text']} |" for e in d["job_events"]]
        lines.append("")
    lines += ["### Cuts", ""]
    first = d["cuts"][0] if d["cuts"] else None
    if first is not None and first["index"] == 1 and first["actual_length"] is None:
        # a reader sees "-" in the first row and asks why (decision M2 of the personality)
        lines += [f"Cut {first['index']} has no piece length: a piece is the material between two cuts, and the first "
                  "cut of the run has no cut before it (it trims the start of the material), so it is recorded but not "
                  "measured or checked.", ""]
    lines.append(cut_table_markdown(d))
    for p in plots or []:
        lines.append(f"![{Path(p).stem}]({Path(p).name})")
    return "\n".join(lines) + "\n"


def write_plots(d: Mapping[str, Any], data: Mapping[str, np.ndarray] | None, out_dir: str | Path) -> list[Path]:
    """The FS701 figures (module docstring); returns the files written."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    lu = d["length_unit"]
    cuts = d["cuts"]
    written: list[Path] = []
    tol = d["tolerance"]

    # 1. length error per piece (or mark offset)
    fig, ax = plt.subplots(figsize=(9, 4), constrained_layout=True)
    marks = [c for c in cuts if c.get("mark_offset_counts") is not None]
    if marks:
        ax.bar([c["index"] - 0.2 for c in marks], [c["mark_offset_counts"] for c in marks], width=0.4, color="tab:blue",
               label="offset to the print mark")
        ax.axhline(d["tolerance"]["mark_counts"], color="tab:red", linestyle="--", linewidth=1, label="tolerance")
        ax.axhline(-d["tolerance"]["mark_counts"], color="tab:red", linestyle="--", linewidth=1)
        ax.set_ylabel("offset [carriage increments]")
    pieces = [c for c in cuts if c["error_counts"] is not None]
    if pieces:  # (shared with the CLM's flying cutoff, axisline.report.cuts)
        tolerances = () if marks else ((tol["constant_speed_counts"], "--", "tolerance (constant speed)"),
                                       (tol["ramp_counts"], ":", "tolerance (ramps)"))
        length_error_figure(plt, ax, pieces, width=0.4 if marks else 0.8, shift=0.2 if marks else 0.0, tolerances=tolerances)
        if marks:
            ax.set_ylabel("offset [carriage increments]")
    finish_cut_axes(ax)
    kc = d["counts_per_lu"]["carriage"]
    sec = ax.secondary_yaxis("right", functions=(lambda y: y / kc, lambda y: y * kc))
    sec.set_ylabel(f"[{lu}]")
    ax.set_title("FS701: " + ("offset to the print marks" if marks else "length error of every piece"))
    path = out / "fs701_length_error.png"
    fig.savefig(path, dpi=90)
    plt.close(fig)
    written.append(path)

    t_cut = [c["time"] for c in cuts]
    data = data or {}
    t = np.asarray(data["t"]) if "t" in data else None

    # 2. line speed with the cut instants, in m/min (the FS701's line speed register is LU/min)
    k, unit = line_speed_unit(lu)
    fig, ax = plt.subplots(figsize=(9, 4), constrained_layout=True)
    if t is not None and "fs701.line_speed" in data:
        ax.plot(t, np.asarray(data["fs701.line_speed"]) * k, label="FS701 line speed (#2, Sampling Time)", linewidth=0.6,
                color="tab:orange", alpha=0.7)
    if t is not None and "material.speed" in data:
        ax.plot(t, np.asarray(data["material.speed"]) * 60.0 * k, label="material (plant)", linewidth=1.5, color="tab:blue")
    ax.plot(t_cut, [c["line_speed"] * k for c in cuts], "v", color="tab:red", markersize=6, label="cuts")
    ax.set_xlabel("time [s]")
    ax.set_ylabel(f"line speed [{unit}]")
    ax.grid(True, alpha=0.3)
    ax.legend(loc="lower center", fontsize=8)
    ax.set_title("line speed and cuts")
    path = out / "fs701_line_speed.png"
    fig.savefig(path, dpi=90)
    plt.close(fig)
    written.append(path)

    # 3. carriage position / velocity / position error
    car = d["carriage"]
    if t is not None and f"{car}.actual_position" in data:
        fig, rows = plt.subplots(3, 1, sharex=True, figsize=(9, 9), constrained_layout=True)
        ax = rows[0]
        for key, label in ((f"{car}.command_position", "set point"), (f"{car}.actual_position", "actual")):
            if key in data:
                ax.plot(t, data[key], label=label, linewidth=1.0)
        for tc in t_cut:
            ax.axvline(tc, color="tab:red", linewidth=0.4, alpha=0.5)
        ax.set_ylabel(f"carriage position [{lu}]")
        ax.legend(loc="upper right", fontsize=8)
        ax = rows[1]
        for key, label in ((f"{car}.command_velocity", "set point"), (f"{car}.actual_velocity", "actual")):
            if key in data:
                ax.plot(t, data[key], label=label, linewidth=1.0)
        if "material.speed" in data:
            ax.plot(t, data["material.speed"], label="line", linewidth=0.8, linestyle="--", color="black")
        ax.set_ylabel(f"carriage velocity [{lu}/s]")
        ax.legend(loc="upper right", fontsize=8)
        ax = rows[2]
        if "fs701.position_error" in data:
            ax.plot(t, data["fs701.position_error"], linewidth=0.8, label="FS701 position error (#3)")
        ax.set_ylabel("position error [incr]")
        ax.legend(loc="upper right", fontsize=8)
        rows[-1].set_xlabel("time [s]")
        for a in rows:
            a.grid(True, alpha=0.3)
        fig.suptitle(f"carriage {car}: red lines = cuts")
        path = out / "fs701_carriage.png"
        fig.savefig(path, dpi=90)
        plt.close(fig)
        written.append(path)

    # 4. one cut cycle
    if t is not None:
        p = _cycle_plot(plt, d, data, t, out / "fs701_cycle.png")
        if p is not None:
            written.append(p)

    # 5. histogram of the length errors
    hist = error_histogram_figure(plt, cuts, out / "fs701_error_histogram.png", tol["constant_speed_counts"])
    if hist is not None:
        written.append(hist)
    return written


def _rising(x: np.ndarray) -> np.ndarray:
    x = np.asarray(x).astype(bool)
    return np.flatnonzero(x[1:] & ~x[:-1]) + 1


def _carriage_velocity(data: Mapping[str, np.ndarray], carriage: str | None) -> np.ndarray | None:
    if carriage is not None:
        key = f"{carriage}.command_velocity"
        return np.asarray(data[key]) if key in data else None
    keys = [k for k in data if k.endswith(".command_velocity")]
    return np.asarray(data[keys[0]]) if len(keys) == 1 else None


def cycle_window(data: Mapping[str, np.ndarray], carriage: str | None = None) -> tuple[int, int, int, int] | None:
    """(start, ready, completed, end) sample indices of the last complete cut cycle in the trace,
    with a margin of 5 % of the cycle on either side of start and end.

    A whole cycle: from the start of the synchronisation (the carriage set point leaves the start
    position towards the cut: the last sample before Ready to Cut where it did not move in the
    line's direction) over Ready to Cut and Cut completed to the end of the return (the set
    point stops moving back). Needs fs701.ready_to_cut; the carriage's command_velocity
    (`carriage`, or the only one in the trace) gives the start and the end, else fs701.cut_state
    (HOME), else +-1 Ready-to-Cut duration around the synchronous phase."""
    if "fs701.ready_to_cut" not in data:
        return None
    rtc = np.asarray(data["fs701.ready_to_cut"]).astype(bool)
    n = len(rtc)
    rises = _rising(rtc)
    falls = np.flatnonzero(~rtc[1:] & rtc[:-1]) + 1
    v = _carriage_velocity(data, carriage)
    for r in rises[::-1]:
        after = falls[falls > r]
        if len(after) == 0:
            continue
        f = int(after[0])  # Ready to Cut LOW: Cut completed received
        if "fs701.cut_completed" in data:
            cc = np.asarray(data["fs701.cut_completed"]).astype(bool)
            e = [i for i in range(int(r), f + 1) if cc[i] != cc[i - 1]]
            if e:
                f = e[0]
        if v is not None and v[r] != 0.0:
            forward = v * np.sign(v[r])  # > 0: with the line (a line running backwards too)
            before = np.flatnonzero(forward[:r] <= 0.0)
            back = np.flatnonzero(forward[f:] < 0.0)
            if len(before) == 0 or len(back) == 0:
                continue  # the start or the return is not in the trace
            ret = f + int(back[0])
            home = np.flatnonzero(forward[ret:] >= 0.0)
            if len(home) == 0:
                continue
            s0, e0 = int(before[-1]), ret + int(home[0])
        elif "fs701.cut_state" in data:
            cs = np.asarray(data["fs701.cut_state"]).astype(int)
            home_state = 1
            s0 = int(r)
            while s0 > 0 and cs[s0 - 1] != home_state:
                s0 -= 1
            e0 = f
            while e0 < n - 1 and cs[e0] != home_state:
                e0 += 1
            if cs[e0] != home_state:
                continue  # the return is not complete in the trace
        else:
            span = max(f - int(r), 1)
            return max(int(r) - span, 0), int(r), f, min(f + span, n - 1)
        margin = max((e0 - s0) // 20, 1)
        return max(s0 - margin, 0), int(r), f, min(e0 + margin, n - 1)
    return None


def _mark_channel(d: Mapping[str, Any], data: Mapping[str, np.ndarray]) -> str | None:
    """The print-mark sensor's trace channel ("<marks>.state") in Cutting Mode 2, if one."""
    if str(d.get("cutting_mode")) != "2":
        return None
    axis_like = {k.rpartition(".")[0] for k in data if k.endswith(".command_position")}
    keys = [k for k in data if k.endswith(".state") and k.rpartition(".")[0] not in axis_like | {"fs701"}]
    return keys[0] if len(keys) == 1 else None


def _cycle_plot(plt: Any, d: Mapping[str, Any], data: Mapping[str, np.ndarray], t: np.ndarray, path: Path) -> Path | None:
    car = d["carriage"]
    w = cycle_window(data, car if f"{car}.command_velocity" in data else None)
    if w is None:
        return None
    s0, r, f, e0 = w
    sl = slice(s0, e0 + 1)
    tt = t[sl]
    lu = d["length_unit"]
    k, unit = line_speed_unit(lu)  # the FS701 thinks in LU/min: speeds in m/min
    fig, rows = plt.subplots(3, 1, sharex=True, figsize=(9, 8.5), constrained_layout=True)
    ax = rows[0]
    if "material.speed" in data:
        ax.plot(tt, np.asarray(data["material.speed"])[sl] * 60.0 * k, label="line (plant)", color="black", linestyle="--",
                linewidth=1.0)
    if "fs701.line_speed" in data:
        ax.plot(tt, np.asarray(data["fs701.line_speed"])[sl] * k, label="line (FS701 #2)", color="tab:orange", linewidth=0.8)
    for key, label in ((f"{car}.command_velocity", "carriage set point"), (f"{car}.actual_velocity", "carriage actual")):
        if key in data:
            ax.plot(tt, np.asarray(data[key])[sl] * 60.0 * k, label=label, linewidth=1.2)
    ax.set_ylabel(f"speed [{unit}]")
    ax = rows[1]
    for key, label in ((f"{car}.command_position", "set point"), (f"{car}.actual_position", "actual")):
        if key in data:
            ax.plot(tt, np.asarray(data[key])[sl], label=label, linewidth=1.0)
    ax.set_ylabel(f"carriage position [{lu}]")
    ax = rows[2]
    if "fs701.position_error" in data:
        pe = np.asarray(data["fs701.position_error"])
        ax.plot(tt, pe[sl], linewidth=0.9, label="position error (#3)")
        seg = pe[r : f + 1]
        if len(seg):
            ax.set_title(f"Ready to Cut -> Cut completed: min {np.min(seg):.1f}, max {np.max(seg):.1f} increments", fontsize=9)
    ax.set_ylabel("position error [incr]")
    rows[-1].set_xlabel("time [s]")
    # the events of the cycle: the cut(s) and the print marks passing the sensor
    cut_times = [c["time"] for c in d.get("cuts", []) if c.get("time") is not None and tt[0] <= c["time"] <= tt[-1]]
    mark_key = _mark_channel(d, data)
    mark_times = [float(t[i]) for i in _rising(np.asarray(data[mark_key])) if s0 <= i <= e0] if mark_key else []
    for j, a in enumerate(rows):
        first = j == 0  # the events are named once, in the top panel's legend
        a.axvspan(t[r], t[f], color="tab:green", alpha=0.15, label="Ready to Cut -> Cut completed" if first else None)
        for i, tc in enumerate(cut_times):
            a.axvline(tc, color="tab:red", linewidth=1.2, label="cut" if first and i == 0 else None)
        for i, tm in enumerate(mark_times):
            a.axvline(tm, color="tab:purple", linestyle=":", linewidth=1.2,
                      label=f"print mark at the sensor ({mark_key})" if first and i == 0 else None)
        a.grid(True, alpha=0.3)
        if a.get_legend_handles_labels()[0]:
            a.legend(loc="upper right", fontsize=7)
    fig.suptitle(f"one cut cycle: synchronisation, cut, return ({t[s0]:.2f} - {t[e0]:.2f} s)")
    fig.savefig(path, dpi=90)
    plt.close(fig)
    return path


# ============================================================================ documentation


def _md(text: str) -> str:
    return str(text).replace("|", "\\|").replace("\n", " ")


def config_table_markdown(model: Any = None) -> str:
    """The keys of the [device] table (or of `model`): type, default, allowed range, meaning."""
    from axisline.configerrors import allowed_range
    from pydantic_core import PydanticUndefined

    from .config import Fs701Config

    model = Fs701Config if model is None else model
    kinds = {
        "parameters": "table: name = number",
        "inputs": "table: name = true/false or a name",
        "outputs": "table: name = io output",
        "shear": "table [device.shear]",
        "adjust": "table [device.adjust]",
        "acceleration_feed_forward": "float or 'auto'",
    }
    lines = ["| key | type | default | allowed | meaning |", "|---|---|---|---|---|"]
    for name, info in model.model_fields.items():
        ann = info.annotation
        t = kinds.get(name) or getattr(ann, "__name__", None) or str(ann).replace("typing.", "")
        t = t.replace(" | None", " (optional)")
        if info.default is PydanticUndefined and info.default_factory is None:
            default = "required"
        elif info.default_factory is not None:
            v = info.default_factory()
            if isinstance(v, dict):
                default = "{" + ", ".join(f"{k} = {v[k]!r}" for k in v) + "}" if v else "(empty)"
                default = default.replace("'", '"').replace("True", "true").replace("False", "false")
            else:
                default = "(its defaults)"
        else:
            default = "none" if info.default is None else repr(info.default).replace("True", "true").replace("False", "false")
        allowed = allowed_range(info) or ""
        if name == "acceleration_feed_forward":  # a number range or a word: the validator's
            from .loop import LEAD_MAX_MS

            allowed = f">= 0.0 and <= {LEAD_MAX_MS}, or 'auto'"
        lines.append(f"| `{name}` | {_md(t)} | {_md(default)} | {_md(allowed)} | {_md(info.description or '')} |")
    return "\n".join(lines) + "\n"


def _hex(data: bytes) -> str:
    return " ".join(f"{b:02X}" for b in data)


def serial_markdown() -> str:
    """docs/fs701-serial.md: the Drivecom framing and the register and Modbus maps (generated)."""
    from . import drivecom as dc
    from .io_assign import INPUT_FUNCTIONS, OUTPUT_SIGNALS
    from .modbus_map import MODBUS_MAP, MODBUS_WIDE_BASE
    from .registers import REGISTERS, RegisterKind
    from .status import ERRORS, STATUS_WORDS

    def raw_range(r: Any) -> str:
        if r.decimals:
            k = 10**r.decimals
            return f"{r.minimum}..{r.maximum} ({r.minimum / k:.{r.decimals}f}..{r.maximum / k:.{r.decimals}f})"
        return f"{r.minimum}..{r.maximum}"

    read = dc.build_read(11, 0x0000)
    reply = dc.build_reply(0x0000, "1000")
    write = dc.build_write(11, 0x0105, -125)
    bad = bytearray(write)
    bad[-1] ^= 0x01
    out = [
        "# FS701 serial register access: Drivecom and Modbus TCP",
        "",
        "Generated from `axisline/devices/fs701/drivecom.py` and `registers.py` by",
        "`axisline.devices.fs701.report.serial_markdown()` (do not edit by hand;",
        "`tests/devices/fs701/test_serve.py` fails when this file and the code disagree).",
        "",
        "    axisline serve examples/flying_shear.toml --serial-tcp 127.0.0.1:5011 --modbus 127.0.0.1:5020 [--allow-writes]",
        "    axisline serve examples/flying_shear.toml --serial-pty      # prints the pty's path for serial tools",
        "",
        "Both endpoints serve the same live register map: the FS701's parameters, its process values",
        "(read when a request arrives, at a cycle boundary), the single command bits (the serial",
        "\"RS\" column of the I/O card: OR'ed with the hardware inputs into All Commands, so",
        "`0x0901 = 1` is Start) and the status words. Without `--allow-writes` every write is refused",
        "(Drivecom NAK, Modbus exception 01) and changes nothing.",
        "",
        "## Drivecom (serial, TCP, pty)",
        "",
        "Control characters:",
        "",
        "| name | byte | meaning |",
        "|---|---|---|",
        f"| EOT | 0x{dc.EOT:02X} | start of a telegram from the master (aborts one in progress) |",
        f"| STX | 0x{dc.STX:02X} | start of text (data) |",
        f"| ETX | 0x{dc.ETX:02X} | end of text |",
        f"| ENQ | 0x{dc.ENQ:02X} | end of a read request |",
        f"| ACK | 0x{dc.ACK:02X} | write accepted |",
        f"| NAK | 0x{dc.NAK:02X} | telegram refused: nothing was changed |",
        "",
        "Telegrams (AD1 AD2: the unit address as two ASCII digits, default "
        f"{dc.DEFAULT_ADDRESS}, register \"Ser Unit Address\" 0x02C5; C1 C2: the serial code as "
        f"{dc.CODE_CHARS} ASCII hex digits; BCC: XOR of every byte after STX up to and including ETX):",
        "",
        "| telegram | bytes |",
        "|---|---|",
        "| read request | EOT AD1 AD2 C1 C2 ENQ |",
        "| read reply | STX C1 C2 data ETX BCC (NAK if refused) |",
        "| write | EOT AD1 AD2 STX C1 C2 data ETX BCC |",
        "| write reply | ACK, or NAK |",
        "",
        "The data is the raw register value in decimal (\"-\" if negative, no leading zeros) with the",
        "register's implied decimals: +/- Sync Rate 1.25 % is `125`. A write may also give the decimal",
        f"point with exactly the register's decimals (`1.25`). Data longer than {dc.MAX_DATA} characters or a",
        f"telegram longer than {dc.MAX_TELEGRAM} bytes is malformed. An address with a digit 0 is a broadcast:",
        "writes are executed and not answered, reads are ignored.",
        "",
        "Examples (unit address 11):",
        "",
        "| what | bytes (hex) |",
        "|---|---|",
        f"| read Cutting Length (0x0000) | `{_hex(read)}` |",
        f"| reply: 1000 | `{_hex(reply)}` |",
        f"| write +/- Sync Rate (0x0105) = -1.25 % | `{_hex(write)}` |",
        f"| reply | `{dc.ACK:02X}` (ACK) |",
        f"| the same write with a bad BCC | `{_hex(bytes(bad))}` -> `{dc.NAK:02X}` (NAK, unchanged) |",
        "",
        "NAK answers: a malformed telegram, a bad BCC, an unknown register, a read-only register, a",
        "value out of range or with the wrong decimals, a refused command (Adjust/Test Program while",
        "Control Enable is ON), any write while writes are not enabled.",
        "",
        "`axisline.devices.fs701.drivecom.DrivecomClient` is a master for scripts and tests.",
        "",
        "## Modbus TCP",
        "",
        "Holding registers (function codes 3, 6, 16; 4 reads the same image as input registers):",
        "",
        "- address = 2 x serial code; each register is 2 words (32 bit), high word first, two's",
        "  complement for signed registers, the raw value with its implied decimals (as on Drivecom);",
        "- Batch / Waste Counter (0x0170 / 0x0171) and their copies 0x080E / 0x080F count to 9 999 999 999:",
        f"  4 words (64 bit) each at {MODBUS_WIDE_BASE} (0x{MODBUS_WIDE_BASE:04X}), +4, +8, +12;",
        "- reads may start and end anywhere inside mapped registers; writes must cover whole registers;",
        "- exception 01: writes not enabled or a function code not served; 02: an unmapped address or a",
        "  read-only register; 03: a refused value, a bad quantity or a partial write; 04: the device",
        "  refuses the request in its present state (a command it cannot start, \"Store to EEProm\" that",
        "  cannot be written). A refused request changes nothing.",
        "",
        "## Single commands (0x0900 + bit) and the command words",
        "",
        "| bit | serial code | function | type | factory input |",
        "|---|---|---|---|---|",
    ]
    for f in INPUT_FUNCTIONS:
        code = f"0x{f.code:04X}" if f.code is not None else "-"
        inp = f"In{f.default_input}" if f.default_input else ""
        out.append(f"| {f.bit} | {code} | {_md(f.name)} (`{f.attr}`) | {_md(f.type)} | {inp} |")
    out += ["", "## Single outputs (0x0A00 + bit, read only)", "", "| bit | serial code | signal | factory output |", "|---|---|---|---|"]
    for s in OUTPUT_SIGNALS:
        o = f"Out{s.default_output}" if s.default_output else ""
        out.append(f"| {s.bit} | 0x{s.code:04X} | {_md(s.name)} (`{s.attr}`) | {o} |")
    out += ["", "## Status words", "", "| serial code | word | serial write | meaning |", "|---|---|---|---|"]
    for w in STATUS_WORDS:
        out.append(f"| 0x{w.code:04X} | {_md(w.name)} | {'yes' if w.serial_writable else 'no'} | {_md(w.description)} |")
    out += ["", "Error Status (0x0B05) bits:", "", "| bit | error | stops the cutter | cause |", "|---|---|---|---|"]
    for n, e in ERRORS.items():
        out.append(f"| {n} | {_md(e.message)} | {'yes' if e.stops_machine else 'no'} | {_md(e.cause)} |")
    out += [
        "",
        "## Register map",
        "",
        "Raw ranges; decimals are implied (the engineering range in brackets). R/W: writable over the",
        "serial link and Modbus. Reserved registers read 0 and accept only 0.",
        "",
        "| serial code | dec | Modbus | name | attribute | kind | R/W | range (raw) | unit | meaning |",
        "|---|---|---|---|---|---|---|---|---|---|",
    ]
    mb = {e.code: e for e in MODBUS_MAP}
    for r in REGISTERS:
        if r.kind == RegisterKind.RESERVED:
            continue
        e = mb[r.code]
        desc = r.description
        out.append(
            f"| 0x{r.code:04X} | {r.code} | {e.address} ({e.words} words) | {_md(r.name)} | `{r.attr}` | {r.kind} | "
            f"{'RW' if r.writable else 'R'} | {raw_range(r)} | {_md(r.unit)} | {_md(desc)} |"
        )
    reserved = [r for r in REGISTERS if r.kind == RegisterKind.RESERVED]
    out += [
        "",
        f"Reserved (read 0, write only 0): {len(reserved)} registers in the parameter blocks "
        f"({', '.join(f'0x{r.code:04X}' for r in reserved[:3])}, ...).",
        "",
    ]
    return "\n".join(out)
