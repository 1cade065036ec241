"""COMPAX ASCII interface to the cam memory (compax.md §6.1; manual §25)."""

from __future__ import annotations

import socket
import threading

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from serving import Fed

from axisline.devices.compax import CompaxError
from axisline.devices.compax.ascii import MAX_ERROR_REPLY, MAX_LINE, PROMPT, AsciiEndpoint, CamCommands, error_reply
from axisline.devices.compax.cammemory import CamMemory
from axisline.devices.compax.curves import read_curve
from axisline.devices.compax.parameters import Parameters
from axisline.devices.compax.status import LOOP_ENDLESS, StatusValues
from axisline.fieldbus.serial_tcp import SerialTcpServer

from .test_personality import _cycling, build, small


class Recorder:
    """A stand-in for the cam operation: records the commands it gets."""

    def __init__(self, refuse: Exception | None = None) -> None:
        self.calls: list[tuple] = []
        self.refuse = refuse

    def _do(self, *call) -> None:
        if self.refuse is not None:
            raise self.refuse
        self.calls.append(call)

    def setc(self, n: int) -> None:
        self._do("setc", n)

    def setm(self, x: float) -> None:
        self._do("setm", x)

    def sets(self) -> None:
        self._do("sets")

    def posr_cam(self) -> None:
        self._do("posr_cam")

    def loop(self, m: int) -> None:
        self._do("loop", m)


def endpoint(commands=None, memory=None) -> AsciiEndpoint:
    return AsciiEndpoint(memory if memory is not None else CamMemory(), Parameters(), commands, StatusValues())


# -- the manual's examples, byte for byte --------------------------------------------------------


@pytest.mark.parametrize(
    "line",
    [b"F6=0\r", b"B7=001;2;003\r", b"F24=.9\r", b"B25=001;002;003\r", b"I5460=360\r", b"I5436=360\r"],
)
def test_manual_transfer_examples_answer_cr_lf_prompt(line):
    # §25 "Transfer of Data" examples; "After each string COMPAX 70 sends back <cr>, <lf> and prompt (> = $3E)"
    ep = endpoint()
    assert ep.feed(line) == b"\r\n>" == PROMPT
    assert ep.status[30] == 0


def test_manual_transfer_examples_store_their_values():
    ep = endpoint()
    ep.feed(b"F6=0\rB7=001;2;003\rF24=.9\rB25=001;002;003\rI5460=360\rI5436=360\r")
    mem = ep.memory
    assert mem.read("F", 6) == 0.0 and mem.read("B", 7) == (1, 2, 3) and mem.read("B", 25) == (1, 2, 3)
    assert mem.read("F", 24) == pytest.approx(0.9, abs=2**-23)
    assert mem.read("I", 5460) == 360 and mem.read("I", 5436) == 360  # I5436: slave cycle of curve 2


def test_manual_read_back_example_f6():
    # §25 "Checking of Data": after "F6<cr>" COMPAX 70 returns "F0006=0.1234567<cr><lf><$3E>"
    ep = endpoint()
    assert ep.feed(b"F6=0.1234567\r") == b"\r\n>"
    assert ep.feed(b"F6\r") == b"F0006=0.1234567\r\n>"
    assert ep.feed(b"F0006\r") == b"F0006=0.1234567\r\n>"


def test_x20_whole_example_over_the_interface():
    # §25: two curves (straight lines) with 11 set points each, I0001, VF; then check by reading back
    lines = ["RESETF", "I1=2"]
    values = [".0", ".1", ".2", ".3", ".4", ".5", ".6", ".7", ".8", ".9", ".9999999"]
    aux = ["1;10;246", "3;20;236", "7;30;226", "15;40;216", "31;50;206", "63;60;196", "127;70;186", "255;80;176",
           "254;90;166", "252;100;156", "248;110;146"]
    block = [".1", ".6", ".2", ".7", "-.1", "0", ".5", ".05", ".1", ".9"]
    for base, first in ((5460, 1), (5440, 12)):
        lines += [f"I{base}=360", f"F{base - 1}=.0", f"I{base - 2}={first}", f"I{base - 3}={first + 10}",
                  f"I{base - 4}=360", f"F{base - 5}=.0"]
        lines += [f"F{base - 6 - i}={v}" for i, v in enumerate(block)]
        for i, (v, a) in enumerate(zip(values, aux)):
            lines += [f"F{4 + 2 * (first + i)}={v}", f"B{5 + 2 * (first + i)}={a}"]
    lines.append("VF")
    ep = endpoint()
    replies = ep.feed("".join(f"{line}\r" for line in lines).encode())
    assert replies == PROMPT * len(lines)
    mem = ep.memory
    assert read_curve(mem, 1).first_point == 1 and read_curve(mem, 2).last_point == 22
    reads = {
        "I1": "I0001=2", "I5460": "I5460=360", "F5459": "F5459=0.0000000", "I5458": "I5458=1",
        "I5457": "I5457=11", "F5454": "F5454=0.1000000", "F5450": "F5450=-0.1000000", "F5447": "F5447=0.0500000",
        "F5445": "F5445=0.9000000", "I5438": "I5438=12", "I5437": "I5437=22", "F0026": "F0026=0.9999999",
        "B0007": "B0007=1;10;246", "B17": "B0017=63;60;196", "B0049": "B0049=248;110;146", "F28": "F0028=0.0000000",
    }
    for request, answer in reads.items():
        assert ep.feed(f"{request}\r".encode()) == answer.encode() + PROMPT


# -- line handling -------------------------------------------------------------------------------


def test_partial_lines_across_feeds_and_byte_by_byte():
    ep = endpoint()
    assert ep.feed(b"F6=0.12") == b"" and ep.pending == b"F6=0.12"
    assert ep.feed(b"34567") == b""
    assert ep.feed(b"\r") == PROMPT and ep.pending == b""
    out = b"".join(ep.feed(bytes([b])) for b in b"F6\r")
    assert out == b"F0006=0.1234567\r\n>"


def test_lf_has_no_meaning_and_crlf_ends_a_line():
    ep = endpoint()
    assert ep.feed(b"F8=.5\r\n") == PROMPT
    assert ep.feed(b"\nF\n8\r") == b"F0008=0.5000000" + PROMPT
    assert ep.feed(b"\r") == PROMPT  # an empty line just gets the prompt


def test_spaces_and_lower_case_are_accepted():
    ep = endpoint()
    assert ep.feed(b"f 8 = .25\r") == PROMPT
    assert ep.feed(b"b7 = 1; 2; 3\r") == PROMPT
    assert ep.feed(b"f8\r") == b"F0008=0.2500000" + PROMPT


def test_several_lines_in_one_feed_are_answered_in_order():
    ep = endpoint()
    assert ep.feed(b"F6=.5\rF6\rI5460\r") == PROMPT + b"F0006=0.5000000" + PROMPT + b"I5460=360" + PROMPT


# -- errors: the device's reply, nothing changed ------------------------------------------------


@pytest.mark.parametrize(
    ("line", "code"),
    [
        (b"F6=abc\r", 101), (b"F=1\r", 101), (b"Q5\r", 101), (b"B7=1;2\r", 101), (b"I5460=3.5\r", 101),
        (b"F6=1..2\r", 101), (b"F6==1\r", 101), (b"\xff\r", 101), (b"F" + b"0" * MAX_LINE + b"6=0\r", 101),
        (b"F0\r", 102), (b"F5461=0\r", 102), (b"B9999=1;2;3\r", 102),
        (b"F6=1\r", 103), (b"F6=-1.5\r", 103), (b"I5460=8388608\r", 103), (b"B7=256;0;0\r", 103),
        (b"I1=101\r", 103),
        (b"F3=.5\r", 104),
    ],
)
def test_bad_lines_get_an_error_reply_and_change_nothing(line, code):
    ep = endpoint()
    before = ep.memory.words()
    reply = ep.feed(line)
    assert reply.startswith(f"!E{code} ".encode()) and reply.endswith(PROMPT)
    assert reply.isascii()
    assert ep.memory.words() == before and ep.memory.modified == ()
    assert ep.status[30] == code and ep.last_error is not None and ep.last_error.code == code
    assert ep.feed(b"S30\r") == f"S030={code}.000".encode() + PROMPT  # §25: checked by S30 "last error"
    assert ep.feed(b"F6\r") == b"F0006=0.0000000" + PROMPT  # the interface goes on


def test_error_text_names_field_value_and_range():
    ep = endpoint()
    reply = ep.feed(b"F6=1.5\r").decode()
    assert "F0006" in reply and "1.5" in reply and "-1 <= value < 1" in reply
    reply = ep.feed(b"F5461\r").decode()
    assert "5461" in reply and "1 ... 5460" in reply


def test_overlong_line_is_rejected_whole_and_the_next_line_works():
    ep = endpoint()
    reply = ep.feed(b"F6=0." + b"1" * 40 + b"\rF6\r")
    assert reply.startswith(b"!E101 ") and reply.endswith(b"F0006=0.0000000" + PROMPT)


# -- RESETF / VF ---------------------------------------------------------------------------------


def test_resetf_and_vf_commands():
    ep = endpoint()
    assert ep.feed(b"RESETF\r") == PROMPT
    assert ep.memory.curve_count() == 0 and ep.memory.curve_count(valid=True) == 1
    assert ep.feed(b"VF\r") == PROMPT
    assert ep.memory.curve_count(valid=True) == 0


# -- cam commands ----------------------------------------------------------------------------------


def test_cam_commands_pass_through_to_the_handler():
    rec = Recorder()
    assert isinstance(rec, CamCommands)
    ep = endpoint(rec)
    lines = b"SETC 1\rSC1\rSETM 35\rSM 12.5\rSETS\rSS\rPOSR CAM\rPR\rLOOP 10\rLP 0\rLOOP 65000\rSETM 0\rSETM 100\r"
    assert ep.feed(lines) == PROMPT * 13
    assert rec.calls == [("setc", 1), ("setc", 1), ("setm", 35.0), ("setm", 12.5), ("sets",), ("sets",),
                         ("posr_cam",), ("posr_cam",), ("loop", 10), ("loop", 0), ("loop", 65000), ("setm", 0.0),
                         ("setm", 100.0)]


def test_setc_of_a_non_existent_curve_is_e17_and_not_passed_on():
    # §22 "E17: Curve not present"
    rec = Recorder()
    ep = endpoint(rec)
    reply = ep.feed(b"SETC 2\r")
    assert reply.startswith(b"!E17 curve 2 not present") and reply.endswith(PROMPT)
    assert rec.calls == [] and ep.status[30] == 17


@pytest.mark.parametrize(("line", "code"), [
    (b"SETM 101\r", 103), (b"SETM -1\r", 103), (b"LOOP 65001\r", 103), (b"LOOP -1\r", 103), (b"LOOP 1.5\r", 101),
    (b"SETC x\r", 101), (b"SETC\r", 101), (b"SETM .P31\r", 103),
])
def test_cam_command_arguments_are_range_checked(line, code):
    rec = Recorder()
    reply = endpoint(rec).feed(line)
    assert reply.startswith(f"!E{code} ".encode()) and rec.calls == []


def test_operation_parameter_arguments_p40_to_p49():
    # §9: "SETC .P40, SETM .P40, LOOP .P40"
    rec = Recorder()
    ep = endpoint(rec)
    assert ep.feed(b"P40=1\rP41=35.5\rP42=7\r") == PROMPT * 3
    assert ep.feed(b"SETC .P40\rSETM .P41\rLOOP .P42\r") == PROMPT * 3
    assert rec.calls == [("setc", 1), ("setm", 35.5), ("loop", 7)]
    ep.feed(b"P42=2.5\r")
    assert ep.feed(b"LOOP .P42\r").startswith(b"!E103 ")


def test_handler_errors_go_back_to_the_host():
    ep = endpoint(Recorder(CompaxError("curve operation active", code=107)))
    assert ep.feed(b"LOOP 1\r").startswith(b"!E107 curve operation active")
    ep = endpoint(Recorder(ValueError("no curve selected")))
    assert ep.feed(b"SETS\r").startswith(b"!E107 no curve selected")


def test_cam_commands_without_a_handler():
    ep = endpoint()
    assert ep.feed(b"SETC 1\r").startswith(b"!E107 ")
    assert ep.feed(b"POSR CAM\r").startswith(b"!E107 ")


# -- parameters and status -------------------------------------------------------------------------


def test_parameter_write_read_and_vp():
    ep = endpoint()
    assert ep.feed(b"P31=2\r") == PROMPT
    assert ep.feed(b"P31\r") == b"P031=2" + PROMPT
    assert ep.parameters[31] == 0
    assert ep.feed(b"VP\r") == PROMPT and ep.parameters[31] == 2
    assert ep.feed(b"P35=-2.5\rP035\r") == PROMPT + b"P035=-2.500000" + PROMPT
    assert ep.feed(b"P210=1\r") == PROMPT and ep.parameters[210] == 1  # effective immediately
    assert ep.feed(b"P98=720\rVC\r") == PROMPT * 2 and ep.parameters[98] == 720
    assert ep.feed(b"RESETP\r") == PROMPT and ep.parameters[31] == 0


def test_parameter_errors():
    ep = endpoint()
    assert ep.feed(b"P31=7\r").startswith(b"!E103 P31 = 7 out of range")
    assert ep.feed(b"P7=1\r").startswith(b"!E105 ")
    assert ep.feed(b"P7\r").startswith(b"!E105 ")
    assert ep.feed(b"P31=x\r").startswith(b"!E101 ")
    assert ep.parameters.written[31] == 0
    ep.feed(b"P79=50\r")
    assert ep.feed(b"VP\r").startswith(b"!E103 P79")


def test_status_read():
    ep = endpoint()
    ep.status[44] = 350.0
    ep.status[48] = LOOP_ENDLESS
    assert ep.feed(b"S44\r") == b"S044=350.000" + PROMPT
    assert ep.feed(b"S48\r") == b"S048=-8388608.000" + PROMPT
    assert ep.feed(b"S30\r") == b"S030=0.000" + PROMPT
    ep.status.indicators[32] = 1000.0
    ep.feed(b"P233=32\rVP\r")
    assert ep.feed(b"S13\r") == b"S013=1000.000" + PROMPT
    assert ep.feed(b"S40\r").startswith(b"!E105 ")


def test_execute_answers_one_line():
    ep = endpoint()
    assert ep.execute("F6=.5") == PROMPT and ep.execute("F6") == b"F0006=0.5000000" + PROMPT


# -- sessions: one line buffer per connection ---------------------------------------------------


def test_sessions_share_the_device_but_not_the_half_received_line():
    ep = endpoint()
    a, b = ep.session(), ep.session()
    assert a.feed(b"F6") == b"" and a.pending == b"F6"
    assert b.feed(b"F6=.5\r") == PROMPT and b.pending == b""  # b's line is b's alone
    assert a.feed(b"\r") == b"F0006=0.5000000" + PROMPT  # the same cam memory
    assert ep.feed(b"F6\r") == b"F0006=0.5000000" + PROMPT  # the endpoint's own session


@pytest.fixture
def served():
    """The COMPAX personality served over TCP on a cycling machine: (machine, server, queue)."""
    m = build(small())
    m.run(0.1)
    fed = Fed(m.commands)
    srv = SerialTcpServer(m.device.byte_endpoint(), fed).start()
    stop = threading.Event()
    th = threading.Thread(target=_cycling, args=(m, stop))
    th.start()
    try:
        yield m, srv, fed
    finally:
        stop.set()
        th.join()
        srv.stop()


def _host_read(sock) -> bytes:
    """Read as the manual's host does: up to the prompt ">"."""
    got = b""
    while not got.endswith(b">"):
        chunk = sock.recv(1)
        if not chunk:
            break
        got += chunk
    return got


def test_a_half_line_of_a_closed_connection_is_not_glued_onto_the_next_clients_line(served):
    m, srv, fed = served
    m.device.network_writes = True
    with socket.create_connection(srv.address, timeout=5) as first:
        first.sendall(b"F6")  # a host that dies in the middle of "F6<cr>"
        fed.wait(1)
    with socket.create_connection(srv.address, timeout=5) as second:
        second.sendall(b"P33\r")
        assert _host_read(second) == b"P033=0" + PROMPT  # not "F6P33"
    with socket.create_connection(srv.address, timeout=5) as third:
        third.sendall(b"F6=.5")  # a write that was never ended
        fed.wait(3)
    with socket.create_connection(srv.address, timeout=5) as fourth:
        fourth.sendall(b"\r")  # an empty line, to see the prompt, must not end the dead client's write
        assert _host_read(fourth) == PROMPT
    assert m.device.memory.read("F", 6) == 0.0


# lines that are refused, one or more for every error number of the interface
REFUSED_LINES = [
    b"hello", b"F=1", b"F6=abc", b"F6=>", b"F6 > 1", b"I5460=3.5", b"B7=1;2", b"\xff\xfe", b"F" + b"0" * 40,
    b"F0", b"F5461=0", b"B9999=1;2;3",  # E102
    b"F6=1.5", b"I5460=8388608", b"B7=256;0;0", b"P33=7", b"LOOP 70000", b"SETM 101",  # E103
    b"F3=.5", b"I3=5",  # E104
    b"P7", b"P7=1", b"S40",  # E105 (with the long lists of what is known)
    b"SETC 9",  # E17
    b"SETM 50", b"LOOP .P31", b"SETC .P50",  # E107 / E103
]


def test_every_error_reply_over_tcp_is_one_short_ascii_line_ending_at_the_prompt(served):
    # the manual's host reads up to ">": a ">" inside an error text would cut the reply in two
    # and leave the rest to be taken as the answer to the host's next line
    m, srv, _ = served
    with socket.create_connection(srv.address, timeout=5) as c:
        for writes in (False, True):  # refused for want of --allow-writes (E104 / E107), then as lines
            m.device.network_writes = writes
            for line in REFUSED_LINES + [b"F6=0.5", b"VF", b"RESETF", b"P35=2"] * (not writes):
                c.sendall(line + b"\r")
                reply = _host_read(c)
                assert reply.startswith(b"!E") and reply.endswith(PROMPT), (line, reply)
                text = reply[: -len(PROMPT)]
                assert len(text) <= MAX_ERROR_REPLY and all(0x20 <= b < 0x7F for b in text), (line, reply)
                c.sendall(b"S30\r")  # the next answer is the next line's, whole
                assert _host_read(c) == f"S030={int(text[2:].split()[0])}.000".encode() + PROMPT


@settings(max_examples=300)
@given(st.lists(st.binary(max_size=40).map(lambda b: b.replace(b"\r", b"")), min_size=1, max_size=5))
def test_any_line_gets_exactly_one_prompt(lines):
    # whatever a host sends, every line is answered with exactly one ">", the prompt at its end
    ep = endpoint(Recorder())
    out = ep.feed(b"".join(line + b"\r" for line in lines))
    assert out.count(b">") == len(lines) and out.endswith(PROMPT)
    for reply in out.split(PROMPT)[:-1]:
        assert all(0x20 <= b < 0x7F for b in reply) and (not reply.startswith(b"!E") or len(reply) <= MAX_ERROR_REPLY)


@given(st.integers(1, 999), st.text(max_size=300))
def test_error_reply_of_any_text_is_printable_ascii_short_and_without_a_prompt_sign(code, message):
    line = error_reply(code, message)
    assert line.startswith(f"!E{code} ".encode()) and len(line) <= MAX_ERROR_REPLY
    assert b">" not in line and all(0x20 <= b < 0x7F for b in line)


def test_error_texts_of_the_cam_operation_keep_their_meaning_without_the_prompt_sign():
    ep = endpoint(Recorder(CompaxError("coupling M_E = 0.5 > synchronous M_S = 0.3 (§22); first_point ≥ 1 and "
                                       "first_point >= 1", code=103)))
    reply = ep.feed(b"LOOP 1\r")
    assert reply == (b"!E103 coupling M_E = 0.5 more than synchronous M_S = 0.3 (sec. 22); first_point at least 1 "
                     b"and..." + PROMPT)
    assert error_reply(101, "line 'F6 > 1'\n\tnot\x07 ASCII: µ") == b"!E101 line 'F6 more than 1' not? ASCII: ?"
