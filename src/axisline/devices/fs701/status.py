"""FS701 process values, status words, errors 00..05 and the LED model; `StatusImage`.

Source: manual §4.4 and §11 "Process Data" (0x0800..0x081F), §11 "Errors" and "Status of
Commands, Outputs and Errors" (0x0B00..0x0B05), §6 "Error messages", §5 "Function of the LED
indicators"; spec fs701.md §3.11, §3.12, §5.1, §5.2.

`StatusImage` is the one object the device writes and the protocols read: the 32 process
values, the hardware / serial / CAN command words, the output word and the error word. It
also holds the error behaviour of §6 (which errors stop the machine, which only show, what
clears them, which come back while their cause persists) and computes the LED pattern.

Decisions (spec line -> choice -> why):

* spec §5.1 Error 00 "appears in the display only but will not stop the carriage. It can
  only be reset by cycling the power supply": error bit 0 of 0x0B05 is set, but neither
  output "Error" nor the flashing LEDs (a display-only message); only `power_cycle` clears it
  (and it comes back if the DPRAM fault persists).
* spec §5.1 Error 01 "reset automatically when the power supply voltage recovers": it clears
  itself when the device reports the cause gone (`set_error_cause(1, False)`); Clear Error
  and Control Enable OFF clear it too but it returns at once while the voltage is low
  ("the unit will immediately return to the error state if the cause ... has not been
  eliminated"). It stops the machine like errors 02..05 (the manual makes no exception).
* Errors 02..05 stop the machine "after termination of the current cut", set output Error,
  make all LEDs flash; cleared by Clear Error (rising edge), Control Enable OFF, the Reset
  button or a power cycle. Errors with a persistent cause (05: the encoder ratio) return at
  once when cleared while the cause persists; event errors (02, 03, 04) stay cleared.
* "Output Error" (bit 7 of 0x0B04) is owned by the status image: it is the OR of the errors
  that set it (01..05); the device cannot set or clear it by writing the output word.
* spec §3.11 / §8 item 10 "process values #11, #25-#28, #31": the manual's §4.4 / §11 rows
  #11 and #25..#28 are blank (no name, unit or explanation) and its process-data screenshot
  shows every value as "+0000000": they are unused slots of this firmware. They exist (the LCD
  "Variable Nr." accepts 00..31, spec §5.4), are read only and always read 0; a commissioning
  engineer who selects one on the LCD sees 0, not a made-up quantity. The §8.2 LCD screenshot
  labels Nr. 25 "Tension Value" and Nr. 26 "actual Speed": that is the operator software's
  generic LCD-definition dialog (the FS701 has no tension input and its speed is #2) and is not
  adopted. Test: test_unnamed_process_values_read_zero_and_are_read_only.
* spec §3.11 #31 "Test Counter" (named, no explanation): the command with the same number,
  bit 31 "Test Program", is the only "Test" function of the unit, so #31 counts the up/down
  cycles the Test program (the §7.4 "Cycle" function: the drive ramps up and down
  continuously) has completed since it was last entered; entering it resets the counter to 0,
  leaving it keeps the last count; it is 0 after power-up. Tests:
  test_test_counter_counts_the_test_program_cycles, test_serial_test_program_runs_the_cycle_test.
* Control State / Cut State codes are the cut cycle's (spec [GAP]).
* Process values are 32-bit signed in the unit's registers (7 digits and a sign on the
  screen); `set_process_value` refuses anything outside -2**31..2**31-1 instead of wrapping,
  so a device bug shows up. "Read Batch Count" / "Read Waste Count" (#14/#15) are read by the
  register map from the counters 0x0170/0x0171 (10 digits), never from here.
* spec §5.2 [GAP] the LED error scale figure is missing. Model: 6 LEDs, the centre between LED3
  and LED4; error 0 lights LED3+LED4; a lag (positive error, carriage behind the line) lights
  the right side, a lead the left side: |e| <= 8 -> LED4 / LED3, <= 32 -> LED5 / LED2, beyond ->
  LED6 / LED1. 8 is the §7.3 "swings around zero (e.g. +/-8)" of a good analogue gain (centre
  LEDs only); 32 is the §7.5 "position error should not exceed values like 30 and the LEDs
  should remain in the centre area" (4 centre LEDs); beyond lights an extreme LED ("the
  controller is not adjusted well"). The thresholds are a parameter (`LedScale`).
* "all LEDs start to flash at a frequency of approx. 1 Hz": 1 Hz, 50 % duty, ON in the first
  half of each second of device time, for errors that set output Error.
"""

from __future__ import annotations

from typing import Final

from collections.abc import Mapping
from dataclasses import dataclass, field

from .io_assign import OUTPUT_SIGNALS, SERIAL_COMMAND_MASK, output_signal

__all__ = [
    "ProcessValue",
    "PROCESS_VALUES",
    "PROCESS_VALUES_BY_CODE",
    "process_value",
    "PROCESS_BASE",
    "StatusWord",
    "STATUS_WORDS",
    "STATUS_WORDS_BY_CODE",
    "ClearReason",
    "ErrorDef",
    "ERRORS",
    "ERROR_OUTPUT_BIT",
    "WARNING_SIGNALS",
    "LED_COUNT",
    "LED_FLASH_HZ",
    "LedScale",
    "led_pattern",
    "StatusError",
    "StatusImage",
]

PROCESS_BASE = 0x0800
INT32_MIN, INT32_MAX = -(2**31), 2**31 - 1


class StatusError(ValueError):
    """A process value, error number or word the status image does not accept."""


@dataclass(frozen=True, slots=True)
class ProcessValue:
    number: int  # 0..31 (the "Variable Nr." of the MC720 LCD, §8.2)
    name: str
    attr: str
    unit: str
    explanation: str
    aliases: tuple[str, ...] = ()

    @property
    def code(self) -> int:
        return PROCESS_BASE + self.number

    @property
    def reserved(self) -> bool:
        return self.name.startswith("(")


def _pv(number: int, name: str, attr: str, unit: str, text: str, aliases: tuple[str, ...] = ()) -> ProcessValue:
    return ProcessValue(number, name, attr, unit, text, aliases)


# fmt: off
PROCESS_VALUES: tuple[ProcessValue, ...] = (
    _pv(0, "Length Counter", "length_counter", "Incr.", "Material length counter (line encoder)."),
    _pv(1, "Master Frequency", "master_frequency", "Hz", "Frequency of the line encoder.", ("master_freq",)),
    _pv(2, "Line Speed", "line_speed", "LU/min", "Line speed."),
    _pv(3, "Position Error", "position_error", "Incr.",
        "Actual carriage position error (+: carriage lags the line, -: leads)."),
    _pv(4, "Feed Forw. Value", "feed_forw_value", "", "Internal value for the feed-forward set point."),
    _pv(5, "Correction Value", "correction_value", "", "Proportional correction set point."),
    _pv(6, "Integral Value", "integral_value", "", "Integral correction set point."),
    _pv(7, "Carriage Cut Pos", "carriage_cut_pos", "Incr.",
        "Carriage position counter during the cut cycle (related to home position)."),
    _pv(8, "Car. travel dist.", "car_travel_dist", "Incr.", "Carriage travel distance during the cut cycle."),
    _pv(9, "Carriage Abs.Pos", "carriage_abs_pos", "Incr.",
        "Carriage absolute position counter (related to zero position)."),
    _pv(10, "Act. Cut Length", "act_cut_length", "Incr.", "Actual cutting length."),
    _pv(11, "(Value 11)", "value_11", "", "Not named in the manual; reads 0."),
    _pv(12, "Min. Pos. Error", "min_pos_error", "Incr.",
        "Minimum carriage position error between 'Ready to cut' and 'Cut completed'."),
    _pv(13, "Max. Pos. Error", "max_pos_error", "Incr.",
        "Maximum carriage position error between 'Ready to cut' and 'Cut completed'."),
    _pv(14, "Read Batch Count", "read_batch_count", "", "Batch counter value (read only; = register 0x0170)."),
    _pv(15, "Read Waste Count", "read_waste_count", "", "Waste counter value (read only; = register 0x0171)."),
    _pv(16, "Length Cou. Sheet", "length_cou_sheet", "Incr.", "Length counter within one sheet."),
    _pv(17, "Prm. Delay Length", "prm_delay_length", "Incr.", "Delay of the print-mark sensor converted to length."),
    _pv(18, "Printm. Pos. Cou.", "printm_pos_cou", "Incr.", "Counter for the print-mark position."),
    _pv(19, "Miss. Printm. Cou.", "miss_printm_cou", "", "Counter for missing print marks."),
    _pv(20, "Printmark Status", "printmark_status", "", "State of print-mark operation."),
    _pv(21, "Virt. Printmarks", "virt_printmarks", "", "Number of virtual print marks."),
    _pv(22, "Ptr. Write Printm.", "ptr_write_printm", "", "Pointer for writing a print mark to the buffer."),
    _pv(23, "Ptr. Read Printm.", "ptr_read_printm", "", "Pointer for reading a print mark from the buffer."),
    _pv(24, "Printmark Buffer", "printmark_buffer", "", "Print-mark buffer."),
    *(_pv(n, f"(Value {n})", f"value_{n}", "", "Not named in the manual; reads 0.") for n in range(25, 29)),
    _pv(29, "Control State", "control_state", "", "Actual state of the controller (codes: cut cycle)."),
    _pv(30, "Cut State", "cut_state", "", "Actual state of the cut cycle (codes: cut cycle)."),
    _pv(31, "Test Counter", "test_counter", "", "Test counter (no meaning given)."),
)
# fmt: on

PROCESS_VALUES_BY_CODE: dict[int, ProcessValue] = {v.code: v for v in PROCESS_VALUES}
_PV_BY_NAME: dict[str, ProcessValue] = {}
for _v in PROCESS_VALUES:
    for _n in (_v.attr, *_v.aliases):
        _PV_BY_NAME[_n] = _v
#: process values the register map serves from the counters, not from the image
COUNTER_MIRRORS: dict[int, int] = {0x080E: 0x0170, 0x080F: 0x0171}


def process_value(key: "str | int") -> ProcessValue:
    """Process value by attribute name, serial code (0x0800..0x081F) or number (0..31)."""
    if isinstance(key, int) and not isinstance(key, bool):
        pv = PROCESS_VALUES_BY_CODE.get(key) or (PROCESS_VALUES[key] if 0 <= key < 32 else None)
    else:
        pv = _PV_BY_NAME.get(key)  # type: ignore[arg-type]
    if pv is None:
        raise StatusError(f"no FS701 process value {key!r} (codes 0x0800..0x081F)")
    return pv


@dataclass(frozen=True, slots=True)
class StatusWord:
    code: int
    name: str
    attr: str
    bits: str  # "commands", "outputs" or "errors"
    serial_writable: bool
    description: str


STATUS_WORDS: tuple[StatusWord, ...] = (
    StatusWord(0x0B00, "Hardware Commands", "hardware_commands", "commands", False,
               "Functions switched by the hardware inputs X6 'Cont.In' (after the assignment)."),
    StatusWord(0x0B01, "Serial Commands", "serial_commands", "commands", True,
               "Functions switched by the serial link (bit n = single command 0x0900+n)."),
    StatusWord(0x0B02, "CAN Commands", "can_commands", "commands", False, "Functions switched by CAN."),
    StatusWord(0x0B03, "All Commands", "all_commands", "commands", False,
               "Effective functions: Hardware OR Serial OR CAN."),
    StatusWord(0x0B04, "Output Status", "output_status", "outputs", False, "Output signals (bit n = 0x0A00+n)."),
    StatusWord(0x0B05, "Error Status", "error_status", "errors", False, "Errors 00..05 (bit n = error n)."),
)  # fmt: skip
STATUS_WORDS_BY_CODE: dict[int, StatusWord] = {w.code: w for w in STATUS_WORDS}


class ClearReason:
    CLEAR_ERROR: Final = "clear_error"  # rising edge of input "Clear Error"
    CONTROL_ENABLE_OFF: Final = "control_enable_off"
    RESET_BUTTON: Final = "reset_button"
    POWER_CYCLE: Final = "power_cycle"
    ALL: Final = frozenset({CLEAR_ERROR, CONTROL_ENABLE_OFF, RESET_BUTTON, POWER_CYCLE})


_STANDARD = ClearReason.ALL


@dataclass(frozen=True, slots=True)
class ErrorDef:
    number: int  # = bit of 0x0B05
    name: str
    message: str  # what the PC software shows ("Error 02: Cut not possible")
    cause: str
    stops_machine: bool  # carriage stays in closed-loop standstill after the current cut
    sets_error_output: bool  # output "Error" and flashing LEDs
    cleared_by: frozenset[str] = field(default=_STANDARD)
    self_clearing: bool = False  # clears when the cause goes away
    severity: str = "error"  # "error" or "display" (display-only message)

    @property
    def bit(self) -> int:
        return self.number

    @property
    def mask(self) -> int:
        return 1 << self.number


ERRORS: dict[int, ErrorDef] = {
    e.number: e
    for e in (
        ErrorDef(0, "DPRAM Error", "Error 00: DPRAM Error",
                 "Check of the internal dual-port RAM failed; no CAN communication while it exists.",
                 stops_machine=False, sets_error_output=False,
                 cleared_by=frozenset({ClearReason.POWER_CYCLE}), severity="display"),
        ErrorDef(1, "Power Low", "Error 01: Power Low", "The power supply voltage is too low.",
                 stops_machine=True, sets_error_output=True, self_clearing=True),
        ErrorDef(2, "Cut not possible", "Error 02: Cut not possible",
                 "The carriage should start forward before it has fully returned home from the previous cut "
                 "(too short cutting length at too high line speed).",
                 stops_machine=True, sets_error_output=True),
        ErrorDef(3, "Limit switch", "Error 03: Limit Switch",
                 "The rear software limit switch (Minimum Position) was touched in automatic operation.",
                 stops_machine=True, sets_error_output=True),
        ErrorDef(4, "Printmark buffer", "Error 04: Printmark Buffer",
                 "Print-mark buffer overflow: too many marks between the sensor and the carriage home position.",
                 stops_machine=True, sets_error_output=True),
        ErrorDef(5, "Value Range Exceed", "Error 05: Val. Range exceed",
                 "The line : carriage encoder pulse ratio is outside the permitted range (beyond 16:1 / 1:16).",
                 stops_machine=True, sets_error_output=True),
    )
}  # fmt: skip
ERROR_OUTPUT_BIT = output_signal("error").mask
#: outputs that warn without stopping the machine or raising an error
WARNING_SIGNALS: tuple[str, ...] = ("alarm", "master_reverse", "no_printmark", "max_correction")

# ---- LEDs ------------------------------------------------------------------------------------
LED_COUNT = 6
LED_FLASH_HZ = 1.0


@dataclass(frozen=True, slots=True)
class LedScale:
    """Position-error thresholds (carriage increments) of the LED bar (spec §5.2 [GAP])."""

    inner: int = 8  # up to this: LED3 / LED4
    outer: int = 32  # up to this: LED2 / LED5; beyond: LED1 / LED6

    def __post_init__(self) -> None:
        if not 0 < self.inner < self.outer:
            raise StatusError(f"LED scale needs 0 < inner < outer, got {self.inner}, {self.outer}")


def led_pattern(
    led_function: int,
    *,
    hardware_outputs: int = 0,
    position_error: int = 0,
    flashing: bool = False,
    time_s: float = 0.0,
    scale: LedScale = LedScale(),
) -> tuple[bool, ...]:
    """The 6 LEDs, left to right (§5).

    flashing (an error that sets output Error): all LEDs at 1 Hz, independent of LED Function.
    LED Function 0: hardware outputs Out1..Out6 (bit 0 = Out1 = leftmost).
    LED Function 1: position error bar (see LedScale).
    """
    if flashing:
        on = (time_s * LED_FLASH_HZ) % 1.0 < 0.5
        return (on,) * LED_COUNT
    if led_function == 0:
        return tuple(bool(hardware_outputs >> i & 1) for i in range(LED_COUNT))
    if led_function != 1:
        raise StatusError(f"LED Function {led_function!r} is not 0 or 1")
    e = position_error
    leds = [False] * LED_COUNT
    if e == 0:
        leds[2] = leds[3] = True
    else:
        mag = abs(e)
        step = 0 if mag <= scale.inner else 1 if mag <= scale.outer else 2
        leds[3 + step if e > 0 else 2 - step] = True
    return tuple(leds)


# ---- the image -------------------------------------------------------------------------------


def _check_word(value: int, bits: int, what: str) -> int:
    if isinstance(value, bool) or not isinstance(value, int) or not 0 <= value < 1 << bits:
        raise StatusError(f"{what} {value!r} is not a {bits}-bit unsigned word")
    return value


class StatusImage:
    """Process values and status words of one FS701; the device writes, protocols read."""

    __slots__ = ("_process", "hardware_commands", "_serial", "can_commands", "_outputs", "_errors", "_causes")

    def __init__(self) -> None:
        self._process: dict[int, int] = {v.code: 0 for v in PROCESS_VALUES}
        self.hardware_commands = 0  # 0x0B00 (device: IOAssignment.hardware_command_word)
        self._serial = 0  # 0x0B01
        self.can_commands = 0  # 0x0B02
        self._outputs = 0  # device-written signals (bit 7 is owned by the error logic)
        self._errors = 0  # 0x0B05
        self._causes = 0  # errors whose cause is present now

    # ---- process values ---------------------------------------------------------------------
    # (values typed `object`: a wrong type gets StatusError, also when compiled)
    def set_process_value(self, key: "str | int", value: object) -> None:
        pv = process_value(key)
        if pv.code in COUNTER_MIRRORS:
            raise StatusError(f"{pv.name} (0x{pv.code:04X}) mirrors register 0x{COUNTER_MIRRORS[pv.code]:04X}; set the counter")
        if pv.reserved:
            raise StatusError(f"process value 0x{pv.code:04X} is reserved (reads 0)")
        if isinstance(value, bool) or not isinstance(value, int) or not INT32_MIN <= value <= INT32_MAX:
            raise StatusError(f"{pv.name} (0x{pv.code:04X}): {value!r} is not a 32-bit signed integer")
        self._process[pv.code] = value

    def update_process_values(self, values: Mapping["str | int", object]) -> None:
        """Several values at once; all are checked first."""
        probe = StatusImage()
        for k, v in values.items():
            probe.set_process_value(k, v)
        for k in values:  # the checked values, from the probe
            code = process_value(k).code
            self._process[code] = probe._process[code]

    def process_value(self, key: "str | int") -> int:
        return self._process[process_value(key).code]

    # ---- command words ----------------------------------------------------------------------
    @property
    def serial_commands(self) -> int:
        return self._serial

    @serial_commands.setter
    def serial_commands(self, word: int) -> None:
        _check_word(word, 32, "Serial Commands")
        if word & ~SERIAL_COMMAND_MASK:
            raise StatusError(f"Serial Commands 0x{word:08X}: bit 14 (Print Mark) has no serial command")
        self._serial = word

    @property
    def all_commands(self) -> int:
        """0x0B03: the OR of hardware, serial and CAN commands (§4.1.1)."""
        return self.hardware_commands | self._serial | self.can_commands

    def command(self, bit: int) -> bool:
        return bool(self.all_commands >> bit & 1)

    # ---- outputs ----------------------------------------------------------------------------
    @property
    def output_status(self) -> int:
        """0x0B04; bit 7 "Error" is the OR of the active errors that set it."""
        err = ERROR_OUTPUT_BIT if self.error_output else 0
        return (self._outputs & ~ERROR_OUTPUT_BIT) | err

    def set_outputs(self, word: int) -> None:
        """The device's output signals (bit 7 is ignored: the error logic owns it)."""
        self._outputs = _check_word(word, 32, "Output Status")

    def set_output(self, signal: "str | int", on: bool) -> None:
        s = output_signal(signal)
        self._outputs = (self._outputs | s.mask) if on else (self._outputs & ~s.mask)

    def output(self, signal: "str | int") -> bool:
        return bool(self.output_status & output_signal(signal).mask)

    # ---- errors (§6) ------------------------------------------------------------------------
    @property
    def error_status(self) -> int:
        return self._errors

    @staticmethod
    def _error(number: int) -> ErrorDef:
        try:
            return ERRORS[number]
        except (KeyError, TypeError):
            raise StatusError(f"no FS701 error {number!r} (errors 00..05)") from None

    def raise_error(self, number: int) -> None:
        """An error event (02 cut not possible, 03 limit switch, 04 buffer overflow, ...)."""
        self._errors |= self._error(number).mask

    def set_error_cause(self, number: int, present: bool) -> None:
        """A persistent cause (00 DPRAM, 01 supply voltage, 05 encoder ratio) appears or goes.

        Present: the error is set. Gone: a self-clearing error (01) clears; the others stay
        latched until cleared.
        """
        e = self._error(number)
        if present:
            self._causes |= e.mask
            self._errors |= e.mask
        else:
            self._causes &= ~e.mask
            if e.self_clearing:
                self._errors &= ~e.mask

    def clear_errors(self, reason: str = ClearReason.CLEAR_ERROR) -> list[int]:
        """Clear what `reason` clears; errors whose cause persists return at once.

        Returns the numbers that are cleared afterwards (were set before and are not now).
        """
        if reason not in ClearReason.ALL:
            raise StatusError(f"unknown clear reason {reason!r} (one of {sorted(ClearReason.ALL)})")
        before = self._errors
        for e in ERRORS.values():
            if reason in e.cleared_by:
                self._errors &= ~e.mask
        self._errors |= self._causes  # "will immediately return to the error state" (§6)
        return [n for n, e in ERRORS.items() if before & e.mask and not self._errors & e.mask]

    def active_errors(self) -> list[ErrorDef]:
        return [e for e in ERRORS.values() if self._errors & e.mask]

    @property
    def error_output(self) -> bool:
        """Output "Error": an error that sets it is active."""
        return any(e.sets_error_output for e in self.active_errors())

    @property
    def stop_requested(self) -> bool:
        """An active error stops the machine after the current cut."""
        return any(e.stops_machine for e in self.active_errors())

    def error_messages(self) -> list[str]:
        return [e.message for e in self.active_errors()]

    # ---- LEDs -------------------------------------------------------------------------------
    def leds(self, led_function: int, *, hardware_outputs: int = 0, time_s: float = 0.0,
             scale: LedScale = LedScale()) -> tuple[bool, ...]:  # fmt: skip
        return led_pattern(
            led_function,
            hardware_outputs=hardware_outputs,
            position_error=self._process[PROCESS_BASE + 3],
            flashing=self.error_output,
            time_s=time_s,
            scale=scale,
        )

    # ---- power ------------------------------------------------------------------------------
    def power_cycle(self) -> None:
        """Power off and on: words and values 0, errors cleared; present causes return."""
        for code in self._process:
            self._process[code] = 0
        self.hardware_commands = self._serial = self.can_commands = self._outputs = 0
        self.clear_errors(ClearReason.POWER_CYCLE)

    # ---- views ------------------------------------------------------------------------------
    def word(self, code: int) -> int:
        """A status word by serial code 0x0B00..0x0B05."""
        if code == 0x0B00:
            return self.hardware_commands
        if code == 0x0B01:
            return self._serial
        if code == 0x0B02:
            return self.can_commands
        if code == 0x0B03:
            return self.all_commands
        if code == 0x0B04:
            return self.output_status
        if code == 0x0B05:
            return self._errors
        raise StatusError(f"no status word at 0x{code:04X} (0x0B00..0x0B05)")

    def snapshot(self) -> dict[str, object]:
        """Plain data for the HMI / run report."""
        return {
            "process": {v.attr: self._process[v.code] for v in PROCESS_VALUES if not v.reserved},
            "hardware_commands": self.hardware_commands,
            "serial_commands": self._serial,
            "can_commands": self.can_commands,
            "all_commands": self.all_commands,
            "output_status": self.output_status,
            "error_status": self._errors,
            "errors": self.error_messages(),
            "outputs_on": [s.attr for s in OUTPUT_SIGNALS if self.output_status & s.mask],
        }
