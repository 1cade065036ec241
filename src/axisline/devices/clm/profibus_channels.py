"""The two handshake channels of the CLM's Profibus DP image: the variable channel and the
service data channel (manual §10.1 L7692-8036; spec §9.4, §9.5; errata 4, 5, 7, 12).

    vc = VariableChannel(memory.variables)
    vc.exchange(read_control, write_control, data)    # the master's 4 words -> nothing
    vc.words()                                        # [read status, write status, data hi, data lo]

    sc = ServiceChannel(serial_endpoint)              # a `serial.ClmSerialEndpoint`
    sc.exchange([control, d1, d2, d3, d4, d5])        # the master's 6 words
    sc.words()                                        # [status, d1 .. d5]

Words are 16-bit values as Profibus sends them (big-endian: the high byte first on the wire);
a long is two words, the high word first. Both channels act when the master's handshake bit
differs from the one the CLM sent (the variable channel's bit 15, the service channel's toggle
bit 8), so a master that writes the same words again changes nothing.

Variable channel (4 words each way): read control word, write control word, data long (master
-> CLM); read status word, write status word, data long (CLM -> master). A control word holds
the variable number (bits 0-9), the format (bits 10-13), bit 14 (must be 0) and the handshake
bit 15; the status word echoes number and format, or sets bit 14 and puts the error number in
bits 10-13, and toggles its bit 15 to the control word's.

Service data channel (6 words): control/status word + 10 data bytes carrying the X6 serial
protocol (`serial`) without checksum, station and CR LF. Control and status word (the bit rows
of Figs. 10-18..10-32, spec §9.5): bit 15 C (reserved), 13 E (error, status only), 12 R/W
(1 = read), 10 L (last fragment), 8 T (toggle), 7-4 length (valid data bytes), 3-0 format
(0xB; 0xF = terminate). A write request's fragments are collected until L, then the telegram
runs in the serial session; its answer is fetched by read requests, 10 bytes a fragment.

Decisions (spec line -> choice, why)
------------------------------------
1. Variable formats, L7759-7771 ("for the two types of fixed point formats, the places after
   the decimal are always rounded; for the integer format, only the places before the
   decimal"): format 0 rounds half away from zero to an integer, 4 truncates toward zero,
   1 is the value x 1000 rounded, 2 the value x 10^6; a value whose long would exceed
   +-99999999 (the range of every format, L7767-7771) is error 3 "data too large" (positive)
   or 4 "data too small" (negative), on read and on write. Test:
   ``test_profibus_channels.py::test_variable_formats_round_and_limit``,
   ``test_variable_format_ranges``.
2. Format 3 (IEEE, "in preparation", L7770) is error 5 "data not displayable (IEEE)", formats
   5-15 error 2 "unknown format": the CLM names IEEE among its errors, so it knows the code.
   Test: ``test_variable_channel_errors``.
3. Variable numbers, L7785 and spec §9.4: 1000-1023 (the 10-bit field's rest) are error 0
   "too large"; V000-V599 are read-only over the channel: a write is error 6 "not writable";
   error 1 "illegal" has no case, as every number 0-999 is a CLM variable (the serial
   interface reads each). Bit 14 set is error 7, checked first. Test:
   ``test_variable_channel_errors``.
4. A read and a write requested in the same exchange: the write is done first, so the read
   returns the new value. The CLM's data long holds the last read's value (0 after a read
   error); a write leaves it. Test: ``test_variable_write_then_read_same_exchange``.
5. Service channel handshake, L7845/L7864 and errata 5 (Fig. 10-21 prints T = 0 though its
   text says "set to 1"): the status word's T is always the master's T of the request it
   answers (the figures' rows), and a request is new when the master's T differs from the T
   the CLM sent. Test: ``test_profibus_modbus.py::test_reading_a_value_l7870``.
6. "Only the checksum, station number and CR LF ... are disregarded" (L7798): the station byte
   (the telegram's second byte) is taken as a blank whatever it holds, a ``$hh`` that is
   present is still verified (serial decision 3), CR LF at the end of the data are dropped; a
   CR or LF inside the data is serial error 02 (one telegram per service). The session's
   settings are fixed (station 0, no checksum needed, no ``Y`` of its own): B003 belongs to
   X6. Test: ``test_service_station_and_crlf_disregarded``.
7. Replies: the serial reply without ``$hh`` and CR LF, its blanks kept (``# N0000 NOP   ``,
   14 bytes, L7888/L7905). A refused telegram answers the write request with E = 1 and the
   error code 0x01nn (nn the Status 01 number, decimal on the serial line, so "12" is 0x0C,
   errata 7, L7998); the read that follows returns the plain text ``X 01 12 Block # too large``
   without the 20-character padding (errata 12: 25 bytes in 10 + 10 + 5, L8001-8008), with
   '#' (0x23) where the manual prints 0x2C under a '#' glyph (errata 4). A write the CLM took
   answers the next read with ``Y `` (L7975, Fig. 10-28) whatever B003 says. Tests:
   ``test_profibus_modbus.py::test_error_reply_plain_text_l7996``,
   ``test_profibus_modbus.py::test_writing_a_value_l7914``.
8. Error codes the CLM's card raises here (Fig. 10-30): format neither 0xB nor 0xF 0x008B,
   length above 10 0x008C, collected fragments above 128 bytes 0x0085, a reply above 128
   bytes 0x01FF; a read request with nothing to read gets an empty last fragment (length 0,
   L = 1). 0x0088, 0x008A, 0x008D, 0x0090, 0x0095, 0x0096, 0x009A-0x009D, 0x00F0 name card
   internals or SERCOS-style indices that this channel has no case for (the format is always
   B, so it cannot change during collection). Test: ``test_service_error_codes``.
9. Terminate (L8014, Fig. 10-32): format 0xF with T toggled drops the collected fragments and
   any reply not yet read; the status word echoes the control word. Test:
   ``test_profibus_modbus.py::test_terminate_drops_the_reply_l8014``.
10. Serial decision 12 (an acknowledged write is stored): a variable written over the variable
    channel is saved to the memory file before the status word acknowledges it; when it
    cannot be saved the write is undone and answered with error 6 "not writable" (the only
    error number that says the variable was not written). The service channel's telegrams go
    through the serial session, which does the same. Test: ``test_variable_write_is_stored``.
"""

from __future__ import annotations

import sys
from collections.abc import Callable
from typing import Any

from .fields import USER_VARIABLES
from .memory import VARIABLE_COUNT

__all__ = [
    "FORMAT_B", "FORMAT_TERMINATE", "MAX_MESSAGE", "ServiceChannel", "VariableChannel",
    "from_long", "long_words", "to_long", "words_long",
]

_SCALE = 1_000_000
LIMIT = 99_999_999  # every format's range in its long (L7767-7771)

# variable channel error numbers (Fig. 10-14 list, L7775-7783)
E_TOO_LARGE_NUMBER, E_ILLEGAL, E_FORMAT, E_DATA_LARGE, E_DATA_SMALL, E_IEEE, E_NOT_WRITABLE, E_BIT14 = range(8)
_HS = 0x8000
_BIT14 = 0x4000

# service channel
FORMAT_B = 0xB
FORMAT_TERMINATE = 0xF
MAX_MESSAGE = 128  # bytes a message may have (L7861)
FRAGMENT = 10  # data bytes in the 5 data words
C_BIT, E_BIT, R_BIT, L_BIT, T_BIT = 0x8000, 0x2000, 0x1000, 0x0400, 0x0100
ERR_TOO_MUCH = 0x0085
ERR_FORMAT = 0x008B
ERR_LENGTH = 0x008C
ERR_REPLY_LENGTH = 0x01FF


def to_long(raw: int, fmt: int) -> int:
    """A variable (integer millionths) as the channel's long in format 0, 1, 2 or 4 (decision 1);
    ValueError(error number) when it does not fit."""
    if fmt == 0:
        q, r = divmod(abs(raw), _SCALE)
        value = (q + (2 * r >= _SCALE)) * (1 if raw >= 0 else -1)
    elif fmt == 4:
        value = int(abs(raw) // _SCALE) * (1 if raw >= 0 else -1)
    elif fmt == 1:
        q, r = divmod(abs(raw), 1000)
        value = (q + (2 * r >= 1000)) * (1 if raw >= 0 else -1)
    elif fmt == 2:
        value = raw
    else:
        raise ValueError(E_IEEE if fmt == 3 else E_FORMAT)
    if value > LIMIT:
        raise ValueError(E_DATA_LARGE)
    if value < -LIMIT:
        raise ValueError(E_DATA_SMALL)
    return value


def from_long(value: int, fmt: int) -> int:
    """The channel's long in `fmt` as a variable in integer millionths (decision 1)."""
    if fmt not in (0, 1, 2, 4):
        raise ValueError(E_IEEE if fmt == 3 else E_FORMAT)
    if value > LIMIT:
        raise ValueError(E_DATA_LARGE)
    if value < -LIMIT:
        raise ValueError(E_DATA_SMALL)
    return value * (1000 if fmt == 1 else 1 if fmt == 2 else _SCALE)


def long_words(value: int) -> list[int]:
    """A signed 32-bit long as two words, the high word first (Profibus byte order)."""
    u = value & 0xFFFFFFFF
    return [u >> 16, u & 0xFFFF]


def words_long(high: int, low: int) -> int:
    u = (high & 0xFFFF) << 16 | (low & 0xFFFF)
    return u - (1 << 32) if u & 0x80000000 else u


class VariableChannel:
    """The variable channel of one CLM (see the module docstring)."""

    def __init__(self, variables: Any, store: Callable[[], object] | None = None) -> None:
        self.variables = variables
        self._store = store  # saves the retained memory (OSError if it cannot), decision 10
        self.read_status = 0
        self.write_status = 0
        self.data = 0  # the long the CLM sends
        self.requests = 0

    def words(self) -> list[int]:
        return [self.read_status, self.write_status, *long_words(self.data)]

    def exchange(self, read_control: int, write_control: int, data: int) -> None:
        """The master's words; a toggled handshake bit is a request (write first, decision 4)."""
        if (write_control ^ self.write_status) & _HS:
            self.write_status = self._write(write_control, data)
            self.requests += 1
        if (read_control ^ self.read_status) & _HS:
            self.read_status = self._read(read_control)
            self.requests += 1

    @staticmethod
    def _check(control: int, writing: bool) -> tuple[int, int]:
        if control & _BIT14:
            raise ValueError(E_BIT14)
        number, fmt = control & 0x3FF, control >> 10 & 0xF
        if number >= VARIABLE_COUNT:
            raise ValueError(E_TOO_LARGE_NUMBER)
        if fmt not in (0, 1, 2, 4):
            raise ValueError(E_IEEE if fmt == 3 else E_FORMAT)
        if writing and number < USER_VARIABLES:
            raise ValueError(E_NOT_WRITABLE)
        return number, fmt

    def _read(self, control: int) -> int:
        try:
            number, fmt = self._check(control, writing=False)
            self.data = to_long(self.variables[number], fmt)
        except ValueError as e:
            self.data = 0
            return _error_status(control, int(e.args[0]))
        return control & (_HS | 0x3FFF)

    def _write(self, control: int, data: int) -> int:
        try:
            number, fmt = self._check(control, writing=True)
            variables = self.variables
            old, version = variables.values[number], variables.version
            variables.write(number, from_long(data, fmt), by="serial")
        except ValueError as e:  # ClmError is a ValueError too (its code is not a number here)
            code = e.args[0] if isinstance(e.args[0], int) else E_DATA_LARGE
            return _error_status(control, code)
        if self._store is not None and variables.version != version:
            try:
                self._store()
            except OSError as e:  # decision 10: not stored, not done
                variables.values[number], variables.version = old, version
                print(f"clm profibus: V{number:03d} not stored ({e.strerror or e}); undone", file=sys.stderr, flush=True)
                return _error_status(control, E_NOT_WRITABLE)
        return control & (_HS | 0x3FFF)


def _error_status(control: int, error: int) -> int:
    return (control & (_HS | 0x3FF)) | _BIT14 | (error & 0xF) << 10


def _data_bytes(words: list[int]) -> bytes:
    return b"".join(bytes(((w >> 8) & 0xFF, w & 0xFF)) for w in words)


def _data_words(data: bytes) -> list[int]:
    padded = data.ljust(FRAGMENT, b"\0")
    return [padded[2 * k] << 8 | padded[2 * k + 1] for k in range(FRAGMENT // 2)]


class ServiceChannel:
    """The service data channel on a serial endpoint (see the module docstring)."""

    def __init__(self, endpoint: Any) -> None:
        self.endpoint = endpoint  # serial.ClmSerialEndpoint (its settings fixed, decision 6)
        self.session = endpoint.session()
        self.status = 0
        self.data = b""  # the data bytes the CLM sends (<= 10)
        self._collected = bytearray()
        self._reply = b""  # what the read requests fetch
        self.telegrams = 0  # telegrams run (the summary's count)
        self.last_telegram = b""

    def words(self) -> list[int]:
        return [self.status, *_data_words(self.data)]

    def exchange(self, words: list[int]) -> None:
        control = words[0]
        if not (control ^ self.status) & T_BIT:
            return  # not new (decision 5)
        toggle, read = control & T_BIT, control & R_BIT
        fmt, length = control & 0xF, control >> 4 & 0xF
        if fmt == FORMAT_TERMINATE:  # decision 9
            self._collected.clear()
            self._reply = b""
            self._send(control & ~E_BIT & 0xFFFF, b"")
            return
        if fmt != FORMAT_B:
            return self._error(toggle | read, ERR_FORMAT)
        if read:
            return self._read(toggle)
        if length > FRAGMENT:
            return self._error(toggle, ERR_LENGTH)
        if len(self._collected) + length > MAX_MESSAGE:
            self._collected.clear()
            return self._error(toggle, ERR_TOO_MUCH)
        self._collected += _data_bytes(words[1:6])[:length]
        if not control & L_BIT:  # more fragments follow: "a copy ... length 0 and the L-Bit set" (Fig. 10-25)
            self._send(toggle | L_BIT | FORMAT_B, b"")
            return
        message = bytes(self._collected)
        self._collected.clear()
        code = self._run(message)
        if code:
            return self._error(toggle, code)
        self._send(toggle | L_BIT | FORMAT_B, b"")

    def _read(self, toggle: int) -> None:
        part, self._reply = self._reply[:FRAGMENT], self._reply[FRAGMENT:]
        last = L_BIT if not self._reply else 0
        self._send(toggle | R_BIT | last | len(part) << 4 | FORMAT_B, part)

    def _send(self, status: int, data: bytes) -> None:
        self.status, self.data = status, data

    def _error(self, bits: int, code: int) -> None:
        self._send(bits | E_BIT | L_BIT | 2 << 4 | FORMAT_B, bytes((code >> 8, code & 0xFF)))

    def _run(self, message: bytes) -> int:
        """Run one telegram in the serial session; the error code to answer, 0 when taken."""
        while message[-1:] in (b"\r", b"\n"):
            message = message[:-1]
        self._reply = b""
        if b"\r" in message or b"\n" in message or not message:
            self._reply = _plain_error(2)
            return 0x0100 | 2
        if len(message) >= 2:  # decision 6: the station byte is disregarded
            message = message[:1] + b" " + message[2:]
        self.telegrams += 1
        self.last_telegram = message
        answer = self.session.feed(message + b"\r\n")
        if answer.endswith(b"\r\n"):
            answer = answer[:-2]
        if len(answer) >= 3 and answer[-3:-2] == b"$":
            answer = answer[:-3]
        if answer.startswith(b"X 01 ") and answer[5:7].isdigit():  # a Status 01 error (decision 7)
            number = int(answer[5:7])
            self._reply = answer.rstrip(b" ")
            return 0x0100 | number
        if not answer:  # a write the CLM took
            self._reply = b"Y "
            return 0
        if len(answer) > MAX_MESSAGE:
            return ERR_REPLY_LENGTH
        self._reply = answer
        return 0


def _plain_error(number: int) -> bytes:
    from .errors import SERIAL_ERRORS

    return f"X 01 {number:02d} {SERIAL_ERRORS.get(number, '')}".rstrip().encode("ascii")
