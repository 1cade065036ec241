"""CLM homing (manual §7.9 L3694-3803, HOM L1997-2026, Ax23-Ax25 L4688-4754; errata §3.9) on the
simulated plant: the indexing table of examples/rotary_table_clm.toml (incremental encoder,
one marker per motor revolution = 360/590 degree, home cam I1.00.0 from 20.3 degrees,
Ax24 = M2.02.0 +500 0: option 1, + direction, V1 = 500 per mille of 48 deg/s)."""

from __future__ import annotations

from pathlib import Path

import pytest

from axisline.devices.clm.homing import ClmHoming
from axisline.machine import Machine

EXAMPLES = Path(__file__).resolve().parents[3] / "examples"
REV = 360 / 590  # one motor (encoder) revolution, degrees
INC = REV / 4096  # one increment


def table(tmp_path: Path, program: str, params: dict[str, str] | None = None, cam: float = 20.3, width: float = 30.0) -> Machine:
    (tmp_path / "t.prg").write_text(program)
    par = (EXAMPLES / "clm" / "rotary_table.par").read_text()
    for pid, data in (params or {}).items():
        par = "\n".join(line if not line.startswith(pid + " ") else f"{pid} {data}" for line in par.splitlines()) + "\n"
    (tmp_path / "t.par").write_text(par)
    text = (EXAMPLES / "rotary_table_clm.toml").read_text()
    text = text.replace('"clm/rotary_table.prg"', f'"{(tmp_path / "t.prg").as_posix()}"')
    text = text.replace('"clm/rotary_table.par"', f'"{(tmp_path / "t.par").as_posix()}"')
    text = text.replace("position = 20.3", f"position = {cam}").replace("width = 30.0", f"width = {width}")
    (tmp_path / "m.toml").write_text(text)
    return Machine.from_file(tmp_path / "m.toml")


def run_until(m: Machine, seconds: float, done) -> None:
    for _ in range(round(seconds / m.period)):
        m.scheduler.run_cycle()
        if done(m):
            return


HOME = "0000 HOM 1\n0001 AKN M2.02.0 1\n0002 AEA Q1.00.0 1\n0003 JST 0003\n"


def homed_output(m: Machine) -> int:
    from axisline.devices.clm.operands import parse_operand

    return m.device.memory.image.get(parse_operand("M2.02.0", bit=True))


def test_option_1_sequence_speeds_and_reference(tmp_path):
    """Option 1 (Fig. 7-17, L3728-3746): V1 to the cam, V2 = 1/4 V1 off it, V3 = 10 inc/cycle
    back to the first marker, V4 = 1 inc/cycle onto it; the marker gets -Ax25 (decision 6:
    Ax25 = +10, the zero point 10 degrees past the marker, L3556)."""
    m = table(tmp_path, HOME)
    clm = m.device.rt.axes[1]
    procs = []
    start = clm.start_homing

    def spy():
        start()
        procs.append(clm._homing_proc)

    clm.start_homing = spy
    run_until(m, 10.0, lambda m: m.io.output("tool"))
    assert m.io.output("tool") and homed_output(m) == 1 and clm.homed
    proc: ClmHoming = procs[0]
    names = [n for n, _ in proc.phases]
    assert names == ["to cam at V1", "leave cam at V2", "marker search at V3", "onto marker at V4"]
    v = dict(proc.phases)
    assert v["to cam at V1"] == pytest.approx(24.0)  # 500 per mille of Ax06 = 48
    assert v["leave cam at V2"] == pytest.approx(-6.0)
    assert v["marker search at V3"] == pytest.approx(10 * INC / 0.002)
    assert v["onto marker at V4"] == pytest.approx(-INC / 0.002)
    # E = the cam at 20.3 on the plant, M = the first marker after it: k = 34 at 20.7458 degrees
    assert abs(proc.edge - 20.3) < 0.02  # (measured before the new reference: plant frame)
    marker_plant = 34 * REV
    plant = m.units["table"].drive.position
    # the axis rests on the marker (+-1 increment plus the standstill lag) and reads -Ax25 there
    assert abs(plant - marker_plant) < 3 * INC + 0.002
    assert abs(clm.actual_position - (plant - marker_plant) - (-10.0)) < 2 * INC
    assert clm.position == pytest.approx(350.0, abs=0.003)  # modulo IUT = 360


def test_hom_and_akn_on_the_homed_output(tmp_path):
    """HOM proceeds after one cycle (L2026); AKN M2.02.0 1 waits for the Homed output (L2018-2022)."""
    m = table(tmp_path, HOME)
    rt = m.device.rt
    run_until(m, 1.0, lambda m: rt.tasks[0].pc == 1)
    assert rt.tasks[0].pc == 1 and rt.axes[1].homing and homed_output(m) == 0
    run_until(m, 1.0, lambda m: False)
    assert rt.tasks[0].pc == 1  # still homing: AKN waits
    run_until(m, 10.0, lambda m: rt.tasks[0].pc == 3)
    assert homed_output(m) == 1 and not rt.axes[1].homing


def fault(m: Machine) -> str | None:
    e = m.device.rt.modes.fault_error
    return None if e is None else e.code


def test_marker_too_close_to_the_cam_is_4b(tmp_path):
    """L3752-3756: the cam switching point closer than 1/16 revolution to the marker -> 'Mrkr
    Pulse Pos' (4B). The cam at 20.73: the first marker after it at 20.7458 is 0.026 rev away."""
    m = table(tmp_path, HOME, cam=20.73)
    run_until(m, 10.0, lambda m: fault(m) is not None)
    assert fault(m) == "4B" and not m.device.rt.axes[1].homed


class _Marker:
    def __init__(self, on: bool) -> None:
        self.on = on

    def active(self) -> bool:
        return self.on

    def position(self) -> float:
        return 0.0


def test_no_marker_is_4a(tmp_path):
    """L3766: no marker pulse within one encoder revolution -> 'No Marker Pulse' (4A)."""
    m = table(tmp_path, HOME)
    m.device.rt.axes[1].marker = _Marker(False)
    run_until(m, 10.0, lambda m: fault(m) is not None)
    assert fault(m) == "4A"


def test_stuck_marker_is_4f(tmp_path):
    """Errata §3.9: a marker that stays active -> 'Marker high' (4F) (decision 4)."""
    m = table(tmp_path, HOME)
    m.device.rt.axes[1].marker = _Marker(True)
    run_until(m, 10.0, lambda m: fault(m) is not None)
    assert fault(m) == "4F"


def test_cam_too_short_is_49(tmp_path):
    """A cam shorter than the braking from V1 (24 deg/s at 200 deg/s^2: 1.44 degrees) drops
    while braking onto it -> 'Cam too short' (49) (decision 5)."""
    m = table(tmp_path, HOME, width=0.5)
    run_until(m, 10.0, lambda m: fault(m) is not None)
    assert fault(m) == "49"


def test_hom_with_an_absolute_encoder_is_52(tmp_path):
    """L2006-2008: HOM is not needed with an absolute encoder, 'otherwise ... HOM - Command' (52)."""
    m = table(tmp_path, HOME, params={"A120": "0 2 24 1", "A119": "01024 0256", "A102": "0000 0000"})
    run_until(m, 1.0, lambda m: fault(m) is not None)
    assert fault(m) == "52"


def test_option_3_and_4_switch_edge(tmp_path):
    """Options 3/4 (L3787-3795): V1 until the rising edge of the home switch; the edge point reads
    -Ax25 (decision 8). Option 4 standing on the switch first leaves it."""
    for option, start_on in ((2, False), (3, True)):
        m = table(tmp_path, HOME, params={"A124": f"M2.02.0 +500 {option}"}, cam=-5.0 if start_on else 20.3, width=10.0)
        run_until(m, 10.0, lambda m: m.io.output("tool") or fault(m) is not None)
        assert fault(m) is None and homed_output(m) == 1
        clm = m.device.rt.axes[1]
        edge = -5.0 if start_on else 20.3  # option 4 leaves the cam [-5, 5) backwards, then enters it at -5
        # the coordinate -10 sits at the edge (to the cycle: V1 x 2 ms = 0.048 degrees)
        assert abs(clm.actual_position - (m.units["table"].drive.position - edge) + 10.0) < 0.06


def test_option_2_marker_only(tmp_path):
    """Option 2 (L3775-3779): first marker at V3, then to 1/32 revolution before the second,
    V4 onto it; the second marker reads -Ax25 (decision 7)."""
    m = table(tmp_path, HOME, params={"A124": "M2.02.0 +500 1"})
    run_until(m, 10.0, lambda m: m.io.output("tool") or fault(m) is not None)
    assert fault(m) is None and homed_output(m) == 1
    plant = m.units["table"].drive.position
    assert abs(plant - 2 * REV) < 3 * INC + 0.002  # markers at 0 (start), REV, 2 REV: the second after the first


def cutoff_carriage(tmp_path: Path, switch_at: float = 20.0) -> Machine:
    """The roll feed's axis as a flying-cutoff carriage (Ax00 mode 5, linear) with a home switch
    from 20 to 30 mm on I1.00.3, Ax24 type 4 (option 5) with its Homed output on Q1.00.5,
    Ax25 = -5; the CLM in Manual (I0.00.1 wired off) so the jog keys move it."""
    from .clmrig import EXAMPLES as CLM_EXAMPLES, roll_feed_text, with_parameters

    par = with_parameters((CLM_EXAMPLES / "clm" / "roll_feed.par").read_text(), {
        "A100": "1 0 0 5 1", "A123": "00.00.0 I1.00.3", "A124": "Q1.00.5 +100 4", "A125": "-00005.000"})
    (tmp_path / "c.par").write_text(par)
    (tmp_path / "c.prg").write_text("0000 JMP 0000\n")
    text = roll_feed_text(tmp_path / "c.prg", tmp_path / "c.par")
    text = text.replace("[io]", f'[[axis.switches]]\nname = "home"\nkind = "reference"\nposition = {switch_at}\nwidth = 10.0\n\n[io]', 1)
    text = text.replace('"I1.00.2" = true', '"I1.00.2" = true\n"I1.00.3" = "feed.home"\n"I0.00.1" = false', 1)
    text = text.replace("start_at = 0.1", "start_at = 999.0")
    (tmp_path / "m.toml").write_text(text)
    return Machine.from_file(tmp_path / "m.toml")


JOG_STEP = 100.0 * 0.002 + 0.01  # Ax07 = 100 mm/s x one 2 ms NC cycle, + the standstill lag


def _jog(m: Machine, key: str, until) -> None:
    from axisline.devices.clm.operands import parse_operand

    image = m.device.memory.image
    image.set(parse_operand(key, bit=True), 1)
    run_until(m, 5.0, until)
    image.set(parse_operand(key, bit=True), 0)
    run_until(m, 0.5, lambda m: False)


def test_option_5_passive_homing_on_the_switch_edges(tmp_path):
    """Option 5 (L3797-3803, homing.py decision 9): Jog Forward from on the switch homes the
    carriage where it leaves the switch (the switch's end at 30 mm gets -Ax25 = +5); Jog Reverse
    from off the switch homes it where it reaches the switch; HOM is 52 for type 4 (L4739)."""
    from axisline.devices.clm.operands import parse_operand

    m = cutoff_carriage(tmp_path)
    clm = m.device.rt.axes[1]
    plant = m.units["feed"].drive
    homed = lambda: m.device.memory.image.get(parse_operand("Q1.00.5", bit=True))  # noqa: E731
    run_until(m, 0.3, lambda m: False)
    assert m.device.rt.modes.mode == "manual" and clm.drive_enabled and not clm.homed
    # jog reverse onto the switch from 0 is not possible (the switch is ahead): jog forward into it
    _jog(m, "I0.01.0", lambda m: plant.position > 25.0)
    assert not clm.homed  # reaching the switch moving forward is no reference
    _jog(m, "I0.01.0", lambda m: plant.position > 40.0)  # leaves the switch at 30 moving forward
    assert clm.homed and homed() == 1
    # the switch end (plant 30 mm) reads +5 (= -Ax25): actual - plant offset is the same everywhere,
    # to one NC cycle of travel at Ax07 (an ordinary input is sampled once per cycle)
    assert clm.actual_position - plant.position == pytest.approx(5.0 - 30.0, abs=JOG_STEP)
    # homed once: passing the switch again (reverse onto it) does not move the reference
    _jog(m, "I0.01.1", lambda m: plant.position < 25.0)
    assert clm.actual_position - plant.position == pytest.approx(-25.0, abs=JOG_STEP)


def test_option_5_jog_reverse_onto_the_switch(tmp_path):
    """Option 5 (L3799): not on the switch (here -30..-20 mm), Jog Reverse homes the carriage
    where it reaches the switch (its end at -20 mm coming from above gets -Ax25 = +5)."""
    m = cutoff_carriage(tmp_path, switch_at=-30.0)
    clm = m.device.rt.axes[1]
    plant = m.units["feed"].drive
    run_until(m, 0.3, lambda m: False)
    assert not clm.homed
    _jog(m, "I0.01.1", lambda m: plant.position < -25.0)
    assert clm.homed
    assert clm.actual_position - plant.position == pytest.approx(5.0 + 20.0, abs=JOG_STEP)


def test_option_5_hom_is_52(tmp_path):
    """HOM with Ax24 type 4 (passive, L4739): error 52 HOM Command."""
    from axisline.devices.clm.errors import ClmError

    m = cutoff_carriage(tmp_path)
    run_until(m, 0.3, lambda m: False)
    with pytest.raises(ClmError) as e:
        m.device.rt.axes[1].start_homing()
    assert e.value.code == "52"
