"""The web HMI served by uvicorn in a thread of its own (like fieldbus.modbus.ModbusServer).

    srv = HmiServer(call, events, "127.0.0.1", 0, writes_allowed=True).start()
    print(f"http {srv.address[0]}:{srv.address[1]}", f"token {srv.token}")
    ...
    srv.stop()

The socket is bound here, before uvicorn starts, so `start()` reports a port that cannot be
had as an OSError at once and port 0 gives the port the system chose. uvicorn logs at
warning level only (no access log): the event log is the HMI's record of what was done.
"""

from __future__ import annotations

import secrets
import socket
import threading
import time
from typing import Any

import uvicorn

from .app import Call, create_app

__all__ = ["HmiServer"]

START_TIMEOUT = 10.0  # s for uvicorn to come up


def local_host_names(host: str) -> list[str] | None:
    """The Host headers a server bound to a loopback address answers (None: any). A page on
    another site that rebinds its own name to 127.0.0.1 (DNS rebinding) sends its own name
    as Host and is refused, so it cannot read the machine through the operator's browser."""
    if host in ("127.0.0.1", "::1", "localhost") or host.startswith("127."):
        return sorted({"127.0.0.1", "localhost", "::1", "[::1]", host})
    return None


class HmiServer:
    """The HMI on HOST:PORT; with `writes_allowed` and no `token`, a random token is made
    (`.token`, to be printed at start)."""

    def __init__(
        self,
        call: Call,
        events: Any,
        host: str = "127.0.0.1",
        port: int = 0,
        *,
        writes_allowed: bool = False,
        token: str | None = None,
    ) -> None:
        if writes_allowed and not token:
            token = secrets.token_urlsafe(12)
        self.token = token
        self.host = host
        self.port = port
        self.writes_allowed = writes_allowed
        self.app = create_app(call, events, writes_allowed=writes_allowed, token=token, allowed_hosts=local_host_names(host))
        self._server: uvicorn.Server | None = None
        self._thread: threading.Thread | None = None
        self._sock: socket.socket | None = None
        self._error: BaseException | None = None

    @property
    def address(self) -> tuple[str, int]:
        return self.host, self.port

    def start(self) -> "HmiServer":
        try:
            family, kind, proto, _, addr = socket.getaddrinfo(self.host, self.port, type=socket.SOCK_STREAM)[0]
            sock = socket.socket(family, kind, proto)
            sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
            sock.bind(addr)
        except OSError as e:
            raise OSError(f"HMI cannot listen on {self.host}:{self.port}: {e.strerror or e}") from None
        self._sock = sock
        self.port = sock.getsockname()[1]
        config = uvicorn.Config(
            self.app,
            log_level="warning",
            access_log=False,
            lifespan="off",
            ws="websockets-sansio",
            server_header=False,
            timeout_graceful_shutdown=1,
        )
        self._server = server = uvicorn.Server(config)
        self._thread = threading.Thread(target=self._run, name="hmi", daemon=True)
        self._thread.start()
        deadline = time.monotonic() + START_TIMEOUT
        while not server.started and self._thread.is_alive() and time.monotonic() < deadline:
            time.sleep(0.01)
        if not server.started:
            self.stop()
            why = f": {self._error}" if self._error is not None else ""
            raise OSError(f"HMI on {self.host}:{self.port} did not start{why}")
        return self

    def _run(self) -> None:
        assert self._server is not None and self._sock is not None
        try:
            self._server.run(sockets=[self._sock])
        except BaseException as e:  # reported by start()
            self._error = e

    def stop(self) -> None:
        if self._server is not None:
            self._server.should_exit = True
        if self._thread is not None and self._thread.is_alive():
            self._thread.join(5.0)
        if self._sock is not None:
            self._sock.close()
