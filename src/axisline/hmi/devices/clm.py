"""The Rexroth CLM1.4's device view: parameters field by field, task display, program and Logic
Task, the CTA screens, faults, system inputs and outputs, user variables.

Read from the running CLM (`devices/clm/`): the parameter set with every field's range and unit
(`paramtable` through `parameters.PARAMETERS`), the NC tasks and the program memory, the Logic
Task, the process image, the mode machine's fault; the CTA screens are the ones `axisline clm
display` shows (`client.ClmClient`), built from the same status telegrams, answered in-process
by the CLM's serial endpoint.

Writes, by row name, go to the CLM as X6 telegrams through its serial endpoint (`serial.py`),
so the CLM's rules hold (parameters only in Parameter mode, error 05; V600-V999 in any mode)
and an accepted write is in the memory file before the answer, as over the wire (a CLM whose X6
serves the IDS01 with X8 off has no data interface: it takes no writes, serial.py decision 14):

    B002.baud_rate, A106.<field>, ...   one field of a parameter (``#sK`` telegram)
    B002                                a parameter's whole data in the CLM's columns
    V600 ... V999                       a user variable (``#sV`` telegram)

Decisions:
 1. Issue 17 "parameters ... with range and validation" against L4130 / L6809 (the CLM takes
    any well-formed parameter data in Parameter mode and checks the ranges when Parameter mode
    is left, fault 02): the HMI refuses a field outside its range at once, with the text the
    check on leaving Parameter mode would give; a page that accepted 9 600 000 baud and then
    faulted the machine minutes later would not be validation. The checks between parameters
    (paramcheck) stay where the CLM makes them, on leaving Parameter mode: they depend on the
    order the operator writes related fields in. Test: test_clm_parameter_write_in_parameter_mode.
 2. Spec §1.5 / L982-1086 CTA screens: position, tasks, error and I/O, each as the CTA's lines
    (client.py decision 2), queried through a session of the CLM's own serial endpoint at its
    B003 station; with no data interface (X6 on the IDS01, X8 off) the screens say so.
    Test: test_clm_view_has_tasks_program_cta_and_io.
 3. Issue 17 "diagnostics with acknowledge": acknowledge is the CL key (`ModeMachine.clear`,
    the same as External Clear and ``!CLEAR``): it clears only when the cause is gone
    (E-Stop closed, valid mode inputs), as on the CLM. Test: test_clm_acknowledge_is_the_cl_key.
 4. Bounded views: the program listing shows at most `MAX_LISTING` written instructions
    (those around the tasks' instructions first), the Logic Task at most `MAX_LISTING` lines,
    the user variables those that are not 0 (at most 100); the rest is reached by its name.
    Test: test_clm_program_listing_is_bounded_around_the_tasks.
"""

from __future__ import annotations

import re
from decimal import Decimal, InvalidOperation
from typing import Any

from axisline.devices.clm.client import ClmClient
from axisline.devices.clm.errors import SERIAL_ERRORS, ClmError
from axisline.devices.clm.fields import USER_VARIABLES, format_variable, parse_variable_value
from axisline.devices.clm.memory import VARIABLE_COUNT
from axisline.devices.clm.operands import Operand
from axisline.devices.clm.parameters import PARAMETERS, format_data, parse_data
from axisline.devices.clm.serial import ClmSerialEndpoint
from axisline.devices.clm.telegram import emit

from . import _sections as s

__all__ = ["view", "write", "acknowledge", "MAX_LISTING"]

MAX_LISTING = 200
_SYSTEM_INPUTS = (
    ("I0.00", {0: "Parameter Mode", 1: "Automatic / Manual", 2: "E-Stop (0 = stop)", 3: "Start", 4: "Immediate Stop (0 = stop)",
               5: "Enable Axis 1", 6: "Enable Axis 2", 7: "External Clear"}),
    ("I0.01", {0: "Jog + axis 1", 1: "Jog - axis 1", 2: "Jog + axis 2", 3: "Jog - axis 2", 4: "Raster axis 2", 6: "Re-Start",
               7: "Raster axis 1"}),
    ("I0.02", {0: "Enable Axis 3", 1: "Jog + axis 3", 2: "Jog - axis 3", 3: "Enable Axis 4", 4: "Jog + axis 4", 5: "Jog - axis 4"}),
)
_SYSTEM_OUTPUTS = (
    ("Q0.00", {0: "Manual", 1: "Automatic", 2: "Parameter", 5: "No error (active low)"}),
    ("Q0.01", {0: "Restart possible", 1: "Run Task", 5: "Inhibit Operation"}),
)
_USER_BYTES = ("I1.00", "I1.01", "Q1.00", "Q1.01")
_VARIABLE = re.compile(r"V(\d{3})\Z")


def _operand(text: str) -> Operand:
    area, rest = text[0], text[1:].split(".")
    return Operand(area, int(rest[0]), int(rest[1]), int(rest[2]) if len(rest) > 2 else None)


def _endpoint(device: Any) -> ClmSerialEndpoint:
    """The CLM's serial endpoint as `serve` offers it (its store included), with the HMI core's
    write enable (operator's permission and token, checked before a write) for --allow-writes."""
    endpoint = device.byte_endpoint()
    endpoint._writes_allowed = _allowed
    return endpoint


def _allowed() -> bool:
    return True


# -- the view ------------------------------------------------------------------------------------------


def view(device: Any) -> dict[str, Any]:
    rt = device.rt
    memory = device.memory
    modes = rt.modes
    sections: list[dict[str, Any]] = []
    fault = modes.fault_error
    rows = [(fault.code, f"{fault.text}: {fault.detail}" + (f" ({fault.where})" if fault.where else ""), True)] if fault is not None \
        else [("00", "no error" + (" (Parameter mode)" if modes.mode == "parameter" else ""), False)]
    if device.store_error:
        rows.append(("store", f"memory file not written: {device.store_error}", True))
    sections.append(s.diagnostics(f"Fault (mode: {modes.mode})", rows))
    sections += _screens(device)
    sections.append(_tasks(device))
    sections.append(_program(device))
    logic = sorted(memory.logic.items())[:MAX_LISTING]
    state = "running" if rt.logic is not None and modes.logic_may_run() else "stopped"
    sections.append(s.text(f"Logic Task ({state}, {len(memory.logic)} instructions)", [f"{n:04d} {text}" for n, text in logic]))
    sections.append(_io(device))
    params = device.memory.parameters
    sections += s.cached(device, "parameters", (params, params.version), lambda: _parameters(device))
    sections.append(_variables(device))
    meter = getattr(device, "meter", None)
    if meter is not None:
        unit = device.machine.axis(device.config.axes[0]).config.unit
        sections.append(s.cut_table(f"Cuts (the last {s.MAX_ROWS})", meter.records, unit))
    return {"title": f"Rexroth CLM1.4 (axes {', '.join(device.config.axes)})", "sections": sections}


class _Panel(ClmClient):
    """The PC tool's CTA screens, answered by a session of the CLM's own endpoint (decision 2)."""

    def __init__(self, endpoint: ClmSerialEndpoint) -> None:  # (no socket: not ClmClient's __init__)
        self.session = endpoint.session()
        self.station = endpoint.settings.station
        self.address = ("hmi", 0)
        self.timeout = 0.0

    def exchange(self, requests: list[str]) -> list[str]:
        lines = self.session.feed("".join(r + "\r\n" for r in requests).encode("ascii")).decode("ascii", "replace").split("\r\n")
        replies: list[str] = []
        for request in requests:
            wants_53 = request[2:3] == "X" and request[3:].split("$")[0].split()[:1] == ["53"]
            while lines and lines[0][:1] == "X" and lines[0][2:4] == "53" and not wants_53:
                lines.pop(0)  # an automatic error message (B003)
            if not lines or not lines[0]:
                raise ClmError("X01:18", f"no reply to {request[:12]!r}")
            replies.append(lines.pop(0))
        return replies


_NO_INTERFACE = "the CLM has no data interface (B002: X6 serves the IDS01, B004: X8 off): no screens"


def _screens(device: Any) -> list[dict[str, Any]]:
    endpoint = _endpoint(device)
    # (without a data interface a session would only say so on stderr, at every poll of the page)
    panel = _Panel(endpoint) if endpoint.settings.data_interface else None
    out = []
    for name, title in (("position", "CTA: position"), ("tasks", "CTA: tasks"), ("error", "CTA: error (F1)"), ("io", "CTA: I/O status")):
        try:
            lines = panel.screen(name) if panel is not None else [_NO_INTERFACE]
        except ClmError as e:
            lines = [e.detail]
        out.append(s.text(title, lines))
    return out


def _tasks(device: Any) -> dict[str, Any]:
    rt = device.rt
    program = device.memory.program
    rows = []
    for t in rt.tasks:
        ins = program[t.pc]
        rows.append([f"Task {t.number}", "running" if t.running else "stopped", f"{t.pc:04d}", ins.listing(comments=False),
                     None if t.main_return is None else f"{t.main_return:04d}", len(t.stack), "waiting" if t.wait is not None else ""])
    logic = "running" if rt.logic is not None and rt.modes.logic_may_run() else "stopped"
    rows.append(["Logic Task", logic, "", f"{len(device.memory.logic)} instructions", None, 0, ""])
    return s.table("Task display", ["task", "state", "instruction", "listing", "JSR return", "stack", "wait"], rows, newest=0)


def _program(device: Any) -> dict[str, Any]:
    rt = device.rt
    written = device.memory.program.written()
    at = {t.pc: f"T{t.number}" for t in rt.tasks if t.running}
    if len(written) > MAX_LISTING:  # decision 4: the instructions around the tasks first
        near = sorted(written, key=lambda i: min((abs(i.number - pc) for pc in at), default=i.number))[:MAX_LISTING]
        written = sorted(near, key=lambda i: i.number)
    counters = device.memory.program.counters
    rows = [[f"{i.number:04d}", at.get(i.number, ""), i.listing(comments=False)[5:], i.comment, counters.get(i.number)] for i in written]
    return s.table(f"Program ({len(device.memory.program)} instructions)", ["instruction", "task", "command", "comment", "counter"],
                   rows, newest=0)


def _io(device: Any) -> dict[str, Any]:
    image = device.rt.image
    wired_in = {name: value if isinstance(value, str) else str(value).lower() for name, value in device.config.inputs.items()}
    wired_out = dict(device.config.outputs)
    words = []
    for byte, names in _SYSTEM_INPUTS + _SYSTEM_OUTPUTS:
        words.append(s.word(byte, image.get(_operand(byte)), names, 8))
    for byte in _USER_BYTES:
        wired = wired_in if byte[0] == "I" else wired_out
        names = {b: f"{byte}.{b} {wired[f'{byte}.{b}']}" if f"{byte}.{b}" in wired else f"{byte}.{b}" for b in range(8)}
        words.append(s.word(byte, image.get(_operand(byte)), names, 8))
    return s.bits("Inputs and outputs (system I0.00-I0.02, Q0.00-Q0.01; user I1, Q1)", words)


def _field_row(params: Any, pid: str, f: Any, value: Any, used: bool) -> dict[str, Any]:
    spec = PARAMETERS[pid]
    lo, hi = f.low, f.high
    extra: dict[str, Any] = {"form": f.form, "in_use": used}
    if f.allowed is not None:
        numeric = [a for a in f.allowed if isinstance(a, (int, Decimal))]
        if numeric:
            lo, hi = min(numeric), max(numeric)
        extra["allowed"] = [s.clean(a) for a in f.allowed]
    shown = str(value) if isinstance(value, Operand) or f.kind in ("hex", "sign") else value
    label = f"{spec.name}: {f.meaning or f.name.replace('_', ' ')}"
    return s.row(f"{pid}.{f.name}", label, shown, f.unit, lo, hi, True, **extra)


def _parameters(device: Any) -> list[dict[str, Any]]:
    params = device.memory.parameters
    axes = {f"A{n}" for n in range(1, len(device.config.axes) + 1)}
    groups: dict[str, list[dict[str, Any]]] = {}
    for pid, spec in PARAMETERS.items():
        group = pid[:2]
        if group[0] == "A" and group not in axes:
            continue  # an axis the machine has not got
        used = params.used(pid)
        value = params.get(pid)
        for f, v in zip(spec.fields, value.values):
            groups.setdefault(group, []).append(_field_row(params, pid, f, v, used))
    titles = {"B0": "General parameters B000-B019", "C0": "Encoder parameters C000-C008"}
    return [s.parameters(titles.get(g, f"Axis {g[1]} parameters {g}00-{g}42") + " (written in Parameter mode)", rows)
            for g, rows in groups.items()]


def _variables(device: Any) -> dict[str, Any]:
    values = device.memory.variables.user()
    rows = [s.row(f"V{n:03d}", "user variable", format_variable(raw), "", "-99999999.999999", "+99999999.999999", True)
            for n, raw in sorted(values.items()) if raw][:100]
    return s.parameters("User variables V600-V999 (not 0)", rows)


# -- writes ----------------------------------------------------------------------------------------


def write(device: Any, name: str, value: Any) -> tuple[Any, Any]:
    m = _VARIABLE.match(name.upper())
    if m is not None:
        return _write_variable(device, int(m.group(1)), value)
    pid, _, field = name.partition(".")
    pid = pid.upper()
    spec = PARAMETERS.get(pid)
    if spec is None:
        raise ValueError(f"name: {name!r} is not a CLM parameter (B000..B019, A100..A442, C000..C008, or <id>.<field>) "
                         f"nor a user variable (V600..V999)")
    params = device.memory.parameters
    if device.rt.modes.mode != "parameter":  # the CLM's own refusal (serial.py decision 8), said in full
        raise ValueError(f"{pid}: 05 {SERIAL_ERRORS[5]}: parameters are written only in Parameter mode "
                         f"(the CLM is in {device.rt.modes.mode})")
    current = params.get(pid)
    try:
        if field:
            f = next((f for f in spec.fields if f.name == field), None)
            if f is None:
                raise ValueError(f"name: {name!r}: {pid} has the fields {', '.join(f.name for f in spec.fields) or '(none)'}")
            new = current.replace(**{field: _field_value(pid, f, value)})
        else:
            if not isinstance(value, str):
                raise ValueError(f"{pid} = {value!r}: give its data in the CLM's columns, e.g. {format_data(pid, current)!r}")
            new = parse_data(pid, value)
    except ClmError as e:
        raise ValueError(f"{pid}: {e.detail}") from None
    for f, v in zip(spec.fields, new.values):  # decision 1: the range check of leaving Parameter mode, now
        if f.checked and not _in_range(f, v):
            unit = f" {f.unit}" if f.unit else ""
            raise ValueError(f"{pid}.{f.name} = {s.clean(v)}{unit}: allowed {f.range_text()}{unit} ({spec.lines})")
    old_shown = _shown(current, field)
    _send(device, "K", f" {pid} {format_data(pid, new)}")
    return old_shown, _shown(params.get(pid), field)


def _in_range(f: Any, value: Any) -> bool:
    from axisline.devices.clm.parameters import _in_range as check  # the CLM's own field check

    return check(f, value)


def _field_value(pid: str, f: Any, value: Any) -> Any:
    """A field value as `ParamValue.replace` takes it: a str is read in the field's columns."""
    if isinstance(value, bool):
        raise ClmError("02", f"{f.name} = {value!r}: give a number")
    if isinstance(value, str):
        return value.strip()
    if f.kind in ("digit", "number") and isinstance(value, (int, float)):
        try:
            number = Decimal(str(value))
        except InvalidOperation:
            raise ClmError("02", f"{f.name} = {value!r} is not a number") from None
        if not number.is_finite():
            raise ClmError("02", f"{f.name} = {value!r} is not a finite number")
        if f.decimals == 0:
            if number != number.to_integral_value():
                raise ClmError("02", f"{f.name} = {value!r}: the field holds whole numbers ({f.form})")
            return int(number)
        if -number.as_tuple().exponent > f.decimals:  # (exponent: an int for a finite Decimal)
            raise ClmError("02", f"{f.name} = {value!r} has more decimals than the field's {f.decimals} ({f.form})")
        return number
    raise ClmError("02", f"{f.name} = {value!r}: give the field's text ({f.form})")


def _shown(value: Any, field: str) -> Any:
    v = value[field] if field else value.data
    return str(v) if isinstance(v, Operand) else v


def _write_variable(device: Any, n: int, value: Any) -> tuple[Any, Any]:
    if not USER_VARIABLES <= n < VARIABLE_COUNT:
        raise ValueError(f"V{n:03d}: 23 {SERIAL_ERRORS[23]}: only the user variables V600-V999 are written (V000-V599 are the system's)")
    if isinstance(value, bool) or not isinstance(value, (int, float, str)):
        raise ValueError(f"V{n:03d} = {value!r}: a variable holds +12345678.123456 (sign, up to 8 digits, up to 6 decimals)")
    text = str(value).strip() if not isinstance(value, float) else format(Decimal(str(value)), "f")
    try:
        raw = parse_variable_value(text)
    except ValueError as e:
        raise ValueError(f"V{n:03d} = {value!r}: {e}") from None
    variables = device.memory.variables
    old = format_variable(variables[n])
    _send(device, "V", f"{n:03d} {format_variable(raw)} ")
    return old, format_variable(variables[n])


def _send(device: Any, kind: str, body: str) -> None:
    """One write telegram through a session of the CLM's endpoint (stored before the answer)."""
    endpoint = _endpoint(device)
    settings = endpoint.settings
    if not settings.data_interface:
        raise ValueError(_NO_INTERFACE.replace("no screens", "nothing can be written over it"))
    reply = endpoint.session().feed(emit("#", settings.station, kind, body).encode("ascii")).decode("ascii", "replace")
    for line in reply.split("\r\n"):
        if line[:1] == "X" and line[2:5] == "01 ":  # Status 01: refused, nothing changed
            number = line[5:7]
            code = int(number) if number.isdigit() else 2
            raise ValueError(f"refused by the CLM: {code:02d} {SERIAL_ERRORS.get(code, '')} ({body.strip()})")


def acknowledge(device: Any) -> str:
    """Decision 3: the CL key."""
    modes = device.rt.modes
    fault = modes.fault_error
    if fault is None:
        return ""
    modes.clear()
    if modes.fault_error is not None:
        return f"CLM CL key: fault {fault.code} {fault.text} not cleared (its cause is still there)"
    return f"CLM CL key: fault {fault.code} {fault.text}"


def faults(device: Any) -> dict[str, str]:
    """The CLM's fault (its display's error) and a memory file it could not write, for the event log."""
    fault = device.rt.modes.fault_error
    out = {}
    if fault is not None:
        out[f"CLM error {fault.code}"] = f"{fault.text}: {fault.detail}" + (f" ({fault.where})" if fault.where else "")
    if device.store_error:
        out["CLM memory file"] = f"not written: {device.store_error}"
    return out
