"""Reverse optimisation of the flying cutoff (manual §7.12 L4022-4029, A139 L4966-4968, L5964,
L6128, A140 L4970-4978; spec §4.12): the carriage returns home with a reduced acceleration so
that it arrives when the next approach has to start, instead of racing back at A108 and waiting.

    opt = ReverseOptimisation(rt, params)   # part of cutoff.FlyingCutoff (rt.cutoff.reverse)
    opt.plan(cutoff)                        # the next length instruction is known: replan the return
    opt.tick(cutoff)                        # every cycle: the velocity window

Decisions (spec line -> choice, why)
------------------------------------
1. A139 input / output (L5964, L6128; figure lost) -> the function is on while its input is 1
   (00.00.0: off, as the other cutoff inputs); the output is 1 while a return runs with a reduced
   acceleration. Reverse inhibit set (A135) turns it off (L4028 "If the function 'Reverse
   Inhibit' is active, no reverse optimization occurs"). test_reverse_optimisation_slows_the_return.
2. L4024 "Acceleration for reverse motion is calculated" -> the next cut point is known when
   Task 1 reaches the next length instruction (a few cycles after EOS); then the return is
   replanned from the carriage's state with one acceleration r for both ramps: the smallest r
   (>= A140's minimum, and large enough to keep the forward overshoot within A104) whose return
   ends the A140 wait time before the approach has to be planned (cutoff.py decision 1), so the
   carriage "accelerates back into synchronization without standing still". If even A108 does
   not make it, the return stays at A108 ("If optimization of the reverse motion is not
   possible"). test_reverse_optimisation_slows_the_return.
3. A140's three-digit values (units lost) -> the minimum acceleration in per mille of A108 and
   the velocity window in per mille of A106, as every other three-digit ramp and velocity of the
   CLM (ACC, A109, POI); the wait time in seconds (0.00). During an optimised return a material
   speed more than the window above the one it was planned for replans the rest at A108 (L4976).
   test_reverse_optimisation_falls_back_to_a108_when_the_line_speeds_up.
"""

from __future__ import annotations

from fractions import Fraction
from typing import Any

from axisline.motion.profiles import Limits, State, plan

__all__ = ["ReverseOptimisation"]

_LEAD_CYCLES = 10  # as cutoff.py's plan lead (decision 2)


class ReverseOptimisation:
    def __init__(self, rt: Any, params: Any) -> None:
        self.rt = rt
        a139, a140 = params.get("A139"), params.get("A140")
        op_in, op_out = a139["reverse_optimization_input"], a139["reverse_optimization_output"]
        self._input = None if op_in.unset else op_in
        self._output = None if op_out.unset else op_out
        self.wait = float(a140.number("wait_time"))
        self.window = int(a140["velocity_window"])  # per mille of A106 (decision 3)
        self.minimum = int(a140["minimum_acceleration"])  # per mille of A108
        self.active = False
        self.ramp: float | None = None  # the reduced acceleration of the running return
        self._v_plan = 0.0

    def enabled(self, cutoff: Any) -> bool:
        return self._input is not None and bool(self.rt.read_bit(self._input)) and cutoff._reverse_in is None

    def _set(self, on: bool, ramp: float | None = None) -> None:
        self.active, self.ramp = on, ramp
        if self._output is not None:
            self.rt.write_bit(self._output, int(on))

    def plan(self, cutoff: Any) -> None:
        """Decision 2: replan the running return for the cut point just set."""
        if cutoff.state != "returning" or cutoff.target is None or not self.enabled(cutoff):
            return
        master, clm = cutoff.master, cutoff.axis
        v_line = master.velocity if master is not None else 0.0
        if v_line <= 0.0:
            return
        a108 = float(clm.acceleration)
        vmax = float(clm.maximum_velocity)
        s_min = v_line * v_line / (2.0 * a108)
        plan_at = float(cutoff.target) + s_min - 2.0 * s_min - _LEAD_CYCLES * v_line * self.rt.nc_cycle_s
        available = (plan_at - master.position) / v_line - self.wait
        ax = clm.axis
        start = State(ax.command_position, ax.command_velocity, ax.command_acceleration)
        room = clm.max_travel - start.p
        if start.v > 0.0 and room <= 0.0:
            return

        def duration(r: float) -> float:
            return plan("trapezoid", start, State(0.0, 0.0), Limits(v=vmax, a=r, d=r)).duration

        lowest = max(a108 * self.minimum / 1000.0, start.v * start.v / (2.0 * room) if start.v > 0.0 else 0.0, 1e-6 * a108)
        if lowest >= a108 or duration(a108) > available:
            return  # not possible: the return stays at A108
        if duration(lowest) <= available:
            r = lowest
        else:
            lo, hi = lowest, a108  # duration falls as r grows
            for _ in range(50):
                mid = 0.5 * (lo + hi)
                if duration(mid) > available:
                    lo = mid
                else:
                    hi = mid
            r = hi
        clm.move_to(Fraction(0), vmax, ramp=r)
        self._v_plan = v_line
        self._set(True, r)

    def tick(self, cutoff: Any) -> None:
        """Decision 3: the velocity window; the output ends with the return."""
        if not self.active:
            return
        if cutoff.state != "returning":
            self._set(False)
            return
        master, clm = cutoff.master, cutoff.axis
        if master is not None and master.velocity > self._v_plan + self.window / 1000.0 * float(clm.maximum_velocity):
            clm.move_to(Fraction(0), float(clm.maximum_velocity))  # the rest at A108
            self._set(False)
