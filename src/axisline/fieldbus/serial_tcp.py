"""A device's serial protocol served over TCP or a pseudo-terminal.

Serial register access (FS701 Drivecom, the COMPAX ASCII interface, the CLM's protocol)
is a byte stream: bytes in, reply bytes out. The server hands every chunk it receives to
the device's endpoint through the machine's command queue, so the register access happens
at a cycle boundary, never in the middle of a cycle, exactly as a real unit answers its
serial port between scans. A pty lets ordinary serial tools (minicom, pyserial) talk to
the simulated unit as if it were on /dev/ttyS*.

Every connection feeds its own `endpoint.session()` (its receive buffer and parser state),
so what one client leaves half-sent cannot be glued onto the next client's bytes; the pty
is one session. At most `max_connections` clients are served at once: one more is told so
in a short line (`REFUSAL`) and closed. Endpoint errors close their connection with one
line on stderr, never a traceback.

Servers bind to 127.0.0.1 unless told otherwise.
"""

from __future__ import annotations

import os
import select
import socket
import socketserver
import sys
import threading
import tty
from concurrent.futures import TimeoutError as FutureTimeout
from typing import Any

from .clients import peer_name, set_client

REPLY_TIMEOUT = 5.0  # seconds a client waits for the cycle to take its request
MAX_CONNECTIONS = 16  # clients served at once (a serial unit has one host; HMIs and tools add a few)
# pending connects the kernel holds for accept(): socketserver's default of 5 drops the SYNs of
# a burst of clients, which then retry after 1, 2, 4, 8 s (100 connects took 15 s)
BACKLOG = 128
REFUSAL = b"busy: %d connections open, no more are taken; try again later\r\n"


def _note(where: str, exc: BaseException, outcome: str = "connection closed") -> None:
    # one line: a traceback per bad client would flood the operator's console
    print(f"{where}: {outcome} after {type(exc).__name__}: {exc}", file=sys.stderr, flush=True)


class _Handler(socketserver.BaseRequestHandler):
    def handle(self) -> None:
        server: "_Server" = self.server  # type: ignore[assignment]
        sock: socket.socket = self.request
        sock.settimeout(None)
        who = peer_name("serial-tcp", self.client_address)
        set_client(who)  # this thread's context: the requests it submits name their client
        events = server.events
        if events is not None:
            events.emit("connect", f"{who} connected", endpoint="serial-tcp", who=who)
        session = server.endpoint.session()  # this connection's own buffer and parser state
        try:
            self._serve(server, sock, session)
        finally:
            close = getattr(session, "close", None)  # a session in serve's cycle process
            if close is not None:
                close()
            if events is not None:
                events.emit("disconnect", f"{who} disconnected", endpoint="serial-tcp", who=who)

    @staticmethod
    def _serve(server: "_Server", sock: socket.socket, session: Any) -> None:
        while not server.closing:
            try:
                data = sock.recv(4096)
            except OSError:
                return
            if not data:
                return  # the session, with any half-sent request, goes with the connection
            try:
                reply = server.commands.submit(session.feed, data).result(REPLY_TIMEOUT)
            except FutureTimeout:
                return  # the machine stopped cycling: drop the connection
            if reply:
                try:
                    sock.sendall(reply)
                except OSError:
                    return


class _Server(socketserver.ThreadingTCPServer):
    daemon_threads = True
    allow_reuse_address = True
    request_queue_size = BACKLOG
    # stop() closes the open connections itself; joining their threads could wait for ever
    # on a client that never sends
    block_on_close = False

    def __init__(self, address: tuple[str, int], endpoint: Any, commands: Any, max_connections: int, events: Any = None) -> None:
        self.endpoint = endpoint
        self.events = events
        self.commands = commands
        self.max_connections = max_connections
        self.closing = False
        self._lock = threading.Lock()
        self._open: set[socket.socket] = set()
        super().__init__(address, _Handler)

    def process_request(self, request: Any, client_address: Any) -> None:
        with self._lock:
            taken = not self.closing and len(self._open) < self.max_connections
            if taken:
                self._open.add(request)
        if not taken:
            self._refuse(request)
            self.shutdown_request(request)
            return
        try:
            super().process_request(request, client_address)
        except BaseException:
            self._forget(request)
            raise

    def _refuse(self, sock: socket.socket) -> None:
        # in the accepting thread, so it must not block: a short line fits a new socket's
        # send buffer; what the client already sent is read away, else close() would answer
        # it with a reset that can destroy the line before the client reads it
        try:
            sock.setblocking(False)
            sock.send(REFUSAL % self.max_connections)
            sock.shutdown(socket.SHUT_WR)
            for _ in range(16):
                if not sock.recv(4096):
                    break
        except OSError:  # also BlockingIOError: nothing more to read
            pass

    def process_request_thread(self, request: Any, client_address: Any) -> None:
        try:
            super().process_request_thread(request, client_address)
        finally:
            self._forget(request)

    def _forget(self, request: Any) -> None:
        with self._lock:
            self._open.discard(request)

    def handle_error(self, request: Any, client_address: Any) -> None:
        _note(f"serial-tcp {client_address[0]}:{client_address[1]}", sys.exc_info()[1] or RuntimeError("?"))

    def close_connections(self) -> None:
        with self._lock:
            self.closing = True
            open_ = list(self._open)
        for sock in open_:
            try:
                sock.shutdown(socket.SHUT_RDWR)  # its handler's recv returns: the thread ends
            except OSError:
                pass


class SerialTcpServer:
    """Serve `endpoint.session().feed(bytes) -> bytes` on host:port (port 0: any free port),
    one session per connection, at most `max_connections` at once."""

    def __init__(self, endpoint: Any, commands: Any, host: str = "127.0.0.1", port: int = 0, *,
                 max_connections: int = MAX_CONNECTIONS, events: Any = None) -> None:
        if not callable(getattr(endpoint, "session", None)):
            raise TypeError(f"{type(endpoint).__name__} has no session(): a byte endpoint must give every "
                            "connection its own parser state (axisline.devices.base.ByteEndpoint)")
        if max_connections < 1:
            raise ValueError(f"max_connections = {max_connections}; allowed is >= 1")
        self._server = _Server((host, port), endpoint, commands, max_connections, events)
        self._thread = threading.Thread(target=self._server.serve_forever, name="serial-tcp", daemon=True)

    @property
    def address(self) -> tuple[str, int]:
        return self._server.server_address[:2]  # type: ignore[return-value]

    @property
    def connections(self) -> int:
        """Connections being served now."""
        with self._server._lock:
            return len(self._server._open)

    def start(self) -> "SerialTcpServer":
        self._thread.start()
        return self

    def stop(self) -> None:
        self._server.close_connections()
        if self._thread.is_alive():  # shutdown() would wait for ever on a loop that never ran
            self._server.shutdown()
        self._server.server_close()


class PtyBridge:
    """The same byte stream on a pseudo-terminal; `path` is the device name for serial tools.

    The pty is one line, so one session for as long as the bridge runs."""

    def __init__(self, endpoint: Any, commands: Any) -> None:
        self.endpoint = endpoint
        self.commands = commands
        self._session = endpoint.session()
        self._master, self._slave = os.openpty()
        tty.setraw(self._slave)  # no echo, no line editing: a plain 8-bit serial line
        self.path = os.ttyname(self._slave)
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, name="serial-pty", daemon=True)

    def start(self) -> "PtyBridge":
        self._thread.start()
        return self

    def _run(self) -> None:
        while not self._stop.is_set():
            ready, _, _ = select.select([self._master], [], [], 0.1)
            if not ready:
                continue
            try:
                data = os.read(self._master, 4096)
            except OSError:
                return
            try:
                reply = self.commands.submit(self._session.feed, data).result(REPLY_TIMEOUT)
            except FutureTimeout:
                continue
            except Exception as exc:  # an endpoint error: the line stays, its parser starts afresh
                _note(f"serial-pty {self.path}", exc, "session restarted")
                self._session = self.endpoint.session()
                continue
            if reply:
                try:
                    os.write(self._master, reply)
                except OSError:
                    return

    def stop(self) -> None:
        self._stop.set()
        self._thread.join(timeout=1.0)
        os.close(self._master)
        os.close(self._slave)
