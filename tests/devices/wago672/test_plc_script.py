"""The `[[device.plc]]` script: a PLC stand-in on the process image for `axisline run`.

What a user relies on: the example moves the slide through the module's process image and
the run ends with the script; a bad step or bit name is a config error naming it; a wait that
does not come true fails the run naming the step; the watchdog can be switched off for hand
tools and says so on the console when it trips; the headline says what happened.
"""

from __future__ import annotations

import csv
import tomllib
from pathlib import Path

import pytest
from typer.testing import CliRunner

from axisline.cli import app
from axisline.config import parse_machine
from axisline.configerrors import ConfigError
from axisline.devices.wago672.coupler import WATCHDOG_STATUS, WATCHDOG_TIME, pack
from axisline.devices.wago672.image import C1, OutputImage, PositioningSetpoints, S2
from axisline.kernel import WallClock
from axisline.machine import Machine

EXAMPLE = Path(__file__).resolve().parents[3] / "examples" / "wago_stepper.toml"
K = 2560.0  # microsteps per mm in the example
runner = CliRunner()

ENABLE = {"name": "enable", "set": ["Reset_Quit", "Enable", "Stop2_N"], "wait": {"Ready": True, "Stop_N_ACK": True, "Reset": False}}


def example_data(plc: list[dict] | None = None, **device) -> dict:
    data = tomllib.loads(EXAMPLE.read_text())
    if plc is not None:
        data["device"]["plc"] = plc
    data["device"].update(device)
    return data


def build(data: dict, clock=None) -> Machine:
    return Machine(parse_machine(data, "t.toml"), source="t.toml", **({"clock": clock} if clock else {}))


def problems(data: dict) -> list[str]:
    with pytest.raises(ConfigError) as e:
        build(data)
    return e.value.problems


# ---------------------------------------------------------------- the example


def test_the_example_script_runs_to_the_end_with_the_slide_at_the_last_target():
    m = Machine.from_file(EXAMPLE)
    result = m.run()
    assert result.completed and result.faults == []
    dev = m.device
    assert dev.finished is True and dev.script.failed is None
    assert dev.script.steps_done == len(dev.config.plc) == 16
    assert result.simulated_s < 60.0  # ended with the script, not at machine.duration
    module = dev.device(0)
    assert module.actual_position == 128000 and module.reference_ok  # 50 mm, referenced on the cam
    assert m.axis("x").actual_position == pytest.approx(50.0, abs=1 / K)  # within one microstep
    assert m.at_rest()
    # the PLC went through the moves in order: 100 mm, 250 mm, a jog, 50 mm
    names = [e["name"] for e in dev.script.log]
    assert names.index("at 100 mm") < names.index("at 250 mm") < names.index("jog released") < names.index("at 50 mm")
    assert dev.coupler.expiries == 0 and dev.coupler.watchdog_status == 1  # fed every PLC cycle


def test_the_example_headline_and_report_with_axisline_run(tmp_path):
    res = runner.invoke(app, ["run", str(EXAMPLE), "--report", str(tmp_path), "--quiet"])
    said = " ".join(res.output.split())
    assert res.exit_code == 0, said
    assert ("wago672: module 0 (axis x): Single positioning, referenced, at 50.000 mm; 16/16 PLC steps done; "
            "watchdog 100 ms, not tripped") in said
    assert "| 16 | at 50 mm | 0 | Start=0 |" in (tmp_path / "report.md").read_text()
    # the trace has the motion: the slide went out to 250 mm and back to 50 mm
    with open(tmp_path / "trace.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    col = next(c for c in rows[0] if c.startswith("x.actual_position"))
    pos = [float(r[col]) for r in rows]
    assert max(pos) == pytest.approx(250.0, abs=0.01) and pos[-1] == pytest.approx(50.0, abs=1 / K)
    steps = [int(float(r["wago672.plc_step"])) for r in rows]
    running = [n for n in steps if n]  # the running step (1-based; 0 once done)
    assert running == sorted(running) and running[0] == 1
    assert {4, 8, 10, 12, 16} <= set(running)  # the reference run, the three moves and the jog show in the trace


# ---------------------------------------------------------------- config errors


def test_bad_step_key_is_named_with_the_closest_key():
    found = problems(example_data([{"name": "enable", "sett": ["Enable"]}]))
    assert any(p.startswith("device.plc[0].sett: unknown key (plc 'enable'); did you mean set?") for p in found), found


def test_bad_bit_name_in_set_names_step_field_and_the_allowed_bits():
    found = problems(example_data([ENABLE, {"name": "go", "set": ["Enabel"]}]))
    assert len(found) == 1, found
    p = found[0]
    assert p.startswith("device.plc[1].set = ['Enabel'] (plc 'go'): 'Enabel' is not a control bit; did you mean Enable?")
    assert "control bits: MBX, Enable, Stop2_N, Start, M_Positioning" in p and "Reset_Quit" in p


def test_bad_bit_name_in_wait_names_the_status_bit_meant():
    found = problems(example_data([{"wait": {"Start_Ack": True}}]))
    assert any("device.plc[0].wait" in p and "'Start_Ack' is not a status bit; did you mean Start_ACK?" in p
               and "status bits: MBX, ERR, Ready" in p for p in found), found


def test_one_name_stands_for_a_list_and_wait_takes_only_names_or_levels():
    m = build(example_data([{"set": "Enable", "wait": "Ready"}]))
    step = m.device.config.plc[0]
    assert step.set == ["Enable"] and step.wait == {"Ready": True}
    found = problems(example_data([{"wait": {"Ready": "yes"}}]))
    assert found == ["device.plc[0].wait.Ready = 'yes': Input should be a valid boolean"]
    found = problems(example_data([{"wait": 5}]))
    assert found == ["device.plc[0].wait = 5: a table such as {On_Target = true, Busy = false}, or a list of status bit names"]


def test_stop1_n_is_explained_as_input1():
    found = problems(example_data([{"set": ["Stop1_N"]}]))
    assert any("Stop1_N is Input1 (DI1), not an image bit" in p and "Stop2_N" in p for p in found), found


def test_setpoint_out_of_encoding_is_a_config_error_naming_the_range():
    found = problems(example_data([{"name": "fast", "velocity": 40000}]))
    assert any(p.startswith("device.plc[0].velocity = 40000 (plc 'fast')") and "-32768 and <= 32767" in p for p in found), found
    found = problems(example_data([{"target": 2**23}]))
    assert any(p.startswith("device.plc[0].target = 8388608") and "<= 8388607" in p for p in found), found


def test_a_step_for_a_module_that_is_not_there_and_a_bit_both_set_and_cleared():
    found = problems(example_data([{"name": "two", "module": 1, "set": ["Enable"]}]))
    assert any("device.plc[0].module = 1 (step 1 'two'): no such module (allowed: 0 .. 0" in p for p in found), found
    found = problems(example_data([{"set": ["Start"], "clear": ["Start"]}]))
    assert any("Start both in set and clear" in p for p in found), found


# ---------------------------------------------------------------- failures at run time


def test_a_wait_that_times_out_fails_the_run_naming_the_step():
    m = build(example_data([ENABLE, {"name": "never started", "wait": ["Reference_OK"], "timeout_s": 0.5}]))
    result = m.run()
    assert not result.completed
    assert result.simulated_s < 1.0  # the run ends with the failed script
    fault = next(f for f in result.faults if "wago672" in f)
    assert "PLC step 2 'never started' (device.plc[1]), module 0: waited 0.5 s (timeout_s) for Reference_OK = 1; " \
           "the module shows Reference_OK = 0" in fault
    assert m.device.summary()["headline"] == ("wago672: module 0 (axis x): Idle, not referenced, at 0.000 mm; PLC stopped at step 2 "
                                              "'never started' of 2: no Reference_OK = 1 within 0.5 s (the fault says more); "
                                              "watchdog 100 ms, not tripped")


def test_a_failed_step_brakes_a_moving_drive_with_the_stop_ramp():
    data = example_data()
    data["device"]["plc"][3]["timeout_s"] = 0.2  # the reference run takes about 1.9 s
    m = build(data)
    result = m.run()
    assert not result.completed and m.device.script.failure["step"] == 4
    # the PLC's fault reaction: Stop2_N 0, the drive brakes and the run ends at rest, short of the cam
    assert result.simulated_s < 1.0 and m.at_rest()
    dev = m.device.device(0)
    assert not dev.reference_ok and dev.ready  # Enable kept: braked, not switched off


def test_axisline_run_exits_1_and_prints_the_failed_step(tmp_path):
    text = EXAMPLE.read_text().replace('wait = { Reference_OK = true, Busy = false }\ntimeout_s = 30.0',
                                       'wait = { Reference_OK = true, Busy = false }\ntimeout_s = 0.2')
    machine = tmp_path / "short.toml"
    machine.write_text(text)
    res = runner.invoke(app, ["run", str(machine), "--quiet"])
    said = " ".join(res.output.split())
    assert res.exit_code == 1
    assert "PLC step 4 'reference on the cam' (device.plc[3]), module 0: waited 0.2 s (timeout_s) for Reference_OK = 1, Busy = 0" in said


def test_module_error_fails_the_step_with_the_module_error_code():
    # velocity 0 passes the encoding but not the module: it answers Start with its error (decision 2)
    plc = [ENABLE, {"set": ["M_Positioning"], "clear": ["Reset_Quit"], "velocity": 0, "acceleration": 1000, "target": 1000,
                    "wait": ["M_Positioning_ACK"]},
           {"name": "start", "set": ["Start"], "wait": ["Start_ACK"]}]
    m = build(example_data(plc))
    result = m.run()
    assert not result.completed
    fault = next(f for f in result.faults if "wago672" in f)
    assert "PLC step 3 'start' (device.plc[2]), module 0: the module reports Error (S2.7): " in fault
    code = m.device.device(0).errors.error
    assert code and f"{code} " in fault


# ---------------------------------------------------------------- watchdog


def _move_once_then_stop_writing(m: Machine, target: int) -> None:
    """A hand tool: one write of Enable/Stop2_N/mode, one with Start, then only reads."""
    coupler = m.device.coupler
    on = C1.Enable | C1.Stop2_N | C1.M_Positioning
    data = PositioningSetpoints(20000, 4000, target)
    for c1 in (on, on | C1.Start):
        coupler.write_registers(0, pack(OutputImage.build(c1=c1, data=data).to_bytes()))
        m.scheduler.run(20)


def test_watchdog_off_a_hand_tool_may_write_once_and_the_move_completes():
    m = build(example_data([], watchdog_ms=0))  # no script: the test is the hand tool
    lines: list[str] = []
    m.device.notify = lines.append
    _move_once_then_stop_writing(m, int(5 * K))
    m.scheduler.run(2000)  # 2 s without a write
    coupler = m.device.coupler
    assert coupler.expiries == 0 and lines == []
    assert coupler.read_registers("holding", WATCHDOG_TIME, 1) == [0]
    assert coupler.read_registers("holding", WATCHDOG_STATUS, 1) == [0]  # never armed
    assert m.device.device(0).actual_position == int(5 * K)  # the move ran to its end
    assert "watchdog off" in m.device.summary()["headline"]


def test_watchdog_on_trips_and_says_so_once_naming_the_module_and_the_time():
    m = build(example_data([], watchdog_ms=100))
    lines: list[str] = []
    m.device.notify = lines.append
    _move_once_then_stop_writing(m, int(50 * K))
    m.scheduler.run(500)
    coupler = m.device.coupler
    assert coupler.expiries == 1 and len(lines) == 1
    assert lines[0].startswith("wago672: fieldbus watchdog expired at t=")
    assert "no write for 101 ms (watchdog_ms = 100); module 0 (axis x) brakes with the STOP ramp" in lines[0]
    assert m.device.device(0).actual_position < int(50 * K)  # stopped short of the target
    m.scheduler.run(2000)
    assert m.at_rest() and not m.device.device(0).ready  # braked, then the coupler cleared Enable
    assert "watchdog 100 ms, tripped 1 time" in m.device.summary()["headline"]


def test_watchdog_below_10_ms_is_refused_but_0_is_off():
    found = problems(example_data(watchdog_ms=5))
    assert any(p.startswith("device.watchdog_ms = 5: ") and "give 0 (off) or 10 .. 60000" in p for p in found), found
    assert build(example_data(watchdog_ms=0)).device.coupler.watchdog_ms == 0


def test_the_script_feeds_the_watchdog_after_its_last_step():
    m = build(example_data([ENABLE], watchdog_ms=10))
    result = m.run(1.0)  # an explicit duration: 1 s, long after the script is done
    assert result.completed and m.device.script.done
    assert m.device.coupler.expiries == 0 and m.device.device(0).ready


# ---------------------------------------------------------------- one master


def test_serve_does_not_run_the_script(capsys):
    m = build(example_data(), clock=WallClock(1000))
    assert m.device.script is None and m.device.finished is None
    err = capsys.readouterr().err
    assert "wago672: the [[device.plc]] script (16 steps) is not run by serve: the Modbus client is the PLC" in err
    assert "PLC script not run" in m.device.summary()["headline"]


def test_without_a_script_the_headline_says_nothing_drove_the_module():
    data = example_data()
    data["device"].pop("plc")
    m = build(data)
    assert m.device.finished is None
    m.run(0.01)
    h = m.device.summary()["headline"]
    assert h.startswith("wago672: module 0 (axis x): Idle, not referenced, at 0.000 mm; no PLC script ([[device.plc]])")
    assert h.endswith("watchdog 100 ms, not tripped")
    assert not (m.device.coupler.inputs(0)[10] & S2.Busy)
