"""`axisline clm check`: every finding the CLM would report for a set of files, before anything moves.

Per line: what the loaders find (the CLM's load refusals and the faults of a malformed
instruction). Over the whole program (the faults the CLM raises when it reaches an
instruction, which a maintainer wants to know before the machine stops on them):

* 35 "Missing EOS Cmd": a program with part-length commands (LML, LMK, LMR) has no EOS;
* 0A: LML / LMK / LMR at instruction 0000 ("may not be stored in Program Instruction 0000");
* 1A "REP Command": REP directly after SRM for another axis (L2342-2365);
* 31 "Write Sys.-Var.": CVT markers -> variable into V000-V599;
* 0E "Invalid Block #": BIC's largest jump beyond 2999 (L1576-1624); execution that runs off the
  last written instruction through NOPs to 3000 (warning: a task may never get there);
* warnings: RMI 1 0 without its offset feed right after it, SRP with x = 1 (registration.py
  decisions 7, 9), a jump into instructions never written (they are NOPs), CLC on an instruction that is
  no counter (skipped, L1702-1711), SET of V047/V048/Vx00 (allowed only while not homed), a
  counter's target in V999 (its count has no Vn+1 to go to);
* with variables: a field fed by a variable whose stored value does not fit (32, with the reason,
  as a warning: the program may change the variable before it gets there);
* with parameters: commands on axes not enabled in B000 (4E/7E/AE/DE), flying-cutoff rules
  (commands forbidden on axis 1, cutoff commands without Ax00 mode 5), and the parameter
  set's own checks on leaving Parameter mode;
* with the Logic Task: its compiler's findings (38 with the LT number).

Exit status of the command: 0 clean, 1 warnings only, 2 errors.

Decisions (spec line -> choice, why)
------------------------------------
1. C-CHECK: a finding is an error when the CLM would refuse the file or stop with a fault
   whenever it reaches the place (35, 1A, 31, 1D, a flying-cutoff rule, an axis B000 does not
   enable), and a warning when it depends on the run (a jump into unwritten NOPs, running off
   the end into 3000, CLC of a non-counter, a variable's stored value that does not fit, SET of
   a homing variable). Tests: ``tests/devices/clm/test_tool.py::test_warnings_only_exit_1``,
   ``tests/devices/clm/test_manual_programs.py``.
"""

from __future__ import annotations

from collections.abc import Iterable
from pathlib import Path

from .errors import ClmError, Finding, axis_fault
from .fields import Axis, Number, Var, fit_variable
from .files import LoadedFile, read_file
from .program import Instruction, Program

__all__ = ["check_files", "check_program", "exit_status"]

_ENDS = frozenset({"JMP", "JST", "RTS", "JTK"})
_JUMPS = frozenset({"JMP", "JSR", "JST", "BCE", "BAC", "BIO", "BPA", "CPJ", "JTK"})
_PART_LENGTH = frozenset({"LML", "LMK", "LMR"})


def _w(n: int) -> str:
    return f"N{n:04d}"


def check_program(
    program: Program,
    *,
    variables: dict[int, int] | None = None,
    enabled_axes: Iterable[int] | None = None,
    cutoff_axis1: bool | None = None,
) -> list[Finding]:
    """Whole-program findings (see the module doc). `cutoff_axis1` None: parameters unknown."""
    out: list[Finding] = []
    written = program.written()
    numbers = {i.number for i in written}
    mnemonics = {i.mnemonic for i in written}
    if mnemonics & _PART_LENGTH and "EOS" not in mnemonics:
        first = next(i for i in written if i.mnemonic in _PART_LENGTH)
        out.append(Finding(_w(first.number), "35", f"Missing EOS Cmd: {first.mnemonic} starts a cut, but the program has no EOS to end the synchronous phase"))
    previous: Instruction | None = None
    for ins in written:
        out += _instruction(ins, program, numbers, variables)
        if ins.mnemonic == "REP" and previous is not None and previous.mnemonic == "SRM" and previous.number == ins.number - 1:
            if previous.values[0] != ins.values[1]:
                out.append(Finding(_w(ins.number), "1A", f"REP Command: REP for axis {ins.values[1]} directly after SRM for axis {previous.values[0]}"))
        if enabled_axes is not None:
            out += _axes(ins, set(enabled_axes))
        if cutoff_axis1 is not None:
            out += _cutoff(ins, cutoff_axis1)
        previous = ins
    if written:
        last = written[-1]
        if last.mnemonic not in _ENDS:
            out.append(Finding(_w(last.number), "0E", f"Invalid Block #: after {last.mnemonic} at {last.number:04d} execution runs on through NOPs to 3000 (end the task with JMP, JST or RTS)", "warning"))
    return out


def _instruction(ins: Instruction, program: Program, numbers: set[int], variables: dict[int, int] | None) -> list[Finding]:
    out: list[Finding] = []
    w = _w(ins.number)
    m = ins.mnemonic
    if m in _PART_LENGTH and ins.number == 0:
        out.append(Finding(w, "0A", f"Invalid Prg Cmd: {m} may not be stored in instruction 0000 (L2103-2131)"))
    if m in _JUMPS:
        target = _target(ins)
        if isinstance(target, int) and target not in numbers:
            out.append(Finding(w, "0A", f"{m} jumps to {target:04d}, where nothing is written (NOP)", "warning"))
    if m == "CLC" and isinstance(ins.values[0], int) and program[ins.values[0]].mnemonic not in ("COU", "BAC"):
        out.append(Finding(w, "0A", f"CLC {ins.values[0]:04d}: no COU or BAC there, the CLC is skipped (L1702-1711)", "warning"))
    if m == "BIC":
        out += _bic(ins)
    if m == "SRM":
        out += _raster(ins)
    if m == "RMI" and str(ins.values[1]) == "0":
        follow = program[ins.number + 1] if ins.number + 1 < 3000 else None
        if follow is None or follow.mnemonic not in ("POI", "PSI") or str(follow.values[0]) != "1":
            out.append(Finding(w, "0A", "RMI 1 0: the offset feed (POI / PSI 1) must immediately follow it (L2375); the suspended feed is resumed without one", "warning"))
    if m == "SRP" and str(ins.values[2]) != "0":
        out.append(Finding(w, "0A", f"SRP x = {ins.values[2]}: the manual gives this digit no meaning (always 0 in its examples); axisline runs it as 0", "warning"))
    if m == "CVT" and ins.values[3] == "1" and isinstance(ins.values[0], Var) and ins.values[0].number < 600:
        out.append(Finding(w, "31", f"Write Sys.-Var.: CVT markers -> V{ins.values[0].number:03d}, a system variable (V600-V999 only)"))
    if m == "SET" and isinstance(ins.values[0], Var) and ins.values[0].number < 600:
        out.append(Finding(w, "31", f"SET {ins.values[0]}: allowed only while the axis is not homed (L2590), error 31 otherwise", "warning"))
    if m in ("COU", "BAC") and isinstance(ins.values[-1], Var) and ins.values[-1].number == 999:
        out.append(Finding(w, "32", f"{m} target in V999: the count is mirrored into the variable above it, and there is none", "warning"))
    if variables is not None:
        out += _fits(ins, variables)
    return out


def _target(ins: Instruction) -> object:
    for f, v in zip(ins.command.fields, ins.values):
        if isinstance(f, Number) and f.code == "0E":
            return v
    return None


def _bic(ins: Instruction) -> list[Finding]:
    offset, interval, _bit, bits, code = ins.values
    if not all(isinstance(v, int) for v in (offset, interval)):
        return []
    n = int(bits)  # type: ignore[call-overload]
    largest = (2**n - 1) if code == "0" else sum(min(9, 2 ** min(4, n - 4 * d) - 1) * 10**d for d in range((n + 3) // 4))
    top = int(offset) + largest * int(interval)  # type: ignore[call-overload]
    if top > 2999:
        return [Finding(_w(ins.number), "0E", f"Invalid Block #: BIC can jump to {offset} + {largest} x {interval} = {top}, beyond 2999 (L1576-1624)", "warning")]
    return []


# the fast raster inputs belong to one axis each: Raster 1 to axis 1, Raster 2 to axis 2 (L2625)
_RASTER_AXIS = {"I0.01.7": 1, "I0.01.4": 2}


def _raster(ins: Instruction) -> list[Finding]:
    axis, bit = ins.values[0], str(ins.values[3])
    owner = _RASTER_AXIS.get(bit)
    if owner is not None and isinstance(axis, int) and axis != owner:
        return [Finding(_w(ins.number), "1D", f"Command I/O: SRM on axis {axis} with {bit}, the raster input of axis {owner} (L2625)")]
    return []


def _fits(ins: Instruction, variables: dict[int, int]) -> list[Finding]:
    out = []
    for f, v in zip(ins.command.fields, ins.values):
        if isinstance(f, Number) and isinstance(v, Var) and v.number in variables:
            try:
                fit_variable(f, v, variables[v.number])
            except ClmError as e:
                out.append(Finding(_w(ins.number), "32", f"Variable Value: {e.detail} (with the variables file's value)", "warning"))
    return out


def _axes(ins: Instruction, enabled: set[int]) -> list[Finding]:
    for f, v in zip(ins.command.fields, ins.values):
        if isinstance(f, Axis) and isinstance(v, int) and v <= 4 and v not in enabled:
            return [Finding(_w(ins.number), axis_fault(0x0E, v), f"A{v} not enabled: {ins.mnemonic} on axis {v}, which B000 does not enable")]
    return []


def _cutoff(ins: Instruction, cutoff_axis1: bool) -> list[Finding]:
    cmd = ins.command
    w = _w(ins.number)
    if cmd.cutoff_only and not cutoff_axis1:
        return [Finding(w, "0A", f"Invalid Prg Cmd: {cmd.mnemonic} needs axis 1 in flying cutoff (A100 mode 5)")]
    if cutoff_axis1 and cmd.fc_forbidden:
        axis = next((v for f, v in zip(cmd.fields, ins.values) if isinstance(f, Axis)), None)
        if axis == 1 or (axis is None and cmd.mnemonic in ("JST", "RSV")):
            return [Finding(w, "0A", f"Invalid Prg Cmd: {cmd.mnemonic} is not allowed on axis 1 in flying cutoff (L3944-3960)")]
    return []


def check_files(program: Path, params: Path | None = None, logic: Path | None = None, variables: Path | None = None) -> list[Finding]:
    loaded = read_file(program, "program")
    findings = list(loaded.findings)
    values: dict[int, int] | None = None
    if variables is not None:
        v = read_file(variables, "variables")
        findings += v.findings
        values = v.data if isinstance(v.data, dict) else None
    enabled = cutoff = None
    if params is not None:
        p = read_file(params, "parameters")
        findings += p.findings
        if p.data is not None:  # read_parameter_text has run the leaving-Parameter-mode checks
            enabled, cutoff = _machine(p)
    if logic is not None:
        lt = read_file(logic, "logic")
        findings += lt.findings
        if isinstance(lt.data, dict) and lt.ok:  # the compiler's own checks: END, parentheses
            from .logic import check_logic

            findings += [f for f in check_logic(lt.data) if f not in lt.findings]
    if isinstance(loaded.data, Program):
        findings += check_program(loaded.data, variables=values, enabled_axes=enabled, cutoff_axis1=cutoff)
    return findings


def _machine(params: LoadedFile) -> tuple[set[int] | None, bool | None]:
    """Enabled axes (B000) and whether axis 1 is a flying cutoff (A100 mode 5)."""
    ps = params.data
    try:
        enabled = set(ps.enabled_axes())  # type: ignore[attr-defined]
        cutoff = bool(ps.axis_mode(1) == 5)  # type: ignore[attr-defined]
    except (AttributeError, KeyError, TypeError):
        return None, None
    return enabled, cutoff


def exit_status(findings: Iterable[Finding]) -> int:
    findings = list(findings)
    if any(f.is_error for f in findings):
        return 2
    return 1 if findings else 0
