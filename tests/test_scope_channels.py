"""The scope's channel wiring (scope_channels.py): names, order, units and the values read."""

import copy

import numpy as np
import pytest

from axisline.config import parse_machine
from axisline.configerrors import ConfigError
from axisline.kernel import Stage
from axisline.machine import Machine
from axisline.motion.axis import AxisState
from axisline.scope_channels import AXIS_SIGNALS

SERVO = {
    "name": "x", "unit": "mm", "counts_per_unit": 2000.0, "v_max": 200.0, "a_max": 2000.0, "j_max": 50000.0,
    "kv": 40.0, "following_error_limit": 2.0,
    "drive": {"type": "servo", "time_constant": 0.002},
    "encoder": {"lines_per_unit": 500.0, "multiplier": 4},
}
STEPPER = {
    "name": "s", "unit": "deg", "counts_per_unit": 1280.0, "v_max": 50.0, "a_max": 500.0,
    "following_error_limit": 1.0, "drive": {"type": "stepper", "steps_per_unit": 20.0, "microsteps": 64},
}
STATES = list(AxisState)


def machine(channels: list[str] | str) -> Machine:
    data = {
        "machine": {"name": "scope", "cycle_us": 1000, "duration": 2.0},
        "axis": [copy.deepcopy(SERVO), copy.deepcopy(STEPPER)],
        "material": {"speed": 30.0},
        "job": {"steps": [
            {"axis": "x", "command": "power", "on": True},
            {"axis": "s", "command": "power", "on": True},
            {"axis": "x", "command": "move_absolute", "position": 40.0, "wait": "none"},
            {"axis": "s", "command": "move_absolute", "position": 12.5},
        ]},
        "trace": {"channels": channels, "capacity": 5000},
    }
    return Machine(parse_machine(data, "scope.toml"))


def reference(m: Machine, channel: str):
    """The value of `channel` read attribute by attribute, as the scope documents it."""
    if channel.startswith("material."):
        return {"material.position": m.material.position, "material.speed": m.material.velocity}[channel]
    axis, signal = channel.split(".")
    unit = m.units[axis]
    if signal == "state":
        return STATES.index(unit.axis.state)
    if signal in ("actual_velocity", "actual_acceleration", "enabled"):
        return getattr(unit.drive, {"actual_velocity": "velocity", "actual_acceleration": "acceleration"}.get(signal, signal))
    if signal == "velocity_output":
        return unit.velocity_output
    return getattr(unit.axis, signal)


def run_with_reference(m: Machine, cycles: int) -> dict[str, list]:
    """Run, reading every traced channel by hand in the RECORD stage beside the scope."""
    assert m.trace is not None
    names = m.trace.channels
    seen: dict[str, list] = {c: [] for c in names}

    def read_by_hand(cycle: int) -> None:
        for c in names:
            seen[c].append(reference(m, c))

    m.scheduler.add_task("reference", read_by_hand, Stage.RECORD)
    m.scheduler.run(cycles)
    return seen


@pytest.mark.parametrize("channels", [
    # interleaved axes, a plant channel between, subsets in any order (decision 1)
    ["s.enabled", "x.command_position", "x.state", "material.position", "x.following_error",
     "s.command_velocity", "s.state", "x.actual_velocity", "x.enabled", "s.actual_acceleration"],
    "all",
])
def test_channels_keep_the_file_order_and_values(channels: list[str] | str) -> None:
    m = machine(channels)
    seen = run_with_reference(m, 1500)
    data = m.trace.data()
    expected = (
        [f"{a}.{s}" for a in ("x", "s") for s, _, _ in AXIS_SIGNALS] + ["material.position", "material.speed"]
        if channels == "all" else channels
    )
    assert list(data) == ["t", "cycle", *expected]
    for c in expected:
        want = np.array(seen[c], dtype=data[c].dtype)
        assert data[c].tobytes() == want.tobytes(), c
    # a trace worth comparing: both axes moved, powered up, changed state
    assert np.ptp(data["x.command_position"]) > 1.0
    assert data["s.state"].min() == STATES.index(AxisState.DISABLED)
    assert STATES.index(AxisState.DISCRETE_MOTION) in data["s.state"].tolist()


def test_axis_channels_carry_the_axis_unit() -> None:
    m = machine("all")
    units = m.trace.units
    assert units["x.command_position"] == "mm" and units["s.actual_velocity"] == "deg/s"
    assert units["x.command_jerk"] == "mm/s^3" and units["s.state"] == "" and units["x.enabled"] == ""
    assert m.trace.kind("x.state") == "int" and m.trace.kind("s.enabled") == "bool"
    assert m.trace.kind("x.following_error") == "float"


def test_an_unknown_channel_is_named_with_the_channels_available() -> None:
    with pytest.raises(ConfigError) as e:
        machine(["x.command_position", "x.speed"])
    (problem,) = e.value.problems
    assert "unknown channel 'x.speed'" in problem and "x.command_position" in problem
