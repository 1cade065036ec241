"""The flying cutoff's input functions on the simulated plant (manual §7.12 L3952-4022, A133-A137,
A142): immediate cut, manual cut vector, cut inhibit, crop cut, reverse inhibit, rapid stop,
maximum stroke, indexing. Decisions: src/axisline/devices/clm/cutoff_inputs.py."""

from __future__ import annotations

import pytest

from axisline.devices.clm.cutoff import HELD, SYNC
from axisline.devices.clm.operands import parse_operand
from axisline.machine import Machine

from .clmrig import Rig
from .test_cutoff import CONSTANT_500, COUNTS, PROGRAM, machine, run_cuts

LONG = PROGRAM.replace("LML 1 001000.000", "LML 1 002000.000")  # product 1: 2000 mm too


def pulse(m: Machine, name: str, cycles: int = 5) -> None:
    """An unwired CLM input high for `cycles` NC cycles (a pulse), then low."""
    op = parse_operand(name, bit=True)
    image = m.device.memory.image
    image.set(op, 1)
    for _ in range(cycles):
        m.scheduler.run_cycle()
        image.set(op, 1)
    image.set(op, 0)


def run_s(m: Machine, seconds: float) -> None:
    for _ in range(round(seconds / m.period)):
        m.scheduler.run_cycle()


def test_immediate_cut_cuts_at_once(tmp_path):
    """Decision 1 (L3954): 2000 mm pieces; an Immediate Cut pulse at 1.0 s (the carriage at home,
    LML waiting) cuts at once: the first piece is the material fed until then (the strip ramps
    to 500 mm/s at 500 mm/s^2: 250 mm) plus the ramp's stroke (12.5 mm), and the next 2000 mm
    count from that cut."""
    m = machine(tmp_path, LONG, {"A134": "I1.00.1 0100 0"}, profile=CONSTANT_500)
    run_s(m, 1.0)
    assert m.device.meter.records == []
    pulse(m, "I1.00.1")
    cuts = run_cuts(m, 2)
    assert cuts[0]["time"] < 1.3
    assert cuts[0]["actual_length"] == pytest.approx(250.0 + 12.5, abs=5.0)
    assert cuts[1]["target_length"] == 2000.0 and abs(cuts[1]["error_counts"]) <= 2.0


def test_manual_cut_vector_runs_in_manual():
    """Decision 2 (L3958): in Manual the Immediate Cut input starts the program at A134's start
    instruction (0100), which ends with RTS; Automatic waits for it."""
    r = Rig("0000 NOP\n0100 AEA Q1.00.3 1\n0101 WAI 00.010\n0102 RTS\n",
            params={"A100": "0 0 0 5 1", "A111": "01.00 1", "A134": "I1.00.1 0100 0"}, mode="manual")
    r.run(2)
    r.set("I1.00.1", 1)
    r.run(2)
    r.set("I1.00.1", 0)
    assert r.bit("Q1.00.3") == 1 and r.rt.modes.manual_vector
    r.run(20)
    assert not r.rt.modes.manual_vector


def test_cut_inhibit_until_an_immediate_cut(tmp_path):
    """Decision 3 (L3962-3966, L3990): a Cut Inhibit pulse suppresses the synchronization (no cut
    for 4 s of 1000 mm pieces at 500 mm/s), sets the A133 output and stops the product length
    counter; an Immediate Cut pulse cuts at once and ends it."""
    m = machine(tmp_path, params={"A133": "I1.00.2 Q1.00.4", "A134": "I1.00.1 0100 0"}, profile=CONSTANT_500)
    run_s(m, 0.5)
    pulse(m, "I1.00.2")
    product = m.device.rt.cutoff.product_length
    run_s(m, 4.0)
    c = m.device.rt.cutoff
    assert m.device.meter.records == [] and c.inhibited
    assert m.device.memory.image.get(parse_operand("Q1.00.4", bit=True)) == 1
    assert c.product_length == product and c.material_length > product + 1900
    pulse(m, "I1.00.1")
    cuts = run_cuts(m, 2)
    assert not c.inhibited and cuts[0]["time"] < 5.0
    assert abs(cuts[1]["error_counts"]) <= 2.0


def test_crop_cut_sets_the_length(tmp_path):
    """Decision 4 (L4016): a Crop Cut pulse with the carriage at home makes the waiting length
    A142's 300 mm once; then the program's 1000 mm again."""
    m = machine(tmp_path, params={"A142": "0300.00 I1.00.3"}, profile=CONSTANT_500)
    run_s(m, 0.1)
    pulse(m, "I1.00.3")
    cuts = run_cuts(m, 2)
    assert [c["target_length"] for c in cuts] == [300.0, 1000.0]
    assert max(abs(c["error_counts"]) for c in cuts) <= 2.0


def test_reverse_inhibit_holds_the_return(tmp_path):
    """Decision 5 (L3998): with A135 set, after EOS the carriage brakes to a stop and stays out
    (1 s); a pulse on the input sends it home, and the next piece is still 1000 mm."""
    m = machine(tmp_path, params={"A135": "I1.00.5 00000"}, profile='[\n  { time = 0.0, speed = 200.0, acceleration = 500.0 },\n]')
    run_cuts(m, 1)
    c = m.device.rt.cutoff
    while c.state != HELD:
        m.scheduler.run_cycle()
    run_s(m, 1.0)
    clm = c.axis
    assert c.state == HELD and clm.motion_done and clm.actual_position > 200.0
    pulse(m, "I1.00.5")
    cuts = run_cuts(m, 2)
    assert abs(cuts[1]["error_counts"]) <= 2.0


def test_rapid_stop_runs_its_program_then_3b(tmp_path):
    """Decision 6 (L4002-4006): Rapid Stop while synchronous runs the program at A136's start
    (1100: SET V700, EOS) with the gear kept, then error 3B; at home it is 3B at once."""
    program = PROGRAM + "1100 SET V700 = +00000001.000000\n1101 EOS\n"
    m = machine(tmp_path, program, {"A136": "I1.00.6 1100"}, profile=CONSTANT_500)
    c = None
    while c is None or c.state != SYNC:
        m.scheduler.run_cycle()
        c = m.device.rt.cutoff
    pulse(m, "I1.00.6", 1)
    run_s(m, 0.02)
    error = m.device.rt.modes.fault_error
    assert error is not None and error.code == "3B"
    assert m.device.rt.memory.variables[700] == 1_000_000  # the program ran
    assert m.device.meter.records == []  # no cut
    m2 = machine(tmp_path, program, {"A136": "I1.00.6 1100"}, profile=CONSTANT_500)
    run_s(m2, 0.5)
    pulse(m2, "I1.00.6", 1)
    assert m2.device.rt.modes.fault_error.code == "3B"
    assert m2.device.rt.memory.variables[700] == 0


def test_maximum_stroke_is_3c(tmp_path):
    """Decision 7 (L4010-4012): A137 stroke 250 with A104 = 400: synchronous beyond 150 mm the
    processing program (waiting for 200 mm) is dropped for the one at 1100, and its EOS is 3C."""
    program = PROGRAM + "1100 SET V700 = +00000001.000000\n1101 EOS\n"
    m = machine(tmp_path, program, {"A137": "00250 1100"}, profile=CONSTANT_500)
    for _ in range(round(4.0 / m.period)):
        m.scheduler.run_cycle()
        if m.device.rt.modes.fault_error is not None:
            break
    error = m.device.rt.modes.fault_error
    assert error is not None and error.code == "3C"
    assert m.device.rt.memory.variables[700] == 1_000_000
    assert 150.0 < m.device.rt.axes[1].command_position < 160.0  # a few cycles on, not the 200 mm of the program


MANUAL_CUT = """0000 NOP
0001 LML 1 000500.000
0002 JSR 1000
0003 JMP 0000
0100 FUN 2 2 2 2 2 2 1
0101 RTS
1000 AEA Q1.00.0 1
1001 AKN I1.00.0 1
1002 AEA Q1.00.0 0
1003 CPJ V100 < +00050.000 0000.00 1003
1004 EOS
1005 RTS
"""


@pytest.mark.parametrize("indexing", ["1", "0"])
def test_indexing_counts_from_the_manual_cut(tmp_path, indexing):
    """Decision 8, the manual's example scaled by 1/10 (L3981-3987: "A manual cut is executed in
    'Manual' Mode, with a carriage position of +1000mm ... a production length of 5000mm ... If
    indexing is activated ... the first cut piece has a length of 5000mm. If indexing is not
    activated, the first piece has a length of 6000mm"): the strip stands, a manual cut (the
    manual cut vector at 0100 with FUN's material channel) at carriage +100 mm, the carriage
    jogged home, Automatic, LML 500: the first cut is 500 mm from the manual cut with indexing,
    600 mm without (500 from the point under the tool at home, 100 mm and the home window on)."""
    m = machine(tmp_path, MANUAL_CUT, {"A134": f"I1.00.1 0100 {indexing}", "A127": "00.00.0 0005.000"},
                profile='[\n  { time = 3.0, speed = 300.0, acceleration = 1000.0 },\n]', auto_io=True)
    m.io.set_input("auto", False)
    run_s(m, 0.3)
    image = m.device.memory.image
    jog_plus, jog_minus = parse_operand("I0.01.0", bit=True), parse_operand("I0.01.1", bit=True)
    clm = m.device.rt.axes[1]
    image.set(jog_plus, 1)
    while clm.actual_position < 100.0:
        m.scheduler.run_cycle()
    image.set(jog_plus, 0)
    run_s(m, 0.5)
    cutoff = m.device.rt.cutoff
    manual_cut = float(cutoff.material_point())  # the point the manual cut is made at
    pulse(m, "I1.00.1")
    run_s(m, 0.1)
    image.set(jog_minus, 1)
    while clm.actual_position > 3.0:
        m.scheduler.run_cycle()
    image.set(jog_minus, 0)
    run_s(m, 0.5)
    at_home = float(cutoff.material_point())
    assert at_home - manual_cut == pytest.approx(100.0, abs=5.0)
    m.io.set_input("auto", True)
    run_s(m, 0.01)
    assert m.device.rt.modes.fault_error is None
    while cutoff.state != SYNC:
        m.scheduler.run_cycle()
        assert m.device.rt.modes.fault_error is None
    first = 500.0 if indexing == "1" else 500.0 + (at_home - manual_cut)
    assert float(cutoff.target) - manual_cut == pytest.approx(first, abs=1.0 / COUNTS)


def test_indexing_beyond_the_length_is_3a(tmp_path):
    """Decision 8 (L3976 "If more material than the currently set length ... has been fed
    through the processing tool since the last manual cut ... 'Index Length' error"): a manual
    cut, then 600 mm of strip through the tool before Automatic, LML 500: error 3A."""
    m = machine(tmp_path, MANUAL_CUT, {"A134": "I1.00.1 0100 1"},
                profile='[\n  { time = 0.5, speed = 600.0, acceleration = 1e9 },\n  { time = 1.5, speed = 0.0, acceleration = 1e9 },\n]',
                auto_io=True)
    m.io.set_input("auto", False)
    run_s(m, 0.3)
    pulse(m, "I1.00.1")
    run_s(m, 2.0)
    m.io.set_input("auto", True)
    run_s(m, 0.1)
    assert m.device.rt.modes.fault_error.code == "3A"


# -- MLO / MLT (material_length.py) ------------------------------------------------------------------


def _q(m: Machine, name: str) -> int:
    return m.device.memory.image.get(parse_operand(name, bit=True))


def test_mlo_sets_the_bit_every_length(tmp_path):
    """material_length decision 1 (L2186-2189): MLO Q1.00.3 1 000250.000 sets the output when
    250 mm of material have been fed since it was read (the strip ramps: 250 mm at 1.0 s), and,
    the measurement restarted, again after the next 250 mm (at 1.5 s)."""
    program = "0000 NOP\n0001 MLO Q1.00.3 1 000250.000\n0002 JMP 0002\n"
    m = machine(tmp_path, program, profile=CONSTANT_500)
    run_s(m, 0.95)
    assert _q(m, "Q1.00.3") == 0
    run_s(m, 0.1)
    assert _q(m, "Q1.00.3") == 1
    m.device.memory.image.set(parse_operand("Q1.00.3", bit=True), 0)
    run_s(m, 0.4)  # 1.45 s: 475 mm
    assert _q(m, "Q1.00.3") == 0
    run_s(m, 0.1)
    assert _q(m, "Q1.00.3") == 1


def test_mlt_tests_the_material_through_the_tool(tmp_path):
    """material_length decision 2 (L2195-2199): after FUN's material channel starts, MLT
    Q1.00.4 000300.000 makes the output 1 once more than 300 mm went through the tool (the
    carriage stands at home: the strip's travel), 0 before."""
    program = "0000 FUN 2 2 2 2 2 2 1\n0001 NOP\n0002 MLT Q1.00.4 000300.000\n0003 JMP 0002\n"
    m = machine(tmp_path, program, profile=CONSTANT_500)
    run_s(m, 1.0)  # 250 mm
    assert _q(m, "Q1.00.4") == 0
    run_s(m, 0.2)  # 350 mm
    assert _q(m, "Q1.00.4") == 1
    assert m.device.rt.memory.variables[26] == pytest.approx(m.device.rt.cutoff.material_point() * 1_000_000, abs=1_000_000)


# -- LMK / LMR (cutoff_raster.py) ---------------------------------------------------------------------

LMR_PROGRAM = PROGRAM.replace("LML 1 001000.000", "LMR 1 001000.000 000300.000").replace("LML 1 002000.000", "LMR 1 001000.000 000300.000")


def marked(tmp_path, program: str, positions: list[float], params: dict[str, str] | None = None) -> Machine:
    """The example with print marks on the strip at `positions`, a contrast sensor at the tool's
    home (line position 0) on Raster 1 (I0.01.7)."""
    machine(tmp_path, program, params, profile=CONSTANT_500)  # (writes m.toml)
    path = tmp_path / "m.toml"
    text = path.read_text()
    text = text.replace("[io]\n", f"[[marks]]\nname = \"marks\"\nsensor_position = 0.0\nwidth = 3.0\npositions = {positions!r}\n\n[io]\n")
    text = text.replace('"I1.00.0" = "punch_down"', '"I1.00.0" = "punch_down"\n"I0.01.7" = "marks"')
    path.write_text(text)
    return Machine.from_file(path)


def test_lmr_cuts_at_the_marks(tmp_path):
    """cutoff_raster decisions 1, 3, 4 (L2133-2171, Fig. 5-15 with the light barrier at the tool:
    raster distance = mark distance 1000, offset distance = offset 300): every cut is 300 mm
    after its mark on the strip, within 2 carriage counts (the sensor's edge is interpolated
    inside the NC cycle)."""
    marks = [600.0 + 1000.0 * k for k in range(6)]
    cuts = run_cuts(marked(tmp_path, LMR_PROGRAM, marks), 5)
    for k, c in enumerate(cuts):
        assert abs((c["material_point"] - marks[k] - 300.0) * COUNTS) <= 2.0, (k, c["material_point"])
    assert max(abs(c["actual_length"] - 1000.0) for c in cuts[1:]) * COUNTS <= 2.0


def test_lmr_goes_on_over_a_missing_mark(tmp_path):
    """cutoff_raster decision 3: the mark at 3600 is missing; the raster is taken one raster
    distance after the previous one, so that piece is 1000 mm too and the next marks are
    followed again."""
    marks = [600.0, 1600.0, 2600.0, 4600.0, 5600.0]
    cuts = run_cuts(marked(tmp_path, LMR_PROGRAM, marks), 5)
    expected = [900.0, 1900.0, 2900.0, 3900.0, 4900.0]
    for c, point in zip(cuts, expected):
        assert abs(c["material_point"] - point) * COUNTS <= 2.0, (c["material_point"], point)


def test_lmk_corrects_the_length_on_a_raster(tmp_path):
    """cutoff_raster decision 2 (L2105-2107): LMK 1 001000.000 000400.000: without a raster the
    pieces are 1000 mm; one raster (a mark at 2500 mm, the carriage home again) puts that cut
    400 mm after it (2900 instead of 3000), and the next piece counts 1000 from there."""
    program = PROGRAM.replace("LML 1 001000.000", "LMK 1 001000.000 000400.000")
    cuts = run_cuts(marked(tmp_path, program, [2500.0]), 4)
    points = [c["material_point"] for c in cuts]
    for got, want in zip(points, [1000.0, 2000.0, 2900.0, 3900.0]):
        assert abs(got - want) * COUNTS <= 2.0, (points)


STANDING = '[\n  { time = 0.0, speed = 0.0, acceleration = 500.0 },\n]'  # the strip stands


def synchronous_speeds(m: Machine, cuts: int) -> list[float]:
    """Run `cuts` cuts; the carriage's set-point speed in every cycle it was synchronous."""
    speeds: list[float] = []

    def watch(m: Machine) -> None:
        c = m.device.rt.cutoff
        if c is not None and c.state == SYNC:
            speeds.append(c.axis.axis.command_velocity)

    run_cuts(m, cuts, limit_s=8.0, each=watch)
    return speeds


def test_no_material_runs_on_the_variable(tmp_path):
    """cutoff.py decision 10 (C008, L5563-5582): the strip stands; with the No Material input
    (I1.00.7) on and V610 = 500 IU/s the CLM cuts every 1000 mm of the speed the variable gives
    (one cut about every 2 s), the carriage synchronous with that speed."""
    m = machine(tmp_path, PROGRAM, {"C008": "I1.00.7 610"}, profile=STANDING)
    m.device.memory.variables.write(610, 500_000_000, by="serial")
    m.device.memory.image.set(parse_operand("I1.00.7", bit=True), 1)
    speeds = synchronous_speeds(m, 3)
    c = m.device.rt.cutoff
    assert m.material.position == 0.0
    assert [float(x["target"]) for x in c.cuts[:2]] == pytest.approx([1000.0, 2000.0], abs=0.05)  # (the 3rd: punched, EOS to come)
    assert speeds and max(abs(v - 500.0) for v in speeds) < 1e-6


def test_raster_by_edge_or_by_level():
    """cutoff_raster decision 1 (A138 raster detection, L4955): digit 0 takes a rising edge of
    I0.01.7 once, digit 1 the level every cycle it is 1."""
    from fractions import Fraction

    from axisline.devices.clm.cutoff import ClockMaster
    from axisline.devices.clm.cutoff_raster import RasterWatch

    for level, expected in ((False, [None, Fraction(2), None, None]), (True, [None, Fraction(2), Fraction(3), None])):
        r = Rig("0000 NOP\n", params={"A100": "0 0 0 5 1", "A111": "01.00 1"}, mode="manual")
        watch = RasterWatch(r.rt, level=level)
        got = []
        for point, bit in ((1, 0), (2, 1), (3, 1), (4, 0)):
            r.set("I0.01.7", bit)
            got.append(watch.seen((ClockMaster(), point * 1000, 0.0)))  # the spot of material point `point`
        assert got == expected


# -- reverse optimisation (cutoff_reverse.py) ------------------------------------------------------


def _returns(m: Machine, n_cuts: int) -> tuple[list[dict], float, float]:
    """Run `n_cuts`; the largest |set-point acceleration| while returning (once the return is
    replanned, when it is), and the longest time the carriage stood at home with a length waiting."""
    peak, standing, longest = 0.0, 0, 0

    def watch(m: Machine) -> None:
        nonlocal peak, standing, longest
        c = m.device.rt.cutoff
        if c is None:
            return
        if c.state == "returning" and (c.reverse.active or c.reverse._input is None):
            peak = max(peak, abs(c.axis.axis.command_acceleration))
        if c.state == "home" and m.device.rt.tasks[0].wait == "cutoff" and c.cuts:
            standing += 1
            longest = max(longest, standing)
        else:
            standing = 0

    cuts = run_cuts(m, n_cuts, each=watch)
    return cuts, peak, longest * m.period


def test_reverse_optimisation_slows_the_return(tmp_path):
    """cutoff_reverse decisions 1, 2 (L4024 "the flying unit moves back to the original position
    at a reduced acceleration and accelerates back into synchronization without standing still"):
    2000 mm pieces at 30 m/min: at A108 the carriage races back and waits about 3 s at home;
    with A139's input on it returns at a fraction of A108 and waits less than 0.1 s, the pieces
    as long as before; the A139 output shows the optimised return."""
    program = PROGRAM.replace("LML 1 001000.000", "LML 1 002000.000")
    plain, peak_plain, wait_plain = _returns(machine(tmp_path, program, profile=CONSTANT_500), 4)
    opt = {"A139": "I1.01.0 Q1.00.5", "A140": "0.00 050 010", "A104": "+001000.000"}  # room to brake softly
    m = machine(tmp_path, program, opt, profile=CONSTANT_500)
    m.device.memory.image.set(parse_operand("I1.01.0", bit=True), 1)
    cuts, peak, wait = _returns(m, 4)
    assert peak_plain == pytest.approx(10000.0, rel=1e-6) and wait_plain > 2.0
    assert 100.0 <= peak < 0.25 * 10000.0 and wait < 0.1  # (not below A140's 1 % of A108)
    assert max(abs(c["error_counts"]) for c in cuts) <= 2.0 and max(abs(c["error_counts"]) for c in plain) <= 2.0


def test_reverse_optimisation_falls_back_to_a108_when_the_line_speeds_up(tmp_path):
    """cutoff_reverse decision 3 (L4976): the strip speeds up from 30 to 60 m/min during an
    optimised return (window 5 % of A106 = 100 mm/s): the rest of the return runs at A108."""
    program = PROGRAM.replace("LML 1 001000.000", "LML 1 002000.000")
    profile = '[\n  { time = 0.0, speed = 500.0, acceleration = 500.0 },\n  { time = 6.0, speed = 1000.0, acceleration = 2000.0 },\n]'
    m = machine(tmp_path, program, {"A139": "I1.01.0 Q1.00.5", "A140": "0.00 050 010", "A104": "+001000.000"}, profile=profile)
    m.device.memory.image.set(parse_operand("I1.01.0", bit=True), 1)
    events = []

    def watch(m: Machine) -> None:
        c = m.device.rt.cutoff
        if c is not None and c.state == "returning":
            events.append((round(m.device.rt.cycle * m.period, 3), c.reverse.active, _q(m, "Q1.00.5")))

    cuts = run_cuts(m, 4, each=watch)
    assert any(e[1] and e[2] for e in events if e[0] < 6.0)  # optimised (and shown) before the speed change
    fallbacks = [b[0] for a, b in zip(events, events[1:]) if a[1] and not b[1] and b[0] - a[0] < 0.003]
    assert fallbacks and 6.0 < fallbacks[0] < 6.2  # back at A108 once the window was passed
    assert max(abs(c["error_counts"]) for c in cuts) <= 2.0


def test_test_mode_cuts_on_the_internal_clock(tmp_path):
    """cutoff.py decision 11 (L3968-3972): A100's test digit: the strip stands, the internal clock
    at 8 of 32 steps of A106 (500 mm/s, test_speed_steps = 8) is the material; the carriage cuts
    every 1000 mm of it, synchronous at 500 mm/s; "down" and "zero" are the keys."""
    m = machine(tmp_path, PROGRAM, {"A100": "0 0 1 5 1"}, profile=STANDING)
    path = tmp_path / "m.toml"
    path.write_text(path.read_text().replace('report_output = "Q1.00.0"', 'report_output = "Q1.00.0"\ntest_speed_steps = 8'))
    m = Machine.from_file(path)
    speeds = synchronous_speeds(m, 3)
    c = m.device.rt.cutoff
    assert m.material.position == 0.0 and c.test_steps == 8
    assert [float(x["target"]) for x in c.cuts[:2]] == [1000.0, 2000.0]
    assert speeds and max(abs(v - 500.0) for v in speeds) < 1e-6
    c.test_key("down")
    assert c.test_steps == 7
    c.test_key("zero")
    assert c.test_steps == 0


def test_c001_averaging_smooths_the_master_velocity(tmp_path):
    """cutoff.py decision 12 (C001 averaging, L5485-5493): with 7 (128 values, 0.256 s) the
    velocity the carriage is fed forward with is the mean increment of the last 128 cycles:
    while the strip ramps at 500 mm/s^2 it reads about 64 ms of ramp (32 mm/s) behind the
    strip; at constant speed the pieces are still within 2 counts."""
    m = machine(tmp_path, PROGRAM, {"C001": "0 0 00 0 0 7"}, profile=CONSTANT_500)  # (averaging: the last digit)
    run_s(m, 0.6)
    c = m.device.rt.cutoff
    assert m.material.velocity - c.master.velocity == pytest.approx(500.0 * 0.128, abs=3.0)
    cuts = run_cuts(m, 4)
    assert max(abs(x["error_counts"]) for x in cuts[1:]) <= 2.0


def test_a_retract_program_at_the_travel_limit_is_47(tmp_path):
    """cutoff_inputs decision 7 (L4943 "If the maximum travel limit is reached before the
    processing program for moving the tool away from the material is finished ... 'Max. Travel
    Lmt' error"): the retract program at 1100 waits 5 s; the synchronous carriage reaches A104
    (400 mm) first: fault 47."""
    program = PROGRAM + "1100 WAI 05.000\n1101 EOS\n"
    m = machine(tmp_path, program, {"A137": "00250 1100"}, profile=CONSTANT_500)
    for _ in range(round(4.0 / m.period)):
        m.scheduler.run_cycle()
        if m.device.rt.modes.fault_error is not None:
            break
    error = m.device.rt.modes.fault_error
    assert error is not None and error.code == "47"
    assert m.device.rt.axes[1].actual_position == pytest.approx(400.0, abs=2.0)
