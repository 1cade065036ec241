"""Personalities plug into the Machine: registry, [device] table, logic rate, byte endpoints over TCP/pty."""

import os
import socket
import threading
import time

import pytest
from pydantic import BaseModel, ConfigDict, Field

from axisline.config import parse_machine
from axisline.configerrors import ConfigError
from axisline.devices import base
from axisline.fieldbus.serial_tcp import PtyBridge, SerialTcpServer
from axisline.machine import Machine


class EchoConfig(BaseModel):
    model_config = ConfigDict(extra="forbid")
    prefix: str = Field("> ", max_length=8)
    gain: float = Field(1.0, gt=0.0, le=10.0)


class Echo(base.Personality):
    """A test device: counts its logic ticks and answers its byte stream in upper case."""

    name = "echo"
    Config = EchoConfig
    endpoints = ("serial-tcp",)

    def __init__(self, machine, config):
        super().__init__(machine, config)
        self.ticks = []

    def tick(self, cycle):
        self.ticks.append(cycle)

    def byte_endpoint(self):
        dev = self

        class Endpoint:
            def feed(self, data: bytes) -> bytes:
                # the cycle the request was answered in: proves it ran at a cycle boundary
                return dev.config.prefix.encode() + data.upper() + f"@{dev.machine.clock.cycle}".encode()

            def session(self):
                return self  # no parser state to keep apart

        return Endpoint()

    def summary(self):
        return {"ticks": len(self.ticks)}


base.register("echo", f"{__name__}:Echo")


def machine(**device):
    data = {"machine": {"personality": "echo", "logic_every": 4}, "device": device, "trace": {"enabled": False}}
    return Machine(parse_machine(data, "t.toml"))


def test_device_table_is_validated_by_the_personality():
    with pytest.raises(ConfigError) as e:
        machine(gain=50.0)
    assert any(p.startswith("device.gain = 50.0") and "<= 10.0" in p for p in e.value.problems)
    with pytest.raises(ConfigError) as e:
        machine(colour="red")
    assert any(p.startswith("device.colour: unknown key") for p in e.value.problems)


def test_unknown_personality_and_orphan_device_table_are_named():
    with pytest.raises(ConfigError, match="unknown personality 'clm9'"):
        parse_machine({"machine": {"personality": "clm9"}}, "t.toml")
    with pytest.raises(ConfigError, match="needs machine.personality"):
        parse_machine({"device": {"x": 1}}, "t.toml")


def test_device_logic_runs_at_the_logic_rate_and_reports():
    m = machine()
    m.scheduler.run(12)
    assert m.device.ticks == [0, 4, 8]
    assert m.summary(m.run(0.004))["device"] == {"ticks": 4}
    assert m.device.network_writes is False  # writes from the network need the operator's enable


def _cycling(m, stop):
    while not stop.is_set():
        m.scheduler.run_cycle()
        time.sleep(0.0002)


def test_byte_endpoint_over_tcp_answers_at_a_cycle_boundary():
    m = machine(prefix="# ")
    srv = SerialTcpServer(m.device.byte_endpoint(), m.commands).start()
    stop = threading.Event()
    th = threading.Thread(target=_cycling, args=(m, stop))
    th.start()
    try:
        host, port = srv.address
        assert host == "127.0.0.1"
        with socket.create_connection((host, port), timeout=5) as c:
            c.sendall(b"hello")
            reply = c.recv(100)
    finally:
        stop.set()
        th.join()
        srv.stop()
    assert reply.startswith(b"# HELLO@")
    assert int(reply.split(b"@")[1]) >= 0


def test_byte_endpoint_on_a_pty():
    m = machine()
    bridge = PtyBridge(m.device.byte_endpoint(), m.commands).start()
    stop = threading.Event()
    th = threading.Thread(target=_cycling, args=(m, stop))
    th.start()
    try:
        fd = os.open(bridge.path, os.O_RDWR | os.O_NOCTTY)
        os.write(fd, b"abc")
        deadline = time.time() + 5
        got = b""
        while b"@" not in got and time.time() < deadline:
            got += os.read(fd, 100)
        os.close(fd)
    finally:
        stop.set()
        th.join()
        bridge.stop()
    assert got.startswith(b"> ABC@")
