"""The CLM's X6 serial protocol (spec §8; manual §9.2, L6207-7507): through the real TCP endpoint
on the roll feed machine, and on a plant-less runtime (clmrig) where a test needs a state the
plant does not give (axis positions of the manual's figures, a fault, a second axis)."""

from __future__ import annotations

import json
import re
import socket
import threading
import time
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from typer.testing import CliRunner

from axisline.cli import app
from axisline.devices.clm.errors import ClmError
from axisline.devices.clm.serial import ClmSerialEndpoint, error_reply
from axisline.devices.clm.status import STATUS_NUMBERS
from axisline.devices.clm.telegram import checksum, emit
from axisline.fieldbus.serial_tcp import SerialTcpServer
from axisline.machine import Machine

from .clmrig import Rig

EXAMPLES = Path(__file__).resolve().parents[3] / "examples"
ROLL_FEED = EXAMPLES / "roll_feed_clm.toml"
PROGRAM = (EXAMPLES / "clm" / "roll_feed.prg").read_text()
runner = CliRunner()


def tg(control: str, kind: str, body: str, station: int = 0, with_checksum: bool = True) -> bytes:
    return emit(control, station, kind, body, with_checksum).encode("ascii")


def well_formed(reply: bytes) -> list[str]:
    """The reply lines; each a CLM telegram: Y, :snn, or text$hh with the right checksum."""
    assert reply == b"" or reply.endswith(b"\r\n"), reply
    lines = reply.decode("ascii").split("\r\n")[:-1]
    for line in lines:
        if line == "Y" or re.fullmatch(r":[ 1-9A-W][0-9A-F]{2}", line):
            continue
        text, dollar, given = line.rpartition("$")
        assert dollar and text[:1] in "#XVP" and checksum(text) == given, line
    return lines


def error_of(reply: bytes) -> int:
    lines = well_formed(reply)
    assert len(lines) == 1 and lines[0][:1] == "X" and lines[0][2:5] == "01 ", reply
    number = int(lines[0][5:7])
    assert reply == error_reply(number, 0) or lines[0][1] != " "
    return number


# -- the real TCP endpoint on the roll feed machine ----------------------------------------------


def _machine(tmp_path: Path) -> Machine:
    text = ROLL_FEED.read_text().replace('"clm/', f'"{EXAMPLES.as_posix()}/clm/')
    text = text.replace('inputs = ["press_top", "press_bottom"]', 'inputs = ["press_top", "press_bottom", "sel_param", "sel_auto"]')
    text = text.replace('"I1.00.2" = true', '"I1.00.2" = true\n"I0.00.0" = "sel_param"\n"I0.00.1" = "sel_auto"')
    text = text.replace('report_output = "Q1.00.0"', 'report_output = "Q1.00.0"\nmemory_file = "clm.json"')
    path = tmp_path / "roll_feed.toml"
    path.write_text(text)
    return Machine.from_file(path)


class Line:
    """A client of the running machine: `ask` sends bytes and reads `lines` reply lines."""

    def __init__(self, m: Machine, address: tuple[str, int]) -> None:
        self.m = m
        self.sock = socket.create_connection(address, timeout=5)
        self.buffer = b""

    def ask(self, data: bytes, lines: int = 1) -> bytes:
        self.sock.sendall(data)
        while self.buffer.count(b"\r\n") < lines:
            chunk = self.sock.recv(4096)
            assert chunk, "connection closed"
            self.buffer += chunk
        out = b""
        for _ in range(lines):
            line, _, self.buffer = self.buffer.partition(b"\r\n")
            out += line + b"\r\n"
        return out

    def mode(self, wanted: str) -> None:
        io = self.m.io
        self.m.commands.submit(lambda: (io.set_input("sel_param", wanted == "parameter"),
                                        io.set_input("sel_auto", wanted == "automatic"))).result(5)
        deadline = time.monotonic() + 5
        while self.m.device.rt.modes.mode != wanted:
            assert time.monotonic() < deadline, self.m.device.rt.modes.mode
            time.sleep(0.005)


@pytest.fixture
def clm(tmp_path):
    m = _machine(tmp_path)
    m.device.network_writes = True
    srv = SerialTcpServer(m.device.byte_endpoint(), m.commands).start()
    stop = threading.Event()

    def cycling() -> None:
        while not stop.is_set():
            m.scheduler.run_cycle()
            time.sleep(0.0002)

    th = threading.Thread(target=cycling)
    th.start()
    line = Line(m, srv.address)
    line.tmp_path = tmp_path  # type: ignore[attr-defined]
    line.address = srv.address  # type: ignore[attr-defined]
    line.mode("manual")
    try:
        yield line
    finally:
        line.sock.close()
        stop.set()
        th.join()
        srv.stop()


def _retained(m: Machine) -> dict:
    return json.loads(json.dumps(m.device.memory.retained()))


def test_status_queries_over_tcp(clm):
    """Every status number of spec §8.5 answers over TCP: one or two blanks (errata §1.6), each
    reply a well-formed telegram of its own number, or the Status 01 error the CLM sends."""
    assert clm.ask(b"? X  00 \r\n") == clm.ask(b"? X 00 \r\n")
    args = {4: "0007 ", 60: "1 ", 61: "I1.00 ", 63: "14 "}
    for n in STATUS_NUMBERS:
        reply = clm.ask(f"? X  {n:02d} {args.get(n, '')}\r\n".encode())
        line = well_formed(reply)[0]
        assert line.startswith(f"X {n:02d} ") or line[:5] == "X 01 ", line
        if line[:5] == "X 01 ":
            assert n in (9, 41, 47, 54) and int(line[5:7]) in (9, 10)
    assert error_of(clm.ask(b"? X 01 \r\n")) == 9  # Status 01 cannot be queried (L6791)
    assert error_of(clm.ask(b"? X 0A \r\n")) == 8
    assert error_of(clm.ask(b"? X 07 \r\n")) == 9
    # Status 04 of the roll feed's COU at 0007: count 0, preset V602 = 20
    assert clm.ask(b"? X  04 0007 \r\n") == tg("X", "", "04 0007 000000 000020 ")
    assert clm.ask(b":\x20\r\n") == b": 00\r\n"  # polling: fault code hex, no checksum (L7497)


def test_writes_and_read_backs_byte_for_byte(clm):
    """The manual's program telegrams (L6547-6548) are stored and come back byte for byte; a NOP
    reads back as L7888/L7905; a variable and a Logic Task instruction likewise. B003 of the roll
    feed has confirmation on: every accepted write is answered Y (L6362)."""
    m = clm.m
    for example in (b"# N0101 AEA Q1.00.3 1 $C0\r\n", b"# N0102 BPA 0123 M2.02      21112212 $32\r\n"):
        assert clm.ask(example) == b"Y\r\n"
        assert clm.ask(example[:7].replace(b"#", b"?") + b"\r\n") == example
    assert clm.ask(b"? N0100\r\n") == b"# N0100 NOP   $3F\r\n"
    assert clm.ask(b"? N0003\r\n") == m.device.memory.program[3].telegram().encode()
    write = tg("#", "V", "650 +00001234.500000 ")
    assert clm.ask(write) == b"Y\r\n"
    assert clm.ask(b"? V650\r\n") == tg("V", "", "650 +00001234.500000 ")
    assert m.device.memory.variables[650] == 1_234_500_000
    # acknowledged means stored: the memory file holds it before the reply (serial decision 12)
    doc = json.loads((clm.tmp_path / "clm.json").read_text())
    assert doc["variables"]["V650"] == "+00001234.500000" and "0101 AEA Q1.00.3 1" in doc["program"]
    clm.mode("parameter")
    assert clm.ask(tg("#", "P", "0003 AND I1.00.1 ")) == b"Y\r\n"  # before END: the LT grows
    assert clm.ask(tg("#", "P", "0004 ST M5.00.1 ")) == b"Y\r\n"
    assert clm.ask(tg("#", "P", "0005 END ")) == b"Y\r\n"
    assert clm.ask(b"? P 0004\r\n") == tg("P", "", "0004 ST M5.00.1 ")
    assert clm.ask(b"? P0999\r\n") == tg("P", "", "0999 NOP ")
    assert m.device.memory.logic[4] == "ST M5.00.1"


def test_parameter_read_back_is_the_manual_table(clm):
    """Parameters read back in the layout of Figs. 9-14..9-16 (L6591-6670), checksum included;
    the manual's samples written in Parameter mode (with '!' for '#', L6588) come back the same."""
    for sample in (b"# K B002 019200 0 1 8 1$E4", b"# K B003 0 1 00 0 000 000$A8", b"# K B006 $59", b"# K A101 0010.00000$7D"):
        assert clm.ask(b"? K " + sample[4:8] + b"\r\n") == sample + b"\r\n"
    clm.mode("parameter")
    assert clm.ask(b"! K A106 000200.000$79\r\n") == b"Y\r\n"
    assert clm.ask(b"? K A106\r\n") == b"# K A106 000200.000$77\r\n"
    assert clm.ask(b"# K A107 000100.000$77\r\n") == b"Y\r\n"


def test_malformed_telegram_is_02_and_changes_nothing(clm):
    before = _retained(clm.m)
    cases = {
        b"hello\r\n": 2,
        b"# N01X0 NOP  $37\r\n": 1,  # instruction number not decimal
        b"# N3000 NOP  $" + checksum("# N3000 NOP  ").encode() + b"\r\n": 12,
        tg("#", "N", "0100 FOO 1 "): 13,
        tg("#", "N", "0100 POI 7 +000010.000 999 "): 3,  # axis 7: data the CLM would fault on
        tg("#", "V", "650 +1.2.3 "): 18,
        tg("#", "V", "100 +00000001.000000 "): 23,  # a system variable
        tg("#", "X", " 00 "): 2,
        b"? K Z100\r\n": 11,
        b"? K B0A0\r\n": 6,
        b"? K B020\r\n": 7,
        tg("!", "", "FOO "): 13,
        b"# V650 +00000001.000000 $1\r\n": 2,  # one hex digit
    }
    for telegram, number in cases.items():
        assert error_of(clm.ask(telegram)) == number, telegram
    assert clm.ask(b"# V650 \x80\r\n") == error_reply(2)
    assert _retained(clm.m) == before


def test_bad_checksum_is_04_and_changes_nothing(clm):
    before = _retained(clm.m)
    good = tg("#", "V", "650 +00000001.000000 ")
    bad = good.replace(good[-4:-2], b"00" if good[-4:-2] != b"00" else b"01")
    assert error_of(clm.ask(bad)) == 4
    assert error_of(clm.ask(tg("#", "V", "650 +00000001.000000 ", with_checksum=False))) == 4  # validation on (B003 0)
    assert error_of(clm.ask(b"! START \r\n")) == 4  # '!' always needs it (L7339)
    assert _retained(clm.m) == before


def test_write_in_wrong_mode_is_05(clm):
    """Parameters and the Logic Task only in Parameter mode (L6574, L2961), CSETPA / CNOPNC /
    CNOPLT / CCLVAR too (L7426-7482), START only in Automatic; 05 and nothing changes."""
    before = _retained(clm.m)
    a106 = clm.m.device.memory.parameters.data("A106")
    for telegram in (b"# K A106 000200.000$77\r\n", b"! K A106 000200.000$79\r\n", tg("#", "P", "0003 END "),
                     tg("!", "", "CSETPA "), tg("!", "", "CNOPNC "), tg("!", "", "CNOPLT "), tg("!", "", "CCLVAR "),
                     tg("!", "", "START ")):
        assert error_of(clm.ask(telegram)) == 5, telegram
    assert _retained(clm.m) == before
    assert clm.m.device.memory.parameters.data("A106") == a106 == "000500.000"


def test_write_without_allow_writes_is_18(clm):
    clm.m.device.network_writes = False
    before = _retained(clm.m)
    for telegram in (tg("#", "V", "650 +00000001.000000 "), tg("#", "N", "0100 NOP "), tg("!", "", "STOP ")):
        assert error_of(clm.ask(telegram)) == 18
    assert clm.ask(b"? V650\r\n") == tg("V", "", "650 +00000000.000000 ")  # queries stay open
    assert _retained(clm.m) == before


def test_wrong_station_gets_no_reply_and_changes_nothing(clm):
    """B003 station 05 written in Parameter mode takes effect when Parameter mode is left (L6586,
    decision 4); then a telegram for station 3 gets silence and does nothing (L6392)."""
    clm.mode("parameter")
    assert clm.ask(tg("#", "K", " B003 0 1 05 0 000 000")) == b"Y\r\n"
    assert clm.ask(b"? X 53 \r\n") == tg("X", "", "53 01 no error (Parame ")  # still RS232
    clm.mode("manual")
    before = _retained(clm.m)
    clm.sock.sendall(tg("#", "V", "650 +00000007.000000 ", station=3) + b"?3X 53 \r\n")
    assert clm.ask(b"?5X 53 \r\n") == tg("X", "", "53 00 no error         ", station=5)  # the first reply is station 5's
    assert _retained(clm.m) == before
    assert clm.ask(b"?5N0000\r\n") == clm.m.device.memory.program[0].telegram(5).encode()


# -- the protocol on a plant-less runtime ------------------------------------------------------------


def rig(params: dict[str, str] | None = None, mode: str = "manual", axes: int = 1) -> tuple[Rig, ClmSerialEndpoint]:
    r = Rig(PROGRAM, params=params, mode=mode, axes=axes)
    r.run(2)
    return r, ClmSerialEndpoint(r.rt)


def test_framing_cr_lf_cr_lf_and_pieces():
    r, ep = rig()
    s = ep.session()
    answer = tg("X", "", "53 00 no error         ")
    assert s.feed(b"? X 53 \r") == answer
    assert s.feed(b"\n? X 53 \n") == answer  # the LF after CR is no telegram
    assert s.feed(b"? X") == b"" and s.feed(b" 5\x113 \r\n") == answer  # in pieces, XON dropped
    assert s.feed(b"\r\n\r\n") == b""
    other = ep.session()  # a second connection does not see the first one's half telegram
    assert s.feed(b"? X 5") == b"" and other.feed(b"? X 53 \r\n") == answer


def test_overlong_line_is_02():
    r, ep = rig()
    s = ep.session()
    assert s.feed(b"# V650 " + b"1" * 500 + b"\r\n") == error_reply(2)
    assert s.feed(b"? X 53 \r\n") == tg("X", "", "53 00 no error         ")


def test_rs232_needs_a_blank_station():
    r, ep = rig()
    assert error_of(ep.feed(b"?5X 53 \r\n")) == 2


def test_broadcast_executes_silently():
    r, ep = rig({"B003": "0 1 05 0 000 000"})
    assert ep.feed(tg("#", "V", "650 +00000003.000000 ")) == b""  # blank station: for all (L6394)
    assert r.rt.memory.variables[650] == 3_000_000
    assert ep.feed(b"? X 53 \r\n") == b""
    assert ep.feed(b"?5X 53 \r\n") == tg("X", "", "53 00 no error         ", station=5)
    assert ep.feed(b":5\r\n") == b":500\r\n" and ep.feed(b":6\r\n") == b""


def test_checksum_rules():
    r, ep = rig({"B003": "1 1 00 0 000 000"})  # validation off
    assert ep.feed(tg("#", "V", "650 +00000001.000000 ", with_checksum=False)) == b"Y\r\n"
    assert error_of(ep.feed(b"# V650 +00000002.000000 $00\r\n")) == 4  # a present one is verified
    assert error_of(ep.feed(b"! STOP \r\n")) == 4
    assert ep.feed(b"! STOP $$" + checksum("! STOP ").encode() + b"\r\n") == b"Y\r\n"  # the manual's $$
    r2, ep2 = rig({"B003": "0 0 00 0 000 000"})  # validation on, confirmation off
    assert error_of(ep2.feed(tg("#", "V", "650 +00000001.000000 ", with_checksum=False))) == 4
    assert ep2.feed(tg("#", "V", "650 +00000001.000000 ")) == b""
    assert ep2.feed(b"? V650\r\n") == tg("V", "", "650 +00000001.000000 ")


def test_b003_takes_effect_after_parameter_mode():
    r, ep = rig(mode="parameter")
    assert ep.feed(tg("#", "K", " B003 1 1 00 0 000 000")) == b"Y\r\n"  # validation off from now ...
    assert error_of(ep.feed(tg("#", "K", " A106 000200.000", with_checksum=False))) == 4  # ... not yet
    r.set_mode("manual")
    r.run(2)
    assert ep.feed(tg("#", "V", "650 +00000001.000000 ", with_checksum=False)) == b"Y\r\n"


def test_interface_commands():
    r, ep = rig(mode="automatic")
    rt = r.rt
    assert ep.feed(tg("!", "", "START ")) == b"Y\r\n"
    r.run(3)
    assert rt.modes.running and rt.tasks[0].pc > 0
    assert ep.feed(tg("!", "", "STOP ")) == b"Y\r\n"
    r.run(1)
    assert not rt.modes.running and rt.modes.interface_stopped
    r.start()  # the Start input does not continue a !STOP (L7355)
    assert not rt.modes.running
    assert error_of(ep.feed(tg("!", "", "CL0 "))) == 5  # Manual only
    assert ep.feed(tg("!", "", "M1OFF ")) == b"Y\r\n" and 1 not in rt.modes.enabled_axes
    assert ep.feed(tg("!", "", "M1ON ")) == b"Y\r\n" and 1 in rt.modes.enabled_axes
    r.set_mode("parameter")
    r.run(2)
    memory = rt.memory
    for n in (650, 651, 652):
        memory.variables.write(n, 1_000_000, by="serial")
    assert ep.feed(tg("!", "", "CCLVAR06500651 ")) == b"Y\r\n"
    assert [memory.variables[n] for n in (650, 651, 652)] == [0, 0, 1_000_000]
    assert error_of(ep.feed(tg("!", "", "CCLVAR05000651 "))) == 23
    assert error_of(ep.feed(tg("!", "", "CNOPNC00050003 "))) == 2
    counters = dict(memory.program.counters)
    assert ep.feed(tg("!", "", "CNOPNC00000002 ")) == b"Y\r\n"
    assert memory.program[2].mnemonic == "NOP" and memory.program[3].mnemonic == "PSI"
    assert memory.program.counters == counters  # the COU at 0007 keeps its count
    memory.logic = {0: "LD I1.00.0", 1: "ST M5.00.0", 2: "END"}
    assert ep.feed(tg("!", "", "CNOPLT00010001 ")) == b"Y\r\n"
    assert ep.feed(b"? P0001\r\n") == tg("P", "", "0001 NOP ") and memory.logic[0] == "LD I1.00.0"
    assert ep.feed(tg("!", "", "CNOPLT ")) == b"Y\r\n"
    assert ep.feed(b"? P0000\r\n") == tg("P", "", "0000 END ") and ep.feed(b"? P0002\r\n") == tg("P", "", "0002 NOP ")
    memory.parameters.set("A106", "000200.000")
    assert ep.feed(tg("!", "", "CSETPA ")) == b"Y\r\n" and memory.parameters.data("A106") == "000100.000"
    assert ep.feed(tg("!", "", "CCLVAR0019 ")) == b"Y\r\n"
    assert error_of(ep.feed(tg("!", "", "START "))) == 5


def test_automatic_error_message():
    """B003 automatic error messages (RS232): a new fault comes as Status 53 ahead of the next
    reply (decision 6)."""
    r, ep = rig({"B003": "0 1 00 1 000 000"}, mode="automatic")
    s = ep.session()
    assert s.feed(b"\n") == b""
    r.set("I0.00.2", 0)  # E-Stop open: fault 03
    r.run(1)
    assert s.feed(b"\n") == tg("X", "", "53 03 EMERGENCY STOP   ")
    assert s.feed(b"\n") == b""  # reported once
    late = ep.session()  # a session that connects later is not told about it
    assert late.feed(b"\n") == b""


def test_unsaved_write_is_undone():
    r = Rig(PROGRAM, mode="manual")
    r.run(2)

    def full() -> None:
        raise OSError(28, "No space left on device")

    ep = ClmSerialEndpoint(r.rt, store=full)
    assert ep.feed(tg("#", "V", "650 +00000001.000000 ") + tg("#", "N", "0100 WAI 01.000 ") + b"? V650\r\n") == (
        error_reply(18) + error_reply(18) + tg("V", "", "650 +00000001.000000 "))
    assert r.rt.memory.variables[650] == 0 and r.rt.memory.program[100].mnemonic == "NOP"


def test_status_03_manual_examples():
    """Figs. 9-17/9-18 (L6860-6890): 1319.67 IU with A119 01500, A101 10 -> 000C14FA; 3272.25 IU
    with an absolute A219 04096, A201 20 -> 000A39CD; the reply is L6855's."""
    params = {"B000": "1 0 0", "A119": "01500 0000", "A101": "0010.00000", "A219": "04096 0512",
              "A201": "0020.00000", "A220": "0 1 12 1"}
    r, ep = rig(params, axes=2)
    r.axes[1].actual_position, r.axes[2].actual_position = 1319.67, 3272.25
    assert ep.feed(b"? X  03 \r\n") == tg("X", "", "03 000C14FA 000A39CD ")
    r.axes[1].actual_position = -0.01
    assert ep.feed(b"? X  03 \r\n")[5:13] == b"FFFFFFFA"  # -6 increments


def test_status_00_10_44_columns():
    r, ep = rig({"B000": "1 0 0"}, axes=2)
    r.axes[1].actual_position, r.axes[1].homed = 1375.345, True
    r.axes[2].actual_position, r.axes[2].lag = -250.0, 0.012
    assert ep.feed(b"? X  00 \r\n") == tg("X", "", "00 A+001375.345  -000250.000 ")
    assert ep.feed(b"? X  10 \r\n") == tg("X", "", "10 +000000.000 +000000.012 ")
    assert ep.feed(b"? X  44 \r\n") == tg("X", "", "44" + " " * 27)  # axes 3, 4 absent: blanks


def test_status_02_08_39_tasks():
    r, ep = rig({"B011": "0200 0800 0", "B012": "0000 0900"}, mode="automatic")
    r.start()
    r.rt.tasks[0].stack.append(5)
    assert ep.feed(b"? X 02 \r\n") == tg("X", "", f"02 {r.rt.tasks[0].pc:04d} 0005 ")
    reply = well_formed(ep.feed(b"? X 08 \r\n"))[0]
    assert reply.startswith(f"X 08 {r.rt.tasks[0].pc:04d} 0005 0")
    assert reply.rpartition("$")[0] == f"X 08 {r.rt.tasks[0].pc:04d} 0005 {r.rt.tasks[1].pc:04d}      {r.rt.tasks[2].pc:04d}      "
    assert ep.feed(b"? X 39 \r\n") == tg("X", "", f"39 {' ' * 9} {r.rt.tasks[4].pc:04d}      ")


def test_status_42_45_48_49():
    r, ep = rig()
    r.axes[1].rpm = 1234.567
    assert ep.feed(b"? X 48 \r\n") == tg("X", "", "48 1 +1234.57 0 +0000.00 ")
    assert ep.feed(b"? X 42 \r\n") == tg("X", "", "42 0 +0000.00 0 +0000.00 ")
    assert ep.feed(b"? X 49 \r\n") == tg("X", "", "49 +00000 +00000 ")
    assert ep.feed(b"? X 45 \r\n") == tg("X", "", "45 +00000 +00000 ")


def test_status_not_available():
    r, ep = rig()
    assert error_of(ep.feed(b"? X 47 \r\n")) == 9  # C000 has a resolution (01250): part 3 missing
    assert error_of(ep.feed(b"? X 09 \r\n")) == 10  # axis 1 not a measuring wheel (L7193's rule)
    assert ep.feed(b"? X 41 \r\n").startswith(b"X 41  +000000.000 $")  # 0 before any raster (registration decision 6)
    assert error_of(ep.feed(b"? X 54 \r\n")) == 9
    r2, ep2 = rig({"C000": "00000 0000"})
    assert error_of(ep2.feed(b"? X 47 \r\n")) == 10


def test_status_53_fault_and_text():
    r, ep = rig()
    r.rt.message = "FEED 250 MM"
    assert ep.feed(b"? X 53 \r\n") == tg("X", "", "53 00 FEED 250 MM      ")
    r.rt.modes.fault(ClmError("43", "lag", "N0003"))
    assert ep.feed(b"? X 53 \r\n") == tg("X", "", "53 43 Excess Pos Lag 1 ")
    assert ep.feed(b":\x20\r\n") == b": 43\r\n"


def test_status_60_where():
    r, ep = rig()
    r.rt.modes.fault(ClmError("32", "V601 = +00001000.000000 in velocity: too large", "N0003"))
    assert ep.feed(b"? X 60 1 \r\n") == tg("X", "", "60 1 0003 ")
    assert ep.feed(b"? X 60 3 \r\n") == tg("X", "", "60 3 0601 ")
    assert ep.feed(b"? X 60 2 \r\n") == tg("X", "", "60 2      ")
    assert error_of(ep.feed(b"? X 60 \r\n")) == 2


def test_status_61_byte():
    r, ep = rig()
    r.set("M2.02", 0b1010_0001)
    assert ep.feed(b"? X  61 M2.02 \r\n") == tg("X", "", "61 M2.02 10100001 ")
    assert error_of(ep.feed(b"? X  61 X2.02 \r\n")) == 18
    assert error_of(ep.feed(b"? X  61 M2.20 \r\n")) == 18


def test_status_63_text():
    r, ep = rig()
    r.rt.text_lines[:] = ["LINE ONE", "LINE TWO", "", ""]
    assert ep.feed(b"? X 63 12 \r\n") == tg("X", "", "63 " + "LINE ONE".ljust(16) + "LINE TWO".ljust(16) + " ")
    assert error_of(ep.feed(b"? X 63 31 \r\n")) == 2


def test_status_04_counter():
    r, ep = rig()
    r.rt.memory.program.counters[7] = 12
    r.rt.memory.variables.write(602, 20_500_000, by="serial")
    assert ep.feed(b"? X 04 0007 \r\n") == tg("X", "", "04 0007 000012 000020 ")
    assert ep.feed(b"? X 04 0003 \r\n") == tg("X", "", "04 0003               ")
    assert error_of(ep.feed(b"? X 04 3000 \r\n")) == 12


def test_status_05_19_versions():
    r, ep = rig()
    assert ep.feed(b"? X 05 \r\n") == tg("X", "", "05  FWA-CLM1.4-LAP-05VRS ")
    assert ep.feed(b"? X 19 \r\n") == tg("X", "", "19 CLM01.4-P-E-4-BCLM1.4-LAP-05VRS")


def test_manual_checksum_examples_are_accepted():
    """Fig. 9-12 example 2 (L6516, $45) at station 5; the RS485 query example (L6292-6298)."""
    r, ep = rig({"B003": "0 1 05 0 000 000"}, mode="parameter")
    assert ep.feed(b"#5N0123 NOP  $45\r\n") == b"Y\r\n"
    r2, ep2 = rig({"B003": "0 1 10 0 000 000"})
    assert ep2.feed(b"?AN0000\r\n") == r2.rt.memory.program[0].telegram(10).encode()


@settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.lists(st.binary(max_size=60) | st.sampled_from([b"\r\n", b"? X 53 ", b"# V6", b"! ", b"$", b"\n"]), max_size=12))
def test_random_bytes_never_raise(chunks):
    r, ep = _FUZZ
    s = ep.session()
    for chunk in chunks:
        well_formed(s.feed(chunk))


_FUZZ = rig(mode="manual")


# -- the PC tool: clm save and clm display ----------------------------------------------------------


def test_clm_save_round_trip(clm):
    m = clm.m
    host, port = clm.address
    out = clm.tmp_path / "backup"
    result = runner.invoke(app, ["clm", "save", "--connect", f"{host}:{port}", str(out)])
    assert result.exit_code == 0, result.output
    names = ("program.txt", "parameters.txt", "logic.txt", "variables.txt")
    assert sorted(p.name for p in out.iterdir()) == sorted(names)
    check = runner.invoke(app, ["clm", "check", str(out / "program.txt"), "--params", str(out / "parameters.txt"),
                                "--logic", str(out / "logic.txt"), "--variables", str(out / "variables.txt")])
    assert check.exit_code == 0, check.output
    memory = m.device.memory
    assert (out / "program.txt").read_bytes() == memory.program.telegrams().encode()
    assert (out / "parameters.txt").read_text().splitlines() == memory.parameters.telegrams()
    assert "# P0002 ST M5.00.0 $" in (out / "logic.txt").read_text()
    assert (out / "variables.txt").read_text().splitlines()[0].startswith("# V600 +00000250.000000 $")
    bad = runner.invoke(app, ["clm", "save", "--connect", f"{host}:{port}", "--station", "7", str(out)])
    assert bad.exit_code == 2 and "error 02" in bad.output  # RS232: only a blank station (L6390)


def test_clm_display_once(clm):
    host, port = clm.address
    screens = {
        "position": "P 1  +",
        "io": "I/O - Status",
        "variables": "+00000250.000000",
        "counters": "Total: 000020",
        "tasks": "T1 ",
        "error": "Error 00",
    }
    for screen, expected in screens.items():
        extra = ["--counter", "7"] if screen == "counters" else []
        result = runner.invoke(app, ["clm", "display", "--connect", f"{host}:{port}", "--screen", screen, "--once", *extra])
        assert result.exit_code == 0, result.output
        assert expected in result.output, (screen, result.output)
