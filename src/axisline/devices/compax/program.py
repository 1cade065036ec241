"""The COMPAX program memory: numbered program sets N001 ... N250 and their commands (issue 19).

    from axisline.devices.compax.program import ProgramMemory, parse_command
    prog = ProgramMemory()
    prog.write(1, "P210=1"); prog.write(2, "SETC 1"); prog.write(6, "LOOP 1")
    prog.write(12, "GOTO 6")             # the target must be a stored set (E17 otherwise)
    prog.read(12)                         # "N012: GOTO 6"
    parse_command("If I8=1 GOTO 6")       # Command(kind=IF, args=(8, 1, 6))

The supplement builds its examples on program sets as the standard COMPAX keeps them
("N001: P210=1  Parallel mode", "N007: If I8=1 GOTO 6", "N012: GOTO 6", manual §15.2
L1474-1484, L1501-1510) and names the interpreter's two modes (P210, L1401-1415). This module
holds the sets and their grammar; `programrun` executes them. Lines are read as the ASCII
interface reads them: spaces do not matter, letters may be lower case.

Commands (the supplement's; `Kind`)
-----------------------------------
=====================  ==============================================================
``Pn=value``           parameter assignment (``P210=1``, L1474)
``VP`` / ``VC``        parameters valid
``SETC n`` ``SC n``    curve selection (n or ``.P40`` ... ``.P49``, L760)
``SETM x`` ``SM x``    master start point, % (0 ... 100)
``SETS`` ``SS``        curve start adjusted to the slave
``POSR CAM`` ``PR``    travel to the curve point
``LOOP m`` ``LP m``    cam operation, m travels (0 ... 65000)
``POSA x`` ``POSR x``  positioning, absolute / relative (units of the slave)
``POSA HOME``          machine datum travel
``SPEED x``            speed of POSA / POSR / POSR CAM, % of the slave's v_max
``ACCEL x``            their ramp time, ms from 0 to v_max
``WAIT x``             wait x ms
``GOTO n``             continue at set n
``IF In=x GOTO n``     jump when input In is x (0 / 1)
``OUTPUT On=x``        set output On (O1 ... O12)
``END``                end of the program
=====================  ==============================================================

Decisions (the standard COMPAX manual, which would define the program memory, is not among
the sources; each entry is decided from the supplement's usage; tests in
tests/devices/compax/test_program.py unless named)
----------------------------------------------------------------------------------------
1. Set numbers (L1474 "N001:" ... L1484 "N012:"): sets N001 ... N250, three digits in the
   read-back; a set is written over the interface as ``N<n>: <command>`` (colon optional,
   ``N1 SETC 1`` = ``N001: SETC 1``), read as ``N<n>`` -> ``N001: SETC 1`` (the command in
   its written form, single spaces, upper case), cleared with ``N<n>:`` and nothing after.
   250: the common size of a COMPAX program memory; the supplement's programs use 12.
   Test: test_a_set_is_written_read_back_and_cleared.
2. Gaps (L1477-1478: the listing goes from N004 to N006, N005 is absent): sets need not be
   consecutive; the program runs the stored sets in number order, so a gap is skipped, and
   it ends after its highest set (or at END). Test: test_gaps_are_skipped.
3. A jump to a missing set (GOTO n / IF ... GOTO n to an unprogrammed n) is the standard
   device's E17, whose "previous meaning, 'Selected set number not present', is retained"
   (L1939-1941): the line is refused with E17 and nothing is stored. Every stored jump
   resolves: a set that a jump targets cannot be cleared (E17 too), and a jump may only point
   to a set stored before it, so a host loads a forward target first; a program file is
   checked as a whole, so forward jumps need no order there. Reading a set that is not
   stored is E17 as well. Test: test_jump_to_a_missing_set_is_e17_and_changes_nothing.
4. Locked commands (L164 "Locked Commands: Label related positioning; GOSUB EXT; OUTPUT O0;
   SPEED SYNC; GOTO EXT; Fast start via I15"): GOSUB EXT, GOTO EXT, OUTPUT O0 (any value)
   and SPEED SYNC are recognised and refused with E107 "command not available" (axisline's
   number; the supplement gives none) naming the supplement's list, as a set and as a direct
   interface line. Label related positioning and the fast start are not commands of this
   grammar (their standard syntax is not in the sources); a line in an unknown form is E101.
   Test: test_locked_commands_are_refused_with_e107.
5. OUTPUT (L641 "O13 and O14 cannot be used by means of the OUTPUT-command", L971 "Beyond cam
   operation (by LOOP n) the outputs O7 to O12 are accessible by OUTPUT"): OUTPUT O1 ... O12
   with 0 or 1 is stored; O13 ... O16 are refused at once (E107, the device drives them); O7
   ... O12 during cam operation are refused when the set runs (camop.set_output).
   Test: test_a_malformed_set_gets_the_devices_error_and_changes_nothing.
6. IF (L1506 "If I8=1 GOTO 6"): the only condition form of the supplement, ``IF In=x GOTO
   n`` with an input I1 ... I16 and x = 0 or 1; inputs not wired in [device].inputs read 0.
   Test: test_programs_of_the_manual.py::test_variable_linking_repeats_curve_1_while_i8_then_curve_2.
7. WAIT x (the start-up list's WAIT ms): 0 ... 65000 ms, rounded up to whole 1 ms cycles.
   Test: test_programrun.py::test_wait_takes_its_milliseconds.
8. SPEED / ACCEL (L787 POSR CAM "with the values adjusted by means of ACCEL and SPEED"; their
   units are the standard manual's [GAP]): SPEED x in % of the slave axis' v_max (0 < x <=
   100, default 100), ACCEL x as the ramp time in ms from 0 to v_max (1 ... 65000; default:
   the axis' a_max), for the acceleration and the braking ramp alike. They apply to the
   following POSA, POSR and POSR CAM. Test: test_speed_and_accel_apply_to_the_positioning_sets.
9. POSA x / POSR x: x in the slave's units, |x| <= 4 000 000 (L301 "The max. travel distance is
   limited to +-4 million units"). Test: test_a_malformed_set_gets_the_devices_error_and_changes_nothing.
10. Parameter assignments are checked when the set is stored (number E105, value E103), as an
   interface write would be, and take effect when the set runs (program sets change the
   working parameters, not the parameter file: a program's ``P210=1`` is not an operator's
   parameter change). Test: test_a_malformed_set_gets_the_devices_error_and_changes_nothing,
   test_programs_of_the_manual.py::test_sec_14_master_related_label_setup_procedure.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from enum import Enum
from typing import Any, Iterable

from axisline.devices.compax import E_CURVE_NOT_PRESENT, E_NOT_AVAILABLE, E_SYNTAX, E_VALUE, CompaxError
from axisline.devices.compax.parameters import Parameters

__all__ = [
    "MAX_SET",
    "MOTION_KINDS",
    "Command",
    "Kind",
    "ProgramMemory",
    "format_set",
    "parse_command",
    "parse_set_line",
]

#: Highest set number (decision 1).
MAX_SET = 250
MAX_TRAVEL = 4_000_000.0  # L301: "+-4 million units"
LOCKED_TEXT = "locked in the COMPAX XX70 (supplement sec. 2: label related positioning, GOSUB EXT, OUTPUT O0, SPEED SYNC, GOTO EXT)"


class Kind(str, Enum):
    PARAM = "P"
    VP = "VP"
    VC = "VC"
    SETC = "SETC"
    SETM = "SETM"
    SETS = "SETS"
    POSR_CAM = "POSR CAM"
    LOOP = "LOOP"
    POSA = "POSA"
    POSR = "POSR"
    POSA_HOME = "POSA HOME"
    SPEED = "SPEED"
    ACCEL = "ACCEL"
    WAIT = "WAIT"
    GOTO = "GOTO"
    IF = "IF"
    OUTPUT = "OUTPUT"
    END = "END"


#: Positioning commands: the sequencing rules of P210 apply to them (L1403-1407).
MOTION_KINDS = (Kind.POSR_CAM, Kind.LOOP, Kind.POSA, Kind.POSR, Kind.POSA_HOME)


@dataclass(frozen=True)
class Command:
    """One parsed command: its kind, its arguments and its written form (``text``)."""

    kind: Kind
    args: tuple[Any, ...]
    text: str

    @property
    def target(self) -> int | None:
        """The set a GOTO / IF jumps to."""
        if self.kind is Kind.GOTO:
            return int(self.args[0])
        if self.kind is Kind.IF:
            return int(self.args[2])
        return None


_NUM = r"[+-]?(?:\d+(?:\.\d*)?|\.\d+)"
_OPERAND = rf"(\.P\d+|{_NUM})"
_SIMPLE = {"VP": Kind.VP, "VC": Kind.VC, "SETS": Kind.SETS, "SS": Kind.SETS, "POSRCAM": Kind.POSR_CAM,
           "PR": Kind.POSR_CAM, "POSAHOME": Kind.POSA_HOME, "END": Kind.END}
_LOCKED = re.compile(r"GOSUBEXT|GOTOEXT|SPEEDSYNC|OUTPUTO0(=.*)?")
_FORMS: tuple[tuple[re.Pattern[str], Kind], ...] = tuple(
    (re.compile(p), k)
    for p, k in (
        (r"P(\d+)=(" + _NUM + ")", Kind.PARAM),
        (r"(?:SETC|SC)" + _OPERAND, Kind.SETC),
        (r"(?:SETM|SM)" + _OPERAND, Kind.SETM),
        (r"(?:LOOP|LP)" + _OPERAND, Kind.LOOP),
        (r"POSA(" + _NUM + ")", Kind.POSA),
        (r"POSR(" + _NUM + ")", Kind.POSR),
        (r"SPEED(" + _NUM + ")", Kind.SPEED),
        (r"ACCEL(" + _NUM + ")", Kind.ACCEL),
        (r"WAIT(" + _NUM + ")", Kind.WAIT),
        (r"GOTO(\d+)", Kind.GOTO),
        (r"IFI(\d+)=(\d+)GOTO(\d+)", Kind.IF),
        (r"OUTPUTO(\d+)=(\d+)", Kind.OUTPUT),
    )
)
_SET_LINE = re.compile(r"N(\d+)(:?)(.*)")


def _err(code: int, text: str, message: str, field: str, value: Any, allowed: str | None = None) -> CompaxError:
    return CompaxError(f"{text!r}: {message}", code=code, field=field, value=value, allowed=allowed)


def _number(raw: str) -> float:
    return float(raw)


def _operand(text: str, raw: str, name: str, lo: float, hi: float, integer: bool) -> Any:
    """A number in lo ... hi, or an operation parameter .P40 ... .P49 (kept as the string)."""
    if raw.startswith(".P"):
        n = int(raw[2:])
        if not 40 <= n <= 49:
            raise _err(E_VALUE, text, f".P{n} not allowed; commands may refer to P40 ... P49", name, raw, ".P40 ... .P49")
        return raw
    value = _number(raw)
    if integer and value != int(value):
        raise _err(E_VALUE, text, f"{name} {raw} must be a whole number", name, raw, f"{lo:g} ... {hi:g}")
    if not lo <= value <= hi:
        raise _err(E_VALUE, text, f"{name} {raw} out of range; allowed is {lo:g} ... {hi:g}", name, raw, f"{lo:g} ... {hi:g}")
    return int(value) if integer else value


def _range(text: str, value: float, name: str, lo: float, hi: float, *, low_open: bool = False) -> None:
    if not (lo < value <= hi if low_open else lo <= value <= hi):
        allowed = f"{'more than ' if low_open else ''}{lo:g} ... {hi:g}"
        raise _err(E_VALUE, text, f"{name} {value:g} out of range; allowed is {allowed}", name, value, allowed)


def parse_command(text: str) -> Command:
    """The command of one program set (decisions 4 ... 10); raises CompaxError (E101 malformed,
    E103 value, E105 parameter number, E107 locked)."""
    shown = " ".join(text.split())
    key = "".join(text.split()).upper()
    if not key:
        raise _err(E_SYNTAX, shown, "empty command", "command", text)
    if not key.isascii() or not key.isprintable():
        raise _err(E_SYNTAX, shown, "only printable ASCII is allowed", "command", text)
    if _LOCKED.fullmatch(key):
        raise _err(E_NOT_AVAILABLE, shown, LOCKED_TEXT, "command", shown, "not a locked command")
    simple = _SIMPLE.get(key)
    if simple is not None:
        return Command(simple, (), simple.value)
    for pattern, kind in _FORMS:
        m = pattern.fullmatch(key)
        if m is not None:
            return _build(kind, m.groups(), shown)
    raise _err(E_SYNTAX, shown, "not a program command of the COMPAX XX70 (see docs/compax.md)", "command", text)


def _build(kind: Kind, g: tuple[str, ...], shown: str) -> Command:
    if kind is Kind.PARAM:
        number, raw = int(g[0]), g[1]
        probe = Parameters()
        probe[number] = float(raw) if "." in raw else int(raw)  # E105 unknown number, E103 range
        return Command(kind, (number, probe.written[number]), f"P{number}={raw}")
    if kind is Kind.SETC:
        return Command(kind, (_operand(shown, g[0], "SETC", 1, 100, True),), f"SETC {g[0]}")
    if kind is Kind.SETM:
        return Command(kind, (_operand(shown, g[0], "SETM", 0, 100, False),), f"SETM {g[0]}")
    if kind is Kind.LOOP:
        return Command(kind, (_operand(shown, g[0], "LOOP", 0, 65000, True),), f"LOOP {g[0]}")
    value = _number(g[0]) if kind in (Kind.POSA, Kind.POSR, Kind.SPEED, Kind.ACCEL, Kind.WAIT) else 0.0
    if kind in (Kind.POSA, Kind.POSR):
        _range(shown, value, kind.value, -MAX_TRAVEL, MAX_TRAVEL)
        return Command(kind, (value,), f"{kind.value} {g[0]}")
    if kind is Kind.SPEED:
        _range(shown, value, "SPEED", 0.0, 100.0, low_open=True)
        return Command(kind, (value,), f"SPEED {g[0]}")
    if kind is Kind.ACCEL:
        _range(shown, value, "ACCEL", 1.0, 65000.0)
        return Command(kind, (value,), f"ACCEL {g[0]}")
    if kind is Kind.WAIT:
        _range(shown, value, "WAIT", 0.0, 65000.0)
        return Command(kind, (value,), f"WAIT {g[0]}")
    if kind is Kind.GOTO:
        n = _set_number(shown, g[0])
        return Command(kind, (n,), f"GOTO {n}")
    if kind is Kind.IF:
        i, x, n = int(g[0]), int(g[1]), _set_number(shown, g[2])
        _range(shown, i, "input I", 1, 16)
        _range(shown, x, "input value", 0, 1)
        return Command(kind, (i, x, n), f"IF I{i}={x} GOTO {n}")
    # OUTPUT
    o, x = int(g[0]), int(g[1])
    if o in (13, 14, 15, 16):
        raise _err(E_NOT_AVAILABLE, shown, f"O{o} is not available by OUTPUT (O13/O14 only as auxiliary functions, "
                   "O15/O16 are the device's)", "OUTPUT", o, "O1 ... O12")
    _range(shown, o, "output O", 1, 12)
    _range(shown, x, "output value", 0, 1)
    return Command(kind, (o, x), f"OUTPUT O{o}={x}")


def _set_number(text: str, raw: str) -> int:
    n = int(raw)
    if not 1 <= n <= MAX_SET:
        raise _err(E_VALUE, text, f"set N{n} out of range; allowed is N001 ... N{MAX_SET:03d}", "set", n,
                   f"1 ... {MAX_SET}")
    return n


def parse_set_line(line: str) -> tuple[int, str | None] | None:
    """``N<n>[:] [command]`` -> (n, command text, None to read, '' to clear); None: not a set line."""
    key = "".join(line.split()).upper()
    m = _SET_LINE.fullmatch(key)
    if m is None or not m[1]:
        return None
    n = _set_number(line.strip(), m[1])
    if not m[2] and not m[3]:
        return n, None
    # the command keeps its own spaces for the error texts: take it from the line as given
    raw = line.split(":", 1)[1] if ":" in line else re.sub(r"^\s*[Nn]\s*\d+", "", line, count=1)
    return n, raw.strip()


def format_set(number: int, command: Command) -> str:
    """The read-back form ``N001: SETC 1``."""
    return f"N{number:03d}: {command.text}"


class ProgramMemory:
    """The program sets N001 ... N250 (see the module doc). Every change is all or nothing."""

    def __init__(self) -> None:
        self._sets: dict[int, Command] = {}

    # -- reading -----------------------------------------------------------------------------

    def __len__(self) -> int:
        return len(self._sets)

    def __contains__(self, number: object) -> bool:
        return number in self._sets

    def numbers(self) -> list[int]:
        return sorted(self._sets)

    def command(self, number: int) -> Command:
        try:
            return self._sets[number]
        except KeyError:
            raise CompaxError(f"N{number:03d}: selected set number not present (E17)", code=E_CURVE_NOT_PRESENT,
                              field="set", value=number, allowed=self._stored_text()) from None

    def read(self, number: int) -> str:
        return format_set(number, self.command(number))

    def first(self) -> int | None:
        return min(self._sets) if self._sets else None

    def next_after(self, number: int) -> int | None:
        """The stored set following `number` (gaps skipped, decision 2), None after the last."""
        later = [n for n in self._sets if n > number]
        return min(later) if later else None

    def lines(self) -> list[str]:
        return [format_set(n, self._sets[n]) for n in sorted(self._sets)]

    def _stored_text(self) -> str:
        return "a stored set (" + (", ".join(f"N{n:03d}" for n in sorted(self._sets)[:8]) or "none") + \
            (", ..." if len(self._sets) > 8 else "") + ")"

    # -- writing -----------------------------------------------------------------------------

    def write(self, number: int, text: str) -> Command:
        """Store set `number` (decisions 1, 3); its jump target must be stored already."""
        _set_number(f"N{number}", str(number))
        command = parse_command(text)
        target = command.target
        if target is not None and target not in self._sets and target != number:
            raise CompaxError(f"N{number:03d}: {command.text}: set N{target:03d} not present (E17; store it first)",
                              code=E_CURVE_NOT_PRESENT, field="set", value=target, allowed=self._stored_text())
        self._sets[number] = command
        return command

    def clear(self, number: int) -> None:
        """Clear set `number` (nothing if it is not stored); refused while a jump targets it."""
        _set_number(f"N{number}", str(number))
        users = [n for n, c in self._sets.items() if c.target == number and n != number]
        if users:
            raise CompaxError(f"N{number:03d} cannot be cleared: N{users[0]:03d} jumps to it (E17)",
                              code=E_CURVE_NOT_PRESENT, field="set", value=number,
                              allowed="a set no GOTO / IF points to")
        self._sets.pop(number, None)

    def replace(self, lines: Iterable[str], source: str = "program") -> None:
        """Take a whole program (``N001: ...`` lines); checked as a whole, so forward jumps are
        fine (decision 3). A problem names the line; nothing changes then."""
        new = ProgramMemory()
        for k, line in enumerate(lines, 1):
            parsed = None
            try:
                parsed = parse_set_line(line)
                if parsed is None or parsed[1] is None or parsed[1] == "":
                    raise CompaxError("not a program set 'N<n>: <command>'", code=E_SYNTAX, field="line", value=line)
                number, text = parsed
                if number in new._sets:
                    raise CompaxError(f"N{number:03d} given twice", code=E_VALUE, field="set", value=number)
                new._sets[number] = parse_command(text)
            except CompaxError as e:
                raise CompaxError(f"{source}: line {k} {line.strip()!r}: {e}", code=e.code, field=f"{source}[{k}]",
                                  value=line, allowed=e.allowed) from None
        for number, command in new._sets.items():
            target = command.target
            if target is not None and target not in new._sets:
                raise CompaxError(f"{source}: N{number:03d} {command.text}: set N{target:03d} not present (E17, "
                                  "selected set number not present)",
                                  code=E_CURVE_NOT_PRESENT, field=f"N{number:03d}", value=target)
        self._sets = new._sets

    def copy(self) -> ProgramMemory:
        other = ProgramMemory()
        other._sets = dict(self._sets)
        return other

    def restore(self, snapshot: ProgramMemory) -> None:
        self._sets = dict(snapshot._sets)

    def __eq__(self, other: object) -> bool:
        return isinstance(other, ProgramMemory) and self._sets == other._sets

    __hash__ = None  # type: ignore[assignment]

    def __repr__(self) -> str:
        return f"ProgramMemory({len(self._sets)} sets)"


def read_program_file(path: Any, limit: int = 1 << 20) -> list[str]:
    """The set lines of a program file: ``N001: P210=1`` per line; ``#`` or ``;`` starts a
    comment, blank lines are skipped (the manual's listings carry a comment column)."""
    from axisline.configerrors import read_text

    lines = []
    for raw in read_text(path, limit).splitlines():
        line = re.split(r"[#;]", raw, maxsplit=1)[0].strip()
        if line:
            lines.append(line)
    return lines
