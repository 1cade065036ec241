"""The CLM running: one NC cycle of the mode machine, the Logic Task and the five NC tasks.

    rt = ClmRuntime(memory, axes, nc_cycle_s=0.002)
    rt.step()            # once per NC cycle, after the caller sampled the inputs into rt.image

The runtime works on the CLM's process image only; the personality (`personality`) copies the
wired inputs into it before `step` and the outputs out of it at the next cycle's start ("Hardware
outputs are set at the beginning of the following cycle", L1437), so the runtime can be tested
without a plant.

Per NC cycle (spec §1.4, §2, §3.9): the system variables are brought up to date; the mode inputs,
E-Stop, Start, Immediate Stop and External Clear are evaluated; the Logic Task's scan advances;
tasks 1..5 run one instruction each (Task 3 in Manual and Automatic, tasks 1, 2, 4, 5 in
Automatic after Start; the manual vector in Manual in the Task 1 slot); the axes are monitored;
the restart image of a running program is kept current (`restart`).
The rules of each mode change, stop and fault (what stops, what is cleared, where a task goes
on) are in `modes`.

Decisions (spec line -> choice, why)
------------------------------------
1. C-LT-SCAN, errata §1.3 (about 1000 assignments a second, at least 4 ms; I/O sampled at the
   scan start): a scan spans ceil(max(4, N) ms / T) NC cycles; it reads the image as it was at
   its first cycle and its writes appear at its last cycle, so the NC tasks see an LT output
   change one scan after the input that caused it. Test:
   ``tests/devices/clm/test_runtime.py::test_logic_task_scan_takes_its_time``.
2. C-SYSVAR, §5.6 Fig. 5-1/5-2: V000 counts every NC cycle, V001 the cycles while the program
   runs in Automatic, V002-V006 hold the tasks' instruction numbers, Vx00/Vx03/Vx04/Vx10 the
   axes' actual position, lag, actual velocity and remaining distance; each is the live value
   when it is read (the axes' values are those sampled at the cycle's start); V007-V010 are the
   analog inputs (analog.py), V011 master encoder 1 (master_encoder.py), V015-V018 the IDS01
   decade switch (decade_switch.py, stored when a telegram arrives). Test:
   ``test_system_variables``.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

from .errors import ClmError, axis_fault
from .execute import HANDLERS
from .fields import Axis, Choice, Number, Var, fit_variable
from .logic import LogicError, LogicProgram, compile_logic
from .memory import ClmMemory
from .modes import ModeMachine
from .nc import NcTask
from .override import VelocityFunctions
from .operands import Operand, exists
from .program import Instruction
from .registration import Registration
from .restart import Restart

__all__ = ["ClmRuntime"]

_SCALE = 1_000_000


class ClmRuntime:
    def __init__(self, memory: ClmMemory, axes: dict[int, Any], nc_cycle_s: float) -> None:
        self.memory = memory
        self.image = memory.image  # one image for the life of the CLM (written in place)
        self.axes = axes  # CLM axis number -> ClmAxis (the axes the machine file gives the CLM)
        self.nc_cycle_s = nc_cycle_s
        self.cycle = 0
        self.tasks = [NcTask(n) for n in range(1, 6)]
        self.master_factor = _SCALE  # FAK 5: master encoder 1's feed constant factor
        self.master_encoder: Any = None  # master_encoder.MasterEncoder1 when wired on the plant
        self.cutoff: Any = None  # cutoff.FlyingCutoff while axis 1 is in Ax00 mode 5 (set by modes)
        self.material_outputs: Any = None  # material_length.MaterialOutputs once an MLO ran
        self.analog: Any = None  # analog.ClmAnalogInputs, set by the personality (V007-V010, Status 45/49)
        self.message = ""  # Status 53 text (TXT mode 1)
        self.text_lines = [""] * 4  # Status 63 (TXT mode 0)
        self._txt_run: tuple[int, int] = (-1, 0)  # (cycle, next line) of the TXT run in progress
        self.logic: LogicProgram | None = None
        self._lt_owned: set[tuple[str, int, int, int | None]] = set()
        self._lt_scan: tuple[int, Any] | None = None  # (cycle its writes appear, image snapshot)
        self.on_move: Callable[[Any, NcTask], None] | None = None  # the report's hook
        self.modes = ModeMachine(self)
        self._run_cycles = 0  # V001
        self.calculator_cycle = -1  # the cycle the shared calculating unit last worked (MAT)
        self._time_origin = 0  # V019 counts the hours since this cycle (!CCLVAR0019 sets it)
        memory.variables.system = self.system_value
        self.velocity = VelocityFunctions(self)  # B017/VEO override, VCC, AEO (override.py)
        self.registration = Registration(self)  # SRM/REP/SRP/RMI, raster latch (registration.py)
        self.restart = Restart(self)  # the restart image, B016, RSV, Re-Start (restart.py)

    # -- the cycle -------------------------------------------------------------------------


    def step(self) -> None:
        """One NC cycle (the inputs already sampled into the image)."""
        if self.modes.running:
            self._run_cycles += 1
        try:
            self.modes.evaluate()
            self.velocity.tick()
            self._logic_task()
            if self.cutoff is not None:  # length counters, the end of the return (cutoff.py)
                self.cutoff.tick(self.modes.mode)
            if self.material_outputs is not None:  # MLO (material_length.py)
                self.material_outputs.tick(self.modes.mode)
            registration = self.registration
            if registration.armed:  # a mark is awaited: latch it before the tasks look
                registration.tick()
            suspended = registration.suspended_task  # RMI: Task 1 waits for RMI 1 1
            modes = self.modes
            for task in self.tasks:  # (a task that is not running is not asked about)
                if task.running and task.number != suspended and modes.task_may_run(task):
                    task.step(self, HANDLERS)
            self.restart.after_tasks()  # an RSV that ends the restart program restores now
            data, enable, (ea, es) = self.image.data, modes.enable_places, modes.estop_place
            for axis in self.axes.values():  # (modes.axis_enable_input and .estop_ok, read in place)
                at, shift = enable[axis.number]
                err = axis.tick(modes.mode, bool(data[at] >> shift & 1), bool(data[ea] >> es & 1))
                if err is not None:
                    raise err
        except ClmError as e:
            self.modes.fault(e)
        self.modes.outputs()
        self.restart.tick()  # the battery-buffered image of the running program (restart decision 10)
        self.cycle += 1

    def clear_time_counter(self) -> None:
        """``!CCLVAR0019``: the running-time counter V019 starts again at 0 (§7.13)."""
        self._time_origin = self.cycle

    def cycles_for_ms(self, ms: int) -> int:
        return math.ceil(ms / (self.nc_cycle_s * 1000) - 1e-9)

    # -- Logic Task ---------------------------------------------------------------------------

    def compile_logic(self) -> None:
        """On leaving Parameter mode and at power on (L3177): fault 38 when it does not compile."""
        self.logic, self._lt_scan, self._lt_owned = None, None, set()
        if not self.memory.logic:  # an empty Logic Task memory is END at 0000, the state !sCNOPLT leaves
            return
        try:
            program = compile_logic(self.memory.logic)
        except LogicError as e:
            first = e.errors[0] if getattr(e, "errors", None) else e
            raise ClmError("38", first.detail, first.where) from None
        self.logic = program
        self._lt_owned = {(op.area, op.source, op.byte, op.bit) for op in program.writes}

    def _logic_task(self) -> None:
        program = self.logic
        if program is None or not program.active or not self.modes.logic_may_run():
            self._lt_scan = None
            return
        if self._lt_scan is None:  # a scan begins: it samples the image now (errata §1.3)
            span = max(1, math.ceil(program.scan_time_ms / (self.nc_cycle_s * 1000) - 1e-9))
            self._lt_scan = (self.cycle + span - 1, self.image.copy())
        end, snapshot = self._lt_scan
        if self.cycle < end:
            return
        program.scan(snapshot)
        for op in program.writes:
            self.image.set(op, snapshot.get(op))
        self._lt_scan = None

    def lt_owns(self, op: Operand) -> bool:
        return (op.area, op.source, op.byte, op.bit) in self._lt_owned or (op.area, op.source, op.byte, None) in self._lt_owned

    # -- image access for the NC commands -----------------------------------------------------

    def read_bit(self, op: Operand) -> int:
        return self.image.get(op)

    def read_byte(self, op: Operand) -> int:
        return self.image.get(op)

    def write_bit(self, op: Operand, value: int) -> None:
        if not self.lt_owns(op):  # decision C-LT-OWNED (execute)
            self.image.set(op, 1 if value else 0)

    def write_byte(self, op: Operand, value: int) -> None:
        if self.lt_owns(op):
            return
        if not self._lt_owned:
            self.image.set(op, value & self.image.locate(op)[2])
            return
        for bit in range(8):  # bit-wise: an LT-owned bit in the byte stays the Logic Task's
            target = Operand(op.area, op.source, op.byte, bit)
            if exists(target) and not self.lt_owns(target):
                self.image.set(target, (value >> bit) & 1)

    # -- field values -------------------------------------------------------------------------

    def variable(self, ref: Var) -> int:
        raw = self.memory.variables[ref.number]
        return -raw if ref.sign < 0 else raw

    def number(self, ins: Instruction, index: int) -> int:
        """A numeric field's value: the constant, or the variable fitted to the field (32)."""
        value = ins.values[index]
        if isinstance(value, Var):
            f = ins.command.fields[index]
            assert isinstance(f, Number)
            return fit_variable(f, value, self.memory.variables[value.number])
        return int(value)  # type: ignore[call-overload]

    def target(self, ins: Instruction, index: int) -> int:
        n = self.number(ins, index)
        if not 0 <= n <= 2999:
            raise ClmError("0E", f"{ins.command.fields[index].name} = {n}: instructions are 0000-2999")
        return n

    def state_value(self, ins: Instruction, index: int) -> int:
        """A 0/1 state field; from a variable it must be 0 or 1 (32)."""
        value = ins.values[index]
        if isinstance(value, Var):
            raw = self.memory.variables[value.number]
            if raw not in (0, _SCALE):
                raise ClmError("32", f"{value} = {raw / _SCALE:.6f}: the state is 0 or 1")
            return raw // _SCALE
        assert isinstance(ins.command.fields[index], Choice)
        return int(str(value))

    def axis(self, ins: Instruction, index: int) -> Any:
        value = ins.values[index]
        if isinstance(value, Var):
            raw = self.memory.variables[value.number]
            field = ins.command.fields[index]
            assert isinstance(field, Axis)
            if raw % _SCALE or raw // _SCALE not in field.axes:
                raise ClmError("16", f"{value} = {raw / _SCALE:.6f}: the axis is {field.describe()}")
            value = raw // _SCALE
        number = int(value)  # type: ignore[call-overload]
        if number == 1 and self.cutoff is not None and ins.command.fc_forbidden:
            raise ClmError("0A", f"{ins.mnemonic} may not be programmed for axis 1 in flying cutoff (L3944-3947)")
        axis = self.axes.get(number)
        if axis is None or number not in self.modes.enabled_axes:
            raise ClmError(axis_fault(0x0E, number), f"{ins.mnemonic} for axis {number}, which is not enabled")
        return axis

    def feed_allowed(self, axis: Any) -> bool:
        """No Interrupt (Ax15) and no open feed roll (Ax30, feedroll.py decision 2)."""
        return self.modes.feed_allowed(axis.number) and not getattr(axis, "feed_roll_open", False)

    def moved(self, axis: Any, task: NcTask) -> None:
        if self.on_move is not None:
            self.on_move(axis, task)

    def set_position_variable(self, number: int, raw: int) -> None:
        """SET V047/V048/Vx00 while not homed: the actual position becomes the value (L2590)."""
        axis_number = number // 100 if number >= 100 else number - 46
        axis = self.axes.get(axis_number)
        if axis is None or axis.homed:
            raise ClmError("31", f"V{number:03d} can be set only while axis {axis_number} is not homed (L2590)")
        if number in (47, 48) and hasattr(axis, "set_motor_actual"):  # the motor encoder (measuring_wheel.py 8)
            axis.set_motor_actual(raw / _SCALE)
        else:
            axis.set_actual(raw / _SCALE)

    # -- program flow -------------------------------------------------------------------------

    def programmed_stop(self, task: NcTask, target: int) -> None:
        self.modes.immediate_stop(programmed=True)

    def manual_vector_running(self, task: NcTask) -> bool:
        return task.number == 1 and self.modes.manual_vector

    def end_manual_vector(self) -> None:
        self.modes.end_manual_vector()

    def show_text(self, mode: str, text: str, task: NcTask) -> None:
        if mode == "1":
            self.message = text
            return
        cycle, line = self._txt_run
        line = line if cycle == self.cycle else 0  # a run of TXT in one cycle fills lines 1..4
        self.text_lines[line % 4] = text
        self._txt_run = (self.cycle, line + 1)

    # -- system variables ---------------------------------------------------------------------

    def system_value(self, number: int) -> int | None:
        """A live system variable (decision C-SYSVAR), None for one the CLM keeps stored."""
        if number == 0:
            return self.cycle * _SCALE
        if number == 1:
            return self._run_cycles * _SCALE
        if 2 <= number <= 6:
            return self.tasks[number - 2].pc * _SCALE
        if number == 19:
            return int((self.cycle - self._time_origin) * self.nc_cycle_s / 3600) * _SCALE
        if 7 <= number <= 10:  # V007-V010: the analog inputs standardized to +-1 (analog.py decision 1)
            return None if self.analog is None else self.analog.standardized(number - 6)
        if number == 11:  # V011: master encoder 1's velocity, IU/s (master_encoder.py decision 4)
            me = self.master_encoder
            return None if me is None else round(me.velocity * _SCALE)
        axis = self.axes.get(number // 100) if number >= 100 else None
        if axis is None:
            return None
        value = {0: getattr(axis, "position", axis.actual_position), 3: axis.lag, 4: axis.actual_velocity, 10: axis.remaining_distance}.get(number % 100)
        return None if value is None else round(value * _SCALE)
