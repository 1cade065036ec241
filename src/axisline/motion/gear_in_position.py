"""MC_GearInPos: a gear that reaches its sync state exactly when the master passes the sync
position (`GearInPos`), its feasibility check (`SyncCheck`) and error (`GearInPosError`).
After the sync it is an ordinary `Gear` (gear.py).

`GearInPos(master, slave, n, d, master_sync_position=m_sync, slave_sync_position=s_sync)`
makes the slave reach s = s_sync + ratio * (m - m_sync) with matching velocity exactly when
the master passes m_sync. The approach is planned in the master domain: its time variable
is tau = (m - m0) / V (m0: master position at `gear_in`, V: the nominal master speed, the
master's velocity then or `master_velocity`). In tau the slave waits, then makes the
time-optimal move of profiles.plan (the axis shape and limits, speed capped at `velocity`)
from its state to (s_sync, ratio * V), started so that it ends exactly at
tau_sync = (m_sync - m0) / V. Sampling the move at tau(m) of the actual master position
makes the synchronisation exact even when the master speed changes during the approach
(the slave's real speed and acceleration then scale with m'/V and (m'/V)^2). A slave that
is moving at the start coasts at its velocity (acceleration ramped out) before the move;
the start of the move is then found by bisection (the end time is monotonic in it).
When the master passes m_sync, the integer law takes over, referenced at the sync point.

Infeasible requests are reported before any motion: the constructor and `gear_in` raise
GearInPosError naming the master distance the slave needs and the distance available;
`check()` returns the same as a SyncCheck without raising.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from axisline.motion.gear import _APPROACH, Gear, GearError, _number, _positive
from axisline.motion.profiles import Limits, Profile, State, plan, plan_velocity

__all__ = ["GearInPos", "GearInPosError", "SyncCheck"]


class GearInPosError(GearError):
    """A gear-in-position request the slave cannot reach in the master distance left."""

    def __init__(self, text: str, needed: float, available: float) -> None:
        super().__init__(text)
        self.needed = needed
        self.available = available


@dataclass(frozen=True)
class SyncCheck:
    """Feasibility of a gear in position: master distances in master units (nan: n/a)."""

    feasible: bool
    needed: float
    available: float
    message: str = ""


@dataclass(frozen=True)
class _Approach:
    pre: Profile
    move: Profile
    wait: float
    x0: int
    V: float
    needed: float
    available: float


class GearInPos(Gear):
    """MC_GearInPos: reach s = s_sync + ratio * (m - m_sync) exactly when the master passes m_sync.

    master_sync_position / slave_sync_position: m_sync (master units), s_sync (slave units).
    velocity: speed cap of the approach move (None: the slave's v_max).
    master_velocity: nominal master speed of the master-domain plan (None: the master's
    velocity at gear_in; needed when the master stands at gear_in).
    acceleration / deceleration: limits of the approach move (None: the slave's a_max / d_max),
    for a controller whose ramps are its own parameters (the CLM's flying cutoff: Ax08).

    The constructor checks the request against the current master and slave state and
    raises GearInPosError when the slave cannot reach the sync state in the master
    distance left; `check()` answers without raising; `gear_in()` checks again, then
    couples (module docstring). After the sync it is an ordinary Gear.
    """

    def __init__(
        self,
        master: Any,
        slave: Any,
        numerator: int,
        denominator: int,
        *,
        master_sync_position: float,
        slave_sync_position: float,
        velocity: float | None = None,
        master_velocity: float | None = None,
        acceleration: float | None = None,
        deceleration: float | None = None,
    ) -> None:
        super().__init__(master, slave, numerator, denominator)
        if acceleration is not None:
            self._a_max = _positive("acceleration", acceleration)
        if deceleration is not None:
            self._d_max = _positive("deceleration", deceleration)
        self.master_sync_position = _number("master_sync_position", master_sync_position)
        self.slave_sync_position = _number("slave_sync_position", slave_sync_position)
        self.approach_velocity = None if velocity is None else _positive("velocity", velocity)
        self.master_velocity = None if master_velocity is None else _number("master_velocity", master_velocity)
        self._plan()  # raises when infeasible: reported before any motion

    @property
    def sync_started(self) -> bool:
        """PLCopen StartSync: the slave has begun its approach move."""
        return self._ap_started or self._in_gear

    def check(self) -> SyncCheck:
        """Feasibility from the current master and slave state (does not raise for infeasibility)."""
        try:
            ap = self._plan()
        except GearInPosError as e:
            return SyncCheck(False, e.needed, e.available, str(e))
        except GearError as e:
            return SyncCheck(False, math.nan, math.nan, str(e))
        return SyncCheck(True, ap.needed, ap.available)

    def gear_in(self) -> Any:
        """Plan the approach (GearInPosError before any motion), then couple the slave."""
        ap = self._plan()
        cmd = self.slave.start_sync(self)
        if cmd.error:
            return cmd
        self._clear_transients()
        self._in_gear = False
        # the law after the sync: s_sync at the (fractional) master count of m_sync
        xs = self.master_sync_position * self._cpu_m
        mc = math.floor(xs)
        sigma = self.slave_sync_position * self._cpu_s - self._K * (xs - mc)
        sc = math.floor(sigma)
        self._mc_ref = mc
        self._sc_ref = sc
        self._offset = (sigma - sc) / self._cpu_s
        self._ap_pre = ap.pre
        self._ap_move = ap.move
        self._ap_wait = ap.wait
        self._ap_x0 = ap.x0
        self._ap_V = ap.V
        self._ap_scale = self._cpu_m * ap.V
        self._ap_xs = xs
        self._ap_dir = 1.0 if ap.V > 0.0 else -1.0
        self._mode = _APPROACH
        return cmd

    def _plan(self) -> _Approach:
        m = self.master
        x0 = int(m.counts)
        vm = float(m.velocity)
        am = float(m.acceleration)
        V = self.master_velocity if self.master_velocity is not None else vm
        if V == 0.0:
            raise GearError(
                "gear in position: the master is at rest; give master_velocity (the nominal master speed of the approach)"
            )
        R = self._R
        v_sync = R * V
        v_lim = self._v_max if self.approach_velocity is None else min(self._v_max, self.approach_velocity)
        if abs(v_sync) > v_lim:
            raise GearError(
                f"gear in position: the sync velocity {v_sync:.6g} (ratio {R:.6g} x master {V:.6g}) exceeds "
                f"the slave's velocity limit {v_lim:.6g}"
            )
        sl = self.slave
        s0, v0, a0 = float(sl.command_position), float(sl.command_velocity), float(sl.command_acceleration)
        at_rest = v0 == 0.0 and a0 == 0.0
        if at_rest:
            v0t = a0t = 0.0
        elif vm == 0.0:
            raise GearError("gear in position: the slave moves while the master stands; bring the slave to rest first")
        else:
            # the slave's state in the master domain: ds/dtau = v * V/vm, d2s/dtau2 = (a - ds/dtau*am/V) (V/vm)^2
            k = V / vm
            v0t = v0 * k
            a0t = (a0 - v0t * am / V) * k * k
        j = self._jerk()
        lim = Limits(v=v_lim, a=self._a_max, d=self._d_max, j=j)
        start = State(s0, v0t, a0t)
        target = State(self.slave_sync_position, v_sync)
        sign = 1.0 if V > 0.0 else -1.0
        available = (self.master_sync_position - x0 / self._cpu_m) * sign
        tau_sync = available / abs(V)
        try:
            move0 = plan(self._shape, start, target, lim)
        except ValueError as e:
            raise GearError(f"gear in position: {e}") from None
        needed = move0.duration * abs(V)
        if tau_sync < move0.duration:
            raise GearInPosError(
                f"gear in position not feasible: the slave needs {needed:.6g} master units of travel to reach "
                f"the sync state (s = {self.slave_sync_position:g} at velocity {v_sync:.6g}), but only "
                f"{available:.6g} remain to the master sync position {self.master_sync_position:g} "
                f"(short by {needed - available:.6g})",
                needed,
                available,
            )
        if at_rest:
            pre = plan_velocity(self._shape, start, 0.0, lim)  # empty: the slave waits at s0
            return _Approach(pre, move0, tau_sync - move0.duration, x0, V, needed, available)
        # a moving slave coasts (acceleration ramped out) until the move starts; find that
        # start by bisection: w + duration(w) does not decrease (the coast is a feasible path)
        v_coast = v0t + (a0t * abs(a0t) / (2.0 * j) if j is not None else 0.0)
        v_coast = max(-v_lim, min(v_lim, v_coast))
        pre = plan_velocity(self._shape, start, v_coast, lim)

        def move_from(w: float) -> Profile:
            p, v, a, _ = pre.sample(w)
            return plan(self._shape, State(p, v, a), target, lim)

        lo, hi = 0.0, tau_sync
        best = move0
        for _ in range(200):
            mid = 0.5 * (lo + hi)
            if not lo < mid < hi:
                break
            mv = move_from(mid)
            if mid + mv.duration <= tau_sync:
                lo, best = mid, mv
            else:
                hi = mid
        if abs(lo + best.duration - tau_sync) > 1e-9 * max(tau_sync, 1e-3):
            raise GearError("gear in position: no approach ending exactly at the sync position was found")
        return _Approach(pre, best, tau_sync - best.duration, x0, V, needed, available)
