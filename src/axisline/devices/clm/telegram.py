"""The CLM serial telegram: framing, station byte, checksum (manual §9.2, L6380-6540; spec §8.2-8.3).

    <c1><s><c3><information ...>[$hh]<CR><LF>

``c1`` is ``?`` query, ``#`` write (``!`` is accepted instead of ``#`` for parameters, "for
compatibility to older firmware versions"), ``!`` interface command, ``:`` polling; the
CLM's replies begin with ``#`` (read-back), ``X`` (status), ``V`` (variable), ``P`` (Logic
Task) or are the confirmation ``Y``. ``s`` is the station: a blank on RS232, ``1``-``9``,
``A``-``W`` (10-32) on RS485. ``c3`` is the information type ``N`` program, ``K`` parameter,
``X`` status, ``P`` Logic Task, ``V`` variable.

The checksum (Fig. 9-12, L6470-6520) covers every character from the first control
character to the last one before ``$``, station and blanks included: the byte sum, its high
byte added to its low byte, then the two's complement of the low byte, as two upper-case hex
digits. The manual's two worked sums (``$C4``, ``$45``) are tests.

Parsing is tolerant where the manual's printed examples are (CR LF or CR or LF or nothing at
the end, `$hh` in either case); emitting is exact. A telegram that cannot be framed is refused
with Status 01 error 02 "RS Format Error", a wrong checksum with 04 "RS Checksum Error".

Decisions (spec line -> choice, why)
------------------------------------
1. C-CHECKSUM-OPTIONAL, L6370 "the checksum can be disregarded" when validation is off: a
   telegram without ``$hh`` is read unless the caller requires one (B003 validation on, and
   always for ``!`` commands, errata §1.13); a ``$hh`` that is present is always verified.
   Tests: ``test_lower_case_checksum_and_missing_checksum``.
"""

from __future__ import annotations

from dataclasses import dataclass

from .errors import ClmError, serial_code

__all__ = ["Telegram", "checksum", "emit", "parse_telegram", "station_char", "station_number"]

CONTROL = "?#!:"
REPLY = "XVPY"
KINDS = "NKXPV"
_STATIONS = " 123456789ABCDEFGHIJKLMNOPQRSTUVW"  # index = station number, 0 = the RS232 blank
_MAX_LINE = 200  # a telegram's information is at most 32 characters; anything far longer is garbage


def checksum(text: str | bytes) -> str:
    """The two hex digits of the CLM checksum over `text` (control character .. last before ``$``)."""
    data = text.encode("latin-1") if isinstance(text, str) else text
    total = sum(data)
    total = (total >> 8) + (total & 0xFF)
    return f"{(-total) & 0xFF:02X}"


def station_char(number: int) -> str:
    """``0`` (RS232) -> ``' '``, 1-9 -> ``'1'``-``'9'``, 10-32 -> ``'A'``-``'W'``."""
    if not 0 <= number <= 32:
        raise ValueError(f"station = {number}: allowed 0 (RS232) or 1..32 (RS485)")
    return _STATIONS[number]


def station_number(char: str) -> int:
    at = _STATIONS.find(char.upper()) if len(char) == 1 else -1
    if at < 0:
        raise ClmError(serial_code(2), f"station {char!r}: allowed a blank (RS232) or 1-9, A-W (RS485)")
    return at


@dataclass(frozen=True)
class Telegram:
    """One framed telegram. ``body`` is everything after the information type up to ``$``."""

    control: str  # '?', '#', '!', ':' (or a reply letter 'X', 'V', 'P', 'Y')
    station: int
    kind: str  # 'N', 'K', 'X', 'P', 'V' after '?' / '#'; '' otherwise (a reply's letter is its control)
    body: str
    checksum: str | None  # the two hex digits received, None when the telegram had none

    @property
    def text(self) -> str:
        """The checksummed part: control character .. last character before ``$``."""
        return f"{self.control}{station_char(self.station)}{self.kind}{self.body}"

    def emit(self, with_checksum: bool = True) -> str:
        return emit(self.control, self.station, self.kind, self.body, with_checksum)


def emit(control: str, station: int, kind: str, body: str, with_checksum: bool = True) -> str:
    """The telegram as the CLM sends it, ``CR LF`` included."""
    text = f"{control}{station_char(station)}{kind}{body}"
    return f"{text}${checksum(text)}\r\n" if with_checksum else f"{text}\r\n"


def parse_telegram(line: str | bytes, *, require_checksum: bool = False) -> Telegram:
    """Frame one telegram; verify its checksum when it carries one.

    Raises `ClmError` X01:02 (format) or X01:04 (checksum). `require_checksum` refuses a
    telegram without ``$hh`` (B003 checksum validation on, and always for ``!`` commands).
    """
    if isinstance(line, bytes):
        try:
            line = line.decode("ascii")
        except UnicodeDecodeError:
            raise ClmError(serial_code(2), "the telegram holds a byte that is not ASCII") from None
    if len(line) > _MAX_LINE:
        raise ClmError(serial_code(2), f"the telegram is {len(line)} characters long (at most {_MAX_LINE})")
    line = line.rstrip("\r\n")
    if not line.isascii() or not line.isprintable():
        raise ClmError(serial_code(2), "the telegram holds a control or non-ASCII character")
    if len(line) < 2 or line[0] not in CONTROL + REPLY:
        raise ClmError(serial_code(2), f"{line[:20]!r}: a telegram begins with ?, #, !, : (or a reply X, V, P, Y) and a station")
    control = line[0]
    station = station_number(line[1])
    received = None
    dollar = line.rfind("$")
    if dollar >= 0:
        received = line[dollar + 1 :].upper()
        line = line[:dollar]
        if len(received) != 2 or any(c not in "0123456789ABCDEF" for c in received):
            raise ClmError(serial_code(2), f"checksum {received[:8]!r}: two hex digits expected after $")
    if "$" in line:
        raise ClmError(serial_code(2), "more than one $ in the telegram")
    rest = line[2:]
    kind = ""
    if control in "?#" and rest[:1] in KINDS and rest:
        kind, rest = rest[0], rest[1:]
    if control in "?#" and not kind:
        raise ClmError(serial_code(2), f"{line[:20]!r}: the information type after the station must be N, K, X, P or V")
    if received is not None:
        expected = checksum(line)
        if received != expected:
            raise ClmError(serial_code(4), f"checksum ${received} received, ${expected} computed")
    elif require_checksum:
        raise ClmError(serial_code(4), "the telegram has no checksum ($hh) and checksum validation is on")
    return Telegram(control, station, kind, rest, received)
