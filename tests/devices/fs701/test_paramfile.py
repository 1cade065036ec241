"""FS701 parameter files: round trip, atomic save, validated load, compare."""

from __future__ import annotations

import os

import pytest

from axisline.devices.fs701.io_assign import IOAssignment
from axisline.devices.fs701.parameters import ParameterSet
from axisline.devices.fs701.paramfile import (
    ParamFileError,
    diff_parameter_files,
    format_parameter_file,
    load_into,
    load_parameter_file,
    load_parameters,
    parse_parameter_file,
    save_parameters,
)


def commissioned() -> ParameterSet:
    """The values of the §4.2 .. §4.3.7 screenshots."""
    return ParameterSet({
        "cutting_length": 10_000, "test_cut_length": 10_000, "virtual_line_speed": 10_000,
        "p_gain": 500, "max_line_speed": 2_000_000, "sampling_time": 10,
        "home_window": 3, "minimum_position": -100, "maximum_position": 10_000, "alarm_position": 9000,
        "led_function": 1, "master_rev_limit": 100, "batch_counter": 243, "waste_counter": 9,
        "additional_cuts": 1, "add_cut_1_length": 1000, "add_cut_2_length": 2000, "add_cut_3_length": 3000,
        "dir_counter_1": 0, "ana_out_gain_2": 10.17, "sync_rate": -1.25, "photocell_delay": 12.5, "i_time": 0.03,
    })  # fmt: skip


def test_round_trip_with_io(tmp_path):
    p = commissioned()
    io = IOAssignment.default()
    io.assign_input("reset_batch_cou", 12)
    path = save_parameters(tmp_path / "shear.toml", p, io, comment="line 3")
    loaded = load_parameter_file(path)
    assert loaded.params == p and loaded.io == io and loaded.comment == "line 3"
    text = path.read_text()
    assert "sync_rate = -1.25" in text and "# 0x0105 +/- Sync Rate [%] -9.99..9.99" in text
    assert "ana_out_gain_2 = 10.17" in text and "i_time = 0.030" in text


def test_only_changed_and_missing_parameters_take_defaults(tmp_path):
    p = commissioned()
    path = save_parameters(tmp_path / "changed.toml", p, only_changed=True)
    text = path.read_text()
    assert "[communication]" not in text and "gap_time" not in text
    loaded = load_parameter_file(path)
    assert loaded.params == p and loaded.io is None


def test_aliases_are_accepted_once(tmp_path):
    text = format_parameter_file(ParameterSet(), only_changed=True)
    ok = text + "\n[basic_settings]\nrel_return_speed = 2.00\nsync_mode = 0\n"
    assert parse_parameter_file(ok).params.return_speed == 2.0
    twice = text + "\n[basic_settings]\nreturn_speed = 2.00\nrel_return_speed = 1.50\n"
    with pytest.raises(ParamFileError, match="given twice"):
        parse_parameter_file(twice)


def test_bad_file_changes_nothing_and_names_line_parameter_value_range(tmp_path):
    good = save_parameters(tmp_path / "good.toml", commissioned())
    text = good.read_text()
    bad_text = text.replace("sync_rate = -1.25", "sync_rate = -12.5").replace("cutting_length = 10000", "cuting_length = 10000")
    bad = tmp_path / "bad.toml"
    bad.write_text(bad_text)
    target = ParameterSet()
    io = IOAssignment.default()
    with pytest.raises(ParamFileError) as info:
        load_into(bad, target, io)
    assert target == ParameterSet() and io == IOAssignment.default()
    msg = str(info.value)
    sync_line = bad_text.splitlines().index("sync_rate = -12.5                # 0x0105 +/- Sync Rate [%] -9.99..9.99") + 1
    assert f"line {sync_line}: [basic_settings] sync_rate" in msg and "-12.5" in msg and "-9.99..9.99" in msg
    assert "cuting_length: no such FS701 parameter" in msg and len(info.value.problems) == 2
    loaded = load_into(good, target, io)
    assert target == commissioned() and loaded.io is None


@pytest.mark.parametrize(
    "mutation, message",
    [
        (lambda t: t.replace("[general]", "[general"), "not valid TOML"),
        (lambda t: t.replace('format = "axisline.fs701.parameters"', 'format = "other"'), "format must be"),
        (lambda t: t.replace("version = 1", "version = 2"), "version must be 1"),
        (lambda t: t + "\n[nonsense]\na = 1\n", "unknown table or key 'nonsense'"),
        (lambda t: t.replace("[general]", "[general]\ntool_width = 5"), r"belongs to block \[basic_settings\]"),
        (lambda t: t.replace("edge_sense = 0", "edge_sense = true"), "must be a number"),
        (lambda t: t.replace("edge_sense = 0", 'edge_sense = "0"'), "must be a number"),
        (lambda t: t.replace("sync_rate = 0.00", "sync_rate = 0.001"), "resolution 0.01"),
        (lambda t: t.replace("ser_unit_address = 11", "ser_unit_address = 20"), "digit 0"),
        (lambda t: t + "\n[io.inputs]\nprint_mark = [3]\n", "fixed to In15"),
        (lambda t: t + "\n[io.inputs]\nstart_gapp = [3]\n", "io.inputs.start_gapp"),
        (lambda t: t + "\n[io.outputs]\nalarm = [9]\n", "1..8"),
        (lambda t: t + "\n[io.outputs]\nalarm = 'x'\n", "must be a list"),
    ],
)
def test_each_kind_of_bad_file_is_refused(mutation, message):
    text = format_parameter_file(ParameterSet())
    with pytest.raises(ParamFileError, match=message):
        parse_parameter_file(mutation(text), "x.toml")


def test_syntax_error_names_the_line():
    text = format_parameter_file(ParameterSet()).replace("tool_width = 0", "tool_width = = 0")
    with pytest.raises(ParamFileError, match=r"line \d+"):
        parse_parameter_file(text)


def test_unreadable_file(tmp_path):
    with pytest.raises(ParamFileError, match="cannot read"):
        load_parameters(tmp_path / "missing.toml")


def test_atomic_save_keeps_the_old_file_on_failure(tmp_path, monkeypatch):
    path = save_parameters(tmp_path / "shear.toml", commissioned())
    old = path.read_bytes()

    def broken_fsync(fd):
        raise OSError("disk full")

    monkeypatch.setattr(os, "fsync", broken_fsync)
    with pytest.raises(OSError, match="disk full"):
        save_parameters(path, ParameterSet())
    monkeypatch.undo()
    assert path.read_bytes() == old
    assert sorted(os.listdir(tmp_path)) == ["shear.toml"]  # no temporary file left behind
    assert load_parameters(path) == commissioned()


def test_compare_files(tmp_path):
    a = save_parameters(tmp_path / "a.toml", commissioned(), IOAssignment.default())
    changed = commissioned()
    changed.cutting_length = 12_000
    io = IOAssignment.default()
    io.assign_output("no_printmark", 8)
    b = save_parameters(tmp_path / "b.toml", changed, io)
    params, io_diff = diff_parameter_files(a, b)
    assert [(d.name, d.ours, d.theirs) for d in params] == [("cutting_length", 10_000, 12_000)]
    assert io_diff == ["output no_printmark: [] != [8]"]
    c = save_parameters(tmp_path / "c.toml", changed)
    assert diff_parameter_files(b, c)[1] == ["I/O assignment present in only one file"]
    assert diff_parameter_files(a, a) == ([], [])
