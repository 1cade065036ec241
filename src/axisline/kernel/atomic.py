"""Atomic file writes: a reader sees the old file or the new one, never half of either.

Used for traces, parameter sets, programs and curves. The data goes to a temporary file in
the target's directory (so ``os.replace`` stays on one filesystem and is atomic), is flushed
and fsynced, then replaces the target; the directory is fsynced so the rename survives a
power cut.
"""

from __future__ import annotations

import os
import tempfile
from collections.abc import Iterator
from contextlib import contextmanager
from typing import IO, Any

__all__ = ["atomic_open", "atomic_write_bytes", "atomic_write_text", "remove_stale_temporaries", "unwritable_reason"]

_WRITE_MODES = frozenset({"w", "wt", "wb"})
_TMP_SUFFIX = ".tmp"  # temporary files are ".NAME.<random>.tmp" beside NAME (remove_stale_temporaries)


def _umask() -> int:
    # Reading /proc avoids os.umask's set-and-restore, which races with other threads.
    try:
        with open("/proc/self/status", encoding="ascii") as status:
            for line in status:
                if line.startswith("Umask:"):
                    return int(line.split()[1], 8)
    except OSError:
        pass
    mask = os.umask(0o022)
    os.umask(mask)
    return mask


def _new_file_mode(path: str) -> int:
    # Keep the permissions of the file being replaced; a new file gets what open() would give.
    try:
        return os.stat(path).st_mode & 0o7777
    except FileNotFoundError:
        return 0o666 & ~_umask()


def _fsync_directory(directory: str) -> None:
    try:
        fd = os.open(directory, os.O_RDONLY)
    except OSError:  # not possible on every platform (e.g. Windows); the rename is still atomic
        return
    try:
        os.fsync(fd)
    except OSError:
        pass
    finally:
        os.close(fd)


@contextmanager
def atomic_open(
    path: str | os.PathLike[str],
    mode: str = "w",
    *,
    encoding: str | None = None,
    newline: str | None = None,
) -> Iterator[IO[Any]]:
    """Open ``path`` for writing; the file appears complete when the block exits normally.

    ``mode`` is "w"/"wt" (text, UTF-8 unless ``encoding`` is given) or "wb". If the block
    raises, the target is left untouched and the temporary file is removed.
    """
    if mode not in _WRITE_MODES:
        raise ValueError(f"atomic_open mode must be one of 'w', 'wt', 'wb', got {mode!r}")
    target = os.path.abspath(os.fspath(path))
    directory, name = os.path.split(target)
    binary = "b" in mode
    if binary and (encoding is not None or newline is not None):
        raise ValueError("encoding and newline apply to text mode only")
    if not binary and encoding is None:
        encoding = "utf-8"  # never the locale's: files must read the same on every machine

    fd, tmp_path = tempfile.mkstemp(dir=directory, prefix=f".{name}.", suffix=_TMP_SUFFIX)
    try:
        os.chmod(tmp_path, _new_file_mode(target))
        file = os.fdopen(fd, mode, encoding=encoding, newline=newline)
    except BaseException:
        os.close(fd)
        os.unlink(tmp_path)
        raise
    try:
        with file:
            yield file
            file.flush()
            os.fsync(file.fileno())
        os.replace(tmp_path, target)
    except BaseException:
        try:
            os.unlink(tmp_path)
        except FileNotFoundError:
            pass
        raise
    _fsync_directory(directory)


def atomic_write_bytes(path: str | os.PathLike[str], data: bytes) -> None:
    """Replace ``path`` with ``data`` atomically."""
    with atomic_open(path, "wb") as file:
        file.write(data)


def atomic_write_text(
    path: str | os.PathLike[str], text: str, *, encoding: str = "utf-8", newline: str | None = None
) -> None:
    """Replace ``path`` with ``text`` atomically (UTF-8 by default)."""
    with atomic_open(path, "w", encoding=encoding, newline=newline) as file:
        file.write(text)


def remove_stale_temporaries(path: str | os.PathLike[str]) -> list[str]:
    """Remove the temporary files that interrupted atomic writes of ``path`` left beside it.

    A process killed between creating ``.NAME.<random>.tmp`` and the rename leaves it behind;
    the target itself is intact. Call this only where no other writer of ``path`` can be
    running (a device's start), since a live writer's temporary file looks the same.
    Returns the paths removed; a directory that cannot be listed removes nothing.
    """
    directory, name = os.path.split(os.path.abspath(os.fspath(path)))
    prefix = f".{name}."
    removed: list[str] = []
    try:
        entries = os.listdir(directory)
    except OSError:
        return removed
    for entry in entries:
        # prefix + at least one random character + suffix: never NAME itself or ".NAME.tmp"
        if not (entry.startswith(prefix) and entry.endswith(_TMP_SUFFIX)) or len(entry) <= len(prefix) + len(_TMP_SUFFIX):
            continue
        candidate = os.path.join(directory, entry)
        if not os.path.isfile(candidate) or os.path.islink(candidate):
            continue  # mkstemp makes regular files only; anything else is not ours
        try:
            os.unlink(candidate)
        except FileNotFoundError:
            continue
        removed.append(candidate)
    return removed


def unwritable_reason(path: str | os.PathLike[str]) -> str | None:
    """Why an atomic write of ``path`` would fail, or None if it can be written.

    The write needs a regular file (or nothing) at ``path`` and a writable directory for
    the temporary file and the rename; missing directories count as writable when the
    nearest existing one is (callers create them with ``mkdir(parents=True)``). A file
    that exists read-only is refused too: it was made read-only to keep it as it is.
    """
    target = os.path.abspath(os.fspath(path))
    if os.path.isdir(target):
        return "is a directory, not a file"
    if os.path.lexists(target):
        if not os.path.isfile(target):
            return "exists and is not a regular file"
        if not os.access(target, os.W_OK):
            return "is read-only"
    directory = os.path.dirname(target)
    while not os.path.lexists(directory):
        parent = os.path.dirname(directory)
        if parent == directory:
            break
        directory = parent
    if not os.path.isdir(directory):
        return f"{directory} is not a directory"
    if not os.access(directory, os.W_OK | os.X_OK):
        return f"directory {directory} is not writable"
    return None
