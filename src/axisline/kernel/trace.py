"""Trace (the scope): per-cycle samples of named channels into preallocated numpy arrays.

Channels are declared before the run; ``record(cycle)`` in the RECORD stage samples them. A
finished trace is saved as npz (arrays plus units and period) or csv. Saved npz files are
byte-identical for identical runs: the zip entries carry a fixed timestamp, so a file hash
can check a simulation for regressions.

Cost (issue 18): writing one value into a numpy array from Python costs several times
more than reading it, and the scope samples dozens of channels per cycle. So ``record``
packs a sample's values with ``struct`` into one record of a preallocated byte block (the
row block, read by numpy as records of the channels' dtypes), and every ``_BLOCK`` samples
one numpy copy per channel moves the block into the columns. Every read (``data``,
``snapshot``, ``since``, ``save_npz``, ``save_csv``) copies the block first; ``len``,
``stored`` and ``overflowed`` count each sample as it is recorded. A getter may serve
several channels (``add_channels``): one call per axis instead of one per signal.

Decisions:

1. Issue 18 "the scope writing rows in blocks": a block is 256 samples (at most the
   capacity): the per-channel copy then costs a few percent of recording the samples, and
   the block of a 16-axis machine with 176 channels takes 340 kB. Tests:
   tests/kernel/test_trace.py::test_reads_mid_block_see_every_sample_recorded and
   ::test_ring_wraps_inside_a_block.
2. A value is stored exactly as numpy stores it assigned to its column, as before:
   ``struct`` packs floats, integers and truth values as numpy would convert them, and
   a value it does not take (a float for an int channel, None for a float one) is written
   by numpy itself, in the cycle that sampled it (a value numpy refuses, NaN on an int
   channel, still raises there). Test: ::test_block_stores_what_numpy_assignment_stores.
"""

from __future__ import annotations

import csv
import json
import os
import zipfile
from struct import Struct, calcsize
from struct import error as StructError
from collections.abc import Callable, Iterable, Sequence
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
# struct's codes: native double, long long (64 bits on every platform numpy's int64 is) and _Bool
_PACK_CODES = {np.dtype(np.float64): "d", np.dtype(np.int64): "q", np.dtype(np.bool_): "?"}
_RESERVED = ("t", "cycle")
_META_KEY = "__meta__"
_FORMAT = "axisline-trace"
_FORMAT_VERSION = 1
_ZIP_DATE = (1980, 1, 1, 0, 0, 0)  # fixed so identical data gives identical files
# samples gathered in the row block before they are copied into the columns (decision 1)
_BLOCK = 256


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

    A sample's values go to a row block first and reach the columns a block at a time
    (module docstring); every read (``data``, ``snapshot``, ``since``, the files) copies the
    block over first, so it sees every sample recorded so far.
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
        # the getters as declared: rows (one call, several channels) and single values
        self._row_getters: list[tuple[Callable[[], Sequence[Any]], tuple[str, ...]]] = []
        self._value_getters: list[tuple[Callable[[], Any], str]] = []
        # the row block: each sample packed as one record of the rows' values, then the
        # single values (_arrange); the getters with the packer and byte offset of their values
        self._block = min(_BLOCK, capacity)  # never more samples waiting than the buffers hold
        self._rows: tuple[tuple[Callable[[], Sequence[Any]], Struct, int, tuple[str, ...]], ...] = ()
        self._values: tuple[Callable[[], Any], ...] = ()
        self._values_packer = Struct("=")
        self._values_offset = 0
        self._values_names: tuple[str, ...] = ()
        self._sample_size = 0
        self._bytes = bytearray()
        self._records: np.ndarray = np.zeros(0)  # the block's bytes as numpy records
        self._fields: tuple[tuple[np.ndarray, np.ndarray], ...] = ()  # (column, its field of _records)
        self._pending_cycles: list[int] = []  # the cycles of the samples in the block
        self._flushed = 0  # samples already in the columns
        self._calls = 0
        self._taken = 0  # samples stored since the start, including overwritten ones
        self.overflowed = False

    def add_channel(
        self,
        name: str,
        getter: Callable[[], Any],
        unit: str = "",
        kind: type = float,
    ) -> None:
        """Declare a channel before recording starts; ``getter()`` returns its current value."""
        if not callable(getter):
            raise TypeError(f"channel {name!r}: getter must be callable, got {getter!r}")
        self._declare((name,), (unit,), (kind,))
        self._value_getters.append((getter, name))
        self._arrange()

    def add_channels(
        self,
        names: Sequence[str],
        getter: Callable[[], Sequence[Any]],
        units: Sequence[str] | None = None,
        kinds: Sequence[type] | None = None,
    ) -> None:
        """Declare several channels read by one call: ``getter()`` returns their values, in
        the order of ``names`` (a tuple or list of that length). Cheaper per sample than one
        getter per channel; ``units`` and ``kinds`` default to "" and float."""
        names = tuple(names)
        if not names:
            raise ValueError("add_channels: no channel names given")
        units = tuple(units) if units is not None else ("",) * len(names)
        kinds = tuple(kinds) if kinds is not None else (float,) * len(names)
        if len(units) != len(names) or len(kinds) != len(names):
            raise ValueError(
                f"add_channels: {len(names)} names but {len(units)} units and {len(kinds)} kinds"
            )
        if not callable(getter):
            raise TypeError(f"channels {', '.join(map(repr, names))}: getter must be callable, got {getter!r}")
        self._declare(names, units, kinds)
        self._row_getters.append((getter, names))
        self._arrange()

    def _declare(self, names: tuple[str, ...], units: tuple[str, ...], kinds: tuple[type, ...]) -> None:
        """Check every name, unit and kind first: a refused declaration adds nothing."""
        if self._calls:
            raise RuntimeError(f"channel {names[0]!r} added after recording started; add it before")
        seen: set[str] = set()
        dtypes = []
        for name, kind in zip(names, kinds):
            if not isinstance(name, str) or not name or name.startswith("__"):
                raise ValueError(
                    f"channel name must be a non-empty string not starting with '__', got {name!r}"
                )
            if name in _RESERVED or name in self._buffers or name in seen:
                raise ValueError(f"channel {name!r} already exists")
            seen.add(name)
            dtype = _DTYPES.get(kind)
            if dtype is None:
                raise ValueError(f"channel {name!r}: kind must be float, int or bool, got {kind!r}")
            dtypes.append(dtype)
        for name, unit, dtype in zip(names, units, dtypes):
            self._buffers[name] = np.zeros(self.capacity, dtype=dtype)
            self._units[name] = str(unit)

    def _arrange(self) -> None:
        """The row block's record: where each channel's value sits in a packed sample.

        Each getter's values are packed by one Struct in native layout ("@": the C
        compiler's alignment, so struct copies native doubles without converting them); its
        part of the record starts at a multiple of 8 bytes, where that layout holds.
        """
        names: list[str] = []
        offsets: list[int] = []
        size = 0

        def place(segment: tuple[str, ...]) -> tuple[Struct, int]:
            nonlocal size
            start = size
            codes = ""
            for name in segment:
                code = _PACK_CODES[self._buffers[name].dtype]
                names.append(name)
                offsets.append(start + calcsize("@" + codes + code) - calcsize("@" + code))
                codes += code
            packer = Struct("@" + codes)
            size = -(-(start + packer.size) // 8) * 8
            return packer, start

        rows = []
        for getter, segment in self._row_getters:
            packer, start = place(segment)
            rows.append((getter, packer, start, segment))
        self._rows = tuple(rows)
        self._values = tuple(getter for getter, _ in self._value_getters)
        self._values_names = tuple(name for _, name in self._value_getters)
        self._values_packer, self._values_offset = place(self._values_names)
        record = np.dtype({
            "names": names,
            "formats": [self._buffers[name].dtype for name in names],
            "offsets": offsets,
            "itemsize": max(size, 8),
        })
        self._sample_size = record.itemsize
        self._bytes = bytearray(self._block * record.itemsize)
        self._records = np.frombuffer(self._bytes, dtype=record)
        self._fields = tuple((self._buffers[name], self._records[name]) for name in names)

    @property
    def channels(self) -> tuple[str, ...]:
        return tuple(self._buffers)

    @property
    def units(self) -> dict[str, str]:
        """Unit per column, including "t" ("s") and "cycle" ("")."""
        return dict(self._units)

    @property
    def stored(self) -> int:
        """Samples stored since the start (or ``clear``), overwritten ones included: the
        number the next sample gets (see ``since``)."""
        return self._taken

    def kind(self, name: str) -> str:
        """Value type of channel ``name``: "float", "int" or "bool"."""
        return _KIND_NAMES[self._buffers[name].dtype]

    def record(self, cycle: int) -> bool:
        """Sample every channel for ``cycle``; return whether a sample was stored."""
        calls = self._calls
        self._calls = calls + 1
        if calls % self.decimation:
            return False
        stored = self._taken
        if stored >= self.capacity:
            self.overflowed = True
            if not self._ring:
                return False
        slot = stored - self._flushed  # the sample's record in the block
        buf = self._bytes
        base = slot * self._sample_size
        for getter, packer, offset, names in self._rows:
            values = getter()
            try:
                packer.pack_into(buf, base + offset, *values)
            except (StructError, TypeError, OverflowError):
                self._convert(slot, names, values)
        if self._values:
            values = [getter() for getter in self._values]
            try:
                self._values_packer.pack_into(buf, base + self._values_offset, *values)
            except (StructError, TypeError, OverflowError):
                self._convert(slot, self._values_names, values)
        self._pending_cycles.append(cycle)
        stored += 1
        self._taken = stored
        if stored - self._flushed >= self._block:
            self._flush()
        return True

    def _convert(self, slot: int, names: tuple[str, ...], values: Sequence[Any]) -> None:
        """Values struct does not take (a float for an int channel, None for a float one):
        numpy converts them, as it did writing each value into its column."""
        if not isinstance(values, (tuple, list)) or len(values) != len(names):
            got = f"{len(values)} values" if isinstance(values, (tuple, list)) else repr(values)
            raise ValueError(
                f"trace channels {', '.join(names)}: the getter returned {got} for {len(names)} channels"
            )
        records = self._records
        for name, value in zip(names, values):
            records[name][slot] = value

    def _flush(self) -> None:
        """Copy the samples of the row block into the columns (the block then is empty)."""
        count = self._taken - self._flushed
        if count <= 0:
            return
        cycles = np.array(self._pending_cycles, dtype=np.int64)
        columns = [(column, field[:count]) for column, field in self._fields]
        # exact: cycle * period_us is an integer below 2**53 for 285 years of cycles, so the
        # float division rounds as Python's int / int does
        columns.append((self._times, cycles * self.period_us / 1_000_000))
        columns.append((self._cycles, cycles))
        start = self._flushed % self.capacity
        first = min(count, self.capacity - start)  # a ring wraps round at most once per block
        for column, values in columns:
            column[start : start + first] = values[:first]
            if first < count:
                column[: count - first] = values[first:]
        self._pending_cycles.clear()
        self._flushed = self._taken

    def clear(self) -> None:
        """Forget all samples (re-arm the scope); channels stay declared."""
        self._pending_cycles.clear()
        self._flushed = 0
        self._calls = 0
        self._taken = 0
        self.overflowed = False

    def __len__(self) -> int:
        """Samples held (at most ``capacity``)."""
        return min(self._taken, self.capacity)

    def _in_time_order(self, buffer: np.ndarray) -> np.ndarray:
        held = len(self)
        if self._taken <= self.capacity:
            return buffer[:held].copy()
        oldest = self._taken % self.capacity
        return np.concatenate((buffer[oldest:], buffer[:oldest]))

    def data(self) -> dict[str, np.ndarray]:
        """Copies in time order: "t" [s], "cycle", then the channels in declaration order."""
        self._flush()
        columns = {
            "t": self._in_time_order(self._times),
            "cycle": self._in_time_order(self._cycles),
        }
        for name, buffer in self._buffers.items():
            columns[name] = self._in_time_order(buffer)
        return columns

    def since(
        self, first: int, channels: Iterable[str] | None = None, limit: int | None = None
    ) -> tuple[int, dict[str, np.ndarray]]:
        """Samples numbered ``first`` on, oldest first (a live scope's next piece).

        Sample n is the n-th stored since the start (or ``clear``); ``stored`` is the number
        the next one gets. Samples a ring has overwritten are gone, so the answer starts at
        the oldest held at the earliest; with ``limit``, it holds the newest ``limit`` at
        most. Returns the number of the first sample returned and copies of the columns
        "t", "cycle" and ``channels`` (every channel when None).
        """
        if isinstance(first, bool) or not isinstance(first, int) or first < 0:
            raise ValueError(f"since: first sample must be an integer >= 0, got {first!r}")
        if limit is not None:
            limit = _check_count("since: limit", limit)
        names = tuple(self._buffers) if channels is None else tuple(channels)
        for name in names:
            if name not in self._buffers:
                raise ValueError(f"since: unknown channel {name!r} (available: {', '.join(self._buffers)})")
        self._flush()
        stored = self._taken
        start = max(first, stored - len(self))
        if limit is not None:
            start = max(start, stored - limit)
        index = np.arange(min(start, stored), stored) % self.capacity
        columns = {"t": self._times[index], "cycle": self._cycles[index]}
        for name in names:
            columns[name] = self._buffers[name][index]  # (indexing with an array copies)
        return min(start, stored), columns

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
