"""CLM Logic Task (manual chapter 6, L2959-3170; spec §3.8; errata §1.2, §1.3, §1.18) and its image."""

from __future__ import annotations

import itertools

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from axisline.devices.clm.errors import FAULTS, SERIAL_ERRORS, ClmError, Finding
from axisline.devices.clm.image import LAYOUT, ProcessImage
from axisline.devices.clm.logic import (
    INSTRUCTIONS,
    LogicError,
    check_logic,
    compile_logic,
    logic_listing,
    logic_telegrams,
    parse_instruction,
    read_logic_text,
    scan_time_ms,
)
from axisline.devices.clm.operands import Operand, exists, parse_operand
from axisline.devices.clm.telegram import checksum


def bit(text: str) -> Operand:
    return parse_operand(text, bit=True, code="38")


def byte(text: str) -> Operand:
    return parse_operand(text, bit=False, code="38")


def program(*instructions: str):
    return compile_logic(list(instructions))


def errors_of(lines) -> list[Finding]:
    return [f for f in check_logic(lines) if f.is_error]


def known_code(code: str) -> bool:
    if code.startswith("X01:"):
        return int(code[4:]) in SERIAL_ERRORS
    return code in FAULTS


# -- the process image -----------------------------------------------------------------------------


def test_layout_follows_operand_ranges():
    """§9.1 (L5699-5760, Fig. 9-8 L6148-6155): every source's bytes, no more, no fewer."""
    assert LAYOUT[("M", 6)][1] == 40  # M6.00-M6.39
    assert LAYOUT[("I", 1)][1] == 11  # I1.00-I1.10
    assert LAYOUT[("Q", 2)][1] == 6  # Q2.00-Q2.05
    for (area, source), (_start, count) in LAYOUT.items():
        assert exists(Operand(area, source, count - 1))
        assert not exists(Operand(area, source, count))
    image = ProcessImage()
    with pytest.raises(ValueError):
        image.get(Operand("M", 6, 40))


def test_bits_and_bytes_share_the_image():
    """L5708-5716: I1.00.6 is bit 6 of byte I1.00 (bit 7 the most significant)."""
    image = ProcessImage()
    image.set(bit("I1.00.6"), 1)
    assert image.get(byte("I1.00")) == 0b0100_0000
    image.set(byte("M6.20"), 0b1000_0001)
    assert [image.get(bit(f"M6.20.{b}")) for b in range(8)] == [1, 0, 0, 0, 0, 0, 0, 1]
    copy = image.copy()
    copy.set(bit("M6.20.0"), 0)
    assert image.get(bit("M6.20.0")) == 1 and copy != image


def test_missing_bits_read_zero():
    """L1479: "For inputs not present in the hardware, the signal level is always set to 0"."""
    image = ProcessImage()
    image.set(byte("Q1.06"), 0xFF)  # Q1.06.0-Q1.06.2 exist (X22 pins 19-21)
    assert image.get(byte("Q1.06")) == 0b0000_0111
    image.set(byte("I0.02"), 0xFF)  # I0.02.0-I0.02.5
    assert image.get(byte("I0.02")) == 0b0011_1111
    assert ProcessImage().get(bit("I1.10.7")) == 0


def test_unset_operand_reads_zero():
    """Spec §3.3: a parameter's 00.00.0 means "not programmed"."""
    image = ProcessImage()
    unset = Operand("", 0, 0, 0)  # what parse_operand("00.00.0", unset_ok=True) stands for
    image.set(unset, 1)
    assert image.get(unset) == 0 and image == ProcessImage()


def test_set_refuses_values_that_do_not_fit():
    image = ProcessImage()
    with pytest.raises(ValueError):
        image.set(bit("M6.20.0"), 2)
    with pytest.raises(ValueError):
        image.set(byte("M6.20"), 256)
    with pytest.raises(ValueError):
        image.set(Operand("Q", 1, 6, 5), 1)  # Q1.06.5 does not exist


# -- instructions and their truth tables -----------------------------------------------------------

BOOL1 = (1, 0, 1, 0)
BOOL2 = (1, 1, 0, 0)
TABLES = {
    # AND/ANDN: the figures at L3060-3070 lost their values; from the definitions L3053-3054
    "AND": (1, 0, 0, 0),
    "ANDN": (0, 0, 1, 0),
    "OR": (1, 1, 1, 0),  # L3085
    "ORN": (1, 0, 1, 1),  # L3092
    "XOR": (0, 1, 1, 0),  # L3110
    "XORN": (1, 0, 0, 1),  # L3117
}


def test_the_25_instructions():
    """Fig. 6-1 (L3011-3021) with §6.4-6.6: 25 instructions."""
    assert len(INSTRUCTIONS) == len(set(INSTRUCTIONS)) == 25


@pytest.mark.parametrize("logic", sorted(TABLES))
def test_truth_tables(logic):
    """L3053-3117: bool3 = bool1 <logic> bool2 for bool1 = 1 0 1 0, bool2 = 1 1 0 0."""
    lt = program("LD M6.20.0", f"{logic} M6.20.1", "ST Q1.00.0", "END")
    image = ProcessImage()
    results = []
    for b1, b2 in zip(BOOL1, BOOL2, strict=True):
        image.set(bit("M6.20.0"), b1)
        image.set(bit("M6.20.1"), b2)
        lt.scan(image)
        results.append(image.get(bit("Q1.00.0")))
    assert tuple(results) == TABLES[logic]


@pytest.mark.parametrize("logic", sorted(TABLES))
def test_byte_operands_work_on_all_8_bits(logic):
    """Errata §1.18, L3051/L3074/L3099 "functions bit-by-bit": the four columns of each table
    as bits 0-3 of one byte give the whole table in one instruction; STN negates bit by bit
    (L3036)."""
    column_bits = lambda values: sum(v << i for i, v in enumerate(values))  # noqa: E731
    lt = program("LD M6.20", f"{logic} M6.21", "ST M5.00", "STN Q2.02", "END")
    image = ProcessImage()
    image.set(byte("M6.20"), column_bits(BOOL1))
    image.set(byte("M6.21"), column_bits(BOOL2))
    lt.scan(image)
    low = column_bits(TABLES[logic])
    assert image.get(byte("M5.00")) & 0x0F == low
    assert image.get(byte("Q2.02")) == image.get(byte("M5.00")) ^ 0xFF


def test_byte_load_negated_fills_missing_bits():
    """L1479 + L3034 LDN: the 5 missing bits of Q1.06 read 0, so LDN gives them 1."""
    lt = program("LDN Q1.06", "ST M6.30", "END")
    image = ProcessImage()
    lt.scan(image)
    assert image.get(byte("M6.30")) == 0xFF


@pytest.mark.parametrize(
    ("instruction", "before", "value", "after"),
    [
        ("SET", 0, 0, 1), ("RES", 1, 1, 0),
        ("SETC", 0, 1, 1), ("SETC", 0, 0, 0), ("SETCN", 0, 0, 1), ("SETCN", 0, 1, 0),
        ("RESC", 1, 1, 0), ("RESC", 1, 0, 1), ("RESCN", 1, 0, 0), ("RESCN", 1, 1, 1),
    ],
)
def test_set_and_reset(instruction, before, value, after):
    """L3040-3045: SET/RES unconditional, ...C if the previous result is TRUE, ...CN if FALSE;
    "otherwise no change"."""
    lt = program("LD M6.20.0", f"{instruction} Q1.00.0", "END")
    image = ProcessImage()
    image.set(bit("Q1.00.0"), before)
    image.set(bit("M6.20.0"), value)
    lt.scan(image)
    assert image.get(bit("Q1.00.0")) == after


def test_set_and_reset_take_bits_only():
    """L3040-3045 "Setting the bit operand": a byte is refused (decision 1)."""
    for mnemonic in ("SET", "SETC", "SETCN", "RES", "RESC", "RESCN"):
        (finding,) = errors_of(["LD M6.20.0", f"{mnemonic} M6.21", "END"])
        assert (finding.where, finding.code) == ("LT0001", "38") and "bit operand" in finding.text


def test_width_mixing_is_fault_38():
    """Decision 1: one chain keeps the width of its LD (L3051 "bit-by-bit")."""
    cases = {
        ("LD M6.20", "AND M6.21.0", "END"): "LT0001",
        ("LD M6.20.0", "ST M6.21", "END"): "LT0001",
        ("LD M6.20", "SETC M6.21.0", "END"): "LT0001",
        ("LD M6.20.0", "AND(", "LD M6.21", ")", "END"): "LT0003",
    }
    for lines, where in cases.items():
        (finding,) = errors_of(list(lines))
        assert (finding.where, finding.code) == (where, "38")


# -- the manual's examples over several scans ------------------------------------------------------

EDGE_IN, EDGE_OUT = bit("M6.20.0"), bit("M6.20.1")
INPUTS = (0, 1, 1, 1, 0, 0, 1, 0, 1, 1)


def run_scans(lt, inputs):
    image, out = ProcessImage(), []
    for value in inputs:
        image.set(EDGE_IN, value)
        lt.scan(image)
        out.append(image.get(EDGE_OUT))
    return out


def test_positive_edge_gives_one_scan_pulse():
    """L3130-3148 "Spurious Pulse Positive Starting Edge": M6.20.1 is 1 for exactly the scan
    in which M6.20.0 rises (decision 7)."""
    text = "LD   M6.20.0\nANDN M6.20.4\nST   M6.20.1\nLD   M6.20.0\nST   M6.20.4\nEND\n"
    lines, findings = read_logic_text(text, "L3142")
    assert findings == []
    out = run_scans(compile_logic(lines), INPUTS)
    assert out == [int(now and not before) for before, now in zip((0,) + INPUTS, INPUTS)]
    assert out == [0, 1, 0, 0, 0, 0, 1, 0, 1, 0]


def test_negative_edge_gives_one_scan_pulse():
    """L3150-3168 "Spurious Pulse Negative Starting Edge" (as printed, M6.20.4 holds the
    negated input): M6.20.1 is 1 for exactly the scan in which M6.20.0 falls."""
    text = "LDN  M6.20.0\nANDN M6.20.4\nST   M6.20.1\nLDN  M6.20.0\nST   M6.20.4\nEND\n"
    lines, _ = read_logic_text(text, "L3162")
    lt = compile_logic(lines)
    image = ProcessImage()
    image.set(bit("M6.20.4"), 1)  # the flag after a scan with the input at 0, i.e. steady state
    out = []
    for value in INPUTS:
        image.set(EDGE_IN, value)
        lt.scan(image)
        out.append(image.get(EDGE_OUT))
    assert out == [int(before and not now) for before, now in zip((0,) + INPUTS, INPUTS)]
    assert out == [0, 0, 0, 0, 1, 0, 0, 1, 0, 0]


def test_later_instructions_see_earlier_writes():
    """Decision 7: a marker written at LT0001 is read with its new value at LT0002 of the same
    scan (L5728: markers are processed at the start of the Logic Task; errata §3.5)."""
    lt = program("LD I1.00.0", "ST M6.21.0", "LD M6.21.0", "ST Q1.00.0", "END")
    image = ProcessImage()
    image.set(bit("I1.00.0"), 1)
    lt.scan(image)
    assert image.get(bit("Q1.00.0")) == 1


# -- parentheses -----------------------------------------------------------------------------------

PAREN = {"AND(": lambda x, t: x & t, "ANDN(": lambda x, t: x & (1 - t), "OR(": lambda x, t: x | t,
         "ORN(": lambda x, t: x | (1 - t), "XOR(": lambda x, t: x ^ t, "XORN(": lambda x, t: x ^ (1 - t)}


@pytest.mark.parametrize("opener", sorted(PAREN))
def test_parentheses_with_and_without_operand(opener):
    """L3055-3104 "... with the (negated) logical value of the following term"; decision 2:
    ``AND(`` alone then ``LD b``, or ``AND( b``, both mean a <op> (b OR c)."""
    bare = program("LD M6.20.0", opener, "LD M6.20.1", "OR M6.20.2", ")", "ST Q1.00.0", "END")
    loaded = program("LD M6.20.0", f"{opener} M6.20.1", "OR M6.20.2", ")", "ST Q1.00.0", "END")
    for a, b, c in itertools.product((0, 1), repeat=3):
        for lt in (bare, loaded):
            image = ProcessImage()
            for name, v in zip(("M6.20.0", "M6.20.1", "M6.20.2"), (a, b, c), strict=True):
                image.set(bit(name), v)
            lt.scan(image)
            assert image.get(bit("Q1.00.0")) == PAREN[opener](a, b | c), (opener, a, b, c)


def test_deep_nesting_is_accepted():
    """Decision 3: no depth limit but the memory (L8656 names only wrong positioning)."""
    depth = 300
    lines = ["LD M6.20.0"] + ["AND( M6.20.1"] * depth + [")"] * depth + ["ST Q1.00.0", "END"]
    lt = compile_logic(lines)
    image = ProcessImage()
    image.set(bit("M6.20.0"), 1)
    image.set(bit("M6.20.1"), 1)
    lt.scan(image)
    assert image.get(bit("Q1.00.0")) == 1
    image.set(bit("M6.20.1"), 0)
    lt.scan(image)
    assert image.get(bit("Q1.00.0")) == 0


def _expression(draw, depth):
    """A random term over M6.20.0-3 as (IL lines, evaluator)."""
    name = f"M6.20.{draw(st.integers(0, 3))}"
    negate = draw(st.booleans())
    lines = [f"{'LDN' if negate else 'LD'} {name}"]
    parts = [lambda v, n=name, neg=negate: v[n] ^ neg]
    ops = []
    for _ in range(draw(st.integers(0, 3))):
        logic = draw(st.sampled_from(sorted(TABLES)))
        if depth > 0 and draw(st.booleans()):
            inner_lines, inner = _expression(draw, depth - 1)
            if draw(st.booleans()) and inner_lines[0].startswith("LD "):  # AND( x form
                lines += [f"{logic}( {inner_lines[0][3:]}", *inner_lines[1:], ")"]
            else:
                lines += [f"{logic}(", *inner_lines, ")"]
            parts.append(inner)
        else:
            other = f"M6.20.{draw(st.integers(0, 3))}"
            lines.append(f"{logic} {other}")
            parts.append(lambda v, n=other: v[n])
        ops.append(logic)

    def evaluate(v, parts=parts, ops=ops):
        acc = parts[0](v)
        for logic, part in zip(ops, parts[1:], strict=True):
            acc = {"AND": lambda x, y: x & y, "OR": lambda x, y: x | y, "XOR": lambda x, y: x ^ y}[logic.removesuffix("N")](
                acc, part(v) ^ logic.endswith("N"))
        return acc

    return lines, evaluate


@st.composite
def expressions(draw):
    return _expression(draw, 3)


@settings(max_examples=150, deadline=None)
@given(expressions())
def test_random_terms_evaluate_like_boolean_algebra(expression):
    """L3053-3104: nested terms evaluate as the logic they spell, for every input."""
    lines, evaluate = expression
    lt = compile_logic(lines + ["ST Q1.00.0", "END"])
    for values in itertools.product((0, 1), repeat=4):
        named = {f"M6.20.{i}": v for i, v in enumerate(values)}
        image = ProcessImage()
        for name, v in named.items():
            image.set(bit(name), v)
        lt.scan(image)
        assert image.get(bit("Q1.00.0")) == evaluate(named)


# -- fault 38 --------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("lines", "where", "says"),
    [
        # L8653 "An invalid command is programmed in the Logic Task"
        (["LD M6.20.0", "ADD M6.20.1", "END"], "LT0001", "not a Logic Task command"),
        (["LD M6.20.0", "LD", "END"], "LT0001", "needs an operand"),
        (["LD M6.20.0", "NOP M6.20.0", "END"], "LT0001", "takes no operand"),
        # L8654 "An invalid input, output or marker number ..."
        (["LD M6.40.0", "END"], "LT0000", "does not exist"),
        (["LD I0.02.6", "END"], "LT0000", "does not exist"),
        (["LD M7.00.0", "END"], "LT0000", "does not exist"),
        (["LD M6.20.9", "END"], "LT0000", "does not exist"),
        (["LD M6.20.0.1", "END"], "LT0000", "not a byte operand"),
        # L3025: loads and logic read M0, M1, M4-M6, Q0-Q2, I0-I2
        (["LD M2.00.0", "END"], "LT0000", "may not be read"),
        (["LD M6.20.0", "OR M3.00.0", "END"], "LT0001", "may not be read"),
        # L3027: store, set, reset write M5, M6, Q1, Q2.02-Q2.05
        (["LD M6.20.0", "ST I1.00.0", "END"], "LT0001", "may not be written"),
        (["LD M6.20.0", "ST Q0.00.0", "END"], "LT0001", "may not be written"),
        (["SET Q2.01.0", "END"], "LT0000", "may not be written"),
        (["RES M4.00.0", "END"], "LT0000", "may not be written"),
        (["LD M6.20.0", "STN M1.00.0", "END"], "LT0001", "may not be written"),
        # L8655 "No END command is programmed"
        (["LD M6.20.0", "ST M6.20.1"], "LT0002", "no END"),
        # L8656 "The positioning of the parentheses is wrong"
        (["LD M6.20.0", ")", "ST M6.20.1", "END"], "LT0001", "without an open parenthesis"),
        (["LD M6.20.0", "AND(", "LD M6.20.1", "ST M6.20.2", "END"], "LT0001", "not closed"),
        (["LD M6.20.0", "AND(", ")", "ST M6.20.2", "END"], "LT0002", "has no value"),
        (["LD M6.20.0", "AND(", "END", ")"], "LT0001", "not closed"),
        # decision 4: the current value before a load
        (["AND M6.20.0", "END"], "LT0000", "loaded none"),
    ],
)
def test_fault_38_causes_name_their_instruction(lines, where, says):
    """L8651-8656: fault 38 "Logic Prg. Error" with the LT instruction (F1: "LT Instr", L8097)."""
    errors = errors_of(lines)
    assert [(f.where, f.code) for f in errors] == [(where, "38")], errors
    assert says in errors[0].text and errors[0].text.startswith("Logic Prg. Error")
    with pytest.raises(LogicError) as raised:
        compile_logic(lines)
    assert isinstance(raised.value, ClmError) and raised.value.where == where


def test_compile_collects_all_errors():
    """L2961: a program with any error does not start; every error is reported."""
    lines = {0: "LD M2.00.0", 1: "ST Q0.00.0", 2: "FOO", 3: ")"}
    with pytest.raises(LogicError) as raised:
        compile_logic(lines)
    assert [e.where for e in raised.value.errors] == ["LT0000", "LT0001", "LT0002", "LT0003", "LT0004"]
    assert {e.code for e in raised.value.errors} == {"38"}
    assert "and 4 more" in raised.value.detail


def test_value_used_before_load_is_fault_38():
    """Decision 4: L3053 "current value" presupposes a load; SET/RES need none."""
    assert errors_of(["SET Q1.00.0", "RES Q1.00.1", "END"]) == []
    for first in ("ST Q1.00.0", "ANDN M6.20.0", "SETC Q1.00.0", "AND(", "OR( M6.20.0"):
        lines = [first, "END"] if "(" not in first else [first, ")", "END"] if " " in first else [first, "LD M6.20.1", ")", "END"]
        (finding,) = errors_of(lines)
        assert finding.where == "LT0000" and "loaded none" in finding.text
    (finding,) = errors_of(["LD M6.20.0", "AND(", "OR M6.20.1", ")", "END"])
    assert finding.where == "LT0002" and "term opened at LT0001" in finding.text


def test_refused_parenthesis_keeps_its_partner_quiet():
    """One bad ``AND(`` is one fault, not also a fault at its ``)``."""
    errors = errors_of(["LD M6.20.0", "AND( M2.00.0", ")", "ST Q1.00.0", "END"])
    assert [f.where for f in errors] == ["LT0001"]


def test_after_end_is_not_compiled():
    """Decision 5 (L2995, L7453-7462): only 0000 up to the first END is compiled."""
    lines = {0: "LD M6.20.0", 1: "ST Q1.00.0", 2: "END", 5: ")", 6: "garbage"}
    lt = compile_logic(lines)
    assert lt.end == 2 and lt.assignments == 3 and sorted(lt.instructions) == [0, 1, 2]
    (warning,) = check_logic(lines)
    assert warning.severity == "warning" and warning.where == "LT0005" and "not compiled" in warning.text


def test_end_at_0000_deactivates():
    """L2997 "To deactivate the Logic Task, an END command must be programmed into program
    instruction 0000"; L7462 !sCNOPLT writes END there."""
    lt = compile_logic({0: "END", 1: "LD M6.20.0", 2: "ST Q1.00.0"})
    assert not lt.active
    image = ProcessImage()
    image.set(bit("M6.20.0"), 1)
    lt.scan(image)
    assert image.get(bit("Q1.00.0")) == 0
    assert compile_logic(["LD M6.20.0", "ST Q1.00.0", "END"]).active


def test_unlisted_instructions_are_nop():
    """L2961 1000 lines; what is not given is NOP (an empty line too)."""
    lt = compile_logic({0: "LD M6.20.0", 7: "", 500: "ST Q1.00.0", 999: "END"})
    assert lt.assignments == 1000 and lt.scan_time_ms == 1000.0
    image = ProcessImage()
    image.set(bit("M6.20.0"), 1)
    lt.scan(image)
    assert image.get(bit("Q1.00.0")) == 1


def test_instruction_numbers_outside_the_memory():
    """L2961: 0000-0999."""
    (finding,) = errors_of({0: "END", 1000: "NOP"})
    assert finding.code == "38" and "0000-0999" in finding.text
    full = errors_of(["NOP"] * 1000 + ["END"])  # END at 1000 is outside, so there is none
    assert [(f.where, f.code) for f in full] == [("LT1000", "38"), ("LT0999", "38")]


def test_scan_time():
    """Decision 8: L2963 "1000 assignments/sec ... minimum cycle time of 4 ms" (errata §1.3)."""
    assert scan_time_ms(1) == scan_time_ms(4) == 4.0
    assert scan_time_ms(250) == 250.0
    assert program("LD M6.20.0", "ST M6.20.1", "END").scan_time_ms == 4.0
    assert compile_logic({0: "LD M6.20.0", 1: "ST M6.20.1", 99: "END"}).scan_time_ms == 100.0


def test_writes_lists_owned_outputs():
    """L5724: an output named in the Logic Task belongs to it."""
    lt = program("LD M6.20.0", "ST Q1.00.0", "SET Q1.00.0", "RESC M5.00.1", "END")
    assert [str(op) for op in lt.writes] == ["Q1.00.0", "M5.00.1"]


# -- listing files ---------------------------------------------------------------------------------

EDGE = {0: "LD M6.20.0", 1: "ANDN M6.20.4", 2: "ST M6.20.1", 3: "LD M6.20.0", 4: "ST M6.20.4", 5: "END"}


def test_listing_round_trip():
    """Decision 11: a listing names every instruction that is not NOP."""
    lines = dict(EDGE) | {7: "NOP", 8: "XORN( Q2.05.7", 9: ")"}
    text = logic_listing(lines)
    assert text.splitlines()[0] == "0000\tLD\tM6.20.0"
    assert "NOP" not in text
    again, findings = read_logic_text(text, "rt")
    assert findings == []
    assert again == {n: t for n, t in lines.items() if t != "NOP"}


def test_listing_forms_read():
    """The manual's listing style (``0000<tab>POI<tab>... - comment``), comments, unnumbered
    lines as printed at L3142-3146, lower case; decision 12 for a number given twice."""
    text = (
        "; edge detection, L3142\n"
        "# a comment line\n"
        "0000\tLD\tM6.20.0\t- the input\n"
        "0001  andn  m6.20.4   ; not yet seen\n"
        "ST   M6.20.1\n"
        "0003 LD M6.20.0\n"
        "0004 ST M6.20.4\n"
        "0004 ST M6.20.4\n"
        "\n"
        "0005 AND(M6.20.0\n"
        "0006 )\n"
        "END\n"
    )
    lines, findings = read_logic_text(text, "edge.lt")
    assert lines == EDGE | {5: "AND( M6.20.0", 6: ")", 7: "END"}
    (warning,) = findings
    assert (warning.where, warning.severity, warning.source) == ("LT0004", "warning", "edge.lt:8")


def test_listing_lines_refused_like_the_keypad():
    """L2993: an instruction with an error is not accepted; one finding per line, the rest is read."""
    text = "0000 LD M6.20.0\n0001 ST Q0.00.0\n0002 LX M6.20.0\n1000 END\n0003 END\n12345678 NOP\n??\n"
    lines, findings = read_logic_text(text, "bad.lt")
    assert lines == {0: "LD M6.20.0", 3: "END"}
    assert [(f.where, f.code, f.source) for f in findings] == [
        ("LT0001", "38", "bad.lt:2"),
        ("LT0002", "38", "bad.lt:3"),
        ("line 4", "38", "bad.lt:4"),
        ("line 6", "38", "bad.lt:6"),
        ("line 7", "38", "bad.lt:7"),
    ]


# -- telegrams -------------------------------------------------------------------------------------


def test_telegram_round_trip():
    """Decisions 10, 11: ``#sPnnnn_<instruction>_$hh``, 0000 up to the last, gaps as NOP."""
    lines = {0: "LD M6.20.0", 1: "ANDN( M6.20.4", 2: ")", 3: "ST Q2.05", 5: "END"}
    with pytest.raises(ClmError):
        compile_logic(lines)  # ST of a byte after a bit: the telegrams do not judge the program
    telegrams = logic_telegrams(lines)
    assert telegrams[0] == f"# P0000 LD M6.20.0 ${checksum('# P0000 LD M6.20.0 ')}\r\n"
    assert telegrams[4].startswith("# P0004 NOP $") and len(telegrams) == 6
    again, findings = read_logic_text("".join(telegrams), "rt")
    assert findings == []
    assert again == lines | {4: "NOP"}
    station = logic_telegrams(EDGE, station=12)
    assert station[0].startswith("#CP0000 LD M6.20.0 $")
    assert read_logic_text("".join(station))[0] == EDGE


def test_telegram_forms_read():
    """L6712-6735: the manual's ``_`` notation, a blank before the number (``?sP_xxxx``), no
    checksum, the read-back ``Psxxxx_dddddddd_$hh``; at most 16 characters of instruction."""
    body = "# P_0000_LD_M6.20.0_".replace("_", " ")
    manual = "#_P0000_LD_M6.20.0_$" + checksum("# P0000 LD M6.20.0 ")
    blank = f"{body}${checksum(body)}"
    reply = "P 0001 ANDN M6.20.4 $" + checksum("P 0001 ANDN M6.20.4 ")
    text = "\r\n".join([manual, blank, reply, "# P0002 ST M6.20.1", "# P0003 XORN(  M6.20.0 "]) + "\r\n"
    lines, findings = read_logic_text(text, "t")
    assert findings == []
    assert lines == {0: "LD M6.20.0", 1: "ANDN M6.20.4", 2: "ST M6.20.1", 3: "XORN( M6.20.0"}


@pytest.mark.parametrize(
    ("line", "code"),
    [
        ("# P0000 LD M2.00.0 ", "X01:25"),  # L6823 "Invalid operand in the Logic Task command"
        ("# P0000 ST I1.00.0 ", "X01:25"),
        ("# P0000 SET M6.20 ", "X01:25"),
        ("# P0000 LD M6.40.0 ", "X01:25"),
        ("# P0000 LOAD M6.20.0 ", "X01:13"),  # "An invalid command was transmitted"
        ("# P1000 END ", "X01:12"),  # "Block # too large"
        ("# P00x0 END ", "X01:01"),  # "not a decimal value"
        ("# P0000 ", "X01:13"),
        ("# P0000 LD                M6.20.0 ", "X01:02"),  # more than 16 characters
        ("# N0000 NOP ", "X01:02"),  # an NC instruction in a Logic Task file
        ("# P0000 END $00", "X01:04"),  # L6470-6520 checksum
    ],
)
def test_telegram_errors_carry_status_01_codes(line, code):
    """§9.2 Status 01 (L6796-6823): the CLM refuses a bad telegram and keeps its memory."""
    lines, findings = read_logic_text(line + "\r\n", "t")
    assert lines == {}
    (finding,) = findings
    assert finding.code == code and finding.source == "t:1"


def test_parse_instruction_codes():
    """Fault 38 in a program, Status 01 errors 13/25 over the serial line (L6819, L6823)."""
    assert str(parse_instruction("  xorn (   q1.06.2 ", 3)) == "XORN( Q1.06.2"
    with pytest.raises(ClmError) as raised:
        parse_instruction("LD M2.00.0", 7)
    assert (raised.value.code, raised.value.where) == ("38", "LT0007")
    with pytest.raises(ClmError) as raised:
        parse_instruction("LD M2.00.0", 7, serial=True)
    assert raised.value.code == "X01:25"


# -- fuzzing ---------------------------------------------------------------------------------------

WORDS = st.sampled_from([*INSTRUCTIONS, "M6.20.0", "M6.20", "Q1.00.0", "I0.02.6", "M2.00.0", "(", ")", "#", "P",
                         "$", "_", "-", ";", " ", "\t", "\r\n", "\n", "0000", "0999", "1000", "# P", "P 0001", "ü"])
TEXTS = st.one_of(st.text(max_size=200), st.lists(WORDS, max_size=40).map("".join))


@settings(max_examples=400, deadline=None)
@given(TEXTS)
def test_read_logic_text_never_raises(text):
    """Any text gives instructions and findings, never an exception; every finding has a CLM code."""
    lines, findings = read_logic_text(text, "fuzz")
    assert all(0 <= n <= 999 for n in lines)
    assert all(known_code(f.code) for f in findings)
    for n, instruction in lines.items():
        assert str(parse_instruction(instruction, n)) == instruction


@settings(max_examples=400, deadline=None)
@given(st.dictionaries(st.integers(-5, 1005), st.one_of(st.text(max_size=30), st.lists(WORDS, max_size=4).map(" ".join)), max_size=12))
def test_compile_logic_raises_only_clm_errors(lines):
    """Any program compiles or is refused with fault 38; the findings agree with the outcome."""
    try:
        lt = compile_logic(lines)
    except ClmError as error:
        assert isinstance(error, LogicError) and all(e.code == "38" for e in error.errors)
        assert any(f.is_error for f in check_logic(lines))
    else:
        assert not any(f.is_error for f in check_logic(lines))
        lt.scan(ProcessImage())
