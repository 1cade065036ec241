"""The PDO mapping comes from the EDS: written to the drive at start, checked for what CSP needs."""

from __future__ import annotations

from pathlib import Path

import pytest

from axisline.configerrors import ConfigError
from axisline.drives.config import GENERIC_EDS
from axisline.machine import Machine
from axisline.motion.axis import AxisState

from .conftest import absent, axis_table, run_until, simulated


def _entries(pdo_map) -> list[int]:
    return [v.index for v in pdo_map.map]


def test_the_generic_eds_mapping_on_the_controller_and_on_the_drive(machines, channel):
    m = machines(axis_table("x", channel, 5))
    node = m.units["x"].drive.node
    rpdo1, rpdo2, tpdo1, tpdo2 = node.rpdo.map[1], node.rpdo.map[2], node.tpdo.map[1], node.tpdo.map[2]
    assert (rpdo1.cob_id, rpdo1.trans_type, _entries(rpdo1)) == (0x205, 1, [0x6040, 0x607A, 0x6060])
    assert (rpdo2.cob_id, rpdo2.trans_type, _entries(rpdo2)) == (0x305, 1, [0x60B1, 0x60FF])
    assert (tpdo1.cob_id, tpdo1.trans_type, _entries(tpdo1)) == (0x185, 1, [0x6041, 0x6064, 0x6061])
    assert (tpdo2.cob_id, tpdo2.trans_type, _entries(tpdo2)) == (0x285, 1, [0x60F4, 0x606C])
    # the drive holds the same mapping (written by SDO at start), as it reads it for itself
    sim = simulated(m, "x").node
    assert [_entries(sim.tpdo.map[1]), _entries(sim.tpdo.map[2])] == [[0x6041, 0x6064, 0x6061], [0x60F4, 0x606C]]
    assert [_entries(sim.rpdo.map[1]), _entries(sim.rpdo.map[2])] == [[0x6040, 0x607A, 0x6060], [0x60B1, 0x60FF]]
    assert sim.sdo[0x1006].raw == 1000  # the SYNC period, us
    assert sim.sdo[0x1017].raw == 100  # its heartbeat
    assert sim.sdo[0x1016][1].raw == (127 << 16) | 500  # it watches axisline's heartbeat


def _eds_with(tmp_path: Path, replace: dict[str, str]) -> Path:
    text = GENERIC_EDS.read_text()
    for old, new in replace.items():
        assert old in text
        text = text.replace(old, new)
    p = tmp_path / "drive.eds"
    p.write_text(text)
    return p


def test_a_different_mapping_in_the_eds_is_the_one_used(machines, channel, tmp_path):
    """Position first, statusword second in TPDO1: both sides follow the EDS, the values stay right."""
    eds = _eds_with(tmp_path, {
        "[1A00sub1]\nParameterName=Mapped object 1\nObjectType=0x7\nDataType=0x0007\nAccessType=rw\nDefaultValue=0x60410010":
        "[1A00sub1]\nParameterName=Mapped object 1\nObjectType=0x7\nDataType=0x0007\nAccessType=rw\nDefaultValue=0x60640020",
        "[1A00sub2]\nParameterName=Mapped object 2\nObjectType=0x7\nDataType=0x0007\nAccessType=rw\nDefaultValue=0x60640020":
        "[1A00sub2]\nParameterName=Mapped object 2\nObjectType=0x7\nDataType=0x0007\nAccessType=rw\nDefaultValue=0x60410010",
    })
    m = machines(axis_table("x", channel, 6, eds=str(eds)))
    drive = m.units["x"].drive
    assert _entries(drive.node.tpdo.map[1]) == [0x6064, 0x6041, 0x6061]
    m.submit("x", "power", on=True)
    m.submit("x", "move_absolute", position=12.5)
    assert run_until(m, lambda: m.axis("x").state is AxisState.STANDSTILL and abs(drive.position - 12.5) < 0.002)
    assert drive.state == "OPERATION ENABLED"
    assert drive.counts == simulated(m, "x").counts


def test_an_eds_without_the_position_in_a_tpdo_is_refused(machines, channel, tmp_path):
    eds = _eds_with(tmp_path, {
        "[1A00sub2]\nParameterName=Mapped object 2\nObjectType=0x7\nDataType=0x0007\nAccessType=rw\nDefaultValue=0x60640020":
        "[1A00sub2]\nParameterName=Mapped object 2\nObjectType=0x7\nDataType=0x0007\nAccessType=rw\nDefaultValue=0x606C0020",
    })
    with pytest.raises(ConfigError) as e:
        machines(axis_table("x", channel, 7, eds=str(eds)))
    assert "0x6064 (position actual value) is in no TPDO sent on SYNC" in str(e.value)


def test_a_missing_eds_file_is_named(machines, channel, tmp_path):
    with pytest.raises(ConfigError) as e:
        machines(axis_table("x", channel, 7, eds=str(tmp_path / "nope.eds")))
    assert "drive.eds" in str(e.value) and "no such file" in str(e.value)


def test_a_file_that_is_no_eds_is_named(machines, channel, tmp_path):
    bad = tmp_path / "bad.eds"
    bad.write_text("[1000]\nthis is not = an EDS\n")
    with pytest.raises(ConfigError) as e:
        Machine(absent(axis_table("x", channel, 7, eds=str(bad))))
    assert "drive.eds" in str(e.value)
