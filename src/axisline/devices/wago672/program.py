"""Run programs of the 750-672: the command encoding and the interpreter (manual §3.10.5,
§3.11.1.7, §4.3; wago.md §2.12, §3.9, §5.6 .. §5.8).

    lines = [Line(Cmd.SET_VELOCITY, 20000), Line(Cmd.WAIT_TEST_BIT, 0x30, 1), Line(Cmd.MOVE, 65056),
             Line(Cmd.GOTO, 1)]
    blocks = [line.encode() for line in lines]            # DLD_CONT MB2..MB5 (compressed 24 bit)
    Line.decode(bytes([0x25, 0x20, 0x4E, 0x00]))          # Line(SET_VELOCITY, 20000)

A program line is 4 bytes: command, Data 1 (LSB), Data 2, Data 3 (MSB) - exactly MB2..MB5 of
a DRIVE_COMMAND. `Line(cmd, *args)` encodes by command: one 24-bit value (MOVE, MOVE_REL,
SET_ACTUALPOSITION: signed; WAIT_TIME, SET_ACC_PARAM_*: unsigned), a 16-bit value and a byte
(SPEED*, SET_VELOCITY*, SET_ACC with SEL), a byte and a 16-bit value (VAR_SET/INC/DEC), single
bytes (bit numbers, filter numbers, table entries), a 16-bit jump target / label and a bit
number (GOTO_IF...).

`ProgramEngine` is the device's `program` (the RunProgram seam of device.py): Start in the Run
program mode calls `start(Start_Instruction_Counter)` (the address in D2..D3 of the process
image, 0-based line index; a running program is interrupted and starts again there), the device
calls `tick` every 1 ms while the mode is active and `stop` when the mode ends (mode bit
cleared, Stop1_N/Stop2_N, Enable or an error). Each tick the interpreter executes consecutive
lines until one has to wait:

* move commands (MOVE, MOVE_TABLE, MOVE_REL, MOVE_TABLE_REL, SPEED, START_REFERENCING) go to
  `device.drive_command(..., source="program")`; one is started only when the previous motion
  has ended (the device answers 0x12 while Busy; the line is repeated every tick) - "there is no
  waiting for the end of the process" after it has started;
* the _IMMEDIATE variants, STOP_FAST, STOP_NO_RAMP and the SET_* commands act at once;
* WAIT_TIME waits the given ms, WAIT_TEST_BIT until the bit has the given state;
* VAR_* (filters.py), WR_BIT, NOP, LABEL run at once; GOTO* jump (0-based line numbers);
* PROG_STOP ends the program (STOP_FAST; error 1311..1318 for message 1..8), PROG_END (0x00 /
  0xFF, the content of a blank line) ends it with STOP_FAST and error 1319 TBL_PROGRAM_END.

Autostart (§3.11.1.7.4): with HwSwConfig bit 7 (Program_Autostart) the program found in the
EEPROM starts at address 0 once after each reset, as soon as Ready and Stop_N_ACK are set while
Reset is still set and no mode is selected; it runs without the Run program mode
(`autostarted`) and ends when Reset is acknowledged (Reset_Quit). Without a valid program in the
EEPROM it is error 1142 CM_AUTOSTART_NOT_POSSIBLE.

Decisions ([AMBIGUOUS]/[CONFLICT]/[RECONSTRUCTED] points of wago.md; the manual wins):
* P1 Jump targets (wago.md §3.9 [AMBIGUOUS] "range 1 … 500" vs. the example of §3.11.1.7.3,
  §10.3 item 11): GOTO* operands are 0-based line indexes (the example's "0xF5 0x02 - Go to line
  2" with lines numbered from 0); the table has 400 lines, a target >= 400 (or running past line
  399) is 1323 TBL_ENDOFTABLE. Test: test_program::test_run_program_example_of_the_manual.
* P2 Labels (§10.3 item 12): 16-bit label numbers 0 .. 65535; the lowest line with the label
  wins; a missing label is 1322 TBL_LABELNOTFOUND. Test:
  test_program::test_labels_and_conditional_jumps_with_a_counter,
  test_program::test_a_missing_label_and_jumps_out_of_the_table.
* P3 Run-program example target (§10.3 item 10, wago.md §9.10): the printed bytes 0x20 0xFE
  0x00 are authoritative: the move goes to 65056, not the prose's 65065. Test:
  test_program::test_run_program_example_of_the_manual.
* P4 Lines per tick (wago.md §5.6 [RECONSTRUCTED]): at most 16 lines are executed per 1 ms tick
  (an endless GOTO loop costs 16 lines a tick and keeps the module responsive). A line that
  started a motion (a move command accepted by the drive) is the last of its tick: the next line
  runs one tick later, when the status bits show the new motion, so "MOVE; WAIT_TEST_BIT
  On_Target 1" waits for this move, not the last one. Test:
  test_program::test_an_endless_goto_loop_runs_16_lines_a_tick,
  test_program::test_labels_and_conditional_jumps_with_a_counter.
* P5 PROG_END / PROG_STOP "Sets speed to Zero, deactivates the final step" (wago.md §5.6
  [AMBIGUOUS], §10.3 item 30): the drive is braked with STOP_FAST (Acceleration_Stop_Fast);
  PROG_STOP 0 ends without error and leaves the output stage on; PROG_END and PROG_STOP 1..8
  raise 1319 / 1311..1318 (1318 for message 8 [RECONSTRUCTED]), which switches the output stage
  off like every error. A reserved message number 9..255 is 1321 TBL_UNKNOWN_CMD. Test:
  test_program::test_prog_end_and_prog_stop.
* P6 Restart (§3.11.1.7 C1 text vs. sequence diagram (9), wago.md §5.6 [CONFLICT]): a Start edge
  during a running program brakes the drive (the device's STOP_FAST) and restarts the program at
  the address in D2..D3; its first move command waits for standstill. Test:
  test_program::test_start_edge_restarts_at_the_new_address.
* P7 Move command manager (wago.md §5.8): a STOP ramp of a higher priority source (Stop1_N /
  Stop2_N, limit switch, software limit, mode exit) - and the program's own STOP_FAST, which is
  "processed in priority" - is never interrupted: while it brakes every program move command
  (immediate ones too) waits for standstill; then the device decides (a start toward an active
  limit switch is 1931); 1911 COMMAND_IS_RUNNING / 1912 HIGH_Prio_COMMAND_IS_RUNNING, which
  the manual marks "internal", are not raised for this. A move command the device refuses
  without an error code (0x23: a start outside the software limits, START_REFERENCING at a limit
  switch) cannot be executed by the program: error 1115 CI_COMMAND_DENIED ends it. START_REFERENCING waits like MOVE (it is a
  motion command). Test: test_program::test_a_stop_ramp_is_not_interrupted_by_the_program,
  test_program::test_a_move_the_drive_refuses_is_1115.
* P8 WAIT_TEST_BIT / WR_BIT / GOTO_IF state byte: 0 is 0, every other value 1. WAIT_TIME counts
  from the tick its line is reached: WAIT_TIME n lets the next line run n ticks later. Test:
  test_program::test_wait_time_and_wr_bit.
* P9 Autostart (wago.md §5.7 [RECONSTRUCTED], §10.3 item 28): checked every tick after a reset
  until Reset is acknowledged; Reset_Quit before Ready and Stop_N_ACK cancels the opportunity.
  The autostarted program needs no mode; selecting the Run program mode adopts it (it goes on as
  a normal run program), selecting any other mode ends it (a move it started is completed - the
  selected mode's source takes over, §3.10.5), Reset_Quit ends it with STOP_FAST. Test:
  test_program::test_autostart_*.
* P10 State variable 40 "Current run command": the command byte of the line at the command
  counter; 41 (device) the counter itself. Test: test_program::test_run_program_example_of_the_manual.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from enum import IntEnum
from typing import TYPE_CHECKING

from axisline.devices.wago672.device import RC, Opcode
from axisline.devices.wago672.errors import WagoError
from axisline.devices.wago672.image import MODE_IDLE, MODE_PROGRAM
from axisline.devices.wago672.tables import MAX_DATA_SETS, TableKind

if TYPE_CHECKING:
    from axisline.devices.wago672.device import Wago672
    from axisline.devices.wago672.filters import FilterBank
    from axisline.devices.wago672.tables import Table, TableManager

__all__ = ["Cmd", "Line", "ProgramEngine", "LINES_PER_TICK", "PROGRAM_LINES", "encode_program", "MOVE_COMMANDS"]

LINES_PER_TICK = 16  # P4
PROGRAM_LINES = MAX_DATA_SETS[TableKind.PROGRAM]  # 400


class Cmd(IntEnum):
    """Every run command (manual §4.3, wago.md §3.9)."""

    PROG_END = 0x00
    MOVE = 0x02
    MOVE_IMMEDIATE = 0x03
    MOVE_TABLE = 0x04
    MOVE_TABLE_IMMEDIATE = 0x05
    MOVE_REL = 0x06
    MOVE_TABLE_REL = 0x08
    SPEED = 0x10
    SPEED_IMMEDIATE = 0x11
    STOP_FAST = 0x18
    STOP_NO_RAMP = 0x19
    TORQ = 0x1C
    TORQ_IMM = 0x1D
    START_REFERENCING = 0x20
    SET_ACC_MODE = 0x21
    SET_ACC = 0x22
    SET_ACC_PARAM_UP = 0x23
    SET_ACC_PARAM_DOWN = 0x24
    SET_VELOCITY = 0x25
    SET_VELOCITY_TARGET = 0x2B
    SET_ACTUALPOSITION = 0x2E
    SET_ACTUALPOSITION_ZERO = 0x2F
    SET_CURRENT = 0x39
    VAR_SET = 0x50
    VAR_INC = 0x51
    VAR_DEC = 0x52
    VAR_ADD = 0x53
    VAR_SUB = 0x54
    VAR_MUL = 0x55
    VAR_COPY = 0x56
    VAR_DIV = 0x57
    WAIT_TIME = 0x70
    WAIT_TEST_BIT = 0x71
    WR_BIT = 0x78
    NOP = 0xF0
    PROG_STOP = 0xF1
    GOTO = 0xF5
    GOTO_IF = 0xF6
    GOTO_IF_NOT = 0xF7
    GOTO_LABEL = 0xF8
    GOTO_LABEL_IF = 0xF9
    GOTO_LABEL_IF_NOT = 0xFA
    LABEL = 0xFB
    PROG_END_FF = 0xFF


# operand layout per command: field sizes in bytes (signedness) over Data 1..3
_S24 = (("s", 3),)
_U24 = (("u", 3),)
_S16_B = (("s", 2), ("u", 1))
_B_S16 = (("u", 1), ("s", 2))
_U16_B = (("u", 2), ("u", 1))
_BBB = (("u", 1), ("u", 1), ("u", 1))
_NONE: tuple[tuple[str, int], ...] = ()
_LAYOUT: dict[int, tuple[tuple[str, int], ...]] = {
    Cmd.PROG_END: _NONE, Cmd.PROG_END_FF: _NONE, Cmd.NOP: _NONE,
    Cmd.STOP_FAST: _NONE, Cmd.STOP_NO_RAMP: _NONE, Cmd.SET_ACTUALPOSITION_ZERO: _NONE,
    Cmd.MOVE: _S24, Cmd.MOVE_IMMEDIATE: _S24, Cmd.MOVE_REL: _S24, Cmd.SET_ACTUALPOSITION: _S24,
    Cmd.SET_ACC_PARAM_UP: _U24, Cmd.SET_ACC_PARAM_DOWN: _U24, Cmd.WAIT_TIME: _U24,
    Cmd.MOVE_TABLE: _BBB, Cmd.MOVE_TABLE_IMMEDIATE: _BBB, Cmd.MOVE_TABLE_REL: _BBB,
    Cmd.SPEED: _S16_B, Cmd.SPEED_IMMEDIATE: _S16_B, Cmd.SET_ACC: _S16_B,
    Cmd.SET_VELOCITY: _S16_B, Cmd.SET_VELOCITY_TARGET: _S16_B, Cmd.TORQ: _S16_B, Cmd.TORQ_IMM: _S16_B,
    Cmd.START_REFERENCING: _BBB, Cmd.SET_ACC_MODE: _BBB, Cmd.SET_CURRENT: _BBB,
    Cmd.VAR_SET: _B_S16, Cmd.VAR_INC: _B_S16, Cmd.VAR_DEC: _B_S16,
    Cmd.VAR_ADD: _BBB, Cmd.VAR_SUB: _BBB, Cmd.VAR_MUL: _BBB, Cmd.VAR_COPY: _BBB, Cmd.VAR_DIV: _BBB,
    Cmd.WAIT_TEST_BIT: _BBB, Cmd.WR_BIT: _BBB, Cmd.PROG_STOP: _BBB,
    Cmd.GOTO: _U16_B, Cmd.GOTO_IF: _U16_B, Cmd.GOTO_IF_NOT: _U16_B,
    Cmd.GOTO_LABEL: _U16_B, Cmd.GOTO_LABEL_IF: _U16_B, Cmd.GOTO_LABEL_IF_NOT: _U16_B, Cmd.LABEL: _U16_B,
}

# move commands that wait for the end of the previous motion (§3.10.5)
MOVE_COMMANDS = frozenset({Cmd.MOVE, Cmd.MOVE_TABLE, Cmd.MOVE_REL, Cmd.MOVE_TABLE_REL, Cmd.SPEED, Cmd.START_REFERENCING})
_IMMEDIATE = frozenset({Cmd.MOVE_IMMEDIATE, Cmd.MOVE_TABLE_IMMEDIATE, Cmd.SPEED_IMMEDIATE})
_DEVICE = frozenset({
    Cmd.STOP_FAST, Cmd.STOP_NO_RAMP, Cmd.TORQ, Cmd.TORQ_IMM, Cmd.SET_ACC_MODE, Cmd.SET_ACC, Cmd.SET_ACC_PARAM_UP,
    Cmd.SET_ACC_PARAM_DOWN, Cmd.SET_VELOCITY, Cmd.SET_VELOCITY_TARGET, Cmd.SET_ACTUALPOSITION,
    Cmd.SET_ACTUALPOSITION_ZERO, Cmd.SET_CURRENT,
})
_VAR = frozenset(range(0x50, 0x58))


@dataclass(frozen=True, slots=True)
class Line:
    """One program line: the command and its operands (see the module docstring)."""

    cmd: int
    args: tuple[int, ...] = ()

    def __init__(self, cmd: int, *args: int) -> None:
        cmd = int(cmd)
        layout = _LAYOUT.get(cmd)
        if layout is None:
            raise ValueError(f"{cmd:#04x} is not a run command")
        if len(args) > len(layout):
            raise ValueError(f"{_name(cmd)} takes at most {len(layout)} operands, got {len(args)}")
        object.__setattr__(self, "cmd", cmd)
        object.__setattr__(self, "args", tuple(int(a) for a in args) + (0,) * (len(layout) - len(args)))
        self.data()  # range check of the operands

    def data(self) -> bytes:
        """Data 1..3 (MB3..MB5)."""
        out = b""
        for (kind, size), value in zip(_LAYOUT[self.cmd], self.args):
            bits = 8 * size
            lo, hi = (-(1 << (bits - 1)), (1 << (bits - 1)) - 1) if kind == "s" else (0, (1 << bits) - 1)
            if not lo <= value <= hi:
                raise ValueError(f"{_name(self.cmd)}: operand {value} is outside {lo} .. {hi}")
            out += (value & ((1 << bits) - 1)).to_bytes(size, "little")
        return out.ljust(3, b"\x00")

    def encode(self) -> bytes:
        """The 4 bytes of the line (command, Data 1 LSB, Data 2, Data 3 MSB)."""
        return bytes([self.cmd]) + self.data()

    @classmethod
    def decode(cls, raw: bytes) -> Line:
        raw = bytes(raw)
        if len(raw) != 4:
            raise ValueError(f"a program line is 4 bytes, got {len(raw)}")
        layout = _LAYOUT.get(raw[0])
        if layout is None:
            raise ValueError(f"{raw[0]:#04x} is not a run command")
        args = []
        pos = 1
        for kind, size in layout:
            args.append(int.from_bytes(raw[pos : pos + size], "little", signed=kind == "s"))
            pos += size
        return cls(raw[0], *args)

    def __repr__(self) -> str:
        return f"Line({_name(self.cmd)}{''.join(', ' + str(a) for a in self.args)})"


def encode_program(lines: Sequence[Line]) -> list[bytes]:
    """DLD_CONT blocks of a compressed 24-bit download."""
    return [line.encode() for line in lines]


def _name(cmd: int) -> str:
    try:
        return Cmd(cmd).name
    except ValueError:
        return f"{cmd:#04x}"


class ProgramEngine:
    """The run-program interpreter (RunProgram seam of device.py); installs itself as `device.program`."""

    def __init__(self, device: Wago672, tables: TableManager, filters: FilterBank) -> None:
        self.device = device
        self.tables = tables
        self.filters = filters
        self.running = False
        self.counter = 0
        self.autostarted = False
        self._table: Table | None = None
        self._labels: dict[int, int] | None = None
        self._wait_line: int | None = None
        self._wait_until = 0
        self._autostart_done = False
        self._now = 0
        device.program = self
        device.tick_hooks.append(self._autostart)
        device.extra_variables[40] = self.command

    # ---- RunProgram protocol
    def start(self, address: int, device: Wago672) -> None:
        table = self.tables.active_table(TableKind.PROGRAM)
        if table is None:
            raise WagoError(1352, "no valid run program table is active (download it and TABLE_START)")
        if not 0 <= address < table.size:
            raise WagoError(1323, f"Start_Instruction_Counter {address} is outside the program 0 .. {table.size - 1}")
        self._table = table
        self._labels = None
        self.counter = address
        self._wait_line = None
        self.running = True
        self.autostarted = False

    def stop(self, device: Wago672) -> None:
        self.running = False
        self.autostarted = False
        self._wait_line = None

    def reset(self) -> None:
        """Warm start: no program runs, the autostart is armed again."""
        self.stop(self.device)
        self._table = None
        self.counter = 0
        self._autostart_done = False

    def command(self) -> int:
        """State variable 40: the command at the command counter."""
        t = self._table
        if t is None or not 0 <= self.counter < t.size:
            return 0
        return t.entries[self.counter][0]

    def table_stop(self) -> tuple[int, int]:
        """TABLE_STOP: end the processing, then STOP_FAST; (return code, status)."""
        if not self.running:
            return RC.OK, 0
        rc = self.device.drive_command(Opcode.STOP_FAST, source="program")
        self.stop(self.device)
        return rc, rc

    # ---- the interpreter
    def tick(self, cycle: int, device: Wago672) -> None:
        if not self.running or self._table is None:
            return
        self._now = cycle
        for _ in range(LINES_PER_TICK):
            if not self.running:
                return
            try:
                if not self._step(device):
                    return
            except WagoError as e:
                self.running = False
                device.raise_error(e.code, e.text)
                self.stop(device)
                return

    def _goto(self, target: int) -> None:
        if not 0 <= target < PROGRAM_LINES or self._table is None or target >= self._table.size:
            raise WagoError(1323, f"line {self.counter}: jump target {target} is outside the program 0 .. {PROGRAM_LINES - 1}")
        self.counter = target

    def _label(self, label: int) -> int:
        if self._labels is None:
            labels: dict[int, int] = {}
            assert self._table is not None
            for i, (cmd, data) in enumerate(self._table.entries):
                if cmd == Cmd.LABEL:
                    labels.setdefault(data & 0xFFFF, i)
            self._labels = labels
        line = self._labels.get(label)
        if line is None:
            raise WagoError(1322, f"line {self.counter}: label {label} is not defined in the program")
        return line

    def _end(self, device: Wago672) -> None:
        device.drive_command(Opcode.STOP_FAST, source="program")
        self.running = False

    def _step(self, device: Wago672) -> bool:
        """Execute the line at the counter; False if it has to wait."""
        table = self._table
        assert table is not None
        if self.counter >= table.size:
            raise WagoError(1323, f"the program ran past its last line {table.size - 1}")
        cmd, d = table.line(self.counter)
        if cmd in MOVE_COMMANDS or cmd in _IMMEDIATE:
            if device.stopping:
                return False  # P7: a STOP ramp is not interrupted
            if cmd == Cmd.START_REFERENCING and device.busy:
                return False
            rc = device.drive_command(cmd, d, source="program")
            if rc == RC.NOT_ACCEPTED:
                return False
            if rc == RC.ACCESS_DENIED:
                raise WagoError(1115, f"line {self.counter}: {_name(cmd)} cannot be executed now (refused by the drive)")
            if rc != RC.OK:
                self.running = False
                return False
            self.counter += 1
            return False  # P4: the next line runs in the next tick, with the status bits of this motion
        elif cmd in _DEVICE:
            rc = device.drive_command(cmd, d, source="program")
            if rc == RC.ACCESS_DENIED:
                raise WagoError(1115, f"line {self.counter}: {_name(cmd)} cannot be executed now")
            if rc != RC.OK:
                self.running = False
                return False
        elif cmd in _VAR:
            self.filters.execute(cmd, d)
        elif cmd == Cmd.WAIT_TIME:
            if self._wait_line != self.counter:
                self._wait_line = self.counter
                self._wait_until = self._now + int.from_bytes(d, "little")
            if self._now < self._wait_until:
                return False
            self._wait_line = None
        elif cmd == Cmd.WAIT_TEST_BIT:
            if device.bits.read(d[0]) != bool(d[1]):
                return False
        elif cmd == Cmd.WR_BIT:
            device.bits.write(d[0], bool(d[1]))
        elif cmd in (Cmd.NOP, Cmd.LABEL):
            pass
        elif cmd in (Cmd.GOTO, Cmd.GOTO_IF, Cmd.GOTO_IF_NOT):
            if cmd == Cmd.GOTO or device.bits.read(d[2]) == (cmd == Cmd.GOTO_IF):
                self._goto(d[0] | d[1] << 8)
                return True
        elif cmd in (Cmd.GOTO_LABEL, Cmd.GOTO_LABEL_IF, Cmd.GOTO_LABEL_IF_NOT):
            if cmd == Cmd.GOTO_LABEL or device.bits.read(d[2]) == (cmd == Cmd.GOTO_LABEL_IF):
                self._goto(self._label(d[0] | d[1] << 8))
                return True
        elif cmd == Cmd.PROG_STOP:
            message = d[0]
            self._end(device)
            if message == 0:
                return False
            if message > 8:
                raise WagoError(1321, f"line {self.counter}: PROG_STOP error message {message} is reserved (1 .. 8)")
            raise WagoError(1310 + message, f"line {self.counter}: PROG_STOP with error message {message}")
        elif cmd in (Cmd.PROG_END, Cmd.PROG_END_FF):
            self._end(device)
            raise WagoError(1319, f"line {self.counter}: PROG_END - the program ended without PROG_STOP")
        else:
            raise WagoError(1321, f"line {self.counter}: {cmd:#04x} is not a run command")
        self.counter += 1
        return True

    # ---- autostart (P9)
    def _autostart(self, cycle: int) -> None:
        dev = self.device
        if self.autostarted:
            if not self.running:
                self.autostarted = False
            elif not dev.reset_flag:
                dev.drive_command(Opcode.STOP_FAST, source="program")
                self.stop(dev)
            elif dev.mode == MODE_PROGRAM:
                self.autostarted = False  # adopted by the Run program mode
            elif dev.mode != MODE_IDLE:
                self.stop(dev)
            return
        if self._autostart_done:
            return
        if not dev.reset_flag:
            self._autostart_done = True  # Reset_Quit before the start: no autostart after this reset
            return
        if not dev.config["HwSwConfig"] & 0x80:
            return
        if not (dev.ready and dev.stop_n_ack and dev.mode == MODE_IDLE):
            return
        self._autostart_done = True
        if self.tables.eeprom_program() is None:
            dev.raise_error(1142, "Program_Autostart is set but no valid run program is stored in the EEPROM")
            return
        try:
            self.start(0, dev)
        except WagoError as e:
            dev.raise_error(1142, e.text)
            return
        self.autostarted = True
