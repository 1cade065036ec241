"""Reading and writing the CLM's files: program, parameters, Logic Task, variables.

A file holds one kind of data, one item a line, in either form:

* transfer: the telegrams a PC tool sends over the X6 port (``#_N…$hh``, ``#_K…``, ``#_P…``,
  ``#_V…``), CR LF or LF line ends; the manual's ``_`` notation for a blank is read as a blank
  in a telegram line that has no blank at all (a real telegram always has one);
* listing: as the manual prints it (``0000 POI 1 +000100.000 999  - comment``,
  ``B002 019200 0 1 8 1``, ``0000 LD M6.20.0``, ``V600 +100.5``); ``;`` starts a comment line.

Every line is read; every bad line is a `Finding` (where, CLM code, text, file:line), so a
maintainer sees the whole list at once. A file with an error is never taken half: the
caller gets the findings and keeps nothing (`LoadedFile.ok`). Files are written with the
kernel's atomic write (a reader sees the old file or the new one).

Decisions (spec line -> choice, why)
------------------------------------
1. C-UNDERSCORE, spec §0: the manual writes ``_`` for a blank in telegrams, but ``_`` is also
   a legal TXT character: in a file, a telegram line is read in the manual's notation only
   when it has no blank at all (a real telegram always has one). Test:
   ``tests/devices/clm/test_tool.py::test_broken_transfer_file_reports_status_01_errors``.
2. C-ENCODING: files are read as UTF-8, else Latin-1 (old PC tools write their code page, and
   only comments may carry it); a file over 4 MB is refused before it is read (3000
   instructions are ~150 kB). Test: ``test_unreadable_or_binary_input_is_a_finding_not_a_traceback``.
"""

from __future__ import annotations

import os
import re
from dataclasses import dataclass, field
from pathlib import Path

from ...kernel import atomic_write_text
from .errors import ClmError, Finding
from .program import Program, parse_listing_line, parse_program_telegram
from .variables import parse_variable_line, variable_listing, variable_telegrams

__all__ = [
    "KINDS",
    "LoadedFile",
    "detect_kind",
    "normalise_line",
    "read_file",
    "read_program_text",
    "read_text",
    "read_variable_text",
    "write_file",
]

KINDS = ("program", "parameters", "logic", "variables")
MAX_FILE_BYTES = 4 * 1024 * 1024  # 3000 instructions of ~40 characters are ~150 kB


@dataclass
class LoadedFile:
    kind: str
    data: object  # Program | ParameterSet | dict[int, str] (Logic Task) | dict[int, int] (variables)
    findings: list[Finding] = field(default_factory=list)

    @property
    def ok(self) -> bool:
        return not any(f.is_error for f in self.findings)


def normalise_line(line: str) -> str:
    """A telegram line in the manual's notation (``#_N0101_AEA_…``) with blanks for ``_``."""
    s = line.rstrip("\r\n")
    if s[:1] in "#!?" and " " not in s and "_" in s:
        return s.replace("_", " ")
    return s


def _is_comment(s: str) -> bool:
    return not s or s.startswith(";") or s.startswith("//")


def read_text(path: Path) -> str:
    """A file's text; ClmError (Status 01 error 02) when it cannot be read or is too large."""
    from .errors import serial_code

    try:
        size = os.stat(path).st_size
        if size > MAX_FILE_BYTES:
            raise ClmError(serial_code(2), f"{path}: {size} bytes; a CLM file is at most {MAX_FILE_BYTES} bytes")
        raw = Path(path).read_bytes()
    except OSError as e:
        raise ClmError(serial_code(2), f"{path}: cannot be read ({e.strerror})") from None
    try:
        return raw.decode("utf-8")
    except UnicodeDecodeError:
        return raw.decode("latin-1")  # old PC tools write their code page; comments may carry it


def read_program_text(text: str, source: str = "program") -> tuple[Program, list[Finding]]:
    program = Program()
    findings: list[Finding] = []
    seen: dict[int, int] = {}
    for lineno, raw in enumerate(text.splitlines(), 1):
        s = normalise_line(raw).strip()
        if _is_comment(s):
            continue
        at = f"{source}:{lineno}"
        try:
            instruction = parse_program_telegram(s) if s[0] in "#!" else parse_listing_line(s)
        except ClmError as e:
            findings.append(Finding.of(e, where=f"line {lineno}", source=at))
            continue
        n = instruction.number
        if n in seen:
            findings.append(Finding(f"N{n:04d}", "0A", f"instruction {n:04d} is written twice (line {seen[n]} and here); the later one is kept", "warning", at))
        seen[n] = lineno
        program.store(instruction)
    return program, findings


def read_variable_text(text: str, source: str = "variables") -> tuple[dict[int, int], list[Finding]]:
    values: dict[int, int] = {}
    findings: list[Finding] = []
    for lineno, raw in enumerate(text.splitlines(), 1):
        s = normalise_line(raw).strip()
        if _is_comment(s):
            continue
        try:
            n, v = parse_variable_line(s)
        except ClmError as e:
            findings.append(Finding.of(e, where=f"line {lineno}", source=f"{source}:{lineno}"))
            continue
        values[n] = v
    return values, findings


_LOGIC_ONLY = re.compile(r"\s*\d+[ \t]+(LDN?|STN?|SETC?N?|RESC?N?|ANDN?\(?|ORN?\(?|XORN?\(?|\)|END)(?=\s|$)", re.I)
_PARAMETER = re.compile(r"\s*[ABC]\d{3}(?=\s|$)")


def detect_kind(text: str) -> str:
    """Which of the four files this is, from its first lines."""
    for raw in text.splitlines():
        s = normalise_line(raw).strip()
        if _is_comment(s):
            continue
        if s[:1] in "#!" and len(s) > 2:
            return {"N": "program", "K": "parameters", "P": "logic", "V": "variables"}.get(s[2], "program")
        if s[:1] == "V":
            return "variables"
        if _PARAMETER.match(s):
            return "parameters"
        if _LOGIC_ONLY.match(s):
            return "logic"
        if re.match(r"\s*\d+[ \t]+[A-Za-z]{3}(?=\s|$)", s) and not re.match(r"\s*\d+[ \t]+NOP\s*$", s, re.I):
            return "program"
    return "program"


def read_file(path: Path, kind: str | None = None) -> LoadedFile:
    """Read one CLM file of `kind` (detected when None); never raises for bad content."""
    source = Path(path).name
    try:
        text = read_text(Path(path))
    except ClmError as e:
        return LoadedFile(kind or "program", None, [Finding.of(e, where=source)])
    kind = kind or detect_kind(text)
    data: object
    if kind == "program":
        data, findings = read_program_text(text, source)
    elif kind == "variables":
        data, findings = read_variable_text(text, source)
    elif kind == "parameters":
        from .parameters import read_parameter_text

        data, findings = read_parameter_text(text, source)
    elif kind == "logic":
        from .logic import read_logic_text

        data, findings = read_logic_text(text, source)
    else:
        raise ValueError(f"kind = {kind!r}: one of {', '.join(KINDS)}")
    return LoadedFile(kind, data, findings)


def render(loaded: LoadedFile, form: str) -> str:
    """The file's data as `form` ('transfer' | 'listing')."""
    if form not in ("transfer", "listing"):
        raise ValueError(f"form = {form!r}: transfer or listing")
    transfer = form == "transfer"
    if loaded.kind == "program":
        program: Program = loaded.data  # type: ignore[assignment]
        return program.telegrams() if transfer else program.listing()
    if loaded.kind == "variables":
        values: dict[int, int] = loaded.data  # type: ignore[assignment]
        return variable_telegrams(values) if transfer else variable_listing(values)
    if loaded.kind == "parameters":
        params = loaded.data
        return "".join(t if t.endswith("\n") else t + "\n" for t in params.telegrams()) if transfer else params.listing()  # type: ignore[attr-defined]
    from .logic import logic_listing, logic_telegrams

    lines: dict[int, str] = loaded.data  # type: ignore[assignment]
    return "".join(t if t.endswith("\n") else t + "\n" for t in logic_telegrams(lines)) if transfer else logic_listing(lines)


def write_file(path: Path, loaded: LoadedFile, form: str) -> None:
    """Write `loaded` in `form` atomically; a file with errors is refused (ValueError)."""
    if not loaded.ok:
        raise ValueError(f"{path}: not written, the input has errors")
    text = render(loaded, form)
    if form == "transfer":
        text = text.replace("\r\n", "\n").replace("\n", "\r\n")  # the CLM's CR LF
    atomic_write_text(Path(path), text, encoding="ascii" if form == "transfer" else "utf-8", newline="")
