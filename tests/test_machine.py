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
