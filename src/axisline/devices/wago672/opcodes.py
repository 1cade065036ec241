"""The 750-672's move-command opcodes and mailbox return codes, as plain int constants (read in
the compiled per-cycle code: a class attribute of int, not an Enum member).

`program.Cmd` is the run-program view of the same opcodes (an IntEnum, for listings and errors);
a test holds the two to the same values.
"""

from __future__ import annotations

from typing import Final

__all__ = ["Opcode", "RC"]


class Opcode:
    """Move-mode commands of DRIVE_COMMAND and run programs (manual §4.3, wago.md §3.9)."""

    PROG_END: Final = 0x00
    MOVE: Final = 0x02
    MOVE_IMMEDIATE: Final = 0x03
    MOVE_TABLE: Final = 0x04
    MOVE_TABLE_IMMEDIATE: Final = 0x05
    MOVE_REL: Final = 0x06
    MOVE_TABLE_REL: Final = 0x08
    SPEED: Final = 0x10
    SPEED_IMMEDIATE: Final = 0x11
    STOP_FAST: Final = 0x18
    STOP_NO_RAMP: Final = 0x19
    TORQ: Final = 0x1C
    TORQ_IMM: Final = 0x1D
    START_REFERENCING: Final = 0x20
    SET_ACC_MODE: Final = 0x21
    SET_ACC: Final = 0x22
    SET_ACC_PARAM_UP: Final = 0x23
    SET_ACC_PARAM_DOWN: Final = 0x24
    SET_VELOCITY: Final = 0x25
    SET_VELOCITY_TARGET: Final = 0x2B
    SET_ACTUALPOSITION: Final = 0x2E
    SET_ACTUALPOSITION_ZERO: Final = 0x2F
    SET_CURRENT: Final = 0x39


class RC:
    """Mailbox return codes (Status_Mbx bits 0..6, wago.md §3.7)."""

    OK: Final = 0x00
    GENERAL_ERROR: Final = 0x01
    STILL_EXECUTING: Final = 0x11
    NOT_ACCEPTED: Final = 0x12
    UNKNOWN_COMMAND: Final = 0x13
    ACCESS_DENIED: Final = 0x23
