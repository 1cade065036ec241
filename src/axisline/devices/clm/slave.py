"""Slave axis / synchronous axis (Ax00 modes 1 and 2, FOL; manual L1951-1979, §7.6 L3475-3499).

    f = Follower(clm_axis, mode=2, master=1)   # made by ClmAxis.configure for Ax00 mode 1/2
    f.fol(on=True, ramp=True, factor=Fraction(3, 2))   # FOL 2 1 2 1.500000

While the slave's drive is on the kernel axis is in SynchronizedMotion on this source; its
set point is the sum of two parts:

    p = F + U
    F  the following part: F_base + the kernel's integer Gear (master counts x factor, the
       law referenced at coupling: no drift) + E, a velocity ramp in the error domain (mode 2)
    U  the slave's own positionings (POI/PSI/POA/PSA/CON/jog), planned here in the U frame
       (the axis frame less F): "additive in terms of velocity" (L1965).

The Gear gets a stand-in slave (`_LawSlave`) whose catch-up is instantaneous: the Gear only
supplies the exact law, the ramps are the CLM's (ACC / Ax08-Ax09), planned here.

Decisions (spec line -> choice, why)
------------------------------------
1. Ax00 mode 1 "same movements as the master axis" (L4190) -> follows the master axis' set
   point (AxisMaster "command"); mode 2 "follows the actual position" -> its actual position.
   test_slave_follows_master_travel_times_factor_exactly, test_synchronous_axis_follows_the_set_point.
2. Master 5 (master encoder 1, L3481 C000-C003) -> the simulated plant has no master encoder
   for the CLM (as override.py decision 11): no following; FOL on such an axis stops with 0A
   "comes with the master encoders". Not tested yet (needs C000-C003 set up).
3. FOL on an axis that is not Ax00 mode 1/2 -> no function, the program proceeds after one
   cycle: "The 'FOL' command is only effective if Slave Axis / Synchronous Axis Mode is
   enabled" (L3489). test_fol_on_a_normal_axis_does_nothing.
4. The on/off state before any FOL -> on: "If Slave Axis / Synchronous Axis Mode is enabled,
   the slave axis executes all movements synchronously with the master axis" (L3477); FOL
   turns it off. Defaults after Parameter mode or an error acknowledge: on, mode 1, factor
   1.000000 (L1967); a Manual <-> Automatic change keeps all three (L1969).
   test_defaults_and_manual_automatic_keep_fol.
5. Slave travel = master travel (IU) x factor (Fig. 5-14, L1961) -> Gear ratio in counts from
   the exact factor f.ffffff and the two axes' counts per IU (Gear.counts_ratio); each
   coupling references the law again. test_slave_follows_master_travel_times_factor_exactly.
6. Mode 1 on/off/factor "with no ramp" (L1971) -> the following velocity steps (position
   continuous); mode 2 (L1973-1975) -> on/off and a factor change ramp the following
   velocity with the slave's ACC acceleration / deceleration (Ax09 per mille of Ax08); the
   distance the ramp loses is not made up ("without phase adjustment", L4190).
   test_mode_2_ramps_on_and_off, test_factor_change_resynchronizes.
7. POI/PSI/POA/PSA/CON/jog of the slave (L1965, L3491-3497) -> the own part U: targets of the
   ClmAxis are in the U frame (POI adds L x FAK to the last U target); in position (PSI/PSA,
   Ax27) = U's move ended at its target: the actual position cannot be split into its own and
   its following part, and the following's lag (v / Kv behind a running master) is the Ax14
   monitoring's. test_poi_on_the_slave_adds.
8. Immediate Stop (L1977) -> the following ramps down with the deceleration, the activation
   state stays; the next Start ramps it on again when it was on. Not tested yet.
"""

from __future__ import annotations

from fractions import Fraction
from types import SimpleNamespace
from typing import Any

from axisline.motion.axis import AxisState
from axisline.motion.gear import Gear
from axisline.motion.master import AxisMaster
from axisline.motion.profiles import Limits, Profile, State, plan, plan_velocity

from .errors import ClmError

__all__ = ["Follower"]

_BIG = 1e15  # limits that never bind


class _LawSlave:
    """What Gear reads of its slave: counts per unit and period; at rest at 0, unlimited ramps
    (the Gear's catch-up is instantaneous; the CLM ramps are Follower's)."""

    def __init__(self, axis: Any) -> None:
        self.config = SimpleNamespace(counts_per_unit=axis.config.counts_per_unit, v_max=_BIG, a_max=_BIG,
                                      d_max=None, j_max=None, shape="trapezoid")
        self.period = axis.period
        self.command_position = self.command_velocity = self.command_acceleration = 0.0


class Follower:
    """The SyncSource of one slave / synchronous axis; see the module docstring."""

    def __init__(self, clm: Any, mode: int, master: int) -> None:
        self.clm = clm
        self.axis = clm.axis
        self.mode = mode  # Ax00: 1 synchronous (master set point), 2 slave (master actual)
        self.master_number = master
        self._T = float(self.axis.period)
        self.defaults()
        self._attached = False
        self._gear: Gear | None = None
        self._fbase = 0.0  # F without the gear and the ramp
        self._ramp: Profile | None = None  # E (error domain) or, geared out, the whole F - F_base
        self._ramp_c0 = 0
        self._f = (0.0, 0.0, 0.0)  # F of the last sample
        self._vm = 0.0
        self._u = (0.0, 0.0, 0.0)  # U of the last sample
        self._own: Profile | None = None
        self._own_c0 = 0
        self._held = False  # Immediate Stop: following ramped down, activation kept

    # ------------------------------------------------------------------ FOL

    def defaults(self) -> None:
        """Leaving Parameter mode, an error acknowledge: on, mode 1, factor 1 (decision 4)."""
        self.on = True
        self.ramped = False
        self.factor = Fraction(1)
        if getattr(self, "_attached", False):
            self._gear_out(ramp=False)
            self._gear_in(ramp=False)

    def fol(self, on: bool, ramp: bool, factor: Fraction) -> None:
        if self.master_number == 5:
            raise ClmError("0A", "FOL with master encoder 1 needs a master encoder on the plant: it comes with the master encoders")
        changed = factor != self.factor
        self.ramped, self.factor = ramp, factor
        if on != self.on:
            self.on = on
            if self._attached and not self._held:
                self._gear_in(ramp) if on else self._gear_out(ramp)
        elif on and changed and self._gear is not None:
            self._set_factor(ramp)

    @property
    def synchronous(self) -> bool:
        """M1.x0.0: following the master at the set factor (no ramp running)."""
        return self._gear is not None and self._ramp is None

    # ------------------------------------------------------------------ kernel coupling

    def attach(self) -> None:
        """The drive is on (or the axis free again): take over the kernel axis' set point."""
        ax = self.axis
        self._f = (self._f[0], 0.0, 0.0)
        self._fbase = self._f[0]
        self._ramp = None
        self._gear = None
        self._own = None
        self._u = (ax.command_position - self._fbase, 0.0, 0.0)
        self._cycle = None
        if ax.start_sync(self).error:
            return
        self._attached = True
        if self.on and not self._held:
            self._gear_in(self.ramped)

    def detach(self) -> None:
        self._attached = False
        self._gear = None
        self._ramp = None
        self._own = None

    def keep(self) -> None:
        """Once per NC cycle with the drive on: re-attach after CPL / homing left the sync."""
        ax = self.axis
        if ax.state is not AxisState.SYNCHRONIZED_MOTION and ax.state not in (AxisState.HOMING, AxisState.ERROR_STOP):
            self.attach()

    def _master(self) -> Any:
        peer = self.clm.peers.get(self.master_number)
        if peer is None:
            raise ClmError("0A", f"axis {self.clm.number} follows axis {self.master_number}, which the machine file does not give the CLM")
        return AxisMaster(peer.axis, "command" if self.mode == 1 else "actual")

    def _ratio(self, master: Any) -> tuple[int, int]:
        return Gear.counts_ratio(self.factor, master.counts_per_unit, self.axis.config.counts_per_unit)

    def _gear_in(self, ramp: bool) -> None:
        if self.master_number == 5:  # no master encoder on the plant (decision 2)
            return
        master = self._master()
        n, d = self._ratio(master)
        self._fbase = self._f[0]
        self._gear = Gear(master, _LawSlave(self.axis), n, d)  # couples in its first sample
        self._ramp = None
        if ramp:  # E from (0, -ratio x vm) to velocity 0 with the ACC acceleration (decision 6)
            v_target = float(self.factor) * master.velocity
            self._start_ramp(State(0.0, -v_target, 0.0), self.clm.acceleration)

    def _gear_out(self, ramp: bool) -> None:
        p, v, a = self._f
        self._gear = None
        self._fbase = p
        self._ramp = None
        if ramp and (v or a):  # F itself brakes to rest (the ramp holds all of F - F_base)
            self._start_ramp(State(0.0, v, a), self.clm.deceleration)

    def _set_factor(self, ramp: bool) -> None:
        gear = self._gear
        assert gear is not None
        old = gear.ratio
        gear.set_ratio(*self._ratio(gear.master))
        if ramp:
            e, ev, ea = self._ramp_state()
            self._start_ramp(State(e, ev + (old - gear.ratio) * self._vm, ea), self.clm.acceleration)

    def _start_ramp(self, s: State, accel: float) -> None:
        self._ramp = plan_velocity("trapezoid", s, 0.0, Limits(v=_BIG, a=accel, d=accel))
        self._ramp_c0 = self._now()

    def _ramp_state(self) -> tuple[float, float, float]:
        if self._ramp is None or self._cycle is None:
            return 0.0, 0.0, 0.0
        p, v, a, _ = self._ramp.sample((self._cycle - self._ramp_c0) * self._T)
        return p, v, a

    # ------------------------------------------------------------------ Immediate Stop / Start

    def hold(self) -> None:
        """Immediate Stop / Interrupt: the following ramps down, the activation stays (L1977)."""
        if self._attached and not self._held:
            self._held = True
            if self._gear is not None:
                self._gear_out(True)

    def release(self) -> None:
        """Start after an Immediate Stop: synchronize again when on (L1978)."""
        if self._held:
            self._held = False
            if self._attached and self.on:
                self._gear_in(True)

    # ------------------------------------------------------------------ the own part U

    @property
    def attached(self) -> bool:
        return self._attached

    @property
    def u(self) -> float:
        return self._u[0]

    @property
    def follow_position(self) -> float:
        return self._f[0]

    @property
    def own_done(self) -> bool:
        return self._own is None and self._u[1] == 0.0

    def own_move(self, goal: float, speed: float, accel: float, decel: float, jerk: float | None) -> None:
        c = self.axis.config
        shape = "jerk" if jerk is not None else "trapezoid"
        self._own = plan(shape, State(*self._u), State(goal, 0.0), Limits(v=min(speed, c.v_max), a=accel, d=decel, j=jerk))
        self._own_c0 = self._now()

    def own_velocity(self, velocity: float, accel: float, decel: float, jerk: float | None) -> float:
        """CON / jog / braking (velocity 0); returns where a stop ends (velocity 0)."""
        shape = "jerk" if jerk is not None else "trapezoid"
        prof = plan_velocity(shape, State(*self._u), velocity, Limits(v=_BIG, a=accel, d=decel, j=jerk))
        self._own = prof
        self._own_c0 = self._now()
        return prof.sample(prof.duration)[0]

    def _now(self) -> int:
        if self._cycle is not None:
            return self._cycle  # the last sampled cycle: a new plan starts from its state
        last = self.axis._cycle
        return 0 if last is None else last

    # ------------------------------------------------------------------ per cycle (SyncSource)

    _cycle: int | None = None

    def sample(self, cycle: int) -> tuple[float, float, float]:
        T = self._T
        # F: base + law + ramp
        p = self._fbase
        v = a = 0.0
        gear = self._gear
        if gear is not None:
            gp, gv, ga = gear.sample(cycle)
            p += gp
            v += gv
            a += ga
            self._vm = gear.master.velocity
        ramp = self._ramp
        if ramp is not None:
            t = (cycle - self._ramp_c0) * T
            e, ev, ea, _ = ramp.sample(t)
            p += e
            v += ev
            a += ea
            if t >= ramp.duration:
                self._fbase += ramp.target.p
                self._ramp = None
        self._f = (p, v, a)
        # U: the own positionings
        own = self._own
        if own is not None:
            t = (cycle - self._own_c0) * T
            up, uv, ua, _ = own.sample(t)
            if t >= own.duration and own.target.v == 0.0:  # a move / stop ended (CON keeps running)
                uv = ua = 0.0
                self._own = None
            self._u = (up, uv, ua)
        self._cycle = cycle
        u = self._u
        return p + u[0], v + u[1], a + u[2]
