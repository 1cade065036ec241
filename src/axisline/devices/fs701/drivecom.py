"""FS701 serial register access: the Drivecom protocol (after ISO 1745) that motrona units use.

The FS701 manual gives the serial *settings* (§4.3.6: unit address 11..99, baud rate, data
format 7E1 by default) and the serial *codes* of every register (§11), but not the telegram
format (spec §6 [GAP]). The framing below is the one motrona documents for its units (the
"SERPRO" Drivecom description quoted in their device manuals); the decisions at the end say
how the FS701's 4-digit serial codes and its broadcast addresses fit into it.

Control characters::

    EOT 0x04   start of a telegram from the master (also aborts any telegram in progress)
    STX 0x02   start of text (data)
    ETX 0x03   end of text
    ENQ 0x05   end of a read request
    ACK 0x06   write accepted
    NAK 0x15   telegram refused (nothing was changed)

Fields::

    AD1 AD2    unit address as two ASCII decimal digits: address 11 -> "1" "1" (0x31 0x31)
    C1 C2      register code: the serial code's high byte (C1) and low byte (C2), each as two
               ASCII hex digits -> four characters, the manual's hex code: 0x0105 -> "0105"
    data       value text: the raw register value in decimal, "-" if negative, no leading zeros,
               decimals implied by the register (Sync Rate 1.50 % -> "150"); see registers.py
    BCC        block check character: XOR of every byte after STX up to and including ETX

Telegrams::

    read request   EOT AD1 AD2 C1 C2 ENQ
    read reply     STX C1 C2 data ETX BCC          (NAK if the request is refused)
    write          EOT AD1 AD2 STX C1 C2 data ETX BCC
    write reply    ACK, or NAK (nothing changed)

Examples (unit address 11, factory default)::

    read Cutting Length (0x0000):     04 31 31 30 30 30 30 05          EOT "11" "0000" ENQ
    reply, value 1000:                02 30 30 30 30 31 30 30 30 03 02 STX "0000" "1000" ETX BCC
    write +/- Sync Rate (0x0105) = -1.25 %:
                                      04 31 31 02 30 31 30 35 2D 31 32 35 03 1C
                                                                       EOT "11" STX "0105" "-125" ETX BCC
    reply:                            06                                ACK

`DrivecomEndpoint.session().feed(bytes) -> bytes` frames a byte stream as a unit on an RS485 bus
does (one session per connection: one client's unfinished telegram never frames another's bytes;
`DrivecomEndpoint.feed` is the endpoint's own session):

* telegrams may arrive in pieces over several calls; several may arrive in one call;
* bytes outside a telegram (line noise, replies of other units) are skipped up to the next EOT;
* an EOT inside a telegram abandons it (the master restarted) - except in the BCC position,
  where any byte value is the check character;
* a telegram for another address is parsed to its end (so its BCC cannot be mistaken for an
  EOT) and ignored without a reply;
* a malformed telegram for this unit (bad code, no ENQ, control character in the data, too
  long), a bad BCC, an unknown register, a read-only register, a value out of range, a
  refused command or a write while writes are not allowed: NAK, and nothing is changed.

Decisions (spec line -> choice -> why):

* spec §6 [GAP] framing: the motrona Drivecom framing above (the brief's EOT/STX/ETX/ENQ
  telegrams, BCC = XOR after STX through ETX).
* Register code width: motrona's compact units use two code characters; the FS701's serial
  codes are 16-bit (0x0000..0x0B05, §11), which two 7-bit characters cannot carry (the
  default data format is 7E1). C1 and C2 are therefore the high and low byte of the code,
  each sent as two ASCII hex digits: four characters, exactly the 4-digit hex codes the
  manual prints. Upper and lower case hex are accepted; replies use upper case.
  (`CODE_CHARS`; one constant to change if a unit trace shows otherwise.)
* Address: "Address numbers containing zeros like 01, 02, 03, ..., 10, 20, etc. are not
  permitted because these are reserved for broadcast messages (collective addressing of
  several units)" (§4.3.6). A "0" in an address digit is a wildcard: "00" addresses every
  unit, "10" every unit whose first digit is 1, "01" every unit whose second digit is 1. A
  broadcast write is executed but never answered (several units would answer at once); a
  broadcast read is ignored.
* Value text on the wire: raw integer with implied decimals (spec §6 "decimal with fixed
  implied decimals per register"); writes may also use the decimal point with exactly the
  register's decimals ("1.25" = "125" for Sync Rate).
* The endpoint's address: `address=11` (factory default) as given; `address=None` follows the
  register "Ser Unit Address" (0x02C5) live, so a new address written over the link applies
  from the next telegram (the write itself is acknowledged under the old address).
* Read requests of unknown registers are answered NAK (a compact motrona unit may answer
  "STX C1 C2 EOT"; one refusal form keeps the client simple).
* Data longer than 16 characters or a telegram of more than 32 bytes is malformed (NAK) so a
  stream without ETX cannot grow a buffer without bound.
* No time-outs inside the endpoint (it has no clock): the transport calls `reset()` after an
  inter-character pause to drop a partial telegram.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from .registers import RegisterError, RegisterMap, register

__all__ = [
    "EOT",
    "STX",
    "ETX",
    "ENQ",
    "ACK",
    "NAK",
    "CODE_CHARS",
    "DEFAULT_ADDRESS",
    "DrivecomError",
    "bcc",
    "encode_address",
    "encode_code",
    "build_read",
    "build_write",
    "build_reply",
    "Reply",
    "parse_reply",
    "DrivecomEndpoint",
    "DrivecomSession",
    "DrivecomClient",
]

EOT, STX, ETX, ENQ, ACK, NAK = 0x04, 0x02, 0x03, 0x05, 0x06, 0x15
CODE_CHARS = 4
DEFAULT_ADDRESS = 11
MAX_DATA = 16
MAX_TELEGRAM = 32
_HEX = frozenset(b"0123456789ABCDEFabcdef")
_DIGITS = frozenset(b"0123456789")


class DrivecomError(ValueError):
    """A telegram or reply that is not valid Drivecom, or a NAK."""


def bcc(body: bytes) -> int:
    """Block check character: XOR of the bytes (those after STX, through ETX)."""
    x = 0
    for b in body:
        x ^= b
    return x


def _check_address(address: int, *, broadcast: bool = False) -> int:
    if isinstance(address, bool) or not isinstance(address, int) or not 0 <= address <= 99:
        raise DrivecomError(f"unit address {address!r} is outside 0..99")
    if not broadcast and (address < 11 or "0" in f"{address:02d}"):
        raise DrivecomError(f"unit address {address:02d} is not a unit address (11..99 without a digit 0)")
    return address


def encode_address(address: int, *, broadcast: bool = False) -> bytes:
    """AD1 AD2: 11 -> b"11". broadcast=True allows the collective addresses (a digit 0)."""
    return f"{_check_address(address, broadcast=broadcast):02d}".encode("ascii")


def encode_code(code: int) -> bytes:
    """C1 C2: 0x0105 -> b"0105"."""
    if isinstance(code, bool) or not isinstance(code, int) or not 0 <= code <= 0xFFFF:
        raise DrivecomError(f"register code {code!r} is outside 0x0000..0xFFFF")
    return f"{code:04X}".encode("ascii")


def _value_text(value: "int | str") -> bytes:
    text = str(value) if isinstance(value, int) and not isinstance(value, bool) else value
    if not isinstance(text, str) or not text or len(text) > MAX_DATA:
        raise DrivecomError(f"value {value!r} is not a value text of 1..{MAX_DATA} characters")
    raw = text.encode("ascii", errors="strict")
    if any(b < 0x20 or b > 0x7E for b in raw):
        raise DrivecomError(f"value {value!r} contains control characters")
    return raw


def build_read(address: int, code: int) -> bytes:
    """Read request EOT AD1 AD2 C1 C2 ENQ."""
    return bytes([EOT]) + encode_address(address) + encode_code(code) + bytes([ENQ])


def build_write(address: int, code: int, value: "int | str", *, broadcast: bool = False) -> bytes:
    """Write telegram EOT AD1 AD2 STX C1 C2 data ETX BCC (value: raw int or value text)."""
    body = encode_code(code) + _value_text(value) + bytes([ETX])
    return bytes([EOT]) + encode_address(address, broadcast=broadcast) + bytes([STX]) + body + bytes([bcc(body)])


def build_reply(code: int, text: str) -> bytes:
    """Read reply STX C1 C2 data ETX BCC."""
    body = encode_code(code) + _value_text(text) + bytes([ETX])
    return bytes([STX]) + body + bytes([bcc(body)])


@dataclass(frozen=True, slots=True)
class Reply:
    kind: str  # "data", "ack" or "nak"
    code: int | None = None
    text: str | None = None

    @property
    def value(self) -> int:
        if self.text is None:
            raise DrivecomError(f"a {self.kind} reply has no value")
        return int(self.text)


def parse_reply(data: bytes) -> Reply:
    """Parse one complete reply (ACK, NAK or STX .. ETX BCC); checks the BCC."""
    if data == bytes([ACK]):
        return Reply("ack")
    if data == bytes([NAK]):
        return Reply("nak")
    if len(data) < 2 + CODE_CHARS + 2 or data[0] != STX or data[-2] != ETX:
        raise DrivecomError(f"not a Drivecom reply: {data!r}")
    body = data[1:-1]
    if bcc(body) != data[-1]:
        raise DrivecomError(f"bad BCC in reply {data!r}: 0x{data[-1]:02X}, expected 0x{bcc(body):02X}")
    code_field, text = body[:CODE_CHARS], body[CODE_CHARS:-1]
    if not set(code_field) <= _HEX or not text:
        raise DrivecomError(f"malformed reply {data!r}")
    return Reply("data", int(code_field, 16), text.decode("ascii"))


# --------------------------------------------------------------------------------------------
# the unit side

_IDLE, _ADDR, _KIND, _READ, _WRITE, _BCC = range(6)


class DrivecomEndpoint:
    """One FS701 on a Drivecom bus: bytes in, reply bytes out (see module doc).

    The unit (address, register map, counters) is one; every connection frames its own
    telegrams in a `session()`. `feed` and `reset` are the endpoint's own session, for
    in-process callers."""

    def __init__(
        self,
        register_map: RegisterMap,
        address: int | None = DEFAULT_ADDRESS,
        *,
        writes_allowed: bool | Callable[[], bool] = True,
    ) -> None:
        if address is not None:
            _check_address(address)
        self.regmap = register_map
        self._address = address
        self.writes_allowed = writes_allowed
        self.telegrams = 0  # complete telegrams for this unit (incl. refused ones)
        self.naks = 0
        self.ignored = 0  # telegrams for other units
        self._session = DrivecomSession(self)

    @property
    def address(self) -> int:
        return self._address if self._address is not None else self.regmap.params.get_raw("ser_unit_address")

    def session(self) -> "DrivecomSession":
        """A telegram parser of its own for one connection (see `DrivecomSession`)."""
        return DrivecomSession(self)

    def reset(self) -> None:
        """Drop a partial telegram (call after an inter-character time-out)."""
        self._session.reset()

    def feed(self, data: bytes) -> bytes:
        return self._session.feed(data)

    # ---- addressing -------------------------------------------------------------------------
    def _addressed(self, a: bytes) -> str:
        """"unit", "broadcast" or "" (another unit) for the address field `a`."""
        own = f"{self.address:02d}".encode("ascii")
        if a == own:
            return "unit"
        if (a[0:1] == b"0" or a[0] == own[0]) and (a[1:2] == b"0" or a[1] == own[1]) and b"0" in a:
            return "broadcast"
        return ""

    def _malformed(self, addr: bytes, out: bytearray) -> None:
        target = self._addressed(addr)
        if target == "unit":
            self.telegrams += 1
            self._nak(out)
        elif not target:
            self.ignored += 1

    def _nak(self, out: bytearray) -> None:
        self.naks += 1
        out.append(NAK)

    # ---- telegrams --------------------------------------------------------------------------
    def _finish_read(self, addr: bytes, code_field: bytes, out: bytearray) -> None:
        target = self._addressed(addr)
        if target != "unit":  # other unit, or a broadcast read nobody may answer
            self.ignored += target == ""
            return
        self.telegrams += 1
        if len(code_field) != CODE_CHARS:
            self._nak(out)
            return
        code = int(code_field, 16)
        try:
            text = self.regmap.read_text(code)
        except RegisterError:
            self._nak(out)
            return
        out += build_reply(code, text)

    def _finish_write(self, addr: bytes, body: bytes, check: int, out: bytearray) -> None:
        """`body`: C1 C2 data ETX; `check`: the BCC received."""
        target = self._addressed(addr)
        if not target:
            self.ignored += 1
            return
        reply = target == "unit"
        if reply:
            self.telegrams += 1
        ok = (
            bcc(body) == check
            and len(body) > CODE_CHARS + 1
            and len(body) - CODE_CHARS - 1 <= MAX_DATA
            and set(body[:CODE_CHARS]) <= _HEX
        )
        if ok:
            allowed = self.writes_allowed() if callable(self.writes_allowed) else self.writes_allowed
            ok = bool(allowed)
        if ok:
            code = int(body[:CODE_CHARS], 16)
            try:
                register(code)
                self.regmap.write_text(code, body[CODE_CHARS:-1].decode("ascii"))
            except RegisterError:
                ok = False
        if reply:
            if ok:
                out.append(ACK)
            else:
                self._nak(out)


class DrivecomSession:
    """One connection's telegram framing on a `DrivecomEndpoint`: ``feed(bytes) -> bytes``.

    Its own state, so a telegram one client leaves unfinished dies with its connection: a
    write cut off before its BCC would otherwise take the next client's EOT as that BCC and
    swallow the read request behind it."""

    def __init__(self, endpoint: DrivecomEndpoint) -> None:
        self.endpoint = endpoint
        self.reset()

    def reset(self) -> None:
        """Drop a partial telegram (call after an inter-character time-out)."""
        self._state = _IDLE
        self._buf = bytearray()  # address, then code (+ data)
        self._addr = b""

    def feed(self, data: bytes) -> bytes:
        out = bytearray()
        for b in data:
            self._byte(b, out)
        return bytes(out)

    def _byte(self, b: int, out: bytearray) -> None:
        state = self._state
        if state == _BCC:
            self._state = _IDLE
            self.endpoint._finish_write(self._addr, bytes(self._buf), b, out)
            return
        if b == EOT:  # start of a telegram; abandons one in progress
            self._state, self._buf, self._addr = _ADDR, bytearray(), b""
            return
        if state == _IDLE:
            return  # noise, replies of other units, ACK/NAK of a master
        if state == _ADDR:
            if b not in _DIGITS:
                self._state = _IDLE  # cannot tell whom it was for: stay silent
                return
            self._buf.append(b)
            if len(self._buf) == 2:
                self._addr, self._buf = bytes(self._buf), bytearray()
                self._state = _KIND
            return
        if state == _KIND:
            if b == STX:
                self._state = _WRITE
                return
            self._state = _READ  # first code character of a read request
            state = _READ
        if state == _READ:
            if b == ENQ:
                self._state = _IDLE
                self.endpoint._finish_read(self._addr, bytes(self._buf), out)
                return
            if len(self._buf) >= CODE_CHARS or b not in _HEX:
                self._malformed(out)
                return
            self._buf.append(b)
            return
        # _WRITE
        if b == ETX:
            self._buf.append(b)
            self._state = _BCC
            return
        if b < 0x20 or b > 0x7E or len(self._buf) >= MAX_TELEGRAM:
            self._malformed(out)
            return
        self._buf.append(b)

    def _malformed(self, out: bytearray) -> None:
        self._state = _IDLE
        self.endpoint._malformed(self._addr, out)


# --------------------------------------------------------------------------------------------
# the master side


class DrivecomClient:
    """A Drivecom master over a transport `send(bytes) -> reply bytes` (e.g. endpoint.feed)."""

    def __init__(self, transport: Callable[[bytes], bytes], address: int = DEFAULT_ADDRESS) -> None:
        self.transport = transport
        self.address = _check_address(address)

    def read_text(self, code: int) -> str:
        reply = parse_reply(self.transport(build_read(self.address, code)))
        if reply.kind != "data":
            raise DrivecomError(f"read 0x{code:04X}: unit answered {reply.kind.upper()}")
        if reply.code != code:
            raise DrivecomError(f"read 0x{code:04X}: reply is for 0x{reply.code:04X}")
        return reply.text or ""

    def read(self, code: int) -> int:
        """Raw value of a register."""
        return int(self.read_text(code))

    def write(self, code: int, value: "int | str") -> None:
        """Write a raw value or value text; DrivecomError on NAK."""
        reply = parse_reply(self.transport(build_write(self.address, code, value)))
        if reply.kind != "ack":
            raise DrivecomError(f"write 0x{code:04X} = {value!r}: unit answered {reply.kind.upper()}")
