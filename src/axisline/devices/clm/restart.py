"""Restart (manual §7.11, L3819-3857): continue tasks 1, 2, 4, 5 where a power loss, an error or
a switch from Automatic to Manual interrupted them; B016's restart program and RSV (L2435-2466);
the Re-Start input and the Restart-possible output (§9.1, L5920-5927, L6066-6074).

    rt.restart = Restart(rt)       # the runtime owns one
    rt.restart.possible            # an image waits (output Q0.01.0)
    rt.restart.edge()              # a rising edge at Re-Start in Automatic (modes calls it)

The *restart image* is the state of the interrupted program: per task 1, 2, 4, 5 whether it
ran, its instruction, its subroutine stack and whether it waited for a positioning (PSA/PSI);
per axis the absolute target (exact IU), the feedrate (IU/s), the program's ACC and FAK and the
actual position; the outputs Q1.00-Q1.06 and Q2.02-Q2.05; the NC markers M2; FAK 5. While a
program runs in Automatic the image is kept up to date in the battery-buffered memory
(`memory.ClmMemory.restart`, written by `memory.RetainedStore` with the rest); at a mode change
or a fault it is taken at that moment. Restoring it (B016 = 0000 at the Re-Start edge, or the
RSV that ends the restart program) writes the outputs and markers back, sends every axis to its
target at its feedrate and lets the tasks go on at their instructions.

Decisions (spec line -> choice, why)
------------------------------------
1. L3827 "feedrate, absolute target position, status of the outputs, etc." -> "etc." is what a
   program needs to go on as if never interrupted: the tasks' instructions, stacks, running
   flags and positioning waits; per axis the program's ACC and FAK (a mode change resets them,
   L1413, L1933) and FAK 5; the outputs Q1 and Q2.02-05 (the NC's writable outputs; bits the
   Logic Task owns stay the Logic Task's); the markers M2 (cleared by a mode change, a fault
   and a power loss, L6191). Not in it: variables, counters, M3 and M6.00-19 (battery-
   buffered anyway), CON's velocity run (it has no target: the program's next CON starts it
   again), VEO / VCC / AEO, SRP and REP (a mode change ends them, the program sets them again),
   a homing in progress (it has no target; a restart program can HOM again), the text lines.
   A command that waited is executed again from its start (WAI waits its full time again, AKN
   looks again) except PSA / PSI, which wait for the restored positioning instead of adding
   their distance a second time. Tests:
   ``tests/devices/clm/test_restart.py::test_feed_interrupted_by_manual_reaches_the_same_target``,
   ``test_image_holds_stack_outputs_markers_acc_fak``, ``test_wai_waits_its_full_time_again``;
   on the plant ``tests/devices/clm/test_restart_power.py::test_plant_estop_then_restart``.
2. L3837 (a) "Power loss, error or E-Stop ... during a program stop or in Manual Mode" and
   L3825 "a program was running in Automatic Mode" -> an image is taken only when Run Task is
   set (Automatic, started, no Immediate Stop / JST / !STOP); a power loss, error or E-Stop
   while it is not set discards an image that waits; a switch to Manual during a program stop
   takes none (the next Re-Start is a Start) but keeps one that waits. Tests:
   ``test_error_during_a_program_stop_is_no_restart``, ``test_estop_in_manual_discards_the_image``.
3. L3838 (b) -> a fault Drive Runaway or Excess Pos Lag (Ax02/Ax03 codes) on an axis whose
   Ax20 encoder type is 0 (incremental) takes no image (its reference is gone); with an
   absolute encoder it does. Test: ``test_lag_with_an_incremental_encoder_is_no_restart``.
4. L3839 (c) -> with Ax00 mode 5 on axis 1 no image is ever taken (L1281: "The 'Restart'
   function must be deactivated"). Test: ``test_flying_cutoff_is_no_restart``.
5. L3841-3844 vs L6070-6074 -> Q0.01.0 is set from the moment an image is taken (also while the
   fault is still shown and in Manual: "can also be set in Manual Mode") until it is restored
   or discarded; it is 0 while a program runs normally. Q2.01.0 stays 0 (the status word has
   no Restart bit, "Fieldbus: -----", L6068). Test: ``test_restart_possible_output``.
6. L3831 "If no Restart is possible ... the same functionality as ... 'Start'" -> a Re-Start
   edge without an image is a Start (also the continuation after Immediate Stop); with one it
   restores; while Run Task is set it does nothing, as Start. A Start (from 0000) discards an
   image: the operator chose to begin again. Tests: ``test_restart_without_an_image_is_start``,
   ``test_start_discards_the_image``.
7. L3848-3856, L5210-5212 (B016) -> B016 = 0000: the edge restores at once and the tasks go on
   in the same cycle. B016 = nnnn: Task 1 runs the restart program from nnnn (stack empty),
   tasks 2, 4, 5 wait; Run Task is set; the axes stay where they are until the program ends. A
   mode change, fault or power loss during the restart program keeps the image (the restart has
   not taken place). Tests: ``test_b016_restart_program_rsv_examples``,
   ``test_interrupted_restart_program_keeps_the_image``.
8. RSV t nnnn fffff (L2435-2466, spec "flags 2-5 not described") -> flag 1 = 1 restores the
   outputs now (program 3: "RSV 0 0000 10000 - Restore status of outputs"); t = 0 goes on with
   the next instruction after one cycle; t = 1 ends the restart program: the rest of the image
   is restored (the outputs only when flag 1 is 1: program 3's "RSV 1 0000 00000 ... except for
   outputs") and one cycle later the interrupted tasks go on ("following the time period of one
   cycle", L2466). nnnn = 0000: Task 1 goes on at its interrupted instruction; nnnn > 0: at
   nnnn, its stack cleared (as the interrupt vector B015), the axes still restored. Flags 2-5
   have no function (every example has them 0 and calls that "completely restore"). An RSV
   outside a restart program has no function. Tests: ``test_b016_restart_program_rsv_examples``,
   ``test_rsv_nnnn_continues_task_1_there``, ``test_rsv_outside_a_restart_program``.
9. L2386 "The RMI command is not executed when a restart occurs" -> a raster interruption in
   progress (Task 1 suspended by RMI) is not part of the image: Task 1's main feed is restored
   with the target and feedrate RMI kept, Task 1 is not suspended, and Task 2 goes back to the
   RMI 1 0 that began the raster cycle (with its stack then), waiting for the next raster; the
   offset feed and the tool program of the interrupted raster are not done. Test:
   ``test_rmi_raster_processing_is_not_restarted``.
10. Power loss (L3821; spec §1.3 battery-buffered memory) -> the image is written to the memory
    file at the end of each NC cycle in which, while the program runs, a task of 1, 2, 4, 5
    completed an instruction that changes state (every command but NOP, jumps, branches, JSR,
    RTS, CST, AKN, AKP, WAI, TXT) or an axis target changed, and when the program starts or
    stops: never per cycle as such, and a program waiting or looping over tests writes nothing.
    A power cut is "the last persisted state": a new runtime on the file finds the image of a
    running program and Restart is possible; the tasks go on at the instructions after the last
    state change (jumps, tests and waits after it run again, with the same effect), an axis
    goes to its saved target; an axis with an incremental encoder first gets the saved actual
    position back (the position counter is buffered; the axis is taken not to have moved while
    off). Tests: ``tests/devices/clm/test_restart_power.py::test_power_loss_restart_from_the_memory_file``,
    ``test_image_is_not_written_while_the_program_only_tests``,
    ``test_plant_power_loss_then_restart_from_the_memory_file``.
11. The program, parameters or Logic Task changed (serial writes, Parameter mode) while an image
    waits -> the image is discarded: its instruction numbers would point into another program.
    Test: ``test_program_change_discards_the_image``.
12. SAC (L2510 clearing an error restores the initial coordinate system; axis.py decision 23)
    -> targets and
    actual positions are kept in the initial frame (less the axis' ``frame_shift``, the SAC
    shift) and put back in the frame the axis has at the restart, so a fault clear between
    does not move the target. Test: ``test_sac_frame_change_keeps_the_target``.
13. Re-Start's fieldbus twin I2.01.6 (L7619, L7665) -> a rising edge of I0.01.6 or of I2.01.6
    (each edge-detected; the fieldbus image is 0 without a fieldbus). Test:
    ``test_fieldbus_restart_input``.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from fractions import Fraction
from typing import TYPE_CHECKING, Any

from .errors import ClmError, axis_fault
from .operands import Operand
from .program import PROGRAM_SIZE, Instruction

if TYPE_CHECKING:
    from .nc import NcTask
    from .runtime import ClmRuntime

__all__ = ["PURE", "Restart", "RestartImage", "op_rsv"]

RESTART_TASKS = (1, 2, 4, 5)
#: commands that change nothing an image holds but the instruction and stack (decision 10)
PURE = frozenset(("NOP", "JMP", "JSR", "RTS", "CST", "BCE", "BPA", "BIO", "BIC", "CPJ", "AKN", "AKP", "WAI", "TXT"))
_OUTPUT_BYTES = tuple(Operand("Q", 1, b) for b in range(7)) + tuple(Operand("Q", 2, b) for b in range(2, 6))
_M2_BYTES = tuple(Operand("M", 2, b) for b in range(20))
_STATES = ("running", "restarting", "interrupted")


@dataclass
class TaskImage:
    running: bool = False
    pc: int = 0
    stack: list[int] = field(default_factory=list)
    moving: bool = False  # waited in a PSA/PSI for its positioning


@dataclass
class AxisImage:
    target: Fraction | None = None
    speed: float = 0.0
    actual: float = 0.0
    acc: tuple[int, int] | None = None  # the program's ACC, None: Ax09
    fak: int | None = None  # the program's FAK (millionths), None: 1.000000


@dataclass
class RestartImage:
    tasks: dict[int, TaskImage]
    axes: dict[int, AxisImage]
    outputs: bytes
    markers: bytes
    master_factor: int = 1_000_000

    def to_json(self, state: str) -> dict[str, object]:
        return {
            "state": state,
            "tasks": {str(n): {"running": t.running, "pc": t.pc, "stack": list(t.stack), "moving": t.moving} for n, t in self.tasks.items()},
            "axes": {str(n): {"target": None if a.target is None else str(a.target), "speed": a.speed, "actual": a.actual,
                              "acc": None if a.acc is None else list(a.acc), "fak": a.fak} for n, a in self.axes.items()},
            "outputs": self.outputs.hex(),
            "markers": self.markers.hex(),
            "master_factor": self.master_factor,
        }

    @staticmethod
    def from_json(doc: object) -> tuple[str, RestartImage]:
        """(state, image) from the memory file; ValueError names the field that is wrong."""

        def need(ok: bool, what: str) -> None:
            if not ok:
                raise ValueError(f"restart.{what}")

        need(isinstance(doc, dict), ": a table")
        assert isinstance(doc, dict)
        state = doc.get("state")
        need(state in _STATES, f"state = {state!r}: one of {', '.join(_STATES)}")
        tasks: dict[int, TaskImage] = {}
        raw_tasks = doc.get("tasks", {})
        need(isinstance(raw_tasks, dict), "tasks: a table")
        for key, t in raw_tasks.items():
            need(key in ("1", "2", "4", "5") and isinstance(t, dict), f"tasks.{key}: tasks 1, 2, 4, 5 as tables")
            pc, stack = t.get("pc", 0), t.get("stack", [])
            need(isinstance(pc, int) and 0 <= pc < PROGRAM_SIZE, f"tasks.{key}.pc = {pc!r}: 0..{PROGRAM_SIZE - 1}")
            need(isinstance(stack, list) and all(isinstance(s, int) and 0 <= s < PROGRAM_SIZE for s in stack) and len(stack) <= 127,
                 f"tasks.{key}.stack: up to 127 instructions 0..{PROGRAM_SIZE - 1}")
            tasks[int(key)] = TaskImage(bool(t.get("running")), pc, list(stack), bool(t.get("moving")))
        axes: dict[int, AxisImage] = {}
        raw_axes = doc.get("axes", {})
        need(isinstance(raw_axes, dict), "axes: a table")
        for key, a in raw_axes.items():
            need(key in ("1", "2", "3", "4") and isinstance(a, dict), f"axes.{key}: axes 1-4 as tables")
            try:
                target = None if a.get("target") is None else Fraction(str(a["target"]))
                speed, actual = float(a.get("speed", 0.0)), float(a.get("actual", 0.0))
            except (ValueError, ZeroDivisionError, TypeError):
                raise ValueError(f"restart.axes.{key}: target (a fraction), speed and actual (numbers)") from None
            acc, fak = a.get("acc"), a.get("fak")
            need(acc is None or (isinstance(acc, list) and len(acc) == 2 and all(isinstance(x, int) and 0 <= x <= 999 for x in acc)),
                 f"axes.{key}.acc = {acc!r}: two per mille values 0..999")
            need(fak is None or (isinstance(fak, int) and 0 <= fak <= 9_999_999), f"axes.{key}.fak = {fak!r}: 0..9999999 millionths")
            axes[int(key)] = AxisImage(target, speed, actual, None if acc is None else (acc[0], acc[1]), fak)
        try:
            outputs, markers = bytes.fromhex(str(doc.get("outputs", ""))), bytes.fromhex(str(doc.get("markers", "")))
        except ValueError:
            raise ValueError("restart.outputs / restart.markers: hex bytes") from None
        need(len(outputs) == len(_OUTPUT_BYTES), f"outputs: {len(_OUTPUT_BYTES)} bytes (Q1.00-06, Q2.02-05)")
        need(len(markers) == len(_M2_BYTES), f"markers: {len(_M2_BYTES)} bytes (M2.00-19)")
        factor = doc.get("master_factor", 1_000_000)
        need(isinstance(factor, int) and factor >= 0, f"master_factor = {factor!r}: millionths, not negative")
        return str(state), RestartImage(tasks, axes, outputs, markers, factor)


class Restart:
    """The restart function of one CLM (see the module docstring)."""

    def __init__(self, rt: ClmRuntime) -> None:
        self.rt = rt
        self.image: RestartImage | None = None  # an image that waits: Restart possible
        self.program = False  # B016's restart program runs (the image still waits)
        self.generation = 0  # bumped by nc.NcTask.step when a task 1/2/4/5 changes state
        self.settings: dict[int, dict[str, Any]] = {}  # axis -> the program's "acc" / "fak"
        self.rmi: tuple[int, list[int]] | None = None  # Task 2's RMI 1 0: (instruction, stack)
        self._version = -1  # memory.version the waiting image belongs to
        self._key: object = None  # what the persisted image was taken from
        self._outputs_done = False  # an RSV restored the outputs already
        self._finish: int | None = None  # RSV t=1 this cycle: Task 1's instruction (-1: interrupted)
        self._restoring = False  # a fault while the image is put back keeps the image

    @property
    def possible(self) -> bool:
        return self.image is not None

    # -- taking the image ------------------------------------------------------------------

    def capture(self) -> RestartImage:
        rt = self.rt
        reg = rt.registration
        tasks = {}
        for n in RESTART_TASKS:
            t = rt.tasks[n - 1]
            tasks[n] = TaskImage(t.running, t.pc, list(t.stack), t.wait == "moving")
        if reg.rmi is not None and self.rmi is not None:  # decision 9: the raster cycle is not kept
            pc, stack = self.rmi
            tasks[2] = TaskImage(True, pc, list(stack), False)
        axes = {}
        for n, axis in rt.axes.items():
            s = self.settings.get(n, {})
            target, speed = getattr(axis, "exact_target", None), float(getattr(axis, "speed", 0.0))
            if n == 1 and reg.rmi is not None:  # the main feed RMI suspended
                target, speed = reg.rmi.target, reg.rmi.speed
            shift = _shift(axis)  # decision 12: in the initial frame
            axes[n] = AxisImage(None if target is None else target - shift, speed, float(axis.actual_position - shift),
                                s.get("acc"), s.get("fak"))
        image = rt.image
        return RestartImage(tasks, axes, bytes(image.get(op) for op in _OUTPUT_BYTES),
                            bytes(image.get(op) for op in _M2_BYTES), rt.master_factor)

    def _excluded(self, error: ClmError | None) -> bool:
        params = self.rt.memory.parameters
        if params.flying_cutoff():  # decision 4
            return True
        if error is not None:  # decision 3
            for n in self.rt.axes:
                if error.code in (axis_fault(0x02, n), axis_fault(0x03, n)) and params.encoder_type(n) == 0:
                    return True
        return False

    def interrupted(self, cause: str, error: ClmError | None = None) -> None:
        """Modes calls this first thing at a fault ('fault') or on leaving Automatic
        ('manual' / 'parameter'), before anything is stopped or cleared (decisions 2-4, 7)."""
        rt = self.rt
        self._finish = None
        if self._restoring:  # e.g. an axis refused its target: the image is still the program's
            pass
        elif self.program:  # the restart program was running: the restart has not happened
            self.program = False
            rt.tasks[0].halt()
        elif rt.modes.running and cause != "parameter":
            self.image = None if self._excluded(error) else self.capture()
        elif cause != "manual":  # error / E-Stop during a stop or in Manual; Parameter mode
            self.image = None
        if cause == "parameter":
            self.image = None
        self._version = rt.memory.version
        self.settings = {}
        self._outputs_done = False
        self._publish()

    def power_on(self) -> None:
        """After power-up: the image of a program that ran (or a restart program) when the power
        went is restorable (decision 10); any other is discarded (decision 2)."""
        rt = self.rt
        doc = rt.memory.restart
        self.image = None
        if doc is not None:
            state, image = RestartImage.from_json(doc)
            if state in ("running", "restarting") and not self._excluded(None):
                self.image = image
                for n, a in image.axes.items():
                    axis = rt.axes.get(n)
                    if axis is not None and rt.memory.parameters.encoder_type(n) == 0:
                        axis.set_actual(a.actual + float(_shift(axis)))  # the buffered counter (decision 10)
        self._version = rt.memory.version
        self._publish()

    def started(self) -> None:
        """A Start from 0000: the image is given up (decision 6)."""
        self.image = None
        self.program = False
        self.settings = {}
        self._publish()

    # -- the edge ------------------------------------------------------------------------------

    def edge(self) -> None:
        """Re-Start rising in Automatic without a fault, Immediate Stop closed (modes)."""
        modes = self.rt.modes
        if modes.running:
            return  # decision 6: as Start while running
        if self.image is None or self.program:
            modes.start()
            return
        b016 = int(self.rt.memory.parameters.get("B016")["restart_instruction"])
        self._outputs_done = False
        modes.begin_restart()
        if b016 == 0:
            self.restore(outputs=True)
            return
        self.program = True
        self.rt.tasks[0].start(b016)
        self._publish()

    def restore(self, outputs: bool, task1_at: int | None = None) -> None:
        """Put the image back: axes, tasks, markers (and outputs); the image is used up."""
        image = self.image
        if image is None:
            return
        self._restoring = True
        try:
            self._restore(image, outputs, task1_at)
        finally:
            self._restoring = False
        self.image = None
        self.program = False
        self.rmi = None
        self._publish()

    def _restore(self, image: RestartImage, outputs: bool, task1_at: int | None) -> None:
        rt = self.rt
        if outputs and not self._outputs_done:
            self.restore_outputs()
        for op, value in zip(_M2_BYTES, image.markers):
            rt.image.set(op, value)
        rt.master_factor = image.master_factor
        self.settings = {}
        for n, a in image.axes.items():
            axis = rt.axes.get(n)
            if axis is None:
                continue
            if a.acc is not None:
                axis.set_acceleration(*a.acc)
                self.settings.setdefault(n, {})["acc"] = a.acc
            if a.fak is not None:
                axis.set_factor(a.fak)
                self.settings.setdefault(n, {})["fak"] = a.fak
            if a.target is not None:
                axis.move_to(a.target + _shift(axis), a.speed)
        for n, ti in image.tasks.items():
            task = rt.tasks[n - 1]
            task.pc, task.running, task.wait = ti.pc, ti.running, "moving" if ti.moving else None
            task.stack[:] = ti.stack
        if task1_at is not None:
            task = rt.tasks[0]
            task.pc, task.running, task.wait = task1_at, True, None
            task.stack.clear()

    def restore_outputs(self) -> None:
        image = self.image
        if image is None:
            return
        for op, value in zip(_OUTPUT_BYTES, image.outputs):
            self.rt.write_byte(op, value)  # bits the Logic Task owns stay its own
        self._outputs_done = True

    # -- per cycle -------------------------------------------------------------------------------

    def after_tasks(self) -> None:
        """An RSV t=1 of this cycle takes effect now: the tasks go on next cycle (decision 8)."""
        at = self._finish
        if at is None:
            return
        self._finish = None
        self.restore(outputs=False, task1_at=at if at > 0 else None)

    def tick(self) -> None:
        """End of the NC cycle: keep the persisted image current (decision 10, cheap: a key of a
        counter and the axis targets) and drop an image of a changed program (decision 11)."""
        rt = self.rt
        if self.image is not None and rt.memory.version != self._version:
            self.image = None
            self.program = False
            self._publish()
            return
        if self.program or not rt.modes.running:
            if self._key is not None:
                self._publish()
            return
        axes = rt.axes
        if len(axes) == 1:  # (the common case without a generator expression per cycle)
            (a,) = axes.values()
            key: tuple[Any, ...] = (self.generation, getattr(a, "exact_target", None))
        else:
            key = (self.generation, *(getattr(a, "exact_target", None) for a in axes.values()))
        if key != self._key:
            memory = rt.memory
            memory.restart = self.capture().to_json("running")
            memory.restart_version += 1
            self._key = key

    def _publish(self) -> None:
        """The memory's copy of what waits (not a running program's state)."""
        memory = self.rt.memory
        self._key = None
        if self.image is None:
            doc = None
        else:
            doc = self.image.to_json("restarting" if self.program else "interrupted")
        if doc != memory.restart:
            memory.restart = doc
            memory.restart_version += 1

    # -- notes from the commands --------------------------------------------------------------

    def note(self, axis: int, name: str, value: Any) -> None:
        """ACC / FAK of the program (decision 1)."""
        self.settings.setdefault(axis, {})[name] = value

    def note_rmi(self, task: NcTask) -> None:
        if task.number == 2:
            self.rmi = (task.pc, list(task.stack))


def _shift(axis: Any) -> Fraction:
    """The axis' SAC shift against its initial frame (0 where the axis has none)."""
    return Fraction(getattr(axis, "frame_shift", 0))


def op_rsv(rt: ClmRuntime, task: NcTask, ins: Instruction) -> int | None:
    """RSV t nnnn fffff: one cycle (decision 8)."""
    rs = rt.restart
    terminate, at, flags = str(ins.values[0]) == "1", rt.target(ins, 1), str(ins.values[2])
    if not (rs.program and task.number == 1):
        return task.pc + 1  # no function outside the restart program
    if flags[0] == "1":
        rs.restore_outputs()
    if terminate:
        rs._finish = at if at else -1
    return task.pc + 1
