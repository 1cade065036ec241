"""CLM rotary table and rotary axis (manual §7.7 L3501-3655, RTM L2468-2486, SAC L2502-2584,
Ax05 L4340-4353; errata §3.10) on the simulated plant (examples/rotary_table_clm.toml: 360
degrees per table revolution, incremental encoder on the motor, gear 590:1)."""

from __future__ import annotations

import json
from fractions import Fraction

import pytest
from typer.testing import CliRunner

from axisline.cli import app
from axisline.devices.clm.errors import ClmError
from axisline.devices.clm.files import read_program_text

from .test_homing import EXAMPLES, HOME, fault, run_until, table

IUT = 360


def test_manual_rotary_table_calculation_example(tmp_path):
    """L3612-3655 (Figs. 7-12..7-15): absolute encoder 1024 lines x 256 revolutions, gear 256:1,
    motor gear 80:1, 1500 RPM at 10 V, 3600 IU (0.1 degree) per table revolution, 17.5 rad/s^2:
    A101 = 3600 / 256 = 14.0625; A112 = 1500 x 256 / 80 = 4800 RPM; A106 = 4800 / 60 x 14.0625 =
    1125 IU/s (the maximum A106 accepts); A108 = 17.5 x 360 / 2 pi = 1002.7 deg/s^2 = 10027 IU/s^2;
    IUT = feed constant x ratio = 3600 (Fig. 7-6), A119 = 01024 0256 (L3529-3531)."""
    a101 = Fraction(3600, 256)
    assert a101 == Fraction("14.0625")
    a112 = Fraction(1500 * 256, 80)
    assert a112 == 4800
    assert a112 / 60 * a101 == 1125
    import math

    assert round(17.5 * 360 / (2 * math.pi), 1) == 1002.7 and round(17.5 * 3600 / (2 * math.pi)) == 10027
    params = {"A101": "0014.06250", "A102": "0000 0000", "A112": "04800 10.0", "A106": "001125.000", "A108": "010027",
              "A107": "000100.000", "A119": "01024 0256", "A120": "0 2 24 1", "A125": "+00010.000"}
    m = table(tmp_path, HOME, params=params)
    p = m.device.memory.parameters
    assert not p.errors(), p.errors()
    clm = m.device.rt.axes[1]
    assert clm.iut == 3600 and clm.homed  # an absolute encoder is its own reference
    assert clm._full_speed == 1125.0  # Ax12 RPM / 60 x Ax01 = the maximum A106


def test_360_over_590_does_not_drift_over_a_million_revolutions(tmp_path):
    """Fig. 7-10 (L3585-3589): feed constant = 360 / 590 = 0.610169491 (printed rounded). Kept
    exact: 10^6 table revolutions of POI +360 land exactly on 10^6 x 590 x 4096 increments and on
    table position 0; the printed constant (or summing it) would drift (decision 20)."""
    m = table(tmp_path, HOME)
    clm = m.device.rt.axes[1]
    assert clm._feed == Fraction(360, 590) and clm.iut == 360
    assert clm._increment == Fraction(360, 590 * 4096)
    clm.homed = True
    n = 1_000_000
    for _ in range(n):
        clm.position_incremental(360_000, 999)  # the drive is off: the target is taken, exact
    assert clm.exact_target == 360 * n
    assert clm.exact_target / clm._increment == n * 590 * 4096  # an integer count: no drift
    assert clm.table_target == 0
    assert abs(0.610169491 * 590 * n - 360 * n) > 0.1  # the printed constant: 0.3 degree off after 10^6 revolutions


def test_shortest_way_on_the_plant(tmp_path):
    """L3601-3603 with Ax05 = 1 (shortest path, L4344): from the home position 350 (Ax25 = +10),
    POA 90 turns +100, 45 turns -45, 315 turns -90 (through 0), 0 turns +45 (through 360); the
    table arrives within the Ax27 window every time (examples/clm/rotary_table.prg)."""
    m = table(tmp_path, (EXAMPLES / "clm" / "rotary_table.prg").read_text())
    rt = m.device.rt
    moves = []
    rt.on_move, hook = (lambda axis, task: (moves.append(axis.exact_target), hook(axis, task))), rt.on_move
    run_until(m, 30.0, lambda m: m.device.finished)
    assert fault(m) is None
    steps = [b - a for a, b in zip([Fraction(-10)] + moves, moves)]
    assert [round(float(s), 6) for s in steps[:4]] == [100.0, -45.0, -90.0, 45.0]
    assert [s % 360 for s in moves[:4]] == [90, 45, 315, 0]
    assert moves[-1] == 360 and steps[4:] == [45] * 8
    records = m.device.records
    assert [round(r["target"], 6) for r in records[:4]] == [90.0, 45.0, 315.0, 0.0]
    assert max(abs(r["error"]) for r in records) <= 0.010  # A127: position reached within 0.01 degree


def test_programmed_direction_and_target_range(tmp_path):
    """Decision 21: programmed direction (RTM 2): the sign is the direction, the magnitude the
    target; shortest way: a target must lie in 0..IUT (L3603), else 50 / 51."""
    m = table(tmp_path, HOME)
    clm = m.device.rt.axes[1]
    clm.homed = True
    clm.set_table_mode(2)
    clm.position_absolute(90_000, 999)
    assert clm.exact_target == 90
    clm.position_absolute(-45_000, 999)  # 45 backwards
    assert clm.exact_target == 45
    clm.position_absolute(30_000, 999)  # 30 forwards: through 360
    assert clm.exact_target == 390
    clm.position_absolute(-30_000, 999)  # already there
    assert clm.exact_target == 390
    clm.set_table_mode(1)
    clm.position_absolute(200_000, 999)  # shortest from 30: -190 > 180, so +170
    assert clm.exact_target == 560
    with pytest.raises(ClmError) as e:
        clm.position_absolute(-10_000, 999)
    assert e.value.code == "50"
    with pytest.raises(ClmError) as e:
        clm.position_absolute(360_001, 999)
    assert e.value.code == "51"


def test_rtm_and_ax05_codes(tmp_path):
    """RTM (L2472-2484) 1 shortest, 2 programmed, 0 Ax05, > 2 no change; Ax05 (L4344) 0
    programmed, 1 shortest; RTM needs a reference (48); an error acknowledge restores Ax05."""
    m = table(tmp_path, HOME)
    clm = m.device.rt.axes[1]
    assert clm.shortest_way  # A105 direction digit 1
    with pytest.raises(ClmError) as e:
        clm.set_table_mode(2)
    assert e.value.code == "48"
    clm.homed = True
    clm.set_table_mode(2)
    assert not clm.shortest_way
    clm.set_table_mode(7)
    assert not clm.shortest_way
    clm.set_table_mode(0)
    assert clm.shortest_way
    clm.set_table_mode(2)
    clm.clear_fault()
    assert clm.shortest_way


def _axis(tmp_path, motion_type: int, **params):
    m = table(tmp_path, HOME, params={"A100": f"0 0 0 0 {motion_type}", **params})
    return m, m.device.rt.axes[1]


@pytest.mark.parametrize("motion_type", [1, 2])
def test_sac_on_a_linear_axis_or_table_needs_a_reference(tmp_path, motion_type):
    """Figs. 5-23 / 5-24 (L2544-2584): not homed, modes 0 and 1 -> 'Axis not homed' (48); mode 9
    no function; homed: mode 0 offsets against the initial frame, mode 1 sets the target's
    coordinate, mode 9 no function (decision 23)."""
    m, clm = _axis(tmp_path, motion_type)
    for mode in (0, 1):
        with pytest.raises(ClmError) as e:
            clm.set_counter(mode, 10_000)
        assert e.value.code == "48"
    clm.set_counter(9, 0)
    clm.homed = True
    clm.set_counter(0, 10_000)
    assert clm.actual_position == pytest.approx(10.0)
    clm.set_counter(0, 10_000)  # relative to the initial frame: not +20
    assert clm.actual_position == pytest.approx(10.0)
    clm.set_counter(1, 0)
    assert clm.actual_position == pytest.approx(0.0)
    clm.set_counter(9, 0)
    assert clm.homed
    clm.clear_fault()  # the initial coordinate system again (L2510)
    assert clm.actual_position == pytest.approx(0.0) and clm._sac_shift == 0


def test_sac_on_a_rotary_axis_homes_it(tmp_path):
    """Fig. 5-22 (L2516-2540): a rotary axis (type 0) not homed: SAC 0/1 sets the actual position
    and homes the axis; homed: mode 9 cancels the reference, actual 0 (a program on the plant:
    V100 reads the position)."""
    program = ("0000 SAC 1 0 +000010.000\n0001 SET V700 = +V100\n0002 NOP\n0003 NOP\n"
               "0004 SAC 1 9 +000000.000\n0005 SET V701 = +V100\n0006 JST 0006\n")
    m, clm = _axis(tmp_path, 0)
    (tmp_path / "t.prg").write_text(program)
    from axisline.machine import Machine

    m = Machine.from_file(tmp_path / "m.toml")
    clm = m.device.rt.axes[1]
    seen = []
    run_until(m, 5.0, lambda m: (seen.append(clm.homed) if m.device.rt.tasks[0].pc == 2 and len(seen) == 0 else None) or m.device.finished)
    v = m.device.memory.variables
    assert fault(m) is None
    assert seen == [True]
    assert v[700] / 1e6 == pytest.approx(10.0, abs=0.01)
    assert v[701] / 1e6 == pytest.approx(0.0, abs=0.01) and not clm.homed


def test_sac_mode_and_controlled_axis_are_1b(tmp_path):
    """L2510 / spec §3.6: a mode other than 0, 1, 9 -> 1B (refused when the program is read); an
    Ax20 controlled axis -> 1B."""
    _, findings = read_program_text("0000 SAC 1 2 +000000.000\n")
    assert [f.code for f in findings if f.is_error] == ["1B"]
    m, clm = _axis(tmp_path, 0, A120="0 3 00 1")
    with pytest.raises(ClmError) as e:
        clm.set_counter(0, 0)
    assert e.value.code == "1B"


def test_rotary_table_example_runs_and_reports(tmp_path):
    """examples/rotary_table_clm.toml with `axisline run`: homed, 12 stations, each index error
    within the A127 window of 0.010 degree; the report lists the stations within 0..360."""
    r = CliRunner().invoke(app, ["run", str(EXAMPLES / "rotary_table_clm.toml"), "--json", str(tmp_path / "r.json"),
                                 "--report", str(tmp_path / "rep"), "--quiet"])
    assert r.exit_code == 0, r.output
    summary = json.loads((tmp_path / "r.json").read_text())
    text = json.dumps(summary)
    assert '"fault": null' in text
    report = (tmp_path / "rep" / "report.md").read_text()
    assert "| 3 |" in report and "315.0000" in report and "| 12 |" in report
