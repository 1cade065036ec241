"""A device's serial protocol served over TCP or a pseudo-terminal.

Serial register access (FS701 Drivecom, the COMPAX ASCII interface, the CLM's protocol)
is a byte stream: bytes in, reply bytes out. The server hands every chunk it receives to
the device's endpoint through the machine's command queue, so the register access happens
at a cycle boundary, never in the middle of a cycle, exactly as a real unit answers its
serial port between scans. A pty lets ordinary serial tools (minicom, pyserial) talk to
the simulated unit as if it were on /dev/ttyS*.

Servers bind to 127.0.0.1 unless told otherwise.
"""

from __future__ import annotations

import os
import socket
import socketserver
import threading
import tty
from concurrent.futures import TimeoutError as FutureTimeout
from typing import Any

REPLY_TIMEOUT = 5.0  # seconds a client waits for the cycle to take its request


class _Handler(socketserver.BaseRequestHandler):
    def handle(self) -> None:
        server: "_Server" = self.server  # type: ignore[assignment]
        sock: socket.socket = self.request
        sock.settimeout(None)
        while not server.closing:
            try:
                data = sock.recv(4096)
            except OSError:
                return
            if not data:
                return
            try:
                reply = server.commands.submit(server.endpoint.feed, data).result(REPLY_TIMEOUT)
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

    def __init__(self, address: tuple[str, int], endpoint: Any, commands: Any) -> None:
        self.endpoint = endpoint
        self.commands = commands
        self.closing = False
        super().__init__(address, _Handler)


class SerialTcpServer:
    """Serve `endpoint.feed(bytes) -> bytes` on host:port (port 0: any free port)."""

    def __init__(self, endpoint: Any, commands: Any, host: str = "127.0.0.1", port: int = 0) -> None:
        self._server = _Server((host, port), endpoint, commands)
        self._thread = threading.Thread(target=self._server.serve_forever, name="serial-tcp", daemon=True)

    @property
    def address(self) -> tuple[str, int]:
        return self._server.server_address[:2]  # type: ignore[return-value]

    def start(self) -> "SerialTcpServer":
        self._thread.start()
        return self

    def stop(self) -> None:
        self._server.closing = True
        self._server.shutdown()
        self._server.server_close()


class PtyBridge:
    """The same byte stream on a pseudo-terminal; `path` is the device name for serial tools."""

    def __init__(self, endpoint: Any, commands: Any) -> None:
        self.endpoint = endpoint
        self.commands = commands
        self._master, self._slave = os.openpty()
        tty.setraw(self._slave)  # no echo, no line editing: a plain 8-bit serial line
        self.path = os.ttyname(self._slave)
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, name="serial-pty", daemon=True)

    def start(self) -> "PtyBridge":
        self._thread.start()
        return self

    def _run(self) -> None:
        import select

        while not self._stop.is_set():
            ready, _, _ = select.select([self._master], [], [], 0.1)
            if not ready:
                continue
            try:
                data = os.read(self._master, 4096)
            except OSError:
                return
            try:
                reply = self.commands.submit(self.endpoint.feed, data).result(REPLY_TIMEOUT)
            except FutureTimeout:
                continue
            if reply:
                os.write(self._master, reply)

    def stop(self) -> None:
        self._stop.set()
        self._thread.join(timeout=1.0)
        os.close(self._master)
        os.close(self._slave)
