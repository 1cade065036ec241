"""The five NC tasks of the CLM: one instruction per task per NC cycle, in the order 1..5.

Manual §5 and §7.5 (L3400-3472), spec §1.4, §3.4, §3.9. A task holds its instruction counter,
its subroutine stack (127 levels: the 128th JSR is fault 0B, an RTS on an empty stack 0C) and,
while a waiting command holds it (AKN, AKP, WAI, PSA, PSI, ...), that command's state. Every
instruction takes one NC cycle, NOP and jumps included; a waiting command is evaluated again
each cycle until its condition holds, then the task goes on in the next cycle ("the process
time is always extended by the cycle time required for the outcome to arrive"). Up to four
consecutive TXT run in one cycle (L2756). A completed instruction of tasks 1, 2, 4, 5 that
changes state (not in `restart.PURE`) bumps the restart generation, so that the battery-buffered
restart image is written only then (restart decision 10).

The command semantics are `execute.HANDLERS`, one function per mnemonic; this module only runs
them. A handler returns the next instruction number, or None to stay on its instruction.

Decisions (spec line -> choice, why)
------------------------------------
1. C-WAI, errata "WAI cycle counting": WAI t holds its task for ceil(t / T) NC cycles counted
   from the cycle it is reached in, and the next instruction runs in the cycle after: WAI
   00.010 at T = 2 ms holds 5 cycles. Test: ``tests/devices/clm/test_nc.py::test_wai_counts_cycles``.
2. C-TXT, L2756 "up to 4 consecutive TXT commands are executed in one cycle": a TXT followed by
   TXT runs on in the same cycle, four at most; the next instruction runs in the next cycle.
   Test: ``test_four_txt_in_one_cycle``.
3. C-TASK-ORDER, L3472 "An output set in Task 1 is processed in Task 4 as a set output": the
   tasks share one image, so a marker or output written by task k is read by the tasks after
   it in the same cycle; the hardware outputs follow at the next cycle's start (`runtime`).
   Test: ``test_a_bit_written_by_task_1_is_seen_by_task_4_in_the_same_cycle``.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from .errors import ClmError
from .program import PROGRAM_SIZE, Instruction
from .restart import PURE

if TYPE_CHECKING:
    from .runtime import ClmRuntime

__all__ = ["STACK_DEPTH", "Handler", "NcTask"]

STACK_DEPTH = 127
TXT_PER_CYCLE = 4

Handler = Callable[["ClmRuntime", "NcTask", Instruction], "int | None"]


@dataclass
class NcTask:
    """One NC task: where it is, its stack, and the state of a command that waits."""

    number: int
    pc: int = 0
    running: bool = False
    stack: list[int] = field(default_factory=list)
    wait: Any = None  # the waiting command's own state (None: the instruction is new)
    #: the instruction after the first JSR of the main program (Status 02 / 08 / 39)
    cycles_on_instruction: int = 0

    def start(self, pc: int) -> None:
        self.pc, self.running, self.wait = pc, True, None
        self.stack.clear()

    def halt(self) -> None:
        """Stop where it is (Immediate Stop, JST, a fault): the next start decides where to go on."""
        self.running = False
        self.wait = None

    def push(self, return_to: int) -> None:
        if len(self.stack) >= STACK_DEPTH:
            raise ClmError("0B", f"task {self.number}: more than {STACK_DEPTH} subroutine levels")
        self.stack.append(return_to)

    def pop(self) -> int:
        if not self.stack:
            raise ClmError("0C", f"task {self.number}: RTS without a JSR")
        return self.stack.pop()

    @property
    def main_return(self) -> int | None:
        """The instruction after the first JSR of the main program (bottom of the stack)."""
        return self.stack[0] if self.stack else None

    def step(self, rt: ClmRuntime, handlers: dict[str, Handler]) -> None:
        """Run this task's instruction(s) of one NC cycle; a fault propagates as ClmError."""
        for _ in range(TXT_PER_CYCLE):
            ins = rt.memory.program[self.pc]
            try:
                nxt = handlers[ins.command.mnemonic](rt, self, ins)
            except ClmError as e:
                raise e.at(f"N{self.pc:04d}") from None
            if nxt is None:  # waits: the same instruction again next cycle
                self.cycles_on_instruction += 1
                return
            self.wait = None
            self.cycles_on_instruction = 0
            if self.number != 3 and ins.mnemonic not in PURE:  # state changed: the restart image follows
                rt.restart.generation += 1
            if not self.running:  # JST / a stop inside the handler: the counter is set, the task rests
                self.pc = nxt
                return
            if nxt >= PROGRAM_SIZE:
                self.running = False
                raise ClmError("0E", f"task {self.number} ran past instruction 2999", f"N{self.pc:04d}")
            was_txt = ins.mnemonic == "TXT"
            self.pc = nxt
            if not (was_txt and rt.memory.program[nxt].mnemonic == "TXT"):
                return
