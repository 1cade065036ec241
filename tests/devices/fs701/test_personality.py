"""The "fs701" personality built from a machine file: configuration, wiring, registers, persistence.

The machines run on the simulated clock (exact and fast); registers are read and written as
the protocol servers do it (between cycles).
"""

from __future__ import annotations

import copy
import tomllib
from pathlib import Path

import pytest

from axisline.config import parse_machine
from axisline.configerrors import ConfigError
from axisline.devices.fs701.cutter import ControlState, CutState
from axisline.devices.fs701.drivecom import ACK, NAK, DrivecomClient, build_read, build_write
from axisline.devices.fs701.paramfile import load_parameter_file
from axisline.devices.fs701.personality import Fs701Personality
from axisline.devices.fs701.modbus_map import encode_words
from axisline.fieldbus.modbus import RegisterRefused
from axisline.machine import Machine
from axisline.motion.axis import AxisState

EXAMPLES = Path(__file__).resolve().parents[3] / "examples"
EXAMPLE = EXAMPLES / "flying_shear.toml"
CUTTING_LENGTH = 0x0000


def example_data(name: str = "flying_shear.toml") -> dict:
    return tomllib.loads((EXAMPLES / name).read_text())


def build(data: dict, source: Path = EXAMPLE) -> Machine:
    return Machine(parse_machine(data, str(source)), source=str(source))


def quick(data: dict) -> dict:
    """No commissioning (an exact drive instead), no trace: construction in milliseconds."""
    d = copy.deepcopy(data)
    d["device"]["commissioning"] = False
    d["axis"][0]["drive"].update(gain_factor=1.0, offset_volts=0.0)
    d["trace"] = {"enabled": False}
    return d


def problems(data: dict, source: Path = EXAMPLE) -> list[str]:
    with pytest.raises(ConfigError) as e:
        build(data, source)
    return e.value.problems


def run_s(m: Machine, seconds: float) -> None:
    m.scheduler.run(int(round(seconds / m.period)))


# ---------------------------------------------------------------------------------- building


def test_the_example_builds_the_fs701_on_its_line():
    m = build(example_data())
    dev = m.device
    assert isinstance(dev, Fs701Personality) and dev.name == "fs701"
    assert set(dev.endpoints) == {"serial-tcp", "modbus"}
    # the parameter file and the [device.parameters] overrides
    assert dev.settings.pulses_line_1000 == 40000 and dev.settings.cutting_length == 1000
    assert dev.params.cutting_length == 1000
    # the FS701's loop drives the carriage through its analogue input
    unit = m.units["carriage"]
    assert unit.controller is not None and unit.controller_volts
    # commissioning found the drive's gain and offset errors (gain_factor 1.046, +21 mV)
    assert dev.commissioning.ok and [s["step"] for s in dev.commissioning.steps] == ["direction", "offset", "gain"]
    assert dev.settings.acc_feed_forward == 0.0  # the FS701's own loop (loop.py L10)
    assert dev.settings.ana_out_gain_2 == pytest.approx(10.0 / 1.046, abs=0.03)
    assert dev.params.ana_out_gain_2 == dev.settings.ana_out_gain_2
    assert dev.settings.ana_out_offset_2 < 0
    assert unit.drive.position == 0.0 and not unit.drive.enabled  # back home after the Adjust program
    assert dev.registers.eeprom.params == dev.params  # the commissioned set is stored
    # the device ticks in LOGIC, before the axes sample their set points
    names = [t.name for t in m.scheduler.tasks]
    assert names.index("device") < names.index("carriage.setpoint") < names.index("carriage.loop")


def test_cycle_by_cycle_the_cutter_follows_the_wired_inputs():
    m = build(quick(example_data()))
    c = m.device.cutter
    run_s(m, 0.01)
    assert c.inputs.control_enable and c.control_state is ControlState.STOP
    assert m.units["carriage"].axis.state is AxisState.SYNCHRONIZED_MOTION
    run_s(m, 0.02)
    assert c.inputs.start_stop and c.control_state is ControlState.AUTOMATIC
    # All Commands = hardware word (In1 Control Enable, In2 Start/Stop)
    assert m.device.registers.status.all_commands & 0b11 == 0b11
    run_s(m, 3.5)
    assert len(m.device.cuts) >= 1 and c.cut_state in tuple(CutState)


# ---------------------------------------------------------------------------------- config errors


def test_device_table_errors_are_named():
    d = example_data()
    d["device"]["colour"] = "red"
    with pytest.raises(ConfigError) as e:
        parse_machine(d, "t.toml")
    assert any(p.startswith("device.colour: unknown key") for p in e.value.problems)
    d = example_data()
    d["device"]["batch"] = -1
    with pytest.raises(ConfigError) as e:
        parse_machine(d, "t.toml")
    assert any(p.startswith("device.batch = -1") and ">= 0" in p for p in e.value.problems)
    d = example_data()
    d["device"]["parameters"]["cuting_length"] = 5
    with pytest.raises(ConfigError) as e:
        parse_machine(d, "t.toml")
    assert any("device.parameters" in p and "'cuting_length'" in p for p in e.value.problems)


@pytest.mark.parametrize(
    "change, expected",
    [
        (lambda d: d["device"].update(carriage="slide"), "device.carriage = 'slide': no such axis"),
        (lambda d: d["axis"][0]["drive"].update(command="digital"), 'command = "analog"'),
        (lambda d: d["axis"][0].pop("encoder"), "needs an [axis.encoder]"),
        (lambda d: d["device"].update(line="roll"), "device.line = 'roll': no such master"),
        (lambda d: d["master"][0]["wheel"].update(circumference=200.0), "pulses_line_1000 = 40000, but the line encoder counts 50000"),
        (lambda d: d["axis"][0]["encoder"].update(multiplier=2), "mode_counter_2 = 2 (x4), but the carriage encoder is evaluated x2"),
        (lambda d: d["device"]["parameters"].update(cutting_length=0), "device.parameters.cutting_length = 0: Cutting Length"),
        (lambda d: d["device"]["parameters"].update(cutting_mode=2), "name the sensor in device.printmark_sensor"),
        (lambda d: d["device"].update(printmark_sensor="eye"), "device.printmark_sensor = 'eye': no such print-mark sensor"),
        (lambda d: d["device"].update(parameter_file="missing.toml"), "device.parameter_file = 'missing.toml': cannot read"),
        (lambda d: d["device"]["inputs"].update(jog_sideways=True), "device.inputs.jog_sideways: no such FS701 input function"),
        (lambda d: d["device"]["inputs"].update(clear_error="reset_button"), "device.inputs.clear_error = 'reset_button': no such sensor or io input"),
        (lambda d: d["device"]["inputs"].update(jog_forward="job"), "the batch job switches only control_enable and start_stop"),
        (lambda d: d["device"]["inputs"].update(start_stop=True), "device.batch: a batch needs the job to switch Start/Stop"),
        (lambda d: d["device"]["outputs"].update(ready_to_cut="lamp") if "outputs" in d["device"] else d["device"].update(outputs={"ready_to_cut": "lamp"}),
         "device.outputs.ready_to_cut = 'lamp': no such io output"),
        (lambda d: d["machine"].update(logic_every=4), "machine.logic_every = 4"),
        (lambda d: d.update(job={"steps": [{"axis": "carriage", "command": "power", "on": True}]}), "the carriage is driven by the FS701"),
    ],
)
def test_configuration_errors_name_the_key(change, expected):
    d = quick(example_data())
    change(d)
    found = problems(d)
    assert any(expected in p for p in found), found


def test_several_problems_are_reported_together():
    d = quick(example_data())
    d["device"]["carriage"] = "slide"
    d["device"]["line"] = "roll"
    found = problems(d)
    assert any("device.carriage" in p for p in found) and any("device.line" in p for p in found)


# ---------------------------------------------------------------------------------- registers


def test_registers_are_live_and_writes_reach_the_cutter():
    m = build(quick(example_data()))
    dev = m.device
    ep = dev.byte_endpoint()
    client = DrivecomClient(ep.feed)
    assert client.read(CUTTING_LENGTH) == 1000
    run_s(m, 5.0)  # the line runs at 60 m/min, cuts are made
    assert client.read(0x0802) == pytest.approx(60000, abs=1600)  # #2 Line Speed, LU/min
    assert client.read(0x0B04) & 0b1  # Output Status: Ready
    assert client.read(0x081D) == int(ControlState.AUTOMATIC)  # #29 Control State
    assert client.read(0x0170) == dev.cutter.batch_counter >= 2  # Batch Counter
    # writes: refused without the operator's enable, accepted with it
    assert ep.feed(build_write(11, CUTTING_LENGTH, 800)) == bytes([NAK])
    assert dev.params.cutting_length == 1000
    dev.network_writes = True
    client.write(CUTTING_LENGTH, 800)
    m.scheduler.run_cycle()
    assert dev.settings.cutting_length == 800  # acts from the next cut on
    # a scaling parameter waits for Control Enable OFF (D3)
    client.write(0x0100, 40100)
    m.scheduler.run_cycle()
    assert dev.params.pulses_line_1000 == 40100 and dev.settings.pulses_line_1000 == 40000


def test_serial_commands_drive_the_cutter_like_the_terminals():
    d = quick(example_data())
    d["device"]["batch"] = 0
    d["device"]["inputs"] = {"control_enable": True, "cut_completed": "shear"}
    m = build(d)
    dev = m.device
    dev.network_writes = True
    client = DrivecomClient(dev.byte_endpoint().feed)
    run_s(m, 0.05)
    assert dev.cutter.control_state is ControlState.STOP
    client.write(0x0901, 1)  # Start / Stop over the serial link
    run_s(m, 4.0)
    assert dev.cutter.control_state is ControlState.AUTOMATIC and len(dev.cuts) >= 1
    assert client.read(0x0B01) == 0b10 and client.read(0x0B03) & 0b11 == 0b11
    client.write(0x0901, 0)
    run_s(m, 0.02)
    assert dev.cutter.control_state is ControlState.STOP
    assert dev.finished is None  # no batch: the run decides its own end


def test_modbus_image_reads_and_refuses():
    m = build(quick(example_data()))
    ep = m.device.register_endpoint()
    assert ep.read_registers("holding", 2 * CUTTING_LENGTH, 2) == encode_words(1000, 2)
    with pytest.raises(RegisterRefused):
        ep.read_registers("holding", 0x0400, 2)  # 0x0200 is no register
    with pytest.raises(RegisterRefused):
        ep.write_registers(0, encode_words(900, 2))  # writes need the enable
    m.device.network_writes = True
    ep.write_registers(0, encode_words(900, 2))
    with pytest.raises(RegisterRefused):
        ep.write_registers(0, encode_words(0, 2))  # out of range
    m.scheduler.run_cycle()
    assert m.device.settings.cutting_length == 900


def test_network_written_counters_and_outputs():
    d = quick(example_data())
    d["io"] = {"outputs": ["rtc_lamp", "out3"]}
    d["device"]["outputs"] = {"ready_to_cut": "rtc_lamp", "Out3": "out3"}  # Out3 = Home (factory map)
    m = build(d)
    dev = m.device
    run_s(m, 0.05)
    assert m.io.output("out3") and not m.io.output("rtc_lamp")
    seen = []
    for _ in range(4000):
        m.scheduler.run_cycle()
        seen.append(m.io.output("rtc_lamp"))
    assert any(seen) and dev.cutter.batch_counter >= 1
    dev.network_writes = True
    DrivecomClient(dev.byte_endpoint().feed).write(0x0170, 100)
    m.scheduler.run_cycle()
    assert dev.cutter.batch_counter == 100


def test_drivecom_naks_a_bad_bcc_and_a_malformed_telegram():
    m = build(quick(example_data()))
    ep = m.device.byte_endpoint()
    m.device.network_writes = True
    tel = bytearray(build_write(11, CUTTING_LENGTH, 700))
    tel[-1] ^= 0x01
    assert ep.feed(bytes(tel)) == bytes([NAK])
    assert ep.feed(b"\x041100Z0\x05") == bytes([NAK])  # a non-hex code character
    assert ep.feed(build_read(11, 0x01A0)) == bytes([NAK])  # unknown register
    assert ep.feed(build_write(11, 0x0802, 5)) == bytes([NAK])  # process values are read only
    assert m.device.params.cutting_length == 1000
    assert ep.feed(build_write(11, CUTTING_LENGTH, 700)) == bytes([ACK])


# ---------------------------------------------------------------------------------- persistence


def test_persist_saves_the_parameter_set_atomically(tmp_path):
    d = quick(example_data())
    d["device"]["save_parameters"] = str(tmp_path / "saved.toml")
    d["device"]["batch"] = 0
    m = build(d)
    run_s(m, 4.0)
    m.device.network_writes = True
    DrivecomClient(m.device.byte_endpoint().feed).write(0x0105, "1.25")  # +/- Sync Rate 1.25 %
    run_s(m, 0.01)
    files = m.persist()
    assert files == [tmp_path / "saved.toml"]
    saved = load_parameter_file(files[0])
    assert saved.params.sync_rate == 1.25 and saved.params.cutting_length == 1000
    assert saved.params.batch_counter == m.device.cutter.batch_counter >= 1
    assert saved.io == m.device.registers.io
    # and the saved set loads into a new machine
    d2 = quick(example_data())
    d2["device"]["parameter_file"] = str(files[0])
    d2["device"]["parameters"] = {}
    assert build(d2).device.settings.sync_rate == 1.25


def test_store_to_eeprom_command_writes_the_file(tmp_path):
    d = quick(example_data())
    d["device"]["save_parameters"] = "eeprom.toml"
    d["device"]["parameter_file"] = str(EXAMPLES / "params" / "fs701_params.toml")
    m = build(d, tmp_path / "machine.toml")  # save_parameters is relative to the machine file
    dev = m.device
    dev.network_writes = True
    c = DrivecomClient(dev.byte_endpoint().feed)
    c.write(0x0000, 1200)
    assert not (tmp_path / "eeprom.toml").exists()
    c.write(0x091D, 1)  # Store to EEProm (bit 29)
    assert load_parameter_file(tmp_path / "eeprom.toml").params.cutting_length == 1200


def test_no_save_file_no_persistence():
    m = build(quick(example_data()))
    assert m.persist() == []


# ---------------------------------------------------------------------------------- virtual line


def test_virtual_master_line_measures_on_the_master():
    d = quick(example_data())
    del d["master"]
    d["device"]["line"] = "virtual"
    d["device"]["batch"] = 3
    d["device"]["inputs"] = {"control_enable": "job", "start_stop": "job", "cut_completed": "shear", "run_virt_master": True}
    d["device"]["parameters"] = {"cutting_length": 500, "virtual_line_speed": 30000}
    m = build(d)
    r = m.run(20.0)
    dev = m.device
    assert r.completed and dev.finished and dev.measured_on == "virtual master"
    pieces = [c for c in dev.cuts if c.actual_length is not None]
    assert len(dev.cuts) == 3 and len(pieces) == 2
    assert all(abs(p.error_counts) <= 1.0 for p in pieces)


def test_the_device_table_is_documented():
    from axisline.devices.fs701.config import AdjustConfig
    from axisline.devices.fs701.personality import ShearConfig
    from axisline.devices.fs701.report import config_table_markdown

    doc = (Path(__file__).resolve().parents[3] / "docs" / "fs701.md").read_text()
    assert config_table_markdown() in doc and config_table_markdown(ShearConfig) in doc
    assert config_table_markdown(AdjustConfig) in doc


def test_a_feed_roll_encoder_as_the_line():
    """Encoder 1 on the feed roll's motor (a master of kind axis_encoder): pieces on the roll's surface."""
    d = quick(example_data())
    del d["master"]
    d["axis"].append({
        "name": "feed", "unit": "mm", "counts_per_unit": 40.0, "v_max": 2000.0, "a_max": 1000.0,
        "following_error_limit": 50.0, "drive": {"type": "servo", "time_constant": 0.002},
        "encoder": {"lines_per_unit": 10.0, "multiplier": 4},
    })
    d["master"] = [{"name": "roll", "kind": "axis_encoder", "axis": "feed"}]
    d["device"].update(line="roll", batch=4)
    d["job"] = {"steps": [
        {"axis": "feed", "command": "power", "on": True},
        {"axis": "feed", "command": "move_velocity", "velocity": 800.0, "acceleration": 400.0},
        {"dwell": 5.0},
        {"axis": "feed", "command": "halt", "deceleration": 400.0},
    ]}
    m = build(d)
    r = m.run(20.0)
    dev = m.device
    assert r.completed and dev.finished and dev.measured_on.startswith("feed axis 'feed'")
    pieces = [c for c in dev.cuts if c.actual_length is not None]
    assert len(dev.cuts) == 4 and len(pieces) == 3
    assert all(abs(p.error_counts) <= 2.0 for p in pieces), pieces
