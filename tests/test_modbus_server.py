"""Modbus TCP server: requests reach the device's registers at cycle boundaries; writes need the enable."""

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
def served():
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
    client = ModbusTcpClient("127.0.0.1", port=srv.address[1], timeout=3)
    assert client.connect()
    yield client, regs, cycles
    client.close()
    stop.set()
    th.join()
    srv.stop()


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
