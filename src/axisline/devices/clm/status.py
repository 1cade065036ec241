"""The CLM's status replies (``?sX__nn_``), read from a running `ClmRuntime` (spec §8.5; manual
§9.2 "Readout of Status Information", L6737-7335).

    body = status_body(rt, 0, [])        # '00  +000250.000             ' (A / blank, sign, 6.3)
    emit("X", station, "", body)          # 'X 00  +000250.000             $hh\\r\\n'

Every reply is ``Xs`` + the status number + its fields as printed, each field in fixed columns
(a blank between fields and one before ``$``), so a host can read them by column. A status that
cannot be answered raises `ClmError` with the Status 01 error the CLM sends instead (08 number
not decimal, 09 status not present, 10 measuring-wheel parameters not set, 18 Status 61 source
refused, 02 an argument missing or malformed).

======  ==========================================================  =====================
status  reply body (``_`` = blank)                                   source
======  ==========================================================  =====================
00      ``00_evmmmmmm.mmm_evnnnnnn.nnn_``  positions axes 1, 2       L6767-6787
02      ``02_nnnn_uuuu_``  Task 1 instruction, return of its 1st JSR L6825-6842
03      ``03_000C14FA_000A39CD_``  axes 1, 2 in increments (hex)     L6844-6890
04      ``04_nnnn_iiiiii_zzzzzz_``  counter of instruction nnnn      L6892-6908
05      ``05__vvvvvvvvvvvvvvvvvvvv_``  firmware version              L6910-6922
08      ``08_aaaa_bbbb_cccc_dddd_eeee_ffff_``  tasks 1-3             L6924-6949
10      ``10_vmmmmmm.mmm_vnnnnnn.nnn_``  lag axes 1, 2               L6975-6993
19      ``19_<hardware><firmware>``  (no blank before ``$``)          L6995-7017
39      ``39_aaaa_bbbb_cccc_dddd_``  tasks 4, 5                      L7019-7042
40      ``40_<hex axis 3>_<hex axis 4>_``                            L7044-7064
42/48   ``48_1_+1234.56_1_+1234.56_``  velocity axes 3, 4 / 1, 2     L7097-7113, L7195-7211
43/44   lag / positions of axes 3, 4 as 10 / 00                      L7115-7155
45/49   ``49_+00000_+00000_``  analog inputs 3, 4 / 1, 2             L7157-7173, L7213-7229
53      ``53_nn_tttttttttttttttt_``  fault code (hex) and text      L7231-7249
60      ``60_a_nnnn_``  where the fault is (0 par., 1 NC, 2 LT, 3 V) L7273-7294
61      ``61_mt.nn_bbbbbbbb_``  one byte of I/Q/M, bit 7 first       L7296-7315
63      ``63_<16/32/48/64 characters>_``  TXT mode 0 lines v..b      L7317-7335
47      ``47_0_+0090.00_``  master encoder 1 in 1/min (master_encoder.py 5) L7175-7193
09      ``09__evmmmmm.mmm_vnnnnnn.nnn_``  measuring wheel, motor (measuring_wheel.py 8)
41      ``41_emmmmmm.mmm_``  axis 1 at the last raster (registration.py 6)
54      cutoff material / product length (cutoff.py decision 8)      L7251-7271
======  ==========================================================  =====================

Decisions (spec line -> choice, why)
------------------------------------
1. C-WIDTH-6-3, errata §1.14 (``evmmmmm.mmm`` 5.3 for axis 1, ``evnnnnnn.nnn`` 6.3 for axis 2,
   L6778, also L6986, L7126, L7146): every position and lag is 6.3 with its sign (the CTA's
   ``1 A +001375.345``, L1031, and the ±999999.999 of the position commands); the manual's
   letter counts are loose elsewhere too (Status 01's text prints 18 ``t`` for "always 20
   characters", L6796/L6802). An axis the CLM does not have or B000 does not enable gives
   blanks of the field's width (the CTA shows nothing for it, L1059). Tests:
   ``tests/devices/clm/test_serial.py::test_status_00_10_44_columns``.
2. C-STATUS-04, errata §1.11 (``Xs04_nnnn_iiii_zzzzzz_____``, L6900, 4 digits for the count but
   COU targets have 6): count and preset both 6 digits, one blank before ``$``; no counter in
   the instruction -> blanks of both widths (L6908). A preset in a variable shows the
   variable's integer part. Test: ``test_status_04_counter``.
3. C-STATUS-08, L6935 prints ``fff`` for Task 3's return field and L6947-6949 say disabled
   tasks and tasks outside a subroutine give blanks: every task field is 4 characters; a task
   is enabled when B011/B012 give it a start instruction (Task 1 always); the return field is
   the bottom of the task's stack (the instruction after the main program's first JSR), blanks
   when the stack is empty. Status 02 is Task 1's pair. Test: ``test_status_02_08_39_tasks``.
4. C-VELOCITY-FLAG, spec §8.5 [MISSING figure] the single digit before each velocity in 42/47/48:
   1 for an enabled axis, 0 (and ``+0000.00``) for one that is not; the velocity is the axis'
   encoder speed in 1/min, clipped to ±9999.99. Analog inputs (45, 49): the voltage in mV
   (10 V = +10000) after the 12-bit conversion and B017's averaging (analog.py decisions 1, 2);
   ``+00000`` on a runtime without the plant's inputs. Tests: ``test_status_42_45_48_49``,
   ``tests/devices/clm/test_analog_status.py::test_status_49_and_45_in_millivolts``.
5. C-NOT-AVAILABLE: Status 47 answers error 10 "M-Wheel Param Error" when master encoder 1 is
   not set up, as L7193 says (C000 without a resolution), and 09 "Status # illegal" ("status
   information that was not present in the CLM", L6815) when it is set up but no encoder is
   wired on the plant (``device.master_encoder_1``); Status 09 is measuring_wheel.py's
   (decision 8: 10 without axis 1 in mode 3/4, 09 without a wheel); 54 (cutoff length
   counters, "only supported for Flying Cutoff", L7271) is 09 without axis 1 in flying cutoff
   (with it: cutoff.py decision 8): a host reads that the value does not exist, not that a
   parameter is wrong.
   Status 01 itself is 09 ("can *not* be queried", L6791). Test:
   ``test_status_not_available``.
6. C-STATUS-53, L7242 prints 14 ``t``: the text field is 16 characters (a CTA line, and TXT's
   16-character text that Status 53 also carries, L7247), cut or padded. A fault shows its hex
   code and text; without one the TXT mode-1 text if any, else ``00 no error`` (``01 no error
   (Parameter mode)``, Fig. 11-2). Test: ``test_status_53_fault_and_text``.
7. C-STATUS-60, L7273-7294: the place of the present fault, if it is of the kind asked for
   (``N0102`` -> 1 ``0102``, ``A106`` -> 0 ``A106``, ``LT0007`` -> 2 ``0007``, ``V620`` -> 3
   ``0620``); for fault 32 (variable value) the variable named in the fault is also given for
   a = 3 (errata §3.7: "Status 60 NC and variable numbers"). Else blanks (L7294). Test:
   ``test_status_60_where``.
8. C-STATUS-61, L6821 ("incorrect source type in Status 61" is error 18): any byte of I0-I2,
   Q0-Q2, M0-M6 is readable; another letter, source or byte is 18. Test:
   ``test_status_61_byte``.
9. C-STATUS-03, Figs. 9-17/9-18 (L6860-6890): increments = IU x Ax19 pulses x 4 / Ax01 for an
   incremental encoder, IU x Ax19 pulses / Ax01 for an absolute one, rounded, as 8 hex digits
   (32-bit two's complement when negative). Test: ``test_status_03_manual_examples``.
10. C-VERSION: Status 05 is ``FWA-CLM1.4-LAP-05VRS`` (20 characters, the firmware the spec
    describes); Status 19 is hardware ``CLM01.4-P-E-4-B`` (the manual's example) and firmware
    ``CLM1.4-LAP-05VRS``, run together as in L7006. Test: ``test_status_05_19_versions``.
"""

from __future__ import annotations

import math
import re
from decimal import Decimal
from collections.abc import Callable
from typing import Any

from .errors import FAULTS, ClmError, serial_code
from .fields import Var
from .operands import parse_operand
from .program import PROGRAM_SIZE, counter_target

__all__ = ["FIRMWARE", "FIRMWARE_SHORT", "HARDWARE", "STATUS_NUMBERS", "status_body"]

FIRMWARE = "FWA-CLM1.4-LAP-05VRS"  # Status 05: 20 characters
HARDWARE = "CLM01.4-P-E-4-B"  # Status 19 (L7006)
FIRMWARE_SHORT = "CLM1.4-LAP-05VRS"  # Status 19: at most 16 characters
STATUS_NUMBERS = (0, 2, 3, 4, 5, 8, 9, 10, 19, 39, 40, 41, 42, 43, 44, 45, 47, 48, 49, 53, 54, 60, 61, 63)
_SCALE = 1_000_000
_VAR_IN_TEXT = re.compile(r"V(\d{3})")


def _finite(value: Any) -> float:
    try:
        x = float(value)
    except (TypeError, ValueError):
        return 0.0
    return x if math.isfinite(x) else 0.0


def _fixed(value: float, integer_digits: int, decimals: int) -> str:
    """``+001375.345``: sign, zero-padded, clipped to the field."""
    limit = 10**integer_digits - 10**-decimals
    x = round(max(-limit, min(limit, _finite(value))), decimals) + 0.0  # no "-0.00"
    if x == 0:
        x = 0.0
    return f"{x:+0{integer_digits + decimals + 2}.{decimals}f}"


def _axis(rt: Any, n: int) -> Any | None:
    """The axis `n` if the CLM has it and B000 enables it (decision 1)."""
    axis = rt.axes.get(n)
    if axis is None or n not in rt.memory.parameters.enabled_axes():
        return None
    return axis


def _position(rt: Any, n: int) -> str:
    axis = _axis(rt, n)
    if axis is None:
        return " " * 12
    homed = "A" if getattr(axis, "homed", False) else " "
    return homed + _fixed(axis.actual_position, 6, 3)


def _lag(rt: Any, n: int) -> str:
    axis = _axis(rt, n)
    return " " * 11 if axis is None else _fixed(axis.lag, 6, 3)


def _increments(rt: Any, n: int) -> str:
    axis = _axis(rt, n)
    if axis is None:
        return " " * 8
    params = rt.memory.parameters
    feed = params.get(f"A{n}01").number("feed_constant")
    pulses = Decimal(int(params.get(f"A{n}19")["pulses"]))
    absolute = params.encoder_type(n) in (1, 2)
    if not feed:
        return " " * 8
    counts = Decimal(repr(_finite(axis.actual_position))) * pulses * (1 if absolute else 4) / feed
    return f"{int(counts.to_integral_value()) & 0xFFFFFFFF:08X}"


def _velocity(rt: Any, n: int) -> str:
    axis = _axis(rt, n)
    if axis is None:
        return "0 " + _fixed(0.0, 4, 2)
    rpm = getattr(axis, "rpm", None)
    if rpm is None:
        feed = float(rt.memory.parameters.get(f"A{n}01").number("feed_constant")) or 1.0
        rpm = _finite(axis.actual_velocity) * 60.0 / feed
    return "1 " + _fixed(rpm, 4, 2)


def _analog(rt: Any, n: int) -> str:
    """Status 45 / 49: the input's voltage in mV as the firmware reads it (12 bits, B017's
    averaging: analog.py decisions 1, 2); +00000 without the plant's analog inputs."""
    analog = getattr(rt, "analog", None)  # analog.ClmAnalogInputs, set by the personality
    mv = analog.millivolts(n) if analog is not None else 0
    return f"{max(-99999, min(99999, mv)):+06d}"


def _task_fields(rt: Any, number: int) -> str:
    task = rt.tasks[number - 1]
    if not _task_enabled(rt, number):
        return " " * 9
    back = task.main_return
    return f"{task.pc:04d} " + ("    " if back is None else f"{back:04d}")


def _task_enabled(rt: Any, number: int) -> bool:
    if number == 1:
        return True
    params = rt.memory.parameters
    pid = "B011" if number in (2, 3) else "B012"
    return int(params.get(pid)[f"task_{number}_start"]) != 0


def _text16(text: str) -> str:
    clean = "".join(c if " " <= c <= "~" and c not in "$\\" else "?" for c in text)
    return clean[:16].ljust(16)


def _fault_code(rt: Any) -> tuple[str, str]:
    """(code, text) of Status 53 and the polling reply (decision 6)."""
    modes = rt.modes
    fault = modes.fault_error
    if fault is not None and not fault.code.startswith("X01:"):
        return fault.code[:2].rjust(2, "0"), fault.text or fault.detail
    if modes.mode == "parameter":
        return "01", FAULTS["01"]
    return "00", rt.message or FAULTS["00"]


def fault_code(rt: Any) -> str:
    """The two hex digits of the present fault (``00`` none, ``01`` none in Parameter mode)."""
    return _fault_code(rt)[0]


def _arg(args: list[str], index: int, what: str) -> str:
    if len(args) <= index:
        raise ClmError(serial_code(2), f"the status query needs {what}")
    return args[index]


def _status_04(rt: Any, args: list[str]) -> str:
    token = _arg(args, 0, "an instruction number (?sX__04_nnnn_)")
    if not token.isdigit() or len(token) > 4:
        raise ClmError(serial_code(1), f"instruction number {token[:8]!r}: four digits 0000-2999")
    n = int(token)
    if n >= PROGRAM_SIZE:
        raise ClmError(serial_code(12), f"instruction number {n}: the program memory is 0000-2999")
    program = rt.memory.program
    ins = program[n]
    if ins.mnemonic not in ("COU", "BAC"):
        return f"04 {n:04d} {' ' * 6} {' ' * 6} "
    count = program.counters.get(n, 0)
    target = counter_target(ins)
    if isinstance(target, Var):
        preset = abs(rt.memory.variables[target.number]) // _SCALE
    else:
        preset = abs(int(target))  # type: ignore[call-overload]
    return f"04 {n:04d} {min(count, 999999):06d} {min(preset, 999999):06d} "


def _status_60(rt: Any, args: list[str]) -> str:
    token = _arg(args, 0, "the kind 0-3 (?sX__60_a_)")
    if token not in ("0", "1", "2", "3"):
        raise ClmError(serial_code(2), f"Status 60 kind {token[:4]!r}: 0 parameter, 1 NC, 2 Logic Task, 3 variable")
    a = int(token)
    fault = rt.modes.fault_error
    number = "    "
    if fault is not None and fault.where:
        where = fault.where
        if a == 0 and re.fullmatch(r"[ABC]\d{3}", where):
            number = where
        elif a == 1 and re.fullmatch(r"N\d{4}", where):
            number = where[1:]
        elif a == 2 and re.fullmatch(r"LT\d{4}", where):
            number = where[2:]
        elif a == 3 and re.fullmatch(r"V\d{3}", where):
            number = f"0{where[1:]}"
    if a == 3 and number == "    " and fault is not None and fault.code == "32":
        m = _VAR_IN_TEXT.search(fault.detail)
        if m:
            number = f"0{m.group(1)}"
    return f"60 {a} {number} "


def _status_61(rt: Any, args: list[str]) -> str:
    token = _arg(args, 0, "a byte (?sX__61_mt.nn_)")
    try:
        op = parse_operand(token, bit=False, code=serial_code(18))
    except ClmError:
        raise ClmError(serial_code(18), f"{token[:8]!r}: Status 61 reads a byte I0-I2, Q0-Q2 or M0-M6 (e.g. I1.00)") from None
    try:
        value = rt.image.get(op)
    except ValueError:
        raise ClmError(serial_code(18), f"{op} is not a byte of the CLM") from None
    return f"61 {op} {value:08b} "


def _status_63(rt: Any, args: list[str]) -> str:
    token = _arg(args, 0, "the lines vb (?sX__63_vb_, 1-4)")
    if len(token) != 2 or not token.isdigit() or not 1 <= int(token[0]) <= int(token[1]) <= 4:
        raise ClmError(serial_code(2), f"Status 63 lines {token[:4]!r}: from line v to line b, 1 <= v <= b <= 4")
    first, last = int(token[0]), int(token[1])
    return "63 " + "".join(_text16(rt.text_lines[i]) for i in range(first - 1, last)) + " "


def _no_master_encoder(rt: Any) -> ClmError:
    """Status 47 without master encoder 1: 10 when C000 has no resolution, else 09."""
    if int(rt.memory.parameters.get("C000")["graduation"]) == 0:
        return ClmError(serial_code(10), "Status 47: master encoder 1 is not set up (C000)")
    return ClmError(serial_code(9), "Status 47: master encoder 1 is not connected on the plant (device.master_encoder_1)")


# status number -> (the formatter of one value, the axes / analog inputs of its two fields)
_PAIRS: dict[int, tuple[Callable[[Any, int], str], int, int]] = {}


def status_body(rt: Any, number: int, args: list[str]) -> str:
    """The reply body of status `number` (without ``X`` and the station); ClmError with the
    Status 01 error the CLM answers instead."""
    pair = _PAIRS.get(number)
    if pair is not None:
        value, a, b = pair
        return f"{number:02d} {value(rt, a)} {value(rt, b)} "
    if number == 2:
        return f"02 {_task_fields(rt, 1)} "
    if number == 8:
        return "08 " + " ".join(_task_fields(rt, n) for n in (1, 2, 3)) + " "
    if number == 39:
        return "39 " + " ".join(_task_fields(rt, n) for n in (4, 5)) + " "
    if number == 4:
        return _status_04(rt, args)
    if number == 5:
        return f"05  {FIRMWARE:20.20} "
    if number == 19:
        return f"19 {HARDWARE}{FIRMWARE_SHORT}"
    if number == 53:
        code, text = _fault_code(rt)
        return f"53 {code} {_text16(text)} "
    if number == 60:
        return _status_60(rt, args)
    if number == 61:
        return _status_61(rt, args)
    if number == 63:
        return _status_63(rt, args)
    if number == 47:
        me = getattr(rt, "master_encoder", None)
        if me is None or int(rt.memory.parameters.get("C000")["graduation"]) == 0:
            raise _no_master_encoder(rt)
        return f"47 0 {_fixed(max(-9999.99, min(9999.99, me.rpm)), 4, 2)} "  # master_encoder.py decision 5
    if number == 9:  # the measuring wheel and the motor encoder of axis 1 (measuring_wheel.py decision 8)
        from .measuring_wheel import status_09

        return status_09(rt)
    if number == 41:  # the axis-1 position latched at the last raster (registration decision 6)
        axis = _axis(rt, 1)
        homed = "A" if axis is not None and getattr(axis, "homed", False) else " "
        return f"41 {homed}{_fixed(rt.registration.latch41, 6, 3)} "
    if number == 54:  # the cutoff length counters (cutoff.py decision 8)
        cutoff = getattr(rt, "cutoff", None)
        if cutoff is None:
            raise ClmError(serial_code(9), "Status 54 (cutoff length counters) is only supported for Flying Cutoff (A100 mode 5, L7271)")
        return cutoff.status_54()
    if number == 1:
        raise ClmError(serial_code(9), "Status 01 is sent by the CLM after a transmission error; it cannot be queried (L6791)")
    raise ClmError(serial_code(9), f"Status {number:02d} is not a status of the CLM")


_PAIRS.update({0: (_position, 1, 2), 44: (_position, 3, 4), 10: (_lag, 1, 2), 43: (_lag, 3, 4),
               3: (_increments, 1, 2), 40: (_increments, 3, 4), 42: (_velocity, 3, 4), 48: (_velocity, 1, 2),
               45: (_analog, 3, 4), 49: (_analog, 1, 2)})
