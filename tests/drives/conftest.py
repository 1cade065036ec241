"""Machines with CiA 402 axes on python-can's virtual bus, each test on a bus of its own."""

from __future__ import annotations

import itertools
import time

import pytest

from axisline.config import MachineConfig, parse_machine
from axisline.drives import close_drives
from axisline.machine import Machine

_channels = itertools.count()


def axis_table(name: str, channel: str, node_id: int, **drive) -> dict:
    table = {
        "type": "cia402", "interface": "virtual", "channel": channel, "node_id": node_id,
        "simulated": {"time_constant": 0.002, "max_velocity": 300.0},
    }
    table.update(drive)
    return {
        "name": name, "kind": "linear", "unit": "mm", "counts_per_unit": 1000.0,
        "v_max": 200.0, "a_max": 2000.0, "kv": 40.0, "following_error_limit": 5.0,
        "jog_velocity": 50.0, "drive": table,
    }


@pytest.fixture
def channel() -> str:
    return f"test-drives-{next(_channels)}-{time.monotonic_ns()}"


@pytest.fixture
def machines():
    """Build machines with make(axes); every bus is left at teardown."""
    built: list[Machine] = []

    def make(*axes: dict, duration: float = 5.0, job: dict | None = None) -> Machine:
        data = {"machine": {"cycle_us": 1000, "duration": duration}, "axis": list(axes), "trace": {"enabled": False}}
        if job is not None:
            data["job"] = job
        m = Machine(parse_machine(data))
        built.append(m)
        return m

    yield make
    for m in built:
        close_drives(m)


def run_until(machine: Machine, predicate, *, cycles: int = 2000, wall_s: float = 10.0) -> bool:
    """Run cycles until predicate() holds (a wall-clock bound for heartbeat waits, not an assertion)."""
    end = time.monotonic() + wall_s
    for _ in range(cycles):
        if predicate():
            return True
        machine.scheduler.run_cycle()
        if time.monotonic() > end:
            break
    return predicate()


def wait_for(predicate, wall_s: float = 5.0) -> bool:
    end = time.monotonic() + wall_s
    while time.monotonic() < end:
        if predicate():
            return True
        time.sleep(0.005)
    return predicate()


def absent(table: dict) -> MachineConfig:
    """A machine with `table`'s axis whose drive is not there: the file says simulated (the
    virtual bus holds nothing else), the test takes the simulated drive away after the check."""
    config = parse_machine({"axis": [table]})
    config.axis[0].drive.simulated = None
    return config


def simulated(machine: Machine, axis: str):
    """The simulated drive behind an axis."""
    drive = machine.units[axis].drive
    return next(sim for sim in drive.bus.simulated if sim.node_id == drive.node_id)
