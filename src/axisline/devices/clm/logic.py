"""The CLM Logic Task: 1000 instructions 0000-0999, compiled once, scanned every 4 ms or more.

    lines, findings = read_logic_text(text, "edge.lt")      # listing lines or #sP telegrams
    program = compile_logic(lines)                           # raises LogicError (fault 38)
    program.scan(image)                                      # one whole scan on a ProcessImage
    program.scan_time_ms                                     # max(4, assignments) ms

Manual chapter 6 (L2959-3170), spec §3.8, errata §1.2, §1.3, §1.18. The language is an
instruction list with one current value: ``LD``/``LDN`` load an operand (negated), ``AND``,
``OR``, ``XOR`` and their ``N`` forms combine it with an operand, ``AND(`` ... ``)`` with the
value of a term, ``ST``/``STN`` assign it, ``SET``/``RES`` set or reset a bit unconditionally,
``SETC``/``RESC`` when the current value is TRUE and ``SETCN``/``RESCN`` when it is FALSE
(L3033-3045). ``NOP`` does nothing, ``END`` ends the program (L3124-3126).

Operand rights (L3025-3027): loads and logic read M0, M1, M4-M6, Q0-Q2, I0-I2; store, set and
reset write M5, M6, Q1, Q2.02-Q2.05. A fault in the program is ``38`` "Logic Prg. Error" at
``LTnnnn``: an invalid command, an invalid input/output/marker number, no ``END``, parentheses
in the wrong place (L8651-8656). Over the serial line each instruction is checked as it
arrives: an unknown command is Status 01 error 13, an invalid operand error 25 (L6823). The
keypad refuses an instruction with a ``?`` in it (L2993); `read_logic_text` refuses in the same
way, one finding per line, and stores only what the CLM would have stored. Writing needs
Parameter mode (L2961, errata §1.2): that gate belongs to the serial endpoint, not to files.

File forms (`read_logic_text` reads both, also mixed):

* listing lines ``0000<tab>LD<tab>M6.20.0<tab>- comment`` like the manual's NC listings: a
  number, the instruction, a comment after a blank and ``-`` or after ``;``; lines that begin
  with ``;`` or ``#`` are comments. A line without a number follows the line before, so the
  manual's examples (L3142-3146) can be pasted as printed.
* telegrams ``#sP0000 LD M6.20.0 $hh`` (decision 10) and the CLM's read-back ``Ps0000 ...``.

Instructions not given are ``NOP``.

Decisions (spec line -> choice, why)
------------------------------------
1. Errata §1.18 "bit-by-bit" (L3036 STN, L3051/L3074/L3099 "functions bit-by-bit", L3054
   "bit-by-bit negated value") against "Setting the bit operand" (L3040-3045) -> ``LD LDN ST
   STN`` and the logic instructions take a bit (``M6.20.0``) or a byte (``M6.20``); a byte is
   combined on all 8 bits at once. ``SET``... ``RESCN`` take bits only. The current value has
   the width of its ``LD``; an operand of the other width in the same chain, or a conditional
   set on a byte result, is fault 38 (the manual gives no meaning to mixing, so the program is
   refused rather than guessed at). Tests: test_byte_operands_work_on_all_8_bits,
   test_width_mixing_is_fault_38, test_set_and_reset_take_bits_only.
2. "LT parentheses with or without an operand" (errata §1, open) -> both. ``AND(`` alone
   opens "the following term" (L3055), which must then start with ``LD``/``LDN``;
   ``AND( M6.20.0`` opens a term already loaded with the operand, as an IEC 61131-3
   instruction list reads it. The text is kept as written. Test:
   test_parentheses_with_and_without_operand.
3. Nesting depth -> no limit but the memory (at most 499 levels). The manual names its limits
   where it has them (JSR: 127 levels, L2058) and for parentheses only "the positioning ... is
   wrong" (L8656). Test: test_deep_nesting_is_accepted.
4. An instruction that uses the current value before any ``LD``/``LDN`` in its term (at the
   start of the program, first in an operand-less term, ``)`` of an empty term) -> fault 38 at
   that instruction: "current value" (L3053) presupposes a load, and every example starts
   with one (L3142, L3162). Test: test_value_used_before_load_is_fault_38.
5. ``END`` (L2995, L2997) -> the program is 0000 up to the first ``END``; what follows is not
   compiled and never runs (a warning in `check_logic` only). Evidence: ``!sCNOPLTvvvvbbbb``
   writes ``END`` to 0000 and leaves the instructions after bbbb as they were (L7453-7462),
   and that must deactivate the task whatever those hold. ``END`` at 0000 -> the program is
   inactive (``active`` False, `scan` does nothing). Tests: test_after_end_is_not_compiled,
   test_end_at_0000_deactivates.
6. No ``END`` -> fault 38 at the instruction after the last one given (where ``END`` belongs,
   0999 at most); an unclosed parenthesis -> fault 38 at its opening instruction, a ``)``
   without one at the ``)``. Test: test_fault_38_causes_name_their_instruction.
7. When a scan sees what (L5720/L5724/L5728: inputs, outputs and markers "are read at the
   beginning of each cycle or at the start of the Logic Task"; errata §1.3) -> one `scan` call
   is one whole scan; the image handed in is the I/O as sampled at its start (the caller,
   part 2, hands the image at each scan start; what the NC tasks change during a scan is seen
   by the next one). Within the scan an instruction reads what earlier instructions of the
   same scan wrote, as tasks do within an NC cycle (errata §3.5). The edge examples
   (L3142-3166) give a one-scan pulse under this reading: the intermediate flag is read
   before it is written, so it holds the previous scan's input. Tests:
   test_positive_edge_gives_one_scan_pulse, test_negative_edge_gives_one_scan_pulse,
   test_later_instructions_see_earlier_writes.
8. Scan time (L2963 "1000 assignments/sec ... minimum cycle time of 4 ms", errata §1.3) ->
   ``max(4, N)`` ms with N the instructions 0000 up to and including ``END``: ``NOP``,
   ``)`` and ``END`` are "Other Assignments" (L3122-3126) and cost their place. Test:
   test_scan_time.
9. AND/ANDN truth tables: the manual's figures lost their values (L3060-3070) -> the
   definitions (L3053-3054) give AND 1 0 0 0 and ANDN 0 0 1 0 for bool1 = 1 0 1 0, bool2 =
   1 1 0 0; OR, ORN, XOR, XORN are the printed tables (L3085, L3092, L3110, L3117). Test:
   test_truth_tables.
10. Write telegram: printed ``#sPx xx_x_d d d d d d d d_$h h C R L F`` (L6729), garbled like
    its own ``$h h C R L F``; it holds four ``x``, as the read-back ``Psxxxx_dddddddd_$hh``
    (L6718) does -> ``#sPnnnn_<instruction>_$hh``: the number, a blank, the command, a blank
    and the operand, a blank before ``$`` as in the NC telegrams (errata §1.8). Reading also
    takes a blank before the number (as in the query ``?sP_xxxx``, L6712) and any blanks
    between the fields; the instruction field has at most 16 characters (L6724, L6735). A
    malformed number is Status 01 error 01, a number above 0999 error 12, an unknown
    command 13, an invalid operand 25. Tests: test_telegram_round_trip, test_telegram_forms_read,
    test_telegram_errors_carry_status_01_codes.
11. `logic_telegrams` sends every instruction 0000 up to the last one given, the gaps as
    ``NOP``, so the CLM's memory matches the file whatever it held before (decision 5 makes
    what lies beyond an ``END`` irrelevant). `logic_listing` lists only what is not ``NOP``.
    Test: test_telegram_round_trip, test_listing_round_trip.
12. A listing that gives a number twice -> the later line is kept (as a second telegram would
    overwrite the first) and a warning says so. Test: test_listing_forms_read.
"""

from __future__ import annotations

import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

from .errors import ClmError, Finding, serial_code
from .image import ProcessImage
from .operands import LT_READ, LT_WRITE, Operand, parse_operand, usable
from .telegram import emit, parse_telegram

__all__ = [
    "INSTRUCTIONS",
    "LT_INSTRUCTIONS",
    "Instruction",
    "LogicError",
    "LogicProgram",
    "check_logic",
    "compile_logic",
    "logic_listing",
    "logic_telegrams",
    "parse_instruction",
    "read_logic_text",
    "scan_time_ms",
]

#: Instructions 0000-0999 (L2961).
LT_INSTRUCTIONS = 1000
FAULT = "38"
#: The instruction field of a telegram holds at most 16 characters (L6724, L6735).
DATA_WIDTH = 16
MIN_SCAN_MS = 4.0

_LOADS = ("LD", "LDN")
_STORES = ("ST", "STN")
_SETS = ("SET", "SETC", "SETCN", "RES", "RESC", "RESCN")
_LOGIC = ("AND", "ANDN", "OR", "ORN", "XOR", "XORN")
_OPENS = tuple(f"{m}(" for m in _LOGIC)
_OTHERS = (")", "END", "NOP")
#: The 25 Logic Task instructions (Fig. 6-1, L3011-3021).
INSTRUCTIONS = _LOADS + _STORES + _SETS + _LOGIC + _OPENS + _OTHERS

_READ_AREAS = "M0, M1, M4-M6, Q0-Q2, I0-I2 (L3025)"
_WRITE_AREAS = "M5, M6, Q1, Q2.02-Q2.05 (L3027)"

# Widths of the current value (decision 1); _UNKNOWN after an instruction that was refused,
# so that one bad line does not drag a chain of follow-up faults behind it.
_BIT, _BYTE, _UNKNOWN = 1, 8, 0


@dataclass(frozen=True, slots=True)
class Instruction:
    """One Logic Task instruction: ``LD M6.20.0``, ``AND(``, ``)``, ``END``."""

    mnemonic: str
    operand: Operand | None = None

    def __str__(self) -> str:
        return self.mnemonic if self.operand is None else f"{self.mnemonic} {self.operand}"


class LogicError(ClmError):
    """Fault 38: the program has errors and does not run; ``errors`` holds all of them."""

    def __init__(self, errors: Sequence[ClmError]) -> None:
        self.errors = tuple(errors)
        first = self.errors[0]
        more = f" (and {len(self.errors) - 1} more)" if len(self.errors) > 1 else ""
        super().__init__(first.code, first.detail + more, first.where)


def _where(number: int) -> str:
    return f"LT{number:04d}"


def _shown(text: str) -> str:
    text = text.strip()
    return repr(text if len(text) <= 20 else text[:20] + "...")


_INSTRUCTION = re.compile(r"\s*(\)|[A-Za-z]+\s*\(|[A-Za-z]+)\s*(.*?)\s*\Z", re.DOTALL)


def _mnemonic_of(text: str) -> str:
    """The command word of an instruction text, upper case (``'andn ('`` -> ``'ANDN('``)."""
    m = _INSTRUCTION.match(text) if text.isascii() else None
    return re.sub(r"\s+", "", m.group(1)).upper() if m else ""


def parse_instruction(text: str, number: int, *, serial: bool = False) -> Instruction:
    """Check one instruction as the CLM does when it is entered (keypad, file or telegram).

    Raises `ClmError` at ``LTnnnn``: fault 38, or with `serial` Status 01 error 13 (unknown
    command) / 25 (invalid operand). Whether the program as a whole is sound (``END``,
    parentheses, a loaded value) is `compile_logic`'s question.
    """
    where = _where(number)
    bad_command = serial_code(13) if serial else FAULT
    bad_operand = serial_code(25) if serial else FAULT
    mnemonic = _mnemonic_of(text)
    if mnemonic not in INSTRUCTIONS:
        raise ClmError(bad_command, f"{_shown(text)} is not a Logic Task command (L3011-3021: {' '.join(INSTRUCTIONS)})", where)
    m = _INSTRUCTION.match(text)
    assert m is not None
    rest = m.group(2).upper()
    if mnemonic in _OTHERS:
        if rest:
            raise ClmError(bad_operand, f"{mnemonic} takes no operand, {_shown(rest)} given", where)
        return Instruction(mnemonic)
    if not rest:
        if mnemonic in _OPENS:
            return Instruction(mnemonic)  # decision 2
        raise ClmError(bad_operand, f"{mnemonic} needs an operand", where)
    if any(c.isspace() for c in rest):
        raise ClmError(bad_operand, f"{mnemonic} takes one operand, {_shown(rest)} given", where)
    bit = rest.count(".") == 2
    try:
        op = parse_operand(rest, bit=bit, code=bad_operand)
    except ClmError as error:
        raise error.at(where) from None
    if mnemonic in _SETS and not op.is_bit:
        raise ClmError(bad_operand, f"{mnemonic} takes a bit operand (L3040-3045 'Setting the bit operand'), not the byte {op}", where)
    if mnemonic in _STORES or mnemonic in _SETS:
        if not usable(op, LT_WRITE):
            raise ClmError(bad_operand, f"{op} may not be written by the Logic Task: {mnemonic} writes {_WRITE_AREAS}", where)
    elif not usable(op, LT_READ):
        raise ClmError(bad_operand, f"{op} may not be read by the Logic Task: {mnemonic} reads {_READ_AREAS}", where)
    return Instruction(mnemonic, op)


# -- compiling ------------------------------------------------------------------------------------

# The compiled program is a flat list of (code, index, shift, mask, invert) over ProcessImage.data:
# the operand's value is data[index] >> shift & mask; invert is 1 (bit) / 0xFF (byte) for the
# negated forms and 0 otherwise.
_LOAD, _AND, _OR, _XOR, _STORE, _SET, _RES, _SETC, _RESC, _OPEN_AND, _OPEN_OR, _OPEN_XOR, _CLOSE = range(13)
_COMBINE = {"AND": _AND, "OR": _OR, "XOR": _XOR}
_OPEN = {"AND": _OPEN_AND, "OR": _OPEN_OR, "XOR": _OPEN_XOR}
_NO_OPERAND = -1

Op = tuple[int, int, int, int, int]


def _memory(lines: Mapping[int, str] | Sequence[str], errors: list[ClmError]) -> dict[int, str]:
    """The instructions given, by number; numbers outside 0000-0999 are faults."""
    items = lines.items() if isinstance(lines, Mapping) else enumerate(lines)
    memory: dict[int, str] = {}
    for number, text in items:
        if not isinstance(text, str):
            raise TypeError(f"Logic Task instruction {number}: text expected, {type(text).__name__} given")
        if not isinstance(number, int) or not 0 <= number < LT_INSTRUCTIONS:
            errors.append(ClmError(FAULT, f"instruction number {number}: the Logic Task has 0000-0999 (L2961)", f"LT{number}"))
            continue
        memory[number] = text
    return memory


def _width(op: Operand) -> int:
    return _BIT if op.is_bit else _BYTE


def _width_name(width: int) -> str:
    return "bit" if width == _BIT else "byte"


def _place(op: Operand, invert: bool, code: int) -> Op:
    at, shift, mask = ProcessImage.locate(op)
    return (code, at, shift, mask, (1 if op.is_bit else 0xFF) if invert else 0)


@dataclass
class _Term:
    """One level of the current value: the program level, or a term in parentheses."""

    opener: int  # the LT number of AND( ...; -1 for the program level
    mnemonic: str
    width: int | None  # _BIT, _BYTE, _UNKNOWN, or None before the first load


def _compile(lines: Mapping[int, str] | Sequence[str]) -> tuple[LogicProgram | None, list[ClmError], list[Finding]]:
    errors: list[ClmError] = []
    warnings: list[Finding] = []
    memory = _memory(lines, errors)
    instructions: dict[int, Instruction] = {}
    ops: list[Op] = []
    writes: list[Operand] = []
    terms = [_Term(-1, "", None)]
    end: int | None = None

    def fault(number: int, detail: str) -> None:
        errors.append(ClmError(FAULT, detail, _where(number)))

    for number in sorted(memory):
        text = memory[number]
        if not text.strip():
            continue  # an empty place is a NOP, as an unlisted one
        try:
            ins = parse_instruction(text, number)
        except ClmError as error:
            errors.append(error)
            # keep the parentheses' structure of a refused AND( ... or ), so that its partner
            # is not reported as well
            refused = _mnemonic_of(text)
            if refused in _OPENS:
                terms.append(_Term(number, refused, _UNKNOWN))
            elif refused == ")" and len(terms) > 1:
                terms.pop()
            terms[-1].width = _UNKNOWN
            continue
        mnemonic, op, term = ins.mnemonic, ins.operand, terms[-1]
        if mnemonic == "NOP":
            continue
        instructions[number] = ins
        if mnemonic == "END":
            end = number
            break
        if mnemonic in _LOADS:
            assert op is not None
            term.width = _width(op)
            ops.append(_place(op, mnemonic == "LDN", _LOAD))
            continue
        if mnemonic in ("SET", "RES"):
            assert op is not None
            writes.append(op)
            ops.append(_place(op, False, _SET if mnemonic == "SET" else _RES))
            continue
        if mnemonic == ")":
            if len(terms) == 1:
                fault(number, "')' without an open parenthesis before it (L8656)")
                continue
            if term.width is None:
                fault(number, f"the term opened by {term.mnemonic} at {_where(term.opener)} has no value: "
                              f"begin it with LD/LDN or give {term.mnemonic} an operand")
            terms.pop()
            outer = terms[-1]
            if term.width and outer.width and term.width != outer.width:
                fault(number, f"the term opened at {_where(term.opener)} is a {_width_name(term.width)} but the value "
                              f"before it is a {_width_name(outer.width)}: the logic works bit-by-bit on one width (L3051)")
            negated = term.mnemonic.endswith("N(")
            ops.append((_CLOSE, 0, 0, 0, (1 if term.width == _BIT else 0xFF) if negated else 0))
            continue
        # every other instruction works on the current value
        if term.width is None:
            where = f"the term opened at {_where(term.opener)}" if len(terms) > 1 else "the program"
            fault(number, f"{mnemonic} uses the current value, but {where} has loaded none: begin with LD or LDN (L3053)")
            term.width = _UNKNOWN
        if mnemonic in _OPENS:
            at, shift, mask = ProcessImage.locate(op) if op else (_NO_OPERAND, 0, 0)
            ops.append((_OPEN[mnemonic[:-1].removesuffix("N")], at, shift, mask, 0))
            terms.append(_Term(number, mnemonic, _width(op) if op else None))
            continue
        assert op is not None
        if mnemonic in ("SETC", "SETCN", "RESC", "RESCN"):
            if term.width == _BYTE:
                fault(number, f"{mnemonic} acts on a TRUE/FALSE result (L3041-3045), but the current value is a byte")
            writes.append(op)
            at, shift, mask = ProcessImage.locate(op)
            ops.append((_SETC if mnemonic.startswith("SET") else _RESC, at, shift, mask, 1 if mnemonic.endswith("N") else 0))
            continue
        if term.width and term.width != _width(op):
            fault(number, f"{op} is a {_width_name(_width(op))} but the current value is a {_width_name(term.width)}: "
                          "the logic works bit-by-bit on one width (L3051)")
        if mnemonic in _STORES:
            writes.append(op)
            ops.append(_place(op, mnemonic == "STN", _STORE))
        else:
            base = mnemonic.removesuffix("N")
            ops.append(_place(op, base != mnemonic, _COMBINE[base]))

    if end is None:
        at = min(max(memory, default=-1) + 1, LT_INSTRUCTIONS - 1)
        fault(at, f"no END: the Logic Task program must end with END (L2995); END belongs at {_where(at)}")
    for term in terms[1:]:
        closing = f"END at {_where(end)}" if end is not None else "the end of the memory"
        fault(term.opener, f"{term.mnemonic} is not closed by ')' before {closing} (L8656)")
    if end is not None:
        after = [n for n in sorted(memory) if n > end and memory[n].strip().upper() not in ("", "NOP")]
        if after:
            span = f"{_where(after[0])}-{_where(after[-1])}"
            text = f"{len(after)} instruction(s) after END at {_where(end)} ({span}) are not compiled and never run (L2997)"
            warnings.append(Finding(_where(after[0]), FAULT, text, "warning"))
    if errors:
        return None, errors, warnings
    assert end is not None
    return LogicProgram(instructions, end, ops, writes), errors, warnings


def compile_logic(lines: Mapping[int, str] | Sequence[str]) -> LogicProgram:
    """Compile the Logic Task as the CLM does on leaving Parameter mode (L2961).

    `lines` maps instruction numbers to instruction texts (``'LD M6.20.0'``), or lists them
    from 0000; a missing or blank place is ``NOP``. Raises `LogicError` (fault 38) with every
    error found: a program with any error does not run.
    """
    program, errors, _ = _compile(lines)
    if program is None:
        raise LogicError(errors)
    return program


def check_logic(lines: Mapping[int, str] | Sequence[str]) -> list[Finding]:
    """Every error (and the warning about instructions after END) of `compile_logic`."""
    _, errors, warnings = _compile(lines)
    return [Finding.of(error) for error in errors] + warnings


def scan_time_ms(n_assignments: int) -> float:
    """One scan of `n_assignments` instructions: about 1 ms each, at least 4 ms (L2963, errata §1.3)."""
    return max(MIN_SCAN_MS, float(n_assignments))


class LogicProgram:
    """A compiled, error-free Logic Task (build it with `compile_logic`)."""

    __slots__ = ("_ops", "end", "instructions", "writes")

    def __init__(self, instructions: dict[int, Instruction], end: int, ops: list[Op], writes: list[Operand]) -> None:
        #: The instructions 0000 up to END (NOP places left out).
        self.instructions = instructions
        #: The number of the END instruction.
        self.end = end
        #: Every operand the program writes; an output among them belongs to the Logic Task
        #: and "can no longer be processed in one of the NC Tasks" (L5724).
        self.writes = tuple(dict.fromkeys(writes))
        self._ops = tuple(ops)

    @property
    def active(self) -> bool:
        """False when END is at 0000: the Logic Task is deactivated (L2997)."""
        return self.end > 0

    @property
    def assignments(self) -> int:
        """Instructions per scan: 0000 up to and including END (decision 8)."""
        return self.end + 1

    @property
    def scan_time_ms(self) -> float:
        return scan_time_ms(self.assignments)

    def scan(self, image: ProcessImage) -> None:
        """Run one whole scan on `image`, the I/O as sampled at the scan's start (decision 7)."""
        data = image.data
        value = 0
        terms: list[tuple[int, int]] = []
        for code, at, shift, mask, invert in self._ops:
            if code == _LOAD:
                value = (data[at] >> shift & mask) ^ invert
            elif code == _AND:
                value &= (data[at] >> shift & mask) ^ invert
            elif code == _OR:
                value |= (data[at] >> shift & mask) ^ invert
            elif code == _XOR:
                value ^= (data[at] >> shift & mask) ^ invert
            elif code == _STORE:
                data[at] = data[at] & ~(mask << shift) | ((value ^ invert) & mask) << shift
            elif code == _SET:
                data[at] |= 1 << shift
            elif code == _RES:
                data[at] &= ~(1 << shift)
            elif code == _SETC:
                if value ^ invert:
                    data[at] |= 1 << shift
            elif code == _RESC:
                if value ^ invert:
                    data[at] &= ~(1 << shift)
            elif code == _CLOSE:
                opened, outer = terms.pop()
                term = value ^ invert
                if opened == _OPEN_AND:
                    value = outer & term
                elif opened == _OPEN_OR:
                    value = outer | term
                else:
                    value = outer ^ term
            else:  # _OPEN_*: keep the value before the term, start the term
                terms.append((code, value))
                if at != _NO_OPERAND:
                    value = data[at] >> shift & mask


# -- files and telegrams --------------------------------------------------------------------------

# A '#' line is a telegram when it looks like one (an information type and a number or a
# checksum), else a comment; a 'P' line is the CLM's read-back (no command begins with P).
_TELEGRAM = re.compile(r"#.[NKXPV](?:\s*[0-9]|.*\$[0-9A-Fa-f]{2}\s*\Z)")
_REPLY = re.compile(r"P.\s*[0-9]{4}")
_LISTING = re.compile(r"([0-9]+)(?:\s+(.*))?\Z", re.DOTALL)
_COMMENT = re.compile(r"\s-|;")


def _program_lines(lines: Mapping[int, str] | Sequence[str]) -> dict[int, Instruction]:
    """The given instructions checked one by one (fault 38 on the first bad one)."""
    errors: list[ClmError] = []
    memory = _memory(lines, errors)
    if errors:
        raise errors[0]
    return {n: parse_instruction(memory[n], n) for n in sorted(memory) if memory[n].strip()}


def logic_telegrams(program_lines: Mapping[int, str] | Sequence[str], station: int = 0) -> list[str]:
    """The write telegrams ``#sPnnnn_<instruction>_$hh CR LF``, 0000 up to the last given (decision 11)."""
    program = _program_lines(program_lines)
    last = max(program, default=-1)
    return [emit("#", station, "P", f"{n:04d} {program.get(n, Instruction('NOP'))} ") for n in range(last + 1)]


def logic_listing(program_lines: Mapping[int, str] | Sequence[str]) -> str:
    """One ``nnnn<tab>COMMAND<tab>OPERAND`` line per instruction that is not NOP."""
    out = []
    for n, ins in _program_lines(program_lines).items():
        if ins.mnemonic != "NOP":
            out.append(f"{n:04d}\t{ins.mnemonic}" + (f"\t{ins.operand}" if ins.operand else "") + "\n")
    return "".join(out)


def read_logic_text(text: str, source: str = "<text>") -> tuple[dict[int, str], list[Finding]]:
    """Read a Logic Task file: listing lines and/or ``#sP`` telegrams (see the module text).

    Returns the accepted instructions by number (normalized text, ``'LD M6.20.0'``) and one
    finding per refused line (where = ``LTnnnn`` when the number is known, else ``line n``;
    source = ``source:n``). Never raises on the text's content.
    """
    lines: dict[int, str] = {}
    findings: list[Finding] = []
    listed: set[int] = set()
    previous = -1
    for line_no, raw in enumerate(text.splitlines(), start=1):
        here = f"{source}:{line_no}"
        line = raw.strip()
        if line[:1] in "#P" and "_" in line and " " not in line:
            line = line.replace("_", " ")  # the manual's notation: '_' for a blank (#_P0000_LD_...)
        try:
            if _TELEGRAM.match(line) or _REPLY.match(line):
                number, ins = _read_telegram(line)
            elif not line or line[0] in ";#":
                continue
            else:
                body = _COMMENT.split(line, 1)[0].strip()
                if not body:
                    continue
                number, ins = _read_listing(body, previous)
                if number in listed:
                    text = f"instruction {number:04d} is given twice; the later line is kept"
                    findings.append(Finding(_where(number), FAULT, text, "warning", here))
                listed.add(number)
        except ClmError as error:
            findings.append(Finding.of(error, where=f"line {line_no}", source=here))
            if error.where and error.where.startswith("LT") and error.where[2:].isdigit():
                previous = int(error.where[2:])  # a refused line still takes its place
            continue
        lines[number] = str(ins)
        previous = number
    return lines, findings


def _read_listing(body: str, previous: int) -> tuple[int, Instruction]:
    m = _LISTING.match(body)
    if m is None:
        if not (body[0].isalpha() or body[0] == ")"):
            raise ClmError(FAULT, f"{_shown(body)} is not a listing line ('0000  LD  M6.20.0')")
        number = previous + 1  # an unnumbered line follows the one before; the first is 0000
        if number >= LT_INSTRUCTIONS:
            raise ClmError(FAULT, f"{_shown(body)} would be instruction {number}: the Logic Task has 0000-0999 (L2961)")
        return number, parse_instruction(body, number)
    if len(m.group(1)) > 4 or int(m.group(1)) >= LT_INSTRUCTIONS:
        raise ClmError(FAULT, f"instruction number {_shown(m.group(1))}: the Logic Task has 0000-0999 (L2961)")
    number = int(m.group(1))
    if not m.group(2):
        raise ClmError(FAULT, "no instruction after the number", _where(number))
    return number, parse_instruction(m.group(2), number)


def _read_telegram(line: str) -> tuple[int, Instruction]:
    telegram = parse_telegram(line)
    if telegram.control == "#" and telegram.kind != "P":
        raise ClmError(serial_code(2), "not a Logic Task telegram (#sP...)")
    head, _, rest = telegram.body.strip().partition(" ")
    if len(head) != 4 or not head.isascii() or not head.isdigit():
        raise ClmError(serial_code(1), f"instruction number {_shown(head)}: four decimal digits expected")
    number = int(head)
    if number >= LT_INSTRUCTIONS:
        raise ClmError(serial_code(12), f"instruction number {head}: the Logic Task has 0000-0999 (L2961)")
    rest = rest.strip()
    if not rest:
        raise ClmError(serial_code(13), "no instruction after the number", _where(number))
    if len(rest) > DATA_WIDTH:
        raise ClmError(serial_code(2), f"instruction field {_shown(rest)} longer than {DATA_WIDTH} characters (L6735)", _where(number))
    return number, parse_instruction(rest, number, serial=True)
