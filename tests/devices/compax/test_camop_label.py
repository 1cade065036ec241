"""COMPAX label synchronisation (label.py): compax.md §2.13, §2.14 (P32/P33), §2.18 O14, §7 X9 ... X13,
Appendix B p180_examples, label_timing_error, label_window_max_fraction_of_MT."""

from __future__ import annotations

import math

import pytest

from axisline.devices.compax.camop import CamState
from axisline.devices.compax.label import LabelSync, poll_fraction

from .test_camop_rig import Rig, line

M_T = 360.0  # 360 increments per master cycle (P143 = 90, P98 = 360)


class Labels:
    """Labels on the product at true master positions (increments): k·pitch + first."""

    def __init__(self, rig: Rig, first: float, pitch: float = 360.0, slip: float = 0.0) -> None:
        self.rig, self.first, self.pitch, self.slip = rig, first, pitch, slip
        self.on = True
        self.origin = rig.enc.counts  # encoder count where the master chain started counting (position 0)

    def edges(self, c0: float, c1: float) -> list[tuple[float, bool]]:
        """Label edges (fraction, rising) while the encoder goes c0 -> c1 (a label is 5 increments long)."""
        out = []
        if not self.on or c1 <= c0:
            return out
        c0 -= self.origin
        c1 -= self.origin
        scale = 1.0 / (1.0 - self.slip)  # the product lags the master by the slip
        k = math.floor((c0 / scale - self.first) / self.pitch)
        for n in range(k - 1, k + 3):
            start = (n * self.pitch + self.first) * scale
            for x, rising in ((start, True), (start + 5.0, False)):
                if c0 < x <= c1:
                    out.append(((x - c0) / (c1 - c0), rising))
        out.sort()
        return out


def master_rig(*, p180=0.0, ref=0.5, window=0.2, k1=0.0, k2=0.0, p32=0.0, p33=1, speed=4, **params) -> Rig:
    curve = line(label_set_point=ref, label_window=window, correction_enable=k1, correction_disable=k2)
    rig = Rig({1: curve}, label=LabelSync(), P33=p33, P180=p180, P32=p32, **params)
    rig.op.setc(1)
    rig.op.setm(0.0)
    rig.op.loop(0)
    rig.inputs["I13"] = True
    rig.start_master(speed)
    return rig


def run_labels(rig: Rig, labels: Labels, cycles: int) -> list[tuple[float, float]]:
    """Step; returns (S51, S52) of each label accepted."""
    out = []
    for _ in range(cycles):
        c0 = rig.enc.counts
        c1 = c0 + rig.speed
        before = rig.op.label.s51, rig.op.label.s52, rig.op.label.correction.requested
        rig.step(i14_edges=labels.edges(c0, c1))
        after = rig.op.label.s51, rig.op.label.s52, rig.op.label.correction.requested
        if after != before:
            out.append(after[:2])
    return out


def test_internal_reference_master_related_x12():
    # §7 X12: M_M = 0.5·M_T, P32 = 0.7·M_T => M_ref = 0.5 - 0.7 + 1 = 0.8·M_T => S50 = 800 ‰ => SETM 80
    curve = line(label_set_point=0.5, label_window=0.05)
    rig = Rig({1: curve}, label=LabelSync(), P33=1, P32=0.7 * M_T)
    rig.op.setc(1)
    assert rig.op.status(50) == pytest.approx(800.0)
    rig.op.setm(rig.op.status(50) / 10)  # "SETM x" with x = S50/10
    assert rig.op.status(44) == pytest.approx(800.0)


def test_internal_reference_slave_related_x13():
    # §7 X13: S_T = 360, S_M = 180, P32 = 300 => S_ref = (S_M - P32) + S_T = 240
    curve = line(label_set_point=0.5, label_window=0.1)
    rig = Rig({1: curve}, label=LabelSync(), P33=2, P32=300.0)
    rig.op.setc(1)
    assert rig.op.status(50) == pytest.approx(1000 * 240 / 360)


def test_master_related_label_converges():
    # L1: the labels lag the master by a 0.5 % slip; the label lands on S50 within the slip of a cycle
    rig = master_rig(ref=0.5, window=0.1, k1=0.6, k2=0.9)
    labels = Labels(rig, first=0.62 * M_T, slip=0.005)
    accepted = run_labels(rig, labels, 90 * 12)
    assert len(accepted) == 12
    # the first label, without the window: 223.2 / 0.995 = 224.3 increments, seen up to 0.1 ms late
    assert accepted[0] == pytest.approx((623.2, 123.2), abs=1.0)
    for s51, s52 in accepted[3:]:
        assert abs(s52) <= 1000 * 0.005 / (1 - 0.005) + 0.2 + 1.0  # one cycle's slip (+ 100 µs sampling)
    assert rig.op.label.o14 and rig.op.output(14)
    assert rig.op.state is CamState.SYNC


def test_corrections_only_between_mk1_and_mk2():
    # §2.13 M_k1 / M_k2: "If M_k1 > M_k2, corrections are implemented past the cycle."
    rig = master_rig(ref=0.5, window=0.2, k1=0.9, k2=0.1)
    labels = Labels(rig, first=0.6 * M_T)
    applied_at = []
    for _ in range(90 * 3):
        c0 = rig.enc.counts
        before = rig.op.label.correction.applied
        rig.step(i14_edges=labels.edges(c0, c0 + rig.speed))
        if rig.op.label.correction.applied != before:
            applied_at.append(rig.chain.s44)
    assert applied_at and all(s44 >= 890.0 or s44 <= 110.0 for s44 in applied_at)


@pytest.mark.parametrize(
    "p180, per_cycle",
    [(10.0, [10.0, 10.0, 10.0, 10.0, 0.0]), (30.0, [30.0, 10.0, 0.0, 0.0, 0.0]), (0.0, [40.0, 0.0, 0.0, 0.0, 0.0]),
     (100.0, [40.0, 0.0, 0.0, 0.0, 0.0])],
)
def test_p180_examples(p180, per_cycle):
    # §7 X11 / Appendix B p180_examples: "Correction value = 40% MF = 20% and P180 = 10%: 10%
    # corrections are carried out in each of 4 cycles." / "P180 = 30%: In the 1st cycle 30% is
    # corrected, in the 2nd cycle 10%." / P180 = 0, 100: initial correction unlimited.
    rig = master_rig(p180=p180, ref=0.5, window=0.2, k1=0.0, k2=0.3)
    labels = Labels(rig, first=0.9 * M_T)  # 40 % after the reference
    run_labels(rig, labels, 90)  # the first label (at 0.9) is taken; its correction runs in the next 0 ... 0.3
    corrected = []
    for _ in range(len(per_cycle)):
        before = rig.op.label.correction.applied
        run_labels(rig, labels, 90)
        corrected.append(round(100 * (rig.op.label.correction.applied - before), 6))
    assert corrected == pytest.approx(per_cycle)
    assert rig.op.status(52) == pytest.approx(0.0, abs=1.5)


def test_first_label_without_window_then_outside_ignored():
    # §2.13 P180 = 0: "Follow-up corrections are then only implemented when the label lies within
    # the label window after the initial correction"
    rig = master_rig(p180=0.0, ref=0.5, window=0.05, k1=0.0, k2=0.3)
    labels = Labels(rig, first=0.8 * M_T)
    run_labels(rig, labels, 90 * 2)
    assert rig.op.label.correction.applied == pytest.approx(0.3)
    labels.first = 0.2 * M_T  # the label jumps 0.3 ... now 0.3 early in the corrected frame: outside
    before = rig.op.label.correction.applied
    run_labels(rig, labels, 90 * 3)
    assert rig.op.label.correction.applied == pytest.approx(before, abs=1e-12)
    assert not rig.op.output(14)  # the windows passed without a label: label missing


def test_o14_label_missing():
    # L3 (§19.2): O14 = 0 after power on; 1 at the first label; 0 after a window without a label,
    # until the next label is recognised
    rig = master_rig(ref=0.5, window=0.1, k1=0.6, k2=0.9)
    labels = Labels(rig, first=0.5 * M_T)
    assert not rig.op.output(14)
    run_labels(rig, labels, 90 * 2)
    assert rig.op.output(14)
    labels.on = False
    run_labels(rig, labels, 90)
    assert not rig.op.output(14)
    run_labels(rig, labels, 90 * 2)
    assert not rig.op.output(14)  # stays 0 across the next window too
    labels.on = True
    run_labels(rig, labels, 90 * 2)
    assert rig.op.output(14)


def test_stuck_high_i14_drifts_by_the_window_per_cycle():
    # §7 X10: M_T = 360, M_f = 18 (5 %), I14 permanently 1 => the master correction drifts by 18
    # units per cycle in the positive master direction
    rig = master_rig(ref=0.5, window=0.05, k1=0.7, k2=0.9)
    labels = Labels(rig, first=0.5 * M_T)
    run_labels(rig, labels, 90 * 3)
    applied = rig.op.label.correction.applied
    rig.step(20)  # outside the window
    rig.inputs["I14"] = True  # I14 goes to 1 (outside the window: ignored) and stays
    rig.step(70)
    for _ in range(4):
        before = rig.op.label.correction.applied
        lead = rig.chain.cycle_position - (rig.enc.counts - labels.origin) % 360
        rig.step(90)
        assert rig.op.label.correction.applied - before == pytest.approx(-0.05)
        assert rig.op.status(52) == pytest.approx(-50.0)
        # the master position runs 18 increments per cycle ahead of the encoder: positive drift
        assert (rig.chain.cycle_position - (rig.enc.counts - labels.origin) % 360 - lead) % 360 == pytest.approx(18.0)
    # five windows since I14 stuck (the first passed during the 70 cycles above): 5 · 18 deg forward
    assert rig.op.label.correction.applied == pytest.approx(applied - 0.25)


def test_label_timing_error():
    # §7 X9 / Appendix B label_timing_error: "The evaluation of I14 occurs in 100µs cycles. (This
    # results in an error of 0.18 degree ... at a master rotation speed of 300 min-1 and a master
    # cycle of 360 degree)."
    assert poll_fraction(0.31) == pytest.approx(0.4) and poll_fraction(0.3) == pytest.approx(0.3)
    rig = master_rig(ref=0.5, window=0.2, k1=0.6, k2=0.9, speed=9, P35=0.2)  # 1.8 deg per ms
    rig.step(10)
    assert rig.op.status(41) == pytest.approx(300.0)
    worst = 0.0
    for k in range(60):
        f = (k * 0.0731 + 0.013) % 1.0
        rig.op.label._restart()  # take every label (first measurement, no window)
        u0 = rig.chain.fraction
        rig.step(i14_edges=[(f, True)])
        u1 = rig.chain.fraction
        true = (u0 + ((u1 - u0) % 1.0) * f) * 360.0
        err = (rig.op.label.s51 * 0.36 - true + 180.0) % 360.0 - 180.0
        worst = max(worst, err)
        assert err >= -1e-9
        rig.step(i14_edges=[(0.9, False)])
    assert 0.1 < worst <= 0.18 + 1e-6
    assert 300 / 60 * 360 * 100e-6 == pytest.approx(0.18)


def test_short_pulse_is_not_seen():
    # L6: "The label impulse has to be longer than 100µs."
    rig = master_rig(ref=0.5, window=0.2)
    rig.step(i14_edges=[(0.31, True), (0.38, False)])
    assert rig.op.label.s51 == 0.0 and not rig.op.output(14)
    rig.step(i14_edges=[(0.31, True), (0.45, False)])
    assert rig.op.output(14)


def test_slave_related_label_converges():
    # §2.13 P33 = 2: the slave feeds the product; the product slips 0.5 % on the feed roller.
    # Corrections in the slave channel after the curve (L1): the labels end on S_ref.
    curve = line(label_set_point=0.5, label_window=0.1, correction_enable=0.6, correction_disable=0.9)
    rig = Rig({1: curve}, label=LabelSync(), P33=2, P32=0.0, P93=1)
    rig.op.setc(1)
    rig.op.setm(0.0)
    rig.op.loop(0)
    rig.inputs["I13"] = True
    rig.start_master(4)
    slip = 0.005
    first = 0.45 * 360.0  # on the product; the sensor sees it when the product has moved that far
    accepted = []
    x_before = rig.x
    for _ in range(90 * 12):
        x0 = rig.x
        x1 = x0 + (x0 - x_before)  # the slave moves on as in the last cycle (perfect drive)
        m0, m1 = x0 * (1 - slip), x1 * (1 - slip)
        edges = []
        k = math.floor((m0 - first) / 360.0)
        for n in (k, k + 1):
            for x, rising in ((n * 360.0 + first, True), (n * 360.0 + first + 5.0, False)):
                if m0 < x <= m1:
                    edges.append(((x - m0) / (m1 - m0), rising))
        before = rig.op.label.s51
        rig.step(i14_edges=sorted(edges))
        if rig.op.label.s51 != before:
            accepted.append(rig.op.status(52))
        x_before = x0
    assert rig.op.status(50) == pytest.approx(500.0)
    assert len(accepted) >= 10
    # first label without the window: product 162 seen at slave 162 / 0.995 (F = 0.4523), + up to 0.1 ms
    assert -47.8 - 0.1 <= accepted[0] <= -47.8 + 1.2
    for s52 in accepted[3:]:
        assert abs(s52) <= 1000 * slip + 1.0  # one cycle's slip
    assert rig.op.output(14)


def test_slave_related_only_while_synchronous():
    # §2.13 "The slave related label synchronization operates from the synchronous operation
    # (O16="1"). This is switched off during decoupling."
    curve = line(label_set_point=0.5, label_window=0.1)
    rig = Rig({1: curve}, label=LabelSync(), P33=2)
    rig.op.setc(1)
    rig.op.loop(0)
    rig.start_master(4)
    rig.step(i14_edges=[(0.5, True)])
    assert rig.op.label.s51 == 0.0  # not synchronous yet
    rig.inputs["I13"] = True
    rig.step(2)
    rig.step(i14_edges=[(0.5, True)])
    assert rig.op.output(14)


def test_p33_acceptance_at_loop_and_cycle_end():
    # L7 / §2.14: P33 = 0 ... 2 with LOOP; 10 ... 12 also at the end of the current cycle
    curve = line(label_set_point=0.5, label_window=0.1)
    rig = Rig({1: curve}, label=LabelSync(), P33=0)
    rig.op.setc(1)
    rig.op.loop(0)
    rig.inputs["I13"] = True
    rig.start_master(4)
    rig.params[33] = 1
    rig.step(100)  # a cycle end: not taken (only with LOOP)
    assert rig.op.label.mode == 0
    rig.params[33] = 11
    rig.step(100)
    assert rig.op.label.mode == 1 and rig.op.label.p33 == 11
    rig.params[33] = 12
    rig.step(100)
    assert rig.op.label.mode == 2


def test_setm_interrupts_master_related_label_synchronisation():
    rig = master_rig(ref=0.5, window=0.1, k1=0.6, k2=0.9)
    labels = Labels(rig, first=0.7 * M_T)
    run_labels(rig, labels, 70)
    assert rig.op.label.correction.pending != 0.0
    rig.op.stop()
    rig.step(10)
    rig.op.setm(0.0)
    assert rig.op.label.correction.pending == 0.0 and rig.op.label._first


def test_window_is_limited_to_0_3():
    # §2.13 "Restriction: M_f <= 0,3 * M_T" (L8)
    rig = master_rig(window=0.45)
    assert rig.op.label.window == 0.3


@pytest.mark.parametrize("p31", [2, 4])
def test_slave_related_setup_with_p31_2_or_4(p31):
    # §2.13 [CONFLICT] the detailed procedure says P31 = "2", the summary P31 = "4" (decision L10):
    # both enable the master with the first reference pulse on I16 after SETC; SETM 0 sets 0
    curve = line(label_set_point=0.5, label_window=0.1)
    rig = Rig({1: curve}, label=LabelSync(), P33=2, P31=p31)
    rig.inputs["I16"] = True  # the master's reference run passes the reference before SETC
    rig.step()
    rig.inputs["I16"] = False
    rig.step()
    rig.op.setc(1)
    rig.op.setm(0.0)
    rig.op.loop(0)
    rig.inputs["I13"] = True
    rig.speed = 4
    rig.step(20)
    assert not rig.chain.counting and rig.chain.s44 == 0.0
    rig.inputs["I16"] = True  # the reference pulse
    rig.step(3)
    rig.inputs["I16"] = False
    rig.step(40)
    assert rig.chain.counting and rig.op.state is CamState.SYNC
    assert rig.chain.cycle_position == 4 * 42


def test_slave_related_start_up_x13():
    # §7 X13: S_T = 360, S_M = 180, P32 = 300 => S_ref = 240; the first label at S_act = 100 gives
    # X = S_act - S_ref = -140, "COMPAX implements this correction in the following curve cycle and
    # this results in the correct slave reference being set. The next label will only be recognised
    # in the label window."
    curve = line(label_set_point=0.5, label_window=0.1, correction_enable=0.6, correction_disable=0.9)
    rig = Rig({1: curve}, label=LabelSync(), P33=2, P32=300.0, P93=1, P180=0.0)
    rig.op.setc(1)
    rig.op.setm(0.0)
    rig.op.loop(0)
    rig.inputs["I13"] = True
    rig.start_master(4)
    taken = []
    x_before = rig.x
    for _ in range(90 * 5):
        x0 = rig.x
        x1 = x0 + (x0 - x_before)
        edges = []
        for n in range(math.floor((x0 - 100.0) / 360.0), math.floor((x0 - 100.0) / 360.0) + 2):
            for x, rising in ((n * 360.0 + 100.0, True), (n * 360.0 + 105.0, False)):
                if x0 < x <= x1:
                    edges.append(((x - x0) / (x1 - x0), rising))
        before = rig.op.label.s51
        rig.step(i14_edges=sorted(edges))
        if rig.op.label.s51 != before:
            taken.append(rig.op.status(52))
        x_before = x0
    assert taken[0] == pytest.approx(1000 * -140 / 360, abs=1.5)
    assert rig.op.label.correction.applied == pytest.approx(-140 / 360, abs=0.005)
    assert all(abs(s52) < 2.0 for s52 in taken[1:]) and len(taken) >= 4
    assert rig.op.output(14)


def test_early_label_large_correction_is_no_jump():
    # L11 (§2.13 M_k1 / M_k2 "When the corrections are allocated, it is ensured that the corrections
    # are terminated in the next label window"): a label early in the window, inside M_k1 ... M_k2,
    # whose correction (15 % forward) is larger than the rest of the range ahead (10 %). The injected
    # correction moves the master itself; the share must be measured in the uncorrected master
    # travel, else each share makes the next bigger (a jump). Here the correction runs out with
    # 10 % of uncorrected travel: the slave feeds (1 + 15/10) times the speed, no more.
    rig = master_rig(ref=0.5, window=0.2, k1=0.3, k2=0.45, speed=4)
    labels = Labels(rig, first=0.35 * M_T)
    rig.record = True
    accepted = run_labels(rig, labels, 90 * 6)
    assert accepted[0] == pytest.approx((350.0, -150.0), abs=1.5)
    steps = [b[1] - a[1] for a, b in zip(rig.trace, rig.trace[1:])]
    assert steps[-1] == pytest.approx(4.0)  # synchronous at the master speed (4 units per cycle)
    assert max(steps) <= 4.0 * (1.0 + 0.15 / 0.10) + 0.2  # no step larger than the speed allows
    assert min(steps) >= -1e-9
    for s51, s52 in accepted[1:]:
        assert abs(s52) <= 1.5  # converged: the next labels land on S50
    assert rig.op.label.correction.pending == pytest.approx(0.0, abs=1e-9)


def test_correction_in_phase_spreads_over_uncorrected_travel():
    # L11 at the Correction level: a master that carries the correction's own offset
    from axisline.motion.registration import Correction

    c = Correction(enable_from=0.3, enable_to=0.45, master_cycle=1.0, spread=True, in_phase=True)
    raw, speed, shares = 0.30, 0.01, []
    c.step(raw)
    raw += speed
    c.step(raw)  # 0.31
    c.set(-0.15)  # 0.15 forward, only 0.14 of the range ahead
    for _ in range(30):
        raw += speed
        before = c.offset
        c.step((raw + c.offset) % 1.0)
        shares.append(c.offset - before)
    assert sum(shares) == pytest.approx(0.15)
    assert max(shares) == pytest.approx(0.15 / 0.14 * speed)  # even shares, no feedback
    assert all(s == 0.0 for s in shares[14:])


def test_on_label_hook_and_corrected_total():
    # the public hook the personality records labels with: each accepted label once, (S51, S52)
    rig = master_rig(ref=0.5, window=0.1, k1=0.6, k2=0.9)
    seen = []
    rig.op.label.on_label = lambda s51, s52: seen.append((s51, s52))
    labels = Labels(rig, first=0.62 * M_T, slip=0.005)
    accepted = run_labels(rig, labels, 90 * 5)
    assert seen == accepted and len(seen) == 5
    # corrected: the sum of what was applied (it survives the Correction being replaced or reset)
    assert rig.op.label.corrected == pytest.approx(rig.op.label.correction.applied)
    rig.op.label.interrupt()  # (SETM) restarts the master related synchronisation: applied resets, corrected not
    assert rig.op.label.correction.applied == 0.0 and rig.op.label.corrected != 0.0
