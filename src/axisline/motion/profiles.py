"""Point-to-point and velocity profiles: input state + limits in, trajectory out.

    from axisline.motion.profiles import plan, State, Limits
    prof = plan("jerk", State(p=0.0, v=0.0, a=0.0), State(p=10.0, v=0.0),
                Limits(v=1.0, a=2.0, d=2.0, j=10.0))
    prof.duration, prof.sample(t) -> (p, v, a, j)

Every profile is a short list of segments. A segment is either a polynomial with
constant jerk or a sin² acceleration ramp; sampling finds the segment with a
bisection over at most ~10 start times and evaluates a closed form, so it is O(1)
and builds no containers.

How the plan is found (shapes "trapezoid", "jerk", "sin2")
------------------------------------------------------------
In the frame where the move goes "up" (the other direction is mirrored), a
time-optimal profile has the form

    ramp a0 -> A1,  hold A1 (only at the acceleration limit),
    ramp A1 -> A2   (with a cruise at a = 0, |v| = v_max, inserted where a crosses 0),
    hold A2 (only at the deceleration limit),  ramp A2 -> 0

with A1 >= a0 and A2 <= 0 ("up-down-down-up" jerk signs). This is the family of
profiles Ruckig's time-optimal step 1 searches (see its ``Profile`` check), so the
durations agree. Given (A1, hold1) the velocity condition fixes A2 and hold2 in
closed form; the remaining position condition is one scalar equation, solved by
bracketing on a grid and refining with the Illinois method. The fastest valid
candidate over both directions wins. A ramp's duration is k*|dA|/j, with k = 1
for a linear ramp, pi/2 for sin² (same peak jerk), and 0 for the trapezoid
(infinite jerk); the mean acceleration over a ramp is (A+B)/2 for both shapes, so
one velocity equation serves all three shapes.

The sin² shape splits the A1 -> A2 ramp at a = 0 into two bells, as the WAGO
750-672 profile does (ramp-up, drive phase, ramp-down as separate bells).

Limits.a bounds the ramp that drives toward the target (A1), Limits.d the one that
brakes into it (A2). With a == d this is the symmetric limit Ruckig uses.

WAGO time/path variants ("trapezoid/time", "jerk/time", "sin2/time", ".../path")
------------------------------------------------------------------------------
The ramp-up lasts Limits.up_time and the ramp-down Limits.down_time (or covers
up_path/down_path): ramp v0 -> vp, cruise, ramp vp -> vf, each ramp a single bell
(triangle for "jerk", sin² bell for "sin2", constant for "trapezoid"). See
docs/decisions.md (WAGO §2.7).

Start states outside the limits (|a0| above the limit, or a velocity that would
exceed v_max) first get a braking phase back inside the limits; from there the
plan is time-optimal. Ruckig brakes with a different heuristic, so such cases
need not match its duration.
"""

from __future__ import annotations

import math
from bisect import bisect_right
from dataclasses import dataclass
from typing import Callable

__all__ = ["State", "Limits", "Profile", "plan", "plan_velocity", "SHAPES"]

_SIN2_C = 0.25 - 1.0 / (math.pi * math.pi)  # position coefficient of a sin² ramp
_LINEAR, _SIN2 = 0, 1  # segment kinds

# base shape -> (ramp time factor k, position coefficient c, split ramps at a = 0)
_BASE = {
    "trapezoid": (0.0, 1.0 / 6.0, False),
    "jerk": (1.0, 1.0 / 6.0, False),
    "sin2": (math.pi / 2.0, _SIN2_C, True),
}
SHAPES = tuple(_BASE) + tuple(f"{b}/{v}" for v in ("time", "path") for b in _BASE)


@dataclass(frozen=True, slots=True)
class State:
    """Kinematic state: position, velocity, acceleration (user units, seconds)."""

    p: float = 0.0
    v: float = 0.0
    a: float = 0.0


@dataclass(frozen=True, slots=True)
class Limits:
    """Motion limits.

    v: maximum speed; a: acceleration; d: deceleration (None: same as a);
    j: jerk (shapes "jerk" and "sin2"; for sin² the peak jerk);
    ramp_time: alternative to j, time for the acceleration to rise from 0 to a
    (WAGO Acceleration_RampUp_Param with AccParam 0): j = a / ramp_time;
    up_time/down_time, up_path/down_path: the WAGO time/path variants.
    """

    v: float
    a: float
    d: float | None = None
    j: float | None = None
    ramp_time: float | None = None
    up_time: float | None = None
    down_time: float | None = None
    up_path: float | None = None
    down_path: float | None = None


class Profile:
    """A planned trajectory; sample(t) -> (p, v, a, j).

    Before t = 0 it holds the start state; from `duration` on it continues at the
    final velocity with a = 0 (a velocity profile keeps running, a position profile
    that ends at rest stays at its target).
    """

    __slots__ = ("duration", "start", "target", "shape", "_t0", "_p", "_v", "_a", "_j", "_tau", "_kind")

    def __init__(self, shape: str, start: State, target: State, segments: list[tuple]) -> None:
        self.shape = shape
        self.start = start
        self.target = target
        t = 0.0
        self._t0: list[float] = []
        self._p: list[float] = []
        self._v: list[float] = []
        self._a: list[float] = []
        self._j: list[float] = []
        self._tau: list[float] = []
        self._kind: list[int] = []
        for kind, dur, p, v, a, x in segments:
            if dur <= 0.0:
                continue
            if kind == _SIN2 and dur < 1e-9:
                # pi/dur would overflow the sin² closed form; over a nanosecond a linear
                # ramp with the same acceleration change is the same curve to rounding
                kind, x = _LINEAR, x / dur
            self._t0.append(t)
            self._p.append(p)
            self._v.append(v)
            self._a.append(a)
            self._j.append(x)
            self._tau.append(dur)
            self._kind.append(kind)
            t += dur
        self.duration = t

    @property
    def segments(self) -> int:
        return len(self._t0)

    def sample(self, t: float) -> tuple[float, float, float, float]:
        """State at time t (seconds from the start of the profile)."""
        if t >= self.duration:
            tg = self.target
            return (tg.p + tg.v * (t - self.duration), tg.v, 0.0, 0.0)
        if t <= 0.0:
            s = self.start
            return (s.p + s.v * t, s.v, s.a, 0.0) if t < 0.0 else (s.p, s.v, s.a, 0.0)
        i = bisect_right(self._t0, t) - 1
        dt = t - self._t0[i]
        p, v, a, x = self._p[i], self._v[i], self._a[i], self._j[i]
        if self._kind[i] == _LINEAR:
            return (
                p + dt * (v + dt * (a / 2.0 + dt * x / 6.0)),
                v + dt * (a + dt * x / 2.0),
                a + dt * x,
                x,
            )
        tau = self._tau[i]
        w = math.pi / tau
        sn, c = math.sin(w * dt), math.cos(w * dt)
        return (
            p + v * dt + a * dt * dt / 2.0 + x / 2.0 * (dt * dt / 2.0 + (c - 1.0) / (w * w)),
            v + a * dt + x / 2.0 * (dt - sn / w),
            a + x / 2.0 * (1.0 - c),
            x / 2.0 * w * sn,
        )

    def sample_many(self, ts):
        """Vectorised sampling for plots and reports (allocates; not for the cycle)."""
        import numpy as np

        out = np.empty((len(ts), 4))
        for k, t in enumerate(ts):
            out[k] = self.sample(float(t))
        return out

    def __repr__(self) -> str:
        return f"Profile({self.shape!r}, duration={self.duration:.6g}, segments={self.segments})"


# ---------------------------------------------------------------- validation


def _finite(name: str, x: float) -> float:
    if not isinstance(x, (int, float)) or isinstance(x, bool) or not math.isfinite(x):
        raise ValueError(f"{name} must be a finite number, got {x!r}")
    return float(x)


def _positive(name: str, x: float | None, why: str = "") -> float:
    if x is None:
        raise ValueError(f"{name} is required{why}")
    x = _finite(name, x)
    if x <= 0.0:
        raise ValueError(f"{name} must be > 0{why}, got {x!r}")
    return x


def _check_state(name: str, s: State) -> None:
    _finite(f"{name}.p", s.p)
    _finite(f"{name}.v", s.v)
    _finite(f"{name}.a", s.a)


class _Ramp:
    """Ramp law for one plan: duration factor k, position coefficient c, jerk j."""

    __slots__ = ("k", "c", "j", "split", "kind")
    k: float
    c: float
    j: float
    split: bool
    kind: int

    def __init__(self, base: str, limits: Limits | None, amax: float) -> None:
        self.k, self.c, self.split = _BASE[base]
        self.kind = _SIN2 if base == "sin2" else _LINEAR
        if limits is None:  # a copy whose j the caller sets (see linear())
            return
        if base == "trapezoid":
            self.j = math.inf
        elif limits.j is not None:
            self.j = _positive("Limits.j", limits.j)
        elif limits.ramp_time is not None:
            self.j = amax / _positive("Limits.ramp_time", limits.ramp_time)
        else:
            raise ValueError(f"Limits.j (or Limits.ramp_time) is required for shape {base!r}")

    def time(self, da: float) -> float:
        return 0.0 if self.k == 0.0 else self.k * abs(da) / self.j

    def dv(self, a_from: float, a_to: float) -> float:
        """Velocity gained over a ramp a_from -> a_to (any sign)."""
        return 0.0 if self.k == 0.0 else (a_from + a_to) / 2.0 * self.time(a_to - a_from)

    def linear(self) -> "_Ramp":
        """The linear ramp law with the same peak jerk."""
        if self.kind == _LINEAR:
            return self
        r = _Ramp("jerk", None, 0.0)
        r.j = self.j
        return r


def _ramp_dp(v: float, a: float, da: float, tau: float, c: float) -> float:
    return tau * (v + tau * (a / 2.0 + da * c))


# ---------------------------------------------------------------- UDDU family


@dataclass(slots=True)
class _Cand:
    a1: float
    t2: float
    t4: float
    a2: float
    t6: float
    duration: float


def _down_part(r: _Ramp, v: float, a1: float, vf: float, dmax: float, edge: bool = False):
    """From (v, a1) ramp down to A2 (>= -dmax), hold, ramp up to 0 at vf.

    Returns (a2, t6) or None when the velocity cannot be reached this way. `edge`: the
    caller stands on the boundary A2 = 0 of the feasible set (where the scans start), so
    a result just outside it is rounding, not infeasibility.
    """
    dv = vf - v
    if r.k == 0.0:  # trapezoid: only the hold at -dmax brakes
        if dv > 0.0:
            if not edge:
                return None
            dv = 0.0
        return -dmax, -dv / dmax
    h = r.j * dv / r.k
    s = a1 * a1 / 2.0 - h
    if s < 0.0:
        if not edge and s < -1e-12 * (a1 * a1 + abs(h)):
            return None
        s = 0.0
    a2 = -math.sqrt(s)
    if a2 > a1 + 1e-12 * (abs(a1) + 1.0):
        return None
    if a2 < -dmax:
        a2 = -dmax
        t6 = (dv - r.k * (a1 * a1 - 2.0 * dmax * dmax) / (2.0 * r.j)) / a2
        return a2, max(t6, 0.0)
    return min(a2, a1), 0.0


def _ramp_step(r: _Ramp, p: float, v: float, a_from: float, a_to: float, emit: Callable | None) -> tuple[float, float, float]:
    """One ramp of the UDDU walk: (p, v, duration) after it (module level and typed: the walk
    runs ~20 times per plan, and a closure's boxed floats cost more than its arithmetic)."""
    tau = r.time(a_to - a_from)
    if tau > 0.0:
        da = a_to - a_from
        if emit is not None:
            if r.kind == _SIN2:
                emit(_SIN2, tau, p, v, a_from, da)
            else:
                emit(_LINEAR, tau, p, v, a_from, math.copysign(r.j, da))
        p += _ramp_dp(v, a_from, da, tau, r.c)
        v += (a_from + a_to) / 2.0 * tau
    return p, v, tau


def _hold_step(p: float, v: float, a: float, dur: float, emit: Callable | None) -> tuple[float, float, float]:
    if dur > 0.0:
        if emit is not None:
            emit(_LINEAR, dur, p, v, a, 0.0)
        p += dur * (v + dur * a / 2.0)
        v += a * dur
    return p, v, dur


def _integrate(r: _Ramp, v0: float, a0: float, a1: float, t2: float, t4: float, a2: float, t6: float,
               emit: Callable | None = None) -> tuple[float, float, float]:
    """Walk the UDDU phases from p = 0; returns (p, v, duration). emit(kind, dur, p, v, a, x)."""
    p, v, t = 0.0, v0, 0.0
    p, v, d = _ramp_step(r, p, v, a0, a1, emit)
    t += d
    p, v, d = _hold_step(p, v, a1, t2, emit)
    t += d
    if t4 > 0.0 or (r.split and a1 > 0.0 > a2):
        p, v, d = _ramp_step(r, p, v, a1, 0.0, emit)
        t += d
        p, v, d = _hold_step(p, v, 0.0, t4, emit)
        t += d
        p, v, d = _ramp_step(r, p, v, 0.0, a2, emit)
        t += d
    else:
        p, v, d = _ramp_step(r, p, v, a1, a2, emit)
        t += d
    p, v, d = _hold_step(p, v, a2, t6, emit)
    t += d
    p, v, d = _ramp_step(r, p, v, a2, 0.0, emit)
    t += d
    return p, v, t


def _illinois(f: Callable[[float], float | None], lo: float, hi: float, flo: float, fhi: float) -> float | None:
    """Root of f in [lo, hi] with f(lo), f(hi) of opposite sign (modified regula falsi).

    None when f has no value somewhere inside (no profile there): the sign change of the two
    ends then spans a gap of infeasible parameters, not a root."""
    side = 0
    x = lo
    for _ in range(200):
        x = (lo * fhi - hi * flo) / (fhi - flo)
        if not lo <= x <= hi:
            x = 0.5 * (lo + hi)
        fx = f(x)
        if fx is None:
            return None
        if fx == 0.0 or hi - lo <= 4e-16 * max(abs(lo), abs(hi), 1e-300):
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


_GRID = 4  # p_end is monotonic on each interval in every case tried; a few points guard the rest


class _UpSolver:
    """The UDDU candidates of one plan (up frame): the search state as typed fields and its
    steps as methods, so the compiled search runs on unboxed floats (no closures)."""

    r: _Ramp
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
    out: list[_Cand]

    def __init__(self, r: _Ramp, v0: float, a0: float, dist: float, vf: float, vmax: float, amax: float, dmax: float) -> None:
        self.r, self.v0, self.a0, self.dist, self.vf = r, v0, a0, dist, vf
        self.vmax, self.amax, self.dmax = vmax, amax, dmax
        self.k, self.j = r.k, r.j
        self.vary_t2 = False
        self.out = []

    def peak_v(self, a1: float, t2: float) -> float:
        # velocity where the acceleration crosses zero after (a1, t2); a1 >= 0
        r = self.r
        return self.v0 + r.dv(self.a0, a1) + a1 * t2 + r.dv(a1, 0.0)

    def a1_for_peak(self, v_peak: float) -> float:
        # A1 (no hold) whose zero crossing happens at v_peak:
        # v0 + k (A1^2 - a0^2)/(2j) + k A1^2/(2j) = v_peak
        a0 = self.a0
        return math.sqrt(max(self.j * (v_peak - self.v0) / self.k + a0 * a0 / 2.0, 0.0))

    def cruise(self) -> None:
        """Reach v_max with a = 0, cruise, brake to vf."""
        r, v0, a0, vmax, amax, k, j = self.r, self.v0, self.a0, self.vmax, self.amax, self.k, self.j
        v_stop = v0 + r.dv(a0, 0.0)
        if v_stop <= vmax * (1.0 + 1e-12):
            if k == 0.0:
                a1, t2 = amax, max((vmax - v0) / amax, 0.0)
            else:
                a1 = self.a1_for_peak(vmax)
                t2 = 0.0
                if a1 > amax:
                    a1 = amax
                    t2 = (vmax - v0 - k * (2.0 * amax * amax - a0 * a0) / (2.0 * j)) / amax
            if a1 < a0 and v_stop >= vmax - 1e-12 * vmax:
                a1 = a0  # already at the speed limit (within rounding): just let a fall to 0
            if a1 >= a0 - 1e-12 and t2 >= 0.0:
                dn = _down_part(r, vmax, 0.0, self.vf, self.dmax)
                if dn is not None:
                    a2, t6 = dn
                    p, _, t = _integrate(r, v0, a0, a1, t2, 0.0, a2, t6)
                    t4 = (self.dist - p) / vmax
                    if t4 >= 0.0:
                        self.out.append(_Cand(a1, t2, t4, a2, t6, t + t4))

    # -- no cruise: one free parameter, first A1 in [a0, amax], then hold1 at amax
    def end_error(self, a1: float, t2: float, edge: bool = False) -> float | None:
        r = self.r
        dn = _down_part(r, self.v0 + r.dv(self.a0, a1) + a1 * t2, a1, self.vf, self.dmax, edge)
        if dn is None:
            return None
        p, _, _ = _integrate(r, self.v0, self.a0, a1, t2, 0.0, dn[0], dn[1])
        return p - self.dist

    def f(self, x: float, edge: bool) -> float | None:
        return self.end_error(self.amax, x, edge) if self.vary_t2 else self.end_error(x, 0.0, edge)

    def f_root(self, x: float) -> float | None:
        return self.f(x, False)

    def make(self, x: float, edge: bool) -> None:
        if self.vary_t2:
            self.add(self.amax, x, edge)
        else:
            self.add(x, 0.0, edge)

    def scan(self, lo: float, hi: float, edge: bool) -> None:
        """Roots of f on [lo, hi]; edge: lo is the feasibility boundary A2 = 0."""
        if not hi >= lo:
            return
        n = _GRID if hi > lo else 0
        xs = [lo + (hi - lo) * i / n for i in range(n)] + [hi] if n else [lo]
        prev_x: float | None = None
        prev_f: float | None = None
        # a root on a grid point within rounding (e.g. exactly at t2max when the start is one
        # ulp below v_max) has no sign change to bracket it: taken as found (`add` checks it)
        zero = 1e-12 * max(1.0, abs(self.dist), abs(self.v0), abs(self.vf))
        for i, x in enumerate(xs):
            at_edge = edge and i == 0
            fx = self.f(x, at_edge)
            if fx is None:
                prev_x = prev_f = None
                continue
            if abs(fx) <= zero:
                self.make(x, at_edge)
            elif prev_f is not None and prev_x is not None and (fx > 0.0) != (prev_f > 0.0):
                root = _illinois(self.f_root, prev_x, x, prev_f, fx)
                if root is not None:
                    self.make(root, False)
            prev_x, prev_f = x, fx

    def add(self, a1: float, t2: float, edge: bool) -> None:
        r = self.r
        dn = _down_part(r, self.v0 + r.dv(self.a0, a1) + a1 * t2, a1, self.vf, self.dmax, edge)
        if dn is None:
            return
        a2, t6 = dn
        if a1 > 0.0 and self.peak_v(a1, t2) > self.vmax * (1.0 + 1e-9):
            return
        p, v, t = _integrate(r, self.v0, self.a0, a1, t2, 0.0, a2, t6)
        tol = 1e-9 * max(1.0, abs(self.dist), abs(self.v0), abs(self.vf))
        if abs(p - self.dist) <= tol and abs(v - self.vf) <= tol:
            self.out.append(_Cand(a1, t2, 0.0, a2, t6, t))


def _solve_up(r: _Ramp, v0: float, a0: float, dist: float, vf: float, vmax: float, amax: float, dmax: float) -> list[_Cand]:
    """All UDDU candidates (up frame) reaching (dist, vf, a=0) from (0, v0, a0)."""
    sol = _UpSolver(r, v0, a0, dist, vf, vmax, amax, dmax)
    k, j = r.k, r.j
    sol.cruise()
    # The down part exists only while it has velocity left to shed (A2 <= 0); the
    # scans start at that boundary, or a root next to it would not be bracketed.
    if k > 0.0:
        hi = amax
        if hi > 0.0 and sol.peak_v(hi, 0.0) > vmax:
            hi = sol.a1_for_peak(vmax)  # largest A1 whose zero-crossing velocity stays within v_max
        hi = min(hi, amax)
        rhs = a0 * a0 / 2.0 + j * (vf - v0) / k  # feasible (A2 <= 0): A1^2 >= rhs
        edge = rhs > 0.0 and math.sqrt(rhs) > a0
        lo = math.sqrt(rhs) if edge else a0
        sol.vary_t2 = False
        sol.scan(lo, hi, edge)
    if amax >= a0 - 1e-12:
        base = v0 + r.dv(a0, amax)
        t2max = (vmax - r.dv(amax, 0.0) - base) / amax
        lo = (vf - base - (k * amax * amax / (2.0 * j) if k else 0.0)) / amax
        edge = lo > 0.0
        lo = max(lo, 0.0)
        sol.vary_t2 = True
        sol.scan(lo, t2max, edge)
    return sol.out


def _emit_collect(sign: float, p0: float, segs: list):
    def emit(kind, dur, p, v, a, x):
        segs.append((kind, dur, p0 + sign * p, sign * v, sign * a, sign * x))

    return emit


# ---------------------------------------------------------------- braking into the limits


def _brake(r: _Ramp, start: State, vmax: float, alim: float, segs: list) -> State:
    """Bring a start state that violates the limits back inside them (appends segments).

    Order: acceleration to its limit, then (sin² only) acceleration to 0, then speed to v_max.
    """
    p, v, a = start.p, start.v, start.a
    if abs(a) > alim:
        tgt = math.copysign(alim, a)
        r0 = r.linear()
        tau = r0.time(tgt - a)
        if tau > 0.0:
            segs.append((_LINEAR, tau, p, v, a, math.copysign(r0.j, tgt - a)))
            p += _ramp_dp(v, a, tgt - a, tau, r0.c)
            v += (a + tgt) / 2.0 * tau
        a = tgt
    settled = _settle_acceleration(r, State(p, v, a), segs)
    p, v, a = settled.p, settled.v, settled.a
    v_stop = v + r.dv(a, 0.0)
    if abs(v_stop) > vmax or abs(v) > vmax:
        target_v = math.copysign(vmax, v_stop if abs(v_stop) > vmax else v)
        sub = _velocity_segments(r, State(p, v, a), target_v, alim, alim)
        segs.extend(sub)
        end = _end_of(sub, State(p, v, a))
        p, v, a = end.p, end.v, 0.0
    return State(p, v, a)


def _settle_acceleration(r: _Ramp, s: State, segs: list) -> State:
    """A sin² plan from a != 0 (a replan in the middle of a ramp) first ramps a to 0.

    State carries no jerk, so a new sin² bell would start with zero jerk and hold the
    start acceleration longer than the ramp it replaces, carrying the speed past v_max.
    A linear ramp at the full jerk removes it at least as fast as any sin² ramp; from
    a = 0 on, the plan is made of sin² bells again.
    """
    if r.kind != _SIN2 or s.a == 0.0:
        return s
    lin = r.linear()
    tau = lin.time(s.a)
    segs.append((_LINEAR, tau, s.p, s.v, s.a, -math.copysign(lin.j, s.a)))
    return State(s.p + _ramp_dp(s.v, s.a, -s.a, tau, lin.c), s.v + s.a / 2.0 * tau, 0.0)


def _seg_end(kind: int, dur: float, p: float, v: float, a: float, x: float) -> State:
    """State at the end of one segment (x: jerk, or the acceleration change of a sin² ramp)."""
    if kind == _LINEAR:
        return State(p + dur * (v + dur * (a / 2.0 + dur * x / 6.0)), v + dur * (a + dur * x / 2.0), a + dur * x)
    return State(p + v * dur + a * dur * dur / 2.0 + x * _SIN2_C * dur * dur, v + a * dur + x / 2.0 * dur, a + x)


def _end_of(segs: list, s: State) -> State:
    return _seg_end(*segs[-1]) if segs else s


# ---------------------------------------------------------------- velocity changes


def _velocity_segments(r: _Ramp, s: State, vt: float, amax: float, dmax: float) -> list:
    """Time-optimal change from (v, a) to (vt, 0): ramp, hold, ramp (no position target)."""
    v_stop = s.v + r.dv(s.a, 0.0)
    sign = 1.0 if vt >= v_stop else -1.0
    v0, a0, dv = sign * s.v, sign * s.a, sign * (vt - s.v)
    # speeding up in the travel direction uses a, slowing down uses d
    lim = amax if abs(vt) >= abs(s.v) else dmax
    k, j = r.k, r.j
    if k == 0.0:
        a1, t2 = lim, max(dv / lim, 0.0)
    else:
        # v0 + k (A1^2 - a0^2)/(2j) + k A1^2/(2j) = vt, with A1 held at the limit if needed
        a1 = math.sqrt(max(j * dv / k + a0 * a0 / 2.0, 0.0))
        t2 = 0.0
        if a1 > lim:
            a1 = lim
            t2 = max((dv - k * (2.0 * lim * lim - a0 * a0) / (2.0 * j)) / lim, 0.0)
    segs: list = []
    # the UDDU walker with an empty braking part: ramp a0 -> A1, hold, ramp A1 -> 0
    _integrate(r, v0, a0, a1, t2, 0.0, 0.0, 0.0, _emit_collect(sign, s.p, segs))
    return segs


# ---------------------------------------------------------------- WAGO time/path variants


def _bell(kind_base: str, dur: float, p: float, v: float, dv: float, segs: list) -> tuple[float, float]:
    """One ramp of total duration dur changing the velocity by dv, as a single bell."""
    if dur <= 0.0 or dv == 0.0:
        return p, v
    if kind_base == "trapezoid":
        a = dv / dur
        segs.append((_LINEAR, dur, p, v, a, 0.0))
        return p + dur * (v + dur * a / 2.0), v + dv
    ap = 2.0 * dv / dur  # peak of a triangle or sin² bell of mean dv/dur
    h = dur / 2.0
    if kind_base == "jerk":
        jj = ap / h
        segs.append((_LINEAR, h, p, v, 0.0, jj))
        p1 = p + h * (v + h * h * jj / 6.0)
        v1 = v + ap * h / 2.0
        segs.append((_LINEAR, h, p1, v1, ap, -jj))
    else:
        segs.append((_SIN2, h, p, v, 0.0, ap))
        p1 = p + v * h + ap * _SIN2_C * h * h
        v1 = v + ap * h / 2.0
        segs.append((_SIN2, h, p1, v1, ap, -ap))
    return p + (v + dv / 2.0) * dur, v + dv


def _plan_timed(base: str, variant: str, start: State, target: State, limits: Limits, vmax: float) -> list:
    if start.a != 0.0:
        raise ValueError(f"State.a must be 0 at the start of a ramp time/path shape ({base}/{variant}), got {start.a!r}")
    dist = target.p - start.p
    v0, vf = start.v, target.v
    if variant == "time":
        tu = _positive("Limits.up_time", limits.up_time, " for ramp time shapes")
        td = _positive("Limits.down_time", limits.down_time, " for ramp time shapes")
    else:
        su = _positive("Limits.up_path", limits.up_path, " for ramp path shapes")
        sd = _positive("Limits.down_path", limits.down_path, " for ramp path shapes")
        vt = math.copysign(vmax, dist if dist != 0.0 else 1.0)
        # the path fixes the ramp time at full speed; shorter moves keep those times
        tu = 2.0 * su / max(abs(v0 + vt), 1e-300)
        td = 2.0 * sd / max(abs(vt + vf), 1e-300)
    # ramps of fixed duration: distance = (v0+vp)/2*tu + (vp+vf)/2*td (+ cruise)
    vp = (2.0 * dist - v0 * tu - vf * td) / (tu + td)
    cruise = 0.0
    if abs(vp) > vmax:
        vp = math.copysign(vmax, vp)
        cruise = (dist - (v0 + vp) / 2.0 * tu - (vp + vf) / 2.0 * td) / vp
    segs: list = []
    p, v = _bell(base, tu, start.p, v0, vp - v0, segs)
    if cruise > 0.0:
        segs.append((_LINEAR, cruise, p, v, 0.0, 0.0))
        p += v * cruise
    _bell(base, td, p, v, vf - vp, segs)
    return segs


# ---------------------------------------------------------------- public API


def _common(shape: str, start: State, limits: Limits) -> tuple[str, str, float, float, float]:
    if shape not in SHAPES:
        raise ValueError(f"shape must be one of {', '.join(SHAPES)}; got {shape!r}")
    base, _, variant = shape.partition("/")
    _check_state("start", start)
    vmax = _positive("Limits.v", limits.v)
    amax = _positive("Limits.a", limits.a)
    dmax = amax if limits.d is None else _positive("Limits.d", limits.d)
    return base, variant, vmax, amax, dmax


_TINY = 1e-100


def _snap_tiny(s: State, vmax: float, amax: float) -> State:
    """Values 1e-100 below the limits are 0: their squares underflow in the closed forms."""
    v = 0.0 if abs(s.v) < _TINY * vmax else s.v
    a = 0.0 if abs(s.a) < _TINY * amax else s.a
    return s if (v, a) == (s.v, s.a) else State(s.p, v, a)


def plan(shape: str, start: State, target: State, limits: Limits) -> Profile:
    """Plan a move from `start` to `target` (position and velocity, a = 0)."""
    base, variant, vmax, amax, dmax = _common(shape, start, limits)
    _check_state("target", target)
    if target.a != 0.0:
        raise ValueError(f"target.a must be 0 (the move ends in constant velocity), got {target.a!r}")
    if abs(target.v) > vmax:
        raise ValueError(f"target.v = {target.v!r} is outside the velocity limit +-{vmax!r} (Limits.v)")
    if variant:
        return Profile(shape, start, target, _plan_timed(base, variant, start, target, limits, vmax))

    r = _Ramp(base, limits, max(amax, dmax))
    segs: list = []
    s = _brake(r, _snap_tiny(start, vmax, amax), vmax, min(amax, dmax), segs)
    # distances and speeds 1e-100 below the limits are 0 (their squares would underflow)
    dist = 0.0 if abs(target.p - s.p) < _TINY * vmax * vmax / amax else target.p - s.p
    vf = 0.0 if abs(target.v) < _TINY * vmax else target.v
    best = None
    # With a != d some moves (e.g. a run-up that must first back away) have no
    # profile with the drive ramp at a and the braking ramp at d; they fall back to
    # min(a, d) for both, which keeps every limit and always has a solution.
    for a_lim, d_lim in ((amax, dmax), (min(amax, dmax), min(amax, dmax))):
        for sign in (1.0, -1.0):
            cands = _solve_up(r, sign * s.v, sign * s.a, sign * dist, sign * vf, vmax, a_lim, d_lim)
            for c in cands:
                if best is None or c.duration < best[1].duration:
                    best = (sign, c)
        if best is not None or amax == dmax:
            break
    if best is None:  # pragma: no cover - the family always holds a solution inside the limits
        raise ValueError(f"no profile found from {start} to {target} with {limits}")
    sign, c = best
    _integrate(r, sign * s.v, sign * s.a, c.a1, c.t2, c.t4, c.a2, c.t6, _emit_collect(sign, s.p, segs))
    return Profile(shape, start, target, segs)


def plan_velocity(shape: str, start: State, v_target: float, limits: Limits) -> Profile:
    """Reach velocity `v_target` (with a = 0) as fast as the limits allow; then keep it."""
    base, variant, vmax, amax, dmax = _common(shape, start, limits)
    v_target = _finite("v_target", v_target)
    if abs(v_target) > vmax:
        raise ValueError(f"v_target = {v_target!r} is outside the velocity limit +-{vmax!r} (Limits.v)")
    if variant:
        if start.a != 0.0:
            raise ValueError(f"State.a must be 0 at the start of a ramp time/path shape ({shape}), got {start.a!r}")
        up = abs(v_target) >= abs(start.v)
        if variant == "time":
            dur = _positive("Limits.up_time" if up else "Limits.down_time", limits.up_time if up else limits.down_time)
        else:
            path = _positive("Limits.up_path" if up else "Limits.down_path", limits.up_path if up else limits.down_path)
            dur = 2.0 * path / max(abs(start.v + v_target), 1e-300)
        segs: list = []
        _bell(base, dur, start.p, start.v, v_target - start.v, segs)
        end = _end_of(segs, start) if segs else start
        return Profile(shape, start, State(end.p, v_target), segs)
    r = _Ramp(base, limits, max(amax, dmax))
    segs = []
    s = _brake(r, start, vmax, min(amax, dmax), segs)
    segs.extend(_velocity_segments(r, s, v_target, amax, dmax))
    end = _end_of(segs, start) if segs else start
    return Profile(shape, start, State(end.p, v_target), segs)


# Compiled, the public names get this source's docstrings and annotations back (help(),
# inspect.signature); in plain Python this does nothing. See axisline/_docs.py.
from axisline._docs import document as _document  # noqa: E402

# hot: called every cycle from interpreted code (devices), left compiled-only (no wrapper)
_document(globals(), hot={"Profile": ("sample",)})
