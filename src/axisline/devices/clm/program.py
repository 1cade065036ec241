"""CLM program instructions: parsing and writing the two file forms, and the program memory.

Two forms of the same instruction:

* listing, as the manual prints programs: ``0002 COU +00000 Q1.00.4 000010  - comment``
  (blanks or tabs between fields; a comment after the fields begins with ``-`` or ``;``;
  ``;`` lines are comments);
* transfer, one serial telegram as a PC tool sends it (§9.2, L6520-6575):
  ``#_N0101_AEA_Q1.00.3_1_$C0``, i.e. ``#sNbbbb ccc <data> $hh`` with the data in the
  command's columns (see `commands`) and a blank before ``$``.

Parsing is field-driven: each field of the command's row takes its token from the text, so
``V600>=+12345.678`` (CPJ's printed form) and ``V600 >= +V601`` both read, and a ``-`` after
the fields is a comment while MAT's ``V601 - V602`` is an operator. Every refusal carries the
CLM's code: in a listing the fault the CLM raises for it (0A invalid command or data, 0E
block number, 16 axis, 1D operand, 3D bit count, 1B SAC mode, 1F SRP variable field, 31
system variable); in a telegram the Status 01 error the CLM answers with (01 block number not
decimal, 02 format, 03 block data, 04 checksum, 12 block number too large, 13 invalid command,
16 value too large) and, for a value of the right shape the CLM would stop on when it
reaches it, that fault.

The program memory holds 3000 instructions 0000-2999; an instruction never written is NOP
(§5.2). Counters (COU, BAC) are kept per instruction number beside it; storing a counter
instruction applies its actual-quantity offset once and stores it back as ``+00000``
(L1753-1770: "significant only if the COU command has been read in (even when storing
occurs via the RS interface)"; a ``0`` in the sign place zeroes the count).

Decisions (spec line -> choice, why)
------------------------------------
1. C-LOAD, errata §2 / chapter 11: the CLM stores an instruction of the right shape and
   faults (16, 1D, 1B, 1F, 3D, 31) only when a task reaches it; axisline refuses such a line
   when the file is loaded, with that fault code and the line, because the issue asks that a
   file with a bad line is reported whole and nothing of it kept, and a maintainer wants to
   know before the machine stops. A telegram the CLM could not store at all is answered with
   its Status 01 error (01, 02, 03, 04, 12, 13; 16 "Value too large" for a number of the
   right shape beyond its range; L6820 gives no description). Tests: ``test_each_kind_of_bad_instruction_has_its_clm_code``,
   ``test_telegram_refusals_are_the_status_01_errors``.
2. C-LISTING, the listing form (no file format is printed; the manual prints listings): a
   comment follows the fields after a tab, ``-`` or ``;`` (the manual's own tables separate
   comments by a tab, with or without ``-``); numbers with fewer digits than the field are
   read (the manual prints ``+00010.005`` and ``WAI 00.02``) and written in full width; TXT's
   text is written in double quotes (its blanks matter) and read with or without them.
   Tests: ``test_listing_with_tabs_and_comments``, ``test_manual_listing_line``.
3. C-COUNTER, L1753-1770 do not say what a negative offset larger than the count gives: the
   count stops at 0 (a count of parts is never negative). Test:
   ``test_counter_offset_applies_once_on_load_and_is_stored_back_as_zero``.
4. C-REP, L2350 says REP "must not be executed immediately after the SRM command", but the
   manual's permitted combination (L2361-2365) and error 1A (L8484-8486) put it right there:
   REP after SRM is read, and 1A is reported when its axis differs from the SRM's. Test:
   ``test_rep_directly_after_srm_for_the_same_axis_is_allowed_for_another_axis_1a``.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, replace

from .commands import COMMANDS, Command, Literal
from .errors import ClmError, serial_code
from .fields import BitField, Compare, Field, Mask, Number, Text, VarField
from .telegram import emit, parse_telegram

__all__ = [
    "PROGRAM_SIZE",
    "Instruction",
    "Program",
    "parse_instruction",
    "parse_listing_line",
    "parse_program_telegram",
]

PROGRAM_SIZE = 3000

_NUMBERISH = re.compile(r"[+-]?[ \t]?V\d+|[+-]?[ \t]?[\d.,]+")
_OPERAND = re.compile(r"[IQM]?\d+\.\d+(?:\.\d+)?")
_DIGITS = re.compile(r"\d+")
_VARIABLE = re.compile(r"[+-]?V\d+")
_CHUNK = re.compile(r"\S+")
_COMMENT = re.compile(r" *\t|\s*(?:[-;]|//)")  # the manual's listings: a tab, or "- comment"
_LISTING = re.compile(r"\s*(\d+)[ \t]+([A-Za-z]{3})(?=\s|$)(.*)\Z", re.S)


def _token_pattern(f: Field) -> re.Pattern[str]:
    if isinstance(f, BitField):  # ByteField too
        return _OPERAND
    if isinstance(f, Mask):
        return _DIGITS
    if isinstance(f, VarField):
        return _VARIABLE
    if isinstance(f, Compare):
        return re.compile("|".join(re.escape(op) for op in sorted(f.operators, key=len, reverse=True)))
    if isinstance(f, Literal):
        return re.compile(re.escape(f.text))
    return _NUMBERISH


@dataclass(frozen=True)
class Instruction:
    number: int
    command: Command
    values: tuple[object, ...]
    comment: str = ""

    @property
    def mnemonic(self) -> str:
        return self.command.mnemonic

    def value(self, name: str) -> object:
        for f, v in zip(self.command.fields, self.values):
            if f.name == name:
                return v
        raise KeyError(name)

    def listing(self, comments: bool = True) -> str:
        """``0000 POI 1 +000200.000 999`` (and ``  - comment``)."""
        parts = []
        for f, v in zip(self.command.fields, self.values):
            text = f.format(v)
            parts.append(f'"{text.rstrip()}"' if isinstance(f, Text) else text)
        line = " ".join([f"{self.number:04d}", self.mnemonic, *parts])
        return f"{line}  - {self.comment}" if comments and self.comment else line

    def data(self) -> str:
        """The fields in the CLM's serial columns (see `commands`)."""
        out = ""
        cmd = self.command
        template = (cmd.template or "").replace("_", " ")[len(cmd.mnemonic) + 1 :]
        for f, col, v in zip(cmd.fields, cmd.columns, self.values):
            glued = bool(template) and 0 < col <= len(template) and template[col - 1] != " "
            if len(out) < col:
                out = out.ljust(col)
            elif out and not (glued and len(out) == col):
                out += " "
            out += f.format(v)
        return out

    def telegram(self, station: int = 0) -> str:
        """``#_N0101_AEA_Q1.00.3_1_$C0`` (with blanks), CR LF included."""
        return emit("#", station, "N", f"{self.number:04d} {self.mnemonic} {self.data()} ")


def parse_instruction(number: int, mnemonic: str, data: str, *, comments: bool = True) -> Instruction:
    """Read the fields of one instruction; `comments` lets text after the fields be a comment."""
    cmd = COMMANDS.get(mnemonic.upper())
    if cmd is None:
        raise ClmError("0A", f"{mnemonic[:8]!r} is not a CLM command (ACC .. WAI, 55 commands)")
    values: list[object] = []
    pos = 0
    for f in cmd.fields:
        while pos < len(data) and data[pos] in " \t":
            pos += 1
        if isinstance(f, Text):
            text, pos = _text(data, pos)
            values.append(f.parse(text))
            continue
        m = _token_pattern(f).match(data, pos)
        if m is None:
            chunk = _CHUNK.match(data, pos)
            raise f.refuse(chunk.group(0) if chunk else "", f.describe() + (" (missing)" if chunk is None else ""))
        values.append(f.parse(re.sub(r"\s", "", m.group(0))))
        pos = m.end()
    rest = data[pos:]
    comment = ""
    if rest.strip():
        if not (comments and _COMMENT.match(rest)):
            raise ClmError("0A", f"{cmd.mnemonic}: unexpected {rest.strip()[:24]!r} after the last field ({_syntax(cmd)})")
        comment = re.sub(r"^\s*(?:-\s|;|//)?\s*", "", rest).strip()
    return Instruction(number, cmd, tuple(values), comment)


def _text(data: str, pos: int) -> tuple[str, int]:
    if data.startswith('"', pos):
        end = data.find('"', pos + 1)
        if end < 0:
            raise ClmError("0A", "TXT: the text's closing quote is missing")
        return data[pos + 1 : end], end + 1
    end = len(data)
    for stop in ("\t", ";"):
        at = data.find(stop, pos)
        if at >= 0:
            end = min(end, at)
    return data[pos:end].rstrip(), end


def _syntax(cmd: Command) -> str:
    return " ".join([cmd.mnemonic, *(f.name for f in cmd.fields)])


def _number(text: str, code_not_decimal: str, code_too_large: str) -> int:
    if not text.isdigit() or len(text) > 4:
        raise ClmError(code_not_decimal, f"instruction number {text[:8]!r}: four digits 0000-2999")
    n = int(text)
    if n >= PROGRAM_SIZE:
        raise ClmError(code_too_large, f"instruction number {n}: the program memory is 0000-2999")
    return n


def parse_listing_line(line: str) -> Instruction:
    """``0002 COU +00000 Q1.00.4 000010  - comment`` -> Instruction (ClmError with the CLM code)."""
    m = _LISTING.match(line)
    if m is None:
        raise ClmError("0A", f"{line.strip()[:30]!r}: an instruction line is NNNN CMD fields (e.g. 0000 POI 1 +000100.000 999)")
    number = _number(m.group(1), "0E", "0E")
    try:
        return parse_instruction(number, m.group(2), m.group(3))
    except ClmError as e:
        raise e.at(f"N{number:04d}") from None


_SHAPE_FAULTS = {"0A": 3, "0E": 3}  # in a telegram, data the CLM cannot store: X01:03


def parse_program_telegram(line: str, *, require_checksum: bool = False) -> Instruction:
    """``#_N0101_AEA_Q1.00.3_1_$C0`` -> Instruction; refusals as the CLM answers them."""
    t = parse_telegram(line, require_checksum=require_checksum)
    if t.control not in "#!" or t.kind != "N":
        raise ClmError(serial_code(2), "a program telegram is #sNbbbb ccc data $hh")
    body = t.body
    number = _number(body[:4], serial_code(1), serial_code(12))
    where = f"N{number:04d}"
    rest = body[4:]
    m = re.match(r"\s+([A-Za-z]{3})(?=\s|$)", rest)
    if m is None:
        raise ClmError(serial_code(13), f"no command after the instruction number: {rest.strip()[:12]!r}", where)
    try:
        return parse_instruction(number, m.group(1), rest[m.end() :], comments=False)
    except ClmError as e:
        if e.code == "0A" and m.group(1).upper() not in COMMANDS:
            raise ClmError(serial_code(13), e.detail, where) from None
        if e.code in _SHAPE_FAULTS:
            number = 16 if e.out_of_range else _SHAPE_FAULTS[e.code]  # 16 "Value too large"
            raise ClmError(serial_code(number), e.detail, where) from None
        raise e.at(where) from None


def _nop(number: int) -> Instruction:
    return Instruction(number, COMMANDS["NOP"], ())


class Program:
    """The program memory (0000-2999, unwritten = NOP) and the counters kept beside it."""

    def __init__(self) -> None:
        self._instructions: dict[int, Instruction] = {}
        self.counters: dict[int, int] = {}  # actual quantity per COU / BAC instruction

    def __getitem__(self, number: int) -> Instruction:
        if not 0 <= number < PROGRAM_SIZE:
            raise ClmError("0E", f"instruction {number}: the program memory is 0000-2999")
        return self._instructions.get(number) or _nop(number)

    def __len__(self) -> int:
        return len(self._instructions)

    def written(self) -> list[Instruction]:
        """The instructions that were written (explicit NOPs included), by number."""
        return [self._instructions[n] for n in sorted(self._instructions)]

    def store(self, instruction: Instruction) -> Instruction:
        """Store one instruction as the CLM does; returns what is kept (offset applied)."""
        n = instruction.number
        if not 0 <= n < PROGRAM_SIZE:
            raise ClmError("0E", f"instruction {n}: the program memory is 0000-2999")
        if instruction.mnemonic in ("COU", "BAC"):
            offset_field = instruction.command.fields[1 if instruction.mnemonic == "BAC" else 0]
            offset = instruction.value(offset_field.name)
            count = self.counters.get(n, 0)
            self.counters[n] = 0 if offset is None else max(0, count + int(offset))  # type: ignore[call-overload]
            values = list(instruction.values)
            values[instruction.command.fields.index(offset_field)] = 0
            instruction = replace(instruction, values=tuple(values))
        else:
            self.counters.pop(n, None)
        self._instructions[n] = instruction
        return instruction

    def copy(self) -> Program:
        p = Program()
        p._instructions = dict(self._instructions)
        p.counters = dict(self.counters)
        return p

    def listing(self, comments: bool = True) -> str:
        return "".join(i.listing(comments) + "\n" for i in self.written())

    def telegrams(self, station: int = 0) -> str:
        return "".join(i.telegram(station) for i in self.written())


def counter_target(instruction: Instruction) -> object:
    """The target quantity field of a COU/BAC (a `Var` mirrors the count into Vn+1)."""
    return instruction.values[-1] if instruction.mnemonic in ("COU", "BAC") else None


def number_fields(instruction: Instruction) -> list[tuple[Number, object]]:
    return [(f, v) for f, v in zip(instruction.command.fields, instruction.values) if isinstance(f, Number)]
