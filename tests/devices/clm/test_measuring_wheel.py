"""Measuring wheel mode of the CLM on the simulated plant (manual §7.2 L3203-3250, Ax16
L4609-4621, Ax31 L4822-4831, FUN L1981-1995, Status 09 L6951-6973): a feed roll that slips 2 %
on the strip it pulls (a wheel master with ``carrier = "feed"``) and a measuring wheel rolling
on the strip as master encoder 1. Decisions: src/axisline/devices/clm/measuring_wheel.py."""

from __future__ import annotations

from fractions import Fraction
from pathlib import Path

import pytest

from axisline.devices.clm import execute
from axisline.devices.clm.errors import ClmError
from axisline.devices.clm.master_encoder import MasterEncoder
from axisline.devices.clm.measuring_wheel import op_fun, status_09
from axisline.devices.clm.operands import parse_operand
from axisline.configerrors import ConfigError
from axisline.kernel.scheduler import Stage
from axisline.machine import Machine

from .clmrig import Rig, with_parameters, run_to as run

EXAMPLES = Path(__file__).resolve().parents[3] / "examples"
WHEEL_COUNT = 200 / (4 * 1250)  # IU of one wheel count: C002 / (4 x C000)
PIECE_PROGRAM = (EXAMPLES / "clm" / "measuring_wheel.prg").read_text()


def machine(tmp_path: Path, program: str = PIECE_PROGRAM, params: dict[str, str] | None = None, *,
            wire: bool = True, inputs: str = "", slip: float = 0.02, io_inputs: list[str] | None = None) -> Machine:
    """examples/measuring_wheel_clm.toml with `program` and its parameters changed by `params`."""
    (tmp_path / "t.prg").write_text(program)
    par = (EXAMPLES / "clm" / "measuring_wheel.par").read_text()
    (tmp_path / "t.par").write_text(with_parameters(par, params or {}))
    text = (EXAMPLES / "measuring_wheel_clm.toml").read_text()
    text = text.replace('program = "clm/measuring_wheel.prg"', f'program = "{(tmp_path / "t.prg").as_posix()}"')
    text = text.replace('parameters = "clm/measuring_wheel.par"', f'parameters = "{(tmp_path / "t.par").as_posix()}"')
    text = text.replace("slip = 0.02\n", f"slip = {slip}\n")
    if not wire:
        text = text.replace('master_encoder_1 = "wheel"\n', "")
    if inputs:
        text = text.replace("[device.outputs]", f"[device.inputs]\n{inputs}\n[device.outputs]")
    if io_inputs:
        text = text.replace("[io]\n", f"[io]\ninputs = {io_inputs!r}\n".replace("'", '"'))
        if "start" in io_inputs:  # the Start key is the test's (start_at would press it)
            text = text.replace("start_at = 0.1 ", "# start_at = 0.1 ")
    path = tmp_path / "m.toml"
    path.write_text(text)
    return Machine.from_file(path)


def strip(m: Machine):
    """The strip the feed roll pulls (the SlipContact under the wheel)."""
    return m.masters["wheel"].encoder.contact.source


def cut_positions(m: Machine, until_s: float, out: str = "Q1.00.0") -> list[float]:
    """The strip's position at each rising edge of the cut signal, until `until_s`."""
    rt, material = m.device.rt, strip(m)
    op = parse_operand(out, bit=True)
    previous, cuts = 0, []
    while rt.cycle * m.period < until_s - 1e-9:
        m.scheduler.run_cycle()
        now = rt.image.get(op)
        if now and not previous:
            cuts.append(material.position)
        previous = now
    return cuts


def pieces(cuts: list[float]) -> list[float]:
    return [b - a for a, b in zip([0.0] + cuts, cuts)]


def test_version_1_cuts_the_strip_to_length_although_the_roll_slips(tmp_path):
    """L3205 "The motor encoder cannot be used to measure the material length if there is slip
    ... the measuring wheel encoder ... the individual lengths can be measured accurately";
    L3246 Version 1: the loop closes through the wheel. The example's 10 pieces of 500 mm,
    measured on the simulated strip: 500 mm in mode 3, 490 mm (2 % short) as a normal axis."""
    with_wheel = pieces(cut_positions(machine(tmp_path), 14.0))
    assert len(with_wheel) == 10
    for length in with_wheel:
        assert length == pytest.approx(500.0, abs=3 * WHEEL_COUNT)
    normal = pieces(cut_positions(machine(tmp_path, params={"A100": "0 0 0 0 0"}), 14.0))
    assert len(normal) == 10
    for length in normal:
        assert 488.0 < length < 492.0  # 500 x (1 - 0.02 +- the seeded jitter)


def test_switching_encoders_keeps_the_position(tmp_path):
    """Decision 1 (L3229 "switch ... at any time in Automatic Mode"): with the Ax31 input off
    mid-feed the loop closes on the motor and the wheel difference stops growing; the position
    never jumps; the piece is 2 % short only for the part fed on the motor."""
    m = machine(tmp_path, "0000 PSI 1 +001000.000 500\n0001 JMP 0001\n", {"A131": "I1.00.3"})
    rt, axis = m.device.rt, m.device.rt.axes[1]
    active = parse_operand("I1.00.3", bit=True)
    rt.image.set(active, 1)  # (unwired: the test sets it)
    run(m, 0.5)
    wheel = axis.wheel
    assert wheel.active and wheel.gain < -1.0
    positions = [axis.actual_position]
    rt.image.set(active, 0)
    gain = None
    for _ in range(300):  # 0.6 s on the motor encoder
        m.scheduler.run_cycle()
        positions.append(axis.actual_position)
        gain = wheel.gain if gain is None else gain
        assert not wheel.active and wheel.gain == gain
    rt.image.set(active, 1)
    for _ in range(10):
        m.scheduler.run_cycle()
        positions.append(axis.actual_position)
    steps = [b - a for a, b in zip(positions, positions[1:])]
    assert max(abs(s) for s in steps) <= 225.0 * m.period + 2 * WHEEL_COUNT  # 500 per mille of 450 mm/s: no jump
    run(m, 6.0)
    assert axis.actual_position == pytest.approx(1000.0, abs=0.1)
    travel_on_motor = 225.0 * 0.6  # the part of the feed on the motor encoder
    assert 1000.0 - 0.03 * travel_on_motor < strip(m).position < 1000.0 - 0.01 * travel_on_motor


def test_manual_repositions_on_the_motor_encoder(tmp_path):
    """Decision 2 (L3229, L4831 "the repositioning comes from the servo drive in Manual Mode"):
    jogging in Manual moves the axis position with the motor encoder, not the wheel."""
    m = machine(tmp_path, "0000 JMP 0000\n", inputs='"I0.00.1" = false\n"I0.01.0" = true')
    run(m, 1.0)
    axis = m.device.rt.axes[1]
    assert m.device.rt.modes.mode == "manual"
    assert axis.actual_position > 50.0  # jogged at A107 100 mm/s
    assert not axis.wheel.active and axis.wheel.gain == 0.0
    assert axis.motor_position == axis.actual_position
    assert strip(m).position == pytest.approx(0.98 * axis.actual_position, rel=0.005)


def test_poa_in_version_1_is_0a(tmp_path):
    """Decision 3 (L4198 "Only relative distances are traversed"): POA in mode 3 stops the
    program with 0A; Version 2 accepts it (and asks for a reference like a normal axis: 48)."""
    m = machine(tmp_path, "0000 POA 1 +000100.000 500\n0001 JMP 0001\n")
    run(m, 0.3)
    fault = m.device.rt.modes.fault_error
    assert fault is not None and fault.code == "0A" and "L4198" in fault.detail
    m = machine(tmp_path, "0000 POA 1 +000100.000 500\n0001 JMP 0001\n", {"A100": "0 0 0 4 0"})
    run(m, 0.3)
    assert m.device.rt.modes.fault_error.code == "48"


def test_version_2_corrects_the_feed_and_compiles_the_rest(tmp_path):
    """Decision 4 (L3247): Version 2 closes the loop on the motor and adds the motor - wheel
    difference of the feed to its target until the motor is within Ax27; what comes after is
    added to the next feed. The pieces come out 500 mm on the strip, the roll turns 2 % more."""
    m = machine(tmp_path, params={"A100": "0 0 0 4 0"})
    lengths = pieces(cut_positions(m, 14.0))
    assert len(lengths) == 10
    for length in lengths:
        assert length == pytest.approx(500.0, abs=0.15)
    assert sum(lengths) == pytest.approx(5000.0, abs=0.15)  # the compiled rest does not add up
    axis = m.device.rt.axes[1]
    assert axis.wheel.version == 2 and axis.wheel.gain == pytest.approx(-0.02 / 0.98 * axis.actual_position, rel=0.15)
    assert axis.actual_position > 5090.0  # the motor's own frame: 500 / 0.98 a piece


def test_ax16_window_1_faults_4c(tmp_path):
    """Decision 5 (L4615, L8891-8901): motor and wheel differ by about 4 mm per 200 mm wheel
    revolution (2 % slip); window 1 = 03 IU is exceeded within the first revolution: 4C
    "Encoder Fault A1". The example's 10 IU does not fault."""
    m = machine(tmp_path, params={"A116": "03 00 00.00.0"})
    run(m, 2.0)
    fault = m.device.rt.modes.fault_error
    assert fault is not None and fault.code == "4C" and fault.text == "Encoder Fault A1"
    assert not m.device.rt.axes[1].drive_enabled
    assert strip(m).position < 200.0  # within one wheel revolution
    m = machine(tmp_path)
    run(m, 3.0)
    assert m.device.rt.modes.fault_error is None


def test_ax16_window_2_output(tmp_path):
    """Decision 5 (L4617 "the output ... is turned on"): 4 mm per revolution is beyond window 2
    = 03 IU: Q1.00.2 comes on and stays on while the slip goes on; window 2 = 05 leaves it off."""
    m = machine(tmp_path)
    rt = m.device.rt
    seen = []
    for _ in range(int(6.0 / m.period)):
        m.scheduler.run_cycle()
        seen.append(rt.image.get(parse_operand("Q1.00.2", bit=True)))
    first = seen.index(1)
    assert first * m.period < 1.5
    assert all(seen[first:])  # no flicker at each new revolution
    m = machine(tmp_path, params={"A116": "10 05 Q1.00.2"})
    run(m, 6.0)
    assert rt is not m.device.rt and m.device.rt.image.get(parse_operand("Q1.00.2", bit=True)) == 0


def test_wheel_losing_contact_is_stopped_by_the_monitoring(tmp_path):
    """L3231-3240: the wheel must be pressed against the material, else "the drive can
    temporarily run on until it is stopped by error detection"; L8895 4C "no repositioning by
    the measuring wheel occurred". The wheel lifts mid-feed (it turns at a tenth of the strip):
    the loop's position stops following, Ax14 stops it as a lag (43) within its 0.3 mm window;
    with Ax14 off, Ax16's window 1 (10 IU) stops it with 4C. Decision 5."""
    for a114, code, run_on in (("0 010 00.00.0", "43", 3.0), ("1 010 00.00.0", "4C", 15.0)):
        m = machine(tmp_path, params={"A114": a114})
        run(m, 0.5)
        m.masters["wheel"].encoder.contact.set_slip(0.9)
        lifted = strip(m).position
        rt = m.device.rt
        while rt.modes.fault_error is None and rt.cycle < 1500:
            m.scheduler.run_cycle()
        assert rt.modes.fault_error is not None and rt.modes.fault_error.code == code
        assert strip(m).position - lifted < run_on  # the strip ran on this far until the fault
        m.scheduler.run_cycle()
        assert not rt.axes[1].drive_enabled


def test_parameter_mode_keeps_the_wheel_position(tmp_path):
    """Decision 6: leaving Parameter mode in the same measuring wheel mode, the wheel's
    difference carries over: the position does not jump and the next piece is 500 mm again."""
    m = machine(tmp_path, "0000 PSI 1 +000500.000 999\n0001 WAI 01.000\n0002 JMP 0000\n",
                inputs='"I0.00.0" = "parameter"\n"I0.00.1" = "automatic"\n"I0.00.3" = "start"',
                io_inputs=["parameter", "automatic", "start"])
    io, rt = m.io, m.device.rt
    io.set_input("automatic", True)
    io.set_input("start", True)
    run(m, 0.2)
    io.set_input("start", False)
    run(m, 1.8)  # the first piece is fed, the program waits
    axis = rt.axes[1]
    gain, position = axis.wheel.gain, axis.actual_position
    assert position == pytest.approx(500.0, abs=0.1) and gain < -5.0
    io.set_input("automatic", False)
    io.set_input("parameter", True)
    run(m, 2.0)
    assert rt.modes.mode == "parameter"
    io.set_input("parameter", False)
    io.set_input("automatic", True)
    run(m, 2.2)
    assert axis.wheel.gain == pytest.approx(gain, abs=0.05) and axis.actual_position == pytest.approx(position, abs=0.1)
    start = strip(m).position
    io.set_input("start", True)
    run(m, 2.3)
    io.set_input("start", False)
    run(m, 4.0)
    assert rt.modes.fault_error is None
    assert strip(m).position - start == pytest.approx(500.0, abs=3 * WHEEL_COUNT)


def test_without_a_wheel_the_axis_runs_on_the_motor(tmp_path):
    """Decision 6: mode 3 without device.master_encoder_1 feeds on the motor encoder (the pieces
    are 2 % short) and Status 09 answers 09 "Status # illegal"."""
    m = machine(tmp_path, wire=False)
    lengths = pieces(cut_positions(m, 4.0))
    assert lengths and all(488.0 < length < 492.0 for length in lengths)
    with pytest.raises(ClmError) as e:
        status_09(m.device.rt)
    assert e.value.code == "X01:09"


def test_status_09_and_v047(tmp_path):
    """Decision 8, Status 09 ``Xs09__evmmmmm.mmm_vnnnnnn.nnn_`` (L6951-6973): m = the position
    from the wheel, n = the motor encoder (V047, L1380); not in measuring wheel mode: error 10."""
    m = machine(tmp_path)
    cut_positions(m, 1.4)  # the first piece is fed and cut
    rt, axis = m.device.rt, m.device.rt.axes[1]
    body = status_09(rt)
    motor = axis.motor_position
    assert body == f"09   +000{axis.actual_position:07.3f} +000{motor:07.3f} "
    assert axis.actual_position == pytest.approx(500.0, abs=0.1)
    assert motor == pytest.approx(500.0 / 0.98, abs=1.5)  # the roll turned 2 % more
    assert rt.memory.variables[47] == round(motor * 1_000_000)
    assert rt.memory.variables[100] == round(axis.actual_position * 1_000_000)
    rig = Rig("0000 JMP 0000\n")
    with pytest.raises(ClmError) as e:
        status_09(rig.rt)
    assert e.value.code == "X01:10"


def test_set_v047_sets_the_motor_encoder(tmp_path):
    """Decision 8 (L2594 "If Axis X is not homed, the system variables V047 ... can be set"):
    setting V047 sets the motor encoder's reading; the wheel's difference stays. (SET V047
    reaches it through runtime.set_position_variable, see the lead's wiring.)"""
    m = machine(tmp_path, "0000 PSI 1 +000300.000 500\n0001 JMP 0001\n")
    run(m, 2.0)
    axis = m.device.rt.axes[1]
    gain = axis.wheel.gain
    assert gain < -1.0
    axis.set_motor_actual(1000.0)
    assert axis.motor_position == pytest.approx(1000.0)
    assert axis.actual_position - axis.motor_position == pytest.approx(gain)
    run(m, 2.5)
    assert axis.motor_position == pytest.approx(1000.0, abs=0.1)  # no motion from it


def test_fun_measures_feed_lengths(tmp_path, monkeypatch):
    """Decision 7, FUN (L1981-1995, V040/V041 L1376-1377, Vx11/Vx12 Fig. 5-2): a channel
    measures from its first FUN; 0 buffers and restarts, 1 restarts, 2 leaves it."""
    monkeypatch.setitem(execute.HANDLERS, "FUN", op_fun)  # (the lead wires it into execute.py)
    program = (
        "0000 FUN 2 2 1 2 2 2 2\n"      # axis 1 measures
        "0001 PSI 1 +000500.000 999\n"
        "0002 FUN 0 0 0 0 2 2 2\n"      # buffer axis 1 (500), ME1 (not started: 0); restart both
        "0003 PSI 1 +000200.000 999\n"
        "0004 FUN 2 2 1 2 2 2 2\n"      # axis 1 restarts, its buffer stays
        "0005 JMP 0005\n"
    )
    m = machine(tmp_path, program)
    rt = m.device.rt
    v = rt.memory.variables
    run(m, 0.05)
    assert v[111] == 0 and v[40] == 0  # not activated yet
    run(m, 3.0)
    assert rt.modes.fault_error is None
    assert v[112] / 1e6 == pytest.approx(500.0, abs=0.1)  # axis 1's first feed, on the wheel
    assert v[41] == 0  # master encoder 1 had not been started
    assert v[40] / 1e6 == pytest.approx(200.0, abs=0.1)  # the wheel since the FUN at 0002
    assert abs(v[111]) / 1e6 < 0.1  # restarted at 0004
    assert v[211] == v[212] == v[42] == 0  # no axis 2, no master encoder 2
    m = machine(tmp_path, program, {"A100": "0 0 0 4 0"})  # Version 2: the material fed, not the motor's 510
    run(m, 3.0)
    assert m.device.rt.memory.variables[112] / 1e6 == pytest.approx(500.0, abs=0.15)


class _Counts:
    """A master with integer counts (what MasterEncoder reads of a wheel master)."""

    counts = 0

    def update(self, cycle: int) -> None:
        pass


def test_master_encoder_2_reads_c004_c006_without_fak5(tmp_path):
    """master_encoder.py decision 7 (C004-C007 L5533-5561; FAK 5 is master encoder 1's, L1935):
    one class for both; master encoder 2 scales by C006 / (4 x C004), signed by C005."""
    m = machine(tmp_path, params={"C004": "01000 0000", "C006": "0100.00000", "C005": "0 0 00 0 1 0"})
    rt = m.device.rt
    rt.master_factor = 2_000_000  # FAK 5 2.000000
    source = _Counts()
    me2 = MasterEncoder(source, rt, 2)
    source.counts = 4000  # one revolution of 4 x 1000 counts
    me2.sample(1)
    assert me2.position == Fraction(-100)  # C005 direction 1; FAK 5 not applied
    assert me2.counts_per_revolution == 4000 and me2.set_up
    assert rt.master_encoder.scale == Fraction(2 * 200, 4 * 1250)  # master encoder 1 takes FAK 5
    with pytest.raises(ValueError, match="master encoders 1 and 2"):
        MasterEncoder(source, rt, 3)


def _tables(text: str, head: str, sub: str) -> str:
    """The lines of the table `head` and its sub-tables `sub`... in the machine file `text`."""
    out, inside = [], False
    for line in text.splitlines(keepends=True):
        if line.startswith("["):
            inside = line.startswith(head) or (inside and line.startswith(sub))
        if inside:
            out.append(line)
    return "".join(out)


def two_axis_machine(tmp_path: Path, program: str, a216: str, wire_2: str = "direct") -> Machine:
    """The example with a second feed roll (axis 2, A200 mode 3) whose strip carries a second
    wheel, master encoder 2 (C004 01250, C006 0200.00000): built here ("direct") or by the
    personality's device.master_encoder_2 ("key")."""
    axis2 = {"B000": "1 0 0", "A200": "0 0 0 3 0", "A206": "000450.000", "A208": "005000", "A211": "10.00 0",
             "A216": a216, "A227": "M2.00.1 0000.050", "C004": "01250 0000", "C006": "0200.00000"}
    m_text = (EXAMPLES / "measuring_wheel_clm.toml").read_text()
    feed_axis = _tables(m_text, "[[axis]]", "[axis.")
    wheel = _tables(m_text, "[[master]]", "[master.")
    extra = feed_axis.replace('name = "feed"', 'name = "feed2"') + wheel.replace('name = "wheel"', 'name = "wheel2"').replace('carrier = "feed"', 'carrier = "feed2"')
    (tmp_path / "t.prg").write_text(program)
    par = with_parameters((EXAMPLES / "clm" / "measuring_wheel.par").read_text(), axis2)
    (tmp_path / "t.par").write_text(par)
    text = m_text.replace("[io]", extra + "[io]").replace('axes = ["feed"]', 'axes = ["feed", "feed2"]')
    if wire_2 == "key":
        text = text.replace('master_encoder_1 = "wheel"\n', 'master_encoder_1 = "wheel"\nmaster_encoder_2 = "wheel2"\n')
    text = text.replace('program = "clm/measuring_wheel.prg"', f'program = "{(tmp_path / "t.prg").as_posix()}"')
    text = text.replace('parameters = "clm/measuring_wheel.par"', f'parameters = "{(tmp_path / "t.par").as_posix()}"')
    path = tmp_path / "m2.toml"
    path.write_text(text)
    m = Machine.from_file(path)
    if wire_2 == "key":
        return m
    # master encoder 2 built directly (the personality's device.master_encoder_2 does the same),
    # read in INPUTS after the wheels, as the personality reads master encoder 1 before the runtime
    me2 = MasterEncoder(m.masters["wheel2"], m.device.rt, 2)
    m.device.rt.master_encoder_2 = me2
    m.scheduler.add_task("master_encoder_2", me2.sample, Stage.INPUTS)
    return m


def test_master_encoder_2_is_the_wheel_of_axis_2(tmp_path):
    """L4228 "Master Encoder 1 is intended for use with axis 1 and Master Encoder 2 ... with axis
    2": axis 2 in mode 3 feeds its strip to length on master encoder 2; its Encoder Fault is 7C
    (L8887-8891)."""
    m = two_axis_machine(tmp_path, "0000 PSI 2 +000500.000 999\n0001 JMP 0001\n", "10 00 00.00.0")
    axis2 = m.device.rt.axes[2]
    assert axis2.wheel is not None and axis2.wheel.encoder is m.device.rt.master_encoder_2
    assert m.device.rt.axes[1].wheel.encoder is m.device.rt.master_encoder
    run(m, 2.0)
    assert m.device.rt.modes.fault_error is None
    assert m.masters["wheel2"].encoder.contact.source.position == pytest.approx(500.0, abs=3 * WHEEL_COUNT)
    assert axis2.motor_position == pytest.approx(500.0 / 0.98, abs=1.5)
    m = two_axis_machine(tmp_path, "0000 PSI 2 +000500.000 999\n0001 JMP 0001\n", "03 00 00.00.0")
    run(m, 2.0)
    fault = m.device.rt.modes.fault_error
    assert fault is not None and fault.code == "7C" and fault.text == "Encoder Fault A2"


def test_a_wheel_carrier_must_be_an_axis(tmp_path):
    """sync_setup: ``carrier`` names the axis whose feed roll moves the strip under the wheel; a
    wrong name, or a carrier on a master that is no wheel, is a clear machine-file error."""
    text = (EXAMPLES / "measuring_wheel_clm.toml").read_text().replace("clm/", f"{(EXAMPLES / 'clm').as_posix()}/")
    path = tmp_path / "bad.toml"
    path.write_text(text.replace('carrier = "feed"', 'carrier = "roll"'))
    with pytest.raises(ConfigError, match="carrier = 'roll': no such axis \\(axes: feed\\)"):
        Machine.from_file(path)
    path.write_text(text.replace('kind = "wheel"', 'kind = "virtual"\nacceleration = 100.0'))
    with pytest.raises(ConfigError, match="carrier = 'feed' is for a master of kind 'wheel'"):
        Machine.from_file(path)

def test_fun_status_09_and_set_v047_through_the_program(tmp_path):
    """FUN in execute.HANDLERS, Status 09 in status_body, SET V047 through
    runtime.set_position_variable (measuring_wheel.py decisions 7, 8)."""
    from axisline.devices.clm.status import status_body

    program = ("0000 FUN 2 2 1 2 2 2 2\n0001 PSI 1 +000300.000 999\n0002 FUN 0 2 0 2 2 2 2\n"
               "0003 WAI 00.300\n0004 SET V047 = +00001000.000000\n0005 JMP 0005\n")
    m = machine(tmp_path, program)
    run(m, 2.0)
    rt, axis = m.device.rt, m.device.rt.axes[1]
    assert rt.modes.fault_error is None
    assert rt.memory.variables[112] / 1e6 == pytest.approx(300.0, abs=0.1)
    assert axis.motor_position == pytest.approx(1000.0, abs=0.05)
    assert status_body(rt, 9, []) == status_09(rt)


def test_master_encoder_2_from_the_machine_file(tmp_path):
    """device.master_encoder_2 wires master encoder 2 as axis 2's wheel (personality)."""
    m = two_axis_machine(tmp_path, "0000 PSI 2 +000500.000 999\n0001 JMP 0001\n", "10 00 00.00.0", wire_2="key")
    rt = m.device.rt
    assert rt.master_encoder_2 is not None and rt.axes[2].wheel.encoder is rt.master_encoder_2
    run(m, 2.0)
    assert m.masters["wheel2"].encoder.contact.source.position == pytest.approx(500.0, abs=3 * WHEEL_COUNT)
