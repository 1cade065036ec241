"""CLM1.4 Open Feed Roll, the electrical release of a feed roll (manual §7.10 L3805-3818, Ax30
L4810-4820; spec §4.10): a part of `axis.ClmAxis` (a mixin).

    A130 I1.00.4 Q1.00.3          # input "Open Feed Roll", output "Open Feed Roll Enabled"
    clm.feed_roll_open            # the loop is open: 0 V, the drive may drift

With the input at 24 V the CLM waits until the drive is in position, then sets the output and
commands 0 V: the position loop is open and the roll may be turned (e.g. by the press' pilots
pulling the strip into place) while the encoder keeps the actual position. A feed while the roll
is open waits until the input is 0 again.

Decisions (spec line -> choice, why)
------------------------------------
1. L3811 "This output is powered when the drive is in position. At the same time, a command
   value of 0 is issued" -> the input opens the roll only when the axis is in position (Ax27,
   axis.py decision 11: a feed in progress ends first); then the output is set and the loop
   commands 0 V; the Ax14 monitoring is suspended and the set point follows the actual position
   each cycle (the drift is no lag); Drive Enable stays on. The output drops when the roll
   closes, and with Drive Enable (a fault, E-Stop, Parameter mode).
   tests/devices/clm/test_feedroll.py::test_open_feed_roll_releases_in_position.
2. L3817 "motion and proceeding to the next instruction are delayed until the input becomes 0"
   -> a positioning reached while the roll is open is held (Inhibit Operation, as a move
   waiting for Drive Enable, axis.py decision 17) and jog keys are dead; the NC task waits at
   the instruction (runtime.feed_allowed). test_open_feed_roll_delays_the_feed.
3. Closing (input 0; spec [INFERRED] "The actual position keeps being tracked") -> as CPL
   (L1798-1806): set point and target become the actual position, so the loop does not pull
   the roll back to where it was opened (the strip was released to be moved); a feed held while
   open then goes its programmed distance from there. test_open_feed_roll_delays_the_feed.
"""

from __future__ import annotations

from fractions import Fraction
from typing import Any

from .operands import Operand

__all__ = ["OpenFeedRoll"]


class OpenFeedRoll:
    """Ax30 of `axis.ClmAxis` (the axis' state is kept there)."""

    axis: Any
    loop: Any
    image: Any
    _target: Fraction | None
    _blocked: bool
    _drive_on: bool
    feed_roll_open = False
    _ax30_in: Operand | None = None  # None: the function is not programmed (00.00.0)
    _ax30_out: Operand | None = None
    _opened_at: Fraction | None = None  # the target when the roll opened

    def _configure_feed_roll(self, params: Any, number: int) -> None:
        """Ax30 (after Parameter mode: the roll is closed)."""
        p30 = params.get(f"A{number}30")
        inp, out = p30["open_feed_roll_input"], p30["open_feed_roll_output"]
        self._ax30_in = None if inp.unset else inp
        self._ax30_out = None if out.unset else out
        if self.feed_roll_open:
            self._set_open(False)

    def _feed_roll_tick(self) -> None:
        """After the drive's cycle (axisdrive.py, which calls it when Ax30 has an input): Ax30
        (decisions 1-3)."""
        inp = self._ax30_in
        if inp is None:
            return
        want = bool(self.image.get(inp)) and self._drive_on
        if want and not self.feed_roll_open and self.in_position:  # type: ignore[attr-defined]
            self._set_open(True)
        elif not want and self.feed_roll_open:
            self._set_open(False)
            if self._drive_on:
                self._close()
        if self.feed_roll_open:  # the drift is no lag: the set point follows the roll
            ax = self.axis
            ax.power(False)
            ax.power(True)
        if self._ax30_out is not None:
            self.image.set(self._ax30_out, int(self.feed_roll_open))

    def _set_open(self, on: bool) -> None:
        self.feed_roll_open = on
        self.loop.open = on
        self.loop.resync()
        if on:  # in position: the target (or where the axis stands) is the base of a held feed
            if self._target is None:
                self._target = Fraction(self.axis.command_position)
            self._opened_at = self._target

    def _close(self) -> None:
        """Decision 3: set point and target := actual; a feed held while open goes from there."""
        ax = self.axis
        actual = Fraction(ax.actual_position)
        held = self._blocked and self._target is not None
        distance = self._target - self._opened_at if held and self._opened_at is not None else Fraction(0)  # type: ignore[operator]
        ax.power(False)
        ax.power(True)
        self.loop.resync()
        self._target = actual + distance
        if held:
            self._start()  # type: ignore[attr-defined]
