"""Cycle scheduler: command boundary, then the six stages in order, then the clock tick."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from enum import IntEnum

from .clock import Clock
from .commands import CommandQueue

__all__ = ["Scheduler", "Stage", "Task"]


class Stage(IntEnum):
    """Stages of one cycle, in the order they run."""

    INPUTS = 0  # sample encoders, digital/analog inputs, marks
    LOGIC = 1  # device personalities: programs, tasks, parameters
    SETPOINTS = 2  # motion: axis state machines, profiles, gears, cams
    POSITION_LOOP = 3  # Kv, feed-forward, following-error monitoring
    ACTUATE = 4  # drive commands and outputs to the plant
    RECORD = 5  # scope / trace


@dataclass(frozen=True, slots=True)
class Task:
    """A callable run as ``fn(cycle)`` in ``stage`` on cycles where (cycle - phase) % every == 0."""

    name: str
    fn: Callable[[int], object]
    stage: Stage
    every: int = 1
    phase: int = 0

    def runs_on(self, cycle: int) -> bool:
        return (cycle - self.phase) % self.every == 0


class Scheduler:
    """Runs cycles on a clock; external commands apply only at cycle boundaries."""

    def __init__(self, clock: Clock, commands: CommandQueue | None = None) -> None:
        self.clock = clock
        self.commands = commands if commands is not None else CommandQueue()
        self._tasks: dict[str, Task] = {}
        # Flat (fn, every, phase) in cycle order, rebuilt when tasks change, so a cycle only
        # iterates a tuple. A change made during a cycle takes effect at the next one.
        self._plan: tuple[tuple[Callable[[int], object], int, int], ...] = ()
        self._stop_requested = False
        self._in_cycle = False

    # -- tasks -----------------------------------------------------------------------------

    def add_task(
        self,
        name: str,
        fn: Callable[[int], object],
        stage: Stage,
        every: object = 1,
        phase: object = 0,
    ) -> Task:
        """Register ``fn(cycle)``; within a stage, tasks run in registration order.

        ``every`` (>= 1) and ``phase`` (0..every-1) are integers; they are typed ``object``
        because the checks below, not the signature, refuse anything else with a ValueError
        that names them (a compiled signature would raise a bare TypeError first)."""
        if not isinstance(name, str) or not name:
            raise ValueError(f"task name must be a non-empty string, got {name!r}")
        if name in self._tasks:
            raise ValueError(f"task {name!r} is already registered")
        if not callable(fn):
            raise TypeError(f"task {name!r}: fn must be callable, got {fn!r}")
        if not isinstance(stage, Stage):
            raise TypeError(f"task {name!r}: stage must be a Stage, got {stage!r}")
        if isinstance(every, bool) or not isinstance(every, int) or every < 1:
            raise ValueError(f"task {name!r}: every must be an integer >= 1, got {every!r}")
        if isinstance(phase, bool) or not isinstance(phase, int) or not 0 <= phase < every:
            raise ValueError(
                f"task {name!r}: phase must be an integer in 0..{every - 1}, got {phase!r}"
            )
        task = Task(name, fn, stage, every, phase)
        self._tasks[name] = task
        self._rebuild_plan()
        return task

    def remove_task(self, name: str) -> Task:
        """Unregister a task; KeyError if there is none by that name."""
        try:
            task = self._tasks.pop(name)
        except KeyError:
            raise KeyError(f"no task named {name!r}") from None
        self._rebuild_plan()
        return task

    @property
    def tasks(self) -> tuple[Task, ...]:
        """Registered tasks in the order a cycle runs them."""
        return tuple(sorted(self._tasks.values(), key=lambda task: task.stage))

    def _rebuild_plan(self) -> None:
        # sorted() is stable and dicts keep insertion order: registration order per stage.
        self._plan = tuple((task.fn, task.every, task.phase) for task in self.tasks)

    # -- running ---------------------------------------------------------------------------

    def run_cycle(self) -> int:
        """Run one cycle and return its index.

        Order: queued commands (boundary), INPUTS .. RECORD, clock tick. If a task raises,
        the exception propagates and the clock is not ticked.
        """
        if self._in_cycle:
            raise RuntimeError("run_cycle called from inside a cycle")
        self._in_cycle = True
        try:
            clock = self.clock
            cycle = clock.cycle
            self.commands.apply_pending(cycle)
            for fn, every, phase in self._plan:
                if every == 1 or (cycle - phase) % every == 0:
                    fn(cycle)
            clock.tick()
        finally:
            self._in_cycle = False
        return cycle

    def run(self, cycles: int) -> int:
        """Run ``cycles`` cycles, or fewer if ``stop()`` is called; return how many ran."""
        if isinstance(cycles, bool) or not isinstance(cycles, int) or cycles < 0:
            raise ValueError(f"cycles must be an integer >= 0, got {cycles!r}")
        done = 0
        while done < cycles:
            if self._stop_requested:
                self._stop_requested = False
                break
            self.run_cycle()
            done += 1
        return done

    def run_until(self, predicate: Callable[[], bool], max_cycles: int) -> bool:
        """Run cycles until ``predicate()`` is true (checked before each cycle).

        Returns True when the predicate held, False when ``max_cycles`` ran out or
        ``stop()`` was called first.
        """
        if isinstance(max_cycles, bool) or not isinstance(max_cycles, int) or max_cycles < 0:
            raise ValueError(f"max_cycles must be an integer >= 0, got {max_cycles!r}")
        done = 0
        while not predicate():
            if done >= max_cycles:
                return False
            if self._stop_requested:
                self._stop_requested = False
                return False
            self.run_cycle()
            done += 1
        return True

    def stop(self) -> None:
        """Ask a running ``run``/``run_until`` to return after the current cycle.

        Safe to call from a signal handler or another thread: it only sets a flag, which
        the run loop reads between cycles and clears when it honours it.
        """
        self._stop_requested = True

    @property
    def stop_requested(self) -> bool:
        return self._stop_requested
