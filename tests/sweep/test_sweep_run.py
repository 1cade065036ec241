"""Running sweeps: Dask (threads and processes) and a single process give the same files; a
failing case, a bad key, resume, the command's exit codes."""

from __future__ import annotations


import pyarrow.parquet as pq
import pytest

from axisline.sweep import engine as engine_mod
from axisline.sweep.engine import prepare, run_sweep
from axisline.sweep.spec import SweepError

# 2 x 3 cases of the test slide (it moves to 100 mm). sw_limit_low = 110 with sw_limit_high = 50
# is refused by the machine-file model in that case only (each value alone is fine): the case
# fails, the others run. A limit on the way to 100 mm refuses the move: a runtime fault.
SWEEP = """
[sweep]
name = "slide sweep"
base = "@SLIDE@"
duration = 2.0
collect = ["completed", "axes.x.max_following_error", "axes.x.max_speed", "job.events.t", "job.events.text"]
feasible = ["completed == true", "axes.x.max_following_error <= 0.4"]

[parameters]
"axis.x.sw_limit_low" = [-10.0, 110.0]
"axis.x.sw_limit_high" = [1000.0, 120.0, 50.0]

[report]
heatmap = { x = "axis.x.sw_limit_high", y = "axis.x.sw_limit_low", metric = "axes.x.max_following_error" }
line = { x = "axis.x.sw_limit_high", metric = "axes.x.max_speed" }
"""

FILES = ("results.csv", "job.events.csv", "report.md")


def _texts(out):
    return {name: (out / name).read_text(encoding="utf-8") for name in FILES}


@pytest.fixture(scope="module")
def reference(tmp_path_factory):
    """The sweep in this process (workers = 0): the reference of the engine tests."""
    tmp = tmp_path_factory.mktemp("ref")
    f = tmp / "sweep.toml"
    from .conftest import SLIDE

    f.write_text(SWEEP.replace("@SLIDE@", str(SLIDE)), encoding="utf-8")
    out = tmp / "out"
    outcome = run_sweep(f, out, workers=0)
    return f, out, outcome


def test_single_process_results(reference):
    _, out, outcome = reference
    assert (outcome.total, outcome.ran, outcome.ok, outcome.fault, outcome.failed) == (6, 6, 2, 3, 1)
    table = pq.read_table(out / "results.parquet").to_pylist()
    by = {(r["axis.x.sw_limit_low"], r["axis.x.sw_limit_high"]): r for r in table}
    good = by[(-10.0, 1000.0)]
    assert good["status"] == "ok" and good["completed"] is True and good["feasible"] is True
    assert 0.0 < good["axes.x.max_following_error"] <= 0.4 and good["axes.x.max_speed"] > 150
    assert by[(-10.0, 50.0)]["status"] == "fault" and by[(-10.0, 50.0)]["feasible"] is False
    events = pq.read_table(out / "job.events.parquet").to_pylist()
    assert {e["job.events.text"] for e in events if e["case"] == good["case"]} == {"x.power", "x.move_absolute"}
    report = (out / "report.md").read_text()
    assert "**6 cases**: 2 completed, 3 ended on a runtime fault, 1 failed." in report
    assert (out / "heatmap.png").stat().st_size > 1000 and (out / "line.png").stat().st_size > 1000


def test_a_case_that_raises_is_recorded_and_the_others_run(reference):
    _, out, _ = reference
    table = pq.read_table(out / "results.parquet").to_pylist()
    failed = [r for r in table if r["status"] == "failed"]
    assert len(failed) == 1 and (failed[0]["axis.x.sw_limit_low"], failed[0]["axis.x.sw_limit_high"]) == (110.0, 50.0)
    assert "sw_limit_low = 110 must be below sw_limit_high = 50" in failed[0]["error"]
    assert failed[0]["feasible"] is None and failed[0]["completed"] is None
    assert "## Failed cases" in (out / "report.md").read_text()


@pytest.mark.parametrize("processes", [False, True], ids=["threads", "processes"])
def test_dask_and_single_process_give_identical_files(reference, tmp_path, processes):
    f, ref_out, _ = reference
    out = tmp_path / "out"
    outcome = run_sweep(f, out, workers=2, processes=processes)
    assert outcome.ran == 6
    assert _texts(out) == _texts(ref_out)
    assert pq.read_table(out / "results.parquet").equals(pq.read_table(ref_out / "results.parquet"))


def test_bad_key_exits_2_naming_it_before_anything_runs(sweep_file, run_cli, tmp_path, monkeypatch):
    ran = []
    monkeypatch.setattr(engine_mod, "run_case", lambda *a, **k: ran.append(a))
    f = sweep_file(SWEEP.replace("\n[report]", '"axis.x.kvv" = [10.0]\n[report]'))
    out = tmp_path / "out"
    r = run_cli(f, "--out", out, "--workers", "0")
    assert r.exit_code == 2, r.output
    assert "parameters.'axis.x.kvv' = 10.0: axis[0].kvv: unknown key" in r.output and "did you mean kv" in r.output
    assert not ran and not (out / "journal").exists()
    f = sweep_file(SWEEP.replace("\n[report]", '"axis.y.kv" = [10.0]\n[report]'))
    r = run_cli(f, "--out", out, "--workers", "0")
    assert r.exit_code == 2 and "parameters.'axis.y.kv': no entry of axis has name = 'y' (names: 'x')" in r.output
    f = sweep_file(SWEEP.replace("\n[report]", '"axis.x.kv" = [10.0, -1.0]\n[report]'))
    r = run_cli(f, "--out", out, "--workers", "0")
    assert r.exit_code == 2 and "parameters.'axis.x.kv' = -1.0: axis[0].kv = -1.0" in r.output and "allowed" in r.output
    assert not ran and not (out / "journal").exists()


def test_resume_skips_done_cases_and_reruns_failed_ones(sweep_file, tmp_path, monkeypatch):
    """journal.py decision 1."""
    f = sweep_file(SWEEP)
    out = tmp_path / "out"
    run_sweep(f, out, workers=0)
    before = (out / "results.csv").read_text()
    seen = []
    real = engine_mod.run_case
    monkeypatch.setattr(engine_mod, "run_case", lambda *a: seen.append(a[2]) or real(*a))
    again = run_sweep(f, out, workers=0)
    assert (again.ran, again.skipped) == (1, 5) and seen == [5]  # the failed case only
    assert (out / "results.csv").read_text() == before
    seen.clear()  # a grown grid: only the new cases run
    grown = sweep_file(SWEEP.replace("[1000.0, 120.0, 50.0]", "[1000.0, 120.0, 50.0, 500.0]"))
    third = run_sweep(grown, out, workers=0)
    assert third.total == 8 and sorted(seen) == [3, 6, 7] and third.ran == 3
    assert len(list((out / "journal").glob("part-*.jsonl"))) == 1  # compacted at the end


def test_unknown_collect_field_stops_the_sweep(sweep_file, tmp_path):
    """engine.py decision 2."""
    f = sweep_file(SWEEP.replace('"job.events.text"]', '"axes.x.max_folowing_error"]'))
    with pytest.raises(SweepError) as e:
        run_sweep(f, tmp_path / "out", workers=0)
    assert "sweep.collect: 'axes.x.max_folowing_error' is not in the run summary" in e.value.problems[0]
    assert "max_following_error" in e.value.problems[0]


def test_cli_exit_codes_and_summary_line(sweep_file, run_cli, tmp_path):
    f = sweep_file(SWEEP)
    out = tmp_path / "out"
    r = run_cli(f, "--out", out, "--workers", "0")
    assert r.exit_code == 1, r.output  # one case failed
    assert "6 cases (2 completed, 3 fault, 1 failed); ran 6, 0 already done" in r.output
    assert str(out / "results.parquet") in r.output
    ok = sweep_file(SWEEP.replace("[-10.0, 110.0]", "[-10.0]"), "ok.toml")
    r = run_cli(ok, "--out", tmp_path / "ok", "--workers", "0")
    assert r.exit_code == 0, r.output
    for args, expected in (
        (("--workers", "-1"), "--workers = -1: allowed: 0 .. 1024"),
        (("--workers", "2", "--scheduler", "tcp://127.0.0.1:1"), "not with --scheduler"),
        (("--scheduler", "localhost"), "expected a Dask scheduler address"),
    ):
        r = run_cli(ok, "--out", tmp_path / "x", *args)
        assert r.exit_code == 2 and expected in r.output, r.output
    r = run_cli(tmp_path / "missing.toml", "--out", tmp_path / "x")
    assert r.exit_code == 2 and "cannot read" in r.output


def test_default_out_folder(sweep_file, run_cli, tmp_path, monkeypatch):
    """cli.py decision 2."""
    f = sweep_file(SWEEP.replace("[-10.0, 110.0]", "[-10.0]").replace("[1000.0, 120.0, 50.0]", "[1000.0]"), "tiny.toml")
    monkeypatch.chdir(tmp_path)
    r = run_cli(f, "--workers", "0")
    assert r.exit_code == 0, r.output
    assert (tmp_path / "out" / "sweeps" / "tiny" / "results.csv").is_file()


def test_prepare_checks_the_base_file(sweep_file, tmp_path):
    bad = tmp_path / "bad_machine.toml"
    bad.write_text("[machine]\ncycle_us = 1\n")
    f = sweep_file(SWEEP.replace("@SLIDE@", str(bad)))
    with pytest.raises(SweepError) as e:
        prepare(f)
    assert e.value.problems[0].startswith("sweep.base = ") and "machine.cycle_us = 1" in e.value.problems[0]


def test_an_existing_cluster_runs_the_same_sweep(reference, tmp_path):
    """--scheduler: the sweep on a cluster it did not start (here a local one over TCP)."""
    import logging

    from dask.distributed import LocalCluster

    f, ref_out, _ = reference
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=False, protocol="tcp", dashboard_address=None,
                      silence_logs=logging.ERROR) as cluster:
        assert cluster.scheduler_address.startswith("tcp://")
        outcome = run_sweep(f, tmp_path / "out", scheduler=cluster.scheduler_address)
        assert outcome.ran == 6 and cluster.scheduler is not None  # the sweep left the cluster running
    assert _texts(tmp_path / "out") == _texts(ref_out)


def test_journal_parts_are_whole_and_unreadable_lines_are_skipped(tmp_path):
    """journal.py decision 2: parts written whole; a line that is not a result is ignored."""
    from axisline.sweep.journal import Journal

    j = Journal(tmp_path)
    j.add({"key": "a", "status": "ok", "values": {"x": 1}})
    j.add({"key": "b", "status": "failed", "values": {}})
    j.flush()
    (tmp_path / "journal" / "part-000002.jsonl").write_text('{"key": "a", "status": "ok", "values": {"x": 2}}\n{"key": "c", "sta\n')
    stored = Journal(tmp_path).load()
    assert set(stored) == {"a", "b"} and stored["a"]["values"] == {"x": 2}  # the later part wins
    nxt = Journal(tmp_path)
    nxt.add({"key": "d", "status": "ok", "values": {}})
    nxt.flush()
    assert (tmp_path / "journal" / "part-000003.jsonl").is_file()
    nxt.compact()
    assert [p.name for p in (tmp_path / "journal").iterdir()] == ["part-000004.jsonl"]
    assert set(Journal(tmp_path).load()) == {"a", "b", "d"}


def test_progress_bar_on_a_terminal(sweep_file, tmp_path):
    """engine.py decision 1: on a terminal, a bar with cases done, failed, faults and the rate."""
    import io

    from rich.console import Console

    buf = io.StringIO()
    console = Console(file=buf, force_terminal=True, width=140, color_system=None)
    run_sweep(sweep_file(SWEEP), tmp_path / "out", workers=0, console=console)
    text = buf.getvalue()
    assert "sweep" in text and "6/6" in text and "failed 1" in text and "fault 3" in text and "cases/s" in text
    quiet = io.StringIO()
    run_sweep(sweep_file(SWEEP), tmp_path / "out2", workers=0, console=Console(file=quiet, force_terminal=False))
    assert quiet.getvalue() == ""  # not a terminal: no bar (the command prints one line at the end)


def test_an_exception_in_a_case_on_dask_is_recorded(sweep_file, tmp_path, monkeypatch):
    """Any exception of a case (here a made-up one, on a 2-worker cluster) is its error; the sweep goes on."""
    from axisline.sweep import worker

    real = worker._run

    def broken(m, duration, stop_on_fault):
        if m.config.axis[0].sw_limit_high == 120.0:
            raise ZeroDivisionError("made up for the test")
        return real(m, duration, stop_on_fault)

    monkeypatch.setattr(worker, "_run", broken)
    outcome = run_sweep(sweep_file(SWEEP), tmp_path / "out", workers=2, processes=False)
    errors = {r["case"]: r["error"] for r in outcome.results if r["status"] == "failed"}
    assert set(errors) == {1, 4, 5} and outcome.ok == 1
    assert errors[1].startswith("ZeroDivisionError: made up for the test (at test_sweep_run.py:")
