"""Cams built from motion-law segments (VDI 2143 style), in master and slave user units.

    from axisline.motion.segments import SegmentCam, segments_from_table
    cam = SegmentCam([(90.0, 0.0, "dwell"),
                      (180.0, 50.0, "cycloidal"),
                      (270.0, 50.0, "dwell"),
                      (360.0, 0.0, "modified_sine")], start=0.0)
    s, ds, dds, ddds = cam.eval(123.0)        # derivatives with respect to the master position

One master cycle runs from x = 0 to x = master_period; segment i runs from the previous
segment's master end (0 for the first) to its own, and moves the slave from the previous
slave end (`start` for the first) to its own. A segment's law is

* a motion-law name from `axisline.motion.laws.LAWS` ("cycloidal", "poly345", ...): the
  slave follows s0 + h * law(u) with u = (x - x0)/L, L the master length and h the stroke
  (h < 0 draws the same law as a return);
* "dwell": the slave rests (its slave end must equal its start);
* "constant_velocity": ds/dx = h/L throughout;
* "auto": a 5th-order transition whose boundary velocity and acceleration are taken from
  its neighbours, so the cam is C2 across it (where the neighbours' own laws allow).

Boundary matching of "auto" segments
------------------------------------
At a joint with a named law (or dwell) on one side, the "auto" side takes that law's
ds/dx and d2s/dx2 there (law end values scaled by h/L and h/L^2). At a joint between two
"auto" segments nothing fixes the velocity and acceleration, so they are chosen to make
the third and fourth derivatives continuous as well: a run of "auto" segments is then the
quintic spline through the given points, clamped by its neighbours (periodic if the whole
cam is "auto"). Velocity and acceleration are only continuous where the neighbouring laws
agree: a dwell next to a simple-harmonic rise keeps the law's acceleration step.

`periodic=True` (default): the cam runs cycle after cycle, closed (slave returns to the
start) or open (the slave advances by `cycle_offset` per cycle, COMPAX reset mode), so the
last segment's end joins the first segment's start and "auto" segments there match across
the wrap. `periodic=False`: a single pass; an "auto" segment at either end of the cycle
starts or ends at rest (ds/dx = d2s/dx2 = 0).
"""

from __future__ import annotations

import math
import numbers
from bisect import bisect_right
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any, Callable, Union

import numpy as np

from axisline.motion.curve import CamCurve
from axisline.motion.laws import LAW_NAMES, LAWS, PolyPiece, dwell, quintic_coefficients

__all__ = ["Segment", "SegmentCam", "segments_from_table", "SEGMENT_LAWS"]

#: law names a segment may use
SEGMENT_LAWS: tuple[str, ...] = (*LAW_NAMES, "dwell", "auto")

_FIELDS = ("master_end", "slave_end", "law")


@dataclass(frozen=True)
class Segment:
    """One cam segment: ends at master position `master_end` with the slave at `slave_end`."""

    master_end: float
    slave_end: float
    law: str


RowLike = Union[Segment, Mapping[str, Any], Sequence[Any]]


def _allowed_laws() -> str:
    return ", ".join(SEGMENT_LAWS)


def _number(i: int, field: str, value: Any) -> float:
    """A finite float from a number or numeric text (CSV cells arrive as text)."""
    if isinstance(value, bool):  # bool is an int subclass; True as a position is a mistake
        raise ValueError(f"segment {i}: {field} = {value!r} must be a finite number")
    try:
        x = float(value.strip() if isinstance(value, str) else value)
    except (TypeError, ValueError):
        raise ValueError(f"segment {i}: {field} = {value!r} must be a finite number") from None
    if not math.isfinite(x):
        raise ValueError(f"segment {i}: {field} = {value!r} must be a finite number")
    return x


def _law_name(i: int, value: Any) -> str:
    if not isinstance(value, str):
        raise ValueError(f"segment {i}: law = {value!r} must be one of: {_allowed_laws()}")
    name = value.strip().lower()
    if name not in SEGMENT_LAWS:
        raise ValueError(f"segment {i}: law = {value!r} is not known; allowed: {_allowed_laws()}")
    return name


def segments_from_table(rows: Iterable[RowLike]) -> list[Segment]:
    """Segments from table rows, e.g. parsed from a machine file or a CSV.

    A row is a `Segment`, a mapping with the keys "master_end", "slave_end", "law", or a
    sequence (master_end, slave_end, law). Numbers may be given as text. Raises ValueError
    naming the row (segment index), the field, the value and what is allowed.
    """
    out: list[Segment] = []
    for i, row in enumerate(rows):
        if isinstance(row, Segment):
            values: Sequence[Any] = (row.master_end, row.slave_end, row.law)
        elif isinstance(row, Mapping):
            unknown = sorted(str(k) for k in row if k not in _FIELDS)
            if unknown:
                raise ValueError(
                    f"segment {i}: unknown field(s) {', '.join(unknown)}; allowed: {', '.join(_FIELDS)}"
                )
            missing = [f for f in _FIELDS if f not in row]
            if missing:
                raise ValueError(f"segment {i}: missing field(s) {', '.join(missing)}; "
                                 f"each segment needs {', '.join(_FIELDS)}")
            values = (row["master_end"], row["slave_end"], row["law"])
        elif isinstance(row, Sequence) and not isinstance(row, str) and len(row) == 3:
            values = row
        else:
            raise ValueError(
                f"segment {i}: row = {row!r} must be a Segment, a mapping with {', '.join(_FIELDS)}, "
                "or a (master_end, slave_end, law) sequence"
            )
        out.append(Segment(_number(i, "master_end", values[0]), _number(i, "slave_end", values[1]),
                           _law_name(i, values[2])))
    return out


# boundary value of an "auto" segment: either a known number or the index of an unknown
_Known = tuple[str, float]


class SegmentCam(CamCurve):
    """A cam over one master cycle made of consecutive motion-law segments (see module doc).

    Parameters
    ----------
    segments: rows accepted by `segments_from_table` (Segment, mapping or 3-sequence).
    start: slave position at x = 0 (slave user units).
    master_period: length of the master cycle; defaults to the last segment's master end,
        and if given must equal it.
    periodic: whether the cycle repeats (boundary conditions wrap from the end to the start).
    """

    def __init__(self, segments: Iterable[RowLike], *, start: float = 0.0,
                 master_period: float | None = None, periodic: bool = True) -> None:
        segs = segments_from_table(segments)
        if not segs:
            raise ValueError("segments: a cam needs at least one segment")
        if isinstance(start, bool) or not (isinstance(start, numbers.Real) and math.isfinite(start)):
            raise ValueError(f"start = {start!r} must be a finite number (slave position at x = 0)")
        self.segments: tuple[Segment, ...] = tuple(segs)
        self.periodic = bool(periodic)
        self._validate(segs, float(start), master_period)
        self.master_period = segs[-1].master_end

        n = len(segs)
        x0 = [0.0] + [s.master_end for s in segs[:-1]]
        s0 = [float(start)] + [s.slave_end for s in segs[:-1]]
        lengths = [seg.master_end - a for seg, a in zip(segs, x0)]
        strokes = [seg.slave_end - b for seg, b in zip(segs, s0)]

        # real-unit (ds/dx, d2s/dx2) at the start and end of every named-law segment
        ends: list[tuple[float, float, float, float] | None] = []
        for seg, L, h in zip(segs, lengths, strokes):
            if seg.law == "auto":
                ends.append(None)
                continue
            if seg.law == "dwell":
                ends.append((0.0, 0.0, 0.0, 0.0))
                continue
            law = LAWS[seg.law]
            _, va, aa, _ = law.eval_scalar(0.0)
            _, vb, ab, _ = law.eval_scalar(1.0)
            ends.append((h / L * va, h / L**2 * aa, h / L * vb, h / L**2 * ab))

        auto_bc = self._match_auto(segs, lengths, strokes, ends)

        # per segment: start, 1/L, s0, scale of s, of ds, of dds, of ddds, and the shape
        self._x0 = x0
        self._inv_len = [1.0 / L for L in lengths]
        self._s0 = s0
        self._ks: list[float] = []
        self._k1: list[float] = []
        self._k2: list[float] = []
        self._k3: list[float] = []
        self._fs: list[Callable[[float], tuple[float, float, float, float]]] = []
        self._fa: list[Callable[[np.ndarray], tuple]] = []
        #: real-unit (ds/dx, d2s/dx2) at the start and end of each segment, as built
        self.boundary: tuple[tuple[float, float, float, float], ...]
        boundary = []
        for i, (seg, L, h) in enumerate(zip(segs, lengths, strokes)):
            if seg.law == "auto":
                V0, A0, V1, A1 = auto_bc[i]
                # slave-unit polynomial in u: the stroke may be 0 (a transition between equal
                # levels), so it is not normalised by h
                piece = PolyPiece(0.0, 1.0, quintic_coefficients(h, V0 * L, A0 * L * L, V1 * L, A1 * L * L))
                scale = 1.0
                self._fs.append(piece.at)
                self._fa.append(piece.at_array)
                boundary.append((V0, A0, V1, A1))
            else:
                law = dwell() if seg.law == "dwell" else LAWS[seg.law]
                scale = 0.0 if seg.law == "dwell" else h
                self._fs.append(law.eval_scalar)
                self._fa.append(law.eval)
                boundary.append(ends[i])
            self._ks.append(scale)
            self._k1.append(scale / L)
            self._k2.append(scale / L**2)
            self._k3.append(scale / L**3)
        self.boundary = tuple(boundary)
        self._n = n
        self._offset = segs[-1].slave_end - float(start)

    # ---------------------------------------------------------------------------------
    # construction helpers
    # ---------------------------------------------------------------------------------

    @staticmethod
    def _validate(segs: list[Segment], start: float, master_period: float | None) -> None:
        prev_x, prev_s = 0.0, start
        for i, seg in enumerate(segs):
            if not seg.master_end > prev_x:
                what = "0 (the cycle starts at x = 0)" if i == 0 else f"the previous master_end {prev_x!r}"
                raise ValueError(f"segment {i}: master_end = {seg.master_end!r} must be greater than {what}; "
                                 "master end positions must increase strictly")
            if seg.law == "dwell" and seg.slave_end != prev_s:
                raise ValueError(f"segment {i}: slave_end = {seg.slave_end!r} must equal the segment's start "
                                 f"{prev_s!r} for law 'dwell' (the slave rests)")
            prev_x, prev_s = seg.master_end, seg.slave_end
        if master_period is not None:
            if isinstance(master_period, bool) or not (isinstance(master_period, numbers.Real)
                                                         and math.isfinite(master_period) and master_period > 0):
                raise ValueError(f"master_period = {master_period!r} must be a finite number > 0")
            if segs[-1].master_end != float(master_period):
                raise ValueError(f"segment {len(segs) - 1}: master_end = {segs[-1].master_end!r} must equal "
                                 f"master_period = {master_period!r} (the last segment ends the cycle)")

    def _match_auto(self, segs: list[Segment], lengths: list[float], strokes: list[float],
                    ends: list[tuple[float, float, float, float] | None]) -> dict[int, tuple[float, ...]]:
        """Real-unit boundary (V0, A0, V1, A1) for every "auto" segment.

        Joint k is the start of segment k (joint 0 joins the last segment's end when periodic).
        A joint with a named law on either side takes that law's values; a joint between two
        "auto" segments gets unknowns (V, A) fixed by continuity of d3s/dx3 and d4s/dx4.
        """
        n = len(segs)
        auto = [seg.law == "auto" for seg in segs]
        if not any(auto):
            return {}

        # boundary values per joint and side; a value is ("k", number) or ("u", unknown index)
        n_unknown = 0
        joint_val: dict[int, tuple[_Known, _Known]] = {}
        unknown_joints: list[int] = []
        for k in range(n):
            right = k
            left = k - 1 if k > 0 else (n - 1 if self.periodic else None)
            if left is None:
                joint_val[k] = (("k", 0.0), ("k", 0.0))  # single pass: start at rest
            elif not auto[right]:
                va, aa = ends[right][0], ends[right][1]
                joint_val[k] = (("k", va), ("k", aa))
            elif not auto[left]:
                vb, ab = ends[left][2], ends[left][3]
                joint_val[k] = (("k", vb), ("k", ab))
            else:
                joint_val[k] = (("u", n_unknown), ("u", n_unknown + 1))
                n_unknown += 2
                unknown_joints.append(k)

        def start_bc(i: int) -> tuple[_Known, _Known]:
            return joint_val[i]

        def end_bc(i: int) -> tuple[_Known, _Known]:
            if i + 1 < n:
                return joint_val[i + 1]
            if self.periodic:
                return joint_val[0]
            return (("k", 0.0), ("k", 0.0))  # single pass: end at rest

        z = np.zeros(0)
        if n_unknown:
            z = self._solve_auto_joints(n, auto, lengths, strokes, unknown_joints, start_bc, end_bc, n_unknown)

        def value(b: _Known) -> float:
            return b[1] if b[0] == "k" else float(z[int(b[1])])

        out: dict[int, tuple[float, ...]] = {}
        for i in range(n):
            if auto[i]:
                (v0, a0), (v1, a1) = start_bc(i), end_bc(i)
                out[i] = (value(v0), value(a0), value(v1), value(a1))
        return out

    @staticmethod
    def _auto_affine(L: float, h: float) -> tuple[np.ndarray, np.ndarray]:
        """(const, G): the auto segment's (d3 start, d4 start, d3 end, d4 end) in real units
        is const + G @ (V0, A0, V1, A1); exact because the quintic is linear in its data."""

        def d34(h_: float, V0: float, A0: float, V1: float, A1: float) -> np.ndarray:
            c = quintic_coefficients(h_, V0 * L, A0 * L * L, V1 * L, A1 * L * L)
            c3, c4, c5 = c[3], c[4], c[5]
            return np.array([6.0 * c3 / L**3, 24.0 * c4 / L**4,
                             (6.0 * c3 + 24.0 * c4 + 60.0 * c5) / L**3, (24.0 * c4 + 120.0 * c5) / L**4])

        const = d34(h, 0.0, 0.0, 0.0, 0.0)
        G = np.empty((4, 4))
        for p in range(4):
            unit = [0.0, 0.0, 0.0, 0.0]
            unit[p] = 1.0
            G[:, p] = d34(0.0, *unit)
        return const, G

    def _solve_auto_joints(self, n: int, auto: list[bool], lengths: list[float], strokes: list[float],
                           unknown_joints: list[int], start_bc, end_bc, n_unknown: int) -> np.ndarray:
        M = np.zeros((n_unknown, n_unknown))
        rhs = np.zeros(n_unknown)
        affine = {i: self._auto_affine(lengths[i], strokes[i]) for i in range(n) if auto[i]}
        for row_pair, k in enumerate(unknown_joints):
            right = k
            left = k - 1 if k > 0 else n - 1
            # residual rows: d3 and d4 of the left segment's end minus those of the right's start
            for sign, seg, outs in ((1.0, left, (2, 3)), (-1.0, right, (0, 1))):
                const, G = affine[seg]
                params = (*start_bc(seg), *end_bc(seg))
                for r_off, out in enumerate(outs):
                    row = 2 * row_pair + r_off
                    rhs[row] -= sign * const[out]
                    for p, b in enumerate(params):
                        if b[0] == "u":
                            M[row, int(b[1])] += sign * G[out, p]
                        else:
                            rhs[row] -= sign * G[out, p] * b[1]
        # equilibrate: velocities and accelerations (and d3/d4 rows) differ by powers of L
        col = np.max(np.abs(M), axis=0)
        col[col == 0.0] = 1.0
        Ms = M / col
        row = np.max(np.abs(Ms), axis=1)
        row[row == 0.0] = 1.0
        try:
            y = np.linalg.solve(Ms / row[:, None], rhs / row)
        except np.linalg.LinAlgError:
            raise ValueError("segments: the 'auto' segments' boundary conditions cannot be matched "
                             "(singular system); give one of them a named law") from None
        return y / col

    # ---------------------------------------------------------------------------------
    # CamCurve
    # ---------------------------------------------------------------------------------

    def eval(self, x: float) -> tuple[float, float, float, float]:
        """(s, ds/dx, d2s/dx2, d3s/dx3) at master position x (0 <= x <= master_period).

        A bisect over the segment starts, then one closed form. At a joint the later segment
        is used; outside [0, master_period] the first/last segment is extended.
        """
        i = bisect_right(self._x0, x) - 1
        if i < 0:
            i = 0
        u = (x - self._x0[i]) * self._inv_len[i]
        s, v, a, j = self._fs[i](u)
        return (self._s0[i] + self._ks[i] * s, self._k1[i] * v, self._k2[i] * a, self._k3[i] * j)

    def eval_array(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        xx = np.asarray(x, dtype=float)
        idx = np.clip(np.searchsorted(self._x0, xx, side="right") - 1, 0, self._n - 1)
        out = [np.empty(xx.shape) for _ in range(4)]
        for i in np.unique(idx):
            i = int(i)
            mask = idx == i
            u = (xx[mask] - self._x0[i]) * self._inv_len[i]
            s, v, a, j = self._fa[i](u)
            out[0][mask] = self._s0[i] + self._ks[i] * np.asarray(s)
            out[1][mask] = self._k1[i] * np.asarray(v)
            out[2][mask] = self._k2[i] * np.asarray(a)
            out[3][mask] = self._k3[i] * np.asarray(j)
        return out[0], out[1], out[2], out[3]

    @property
    def cycle_offset(self) -> float:  # type: ignore[override]
        """Slave travel per master cycle, exact from the table (evaluating the last segment at
        its end can be off by rounding, which would make a closed cam look open)."""
        return self._offset

    @classmethod
    def from_table(cls, rows: Iterable[RowLike], **kwargs: Any) -> "SegmentCam":
        """Same as SegmentCam(rows, ...): rows as accepted by `segments_from_table`."""
        return cls(rows, **kwargs)

    def __repr__(self) -> str:
        laws = ", ".join(seg.law for seg in self.segments)
        return f"SegmentCam(master_period={self.master_period!r}, start={self.start!r}, [{laws}])"
