"""Machine-level print-mark jobs: Cutting Mode 3 (additional cuts) and the print-mark window
with teach, driven through the personality on a short variant of
examples/flying_shear_printmark.toml (written to tmp_path; same carriage, wheel, parameters).

The cuts are measured on the simulated strip (line.py): print-mark cuts by their offset to the
mark, additional cuts by their piece length (line.py M5).
"""

from __future__ import annotations

import tomllib
from pathlib import Path

import pytest

from axisline.config import parse_machine
from axisline.devices.fs701.drivecom import DrivecomClient
from axisline.machine import Machine

EXAMPLES = Path(__file__).resolve().parents[3] / "examples"
PRINTMARK = EXAMPLES / "flying_shear_printmark.toml"
TEACH = 0x090D  # single command "Teach Printmark" (bit 13)


def _toml(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, str):
        return '"' + v.replace("\\", "\\\\").replace('"', '\\"') + '"'
    if isinstance(v, list):
        return "[" + ", ".join(_toml(x) for x in v) + "]"
    if isinstance(v, dict):
        return "{ " + ", ".join(f"{k} = {_toml(x)}" for k, x in v.items()) + " }"
    return repr(v)


def _dump(data: dict) -> str:
    """A small TOML writer for the example's shape (tables, arrays of tables, inline values)."""
    out: list[str] = []

    def table(prefix: str, d: dict, array: bool = False) -> None:
        simple = {k: v for k, v in d.items() if not isinstance(v, dict) and not (isinstance(v, list) and v and isinstance(v[0], dict) and k != "profile")}
        out.append(f"[[{prefix}]]" if array else f"[{prefix}]")
        out.extend(f"{k} = {_toml(v)}" for k, v in simple.items())
        for k, v in d.items():
            if isinstance(v, dict):
                table(f"{prefix}.{k}", v)
            elif isinstance(v, list) and v and isinstance(v[0], dict) and k != "profile":
                for item in v:
                    table(f"{prefix}.{k}", item, array=True)

    for k, v in data.items():
        if isinstance(v, dict):
            table(k, v)
        elif isinstance(v, list) and v and isinstance(v[0], dict):
            for item in v:
                table(k, item, array=True)
    return "\n".join(out) + "\n"


def machine_file(tmp_path: Path, *, speed: float, marks: dict, parameters: dict, batch: int, duration: float) -> Path:
    data = tomllib.loads(PRINTMARK.read_text())
    data["machine"]["duration"] = duration
    data["trace"] = {"enabled": False}
    data["material"]["profile"] = [{"time": 0.0, "speed": speed, "acceleration": 250.0}]
    data["marks"][0].update(marks)
    data["marks"][0] = {k: v for k, v in data["marks"][0].items() if v is not None}  # None: removed
    dev = data["device"]
    dev["parameter_file"] = str(EXAMPLES / dev["parameter_file"])
    dev["commissioning"] = False  # the example's drive errors are left to the Adjust tests
    dev["batch"] = batch
    dev["parameters"].update(parameters)
    data["axis"][0]["drive"].update(gain_factor=1.0, offset_volts=0.0)
    path = tmp_path / "printmark_short.toml"
    path.write_text(_dump(data))
    return path


def load(path: Path) -> Machine:
    return Machine(parse_machine(tomllib.loads(path.read_text()), str(path)), source=str(path))


def test_cutting_mode_3_cuts_the_additional_pieces_before_each_mark(tmp_path):
    """Spec §2.12 / cutter P7: Additional Cuts 2, L1 = 300, L2 = 250, mark pitch 800, Tool Width
    0: per mark the cuts M - 550, M - 300, M; pieces tail 250, L2 250, L1 300 (ending on the mark)."""
    path = machine_file(
        tmp_path,
        speed=250.0,  # 15 m/min: a cut every second at least (250 mm pieces)
        marks={"jitter": 0.0},
        parameters={"cutting_mode": 3, "additional_cuts": 2, "add_cut_1_length": 300, "add_cut_2_length": 250},
        batch=12,
        duration=40.0,
    )
    m = load(path)
    result = m.run()
    dev = m.device
    assert result.completed and result.faults == [], result.faults
    assert dev.errors_raised == [] and dev.cutter.batch_counter >= 12
    cuts = dev.cuts
    kinds = [c.kind for c in cuts]
    assert kinds.count("PRINTMARK") >= 3 and kinds.count("ADDITIONAL") >= 2 * kinds.count("PRINTMARK")
    marks_at = [c for c in cuts if c.kind == "PRINTMARK"]
    for c in marks_at:  # on the mark (first = 100, pitch 800)
        assert abs(c.mark_offset_counts) <= 2.0, c
        assert (c.material_point - 100.0) % 800.0 == pytest.approx(0.0, abs=0.2) or (c.material_point - 100.0) % 800.0 == pytest.approx(800.0, abs=0.2)
    # every mark after the first: tail, L2, L1 in this order
    first = kinds.index("PRINTMARK")
    seq = cuts[first + 1 :]
    for k in range(0, len(seq) - 2, 3):
        tail, l2, l1 = seq[k : k + 3]
        assert (tail.kind, l2.kind, l1.kind) == ("ADDITIONAL", "ADDITIONAL", "PRINTMARK")
        assert tail.actual_length == pytest.approx(250.0, abs=0.1)
        assert l2.actual_length == pytest.approx(250.0, abs=0.1)
        assert l1.actual_length == pytest.approx(300.0, abs=0.1)
        assert tail.mark_offset is None and tail.in_tolerance  # checked as a length (line.py M5)
        assert l1.material_point - tail.material_point == pytest.approx(550.0, abs=0.1)
    stats = dev.summary()["batch"]
    assert stats["out_of_tolerance"] == []


def _window_machine(tmp_path: Path) -> Machine:
    # decoy marks 300 before each valid one; the decoys pass the sensor first
    valid = [500.0 + 800.0 * k for k in range(40)]
    decoys = [v - 300.0 for v in valid]
    path = machine_file(
        tmp_path,
        speed=500.0,
        marks={"positions": sorted(valid + decoys), "jitter": None, "first": None, "pitch": None},
        parameters={"printmark_window": 100, "cutting_length": 800},
        batch=8,
        duration=40.0,
    )
    return load(path)


def _run_to_end(m: Machine, on_cycle=None, limit_s: float = 40.0) -> None:
    for _ in range(int(limit_s / m.period)):
        m.scheduler.run_cycle()
        if on_cycle is not None:
            on_cycle()
        if m.device.finished:
            break


def _phase(c) -> float:
    return (c.material_point - 500.0) % 800.0


def test_printmark_window_taught_on_the_valid_mark_ignores_the_decoys(tmp_path):
    """Spec §2.10: Teach Printmark HIGH while the valid mark approaches the sensor, LOW before
    the next mark: the window sits on the valid marks, the decoys 300 mm before them are blanked."""
    m = _window_machine(tmp_path)
    dev = m.device
    dev.network_writes = True
    client = DrivecomClient(dev.byte_endpoint().feed)
    sensor = dev.mark_sensor
    state = {"last": False, "edges": 0, "teach": None}

    def teach():
        on = bool(sensor.state)
        if on and not state["last"]:
            state["edges"] += 1
            if state["edges"] == 2:  # the valid mark passed while Teach was HIGH
                client.write(TEACH, 0)
                state["teach"] = "done"
        if not on and state["last"] and state["edges"] == 1 and state["teach"] is None:
            client.write(TEACH, 1)  # after the first decoy, before the valid mark
            state["teach"] = "on"
        state["last"] = on

    _run_to_end(m, teach)
    assert state["teach"] == "done"
    assert dev.cutter.outputs.printm_teached  # output "Printm. teached"
    assert client.read(0x0814) & 0b1001 == 0b1001  # #20 Printmark Status: window on, taught
    assert dev.finished and dev.errors_raised == []
    cuts = [c for c in dev.cuts if c.kind == "PRINTMARK"]
    assert len(cuts) >= 6
    # the first decoy passed the sensor before the teach: registered (the untaught window
    # locks on the first mark), it is still cut; every mark registered after it is a valid one
    assert abs(_phase(cuts[0]) - 500.0) <= 0.2
    for c in cuts[1:]:  # on the valid marks (500 + 800 k), not on the decoys (200 + 800 k)
        assert min(_phase(c), 800.0 - _phase(c)) <= 0.2, c
        assert abs(c.mark_offset_counts) <= 2.0
    assert cuts[1].actual_length == pytest.approx(300.0, abs=0.1)  # decoy -> valid mark
    assert all(c.actual_length == pytest.approx(800.0, abs=0.1) for c in cuts[2:])
    assert client.read(0x0813) == 0  # #19 no missing marks


def test_without_teach_the_window_locks_on_the_first_mark_seen(tmp_path):
    """Contrast (cutter P2 "before a teach the first mark places the window"): the first mark
    the sensor sees is a decoy, so the untaught window cuts on the decoys."""
    m = _window_machine(tmp_path)
    dev = m.device
    _run_to_end(m)
    assert not dev.cutter.outputs.printm_teached
    cuts = [c for c in dev.cuts if c.kind == "PRINTMARK"]
    assert len(cuts) >= 6
    assert all(abs(_phase(c) - 500.0) <= 0.2 for c in cuts)  # 200 + 800 k: the decoys
