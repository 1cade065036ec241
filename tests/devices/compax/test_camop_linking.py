"""COMPAX curve linking, interruption and errors: compax.md §2.14 (§15), §2.4 (E25), §2.11 (§12.0.1),
§2.17 (I12), §5.1 (E10); §7 X3, X14, X15; Appendix B curve_linking_normal_mode."""

from __future__ import annotations

import pytest

from axisline.devices.compax import CompaxError
from axisline.devices.compax.camop import LINK_LEAD_CYCLES, CamState
from axisline.motion.axis import AxisState

from .test_camop_rig import FULL, Curve, Rig, line

# §15.3.4: "Curve 1 from 0 ... 360° (travelled 2 times); Curve 2 from 0 ... -300°; Curve 3 from
# 0 ... 260°; Curve 4 from 0 ... -320°; Curve 5 from 0 ... -360°"
X14 = {
    1: Curve(number=1, slave_cycle=360.0, set_points=[0.0, 0.5, FULL]),
    2: Curve(number=2, slave_cycle=300.0, set_points=[0.0, -0.5, -1.0]),
    3: Curve(number=3, slave_cycle=260.0, set_points=[0.0, 0.5, FULL]),
    4: Curve(number=4, slave_cycle=320.0, set_points=[0.0, -0.5, -1.0]),
    5: Curve(number=5, slave_cycle=360.0, set_points=[0.0, -0.5, -1.0]),
}


def linked_run(p93: int, program, speed: int = 4, lead: int = 30, curves=None):
    """P210 = 1, P34 = 4: SETC / LOOP of the first curve, then each next SETC + LOOP as soon as
    the link slot is free and the running curve has `lead` ms or more to go. Returns the rig and
    (curve, S1, set point) at every change of the active curve and at the end."""
    rig = Rig(curves or X14, P210=1, P34=4, P93=p93)
    rig.record = True
    first, m = program[0]
    rig.op.setc(first)
    rig.op.setm(0.0)
    rig.op.loop(m)
    rig.inputs["I13"] = True
    rig.step()
    rig.start_master(speed)
    todo = list(program[1:])
    seen = []
    current = first
    while rig.op.loop_active:
        if todo and rig.op._link is None:
            n, m = todo.pop(0)
            rig.op.setc(n)
            rig.op.loop(m)
        rig.step()
        if rig.op.status(43) != current:
            current = int(rig.op.status(43))
            seen.append((current, rig.op.status(1), rig.p))
        if rig.cycle > 10000:
            raise AssertionError("linked curves did not end")
    seen.append((current, rig.op.status(1), rig.p))
    return rig, seen


def test_curve_linking_normal_mode_keeps_the_absolute_reference():
    # §7 X14 / Appendix B curve_linking_normal_mode: absolute slave position after each curve
    # 360, 720 (curve 1 twice), 420, 680, 360, 0 - each curve's value 0 on the previous end value
    rig, seen = linked_run(1, [(1, 2), (2, 1), (3, 1), (4, 1), (5, 1)])
    ends = [round(s1, 6) for _, s1, _ in seen]
    assert [c for c, _, _ in seen] == [2, 3, 4, 5, 5]
    # the transfers happen exactly at the master-cycle wraps (4 deg per ms divides 360)
    assert [p for _, _, p in seen[:-1]] == pytest.approx([720.0, 420.0, 680.0, 360.0])
    assert ends[-1] == pytest.approx(0.0)
    assert rig.op.state is CamState.IDLE


def test_curve_linking_is_seamless():
    # §2.14 "the 2nd curve then starts instantaneously after the 1st curve is terminated":
    # the slave set point has no jump at a transfer between curves starting at 0
    rig, seen = linked_run(1, [(1, 1), (3, 1), (1, 1)])
    p = [r[1] for r in rig.trace]
    assert len(p) > 3 * 90 and all(abs(b - a) <= 4.0 + 1e-9 for a, b in zip(p, p[1:]))


def test_curve_linking_to_a_curve_not_starting_at_0_jumps():
    # manual §15.3.4 Normal mode: "In the curve transfer, the zero point of the next curve is set
    # to the last curve point of the last curve" / "Attention! In curves that do not begin at 0
    # (e.g. first curve value is at 60°), COMPAX receives a set point jump when switching to these
    # curves; i.e. the transfer is not smooth!" (compax.md §2.14, camop D14)
    curves = {1: X14[1], 6: Curve(number=6, slave_cycle=360.0, set_points=[60.0 / 360.0, 0.5, FULL])}
    rig, seen = linked_run(1, [(1, 1), (6, 1)], curves=curves)
    p = [r[1] for r in rig.trace]
    steps = [b - a for a, b in zip(p, p[1:])]
    jumps = [k for k, d in enumerate(steps) if abs(d) > 4.0 + 1e-9]
    assert len(jumps) == 1  # one set-point jump, at the transfer
    k = jumps[0]
    # the master reaches the wrap in this cycle (4° per ms): curve 1 ends at 360 = the zero point
    # of curve 6, whose first value 60° is set at once: 356 -> 420 (4° of curve 1, then 60°)
    assert (p[k], p[k + 1]) == pytest.approx((356.0, 420.0))
    assert steps[k + 1] == pytest.approx(4.0 * 120.0 / 180.0)  # then curve 6's own gradient
    assert [c for c, _, _ in seen] == [6, 6]
    assert seen[-1][1] == pytest.approx(720.0)  # curve 6 ends at its zero point + S_T: the absolute reference
    assert rig.op.state is CamState.IDLE


def test_curve_linking_reset_mode_counts_back_by_the_last_curve():
    # §2.14 reset mode: "The actual value is back-calculated after each curve cycle to S_T of the
    # last curve cycle." Every curve here starts at 0: S1 stays within the running curve's range.
    rig, seen = linked_run(3, [(1, 2), (2, 1), (3, 1), (4, 1), (5, 1)])
    for curve, s1, _ in seen[:-1]:
        lo, hi = sorted((0.0, X14[curve].set_points[-1] * X14[curve].slave_cycle))
        assert lo - 5.0 <= s1 <= hi + 5.0
    # the plant moved as in normal mode: 360 + 360 - 300 + 260 - 320 - 360 = 0
    assert rig.x == pytest.approx(0.0, abs=1e-6)


def test_link_needs_10_ms_lead():
    # §7 X15 / §2.14 "the curve must have already been selected using SETC and LOOP, ca. 10ms before
    # the start of the next curve" (decision D14): a later link is a new LOOP (coupling again)
    assert LINK_LEAD_CYCLES == 10
    for lead, cycles in ((12, 1), (5, 2)):
        rig = Rig(X14, P210=1, P34=4, P93=1)
        rig.op.setc(1)
        rig.op.setm(0.0)
        rig.op.loop(1)
        rig.inputs["I13"] = True
        rig.step()
        rig.start_master(7)
        rig.until(lambda: rig.chain.position >= 360.0 - 7 * lead)
        rig.op.setc(3)
        rig.op.loop(1)
        rig.until(lambda: rig.op.status(43) == 3)
        start = rig.cycle
        rig.until(lambda: not rig.op.loop_active)
        # linked: one cycle; too late: a new LOOP 1 that couples just after the cycle start runs ~2
        assert round((rig.cycle - start) * 7 / 360) == cycles


def test_link_rules():
    rig = Rig(X14, P210=1, P34=4)
    rig.op.setc(1)
    rig.op.loop(1)
    with pytest.raises(CompaxError) as e:
        rig.op.setc(9)
    assert e.value.code == 17
    rig.op.setc(2)
    with pytest.raises(CompaxError):
        rig.op.loop(0)  # "The variable LOOP 0 cannot be used in this case."
    rig.op.loop(1)
    rig.op.setc(3)
    with pytest.raises(CompaxError) as e:
        rig.op.loop(1)  # a second linked LOOP while one waits
    assert e.value.code == 107


def test_p34_4_without_a_linked_curve_stops_at_the_end_of_the_master_cycle():
    # §2.11 P34 = 4: "Leave curve when loop counter terminates (LOOP n) at the end of the master cycle"
    rig = Rig({1: line(decoupling=0.2, braking=0.7, standstill=0.5)}, P34=4, P93=1)
    rig.op.setc(1)
    rig.op.setm(0.0)
    rig.op.loop(2)
    rig.inputs["I13"] = True
    rig.step()
    rig.start_master(4)
    rig.until(lambda: not rig.op.loop_active)
    assert rig.p == pytest.approx(720.0)  # the decoupling parameters are not used
    rig.step(3)
    assert rig.axis.state is AxisState.STANDSTILL and rig.p == pytest.approx(720.0)


def test_software_limit_e25_stops_and_blocks_master_counting():
    # §7 X3 / §2.4: "when reaching the limits, the slave will be stopped, the cam operation will be
    # interrupted, the counting impulses at the encoder input will be disabled, ... E25"
    rig = Rig({1: line()}, P93=1, P11=500.0, P12=-100.0)
    rig.op.posa_home()  # D20: the machine datum first
    rig.step(2)
    rig.op.setc(1)
    rig.op.setm(0.0)
    rig.op.loop(0)
    rig.inputs["I13"] = True
    rig.step()
    rig.start_master(4)
    rig.until(lambda: not rig.op.loop_active)
    assert rig.op.status(30) == 25 and not rig.chain.counting
    rig.step(200)
    assert rig.axis.state is AxisState.STANDSTILL and rig.p <= 510.0
    s44 = rig.chain.s44
    rig.step(50)
    assert rig.chain.s44 == s44  # the encoder input stays disabled ...
    rig.inputs["I16"] = False
    rig.step()
    rig.inputs["I16"] = True  # ... until master position measurement is switched on again
    rig.step(5)
    assert rig.chain.counting
    # "The limit supervision only becomes active again when the slave moves back to the admissible area."
    rig.op.loop(0)
    rig.step(20)
    assert rig.op.loop_active and rig.op.state is CamState.SYNC


def test_software_limits_off_and_in_reset_mode():
    # §2.4 "P11=+4 000 000; P12=-4 000 000" switch the supervision off; reset mode: ineffective
    for params in ({"P93": 1}, {"P93": 3, "P11": 500.0}):
        rig = Rig({1: line()}, **params)
        rig.op.setc(1)
        rig.op.loop(0)
        rig.inputs["I13"] = True
        rig.step()
        rig.start_master(9)
        rig.step(200)
        assert rig.op.loop_active and rig.op.status(30) == 0


def test_tracking_error_e10_interrupts_the_cam_operation():
    # §2.11 "With these settings, rapid coupling movements are possible! This can trigger Error E10"
    rig = Rig({1: line(coupling=0.3, synchronous=0.3)}, P34=1, plant_lag=True, fe_limit=20.0)
    rig.op.setc(1)
    rig.op.loop(0)
    rig.inputs["I13"] = True
    rig.start_master(9)
    rig.until(lambda: rig.axis.state is AxisState.ERROR_STOP, limit=2000)
    rig.step()
    assert rig.op.status(30) == 10 and rig.op.state is CamState.IDLE and not rig.op.output(16)


def test_break_interrupts_with_a_ramp():
    # §2.11 (§12.0.1): "Stop interrupts the cam operation and brings the slave to a standstill via a
    # ramp ... producing an undefined target position."
    rig = Rig({1: line()}, P93=1)
    rig.op.setc(1)
    rig.op.loop(0)
    rig.inputs["I13"] = True
    rig.step()
    rig.start_master(9)
    rig.step(100)
    cmd = rig.op.brk(deceleration=1e5)
    assert rig.op.state is CamState.IDLE and not rig.op.loop_active
    rig.until(lambda: cmd.done)
    assert rig.p > 900.0 and rig.axis.state is AxisState.STANDSTILL
    assert rig.op.offset == pytest.approx(720.0)  # the curve offset of the master cycle, kept for POSR CAM


def test_i12_enables_the_output_stage_but_not_during_cam_operation():
    # §2.17 I12: "By I12="1" the power output stage is enabled ... when the LOOP command is active
    # [I12] is not evaluated."
    rig = Rig({1: line()})
    rig.inputs["I12"] = False
    rig.step()
    assert rig.axis.state is AxisState.DISABLED
    rig.inputs["I12"] = True
    rig.step()
    assert rig.axis.state is AxisState.STANDSTILL
    rig.op.setc(1)
    rig.op.loop(0)
    rig.inputs["I12"] = False
    rig.step(5)
    assert rig.axis.state is AxisState.SYNCHRONIZED_MOTION
