"""What the cycle process of `axisline serve` does between two cycles.

The WallClock calls `CycleSide.idle(deadline)` when a cycle's work is done. In that idle time,
in this order:

1. overruns: the cycle that just ended is checked against the overrun limit
   (`[realtime] overrun_us`, default one period); overruns are counted and logged (at most
   one event a second, with the count since the last); `on_overrun = "stop"` also stops every
   axis with its stop ramp, once per episode;
2. requests: the clients' requests waiting on the link are answered (CycleLink.pump) until half
   a period before the deadline (and before the busy-wait tail); at least one is answered per
   cycle, so a busy cycle slows clients down without starving them. Half, not all of the idle
   time: a cycle process busy to the deadline with 50 clients' requests started late more
   often (p99.9 ~1 ms against ~0.3 ms with half; bench/bench_serve.py), and clients still get
   thousands of answers a second;
3. faults: every 10 ms the axes' and the device's faults are compared with the last look;
   a new fault and a cleared one become events;
4. garbage: with `gc = "idle"`, a collection if enough time is left (realtime.py).

Decisions (issue 17 point -> choice, why):

1. "Overruns are counted" -> an overrun is a cycle that starts later than `overrun_us` after
   its deadline (default: one period), not every cycle a microsecond late: sleep jitter of tens
   of microseconds is normal on a general-purpose OS and is what the lateness percentiles
   show. Events are rate-limited to one a second (with the count), so an overloaded machine
   cannot flood its own log. Test: tests/serve/test_serve.py::test_overruns_are_counted_and_can_stop_the_axes.
2. "the reaction is configurable (log, or stop the axes with their ramps)" -> "stop" stops
   every axis with its stop ramp (the device's own stop where it has one), once per episode;
   serving goes on, so the operator sees why in the HMI and the log. Same test.
3. Faults are compared every 10 ms of wall time (not every cycle): a fault event 10 ms late
   is immaterial to an operator, a per-cycle comparison costs every cycle.
   Test: test_a_fault_appears_in_the_event_log.
"""

from __future__ import annotations

import time
from typing import Any, Callable

from .link import CycleLink
from .realtime import IdleCollector

__all__ = ["CycleSide"]

_FAULT_LOOK_S = 0.010  # how often faults are compared (wall time)
_OVERRUN_EVENT_S = 1.0  # at most one overrun event a second


class CycleSide:
    def __init__(self, machine: Any, link: CycleLink, realtime: Any, *, timer: Callable[[], float] = time.perf_counter) -> None:
        self.machine = machine
        self.link = link
        self.timer = timer
        period = machine.clock.period
        self.margin = 0.5 * period + realtime.busy_wait_us * 1e-6
        self.overrun_s = (realtime.overrun_us if realtime.overrun_us is not None else machine.clock.period_us) * 1e-6
        self.stop_on_overrun = realtime.on_overrun == "stop"
        self.collect = IdleCollector(realtime.gc == "idle")
        self.overruns = 0
        self._overruns_logged = 0
        self._last_overrun_event = -1e9
        self._stopped_for_overrun = False
        self._next_fault_look = 0.0
        self._faults: dict[str, str] = {}
        self._device_faults = _device_faults(machine.device)
        self._lateness = machine.clock.lateness
        self._last_samples = 0
        self._worst_since = 0.0
        self._previous_deadline: float | None = None
        self.longest_work_s = 0.0  # the longest cycle (its stages), for the stop event
        self.longest_pump_s = 0.0  # the longest time spent answering requests between two cycles

    def idle(self, deadline: float) -> None:
        start = self.timer()
        previous = self._previous_deadline
        if previous is not None:
            work = start - previous - self._lateness.last
            if work > self.longest_work_s:
                self.longest_work_s = work
        self._previous_deadline = deadline
        self._check_overrun()
        self.link.pump(deadline - self.margin, self.timer)
        now = self.timer()
        if now - start > self.longest_pump_s:
            self.longest_pump_s = now - start
        if now >= self._next_fault_look:
            self._next_fault_look = now + _FAULT_LOOK_S
            self.look_for_faults()
        self.collect(deadline, self.timer)

    # -- overruns ---------------------------------------------------------------------------

    def _check_overrun(self) -> None:
        lateness = self._lateness
        if lateness.samples == self._last_samples:
            return
        self._last_samples = lateness.samples
        late = lateness.last
        if late <= self.overrun_s:
            if self._stopped_for_overrun and self.machine.at_rest():
                self._stopped_for_overrun = False  # the next overrun stops again
            return
        self.overruns += 1
        if late > self._worst_since:
            self._worst_since = late
        now = self.timer()
        if now - self._last_overrun_event >= _OVERRUN_EVENT_S:
            count = self.overruns - self._overruns_logged
            self._overruns_logged = self.overruns
            self._last_overrun_event = now
            self.link.emit("overrun", f"{count} cycle(s) started more than {self.overrun_s * 1e3:g} ms late "
                           f"(worst {self._worst_since * 1e3:.2f} ms); {self.overruns} in all",
                           count=count, total=self.overruns, worst_ms=round(self._worst_since * 1e3, 3),
                           cycle=self.machine.clock.cycle)
            self._worst_since = 0.0
        if self.stop_on_overrun and not self._stopped_for_overrun:
            self._stopped_for_overrun = True
            self.stop_axes("overrun")

    def stop_axes(self, why: str) -> None:
        """Every moving axis stops with its stop ramp (the device's own stop where it has one)."""
        m = self.machine
        if m.device is None or not m.device.stop():
            for axis in m.axes.values():
                if axis.powered and axis.command_velocity != 0.0:
                    axis.stop()
        self.link.emit("stop", f"axes stopped with their ramps after an {why} (realtime.on_overrun = \"stop\")",
                       reason=why, cycle=m.clock.cycle)

    # -- faults ---------------------------------------------------------------------------

    def current_faults(self) -> dict[str, str]:
        faults: dict[str, str] = {}
        for name, axis in self.machine.axes.items():
            if axis.error_id:
                faults[f"axis {name}"] = f"error {axis.error_id:#x}: {axis.error_text}"
        device = self.machine.device
        if device is not None and self._device_faults is not None:
            try:
                faults.update(self._device_faults(device))
            except Exception as e:  # a device view must not stop the cycle
                faults["device"] = f"its fault list failed: {type(e).__name__}: {e}"
        return faults

    def look_for_faults(self) -> None:
        now = self.current_faults()
        before = self._faults
        if now == before:
            return
        cycle = self.machine.clock.cycle
        for source, text in now.items():
            if before.get(source) != text:
                kind = "watchdog" if source.startswith("watchdog") else "fault"
                self.link.emit(kind, f"{source}: {text}", source=source, text=text, cycle=cycle)
        for source, text in before.items():
            if source not in now:
                self.link.emit("cleared", f"{source}: cleared ({text})", source=source, text=text, cycle=cycle)
        self._faults = now


def _device_faults(device: Any) -> Callable[[Any], dict[str, str]] | None:
    if device is None:
        return None
    from ..hmi.devices import MODULES, device_faults

    return device_faults if getattr(device, "name", None) in MODULES else None
