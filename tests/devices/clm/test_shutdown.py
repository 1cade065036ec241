"""Shutdown (`axisline serve`'s Ctrl-C, SIGTERM): the CLM stops as its Immediate Stop does (tasks
stop where they are, the axes decelerate with their current ramps), without a fault."""

from __future__ import annotations

from pathlib import Path

import pytest

from axisline.machine import Machine

EXAMPLES = Path(__file__).resolve().parents[3] / "examples"


@pytest.mark.parametrize("example, cycles", [
    ("roll_feed_clm", 257),  # mid-feed: the kernel's own stop ramp tripped Drive Runaway (fault 42) here
    ("roll_feed_clm", 600),
    ("flying_cutoff_clm", 1500),
    ("rotary_table_clm", 400),
])
def test_a_shutdown_in_the_middle_of_a_motion_stops_the_axes_without_a_fault(example, cycles):
    m = Machine.from_file(EXAMPLES / f"{example}.toml")
    m.scheduler.run(cycles)
    assert m.device.rt.modes.fault_error is None
    assert m.stop_all()  # every axis at rest
    assert m.device.rt.modes.fault_error is None
    assert all(axis.command_velocity == 0.0 for axis in m.axes.values())
