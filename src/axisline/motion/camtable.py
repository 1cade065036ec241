"""Cam tables with linear interpolation: `PointTable`, the scaled view `ScaledCurve`, COMPAX
24-bit fractions, the modulo master, and the point checks and CSV files every table shares.
`axisline.motion.cam` is the place to import them from; its docstring describes them. The
cubic splines are in spline.py, the cam editor's check and plot in camcheck.py.
"""

from __future__ import annotations

import csv
import math
import os
from bisect import bisect_right
from collections.abc import Callable, Iterator, Sequence
from typing import Any, Literal

import numpy as np

from axisline.kernel.atomic import atomic_write_text
from axisline.motion.curve import CamCurve

__all__ = [
    "DEFAULT_MAX_POINTS",
    "FRACTION_ONE",
    "ModuloMaster",
    "PointTable",
    "ScaledCurve",
    "decode_fraction",
    "encode_fraction",
]

#: Largest table a constructor or `from_csv` accepts unless told otherwise. COMPAX cam
#: memory holds 2500 set points (compax.md §2.7.2); PC-side tables may be much finer.
DEFAULT_MAX_POINTS = 100_000

#: 24-bit fraction scale: Fx = Ix / 2**23 (compax.md §6.2 item 3).
FRACTION_ONE = 1 << 23
_FRACTION_MAX = FRACTION_ONE - 1  # 0x7FFFFF, the largest positive fraction
_WORD_MASK = 0xFFFFFF

# A table counts as equidistant when every master position lies this close (relative to
# the step) to k * step. The O(1) index is then off by at most one and corrected against
# the stored positions, so it always agrees with bisection.
_EQUIDISTANT_TOLERANCE = 1e-9


# ---------------------------------------------------------------------------------------
# COMPAX 24-bit fractions


def encode_fraction(value: float) -> int:
    """A fraction of the slave (or master) cycle as the 24-bit word COMPAX stores (F format).

    Ix = floor(value · 2²³), limited to −2²³ … 2²³−1, as 24-bit two's complement
    (compax.md §6.2 item 3 [DERIVED]). Floor, not round: the manual's table maps
    0.99999999 to 7F FF FF (round would overflow) and −0.00000001 to FF FF FF (round would
    give 0). Values from −1 up to (not including) 1 are allowed.
    """
    value = float(value)
    if not math.isfinite(value) or not -1.0 <= value < 1.0:
        raise ValueError(
            f"24-bit fraction {value!r} out of range: allowed is -1 <= value < 1 (compax.md §6.2)"
        )
    raw = min(math.floor(value * FRACTION_ONE), _FRACTION_MAX)
    return raw & _WORD_MASK


def decode_fraction(word: int, *, full_scale_is_one: bool = False) -> float:
    """The value of a 24-bit F-format word (two's complement): Ix / 2²³.

    With ``full_scale_is_one`` the largest word 0x7FFFFF reads as exactly 1.0 (the full
    slave cycle S_T, compax.md §4 [DERIVED]); otherwise as 8388607 / 2²³.
    """
    if isinstance(word, bool) or not isinstance(word, (int, np.integer)) or not 0 <= word <= _WORD_MASK:
        shown = f"0x{int(word):X}" if isinstance(word, (int, np.integer)) and not isinstance(word, bool) else repr(word)
        raise ValueError(f"24-bit word {shown} out of range: allowed is an integer 0 ... 0xFFFFFF")
    word = int(word)
    if full_scale_is_one and word == _FRACTION_MAX:
        return 1.0
    signed = word - (1 << 24) if word & 0x800000 else word
    return signed / FRACTION_ONE


# ---------------------------------------------------------------------------------------
# master cycles


class ModuloMaster:
    """Splits an unbounded master position into (cycle index, position in the cycle).

    ``split(x)`` returns (k, r) with x = k · period + r and 0 <= r < period, also for
    negative x. Integer positions with an integer period (encoder counts) use integer
    division and are exact. For floats the remainder comes from ``math.fmod``, which is
    exact in IEEE arithmetic; only when adding the period to a tiny negative remainder
    rounds up to the period itself is r set to 0 (and k moved on), so r never equals the
    period.
    """

    __slots__ = ("period",)

    def __init__(self, period: int | float) -> None:
        if isinstance(period, bool) or not isinstance(period, (int, float)) or not (
            math.isfinite(period) and period > 0
        ):
            raise ValueError(f"master period {period!r} not allowed: it must be a finite number > 0")
        self.period: int | float = period  # an int period keeps integer positions exact

    def split(self, x: int | float) -> tuple[int, int | float]:
        period = self.period
        if isinstance(x, int) and isinstance(period, int):
            k, ri = divmod(x, period)
            return k, ri
        r = math.fmod(x, period) + 0.0  # + 0.0 turns -0.0 into 0.0
        if r < 0.0:
            r += period
            if r >= period:  # -tiny + period rounded up to period
                r = 0.0
        # x - r is within rounding of a multiple of the period; round() picks that multiple.
        return round((x - r) / period), r

    def position(self, x: int | float) -> int | float:
        """The position within the cycle, 0 <= r < period."""
        return self.split(x)[1]

    def __repr__(self) -> str:
        return f"ModuloMaster(period={self.period!r})"


# ---------------------------------------------------------------------------------------
# point validation and CSV


def _point_label(i: int, field: str) -> str:
    return f"point {i} ({field})"


def _validate_points(
    master: Sequence[float | str],
    slave: Sequence[float | str],
    *,
    max_points: int,
    label: Callable[[int, str], str] = _point_label,
) -> tuple[tuple[float, ...], tuple[float, ...]]:
    """Floats of the points, or ValueError naming the point, the value and what is allowed."""
    if len(master) != len(slave):
        raise ValueError(
            f"master has {len(master)} values and slave {len(slave)}: one slave value per master position"
        )
    n = len(master)
    if n < 2:
        raise ValueError(f"a cam table needs at least 2 points, got {n}")
    if n > max_points:
        raise ValueError(f"a cam table may hold at most max_points={max_points} points, got {n}")
    m_out: list[float] = []
    s_out: list[float] = []
    for i in range(n):
        for field, raw, out in (("master", master[i], m_out), ("slave", slave[i], s_out)):
            try:
                value = float(raw)
            except (TypeError, ValueError):
                raise ValueError(f"{label(i, field)}: {raw!r} is not a number") from None
            if not math.isfinite(value):
                raise ValueError(f"{label(i, field)}: {raw!r} not allowed, values must be finite numbers")
            out.append(value)
    if m_out[0] != 0.0:
        raise ValueError(f"{label(0, 'master')}: {m_out[0]!r} not allowed, the first master position must be 0")
    for i in range(1, n):
        if not m_out[i] > m_out[i - 1]:
            raise ValueError(
                f"{label(i, 'master')}: {m_out[i]!r} not allowed, master positions must be strictly "
                f"increasing (previous {m_out[i - 1]!r})"
            )
    return tuple(m_out), tuple(s_out)


def _csv_rows(reader: Any) -> Iterator[list[str]]:
    """The reader's rows; csv.Error (a field over csv's size limit, a NUL byte) as ValueError,
    which is what a caller of `from_csv` handles for a bad file."""
    try:
        yield from reader
    except csv.Error as e:
        raise ValueError(f"line {reader.line_num}: not a CSV point table ({e})") from None


def _read_points_csv(
    path: str | os.PathLike[str], max_points: int
) -> tuple[tuple[float, ...], tuple[float, ...]]:
    master: list[str] = []
    slave: list[str] = []
    lines: list[int] = []
    header_seen = False
    with open(path, encoding="utf-8", newline="") as file:
        reader = csv.reader(file)
        for row in _csv_rows(reader):
            line = reader.line_num
            if not row or all(not cell.strip() for cell in row):
                continue  # blank lines (e.g. a trailing one) carry no point
            cells = [cell.strip() for cell in row]
            if not header_seen:
                if [cell.lower() for cell in cells] != ["master", "slave"]:
                    raise ValueError(f"line {line}: header must be 'master,slave', got {','.join(row)!r}")
                header_seen = True
                continue
            if len(cells) != 2:
                raise ValueError(f"line {line}: expected 2 fields (master,slave), got {len(cells)}: {row!r}")
            if len(master) >= max_points:
                raise ValueError(
                    f"line {line}: more than max_points={max_points} points; a table may hold at most "
                    f"{max_points} points (pass a larger max_points to load it)"
                )
            master.append(cells[0])
            slave.append(cells[1])
            lines.append(line)
    if not header_seen:
        raise ValueError(f"{os.fspath(path)}: empty file, expected the header 'master,slave' and points")

    def label(i: int, field: str) -> str:
        if i < len(lines):
            return f"line {lines[i]}, field '{field}'"
        return f"point {i} ({field})"

    return _validate_points(master, slave, max_points=max_points, label=label)


# ---------------------------------------------------------------------------------------
# tables


class _KnotTable(CamCurve):
    """Shared by point tables and splines: validated knots and the interval lookup."""

    master: tuple[float, ...]
    slave: tuple[float, ...]

    def _set_knots(
        self,
        master: Sequence[float],
        slave: Sequence[float],
        max_points: int,
        equidistant: bool | None,
    ) -> None:
        self.master, self.slave = _validate_points(master, slave, max_points=max_points)
        n = len(self.master)
        self.master_period = self.master[-1]
        self._last_segment = n - 2
        self._m_last = self.master[-1]
        step = self.master_period / (n - 1)
        regular = all(
            abs(m - k * step) <= _EQUIDISTANT_TOLERANCE * step for k, m in enumerate(self.master)
        )
        if equidistant is True and not regular:
            raise ValueError("equidistant=True but the master positions are not equally spaced")
        use_step = regular if equidistant is None else equidistant
        self.equidistant_step: float | None = step if use_step else None
        self._inv_step = 1.0 / step if use_step else 0.0

    def __len__(self) -> int:
        return len(self.master)

    def segment(self, x: float) -> int:
        """Index i of the interval master[i] <= x < master[i+1] (clamped to the table)."""
        m = self.master
        last = self._last_segment
        if self._inv_step:
            i = int(x * self._inv_step)
            if i < 0:
                i = 0
            elif i > last:
                i = last
            if x < m[i]:
                if i > 0:
                    i -= 1
            elif i < last and x >= m[i + 1]:
                i += 1
            return i
        i = bisect_right(m, x) - 1
        if i < 0:
            return 0
        return last if i > last else i

    def last_point_passed(self, x: float) -> int:
        """Index of the last point whose master position is <= x (0 below the table)."""
        if x >= self._m_last:
            return self._last_segment + 1
        return self.segment(x)

    def _segments(self, x: np.ndarray) -> np.ndarray:
        idx = np.searchsorted(np.asarray(self.master), x, side="right") - 1
        return np.clip(idx, 0, self._last_segment)

    def check_points(self) -> np.ndarray:
        """Master positions where the extremes of the derivatives can lie (used by `check`)."""
        return np.asarray(self.master)

    # -- CSV ---------------------------------------------------------------------------

    def to_csv(self, path: str | os.PathLike[str]) -> None:
        """Save the points as ``master,slave`` CSV, atomically, exactly (shortest repr)."""
        lines = ["master,slave"]
        lines.extend(f"{m!r},{s!r}" for m, s in zip(self.master, self.slave))
        atomic_write_text(path, "\n".join(lines) + "\n")

    @classmethod
    def _from_points(cls, master: Sequence[float], slave: Sequence[float], **kwargs: Any) -> Any:
        return cls(master, slave, **kwargs)  # type: ignore[call-arg]

    @classmethod
    def _equidistant_master(cls, n: int, master_period: float) -> list[float]:
        if isinstance(master_period, bool) or not (math.isfinite(master_period) and master_period > 0):
            raise ValueError(f"master_period {master_period!r} not allowed: it must be a finite number > 0")
        if n < 2:
            raise ValueError(f"a cam table needs at least 2 points, got {n}")
        last = n - 1
        master = [master_period * k / last for k in range(n)]
        master[-1] = float(master_period)
        return master


class PointTable(_KnotTable):
    """Slave positions at master positions, linear between them.

    ``PointTable(master, slave)``: master positions strictly increasing, first 0, last the
    master cycle. ``equidistant``: None recognises equally spaced tables (O(1) lookup),
    False forces bisection, True insists on equal spacing.
    """

    def __init__(
        self,
        master: Sequence[float],
        slave: Sequence[float],
        interpolation: Literal["linear"] = "linear",
        *,
        max_points: int = DEFAULT_MAX_POINTS,
        equidistant: bool | None = None,
    ) -> None:
        if interpolation != "linear":
            raise ValueError(
                f"interpolation {interpolation!r} not supported by PointTable: allowed is 'linear' "
                "(use SplineTable for a cubic spline)"
            )
        self.interpolation = interpolation
        self._set_knots(master, slave, max_points, equidistant)
        m, s = self.master, self.slave
        self._slope = tuple((s[i + 1] - s[i]) / (m[i + 1] - m[i]) for i in range(len(m) - 1))
        self._s_last = s[-1]
        self._slope_last = self._slope[-1]
        self._point_acc: list[float] | None = None  # set_point_acceleration, built on first use

    @classmethod
    def equidistant(
        cls,
        slave_values: Sequence[float],
        master_period: float,
        interpolation: Literal["linear"] = "linear",
        *,
        max_points: int = DEFAULT_MAX_POINTS,
    ) -> PointTable:
        """COMPAX-style set points: point k at master position k · master_period / (N − 1)."""
        master = cls._equidistant_master(len(slave_values), master_period)
        return cls(master, slave_values, interpolation, max_points=max_points, equidistant=True)

    @classmethod
    def from_fractions(
        cls,
        fractions: Sequence[int],
        master_cycle: float,
        slave_cycle: float,
        *,
        max_points: int = DEFAULT_MAX_POINTS,
    ) -> PointTable:
        """Equidistant table from COMPAX 24-bit set-point words (F format, fractions of S_T).

        Each word is the 24-bit two's complement the cam memory holds (0 … 0xFFFFFF, e.g.
        0x400000 = 0.5, 0xC00000 = −0.5); 0x7FFFFF is the full slave cycle. Point k sits at
        k · M_T / (N − 1) with slave F_k · S_T (compax.md §2.7.2, §4 [DERIVED]).
        """
        if not (math.isfinite(slave_cycle)):
            raise ValueError(f"slave_cycle {slave_cycle!r} not allowed: it must be a finite number")
        values = []
        for k, word in enumerate(fractions):
            try:
                values.append(decode_fraction(word, full_scale_is_one=True) * slave_cycle)
            except ValueError as exc:
                raise ValueError(f"set point {k}: {exc}") from None
        return cls.equidistant(values, master_cycle, max_points=max_points)

    def fractions(self, slave_cycle: float) -> list[int]:
        """The slave values as COMPAX 24-bit words (fractions of ``slave_cycle``).

        The full slave cycle becomes 0x7FFFFF (the inverse of `from_fractions`).
        """
        if not (math.isfinite(slave_cycle) and slave_cycle != 0):
            raise ValueError(f"slave_cycle {slave_cycle!r} not allowed: it must be a finite number != 0")
        words = []
        for k, s in enumerate(self.slave):
            value = s / slave_cycle
            if value == 1.0:
                words.append(_FRACTION_MAX)
                continue
            try:
                words.append(encode_fraction(value))
            except ValueError as exc:
                raise ValueError(f"point {k} (slave {s!r}): {exc}") from None
        return words

    @classmethod
    def from_csv(
        cls,
        path: str | os.PathLike[str],
        interpolation: Literal["linear"] = "linear",
        *,
        max_points: int = DEFAULT_MAX_POINTS,
    ) -> PointTable:
        """Load a ``master,slave`` CSV (see the module doc for what is rejected)."""
        master, slave = _read_points_csv(path, max_points)
        return cls(master, slave, interpolation, max_points=max_points)

    def eval(self, x: float) -> tuple[float, float, float, float]:
        if x >= self._m_last:  # exact end value: the cycle offset of an open curve must not drift
            return self._s_last, self._slope_last, 0.0, 0.0
        i = self.segment(x)
        k = self._slope[i]
        return self.slave[i] + k * (x - self.master[i]), k, 0.0, 0.0

    def set_point_acceleration(self, x: float) -> float:
        """d2s/dx2 of the set points, for a slave's acceleration set point: at each point the
        second difference over its k-th neighbours on either side, linear between points; the
        curve repeats across the cycle ends (an open curve with its slave travel per cycle).

        k = max(1, (N - 1) // 100), one per cent of the cycle either side: the linear
        interpolation puts the whole acceleration into impulses at the points, and a second
        difference of neighbouring points multiplies the set points' quantisation (COMPAX:
        2^-23 of S_T) by 1/h^2: over k points it shrinks by k^2 while a motion law's
        acceleration, smooth over many points, stays. `eval` keeps 0 inside the intervals
        (the exact interpolation)."""
        acc = self._point_acc
        if acc is None:
            acc = self._point_acc = self._second_differences()
        if x >= self._m_last:
            return acc[-1]
        i = self.segment(x)
        m = self.master
        w = (x - m[i]) / (m[i + 1] - m[i])
        return acc[i] + (acc[i + 1] - acc[i]) * w

    def eval_with_acceleration(self, x: float) -> tuple[float, float, float]:
        """(s, ds, d2s) at x in one interval search: `eval`'s s and ds and
        `set_point_acceleration`'s d2s, the same numbers (a cam follower's set point needs all
        three every cycle)."""
        acc = self._point_acc
        if acc is None:
            acc = self._point_acc = self._second_differences()
        if x >= self._m_last:
            return self._s_last, self._slope_last, acc[-1]
        m = self.master
        if self._inv_step:  # `segment` of an equidistant table, inline: this runs every cycle
            last = self._last_segment
            i = int(x * self._inv_step)
            if i < 0:
                i = 0
            elif i > last:
                i = last
            if x < m[i]:
                if i > 0:
                    i -= 1
            elif i < last and x >= m[i + 1]:
                i += 1
        else:
            i = self.segment(x)
        mi = m[i]
        k = self._slope[i]
        w = (x - mi) / (m[i + 1] - mi)
        return self.slave[i] + k * (x - mi), k, acc[i] + (acc[i + 1] - acc[i]) * w

    def _second_differences(self) -> list[float]:
        m, s = self.master, self.slave
        n = len(m)
        period, travel = m[-1], s[-1] - s[0]
        k = min(max(1, (n - 1) // 100), n - 1)

        def point(j: int) -> tuple[float, float]:
            # point j of the repeated curve: j < 0 the previous cycle, j > n - 1 the next
            if j < 0:
                return m[j + n - 1] - period, s[j + n - 1] - travel
            if j > n - 1:
                return m[j - n + 1] + period, s[j - n + 1] + travel
            return m[j], s[j]

        out = []
        for i in range(n):
            ml, sl = point(i - k)
            mr, sr = point(i + k)
            hl, hr = m[i] - ml, mr - m[i]
            out.append(2.0 * ((sr - s[i]) / hr - (s[i] - sl) / hl) / (hl + hr))
        return out

    def eval_array(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        x = np.asarray(x, dtype=float).ravel()
        idx = self._segments(x)
        m = np.asarray(self.master)
        slope = np.asarray(self._slope)[idx]
        s = np.asarray(self.slave)[idx] + slope * (x - m[idx])
        s = np.where(x >= self._m_last, self._s_last, s)
        zeros = np.zeros_like(x)
        return s, slope, zeros, zeros.copy()

    def __repr__(self) -> str:
        kind = "equidistant" if self.equidistant_step is not None else "general"
        return f"PointTable({len(self)} points, {kind}, master_period={self.master_period!r})"



# ---------------------------------------------------------------------------------------
# scaling


class ScaledCurve(CamCurve):
    """A curve with its master cycle stretched and its slave values scaled and shifted.

    s'(x) = slave_scale · s(x / master_scale) + slave_offset, so
    ds' = slave_scale · ds / master_scale, dds' = slave_scale · dds / master_scale², ...
    """

    def __init__(
        self,
        curve: CamCurve,
        master_scale: float = 1.0,
        slave_scale: float = 1.0,
        slave_offset: float = 0.0,
    ) -> None:
        if not (math.isfinite(master_scale) and master_scale > 0):
            raise ValueError(f"master_scale {master_scale!r} not allowed: it must be a finite number > 0")
        for name, value in (("slave_scale", slave_scale), ("slave_offset", slave_offset)):
            if not math.isfinite(value):
                raise ValueError(f"{name} {value!r} not allowed: it must be a finite number")
        self.curve = curve
        self.master_scale = float(master_scale)
        self.slave_scale = float(slave_scale)
        self.slave_offset = float(slave_offset)
        self.master_period = curve.master_period * self.master_scale
        self._inv = 1.0 / self.master_scale
        self._k1 = self.slave_scale * self._inv
        self._k2 = self._k1 * self._inv
        self._k3 = self._k2 * self._inv

    def eval(self, x: float) -> tuple[float, float, float, float]:
        # At the cycle end ask the inner curve for its own end exactly (x * (1/scale) may round
        # just below it), so an open curve's offset scales without drift.
        u = self.curve.master_period if x >= self.master_period else x * self._inv
        s, ds, dds, ddds = self.curve.eval(u)
        return self.slave_scale * s + self.slave_offset, self._k1 * ds, self._k2 * dds, self._k3 * ddds

    def eval_array(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        x = np.asarray(x, dtype=float).ravel()
        u = np.where(x >= self.master_period, self.curve.master_period, x * self._inv)
        s, ds, dds, ddds = self.curve.eval_array(u)
        return self.slave_scale * s + self.slave_offset, self._k1 * ds, self._k2 * dds, self._k3 * ddds

    def check_points(self) -> np.ndarray:
        inner = getattr(self.curve, "check_points", None)
        if inner is None:
            return np.zeros(0)
        return np.asarray(inner(), dtype=float) * self.master_scale

    def __repr__(self) -> str:
        return (
            f"ScaledCurve({self.curve!r}, master_scale={self.master_scale!r}, "
            f"slave_scale={self.slave_scale!r}, slave_offset={self.slave_offset!r})"
        )
