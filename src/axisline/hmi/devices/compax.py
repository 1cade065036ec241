"""The COMPAX XX70's device view: parameters P.., status values S.., I/O, errors, cam curves.

Read from the personality's own objects: `parameters.Parameters` (written and valid values,
`ParamSpec` ranges, units and "valid from"), the live status values (`LiveStatus`, what
``S44<cr>`` answers), the cam operation's inputs and outputs, and the curves of the cam memory
(`curves.read_curve`) plotted as slave position over master position.

A write is the ASCII interface's ``P<n>=<value>`` line, executed by the personality's own
interface (`byte_endpoint()`, its store included; the HMI core's write enable stands in for
``--allow-writes``), so the range check
is `Parameters`' and an accepted value is saved to the parameter file before the answer, as an
interface line is. Like on the device, a written parameter becomes valid with VP / VC (or its
trigger, the "valid from" of §23): the row shows the written value, the valid one beside it.

Decisions:
 1. Issue 17 "a refused write changes nothing": the value is checked on a copy of the
    parameters (`Parameters.snapshot`, the same `__setitem__` check the interface line runs)
    before the line goes to the interface, so a refused HMI write does not set S30 "last
    error": S30 stays what the host on the serial line last caused, which is what it polls to
    check its transfers (ascii.py decision 1). Test: test_compax_write_in_range_and_refused.
 2. compax.md §2.4 / §5.1 "after Quit, COMPAX 70 is ready for an internal positioning": the
    HMI's acknowledge is Quit: the slave axis leaves ErrorStop (the kernel's reset), the last
    error of the cam operation and S30 return to 0. It does not switch the master counting
    back on after E25 ("the encoder input is still disabled": the manual wants that done on
    purpose). Test: test_compax_acknowledge_is_quit.
 3. §22 cam memory: each curve of the valid memory (what SETC selects) is one plot series,
    slave position F·S_T over the master cycle, at most `MAX_CURVES` curves, each thinned to
    500 points (the first and last set points kept). Test: test_compax_view_has_curves_and_status.
"""

from __future__ import annotations

from typing import Any

from axisline.devices.compax import DEVICE_ERRORS, INTERFACE_ERRORS, CompaxError
from axisline.devices.compax.curves import read_curve
from axisline.devices.compax.parameters import PARAMETERS
from axisline.devices.compax.status import STATUS
from axisline.motion.axis import AxisState

from . import _sections as s

__all__ = ["view", "write", "acknowledge", "MAX_CURVES"]

MAX_CURVES = 8
_INPUTS = ("I12", "I13", "I14", "I15", "I16")
_INPUT_NAMES = {0: "I12 power stage", 1: "I13 coupling", 2: "I14 label", 3: "I15 aux functions", 4: "I16 master counting"}
_OUTPUT_NAMES = {n - 1: f"O{n}" for n in range(1, 17)} | {13: "O14 label ok", 14: "O15 no tracking warning", 15: "O16 synchronous"}


def _param_row(params: Any, number: int) -> dict[str, Any]:
    spec = PARAMETERS[number]
    lo, hi = spec.minimum, spec.maximum
    extra: dict[str, Any] = {"valid": params.valid[number], "valid_from": spec.valid_from.value}
    if spec.allowed is not None:
        lo, hi = min(spec.allowed), max(spec.allowed)
        extra["allowed"] = list(spec.allowed)
    if spec.bitmask is not None:
        lo, hi = 0, spec.bitmask
    if spec.meanings:
        extra["choices"] = {str(k): v for k, v in spec.meanings}
    pending = params.pending().get(number)
    if pending is not None:
        extra["note"] = f"{pending}: valid from {spec.valid_from.value}"
    return s.row(f"P{number}", spec.meaning, params.written[number], spec.unit, lo, hi, True, **extra)


def view(device: Any) -> dict[str, Any]:
    params = device.params
    op = device.op
    sections: list[dict[str, Any]] = [
        s.parameters("Parameters (§23; written, valid with VP / VC)", [_param_row(params, n) for n in sorted(PARAMETERS)]),
        s.parameters("Status values (§20)",
                     [s.row(f"S{n}", spec.meaning, device.status.read(n, params), spec.unit) for n, spec in STATUS.items()]),
    ]
    inputs = sum(1 << k for k, name in enumerate(_INPUTS) if op.input(name))
    sections.append(s.bits("Inputs and outputs", [s.word("I12 ... I16", inputs, _INPUT_NAMES), s.word("O1 ... O16", op.out, _OUTPUT_NAMES)]))
    last = int(op.last_error)
    s30 = int(device.status[30])
    codes = {**DEVICE_ERRORS, **INTERFACE_ERRORS}
    rows = [(f"E{code}", text, code in (last, s30)) for code, text in sorted(codes.items())]
    rows.append(("O14", "label missing (O14 = 0 with label synchronisation on)", int(params[33]) != 0 and not op.output(14)))
    rows.append(("O15", "tracking warning (O15 = 0: following error beyond P79)", not op.output(15)))
    rows += [(f"line {e['line']}", f"start-up line {e['text']!r}: {e['reply']}", True) for e in device.program_errors[-10:]]
    sections.append(s.diagnostics("Errors (§5.1; S30 last error)", rows))
    memory = device.memory
    key = (memory, memory.words(valid=True), device.op.curve.number if device.op.curve is not None else None)
    sections += s.cached(device, "curves", key, lambda: _curves(device))  # rebuilt when VF changed the curves
    curve = op.curve
    lines = [
        f"State: {op.state.value}" + (f", curve {curve.number}" if curve is not None else ", no curve selected"),
        f"LOOP active: {'yes' if op.loop_active else 'no'}   S48 loop counter: {device.status.read(48):g}",
        f"Slave axis {device.config.slave!r}: {device.axis.state.name}",
        f"Start-up program: line {min(device.pc + 1, len(device.program))} of {len(device.program)}"
        + (" (done)" if device.pc >= len(device.program) else ""),
    ]
    pending = params.pending()
    if pending:
        lines.append("Written, not yet valid: " + ", ".join(f"P{n} ({what})" for n, what in pending.items()))
    sections.append(s.text("Cam operation", lines))
    return {"title": f"Parker COMPAX XX70 (slave {device.config.slave!r}, master {device.config.master!r})", "sections": sections}


def _curves(device: Any) -> list[dict[str, Any]]:
    """Decision 3: the curves of the valid cam memory as slave over master position."""
    memory = device.memory
    out = []
    count = memory.curve_count(valid=True)
    active = device.op.curve.number if device.op.curve is not None else None
    for number in range(1, min(count, MAX_CURVES) + 1):
        try:
            c = read_curve(memory, number, valid=True)
        except CompaxError:
            continue
        n = c.n_points
        xs = [c.master_cycle * k / (n - 1) for k in range(n)] if n > 1 else [0.0]
        ys = [c.slave_cycle * f for f in c.set_points]
        title = f"Curve {number}" + (" (active)" if number == active else "") + f": M_T {c.master_cycle:g}, S_T {c.slave_cycle:g}, {n} set points"
        out.append(s.plot(title, "master position (P90 units)", "slave position (P90 units)", [(f"curve {number}", xs, ys)]))
    return out


def write(device: Any, name: str, value: Any) -> tuple[Any, Any]:
    key = name.upper()
    number = int(key[1:]) if key[:1] == "P" and key[1:].isdigit() else None
    if number is None or number not in PARAMETERS:
        raise ValueError(f"name: {name!r} is not a COMPAX parameter (P1 ... P250, as the rows name them)")
    if isinstance(value, bool) or not isinstance(value, (int, float, str)):
        raise ValueError(f"P{number} = {value!r} is not a number; allowed is {PARAMETERS[number].range_text()}")
    params = device.params
    probe = params.snapshot()
    try:
        probe[number] = value.strip() if isinstance(value, str) else value  # decision 1: the check, on a copy
    except CompaxError as e:
        raise ValueError(str(e)) from None
    spec = PARAMETERS[number]
    stored = probe.written[number]
    text = str(int(stored)) if spec.integer else f"{float(stored):.{spec.decimals}f}"
    old = params.written[number]
    endpoint = device.byte_endpoint()  # the interface `serve` offers, with its store ...
    endpoint._writes_allowed = _allowed  # ... and the HMI core's write enable instead of --allow-writes
    reply = endpoint.execute(f"P{number}={text}").decode("ascii", "replace")
    if reply.startswith("!E"):  # (the store failed: undone by the endpoint, E108)
        raise ValueError(reply.removesuffix("\r\n>").strip())
    return old, params.written[number]


def _allowed() -> bool:
    return True  # the HMI core checked the operator's write enable and token


def acknowledge(device: Any) -> str:
    """Decision 2: Quit."""
    op = device.op
    what = []
    if device.axis.state is AxisState.ERROR_STOP:
        what.append(f"slave {device.config.slave!r} ({device.axis.error_text})")
        device.axis.reset()
    codes = {**DEVICE_ERRORS, **INTERFACE_ERRORS}
    for code in sorted({int(op.last_error), int(device.status[30])} - {0}):
        what.append(f"E{code} {codes.get(code, '')}".rstrip())
    op.last_error = 0
    device.status[30] = 0.0
    return f"COMPAX Quit: {', '.join(what)}" if what else ""


def faults(device: Any) -> dict[str, str]:
    """The active error (S30 / the last error) and the start-up program's errors, for the event log."""
    codes = {**DEVICE_ERRORS, **INTERFACE_ERRORS}
    out = {}
    for code in {int(device.op.last_error), int(device.status[30])} - {0}:
        out[f"COMPAX E{code}"] = codes.get(code, "error")
    return out
