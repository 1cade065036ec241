"""The FS701's Modbus holding registers: a refused multi-register write changes nothing.

The single commands 0x0900 + n (serial codes) sit at holding registers 2 x code, two
registers each; Adjust Program is code 0x091E (bit 30), Test Program 0x091F (bit 31). An
FC16 over both asks for the two programs at once, which the FS701 refuses; before the
register map checked writes as a whole, the Adjust bit was already set (and the Adjust
program started) when the Test bit was refused.
"""

from __future__ import annotations

import socket
import struct
import time

import pytest

from axisline.devices.fs701.registers import CommandRefusedError, RegisterMap
from axisline.fieldbus.modbus import ModbusServer

# the example line with Control Enable and Start from the serial link (so OFF), and a thread
# running its cycles in about real time
from devices.fs701.test_programs import serial_machine
from devices.fs701.test_serve import Cycling

ADJUST, TEST, CONTROL_ENABLE = 0x091E, 0x091F, 0x0900
CUTTING_LENGTH = 0x0000


def fc16(tid: int, address: int, values: list[int]) -> bytes:
    pdu = struct.pack(f">BHHB{len(values)}H", 16, address, len(values), 2 * len(values), *values)
    return struct.pack(">HHHB", tid, 0, len(pdu) + 1, 1) + pdu


def reply(sock: socket.socket) -> bytes:
    buf = b""
    while len(buf) < 7 or len(buf) < 6 + struct.unpack(">H", buf[4:6])[0]:
        chunk = sock.recv(256)
        assert chunk, "connection closed"
        buf += chunk
    return buf[7:]


def test_fc16_over_adjust_and_test_program_is_refused_and_starts_nothing():
    m = serial_machine()
    dev = m.device
    srv = ModbusServer(dev.register_endpoint(), m.commands, "127.0.0.1", 0, writes_allowed=lambda: dev.network_writes).start()
    try:
        with Cycling(m), socket.create_connection(srv.address, timeout=5) as s:
            before = dev.registers.status.serial_commands
            assert not before & 1  # Control Enable OFF: either program alone would start
            s.sendall(fc16(1, 2 * ADJUST, [0, 1, 0, 1]))
            answer = reply(s)
            assert answer[0] == 0x90 and answer[1] in (2, 3, 4)  # refused
            # Control Enable and Adjust in one write: Adjust needs Control Enable off
            block = [0] * 62
            block[1] = 1  # 0x0900 Control Enable = 1
            block[61] = 1  # 0x091E Adjust Program = 1
            s.sendall(fc16(2, 2 * CONTROL_ENABLE, block))
            assert reply(s)[0] == 0x90
            time.sleep(0.1)  # cycles run: a set command bit would start the program now
            assert dev.registers.status.serial_commands == before
            assert dev.programs == []
    finally:
        srv.stop()


def test_a_refused_write_of_several_registers_changes_none_of_them():
    m = RegisterMap()
    with pytest.raises(CommandRefusedError):
        m.write_many([(CUTTING_LENGTH, 2000), (ADJUST, 1), (TEST, 1)])
    assert (m.read(CUTTING_LENGTH), m.status.serial_commands) == (1000, 0)
    m.write(CONTROL_ENABLE, 1)
    with pytest.raises(CommandRefusedError):
        m.write_many([(ADJUST, 0), (TEST, 1)])  # Test Program needs Control Enable off
    assert m.status.serial_commands == 1
    # judged on the state it produces: Control Enable off and Adjust on, in either order
    m.write_many([(ADJUST, 1), (CONTROL_ENABLE, 0)])
    assert m.status.serial_commands == 1 << 30


def test_a_write_that_produces_a_valid_state_is_applied_whole():
    m = RegisterMap()
    m.write_many([(CUTTING_LENGTH, 2000), (ADJUST, 1), (TEST, 0)])
    assert (m.read(CUTTING_LENGTH), m.read(ADJUST), m.read(TEST)) == (2000, 1, 0)
