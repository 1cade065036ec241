"""The manual's chapter 5 and 7.5 programs on the simulated plant (a feed axis as in
examples/roll_feed_clm.toml: Vmax 500 mm/s, 5000 mm/s², Kv 10, A127 window 0.05 mm on M2.00.0),
each with the outcome the manual documents."""

from __future__ import annotations

from pathlib import Path

from axisline.machine import Machine

from .clmrig import roll_feed_text, with_parameters

EXAMPLES = Path(__file__).resolve().parents[3] / "examples"


def machine(tmp_path: Path, program: str, params: dict[str, str] | None = None, duration: float = 30.0) -> Machine:
    prg = tmp_path / "test.prg"
    prg.write_text(program)
    (tmp_path / "test.par").write_text(with_parameters((EXAMPLES / "clm" / "roll_feed.par").read_text(), params or {}))
    text = roll_feed_text(prg, tmp_path / "test.par")
    text = text.replace("duration = 60.0", f"duration = {duration}")
    path = tmp_path / "m.toml"
    path.write_text(text)
    return Machine.from_file(path)


def run_recording(m: Machine, seconds: float, probe) -> list:
    out = []
    for _ in range(round(seconds / m.period)):
        m.scheduler.run_cycle()
        out.append(probe(m))
    return out


def test_fak_example(tmp_path):
    """Fig. 5-13 (L1939-1945): PSI 100 -> 100; FAK 1.2345, PSI 100 -> 123.45; FAK 1.0003, PSI 100 -> 100.03.
    (The printed subroutine JSR 0100 is not shown: here the position is noted in V700-V702.)"""
    m = machine(tmp_path, "0000 PSI 1 +000100.000 999\n0001 SET V700 = +V100\n0002 FAK 1 1.234500\n"
                "0003 PSI 1 +000100.000 999\n0004 SET V701 = +V100\n0005 FAK 1 1.000300\n0006 PSI 1 +000100.000 999\n"
                "0007 SET V702 = +V100\n0008 JST 0008\n")
    m.run()
    v = m.device.memory.variables
    steps = [v[700] / 1e6, (v[701] - v[700]) / 1e6, (v[702] - v[701]) / 1e6]
    for got, want in zip(steps, (100.0, 123.45, 100.03)):
        assert abs(got - want) < 0.1, steps
    assert abs(m.device.rt.axes[1].exact_target - (100 + 123.45 + 100.03)) < 1e-9


def test_poi_example_adds_to_the_target(tmp_path):
    """L2285-2296: 'POI 1 -000100.000 999' then 'PSI 1 +000200.000 999' from the same start:
    'The drive unit traverses the distance: -100 +200 = +100'."""
    m = machine(tmp_path, "0000 POI 1 -000100.000 999\n0001 PSI 1 +000200.000 999\n0002 JST 0002\n")
    m.run()
    assert abs(m.axis("feed").actual_position - 100.0) < 0.1


def test_acc_example_halves_the_acceleration(tmp_path):
    """Fig. 5-3 (L1417-1424; 'AKN M2.00.0' printed without its state, 1 meant): ACC 1 999 999,
    POI 200; ACC 1 500 999 reduces the acceleration to 50 % for PSI 300."""
    program = ("0000 ACC 1 999 999\n0001 POI 1 +000200.000 999\n0002 AKN M2.00.0 1\n0003 ACC 1 500 999\n"
               "0004 WAI 00.100\n0005 PSI 1 +000300.000 999\n0006 WAI 02.000\n0007 JST 0000\n")
    m = machine(tmp_path, program)
    task = m.device.rt.tasks[0]
    samples = run_recording(m, 2.5, lambda m: (task.pc, m.axis("feed").command_acceleration))
    first = max(a for pc, a in samples if pc <= 2)
    second = max(a for pc, a in samples if pc == 5)
    assert abs(first - 0.999 * 5000) < 60 and abs(second - 0.5 * 5000) < 60, (first, second)
    assert abs(m.axis("feed").actual_position - 500.0) < 0.1


def test_psa_proceeds_inside_the_position_window(tmp_path):
    """L2300-2322: with switching threshold Ax27 = 0.20, PSA 1 +200 proceeds when the drive is at
    +199.80 ... +200.20 (the example starts at +100: POA 100 first; the axis is homed as the
    example assumes, homing itself comes with part 3)."""
    program = "0000 POA 1 +000100.000 999\n0001 PSA 1 +000200.000 999\n0002 AEA Q1.00.0 1\n0003 JST 0003\n"
    m = machine(tmp_path, program, params={"A127": "M2.00.0 0000.200"})
    m.device.rt.axes[1].homed = True
    positions = run_recording(m, 2.0, lambda m: (m.io.output("press_valve"), m.axis("feed").actual_position))
    at_signal = next(p for on, p in positions if on)
    assert 199.8 <= at_signal <= 200.2


def test_task_1_example_counts_100_cycles(tmp_path):
    """§7.5 Task 1 (L3416-3422): AKN M2.00.0 (position reached, A127), PSI 100, pulse Q1.01.0 for
    250 ms, COU to 100 pieces sets Q1.00.0."""
    program = ("0000 AKN M2.00.0 1\n0001 PSI 1 +000100.000 999\n0002 AEA Q1.01.0 1\n0003 WAI 00.250\n"
               "0004 AEA Q1.01.0 0\n0005 COU +00000 Q1.00.0 000100\n0006 JMP 0000\n")
    m = machine(tmp_path, program, duration=70.0)
    image = m.device.memory.image
    from axisline.devices.clm.operands import parse_operand

    q = parse_operand("Q1.00.0", bit=True)
    for _ in range(round(60.0 / m.period)):
        m.scheduler.run_cycle()
        if image.get(q):
            break
    assert image.get(q) == 1
    assert abs(m.axis("feed").actual_position - 100 * 100.0) < 0.1


def _until_stopped(m: Machine, seconds: float) -> None:
    rt = m.device.rt
    started = False
    for _ in range(round(seconds / m.period)):
        m.scheduler.run_cycle()
        started = started or rt.modes.running
        if started and not rt.modes.running:
            return
    raise AssertionError("the program did not stop")


def test_bac_and_cou_examples_on_the_plant(tmp_path):
    """BAC a) 10 positionings, b) 9 (L1546-1563); COU: 10, then Q1.00.4 (L1739-1751)."""
    from .test_nc import listing

    for name, parts in (("bac_example_a", 10), ("bac_example_b", 9), ("cou_example", 10)):
        m = machine(tmp_path, listing(name) + "\n")
        _until_stopped(m, 40.0)
        assert abs(m.axis("feed").actual_position - 50.0 * parts) < 0.1, name


def test_psi_example(tmp_path):
    """L2330-2340: PSI 100, WAI 0.5, AEA Q1.00.6 1: the output comes 0.5 s after axis 1 is in
    position at +100 (the printed JSR 0666 is replaced by a stop)."""
    m = machine(tmp_path, "0000 PSI 1 +000100.000 999\n0001 WAI 00.500\n0002 AEA Q1.00.6 1\n0003 JST 0003\n")
    from axisline.devices.clm.operands import parse_operand

    q = parse_operand("Q1.00.6", bit=True)
    rt = m.device.rt
    in_position_at = output_at = None
    for k in range(round(3.0 / m.period)):
        m.scheduler.run_cycle()
        if in_position_at is None and rt.tasks[0].pc == 1:
            in_position_at = k
        if output_at is None and m.device.memory.image.get(q):
            output_at = k
    assert abs(m.axis("feed").actual_position - 100.0) < 0.1
    assert (output_at - in_position_at) * m.period == __import__("pytest").approx(0.5, abs=3 * m.period)  # + the cycles of WAI and AEA themselves


def test_akp_example_mask(tmp_path):
    """L1481-1502: mask 21001220 (bit 7 first): bits 0, 4, 5 must be 0, bits 3 and 6 must be 1,
    bits 1, 2, 7 are not checked."""
    from .clmrig import Rig

    rig = Rig("0000 AKP M2.02 21001220\n0001 JST 0001\n")
    rig.set("M2.02", 0b10001110)  # 7 1, 6 0: bit 6 must be 1 -> waits
    rig.run()
    rig.start()
    rig.run(3)
    assert rig.rt.tasks[0].pc == 0
    rig.set("M2.02", 0b11001110)  # 6 1, 5 0, 4 0, 3 1, 2 1, 1 1, 0 0: holds
    rig.run(2)
    assert rig.rt.tasks[0].pc == 1
