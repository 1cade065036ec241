"""CiA 402 words both sides of the bus use: controlword commands, statusword states, error texts.

The state names and statusword masks are canopen's own (canopen.profiles.p402.State402); this
module adds what canopen leaves out: decoding a controlword into the command a drive acts on
(the simulated drive needs it), the statusword a drive reports in each state, the CiA 402
objects axisline maps, and the texts of the error codes a drive reports in EMCY / 0x603F.
"""

from __future__ import annotations

from canopen.emcy import EmcyError
from canopen.profiles.p402 import OperationMode, State402

__all__ = [
    "CSP",
    "PV",
    "HOMING",
    "CW_HOMING_START",
    "SW_HOMING_ATTAINED",
    "SW_HOMING_ERROR",
    "SW_TARGET_REACHED",
    "CW_SHUTDOWN",
    "CW_SWITCH_ON",
    "CW_ENABLE_OPERATION",
    "CW_DISABLE_VOLTAGE",
    "CW_QUICK_STOP",
    "CW_FAULT_RESET",
    "HEARTBEAT_ERROR",
    "FOLLOWING_ERROR",
    "command_of",
    "error_text",
    "state_of",
    "statusword_of",
]

CSP = OperationMode.CYCLIC_SYNCHRONOUS_POSITION  # 8
PV = OperationMode.PROFILED_VELOCITY  # 3
HOMING = OperationMode.HOMING  # 6

# homing mode: controlword bit 4 starts it (rising edge); statusword bits 12 / 13 report it
CW_HOMING_START = 0x10
SW_HOMING_ATTAINED = 0x1000
SW_HOMING_ERROR = 0x2000
SW_TARGET_REACHED = 0x0400

# controlword (0x6040) commands, CiA 402 table "device control commands"
CW_SHUTDOWN = State402.CW_SHUTDOWN  # 0x06: -> READY TO SWITCH ON
CW_SWITCH_ON = State402.CW_SWITCH_ON  # 0x07: -> SWITCHED ON
CW_ENABLE_OPERATION = State402.CW_OPERATION_ENABLED  # 0x0F: -> OPERATION ENABLED (3 + 4 from READY)
CW_DISABLE_VOLTAGE = State402.CW_DISABLE_VOLTAGE  # 0x00: -> SWITCH ON DISABLED
CW_QUICK_STOP = State402.CW_QUICK_STOP  # 0x02: -> QUICK STOP ACTIVE
CW_FAULT_RESET = 0x80  # bit 7, acted on at its rising edge: FAULT -> SWITCH ON DISABLED

# error codes (CiA 301 / CiA 402) axisline itself raises
HEARTBEAT_ERROR = 0x8130  # "life guard error or heartbeat error"
FOLLOWING_ERROR = 0x8611  # "following error" (the drive's 0x6065 window)

# statusword of each state: the low bits of canopen's masks plus "voltage enabled" (bit 4)
# where the power stage is on, and "quick stop" (bit 5) set outside QUICK STOP ACTIVE
_STATUSWORD = {
    "NOT READY TO SWITCH ON": 0x0000,
    "SWITCH ON DISABLED": 0x0040,
    "READY TO SWITCH ON": 0x0021,
    "SWITCHED ON": 0x0033,
    "OPERATION ENABLED": 0x0037,
    "QUICK STOP ACTIVE": 0x0017,
    "FAULT REACTION ACTIVE": 0x000F,
    "FAULT": 0x0008,
}

# texts of common drive error codes (CiA 402 annex, error code table); others fall back to
# canopen's class text ("Current", "Monitoring", ...)
_ERROR_TEXTS = {
    0x2310: "continuous over-current",
    0x2320: "short circuit / earth leakage",
    0x3210: "DC link over-voltage",
    0x3220: "DC link under-voltage",
    0x4210: "excess temperature device",
    0x4310: "excess temperature drive",
    0x5441: "drive inhibited (STO / enable input)",
    0x7305: "incremental sensor 1 fault",
    0x7310: "speed sensor fault",
    0x8130: "heartbeat lost",
    0x8400: "velocity speed controller",
    0x8611: "following error",
    0xFF00: "manufacturer-specific error",
}


def state_of(statusword: int) -> str:
    """The CiA 402 state a statusword reports (canopen's masks)."""
    for state, (mask, value) in State402.SW_MASK.items():
        if statusword & mask == value:
            return state
    return "UNKNOWN"


def statusword_of(state: str) -> int:
    """The statusword a drive reports in `state` (state bits only)."""
    return _STATUSWORD[state]


def command_of(controlword: int) -> str:
    """The device control command a controlword carries (fault reset is bit 7, see above).

    Returns one of "disable voltage", "quick stop", "shutdown", "switch on",
    "enable operation" (CiA 402, "device control commands"; x = don't care)."""
    if not controlword & 0x02:  # enable voltage = 0
        return "disable voltage"
    if not controlword & 0x04:  # quick stop bit is active low
        return "quick stop"
    if not controlword & 0x01:
        return "shutdown"
    if not controlword & 0x08:
        return "switch on"
    return "enable operation"


def error_text(code: int) -> str:
    """A drive error code in words: "0x2310 continuous over-current"."""
    text = _ERROR_TEXTS.get(code)
    if text is None:
        text = EmcyError(code, 0, b"", 0.0).get_desc().lower() or "error"
    return f"0x{code:04X} {text}"
