"""The field types of CLM instructions: fixed-point numbers, axes, instruction numbers,
operands, masks, variables; how a variable's value fits a field (error 32).

Numbers are kept exact: a constant is an integer count of the field's last digit (``+123456.789``
in a 6.3 field is ``123456789``), so nothing drifts through a float.

The variable fit (manual §5.6, L1283-1343; errata §1.9, §3.7): all variables have the format
``+12345678.123456``; used in a field, a variable is **truncated** to the field's digits
(.123456 -> .123, 999.9999 -> 999), multiplied by the sign written in front of it in the
command, then checked against the field's range and sign; a value that does not fit is error
32 "Variable Value" with the reason (too large, negative where the field has no sign).
"""

from __future__ import annotations

import re
from dataclasses import dataclass

from .errors import ClmError
from .operands import NC_READ, NC_WRITE, Operand, parse_operand, usable

__all__ = [
    "HOMING_SETTABLE",
    "USER_VARIABLES",
    "VARIABLE_SCALE",
    "Axis",
    "BitField",
    "ByteField",
    "Choice",
    "Compare",
    "Field",
    "Mask",
    "Number",
    "Text",
    "Var",
    "VarField",
    "fit_variable",
    "format_variable",
    "parse_variable_value",
]

VARIABLE_SCALE = 10**6  # variables hold 6 decimals: stored as integer millionths
VARIABLE_MAX = 10**14 - 1  # +99999999.999999
USER_VARIABLES = 600  # V600-V999 are the user's, V000-V599 the system's (§5.6, L1383-1395)
HOMING_SETTABLE = frozenset({47, 48, 100, 200, 300, 400})  # SET while not homed (L2590)
_VAR = re.compile(r"([+-]?)V(\d{3})\Z")


@dataclass(frozen=True, slots=True)
class Var:
    """A variable in a field: ``V600``, ``+V601``, ``-V604`` (sign 0 = written without one)."""

    number: int
    sign: int = 0

    def __str__(self) -> str:
        return f"{'+' if self.sign > 0 else '-' if self.sign < 0 else ''}V{self.number:03d}"


def _variable(token: str) -> Var | None:
    m = _VAR.match(token)
    if m is None:
        return None
    return Var(int(m.group(2)), {"+": 1, "-": -1, "": 0}[m.group(1)])


class Field:
    """One field of an instruction. `parse` takes one token and returns the value (a `Var`
    when the field takes variables and got one); `format` writes it as the CLM shows it."""

    name: str
    width: int  # characters of the constant form
    takes_variable: bool = False
    code: str = "0A"  # the fault for a value this field refuses

    def parse(self, token: str) -> object:
        raise NotImplementedError

    def format(self, value: object) -> str:
        raise NotImplementedError

    def describe(self) -> str:
        raise NotImplementedError

    def refuse(self, token: str, allowed: str) -> ClmError:
        return ClmError(self.code, f"{self.name} = {token[:24]!r}: allowed {allowed}")

    def parse_variable(self, token: str) -> Var | None:
        v = _variable(token)
        if v is None:
            return None
        if not self.takes_variable:
            raise self.refuse(token, f"{self.describe()} (no variable in this field)")
        return v


class Number(Field):
    """A fixed-point constant: `digits` before and `decimals` after the point, signed or not."""

    def __init__(
        self,
        name: str,
        digits: int,
        decimals: int = 0,
        *,
        signed: bool = False,
        low: int | None = None,
        high: int | None = None,
        variable: bool = True,
        code: str = "0A",
        sign_zero: bool = False,
    ) -> None:
        self.name, self.digits, self.decimals, self.signed = name, digits, decimals, signed
        top = 10 ** (digits + decimals) - 1
        self.high = top if high is None else high
        self.low = (-top if signed else 0) if low is None else low
        self.takes_variable = variable
        self.code = code
        self.sign_zero = sign_zero  # COU/BAC offsets: a '0' in the sign place means "set to zero"
        self.width = digits + (1 + decimals if decimals else 0) + (1 if signed else 0)
        self._pattern = re.compile(r"([+-]%s)?(\d{1,%d})(?:[.,](\d{0,%d}))?\Z" % ("|0" if sign_zero else "", digits, decimals) if decimals else r"([+-]%s)?(\d{1,%d})\Z" % ("|0" if sign_zero else "", digits))

    def describe(self) -> str:
        return f"{self.text(self.low)}..{self.text(self.high)}"

    def text(self, raw: int) -> str:
        sign = ("-" if raw < 0 else "+") if self.signed else ""
        whole, frac = divmod(abs(raw), 10**self.decimals)
        body = f"{whole:0{self.digits}d}" + (f".{frac:0{self.decimals}d}" if self.decimals else "")
        return sign + body

    def parse(self, token: str) -> object:
        v = self.parse_variable(token)
        if v is not None:
            if v.sign and not self.signed:
                raise self.refuse(token, f"{self.describe()} or Vnnn without a sign")
            return v
        if self.sign_zero and len(token) == self.digits + 1 and set(token) == {"0"}:
            return None  # "000000": set the count to zero (COU/BAC offset table, L1753-1770)
        m = self._pattern.match(token)
        if m is None or (m.group(1) and m.group(1) != "0" and not self.signed):
            raise self.refuse(token, self.describe() + (" or Vnnn" if self.takes_variable else ""))
        sign = -1 if m.group(1) == "-" else 1
        frac = (m.group(3) or "") if self.decimals else ""
        raw = sign * (int(m.group(2)) * 10**self.decimals + (int(frac.ljust(self.decimals, "0")) if frac else 0))
        if not self.low <= raw <= self.high:
            error = self.refuse(token, self.describe())
            error.out_of_range = True  # right shape, wrong size: over the interface "Value too large"
            raise error
        return raw

    def format(self, value: object) -> str:
        if value is None:  # the offset's "zero" form
            return "0" * (self.digits + 1)
        return str(value) if isinstance(value, Var) else self.text(int(value))  # type: ignore[call-overload]


class Axis(Field):
    """Axis 1-4 (FAK also 5, master encoder 1) or Vnnn; anything else is 16 "Axis No. false"."""

    def __init__(self, name: str = "axis", axes: tuple[int, ...] = (1, 2, 3, 4), variable: bool = True) -> None:
        self.name, self.axes, self.takes_variable = name, axes, variable
        self.code, self.width = "16", 1

    def describe(self) -> str:
        return ", ".join(map(str, self.axes))

    def parse(self, token: str) -> object:
        v = self.parse_variable(token)
        if v is not None:
            if v.sign:
                raise self.refuse(token, f"{self.describe()} or Vnnn without a sign")
            return v
        if len(token) != 1 or not token.isdigit() or int(token) not in self.axes:
            raise self.refuse(token, self.describe() + (" or Vnnn" if self.takes_variable else ""))
        return int(token)

    def format(self, value: object) -> str:
        return str(value)


class Choice(Field):
    """A selector of fixed digits (mode, state, direction ...), meanings kept for the docs."""

    def __init__(self, name: str, choices: dict[str, str], *, variable: bool = False, code: str = "0A") -> None:
        self.name, self.choices, self.takes_variable, self.code = name, choices, variable, code
        self.width = max(len(c) for c in choices)

    def describe(self) -> str:
        return " | ".join(f"{k} {v}" if v else k for k, v in self.choices.items())

    def parse(self, token: str) -> object:
        v = self.parse_variable(token)
        if v is not None:
            return v
        if token not in self.choices:
            raise self.refuse(token, " | ".join(self.choices) + (" or Vnnn" if self.takes_variable else ""))
        return token

    def format(self, value: object) -> str:
        return str(value)


class BitField(Field):
    """A bit operand ``I1.00.6``; `write` fields need an operand the NC tasks may write."""

    def __init__(self, name: str = "bit", *, write: bool = False) -> None:
        self.name, self.write, self.code, self.width = name, write, "1D", 7

    def describe(self) -> str:
        return "a bit operand the NC tasks may " + ("write (Q1, Q2.02-05, M2-M4)" if self.write else "read (I0-2, Q0-2, M0-M5)")

    def parse(self, token: str) -> object:
        op = parse_operand(token, bit=True, code=self.code)
        return self._rights(op, token)

    def _rights(self, op: Operand, token: str) -> Operand:
        if not usable(op, NC_WRITE if self.write else NC_READ):
            raise self.refuse(token, self.describe())
        return op

    def format(self, value: object) -> str:
        return str(value)


class ByteField(BitField):
    def __init__(self, name: str = "byte", *, write: bool = False) -> None:
        super().__init__(name, write=write)
        self.width = 5

    def describe(self) -> str:
        return "a byte operand the NC tasks may " + ("write (Q1, Q2.02-05, M2-M4)" if self.write else "read (I0-2, Q0-2, M0-M5)")

    def parse(self, token: str) -> object:
        op = parse_operand(token, bit=False, code=self.code)
        return self._rights(op, token)


class Mask(Field):
    """Eight digits, bit 7 first: 0 / 1 / 2 (don't care, or unchanged for APE)."""

    def __init__(self, name: str = "mask") -> None:
        self.name, self.width = name, 8

    def describe(self) -> str:
        return "8 digits of 0, 1, 2 (bit 7 first)"

    def parse(self, token: str) -> object:
        if len(token) != 8 or set(token) - set("012"):
            raise self.refuse(token, self.describe())
        return token

    def format(self, value: object) -> str:
        return str(value)


class VarField(Field):
    """A variable named by number (``Vnnn``): the target of SET/MAT, the compared one of CPJ."""

    def __init__(
        self, name: str = "variable", *, write: bool = False, low: int = 0, high: int = 999, code: str = "0A", homing_exempt: bool = False
    ) -> None:
        self.name, self.write, self.low, self.high, self.code = name, write, low, high, code
        self.width, self.takes_variable = 4, True
        # SET may write V047, V048 and Vx00 while the axis is not homed (L2590); the others
        # only V600-V999 (error 31 "Write Sys.-Var.", L1393)
        self.homing_exempt = homing_exempt

    def describe(self) -> str:
        return f"V{self.low:03d}..V{self.high:03d}"

    def parse(self, token: str) -> object:
        v = _variable(token)
        if v is None or v.sign:
            raise self.refuse(token, self.describe())
        if not self.low <= v.number <= self.high:
            raise self.refuse(token, self.describe())
        if self.write and v.number < USER_VARIABLES and not (self.homing_exempt and v.number in HOMING_SETTABLE):
            raise ClmError("31", f"{self.name} = {token}: the NC program writes V600-V999 only" + (" (and V047, V048, Vx00 while the axis is not homed)" if self.homing_exempt else ""))
        return v

    def format(self, value: object) -> str:
        return str(value)


class Compare(Field):
    """The comparison of CPJ / CPS (and the operator of MAT)."""

    def __init__(self, name: str, operators: tuple[str, ...]) -> None:
        self.name, self.operators, self.width = name, operators, max(map(len, operators))

    def describe(self) -> str:
        return " ".join(self.operators)

    def parse(self, token: str) -> object:
        if token not in self.operators:
            raise self.refuse(token, self.describe())
        return token

    def format(self, value: object) -> str:
        return str(value)


class Text(Field):
    """TXT's 16 characters: ASCII 32-95 except ``$`` and ``\\`` (L2737-2806)."""

    def __init__(self, name: str = "text", length: int = 16) -> None:
        self.name, self.width = name, length

    def describe(self) -> str:
        return f"up to {self.width} characters of ASCII 32-95 except $ and \\ (upper case)"

    def parse(self, token: str) -> object:
        bad = [c for c in token if not 32 <= ord(c) <= 95 or c in "$\\"]
        if len(token) > self.width or bad:
            raise self.refuse(token, self.describe())
        return token.ljust(self.width)

    def format(self, value: object) -> str:
        return str(value)


# ---- variables -----------------------------------------------------------------------------

_VALUE = re.compile(r"([+-]?)(\d{1,8})(?:[.,](\d{0,6}))?\Z")


def parse_variable_value(text: str) -> int:
    """``+12345678.123456`` -> 12345678123456 (millionths). ValueError names the format."""
    m = _VALUE.match(text.strip())
    if m is None:
        raise ValueError(f"{text.strip()[:24]!r}: a variable holds +12345678.123456 (sign, up to 8 digits, up to 6 decimals)")
    raw = int(m.group(2)) * VARIABLE_SCALE + int((m.group(3) or "").ljust(6, "0"))
    return -raw if m.group(1) == "-" else raw


def format_variable(raw: int) -> str:
    whole, frac = divmod(abs(raw), VARIABLE_SCALE)
    return f"{'-' if raw < 0 else '+'}{whole:08d}.{frac:06d}"


def fit_variable(field: Number, ref: Var, raw: int) -> int:
    """The value variable `ref` (holding `raw` millionths) gives in `field`, or error 32.

    Truncated to the field's decimals (toward zero), the command's sign applied, then the
    field's range and sign checked (L1295-1341).
    """
    scale = 10 ** (6 - field.decimals)
    value = (abs(raw) // scale) * (1 if raw >= 0 else -1)
    if ref.sign < 0:
        value = -value
    where = f"V{ref.number:03d} = {format_variable(raw)} in {field.name}"
    if value < 0 and field.low >= 0:
        raise ClmError("32", f"{where}: negative, the field takes {field.describe()}")
    if not field.low <= value <= field.high:
        raise ClmError("32", f"{where}: too large, the field takes {field.describe()}")
    return value
