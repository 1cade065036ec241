"""The WAGO 750-672's device view: per module its process image decoded, mailbox, configuration
table and error memory; the coupler's watchdog.

Read from the coupler (`coupler.py`: the output image as the PLC wrote it, the input image as
the module returned it) decoded with the module's own codecs (`image.py`: C0..C3 / S0..S3 as
the manual's bit names, the mode's data layout), the configuration table (`config_table.py`:
every entry with its range and the device's error code) and the error memory (`errors.py`).

Writes, by row name:

    <name> / m<k>.<name>     a configuration-table value of module k (0 without the prefix)
                             through `ConfigTable.set`: the entry check the mailbox's
                             CONFIG_WR runs (`write_bytes` checks each entry it touches)
    m<k>.out<r>              output register r (0..5) of module k through the coupler's
                             `write_registers`, the path of a Modbus FC6 / FC16

Decisions:
 1. Issue 17 "the WAGO process image decoded": the output registers are writable from the HMI
    because they are the 750-672's registers a commissioning engineer sets by hand (what a
    Modbus tool does, coupler.py decision W2); a write re-arms the fieldbus watchdog like any
    Modbus write, so with watchdog_ms > 0 the module brakes with its STOP ramp when no further
    write follows: the HMI does not keep a motor running behind the PLC's back.
    Test: tests/hmi/test_device_views.py::test_wago_output_register_write_goes_to_the_module.
 2. A refused CONFIG_WR answers only "access denied" on the mailbox; the HMI gives the
    `ConfigValueError` text behind it (field, value, range and the device's error code where
    the manual names one), and nothing is stored. Test: test_wago_config_write_in_range_and_refused.
 3. Issue 17 "diagnostics with acknowledge": acknowledge is the module's DIAG_QUIT_ERROR /
    Error_Quit (`Wago672.quit_errors`) on every module: a 1xxx error clears once its cause is
    gone, a 2xxx error warm-starts the module, a 3xxx error stays until power-off (manual
    §4.4.1-4.4.4). Test: test_wago_acknowledge_quits_the_error.
"""

from __future__ import annotations

import re
from typing import Any

from axisline.devices.wago672.config_table import ConfigTable, ConfigValueError
from axisline.devices.wago672.coupler import REGISTERS_PER_MODULE, pack
from axisline.devices.wago672.errors import ERRORS, describe
from axisline.devices.wago672.image import (
    C0, C1, C2, C3, MODE_NAMES, MODE_PROGRAM, MODE_SPEED, S0, S1, S2, S3, InputImage, OutputImage,
    PositioningSetpoints, ProgramSetpoints, SpeedSetpoints,
)

from . import _sections as s

__all__ = ["view", "write", "acknowledge"]

_NAME = re.compile(r"(?:m(\d+)\.)?(.+)\Z")
_OUT = re.compile(r"out(\d+)\Z")
#: what each output register holds (low byte | high byte), coupler.py's map
_REGISTER_BYTES = ("C0 | reserved", "D0 | D1", "D2 | D3", "D4 | D5", "D6 | C3", "C2 | C1")


def _names(flag: Any) -> dict[int, str]:
    return {m.value.bit_length() - 1: m.name for m in flag}


_BITS = {k: _names(f) for k, f in (("C0", C0), ("C1", C1), ("C2", C2), ("C3", C3), ("S0", S0), ("S1", S1), ("S2", S2), ("S3", S3))}


def _prefix(device: Any, index: int) -> str:
    return f"m{index}." if len(device.modules) > 1 else ""


def view(device: Any) -> dict[str, Any]:
    sections: list[dict[str, Any]] = []
    coupler = device.coupler
    for m in device.modules:
        sections += _module(device, m)
    c = coupler.summary()
    sections.append(s.text("Coupler", [
        f"Modules: {c['modules']} ({c['registers_per_module']} input and output registers each)",
        f"Fieldbus watchdog: {c['watchdog_ms']} ms, {c['watchdog_status']}, {c['watchdog_expiries']} expiries",
        f"Requests: {c['reads']} reads, {c['writes']} writes",
    ]))
    axes = ", ".join(repr(m.axis) for m in device.modules)
    return {"title": f"WAGO 750-672 stepper module{'s' if len(device.modules) > 1 else ''} (axis {axes})", "sections": sections}


def _module(device: Any, m: Any) -> list[dict[str, Any]]:
    k = m.index
    dev = m.device
    pre = _prefix(device, k)
    head = f"Module {k} (axis {m.axis!r})"
    out_raw = device.coupler.outputs(k)
    out = OutputImage.from_bytes(out_raw)
    inp = InputImage.from_bytes(device.coupler.inputs(k))
    words = [s.word(f"C{n} (output)", getattr(out, f"c{n}"), _BITS[f"C{n}"], 8) for n in (0, 1, 2, 3)]
    words += [s.word(f"S{n} (input)", getattr(inp, f"s{n}"), _BITS[f"S{n}"], 8) for n in (0, 1, 2, 3)]
    sections = [s.bits(f"{head}: control and status bytes", words)]
    data = [
        s.row(f"{pre}mode", "Command (C1): mode requested", MODE_NAMES.get(out.command, str(out.command))),
        s.row(f"{pre}mode_ack", "Command_ACK (S1): mode running", MODE_NAMES.get(inp.command_ack, str(inp.command_ack))),
    ]
    if out.mailbox:
        data.append(s.row(f"{pre}mb_request", "MB0..MB5 (request)", out.mailbox_request.hex(" ")))
    elif out.command == MODE_SPEED:
        sp = SpeedSetpoints.decode(out.data)
        data += [s.row(f"{pre}set_velocity", "Velocity (set point)", sp.velocity, "speed units"),
                 s.row(f"{pre}set_acceleration", "Acceleration (set point)", sp.acceleration, "acc. units")]
    elif out.command == MODE_PROGRAM:
        data.append(s.row(f"{pre}start_counter", "Starting value for command counter", ProgramSetpoints.decode(out.data).start_counter))
    else:
        pp = PositioningSetpoints.decode(out.data)
        data += [s.row(f"{pre}set_velocity", "Velocity (set point)", pp.velocity, "speed units", 1, 25000),
                 s.row(f"{pre}set_acceleration", "Acceleration (set point)", pp.acceleration, "acc. units", 1, 32767),
                 s.row(f"{pre}set_target", "Target position", pp.target, "position units", -8388608, 8388607)]
    if inp.mailbox:
        data.append(s.row(f"{pre}mb_reply", "MB0..MB5 (reply)", inp.mailbox_reply.hex(" ")))
    elif inp.command_ack == MODE_PROGRAM:
        pa = inp.program()
        data += [s.row(f"{pre}velocity", "Current velocity", pa.velocity, "speed units"),
                 s.row(f"{pre}counter", "Current value for command counter", pa.counter),
                 s.row(f"{pre}position", "Current position", pa.position, "position units")]
    else:
        pa2 = inp.positioning()
        data += [s.row(f"{pre}velocity", "Actual velocity", pa2.velocity, "speed units"),
                 s.row(f"{pre}position", "Actual position", pa2.position, "position units")]
    sections.append(s.parameters(f"{head}: process data (D0..D6)", data))
    regs = pack(out_raw)
    sections.append(s.parameters(f"{head}: output registers (Modbus {REGISTERS_PER_MODULE * k:#06x}..)", [
        s.row(f"m{k}.out{r}", f"register {REGISTERS_PER_MODULE * k + r:#06x}: {_REGISTER_BYTES[r]}", v, "", 0, 0xFFFF, True)
        for r, v in enumerate(regs)
    ]))
    mbx = m.mailbox
    sections.append(s.text(f"{head}: mailbox", [
        f"Mailbox: {'on' if inp.mailbox else 'off'} (C0.5 {'set' if out.mailbox else 'clear'})",
        f"Last request: opcode {mbx._opcode:#04x}, toggle {1 if mbx._toggle else 0}; {mbx.executed} requests executed",
        f"Last reply: {mbx._reply.hex(' ')}",
    ]))
    cfg = dev.config
    sections += s.cached(m, "config", (cfg, cfg.generation), lambda: _config(pre, head, cfg))
    errs = dev.errors
    errs = dev.errors
    diag = []
    for code, what in ((errs.error, "error"), (errs.warning, "warning")):
        if code:
            entry = ERRORS.get(code)
            diag.append((code, f"{what}: {describe(code)}" + (f" ({errs.text})" if errs.text and entry is None else ""), True))
    if not diag:
        diag.append((0, "no error, no warning", False))
    sections.append(s.diagnostics(f"{head}: error memory (§3.12)", diag))
    sections.append(s.text(f"{head}: state", [
        f"Mode: {MODE_NAMES.get(dev.mode, str(dev.mode))}   Ready: {'yes' if dev.ready else 'no'}",
        f"Position: {dev.actual_position}   Velocity: {dev.actual_velocity}",
        f"On target: {'yes' if dev.on_target else 'no'}   Busy: {'yes' if dev.busy else 'no'}   "
        f"Reference OK: {'yes' if dev.reference_ok else 'no'}",
    ]))
    return sections


def _config(pre: str, head: str, cfg: Any) -> list[dict[str, Any]]:
    """The configuration table of a module, and its pointer table (bit linking)."""
    rows, pointers = [], []
    for e in ConfigTable.entries():
        if e.ignored:
            continue
        r = s.row(f"{pre}{e.name}", f"{e.meaning} (address {e.address}, {e.type})" if e.meaning else f"address {e.address}, {e.type}",
                  cfg.get(e.name), "", e.lo, e.hi, True,
                  **({"allowed": list(e.allowed)} if e.allowed else {}), **({"error_code": e.error_code} if e.error_code else {}))
        (pointers if e.name.startswith("Ptr_") else rows).append(r)
    return [s.parameters(f"{head}: configuration table (§4.6)", rows),
            s.parameters(f"{head}: bit linking, pointer table (§4.5)", pointers)]


def _locate(device: Any, name: str) -> tuple[Any, str]:
    m = _NAME.match(name)
    assert m is not None  # (.+ matches any non-empty name)
    index = int(m.group(1)) if m.group(1) is not None else 0
    if not 0 <= index < len(device.modules):
        raise ValueError(f"name: {name!r}: no module {index} (modules 0 .. {len(device.modules) - 1})")
    return device.modules[index], m.group(2)


def write(device: Any, name: str, value: Any) -> tuple[Any, Any]:
    module, field = _locate(device, name)
    reg = _OUT.match(field)
    if reg is not None:
        return _write_register(device, module, int(reg.group(1)), name, value)
    try:
        entry = ConfigTable.entry(field)
    except KeyError:
        raise ValueError(f"name: {name!r} is neither a configuration variable (e.g. 'SetupSpeed') nor an output "
                         f"register (m<k>.out0 .. m<k>.out{REGISTERS_PER_MODULE - 1})") from None
    if entry.ignored:
        raise ValueError(f"{entry.name} (address {entry.address}) is not documented: writes are dropped by the module")
    if isinstance(value, str) and re.fullmatch(r"\s*[+-]?\d+\s*", value):
        value = int(value)
    if isinstance(value, float) and value.is_integer():
        value = int(value)
    cfg = module.device.config
    old = cfg.get(entry.name)
    if isinstance(value, bool) or not isinstance(value, int):
        raise ValueError(f"{entry.name} = {value!r} is not an integer (allowed {entry.range_text})")
    try:
        cfg.set(entry.name, value)  # decision 2: `_check`, the test CONFIG_WR's write_bytes runs per entry
    except ConfigValueError as e:
        raise ValueError(str(e)) from None
    return old, cfg.get(entry.name)


def _write_register(device: Any, module: Any, r: int, name: str, value: Any) -> tuple[Any, Any]:
    from axisline.fieldbus.modbus import RegisterRefused

    if not 0 <= r < REGISTERS_PER_MODULE:
        raise ValueError(f"name: {name!r}: output registers are out0 .. out{REGISTERS_PER_MODULE - 1}")
    if isinstance(value, str) and re.fullmatch(r"\s*(0x[0-9a-fA-F]+|\d+)\s*", value):
        value = int(value.strip(), 0)
    if isinstance(value, bool) or not isinstance(value, int) or not 0 <= value <= 0xFFFF:
        raise ValueError(f"{name} = {value!r}: a register holds 0 .. 65535")
    coupler = device.coupler
    k = module.index
    old = pack(coupler.outputs(k))[r]
    try:
        coupler.write_registers(REGISTERS_PER_MODULE * k + r, [value])  # decision 1: the Modbus write's path
    except RegisterRefused as e:
        raise ValueError(f"{name} = {value}: {e}") from None
    return old, pack(coupler.outputs(k))[r]


def acknowledge(device: Any) -> str:
    """Decision 3: DIAG_QUIT_ERROR on every module."""
    what = []
    for m in device.modules:
        errs = m.device.errors
        held = [f"{describe(c)}" for c in (errs.error, errs.warning) if c]
        m.device.quit_errors()
        if held:
            what.append(f"module {m.index}: {'; '.join(held)}")
    return f"750-672 error quit: {', '.join(what)}" if what else ""


def faults(device: Any) -> dict[str, str]:
    """Each module's error memory and the coupler's watchdog, for the event log: a "watchdog"
    source changes its text at every expiry, so each trip is an event."""
    out = {}
    for m in device.modules:
        errs = m.device.errors
        for code, what in ((errs.error, "error"), (errs.warning, "warning")):
            if code:
                out[f"750-672 module {m.index} {what}"] = describe(code)
    expiries = device.coupler.summary()["watchdog_expiries"]
    if expiries:
        out["watchdog"] = f"fieldbus watchdog expired ({expiries} time{'s' if expiries != 1 else ''} since start)"
    return out
