"""The Machine: machine-file validation, determinism, command queue, stages, stop."""

import copy
import threading
from pathlib import Path

import numpy as np
import pytest

from axisline.config import load_machine_file, parse_machine
from axisline.configerrors import ConfigError
from axisline.machine import Machine
from axisline.motion.axis import AxisState

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"

AXIS = {
    "name": "x",
    "unit": "mm",
    "counts_per_unit": 2000.0,
    "v_max": 200.0,
    "a_max": 2000.0,
    "j_max": 50000.0,
    "kv": 40.0,
    "following_error_limit": 2.0,
    "drive": {"type": "servo", "time_constant": 0.002},
    "encoder": {"lines_per_unit": 500.0, "multiplier": 4},
}


def machine_data(**over):
    data = {"machine": {"name": "t", "cycle_us": 1000}, "axis": [copy.deepcopy(AXIS)], "trace": {"capacity": 20000}}
    data.update(over)
    return data


def problems(data) -> list[str]:
    with pytest.raises(ConfigError) as e:
        parse_machine(data, "test.toml")
    return e.value.problems


# -- the machine file: every bad key named with its value and range -------------------------


def test_unknown_key_is_named_with_the_keys_allowed_there():
    d = machine_data()
    d["axis"][0]["vmax"] = 3.0
    (p,) = problems(d)
    assert p.startswith("axis[0].vmax: unknown key")
    assert "v_max" in p


def test_out_of_range_value_names_key_value_and_range():
    d = machine_data()
    d["machine"]["cycle_us"] = 20000
    (p,) = problems(d)
    assert "machine.cycle_us = 20000" in p and "250" in p and "10000" in p


def test_nested_drive_value_is_named():
    d = machine_data()
    d["axis"][0]["drive"]["time_constant"] = -0.5
    (p,) = problems(d)
    assert p.startswith("axis[0].drive.time_constant = -0.5")
    assert "allowed" in p


def test_wrong_type_is_named():
    d = machine_data()
    d["axis"][0]["v_max"] = "fast"
    (p,) = problems(d)
    assert "axis[0].v_max = 'fast'" in p


def test_cross_checks_name_the_problem():
    d = machine_data(job={"steps": [{"axis": "y", "command": "power", "on": True}]})
    (p,) = problems(d)
    assert "job.steps[0].axis = 'y'" in p and "x" in p
    d = machine_data()
    d["axis"].append(copy.deepcopy(AXIS))
    assert "used twice" in problems(d)[0]
    d = machine_data(job={"steps": [{"axis": "x", "command": "halt", "position": 3.0}]})
    assert "does not take position" in problems(d)[0]


def test_toml_syntax_error_is_a_config_error(tmp_path):
    f = tmp_path / "bad.toml"
    f.write_text("[machine\nname = 1\n")
    with pytest.raises(ConfigError, match="TOML syntax"):
        load_machine_file(f)


def test_example_machine_files_are_valid():
    for f in EXAMPLES.glob("*.toml"):
        load_machine_file(f)


# -- running ---------------------------------------------------------------------------------


def run_example(seed=None):
    m = Machine.from_file(EXAMPLES / "positioning.toml", seed=seed)
    result = m.run()
    return m, result


def test_positioning_example_completes_at_its_targets():
    m, result = run_example()
    assert result.completed, result.faults
    x, r = m.axis("x"), m.axis("r")
    assert x.state is AxisState.STANDSTILL and r.state is AxisState.STANDSTILL
    assert x.command_position == pytest.approx(0.0, abs=1e-9)
    assert abs(x.position) <= 2 / 2000  # within the encoder's counts
    assert r.position == pytest.approx(30.0, abs=1 / 355.5)  # one microstep
    assert r.command_position == pytest.approx(390.0)  # 300 -> 30 the shortest way: +90 across 0


def test_same_file_and_seed_give_a_bit_identical_trace():
    a, _ = run_example(seed=3)
    b, _ = run_example(seed=3)
    da, db = a.trace.data(), b.trace.data()
    assert da.keys() == db.keys()
    for k in da:
        assert da[k].tobytes() == db[k].tobytes(), k


def test_simulated_time_is_cycle_count_times_period():
    m = Machine(parse_machine(machine_data(machine={"cycle_us": 250})))
    m.scheduler.run(4000)
    assert m.clock.cycle == 4000 and m.clock.now == 1.0
    t = m.trace.data()["t"]
    assert t[-1] == 3999 * 250 / 1e6


def test_external_commands_take_effect_at_a_cycle_boundary():
    m = Machine(parse_machine(machine_data()))
    fut = m.submit("x", "power", on=True)
    assert m.axis("x").state is AxisState.DISABLED  # nothing happens between cycles
    m.scheduler.run_cycle()
    assert fut.done() and m.axis("x").state is AxisState.STANDSTILL

    # from another thread, while cycles run: applied before the stages of one cycle
    seen = []
    m.scheduler.add_task("probe", lambda c: seen.append((c, m.axis("x").state)), m.scheduler.tasks[0].stage)
    done = threading.Event()

    def client():
        m.submit("x", "move_absolute", position=10.0).result(timeout=5)
        done.set()

    th = threading.Thread(target=client)
    th.start()
    for _ in range(2000):
        m.scheduler.run_cycle()
        if done.is_set():
            break
    th.join()
    moving = [c for c, s in seen if s is AxisState.DISCRETE_MOTION]
    assert moving, "the move never started"
    # the state flips exactly at one boundary: all earlier probes saw STANDSTILL
    first = moving[0]
    assert all(s is AxisState.STANDSTILL for c, s in seen if c < first)


def test_following_error_fault_ends_the_run_with_the_reason():
    d = machine_data(job={"steps": [{"axis": "x", "command": "power", "on": True}, {"axis": "x", "command": "move_absolute", "position": 100.0}]})
    d["axis"][0]["kv"] = 1.0
    d["axis"][0]["velocity_feed_forward"] = 0.0  # a badly tuned loop lags far behind
    d["axis"][0]["following_error_limit"] = 0.5
    m = Machine(parse_machine(d))
    result = m.run(5.0)
    assert not result.completed
    assert any("following error" in f and "0.5" in f for f in result.faults)
    assert m.axis("x").state is AxisState.ERROR_STOP


def test_stop_all_brings_moving_axes_to_rest_with_their_ramps():
    d = machine_data(job={"steps": [{"axis": "x", "command": "power", "on": True}, {"axis": "x", "command": "move_velocity", "velocity": 150.0}]})
    m = Machine(parse_machine(d))
    m.run(0.5, until_job_done=False)
    assert m.axis("x").command_velocity == pytest.approx(150.0)
    assert m.stop_all()
    ax = m.axis("x")
    assert ax.state is AxisState.STANDSTILL and ax.command_velocity == 0.0
    v = m.trace.data()["x.command_velocity"]
    assert np.max(np.abs(np.diff(v))) <= 2000.0 * m.period * (1 + 1e-9)  # ramped, never a step


def test_stepper_axis_follows_its_set_point_in_microsteps():
    d = machine_data()
    d["axis"][0] = {
        "name": "s", "unit": "mm", "counts_per_unit": 1280.0, "v_max": 50.0, "a_max": 500.0,
        "following_error_limit": 1.0, "drive": {"type": "stepper", "steps_per_unit": 20.0, "microsteps": 64},
    }
    d["job"] = {"steps": [{"axis": "s", "command": "power", "on": True}, {"axis": "s", "command": "move_absolute", "position": 12.5}]}
    m = Machine(parse_machine(d))
    assert m.run(5.0).completed
    assert m.units["s"].drive.position_microsteps == 12.5 * 1280


PLANT = """
[machine]
duration = 20.0
seed = 5
[[axis]]
name = "x"
unit = "mm"
counts_per_unit = 2000.0
v_max = 200.0
a_max = 2000.0
j_max = 50000.0
kv = 30.0
following_error_limit = 2.0
[axis.drive]
type = "servo"
command = "analog"
velocity_per_volt = 30.0
offset_volts = 0.01
[axis.encoder]
lines_per_unit = 500.0
[[axis.switches]]
name = "ref"
kind = "reference"
position = -40.0
width = 10.0
[material]
speed = 500.0
[[marks]]
name = "marks"
pitch = 200.0
width = 5.0
jitter = 0.5
sensor_position = 100.0
[io]
inputs = ["x.ref"]
[[job.steps]]
axis = "x"
command = "power"
on = true
[[job.steps]]
axis = "x"
command = "home"
method = "switch"
switch = "ref"
velocity = 20.0
direction = "negative"
position = 0.0
[[job.steps]]
axis = "x"
command = "move_absolute"
position = 100.0
"""


def plant_machine(tmp_path, text=PLANT, seed=None):
    f = tmp_path / "plant.toml"
    f.write_text(text)
    return Machine.from_file(f, seed=seed)


def test_switch_homing_in_a_machine_gives_the_switch_edge_the_home_position(tmp_path):
    m = plant_machine(tmp_path)
    assert m.run().completed
    ax = m.axis("x")
    assert ax.homed
    # searching negative from 0 the cam (-40 .. -30 in the plant) is met at -30: that is 0 now
    assert ax.position_offset == pytest.approx(30.0, abs=0.05)
    assert ax.actual_position == pytest.approx(100.0, abs=0.05)
    assert m.units["x"].drive.position == pytest.approx(70.0, abs=0.05)
    # the switch reached the I/O image while the axis passed it
    assert m.trace.data()["io.x.ref"].any()


def test_analog_offset_leaves_the_p_loop_steady_state_error(tmp_path):
    m = plant_machine(tmp_path)
    m.run()
    m.scheduler.run(2000)  # settle fully
    # offset 0.01 V * 30 mm/s/V must be held by kv * error: error = 0.3 / 30 mm
    assert m.axis("x").following_error == pytest.approx(-0.01, abs=1e-3)


def test_print_marks_on_the_material_are_captured_with_their_times(tmp_path):
    m = plant_machine(tmp_path)
    m.run(1.0)
    edges = [e for e in m.sensors["marks"].edges if e.rising]
    # 500 mm/s past a sensor at 100 mm, marks every 200 mm (jitter sigma 0.5 mm): 100, 300, 500
    assert [round(e.time, 2) for e in edges] == [0.2, 0.6, 1.0][: len(edges)] and len(edges) >= 2
    for e in edges:
        assert e.position == pytest.approx(500.0 * e.time, rel=1e-12)  # material travel at the edge
        assert abs(e.position - 100.0 - 200.0 * e.mark) <= 1.5 + 1e-9  # mark k: jitter sigma 0.5, clipped at 3 sigma
    d = m.trace.data()
    # the scope records after the plant step: the last sample is the travel at the end of the run
    assert d["material.position"][-1] == pytest.approx(500.0 * m.clock.cycle * m.period, rel=1e-9)


def test_mark_jitter_follows_the_seed(tmp_path):
    times = []
    for seed in (5, 5, 6):
        m = plant_machine(tmp_path, seed=seed)
        m.run(2.0)
        times.append([e.time for e in m.sensors["marks"].edges])
    assert times[0] == times[1] and times[0] != times[2]


def test_homing_on_a_switch_the_axis_does_not_have_is_named(tmp_path):
    with pytest.raises(ConfigError, match="switch = 'home'"):
        plant_machine(tmp_path, PLANT.replace('switch = "ref"', 'switch = "home"'))


def test_logic_task_runs_at_its_sub_rate():
    steps = [{"axis": "x", "command": "power", "on": True}] + [
        {"axis": "x", "command": "move_relative", "distance": 1.0, "wait": "none"} for _ in range(3)
    ]
    m = Machine(parse_machine(machine_data(machine={"logic_every": 4}, job={"steps": steps})))
    m.scheduler.run(20)
    # one step per logic cycle, and logic cycles are 0, 4, 8, 12 (T = 1 ms)
    assert [round(e.t * 1000) for e in m.job.events] == [0, 4, 8, 12]


def test_an_axis_starting_away_from_zero_is_enabled_where_it_stands(tmp_path):
    """A drive whose initial position is 45 mm ([axis.drive] position): the axis' set point
    starts there, so the power-on of the first cycle does not pull it to 0 (no following error)."""
    text = (EXAMPLES / "positioning.toml").read_text().replace('type = "servo"', 'type = "servo"\nposition = 45.0', 1)
    (tmp_path / "m.toml").write_text(text)
    m = Machine.from_file(tmp_path / "m.toml")
    axis = m.axis(m.config.axis[0].name)
    assert axis.command_position == pytest.approx(45.0)
    for _ in range(20):
        m.scheduler.run_cycle()
    assert axis.state is not AxisState.ERROR_STOP
    assert abs(axis.following_error) < 0.1  # (the job starts moving at once: a lag, not 45 mm)


def test_set_directions_turns_a_mirrored_encoder_round(tmp_path):
    """Machine.set_directions: the x slide's encoder mounted mirrored (direction = -1) runs away
    with the kernel loop; counted the other way by the controller it completes the job exactly
    as the correctly wired machine does. A stepper has nothing to turn."""
    text = (EXAMPLES / "positioning.toml").read_text()
    mirrored = text.replace("[axis.encoder]", "[axis.encoder]\ndirection = -1", 1)
    (tmp_path / "m.toml").write_text(mirrored)
    wrong = Machine.from_file(tmp_path / "m.toml")
    assert not wrong.run().completed  # following error: the loop pushes the wrong way
    fixed = Machine.from_file(tmp_path / "m.toml")
    fixed.set_directions("x", feedback=-1)
    result = fixed.run()
    assert result.completed, result.faults
    ref, _ = run_example()
    assert fixed.axis("x").position == pytest.approx(ref.axis("x").position, abs=2 / 2000)
    with pytest.raises(ValueError, match="stepper"):
        fixed.set_directions("r", output=-1)
    with pytest.raises(ValueError, match="-1"):
        fixed.set_directions("x", feedback=0)


def test_every_trace_channel_of_the_line_and_masters_has_a_unit():
    """Issue 16 (units on every trace channel): the material line takes [material] unit (or the
    first axis' unit), a wheel master the line's, an axis master its axis', a virtual one its own."""
    m = Machine.from_file(EXAMPLES / "flying_shear.toml")
    units = m.trace.units() if callable(m.trace.units) else m.trace.units
    assert units["material.position"] == "mm" and units["material.speed"] == "mm/s"
    m = Machine.from_file(EXAMPLES / "cam_packaging.toml")  # knife in deg, the web in mm
    units = m.trace.units() if callable(m.trace.units) else m.trace.units
    assert units["material.speed"] == "mm/s" and units["wheel.velocity"] == "mm/s"
    assert units["knife.command_velocity"] == "deg/s"
    m = Machine.from_file(EXAMPLES / "cam_sync.toml")
    units = m.trace.units() if callable(m.trace.units) else m.trace.units
    assert units["line.velocity"] == "mm/s"


def test_axis_plot_has_no_empty_panel_and_a_unit_on_each():
    """Issue 16: the FS701 scope records no acceleration or jerk of the carriage: its plot has
    position, velocity and following error only, each with its unit; the positioning example
    (every channel recorded) keeps all five."""
    from axisline.report.plots import axis_panels

    for name, axis, labels in (("flying_shear.toml", "carriage", ["position", "velocity", "following error"]),
                               ("positioning.toml", "x", ["position", "velocity", "acceleration", "jerk", "following error"])):
        m = Machine.from_file(EXAMPLES / name)
        for _ in range(20):
            m.scheduler.run_cycle()
        data = m.trace.data() if callable(m.trace.data) else m.trace.data
        units = m.trace.units() if callable(m.trace.units) else m.trace.units
        panels = axis_panels(data, units, axis)
        assert [p[0] for p in panels] == labels
        assert all(p[2] for p in panels)
