"""The CiA 402 state machine follows the axis' power and reset (issue 20); PV for jog."""

from __future__ import annotations

import pytest

from axisline.drives.cia402 import CSP, PV, command_of, state_of, statusword_of
from axisline.motion.axis import AxisState

from .conftest import axis_table, run_until, simulated, wait_for


@pytest.mark.parametrize(
    "state",
    ["SWITCH ON DISABLED", "READY TO SWITCH ON", "SWITCHED ON", "OPERATION ENABLED", "QUICK STOP ACTIVE", "FAULT"],
)
def test_statusword_round_trip(state):
    assert state_of(statusword_of(state)) == state


@pytest.mark.parametrize(
    "controlword, command",
    [(0x0000, "disable voltage"), (0x0002, "quick stop"), (0x0006, "shutdown"), (0x0007, "switch on"),
     (0x000F, "enable operation"), (0x008F, "enable operation"), (0x000B, "quick stop")],
)
def test_controlword_commands(controlword, command):
    """CiA 402 device control commands (bits 0..3; bit 2 quick stop is active low)."""
    assert command_of(controlword) == command


def test_start_brings_the_drive_to_ready_to_switch_on(machines, channel):
    m = machines(axis_table("x", channel, 1))
    drive = m.units["x"].drive
    assert drive.state == "READY TO SWITCH ON"
    assert not drive.enabled
    assert simulated(m, "x").node.nmt.state == "OPERATIONAL"


def test_power_on_enables_in_the_same_cycle_and_power_off_shuts_down(machines, channel):
    m = machines(axis_table("x", channel, 1))
    drive, axis, sim = m.units["x"].drive, m.axis("x"), simulated(m, "x")
    m.submit("x", "power", on=True)
    m.scheduler.run_cycle()
    assert axis.state is AxisState.STANDSTILL
    assert drive.state == "OPERATION ENABLED" and drive.enabled  # 0x0F from READY: transitions 3 + 4 at one SYNC
    m.submit("x", "move_absolute", position=20.0)
    assert run_until(m, lambda: axis.state is AxisState.STANDSTILL and axis.command_position == 20.0)
    assert run_until(m, lambda: abs(drive.position - 20.0) < 0.002)
    assert sim.servo.enabled
    m.submit("x", "power", on=False)
    m.scheduler.run_cycle()
    assert axis.state is AxisState.DISABLED
    assert drive.state == "READY TO SWITCH ON"  # shutdown: power stage off, the motor coasts
    assert not sim.servo.enabled


def test_reset_after_a_drive_fault_brings_the_drive_back(machines, channel):
    m = machines(axis_table("x", channel, 1))
    drive, axis, sim = m.units["x"].drive, m.axis("x"), simulated(m, "x")
    m.submit("x", "power", on=True)
    m.scheduler.run_cycle()
    sim.inject_fault(0x4310)
    assert run_until(m, lambda: axis.state is AxisState.ERROR_STOP, cycles=20)
    assert drive.state == "FAULT"
    run_until(m, lambda: axis.motion_ended, cycles=100)
    m.submit("x", "reset")
    assert run_until(m, lambda: drive.state == "OPERATION ENABLED", cycles=20)  # fault reset, then enable
    assert axis.state is AxisState.STANDSTILL
    for _ in range(60):  # the fault does not come back: the drive was reset, not just the axis
        m.scheduler.run_cycle()
    assert axis.state is AxisState.STANDSTILL and axis.error_id == 0
    m.submit("x", "move_relative", distance=5.0)
    assert run_until(m, lambda: axis.state is AxisState.STANDSTILL and abs(drive.position - 5.0) < 0.002)


def test_leaving_the_bus_quick_stops_an_enabled_drive(machines, channel):
    m = machines(axis_table("x", channel, 1))
    sim = simulated(m, "x")
    m.submit("x", "power", on=True)
    m.scheduler.run_cycle()
    m.submit("x", "move_velocity", velocity=50.0)
    run_until(m, lambda: m.axis("x").command_velocity == 50.0)
    m.units["x"].drive.close()  # (what close_drives and the exit handler do first)
    # the drive ramps down with its quick stop deceleration, then (0x605A = 2) switches off
    assert wait_for(lambda: sim.state in ("QUICK STOP ACTIVE", "SWITCH ON DISABLED"))
    assert sim.state == "QUICK STOP ACTIVE"  # one SYNC after the quick stop: still braking


def test_jog_in_profile_velocity_when_chosen(machines, channel):
    m = machines(axis_table("x", channel, 1, jog="pv"))
    drive, axis = m.units["x"].drive, m.axis("x")
    m.submit("x", "power", on=True)
    m.scheduler.run_cycle()
    assert drive.mode_display == CSP
    m.submit("x", "jog", direction=1)
    assert run_until(m, lambda: axis.command_velocity == 50.0, cycles=500)
    assert drive.mode_display == PV
    for _ in range(100):
        m.scheduler.run_cycle()
    assert drive.velocity == pytest.approx(50.0, abs=0.01)  # the drive's velocity loop on the jog speed
    assert abs(axis.following_error) < 1.0
    m.submit("x", "jog", direction=0)
    assert run_until(m, lambda: axis.state is AxisState.STANDSTILL, cycles=500)
    assert drive.mode_display == CSP
    for _ in range(200):
        m.scheduler.run_cycle()
    assert abs(drive.position - axis.command_position) < 0.002  # CSP holds the set point again


def test_jog_in_csp_by_default(machines, channel):
    m = machines(axis_table("x", channel, 1))
    drive, axis = m.units["x"].drive, m.axis("x")
    m.submit("x", "power", on=True)
    m.submit("x", "jog", direction=-1)
    assert run_until(m, lambda: axis.command_velocity == -50.0, cycles=500)
    assert drive.mode_display == CSP
