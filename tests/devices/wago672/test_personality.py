"""The "wago672" personality built from a machine file: modules, wiring, cycle order, checks.

The registers are written as the Modbus server writes them (between cycles) and the machine
runs on its simulated clock, so these tests are exact and fast.
"""

from __future__ import annotations

import copy
import tomllib
from pathlib import Path

import pytest

from axisline.config import parse_machine
from axisline.configerrors import ConfigError
from axisline.devices import base
from axisline.devices.wago672.coupler import Coupler, pack, unpack
from axisline.devices.wago672.image import C1, S1, S2, S3, InputImage, OutputImage, PositioningSetpoints
from axisline.devices.wago672.mailbox import Mailbox
from axisline.devices.wago672.personality import Wago672Personality
from axisline.kernel import Stage
from axisline.machine import Machine
from axisline.motion.axis import AxisState

EXAMPLE = Path(__file__).resolve().parents[3] / "examples" / "wago_stepper.toml"
ON = C1.Enable | C1.Stop2_N
K = 2560.0  # microsteps per mm in the example


def example_data() -> dict:
    """The example without its [[device.plc]] script: these tests are the PLC."""
    data = tomllib.loads(EXAMPLE.read_text())
    data["device"].pop("plc", None)
    return data


def build(data: dict) -> Machine:
    return Machine(parse_machine(data, "t.toml"), source="t.toml")


def axis(name: str, **kw) -> dict:
    a = {
        "name": name, "unit": "mm", "counts_per_unit": K, "v_max": 25.0, "a_max": 400.0, "following_error_limit": 1.0,
        "drive": {"type": "stepper", "steps_per_unit": 40.0, "microsteps": 64},
    }
    a.update(kw)
    return a


def two_axis_data() -> dict:
    return {
        "machine": {"cycle_us": 1000, "personality": "wago672"},
        "axis": [axis("x"), axis("y")],
        "io": {"inputs": ["jog_plus"], "outputs": ["y_in_position"]},
        "device": {
            "watchdog_ms": 50,
            "modules": [
                {"axis": "x", "inputs": {"Input1": True}},
                {"axis": "y", "inputs": {"Input1": True, "Input3": "jog_plus"}, "outputs": {"Output1": "y_in_position"}},
            ],
        },
        "trace": {"enabled": False},
    }


def write(m: Machine, module: int, image: OutputImage) -> None:
    m.device.coupler.write_registers(6 * module, pack(image.to_bytes()))


def inputs(m: Machine, module: int = 0) -> InputImage:
    return InputImage.from_bytes(unpack(m.device.coupler.read_registers("input", 6 * module, 6)))


def run_until(m: Machine, predicate, limit: int = 5000, feed: tuple[int, OutputImage] | None = None) -> None:
    """Cycles until predicate(); `feed` is re-written every 10 ms (a PLC feeding the watchdog)."""
    for n in range(limit):
        if feed is not None and n % 10 == 0:
            write(m, *feed)
        m.scheduler.run_cycle()
        if predicate():
            return
    raise AssertionError(f"not reached within {limit} cycles: {inputs(m)}")


def start_move(m: Machine, module: int, target: int, velocity: int = 25000, acceleration: int = 2000) -> OutputImage:
    write(m, module, OutputImage(c1=ON))
    m.scheduler.run(2)
    write(m, module, OutputImage(c1=ON | C1.M_Positioning))
    m.scheduler.run(2)
    assert inputs(m, module).s1 == ON | C1.M_Positioning
    image = OutputImage(c1=ON | C1.M_Positioning | C1.Start, data=PositioningSetpoints(velocity, acceleration, target).encode())
    write(m, module, image)
    m.scheduler.run(1)
    return image


# ---------------------------------------------------------------- building


def test_registered_under_wago672_by_importing_base():
    assert base.PERSONALITIES["wago672"] == "axisline.devices.wago672.personality:Wago672Personality"
    assert base.load("wago672") is Wago672Personality


def test_example_machine_file_builds_the_personality():
    m = build(example_data())
    dev = m.device
    assert isinstance(dev, Wago672Personality)
    assert dev.name == "wago672" and dev.endpoints == ("modbus",)
    coupler = dev.register_endpoint()
    assert isinstance(coupler, Coupler) and coupler is dev.coupler
    assert coupler.watchdog_ms == 100 and coupler.size == 6
    assert dev.device(0).axis is m.axis("x")
    assert dev.device(0).config["SetupSpeed"] == 20000  # the [device.modules.config] value
    assert dev.device(0).config.factory_bytes() == dev.device(0).config.to_bytes()  # ... is the FACTORY_DEFAULT
    assert isinstance(dev.device(0).mailbox, Mailbox)  # mailbox, tables, run programs are plugged in
    assert dev.network_writes is False and coupler.network_writes is False
    dev.network_writes = True
    assert coupler.network_writes is True  # the coupler reads the operator's enable
    m.scheduler.run(3)
    st = inputs(m)
    assert st.s3 & S3.Input1  # Input1 (Stop1_N) wired high: a ready machine
    assert not st.s3 & (S3.Input2 | S3.Input5 | S3.Input6)  # at 0 mm: off the cam, between the limits
    assert dev.persist() == []
    s = m.summary(m.run(0.002))["device"]
    assert s["coupler"]["watchdog_ms"] == 100 and s["coupler"]["watchdog_status"] == "not started"
    assert s["modules"][0]["axis"] == "x" and s["modules"][0]["mode"] == "Idle" and s["modules"][0]["ready"] is False


def test_the_module_ticks_in_logic_before_the_axis_samples_its_set_point():
    m = build(example_data())
    order = [t.name for t in m.scheduler.tasks]
    device = next(t for t in m.scheduler.tasks if t.name == "device")
    assert device.stage is Stage.LOGIC and device.every == 1
    assert order.index("device") < order.index("x.setpoint")
    image = start_move(m, 0, 12800)
    dev, ax = m.device.device(0), m.axis("x")
    for n in range(300):
        if n % 10 == 0:
            write(m, 0, image)
        m.scheduler.run_cycle()
        # the set point the axis took in this cycle is the module's set point of this cycle
        assert ax.command_position * K == pytest.approx(dev.position_steps, abs=1e-6)


def test_a_move_through_the_registers_moves_the_plant():
    m = build(example_data())
    image = start_move(m, 0, 25600)  # 10 mm
    run_until(m, lambda: inputs(m).s2 & S2.On_Target, feed=(0, image))
    st = inputs(m)
    assert st.positioning().position == 25600 and not st.s2 & S2.Busy
    m.scheduler.run(3)
    assert m.units["x"].drive.position == pytest.approx(10.0)
    assert m.axis("x").state is AxisState.STANDSTILL


def test_switches_and_io_inputs_are_wired_to_the_module_inputs():
    data = example_data()
    data["axis"][0]["drive"]["position_microsteps"] = int(-17.5 * K)  # on the reference cam
    m = build(data)
    m.scheduler.run(3)
    assert inputs(m).s3 & S3.Input2
    data["axis"][0]["drive"]["position_microsteps"] = int(-30 * K)  # beyond the negative limit switch
    m = build(data)
    m.scheduler.run(3)
    assert inputs(m).s3 & S3.Input6 and not inputs(m).s3 & S3.Input2

    m = build(two_axis_data())
    m.scheduler.run(2)
    assert not inputs(m, 1).s3 & S3.Input3
    m.io.set_input("jog_plus", True)  # the jog button, an [io] input wired to Input3 (Jog_Pos)
    write(m, 1, OutputImage(c1=ON | C1.M_Jog))
    m.scheduler.run(5)
    assert inputs(m, 1).s3 & S3.Input3 and inputs(m, 1).s1 & S1.M_Jog_ACK
    run_until(m, lambda: m.axis("y").command_position > 1.0, feed=(1, OutputImage(c1=ON | C1.M_Jog)))
    assert m.axis("x").command_position == 0.0


def test_several_modules_on_one_coupler_and_a_digital_output():
    m = build(two_axis_data())
    assert m.device.coupler.size == 12
    image = start_move(m, 1, -5120)  # module 1: registers 6..11, axis y
    assert not inputs(m, 0).s1  # module 0 untouched
    run_until(m, lambda: inputs(m, 1).s2 & S2.On_Target, feed=(1, image))
    m.scheduler.run(2)
    assert m.units["y"].drive.position == pytest.approx(-2.0)
    assert m.units["x"].drive.position == 0.0
    assert m.io.output("y_in_position") is True  # DO1 = On_Target, wired to an io output
    summary = m.device.summary()
    assert [mod["axis"] for mod in summary["modules"]] == ["x", "y"]
    assert summary["modules"][1]["on_target"] is True and summary["modules"][1]["position"] == -5120


def test_watchdog_in_the_machine_stops_the_axis_with_its_ramp():
    m = build(two_axis_data())
    image = start_move(m, 0, 2_000_000)
    run_until(m, lambda: inputs(m).s2 & S2.On_Speed, feed=(0, image))
    run_until(m, lambda: m.device.coupler.watchdog_expired, limit=100)
    p0, v0 = m.units["x"].drive.position, m.axis("x").command_velocity
    run_until(m, lambda: m.units["x"].drive.velocity == 0.0, limit=1000)
    m.scheduler.run(3)
    stop_fast = 30000 * 1000 / 40 / K  # mm/s^2
    assert m.units["x"].drive.position - p0 == pytest.approx(v0 * v0 / (2 * stop_fast), rel=0.1)
    assert m.axis("x").state is AxisState.DISABLED and inputs(m).s1 == 0
    assert m.summary(m.run(0.001))["device"]["coupler"]["watchdog_expiries"] == 1


# ---------------------------------------------------------------- machine-file checks


def _bad(change) -> list[str]:
    data = copy.deepcopy(two_axis_data())
    change(data)
    with pytest.raises(ConfigError) as e:
        build(data)
    return e.value.problems


@pytest.mark.parametrize(
    ("change", "expected"),
    [
        (lambda d: d["device"]["modules"][0].update(axis="z"), "device.modules[0].axis = 'z': no such axis"),
        (lambda d: d["device"]["modules"][1].update(axis="x"), "device.modules[1].axis = 'x': already driven by device.modules[0]"),
        (lambda d: d["axis"][0].update(drive={"type": "servo"}), "the 750-672 drives a stepper"),
        (lambda d: d["axis"][0].update(counts_per_unit=1000.0), "counts_per_unit = 1000: the 750-672 counts microsteps"),
        (lambda d: d["axis"][0]["drive"].update(microsteps=16), "drive.microsteps = 16"),
        (lambda d: d["machine"].update(cycle_us=500), "machine.cycle_us = 500: the 750-672 runs a 1 ms TICK"),
        (lambda d: d["machine"].update(logic_every=2), "machine.logic_every = 2"),
        (lambda d: d["device"]["modules"][0]["inputs"].update(Input2="x.ref"), "device.modules[0].inputs.Input2 = 'x.ref': no such switch"),
        (lambda d: d["device"]["modules"][0].update(outputs={"Output2": "lamp"}), "device.modules[0].outputs.Output2 = 'lamp': no such io output"),
        (lambda d: d["device"]["modules"][0].update(config={"SetupSpeeed": 100}), "device.modules[0].config: no configuration variable named 'SetupSpeeed'"),
        (lambda d: d["device"]["modules"][0].update(config={"SetupSpeed": 30000}), "device.modules[0].config:"),
        (lambda d: d.update(job={"steps": [{"axis": "x", "command": "power", "on": True}]}), "job.steps[0].axis = 'x': the axis is driven by the 750-672"),
    ],
)
def test_machine_file_mistakes_are_named(change, expected):
    problems = _bad(change)
    assert any(expected in p for p in problems), problems


@pytest.mark.parametrize(
    ("device", "expected"),
    [
        ({"modules": []}, "device.modules"),
        ({"modules": [{"axis": "x", "inputs": {"Input7": True}}]}, "device.modules[0].inputs.Input7"),
        ({"modules": [{"axis": "x"}], "watchdog_ms": 5}, "device.watchdog_ms = 5"),
        ({"modules": [{"axis": "x"}], "colour": "red"}, "device.colour: unknown key"),
    ],
)
def test_device_table_is_validated(device, expected):
    data = two_axis_data()
    data["device"] = device
    with pytest.raises(ConfigError) as e:
        parse_machine(data, "t.toml")
    assert any(expected in p for p in e.value.problems), e.value.problems


def test_an_unwired_input1_keeps_the_stop_circuit_open():
    data = two_axis_data()
    data["device"]["modules"][0]["inputs"] = {}
    m = build(data)
    write(m, 0, OutputImage(c1=ON))
    m.scheduler.run(3)
    st = inputs(m)
    assert st.s1 & S1.Ready and not st.s1 & S1.Stop_N_ACK  # Stop1_N = 0: the axis cannot start
    assert not st.s3 & S3.Input1


def test_an_unreadable_eeprom_image_is_named(tmp_path):
    bad = tmp_path / "x.eeprom.json"
    bad.write_text("{ not json")
    data = two_axis_data()
    data["device"]["modules"][0]["eeprom"] = str(bad)
    with pytest.raises(ConfigError) as e:
        build(data)
    assert any(p.startswith("device.modules[0].eeprom = ") and "cannot be read" in p for p in e.value.problems), e.value.problems


def test_eeprom_path_is_relative_to_the_machine_file(tmp_path):
    data = two_axis_data()
    data["device"]["modules"][1]["eeprom"] = "y.eeprom.json"
    m = Machine(parse_machine(data, str(tmp_path / "m.toml")), source=str(tmp_path / "m.toml"))
    tables = m.device.modules[1].mailbox.tables
    assert tables.path == tmp_path / "y.eeprom.json"
    assert m.persist() == []  # nothing stored yet: no file
