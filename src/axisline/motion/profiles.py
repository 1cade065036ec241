"""Point-to-point and velocity profiles: input state + limits in, trajectory out.

    from axisline.motion.profiles import plan, State, Limits
    prof = plan("jerk", State(p=0.0, v=0.0, a=0.0), State(p=10.0, v=0.0),
                Limits(v=1.0, a=2.0, d=2.0, j=10.0))
    prof.duration, prof.sample(t) -> (p, v, a, j)

This module checks the request and puts the plan together; the pieces live beside it:
motion.profile_segments (State, Limits, the Profile and its sampling) and motion.uddu
(the time-optimal search for "trapezoid", "jerk" and "sin2": see its docstring for the
profile family, the same as Ruckig's, so the durations agree).

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
from typing import Final

from axisline.motion.profile_segments import LINEAR, SIN2, SIN2_C, Limits, Profile, Segments, State, seg_end
from axisline.motion.uddu import BASE, Cand, Ramp, Walk, fmax, fmin, integrate, ramp_dp, solve_up

__all__ = ["State", "Limits", "Profile", "plan", "plan_velocity", "SHAPES"]

SHAPES: Final = tuple(BASE) + tuple(f"{b}/{v}" for v in ("time", "path") for b in BASE)
_PARTS: Final[dict[str, tuple[str, str]]] = {}
for _shape in SHAPES:
    _base, _, _variant = _shape.partition("/")
    _PARTS[_shape] = (_base, _variant)


# ---------------------------------------------------------------- validation


def _finite(name: str, x: float) -> float:
    if not _is_finite(x):
        raise ValueError(f"{name} must be a finite number, got {x!r}")
    return float(x)


def _is_finite(x: float) -> bool:
    if isinstance(x, float):
        return x - x == 0.0  # 0 for every finite float, NaN for inf and NaN (no math call)
    return isinstance(x, int) and not isinstance(x, bool) and math.isfinite(x)


def _positive(name: str, x: float | None, why: str = "") -> float:
    if x is None:
        raise ValueError(f"{name} is required{why}")
    x = _finite(name, x)
    if x <= 0.0:
        raise ValueError(f"{name} must be > 0{why}, got {x!r}")
    return x


def _check_state(name: str, s: State) -> None:
    # the field names are only formatted for the error (every plan checks two states)
    if not (_is_finite(s.p) and _is_finite(s.v) and _is_finite(s.a)):
        _finite(name + ".p", s.p)
        _finite(name + ".v", s.v)
        _finite(name + ".a", s.a)


def _ramp(base: str, limits: Limits, amax: float) -> Ramp:
    """The ramp law of a plan, its jerk checked (Limits.j, or amax / Limits.ramp_time)."""
    if base == "trapezoid":
        return Ramp(base, math.inf)
    if limits.j is not None:
        return Ramp(base, _positive("Limits.j", limits.j))
    if limits.ramp_time is not None:
        return Ramp(base, amax / _positive("Limits.ramp_time", limits.ramp_time))
    raise ValueError(f"Limits.j (or Limits.ramp_time) is required for shape {base!r}")


def _end_of(segs: list, s: State) -> State:
    """State at the end of the last of (kind, duration, p, v, a, x) segments; `s` if none."""
    if not segs:
        return s
    kind, dur, p, v, a, x = segs[-1]
    return seg_end(kind, dur, p, v, a, x)


# ---------------------------------------------------------------- braking into the limits


def _brake(r: Ramp, start: State, vmax: float, alim: float, segs: Segments) -> State:
    """Bring a start state that violates the limits back inside them (adds segments).

    Order: acceleration to its limit, then (sin² only) acceleration to 0, then speed to v_max.
    A start inside the limits comes back as it is.
    """
    p, v, a = start.p, start.v, start.a
    s = start
    if abs(a) > alim:
        tgt = math.copysign(alim, a)
        r0 = r.linear()
        tau = r0.time(tgt - a)
        if tau > 0.0:
            segs.add(LINEAR, tau, p, v, a, math.copysign(r0.j, tgt - a))
            p += ramp_dp(v, a, tgt - a, tau, r0.c)
            v += (a + tgt) / 2.0 * tau
        a = tgt
        s = State(p, v, a)
    s = _settle_acceleration(r, s, segs)
    p, v, a = s.p, s.v, s.a
    v_stop = v + r.dv(a, 0.0)
    if abs(v_stop) > vmax or abs(v) > vmax:
        target_v = math.copysign(vmax, v_stop if abs(v_stop) > vmax else v)
        added = segs.added
        _velocity_segments(r, s, target_v, alim, alim, segs)
        end = segs.end(s) if segs.added > added else s
        s = State(end.p, end.v, 0.0)
    return s


def _settle_acceleration(r: Ramp, s: State, segs: Segments) -> State:
    """A sin² plan from a != 0 (a replan in the middle of a ramp) first ramps a to 0.

    State carries no jerk, so a new sin² bell would start with zero jerk and hold the
    start acceleration longer than the ramp it replaces, carrying the speed past v_max.
    A linear ramp at the full jerk removes it at least as fast as any sin² ramp; from
    a = 0 on, the plan is made of sin² bells again.
    """
    if r.kind != SIN2 or s.a == 0.0:
        return s
    lin = r.linear()
    tau = lin.time(s.a)
    segs.add(LINEAR, tau, s.p, s.v, s.a, -math.copysign(lin.j, s.a))
    return State(s.p + ramp_dp(s.v, s.a, -s.a, tau, lin.c), s.v + s.a / 2.0 * tau, 0.0)


# ---------------------------------------------------------------- velocity changes


def _velocity_segments(r: Ramp, s: State, vt: float, amax: float, dmax: float, segs: Segments) -> None:
    """Time-optimal change from (v, a) to (vt, 0): ramp, hold, ramp (no position target)."""
    v_stop = s.v + r.dv(s.a, 0.0)
    sign = 1.0 if vt >= v_stop else -1.0
    v0, a0, dv = sign * s.v, sign * s.a, sign * (vt - s.v)
    # speeding up in the travel direction uses a, slowing down uses d
    lim = amax if abs(vt) >= abs(s.v) else dmax
    k, j = r.k, r.j
    if k == 0.0:
        a1, t2 = lim, fmax(dv / lim, 0.0)
    else:
        # v0 + k (A1^2 - a0^2)/(2j) + k A1^2/(2j) = vt, with A1 held at the limit if needed
        a1 = math.sqrt(fmax(j * dv / k + a0 * a0 / 2.0, 0.0))
        t2 = 0.0
        if a1 > lim:
            a1 = lim
            t2 = fmax((dv - k * (2.0 * lim * lim - a0 * a0) / (2.0 * j)) / lim, 0.0)
    # the UDDU walker with an empty braking part: ramp a0 -> A1, hold, ramp A1 -> 0
    integrate(r, v0, a0, a1, t2, 0.0, 0.0, 0.0, Walk(segs, sign, s.p))


# ---------------------------------------------------------------- WAGO time/path variants


def _bell(kind_base: str, dur: float, p: float, v: float, dv: float, segs: Segments) -> tuple[float, float]:
    """One ramp of total duration dur changing the velocity by dv, as a single bell."""
    if dur <= 0.0 or dv == 0.0:
        return p, v
    if kind_base == "trapezoid":
        a = dv / dur
        segs.add(LINEAR, dur, p, v, a, 0.0)
        return p + dur * (v + dur * a / 2.0), v + dv
    ap = 2.0 * dv / dur  # peak of a triangle or sin² bell of mean dv/dur
    h = dur / 2.0
    if kind_base == "jerk":
        jj = ap / h
        segs.add(LINEAR, h, p, v, 0.0, jj)
        p1 = p + h * (v + h * h * jj / 6.0)
        v1 = v + ap * h / 2.0
        segs.add(LINEAR, h, p1, v1, ap, -jj)
    else:
        segs.add(SIN2, h, p, v, 0.0, ap)
        p1 = p + v * h + ap * SIN2_C * h * h
        v1 = v + ap * h / 2.0
        segs.add(SIN2, h, p1, v1, ap, -ap)
    return p + (v + dv / 2.0) * dur, v + dv


def _plan_timed(base: str, variant: str, start: State, target: State, limits: Limits, vmax: float) -> Segments:
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
    segs = Segments()
    p, v = _bell(base, tu, start.p, v0, vp - v0, segs)
    if cruise > 0.0:
        segs.add(LINEAR, cruise, p, v, 0.0, 0.0)
        p += v * cruise
    _bell(base, td, p, v, vf - vp, segs)
    return segs


# ---------------------------------------------------------------- public API


def _common(shape: str, start: State, limits: Limits) -> tuple[str, str, float, float, float]:
    parts = _PARTS.get(shape)
    if parts is None:
        raise ValueError(f"shape must be one of {', '.join(SHAPES)}; got {shape!r}")
    base, variant = parts
    _check_state("start", start)
    vmax = _positive("Limits.v", limits.v)
    amax = _positive("Limits.a", limits.a)
    dmax = amax if limits.d is None else _positive("Limits.d", limits.d)
    return base, variant, vmax, amax, dmax


_TINY: Final = 1e-100


def _snap_tiny(s: State, vmax: float, amax: float) -> State:
    """Values 1e-100 below the limits are 0: their squares underflow in the closed forms."""
    v = 0.0 if abs(s.v) < _TINY * vmax else s.v
    a = 0.0 if abs(s.a) < _TINY * amax else s.a
    return s if (v == s.v and a == s.a) else State(s.p, v, a)


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

    r = _ramp(base, limits, fmax(amax, dmax))
    segs = Segments()
    s = _brake(r, _snap_tiny(start, vmax, amax), vmax, fmin(amax, dmax), segs)
    # distances and speeds 1e-100 below the limits are 0 (their squares would underflow)
    dist = 0.0 if abs(target.p - s.p) < _TINY * vmax * vmax / amax else target.p - s.p
    vf = 0.0 if abs(target.v) < _TINY * vmax else target.v
    best: Cand | None = None
    best_sign = 1.0
    # With a != d some moves (e.g. a run-up that must first back away) have no
    # profile with the drive ramp at a and the braking ramp at d; they fall back to
    # min(a, d) for both, which keeps every limit and always has a solution.
    both = fmin(amax, dmax)
    for a_lim, d_lim in ((amax, dmax), (both, both)):
        for sign in (1.0, -1.0):
            for c in solve_up(r, sign * s.v, sign * s.a, sign * dist, sign * vf, vmax, a_lim, d_lim):
                if best is None or c.duration < best.duration:
                    best, best_sign = c, sign
        if best is not None or amax == dmax:
            break
    if best is None:  # pragma: no cover - the family always holds a solution inside the limits
        raise ValueError(f"no profile found from {start} to {target} with {limits}")
    sign, c = best_sign, best
    integrate(r, sign * s.v, sign * s.a, c.a1, c.t2, c.t4, c.a2, c.t6, Walk(segs, sign, s.p))
    return Profile(shape, start, target, segs)


def plan_velocity(shape: str, start: State, v_target: float, limits: Limits) -> Profile:
    """Reach velocity `v_target` (with a = 0) as fast as the limits allow; then keep it."""
    base, variant, vmax, amax, dmax = _common(shape, start, limits)
    v_target = _finite("v_target", v_target)
    if abs(v_target) > vmax:
        raise ValueError(f"v_target = {v_target!r} is outside the velocity limit +-{vmax!r} (Limits.v)")
    segs = Segments()
    if variant:
        if start.a != 0.0:
            raise ValueError(f"State.a must be 0 at the start of a ramp time/path shape ({shape}), got {start.a!r}")
        up = abs(v_target) >= abs(start.v)
        if variant == "time":
            dur = _positive("Limits.up_time" if up else "Limits.down_time", limits.up_time if up else limits.down_time)
        else:
            path = _positive("Limits.up_path" if up else "Limits.down_path", limits.up_path if up else limits.down_path)
            dur = 2.0 * path / max(abs(start.v + v_target), 1e-300)
        _bell(base, dur, start.p, start.v, v_target - start.v, segs)
        end = segs.end(start)
        return Profile(shape, start, State(end.p, v_target), segs)
    r = _ramp(base, limits, fmax(amax, dmax))
    s = _brake(r, start, vmax, fmin(amax, dmax), segs)
    _velocity_segments(r, s, v_target, amax, dmax, segs)
    end = segs.end(start)
    return Profile(shape, start, State(end.p, v_target), segs)


# Compiled, the public names get this source's docstrings and annotations back (help(),
# inspect.signature); in plain Python this does nothing. See axisline/_docs.py.
from axisline._docs import document as _document  # noqa: E402

_document(globals())
