"""Cycle clocks: simulated (as fast as possible, exact) and wall clock (soft real time).

Time is the integer cycle counter times the integer period in microseconds. It is computed,
never accumulated, so a simulated run gives the same time stamps on every machine.
"""

from __future__ import annotations

import numbers
import time
from abc import ABC, abstractmethod
from collections.abc import Callable

__all__ = [
    "MAX_PERIOD_US",
    "MIN_PERIOD_US",
    "Clock",
    "SimulatedClock",
    "Lateness",
    "WallClock",
    "check_period_us",
    "cycle_time",
]

MIN_PERIOD_US = 250
MAX_PERIOD_US = 10_000


def check_period_us(period_us: object) -> int:
    """Return ``period_us`` if it is an integer number of microseconds in 250..10000."""
    # bool is an int subclass but never a period; floats are refused even when whole, so a
    # config that computed 999.9999 us is reported instead of silently truncated.
    if isinstance(period_us, numbers.Integral) and not isinstance(period_us, bool):
        if MIN_PERIOD_US <= period_us <= MAX_PERIOD_US:
            return int(period_us)
    raise ValueError(
        f"cycle period must be an integer number of microseconds in "
        f"{MIN_PERIOD_US}..{MAX_PERIOD_US} (0.25 ms to 10 ms), got {period_us!r}"
    )


def cycle_time(cycle: int, period_us: int) -> float:
    """Time in seconds at the start of ``cycle``; exact integer product, one rounding."""
    return cycle * period_us / 1_000_000


class Clock(ABC):
    """The cycle counter every kernel part reads; ``tick()`` ends the current cycle."""

    __slots__ = ("_period_us", "_cycle")

    def __init__(self, period_us: int) -> None:
        self._period_us = check_period_us(period_us)
        self._cycle = 0

    @property
    def period_us(self) -> int:
        """Cycle period in microseconds."""
        return self._period_us

    @property
    def period(self) -> float:
        """Cycle period in seconds."""
        return self._period_us / 1_000_000

    @property
    def cycle(self) -> int:
        """Index of the current cycle, 0 before the first tick."""
        return self._cycle

    @property
    def now(self) -> float:
        """Simulated time in seconds at the start of the current cycle."""
        return self._cycle * self._period_us / 1_000_000

    @abstractmethod
    def tick(self) -> None:
        """End the current cycle and start the next one."""

    def __repr__(self) -> str:
        return f"{type(self).__name__}(period_us={self._period_us}, cycle={self._cycle})"


class SimulatedClock(Clock):
    """Runs cycles back to back; never sleeps, never reads the wall clock."""

    __slots__ = ()

    def tick(self) -> None:
        self._cycle += 1


class Lateness:
    """How late cycles started after their deadlines: a histogram in 1 us steps up to 100 ms.

    Fixed memory whatever the run length, one list increment per cycle; percentiles are read
    off the cumulative counts (to the microsecond), the worst case is kept exactly."""

    __slots__ = ("_counts", "samples", "worst", "last")

    BINS = 100_000  # 1 us each: 0 .. 100 ms; later cycles land in the last bin

    def __init__(self) -> None:
        self._counts = [0] * self.BINS
        self.samples = 0
        self.worst = 0.0
        self.last = 0.0

    def add(self, late_s: float) -> None:
        self.last = late_s
        i = int(late_s * 1e6)
        if i < 0:
            i = 0
        elif i >= 100_000:
            i = 99_999
        self._counts[i] += 1
        self.samples += 1
        if late_s > self.worst:
            self.worst = late_s

    def percentile(self, p: float) -> float:
        """Lateness in seconds that ``p`` percent of the cycles did not exceed (bin's upper edge)."""
        if not self.samples:
            return 0.0
        rank = p / 100.0 * self.samples
        seen = 0
        for i, n in enumerate(self._counts):
            seen += n
            if n and seen >= rank:
                return min((i + 1) * 1e-6, self.worst)
        return self.worst

    def summary(self) -> dict[str, float]:
        """p50 / p99 / p99.9 / max in microseconds and the number of cycles measured."""
        return {
            "cycles": self.samples,
            "p50_us": round(self.percentile(50) * 1e6, 1),
            "p99_us": round(self.percentile(99) * 1e6, 1),
            "p99_9_us": round(self.percentile(99.9) * 1e6, 1),
            "max_us": round(self.worst * 1e6, 1),
        }


class WallClock(Clock):
    """Paces cycles on the wall clock (soft real time: perf_counter + sleep).

    The first tick anchors the cycle grid; each later tick waits for the next deadline on
    that grid. A tick that arrives after its deadline is an overrun and returns at once, so
    a short stall is made up by the following cycles. After a stall of more than
    ``stall_cycles`` periods the grid is re-based on the present instead, because racing
    through hundreds of cycles back to back would hit the plant with a burst.

    The wait before a deadline is the cycle's idle time: ``idle(deadline)``, when set, runs
    there first (`serve` answers its clients' requests and collects garbage in it, so neither
    happens inside a cycle; it is called with a deadline already passed too), then the clock sleeps, and the last ``busy_wait_us`` before the
    deadline it spins instead: the OS wakes a sleeper up to tens of microseconds late, a
    spinning thread is already running. ``lateness`` keeps the distribution of how late each
    cycle started.
    """

    __slots__ = (
        "_period_s",
        "_stall_cycles",
        "_timer",
        "_sleep",
        "_base",
        "_cycles_since_base",
        "overruns",
        "rebases",
        "late_max",
        "lateness",
        "idle",
        "_busy_wait_s",
    )

    def __init__(
        self,
        period_us: int,
        *,
        stall_cycles: int = 100,
        timer: Callable[[], float] = time.perf_counter,
        sleep: Callable[[float], None] = time.sleep,
        busy_wait_us: int = 0,
        idle: Callable[[float], None] | None = None,
    ) -> None:
        super().__init__(period_us)
        if isinstance(busy_wait_us, bool) or not isinstance(busy_wait_us, int) or not 0 <= busy_wait_us <= self._period_us:
            raise ValueError(f"busy_wait_us must be an integer in 0..{self._period_us} (the period), got {busy_wait_us!r}")
        self._busy_wait_s = busy_wait_us / 1_000_000
        self.idle = idle
        """Called with the next deadline (timer seconds) when a cycle ends before it."""
        self.lateness = Lateness()
        if isinstance(stall_cycles, bool) or not isinstance(stall_cycles, int) or stall_cycles < 1:
            raise ValueError(f"stall_cycles must be an integer >= 1, got {stall_cycles!r}")
        self._period_s = self._period_us / 1_000_000
        self._stall_cycles = stall_cycles
        self._timer = timer
        self._sleep = sleep
        self._base: float | None = None
        self._cycles_since_base = 0
        self.overruns = 0
        """Ticks that came after their deadline (the cycle's work took too long)."""
        self.rebases = 0
        """Stalls longer than ``stall_cycles`` periods, after which the grid was re-based."""
        self.late_max = 0.0
        """Worst lateness seen in seconds: how long after its deadline a cycle started."""

    def tick(self) -> None:
        now = self._timer()
        if self._base is None:
            self._base = now
            self._cycle += 1
            return
        self._cycles_since_base += 1
        # Deadlines are base + n * period, not accumulated, so the grid does not drift.
        deadline = self._base + self._cycles_since_base * self._period_s
        idle = self.idle
        if idle is not None:
            # also when the cycle is late: then idle does only what cannot wait (it answers one
            # waiting request, so clients of a busy machine are slowed down, never starved)
            idle(deadline)
            now = self._timer()
        if now < deadline:
            wake = deadline - self._busy_wait_s
            while now < wake:
                self._sleep(wake - now)
                now = self._timer()
            while now < deadline:  # the busy-wait tail (empty unless busy_wait_us)
                now = self._timer()
        else:
            self.overruns += 1
            if now - deadline > self._stall_cycles * self._period_s:
                self.rebases += 1
                self._base = now
                self._cycles_since_base = 0
        late = now - deadline
        if late > self.late_max:
            self.late_max = late
        self.lateness.add(late)
        self._cycle += 1
