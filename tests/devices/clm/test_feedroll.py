"""Open Feed Roll (electrical release) of the CLM on the simulated plant: manual §7.10
L3805-3818, Ax30 L4810-4820. Decisions: src/axisline/devices/clm/feedroll.py."""

from __future__ import annotations

from pathlib import Path

import pytest

from axisline.devices.clm.operands import parse_operand
from axisline.machine import Machine

from .clmrig import with_parameters, run_to as run

EXAMPLES = Path(__file__).resolve().parents[3] / "examples"
OPEN = parse_operand("I1.00.4", bit=True)  # A130's input (unwired: the test sets it)
ENABLED = parse_operand("Q1.00.3", bit=True)  # A130's output "Open Feed Roll Enabled"
DRIFT = 0.02 * 50.0  # the amplifier's 0.02 V offset at 50 mm/s per volt: mm/s with 0 V commanded


def machine(tmp_path: Path, program: str) -> Machine:
    """examples/measuring_wheel_clm.toml as a normal feed axis (A100 mode 0) with A130 and an
    amplifier offset of 0.02 V, so that the open roll drifts."""
    (tmp_path / "t.prg").write_text(program)
    par = with_parameters((EXAMPLES / "clm" / "measuring_wheel.par").read_text(), {"A100": "0 0 0 0 0", "A130": "I1.00.4 Q1.00.3"})
    (tmp_path / "t.par").write_text(par)
    text = (EXAMPLES / "measuring_wheel_clm.toml").read_text()
    text = text.replace('program = "clm/measuring_wheel.prg"', f'program = "{(tmp_path / "t.prg").as_posix()}"')
    text = text.replace('parameters = "clm/measuring_wheel.par"', f'parameters = "{(tmp_path / "t.par").as_posix()}"')
    text = text.replace("max_acceleration = 30000.0\n", "max_acceleration = 30000.0\noffset_volts = 0.02\n", 1)
    path = tmp_path / "m.toml"
    path.write_text(text)
    return Machine.from_file(path)


def test_open_feed_roll_releases_in_position(tmp_path):
    """Decision 1 (L3811 "This output is powered when the drive is in position. At the same
    time, a command value of 0 is issued. Then, it is possible that the drive may drift"): the
    input mid-feed opens the roll only once the feed is in position; then 0 V, the drive drifts,
    no lag fault; closing does not pull the roll back."""
    m = machine(tmp_path, "0000 PSI 1 +000500.000 999\n0001 JMP 0001\n")
    rt, axis = m.device.rt, m.device.rt.axes[1]
    run(m, 0.4)
    rt.image.set(OPEN, 1)
    run(m, 0.8)
    assert rt.image.get(ENABLED) == 0 and not axis.feed_roll_open  # the feed goes on
    assert 100.0 < axis.actual_position < 480.0
    while not axis.feed_roll_open and rt.cycle < 800:
        m.scheduler.run_cycle()
    opened, when = axis.actual_position, rt.cycle * m.period
    assert opened == pytest.approx(500.0, abs=0.1)  # in position (Ax27 0.05) as it opened, settling a cycle
    m.scheduler.run_cycle()
    assert rt.image.get(ENABLED) == 1 and axis.volts == 0.0
    run(m, when + 3.0)
    assert axis.actual_position - opened == pytest.approx(3.0 * DRIFT, rel=0.1)  # it drifts
    assert rt.modes.fault_error is None and axis.drive_enabled
    rt.image.set(OPEN, 0)
    closed = axis.actual_position
    run(m, when + 3.4)
    assert rt.image.get(ENABLED) == 0 and not axis.feed_roll_open
    assert axis.actual_position == pytest.approx(closed, abs=0.05)  # not pulled back to 500
    assert rt.modes.fault_error is None


def test_open_feed_roll_delays_the_feed(tmp_path):
    """Decisions 2, 3 (L3817 "While the feed rolls are open, when a feed instruction is
    encountered, motion and proceeding to the next instruction are delayed until the input
    becomes 0"): the second feed waits while the roll is open, then goes its 200 mm from where
    the roll stands."""
    m = machine(tmp_path, "0000 PSI 1 +000500.000 999\n0001 PSI 1 +000200.000 999\n0002 JMP 0002\n")
    rt, axis = m.device.rt, m.device.rt.axes[1]
    run(m, 0.3)  # the first feed runs
    rt.image.set(OPEN, 1)
    run(m, 3.0)
    assert axis.feed_roll_open and rt.tasks[0].pc == 1  # the second feed waits
    assert axis.actual_position == pytest.approx(500.0 + DRIFT * 1.7, abs=0.5)
    rt.image.set(OPEN, 0)
    m.scheduler.run_cycle()
    closed = axis.actual_position
    run(m, 4.5)
    assert rt.tasks[0].pc == 2
    assert axis.actual_position == pytest.approx(closed + 200.0, abs=0.1)
    assert rt.modes.fault_error is None

def test_open_feed_roll_holds_the_task_at_a_poi(tmp_path):
    """Decision 2 (L3817 "proceeding to the next instruction [is] delayed"): a POI, which does
    not wait for the position, waits at its instruction while the roll is open."""
    m = machine(tmp_path, "0000 PSI 1 +000500.000 999\n0001 POI 1 +000200.000 999\n0002 AEA Q1.00.1 1\n0003 JMP 0003\n")
    rt, axis = m.device.rt, m.device.rt.axes[1]
    run(m, 0.3)
    rt.image.set(OPEN, 1)
    run(m, 3.0)
    assert axis.feed_roll_open and rt.tasks[0].pc == 1 and rt.image.get(parse_operand("Q1.00.1", bit=True)) == 0
    rt.image.set(OPEN, 0)
    m.scheduler.run_cycle()
    closed = axis.actual_position
    run(m, 4.5)
    assert rt.tasks[0].pc == 3
    assert axis.actual_position == pytest.approx(closed + 200.0, abs=0.1)
