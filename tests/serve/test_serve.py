"""`axisline serve` as an operator runs it: the cycle and the endpoints in two processes, the
event log, the realtime measures and their messages, the trace and report when stopped."""

from __future__ import annotations

import json
import signal
import subprocess
import sys
import time
from pathlib import Path

import psutil
from pymodbus.client import ModbusTcpClient

from axisline.devices.fs701.modbus_map import encode_words

import serving

ROOT = Path(__file__).resolve().parents[2]
FS701 = ROOT / "examples" / "flying_shear.toml"
FAULTY = ROOT / "tests" / "hmi" / "fault_machine.toml"
CUTTING_LENGTH = 0x0000


def start(*args: str) -> tuple[subprocess.Popen, dict[str, str]]:
    return serving.serve(*args, cwd=ROOT)


def stop(proc: subprocess.Popen) -> tuple[str, str]:
    proc.send_signal(signal.SIGINT)
    out, err = proc.communicate(timeout=60)
    assert proc.returncode == 0, err
    return out, err


def events(path: Path) -> list[dict]:
    return [json.loads(line) for line in path.read_text(encoding="utf-8").splitlines()]


def with_realtime(tmp_path: Path, base: Path, table: str) -> Path:
    text = base.read_text(encoding="utf-8")
    path = tmp_path / base.name
    path.write_text(text + "\n[realtime]\n" + table + "\n", encoding="utf-8")
    return path


def test_the_endpoints_run_in_a_process_of_their_own(tmp_path):
    proc, eps = start(str(FS701), "--modbus", "127.0.0.1:0")
    try:
        port = int(eps["modbus"].rsplit(":", 1)[1])
        children = psutil.Process(proc.pid).children()
        assert len(children) == 1
        listening = {c.laddr.port for c in children[0].net_connections(kind="tcp") if c.status == psutil.CONN_LISTEN}
        assert port in listening  # the server is the child's, not the cycle process's
        own = {c.laddr.port for c in psutil.Process(proc.pid).net_connections(kind="tcp") if c.status == psutil.CONN_LISTEN}
        assert port not in own
    finally:
        out, err = stop(proc)
    assert "stopped" in out and "lateness p50" in err


def test_the_event_log_names_who_wrote_what_old_to_new_and_the_refusals(tmp_path):
    log = tmp_path / "events.jsonl"
    proc, eps = start(str(FS701), "--modbus", "127.0.0.1:0", "--allow-writes", "--log", str(log))
    try:
        port = int(eps["modbus"].rsplit(":", 1)[1])
        c = ModbusTcpClient("127.0.0.1", port=port, timeout=5)
        assert c.connect()
        try:
            assert not c.write_registers(2 * CUTTING_LENGTH, encode_words(900, 2)).isError()
            bad = c.write_registers(2 * CUTTING_LENGTH, encode_words(0, 2))  # below the range
            assert bad.isError() and bad.exception_code == 3
            assert c.read_holding_registers(2 * CUTTING_LENGTH, count=2).registers == encode_words(900, 2)
        finally:
            c.close()
        time.sleep(0.3)
    finally:
        out, err = stop(proc)
    log_events = events(log)
    kinds = [e["kind"] for e in log_events]
    assert kinds[0] == "start" and kinds[-1] == "stop"
    assert "connect" in kinds and "disconnect" in kinds
    writes = [e for e in log_events if e["kind"] == "write"]
    assert len(writes) == 2
    ok, refused = writes
    assert ok["accepted"] is True and ok["who"].startswith("modbus 127.0.0.1:")
    assert [(c["old"], c["new"]) for c in ok["changes"]] == list(zip(encode_words(1000, 2), encode_words(900, 2)))
    assert refused["accepted"] is False and refused["reason"]
    assert log_events[-1]["lateness"]["cycles"] > 0
    assert "write" in err  # the console shows the same events


def test_a_write_without_the_operators_enable_is_logged_as_refused(tmp_path):
    log = tmp_path / "events.jsonl"
    proc, eps = start(str(FS701), "--modbus", "127.0.0.1:0", "--log", str(log))
    try:
        c = ModbusTcpClient("127.0.0.1", port=int(eps["modbus"].rsplit(":", 1)[1]), timeout=5)
        assert c.connect()
        assert c.write_registers(0, encode_words(900, 2)).exception_code == 1
        c.close()
        time.sleep(0.2)
    finally:
        stop(proc)
    (write,) = [e for e in events(log) if e["kind"] == "write"]
    assert write["accepted"] is False and "--allow-writes" in write["reason"]


def test_a_fault_appears_in_the_event_log(tmp_path):
    log = tmp_path / "events.jsonl"
    proc, _ = start(str(FAULTY), "--log", str(log))
    try:
        deadline = time.monotonic() + 10
        while not any(e["kind"] == "fault" for e in events(log)):
            assert time.monotonic() < deadline, events(log)
            time.sleep(0.1)
    finally:
        stop(proc)
    fault = next(e for e in events(log) if e["kind"] == "fault")
    assert fault["source"] == "axis x" and "error" in fault["text"]


def test_trace_and_report_are_written_when_stopped(tmp_path):
    trace, report = tmp_path / "ring.npz", tmp_path / "report"
    proc, _ = start(str(FS701), "--trace", str(trace), "--report", str(report))
    time.sleep(1.0)
    out, err = stop(proc)
    import numpy as np

    with np.load(trace) as data:
        assert len(data["t"]) > 100 and (np.diff(data["t"]) > 0).all()
    assert trace.with_suffix(".csv").is_file()
    assert (report / "report.md").is_file() and (report / "summary.json").is_file()


def test_overruns_are_counted_and_can_stop_the_axes(tmp_path):
    machine = with_realtime(tmp_path, FAULTY, 'overrun_us = 1\non_overrun = "stop"')
    log = tmp_path / "events.jsonl"
    proc, _ = start(str(machine), "--log", str(log))
    try:
        deadline = time.monotonic() + 10
        while not any(e["kind"] == "overrun" for e in events(log)):
            assert time.monotonic() < deadline
            time.sleep(0.1)
    finally:
        out, err = stop(proc)
    log_events = events(log)
    overrun = next(e for e in log_events if e["kind"] == "overrun")
    assert overrun["count"] >= 1 and overrun["worst_ms"] > 0.001
    assert any(e["kind"] == "stop" and e.get("reason") == "overrun" for e in log_events)
    assert log_events[-1]["overruns"] >= overrun["total"]


def test_the_realtime_measures_say_what_was_applied_and_what_was_refused(tmp_path):
    machine = with_realtime(tmp_path, FAULTY, 'gc = "idle"\nbusy_wait_us = 50\nfifo_priority = 10\ncpus = [0]')
    proc, _ = start(str(machine))
    time.sleep(0.5)
    out, err = stop(proc)
    assert "garbage collected in idle time only" in err
    assert "busy-wait 50 us before each deadline" in err
    assert "SCHED_FIFO priority 10" in err  # applied, or "not permitted here (...)" with the reason
    assert "CPU 0" in err or "realtime.cpus = [0] not applied" in err


def test_a_busy_wait_longer_than_the_cycle_is_a_bad_machine_file(tmp_path):
    machine = with_realtime(tmp_path, FAULTY, "busy_wait_us = 5000")
    res = subprocess.run([sys.executable, "-m", "axisline.cli", "serve", str(machine), "--duration", "0.1"],
                         capture_output=True, text=True, timeout=60, cwd=ROOT)
    assert res.returncode == 2
    assert "busy_wait_us = 5000" in res.stderr and "0..1000" in res.stderr


def test_the_endpoint_process_ends_when_the_cycle_process_is_killed():
    proc, _ = start(str(FS701), "--modbus", "127.0.0.1:0")
    (child,) = psutil.Process(proc.pid).children()
    proc.kill()  # kill -9: no shutdown message
    proc.wait(10)
    child.wait(10)  # it read end-of-file on the link and ended
    assert not child.is_running() or child.status() == psutil.STATUS_ZOMBIE


def test_a_device_watchdog_trip_is_a_watchdog_event(tmp_path):
    log = tmp_path / "events.jsonl"
    proc, eps = start(str(ROOT / "examples" / "wago_stepper.toml"), "--modbus", "127.0.0.1:0", "--allow-writes", "--log", str(log))
    try:
        c = ModbusTcpClient("127.0.0.1", port=int(eps["modbus"].rsplit(":", 1)[1]), timeout=5)
        assert c.connect()
        assert not c.write_registers(0, [0, 0, 0, 0, 0, 0x0300]).isError()  # one write, then silence
        deadline = time.monotonic() + 10
        while not any(e["kind"] == "watchdog" for e in events(log)):
            assert time.monotonic() < deadline, events(log)
            time.sleep(0.1)
        c.close()
    finally:
        stop(proc)
    trip = next(e for e in events(log) if e["kind"] == "watchdog")
    assert "fieldbus watchdog expired (1 time" in trip["text"]
    write = next(e for e in events(log) if e["kind"] == "write")
    assert write["accepted"] is True and write["what"] == "registers 0..5"


def test_a_serial_protocol_write_is_logged_with_the_parameter_old_and_new(tmp_path):
    import socket

    from axisline.devices.fs701.drivecom import ACK, NAK, build_write

    log = tmp_path / "events.jsonl"
    proc, eps = start(str(FS701), "--serial-tcp", "127.0.0.1:0", "--allow-writes", "--log", str(log))
    try:
        host, port = eps["serial-tcp"].rsplit(":", 1)
        with socket.create_connection((host, int(port)), timeout=5) as s:
            s.sendall(build_write(11, CUTTING_LENGTH, 900))
            assert s.recv(64) == bytes([ACK])
            s.sendall(build_write(11, CUTTING_LENGTH, 0))  # below the range: the device's NAK
            assert s.recv(64) == bytes([NAK])
        time.sleep(0.3)
    finally:
        stop(proc)
    ok, refused = [e for e in events(log) if e["kind"] == "write"]
    assert ok["accepted"] is True and ok["who"].startswith("serial-tcp 127.0.0.1:")
    assert {"what": "cutting_length", "old": 1000, "new": 900} in ok["changes"]
    assert refused["accepted"] is False and "no stored value changed" in refused["reason"]


def test_only_the_endpoints_asked_for_are_made(tmp_path):
    """Making an endpoint can be an act of the device: the CLM's Profibus image checks B008 and
    faults 34 without a DP slave address. Without --modbus it is not made, and no fault comes."""
    log = tmp_path / "events.jsonl"
    proc, _ = start(str(ROOT / "examples" / "roll_feed_clm.toml"), "--serial-tcp", "127.0.0.1:0", "--http", "127.0.0.1:0",
                    "--log", str(log))
    time.sleep(0.5)
    stop(proc)
    assert not [e for e in events(log) if e["kind"] == "fault" and "error 34" in e["message"]]
