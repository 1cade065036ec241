"""Electronic gear: a slave axis coupled to a master by an integer ratio (PLCopen MC_GearIn,
MC_GearOut, MC_GearInPos, MC_Phasing).

    gear = Gear(master, slave_axis, numerator=16523, denominator=11872)
    gear.gear_in()                      # slave_axis.start_sync(gear); couples on the fly
    ... each cycle: master.update(c); slave_axis.update_setpoint(c)  (calls gear.sample(c))
    gear.set_ratio(3, 2, ramp_distance=50.0)   # ratio change with a ramp
    gear.phasing(5.0, velocity=20.0, acceleration=200.0)   # shift the master seen by the slave
    gear.gear_out()                     # the slave keeps its velocity; slave_axis.end_sync() halts

The law (integer, drift free)
-----------------------------
The ratio acts on COUNTS: `numerator` slave counts per `denominator` master counts (master
counts: `master.counts`, see master.py for masters without counts of their own; slave
counts: the axis' `counts_per_unit`). Every cycle the gear computes, with Python ints,

    q, r = divmod((master_counts - master_ref) * numerator, denominator)
    slave_counts = slave_ref + q                                    (the integer law)
    position     = (slave_ref + q + r / denominator) / slave_counts_per_unit + offset

from the reference (master_ref, slave_ref) fixed at coupling: nothing is accumulated, so
a ratio such as 16523/11872 runs for days without drift. `offset` is a constant float:
the sub-count part of the slave position at coupling and the position offset gathered
while catching up. In user units the ratio is `ratio` = numerator * master counts_per_unit
/ (denominator * slave counts_per_unit); velocity = ratio * master velocity and
acceleration = ratio * master acceleration (the master's read-outs).

Gear in (MC_GearIn), on the fly or at standstill
------------------------------------------------
The coupling is made in the first `sample` after `gear_in` (the cycle after the command,
when the master of that cycle is known). The slave's last set point (p0, v0, a0) is
continued by the geared position g(t) plus a catch-up term e(t): the slave position is

    s(t) = g(t) + e(t),   g = the integer law referenced so that g continues p0,
    e: plan_velocity in the error domain from (0, v0 - ratio*vm, a0 - ratio*am) to
       velocity 0, with the slave's shape, acceleration (deceleration when the slave slows
       down) and jerk.

So the slave keeps following the moving master exactly while it matches the velocity; for
a master at constant speed the slave's velocity moves monotonically from v0 to ratio*vm
and its acceleration and jerk stay within the axis limits (an accelerating master passes
its own acceleration through the ratio, as any gear does). When e(t) has ended, its final
value (the offset gathered while catching up) is folded into `offset` and `in_gear` is
set. With master and slave at rest e is zero: the gear couples at once.

Gear out (MC_GearOut)
---------------------
`gear_out()` releases the slave from the master: it keeps its velocity (an acceleration
left at that moment is ramped out with the axis' jerk, which adds a*|a|/(2j) to the
velocity; with the "trapezoid" shape the acceleration ends at once). The axis stays in
SynchronizedMotion following that velocity until `slave.end_sync()` halts it with its
ramp (or `gear_out(halt=True)`, which does both at once).

Ratio change (while coupled)
----------------------------
`set_ratio(n, d, ramp_distance=D)` blends the ratio over D master units, as a function of
master position x (not of time), starting at the master position of the change and in the
master's direction of travel (forward at rest):

    K(x) = K_old + (K_new - K_old) * h(u),  u = (x - x1) / D,  h(u) = 3u^2 - 2u^3
    s(x) = old law(x) + (K_new - K_old) * D * H(u),  H(u) = u^3 - u^4/2 (integral of h)

h is smooth at both ends, so neither position, velocity nor acceleration steps. The new
integer law is referenced at the end of the ramp (x1 + D, its exact rational slave count),
so from there the gear is exact again. `ramp_time` instead of a distance means the master
distance covered in that time at the master speed of the change (a master at rest: the new
ratio applies at once, without a step since nothing moves). The extra acceleration of the
blend is (K_new - K_old) * h'(u) / D * master_speed^2: choose D long enough for the slave.

Phasing (MC_Phasing)
--------------------
`phasing(shift, velocity, acceleration, ...)` shifts the master position seen by the slave
by `shift` master units with a profile (profiles.plan, the slave's shape; limits in master
units). The shift is rounded to whole master counts; when the profile ends it is folded
into the integer reference (master_ref -= shift counts), so the law stays exact. Shifts
add up; a shift during a shift replans from the current phase state. `phase` reads the
total shift.

Gear in position (MC_GearInPos, the flying saw): gear_in_position.py.

Hot path: `sample` allocates only the ints, floats and the result tuple Python needs.
"""

from __future__ import annotations

import math
from fractions import Fraction
from typing import Any

from axisline.motion.profiles import Limits, Profile, State, plan, plan_velocity

__all__ = ["Gear", "GearError"]  # GearInPos, GearInPosError, SyncCheck: gear_in_position.py

# modes of a gear
_PENDING = 0  # not yet coupled: couples on the fly in the next sample
_COUPLED = 1  # following the integer law (maybe with a catch-up, ratio ramp or phasing)
_APPROACH = 2  # gear in position: the master-domain approach runs
_FREE = 3  # geared out: the slave keeps its velocity

_BIG_SPEED = 1e15  # a velocity limit that never binds (error-domain and phase profiles)


class GearError(ValueError):
    """A gear request that cannot be carried out (the text says why)."""


def _ratio_int(name: str, x: Any) -> int:
    if isinstance(x, bool) or not isinstance(x, int):
        raise GearError(f"{name} must be an integer, got {x!r}")
    return x


def _number(name: str, x: Any) -> float:
    if isinstance(x, bool) or not isinstance(x, (int, float)) or not math.isfinite(x):
        raise GearError(f"{name} must be a finite number, got {x!r}")
    return float(x)


def _positive(name: str, x: Any) -> float:
    x = _number(name, x)
    if x <= 0.0:
        raise GearError(f"{name} must be > 0, got {x:g}")
    return x


class Gear:
    """Electronic gear: a SyncSource for `slave.start_sync`; see the module docstring.

    master: a master.py source (or any object with update(cycle), counts, counts_per_unit,
    position, velocity, acceleration). slave: the Axis that follows (its config gives
    counts_per_unit, shape and limits; its period the cycle time).
    numerator / denominator: slave counts per master counts (denominator > 0).
    """

    def __init__(self, master: Any, slave: Any, numerator: int, denominator: int) -> None:
        self.master = master
        self.slave = slave
        cfg = slave.config
        self._T = float(slave.period)
        self._cpu_m = float(master.counts_per_unit)
        self._cpu_s = float(cfg.counts_per_unit)
        if not (self._cpu_m > 0.0 and self._cpu_s > 0.0):
            raise GearError("master and slave counts_per_unit must be > 0")
        self._v_max = float(cfg.v_max)
        self._a_max = float(cfg.a_max)
        self._d_max = float(cfg.d_max if cfg.d_max is not None else cfg.a_max)
        self._j_max = None if cfg.j_max is None else float(cfg.j_max)
        self._shape = cfg.shape if cfg.shape is not None else ("jerk" if cfg.j_max is not None else "trapezoid")
        self._num = 0
        self._den = 1
        self._K = 0.0  # slave counts per master count
        self._R = 0.0  # slave units per master unit
        self._set_law(numerator, denominator)

        self._mode = _PENDING
        self._in_gear = False
        # integer law: position = (sc_ref + q + r/den) / cpu_s + offset
        self._mc_ref = 0
        self._sc_ref = 0
        self._offset = 0.0
        # ratio ramp: the old law below the ramp start, blend inside [x1, x1 + dc]
        self._ramping = False
        self._ramp_x1 = 0
        self._ramp_dc = 1
        self._ramp_dk = 0.0  # K_new - K_old
        self._ramp_dr = 0.0  # R_new - R_old
        self._old_num = 0
        self._old_den = 1
        self._old_mc_ref = 0
        self._old_sc_ref = 0
        self._old_offset = 0.0
        self._old_R = 0.0
        # catch-up (error domain, time): s = law + e(t)
        self._catch: Profile | None = None
        self._catch_c0 = 0
        # phasing (master units, time): the law sees master + phi(t)
        self._phase: Profile | None = None
        self._phase_c0 = 0
        self._phase_counts = 0  # target of the running phasing, master counts (not folded yet)
        self._phase_folded = 0  # phasing folded into the reference, master counts
        self._phi = 0.0  # phase of the last sample (running part), master units
        # gear in position (master domain)
        self._ap_pre: Profile | None = None
        self._ap_move: Profile | None = None
        self._ap_wait = 0.0
        self._ap_x0 = 0
        self._ap_scale = 1.0  # cpu_m * V: master counts per unit of tau
        self._ap_V = 1.0
        self._ap_xs = 0.0  # sync position in master counts (float)
        self._ap_dir = 1.0
        self._ap_started = False
        # geared out
        self._free: Profile | None = None
        self._free_c0 = 0
        # last sample
        self._cycle: int | None = None
        self._x = 0
        self._vm = 0.0
        self._q = 0
        self._p = 0.0
        self._v = 0.0
        self._a = 0.0

    @staticmethod
    def counts_ratio(ratio: int | str | Fraction, master_counts_per_unit: float, slave_counts_per_unit: float) -> tuple[int, int]:
        """(numerator, denominator) in counts for a ratio in user units (slave units per master unit).

        Exact: give the ratio as an int, a Fraction or a decimal string ("1.5", "16523/11872");
        a float is read as its decimal repr. The scales are read the same way.
        """

        def exact(name: str, x: Any) -> Fraction:
            if isinstance(x, bool):
                raise GearError(f"{name} must be a number, got {x!r}")
            try:
                return Fraction(repr(x)) if isinstance(x, float) else Fraction(x)
            except (TypeError, ValueError):
                raise GearError(f"{name} must be a number, got {x!r}") from None

        k = exact("ratio", ratio) * exact("slave_counts_per_unit", slave_counts_per_unit) / exact(
            "master_counts_per_unit", master_counts_per_unit
        )
        return k.numerator, k.denominator

    # ------------------------------------------------------------------ read-outs

    @property
    def numerator(self) -> int:
        return self._num

    @property
    def denominator(self) -> int:
        return self._den

    @property
    def ratio(self) -> float:
        """Slave units per master unit of the current law (the target of a running ratio ramp)."""
        return self._R

    @property
    def in_gear(self) -> bool:
        """Synchronised: the catch-up has ended (gear in) or the master passed the sync position."""
        return self._in_gear

    @property
    def engaged(self) -> bool:
        """The gear drives the slave from the master (coupled or approaching)."""
        return self._mode in (_COUPLED, _APPROACH) and self._cycle is not None

    @property
    def catching_up(self) -> bool:
        return self._catch is not None

    @property
    def ratio_ramping(self) -> bool:
        return self._ramping

    @property
    def phasing_active(self) -> bool:
        return self._phase is not None

    @property
    def phase(self) -> float:
        """Total shift of the master position seen by the slave, master units."""
        return self._phase_folded / self._cpu_m + self._phi

    @property
    def slave_counts(self) -> int:
        """Integer law of the last sample: slave_ref + (master - master_ref) * num // den.

        Without the catch-up and phasing transients and the sub-count `offset`."""
        return self._q

    @property
    def reference(self) -> tuple[int, int]:
        """(master_ref, slave_ref) counts of the integer law."""
        return self._mc_ref, self._sc_ref

    @property
    def offset(self) -> float:
        """Constant slave position added to the integer law, slave units."""
        return self._offset

    @property
    def position(self) -> float:
        """Slave set point of the last sample (p, v, a below likewise)."""
        return self._p

    @property
    def velocity(self) -> float:
        return self._v

    @property
    def acceleration(self) -> float:
        return self._a

    # ------------------------------------------------------------------ helpers

    def _set_law(self, numerator: int, denominator: int) -> None:
        n = _ratio_int("numerator", numerator)
        d = _ratio_int("denominator", denominator)
        if d <= 0:
            raise GearError(f"denominator must be > 0, got {d}")
        self._num = n
        self._den = d
        self._K = n / d
        self._R = n * self._cpu_m / (d * self._cpu_s)

    def _jerk(self) -> float | None:
        return self._j_max if self._shape != "trapezoid" else None

    def _reference_at(self, x: int, position: float) -> None:
        """Reference the integer law so that it gives `position` at master counts x."""
        sigma = position * self._cpu_s
        sc = math.floor(sigma)
        self._mc_ref = x
        self._sc_ref = sc
        self._offset = position - sc / self._cpu_s

    def _clear_transients(self) -> None:
        self._catch = None
        self._ramping = False
        self._phase = None
        self._phase_counts = 0
        self._phase_folded = 0
        self._phi = 0.0
        self._free = None
        self._ap_pre = self._ap_move = None
        self._ap_started = False

    # ------------------------------------------------------------------ commands

    def gear_in(self) -> Any:
        """MC_GearIn: couple the slave (slave.start_sync(self)); returns the axis' handle.

        The coupling is made from the slave's set point in the next cycle (module docstring).
        """
        cmd = self.slave.start_sync(self)
        if not cmd.error:
            self._clear_transients()
            self._mode = _PENDING
            self._in_gear = False
        return cmd

    def gear_out(self, halt: bool = False, deceleration: float | None = None) -> Any:
        """MC_GearOut: the slave leaves the master and keeps its velocity.

        halt=True also ends the synchronisation at once (slave.end_sync(deceleration)) and
        returns that halt handle; otherwise None, and `slave.end_sync()` halts later.
        """
        if not self.engaged:
            raise GearError("the gear is not engaged (gear_in first, and run a cycle)")
        a = self._a
        j = self._jerk()
        v_keep = self._v + (a * abs(a) / (2.0 * j) if j is not None else 0.0)
        v_keep = max(-self._v_max, min(self._v_max, v_keep))
        lim = Limits(v=max(self._v_max, abs(v_keep)), a=self._a_max, d=self._d_max, j=j)
        self._free = plan_velocity(self._shape, State(self._p, self._v, a), v_keep, lim)
        self._free_c0 = self._cycle  # type: ignore[assignment]
        self._catch = None
        self._phase = None
        self._ramping = False
        self._ap_pre = self._ap_move = None
        self._mode = _FREE
        self._in_gear = False
        if halt:
            return self.slave.end_sync(deceleration)
        return None

    def set_ratio(
        self,
        numerator: int,
        denominator: int,
        *,
        ramp_distance: float | None = None,
        ramp_time: float | None = None,
    ) -> None:
        """Change the ratio; while coupled with a ramp over a master distance or time (docstring)."""
        n = _ratio_int("numerator", numerator)
        d = _ratio_int("denominator", denominator)
        if d <= 0:
            raise GearError(f"denominator must be > 0, got {d}")
        if ramp_distance is not None and ramp_time is not None:
            raise GearError("give ramp_distance or ramp_time, not both")
        dist = 0.0 if ramp_distance is None else _number("ramp_distance", ramp_distance)
        rt = 0.0 if ramp_time is None else _number("ramp_time", ramp_time)
        if dist < 0.0 or rt < 0.0:
            raise GearError("ramp_distance and ramp_time must be >= 0")
        if self._mode == _APPROACH:
            raise GearError("the ratio cannot change while gearing in at a position")
        if self._mode != _COUPLED or self._cycle is None:
            self._set_law(n, d)  # not coupled: the ratio applies at the next coupling
            return
        if self._ramping:
            raise GearError("a ratio ramp is running; change the ratio again when it has ended")
        if self._phase is not None:
            raise GearError("phasing is running; change the ratio when it has ended")
        x1 = self._x
        if ramp_time is not None:
            dist = abs(self._vm) * rt
        dc = round(dist * self._cpu_m)
        if self._vm < 0.0:
            dc = -dc
        k_old = Fraction(self._num, self._den)
        k_new = Fraction(n, d)
        # exact slave count at the end of the ramp: old law at x1 + the blend's mean ratio * dc
        sigma_end = self._sc_ref + (x1 - self._mc_ref) * k_old + dc * (k_old + k_new) / 2
        sc_new = math.floor(sigma_end)
        offset_new = self._offset + float(sigma_end - sc_new) / self._cpu_s
        if dc != 0:
            self._old_num, self._old_den = self._num, self._den
            self._old_mc_ref, self._old_sc_ref, self._old_offset = self._mc_ref, self._sc_ref, self._offset
            self._old_R = self._R
            k_before = self._K
            r_before = self._R
            self._set_law(n, d)
            self._ramp_x1 = x1
            self._ramp_dc = dc
            self._ramp_dk = self._K - k_before
            self._ramp_dr = self._R - r_before
            self._ramping = True
        else:
            self._set_law(n, d)
        self._mc_ref = x1 + dc
        self._sc_ref = sc_new
        self._offset = offset_new

    def phasing(
        self,
        shift: float,
        velocity: float,
        acceleration: float,
        deceleration: float | None = None,
        jerk: float | None = None,
    ) -> None:
        """MC_Phasing: shift the master position seen by the slave by `shift` master units.

        velocity/acceleration/deceleration/jerk: limits of the shift profile in master
        units (jerk None with a jerk-limited slave shape: slave j_max / |ratio|).
        """
        s = _number("shift", shift)
        lim_v = _positive("velocity", velocity)
        lim_a = _positive("acceleration", acceleration)
        lim_d = lim_a if deceleration is None else _positive("deceleration", deceleration)
        if self._mode != _COUPLED or self._cycle is None:
            raise GearError("phasing needs a coupled gear (gear_in and run a cycle first)")
        if self._ramping:
            raise GearError("a ratio ramp is running; phase when it has ended")
        shape = self._shape
        j: float | None
        if jerk is not None:
            j = _positive("jerk", jerk)
            if shape == "trapezoid":
                shape = "jerk"
        elif shape != "trapezoid":
            if self._R == 0.0 or self._j_max is None:
                raise GearError("give the phasing jerk (the ratio is 0)")
            j = self._j_max / abs(self._R)
        else:
            j = None
        if self._phase is not None:
            phi, phi_v, phi_a, _ = self._phase.sample((self._cycle - self._phase_c0) * self._T)
        else:
            phi = phi_v = phi_a = 0.0
        target_counts = round((self._phase_counts / self._cpu_m + s) * self._cpu_m)
        target = target_counts / self._cpu_m
        try:
            prof = plan(shape, State(phi, phi_v, phi_a), State(target, 0.0), Limits(v=lim_v, a=lim_a, d=lim_d, j=j))
        except ValueError as e:
            raise GearError(f"phasing: {e}") from None
        self._phase = prof
        self._phase_c0 = self._cycle
        self._phase_counts = target_counts

    # ------------------------------------------------------------------ per cycle (hot path)

    def sample(self, cycle: int) -> tuple[float, float, float]:
        """Slave set point (p, v, a) of `cycle`, slave user units (SyncSource)."""
        m = self.master
        m.update(cycle)
        x = m.counts
        vm = m.velocity
        am = m.acceleration
        mode = self._mode
        if mode == _PENDING:
            self._couple(cycle, vm, am, x)
            mode = _COUPLED
        elif mode == _APPROACH:
            if (x - self._ap_xs) * self._ap_dir < 0.0:
                return self._approach(cycle, x, vm, am)
            self._mode = mode = _COUPLED  # the master passed the sync position: the law takes over
            self._ap_pre = self._ap_move = None
            self._in_gear = True
        elif mode == _FREE:
            assert self._free is not None
            p, v, a, _ = self._free.sample((cycle - self._free_c0) * self._T)
            return self._store(cycle, x, vm, p, v, a)

        T = self._T
        # phasing: fold a finished shift into the integer reference first (exact law)
        phi = phi_v = phi_a = 0.0
        prof = self._phase
        if prof is not None:
            t = (cycle - self._phase_c0) * T
            if t >= prof.duration:
                self._mc_ref -= self._phase_counts
                self._phase_folded += self._phase_counts
                self._phase_counts = 0
                self._phase = None
            else:
                phi, phi_v, phi_a, _ = prof.sample(t)
        self._phi = phi

        cpu_s = self._cpu_s
        if self._ramping:
            u = (x - self._ramp_x1) / self._ramp_dc
            if u >= 1.0:
                self._ramping = False
            else:
                qo, ro = divmod((x - self._old_mc_ref) * self._old_num, self._old_den)
                self._q = self._old_sc_ref + qo
                p = self._q / cpu_s + (ro / self._old_den) / cpu_s + self._old_offset
                if u <= 0.0:
                    v = self._old_R * vm
                    a = self._old_R * am
                else:
                    dc = self._ramp_dc
                    p += self._ramp_dk * dc * (u * u * u * (1.0 - 0.5 * u)) / cpu_s
                    r_u = self._old_R + self._ramp_dr * (u * u * (3.0 - 2.0 * u))
                    v = r_u * vm
                    xdot = vm * self._cpu_m
                    a = r_u * am + self._ramp_dk * (6.0 * u * (1.0 - u)) / dc * xdot * xdot / cpu_s
                return self._finish(cycle, x, vm, p, v, a)

        q, r = divmod((x - self._mc_ref) * self._num, self._den)
        self._q = self._sc_ref + q
        p = self._q / cpu_s + (r / self._den) / cpu_s + self._offset
        R = self._R
        v = R * (vm + phi_v)
        a = R * (am + phi_a)
        if phi != 0.0:
            p += R * phi
        return self._finish(cycle, x, vm, p, v, a)

    def _finish(self, cycle: int, x: int, vm: float, p: float, v: float, a: float) -> tuple[float, float, float]:
        """Add the catch-up term (folding it into the offset when it has ended) and store."""
        catch = self._catch
        if catch is not None:
            t = (cycle - self._catch_c0) * self._T
            e, ev, ea, _ = catch.sample(t)
            p += e
            v += ev
            a += ea
            if t >= catch.duration:
                self._offset += catch.target.p  # the offset gathered while catching up is kept
                if self._ramping:
                    self._old_offset += catch.target.p
                self._catch = None
                self._in_gear = True
        return self._store(cycle, x, vm, p, v, a)

    def _store(self, cycle: int, x: int, vm: float, p: float, v: float, a: float) -> tuple[float, float, float]:
        self._cycle = cycle
        self._x = x
        self._vm = vm
        self._p = p
        self._v = v
        self._a = a
        return p, v, a

    def _couple(self, cycle: int, vm: float, am: float, x: int) -> None:
        """Gear in on the fly from the slave's last set point (cycle - 1); see the docstring."""
        s = self.slave
        p0, v0, a0 = s.command_position, s.command_velocity, s.command_acceleration
        R = self._R
        T = self._T
        # the geared position continues the last set point: one cycle of master motion on
        self._reference_at(x, p0 + R * vm * T)
        self._clear_transients()
        self._mode = _COUPLED
        ev = v0 - R * vm
        ea = a0 - R * am
        if ev == 0.0 and ea == 0.0:
            self._in_gear = True
            return
        vt = R * vm
        if v0 * vt >= 0.0:
            lim_a = self._a_max if abs(vt) >= abs(v0) else self._d_max  # speeding up or slowing down
        else:
            lim_a = min(self._a_max, self._d_max)  # reversing: brake, then speed up
        lim = Limits(v=_BIG_SPEED, a=lim_a, d=lim_a, j=self._jerk())
        self._catch = plan_velocity(self._shape, State(0.0, ev, ea), 0.0, lim)
        self._catch_c0 = cycle - 1
        self._in_gear = False

    def _approach(self, cycle: int, x: int, vm: float, am: float) -> tuple[float, float, float]:
        """Gear in position: the master-domain move sampled at tau of the master position."""
        tau = (x - self._ap_x0) / self._ap_scale
        if tau < self._ap_wait:
            assert self._ap_pre is not None
            p, pv, pa, _ = self._ap_pre.sample(tau)
        else:
            assert self._ap_move is not None
            p, pv, pa, _ = self._ap_move.sample(tau - self._ap_wait)
            self._ap_started = True
        V = self._ap_V
        k = vm / V
        return self._store(cycle, x, vm, p, pv * k, pa * k * k + pv * am / V)
