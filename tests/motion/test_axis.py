"""Axis: PLCopen state rules, commands, buffer modes, modulo, software limits, position loop."""

from __future__ import annotations

import math

import pytest
from pydantic import ValidationError

from axisline.motion.axis import (
    Axis,
    AxisConfig,
    AxisState,
    BufferMode,
    Direction,
    ErrorId,
    MotionCommand,
)
from axisline.motion.homing import DirectHoming
from axisline.motion.profiles import Limits, State, plan

T = 0.001  # 1 ms kernel cycle
EPS = 1e-9


def config(**kw) -> AxisConfig:
    base = dict(name="x", unit="mm", counts_per_unit=1000.0, v_max=100.0, a_max=1000.0, following_error_limit=5.0)
    base.update(kw)
    return AxisConfig(**base)


class Rig:
    """The kernel cycle around one axis with a plant: perfect follower unless `plant` is given.

    plant(rig, velocity_command) -> new actual position in the plant frame.
    """

    def __init__(self, axis: Axis, plant=None) -> None:
        self.axis = axis
        self.cycle = 0
        self.actual = axis.command_position - axis.position_offset
        self.v_out = 0.0
        self.plant = plant
        self.trace: list[tuple[int, float, float, float]] = []  # (cycle, p, v, a)

    def step(self, n: int = 1) -> None:
        ax = self.axis
        for _ in range(n):
            self.cycle += 1
            ax.update_setpoint(self.cycle)
            self.trace.append((self.cycle, ax.command_position, ax.command_velocity, ax.command_acceleration))
            if self.plant is None:
                self.actual = ax.command_position - ax.position_offset
            else:
                self.actual = self.plant(self, self.v_out)
            self.v_out = ax.position_loop(self.actual)

    def until(self, predicate, limit: int = 100_000) -> int:
        for _ in range(limit):
            if predicate():
                return self.cycle
            self.step()
        raise AssertionError(f"condition not reached in {limit} cycles; {self.axis!r}")


def powered(**kw) -> tuple[Axis, Rig]:
    ax = Axis(config(**kw), T)
    rig = Rig(ax)
    rig.step()
    ax.power(True)
    rig.step()
    return ax, rig


def every_motion_command(ax: Axis) -> dict[str, MotionCommand]:
    return {
        "move_absolute": ax.move_absolute(10.0),
        "move_relative": ax.move_relative(10.0),
        "move_additive": ax.move_additive(10.0),
        "move_velocity": ax.move_velocity(10.0),
        "halt": ax.halt(),
        "stop": ax.stop(),
        "jog": ax.jog(1),
        "home": ax.home(DirectHoming(0.0)),
        "start_sync": ax.start_sync(ConstantVelocity(0.0, 1.0)),
    }


class ConstantVelocity:
    """Sync source: p = p0 + v * t."""

    def __init__(self, p0: float, v: float) -> None:
        self.p0, self.v = p0, v

    def sample(self, cycle: int) -> tuple[float, float, float]:
        return (self.p0 + self.v * cycle * T, self.v, 0.0)


# ------------------------------------------------------------------ configuration


def test_config_defaults_follow_the_limits() -> None:
    cfg = config()
    assert cfg.shape == "trapezoid"
    assert cfg.d_max == cfg.a_max and cfg.error_deceleration == cfg.d_max
    assert cfg.jog_velocity == pytest.approx(10.0) and cfg.jog_acceleration == cfg.a_max
    assert config(j_max=1e5).shape == "jerk"


@pytest.mark.parametrize(
    "bad, field",
    [
        (dict(v_max=0.0), "v_max"),
        (dict(counts_per_unit=-1.0), "counts_per_unit"),
        (dict(velocity_feed_forward=1.5), "velocity_feed_forward"),
        (dict(colour="red"), "colour"),
        (dict(kind="modulo"), "modulo_period"),
        (dict(shape="jerk"), "j_max"),
        (dict(sw_limits_enabled=True, sw_limit_low=5.0, sw_limit_high=1.0), "sw_limit_low"),
        (dict(kind="modulo", modulo_period=360.0, sw_limits_enabled=True, sw_limit_high=1.0), "sw_limits_enabled"),
        (dict(jog_velocity=200.0), "jog_velocity"),
    ],
)
def test_config_rejects_bad_values_naming_the_field(bad: dict, field: str) -> None:
    with pytest.raises(ValidationError, match=field):
        config(**bad)


def test_every_config_field_is_described() -> None:
    for name, info in AxisConfig.model_fields.items():
        assert info.description, name


# ------------------------------------------------------------------ power, reset, fault


def test_power_on_goes_to_standstill_and_power_off_to_disabled() -> None:
    ax = Axis(config(), T)
    assert ax.state is AxisState.DISABLED
    ax.power(True)
    assert ax.state is AxisState.STANDSTILL
    ax.move_velocity(50.0)
    assert ax.state is AxisState.CONTINUOUS_MOTION
    ax.power(False)
    assert ax.state is AxisState.DISABLED


def test_power_on_takes_the_set_point_from_the_actual_position() -> None:
    ax = Axis(config(), T)
    ax.update_setpoint(1)
    ax.position_loop(12.5)  # axis moved by hand while disabled
    ax.power(True)
    ax.update_setpoint(2)
    assert ax.command_position == 12.5
    assert ax.position_loop(12.5) == 0.0


def test_motion_commands_are_rejected_while_disabled() -> None:
    ax = Axis(config(), T)
    for name, cmd in every_motion_command(ax).items():
        assert cmd.error and cmd.error_id == ErrorId.AXIS_DISABLED, name
        assert not cmd.busy and "disabled" in cmd.error_text
        assert ax.state is AxisState.DISABLED, name


def test_fault_goes_to_error_stop_and_brakes_with_the_error_deceleration() -> None:
    ax, rig = powered(error_deceleration=4000.0)
    move = ax.move_velocity(100.0)
    rig.until(lambda: move.in_velocity)
    ax.fault(ErrorId.DRIVE_FAULT, "drive overcurrent")
    assert ax.state is AxisState.ERROR_STOP and move.aborted
    assert ax.error_id == ErrorId.DRIVE_FAULT and ax.error_text == "drive overcurrent"
    start = rig.cycle
    rig.until(lambda: ax.command_velocity == 0.0)
    # 100 mm/s at 4000 mm/s^2 takes 25 ms (the config's 1000 mm/s^2 would take 100 ms)
    assert rig.cycle - start == 25
    assert min(a for _, _, _, a in rig.trace[start:]) == pytest.approx(-4000.0)
    rig.step(50)
    assert ax.state is AxisState.ERROR_STOP  # stays until reset


def test_motion_commands_are_rejected_in_error_stop_and_leave_it_unchanged() -> None:
    ax, rig = powered()
    ax.fault(ErrorId.DRIVE_FAULT, "encoder wire break")
    rig.step(5)
    for name, cmd in every_motion_command(ax).items():
        assert cmd.error and cmd.error_id == ErrorId.AXIS_ERROR_STOP, name
        assert "encoder wire break" in cmd.error_text
        assert ax.state is AxisState.ERROR_STOP, name
    assert ax.error_id == ErrorId.DRIVE_FAULT and ax.error_text == "encoder wire break"


def test_a_second_fault_keeps_the_first_reason() -> None:
    ax, rig = powered()
    ax.fault(ErrorId.DRIVE_FAULT, "first")
    ax.fault(ErrorId.FOLLOWING_ERROR, "second")
    assert ax.error_id == ErrorId.DRIVE_FAULT and ax.error_text == "first"


def test_reset_in_error_stop_goes_to_standstill_when_powered_after_the_ramp() -> None:
    ax, rig = powered()
    move = ax.move_velocity(100.0)
    rig.step(200)
    ax.fault()
    reset = ax.reset()
    assert reset.busy and ax.state is AxisState.ERROR_STOP  # still braking
    rig.until(lambda: reset.done)
    assert ax.state is AxisState.STANDSTILL and ax.command_velocity == 0.0
    assert ax.error_id == 0 and ax.error_text == ""
    assert move.aborted
    assert not ax.move_relative(1.0).error  # commands are accepted again


def test_power_off_in_error_stop_keeps_error_stop_and_reset_goes_to_disabled() -> None:
    ax, rig = powered()
    ax.fault()
    ax.power(False)
    rig.step(3)
    assert ax.state is AxisState.ERROR_STOP  # PLCopen: only MC_Reset leaves ErrorStop
    ax.reset()
    assert ax.state is AxisState.DISABLED
    ax.power(True)
    assert ax.state is AxisState.STANDSTILL


def test_power_on_in_error_stop_needs_a_reset() -> None:
    ax, rig = powered()
    ax.fault()
    ax.power(False)
    ax.power(True)
    rig.step(3)
    assert ax.state is AxisState.ERROR_STOP
    ax.reset()
    assert ax.state is AxisState.STANDSTILL


def test_reset_outside_error_stop_does_nothing() -> None:
    ax, rig = powered()
    move = ax.move_absolute(5.0)
    cmd = ax.reset()
    assert cmd.done and ax.state is AxisState.DISCRETE_MOTION and move.busy


# ------------------------------------------------------------------ stop


def test_stopping_is_held_while_the_stop_is_active_and_left_after_release() -> None:
    ax, rig = powered()
    move = ax.move_velocity(100.0)
    rig.step(150)
    stop = ax.stop()
    assert ax.state is AxisState.STOPPING and move.aborted and stop.busy
    rig.until(lambda: stop.done)
    assert ax.command_velocity == 0.0
    rig.step(20)
    assert ax.state is AxisState.STOPPING  # ramp ended, stop still held
    ax.stop_release()
    assert ax.state is AxisState.STANDSTILL


def test_stop_released_early_leaves_stopping_when_the_ramp_ends() -> None:
    ax, rig = powered()
    ax.move_velocity(100.0)
    rig.step(150)
    stop = ax.stop()
    ax.stop_release()
    rig.step()
    assert ax.state is AxisState.STOPPING  # the ramp still runs
    rig.until(lambda: stop.done)
    assert ax.state is AxisState.STANDSTILL and ax.command_velocity == 0.0


def test_every_motion_command_is_rejected_while_stopping() -> None:
    ax, rig = powered()
    ax.move_velocity(100.0)
    rig.step(150)
    stop = ax.stop()
    rig.step(3)
    v = ax.command_velocity
    for name, cmd in every_motion_command(ax).items():
        assert cmd.error and cmd.error_id == ErrorId.AXIS_STOPPING, name
        assert ax.state is AxisState.STOPPING, name
    assert stop.busy and not stop.aborted
    rig.step()
    assert ax.command_velocity < v  # still braking along the stop ramp


# ------------------------------------------------------------------ moves, halt, timing


def test_a_move_is_done_in_the_cycle_its_profile_ends_with_the_set_point_on_target() -> None:
    ax, rig = powered()
    c0 = rig.cycle
    move = ax.move_absolute(12.345, velocity=40.0)
    assert ax.state is AxisState.DISCRETE_MOTION and move.busy and move.active
    duration = plan("trapezoid", State(0.0), State(12.345), Limits(v=40.0, a=1000.0, d=1000.0)).duration
    last = c0 + math.ceil(duration / T - 1e-9)
    rig.until(lambda: rig.cycle == last - 1)
    assert not move.done and ax.command_position != 12.345
    rig.step()
    assert move.done and not move.busy and not move.active
    assert ax.command_position == 12.345 and ax.command_velocity == 0.0
    assert ax.state is AxisState.STANDSTILL


def test_a_command_between_cycles_starts_from_the_last_set_point_at_that_cycle() -> None:
    ax, rig = powered(j_max=50_000.0)
    ax.move_velocity(60.0)
    rig.step(37)
    k = rig.cycle
    start = State(ax.command_position, ax.command_velocity, ax.command_acceleration)
    ax.move_absolute(30.0)
    expected = plan("jerk", start, State(30.0), Limits(v=100.0, a=1000.0, d=1000.0, j=50_000.0))
    for _ in range(100):
        rig.step()
        p, v, a, j = expected.sample((rig.cycle - k) * T)
        assert (ax.command_position, ax.command_velocity, ax.command_acceleration) == (p, v, a)


def test_move_relative_and_additive_targets() -> None:
    ax, rig = powered()
    first = ax.move_absolute(20.0)
    rig.step(40)
    assert first.busy
    add = ax.move_additive(5.0)  # the previous target + 5, not the set point + 5
    assert first.aborted and add.target == 25.0
    rig.until(lambda: add.done)
    assert ax.command_position == 25.0
    rel = ax.move_relative(-3.0)
    rig.until(lambda: rel.done)
    assert ax.command_position == 22.0
    ax.move_velocity(50.0)
    rig.step(30)
    halt = ax.halt()
    rig.until(lambda: halt.done)
    here = ax.command_position
    add2 = ax.move_additive(1.0)  # no position target after a halt: relative to the set point
    assert add2.target == pytest.approx(here + 1.0)


def test_halt_brakes_in_discrete_motion_then_standstill() -> None:
    ax, rig = powered()
    vel = ax.move_velocity(80.0)
    rig.step(100)
    halt = ax.halt(deceleration=400.0)
    assert vel.aborted and ax.state is AxisState.DISCRETE_MOTION
    start = rig.cycle
    rig.until(lambda: halt.done)
    assert rig.cycle - start == 200  # 80 mm/s at 400 mm/s^2
    assert ax.state is AxisState.STANDSTILL and ax.command_velocity == 0.0


def test_halt_is_interrupted_by_a_new_move() -> None:
    ax, rig = powered()
    ax.move_velocity(80.0)
    rig.step(100)
    halt = ax.halt(deceleration=200.0)
    rig.step(50)
    move = ax.move_absolute(2.0)
    assert halt.aborted and not halt.done and move.active
    rig.until(lambda: move.done)
    assert ax.command_position == 2.0 and ax.state is AxisState.STANDSTILL


def test_buffered_move_starts_exactly_in_the_cycle_the_previous_is_done() -> None:
    ax, rig = powered()
    first = ax.move_absolute(10.0)
    second = ax.move_absolute(4.0, buffer_mode=BufferMode.BUFFERED)
    third = ax.move_relative(1.0, buffer_mode=BufferMode.BUFFERED)
    assert second.busy and not second.active and first.active
    rig.until(lambda: first.done)
    k = rig.cycle
    assert second.active and not first.aborted and ax.state is AxisState.DISCRETE_MOTION
    assert ax.command_position == 10.0
    rig.step()
    assert ax.command_position < 10.0  # moving toward 4 from the next cycle on
    rig.until(lambda: second.done)
    assert third.active and third.target == 5.0  # relative to where the second ended
    rig.until(lambda: third.done)
    assert ax.command_position == 5.0
    assert all(p <= 10.0 + EPS for c, p, _, _ in rig.trace if c >= k)


def test_buffered_behind_a_velocity_command_starts_when_in_velocity() -> None:
    ax, rig = powered()
    vel = ax.move_velocity(50.0)
    move = ax.move_relative(10.0, buffer_mode=BufferMode.BUFFERED)
    rig.until(lambda: move.active)
    assert vel.aborted and ax.command_velocity == pytest.approx(50.0)
    rig.until(lambda: move.done)
    assert ax.state is AxisState.STANDSTILL


def test_an_aborting_command_clears_the_buffer() -> None:
    ax, rig = powered()
    ax.move_absolute(10.0)
    queued = ax.move_absolute(0.0, buffer_mode=BufferMode.BUFFERED)
    rig.step(10)
    ax.move_absolute(3.0)
    assert queued.aborted and not queued.busy


@pytest.mark.parametrize("shape, j_max", [("trapezoid", None), ("jerk", 40_000.0), ("sin2", 40_000.0)])
def test_aborting_replans_are_continuous_in_position_and_velocity(shape: str, j_max: float | None) -> None:
    ax, rig = powered(shape=shape, j_max=j_max, d_max=800.0)
    ax.move_absolute(50.0)
    rig.step(120)
    ax.move_absolute(20.0)  # reverse while running at speed
    rig.step(40)
    ax.move_velocity(-60.0)
    rig.step(45)
    ax.move_absolute(80.0, velocity=30.0)  # slower than now: brakes into the new limit
    rig.step(60)
    ax.move_additive(-10.0, velocity=100.0)
    last = ax.move_relative(0.0, buffer_mode=BufferMode.BUFFERED)
    rig.until(lambda: last.done)
    assert ax.command_position == pytest.approx(70.0, abs=1e-9)
    # profiles.State carries no jerk: a sin² replan from inside a ramp starts a new bell at
    # zero jerk, whose velocity gain k*a²/(2j) can pass v_max (reported to the lead)
    v_bound = 100.0 if shape != "sin2" else 100.0 + math.pi / 2 * 1000.0**2 / (2 * 40_000.0)
    prev = (0.0, 0.0)
    for _, p, v, _ in rig.trace:
        assert abs(p - prev[0]) <= v_bound * T + 1e-9
        assert abs(v - prev[1]) <= 1000.0 * T + 1e-9
        prev = (p, v)


def test_values_above_the_config_limits_are_clamped_and_invalid_ones_rejected() -> None:
    ax, rig = powered()
    fast = ax.move_absolute(50.0, velocity=500.0)
    assert fast.clamped and fast.busy
    rig.step(300)
    assert max(abs(v) for _, _, v, _ in rig.trace) == pytest.approx(100.0)
    bad = ax.move_absolute(0.0, acceleration=-1.0)
    assert bad.error and bad.error_id == ErrorId.INVALID_PARAMETER and "acceleration" in bad.error_text
    assert fast.busy  # a rejected command does not abort the running one
    nan = ax.move_relative(float("nan"))
    assert nan.error and "distance" in nan.error_text


def test_move_velocity_reports_in_velocity_and_jog_zero_ends_the_jog() -> None:
    ax, rig = powered(jog_velocity=20.0, jog_acceleration=200.0)
    vel = ax.move_velocity(-40.0)
    assert ax.state is AxisState.CONTINUOUS_MOTION
    rig.until(lambda: vel.in_velocity)
    assert ax.command_velocity == -40.0 and vel.busy and not vel.done
    jog = ax.jog(1)
    assert vel.aborted
    rig.until(lambda: jog.in_velocity)
    assert ax.command_velocity == 20.0
    end = ax.jog(0)
    assert end is jog and ax.state is AxisState.DISCRETE_MOTION
    start = rig.cycle
    rig.until(lambda: jog.done)
    assert rig.cycle - start == 100  # 20 mm/s at the jog deceleration 200 mm/s^2
    assert ax.state is AxisState.STANDSTILL
    assert ax.jog(0).done  # nothing to end


# ------------------------------------------------------------------ modulo


def modulo_axis(at: float) -> tuple[Axis, Rig]:
    ax, rig = powered(kind="modulo", modulo_period=360.0, unit="deg", v_max=720.0, a_max=7200.0, following_error_limit=2.0)
    ax.set_position(at)
    rig.step()
    return ax, rig


@pytest.mark.parametrize(
    "start, target, direction, travel",
    [
        (350.0, 10.0, Direction.SHORTEST, 20.0),  # across 0 forward
        (10.0, 350.0, Direction.SHORTEST, -20.0),  # across 0 backward
        (10.0, 350.0, Direction.POSITIVE, 340.0),
        (350.0, 10.0, Direction.NEGATIVE, -340.0),
        (10.0, 20.0, Direction.NEGATIVE, -350.0),
        (0.0, 180.0, Direction.SHORTEST, 180.0),  # half a turn either way: positive
        (180.0, 0.0, Direction.SHORTEST, 180.0),
        (90.0, 90.0, Direction.POSITIVE, 0.0),
    ],
)
def test_modulo_moves_wrap_across_zero(start: float, target: float, direction: Direction, travel: float) -> None:
    ax, rig = modulo_axis(start)
    p0 = ax.command_position
    first = len(rig.trace)
    move = ax.move_absolute(target, direction=direction)
    rig.until(lambda: move.done)
    assert ax.command_position - p0 == pytest.approx(travel, abs=1e-9)
    assert ax.position == pytest.approx(target, abs=1e-9)
    positions = [p0] + [p for _, p, _, _ in rig.trace[first:]]
    for a, b in zip(positions, positions[1:]):  # continuous, one direction only
        assert abs(b - a) <= 720.0 * T + 1e-9
        assert (b - a) * travel >= -1e-12
    assert all(0.0 <= ax.wrap(p) < 360.0 for p in positions)


def test_modulo_current_direction_follows_the_motion() -> None:
    ax, rig = modulo_axis(100.0)
    ax.move_velocity(-90.0)
    rig.step(200)
    p0 = ax.command_position
    move = ax.move_absolute(80.0, direction=Direction.CURRENT)
    rig.until(lambda: move.done)
    # keeps turning negative (from 100 - ~13 deg down to 80) instead of reversing
    assert ax.command_position < p0 and ax.position == pytest.approx(80.0, abs=1e-9)


def test_modulo_target_outside_the_period_is_rejected() -> None:
    ax, rig = modulo_axis(0.0)
    cmd = ax.move_absolute(360.0)
    assert cmd.error and cmd.error_id == ErrorId.INVALID_PARAMETER and "360" in cmd.error_text


def test_modulo_velocity_runs_endlessly_with_wrapped_position() -> None:
    ax, rig = modulo_axis(0.0)
    ax.move_velocity(720.0)
    rig.step(1500)
    assert ax.command_position > 720.0
    assert 0.0 <= ax.position < 360.0
    assert ax.position == pytest.approx(ax.command_position % 360.0)


# ------------------------------------------------------------------ software limits


def limited(**kw) -> tuple[Axis, Rig]:
    return powered(sw_limits_enabled=True, sw_limit_low=-10.0, sw_limit_high=100.0, **kw)


def test_target_outside_the_software_limits_is_rejected_naming_limit_and_value() -> None:
    ax, rig = limited()
    high = ax.move_absolute(100.5)
    assert high.error and high.error_id == ErrorId.SW_LIMIT_HIGH
    assert "100.5" in high.error_text and "limit high 100" in high.error_text
    low = ax.move_relative(-12.0)
    assert low.error and low.error_id == ErrorId.SW_LIMIT_LOW and "-12" in low.error_text and "-10" in low.error_text
    assert ax.state is AxisState.STANDSTILL
    ok = ax.move_absolute(100.0)
    assert ok.busy


@pytest.mark.parametrize("shape, j_max", [("trapezoid", None), ("jerk", 20_000.0), ("sin2", 20_000.0)])
def test_jog_stops_at_the_software_limit_not_beyond(shape: str, j_max: float | None) -> None:
    ax, rig = limited(shape=shape, j_max=j_max, jog_velocity=80.0, jog_acceleration=400.0)
    jog = ax.jog(1)
    rig.until(lambda: ax.state is AxisState.STANDSTILL)
    assert jog.error and jog.error_id == ErrorId.SW_LIMIT_HIGH and "100" in jog.error_text
    assert ax.warning == jog.error_text
    assert max(p for _, p, _, _ in rig.trace) <= 100.0 + 1e-9
    assert ax.command_position == pytest.approx(100.0, abs=1e-9)
    again = ax.jog(1)  # at the limit: no further
    assert again.error and again.error_id == ErrorId.SW_LIMIT_HIGH and ax.state is AxisState.STANDSTILL
    back = ax.move_velocity(-100.0, acceleration=2000.0)  # clamped to a_max, moves away
    assert back.busy and back.clamped
    rig.until(lambda: ax.state is AxisState.STANDSTILL)
    assert back.error_id == ErrorId.SW_LIMIT_LOW
    assert min(p for _, p, _, _ in rig.trace) >= -10.0 - 1e-9
    assert ax.command_position == pytest.approx(-10.0, abs=1e-9)


def test_velocity_move_far_from_the_limit_is_not_braked() -> None:
    ax, rig = limited()
    vel = ax.move_velocity(10.0)
    rig.step(2000)  # 20 mm of 100
    assert vel.busy and vel.in_velocity and ax.command_velocity == 10.0


# ------------------------------------------------------------------ position loop


def test_position_loop_is_feed_forward_plus_kv_times_following_error() -> None:
    ax, rig = powered(kv=20.0, velocity_feed_forward=0.9)
    ax.move_velocity(50.0)
    rig.step(10)
    ax.update_setpoint(rig.cycle + 1)
    out = ax.position_loop(ax.command_position - 0.1)
    assert ax.following_error == pytest.approx(0.1)
    assert out == pytest.approx(0.9 * ax.command_velocity + 20.0 * 0.1)


def lagging_drive(gain: float):
    """A drive that delivers only `gain` of the commanded velocity."""

    def plant(rig: Rig, v_out: float) -> float:
        return rig.actual + gain * v_out * T

    return plant


def test_a_drive_that_keeps_up_does_not_trip() -> None:
    ax, rig = powered()
    rig.plant = lagging_drive(1.0)
    move = ax.move_absolute(50.0)
    rig.until(lambda: move.done)
    assert ax.state is AxisState.STANDSTILL


def test_following_error_trips_error_stop_with_value_and_limit_in_the_reason() -> None:
    ax, rig = powered()
    rig.plant = lagging_drive(0.2)
    move = ax.move_velocity(100.0)
    rig.until(lambda: ax.state is AxisState.ERROR_STOP)
    fe = ax.following_error
    assert 5.0 < fe < 5.5
    assert ax.error_id == ErrorId.FOLLOWING_ERROR
    assert ax.error_text == f"following error {fe:.4g} mm exceeds limit 5 mm"
    assert move.aborted


def test_reset_after_a_following_error_takes_the_actual_position() -> None:
    ax, rig = powered()
    rig.plant = lambda rig, v: 0.0  # drive stuck
    ax.move_velocity(100.0)
    rig.until(lambda: ax.state is AxisState.ERROR_STOP)
    reset = ax.reset()
    rig.until(lambda: reset.done)
    assert ax.state is AxisState.STANDSTILL and ax.command_position == 0.0
    rig.step(5)
    assert ax.state is AxisState.STANDSTILL and rig.v_out == 0.0


def test_set_position_shifts_set_point_and_actual_without_motion() -> None:
    ax, rig = powered()
    rig.plant = lagging_drive(1.0)
    ax.move_velocity(20.0)
    rig.step(200)
    fe, v, out = ax.following_error, ax.command_velocity, rig.v_out
    p = ax.command_position
    cmd = ax.set_position(500.0)
    assert cmd.done and ax.command_position == 500.0
    assert ax.actual_position == pytest.approx(500.0 - fe)
    rig.step()
    assert ax.command_position == pytest.approx(500.0 + v * T)  # the motion goes on from there
    assert ax.following_error == pytest.approx(fe, abs=1e-6) and rig.v_out == pytest.approx(out, abs=1e-4)
    assert ax.position_offset == pytest.approx(500.0 - p)
    ax.halt()
    rig.until(lambda: ax.state is AxisState.STANDSTILL)
    before, actual = ax.command_position, ax.actual_position
    ax.set_position(-1.0, relative=True)
    assert ax.command_position == before - 1.0 and ax.actual_position == actual - 1.0
    rig.step(5)
    assert ax.command_position == before - 1.0 and ax.state is AxisState.STANDSTILL


def test_set_position_at_rest_moves_nothing() -> None:
    ax, rig = powered()
    ax.set_position(42.0)
    rig.step(10)
    assert ax.command_position == 42.0 and ax.actual_position == 42.0
    assert ax.command_velocity == 0.0 and rig.v_out == 0.0 and ax.state is AxisState.STANDSTILL
    move = ax.move_absolute(40.0)
    rig.until(lambda: move.done)
    assert rig.actual == pytest.approx(-2.0)  # the plant moved by -2 in its own frame


# ------------------------------------------------------------------ synchronized motion


def test_sync_source_is_followed_and_end_sync_halts() -> None:
    ax, rig = powered()
    source = ConstantVelocity(0.0, 30.0)
    sync = ax.start_sync(source)
    assert ax.state is AxisState.SYNCHRONIZED_MOTION and sync.active
    for _ in range(50):
        rig.step()
        assert ax.command_position == source.sample(rig.cycle)[0] and ax.command_velocity == 30.0
    halt = ax.end_sync(deceleration=300.0)
    assert sync.done and not sync.busy and ax.state is AxisState.DISCRETE_MOTION
    start = rig.cycle
    rig.until(lambda: halt.done)
    assert rig.cycle - start == 100  # 30 mm/s at 300 mm/s^2, no jump
    assert ax.state is AxisState.STANDSTILL
    assert ax.end_sync().error_id == ErrorId.INVALID_STATE


def test_a_move_aborts_sync() -> None:
    ax, rig = powered()
    sync = ax.start_sync(ConstantVelocity(0.0, 30.0))
    rig.step(20)
    move = ax.move_absolute(0.0)
    assert sync.aborted and ax.state is AxisState.DISCRETE_MOTION
    rig.until(lambda: move.done)
    assert ax.command_position == 0.0


def test_a_command_before_the_first_cycle_starts_in_the_first_cycle() -> None:
    ax = Axis(config(), T)
    ax.power(True)
    move = ax.move_absolute(1.0)
    ax.update_setpoint(500)
    expected = plan("trapezoid", State(0.0), State(1.0), Limits(v=100.0, a=1000.0, d=1000.0))
    assert ax.command_position == expected.sample(T)[0] > 0.0 and move.active
