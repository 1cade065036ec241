"""The COMPAX program memory (issue 19): sets N001 ... loaded and read back over the ASCII
interface, their grammar, the device's errors for malformed sets, missing jump targets and locked
commands (nothing stored then), storage with the cam memory, and program_file (program.py,
endpoint.py). Seed lines (Lnnnn) are of /work/shared/seeds/004_67df1072c2ac0157.txt."""

from __future__ import annotations

import json

import pytest

from axisline.configerrors import ConfigError
from axisline.devices.compax import CompaxError
from axisline.devices.compax.program import Kind, ProgramMemory, parse_command

from .program_machine import build, send, straight

CURVES = [straight(1, 360.0), straight(2, 360.0)]


def test_a_set_is_written_read_back_and_cleared():
    # program.py decision 1; the manual's form "N001: P210=1" (L1474), spaces and case free
    m = build(CURVES)
    assert send(m, "N001: P210=1", "n2 setc 1", "N006:LOOP 1", "N007: If I8=1 GOTO 6") == [b"\r\n>"] * 4
    assert send(m, "N1", "N002", "N6", "N7") == [b"N001: P210=1\r\n>", b"N002: SETC 1\r\n>", b"N006: LOOP 1\r\n>",
                                                 b"N007: IF I8=1 GOTO 6\r\n>"]
    assert m.device.program_memory.numbers() == [1, 2, 6, 7]
    assert send(m, "N002:") == [b"\r\n>"]  # cleared
    assert send(m, "N2")[0].startswith(b"!E17 ")  # "Selected set number not present" (L1941)
    assert send(m, "S30") == [b"S030=17.000\r\n>"]


def test_the_grammar_of_the_supplements_commands():
    cases = {
        "P210=1": (Kind.PARAM, (210, 1)), "VP": (Kind.VP, ()), "SC .P40": (Kind.SETC, (".P40",)),
        "SETM 35": (Kind.SETM, (35.0,)), "SS": (Kind.SETS, ()), "POSR CAM": (Kind.POSR_CAM, ()),
        "PR": (Kind.POSR_CAM, ()), "LP 0": (Kind.LOOP, (0,)), "POSA -12.5": (Kind.POSA, (-12.5,)),
        "POSR 64": (Kind.POSR, (64.0,)), "POSA HOME": (Kind.POSA_HOME, ()), "WAIT 100": (Kind.WAIT, (100.0,)),
        "GOTO 6": (Kind.GOTO, (6,)), "IF I8=0 GOTO 3": (Kind.IF, (8, 0, 3)), "OUTPUT O7=1": (Kind.OUTPUT, (7, 1)),
        "SPEED 50": (Kind.SPEED, (50.0,)), "ACCEL 200": (Kind.ACCEL, (200.0,)), "END": (Kind.END, ()),
    }
    for text, (kind, args) in cases.items():
        c = parse_command(text)
        assert (c.kind, c.args) == (kind, args), text


@pytest.mark.parametrize("line, code", [
    ("N001: SETC", 101), ("N001: FOO 3", 101), ("N001: SETC 1;2", 101), ("N001: LOOP 70000", 103),
    ("N001: SETM 101", 103), ("N001: SETC .P39", 103), ("N001: P33=5", 103), ("N001: P999=1", 105),
    ("N300: SETC 1", 103), ("N001: IF I17=1 GOTO 1", 103), ("N001: OUTPUT O14=1", 107),
    ("N001: OUTPUT O7=2", 103), ("N001: WAIT -1", 103), ("N001: SPEED 0", 103), ("N001: POSA 5000000", 103),
])
def test_a_malformed_set_gets_the_devices_error_and_changes_nothing(tmp_path, line, code):
    m = build(CURVES, memory_file=str(tmp_path / "cam.json"))
    assert send(m, "N001: SETC 2") == [b"\r\n>"]
    stored = (tmp_path / "cam.json").read_bytes()
    reply = send(m, line)[0]
    assert reply.startswith(b"!E%d " % code) and reply.endswith(b"\r\n>"), reply
    assert send(m, "N1", "S30") == [b"N001: SETC 2\r\n>", b"S030=%d.000\r\n>" % code]
    assert (tmp_path / "cam.json").read_bytes() == stored


def test_jump_to_a_missing_set_is_e17_and_changes_nothing(tmp_path):
    # program.py decision 3: E17 "Previous meaning, 'Selected set number not present', is retained"
    m = build(CURVES, memory_file=str(tmp_path / "cam.json"))
    assert send(m, "N001: SETC 1", "N002: LOOP 1") == [b"\r\n>"] * 2
    stored = (tmp_path / "cam.json").read_bytes()
    for line in ("N003: GOTO 5", "N003: IF I8=1 GOTO 4", "N002: GOTO 9"):
        reply = send(m, line)[0]
        assert reply.startswith(b"!E17 ") and b"N00" in reply, reply
    assert m.device.program_memory.lines() == ["N001: SETC 1", "N002: LOOP 1"]
    assert (tmp_path / "cam.json").read_bytes() == stored
    # a jump target cannot be cleared while the jump is stored
    assert send(m, "N003: GOTO 1") == [b"\r\n>"]
    assert send(m, "N001:")[0].startswith(b"!E17 ") and 1 in m.device.program_memory


def test_locked_commands_are_refused_with_e107():
    # L164 "Locked Commands: Label related positioning; GOSUB EXT; OUTPUT O0; SPEED SYNC; GOTO EXT"
    m = build(CURVES)
    for command in ("GOSUB EXT", "GOTO EXT", "OUTPUT O0=1", "SPEED SYNC"):
        for line in (f"N001: {command}", command):
            reply = send(m, line)[0]
            assert reply.startswith(b"!E107 ") and b"locked" in reply, (line, reply)
        with pytest.raises(CompaxError) as e:
            ProgramMemory().write(1, command)
        assert e.value.code == 107
    assert len(m.device.program_memory) == 0


def test_program_flow_commands_are_sets_only():
    # endpoint.py decision 2: GOTO, IF, WAIT and END have no meaning as a direct line
    m = build(CURVES)
    for line in ("GOTO 1", "IF I8=1 GOTO 1", "WAIT 10", "END"):
        assert send(m, line)[0].startswith(b"!E101 "), line


def test_writes_and_commands_need_the_operators_enable():
    m = build(CURVES)
    assert send(m, "N001: SETC 1") == [b"\r\n>"]
    m.device.network_writes = False
    assert send(m, "N002: LOOP 1")[0].startswith(b"!E104 ")
    for line in ("START", "STOP", "BREAK", "POSA 10", "OUTPUT O7=1"):
        assert send(m, line)[0].startswith(b"!E107 "), line
    assert send(m, "N1") == [b"N001: SETC 1\r\n>"]  # reads are always answered
    assert m.device.program_memory.numbers() == [1] and m.device.run.state == "stopped"


def test_program_is_saved_with_the_cam_memory(tmp_path):
    # endpoint.py decision 3: saved (atomically) before the reply, loaded at the next power on
    cam = tmp_path / "cam.json"
    m = build(CURVES, memory_file=str(cam))
    program = ["N001: P210=1", "N002: SETC 1", "N006: LOOP 1", "N012: GOTO 6"]
    for line in program:
        assert send(m, line) == [b"\r\n>"]
        assert json.loads(cam.read_text())["program"][-1] == line  # on disk when acknowledged
    assert send(m, "F3000=0.25") == [b"\r\n>"]  # a cam memory write keeps the program in the file
    doc = json.loads(cam.read_text())
    assert doc["program"] == program and doc["format"] == "axisline-compax-cam-memory"
    again = build(CURVES, memory_file=str(cam), program_file=str(tmp_path / "other.prg"))
    assert again.device.program_memory.lines() == program  # the stored program wins over program_file
    assert send(again, "N12") == [b"N012: GOTO 6\r\n>"]


def test_a_failed_save_is_undone_and_answered_e108(tmp_path):
    cam = tmp_path / "cam.json"
    m = build(CURVES, memory_file=str(cam))
    assert send(m, "N001: SETC 1") == [b"\r\n>"]
    cam.unlink()
    cam.mkdir()  # the store's place is taken
    reply = send(m, "N002: LOOP 1")[0]
    assert reply.startswith(b"!E108 ") and b"not stored" in reply
    assert m.device.program_memory.lines() == ["N001: SETC 1"]


def test_program_file_is_loaded_checked_as_a_whole_and_named_in_errors(tmp_path):
    prg = tmp_path / "linking.prg"
    prg.write_text("# the manual's example 2, with a forward jump\n"
                   "N001: P210=1     ; Parallel mode\n"
                   "N002: GOTO 4\n"
                   "N004: SETC 1     # select\n\n")
    m = build(CURVES, program_file=str(prg))
    assert m.device.program_memory.lines() == ["N001: P210=1", "N002: GOTO 4", "N004: SETC 1"]
    prg.write_text("N001: P210=1\nN002: SETM x\n")
    with pytest.raises(ConfigError) as e:
        build(CURVES, program_file=str(prg))
    problem = " ".join(e.value.problems)
    assert f"device.program_file = '{prg}'" in problem and "line 2 'N002: SETM x'" in problem
    prg.write_text("N001: GOTO 7\n")
    with pytest.raises(ConfigError) as e:
        build(CURVES, program_file=str(prg))
    assert "set N007 not present (E17" in " ".join(e.value.problems)
    with pytest.raises(ConfigError) as e:
        build(CURVES, program_file=str(tmp_path / "none.prg"))
    assert "device.program_file" in " ".join(e.value.problems)


def test_sets_are_refused_while_the_program_runs():
    m = build(CURVES)
    assert send(m, "N001: WAIT 1000", "START") == [b"\r\n>"] * 2
    m.scheduler.run_cycle()
    reply = send(m, "N002: SETC 1")[0]
    assert reply.startswith(b"!E107 ") and 2 not in m.device.program_memory
    assert send(m, "START")[0].startswith(b"!E107 ")  # running already
    assert send(m, "STOP", "N002: SETC 1") == [b"\r\n>"] * 2


def test_start_without_sets_is_e17():
    m = build(CURVES)
    assert send(m, "START")[0].startswith(b"!E17 ")


def test_gaps_are_skipped():
    # program.py decision 2: the listing of L1474-1484 has no N005
    m = build(CURVES)
    assert send(m, "N001: OUTPUT O1=1", "N005: OUTPUT O2=1", "START") == [b"\r\n>"] * 3
    m.scheduler.run_cycle()
    m.scheduler.run_cycle()
    assert m.device.op.output(1) and m.device.op.output(2)
    assert m.device.run.state == "ended" and m.device.run.executed == 2


def test_speed_and_accel_apply_to_the_positioning_sets():
    # program.py decision 8: SPEED in % of v_max (20000 deg/s), ACCEL in ms from 0 to v_max
    m = build(CURVES)
    assert send(m, "N001: SPEED 10", "N002: ACCEL 100", "N003: POSA 1000", "START") == [b"\r\n>"] * 4
    ax = m.device.axis
    v, a = [], []
    for _ in range(1000):
        m.scheduler.run_cycle()
        v.append(ax.command_velocity)
        a.append(abs(ax.command_acceleration))
    assert max(v) == pytest.approx(2000.0) and max(a) == pytest.approx(20000.0 / 0.1)
    assert ax.command_position == pytest.approx(1000.0)


def test_acknowledged_sets_survive_a_kill_9(tmp_path):
    # issue 19: "stored with the cam memory (atomically, kept through a kill -9 once acknowledged)"
    import socket
    from pathlib import Path

    from serving import serve

    from axisline.machine import Machine

    example = Path(__file__).resolve().parents[3] / "examples" / "cam_linking.toml"
    text = example.read_text().replace('program_file = "cam_linking.prg"', 'memory_file = "belt.cam.json"')
    machine = tmp_path / "belt.toml"
    machine.write_text(text.replace('startup = ["SETC 1", "START"]', "startup = []"))
    proc, endpoints = serve(str(machine), "--serial-tcp", "127.0.0.1:0", "--allow-writes")
    try:
        host, _, port = endpoints["serial-tcp"].rpartition(":")
        with socket.create_connection((host, int(port)), timeout=10) as sock:
            for line in ("N001: P210=1", "N002: SETC 1", "N006: LOOP 1", "N012: GOTO 6"):
                sock.sendall(line.encode() + b"\r")
                reply = b""
                while not reply.endswith(b"\r\n>"):
                    reply += sock.recv(256)
                assert reply == b"\r\n>", (line, reply)
            proc.kill()  # SIGKILL right after the last reply: no shutdown save
    finally:
        proc.kill()
        proc.wait(timeout=10)
    again = Machine.from_file(machine)
    assert again.device.program_memory.lines() == ["N001: P210=1", "N002: SETC 1", "N006: LOOP 1", "N012: GOTO 6"]
