"""Who is making the network request the cycle is answering now, and whether it is a write.

`axisline serve` answers protocol and HMI requests at cycle boundaries (serve/link.py). Around
each one it sets `current` to a `Request` naming the client; a device's write gate (reading
`Personality.network_writes`) calls `note_write_gate()`, which marks the request as a write
and lets the audit take the "old" values before the device applies anything. The event log
then says who wrote what, old -> new, or that the write was refused (serve/audit.py).

A module-level holder, not a context variable: requests are answered one at a time, in the
cycle's own thread; outside `serve` nothing sets it and the gate costs one attribute read.
"""

from __future__ import annotations

from typing import Any, Callable

__all__ = ["Request", "current", "note_write_gate"]


class Request:
    """One network request being answered: its client and what the audit took before."""

    __slots__ = ("who", "endpoint", "write", "before", "snapshot")

    def __init__(self, who: str, endpoint: str, snapshot: Callable[[], dict[str, Any]] | None = None) -> None:
        self.who = who
        self.endpoint = endpoint
        self.write = False  # the device consulted its write gate
        self.before: dict[str, Any] | None = None  # the audited values before the write
        self.snapshot = snapshot


#: the request being answered (set and cleared by serve/link.py), else None
current: list[Request | None] = [None]


def note_write_gate() -> None:
    """A device is about to decide on a write: mark the request and take the "old" values once."""
    request = current[0]
    if request is None or request.write:
        return
    request.write = True
    if request.snapshot is not None:
        try:
            request.before = request.snapshot()
        except Exception:  # an audit must never break the write it watches
            request.before = None
