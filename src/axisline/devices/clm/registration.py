"""Mark search and registration of the CLM: SRM with REP, SRP modes 0-3, RMI, Status 41.

    rt.registration = Registration(rt)        # the runtime owns one
    rt.registration.armed                     # False: nothing costs a cycle (runtime checks it)

A command that waits for a mark *arms* a `Watch` on its input; while any watch is armed the
runtime calls `tick` once per NC cycle before the tasks run, and the watch latches the axis
position at the mark:

* a raster input (I0.01.7 Raster 1 for axis 1, I0.01.4 Raster 2 for axis 2) wired to a plant
  sensor with sub-cycle edges (`personality`: ``"I0.01.7" = "marks"``) latches at the CLM's
  100 us resolution: the edge time is rounded up to the next 100 us of the cycle and the axis
  position there is interpolated by the kernel's `MarkCapture` between the actual positions at
  the cycle's start and end (L2610-2612, L7091-7093 "approximately 0 to 150 us");
* every other input (and a raster input without such a sensor) is seen at the cycle: the image
  bit, debounced for one cycle (L2630 "a debouncing time of the time period of one cycle";
  the raster has "no hardware debouncing", L2610); the position is the actual one then.

Decisions (spec line -> choice, why)
------------------------------------
1. SRM (L2604-2616) -> CON at the signed per mille until a rising edge, then "immediately" a
   positioning to mark + offset (in IU, FAK not applied: Fig. 5-27 reads it as IU) at the
   search speed; the task proceeds in the cycle the mark is detected (L2606), the offset move runs on
   as a POI does. Tests: tests/devices/clm/test_registration.py::test_srm_accuracy_normal_input_and_raster,
   test_srm_offset_example.
2. Normal-input latency (L2630-2635, Fig. 5-25 "v x 2 x cycle time") -> seen at the next cycle
   start, accepted one cycle later (debounce): the latch is T..2T late, at 100 IU/s and 2 ms
   0.2..0.4 IU; Raster 1: <= 100 us, 0.01 IU. Test: test_srm_accuracy_normal_input_and_raster.
3. REP placement, spec S-L2732 and errata §1.17 (L2350 "must not ... immediately after" vs the
   example L2364-2365 and error 1A) -> both readings: a REP on the line right after an SRM
   limits that SRM (a different axis there is 1A, checked when the SRM starts), and every REP
   executed sets a limit for its axis that stays for all later SRMs "until another REP" (L2352),
   cleared by a mode change, a fault or power up (L2354); distance 0 = no limit. Exceeding the
   distance from the search start: PBK-brake and jump to the REP target at once (L2348).
   Tests: test_rep_limit_jumps_and_brakes, test_rep_persists_until_the_next_rep, test_rep_other_axis_is_1a.
4. SRP (L2653-2700) -> measurement on each PSI of axis 1 after SRP (not POI/POA/PSA: "the
   following feed command PSI"); measured (+0) = end position - mark, desired (+1) is the
   program's value (the examples SET it; spec ambiguity 9), correction = desired - measured
   limited to +-(+2) (0 = no correction); modes 1 next PSI, 2 the current one at once, 3 none;
   +3/+4 from the PSI's start position, +4 = 0 no end; +0 and marker M2.xx.4 are cleared when
   the next PSI starts; a window passed without a mark completes the PSI and jumps to +5.
   Tests: test_srp_mode_1_corrects_the_next_psi, test_srp_mode_3_only_detects, test_srp_search_window_jump.
5. RMI (L2373-2433, errata §1.16) -> any input (I1.01.7 in Fig. 5-20 is an ordinary input,
   latched at the cycle; I0.01.7 at 100 us); at the mark Task 1 is suspended (not stepped) with
   its target and speed kept; the PSI/POI of Task 2 then goes to mark + offset (000 per mille:
   the last speed); RMI 1 1 moves to the kept target at the kept speed and Task 1 goes on.
   Test: test_rmi_fig_5_20_suspends_and_resumes_the_feed.
7. RMI constraints (L2391-2407) -> RMI in a task other than 2 is fault 0A when it runs (L2393
   "must be programmed in Task 2"); RMI 1 0 while the feed of the last raster still waits for
   its RMI 1 1 is 0A ("Detecting an additional raster before the command RMI_1_1 is not
   possible", L2403: the program lost its RMI 1 1); the offset feed not directly after RMI 1 0
   is a load-time warning of `axisline clm check` (L2375); the direction and braking rules
   (L2397, L2405) are the physics of the plant: an offset feed shorter than the braking distance
   reverses the axis, as the manual warns. Tests: test_rmi_outside_task_2_is_0a,
   test_rmi_twice_without_resume_is_0a, test_rmi_short_offset_reverses.
8. RMI's offset feed at 000 per mille (L2382 "the previous command velocity remains valid")
   and the speed of the resumed feed (L2380 "reset to its previous value") -> both as in
   decision 5. Test: test_rmi_fig_5_20_suspends_and_resumes_the_feed.
9. SRP's third field x (L2649 header, always 0 in Figs. 5-29 / 5-30; its meaning is not in
   the manual) -> the grammar takes 0 or 1 as the CLM's column does; x = 1 runs as 0 and
   `axisline clm check` warns. Test: test_srp_x_1_is_a_warning.
6. Status 41 (L7066-7093) -> the axis-1 position latched at the last mark of SRM, SRP or RMI,
   "A" when homed; 0 before any mark. Test: test_status_41_is_the_last_latch.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction
from typing import TYPE_CHECKING, Any

from axisline.motion.registration import ChannelMotion, MarkCapture

from .errors import ClmError
from .fields import VARIABLE_SCALE, Var
from .operands import Operand
from .program import PROGRAM_SIZE, Instruction

if TYPE_CHECKING:
    from .nc import NcTask
    from .runtime import ClmRuntime

__all__ = ["RASTER", "RASTER_RESOLUTION_S", "Registration", "op_rep", "op_rmi", "op_srm", "op_srp"]

RASTER = {(0, 1, 7): 1, (0, 1, 4): 2}  # (source, byte, bit) -> axis: Raster 1 / Raster 2 (L2625)
RASTER_RESOLUTION_S = 100e-6  # L2612 "within a time frame of approx. 100 microseconds"


class Watch:
    """One armed mark detection on an input for an axis (see the module docstring)."""

    def __init__(self, rt: ClmRuntime, axis: Any, op: Operand) -> None:
        self.axis = axis
        self.op = op
        self.mark: float | None = None  # the latched axis position (axis frame), once detected
        key = (op.source, op.byte, op.bit)
        sensor = rt.registration.raster_sensors.get(key) if op.area == "I" else None
        self.sensor = sensor  # a plant sensor with sub-cycle edges: raster latch
        self.debounce = key not in RASTER or op.area != "I"
        self.period = rt.nc_cycle_s
        self.channel = ChannelMotion(axis.actual_position)
        self.capture = MarkCapture(self.channel, period=self.period)
        bit = rt.read_bit(op)
        self._b1 = self._b2 = bit
        self.start = Fraction(axis.actual_position)
        self.start_of: Fraction | None = None  # the start `start_f` is the float of (_beyond)
        self.start_f = 0.0
        self._pending: float | None = None  # a mark seen, latched at the next poll (-1: at the cycle)
        self.data: Any = None  # the arming command's own values

    def poll(self, rt: ClmRuntime) -> None:
        """The axis position reaches the NC one cycle after the input image (the kernel axis'
        actual position is that of the previous cycle's end), so a mark seen now is latched at
        the next poll, when the positions around it are known (decision 2)."""
        if self.mark is not None:
            return
        position = self.axis.actual_position
        self.channel.advance(position)
        pending = self._pending
        if pending is not None:
            self.mark = position if pending < 0.0 else self.capture.capture(pending).master
            return
        if self.sensor is not None:
            for edge in self.sensor.edges:  # the edges of the plant cycle just ended
                if edge.rising:
                    steps = math.ceil(edge.fraction * self.period / RASTER_RESOLUTION_S - 1e-9)
                    self._pending = min(1.0, steps * RASTER_RESOLUTION_S / self.period)
                    return
            return
        bit = rt.read_bit(self.op)
        if self.debounce:
            rising = bit and self._b1 and not self._b2
        else:
            rising = bit and not self._b1
        self._b2, self._b1 = self._b1, bit
        if rising:
            self._pending = -1.0  # the position of the cycle it is accepted in


@dataclass
class Srp:
    mode: int
    base: int  # Vbase
    marker: Operand  # M2.xx.4
    pending: Fraction = Fraction(0)  # mode 1: the correction of the next PSI
    watch: Watch | None = None
    target: Fraction | None = None  # the end position of the measured PSI
    missed: bool = False


@dataclass
class Rmi:
    mark: float
    target: Fraction | None
    speed: float
    offset_done: bool = False


class Registration:
    def __init__(self, rt: ClmRuntime) -> None:
        self.rt = rt
        self.raster_sensors: dict[tuple[int, int, int | None], Any] = {}  # wired by the personality
        self.watches: list[Watch] = []
        self.armed = False
        self.limits: dict[int, tuple[int, Fraction]] = {}  # REP: axis -> (target, distance)
        self.srp: Srp | None = None
        self.rmi: Rmi | None = None
        self.suspended_task: int | None = None  # RMI: Task 1 is not stepped while suspended
        self.latch41: float = 0.0
        self.products: list[dict[str, float]] = []  # SRP: per measured PSI (the report's table)

    # -- watches -------------------------------------------------------------------------------

    def arm(self, axis: Any, op: Operand) -> Watch:
        w = Watch(self.rt, axis, op)
        self.watches.append(w)
        self.armed = True
        return w

    def disarm(self, w: Watch | None) -> None:
        if w is not None and w in self.watches:
            self.watches.remove(w)
        self.armed = bool(self.watches)

    def tick(self) -> None:
        """Once per NC cycle while a watch is armed, before the tasks."""
        rt = self.rt
        for w in list(self.watches):
            w.poll(rt)
            if w.mark is not None and w.axis.number == 1:
                self.latch41 = w.mark
        srp = self.srp
        if srp is not None and srp.watch is not None:
            self._srp_poll(srp)

    def reset(self) -> None:
        """Mode change, fault, power up: REP limits cleared (L2354), SRP / RMI ended."""
        self.watches.clear()
        self.armed = False
        self.limits.clear()
        self.srp = None
        self.rmi = None
        self.suspended_task = None

    @property
    def hooked(self) -> bool:
        """SRP or RMI take part in the positionings of axis 1."""
        return self.srp is not None or self.rmi is not None

    # -- positionings (execute._position) ------------------------------------------------------

    def position(self, axis: Any, task: NcTask, absolute: bool, wait: bool, value: int, per_mille: int) -> None:
        rmi = self.rmi
        if rmi is not None and task.number == 2 and not absolute and not rmi.offset_done:
            rmi.offset_done = True  # the offset from the raster position (L2379)
            axis.move_to(Fraction(rmi.mark) + Fraction(value, 1000), None if per_mille == 0 else axis.per_mille_speed(per_mille))
            return
        srp = self.srp
        measured = srp is not None and wait and not absolute and task.number != 2
        if measured:
            self._srp_clear(srp)  # type: ignore[arg-type]
        start = axis.exact_target if axis.exact_target is not None else Fraction(axis.command_position)
        if absolute:
            axis.position_absolute(value, per_mille)
        else:
            axis.position_incremental(value, per_mille)
        if measured:
            assert srp is not None
            if srp.mode == 1 and srp.pending:
                axis.shift_target(srp.pending)
            srp.pending = Fraction(0)
            srp.watch = self.arm(axis, Operand("I", 0, 1, 7))
            srp.watch.start = start
            srp.target = axis.exact_target
            srp.missed = False

    def feed_done(self, task: NcTask, nxt: int) -> int:
        """A PSI of axis 1 is in position: SRP's jump when its window passed without a mark."""
        srp = self.srp
        if srp is None or task.number == 2:
            return nxt
        self.disarm(srp.watch)
        srp.watch = None
        if srp.missed:
            srp.missed = False
            target = self._var(srp.base + 5) // VARIABLE_SCALE
            if not 0 <= target < PROGRAM_SIZE:
                raise ClmError("0E", f"SRP: V{srp.base + 5:03d} = {target} is no instruction")
            return target
        return nxt

    # -- SRP -------------------------------------------------------------------------------------

    def _var(self, n: int) -> int:
        return self.rt.memory.variables[n]

    def _srp_clear(self, srp: Srp) -> None:
        self.rt.image.set(srp.marker, 0)
        self.rt.memory.variables.write(srp.base, 0)
        self.disarm(srp.watch)
        srp.watch = None

    def _srp_poll(self, srp: Srp) -> None:
        w = srp.watch
        assert w is not None and srp.target is not None
        if w.mark is None:  # (every cycle of the search)
            end_raw = self._var(srp.base + 4)
            if end_raw and _beyond(w, end_raw):
                srp.missed = True  # the end of search passed: the PSI completes, then +5
                self.disarm(w)
                srp.watch = None
            return
        begin = Fraction(self._var(srp.base + 3), VARIABLE_SCALE)
        end = Fraction(self._var(srp.base + 4), VARIABLE_SCALE)
        travelled = abs(Fraction(w.mark) - w.start)
        if travelled < begin or (end and travelled > end):
            w.mark = None  # outside the search window: ignored, search on
            return
        self.disarm(w)
        srp.watch = None
        measured = srp.target - Fraction(w.mark)
        self.rt.memory.variables.write(srp.base, round(measured * VARIABLE_SCALE))
        self.rt.image.set(srp.marker, 1)
        desired = Fraction(self._var(srp.base + 1), VARIABLE_SCALE)
        limit = abs(Fraction(self._var(srp.base + 2), VARIABLE_SCALE))
        correction = max(-limit, min(limit, desired - measured))
        if len(self.products) < 100_000:
            self.products.append({"product": len(self.products) + 1, "mark": w.mark, "measured": float(measured),
                                  "correction": float(correction) if srp.mode != 3 else 0.0})
        if srp.mode == 3:
            return
        if srp.mode == 1:
            srp.pending = correction
        else:  # mode 2: the current positioning at once
            w.axis.shift_target(correction)


def _beyond(w: Watch, end_raw: int) -> bool:
    """|actual - start| > end (end in millionths), exact. The float difference decides when it
    is clearly inside (a margin a million times any rounding of it): the exact Fractions are
    worked out only near the end of the search, not in every cycle of it."""
    actual = w.axis.actual_position
    start = w.start
    if start is not w.start_of:
        w.start_of, w.start_f = start, float(start)
    end_f = end_raw / VARIABLE_SCALE
    if abs(actual - w.start_f) < end_f - 1e-9 * (1.0 + abs(actual) + abs(w.start_f) + end_f):
        return False
    return abs(Fraction(actual) - start) > Fraction(end_raw, VARIABLE_SCALE)


# -- the commands ------------------------------------------------------------------------------


def _axis_number(rt: ClmRuntime, ins: Instruction, index: int) -> int:
    value = ins.values[index]
    if isinstance(value, Var):
        return rt.memory.variables[value.number] // VARIABLE_SCALE
    return int(value)  # type: ignore[call-overload]


def _rep_after(rt: ClmRuntime, task: NcTask, number: int) -> tuple[int, Fraction] | None:
    """The limit of this SRM: a REP on the next line (1A on another axis), else the axis' REP."""
    nxt = task.pc + 1
    if nxt < PROGRAM_SIZE:
        ins = rt.memory.program[nxt]
        if ins.mnemonic == "REP":
            other = _axis_number(rt, ins, 1)
            if other != number:
                raise ClmError("1A", f"REP at {nxt:04d} for axis {other} right after SRM for axis {number}")
            distance = Fraction(rt.number(ins, 2), 1000)
            return (rt.target(ins, 0), distance) if distance else None
    return rt.registration.limits.get(number)


def op_srm(rt: ClmRuntime, task: NcTask, ins: Instruction) -> int | None:
    reg = rt.registration
    axis = rt.axis(ins, 0)
    if task.wait is None:
        limit = _rep_after(rt, task, axis.number)
        per_mille = rt.number(ins, 2)
        axis.continuous(True, per_mille)
        w = reg.arm(axis, ins.values[3])  # type: ignore[arg-type]
        w.data = (limit, Fraction(rt.number(ins, 1), 1000), per_mille)
        task.wait = w
        return None
    w = task.wait
    limit, offset, per_mille = w.data
    if w.mark is not None:
        reg.disarm(w)
        axis.move_to(Fraction(w.mark) + offset, axis.per_mille_speed(abs(per_mille)))
        return task.pc + 1
    if limit is not None and abs(Fraction(axis.actual_position) - w.start) > limit[1]:
        reg.disarm(w)
        axis.stop_motion()  # "decelerates to a complete stop" (L2348)
        return limit[0]
    return None


def op_rep(rt: ClmRuntime, task: NcTask, ins: Instruction) -> int | None:
    number = _axis_number(rt, ins, 1)
    if task.pc > 0:
        before = rt.memory.program[task.pc - 1]
        if before.mnemonic == "SRM" and _axis_number(rt, before, 0) != number:
            raise ClmError("1A", f"REP for axis {number} right after SRM for axis {_axis_number(rt, before, 0)}")
    distance = Fraction(rt.number(ins, 2), 1000)
    if distance:
        rt.registration.limits[number] = (rt.target(ins, 0), distance)
    else:
        rt.registration.limits.pop(number, None)
    return task.pc + 1


def op_srp(rt: ClmRuntime, task: NcTask, ins: Instruction) -> int | None:
    reg = rt.registration
    rt.axis(ins, 0)
    mode = int(str(ins.values[1]))
    if reg.srp is not None:
        reg.disarm(reg.srp.watch)
    if mode == 0:
        reg.srp = None
        return task.pc + 1
    base: Var = ins.values[3]  # type: ignore[assignment]
    byte: Operand = ins.values[4]  # type: ignore[assignment]
    reg.srp = Srp(mode, base.number, Operand(byte.area, byte.source, byte.byte, 4))
    return task.pc + 1


def op_rmi(rt: ClmRuntime, task: NcTask, ins: Instruction) -> int | None:
    reg = rt.registration
    axis = rt.axis(ins, 0)
    if str(ins.values[1]) == "1":  # resume the main feed (L2425)
        if task.number != 2:
            raise ClmError("0A", f"RMI in Task {task.number}: the raster program must be in Task 2 (L2393)")
        rmi = reg.rmi
        if rmi is not None:
            if rmi.target is not None:
                axis.move_to(rmi.target, rmi.speed)
            reg.rmi = None
            reg.suspended_task = None
        return task.pc + 1
    if task.wait is None:
        if task.number != 2:
            raise ClmError("0A", f"RMI in Task {task.number}: the raster program must be in Task 2 (L2393)")
        if reg.rmi is not None:
            raise ClmError("0A", "RMI 1 0 while the feed of the last raster waits for its RMI 1 1: no additional raster before it (L2403)")
        task.wait = reg.arm(axis, ins.values[2])  # type: ignore[arg-type]
        return None
    w = task.wait
    if w.mark is None:
        return None
    reg.disarm(w)
    reg.rmi = Rmi(w.mark, axis.exact_target, axis.speed)
    reg.suspended_task = 1
    return task.pc + 1
