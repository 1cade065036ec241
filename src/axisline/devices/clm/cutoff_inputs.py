"""The flying cutoff's input functions (manual §7.12 L3952-4022, A133-A137, A142; spec §4.12):
immediate cut and the manual cut vector (A134), cut inhibit (A133), crop cut (A142), reverse
inhibit (A135), rapid stop (A136, error 3B), maximum stroke (A137, error 3C) and indexing (A134's
digit, error 3A). `CutoffInputs` is a part of `cutoff.FlyingCutoff` (one object per CLM).

Decisions (spec line -> choice, why)
------------------------------------
1. L3954 "immediately accelerates to the material speed, regardless of the pre-set length ...
   only accepted if the axis is at the start position (Position 0). The signal must be a pulse"
   -> a rising edge in Automatic while a length instruction waits with the carriage at home
   (within A127) makes the cut point the one a plain ramp meets at once (the point under the
   tool now plus the ramp's stroke); the following lengths count from it. Elsewhere the edge is
   not accepted. test_immediate_cut_cuts_at_once.
2. L3958 (manual cut vector) -> in Manual a rising edge starts Task 1 at A134's start
   instruction, as B014's manual vector (jog disabled, Automatic held off until its RTS).
   test_manual_cut_vector_runs_in_manual.
3. L3962-3966 (cut inhibit) -> a rising edge in Automatic before the approach has started
   inhibits the synchronization (the A133 output is set while it lasts); only an immediate cut
   ends it (cutting at once); Manual cancels it; the product length counter stands meanwhile.
   test_cut_inhibit_until_an_immediate_cut.
4. L4016 (crop cut) -> a rising edge in Automatic with the carriage at home sets the A142 length
   (plus A141) as the length of the instruction waiting now, once. test_crop_cut_sets_the_length.
5. L3998 (reverse inhibit) -> with A135 set, EOS brakes the carriage to a stop instead of
   returning it; a rising edge after EOS starts the return (a signal present at EOS is "not
   evaluated": it needs to go and come again). test_reverse_inhibit_holds_the_return.
6. L4002-4006, L4914-4927 (rapid stop) -> a rising edge in Automatic: synchronous with an A136
   start instruction -> Task 1 continues there (the processing program is dropped, the gear
   holds), and its EOS is fault 3B; otherwise fault 3B at once (the fault sets the command to
   0 V). test_rapid_stop_runs_its_program_then_3b.
7. L4010-4012, L4933-4945 (maximum stroke) -> checked every cycle while synchronous: A104 -
   the carriage's set point < the A137 stroke -> as rapid stop with A137's start and fault 3C.
   A retract program still running when the carriage reaches A104 is fault 47 "Max Travel Lmt 1"
   (L4943, the carriage homed or not). test_maximum_stroke_is_3c,
   test_a_retract_program_at_the_travel_limit_is_47.
8. L3976-3987 (indexing, A134 digit 1) -> the first length after Automatic counts from the cut
   made in Manual: the material the FUN material channel (V026) measured through the tool
   since then is subtracted (last cut = point under the tool - V026); more than the length is
   fault 3A "Index Length". Without indexing, or without a FUN measurement, the length counts
   from the point under the tool (the manual's 6000 mm). test_indexing_counts_from_the_manual_cut.
"""

from __future__ import annotations

from typing import Any

from .errors import ClmError, axis_fault
from .operands import Operand

__all__ = ["CutoffInputs"]


def _op(value: Any) -> Operand | None:
    return None if value.unset else value


class CutoffInputs:
    """Mixin of FlyingCutoff: the A133-A137 / A142 inputs; see the module docstring."""

    rt: Any
    state: str

    def _configure_inputs(self, params: Any) -> None:
        a133, a134, a135 = params.get("A133"), params.get("A134"), params.get("A135")
        a136, a137, a142 = params.get("A136"), params.get("A137"), params.get("A142")
        self._inhibit_in, self._inhibit_out = _op(a133["cut_inhibit_input"]), _op(a133["cut_inhibit_output"])
        self._immediate_in = _op(a134["immediate_cut_input"])
        self.manual_cut_start = int(a134["manual_cut_start"])
        self.indexing = int(a134["indexing"]) == 1
        self._reverse_in = _op(a135["reverse_inhibit_input"])
        self._rapid_in = _op(a136["rapid_stop_input"])
        self.rapid_start = int(a136["rapid_stop_start"])
        self.max_stroke = float(a137.number("maximum_stroke"))
        self.stroke_start = int(a137["maximum_stroke_start"])
        from fractions import Fraction

        self.crop_length = Fraction(str(a142.number("crop_cut_length")))
        self._crop_in = _op(a142["crop_cut_input"])
        self._edge_inputs = any(op is not None for op in (self._immediate_in, self._inhibit_in, self._crop_in, self._rapid_in, self._reverse_in))
        self.inhibited = False
        self.reverse_held = False
        self.retract_fault: str | None = None  # "3B" / "3C": the retract program's EOS faults
        self._previous: dict[Operand, int] = {}

    def _edge(self, op: Operand | None) -> bool:
        if op is None:
            return False
        now = self.rt.read_bit(op)
        before = self._previous.get(op, now)
        self._previous[op] = now
        return bool(now and not before)

    def _at_home(self) -> bool:
        axis = self.axis  # type: ignore[attr-defined]
        return bool(axis.motion_done and abs(axis.actual_position) <= float(getattr(axis, "threshold", 0.0)))

    def _waiting_length(self) -> bool:
        task = self.rt.tasks[0]
        return bool(task.running and task.wait == "cutoff")

    # -- per cycle ------------------------------------------------------------------------------

    def tick_inputs(self, mode: str) -> None:
        if self._edge_inputs:
            immediate = self._edge(self._immediate_in)
            inhibit = self._edge(self._inhibit_in)
            crop = self._edge(self._crop_in)
            rapid = self._edge(self._rapid_in)
            reverse = self._edge(self._reverse_in)
        else:  # none of the five inputs is programmed (00.00.0): nothing to read
            immediate = inhibit = crop = rapid = reverse = False
        if mode == "manual":
            self._set_inhibit(False)  # decision 3: Manual cancels it
            modes = self.rt.modes
            if immediate and not modes.manual_vector and self.manual_cut_start:  # decision 2
                self.rt.tasks[0].start(self.manual_cut_start)
                modes.manual_vector = True
            return
        if mode != "automatic" or not self.rt.modes.running:
            return
        if rapid:  # decision 6
            self._retract("3B", self.rapid_start, "Rapid Stop input")
            return
        if self.retract_fault is not None:  # decision 7: the retract program must end before A104
            axis = self.axis  # type: ignore[attr-defined]
            if axis.actual_position >= axis.max_travel:
                raise ClmError(axis_fault(0x07, 1), f"the retract program ({self.retract_fault}) had not ended (EOS) when the "
                                                    f"carriage reached A104 = {axis.max_travel:.3f} (L4943)")
        if self.state == "synchronous" and self.max_stroke > 0.0 and self.retract_fault is None:  # decision 7
            axis = self.axis  # type: ignore[attr-defined]
            if axis.max_travel - axis.command_position < self.max_stroke:
                self._retract("3C", self.stroke_start, f"A137 maximum stroke {self.max_stroke:.3f}")
                return
        if inhibit and self.state in ("home", "returning"):
            self._set_inhibit(True)
        if crop and self._at_home() and self._waiting_length() and self.state == "home":  # decision 4
            self.set_length(self.crop_length)  # type: ignore[attr-defined]
        if immediate and self._at_home() and self._waiting_length() and self.state == "home":  # decision 1
            self._set_inhibit(False)
            self.cut_now()  # type: ignore[attr-defined]
        if reverse and self.reverse_held:  # decision 5
            self.reverse_held = False
            self.return_home()  # type: ignore[attr-defined]

    def _set_inhibit(self, on: bool) -> None:
        if on != self.inhibited:
            self.inhibited = on
            if self._inhibit_out is not None:
                self.rt.write_bit(self._inhibit_out, int(on))

    def _retract(self, code: str, start: int, why: str) -> None:
        """Decisions 6, 7: synchronous with a program -> Task 1 runs it; else the fault now."""
        if self.state == "synchronous" and start:
            task = self.rt.tasks[0]
            task.stack.clear()
            task.pc, task.wait = start, None
            self.retract_fault = code
            return
        raise ClmError(code, f"{why} (not synchronous or no retract program): the drive command is set to 0 V")

    def after_retract(self) -> None:
        """EOS of the rapid stop / maximum stroke program: its fault."""
        code, self.retract_fault = self.retract_fault, None
        if code is not None:
            raise ClmError(code, "the retract program ended (EOS): the drive command is set to 0 V")
