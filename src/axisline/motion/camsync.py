"""Cam coupling: a slave that follows a cam curve of a master, coupling and decoupling on the fly.

`CamFollower` is a sync source for `Axis.start_sync`: each cycle it reads the master
(any object with `position`, `velocity`, `acceleration` updated before the slaves sample,
see motion.master) and gives the slave set point from the curve:

    s = curve(x),  v = s'(x) vm,  a = s''(x) vm^2 + s'(x) am,   x = master position - master_offset

Coupling and decoupling happen in the master domain, as on a mechanical cam or the COMPAX
cam controller (compax.md §2.11): the slave, at rest at s0, starts moving when the master
passes the coupling position M_E and is on the curve, with the curve's velocity and
acceleration, at the synchronous position M_S; decoupling starts at M_A and brings the
slave to rest at the standstill position S_0 at the braking position M_B. In between, the
set point is a blend with a 5th-order smooth step h(u) (h, h', h'' are 0 at u = 0 and
h = 1, h' = h'' = 0 at u = 1):

    coupling:   s = s0 + (curve(x) - s0) h(u),        u = (x - x_E) / (M_S - M_E)
    decoupling: s = curve(x) + (S_0 - curve(x)) h(u),  u = (x - x_A) / (M_B - M_A)

so position, velocity and acceleration are continuous at both ends whatever the master
speed (a master that slows down slows the coupling with it).

Acceleration set point (issue 16): an encoder master (motion.master.EncoderMaster) moves in
whole counts, and the change of its counted speed per cycle is count noise (one count per
cycle squared); the follower takes vm and am of the acceleration from an observer of the
counts (motion.master_observer), position and velocity stay the master's own. On a point
table, whose interpolation puts the acceleration into impulses at the points, s'' is the set
points' second difference (PointTable.set_point_acceleration). Test:
tests/test_plots_first_hour.py::test_cam_follower_on_a_wheel_has_the_laws_acceleration. Positions M_E, M_S, M_A, M_B
are positions within the master cycle; the coupling starts at the next time the master
passes M_E going forward.
"""

from __future__ import annotations

import math
from enum import Enum
from typing import Protocol

from .curve import CamCurve
from .master import EncoderMaster
from .master_observer import MasterObserver


class MasterReading(Protocol):
    """What a cam follower reads of its master (motion.master implements it)."""

    @property
    def position(self) -> float: ...

    @property
    def velocity(self) -> float: ...

    @property
    def acceleration(self) -> float: ...


class CamState(Enum):
    WAITING = "waiting for the coupling position"
    COUPLING = "coupling"
    SYNCHRONOUS = "synchronous"
    DECOUPLING = "decoupling"
    DECOUPLED = "decoupled"


def smooth_step(u: float) -> tuple[float, float, float]:
    """h, dh/du, d2h/du2 of 10u^3 - 15u^4 + 6u^5, clamped to [0, 1]."""
    if u <= 0.0:
        return 0.0, 0.0, 0.0
    if u >= 1.0:
        return 1.0, 0.0, 0.0
    u2 = u * u
    return u2 * u * (10.0 + u * (-15.0 + 6.0 * u)), 30.0 * u2 * (1.0 - u) ** 2, 60.0 * u * (1.0 - u) * (1.0 - 2.0 * u)


def _next_crossing(x: float, pos: float, period: float) -> float:
    """The first master position >= x whose place in the cycle is `pos`."""
    k = math.ceil((x - pos) / period - 1e-12)
    return pos + k * period


class CamFollower:
    """Slave set points from a cam curve of a master, with coupling and decoupling on the fly.

    master: read each cycle (position, velocity, acceleration), already updated for the cycle.
    curve: the cam (motion.curve.CamCurve); the slave position is curve.at(x), continued
        over master cycles (open curves add their slave offset per cycle).
    master_offset: master position that corresponds to curve position 0 (COMPAX SETM).
    slave_offset: added to the curve value (COMPAX SETS, "automatic curve adjustment").
    """

    def __init__(self, master: MasterReading, curve: CamCurve, *, master_offset: float = 0.0, slave_offset: float = 0.0) -> None:
        for name, value in (("master_offset", master_offset), ("slave_offset", slave_offset)):
            if not math.isfinite(value):
                raise ValueError(f"{name} must be finite, got {value!r}")
        self.master = master
        # masters of motion.master update once per cycle however many slaves read them
        self._update_master = getattr(master, "update", None)
        self.curve = curve
        self.master_offset = float(master_offset)
        self.slave_offset = float(slave_offset)
        self.state = CamState.SYNCHRONOUS
        self._s0 = 0.0  # coupling start / decoupling stop position of the slave
        self._x0 = self._x1 = 0.0  # master span of the blend (unbounded master coordinates)
        self._waiting_for = 0.0  # master position where the pending blend starts
        self._pending: tuple[float, float] | None = None  # decoupling span waiting for M_A
        self._stop = 0.0  # where the pending decoupling stops the slave
        self.p = self.v = self.a = 0.0
        # an encoder master moves in whole counts: the acceleration set point takes its speed and
        # acceleration from an observer of the counts, not from their differences (issue 16)
        self._observer: MasterObserver | None = None
        self._counts = 0
        if isinstance(master, EncoderMaster):
            self._observer = MasterObserver(master.period)
            self._counts = master.counts
        # a point table's set points: its acceleration between them (PointTable.set_point_acceleration)
        self._point_acc = getattr(curve, "set_point_acceleration", None)

    # -- the curve in slave units ------------------------------------------------------

    def curve_state(self, x: float) -> tuple[float, float, float]:
        """(s, ds/dx, d2s/dx2) of the curve at master coordinate x (offsets applied)."""
        s, ds, dds, _ = self.curve.at(x)
        return s + self.slave_offset, ds, dds

    def master_x(self) -> float:
        return self.master.position - self.master_offset

    # -- commands ------------------------------------------------------------------------

    def couple(self, slave_position: float, coupling: float | None = None, synchronous: float | None = None) -> None:
        """Couple a slave at rest at `slave_position`.

        coupling/synchronous (M_E, M_S, positions in the master cycle, M_E < M_S): wait for the
        master to pass M_E, blend, synchronous at M_S. Both None: adjust the curve so that the
        slave is on it where it stands (the slave does not move: COMPAX M_E = M_S = 0).
        A synchronous position below the coupling position lies in the next master cycle.
        """
        x = self.master_x()
        if coupling is None and synchronous is None:
            s, _, _ = self.curve_state(x)
            self.slave_offset += slave_position - s
            self.state = CamState.SYNCHRONOUS
            return
        if coupling is None or synchronous is None:
            raise ValueError("give both the coupling and the synchronous position, or neither")
        period = self.curve.master_period
        for name, value in (("coupling position", coupling), ("synchronous position", synchronous)):
            if not (math.isfinite(value) and 0.0 <= value < period):
                raise ValueError(f"{name} {value!r} must lie in the master cycle [0, {period:g})")
        span = (synchronous - coupling) % period
        if span == 0.0:
            raise ValueError("coupling and synchronous position must differ (a jump coupling has no blend)")
        self._s0 = float(slave_position)
        self._x0 = _next_crossing(x, coupling, period)
        self._x1 = self._x0 + span
        self.state = CamState.WAITING
        self.p, self.v, self.a = self._s0, 0.0, 0.0

    def decouple(self, decoupling: float, braking: float, standstill: float) -> None:
        """Leave the curve: from the master's next pass of M_A blend to rest at S_0 at M_B.

        standstill (S_0) is a slave position within the slave cycle of the curve; on an open
        curve (a feed per cycle) the slave stops at the repetition of S_0 nearest to where the
        curve is at M_B, so decoupling never turns the slave back a whole cycle.
        """
        period = self.curve.master_period
        for name, value in (("decoupling position", decoupling), ("braking position", braking)):
            if not (math.isfinite(value) and 0.0 <= value < period):
                raise ValueError(f"{name} {value!r} must lie in the master cycle [0, {period:g})")
        if not math.isfinite(standstill):
            raise ValueError(f"standstill position must be finite, got {standstill!r}")
        span = (braking - decoupling) % period
        if span == 0.0:
            raise ValueError("decoupling and braking position must differ")
        x0 = _next_crossing(self.master_x(), decoupling, period)
        self._pending = (x0, x0 + span)
        # an open curve advances its offset every cycle: S_0 repeats with it, and the slave
        # stops at the repetition nearest to where the curve is at M_B (no turn backwards)
        stop = standstill + self.slave_offset
        offset = self.curve.cycle_offset
        if offset != 0.0:
            stop += round((self.curve_state(x0 + span)[0] - stop) / offset) * offset
        self._stop = stop

    @property
    def synchronous(self) -> bool:
        """On the curve (COMPAX O16)."""
        return self.state is CamState.SYNCHRONOUS

    # -- per cycle -----------------------------------------------------------------------

    def sample(self, cycle: int) -> tuple[float, float, float]:
        if self._update_master is not None:
            self._update_master(cycle)
        m = self.master
        x = m.position - self.master_offset
        vm, am = m.velocity, m.acceleration
        va, aa = vm, am  # master speed and acceleration for the acceleration set point
        obs = self._observer
        if obs is not None:
            counts = m.counts
            obs.update(counts - self._counts)
            self._counts = counts
            cpu = m.counts_per_unit
            va, aa = obs.velocity / cpu, obs.acceleration / cpu
        state = self.state
        if self._pending is not None and state is CamState.SYNCHRONOUS and x >= self._pending[0]:
            self._x0, self._x1 = self._pending
            self._pending = None
            self._s0 = self._stop
            state = self.state = CamState.DECOUPLING
        if state is CamState.WAITING:
            if x < self._x0:
                return self._s0, 0.0, 0.0
            state = self.state = CamState.COUPLING
        if state is CamState.DECOUPLED:
            return self._s0, 0.0, 0.0
        s, ds, dds = self.curve_state(x)
        if self._point_acc is not None:
            period = self.curve.master_period
            dds = self._point_acc(x - math.floor(x / period) * period)
        if state is CamState.SYNCHRONOUS:
            p, dp, ddp = s, ds, dds
        else:
            length = self._x1 - self._x0
            h, dh, ddh = smooth_step((x - self._x0) / length)
            dh /= length
            ddh /= length * length
            if state is CamState.COUPLING:  # s0 + (s - s0) h
                d = s - self._s0
                p = self._s0 + d * h
                dp = ds * h + d * dh
                ddp = dds * h + 2.0 * ds * dh + d * ddh
                if x >= self._x1:
                    self.state = CamState.SYNCHRONOUS
            else:  # decoupling: s + (stop - s) h
                d = self._s0 - s
                p = s + d * h
                dp = ds + (-ds) * h + d * dh
                ddp = dds - dds * h - 2.0 * ds * dh + d * ddh
                if x >= self._x1:
                    self.state = CamState.DECOUPLED
                    p, dp, ddp = self._s0, 0.0, 0.0
        # chain rule: master coordinate -> time
        self.p, self.v, self.a = p, dp * vm, ddp * va * va + dp * aa
        return self.p, self.v, self.a
