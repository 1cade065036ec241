"""The CLM1.4 parameters: their data in the CLM's columns, the checks on leaving Parameter mode, files.

Manual chapter 8 (L4118-5695), the transmission table Figs. 9-14..9-16 (L6590-6672); spec §5,
§8.4; errata §1.20 and §3.4. The per-parameter table is `paramtable`.

    params, findings = read_parameter_text(text, "machine.par")
    params.set("A106", "000400.000")
    params.check()        # [] or Findings: fault 02 (or 17) with the parameter id
    params.telegrams()    # ['# K B000 0 0 0$8E', '# K B001 0 0$DD', ...]
    params.listing()      # 'B000 0 0 0\\nB001 0 0\\n...'

A parameter's data is its fields in the CLM's columns, one blank between fields (none before a
glued field), no blank before ``$``: ``# K B002 019200 0 1 8 1$E4``, ``# K B006 $59``.
`parse_data` reads it tolerantly, `format_data` prints it exactly, so every sample of the
manual's table comes back byte for byte with its checksum.

`ParameterSet.check` is what the CLM does after power-up, Clear, loading parameters and on
leaving Parameter mode (L4130, L4162): "erroneous or missing parameters" give fault 02
"INVALID Parameter" naming the parameter (L8259-8269). It checks every field of a parameter in
use against its range, then how parameters fit together (spec §5.6 and the manual sentences
cited at each check). A parameter that is not in use is not checked at all (errata §3.4).

A parameter file holds one parameter a line, as telegrams (``#_K_B000_0_0_0$8E``, ``_`` or
blanks, ``!`` for ``#``, a checksum verified) or as a listing (``B000 0 0 0``, ``; comment``
at the end, ``#`` comment lines); `read_parameter_text` reports every bad line and then the
checks, and returns the set with the good lines on top of the defaults.

Decisions (spec line -> choice, why)
------------------------------------
1. Spec §0, errata §3.4 "layouts read right to left": a figure's labels are read right to
   left (the first label printed is the rightmost field; it holds wherever the fields of a
   sample differ in form: Ax05, Ax11, Ax12, Ax14, Ax19, Ax24, Ax27, Ax29, Ax34, Ax35, Ax36,
   Ax42, B003, B015, B018, C000, C001, C008). Numbered paragraphs ("1) Feed angle monitoring
   2) Interrupt", "1) Averaging 2) Override") follow the title ("Feed Angle Monitoring /
   Interrupt") and read left to right. Test: ``test_manual_sample_reproduced``.
2. Errata §3.4: the six samples that fail their checksum as printed are read as ``B000 0 0 0``,
   ``B001 0 0``, ``B004 000000 0 0 0 0``, ``B008 0 0 0 0 02``, ``B017 0 0 0 0 0 0``,
   ``A123 I1.00.0 I1.00.1``; the printed lines are refused with X01:04. Tests:
   ``test_printed_misprint_refused_with_x01_04``, ``test_corrected_misprint_accepted``.
3. Ax00 (figure lost, L4182-4226): ``master reserved test_mode mode motion_type``. The prose
   after the figure names "Type of Motion" first, then "Mode", so by 1. they are the two
   rightmost digits (spec §5.2 guessed left to right, against its own rule); the sample
   ``1 0 0 0 0`` is then a rotary normal axis whose leftmost 1 is the master "axis 1", the
   natural master for axes 2-4. Masters: 1-3 = axis 1-3, 5 = master encoder 1 (C001 calls it
   encoder 5, L5509). Test: ``test_ax00_layout_and_combinations``.
4. B000 (figure lost): three digits enabling axes 2, 3, 4 left to right (axis 1 always
   works, L4158; ascending like B018's bytes). B001: language (codes lost, unchecked), write
   protection (index "Language Selection / Write Protection 8-34", L1095). Test:
   ``test_b000_enables_axes_left_to_right``.
5. B002/B004 (labels lost): ``baud function parity data_bits stop_bits``; 7/8 and 1/2 are the
   ``8 1`` of every sample (L6256-6258); function 0 = data interface / 1 = IDS01 (L6301) is put
   before parity so that the sample's ``0 1`` is a data interface; which parity code is odd or
   even is lost. Baud 000000 (off, L6327) or IDS01 ("the other values need not be input",
   L5028) leaves the other fields and B003/B005 unchecked. Test:
   ``test_interface_fields_unused_when_off``.
6. B008 (errata §1.20): ``format hardware_signals operating_mode profibus_signals address``.
   The checksum fixes four digits and a 2-digit address; operating mode is 0 or 3 (L7576), so
   only the third digit can hold it in the display example ``1 1 0 1 05`` (L5064); "Profibus
   System Signal Enabled" printed before "CLM Hardware ..." (L5073-5077) is right of it (1.);
   the format takes the digit left. Address 00 = delivery state (L7519). Test:
   ``test_b008_layout``.
7. B017: ``averaging override_axis_1..4 reserved`` (1., numbered paragraphs; the verified
   sample has six digits, one meaning is lost). Ax20 (figure lost): ``encoder_number
   encoder_type data_bits track_monitoring``, C001's verified layout (L5485-5509) without
   direction and averaging; type 3 = "Controlled Axis" (L8499). Test:
   ``test_encoder_type_ranges``.
8. Fields whose meaning is lost or "in preparation" (B001 language, B011's last digit, B017's
   sixth, B019, Ax00's fifth, Ax17, Ax20's encoder number, Ax21, Ax22, Ax28, Ax35's reserved,
   C003/C007) are kept and printed back but not range-checked: L8269's "generally the value
   0" is advice, a stricter check would refuse real files; a field the manual gives no range
   for (Ax27's threshold, Ax29, Ax37, Ax40, Ax41, ...) takes any value of its form. Reserved
   parameters (B006, B007, B009, B013, Ax13, Ax18, Ax26) take no data, as their samples.
   Test: ``test_reserved_parameters_take_no_data``.
9. Spec §8.6 [MISSING] CSETPA defaults: the corrected sample table, except B008 address 00
   (L7519), B012 ``0000 0000`` (display L5144; the sample would start tasks 4 and 5), B018
   ``0 0000000`` (clear every output on a fault), Ax23/Ax24/Ax27 I/O ``00.00.0`` (one table
   serves four axes; double assignment "must be avoided", L4178). They pass `check`. Test:
   ``test_defaults``.
10. Errata §3.4 unused parameters: not in use are a disabled axis (B000), Ax02 outside rotary
    table with incremental encoder (L4278), Ax03/Ax04 outside linear (L2518, L3558), Ax05
    outside rotary table (L4350), Ax16 outside measuring wheel, Ax33-Ax42 unless axis 1 is a
    flying cutoff (L5650-5659: "---" for axes 2-4), C000-C003 unless master encoder 1 serves a
    slave, measuring wheel or cutoff (L5511), C004-C007 unless axis 2 is a measuring wheel
    (L4228), C008 unless cutoff, B003/B005 (5.), B014/B015 without input, B019. Test:
    ``test_unused_parameters_not_checked``.
11. Checks beyond spec §5.6, each a manual sentence, all fault 02: Ax03's sign per encoder
    (L4302, L4309), Ax04 >= 0 (L4338), Ax19 per encoder type (L4637-4650; Fig. 8-15's
    100-10000 is the incremental case), Ax20 data bits per type (L4656-4657), Ax00 per axis
    (L4202-4226), feedforward only for slave/synchronous/cutoff (L4457, L3489), Option 5 only
    for cutoff (L4741). Test: ``test_interaction``.
12. Possible Vmax (L4365) in exact fractions, equality allowed (errata §3.4; the 1125 IU/s
    example, L3643-3649); on a rotary table with incremental encoder the feed constant is
    Ax01 x Y/X (L3581). IUT = Ax01 (incremental) or Ax01 x the Ax19 ratio (absolute,
    single-turn 2^bits, L3545); |Ax25| <= IUT (L3552, L3593). Test:
    ``test_rotary_table_example_accepts_vmax_equal``.
13. Error 17 (axes 3/4 without the expansion, L8461) needs the hardware: `check` reports it
    only with ``axes_fitted=2``. Test: ``test_hardware_axes_3_4``.
14. Spec §8.5 unknown ids: a block other than B0, A1-A4, C0 is X01:11 "Invalid Param Block"
    (the identifier is the block, L4148), a number that is not two decimal digits X01:06, one
    beyond its block (B020, A143, C009) X01:07. Test: ``test_unknown_ids``.
15. Reading: one or two blanks between fields (three: 02), a tab as a blank in listings (the
    manual's own, L3428, L3531), fewer leading digits, ``,`` for ``.`` (spec §8.1); a signed
    field needs its sign. Printing is exact. Test: ``test_parse_tolerance``.
16. Files: ``_`` is a blank in every telegram line (no parameter data holds ``_``); a ``#``
    line that is not ``#sK`` is a comment; ``$hh`` is verified when present (telegram
    C-CHECKSUM-OPTIONAL); a parameter written twice keeps the later line (warning 02);
    `read_parameter_text` ends with `check` ("loading parameters" is checked, L4130). Test:
    ``test_every_bad_line_reported``.
17. Order of ids: the manual's block order B0, A1..A4, C0 (keypad, L4168; Figs. 9-14..9-16).
    Values: Decimal for fractional and signed fields (A125's ``-00000.000`` keeps its sign),
    int, Operand, and ``'+'``/``'-'`` for Ax24's direction. Test:
    ``test_round_trip_listing_and_telegrams``.
"""

from __future__ import annotations

import os
import re
from collections.abc import Iterator, Sequence
from dataclasses import dataclass
from decimal import Decimal, InvalidOperation

from ...kernel import atomic_write_text
from .errors import ClmError, Finding, serial_code
from .operands import Operand, parse_operand
from .paramcheck import interaction_errors
from .paramtable import AXIS_ROWS, ENCODER_ROWS, GENERAL_ROWS, MIN_MAX, Field, Row
from .telegram import emit

__all__ = [
    "MIN_MAX",
    "PARAMETERS",
    "Field",
    "ParamSpec",
    "ParamValue",
    "ParameterSet",
    "check_id",
    "format_data",
    "parse_data",
    "read_parameter_text",
]

INVALID = "02"  # fault "INVALID Parameter" (L8262)
FieldValue = int | Decimal | str | Operand


@dataclass(frozen=True, slots=True)
class ParamSpec:
    """One parameter id (``A203``): its row of the table, for axis ``axis`` if an axis parameter."""

    pid: str
    row: Row
    axis: int | None = None

    @property
    def key(self) -> str:
        return self.row.key

    @property
    def name(self) -> str:
        return self.row.name

    @property
    def fields(self) -> tuple[Field, ...]:
        return self.row.fields

    @property
    def lines(self) -> str:
        return self.row.lines

    @property
    def default(self) -> ParamValue:
        """What ``!sCSETPA`` writes (decision 9); a field's default is ``spec.default[name]``."""
        return _DEFAULTS[self.pid]

    def index(self, name: str) -> int:
        for i, f in enumerate(self.fields):
            if f.name == name:
                return i
        raise KeyError(f"{self.pid} has no field {name!r} (fields: {', '.join(f.name for f in self.fields)})")


def _build() -> dict[str, ParamSpec]:
    specs = {row.key: ParamSpec(row.key, row) for row in GENERAL_ROWS}
    for axis in range(1, 5):
        for row in AXIS_ROWS:
            pid = f"A{axis}{row.key[2:]}"
            specs[pid] = ParamSpec(pid, row, axis)
    specs.update({row.key: ParamSpec(row.key, row) for row in ENCODER_ROWS})
    return specs


PARAMETERS: dict[str, ParamSpec] = _build()
_ORDER = {pid: i for i, pid in enumerate(PARAMETERS)}
_LAST_NUMBER = {"B0": 19, "A1": 42, "A2": 42, "A3": 42, "A4": 42, "C0": 8}  # L4150-4156


def check_id(token: str) -> str:
    """``token`` as a parameter id, or the CLM's refusal (decision 14)."""
    group, number = token[:2], token[2:]
    if group not in _LAST_NUMBER:
        raise ClmError(serial_code(11), f"{token[:12]!r}: a parameter id is a block B0, A1-A4 or C0 and two digits (L4148-4156)")
    if re.fullmatch(r"[0-9]{2}", number) is None:
        raise ClmError(serial_code(6), f"{token[:12]!r}: the number after {group} must be two decimal digits")
    if int(number) > _LAST_NUMBER[group]:
        raise ClmError(serial_code(7), f"{token}: block {group} ends at {group}{_LAST_NUMBER[group]:02d}")
    return token


def _spec(pid: str) -> ParamSpec:
    spec = PARAMETERS.get(pid)
    if spec is None:
        check_id(pid)  # raises: every id it accepts is in the table
        raise AssertionError(pid)
    return spec


# -- one field ----------------------------------------------------------------------------------------

_NUMBER = re.compile(r"([+-]?)([0-9]*)(?:[.,]([0-9]*))?\Z")


def _parse_field(pid: str, f: Field, token: str) -> FieldValue:
    def bad(why: str) -> ClmError:
        return ClmError(INVALID, f"{f.name} = {token[:20]!r}: {why}", pid)

    if f.kind == "operand":
        try:
            return parse_operand(token, bit=True, code=INVALID, unset_ok=True)
        except ClmError as e:
            raise bad(e.detail) from None
    if f.kind == "sign":
        if token not in ("+", "-"):
            raise bad("expected + or -")
        return token
    if f.kind == "digit":
        if len(token) != 1 or token not in "0123456789":
            raise bad("expected one digit")
        return int(token)
    if f.kind == "hex":
        if re.fullmatch(rf"[0-9A-Fa-f]{{1,{f.int_digits}}}", token) is None:
            raise bad(f"expected {f.int_digits} hex digits")
        return int(token, 16)
    m = _NUMBER.match(token)
    if m is None or not (m.group(2) or m.group(3)):
        raise bad(f"expected {f.form}")
    sign, whole, fraction = m.group(1), m.group(2), m.group(3)
    if f.signed and not sign:
        raise bad(f"needs its sign: {f.form}")
    if sign and not f.signed:
        raise bad(f"takes no sign: {f.form}")
    if len(whole) > f.int_digits:
        raise bad(f"at most {f.int_digits} digits before the point: {f.form}")
    if fraction is not None and len(fraction) > f.decimals:
        raise bad(f"at most {f.decimals} decimals: {f.form}" if f.decimals else f"a whole number: {f.form}")
    if f.decimals:  # quantized to the field's decimals, so the value prints back as read
        return Decimal(f"{sign}{whole or '0'}.{(fraction or '').ljust(f.decimals, '0')}")
    return Decimal(f"{sign}{whole}") if f.signed else int(whole)


def _format_field(pid: str, f: Field, value: object) -> str:
    def bad(why: str) -> ClmError:
        return ClmError(INVALID, f"{f.name} = {value!r}: {why}", pid)

    if isinstance(value, str) and f.kind != "sign":
        return _format_field(pid, f, _parse_field(pid, f, value))
    if f.kind == "operand":
        if not isinstance(value, Operand) or not value.is_bit:
            raise bad("expected a bit operand")
        return "00.00.0" if value.unset else str(value)
    if f.kind == "sign":
        if value not in ("+", "-"):
            raise bad("expected '+' or '-'")
        return str(value)
    if f.kind in ("digit", "hex") or not (f.decimals or f.signed):
        if not isinstance(value, int) or isinstance(value, bool):
            raise bad("expected a whole number")
        base = 16 if f.kind == "hex" else 10
        if not 0 <= value < base**f.int_digits:
            raise bad(f"does not fit {f.form}")
        return f"{value:0{f.int_digits}X}" if f.kind == "hex" else f"{value:0{f.int_digits}d}"
    if isinstance(value, bool) or not isinstance(value, (int, Decimal)):
        raise bad("expected a Decimal")
    d = Decimal(value)
    try:
        q = d.quantize(Decimal(1).scaleb(-f.decimals))
    except InvalidOperation:
        raise bad(f"does not fit {f.form}") from None
    if q != d:
        raise bad(f"more than {f.decimals} decimals: {f.form}")
    negative = q.is_signed()
    if negative and not f.signed and q != 0:
        raise bad(f"takes no sign: {f.form}")
    width = f.int_digits + (f.decimals + 1 if f.decimals else 0)
    body = f"{abs(q):0{width}.{f.decimals}f}"
    if len(body) > width:
        raise bad(f"does not fit {f.form}")
    return ("-" if negative else "+") + body if f.signed else body


# -- one parameter ------------------------------------------------------------------------------------


@dataclass(frozen=True, slots=True)
class ParamValue:
    """A parameter's data: one value per field, left to right as transmitted."""

    pid: str
    values: tuple[FieldValue, ...]

    @property
    def spec(self) -> ParamSpec:
        return _spec(self.pid)

    def __getitem__(self, name: str) -> FieldValue:
        return self.values[self.spec.index(name)]

    def number(self, name: str) -> Decimal:
        """A digit or number field as a Decimal (exact, for arithmetic across parameters)."""
        value = self[name]
        if isinstance(value, bool) or not isinstance(value, (int, Decimal)):
            raise TypeError(f"{self.pid} {name} is not a number: {value!r}")
        return Decimal(value)

    def as_dict(self) -> dict[str, FieldValue]:
        return {f.name: v for f, v in zip(self.spec.fields, self.values)}

    def replace(self, **changes: FieldValue) -> ParamValue:
        """A copy with some fields changed (a ``str`` is read as the field's columns)."""
        values = list(self.values)
        for name, value in changes.items():
            values[self.spec.index(name)] = value
        return parse_data(self.pid, format_data(self.pid, values))

    @property
    def data(self) -> str:
        return format_data(self.pid, self)

    def __str__(self) -> str:
        return f"{self.pid} {self.data}".rstrip()


def parse_data(pid: str, data: str) -> ParamValue:
    """Read `pid`'s data (``'019200 0 1 8 1'``); ClmError 02 naming the field when it is malformed."""
    spec = _spec(pid)
    fields = spec.fields
    text = data.strip(" ")
    if not fields:
        if text:
            raise ClmError(INVALID, f"{spec.name} is reserved and takes no data, got {text[:20]!r} ({spec.lines})", pid)
        return ParamValue(pid, ())
    values: list[FieldValue] = []
    pos, end = 0, len(text)
    for i, f in enumerate(fields):
        if i and not f.glued:
            gap = len(text) - pos - len(text[pos:].lstrip(" "))
            if gap > 2:
                raise ClmError(INVALID, f"{gap} blanks before {f.name}: fields are separated by one blank (two tolerated)", pid)
            pos += gap
        if pos >= end:
            raise ClmError(INVALID, f"{f.name} is missing: {pid} is {_layout(spec)}", pid)
        if i + 1 < len(fields) and fields[i + 1].glued:
            stop = pos + f.columns  # a field with a glued neighbour has a fixed width
        else:
            blank = text.find(" ", pos)
            stop = end if blank < 0 else blank
        values.append(_parse_field(pid, f, text[pos:stop]))
        pos = stop
    if text[pos:].strip(" "):
        raise ClmError(INVALID, f"{text[pos:].strip()[:20]!r} after the last field: {pid} is {_layout(spec)}", pid)
    return ParamValue(pid, tuple(values))


def format_data(pid: str, value: ParamValue | Sequence[FieldValue]) -> str:
    """`pid`'s data in the CLM's columns (``'019200 0 1 8 1'``); ClmError 02 if a value does not fit."""
    spec = _spec(pid)
    if isinstance(value, ParamValue):
        if value.pid != pid:
            raise ClmError(INVALID, f"a value of {value.pid} given for {pid}", pid)
        values: Sequence[FieldValue] = value.values
    else:
        values = value
    if len(values) != len(spec.fields):
        raise ClmError(INVALID, f"{len(values)} values for {len(spec.fields)} fields: {pid} is {_layout(spec)}", pid)
    out = []
    for i, (f, v) in enumerate(zip(spec.fields, values)):
        text = _format_field(pid, f, v)
        out.append(text if i == 0 or f.glued else " " + text)
    return "".join(out)


def _layout(spec: ParamSpec) -> str:
    if not spec.fields:
        return "empty"
    return "".join(("" if i == 0 or f.glued else " ") + f"<{f.name}>" for i, f in enumerate(spec.fields))


_DEFAULTS: dict[str, ParamValue] = {pid: parse_data(pid, spec.row.default) for pid, spec in PARAMETERS.items()}

MASTER_ENCODER_1 = 5


class ParameterSet:
    """All parameters of one CLM, starting from the defaults (what ``!sCSETPA`` writes)."""

    def __init__(self) -> None:
        self._values: dict[str, ParamValue] = dict(_DEFAULTS)
        #: counts every store: a reader that derives values per cycle (master_encoder) keeps them
        #: while the version stays (stored values are replaced, never changed in place)
        self.version = 0

    def reset(self) -> None:
        """Every parameter to its default (``!sCSETPA``, spec §8.6)."""
        self._values = dict(_DEFAULTS)
        self.version += 1

    def copy(self) -> ParameterSet:
        other = ParameterSet()
        other._values = dict(self._values)
        return other

    def get(self, pid: str) -> ParamValue:
        _spec(pid)
        return self._values[pid]

    __getitem__ = get

    def set(self, pid: str, value: ParamValue | str) -> ParamValue:
        """Store `pid`; `value` is its data (``'0010.00000'``) or a ParamValue. Ranges are `check`'s."""
        stored = parse_data(pid, value) if isinstance(value, str) else parse_data(pid, format_data(pid, value))
        self._values[pid] = stored
        self.version += 1
        return stored

    def data(self, pid: str) -> str:
        return format_data(pid, self.get(pid))

    def __iter__(self) -> Iterator[ParamValue]:
        return iter(self._values[pid] for pid in PARAMETERS)

    def __eq__(self, other: object) -> bool:
        return isinstance(other, ParameterSet) and self.listing() == other.listing()

    __hash__ = None  # type: ignore[assignment]  # mutable

    # -- what is in use ------------------------------------------------------------------------------

    def enabled_axes(self) -> tuple[int, ...]:
        """Axis 1 always (L4158), axes 2-4 as B000 enables them."""
        b000 = self._values["B000"]
        return (1,) + tuple(axis for axis in (2, 3, 4) if b000[f"enable_axis_{axis}"] == 1)

    def axis_mode(self, axis: int) -> int:
        """Ax00's mode digit: 0 normal .. 5 flying cutoff."""
        return int(self._values[f"A{axis}00"].number("mode"))

    def motion_type(self, axis: int) -> int:
        """Ax00's type of motion: 0 rotary, 1 linear, 2 rotary table."""
        return int(self._values[f"A{axis}00"].number("motion_type"))

    def encoder_type(self, axis: int) -> int:
        """Ax20's encoder type: 0 incremental, 1 single-turn, 2 multi-turn, 3 controlled axis."""
        return int(self._values[f"A{axis}20"].number("encoder_type"))

    def flying_cutoff(self) -> bool:
        return self.axis_mode(1) == 5

    def master_encoder_1_used(self) -> bool:
        """Master encoder 1 serves a slave axis, axis 1's measuring wheel or the cutoff (L5511)."""
        if self.axis_mode(1) in (2, 3, 4, 5):
            return True
        return any(self.axis_mode(a) == 2 and self._values[f"A{a}00"]["master"] == MASTER_ENCODER_1 for a in self.enabled_axes())

    def used(self, pid: str) -> bool:
        """Whether the CLM uses (and so checks) `pid` with the other parameters as they are (decision 10)."""
        spec = _spec(pid)
        if spec.axis is not None:
            axis, number = spec.axis, int(spec.key[2:])
            if axis not in self.enabled_axes():
                return False
            if number >= 33:
                return axis == 1 and self.flying_cutoff()
            if number == 2:
                return self.motion_type(axis) == 2 and self.encoder_type(axis) == 0
            if number in (3, 4):
                return self.motion_type(axis) == 1
            if number == 5:
                return self.motion_type(axis) == 2
            if number == 16:
                return self.axis_mode(axis) in (3, 4)
            return True
        if pid in ("B003", "B005"):
            port = self._values["B002" if pid == "B003" else "B004"]
            return port["baud_rate"] != 0 and port["function"] == 0
        if pid == "B014":
            b014 = self._values[pid]
            return not _unset(b014["start_input"]) or b014["start_on_mode_change"] != 0
        if pid == "B015":
            return not _unset(self._values[pid]["interrupt_input"])
        if pid == "B019":
            return False
        if pid[0] == "C":
            number = int(pid[1:])
            if number <= 3:
                return self.master_encoder_1_used()
            if number <= 7:
                return 2 in self.enabled_axes() and self.axis_mode(2) in (3, 4)
            return self.flying_cutoff()
        return True

    def _unused_fields(self, pid: str) -> frozenset[str]:
        if pid in ("B002", "B004"):
            port = self._values[pid]
            if port["function"] == 1:
                return frozenset({"baud_rate", "parity", "data_bits", "stop_bits"})
            if port["baud_rate"] == 0:
                return frozenset({"parity", "data_bits", "stop_bits"})
        return frozenset()

    # -- the check on leaving Parameter mode ----------------------------------------------------------

    def check(self, *, axes_fitted: int = 4) -> list[Finding]:
        """The CLM's parameter check (L4130, L4162): fault 02 (17) with the parameter id."""
        return [Finding.of(e) for e in self.errors(axes_fitted=axes_fitted)]

    def errors(self, *, axes_fitted: int = 4) -> list[ClmError]:
        """`check` as ClmErrors, in id order."""
        errors: list[ClmError] = []
        for pid, spec in PARAMETERS.items():
            if not self.used(pid):
                continue
            skip = self._unused_fields(pid)
            for f, v in zip(spec.fields, self._values[pid].values):
                if f.checked and f.name not in skip and not _in_range(f, v):
                    unit = f" {f.unit}" if f.unit else ""
                    text = _format_field(pid, f, v)
                    errors.append(ClmError(INVALID, f"{f.name} = {text}{unit}: allowed {f.range_text()}{unit} ({spec.lines})", pid))
        errors += interaction_errors(self, {e.where for e in errors if e.where}, axes_fitted)
        return sorted(errors, key=lambda e: _ORDER.get(e.where or "", len(_ORDER)))

    # -- output ----------------------------------------------------------------------------------------

    def telegrams(self, station: int = 0) -> list[str]:
        """One ``# K <id> <data>$hh`` per parameter, in id order (no line end)."""
        return [emit("#", station, "K", f" {pid} {self.data(pid)}").rstrip("\r\n") for pid in PARAMETERS]

    def listing(self) -> str:
        """``B002 019200 0 1 8 1`` lines, in id order."""
        return "".join(f"{pid} {self.data(pid)}".rstrip() + "\n" for pid in PARAMETERS)

    def save(self, path: str | os.PathLike[str], *, telegrams: bool = False) -> None:
        """Write the set atomically: a listing, or telegrams with the CLM's CR LF."""
        if telegrams:
            atomic_write_text(path, "".join(t + "\r\n" for t in self.telegrams()), encoding="ascii", newline="")
        else:
            atomic_write_text(path, self.listing())


def _unset(value: FieldValue) -> bool:
    return isinstance(value, Operand) and value.unset


def _in_range(f: Field, value: FieldValue) -> bool:
    if f.allowed is not None:
        return value in f.allowed
    if not isinstance(value, (int, Decimal)):
        return True
    return (f.low is None or value >= f.low) and (f.high is None or value <= f.high)


def read_parameter_text(text: str, source: str = "parameters") -> tuple[ParameterSet, list[Finding]]:
    """A parameter file (either form) read into a ParameterSet with its findings: paramfile.py."""
    from .paramfile import read_parameter_text as read  # (paramfile builds on this module)

    return read(text, source)
