"""Cam tables: point tables, cubic splines, scaled curves, and the cam editor's checks.

    from axisline.motion.cam import PointTable, SplineTable, ScaledCurve, check, plot_cam
    table = PointTable.equidistant([0.0, 10.0, 30.0, 60.0, 90.0, 100.0], master_period=360.0)
    s, ds, dds, ddds = table.eval(90.0)          # hot path: O(1), builds no containers
    report = check(table, master_speed=720.0, v_max=500.0)

Every table implements `axisline.motion.curve.CamCurve`: `eval(x)` over one master cycle
0 <= x <= master_period, `at(x)` for any master position (open curves add their slave
travel per cycle).

Point tables (`PointTable`)
---------------------------
Master positions strictly increasing, the first 0 and the last the master cycle. Between
points the slave moves linearly, so ds is constant per interval and the higher derivatives
are 0 inside the intervals (the velocity steps at a point; the curve's acceleration there
is an impulse this model does not report). At a point the derivatives are those of the
interval that starts there. Equidistant tables (COMPAX set points, compax.md §2.7.2
[DERIVED]: point k at k·M_T/(N−1)) find their interval in O(1) from int(x / step);
other tables bisect (O(log n)). An equidistant table is recognised whatever constructor
built it.

COMPAX set points are 24-bit fractions of the slave cycle (compax.md §6.2 item 3,
formula 14: Fx = Ix / 2²³, two's complement, sign bit then 2⁻¹ … 2⁻²³); `encode_fraction`
and `decode_fraction` convert, `PointTable.from_fractions` builds the curve. The largest
fraction 0x7FFFFF (0.99999988) stands for the full slave cycle (compax.md §2.7.2: "last set
point of open monotone curves must be 0.9999999 (= S_T)", §4 [DERIVED] "treat F=0x7FFFFF
as exactly 1.0"), so an open curve from 0 to 0x7FFFFF moves exactly S_T per cycle and
does not drift (§2.20).

Splines (`SplineTable`)
-----------------------
A cubic spline through the points, C2 (position, velocity and acceleration continuous),
evaluated from its piecewise polynomial with analytic derivatives. End conditions:

* ``periodic=True``: ds and dds at the cycle end equal those at the start, so the curve
  continues C2 into the next cycle. For a closed curve s wraps too; an open curve (last
  slave value != first) continues with its slave offset per cycle - the usual choice for a
  feed that repeats.
* ``periodic=False``: "natural" (dds = 0 at both ends) unless ``end_slopes=(ds0, ds1)``
  is given ("clamped": the slave gradients at the start and end are prescribed, e.g. 0 for
  a rest at both ends, or the neighbouring curve's gradient when curves are linked).
  Natural is the default because it needs no extra numbers and adds no acceleration at
  the ends.

Scaling (`ScaledCurve`)
-----------------------
``master_scale`` stretches the master cycle (the scaled curve covers master_scale × the
original cycle), ``slave_scale`` multiplies the slave values (COMPAX P36, "slave set point
= P36 · s_curve", compax.md §4 [DERIVED]), ``slave_offset`` is added. COMPAX P35 multiplies
the master *position* in the master channel (compax.md §1.3); the same curve seen through
P35 is ``ScaledCurve(curve, master_scale=1 / P35)`` for P35 > 0.

Checks and plots
----------------
`check` samples one master cycle at a constant master speed (plus the points where the
extremes of a table can lie), converts to time units with the rules of `curve.py`
(v = ds·vm, a = dds·vm² + ds·am, j = ddds·vm³ + 3·dds·vm·am) and compares with slave
limits; `plot_cam` draws position, velocity, acceleration and jerk to a PNG. A curve may
offer ``check_points() -> ndarray`` (master positions where its derivative extremes can
lie: knots, interior maxima of ds); `check` samples those too, so a table's extremes are
found exactly. Curves without it are checked on the grid alone.

CSV
---
``master,slave`` header, one point per line, numbers written with Python's shortest
round-trip repr so a save/load round trip is exact. Saving is atomic
(`axisline.kernel.atomic`). Reading rejects, with the line, the field, the value and what
is allowed: a wrong header, a row without exactly two fields, a value that is not a finite
number, a master position that does not increase, a first master position other than 0,
fewer than 2 points, more than ``max_points`` points.
"""

from __future__ import annotations

import csv
import math
import os
from bisect import bisect_right
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass
from typing import Any, Literal

import numpy as np

from axisline.kernel.atomic import atomic_open, atomic_write_text
from axisline.motion.curve import CamCurve

__all__ = [
    "DEFAULT_MAX_POINTS",
    "FRACTION_ONE",
    "CamCheck",
    "ModuloMaster",
    "PointTable",
    "ScaledCurve",
    "SplineTable",
    "check",
    "decode_fraction",
    "encode_fraction",
    "plot_cam",
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

    def __init__(self, period: float) -> None:
        if isinstance(period, bool) or not isinstance(period, (int, float)) or not (
            math.isfinite(period) and period > 0
        ):
            raise ValueError(f"master period {period!r} not allowed: it must be a finite number > 0")
        self.period = period

    def split(self, x: float) -> tuple[int, float]:
        period = self.period
        if isinstance(x, int) and isinstance(period, int):
            k, r = divmod(x, period)
            return k, r
        r = math.fmod(x, period) + 0.0  # + 0.0 turns -0.0 into 0.0
        if r < 0.0:
            r += period
            if r >= period:  # -tiny + period rounded up to period
                r = 0.0
        # x - r is within rounding of a multiple of the period; round() picks that multiple.
        return round((x - r) / period), r

    def position(self, x: float) -> float:
        """The position within the cycle, 0 <= r < period."""
        return self.split(x)[1]

    def __repr__(self) -> str:
        return f"ModuloMaster(period={self.period!r})"


# ---------------------------------------------------------------------------------------
# point validation and CSV


def _point_label(i: int, field: str) -> str:
    return f"point {i} ({field})"


def _validate_points(
    master: Sequence[float],
    slave: Sequence[float],
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
# cubic spline


def _solve_tridiagonal(lower: list[float], diag: list[float], upper: list[float], rhs: list[float]) -> list[float]:
    """Thomas algorithm; lower[0] and upper[-1] are ignored. Diagonally dominant systems only."""
    n = len(diag)
    c = [0.0] * n
    d = [0.0] * n
    c[0] = upper[0] / diag[0] if n > 1 else 0.0
    d[0] = rhs[0] / diag[0]
    for i in range(1, n):
        denom = diag[i] - lower[i] * c[i - 1]
        c[i] = upper[i] / denom if i < n - 1 else 0.0
        d[i] = (rhs[i] - lower[i] * d[i - 1]) / denom
    x = [0.0] * n
    x[-1] = d[-1]
    for i in range(n - 2, -1, -1):
        x[i] = d[i] - c[i] * x[i + 1]
    return x


def _solve_cyclic(lower: list[float], diag: list[float], upper: list[float], rhs: list[float]) -> list[float]:
    """Cyclic tridiagonal system: lower[0] is the top-right corner, upper[-1] the bottom-left.

    Small systems are assembled densely (the corners may coincide with the band); larger
    ones use the Sherman-Morrison correction of a plain tridiagonal solve, O(n).
    """
    n = len(diag)
    if n < 3:
        a = np.zeros((n, n))
        for i in range(n):
            a[i, i] += diag[i]
            a[i, (i - 1) % n] += lower[i]
            a[i, (i + 1) % n] += upper[i]
        return [float(v) for v in np.linalg.solve(a, np.asarray(rhs, dtype=float))]
    alpha = upper[-1]  # A[n-1, 0]
    beta = lower[0]  # A[0, n-1]
    gamma = -diag[0]
    d = list(diag)
    d[0] = diag[0] - gamma
    d[-1] = diag[-1] - alpha * beta / gamma
    y = _solve_tridiagonal(lower, d, upper, rhs)
    u = [0.0] * n
    u[0] = gamma
    u[-1] = alpha
    z = _solve_tridiagonal(lower, d, upper, u)
    # v = (1, 0, ..., 0, beta / gamma)
    vy = y[0] + beta / gamma * y[-1]
    vz = z[0] + beta / gamma * z[-1]
    factor = vy / (1.0 + vz)
    return [y[i] - factor * z[i] for i in range(n)]


class SplineTable(_KnotTable):
    """Cubic spline (C2) through the points; see the module doc for the end conditions."""

    def __init__(
        self,
        master: Sequence[float],
        slave: Sequence[float],
        periodic: bool,
        *,
        end_slopes: tuple[float, float] | None = None,
        max_points: int = DEFAULT_MAX_POINTS,
        equidistant: bool | None = None,
    ) -> None:
        self._set_knots(master, slave, max_points, equidistant)
        if periodic and end_slopes is not None:
            raise ValueError(
                "end_slopes apply to a non-periodic spline; a periodic one takes its end slopes from the wrap"
            )
        if end_slopes is not None:
            if len(end_slopes) != 2 or not all(math.isfinite(float(v)) for v in end_slopes):
                raise ValueError(f"end_slopes {end_slopes!r} not allowed: give two finite gradients (start, end)")
        self.periodic = bool(periodic)
        self.end_slopes = None if end_slopes is None else (float(end_slopes[0]), float(end_slopes[1]))
        second = self._second_derivatives()
        m, y = self.master, self.slave
        a, b, c, d = [], [], [], []
        for i in range(len(m) - 1):
            h = m[i + 1] - m[i]
            delta = (y[i + 1] - y[i]) / h
            a.append(y[i])
            b.append(delta - h * (2.0 * second[i] + second[i + 1]) / 6.0)
            c.append(second[i] / 2.0)
            d.append((second[i + 1] - second[i]) / (6.0 * h))
        self._a, self._b, self._c, self._d = tuple(a), tuple(b), tuple(c), tuple(d)
        h_last = m[-1] - m[-2]
        self._end = (
            y[-1],
            b[-1] + h_last * (2.0 * c[-1] + 3.0 * d[-1] * h_last),
            2.0 * c[-1] + 6.0 * d[-1] * h_last,
            6.0 * d[-1],
        )

    def _second_derivatives(self) -> list[float]:
        """dds at every knot (the spline's moments M_i)."""
        m, y = self.master, self.slave
        n = len(m)
        h = [m[i + 1] - m[i] for i in range(n - 1)]
        delta = [(y[i + 1] - y[i]) / h[i] for i in range(n - 1)]
        if self.periodic:
            k = n - 1  # unknowns M_0 .. M_{n-2}; M_{n-1} = M_0
            lower = [h[i - 1] for i in range(k)]  # h[-1] is the last interval: wraps
            diag = [2.0 * (h[i - 1] + h[i]) for i in range(k)]
            upper = [h[i] for i in range(k)]
            rhs = [6.0 * (delta[i] - delta[i - 1]) for i in range(k)]
            moments = _solve_cyclic(lower, diag, upper, rhs)
            return moments + [moments[0]]
        if n == 2 and self.end_slopes is None:
            return [0.0, 0.0]
        lower = [0.0] * n
        diag = [0.0] * n
        upper = [0.0] * n
        rhs = [0.0] * n
        for i in range(1, n - 1):
            lower[i] = h[i - 1]
            diag[i] = 2.0 * (h[i - 1] + h[i])
            upper[i] = h[i]
            rhs[i] = 6.0 * (delta[i] - delta[i - 1])
        if self.end_slopes is None:  # natural: M_0 = M_{n-1} = 0
            diag[0] = diag[-1] = 1.0
        else:  # clamped: s'(0) and s'(P) given
            ds0, ds1 = self.end_slopes
            diag[0], upper[0], rhs[0] = 2.0 * h[0], h[0], 6.0 * (delta[0] - ds0)
            lower[-1], diag[-1], rhs[-1] = h[-1], 2.0 * h[-1], 6.0 * (ds1 - delta[-1])
        return _solve_tridiagonal(lower, diag, upper, rhs)

    @classmethod
    def equidistant(
        cls,
        slave_values: Sequence[float],
        master_period: float,
        periodic: bool,
        *,
        end_slopes: tuple[float, float] | None = None,
        max_points: int = DEFAULT_MAX_POINTS,
    ) -> SplineTable:
        """Spline through equally spaced points (point k at k · master_period / (N − 1))."""
        master = cls._equidistant_master(len(slave_values), master_period)
        return cls(master, slave_values, periodic, end_slopes=end_slopes, max_points=max_points, equidistant=True)

    @classmethod
    def from_csv(
        cls,
        path: str | os.PathLike[str],
        periodic: bool,
        *,
        end_slopes: tuple[float, float] | None = None,
        max_points: int = DEFAULT_MAX_POINTS,
    ) -> SplineTable:
        master, slave = _read_points_csv(path, max_points)
        return cls(master, slave, periodic, end_slopes=end_slopes, max_points=max_points)

    def eval(self, x: float) -> tuple[float, float, float, float]:
        if x >= self._m_last:
            return self._end
        i = self.segment(x)
        t = x - self.master[i]
        b, c, d = self._b[i], self._c[i], self._d[i]
        return (
            self._a[i] + t * (b + t * (c + t * d)),
            b + t * (2.0 * c + 3.0 * d * t),
            2.0 * c + 6.0 * d * t,
            6.0 * d,
        )

    def eval_array(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        x = np.asarray(x, dtype=float).ravel()
        idx = self._segments(x)
        t = x - np.asarray(self.master)[idx]
        a = np.asarray(self._a)[idx]
        b = np.asarray(self._b)[idx]
        c = np.asarray(self._c)[idx]
        d = np.asarray(self._d)[idx]
        s = a + t * (b + t * (c + t * d))
        ds = b + t * (2.0 * c + 3.0 * d * t)
        dds = 2.0 * c + 6.0 * d * t
        ddds = 6.0 * d
        end = x >= self._m_last
        s = np.where(end, self._end[0], s)
        return s, ds, dds, ddds

    def check_points(self) -> np.ndarray:
        """Knots plus, per interval, where ds has its extreme (dds = 0 inside the interval)."""
        points = list(self.master)
        for i in range(len(self.master) - 1):
            c, d = self._c[i], self._d[i]
            if d != 0.0:
                t = -c / (3.0 * d)
                if 0.0 < t < self.master[i + 1] - self.master[i]:
                    points.append(self.master[i] + t)
        return np.asarray(points)

    def __repr__(self) -> str:
        kind = "periodic" if self.periodic else ("clamped" if self.end_slopes else "natural")
        return f"SplineTable({len(self)} points, {kind}, master_period={self.master_period!r})"


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


# ---------------------------------------------------------------------------------------
# cam editor check and plot


@dataclass(frozen=True, slots=True)
class CamCheck:
    """Slave motion over one master cycle at a constant master speed (time units).

    ``max_*`` are absolute values; ``*_at`` the master position (within the cycle) where
    they occur. ``*_exceeded`` is False when no limit was given. ``max_master_speed`` is the
    largest |master speed| up to which every given limit holds (at the same master
    acceleration); ``inf`` when no limit binds.
    """

    master_speed: float
    master_acceleration: float
    max_velocity: float
    max_velocity_at: float
    max_acceleration: float
    max_acceleration_at: float
    max_jerk: float
    max_jerk_at: float
    v_max: float | None
    a_max: float | None
    j_max: float | None
    velocity_exceeded: bool
    acceleration_exceeded: bool
    jerk_exceeded: bool
    max_master_speed: float

    @property
    def within_limits(self) -> bool:
        return not (self.velocity_exceeded or self.acceleration_exceeded or self.jerk_exceeded)


# A limit counts as exceeded only beyond this relative margin, so that running exactly at
# `max_master_speed` (computed in floating point) passes.
_LIMIT_MARGIN = 1e-9


def _check_limit(name: str, value: float | None) -> float | None:
    if value is None:
        return None
    value = float(value)
    if not (math.isfinite(value) and value > 0):
        raise ValueError(f"{name} {value!r} not allowed: a limit must be a finite number > 0 (or None)")
    return value


def _sample_positions(curve: CamCurve, n: int) -> np.ndarray:
    period = curve.master_period
    grid = np.linspace(0.0, period, n)
    extra = getattr(curve, "check_points", None)
    if extra is not None:
        points = np.asarray(extra(), dtype=float)
        points = points[(points >= 0.0) & (points <= period)]
        grid = np.concatenate([grid, points])
    return np.unique(grid)


def _first_speed_over_jerk(ddds: np.ndarray, dds: np.ndarray, am: float, j_max: float) -> float:
    """Smallest w > 0 with |ddds·w³ + 3·dds·am·w| = j_max over all samples (inf if none)."""
    p = ddds
    q = 3.0 * dds * am
    best = math.inf
    linear = (p == 0.0) & (q != 0.0)
    if np.any(linear):
        best = min(best, float(np.min(j_max / np.abs(q[linear]))))
    cubic = p != 0.0
    if not np.any(cubic):
        return best
    if am == 0.0:
        return min(best, float(np.min(np.cbrt(j_max / np.abs(p[cubic])))))
    pc, qc = p[cubic], q[cubic]
    roots = []
    for sign in (1.0, -1.0):
        # w³ + (q/p)·w − sign·j/p = 0 as a batch of companion matrices
        comp = np.zeros((pc.size, 3, 3))
        comp[:, 0, 1] = -qc / pc
        comp[:, 0, 2] = sign * j_max / pc
        comp[:, 1, 0] = 1.0
        comp[:, 2, 1] = 1.0
        roots.append(np.linalg.eigvals(comp))
    r = np.concatenate(roots, axis=1)
    real = np.abs(r.imag) <= 1e-9 * np.maximum(1.0, np.abs(r.real))
    positive = real & (r.real > 0.0)
    if np.any(positive):
        best = min(best, float(np.min(r.real[positive])))
    return best


def check(
    curve: CamCurve,
    master_speed: float,
    master_acceleration: float = 0.0,
    n: int = 2001,
    *,
    v_max: float | None = None,
    a_max: float | None = None,
    j_max: float | None = None,
) -> CamCheck:
    """What the slave does over one master cycle at ``master_speed`` (master units / s).

    Samples ``n`` equally spaced master positions plus the curve's ``check_points()`` (the
    knots of a table and, for a spline, the interior extremes of ds), so the extremes of a
    table are found exactly, and those of other curves to the sampling resolution.
    """
    vm = float(master_speed)
    am = float(master_acceleration)
    if not (math.isfinite(vm) and math.isfinite(am)):
        raise ValueError(f"master speed {master_speed!r} / acceleration {master_acceleration!r} must be finite")
    if n < 2:
        raise ValueError(f"n {n!r} not allowed: sample at least 2 master positions")
    v_lim = _check_limit("v_max", v_max)
    a_lim = _check_limit("a_max", a_max)
    j_lim = _check_limit("j_max", j_max)

    x = _sample_positions(curve, n)
    _, ds, dds, ddds = (np.asarray(arr, dtype=float) for arr in curve.eval_array(x))
    v = np.abs(ds * vm)
    a = np.abs(dds * vm * vm + ds * am)
    j = np.abs(ddds * vm**3 + 3.0 * dds * vm * am)
    iv, ia, ij = int(np.argmax(v)), int(np.argmax(a)), int(np.argmax(j))

    def exceeded(peak: float, limit: float | None) -> bool:
        return limit is not None and peak > limit * (1.0 + _LIMIT_MARGIN)

    speed = math.inf
    if v_lim is not None:
        peak = float(np.max(np.abs(ds)))
        if peak > 0.0:
            speed = min(speed, v_lim / peak)
    if a_lim is not None:
        base = ds * am
        if np.any(np.abs(base) > a_lim):
            speed = 0.0  # the master acceleration alone breaks the limit
        else:
            with np.errstate(divide="ignore", invalid="ignore"):
                w2 = np.where(dds > 0.0, (a_lim - base) / dds, np.where(dds < 0.0, (a_lim + base) / -dds, np.inf))
            speed = min(speed, float(np.sqrt(np.min(w2))))
    if j_lim is not None:
        speed = min(speed, _first_speed_over_jerk(ddds, dds, am, j_lim))

    return CamCheck(
        master_speed=vm,
        master_acceleration=am,
        max_velocity=float(v[iv]),
        max_velocity_at=float(x[iv]),
        max_acceleration=float(a[ia]),
        max_acceleration_at=float(x[ia]),
        max_jerk=float(j[ij]),
        max_jerk_at=float(x[ij]),
        v_max=v_lim,
        a_max=a_lim,
        j_max=j_lim,
        velocity_exceeded=exceeded(float(v[iv]), v_lim),
        acceleration_exceeded=exceeded(float(a[ia]), a_lim),
        jerk_exceeded=exceeded(float(j[ij]), j_lim),
        max_master_speed=speed,
    )


def plot_cam(
    curve: CamCurve,
    master_speed: float,
    path: str | os.PathLike[str],
    *,
    n: int = 1001,
    title: str | None = None,
    jerk: bool = True,
    limits: dict[str, float | None] | None = None,
    unit: str = "",
) -> list[tuple[str, float | None]]:
    """Slave position, velocity, acceleration (and jerk) over one master cycle, as a PNG.

    Velocity and the rest are in time units at the constant ``master_speed``; ``limits``
    (``v_max``, ``a_max``, ``j_max`` of the slave axis) are drawn as dashed lines at +-limit on
    their panels, ``unit`` (the slave's) labels the axes; returns the panels drawn as (label,
    limit). Drawn with
    matplotlib's Agg canvas directly (no pyplot, no global backend switch); the file is
    written atomically.
    """
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    vm = float(master_speed)
    x = _sample_positions(curve, n)
    s, ds, dds, ddds = (np.asarray(arr, dtype=float) for arr in curve.eval_array(x))
    u = unit or "units"
    lim = limits or {}
    rows: list[tuple[str, np.ndarray, float | None]] = [
        (f"slave position\n[{u}]", s, None),
        (f"slave velocity\n[{u}/s]", ds * vm, lim.get("v_max")),
        (f"slave acceleration\n[{u}/s²]", dds * vm * vm, lim.get("a_max")),
    ]
    if jerk:
        rows.append((f"slave jerk\n[{u}/s³]", ddds * vm**3, lim.get("j_max")))
    fig = Figure(figsize=(8.0, 2.2 * len(rows) + 0.6))
    FigureCanvasAgg(fig)
    axes = fig.subplots(len(rows), 1, sharex=True)
    for ax, (label, values, limit) in zip(np.atleast_1d(axes), rows):
        # step-like curves (a linear table's velocity) read best as drawn lines between samples
        ax.plot(x, values, linewidth=1.2)
        if limit is not None:  # the axis' limit, both signs: where the cam asks too much
            for sign in (1.0, -1.0):
                ax.axhline(sign * limit, color="tab:red", linestyle="--", linewidth=0.9,
                           label="axis limit" if sign > 0 else None)
            ax.legend(loc="upper right", fontsize=7)
        ax.set_ylabel(label)
        ax.grid(True, alpha=0.3)
    np.atleast_1d(axes)[-1].set_xlabel("master position")
    fig.suptitle(title or f"{curve!r} at master speed {vm:g}/s", fontsize=9)
    fig.tight_layout()
    with atomic_open(path, "wb") as file:
        fig.savefig(file, format="png", dpi=100)
    return [(label, limit) for label, _, limit in rows]

