"""Soft real-time measures of the cycle process (`[realtime]` in the machine file).

Python on a general-purpose OS cannot promise a deadline; these measures remove the large,
avoidable causes of lateness, each switched on by the user:

- gc = "idle": the objects made while the machine was built are frozen (never scanned
  again), automatic collection is switched off, and the cycle side collects the youngest
  generation in idle time, once enough objects have piled up and enough time is left before
  the next deadline. An automatic collection inside a cycle costs up to milliseconds.
- cpus: the cycle process is pinned to these CPUs (os.sched_setaffinity); the endpoint
  process is pinned to the others, so protocol work does not run where the cycle runs.
- fifo_priority: SCHED_FIFO for the cycle process. Needs CAP_SYS_NICE or an rtprio limit;
  where refused, serve says so in one line and runs with the normal scheduler.
- busy_wait_us: the WallClock spins through the last microseconds before each deadline.
"""

from __future__ import annotations

import gc
import os
import time
from typing import Any

__all__ = ["IdleCollector", "apply_cycle_measures", "endpoint_cpus", "measures_on"]

# gc = "idle": collect generation 0 once this many allocations are pending (Python's own
# threshold is 700; a collection of that many young objects takes tens of microseconds) ...
_GEN0_PENDING = 700
# ... and only when at least this much idle time is left before the deadline
_GEN0_IDLE_S = 200e-6
_OLDER_IDLE_S = 600e-6  # generation 1 and 2 collections need more room


def apply_cycle_measures(realtime: Any) -> list[str]:
    """Apply the measures to this (the cycle) process; returns what was done and refused,
    one line each, for the console and the event log."""
    notes: list[str] = []
    if realtime.cpus:
        try:
            os.sched_setaffinity(0, set(realtime.cpus))
            notes.append(f"cycle pinned to CPU {', '.join(map(str, sorted(set(realtime.cpus))))}")
        except (OSError, ValueError) as e:
            notes.append(f"realtime.cpus = {realtime.cpus} not applied ({e}); the cycle runs on any CPU "
                         f"(this machine has CPUs 0..{(os.cpu_count() or 1) - 1})")
    if realtime.fifo_priority:
        try:
            os.sched_setscheduler(0, os.SCHED_FIFO, os.sched_param(realtime.fifo_priority))
            notes.append(f"cycle on SCHED_FIFO priority {realtime.fifo_priority}")
        except (OSError, AttributeError) as e:
            notes.append(f"realtime.fifo_priority = {realtime.fifo_priority} not permitted here ({e}): "
                         "the cycle runs with the normal scheduler (needs CAP_SYS_NICE or an rtprio limit)")
    if realtime.gc == "idle":
        gc.collect()
        gc.freeze()
        gc.disable()
        notes.append("garbage collected in idle time only")
    if realtime.busy_wait_us:
        notes.append(f"busy-wait {realtime.busy_wait_us} us before each deadline")
    return notes


def measures_on(realtime: Any) -> bool:
    """Whether the user switched on any soft real-time measure."""
    return bool(realtime.gc == "idle" or realtime.cpus or realtime.fifo_priority or realtime.busy_wait_us)


def endpoint_cpus(realtime: Any) -> set[int] | None:
    """CPUs for the endpoint process: the ones the cycle does not use (None: no pinning)."""
    if not realtime.cpus:
        return None
    try:
        allowed = os.sched_getaffinity(0)
    except OSError:
        return None
    rest = allowed - set(realtime.cpus)
    return rest or None


class IdleCollector:
    """Garbage collection in the idle time before a deadline (gc = "idle")."""

    __slots__ = ("enabled", "collections", "longest_s")

    def __init__(self, enabled: bool) -> None:
        self.enabled = enabled
        self.collections = 0
        self.longest_s = 0.0  # the longest collection, for the stop event

    def __call__(self, deadline: float, timer: Any = time.perf_counter) -> None:
        if not self.enabled:
            return
        pending, gen1, gen2 = gc.get_count()
        if pending < _GEN0_PENDING:
            return
        start = timer()
        left = deadline - start
        if gen2 >= 10 and left > _OLDER_IDLE_S:
            gc.collect(2)
        elif gen1 >= 10 and left > _OLDER_IDLE_S:
            gc.collect(1)
        elif left > _GEN0_IDLE_S:
            gc.collect(0)
        else:
            return
        self.collections += 1
        took = timer() - start
        if took > self.longest_s:
            self.longest_s = took
