"""The machine as the web HMI sees it: read-outs and the few writes, run at cycle boundaries.

`MachineView.call(method, args, who)` runs in the cycle process, between two cycles (the
endpoint process submits it through the machine's command queue), so every answer is one
consistent picture of the machine and a write lands exactly at a boundary, as a fieldbus
write does. Answers are plain JSON values (numbers, strings, lists, dicts; a non-finite
number becomes null), so they cross a process boundary and `json.dumps` unchanged.

Methods:

    overview     machine name, cycle, time, personality, faults, and every axis: PLCopen
                 state, position, velocity, following error, error id and text, unit
    channels     the scope's channels with unit and kind, its capacity and sample period
    scope        {"channels": [...], "since": n[, "limit": m]}: the samples n.. of those
                 channels from the machine's trace (at most `MAX_SAMPLES` per call) and
                 the `next` sample number to ask for
    io           the digital I/O image (inputs with their forcing, outputs) and the sensors
    device       the personality's device view (axisline.hmi.devices), sections of a page
    write        {"target": "device"|"io", "name": ..., "value": ...}: a device parameter
                 through the personality's own validation, or an input force
    acknowledge  fault reset of the device and of every axis in ErrorStop

Every write and acknowledge is an event (`emit`), accepted or refused with the reason; a
refused write raises `HmiRefused` and changes nothing.

Decisions:

1. Issue 17 "I/O image": the HMI forces digital *inputs* only (true/false; null
   releases the force); an output is the controller's, and forcing it from a web page
   would move the plant behind the program's back. Refused with 400 naming the output.
   Test: tests/hmi/test_api.py::test_io_output_force_refused.
2. Issue 17 "live scope": a client more than `limit` samples behind gets the newest
   `limit` samples and a `skipped` count, not the backlog: a live scope shows the present,
   and the cycle never copies more than `MAX_SAMPLES` samples per channel at a boundary.
   Test: tests/hmi/test_api.py::test_scope_far_behind_skips_to_the_newest.
3. Issue 17 "faults with acknowledge": acknowledge resets every axis in ErrorStop
   (PLCopen MC_Reset: the axis leaves ErrorStop once its error ramp has ended) and then
   the device's own diagnostics; it is one request because the operator acknowledges the
   machine, not an axis. Test: tests/hmi/test_api.py::test_acknowledge_resets_a_tripped_axis.
"""

from __future__ import annotations

import importlib
import importlib.util
import math
from enum import Enum
from fractions import Fraction
from typing import Any, Callable

import numpy as np

from axisline.motion.axis import AxisState

__all__ = ["HmiRefused", "MachineView", "MAX_SAMPLES", "jsonable"]

#: samples of one scope call (per channel): bounds the copy made at a cycle boundary
MAX_SAMPLES = 5000
#: channels of one scope call
MAX_CHANNELS = 16


class HmiRefused(Exception):
    """A request the HMI refuses: `status` is the HTTP status (400 bad request, 403 not
    allowed, 404 no such thing); the message names the field, the value and what is allowed."""

    def __init__(self, message: str, status: int = 400) -> None:
        super().__init__(message, status)  # both in args: the refusal pickles across processes
        self.message = message
        self.status = status

    def __str__(self) -> str:
        return self.message


def jsonable(value: Any) -> Any:
    """`value` as plain JSON: numpy scalars and arrays, enums and fractions converted,
    NaN and infinities as None (strict JSON has no such numbers)."""
    if value is None or isinstance(value, (bool, str, int)):
        return value
    if isinstance(value, float):
        return value if math.isfinite(value) else None
    if isinstance(value, dict):
        return {str(k): jsonable(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [jsonable(v) for v in value]
    if isinstance(value, Enum):
        return jsonable(value.value)
    if isinstance(value, Fraction):
        return float(value)
    tolist = getattr(value, "tolist", None)  # numpy scalars and arrays
    if tolist is not None:
        return jsonable(tolist())
    return str(value)


def _devices_module() -> Any:
    """axisline.hmi.devices (the device views), or None while it does not exist yet.

    A module that exists but fails to import is a bug to see, not a page to hide."""
    if importlib.util.find_spec("axisline.hmi.devices") is None:
        return None
    return importlib.import_module("axisline.hmi.devices")


def _number(x: Any) -> float | None:
    x = float(x)
    return x if math.isfinite(x) else None


class MachineView:
    """Answers the HMI's requests from a Machine; call only between cycles."""

    def __init__(self, machine: Any, emit: Callable[..., Any]) -> None:
        self.machine = machine
        self.emit = emit
        self._methods: dict[str, Callable[[dict[str, Any], str], Any]] = {
            "overview": self._overview,
            "channels": self._channels,
            "scope": self._scope,
            "io": self._io,
            "device": self._device,
            "write": self._write,
            "acknowledge": self._acknowledge,
        }

    def call(self, method: str, args: dict[str, Any] | None, who: str) -> Any:
        fn = self._methods.get(method)
        if fn is None:
            raise HmiRefused(f"method {method!r}: no such request (known: {', '.join(self._methods)})", 404)
        if args is None:
            args = {}
        if not isinstance(args, dict):
            raise HmiRefused(f"args: a JSON object expected, got {type(args).__name__}")
        if method == "scope":  # thousands of samples, made JSON by numpy: not walked again
            return fn(args, who)
        return jsonable(fn(args, who))

    # -- read-outs ------------------------------------------------------------------

    def _overview(self, args: dict[str, Any], who: str) -> dict[str, Any]:
        m = self.machine
        axes = []
        for name, unit in m.units.items():
            ax = unit.axis
            axes.append({
                "name": name,
                "state": ax.state.value,
                "powered": bool(ax.powered),
                "position": _number(ax.actual_position),
                "command_position": _number(ax.command_position),
                "velocity": _number(unit.drive.velocity * unit.feedback_sign),
                "following_error": _number(ax.following_error),
                "error_id": int(ax.error_id),
                "error": ax.error_text,
                "warning": getattr(ax, "warning", None) or "",
                "unit": unit.config.unit,
            })
        return {
            "name": m.config.machine.name,
            "personality": m.config.machine.personality,
            "cycle": m.clock.cycle,
            "time": m.clock.now,
            "period_us": m.clock.period_us,
            "axes": axes,
            "faults": list(m.faults[-20:]),
            "job": {"finished": bool(m.job.finished), "failed": m.job.failed},
        }

    def _channels(self, args: dict[str, Any], who: str) -> dict[str, Any]:
        tr = self.machine.trace
        if tr is None:
            return {"channels": [], "capacity": 0, "period_s": None, "mode": None}
        units = tr.units
        return {
            "channels": [{"name": c, "unit": units.get(c, ""), "kind": tr.kind(c)} for c in tr.channels],
            "capacity": tr.capacity,
            "period_s": tr.decimation * tr.period_us / 1e6,
            "mode": tr.mode,
        }

    def _scope(self, args: dict[str, Any], who: str) -> dict[str, Any]:
        tr = self.machine.trace
        if tr is None:
            raise HmiRefused("scope: this machine records no trace ([trace] enabled = false)", 404)
        channels = args.get("channels", [])
        if isinstance(channels, str):
            channels = [c for c in channels.split(",") if c]
        if not isinstance(channels, list) or not all(isinstance(c, str) for c in channels):
            raise HmiRefused(f"channels: a list of channel names expected, got {channels!r}")
        if len(channels) > MAX_CHANNELS:
            raise HmiRefused(f"channels: {len(channels)} channels asked, at most {MAX_CHANNELS} per request")
        known = tr.channels
        for c in channels:
            if c not in known:
                raise HmiRefused(f"channels: unknown channel {c!r} (available: {', '.join(known)})")
        since = _count_arg(args, "since", 0, 0, None)
        limit = _count_arg(args, "limit", MAX_SAMPLES, 1, MAX_SAMPLES)
        # sample n is the n-th the trace stored (Trace.stored counts every one, overwritten
        # ones included); a ring keeps the newest `capacity`
        stored = tr.stored
        if since > stored:  # a client from before the scope was re-armed: start anew
            since = stored - min(len(tr), limit)
        start, columns = tr.since(since, channels, limit)  # decision 2: the newest `limit` samples
        units = tr.units
        return {
            "since": start,
            "next": stored,
            "skipped": start - since,
            "t": columns["t"].tolist(),
            "data": {c: _samples(columns[c]) for c in channels},
            "units": {c: units.get(c, "") for c in channels},
        }

    def _io(self, args: dict[str, Any], who: str) -> dict[str, Any]:
        m = self.machine
        io = m.io
        forced = io.forced
        return {
            "inputs": [{"name": n, "value": io.read(n), "forced": forced.get(n)} for n in io.inputs],
            "outputs": [{"name": n, "value": io.output(n), "forced": forced.get(n)} for n in io.outputs],
            "sensors": [{"name": n, "value": bool(s.state)} for n, s in m.sensors.items()],
        }

    def _device(self, args: dict[str, Any], who: str) -> dict[str, Any]:
        dev = self.machine.device
        if dev is None:
            return {"title": "no device personality", "sections": []}
        mod = _devices_module()
        if mod is None:
            return {"title": str(self.machine.config.machine.personality), "sections": []}
        try:
            return mod.device_view(dev)
        except ValueError as e:  # a personality without a device view (yet)
            raise HmiRefused(str(e), 404) from None

    # -- writes ---------------------------------------------------------------------

    def _write(self, args: dict[str, Any], who: str) -> dict[str, Any]:
        target, name, value = args.get("target"), args.get("name"), args.get("value")
        what = f"{target}.{name}"
        try:
            if "value" not in args:
                raise HmiRefused("value: missing (the value to write)")
            if not isinstance(name, str) or not name:
                raise HmiRefused(f"name: a parameter or input name expected, got {name!r}")
            if target == "device":
                old, new = self._write_device(name, value)
            elif target == "io":
                old, new = self._force_input(name, value)
            else:
                raise HmiRefused(f"target: {target!r} is not writable (allowed: 'device', 'io')")
        except HmiRefused as e:
            self.emit("write", f"{who}: write {what} = {value!r} refused: {e.message}", endpoint="http", who=who,
                      what=what, target=target, name=name, value=jsonable(value), accepted=False, reason=e.message)
            raise
        self.emit("write", f"{who}: {what}: {_shown(old)} -> {_shown(new)}", endpoint="http", who=who,
                  what=what, target=target, name=name, old=jsonable(old), new=jsonable(new), accepted=True)
        return {"target": target, "name": name, "old": old, "new": new}

    def _write_device(self, name: str, value: Any) -> tuple[Any, Any]:
        dev = self.machine.device
        if dev is None:
            raise HmiRefused("target: 'device': this machine has no device personality", 404)
        mod = _devices_module()
        if mod is None:
            raise HmiRefused(f"target: 'device': the {self.machine.config.machine.personality} device view is not available", 404)
        try:
            return mod.device_write(dev, name, value)
        except ValueError as e:  # the device's own validation: names the parameter, value and range
            raise HmiRefused(str(e)) from None

    def _force_input(self, name: str, value: Any) -> tuple[Any, Any]:
        io = self.machine.io
        if name not in io.inputs:
            if name in io.outputs:
                raise HmiRefused(f"name: {name!r} is an output; the HMI forces inputs only (inputs: {', '.join(io.inputs) or 'none'})")
            raise HmiRefused(f"name: no digital input {name!r} (inputs: {', '.join(io.inputs) or 'none'})", 404)
        if isinstance(value, int) and not isinstance(value, bool) and value in (0, 1):
            value = bool(value)
        if value is not None and not isinstance(value, bool):
            raise HmiRefused(f"value: {value!r} for input {name!r}: true or false forces it, null releases the force")
        old = _level(io, name)
        if value is None:
            io.release(name)
            return old, "not forced"  # the physical level again from the next sample
        io.force(name, value)
        return old, _level(io, name)

    def _acknowledge(self, args: dict[str, Any], who: str) -> dict[str, Any]:
        m = self.machine
        reset = []
        for name, unit in m.units.items():
            ax = unit.axis
            if ax.state is AxisState.ERROR_STOP:
                text = ax.error_text
                ax.reset()  # leaves ErrorStop at once, or when the error ramp has ended
                reset.append({"axis": name, "error": text})
        device = ""
        if m.device is not None:
            mod = _devices_module()
            if mod is not None:
                try:
                    device = str(mod.device_acknowledge(m.device))
                except ValueError as e:  # the device refuses, or has no device view: said, axes still reset
                    device = f"device not acknowledged: {e}"
        parts = [f"axis {r['axis']} ({r['error']})" for r in reset] + ([device] if device else [])
        self.emit("acknowledge", f"{who}: acknowledged {', '.join(parts) or 'no active fault'}",
                  endpoint="http", who=who, axes=[r["axis"] for r in reset], device=device)
        return {"axes": reset, "device": device}


def _samples(column: np.ndarray) -> list[Any]:
    """A trace column as a JSON list: NaN and infinities (a float channel) as None."""
    if column.dtype.kind == "f" and not np.isfinite(column).all():
        return [x if math.isfinite(x) else None for x in column.tolist()]
    return column.tolist()


def _shown(value: Any) -> str:
    """A value in an event's message: text as it reads ("forced True"), numbers as numbers."""
    return value if isinstance(value, str) else repr(value)


def _level(io: Any, name: str) -> str:
    """An input as the operator reads it: its value and whether it is forced."""
    forced = io.forced.get(name)
    return f"forced {forced}" if forced is not None else f"{io.read(name)}"


def _count_arg(args: dict[str, Any], name: str, default: int, low: int, high: int | None) -> int:
    value = args.get(name, default)
    if isinstance(value, str) and value.strip().isdigit():
        value = int(value)
    if isinstance(value, bool) or not isinstance(value, int) or value < low or (high is not None and value > high):
        allowed = f"{low}..{high}" if high is not None else f">= {low}"
        raise HmiRefused(f"{name}: {value!r} is not an integer in {allowed}")
    return value
