"""The CLM's Profibus DP process image, served as Modbus TCP registers (manual §10.1
L7511-8085; spec §9; errata 4, 5, 7, 12, 19, 20; docs/clm-profibus.md).

    pb = ClmProfibus(rt, writes_allowed=lambda: True)   # the personality's register_endpoint()
    pb.cycle(rt.step)                                   # every NC cycle instead of rt.step()
    pb.write_registers(6, [0x0002])                     # the PLC: Automatic (control word bit 1)
    pb.read_registers("input", 0, 14)                   # the PLC: the CLM's whole input area

A PLC that talked Profibus DP to the CLM sends the same words over Modbus TCP. One register is
one DP word with its bytes in the order Profibus sends them (big-endian: the register's high
byte is the word's first byte on the wire); a long is two registers, the high word first.

=================  =======  ==========================================================
address            FC       what (the DP word)
=================  =======  ==========================================================
0x0000 .. 0x0005   3 6 16   master -> CLM: service data channel (control word, 5 data words)
0x0006             3 6 16   I/O control word: bits 0-7 = I2.00, 8-15 = I2.01 (Figs. 10-6/8)
0x0007, 0x0008     3 6 16   user words: I2.02 / I2.03 and I2.04 / I2.05
0x0009 .. 0x000C   3 6 16   variable channel: read control, write control, data long
0x0000 .. 0x000D   4        CLM -> master: service status word + 5 data words, I/O status
0x0100 .. 0x010D   3        word (Q2.00/Q2.01), user words Q2.02-Q2.05, diagnostic word,
                            variable channel: read status, write status, data long
0x0200             3 4 6 16 fieldbus watchdog time in ms (V046; 0 = off)
0x0201             3 4      watchdog: 0 not started, 1 running, 2 expired
=================  =======  ==========================================================

With B008 format 1 the variable channel is absent (0x0009-0x000C, input 0x000A-0x000D are
refused with exception 02). The channels act on the write that toggles their handshake bit
(`profibus_channels`), so a PLC writes a channel's words in one FC16 (or the control word last).

Per NC cycle (`cycle`): B008 is taken outside Parameter mode; the watchdog is checked; the
control word's bits are laid over the system inputs I0.00-I0.02 for the mode machine's step and
the hardware bits are put back after it (so Status 61 and the next cycle see the hardware); the
status word's reserved bits and brakes 3/4 are set.

Decisions (spec line -> choice, why)
------------------------------------
1. Register map (issue 14: "same bytes"): the DP output area (service channel, then the
   process data as Fig. 10-1 orders them) from holding register 0, the input area from input
   register 0 and, for clients with FC3 only, from holding register 0x0100 (the WAGO
   coupler's read-back offset idea). Test: ``test_profibus_modbus.py::test_register_map_and_byte_order``.
2. Byte order of the I/O words, L7580-7663 (the status/control word numbers bit 0 = x.00.0,
   bit 8 = x.01.0) and L7665-7690 (user words "I2.02 / I2.03 in one word"): one rule for all
   three words, byte 2k is bits 0-7 and byte 2k+1 bits 8-15 (so I2.02 is the low byte of
   word 2, as I2.00 is of word 1); the spec's inference "lower byte number in the high byte"
   would give word 1 and words 2-3 opposite rules. Test: ``test_register_map_and_byte_order``.
3. B008 (errata 20, parameters decision 6: ``format hardware operating_mode profibus
   address``), taken outside Parameter mode ("read from Parameter Mode to the operating mode",
   L7527): formats 0 and 2 give the same channels (Fig. 10-4 differs in nothing else); format
   1 drops the variable channel. The service channel is there in every format (Fig. 10-1).
   Test: ``test_format_1_has_no_variable_channel``.
4. Address, L7519-7525: outside 2..89 (00 at delivery) the card does not start: fault 34
   "Fieldbus Init" naming B008's address, once each time the CLM leaves Parameter mode or powers
   on, and every request is answered with exception 04 until an address 2..89 is taken. Test:
   ``test_address_outside_2_89_is_fault_34``.
5. System inputs (L5770-5900, L7576-7624, L8046-8053): with B008's "Profibus system signals"
   0 the control word is no system input (the PLC still writes I2.00-I2.05 for the program).
   With 1: Parameter (bit 0) is hardware OR fieldbus always ("dominant ... Parameter Mode can
   be forced independently from the fieldbus", L5847). Mode 3 with "hardware system signals" 1:
   every other system input is hardware OR its control-word bit ("the logical '1' signal is
   dominant", L5071; E-Stop bit 2 and Immediate Stop bit 4 too, so a 1 from either side keeps
   the machine running; bit 15 enables all four axes). Mode 0 (or hardware signals 0): E-Stop
   and the axis enables come from the hardware only (L8046-8053 "must be assigned"); the others
   from the control word only. Jog 3/4 (bits 5, 6, 12, 13) and Brake 3/4 (status bits 11, 12)
   are used in both modes as Figs. 10-5/10-6 define them, although the I/O list says "only
   Fieldbus Operating Mode 3" (L5896-5899, L6052-6055): the Profibus chapter defines the words.
   Tests: ``test_control_word_in_mode_0``, ``test_mode_3_ors_hardware_and_fieldbus``,
   ``test_which_side_gives_the_system_inputs``.
6. The merged inputs exist during the NC cycle only: the hardware bits are put back after the
   step, so Status 61 of I0 and the next cycle's edge detection see the hardware; the Logic
   Task (run inside the step) sees the inputs as the firmware does. Test:
   ``test_control_word_in_mode_0``.
7. Status word (Figs. 10-5/10-7; errata 19): Q2.00/Q2.01 as the mode machine mirrors them from
   Q0.00/Q0.01 (Fault = Q2.00.5 is 1 when there is *no* fault), with the reserved bits 8 and
   10 at 0 and bits 11/12 = Brake 3/4 (Q0.02.0 / Q0.02.1), written back into Q2.01 so the
   program and Status 61 read the same byte. Test: ``test_status_word_and_diagnostic``.
8. Diagnostic word, L7692 ("a hexadecimal number ... the diagnostic numbers"): the fault code
   of the display and Status 53 as a number, 0x00 no error, 0x01 Parameter mode, 0x37 fieldbus
   timeout. Test: ``test_status_word_and_diagnostic``.
9. Fieldbus timeout, V046 "Timeout set by the fieldbus master, in ms" (L1378), error 37: Modbus
   TCP has no DP watchdog, so the CLM keeps one: armed by the first write of the output area
   (0x0000-0x000C), re-triggered by every later one (reads do not), expired when no write
   came for longer than the watchdog time (register 0x0200, default 1000 ms, 0 = off; V046
   shows it), counted in NC cycles. On expiry the control word and user words are taken as 0
   (a DP slave's outputs of a lost master) and, when the control word is a system input (5.)
   and the CLM is not in Parameter mode, fault 37 "Fieldbus Timeout" is raised once; the next
   write re-arms it. V045 (baud rate) stays 0: there is no Profibus baud rate on TCP. Tests:
   ``test_watchdog_timeout_is_fault_37``, ``test_which_side_gives_the_system_inputs``,
   ``test_profibus_channels.py::test_no_fault_37_in_parameter_mode``.
10. Requests act at once at the cycle boundary the Modbus server runs them at (the server goes
    through the machine's command queue); a refused request (an address outside the map, a
    write to the input area, the variable channel in format 1) changes nothing. Writes need
    ``serve --allow-writes`` (the server refuses them with exception 01 otherwise). Test:
    ``test_refusals``.

Tests are in ``tests/devices/clm/test_profibus_modbus.py`` unless named with their file.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from .errors import ClmError
from .image import ProcessImage
from .operands import Operand
from .profibus_channels import ServiceChannel, VariableChannel, words_long
from .serial import ClmSerialEndpoint, Settings
from .status import fault_code

__all__ = ["ClmProfibus", "B008", "read_b008", "INPUT_READBACK", "WATCHDOG_TIME", "WATCHDOG_STATUS"]

OUT_WORDS = 13  # service 6 + I/O 3 + variable 4
IN_WORDS = 14  # service 6 + I/O 3 + diagnostic 1 + variable 4
OUT_WORDS_F1, IN_WORDS_F1 = 9, 10  # format 1: no variable channel
INPUT_READBACK = 0x0100
WATCHDOG_TIME = 0x0200
WATCHDOG_STATUS = 0x0201
WD_NOT_STARTED, WD_RUNNING, WD_EXPIRED = 0, 1, 2
DEFAULT_WATCHDOG_MS = 1000
_IO = 6  # first I/O word in both areas

_SETTINGS = Settings(station=0, checksum=False, confirmation=False, auto_error=False, data_interface=True)


class _ServiceSerial(ClmSerialEndpoint):
    """The X6 protocol with the settings of the service channel (channels decision 6)."""

    @property
    def settings(self) -> Settings:  # type: ignore[override]
        return _SETTINGS


class B008:
    """B008 as taken outside Parameter mode."""

    __slots__ = ("format", "hardware", "mode", "profibus", "address")

    def __init__(self, fmt: int = 0, hardware: int = 0, mode: int = 0, profibus: int = 0, address: int = 0) -> None:
        self.format, self.hardware, self.mode, self.profibus, self.address = fmt, hardware, mode, profibus, address

    @property
    def address_ok(self) -> bool:
        return 2 <= self.address <= 89

    @property
    def ored(self) -> bool:
        """Mode 3 with the hardware system signals on: hardware OR fieldbus (decision 5)."""
        return self.mode == 3 and self.hardware == 1


def read_b008(params: Any) -> B008:
    v = params.get("B008")
    return B008(int(v["process_data_format"]), int(v["hardware_system_signals"]), int(v["operating_mode"]),
                int(v["profibus_system_signals"]), int(v["slave_address"]))


def _op(text: str) -> Operand:
    area, rest = text[0], text[1:].split(".")
    return Operand(area, int(rest[0]), int(rest[1]), int(rest[2]))


# control word bit -> the system inputs it is the twin of, and its source in mode 0 (decision 5)
_OR, _FIELDBUS, _HARDWARE = 0, 1, 2
_TWINS: tuple[tuple[int, tuple[str, ...], int], ...] = (
    (0, ("I0.00.0",), _OR),  # Parameter: dominant from either side
    (1, ("I0.00.1",), _FIELDBUS),  # Manual / Automatic
    (2, ("I0.00.2",), _HARDWARE),  # E-Stop (mode 3 only)
    (3, ("I0.00.3",), _FIELDBUS),  # Start
    (4, ("I0.00.4",), _FIELDBUS),  # Immediate Stop
    (5, ("I0.02.1",), _FIELDBUS),  # Jog Forward 3
    (6, ("I0.02.2",), _FIELDBUS),  # Jog Reverse 3
    (7, ("I0.00.7",), _FIELDBUS),  # Clear Errors
    (8, ("I0.01.0",), _FIELDBUS), (9, ("I0.01.1",), _FIELDBUS),  # Jog 1
    (10, ("I0.01.2",), _FIELDBUS), (11, ("I0.01.3",), _FIELDBUS),  # Jog 2
    (12, ("I0.02.4",), _FIELDBUS), (13, ("I0.02.5",), _FIELDBUS),  # Jog 4
    (14, ("I0.01.6",), _FIELDBUS),  # Restart
    (15, ("I0.00.5", "I0.00.6", "I0.02.0", "I0.02.3"), _HARDWARE),  # Enable (all axes), mode 3 only
)
_I0 = tuple(ProcessImage.locate(Operand("I", 0, b))[0] for b in range(3))
_I2 = tuple(ProcessImage.locate(Operand("I", 2, b))[0] for b in range(6))
_Q2 = tuple(ProcessImage.locate(Operand("Q", 2, b))[0] for b in range(6))
_BRAKES = (ProcessImage.locate(_op("Q0.02.0")), ProcessImage.locate(_op("Q0.02.1")))


def _refused(message: str, code: int = 2) -> Exception:
    from axisline.fieldbus.modbus import RegisterRefused

    return RegisterRefused(message, code)


class ClmProfibus:
    """The DP image of one CLM as a `RegisterEndpoint` (see the module docstring)."""

    def __init__(self, rt: Any, writes_allowed: Callable[[], bool] = lambda: True,
                 store: Callable[[], object] | None = None) -> None:
        self.rt = rt
        self._writes_allowed = writes_allowed
        self.out = [0] * OUT_WORDS  # the PLC's output area as last written
        self.variables = VariableChannel(rt.memory.variables, store)
        self.service = ServiceChannel(_ServiceSerial(rt, writes_allowed, store=store))
        self.settings = B008()
        self._latched = False  # B008 taken since the last Parameter mode
        self._taken = False  # B008 taken at all (before: the card has not started yet)
        self.watchdog_ms = DEFAULT_WATCHDOG_MS
        self.watchdog_status = WD_NOT_STARTED
        self.expiries = 0
        self._last_write = 0  # rt.cycle of the last write of the output area
        self._twins = [(bit, tuple(ProcessImage.locate(_op(t))[:2] for t in ops), src) for bit, ops, src in _TWINS]
        self._saved = b""
        self._set_v046()

    @property
    def network_writes(self) -> bool:
        return bool(self._writes_allowed())

    # -- the NC cycle -------------------------------------------------------------------------

    def cycle(self, step: Callable[[], None]) -> None:
        """One NC cycle around the runtime's `step` (the personality's per-cycle hook)."""
        self._take_b008()
        self._watchdog()
        self._lay_over_inputs()
        try:
            step()
        finally:
            self._put_back_inputs()
            self._status_word()

    def _take_b008(self) -> None:
        modes = self.rt.modes
        if modes.mode == "parameter":
            self._latched = False
            return
        if self._latched:
            return
        self._latched = self._taken = True
        try:
            self.settings = read_b008(self.rt.memory.parameters)
        except (KeyError, ValueError, TypeError):
            self.settings = B008()
        if not self.settings.address_ok and modes.mode != "power-on":
            modes.fault(ClmError("34", f"B008 slave address {self.settings.address:02d}: Profibus DP allows 02-89 (L7523)", "B008"))
        elif not self.settings.address_ok:
            self._latched = False  # power-on: the mode machine takes the parameters in this step; raise next cycle

    def _watchdog(self) -> None:
        if self.watchdog_status != WD_RUNNING or self.watchdog_ms <= 0:
            return
        rt = self.rt
        elapsed_ms = (rt.cycle - self._last_write) * rt.nc_cycle_s * 1000
        if elapsed_ms <= self.watchdog_ms + 1e-9:
            return
        self.watchdog_status = WD_EXPIRED
        self.expiries += 1
        for k in range(_IO, _IO + 3):  # the PLC's process outputs as a lost master leaves them
            self.out[k] = 0
        self._io_to_image()
        if self.settings.profibus and rt.modes.mode not in ("parameter", "power-on"):
            rt.modes.fault(ClmError("37", f"no write of the PLC's output area for {elapsed_ms:.0f} ms (watchdog {self.watchdog_ms} ms, V046)"))

    def _lay_over_inputs(self) -> None:
        data = self.rt.image.data
        self._saved = bytes(data[i] for i in _I0)
        s = self.settings
        if not (s.profibus and s.address_ok):
            return
        word = data[_I2[0]] | data[_I2[1]] << 8
        ored = s.ored
        for bit, places, source in self._twins:
            fb = word >> bit & 1
            for at, shift in places:
                if source == _OR or ored:
                    on = fb or data[at] >> shift & 1
                elif source == _FIELDBUS:
                    on = fb
                else:
                    continue
                data[at] = data[at] | (1 << shift) if on else data[at] & ~(1 << shift)

    def _put_back_inputs(self) -> None:
        if self._saved:
            data = self.rt.image.data
            for i, b in zip(_I0, self._saved):
                data[i] = b
            self._saved = b""

    def _status_word(self) -> None:
        data = self.rt.image.data
        high = data[_Q2[1]] & ~0b0001_1101  # reserved 8, 10; brakes 3/4 set below (decision 7)
        for (at, shift, _), bit in zip(_BRAKES, (3, 4)):
            high |= (data[at] >> shift & 1) << bit
        data[_Q2[1]] = high

    def summary(self) -> dict[str, Any]:
        """What the run summary shows of the fieldbus (the personality's ``summary()``)."""
        s = self.settings
        return {"format": s.format, "operating_mode": s.mode, "system_inputs": bool(s.profibus), "address": s.address,
                "running": self._taken and s.address_ok, "watchdog_ms": self.watchdog_ms,
                "watchdog_expiries": self.expiries, "service_telegrams": self.service.telegrams,
                "variable_requests": self.variables.requests}

    # -- the image ------------------------------------------------------------------------------

    @property
    def out_words(self) -> int:
        return OUT_WORDS_F1 if self.settings.format == 1 else OUT_WORDS

    @property
    def in_words(self) -> int:
        return IN_WORDS_F1 if self.settings.format == 1 else IN_WORDS

    def input_area(self) -> list[int]:
        data = self.rt.image.data
        q = [data[i] for i in _Q2]
        words = self.service.words() + [q[0] | q[1] << 8, q[2] | q[3] << 8, q[4] | q[5] << 8, self.diagnostic()]
        if self.settings.format != 1:
            words += self.variables.words()
        return words

    def diagnostic(self) -> int:
        try:
            return int(fault_code(self.rt), 16) & 0xFFFF
        except ValueError:
            return 0xFF

    def _io_to_image(self) -> None:
        data = self.rt.image.data
        for k in range(3):
            word = self.out[_IO + k]
            data[_I2[2 * k]], data[_I2[2 * k + 1]] = word & 0xFF, word >> 8

    def _set_v046(self) -> None:
        self.rt.memory.variables.set_system(46, self.watchdog_ms * 1_000_000)

    # -- RegisterEndpoint ---------------------------------------------------------------------------

    def _check_active(self) -> None:
        if self._taken and not self.settings.address_ok:
            raise _refused(f"the Profibus card is not running: B008 slave address {self.settings.address:02d}, allowed 02-89", 4)

    def read_registers(self, kind: str, address: int, count: int) -> list[int]:
        if kind not in ("holding", "input"):
            raise _refused(f"register kind {kind!r} is not served")
        end = address + count
        if address >= WATCHDOG_TIME and end <= WATCHDOG_STATUS + 1:
            return [(self.watchdog_ms, self.watchdog_status)[a - WATCHDOG_TIME] for a in range(address, end)]
        self._check_active()
        if kind == "input":
            base, size, words = 0, self.in_words, self.input_area
        elif address >= INPUT_READBACK:
            base, size, words = INPUT_READBACK, self.in_words, self.input_area
        else:
            base, size, words = 0, self.out_words, lambda: self.out[: self.out_words]
        if not (base <= address and end <= base + size):
            raise _refused(
                f"registers {address:#06x}..{end - 1:#06x} ({kind}) are not all in the CLM's DP image: output area "
                f"0x0000..{self.out_words - 1:#06x} (FC3), input area 0x0000..{self.in_words - 1:#06x} (FC4) or "
                f"{INPUT_READBACK:#06x}..{INPUT_READBACK + self.in_words - 1:#06x} (FC3), watchdog {WATCHDOG_TIME:#06x}/{WATCHDOG_STATUS:#06x}"
                + (" (B008 format 1: no variable channel)" if self.settings.format == 1 else "")
            )
        return words()[address - base: end - base]

    def write_registers(self, address: int, values: list[int]) -> None:
        if not self.network_writes:
            raise _refused("writes from the network are not enabled (serve --allow-writes)")
        end = address + len(values)
        if address == WATCHDOG_TIME and end == WATCHDOG_TIME + 1:
            self.watchdog_ms = int(values[0])
            self._set_v046()
            return
        self._check_active()
        if not (0 <= address and end <= self.out_words):
            raise _refused(
                f"registers {address:#06x}..{end - 1:#06x} are not writable: the output area is 0x0000..{self.out_words - 1:#06x}"
                + (" (B008 format 1: no variable channel)" if self.settings.format == 1 else "")
                + f", the watchdog time {WATCHDOG_TIME:#06x}"
            )
        if any(not 0 <= v <= 0xFFFF for v in values):
            raise _refused("a register holds 0..65535", 3)
        self.out[address:end] = [int(v) for v in values]
        self._last_write = self.rt.cycle
        self.watchdog_status = WD_RUNNING
        if address < _IO + 3 and end > _IO:
            self._io_to_image()
        if end > 0 and address < _IO:
            self.service.exchange(self.out[:_IO])
        if self.settings.format != 1 and end > 9:
            o = self.out
            self.variables.exchange(o[9], o[10], words_long(o[11], o[12]))
