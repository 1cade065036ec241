"""The cam-curve interface every cam in axisline implements.

A curve gives the slave position as a function of the master position over one master
cycle, with its derivatives with respect to the master position:

    s, ds, dds, ddds = curve.eval(x)        # 0 <= x <= master_period (user units of the master)

Point tables, splines and cams built from motion laws (motion.cam, motion.segments) all
implement `CamCurve`; couplings (motion.camsync) and checks use only this interface.

Beyond one cycle the curve repeats (`at`): a closed curve returns to its start value, an
open curve (COMPAX "reset mode", a feed per cycle) adds its slave offset per master cycle
so the slave keeps moving forward. Slave velocity, acceleration and jerk in time follow
from the master's motion: v = ds * vm, a = dds * vm^2 + ds * am, j = ddds * vm^3 + 3 dds vm am + ds jm.
"""

from __future__ import annotations

import math
from abc import ABC, abstractmethod
from functools import cached_property

import numpy as np


class CamCurve(ABC):
    """Slave position as a function of master position over one master cycle.

    Curves are immutable once built (a scaled or edited curve is a new object), so derived
    values such as `cycle_offset` are computed once.
    """

    #: length of one master cycle (master user units), > 0
    master_period: float

    @abstractmethod
    def eval(self, x: float) -> tuple[float, float, float, float]:
        """(s, ds/dx, d2s/dx2, d3s/dx3) at 0 <= x <= master_period (scalar, hot path)."""

    def eval_array(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """Vectorised eval over one cycle (plots, checks); subclasses may override for speed."""
        out = np.array([self.eval(float(xi)) for xi in np.asarray(x, dtype=float).ravel()])
        if out.size == 0:
            out = np.zeros((0, 4))
        return out[:, 0], out[:, 1], out[:, 2], out[:, 3]

    @property
    def start(self) -> float:
        return self.eval(0.0)[0]

    @cached_property
    def cycle_offset(self) -> float:
        """Slave travel per master cycle: 0 for a closed curve, the feed for an open one."""
        return self.eval(self.master_period)[0] - self.eval(0.0)[0]

    @property
    def closed(self) -> bool:
        return abs(self.cycle_offset) <= 1e-12 * max(1.0, abs(self.start))

    def at(self, x: float) -> tuple[float, float, float, float]:
        """The curve continued over any master position: cycles repeat, open curves add their offset."""
        period = self.master_period
        k = math.floor(x / period)
        s, ds, dds, ddds = self.eval(x - k * period)
        return s + k * self.cycle_offset, ds, dds, ddds
