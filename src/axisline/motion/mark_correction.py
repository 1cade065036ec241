"""The correction (registration.py describes the whole): a measured deviation applied over
cycles, limited in size and rate.
"""

from __future__ import annotations

import math

from axisline.motion.registration_common import _check_finite, _check_limit, _check_positive, phase

__all__ = ["Correction"]


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
