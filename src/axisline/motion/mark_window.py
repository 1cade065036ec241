"""The mark window (registration.py describes the whole): where the next mark is expected,
which marks count, teaching, missing marks and their substitutes.
"""

from __future__ import annotations

import math
from enum import IntEnum

from axisline.motion.registration_common import Startup, Substitute, _check_finite, _check_positive, _is_count, phase, wrap

__all__ = ["MarkVerdict", "MarkWindow"]


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
