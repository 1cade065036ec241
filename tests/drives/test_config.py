"""[axis.drive] type = "cia402" in the machine file: checked like every other table."""

from __future__ import annotations

from pathlib import Path

import pytest

from axisline.config import load_machine_file, parse_machine
from axisline.configerrors import ConfigError

from .conftest import axis_table

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def _problems(**drive) -> str:
    table = axis_table("x", "c", 1)
    table["drive"].update(drive)
    with pytest.raises(ConfigError) as e:
        parse_machine({"axis": [table]})
    return "\n".join(e.value.problems)


def test_the_example_loads_and_names_a_cia402_drive():
    config = load_machine_file(EXAMPLES / "positioning_cia402.toml")
    drive = config.axis[0].drive
    assert (drive.type, drive.interface, drive.node_id, drive.mode) == ("cia402", "virtual", 1, "csp")
    assert drive.simulated is not None and drive.simulated.time_constant == 0.002


def test_bitrate_must_be_a_canopen_rate():
    text = _problems(bitrate=123_456)
    assert "bitrate" in text and "123456" in text and "1000000" in text


def test_node_id_range():
    text = _problems(node_id=128)
    assert "node_id" in text and "127" in text


def test_a_simulated_drive_is_for_the_virtual_bus_only():
    text = _problems(interface="socketcan", channel="can0")
    assert "simulated" in text and "virtual" in text


def test_heartbeat_timeout_exceeds_the_heartbeat():
    text = _problems(heartbeat_ms=200, heartbeat_timeout_ms=150)
    assert "heartbeat_timeout_ms = 150" in text and "heartbeat_ms = 200" in text


def test_the_controller_needs_its_own_node_id():
    assert "controller_id = 1" in _problems(controller_id=1)


def test_unknown_keys_and_modes_are_refused():
    assert "mode" in _problems(mode="pp")
    assert "kp" in _problems(kp=3)


def test_the_virtual_bus_needs_the_simulated_drive():
    """python-can's virtual bus is in-process: a file naming it without a simulated drive is refused."""
    table = axis_table("x", "c", 1)
    del table["drive"]["simulated"]
    with pytest.raises(ConfigError) as e:
        parse_machine({"axis": [table]})
    assert "virtual" in str(e.value) and "[axis.drive.simulated]" in str(e.value)


def test_a_device_loop_or_turned_directions_are_refused_on_a_cia402_axis(machines, channel):
    """A drive in CSP closes its own loop: a CLM/FS701 +-10 V loop or a turned polarity would be
    silently ignored, so the machine refuses them with the reason."""
    from .conftest import axis_table

    m = machines(axis_table("x", channel, 1))
    with pytest.raises(ValueError, match="closes its own position loop"):
        m.drive_by("x", lambda actual, velocity: 0.0)
    with pytest.raises(ValueError, match="0x607E"):
        m.set_directions("x", output=-1)
    m.set_directions("x")  # the default wiring is fine
