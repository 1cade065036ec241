"""The CLM's Profibus DP image over the real Modbus TCP server (issue 14): every exchange of the
manual's chapter 10 byte for byte, the I/O channel as system inputs, the diagnostic word, the
watchdog (fault 37) and the refusals.

Register map (profibus.py decision 1): holding 0x0000-0x000C = the PLC's output area (service
channel 0-5, I/O 6-8, variable channel 9-12); input registers 0x0000-0x000D = the CLM's input
area (service 0-5, I/O 6-8, diagnostic 9, variable channel 10-13).

These tests use the personality's register_endpoint() once personality.py offers "modbus", and
install the same hook from profibus_rig.install until then; test_serve_modbus runs the real
`axisline serve --modbus` and waits for that wiring.
"""

from __future__ import annotations

import struct

import pytest
from serving import serve

from axisline.devices.clm.operands import parse_operand
from axisline.devices.clm.personality import ClmPersonality

from .profibus_rig import Served, machine, machine_file

# service control/status word bits (spec §9.5): R/W 12, L 10, T 8, length 7-4, format 3-0
R, E, L, T, B = 0x1000, 0x2000, 0x0400, 0x0100, 0xB


def word(*, r=0, e=0, last=0, t=0, length=0, fmt=B) -> int:
    return (R if r else 0) | (E if e else 0) | (L if last else 0) | (T if t else 0) | length << 4 | fmt


def data_words(data: bytes) -> list[int]:
    data = data.ljust(10, b"\0")
    return [data[k] << 8 | data[k + 1] for k in range(0, 10, 2)]


@pytest.fixture
def served(tmp_path):
    s = Served(machine(tmp_path))
    s.cycles(3)
    yield s
    s.close()


def send(s: Served, control: int, data: bytes = b"") -> tuple[int, bytes]:
    """The master's service words (one FC16), then the CLM's (FC4): (status word, data bytes)."""
    assert s.write(0, [control, *data_words(data)])[0] == 16
    raw = s.read_bytes(0, 6)
    status = raw[0] << 8 | raw[1]
    return status, raw[2: 2 + (status >> 4 & 0xF)]


def test_reading_a_value_l7870(served):
    """L7870-7910, Figs. 10-18..10-23: '? N0000 ' written (R=0, L=1, T=1, length 8), the write
    response without data, then the 14-byte reply '# N0000 NOP   ' in a 10-byte and a 4-byte
    fragment, the toggle bit echoing the master's (errata 5)."""
    status, data = send(served, word(last=1, t=1, length=8), bytes.fromhex("3F 20 4E 30 30 30 30 20"))
    assert status == word(last=1, t=1, length=0) and data == b""  # Fig. 10-19
    status, data = send(served, word(r=1, last=1, t=0))  # Fig. 10-20
    assert status == word(r=1, last=0, t=0, length=10)  # Fig. 10-21
    assert data == bytes.fromhex("23 20 4E 30 30 30 30 20 4E 4F")
    status, data = send(served, word(r=1, last=1, t=1))  # Fig. 10-22
    assert status == word(r=1, last=1, t=1, length=4)  # Fig. 10-23
    assert data == bytes.fromhex("50 20 20 20")


def test_writing_a_value_l7914(tmp_path):
    """L7914-7975, Figs. 10-24..10-28: '# N0000 NOP ' (12 bytes) in two fragments, each answered
    by a copy with length 0 and L set; the confirmation read returns 'Y ' (59 20). The
    instruction is then NOP in the CLM's memory."""
    s = Served(machine(tmp_path, program="0000 WAI 01.000\n0001 JMP 0000\n"))
    try:
        s.cycles(3)
        assert s.m.device.memory.program[0].mnemonic == "WAI"
        status, _ = send(s, word(last=0, t=1, length=10), b"# N0000 NO")  # Fig. 10-24
        assert status == word(last=1, t=1, length=0)  # Fig. 10-25
        status, _ = send(s, word(last=1, t=0, length=2), bytes.fromhex("50 20"))  # Fig. 10-26
        assert status == word(last=1, t=0, length=0)  # Fig. 10-27: no error bit
        status, data = send(s, word(r=1, last=1, t=1))  # Fig. 10-28
        assert status == word(r=1, last=1, t=1, length=2) and data == bytes.fromhex("59 20")
        assert s.m.device.memory.program[0].mnemonic == "NOP"
    finally:
        s.close()


def test_error_reply_plain_text_l7996(served):
    """L7996-8008, Fig. 10-31: '? N3000 ' is refused with E = 1 and the code 0x010C (Status 01
    error 12 "Block # too large", decimal 12 = 0x0C, errata 7); the reads that follow return
    the plain text 'X 01 12 Block # too large' unpadded in 10 + 10 + 5 bytes (errata 12), with
    0x23 for the '#' the manual prints as 2C (errata 4)."""
    status, data = send(served, word(last=1, t=1, length=8), b"? N3000 ")
    assert status == word(e=1, last=1, t=1, length=2)  # Fig. 10-29: R and T as the master's
    assert data == bytes.fromhex("01 0C")
    fragments = []
    for t in (0, 1, 0):
        status, data = send(served, word(r=1, last=1, t=t))
        fragments.append((status, data))
    assert [d for _, d in fragments] == [bytes.fromhex("58 20 30 31 20 31 32 20 42 6C"),
                                        bytes.fromhex("6F 63 6B 20 23 20 74 6F 6F 20"),
                                        bytes.fromhex("6C 61 72 67 65")]
    assert [s & (L | T | 0xF0) for s, _ in fragments] == [0x00A0, T | 0x00A0, L | 0x0050]
    assert all(s & E == 0 and s & R for s, _ in fragments)


def test_terminate_drops_the_reply_l8014(served):
    """L8010-8036, Fig. 10-32: format 0xF with length, L and R at 0 and T toggled ends the
    exchange: the slave echoes it and the rest of the reply is gone (the next read is empty)."""
    send(served, word(last=1, t=1, length=8), b"? N0000 ")
    status, data = send(served, word(r=1, last=1, t=0))
    assert status >> 4 & 0xF == 10 and not status & L  # a fragment still to come
    status, _ = send(served, word(t=1, fmt=0xF))
    assert status == word(t=1, fmt=0xF)
    status, data = send(served, word(r=1, last=1, t=0))
    assert status == word(r=1, last=1, t=0, length=0) and data == b""


def test_variable_handshake_fig_10_13(served):
    """L7736-7748, Fig. 10-13: after the restart the handshake bits are equal (no function); a
    toggled control bit is a request, the status bit follows when it is processed. V600 written
    in format 1 (fixed point 3: 12345.678 as 12345678), read back in format 0 (rounded)."""
    def var_words():
        return served.read(10, 4)

    assert var_words()[:2] == [0, 0]  # no function
    number, fmt1, fmt0 = 600, 1 << 10, 0 << 10
    served.write(9, [0, 0x8000 | fmt1 | number, *struct.unpack(">HH", struct.pack(">i", 12345678))])  # request
    rs, ws, hi, lo = var_words()
    assert ws == 0x8000 | fmt1 | number  # processed: the status bit follows
    assert served.m.device.memory.variables[600] == 12_345_678_000
    served.write(9, [0x8000 | fmt0 | number])  # a read request (control bit 0 -> 1)
    rs, ws, hi, lo = var_words()
    assert rs == 0x8000 | fmt0 | number and struct.unpack(">i", struct.pack(">HH", hi, lo))[0] == 12346
    served.write(9, [0x8000 | fmt0 | number])  # written again unchanged: no new request
    served.write(9, [fmt1 | number])  # toggled back 1 -> 0: a request (row "0 1")
    rs, _, hi, lo = var_words()
    assert rs == fmt1 | number and (hi << 16 | lo) == 12345678  # "0 0": processed


def test_variable_channel_errors_over_modbus(served):
    """L7773-7785: a system variable is not writable (error 6 in bits 10-13, bit 14 set)."""
    served.write(9, [0, 0x8000 | 1 << 10 | 100, 0, 5])
    assert served.read(11, 1)[0] == 0x8000 | 0x4000 | 6 << 10 | 100


def test_register_map_and_byte_order(served):
    """profibus.py decisions 1, 2: the user words carry I2.02 in the low byte and I2.03 in the
    high byte (as word 1 carries I2.00 / I2.01 in bits 0-7 / 8-15); the input area is also
    readable by FC3 from 0x0100; the output area reads back by FC3 at 0."""
    served.write(7, [0x1234, 0xABCD])
    image = served.m.device.memory.image
    assert image.get(parse_operand("I2.02", bit=False)) == 0x34 and image.get(parse_operand("I2.03", bit=False)) == 0x12
    assert image.get(parse_operand("I2.04", bit=False)) == 0xCD and image.get(parse_operand("I2.05", bit=False)) == 0xAB
    with served.lock:
        image.set(parse_operand("Q2.02", bit=False), 0x56)
        image.set(parse_operand("Q2.03", bit=False), 0x78)
    assert served.read_bytes(7, 1) == bytes.fromhex("78 56")  # Q2.03 first on the wire
    assert served.read(0x0100, 14, fc=3) == served.read(0, 14)
    assert served.read(7, 2, fc=3) == [0x1234, 0xABCD]


def test_control_word_in_mode_0(served):
    """L7576-7624, L8046-8053 (profibus.py decision 5, 6): B008 '0 1 0 1 05' (mode 0, Profibus
    system signals on): the machine file's hardware Automatic input is ignored, the control
    word selects the mode and starts; the status word shows it (Automatic bit 1, Run bit 9)."""
    dev = served.m.device
    served.cycles(3)
    assert dev.rt.modes.mode == "manual"  # hardware Automatic (wired true) does not count in mode 0
    served.write(6, [1 << 1 | 1 << 4])  # Automatic, Immediate Stop closed
    served.cycles(3)
    assert dev.rt.modes.mode == "automatic" and not dev.rt.modes.running
    served.write(6, [1 << 1 | 1 << 4 | 1 << 3])  # Start
    served.cycles(3)
    served.write(6, [1 << 1 | 1 << 4])
    served.cycles(3)
    assert dev.rt.modes.running
    status = served.read(6, 1)[0]
    assert status & 1 << 1 and status & 1 << 9 and status & 1 << 5 and not status & 1
    # the hardware bit is put back after each cycle: the image shows the wired input (decision 6)
    assert dev.memory.image.get(parse_operand("I0.00.3", bit=True)) == 0


def test_mode_3_ors_hardware_and_fieldbus(tmp_path):
    """L5067-5071, L5795 (decision 5): mode 3 ORs the hardware and the control word, '1'
    dominant: the hardware Automatic input gives Automatic with the control word 0; an open
    hardware E-Stop is overridden by the control word's E-Stop bit 2."""
    s = Served(machine(tmp_path, b008="0 1 3 1 05", inputs='"I0.00.2" = false'))
    try:
        s.write(6, [1 << 2])  # E-Stop closed from the fieldbus (fault 03 of the first cycles stays until cleared)
        s.cycles(3)
        s.write(6, [1 << 2 | 1 << 7])  # Clear Errors
        s.cycles(3)
        s.write(6, [1 << 2])
        s.cycles(3)
        modes = s.m.device.rt.modes
        assert modes.mode == "automatic" and modes.fault_error is None
        s.write(6, [0])  # the fieldbus E-Stop opens too: fault 03
        s.cycles(3)
        assert modes.fault_error is not None and modes.fault_error.code == "03"
        assert s.read(9, 1)[0] == 0x03  # the diagnostic word
    finally:
        s.close()


def test_status_word_and_diagnostic(served):
    """Figs. 10-5, errata 19, L7692 (decisions 7, 8): brake 3 in bit 11, the reserved bits 0.
    Parameter and Automatic selected together
    from the fieldbus is fault 08: the diagnostic word is 0x0008 and the Fault bit (Q2.00.5,
    active low) drops; Clear Errors (bit 7) clears it once the mode inputs are valid."""
    assert served.read(9, 1)[0] == 0x00 and served.read(6, 1)[0] & 1 << 5
    image = served.m.device.memory.image
    with served.lock:  # Brake 3 (Q0.02.0) shows as status bit 11 (Q2.01.3)
        image.set(parse_operand("Q0.02.0", bit=True), 1)
    served.cycles(1)
    assert served.read(6, 1)[0] & 1 << 11 and not served.read(6, 1)[0] & (1 << 12 | 1 << 8 | 1 << 10)
    assert image.get(parse_operand("Q2.01.3", bit=True)) == 1
    served.write(6, [1 << 0 | 1 << 1])
    served.cycles(3)
    assert served.read(9, 1)[0] == 0x08
    assert not served.read(6, 1)[0] & 1 << 5
    served.write(6, [0])
    served.cycles(2)
    served.write(6, [1 << 7])
    served.cycles(3)
    assert served.read(9, 1)[0] == 0x00 and served.read(6, 1)[0] & 1 << 5


def test_watchdog_timeout_is_fault_37(served):
    """V046, fault 37 (decision 9): with the watchdog at 20 ms (register 0x0200, shown in V046) a
    PLC that stops writing gives fault 37 after 20 ms of NC cycles; the control word is then
    taken as 0 and the next write re-arms the watchdog."""
    dev = served.m.device
    served.write(0x0200, [20])
    assert dev.memory.variables[46] == 20_000_000
    assert served.read(0x0201, 1)[0] == 0  # not started before the first write
    served.write(6, [1 << 1 | 1 << 4])
    served.cycles(3)
    assert dev.rt.modes.mode == "automatic" and served.read(0x0201, 1, fc=3)[0] == 1
    served.cycles(15)  # 30 ms without a write
    assert dev.rt.modes.fault_error.code == "37"
    assert served.read(9, 1)[0] == 0x37 and served.read(0x0201, 1)[0] == 2
    assert dev.rt.modes.mode == "manual"  # the control word was taken as 0
    assert dev.profibus.summary()["watchdog_expiries"] == 1
    served.write(6, [1 << 7])  # Clear Errors: re-armed, and the fault is cleared
    served.cycles(3)
    assert dev.rt.modes.fault_error is None and served.read(0x0201, 1)[0] == 1


def test_format_1_has_no_variable_channel(tmp_path):
    """Fig. 10-4 (decision 3): format 1 sends 3 and receives 4 words: the variable channel's
    registers are refused with exception 02, the rest is served."""
    s = Served(machine(tmp_path, b008="1 1 0 1 05"))
    try:
        s.cycles(3)
        assert len(s.read(0, 10)) == 10
        assert s.request(struct.pack(">BHH", 4, 0, 14)) == bytes((0x84, 2))
        assert s.write(9, [0x8000]) == bytes((0x90, 2))
        assert s.write(6, [0])[0] == 16
    finally:
        s.close()


def test_address_outside_2_89_is_fault_34(tmp_path):
    """L7519-7525 (decision 4): B008 address 00 (delivery) or 90 does not start the card: fault
    34 naming B008, every request of the image answered with exception 04."""
    s = Served(machine(tmp_path, b008="0 1 0 1 90"))
    try:
        s.cycles(5)
        fault = s.m.device.rt.modes.fault_error
        assert fault is not None and fault.code == "34" and "B008" in fault.message and "90" in fault.message
        assert s.request(struct.pack(">BHH", 4, 0, 14)) == bytes((0x84, 4))
        assert s.write(6, [0]) == bytes((0x90, 4))
        assert s.read(0x0200, 1) == [1000]  # the watchdog registers stay readable
    finally:
        s.close()


def test_refusals(served):
    """Decision 10: outside the map 02, the input area is not writable (02), a write without
    serve --allow-writes is exception 01; a refused request changes nothing."""
    assert served.request(struct.pack(">BHH", 4, 0x0300, 1)) == bytes((0x84, 2))
    assert served.write(0x0100, [1]) == bytes((0x90, 2))
    assert served.write(12, [1, 2]) == bytes((0x90, 2))
    assert served.read(12, 1, fc=3) == [0]
    served.m.device.network_writes = False
    assert served.write(6, [2]) == bytes((0x90, 1))
    assert served.read(6, 1, fc=3) == [0]


@pytest.mark.skipif("modbus" not in ClmPersonality.endpoints, reason="personality.py does not offer the Modbus endpoint yet")
def test_serve_modbus(tmp_path):
    """Issue 14: `axisline serve MACHINE --modbus` serves the DP image: the manual's read of
    '? N0000 ' (L7870) over a real TCP connection to the served machine."""
    import socket
    import time

    proc, endpoints = serve(str(machine_file(tmp_path)), "--modbus", "127.0.0.1:0", "--allow-writes")
    try:
        host, _, port = endpoints["modbus"].rpartition(":")
        with socket.create_connection((host, int(port)), timeout=10) as sock:
            def request(pdu: bytes) -> bytes:
                sock.sendall(struct.pack(">HHHB", 1, 0, len(pdu) + 1, 1) + pdu)
                head = b""
                while len(head) < 7:
                    head += sock.recv(7 - len(head))
                body, length = b"", struct.unpack(">HHHB", head)[2] - 1
                while len(body) < length:
                    body += sock.recv(length - len(body))
                return body

            def exchange(words: list[int]) -> bytes:
                assert request(struct.pack(">BHHB6H", 16, 0, 6, 12, *words))[0] == 16
                deadline = time.monotonic() + 5
                while True:  # the CLM answers at its next cycle boundary
                    reply = request(struct.pack(">BHH", 4, 0, 6))[2:]
                    if (reply[0] << 8 | reply[1]) & T == words[0] & T or time.monotonic() > deadline:
                        return reply

            assert exchange([word(last=1, t=1, length=8), *data_words(b"? N0000 ")])[:2] == bytes.fromhex("05 0B")
            first = exchange([word(r=1, last=1, t=0), 0, 0, 0, 0, 0])
            second = exchange([word(r=1, last=1, t=1), 0, 0, 0, 0, 0])
            assert first[2:] + second[2:6] == b"# N0000 NOP   "
    finally:
        proc.terminate()
        proc.wait(timeout=20)


@pytest.mark.parametrize("b008, automatic", [("0 0 3 1 05", False), ("0 1 0 0 05", True)])
def test_which_side_gives_the_system_inputs(tmp_path, b008, automatic):
    """Decision 5: mode 3 with the hardware system signals 0 acts as mode 0 (the hardware
    Automatic input, wired true, does not count); with the Profibus system signals 0 the control
    word is no system input (the hardware's Automatic counts, the control word's Parameter bit
    does not) and a lost PLC is no fault 37 (decision 9), though its words go to 0."""
    s = Served(machine(tmp_path, b008=b008))
    try:
        s.write(0x0200, [10])
        s.write(6, [1 << 0, 0x00FF])  # Parameter Mode from the fieldbus, user word I2.02 = FF
        s.cycles(3)
        modes = s.m.device.rt.modes
        image = s.m.device.memory.image
        assert image.get(parse_operand("I2.02", bit=False)) == 0xFF
        if automatic:
            assert modes.mode == "automatic"
            s.cycles(10)  # 20 ms without a write: the words go, no fault
            assert s.read(0x0201, 1)[0] == 2 and modes.fault_error is None
            assert image.get(parse_operand("I2.02", bit=False)) == 0
        else:
            assert modes.mode == "parameter"
            s.write(6, [0])
            s.cycles(3)
            assert modes.mode == "manual"
    finally:
        s.close()
