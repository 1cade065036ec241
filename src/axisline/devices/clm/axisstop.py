"""Stopping, resuming and jogging a CLM axis (a part of `axis.ClmAxis`): PBK, Immediate Stop /
JST and the next Start, CPL, the jog keys of Manual.

    clm.stop_motion()        # PBK: brake with the current deceleration, the rest is dropped
    clm.immediate_stop()     # Immediate Stop / JST: brake, the rest is kept ...
    clm.resume()             # ... and the next Start goes on to the target
    clm.jog(+1)              # Manual: the jog key, once per cycle

The decisions are the axis': axis.py decisions 10, 12, 15, 18 and 19.
"""

from __future__ import annotations

from fractions import Fraction
from typing import Any

from axisline.motion.profiles import Limits, State, plan_velocity

__all__ = ["StopAndJog"]


class StopAndJog:
    """Mixed into `ClmAxis` (its state: the kernel axis, target, CON, jog, kept, blocked ...)."""

    axis: Any
    follower: Any
    _con: float | None
    _jog: int
    _kept: bool
    _blocked: bool
    _braking: bool
    _drive_on: bool
    _vjog: float
    _min: Fraction
    _max: Fraction
    _sac_shift: Fraction
    _linear: bool
    loop: Any

    def stop_motion(self) -> None:
        """PBK: brake with the current deceleration, the rest is ignored, CON off (L2219)."""
        if self._abort_homing():
            self._con = None
            self._jog = 0
            self._kept = self._blocked = False
            return
        self._con = None
        self._jog = 0
        self._kept = self._blocked = False
        self._target = self._brake()

    def immediate_stop(self) -> None:
        """Immediate Stop input / JST: brake, keep the remaining distance (L5879, L2077)."""
        if self._abort_homing():
            return
        if self._following:  # slave: the following ramps down, its activation stays (L1977)
            self.follower.hold()  # type: ignore[union-attr]
        if self._con is not None or self._jog:
            self.stop_motion()  # CON is switched off (L2077), a jog ends
            return
        if self._target is None or self.motion_done:
            return
        self._blocked = False
        self._kept = True
        self._brake()

    def resume(self) -> None:
        """The next Start: the kept remaining distance first."""
        if self.follower is not None:  # slave: synchronize again when on (L1978)
            self.follower.release()
        if self._kept:
            self._kept = False
            self._start()

    def _brake(self) -> Fraction | None:
        """Brake to rest with the current deceleration; returns where the set point stops."""
        ax = self.axis
        if not ax.powered:
            return None
        d, j = self.deceleration, self._jerk()
        if self._following:  # slave: only the own part brakes
            f = self.follower
            assert f is not None
            if f.own_done:
                return Fraction(f.u)
            self._braking = True
            return Fraction(f.own_velocity(0.0, d, d, j))
        if ax.command_velocity == 0.0 and ax.command_acceleration == 0.0 and ax.motion_ended:
            if ax.active_command is not None:
                ax.halt()
            return Fraction(ax.command_position)
        stop = self._stop_point(d, j)
        ax.move_velocity(0.0, acceleration=d, deceleration=d, jerk=j)
        self._braking = True
        return Fraction(stop)

    def _stop_point(self, d: float, j: float | None) -> float:
        """Where move_velocity(0, d, d, j) from the set point ends: the kernel's plan, mirrored."""
        ax = self.axis
        c = ax.config
        shape = c.shape if c.shape is not None else ("jerk" if c.j_max is not None else "trapezoid")
        if j is not None and shape == "trapezoid":
            shape = "jerk"
        jj = j if j is not None else c.j_max
        if jj is not None and c.j_max is not None:
            jj = min(jj, c.j_max)
        d_max = c.d_max if c.d_max is not None else c.a_max
        lim = Limits(v=c.v_max, a=min(d, c.a_max), d=min(d, d_max), j=jj if shape != "trapezoid" else None)
        prof = plan_velocity(shape, State(ax.command_position, ax.command_velocity, ax.command_acceleration), 0.0, lim)
        return prof.sample(prof.duration)[0]

    def clear_lag(self) -> None:
        """CPL: the set point becomes the actual position, once (decision 18)."""
        self._check()
        ax = self.axis
        self._con = None
        self._jog = 0
        self._kept = self._blocked = self._braking = False
        if ax.powered:
            ax.power(False)
            ax.power(True)
        self._target = Fraction(ax.actual_position)
        if self.follower is not None and self.follower.attached:  # slave: in the own part's frame
            self._target -= Fraction(self.follower.follow_position)
        self.loop.resync()

    def jog(self, direction: int) -> None:
        """Manual: -1 / 0 / +1 at Ax07 (decisions 15, 19); called every cycle with the keys."""
        if direction not in (-1, 0, 1):
            raise ValueError(f"jog direction is -1, 0 or +1, not {direction}")
        if direction == self._jog:
            return
        if direction == 0:
            self.stop_motion()
            return
        ax = self.axis
        if not (self._drive_on and ax.powered) or self.feed_roll_open:
            return  # nothing moves (Inhibit Operation, an open feed roll); asked again next cycle
        self._con = None
        self._kept = self._blocked = self._braking = False
        a, d, j = self.acceleration, self.deceleration, self._jerk()
        if self._following:  # slave jog keys: only the slave moves (L3495)
            self.follower.own_velocity(direction * self._vjog, a, d, j)  # type: ignore[union-attr]
            self._jog = direction
            self._target = None
            return
        if self._limits_apply():
            limit = (self._max if direction > 0 else self._min) + self._sac_shift
            if (Fraction(ax.command_position) - limit) * direction >= 0:
                self._jog = direction  # the key is dead at the limit (L4294, L4330)
                self._target = None
                return
            ax.move_absolute(float(limit), velocity=self._vjog, acceleration=a, deceleration=d, jerk=j)
        else:
            ax.move_velocity(direction * self._vjog, acceleration=a, deceleration=d, jerk=j)
        self._jog = direction
        self._target = None

    def _limits_apply(self) -> bool:
        return self._linear and self.homed
