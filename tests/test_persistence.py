"""Shutdown and persistence (issue 15): what a device acknowledges survives a kill -9, a
second signal does not cut the stop ramps short, interrupted saves leave no litter, and a
store that cannot be written is refused by the check and answered by the protocol."""

from __future__ import annotations

import os
import signal
import socket
import time
import tomllib
from pathlib import Path

import pytest
from serving import serve
from typer.testing import CliRunner

from axisline.cli import app
from axisline.config import parse_machine
from axisline.configerrors import ConfigError
from axisline.devices.compax.cammemory import CamMemory
from axisline.devices.compax.personality import load_parameters
from axisline.devices.fs701.drivecom import DrivecomClient, DrivecomError
from axisline.devices.fs701.paramfile import load_parameter_file
from axisline.fieldbus.modbus import RegisterRefused
from axisline.machine import Machine

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
runner = CliRunner()
STORE_TO_EEPROM = 0x091D  # FS701 serial command bit 29


def _compax_machine(tmp_path: Path) -> Path:
    """The COMPAX example keeping its cam memory and parameters beside the machine file."""
    text = (EXAMPLES / "cam_packaging.toml").read_text()
    text = text.replace('# memory_file = "cam_packaging.cam.json"', 'memory_file = "knife.cam.json"\nparameter_file = "knife.params.json"')
    text = text.replace('csv = "curves/', f'csv = "{EXAMPLES.as_posix()}/curves/')
    path = tmp_path / "knife.toml"
    path.write_text(text)
    return path


def _connect(where: str) -> socket.socket:
    host, _, port = where.rpartition(":")
    return socket.create_connection((host, int(port)), timeout=10)


def _ask(sock: socket.socket, line: str) -> bytes:
    sock.sendall(line.encode("ascii") + b"\r")
    reply = b""
    while not reply.endswith(b"\r\n>"):
        chunk = sock.recv(256)
        assert chunk, f"connection dropped after {line!r}"
        reply += chunk
    return reply


# ------------------------------------------------------------------------ acknowledged = stored


def test_every_acknowledged_compax_write_survives_a_kill_9_right_after_the_reply(tmp_path):
    machine = _compax_machine(tmp_path)
    words: dict[int, float] = {}  # F address -> value, every write acknowledged so far
    p179 = None
    for kill in range(12):
        proc, endpoints = serve(str(machine), "--serial-tcp", "127.0.0.1:0", "--allow-writes")
        try:
            with _connect(endpoints["serial-tcp"]) as sock:
                # set points in the free middle of the memory (the curves stay as they are)
                for k in range(3):
                    address, value = 3000 + 2 * (3 * kill + k), round(0.01 * (3 * kill + k + 1), 2)
                    assert _ask(sock, f"F{address}={value}") == b"\r\n>"
                    words[address] = value
                p179 = 1000 + kill
                assert _ask(sock, f"P179={p179}") == b"\r\n>"
                proc.kill()  # SIGKILL at once: no shutdown save, no flush
        finally:
            proc.kill()
            proc.wait(timeout=10)
        # what a restart loads (the device's power-on)
        memory = CamMemory.load(tmp_path / "knife.cam.json")
        for address, value in words.items():
            assert memory.read("F", address) == pytest.approx(value, abs=2**-23), (kill, address)
        assert load_parameters(tmp_path / "knife.params.json").written[179] == p179
    assert not [p.name for p in tmp_path.iterdir() if p.name.endswith(".tmp")]


def test_serve_removes_the_temporary_files_of_interrupted_saves(tmp_path):
    machine = _compax_machine(tmp_path)
    stale = [tmp_path / ".knife.cam.json.k3xq9z1a.tmp", tmp_path / ".knife.params.json.0bq7wm2e.tmp"]
    for p in stale:
        p.write_text('{"half": ')
    others = [tmp_path / ".other.json.k3xq9z1a.tmp", tmp_path / "knife.cam.json.tmp"]  # not a save of a store
    for p in others:
        p.write_text("keep")
    proc, _ = serve(str(machine), "--duration", "0.1")
    out, err = proc.communicate(timeout=60)
    assert proc.returncode == 0, err
    assert not any(p.exists() for p in stale)
    assert all(p.exists() for p in others)
    assert "removed" in err and ".knife.cam.json.k3xq9z1a.tmp" in err.replace("\n", "")


def test_a_shutdown_save_that_fails_is_reported_without_a_traceback(tmp_path):
    machine = _compax_machine(tmp_path)
    proc, _ = serve(str(machine))
    try:
        (tmp_path / "knife.cam.json").mkdir()  # taken after the check passed
        proc.send_signal(signal.SIGTERM)
        out, err = proc.communicate(timeout=60)
    finally:
        if proc.poll() is None:
            proc.kill()
    assert proc.returncode == 1
    assert "cannot save" in err and "Traceback" not in err and "stopped" in out


# ------------------------------------------------------------------------ a second signal

RAMP = """
[machine]
cycle_us = 1000
[[axis]]
name = "x"
unit = "mm"
counts_per_unit = 1000.0
v_max = 100.0
a_max = 1000.0
d_max = 40.0
error_deceleration = 40.0
following_error_limit = 5.0
[axis.drive]
type = "servo"
[[job.steps]]
axis = "x"
command = "power"
on = true
[[job.steps]]
axis = "x"
command = "move_velocity"
velocity = 100.0
wait = "none"
"""


def test_a_second_sigterm_during_the_stop_ramps_does_not_cut_them_short(tmp_path):
    machine = tmp_path / "ramp.toml"
    machine.write_text(RAMP)
    proc, _ = serve(str(machine))
    try:
        time.sleep(0.6)  # at 100 mm/s by now: the stop ramp takes 2.5 s
        proc.send_signal(signal.SIGTERM)
        time.sleep(0.5)
        proc.send_signal(signal.SIGTERM)  # impatient: the ramp is still running
        proc.send_signal(signal.SIGINT)
        out, err = proc.communicate(timeout=60)
    finally:
        if proc.poll() is None:
            proc.kill()
    assert proc.returncode == 0, err
    assert "axes at rest" in err and "stopped" in out
    assert "already stopping" in err and "kill -9" in err


# ------------------------------------------------------------------------ unwritable save paths


def test_check_refuses_a_save_path_that_cannot_be_written(tmp_path):
    machine = _compax_machine(tmp_path)
    machine.write_text(machine.read_text().replace('"knife.params.json"', '"plain/knife.params.json"'))
    (tmp_path / "knife.cam.json").mkdir()  # a directory where the cam memory goes
    (tmp_path / "plain").write_text("a file where the parameter file's folder goes")
    res = runner.invoke(app, ["check", str(machine)])
    said = " ".join(res.output.split())  # the console wraps long lines
    assert res.exit_code == 2
    assert "device.memory_file = 'knife.cam.json':" in said and "is a directory" in said
    assert "device.parameter_file = 'plain/knife.params.json':" in said and "plain is not a directory" in said

    fs701 = tomllib.loads((EXAMPLES / "flying_shear.toml").read_text())
    fs701["device"]["parameter_file"] = str(EXAMPLES / fs701["device"]["parameter_file"])
    wago = tomllib.loads((EXAMPLES / "wago_stepper.toml").read_text())
    for data, table, key, value, why in ((fs701, fs701["device"], "save_parameters", "plain/eeprom.toml", "is not a directory"),
                                         (fs701, fs701["device"], "save_parameters", str(tmp_path), "is a directory"),
                                         (wago, wago["device"]["modules"][0], "eeprom", str(tmp_path), "is a directory")):
        table[key] = value
        with pytest.raises(ConfigError) as e:
            Machine(parse_machine(data, str(tmp_path / "s.toml")), source=str(tmp_path / "s.toml"))
        del table[key]
        assert any(f"{key} = {value!r}: " in p and why in p for p in e.value.problems), e.value.problems


@pytest.mark.skipif(os.geteuid() == 0, reason="root writes into read-only directories")
def test_check_refuses_a_read_only_save_directory(tmp_path):
    machine = _compax_machine(tmp_path)
    text = machine.read_text().replace('memory_file = "knife.cam.json"', 'memory_file = "ro/knife.cam.json"')
    machine.write_text(text)
    (tmp_path / "ro").mkdir()
    (tmp_path / "ro").chmod(0o555)
    try:
        res = runner.invoke(app, ["check", str(machine)])
    finally:
        (tmp_path / "ro").chmod(0o755)
    said = " ".join(res.output.split())
    assert res.exit_code == 2 and "device.memory_file = 'ro/knife.cam.json'" in said and "not writable" in said


# ------------------------------------------------------------------------ a store failing at run time


def test_a_compax_store_failing_at_run_time_is_answered_e108_and_changes_nothing(tmp_path):
    m = Machine.from_file(_compax_machine(tmp_path))
    dev = m.device
    dev.network_writes = True
    ep = dev.byte_endpoint()
    assert ep.feed(b"F3000=0.25\r") == b"\r\n>"
    # the store's place is taken by a directory (a full or broken disk looks the same to us)
    (tmp_path / "knife.cam.json").unlink()
    (tmp_path / "knife.cam.json").mkdir()
    (tmp_path / "knife.params.json").unlink(missing_ok=True)
    (tmp_path / "knife.params.json").mkdir()
    for line, unchanged in ((b"F3000=0.5\r", lambda: dev.memory.read("F", 3000) == 0.25),
                            (b"P179=77\r", lambda: dev.params.written[179] == 0)):
        reply = ep.feed(line)
        assert reply.startswith(b"!E108 ") and b"not stored" in reply and reply.endswith(b"\r\n>"), reply
        assert unchanged(), line
        assert ep.feed(b"S30\r") == b"S030=108.000\r\n>"
    assert ep.feed(b"F3000\r").startswith(b"F3000=0.25")
    # the store is back: the next write is kept again
    (tmp_path / "knife.cam.json").rmdir()
    assert ep.feed(b"F3000=0.5\r") == b"\r\n>"
    assert CamMemory.load(tmp_path / "knife.cam.json").read("F", 3000) == 0.5


def test_an_fs701_store_to_eeprom_failing_at_run_time_is_refused_on_both_interfaces(tmp_path):
    d = tomllib.loads((EXAMPLES / "flying_shear.toml").read_text())
    d["device"].update(parameter_file=str(EXAMPLES / d["device"]["parameter_file"]), save_parameters="eeprom.toml",
                       commissioning=False)
    d["trace"] = {"enabled": False}
    m = Machine(parse_machine(d, str(tmp_path / "m.toml")), source=str(tmp_path / "m.toml"))
    dev = m.device
    dev.network_writes = True
    c = DrivecomClient(dev.byte_endpoint().feed)
    c.write(0x0000, 1200)
    c.write(STORE_TO_EEPROM, 1)  # ACK only once the file is written
    assert load_parameter_file(tmp_path / "eeprom.toml").params.cutting_length == 1200
    c.write(STORE_TO_EEPROM, 0)
    (tmp_path / "eeprom.toml").unlink()
    (tmp_path / "eeprom.toml").mkdir()
    c.write(0x0000, 1300)
    with pytest.raises(DrivecomError, match="NAK"):
        c.write(STORE_TO_EEPROM, 1)
    assert dev.registers.eeprom.params.cutting_length == 1200  # the EEPROM keeps what it had
    c.write(STORE_TO_EEPROM, 0)
    with pytest.raises(RegisterRefused, match="Store to EEProm") as refused:
        dev.register_endpoint().write_registers(2 * STORE_TO_EEPROM, [0, 1])
    assert refused.value.exception_code == 4  # "refused by the device", not an address error
    assert dev.registers.eeprom.params.cutting_length == 1200
