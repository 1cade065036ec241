"""The cycle kernel: clock, scheduler with stages and sub-rates, command queue, trace."""

from .atomic import atomic_open, atomic_write_bytes, atomic_write_text
from .clock import (
    MAX_PERIOD_US,
    MIN_PERIOD_US,
    Clock,
    SimulatedClock,
    WallClock,
    check_period_us,
    cycle_time,
)
from .commands import CommandQueue, MissedCycleError
from .scheduler import Scheduler, Stage, Task
from .trace import Recording, Trace

__all__ = [
    "MAX_PERIOD_US",
    "MIN_PERIOD_US",
    "Clock",
    "CommandQueue",
    "MissedCycleError",
    "Recording",
    "Scheduler",
    "SimulatedClock",
    "Stage",
    "Task",
    "Trace",
    "WallClock",
    "atomic_open",
    "atomic_write_bytes",
    "atomic_write_text",
    "check_period_us",
    "cycle_time",
]
