"""What each NC command does when a task reaches it (manual §5.7, L1403-2955; spec §3.6).

One function per mnemonic, ``handler(rt, task, ins) -> next instruction | None (wait)``,
collected in `HANDLERS`. Field values are read through the runtime (`rt.value`), which fits a
variable to its field (fault 32) and checks an axis (16, 4E). LML and EOS are the flying
cutoff's (`cutoff`, rt.cutoff), LMK and LMR `cutoff_raster`, MLO and MLT `material_length`. In flying cutoff a command forbidden for axis 1
(commands.py ``fc_forbidden``, L3944-3947) is fault 0A when it addresses axis 1 (JST at all). RSV is `restart.op_rsv` (the restart program,
restart.py); ACC and FAK note the program's values there for the restart image, and RMI notes
where Task 2's raster cycle began (restart decisions 1, 9). VCC, VEO and AEO are here, their state and
decisions in `override` (rt.velocity); SRM, REP, SRP and RMI in `registration`
(rt.registration), which also takes part in PSI/POI of axis 1 while SRP or RMI is active.

Decisions (spec line -> choice, why)
------------------------------------
1. C-CVT-BINARY, §5.7 CVT (L1870-1880) gives the binary format as "1 x operational sign bit
   ... 4 x bytes before the decimal point; 4 x bytes after the decimal point" without the
   coding of the fraction: the 4 bytes after the point hold the six decimals as an integer
   (0-999999), least significant byte first like the BCD form of Fig. 5-8, the sign in bit 7 of
   the highest byte. Test: ``tests/devices/clm/test_nc.py::test_cvt_binary_round_trip``.
2. C-MAT, "The calculating unit ... is independent of the cycle time ... this command can endure
   over the time period of multiple cycles" (L2176-2180) without a number: the unit is shared
   by the five tasks and does one calculation per NC cycle; a MAT takes it in the cycle it is
   reached (waiting while another task's MAT has it), its result is stored in the next cycle,
   and the task goes on then: two cycles, more when tasks calculate at once. Products and
   quotients are cut to six decimals toward zero, as a field truncates a variable (§5.6); a
   result beyond +-99999999.999999 is fault 32, a division by zero 07. Tests: ``test_mat``,
   ``test_mat_takes_two_cycles_and_the_unit_is_shared``.
3. C-CID, the operation digit of CID (decision C-LOST): 0 assigns, 1 adds, 2 subtracts the
   5.3 value. Test: ``test_cid``.
4. C-LT-OWNED, errata "an NC write to an LT-owned output": L5723 "this output can no longer be
   processed in one of the NC Tasks": the NC write has no effect on an output or marker the
   Logic Task writes (`clm check --logic` warns about it). Test: ``test_nc_write_to_a_logic_task_output_has_no_effect``.
"""

from __future__ import annotations

from fractions import Fraction
from typing import TYPE_CHECKING

from .errors import ClmError
from .fields import VARIABLE_MAX, VARIABLE_SCALE, Var
from .operands import Operand
from .program import Instruction
from .cutoff_raster import op_lmk, op_lml, op_lmr
from .material_length import op_mlo, op_mlt
from .measuring_wheel import op_fun
from .registration import op_rep, op_rmi, op_srm, op_srp
from .restart import op_rsv

if TYPE_CHECKING:
    from .nc import Handler, NcTask
    from .runtime import ClmRuntime

__all__ = ["HANDLERS", "LATER"]

# commands of the later parts: the part that brings them
LATER: dict[str, str] = {}  # (every command is there since part 4)


def _next(task: NcTask) -> int:
    return task.pc + 1


# -- bits and bytes -------------------------------------------------------------------------


def _bits(rt: ClmRuntime, start: Operand, count: int) -> list[int]:
    """`count` bits from `start` upward, on into the next bytes (BIC, CIO; L1590)."""
    out = []
    byte, bit = start.byte, start.bit or 0
    for _ in range(count):
        out.append(rt.read_bit(Operand(start.area, start.source, byte, bit)))
        bit += 1
        if bit == 8:
            byte, bit = byte + 1, 0
    return out


def _mask_holds(value: int, mask: str) -> bool:
    """Mask digits bit 7 first: 0 must be 0, 1 must be 1, 2 not checked (AKP, BPA, BIO)."""
    for i, digit in enumerate(mask):
        bit = (value >> (7 - i)) & 1
        if digit != "2" and bit != int(digit):
            return False
    return True


def op_nop(rt: ClmRuntime, task: NcTask, ins: Instruction) -> int | None:
    return _next(task)


def op_aea(rt: ClmRuntime, task: NcTask, ins: Instruction) -> int | None:
    rt.write_bit(ins.values[0], rt.state_value(ins, 1))  # type: ignore[arg-type]
    return _next(task)


def op_akn(rt: ClmRuntime, task: NcTask, ins: Instruction) -> int | None:
    return _next(task) if rt.read_bit(ins.values[0]) == rt.state_value(ins, 1) else None  # type: ignore[arg-type]


def op_akp(rt: ClmRuntime, task: NcTask, ins: Instruction) -> int | None:
    return _next(task) if _mask_holds(rt.read_byte(ins.values[0]), str(ins.values[1])) else None  # type: ignore[arg-type]


def op_ape(rt: ClmRuntime, task: NcTask, ins: Instruction) -> int | None:
    op: Operand = ins.values[0]  # type: ignore[assignment]
    value = rt.read_byte(op)
    for i, digit in enumerate(str(ins.values[1])):
        bit = 1 << (7 - i)
        if digit == "0":
            value &= ~bit
        elif digit == "1":
            value |= bit
    rt.write_byte(op, value)
    return _next(task)


def op_bce(rt: ClmRuntime, task: NcTask, ins: Instruction) -> int | None:
    return rt.target(ins, 0) if rt.read_bit(ins.values[1]) == rt.state_value(ins, 2) else _next(task)  # type: ignore[arg-type]


def op_bpa(rt: ClmRuntime, task: NcTask, ins: Instruction) -> int | None:
    return rt.target(ins, 0) if _mask_holds(rt.read_byte(ins.values[1]), str(ins.values[2])) else _next(task)  # type: ignore[arg-type]


def op_bio(rt: ClmRuntime, task: NcTask, ins: Instruction) -> int | None:
    mask = str(ins.values[3])
    both = _mask_holds(rt.read_byte(ins.values[1]), mask) and _mask_holds(rt.read_byte(ins.values[2]), mask)  # type: ignore[arg-type]
    return rt.target(ins, 0) if both else _next(task)


def op_bic(rt: ClmRuntime, task: NcTask, ins: Instruction) -> int | None:
    """Target = offset + value x interval; the bits from the start bit upward, the first the
    lowest weight; BCD: 4 bits a decade, a decade above 9 is fault 0D (L1576-1624)."""
    offset, interval = rt.target(ins, 0), rt.number(ins, 1)
    bits = _bits(rt, ins.values[2], int(ins.values[3]))  # type: ignore[arg-type, call-overload]
    if ins.values[4] == "0":
        value = sum(b << i for i, b in enumerate(bits))
    else:
        value = 0
        for decade in range(0, len(bits), 4):
            digit = sum(b << i for i, b in enumerate(bits[decade : decade + 4]))
            if digit > 9:
                raise ClmError("0D", f"BIC: BCD decade {decade // 4 + 1} reads {digit}")
            value += digit * 10 ** (decade // 4)
    target = offset + value * interval
    if target > 2999:
        raise ClmError("0E", f"BIC: {offset} + {value} x {interval} = {target}, beyond 2999")
    return target


def op_cio(rt: ClmRuntime, task: NcTask, ins: Instruction) -> int | None:
    count = rt.number(ins, 2)
    if not 1 <= count <= 32:
        raise ClmError("3D", f"CIO of {count} bits: at most 32 (L8693-8695)")
    source, dest = ins.values[0], ins.values[1]
    bits = _bits(rt, source, count)  # type: ignore[arg-type]
    byte, bit = dest.byte, dest.bit or 0  # type: ignore[union-attr]
    for b in bits:
        rt.write_bit(Operand(dest.area, dest.source, byte, bit), b)  # type: ignore[union-attr]
        bit += 1
        if bit == 8:
            byte, bit = byte + 1, 0
    return _next(task)


# -- counters -------------------------------------------------------------------------------


def _count(rt: ClmRuntime, task: NcTask, ins: Instruction) -> bool:
    """Increment first, then compare (L1544-1546, L1733): True when the target is reached
    (the count is then 0 again). A target in Vn mirrors the count into Vn+1 (L1770)."""
    counters = rt.memory.program.counters
    target = rt.number(ins, len(ins.values) - 1)
    count = counters.get(task.pc, 0) + 1
    reached = count >= target
    counters[task.pc] = 0 if reached else count
    ref = ins.values[-1]
    if isinstance(ref, Var) and ref.number < 999:
        rt.memory.variables.write(ref.number + 1, counters[task.pc] * VARIABLE_SCALE)
    return reached


def op_cou(rt: ClmRuntime, task: NcTask, ins: Instruction) -> int | None:
    if _count(rt, task, ins):
        rt.write_bit(ins.values[1], 1)  # type: ignore[arg-type]  # only set, never cleared (L1735)
    return _next(task)


def op_bac(rt: ClmRuntime, task: NcTask, ins: Instruction) -> int | None:
    return _next(task) if _count(rt, task, ins) else rt.target(ins, 0)


def op_clc(rt: ClmRuntime, task: NcTask, ins: Instruction) -> int | None:
    n = rt.target(ins, 0)
    if rt.memory.program[n].mnemonic in ("COU", "BAC"):  # else skipped (L1709)
        rt.memory.program.counters[n] = 0
    return _next(task)


# -- variables ------------------------------------------------------------------------------


def _compare(a: int, op: str, b: int, tolerance: int) -> bool:
    if op == "=":
        return abs(a - b) <= tolerance
    if op == "<>":
        return abs(a - b) > tolerance
    return {"<": a < b, ">": a > b, "<=": a <= b, ">=": a >= b}[op]


def _comparison(rt: ClmRuntime, ins: Instruction) -> bool:
    """CPJ / CPS: Vxxx <op> operand within the tolerance for = and <> (L1780-1790)."""
    a = rt.variable(ins.values[0])  # type: ignore[arg-type]
    b = rt.number(ins, 2) * 1000  # 5.3 -> millionths
    tolerance = rt.number(ins, 3) * 10_000  # 4.2 -> millionths
    return _compare(a, str(ins.values[1]), b, tolerance)


def op_cpj(rt: ClmRuntime, task: NcTask, ins: Instruction) -> int | None:
    return rt.target(ins, 4) if _comparison(rt, ins) else _next(task)


def op_cps(rt: ClmRuntime, task: NcTask, ins: Instruction) -> int | None:
    rt.write_bit(ins.values[4], int(_comparison(rt, ins)))  # type: ignore[arg-type]
    return _next(task)


def _store(rt: ClmRuntime, ref: Var, raw: int, *, homing_exempt: bool = False) -> None:
    if not -VARIABLE_MAX <= raw <= VARIABLE_MAX:
        raise ClmError("32", f"V{ref.number:03d}: {raw / 1e6:.6f} is beyond +-99999999.999999")
    rt.memory.variables.write(ref.number, raw, homing_exempt=homing_exempt)
    if homing_exempt and ref.number < 600:
        rt.set_position_variable(ref.number, raw)


def op_set(rt: ClmRuntime, task: NcTask, ins: Instruction) -> int | None:
    _store(rt, ins.values[0], rt.number(ins, 2), homing_exempt=True)  # type: ignore[arg-type]
    return _next(task)


def op_cid(rt: ClmRuntime, task: NcTask, ins: Instruction) -> int | None:
    ref: Var = ins.values[0]  # type: ignore[assignment]
    value = rt.number(ins, 2) * 1000  # 5.3 -> millionths
    old = rt.memory.variables[ref.number]
    _store(rt, ref, {"0": value, "1": old + value, "2": old - value}[str(ins.values[1])])
    return _next(task)


def op_mat(rt: ClmRuntime, task: NcTask, ins: Instruction) -> int | None:
    """The calculating unit is shared by the tasks and works one calculation a cycle: a MAT
    takes the unit in one cycle (waiting while another task's MAT has it) and stores its result
    and goes on in the next (decision C-MAT)."""
    if task.wait is None:
        if rt.calculator_cycle == rt.cycle:  # another task's calculation this cycle
            return None
        rt.calculator_cycle = rt.cycle
        task.wait = _calculate(rt, ins)
        return None
    _store(rt, ins.values[0], task.wait)  # type: ignore[arg-type]
    return _next(task)


def _calculate(rt: ClmRuntime, ins: Instruction) -> int:
    a = rt.variable(ins.values[2])  # type: ignore[arg-type]
    b = rt.number(ins, 4)
    op = str(ins.values[3])
    if op == "+":
        r = a + b
    elif op == "-":
        r = a - b
    elif op == "*":
        p = a * b
        r = abs(p) // VARIABLE_SCALE * (1 if p >= 0 else -1)
    else:
        if b == 0:
            raise ClmError("07", f"MAT: {ins.values[2]} / 0")
        q = abs(a) * VARIABLE_SCALE // abs(b)
        r = q if (a >= 0) == (b > 0) else -q
    if not -VARIABLE_MAX <= r <= VARIABLE_MAX:
        raise ClmError("32", f"{ins.values[0]}: {r / 1e6:.6f} is beyond +-99999999.999999")
    return r


def op_cvt(rt: ClmRuntime, task: NcTask, ins: Instruction) -> int | None:
    """Variable <-> eight marker bytes, BCD (Fig. 5-8, L1853-1885) or binary (decision 1)."""
    ref: Var = ins.values[0]  # type: ignore[assignment]
    first: Operand = ins.values[1]  # type: ignore[assignment]
    binary, to_variable = ins.values[2] == "1", ins.values[3] == "1"
    places = [Operand(first.area, first.source, first.byte + i) for i in range(8)]
    if to_variable:
        data = [rt.read_byte(p) for p in places]
        rt.memory.variables.write(ref.number, _from_markers(data, binary))
    else:
        for p, value in zip(places, _to_markers(rt.memory.variables[ref.number], binary)):
            rt.write_byte(p, value)
    return _next(task)


def _to_markers(raw: int, binary: bool) -> list[int]:
    whole, frac = divmod(abs(raw), VARIABLE_SCALE)
    if binary:
        data = list(frac.to_bytes(4, "little")) + list(whole.to_bytes(4, "little"))
        if raw < 0:
            data[7] |= 0x80
        return data
    digits = f"{whole:08d}"[::-1]  # least significant first
    decimals = f"{frac:06d}"[::-1]
    pack = lambda s, i: int(s[i + 1]) << 4 | int(s[i])  # noqa: E731  (low nibble: the lower digit)
    return [pack(decimals, 0), pack(decimals, 2), pack(decimals, 4), pack(digits, 0), pack(digits, 2), pack(digits, 4), pack(digits, 6), 0xFF if raw < 0 else 0]


def _from_markers(data: list[int], binary: bool) -> int:
    if binary:
        negative = bool(data[7] & 0x80)
        frac = int.from_bytes(bytes(data[:4]), "little")
        whole = int.from_bytes(bytes(data[4:7] + [data[7] & 0x7F]), "little")
        if frac >= VARIABLE_SCALE or whole >= 10**8:
            raise ClmError("32", "CVT: the markers hold a value beyond +-99999999.999999")
        raw = whole * VARIABLE_SCALE + frac
        return -raw if negative else raw
    nibbles = []
    for byte in data[:7]:
        low, high = byte & 0x0F, byte >> 4
        if low > 9 or high > 9:
            raise ClmError("0D", f"CVT: marker byte {byte:08b} is not BCD")
        nibbles += [low, high]
    frac = sum(d * 10**i for i, d in enumerate(nibbles[:6]))
    whole = sum(d * 10**i for i, d in enumerate(nibbles[6:14]))
    raw = whole * VARIABLE_SCALE + frac
    return -raw if data[7] else raw


# -- program flow ---------------------------------------------------------------------------


def op_jmp(rt: ClmRuntime, task: NcTask, ins: Instruction) -> int | None:
    return rt.target(ins, 0)


def op_jsr(rt: ClmRuntime, task: NcTask, ins: Instruction) -> int | None:
    target = rt.target(ins, 0)
    task.push(task.pc + 1)
    return target


def op_rts(rt: ClmRuntime, task: NcTask, ins: Instruction) -> int | None:
    if rt.cutoff is not None:
        rt.cutoff.end_of_program(task)  # a processing program without EOS: 35 (cutoff.py 5)
    if not task.stack and rt.manual_vector_running(task):
        rt.end_manual_vector()  # the manual vector program ends with RTS on an empty stack (L3377)
        return task.pc
    return task.pop()


def op_jst(rt: ClmRuntime, task: NcTask, ins: Instruction) -> int | None:
    """Jump, then stop there: all of tasks 1, 2, 4, 5 stop as at Immediate Stop (L2064-2081)."""
    target = rt.target(ins, 0)
    if rt.cutoff is not None:
        raise ClmError("0A", "JST may not be programmed in flying cutoff (L3944-3947)")
    rt.programmed_stop(task, target)
    return target


def op_jtk(rt: ClmRuntime, task: NcTask, ins: Instruction) -> int | None:
    target, number = rt.target(ins, 0), int(str(ins.values[1]))
    if number == task.number:
        return target
    other = rt.tasks[number - 1]
    other.pc, other.wait = target, None  # its instruction is aborted (L2090)
    return _next(task)


def op_cst(rt: ClmRuntime, task: NcTask, ins: Instruction) -> int | None:
    selection = {"0": (1, 2), "1": (1,), "2": (2,), "3": (1, 2, 4, 5), "4": (4,), "5": (5,)}[str(ins.values[0])]
    levels = int(ins.values[1])  # type: ignore[call-overload]
    for n in selection:
        stack = rt.tasks[n - 1].stack
        del stack[len(stack) - levels if levels else 0 :]
    return _next(task)


def op_wai(rt: ClmRuntime, task: NcTask, ins: Instruction) -> int | None:
    if task.wait is None:
        task.wait = rt.cycle + rt.cycles_for_ms(rt.number(ins, 0))  # ss.sss: ms
    return _next(task) if rt.cycle >= task.wait else None


def op_txt(rt: ClmRuntime, task: NcTask, ins: Instruction) -> int | None:
    rt.show_text(str(ins.values[0]), str(ins.values[1]), task)
    return _next(task)


# -- axes -----------------------------------------------------------------------------------


def op_acc(rt: ClmRuntime, task: NcTask, ins: Instruction) -> int | None:
    axis = rt.axis(ins, 0)
    values = (rt.number(ins, 1), rt.number(ins, 2))
    axis.set_acceleration(*values)
    rt.restart.note(axis.number, "acc", values)  # part of the restart image
    return _next(task)


def op_fak(rt: ClmRuntime, task: NcTask, ins: Instruction) -> int | None:
    number = int(ins.values[0])  # type: ignore[call-overload]
    if number == 5:
        rt.master_factor = rt.number(ins, 1)  # master encoder 1's feed constant (part 3/4 use it)
    else:
        axis = rt.axis(ins, 0)
        axis.set_factor(rt.number(ins, 1))
        rt.restart.note(axis.number, "fak", rt.number(ins, 1))  # part of the restart image
    return _next(task)


def op_con(rt: ClmRuntime, task: NcTask, ins: Instruction) -> int | None:
    rt.axis(ins, 0).continuous(rt.state_value(ins, 1) == 1, rt.number(ins, 2))
    return _next(task)


def op_pbk(rt: ClmRuntime, task: NcTask, ins: Instruction) -> int | None:
    rt.axis(ins, 0).stop_motion()
    return _next(task)


def op_cpl(rt: ClmRuntime, task: NcTask, ins: Instruction) -> int | None:
    rt.axis(ins, 0).clear_lag()
    return _next(task)


def _position(absolute: bool, wait: bool) -> Handler:
    def handler(rt: ClmRuntime, task: NcTask, ins: Instruction) -> int | None:
        axis = rt.axis(ins, 0)
        if task.wait is None:
            if not rt.feed_allowed(axis):  # Interrupt input of the axis missing: wait (§5.5)
                return None
            rt.velocity.positioned(axis)  # VCC mode 0 measures from here (override decision 8)
            if axis.number == 1 and rt.registration.hooked:  # SRP measures / corrects, RMI offset
                rt.registration.position(axis, task, absolute, wait, rt.number(ins, 1), rt.number(ins, 2))
            elif absolute:
                axis.position_absolute(rt.number(ins, 1), rt.number(ins, 2))
            else:
                axis.position_incremental(rt.number(ins, 1), rt.number(ins, 2))
            rt.moved(axis, task)
            if not wait:
                return _next(task)
            task.wait = "moving"
            return None
        if not axis.in_position:
            return None
        if axis.number == 1 and rt.registration.hooked:
            return rt.registration.feed_done(task, _next(task))  # SRP: +5 when the window passed
        return _next(task)

    return handler


# -- velocity functions (state and decisions in override.py) -------------------------------------


def op_vcc(rt: ClmRuntime, task: NcTask, ins: Instruction) -> int | None:
    """VCC a P vvv m x: waits for the distance (mode 0) or the braking point (mode 1)."""
    axis = rt.axis(ins, 0)
    if task.wait is None:
        task.wait = rt.velocity.vcc_start(axis, rt.number(ins, 1), rt.number(ins, 2), int(str(ins.values[3])))
    return _next(task) if rt.velocity.vcc_poll(axis, task.wait) else None


def op_veo(rt: ClmRuntime, task: NcTask, ins: Instruction) -> int | None:
    """VEO a s x vvv f: one cycle (L2878)."""
    rt.velocity.set_veo(rt.axis(ins, 0), int(str(ins.values[1])), rt.number(ins, 3), str(ins.values[4]) == "1")
    return _next(task)


def op_aeo(rt: ClmRuntime, task: NcTask, ins: Instruction) -> int | None:
    """AEO a x y sss mmm: one cycle (L1446)."""
    rt.velocity.aeo(rt.axis(ins, 0), str(ins.values[1]) == "1", rt.number(ins, 3), rt.number(ins, 4))
    return _next(task)


# -- homing, rotary table, coordinates (state and decisions in axis.py 20-24, homing.py) ----------


def op_hom(rt: ClmRuntime, task: NcTask, ins: Instruction) -> int | None:
    """HOM a: starts the Ax24 homing and proceeds after one cycle; completion is polled with
    AKN on the Homed output (L2010-2026)."""
    rt.axis(ins, 0).start_homing()
    return _next(task)


def op_rtm(rt: ClmRuntime, task: NcTask, ins: Instruction) -> int | None:
    """RTM a m: 0 Ax05, 1 shortest, 2 programmed direction, > 2 no change (L2468-2486)."""
    rt.axis(ins, 0).set_table_mode(rt.number(ins, 1))
    return _next(task)


def op_sac(rt: ClmRuntime, task: NcTask, ins: Instruction) -> int | None:
    """SAC a m value: set / offset the coordinates per motion type (Figs. 5-22..5-24)."""
    rt.axis(ins, 0).set_counter(int(str(ins.values[1])), rt.number(ins, 2))
    return _next(task)


def op_fol(rt: ClmRuntime, task: NcTask, ins: Instruction) -> int | None:
    """FOL a on/off mode factor: one cycle; no function unless Ax00 mode 1/2 (slave.py 3)."""
    follower = rt.axis(ins, 0).follower
    if follower is not None:
        follower.fol(str(ins.values[1]) == "1", str(ins.values[2]) == "2", Fraction(rt.number(ins, 3), 1_000_000))
    return _next(task)


def op_rmi_noted(rt: ClmRuntime, task: NcTask, ins: Instruction) -> int | None:
    """RMI (registration.py); RMI 1 0 reached anew is where a restart sends Task 2 back to
    (restart decision 9)."""
    if task.wait is None and str(ins.values[1]) == "0":
        rt.restart.note_rmi(task)
    return op_rmi(rt, task, ins)


# -- flying cutoff (state and decisions in cutoff.py) ---------------------------------------------


def op_eos(rt: ClmRuntime, task: NcTask, ins: Instruction) -> int | None:
    """EOS: the synchronous phase ends, the carriage returns home (L1905-1911)."""
    if rt.cutoff is None:
        raise ClmError("0A", "EOS needs axis 1 in flying cutoff (A100 mode 5, L1911)")
    rt.cutoff.eos(task)
    return _next(task)


def _later(rt: ClmRuntime, task: NcTask, ins: Instruction) -> int | None:
    raise ClmError("0A", f"{ins.mnemonic} is not available in this version of axisline (it comes with {LATER[ins.mnemonic]})")


HANDLERS: dict[str, Handler] = {
    "ACC": op_acc, "AEA": op_aea, "AKN": op_akn, "AKP": op_akp, "APE": op_ape, "BAC": op_bac,
    "BCE": op_bce, "BIC": op_bic, "BIO": op_bio, "BPA": op_bpa, "CID": op_cid, "CIO": op_cio,
    "CLC": op_clc, "CON": op_con, "COU": op_cou, "CPJ": op_cpj, "CPL": op_cpl, "CPS": op_cps,
    "CST": op_cst, "CVT": op_cvt, "FAK": op_fak, "JMP": op_jmp, "JSR": op_jsr, "JST": op_jst,
    "JTK": op_jtk, "MAT": op_mat, "NOP": op_nop, "PBK": op_pbk, "RTS": op_rts, "SET": op_set,
    "TXT": op_txt, "WAI": op_wai, "VCC": op_vcc, "VEO": op_veo, "AEO": op_aeo,
    "POA": _position(True, False), "POI": _position(False, False),
    "PSA": _position(True, True), "PSI": _position(False, True),
    "HOM": op_hom, "FOL": op_fol, "RTM": op_rtm, "SAC": op_sac,
    "SRM": op_srm, "REP": op_rep, "SRP": op_srp, "RMI": op_rmi_noted, "RSV": op_rsv,
    "FUN": op_fun,  # feed length measurement (measuring_wheel.py decision 7)
    "LML": op_lml, "EOS": op_eos,  # flying cutoff (cutoff.py)
    "LMK": op_lmk, "LMR": op_lmr,  # raster-corrected lengths (cutoff_raster.py)
    "MLO": op_mlo, "MLT": op_mlt,  # material length (material_length.py)
    **dict.fromkeys(LATER, _later),
}
