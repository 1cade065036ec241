"""Cam motion laws (VDI 2143 "Bewegungsgesetze für Kurvengetriebe") in normalised form.

A motion law maps the normalised master position u in [0, 1] to the normalised slave
stroke s(u); a rise goes from s(0) = 0 to s(1) = 1. Its derivatives with respect to u are
the normalised velocity v, acceleration a and jerk j:

    from axisline.motion.laws import LAWS, evaluate
    s, v, a, j = evaluate("cycloidal", u)          # u: float or numpy array
    LAWS["cycloidal"].cv, .ca, .cj                 # characteristic values max|v|, max|a|, max|j|

A cam segment of master length L and slave stroke h scales them as
ds/dx = h/L * v, d2s/dx2 = h/L^2 * a, d3s/dx3 = h/L^3 * j.

How the laws are built
----------------------
Each law is written from its definition as a few pieces on consecutive sub-intervals of
[0, 1]. The trigonometric laws (simple harmonic, cycloidal, modified sine, modified
trapezoid) are defined by the *shape of their acceleration*; the piece's acceleration is
p + q sin(w t) + r cos(w t) (t measured from the piece start), velocity and position
follow by exact integration, the integration constants come from continuity with the
previous piece, and the amplitude is fixed at the end by s(1) = 1. So nothing but the
shape is typed in: the textbook amplitudes (e.g. 8 pi / (pi + 2) = 4.888 for the modified
trapezoid) come out of the construction. The polynomial laws are written as coefficients.

The characteristic values cv, ca, cj are computed when a law is built: every piece is
sampled densely including its own end points (so one-sided limits at piece joints count)
and the best sample is refined by golden-section search. Where a law's textbook value is
infinite (an acceleration or jerk impulse at the ends when the law is joined to dwells),
the value is the maximum of the finite part inside the law; `.notes` says so.

General VDI 2143 segment types: `dwell()`, `rise(name)`, `return_(name)` and
`transition(v0, a0, v1, a1)` (the 5th-order polynomial for given boundary velocity and
acceleration) return objects with the same interface as the entries of `LAWS`.
"""

from __future__ import annotations

import math
from bisect import bisect_right
from typing import Callable, Sequence, Union

import numpy as np

__all__ = [
    "MotionLaw",
    "LAWS",
    "LAW_NAMES",
    "evaluate",
    "dwell",
    "rise",
    "return_",
    "transition",
    "quintic_coefficients",
]

ArrayLike = Union[float, np.ndarray]
Quad = tuple[ArrayLike, ArrayLike, ArrayLike, ArrayLike]

_TWO_PI = 2.0 * math.pi
_FOUR_PI = 4.0 * math.pi


# --------------------------------------------------------------------------------------
# pieces: closed forms on one sub-interval, in the local coordinate t = u - u0
# --------------------------------------------------------------------------------------


class PolyPiece:
    """s(t) = sum c[k] t^k on [u0, u1]."""

    __slots__ = ("u0", "u1", "c", "dc", "ddc", "dddc")

    def __init__(self, u0: float, u1: float, coeffs: Sequence[float]) -> None:
        self.u0 = float(u0)
        self.u1 = float(u1)
        c = [float(x) for x in coeffs] or [0.0]
        self.c = tuple(c)
        # derivative coefficients, prepared once so evaluation is plain Horner
        self.dc = tuple(k * c[k] for k in range(1, len(c))) or (0.0,)
        self.ddc = tuple(k * self.dc[k] for k in range(1, len(self.dc))) or (0.0,)
        self.dddc = tuple(k * self.ddc[k] for k in range(1, len(self.ddc))) or (0.0,)

    @staticmethod
    def _horner(c: tuple[float, ...], t):
        acc = c[-1]
        for ck in c[-2::-1]:
            acc = acc * t + ck
        return acc

    def at(self, t):
        """(s, v, a, j) at local t; works for floats and arrays alike."""
        h = self._horner
        return h(self.c, t), h(self.dc, t), h(self.ddc, t), h(self.dddc, t)

    def at_array(self, t: np.ndarray):
        s, v, a, j = self.at(t)
        # constant polynomials give scalars; broadcast so callers always get arrays
        return tuple(np.broadcast_to(np.asarray(x, dtype=float), t.shape) for x in (s, v, a, j))

    def scaled(self, k: float) -> "PolyPiece":
        return PolyPiece(self.u0, self.u1, [k * x for x in self.c])


class _TrigPiece:
    """Acceleration a(t) = p + q sin(w t) + r cos(w t) on [u0, u1], integrated exactly.

    v(t) = v0 + p t + q (1 - cos w t)/w + r sin(w t)/w
    s(t) = s0 + v0 t + p t^2/2 + q (t/w - sin(w t)/w^2) + r (1 - cos w t)/w^2
    j(t) = q w cos(w t) - r w sin(w t)
    """

    __slots__ = ("u0", "u1", "p", "q", "r", "w", "s0", "v0")

    def __init__(self, u0: float, u1: float, p: float, q: float, r: float, w: float,
                 s0: float = 0.0, v0: float = 0.0) -> None:
        self.u0, self.u1 = float(u0), float(u1)
        self.p, self.q, self.r = float(p), float(q), float(r)
        # w only matters when q or r is non-zero; keep it non-zero so the formulas stay finite
        self.w = float(w) if w != 0.0 else 1.0
        self.s0, self.v0 = float(s0), float(v0)

    def _at(self, t, sin: Callable, cos: Callable):
        p, q, r, w = self.p, self.q, self.r, self.w
        sw, cw = sin(w * t), cos(w * t)
        a = p + q * sw + r * cw
        v = self.v0 + p * t + q * (1.0 - cw) / w + r * sw / w
        s = self.s0 + self.v0 * t + 0.5 * p * t * t + q * (t / w - sw / (w * w)) + r * (1.0 - cw) / (w * w)
        j = q * w * cw - r * w * sw
        return s, v, a, j

    def at(self, t: float):
        return self._at(t, math.sin, math.cos)

    def at_array(self, t: np.ndarray):
        return self._at(t, np.sin, np.cos)

    def end(self) -> tuple[float, float]:
        """(s, v) at the piece's end: the next piece's integration constants."""
        s, v, _, _ = self.at(self.u1 - self.u0)
        return s, v

    def scaled(self, k: float) -> "_TrigPiece":
        return _TrigPiece(self.u0, self.u1, k * self.p, k * self.q, k * self.r, self.w,
                          k * self.s0, k * self.v0)


_Piece = Union[PolyPiece, _TrigPiece]


def _chain_trig(shapes: Sequence[tuple[float, float, float, float, float, float]],
                v_start: float = 0.0) -> list[_TrigPiece]:
    """Pieces from acceleration shapes (u0, u1, p, q, r, w), integrated continuously from
    s(0) = 0, v(0) = v_start, then scaled so that s(1) = 1 (this fixes the amplitude)."""
    pieces: list[_TrigPiece] = []
    s0, v0 = 0.0, v_start
    for u0, u1, p, q, r, w in shapes:
        piece = _TrigPiece(u0, u1, p, q, r, w, s0, v0)
        pieces.append(piece)
        s0, v0 = piece.end()
    k = 1.0 / s0
    return [piece.scaled(k) for piece in pieces]


# --------------------------------------------------------------------------------------
# the law object
# --------------------------------------------------------------------------------------

_GOLDEN = (math.sqrt(5.0) - 1.0) / 2.0


def _golden_max(f: Callable[[float], float], lo: float, hi: float, tol: float = 1e-13) -> tuple[float, float]:
    """(max f, argmax) of a unimodal f on [lo, hi] by golden-section search."""
    c = hi - _GOLDEN * (hi - lo)
    d = lo + _GOLDEN * (hi - lo)
    fc, fd = f(c), f(d)
    while hi - lo > tol:
        if fc >= fd:
            hi, d, fd = d, c, fc
            c = hi - _GOLDEN * (hi - lo)
            fc = f(c)
        else:
            lo, c, fc = c, d, fd
            d = lo + _GOLDEN * (hi - lo)
            fd = f(d)
    x = 0.5 * (lo + hi)
    return f(x), x


def _peak(piece: _Piece, k: int, samples: int = 1025) -> tuple[float, float]:
    """(max |k-th output| on the closed piece, where), sampling then refining the best sample."""
    length = piece.u1 - piece.u0
    t = np.linspace(0.0, length, samples)
    vals = np.abs(np.asarray(piece.at_array(t)[k], dtype=float))
    i = int(np.argmax(vals))
    best, where = float(vals[i]), float(t[i])
    lo, hi = t[max(i - 1, 0)], t[min(i + 1, samples - 1)]

    def f(tt: float) -> float:
        return abs(float(piece.at(tt)[k]))

    refined, at = _golden_max(f, float(lo), float(hi))
    if refined > best:
        best, where = refined, at
    return best, piece.u0 + where


class MotionLaw:
    """A normalised motion law on u in [0, 1] (see the module docstring).

    Attributes: name, notes, cv, ca, cj (max |v|, |a|, |j| over [0, 1], computed on
    construction) and u_cv, u_ca, u_cj (where they occur), s0/s1 (start and end value),
    joints (the internal piece boundaries, where the closed form changes).
    """

    __slots__ = ("name", "notes", "_pieces", "_starts", "cv", "ca", "cj", "u_cv", "u_ca", "u_cj",
                 "s0", "s1", "joints")

    def __init__(self, name: str, pieces: Sequence[_Piece], notes: str = "") -> None:
        if not pieces:
            raise ValueError(f"motion law {name!r}: needs at least one piece")
        self.name = name
        self.notes = notes
        self._pieces = tuple(pieces)
        self._starts = [p.u0 for p in self._pieces]
        self.joints = tuple(self._starts[1:])
        peaks = []
        for k in (1, 2, 3):
            best = max((_peak(p, k) for p in self._pieces), key=lambda bw: bw[0])
            peaks.append(best)
        (self.cv, self.u_cv), (self.ca, self.u_ca), (self.cj, self.u_cj) = peaks
        self.s0 = float(self.eval(0.0)[0])
        self.s1 = float(self.eval(1.0)[0])

    def __repr__(self) -> str:
        return f"MotionLaw({self.name!r}, cv={self.cv:.4g}, ca={self.ca:.4g}, cj={self.cj:.4g})"

    def eval_scalar(self, u: float) -> tuple[float, float, float, float]:
        """(s, v, a, j) at a float u (hot path: a bisect over at most a few pieces, math only).

        Outside [0, 1] the first/last piece is extended. At a joint the later piece is used.
        """
        pieces = self._pieces
        i = bisect_right(self._starts, u) - 1
        piece = pieces[i if i >= 0 else 0]
        return piece.at(u - piece.u0)

    def eval(self, u: ArrayLike) -> Quad:
        """(s, v, a, j) at u: floats for a float, arrays of u's shape for an array."""
        if np.ndim(u) == 0 and not isinstance(u, np.ndarray):
            s, v, a, j = self.eval_scalar(float(u))
            return float(s), float(v), float(a), float(j)
        uu = np.asarray(u, dtype=float)
        out = [np.empty(uu.shape) for _ in range(4)]
        if len(self._pieces) == 1:
            idx = np.zeros(uu.shape, dtype=np.intp)
        else:
            idx = np.clip(np.searchsorted(self._starts, uu, side="right") - 1, 0, len(self._pieces) - 1)
        for i, piece in enumerate(self._pieces):
            mask = idx == i
            if not mask.any():
                continue
            vals = piece.at_array(uu[mask] - piece.u0)
            for o, val in zip(out, vals):
                o[mask] = val
        return out[0], out[1], out[2], out[3]

    __call__ = eval


# --------------------------------------------------------------------------------------
# the standard laws
# --------------------------------------------------------------------------------------


def _constant_velocity() -> MotionLaw:
    return MotionLaw(
        "constant_velocity",
        [PolyPiece(0.0, 1.0, [0.0, 1.0])],
        notes=(
            "s = u. Joined to dwells the velocity steps 0 -> 1 at u = 0 and 1 -> 0 at u = 1, "
            "so the acceleration has (infinite) impulses at the ends; ca = cj = 0 are the "
            "maxima of the finite part inside (0, 1). Use it between 'auto' transitions."
        ),
    )


def _simple_harmonic() -> MotionLaw:
    # acceleration shape: a half cosine wave over the whole stroke
    pieces = _chain_trig([(0.0, 1.0, 0.0, 0.0, 1.0, math.pi)])
    return MotionLaw(
        "simple_harmonic",
        pieces,
        notes=(
            "s = (1 - cos(pi u))/2. The acceleration is +-pi^2/2 at u = 0 and u = 1, so joined "
            "to dwells it steps there and the jerk has (infinite) impulses at the ends; "
            "cj = pi^3/2 is the maximum of the finite jerk inside (0, 1)."
        ),
    )


def _cycloidal() -> MotionLaw:
    # acceleration shape: one full sine wave
    pieces = _chain_trig([(0.0, 1.0, 0.0, 1.0, 0.0, _TWO_PI)])
    return MotionLaw(
        "cycloidal",
        pieces,
        notes="s = u - sin(2 pi u)/(2 pi). C2 with rest at both ends (a = 0); jerk steps at the ends.",
    )


def _modified_sine() -> MotionLaw:
    # acceleration: quarter sine wave rising over 1/8, a sine arc of three times the period
    # over the middle 3/4 (peak -> 0 -> -peak), quarter wave back to 0 over the last 1/8
    w_short = _FOUR_PI  # quarter period = 1/8
    w_long = _FOUR_PI / 3.0  # half period = 3/4
    pieces = _chain_trig([
        (0.0, 0.125, 0.0, 1.0, 0.0, w_short),
        (0.125, 0.875, 0.0, 0.0, 1.0, w_long),
        (0.875, 1.0, 0.0, 0.0, -1.0, w_short),
    ])
    return MotionLaw(
        "modified_sine",
        pieces,
        notes=(
            "Sine acceleration segments over 1/8, 3/4, 1/8 of the stroke. C2 (jerk continuous "
            "inside, steps at the ends); ca = 4 pi^2/(4 + pi)."
        ),
    )


def _modified_trapezoid() -> MotionLaw:
    # acceleration: quarter sine up over 1/8, constant over 1/4, half cosine down through 0
    # over 1/4, constant negative over 1/4, quarter sine back to 0 over 1/8
    w = _FOUR_PI  # quarter period = 1/8
    pieces = _chain_trig([
        (0.0, 0.125, 0.0, 1.0, 0.0, w),
        (0.125, 0.375, 1.0, 0.0, 0.0, w),
        (0.375, 0.625, 0.0, 0.0, 1.0, w),
        (0.625, 0.875, -1.0, 0.0, 0.0, w),
        (0.875, 1.0, 0.0, 0.0, -1.0, w),
    ])
    return MotionLaw(
        "modified_trapezoid",
        pieces,
        notes=(
            "Acceleration of sine quarter-waves and constant parts over 1/8, 1/4, 1/4, 1/4, 1/8. "
            "C2 (jerk continuous inside, steps at the ends); ca = 8 pi/(pi + 2)."
        ),
    )


def _poly345() -> MotionLaw:
    return MotionLaw(
        "poly345",
        [PolyPiece(0.0, 1.0, [0.0, 0.0, 0.0, 10.0, -15.0, 6.0])],
        notes="s = 10u^3 - 15u^4 + 6u^5. C2 with rest at both ends; jerk steps (60) at the ends.",
    )


def _poly4567() -> MotionLaw:
    return MotionLaw(
        "poly4567",
        [PolyPiece(0.0, 1.0, [0.0, 0.0, 0.0, 0.0, 35.0, -84.0, 70.0, -20.0])],
        notes="s = 35u^4 - 84u^5 + 70u^6 - 20u^7. C3: jerk is zero at both ends.",
    )


LAWS: dict[str, MotionLaw] = {
    law.name: law
    for law in (
        _constant_velocity(),
        _simple_harmonic(),
        _cycloidal(),
        _modified_sine(),
        _modified_trapezoid(),
        _poly345(),
        _poly4567(),
    )
}

LAW_NAMES: tuple[str, ...] = tuple(LAWS)


def _law(name: str) -> MotionLaw:
    try:
        return LAWS[name]
    except (KeyError, TypeError):
        raise ValueError(f"unknown motion law {name!r}; allowed: {', '.join(LAW_NAMES)}") from None


def evaluate(name: str, u: ArrayLike) -> Quad:
    """(s, v, a, j) of the named law at u (float or numpy array); v, a, j are d/du, d2/du2, d3/du3."""
    return _law(name).eval(u)


# --------------------------------------------------------------------------------------
# general VDI 2143 segment types
# --------------------------------------------------------------------------------------

_DWELL = MotionLaw("dwell", [PolyPiece(0.0, 1.0, [0.0])], notes="s = 0: the slave rests.")


def dwell() -> MotionLaw:
    """Rest: s = 0 over the whole segment."""
    return _DWELL


def rise(law_name: str) -> MotionLaw:
    """The named law as a rise, s from 0 to 1."""
    return _law(law_name)


_RETURNS: dict[str, MotionLaw] = {}


def return_(law_name: str) -> MotionLaw:
    """The named law as a return, s from 1 to 0: s_return(u) = 1 - s_rise(u)."""
    base = _law(law_name)
    law = _RETURNS.get(law_name)
    if law is None:
        pieces: list[_Piece] = []
        for p in base._pieces:
            # negate everything, then add 1 to each piece's constant term (its value at t = 0)
            neg = p.scaled(-1.0)
            if isinstance(neg, PolyPiece):
                pieces.append(PolyPiece(neg.u0, neg.u1, [neg.c[0] + 1.0, *neg.c[1:]]))
            else:
                pieces.append(_TrigPiece(neg.u0, neg.u1, neg.p, neg.q, neg.r, neg.w, neg.s0 + 1.0, neg.v0))
        law = MotionLaw(f"return_{law_name}", pieces, notes=f"1 - {law_name}. " + base.notes)
        _RETURNS[law_name] = law
    return law


def quintic_coefficients(h: float, v0: float, a0: float, v1: float, a1: float) -> tuple[float, ...]:
    """Coefficients c0..c5 of p(t) = sum c_k t^k on t in [0, 1] with
    p(0) = 0, p'(0) = v0, p''(0) = a0, p(1) = h, p'(1) = v1, p''(1) = a1.

    With c0..c2 fixed by the start, the end conditions leave
        c3 + c4 + c5 = R0,  3c3 + 4c4 + 5c5 = R1,  6c3 + 12c4 + 20c5 = R2
    (R0 = h - v0 - a0/2, R1 = v1 - v0 - a0, R2 = a1 - a0), solved here in closed form.
    """
    r0 = h - v0 - 0.5 * a0
    r1 = v1 - v0 - a0
    r2 = a1 - a0
    c3 = 10.0 * r0 - 4.0 * r1 + 0.5 * r2
    c4 = -15.0 * r0 + 7.0 * r1 - r2
    c5 = 6.0 * r0 - 3.0 * r1 + 0.5 * r2
    return (0.0, float(v0), 0.5 * float(a0), c3, c4, c5)


def transition(v0: float, a0: float, v1: float, a1: float) -> MotionLaw:
    """The 5th-order polynomial with s(0) = 0, s(1) = 1 and normalised boundary velocity and
    acceleration v0, a0 (at u = 0) and v1, a1 (at u = 1).

    Normalised means derivatives with respect to u of the normalised stroke: for a segment of
    master length L and stroke h, v = ds/dx * L / h and a = d2s/dx2 * L^2 / h.
    transition(0, 0, 0, 0) is poly345.
    """
    vals = (v0, a0, v1, a1)
    for field, val in zip(("v0", "a0", "v1", "a1"), vals):
        if not math.isfinite(val):
            raise ValueError(f"transition: {field} = {val!r} must be a finite number")
    return MotionLaw(
        f"transition(v0={v0:g}, a0={a0:g}, v1={v1:g}, a1={a1:g})",
        [PolyPiece(0.0, 1.0, quintic_coefficients(1.0, v0, a0, v1, a1))],
        notes="5th-order polynomial meeting s, v, a at both ends (VDI 2143 general transition).",
    )
