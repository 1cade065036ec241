"""The COMPAX program interpreter: runs the sets of the program memory on the cam operation.

    run = ProgramRun(program, op, params)       # op: camop.CamOperation on the slave axis
    run.start()                                 # START: from N001 (or where STOP left it)
    every 1 ms cycle:   run.tick(cycle); op.tick(cycle); run.watch(cycle)
    run.stop() / run.brk()                      # STOP / BREAK
    run.summary()                               # state, set, errors, the curve transfers

Sequencing (manual §15.1 L1401-1415, §23 P210 L1983): with P210 = 0 ("linear processing of
the program memory") a set waits while a positioning command runs, so a LOOP holds the
program until it has been carried out, and a POSA until the slave stands. With P210 = 1
("the program continues to run during positioning commands and stops at the next
positioning command") only the next positioning set waits; a SETC and a LOOP given while a
LOOP runs select and link the next curve (§15.2 L1429-1434: "the 2nd curve then starts
instantaneously after the 1st curve is terminated"), which the cam operation takes over at
the end of the running LOOP's counter (camop D14). Positioning sets wait for the power stage
(L136-140 "if the program is not functioning: The output stage is disabled in the basic
condition! It can be enabled by I12").

Decisions (tests in tests/devices/compax/test_programrun.py unless named)
-------------------------------------------------------------------------
1. One set per 1 ms cycle (L1434 "A processing time of ca. 10ms is required for the
   interpretation of the commands in the program memory"; the time per set is not given):
   each cycle the interpreter executes at most one set, so a GOTO loop never holds a cycle
   and a linked SETC + LOOP take two cycles, well inside the 10 ms the cam operation asks
   for (LINK_LEAD_CYCLES). Test: test_one_set_per_cycle.
2. Parallel mode and linking (L1405-1410, L1429-1434, L1497-1510): with P210 = 1 a SETC while
   a LOOP runs waits while a linked LOOP is still pending (the curve memory "only operates
   forwards": one curve ahead), then selects the next curve; the LOOP after it links it; any
   other positioning set waits until the running one is done ("stops at the next positioning
   command"). A LOOP while a LOOP runs without a SETC since links the running curve again:
   the variable linking example "N006: LOOP 1 / N007: If I8=1 GOTO 6 ... Curve 1 is repeated
   until I8=0" (L1505-1506) repeats curve 1 seamlessly, as it can only mean. Tests: the §15
   programs in test_programs_of_the_manual.py.
3. LOOP in linear mode (L1403, L890 "the LOOP - command is still active and COMPAX does not
   carry out any commands"): with P210 = 0 every set waits while a LOOP is active or the
   slave positions, so LOOP 0 holds the program until STOP / BREAK. Tests:
   test_loop_0_holds_the_program_until_stop_which_continues_at_the_next_set,
   test_parallel_mode_runs_on_during_a_positioning_and_stops_at_the_next.
4. START / STOP / BREAK (§12.0.1 L916-922 "Stop interrupts the cam operation and brings the
   slave to a standstill via a ramp ... As a further step the next command will be used in
   the program memory"; the standard manual's program control is not in the sources): START
   runs the program from its set pointer (N001 after power on, END and BREAK); STOP brakes
   the slave on its ramp (camop.stop, leaving the LOOP), halts the program and leaves the
   pointer on the set after the interrupted one, where the next START continues; BREAK does
   the same and puts the pointer back to the first set. START while the program runs is
   E107; START without sets is E17 ("Selected set number not present"). Tests:
   test_loop_0_holds_the_program_until_stop_which_continues_at_the_next_set,
   test_break_puts_the_program_back_to_its_first_set, test_program.py::test_start_without_sets_is_e17.
5. Errors (the standard device stops its program at an error): a set answered with an error
   (E17 curve not present, E107 command refused now, ...) stops the program on that set
   with the error (S30); a slave that falls into an error stop (E10 tracking error, E25)
   stops it too. START runs the set again. Test:
   test_a_set_answered_with_an_error_stops_the_program_and_fails_the_run.
6. The program's end (the set after the last stored one, or END) leaves the pointer on the
   first set; a LOOP still running then runs on (a LOOP is a command of the device, not of
   the program). Test: test_programs_of_the_manual.py::test_example_1_doffing_curves_in_normal_mode.
"""

from __future__ import annotations

import math
from typing import Any, Callable

from axisline.devices.compax import E_CURVE_NOT_PRESENT, E_NOT_AVAILABLE, E_TRACKING, CompaxError
from axisline.devices.compax.masterchain import valid_values
from axisline.devices.compax.program import MOTION_KINDS, Command, Kind, ProgramMemory
from axisline.motion.axis import AxisState

__all__ = ["ProgramRun", "STATES"]

STATES = ("stopped", "running", "ended", "error")
_MOVING = (AxisState.DISCRETE_MOTION, AxisState.CONTINUOUS_MOTION, AxisState.HOMING, AxisState.STOPPING)
MAX_LOG = 2000  # curve transfers kept for the summary


class ProgramRun:
    """Runs a `ProgramMemory` on a `CamOperation` (see the module doc)."""

    def __init__(self, program: ProgramMemory, op: Any, params: Any, *,
                 on_error: Callable[[dict[str, Any]], None] | None = None) -> None:
        self.program = program
        self.op = op
        self.params = params
        self._pv = valid_values(params)  # the valid values, read every cycle
        self.axis = op.axis
        self.period = float(op.period)
        self.on_error = on_error
        self.state = "stopped"
        self.pointer: int | None = None  # the set to run next (None: the first)
        self.executed = 0  # sets run since power on
        self.errors: list[dict[str, Any]] = []
        self.log: list[dict[str, Any]] = []  # LOOP starts, curve transfers, LOOP ends
        self.speed = 100.0  # SPEED, % of v_max
        self.accel: float | None = None  # ACCEL, ms from 0 to v_max (None: the axis' a_max)
        self._wait_until: int | None = None
        self._cycle = 0
        self._seen: tuple[bool, Any] = (False, None)

    # ------------------------------------------------------------------ control (decision 4)

    @property
    def running(self) -> bool:
        return self.state == "running"

    def start(self) -> None:
        if self.running:
            raise CompaxError("START not allowed: the program is running", code=E_NOT_AVAILABLE, field="START",
                              allowed="program stopped")
        if not len(self.program):
            raise CompaxError("START: no program sets stored (E17, selected set number not present)",
                              code=E_CURVE_NOT_PRESENT, field="START", allowed="N001 ... N250 stored")
        if self.pointer is None or self.pointer not in self.program:
            self.pointer = self._from(self.pointer)
        self.state = "running"

    def stop(self) -> None:
        """STOP: brake the slave on its ramp (leaving a LOOP); continue later after the set."""
        self._halt_motion()
        if self.running:
            self.state = "stopped"
        self._wait_until = None

    def brk(self) -> None:
        """BREAK: as STOP, and the program starts again at its first set."""
        self.stop()
        self.state = "stopped"
        self.pointer = self.program.first()

    def _halt_motion(self) -> None:
        op, ax = self.op, self.axis
        if op.loop_active or ax.state in _MOVING:
            op.stop()

    def direct(self, command: Command) -> None:
        """A command sent over the interface (endpoint.py decision 2): a positioning command
        while another runs, or with the power stage off, is refused with E107."""
        if command.kind in MOTION_KINDS:
            if self.busy():
                raise CompaxError(f"{command.text} refused: a positioning command runs (the second one is "
                                  "rejected, sec. 15.1)", code=E_NOT_AVAILABLE, field=command.kind.value,
                                  allowed="slave at standstill, no LOOP active")
            if self.axis.state is AxisState.DISABLED:
                raise CompaxError(f"{command.text} refused: the power stage is off (I12)", code=E_NOT_AVAILABLE,
                                  field="I12", allowed="I12 = 1")
        self._execute(command, self._cycle)

    def _from(self, number: int | None) -> int | None:
        """The stored set at or after `number` (the first set for None)."""
        if number is None:
            return self.program.first()
        return number if number in self.program else self.program.next_after(number)

    # ------------------------------------------------------------------ per cycle

    def busy(self) -> bool:
        """A positioning command runs: a LOOP (or a linked one waits), or the slave moves."""
        op = self.op
        return bool(op.loop_active or self.axis.state in _MOVING or op.datum_travel_pending)

    def _parallel(self) -> bool:
        return int(self._pv[210]) == 1

    def tick(self, cycle: int) -> None:
        """One cycle, before the cam operation's: run at most one set (decision 1)."""
        self._cycle = cycle
        if self.state != "running":
            return
        if self.axis.state is AxisState.ERROR_STOP:  # decision 5
            code = self.op.last_error or E_TRACKING
            self._fail(CompaxError(f"slave {self.axis.name} in error stop ({self.axis.error_text or 'fault'})",
                                   code=code, field="axis"), None)
            return
        number = self.pointer
        if number is None or number not in self.program:
            number = self._from(number)
            if number is None:
                self._end()
                return
            self.pointer = number
        command = self.program.command(number)
        if not self._parallel() and self.busy():  # decision 3
            return
        try:
            outcome = self._execute(command, cycle)
        except CompaxError as e:
            self._fail(e, number)
            return
        if outcome == "wait":
            return
        self.executed += 1
        if outcome == "end":
            self._end()
        elif isinstance(outcome, int):
            self.pointer = outcome
        else:
            self.pointer = self.program.next_after(number)
            if self.pointer is None:
                self._end()

    def _end(self) -> None:
        self.state = "ended"
        self.pointer = self.program.first()

    def _fail(self, e: CompaxError, number: int | None) -> None:
        self.state = "error"
        self._wait_until = None
        code = e.code if e.code is not None else E_NOT_AVAILABLE
        record = {"set": number, "text": self.program.read(number) if number in self.program else None,
                  "code": code, "message": str(e), "t": self._cycle * self.period}
        self.errors.append(record)
        if self.on_error is not None:
            self.on_error(record)

    # ------------------------------------------------------------------ one set

    def _execute(self, c: Command, cycle: int) -> str | int:
        """Run one set: "next", "wait" (run it again next cycle), "end" or a set number."""
        op, k = self.op, c.kind
        if k in MOTION_KINDS:
            return self._motion(c)
        if k is Kind.SETC:
            if op.loop_active and op.link_pending:
                return "wait"  # decision 2: one curve ahead
            op.setc(c.args[0])
        elif k is Kind.SETM:
            op.setm(c.args[0])
        elif k is Kind.SETS:
            op.sets()
        elif k is Kind.PARAM:
            self.params[c.args[0]] = c.args[1]
        elif k in (Kind.VP, Kind.VC):
            make_valid = getattr(self.params, "make_valid", None)
            if callable(make_valid):
                make_valid(k.value)
        elif k is Kind.SPEED:
            self.speed = float(c.args[0])
        elif k is Kind.ACCEL:
            self.accel = float(c.args[0])
        elif k is Kind.WAIT:
            if self._wait_until is None:
                self._wait_until = cycle + max(0, math.ceil(c.args[0] / 1000.0 / self.period - 1e-9))
            if cycle < self._wait_until:
                return "wait"
            self._wait_until = None
        elif k is Kind.GOTO:
            return self._jump(c.args[0])
        elif k is Kind.IF:
            i, x, n = c.args
            if bool(op.input(f"I{i}")) == bool(x):
                return self._jump(n)
        elif k is Kind.OUTPUT:
            op.set_output(c.args[0], bool(c.args[1]))
        elif k is Kind.END:
            return "end"
        return "next"

    def _jump(self, number: int) -> int:
        self.program.command(number)  # E17 if it is not there (cannot happen: checked when stored)
        return number

    def _motion(self, c: Command) -> str:
        op, ax, k = self.op, self.axis, c.kind
        if k is Kind.LOOP and op.loop_active and self._parallel():
            if op.link_pending:
                return "wait"
            if not op.next_curve_selected and op.curve is not None:
                op.setc(op.curve.number)  # decision 2: link the running curve again
            op.loop(c.args[0])
            return "next"
        if self.busy():
            return "wait"
        if ax.state is AxisState.DISABLED:
            return "wait"  # the power stage is off (L136-140)
        v_max = float(ax.config.v_max)
        velocity = v_max * self.speed / 100.0
        acceleration = v_max / (self.accel / 1000.0) if self.accel else None
        if k is Kind.LOOP:
            op.loop(c.args[0])
        elif k is Kind.POSR_CAM:
            op.posr_cam(velocity, acceleration)
        elif k is Kind.POSA_HOME:
            op.posa_home(interface=False)
        else:
            move = ax.move_absolute if k is Kind.POSA else ax.move_relative
            cmd = move(float(c.args[0]), velocity, acceleration, acceleration)  # ACCEL: both ramps
            if getattr(cmd, "error", False):
                raise CompaxError(f"{c.text}: {cmd.error_text}", code=E_NOT_AVAILABLE, field=c.kind.value,
                                  value=c.args[0])
        return "next"

    # ------------------------------------------------------------------ record

    def watch(self, cycle: int) -> None:
        """After the cam operation's cycle: log LOOP starts, curve transfers and LOOP ends (for
        the summary and the report) with S1, the curve set point S47 and the master position S44
        of that cycle. A transfer gives the cam operation a new curve object, also when it links
        the same curve."""
        op = self.op
        active, curve = bool(op.loop_active), op.curve
        seen = self._seen
        if seen[0] == active and seen[1] is curve:
            return  # nothing changed (the cycle of a running or an idle cam operation)
        was_active, was_curve = seen
        self._seen = (active, curve)
        if (active == was_active and (not active or curve is was_curve)) or len(self.log) >= MAX_LOG:
            return
        event = "end" if was_active and not active else ("transfer" if was_active else "loop")
        self.log.append({"t": cycle * self.period, "event": event, "curve": int(op.status(43)),
                         "loop": int(op.loop_m), "S1": float(op.status(1)),
                         "S44": float(op.status(44)), "set_point": float(op.status(47))})

    def summary(self) -> dict[str, Any]:
        return {
            "sets": len(self.program),
            "state": self.state,
            "next_set": self.pointer,
            "executed": self.executed,
            "errors": list(self.errors),
            "curves": list(self.log),
        }

    def report_lines(self) -> list[str]:
        """The program section of report.md (Markdown lines; empty without a program)."""
        if not len(self.program):
            return []
        lines = ["## COMPAX program", "",
                 f"- {len(self.program)} sets, {self.executed} run; state {self.state}"
                 + (f", next set N{self.pointer:03d}" if self.pointer else ""), ""]
        if self.errors:
            e = self.errors[-1]
            where = f"N{e['set']:03d}" if e["set"] else "the slave"
            lines += [f"- error at {where}: {e['message']}", ""]
        if self.log:
            lines += ["| t [s] | event | curve | LOOP | S44 [per mille] | S1 | S47 |", "|---|---|---|---|---|---|---|"]
            for r in self.log[:200]:
                lines.append(f"| {r['t']:.3f} | {r['event']} | {r['curve']} | {r['loop']} | {r['S44']:.1f} | "
                             f"{r['S1']:.3f} | {r['set_point']:.3f} |")
            if len(self.log) > 200:
                lines.append(f"| ... | {len(self.log) - 200} more in summary.json | | | | | |")
            lines.append("")
        return lines
