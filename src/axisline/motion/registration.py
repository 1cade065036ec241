"""Registration to print marks and labels: capture, window, correction, missing marks, mark queue.

The generic parts both registration personalities build on (a flying cut-off that cuts at print
marks, a cam controller that keeps labels in phase with its curve). Device parameter names stay
in the devices; every behaviour they need is a combination of the pieces here:

:class:`ChannelMotion`, :class:`MarkCapture`
    Where the master and the slave were when a mark passed the sensor. The sensor edge carries a
    sub-cycle moment (absolute time or fraction of the cycle); positions are interpolated between
    the cycle's start and end (linearly, or exactly for constant acceleration when velocities are
    known), the sensor's dead time is taken back and a fixed sensor-to-tool distance added.

:class:`MarkWindow`
    The expected mark position (cyclic with a cycle length, or linear with a pitch) and a window
    of +-half_width around it. Marks outside are ignored and counted; "teach" takes a mark as the
    new expected position; the start-up may accept marks without the window. A window that passes
    without a mark yields a substitute mark and counts a miss; ``missing_alarm_after``
    consecutive misses set the alarm, the next good mark clears it.

:class:`Correction`
    The correction ``measured - expected`` distributed smoothly: limited per mark, limited per
    cycle, optionally only inside a master range (spread over it in proportion to master travel).

:class:`Registration`
    Window + correction glued together for the usual per-cycle loop, with master-side or
    slave-side application.

:class:`MarkQueue`
    Marks between the sensor and the tool, first in first out, in a preallocated ring buffer;
    each becomes due when the tool reaches it; overflow is reported, never silently dropped;
    virtual marks fill the gap at start; only every n-th mark starts a product.

Sign conventions
----------------
*Deviation* (also called the measured correction) is ``measured - expected``: positive when the
mark came late in the measuring frame (the frame had already run past the expected position).
Cyclic deviations are wrapped into ``(-cycle/2, cycle/2]``.

Marks must be measured in the frame the correction acts on (the corrected master seen by the
slave, or the slave position including its correction). Then each new mark already shows what
the earlier corrections achieved, so a new deviation *replaces* the correction still pending
instead of adding to it; that is what keeps registration free of overshoot.

:attr:`Correction.offset` is ``-(correction applied so far)``: the amount to **add** to the
measuring frame so that the next mark lands on its expected position. For master-side
correction add it to the master position the slave follows; for slave-side correction add it to
the slave set point when the slave moves the tool. When the corrected channel instead *carries*
the material (a feed roll whose curve position is the measuring frame), moving the set point
forward makes marks arrive *earlier* in the curve, so subtract it there.

Per-cycle path: no containers are built (the queue is a preallocated numpy ring buffer); the
objects returned per mark are small named tuples.
"""

from __future__ import annotations

import math
from enum import IntEnum
from typing import Literal, NamedTuple, Protocol

import numpy as np

__all__ = [
    "CapturedMark",
    "ChannelMotion",
    "Correction",
    "MarkCapture",
    "MarkKind",
    "MarkQueue",
    "MarkVerdict",
    "MarkWindow",
    "QueuedMark",
    "Registration",
    "Side",
    "Startup",
    "Substitute",
    "expected_at_sensor",
    "phase",
    "wrap",
]

Side = Literal["master", "slave"]
Startup = Literal["window", "first", "until_inside"]
Substitute = Literal["expected", "extrapolate"]

# A fraction this far outside 0..1 is rounding of an edge on the cycle boundary, not an error.
_FRACTION_TOLERANCE = 1e-9


def _check_positive(name: str, value: float) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise ValueError(f"{name} must be a number > 0, got {value!r}")
    if not (math.isfinite(value) and value > 0.0):
        raise ValueError(f"{name} must be a finite number > 0, got {value!r}")
    return float(value)


def _check_finite(name: str, value: float) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise ValueError(f"{name} must be a finite number, got {value!r}")
    return float(value)


def _is_count(value: object, minimum: int) -> bool:
    return isinstance(value, int) and not isinstance(value, bool) and value >= minimum


def _check_limit(name: str, value: float | None) -> float:
    """A magnitude limit: None means unlimited (stored as inf)."""
    if value is None:
        return math.inf
    value = _check_finite(name, value)
    if value <= 0.0:
        raise ValueError(f"{name} must be > 0 (or None for no limit), got {value!r}")
    return value


def wrap(distance: float, cycle: float) -> float:
    """``distance`` wrapped into ``(-cycle/2, cycle/2]``: the shortest way round a cycle.

    The upper end is closed so that a mark exactly half a cycle away has one deviation, not two.
    """
    r = math.fmod(distance, cycle)  # exact, sign of ``distance``, |r| < cycle
    half = 0.5 * cycle
    if r > half:
        r -= cycle
    elif r <= -half:
        r += cycle
    return r


def phase(position: float, cycle: float) -> float:
    """``position`` reduced into ``[0, cycle)``."""
    r = math.fmod(position, cycle)
    if r < 0.0:
        r += cycle
        if r >= cycle:  # -1e-20 + cycle rounds to cycle
            r = 0.0
    return r


def expected_at_sensor(processing_point: float, sensor_to_tool: float, cycle: float) -> float:
    """Where in the cycle a mark must pass the sensor so that it meets the tool at
    ``processing_point``: ``processing_point - sensor_to_tool`` reduced into ``[0, cycle)``.

    The sensor sits ``sensor_to_tool`` (in the units of the cycle) upstream of the tool, so the
    mark passes it that much earlier.
    """
    return phase(processing_point - sensor_to_tool, _check_positive("cycle", cycle))


# -- capture ---------------------------------------------------------------------------------


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


# -- window ----------------------------------------------------------------------------------


class MarkVerdict(IntEnum):
    """What a window made of a mark."""

    IGNORED = 0
    """Outside the window (or a second mark in the same window): no correction, counted."""
    ACCEPTED = 1
    """Inside the window: its deviation is a correction."""
    STARTUP = 2
    """Outside the window, accepted because the start-up takes marks without the window."""
    TAUGHT = 3
    """Teach was armed: the mark became the new expected position (deviation 0)."""


class MarkWindow:
    """Expected mark position, window around it, teach, and missing-mark monitoring.

    Positions are in the measuring frame (master or slave units) and must be given in time
    order: every mark with :meth:`mark`, and once per cycle, after that cycle's marks, the
    frame position at the end of the cycle with :meth:`update`.

    Exactly one of:

    ``cycle``
        Cyclic: the mark is expected at the same place ``expected`` in every cycle (``0 ..
        cycle``). Positions may be given wrapped or unwrapped (they are followed across the cycle
        boundary, so no position may jump by half a cycle or more between two calls);
        deviations are wrapped into ``(-cycle/2, cycle/2]``.
    ``pitch``
        Linear: marks follow one another ``pitch`` apart on an unwrapped position; ``expected``
        is the first one's position. With ``follow_marks`` each accepted mark re-anchors the
        grid (the next is expected one pitch after it) instead of the fixed grid
        ``expected + k * pitch``.

    ``half_width`` is half the window (a mark exactly on the edge is inside); None disables the
    window: every mark is valid and belongs to the nearest expected position.

    ``startup`` decides how the first marks are taken:

    - ``"window"``: the window applies from the first mark;
    - ``"first"``: the first mark is accepted wherever it is, the window applies afterwards (a
      label controller's initial correction, unlimited);
    - ``"until_inside"``: marks are accepted without the window until one lies inside it (a
      start-up correction limited per mark that walks the mark into the window).

    Missing marks are monitored only once the window applies. A window that passes without a
    mark yields a substitute: at the expected position (``substitute="expected"``: no
    correction), or one pitch (cycle) after the previous mark or substitute
    (``"extrapolate"``: the preset length after the last mark). ``missing_alarm_after``
    consecutive misses set :attr:`alarm` (0: never); the next accepted mark clears it.
    """

    def __init__(
        self,
        expected: float,
        *,
        half_width: float | None = None,
        cycle: float | None = None,
        pitch: float | None = None,
        follow_marks: bool = False,
        startup: Startup = "window",
        substitute: Substitute = "expected",
        missing_alarm_after: int = 0,
        position: float = 0.0,
    ) -> None:
        if (cycle is None) == (pitch is None):
            raise ValueError("give either a cycle (cyclic window) or a pitch (linear window)")
        self.cyclic = cycle is not None
        if cycle is not None:
            self.period = _check_positive("cycle", cycle)
        else:
            self.period = _check_positive("pitch", pitch)  # type: ignore[arg-type]
        if half_width is None:
            self.half_width = 0.5 * self.period
        else:
            half_width = _check_finite("half_width", half_width)
            if not 0.0 <= half_width <= 0.5 * self.period:
                raise ValueError("half_width must lie in 0 .. half the cycle (pitch)")
            self.half_width = half_width
        if follow_marks and self.cyclic:
            raise ValueError("follow_marks is for linear windows; a cyclic window is taught instead")
        if startup not in ("window", "first", "until_inside"):
            raise ValueError(f"startup must be 'window', 'first' or 'until_inside', got {startup!r}")
        if substitute not in ("expected", "extrapolate"):
            raise ValueError(f"substitute must be 'expected' or 'extrapolate', got {substitute!r}")
        if not _is_count(missing_alarm_after, 0):
            raise ValueError("missing_alarm_after must be an integer >= 0")
        self.follow_marks = bool(follow_marks)
        self.startup = startup
        self.substitute_mode = substitute
        self.missing_alarm_after = missing_alarm_after
        self._expected = _check_finite("expected", expected)
        if self.cyclic:
            self._expected = phase(self._expected, self.period)
        self.reset(position)

    def reset(self, position: float = 0.0) -> None:
        """Start over at frame position ``position``: start-up again, counters and alarm
        cleared, teach disarmed. The expected position is kept."""
        position = _check_finite("position", position)
        self._p = position  # last frame position given, caller's coordinates
        self._u = position  # the same, unwrapped (internal coordinates)
        self._windowing = self.startup == "window"
        self._seen = False  # the current window has had its mark
        self._teach_armed = False
        self._last_mark = math.nan  # internal position of the last mark or substitute
        self._substitute_u = math.nan
        self._closed_missing = False  # a window closed without a mark since the last update
        self._place_window()
        self.accepted = 0
        """Marks accepted (in the window, or at start-up)."""
        self.ignored = 0
        """Marks outside the window (or extra marks in one window)."""
        self.missing = 0
        """Windows that passed without a mark."""
        self.consecutive_missing = 0
        self.alarm = False
        """``missing_alarm_after`` windows in a row passed without a mark."""
        self.taught = False
        """The expected position was set by teach."""
        self.measured = math.nan
        """Position of the last mark given to :meth:`mark` (caller's coordinates)."""
        self.deviation = math.nan
        """``measured - expected`` of the last mark, unlimited (wrapped when cyclic)."""
        self.substitute = math.nan
        """Position of the last substitute mark (caller's coordinates)."""

    # -- coordinates -------------------------------------------------------------------------

    def _internal(self, x: float) -> float:
        if self.cyclic:
            return self._u + wrap(x - self._p, self.period)
        return x

    def _caller(self, xu: float) -> float:
        return self._p + (xu - self._u) if self.cyclic else xu

    def _place_window(self) -> None:
        """Current window: the first whose end the frame has not passed."""
        if self.cyclic:
            # the expected position nearest to the frame, then the first window not yet passed
            self._centre = self._u + wrap(self._expected - self._p, self.period)
            if self._centre + self.half_width < self._u:
                self._centre += self.period
            elif self._centre - self.period + self.half_width >= self._u:
                self._centre -= self.period
        else:
            # the first window of the grid whose end is still ahead
            k = max(0, math.ceil((self._u - self.half_width - self._expected) / self.period))
            self._centre = self._expected + k * self.period
        # A window the frame is already inside was never watched from its start: it is not
        # held against the line if its mark has gone by already.
        self._watched = self._centre - self.half_width >= self._u

    # -- state -------------------------------------------------------------------------------

    @property
    def expected(self) -> float:
        """Expected mark position: the phase ``0 .. cycle`` (cyclic) or the current window's
        centre (linear)."""
        return self._expected if self.cyclic else self._centre

    @property
    def windowing(self) -> bool:
        """The window applies (start-up is over); misses are monitored."""
        return self._windowing

    @property
    def window_open(self) -> bool:
        """The frame is inside the current window (always, with the window disabled)."""
        return abs(self._u - self._centre) <= self.half_width

    def set_expected(self, expected: float) -> None:
        """Move the expected position (cyclic: the phase; linear: the current window's centre)."""
        expected = _check_finite("expected", expected)
        if self.cyclic:
            shift = wrap(expected - self._expected, self.period)
            self._expected = phase(expected, self.period)
            self._centre += shift
        else:
            self._centre = expected
            self._expected = expected

    def teach(self, position: float) -> None:
        """Take ``position`` (caller's frame, e.g. where teach was released at standstill) as
        the expected mark position; the current window is centred there."""
        position = _check_finite("position", position)
        xu = self._internal(position)
        self._expected = phase(position, self.period) if self.cyclic else position
        self._centre = xu
        # The frame stands in the new window's middle: half a window cannot count as missed.
        self._watched = False
        self.taught = True

    def arm_teach(self) -> None:
        """Take the next mark, wherever it is, as the new expected position. Until it comes,
        windows passing without a mark are not counted as missing."""
        self._teach_armed = True
        self.taught = False

    # -- per mark / per cycle ----------------------------------------------------------------

    def _close_window(self) -> None:
        # While teach is armed the window is about to move: the old one is not held against
        # the line.
        if not self._seen and self._windowing and self._watched and not self._teach_armed:
            self.missing += 1
            self.consecutive_missing += 1
            if self.missing_alarm_after and self.consecutive_missing >= self.missing_alarm_after:
                self.alarm = True
            if self.substitute_mode == "extrapolate" and not math.isnan(self._last_mark):
                sub = self._last_mark + self.period
            else:
                sub = self._centre
            self._last_mark = sub
            self._substitute_u = sub
            self._closed_missing = True
            if self.follow_marks:
                # the grid continues from the substitute
                self._centre = sub
        self._seen = False
        self._watched = True
        self._centre += self.period

    def _close_until(self, xu: float) -> None:
        # A position exactly on the window end is still inside (the closed interval).
        while self._centre + self.half_width < xu:
            self._close_window()

    def mark(self, position: float) -> MarkVerdict:
        """A mark captured at ``position`` (measuring frame). Returns what the window made of
        it; :attr:`deviation` holds ``measured - expected``."""
        xu = self._internal(position)
        self._close_until(xu)  # windows that ended before this mark (earlier in the cycle)
        self.measured = position
        if self._teach_armed:
            self._teach_armed = False
            self._expected = phase(position, self.period) if self.cyclic else position
            self._centre = xu
            self.deviation = 0.0
            self.taught = True
            self._windowing = True
            self._good(xu, True)
            return MarkVerdict.TAUGHT
        if self.cyclic:
            deviation = wrap(xu - self._centre, self.period)
        else:
            deviation = xu - self._centre
        self.deviation = deviation
        inside = abs(deviation) <= self.half_width
        if inside and not self._seen:
            # a mark in the window ends any start-up
            self._windowing = True
            self._good(xu, True)
            return MarkVerdict.ACCEPTED
        if not self._windowing and not inside:
            if self.startup == "first":
                self._windowing = True
            # The mark stands for the window nearest to it; if that is the current one, it has
            # had its mark (no miss when it closes).
            nearest = xu - deviation
            self._good(xu, abs(nearest - self._centre) < 0.5 * self.period)
            return MarkVerdict.STARTUP
        self.ignored += 1
        return MarkVerdict.IGNORED

    def _good(self, xu: float, in_current: bool) -> None:
        self.accepted += 1
        self.consecutive_missing = 0
        self.alarm = False
        self._last_mark = xu
        if self.follow_marks:
            # re-anchor: this window is the mark's, the next is one pitch after the mark
            self._centre = xu
            in_current = True
        if in_current:
            self._seen = True

    def update(self, position: float) -> float | None:
        """Frame position at the end of a cycle (after the cycle's marks). Closes the windows
        passed; returns the substitute position if a window passed without a mark since the
        last update (this cycle), else None. Windows are a cycle (pitch) apart, far more than a
        cycle's travel, so at most one passes per cycle."""
        position = _check_finite("position", position)
        if self.cyclic:
            self._u += wrap(position - self._p, self.period)
        else:
            self._u = position
        self._p = position
        self._close_until(self._u)
        if self._closed_missing:
            self._closed_missing = False
            self.substitute = self._caller(self._substitute_u)
            return self.substitute
        return None


# -- correction ------------------------------------------------------------------------------


class Correction:
    """Distributes corrections smoothly onto the corrected channel.

    :meth:`set` takes a new correction (a mark's deviation); it replaces the correction still
    pending (see the module docstring: marks are measured in the corrected frame), limited to
    ``max_per_mark`` in magnitude. :meth:`step`, once per cycle, applies part of the pending
    correction:

    - at most ``max_per_cycle`` per cycle (a correction velocity times the cycle period), so
      the corrected channel never steps;
    - only while the master is inside ``enable_from .. enable_to`` of a ``master_cycle`` (the
      range wraps past the cycle end when ``enable_from > enable_to``; equal ends mean the whole
      cycle), e.g. to keep the tool's synchronous zone free of corrections;
    - with ``spread`` in proportion to the master travel through that range, so the correction
      runs out exactly at ``enable_to`` (a correction that comes mid-range uses the rest of
      the range; ``max_per_cycle`` still caps each share, and what it holds back waits for
      the next pass).

    The range and ``spread`` assume a master that moves forward by less than a cycle per step,
    as label registration requires.

    ``in_phase``: the correction is injected into the very master position given to
    :meth:`step` (a correction before the curve, in the master position integrator). The range
    and the spread are then measured in the uncorrected master travel (the phase minus the
    correction's own steps), from the corrected position at the last :meth:`set`; otherwise each
    share would move the master, which makes the next share bigger (positive feedback, a jump).

    With none of these the whole pending correction is applied in the next cycle.
    """

    __slots__ = (
        "max_per_mark",
        "max_per_cycle",
        "enable_from",
        "enable_to",
        "master_cycle",
        "spread",
        "in_phase",
        "_length",
        "_prev",
        "_pos",
        "requested",
        "pending",
        "applied",
        "last_step",
    )

    def __init__(
        self,
        *,
        max_per_mark: float | None = None,
        max_per_cycle: float | None = None,
        enable_from: float | None = None,
        enable_to: float | None = None,
        master_cycle: float | None = None,
        spread: bool = False,
        in_phase: bool = False,
    ) -> None:
        self.max_per_mark = _check_limit("max_per_mark", max_per_mark)
        self.max_per_cycle = _check_limit("max_per_cycle", max_per_cycle)
        if (enable_from is None) != (enable_to is None):
            raise ValueError("give both enable_from and enable_to, or neither")
        if enable_from is not None and enable_to is not None:  # (both or neither: checked above)
            if master_cycle is None:
                raise ValueError("a correction range needs the master_cycle")
            self.master_cycle = _check_positive("master_cycle", master_cycle)
            self.enable_from = phase(_check_finite("enable_from", enable_from), self.master_cycle)
            self.enable_to = phase(_check_finite("enable_to", enable_to), self.master_cycle)
            length = phase(self.enable_to - self.enable_from, self.master_cycle)
            self._length = length if length > 0.0 else self.master_cycle
        else:
            if spread:
                raise ValueError("spread needs a correction range (enable_from, enable_to)")
            self.master_cycle = math.nan
            self.enable_from = self.enable_to = math.nan
            self._length = math.nan
        self.spread = bool(spread)
        self.in_phase = bool(in_phase)
        self.reset()

    def reset(self) -> None:
        """Forget all corrections (pending and applied)."""
        self._prev = math.nan
        self._pos = math.nan
        self.requested = 0.0
        """Last correction given to :meth:`set`, before the per-mark limit."""
        self.pending = 0.0
        """Correction still to apply (same sign as the deviation)."""
        self.applied = 0.0
        """Correction applied since the reset (same sign as the deviation)."""
        self.last_step = 0.0
        """Change of :attr:`offset` in the last :meth:`step`."""

    @property
    def offset(self) -> float:
        """Add to the measuring frame (master seen by the slave, or the slave set point)."""
        return -self.applied

    def set(self, correction: float) -> float:
        """A new correction (``measured - expected``); returns it limited per mark."""
        correction = _check_finite("correction", correction)
        self.requested = correction
        limit = self.max_per_mark
        limited = max(-limit, min(limit, correction))
        self.pending = limited
        self._pos = self._prev  # in_phase: the range is measured from the corrected position now
        return limited

    def cancel(self) -> None:
        """Drop the pending correction (e.g. when teach re-defines the reference)."""
        self.pending = 0.0

    def _share(self, master_phase: float | None) -> float:
        """Fraction of the pending correction this cycle may apply (before the rate limit)."""
        if math.isnan(self.master_cycle):
            return 1.0
        if master_phase is None:
            raise ValueError("a correction range needs the master phase every cycle")
        cycle = self.master_cycle
        length = self._length
        now = phase(master_phase - self.enable_from, cycle)
        prev = now if math.isnan(self._prev) else self._prev
        self._prev = now
        # master increases (as label registration requires); travel below a cycle per step
        if self.in_phase:
            # the phase carries the correction's own last step: take it out (uncorrected travel)
            travel = phase(now - prev - self.last_step, cycle)
            if math.isnan(self._pos):
                self._pos = prev
            prev = self._pos
            now = phase(prev + travel, cycle)
            self._pos = now
        else:
            travel = phase(now - prev, cycle)
        if prev < length:
            remaining = length - prev
            inside = min(travel, remaining)
        else:
            # outside at the start of the step; maybe entering the range during it
            remaining = length
            inside = max(0.0, min(travel - (cycle - prev), length))
        if not self.spread:
            # enabled for travel through the range, or standing inside it
            return 1.0 if (inside > 0.0 or (travel == 0.0 and now < length)) else 0.0
        return min(1.0, inside / remaining) if remaining > 0.0 else 1.0

    def step(self, master_phase: float | None = None) -> float:
        """Apply this cycle's share of the pending correction; returns :attr:`offset`.

        ``master_phase`` (units of ``master_cycle``) is needed when a correction range is set.
        """
        share = self._share(master_phase)
        pending = self.pending
        if pending == 0.0 or share == 0.0:
            self.last_step = 0.0
            return -self.applied
        amount = pending * share
        limit = self.max_per_cycle
        if amount > limit:
            amount = limit
        elif amount < -limit:
            amount = -limit
        if abs(amount) >= abs(pending):
            amount = pending  # exactly used up, no rounding residue left pending
            self.pending = 0.0
        else:
            self.pending = pending - amount
        self.applied += amount
        self.last_step = -amount
        return -self.applied


class Registration:
    """A window and a correction working together, applied on the master or the slave side.

    Per cycle: :meth:`mark` for each captured mark (in the measuring frame, i.e. including the
    correction), then :meth:`step` with the frame position at the cycle end. An accepted mark's
    deviation becomes the pending correction; a taught mark cancels it (the reference changed);
    ignored marks and substitutes never steer the correction (they carry no measurement), so a
    correction in progress runs on.

    ``side`` says where the offset goes: ``"master"`` (the master position the slave follows,
    :meth:`master_for_slave`) or ``"slave"`` (the slave set point, :meth:`slave_set_point`).
    """

    __slots__ = ("window", "correction", "side")

    def __init__(self, window: MarkWindow, correction: Correction, *, side: Side = "master") -> None:
        if side not in ("master", "slave"):
            raise ValueError(f"side must be 'master' or 'slave', got {side!r}")
        self.window = window
        self.correction = correction
        self.side = side

    @property
    def offset(self) -> float:
        return self.correction.offset

    def mark(self, position: float) -> MarkVerdict:
        verdict = self.window.mark(position)
        if verdict is MarkVerdict.ACCEPTED or verdict is MarkVerdict.STARTUP:
            self.correction.set(self.window.deviation)
        elif verdict is MarkVerdict.TAUGHT:
            self.correction.cancel()
        return verdict

    def step(self, position: float, master_phase: float | None = None) -> float:
        """End of a cycle: window bookkeeping at frame ``position``, then this cycle's share of
        the correction. Returns the offset."""
        self.window.update(position)
        return self.correction.step(master_phase)

    def master_for_slave(self, master: float) -> float:
        """Master position the slave follows (corrected when the side is the master)."""
        return master + self.correction.offset if self.side == "master" else master

    def slave_set_point(self, set_point: float) -> float:
        """Slave set point (corrected when the side is the slave)."""
        return set_point + self.correction.offset if self.side == "slave" else set_point


# -- queue between sensor and tool -----------------------------------------------------------


class MarkKind(IntEnum):
    REAL = 0
    """Captured at the sensor."""
    VIRTUAL = 1
    """Filled in at start for the stretch between sensor and tool nobody has seen."""
    SUBSTITUTE = 2
    """Stands for a mark that was missing from its window."""


class QueuedMark(NamedTuple):
    position: float
    """Mark position as captured at the sensor (master/material coordinates)."""
    due: float
    """Tool position at which it is due: ``position + distance``."""
    kind: MarkKind


class MarkQueue:
    """Marks between the sensor and the tool, first in, first out.

    ``capacity`` marks fit (a preallocated ring buffer). ``distance`` is the sensor-to-tool
    distance: a mark captured at ``position`` is due when the tool position reaches
    ``position + distance`` (0 if the positions pushed are already at the tool).

    A mark that does not fit sets :attr:`overflow` (latched until :meth:`clear_overflow` or
    :meth:`reset`) and counts in :attr:`overflows`; :meth:`push` returns False. Marks already
    queued are never overwritten.

    ``marks_per_product``: only every n-th real (or substitute) mark starts a product and is
    queued, beginning with the first after a reset; the others are counted and skipped.
    """

    __slots__ = (
        "capacity",
        "distance",
        "marks_per_product",
        "_positions",
        "_kinds",
        "_read",
        "_count",
        "_seen",
        "overflow",
        "overflows",
        "skipped",
    )

    def __init__(
        self, capacity: int = 64, *, distance: float = 0.0, marks_per_product: int = 1
    ) -> None:
        if not _is_count(capacity, 1):
            raise ValueError("capacity must be an integer >= 1")
        if not _is_count(marks_per_product, 1):
            raise ValueError("marks_per_product must be an integer >= 1")
        self.capacity = capacity
        self.distance = _check_finite("distance", distance)
        self.marks_per_product = marks_per_product
        self._positions = np.zeros(capacity, dtype=np.float64)
        self._kinds = np.zeros(capacity, dtype=np.int8)
        self.reset()

    def reset(self) -> None:
        """Empty the queue, restart the marks-per-product count, clear the overflow."""
        self._read = 0
        self._count = 0
        self._seen = 0
        self.overflow = False
        self.overflows = 0
        self.skipped = 0

    def clear_overflow(self) -> None:
        self.overflow = False

    def __len__(self) -> int:
        return self._count

    @property
    def full(self) -> bool:
        return self._count == self.capacity

    @property
    def read_index(self) -> int:
        """Ring-buffer slot of the oldest mark."""
        return self._read

    @property
    def write_index(self) -> int:
        """Ring-buffer slot the next mark goes to."""
        return (self._read + self._count) % self.capacity

    def push(self, position: float, kind: MarkKind = MarkKind.REAL) -> bool:
        """Queue a mark captured at ``position``. Returns True if queued; False if skipped
        (marks per product) or if the queue is full (then :attr:`overflow` is set)."""
        if kind is not MarkKind.VIRTUAL:
            # virtual marks are spaced a product apart already; real ones are counted
            n = self._seen
            self._seen = n + 1
            if n % self.marks_per_product:
                self.skipped += 1
                return False
        if self._count == self.capacity:
            self.overflow = True
            self.overflows += 1
            return False
        slot = (self._read + self._count) % self.capacity
        self._positions[slot] = position
        self._kinds[slot] = kind
        self._count += 1
        return True

    def fill_virtual(self, position: float, spacing: float) -> int:
        """Line start at master ``position``: empty the queue and fill the stretch between
        sensor and tool with virtual marks ``spacing`` apart, as if they had passed the sensor
        at ``position - k * spacing`` (k = n .. 1, n = floor(distance / spacing)), so the
        tool works from the first one instead of waiting for the first real mark. Returns n."""
        spacing = _check_positive("spacing", spacing)
        self.reset()
        n = math.floor(self.distance / spacing + 1e-9)
        for k in range(n, 0, -1):
            self.push(position - k * spacing, MarkKind.VIRTUAL)
        return n

    def _head(self) -> int:
        if not self._count:
            raise IndexError("the mark queue is empty")
        return self._read

    @property
    def head_position(self) -> float:
        return float(self._positions[self._head()])

    @property
    def head_due(self) -> float:
        """Tool position at which the oldest mark is due."""
        return float(self._positions[self._head()]) + self.distance

    @property
    def head_kind(self) -> MarkKind:
        return MarkKind(int(self._kinds[self._head()]))

    def is_due(self, tool_position: float) -> bool:
        """The oldest mark has reached the tool at ``tool_position``."""
        return self._count > 0 and tool_position >= float(self._positions[self._read]) + self.distance

    def pop(self) -> QueuedMark:
        """Remove and return the oldest mark."""
        slot = self._head()
        position = float(self._positions[slot])
        mark = QueuedMark(position, position + self.distance, MarkKind(int(self._kinds[slot])))
        self._read = (slot + 1) % self.capacity
        self._count -= 1
        return mark

    def pop_due(self, tool_position: float) -> QueuedMark | None:
        """The oldest mark if it is due at ``tool_position``, else None."""
        return self.pop() if self.is_due(tool_position) else None

    def marks(self) -> list[QueuedMark]:
        """Snapshot, oldest first (for display; allocates)."""
        out = []
        for i in range(self._count):
            slot = (self._read + i) % self.capacity
            p = float(self._positions[slot])
            out.append(QueuedMark(p, p + self.distance, MarkKind(int(self._kinds[slot]))))
        return out
