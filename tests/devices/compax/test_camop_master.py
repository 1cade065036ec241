"""COMPAX master reference chain (masterchain.py): compax.md §1.3, §2.5, §2.10, §2.15, §2.16, §2.19."""

from __future__ import annotations

from fractions import Fraction

import pytest

from axisline.devices.compax import CompaxError
from axisline.devices.compax.masterchain import MasterChain, scaled_master_cycle

from .test_camop_rig import Encoder, Params


def chain(**params):
    p = Params({98: 360.0, 143: 90})
    p.update({int(k[1:]): v for k, v in params.items()})
    enc = Encoder()
    return MasterChain(p, enc), enc, p


class Runner:
    def __init__(self, ch, enc):
        self.ch, self.enc, self.cycle, self.i16 = ch, enc, 0, False

    def step(self, counts=0, n=1, **kw):
        wraps = 0
        for _ in range(n):
            self.cycle += 1
            self.enc.counts += counts
            wraps += self.ch.update(self.cycle, self.i16, **kw)
            kw = {}
        return wraps


def test_scaled_master_cycle_default_is_16384_increments():
    # §7 X4: P98 = 360, P143 = 4096 => 16384 increments per master revolution, M_T = 360
    assert scaled_master_cycle(360, 4096, 360) == 16384
    ch, _, _ = chain(P143=4096)
    ch.select_curve(360.0)
    assert ch.scaled_cycle == 16384.0


def test_value_range_rule():
    # §2.5 / §4 formula 3: M_T·4·P143/P98 <= 4 000 000; decision MC7: refused at SETC, code 103
    ch, _, _ = chain(P143=4096, P98=360.0)
    ch.select_curve(87890.0)  # 3 999 971 increments: allowed
    with pytest.raises(CompaxError) as e:
        ch.select_curve(87891.0)  # 4 000 017 increments
    assert e.value.code == 103 and "4 000 000" in str(e.value)
    assert ch.master_cycle == 87890.0  # unchanged


def test_no_counting_before_a_curve_is_selected():
    # §2.10 "If no curve has been selected since "Power on", I16 is not taken into account."
    ch, enc, _ = chain()
    r = Runner(ch, enc)
    r.step()
    r.i16 = True
    r.step(5, n=3)
    assert not ch.counting and ch.cycle_position == 0


def test_p31_0_enables_on_a_rising_edge_counts_from_the_latch_and_stops_on_0():
    ch, enc, _ = chain(P31=0)
    r = Runner(ch, enc)
    r.i16 = True
    r.step(3)
    ch.select_curve(360.0)  # MC2: I16 already 1 at the first SETC does not enable
    r.step(3, n=2)
    assert not ch.counting
    r.i16 = False
    r.step(3)
    enc.counts += 7  # moves between the samples; I16 rose when the counter showed 12 + 3
    r.i16 = True
    r.step(0, i16_latch=enc.counts - 4)  # "exactly counted without any time lag" from the edge
    assert ch.counting and ch.cycle_position == 4
    r.step(10, n=2)
    assert ch.cycle_position == 24
    r.i16 = False
    r.step(10)
    assert not ch.counting and ch.cycle_position == 24


def test_p31_9_counts_from_the_next_sample_without_preset():
    ch, enc, _ = chain(P31=9)
    r = Runner(ch, enc)
    ch.select_curve(360.0)
    ch.setm(50.0)
    r.step(10)
    r.i16 = True
    r.step(10, i16_latch=enc.counts)  # no latch, no preset ("in the next sampling cycle")
    assert ch.cycle_position == 180
    r.step(10)
    assert ch.cycle_position == 190


def test_setm_preset_at_each_enabling():
    # MC3: SETM sets the position and presets it at every enabling; §14.6.1 "Once I16="1" is
    # recognised, S44 also begins to operate from the value in S50"
    ch, enc, _ = chain(P31=0)
    r = Runner(ch, enc)
    ch.select_curve(360.0)
    ch.setm(80.0)
    assert ch.s44 == pytest.approx(800.0)
    r.i16 = True
    r.step(10)
    r.step(10)
    assert ch.cycle_position == 298
    r.i16 = False
    r.step(10)
    r.i16 = True
    r.step(10)  # enabled again: preset to 80 % (288), counting starts at the sample
    assert ch.cycle_position == 288
    ch.select_curve(360.0)  # a new SETC clears the preset
    r.i16 = False
    r.step(10)
    r.i16 = True
    r.step(10)
    assert ch.cycle_position == 288


def test_p31_1_starts_at_the_encoder_zero_pulse():
    ch, enc, _ = chain(P31=1)
    r = Runner(ch, enc)
    ch.select_curve(360.0)
    r.i16 = True
    r.step(10, n=3)
    assert not ch.counting
    r.step(10, zero_pulse=enc.counts + 6)  # the zero pulse passed 4 increments before the sample
    assert ch.counting and ch.cycle_position == 4
    r.i16 = False
    r.step(10)
    assert not ch.counting


def test_p31_2_edge_after_setc_enables_setc_with_i16_0_disables():
    ch, enc, _ = chain(P31=2)
    r = Runner(ch, enc)
    ch.select_curve(360.0)
    r.i16 = True
    r.step(5)
    assert ch.counting
    r.i16 = False
    r.step(5)
    assert ch.counting and ch.cycle_position == 5  # latched by the edge since the SETC
    ch.select_curve(360.0)  # SETC with I16 = 0: disabled
    r.step(5)
    assert not ch.counting
    r.i16 = True
    r.step(5)
    ch.select_curve(360.0)  # SETC with I16 = 1: "the master position measurement continues to operate!"
    r.step(5)
    assert ch.counting
    r.i16 = False
    r.step(5)  # ... until I16 falls (no edge since that SETC)
    assert not ch.counting


def test_p31_2_with_the_internal_time_base_works_like_p31_0():
    ch, enc, _ = chain(P31=2, P30=1)
    r = Runner(ch, enc)
    ch.select_curve(360.0)
    r.i16 = True
    r.step()
    r.step()
    assert ch.counting
    r.i16 = False
    r.step()
    assert not ch.counting


def test_p31_3_one_master_cycle_retriggered_while_i16_is_1():
    ch, enc, _ = chain(P31=3)
    r = Runner(ch, enc)
    ch.select_curve(360.0)
    r.i16 = True
    r.step(0)
    assert ch.counting
    wraps = r.step(10, n=36)  # one full cycle: I16 still 1 -> automatic triggering
    assert wraps == 1 and ch.counting
    r.i16 = False
    r.step(10, n=40)
    assert not ch.counting and ch.cycle_position == 0  # stopped at the end of the cycle
    r.i16 = True  # a new edge (no SETC needed) starts another cycle
    r.step(10)
    assert ch.counting


def test_p31_5_one_master_cycle_independent_of_i16():
    ch, enc, _ = chain(P31=5)
    r = Runner(ch, enc)
    ch.select_curve(360.0)
    r.i16 = True
    r.step(0)
    r.step(10, n=40)
    assert not ch.counting and ch.cycle_position == 0
    ch.select_curve(360.0)
    r.i16 = False
    r.step()
    r.i16 = True
    r.step(10)
    assert ch.counting


def test_p31_4_setc_disables_independent_of_i16():
    ch, enc, _ = chain(P31=4)
    r = Runner(ch, enc)
    ch.select_curve(360.0)
    r.i16 = True
    r.step(1)
    r.i16 = False
    r.step(1, n=5)
    assert ch.counting
    r.i16 = True
    r.step(1)
    ch.select_curve(360.0)
    r.step(1)
    assert not ch.counting  # I16 = 1 but no new edge since the SETC


def test_block_needs_a_new_i16_edge():
    # E25 (§2.4): counting disabled until master position measurement is enabled again
    ch, enc, _ = chain(P31=0)
    r = Runner(ch, enc)
    ch.select_curve(360.0)
    r.i16 = True
    r.step(1)
    ch.block()
    r.step(1, n=3)
    assert not ch.counting
    r.i16 = False
    r.step()
    r.i16 = True
    r.step()
    assert ch.counting


@pytest.mark.parametrize(
    "p98, mt, p35, per_minute",
    [(360.0, 360.0, 1.0, 100.0), (360.0, 360.0, 2.0, 200.0), (360.0, 36000.0, 12.0, 12.0)],
)
def test_internal_time_base_cycle_rates(p98, mt, p35, per_minute):
    # §7 X16 / Appendix B internal_time_base: n = 100 min^-1 · P35 · P98 / M_T cycles per minute
    ch, enc, _ = chain(P30=1, P98=p98, P35=p35, P143=1024)
    r = Runner(ch, enc)
    ch.select_curve(mt)
    r.i16 = True
    r.step()  # enabled: the time base starts here
    ms_per_cycle = round(60000.0 / per_minute)
    assert r.step(n=ms_per_cycle * 3 - 1) == 2 and ch.fraction > 0.99
    assert r.step(n=2) == 1 and ch.fraction < 0.01  # exactly 3 cycles in 3 * 60000 / n ms
    assert ch.s41 == pytest.approx(per_minute)  # decision MC1: S41 in master cycles per minute


def test_internal_time_base_ramp_p39():
    # §7 X17: P39 = 1000 ms, 100 cycles/min target: half the speed at 500 ms
    ch, enc, _ = chain(P30=1, P39=1000, P143=1024)
    r = Runner(ch, enc)
    ch.select_curve(360.0)
    r.i16 = True
    r.step()
    r.step(n=500)
    assert ch.s41 == pytest.approx(50.0, abs=0.1)
    r.step(n=600)
    assert ch.s41 == pytest.approx(100.0)


def test_s41_is_master_cycles_per_minute():
    ch, enc, _ = chain(P143=1024, P98=360.0)  # 4096 increments per encoder revolution
    r = Runner(ch, enc)
    ch.select_curve(720.0)  # M_T* = 8192 increments = 2 encoder revolutions
    r.i16 = True
    r.step()
    r.step(8192 // 60)  # about one cycle per minute... per ms: 136 increments
    assert ch.s41 == pytest.approx(136 * 60000 / 8192)
    assert ch.s46 == 0
    r.step(-5)
    assert ch.s46 == 1


def test_p179_ramp():
    # §7 X18: P179 = 1000 ms per 1.0: P35 1 -> 2 reaches 1.5 at 500 ms, 2.0 at 1000 ms; 1 -> 3: 2000 ms
    ch, enc, p = chain(P179=1000)
    r = Runner(ch, enc)
    ch.select_curve(360.0)
    p[35] = 2.0
    r.step(n=500)
    assert ch.p35 == pytest.approx(1.5)
    r.step(n=500)
    assert ch.p35 == 2.0
    p[35] = 1.0
    r.step(n=1000)
    p[35] = 3.0
    r.step(n=1999)
    assert ch.p35 < 3.0
    r.step()
    assert ch.p35 == 3.0


def test_p35_scales_the_master_increments():
    ch, enc, p = chain(P35=0.5)
    r = Runner(ch, enc)
    ch.select_curve(360.0)
    r.i16 = True
    r.step()
    r.step(3, n=5)
    assert ch.cycle_position == 7.5
    assert ch.increments == (7, 0.5)


def test_p35_triggered_transfer_waits_for_the_cycle_end_while_synchronous():
    # §2.16: P30 tens digit 1 -> P35 taken at the end of the master cycle, only with O16 = 1
    ch, enc, p = chain(P30=10)
    r = Runner(ch, enc)
    ch.select_curve(360.0)
    r.i16 = True
    r.step()
    ch.synchronous = True
    p[35] = 2.0
    r.step(10, n=30)
    assert ch.p35 == 1.0 and ch.cycle_position == 300
    r.step(10, n=6)  # the wrap at 360
    assert ch.p35 == 2.0
    r.step(10)
    assert ch.cycle_position == 20
    ch.synchronous = False
    p[35] = 1.0
    r.step(10)
    assert ch.p35 == 1.0  # not synchronous: immediately


def test_s42_overflow():
    # decision MC9: the counted increments restart at ±8 000 000
    ch, enc, _ = chain(P143=1_000_000, P98=1.0)
    r = Runner(ch, enc)
    ch.select_curve(1.0)  # M_T* = 4 000 000
    r.i16 = True
    r.step()
    r.step(1_000_000, n=9)
    assert ch.s42 == 1_000_000 and ch.s44 == pytest.approx(250.0)
    r.step(-1_000_000, n=11)
    assert ch.s42 == -2_000_000


def test_integer_chain_is_exact_over_a_long_run():
    # §2.20 first condition: M_T* integer and P35 = 1 -> no drift in the master channel
    ch, enc, _ = chain(P143=1024, P98=1024.0)
    ch.select_curve(11872.0)  # M_T* = 11872·4096/1024 = 47488
    assert ch.scaled_cycle == 47488.0
    r = Runner(ch, enc)
    r.i16 = True
    r.step()
    total, wraps = 0, 0
    for k in range(3000):
        d = 40_000 + (k * 7919) % 9973
        total += d
        wraps += r.step(d)
    assert (wraps, ch.increments) == (total // 47488, (total % 47488, 0.0))
    assert Fraction(ch.cycle_position) == Fraction(total % 47488)


def test_jump_free_switch_to_the_internal_time_base():
    # §2.15 "P35_new = P35_old · V_ext / P98" (decision MC11: V_ext in master units per 1/100 min)
    from axisline.devices.compax.masterchain import jump_free_p35

    ch, enc, p = chain(P143=1024, P98=360.0, P35=1.5)
    r = Runner(ch, enc)
    ch.select_curve(360.0)
    r.i16 = True
    r.step()
    r.step(20, n=5)  # 20 increments/ms = 20·360/4096 deg/ms before P35
    v_enc = ch.velocity
    v_ext = 20 * 360 / 4096 * 60000 / 100  # master units per 1/100 minute
    p[35] = jump_free_p35(1.5, v_ext, 360.0)
    p[30] = 1  # P39 = 0, counting enabled: the time base takes over at the same speed
    r.step(n=5)
    assert ch.velocity == pytest.approx(v_enc, rel=1e-12)
