"""The FS701's registers over the network: Drivecom over TCP, Modbus TCP, and `axisline serve`.

Against a running Machine (cycled in a thread, as serve does on the wall clock): requests reach
the register map at cycle boundaries through the machine's command queue. Loopback only;
every wait has a deadline.
"""

from __future__ import annotations

import copy
import os
import select
import signal
import socket
import subprocess
import sys
import threading
import time
import tomllib
from pathlib import Path

import pytest
from pymodbus.client import ModbusTcpClient
from serving import Fed

from axisline.config import parse_machine
from axisline.devices.fs701.drivecom import ACK, ETX, NAK, STX, build_read, build_write, parse_reply
from axisline.devices.fs701.modbus_map import encode_words
from axisline.fieldbus.modbus import ModbusServer
from axisline.fieldbus.serial_tcp import PtyBridge, SerialTcpServer
from axisline.machine import Machine

EXAMPLE = Path(__file__).resolve().parents[3] / "examples" / "flying_shear.toml"
CUTTING_LENGTH = 0x0000
SYNC_RATE = 0x0105


def machine() -> Machine:
    data = tomllib.loads(EXAMPLE.read_text())
    data = copy.deepcopy(data)
    data["device"]["commissioning"] = False
    data["axis"][0]["drive"].update(gain_factor=1.0, offset_volts=0.0)
    data["trace"] = {"enabled": False}
    return Machine(parse_machine(data, str(EXAMPLE)), source=str(EXAMPLE))


class Cycling:
    """Run the machine's cycles in a thread (about real time) while a test talks to it."""

    def __init__(self, m: Machine) -> None:
        self.m = m
        self.stop = threading.Event()
        self.thread = threading.Thread(target=self._run, daemon=True)

    def _run(self) -> None:
        while not self.stop.is_set():
            self.m.scheduler.run_cycle()
            time.sleep(0.0002)

    def __enter__(self) -> "Cycling":
        self.thread.start()
        return self

    def __exit__(self, *exc) -> None:
        self.stop.set()
        self.thread.join(timeout=5)


def recv_reply(sock: socket.socket) -> bytes:
    """One Drivecom reply: ACK, NAK or STX .. ETX BCC (the socket has a timeout)."""
    buf = b""
    while True:
        chunk = sock.recv(64)
        if not chunk:
            return buf
        buf += chunk
        if buf[:1] in (bytes([ACK]), bytes([NAK])):
            return buf
        if buf[:1] == bytes([STX]) and ETX in buf[:-1]:
            return buf


def test_drivecom_over_tcp_reads_writes_and_naks():
    m = machine()
    dev = m.device
    srv = SerialTcpServer(dev.byte_endpoint(), m.commands).start()
    try:
        with Cycling(m), socket.create_connection(srv.address, timeout=5) as s:
            s.sendall(build_read(11, CUTTING_LENGTH))
            r = parse_reply(recv_reply(s))
            assert (r.kind, r.code, r.value) == ("data", CUTTING_LENGTH, 1000)
            # a write without the operator's enable: NAK, unchanged
            s.sendall(build_write(11, SYNC_RATE, "1.50"))
            assert recv_reply(s) == bytes([NAK])
            assert dev.params.sync_rate == 0.0
            # serve --allow-writes
            dev.network_writes = True
            s.sendall(build_write(11, SYNC_RATE, "1.50"))
            assert recv_reply(s) == bytes([ACK])
            s.sendall(build_read(11, SYNC_RATE))
            assert parse_reply(recv_reply(s)).text == "150"
            # a bad BCC: NAK and nothing changes
            bad = bytearray(build_write(11, SYNC_RATE, "-2.00"))
            bad[-1] ^= 0x20
            s.sendall(bytes(bad))
            assert recv_reply(s) == bytes([NAK])
            # an out-of-range value and an unknown register: NAK
            s.sendall(build_write(11, SYNC_RATE, "1200"))
            assert recv_reply(s) == bytes([NAK])
            s.sendall(build_read(11, 0x0B06))
            assert recv_reply(s) == bytes([NAK])
            s.sendall(build_read(11, SYNC_RATE))
            assert parse_reply(recv_reply(s)).text == "150"
            deadline = time.time() + 5
            while dev.settings.sync_rate != 1.5 and time.time() < deadline:
                time.sleep(0.01)
    finally:
        srv.stop()
    assert dev.params.sync_rate == 1.5 and dev.settings.sync_rate == 1.5  # the cutter took it


def test_drivecom_telegram_left_unfinished_by_a_client_does_not_touch_the_next_clients():
    m = machine()
    dev = m.device
    dev.network_writes = True
    fed = Fed(m.commands)
    srv = SerialTcpServer(dev.byte_endpoint(), fed).start()
    try:
        with Cycling(m):
            with socket.create_connection(srv.address, timeout=5) as first:
                first.sendall(build_write(11, CUTTING_LENGTH, 700)[:-1])  # the write without its BCC
                fed.wait(1)
            with socket.create_connection(srv.address, timeout=5) as second:
                # its EOT is not the dead write's BCC: the read is answered, the write never made
                second.sendall(build_read(11, CUTTING_LENGTH))
                r = parse_reply(recv_reply(second))
                assert (r.kind, r.code, r.value) == ("data", CUTTING_LENGTH, 1000)
                second.sendall(build_write(11, CUTTING_LENGTH, 800))  # and its own write works
                assert recv_reply(second) == bytes([ACK])
    finally:
        srv.stop()
    assert dev.params.cutting_length == 800


def test_modbus_reads_and_writes_holding_registers():
    m = machine()
    dev = m.device
    srv = ModbusServer(dev.register_endpoint(), m.commands, "127.0.0.1", 0, writes_allowed=lambda: dev.network_writes).start()
    try:
        with Cycling(m):
            c = ModbusTcpClient("127.0.0.1", port=srv.address[1], timeout=3)
            assert c.connect()
            try:
                r = c.read_holding_registers(2 * CUTTING_LENGTH, count=2)
                assert not r.isError() and r.registers == encode_words(1000, 2)
                w = c.write_registers(2 * CUTTING_LENGTH, encode_words(900, 2))
                assert w.isError() and w.exception_code == 1  # writes not enabled
                dev.network_writes = True
                w = c.write_registers(2 * CUTTING_LENGTH, encode_words(900, 2))
                assert not w.isError()
                assert c.read_holding_registers(2 * CUTTING_LENGTH, count=2).registers == encode_words(900, 2)
                bad = c.write_registers(2 * CUTTING_LENGTH, encode_words(0, 2))  # below the range
                assert bad.isError() and bad.exception_code == 3  # illegal data value
                half = c.write_register(2 * CUTTING_LENGTH + 1, 5)  # half of a 32-bit entry
                assert half.isError()
                assert c.read_holding_registers(2 * CUTTING_LENGTH, count=2).registers == encode_words(900, 2)
                r = c.read_holding_registers(2 * 0x0802, count=2)  # #2 Line Speed, live
                assert not r.isError()
            finally:
                c.close()
            deadline = time.time() + 5
            while dev.settings.cutting_length != 900 and time.time() < deadline:
                time.sleep(0.01)
    finally:
        srv.stop()
    assert dev.settings.cutting_length == 900


def test_drivecom_on_a_pty():
    m = machine()
    bridge = PtyBridge(m.device.byte_endpoint(), m.commands).start()
    try:
        with Cycling(m):
            fd = os.open(bridge.path, os.O_RDWR | os.O_NOCTTY)
            try:
                os.write(fd, build_read(11, CUTTING_LENGTH))
                deadline = time.time() + 5
                got = b""
                while not (got[:1] == bytes([STX]) and ETX in got[:-1]) and time.time() < deadline:
                    r, _, _ = select.select([fd], [], [], 0.1)
                    if r:
                        got += os.read(fd, 64)
            finally:
                os.close(fd)
    finally:
        bridge.stop()
    assert parse_reply(got).value == 1000


def _serve(*extra: str) -> subprocess.Popen:
    return subprocess.Popen(
        [sys.executable, "-m", "axisline.cli", "serve", str(EXAMPLE), *extra],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
    )


def _endpoint(proc: subprocess.Popen, prefix: str, timeout: float = 20.0) -> tuple[str, int]:
    found: list[str] = []
    done = threading.Event()

    def read() -> None:
        for line in proc.stdout:
            if line.startswith(prefix + " "):
                found.append(line.split()[1])
                break
        done.set()

    threading.Thread(target=read, daemon=True).start()
    if not done.wait(timeout) or not found:
        proc.kill()
        _, err = proc.communicate(timeout=10)
        raise AssertionError(f"no '{prefix} HOST:PORT' line from serve: {err}")
    host, _, port = found[0].rpartition(":")
    return host, int(port)


def test_serve_answers_drivecom_over_tcp_and_stops_on_sigterm():
    proc = _serve("--serial-tcp", "127.0.0.1:0")
    try:
        host, port = _endpoint(proc, "serial-tcp")
        assert host == "127.0.0.1"
        with socket.create_connection((host, port), timeout=5) as s:
            s.sendall(build_read(11, CUTTING_LENGTH))
            r = parse_reply(recv_reply(s))
            assert r.value == 1000
            s.sendall(build_write(11, CUTTING_LENGTH, 900))  # no --allow-writes
            assert recv_reply(s) == bytes([NAK])
        proc.send_signal(signal.SIGTERM)
        out, err = proc.communicate(timeout=20)
    finally:
        if proc.poll() is None:
            proc.kill()
    assert proc.returncode == 0, err
    assert "stopped" in out


def test_the_serial_document_is_the_generated_one():
    from axisline.devices.fs701.report import serial_markdown

    doc = Path(__file__).resolve().parents[3] / "docs" / "fs701-serial.md"
    assert doc.read_text() == serial_markdown(), "regenerate: docs/fs701-serial.md from report.serial_markdown()"
