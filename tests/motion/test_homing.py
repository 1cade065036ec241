"""Homing: HOMING state, direct and switch homing, failures, commands while homing."""

from __future__ import annotations

import pytest

from axisline.motion.axis import Axis, AxisConfig, AxisState, ErrorId
from axisline.motion.homing import DirectHoming, SwitchHoming

T = 0.001


def rig(**kw):
    """Axis with a perfect follower; returns (axis, step, plant) with plant['x'] the plant position."""
    base = dict(name="x", unit="mm", counts_per_unit=1000.0, v_max=100.0, a_max=1000.0, following_error_limit=5.0)
    base.update(kw)
    ax = Axis(AxisConfig(**base), T)
    plant = {"x": 37.0, "cycle": 0}  # the machine stands at 37 mm in plant coordinates

    def step(n: int = 1) -> None:
        for _ in range(n):
            plant["cycle"] += 1
            ax.update_setpoint(plant["cycle"])
            if ax.powered:
                plant["x"] = ax.command_position - ax.position_offset
            ax.position_loop(plant["x"])

    step()
    ax.power(True)
    step()
    return ax, step, plant


def until(step, predicate, limit: int = 50_000) -> None:
    for _ in range(limit):
        if predicate():
            return
        step()
    raise AssertionError("condition not reached")


def test_direct_homing_sets_the_position_and_is_done_in_the_first_cycle() -> None:
    ax, step, plant = rig()
    home = ax.home(DirectHoming(100.0))
    assert ax.state is AxisState.HOMING and home.busy and not ax.homed
    step()
    assert home.done and ax.state is AxisState.STANDSTILL and ax.homed
    assert ax.command_position == 100.0 and ax.actual_position == 100.0
    assert plant["x"] == 37.0  # no motion


@pytest.mark.parametrize("start, direction", [(37.0, -1), (5.0, -1), (-20.0, 1)])
def test_switch_homing_gives_the_switch_edge_the_home_position(start: float, direction: int) -> None:
    ax, step, plant = rig(j_max=50_000.0)
    ax.set_position(start)  # plant 37 is `start` before homing; the switch edge is at plant 20
    switch_edge = 20.0

    def switch() -> bool:  # actuated beyond the edge in the search direction
        return plant["x"] <= switch_edge if direction == -1 else plant["x"] >= switch_edge

    if direction == 1:
        ax.move_absolute(start - 30.0)  # stand before the edge (plant 7)
        until(step, lambda: ax.state is AxisState.STANDSTILL)
    home = ax.home(SwitchHoming(switch, velocity=10.0, direction=direction, position=0.0))
    until(step, lambda: home.done)
    assert ax.state is AxisState.STANDSTILL and ax.homed and ax.command_velocity == 0.0
    # the edge now has coordinate 0: within one cycle of travel at the search speed
    assert switch_edge + ax.position_offset == pytest.approx(0.0, abs=10.0 * T + 1e-9)
    assert ax.command_position == pytest.approx(plant["x"] + ax.position_offset)


def test_switch_homing_leaves_an_actuated_switch_first() -> None:
    ax, step, plant = rig()
    switch = lambda: plant["x"] <= 40.0  # noqa: E731 - already actuated at 37
    home = ax.home(SwitchHoming(switch, velocity=10.0, direction=-1, position=5.0))
    highest = plant["x"]
    while not home.done:
        step()
        highest = max(highest, plant["x"])
    assert highest > 40.0  # it left the switch upward before searching the edge downward
    assert 40.0 + ax.position_offset == pytest.approx(5.0, abs=10.0 * T + 1e-9)


def test_switch_not_found_fails_homing_into_error_stop() -> None:
    ax, step, plant = rig()
    home = ax.home(SwitchHoming(lambda: False, velocity=20.0, direction=1, position=0.0, max_distance=5.0))
    until(step, lambda: ax.state is AxisState.ERROR_STOP)
    assert ax.error_id == ErrorId.HOMING_FAILED and "not found within 5" in ax.error_text
    assert home.aborted and not ax.homed
    until(step, lambda: ax.command_velocity == 0.0)  # braked with the error deceleration


def test_homing_needs_standstill_and_rejects_motion_while_homing() -> None:
    ax, step, plant = rig()
    ax.move_velocity(10.0)
    busy = ax.home(DirectHoming(0.0))
    assert busy.error and busy.error_id == ErrorId.INVALID_STATE
    halt = ax.halt()
    until(step, lambda: halt.done)
    home = ax.home(SwitchHoming(lambda: False, velocity=10.0, direction=1, position=0.0))
    step(10)
    for cmd in (ax.move_absolute(0.0), ax.move_velocity(1.0), ax.halt(), ax.jog(1), ax.set_position(1.0)):
        assert cmd.error and cmd.error_id == ErrorId.AXIS_HOMING
    assert ax.state is AxisState.HOMING and home.busy
    stop = ax.stop()  # the one command that ends homing early
    assert home.aborted and ax.state is AxisState.STOPPING
    until(step, lambda: stop.done)
    ax.stop_release()
    assert ax.state is AxisState.STANDSTILL and not ax.homed
