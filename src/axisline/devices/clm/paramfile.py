"""CLM parameter files: the listing form (``A106 000500.000 ; comment``) and the telegram form
(``#_K_A106_000500.000$hh``), read into a `parameters.ParameterSet` with a finding for every bad
line (parameters.py decision 16).

    params, findings = read_parameter_text(text, "machine.par")
"""

from __future__ import annotations

import re

from .errors import ClmError, Finding, serial_code
from .parameters import INVALID, PARAMETERS, ParameterSet, ParamValue, check_id, parse_data
from .telegram import parse_telegram

__all__ = ["read_parameter_text"]

_TELEGRAM = re.compile(r"[#!][ 0-9A-Z]K(?: |\$|\Z)")  # '#', station, 'K' (after '_' -> blank)
_TELEGRAM_ID = re.compile(r"[#!].K +([^ $]{1,8})")


def _split_id(body: str) -> tuple[str, str]:
    """``'B002 019200 0 1 8 1'`` -> (``'B002'``, ``'019200 0 1 8 1'``)."""
    m = re.match(r"(\S+)( *)(.*)\Z", body, re.S)
    if m is None:
        raise ClmError(serial_code(2), "no parameter id in the line")
    pid = check_id(m.group(1))
    if m.group(3) and len(m.group(2)) > 2:
        raise ClmError(INVALID, f"{len(m.group(2))} blanks after the id: one blank (two tolerated)", pid)
    return pid, m.group(3)


def _read_telegram(line: str) -> tuple[str, ParamValue]:
    text = line.replace("_", " ")
    guess = _TELEGRAM_ID.match(text)
    try:
        telegram = parse_telegram(text)
    except ClmError as e:
        if guess and guess.group(1) in PARAMETERS:
            e.at(guess.group(1))
        raise
    body = telegram.body[1:] if telegram.control == "!" else telegram.body  # '!' frames no kind (telegram.py)
    if not body.startswith(" "):
        raise ClmError(serial_code(2), "a parameter telegram is #sK <id> <data>$hh")
    pid, data = _split_id(body[1:])
    return pid, parse_data(pid, data)


def _read_line(line: str) -> tuple[str, ParamValue] | None:
    """One line of a parameter file: (id, value), or None for a comment."""
    if line[0] in "#!":
        if _TELEGRAM.match(line.replace("_", " ")):
            return _read_telegram(line)
        if line[0] == "#":
            return None
        raise ClmError(serial_code(2), f"{line[:20]!r}: a line with ! is a parameter telegram '!_K_B000_0_0_0$hh'")
    body = line.split(";", 1)[0].replace("\t", " ").strip()
    if not body:
        return None
    pid, data = _split_id(body)
    return pid, parse_data(pid, data)


def read_parameter_text(text: str, source: str = "parameters") -> tuple[ParameterSet, list[Finding]]:
    """A parameter file: the defaults with the good lines applied, and a Finding for every bad line
    and for every failed check of the result (decision 16). Never raises for bad content."""
    params = ParameterSet()
    findings: list[Finding] = []
    origin: dict[str, int] = {}
    for lineno, raw in enumerate(text.splitlines(), 1):
        line = raw.strip()
        if not line:
            continue
        at = f"{source}:{lineno}"
        try:
            read = _read_line(line)
        except ClmError as e:
            findings.append(Finding.of(e, where=f"line {lineno}", source=at))
            continue
        if read is None:
            continue
        pid, value = read
        if pid in origin:
            findings.append(Finding(pid, INVALID, f"{pid} is written twice (line {origin[pid]} and here); the later one is kept", "warning", at))
        params._values[pid] = value
        params.version += 1
        origin[pid] = lineno
    for error in params.errors():
        line_of = origin.get(error.where or "")
        findings.append(Finding.of(error, source=f"{source}:{line_of}" if line_of else source))
    return params, findings
