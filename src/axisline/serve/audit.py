"""The audit of writes from the network: who wrote what, old -> new, or why it was refused.

Runs in the cycle process around each request (serve/link.py). Two kinds of write:

- a Modbus register write (FC6/FC16): the registers are read before it (holding registers,
  where the device has them), so the event lists every register's old -> new; a refused write
  gets the device's reason (its exception text) and, by the endpoints' all-or-nothing rule,
  changed nothing;
- a byte-protocol request that reached a device's write gate (`Personality.network_writes`,
  kernel/requests.py): the device's parameter image is taken at the gate, before the device
  applies anything, and again after; the event lists the values that changed. Without the
  operator's enable the write is refused by the gate. A write the device answered without
  changing a stored value (a value out of range, a locked command) is logged as not accepted,
  with the device's reply: that is the device's own refusal, in its own words.

The parameter image is what the HMI's device view lists as parameters (hmi/devices): one
place says what a device's parameters are. It is taken only when a request is a write.
"""

from __future__ import annotations

from typing import Any, Callable

from ..kernel.requests import Request

__all__ = ["Audit"]

_TEXT_MAX = 160  # characters of a request or reply quoted in an event


def _text(data: Any) -> str:
    if isinstance(data, (bytes, bytearray)):
        data = bytes(data).decode("latin-1")
    text = " ".join(str(data).replace("\r", " ").replace("\n", " ").split())
    return text if len(text) <= _TEXT_MAX else text[: _TEXT_MAX - 3] + "..."


class Audit:
    """Writes to the event log (``emit(kind, message, **fields)``) for one served machine."""

    def __init__(self, device: Any, emit: Callable[..., None], image: Callable[[], dict[str, Any]] | None = None) -> None:
        self._device = device
        self._emit = emit
        self._image = image if image is not None else _parameter_image(device)

    def snapshot(self) -> dict[str, Any]:
        return self._image() if self._image is not None else {}

    # -- register writes (Modbus) -----------------------------------------------------------

    def registers_before(self, endpoint: Any, address: int, values: list[int]) -> list[int] | None:
        try:
            return [int(v) for v in endpoint.read_registers("holding", address, len(values))]
        except Exception:  # write-only registers: the event says so
            return None

    def register_write(self, request: Request, args: tuple, before: list[int] | None, ok: bool, result: Any) -> None:
        address, values = args[0], list(args[1])
        what = f"register {address}" if len(values) == 1 else f"registers {address}..{address + len(values) - 1}"
        if ok:
            changes = [
                {"what": f"register {address + i}", "old": None if before is None else before[i], "new": v}
                for i, v in enumerate(values)
            ]
            shown = ", ".join(f"{c['what']}: {'?' if c['old'] is None else c['old']} -> {c['new']}" for c in changes)
            self._emit("write", f"{request.who}: {shown}", endpoint=request.endpoint, who=request.who,
                       what=what, changes=changes, accepted=True)
        else:
            reason = _text(result) or type(result).__name__
            self._emit("write", f"{request.who}: write of {what} = {values} refused: {reason}",
                       endpoint=request.endpoint, who=request.who, what=what, new=values, accepted=False, reason=reason)

    # -- byte-protocol writes -----------------------------------------------------------------

    def byte_write(self, request: Request, args: tuple, ok: bool, result: Any) -> None:
        what = _text(args[0]) if args else ""
        enabled = bool(getattr(self._device, "_network_writes", False))
        if not enabled:
            reason = "network writes are not enabled (serve --allow-writes)"
            self._emit("write", f"{request.who}: {what!r} refused: {reason}", endpoint=request.endpoint,
                       who=request.who, what=what, accepted=False, reason=reason)
            return
        before = request.before or {}
        after = self.snapshot() if request.before is not None else {}
        changes = [
            {"what": name, "old": before.get(name), "new": value}
            for name, value in after.items()
            if before.get(name) != value
        ]
        reply = _text(result) if ok else f"{type(result).__name__}: {_text(result)}"
        if changes:
            shown = ", ".join(f"{c['what']}: {c['old']} -> {c['new']}" for c in changes)
            self._emit("write", f"{request.who}: {what!r}: {shown}", endpoint=request.endpoint, who=request.who,
                       what=what, changes=changes, accepted=True, reply=reply)
        else:
            self._emit("write", f"{request.who}: {what!r} changed no stored value; the device answered {reply!r}",
                       endpoint=request.endpoint, who=request.who, what=what, accepted=False,
                       reason=f"no stored value changed; the device answered {reply!r}", reply=reply)


def _parameter_image(device: Any) -> Callable[[], dict[str, Any]] | None:
    """name -> value of the device's parameters, from its HMI device view."""
    if device is None:
        return None
    try:
        from ..hmi.devices import device_view
    except ImportError:
        return None

    def image() -> dict[str, Any]:
        values: dict[str, Any] = {}
        for section in device_view(device).get("sections", ()):
            if section.get("type") == "parameters":
                for row in section.get("rows", ()):
                    values[str(row.get("name"))] = row.get("value")
        return values

    return image
