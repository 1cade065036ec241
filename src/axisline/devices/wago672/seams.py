"""What plugs into a 750-672 (a part of `device.Wago672`): the mailbox engine, the run-program
interpreter, the position table, and the wiring of the digital inputs DI1 .. DI6.

    dev = Wago672(axis, inputs={"Input1": True, "Input2": lambda: ref_switch.state})
    dev.mailbox      # MailboxHandler: MB0..MB5 of the PLC in, the reply out (every tick with C0.5)
    dev.program      # RunProgram: start / stop / tick, running, counter
    dev.position_table(index, src) -> position     # MOVE_TABLE*

`mailbox.attach(dev)` plugs in the real ones (mailbox.py, program.py, tables.py); until then
`NoMailbox` answers every opcode but IDLE with 0x13 and MOVE_TABLE finds no position table.

The seams of `Wago672` for the second engineer (mailbox, tables, run programs, camshaft, bit
linking, Modbus):
* `mailbox`: handler called every tick while C0.5 is set with MB0..MB5 of the PLC, returns
  the 6 reply bytes (default `NoMailbox`: toggle handshake, every opcode but IDLE is 0x13).
* `drive_command(opcode, data)`: the move commands of §3.9 (DRIVE_COMMAND, run programs).
* `program`: run-program hook (start(address), stop(), tick(cycle), running, counter).
* `position_table(index, src) -> position`: MOVE_TABLE* lookup; `cam_pattern(position) -> int`:
  CAM1..8 bit sample of the camshaft table at a position (microsteps).
* `bits` (BitTable): the bit field, updated each tick; `config` (ConfigTable).
* `state_variable(n)`: DIAG_RD_VAR; `errors`: the error memory (DIAG_RD_ERROR/DIAG_QUIT_ERROR
  -> `quit_errors()`); `warm_start()`.
* `tick_hooks` (called each tick after the source bits are written), `extra_variables` (more
  state variables), `stopping`, and a program with `autostarted` set runs in Idle mode
  (Program_Autostart). `mailbox.attach(dev)` plugs all of these in (mailbox.py, tables.py,
  program.py, filters.py, recorder.py).
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from functools import partial
from typing import TYPE_CHECKING, Any, Protocol

from axisline.devices.wago672.opcodes import RC
from axisline.devices.wago672.errors import WagoError

if TYPE_CHECKING:
    from axisline.devices.wago672.device import Wago672

__all__ = ["MailboxHandler", "NoMailbox", "RunProgram", "Inputs", "no_position_table"]


class MailboxHandler(Protocol):
    """The mailbox engine: called every tick while the mailbox is on (C0.5) with MB0..MB5 of
    the PLC; returns MB0..MB5 of the reply (6 bytes)."""

    def exchange(self, request: bytes, device: Wago672) -> bytes: ...


class NoMailbox:
    """Placeholder mailbox: the toggle handshake of §3.7.4 with return code 0x13 (unknown
    command) for every opcode except IDLE (0x00 OK) - "mailbox not available" until the
    mailbox engine is plugged in."""

    def __init__(self) -> None:
        self._reply = bytes(6)
        self._last: tuple[int, int] | None = None

    def exchange(self, request: bytes, device: Wago672) -> bytes:
        opcode, toggle = request[0], request[1] & 0x80
        if self._last is None or (opcode, toggle) != self._last:
            self._last = (opcode, toggle)
            rc = RC.OK if opcode == 0x00 else RC.UNKNOWN_COMMAND
            self._reply = bytes([opcode, toggle | rc, 0, 0, 0, 0])
        return self._reply


class RunProgram(Protocol):
    """Run-program interpreter hook (table manager engineer)."""

    running: bool
    counter: int

    def start(self, address: int, device: Wago672) -> None: ...  # raises WagoError (e.g. 1352)
    def stop(self, device: Wago672) -> None: ...
    def tick(self, cycle: int, device: Wago672) -> None: ...


def no_position_table(index: int, src: int) -> int:
    raise WagoError(1333, f"position table entry {index} (SRC {src}): no position table is active")


_CONSTANT_TYPES = (bool, int, float, type(None))


class Inputs:
    """DI1 .. DI6 from a mapping of booleans or callables ("Input1".."Input6" or 1..6).

    The mapping may change between ticks (a test rig rewires an input): `levels` compares it
    with the copy it last sorted into constants and functions, so a tick calls the functions
    only (a machine file wires the switches as functions of the position)."""

    def __init__(self, inputs: Mapping[Any, Any] | None) -> None:
        self.source = inputs if inputs is not None else {}
        self._seen: Any = None  # the mapping as `_sort` saw it
        self._fixed = bytes(6)  # the inputs wired to constants (0/1 each)
        self._functions: tuple[tuple[int, Callable[[], Any]], ...] = ()

    def read(self, n: int) -> bool:
        src = self.source
        v = src.get(f"Input{n}", src.get(n, False)) if hasattr(src, "get") else False
        if callable(v):
            v = v()
        return bool(v)

    def levels(self) -> bytes:
        """DI1 .. DI6 as six 0/1 bytes (`read` of each)."""
        src = self.source
        if src != self._seen:
            self._sort(src)
        if not self._functions:
            return self._fixed
        out = bytearray(self._fixed)
        for i, read in self._functions:
            if read():
                out[i] = 1
        return bytes(out)

    def _sort(self, src: Any) -> None:
        fixed = bytearray(6)
        functions = []
        if hasattr(src, "get"):
            for i in range(6):
                v = src.get(f"Input{i + 1}", src.get(i + 1, False))
                if callable(v):
                    functions.append((i, v))
                elif type(v) not in _CONSTANT_TYPES:
                    functions.append((i, partial(bool, v)))  # its truth may change: taken each tick
                elif v:
                    fixed[i] = 1
            self._seen = dict(src)
        else:
            self._seen = src  # not a mapping: every input open
        self._fixed = bytes(fixed)
        self._functions = tuple(functions)
