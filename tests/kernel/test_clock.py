"""Cycle clocks: period validation, exact time, simulated vs wall-clock pacing."""

from __future__ import annotations

import time

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from axisline.kernel import Clock, SimulatedClock, WallClock, check_period_us, cycle_time

CLOCKS = [SimulatedClock, WallClock]


class FakeTime:
    """A perf_counter/sleep pair under test control: sleeping advances time exactly."""

    def __init__(self, start: float = 100.0) -> None:
        self.t = start
        self.slept: list[float] = []

    def timer(self) -> float:
        return self.t

    def sleep(self, seconds: float) -> None:
        self.slept.append(seconds)
        self.t += seconds


@pytest.mark.parametrize("clock_type", CLOCKS)
@pytest.mark.parametrize("period_us", [250, 1000, 4000, 10_000])
def test_accepts_periods_in_range(clock_type: type[Clock], period_us: int) -> None:
    clock = clock_type(period_us)
    assert isinstance(clock, Clock)
    assert clock.period_us == period_us
    assert clock.period == period_us / 1e6
    assert clock.cycle == 0
    assert clock.now == 0.0


@pytest.mark.parametrize("clock_type", CLOCKS)
@pytest.mark.parametrize("bad", [249, 10_001, 0, -1000, 1000.0, 999.5, "1000", None, True])
def test_rejects_bad_period_naming_field_value_and_range(
    clock_type: type[Clock], bad: object
) -> None:
    with pytest.raises(ValueError) as info:
        clock_type(bad)  # type: ignore[arg-type]
    message = str(info.value)
    assert "cycle period" in message
    assert repr(bad) in message
    assert "250" in message and "10000" in message


def test_numpy_integer_period_is_accepted() -> None:
    # Periods read from arrays or computed with numpy are still whole microseconds.
    assert check_period_us(np.int64(2000)) == 2000
    assert type(check_period_us(np.int64(2000))) is int


def test_now_is_exact_not_accumulated() -> None:
    clock = SimulatedClock(1000)
    accumulated = 0.0
    for _ in range(300):
        clock.tick()
        accumulated += clock.period
    # Summing 0.001 drifts (0.3000000000000002); the clock does not.
    assert accumulated != 0.3
    assert clock.now == 0.3
    assert clock.cycle == 300


@given(period_us=st.integers(250, 10_000), cycles=st.integers(0, 10**9))
def test_now_equals_integer_product(period_us: int, cycles: int) -> None:
    clock = SimulatedClock(period_us)
    clock._cycle = cycles  # jump ahead; ticking a billion times would only slow the test
    assert clock.now == cycles * period_us / 1e6 == cycle_time(cycles, period_us)


def test_simulated_clock_never_sleeps_nor_reads_wall_clock(monkeypatch: pytest.MonkeyPatch) -> None:
    def forbidden(*_: object) -> float:
        raise AssertionError("simulated clock touched wall time")

    for name in ("sleep", "perf_counter", "monotonic", "time", "perf_counter_ns", "monotonic_ns"):
        monkeypatch.setattr(time, name, forbidden)
    clock = SimulatedClock(250)
    for _ in range(10_000):
        clock.tick()
    assert clock.cycle == 10_000
    assert clock.now == 2.5


def test_wall_clock_paces_cycles_loosely() -> None:
    clock = WallClock(1000)
    start = time.perf_counter()
    for _ in range(20):
        clock.tick()
    elapsed = time.perf_counter() - start
    # The first tick anchors the grid, the other 19 each wait for a 1 ms deadline.
    assert elapsed >= 0.019
    assert clock.cycle == 20
    assert clock.now == 0.02


def test_wall_clock_waits_for_each_deadline_on_a_fixed_grid() -> None:
    fake = FakeTime()
    clock = WallClock(1000, timer=fake.timer, sleep=fake.sleep)
    clock.tick()  # anchors at t=100.0
    for n in range(1, 6):
        fake.t += 0.0003  # 0.3 ms of work per cycle
        clock.tick()
        assert fake.t == pytest.approx(100.0 + n * 0.001)
    assert clock.overruns == 0
    assert clock.late_max == pytest.approx(0.0, abs=1e-12)


def test_wall_clock_counts_overruns_and_catches_up_after_short_stall() -> None:
    fake = FakeTime()
    clock = WallClock(1000, timer=fake.timer, sleep=fake.sleep)
    clock.tick()  # anchor at 100.0; next deadline 100.001
    fake.t += 0.0035  # one cycle's work took 3.5 ms
    clock.tick()
    assert clock.overruns == 1
    assert clock.late_max == pytest.approx(0.0025)
    # Deadlines 100.002 and 100.003 have passed: the next ticks run without sleeping ...
    slept_before = len(fake.slept)
    clock.tick()
    clock.tick()
    assert len(fake.slept) == slept_before
    assert clock.overruns == 3
    # ... then the clock is back on the original grid.
    clock.tick()
    assert fake.t == pytest.approx(100.004)
    assert clock.rebases == 0


def test_wall_clock_rebases_after_long_stall_instead_of_racing() -> None:
    fake = FakeTime()
    clock = WallClock(1000, timer=fake.timer, sleep=fake.sleep)
    clock.tick()
    fake.t += 0.5  # stalled 500 cycles (debugger, swap, suspended laptop)
    clock.tick()
    assert clock.overruns == 1
    assert clock.rebases == 1
    assert clock.late_max == pytest.approx(0.499)
    stalled_at = fake.t
    clock.tick()  # paced again: waits one full period from the stall, no burst of cycles
    assert fake.t == pytest.approx(stalled_at + 0.001)
    assert clock.overruns == 1
    assert clock.cycle == 3


def test_wall_clock_late_max_includes_oversleeping() -> None:
    fake = FakeTime()

    def late_sleep(seconds: float) -> None:
        fake.sleep(seconds + 0.0002)  # the OS wakes us 0.2 ms late

    clock = WallClock(1000, timer=fake.timer, sleep=late_sleep)
    clock.tick()
    clock.tick()
    assert clock.overruns == 0
    assert clock.late_max == pytest.approx(0.0002)


def test_wall_clock_rejects_bad_stall_cycles() -> None:
    with pytest.raises(ValueError, match="stall_cycles"):
        WallClock(1000, stall_cycles=0)


def test_wall_clock_runs_the_idle_work_before_it_sleeps_and_spins_the_busy_wait_tail() -> None:
    fake = FakeTime()
    seen: list[float] = []

    def idle(deadline: float) -> None:
        seen.append(deadline - fake.t)  # idle time left when the cycle's work is done
        fake.t += 0.0002  # answering requests takes 0.2 ms of it

    reads = []

    def spinning_timer() -> float:  # each read while spinning takes 10 us
        reads.append(fake.t)
        if fake.t >= 100.0009 - 1e-12:
            fake.t += 0.00001
        return fake.t

    clock = WallClock(1000, timer=spinning_timer, sleep=fake.sleep, busy_wait_us=100, idle=idle)
    clock.tick()  # anchors at 100.0; idle is not called before there is a deadline
    fake.t += 0.0003
    clock.tick()
    assert seen == [pytest.approx(0.0007)]
    # it slept only to 100 us before the deadline, then read the timer until the deadline
    assert fake.slept == [pytest.approx(0.0004)]
    assert fake.t >= 100.001 and len(reads) >= 10  # spun through the last 100 us
    assert clock.lateness.samples == 1


def test_wall_clock_calls_idle_when_late_too_with_the_passed_deadline() -> None:
    fake = FakeTime()
    seen: list[float] = []
    clock = WallClock(1000, timer=fake.timer, sleep=fake.sleep, idle=lambda d: seen.append(d - fake.t))
    clock.tick()
    fake.t += 0.003  # a 3 ms cycle
    clock.tick()
    assert seen and seen[0] < 0  # serve answers one waiting request even then
    assert clock.lateness.last == pytest.approx(0.002)


def test_busy_wait_longer_than_the_period_is_refused_with_the_range() -> None:
    with pytest.raises(ValueError, match=r"busy_wait_us must be an integer in 0\.\.1000"):
        WallClock(1000, busy_wait_us=1500)


def test_lateness_percentiles_to_the_microsecond_and_the_exact_worst() -> None:
    from axisline.kernel.clock import Lateness

    late = Lateness()
    for us in range(1, 1001):  # 1 .. 1000 us, one cycle each
        late.add(us * 1e-6 - 1e-9)
    late.add(0.25)  # one stall beyond the histogram's 100 ms
    s = late.summary()
    assert s["cycles"] == 1001
    assert s["p50_us"] == pytest.approx(501, abs=1)
    assert s["p99_us"] == pytest.approx(991, abs=1)
    assert s["max_us"] == pytest.approx(250000.0)
    assert Lateness().summary()["p99_us"] == 0.0
