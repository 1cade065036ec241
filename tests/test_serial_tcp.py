"""The serial-over-TCP server: a session per connection, a bounded number of clients with a
clear refusal, a burst of connects accepted at once, clean stop, endpoint errors without a
traceback. Real sockets on loopback; the device is a small line protocol (the protocols of the
devices are tested over TCP with them: compax/test_ascii.py, fs701/test_serve.py); every wait
has a deadline."""

from __future__ import annotations

import selectors
import socket
import threading
import time

import pytest

from axisline.fieldbus.serial_tcp import REFUSAL, SerialTcpServer
from axisline.kernel.commands import CommandQueue


class Lines:
    """A line protocol: each session answers `ok <line>` per line; `boom` raises."""

    def __init__(self) -> None:
        self.sessions = 0

    def session(self) -> "LineSession":
        self.sessions += 1
        return LineSession()


class LineSession:
    def __init__(self) -> None:
        self.buffer = b""

    def feed(self, data: bytes) -> bytes:
        self.buffer += data
        out = b""
        while b"\n" in self.buffer:
            line, self.buffer = self.buffer.split(b"\n", 1)
            if line == b"boom":
                raise RuntimeError("endpoint bug")
            out += b"ok " + line + b"\n"
        return out


@pytest.fixture
def queue():
    """A command queue applied in a thread, as the machine's cycle does."""
    q = CommandQueue()
    stop = threading.Event()

    def cycle() -> None:
        n = 0
        while not stop.is_set():
            q.apply_pending(n)
            n += 1
            time.sleep(0.0005)

    th = threading.Thread(target=cycle, daemon=True)
    th.start()
    yield q
    stop.set()
    th.join(timeout=5)


def read_line(sock: socket.socket) -> bytes:
    got = b""
    while not got.endswith(b"\n"):
        chunk = sock.recv(256)
        if not chunk:
            break
        got += chunk
    return got


def ask(sock: socket.socket, line: bytes) -> bytes:
    sock.sendall(line + b"\n")
    return read_line(sock)


def test_an_endpoint_without_sessions_is_refused_at_construction():
    class Shared:
        def feed(self, data: bytes) -> bytes:
            return data

    with pytest.raises(TypeError, match="session"):
        SerialTcpServer(Shared(), CommandQueue())


def test_every_connection_gets_its_own_session(queue):
    ep = Lines()
    srv = SerialTcpServer(ep, queue).start()
    try:
        with socket.create_connection(srv.address, timeout=5) as a, socket.create_connection(srv.address, timeout=5) as b:
            a.sendall(b"hal")
            assert ask(b, b"x") == b"ok x\n"  # b's line is b's alone
            assert ask(a, b"f") == b"ok half\n"
    finally:
        srv.stop()
    assert ep.sessions == 2


def test_connections_beyond_the_limit_get_a_refusal_line_and_are_closed(queue):
    srv = SerialTcpServer(Lines(), queue, max_connections=2).start()
    try:
        first = socket.create_connection(srv.address, timeout=5)
        second = socket.create_connection(srv.address, timeout=5)
        assert ask(first, b"1") == b"ok 1\n" and ask(second, b"2") == b"ok 2\n"
        with socket.create_connection(srv.address, timeout=5) as third:
            third.sendall(b"3\n")  # a client that talks at once still reads why it is refused
            assert read_line(third) == REFUSAL % 2 == b"busy: 2 connections open, no more are taken; try again later\r\n"
            assert third.recv(100) == b""  # then closed
        assert ask(first, b"still") == b"ok still\n"  # the served clients are not disturbed
        first.close()
        deadline = time.time() + 5
        while srv.connections > 1 and time.time() < deadline:
            time.sleep(0.01)
        with socket.create_connection(srv.address, timeout=5) as again:  # a freed place is taken again
            assert ask(again, b"4") == b"ok 4\n"
        second.close()
    finally:
        srv.stop()


def test_a_burst_of_a_hundred_connects_completes_before_the_server_accepts_them(queue):
    # 100 clients connecting at the same moment: the kernel completes their connects while the
    # server's thread takes them one by one. With socketserver's listen backlog of 5 only 6
    # got through; the others retried their SYN after 1, 2, 4, 8 s (100 connects took 15 s).
    # The server is not started yet, so no accepting can hide a short backlog.
    srv = SerialTcpServer(Lines(), queue, max_connections=100)
    clients = []
    sel = selectors.DefaultSelector()
    try:
        for _ in range(100):
            c = socket.socket()
            c.setblocking(False)
            c.connect_ex(srv.address)
            clients.append(c)
            sel.register(c, selectors.EVENT_WRITE)
        connected = 0
        deadline = time.monotonic() + 5.0  # far above what the 100 handshakes take
        while connected < 100 and time.monotonic() < deadline:
            for key, _ in sel.select(timeout=0.1):
                assert key.fileobj.getsockopt(socket.SOL_SOCKET, socket.SO_ERROR) == 0
                sel.unregister(key.fileobj)
                connected += 1
        assert connected == 100
        srv.start()
        for i, c in enumerate(clients):  # and every one of them is served
            c.setblocking(True)
            c.settimeout(5)
            assert ask(c, b"%d" % i) == b"ok %d\n" % i
    finally:
        sel.close()
        for c in clients:
            c.close()
        srv.stop()


def test_stop_closes_the_open_connections(queue):
    srv = SerialTcpServer(Lines(), queue).start()
    with socket.create_connection(srv.address, timeout=5) as c:
        assert ask(c, b"a") == b"ok a\n"
        srv.stop()
        assert c.recv(100) == b""  # the client sees the end, it is not left hanging


def test_an_endpoint_error_closes_only_that_connection_with_one_line_on_stderr(queue, capfd):
    srv = SerialTcpServer(Lines(), queue).start()
    try:
        with socket.create_connection(srv.address, timeout=5) as bad, socket.create_connection(srv.address, timeout=5) as good:
            bad.sendall(b"boom\n")
            assert bad.recv(100) == b""
            assert ask(good, b"fine") == b"ok fine\n"
    finally:
        srv.stop()
    err = capfd.readouterr().err
    assert "Traceback" not in err
    assert [line for line in err.splitlines() if line] == [
        line for line in err.splitlines() if "connection closed after RuntimeError: endpoint bug" in line
    ] and err.count("endpoint bug") == 1
