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


class WallClock(Clock):
    """Paces cycles on the wall clock (soft real time: perf_counter + sleep).

    The first tick anchors the cycle grid; each later tick waits for the next deadline on
    that grid. A tick that arrives after its deadline is an overrun and returns at once, so
    a short stall is made up by the following cycles. After a stall of more than
    ``stall_cycles`` periods the grid is re-based on the present instead, because racing
    through hundreds of cycles back to back would hit the plant with a burst.
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
    )

    def __init__(
        self,
        period_us: int,
        *,
        stall_cycles: int = 100,
        timer: Callable[[], float] = time.perf_counter,
        sleep: Callable[[float], None] = time.sleep,
    ) -> None:
        super().__init__(period_us)
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
        if now < deadline:
            while now < deadline:
                self._sleep(deadline - now)
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
        self._cycle += 1
