"""Slave axis / synchronous axis (Ax00 modes 1/2, FOL; L1951-1979, §7.6 L3475-3499) on a
two-axis plant: examples/roll_feed_clm.toml's feed axis twice, B000 enabling axis 2, A200 a
slave of axis 1 (decisions in src/axisline/devices/clm/slave.py)."""

from __future__ import annotations

from pathlib import Path

from axisline.machine import Machine

from .clmrig import roll_feed_text

EXAMPLES = Path(__file__).resolve().parents[3] / "examples"


def machine(tmp_path: Path, program: str, a200: str = "1 0 0 2 0", duration: float = 60.0) -> Machine:
    prg = tmp_path / "test.prg"
    prg.write_text(program)
    lines = (EXAMPLES / "clm" / "roll_feed.par").read_text().splitlines()
    axis1 = {line[2:4]: line[4:] for line in lines if line.startswith("A1")}
    out = []
    for line in lines:
        if line.startswith("A2"):
            line = "A2" + line[2:4] + axis1[line[2:4]]  # axis 2 = a copy of axis 1
        if line.startswith("A200"):
            line = "A200 " + a200
        if line.startswith("B000"):
            line = "B000 1 0 0"
        out.append(line)
    (tmp_path / "test.par").write_text("\n".join(out) + "\n")
    text = roll_feed_text(prg, tmp_path / "test.par")
    block = text[text.index("[[axis]]"):text.index("[io]")]
    text = text.replace(block, block + block.replace('name = "feed"', 'name = "slave"'))
    text = text.replace('axes = ["feed"]', 'axes = ["feed", "slave"]')
    text = text.replace("duration = 60.0", f"duration = {duration}")
    path = tmp_path / "m.toml"
    path.write_text(text)
    return Machine.from_file(path)


def cycles(m: Machine, seconds: float, probe=None) -> list:
    out = []
    for _ in range(round(seconds / m.period)):
        m.scheduler.run_cycle()
        if probe is not None:
            out.append(probe(m))
    return out


def test_slave_follows_master_travel_times_factor_exactly(tmp_path):
    """Fig. 5-14 (L1961): slave travel = master travel x slave factor; mode 2 follows the master's
    actual position (L4192); 40 feeds of 250 IU = 1000 revolutions of the 10-IU roll, no drift."""
    feeds = "".join(f"{n + 2:04d} PSI 1 +000250.000 999\n" for n in range(40))
    m = machine(tmp_path, "0000 FOL 2 1 1 0.876543\n0001 WAI 00.200\n" + feeds + "0042 JMP 0042\n")
    master, slave = m.axis("feed"), m.axis("slave")
    cycles(m, 0.2)
    m0, s0 = master.actual_position, slave.command_position
    cycles(m, 30.0)
    assert abs(master.actual_position - m0 - 10000.0) < 0.1
    assert abs((slave.command_position - s0) - 0.876543 * (master.actual_position - m0)) < 1e-6
    assert abs(slave.actual_position - slave.command_position) < 0.01
    assert m.device.rt.modes.fault_error is None


def test_synchronous_axis_follows_the_set_point(tmp_path):
    """Ax00 mode 1 (L4190): 'the same movements as the master axis' -> its set point, exactly."""
    m = machine(tmp_path, "0000 PSI 1 +000250.000 999\n0001 PSI 1 -000100.000 500\n0002 JMP 0002\n", a200="1 0 0 1 0")
    master, slave = m.axis("feed"), m.axis("slave")
    cycles(m, 0.05)
    m0, s0 = master.command_position, slave.command_position
    diffs = cycles(m, 2.0, lambda m: (slave.command_position - s0) - (master.command_position - m0))
    assert max(abs(d) for d in diffs) < 1e-9
    assert abs(master.command_position - m0 - 150.0) < 1e-6


def test_mode_2_ramps_on_and_off(tmp_path):
    """L1973: 'the slave axis accelerates or decelerates using an acceleration ramp' (Ax08 5000
    IU/s^2 at ACC 000); mode 1 steps (L1971)."""
    program = ("0000 FOL 2 0 1 1.000000\n0001 CON 1 1 +500\n0002 WAI 01.000\n0003 FOL 2 1 2 1.000000\n"
               "0004 WAI 01.000\n0005 FOL 2 0 2 1.000000\n0006 WAI 01.000\n0007 FOL 2 1 1 1.000000\n0008 JMP 0008\n")
    m = machine(tmp_path, program, a200="1 0 0 1 0")  # the master's set point: no encoder noise
    slave = m.axis("slave")
    task = m.device.rt.tasks[0]
    rec = cycles(m, 3.8, lambda m: (task.pc, slave.command_velocity, slave.command_acceleration))
    on = [(v, a) for pc, v, a in rec if pc == 4]
    off = [(v, a) for pc, v, a in rec if pc == 6]
    assert max(abs(a) for v, a in on + off) <= 5000 * 1.001
    assert abs(on[-1][0] - 250.0) < 1e-6 and 0 < on[1][0] < 250.0 - 1
    assert off[-1][0] == 0.0 and 0 < off[1][0] < 250.0
    step = [v for pc, v, a in rec if pc == 8]
    assert abs(step[1] - 250.0) < 1e-6  # mode 1: no ramp


def test_factor_change_resynchronizes(tmp_path):
    """L1975: mode 2 factor change -> re-synchronization with the acceleration ramp; M1.20.0 'Axis 2
    synchronous' is 0 during the ramp, 1 when synchronous again."""
    program = ("0000 FOL 2 1 2 1.000000\n0001 CON 1 1 +500\n0002 WAI 01.000\n0003 FOL 2 1 2 1.500000\n"
               "0004 WAI 01.000\n0005 JMP 0005\n")
    m = machine(tmp_path, program, a200="1 0 0 1 0")
    slave = m.axis("slave")
    task = m.device.rt.tasks[0]
    image = m.device.memory.image
    from axisline.devices.clm.operands import Operand

    rec = cycles(m, 2.5, lambda m: (task.pc, slave.command_velocity, slave.command_acceleration, image.get(Operand("M", 1, 20, 0))))
    after = [r for r in rec if r[0] == 4]
    assert abs(after[-1][1] - 375.0) < 1e-6 and after[-1][3] == 1
    assert any(r[3] == 0 for r in after) and max(abs(r[2]) for r in after) <= 5000 * 1.001


def test_poi_on_the_slave_adds(tmp_path):
    """L1965 'Other programmed positioning motions of the slave axis ... are additive in terms of
    velocity': PSI 2 +100 while following a running master; only the slave moves (L3487)."""
    program = ("0000 CON 1 1 +500\n0001 WAI 00.500\n0002 PSI 2 +000100.000 500\n0003 AEA Q1.00.1 1\n"
               "0004 CON 1 0 +000\n0005 JMP 0005\n")
    m = machine(tmp_path, program)
    master, slave = m.axis("feed"), m.axis("slave")
    cycles(m, 0.05)  # at rest, before the program starts (0.1 s)
    m0, s0 = master.actual_position, slave.command_position
    rec = cycles(m, 3.2, lambda m: slave.command_velocity - master.actual_velocity)
    assert m.device.rt.tasks[0].pc == 5
    # (the gear reads the master actual of the cycle before: at rest it may differ by one count)
    assert abs((slave.command_position - s0) - (master.actual_position - m0) - 100.0) <= 1 / 409.6 + 1e-9
    assert max(rec) > 200.0  # the own move at 50 % of Ax06 on top of the following


def test_fol_on_a_normal_axis_does_nothing(tmp_path):
    """L3489 'The FOL command is only effective if Slave Axis / Synchronous Axis Mode is enabled'
    -> no function, the program goes on after one cycle (slave.py decision 3)."""
    m = machine(tmp_path, "0000 FOL 1 1 2 2.000000\n0001 PSI 1 +000100.000 999\n0002 JMP 0002\n")
    cycles(m, 1.0)
    assert m.device.rt.modes.fault_error is None
    assert abs(m.axis("feed").actual_position - 100.0) < 0.1


def test_defaults_and_manual_automatic_keep_fol(tmp_path):
    """L1967-1969: a mode change keeps on/off and factor; clearing an error restores mode 1, factor 1."""
    m = machine(tmp_path, "0000 FOL 2 0 2 1.500000\n0001 JMP 0001\n")
    cycles(m, 0.3)
    f = m.device.rt.axes[2].follower
    assert (f.on, f.ramped, f.factor) == (False, True, 1.5)
    m.device.rt.axes[2].reset_defaults()  # what a Manual <-> Automatic change does to an axis
    assert (f.on, f.factor) == (False, 1.5)
    m.device.rt.axes[2].clear_fault()
    assert (f.on, f.ramped, f.factor) == (True, False, 1)
