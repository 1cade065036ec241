"""Files a device reads itself (parameter sets, cam memories, EEPROM images, cam CSVs) are
refused by size before they are read, and a malformed one is a clear error, never a traceback
(issue 15, "Size limits are enforced before work is done")."""

from __future__ import annotations

import os
import time
from pathlib import Path

import pytest
from typer.testing import CliRunner

from axisline.cli import app

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
runner = CliRunner()


def _huge(path: Path, size: int = 50 << 20) -> Path:
    with open(path, "wb") as f:  # sparse: costs nothing to make, 50 MB to read
        f.truncate(size)
    return path


def _machine(tmp_path: Path, example: str, replace: tuple[str, str]) -> Path:
    text = (EXAMPLES / example).read_text().replace(*replace)
    machine = tmp_path / example
    machine.write_text(text)
    for folder in ("params", "curves"):
        if (EXAMPLES / folder).exists() and not (tmp_path / folder).exists():
            os.symlink(EXAMPLES / folder, tmp_path / folder)
    return machine


def test_a_50_mb_fs701_parameter_file_is_refused_at_once(tmp_path):
    _huge(tmp_path / "huge.toml")
    machine = _machine(tmp_path, "flying_shear.toml", ('parameter_file = "params/fs701_params.toml"', 'parameter_file = "huge.toml"'))
    start = time.monotonic()
    r = runner.invoke(app, ["check", str(machine)])
    assert time.monotonic() - start < 2.0
    assert r.exit_code == 2, r.output
    assert "MiB" in r.output and "limit" in r.output


@pytest.mark.parametrize("content", [b"", b"[]", b"{", b"\xff\xfe", b"[" * 100_000 + b"]" * 100_000])
def test_a_malformed_compax_memory_or_parameter_file_is_a_clear_error(tmp_path, content):
    for key in ("memory_file", "parameter_file"):
        (tmp_path / "bad.json").write_bytes(content)
        machine = _machine(tmp_path, "cam_packaging.toml", ('# memory_file = "cam_packaging.cam.json"', f'{key} = "bad.json"'))
        r = runner.invoke(app, ["check", str(machine)])
        assert r.exit_code == 2, (key, r.output)
        assert r.exception is None or isinstance(r.exception, SystemExit), r.exception


def test_a_50_mb_compax_memory_file_is_refused_at_once(tmp_path):
    _huge(tmp_path / "huge.json")
    machine = _machine(tmp_path, "cam_packaging.toml", ('# memory_file = "cam_packaging.cam.json"', 'memory_file = "huge.json"'))
    start = time.monotonic()
    r = runner.invoke(app, ["check", str(machine)])
    assert time.monotonic() - start < 2.0
    assert r.exit_code == 2 and "limit" in r.output, r.output


def test_a_cam_csv_with_one_endless_line_is_a_value_error(tmp_path):
    from axisline.motion.cam import PointTable

    csv = tmp_path / "one_line.csv"
    csv.write_text("master,slave\n" + "1" * 300_000 + ",2\n")  # a field over csv's own limit
    with pytest.raises(ValueError, match="not a CSV point table"):
        PointTable.from_csv(csv)
