"""Mark capture (registration.py describes the whole): where a mark was, from a sensor edge
between two cycles, on each channel"s motion within the cycle.
"""

from __future__ import annotations

import math
from typing import NamedTuple, Protocol

from axisline.motion.registration_common import _FRACTION_TOLERANCE, _check_finite, _check_positive

__all__ = ["CapturedMark", "ChannelMotion", "MarkCapture"]


class ChannelMotion:
    """Position (and optionally velocity) of one channel at the start and end of the last cycle.

    Call :meth:`advance` once per cycle with the position at the cycle's end (the end becomes
    the next start). Inside the cycle the position is interpolated:

    - linear when no velocities are known (exact at constant velocity);
    - quadratic through start position, start velocity and end position when only the start
      velocity is known;
    - cubic Hermite through both positions and both velocities when both are known. A motion of
      constant acceleration is a quadratic, which the cubic reproduces exactly, so a mark is
      captured exactly while the line accelerates.
    """

    __slots__ = ("start", "end", "v_start", "v_end")

    def __init__(self, position: float = 0.0, velocity: float | None = None) -> None:
        self.start = float(position)
        self.end = float(position)
        v = math.nan if velocity is None else float(velocity)
        self.v_start = v
        self.v_end = v

    def advance(self, position: float, velocity: float | None = None) -> None:
        """End of a cycle: the old end becomes the start; ``position`` is the new end."""
        self.start = self.end
        self.v_start = self.v_end
        self.end = float(position)
        self.v_end = math.nan if velocity is None else float(velocity)

    def shift(self, distance: float) -> None:
        """Move both ends by ``distance`` (the frame was re-based, e.g. a counter was set)."""
        self.start += distance
        self.end += distance

    def _coefficients(self, period: float) -> tuple[float, float, float, float]:
        """p(s) = c0 + c1 s + c2 s^2 + c3 s^3 over the cycle, s = fraction 0..1."""
        p0, p1 = self.start, self.end
        d = p1 - p0
        if math.isnan(self.v_start):
            return p0, d, 0.0, 0.0
        m0 = self.v_start * period
        if math.isnan(self.v_end):
            return p0, m0, d - m0, 0.0
        m1 = self.v_end * period
        return p0, m0, 3.0 * d - 2.0 * m0 - m1, -2.0 * d + m0 + m1

    def position_at(self, fraction: float, period: float) -> float:
        c0, c1, c2, c3 = self._coefficients(period)
        s = fraction
        return c0 + s * (c1 + s * (c2 + s * c3))

    def velocity_at(self, fraction: float, period: float) -> float:
        _, c1, c2, c3 = self._coefficients(period)
        s = fraction
        return (c1 + s * (2.0 * c2 + 3.0 * s * c3)) / period

    def acceleration_at(self, fraction: float, period: float) -> float:
        _, _, c2, c3 = self._coefficients(period)
        return (2.0 * c2 + 6.0 * fraction * c3) / (period * period)


class CapturedMark(NamedTuple):
    """Where the channels were when a mark passed the sensor (sensor delay taken back)."""

    time: float
    """When the mark passed the sensor: edge time minus sensor delay (nan if no time given)."""
    fraction: float
    """The same moment as a fraction of the capturing cycle (negative: before the cycle)."""
    master: float
    """Master position when the mark passed the sensor."""
    slave: float
    """Slave position at that moment (nan without a slave channel)."""
    at_tool: float
    """``master + sensor_to_tool``: master position at which the mark reaches the tool."""
    delay_length: float
    """Master travel during the sensor delay (what the delay compensation took back)."""


class _EdgeLike(Protocol):
    @property
    def time(self) -> float: ...

    @property
    def fraction(self) -> float: ...


class MarkCapture:
    """Captures master and slave positions at a sensor edge.

    ``sensor_delay`` (seconds) is the sensor's dead time: it reports a mark ``sensor_delay``
    after the mark really passed. The captured positions are those at ``t_edge - sensor_delay``,
    so a delayed sensor still reports the true mark position. A negative delay would describe a
    sensor that reports early. The delay is taken back with the channel's velocity and
    acceleration at the edge, ``p - v d + a d^2 / 2``: exact while the acceleration is constant,
    which over a few milliseconds of sensor dead time is the case that matters.

    ``sensor_to_tool`` is the fixed distance (master units) from the sensor to the tool; it is
    added to give :attr:`CapturedMark.at_tool`.
    """

    __slots__ = ("master", "slave", "period", "sensor_delay", "sensor_to_tool")

    def __init__(
        self,
        master: ChannelMotion,
        slave: ChannelMotion | None = None,
        *,
        period: float,
        sensor_delay: float = 0.0,
        sensor_to_tool: float = 0.0,
    ) -> None:
        self.master = master
        self.slave = slave
        self.period = _check_positive("period", period)
        self.sensor_delay = _check_finite("sensor_delay", sensor_delay)
        self.sensor_to_tool = _check_finite("sensor_to_tool", sensor_to_tool)

    def _position(self, channel: ChannelMotion, fraction: float) -> float:
        period = self.period
        p = channel.position_at(fraction, period)
        d = self.sensor_delay
        if d == 0.0:
            return p
        v = channel.velocity_at(fraction, period)
        a = channel.acceleration_at(fraction, period)
        return p - v * d + 0.5 * a * d * d

    def capture(
        self,
        fraction: float | None = None,
        *,
        time: float | None = None,
        cycle_start: float | None = None,
    ) -> CapturedMark:
        """Capture at ``fraction`` (0..1) of the last cycle, or at absolute ``time`` (seconds)
        of the cycle starting at ``cycle_start``."""
        if time is not None:
            if cycle_start is None:
                raise ValueError("an absolute edge time needs the cycle_start time")
            edge_fraction = (time - cycle_start) / self.period
            if fraction is not None and abs(fraction - edge_fraction) > 1e-6:
                raise ValueError("fraction and time disagree")
            fraction = edge_fraction
        elif fraction is None:
            raise ValueError("give the edge's fraction of the cycle or its time")
        if time is None and cycle_start is not None:
            time = cycle_start + fraction * self.period
        return self._capture(fraction, math.nan if time is None else time)

    def capture_edge(self, edge: _EdgeLike) -> CapturedMark:
        """Capture at a sensor edge that carries both its time and its fraction of the cycle
        (a plant :class:`~axisline.plant.sensors.Edge`, or a real input's latch)."""
        return self._capture(edge.fraction, edge.time)

    def _capture(self, fraction: float, time: float) -> CapturedMark:
        if not -_FRACTION_TOLERANCE <= fraction <= 1.0 + _FRACTION_TOLERANCE:
            raise ValueError(f"the edge must lie in the cycle (fraction 0..1), got {fraction!r}")
        fraction = min(1.0, max(0.0, fraction))
        at_edge = self.master.position_at(fraction, self.period)
        master = self._position(self.master, fraction)
        slave = math.nan if self.slave is None else self._position(self.slave, fraction)
        delay = self.sensor_delay
        return CapturedMark(
            time=time - delay,
            fraction=fraction - delay / self.period,
            master=master,
            slave=slave,
            at_tool=master + self.sensor_to_tool,
            delay_length=at_edge - master,
        )
