"""The time-optimal search for "trapezoid", "jerk" and "sin2" plans (the UDDU family).

In the frame where the move goes "up" (the other direction is mirrored), a
time-optimal profile has the form

    ramp a0 -> A1,  hold A1 (only at the acceleration limit),
    ramp A1 -> A2   (with a cruise at a = 0, |v| = v_max, inserted where a crosses 0),
    hold A2 (only at the deceleration limit),  ramp A2 -> 0

with A1 >= a0 and A2 <= 0 ("up-down-down-up" jerk signs). This is the family of
profiles Ruckig's time-optimal step 1 searches (see its ``Profile`` check), so the
durations agree. Given (A1, hold1) the velocity condition fixes A2 and hold2 in
closed form; the remaining position condition is one scalar equation in one free
parameter, which runs along a path: A1 from its lowest feasible value up to the
acceleration limit (no hold), then the hold at the limit up to v_max, then the
cruise (closed form). It is solved by bracketing on a grid and refining with the
Illinois method. A ramp's duration is k*|dA|/j, with k = 1 for a linear ramp,
pi/2 for sin² (same peak jerk), and 0 for the trapezoid (infinite jerk); the mean
acceleration over a ramp is (A+B)/2 for both shapes, so one velocity equation
serves all three shapes. The sin² shape splits the A1 -> A2 ramp at a = 0 into two
bells, as the WAGO 750-672 profile does.

Cost: the cruise candidate is closed form; each scan evaluates the end error (one
walk of the phases) at its two ends and walks into its grid of _GRID intervals only
where a root may be (Decisions 1): about 10 evaluations per plan on the random
moving-start set, 4 when nothing is left to find, against 18 for the whole grid. The
search state lives in typed fields of `UpSolver`, so the compiled search runs on
unboxed floats ("no value here" is NaN, not None, for the same reason), and the
winner is walked once more to write its segments straight into the profile.

Decisions
---------
1. (issue 18: "~20 evaluations of the root search per plan ... bracket the root
   better") Along a scan, write the end error as f = M + vf * T, with T the duration
   and M the end position carried on at vf to a common time after both ends. A
   larger A1 or a longer hold gives an acceleration at least as high at every instant
   up to the braking and more velocity to shed, so T and M never fall along the scan
   (for the starts plan() hands over: |a0| within both limits, a0 = 0 for sin² and
   the trapezoid; a sin² start at a0 < 0, which plan() first ramps to 0, lacks it).
   Between two evaluated points f therefore lies within [M_i + min(vf T), M_k +
   max(vf T)] (for vf >= 0 simply [f_i, f_k]); where that range excludes zero the
   points between them are neither zero nor a sign change, and the scan does not
   evaluate them. The grid is halved down to its _GRID intervals where it does not:
   the same grid points in the same order where a root is, so the same brackets and
   the same Illinois iterations. Plans stay bit-identical (440,000 random plans of
   the three shapes compared with the whole-grid search; every example's trace
   unchanged). With vf < 0 the error itself can turn (two roots in one scan seen in
   random requests): that is why the grid stays, and the bound uses M and T, not f.
   Tests: tests/motion/test_profiles_search.py (the pruned and the whole-grid search
   give the same candidates; M and T rise along every scan).
2. (issue 18, the same point) The two scans form one path that ends in the cruise
   profile with no cruise time: A1 up to the value that reaches v_max (or amax), then
   the hold up to v_max. Where the cruise candidate exists and vf >= 0, the error
   rises along that path (Decisions 1) to -(cruise length) at its end, so no scan can
   hold a root and neither is walked; the cruise must be longer than twice the zero
   tolerance of the grid, so that a root within rounding of the path's end is still
   found as before. Bit-identical as in 1 (same tests and comparisons).
"""

from __future__ import annotations

import math
from typing import Final

from axisline.motion.profile_segments import LINEAR, SIN2, SIN2_C, Segments

# base shape -> (ramp time factor k, position coefficient c, split ramps at a = 0)
BASE: Final[dict[str, tuple[float, float, bool]]] = {
    "trapezoid": (0.0, 1.0 / 6.0, False),
    "jerk": (1.0, 1.0 / 6.0, False),
    "sin2": (math.pi / 2.0, SIN2_C, True),
}


class Ramp:
    """Ramp law for one plan: duration factor k, position coefficient c, jerk j."""

    __slots__ = ("k", "c", "j", "split", "kind")
    k: float
    c: float
    j: float
    split: bool
    kind: int

    def __init__(self, base: str, j: float) -> None:
        self.k, self.c, self.split = BASE[base]
        self.kind = SIN2 if base == "sin2" else LINEAR
        self.j = math.inf if base == "trapezoid" else j

    def time(self, da: float) -> float:
        return 0.0 if self.k == 0.0 else self.k * abs(da) / self.j

    def dv(self, a_from: float, a_to: float) -> float:
        """Velocity gained over a ramp a_from -> a_to (any sign)."""
        return 0.0 if self.k == 0.0 else (a_from + a_to) / 2.0 * self.time(a_to - a_from)

    def linear(self) -> Ramp:
        """The linear ramp law with the same peak jerk."""
        if self.kind == LINEAR:
            return self
        return Ramp("jerk", self.j)


def fmax(a: float, b: float) -> float:
    """max(a, b) for two floats, the same result without the builtin's boxed call."""
    return b if b > a else a


def fmin(a: float, b: float) -> float:
    """min(a, b) for two floats, the same result without the builtin's boxed call."""
    return b if b < a else a


def ramp_dp(v: float, a: float, da: float, tau: float, c: float) -> float:
    return tau * (v + tau * (a / 2.0 + da * c))


class Cand:
    """One profile of the family: its free parameters and duration (a plain class: a
    dataclass's generated __init__ runs as interpreted code)."""

    a1: float
    t2: float
    t4: float
    a2: float
    t6: float
    duration: float

    def __init__(self, a1: float, t2: float, t4: float, a2: float, t6: float, duration: float) -> None:
        self.a1, self.t2, self.t4, self.a2, self.t6, self.duration = a1, t2, t4, a2, t6, duration


def down_part(r: Ramp, v: float, a1: float, vf: float, dmax: float, edge: bool = False) -> tuple[bool, float, float]:
    """From (v, a1) ramp down to A2 (>= -dmax), hold, ramp up to 0 at vf.

    Returns (found, a2, t6); not found when the velocity cannot be reached this way.
    `edge`: the caller stands on the boundary A2 = 0 of the feasible set (where the scans
    start), so a result just outside it is rounding, not infeasibility.
    """
    dv = vf - v
    if r.k == 0.0:  # trapezoid: only the hold at -dmax brakes
        if dv > 0.0:
            if not edge:
                return False, 0.0, 0.0
            dv = 0.0
        return True, -dmax, -dv / dmax
    h = r.j * dv / r.k
    s = a1 * a1 / 2.0 - h
    if s < 0.0:
        if not edge and s < -1e-12 * (a1 * a1 + abs(h)):
            return False, 0.0, 0.0
        s = 0.0
    a2 = -math.sqrt(s)
    if a2 > a1 + 1e-12 * (abs(a1) + 1.0):
        return False, 0.0, 0.0
    if a2 < -dmax:
        a2 = -dmax
        t6 = (dv - r.k * (a1 * a1 - 2.0 * dmax * dmax) / (2.0 * r.j)) / a2
        return True, a2, fmax(t6, 0.0)
    return True, fmin(a2, a1), 0.0


class Walk:
    """Where the UDDU walk writes its segments: `out`, mirrored by `sign` about p0.

    The search walks without one (only the end state counts); the winner is walked once
    more with one to write the profile.
    """

    out: Segments
    sign: float
    p0: float

    def __init__(self, out: Segments, sign: float, p0: float) -> None:
        self.out, self.sign, self.p0 = out, sign, p0

    def emit(self, kind: int, dur: float, p: float, v: float, a: float, x: float) -> None:
        sign = self.sign
        self.out.add(kind, dur, self.p0 + sign * p, sign * v, sign * a, sign * x)


def ramp_step(r: Ramp, p: float, v: float, a_from: float, a_to: float, w: Walk | None) -> tuple[float, float, float]:
    """One ramp of the UDDU walk: (p, v, duration) after it."""
    tau = r.time(a_to - a_from)
    if tau > 0.0:
        da = a_to - a_from
        if w is not None:
            if r.kind == SIN2:
                w.emit(SIN2, tau, p, v, a_from, da)
            else:
                w.emit(LINEAR, tau, p, v, a_from, math.copysign(r.j, da))
        p += ramp_dp(v, a_from, da, tau, r.c)
        v += (a_from + a_to) / 2.0 * tau
    return p, v, tau


def hold_step(p: float, v: float, a: float, dur: float, w: Walk | None) -> tuple[float, float, float]:
    if dur > 0.0:
        if w is not None:
            w.emit(LINEAR, dur, p, v, a, 0.0)
        p += dur * (v + dur * a / 2.0)
        v += a * dur
    return p, v, dur


def integrate(r: Ramp, v0: float, a0: float, a1: float, t2: float, t4: float, a2: float, t6: float,
              w: Walk | None = None) -> tuple[float, float, float]:
    """Walk the UDDU phases from p = 0; returns (p, v, duration); w: where segments go."""
    p, v, t = 0.0, v0, 0.0
    p, v, d = ramp_step(r, p, v, a0, a1, w)
    t += d
    p, v, d = hold_step(p, v, a1, t2, w)
    t += d
    if t4 > 0.0 or (r.split and a1 > 0.0 > a2):
        p, v, d = ramp_step(r, p, v, a1, 0.0, w)
        t += d
        p, v, d = hold_step(p, v, 0.0, t4, w)
        t += d
        p, v, d = ramp_step(r, p, v, 0.0, a2, w)
        t += d
    else:
        p, v, d = ramp_step(r, p, v, a1, a2, w)
        t += d
    p, v, d = hold_step(p, v, a2, t6, w)
    t += d
    p, v, d = ramp_step(r, p, v, a2, 0.0, w)
    t += d
    return p, v, t


def _rise(k: float, j: float, c: float, p: float, v: float, a_from: float, a_to: float) -> tuple[float, float, float]:
    """ramp_step without a Walk, on the ramp law's numbers: (p, v, duration) after it."""
    da = a_to - a_from
    tau = 0.0 if k == 0.0 else k * abs(da) / j
    if tau > 0.0:
        p += tau * (v + tau * (a_from / 2.0 + da * c))
        v += (a_from + a_to) / 2.0 * tau
    return p, v, tau


def walk_end(r: Ramp, v0: float, a0: float, a1: float, t2: float, a2: float, t6: float) -> tuple[float, float, float]:
    """integrate() with no cruise (t4 = 0) and no segments: the search's inner loop, the same
    arithmetic in the same order (tests/motion/test_profiles_search.py compares them)."""
    k, j, c = r.k, r.j, r.c
    p, v, t = _rise(k, j, c, 0.0, v0, a0, a1)
    if t2 > 0.0:
        p += t2 * (v + t2 * a1 / 2.0)
        v += a1 * t2
    t += t2
    if r.split and a1 > 0.0 > a2:
        p, v, d = _rise(k, j, c, p, v, a1, 0.0)
        t += d
        t += 0.0  # the empty cruise, as integrate() adds it
        p, v, d = _rise(k, j, c, p, v, 0.0, a2)
        t += d
    else:
        p, v, d = _rise(k, j, c, p, v, a1, a2)
        t += d
    if t6 > 0.0:
        p += t6 * (v + t6 * a2 / 2.0)
        v += a2 * t6
    t += t6
    p, v, d = _rise(k, j, c, p, v, a2, 0.0)
    return p, v, t + d


_GRID: Final = 4  # intervals per scan: a few points guard against an error that turns (vf < 0)


class UpSolver:
    """The UDDU candidates of one plan (up frame): the search state as typed fields and its
    steps as methods, so the compiled search runs on unboxed floats (no closures)."""

    r: Ramp
    v0: float
    a0: float
    dist: float
    vf: float
    vmax: float
    amax: float
    dmax: float
    k: float
    j: float
    vary_t2: bool  # the scan in progress: A1 = amax with t2 free, else A1 free with t2 = 0
    prune: bool  # skip grid intervals that no_root clears (False: walk every point)
    cruise_gap: float  # distance the cruise candidate covers at v_max (-1: no cruise)
    zero: float  # |end error| taken as a root on a grid point
    prev_x: float  # the scan's last visited grid point and its end error (NaN: none)
    prev_f: float
    tol: float  # end state error a candidate may have
    out: list[Cand]

    def __init__(self, r: Ramp, v0: float, a0: float, dist: float, vf: float, vmax: float, amax: float, dmax: float) -> None:
        self.r, self.v0, self.a0, self.dist, self.vf = r, v0, a0, dist, vf
        self.vmax, self.amax, self.dmax = vmax, amax, dmax
        self.k, self.j = r.k, r.j
        self.vary_t2 = False
        self.prune = True
        self.cruise_gap = -1.0
        self.prev_x, self.prev_f = 0.0, math.nan
        scale = fmax(fmax(fmax(1.0, abs(dist)), abs(v0)), abs(vf))
        # a root on a grid point within rounding (e.g. exactly at t2max when the start is one
        # ulp below v_max) has no sign change to bracket it: taken as found (`add` checks it)
        self.zero = 1e-12 * scale
        self.tol = 1e-9 * scale
        self.out = []

    def peak_v(self, a1: float, t2: float) -> float:
        # velocity where the acceleration crosses zero after (a1, t2); a1 >= 0
        r = self.r
        return self.v0 + r.dv(self.a0, a1) + a1 * t2 + r.dv(a1, 0.0)

    def a1_for_peak(self, v_peak: float) -> float:
        # A1 (no hold) whose zero crossing happens at v_peak:
        # v0 + k (A1^2 - a0^2)/(2j) + k A1^2/(2j) = v_peak
        a0 = self.a0
        return math.sqrt(fmax(self.j * (v_peak - self.v0) / self.k + a0 * a0 / 2.0, 0.0))

    def cruise(self) -> None:
        """Reach v_max with a = 0, cruise, brake to vf."""
        r, v0, a0, vmax, amax, k, j = self.r, self.v0, self.a0, self.vmax, self.amax, self.k, self.j
        v_stop = v0 + r.dv(a0, 0.0)
        if v_stop <= vmax * (1.0 + 1e-12):
            if k == 0.0:
                a1, t2 = amax, fmax((vmax - v0) / amax, 0.0)
            else:
                a1 = self.a1_for_peak(vmax)
                t2 = 0.0
                if a1 > amax:
                    a1 = amax
                    t2 = (vmax - v0 - k * (2.0 * amax * amax - a0 * a0) / (2.0 * j)) / amax
            if a1 < a0 and v_stop >= vmax - 1e-12 * vmax:
                a1 = a0  # already at the speed limit (within rounding): just let a fall to 0
            if a1 >= a0 - 1e-12 and t2 >= 0.0:
                found, a2, t6 = down_part(r, vmax, 0.0, self.vf, self.dmax)
                if found:
                    p, _, t = walk_end(r, v0, a0, a1, t2, a2, t6)
                    t4 = (self.dist - p) / vmax
                    if t4 >= 0.0:
                        self.out.append(Cand(a1, t2, t4, a2, t6, t + t4))
                        self.cruise_gap = t4 * vmax

    # -- no cruise: one free parameter, first A1 in [a0, amax], then hold1 at amax
    def end(self, x: float, edge: bool) -> tuple[float, float]:
        """(end position minus the target, duration) at the scan parameter x; the error is
        NaN where no profile has this x."""
        r = self.r
        a1 = self.amax if self.vary_t2 else x
        t2 = x if self.vary_t2 else 0.0
        found, a2, t6 = down_part(r, self.v0 + r.dv(self.a0, a1) + a1 * t2, a1, self.vf, self.dmax, edge)
        if not found:
            return math.nan, 0.0
        p, _, t = walk_end(r, self.v0, self.a0, a1, t2, a2, t6)
        return p - self.dist, t

    def f(self, x: float, edge: bool) -> float:
        return self.end(x, edge)[0]

    def make(self, x: float, edge: bool) -> None:
        if self.vary_t2:
            self.add(self.amax, x, edge)
        else:
            self.add(x, 0.0, edge)

    def scan(self, lo: float, hi: float, edge: bool) -> None:
        """Roots of f on [lo, hi] on a grid of _GRID intervals; edge: lo is the feasibility
        boundary A2 = 0.

        The grid points are visited in order (`visit`: a point within rounding of zero, or a
        sign change from the previous point, gives a candidate), but an interval between two
        evaluated points that `no_root` clears is not walked into (Decisions 1): its inner
        points would neither be zero nor change sign.
        """
        if not hi >= lo:
            return
        self.prev_x, self.prev_f = lo, math.nan
        if not hi > lo:
            self.visit(lo, self.f(lo, edge), edge)
            return
        x0 = lo + (hi - lo) * 0 / _GRID  # the grid's first point as written (-0.0 becomes 0.0)
        f_lo, t_lo = self.end(x0, edge)
        self.visit(x0, f_lo, edge)
        f_hi, t_hi = self.end(hi, False)
        self.between(lo, hi, 0, _GRID, f_lo, t_lo, f_hi, t_hi)
        self.visit(hi, f_hi, False)

    def between(self, lo: float, hi: float, i: int, k: int, f_i: float, t_i: float, f_k: float, t_k: float) -> None:
        """Visit the grid points strictly between points i and k (evaluated: f, t) in order."""
        if k - i < 2 or self.no_root(f_i, t_i, f_k, t_k):
            return
        m = (i + k) // 2
        x = lo + (hi - lo) * m / _GRID
        f_m, t_m = self.end(x, False)
        self.between(lo, hi, i, m, f_i, t_i, f_m, t_m)
        self.visit(x, f_m, False)
        self.between(lo, hi, m, k, f_m, t_m, f_k, t_k)

    def no_root(self, f_i: float, t_i: float, f_k: float, t_k: float) -> bool:
        """True when f stays beyond +-zero between two feasible points of the scan.

        f = M + vf * T, with the duration T and M (the end position carried on at vf to a
        common time after both ends) both rising along the scan (Decisions 1): between the
        points, f lies within [M_i + min(vf T), M_k + max(vf T)].
        """
        if not (self.prune and f_i == f_i and f_k == f_k):
            return False  # an end without a profile: the scan walks the grid there
        vf, zero = self.vf, self.zero
        if vf >= 0.0:
            return f_i > zero or f_k < -zero
        return f_k + vf * (t_i - t_k) < -zero or f_i + vf * (t_k - t_i) > zero

    def visit(self, x: float, fx: float, edge: bool) -> None:
        if fx != fx:  # no profile here
            self.prev_f = math.nan
            return
        prev_f = self.prev_f
        if abs(fx) <= self.zero:
            self.make(x, edge)
        elif prev_f == prev_f and (fx > 0.0) != (prev_f > 0.0):
            root = self.illinois(self.prev_x, x, prev_f, fx)
            if root == root:
                self.make(root, False)
        self.prev_x, self.prev_f = x, fx

    def illinois(self, lo: float, hi: float, flo: float, fhi: float) -> float:
        """Root of f in [lo, hi] with f(lo), f(hi) of opposite sign (modified regula falsi).

        NaN when f has no value somewhere inside (no profile there): the sign change of the
        two ends then spans a gap of infeasible parameters, not a root."""
        side = 0
        x = lo
        for _ in range(200):
            x = (lo * fhi - hi * flo) / (fhi - flo)
            if not lo <= x <= hi:
                x = 0.5 * (lo + hi)
            fx = self.f(x, False)
            if fx != fx:
                return math.nan
            if fx == 0.0 or hi - lo <= 4e-16 * fmax(fmax(abs(lo), abs(hi)), 1e-300):
                return x
            if (fx > 0.0) == (fhi > 0.0):
                hi, fhi = x, fx
                if side == 1:
                    flo /= 2.0
                side = 1
            else:
                lo, flo = x, fx
                if side == -1:
                    fhi /= 2.0
                side = -1
        return x

    def bounds(self, vary_t2: bool) -> tuple[bool, float, float, bool]:
        """(exists, lo, hi, edge) of a scan: A1 with no hold (vary_t2 False; not for the
        trapezoid, whose ramps take no time) or the hold at A1 = amax (vary_t2 True).

        The down part exists only while it has velocity left to shed (A2 <= 0); the
        scans start at that boundary (edge), or a root next to it would not be bracketed.
        """
        r, v0, a0, vf, vmax, amax, k, j = self.r, self.v0, self.a0, self.vf, self.vmax, self.amax, self.k, self.j
        if not vary_t2:
            if not k > 0.0:
                return False, 0.0, 0.0, False
            hi = amax
            if hi > 0.0 and self.peak_v(hi, 0.0) > vmax:
                hi = self.a1_for_peak(vmax)  # largest A1 whose zero-crossing velocity stays within v_max
            hi = fmin(hi, amax)
            rhs = a0 * a0 / 2.0 + j * (vf - v0) / k  # feasible (A2 <= 0): A1^2 >= rhs
            edge = rhs > 0.0 and math.sqrt(rhs) > a0
            lo = math.sqrt(rhs) if edge else a0
            return True, lo, hi, edge
        if not amax >= a0 - 1e-12:
            return False, 0.0, 0.0, False
        base = v0 + r.dv(a0, amax)
        t2max = (vmax - r.dv(amax, 0.0) - base) / amax
        lo = (vf - base - (k * amax * amax / (2.0 * j) if k else 0.0)) / amax
        edge = lo > 0.0
        lo = fmax(lo, 0.0)
        return True, lo, t2max, edge

    def add(self, a1: float, t2: float, edge: bool) -> None:
        r = self.r
        found, a2, t6 = down_part(r, self.v0 + r.dv(self.a0, a1) + a1 * t2, a1, self.vf, self.dmax, edge)
        if not found:
            return
        if a1 > 0.0 and self.peak_v(a1, t2) > self.vmax * (1.0 + 1e-9):
            return
        p, v, t = walk_end(r, self.v0, self.a0, a1, t2, a2, t6)
        tol = self.tol
        if abs(p - self.dist) <= tol and abs(v - self.vf) <= tol:
            self.out.append(Cand(a1, t2, 0.0, a2, t6, t))


def solve_up(r: Ramp, v0: float, a0: float, dist: float, vf: float, vmax: float, amax: float, dmax: float,
             prune: bool = True) -> list[Cand]:
    """All UDDU candidates (up frame) reaching (dist, vf, a=0) from (0, v0, a0).

    prune=False walks every grid point of every scan (the reference the pruning is tested
    against, tests/motion/test_profiles_search.py)."""
    sol = UpSolver(r, v0, a0, dist, vf, vmax, amax, dmax)
    sol.prune = prune
    sol.cruise()
    if prune and vf >= 0.0 and sol.cruise_gap > 2.0 * sol.zero:
        return sol.out  # the scans end where the cruise starts, short of the target (Decisions 2)
    found, lo, hi, edge = sol.bounds(False)
    if found:
        sol.vary_t2 = False
        sol.scan(lo, hi, edge)
    found, lo, hi, edge = sol.bounds(True)
    if found:
        sol.vary_t2 = True
        sol.scan(lo, hi, edge)
    return sol.out
