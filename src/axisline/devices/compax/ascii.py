"""The COMPAX XX70 ASCII interface (RS232 / RS485) to the cam memory (compax.md §6.1; manual §25).

    from axisline.devices.compax.ascii import AsciiEndpoint
    endpoint = AsciiEndpoint(memory, parameters, commands=cam_operation, status=status)
    endpoint.feed(b"F6=0.1234567\\r")      # -> b"\\r\\n>"
    endpoint.feed(b"F6\\r")                # -> b"F0006=0.1234567\\r\\n>"

Bytes in, bytes out, no sockets: a transport (serial port, pty, TCP) takes one
`endpoint.session()` per connection, calls its `feed` with whatever it received and sends
back what `feed` returns; `endpoint.feed` is one such session for in-process callers.
Memory, parameters and status are the device's; only the half-received line belongs to
the session, so a line one client leaves unfinished cannot run into the next client's
("F6" + "P33<cr>" would read as "F6P33"). Lines may arrive in pieces;
<cr> ends a line, <lf> "has no meaning" and is dropped, spaces are ignored, letters may
be lower case.

Lines (the manual's examples are exact; the rest is marked in the decisions):

=========================  =======================================  ==========================
line                       does                                     reply (then <cr><lf>>)
=========================  =======================================  ==========================
F6=0 / F24=.9              write a set point (F format)             -
B7=001;2;003               write an aux function (B format)         -
I5460=360                  write a control block integer            -
F6 / I5460 / B7            read back                                F0006=0.1234567 / ...
RESETF                     whole cam memory to 0                    -
VF                         declare the cam memory valid             -
SETC n, SETM x, SETS,      cam commands, to the `CamCommands`       -
POSR CAM, LOOP m           handler (short forms SC, SM, SS, PR, LP;
                           n, x, m may be .P40 ... .P49)
POSA HOME                  machine datum travel (also during        -
                           cam operation, §2.11 exception)
P31=2 / P31                write / read a parameter                 P031=2
VP, VC, RESETP             parameter acceptance / reset             -
S44                        read a status value                      S044=350.000
=========================  =======================================  ==========================

"After each string COMPAX 70 sends back the sequence <cr>, <lf> and prompt (> = $3E)":
every line - also an empty or a wrong one - is answered and the answer ends with
<cr><lf>>. A wrong line changes nothing (the memory and the parameters stay as they were)
and is answered with ``!E<number> <what was wrong>``; S30 ("last error", the manual's way
to check a transfer) then holds the number. The numbers: E17 curve not present (the
manual's); E101 malformed line, E102 address out of range, E103 value does not fit, E104
reserved address, E105 unknown parameter / status, E107 command not available (axisline's,
see `axisline.devices.compax`). An error reply is at most `MAX_ERROR_REPLY` printable
ASCII characters and never holds a ">" before the prompt (`error_reply`, decision 1).

Decisions (spec line -> choice, why)
------------------------------------
1. §6.1 [GAP] error reply: the supplement only says errors are checked with S30 "last
   error"; the standard User Guide (not among our sources) says errors are reported
   "depending on P20". Chosen: ``!E<n> <text>`` before the usual <cr><lf>>, and S30 = n,
   so a host that only checks S30 and one that reads the reply both see it. The text is
   for a person: printable ASCII, ">" written out (" > " -> " more than ", " >= " ->
   " at least ", any other ">" -> "?", as a byte the reply cannot carry), cut at a word
   to at most 100 characters for the whole line (docs/compax.md "Error replies").
2. §6.1 read-back: "F6<cr>" -> "F0006=0.1234567<cr><lf>>" (address zero-padded to 4
   digits, 7 decimals; see `cammemory.format_fraction` for which 7 decimals). By the same
   pattern I reads back "I5460=360" (signed decimal) and B "B0007=1;10;246" (three
   unpadded decimals 0 ... 255, as in the manual's tables).
3. [GAP] parameter and status access: the standard device reads and writes parameters
   and reads status values over RS232 (§1 of the supplement lists "P210=1" as a command;
   S30 is read to check transfers); the forms "P<n>=<value>", "P<n>" -> "P031=2" and
   "S<n>" -> "S044=350.000" (3-digit numbers, status format of §20) are axisline's.
4. [GAP] line length: lines longer than 30 characters (the standard COMPAX entry buffer)
   are rejected with E101 as a whole.
5. "Before sending the next string, prompt must be ordered": a host that sends several
   lines at once gets each answer in order (the simulated device answers at once).
6. SETC n is checked against the valid cam memory before the handler sees it (E17 if
   the curve is not present, §22); SETM x must be 0 ... 100 (%), LOOP m 0 ... 65000
   (§9). ".P40" arguments take the valid value of P40 ... P49 (§9: "may also refer to
   the operation parameters (P40...P49)"). The handler does everything else (a curve
   must be selected first, P1 = 0 for POSR CAM, ...) and may raise CompaxError itself.
7. RESETF / VF take up to 1 s / 0.5 s on the device; the endpoint answers at once (the
   duration is in `CamMemory.vf()`'s result for a caller that simulates time).
"""

from __future__ import annotations

import re
from collections.abc import Callable
from typing import Protocol, runtime_checkable

from axisline.devices.compax import (
    E_NOT_AVAILABLE,
    E_SYNTAX,
    E_VALUE,
    CompaxError,
)
from axisline.devices.compax.cammemory import CamMemory, Fmt, decode_bytes, decode_int, format_fraction
from axisline.devices.compax.curves import read_curve
from axisline.devices.compax.parameters import Parameters
from axisline.devices.compax.status import StatusValues, format_status

__all__ = ["MAX_ERROR_REPLY", "MAX_LINE", "PROMPT", "AsciiEndpoint", "AsciiSession", "CamCommands", "error_reply"]

#: What ends every answer: <cr> <lf> and the prompt ">" ($3E).
PROMPT = b"\r\n>"
#: Longest line accepted (decision 4).
MAX_LINE = 30
#: Longest error reply before <cr><lf>> (decision 1): the host's receive buffer is not
#: ours to overrun, and a parameter list of E105 would otherwise run to 450 characters.
MAX_ERROR_REPLY = 100


@runtime_checkable
class CamCommands(Protocol):
    """The cam commands of §9, implemented by the cam operation (``camop``).

    Arguments arrive range-checked (decision 6). Raise `CompaxError` to refuse a command;
    its number and text go back to the host.
    """

    def setc(self, n: int) -> None:
        """SETC n: select curve n (exists in the valid cam memory)."""

    def setm(self, x: float) -> None:
        """SETM x: master position := x/100 · master cycle, 0 <= x <= 100."""

    def sets(self) -> None:
        """SETS: shift the curve so that the slave does not move."""

    def posr_cam(self) -> None:
        """POSR CAM: travel to the curve position of the actual master position."""

    def loop(self, m: int) -> None:
        """LOOP m: activate cam operation for m travels (0 = endless), 0 <= m <= 65000."""


_NUMBER = r"[+-]?(?:\d+(?:\.\d*)?|\.\d+)"
_INTEGER = r"[+-]?\d+"
_RE_MEMORY = re.compile(r"([IFB])(\d+)(?:=(.*))?")
_RE_PARAM = re.compile(r"P(\d+)(?:=(.*))?")
_RE_STATUS = re.compile(r"S(\d+)")
_RE_CAM = re.compile(r"(SETC|SC|SETM|SM|LOOP|LP)(.+)")
_RE_NUMBER = re.compile(_NUMBER)
_RE_INTEGER = re.compile(_INTEGER)
_RE_OPERATION_PARAM = re.compile(r"\.P(\d+)")
# error texts name formulas with a few non-ASCII signs; the line carries ASCII only
_ASCII = str.maketrans({"·": "*", "‰": " per mille", "≤": "<=", "≥": ">=", "±": "+/-", "²": "^2", "⁻": "^-",
                        "¹": "1", "§": "sec. "})
# the manual's host reads up to ">" (the prompt): a ">" in the text would end its read early
_GREATER = ((" >= ", " at least "), (" > ", " more than "), (">", "?"))


def error_reply(code: int, message: str) -> bytes:
    """The error line ``!E<code> <text>`` (without the prompt) of decision 1: printable
    ASCII, no ">", at most `MAX_ERROR_REPLY` characters."""
    text = " ".join(message.translate(_ASCII).split())  # one line: <cr> / <lf> / tabs as spaces
    for sign, words in _GREATER:
        text = text.replace(sign, words)
    text = "".join(c if " " <= c <= "~" else "?" for c in text)
    line = f"!E{code} {text}"
    if len(line) > MAX_ERROR_REPLY:
        cut = line[: MAX_ERROR_REPLY - 3]
        if " " in cut[len(f"!E{code} "):]:  # end at a word, not inside a number
            cut = cut.rsplit(" ", 1)[0]
        line = cut.rstrip(" ,;:") + "..."
    return line.encode("ascii")


def _echo(text: str) -> str:
    """The host's line as an error text shows it: its ">" as "?" (see `error_reply`), so
    that "F6 > 1" is not shown as "F6 more than 1"."""
    return text.strip().replace(">", "?")


def _syntax(line: str, what: str) -> CompaxError:
    return CompaxError(f"malformed line {_echo(line)!r}: {what}", code=E_SYNTAX, field="line", value=line)


class AsciiEndpoint:
    """The interface of one COMPAX: ``feed(bytes) -> bytes`` (see the module doc)."""

    def __init__(
        self,
        memory: CamMemory,
        parameters: Parameters,
        commands: CamCommands | None = None,
        status: StatusValues | None = None,
    ) -> None:
        self.memory = memory
        self.parameters = parameters
        self.commands = commands
        self.status = status if status is not None else StatusValues()
        #: the last error answered on any session (None before the first); S30 is the device's
        self.last_error: CompaxError | None = None
        self._session = AsciiSession(self)

    # -- transport side ---------------------------------------------------------------------

    def session(self) -> "AsciiSession":
        """A line buffer of its own for one connection (see the module doc)."""
        return AsciiSession(self)

    def feed(self, data: bytes) -> bytes:
        """Take received bytes; return the answers to every line they complete (the
        endpoint's own session: for in-process callers, not for a second connection)."""
        return self._session.feed(data)

    @property
    def pending(self) -> bytes:
        """Bytes of a line not yet ended by <cr> (the endpoint's own session)."""
        return self._session.pending

    def execute(self, line: str) -> bytes:
        """Answer one line (without its <cr>), as `feed` would."""
        return self._answer(line.encode("ascii", "replace"), len(line) > MAX_LINE)

    def _answer(self, raw: bytes, overlong: bool) -> bytes:
        try:
            if overlong:
                shown = raw.decode("ascii", "replace")
                raise CompaxError(f"line {shown!r}... longer than {MAX_LINE} characters", code=E_SYNTAX,
                                  field="line", value=shown)
            try:
                text = raw.decode("ascii")
            except UnicodeDecodeError:
                raise CompaxError(f"line {raw!r} holds a byte that is not ASCII", code=E_SYNTAX, field="line",
                                  value=raw) from None
            body = self._dispatch(text)
        except CompaxError as exc:
            self.last_error = exc
            code = exc.code if exc.code is not None else E_VALUE
            self.status[30] = code
            return error_reply(code, str(exc)) + PROMPT
        return body.encode("ascii", "replace") + PROMPT

    # -- lines --------------------------------------------------------------------------------

    def _dispatch(self, text: str) -> str:
        line = "".join(text.split()).upper()
        if not line:
            return ""
        if not line.isprintable():
            raise _syntax(text, "control characters are not allowed")
        if line == "RESETF":
            self.memory.resetf()
            return ""
        if line == "VF":
            self.memory.vf()
            return ""
        if line in ("VP", "VC"):
            self.parameters.make_valid(line)
            return ""
        if line == "RESETP":
            self.parameters.resetp()
            return ""
        if line in ("SETS", "SS"):
            self._call(self._handler(text).sets)
            return ""
        if line in ("POSRCAM", "PR"):
            self._call(self._handler(text).posr_cam)
            return ""
        if line == "POSAHOME":  # machine datum travel, also during cam operation (§2.11 exception)
            handler = self._handler(text)
            home = getattr(handler, "posa_home", None)
            if not callable(home):
                raise CompaxError(f"{_echo(text)!r}: the attached cam operation has no machine datum travel",
                                  code=E_NOT_AVAILABLE, field="command", value=text)
            self._call(home)
            return ""
        match = _RE_MEMORY.fullmatch(line)
        if match:
            return self._memory(text, Fmt(match[1]), int(match[2]), match[3])
        match = _RE_PARAM.fullmatch(line)
        if match:
            return self._parameter(text, int(match[1]), match[2])
        match = _RE_STATUS.fullmatch(line)
        if match:
            number = int(match[1])
            value = 0.0 if number == 30 and self.last_error is None else self.status.read(number, self.parameters)
            return f"S{number:03d}={format_status(value)}"
        match = _RE_CAM.fullmatch(line)
        if match:
            self._cam(text, match[1], match[2])
            return ""
        # the list of lines is in docs/compax.md: spelt out here it would not fit an error reply
        raise _syntax(text, "not a command of this interface")

    def _memory(self, text: str, fmt: Fmt, address: int, value: str | None) -> str:
        if value is None:
            word = self.memory.word(address)
            if fmt is Fmt.I:
                shown = str(decode_int(word))
            elif fmt is Fmt.F:
                shown = format_fraction(word)
            else:
                shown = ";".join(str(b) for b in decode_bytes(word))
            return f"{fmt.value}{address:04d}={shown}"
        if fmt is Fmt.I:
            if not _RE_INTEGER.fullmatch(value):
                raise _syntax(text, f"I value {value!r} must be an integer")
            parsed: object = int(value)
        elif fmt is Fmt.F:
            if not _RE_NUMBER.fullmatch(value):
                raise _syntax(text, f"F value {value!r} must be a decimal number such as .9 or -0.1")
            parsed = float(value)
        else:
            parts = value.split(";")
            if len(parts) != 3 or not all(_RE_INTEGER.fullmatch(p) for p in parts):
                raise _syntax(text, f"B value {value!r} must be three integers 'digital;analogue 0;analogue 1'")
            parsed = tuple(int(p) for p in parts)
        self.memory.write(fmt, address, parsed)
        return ""

    def _parameter(self, text: str, number: int, value: str | None) -> str:
        if value is None:
            return f"P{number:03d}={self.parameters.format(number)}"
        if not _RE_NUMBER.fullmatch(value):
            raise _syntax(text, f"parameter value {value!r} must be a decimal number")
        self.parameters[number] = float(value) if "." in value else int(value)
        return ""

    def _handler(self, text: str) -> CamCommands:
        if self.commands is None:
            raise CompaxError(f"{_echo(text)!r}: no cam operation is attached to this interface",
                              code=E_NOT_AVAILABLE, field="command", value=text)
        return self.commands

    def _argument(self, text: str, raw: str, integer: bool) -> float | int:
        match = _RE_OPERATION_PARAM.fullmatch(raw)
        if match:
            number = int(match[1])
            if not 40 <= number <= 49:
                raise CompaxError(f"{_echo(text)!r}: .P{number} not allowed; commands may refer to P40 ... P49",
                                  code=E_VALUE, field="argument", value=raw, allowed=".P40 ... .P49")
            value = self.parameters.valid[number]
            if integer and value != int(value):
                raise CompaxError(f"{_echo(text)!r}: P{number} = {value} is not an integer", code=E_VALUE,
                                  field=f"P{number}", value=value, allowed="an integer")
            return int(value) if integer else float(value)
        if integer:
            if not _RE_INTEGER.fullmatch(raw):
                raise _syntax(text, f"argument {raw!r} must be an integer or .P40 ... .P49")
            return int(raw)
        if not _RE_NUMBER.fullmatch(raw):
            raise _syntax(text, f"argument {raw!r} must be a number or .P40 ... .P49")
        return float(raw)

    def _cam(self, text: str, command: str, raw: str) -> None:
        handler = self._handler(text)
        if command in ("SETC", "SC"):
            n = int(self._argument(text, raw, integer=True))
            read_curve(self.memory, n, valid=True)  # E17 if the curve is not present
            self._call(handler.setc, n)
        elif command in ("SETM", "SM"):
            x = float(self._argument(text, raw, integer=False))
            if not 0.0 <= x <= 100.0:
                raise CompaxError(f"SETM {x:g} out of range; allowed is 0.000 ... 100.000 (% of the master cycle)",
                                  code=E_VALUE, field="SETM x", value=x, allowed="0 ... 100")
            self._call(handler.setm, x)
        else:  # LOOP / LP
            m = int(self._argument(text, raw, integer=True))
            if not 0 <= m <= 65000:
                raise CompaxError(f"LOOP {m} out of range; allowed is 0 ... 65000", code=E_VALUE, field="LOOP m",
                                  value=m, allowed="0 ... 65000")
            self._call(handler.loop, m)

    @staticmethod
    def _call(method: Callable[..., object], *arguments: object) -> None:
        try:
            method(*arguments)
        except CompaxError:
            raise
        except ValueError as exc:  # a handler refusing with a plain ValueError
            raise CompaxError(str(exc), code=E_NOT_AVAILABLE, field="command", value=arguments) from None

    def __repr__(self) -> str:
        return f"AsciiEndpoint(memory={self.memory!r}, commands={type(self.commands).__name__})"


class AsciiSession:
    """One connection's line buffer on an `AsciiEndpoint`: ``feed(bytes) -> bytes``.

    Dropped with its connection, so what a client left unfinished goes with it."""

    def __init__(self, endpoint: AsciiEndpoint) -> None:
        self.endpoint = endpoint
        self._buffer = bytearray()
        self._overlong = False

    def feed(self, data: bytes) -> bytes:
        """Take received bytes; return the answers to every line they complete."""
        out = bytearray()
        for byte in bytes(data):
            if byte == 0x0A:  # <lf> has no meaning
                continue
            if byte == 0x0D:
                raw = bytes(self._buffer)
                overlong = self._overlong
                self._buffer.clear()
                self._overlong = False
                out += self.endpoint._answer(raw, overlong)
                continue
            if len(self._buffer) >= MAX_LINE:
                self._overlong = True
            else:
                self._buffer.append(byte)
        return bytes(out)

    @property
    def pending(self) -> bytes:
        """Bytes of a line not yet ended by <cr>."""
        return bytes(self._buffer)
