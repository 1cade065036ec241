"""COMPAX cam operation, the simplest case first: SETC / SETM / SETS / POSR CAM / LOOP with P34 = 0
and M_E = M_S = 0, operation modes, status values, drift-free scaled curves
(compax.md §2.1, §2.7, §2.8, §2.19, §2.20, §7 X5, X6, X19, X20, X24; Appendix A, B)."""

from __future__ import annotations

from fractions import Fraction

import pytest

from axisline.devices.compax import CompaxError
from axisline.devices.compax.camop import LOOP0_S48, CamState
from axisline.motion.axis import AxisState

from .test_camop_rig import FULL, Curve, Rig, line


def coupled(rig: Rig, m: int = 0, setm: float = 0.0, speed: int = 0) -> Rig:
    """SETC 1, SETM, master enabled, LOOP m, I13 = 1 (P34 = 0, M_E = M_S = 0: couples at once)."""
    rig.op.setc(1)
    rig.op.setm(setm)
    rig.start_master(0)
    rig.op.loop(m)
    rig.inputs["I13"] = True
    rig.step()
    rig.speed = speed
    return rig


def test_setc_of_a_missing_curve_is_e17():
    # §0 Misc. / §5.1: "E17: Error message when selecting non-existent curve"
    rig = Rig()
    with pytest.raises(CompaxError) as e:
        rig.op.setc(5)
    assert e.value.code == 17 and rig.op.status(30) == 17
    assert rig.op.curve is None and rig.op.status(43) == 0


def test_curve_example_of_the_manual_is_the_straight_line():
    # §7 X20: curve(m) = m for M_T = S_T = 360 (set points 0, .1, ..., .9999999)
    rig = Rig()
    rig.op.setc(1)
    for percent, value in ((0.0, 0.0), (35.0, 126.0), (50.0, 180.0), (99.5, 358.2)):
        rig.op.setm(percent)
        assert rig.op.curve_value() == pytest.approx(value)
    rig.op.setm(50.0)
    rig.step()
    assert rig.op.status(45) == pytest.approx(500.0) and rig.op.status(44) == pytest.approx(500.0)
    assert rig.op.status(43) == 1


def test_curve_full_fraction_is_exactly_the_slave_cycle():
    # decision D1: 0.9999999 (0x7FFFFF) is the full slave cycle, so the open curve moves S_T per cycle
    rig = Rig()
    rig.op.setc(1)
    curve = rig.op.curve
    assert curve.f_last == 1.0 and curve.open
    rig.op.setm(100.0)
    assert rig.op.curve_value() == 0.0  # 100 % is the start of the next cycle


def test_setm_35_then_sets_does_not_move_the_slave():
    # §7 X5: "SETC 2 / SETM 35 / SETS: The slave position is adjusted to the curve position.
    # The slave does not move."
    rig = Rig({2: line(number=2)})
    rig.axis.set_position(50.0)
    rig.op.setc(2)
    rig.op.setm(35.0)
    assert rig.chain.s44 == pytest.approx(350.0)
    rig.op.sets()
    rig.step(5)
    assert rig.p == 50.0 and rig.axis.state is AxisState.STANDSTILL
    assert rig.op.curve_value() == pytest.approx(50.0)  # the curve runs through the slave
    rig.op.loop(0)
    rig.inputs["I13"] = True
    rig.step()
    assert rig.op.state is CamState.SYNC and rig.p == 50.0
    rig.start_master(2)
    rig.step(10)
    assert rig.p == pytest.approx(50.0 + 2 * 10)  # followed from the aligned curve (1 increment = 1 deg)


def test_posr_cam_travels_to_the_curve_value_of_the_master_position():
    # §7 X5: "SETC 2 / SETM 35 / POSR CAM ... the slave will travel to the slave position which
    # corresponds to the chosen master starting point." (126 deg on the straight line)
    rig = Rig({2: line(number=2)})
    rig.axis.set_position(300.0)
    rig.op.setc(2)
    rig.op.setm(35.0)
    cmd = rig.op.posr_cam()
    rig.until(lambda: cmd.done)
    assert rig.p == pytest.approx(126.0) and rig.op.status(49) == pytest.approx(126.0)


def test_simplest_cam_operation_follows_the_master_and_ends_after_m_loops():
    # P34 = 0, M_E = M_S = 0: coupling by I13 with automatic curve adjustment (§2.11 table);
    # LOOP 3 from SETM 0 with a standing master: exactly three whole cycles, then stop (normal mode)
    rig = coupled(Rig(P93=1), m=3, speed=2)
    assert rig.op.state is CamState.SYNC and rig.op.output(16)
    assert rig.op.status(48) == 3 and rig.op.status(2) == 3
    rig.step(180)  # one cycle: 360 increments
    assert rig.op.status(48) == 2
    assert rig.p == pytest.approx(360.0)
    rig.step(360)
    assert rig.op.status(48) == 0
    assert rig.op.state is CamState.IDLE and not rig.op.output(16)
    assert rig.p == pytest.approx(3 * 360.0)  # stopped exactly at the end of the third cycle
    rig.step(5)
    assert rig.axis.state is AxisState.STANDSTILL and rig.p == pytest.approx(1080.0)


def test_loop_counts_only_cycles_travelled_synchronously_as_a_whole():
    # §2.8 LOOP 1: "A curve is designated as processed, when it has been completely travelled once
    # synchronously (O16=1 during the whole cycle)." Coupling mid-cycle: the partial cycle does not count.
    rig = Rig(P93=1)
    rig.op.setc(1)
    rig.op.setm(0.0)
    rig.start_master(3)
    rig.step(40)  # master at 123 deg
    rig.op.loop(1)
    rig.inputs["I13"] = True
    rig.step()
    assert rig.op.state is CamState.SYNC and rig.op.status(48) == 1
    assert rig.op.status(44) == pytest.approx(1000 * 123 / 360)
    start = rig.p
    rig.until(lambda: rig.op.state is CamState.IDLE)
    assert rig.p - start == pytest.approx(360.0 - 123.0 + 360.0)  # rest of the first cycle + one whole


def test_loop_0_is_endless_and_only_stop_ends_it():
    # §7 X6 / X24: LOOP 0 -> S48 = -8388608, endless
    rig = coupled(Rig(), m=0, speed=9)
    assert rig.op.status(48) == LOOP0_S48 == -8388608
    rig.step(400)  # 10 cycles
    assert rig.op.state is CamState.SYNC and rig.op.status(48) == -8388608
    cmd = rig.op.stop()
    assert rig.op.state is CamState.IDLE and not rig.op.output(16)
    rig.until(lambda: cmd.done)
    assert rig.axis.state is AxisState.STANDSTILL


def test_loop_range():
    rig = Rig()
    rig.op.setc(1)
    for bad in (-1, 65001, 1.5):
        with pytest.raises(CompaxError):
            rig.op.loop(bad)


def test_coupling_m_e_m_s_0_p34_0_works_with_a_negative_master():
    # §2.11: "In this setting, the slave can be coupled even if the master movement is negative."
    rig = Rig()
    rig.op.setc(1)
    rig.op.setm(50.0)
    rig.start_master(-2)
    rig.step(3)
    assert rig.op.status(46) == 1
    rig.op.loop(0)
    rig.inputs["I13"] = True
    rig.step()
    assert rig.op.state is CamState.SYNC and rig.op.output(16)
    p = rig.p
    rig.step(10)
    assert rig.p == pytest.approx(p - 20.0)


def test_reset_mode_keeps_the_actual_value_between_curve_start_and_end():
    # §2.1 P93 = 3: "The indicated actual slave value is moving between curve start and curve
    # end during the whole cam operation." The motion itself stays continuous.
    rig = coupled(Rig(P93=3), m=0, speed=7)
    rig.record = True
    lo, hi = 0.0, 0.0
    for _ in range(2000):
        rig.step()
        s1 = rig.op.status(1)
        lo, hi = min(lo, s1), max(hi, s1)
    assert lo >= 0.0 and hi <= 360.0
    v = [r[2] for r in rig.trace]
    assert min(v) == pytest.approx(7000.0) and max(v) == pytest.approx(7000.0)
    assert rig.axis.following_error == pytest.approx(0.0, abs=1e-9)
    # the plant moved on continuously: 2000 cycles * 7 increments
    assert rig.x == pytest.approx(2000 * 7.0)


def test_normal_mode_keeps_the_absolute_reference():
    rig = coupled(Rig(P93=1), m=0, speed=7)
    rig.step(2000)
    assert rig.op.status(1) == pytest.approx(2000 * 7.0)
    assert 0.0 <= rig.op.status(45) < 1000.0  # S45 stays the curve value in per mille


def test_closed_curve_is_not_reset():
    closed = Curve(set_points=[0.0, 0.5, 0.0])
    rig = coupled(Rig({1: closed}, P93=3), m=0, speed=6)
    rig.step(30)  # master 180: slave at the curve's top
    assert rig.p == pytest.approx(180.0)
    rig.step(30)
    assert rig.p == pytest.approx(0.0, abs=1e-9)
    assert rig.axis.position_offset == 0.0


def test_loop_folds_the_slave_into_the_slave_cycle():
    # decision D8 / §11.1.1: "In case of the actual slave position exceeding the slave cycle at
    # the moment of the curve entering (LOOP) both the set position and the actual position are
    # counted back by n·S_T."
    rig = Rig(P93=1)
    rig.axis.set_position(1000.0)
    rig.op.setc(1)
    rig.op.loop(0)
    assert rig.op.status(1) == pytest.approx(280.0) and rig.p == pytest.approx(280.0)
    # with SETS before LOOP there is no fold: the curve is aligned to the slave
    rig2 = Rig(P93=1)
    rig2.axis.set_position(1000.0)
    rig2.op.setc(1)
    rig2.op.sets()
    rig2.op.loop(0)
    assert rig2.p == 1000.0


def test_commands_are_refused_while_the_loop_is_active():
    # decision D11 (§11.2 "the LOOP-command is still active and COMPAX does not carry out any commands")
    rig = coupled(Rig(), m=0, speed=1)
    for command in (lambda: rig.op.setc(1), lambda: rig.op.setm(0.0), rig.op.sets, rig.op.posr_cam,
                    lambda: rig.op.loop(2)):
        with pytest.raises(CompaxError) as e:
            command()
        assert e.value.code == 107


def test_commands_without_a_curve_have_no_effect():
    # "This command only becomes efficient after a curve has been selected. Exception: SETM 0"
    rig = Rig()
    rig.op.setm(40.0)
    assert rig.chain.s44 == 0.0
    rig.op.sets()
    assert rig.op.posr_cam() is None
    rig.op.loop(3)
    assert not rig.op.loop_active


def test_endless_posr_cam_moves_by_the_curve_set_point():
    # decision D10 (§2.8 note on endless operation): the actual position is set to 0 at the start
    rig = Rig(P93=2)
    rig.axis.set_position(5000.0)
    rig.op.setc(1)
    rig.op.setm(25.0)
    cmd = rig.op.posr_cam()
    rig.until(lambda: cmd.done)
    assert rig.p == pytest.approx(90.0)
    assert rig.x == pytest.approx(90.0)  # moved 90 on the plant


def test_speed_control_mode_refuses_loop():
    rig = Rig(P93=4)
    rig.op.setc(1)
    with pytest.raises(CompaxError):
        rig.op.loop(1)


def test_p36_taken_at_the_curve_zero_point():
    # decision D9 / §3.1 footnote 5: "P36, after VP, is only accepted at the next curve zero point or with SETC"
    rig = coupled(Rig(P93=1), m=0, speed=4)
    rig.step(45)  # master 180
    assert rig.p == pytest.approx(180.0)
    rig.params[36] = 2.0
    rig.step(10)
    assert rig.p == pytest.approx(220.0)  # not yet
    rig.step(35)  # the wrap at 360: the finished cycle counted with P36 = 1
    assert rig.p == pytest.approx(360.0)
    rig.step(10)
    assert rig.p == pytest.approx(360.0 + 2 * 40.0)
    assert rig.op.status(45) == pytest.approx(1000 * 40 / 360)


def test_status_values():
    rig = coupled(Rig(P93=1, P143=90), m=5, speed=6)
    rig.step(20)
    op = rig.op
    assert op.status(41) == pytest.approx(6 * 60000 / 360)  # 1000 master cycles per minute
    assert op.status(42) == 120 and op.status(44) == pytest.approx(1000 * 120 / 360)
    assert op.status(43) == 1 and op.status(46) == 0
    assert op.status(47) == pytest.approx(120.0) and op.status(45) == pytest.approx(1000 * 120 / 360)
    assert op.status(1) == pytest.approx(120.0) and op.status(2) == 5
    assert op.status(48) == 5
    rig.params[233] = 33  # cycle counter (§2.19 optimizing indicator 33)
    rig.params[234] = 37  # encoder frequency [incr/ms]
    assert op.status(13) == pytest.approx(120 / 360) and op.status(14) == 6
    with pytest.raises(CompaxError):
        op.status(99)


def test_drift_free_scaled_curve_16523_over_11872():
    # §7 X19 / §2.20 / Appendix B drift_free_gear: straight line (0,0)-(11872, 16523) with
    # P35 = P36 = 1, P83 = P98 = 1024, P90 = 0 (increments): synchronous without drift.
    i_m = Fraction(20, 63) * Fraction(26, 64) * Fraction(6, 53)
    i_s = Fraction(20, 82) * Fraction(8, 33) * Fraction(11, 62)
    assert i_m / i_s == Fraction(16523, 11872)
    gear = Curve(master_cycle=11872.0, slave_cycle=16523.0, set_points=[0.0, FULL])
    rig = Rig({1: gear}, P93=1, P98=1024.0, P143=1024)  # M_T* = 11872·4096/1024 = 47488
    rig.op.setc(1)
    assert rig.chain.scaled_cycle == 47488.0
    coupled(rig, m=0)
    total = 0
    for k in range(50000):  # about 40 000 master cycles
        d = 30_000 + (k * 7919) % 9973  # irregular master motion, ~0.8 master cycles per ms
        rig.speed = d
        total += d
        rig.step()
    # the slave is exactly S_T/M_T* per master increment: 16523 / 47488
    exact = Fraction(total) * Fraction(16523, 47488)
    assert abs(Fraction(rig.p) - exact) < Fraction(1, 10**6)
    assert rig.op.status(48) == LOOP0_S48
    # and in reset mode the same run stays inside one slave cycle, still exact
    rig2 = Rig({1: gear}, P93=3, P98=1024.0, P143=1024)
    coupled(rig2, m=0)
    rig2.speed = 47488 // 2 + 1
    rig2.step(4000)
    exact2 = (Fraction(4000 * (47488 // 2 + 1)) % 47488) * Fraction(16523, 47488)
    assert abs(Fraction(rig2.p) - exact2) < Fraction(1, 10**8)


def test_operation_parameters_as_arguments():
    # §2.8 "The commands SETC n, SETM x and LOOP m may also refer to the operation parameters;
    # (P40...P49); i. e. SETC .P40, SETM .P40, LOOP .P40."
    rig = Rig({2: line(number=2)}, P40=2, P41=25.0, P42=3)
    rig.op.setc(".P40")
    rig.op.setm(".P41")
    assert rig.op.status(43) == 2 and rig.chain.s44 == pytest.approx(250.0)
    rig.op.loop(".P42")
    assert rig.op.status(48) == 3
    with pytest.raises(CompaxError):
        rig.op.setc(".P39")


def _quantised_run(p68: float, cycles: int = 400) -> tuple[list[float], list[float]]:
    """A master encoder that counts 3 and 4 increments in turn (3.5 per ms: quantisation noise of a
    low-resolution master channel); the slave on the straight line. Returns (positions, speeds)."""
    rig = Rig(P68=p68)
    coupled(rig)
    rig.record = True
    for k in range(cycles):
        rig.speed = 3 + k % 2
        rig.step()
    tail = rig.trace[-200:]
    return [r[1] for r in tail], [r[2] for r in tail]


def test_p68_filters_the_speed_feed_forward_only():
    # D19: P68 (compax.md §2.1 "optional filter P68", §3 "Only use filter P68, if quantization
    # noises can be heard due to low resolution in the master channel"): PT1, T_f = P68 % of 1 ms
    p0, v0 = _quantised_run(0.0)
    p2, v2 = _quantised_run(200.0)  # T_f = 2 ms: alpha = 1/3, the 3-4-3-4 ripple x alpha / (2 - alpha) = 0.2
    ripple0 = max(v0) - min(v0)
    ripple2 = max(v2) - min(v2)
    assert ripple0 == pytest.approx(1000.0, rel=1e-6)  # 3 vs 4 deg per ms: 1000 deg/s peak to peak
    assert ripple2 == pytest.approx(0.2 * ripple0, rel=1e-3)
    assert sum(v2) / len(v2) == pytest.approx(3500.0, rel=1e-3)  # the mean speed is kept
    assert p2 == pytest.approx(p0)  # the position set point is not filtered


def test_p68_0_is_off():
    # P68 = 0 "filter switched off": the feed-forward follows the master speed at once
    _, v0 = _quantised_run(0.0, cycles=50)
    assert v0[-1] in (3000.0, 4000.0) and abs(v0[-1] - v0[-2]) == pytest.approx(1000.0)
