"""What `axisline run` says about a WAGO 750-672 machine: the headline and the report section.

The headline is one line in the module's words (the console prints it; grep finds it):

    wago672: module 0 (axis x): Single positioning, referenced, at 50.000 mm; 16/16 PLC steps done; watchdog 100 ms, not tripped

Without a `[[device.plc]]` script nothing drives the module in `run` (its PLC is the network's,
under `serve`), and the headline says so instead of leaving an idle axis unexplained.
"""

from __future__ import annotations

from typing import Any

__all__ = ["headline", "report_section"]


def _watchdog(coupler: dict[str, Any]) -> str:
    if coupler["watchdog_status"] == "off":
        return "watchdog off"
    n = coupler["watchdog_expiries"]
    tripped = "not tripped" if not n else f"tripped {n} time{'s' if n != 1 else ''}"
    return f"watchdog {coupler['watchdog_ms']} ms, {tripped}"


def _module(m: dict[str, Any]) -> str:
    state = [m["mode"], "referenced" if m["reference_ok"] else "not referenced",  # the mode in the manual's words
             f"at {m['axis_position']:.3f} {m['unit']}"]
    if m["error"]:
        state.append(f"error {m['error']}")
    return f"module {m['module']} (axis {m['axis']}): " + ", ".join(state)


def headline(summary: dict[str, Any]) -> str:
    """The device summary's one line (see the module docstring)."""
    plc = summary.get("plc")
    if plc is None:
        what = ("no PLC script ([[device.plc]]): nothing drove the module; `axisline serve --modbus` gives it a PLC"
                if not summary.get("plc_configured") else "PLC script not run (serve: the Modbus client is the PLC)")
    elif plc["failed"]:
        f = plc["failure"]
        what = f"PLC stopped at {f['label']} of {plc['steps']}: {f['reason']} (the fault says more)"
    else:
        what = f"{plc['done']}/{plc['steps']} PLC steps done"
    modules = "; ".join(_module(m) for m in summary["modules"])
    return f"wago672: {modules}; {what}; {_watchdog(summary['coupler'])}"


def report_section(summary: dict[str, Any]) -> str:
    """report.md's section: the headline, then the PLC steps with their times."""
    lines = ["## WAGO 750-672", "", summary.get("headline", ""), ""]
    plc = summary.get("plc")
    if plc and plc["log"]:
        lines += ["| step | name | module | writes | started, s | done, s |", "|---|---|---|---|---|---|"]
        for e in plc["log"]:
            lines.append(f"| {e['step']} | {e['name'] or ''} | {e['module']} | {e['writes'] or '-'} | {e['t_start']:.3f} | {e['t_done']:.3f} |")
        lines.append("")
    if plc and plc["failed"]:
        lines += [f"**Failed:** {plc['failed']}", ""]
    return "\n".join(lines)
