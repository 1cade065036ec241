"""Restart after a power loss (restart.py decision 10) and on the plant: the memory file keeps
the image of a running program; a new runtime (or machine) on the same file restarts it."""

from __future__ import annotations

import json
from pathlib import Path

from axisline.devices.clm.memory import ClmMemory, RetainedStore
from axisline.devices.clm.operands import parse_operand
from axisline.devices.clm.runtime import ClmRuntime
from axisline.machine import Machine

from .clmrig import EXAMPLES, Rig, roll_feed_text, with_parameters
from .test_restart import RAxis, restart, run_until

# -- power loss (decision 10) ---------------------------------------------------------------------


def _stored_rig(path: Path, program: str, **kw) -> tuple[Rig, RetainedStore]:
    r = Rig(program, **kw)
    r.axes[1] = RAxis(1)
    return r, RetainedStore(path)


def _run_saving(r: Rig, store: RetainedStore, cycles: int) -> int:
    writes = 0
    for _ in range(cycles):
        r.run()
        writes += store.save(r.rt.memory)
    return writes


def _start_saving(r: Rig, store: RetainedStore) -> None:
    """Power on, then press Start, saving the memory at each cycle as the personality does."""
    _run_saving(r, store, 2)
    r.set("I0.00.3", 1)
    _run_saving(r, store, 1)
    r.set("I0.00.3", 0)


def _power_up(path: Path) -> Rig:
    """A new CLM on the same memory file (the process killed and started again)."""
    memory = ClmMemory()
    RetainedStore(path).load(memory)
    r = Rig("0000 NOP\n")
    r.axes.clear()
    r.axes[1] = RAxis(1)
    r.rt = ClmRuntime(memory, r.axes, 0.002)
    for name in ("I0.00.2", "I0.00.4", "I0.00.5", "I0.00.6"):
        r.set(name, 1)
    r.set_mode("automatic")
    r.run()
    return r


PROGRAM_2 = "0000 PSI 1 +000100.000 999\n0001 AEA Q1.00.0 1\n0002 PSI 1 +000050.000 999\n0003 AEA Q1.00.1 1\n0004 JST 0004\n"


def test_power_loss_restart_from_the_memory_file(tmp_path):
    """L3821 "a loss of power": the process dies in the second feed; a new runtime on the
    memory file has Restart possible, sets the output again and feeds on to 150 (the position
    counter of the incremental axis back where it was when the image was last written)."""
    path = tmp_path / "clm.json"
    r, store = _stored_rig(path, PROGRAM_2)
    _start_saving(r, store)
    run_until(r, lambda: r.rt.tasks[0].pc == 2 and r.axes[1].pos > 110_000)
    store.save(r.rt.memory)
    doc = json.loads(path.read_text())["restart"]
    assert doc["state"] == "running" and doc["tasks"]["1"] == {"running": True, "pc": 2, "stack": [], "moving": True}
    saved = doc["axes"]["1"]["actual"]  # where the axis was when the PSI's image was written
    assert doc["axes"]["1"]["target"] == "150" and 100.0 <= saved < 110.0

    r2 = _power_up(path)
    assert r2.bit("Q0.01.0") == 1 and r2.axes[1].pos == round(saved * 1000) and r2.bit("Q1.00.0") == 0
    restart(r2)
    assert r2.bit("Q1.00.0") == 1
    run_until(r2, lambda: r2.bit("Q1.00.1") == 1)
    assert r2.axes[1].pos == 150_000 and [m[0] for m in r2.axes[1].moves] == ["to"]


def test_power_loss_in_a_program_stop_is_no_restart(tmp_path):
    """L3837 (a): the power goes during Immediate Stop: no restart after power-up; Re-Start is
    Start (from 0000)."""
    path = tmp_path / "clm.json"
    r, store = _stored_rig(path, PROGRAM_2)
    _start_saving(r, store)
    _run_saving(r, store, 5)
    r.set("I0.00.4", 0)
    _run_saving(r, store, 2)
    r2 = _power_up(path)
    assert r2.bit("Q0.01.0") == 0
    restart(r2)
    assert r2.rt.modes.running and r2.axes[1].moves == [("inc", 100_000, 999)]


def test_image_is_not_written_while_the_program_only_tests(tmp_path):
    """Decision 10: a program looping over tests and waits writes nothing; an instruction that
    changes state (here AEA) is written at the end of its cycle with the instruction after it."""
    path = tmp_path / "clm.json"
    r, store = _stored_rig(path, "0000 AEA Q1.00.0 1\n0001 BCE 0003 I1.00.0 1\n0002 JMP 0001\n0003 AEA Q1.01.0 1\n"
                                 "0004 AKN I1.00.1 1\n0005 JST 0005\n")
    _start_saving(r, store)
    _run_saving(r, store, 2)
    assert _run_saving(r, store, 500) == 0
    r.set("I1.00.0", 1)
    assert _run_saving(r, store, 5) == 1
    doc = json.loads(path.read_text())["restart"]
    assert doc["tasks"]["1"]["pc"] == 4 and bytes.fromhex(doc["outputs"])[:2] == bytes([1, 1])  # Q1.00.0, Q1.01.0
    assert _run_saving(r, store, 500) == 0
    r.set("I1.00.1", 1)
    _run_saving(r, store, 3)
    assert json.loads(path.read_text()).get("restart") is None  # JST: the program stopped


def test_a_bad_restart_image_in_the_memory_file_is_refused(tmp_path):
    """A memory file with a broken image is refused with the field named, not a traceback."""
    path = tmp_path / "clm.json"
    r, store = _stored_rig(path, PROGRAM_2)
    _run_saving(r, store, 2)
    r.set("I0.00.3", 1)
    _run_saving(r, store, 3)
    doc = json.loads(path.read_text())
    doc["restart"]["tasks"]["1"]["pc"] = 3000
    path.write_text(json.dumps(doc))
    try:
        RetainedStore(path).load(ClmMemory())
    except ValueError as e:
        assert "restart.tasks.1.pc = 3000" in str(e)
    else:
        raise AssertionError("loaded")


# -- on the plant ------------------------------------------------------------------------------


def test_plant_feed_interrupted_by_manual_reaches_the_same_absolute_target(tmp_path):
    """The roll feed (examples/roll_feed_clm.toml) with its mode switch and Re-Start wired:
    PSI 250 is interrupted by Automatic -> Manual; the axis brakes short of 250; Re-Start
    feeds on to 250.000 exactly as the program's target (no lost dimension)."""
    m = _plant(tmp_path, "0000 PSI 1 +000250.000 999\n0001 AEA Q1.00.0 1\n0002 JST 0002\n")
    axis = m.device.rt.axes[1]

    def cycles(seconds: float) -> None:
        _cycles(m, seconds)

    cycles(0.35)  # Start at 0.1 s; the feed of 250 at 500 mm/s is under way
    assert 20.0 < axis.actual_position < 240.0
    m.io.set_input("auto", False)
    cycles(0.5)
    stopped = axis.actual_position
    assert stopped < 249.0 and m.device.rt.restart.possible
    m.io.set_input("auto", True)
    cycles(0.05)
    m.io.set_input("restart", True)
    cycles(0.05)
    m.io.set_input("restart", False)
    cycles(1.0)
    assert m.io.output("press_valve")
    assert axis.exact_target == 250 and abs(axis.actual_position - 250.0) < 0.05


def test_power_loss_with_an_absolute_encoder_keeps_its_position(tmp_path):
    """Decision 10: an absolute encoder tells its position after power-up (no saved counter
    is put back); the restart then feeds to the saved target from there."""
    path = tmp_path / "clm.json"
    r, store = _stored_rig(path, PROGRAM_2, params={"A120": "0 2 24 1"})
    _start_saving(r, store)
    run_until(r, lambda: r.rt.tasks[0].pc == 2 and r.axes[1].pos > 110_000)
    store.save(r.rt.memory)
    r2 = _power_up(path)
    assert r2.bit("Q0.01.0") == 1 and r2.axes[1].pos == 0  # the new axis reads its own position
    restart(r2)
    run_until(r2, lambda: r2.bit("Q1.00.1") == 1)
    assert r2.axes[1].pos == 150_000


def _plant(tmp_path: Path, program: str) -> Machine:
    prg = tmp_path / "t.prg"
    prg.write_text(program)
    par = tmp_path / "t.par"
    par.write_text(with_parameters((EXAMPLES / "clm" / "roll_feed.par").read_text(), {}))
    text = roll_feed_text(prg, par)
    text = text.replace('inputs = ["press_top", "press_bottom"]', 'inputs = ["press_top", "press_bottom", "auto", "restart", "estop", "clear"]')
    text = text.replace('"I1.00.2" = true', '"I1.00.2" = true\n"I0.00.1" = "auto"\n"I0.01.6" = "restart"\n"I0.00.2" = "estop"\n"I0.00.7" = "clear"')
    text = text.replace('[device]\n', f'[device]\nmemory_file = "{(tmp_path / "clm.json").as_posix()}"\n')
    (tmp_path / "m.toml").write_text(text)
    m = Machine.from_file(tmp_path / "m.toml")
    m.io.set_input("auto", True)
    m.io.set_input("estop", True)
    m.io.sample()  # closed from power-on (the first NC cycle reads the image before the scheduler samples)
    return m


def _press(m: Machine, name: str) -> None:
    m.io.set_input(name, True)
    _cycles(m, 0.05)
    m.io.set_input(name, False)
    _cycles(m, 0.05)


def _cycles(m: Machine, seconds: float) -> None:
    for _ in range(round(seconds / m.period)):
        m.scheduler.run_cycle()


def test_plant_power_loss_then_restart_from_the_memory_file(tmp_path):
    """L3821 "a loss of power" on the plant: the process is dropped in the middle of the second
    feed (nothing saved at the end); a new machine on the same memory_file has Restart
    possible, and Re-Start sets the press output again and feeds to the program's 500."""
    program = "0000 PSI 1 +000250.000 999\n0001 AEA Q1.01.0 1\n0002 PSI 1 +000250.000 999\n0003 AEA Q1.00.0 1\n0004 JST 0004\n"
    m = _plant(tmp_path, program)
    axis = m.device.rt.axes[1]
    _cycles(m, 1.05)  # the first feed is done, the second one under way
    assert m.device.rt.tasks[0].pc == 2 and 250.0 < axis.actual_position < 490.0
    del m  # the power goes: no persist at the end
    saved = json.loads((tmp_path / "clm.json").read_text())["restart"]["axes"]["1"]["actual"]
    assert 245.0 < saved < 255.0  # written when the second PSI started

    m2 = _plant(tmp_path, program)
    _cycles(m2, 0.05)
    rt = m2.device.rt
    assert rt.restart.possible and m2.device.memory.image.get(_q("Q0.01.0")) == 1
    assert abs(rt.axes[1].actual_position - saved) < 0.01  # the incremental axis' counter is back
    m2.io.set_input("restart", True)
    _cycles(m2, 0.05)
    m2.io.set_input("restart", False)
    _cycles(m2, 1.5)
    assert m2.io.output("press_valve") and rt.axes[1].exact_target == 500
    assert abs(rt.axes[1].actual_position - 500.0) < 0.05


def _q(name: str):
    return parse_operand(name, bit=True)


def test_plant_estop_then_restart(tmp_path):
    """L3821 "an error message" on the plant: E-Stop (03) in the middle of PSI 250 drops the
    drive and clears Q1.01.0 (B018 default); after the clear, Re-Start sets Q1.01.0 again and
    the feed ends at 250.000 (the drive is enabled again first)."""
    m = _plant(tmp_path, "0000 AEA Q1.01.0 1\n0001 PSI 1 +000250.000 999\n0002 AEA Q1.00.0 1\n0003 JST 0003\n")
    rt = m.device.rt
    axis = rt.axes[1]
    _cycles(m, 0.35)
    assert 20.0 < axis.actual_position < 240.0
    m.io.set_input("estop", False)
    _cycles(m, 0.5)
    assert rt.modes.fault_error.code == "03" and rt.restart.possible
    assert m.device.memory.image.get(_q("Q1.01.0")) == 0 and axis.actual_position < 249.0
    m.io.set_input("estop", True)
    _press(m, "clear")
    assert rt.modes.fault_error is None
    _press(m, "restart")
    assert m.device.memory.image.get(_q("Q1.01.0")) == 1
    _cycles(m, 1.5)
    assert m.io.output("press_valve") and axis.exact_target == 250 and abs(axis.actual_position - 250.0) < 0.05
