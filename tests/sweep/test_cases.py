"""The grid: values of each form, random draws and per-case seeds, dotted keys into the machine data."""

from __future__ import annotations

import pytest

from axisline.sweep.cases import Grid, parameter_values
from axisline.sweep.keys import KeyPathError, parse_key, set_key, walk
from axisline.sweep.spec import RandomParameter, RangeParameter, load_sweep_file


def test_ranges_include_the_stop_and_keep_whole_numbers():
    assert parameter_values("k", RangeParameter(start=100, stop=200, step=50), 0) == [100, 150, 200]
    assert parameter_values("k", RangeParameter(start=0.1, stop=0.3, step=0.1), 0) == [0.1, 0.2, 0.3]
    assert parameter_values("k", RangeParameter(start=1, stop=2, num=3), 0) == [1.0, 1.5, 2.0]
    logs = parameter_values("k", RangeParameter(start=10, stop=1000, num=3, scale="log"), 0)
    assert logs == pytest.approx([10, 100, 1000])
    whole = parameter_values("k", RangeParameter(start=40, stop=2400, num=5, scale="log", round=0), 0)
    assert all(isinstance(v, int) for v in whole) and whole[0] == 40 and whole[-1] == 2400


def test_random_draws_are_stable_and_seeded():
    """spec.py decision 2: draw j depends on (seed, key, j) only: more draws keep the first ones."""
    three = parameter_values("axis.x.kv", RandomParameter(random="uniform", low=10, high=20, count=3), 7)
    five = parameter_values("axis.x.kv", RandomParameter(random="uniform", low=10, high=20, count=5), 7)
    assert five[:3] == three and all(10 <= v <= 20 for v in five)
    assert parameter_values("axis.x.kv", RandomParameter(random="uniform", low=10, high=20, count=3), 8) != three
    assert parameter_values("axis.x.v_max", RandomParameter(random="uniform", low=10, high=20, count=3), 7) != three
    ints = parameter_values("k", RandomParameter(random="integers", low=1, high=3, count=50), 0)
    assert set(ints) <= {1, 2, 3} and all(isinstance(v, int) for v in ints)
    logs = parameter_values("k", RandomParameter(random="loguniform", low=1, high=1000, count=50), 0)
    assert all(1 <= v <= 1000 for v in logs)


def test_per_case_seeds_follow_the_values(sweep_file):
    """spec.py decision 3: a case's machine seed comes from its values, not its place."""
    def grid(values: str) -> Grid:
        spec = load_sweep_file(sweep_file(f"""
            [sweep]
            base = "@SLIDE@"
            machine_seed = "per_case"
            seed = 5
            [parameters]
            "axis.x.kv" = {values}
        """))
        return Grid(spec, "base text", 5.0)

    small = {c.overrides: (c.seed, c.key) for c in grid("[20, 30]").cases()}
    grown = {c.overrides: (c.seed, c.key) for c in grid("[10, 20, 30]").cases()}
    assert len(grown) == 3 and all(grown[k] == v for k, v in small.items())
    seeds = [s for s, _ in grown.values()]
    assert len(set(seeds)) == 3 and all(0 <= s < 2**63 for s in seeds)


def test_grid_order_and_keys(sweep_file):
    spec = load_sweep_file(sweep_file("""
        [sweep]
        base = "@SLIDE@"
        [parameters]
        "axis.x.kv" = [20, 30]
        "axis.x.v_max" = [100, 150, 200]
    """))
    g = Grid(spec, "text", 5.0)
    cases = list(g.cases())
    assert len(g) == 6 == len(cases) and [c.index for c in cases] == list(range(6))
    assert cases[1].overrides == (("axis.x.kv", 20), ("axis.x.v_max", 150))  # the first key varies slowest
    assert len({c.key for c in cases}) == 6 and all(c.seed is None for c in cases)
    assert Grid(spec, "other text", 5.0).case(0, (20, 100)).key != cases[0].key  # a changed base runs again


def test_a_value_twice_is_refused(sweep_file):
    from axisline.sweep.engine import prepare
    from axisline.sweep.spec import SweepError

    f = sweep_file('[sweep]\nbase = "@SLIDE@"\n[parameters]\n"axis.x.kv" = [20, 20.0]\n')
    with pytest.raises(ValueError, match="comes twice"):
        Grid(load_sweep_file(f), "text", 5.0)
    with pytest.raises(SweepError, match=r"parameters.'axis.x.kv': the value 20.0 comes twice"):
        prepare(f)


def test_dotted_keys_by_name_index_and_new_tables():
    data = {"axis": [{"name": "x", "kv": 1}, {"name": "carriage", "kv": 2}], "material": {"profile": [{"speed": 1.0}]}}
    assert parse_key("material.profile[0].speed") == ["material", "profile", 0, "speed"]
    set_key(data, "axis.carriage.kv", 40)
    set_key(data, "axis[0].drive.time_constant", 0.01)
    set_key(data, "material.profile[0].speed", 500)
    set_key(data, "device.parameters.cutting_length", 700)
    assert data["axis"][1]["kv"] == 40 and data["axis"][0]["drive"] == {"time_constant": 0.01}
    assert walk(data, "material.profile[0].speed") == 500 and data["device"] == {"parameters": {"cutting_length": 700}}
    with pytest.raises(KeyPathError, match=r"no entry of axis has name = 'y' \(names: 'x', 'carriage'\)"):
        set_key(data, "axis.y.kv", 1)
    with pytest.raises(KeyPathError, match=r"material.profile has 1 entries \(allowed index: 0 .. 0\)"):
        set_key(data, "material.profile[3].speed", 1)
    with pytest.raises(KeyPathError, match="is a list of tables; name an entry"):
        set_key(data, "axis.x", 1)
