"""The eight filters, timers and counters FILT1 .. FILT8 of the bit I/O driver (manual §3.10.4.3,
§4.6 addresses 168..175, 224..263; wago.md §5.5) and their variables (VAR_* commands, §4.3.4.2).

    bank = FilterBank(dev)        # installs itself: bits.filter_output, tick hook, variables 91..98
    bank.execute(0x50, bytes([1, 0x10, 0x00]))   # VAR_SET FILT1 := 16 (mailbox or run program)

Each filter has an input (the bit Ptr_FILTn points at; a FILT bit linked to MZERO/MONE takes
the value written with WR_BIT as its input), a function (FilterN_Function, 0..11), a time
constant (FilterN_Time, ms, 0..16777215) and a variable (the counter/math value, state
variables 91..98). Reading the bit FILTn (168 + n - 1) gives the filter's output; a filter may
feed another one (Ptr_FILT2 = 0xA8: FILT1 -> FILT2, the series example of Fig. 3.10.4-9).

    0 no filtering        output = input
    1 inversion           output = NOT input (undelayed)
    2 start edge          output 0 until the input has been 0 once after a reset, then = input
    3 low pass            output takes a new input state once it has been constant for T ms
    4 pulse extension     1 at the 0->1 edge, 0 T ms after the 1->0 edge (retriggerable)
    5 monoflop            1 for exactly T ms from a 0->1 edge (not retriggerable)
    6 pulse delay         1 once the input has been 1 for T ms, 0 as soon as the input is 0
    7 math                output = variable != 0; the variable only changes by VAR_* commands
    8 counter up          variable + 1 per 0->1 edge of the input; output = variable != 0
    9 counter up to zero  as 8, but counting halts at 0 (preload a negative start value)
    10 counter down       variable - 1 per 0->1 edge
    11 counter down to 0  as 10, halted at 0 (preload a positive start value)

The functions 0..2 and 7..11 are computed when the bit is read (undelayed); the timed functions
3..6, the start-edge state and the counters are evaluated once per 1 ms tick, after the device
has written its status bits (so a counter counts at most one edge per ms: "the maximum counting
frequency for external signals is 1 kHz"). A change of FilterN_Function resets that filter.

VAR commands (DRIVE_COMMAND in mailbox move mode, or a run-program line): VAR_SET/INC/DEC
(Data1 = filter 1..8, Data2..3 = 16-bit value), VAR_ADD/SUB/MUL/DIV/COPY (three/two filter
numbers). A filter number outside 1..8 is 1247 IO_UNKNOWN_TIMER, writing a variable whose
function is not math or a counter (7..11) is 1248 IO_TIMERMODE, a divisor 0 is 1251
IO_DIVISION_ZERO; the variable keeps its value then.

Bit linking (bits.py, finished here): FILTn linked to MZERO/MONE takes the WR_BIT value as its
input; a chain deeper than four levels reads 0 and raises 1245 through `bits.on_error` (set
here to the device's raise_error) instead of stopping the module. Tests:
test_filters::test_a_filter_linked_to_mzero_counts_wr_bit_edges,
test_filters::test_too_deep_links_read_zero_and_raise_1245_without_stopping_the_module.

Decisions ([AMBIGUOUS]/[RECONSTRUCTED] points of wago.md §5.5 and §3.9; the manual wins):
* F1 Variable width (wago.md §3.9 "[AMBIGUOUS] signedness and overflow"): signed 32 bit,
  wrapping on overflow; the 16-bit value of VAR_SET/INC/DEC is sign-extended (0xFFFF = -1);
  VAR_DIV truncates toward zero (-7 / 2 = -3). Test: test_filters::test_var_arithmetic_*.
* F2 Pulse delay (function 6, wago.md §5.5 [AMBIGUOUS], §10.3 item 20): the manual's last
  sentence "The output is not reset if the input is deactivated before the set time expires" is
  read as the standard on-delay: an input that drops before T never sets the output. Test:
  test_filters::test_pulse_delay_is_an_on_delay.
* F3 Counter output (wago.md §10.3 item 21, [RECONSTRUCTED]): output = variable != 0, as for
  math (the manual says so for math). "Counter, up/down, stop": counting halts while the variable
  is 0 - the manual's "stop at overrun" heading and "halted when the filter value reaches zero"
  text agree with a wrapping 32-bit variable. Test: test_filters::test_counters.
* F4 Edges at reset (wago.md §5.5 [RECONSTRUCTED]): the first tick after a reset only samples
  the input - an input that is already 1 is not an edge (a counter does not count it, a monoflop
  does not fire), consistent with the start-edge filter's "wait state as long as the input is
  active". The pulse delay (6) is a level function: an input 1 from the reset on sets the output
  T ms later. Test: test_filters::test_an_input_active_at_reset_is_no_edge.
* F5 Timing (wago.md §5.5 [RECONSTRUCTED] precise rules): with the input change first seen in
  tick k, low pass and pulse delay switch in tick k + T, pulse extension drops in tick k + T after
  the falling edge, the monoflop is 1 in ticks k .. k + T - 1. T = 0: at once (the monoflop gives
  no pulse). Test: test_filters::test_timings_of_the_manual_figures.
* F6 VAR commands read any filter's variable (the sources of ADD/SUB/MUL/DIV/COPY and MOVE_TABLE
  with SRC = 1 need no particular function); only the written variable needs function 7..11.
  State variables 91..98 (DIAG_RD_VAR) show the variable for 7..11, the running time [ms] of
  the timer for 3..6 and the output for 0..2. Test: test_filters::test_state_variables_91_to_98.
"""

from __future__ import annotations

from enum import IntEnum
from typing import TYPE_CHECKING

from axisline.devices.wago672.errors import WagoError

if TYPE_CHECKING:
    from axisline.devices.wago672.device import Wago672

__all__ = ["FILTERS", "FilterFunction", "VarOpcode", "FilterBank", "wrap32"]

FILTERS = 8
STATE_VARIABLE_BASE = 90  # FilterN -> state variable 90 + N (91 .. 98)


class FilterFunction(IntEnum):
    """FilterN_Function (configuration addresses 224 .. 231)."""

    NONE = 0
    INVERSION = 1
    START_EDGE = 2
    LOW_PASS = 3
    PULSE_EXTENSION = 4
    MONOFLOP = 5
    PULSE_DELAY = 6
    MATH = 7
    COUNTER_UP = 8
    COUNTER_UP_TO_ZERO = 9
    COUNTER_DOWN = 10
    COUNTER_DOWN_TO_ZERO = 11


class VarOpcode(IntEnum):
    """The mathematic commands (§4.3.4.2)."""

    VAR_SET = 0x50
    VAR_INC = 0x51
    VAR_DEC = 0x52
    VAR_ADD = 0x53
    VAR_SUB = 0x54
    VAR_MUL = 0x55
    VAR_COPY = 0x56
    VAR_DIV = 0x57


_WRITABLE = frozenset(range(7, 12))  # math and counters


def wrap32(value: int) -> int:
    """Signed 32-bit two's complement wrap (F1)."""
    value &= 0xFFFFFFFF
    return value - 0x100000000 if value & 0x80000000 else value


class _Filter:
    __slots__ = ("function", "value", "output", "armed", "prev", "since")

    def __init__(self) -> None:
        self.function = -1
        self.reset()

    def reset(self) -> None:
        self.value = 0
        self.output = False
        self.armed = False
        self.prev: bool | None = None  # input of the last tick (None: first tick after a reset)
        self.since: int | None = None  # cycle a timer started


class FilterBank:
    """FILT1 .. FILT8 of one device; installs itself into the device (see the module docstring)."""

    def __init__(self, device: Wago672) -> None:
        self.device = device
        self._f = [_Filter() for _ in range(FILTERS)]
        self._cycle = 0
        # the configuration generation the filters' functions were last taken from, and the
        # filters whose tick does something (functions 2 .. 6 and the counters)
        self._generation: int | None = None
        self._ticking: list[int] = []
        device.bits.filter_output = self.output
        device.bits.on_error = device.raise_error
        device.tick_hooks.append(self.tick)
        for n in range(1, FILTERS + 1):
            device.extra_variables[STATE_VARIABLE_BASE + n] = lambda n=n: self.state_variable(n)

    # ---- configuration
    def function(self, n: int) -> int:
        return self.device.config.values[224 + n - 1]

    def time(self, n: int) -> int:
        return self.device.config.values[232 + 4 * (n - 1)]

    # ---- the bit FILTn
    def output(self, n: int, value: bool) -> bool:
        """FILTn's output for the input `value` (the bit table's `filter_output` hook)."""
        f = self._f[n - 1]
        fn = self.function(n)
        if fn != f.function:
            return self._live(fn, f, value, fresh=True)
        return self._live(fn, f, value)

    @staticmethod
    def _live(fn: int, f: _Filter, value: bool, fresh: bool = False) -> bool:
        if fn == FilterFunction.NONE:
            return value
        if fn == FilterFunction.INVERSION:
            return not value
        if fn == FilterFunction.START_EDGE:
            return value and f.armed and not fresh
        if fn >= FilterFunction.MATH:
            return f.value != 0 and not fresh
        return f.output and not fresh

    # ---- variables
    def value(self, n: int) -> int:
        """The variable of FILTn (1247 for n outside 1..8)."""
        return self._filter(n).value

    def set_value(self, n: int, value: int) -> None:
        """Write the variable of FILTn (1247, 1248 - see the module docstring)."""
        f = self._writable(n)
        fn = self.function(n)
        if f.function != fn:
            f.reset()
            f.function = fn
        f.value = wrap32(value)

    def _writable(self, n: int) -> _Filter:
        f = self._filter(n)
        fn = self.function(n)
        if fn not in _WRITABLE:
            raise WagoError(1248, f"FILT{n}: function {fn} ({_name(fn)}) has no writable variable (math or counter 7 .. 11 needed)")
        return f

    def _filter(self, n: int) -> _Filter:
        if isinstance(n, bool) or not isinstance(n, int) or not 1 <= n <= FILTERS:
            raise WagoError(1247, f"filter {n!r} does not exist (FILT1 .. FILT8 = 1 .. 8)")
        return self._f[n - 1]

    def state_variable(self, n: int) -> int:
        """State variable 90 + n (F6)."""
        f = self._f[n - 1]
        fn = self.function(n)
        if fn != f.function:
            return 0
        if fn >= FilterFunction.MATH:
            return f.value
        if fn >= FilterFunction.LOW_PASS:
            return self._cycle - f.since if f.since is not None else 0
        return int(self.device.bits.read(167 + n))

    def execute(self, opcode: int, data: bytes | tuple[int, int, int]) -> None:
        """A VAR_* command with Data 1..3; raises WagoError (1247, 1248, 1251)."""
        d = bytes(data)
        op = VarOpcode(opcode)
        if op in (VarOpcode.VAR_SET, VarOpcode.VAR_INC, VarOpcode.VAR_DEC):
            n = d[0]
            imm = int.from_bytes(d[1:3], "little", signed=True)
            if op == VarOpcode.VAR_SET:
                new = imm
            elif op == VarOpcode.VAR_INC:
                new = self.value(n) + imm
            else:
                new = self.value(n) - imm
            self.set_value(n, new)
            return
        target = d[0]
        self._writable(target)
        if op == VarOpcode.VAR_COPY:
            self.set_value(target, self.value(d[1]))
            return
        a, b = self.value(d[1]), self.value(d[2])
        if op == VarOpcode.VAR_ADD:  # Result := Summand1 (Data3) + Summand2 (Data2)
            new = b + a
        elif op == VarOpcode.VAR_SUB:  # Difference := Minuend (Data2) - Subtrahend (Data3)
            new = a - b
        elif op == VarOpcode.VAR_MUL:
            new = a * b
        else:  # VAR_DIV: Quotient := Dividend (Data2) / Divisor (Data3)
            if b == 0:
                raise WagoError(1251, f"VAR_DIV FILT{target} := FILT{d[1]} / FILT{d[2]}: the divisor FILT{d[2]} is 0")
            q = abs(a) // abs(b)
            new = q if (a >= 0) == (b > 0) else -q
        self.set_value(target, new)

    # ---- the tick
    def reset(self) -> None:
        """Warm start: all filters back to their state after a reset (variables 0)."""
        for f in self._f:
            f.function = -1
            f.reset()
        self._generation = None

    def tick(self, cycle: int) -> None:
        self._cycle = cycle
        generation = self.device.config.generation
        if generation != self._generation:
            # a changed configuration (or a reset): take each filter's function before its
            # tick, one filter after the other, as the module does
            self._generation = generation
            self._ticking = []
            for i in range(FILTERS):
                self._tick_filter(i, cycle, sync=True)
            return
        # the functions are the configuration's: only the filters that work in a tick
        for i in self._ticking:
            self._tick_filter(i, cycle)

    def _tick_filter(self, i: int, cycle: int, sync: bool = False) -> None:
        f = self._f[i]
        n = i + 1
        if sync:
            fn = self.function(n)
            if fn != f.function:
                f.reset()
                f.function = fn
            if fn in (FilterFunction.NONE, FilterFunction.INVERSION, FilterFunction.MATH):
                return
            self._ticking.append(i)
        else:
            fn = f.function
        bits = self.device.bits
        try:
            x = bits.filter_input(n)
        except WagoError as e:
            self.device.raise_error(e.code, e.text)
            return
        prev = f.prev
        rising = prev is False and x
        falling = bool(prev) and not x
        f.prev = x
        t = self.time(n)
        if fn == FilterFunction.START_EDGE:
            if not x:
                f.armed = True
        elif fn == FilterFunction.LOW_PASS:
            if prev is None:
                f.output = x
            elif x != f.output:
                if f.since is None:
                    f.since = cycle
                if cycle - f.since >= t:
                    f.output = x
                    f.since = None
            else:
                f.since = None
        elif fn == FilterFunction.PULSE_EXTENSION:
            if x:
                f.output = True
                f.since = None
            elif f.output:
                if falling or f.since is None:
                    f.since = cycle
                if cycle - f.since >= t:
                    f.output = False
                    f.since = None
        elif fn == FilterFunction.MONOFLOP:
            if f.output and cycle - f.since >= t:  # type: ignore[operator]
                f.output = False
                f.since = None
            if rising and not f.output and f.since is None:
                f.since = cycle
                f.output = t > 0
                if not f.output:
                    f.since = None
        elif fn == FilterFunction.PULSE_DELAY:
            if x:
                if f.since is None:
                    f.since = cycle
                if cycle - f.since >= t:
                    f.output = True
            else:
                f.output = False
                f.since = None
        elif rising:  # counters
            if fn == FilterFunction.COUNTER_UP:
                f.value = wrap32(f.value + 1)
            elif fn == FilterFunction.COUNTER_UP_TO_ZERO:
                if f.value != 0:
                    f.value = wrap32(f.value + 1)
            elif fn == FilterFunction.COUNTER_DOWN:
                f.value = wrap32(f.value - 1)
            elif fn == FilterFunction.COUNTER_DOWN_TO_ZERO:
                if f.value != 0:
                    f.value = wrap32(f.value - 1)


def _name(fn: int) -> str:
    try:
        return FilterFunction(fn).name.lower().replace("_", " ")
    except ValueError:
        return "undefined"
