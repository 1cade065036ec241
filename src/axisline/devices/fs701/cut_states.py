"""The FS701's cut-cycle states, cut kinds and error numbers, and the constants of the cut
cycle (cutter.py describes the cycle and its decisions).
"""

from __future__ import annotations

from enum import IntEnum
from typing import Final

# Final: compiled, the numbers are built into the modules that use them (no lookup per use)
__all__ = ["ACC_WINDOW", "RETURN_REPLAN_FRACTION", "RETURN_TARGET_FRACTION", "S_RAMP_PEAK_FACTOR", "ControlState", "CutKind", "CutState", "FS701Error"]

S_RAMP_PEAK_FACTOR: Final = 1.25
"""Manual §4.3.1: S-ramps reach 1.25 x the (linear) acceleration setting at their steepest point."""
_S_JERK_FRACTION: Final = 0.2  # jerk phase / ramp time: peak/mean = 1/(1 - 0.2) = 1.25
_BIG: Final = 1e15  # a speed limit that never binds
_V_EPS: Final = 1e-9  # LU/s: below this the line stands
# s: the window of the line-acceleration estimate (LineMaster.acceleration): its count noise
# times a feed-forward lead of a few ms stays below the 1 ms speed measurement's own, and it
# follows a change of the line's ramp within 2 windows
ACC_WINDOW: Final = 0.008
RETURN_TARGET_FRACTION: Final = 0.75
"""C4: the return is planned to end within this fraction of the time left to the next start."""
RETURN_REPLAN_FRACTION: Final = 0.9
"""C4: the return is re-planned faster when its predicted end passes this fraction."""


class FS701Error(IntEnum):
    """Error numbers = bits of the Error Status register 0x0B05 (manual §6, §11)."""

    DPRAM = 0
    POWER_LOW = 1
    CUT_NOT_POSSIBLE = 2
    LIMIT_SWITCH = 3
    PRINTMARK_BUFFER = 4
    VALUE_RANGE = 5


class ControlState(IntEnum):
    """Process value #29 "Control State" (codes not in the manual [GAP]: chosen here)."""

    DISABLED = 0
    STOP = 1  # Start/Stop LOW: holding home, jog / immediate cut
    AUTOMATIC = 2
    ERROR = 3


class CutState(IntEnum):
    """Process value #30 "Cut State" (codes not in the manual [GAP]: chosen here)."""

    IDLE = 0  # disabled
    HOME = 1  # holding at home, waiting for the start point
    ACCELERATION = 2
    SYNCHRONOUS = 3  # synchronous, Synchron Time / Cut Window running
    READY_TO_CUT = 4
    GAP = 5
    GAP_COMPLETED = 6
    DECELERATION = 7
    RETURN = 8
    JOG = 9


#: the states in which the carriage runs synchronous with the blade down or coming (Ready to Cut)
# (a tuple: `in` on a set would call Enum.__hash__, a Python function, every cycle)
_SYNC_STATES: Final = (CutState.READY_TO_CUT, CutState.GAP, CutState.GAP_COMPLETED)
# states of the carriage outside a cut cycle (standing or jogging, or disabled)
_OUT_OF_CYCLE: Final = (CutState.HOME, CutState.JOG, CutState.IDLE)


class CutKind(IntEnum):
    NORMAL = 0  # Cutting Length (length mode)
    TEST = 1  # Test Cut. Length (waste)
    IMMEDIATE = 2  # Immediate Cut (waste)
    LATE = 3  # first cut after Start/Clear Error whose start point had passed (waste, C9)
    PRINTMARK = 4  # cut to a print mark
    VIRTUAL = 5  # virtual print mark (start) or substitute for a missing mark
    ADDITIONAL = 6  # additional cut (Cutting Mode 3)


_WASTE: Final = (CutKind.TEST, CutKind.IMMEDIATE, CutKind.LATE)
