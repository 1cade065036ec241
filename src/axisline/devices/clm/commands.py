"""The 55 commands of the CLM program language as one grammar table (manual §5.7, L1403-2955;
errata §2 lists them with their syntax and lines).

Each command is a row: its fields in order (types from `fields`), how it proceeds (one cycle,
or waits), whether it is forbidden on axis 1 in flying cutoff (L3944-3960), whether it may
stand at instruction 0000, and the serial column template. One parser (`program`) reads every
row; there is no code per command here.

Serial columns (decision C-COLUMNS): "The data formats are stipulated for each command and
must be complied with!" (L6538). Fig. 9-13 prints the constant form of ACC .. CPS: those
templates give the column where each field starts (BPA with the six blanks its checksum needs,
errata §1.8). A field that is longer than its column (a ``Vnnn`` in a 3-digit column) pushes
the rest along by keeping one blank after it. For the commands whose serial form is not
printed, the columns follow the one checksum-verified long instruction, POI in the sum table
of Fig. 9-12 (``POI_1____+123456.789_123_``): the axis field is four wide (the width of its
``Vnnn``), every other field as wide as its constant, one blank between fields.

Decisions (spec line -> choice, why)
------------------------------------
1. C-COLUMNS, spec §8.4 [INFERRED] padding / errata §1.8 "column-aligned": a field starts at
   its column in the Fig. 9-13 constant form (BPA with six blanks: only then does its printed
   ``$32`` verify), a longer value (``Vnnn`` in a 3-digit column) keeps one blank after it;
   commands without a printed form use the POI sum table's layout (axis four wide, the rest at
   their width, one blank apart); the data is framed ``bbbb ccc <data> `` so that NOP's empty
   data gives the two blanks of ``#5N0123_NOP__$45``. Tests:
   ``test_fig_9_13_constant_forms_are_the_columns_axisline_writes``,
   ``test_checksum_verified_program_telegrams_are_reproduced_byte_for_byte``,
   ``test_nop_telegram_has_two_blanks_after_the_command``.
2. C-LOST, the commands whose syntax diagram is lost (errata §2; spec FOL, FUN, LMK, LMR,
   MLO, MLT, AEO, CID, CVT [MISSING]): FOL ``a on/off mode factor`` (mode 1 without, 2 with
   ramp, factor 1.6 as FAK, L1951-1979); FUN seven digits 0/1/2 in the order the manual lists
   the channels: master encoder 1, master encoder 2, axes 1-4, material (L1989-1993); LMK ``1
   length offset`` (LML plus the offset distance set on a raster, L2103-2117); LMR ``1
   raster-distance offset-distance`` (the two values its surviving examples compute,
   L2148-2171); MLO ``bit state length`` and MLT ``bit length`` (L2184-2203, the bit written);
   AEO ``a x y scale minimum``: x on/off, y the source (1 = master encoder 1, the only one
   described), the minimum acceleration in per mille of Ax09 like ACC (three digits: the
   printed ``500____100`` is exact with it); CID ``V d value``: d 0 assign, 1 add, 2 subtract;
   CVT f 0 BCD / 1 binary, d 0 variable -> markers / 1 markers -> variable (the two examples
   L1860, L1901); RSV's five restore flags as one 5-digit block as every example prints them
   (L2448-2462). Test: ``test_lost_syntax_commands_read_and_round_trip``.
3. C-VARIABLES, which fields take ``Vnnn`` (§5.2 "If both example lines contain a variable or a
   constant in the same location, only this type of value is allowed"): every axis,
   instruction, per-mille, length, state, count, time and tolerance field (the printed pairs
   show variables there, RTM's mode too, L2470); operands, masks, operators, selector digits
   and the COU/BAC offsets are constants. Tests: ``test_fig_9_13_variable_forms_read``,
   ``test_selector_fields_refuse_values_outside_the_manual``.
4. C-BIC, Fig. 9-13 prints ``BIC_0234_56_____M0.12.3_0_1_`` with a bit count of 0, outside the
   1-8 of the text (L1580-1584): the text wins, 0 is refused. Test:
   ``test_selector_fields_refuse_values_outside_the_manual``.
5. C-MAT, MAT's constant is printed 6.6 (``+123456.987654``, L2177), SET's 8.6: both take the
   variable format 8.6 (a MAT result is a variable); shorter constants are read.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from .fields import Axis, BitField, ByteField, Choice, Compare, Field, Mask, Number, Text, VarField

__all__ = ["COMMANDS", "Command", "Literal"]


class Literal(Field):
    """A fixed character in the syntax (the ``=`` of SET and MAT); it carries no value."""

    def __init__(self, text: str) -> None:
        self.name, self.text, self.width = f"'{text}'", text, len(text)

    def describe(self) -> str:
        return repr(self.text)

    def parse(self, token: str) -> object:
        if token != self.text:
            raise self.refuse(token, self.describe())
        return self.text

    def format(self, value: object) -> str:
        return self.text


# ---- field makers (names in the manual's words) ---------------------------------------------


def axis(variable: bool = True) -> Axis:
    return Axis(variable=variable)


def axis1() -> Axis:  # the flying cutoff / registration commands run on axis 1 only
    return Axis(axes=(1,))


def target(name: str = "target instruction") -> Number:
    # "target instruction field contains invalid characters" and > 2999 are 0E (Fig. 11-2)
    return Number(name, 4, high=2999, code="0E")


def length(name: str = "length") -> Number:
    return Number(name, 6, 3, signed=True)


def unsigned_length(name: str) -> Number:
    return Number(name, 6, 3)


def velocity(name: str = "velocity") -> Number:
    return Number(name, 3)  # per mille of Ax06, 000-999


def state(name: str = "state") -> Choice:
    return Choice(name, {"0": "", "1": ""}, variable=True)


def flag(name: str, choices: dict[str, str]) -> Choice:
    return Choice(name, choices)


COMPARISONS = ("<=", ">=", "<>", "<", ">", "=")


@dataclass(frozen=True)
class Command:
    mnemonic: str
    title: str
    fields: tuple[Field, ...]
    lines: str  # manual lines of its section
    waits: bool = False  # proceeds only when its condition holds (else after one cycle)
    fc_forbidden: bool = False  # not on axis 1 in flying cutoff (L3944-3960)
    cutoff_only: bool = False  # axis 1 in flying cutoff (Ax00 mode 5) only
    not_at_0000: bool = False
    template: str | None = None  # Fig. 9-13 constant form (``_`` = blank), when printed
    columns: tuple[int, ...] = field(default=(), compare=False)

    def __post_init__(self) -> None:
        object.__setattr__(self, "columns", _columns(self))


def _columns(cmd: Command) -> tuple[int, ...]:
    """The column (in the data, after ``CMD``+blank) where each field starts."""
    if cmd.template is None:
        cols, at = [], 0
        for f in cmd.fields:
            cols.append(at)
            width = 4 if isinstance(f, Axis) else f.width
            at += width + 1
        return tuple(cols)
    data = cmd.template.replace("_", " ")[len(cmd.mnemonic) + 1 :]
    cols, at = [], 0
    for f in cmd.fields:
        while at < len(data) and data[at] == " ":
            at += 1
        cols.append(at)
        at += _printed_width(f, data, at)
    return tuple(cols)


def _printed_width(f: Field, data: str, at: int) -> int:
    if isinstance(f, (Compare, Literal)):
        ops = sorted(COMPARISONS, key=len, reverse=True) if isinstance(f, Compare) else [f.text]
        return next(len(op) for op in ops if data.startswith(op, at))
    if isinstance(f, VarField) and data.startswith("V", at):
        return 4
    end = at
    while end < len(data) and data[end] != " " and not (end > at and data[end] in "<>="):
        end += 1
    return end - at


_ON_OFF = {"0": "off", "1": "on"}

_TABLE: tuple[Command, ...] = (
    Command("ACC", "Acceleration Change", (axis(), velocity("acceleration"), velocity("deceleration")), "L1405-1431", fc_forbidden=True, template="ACC_1____234_567_"),
    Command("AEA", "Bit Set/Clear", (BitField(write=True), state()), "L1433-1440", template="AEA_Q1.01.1_1_"),
    Command(
        "AEO",
        "Acceleration Override",  # x, y not described (L1443-1445 lost): on/off and source, decision C-LOST
        (axis(), flag("mode", {"0": "off", "1": "on"}), flag("source", {"1": "master encoder 1"}), velocity("scaling factor"), velocity("minimum acceleration")),
        "L1442-1468",
        fc_forbidden=True,
        template="AEO_1____1_1_500____100_",
    ),
    Command("AKN", "Acknowledge Bit", (BitField(), state()), "L1470-1479", waits=True, template="AKN_M2.02.3_1_"),
    Command("AKP", "Acknowledge Byte", (ByteField(), Mask()), "L1481-1502", waits=True, template="AKP_M2.02_01201201_"),
    Command("APE", "Byte Set/Clear", (ByteField(write=True), Mask()), "L1504-1536", template="APE_Q1.01_01201201_"),
    Command(
        "BAC",
        "Branch Conditional on Count",
        (target(), Number("actual quantity offset", 4, signed=True, variable=False, sign_zero=True), Number("target quantity", 5)),
        "L1538-1565",
        template="BAC_1234_-5678_98765_",
    ),
    Command("BCE", "Branch Conditional on Bit", (target(), BitField(), state()), "L1567-1574", template="BCE_0234_I1.00.3____1_"),
    Command(
        "BIC",
        "Branch Conditional on Bit Field Value",
        (target("instruction offset"), Number("jump interval", 2), BitField("start bit"), Number("number of bits", 1, low=1, high=8, variable=False), flag("code", {"0": "binary", "1": "BCD"})),
        "L1576-1624",
        template="BIC_0234_56_____M0.12.3_0_1_",
    ),
    Command("BIO", "Branch Conditional on Byte Compare", (target(), ByteField("byte 1"), ByteField("byte 2"), Mask()), "L1626-1653", template="BIO_0234_M2.03_Q0.00_01201201_"),
    Command("BPA", "Branch Conditional on Byte", (target(), ByteField(), Mask()), "L1655-1667", template="BPA_0234_M2.02______01201201_"),
    Command("CID", "Change Variable Value", (VarField(write=True), flag("operation", {"0": "assign", "1": "add", "2": "subtract"}), Number("value", 5, 3, signed=True)), "L1669-1673", template="CID_V600_1_____+12345.678_"),
    Command("CIO", "Copy Bit Field", (BitField("source bit"), BitField("destination bit", write=True), Number("number of bits", 2, low=1, high=32, code="3D")), "L1675-1700", template="CIO_M2.02.3_Q1.01.1_08_"),
    Command("CLC", "Clear Counter", (target("counter instruction"),), "L1702-1711", template="CLC_0234_"),
    Command("CON", "Continuous Operation", (axis(), state("on/off"), Number("velocity", 3, signed=True)), "L1713-1725", fc_forbidden=True, template="CON_1____1____+234_"),
    Command(
        "COU",
        "Counter",
        (Number("actual quantity offset", 5, signed=True, variable=False, sign_zero=True), BitField("target bit", write=True), Number("target quantity", 6)),
        "L1727-1772",
        template="COU_+12345_Q1.01.1_654321_",
    ),
    Command(
        "CPJ",
        "Compare and Jump",
        (VarField("compared variable"), Compare("condition", COMPARISONS), Number("operand", 5, 3, signed=True), Number("tolerance", 4, 2), target()),
        "L1774-1792",
        template="CPJ_V600>=+12345.678_1234.56_1234_",
    ),
    Command("CPL", "Clear Position Lag", (axis(),), "L1794-1806", fc_forbidden=True, template="CPL_1_"),
    Command(
        "CPS",
        "Compare and Set a Bit",
        (VarField("compared variable"), Compare("condition", COMPARISONS), Number("operand", 5, 3, signed=True), Number("tolerance", 4, 2), BitField("result bit", write=True)),
        "L1808-1816",
        template="CPS_V602<=+12345.678_1234.56_Q1.01.1_",
    ),
    Command(
        "CST",
        "Clear Subroutine Stack",
        (flag("tasks", {"0": "1+2", "1": "1", "2": "2", "3": "1+2+4+5", "4": "4", "5": "5"}), Number("levels", 1, variable=False)),
        "L1818-1842",
    ),
    Command(
        "CVT",
        "Convert Variable <-> Marker",
        (VarField(), ByteField("first marker byte", write=True), flag("format", {"0": "BCD", "1": "binary"}), flag("direction", {"0": "variable to markers", "1": "markers to variable"})),
        "L1844-1903",
    ),
    Command("EOS", "End of Synchronization", (), "L1905-1911", cutoff_only=True),
    Command("FAK", "Length Scaling Factor", (Axis(axes=(1, 2, 3, 4, 5), variable=False), Number("factor", 1, 6, variable=False)), "L1913-1949"),
    Command(
        "FOL",
        "Follow Master",
        (axis(), flag("on/off", _ON_OFF), flag("slave mode", {"1": "without ramp", "2": "with ramp"}), Number("slave factor", 1, 6, variable=False)),
        "L1951-1979",
        fc_forbidden=True,
    ),
    # FUN: one digit per measuring channel in the order the manual lists them (L1989-1993)
    Command("FUN", "Functions", tuple(flag(f"{n}", {"0": "buffer, clear, restart", "1": "clear, restart", "2": "no change"}) for n in ("master encoder 1", "master encoder 2", "axis 1", "axis 2", "axis 3", "axis 4", "material")), "L1981-1995"),
    Command("HOM", "Home Axis", (axis(),), "L1997-2026", fc_forbidden=True),
    Command("JMP", "Jump Unconditional", (target(),), "L2028-2043"),
    Command("JSR", "Jump to Subroutine", (target(),), "L2045-2062"),
    Command("JST", "Jump and Stop", (target(),), "L2064-2081", fc_forbidden=True),
    Command("JTK", "Jump in Task", (target(), flag("task", {"1": "", "2": "", "4": "", "5": ""})), "L2083-2101"),
    Command("LMK", "Part Length with Length Correction", (axis1(), unsigned_length("length"), unsigned_length("offset distance")), "L2103-2117", waits=True, cutoff_only=True, not_at_0000=True),
    Command("LML", "Part Length", (axis1(), unsigned_length("length")), "L2119-2131", waits=True, cutoff_only=True, not_at_0000=True),
    Command("LMR", "Part Length with Registration", (axis1(), unsigned_length("raster distance"), unsigned_length("offset distance")), "L2133-2171", waits=True, cutoff_only=True, not_at_0000=True),
    Command(
        "MAT",
        "Mathematics",
        (VarField("result", write=True), Literal("="), VarField("operand 1"), Compare("operation", ("+", "-", "*", "/")), Number("operand 2", 8, 6, signed=True)),
        "L2173-2182",
        waits=True,
    ),
    Command("MLO", "Material Length Output", (BitField(write=True), state(), unsigned_length("material length")), "L2184-2191"),
    Command("MLT", "Material Length Test", (BitField(write=True), unsigned_length("material length")), "L2193-2203", cutoff_only=True),
    Command("NOP", "No Operation", (), "L2205-2211"),
    Command("PBK", "Stop Motion", (axis(),), "L2213-2235", fc_forbidden=True),
    Command("POA", "Positioning, Absolute", (axis(), length("position"), velocity()), "L2237-2278", fc_forbidden=True),
    Command("POI", "Positioning, Incremental", (axis(), length(), velocity()), "L2280-2298"),
    Command("PSA", "Positioning, Absolute with In-Position", (axis(), length("position"), velocity()), "L2300-2322", waits=True, fc_forbidden=True),
    Command("PSI", "Positioning, Incremental with In-Position", (axis(), length(), velocity()), "L2324-2340", waits=True),
    Command("REP", "Registration Position Limit", (target("search limit instruction"), axis(), unsigned_length("search distance")), "L2342-2365", fc_forbidden=True),
    Command("RMI", "Registration Mark Interrupt", (Axis(axes=(1,), variable=False), flag("mode", {"0": "wait for raster, offset", "1": "resume main feed"}), BitField("raster input")), "L2367-2433", waits=True, fc_forbidden=True),
    Command(
        "RSV",
        "Restart Vector",
        (flag("terminate", {"0": "no", "1": "yes"}), target("instruction"), Choice("restore flags", {f"{n:05b}": "" for n in range(32)})),
        "L2435-2466",
        fc_forbidden=True,
    ),
    Command("RTM", "Rotary Table Mode", (axis(), Number("mode", 1)), "L2468-2486", fc_forbidden=True),
    Command("RTS", "Return from Subroutine", (), "L2488-2500"),
    Command("SAC", "Set Absolute Position Counter", (axis(), Choice("mode", {"0": "offset", "1": "set", "9": "cancel reference"}, code="1B"), length("position")), "L2502-2584", fc_forbidden=True),
    Command("SET", "Set Variable Value", (VarField("variable", write=True, homing_exempt=True), Literal("="), Number("value", 8, 6, signed=True)), "L2586-2596"),
    Command("SRM", "Search for Registration Mark", (axis(), length("offset"), Number("search velocity", 3, signed=True), BitField("reference input")), "L2598-2647", waits=True, fc_forbidden=True),
    Command(
        "SRP",
        "Print Mark Registration",
        (Axis(axes=(1,), variable=False), flag("mode", {"0": "", "1": "", "2": "", "3": ""}), flag("x", {"0": "", "1": ""}), VarField("variable field", low=600, high=990, code="1F"), ByteField("marker byte", write=True)),
        "L2649-2735",
        fc_forbidden=True,
    ),
    Command("TXT", "Text Row", (flag("mode", {"0": "text (Status 63)", "1": "message (Status 53)"}), Text()), "L2737-2806"),
    Command(
        "VCC",
        "Velocity Change",
        (axis(), length("switching position"), velocity(), flag("mode", {"0": "after the distance", "1": "at the position"}), flag("reference", {"0": "", "1": ""})),
        "L2808-2859",
        waits=True,
        fc_forbidden=True,
    ),
    Command(
        "VEO",
        "Velocity Override",
        (axis(), Choice("source", {str(n): "" for n in range(6)}, variable=False), flag("x", {"0": "", "1": ""}), velocity("override"), flag("use", {"0": "factor", "1": "limit"})),
        "L2861-2944",
    ),
    Command("WAI", "Wait", (Number("time", 2, 3),), "L2946-2953", waits=True),
)

COMMANDS: dict[str, Command] = {c.mnemonic: c for c in _TABLE}
assert len(COMMANDS) == 55, len(COMMANDS)
