"""Every fault path of issue 20: EMCY, the fault bit, heartbeat loss, a drive that leaves
OPERATIONAL, the controller going away, a node that never answers."""

from __future__ import annotations

from pathlib import Path

import pytest
from typer.testing import CliRunner

from axisline.configerrors import ConfigError
from axisline.machine import Machine
from axisline.motion.axis import AxisState

from .conftest import absent, axis_table, run_until, simulated, wait_for

FAST_HEARTBEAT = {"heartbeat_ms": 20, "heartbeat_timeout_ms": 300, "response_timeout": 0.1}


def _powered(machines, *axes):
    m = machines(*axes)
    for a in axes:
        m.submit(a["name"], "power", on=True)
    m.scheduler.run_cycle()
    return m


def test_emcy_puts_the_axis_in_error_stop_with_the_drive_code(machines, channel):
    m = _powered(machines, axis_table("x", channel, 3))
    axis = m.axis("x")
    m.submit("x", "move_velocity", velocity=40.0)
    run_until(m, lambda: axis.command_velocity == 40.0)
    simulated(m, "x").inject_fault(0x2310)
    assert run_until(m, lambda: axis.state is AxisState.ERROR_STOP, cycles=10)
    assert axis.error_id == 0x2310
    assert "node 3" in axis.error_text and "0x2310 continuous over-current" in axis.error_text
    assert "EMCY" in axis.error_text
    assert any("0x2310" in f for f in m.faults)


def test_fault_bit_without_emcy_reads_the_error_code(machines, channel):
    m = _powered(machines, axis_table("x", channel, 2))
    axis = m.axis("x")
    simulated(m, "x").inject_fault(0x7305, emcy=False)
    assert run_until(m, lambda: axis.state is AxisState.ERROR_STOP, cycles=10)
    assert axis.error_id == 0x7305  # 0x603F, read by SDO
    assert "fault 0x7305 incremental sensor 1 fault" in axis.error_text


def test_a_fault_on_one_drive_leaves_the_other_axis_alone(machines, channel):
    m = _powered(machines, axis_table("x", channel, 1), axis_table("y", channel, 2))
    m.submit("y", "move_velocity", velocity=30.0)
    simulated(m, "x").inject_fault(0x3210)
    assert run_until(m, lambda: m.axis("x").state is AxisState.ERROR_STOP, cycles=10)
    for _ in range(50):
        m.scheduler.run_cycle()
    assert m.axis("y").state is AxisState.CONTINUOUS_MOTION  # one SYNC for both: y still runs


def _two_moving(machines, channel):
    m = _powered(machines, axis_table("x", channel, 1, **FAST_HEARTBEAT), axis_table("y", channel, 2, **FAST_HEARTBEAT))
    m.submit("x", "move_velocity", velocity=30.0)
    m.submit("y", "move_velocity", velocity=60.0)
    run_until(m, lambda: m.axis("y").command_velocity == 60.0)
    return m, m.axis("x"), m.axis("y")


def _the_others_stopped(m, x, y):
    assert x.error_id == 0x8130 and "drive node 1 on virtual:" in x.error_text
    assert y.state is AxisState.STOPPING  # the other axis stops with its own ramp ...
    assert run_until(m, lambda: y.state is AxisState.STANDSTILL, cycles=1000)  # ... and stands still
    assert y.error_id == 0
    assert any("drive node 1" in f and "(axis x)" in f and "other axes were stopped" in f for f in m.faults)


def test_heartbeat_loss_stops_the_others(machines, channel):
    m, x, y = _two_moving(machines, channel)
    simulated(m, "x").go_silent(heartbeat_only=True)  # PDOs still come: only the heartbeat tells
    assert run_until(m, lambda: x.state is AxisState.ERROR_STOP, cycles=100_000, wall_s=20.0)
    assert "heartbeat lost" in x.error_text
    _the_others_stopped(m, x, y)


def test_a_drive_gone_silent_stops_the_others(machines, channel):
    m, x, y = _two_moving(machines, channel)
    simulated(m, "x").go_silent()  # no heartbeat, no TPDO: whichever is noticed first names it
    assert run_until(m, lambda: x.state is AxisState.ERROR_STOP, cycles=100_000, wall_s=20.0)
    assert "heartbeat lost" in x.error_text or "no TPDO after 3 SYNCs" in x.error_text
    assert x.error_id == 0x8130  # not the following error the frozen position would cause later
    _the_others_stopped(m, x, y)
    assert m.units["x"].drive.missed >= 1


def test_drive_leaving_operational_faults_its_axis(machines, channel):
    m = _powered(machines, axis_table("x", channel, 4, **FAST_HEARTBEAT))
    axis = m.axis("x")
    sim = simulated(m, "x")
    sim.node.nmt.send_command(0x80)  # the drive drops to PRE-OPERATIONAL (a reset, a bus-off recovery ...)
    assert run_until(m, lambda: axis.state is AxisState.ERROR_STOP, cycles=100_000, wall_s=20.0)
    assert axis.error_id == 0x8130
    assert "left OPERATIONAL" in axis.error_text and "PRE-OPERATIONAL" in axis.error_text


def test_controller_loss_quick_stops_the_drive(machines, channel):
    m = _powered(machines, axis_table("x", channel, 1, controller_timeout_ms=300))
    sim = simulated(m, "x")
    emcy = []
    m.units["x"].drive.node.emcy.add_callback(emcy.append)
    m.submit("x", "move_velocity", velocity=50.0)
    run_until(m, lambda: m.axis("x").command_velocity == 50.0)
    run_until(m, lambda: False, cycles=20)
    assert sim.servo.velocity > 40.0
    m.units["x"].drive.bus.stop_heartbeat()  # axisline is gone: no heartbeat, no SYNC
    assert wait_for(lambda: sim.state == "SWITCH ON DISABLED", wall_s=10.0)
    assert sim.servo.velocity == pytest.approx(0.0, abs=1e-6)  # it braked with its quick stop ramp
    assert wait_for(lambda: any(e.code == 0x8130 for e in emcy))


def test_a_node_that_never_answers_is_a_clear_error(channel):
    with pytest.raises(ConfigError) as e:
        Machine(absent(axis_table("x", channel, 9, response_timeout=0.1)))
    text = str(e.value)
    assert "drive node 9" in text and "no answer" in text and "0x1000" in text and "within 0.1 s" in text
    assert "node_id = 9" in text and "bitrate = 1000000" in text


def test_a_refused_start_leaves_no_bus_open(channel):
    from axisline.drives import bus

    with pytest.raises(ConfigError):
        Machine(absent(axis_table("x", channel, 9, response_timeout=0.05)))
    assert not [b for b in bus._OPEN if b.channel == channel]  # no receive thread left behind


def test_run_names_a_bus_that_cannot_be_opened_and_exits_2(tmp_path: Path):
    from axisline.cli import app

    f = tmp_path / "m.toml"
    f.write_text(
        '[[axis]]\nname = "x"\nunit = "mm"\ncounts_per_unit = 1000.0\nv_max = 100.0\na_max = 1000.0\nfollowing_error_limit = 1.0\n'
        '[axis.drive]\ntype = "cia402"\ninterface = "socketcan"\nchannel = "nosuchcan7"\nnode_id = 5\n'
    )
    r = CliRunner().invoke(app, ["run", str(f)])
    assert r.exit_code == 2
    assert "nosuchcan7" in r.output and "cannot open the bus" in r.output
    assert "Traceback" not in r.output
