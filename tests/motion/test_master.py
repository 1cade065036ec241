"""Master sources: axis, encoder (window / first-order velocity, counter wrap), virtual master, time base."""

from __future__ import annotations

import math

import pytest

from axisline.motion.axis import Axis, AxisConfig
from axisline.motion.master import (
    FINE_COUNTS_PER_UNIT,
    AxisMaster,
    EncoderMaster,
    TimeBase,
    VirtualMaster,
)
from axisline.plant.encoder import IncrementalEncoder

T = 0.001  # 1 ms kernel cycle


class Line:
    """A material line the encoder reads: position(t) given as a function of time."""

    def __init__(self, law) -> None:
        self.law = law
        self.position = law(0.0)

    def at(self, cycle: int) -> None:
        self.position = self.law(cycle * T)


def run_encoder(master: EncoderMaster, line: Line, encoder: IncrementalEncoder, cycles: range):
    """INPUTS (encoder sampled) then the master update, per cycle; yields the cycle."""
    for c in cycles:
        line.at(c)
        encoder.sample()
        master.update(c)
        yield c


# ------------------------------------------------------------------------ encoder master


def test_window_velocity_is_the_exact_line_speed_once_the_sampling_time_is_full() -> None:
    # 123.4 mm/s at 1000 counts/mm: 123.4 counts per cycle, so a single cycle sees 123 or 124
    line = Line(lambda t: 123.4 * t)
    enc = IncrementalEncoder(line, lines_per_unit=250.0, multiplier=4)
    window = EncoderMaster(enc, 1000.0, T, velocity_filter="window", sampling_time=0.010)
    assert window.window_cycles == 10
    for c in run_encoder(window, line, enc, range(1, 200)):
        if c > 10:  # full after 11 updates: 10 cycles = 1234 counts exactly, whatever the phase
            assert window.velocity == pytest.approx(123.4, abs=1e-9)
        if c > 20:  # the acceleration compares with the velocity a full window earlier
            assert window.acceleration == pytest.approx(0.0, abs=1e-6)
        assert window.position == enc.counts / 1000.0


def test_one_cycle_window_shows_the_count_quantisation() -> None:
    # FS701 "Normal setting: 1 ms": a 1-cycle window sees whole counts per cycle only
    line = Line(lambda t: 123.4 * t)
    enc = IncrementalEncoder(line, lines_per_unit=250.0, multiplier=4)
    master = EncoderMaster(enc, 1000.0, T)  # sampling time defaults to one cycle
    seen = set()
    for c in run_encoder(master, line, enc, range(1, 50)):
        if c > 1:  # the first update has no history yet
            seen.add(round(master.velocity, 6))
    assert seen == {123.0, 124.0}


def test_window_velocity_lags_a_ramp_by_half_the_sampling_time() -> None:
    a = 500.0  # mm/s^2
    line = Line(lambda t: 0.5 * a * t * t)
    enc = IncrementalEncoder(line, lines_per_unit=2500.0, multiplier=4)  # 10000 counts/mm
    n = 20
    master = EncoderMaster(enc, 10000.0, T, sampling_time=n * T)
    quantum = 2.0 / (10000.0 * n * T)  # two counts over the window
    for c in run_encoder(master, line, enc, range(1, 400)):
        if c > 2 * n:  # the window of the window (acceleration) is full
            expected = a * c * T - a * n * T / 2.0  # the mean speed over the window
            assert master.velocity == pytest.approx(expected, abs=quantum)
            assert master.acceleration == pytest.approx(a, abs=2.0 * quantum / (n * T))


def test_first_order_velocity_converges_and_lags_a_ramp_by_the_filter_lag() -> None:
    tau = 0.02
    line = Line(lambda t: 120.0 * t)  # 1200 counts per cycle exactly
    enc = IncrementalEncoder(line, lines_per_unit=2500.0, multiplier=4)
    master = EncoderMaster(enc, 10000.0, T, velocity_filter="first_order", time_constant=tau)
    for c in run_encoder(master, line, enc, range(1, 500)):
        pass
    assert master.velocity == pytest.approx(120.0, abs=1e-6)

    a = 500.0
    line = Line(lambda t: 0.5 * a * t * t)
    enc = IncrementalEncoder(line, lines_per_unit=2500.0, multiplier=4)
    master = EncoderMaster(enc, 10000.0, T, velocity_filter="first_order", time_constant=tau)
    lag = T / math.expm1(T / tau) + T / 2.0  # filter lag + half a cycle of the count difference
    assert lag == pytest.approx(tau, rel=0.01)
    for c in run_encoder(master, line, enc, range(1, 600)):
        if c > 20 * tau / T:
            assert master.velocity == pytest.approx(a * (c * T - lag), abs=0.02)
            assert master.acceleration == pytest.approx(a, abs=30.0)


def test_first_order_needs_a_time_constant() -> None:
    enc = IncrementalEncoder(Line(lambda t: 0.0), lines_per_unit=250.0)
    with pytest.raises(ValueError, match="time_constant"):
        EncoderMaster(enc, 1000.0, T, velocity_filter="first_order")


def test_counter_wrap_is_unwrapped_forward_and_back() -> None:
    # a 12-bit counter wraps every 4096 counts; the master counts on without a jump
    law = lambda t: 40.0 * t if t < 1.0 else 40.0 - 60.0 * (t - 1.0)  # noqa: E731
    line = Line(law)
    enc = IncrementalEncoder(line, lines_per_unit=250.0, multiplier=4, counter_bits=12)
    master = EncoderMaster(enc, 1000.0, T, sampling_time=0.005)
    wraps = 0
    previous_raw = enc.counts
    for c in run_encoder(master, line, enc, range(1, 2000)):
        assert master.counts == enc.counts_unwrapped
        wraps += abs(enc.counts - previous_raw) > 2048
        previous_raw = enc.counts
        if c > 10 and 0.01 < c * T < 0.99:
            assert master.velocity == pytest.approx(40.0, abs=0.3)
        if c * T > 1.01:
            assert master.velocity == pytest.approx(-60.0, abs=0.3)
    assert wraps >= 10  # the test really crossed the counter's wrap many times
    assert master.position == pytest.approx(law(1999 * T), abs=1e-3)


class RawCounter:
    """A 16-bit hardware counter without a delta() method."""

    def __init__(self) -> None:
        self.value = 0

    @property
    def counts(self) -> int:
        return self.value % 65536


def test_an_object_with_counts_wraps_with_counter_bits_and_the_multiplier_reverses() -> None:
    hw = RawCounter()
    master = EncoderMaster(hw, 100.0, T, counter_bits=16, multiplier=-1)
    assert master.counts_per_unit == 100.0
    for c in range(1, 300):
        hw.value += 1000  # wraps every 65.5 cycles
        master.update(c)
        assert master.counts == -1000 * c
        assert master.position == pytest.approx(-10.0 * c)


def test_update_is_idempotent_within_a_cycle() -> None:
    line = Line(lambda t: 50.0 * t)
    enc = IncrementalEncoder(line, lines_per_unit=250.0, multiplier=4)
    master = EncoderMaster(enc, 1000.0, T, sampling_time=0.004)
    for c in run_encoder(master, line, enc, range(1, 20)):
        v, counts = master.velocity, master.counts
        master.update(c)  # a second slave asking for the same cycle
        assert (master.velocity, master.counts) == (v, counts)
    assert master.velocity == pytest.approx(50.0)


# ------------------------------------------------------------------------ virtual master, time base


def test_virtual_master_ramps_to_its_velocity_and_integrates_exactly() -> None:
    vm = VirtualMaster(T, 50.0, acceleration=100.0, counts_per_unit=1000.0)
    for c in range(1, 2001):
        vm.update(c)
        assert abs(vm.acceleration) <= 100.0
        assert vm.counts == math.floor(vm.position * 1000.0 + 0.5)
    # trapezoid: 0.5 s ramp covering 12.5, then 50/s: p(2 s) = 87.5 exactly
    assert vm.in_velocity and vm.velocity == 50.0
    assert vm.position == pytest.approx(87.5, abs=1e-9)
    assert vm.counts == 87500


def test_virtual_master_changes_velocity_on_the_fly_without_steps() -> None:
    vm = VirtualMaster(T, 80.0, acceleration=200.0, jerk=4000.0)
    assert vm.shape == "jerk" and vm.counts_per_unit == FINE_COUNTS_PER_UNIT
    prev = None
    for c in range(1, 3000):
        if c == 300:
            vm.set_velocity(-20.0)  # in the middle of the ramp up
        vm.update(c)
        if prev is not None:
            p0, v0, a0 = prev
            assert abs(vm.velocity - v0) <= 200.0 * T * (1 + 1e-9)
            assert abs(vm.acceleration - a0) <= 4000.0 * T * (1 + 1e-9)
            assert vm.position - p0 == pytest.approx((vm.velocity + v0) / 2 * T, abs=1e-6)
        prev = (vm.position, vm.velocity, vm.acceleration)
    assert vm.velocity == -20.0 and vm.in_velocity


def test_time_base_speed_changes_ramp_over_the_ramp_time_whatever_their_size() -> None:
    tb = TimeBase(T, 10.0, ramp_time=0.5)
    assert tb.velocity == 10.0  # the initial speed holds from the start
    for c in range(1, 1001):
        tb.update(c)
    assert tb.position == pytest.approx(10.0, abs=1e-12)
    tb.set_speed(30.0)
    for c in range(1001, 2001):
        tb.update(c)
        if c == 1250:
            assert tb.velocity == pytest.approx(20.0) and tb.acceleration == pytest.approx(40.0)
    # 1 s at 10, 0.5 s ramp averaging 20, 0.5 s at 30
    assert tb.position == pytest.approx(10.0 + 10.0 + 15.0, abs=1e-9)
    tb.set_speed(35.0)  # a fifth of the change, same ramp time (COMPAX P39 is an absolute time)
    for c in range(2001, 2600):
        tb.update(c)
        if c == 2250:
            assert tb.acceleration == pytest.approx(10.0)
    assert tb.velocity == 35.0 and tb.acceleration == 0.0


# ------------------------------------------------------------------------ axis master


def axis() -> Axis:
    cfg = AxisConfig(name="line", unit="mm", counts_per_unit=1000.0, v_max=500.0, a_max=1000.0, following_error_limit=5.0)
    ax = Axis(cfg, T)
    ax.power(True)
    return ax


def test_axis_master_reads_the_set_point_exactly() -> None:
    ax = axis()
    master = AxisMaster(ax)
    ax.move_velocity(100.0)
    for c in range(1, 300):
        ax.update_setpoint(c)
        ax.position_loop(ax.command_position)
        master.update(c)
        assert (master.position, master.velocity, master.acceleration) == (
            ax.command_position,
            ax.command_velocity,
            ax.command_acceleration,
        )
        assert master.counts == math.floor(ax.command_position * FINE_COUNTS_PER_UNIT + 0.5)


def test_axis_master_actual_uses_the_actual_position() -> None:
    ax = axis()
    master = AxisMaster(ax, use="actual", counts_per_unit=1000.0)
    ax.move_velocity(100.0)
    lagging = 0.0
    for c in range(1, 300):
        ax.update_setpoint(c)
        lagging = ax.command_position - 0.05 if c > 1 else 0.0  # a plant that trails the set point
        ax.position_loop(lagging)
        master.update(c)
        assert master.position == ax.actual_position == lagging
        assert master.counts == math.floor(lagging * 1000.0 + 0.5)
    assert master.velocity == pytest.approx(100.0)
    assert master.acceleration == pytest.approx(0.0, abs=1e-6)


def test_axis_master_rejects_an_unknown_use() -> None:
    with pytest.raises(ValueError, match="use"):
        AxisMaster(axis(), use="target")  # type: ignore[arg-type]
