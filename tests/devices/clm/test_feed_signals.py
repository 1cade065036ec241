"""Ax29 presignaling and Ax32 velocity reached / deceleration active (manual L4788-4808,
L4833-4840; feed_signals.py) on the roll feed of examples/roll_feed_clm.toml (Ax06 = 500 mm/s,
Ax08 = 5000 mm/s^2, 2 ms NC cycle)."""

from __future__ import annotations

from pathlib import Path

from axisline.devices.clm.operands import parse_operand
from axisline.machine import Machine

from .clmrig import EXAMPLES, roll_feed_text, with_parameters

FEEDS = """\
0000 POI 1 +000100.000 400
0001 AKN Q1.00.4 1
0002 WAI 00.500
0003 POI 1 +000050.000 400
0004 JMP 0004
"""


def feed_machine(tmp_path: Path, params: dict[str, str]) -> Machine:
    par = with_parameters((EXAMPLES / "clm" / "roll_feed.par").read_text(), params)
    (tmp_path / "f.par").write_text(par)
    (tmp_path / "f.prg").write_text(FEEDS)
    (tmp_path / "m.toml").write_text(roll_feed_text(tmp_path / "f.prg", tmp_path / "f.par"))
    return Machine.from_file(tmp_path / "m.toml")


def record(m: Machine, seconds: float, *names: str) -> list[tuple[float, float, float, tuple[int, ...]]]:
    """Per cycle: (set point, target, set-point velocity, the named bits)."""
    image = m.device.memory.image
    ops = [parse_operand(n, bit=True) for n in names]
    clm = m.device.rt.axes[1]
    out = []
    for _ in range(round(seconds / m.period)):
        m.scheduler.run_cycle()
        out.append((clm.command_position, clm.target, clm.axis.command_velocity, tuple(image.get(op) for op in ops)))
    return out


def test_presignal_at_the_distance_before_the_target(tmp_path):
    """A129 Q1.00.4 0.0 0010: constant output from 10 IU before the target (decisions 1, 2);
    the program's AKN on it goes on at that moment, not at the end of the feed."""
    m = feed_machine(tmp_path, {"A129": "Q1.00.4 0.0 0010"})
    rows = record(m, 2.0, "Q1.00.4")
    first_on = next(i for i, r in enumerate(rows) if r[3][0])
    pos, target = rows[first_on][0], rows[first_on][1]
    assert target == 100.0
    # on in the NC cycle after the one whose set point came within 10 IU of the target (the NC
    # cycle sees the set point of the cycle before; one cycle at 200 mm/s covers 0.4 mm)
    before, last_away = rows[first_on - 1][0], rows[first_on - 2][0]
    assert 100.0 - before <= 10.0 < 100.0 - last_away and pos > before
    # constant signal: on until the next feed instruction (0003, after the 0.5 s wait)
    on = [r[3][0] for r in rows[first_on:]]
    second = next(i for i, r in enumerate(rows) if r[1] == 150.0)
    assert all(on[: second - first_on - 1])
    assert rows[second][3][0] == 0  # "disabled each time a new feed instruction is received"


def test_presignal_pulse_and_reset_by_the_next_feed(tmp_path):
    """A129 Q1.00.4 0.1 0010: a 0.1 s pulse (50 NC cycles of 2 ms) from 10 IU before the target,
    again before the second target (decision 3)."""
    m = feed_machine(tmp_path, {"A129": "Q1.00.4 0.1 0010"})
    rows = record(m, 2.5, "Q1.00.4")
    bits = [r[3][0] for r in rows]
    runs = []
    i = 0
    while i < len(bits):
        if bits[i]:
            j = i
            while j < len(bits) and bits[j]:
                j += 1
            runs.append((i, j - i))
            i = j
        else:
            i += 1
    assert [length for _, length in runs] == [50, 50]
    assert rows[runs[0][0]][1] == 100.0 and rows[runs[1][0]][1] == 150.0
    assert 150.0 - rows[runs[1][0] - 1][0] <= 10.0 < 150.0 - rows[runs[1][0] - 2][0]


def test_presignal_off_when_not_programmed(tmp_path):
    """A129 00.00.0 (the example's): no output; the program waits for Q1.00.4 for ever."""
    m = feed_machine(tmp_path, {})
    rows = record(m, 2.0, "Q1.00.4")
    assert not any(r[3][0] for r in rows)
    assert m.device.rt.axes[1].target == 100.0  # still waiting at 0001


def test_ax32_velocity_reached_and_deceleration(tmp_path):
    """A132 Q1.00.6 Q1.00.7 (left: Target Velocity Reached, right: Deceleration Active,
    decision 4): reached only at 400 per mille of Ax06 = 200 mm/s with no acceleration,
    deceleration only while the set point slows down; both 0 at rest."""
    m = feed_machine(tmp_path, {"A129": "Q1.00.4 0.0 0010", "A132": "Q1.00.6 Q1.00.7"})
    rows = record(m, 2.0, "Q1.00.6", "Q1.00.7")
    # the bits of a cycle describe the set point of the cycle before (the NC cycle runs first)
    pairs = list(zip(rows, rows[1:]))
    reached = [prev for prev, now in pairs if now[3][0]]
    slowing = [prev for prev, now in pairs if now[3][1]]
    assert reached and slowing
    assert all(abs(abs(r[2]) - 200.0) < 0.2 for r in reached)
    cruising = [prev for prev, now in pairs if abs(prev[2] - 200.0) < 1e-9 and prev[0] > 5.0]
    assert len(reached) >= len(cruising) > 0
    assert all(r[2] > 0.0 for r in slowing)
    first_slow = next(i for i, (prev, now) in enumerate(pairs) if now[3][1])
    assert pairs[first_slow - 1][1][3][0] == 1  # cruising right before the braking ramp
    assert all(now[3] == (0, 0) for prev, now in pairs if prev[2] == 0.0)
