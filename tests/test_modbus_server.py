"""Modbus TCP server: requests reach the device's registers at cycle boundaries; writes need the enable.

The raw-socket tests below send Modbus TCP frames byte for byte, as a PLC or a test tool
does, and read the replies the same way: pipelined requests, every exception a client can
provoke, garbage on the connection; none of it may leave a traceback in the server's log.
"""

import logging
import socket
import struct
import threading
import time

import pytest
from pymodbus.client import ModbusTcpClient

from axisline.fieldbus.modbus import ModbusServer, RegisterRefused
from axisline.kernel import CommandQueue


class Registers:
    """100 holding registers; input registers read as holding + 1000."""

    def __init__(self):
        self.network_writes = True
        self.r = list(range(100))
        self.boundaries = []

    def read_registers(self, kind, address, count):
        if address + count > 100:
            raise RegisterRefused(f"address {address + count - 1} beyond 99")
        base = self.r[address : address + count]
        return base if kind == "holding" else [x + 1000 for x in base]

    def write_registers(self, address, values):
        if address + len(values) > 100 or any(v > 5000 for v in values):
            raise RegisterRefused("refused")
        self.r[address : address + len(values)] = values


@pytest.fixture
def server():
    """A server on a free port with its cycle running: (server, registers)."""
    q = CommandQueue()
    regs = Registers()
    srv = ModbusServer(regs, q, "127.0.0.1", 0).start()
    stop = threading.Event()
    cycles = []

    def cycle():
        c = 0
        while not stop.is_set():
            if q.apply_pending(c):
                cycles.append(c)
            c += 1
            time.sleep(0.0005)

    th = threading.Thread(target=cycle, daemon=True)
    th.start()
    srv.cycles = cycles
    yield srv, regs
    stop.set()
    th.join()
    srv.stop()


@pytest.fixture
def served(server):
    srv, regs = server
    client = ModbusTcpClient("127.0.0.1", port=srv.address[1], timeout=3)
    assert client.connect()
    yield client, regs, srv.cycles
    client.close()


def test_reads_with_function_codes_3_and_4(served):
    client, regs, cycles = served
    assert client.read_holding_registers(3, count=4).registers == [3, 4, 5, 6]
    assert client.read_input_registers(3, count=2).registers == [1003, 1004]
    assert cycles, "requests were applied by the cycle"


def test_writes_with_function_codes_6_and_16(served):
    client, regs, _ = served
    assert not client.write_registers(5, [111, 222]).isError()
    assert not client.write_register(7, 333).isError()
    assert client.read_holding_registers(4, count=5).registers == [4, 111, 222, 333, 8]


def test_refused_address_or_value_is_exception_2_and_changes_nothing(served):
    client, regs, _ = served
    r = client.read_holding_registers(98, count=4)
    assert r.isError() and r.exception_code == 2
    before = list(regs.r)
    w = client.write_registers(10, [1, 9999])
    assert w.isError() and w.exception_code == 2
    assert regs.r == before


def test_writes_need_the_operators_enable(served):
    client, regs, _ = served
    regs.network_writes = False
    w = client.write_register(1, 7)
    assert w.isError() and w.exception_code == 1
    assert regs.r[1] == 1
    assert client.read_holding_registers(1, count=1).registers == [1]  # reads still work


# ---------------------------------------------------------------------------- raw frames


def frame(tid, pdu, unit=1):
    """A Modbus TCP request: MBAP header (transaction, protocol 0, length, unit) + PDU."""
    return struct.pack(">HHHB", tid, 0, len(pdu) + 1, unit) + pdu


def read_pdu(address, count, fc=3):
    return struct.pack(">BHH", fc, address, count)


def write_pdu(address, values):
    return struct.pack(f">BHHB{len(values)}H", 16, address, len(values), 2 * len(values), *values)


def recv_exactly(sock, n):
    buf = b""
    while len(buf) < n:
        chunk = sock.recv(n - len(buf))
        if not chunk:
            raise ConnectionError(f"connection closed after {len(buf)} of {n} bytes")
        buf += chunk
    return buf


def recv_frame(sock):
    """One reply: (transaction id, unit, PDU)."""
    tid, proto, length, unit = struct.unpack(">HHHB", recv_exactly(sock, 7))
    assert proto == 0
    return tid, unit, recv_exactly(sock, length - 1)


def registers_of(pdu):
    fc, n = pdu[0], pdu[1]
    assert fc in (3, 4) and len(pdu) == 2 + n, pdu.hex(" ")
    return list(struct.unpack(f">{n // 2}H", pdu[2:]))


@pytest.fixture
def connect(server):
    srv, _ = server
    socks = []

    def open_():
        s = socket.create_connection(srv.address, timeout=5)
        s.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
        socks.append(s)
        return s

    yield open_
    for s in socks:
        s.close()


@pytest.fixture(autouse=True)
def no_traceback_in_the_log(caplog):
    """Whatever a client sends, the server's log has no traceback (checked after every test)."""
    caplog.set_level(logging.DEBUG)
    yield
    bad = [r for r in caplog.records if r.exc_info or "Traceback" in r.getMessage()]
    assert not bad, "\n".join(caplog.text.splitlines()[:40])


def ask(sock, pdu, tid=7, unit=1):
    sock.sendall(frame(tid, pdu, unit))
    rtid, runit, reply = recv_frame(sock)
    assert (rtid, runit) == (tid, unit)
    return reply


# ---------------------------------------------------------------------------- pipelining


def test_two_requests_sent_back_to_back_get_their_own_replies(connect):
    s = connect()
    s.sendall(frame(0x1111, read_pdu(10, 2)))
    s.sendall(frame(0x2222, read_pdu(50, 3, fc=4)))
    t1, _, r1 = recv_frame(s)
    t2, _, r2 = recv_frame(s)
    assert (t1, registers_of(r1)) == (0x1111, [10, 11])
    assert (t2, registers_of(r2)) == (0x2222, [1050, 1051, 1052])


def test_ten_requests_in_one_segment_are_answered_in_order_none_lost(connect, server):
    _, regs = server
    s = connect()
    requests = [
        (0x0100, read_pdu(0, 2)),
        (0x0101, write_pdu(0, [500, 501])),  # the reads after it see it: requests run in order
        (0x0102, read_pdu(0, 2)),
        (0x0103, read_pdu(1, 1, fc=4)),
        (0x0104, struct.pack(">BHH", 6, 2, 777)),
        (0x0105, read_pdu(2, 1)),
        (0x0106, read_pdu(99, 2)),  # refused: exception 02, the rest still answered
        (0x0107, bytes([0x2B, 0x0E, 0x01, 0x00])),  # unknown function: 01
        (0x0108, read_pdu(90, 10)),
        (0x0109, read_pdu(0, 3, fc=4)),
    ]
    s.sendall(b"".join(frame(tid, pdu, unit=tid & 0xFF) for tid, pdu in requests))
    replies = [recv_frame(s) for _ in requests]
    assert [(t, u) for t, u, _ in replies] == [(tid, tid & 0xFF) for tid, _ in requests]
    pdus = [p for _, _, p in replies]
    assert registers_of(pdus[0]) == [0, 1]
    assert pdus[1] == struct.pack(">BHH", 16, 0, 2)
    assert registers_of(pdus[2]) == [500, 501]
    assert registers_of(pdus[3]) == [1501]
    assert pdus[4] == struct.pack(">BHH", 6, 2, 777)
    assert registers_of(pdus[5]) == [777]
    assert pdus[6] == bytes([0x83, 0x02])
    assert pdus[7] == bytes([0xAB, 0x01])
    assert registers_of(pdus[8]) == list(range(90, 100))
    assert registers_of(pdus[9]) == [1500, 1501, 1777]
    assert regs.r[:3] == [500, 501, 777]


def test_a_request_split_over_several_segments_is_answered_once(connect):
    s = connect()
    data = frame(0x0042, read_pdu(5, 1))
    for b in data:
        s.sendall(bytes([b]))
        time.sleep(0.002)
    assert recv_frame(s) == (0x0042, 1, bytes([3, 2, 0, 5]))


def test_clients_on_separate_connections_each_get_their_own_replies(connect):
    a, b = connect(), connect()
    a.sendall(frame(1, read_pdu(1, 1)) + frame(2, read_pdu(2, 1)))
    b.sendall(frame(1, read_pdu(3, 1)) + frame(2, read_pdu(4, 1)))
    assert [registers_of(recv_frame(b)[2]) for _ in range(2)] == [[3], [4]]
    assert [registers_of(recv_frame(a)[2]) for _ in range(2)] == [[1], [2]]


# ---------------------------------------------------------------------------- exceptions

# function codes the server does not serve, each with a request PDU a client could send:
# bit and file access, diagnostics, the serial-line-only functions, and codes >= 0x80
UNSERVED = [
    bytes([0x01, 0, 0, 0, 8]),  # read coils
    bytes([0x02, 0, 0, 0, 8]),  # read discrete inputs
    bytes([0x05, 0, 1, 0xFF, 0]),  # write single coil
    bytes([0x07]),  # read exception status
    bytes([0x08, 0, 0, 0x12, 0x34]),  # diagnostics: return query data
    bytes([0x0B]),  # get comm event counter
    bytes([0x0C]),  # get comm event log
    bytes([0x0F, 0, 0, 0, 8, 1, 0xFF]),  # write multiple coils
    bytes([0x11]),  # report server id
    bytes([0x14, 7, 6, 0, 1, 0, 0, 0, 1]),  # read file record
    bytes([0x15, 9, 6, 0, 1, 0, 0, 0, 1, 0x12, 0x34]),  # write file record
    bytes([0x16, 0, 0, 0xFF, 0xFF, 0, 0]),  # mask write register
    bytes([0x17, 0, 0, 0, 1, 0, 0, 0, 1, 2, 0, 5]),  # read/write multiple registers
    bytes([0x18, 0, 0]),  # read FIFO queue
    bytes([0x2B, 0x0E, 0x01, 0x00]),  # read device identification
    bytes([0x00]),
    bytes([0x41, 1, 2, 3]),
    bytes([0x81]),
    bytes([0x83, 0, 0, 0, 1]),
    bytes([0xFF]),
]


@pytest.mark.parametrize("pdu", UNSERVED, ids=[f"fc{p[0]:02x}" for p in UNSERVED])
def test_a_function_the_device_does_not_serve_is_exception_01(connect, server, pdu):
    _, regs = server
    before = list(regs.r)
    s = connect()
    assert ask(s, pdu) == bytes([pdu[0] | 0x80, 0x01])
    assert regs.r == before
    assert registers_of(ask(s, read_pdu(4, 1))) == [4]  # the connection still serves


@pytest.mark.parametrize(
    "pdu",
    [
        read_pdu(0, 0),
        read_pdu(0, 126),
        read_pdu(0, 0, fc=4),
        read_pdu(0, 126, fc=4),
        bytes([0x03, 0, 0]),  # too short for address and quantity
        read_pdu(0, 1) + b"\x00",  # too long
        bytes([0x06, 0, 1, 0]),
        struct.pack(">BHHB", 16, 0, 0, 0),  # quantity 0
        struct.pack(">BHHB", 16, 0, 124, 248) + bytes(240),  # quantity 124 > 123 (and cut to fit a frame)
        struct.pack(">BHHBH", 16, 0, 2, 2, 5),  # byte count != 2 x quantity
        struct.pack(">BHHBH", 16, 0, 2, 4, 5),  # fewer bytes than the byte count
        struct.pack(">BHHB3H", 16, 0, 2, 4, 5, 6, 7),  # more bytes than the byte count
        bytes([0x10, 0, 0]),
    ],
    ids=lambda p: p[:8].hex(),
)
def test_a_bad_quantity_or_length_is_exception_03_and_changes_nothing(connect, server, pdu):
    _, regs = server
    before = list(regs.r)
    assert ask(connect(), pdu) == bytes([pdu[0] | 0x80, 0x03])
    assert regs.r == before


@pytest.mark.parametrize(
    "pdu",
    [
        read_pdu(98, 4),  # the device has no register 100
        read_pdu(0xFFFF, 2),  # beyond the 65536 Modbus addresses
        read_pdu(200, 1, fc=4),
        struct.pack(">BHH", 6, 100, 1),
        write_pdu(99, [1, 2]),
        write_pdu(0xFFFF, [1, 2]),
        write_pdu(10, [1, 9999]),  # a value the device refuses
    ],
    ids=lambda p: p.hex(),
)
def test_an_address_the_device_refuses_is_exception_02_and_changes_nothing(connect, server, pdu):
    _, regs = server
    before = list(regs.r)
    assert ask(connect(), pdu) == bytes([pdu[0] | 0x80, 0x02])
    assert regs.r == before


def test_write_file_record_without_writes_enabled_is_refused_and_writes_nothing(connect, server):
    _, regs = server
    regs.network_writes = False
    s = connect()
    before = list(regs.r)
    assert ask(s, bytes([0x15, 9, 6, 0, 1, 0, 0, 0, 1, 0x12, 0x34])) == bytes([0x95, 0x01])
    assert ask(s, write_pdu(0, [9])) == bytes([0x90, 0x01])  # and FC16 needs the enable
    assert regs.r == before


def test_a_device_that_fails_is_exception_04_logged_without_traceback(connect, server, caplog):
    _, regs = server

    def broken(kind, address, count):
        raise RuntimeError("register image not ready")

    regs.read_registers = broken
    s = connect()
    assert ask(s, read_pdu(0, 1)) == bytes([0x83, 0x04])
    assert "register image not ready" in caplog.text


# ---------------------------------------------------------------------------- garbage


@pytest.mark.parametrize(
    "garbage",
    [
        b"GET / HTTP/1.1\r\nHost: plc\r\n\r\n",  # protocol id 0x5420
        bytes(12),  # length 0: no unit id, no function code
        struct.pack(">HHHB", 1, 0, 1, 1),  # length 1: a unit id and no function code
        struct.pack(">HHHB", 1, 0, 300, 1) + bytes(299),  # longer than any Modbus PDU
        bytes(range(256)) * 4,
        b"\xff" * 64,
    ],
    ids=["http", "zeros", "no-function", "too-long", "bytes", "ff"],
)
def test_garbage_closes_that_connection_and_the_server_keeps_serving(connect, garbage):
    s = connect()
    s.sendall(garbage)
    s.settimeout(3)
    try:
        rest = s.recv(4096)
    except ConnectionResetError:
        rest = b""
    assert rest == b""  # closed: the framing is lost, nothing is guessed
    assert registers_of(ask(connect(), read_pdu(6, 1))) == [6]


def test_a_client_that_leaves_mid_request_does_not_disturb_the_server(connect):
    s = connect()
    s.sendall(frame(1, read_pdu(0, 1))[:9])
    s.close()
    assert registers_of(ask(connect(), read_pdu(6, 1))) == [6]


def test_a_request_the_cycle_does_not_take_in_time_is_busy_and_never_runs():
    q = CommandQueue()  # nobody applies it: the machine stopped cycling
    regs = Registers()
    srv = ModbusServer(regs, q, "127.0.0.1", 0, reply_timeout=0.2).start()
    try:
        with socket.create_connection(srv.address, timeout=5) as s:
            assert ask(s, write_pdu(0, [42])) == bytes([0x90, 0x06])
        q.apply_pending(0)
        assert regs.r[0] == 0
    finally:
        srv.stop()


@pytest.mark.parametrize("code", [2, 3, 4])
def test_a_refusal_answers_with_the_exception_code_the_device_gives(connect, server, code):
    _, regs = server

    def refuse(address, values):
        raise RegisterRefused("not now", exception_code=code)

    regs.write_registers = refuse
    assert ask(connect(), write_pdu(0, [1])) == bytes([0x90, code])


def test_a_refusal_takes_only_the_codes_of_a_refusal():
    with pytest.raises(ValueError, match="2, 3 or 4"):
        RegisterRefused("x", exception_code=1)
