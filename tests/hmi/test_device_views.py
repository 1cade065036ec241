"""The device views of the four personalities (axisline.hmi.devices, issue 17): what the HMI's
device page shows is what the device reports over its own protocol, a write goes through the
device's own validation (refused: the device's message, nothing changed), and acknowledge is
the device's own fault reset.

Each test builds the personality's example machine on the simulated clock and runs it; the
protocol read-backs go through the endpoints `serve` offers (Modbus, Drivecom, the ASCII
interface, the CLM's X6 telegrams).
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import pytest

from axisline.devices.compax.curves import read_curve
from axisline.devices.fs701.modbus_map import decode_words
from axisline.devices.wago672.coupler import OUTPUT_READBACK, unpack
from axisline.devices.wago672.image import InputImage
from axisline.devices.wago672.mailbox import MbxOpcode
from axisline.hmi.devices import device_acknowledge, device_faults, device_view, device_write
from axisline.machine import Machine

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def _view(machine: Machine) -> dict[str, Any]:
    """The device view, checked to be strict JSON (no NaN, no numpy, no Decimal)."""
    view = device_view(machine.device)
    assert json.loads(json.dumps(view, allow_nan=False)) == view
    assert isinstance(view["title"], str) and view["title"]
    return view


def _sections(view: dict[str, Any], kind: str) -> list[dict[str, Any]]:
    return [s for s in view["sections"] if s["type"] == kind]


def _row(view: dict[str, Any], name: str) -> dict[str, Any]:
    rows = [r for s in _sections(view, "parameters") for r in s["rows"] if r["name"] == name]
    assert len(rows) == 1, f"{name}: {len(rows)} rows"
    return rows[0]


def _refused(device: Any, name: str, value: Any, *words: str) -> str:
    with pytest.raises(ValueError) as info:
        device_write(device, name, value)
    text = str(info.value)
    for w in words:
        assert w in text, f"{w!r} not in {text!r}"
    return text


# -- FS701 -------------------------------------------------------------------------------------------


@pytest.fixture
def shear() -> Machine:
    m = Machine.from_file(EXAMPLES / "flying_shear.toml")
    m.scheduler.run(3500)  # the batch has started: the first cuts are made
    return m


def _modbus_value(device: Any, code: int) -> int:
    """A register as the Modbus endpoint reads it: 2 x code, 2 words, high word first."""
    return decode_words(device.register_endpoint().read_registers("holding", 2 * code, 2))


def test_fs701_view_shows_registers_words_and_the_growing_cut_table(shear):
    d = shear.device
    view = _view(shear)
    row = _row(view, "cutting_length")
    assert row["value"] == _modbus_value(d, 0x0000) == 1000  # examples/flying_shear.toml
    assert (row["min"], row["max"], row["unit"], row["writable"]) == (1, 999999, "LU", True)
    sync = _row(view, "sync_rate")  # implied decimals: the engineering value, the raw one on the wire
    assert sync["value"] * 100 == pytest.approx(_modbus_value(d, 0x0105))
    assert _row(view, "line_speed")["value"] == _modbus_value(d, 0x0802)  # process value #2
    words = {w["name"]: w for s in _sections(view, "bits") for w in s["words"]}
    outputs = words["Output Status (0x0B04)"]
    assert outputs["value"] == _modbus_value(d, 0x0B04)
    assert {b["name"]: b["set"] for b in outputs["bits"]}["Ready"] is True
    errors = _sections(view, "diagnostics")[0]["rows"]
    assert [r["code"] for r in errors] == ["00", "01", "02", "03", "04", "05"] and not any(r["active"] for r in errors)
    cuts = _sections(view, "table")[0]
    before = len(cuts["rows"])
    assert before >= 1 and cuts["rows"][0][0] == 1
    shear.scheduler.run(3000)  # 60 m/min, 1 m pieces: about one cut a second
    after = _sections(_view(shear), "table")[0]["rows"]
    assert len(after) >= before + 2
    assert after[-1][0] == len(d.meter.records)  # the newest cut is the last row
    last = d.meter.records[-1].as_dict()
    assert after[-1][5] == pytest.approx(last["error_lu"])


def test_fs701_write_in_range_and_refused(shear):
    d = shear.device
    assert device_write(d, "cutting_length", 900) == (1000, 900)
    assert _modbus_value(d, 0x0000) == 900
    assert _row(_view(shear), "cutting_length")["value"] == 900
    _refused(d, "cutting_length", 0, "cutting_length", "0", "1..999999 LU")
    _refused(d, "cutting_length", 1e7, "Cutting Length", "1..999999")
    _refused(d, "sync_rate", 1.234, "sync_rate", "1.234", "resolution 0.01")
    _refused(d, "no_such_parameter", 1, "no_such_parameter")
    assert _modbus_value(d, 0x0000) == 900  # a refused write changed nothing
    assert device_write(d, "Cutting Length", "1000") == (900, 1000)  # the manual's name, a text value


def test_fs701_acknowledge_clears_error_02(shear):
    """Manual §6: Error 02 "Cut not possible" (too short a length at this line speed) stops the
    cutting; Clear Error clears it (decision 1 of hmi/devices/fs701.py)."""
    d = shear.device
    device_write(d, "cutting_length", 20)
    shear.scheduler.run(1000)
    view = _view(shear)
    active = [r for r in _sections(view, "diagnostics")[0]["rows"] if r["active"]]
    assert [r["code"] for r in active] == ["02"]
    assert _modbus_value(d, 0x0B05) == 1 << 2
    assert list(device_faults(d)) == ["FS701 error 02"]  # serve's event log sees the same
    device_write(d, "cutting_length", 1000)
    assert "Error 02" in device_acknowledge(d)
    shear.scheduler.run(2)
    assert _modbus_value(d, 0x0B05) == 0
    assert device_faults(d) == {}
    assert d.registers.status.serial_commands == 0  # the Clear Error pulse is released
    cuts = len(d.meter.records)
    shear.scheduler.run(3000)
    assert len(d.meter.records) > cuts  # cutting again
    assert device_acknowledge(d) == ""  # nothing left to acknowledge


# -- COMPAX -----------------------------------------------------------------------------------------


@pytest.fixture
def cam() -> Machine:
    m = Machine.from_file(EXAMPLES / "cam_packaging.toml")
    m.scheduler.run(2000)
    return m


def _ascii(device: Any, line: str) -> str:
    reply = device.byte_endpoint().execute(line).decode("ascii")
    return reply.removesuffix("\r\n>")


def test_compax_view_has_curves_and_status(cam):
    d = cam.device
    view = _view(cam)
    for n in (32, 33, 93):
        assert _ascii(d, f"P{n}") == f"P{n:03d}={d.params.format(n)}"
        row = _row(view, f"P{n}")
        assert row["value"] == pytest.approx(float(_ascii(d, f"P{n}").split("=")[1]))
    assert _row(view, "P33")["allowed"] == [0, 1, 2, 10, 11, 12]
    assert _row(view, "S44")["value"] == pytest.approx(float(_ascii(d, "S44").split("=")[1]), abs=1e-3)
    assert _row(view, "S43")["value"] == 1  # the example runs curve 1
    plots = _sections(view, "plot")
    assert len(plots) == d.memory.curve_count(valid=True)
    curve = read_curve(d.memory, 1)
    series = plots[0]["series"][0]
    assert len(series["x"]) == len(series["y"]) == curve.n_points <= 500
    assert series["x"][-1] == pytest.approx(curve.master_cycle)
    assert series["y"][-1] == pytest.approx(curve.slave_cycle * curve.set_points[-1])
    words = {w["name"]: w for s in _sections(view, "bits") for w in s["words"]}
    assert words["O1 ... O16"]["value"] == d.op.out
    assert {b["name"]: b["set"] for b in words["O1 ... O16"]["bits"]}["O16 synchronous"] is d.op.output(16)


def test_a_long_curve_is_thinned_to_500_points_keeping_both_ends():
    """A curve of the whole cam memory (5460 set points) is plotted with 500 points."""
    from axisline.hmi.devices._sections import downsample, plot

    xs = list(range(5460))
    x, y = downsample(xs, [2 * v for v in xs])
    assert len(x) == 500 and x[0] == 0 and x[-1] == 5459 and y == [2 * v for v in x]
    series = plot("curve", "m", "s", [("c", [0.0, float("nan")], [1.0, 2.0])])["series"][0]
    assert series == {"name": "c", "x": [0.0, None], "y": [1.0, 2.0]}  # strict JSON: no NaN


def test_compax_write_in_range_and_refused(cam):
    d = cam.device
    old = d.params.written[32]
    assert device_write(d, "P32", 1.5) == (old, 1.5)
    assert float(_ascii(d, "P32").split("=")[1]) == 1.5  # the interface reads the written value back
    assert d.params.pending()[32] == "written"  # valid with VP, as on the device
    row = _row(_view(cam), "P32")
    assert row["value"] == 1.5 and "VP" in row["note"]
    _refused(d, "P33", 5, "P33", "5", "0, 1, 2, 10, 11, 12")
    _refused(d, "P93", 2.5, "P93", "2.5")
    _refused(d, "P999", 1, "P999")
    assert d.params.written[33] == 1 and d.params.written[93] == 3
    assert _ascii(d, "S30") == "S030=0.000"  # decision 1: a refused HMI write is not the host's last error


def test_compax_acknowledge_is_quit(cam):
    d = cam.device
    d.network_writes = True
    assert _ascii(d, "SETC 9").startswith("!E17")  # manual §22: "Curve not present"
    assert _ascii(d, "S30") == "S030=17.000"
    active = [r["code"] for r in _sections(_view(cam), "diagnostics")[0]["rows"] if r["active"]]
    assert "E17" in active
    assert device_faults(d) == {"COMPAX E17": "Curve not present"}
    assert "E17 Curve not present" in device_acknowledge(d)
    assert device_faults(d) == {}
    assert _ascii(d, "S30") == "S030=0.000"
    active = [r["code"] for r in _sections(_view(cam), "diagnostics")[0]["rows"] if r["active"] and r["code"].startswith("E")]
    assert active == []
    assert device_acknowledge(d) == ""


# -- WAGO 750-672 -------------------------------------------------------------------------------------


@pytest.fixture
def stepper() -> Machine:
    m = Machine.from_file(EXAMPLES / "wago_stepper.toml")
    m.scheduler.run(1500)
    return m


def _config_rd(device: Any, address: int, size: int) -> int:
    """A configuration value as the mailbox's CONFIG_RD returns it."""
    _, payload = device.modules[0].mailbox.execute(MbxOpcode.CONFIG_RD, bytes([address & 0xFF, address >> 8, size, 0]))
    return int.from_bytes(payload[:size], "little")


def test_wago_view_decodes_the_process_image(stepper):
    d = stepper.device
    view = _view(stepper)
    image = InputImage.from_bytes(unpack(d.coupler.read_registers("input", 0, 6)))
    assert _row(view, "position")["value"] == image.positioning().position
    words = {w["name"]: w for s in _sections(view, "bits") for w in s["words"]}
    assert words["S1 (input)"]["value"] == image.s1
    assert {b["name"]: b["set"] for b in words["S1 (input)"]["bits"]}["Ready"] is bool(image.s1 & 1)
    outputs = unpack(d.coupler.read_registers("holding", OUTPUT_READBACK, 6))
    assert words["C1 (output)"]["value"] == outputs[11]  # C1 is byte 11 of the image
    assert _row(view, "SetupSpeed")["value"] == _config_rd(d, 44, 2)
    assert (_row(view, "SetupSpeed")["min"], _row(view, "SetupSpeed")["max"]) == (0, 25000)


def test_wago_config_write_in_range_and_refused(stepper):
    d = stepper.device
    old = _config_rd(d, 44, 2)
    _view(stepper)  # (the table is built once per change: the next view shows the write)
    assert device_write(d, "SetupSpeed", 3000) == (old, 3000)
    assert _config_rd(d, 44, 2) == 3000
    assert _row(_view(stepper), "SetupSpeed")["value"] == 3000
    _refused(d, "SetupSpeed", 30000, "1211", "SetupSpeed", "30000", "0 .. 25000")  # the manual's error code
    _refused(d, "Speed", 0, "1117", "1 .. 25000")
    _refused(d, "SetupSpeed", 1.5, "SetupSpeed", "1.5")
    _refused(d, "m3.Speed", 5, "no module 3")
    assert _config_rd(d, 44, 2) == 3000


def test_wago_output_register_write_goes_to_the_module(stepper):
    d = stepper.device
    assert device_write(d, "m0.out1", 0x1234)[1] == 0x1234
    assert d.coupler.read_registers("holding", OUTPUT_READBACK + 1, 1) == [0x1234]
    _refused(d, "m0.out1", 70000, "0 .. 65535")
    _refused(d, "m0.out6", 1, "out0 .. out5")
    assert d.coupler.read_registers("holding", OUTPUT_READBACK + 1, 1) == [0x1234]


def test_wago_acknowledge_quits_the_error(stepper):
    d = stepper.device
    mailbox = d.modules[0].mailbox
    mailbox.execute(MbxOpcode.CONFIG_SET_PTR, bytes([0, 0, 5, 0]))  # 5 bytes: error 1161 CONFIG_WRITE_SIZE
    stepper.scheduler.run(2)
    diag = _sections(_view(stepper), "diagnostics")[0]["rows"]
    assert diag[0]["code"] == 1161 and diag[0]["active"]
    assert list(device_faults(d)) == ["750-672 module 0 error"] and "1161" in device_faults(d)["750-672 module 0 error"]
    assert "1161" in device_acknowledge(d)
    stepper.scheduler.run(2)
    assert device_faults(d) == {}
    assert d.device(0).errors.error == 0
    assert not _sections(_view(stepper), "diagnostics")[0]["rows"][0]["active"]


# -- CLM1.4 ----------------------------------------------------------------------------------------------


@pytest.fixture
def clm(tmp_path) -> Machine:
    """The roll feed with its mode and E-Stop inputs on [io] inputs the test switches."""
    text = (EXAMPLES / "roll_feed_clm.toml").read_text().replace('"clm/', f'"{EXAMPLES.as_posix()}/clm/')
    text = text.replace('inputs = ["press_top", "press_bottom"]', 'inputs = ["press_top", "press_bottom", "sel_param", "sel_auto", "estop"]')
    text = text.replace('"I1.00.2" = true', '"I1.00.2" = true\n"I0.00.0" = "sel_param"\n"I0.00.1" = "sel_auto"\n"I0.00.2" = "estop"')
    path = tmp_path / "roll_feed.toml"
    path.write_text(text)
    m = Machine.from_file(path)
    m.io.set_input("sel_auto", True)
    m.io.set_input("estop", True)  # closed
    m.io.sample()  # the levels in the image from power-on (an open E-Stop at power-on is fault 03)
    m.scheduler.run(1000)
    return m


def _mode(m: Machine, wanted: str) -> None:
    m.io.set_input("sel_param", wanted == "parameter")
    m.io.set_input("sel_auto", wanted == "automatic")
    m.scheduler.run(3)
    assert m.device.rt.modes.mode == wanted


def _x6(device: Any, body: str) -> str:
    """A query over the CLM's X6 protocol (checksum and line end stripped)."""
    reply = device.byte_endpoint().feed(f"? {body}\r\n".encode("ascii")).decode("ascii")
    return reply.split("$")[0]


def test_clm_view_has_tasks_program_cta_and_io(clm):
    d = clm.device
    view = _view(clm)
    assert _row(view, "A101.feed_constant")["value"] == float(d.memory.parameters.get("A101")["feed_constant"])
    assert _x6(d, "K A101").endswith(d.memory.parameters.data("A101"))
    tables = {s["title"].split(" (")[0]: s for s in _sections(view, "table")}
    tasks = tables["Task display"]["rows"]
    t1 = d.rt.tasks[0]
    assert tasks[0][:3] == ["Task 1", "running", f"{t1.pc:04d}"]
    assert _x6(d, "X  08 ")[5:9] == f"{t1.pc:04d}"  # Status 08: Task 1's instruction
    program = tables["Program"]["rows"]
    assert [r[0] for r in program] == [f"{i.number:04d}" for i in d.memory.program.written()]
    assert [r for r in program if r[1] == "T1"][0][0] == f"{t1.pc:04d}"
    texts = {s["title"]: s["lines"] for s in _sections(view, "text")}
    assert texts["CTA: tasks"] == ["Tasks", f"T1 {t1.pc:04d}"]
    assert texts["CTA: error (F1)"][:2] == ["Error 00", "no error"]
    words = {w["name"]: w for s in _sections(view, "bits") for w in s["words"]}
    i000 = words["I0.00"]
    assert format(i000["value"], "08b") == _x6(d, "X  61 I0.00 ")[11:19]  # Status 61, bit 7 first
    assert {b["name"]: b["set"] for b in i000["bits"]}["Automatic / Manual"] is True
    assert {b["name"]: b["set"] for b in words["Q0.00"]["bits"]}["Automatic"] is True
    assert not _sections(view, "diagnostics")[0]["rows"][0]["active"]


def test_clm_parameter_write_in_parameter_mode(clm):
    d = clm.device
    params = d.memory.parameters
    _refused(d, "A101.feed_constant", 12.5, "05", "Parameter mode")  # the CLM's rule (L6574)
    assert params.data("A101") == "0010.00000"
    _mode(clm, "parameter")
    _view(clm)
    assert device_write(d, "A101.feed_constant", 12.5) == (10, 12.5)
    assert _x6(d, "K A101").endswith("0012.50000")
    assert _row(_view(clm), "A101.feed_constant")["value"] == 12.5
    _refused(d, "B002.baud_rate", 1234, "B002.baud_rate", "1234", "9600")  # decision 1: at once, not at fault 02
    _refused(d, "A101.feed_constant", 99999, "feed_constant")
    _refused(d, "A101.feed_constant", 1.234567, "decimals")
    _refused(d, "A101.no_such_field", 1, "feed_constant")
    assert params.data("A101") == "0012.50000" and params.data("B002").startswith("019200")
    assert device_write(d, "A101", "0010.00000") == ("0012.50000", "0010.00000")  # the whole data
    _mode(clm, "automatic")
    assert d.rt.modes.fault_error is None


def test_clm_variable_write_in_any_mode(clm):
    d = clm.device
    old = _x6(d, "V600").split()[-1]
    assert device_write(d, "V600", 12.5) == (old, "+00000012.500000")
    assert _x6(d, "V600").split()[-1] == "+00000012.500000"
    _refused(d, "V100", 1, "23", "V600-V999")
    _refused(d, "V600", "1e5", "V600")
    assert _row(_view(clm), "V600")["value"] == "+00000012.500000"


def test_clm_acknowledge_is_the_cl_key(clm):
    d = clm.device
    clm.io.set_input("estop", False)  # E-Stop: fault 03
    clm.scheduler.run(2)
    rows = _sections(_view(clm), "diagnostics")[0]["rows"]
    assert rows[0]["code"] == "03" and rows[0]["active"]
    assert list(device_faults(d)) == ["CLM error 03"]
    assert "not cleared" in device_acknowledge(d)  # the cause is still there (modes.py: clear only when it is gone)
    assert d.rt.modes.fault_error is not None
    clm.io.set_input("estop", True)
    clm.scheduler.run(2)
    assert "03" in device_acknowledge(d)
    assert d.rt.modes.fault_error is None
    assert device_faults(d) == {}
    assert _sections(_view(clm), "text")[2]["lines"][:2] == ["Error 00", "no error"]


def test_a_device_without_a_view_is_refused():
    class Other:
        name = "other"

    with pytest.raises(ValueError, match="no device view"):
        device_view(Other())
    with pytest.raises(ValueError, match="no device view"):
        device_write(Other(), "x", 1)


def test_clm_program_listing_is_bounded_around_the_tasks(clm):
    """Decision 4 of hmi/devices/clm.py: at most MAX_LISTING instructions, the running task's first."""
    from dataclasses import replace

    from axisline.hmi.devices.clm import MAX_LISTING

    d = clm.device
    program = d.memory.program
    sample = program.written()[0]
    for n in range(1000, 1400):  # a long program: 400 more instructions far from Task 1
        program.store(replace(sample, number=n))
    rows = [s for s in _sections(_view(clm), "table") if s["title"].startswith("Program")][0]["rows"]
    assert len(rows) == MAX_LISTING
    assert f"{d.rt.tasks[0].pc:04d}" in [r[0] for r in rows]
    assert [r[0] for r in rows] == sorted(r[0] for r in rows)
