"""The COMPAX program interpreter's sequencing (programrun.py): one set per cycle, P210 = 0 / 1
(L1401-1415, L1983), STOP / BREAK / START (§12.0.1 L916-922), errors, the power stage (L136-140).
Seed lines (Lnnnn) are of /work/shared/seeds/004_67df1072c2ac0157.txt."""

from __future__ import annotations

import pytest

from axisline.devices.compax.camop import CamState
from axisline.motion.axis import AxisState

from .program_machine import Run, build, load, send, straight

CURVES = [straight(1, 360.0)]


def test_one_set_per_cycle():
    # programrun decision 1: a GOTO loop never holds a cycle, each set takes one cycle
    m = build(CURVES)
    load(m, ["N001: OUTPUT O1=1", "N002: OUTPUT O2=1", "N003: GOTO 3"])
    send(m, "START")
    op, run = m.device.op, m.device.run
    m.scheduler.run_cycle()
    assert op.output(1) and not op.output(2)
    m.scheduler.run_cycle()
    assert op.output(2) and run.executed == 2
    Run(m).cycles(50)
    assert run.executed == 52 and run.state == "running" and run.pointer == 3


@pytest.mark.parametrize("p210", [0, 1])
def test_parallel_mode_runs_on_during_a_positioning_and_stops_at_the_next(p210):
    # L1403 "P210="0": linear processing of the program memory"; L1405-1407 "P210="1": the
    # program continues to run during positioning commands and stops at the next positioning command"
    m = build(CURVES, parameters={"P210": p210})
    load(m, ["N001: SPEED 5", "N002: POSA 100", "N003: OUTPUT O7=1", "N004: POSA 0", "N005: OUTPUT O8=1"])
    send(m, "START")
    op, ax = m.device.op, m.device.axis
    run = Run(m)
    run.cycles(10)
    assert ax.state is AxisState.DISCRETE_MOTION
    assert op.output(7) is (p210 == 1)  # set at once in parallel mode only
    assert m.device.run.pointer == (4 if p210 else 3)  # parallel: waits at the next POSA
    run.cycles(2000, until=lambda: m.device.run.state == "ended" and ax.state is AxisState.STANDSTILL)
    assert op.output(7) and op.output(8) and ax.command_position == pytest.approx(0.0)
    assert max(run.p) == pytest.approx(100.0)  # the second POSA waited for the first


def test_loop_0_holds_the_program_until_stop_which_continues_at_the_next_set():
    # L890-891 "the LOOP - command is still active and COMPAX does not carry out any commands";
    # L916-922 "Stop interrupts the cam operation and brings the slave to a standstill via a
    # ramp ... As a further step the next command will be used in the program memory"
    m = build(CURVES)
    load(m, ["N001: SETC 1", "N002: SETM 0", "N003: LOOP 0", "N004: OUTPUT O7=1"])
    send(m, "START")
    run, op = Run(m), m.device.op
    run.cycles(5)
    run.master_on()
    run.cycles(500)
    assert op.state is CamState.SYNC and not op.output(7) and m.device.run.pointer == 4
    assert send(m, "STOP") == [b"\r\n>"]
    assert not op.loop_active and m.device.run.state == "stopped"
    run.cycles(300, until=lambda: m.device.axis.state is AxisState.STANDSTILL)
    assert m.device.axis.state is AxisState.STANDSTILL and not op.output(7)
    assert send(m, "START") == [b"\r\n>"]
    run.cycles(5)
    assert op.output(7) and m.device.run.state == "ended" and m.device.run.pointer == 1


def test_break_puts_the_program_back_to_its_first_set():
    m = build(CURVES)
    load(m, ["N001: OUTPUT O1=1", "N002: WAIT 1000", "N003: OUTPUT O2=1"])
    send(m, "START")
    Run(m).cycles(20)
    assert m.device.run.pointer == 2
    assert send(m, "BREAK") == [b"\r\n>"]
    assert m.device.run.pointer == 1 and m.device.run.state == "stopped"
    m.device.op.set_output(1, False)
    send(m, "START")
    Run(m).cycles(1)
    assert m.device.op.output(1) and m.device.run.pointer == 2


def test_wait_takes_its_milliseconds():
    m = build(CURVES)
    load(m, ["N001: WAIT 50", "N002: OUTPUT O1=1"])
    send(m, "START")
    run = Run(m)
    run.cycles(49)
    assert not m.device.op.output(1)
    run.cycles(3)
    assert m.device.op.output(1)


def test_a_set_answered_with_an_error_stops_the_program_and_fails_the_run():
    # programrun decision 5: SETC of a curve that is not there is E17 (L1939)
    m = build(CURVES)
    load(m, ["N001: SETC 7", "N002: OUTPUT O1=1"])
    send(m, "START")
    result = m.run(0.05)
    assert not result.completed and m.device.run.state == "error" and not m.device.op.output(1)
    assert any("program set 'N001: SETC 7'" in f and "!E17" in f for f in result.faults), result.faults
    assert send(m, "S30") == [b"S030=17.000\r\n>"]
    assert m.device.summary()["program_memory"]["errors"][0]["set"] == 1


def test_positioning_sets_wait_for_the_power_stage():
    # L136-140 "if the program is not functioning: The output stage is disabled in the basic
    # condition! It can be enabled by I12="1"."
    m = build(CURVES, inputs={"I12": "power"}, io_inputs=("power",))
    load(m, ["N001: POSA 10", "N002: OUTPUT O1=1"])
    send(m, "START")
    run = Run(m)
    run.cycles(50)
    assert m.device.run.pointer == 1 and m.device.axis.state is AxisState.DISABLED
    m.io.set_input("power", True)
    run.cycles(500, until=lambda: m.device.run.state == "ended")
    assert m.device.axis.command_position == pytest.approx(10.0) and m.device.op.output(1)


def test_a_second_positioning_command_over_the_interface_is_rejected():
    # L1409 "When commands are set by bus, it is the second positioning command that is rejected"
    m = build(CURVES)
    Run(m).cycles(1)  # I12 (wired true) powers the slave in the first cycle
    assert send(m, "SPEED 5", "POSA 100") == [b"\r\n>"] * 2
    Run(m).cycles(5)
    assert send(m, "POSR 10")[0].startswith(b"!E107 ")
    Run(m).cycles(2000, until=lambda: m.device.axis.state is AxisState.STANDSTILL)
    assert send(m, "POSR 10") == [b"\r\n>"]
    Run(m).cycles(2000, until=lambda: m.device.axis.state is AxisState.STANDSTILL)
    assert m.device.axis.command_position == pytest.approx(110.0)


def test_startup_start_runs_the_program_file(tmp_path):
    prg = tmp_path / "p.prg"
    prg.write_text("N001: SETC 1\nN002: OUTPUT O7=1\n")
    m = build(CURVES, program_file=str(prg), startup=["START"])
    result = m.run(0.05)
    assert result.completed and m.device.op.output(7)
    s = m.device.summary()["program_memory"]
    assert s["state"] == "ended" and s["executed"] == 2 and s["sets"] == 2


def test_shutdown_stops_the_program_and_the_cam_operation():
    # serve's Ctrl-C / SIGTERM (Personality.stop): no set runs after it, the slave brakes
    m = build(CURVES)
    load(m, ["N001: SETC 1", "N002: LOOP 0", "N003: OUTPUT O7=1"])
    send(m, "START")
    Run(m).cycles(5)
    Run(m).master_on()
    Run(m).cycles(300)
    assert m.device.op.state is CamState.SYNC
    assert m.stop_all(2.0)
    assert m.device.run.state == "stopped" and not m.device.op.loop_active and not m.device.op.output(7)
    assert m.device.axis.state is AxisState.STANDSTILL
