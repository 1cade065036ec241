"""Homing by the drive at start (homing_method), and by axisline (the axis' home step)."""

from __future__ import annotations

import pytest

from axisline.configerrors import ConfigError
from axisline.motion.axis import AxisState
from axisline.motion.homing import DirectHoming

from .conftest import axis_table, run_until, simulated


def _table(channel: str, node_id: int, **drive) -> dict:
    table = axis_table("x", channel, node_id, **drive)
    table["drive"]["simulated"]["position"] = 12.0  # the motor stands at 12 mm of its encoder
    return table


def test_the_drive_homes_at_start_and_the_axis_runs_in_its_frame(machines, channel):
    m = machines(_table(channel, 1, homing_method=35, home_offset=100.0))
    drive, axis, sim = m.units["x"].drive, m.axis("x"), simulated(m, "x")
    assert drive.position == pytest.approx(100.0)  # here is home = 100 mm
    assert sim.mode == 8 and drive.state == "READY TO SWITCH ON"  # back in CSP, disabled
    m.submit("x", "power", on=True)
    m.submit("x", "move_absolute", position=105.0)
    assert run_until(m, lambda: axis.state is AxisState.STANDSTILL and abs(drive.position - 105.0) < 0.002)
    assert sim.servo.position == pytest.approx(17.0, abs=0.005)  # the motor moved the 5 mm


def test_a_homing_method_the_drive_fails_is_a_clear_error(machines, channel):
    with pytest.raises(ConfigError) as e:
        machines(_table(channel, 2, homing_method=19))  # a home-switch method: not simulated
    text = str(e.value)
    assert "drive node 2" in text and "homing by the drive, method 19" in text and "homing error" in text


def test_homing_by_axisline_keeps_the_drive_frame(machines, channel):
    m = machines(_table(channel, 3))
    drive, axis = m.units["x"].drive, m.axis("x")
    assert drive.position == pytest.approx(12.0)
    m.submit("x", "power", on=True)
    m.scheduler.run_cycle()
    handle = axis.home(DirectHoming(0.0))
    assert run_until(m, lambda: handle.done, cycles=50)
    assert axis.position == pytest.approx(0.0, abs=0.001)
    m.submit("x", "move_absolute", position=3.0)
    assert run_until(m, lambda: axis.state is AxisState.STANDSTILL and abs(axis.actual_position - 3.0) < 0.002)
    assert drive.position == pytest.approx(15.0, abs=0.002)  # the drive still counts from its own zero
