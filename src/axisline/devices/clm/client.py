"""A PC tool's side of the CLM's X6 protocol: backup (`save`) and the CTA screens (`screen`).

    with ClmClient("127.0.0.1", 5020) as clm:
        clm.save(Path("backup"))              # program.txt, parameters.txt, logic.txt, variables.txt
        print("\\n".join(clm.screen("position")))

Requests go out in batches (one reply line per request, in order; the CLM answers every complete
telegram of a reception at one cycle boundary), so a backup of 3000 instructions, 200
parameters, 1000 Logic Task instructions and 400 variables takes some 70 round trips. Every
reply's checksum is verified; a Status 01 reply raises `ClmError` with its error. A Status 53
telegram that arrives while no Status 53 was asked for is an automatic error message (B003)
and is skipped.

Decisions (spec line -> choice, why)
------------------------------------
1. C-SAVE-WHAT, issue 12 ("reads program, parameters, Logic Task and variables back ... the PC
   tool's backup"): the CLM keeps no "written" mark, so all 3000 instructions are read and the
   ones that are not NOP are kept; every parameter; the Logic Task 0000-0999, NOP left out
   (`logic_telegrams` writes the gaps back as NOP); V600-V999, 0 left out (a cleared variable
   is 0). Files are the transfer form (telegrams, CR LF, checksums) that `axisline clm check`
   and `convert` read and any terminal program sends back; each is written atomically, and
   nothing is written unless all four were read. Test:
   ``tests/devices/clm/test_serial.py::test_clm_save_round_trip``.
2. C-DISPLAY, spec §1.5 / L982-1086: each screen is the CTA's 16-character lines built from
   status queries: position (Status 00/44, with lag 10/43 and velocity 48/42 beneath, as the
   CTA's sub-displays), io (Status 61 per byte, ``.`` for 0, bit 7 first, L996-1001), variables
   (``?sVxxx``, L984-988), counters (Status 04, ``Act.``/``Total``, L1011-1021), tasks (Status
   08/39 with the mode from Status 53/polling), error (Status 53 and Status 60's NC / LT /
   variable places, the F1 key's screen, L935-937). Test: ``test_clm_display_once``.
"""

from __future__ import annotations

import re
import socket
from pathlib import Path

from ...kernel import atomic_write_text
from .errors import SERIAL_ERRORS, ClmError, serial_code
from .fields import USER_VARIABLES, parse_variable_value
from .logic import LT_INSTRUCTIONS, logic_telegrams
from .memory import VARIABLE_COUNT
from .parameters import PARAMETERS, ParameterSet, check_id, parse_data
from .program import PROGRAM_SIZE, Program, parse_program_telegram
from .telegram import checksum, station_char
from .variables import variable_telegrams

__all__ = ["SCREENS", "ClmClient", "parse_address"]

SCREENS = ("position", "io", "variables", "counters", "tasks", "error")
BATCH = 64
FILES = {"program": "program.txt", "parameters": "parameters.txt", "logic": "logic.txt", "variables": "variables.txt"}


def parse_address(text: str) -> tuple[str, int]:
    """``HOST:PORT`` -> (host, port); ValueError with the expected form."""
    host, sep, port = text.rpartition(":")
    if not sep or not port.isdigit() or not 0 < int(port) <= 65535:
        raise ValueError(f"--connect = {text!r}: expected HOST:PORT with a port in 1..65535")
    return host or "127.0.0.1", int(port)


class ClmClient:
    """One connection to a CLM endpoint (`axisline serve --serial-tcp`), at a station."""

    def __init__(self, host: str, port: int, station: int = 0, timeout: float = 5.0) -> None:
        station_char(station)  # ValueError for a station outside 0..32
        self.address = (host, port)
        self.station = station
        self.timeout = timeout
        self._sock = socket.create_connection(self.address, timeout=timeout)
        self._buffer = b""

    def close(self) -> None:
        self._sock.close()

    def __enter__(self) -> ClmClient:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    # -- telegrams -------------------------------------------------------------------------

    def telegram(self, control: str, kind: str, body: str) -> str:
        text = f"{control}{station_char(self.station)}{kind}{body}"
        return f"{text}${checksum(text)}"

    def _line(self) -> str:
        while b"\n" not in self._buffer:
            try:
                chunk = self._sock.recv(65536)
            except socket.timeout:
                raise ConnectionError(
                    f"no reply from {self.address[0]}:{self.address[1]} within {self.timeout:g} s "
                    f"(the CLM answers only its B003 station; --station {self.station} was used)") from None
            if not chunk:
                raise ConnectionError(f"{self.address[0]}:{self.address[1]} closed the connection")
            self._buffer += chunk
        line, _, self._buffer = self._buffer.partition(b"\n")
        return line.rstrip(b"\r").decode("ascii", "replace")

    def exchange(self, requests: list[str]) -> list[str]:
        """Send `requests` (telegrams without CR LF) in batches; one reply line each, in order.
        Automatic Status 53 messages that nobody asked for are skipped."""
        replies: list[str] = []
        for start in range(0, len(requests), BATCH):
            batch = requests[start : start + BATCH]
            self._sock.sendall("".join(r + "\r\n" for r in batch).encode("ascii"))
            for request in batch:
                wants_53 = request[2:3] == "X" and request[3:].split("$")[0].split()[:1] == ["53"]
                while True:
                    line = self._line()
                    if line[:1] == "X" and line[2:4] == "53" and not wants_53:
                        continue  # an automatic error message (B003)
                    break
                replies.append(line)
        return replies

    @staticmethod
    def check(line: str) -> str:
        """The reply without ``$hh`` after its checksum is verified; Status 01 -> ClmError."""
        if "$" not in line:
            raise ClmError(serial_code(2), f"reply {line[:40]!r} carries no checksum")
        text, _, given = line.rpartition("$")
        if checksum(text) != given.upper():
            raise ClmError(serial_code(4), f"reply {line[:40]!r}: checksum ${given}, computed ${checksum(text)}")
        if text[:1] == "X" and text[2:5] == "01 ":
            number = text[5:7]
            code = int(number) if number.isdigit() else 2
            raise ClmError(serial_code(code), f"the CLM answered Status 01 error {code:02d} {SERIAL_ERRORS.get(code, '')}")
        return text

    def status(self, number: int, *args: str) -> str:
        body = f"  {number:02d} " + "".join(f"{a} " for a in args)
        return self.check(self.exchange([self.telegram("?", "X", body)])[0])

    # -- backup ---------------------------------------------------------------------------------

    def read_program(self) -> Program:
        replies = self.exchange([self.telegram("?", "N", f"{n:04d}") for n in range(PROGRAM_SIZE)])
        program = Program()
        for line in replies:
            self.check(line)
            instruction = parse_program_telegram(line)
            if instruction.mnemonic != "NOP":
                program.store(instruction)
        return program

    def read_parameters(self) -> ParameterSet:
        params = ParameterSet()
        replies = self.exchange([self.telegram("?", "K", f" {pid}") for pid in PARAMETERS])
        for pid, line in zip(PARAMETERS, replies):
            m = re.match(r" (\S+) ?(.*)\Z", self.check(line)[3:])
            if m is None or check_id(m.group(1)) != pid:
                raise ClmError(serial_code(2), f"reply {line[:40]!r} to the query of {pid}")
            params.set(pid, parse_data(pid, m.group(2)))
        return params

    def read_logic(self) -> dict[int, str]:
        lines: dict[int, str] = {}
        replies = self.exchange([self.telegram("?", "P", f" {n:04d}") for n in range(LT_INSTRUCTIONS)])
        for n, line in enumerate(replies):
            body = self.check(line)[2:]
            head, _, text = body.strip().partition(" ")
            if head != f"{n:04d}":
                raise ClmError(serial_code(2), f"reply {line[:40]!r} to the query of LT {n:04d}")
            text = text.strip()
            if text and text != "NOP":
                lines[n] = text
        return lines

    def read_variables(self) -> dict[int, int]:
        values: dict[int, int] = {}
        numbers = range(USER_VARIABLES, VARIABLE_COUNT)
        replies = self.exchange([self.telegram("?", "V", f"{n:03d}") for n in numbers])
        for n, line in zip(numbers, replies):
            m = re.fullmatch(r"V.(\d{3}) (\S+) ", self.check(line))
            if m is None or int(m.group(1)) != n:
                raise ClmError(serial_code(2), f"reply {line[:40]!r} to the query of V{n:03d}")
            value = parse_variable_value(m.group(2))
            if value:
                values[n] = value
        return values

    def save(self, directory: Path) -> dict[str, Path]:
        """Read all four memories, then write the four transfer files (decision 1)."""
        program = self.read_program()
        params = self.read_parameters()
        logic = self.read_logic()
        variables = self.read_variables()
        texts = {
            "program": program.telegrams(),
            "parameters": "".join(t + "\r\n" for t in params.telegrams()),
            "logic": "".join(logic_telegrams(logic)),
            "variables": variable_telegrams(variables),
        }
        directory.mkdir(parents=True, exist_ok=True)
        written = {}
        for kind, text in texts.items():
            path = directory / FILES[kind]
            atomic_write_text(path, text.replace("\r\n", "\n").replace("\n", "\r\n"), encoding="ascii", newline="")
            written[kind] = path
        return written

    # -- the CTA screens ----------------------------------------------------------------------------

    def screen(self, name: str, *, variable: int = USER_VARIABLES, counter: int = 0,
               io_bytes: tuple[str, ...] = ("I0.00", "I1.00", "Q1.00")) -> list[str]:
        """The lines of one CTA screen (decision 2)."""
        if name not in SCREENS:
            raise ValueError(f"--screen = {name!r}: one of {', '.join(SCREENS)}")
        return getattr(self, f"_screen_{name}")(variable=variable, counter=counter, io_bytes=io_bytes)

    def _statuses(self, *queries: tuple[int, ...] | tuple[int, str]) -> list[str]:
        requests = [self.telegram("?", "X", f"  {q[0]:02d} " + "".join(f"{a} " for a in q[1:])) for q in queries]
        return [self.check(line) for line in self.exchange(requests)]

    def _screen_position(self, **_: object) -> list[str]:
        s00, s44, s10, s43, s48, s42 = self._statuses((0,), (44,), (10,), (43,), (48,), (42,))
        pos = _fields(s00, 12, 2) + _fields(s44, 12, 2)
        lag = _fields(s10, 11, 2) + _fields(s43, 11, 2)
        vel = _fields(s48, 10, 2) + _fields(s42, 10, 2)
        lines = [f"{'Pos '[i]} {i + 1} {p}" if p.strip() else f"{'Pos '[i]} {i + 1}" for i, p in enumerate(pos)]
        lines += [f"{'Lag '[i]} {i + 1} {p}" if p.strip() else f"{'Lag '[i]} {i + 1}" for i, p in enumerate(lag)]
        lines += [f"{'Vel '[i]} {i + 1} {v[2:].strip()}/min" if v[:1] == "1" else f"{'Vel '[i]} {i + 1}" for i, v in enumerate(vel)]
        return lines

    def _screen_io(self, io_bytes: tuple[str, ...], **_: object) -> list[str]:
        replies = self._statuses(*((61, b) for b in io_bytes))
        lines = ["I/O - Status"]
        for reply in replies:
            operand, bits = reply[5:10], reply[11:19]
            lines.append(f"{operand} {bits.replace('0', '.')}")
        return lines

    def _screen_variables(self, variable: int, **_: object) -> list[str]:
        if not 0 <= variable < VARIABLE_COUNT:
            raise ValueError(f"--variable = {variable}: V000-V999")
        reply = self.check(self.exchange([self.telegram("?", "V", f"{variable:03d}")])[0])
        value = reply.split()[-1] if reply.split() else ""
        return ["Variable :", f"V{variable:03d}", value]

    def _screen_counters(self, counter: int, **_: object) -> list[str]:
        if not 0 <= counter < PROGRAM_SIZE:
            raise ValueError(f"--counter = {counter}: instructions 0000-2999")
        reply = self._statuses((4, f"{counter:04d}"))[0]
        actual, total = reply[10:16], reply[17:23]
        lines = [f"E:{counter:04d} Counter"]
        if actual.strip():
            lines += [f"Act. : {actual}", f"Total: {total}"]
        return lines

    def _screen_tasks(self, **_: object) -> list[str]:
        s08, s39 = self._statuses((8,), (39,))
        fields = _fields(s08, 9, 3) + _fields(s39, 9, 2)
        lines = ["Tasks"]
        for n, f in enumerate(fields, start=1):
            if f.strip():
                current, back = f[:4], f[5:].strip()
                lines.append(f"T{n} {current}" + (f" JSR>{back}" if back else ""))
        return lines

    def _screen_error(self, **_: object) -> list[str]:
        s53, *places = self._statuses((53,), (60, "0"), (60, "1"), (60, "2"), (60, "3"))
        code, text = s53[5:7], s53[8:24].rstrip()
        lines = [f"Error {code}", text]
        for label, reply in zip(("Param.   :", "NC Instr :", "LT Instr :", "Variable :"), places):
            number = reply[7:11]
            if number.strip():
                lines.append(f"{label} {number}")
        return lines


def _fields(reply: str, width: int, count: int) -> list[str]:
    """`count` fixed-width fields after ``Xsnn `` (a blank between them)."""
    out = []
    at = 5
    for _ in range(count):
        out.append(reply[at : at + width].ljust(width))
        at += width + 1
    return out
