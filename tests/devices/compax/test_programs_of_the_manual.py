"""Every program listing of the COMPAX supplement, loaded over the ASCII interface as printed and
run on the simulated plant (issue 19). Seed lines (Lnnnn) are of
/work/shared/seeds/004_67df1072c2ac0157.txt; "SETM x" ("Align master", a placeholder in the
listings) is loaded as SETM 0, and the listings' "...." / "If I8=...." placeholder lines are left
out (the set numbers printed are kept)."""

from __future__ import annotations

import pytest

from axisline.devices.compax.camop import CamState

from .program_machine import Run, build, doffing, load, open_segment, send, straight

# §15.2 "Program example 2: Multiple travelling of open curves" (L1474-1484)
EXAMPLE_2 = ["N001: P210=1", "N002: SETC 1", "N003: SETM 0", "N004: SETS", "N006: LOOP 1", "N007: SETC 2",
             "N008: LOOP 2", "N009: SETC 3", "N010: LOOP 1", "N011: SETC 1", "N012: GOTO 6"]
# §15.2 "Variable Curve linking" (L1501-1510), N008 "...." left out
VARIABLE = ["N001: P210=1", "N002: SETC 1", "N003: SETM 0", "N004: SETS", "N006: LOOP 1",
            "N007: If I8=1 GOTO 6", "N009: SETC 2", "N010: LOOP 1"]
# §15.2 "Program example 1: Curves in the normal mode" (L1446-1462, printed without set numbers)
EXAMPLE_1 = ["N001: P210=1", "N002: SETC 1", "N003: SETM 0", "N004: SETS", "N005: LOOP 1", "N006: SETC 2",
             "N007: LOOP 1", "N008: SETC 3", "N009: LOOP 1", "N010: SETC 4", "N011: LOOP 1"]


def started(curves, program, inputs_on=(), **kw):
    m = build(curves, **kw)
    for name in inputs_on:
        m.io.set_input(name, True)
    load(m, program)
    assert send(m, "START") == [b"\r\n>"]
    run = Run(m)
    run.cycles(20)  # the sets up to the first LOOP (one set per ms); the master still stands
    run.master_on()
    return m, run


def test_example_2_open_curves_run_in_the_printed_order_without_speed_jumps():
    # L1466 "It is also possible to compile a motion profile from several curve segments which do
    # not have acceleration or speed zero at the curve borders"; curves 1 and 2 change speed in
    # the middle, curve 3 is straight; all have gradient 1 at their borders (L1548 "The gradients
    # on the end of a curve and on the start of the next curve must coincide")
    curves = [open_segment(1, 330.0, 420.0), open_segment(2, 210.0, 300.0), straight(3, 360.0)]
    m, run = started(curves, EXAMPLE_2, parameters={"P34": 4})
    run.cycles(1200)
    events = [(r["event"], r["curve"], r["loop"]) for r in run.log]
    # N006 LOOP 1 (curve 1), N008 LOOP 2 (curve 2 twice), N010 LOOP 1 (curve 3), N011 + N012 GOTO 6: again
    assert events[:7] == [("loop", 1, 1), ("transfer", 2, 2), ("transfer", 3, 1), ("transfer", 1, 1),
                          ("transfer", 2, 2), ("transfer", 3, 1), ("transfer", 1, 1)]
    # loop counts: curve 1 one master cycle (120 ms), curve 2 two, curve 3 one
    t = [r["t"] for r in run.log[1:7]]
    assert [(b - a) / 0.12 for a, b in zip(t, t[1:])] == pytest.approx([2.0, 1.0, 1.0, 2.0, 1.0], abs=0.01)
    # normal mode (L1555): the next curve's zero point on the last curve's end - the absolute
    # reference: 420, 420 + 2*300, + 360, + 420, ... (S47 of the transfer cycle less the new
    # curve's value at S44, gradient 1 at the curve start)
    zeros = [r["set_point"] - 360.0 * r["S44"] / 1000.0 for r in run.log[1:7]]
    assert zeros == pytest.approx([420.0, 1020.0, 1380.0, 1800.0, 2400.0, 2760.0], abs=1e-4)  # S_T / 2^23
    # no speed jump at the transfers: the speed changes there no more than inside a curve
    steps = run.speed_steps()
    at = [round(r["t"] * 1000) for r in run.log[1:7]]
    transfer_steps = [steps[k - 4:k + 3].max() for k in at]
    inside = steps[40:][steps[40:] > 0].max()
    assert max(transfer_steps) < 0.05 * inside
    assert m.device.run.state == "running" and not m.device.run.errors and not m.faults


def test_variable_linking_repeats_curve_1_while_i8_then_curve_2():
    # L1497 "a variable number of cycles ... implemented using an external counter in the program
    # memory"; L1506 "N007: If I8=1 GOTO 6  Curve 1 is repeated until I8=0"
    curves = [open_segment(1, 330.0, 420.0), open_segment(2, 210.0, 300.0)]
    m, run = started(curves, VARIABLE, inputs_on=("repeat",), parameters={"P34": 4}, inputs={"I8": "repeat"},
                     io_inputs=("repeat",))
    run.cycles(600)  # five runs of curve 1 with I8 = 1
    m.io.set_input("repeat", False)
    run.cycles(1000, until=lambda: m.device.run.state == "ended" and not m.device.op.loop_active)
    curves_run = [r["curve"] for r in run.log if r["event"] in ("loop", "transfer")]
    assert curves_run[-1] == 2 and curves_run.count(2) == 1
    ones = curves_run.count(1)
    assert 6 <= ones <= 8  # five with I8 = 1, then at most two already linked when I8 fell
    assert run.log[-1]["event"] == "end"
    # the slave followed the linked curves seamlessly: each transfer at the end value of the
    # previous curve (ones x 420), no speed jump
    transfers = [r for r in run.log if r["event"] == "transfer"]
    zeros = [r["set_point"] - 360.0 * r["S44"] / 1000.0 for r in transfers]
    # (to the 24-bit resolution of the set points, S_T / 2^23 = 5e-5 deg)
    assert zeros == pytest.approx([420.0 * k for k in range(1, len(transfers) + 1)], abs=1e-4)
    steps = run.speed_steps()
    inside = steps[40:][steps[40:] > 0].max()
    assert max(steps[round(r["t"] * 1000) - 4:round(r["t"] * 1000) + 3].max() for r in transfers) < 0.05 * inside
    # P34 = 4 (L1417): the last curve is left at the end of its master cycle, at its end value
    assert m.device.axis.command_position == pytest.approx(420.0 * ones + 300.0, abs=1e-6)
    assert m.device.op.state is CamState.IDLE and not m.faults


def test_example_1_doffing_curves_in_normal_mode():
    # L1440-1444: start position 1 -> doffing 1 -> start 2 -> doffing 2 -> start 1, curves with
    # standstill phases at the ends (L1464); each curve continues from the end of the last
    curves = [doffing(1, 200.0), doffing(2, -120.0), doffing(3, 150.0), doffing(4, -230.0)]
    m, run = started(curves, EXAMPLE_1, parameters={"P34": 4})
    run.cycles(1200, until=lambda: m.device.run.state == "ended" and not m.device.op.loop_active)
    log = run.log
    assert [(r["event"], r["curve"]) for r in log] == [("loop", 1), ("transfer", 2), ("transfer", 3),
                                                       ("transfer", 4), ("end", 4)]
    # at each transfer the slave stands (dwell) exactly on the positions of the sequence
    assert [r["set_point"] for r in log[1:]] == pytest.approx([200.0, 80.0, 230.0, 0.0], abs=1e-6)
    assert m.device.run.state == "ended" and not m.faults


def test_normal_mode_linking_of_sec_15_3_4_keeps_the_absolute_reference():
    # L1556-1568: "Curve 1 is travelled 2 times; at the start of curve 2 an alignment is
    # implemented, so that the curve value 0 of curve 2 starts from the end value of curve 1";
    # curves 0...360, 0...-300, 0...260, 0...-320, 0...-360 (test vector X14: 360, 720, 420, 680, 360, 0)
    curves = [straight(1, 360.0), straight(2, -300.0), straight(3, 260.0), straight(4, -320.0), straight(5, -360.0)]
    program = ["N001: P210=1", "N002: SETC 1", "N003: SETM 0", "N004: LOOP 2", "N005: SETC 2", "N006: LOOP 1",
               "N007: SETC 3", "N008: LOOP 1", "N009: SETC 4", "N010: LOOP 1", "N011: SETC 5", "N012: LOOP 1"]
    m, run = started(curves, program, parameters={"P34": 4})
    run.cycles(1500, until=lambda: m.device.run.state == "ended" and not m.device.op.loop_active)
    transfers = [r for r in run.log if r["event"] == "transfer"]
    assert [r["curve"] for r in transfers] == [2, 3, 4, 5]
    # the new curve's zero point (S47 less its value at S44) on the old curve's end value
    slave_cycles = {2: -300.0, 3: 260.0, 4: -320.0, 5: -360.0}
    zeros = [r["set_point"] - slave_cycles[r["curve"]] * r["S44"] / 1000.0 for r in transfers]
    assert zeros == pytest.approx([720.0, 420.0, 680.0, 360.0], abs=1e-6)
    assert run.log[-1]["event"] == "end" and m.device.axis.command_position == pytest.approx(0.0, abs=1e-6)


def test_reset_mode_linking_counts_back_each_curve():
    # L1570 "In the reset mode (P93=3), the motion behaviour is comparable to that in normal mode,
    # but with modified value ranges for the actual value (S1). The actual value is back-calculated
    # after each curve cycle to S_T of the last curve cycle."
    curves = [straight(1, 360.0), straight(2, -300.0), straight(3, 260.0)]
    program = ["N001: P210=1", "N002: SETC 1", "N003: SETM 0", "N004: LOOP 2", "N005: SETC 2", "N006: LOOP 1",
               "N007: SETC 3", "N008: LOOP 1"]
    m, run = started(curves, program, parameters={"P34": 4, "P93": 3})
    run.cycles(800, until=lambda: m.device.run.state == "ended" and not m.device.op.loop_active)
    assert [r["curve"] for r in run.log] == [1, 2, 3, 3]
    assert max(abs(p) for p in run.p) <= 360.0 + 3.5  # S1 stays within a curve's range
    assert m.device.run.state == "ended" and not m.faults


def test_sec_9_setm_and_sets_align_the_curve_without_motion():
    # L757: "SETC 2 / SETM 35: The actual master position is set to 35% of the master cycle /
    # SETS: The slave position is adjusted to the curve position. The slave does not move."
    m = build([straight(1, 360.0), straight(2, 360.0)])
    load(m, ["N001: SETC 2", "N002: SETM 35", "N003: SETS"])
    send(m, "START")
    run = Run(m)
    run.cycles(10)
    assert m.device.run.state == "ended"
    assert m.device.op.status(44) == pytest.approx(350.0) and m.device.axis.command_position == 0.0
    assert send(m, "S44") == [b"S044=350.000\r\n>"]


def test_sec_9_posr_cam_travels_to_the_curve_point():
    # L785-787: "SETC 2 / SETM 35 / POSR CAM By a normal positioning (with the values adjusted by
    # means of ACCEL and SPEED) the slave will travel to the slave position which corresponds to
    # the chosen master starting point": 35 % of the straight 360 deg curve = 126 deg
    m = build([straight(1, 360.0), straight(2, 360.0)])
    load(m, ["N001: SPEED 10", "N002: SETC 2", "N003: SETM 35", "N004: POSR CAM", "N005: OUTPUT O7=1"])
    send(m, "START")
    run = Run(m)
    run.cycles(30)
    assert m.device.run.pointer == 5 and not m.device.op.output(7)  # linear mode: held until the slave stands
    assert max(run.v) == pytest.approx(2000.0)  # SPEED 10: 10 % of v_max
    run.cycles(500, until=lambda: m.device.run.state == "ended")
    assert m.device.axis.command_position == pytest.approx(126.0) and m.device.op.output(7)


def test_sec_11_1_loop_10_holds_the_program_in_linear_mode():
    # L862-865: "SETC 1 / (SETM x) / LOOP 10 Cam operation e. g. activated for 10 loops"; L1403
    # "P210=0: linear processing of the program memory": the next set runs after the 10 loops
    m = build([straight(1, 360.0)], parameters={"P34": 4})
    load(m, ["N001: SETC 1", "N002: SETM 0", "N003: LOOP 10", "N004: OUTPUT O7=1"])
    send(m, "START")
    run = Run(m)
    run.cycles(10)
    run.master_on()
    run.cycles(1150)  # 9.6 master cycles: the LOOP still runs, O7 is not set
    assert m.device.op.loop_active and m.device.op.status(48) == 1.0 and not m.device.op.output(7)
    run.cycles(200, until=lambda: m.device.run.state == "ended")
    assert not m.device.op.loop_active and m.device.op.output(7)
    assert m.device.axis.command_position == pytest.approx(3600.0, abs=1e-6)  # 10 x S_T, normal mode


def test_sec_14_master_related_label_setup_procedure():
    # L1303-1309 "Summarised procedure: P31 = 2 / SETC n / POSA 0 / SETM x with x = S50/10 /
    # LOOP n and I13=1": as program sets; M_M = 0.5, P32 = 0.7 M_T: S50 = 800 per mille, SETM 80
    label = straight(1, 360.0)
    label.update(label_set_point=0.5, label_window=0.1)
    m = build([label], parameters={"P33": 1, "P32": 252.0})
    load(m, ["N001: P31=2", "N002: VP", "N003: SETC 1", "N004: POSA 0", "N005: SETM 80", "N006: LOOP 0"])
    send(m, "START")
    Run(m).cycles(20)
    op = m.device.op
    assert op.loop_active and op.status(44) == pytest.approx(800.0) and op.status(50) == pytest.approx(800.0)
    assert m.device.params[31] == 2 and m.device.run.state == "ended"
