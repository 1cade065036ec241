"""Masters, cams and couplings from the machine file (examples/cam_sync.toml and variants)."""

from pathlib import Path

import pytest

from axisline.config import parse_machine
from axisline.configerrors import ConfigError
from axisline.machine import Machine
from axisline.motion.axis import AxisState
from axisline.motion.camsync import CamState

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


def test_synchronous_motion_example_gears_cams_and_meets_the_line():
    m = Machine.from_file(EXAMPLES / "cam_sync.toml")
    line = m.masters["line"]
    feed, knife, carriage = m.axis("feed"), m.axis("knife"), m.axis("carriage")
    seen = {"feed": [], "knife": [], "carriage": []}
    for _ in range(int(8.0 / m.period)):  # line at speed, every coupling made, before any leaves
        m.scheduler.run_cycle()
        if feed.state is AxisState.SYNCHRONIZED_MOTION:
            seen["feed"].append(feed.command_position - 1.5 * line.position)
        f = m._followers.get("knife")
        if f is not None and f.state is CamState.SYNCHRONOUS:
            seen["knife"].append(knife.command_position - f.curve_state(line.position)[0])
        if carriage.state is AxisState.SYNCHRONIZED_MOTION and line.position >= 2000.0:
            seen["carriage"].append(carriage.command_position - (50.0 + line.position - 2000.0))
    # the gear holds 3:2 exactly once in gear (the offset gathered while catching up is constant)
    tail = seen["feed"][-2000:]
    assert max(tail) - min(tail) <= 2e-3  # within the integer law's count resolution (1 µm)
    assert max(abs(e) for e in seen["knife"]) <= 1e-9  # on the curve whenever synchronous
    assert seen["carriage"] and max(abs(e) for e in seen["carriage"]) <= 1e-3  # met the line at 2000 mm
    result = m.run()
    assert result.completed, result.faults
    # the knife left the curve forward to its standstill position 0 deg (the set point, wrapped)
    assert knife.state is AxisState.STANDSTILL
    assert min(knife.wrap(knife.command_position), 360.0 - knife.wrap(knife.command_position)) <= 1e-6


def test_sync_example_is_deterministic():
    a = Machine.from_file(EXAMPLES / "cam_sync.toml")
    b = Machine.from_file(EXAMPLES / "cam_sync.toml")
    a.run()
    b.run()
    for k, v in a.trace.data().items():
        assert v.tobytes() == b.trace.data()[k].tobytes(), k


def _base(**extra):
    data = {
        "machine": {"duration": 5.0},
        "axis": [{"name": "s", "unit": "mm", "counts_per_unit": 1000.0, "v_max": 500.0, "a_max": 5000.0,
                  "j_max": 100000.0, "kv": 50.0, "following_error_limit": 5.0}],
        "master": [{"name": "line", "kind": "virtual", "velocity": 200.0, "acceleration": 1000.0, "counts_per_unit": 1000.0}],
        "trace": {"enabled": False},
    }
    data.update(extra)
    return data


def test_an_infeasible_gear_in_position_fails_the_job_naming_the_distances():
    data = _base(job={"steps": [
        {"axis": "s", "command": "power", "on": True},
        {"axis": "s", "command": "gear_in_pos", "master": "line", "numerator": 1, "denominator": 1,
         "master_sync_position": 5.0, "slave_sync_position": 400.0},
    ]})
    m = Machine(parse_machine(data))
    result = m.run()
    assert not result.completed
    assert any("gear_in_pos" in f and "needs" in f and "remain" in f for f in result.faults), result.faults


def test_cam_from_csv_beside_the_machine_file(tmp_path):
    (tmp_path / "c.csv").write_text("master,slave\n0,0\n50,10\n100,0\n")
    toml = (EXAMPLES / "cam_sync.toml").read_text()
    toml = toml.replace('kind = "segments"\nmaster_period = 360.0', 'kind = "spline"\ncsv = "c.csv"\nmaster_period = 100.0')
    start = toml.index("segments = [")
    toml = toml[:start] + toml[toml.index("]\n", start) + 2:]
    (tmp_path / "m.toml").write_text(toml)
    m = Machine.from_file(tmp_path / "m.toml")
    assert m.cams["cut"].eval(50.0)[0] == pytest.approx(10.0)


@pytest.mark.parametrize(
    "change, text",
    [
        ({"job": {"steps": [{"axis": "s", "command": "gear_in", "master": "belt", "numerator": 1, "denominator": 1}]}}, "master = 'belt'"),
        ({"job": {"steps": [{"axis": "s", "command": "gear_in", "master": "line"}]}}, "needs numerator and denominator"),
        ({"job": {"steps": [{"axis": "s", "command": "cam_in", "master": "line", "cam": "x"}]}}, "cam = 'x'"),
        ({"cam": [{"name": "c", "master_period": 10.0}]}, "needs exactly one of"),
        ({"master": [{"name": "line", "kind": "axis"}]}, "needs axis"),
        ({"master": [{"name": "line", "kind": "virtual"}]}, "needs an acceleration"),
    ],
)
def test_sync_configuration_errors_name_the_problem(change, text):
    with pytest.raises(ConfigError) as e:
        parse_machine(_base(**change), "t.toml")
    assert any(text in p for p in e.value.problems), e.value.problems
