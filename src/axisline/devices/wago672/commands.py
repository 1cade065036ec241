"""The move commands of the 750-672 (a part of `device.Wago672`; manual §4.3, wago.md §3.9): the
sub-commands of the mailbox's DRIVE_COMMAND and the lines of a run program.

    rc = dev.drive_command(Opcode.MOVE, (0x00, 0x28, 0x00))      # MOVE 10240, source "mailbox"
    rc = dev.drive_command(Opcode.SET_VELOCITY, (0xA8, 0x61, 0))  # SET_VELOCITY 25000
    rc == RC.OK                                                   # the mailbox's return code

A command the module rejects with an error code raises that error (the output stage goes
off) and returns 0x01; a command outside its mode is 0x23, a MOVE while a process runs 0x12.

Decisions ([AMBIGUOUS]/[RECONSTRUCTED] points of wago.md §2.2 and §3.9; the manual wins):
* D17 MOVE/MOVE_REL/SPEED (non-immediate) are accepted when no process is running (Busy = 0),
  also after a stop left On_Target at 0 - a literal "On_Target has been set" would lock MOVE out
  after every STOP until MOVE_IMMEDIATE. While a process runs they return 0x12.
* D18 MOVE_REL is relative to the last accepted target while one is valid; a stop, STOP_NO_RAMP,
  Enable loss, a reference run or a set position invalidate it (wago.md §2.2 [RECONSTRUCTED]).

Tests: D17, D18 test_drive_command.py::test_speed_and_stop_fast.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from axisline.devices.wago672.errors import WagoError
from axisline.devices.wago672.image import MODE_IDLE, MODE_MAILBOX, MODE_PROGRAM
from axisline.devices.wago672.opcodes import RC, Opcode
from axisline.devices.wago672.thermal import CurrentPhase
from axisline.devices.wago672.modes import Modes

__all__ = ["Opcode", "RC", "MoveCommands"]


class MoveCommands(Modes):
    """DRIVE_COMMAND and the run programs' move commands: a layer of `Wago672` over `Modes` (state.py)."""

    def drive_command(self, opcode: int, data: bytes | tuple[int, int, int] = (0, 0, 0), source: str = "mailbox") -> int:
        """Execute a move-mode command (DRIVE_COMMAND sub-command or run-program line).

        data: Data 1..3 (MB3..MB5, LSB first). source: "mailbox" (needs the mode "Run commands
        via mailbox") or "program" (needs the run-program mode). Returns the mailbox return code;
        a command the module rejects with an error code raises that error and returns 0x01.
        """
        d = bytes(data)
        if len(d) != 3:
            raise ValueError(f"drive_command data must be 3 bytes (Data 1..3), got {len(d)}")
        needed = MODE_MAILBOX if source == "mailbox" else MODE_PROGRAM
        if source not in ("mailbox", "program"):
            raise ValueError(f"source must be 'mailbox' or 'program', got {source!r}")
        if (self.mode != needed and not (source == "program" and self._autostarted())) or self._mode_exit or not self._ready:
            return RC.ACCESS_DENIED
        handler = _COMMANDS.get(opcode)
        if handler is None:
            code = 1114 if opcode in (Opcode.TORQ, Opcode.TORQ_IMM) else 1112
            self._raise(code, f"move command {opcode:#04x} is not available on the 750-672")
            return RC.UNKNOWN_COMMAND
        try:
            return handler(self, d, source)
        except WagoError as e:
            self._raise(e.code, e.text)
            return RC.GENERAL_ERROR

    def _autostarted(self) -> bool:
        """A run program started by Program_Autostart runs while no mode is selected (program.py)."""
        return self.mode == MODE_IDLE and bool(getattr(self.program, "autostarted", False))

    @property
    def stopping(self) -> bool:
        """A STOP ramp brakes the drive (Stop1_N/Stop2_N, limit switch, mode exit, STOP_FAST)."""
        return self._stopping

    def _busy_process(self) -> bool:
        return self.busy or self._pending is not None

    def _cmd_move(self, d: bytes, source: str, immediate: bool = False, relative: bool = False) -> int:
        if not immediate and self._busy_process():
            return RC.NOT_ACCEPTED
        if not self._stop_chain_open():
            return RC.ACCESS_DENIED
        value = int.from_bytes(d, "little", signed=True)
        if relative:
            base = self._last_target if self._last_target is not None else self._state().p
            target = base + self.scaling.distance(value)
        else:
            target = self._absolute_target(value)
        return self._mbx_move(target, source)

    def _mbx_move(self, target: float, source: str) -> int:
        self._source = source
        ok = self._move(target, self.velocity, self.acc_up, self.acc_down, self.velocity_target)
        return RC.OK if ok else RC.ACCESS_DENIED

    def _cmd_move_table(self, d: bytes, source: str, immediate: bool = False, relative: bool = False) -> int:
        if not immediate and self._busy_process():
            return RC.NOT_ACCEPTED
        if not self._stop_chain_open():
            return RC.ACCESS_DENIED
        value = self.position_table(d[0], d[1] & 1)
        if relative:
            base = self._last_target if self._last_target is not None else self._state().p
            target = base + self.scaling.distance(value)
        else:
            target = self._absolute_target(value)
        return self._mbx_move(target, source)

    def _cmd_speed(self, d: bytes, source: str, immediate: bool = False) -> int:
        if not immediate and self._busy_process():
            return RC.NOT_ACCEPTED
        if not self._stop_chain_open():
            return RC.ACCESS_DENIED
        v = int.from_bytes(d[0:2], "little", signed=True)
        if not -25000 <= v <= 25000:
            raise WagoError(1117, f"SPEED velocity = {v} is outside -25000 .. 25000")
        self._source = source
        ok = self._speed(v, self.acc_up, self.acc_down)
        return RC.OK if ok else RC.ACCESS_DENIED

    def _stop_chain_open(self) -> bool:
        """Stop1_N and Stop2_N are 1: the drive may be started."""
        return self._stop_n_ack and bool(self._sig.stop2_n and self._sig.stop1_n)

    def _cmd_stop_fast(self, d: bytes, source: str) -> int:
        if self.program is not None and source == "mailbox" and self.program.running:
            self.program.stop(self)  # type: ignore[arg-type]  # a layer of Wago672
        self._ref = None
        self._stop_fast()
        self.busy = False if self._at_rest() else self.busy
        return RC.OK

    def _cmd_stop_no_ramp(self, d: bytes, source: str) -> int:
        self._ref = None
        self._no_ramp()
        self.busy = False
        return RC.OK

    def _cmd_reference(self, d: bytes, source: str) -> int:
        if not self._stop_chain_open():
            return RC.ACCESS_DENIED
        swt, std, dirbit = d[2] & 1, (d[2] >> 1) & 1, (d[2] >> 2) & 1
        self._mailbox_reference = True
        self._source = source
        ok = self._start_reference(1 if std else -1, bool(swt), 1 if dirbit else -1, self._sig)
        if not ok:
            # mailbox: "error message 23" at a limit switch, no Err_Range bit needed
            return RC.ACCESS_DENIED
        return RC.OK

    def _cmd_acc_mode(self, d: bytes, source: str) -> int:
        m = d[0]
        for shift, name in ((0, "ACC_T"), (2, "ACC_M"), (4, "DEC_T"), (6, "DEC_M")):
            if (m >> shift) & 3 == 3:
                raise WagoError(1557, f"SET_ACC_MODE {name} = 3 is reserved (allowed 0 .. 2)")
        self.acc_mode = m
        return RC.OK

    def _cmd_acc(self, d: bytes, source: str) -> int:
        a = int.from_bytes(d[0:2], "little", signed=True)
        if not 1 <= a <= 32767:
            raise WagoError(1121, f"SET_ACC acceleration = {a} is outside 1 .. 32767")
        sel = d[2] & 3
        if sel in (0, 1, 3):
            self.acc_up = a
        if sel in (0, 2, 3):
            self.acc_down = a
        return RC.OK

    def _cmd_acc_param(self, d: bytes, source: str, down: bool = False) -> int:
        v = int.from_bytes(d, "little")
        if not 1 <= v <= 16777215:
            raise WagoError(1557, f"SET_ACC_PARAM_{'DOWN' if down else 'UP'} = {v} is outside 1 .. 16777215")
        if down:
            self.param_down = v
        else:
            self.param_up = v
        return RC.OK

    def _cmd_velocity(self, d: bytes, source: str, target: bool = False) -> int:
        v = int.from_bytes(d[0:2], "little", signed=True)
        lo = 0 if target else 1
        if not lo <= v <= 25000:
            raise WagoError(1117, f"SET_VELOCITY{'_TARGET' if target else ''} = {v} is outside {lo} .. 25000")
        if target:
            self.velocity_target = v
        else:
            self.velocity = v
        return RC.OK

    def _cmd_set_position(self, d: bytes, source: str, zero: bool = False) -> int:
        if not self._at_rest() or self._busy_process():
            raise WagoError(1125, "the actual value can only be set at standstill")
        value = 0 if zero else int.from_bytes(d, "little", signed=True)
        steps = self.scaling.steps(value, "SET_ACTUALPOSITION")
        period = self.config.values["Rotary_Axis_Period"]
        if period and not 0 <= steps < period:
            raise WagoError(1261, f"SET_ACTUALPOSITION {value} is outside the rotary axis range 0 .. {period - 1} microsteps")
        self._set_actual(float(steps))
        return RC.OK

    def _cmd_current(self, d: bytes, source: str) -> int:
        ratio = d[0]
        if ratio > 150:
            raise WagoError(1217, f"SET_CURRENT {ratio} % is above 150 %")
        for bit, phase in enumerate((CurrentPhase.STANDSTILL, CurrentPhase.RAMP_UP, CurrentPhase.DRIVE, CurrentPhase.RAMP_DOWN)):
            if d[1] >> bit & 1:
                self._ratio_set[phase] = ratio
        return RC.OK


_COMMANDS: dict[int, Callable[[Any, bytes, str], int]] = {
    Opcode.MOVE: lambda dev, d, s: dev._cmd_move(d, s),
    Opcode.MOVE_IMMEDIATE: lambda dev, d, s: dev._cmd_move(d, s, immediate=True),
    Opcode.MOVE_REL: lambda dev, d, s: dev._cmd_move(d, s, relative=True),
    Opcode.MOVE_TABLE: lambda dev, d, s: dev._cmd_move_table(d, s),
    Opcode.MOVE_TABLE_IMMEDIATE: lambda dev, d, s: dev._cmd_move_table(d, s, immediate=True),
    Opcode.MOVE_TABLE_REL: lambda dev, d, s: dev._cmd_move_table(d, s, relative=True),
    Opcode.SPEED: lambda dev, d, s: dev._cmd_speed(d, s),
    Opcode.SPEED_IMMEDIATE: lambda dev, d, s: dev._cmd_speed(d, s, immediate=True),
    Opcode.STOP_FAST: MoveCommands._cmd_stop_fast,
    Opcode.STOP_NO_RAMP: MoveCommands._cmd_stop_no_ramp,
    Opcode.START_REFERENCING: MoveCommands._cmd_reference,
    Opcode.SET_ACC_MODE: MoveCommands._cmd_acc_mode,
    Opcode.SET_ACC: MoveCommands._cmd_acc,
    Opcode.SET_ACC_PARAM_UP: lambda dev, d, s: dev._cmd_acc_param(d, s),
    Opcode.SET_ACC_PARAM_DOWN: lambda dev, d, s: dev._cmd_acc_param(d, s, down=True),
    Opcode.SET_VELOCITY: lambda dev, d, s: dev._cmd_velocity(d, s),
    Opcode.SET_VELOCITY_TARGET: lambda dev, d, s: dev._cmd_velocity(d, s, target=True),
    Opcode.SET_ACTUALPOSITION: lambda dev, d, s: dev._cmd_set_position(d, s),
    Opcode.SET_ACTUALPOSITION_ZERO: lambda dev, d, s: dev._cmd_set_position(d, s, zero=True),
    Opcode.SET_CURRENT: MoveCommands._cmd_current,
}
