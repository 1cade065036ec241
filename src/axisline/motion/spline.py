"""Cubic spline cam tables (`SplineTable`): C2 through the points, periodic, natural or clamped
ends. `axisline.motion.cam` is the place to import it from; its docstring describes it.
"""

from __future__ import annotations

import math
import os
from collections.abc import Sequence

import numpy as np

from axisline.motion.camtable import DEFAULT_MAX_POINTS, _KnotTable, _read_points_csv

__all__ = ["SplineTable"]

# ---------------------------------------------------------------------------------------
# cubic spline


def _solve_tridiagonal(lower: list[float], diag: list[float], upper: list[float], rhs: list[float]) -> list[float]:
    """Thomas algorithm; lower[0] and upper[-1] are ignored. Diagonally dominant systems only."""
    n = len(diag)
    c = [0.0] * n
    d = [0.0] * n
    c[0] = upper[0] / diag[0] if n > 1 else 0.0
    d[0] = rhs[0] / diag[0]
    for i in range(1, n):
        denom = diag[i] - lower[i] * c[i - 1]
        c[i] = upper[i] / denom if i < n - 1 else 0.0
        d[i] = (rhs[i] - lower[i] * d[i - 1]) / denom
    x = [0.0] * n
    x[-1] = d[-1]
    for i in range(n - 2, -1, -1):
        x[i] = d[i] - c[i] * x[i + 1]
    return x


def _solve_cyclic(lower: list[float], diag: list[float], upper: list[float], rhs: list[float]) -> list[float]:
    """Cyclic tridiagonal system: lower[0] is the top-right corner, upper[-1] the bottom-left.

    Small systems are assembled densely (the corners may coincide with the band); larger
    ones use the Sherman-Morrison correction of a plain tridiagonal solve, O(n).
    """
    n = len(diag)
    if n < 3:
        a = np.zeros((n, n))
        for i in range(n):
            a[i, i] += diag[i]
            a[i, (i - 1) % n] += lower[i]
            a[i, (i + 1) % n] += upper[i]
        return [float(v) for v in np.linalg.solve(a, np.asarray(rhs, dtype=float))]
    alpha = upper[-1]  # A[n-1, 0]
    beta = lower[0]  # A[0, n-1]
    gamma = -diag[0]
    d = list(diag)
    d[0] = diag[0] - gamma
    d[-1] = diag[-1] - alpha * beta / gamma
    y = _solve_tridiagonal(lower, d, upper, rhs)
    u = [0.0] * n
    u[0] = gamma
    u[-1] = alpha
    z = _solve_tridiagonal(lower, d, upper, u)
    # v = (1, 0, ..., 0, beta / gamma)
    vy = y[0] + beta / gamma * y[-1]
    vz = z[0] + beta / gamma * z[-1]
    factor = vy / (1.0 + vz)
    return [y[i] - factor * z[i] for i in range(n)]


class SplineTable(_KnotTable):
    """Cubic spline (C2) through the points; see the module doc for the end conditions."""

    def __init__(
        self,
        master: Sequence[float],
        slave: Sequence[float],
        periodic: bool,
        *,
        end_slopes: tuple[float, float] | None = None,
        max_points: int = DEFAULT_MAX_POINTS,
        equidistant: bool | None = None,
    ) -> None:
        self._set_knots(master, slave, max_points, equidistant)
        if periodic and end_slopes is not None:
            raise ValueError(
                "end_slopes apply to a non-periodic spline; a periodic one takes its end slopes from the wrap"
            )
        if end_slopes is not None:
            if len(end_slopes) != 2 or not all(math.isfinite(float(v)) for v in end_slopes):
                raise ValueError(f"end_slopes {end_slopes!r} not allowed: give two finite gradients (start, end)")
        self.periodic = bool(periodic)
        self.end_slopes = None if end_slopes is None else (float(end_slopes[0]), float(end_slopes[1]))
        second = self._second_derivatives()
        m, y = self.master, self.slave
        a, b, c, d = [], [], [], []
        for i in range(len(m) - 1):
            h = m[i + 1] - m[i]
            delta = (y[i + 1] - y[i]) / h
            a.append(y[i])
            b.append(delta - h * (2.0 * second[i] + second[i + 1]) / 6.0)
            c.append(second[i] / 2.0)
            d.append((second[i + 1] - second[i]) / (6.0 * h))
        self._a, self._b, self._c, self._d = tuple(a), tuple(b), tuple(c), tuple(d)
        h_last = m[-1] - m[-2]
        self._end = (
            y[-1],
            b[-1] + h_last * (2.0 * c[-1] + 3.0 * d[-1] * h_last),
            2.0 * c[-1] + 6.0 * d[-1] * h_last,
            6.0 * d[-1],
        )

    def _second_derivatives(self) -> list[float]:
        """dds at every knot (the spline's moments M_i)."""
        m, y = self.master, self.slave
        n = len(m)
        h = [m[i + 1] - m[i] for i in range(n - 1)]
        delta = [(y[i + 1] - y[i]) / h[i] for i in range(n - 1)]
        if self.periodic:
            k = n - 1  # unknowns M_0 .. M_{n-2}; M_{n-1} = M_0
            lower = [h[i - 1] for i in range(k)]  # h[-1] is the last interval: wraps
            diag = [2.0 * (h[i - 1] + h[i]) for i in range(k)]
            upper = [h[i] for i in range(k)]
            rhs = [6.0 * (delta[i] - delta[i - 1]) for i in range(k)]
            moments = _solve_cyclic(lower, diag, upper, rhs)
            return moments + [moments[0]]
        if n == 2 and self.end_slopes is None:
            return [0.0, 0.0]
        lower = [0.0] * n
        diag = [0.0] * n
        upper = [0.0] * n
        rhs = [0.0] * n
        for i in range(1, n - 1):
            lower[i] = h[i - 1]
            diag[i] = 2.0 * (h[i - 1] + h[i])
            upper[i] = h[i]
            rhs[i] = 6.0 * (delta[i] - delta[i - 1])
        if self.end_slopes is None:  # natural: M_0 = M_{n-1} = 0
            diag[0] = diag[-1] = 1.0
        else:  # clamped: s'(0) and s'(P) given
            ds0, ds1 = self.end_slopes
            diag[0], upper[0], rhs[0] = 2.0 * h[0], h[0], 6.0 * (delta[0] - ds0)
            lower[-1], diag[-1], rhs[-1] = h[-1], 2.0 * h[-1], 6.0 * (ds1 - delta[-1])
        return _solve_tridiagonal(lower, diag, upper, rhs)

    @classmethod
    def equidistant(
        cls,
        slave_values: Sequence[float],
        master_period: float,
        periodic: bool,
        *,
        end_slopes: tuple[float, float] | None = None,
        max_points: int = DEFAULT_MAX_POINTS,
    ) -> SplineTable:
        """Spline through equally spaced points (point k at k · master_period / (N − 1))."""
        master = cls._equidistant_master(len(slave_values), master_period)
        return cls(master, slave_values, periodic, end_slopes=end_slopes, max_points=max_points, equidistant=True)

    @classmethod
    def from_csv(
        cls,
        path: str | os.PathLike[str],
        periodic: bool,
        *,
        end_slopes: tuple[float, float] | None = None,
        max_points: int = DEFAULT_MAX_POINTS,
    ) -> SplineTable:
        master, slave = _read_points_csv(path, max_points)
        return cls(master, slave, periodic, end_slopes=end_slopes, max_points=max_points)

    def eval(self, x: float) -> tuple[float, float, float, float]:
        if x >= self._m_last:
            return self._end
        i = self.segment(x)
        t = x - self.master[i]
        b, c, d = self._b[i], self._c[i], self._d[i]
        return (
            self._a[i] + t * (b + t * (c + t * d)),
            b + t * (2.0 * c + 3.0 * d * t),
            2.0 * c + 6.0 * d * t,
            6.0 * d,
        )

    def eval_array(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        x = np.asarray(x, dtype=float).ravel()
        idx = self._segments(x)
        t = x - np.asarray(self.master)[idx]
        a = np.asarray(self._a)[idx]
        b = np.asarray(self._b)[idx]
        c = np.asarray(self._c)[idx]
        d = np.asarray(self._d)[idx]
        s = a + t * (b + t * (c + t * d))
        ds = b + t * (2.0 * c + 3.0 * d * t)
        dds = 2.0 * c + 6.0 * d * t
        ddds = 6.0 * d
        end = x >= self._m_last
        s = np.where(end, self._end[0], s)
        return s, ds, dds, ddds

    def check_points(self) -> np.ndarray:
        """Knots plus, per interval, where ds has its extreme (dds = 0 inside the interval)."""
        points = list(self.master)
        for i in range(len(self.master) - 1):
            c, d = self._c[i], self._d[i]
            if d != 0.0:
                t = -c / (3.0 * d)
                if 0.0 < t < self.master[i + 1] - self.master[i]:
                    points.append(self.master[i] + t)
        return np.asarray(points)

    def __repr__(self) -> str:
        kind = "periodic" if self.periodic else ("clamped" if self.end_slopes else "natural")
        return f"SplineTable({len(self)} points, {kind}, master_period={self.master_period!r})"
