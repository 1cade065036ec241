"""The COMPAX personality in a Machine: the [device] table, the start-up program, the I/O wiring,
the ASCII interface through byte_endpoint (and over TCP), persistence of the cam memory."""

from __future__ import annotations

import copy
import json
import socket
import threading
import time
import tomllib
from pathlib import Path

import pytest

from axisline.config import parse_machine
from axisline.configerrors import ConfigError
from axisline.devices.compax.camop import CamState
from axisline.devices.compax.curves import curve_from_csv, read_curve
from axisline.devices.compax.personality import CompaxPersonality, derive_master_scaling
from axisline.fieldbus.serial_tcp import SerialTcpServer
from axisline.machine import Machine
from axisline.motion.axis import AxisState

EXAMPLES = Path(__file__).resolve().parents[3] / "examples"
EXAMPLE = EXAMPLES / "cam_packaging.toml"


def example_data() -> dict:
    return tomllib.loads(EXAMPLE.read_text())


def small(**device) -> dict:
    """A slave on the internal time base with a straight-line curve: quick to build and run."""
    data = {
        "machine": {"personality": "compax", "duration": 2.0},
        "axis": [{"name": "s", "unit": "deg", "counts_per_unit": 100.0, "v_max": 5000.0, "a_max": 1e6,
                  "kv": 80.0, "following_error_limit": 10.0, "drive": {"type": "servo", "time_constant": 0.001}}],
        "io": {"inputs": ["couple"], "outputs": ["sync", "warn"]},
        "device": {
            "slave": "s",
            "master": "internal",
            "parameters": {"P35": 1.0},
            "inputs": {"I13": True, "I16": True},
            "outputs": {"O16": "sync", "O15": "warn"},
            "startup": ["SETC 1", "SETM 0", "LOOP 0"],
        },
        "trace": {"enabled": False},
    }
    data["device"].update(device)
    return data


def build(data: dict, source: str | Path = "") -> Machine:
    return Machine(parse_machine(data, str(source) or "t.toml"), source=str(source))


# --------------------------------------------------------------------------- construction


def test_built_from_the_example_machine_file():
    m = Machine.from_file(EXAMPLE)
    dev = m.device
    assert isinstance(dev, CompaxPersonality) and dev.name == "compax" and dev.endpoints == ("serial-tcp",)
    # the wheel: 1000 lines x4 per 200 mm -> P98 = 200, P143 = 1000 (4*P143/P98 = 20 counts/mm)
    assert dev.params[98] == 200.0 and dev.params[143] == 1000
    assert dev.params[180] == 5.0  # VP made it valid; P32 / P33 are armed until the LOOP (their "valid from")
    assert dev.params.written[32] == 450.0 and dev.params.pending() == {32: "armed", 33: "armed"}
    assert dev.memory.curve_count() == 2
    knife = dev.curve(1)
    assert knife.master_cycle == 300.0 and knife.slave_cycle == pytest.approx(360.0) and knife.n_points == 301
    assert knife.label_window == pytest.approx(0.1, abs=1e-6) and knife.correction_enable == pytest.approx(0.15, abs=1e-6)
    jaw = dev.curve(2)  # from examples/curves/sealing_jaw.csv
    assert jaw.n_points == 31 and jaw.closed and max(jaw.set_points) == pytest.approx(1.0)
    assert dev.axis is m.axis("knife")
    # I14 is the print-mark sensor: its edges go to the label synchronisation
    assert dev._i14 is m.sensors["labels"]


@pytest.mark.parametrize(
    "change, text",
    [
        (lambda d: d["device"].update(slave="arm"), "device.slave = 'arm': no such axis (axes: knife)"),
        (lambda d: d["device"].update(master="belt"), "device.master = 'belt': no such master or axis with an encoder"),
        (lambda d: d["device"].update(master="knife"), "device.master = 'knife': axis 'knife' has no [axis.encoder]"),
        (lambda d: d["device"]["parameters"].update(P33=5), "device.parameters: P33 = 5 out of range"),
        (lambda d: d["device"]["parameters"].update(P999=1), "device.parameters: P999 = 1: not a parameter"),
        (lambda d: d["device"].update(startup=["SETC 1", "GOTO 1"]), "device.startup[1] = 'GOTO 1'"),
        (lambda d: d["device"]["inputs"].update(I14="marks"), "device.inputs.I14 = 'marks': no such switch, sensor or io input"),
        (lambda d: d["device"]["outputs"].update(O16="lamp"), "device.outputs.O16 = 'lamp': no such io output"),
        (lambda d: d["device"]["curves"][1].update(csv="curves/none.csv"), "device.curves[1] (curve 2)"),
        (lambda d: d["device"]["curves"][0].pop("points"), "segments need master_period and points"),
        (lambda d: d["device"]["curves"][0].update(label_window=0.5), "device.curves[0].label_window = 0.5"),
        (lambda d: d["device"]["curves"][1].update(number=3), "the next new curve is 2"),
        (lambda d: d["device"].update(colour="red"), "device.colour: unknown key"),
        (lambda d: d["machine"].update(cycle_us=500), "machine.cycle_us = 500: COMPAX works in 1 ms cycles"),
        (lambda d: d["machine"].update(logic_every=2), "machine.logic_every = 2"),
        (lambda d: d.update(job={"steps": [{"axis": "knife", "command": "power", "on": True}]}),
         "job.steps[0].axis = 'knife': the axis is the COMPAX slave"),
    ],
)
def test_config_errors_name_the_key(change, text):
    data = example_data()
    change(data)
    with pytest.raises(ConfigError) as e:
        build(data, EXAMPLE)
    assert any(text in p for p in e.value.problems), e.value.problems


def test_master_scaling_is_derived_or_asked_for():
    assert derive_master_scaling(20.0, preferred_p98=200.0) == (200.0, 1000)
    assert derive_master_scaling(1000.0) == (1.0, 250)  # an axis encoder of 250 lines/mm x4
    assert derive_master_scaling(1e9) is None
    data = small(master="wheel")
    data["material"] = {"speed": 100.0}
    data["master"] = [{"name": "wheel", "kind": "wheel", "wheel": {"lines_per_revolution": 1001, "circumference": 97.0, "multiplier": 1}}]
    with pytest.raises(ConfigError) as e:
        build(data)
    assert any("set P98 and P143" in p for p in e.value.problems)
    data["device"]["parameters"] = {"P98": 388.0, "P143": 1001}  # given: taken as they are
    assert build(data).device.params[143] == 1001


def test_internal_time_base_needs_p30_1():
    data = small(parameters={"P30": 0})
    with pytest.raises(ConfigError, match="P30 = 0 selects the encoder"):
        build(data)


# --------------------------------------------------------------------------- start-up program, I/O


def test_startup_program_waits_for_the_power_stage_then_couples_and_sets_the_outputs():
    m = build(small())
    dev = m.device
    m.scheduler.run_cycle()  # cycle 0: SETC, SETM done; LOOP waits for I12 to power the slave
    assert dev.pc == 2 and dev.op.curve is not None and not dev.op.loop_active
    m.run(0.5)
    assert dev.pc == 3 and dev.op.loop_active and dev.op.state is CamState.SYNC
    assert dev.axis.state is AxisState.SYNCHRONIZED_MOTION
    # internal time base: 100 rev/min of the 360 deg delivery curve = 600 deg/s
    assert dev.op.status(41) == pytest.approx(100.0)
    assert dev.axis.command_velocity == pytest.approx(600.0)
    assert m.io.output("sync") is True and dev.op.output(16)
    assert m.io.output("warn") is True  # O15: tracking error within P79
    s = dev.summary()
    assert s["program"] == {"lines": 3, "next_line": None, "done": True, "errors": []}
    assert s["state"] == "synchronous" and s["curve"] == 1 and s["status"]["S43"] == 1.0
    assert json.dumps(m.summary(m.run(0.001)))  # the whole summary is JSON
    # the io outputs follow O16 off again (they are written in the cycle an output changes)
    dev.op.stop()
    m.run(0.01)
    assert not dev.op.output(16) and m.io.output("sync") is False
    assert m.io.output("warn") is dev.op.output(15)


def test_a_wrong_startup_line_stops_the_program_and_fails_the_run():
    m = build(small(startup=["SETC 4", "LOOP 0"]))
    result = m.run(0.05)
    assert not result.completed
    assert any("start-up line 1 'SETC 4'" in f and "!E17" in f for f in result.faults), result.faults
    assert m.device.summary()["program"]["errors"][0]["line"] == 1
    assert not m.device.op.loop_active


def test_wait_in_the_program_and_inputs_from_io():
    m = build(small(startup=["WAIT 20", "SETC 1", "LOOP 0"], inputs={"I13": "couple", "I16": True}))
    dev = m.device
    m.run(0.010)
    assert dev.op.curve is None
    m.run(0.030)
    assert dev.op.loop_active and dev.op.state is CamState.READY  # I13 = io input "couple" is 0
    m.io.set_input("couple", True)
    m.run(0.010)
    assert dev.op.state is CamState.SYNC


def test_the_manuals_setting_procedure_with_the_label_on_i14_and_i16():
    # §2.13 master related: "Label signal connected to I14 and I16. P31 = "2". "SETC n". ... "SETM x"
    # with x = S50/10 = M_ref. "LOOP n" and "I13="1"": the master starts counting at the first
    # label (latched at its edge) from the reference, so the first label needs no correction
    data = example_data()
    data["device"]["inputs"]["I16"] = "labels"
    data["device"]["parameters"]["P31"] = 2
    data["device"]["startup"] = ["SETC 1", "SETM 75", "LOOP 0"]
    m = build(data, EXAMPLE)
    m.run(0.8)
    assert not m.device.op.chain.counting and m.device.op.chain.s44 == pytest.approx(750.0)
    m.run(1.4)
    labelled = [r for r in m.device.summary()["cycles"] if r["error_before"] is not None]
    assert len(labelled) >= 2
    assert abs(labelled[0]["error_before"]) < 1.0 and abs(labelled[1]["error_before"]) < 6.0


# --------------------------------------------------------------------------- ASCII interface


def _ask(endpoint, line: str) -> bytes:
    return endpoint.feed(line.encode() + b"\r")


def test_ascii_interface_reads_always_writes_only_with_the_operators_enable():
    m = build(small())
    m.run(0.1)
    dev = m.device
    ep = dev.byte_endpoint()
    words = dev.memory.words()
    written = dict(dev.params.written)
    assert _ask(ep, "F6") == b"F0006=0.0000000\r\n>"
    assert _ask(ep, "I5460") == b"I5460=360\r\n>"
    assert _ask(ep, "P35") == b"P035=1.000000\r\n>"
    assert _ask(ep, "S43") == b"S043=1.000\r\n>"
    assert _ask(ep, "S41") == b"S041=100.000\r\n>"
    for line, code in (("F6=0.5", b"!E104"), ("P35=2", b"!E104"), ("VF", b"!E107"), ("RESETF", b"!E107"),
                       ("SETC 1", b"!E107"), ("LOOP 2", b"!E107")):
        reply = _ask(ep, line)
        assert reply.startswith(code + b" ") and b"--allow-writes" in reply and reply.endswith(b"\r\n>"), reply
    assert _ask(ep, "S30") == b"S030=107.000\r\n>"  # the last error, as a host checks a transfer
    assert dev.memory.words() == words and dict(dev.params.written) == written
    assert dev.op.loop_active  # the refused commands did nothing

    dev.network_writes = True  # serve --allow-writes
    for line, code in (("F6=1.5", b"!E103"), ("F9999=0.1", b"!E102"), ("F6=x", b"!E101"), ("B7=1;2", b"!E101"),
                       ("I3=5", b"!E104"), ("P33=7", b"!E103"), ("SETC 9", b"!E17"), ("SETM 50", b"!E107"),
                       ("LOOP 70000", b"!E103"), ("hello", b"!E101")):
        assert _ask(ep, line).startswith(code), line
    assert dev.memory.words() == words and dict(dev.params.written) == written  # errors change nothing
    assert _ask(ep, "F8=0.5") == b"\r\n>"
    assert _ask(ep, "F8") == b"F0008=0.5000000\r\n>"
    assert dev.memory.dirty and _ask(ep, "VF") == b"\r\n>" and not dev.memory.dirty
    assert _ask(ep, "P32=12.5") == b"\r\n>" and _ask(ep, "P32") == b"P032=12.500000\r\n>"
    assert dev.params[32] == 0.0 and _ask(ep, "VP") == b"\r\n>" and dev.params.pending() == {32: "armed"}


def _cycling(m, stop):
    while not stop.is_set():
        m.scheduler.run_cycle()
        time.sleep(0.0002)


def _exchange(sock, data: bytes) -> bytes:
    sock.sendall(data)
    got = b""
    while not got.endswith(b">"):
        chunk = sock.recv(1000)
        if not chunk:
            break
        got += chunk
    return got


def test_ascii_interface_over_tcp_end_to_end():
    m = build(small())
    dev = m.device
    srv = SerialTcpServer(dev.byte_endpoint(), m.commands).start()
    stop = threading.Event()
    th = threading.Thread(target=_cycling, args=(m, stop))
    th.start()
    try:
        with socket.create_connection(srv.address, timeout=5) as c:
            assert _exchange(c, b"F6\r") == b"F0006=0.0000000\r\n>"
            assert _exchange(c, b"F6=0.25\r").startswith(b"!E104 ")
            dev.network_writes = True
            assert _exchange(c, b"F6=0.25\r") == b"\r\n>"
            assert _exchange(c, b"f 6\r\n") == b"F0006=0.2500000\r\n>"  # spaces, lower case, <lf> ignored
            c.sendall(b"S4")  # half a line: answered once the rest arrives
            time.sleep(0.05)
            assert _exchange(c, b"3\r") == b"S043=1.000\r\n>"
    finally:
        stop.set()
        th.join()
        srv.stop()
    assert dev.memory.read("F", 6) == pytest.approx(0.25)


# --------------------------------------------------------------------------- persistence


def test_cam_memory_and_parameters_survive_a_restart(tmp_path):
    data = small(memory_file="state/cam.json", parameter_file="state/params.json")
    source = tmp_path / "m.toml"
    m = build(data, source)
    dev = m.device
    assert dev.persist() == [tmp_path / "state" / "cam.json", tmp_path / "state" / "params.json"]
    dev.network_writes = True
    ep = dev.byte_endpoint()
    # a second curve written over the interface, word by word (manual §25), and a parameter
    lines = ["I0001=2", "I5440=90", "F5439=0", "I5438=3", "I5437=5", "I5436=180", "F5435=0",
             "F10=0", "F12=0.5", "F14=.9999999", "VF", "P32=12.5", "VP"]
    for line in lines:
        assert _ask(ep, line) == b"\r\n>", line
    assert read_curve(dev.memory, 2).master_cycle == 90.0
    files = m.persist()
    assert [f.name for f in files] == ["cam.json", "params.json"]
    again = build(data, source)  # power on: the files are loaded, the configured curves are not
    curve = again.device.curve(2)
    assert curve.master_cycle == 90.0 and curve.slave_cycle == 180.0 and curve.set_points == pytest.approx([0.0, 0.5, 1.0])
    assert again.device.params[32] == 12.5 and again.device.params.pending() == {}
    again.run(0.05)
    assert again.device.op.loop_active
    (tmp_path / "state" / "cam.json").write_text("{}")
    with pytest.raises(ConfigError, match="device.memory_file = 'state/cam.json'"):
        build(data, source)


def test_curves_export_as_csv_and_import_again(tmp_path):
    m = Machine.from_file(EXAMPLE)
    path = m.device.export_curve(2, tmp_path / "jaw.csv")
    back = curve_from_csv(path, 2)
    assert back.master_cycle == 300.0 and back.set_points == pytest.approx(m.device.curve(2).set_points, abs=1e-6)
    assert path.read_text().splitlines()[0] == "master,slave"


def test_startup_state_copy_is_independent():
    # two machines from one file share nothing (each personality owns its memory and parameters)
    a, b = build(example_data(), EXAMPLE), build(copy.deepcopy(example_data()), EXAMPLE)
    a.device.memory.write("F", 6, 0.5)
    assert b.device.memory.read("F", 6) == 0.0


# --------------------------------------------------------------------------- scope channels


def test_compax_channels_come_from_the_trace_channels_hook():
    # Personality.trace_channels(): the machine builds the scope with them (all, or named ones)
    data = small()
    data["trace"] = {"enabled": True, "channels": ["s.command_position", "compax.S44", "compax.O16", "compax.state"]}
    m = build(data)
    assert set(m.device.trace_channels()) >= {"compax.S44", "compax.S45", "compax.S52", "compax.O14",
                                              "compax.O15", "compax.O16", "compax.state"}
    assert list(m.trace.channels)[-3:] == ["compax.S44", "compax.O16", "compax.state"]
    m.run(0.3)
    d = m.trace.data()
    assert d["compax.S44"].max() > 0.0 and d["compax.O16"][-1]
    data["trace"] = {"enabled": True}  # all channels: the compax ones are in from the first sample
    m = build(data)
    assert "compax.S52" in m.trace.channels
    data["device"]["trace"] = False
    m = build(data)
    assert not any(c.startswith("compax.") for c in m.trace.channels)
    data["trace"] = {"enabled": True, "channels": ["compax.S44"]}
    with pytest.raises(ConfigError, match="compax.S44"):
        build(data)


def test_analog_aux_channels_in_the_scope_and_the_summary():
    # P1 (compax.md §2.1 "2 analogue signals within +/- 10V", §7 X22 volt = signed byte · 10 / 128):
    # the curve's analogue aux functions, interpolated over the master position, as compax.A0 / A1
    import dataclasses

    from axisline.devices.compax.curves import write_curve

    data = small()
    data["trace"] = {"enabled": True, "channels": ["compax.S44", "compax.A0", "compax.A1"]}
    m = build(data)
    dev = m.device
    assert dev.summary()["analog"] == {"A0": 0.0, "A1": 0.0}  # no curve selected yet
    curve = dev.curve(1, valid=False)
    assert curve.n_points == 2
    write_curve(dev.memory, dataclasses.replace(curve, aux_digital=[0, 0], aux_analog0=[0, 127], aux_analog1=[-128, 0]))
    dev.memory.vf()
    m.run(0.5)
    d = m.trace.data()
    u = d["compax.S44"] / 1000.0  # the master position, fraction of the cycle
    assert d["compax.A0"] == pytest.approx(u * 127 * 10 / 128, abs=1e-6)
    assert d["compax.A1"] == pytest.approx((1 - u) * -10.0, abs=1e-6)
    s = dev.summary()["analog"]
    u = dev.op.chain.s44 / 1000.0
    assert s["A0"] == pytest.approx(u * 127 * 10 / 128) and s["A1"] == pytest.approx((u - 1) * 10.0)
    assert d["compax.A0"].max() > 5.0 and d["compax.A1"].min() < -5.0
