"""The link between the cycle process and the endpoint process of `axisline serve`.

Why two processes: protocol servers and the HMI are Python threads; in the cycle's process
they compete with the cycle for the interpreter, and 50 polling clients made the cycle up to
80 ms late (Modbus) and 500 ms (serial). Here the cycle runs alone in its process (as the
real-time thread of LinuxCNC does) and the servers run in an endpoint process; a request
crosses one pipe and is answered by the cycle process in its idle time, between two cycles
(`CycleLink.pump`, called by the WallClock before it sleeps), so a request still sees and
changes the machine only at a cycle boundary, as before, and never inside a cycle.

Messages (tuples, pickled by multiprocessing.Connection):

    endpoint -> cycle   ("call", id, target, method, args, who, endpoint)
                        ("session", id, target, who, endpoint)   a byte session, by handle
                        ("close", handle)                        the connection ended
                        ("listening", kind, where) / ("started",) / ("failed", text)
    cycle -> endpoint   ("reply", id, ok, value or exception)
                        ("event", kind, message, fields)
                        ("shutdown",)

Two one-way pipes: requests (endpoint -> cycle) and replies and events (cycle -> endpoint). The
cycle process reads with poll(0) and writes without blocking (`_Outbox`), so a slow endpoint
process never blocks a cycle, and it has no thread of its own.
Targets are the device's endpoints by role ("byte", "register") and the HMI's view ("hmi");
sessions get handles "s1", "s2", ... A request once sent is not
withdrawn (a cancelled Future would say "not done" of a write the cycle may already have
applied): it is answered, or failed with `LinkClosed` when the cycle process goes away.

Decisions (issue 17 point -> choice, why):

1. "the cycle runs in a process of its own and talks to the endpoint/HMI process through a
   shared-memory image published once per cycle and a command queue" -> a pipe each way, and every
   request (reads included) is answered by the cycle process in its idle time; no image is
   published. Why: the answers of the serial protocols (COMPAX, CLM, FS701 Drivecom) and of the
   HMI's device views are computed by the device code, not read from a register image; a
   shared image would mean a second copy of every device's read path in the endpoint process.
   Answering in the idle time costs the cycle nothing while it has idle time, keeps one read
   path, and keeps reads consistent with a cycle boundary. Tests: tests/serve/test_link.py,
   tests/serve/test_serve.py::test_the_endpoints_run_in_a_process_of_their_own; `make bench`
   (serve lateness) holds the numbers.
2. A request once sent is never withdrawn (module docstring); a client waits for its answer
   or for the link to close. Test: test_requests_fail_with_link_closed_when_the_cycle_process_goes_away.
3. With no idle time left, one waiting request is still answered per cycle: clients of an
   overloaded machine are slowed down, never starved. Test:
   test_the_pump_answers_one_waiting_request_even_without_idle_time.
"""

from __future__ import annotations

import itertools
import os
import pickle
import struct
import threading
import time
from collections import deque
from concurrent.futures import Future
from typing import Any, Callable

from ..fieldbus.clients import current_client
from ..kernel import requests
from .audit import Audit

_LENGTH = struct.Struct("!i")  # multiprocessing.Connection's message header

__all__ = ["CycleLink", "EndpointLink", "LinkClosed", "RemoteCommands", "RemoteEndpoint", "RemoteError"]


class LinkClosed(ConnectionError):
    """The cycle process is gone (stopped or killed): the request was not answered."""


class RemoteError(RuntimeError):
    """An exception of the cycle process that could not be pickled, as its type and text."""


def _portable(exc: BaseException) -> BaseException:
    try:
        pickle.loads(pickle.dumps(exc))
        return exc
    except Exception:
        return RemoteError(f"{type(exc).__name__}: {exc}")


# ---------------------------------------------------------------------------- cycle side


HOLD_CYCLES = 50  # pumps a long request may wait for an idle time that holds it
_LONG_S = 100e-6  # a request that took longer than this is "long" (the pump schedules it)


def _cost_key(message: tuple) -> tuple:
    if message[0] != "call":
        return (message[0],)
    if message[2] == "hmi" and message[4]:
        return ("hmi", message[4][0])  # the HMI's method: "device" is long, "overview" short
    return ("call", message[3])


class _Outbox:
    """Messages to the endpoint process, written without ever blocking the cycle.

    The pipe's write end is non-blocking: what the pipe does not take now (the endpoint
    process is busy) stays here and is written at the next pump. The framing is
    multiprocessing.Connection's (a 4-byte big-endian length, then the pickle), so the
    endpoint process reads it with `Connection.recv`. No thread: a sender thread in the cycle
    process would compete with the cycle for the interpreter, which is what serve's two
    processes exist to avoid."""

    def __init__(self, conn: Any) -> None:
        self._conn = conn  # kept: closing it closes the descriptor
        self._fd = conn.fileno()
        os.set_blocking(self._fd, False)
        self._pending = bytearray()
        self.closed = False

    def put(self, message: tuple) -> None:
        try:
            data = pickle.dumps(message, protocol=pickle.HIGHEST_PROTOCOL)
        except Exception as exc:  # an unpicklable reply value: answer with its text
            if message[0] != "reply":
                return
            data = pickle.dumps(("reply", message[1], False, RemoteError(f"unsendable reply: {exc}")))
        self._pending += _LENGTH.pack(len(data)) + data
        self.flush()

    def flush(self) -> None:
        pending = self._pending
        while pending and not self.closed:
            try:
                n = os.write(self._fd, pending)
            except BlockingIOError:
                return
            except OSError:  # the endpoint process is gone
                self.closed = True
                pending.clear()
                return
            del pending[:n]

    @property
    def waiting(self) -> int:
        """Bytes not yet taken by the pipe."""
        return len(self._pending)

    def close(self, timeout: float = 5.0) -> None:
        end = time.monotonic() + timeout
        while self._pending and not self.closed and time.monotonic() < end:
            self.flush()
            time.sleep(0.001)
        self._conn.close()


class CycleLink:
    """The cycle process's end: answers requests at cycle boundaries, sends events."""

    def __init__(self, inbox: Any, outbox: Any, targets: dict[str, Callable[[], Any]], audit: Audit | None = None) -> None:
        self._conn = inbox
        self._out = _Outbox(outbox)
        self._factories = targets  # role -> factory, made on first use (a device may offer none)
        self._objects: dict[str, Any] = {}
        self._handles = itertools.count(1)
        self.audit = audit
        self.answered = 0
        self.slowest: tuple[float, str] = (0.0, "")  # the longest request answered: seconds, what
        self._costs: dict[tuple, deque[float]] = {}  # what each kind of request took lately (pump)
        self._held: tuple | None = None  # a long request waiting for enough idle time
        self._held_for = 0
        self.endpoint_messages: list[tuple] = []  # listening/started/failed, read by serve

    @property
    def closed(self) -> bool:
        return self._out.closed

    # -- sending (never blocks the cycle) ------------------------------------------------

    def send(self, message: tuple) -> None:
        self._out.put(message)

    def emit(self, kind: str, message: str, **fields: Any) -> None:
        self._out.put(("event", kind, message, fields))

    def close(self) -> None:
        self._out.put(("shutdown",))
        self._out.close()

    # -- receiving ------------------------------------------------------------------------

    def prepare(self) -> list[str]:
        """Make every target now, before the cycles run: making one (a device's endpoint, the
        HMI's view: imports, tables) can take milliseconds, which inside the first request's
        idle time would make a cycle late. Returns the problems (a target that failed)."""
        problems = []
        for name in list(self._factories):
            try:
                self._target(name)
            except Exception as exc:
                problems.append(f"{name}: {type(exc).__name__}: {exc}")
        return problems

    def _target(self, name: str) -> Any:
        obj = self._objects.get(name)
        if obj is None:
            factory = self._factories.get(name)
            if factory is None:
                raise LookupError(f"no endpoint {name!r} on this machine")
            obj = self._objects[name] = factory()
        return obj

    def pump(self, until: float, timer: Callable[[], float] = time.perf_counter) -> int:
        """Answer requests until ``until`` (timer seconds) or none is waiting. Returns how many
        were handled.

        At least one waiting request is answered even when the cycle has no idle time left, so
        clients are slowed down by a busy cycle but never starved. A request known to be long
        (the HMI's device page: up to a millisecond) waits for an idle time that holds it,
        judged by what the same kind of request took before, at most `HOLD_CYCLES` pumps; later
        requests wait behind it, so every client's requests keep their order."""
        self._out.flush()
        conn = self._conn
        handled = 0
        try:
            while True:
                message = self._held
                if message is None:
                    if not conn.poll(0):
                        break
                    message = conn.recv()
                key = _cost_key(message)
                seen = self._costs.get(key)
                # the least of the last few: preemption and page faults only ever add time,
                # so one slow answer does not make a short request "long"
                estimate = min(seen) if seen else 0.0
                t0 = timer()
                if estimate > _LONG_S and t0 + estimate > until and self._held_for < HOLD_CYCLES:
                    self._held = message
                    self._held_for += 1
                    break
                self._held = None
                self._held_for = 0
                self._handle(message)
                handled += 1
                t1 = timer()
                took = t1 - t0
                if seen is None:
                    seen = self._costs[key] = deque(maxlen=8)
                seen.append(took)
                if took > self.slowest[0]:
                    self.slowest = (took, " ".join(str(k) for k in key))
                if t1 >= until:
                    break
        except (EOFError, OSError):
            self._out.closed = True
        return handled

    def _handle(self, message: tuple) -> None:
        kind = message[0]
        if kind == "call":
            _, rid, target, method, args, who, endpoint = message
            self._call(rid, target, method, args, who, endpoint)
        elif kind == "session":
            _, rid, target, who, endpoint = message
            try:
                session = self._target(target).session()
            except Exception as exc:
                self.send(("reply", rid, False, _portable(exc)))
                return
            handle = f"s{next(self._handles)}"
            self._objects[handle] = session
            self.send(("reply", rid, True, handle))
        elif kind == "close":
            self._objects.pop(message[1], None)
        else:  # listening / started / failed: for serve's start-up
            self.endpoint_messages.append(message)

    def _call(self, rid: int, target: str, method: str, args: tuple, who: str, endpoint: str) -> None:
        audit = self.audit
        request = requests.Request(who, endpoint, audit.snapshot if audit is not None else None)
        before = None
        try:
            obj = self._target(target)
            fn = getattr(obj, method)
            if audit is not None and method == "write_registers":
                before = audit.registers_before(obj, *args)
            requests.current[0] = request
            try:
                value, ok = fn(*args), True
            finally:
                requests.current[0] = None
        except Exception as exc:
            value, ok = _portable(exc), False
        self.answered += 1
        self.send(("reply", rid, ok, value))
        if audit is not None:
            if method == "write_registers":
                audit.register_write(request, args, before, ok, value)
            elif request.write:
                audit.byte_write(request, args, ok, value)


# ---------------------------------------------------------------------------- endpoint side


class EndpointLink:
    """The endpoint process's end: sends requests, resolves their Futures, logs events."""

    def __init__(self, inbox: Any, outbox: Any, on_event: Callable[[str, str, dict[str, Any]], None]) -> None:
        self._conn = inbox
        self._outbox = outbox
        self._on_event = on_event
        self._ids = itertools.count(1)
        self._waiting: dict[int, Future[Any]] = {}
        self._lock = threading.Lock()
        self._send_lock = threading.Lock()
        self.shutdown = threading.Event()
        self._reader = threading.Thread(target=self._read_loop, name="link-read", daemon=True)

    def start(self) -> "EndpointLink":
        self._reader.start()
        return self

    def send(self, message: tuple) -> None:
        with self._send_lock:
            self._outbox.send(message)

    def _request(self, message_of: Callable[[int], tuple]) -> Future[Any]:
        future: Future[Any] = Future()
        future.set_running_or_notify_cancel()  # sent requests are not withdrawn (module docstring)
        rid = next(self._ids)
        with self._lock:
            if self.shutdown.is_set():
                future.set_exception(LinkClosed("the machine is not running"))
                return future
            self._waiting[rid] = future
        try:
            self.send(message_of(rid))
        except (OSError, EOFError, ValueError) as exc:
            with self._lock:
                self._waiting.pop(rid, None)
            future.set_exception(LinkClosed(f"the machine is not running ({exc})"))
        return future

    def call(self, target: str, method: str, args: tuple, who: str = "", endpoint: str = "") -> Future[Any]:
        return self._request(lambda rid: ("call", rid, target, method, tuple(args), who, endpoint))

    def open_session(self, target: str, who: str = "", endpoint: str = "") -> Future[Any]:
        return self._request(lambda rid: ("session", rid, target, who, endpoint))

    def _read_loop(self) -> None:
        try:
            while True:
                message = self._conn.recv()
                kind = message[0]
                if kind == "reply":
                    _, rid, ok, value = message
                    with self._lock:
                        future = self._waiting.pop(rid, None)
                    if future is not None:
                        (future.set_result if ok else future.set_exception)(value)
                elif kind == "event":
                    self._on_event(message[1], message[2], message[3])
                elif kind == "shutdown":
                    break
        except (EOFError, OSError):
            pass
        finally:
            with self._lock:
                self.shutdown.set()
                waiting, self._waiting = self._waiting, {}
            for future in waiting.values():
                future.set_exception(LinkClosed("the machine stopped before answering"))


class RemoteMethod:
    """`target.method` in the cycle process; what a protocol server submits."""

    __slots__ = ("target", "method", "__name__")

    def __init__(self, target: str, method: str) -> None:
        self.target = target
        self.method = method
        self.__name__ = method

    def __call__(self, *args: Any) -> Any:  # pragma: no cover - always submitted, never called here
        raise RuntimeError("a remote method runs in the cycle process: submit it to RemoteCommands")


class RemoteSession:
    """One connection's byte session, living in the cycle process."""

    def __init__(self, link: EndpointLink, handle: str) -> None:
        self._link = link
        self.handle = handle
        self.feed = RemoteMethod(handle, "feed")

    def close(self) -> None:
        try:
            self._link.send(("close", self.handle))
        except (OSError, EOFError, ValueError):
            pass


class RemoteEndpoint:
    """A device endpoint ("byte" or "register") as the protocol servers expect it."""

    def __init__(self, link: EndpointLink, target: str, endpoint: str) -> None:
        self._link = link
        self._target = target
        self._endpoint = endpoint
        self.read_registers = RemoteMethod(target, "read_registers")
        self.write_registers = RemoteMethod(target, "write_registers")

    def session(self) -> RemoteSession:
        handle = self._link.open_session(self._target, current_client(), self._endpoint).result()
        return RemoteSession(self._link, handle)


class RemoteCommands:
    """Stands in for the machine's CommandQueue in the endpoint process: `submit(method, *args)`
    sends the call to the cycle process; the Future resolves with its answer."""

    def __init__(self, link: EndpointLink, endpoint: str) -> None:
        self._link = link
        self._endpoint = endpoint

    def submit(self, fn: RemoteMethod, /, *args: Any) -> Future[Any]:
        if not isinstance(fn, RemoteMethod):
            raise TypeError(f"only remote methods cross to the cycle process, got {fn!r}")
        return self._link.call(fn.target, fn.method, args, current_client(), self._endpoint)
