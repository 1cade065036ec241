"""Motion profiles of the 750-672 in microsteps, built with the kernel's profile generator.

Acceleration types (manual §3.10.2.1.6, config address 60 Acceleration_Modes; wago.md §2.7):

    AccType/DecType   0 constant -> "trapezoid", 1 linear -> "jerk", 2 sin^2 -> "sin2"
    AccParam/DecParam 0 no modification: the parameter is the time of the acceleration increase
                        (jerk time Tj [ms]); 1: ramp time [ms] -> "<shape>/time";
                        2: ramp path [microsteps] -> "<shape>/path"

A ramp law is a `Ramp`. With AccParam 0 the jerk is chosen so that the acceleration rises from
0 to a in exactly Tj: j = a/Tj for the linear ramp and j = (pi/2)*a/Tj for sin^2 (the kernel's
Limits.j is the peak jerk of a sin^2 ramp, docs/decisions.md K2, whose ramp 0 -> a lasts
(pi/2)*a/j). When both phases use the same kernel shape with the same jerk (or both are
time/path variants of one shape) a move is one time-optimal kernel plan. Otherwise - different
types or jerks for acceleration and deceleration, which the WAGO allows ("the acceleration and
brake ramps can be adjusted individually", §2.1.1.3.7) - `plan_move` chains kernel velocity
ramps: ramp-up, cruise, ramp-down, with the peak speed lowered by bisection for a short move
and a braking ramp first when the target is behind or too close for the current speed.

In a chain a ramp path is used as the ramp time it takes at full speed, T = 2 S / (v0 + v1), as
the kernel does for short moves (docs/decisions.md K3); time/path plans from a moving start go
through the chain too, which brakes first when the target is behind or too close. Speeds below
1e-9 microsteps/s count as rest.

`Feed` is the axis' sync source: it samples the running profile at (cycle - c0) * period and
hands the axis its set point in axis units (microsteps / counts_per_unit).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from axisline.devices.wago672.errors import WagoError
from axisline.motion.profiles import Limits, Profile, State, plan, plan_velocity

__all__ = ["Ramp", "ramp_from_mode", "needs_constant_speed", "Cruise", "Chain", "plan_move", "plan_speed", "plan_stop", "Feed"]

_BASES = {0: "trapezoid", 1: "jerk", 2: "sin2"}
_K = {"trapezoid": 0.0, "jerk": 1.0, "sin2": math.pi / 2.0}  # ramp time = k * da / j
ACC_INTERNAL_MAX = 32767 * 8000 / 4  # highest acceleration the module can set [microsteps/s^2]


@dataclass(frozen=True, slots=True)
class Ramp:
    """One ramp law. shape: kernel shape; accel [microsteps/s^2]; jerk (AccParam 0, linear/sin^2);
    time [s] (AccParam 1) or path [microsteps] (AccParam 2)."""

    shape: str
    accel: float
    jerk: float | None = None
    time: float | None = None
    path: float | None = None

    @property
    def base(self) -> str:
        return self.shape.partition("/")[0]

    @property
    def variant(self) -> str:
        return self.shape.partition("/")[2]

    @property
    def smooth(self) -> bool:
        """Linear or sin^2 acceleration: a new set point waits for v = const (§3.11.1.4 note)."""
        return self.base != "trapezoid"

    def limits(self, vmax: float) -> Limits:
        """Kernel limits of a velocity ramp with this law (either direction)."""
        return Limits(
            v=vmax, a=self.accel, d=self.accel, j=self.jerk,
            up_time=self.time, down_time=self.time, up_path=self.path, down_path=self.path,
        )


def ramp_from_mode(acc_type: int, acc_param: int, accel: float, param: int, param_steps: float | None = None, phase: str = "Acc") -> Ramp:
    """The ramp law of one phase from Acceleration_Modes fields and Acc_ParamUp/Down.

    param: the raw parameter (ms for jerk and ramp time); param_steps: the parameter as a
    path in microsteps (AccParam 2, converted from position units by the caller).
    Errors: a reserved type/modification or a parameter 0 where it is used -> 1557
    MCALC_PARA; a time/path ramp that needs more acceleration than the module can make ->
    1554 (time) / 1556 (path) is checked by the caller, who knows the speed.
    """
    if acc_type not in _BASES:
        raise WagoError(1557, f"{phase}Type = {acc_type} is reserved (allowed 0 .. 2)")
    if acc_param not in (0, 1, 2):
        raise WagoError(1557, f"{phase}Param = {acc_param} is reserved (allowed 0 .. 2)")
    if not accel > 0.0:
        raise WagoError(1121, f"acceleration of the {phase.lower()} phase must be > 0, got {accel:g}")
    base = _BASES[acc_type]
    if acc_param == 0:
        if base == "trapezoid":
            return Ramp(base, accel)
        if not 1 <= param <= 16777215:
            raise WagoError(1557, f"Acc_Param{'Up' if phase == 'Acc' else 'Down'} = {param} ms: the jerk time must be 1 .. 16777215")
        return Ramp(base, accel, jerk=_K[base] * accel / (param / 1000.0))
    if not 1 <= param <= 16777215:
        raise WagoError(1557, f"Acc_Param{'Up' if phase == 'Acc' else 'Down'} = {param}: a ramp {'time' if acc_param == 1 else 'path'} must be 1 .. 16777215")
    if acc_param == 1:
        return Ramp(f"{base}/time", accel, time=param / 1000.0)
    steps = float(param if param_steps is None else param_steps)
    if not steps > 0.0:
        raise WagoError(1557, f"ramp path {param} is 0 microsteps after scaling")
    return Ramp(f"{base}/path", accel, path=steps)


# ------------------------------------------------------------------ profile pieces


class Cruise:
    """Constant velocity for `duration` seconds (a profile piece)."""

    __slots__ = ("start", "target", "duration")

    def __init__(self, p: float, v: float, duration: float) -> None:
        self.start = State(p, v, 0.0)
        self.duration = max(duration, 0.0)
        self.target = State(p + v * self.duration, v, 0.0)

    def sample(self, t: float) -> tuple[float, float, float, float]:
        s = self.start
        return (s.p + s.v * t, s.v, 0.0, 0.0)


class Chain:
    """Profiles one after another; each piece starts where the previous one ends.

    Before 0 it holds the start state; after `duration` it continues at the final speed
    (like a kernel Profile)."""

    __slots__ = ("parts", "starts", "duration", "start", "target")

    def __init__(self, parts: list) -> None:
        parts = [p for p in parts if p.duration > 0.0] or parts[:1]
        self.parts = parts
        self.starts = []
        t = 0.0
        for p in parts:
            self.starts.append(t)
            t += p.duration
        self.duration = t
        self.start = parts[0].start
        self.target = parts[-1].target

    def sample(self, t: float) -> tuple[float, float, float, float]:
        if t >= self.duration:
            tg = self.target
            return (tg.p + tg.v * (t - self.duration), tg.v, 0.0, 0.0)
        if t <= 0.0:
            return self.parts[0].sample(t)
        i = len(self.starts) - 1
        while self.starts[i] > t:
            i -= 1
        return self.parts[i].sample(t - self.starts[i])


def _end(prof) -> State:
    return State(prof.target.p, prof.target.v, 0.0)


def _single_shape(up: Ramp, down: Ramp) -> str | None:
    """The kernel shape that plans both phases in one go, if there is one."""
    if up.shape != down.shape:
        return None
    if up.variant or up.base == "trapezoid":
        return up.shape
    assert up.jerk is not None and down.jerk is not None
    return up.shape if math.isclose(up.jerk, down.jerk, rel_tol=1e-12) else None


def needs_constant_speed(up: Ramp, down: Ramp) -> bool:
    """A plan with these ramps must start at a = 0 (time/path variants, chained ramp laws)."""
    return bool(up.variant or down.variant) or _single_shape(up, down) is None


def _change(up: Ramp, down: Ramp, s: State, vt: float) -> list:
    """Velocity change from s (a = 0) to vt: speeding up with `up`, slowing with `down`,
    a reversal as a stop with `down` and a start with `up`."""
    if s.v != 0.0 and vt != 0.0 and (s.v > 0.0) != (vt > 0.0):
        first = plan_velocity(down.shape, s, 0.0, down.limits(abs(s.v)))
        second = plan_velocity(up.shape, _end(first), vt, up.limits(abs(vt)))
        return [first, second]
    ramp = up if abs(vt) >= abs(s.v) else down
    vmax = max(abs(vt), abs(s.v))
    return [plan_velocity(ramp.shape, s, vt, ramp.limits(vmax if vmax > 0.0 else 1.0))]


def _span(parts: list) -> float:
    return parts[-1].target.p - parts[0].start.p


def plan_move(start: State, target: float, vmax: float, up: Ramp, down: Ramp, v_end: float = 0.0):
    """Plan a positioning move to `target` [microsteps] at speed vmax > 0, ending at v_end
    (SET_VELOCITY_TARGET, signed in the direction of the move; 0 usually)."""
    shape = _single_shape(up, down)
    limits = Limits(
        v=vmax, a=up.accel, d=down.accel, j=up.jerk,
        up_time=up.time, down_time=down.time, up_path=up.path, down_path=down.path,
    )
    if shape is not None and not (up.variant and start.v != 0.0):
        return plan(shape, start, State(target, v_end), limits)
    # time/path ramps from a moving start: the chain brakes first when the target is behind or
    # too close (the kernel's time/path plans assume a start toward the target)
    if start.a != 0.0:  # the device defers a replan with smooth ramps until a = 0
        raise WagoError(1557, f"a move with different ramp laws must start at constant speed (a = {start.a:g})")
    return _compose(start, target, vmax, up, down, v_end)


def _as_time(r: Ramp, speed_sum: float) -> Ramp:
    """A ramp path as the ramp time it has at full speed, T = 2 S / |v_from + v_to| (docs/decisions.md
    K3: shorter moves keep the times), so that a short move can lower its peak speed."""
    if r.path is None:
        return r
    return Ramp(f"{r.base}/time", r.accel, time=2.0 * r.path / max(abs(speed_sum), 1e-9))


def _compose(start: State, target: float, vmax: float, up: Ramp, down: Ramp, v_end: float) -> Chain:
    d = target - start.p
    v0 = start.v if abs(start.v) > 1e-9 else 0.0  # a speed below 1e-9 microsteps/s is rest
    start = State(start.p, v0, 0.0)
    if d == 0.0 and v0 == 0.0 and v_end == 0.0:
        return Chain([Cruise(start.p, 0.0, 0.0)])
    sgn = math.copysign(1.0, d if d != 0.0 else (v0 if v0 != 0.0 else 1.0))
    if v0 != 0.0:
        # can the target be reached in the current direction of travel?
        v_full = max(abs(v0), vmax)
        bu, bd = _as_time(up, v_full), _as_time(down, v_full)
        direct = _change(bu, bd, start, v_end) if v_end * v0 >= 0.0 else _change(bu, bd, start, 0.0)
        if (v0 > 0.0) != (d > 0.0) or abs(_span(direct)) > abs(d):
            brake = _change(bu, bd, start, 0.0)
            rest = _compose(_end(brake[-1]), target, vmax, up, down, v_end)
            return Chain(brake + rest.parts)
    vf = v_end
    # moving toward the target (or at rest): a ramp path becomes the time it takes at full speed
    vt = sgn * vmax
    up, down = _as_time(up, v0 + vt), _as_time(down, vt + vf)

    def parts_for(vp: float) -> list:
        first = _change(up, down, start, sgn * vp)
        last = _change(up, down, _end(first[-1]), vf)
        return first + last

    full = parts_for(vmax)
    covered = sgn * _span(full)
    if covered <= sgn * d:
        return _with_cruise(start, vmax * sgn, (sgn * d - covered) / vmax, up, down, vf)
    # too short for vmax: bisect the peak speed between the current speed and vmax
    lo, hi = abs(v0), vmax
    if sgn * _span(parts_for(lo)) > sgn * d:
        lo = 0.0  # (cannot happen after the braking check; keeps the bracket valid)
    for _ in range(80):
        mid_v = 0.5 * (lo + hi)
        if sgn * _span(parts_for(mid_v)) <= sgn * d:
            lo = mid_v
        else:
            hi = mid_v
        if hi - lo <= 1e-12 * max(vmax, 1.0):
            break
    vp = lo
    covered = sgn * _span(parts_for(vp)) if vp > 0.0 else 0.0
    cruise = sgn * d - covered
    if vp <= 0.0:  # a move below the bisection's resolution: one constant-acceleration move
        return Chain([plan("trapezoid", start, State(target, vf), Limits(v=vmax, a=up.accel, d=down.accel))])
    return _with_cruise(start, sgn * vp, cruise / vp, up, down, vf)


def _with_cruise(start: State, vp: float, cruise: float, up: Ramp, down: Ramp, vf: float) -> Chain:
    first = _change(up, down, start, vp)
    c = Cruise(_end(first[-1]).p, vp, cruise)
    last = _change(up, down, c.target, vf)
    return Chain(first + [c] + last)


def plan_speed(start: State, v_target: float, up: Ramp, down: Ramp):
    """Speed control: run to v_target [microsteps/s] (signed) and keep it."""
    if start.a == 0.0 and start.v != 0.0 and abs(start.v) <= 1e-9:
        start = State(start.p, 0.0, 0.0)  # a speed below 1e-9 microsteps/s is rest
    if start.a != 0.0 and (up.variant or down.variant):
        raise WagoError(1557, f"a ramp time/path speed change must start at constant speed (a = {start.a:g})")
    if start.a != 0.0:
        ramp = up if abs(v_target) >= abs(start.v) else down
        return plan_velocity(ramp.shape, start, v_target, ramp.limits(max(abs(v_target), abs(start.v), 1.0)))
    parts = _change(up, down, start, v_target)
    return parts[0] if len(parts) == 1 else Chain(parts)


def plan_stop(start: State, decel: float) -> Profile:
    """STOP_FAST: brake to standstill at the constant deceleration `decel` (Acceleration_Stop_Fast)."""
    return plan_velocity("trapezoid", start, 0.0, Limits(v=max(abs(start.v), 1.0), a=decel, d=decel))


# ------------------------------------------------------------------ the axis' set-point source


class Feed:
    """Sync source of the axis (kernel `SyncSource`): the module's set point in axis units.

    Positions are unwrapped microsteps in the axis frame; `steps_per_unit` is the axis'
    counts_per_unit (microsteps per axis user unit).

    The module asks for the state of the same cycle several times a tick (the set point a
    plan starts from, the watches, the axis' sample): `state` keeps the last few, until `run`
    or `hold` (the only writers of profile, c0 and p_rest) change what is sampled.
    """

    __slots__ = ("steps_per_unit", "period", "profile", "c0", "p_rest", "_states")

    def __init__(self, steps_per_unit: float, period: float) -> None:
        self.steps_per_unit = steps_per_unit
        self.period = period
        self.profile: Any = None  # a kernel Profile or a Chain of them (None: holding p_rest)
        self.c0 = 0
        self.p_rest = 0.0
        self._states: dict[int, tuple[float, float, float, float]] = {}

    def run(self, profile, c0: int) -> None:
        """Sample `profile` from cycle c0 on (t = 0 at c0: the state the plan started from)."""
        self.profile = profile
        self.c0 = c0
        self._states.clear()

    def hold(self, p: float) -> None:
        self.profile = None
        self.p_rest = p
        self._states.clear()

    def t(self, cycle: int) -> float:
        return (cycle - self.c0) * self.period

    def state(self, cycle: int) -> tuple[float, float, float, float]:
        """(p, v, a, j) in microsteps at `cycle`."""
        states = self._states
        st = states.get(cycle)
        if st is None:
            if self.profile is None:
                st = (self.p_rest, 0.0, 0.0, 0.0)
            else:
                st = self.profile.sample((cycle - self.c0) * self.period)
            if len(states) >= 4:  # a tick looks at this cycle and the last one
                states.clear()
            states[cycle] = st
        return st

    def ended(self, cycle: int) -> bool:
        profile = self.profile
        return profile is None or (cycle - self.c0) * self.period >= profile.duration  # t(cycle)

    def sample(self, cycle: int) -> tuple[float, float, float]:
        p, v, a, _ = self.state(cycle)
        k = self.steps_per_unit
        return (p / k, v / k, a / k)
