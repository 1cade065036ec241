"""Atomic writes: readers see the old file or the new one, never a partial file."""

from __future__ import annotations

import os
import stat
from pathlib import Path

import pytest

from axisline.kernel import atomic_open, atomic_write_bytes, atomic_write_text


def test_write_and_replace_bytes_and_text(tmp_path: Path) -> None:
    path = tmp_path / "params.bin"
    atomic_write_bytes(path, b"\x00\x01first")
    atomic_write_bytes(path, b"second")
    assert path.read_bytes() == b"second"

    text_path = tmp_path / "program.clm"
    atomic_write_text(text_path, "POI 100 ; Weg µm\n")
    assert text_path.read_bytes() == "POI 100 ; Weg µm\n".encode()  # UTF-8 whatever the locale
    assert sorted(p.name for p in tmp_path.iterdir()) == ["params.bin", "program.clm"]


def test_data_is_fsynced_before_the_rename(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    events: list[str] = []
    real_fsync, real_replace = os.fsync, os.replace

    def fsync(fd: int) -> None:
        events.append("fsync")
        real_fsync(fd)

    def replace(src: str, dst: str) -> None:
        events.append("replace")
        real_replace(src, dst)

    monkeypatch.setattr(os, "fsync", fsync)
    monkeypatch.setattr(os, "replace", replace)
    atomic_write_text(tmp_path / "curve.txt", "0 0\n1 1\n")
    assert events[:2] == ["fsync", "replace"]


def test_error_inside_the_block_keeps_the_old_file(tmp_path: Path) -> None:
    path = tmp_path / "params.txt"
    path.write_text("old\n")
    with pytest.raises(RuntimeError):
        with atomic_open(path, "w") as file:
            file.write("half of the new")
            raise RuntimeError("producer failed")
    assert path.read_text() == "old\n"
    assert [p.name for p in tmp_path.iterdir()] == ["params.txt"]


def test_nothing_is_visible_until_the_block_ends(tmp_path: Path) -> None:
    path = tmp_path / "table.csv"
    path.write_text("old\n")
    with atomic_open(path, "w") as file:
        file.write("new\n")
        file.flush()
        assert path.read_text() == "old\n"
    assert path.read_text() == "new\n"


@pytest.mark.skipif(os.name != "posix", reason="POSIX permission bits")
def test_permissions_of_the_replaced_file_are_kept(tmp_path: Path) -> None:
    path = tmp_path / "machine.toml"
    path.write_text("a = 1\n")
    os.chmod(path, 0o640)
    atomic_write_text(path, "a = 2\n")
    assert stat.S_IMODE(os.stat(path).st_mode) == 0o640

    fresh = tmp_path / "fresh.toml"
    atomic_write_text(fresh, "b = 1\n")
    umask = os.umask(0)
    os.umask(umask)
    # Like open(): not the 0600 a temporary file is created with.
    assert stat.S_IMODE(os.stat(fresh).st_mode) == 0o666 & ~umask


@pytest.mark.parametrize("mode", ["r", "a", "w+", "rb", "ab"])
def test_only_plain_write_modes(tmp_path: Path, mode: str) -> None:
    with pytest.raises(ValueError, match="mode"):
        with atomic_open(tmp_path / "x", mode):
            pass
    assert list(tmp_path.iterdir()) == []


def test_missing_directory_raises_and_leaves_nothing(tmp_path: Path) -> None:
    with pytest.raises(FileNotFoundError):
        atomic_write_bytes(tmp_path / "no" / "such" / "dir.bin", b"x")
