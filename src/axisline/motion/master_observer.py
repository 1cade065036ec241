"""A master's speed and acceleration for the slave's acceleration set point, free of count noise.

    obs = MasterObserver(period=0.001, bandwidth=60.0)   # rad/s
    obs.update(delta)            # once per cycle: the master increments counted in that cycle
    obs.start(delta)             # instead, in the cycle counting starts (at the encoder's speed)
    obs.velocity, obs.acceleration                      # increments / s, increments / s^2

Why: a master read from an encoder moves in whole increments. Its speed per cycle (increments
of the cycle / T) jumps by one increment per cycle, and the change of that speed per cycle
(what a finite difference calls the master acceleration) by one increment per T^2: with a
measuring wheel of 0.05 mm per increment and a 1 ms cycle that is 50 000 mm/s^2 of noise,
which the cam law a = s''(x) vm^2 + s'(x) am turns into +-7e4 deg/s^2 on a rotary knife (issue
16). The slave's position and speed set points keep the device's own per-cycle values; only
the acceleration (a trace value and the jerk computed from it) uses this estimate.

The estimate is a third-order tracking observer of the counted position (states p, v, a),
critically damped with all three poles at -bandwidth: each cycle

    p_pred = p + v T + a T^2/2,  v_pred = v + a T,  e = counted - p_pred
    p = p_pred + 3w T e,  v = v_pred + 3w^2 T e,  a = a + w^3 T e

A type-3 loop: it follows a constant master acceleration without a steady error (no lag on a
ramp), and a step of the acceleration settles within about 6/bandwidth. Quantisation noise q
(one increment) reaches the acceleration as about q·w^2 and the jerk as q·w^3, instead of
q/T^2 and q/T^3. Plain float arithmetic on the counted increments: deterministic.

Decisions:
1. bandwidth 30 rad/s (about 5 Hz, settling ~0.2 s) by default: the master of a cam (a line,
   a web) changes its acceleration over tenths of a second; the cam's own acceleration comes
   from the curve (s''·vm²) and is not delayed by it. Test:
   tests/test_plots_first_hour.py::test_compax_knife_acceleration_is_the_cam_law_not_count_noise.
2. A master that starts from standstill (no increment in the last cycle) or stops to it with
   a count the observer's prediction misses by more than 1.5 increments (quantisation explains
   up to one) changed its speed within the cycle (a gated count, a simulated or test master):
   it is taken at that speed at once, acceleration 0, instead of a transient of 0.2 s. A real
   wheel leaves standstill one increment at a time and is tracked. Test:
   tests/test_plots_first_hour.py::test_master_observer_takes_a_start_from_standstill_at_once.
"""

from __future__ import annotations

import math

__all__ = ["MasterObserver", "DEFAULT_BANDWIDTH"]

DEFAULT_BANDWIDTH = 30.0
"""rad/s: the observer's poles (see Decision 1)."""

STEP_INCREMENTS = 1.5
"""A start or stop by more than this many increments in one cycle is a step (Decision 2)."""


class MasterObserver:
    """Speed and acceleration of a counted master position (see the module docstring)."""

    def __init__(self, period: float, bandwidth: float = DEFAULT_BANDWIDTH) -> None:
        for name, value in (("period", period), ("bandwidth", bandwidth)):
            if isinstance(value, bool) or not isinstance(value, (int, float)) or not (math.isfinite(value) and value > 0):
                raise ValueError(f"{name} must be a finite number > 0, got {value!r}")
        if bandwidth * period >= 0.5:
            raise ValueError(f"bandwidth {bandwidth!r} rad/s is too high for a {period!r} s cycle (allowed < {0.5 / period:g})")
        self.period = float(period)
        w, t = float(bandwidth), float(period)
        self._k1, self._k2, self._k3 = 3.0 * w * t, 3.0 * w * w * t, w * w * w * t
        self.counted = 0.0  # sum of the deltas: the master position the observer tracks
        self.position = 0.0
        self.velocity = 0.0
        self.acceleration = 0.0
        self._still = True  # no increment in the last cycle

    def reset(self) -> None:
        """Start again from rest at the counted position (the master was stopped or re-preset)."""
        self.position = self.counted
        self.velocity = self.acceleration = 0.0

    def start(self, delta: float) -> None:
        """The master starts being counted in this cycle, with `delta` increments: it is taken at
        that speed at once (a gated count, e.g. COMPAX I16, starts at the encoder's speed; an
        observer starting from rest would show a long transient that the count does not have)."""
        self.counted += delta
        self.position = self.counted
        self.velocity = delta / self.period
        self.acceleration = 0.0
        self._still = delta == 0

    def update(self, delta: float) -> None:
        """One cycle: `delta` increments counted in it."""
        t = self.period
        a = self.acceleration
        v = self.velocity
        still = self._still
        self._still = now_still = delta == 0
        self.counted = counted = self.counted + delta
        if still != now_still and abs(delta - (v + 0.5 * a * t) * t) > STEP_INCREMENTS:
            # Decision 2: a start from or a stop to standstill in one cycle
            self.position = counted
            self.velocity = delta / t
            self.acceleration = 0.0
            return
        p = self.position + (v + 0.5 * a * t) * t
        e = counted - p
        self.position = p + self._k1 * e
        self.velocity = v + a * t + self._k2 * e
        self.acceleration = a + self._k3 * e
