"""LMK and LMR, the flying cutoff's length commands corrected by the Raster 1 input (I0.01.7;
manual LMK L2103-2117, LMR Examples 1/2 L2133-2171, A138 raster detection L4955; errata §2:
LMR's own section is lost, commands.py C-LOST: ``LMK 1 length offset``, ``LMR 1 raster offset``).

    op_lmk(rt, task, ins)    # LMK 1 001000.000 000400.000
    op_lmr(rt, task, ins)    # LMR 1 000900.000 000400.000 (Fig. 5-15: marks 1000, light barrier 100, offset 300)

The light barrier rides on the carriage (Figs. 5-15 / 5-16); the material point it sees is the
point under the tool shifted by its offset, which the programmed distances contain (Offset
Distance = Offset +- Light Barrier Offset). So a raster at material point ``r`` (the point under
the tool then) puts the cut at ``r + offset distance``.

Decisions (spec line -> choice, why)
------------------------------------
1. A138 raster detection "by level or by edge" (L4955, which digit is which is lost) -> 0 = a
   rising edge, 1 = the level (the input at 1 is a raster). An input wired to a print-mark
   sensor (``"I0.01.7" = "marks"``) gives the sub-cycle moment of its edge: the point is
   interpolated between the two NC cycles (as the SRM / SRP raster latch, registration.py);
   a plain input is taken at the cycle it is read. test_raster_by_edge_or_by_level,
   test_lmr_cuts_at_the_marks.
2. L2105-2107 LMK -> the length counts as LML's; a raster seen from the de-synchronization (the
   EOS before) until the synchronization puts the cut at raster + offset distance instead, once
   per instruction (the first raster). test_lmk_corrects_the_length_on_a_raster.
3. LMR (section lost; Examples 1/2: Raster Distance = mark distance -+ light barrier offset,
   Offset Distance = offset +- light barrier offset) -> the cut is offset distance after the
   raster; the raster distance is the material from the previous raster's mark (the point under
   the tool when it was seen, less nothing: the offsets are in the distances) to the next one:
   when the material under the tool has passed the previous raster by the raster distance and
   no raster came, the raster is taken there (a missing mark does not stop the line, the pieces
   keep the mark distance). The first LMR of a run waits for a real raster.
   test_lmr_cuts_at_the_marks, test_lmr_goes_on_over_a_missing_mark.
4. In this simulation the print-mark sensor is stationary at the tool's home; it is the
   carriage-mounted light barrier while the carriage is at home, where a raster is normally seen
   (LMK L2109: "If the raster signal is only triggered when the carriage is in the home
   position"). test_lmr_cuts_at_the_marks.
"""

from __future__ import annotations

from fractions import Fraction
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from .errors import ClmError
from .fields import Var
from .operands import Operand

if TYPE_CHECKING:
    from .nc import NcTask

__all__ = ["RasterWatch", "op_lml", "op_lmk", "op_lmr", "RASTER_1"]

RASTER_1 = Operand("I", 0, 1, 7)


#: The material point under the tool as read in one NC cycle: (the cutoff's master, its counts,
#: the carriage's actual position); `point_of` makes it the exact Fraction (IU).
Spot = tuple[Any, int, float]


def point_of(spot: Spot) -> Fraction:
    """master - carriage, exact (cutoff.FlyingCutoff.material_point of the spot's cycle)."""
    master, counts, actual = spot
    return master.exact_at(counts) - Fraction(actual)


class RasterWatch:
    """Raster 1 as the flying cutoff sees it: `seen(spot)` returns the material point of a raster
    of this cycle (decision 1), else None. It is given the cycle's spot, not the point: the
    exact Fraction is worked out only in a cycle that has a raster (not in every cycle)."""

    def __init__(self, rt: Any, level: bool) -> None:
        self.rt = rt
        self.level = level
        self._at, self._shift, _ = rt.image.locate(RASTER_1)
        self._before = rt.read_bit(RASTER_1)
        self._previous_spot: Spot | None = None
        self.last: Fraction | None = None  # the point of the last raster (LMR's reference)

    def seen(self, spot: Spot | None) -> Fraction | None:
        rt = self.rt
        previous, self._previous_spot = self._previous_spot, spot
        sensor = rt.registration.raster_sensors.get((0, 1, 7))
        if sensor is not None and not self.level:
            for edge in sensor.edges:  # the edges of the plant cycle just ended
                if edge.rising and spot is not None and previous is not None:
                    point, before = point_of(spot), point_of(previous)
                    return before + (point - before) * Fraction(edge.fraction)
            return None
        now = rt.image.data[self._at] >> self._shift & 1  # (Raster 1 is an input: no Logic Task owns it)
        before, self._before = self._before, now
        if spot is None:
            return None
        if self.level:
            return point_of(spot) if now else None
        return point_of(spot) if (now and not before) else None


def _length(rt: Any, ins: Any, index: int) -> Fraction:
    return Fraction(rt.number(ins, index), 1000)


def _part_length(rt: Any, task: NcTask, ins: Any, line: str, raster: Callable[[], Any], *, wait_for_raster: bool = False) -> int | None:
    """LML / LMK / LMR: the cutoff's length instruction; `raster()` gives its raster mode, taken
    when the instruction is reached (not on the cycles it waits)."""
    cutoff = rt.cutoff
    if cutoff is None:
        raise ClmError("0A", f"{ins.mnemonic} needs axis 1 in flying cutoff (A100 mode 5{line})")
    axis = ins.values[0]
    if task.wait is None or isinstance(axis, Var) or int(axis) not in rt.modes.enabled_axes:  # type: ignore[call-overload]
        rt.axis(ins, 0)  # (its checks; waiting on a constant axis that stays enabled, they hold)
    if task.wait is None:
        cutoff.raster_mode = raster()  # (None: LML, no raster)
        length: Fraction | None = _length(rt, ins, 1)
    elif isinstance(ins.values[1], Var):  # waiting: a variable is still checked every cycle (32)
        length = _length(rt, ins, 1)
    else:
        length = None  # waiting on a constant: the length was taken when the instruction was reached
    return task.pc + 1 if cutoff.lml(task, ins.number, length, wait_for_raster=wait_for_raster) else None


def op_lml(rt: Any, task: NcTask, ins: Any) -> int | None:
    """LML 1 LLLLLL.LLL: waits until the carriage is synchronous with the cut point (L2119-2131)."""
    return _part_length(rt, task, ins, ", L2129", lambda: None)


def op_lmk(rt: Any, task: NcTask, ins: Any) -> int | None:
    """LMK 1 length offset (decision 2)."""
    return _part_length(rt, task, ins, ", L2115", lambda: ("LMK", _length(rt, ins, 2), None))


def op_lmr(rt: Any, task: NcTask, ins: Any) -> int | None:
    """LMR 1 raster offset (decision 3)."""
    return _part_length(rt, task, ins, "", lambda: ("LMR", _length(rt, ins, 2), _length(rt, ins, 1)), wait_for_raster=True)
