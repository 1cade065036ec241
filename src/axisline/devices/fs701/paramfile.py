"""FS701 parameter files: save (atomically), load (validated), compare.

Format: TOML, one table per parameter block, the attribute names of parameters.py as keys and
engineering values (as the OS5.1 cards show them, decimal point included) as values; every
line carries a comment with the serial code, the manual's name, the unit and the range. An
optional ``[io]`` table holds the I/O assignment of the IO Definition card. Example::

    # axisline FS701 parameter set
    format = "axisline.fs701.parameters"
    version = 1
    firmware = "FS701.09"

    [general]
    cutting_length = 2500        # 0x0000 Cutting Length [LU] 1..999999
    test_cut_length = 1000       # 0x0001 Test Cut. Length [LU] 1..999999
    ...
    [basic_settings]
    sync_rate = -1.25            # 0x0105 +/- Sync Rate [%] -9.99..9.99
    ...
    [io]
    inverted_inputs = []
    inverted_outputs = []

    [io.inputs]
    control_enable = [1]
    ...
    [io.outputs]
    ready = [1]

Loading checks everything before it returns anything: TOML syntax (tomllib's message has the
line), the header, every table and key (unknown names are refused - a typo must not silently
leave a default), every value against its register's range and resolution. All problems are
reported together in one `ParamFileError`, each with its line, parameter, value and allowed
range; a bad file changes nothing (`load_into` assigns only after the whole file passed).

Decisions:

* Format: TOML, not the motrona register list, because it is readable and diffable, carries
  names and comments, and tomllib reads it without a dependency. Floats are parsed as
  Decimal (``parse_float=Decimal``) so "9.99" is exactly raw 999.
* Parameters missing from a file take their factory default: a file may list only what
  differs (`save_parameters(..., only_changed=True)`); a complete file is written by default.
* A parameter may be written under an alias (``rel_return_speed``) but only once per file.
* ``[io]`` absent -> the file carries no I/O assignment (``ParameterFile.io is None``) and the
  caller keeps its own; present -> it is the complete card: functions or signals not listed
  are not assigned (Print Mark stays on In15).
* Integers for parameters with decimals mean engineering units (``sync_rate = 1`` is 1.00 %),
  the same rule as `ParameterSet.set`.
"""

from __future__ import annotations

import os
import re
import tomllib
from collections.abc import Mapping
from dataclasses import dataclass
from decimal import Decimal
from pathlib import Path
from typing import Any

from axisline.kernel.atomic import atomic_write_text

from .io_assign import INPUT_FUNCTIONS, OUTPUT_SIGNALS, IOAssignment, IOAssignmentError
from .parameters import BLOCKS, PARAMETERS, ParameterDiff, ParameterError, ParameterSet, parameter

__all__ = [
    "FORMAT",
    "VERSION",
    "ParamFileError",
    "ParameterFile",
    "format_parameter_file",
    "parse_parameter_file",
    "save_parameters",
    "load_parameter_file",
    "load_parameters",
    "load_into",
    "diff_parameter_files",
]

FORMAT = "axisline.fs701.parameters"
VERSION = 1
FIRMWARE = "FS701.09"
_HEADER_KEYS = {"format", "version", "firmware", "comment"}


class ParamFileError(ValueError):
    """A parameter file that cannot be loaded; `problems` lists every finding."""

    def __init__(self, source: str, problems: list[str]) -> None:
        self.source = source
        self.problems = problems
        head = f"{source}: " if source else ""
        if len(problems) == 1:
            super().__init__(head + problems[0])
        else:
            super().__init__(head + f"{len(problems)} problems:\n  " + "\n  ".join(problems))


@dataclass
class ParameterFile:
    params: ParameterSet
    io: IOAssignment | None = None
    comment: str = ""


# --------------------------------------------------------------------------------------------
# writing



MAX_PARAMETER_FILE_BYTES = 1 << 20  # a parameter file is a few kB; anything far larger is not one

def _toml_str(s: str) -> str:
    return '"' + s.replace("\\", "\\\\").replace('"', '\\"').replace("\n", "\\n") + '"'


def format_parameter_file(
    params: ParameterSet, io: IOAssignment | None = None, *, comment: str = "", only_changed: bool = False
) -> str:
    """The text of a parameter file."""
    lines = ["# axisline FS701 parameter set (motrona FS701.09 registers, engineering units)"]
    lines += [f"format = {_toml_str(FORMAT)}", f"version = {VERSION}", f"firmware = {_toml_str(FIRMWARE)}"]
    if comment:
        lines.append(f"comment = {_toml_str(comment)}")
    defaults = ParameterSet()
    for block in BLOCKS.values():
        members = [p for p in PARAMETERS if p.block == block.key]
        if only_changed:
            members = [p for p in members if params.get_raw(p) != defaults.get_raw(p)]
            if not members:
                continue
        lines += ["", f"# {block.title} ({block.section})", f"[{block.key}]"]
        for p in members:
            value = p.format_value(params.get_raw(p))
            unit = f" [{p.unit}]" if p.unit else ""
            rng = f"{p.format_value(p.minimum)}..{p.format_value(p.maximum)}"
            lines.append(f"{f'{p.attr} = {value}':<32} # 0x{p.code:04X} {p.name}{unit} {rng}")
    if io is not None:
        data = io.as_dict()
        lines += ["", "# I/O assignment (IO Definition card, §4.1.3): hardware In1..16 / Out1..8", "[io]"]
        lines.append(f"inverted_inputs = {data['inverted_inputs']}")
        lines.append(f"inverted_outputs = {data['inverted_outputs']}")
        lines += ["", "[io.inputs]"]
        lines += [f"{k} = {v}" for k, v in data["inputs"].items() if v]  # type: ignore[union-attr]
        lines += ["", "[io.outputs]"]
        lines += [f"{k} = {v}" for k, v in data["outputs"].items() if v]  # type: ignore[union-attr]
    return "\n".join(lines) + "\n"


def save_parameters(
    path: str | os.PathLike[str],
    params: ParameterSet,
    io: IOAssignment | None = None,
    *,
    comment: str = "",
    only_changed: bool = False,
) -> Path:
    """Write a parameter file atomically (the old file stays whole if anything fails);
    missing directories are created, as `axisline check` takes them for writable."""
    text = format_parameter_file(params, io, comment=comment, only_changed=only_changed)
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    atomic_write_text(path, text)
    return Path(path)


# --------------------------------------------------------------------------------------------
# reading

_TABLE = re.compile(r"^\s*\[\s*([A-Za-z0-9_.\- ]+?)\s*\]\s*(?:#.*)?$")
_KEY = re.compile(r"^\s*([A-Za-z0-9_-]+)\s*=")


def _line_index(text: str) -> dict[tuple[str, str], int]:
    """(table, key) -> line number, for messages (tomllib does not report value positions)."""
    index: dict[tuple[str, str], int] = {}
    table = ""
    for n, line in enumerate(text.splitlines(), 1):
        m = _TABLE.match(line)
        if m:
            table = m.group(1).replace(" ", "")
            index.setdefault((table, ""), n)
            continue
        m = _KEY.match(line)
        if m:
            index.setdefault((table, m.group(1)), n)
    return index


def parse_parameter_file(text: str, source: str = "") -> ParameterFile:
    """Parse and validate the text of a parameter file; raises ParamFileError."""
    try:
        data = tomllib.loads(text, parse_float=Decimal)
    except tomllib.TOMLDecodeError as exc:
        raise ParamFileError(source, [f"not valid TOML: {exc}"]) from None
    lines = _line_index(text)

    def at(table: str, key: str = "") -> str:
        n = lines.get((table, key))
        return f"line {n}: " if n else ""

    problems: list[str] = []
    if data.get("format") != FORMAT:
        problems.append(f"{at('', 'format')}format must be {FORMAT!r}, got {data.get('format')!r}")
    if data.get("version") != VERSION:
        problems.append(f"{at('', 'version')}version must be {VERSION}, got {data.get('version')!r}")
    comment = data.get("comment", "")
    if not isinstance(comment, str):
        problems.append(f"{at('', 'comment')}comment must be a string")
        comment = ""

    staged: dict[int, int] = {}
    io: IOAssignment | None = None
    for key, value in data.items():
        if key in _HEADER_KEYS:
            continue
        if key == "io":
            io = _parse_io(value, at, problems)
            continue
        if key not in BLOCKS:
            problems.append(
                f"{at(key) or at('', key)}unknown table or key {key!r} (blocks: {', '.join(BLOCKS)}, io)"
            )
            continue
        if not isinstance(value, dict):
            problems.append(f"{at('', key)}{key!r} must be a table [{key}]")
            continue
        for name, v in value.items():
            where = at(key, name)
            try:
                p = parameter(name)
            except ParameterError:
                problems.append(f"{where}[{key}] {name}: no such FS701 parameter")
                continue
            if p.block != key:
                problems.append(f"{where}[{key}] {name}: belongs to block [{p.block}]")
                continue
            if p.code in staged:
                problems.append(f"{where}[{key}] {name}: {p.attr} given twice")
                continue
            if isinstance(v, bool) or not isinstance(v, (int, Decimal)):
                problems.append(f"{where}[{key}] {name} = {v!r}: must be a number")
                continue
            try:
                staged[p.code] = p.to_raw(v)
            except ParameterError as exc:
                problems.append(f"{where}[{key}] {name}: {exc}")
    if problems:
        raise ParamFileError(source, problems)
    params = ParameterSet()
    params.update_raw(staged)
    return ParameterFile(params, io, comment)


def _parse_io(value: Any, at: Any, problems: list[str]) -> IOAssignment | None:
    if not isinstance(value, dict):
        problems.append(f"{at('', 'io')}io must be a table [io]")
        return None
    known = {f.attr for f in INPUT_FUNCTIONS}, {s.attr for s in OUTPUT_SIGNALS}
    ok = True
    for section, names in (("inputs", known[0]), ("outputs", known[1])):
        table = value.get(section, {})
        if not isinstance(table, Mapping):
            problems.append(f"{at('io', section)}io.{section} must be a table [io.{section}]")
            ok = False
            continue
        for name, terms in table.items():
            if not isinstance(terms, (list, int)) or isinstance(terms, bool):
                problems.append(f"{at('io.' + section, name)}io.{section}.{name} = {terms!r}: must be a list of numbers")
                ok = False
            elif name not in names:
                problems.append(f"{at('io.' + section, name)}io.{section}.{name}: no such FS701 {section[:-1]}")
                ok = False
    if not ok:
        return None
    try:
        return IOAssignment.from_dict(value)
    except (IOAssignmentError, TypeError) as exc:
        problems.append(f"{at('io')}io: {exc}")
        return None


def load_parameter_file(path: str | os.PathLike[str]) -> ParameterFile:
    """Read and validate a parameter file; raises ParamFileError (nothing is changed anywhere)."""
    from axisline.configerrors import read_text

    try:  # size checked before reading: a parameter file is a few kB
        text = read_text(path, MAX_PARAMETER_FILE_BYTES)
    except ValueError as exc:
        raise ParamFileError(str(path), [str(exc)]) from None
    return parse_parameter_file(text, str(path))


def load_parameters(path: str | os.PathLike[str]) -> ParameterSet:
    return load_parameter_file(path).params


def load_into(path: str | os.PathLike[str], params: ParameterSet, io: IOAssignment | None = None) -> ParameterFile:
    """Load a file into existing objects (e.g. a RegisterMap's): all or nothing."""
    loaded = load_parameter_file(path)
    params.assign(loaded.params)
    if io is not None and loaded.io is not None:
        io.assign(loaded.io)
    return loaded


def diff_parameter_files(
    a: str | os.PathLike[str] | ParameterFile, b: str | os.PathLike[str] | ParameterFile
) -> tuple[list[ParameterDiff], list[str]]:
    """(parameter differences, I/O assignment differences) between two files."""
    fa = a if isinstance(a, ParameterFile) else load_parameter_file(a)
    fb = b if isinstance(b, ParameterFile) else load_parameter_file(b)
    io_diff: list[str] = []
    if fa.io is not None and fb.io is not None:
        io_diff = fa.io.diff(fb.io)
    elif (fa.io is None) != (fb.io is None):
        io_diff = ["I/O assignment present in only one file"]
    return fa.params.diff(fb.params), io_diff
