"""A CLM on the simulated plant with its Profibus DP image served by the real Modbus TCP server
(in-process, port 0) while a thread runs the machine's cycles; for tests/devices/clm/test_profibus*.

`install` is the personality hook (`register_endpoint()` makes the `ClmProfibus`, the NC cycle
runs through `ClmProfibus.cycle`): it calls the personality's own once personality.py offers
"modbus", and installs the same from here until then.
"""

from __future__ import annotations

import socket
import struct
import threading
import time
from pathlib import Path

from .clmrig import roll_feed_text, with_parameters

from axisline.devices.clm.profibus import ClmProfibus
from axisline.fieldbus.modbus import ModbusServer
from axisline.machine import Machine

PROGRAM = "0000 NOP\n0001 JMP 0000\n"
PARAMS = (Path(__file__).resolve().parents[3] / "examples" / "clm" / "roll_feed.par")


def install(dev) -> ClmProfibus:
    """The personality hook: once personality.py has it (its `endpoints` offer "modbus"),
    `register_endpoint()` itself; until then the same done from here: the `ClmProfibus` made as
    `register_endpoint()` makes it, and the NC cycle run through `ClmProfibus.cycle`."""
    if "modbus" in type(dev).endpoints:
        return dev.register_endpoint()
    if getattr(dev, "profibus", None) is None:
        store = None if dev.store is None else (lambda: dev.store.save(dev.memory))
        dev.profibus = ClmProfibus(dev.rt, lambda: dev.network_writes, store=store)
        step = dev.rt.step
        dev.rt.step = lambda: dev.profibus.cycle(step)
    return dev.profibus


def machine_file(tmp_path: Path, b008: str = "0 1 0 1 05", params: dict[str, str] | None = None,
                 program: str = PROGRAM, inputs: str = "") -> Path:
    """The roll feed machine running `program`, with B008 (and `params`) set, no start_at."""
    prg = tmp_path / "pb.prg"
    prg.write_text(program)
    par = tmp_path / "pb.par"
    par.write_text(with_parameters(PARAMS.read_text(), {"B008": b008, **(params or {})}))
    text = roll_feed_text(prg, par).replace("start_at = 0.1 ", "# ")
    if inputs:
        text = text.replace('"I1.00.2" = true', '"I1.00.2" = true\n' + inputs)
    path = tmp_path / "pb.toml"
    path.write_text(text)
    return path


def machine(tmp_path: Path, b008: str = "0 1 0 1 05", params: dict[str, str] | None = None,
            program: str = PROGRAM, inputs: str = "") -> Machine:
    m = Machine.from_file(machine_file(tmp_path, b008, params, program, inputs))
    m.device.network_writes = True
    install(m.device)
    return m


class Served:
    """The machine and its Modbus server: a thread applies the server's requests at the
    present cycle boundary and runs NC cycles only when the test asks (`cycles`), so the
    simulated time, and with it the watchdog, is the same on every run."""

    def __init__(self, m: Machine) -> None:
        self.m = m
        self.lock = threading.Lock()
        self.stop = threading.Event()
        self.budget = 0
        self.server = ModbusServer(m.device.profibus, m.commands, "127.0.0.1", 0,
                                   writes_allowed=lambda: m.device.network_writes).start()
        self.thread = threading.Thread(target=self._run, daemon=True)
        self.thread.start()
        self.sock = socket.create_connection(self.server.address, timeout=10)
        self.tid = 0

    def _run(self) -> None:
        scheduler = self.m.scheduler
        while not self.stop.is_set():
            with self.lock:
                if self.budget > 0:
                    scheduler.run_cycle()
                    self.budget -= 1
                    continue
                self.m.commands.apply_pending(scheduler.clock.cycle)
            time.sleep(0.0002)

    def close(self) -> None:
        self.sock.close()
        self.stop.set()
        self.thread.join(5)
        self.server.stop()

    def cycles(self, n: int) -> None:
        """Run `n` NC cycles (requests wait at the boundaries between them)."""
        with self.lock:
            self.budget += n
        deadline = time.monotonic() + 10
        while True:
            with self.lock:
                if self.budget == 0:
                    return
            assert time.monotonic() < deadline, "the cycles did not run"
            time.sleep(0.0005)

    # -- raw Modbus TCP, byte for byte as a PLC sends it -----------------------------------------

    def request(self, pdu: bytes) -> bytes:
        self.tid = (self.tid + 1) & 0xFFFF
        self.sock.sendall(struct.pack(">HHHB", self.tid, 0, len(pdu) + 1, 1) + pdu)
        head = self._exactly(7)
        tid, _, length, _ = struct.unpack(">HHHB", head)
        assert tid == self.tid
        return self._exactly(length - 1)

    def _exactly(self, n: int) -> bytes:
        data = b""
        while len(data) < n:
            chunk = self.sock.recv(n - len(data))
            assert chunk, "the server closed the connection"
            data += chunk
        return data

    def write(self, address: int, words: list[int]) -> bytes:
        """FC16; returns the reply PDU."""
        return self.request(struct.pack(f">BHHB{len(words)}H", 16, address, len(words), 2 * len(words), *words))

    def read(self, address: int, count: int, fc: int = 4) -> list[int]:
        reply = self.request(struct.pack(">BHH", fc, address, count))
        assert reply[0] == fc, reply.hex(" ")
        return list(struct.unpack(f">{count}H", reply[2:]))

    def read_bytes(self, address: int, count: int, fc: int = 4) -> bytes:
        reply = self.request(struct.pack(">BHH", fc, address, count))
        assert reply[0] == fc, reply.hex(" ")
        return reply[2:]
