"""Errors, warnings, the single error memory and the LEDs of the 750-672 (manual §3.12, §4.4; wago.md §8, §1.7).

Every code of the manual's table §4.4.7 is here as data (`ERRORS`): code, designation,
description, cause/solution and its class, which the first digit gives (§4.4.1-4.4.4):

* 1111..1999 ACKNOWLEDGE: cleared by a rising edge of Error_Quit (or DIAG_QUIT_ERROR) once
  the cause is gone;
* 2111..2999 WARM_START: only a warm start of the module clears them (Reset bit follows);
* 3111..3999 FATAL: the module stops; only switching it off and on clears them;
* 5111..5999 WARNING: only signalled (Warning bit), no error state, no stop.

"The module has an error memory that can record exactly one error code" (§3.12.1): the
first error is kept until it is acknowledged (wago.md §8.1 [AMBIGUOUS], recommended
reading); later errors are not recorded while it is held. Warnings have their own slot,
since the Warning bit (S3.6) is separate from Error (S2.7).

An error may carry a `cause`: a callable that says whether the condition is still there
(Error_Set bit still 1, overcurrent still integrating, ...). "If the cause of the error is
not eliminated, the bit Error is set again" (§3.12.2): an acknowledge keeps such an error.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from enum import Enum

from axisline.devices.wago672.error_table import TABLE

__all__ = [
    "ErrorClass",
    "ErrorCode",
    "ERRORS",
    "WagoError",
    "error_class",
    "describe",
    "ErrorMemory",
    "err_flag",
    "blink_sequence",
    "blink_signal",
]


class ErrorClass(Enum):
    ACKNOWLEDGE = "acknowledge"  # 1xxx
    WARM_START = "warm start"  # 2xxx
    FATAL = "fatal"  # 3xxx
    WARNING = "warning"  # 5xxx


def error_class(code: int) -> ErrorClass:
    """The class of a code from its first digit (§4.4.1-4.4.4)."""
    if isinstance(code, bool) or not isinstance(code, int) or not 1000 <= code <= 5999 or code // 1000 == 4:
        raise ValueError(f"error code must be 1111..3999 or 5111..5999, got {code!r}")
    return {1: ErrorClass.ACKNOWLEDGE, 2: ErrorClass.WARM_START, 3: ErrorClass.FATAL, 5: ErrorClass.WARNING}[code // 1000]


@dataclass(frozen=True, slots=True)
class ErrorCode:
    code: int
    name: str
    description: str
    cause: str

    @property
    def klass(self) -> ErrorClass:
        return error_class(self.code)


ERRORS: dict[int, ErrorCode] = {c: ErrorCode(c, n, d, s) for c, n, d, s in TABLE}


def describe(code: int) -> str:
    """'1413 PARTMODL_CURRENT_TIME: Time limit for overcurrent reached' (unknown codes too)."""
    e = ERRORS.get(code)
    return f"{code} {e.name}: {e.description}" if e is not None else f"{code} (not in the manual's error table)"


class WagoError(Exception):
    """A command or setting rejected with the device's error code; the message names field, value, range."""

    def __init__(self, code: int, text: str) -> None:
        super().__init__(f"{describe(code)} - {text}")
        self.code = code
        self.text = text


@dataclass(slots=True)
class _Entry:
    code: int
    extra: int
    text: str
    cause: Callable[[], bool] | None


class ErrorMemory:
    """The single error memory plus the warning slot (§3.12.1)."""

    def __init__(self) -> None:
        self._error: _Entry | None = None
        self._warning: _Entry | None = None

    # ---- read-outs
    @property
    def error(self) -> int:
        """Code of the error held (0: none) - what DIAG_RD_ERROR returns first."""
        return self._error.code if self._error is not None else 0

    @property
    def warning(self) -> int:
        return self._warning.code if self._warning is not None else 0

    @property
    def code(self) -> int:
        """DIAG_RD_ERROR: the error, else the warning, else 0."""
        return self.error or self.warning

    @property
    def extra(self) -> int:
        """Extra information of the entry `code` reports (content not specified by the manual)."""
        e = self._error or self._warning
        return e.extra if e is not None else 0

    @property
    def text(self) -> str:
        e = self._error or self._warning
        return e.text if e is not None else ""

    @property
    def error_class(self) -> ErrorClass | None:
        return error_class(self._error.code) if self._error is not None else None

    # ---- raising
    def raise_code(self, code: int, text: str = "", extra: int = 0, cause: Callable[[], bool] | None = None) -> bool:
        """Record `code`; True if it was recorded (the memory was free), False if it was held.

        Warnings (5xxx) go to the warning slot; the first warning is kept the same way.
        """
        klass = error_class(code)
        entry = _Entry(code, int(extra) & 0xFFFF, text or describe(code), cause)
        if klass is ErrorClass.WARNING:
            if self._warning is None:
                self._warning = entry
                return True
            return False
        if self._error is None:
            self._error = entry
            return True
        return False

    def acknowledge(self) -> bool:
        """Error_Quit rising edge / DIAG_QUIT_ERROR. Returns True if a warm start is due.

        1xxx errors and warnings are cleared unless their cause is still present. A 2xxx
        error asks for a warm start (the device performs it, which clears the memory);
        a 3xxx error stays until power-off.
        """
        if self._warning is not None and not (self._warning.cause is not None and self._warning.cause()):
            self._warning = None
        e = self._error
        if e is None:
            return False
        klass = error_class(e.code)
        if klass is ErrorClass.FATAL:
            return False
        if klass is ErrorClass.WARM_START:
            return True
        if e.cause is not None and e.cause():
            return False
        self._error = None
        return False

    def clear(self) -> None:
        """Warm start or power-on: the memory is empty again."""
        self._error = None
        self._warning = None

    def __repr__(self) -> str:
        return f"ErrorMemory(error={self.error}, warning={self.warning})"


def err_flag(error_mode: int, warning_mode: int, error: bool, warning: bool, error_quit: bool) -> bool:
    """S0.6 ERR (§3.7.2, §3.12.3): follows Error/Warning where bit 0 of ErrorNotificationMode
    (addr 113) / WarningNotificationMode (addr 116) enables it; "addressed continuously as long
    as the error is present and Error_Quit is not set"."""
    if error_quit:
        return False
    return bool((error_mode & 1 and error) or (warning_mode & 1 and warning))


# ---------------------------------------------------------------- LED A blink code (§4.4.5)
# The manual: a first sequence at about 10 Hz, "shortly afterward" the highest digit at about
# 2 Hz, then after a 1 s pause each the other digits down to the lowest, then repeat.
# [RECONSTRUCTED] timing: 10 Hz burst of 1 s (50 ms on / 50 ms off), 500 ms gap, digit
# blinks 250 ms on / 250 ms off, 1 s pause after each digit (the last one included).
_BURST_MS, _BURST_HALF, _GAP_MS, _DIGIT_HALF, _PAUSE_MS = 1000, 50, 500, 250, 1000


def blink_sequence(code: int) -> list[tuple[bool, int]]:
    """One period of the LED A pattern for `code` as (level, duration ms) pairs."""
    seq: list[tuple[bool, int]] = []
    for _ in range(_BURST_MS // (2 * _BURST_HALF)):
        seq += [(True, _BURST_HALF), (False, _BURST_HALF)]
    seq.append((False, _GAP_MS))
    for digit in str(int(code)):
        for _ in range(int(digit)):
            seq += [(True, _DIGIT_HALF), (False, _DIGIT_HALF)]
        seq.append((False, _PAUSE_MS))
    return seq


def blink_signal(code: int, t_ms: int) -> bool:
    """Level of LED A (bit ERR_Code) at `t_ms` since the code was raised (0: off)."""
    if not code:
        return False
    seq = blink_sequence(code)
    period = sum(d for _, d in seq)
    t = int(t_ms) % period
    for level, d in seq:
        if t < d:
            return level
        t -= d
    return False  # pragma: no cover - t < period
