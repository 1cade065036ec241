"""A stand-in for axisline.serve.events.EventLog (the lead's), with the same API, for the
HMI tests and the harness until that module exists."""

from __future__ import annotations

import threading
import time
from collections import deque
from typing import Any


class EventLog:
    def __init__(self, keep: int = 10000) -> None:
        self._lock = threading.Lock()
        self._events: deque[dict[str, Any]] = deque(maxlen=keep)
        self._seq = 0

    def emit(self, kind: str, message: str, **fields: Any) -> dict[str, Any]:
        with self._lock:
            self._seq += 1
            event = {"seq": self._seq, "time": time.time(), "kind": kind, "message": message, **fields}
            self._events.append(event)
        return event

    def recent(self, after: int = 0, limit: int = 200) -> list[dict[str, Any]]:
        with self._lock:
            return [e for e in self._events if e["seq"] > after][:limit]


def event_log() -> Any:
    """The real EventLog when it exists, else this stand-in."""
    try:
        from axisline.serve.events import EventLog as Real
    except ImportError:
        return EventLog()
    return Real()
