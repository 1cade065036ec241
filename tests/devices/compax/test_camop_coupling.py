"""COMPAX coupling and decoupling on the fly: every case of the manual's tables (compax.md §2.11,
manual §11.1.1, §11.2.1, §12, §8.2.1; §7 X25, X26)."""

from __future__ import annotations

import numpy as np
import pytest

from axisline.devices.compax.camop import CamState

from .test_camop_rig import T, Rig, line

SPEED = 2  # master increments (= degrees) per ms: 180 ms per master cycle of 360


def rig_for(p34: int, speed: int = SPEED, p93: int = 1, **curve) -> Rig:
    rig = Rig({1: line(**curve)}, P34=p34, P93=p93)
    rig.op.setc(1)
    rig.op.setm(0.0)
    rig.start_master(speed)
    rig.op.loop(0)
    rig.record = True
    return rig


def master_deg(rig: Rig) -> float:
    return rig.chain.position


def run_to(rig: Rig, deg: float) -> None:
    """Step until the master (in the cycle) is at `deg` (exactly, speed divides it)."""
    rig.until(lambda: abs(master_deg(rig) - deg) < 1e-9)


def assert_continuous(trace, v_bound=1e5, a_bound=1e7):
    """No step in position or velocity: each cycle's change is what the velocity (acceleration)
    at its ends explains, to 1 % (5 %) of a cycle's travel at the peak speed (acceleration)."""
    p = np.array([r[1] for r in trace])
    v = np.array([r[2] for r in trace])
    a = np.array([r[3] for r in trace])
    dp = np.diff(p) - (v[1:] + v[:-1]) / 2 * T
    dv = np.diff(v) - (a[1:] + a[:-1]) / 2 * T
    assert np.max(np.abs(dp)) <= 0.01 * np.max(np.abs(v)) * T + 1e-9, int(np.argmax(np.abs(dp)))
    assert np.max(np.abs(dv)) <= 0.05 * np.max(np.abs(a)) * T + 1e-6, int(np.argmax(np.abs(dv)))
    assert np.max(np.abs(v)) <= v_bound and np.max(np.abs(a)) <= a_bound


# -------------------------------------------------------------------------------- coupling


def test_p34_0_me_ms_0_adjusts_at_once_the_slave_does_not_travel():
    # §2.11 "By I13="1" there will be carried out an automatic curve adjustment i. e. the actual
    # slave position will be equated with the actual curve position of the slave (slave does not travel)."
    rig = rig_for(0)
    rig.step(50)  # master at 100
    rig.inputs["I13"] = True
    rig.step()
    assert rig.op.state is CamState.SYNC and rig.op.output(16)
    assert rig.p == 0.0 and rig.op.status(47) == pytest.approx(0.0)
    rig.step(10)
    assert rig.p == pytest.approx(20.0)  # "the slave has to bear a speed leap at the curve start"


def test_p34_1_me_ms_0_adjusts_at_the_beginning_of_the_next_master_cycle():
    # §2.11 "By I13="1" an automatic curve adjustment will be carried out at the beginning of the
    # next master cycle (as M_E=M_S=0)."
    rig = rig_for(1)
    rig.step(50)
    rig.inputs["I13"] = True
    rig.step()
    assert rig.op.state is CamState.WAIT_COUPLE and not rig.op.output(16)
    run_to(rig, 358.0)
    assert rig.p == 0.0
    rig.step()  # master 0: the curve zero point is put on the slave
    assert rig.op.state is CamState.SYNC and rig.op.output(16)
    assert rig.p == pytest.approx(0.0)
    rig.step(5)
    assert rig.p == pytest.approx(10.0)


def test_p34_1_me_ms_equal_waits_for_me_then_follows_with_a_speed_leap():
    # §2.11 "After I13="1", the slave waits for the master position M_E and then immediately
    # follows the curve synchronously with an automatic curve compensation."
    rig = rig_for(1, coupling=0.3, synchronous=0.3)
    rig.step(20)  # master 40
    rig.inputs["I13"] = True
    run_to(rig, 106.0)
    assert rig.op.state is CamState.WAIT_COUPLE and rig.p == 0.0
    rig.step()  # master 108 = M_E
    assert rig.op.state is CamState.SYNC and rig.p == pytest.approx(0.0)
    rig.step()
    assert rig.p == pytest.approx(2.0) and rig.axis.command_velocity == pytest.approx(2000.0)


def test_p34_1_me_below_ms_couples_smoothly_from_me_to_ms():
    # §2.11 / X25 (d): M_E = 0.1, M_S = 0.6 (the manual's example curve): starts at 0.1·M_T,
    # synchronous (O16 = 1) at 0.6·M_T, no speed discontinuity
    rig = rig_for(1, coupling=0.1, synchronous=0.6)
    rig.inputs["I13"] = True
    rig.step()
    run_to(rig, 36.0)
    assert rig.op.state is CamState.COUPLING and rig.p == pytest.approx(0.0)
    run_to(rig, 214.0)
    assert rig.op.state is CamState.COUPLING and not rig.op.output(16)
    rig.step()  # 216 = M_S
    assert rig.op.state is CamState.SYNC and rig.op.output(16)
    assert rig.p == pytest.approx(216.0)  # on the curve (offset 0: curve start = slave zero)
    rig.step(20)
    assert_continuous(rig.trace, v_bound=2000 * 3.0)
    assert rig.axis.command_velocity == pytest.approx(2000.0)


def test_p34_0_me_ignored_coupling_starts_at_i13_and_is_synchronous_at_ms():
    # decision D3: at P34 = 0 M_E is "insignificant": the coupling movement starts with I13 = 1
    for me, ms in ((0.1, 0.6), (0.3, 0.3)):
        rig = rig_for(0, coupling=me, synchronous=ms)
        rig.step(20)  # master 40
        rig.inputs["I13"] = True
        rig.step()
        assert rig.op.state is CamState.COUPLING
        rig.until(lambda: rig.op.state is CamState.SYNC)
        assert master_deg(rig) == pytest.approx(ms * 360.0)
        assert rig.p == pytest.approx(ms * 360.0)
        assert_continuous(rig.trace, v_bound=2000 * 6.0)


def test_coupling_only_with_a_rising_master():
    # §2.11 "Coupling only occurs, with one exception (where M_E=M_S=0 and P34="0"), when the
    # master movement is in the positive direction (S46="0")." D5: the request waits.
    rig = rig_for(1, speed=-2, coupling=0.1, synchronous=0.6)
    rig.step(5)
    rig.inputs["I13"] = True
    rig.step(200)
    assert rig.op.state is CamState.READY and rig.p == 0.0
    rig.speed = 2
    rig.step(2)
    assert rig.op.state is CamState.WAIT_COUPLE


def test_small_coupling_position_is_recognised_when_read_below():
    # decision D4: M_E = 0.005 (1.8 deg) is recognised when a sample below it was read in the cycle
    rig = rig_for(1, speed=5, coupling=0.005, synchronous=0.5)
    run_to(rig, 350.0)
    rig.inputs["I13"] = True
    rig.step()  # 355: waiting; not below M_E in this cycle
    rig.step()  # 360 -> 0: the wrap, read below M_E
    assert rig.op.state is CamState.WAIT_COUPLE
    rig.step()  # 5 >= 1.8: recognised (the blend starts at 1.8)
    assert rig.op.state is CamState.COUPLING and rig.op._U0 == pytest.approx(1.005)


def test_small_coupling_position_not_undershot_is_not_recognised():
    # §2.11 note: "If M_E or M_A is not undershot, then the coupling position or the decoupling
    # position is not recognised." A master moving 9 deg per ms reads 3 deg after every wrap.
    rig = rig_for(1, speed=6, coupling=0.005, synchronous=0.5)
    run_to(rig, 348.0)
    rig.inputs["I13"] = True
    rig.step()  # 354: waiting
    rig.speed = 9
    rig.step(200)  # 363 -> 3, ...: never read below 1.8
    assert rig.op.state is CamState.WAIT_COUPLE and rig.op._K >= 4
    rig.speed = 2  # slower: a sample below M_E after the next wrap
    rig.until(lambda: rig.op.state is CamState.COUPLING)


# -------------------------------------------------------------------------------- decoupling


def synchronous(rig: Rig, deg: float = 0.0) -> Rig:
    """Couple (with a standing master for M_E = M_S = 0, P34 = 0: slave = master position)."""
    speed, rig.speed = rig.speed, 0
    rig.inputs["I13"] = True
    rig.step()
    rig.speed = speed
    assert rig.op.state in (CamState.SYNC, CamState.WAIT_COUPLE, CamState.COUPLING)
    rig.until(lambda: rig.op.state is CamState.SYNC)
    if deg:
        run_to(rig, deg)
    return rig


def test_p34_0_ma_mb_0_stops_immediately():
    # §2.11 "By I13="0" the slave can be stopped immediately." (speed leap; S_0 not considered)
    rig = synchronous(rig_for(0, standstill=0.5), 100.0)
    rig.inputs["I13"] = False
    rig.step()
    assert rig.op.state is CamState.READY and not rig.op.output(16)
    p = rig.p
    assert p == pytest.approx(102.0) and rig.axis.command_velocity == 0.0
    rig.step(50)
    assert rig.p == p and rig.op.loop_active  # LOOP still active ("Curve ready")


def test_p34_0_ma_mb_0_decouples_with_a_negative_master():
    rig = synchronous(rig_for(0), 100.0)
    rig.speed = -2
    rig.step(3)
    rig.inputs["I13"] = False
    rig.step()
    assert rig.op.state is CamState.READY


def test_p34_1_ma_mb_0_stops_at_the_beginning_of_the_next_master_cycle():
    # §2.11 "By I13="0" the slave will only be stopped at the beginning of the next master cycle"
    rig = synchronous(rig_for(1), 100.0)
    rig.inputs["I13"] = False
    rig.step()
    assert rig.op.state is CamState.WAIT_DECOUPLE and rig.op.output(16)
    rig.until(lambda: rig.op.state is CamState.READY)
    assert rig.p == pytest.approx(360.0) and master_deg(rig) == pytest.approx(0.0)


def test_p34_0_ma_mb_equal_decouples_to_s0_at_mb():
    # §2.11 "By I13="0" the decoupling is started. At the master position M_B the slave is on
    # standstill position S_0."
    rig = synchronous(rig_for(0, decoupling=0.3, braking=0.3, standstill=0.5), 20.0)
    rig.trace.clear()
    rig.inputs["I13"] = False
    rig.step()
    assert rig.op.state is CamState.DECOUPLING
    rig.until(lambda: rig.op.state is CamState.READY)
    assert master_deg(rig) == pytest.approx(108.0)
    assert rig.p == pytest.approx(180.0) and rig.axis.command_velocity == 0.0
    assert_continuous(rig.trace, v_bound=2000 * 10.0, a_bound=1e8)


def test_p34_1_ma_mb_equal_waits_for_ma_then_stops_jerkily():
    # §2.11 "After I13="0" the slave waits for the master position M_A and then will stop
    # jerkily. A leap of the rotational speed will occur."
    rig = synchronous(rig_for(1, decoupling=0.3, braking=0.3, standstill=0.5), 20.0)
    rig.inputs["I13"] = False
    rig.step()
    assert rig.op.state is CamState.WAIT_DECOUPLE
    rig.until(lambda: rig.op.state is CamState.READY)
    assert master_deg(rig) == pytest.approx(108.0) and rig.p == pytest.approx(108.0)


def test_p34_0_ma_below_mb_decouples_from_i13_to_s0_at_mb():
    rig = synchronous(rig_for(0, decoupling=0.2, braking=0.7, standstill=-0.1), 20.0)
    rig.inputs["I13"] = False
    rig.step()
    assert rig.op.state is CamState.DECOUPLING
    rig.until(lambda: rig.op.state is CamState.READY)
    assert master_deg(rig) == pytest.approx(252.0)
    assert rig.p == pytest.approx(-36.0)  # S_0 = -0.1·S_T: "retraction" behind the curve start (D7)


def test_p34_1_ma_below_mb_waits_for_ma_blends_to_s0_at_mb():
    # X25 mirror: M_A = 0.2, M_B = 0.7, S_0 = -0.1·S_T (the manual's example control block)
    rig = synchronous(rig_for(1, coupling=0.1, synchronous=0.6, decoupling=0.2, braking=0.7, standstill=-0.1))
    run_to(rig, 300.0)
    rig.trace.clear()
    rig.inputs["I13"] = False
    rig.step()
    assert rig.op.state is CamState.WAIT_DECOUPLE and rig.op.output(16)
    rig.until(lambda: rig.op.state is CamState.DECOUPLING)
    assert master_deg(rig) == pytest.approx(72.0)  # the sample at M_A
    assert not rig.op.output(16)
    rig.until(lambda: rig.op.state is CamState.READY)
    assert master_deg(rig) == pytest.approx(252.0)
    assert rig.p == pytest.approx(360.0 - 36.0)  # S_0 of the master cycle in which M_B is reached
    assert_continuous(rig.trace, v_bound=2000 * 5.0)


def test_after_decoupling_i13_couples_again():
    rig = synchronous(rig_for(1, coupling=0.1, synchronous=0.6, decoupling=0.2, braking=0.7, standstill=0.0))
    rig.inputs["I13"] = False
    rig.until(lambda: rig.op.state is CamState.READY)
    rig.inputs["I13"] = True
    rig.until(lambda: rig.op.state is CamState.SYNC)
    assert rig.op.loop_active and rig.op.output(16)


def test_p34_bit_1_leaves_curve_mode_after_decoupling():
    # §12 "P34 = 2 or 3 (Bit 1 in P34): "Leave curve mode after decoupling" ... regardless of the
    # condition of the loop counter"
    rig = synchronous(rig_for(3, decoupling=0.2, braking=0.7, standstill=0.0))
    rig.inputs["I13"] = False
    rig.until(lambda: rig.op.state is CamState.IDLE)
    assert not rig.op.loop_active
    rig.step(3)
    assert rig.axis.state.value == "Standstill"


def test_decoupling_at_the_end_of_the_loop_uses_the_decoupling_mode():
    # §2.11 "The above cases are also valid if the slave terminates the cam operation after the
    # LOOP-command has been carried out, i. e. the loop counter reaches zero."
    rig = Rig({1: line(decoupling=0.2, braking=0.7, standstill=0.0)}, P34=1, P93=1)
    rig.op.setc(1)
    rig.op.setm(0.0)
    rig.start_master(0)
    rig.op.loop(1)
    rig.inputs["I13"] = True
    rig.step()
    rig.speed = SPEED
    rig.until(lambda: rig.op.status(48) == 0)
    assert rig.op.state is CamState.WAIT_DECOUPLE
    rig.until(lambda: not rig.op.loop_active)
    assert master_deg(rig) == pytest.approx(252.0) and rig.p == pytest.approx(360.0)


def test_s0_equal_st_couples_from_0_continuous_forward():
    # §8.2.1 / X26: "Decoupling on position S_0 = S_T. Coupling from 0. This results in a continuous
    # forward movement of the slave": the slave position never decreases across decouple/couple
    for p93 in (1, 3):
        rig = synchronous(rig_for(1, p93=p93, coupling=0.1, synchronous=0.6, decoupling=0.2, braking=0.7,
                                  standstill=1.0))
        travelled = 0.0
        last = rig.x
        for _ in range(3):
            rig.inputs["I13"] = False
            rig.until(lambda: rig.op.state is CamState.READY)
            rig.inputs["I13"] = True
            rig.until(lambda: rig.op.state is CamState.SYNC)
            rig.step(100)
        p = np.array([r[1] for r in rig.trace])
        v = np.array([r[2] for r in rig.trace])
        assert v.min() >= -1e-9
        travelled = rig.x - last
        assert travelled > 0
        if p93 == 3:
            assert 0.0 <= rig.op.status(1) <= 360.0
        else:
            assert np.all(np.diff(p) >= -1e-9)


def test_s0_equal_st_stop_position_is_the_curve_end():
    rig = synchronous(rig_for(1, coupling=0.1, synchronous=0.6, decoupling=0.2, braking=0.7, standstill=1.0))
    run_to(rig, 300.0)
    rig.inputs["I13"] = False
    rig.until(lambda: rig.op.state is CamState.READY)
    assert rig.p == pytest.approx(720.0)  # S_T of the cycle in which M_B (252) is reached
    assert rig.op.curve_value() == pytest.approx(720.0 + 252.0)  # the curve continues from 0 of the next cycle


def test_i13_edge_rules():
    # decision D5
    rig = rig_for(1, coupling=0.1, synchronous=0.6, decoupling=0.2, braking=0.7, standstill=0.0)
    rig.inputs["I13"] = True
    rig.step()
    assert rig.op.state is CamState.WAIT_COUPLE
    rig.inputs["I13"] = False  # I13 = 0 while waiting for M_E cancels the coupling
    rig.step()
    assert rig.op.state is CamState.READY
    rig.inputs["I13"] = True
    rig.until(lambda: rig.op.state is CamState.COUPLING)
    rig.inputs["I13"] = False  # during the coupling movement: decouples once synchronous
    rig.until(lambda: rig.op.state is not CamState.COUPLING)
    assert rig.op.state in (CamState.WAIT_DECOUPLE, CamState.DECOUPLING)
    rig.until(lambda: rig.op.state is CamState.DECOUPLING)
    rig.inputs["I13"] = True  # during the decoupling movement: ignored
    rig.until(lambda: rig.op.state is CamState.READY)
    rig.step(400)
    assert rig.op.state is CamState.READY  # the edge came while the slave was moving
    rig.inputs["I13"] = False
    rig.step()
    rig.inputs["I13"] = True
    rig.until(lambda: rig.op.state is CamState.SYNC)
    rig.inputs["I13"] = False
    rig.step()
    assert rig.op.state is CamState.WAIT_DECOUPLE
    rig.inputs["I13"] = True  # before M_A: the decoupling is cancelled
    rig.step()
    assert rig.op.state is CamState.SYNC
    rig.step(400)
    assert rig.op.state is CamState.SYNC


def test_loop_with_i13_already_1_couples():
    rig = Rig({1: line()}, P34=0)
    rig.op.setc(1)
    rig.inputs["I13"] = True
    rig.step()
    rig.op.loop(0)
    rig.step()
    assert rig.op.state is CamState.SYNC


def test_stop_interrupts_and_posr_cam_re_enters_seamlessly():
    # §2.11 (§12.0.1) re-entry: STOP; the slave is moved; POSR CAM to the curve value of the master
    # position; LOOP with M_E = M_S, P34 = 0: "If the master now starts up, the slave will start up simultaneously."
    rig = synchronous(rig_for(0, p93=1), 100.0)
    rig.speed = 0
    cmd = rig.op.stop()
    rig.until(lambda: cmd.done)
    assert rig.op.state is CamState.IDLE and not rig.op.output(16)
    m = rig.axis.move_relative(-77.0)
    rig.until(lambda: m.done)
    cmd = rig.op.posr_cam()
    rig.until(lambda: cmd.done)
    assert rig.p == pytest.approx(100.0)
    rig.op.loop(0)
    rig.inputs["I13"] = False
    rig.step()
    rig.inputs["I13"] = True
    rig.step()
    rig.speed = 2
    rig.step(50)
    assert rig.p == pytest.approx(200.0) and rig.op.output(16)
