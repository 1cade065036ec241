"""Command queue: FIFO at the boundary, results in Futures, scheduled commands, threads."""

from __future__ import annotations

import threading
from concurrent.futures import CancelledError

import pytest

from axisline.kernel import CommandQueue, MissedCycleError


def test_commands_wait_for_the_boundary_and_run_fifo() -> None:
    queue = CommandQueue()
    log: list[str] = []
    futures = [queue.submit(log.append, name) for name in ("enable", "home", "move")]
    assert log == []  # nothing runs on the producer's thread
    assert not any(future.done() for future in futures)
    assert len(queue) == 3

    assert queue.apply_pending(0) == 3
    assert log == ["enable", "home", "move"]
    assert all(future.done() for future in futures)
    assert len(queue) == 0
    assert queue.apply_pending(1) == 0


def test_result_and_keyword_arguments_reach_the_future() -> None:
    queue = CommandQueue()

    def move(axis: str, *, position: float, fn: str = "absolute") -> str:
        return f"{axis} {fn} {position}"

    # fn is positional-only in submit, so a command may take a keyword called fn.
    future = queue.submit(move, "X", position=12.5, fn="relative")
    queue.apply_pending(0)
    assert future.result(timeout=0) == "X relative 12.5"


def test_failing_command_reports_to_its_future_and_others_still_run() -> None:
    queue = CommandQueue()
    log: list[int] = []

    def bad() -> None:
        raise ValueError("position out of range")

    first = queue.submit(log.append, 1)
    failing = queue.submit(bad)
    last = queue.submit(log.append, 3)
    assert queue.apply_pending(0) == 3
    assert log == [1, 3]
    assert first.exception() is None and last.exception() is None
    with pytest.raises(ValueError, match="position out of range"):
        failing.result(timeout=0)


def test_cancelled_command_is_skipped_and_not_counted() -> None:
    queue = CommandQueue()
    log: list[str] = []
    kept = queue.submit(log.append, "kept")
    dropped = queue.submit(log.append, "dropped")
    assert dropped.cancel()
    assert queue.apply_pending(0) == 1
    assert log == ["kept"]
    assert kept.result(timeout=0) is None


def test_command_submitted_by_a_command_waits_for_next_boundary() -> None:
    queue = CommandQueue()
    log: list[str] = []

    def first() -> None:
        log.append("first")
        queue.submit(log.append, "follow-up")

    queue.submit(first)
    assert queue.apply_pending(0) == 1
    assert log == ["first"]
    assert queue.apply_pending(1) == 1
    assert log == ["first", "follow-up"]


def test_submit_at_runs_at_that_boundary_in_submission_order() -> None:
    queue = CommandQueue()
    log: list[tuple[int, str]] = []
    cycle = 0

    def note(text: str) -> None:
        log.append((cycle, text))

    queue.submit_at(5, note, "b1")
    queue.submit_at(2, note, "a")
    queue.submit_at(5, note, "b2")
    queue.submit_at(5, note, "b3")
    for cycle in range(8):
        queue.apply_pending(cycle)
    assert log == [(2, "a"), (5, "b1"), (5, "b2"), (5, "b3")]


def test_scheduled_commands_run_before_submitted_ones_at_the_same_boundary() -> None:
    queue = CommandQueue()
    log: list[str] = []
    queue.submit(log.append, "submitted")
    queue.submit_at(0, log.append, "scheduled")
    assert queue.apply_pending(0) == 2
    assert log == ["scheduled", "submitted"]


def test_submit_at_refuses_a_boundary_already_applied() -> None:
    queue = CommandQueue()
    queue.apply_pending(0)
    queue.apply_pending(1)
    with pytest.raises(ValueError, match="cycle 1"):
        queue.submit_at(1, print)
    with pytest.raises(ValueError, match="cycle"):
        queue.submit_at(-3, print)
    queue.submit_at(2, print)  # the next boundary is still fine


def test_scheduled_command_whose_boundary_was_skipped_fails_loudly() -> None:
    queue = CommandQueue()
    log: list[str] = []
    future = queue.submit_at(3, log.append, "late")
    queue.apply_pending(7)  # boundaries 3..6 never applied
    assert log == []
    with pytest.raises(MissedCycleError, match="cycle 3"):
        future.result(timeout=0)


def test_cancel_pending_releases_waiting_producers() -> None:
    queue = CommandQueue()
    futures = [queue.submit(print), queue.submit_at(10, print)]
    assert queue.cancel_pending() == 2
    for future in futures:
        with pytest.raises(CancelledError):
            future.result(timeout=0)
    assert queue.apply_pending(10) == 0


def test_keyboard_interrupt_in_a_command_cancels_the_rest_instead_of_hanging() -> None:
    queue = CommandQueue()

    def interrupt() -> None:
        raise KeyboardInterrupt

    first = queue.submit(interrupt)
    rest = queue.submit(print)
    with pytest.raises(KeyboardInterrupt):
        queue.apply_pending(0)
    assert isinstance(first.exception(timeout=0), KeyboardInterrupt)
    assert rest.cancelled()


def test_many_producer_threads_each_command_runs_once_in_producer_order() -> None:
    queue = CommandQueue()
    producers, per_producer = 4, 2000
    seen: list[tuple[int, int]] = []
    start = threading.Barrier(producers + 1)

    def produce(producer: int) -> None:
        start.wait()
        for i in range(per_producer):
            queue.submit(seen.append, (producer, i))

    threads = [threading.Thread(target=produce, args=(p,)) for p in range(producers)]
    for thread in threads:
        thread.start()
    start.wait()
    cycle = 0
    ran = 0
    while any(thread.is_alive() for thread in threads) or len(queue):
        ran += queue.apply_pending(cycle)
        cycle += 1
    for thread in threads:
        thread.join()
    ran += queue.apply_pending(cycle)

    assert ran == producers * per_producer
    assert sorted(seen) == [(p, i) for p in range(producers) for i in range(per_producer)]
    for p in range(producers):
        assert [i for q, i in seen if q == p] == list(range(per_producer))
