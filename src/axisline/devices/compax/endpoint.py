"""The device's side of the COMPAX ASCII interface: write enable, storing before the reply,
live status values, the program memory's lines, and the stored files (docs/compax.md).

* `CompaxEndpoint` - `ascii.AsciiEndpoint` with the operator's write enable (``serve
  --allow-writes``) and a store callback that saves what a line changed (cam memory,
  program sets, parameters) before its reply; a failed save is undone and answered E108.
* `ProgramInterface` - the program lines of the interface: ``N001: SETC 1`` (write),
  ``N001`` (read back), ``N001:`` (clear), ``START`` / ``STOP`` / ``BREAK`` and the direct
  commands ``POSA x``, ``POSR x``, ``OUTPUT On=x``, ``SPEED x``, ``ACCEL x``.
* `save_store` / `stored_program` - the cam memory file with the program sets in it (the
  program is kept "with the cam memory", issue 19), and the parameter file.

Decisions (tests in tests/devices/compax/test_program.py)
---------------------------------------------------------
1. Program sets over the interface (issue 19 "loaded and read back over the ASCII
   interface"): a set write is a data write (refused with E104 without --allow-writes, like
   F / I / B / P writes); START, STOP, BREAK and the direct commands are commands (E107
   without it). Sets cannot be written while the program runs (E107): the standard device
   edits its program memory with the program stopped, and a set changed under the
   interpreter would run half old, half new. Test: test_sets_are_refused_while_the_program_runs.
2. Direct positioning (L1409 "When commands are set by bus, it is the second positioning
   command that is rejected"): a POSA / POSR over the interface while a positioning command
   (or a LOOP) runs is refused with E107, and so is one with the power stage off.
   GOTO, IF, WAIT and END are program sets only (E101 as a direct line). Tests:
   test_programrun.py::test_a_second_positioning_command_over_the_interface_is_rejected,
   test_program_flow_commands_are_sets_only.
3. Storage (issue 19 "stored with the cam memory (atomically, kept through a kill -9 once
   acknowledged)"): the program sets are a ``"program"`` list of read-back lines in the cam
   memory file (``memory_file``), written atomically with the memory before the reply to a
   set line; a memory file without the key (written before programs existed) holds no
   program, and then ``program_file`` is loaded. Test: test_program_is_saved_with_the_cam_memory.
"""

from __future__ import annotations

import json
import os
import re
from pathlib import Path
from typing import Any, Callable

from axisline.configerrors import read_text
from axisline.devices.compax import E_NOT_AVAILABLE, E_RESERVED, E_STORE, E_SYNTAX, CompaxError
from axisline.devices.compax.ascii import AsciiEndpoint
from axisline.devices.compax.cammemory import MAX_MEMORY_FILE_BYTES, CamMemory
from axisline.devices.compax.parameters import PARAMETERS, Parameters
from axisline.devices.compax.program import Kind, ProgramMemory, parse_command, parse_set_line
from axisline.devices.compax.programrun import ProgramRun
from axisline.devices.compax.status import StatusValues, format_status
from axisline.kernel import atomic_write_text

__all__ = [
    "CompaxEndpoint",
    "LiveStatus",
    "ProgramInterface",
    "load_parameters",
    "save_parameters",
    "save_store",
    "stored_program",
]

_PARAM_FILE_FORMAT = "axisline-compax-parameters"
# writes of the ASCII interface (refused from the network unless writes are enabled)
_DATA_WRITE = re.compile(r"[IFB]\d+=.*|P\d+=.*|N\d+(:.*|[A-Z].*)")
# lines that change what the device keeps through a power cut (saved before the reply)
_STORING = re.compile(r"[IFB]\d+=.*|P\d+=.*|RESETF|RESETP|N\d+(:.*|[A-Z].*)")
_COMMAND = re.compile(r"RESETF|VF|VP|VC|RESETP|SETS|SS|POSRCAM|PR|POSAHOME|START|STOP|BREAK|"
                      r"(SETC|SC|SETM|SM|LOOP|LP|POSA|POSR|OUTPUT|SPEED|ACCEL|GOSUB|GOTO).+")
_STATUS_READ = re.compile(r"S(\d+)")
_DIRECT = re.compile(r"(POSA|POSR|OUTPUT|SPEED|ACCEL|GOSUB|GOTO|IF|WAIT).+|END")
_DIRECT_KINDS = (Kind.POSA, Kind.POSR, Kind.OUTPUT, Kind.SPEED, Kind.ACCEL)


class LiveStatus(StatusValues):
    """The status values read live from the cam operation; S30 is the last error of the
    interface or of the cam operation (whichever came last)."""

    def __init__(self, op: Any) -> None:
        super().__init__()
        self.op = op

    def __getitem__(self, number: int) -> float:
        stored = super().__getitem__(number)  # checks the number
        return stored if number == 30 else float(self.op.status(number))

    def read(self, number: int, parameters: Any = None) -> float:
        return self[number]


class ProgramInterface:
    """The program memory and its interpreter as the interface sees them (decisions 1, 2)."""

    def __init__(self, program: ProgramMemory, run: ProgramRun) -> None:
        self.program = program
        self.run = run

    def handles(self, line: str) -> bool:
        """`line` (spaces removed, upper case) is one of ours."""
        return bool(re.fullmatch(r"N\d+.*|START|STOP|BREAK", line) or _DIRECT.fullmatch(line))

    def answer(self, text: str, line: str) -> str:
        if line == "START":
            self.run.start()
            return ""
        if line == "STOP":
            self.run.stop()
            return ""
        if line == "BREAK":
            self.run.brk()
            return ""
        parsed = parse_set_line(text) if line.startswith("N") else None
        if parsed is not None:
            number, body = parsed
            if body is None:
                return self.program.read(number)
            if self.run.running:
                raise CompaxError(f"N{number:03d} not stored: sets cannot be changed while the program runs "
                                  "(STOP or BREAK first)", code=E_NOT_AVAILABLE, field="set", value=number,
                                  allowed="program stopped")
            if body == "":
                self.program.clear(number)
            else:
                self.program.write(number, body)
            return ""
        command = parse_command(text)  # locked commands: E107 here
        if command.kind not in _DIRECT_KINDS:
            raise CompaxError(f"{command.text!r}: a program set only (write it as N<n>: {command.text})",
                              code=E_SYNTAX, field="line", value=text)
        self.run.direct(command)
        return ""


class CompaxEndpoint(AsciiEndpoint):
    """The ASCII interface with the operator's write enable (see the module docstring)."""

    def __init__(self, memory: CamMemory, parameters: Parameters, commands: Any, status: StatusValues,
                 writes_allowed: Callable[[], bool],
                 store: Callable[[CamMemory, Parameters, ProgramMemory | None], None] | None = None,
                 program: ProgramInterface | None = None) -> None:
        super().__init__(memory, parameters, commands, status)
        self._writes_allowed = writes_allowed
        #: saves what a line changed (given the state before it); None: nothing is kept
        self._store = store
        self.program = program

    def _dispatch(self, text: str) -> str:
        line = "".join(text.split()).upper()
        match = _STATUS_READ.fullmatch(line)
        if match:
            number = int(match[1])
            return f"S{number:03d}={format_status(self.status.read(number, self.parameters))}"
        if not self._writes_allowed():
            if _DATA_WRITE.fullmatch(line):
                # short enough that the hint survives the error reply's length limit
                raise CompaxError(f"{line!r} refused: network writes are off (serve --allow-writes)",
                                  code=E_RESERVED, field="line", value=text)
            if _COMMAND.fullmatch(line):
                raise CompaxError(f"{line!r} refused: network commands are off (serve --allow-writes)",
                                  code=E_NOT_AVAILABLE, field="line", value=text)
        if self._store is None or not _STORING.fullmatch(line):
            return self._route(text, line)
        memory, params = self.memory.copy(), self.parameters.snapshot()
        program = self.program.program.copy() if self.program is not None else None
        body = self._route(text, line)
        try:
            self._store(memory, params, program)
        except OSError as e:
            # the host must not take an unsaved change for a stored one: undo it, say why
            self.memory.restore(memory)
            self.parameters.restore(params)
            if program is not None and self.program is not None:
                self.program.program.restore(program)
            raise CompaxError(f"{line!r} not stored ({e.strerror or e}); nothing changed", code=E_STORE,
                              field="line", value=text) from None
        return body

    def _route(self, text: str, line: str) -> str:
        if self.program is not None and self.program.handles(line):
            return self.program.answer(text, line)
        return super()._dispatch(text)


# ---------------------------------------------------------------------------------------
# stored files


def save_store(path: str | Path, memory: CamMemory, program: ProgramMemory | None) -> None:
    """The cam memory file with the program sets in it (decision 3), atomically."""
    document = memory.document()
    if program is not None:
        document["program"] = program.lines()
    atomic_write_text(path, json.dumps(document) + "\n")


def stored_program(path: str | Path) -> list[str] | None:
    """The program sets of a cam memory file (None: the file holds no program key)."""
    name = os.fspath(path)
    try:
        document = json.loads(read_text(path, MAX_MEMORY_FILE_BYTES))
    except (ValueError, RecursionError) as exc:
        raise CompaxError(f"{name}: not a cam memory file ({exc})", field="file", value=name) from None
    lines = document.get("program") if isinstance(document, dict) else None
    if lines is None:
        return None
    if not isinstance(lines, list) or not all(isinstance(x, str) for x in lines):
        raise CompaxError(f"{name}: 'program' must be a list of set lines ('N001: SETC 1')", field="program",
                          value=name)
    return lines


def save_parameters(params: Parameters, path: str | Path) -> None:
    """The written parameter values as JSON, atomically (what a restart loads)."""
    doc = {"format": _PARAM_FILE_FORMAT, "version": 1,
           "written": {f"P{n}": params.written[n] for n in sorted(PARAMETERS)}}
    atomic_write_text(path, json.dumps(doc, indent=1) + "\n")


def load_parameters(path: str | Path) -> Parameters:
    """A parameter file as the device has it after power on: every value written and valid."""
    name = str(path)
    try:  # the size is checked before the file is read: a parameter file is a few kB
        doc = json.loads(read_text(path, 1 << 20))
    except json.JSONDecodeError as e:
        raise CompaxError(f"{name}: not a parameter file ({e})") from None
    except (ValueError, RecursionError) as e:  # too large, not UTF-8, nested too deep
        raise CompaxError(f"{name}: not a parameter file ({e})") from None
    if not isinstance(doc, dict) or doc.get("format") != _PARAM_FILE_FORMAT or doc.get("version") != 1:
        raise CompaxError(f"{name}: not a parameter file (format {_PARAM_FILE_FORMAT!r}, version 1)")
    written = doc.get("written")
    if not isinstance(written, dict):
        raise CompaxError(f"{name}: 'written' must be a table of parameter values")
    params = Parameters()
    for key, value in written.items():
        m = re.fullmatch(r"P(\d+)", str(key))
        if m is None:
            raise CompaxError(f"{name}: {key!r} is not a parameter number (P<n>)")
        params[int(m[1])] = value
    for event in ("VC", "VP", "SETC", "LOOP", "cycle_end"):  # power on: what was stored is valid
        params.make_valid(event)
    return params
