"""The CLM personality on the simulated plant: the roll feed example, wiring, the NC cycle rule,
the retained memory."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from serving import serve
from typer.testing import CliRunner

from axisline.cli import app
from axisline.configerrors import ConfigError
from axisline.machine import Machine

EXAMPLES = Path(__file__).resolve().parents[3] / "examples"
ROLL_FEED = EXAMPLES / "roll_feed_clm.toml"
runner = CliRunner()


def _machine_file(tmp_path: Path, replace: tuple[str, str] | None = None, extra: str = "") -> Path:
    text = ROLL_FEED.read_text().replace('"clm/', f'"{EXAMPLES.as_posix()}/clm/')
    if replace is not None:
        assert replace[0] in text
        text = text.replace(*replace)
    path = tmp_path / "roll_feed.toml"
    path.write_text(text + extra)
    return path


def test_roll_feed_example_feeds_20_parts_and_reports_each_press_signal():
    """Issue 12: the roll feed runs the CLM's own files; per feed the position error when the press
    signal (Q1.00.0) comes. 20 parts of V600 = 250 mm (V602 = 20), within 0.1 mm (A127 0.05 mm
    plus the settling after PSI proceeds)."""
    m = Machine.from_file(ROLL_FEED)
    result = m.run()
    assert result.completed
    summary = m.device.summary()
    feeds = summary["feeds"]
    assert len(feeds) == 20
    assert [round(f["target"], 6) for f in feeds] == [250.0 * k for k in range(1, 21)]
    assert all(abs(f["error"]) < 0.1 for f in feeds)
    assert summary["fault"] is None and summary["mode"] == "automatic"
    assert m.device.memory.variables[603] == 0  # the count mirrored into V603, back at 0 at the target
    assert m.io.output("batch_done")


def test_the_run_is_deterministic():
    a, b = Machine.from_file(ROLL_FEED), Machine.from_file(ROLL_FEED)
    a.run(), b.run()
    assert a.device.summary()["feeds"] == b.device.summary()["feeds"]


def test_cycle_time_must_be_the_clms_nc_cycle(tmp_path):
    """Issue 12: machine.cycle_us must match B010 (0.0 = 2 ms for one axis, spec §1.4)."""
    path = _machine_file(tmp_path, ("cycle_us = 2000", "cycle_us = 1000"))
    with pytest.raises(ConfigError) as e:
        Machine.from_file(path)
    assert "machine.cycle_us = 1000" in str(e.value) and "cycle_us = 2000" in str(e.value)
    r = runner.invoke(app, ["check", str(path)])
    assert r.exit_code == 2 and "B010" in r.output


def test_a_bad_program_file_is_a_bad_machine_file(tmp_path):
    prg = tmp_path / "bad.prg"
    prg.write_text("0000 POI 7 +000010.000 999\n")
    path = _machine_file(tmp_path, (f'program = "{EXAMPLES.as_posix()}/clm/roll_feed.prg"', f'program = "{prg.as_posix()}"'))
    r = runner.invoke(app, ["check", str(path)])
    out = " ".join(r.output.split())  # rich wraps long lines
    assert r.exit_code == 2 and "device.program" in out and "N0000 16 Axis No. false" in out


def test_retained_memory_keeps_counters_and_variables_across_a_restart(tmp_path):
    """Issue 12: the retained memory survives a restart: saved when it changes, loaded at start
    in place of the files (spec §1.3)."""
    path = _machine_file(tmp_path, extra='\n')
    text = path.read_text().replace('report_output = "Q1.00.0"', 'report_output = "Q1.00.0"\nmemory_file = "roll_feed.clm.json"')
    path.write_text(text)
    m = Machine.from_file(path, duration=3.0)
    m.run(3.0)
    count = m.device.memory.program.counters[7]
    assert 0 < count < 20
    store = tmp_path / "roll_feed.clm.json"
    doc = json.loads(store.read_text())
    assert doc["counters"]["7"] == count  # written at the cycle it changed, not only at shutdown
    m2 = Machine.from_file(path)
    assert m2.device.memory.program.counters[7] == count
    assert m2.device.memory.variables[600] == 250_000_000


def test_retained_memory_survives_kill_9_ofserve(tmp_path):
    """Issue 12: what the CLM acknowledged (a variable written over X6) and what it executed (the
    part counter) are in the memory file at once; a kill -9 at any moment loses none of it and
    leaves a file that loads."""
    import signal
    import socket
    import time

    from axisline.devices.clm.telegram import emit

    path = _machine_file(tmp_path)
    path.write_text(path.read_text().replace('report_output = "Q1.00.0"', 'report_output = "Q1.00.0"\nmemory_file = "roll_feed.clm.json"'))
    for round_ in range(3):
        proc, endpoints = serve(str(path), "--serial-tcp", "127.0.0.1:0", "--allow-writes")
        try:
            host, _, port = endpoints["serial-tcp"].rpartition(":")
            with socket.create_connection((host, int(port)), timeout=10) as sock:
                value = f"+{round_ + 1:08d}.500000"
                sock.sendall(emit("#", 0, "V", f"{610 + round_:03d} {value} ").encode())
                reply = b""
                while not reply.endswith(b"\r\n"):
                    chunk = sock.recv(256)
                    assert chunk
                    reply += chunk
                assert not reply.startswith(b"X"), reply  # no Status 01 error: acknowledged
            time.sleep(0.05 * round_)  # at some moment of the run
        finally:
            proc.send_signal(signal.SIGKILL)
            proc.wait(timeout=10)
        m = Machine.from_file(path)  # the file loads
        for k in range(round_ + 1):
            assert m.device.memory.variables[610 + k] == (k + 1) * 1_000_000 + 500_000
