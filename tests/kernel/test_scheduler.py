"""Scheduler: stage order, sub-rates, commands at the boundary, run/stop."""

from __future__ import annotations

import signal
import threading
import time
import tracemalloc
from pathlib import Path

import pytest

import axisline.kernel as kernel
from axisline.kernel import CommandQueue, Scheduler, SimulatedClock, Stage, WallClock


def make_scheduler(period_us: int = 1000) -> Scheduler:
    return Scheduler(SimulatedClock(period_us))


def test_stages_are_in_cycle_order() -> None:
    assert list(Stage) == [
        Stage.INPUTS,
        Stage.LOGIC,
        Stage.SETPOINTS,
        Stage.POSITION_LOOP,
        Stage.ACTUATE,
        Stage.RECORD,
    ]
    assert sorted(Stage) == list(Stage)


def test_cycle_runs_stages_in_order_and_tasks_in_registration_order() -> None:
    sched = make_scheduler()
    log: list[tuple[int, str]] = []

    def task(name: str):
        return lambda cycle: log.append((cycle, name))

    # Registered deliberately out of stage order.
    sched.add_task("scope", task("scope"), Stage.RECORD)
    sched.add_task("drive", task("drive"), Stage.ACTUATE)
    sched.add_task("profile", task("profile"), Stage.SETPOINTS)
    sched.add_task("encoder", task("encoder"), Stage.INPUTS)
    sched.add_task("kv", task("kv"), Stage.POSITION_LOOP)
    sched.add_task("program", task("program"), Stage.LOGIC)
    sched.add_task("marks", task("marks"), Stage.INPUTS)
    sched.add_task("outputs", task("outputs"), Stage.ACTUATE)

    order = ["encoder", "marks", "program", "profile", "kv", "drive", "outputs", "scope"]
    assert [t.name for t in sched.tasks] == order
    assert sched.run(2) == 2
    assert log == [(0, name) for name in order] + [(1, name) for name in order]


def test_clock_ticks_after_the_stages() -> None:
    sched = make_scheduler(500)
    seen: list[tuple[int, int, float]] = []
    clock = sched.clock
    sched.add_task("probe", lambda c: seen.append((c, clock.cycle, clock.now)), Stage.RECORD)
    assert sched.run_cycle() == 0
    assert sched.run_cycle() == 1
    # Every task of cycle n sees clock.cycle == n and time n*T; the tick comes afterwards.
    assert seen == [(0, 0, 0.0), (1, 1, 0.0005)]
    assert sched.clock.cycle == 2


def test_sub_rate_task_every_4_phase_1() -> None:
    sched = make_scheduler()
    logic: list[int] = []
    fast: list[int] = []
    sched.add_task("logic task", logic.append, Stage.LOGIC, every=4, phase=1)
    sched.add_task("nc task", fast.append, Stage.SETPOINTS)
    sched.run(13)
    assert logic == [1, 5, 9]
    assert fast == list(range(13))


@pytest.mark.parametrize("every,phase", [(0, 0), (-2, 0), (4, 4), (4, -1), (2.0, 0), (4, 1.0)])
def test_bad_rates_are_refused(every: object, phase: object) -> None:
    sched = make_scheduler()
    with pytest.raises(ValueError):
        sched.add_task("t", print, Stage.LOGIC, every=every, phase=phase)  # type: ignore[arg-type]
    assert sched.tasks == ()


def test_duplicate_names_are_refused_and_remove_task_stops_a_task() -> None:
    sched = make_scheduler()
    log: list[str] = []
    sched.add_task("a", lambda c: log.append("a"), Stage.LOGIC)
    sched.add_task("b", lambda c: log.append("b"), Stage.LOGIC)
    with pytest.raises(ValueError, match="'a'"):
        sched.add_task("a", print, Stage.INPUTS)
    sched.run_cycle()
    sched.remove_task("a")
    sched.run_cycle()
    assert log == ["a", "b", "b"]
    with pytest.raises(KeyError, match="'a'"):
        sched.remove_task("a")
    sched.add_task("a", lambda c: log.append("a again"), Stage.INPUTS)  # name is free again
    sched.run_cycle()
    assert log[-2:] == ["a again", "b"]


def test_stage_must_be_a_stage() -> None:
    with pytest.raises(TypeError):
        make_scheduler().add_task("t", print, 2)  # type: ignore[arg-type]


def test_task_added_during_a_cycle_runs_from_the_next_cycle() -> None:
    sched = make_scheduler()
    late: list[int] = []

    def adder(cycle: int) -> None:
        if cycle == 1:
            sched.add_task("late", late.append, Stage.RECORD)

    sched.add_task("adder", adder, Stage.LOGIC)
    sched.run(4)
    assert late == [2, 3]


def test_queued_commands_apply_before_the_first_stage() -> None:
    sched = make_scheduler()
    state = {"target": 0.0}
    seen: list[tuple[int, float]] = []
    sched.add_task("inputs", lambda c: seen.append((c, state["target"])), Stage.INPUTS)
    sched.run(2)
    future = sched.commands.submit(state.__setitem__, "target", 50.0)
    sched.run(1)
    assert future.done()
    assert seen == [(0, 0.0), (1, 0.0), (2, 50.0)]


def test_scripted_commands_apply_at_their_cycle() -> None:
    queue = CommandQueue()
    sched = Scheduler(SimulatedClock(1000), queue)
    assert sched.commands is queue
    state = {"speed": 0}
    seen: list[int] = []
    queue.submit_at(3, state.__setitem__, "speed", 7)
    sched.add_task("setpoints", lambda c: seen.append(state["speed"]), Stage.SETPOINTS)
    sched.run(5)
    assert seen == [0, 0, 0, 7, 7]


def test_command_from_another_thread_mid_cycle_waits_for_the_boundary() -> None:
    """A producer submits while the cycle is between LOGIC and SETPOINTS: the rest of that
    cycle still sees the old value, the next cycle sees the new one in every stage."""
    sched = make_scheduler()
    state = {"setpoint": 0}
    seen: dict[int, list[int]] = {}
    in_logic = threading.Event()
    submitted = threading.Event()
    futures = []

    def producer() -> None:
        in_logic.wait(timeout=5)
        futures.append(sched.commands.submit(state.__setitem__, "setpoint", 1))
        submitted.set()

    def observe(cycle: int) -> None:
        seen.setdefault(cycle, []).append(state["setpoint"])

    def logic(cycle: int) -> None:
        observe(cycle)
        if cycle == 2:
            in_logic.set()
            assert submitted.wait(timeout=5)

    sched.add_task("inputs", observe, Stage.INPUTS)
    sched.add_task("logic", logic, Stage.LOGIC)
    for stage in list(Stage)[2:]:
        sched.add_task(stage.name, observe, stage)
    thread = threading.Thread(target=producer)
    thread.start()
    sched.run(4)
    thread.join()

    assert seen[2] == [0] * 6
    assert seen[3] == [1] * 6
    assert futures[0].result(timeout=0) is None


def test_commands_hammered_from_a_thread_never_split_a_cycle() -> None:
    sched = make_scheduler()
    state = {"value": 0}
    per_cycle: list[set[int]] = []
    current: set[int] = set()
    done = threading.Event()

    def observe(cycle: int) -> None:
        current.add(state["value"])

    def close(cycle: int) -> None:
        current.add(state["value"])
        per_cycle.append(set(current))
        current.clear()

    for stage in list(Stage)[:-1]:
        sched.add_task(stage.name, observe, stage)
    sched.add_task("close", close, Stage.RECORD)

    def producer() -> None:
        for i in range(1, 3001):
            sched.commands.submit(state.__setitem__, "value", i)
            if i % 50 == 0:
                time.sleep(0.0001)  # let the cycle thread in, so submissions interleave
        done.set()

    thread = threading.Thread(target=producer)
    thread.start()
    sched.run_until(lambda: done.is_set() and not len(sched.commands), max_cycles=1_000_000)
    thread.join()
    sched.run(1)

    assert state["value"] == 3000
    assert all(len(values) == 1 for values in per_cycle)  # one value per whole cycle
    assert len({value for values in per_cycle for value in values}) > 2  # it did interleave


def test_run_until_checks_before_each_cycle() -> None:
    sched = make_scheduler()
    count: list[int] = []
    sched.add_task("count", count.append, Stage.LOGIC)
    assert sched.run_until(lambda: len(count) >= 7, max_cycles=100) is True
    assert sched.clock.cycle == 7
    assert sched.run_until(lambda: True, max_cycles=100) is True
    assert sched.clock.cycle == 7  # already true: no cycle run
    assert sched.run_until(lambda: False, max_cycles=5) is False
    assert sched.clock.cycle == 12


def test_stop_from_a_task_ends_the_run_after_that_cycle() -> None:
    sched = make_scheduler()
    sched.add_task("fault", lambda c: sched.stop() if c == 5 else None, Stage.LOGIC)
    assert sched.run(100) == 6
    assert sched.clock.cycle == 6
    assert not sched.stop_requested  # consumed by the run that honoured it
    assert sched.run(3) == 3


def test_stop_ends_run_until() -> None:
    sched = make_scheduler()
    sched.add_task("fault", lambda c: sched.stop() if c == 2 else None, Stage.LOGIC)
    assert sched.run_until(lambda: False, max_cycles=100) is False
    assert sched.clock.cycle == 3


@pytest.mark.skipif(not hasattr(signal, "setitimer"), reason="needs POSIX interval timer")
def test_signal_handler_ends_a_wall_clock_run_cleanly() -> None:
    sched = Scheduler(WallClock(1000))
    recorded: list[int] = []
    sched.add_task("record", recorded.append, Stage.RECORD)
    previous = signal.signal(signal.SIGALRM, lambda signum, frame: sched.stop())
    try:
        signal.setitimer(signal.ITIMER_REAL, 0.05)
        ran = sched.run(60_000)  # a minute if the signal were ignored
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, previous)
    assert 0 < ran < 60_000
    # Clean end: every cycle that started finished all stages and ticked the clock.
    assert recorded == list(range(ran))
    assert sched.clock.cycle == ran


def test_failing_task_propagates_and_does_not_tick() -> None:
    sched = make_scheduler()

    def broken(cycle: int) -> None:
        raise RuntimeError("following error")

    sched.add_task("kv", broken, Stage.POSITION_LOOP)
    with pytest.raises(RuntimeError, match="following error"):
        sched.run(3)
    assert sched.clock.cycle == 0


def test_run_cycle_cannot_nest() -> None:
    sched = make_scheduler()
    sched.add_task("nested", lambda c: sched.run_cycle(), Stage.LOGIC)
    with pytest.raises(RuntimeError, match="inside a cycle"):
        sched.run_cycle()
    sched.remove_task("nested")
    sched.run_cycle()  # the scheduler is usable again
    assert sched.clock.cycle == 1


def test_long_run_does_not_grow_memory() -> None:
    """A controller runs for weeks: cycles (and the command path) must not accumulate."""
    sched = make_scheduler()
    counter = [0]

    def work(cycle: int) -> None:
        counter[0] += 1

    for stage in Stage:
        sched.add_task(stage.name, work, stage)
    sched.add_task("slow", work, Stage.LOGIC, every=4, phase=3)
    kernel_dir = str(Path(kernel.__file__).parent)

    def kernel_bytes(snapshot: tracemalloc.Snapshot) -> int:
        only_kernel = snapshot.filter_traces([tracemalloc.Filter(True, kernel_dir + "/*")])
        return sum(stat.size for stat in only_kernel.statistics("filename"))

    sched.run(1000)  # warm-up
    tracemalloc.start()
    try:
        before = kernel_bytes(tracemalloc.take_snapshot())
        for block in range(20):
            sched.commands.submit(work, 0)
            sched.run(1000)
        after = kernel_bytes(tracemalloc.take_snapshot())
    finally:
        tracemalloc.stop()
    assert after - before < 1024
    assert sched.clock.cycle == 21_000
