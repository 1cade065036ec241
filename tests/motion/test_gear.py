"""Electronic gear: integer law without drift, gear in/out, ratio change, phasing, gear in position."""

from __future__ import annotations

import math
import random
from fractions import Fraction

import pytest

from axisline.motion.axis import Axis, AxisConfig, AxisState
from axisline.motion.gear import Gear, GearError
from axisline.motion.gear_in_position import GearInPos, GearInPosError
from axisline.motion.master import EncoderMaster, Master, TimeBase, VirtualMaster
from axisline.plant.encoder import IncrementalEncoder

T = 0.001  # 1 ms kernel cycle
V_MAX, A_MAX, J_MAX = 1000.0, 5000.0, 2e5  # slave limits, mm, s


def slave_axis(shape: str = "jerk", **kw) -> Axis:
    base = dict(
        name="slave", unit="mm", counts_per_unit=1000.0, v_max=V_MAX, a_max=A_MAX, j_max=J_MAX,
        shape=shape, following_error_limit=5.0,
    )  # fmt: skip
    base.update(kw)
    ax = Axis(AxisConfig(**base), T)
    ax.power(True)
    return ax


def ratio(r: str, master: Master, slave: Axis) -> tuple[int, int]:
    return Gear.counts_ratio(r, master.counts_per_unit, slave.config.counts_per_unit)


class Rig:
    """The kernel cycle: master update, slave set point, perfect plant; records (p, v, a, m, vm)."""

    def __init__(self, master: Master, slave: Axis, cycle: int = 0) -> None:
        self.master = master
        self.slave = slave
        self.cycle = cycle
        self.trace: list[tuple[float, float, float, float, float]] = []

    def step(self, n: int = 1) -> None:
        ax, m = self.slave, self.master
        for _ in range(n):
            self.cycle += 1
            m.update(self.cycle)
            ax.update_setpoint(self.cycle)
            ax.position_loop(ax.command_position - ax.position_offset)
            self.trace.append((ax.command_position, ax.command_velocity, ax.command_acceleration, m.position, m.velocity))

    def until(self, predicate, limit: int = 100_000) -> int:
        for _ in range(limit):
            if predicate():
                return self.cycle
            self.step()
        raise AssertionError(f"condition not reached in {limit} cycles")


def assert_smooth(trace, a_lim: float = A_MAX, j_lim: float | None = J_MAX, v_lim: float = V_MAX) -> None:
    """No step in p, v or a, and the slave's limits kept (with a tolerance for the numerics)."""
    # the check below is exact for a cubic; a jerk (or, for trapezoids, an acceleration) switch
    # inside the cycle leaves at most this much
    p_tol = (j_lim * T**3 if j_lim is not None else a_lim * T**2) / 2.0 + 1e-9
    for k in range(1, len(trace)):
        p0, v0, a0 = trace[k - 1][:3]
        p1, v1, a1 = trace[k][:3]
        # a position step, or a velocity inconsistent with the positions, shows here
        expected = T * (v0 + v1) / 2.0 + T * T * (a0 - a1) / 12.0
        assert abs((p1 - p0) - expected) <= p_tol + 1e-12 * abs(p1), f"position step at {k}: {p1 - p0} vs {expected}"
        assert abs(v1) <= v_lim * (1 + 1e-9), f"speed {v1} above the limit at {k}"
        assert abs(v1 - v0) / T <= a_lim * (1 + 1e-6), f"velocity step at {k}: {(v1 - v0) / T} mm/s^2"
        assert abs(a1) <= a_lim * (1 + 1e-9), f"acceleration {a1} above the limit at {k}"
        if j_lim is not None:
            assert abs(a1 - a0) / T <= j_lim * (1 + 1e-6), f"acceleration step at {k}: {(a1 - a0) / T} mm/s^3"


def assert_no_steps(trace, tol: float) -> None:
    """Positions consistent with the velocities from cycle to cycle (limits not checked)."""
    for k in range(1, len(trace)):
        p0, v0, a0 = trace[k - 1][:3]
        p1, v1, a1 = trace[k][:3]
        expected = T * (v0 + v1) / 2.0 + T * T * (a0 - a1) / 12.0
        assert abs((p1 - p0) - expected) <= tol, f"position step at {k}: {p1 - p0} vs {expected}"


class CountMaster(Master):
    """A master whose counts the test sets (no Axis, no clock): for the long drift run."""

    def __init__(self) -> None:
        super().__init__(counts_per_unit=1000.0)

    def set(self, counts: int) -> None:
        self._counts = counts
        self._p = counts / self.counts_per_unit

    def _update(self, cycle: int) -> None:
        pass


# ------------------------------------------------------------------------ integer law


def test_a_16523_by_11872_gear_has_no_drift_over_ten_million_master_counts() -> None:
    master = CountMaster()
    master.set(-123_457)
    slave = slave_axis()
    num, den = 16523, 11872
    gear = Gear(master, slave, num, den)
    gear.gear_in()
    gear.sample(1)  # master and slave at rest: coupled at once
    assert gear.in_gear
    mc0, sc0 = gear.reference
    offset = gear.offset
    rng = random.Random(7)
    counts, travelled, cycle = -123_457, 0, 1
    while travelled < 10_000_000:
        step = rng.randint(-3_000, 20_000)  # forward on average, with reversals
        counts += step
        travelled += abs(step)
        cycle += 1
        master.set(counts)
        p, _, _ = gear.sample(cycle)
        assert gear.slave_counts == sc0 + (counts - mc0) * num // den
        if rng.random() < 0.05:
            exact = (Fraction(sc0) + Fraction((counts - mc0) * num, den)) / 1000 + Fraction(offset)
            assert abs(Fraction(p) - exact) <= Fraction(1, 10**9) * abs(exact) + Fraction(1, 10**12)
    exact = (Fraction(sc0) + Fraction((counts - mc0) * num, den)) / 1000 + Fraction(offset)
    assert abs(Fraction(p) - exact) <= Fraction(1, 10**9) * abs(exact)
    assert gear.slave_counts == sc0 + (counts - mc0) * num // den


def test_gear_rejects_a_bad_ratio() -> None:
    master, slave = CountMaster(), slave_axis()
    with pytest.raises(GearError, match="denominator"):
        Gear(master, slave, 1, 0)
    with pytest.raises(GearError, match="numerator"):
        Gear(master, slave, 1.5, 2)  # type: ignore[arg-type]


def test_gear_follows_an_encoder_master_count_for_count() -> None:
    class Line:
        position = 0.0

    line = Line()
    enc = IncrementalEncoder(line, lines_per_unit=256.0, multiplier=4, counter_bits=16)
    master = EncoderMaster(enc, 1024.0, T, sampling_time=0.004)
    slave = slave_axis()
    gear = Gear(master, slave, 7, 3)
    rig = Rig(master, slave)
    rig.step()
    gear.gear_in()
    for c in range(3000):
        line.position = 30.0 * (c * T) ** 2  # accelerating line across many counter wraps
        enc.sample()
        rig.step()
        mc0, sc0 = gear.reference
        assert gear.slave_counts == sc0 + (master.counts - mc0) * 7 // 3
    assert master.counts == enc.counts_unwrapped


# ------------------------------------------------------------------------ gear in / gear out


def test_gear_in_at_standstill_couples_at_once_and_follows_exactly() -> None:
    master = VirtualMaster(T, acceleration=400.0, jerk=20000.0)
    slave = slave_axis()
    slave.set_position(12.3)
    rig = Rig(master, slave)
    rig.step(3)
    num, den = ratio("-0.75", master, slave)
    gear = Gear(master, slave, num, den)
    cmd = gear.gear_in()
    assert cmd.active and slave.state is AxisState.SYNCHRONIZED_MOTION
    rig.step()
    assert gear.in_gear and not gear.catching_up
    m0 = master.position
    master.set_velocity(100.0)
    for _ in range(1500):
        rig.step()
        assert slave.command_position == pytest.approx(12.3 - 0.75 * (master.position - m0), abs=1e-9)
        assert slave.command_velocity == pytest.approx(-0.75 * master.velocity, abs=1e-9)
    assert_smooth(rig.trace)


@pytest.mark.parametrize("shape", ["jerk", "sin2"])
def test_gear_in_on_the_fly_matches_the_velocity_within_the_limits_and_keeps_the_offset(shape: str) -> None:
    master = TimeBase(T, 200.0)
    slave = slave_axis(shape)
    rig = Rig(master, slave)
    rig.step(5)
    gear = Gear(master, slave, *ratio("1.5", master, slave))
    p0, m0 = slave.command_position, master.position
    gear.gear_in()
    in_gear_at = rig.until(lambda: gear.in_gear, limit=1000)
    assert_smooth(rig.trace)
    # catch-up from 0 to 300 mm/s: average speed 150 (symmetric ramp), duration 300/a + k a/j
    k = 1.0 if shape == "jerk" else math.pi / 2.0
    duration = 300.0 / A_MAX + k * A_MAX / J_MAX
    assert (in_gear_at - 5) * T == pytest.approx(duration, abs=1.5 * T)
    lost = 300.0 * duration / 2.0  # the slave falls behind the geared position by this much
    rig.step(500)
    assert_smooth(rig.trace)
    p, v, _, m, vm = rig.trace[-1]
    assert p - (p0 + 1.5 * (m - m0)) == pytest.approx(-lost, abs=1e-6)  # the offset is kept
    assert v == pytest.approx(1.5 * vm, abs=1e-9)


def test_gear_out_keeps_the_velocity_then_end_sync_halts() -> None:
    master = TimeBase(T, 200.0)
    slave = slave_axis()
    rig = Rig(master, slave)
    rig.step()
    gear = Gear(master, slave, *ratio("0.5", master, slave))
    sync = gear.gear_in()
    rig.until(lambda: gear.in_gear)
    rig.step(50)
    assert gear.gear_out() is None
    assert not gear.in_gear and slave.state is AxisState.SYNCHRONIZED_MOTION
    master.set_speed(400.0)  # the master speeds up: the geared-out slave must not follow
    rig.step(300)
    assert all(v == pytest.approx(100.0) for _, v, *_ in rig.trace[-300:])
    halt = slave.end_sync()
    assert sync.done and halt.busy
    rig.until(lambda: slave.state is AxisState.STANDSTILL, limit=2000)
    assert halt.done and slave.command_velocity == 0.0
    assert_smooth(rig.trace)
    with pytest.raises(GearError, match="not engaged"):
        gear.gear_out()


def test_gear_out_with_halt_brakes_from_the_geared_velocity() -> None:
    master = TimeBase(T, 100.0)
    slave = slave_axis()
    rig = Rig(master, slave)
    rig.step()
    gear = Gear(master, slave, *ratio("2", master, slave))
    gear.gear_in()
    rig.until(lambda: gear.in_gear)
    halt = gear.gear_out(halt=True, deceleration=2000.0)
    assert slave.state is AxisState.DISCRETE_MOTION
    rig.until(lambda: slave.state is AxisState.STANDSTILL, limit=2000)
    assert halt.done
    assert_smooth(rig.trace)


def test_gear_in_while_the_slave_moves_the_other_way() -> None:
    master = TimeBase(T, 100.0)
    slave = slave_axis()
    slave.move_velocity(-200.0)
    rig = Rig(master, slave)
    rig.until(lambda: slave.command_velocity == -200.0 and slave.command_acceleration == 0.0)
    gear = Gear(master, slave, *ratio("3", master, slave))
    gear.gear_in()
    rig.until(lambda: gear.in_gear, limit=2000)
    rig.step(20)
    assert_smooth(rig.trace)
    assert slave.command_velocity == pytest.approx(300.0)


# ------------------------------------------------------------------------ ratio change, phasing


def test_ratio_change_ramps_over_the_master_distance_then_is_exact() -> None:
    master = TimeBase(T, 100.0)
    slave = slave_axis()
    rig = Rig(master, slave)
    rig.step()
    gear = Gear(master, slave, *ratio("1.5", master, slave))
    gear.gear_in()
    rig.until(lambda: gear.in_gear)
    m1 = master.position
    p1 = slave.command_position
    start = len(rig.trace) - 1
    new_num, new_den = ratio("2.25", master, slave)
    gear.set_ratio(new_num, new_den, ramp_distance=40.0)
    assert gear.ratio_ramping and gear.ratio == pytest.approx(2.25)
    rig.until(lambda: master.position > m1 + 40.0 + 1.0, limit=2000)
    assert not gear.ratio_ramping
    # the blend's acceleration: (2.25 - 1.5) * max h' (1.5) / 40 * 100^2 = 281 mm/s^2 at most
    assert_smooth(rig.trace[start:], a_lim=0.75 * 1.5 / 40.0 * 100.0**2 * 1.001)
    mc_ref, sc_ref = gear.reference
    assert mc_ref == round((m1 + 40.0) * master.counts_per_unit)  # re-based at the end of the ramp
    p_ref, m_ref = slave.command_position, master.position
    for _ in range(1000):
        rig.step()
        assert gear.slave_counts == sc_ref + (master.counts - mc_ref) * new_num // new_den
        assert slave.command_position - p_ref == pytest.approx(2.25 * (master.position - m_ref), abs=1e-9)
        assert slave.command_velocity == pytest.approx(225.0)
    # over the ramp the slave covered the mean ratio: 40 * (1.5 + 2.25) / 2 = 75
    p_end = slave.command_position - 2.25 * (master.position - (m1 + 40.0))
    assert p_end - p1 == pytest.approx(75.0, abs=1e-6)


def test_ratio_change_with_a_ramp_time_and_at_rest() -> None:
    master = TimeBase(T, 50.0)
    slave = slave_axis()
    rig = Rig(master, slave)
    rig.step()
    gear = Gear(master, slave, *ratio("1", master, slave))
    gear.gear_in()
    rig.until(lambda: gear.in_gear)
    gear.set_ratio(*ratio("1.2", master, slave), ramp_time=0.4)  # 0.4 s at 50/s = 20 master units
    m1 = master.position
    rig.until(lambda: not gear.ratio_ramping, limit=1000)
    assert master.position - m1 == pytest.approx(20.0, abs=50.0 * T)
    assert_smooth(rig.trace)
    # master at rest: the new ratio applies at once, without a step
    master.set_speed(0.0, ramp_time=0.2)
    rig.step(205)
    p_rest = slave.command_position
    gear.set_ratio(*ratio("0.5", master, slave), ramp_time=0.4)
    assert not gear.ratio_ramping and gear.ratio == pytest.approx(0.5)
    rig.step(5)
    assert slave.command_position == pytest.approx(p_rest, abs=1e-12)
    master.set_speed(80.0, ramp_time=0.2)
    rig.step(400)
    assert slave.command_velocity == pytest.approx(40.0)
    assert_smooth(rig.trace, j_lim=None)  # the time base ramps with steps of acceleration


@pytest.mark.parametrize("shape", ["trapezoid", "jerk", "sin2"])
def test_phasing_reaches_the_shift_without_steps(shape: str) -> None:
    master = TimeBase(T, 100.0)
    slave = slave_axis(shape)
    rig = Rig(master, slave)
    rig.step()
    gear = Gear(master, slave, *ratio("1.5", master, slave))
    gear.gear_in()
    rig.until(lambda: gear.in_gear)
    rig.step(10)
    before = slave.command_position - 1.5 * master.position
    mc_ref = gear.reference[0]
    gear.phasing(5.0, velocity=40.0, acceleration=400.0)
    assert gear.phasing_active
    rig.until(lambda: not gear.phasing_active, limit=5000)
    rig.step(10)
    assert_smooth(rig.trace, j_lim=None if shape == "trapezoid" else J_MAX)
    assert gear.phase == pytest.approx(5.0)
    after = slave.command_position - 1.5 * master.position
    assert after - before == pytest.approx(1.5 * 5.0, abs=1e-9)
    assert gear.reference[0] == mc_ref - 5 * master.counts_per_unit  # folded into the integer law
    assert slave.command_velocity == pytest.approx(150.0)


def test_phasing_and_ratio_ramp_do_not_overlap() -> None:
    master = TimeBase(T, 100.0)
    slave = slave_axis()
    rig = Rig(master, slave)
    rig.step()
    gear = Gear(master, slave, *ratio("1", master, slave))
    with pytest.raises(GearError, match="coupled"):
        gear.phasing(1.0, velocity=10.0, acceleration=100.0)
    gear.gear_in()
    rig.until(lambda: gear.in_gear)
    gear.phasing(1.0, velocity=10.0, acceleration=100.0)
    with pytest.raises(GearError, match="phasing is running"):
        gear.set_ratio(2, 1, ramp_distance=10.0)


# ------------------------------------------------------------------------ gear in position


def run_to_sync(rig: Rig, gear: GearInPos, m_sync: float, during=None) -> int:
    """Run until the master passes m_sync (not in gear before, in gear then); returns that cycle."""
    while rig.master.position < m_sync:
        assert not gear.in_gear
        if during is not None:
            during(rig)
        rig.step()
    assert gear.in_gear
    return rig.cycle


@pytest.mark.parametrize("shape", ["jerk", "sin2"])
def test_gear_in_pos_synchronises_exactly_at_the_master_sync_position(shape: str) -> None:
    master = TimeBase(T, 200.0)
    slave = slave_axis(shape)
    rig = Rig(master, slave)
    rig.step()
    m_sync, s_sync, r = 500.0, 100.0, 1.5
    gear = GearInPos(master, slave, *ratio("1.5", master, slave), master_sync_position=m_sync, slave_sync_position=s_sync)
    check = gear.check()
    assert check.feasible and check.needed < check.available
    gear.gear_in()
    run_to_sync(rig, gear, m_sync)
    p, v, _, m, vm = rig.trace[-1]
    assert abs(p - (s_sync + r * (m - m_sync))) < 1e-6 * s_sync
    assert v == pytest.approx(r * vm, rel=1e-9)
    # the slave waited at rest, then made its move within the limits
    assert rig.trace[100][:2] == (0.0, 0.0)
    assert_smooth(rig.trace)
    num, den = gear.numerator, gear.denominator
    for _ in range(300):  # after the sync: the integer law, exactly
        rig.step()
        mc_ref, sc_ref = gear.reference
        assert gear.slave_counts == sc_ref + (master.counts - mc_ref) * num // den
    p, v, _, m, vm = rig.trace[-1]
    assert p == pytest.approx(s_sync + r * (m - m_sync), abs=1e-9)
    assert_smooth(rig.trace)


@pytest.mark.parametrize("shape", ["jerk", "sin2"])
def test_gear_in_pos_is_exact_when_the_master_accelerates_during_the_approach(shape: str) -> None:
    master = VirtualMaster(T, 200.0, acceleration=400.0, jerk=10000.0)
    slave = slave_axis(shape)
    rig = Rig(master, slave)
    rig.until(lambda: master.in_velocity)
    m_sync = master.position + 300.0
    s_sync = slave.command_position + 80.0
    gear = GearInPos(master, slave, *ratio("1.3", master, slave), master_sync_position=m_sync, slave_sync_position=s_sync)
    gear.gear_in()
    changed = []

    def speed_up(rig: Rig) -> None:
        if gear.sync_started and not changed:  # the slave is on its way: the line speeds up
            master.set_velocity(260.0)
            changed.append(rig.cycle)

    synced_at = run_to_sync(rig, gear, m_sync, during=speed_up)
    p, v, _, m, vm = rig.trace[-1]
    assert changed and changed[0] < synced_at and vm > 200.0  # the speed changed during the approach
    assert abs(p - (s_sync + 1.3 * (m - m_sync))) < 1e-6 * 80.0
    assert v == pytest.approx(1.3 * vm, rel=1e-9)
    p, _, _, m, _ = rig.trace[-2]  # the last cycle of the approach is already on the relation
    assert abs(p - (s_sync + 1.3 * (m - m_sync))) < 1e-6 * 80.0
    rig.step(100)
    assert_no_steps(rig.trace, tol=1e-5)  # no step anywhere, at the hand-off to the law neither


def test_gear_in_pos_from_a_slave_moving_at_constant_velocity() -> None:
    master = TimeBase(T, 200.0)
    slave = slave_axis()
    slave.move_velocity(50.0)
    rig = Rig(master, slave)
    rig.until(lambda: slave.command_velocity == 50.0 and slave.command_acceleration == 0.0)
    m_sync = master.position + 400.0
    s_sync = slave.command_position + 150.0
    gear = GearInPos(master, slave, *ratio("1", master, slave), master_sync_position=m_sync, slave_sync_position=s_sync)
    gear.gear_in()
    start = len(rig.trace)
    run_to_sync(rig, gear, m_sync)
    p, v, _, m, vm = rig.trace[-1]
    assert abs(p - (s_sync + (m - m_sync))) < 1e-6 * 150.0
    assert v == pytest.approx(vm, rel=1e-9)
    assert_smooth(rig.trace[start - 1 :])


def test_gear_in_pos_reports_an_infeasible_request_before_any_motion() -> None:
    master = TimeBase(T, 200.0)
    slave = slave_axis()
    rig = Rig(master, slave)
    rig.step(10)
    p_before = slave.command_position
    m_sync = master.position + 20.0  # 0.1 s of master travel: too short for 0 -> 300 mm/s over 100 mm
    with pytest.raises(GearInPosError) as info:
        GearInPos(master, slave, *ratio("1.5", master, slave), master_sync_position=m_sync, slave_sync_position=100.0)
    err = info.value
    assert err.available == pytest.approx(20.0)
    assert err.needed > err.available
    assert f"{err.needed:.6g}" in str(err) and f"{err.available:.6g}" in str(err)
    assert slave.state is AxisState.STANDSTILL
    rig.step(5)
    assert slave.command_position == p_before and slave.command_velocity == 0.0


def test_gear_in_pos_check_and_gear_in_see_the_master_come_too_close() -> None:
    master = TimeBase(T, 200.0)
    slave = slave_axis()
    rig = Rig(master, slave)
    rig.step()
    gear = GearInPos(master, slave, *ratio("1.5", master, slave), master_sync_position=100.0, slave_sync_position=50.0)
    assert gear.check().feasible
    rig.step(400)  # the master runs on (80 units) while the request waits
    result = gear.check()
    assert not result.feasible and result.needed > result.available
    assert "needs" in result.message
    with pytest.raises(GearInPosError):
        gear.gear_in()
    assert slave.state is AxisState.STANDSTILL
    rig.step(300)  # past the sync position: a negative distance is available
    assert gear.check().available < 0.0


def test_gear_in_pos_rejects_a_sync_velocity_above_the_slave_limit_and_a_master_at_rest() -> None:
    master = TimeBase(T, 200.0)
    slave = slave_axis(v_max=250.0)
    with pytest.raises(GearError, match="velocity limit"):
        GearInPos(master, slave, *ratio("1.5", master, slave), master_sync_position=500.0, slave_sync_position=50.0)
    still = TimeBase(T, 0.0)
    with pytest.raises(GearError, match="master_velocity"):
        GearInPos(still, slave, *ratio("1", still, slave), master_sync_position=500.0, slave_sync_position=50.0)
    # with a nominal speed the slave waits for the master to start
    gear = GearInPos(
        still, slave, *ratio("1", still, slave), master_sync_position=50.0, slave_sync_position=30.0, master_velocity=100.0
    )
    rig = Rig(still, slave)
    rig.step()
    gear.gear_in()
    rig.step(100)
    assert slave.command_position == 0.0
    still.set_speed(100.0, ramp_time=0.1)
    run_to_sync(rig, gear, 50.0)
    p, v, _, m, vm = rig.trace[-1]
    assert abs(p - (30.0 + (m - 50.0))) < 1e-6 * 30.0 and v == pytest.approx(vm)


def test_gear_in_pos_takes_its_own_approach_acceleration() -> None:
    """GearInPos(acceleration=, deceleration=): a controller's own ramps (the CLM's Ax08 in the
    flying cutoff) instead of the axis' mechanical a_max: the approach stays within them, and a
    sync the lower ramp cannot reach in the distance left is refused before any motion."""
    master = TimeBase(T, 200.0)
    slave = slave_axis("trapezoid", j_max=None)
    rig = Rig(master, slave)
    rig.step()
    a_own = 1000.0  # a fifth of the axis' A_MAX
    # 1:1 from rest to 200 mm/s needs 200^2 / (2 * 1000) = 20 mm of slave travel
    gear = GearInPos(master, slave, *ratio("1", master, slave), master_sync_position=300.0, slave_sync_position=20.0,
                     acceleration=a_own, deceleration=a_own)
    gear.gear_in()
    run_to_sync(rig, gear, 300.0)
    assert max(abs(a) for _, _, a, _, _ in rig.trace) <= a_own * (1 + 1e-9)
    p, v, _, m, vm = rig.trace[-1]
    assert p == pytest.approx(20.0 + (m - 300.0), abs=1e-6)
    assert v == pytest.approx(vm, rel=1e-9)
    # from rest, 200 mm/s 20 mm of master travel away: 0.04 s of ramp at the axis' A_MAX, but
    # 0.2 s (more than the 0.1 s the master takes) at a_own
    master2 = TimeBase(T, 200.0)
    slave2 = slave_axis("trapezoid", j_max=None)
    Rig(master2, slave2).step()
    GearInPos(master2, slave2, *ratio("1", master2, slave2), master_sync_position=20.0, slave_sync_position=10.0)
    with pytest.raises(GearInPosError):
        GearInPos(master2, slave2, *ratio("1", master2, slave2), master_sync_position=20.0, slave_sync_position=10.0,
                  acceleration=a_own)
