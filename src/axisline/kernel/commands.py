"""Command queue: the one door through which other threads change the machine.

Fieldbus and HMI threads ``submit`` calls; the cycle runs them in ``apply_pending`` at the
cycle boundary, so every stage of a cycle sees the same state. Scripted simulations use
``submit_at`` to run a command at the boundary of a given cycle, which makes runs repeatable.
"""

from __future__ import annotations

import heapq
import itertools
import threading
from collections import deque
from collections.abc import Callable
from concurrent.futures import Future
from typing import Any

__all__ = ["CommandQueue", "MissedCycleError"]


class MissedCycleError(RuntimeError):
    """A scheduled command's cycle boundary passed without the queue being applied there."""


class _Command:
    __slots__ = ("fn", "args", "kwargs", "future")

    def __init__(self, fn: Callable[..., Any], args: tuple[Any, ...], kwargs: dict[str, Any]):
        if not callable(fn):
            raise TypeError(f"command must be callable, got {fn!r}")
        self.fn = fn
        self.args = args
        self.kwargs = kwargs
        self.future: Future[Any] = Future()


class CommandQueue:
    """Thread-safe queue of calls applied at cycle boundaries (many producers, one cycle)."""

    def __init__(self) -> None:
        self._lock = threading.Lock()
        self._pending: deque[_Command] = deque()
        # (cycle, submission number, command): the number keeps same-cycle commands in order.
        self._scheduled: list[tuple[int, int, _Command]] = []
        self._numbers = itertools.count()
        self._last_boundary: int | None = None

    def submit(self, fn: Callable[..., Any], /, *args: Any, **kwargs: Any) -> Future[Any]:
        """Run ``fn(*args, **kwargs)`` at the next cycle boundary; the Future gets the result."""
        command = _Command(fn, args, kwargs)
        with self._lock:
            self._pending.append(command)
        return command.future

    def submit_at(
        self, cycle: int, fn: Callable[..., Any], /, *args: Any, **kwargs: Any
    ) -> Future[Any]:
        """Run ``fn(*args, **kwargs)`` at the boundary of ``cycle`` (before its stages run).

        Raises ValueError if that boundary has already been applied.
        """
        if isinstance(cycle, bool) or not isinstance(cycle, int) or cycle < 0:
            raise ValueError(f"command cycle must be an integer >= 0, got {cycle!r}")
        command = _Command(fn, args, kwargs)
        with self._lock:
            if self._last_boundary is not None and cycle <= self._last_boundary:
                raise ValueError(
                    f"command cycle {cycle} is not in the future: "
                    f"the boundary of cycle {self._last_boundary} has been applied"
                )
            heapq.heappush(self._scheduled, (cycle, next(self._numbers), command))
        return command.future

    def apply_pending(self, cycle: int) -> int:
        """Run the commands due at the boundary of ``cycle``; return how many ran.

        Scheduled commands for this cycle run first (in submission order), then the
        submitted ones (FIFO). A command's exception goes to its Future and the rest still
        run. Commands submitted while applying wait for the next boundary.
        """
        scheduled = self._scheduled
        if not scheduled and not self._pending:
            # the usual cycle, without the lock: a command appended meanwhile is simply
            # seen at the next boundary (reading a list's length is atomic in CPython)
            self._last_boundary = cycle
            return 0
        with self._lock:
            self._last_boundary = cycle
            due = bool(scheduled) and scheduled[0][0] <= cycle
            if not due and not self._pending:
                return 0  # the usual cycle: nothing to do, nothing allocated
            missed: list[tuple[int, _Command]] = []
            batch: list[_Command] = []
            while scheduled and scheduled[0][0] <= cycle:
                at, _, command = heapq.heappop(scheduled)
                if at < cycle:
                    missed.append((at, command))
                else:
                    batch.append(command)
            batch.extend(self._pending)
            self._pending.clear()

        for at, command in missed:
            if command.future.set_running_or_notify_cancel():
                command.future.set_exception(
                    MissedCycleError(f"command for cycle {at} reached only at cycle {cycle}")
                )
        ran = 0
        for index, command in enumerate(batch):
            future = command.future
            if not future.set_running_or_notify_cancel():
                continue  # cancelled by its producer before the boundary
            ran += 1
            try:
                result = command.fn(*command.args, **command.kwargs)
            except Exception as exc:
                future.set_exception(exc)
            except BaseException as exc:
                # KeyboardInterrupt/SystemExit end the run; no producer is left waiting.
                future.set_exception(exc)
                for rest in batch[index + 1 :]:
                    rest.future.cancel()
                raise
            else:
                future.set_result(result)
        return ran

    def cancel_pending(self) -> int:
        """Cancel every command not yet run (e.g. at shutdown); return how many."""
        with self._lock:
            commands = list(self._pending)
            commands.extend(command for _, _, command in self._scheduled)
            self._pending.clear()
            self._scheduled.clear()
        return sum(command.future.cancel() for command in commands)

    def __len__(self) -> int:
        """Commands waiting, submitted and scheduled."""
        with self._lock:
            return len(self._pending) + len(self._scheduled)
