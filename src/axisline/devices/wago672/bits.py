"""The 256-bit field of the I/O driver (manual §3.10.3-3.10.4, §4.5; wago.md §5.1-5.4).

Source bits 0..127 are written by the function units that produce them (the device each
tick: On_Target, Busy, ..., Input1..6, KBUS_CTRLx_y from the control bytes). Target bits
128..255 have no value of their own: a target reads the bit its pointer names, the pointer
being the configuration byte at the target's own number (Ptr_Stop1_N at address 194 = 0x30:
Stop1_N follows Input1). A target may point at another target, at most four levels deep
(error 1245 IO_RECURSIVE_LINK beyond).

This is the seam for bit linking: `BitTable` resolves the FACTORY_DEFAULT links and any
relinking in the configuration, keeps the values of bits linked to MZERO/MONE (writable by
mailbox and run program, WR_BIT) and of the user bits. The eight filters/timers/counters
FILT1..8 are filters.py (`filter_output` hook, installed by `FilterBank`; without it a filter
passes its input through, the function "0 no filtering"); `filter_input(n)` reads a filter's
input. With `on_error` set (mailbox.attach sets the device's raise_error) a chain deeper than
four levels reads 0 and reports 1245 instead of raising, so the status bytes, OUT1/OUT2 and the
LEDs can be read with any linking. A FILT bit linked to MZERO/MONE keeps the written value as the filter's input.
WR_BIT on a source bit (0..127) or on a bit without a pointer (224..255) is 1243
IO_USERBIT_READONLY, on a target not linked to MZERO/MONE 1242 IO_ILLEGAL_USERBITNR.

Bit numbers are the manual's names as constants of `Bit` (e.g. `Bit.Stop_N_ACK == 0x11`).

The device reads some 60 bits every 1 ms tick (its input signals, the status bytes S1..S3,
OUT1/OUT2), so the links are not followed per read: `BitTable` follows every pointer chain once
after each change of the configuration (`ConfigTable.generation`) and keeps, per bit, the place
in `field` it reads; a `BitGroup` (`group`, `values`) reads a set of bits in one go.

Decisions (issue 18: "a bit table that resolves its links once per configuration change"):
* B1 A chain that passes a filter bit FILT1..8 or is deeper than four levels is still followed
  at each read: a filter's output is computed when it is read (filters.py: functions 0 .. 2, 7 ..
  11 are undelayed), and the manual issues 1245 each time such a chain is used ("Too many nesting
  levels will yield an ambiguous result and the error ... will be issued"), so neither has one
  place to read; every other chain ends at a source bit, a MZERO/MONE value or a bit without a
  pointer, which is what the table keeps. Reads through either give what the chain gives (tests:
  test_links_and_values::test_random_linkings_read_as_the_manual_rule_after_every_change,
  test_filters::test_too_deep_links_read_zero_and_raise_1245_without_stopping_the_module).
"""

from __future__ import annotations

from collections.abc import Callable
from enum import IntEnum

from axisline.devices.wago672.config_table import ConfigTable
from axisline.devices.wago672.errors import WagoError

__all__ = ["Bit", "BitGroup", "BitTable", "MAX_NESTING", "SPREAD"]

MAX_NESTING = 4  # "the maximum number of nesting levels is four (4)" (§3.10.4)


class Bit(IntEnum):
    """Bit numbers of the bit field (§4.5, wago.md §5.2)."""

    # ---- source bits (0 .. 127)
    ZERO = 0x00
    ONE = 0x01
    MZERO = 0x02
    MONE = 0x03
    Reset = 0x04
    Warning = 0x05
    KBUS_Active = 0x06
    On_Target = 0x08
    Busy = 0x09
    StandStill = 0x0A
    On_Speed = 0x0B
    Direction = 0x0C
    Reference_OK = 0x0D
    PreCalc_ACK = 0x0E
    Error = 0x0F
    Ready = 0x10
    Stop_N_ACK = 0x11
    Start_ACK = 0x12
    Command_ACK_1 = 0x13  # M_Positioning_ACK
    Command_ACK_2 = 0x14  # M_Program_ACK
    Command_ACK_3 = 0x15  # M_Reference_ACK
    Command_ACK_4 = 0x16  # M_Jog_ACK
    Command_ACK_5 = 0x17  # M_DriveByMbx_ACK
    Break = 0x18  # the manual's spelling of the Brake bit: 0 braked, 1 vented
    ERR_Code = 0x19  # blink-code signal of LED A
    SetupSpeed_Active_ACK = 0x1A
    Program_Running = 0x1B
    Ramp_Up = 0x1C
    Ramp_Down = 0x1D
    Trace_Stored = 0x20
    Encoder_A = 0x26
    Encoder_B = 0x27
    Err_Range_Neg = 0x28
    Err_Range_Pos = 0x29
    Err_Range = 0x2A
    Encoder_Z_Toggle = 0x2E
    CAM9 = 0x2F
    Input1 = 0x30
    Input2 = 0x31
    Input3 = 0x32
    Input4 = 0x33
    Input5 = 0x34
    Input6 = 0x35
    Input7 = 0x36
    Input8 = 0x37
    CAM1 = 0x38
    CAM2 = 0x39
    CAM3 = 0x3A
    CAM4 = 0x3B
    CAM5 = 0x3C
    CAM6 = 0x3D
    CAM7 = 0x3E
    CAM8 = 0x3F
    KBUS_CTRL1_0 = 0x40
    KBUS_CTRL2_0 = 0x48
    KBUS_CTRL3_0 = 0x50
    # ---- target bits (128 .. 255)
    KBUS_ST1_0 = 0x80
    KBUS_ST2_0 = 0x88
    KBUS_ST3_0 = 0x90
    KBUS_ST3_6 = 0x96
    KBUS_ST3_7 = 0x97
    UserBit_0 = 0x98
    OUT1 = 0xA0
    OUT2 = 0xA1
    FILT1 = 0xA8
    Enable = 0xB0
    Stop2_N = 0xB1
    Start = 0xB2
    Command_1 = 0xB3  # M_Positioning
    Command_2 = 0xB4  # M_Program
    Command_3 = 0xB5  # M_Reference
    Command_4 = 0xB6  # M_Jog
    Command_5 = 0xB7  # M_DriveByMbx
    Enable_Drive = 0xB8
    Reset_Quit = 0xB9
    Direction_Pos = 0xBA
    Direction_Neg = 0xBB
    Set_Reference = 0xBC
    PreCalc = 0xBD
    SetupSpeed_Active = 0xBE
    Error_Quit = 0xBF
    LimitSwitch_Pos = 0xC0
    LimitSwitch_Neg = 0xC1
    Stop1_N = 0xC2
    Brake_Manual = 0xC3
    Freq_Range_Sel_0 = 0xC4
    Freq_Range_Sel_1 = 0xC5
    Acc_Range_Sel_0 = 0xC6
    Acc_Range_Sel_1 = 0xC7
    Set_Actual_Pos = 0xC8
    Jog_Pos = 0xCA
    Jog_Neg = 0xCB
    LED_B = 0xD0
    LED_C = 0xD1
    LED_D = 0xD2
    LED_A = 0xD3
    LED_E = 0xD4
    LED_F = 0xD5
    Error_Set = 0xDD
    TRACE_TRIGGER = 0xDE
    Trace_Armed = 0xDF


# targets that have a pointer in the configuration table (128 .. 223)
_POINTER_TARGETS = range(128, 224)
_FILTER_BITS = range(168, 176)  # FILT1 .. FILT8
_SLOW = -1  # a link that is read through the chain each time (a filter on it, or too deep)

# a byte -> its eight 0/1 values (value i = bit i): a control byte spread over eight source
# bits without a loop over the bits
SPREAD = tuple(bytes((v >> i) & 1 for i in range(8)) for v in range(256))


class BitGroup:
    """Bits the device reads together every tick (its input signals, the status bytes): the
    table keeps the places they read, found again when the links change (`BitTable.group`)."""

    def __init__(self, bits: tuple[int, ...]) -> None:
        self.bits = bits
        # the places in `field` the bits read, or None while one of them needs the chain
        # (_SLOW); bytes, since indexing bytes is cheap in compiled code
        self.places: bytes | None = None


class BitTable:
    """256 bits by number: sources stored, targets resolved through their pointers.

    `field` holds the values: 0 .. 127 the source bits, 128 .. 223 the values of targets
    linked to MZERO/MONE (written by WR_BIT), 224 .. 255 always 0 (bits without a pointer).
    The device writes its source bits straight into it (`put` for everyone else).

    The links are resolved once per configuration change, not per read: `_link[n]` is the
    place in `field` that bit n reads, found by following the pointer chain as the manual
    describes it; a chain through a filter (its output is computed when read) or deeper than
    four levels (an error each time it is read) is followed at each read, as before.

    `filter_output(n, input) -> bool` computes FILTn (n = 1..8) from its input; the
    placeholder passes the input through (filter function 0).
    """

    def __init__(self, config: ConfigTable) -> None:
        self.config = config
        self.field = bytearray(256)
        self.field[Bit.ONE] = 1
        self.field[Bit.MONE] = 1
        self.filter_output: Callable[[int, bool], bool] = lambda n, value: value
        # set by mailbox.attach: report 1245 and read 0 instead of raising (every reader of a bit)
        self.on_error: Callable[[int, str], None] | None = None
        self._ptr: list[int] = []  # pointers of targets 128..223, refreshed when the config changes
        self._link: list[int] = list(range(256))
        self._groups: list[BitGroup] = []
        self._bytes: dict[int, BitGroup] = {}  # status bytes by their first bit
        self._generation = -1
        # a source bit was written by someone other than the device's tick: the tick rewrites
        # its own source bits (it writes them only when they change: watches._write_sources)
        self.sources_touched = True
        self.reset()

    # ---- links
    def _pointers(self) -> list[int]:
        if self._generation != self.config.generation:
            self._relink()
        return self._ptr

    def _relink(self) -> None:
        """Follow every pointer chain once (after a configuration change)."""
        get = self.config.get
        self._ptr = [get(t) for t in _POINTER_TARGETS]
        self._link = [self._chain_end(n, 0) for n in range(256)]
        self._generation = self.config.generation
        for g in self._groups:
            places = [self._link[n] for n in g.bits]
            g.places = None if _SLOW in places else bytes(places)

    def _chain_end(self, n: int, depth: int) -> int:
        """The place in `field` bit n reads (the steps of `_resolve`), or _SLOW."""
        if n < 128 or n >= 224:
            return n
        if n in _FILTER_BITS:
            return _SLOW
        ptr = self._ptr[n - 128]
        if ptr == Bit.MZERO or ptr == Bit.MONE:
            return n
        if ptr >= 128:
            if depth + 1 >= MAX_NESTING or ptr == n:
                return _SLOW
            return self._chain_end(ptr, depth + 1)
        return ptr

    def group(self, bits: tuple[int, ...]) -> BitGroup:
        """Register bits (at least two, 0 .. 255) that are read together with `values`."""
        if len(bits) < 2 or not all(0 <= n <= 255 for n in bits):
            raise ValueError(f"a bit group needs two or more bit numbers 0 .. 255, got {bits!r}")
        g = BitGroup(tuple(int(n) for n in bits))
        self._groups.append(g)
        self._generation = -1  # its places are found with the next read
        return g

    def values(self, g: BitGroup) -> tuple[bool, ...]:
        """The values of a group's bits, in its order (as `read` of each, in that order)."""
        w = self.word(g)
        return tuple(w >> i & 1 == 1 for i in range(len(g.bits)))

    def word(self, g: BitGroup) -> int:
        """The group's bits packed into an int: bit i is the value of its i-th bit (as `read`)."""
        if self._generation != self.config.generation:
            self._relink()
        places = g.places
        w = 0
        if places is not None:
            field = bytes(self.field)  # a snapshot: its bytes are read without boxing
            for i in range(len(places)):
                if field[places[i]]:
                    w |= 1 << i
            return w
        for i, n in enumerate(g.bits):
            if self._resolve(n, 0):
                w |= 1 << i
        return w

    def reset(self) -> None:
        """After a reset: MZERO-linked bits are 0, MONE-linked bits are 1 (§3.10.4.1)."""
        for t in _POINTER_TARGETS:
            self.field[t] = 1 if self.config.get(t) == Bit.MONE else 0

    # ---- sources (the device, and later the filters/cams/recorder, write these)
    def set_source(self, n: int, value: bool) -> None:
        if not 0 <= n < 128:
            raise WagoError(1241, f"source bit {n} is outside 0 .. 127")
        if n in (Bit.ZERO, Bit.ONE, Bit.MZERO, Bit.MONE):
            raise WagoError(1243, f"bit {n} is a constant and cannot be written")
        self.field[n] = 1 if value else 0
        self.sources_touched = True

    def put(self, n: int, value: bool) -> None:
        """set_source without the checks (hot path)."""
        self.field[n] = 1 if value else 0
        self.sources_touched = True

    def set_byte(self, first: int, value: int) -> None:
        """Eight source bits first .. first+7 from one byte (control bytes -> KBUS_CTRLx_y)."""
        self.field[first : first + 8] = SPREAD[value & 0xFF]

    # ---- reading
    def read(self, n: int) -> bool:
        """Value of bit n (0 .. 255): a source, or the source a target's pointer chain ends at."""
        if type(n) is not int and (isinstance(n, bool) or not isinstance(n, int)) or not 0 <= n <= 255:
            raise WagoError(1241, f"bit number {n!r} is outside 0 .. 255")
        if self._generation != self.config.generation:
            self._relink()
        place = self._link[n]
        if place >= 0:
            return self.field[place] == 1
        return self._resolve(n, 0)

    def _resolve(self, n: int, depth: int) -> bool:
        """Follow the pointer chain of bit n (the slow path: filters and too deep links)."""
        if n < 128:
            return bool(self.field[n])
        if n >= 224:
            return False  # no pointer (unused or internal bits)
        ptr = self._pointers()[n - 128]
        if 168 <= n <= 175:  # FILTn: the pointer selects the filter input, reading gives the output
            return bool(self.filter_output(n - 167, self._filter_input(n, ptr, depth)))
        if ptr in (Bit.MZERO, Bit.MONE):
            return bool(self.field[n])
        if ptr >= 128:
            if depth + 1 >= MAX_NESTING or ptr == n:
                return self._too_deep(n)
            return self._resolve(ptr, depth + 1)
        return bool(self.field[ptr])

    def _filter_input(self, n: int, ptr: int, depth: int) -> bool:
        if ptr in (Bit.MZERO, Bit.MONE):
            return bool(self.field[n])  # written by WR_BIT: the filter's input
        return self._resolve(ptr, depth + 1) if depth < MAX_NESTING else self._too_deep(n)

    def filter_input(self, n: int) -> bool:
        """The input of FILTn (n = 1..8): the bit Ptr_FILTn points at."""
        bit = 167 + n
        return self._filter_input(bit, self._pointers()[bit - 128], 0)

    def _too_deep(self, n: int) -> bool:
        text = f"bit {n:#04x}: the chain of linked bits is deeper than {MAX_NESTING} levels"
        if self.on_error is not None:
            # "Too many nesting levels will yield an ambiguous result and the error ... will be issued"
            self.on_error(1245, text)
            return False
        raise WagoError(1245, text)

    def byte(self, first: int) -> int:
        """Eight bits first .. first+7 as one byte (KBUS_ST1_0.. -> S1, ...)."""
        g = self._bytes.get(first)
        if g is None:
            g = self._bytes[first] = self.group(tuple(range(first, first + 8)))
        return self.word(g)

    # ---- writing (mailbox WR_BIT, run program)
    def writable(self, n: int) -> bool:
        return 128 <= n < 224 and self.config.get(n) in (Bit.MZERO, Bit.MONE)

    def write(self, n: int, value: bool) -> None:
        """Set a target bit that is linked to MZERO or MONE (else 1242; a source bit or a bit
        without pointer: 1243; n > 255: 1241)."""
        if isinstance(n, bool) or not isinstance(n, int) or not 0 <= n <= 255:
            raise WagoError(1241, f"bit number {n!r} is outside 0 .. 255")
        if n < 128 or n >= 224:
            raise WagoError(1243, f"bit {n:#04x} is {'a source bit' if n < 128 else 'an internal bit'} and cannot be written")
        if not self.writable(n):
            raise WagoError(1242, f"bit {n:#04x} is not linked to MZERO or MONE and cannot be set")
        self.field[n] = 1 if value else 0

    def sources(self) -> bytes:
        return bytes(self.field[:128])
