"""The IDS01 decade switch on X6 (manual §7.8 L3659-3693, B002 L5018-5040, V015-V018 L1366-1369,
errors 12-15 L5327-5330 / L8418-8446; spec §4.8): a front-panel thumbwheel unit that gives the
CLM a length in IU and a velocity in %, simulated as a device on the CLM's serial port.

    [device.decade_switch]
    model = "IDS01.1-2"        # IDS01.1-2: 2 decimal places, IDS01.1-3: 3 (L3690)
    length = 123.45            # IU, as the thumbwheels show it (at most the model's decimals)
    velocity = 50              # %, two thumbwheels 00-99
    [[device.decade_switch.events]]   # the operator or the cable, at simulated times (seconds)
    at = 2.0
    length = 200.0             # and/or velocity = ..., link = "ok" | "break" | "checksum" | "format" | "too_long"

    switch = DecadeSwitch(config, cycle_us)    # the unit on the cable (plant side)
    ids = IdsReceiver(rt, switch, cycle_us)    # the CLM's side; the personality ticks it
    ids.tick(cycle)                            # once per NC cycle, before the runtime's step

What the CLM does with it: when B002's function digit selects the IDS01 (parameters.py decision
5), X6 is the decade switch's link (2400 baud, 8 bits, 1 start, 1 stop, no parity, L5034-5040)
and every good telegram loads V015-V018; in Automatic the link is monitored and a bad or missing
telegram is fault 12-15 through the runtime's fault path (`modes.ModeMachine.fault`: tasks 1, 2,
4, 5 stop, drives off, cleared by External Clear / ``!CLEAR``; while the cause lasts it comes
back at the next cycle). The unit's own wire format is not in the manual (spec §12: "its wire
format is not described"); the one below is axisline's, built so that each of the four errors
the manual names has exactly one cause a simulation can produce.

The telegram (decision 2), 12 characters, every 50 ms (12 x 10 bits at 2400 baud):

    LLLLLLVVhh CR LF     LLLLLL the six length thumbwheels, VV the two velocity ones (ASCII
                         digits, most significant first), hh the CLM checksum (telegram.checksum,
                         Fig. 9-12) over the eight digits, upper-case hex

Decisions (spec line -> choice, why)
------------------------------------
1. C-IDS-DIGITS, L1366-1369 (V015 "5 places before the decimal, 1 after", V016 4/2, V017 3/3)
   and L3690 (models with 2 or 3 decimal places): the switch has six length thumbwheels, and
   the CLM loads the same six digits d into all three variables, V015 = d / 10, V016 = d / 100,
   V017 = d / 1000: the CLM cannot know where the panel prints its decimal point, so the program
   picks the variable of its model (V016 for IDS01.1-2, as the manual's example does, V017 for
   IDS01.1-3). The machine file gives the length as the panel shows it; a length with more
   decimals than the model's, or beyond its six digits (9999.99 / 999.999), or negative is
   refused naming the key, value and range. Tests:
   ``tests/devices/clm/test_decade_switch.py::test_digits_load_v015_to_v017``,
   ``test_bad_machine_file_is_refused``.
2. C-IDS-VELOCITY, L1369 ("velocity ... multiplied by a factor of 10. The variable can be
   directly applied in a move command") and L3663 (velocity "in percent"): two velocity
   thumbwheels 00-99 %, V018 = % x 10 (0-990): per mille of Ax06 as every move command's vvv
   field takes it, and it always fits that field (a third digit would allow 100 % = 1000, fault
   32 "directly applied"). Test: ``test_manual_example_feeds_from_the_switch``.
3. C-IDS-TELEGRAM (manual silent, spec §12): the 12-character telegram above, sent back to back
   from power-on, telegram k complete at (k + 1) x 50 ms; it carries the thumbwheels as they
   are when it completes; the CLM takes it at the first NC cycle at or after that time (integer
   microseconds, no wall clock) and, if good, loads V015-V018 at once, so a change on the switch
   reaches the program within 50 ms plus one NC cycle. Tests:
   ``test_telegram_round_trip_and_its_checks``, ``test_manual_example_feeds_from_the_switch``
   (the switch changes mid-run, the next feed takes the new length), ``test_example_machine_file``.
4. C-IDS-ERRORS, L5327-5330 / L8418-8446: each bad telegram is checked in the order 15 (more
   than 10 characters before CR LF: "data string too long"), 14 (a character that is not a digit,
   a checksum that is not two hex digits, or fewer than 10 characters: "Char format"), 13 (the
   checksum does not match); 12 "Break-Error" when no good telegram arrived for 100 ms (two
   telegram times: "no transmission", L3675), also when B002 selects the IDS01 and nothing is
   connected (no ``decade_switch`` in the machine file). A bad telegram loads nothing; the
   variables keep the last good values. Tests: ``test_telegram_round_trip_and_its_checks``,
   ``test_break_is_12_in_automatic_only``, ``test_checksum_format_and_length_errors``,
   ``test_no_switch_connected_is_12``, ``test_cleared_after_the_cable_is_back``.
5. C-IDS-AUTOMATIC, L3675 ("continuous monitoring ... in Automatic Mode"): errors 12-15 are
   faults only in Automatic; in Manual (and Parameter mode) good telegrams still load the
   variables and bad ones are dropped silently. The 100 ms of decision 4 run in every mode, so
   Automatic selected after a break in Manual faults at once. Test:
   ``test_break_is_12_in_automatic_only``.
6. C-IDS-B002, L5028 / L6301: B002's function digit is read on leaving Parameter mode (and at
   power-on), as the CLM takes its parameters; with 0 (data interface) the switch is not read
   and V015-V018 stay 0 (the IDS01 on a data port is not a data host: nothing is answered to
   it). Test: ``test_switch_not_read_without_b002``.
7. C-IDS-EVENTS: the machine file's ``events`` change the thumbwheels (``length``,
   ``velocity``) or the link (``link``: ``ok``, ``break`` = no telegram, ``checksum`` /
   ``format`` / ``too_long`` = every telegram arrives with that fault) at a simulated time
   ``at`` (seconds from power-on, taken at the first NC cycle at or after it; events in the
   order of ``at``, equal times in file order). A link state holds until the next ``link``
   event: one bad telegram is ``link = "checksum"`` followed by ``link = "ok"`` 0.05 s later.
   Test: ``test_checksum_format_and_length_errors``.
8. C-IDS-SERIAL, L5028 ("the other values need not be input") and L6329 (one serial interface
   at once): with the IDS01 on X6 the protocol endpoint (``serve --serial-tcp``) is X8 when B004
   makes X8 a data interface (its B005 settings, serial.py), else the CLM has no data interface
   and the endpoint answers nothing (serial.py decision 14). Test:
   ``test_serial_endpoint_with_the_ids_on_x6``.
"""

from __future__ import annotations

import math
from decimal import Decimal, InvalidOperation
from typing import Any, Literal

from pydantic import BaseModel, ConfigDict, Field, model_validator

from .errors import ClmError
from .telegram import checksum

__all__ = [
    "BREAK_US", "DecadeSwitch", "DecadeSwitchConfig", "DecadeSwitchEvent", "IdsReceiver", "MODELS", "TELEGRAM_US",
    "config_problems", "decode", "encode", "length_digits",
]

#: model -> decimal places of its length (L3690)
MODELS = {"IDS01.1-2": 2, "IDS01.1-3": 3}
LENGTH_DIGITS = 6  # decision 1
DATA_CHARS = 10  # 8 digits + 2 checksum characters, then CR LF (decision 2)
TELEGRAM_US = 50_000  # 12 characters x 10 bits at 2400 baud (L5034-5040)
BREAK_US = 100_000  # decision 4: two telegram times without a good one
_MILLION = 1_000_000
_HEX = "0123456789ABCDEFabcdef"

Link = Literal["ok", "break", "checksum", "format", "too_long"]


class DecadeSwitchEvent(BaseModel):
    """A change at simulated time `at`: thumbwheels and/or the link (decision 7)."""

    model_config = ConfigDict(extra="forbid")

    at: float = Field(ge=0.0, le=1e6, description="seconds after power-on (simulated time)")
    length: float | None = Field(None, description="the length thumbwheels from then on (IU, the model's decimals)")
    velocity: int | None = Field(None, ge=0, le=99, description="the velocity thumbwheels from then on (%, 00-99)")
    link: Link | None = Field(
        None, description="the cable from then on: ok, break (no telegram), checksum / format / too_long (every telegram with that fault)"
    )

    @model_validator(mode="after")
    def _something(self) -> DecadeSwitchEvent:
        if self.length is None and self.velocity is None and self.link is None:
            raise ValueError("an event changes length, velocity or link")
        return self


class DecadeSwitchConfig(BaseModel):
    """``[device.decade_switch]``: the IDS01 on X6 (decade_switch.py)."""

    model_config = ConfigDict(extra="forbid")

    model: Literal["IDS01.1-2", "IDS01.1-3"] = Field(description="IDS01.1-2 (2 decimal places) or IDS01.1-3 (3), L3690")
    length: float = Field(0.0, description="the length thumbwheels at power-on, IU as the panel shows it (6 digits, the model's decimals)")
    velocity: int = Field(0, ge=0, le=99, description="the velocity thumbwheels at power-on, % (00-99); V018 = % x 10")
    events: list[DecadeSwitchEvent] = Field(default_factory=list, max_length=10_000, description="changes at simulated times (decision 7)")


def length_digits(length: float, model: str) -> int:
    """The six thumbwheel digits showing `length` on `model` (ValueError saying why not)."""
    decimals = MODELS[model]
    top = Decimal(10**LENGTH_DIGITS - 1).scaleb(-decimals)
    try:
        value = Decimal(repr(float(length)))
    except (InvalidOperation, ValueError, TypeError):
        raise ValueError("not a number") from None
    if not value.is_finite() or value < 0 or value > top:
        raise ValueError(f"the {model} shows 0 ... {top} (6 digits, {decimals} decimal places)")
    digits = value.scaleb(decimals)
    if digits != digits.to_integral_value():
        raise ValueError(f"the {model} has {decimals} decimal places (0 ... {top})")
    return int(digits)


def config_problems(config: DecadeSwitchConfig, key: str = "device.decade_switch") -> list[str]:
    """Lengths that the model cannot show (decision 1), one line each."""
    problems = []
    for where, length in [(f"{key}.length", config.length)] + [
        (f"{key}.events[{i}].length", e.length) for i, e in enumerate(config.events) if e.length is not None
    ]:
        try:
            length_digits(length, config.model)
        except ValueError as e:
            problems.append(f"{where} = {length!r}: {e}")
    return problems


def encode(digits: int, velocity: int) -> bytes:
    """The IDS01's telegram for the thumbwheels (decision 2): 123.45 and 50 % on an
    IDS01.1-2 -> ``b'012345506B\\r\\n'``."""
    data = f"{digits:06d}{velocity:02d}"
    return f"{data}{checksum(data)}\r\n".encode("ascii")


def decode(frame: bytes) -> tuple[int, int]:
    """(length digits, velocity %) of a received telegram, or ClmError 13/14/15 (decision 4)."""
    text = frame[:-2] if frame.endswith(b"\r\n") else frame
    shown = text[:16].decode("latin-1")
    if len(text) > DATA_CHARS:
        raise ClmError("15", f"IDS01 telegram {shown!r}...: {len(text)} characters before CR LF, the IDS01 sends {DATA_CHARS}")
    data, check = text[:8].decode("latin-1"), text[8:].decode("latin-1")
    bad = next((i for i, c in enumerate(data) if not "0" <= c <= "9"), None)
    if len(text) < DATA_CHARS or bad is not None or not all(c in _HEX for c in check):
        where = f"character {bad + 1} {data[bad]!r} is not a digit" if bad is not None else f"the checksum {check!r} is not two hex digits"
        if len(text) < DATA_CHARS:
            where = f"{len(text)} characters, the IDS01 sends {DATA_CHARS}"
        raise ClmError("14", f"IDS01 telegram {shown!r}: {where}")
    if check.upper() != checksum(data):
        raise ClmError("13", f"IDS01 telegram {shown!r}: checksum ${check.upper()}, the data give ${checksum(data)}")
    return int(data[:6]), int(data[6:])


class DecadeSwitch:
    """The unit on the cable: its thumbwheels, the scheduled events, the telegrams it sends."""

    def __init__(self, config: DecadeSwitchConfig, cycle_us: int) -> None:
        self.model = config.model
        self.digits = length_digits(config.length, config.model)
        self.velocity = config.velocity
        self.link: str = "ok"
        self.cycle_us = cycle_us
        # (cycle it applies at, event), in the order of `at` (stable: file order for equal times)
        self._events = [(math.ceil(e.at * 1e6 / cycle_us - 1e-9), e) for e in sorted(config.events, key=lambda e: e.at)]
        self._next = 0
        self._sent = 0  # telegrams completed so far

    @property
    def length(self) -> float:
        return self.digits / 10 ** MODELS[self.model]

    def _apply_events(self, cycle: int) -> None:
        events = self._events
        while self._next < len(events) and events[self._next][0] <= cycle:
            e = events[self._next][1]
            if e.length is not None:
                self.digits = length_digits(e.length, self.model)
            if e.velocity is not None:
                self.velocity = e.velocity
            if e.link is not None:
                self.link = e.link
            self._next += 1

    def frames(self, cycle: int) -> list[bytes]:
        """The telegrams that completed by NC cycle `cycle` since the last call (decision 3)."""
        self._apply_events(cycle)
        done = cycle * self.cycle_us // TELEGRAM_US
        count, self._sent = min(done - self._sent, 2), done  # (a long pause: the last two matter)
        if count <= 0 or self.link == "break":
            return []
        return [self._frame() for _ in range(count)]

    def _frame(self) -> bytes:
        frame = encode(self.digits, self.velocity)
        if self.link == "checksum":  # the last checksum character off by one
            last = frame[9:10]
            return frame[:9] + (b"1" if last == b"0" else b"0") + b"\r\n"
        if self.link == "format":  # a disturbed bit: the third digit arrives as a letter
            return frame[:2] + bytes([frame[2] | 0x40]) + frame[3:]
        if self.link == "too_long":  # a character too many before CR LF
            return frame[:10] + b"0\r\n"
        return frame


class IdsReceiver:
    """The CLM's side of the link: V015-V018 and the monitoring (decisions 1-6)."""

    def __init__(self, rt: Any, switch: DecadeSwitch | None, cycle_us: int) -> None:
        self.rt = rt
        self.switch = switch
        self.cycle_us = cycle_us
        self.enabled = False
        self._mode: str | None = None
        self._last_good = 0  # the cycle of the last good telegram (or of enabling)
        self.telegrams = 0  # good telegrams received (the report)
        self.errors: dict[str, int] = {}  # fault code -> bad telegrams / breaks seen

    def _take_parameters(self, cycle: int) -> None:
        was = self.enabled
        self.enabled = int(self.rt.memory.parameters.get("B002")["function"]) == 1
        if self.enabled and not was:
            self._last_good = cycle

    def tick(self, cycle: int) -> None:
        mode = self.rt.modes.mode
        if mode != self._mode:
            self._mode = mode
            if mode != "parameter":  # decision 6: B002 as taken on leaving Parameter mode
                self._take_parameters(cycle)
        if not self.enabled:
            return
        automatic = mode == "automatic"
        frames = self.switch.frames(cycle) if self.switch is not None else []
        for frame in frames:
            try:
                digits, velocity = decode(frame)
            except ClmError as e:
                self.errors[e.code] = self.errors.get(e.code, 0) + 1
                if automatic:  # decision 5
                    self.rt.modes.fault(e)
                continue
            self._load(digits, velocity)
            self._last_good = cycle
        if automatic and (cycle - self._last_good) * self.cycle_us > BREAK_US:
            if self.rt.modes.fault_error is None:
                self.errors["12"] = self.errors.get("12", 0) + 1
                silent = (cycle - self._last_good) * self.cycle_us / 1e6
                cause = "no IDS01 connected (device.decade_switch)" if self.switch is None else "check the cable (max. 15 m)"
                self.rt.modes.fault(ClmError("12", f"IDS01 on X6 (B002): no good telegram for {silent:.3f} s; {cause}"))

    def _load(self, digits: int, velocity: int) -> None:
        """Decisions 1, 2: the six digits with 1, 2, 3 decimals; the velocity x 10."""
        variables = self.rt.memory.variables
        self.telegrams += 1
        variables.set_system(15, digits * (_MILLION // 10))
        variables.set_system(16, digits * (_MILLION // 100))
        variables.set_system(17, digits * (_MILLION // 1000))
        variables.set_system(18, velocity * 10 * _MILLION)
