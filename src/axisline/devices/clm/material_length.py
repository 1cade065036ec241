"""MLO and MLT, the material length commands (manual L2184-2203; spec §3, commands.py C-LOST:
``MLO bit state length``, ``MLT bit length``).

    op_mlo(rt, task, ins)     # MLO Q1.00.3 1 000250.000: the bit every 250 IU of material
    op_mlt(rt, task, ins)     # MLT M1.00.0 000300.000: the bit = material through the tool > 300

Decisions (spec line -> choice, why)
------------------------------------
1. L2186-2189 MLO ("a bit can be set or cleared in Automatic Mode, depending upon the length of
   the material that has been fed. When this command is read for the first time, length
   measurement is enabled ... the output is enabled or disabled. The length measurement is
   reset") -> the material fed is master encoder 1's travel (the material counters' source,
   cutoff.py decision 8), in any Ax00 mode (MLO is not a flying-cutoff-only command); each MLO
   instruction measures on its own, from the first time it is read; reading it again while it
   measures changes nothing but its values; whenever the fed length exceeds the programmed one
   the bit takes the state and the measurement restarts from there (checked every NC cycle, and
   at once when the command is read: "If the already fed length ... is greater ... when the
   command is loaded"). Length 0, or leaving Automatic, ends the measurement. One cycle.
   test_mlo_sets_the_bit_every_length.
2. L2195-2199 MLT -> the material "processed through the tool" is FUN's material channel (V026,
   measuring_wheel.py decision 7: master less carriage since its FUN); the bit is 1 when it is
   greater than the length, else 0; without FUN it is 0 (bit 0). One cycle.
   test_mlt_tests_the_material_through_the_tool.
"""

from __future__ import annotations

from fractions import Fraction
from typing import Any

__all__ = ["LengthCounters", "MaterialOutputs", "op_mlo", "op_mlt"]


class LengthCounters:
    """The flying cutoff's material and product length counters (cutoff.py decision 8, Status
    54, !sCLL1 / !sCLL2), exact IU: what is summed so far plus whole counts not yet scaled,
    folded in when the encoder's scale changes (one int sum per NC cycle, not a Fraction)."""

    def __init__(self) -> None:
        self._material = Fraction(0)
        self._product = Fraction(0)
        self._material_counts = 0
        self._product_counts = 0
        self._scale: Any = Fraction(0)

    def add(self, counts: int, scale: Any, *, product: bool) -> None:
        """`counts` of master encoder 1 at `scale` IU per count; the product counter too when
        `product` (Automatic, no Cut Inhibit)."""
        if scale is not self._scale:  # (the same object while C000-C002 and FAK 5 stay)
            self._fold()
            self._scale = scale
        self._material_counts += counts
        if product:
            self._product_counts += counts

    def _fold(self) -> None:
        scale = self._scale
        self._material += self._material_counts * scale
        self._product += self._product_counts * scale
        self._material_counts = self._product_counts = 0

    @property
    def material(self) -> Fraction:
        """All master-encoder-1 movement in Manual and Automatic (IU)."""
        return self._material + self._material_counts * self._scale

    @property
    def product(self) -> Fraction:
        """Movement in Automatic, not while Cut Inhibit is active (IU)."""
        return self._product + self._product_counts * self._scale

    def clear(self, which: int) -> None:
        """!sCLL1 (1: material) / !sCLL2 (2: product)."""
        self._fold()
        if which == 1:
            self._material = Fraction(0)
        else:
            self._product = Fraction(0)

    def status_54(self) -> str:
        """``54 vmmmmmmmm vpppppppp``: whole IU toward zero, sign and 8 digits."""

        def field(x: Fraction) -> str:
            n = max(-99_999_999, min(99_999_999, int(x)))
            return f"{'-' if x < 0 else '+'}{abs(n):08d}"

        return f"54 {field(self.material)} {field(self.product)} "


class MaterialOutputs:
    """The running MLO measurements of one CLM, by instruction number (decision 1)."""

    def __init__(self, rt: Any) -> None:
        self.rt = rt
        self.running: dict[int, list[Any]] = {}  # number -> [bit, state, length, start]

    def load(self, number: int, bit: Any, state: int, length: Fraction) -> None:
        me = self.rt.master_encoder
        if length <= 0 or me is None:
            self.running.pop(number, None)
            return
        entry = self.running.get(number)
        if entry is None:
            self.running[number] = [bit, state, length, me.position]
        else:
            entry[0], entry[1], entry[2] = bit, state, length
        self._check(self.running[number], me.position)

    def _check(self, entry: list[Any], now: Fraction) -> None:
        if now - entry[3] > entry[2]:
            self.rt.write_bit(entry[0], entry[1])
            entry[3] = now

    def tick(self, mode: str) -> None:
        if not self.running:
            return
        me = self.rt.master_encoder
        if mode != "automatic" or me is None:
            self.running.clear()
            return
        now = me.position
        for entry in self.running.values():
            self._check(entry, now)


def op_mlo(rt: Any, task: Any, ins: Any) -> int | None:
    if rt.material_outputs is None:
        rt.material_outputs = MaterialOutputs(rt)
    rt.material_outputs.load(ins.number, ins.values[0], rt.state_value(ins, 1), Fraction(rt.number(ins, 2), 1000))
    return task.pc + 1


def op_mlt(rt: Any, task: Any, ins: Any) -> int | None:
    from .errors import ClmError
    from .measuring_wheel import feed_lengths

    if rt.cutoff is None:
        raise ClmError("0A", "MLT needs axis 1 in flying cutoff (A100 mode 5, L2203)")

    lengths = feed_lengths(rt)
    processed = lengths.current("material") if "material" in lengths.start else Fraction(0)
    rt.write_bit(ins.values[0], int(processed > Fraction(rt.number(ins, 1), 1000)))
    return task.pc + 1
