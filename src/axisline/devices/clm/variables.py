"""The user variables V600-V999 as a file: telegrams or a listing (spec §3.2, §8.4).

* telegram, as written to the CLM: ``# V600 +00000100.000000 $hh`` (``#sVxxx_+dddddddd.dddddd_$hh``;
  the manual's digit counts for the write are "sloppy", errata/spec §8.4: the variable format
  is ``+8.6`` everywhere else, so it is used here) and the CLM's read reply
  ``V 600 +00000100.000000 $hh`` is accepted too;
* listing: ``V600 +100.5`` or ``V600 = -12.25`` (``;`` comments).

Writing a system variable (V000-V599) over the interface is Status 01 error 23 "Wrong
Variable #" (L1393); a malformed value is 18 "Not accepted".
"""

from __future__ import annotations

import re

from .errors import ClmError, serial_code
from .fields import USER_VARIABLES, format_variable, parse_variable_value
from .telegram import emit, parse_telegram

__all__ = ["parse_variable_line", "variable_listing", "variable_telegrams"]

_LISTING = re.compile(r"\s*V(\d+)\s*=?\s*(\S+)\s*(?:;.*)?\Z")


def _check(number_text: str) -> int:
    if not number_text.isdigit() or len(number_text) > 3:
        raise ClmError(serial_code(23), f"V{number_text[:6]}: variables are V000-V999")
    n = int(number_text)
    if n < USER_VARIABLES:
        raise ClmError(serial_code(23), f"V{n:03d} is a system variable (read-only); V600-V999 can be written", f"V{n:03d}")
    return n


def _value(text: str, where: str) -> int:
    try:
        return parse_variable_value(text)
    except ValueError as e:
        raise ClmError(serial_code(18), str(e), where) from None


def parse_variable_line(line: str) -> tuple[int, int]:
    """One variable line (telegram or listing) -> (number, value in millionths)."""
    s = line.strip()
    if s[:1] in "#!V" and len(s) > 2 and (s[2:3] == "V" or s[0] == "V"):
        if s[0] == "V" and not s[1:2].isdigit():  # the CLM's reply form "V 600 ..."
            t = parse_telegram(s)
            m = re.match(r"(\d+)\s+(\S+)\s*\Z", t.body)
        elif s[0] != "V":
            t = parse_telegram(s)
            if t.kind != "V":
                raise ClmError(serial_code(2), "a variable telegram is #sVxxx +value $hh")
            m = re.match(r"(\d+)\s+(\S+)\s*\Z", t.body)
        else:
            m = _LISTING.match(s)
            if m is None:
                raise ClmError(serial_code(2), f"{s[:30]!r}: a variable line is V600 +123.456")
            n = _check(m.group(1))
            return n, _value(m.group(2), f"V{n:03d}")
        if m is None:
            raise ClmError(serial_code(2), f"{s[:30]!r}: a variable telegram carries Vxxx and +12345678.123456")
        n = _check(m.group(1))
        return n, _value(m.group(2), f"V{n:03d}")
    raise ClmError(serial_code(2), f"{s[:30]!r}: a variable line is V600 +123.456 or # V600 +00000123.456000 $hh")


def variable_telegrams(values: dict[int, int], station: int = 0) -> str:
    return "".join(emit("#", station, "V", f"{n:03d} {format_variable(v)} ") for n, v in sorted(values.items()))


def variable_listing(values: dict[int, int]) -> str:
    return "".join(f"V{n:03d} {format_variable(v)}\n" for n, v in sorted(values.items()))
