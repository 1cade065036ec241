"""Bad machine files and command-line values: exit 2 naming the key, the value and the
allowed range, never a traceback; size limits hold before any work is done; and a fuzz
of the examples never gets past the configuration layer into a crash."""

import copy
import json
import math
import os
import shutil
import subprocess
import sys
import time
import tomllib
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from typer.testing import CliRunner

from axisline.cli import app

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
runner = CliRunner()


@pytest.fixture()
def ex(tmp_path):
    """A private copy of examples/ (machine files find their referenced files beside them)."""
    shutil.copytree(EXAMPLES, tmp_path / "ex")
    return tmp_path / "ex"


def _edit(ex: Path, example: str, old: str, new: str, name: str = "bad.toml") -> Path:
    text = (ex / example).read_text()
    assert old in text, old
    f = ex / name
    f.write_text(text.replace(old, new, 1))
    return f


def _refused(args: list[str], *fragments: str) -> str:
    """The command exits 2 with a message holding every fragment, and raises nothing."""
    res = runner.invoke(app, args)
    assert res.exception is None or isinstance(res.exception, SystemExit), repr(res.exception)
    assert res.exit_code == 2, res.output
    flat = " ".join(res.output.split())  # (rich wraps long lines)
    for frag in fragments:
        assert frag in flat, f"{frag!r} not in {flat!r}"
    return flat


def _check_and_run_refuse(f: Path, *fragments: str) -> None:
    for cmd in (["check", str(f)], ["run", str(f), "--duration", "0.05", "--quiet"]):
        _refused(cmd, *fragments)


# -- files that are not UTF-8 -----------------------------------------------------------


def test_a_machine_file_that_is_not_utf8_is_refused(tmp_path):
    f = tmp_path / "latin1.toml"
    f.write_bytes('[machine]\nname = "Schere Süd"\n'.encode("latin-1"))
    _check_and_run_refuse(f, "not UTF-8", "byte 0xfc at position 26")


def test_a_cam_memory_file_that_is_not_utf8_is_refused(ex):
    (ex / "mem.json").write_bytes(b"\xff\xfe{}")
    f = _edit(ex, "cam_packaging.toml", '# memory_file = "cam_packaging.cam.json"', 'memory_file = "mem.json"')
    _check_and_run_refuse(f, "device.memory_file = 'mem.json'", "not UTF-8")


def test_a_compax_parameter_file_that_is_not_utf8_is_refused(ex):
    (ex / "par.json").write_bytes(b"\xff\xfe{}")
    f = _edit(ex, "cam_packaging.toml", '# memory_file = "cam_packaging.cam.json"', 'parameter_file = "par.json"')
    _check_and_run_refuse(f, "device.parameter_file = 'par.json'", "not UTF-8")


def test_a_cam_csv_that_is_not_utf8_or_missing_is_refused(ex):
    (ex / "curves" / "latin1.csv").write_bytes("master,slave\n0,0\n360,1\n# Süd\n".encode("latin-1"))
    cam = '[[cam]]\nname = "t"\nmaster_period = 360.0\ncsv = "{}"\n\n[[cam]]                      # one knife'
    f = _edit(ex, "cam_sync.toml", "[[cam]]                      # one knife", cam.format("curves/latin1.csv"))
    _check_and_run_refuse(f, "cam[0].csv = 'curves/latin1.csv'", "not UTF-8")
    f = _edit(ex, "cam_sync.toml", "[[cam]]                      # one knife", cam.format("curves/nope.csv"))
    _check_and_run_refuse(f, "cam[0].csv = 'curves/nope.csv'", "No such file")


# -- cams of motion laws ----------------------------------------------------------------


def test_a_misspelt_cam_law_names_the_segment_and_the_laws(ex):
    f = _edit(ex, "cam_sync.toml", '"modified_sine"', '"modified_sin"')
    _check_and_run_refuse(f, "cam[0].segments[1].law = 'modified_sin'", "'modified_sine'", "'cycloidal'")


def test_an_extra_key_in_a_cam_segment_is_named(ex):
    f = _edit(ex, "cam_sync.toml", 'slave_end = 0.0, law = "dwell" }', 'slave_end = 0.0, law = "dwell", lenght = 3 }')
    _check_and_run_refuse(f, "cam[0].segments[0].lenght: unknown key", "master_end, slave_end, law")


def test_a_cam_missing_its_last_segment_says_where_the_cycle_ends(ex):
    f = _edit(ex, "cam_sync.toml", '  { master_end = 360.0, slave_end = 360.0, law = "dwell" },\n', "")
    _check_and_run_refuse(f, "cam[0]: cam 'cut': segment 1: master_end = 240.0 must equal master_period = 360.0")


def test_a_point_table_cam_that_does_not_end_the_cycle_is_refused(ex):
    cam = '[[cam]]\nname = "t"\nmaster_period = 360.0\npoints = [[0.0, 0.0], [200.0, 5.0]]\n\n[[cam]]  # one knife'
    f = _edit(ex, "cam_sync.toml", "[[cam]]                      # one knife", cam)
    _check_and_run_refuse(f, "cam[0]: cam 't': the last master point 200.0 must equal master_period 360.0")


# -- plant ------------------------------------------------------------------------------


def test_overlapping_print_marks_are_refused(ex):
    f = _edit(ex, "flying_shear_printmark.toml", "pitch = 800.0\n", "positions = [100.0, 900.0, 905.0]\n")
    _check_and_run_refuse(f, "marks[0]: positions: the marks at 900.0 and 905.0 overlap (width 10.0")


# -- paths ------------------------------------------------------------------------------


@pytest.mark.parametrize(
    "example, old, new, key",
    [
        ("flying_shear.toml", '"params/fs701_params.toml"', '"params/fs\\u0000701.toml"', "device.parameter_file"),
        ("cam_packaging.toml", '# memory_file = "cam_packaging.cam.json"', 'memory_file = "a\\u0000.json"', "device.memory_file"),
        ("cam_packaging.toml", '"curves/sealing_jaw.csv"', '"curves/x\\u0000.csv"', "device.curves[1].csv"),
    ],
)
def test_a_nul_byte_in_a_path_is_refused(ex, example, old, new, key):
    f = _edit(ex, example, old, new)
    _check_and_run_refuse(f, key, "NUL")


def test_a_nul_byte_in_a_cam_csv_path_is_refused(ex):
    cam = '[[cam]]\nname = "t"\nmaster_period = 360.0\ncsv = "a\\u0000.csv"\n\n[[cam]]  # one knife'
    f = _edit(ex, "cam_sync.toml", "[[cam]]                      # one knife", cam)
    _check_and_run_refuse(f, "cam[0].csv", "NUL")


# -- the job: check rejects whatever run would trip over ----------------------------------


@pytest.mark.parametrize(
    "step, needs",
    [
        ('axis = "x"\ncommand = "power"', "power needs on"),
        ('axis = "x"\ncommand = "move_absolute"\nvelocity = 5.0', "move_absolute needs position"),
        ('axis = "x"\ncommand = "move_relative"', "move_relative needs distance"),
        ('axis = "x"\ncommand = "move_velocity"', "move_velocity needs velocity"),
        ('axis = "x"\ncommand = "set_position"', "set_position needs position"),
        ('axis = "x"\ncommand = "jog"', "jog needs direction"),
    ],
)
def test_a_job_step_without_its_required_argument_fails_check(ex, step, needs):
    f = _edit(ex, "positioning.toml", 'axis = "x"\ncommand = "power"\non = true', step)
    _check_and_run_refuse(f, "job.steps[0]", needs)


def test_a_direction_is_checked_against_what_the_command_means_by_it(ex):
    # found by the fuzz below: move_absolute took -1/0/1 (a jog's direction) and crashed run
    f = _edit(ex, "positioning.toml", "position = 500.0", "position = 500.0\ndirection = 1")
    _check_and_run_refuse(f, "job.steps[2]: move_absolute direction = 1", "'shortest', 'positive', 'negative', 'current'")


def test_a_cam_out_without_its_positions_fails_check(ex):
    f = _edit(ex, "cam_sync.toml", "decoupling = 250.0\n", "")
    _check_and_run_refuse(f, "job.steps[10]", "cam_out needs decoupling")


def test_a_non_finite_job_value_is_refused(ex):
    f = _edit(ex, "positioning.toml", "position = 500.0", "position = nan")
    _check_and_run_refuse(f, "job.steps[2].position = nan", "finite")


def test_a_duplicate_trace_channel_is_refused(ex):
    f = _edit(ex, "flying_shear.toml", '"carriage.command_position",', '"carriage.command_position", "carriage.command_position",')
    _check_and_run_refuse(f, "trace.channels", "'carriage.command_position' is listed twice")


def test_run_refuses_an_output_it_could_not_write_before_running(tmp_path):
    (tmp_path / "plain").write_text("")
    flat = _refused(["run", str(EXAMPLES / "positioning.toml"), "--json", str(tmp_path / "plain" / "r.json")],
                    "--json", "is not a directory")
    assert "simulated" not in flat  # refused before the run, not after it


# -- command-line values -----------------------------------------------------------------


@pytest.mark.parametrize("value", ["inf", "nan", "-1", "0", "1e9"])
def test_run_refuses_a_duration_outside_the_machine_files_range(value):
    _refused(["run", str(EXAMPLES / "positioning.toml"), f"--duration={value}", "--quiet"],
             f"--duration = {float(value)!r}", "> 0", "<= 604800")


@pytest.mark.parametrize("value", ["-1", str(2**63)])
def test_run_refuses_a_seed_outside_the_machine_files_range(value):
    _refused(["run", str(EXAMPLES / "positioning.toml"), f"--seed={value}", "--quiet"], f"--seed = {value}", ">= 0")


@pytest.mark.parametrize("value", ["inf", "nan", "-1"])
def test_serve_refuses_a_bad_duration_before_it_starts(value):
    _refused(["serve", str(EXAMPLES / "positioning.toml"), f"--duration={value}"], f"--duration = {float(value)!r}")


# -- size limits ---------------------------------------------------------------------------


def _cli_in_child(*args: str) -> tuple[int, str, float, int]:
    """(exit code, stderr+stdout, wall seconds, peak RSS in MB) of one `axisline` run in a child."""
    code = (
        "import resource, sys\n"
        "from axisline.cli import app\n"
        "try:\n    app(sys.argv[1:])\nexcept SystemExit as e:\n    rc = e.code\n"
        # VmHWM, not ru_maxrss: Linux keeps ru_maxrss across exec (it would be pytest's own)
        "hwm = [l for l in open('/proc/self/status') if l.startswith('VmHWM')][0].split()[1]\n"
        "print('MAXRSS', int(hwm) // 1024, file=sys.stderr)\n"
        "sys.exit(rc)\n"
    )
    t0 = time.perf_counter()
    p = subprocess.run([sys.executable, "-c", code, *args], capture_output=True, text=True, timeout=120,
                       env={**os.environ, "COLUMNS": "200"})
    wall = time.perf_counter() - t0
    rss = int(p.stderr.rsplit("MAXRSS", 1)[1].split()[0])
    return p.returncode, p.stdout + p.stderr.rsplit("MAXRSS", 1)[0], wall, rss


needs_proc = pytest.mark.skipif(not Path("/proc/self/status").exists(), reason="peak memory from /proc")


@needs_proc
def test_a_50_mb_machine_file_is_refused_at_once(tmp_path):
    f = tmp_path / "big.toml"
    f.write_text("[machine]\n" + "# padding padding padding padding padding padding\n" * 1_000_000)
    assert f.stat().st_size > 50e6
    rc, text, wall, rss = _cli_in_child("check", str(f))
    assert rc == 2 and "limit" in text and "MiB" in text, text
    assert wall < 2.0 and rss < 150, (wall, rss)


@needs_proc
def test_30000_masters_are_refused_at_once_with_a_short_message(tmp_path):
    f = tmp_path / "masters.toml"
    # (inline: 30 000 tables in full would be refused for the file's size already)
    f.write_text("master = [" + ", ".join(f'{{name = "m{i}"}}' for i in range(30000)) + "]\n")
    rc, text, wall, rss = _cli_in_child("check", str(f))
    assert rc == 2 and "master" in text and "at most 16" in text, text
    assert len(text) < 2000, len(text)
    assert wall < 2.0 and rss < 150, (wall, rss)


@pytest.mark.parametrize(
    "text, says",
    [
        # tomllib takes time and memory quadratic in the parts of a dotted key: this one, 200 kB,
        # took more memory than the machine has
        ("a." * 100_000 + "b = 1\n", "line 1: a dotted key of more than 16 parts"),
        ("x = " + "[" * 5000 + "]" * 5000 + "\n", "nested too deeply"),
    ],
)
@needs_proc
def test_toml_shapes_that_would_stall_the_parser_are_refused_at_once(tmp_path, text, says):
    f = tmp_path / "shape.toml"
    f.write_text(text)
    rc, out, wall, rss = _cli_in_child("check", str(f))
    assert rc == 2 and says in out, out
    assert wall < 2.0 and rss < 150, (wall, rss)


def test_a_long_value_is_echoed_shortened(ex):
    f = _edit(ex, "positioning.toml", 'name = "two-axis positioning demo"', f'name = "{"n" * 100_000}"')
    flat = _refused(["check", str(f)], "machine.name = 'nnnn", "100000 characters", "at most 200")
    assert len(flat) < 1000
    f = _edit(ex, "positioning.toml", 'axis = "r"\ncommand = "power"', f'axis = "{"r" * 100_000}"\ncommand = "power"')
    assert len(_refused(["check", str(f)], "job.steps[1].axis")) < 1000
    f = _edit(ex, "positioning.toml", 'type = "servo"', f'type = "{"s" * 100_000}"')  # pydantic quotes a tag whole
    assert len(_refused(["check", str(f)], "axis[0].drive")) < 1000


# -- a fuzz of the examples ------------------------------------------------------------------


def _toml_key(k: str) -> str:
    return k if k and all(c.isalnum() or c in "_-" for c in k) else json.dumps(k)


def _toml_value(v) -> str:
    """Inline TOML (the standard library reads TOML but does not write it)."""
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        return "nan" if math.isnan(v) else ("inf" if v == math.inf else "-inf" if v == -math.inf else repr(v))
    if isinstance(v, str):
        return json.dumps(v)
    if isinstance(v, list):
        return "[" + ", ".join(_toml_value(x) for x in v) + "]"
    return "{" + ", ".join(f"{_toml_key(k)} = {_toml_value(x)}" for k, x in v.items()) + "}"


def _to_toml(data: dict) -> str:
    return "".join(f"{_toml_key(k)} = {_toml_value(v)}\n" for k, v in data.items())


def _paths(node, at=()):
    """Every location in a parsed machine file: (path, value)."""
    yield at, node
    if isinstance(node, dict):
        for k, v in node.items():
            yield from _paths(v, (*at, k))
    elif isinstance(node, list):
        for i, v in enumerate(node):
            yield from _paths(v, (*at, i))


_REPLACEMENTS = st.sampled_from(
    ["text", "", True, -1, 0, 2**70, -1e300, 1e300, 1e-300, math.nan, math.inf, -math.inf, [], [1, "a"], {}, {"k": 1}]
)
_FILE_KEYS = ("csv", "parameter_file", "memory_file", "save_parameters", "program_file")
_EXAMPLE_FILES = sorted(p.name for p in EXAMPLES.glob("*.toml"))


@st.composite
def _mutated(draw):
    name = draw(st.sampled_from(_EXAMPLE_FILES))
    data = tomllib.loads((EXAMPLES / name).read_text())
    for _ in range(draw(st.integers(1, 3))):
        spots = [(p, v) for p, v in _paths(data) if p]
        path, value = draw(st.sampled_from(spots))
        *head, last = path
        parent = data
        for part in head:
            parent = parent[part]
        how = draw(st.sampled_from(["delete", "replace", "scale", "unknown key", "missing file"]))
        if how == "delete":
            del parent[last]
        elif how == "replace":
            parent[last] = copy.deepcopy(draw(_REPLACEMENTS))  # (a later mutation may change it)
        elif how == "scale" and isinstance(value, (int, float)) and not isinstance(value, bool):
            parent[last] = value * draw(st.sampled_from([-1, 0, 1000, 1e9, 1e30]))
        elif how == "unknown key" and isinstance(value, dict):
            value["bogus_key"] = 1
        elif how == "missing file":
            for p, v in _paths(data):
                if p and p[-1] in _FILE_KEYS and isinstance(v, str):
                    *h, k = p
                    target = data
                    for part in h:
                        target = target[part]
                    target[k] = "does/not/exist.file"
    return name, data


@pytest.fixture(scope="module")
def fuzz_dir(tmp_path_factory):
    d = tmp_path_factory.mktemp("fuzz") / "ex"
    shutil.copytree(EXAMPLES, d)
    return d


@settings(max_examples=60, suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow])
@given(case=_mutated())
def test_mutated_examples_exit_0_1_or_2_and_never_crash(fuzz_dir, case):
    name, data = case
    f = fuzz_dir / f"mutated_{name}"
    f.write_text(_to_toml(data))
    res = runner.invoke(app, ["check", str(f)])
    assert res.exception is None or isinstance(res.exception, SystemExit), (res.output, res.exception)
    assert res.exit_code in (0, 2), res.output
    if res.exit_code == 0:
        res = runner.invoke(app, ["run", str(f), "--duration", "0.05", "--quiet"])
        assert res.exception is None or isinstance(res.exception, SystemExit), (res.output, res.exception)
        assert res.exit_code in (0, 1), res.output


# -- a misspelt key: the key meant is suggested (issue 16) -----------------------------------


def test_a_misspelt_device_key_suggests_the_key_meant(ex):
    f = _edit(ex, "flying_shear.toml", "ramp_tolerance = 2.0", "ramp_tolerence = 2.0")
    _check_and_run_refuse(f, "device.ramp_tolerence: unknown key; did you mean ramp_tolerance?")


def test_a_misspelt_trace_key_suggests_the_key_meant(ex):
    f = _edit(ex, "positioning.toml", "capacity = 30000", "Capacity = 30000")
    _check_and_run_refuse(f, "trace.Capacity: unknown key; did you mean capacity?")


def test_an_unknown_key_far_from_every_key_gets_no_guess(ex):
    f = _edit(ex, "positioning.toml", "capacity = 30000", "capacity = 30000\nzzzzzz = 1")
    flat = _refused(["check", str(f)], "trace.zzzzzz: unknown key (known keys here: enabled, capacity")
    assert "did you mean" not in flat
