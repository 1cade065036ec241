"""The sweep file: forms of parameters, the checks with the key, value and range named."""

from __future__ import annotations

import pytest

from axisline.sweep.spec import SweepError, holds, load_sweep_file, parse_condition

BASE = """
[sweep]
base = "@SLIDE@"
collect = ["completed", "axes.x.max_following_error"]
"""


def test_the_three_forms_of_a_parameter(sweep_file):
    spec = load_sweep_file(sweep_file(BASE + """
        [parameters]
        "axis.x.kv" = [20, 30.5]
        "axis.x.v_max" = { start = 100, stop = 200, step = 50 }
        "axis.x.a_max" = { random = "uniform", low = 1000, high = 3000, count = 3 }
    """))
    assert list(spec.parameters) == ["axis.x.kv", "axis.x.v_max", "axis.x.a_max"]
    assert spec.parameters["axis.x.kv"] == [20, 30.5]
    assert spec.parameters["axis.x.v_max"].step == 50
    assert spec.parameters["axis.x.a_max"].count == 3


@pytest.mark.parametrize("body, expected", [
    ('"axis.x.kv" = { start = 1, stop = 2 }', "give either step or num"),
    ('"axis.x.kv" = { start = 2, stop = 1, step = 1 }', "runs upwards"),
    ('"axis.x.kv" = { start = 0, stop = 1, num = 3, scale = "log" }', "start > 0"),
    ('"axis.x.kv" = { random = "normal", count = 3, mean = 1 }', "needs std"),
    ('"axis.x.kv" = { random = "uniform", low = 1, high = 2, count = 0 }', "count = 0"),
    ('"axis.x.kv" = 5', "a list of values, a range"),
    ('"axis.x.kv" = []', "at least 1"),
    ('"axis..kv" = [1]', "not a dotted machine-file key"),
])
def test_a_bad_parameter_is_named(sweep_file, body, expected):
    with pytest.raises(SweepError) as e:
        load_sweep_file(sweep_file(BASE + "\n[parameters]\n" + body + "\n"))
    text = "\n".join(e.value.problems)
    assert "parameters" in text and expected in text


def test_wall_clock_fields_are_refused(sweep_file):
    with pytest.raises(SweepError) as e:
        load_sweep_file(sweep_file("""
            [sweep]
            base = "@SLIDE@"
            collect = ["completed", "wall_s"]
            [parameters]
            "axis.x.kv" = [20]
        """))
    assert "sweep.collect" in e.value.problems[0] and "wall-clock" in e.value.problems[0]


def test_unknown_keys_get_a_suggestion(sweep_file):
    with pytest.raises(SweepError) as e:
        load_sweep_file(sweep_file(BASE.replace("collect", "colect") + '[parameters]\n"axis.x.kv" = [1]\n'))
    assert "sweep.colect: unknown key" in e.value.problems[0] and "did you mean collect" in e.value.problems[0]


def test_report_and_feasible_name_what_the_sweep_has(sweep_file):
    with pytest.raises(SweepError) as e:
        load_sweep_file(sweep_file(BASE + """
            [parameters]
            "axis.x.kv" = [20]
            [report]
            line = { x = "axis.x.v_max", metric = "completed" }
        """))
    assert "report.line.x = 'axis.x.v_max': not in parameters" in e.value.problems[0]
    with pytest.raises(SweepError) as e:
        load_sweep_file(sweep_file(BASE.replace('collect =', 'feasible = ["summary.count >= 2"]\ncollect =') + """
            [parameters]
            "axis.x.kv" = [20]
        """))
    assert "'summary.count' is not in sweep.collect" in e.value.problems[0]


def test_conditions():
    assert parse_condition("summary.count >= 2") == ("summary.count", ">=", 2)
    assert parse_condition('status == "ok"') == ("status", "==", "ok")
    assert parse_condition("errors == []") == ("errors", "==", [])
    with pytest.raises(ValueError, match="compares numbers"):
        parse_condition("x < true")
    with pytest.raises(ValueError, match="FIELD OP VALUE"):
        parse_condition("x =! 3")
    assert holds(3, ">=", 2) and not holds(None, ">=", 2) and not holds(True, ">", 0)
    assert holds([], "==", []) and holds(1.5, "!=", 2)


def test_a_machine_file_given_as_the_sweep_file_is_named():
    from .conftest import SLIDE

    with pytest.raises(SweepError, match="this is a machine file; a sweep file names it"):
        load_sweep_file(SLIDE)


def test_a_missing_or_broken_file_is_named(tmp_path):
    with pytest.raises(SweepError, match="cannot read"):
        load_sweep_file(tmp_path / "nope.toml")
    bad = tmp_path / "bad.toml"
    bad.write_text("[sweep\n")
    with pytest.raises(SweepError, match="TOML syntax"):
        load_sweep_file(bad)
