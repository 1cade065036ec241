"""The CLM's X6 serial protocol on the running CLM (spec §8; manual §9.2, L6207-7507).

    endpoint = ClmSerialEndpoint(rt, writes_allowed=lambda: True)
    session = endpoint.session()                   # one per connection (TCP client, pty)
    session.feed(b"?_X__00_\\r\\n")                 # -> b'X 00  +000000.000             $hh\\r\\n'
    session.feed(b"# V600 +00000250.000000 $..\\r\\n")  # -> b'Y\\r\\n' (B003 confirmation on)

Bytes in, bytes out, no sockets (`axisline.fieldbus.serial_tcp` carries them; `feed` runs at a
cycle boundary through the machine's command queue, so a telegram acts between two NC cycles as
on the CLM). Each session has its own line buffer; CR, LF or CR LF ends a telegram.

Telegrams (``s`` = station, ``_`` = blank; replies end ``$hh CR LF`` unless noted):

==========================  ===========================================  =====================
received                    does                                         reply
==========================  ===========================================  =====================
``?sNbbbb``                 read a program instruction                   ``#sNbbbb_ccc_data_``
``?sK_xxyy``                read a parameter                             ``#sK_xxyy_data``
``?sP_xxxx``                read a Logic Task instruction                ``Psxxxx_instr_``
``?sVxxx``                  read a variable                              ``Vsxxx_+12345678.123456_``
``?sX__nn_ [args]``         status (`status`)                            ``Xsnn_..._``
``#sNbbbb_ccc_data_$hh``    store an instruction (any mode)              ``Y`` / nothing
``#sK_xxyy_data$hh``        store a parameter (Parameter mode; ``!``     ``Y`` / nothing
                            for ``#`` accepted)
``#sPxxxx_instr_$hh``       store a Logic Task instruction (Param. mode) ``Y`` / nothing
``#sVxxx_+value_$hh``       store a variable V600-V999 (any mode)        ``Y`` / nothing
``!sSTART_$hh`` ...         interface commands (spec §8.6)               ``Y`` / nothing
``:s``                      polling                                      ``:snn`` (hex, no $hh)
anything refused            changes nothing                              ``Xs01_ff_<20 chars>_``
==========================  ===========================================  =====================

The interface settings are B003 (X6), or B005 when X6 is off or serves the IDS01 and X8 is a
data interface ("Only one serial interface at once", L6329): station number, checksum
validation, confirmation ``Y``, automatic error messages. With the IDS01 on X6 and X8 off there
is no data interface and nothing is answered (decision 14).

Decisions (spec line -> choice, why)
------------------------------------
1. C-FRAMING, L6431 "CR and LF, together, form the end": CR, LF or CR LF ends a telegram (a
   lone LF or CR ends one too; the empty line between CR and LF is nothing); XON/XOFF (0x11,
   0x13, L6455) are flow control, not telegram characters, and are dropped; a line is kept up
   to 200 bytes, a longer one is answered with error 02 as a whole (nothing of it runs).
   Tests: ``test_framing_cr_lf_cr_lf_and_pieces``, ``test_overlong_line_is_02``.
2. C-STATION, L6390-6394 and errata §1.15: with station 00 (RS232) the station byte must be a
   blank; another one is error 02 ("No other character is accepted", and there is no bus to
   disturb). With station 01-32 (RS485) a telegram for another station, or one whose station
   byte cannot be read, gets no reply and does nothing (L6392). A blank ("relevant for all
   users on the bus") is a broadcast: it is executed but never answered (no reply, no ``Y``,
   no Status 01), because 32 answers at once would collide, as Modbus treats address 0.
   Tests: ``test_wrong_station_gets_no_reply_and_changes_nothing``, ``test_broadcast_executes_silently``,
   ``test_rs232_needs_a_blank_station``.
3. C-CHECKSUM, L6355 / L6424 / L7339, errata §1.13: a ``$hh`` that is present is always
   verified (04 if wrong). With validation on (B003 handshake 0/2) a write (``#``, ``!sK``)
   without one is 04; queries ``?`` and polling ``:`` never need one (the manual prints every
   query without it, L6292, L6772-7322, L7491); interface commands ``!`` always need one
   ("necessary ... independent of ... B003", L7339). A doubled ``$$hh`` as printed at START,
   STOP, CLEAR, CCLVAR0019, CL0, CLL1/2 (spec §8.6 "presumably a typo") is read as ``$hh``.
   Tests: ``test_bad_checksum_is_04_and_changes_nothing``, ``test_checksum_rules``.
4. C-SETTINGS-LATCH, L6586 "If no checksum validation function has been programmed prior to
   entering Parameter Mode, this function remains disabled ... until Parameter Mode is
   exited": all of B003 (station, validation, confirmation, automatic messages) is taken when
   the CLM is outside Parameter mode and kept unchanged while it is in it, as the CLM reads its
   parameters on leaving Parameter mode (L4130, L7519). Test: ``test_b003_takes_effect_after_parameter_mode``.
5. C-CONFIRM, L6362: with B003 confirmation 1 every accepted write telegram and interface
   command is answered ``Y CR LF`` (no station, no checksum, as printed); with 0 nothing. A
   host cannot tell the CLM where a "program or parameter set" ends, so a set is confirmed
   telegram by telegram. Test: ``test_writes_and_read_backs_byte_for_byte``.
6. C-AUTO-ERROR, L6340 (RS232 only) and spec §8.8 [INFERRED] Status 53 form: with B003
   automatic error messages on and station 00, a fault that is new since the session last
   looked is sent as its Status 53 telegram in front of the session's next reply. A TCP or pty
   session only sends when it receives, so a host that waits sends any byte (a lone LF is
   enough and is otherwise ignored); a fault raised and cleared between two receptions is not
   reported; a new session does not get the fault that was present when it connected (it was
   sent on the line before the host listened). Test: ``test_automatic_error_message``.
7. C-WRITE-ENABLE, issue 12 / `Personality.network_writes`: without ``serve --allow-writes``
   every ``#`` and ``!`` telegram is refused with error 18 "Not accepted" after its framing,
   station and checksum are checked, and changes nothing; queries and polling stay open. 18
   and not 05: 05 would send the host to switch the CLM to Parameter mode, which would not
   help. Test: ``test_write_without_allow_writes_is_18``.
8. C-MODE, L6215, L6574, L2961 (errata §1.2), L7371-7482: parameters, the Logic Task,
   CCLVAR0019, CSETPA, CNOPNC, CNOPLT, CCLVAR only in Parameter mode, CL0 only in Manual, START
   only in Automatic; otherwise error 05 "Invalid Mode" (checked before the data, which is then
   not looked at). STOP outside Automatic is accepted and does nothing (no program runs, and a
   stop latched there would block the next Start input). Test: ``test_write_in_wrong_mode_is_05``.
9. C-REFUSALS: a telegram that is not ?/#/!/: + station + a known information type is 02; a
   program telegram the CLM could not store is 01/02/03/12/13/16 (`program`, decision C-LOAD:
   data of the right shape that would fault when run is refused here too, as 03); parameter ids
   11/06/07, malformed parameter data 03 ("The transmitted ... data are incorrect", L6809; the
   ranges are checked on leaving Parameter mode, fault 02); Logic Task 01/12/13/25 (and 02 for a
   field over 16 characters); variables 23 (number, L6822) and 18 (data, L6821), 16 beyond
   ±99999999.999999; status 08/09/10/18; an unknown ``!`` command 13 ("An invalid command was
   transmitted", L6819), a range outside its memory 12 (NC, LT) or 23 (variables), a range
   that runs backwards 02. Nothing changes before every check has passed, and no input raises
   out of `feed` (an internal error is answered 02). Tests: ``test_malformed_telegram_is_02_and_changes_nothing``,
   ``test_random_bytes_never_raise`` (hypothesis).
10. C-READBACK: an instruction reads back as its write telegram (`Instruction.telegram`, data
    in the CLM's columns, one blank before ``$``) at the CLM's station, but NOP as the Profibus
    read response prints it, ``# N0000 NOP   `` (three blanks, L7888/L7905, errata §1.8); a
    parameter as the sample table (``# K B002 019200 0 1 8 1$E4``, L6591-6670); an unwritten
    Logic Task instruction is NOP, and 0000 of an empty Logic Task END (the state ``!CNOPLT``
    leaves, L7450); a Logic Task instruction written into an empty memory puts END at 0000
    first, so the task stays off until 0000 is written. Tests: ``test_writes_and_read_backs_byte_for_byte``,
    ``test_parameter_read_back_is_the_manual_table``.
11. C-INTERFACE, spec §8.6: CLEAR is the CL key (``modes.clear``); CCLVAR0019 (and §7.13's
    ``CLLVAR0019``) clears the time counter V019; CL0 (and A138's ``CLO``) makes the next start
    begin at 0000 (in flying cutoff: the next Automatic, cutoff.py decision 7); CLL1/CLL2 clear
    the cutoff's material / product length counter (accepted and without effect when axis 1 is
    not in flying cutoff: the counters are 0 then); MxON/MxOFF switch axis x's interface enable (the
    axis' ``interface_enable`` when it has one); the NC range of CNOPNC keeps the counters of
    the instructions outside it; CNOPLT puts END at 0000 when its range starts there (L7462).
    In flying cutoff START and STOP are answered 18 "Not accepted" ("Interface commands 'Program
    Start' and 'Program Stop' are not allowed via the interface", L3949).
    Tests: ``test_interface_commands``, tests/devices/clm/test_cutoff.py::
    test_start_and_stop_over_the_interface_are_not_accepted.
12. C-DURABLE: a write is acknowledged only once it is stored: after the telegrams of one
    reception, the retained memory is saved (`store`) before the replies go out; if it cannot
    be saved the writes of that reception are undone and each is answered 18. Test:
    ``test_unsaved_write_is_undone``.
13. C-X8-RESPONSE-DELAY, L6337: the RS485 response delay of B003 is not applied (a TCP
    connection has no bus turnaround; delaying would hold the NC cycle).
14. C-IDS-PORT, L5028 ("If the decade switch input is preselected via an IDS01 unit, the other
    values need not be input"), L6301 and L6329 (one serial interface at once): with B002's
    function digit 1, X6 carries the IDS01's telegrams (decade_switch.py), not this protocol.
    The endpoint is then X8 with B005's settings when B004 makes X8 a data interface; when it
    does not, the CLM has no data interface: the endpoint takes the bytes and answers nothing
    (a host on a port wired to the decade switch hears nothing), and says so once per session
    on stderr. B002 is taken outside Parameter mode like B003 (decision 4), so a host that
    writes B002 = IDS01 keeps its session until Parameter mode is left. Test:
    ``tests/devices/clm/test_decade_switch.py::test_serial_endpoint_with_the_ids_on_x6``.
"""

from __future__ import annotations

import re
import sys
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from .errors import SERIAL_ERRORS, ClmError, serial_code
from .fields import USER_VARIABLES, format_variable, parse_variable_value
from .logic import DATA_WIDTH, LT_INSTRUCTIONS, parse_instruction
from .memory import VARIABLE_COUNT
from .parameters import check_id, parse_data
from .program import PROGRAM_SIZE, Program, parse_program_telegram
from .status import fault_code, status_body
from .telegram import Telegram, emit, parse_telegram, station_char

__all__ = ["MAX_LINE", "ClmSerialEndpoint", "ClmSession", "Settings", "error_reply"]

MAX_LINE = 200
_FLOW = (0x11, 0x13)  # XON, XOFF
CONFIRMATION = b"Y\r\n"
_STATUS_ARGS = re.compile(r"\s*(\S+)\s*(.*)\Z", re.S)


@dataclass(frozen=True)
class Settings:
    """The interface functions of B003 (or B005) in effect (decision 4)."""

    station: int = 0  # 0 = RS232
    checksum: bool = True  # validation on
    confirmation: bool = False
    auto_error: bool = False
    data_interface: bool = True  # False: X6 serves the IDS01 and X8 is off (decision 14)


def read_settings(params: Any) -> Settings:
    port = "B003"
    x6, x8 = params.get("B002"), params.get("B004")
    x6_ids = int(x6["function"]) == 1
    x8_data = int(x8["baud_rate"]) != 0 and int(x8["function"]) == 0
    if (int(x6["baud_rate"]) == 0 or x6_ids) and x8_data:
        port = "B005"
    value = params.get(port)
    station = int(value["station_number"])
    return Settings(
        station=station if 0 <= station <= 32 else 0,
        checksum=int(value["handshake_checksum"]) in (0, 2),
        confirmation=int(value["confirmation"]) == 1,
        auto_error=int(value["auto_error_message"]) == 1,
        data_interface=not (x6_ids and not x8_data),
    )


def error_reply(number: int, station: int = 0) -> bytes:
    """``Xs01_ff_tttttttttttttttttttt_$hh CR LF`` (ff decimal, text 20 characters)."""
    text = SERIAL_ERRORS.get(number, "")
    return emit("X", station, "", f"01 {number:02d} {text:20.20} ").encode("ascii")


def _code_number(error: ClmError, otherwise: int) -> int:
    if error.code.startswith("X01:"):
        return int(error.code[4:])
    return otherwise


class _Snapshot:
    """The retained memory before the first write of a reception (decision 12)."""

    def __init__(self, memory: Any) -> None:
        self.program = memory.program.copy()
        self.parameters = memory.parameters.copy()
        self.logic = dict(memory.logic)
        self.values = list(memory.variables.values)
        self.variables_version = memory.variables.version
        self.version = memory.version

    def restore(self, memory: Any) -> None:
        memory.program = self.program
        memory.parameters = self.parameters
        memory.logic = self.logic
        memory.variables.values[:] = self.values
        memory.variables.version = self.variables_version
        memory.version = self.version


class _Outcome:
    __slots__ = ("reply", "wrote")

    def __init__(self, reply: bytes, wrote: bool = False) -> None:
        self.reply = reply
        self.wrote = wrote


class ClmSerialEndpoint:
    """The X6 protocol of one CLM runtime (see the module docstring)."""

    def __init__(self, rt: Any, writes_allowed: Callable[[], bool] = lambda: True,
                 store: Callable[[], object] | None = None) -> None:
        self.rt = rt
        self._writes_allowed = writes_allowed
        #: saves the retained memory (OSError if it cannot): a write is acknowledged after it
        self._store = store
        self._latched: Settings | None = None
        self._session = ClmSession(self)

    # -- transport side ---------------------------------------------------------------------

    def session(self) -> ClmSession:
        return ClmSession(self)

    def feed(self, data: bytes) -> bytes:
        """The endpoint's own session (in-process callers)."""
        return self._session.feed(data)

    @property
    def settings(self) -> Settings:
        """B003 as in effect (decision 4): read outside Parameter mode, kept inside it."""
        if self._latched is None or self.rt.modes.mode != "parameter":
            try:
                self._latched = read_settings(self.rt.memory.parameters)
            except (ClmError, KeyError, ValueError, TypeError):
                self._latched = self._latched or Settings()
        return self._latched

    # -- one telegram -------------------------------------------------------------------------

    def _answer(self, raw: bytes, overlong: bool, settings: Settings) -> tuple[bytes, bool]:
        """(reply, wrote) for one received line; never raises."""
        own = settings.station
        broadcast = False
        if own:  # RS485 (decision 2)
            station = raw[1:2].upper()
            if station == b" ":
                broadcast = True
            elif station != station_char(own).encode():
                return b"", False
        try:
            outcome = self._telegram(raw, overlong, settings)
        except ClmError as e:
            outcome = _Outcome(error_reply(_code_number(e, 2), own))
        except Exception as e:  # a bug must not end the connection: the host sees 02
            print(f"clm serial: {type(e).__name__}: {e} on {raw[:60]!r}", file=sys.stderr, flush=True)
            outcome = _Outcome(error_reply(2, own))
        return (b"" if broadcast else outcome.reply), outcome.wrote

    def _telegram(self, raw: bytes, overlong: bool, settings: Settings) -> _Outcome:
        if overlong:
            raise ClmError(serial_code(2), f"the telegram is longer than {MAX_LINE} characters")
        try:
            text = raw.decode("ascii")
        except UnicodeDecodeError:
            raise ClmError(serial_code(2), "the telegram holds a byte that is not ASCII") from None
        if text[:1] not in ("?", "#", "!", ":"):
            raise ClmError(serial_code(2), f"{text[:12]!r}: a telegram begins with ?, #, ! or :")
        if "$$" in text:  # the manual's doubled $ (decision 3)
            text = text.replace("$$", "$", 1)
        t = parse_telegram(text)
        if settings.station == 0 and t.station != 0:
            raise ClmError(serial_code(2), "RS232: the station byte must be a blank (L6390)")
        is_command = t.control == "!" and not t.body.startswith("K")
        if t.checksum is None and (is_command or (settings.checksum and t.control in "#!")):
            raise ClmError(serial_code(4), "the telegram has no checksum ($hh)")
        own = settings.station
        if t.control == "?":
            return _Outcome(self._query(t, own))
        if t.control == ":":
            if t.body.strip():
                raise ClmError(serial_code(2), "polling is ':s' alone")
            return _Outcome(f":{station_char(own)}{fault_code(self.rt)}\r\n".encode("ascii"))
        if not self._writes_allowed():
            raise ClmError(serial_code(18), "writes from the network are off (serve --allow-writes)")
        if t.control == "!" and is_command:
            self._command(t.body)
        elif t.control == "!" or t.kind == "K":
            self._parameter(t.body[1:] if t.control == "!" else t.body)
        elif t.kind == "N":
            self._program(text)
        elif t.kind == "P":
            self._logic(t.body)
        elif t.kind == "V":
            self._variable(t.body)
        else:
            raise ClmError(serial_code(2), "status information cannot be written")
        return _Outcome(CONFIRMATION if settings.confirmation else b"", wrote=True)

    # -- queries --------------------------------------------------------------------------------

    def _query(self, t: Telegram, own: int) -> bytes:
        memory = self.rt.memory
        body = t.body.strip()
        if t.kind == "X":
            m = _STATUS_ARGS.match(body)
            if m is None:
                raise ClmError(serial_code(8), "no status number")
            number_text = m.group(1)
            if not number_text.isdigit() or len(number_text) > 2:
                raise ClmError(serial_code(8), f"status number {number_text[:6]!r} is not decimal")
            reply = status_body(self.rt, int(number_text), m.group(2).split())
            return emit("X", own, "", reply).encode("ascii")
        if t.kind == "N":
            n = _number(body, 4, PROGRAM_SIZE)
            ins = memory.program[n]
            if ins.mnemonic == "NOP":
                return emit("#", own, "N", f"{n:04d} NOP   ").encode("ascii")
            return ins.telegram(own).encode("ascii")
        if t.kind == "K":
            pid = check_id(body)
            return emit("#", own, "K", f" {pid} {memory.parameters.data(pid)}").encode("ascii")
        if t.kind == "P":
            n = _number(body, 4, LT_INSTRUCTIONS)
            text = memory.logic.get(n) or ("END" if n == 0 and not memory.logic else "NOP")
            return emit("P", own, "", f"{n:04d} {text} ").encode("ascii")
        if t.kind == "V":
            n = _variable_number(body)
            return emit("V", own, "", f"{n:03d} {format_variable(memory.variables[n])} ").encode("ascii")
        raise ClmError(serial_code(2), "unknown information type")

    # -- writes ---------------------------------------------------------------------------------

    def _mode(self, wanted: str, what: str) -> None:
        mode = self.rt.modes.mode
        if mode != wanted:
            raise ClmError(serial_code(5), f"{what} only in {wanted.capitalize()} mode (the CLM is in {mode})")

    def _program(self, text: str) -> None:
        try:
            ins = parse_program_telegram(text)
        except ClmError as e:
            if not e.code.startswith("X01:"):  # a fault the CLM would raise when running it (decision 9)
                raise ClmError(serial_code(3), e.detail, e.where) from None
            raise
        memory = self.rt.memory
        memory.program.store(ins)
        memory.version += 1

    def _parameter(self, body: str) -> None:
        self._mode("parameter", "parameters are written")
        m = re.match(r"\s*(\S+)( *)(.*?)\s*\Z", body, re.S)
        if m is None:
            raise ClmError(serial_code(2), "a parameter telegram is #sK xxyy data$hh")
        pid = check_id(m.group(1))
        if m.group(3) and len(m.group(2)) > 2:
            raise ClmError(serial_code(3), f"{len(m.group(2))} blanks after the parameter id")
        try:
            value = parse_data(pid, m.group(3))
        except ClmError as e:
            raise ClmError(serial_code(3), e.detail, pid) from None
        memory = self.rt.memory
        memory.parameters.set(pid, value)
        memory.version += 1

    def _logic(self, body: str) -> None:
        self._mode("parameter", "the Logic Task is written")
        head, _, rest = body.strip().partition(" ")
        n = _number(head, 4, LT_INSTRUCTIONS)
        rest = rest.strip()
        if not rest:
            raise ClmError(serial_code(13), "no instruction after the number")
        if len(rest) > DATA_WIDTH:
            raise ClmError(serial_code(2), f"the instruction field holds at most {DATA_WIDTH} characters")
        ins = parse_instruction(rest, n, serial=True)
        memory = self.rt.memory
        if not memory.logic and n != 0:
            memory.logic[0] = "END"  # decision 10: the empty memory's END stays at 0000
        memory.logic[n] = str(ins)
        memory.version += 1

    def _variable(self, body: str) -> None:
        m = re.match(r"\s*(\S+)\s+(\S+)\s*\Z", body)
        if m is None:
            raise ClmError(serial_code(2), "a variable telegram is #sVxxx +12345678.123456 $hh")
        n = _variable_number(m.group(1))
        if n < USER_VARIABLES:
            raise ClmError(serial_code(23), f"V{n:03d} is a system variable (read-only)")
        try:
            raw = parse_variable_value(m.group(2))
        except ValueError as e:
            raise ClmError(serial_code(18), str(e)) from None
        self.rt.memory.variables.write(n, raw, by="serial")

    # -- interface commands ----------------------------------------------------------------------

    def _command(self, body: str) -> None:
        command = "".join(body.split())
        rt = self.rt
        modes = rt.modes
        memory = rt.memory
        if command in ("START", "STOP") and getattr(rt, "cutoff", None) is not None:
            raise ClmError(serial_code(18), f"{command}: Program Start / Stop are not allowed via the interface in flying cutoff (L3949)")
        if command == "START":
            self._mode("automatic", "START")
            modes.start(interface=True)
        elif command == "STOP":
            if modes.mode == "automatic":
                modes.immediate_stop(interface=True)
        elif command == "CLEAR":
            modes.clear()
        elif command in ("CCLVAR0019", "CLLVAR0019"):
            self._mode("parameter", "the time counter is cleared")
            rt.clear_time_counter()
        elif command in ("CL0", "CLO"):
            self._mode("manual", "CL0")
            modes.restart_from_zero = True
            if getattr(rt, "cutoff", None) is not None:  # the flying cutoff's next Automatic starts at 0000 (cutoff.py 7)
                rt.cutoff.start_at_zero = True
        elif command in ("CLL1", "CLL2"):
            if getattr(rt, "cutoff", None) is not None:  # decision 11
                rt.cutoff.clear_counter(int(command[3]))
        elif re.fullmatch(r"M[1-4](ON|OFF)", command):
            self._axis_enable(int(command[1]), command.endswith("ON"))
        elif command == "CSETPA":
            self._mode("parameter", "CSETPA")
            memory.parameters.reset()
            memory.version += 1
        elif command.startswith("CNOPNC"):
            self._mode("parameter", "CNOPNC")
            first, last = _range(command[6:], 0, PROGRAM_SIZE - 1, 12)
            self._nop_program(first, last)
        elif command.startswith("CNOPLT"):
            self._mode("parameter", "CNOPLT")
            first, last = _range(command[6:], 0, LT_INSTRUCTIONS - 1, 12)
            old = memory.logic
            logic = {n: t for n, t in old.items() if not first <= n <= last}
            logic.update({n: "NOP" for n in old if first <= n <= last and n != 0})
            if first == 0 or not old:  # an empty memory holds END at 0000 (decision 10)
                logic[0] = "END"
            memory.logic = logic
            memory.version += 1
        elif command.startswith("CCLVAR"):
            self._mode("parameter", "CCLVAR")
            first, last = _range(command[6:], USER_VARIABLES, VARIABLE_COUNT - 1, 23)
            memory.variables.clear_user(first, last)
        else:
            raise ClmError(serial_code(13), f"{command[:16]!r} is not an interface command of the CLM (spec §8.6)")

    def _nop_program(self, first: int, last: int) -> None:
        memory = self.rt.memory
        old = memory.program
        program = Program()
        for ins in old.written():
            if not first <= ins.number <= last:
                program.store(ins)
        program.counters = {n: c for n, c in old.counters.items() if not first <= n <= last}
        memory.program = program
        memory.version += 1

    def _axis_enable(self, number: int, on: bool) -> None:
        rt = self.rt
        axis = rt.axes.get(number)
        if axis is None:
            raise ClmError(serial_code(3), f"the CLM has no axis {number}")
        rt.modes.interface_enable(number, on)


def _number(text: str, digits: int, size: int) -> int:
    text = text.strip()
    if not text.isascii() or not text.isdigit() or len(text) > digits:
        raise ClmError(serial_code(1), f"instruction number {text[:8]!r}: {digits} decimal digits")
    n = int(text)
    if n >= size:
        raise ClmError(serial_code(12), f"instruction number {n}: the memory ends at {size - 1:04d}")
    return n


def _variable_number(text: str) -> int:
    text = text.strip()
    if not text.isascii() or not text.isdigit() or len(text) != 3:
        raise ClmError(serial_code(23), f"variable number {text[:8]!r}: three digits 000-999")
    return int(text)


def _range(text: str, low: int, high: int, beyond: int) -> tuple[int, int]:
    """``''`` -> the whole memory; ``vvvvbbbb`` -> (vvvv, bbbb) checked."""
    if not text:
        return low, high
    if len(text) != 8 or not text.isascii() or not text.isdigit():
        raise ClmError(serial_code(1), f"range {text[:12]!r}: vvvvbbbb, two four-digit numbers")
    first, last = int(text[:4]), int(text[4:])
    if not (low <= first <= high and low <= last <= high):
        raise ClmError(serial_code(beyond), f"range {first:04d}-{last:04d}: allowed {low:04d}-{high:04d}")
    if first > last:
        raise ClmError(serial_code(2), f"range {first:04d}-{last:04d} runs backwards")
    return first, last


class ClmSession:
    """One connection's line buffer and automatic-message state on a `ClmSerialEndpoint`."""

    def __init__(self, endpoint: ClmSerialEndpoint) -> None:
        self.endpoint = endpoint
        self._buffer = bytearray()
        self._overlong = False
        self._seen_fault = endpoint.rt.modes.fault_error  # decision 6: what was there is not news
        self._told_ids = False  # decision 14: the note was printed

    @property
    def pending(self) -> bytes:
        return bytes(self._buffer)

    def feed(self, data: bytes) -> bytes:
        """Take received bytes; return the replies to every telegram they complete."""
        endpoint = self.endpoint
        try:
            settings = endpoint.settings
        except Exception:  # never raise out of feed
            settings = Settings()
        if not settings.data_interface:  # decision 14: X6 is the IDS01's, X8 is off
            self._buffer.clear()
            self._overlong = False
            if not self._told_ids:
                self._told_ids = True
                print("clm serial: X6 serves the IDS01 decade switch (B002) and X8 is off (B004): "
                      "the CLM has no data interface, telegrams are not answered", file=sys.stderr, flush=True)
            return b""
        out = bytearray(self._automatic_message(settings))
        replies: list[tuple[bytes, bool]] = []
        snapshot: _Snapshot | None = None
        for byte in bytes(data):
            if byte in (0x0D, 0x0A):
                if not self._buffer and not self._overlong:
                    continue  # the empty line between CR and LF
                raw, overlong = bytes(self._buffer), self._overlong
                self._buffer.clear()
                self._overlong = False
                if snapshot is None and endpoint._store is not None and raw[:1] in (b"#", b"!"):
                    snapshot = _Snapshot(endpoint.rt.memory)
                replies.append(endpoint._answer(raw, overlong, settings))
                continue
            if byte in _FLOW:
                continue
            if len(self._buffer) >= MAX_LINE:
                self._overlong = True
            else:
                self._buffer.append(byte)
        if snapshot is not None and any(wrote for _, wrote in replies):
            try:
                endpoint._store()  # type: ignore[misc]
            except OSError as e:
                snapshot.restore(endpoint.rt.memory)
                print(f"clm serial: writes not stored ({e.strerror or e}); undone", file=sys.stderr, flush=True)
                refused = error_reply(18, settings.station)
                replies = [(refused if wrote and reply else reply, False) for reply, wrote in replies]
        for reply, _ in replies:
            out += reply
        return bytes(out)

    def _automatic_message(self, settings: Settings) -> bytes:
        rt = self.endpoint.rt
        fault = rt.modes.fault_error
        new = fault is not None and fault is not self._seen_fault
        self._seen_fault = fault
        if not (new and settings.auto_error and settings.station == 0):
            return b""
        try:
            return emit("X", 0, "", status_body(rt, 53, [])).encode("ascii")
        except Exception:
            return b""
