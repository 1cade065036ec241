"""The CLM's operating modes, start and stop, faults, and the system inputs and outputs.

Spec §2 (manual §5.4, §5.5, §7.1, §9.1), §6.2, §6.3; errata §3.8 (what each trigger resets).

=====================  ========  =========================================================
system input           address   what it does here
=====================  ========  =========================================================
Parameter Mode         I0.00.0   with Automatic/Manual: the mode; both on is fault 08
Automatic / Manual     I0.00.1   1 = Automatic
E-Stop (active low)    I0.00.2   0 = fault 03: drive enables off at once
Start                  I0.00.3   rising edge in Automatic starts / continues the program
Immediate Stop (low)   I0.00.4   0 = tasks 1, 2, 4, 5 stop, axes decelerate keeping the rest
Enable Axis 1-4        I0.00.5, I0.00.6, I0.02.0, I0.02.3  the drive's "motor ready"
External Clear         I0.00.7   rising edge clears a fault
Re-Start               I0.01.6   rising edge in Automatic: restart (`restart`), else as Start
Jog + / - axis 1-4     I0.01.0-3, I0.02.1-2, I0.02.4-5 (Manual)
=====================  ========  =========================================================

Outputs: Q0.00.0 Manual, Q0.00.1 Automatic, Q0.00.2 Parameter, Q0.00.5 Error message (active
low: 1 = no fault), Q0.01.0 Restart possible (`restart`), Q0.01.1 Run Task, Q0.01.5 Inhibit
Operation; Q0.00 and Q0.01 are mirrored into the status word Q2.00 / Q2.01 (errata §1.19:
Q2.00.5 is the mirror of the active-low error output; Q2.01.0 is reserved and stays 0). Drive
enable and brake outputs belong to the axes (`axis`).

Mode changes (spec §2.2): into Parameter mode every task and the Logic Task stop and the outputs
and non-retained markers are cleared; out of it the parameters are checked (fault 02 with the
parameter) and the Logic Task compiled (fault 38) and started. Leaving Automatic stops tasks 1,
2, 4, 5, clears M2 and resets ACC, FAK, CON and the texts (errata §3.8); the next Start begins
at 0000 and at the B011/B012 starts. After Immediate Stop, JST or ``!STOP`` the next Start
continues where the tasks stopped, the axes first finishing their remaining distance; a stop by
``!STOP`` is continued only by ``!START`` (L7325). A fault stops tasks 1, 2, 4, 5 (Task 3 and
the Logic Task go on), switches the drives off, clears M2 and the outputs as B018 says; after
it is cleared the program starts again from 0000. The exception is Restart (`restart`): a
fault, a switch to Manual or a power loss while the program runs keeps an image of it that
the Re-Start input (I0.01.6, fieldbus I2.01.6) restores; `restart.Restart.interrupted` is
called before anything is stopped or cleared. In flying cutoff (axis 1 in Ax00 mode 5,
`cutoff`) Start, Immediate Stop, ``!START`` and ``!STOP`` have no function: selecting Automatic
starts the program (cutoff.py decision 7; error 36 away from home).

Decisions (spec line -> choice, why)
------------------------------------
1. C-TASK-ENABLE, B011/B012 (L3428, L3455: ``0200 0000 0`` enables Task 2 at 0200, ``0000 0800
   0`` Task 3 at 0800): a start instruction 0000 means the task is off (Task 1 owns 0000).
   Test: ``tests/devices/clm/test_runtime.py::test_tasks_2_and_3_start_at_b011``.
2. C-FAULT-FIRST: while a fault is present a second one does not replace it (the display and
   Status 53 show the cause, not a consequence). Test: ``test_first_fault_is_kept``.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from .errors import ClmError, axis_fault
from .image import ProcessImage
from .operands import Operand
from .system_io import (AUTOMATIC, CLEAR, ENABLE, ESTOP, IMMEDIATE_STOP, JOG, PARAMETER, RESTART, RESTART_FIELDBUS, START,
                        EdgeBytes, system_outputs)

if TYPE_CHECKING:
    from .nc import NcTask
    from .runtime import ClmRuntime

__all__ = ["ModeMachine"]


def _int(value: object) -> int:
    """A digit or number field's value (int, Decimal or digit string) as an int."""
    return int(value)  # type: ignore[call-overload]


def _operand(value: object) -> Operand:
    """An operand field's value (parameters' ``operand`` fields are Operands)."""
    assert isinstance(value, Operand)
    return value

class ModeMachine:
    def __init__(self, rt: ClmRuntime) -> None:
        self.rt = rt
        self.mode = "power-on"
        self.fault_error: ClmError | None = None
        self.running = False  # Automatic, started, not stopped (Run Task)
        self.restart_from_zero = True
        self.interface_stopped = False
        self.manual_vector = False
        self._pending_interrupt = False
        self._previous: dict[Operand, int] = {}
        self._data = rt.image.data  # the image's bytes (never replaced, written in place)
        self._places = {op: ProcessImage.locate(op) for op in (PARAMETER, AUTOMATIC, ESTOP, START, IMMEDIATE_STOP, CLEAR, RESTART,
                                                              RESTART_FIELDBUS, *ENABLE.values(), *(k for keys in JOG.values() for k in keys))}
        # the four edges evaluate() looks for every cycle, read in one pass (no call per input):
        # the three bytes they are in, as they were at the last cycle, and their bit masks
        self._edge_bytes = EdgeBytes.of(self._places)
        self._edge_before = (0, 0, 0)
        self._mode_places = (self._places[PARAMETER][:2], self._places[AUTOMATIC][:2])
        #: (byte, shift) of E-Stop and of each axis' Enable input (the runtime reads them per axis)
        self.estop_place = self._estop_place = self._places[ESTOP][:2]
        self._stop_place = self._places[IMMEDIATE_STOP][:2]
        self.enable_places = self._enable_places = {n: self._places[op][:2] for n, op in ENABLE.items()}
        self._q = system_outputs()  # where `outputs` writes, as two whole bytes and their mirrors
        self.enabled_axes: frozenset[int] = frozenset()  # B000's axes, less those !MxOFF switched off
        self._enabled_in_order: tuple[int, ...] = ()  # the same, sorted (Automatic checks them every cycle)
        self._parameter_axes: frozenset[int] = frozenset()
        self.interface_off: set[int] = set()
        self._feed_interrupted: set[int] = set()
        # parameter values read every cycle, taken when Parameter mode is left (they change
        # only there): the Ax15 inputs per axis, B014, B015, B018
        self._feed_inputs: list[tuple[int, tuple[Operand, ...]]] = []
        self._b014: tuple[Operand | None, int, int] = (None, 0, 0)
        self._b015: tuple[Operand | None, int, int, int] = (None, 0, 0, 0)
        self._b018: tuple[int, tuple[int, ...]] = (0, (0,) * 7)
        self._stopped_tasks: set[int] = set()  # running when Immediate Stop / JST / !STOP came

    # -- inputs ---------------------------------------------------------------------------

    def _bit(self, op: Operand) -> int:
        at, shift, _ = self._places.get(op) or ProcessImage.locate(op)
        return self._data[at] >> shift & 1

    def _rising(self, op: Operand) -> bool:
        now, before = self._bit(op), self._previous.get(op, 0)
        self._previous[op] = now
        return bool(now and not before)

    def _edge(self, op: Operand, falling: bool) -> bool:
        now, before = self._bit(op), self._previous.get(op, 1 if falling else 0)
        self._previous[op] = now
        return bool(before and not now) if falling else bool(now and not before)

    @property
    def estop_ok(self) -> bool:
        at, shift = self._estop_place
        return bool(self._data[at] >> shift & 1)

    def axis_enable_input(self, number: int) -> bool:
        at, shift = self._enable_places[number]
        return bool(self._data[at] >> shift & 1)

    def _wanted(self) -> str:
        data = self._data
        (pa, ps), (aa, as_) = self._mode_places
        p, a = data[pa] >> ps & 1, data[aa] >> as_ & 1
        if p and a:
            return "invalid"
        return "parameter" if p else "automatic" if a else "manual"

    # -- the cycle ----------------------------------------------------------------------------

    def evaluate(self) -> None:
        data, e = self._data, self._edge_bytes
        (pa, ps), (aa, as_) = self._mode_places  # the mode wanted (as `_wanted`, without the call)
        p, a = data[pa] >> ps & 1, data[aa] >> as_ & 1
        wanted = "invalid" if p and a else "parameter" if p else "automatic" if a else "manual"
        system, restart_x3, restart_dp = data[e.system], data[e.restart_x3], data[e.restart_dp]
        was_system, was_x3, was_dp = self._edge_before
        self._edge_before = (system, restart_x3, restart_dp)
        rising = system & ~was_system
        clear = bool(rising & e.clear)
        start = bool(rising & e.start)
        restart = bool(restart_x3 & ~was_x3 & e.restart or restart_dp & ~was_dp & e.restart_fieldbus)  # restart.py decision 13
        if self.mode == "power-on":
            self._power_on()
        if wanted == "invalid":
            self.fault(ClmError("08", "Parameter and Automatic are selected together"))
            wanted = self.mode if self.mode != "power-on" else "manual"
        if wanted == "automatic" and self.manual_vector:  # suppressed until the vector ends (§7.4)
            wanted = "manual"
        if wanted != self.mode:
            self._change(wanted)
        at, shift = self._estop_place
        if not data[at] >> shift & 1:  # (estop_ok)
            self.fault(ClmError("03", "E-Stop input (I0.00.2) is open"))
            for n in list(self.interface_off):  # "activated ... after an E-Stop" (§9.2 MxON)
                self.interface_enable(n, True)
        if clear and self.fault_error is not None:
            self.clear()
        if self.mode == "automatic" and self.fault_error is None:
            self._automatic(start, restart)
        elif self.mode == "manual":
            self._manual()

    def _power_on(self) -> None:
        self.mode = "manual"
        self._leave_parameter_mode()
        if self.fault_error is None:
            self.rt.restart.power_on()

    def _change(self, wanted: str) -> None:
        old, self.mode = self.mode, wanted
        rt = self.rt
        if old == "automatic" or wanted == "parameter":  # first: the program's state as it is
            rt.restart.interrupted("parameter" if wanted == "parameter" else "manual")
        if old == "automatic":
            self._stop_program()
            rt.memory.leave_automatic()
            if rt.cutoff is not None:
                rt.cutoff.leave_automatic()
        if wanted == "parameter":
            for task in rt.tasks:
                task.halt()
            self.manual_vector = False  # the Logic Task stays compiled but does not run (logic_may_run)
            rt.memory.enter_parameter_mode()
            return
        if old == "parameter":
            self._leave_parameter_mode()
        for axis in rt.axes.values():
            axis.reset_defaults()
        rt.registration.reset()  # REP limits, SRP, RMI end with the mode (L2354)
        rt.message = ""
        self.restart_from_zero = True
        if wanted == "automatic":
            for n in sorted(self.enabled_axes):
                if not self.axis_enable_input(n):
                    self.fault(ClmError(axis_fault(0x00, n), f"Automatic selected without Enable Axis {n}"))
                    return
            if rt.cutoff is not None and self.fault_error is None:
                self._start_cutoff()
        elif wanted == "manual" and self._b014[1] == 1:
            self._start_manual_vector()

    def _start_cutoff(self) -> None:
        """Flying cutoff: Automatic starts the program without Start (cutoff.py decision 7)."""
        rt = self.rt
        try:
            rt.cutoff.enter_automatic()  # Task 1; 36 away from home
        except ClmError as e:
            self.fault(e)
            return
        params = rt.memory.parameters
        starts = {2: params.get("B011")["task_2_start"], 4: params.get("B012")["task_4_start"], 5: params.get("B012")["task_5_start"]}
        for n, at in starts.items():
            if _int(at):
                rt.tasks[n - 1].start(_int(at))
        rt.restart.started()
        self.restart_from_zero = False
        self._stopped_tasks = set()
        self.running = True

    def _leave_parameter_mode(self) -> None:
        rt = self.rt
        params = rt.memory.parameters
        rt.memory.leave_parameter_mode()
        rt.master_factor = 1_000_000  # FAK 5 back to 1.000000 (L1935-1937)
        self._parameter_axes = frozenset(n for n in params.enabled_axes() if n in rt.axes)
        self._set_enabled_axes(self._parameter_axes - self.interface_off)
        self._take_parameters()
        for axis in rt.axes.values():
            axis.configure(params)
        self._make_cutoff()
        errors = params.errors()
        if errors:
            self.fault(errors[0] if errors[0].code in ("02", "17") else ClmError("02", errors[0].detail, errors[0].where))
            return
        try:
            rt.compile_logic()
        except ClmError as e:
            rt.memory.logic_fault()
            self.fault(e)
        task3 = _int(params.get("B011")["task_3_start"])
        if task3:
            rt.tasks[2].start(task3)

    def _make_cutoff(self) -> None:
        """Axis 1 in Ax00 mode 5: the flying cutoff (cutoff.py); its counters and the length
        instruction to start from survive Parameter mode."""
        rt = self.rt
        old = rt.cutoff
        rt.cutoff = None
        if 1 in rt.axes and rt.memory.parameters.axis_mode(1) == 5:
            from .cutoff import FlyingCutoff

            rt.cutoff = FlyingCutoff(rt)
            if old is not None:
                rt.cutoff.carry(old)

    def _take_parameters(self) -> None:
        params = self.rt.memory.parameters
        self._feed_inputs = []
        for n in sorted(self.enabled_axes):
            value = params.get(f"A{n}15")
            ops = tuple(op for op in (_operand(value["interrupt_input"]), _operand(value["feed_angle_input"])) if not op.unset)
            if ops:
                self._feed_inputs.append((n, ops))
        b014 = params.get("B014")
        op = _operand(b014["start_input"])
        self._b014 = (None if op.unset else op, _int(b014["start_on_mode_change"]), _int(b014["start_instruction"]))
        b015 = params.get("B015")
        op = _operand(b015["interrupt_input"])
        self._b015 = (None if op.unset else op, _int(b015["vector_mode"]), _int(b015["interrupt_positioning"]), _int(b015["interrupt_address"]))
        b018 = params.get("B018")
        self._b018 = (_int(b018["fault_code_output"]), tuple(_int(b018[f"clear_q1_{byte:02d}"]) for byte in range(7)))

    def _set_enabled_axes(self, axes: frozenset[int]) -> None:
        self.enabled_axes = axes
        self._enabled_in_order = tuple(sorted(axes))

    def task_may_run(self, task: NcTask) -> bool:
        if not task.running or self.mode == "parameter":
            return False
        if task.number == 3:
            return True
        if task.number == 1 and self.manual_vector:
            return self.mode == "manual"
        return self.mode == "automatic" and self.running and self.fault_error is None

    def logic_may_run(self) -> bool:
        return self.mode != "parameter" and not (self.fault_error is not None and self.fault_error.code == "38")

    def interface_enable(self, number: int, on: bool) -> None:
        """``!MxON`` / ``!MxOFF``: kept through faults and mode changes, undone by power-on and
        E-Stop; a command for a switched-off axis is fault 4E (spec §8.6)."""
        (self.interface_off.discard if on else self.interface_off.add)(number)
        self._set_enabled_axes(self._parameter_axes - self.interface_off)
        axis = self.rt.axes.get(number)
        if axis is not None:
            axis.interface_enable(on)

    def feed_allowed(self, number: int) -> bool:
        return number not in self._feed_interrupted

    # -- Automatic -------------------------------------------------------------------------------

    def _automatic(self, start: bool, restart: bool = False) -> None:
        data, places = self._data, self._enable_places
        for n in self._enabled_in_order:  # "at all times" for the activated axes (§9.1)
            at, shift = places[n]
            if not data[at] >> shift & 1:
                self.fault(ClmError(axis_fault(0x00, n), f"Enable Axis {n} lost in Automatic"))
                return
        if self.rt.cutoff is not None:  # Start and Immediate Stop have no function (L3929-3931)
            if self._feed_inputs:
                self._interrupt_inputs()
            return
        at, shift = self._stop_place
        run_allowed = bool(data[at] >> shift & 1)
        if self.running and not run_allowed:
            self.immediate_stop()
        elif start and run_allowed and not self.interface_stopped:
            self.start()
        elif restart and run_allowed:
            self.rt.restart.edge()  # a restart, or a Start when none is possible (L3831)
        if self._feed_inputs:  # (nothing to do when no Ax15 input is programmed)
            self._interrupt_inputs()
        if self._b015[0] is not None:  # (nor without a B015 input)
            self._interrupt_vector()

    def start(self, interface: bool = False) -> None:
        """Start input (rising edge) or ``!START``: from 0000 after a mode change or a fault,
        else where the tasks stopped (the axes first run their remaining distance)."""
        rt = self.rt
        if self.mode != "automatic" or self.fault_error is not None or (self.interface_stopped and not interface):
            return
        if rt.cutoff is not None:  # flying cutoff: no Start, not even over the interface (L3949)
            return
        if not self._bit(IMMEDIATE_STOP):
            return
        self.interface_stopped = False
        params = rt.memory.parameters
        if self.restart_from_zero:
            rt.restart.started()  # a new run: a waiting restart image is given up
            rt.tasks[0].start(0)
            starts = {2: params.get("B011")["task_2_start"], 4: params.get("B012")["task_4_start"], 5: params.get("B012")["task_5_start"]}
            for n, at in starts.items():
                if _int(at):
                    rt.tasks[n - 1].start(_int(at))
            self.restart_from_zero = False
        else:
            for task in rt.tasks:
                if task.number in self._stopped_tasks:
                    task.running = True
            for axis in rt.axes.values():
                axis.resume()
        self._stopped_tasks = set()
        self.running = True

    def begin_restart(self) -> None:
        """The Re-Start edge restores (or runs the restart program): Run Task is set, the
        program goes on instead of beginning at 0000."""
        self.interface_stopped = False
        self.restart_from_zero = False
        self._stopped_tasks = set()
        self.running = True

    def immediate_stop(self, programmed: bool = False, interface: bool = False) -> None:
        """Immediate Stop input, JST or ``!STOP``: tasks 1, 2, 4, 5 stop where they are (a waiting
        command keeps its state), the axes decelerate keeping the remaining distance."""
        rt = self.rt
        if rt.cutoff is not None and not programmed:  # flying cutoff: no Immediate Stop (L3929, L3949)
            return
        self._stopped_tasks |= {t.number for t in rt.tasks if t.number != 3 and t.running}
        for task in rt.tasks:
            if task.number != 3:
                task.running = False
        for axis in rt.axes.values():
            axis.immediate_stop()
        self.running = False
        self.interface_stopped = self.interface_stopped or interface

    def _stop_program(self) -> None:
        for task in self.rt.tasks:
            if task.number != 3:
                task.halt()
        for axis in self.rt.axes.values():
            axis.stop_motion()
        self.running = False
        self.interface_stopped = False
        self.manual_vector = False

    def _interrupt_inputs(self) -> None:
        """Ax15 Interrupt / Feed Angle Monitoring: lost -> the axis' positioning stops and none
        starts; back -> it goes on without Start (§5.5)."""
        for n, ops in self._feed_inputs:
            lost = not all(self._bit(op) for op in ops)
            if lost and n not in self._feed_interrupted:
                self._feed_interrupted.add(n)
                self.rt.axes[n].immediate_stop()
            elif not lost and n in self._feed_interrupted:
                self._feed_interrupted.discard(n)
                self.rt.axes[n].resume()

    def _interrupt_vector(self) -> None:
        """B015: an edge on its input sends Task 1 to the interrupt program, no return (§7.4)."""
        op, mode, positioning, address = self._b015
        if op is None:
            return
        if self._edge(op, falling=mode in (2, 3)) and self.running:
            self._pending_interrupt = True
        task = self.rt.tasks[0]
        if self._pending_interrupt and (mode in (1, 3) or not task.stack):
            self._pending_interrupt = False
            if positioning:
                for axis in self.rt.axes.values():
                    axis.stop_motion()
            task.stack.clear()
            task.pc, task.wait = address, None

    # -- Manual ---------------------------------------------------------------------------------

    def _manual(self) -> None:
        run_allowed = bool(self._bit(IMMEDIATE_STOP))
        for n in self.enabled_axes:
            plus, minus = (self._bit(op) for op in JOG[n])
            direction = (plus - minus) if run_allowed and self.feed_allowed(n) and not self.manual_vector else 0
            self.rt.axes[n].jog(direction)
        self._interrupt_inputs()
        op = self._b014[0]
        if op is not None and self._rising(op) and not self.manual_vector:
            self._start_manual_vector()

    def _start_manual_vector(self) -> None:
        self.rt.tasks[0].start(self._b014[2])
        self.manual_vector = True

    def end_manual_vector(self) -> None:
        self.rt.tasks[0].halt()
        self.manual_vector = False
        self.restart_from_zero = True

    # -- faults -----------------------------------------------------------------------------------

    def fault(self, error: ClmError) -> None:
        if self.fault_error is not None:
            return  # decision 2: the first fault stays
        rt = self.rt
        rt.restart.interrupted("fault", error)  # first: the image of the running program
        self.fault_error = error
        for task in rt.tasks:
            if task.number != 3:
                task.halt()
        self.running = False
        self.manual_vector = False
        self.restart_from_zero = True
        if rt.cutoff is not None:
            rt.cutoff.leave_automatic()
        for axis in rt.axes.values():
            axis.fault_stop()
        rt.registration.reset()  # REP limits are cleared by a fault (L2354)
        rt.memory.fault()
        self._clear_outputs_b018(on_fault=True)

    def clear(self) -> None:
        """External Clear, the CL key, ``!CLEAR``: only when the cause is gone (E-Stop closed,
        the mode inputs valid); the program then starts from 0000 (§11.1)."""
        if self.fault_error is None:
            return
        if self.fault_error.code == "03" and not self.estop_ok:
            return
        if self.fault_error.code == "08" and self._wanted() == "invalid":
            return
        self._clear_outputs_b018(on_fault=False)
        self.fault_error = None
        self.rt.master_factor = 1_000_000  # FAK 5 back to 1.000000 after an error is cleared (L1935-1937)
        self.restart_from_zero = True
        for axis in self.rt.axes.values():  # the drives may be enabled again
            axis.clear_fault()
        if self.mode == "parameter":
            return
        if self.rt.logic is None and self.rt.memory.logic:
            try:
                self.rt.compile_logic()
            except ClmError as e:
                self.fault(e)

    def _clear_outputs_b018(self, on_fault: bool) -> None:
        """B018 per output byte Q1.00-Q1.06: 0 cleared on the fault, 1 cleared when it is
        cleared, 2 never (spec §5.3)."""
        for byte, digit in enumerate(self._b018[1]):
            if (digit == 0 and on_fault) or (digit == 1 and not on_fault):
                self.rt.write_byte(Operand("Q", 1, byte), 0)

    # -- outputs ----------------------------------------------------------------------------------

    def outputs(self) -> None:
        data = self._data
        fault = self.fault_error
        q = self._q
        b0 = data[q.at0] & q.keep0 | q.mode_bits.get(self.mode, 0)  # Manual, Automatic, Parameter
        if fault is None:
            b0 |= q.ok  # Error message, active low
        b1 = data[q.at1] & q.keep1
        if self.running:
            b1 |= q.run
        if self.rt.restart.image is not None:  # (restart.possible)
            b1 |= q.restart
        data[q.at0], data[q.at1] = b0, b1
        selector = self._b018[0]
        if 1 <= selector <= 6 and fault is not None:
            code = fault.code
            self.rt.image.set(Operand("Q", 1, selector - 1), int(code, 16) if len(code) == 2 else 0)
        data[q.word0] = b0  # Q0.00 / Q0.01 -> the status word Q2.00 / Q2.01
        data[q.word1] = b1 & q.word1_keep  # Restart possible has no status-word bit
