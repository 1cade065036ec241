"""The CLM1.4 flying cutoff on the simulated plant (manual §7.12 L3858-4030, LML L2119-2131,
EOS L1905-1911, Status 54 L7250-7266): examples/flying_cutoff_clm.toml, a punch on a carriage
over a strip measured by a wheel (master encoder 1). Decisions: src/axisline/devices/clm/cutoff.py."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from axisline.devices.clm.cutoff import APPROACH, RETURNING, SYNC
from axisline.devices.clm.status import status_body
from axisline.machine import Machine

from .clmrig import Rig, with_parameters

EXAMPLES = Path(__file__).resolve().parents[3] / "examples"
PROGRAM = (EXAMPLES / "clm" / "flying_cutoff.prg").read_text()
COUNTS = 20.0  # carriage encoder counts per mm (examples/flying_cutoff_clm.toml)
CONSTANT_500 = '[\n  { time = 0.0, speed = 500.0, acceleration = 500.0 },\n]'
LINE_AT_1000 = '[\n  { time = 0.0, speed = 1000.0, acceleration = 1e9 },\n]'  # at speed from the start


def machine(tmp_path: Path, program: str = PROGRAM, params: dict[str, str] | None = None, *,
            profile: str | None = None, auto_io: bool = False) -> Machine:
    """examples/flying_cutoff_clm.toml with `program`, its parameters changed by `params`, and
    the strip's speed profile replaced by `profile` (a TOML array); auto_io: the Automatic input
    I0.00.1 wired to the io input "auto" (m.io.set_input("auto", ...)), Manual at first."""
    (tmp_path / "t.prg").write_text(program)
    par = (EXAMPLES / "clm" / "flying_cutoff.par").read_text()
    (tmp_path / "t.par").write_text(with_parameters(par, params or {}))
    text = (EXAMPLES / "flying_cutoff_clm.toml").read_text()
    text = text.replace('program = "clm/flying_cutoff.prg"', f'program = "{(tmp_path / "t.prg").as_posix()}"')
    text = text.replace('parameters = "clm/flying_cutoff.par"', f'parameters = "{(tmp_path / "t.par").as_posix()}"')
    if profile is not None:
        start = text.index("profile = [")
        end = text.index("]\n", start) + 1
        text = text[:start] + "profile = " + profile + text[end:]
    if auto_io:
        text = text.replace('inputs = ["punch_down"]', 'inputs = ["punch_down", "auto"]')
        text = text.replace('"I1.00.0" = "punch_down"', '"I1.00.0" = "punch_down"\n"I0.00.1" = "auto"')
    path = tmp_path / "m.toml"
    path.write_text(text)
    return Machine.from_file(path)


def run_cuts(m: Machine, n: int, limit_s: float = 80.0, each=None) -> list[dict]:
    """Run until `n` cuts are measured (the punch signal's rising edges); returns the records."""
    cycles = int(limit_s / m.period)
    for _ in range(cycles):
        m.scheduler.run_cycle()
        dev = m.device
        assert dev.rt.modes.fault_error is None, dev.rt.modes.fault_error
        if each is not None:
            each(m)
        if dev.meter is not None and len(dev.meter.records) >= n:
            return dev.meter.records
    raise AssertionError(f"only {len(m.device.meter.records) if m.device.meter else 0} cuts in {limit_s} s")


def test_consecutive_pieces_have_the_programmed_length(tmp_path):
    """Decision 3 and the issue's quality bar: at constant line speed every piece of Fig. 7-20
    (L3896-3921, LML 1 001000.000) is 1000 mm on the strip within 2 carriage encoder counts, the
    first one too (it counts from the point under the tool when Automatic came)."""
    m = machine(tmp_path, profile=CONSTANT_500)
    cuts = run_cuts(m, 8)
    for c in cuts:
        assert c["target_length"] == 1000.0
        assert abs(c["error_counts"]) <= 2.0, c
    assert [c["constant_speed"] for c in cuts[1:]] == [True] * 7


def test_fig_7_20_cuts_product_1_then_product_2(tmp_path):
    """Fig. 7-20 (L3899-3923; its lines 0000-0009 are Fig. 7-19's 5-instruction groups,
    L3871-3885): BAC 0000 counts the 1000 mm pieces of product 1 (100), then BAC 0005 the 2000
    mm pieces of product 2 (200), JMP 0000 starts again. The counts shortened to 3 and 2 (the
    listing otherwise): 1000, 1000, 1000, 2000, 2000, 1000, ... each within 2 counts."""
    program = PROGRAM.replace("BAC 0000 +0000 00100", "BAC 0000 +0000 00003").replace("BAC 0005 +0000 00200", "BAC 0005 +0000 00002")
    cuts = run_cuts(machine(tmp_path, program, profile=CONSTANT_500), 7)
    assert [c["target_length"] for c in cuts] == [1000.0] * 3 + [2000.0] * 2 + [1000.0] * 2
    assert max(abs(c["error_counts"]) for c in cuts) <= 2.0


def test_lml_meets_the_cut_point_at_line_speed(tmp_path):
    """Decision 1 (L3866, L2123 "If the carriage is in synchronous motion with the material, the
    program proceeds"): when LML lets the program go on, the carriage's set point runs at the
    strip's speed and the tool is over the cut point (previous cut + 1000 mm) to the count."""
    seen = []

    def watch(m: Machine) -> None:
        c = m.device.rt.cutoff
        if c is not None and c.state == SYNC and not seen:
            clm = c.axis
            seen.append((clm.axis.command_velocity, c.master.velocity, c.master.exact_position - clm.axis.command_position,
                         c.target, c.gear.slave_sync_position))

    run_cuts(machine(tmp_path, profile=CONSTANT_500), 1, each=watch)
    v_carriage, v_line, point, target, s_sync = seen[0]
    assert v_carriage == pytest.approx(v_line, rel=1e-6) and v_line == pytest.approx(500.0, rel=1e-3)
    assert float(point) == pytest.approx(float(target), abs=1.0 / COUNTS)
    assert s_sync == pytest.approx(500.0**2 / (2 * 10000.0), rel=1e-2)  # v^2 / (2 A108): one ramp


def test_pieces_stay_in_length_while_the_line_ramps(tmp_path):
    """The example's strip speeds up from 30 to 60 m/min and slows to 24 m/min (0.5 m/s^2): the
    gear in position plans in the master domain, so pieces cut in a ramp stay within 2 counts."""
    cuts = run_cuts(machine(tmp_path), 20)
    ramps = [c for c in cuts if not c["constant_speed"]]
    assert len(ramps) >= 3
    assert max(abs(c["error_counts"]) for c in cuts) <= 2.0


def test_eos_returns_home_at_a106(tmp_path):
    """Decision 4 (L3866 "moves to its original position at maximum speed"): after EOS the
    carriage is positioned to 0 at A106 (2000 mm/s) and reaches it; the next LML waits for it."""
    states = []

    def watch(m: Machine) -> None:
        c = m.device.rt.cutoff
        if c is not None and c.state == RETURNING and (not states or states[-1][0] != RETURNING):
            states.append((RETURNING, c.axis.speed, c.axis.target))
        elif c is not None and c.state == APPROACH and states and states[-1][0] == RETURNING:
            states.append((APPROACH, c.axis.command_position, c.axis.axis.command_velocity))

    run_cuts(machine(tmp_path, profile=CONSTANT_500), 2, each=watch)
    assert states[0] == (RETURNING, 2000.0, 0.0)
    assert states[1][0] == APPROACH and states[1][1] == pytest.approx(0.0, abs=1e-9)


def test_a_late_carriage_catches_up_the_cut_point(tmp_path):
    """Decision 2 (L3866 "Any fine adjustment of the position to the exact processing location"):
    the strip already runs at 60 m/min when Automatic comes and the first piece is 50 mm: the
    plain ramp (48.8 mm of stroke) would meet the material too late, so the sync stroke grows and
    the carriage, faster than the strip, still meets the cut point: 50 mm within 2 counts, then
    the 1000 mm pieces."""
    program = PROGRAM.replace("LML 1 001000.000", "LML 1 000050.000").replace("BAC 0000 +0000 00100", "BAC 0000 +0000 00001") \
        .replace("LML 1 002000.000", "LML 1 001000.000")
    gears = []

    def watch(m: Machine) -> None:
        c = m.device.rt.cutoff
        if c is not None and c.gear is not None and (not gears or gears[-1] is not c.gear):
            gears.append(c.gear)

    cuts = run_cuts(machine(tmp_path, program, profile=LINE_AT_1000), 3, each=watch)
    assert [c["target_length"] for c in cuts] == [50.0, 1000.0, 1000.0]
    minimum = 1000.0**2 / (2 * 10000.0)  # v^2 / (2 A108)
    assert gears[0].slave_sync_position > minimum + 10.0  # the first one caught up
    assert gears[1].slave_sync_position == pytest.approx(minimum, rel=0.02)  # the next ones need not
    assert max(abs(c["error_counts"]) for c in cuts) <= 2.0


def test_a_piece_too_short_for_the_stroke_is_47(tmp_path):
    """Decision 2: 300 mm pieces at 60 m/min: the carriage is home again only after the cut point
    of the next piece has passed further than A104 (400 mm) of stroke can make up: fault 47
    "Max Travel Lmt 1", naming the length, instead of a long piece."""
    program = PROGRAM.replace("LML 1 001000.000", "LML 1 000300.000")
    m = machine(tmp_path, program, profile=LINE_AT_1000)
    for _ in range(int(4.0 / m.period)):
        m.scheduler.run_cycle()
        if m.device.rt.modes.fault_error is not None:
            break
    error = m.device.rt.modes.fault_error
    assert error is not None and error.code == "47" and "300.000" in error.detail


def test_tool_width_is_added_to_the_length(tmp_path):
    """Decision 9 (L2127, L4022): A141 = 05.00: the cut points are 1005 mm apart, so the piece
    less the 5 mm kerf is the programmed 1000 mm."""
    m = machine(tmp_path, params={"A141": "05.00"}, profile=CONSTANT_500)
    cuts = run_cuts(m, 4)
    points = [c["material_point"] for c in cuts]
    assert points[2] - points[1] == pytest.approx(1005.0, abs=0.1)
    assert max(abs(c["error_counts"]) for c in cuts) <= 2.0


def test_processing_program_without_eos_is_35(tmp_path):
    """Decision 5 (L1908 "A processing program must always end with this command"): a cutoff
    program that returns (RTS) while the carriage is still synchronous is error 35."""
    program = PROGRAM.replace("1006 EOS", "1006 NOP") + "1100 EOS\n"
    m = machine(tmp_path, program, profile=CONSTANT_500)
    for _ in range(int(6.0 / m.period)):
        m.scheduler.run_cycle()
        if m.device.rt.modes.fault_error is not None:
            break
    assert m.device.rt.modes.fault_error.code == "35"


def test_length_counters_and_status_54(tmp_path):
    """Decision 8 (L3990-3994, L7250-7266): the material and the product length counters follow
    the wheel (Automatic: both); Status 54 gives them in whole IU; !sCLL1 / !sCLL2 clear one each."""
    from axisline.devices.clm.serial import ClmSerialEndpoint
    from axisline.devices.clm.telegram import emit

    m = machine(tmp_path, profile=CONSTANT_500)
    run_cuts(m, 1)
    rt = m.device.rt
    c = rt.cutoff
    wheel = float(rt.master_encoder.position)
    assert float(c.material_length) == pytest.approx(wheel, abs=1e-9)
    assert c.product_length == c.material_length
    body = status_body(rt, 54, [])
    assert body == f"54 +{int(c.material_length):08d} +{int(c.product_length):08d} "
    ep = ClmSerialEndpoint(rt, lambda: True)
    assert ep.feed(emit("!", 0, "", "CLL1 ", True).encode("ascii")) == b"Y\r\n"
    assert c.material_length == 0 and c.product_length > 0
    assert ep.feed(emit("!", 0, "", "CLL2 ", True).encode("ascii")) == b"Y\r\n"
    assert c.product_length == 0


# -- the mode rules on the runtime alone (clmrig: no plant) ------------------------------------------

CUTOFF = {"A100": "0 0 0 5 1", "A111": "01.00 1", "A109": "000 000", "A127": "00.00.0 0000.100"}
LOOP = "0000 NOP\n0001 NOP\n0005 NOP\n0006 LML 1 001000.000\n0007 EOS\n0008 JMP 0005\n"


def test_automatic_away_from_home_is_36():
    """Decision 6 (L3931, spec §4.12): switching to Automatic with the carriage 5 mm from home is
    error 36 "Not Homeposition"; within A127's threshold it starts."""
    r = Rig(LOOP, params=CUTOFF, mode="manual")
    r.run()
    r.axes[1].actual_position = 5.0
    r.set_mode("automatic")
    r.run()
    assert r.fault == "36"
    r2 = Rig(LOOP, params=CUTOFF, mode="manual")
    r2.run()
    r2.axes[1].actual_position = 0.05
    r2.axes[1].threshold = 0.1  # A127
    r2.set_mode("automatic")
    r2.run()
    assert r2.fault is None and r2.rt.modes.running


def test_auto_start_at_the_old_length_instruction_minus_1():
    """Decision 7 (L3929-3931, L4955-4962): no Start needed (and Start / Immediate Stop do
    nothing); after Manual the program goes on at the last length instruction minus 1 (0005
    for the LML at 0006); with A138 "always 0000", or after !sCL0 in Manual, at 0000."""
    r = Rig(LOOP, params=CUTOFF, mode="manual")
    r.run()
    r.set_mode("automatic")
    r.run(10)
    assert r.rt.modes.running and r.rt.tasks[0].pc == 6  # no master encoder: LML waits
    r.set("I0.00.4", 0)  # Immediate Stop: no function
    r.run(2)
    assert r.rt.modes.running and r.rt.tasks[0].running
    r.set("I0.00.4", 1)
    r.set_mode("manual")
    r.run()
    r.set_mode("automatic")
    r.run()
    assert r.rt.tasks[0].running and r.rt.tasks[0].pc in (5, 6)
    assert r.rt.cutoff.length_instruction == 6
    r.set_mode("manual")
    r.run()
    r.rt.cutoff.start_at_zero = True  # what !sCL0 in Manual does
    r.set_mode("automatic")
    r.run()
    assert r.rt.tasks[0].pc in (0, 1)
    always = Rig(LOOP, params={**CUTOFF, "A138": "00.00.0 1 0"}, mode="manual")
    always.run()
    always.set_mode("automatic")
    always.run(10)
    always.set_mode("manual")
    always.run()
    always.set_mode("automatic")
    always.run()
    assert always.rt.tasks[0].pc in (0, 1)


def test_commands_forbidden_on_axis_1_are_0a():
    """L3944-3947: PSA on axis 1 in flying cutoff stops the program with 0A (check.py warns
    at load already)."""
    r = Rig("0000 NOP\n0001 PSA 1 +000010.000 999\n0002 JMP 0002\n", params=CUTOFF, mode="manual")
    r.run()
    r.set_mode("automatic")
    r.run(4)
    assert r.fault == "0A"


def test_run_json_reports_every_cut_in_the_fs701_names(tmp_path):
    """The issue: `axisline run examples/flying_cutoff_clm.toml --json OUT` has the FS701's cut
    names, lengths measured on the simulated strip, and the same summary keys; --report has the
    FS701's cut table and figures."""
    from typer.testing import CliRunner

    from axisline.cli import app

    out = tmp_path / "cut.json"
    report = tmp_path / "report"
    result = CliRunner().invoke(app, ["run", str(EXAMPLES / "flying_cutoff_clm.toml"), "--json", str(out), "--report", str(report), "--quiet"])
    assert result.exit_code == 0, result.output
    # the report: the FS701's cut table and figures (axisline.report.cuts)
    text = (report / "report.md").read_text()
    assert "### Flying cutoff: every cut measured on the material" in text and "| 24 |" in text
    assert (report / "clm_length_error.png").stat().st_size > 0 and (report / "clm_error_histogram.png").exists()
    d = json.loads(out.read_text())
    assert len(d["cuts"]) == 24 and d["summary"]["count"] == 24
    for c in d["cuts"]:
        assert {"target_lu", "actual_lu", "error_lu", "error_counts", "line_speed_lu_min", "max_pos_error_counts"} <= set(c)
        assert c["target_lu"] == 1000.0 and abs(c["error_counts"]) <= 2.0
    assert {"count", "mean_error_lu", "max_abs_error_counts", "cuts_per_minute"} <= set(d["summary"])
    assert d["summary"]["cuts_per_minute"] > 20


def test_poi_on_axis_1_runs_at_a106(tmp_path):
    """L3947 ("the maximum velocity (Parameter A106) is always used as the feedrate") and L3933
    (feedforward always on although A111 says 0): POI 1 +50 at 010 per mille runs at 2000 mm/s."""
    program = "0000 NOP\n0001 POI 1 +000050.000 010\n0002 NOP\n0003 JMP 0002\n1000 EOS\n"
    m = machine(tmp_path, program, params={"A111": "05.00 0"}, profile=CONSTANT_500)
    for _ in range(5):
        m.scheduler.run_cycle()
    clm = m.device.rt.axes[1]
    assert clm.speed == 2000.0 and clm.loop._ff_on


def test_start_and_stop_over_the_interface_are_not_accepted():
    """L3949 ("Interface commands 'Program Start' and 'Program Stop' are not allowed via the
    interface"): in flying cutoff !START and !STOP are answered 18 "Not accepted" and change
    nothing."""
    from axisline.devices.clm.serial import ClmSerialEndpoint
    from axisline.devices.clm.telegram import emit

    r = Rig(LOOP, params=CUTOFF, mode="manual")
    r.run()
    r.set_mode("automatic")
    r.run(3)
    ep = ClmSerialEndpoint(r.rt)
    for command in ("STOP ", "START "):
        reply = ep.feed(emit("!", 0, "", command, True).encode("ascii")).decode("ascii")
        assert reply.startswith("X 01 18"), reply
    assert r.rt.modes.running and r.rt.tasks[0].running
