"""Bit and byte operands of the CLM: ``I1.00.6`` (input, source 1, byte 00, bit 6), ``M2.02``.

Manual §9.1 (L5699-5760), spec §3.3. Each source has a range of bytes, and each user of the
image (the NC tasks, the Logic Task, the parameters) has its own rights on it:

=======  ===============  ==================  =========================  ======================
area     bytes            what                NC tasks                   Logic Task
=======  ===============  ==================  =========================  ======================
I0       00-02 (02.0-5)   system inputs       read                       read
I1       00-10            auxiliary inputs    read                       read
I2       00-05            fieldbus inputs     read                       read
Q0       00-02 (02.0-1)   system outputs      read                       read
Q1       00-06 (06.0-2)   auxiliary outputs   read/write                 read/write
Q2       00-05            fieldbus outputs    read; write 02-05          read; write 02-05
M0       00-49            system markers in   read                       read
M1       00-49            system markers out  read                       read
M2       00-19            NC markers          read/write                 -
M3       00-07            saved NC markers    read/write                 -
M4       00-09            NC -> LT transfer   read/write                 read
M5       00-09            LT -> NC transfer   read                       read/write
M6       00-39            LT markers          -                          read/write
=======  ===============  ==================  =========================  ======================

The Logic Task rows are the manual's (§6, L3025-3030: loads and logic on M0, M1, M4-M6,
Q0-Q2, I0-I2; store/set/reset on M5, M6, Q1, Q2.02-Q2.05). The NC rows follow from the marker
descriptions (M4 "NC read/write, LT read-only", M5 the reverse, M6 "Logic Task markers": the
NC has none of them) and from the system outputs being driven by the CLM's own functions
(decision C-OPERANDS in docs/decisions.md). A parameter may name any input, output or marker
(the manual's own samples use M2.00.0 for "position reached"), and ``00.00.0`` (no letter)
means "not programmed".

An operand outside its range is error 1D "Command I/O" in an NC instruction, 38 in the Logic
Task and fault 02 in a parameter; each caller picks its code, this module only says whether
the operand exists and who may read or write it.

Decisions (spec line -> choice, why)
------------------------------------
1. C-OPERANDS, spec §3.3 gives the Logic Task's rights but not the NC tasks': the NC tasks
   read I0-I2, Q0-Q2, M0-M5 and write Q1, Q2.02-Q2.05, M2, M3, M4 (M4 "NC read/write", M5 "LT
   read/write, NC read-only", M6 the Logic Task's own; the system outputs Q0 and the status
   word Q2.00-01 are driven by the CLM's functions). A write elsewhere is 1D. Tests:
   ``tests/devices/clm/test_program.py::test_each_kind_of_bad_instruction_has_its_clm_code``.
"""

from __future__ import annotations

import re
from typing import NamedTuple

from .errors import ClmError

__all__ = [
    "LT_READ",
    "LT_WRITE",
    "NC_READ",
    "NC_WRITE",
    "Operand",
    "exists",
    "parse_operand",
    "usable",
]

# (area letter, source) -> (last byte, bits of the last byte); every other byte has 8 bits.
_SOURCES: dict[tuple[str, int], tuple[int, int]] = {
    ("I", 0): (2, 6),
    ("I", 1): (10, 8),
    ("I", 2): (5, 8),
    ("Q", 0): (2, 2),
    ("Q", 1): (6, 3),
    ("Q", 2): (5, 8),
    ("M", 0): (49, 8),
    ("M", 1): (49, 8),
    ("M", 2): (19, 8),
    ("M", 3): (7, 8),
    ("M", 4): (9, 8),
    ("M", 5): (9, 8),
    ("M", 6): (39, 8),
}

_ALL = frozenset(_SOURCES)
_INPUTS_OUTPUTS = frozenset(k for k in _SOURCES if k[0] in "IQ")
NC_READ = frozenset(_ALL - {("M", 6)})
NC_WRITE = frozenset({("Q", 1), ("Q", 2), ("M", 2), ("M", 3), ("M", 4)})
LT_READ = frozenset(_INPUTS_OUTPUTS | {("M", 0), ("M", 1), ("M", 4), ("M", 5), ("M", 6)})
LT_WRITE = frozenset({("Q", 1), ("Q", 2), ("M", 5), ("M", 6)})
_FIRST_WRITABLE_BYTE = {("Q", 2): 2}  # Q2.00-Q2.01 are the Profibus status word

_PATTERN = re.compile(r"([IQM]?)(\d{1,2})\.(\d\d)(?:\.(\d))?\Z")  # two source digits: the "00" of 00.00.0


class Operand(NamedTuple):
    """``area`` 'I' | 'Q' | 'M' ('' for the parameters' ``00.00.0`` "not programmed").

    A tuple: the image and the mode machine look operands up in dicts several times a cycle,
    and a tuple's hash and equality run in C."""

    area: str
    source: int
    byte: int
    bit: int | None = None  # None: a byte operand

    @property
    def is_bit(self) -> bool:
        return self.bit is not None

    @property
    def unset(self) -> bool:
        """The parameters' ``00.00.0``: no input / output programmed."""
        return self.area == ""

    @property
    def key(self) -> tuple[str, int]:
        return (self.area, self.source)

    def __str__(self) -> str:
        head = f"{self.area}{self.source}.{self.byte:02d}"
        return head if self.bit is None else f"{head}.{self.bit}"


def parse_operand(text: str, *, bit: bool, code: str = "1D", unset_ok: bool = False) -> Operand:
    """Parse ``I1.00.6`` (bit) or ``M2.02`` (byte); a malformed or absent operand raises `code`.

    The operand must exist in the CLM (its byte and bit in range); rights are checked by
    `usable`. ``unset_ok`` admits ``00.00.0`` / ``00.00`` (parameters only).
    """
    m = _PATTERN.match(text.strip())
    what = "bit operand (e.g. I1.00.6)" if bit else "byte operand (e.g. M2.02)"
    if m is None or (m.group(4) is None) == bit:
        raise ClmError(code, f"{text.strip()[:20]!r} is not a {what}")
    area, source, byte = m.group(1), int(m.group(2)), int(m.group(3))
    if area and len(m.group(2)) > 1:
        raise ClmError(code, f"{text.strip()[:20]!r} is not a {what}")
    b = int(m.group(4)) if m.group(4) is not None else None
    if area == "":
        if unset_ok and source == 0 and byte == 0 and (b is None or b == 0):
            return Operand("", 0, 0, b)
        raise ClmError(code, f"{text.strip()!r}: the operand needs I, Q or M (00.00.0 means 'not programmed' in parameters only)")
    op = Operand(area, source, byte, b)
    if not exists(op):
        raise ClmError(code, f"{op} does not exist ({_range_text(op)})")
    return op


def exists(op: Operand) -> bool:
    limits = _SOURCES.get(op.key)
    if limits is None:
        return False
    last, last_bits = limits
    if op.byte > last:
        return False
    if op.bit is None:
        return True
    return op.bit < (last_bits if op.byte == last else 8)


def _range_text(op: Operand) -> str:
    limits = _SOURCES.get(op.key)
    if limits is None:
        sources = sorted({s for a, s in _SOURCES if a == op.area})
        return f"{op.area} sources are {', '.join(f'{op.area}{s}' for s in sources)}"
    last, last_bits = limits
    tail = f"{op.area}{op.source}.{last:02d}.{last_bits - 1}" if last_bits < 8 else f"{op.area}{op.source}.{last:02d}.7"
    return f"{op.area}{op.source}.00.0..{tail}"


def usable(op: Operand, rights: frozenset[tuple[str, int]]) -> bool:
    """Whether `op` is in `rights` (NC_READ, NC_WRITE, LT_READ, LT_WRITE)."""
    if op.key not in rights:
        return False
    if rights is NC_WRITE or rights is LT_WRITE:
        return op.byte >= _FIRST_WRITABLE_BYTE.get(op.key, 0)
    return True
