"""Trace (the scope): per-cycle samples of named channels into preallocated numpy arrays.

Channels are declared before the run; ``record(cycle)`` in the RECORD stage copies one value
per channel. A finished trace is saved as npz (arrays plus units and period) or csv.
Saved npz files are byte-identical for identical runs: the zip entries carry a fixed
timestamp, so a file hash can check a simulation for regressions.
"""

from __future__ import annotations

import csv
import json
import os
import zipfile
from collections.abc import Callable
from typing import Any, Literal

import numpy as np

from .atomic import atomic_open
from .clock import check_period_us

__all__ = ["Recording", "Trace"]

_DTYPES: dict[type, np.dtype[Any]] = {
    float: np.dtype(np.float64),
    int: np.dtype(np.int64),
    bool: np.dtype(np.bool_),
}
_KIND_NAMES = {np.dtype(np.float64): "float", np.dtype(np.int64): "int", np.dtype(np.bool_): "bool"}
_RESERVED = ("t", "cycle")
_META_KEY = "__meta__"
_FORMAT = "axisline-trace"
_FORMAT_VERSION = 1
_ZIP_DATE = (1980, 1, 1, 0, 0, 0)  # fixed so identical data gives identical files


def _check_count(what: str, value: object) -> int:
    if isinstance(value, bool) or not isinstance(value, int) or value < 1:
        raise ValueError(f"{what} must be an integer >= 1, got {value!r}")
    return value


class Recording:
    """A finished trace: columns "t" [s], "cycle" and the channels, in time order."""

    def __init__(
        self,
        columns: dict[str, np.ndarray],
        units: dict[str, str],
        period_us: int,
        decimation: int = 1,
        overflowed: bool = False,
    ) -> None:
        lengths = {len(column) for column in columns.values()}
        if len(lengths) > 1:
            raise ValueError(f"trace columns differ in length: {sorted(lengths)}")
        for name in _RESERVED:
            if name not in columns:
                raise ValueError(f"trace has no {name!r} column")
        self._columns = columns
        self.units = dict(units)
        self.period_us = period_us
        self.decimation = decimation
        self.overflowed = overflowed

    @property
    def channels(self) -> tuple[str, ...]:
        """Channel names, without "t" and "cycle"."""
        return tuple(name for name in self._columns if name not in _RESERVED)

    def data(self) -> dict[str, np.ndarray]:
        """Copies of all columns: "t", "cycle", then the channels in declaration order."""
        return {name: column.copy() for name, column in self._columns.items()}

    def __len__(self) -> int:
        return len(self._columns["cycle"])

    def save_npz(self, path: str | os.PathLike[str]) -> None:
        """Save atomically as .npz; readable by ``np.load`` and by ``Trace.load_npz``."""
        meta = {
            "format": _FORMAT,
            "version": _FORMAT_VERSION,
            "period_us": self.period_us,
            "decimation": self.decimation,
            "overflowed": self.overflowed,
            "columns": list(self._columns),
            "units": self.units,
        }
        entries = dict(self._columns)
        entries[_META_KEY] = np.array(json.dumps(meta, sort_keys=True))
        # Written by hand rather than np.savez, whose zip entries carry the current time.
        with (
            atomic_open(path, "wb") as file,
            zipfile.ZipFile(file, "w", compression=zipfile.ZIP_STORED, allowZip64=True) as zf,
        ):
            for name, array in entries.items():
                info = zipfile.ZipInfo(f"{name}.npy", date_time=_ZIP_DATE)
                info.compress_type = zipfile.ZIP_STORED
                info.external_attr = 0o644 << 16
                if not array.flags.c_contiguous:
                    array = array.copy(order="C")  # (np.ascontiguousarray would make 0-d 1-d)
                with zf.open(info, "w", force_zip64=True) as entry:
                    np.lib.format.write_array(entry, array, allow_pickle=False)

    def save_csv(self, path: str | os.PathLike[str]) -> None:
        """Save atomically as CSV; header cells are ``name[unit]`` (just ``name`` if no unit)."""
        names = list(self._columns)
        header = [f"{name}[{self.units[name]}]" if self.units.get(name) else name for name in names]
        # tolist() gives Python scalars: repr of a float is the shortest exact round trip.
        columns = [
            column.astype(np.int8).tolist() if column.dtype == np.bool_ else column.tolist()
            for column in self._columns.values()
        ]
        with atomic_open(path, "w", newline="") as file:
            writer = csv.writer(file, lineterminator="\n")
            writer.writerow(header)
            writer.writerows(zip(*columns))

    @classmethod
    def load_npz(cls, path: str | os.PathLike[str]) -> Recording:
        """Read a file written by ``save_npz``."""
        with np.load(path, allow_pickle=False) as npz:
            if _META_KEY not in npz.files:
                raise ValueError(f"{os.fspath(path)!r} is not an axisline trace (no {_META_KEY})")
            meta = json.loads(str(npz[_META_KEY][()]))
            if meta.get("format") != _FORMAT or meta.get("version") != _FORMAT_VERSION:
                raise ValueError(
                    f"{os.fspath(path)!r}: unsupported trace format "
                    f"{meta.get('format')!r} version {meta.get('version')!r}"
                )
            columns = {name: npz[name] for name in meta["columns"]}
        return cls(
            columns,
            meta["units"],
            meta["period_us"],
            decimation=meta["decimation"],
            overflowed=meta["overflowed"],
        )


class Trace:
    """Scope recorder with preallocated buffers.

    ``mode="linear"`` fills ``capacity`` samples then stops (``overflowed`` is set when a
    sample is refused); ``mode="ring"`` keeps the newest ``capacity`` samples
    (``overflowed`` is set once old samples are overwritten). With ``decimation=n`` one
    call of ``record`` in n stores a sample, starting with the first call.
    ``period_us`` (default 1 ms) converts cycles to "t"; pass the clock's period.
    """

    def __init__(
        self,
        capacity: object,
        decimation: object = 1,
        mode: Literal["linear", "ring"] = "linear",
        *,
        period_us: object = 1000,
    ) -> None:
        # capacity, decimation, period_us: integers, typed `object` because the checks refuse
        # anything else with an error naming the setting (not a compiled signature's TypeError)
        self.capacity = capacity = _check_count("trace capacity", capacity)
        self.decimation = _check_count("trace decimation", decimation)
        if mode not in ("linear", "ring"):
            raise ValueError(f"trace mode must be 'linear' or 'ring', got {mode!r}")
        self.mode = mode
        self.period_us = check_period_us(period_us)
        self._ring = mode == "ring"
        self._cycles = np.zeros(capacity, dtype=np.int64)
        self._times = np.zeros(capacity, dtype=np.float64)
        self._buffers: dict[str, np.ndarray] = {}
        self._units: dict[str, str] = {"t": "s", "cycle": ""}
        self._sampling: tuple[tuple[Callable[[], Any], np.ndarray], ...] = ()
        self._calls = 0
        self._stored = 0  # samples stored since the start, including overwritten ones
        self.overflowed = False

    def add_channel(
        self,
        name: str,
        getter: Callable[[], Any],
        unit: str = "",
        kind: type = float,
    ) -> None:
        """Declare a channel before recording starts; ``getter()`` returns its current value."""
        if self._calls:
            raise RuntimeError(f"channel {name!r} added after recording started; add it before")
        if not isinstance(name, str) or not name or name.startswith("__"):
            raise ValueError(
                f"channel name must be a non-empty string not starting with '__', got {name!r}"
            )
        if name in _RESERVED or name in self._buffers:
            raise ValueError(f"channel {name!r} already exists")
        if not callable(getter):
            raise TypeError(f"channel {name!r}: getter must be callable, got {getter!r}")
        dtype = _DTYPES.get(kind)
        if dtype is None:
            raise ValueError(f"channel {name!r}: kind must be float, int or bool, got {kind!r}")
        buffer = np.zeros(self.capacity, dtype=dtype)
        self._buffers[name] = buffer
        self._units[name] = str(unit)
        self._sampling = self._sampling + ((getter, buffer),)

    @property
    def channels(self) -> tuple[str, ...]:
        return tuple(self._buffers)

    @property
    def units(self) -> dict[str, str]:
        """Unit per column, including "t" ("s") and "cycle" ("")."""
        return dict(self._units)

    def kind(self, name: str) -> str:
        """Value type of channel ``name``: "float", "int" or "bool"."""
        return _KIND_NAMES[self._buffers[name].dtype]

    def record(self, cycle: int) -> bool:
        """Sample every channel for ``cycle``; return whether a sample was stored."""
        calls = self._calls
        self._calls = calls + 1
        if calls % self.decimation:
            return False
        stored = self._stored
        if stored < self.capacity:
            index = stored
        elif self._ring:
            index = stored % self.capacity
            self.overflowed = True
        else:
            self.overflowed = True
            return False
        self._cycles[index] = cycle
        self._times[index] = cycle * self.period_us / 1_000_000
        for getter, buffer in self._sampling:
            buffer[index] = getter()
        self._stored = stored + 1
        return True

    def clear(self) -> None:
        """Forget all samples (re-arm the scope); channels stay declared."""
        self._calls = 0
        self._stored = 0
        self.overflowed = False

    def __len__(self) -> int:
        """Samples held (at most ``capacity``)."""
        return min(self._stored, self.capacity)

    def _in_time_order(self, buffer: np.ndarray) -> np.ndarray:
        held = len(self)
        if self._stored <= self.capacity:
            return buffer[:held].copy()
        oldest = self._stored % self.capacity
        return np.concatenate((buffer[oldest:], buffer[:oldest]))

    def data(self) -> dict[str, np.ndarray]:
        """Copies in time order: "t" [s], "cycle", then the channels in declaration order."""
        columns = {
            "t": self._in_time_order(self._times),
            "cycle": self._in_time_order(self._cycles),
        }
        for name, buffer in self._buffers.items():
            columns[name] = self._in_time_order(buffer)
        return columns

    def snapshot(self) -> Recording:
        """The samples held now, detached from the live buffers."""
        return Recording(
            self.data(),
            self._units,
            self.period_us,
            decimation=self.decimation,
            overflowed=self.overflowed,
        )

    def save_npz(self, path: str | os.PathLike[str]) -> None:
        """Save atomically as .npz with units, period, decimation and overflow flag."""
        self.snapshot().save_npz(path)

    def save_csv(self, path: str | os.PathLike[str]) -> None:
        """Save atomically as CSV with a ``name[unit]`` header."""
        self.snapshot().save_csv(path)

    @staticmethod
    def load_npz(path: str | os.PathLike[str]) -> Recording:
        """Read a saved trace: ``.data()``, ``.units``, ``.period_us`` as when it was saved."""
        return Recording.load_npz(path)


# Compiled, the public names get this source's docstrings and annotations back (help(),
# inspect.signature); in plain Python this does nothing. See axisline/_docs.py.
from axisline._docs import document as _document  # noqa: E402

# hot: called every cycle from interpreted code (devices), left compiled-only (no wrapper)
_document(globals(), hot={"Trace": ("record",)})
