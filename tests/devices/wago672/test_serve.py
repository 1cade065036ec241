"""`axisline serve examples/wago_stepper.toml --modbus 127.0.0.1:0` as a subprocess, driven by a PLC."""

from __future__ import annotations

import signal
import subprocess
import sys
import threading
from pathlib import Path

import pytest
from pymodbus.client import ModbusTcpClient

from axisline.devices.wago672.client import Wago672Client

EXAMPLE = Path(__file__).resolve().parents[3] / "examples" / "wago_stepper.toml"


def _serve(*extra: str) -> subprocess.Popen:
    return subprocess.Popen(
        [sys.executable, "-m", "axisline.cli", "serve", str(EXAMPLE), "--modbus", "127.0.0.1:0", *extra],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
    )


def _modbus_port(proc: subprocess.Popen, timeout: float = 20.0) -> int:
    """The port from the "modbus HOST:PORT" line (read with a deadline: never hang on a silent child)."""
    found: list[str] = []
    done = threading.Event()

    def read() -> None:
        for line in proc.stdout:
            if line.startswith("modbus "):
                found.append(line.split()[1])
                break
        done.set()

    threading.Thread(target=read, daemon=True).start()
    if not done.wait(timeout) or not found:
        proc.kill()
        _, err = proc.communicate(timeout=10)
        raise AssertionError(f"no 'modbus HOST:PORT' line from serve: {err}")
    host, _, port = found[0].rpartition(":")
    assert host == "127.0.0.1"
    return int(port)


def _stop(proc: subprocess.Popen) -> tuple[str, str]:
    proc.send_signal(signal.SIGTERM)
    try:
        return proc.communicate(timeout=20)
    finally:
        if proc.poll() is None:
            proc.kill()


def test_serve_runs_the_module_behind_the_modbus_server():
    proc = _serve("--allow-writes")
    try:
        port = _modbus_port(proc)
        with Wago672Client("127.0.0.1", port) as plc:
            plc.enable()
            st = plc.move_to(12800, velocity=25000, acceleration=4000)  # 5 mm
            assert st.on_target and st.position == 12800
            assert plc.status().position == 12800
        out, err = _stop(proc)
    finally:
        if proc.poll() is None:
            proc.kill()
    assert proc.returncode == 0, err
    assert "stopped" in out and "axes at rest" in err


def test_serve_refuses_writes_without_allow_writes():
    proc = _serve()
    try:
        port = _modbus_port(proc)
        c = ModbusTcpClient("127.0.0.1", port=port, timeout=3)
        assert c.connect()
        try:
            assert not c.read_input_registers(0, count=6).isError()
            w = c.write_registers(0, [0, 0, 0, 0, 0, 0x0300])
            assert w.isError() and w.exception_code == 1
        finally:
            c.close()
        out, err = _stop(proc)
    finally:
        if proc.poll() is None:
            proc.kill()
    assert proc.returncode == 0, err


@pytest.mark.parametrize("endpoint", ["--serial-tcp"])
def test_serve_offers_only_modbus(endpoint):
    res = subprocess.run(
        [sys.executable, "-m", "axisline.cli", "serve", str(EXAMPLE), endpoint, "127.0.0.1:0", "--duration", "0.1"],
        capture_output=True, text=True, timeout=30,
    )
    assert res.returncode == 2 and endpoint in res.stderr + res.stdout



def test_serve_says_on_the_console_when_the_watchdog_trips_and_does_not_run_the_script():
    import time

    proc = _serve("--allow-writes")
    try:
        port = _modbus_port(proc)
        c = ModbusTcpClient("127.0.0.1", port=port, timeout=3)
        assert c.connect()
        try:
            assert not c.write_registers(0, [0, 0, 0, 0, 0, 0x0300]).isError()  # Enable, Stop2_N: one write, as mbpoll
            time.sleep(0.6)  # then nothing: the 100 ms watchdog expires
            assert c.read_holding_registers(0x1006, count=1).registers == [2]
        finally:
            c.close()
        out, err = _stop(proc)
    finally:
        if proc.poll() is None:
            proc.kill()
    assert proc.returncode == 0, err
    said = " ".join(err.split())
    assert "wago672: the [[device.plc]] script (16 steps) is not run by serve: the Modbus client is the PLC" in said
    assert said.count("wago672: fieldbus watchdog expired") == 1
    assert "(watchdog_ms = 100); module 0 (axis x) brakes with the STOP ramp" in said
