"""The event log of a served machine: what happened, when, and who did it.

`axisline serve` records every event an operator or a maintainer asks about afterwards:
clients connecting and leaving, every accepted and refused write (who, what, old -> new),
watchdog trips, faults and their acknowledgement, cycle overruns, start and stop. Each event
goes to the console in readable form and, with `serve --log FILE`, to FILE as one JSON object
per line (appended, flushed per line, so `tail -f` and a kill -9 both see every line).

The log lives in the endpoint process (serve/endpoint_process.py): printing and file writes
never cost the cycle. The cycle process sends its events over the link; they are stamped
there with the cycle they happened in, and here with the wall time they were logged.

An event is a dict: "seq" (1, 2, ... in logging order), "time" (ISO 8601, UTC, ms), "kind",
"message" (one readable line) and the kind's own fields. Kinds in use:

    start, stop          the machine starts/stops serving (fields: machine, cycle_us, ...)
    connect, disconnect  a client of an endpoint (endpoint, who)
    write                a write from the network (endpoint, who, what, old, new, accepted,
                         reason when refused)
    fault, acknowledge   an axis or device fault appearing / acknowledged (source, code, text,
                         who for an acknowledgement)
    watchdog             a device watchdog tripped (source, text)
    overrun              cycles that ended after their deadline (count, late_ms; rate limited
                         by the cycle side: at most one event a second)
"""

from __future__ import annotations

import json
import queue
import threading
from collections import deque
from datetime import datetime, timezone
from pathlib import Path
from typing import Any, Callable, TextIO

__all__ = ["EventLog", "format_event"]

#: events kept in memory for the HMI's event page and `recent()`
KEEP = 2000
#: console lines waiting to be printed; beyond, lines are dropped (and counted) rather than
#: holding up the endpoint process
CONSOLE_BACKLOG = 10_000


def format_event(event: dict[str, Any]) -> str:
    """One console line: time, kind, message."""
    return f"{event['time'][11:23]} {event['kind']:<11} {event['message']}"


def _jsonable(value: Any) -> Any:
    # Fields come from devices: tuples, numpy scalars, bytes. The JSON line must never fail.
    if isinstance(value, (str, int, float, bool)) or value is None:
        if isinstance(value, float) and value != value:
            return None
        return value
    if isinstance(value, bytes):
        return value.decode("latin-1")
    if isinstance(value, dict):
        return {str(k): _jsonable(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_jsonable(v) for v in value]
    item = getattr(value, "item", None)  # numpy scalar
    if callable(item):
        try:
            return _jsonable(item())
        except Exception:
            pass
    return str(value)


class EventLog:
    """Thread-safe event log: console lines, optional JSON lines file, recent events in memory."""

    def __init__(
        self,
        console: Callable[[str], None] | None = None,
        json_path: str | Path | None = None,
        *,
        keep: int = KEEP,
    ) -> None:
        self._console = console
        # the console is written by a thread of its own: a terminal or pipe that reads slowly
        # (or not at all) must not hold up whoever emits (the link's reader: every reply)
        self._lines: queue.Queue[str | None] = queue.Queue(maxsize=CONSOLE_BACKLOG)
        self.dropped = 0  # console lines dropped while the console did not keep up
        self._writer: threading.Thread | None = None
        if console is not None:
            self._writer = threading.Thread(target=self._write_console, name="event-console", daemon=True)
            self._writer.start()
        self._lock = threading.Lock()
        self._events: deque[dict[str, Any]] = deque(maxlen=keep)
        self._seq = 0
        self._file: TextIO | None = None
        self._changed = threading.Condition(self._lock)
        if json_path is not None:
            # append: a restarted serve continues the same log; line-buffered writes
            self._file = open(json_path, "a", encoding="utf-8", buffering=1)

    def emit(self, kind: str, message: str, **fields: Any) -> dict[str, Any]:
        """Record one event; returns it (with its "seq" and "time")."""
        now = datetime.now(timezone.utc)
        with self._lock:
            self._seq += 1
            event: dict[str, Any] = {
                "seq": self._seq,
                "time": now.strftime("%Y-%m-%dT%H:%M:%S.") + f"{now.microsecond // 1000:03d}Z",
                "kind": str(kind),
                "message": str(message),
            }
            for key, value in fields.items():
                if key not in event:
                    event[key] = _jsonable(value)
            self._events.append(event)
            if self._file is not None:
                try:
                    self._file.write(json.dumps(event, ensure_ascii=False, allow_nan=False) + "\n")
                except (OSError, ValueError):
                    pass  # a full disk must not stop the machine; the console still shows it
            self._changed.notify_all()
        if self._writer is not None:
            try:
                self._lines.put_nowait(format_event(event))
            except queue.Full:
                self.dropped += 1
        return event

    def _write_console(self) -> None:
        assert self._console is not None
        while True:
            line = self._lines.get()
            if line is None:
                return
            dropped, self.dropped = self.dropped, 0
            if dropped:
                self._console(f"({dropped} event line(s) not shown: the console did not keep up; --log has them all)")
            self._console(line)

    def recent(self, after: int = 0, limit: int = 200) -> list[dict[str, Any]]:
        """The events with seq > after, oldest first, at most ``limit`` (the newest ones)."""
        with self._lock:
            events = [e for e in self._events if e["seq"] > after]
        return events[-limit:] if limit > 0 else []

    def wait(self, after: int, timeout: float) -> bool:
        """Block until an event with seq > after exists (True) or the timeout passes (False)."""
        with self._changed:
            return self._changed.wait_for(lambda: self._seq > after, timeout)

    @property
    def last_seq(self) -> int:
        with self._lock:
            return self._seq

    def close(self) -> None:
        if self._writer is not None:
            try:
                self._lines.put(None, timeout=2.0)
            except queue.Full:
                pass
            self._writer.join(2.0)
        with self._lock:
            if self._file is not None:
                self._file.close()
                self._file = None
