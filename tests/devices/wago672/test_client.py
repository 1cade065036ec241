"""End to end over loopback: the machine on the wall clock (1 ms), the Modbus server, a PLC.

The PLC is `Wago672Client` (the handshakes) or plain pymodbus register writes. Every wait
is bounded; the server listens on 127.0.0.1 on a free port.
"""

from __future__ import annotations

import threading
import time
import tomllib
from contextlib import contextmanager
from pathlib import Path

import pytest
from pymodbus.client import ModbusTcpClient

from axisline.config import parse_machine
from axisline.devices.wago672.client import (
    MODES,
    Mbx,
    Wago672Client,
    Wago672ClientError,
    Wago672DeviceError,
    checksum,
    program_rows,
)
from axisline.devices.wago672.coupler import WD_EXPIRED, WD_RUNNING, pack, unpack
from axisline.devices.wago672.image import C1, S1, S2, InputImage, OutputImage, PositioningSetpoints
from axisline.fieldbus.modbus import ModbusServer
from axisline.kernel import WallClock
from axisline.machine import Machine

EXAMPLE = Path(__file__).resolve().parents[3] / "examples" / "wago_stepper.toml"
K = 2560.0  # microsteps per mm
ON = C1.Enable | C1.Stop2_N


def example(**drive) -> dict:
    data = tomllib.loads(EXAMPLE.read_text())
    data["axis"][0]["drive"].update(drive)
    data["device"]["modules"][0]["config"]["SetupAcceleration"] = 30000  # quick reference runs
    return data


@contextmanager
def serving(data: dict | None = None, *, writes: bool = True):
    m = Machine(parse_machine(data or example(), "t.toml"), clock=WallClock(1000), source="t.toml")
    m.device.network_writes = writes
    srv = ModbusServer(m.device.register_endpoint(), m.commands, "127.0.0.1", 0).start()
    th = threading.Thread(target=m.scheduler.run, args=(10**9,), name="machine", daemon=True)
    th.start()
    try:
        yield m, srv.address[1]
    finally:
        m.scheduler.stop()
        th.join(5.0)
        srv.stop()


def until(predicate, timeout: float, what: str) -> float:
    t0 = time.monotonic()
    while not predicate():
        if time.monotonic() - t0 > timeout:
            raise AssertionError(f"{what}: not within {timeout} s")
        time.sleep(0.002)
    return time.monotonic() - t0


def test_enable_move_to_a_target_and_read_the_position_back():
    with serving() as (m, port), Wago672Client("127.0.0.1", port) as plc:
        st = plc.enable()
        assert st.ready and st.stop_n_ack and st.inputs[0]  # Input1 wired high in the example
        st = plc.move_to(25600, velocity=25000, acceleration=4000)  # 10 mm
        assert st.on_target and not st.busy and st.standstill and st.position == 25600 and st.mode == MODES["positioning"]
        assert m.units["x"].drive.position == pytest.approx(10.0)
        assert plc.move_to(-2560, velocity=25000, acceleration=4000).position == -2560
        # the same position straight from the registers: D4..D6 = bytes 6..8
        assert InputImage.from_bytes(plc.read_inputs()).positioning().position == -2560
        assert plc.read_outputs() == plc.outputs  # read back at 0x0200
        assert plc.read_watchdog() == (100, WD_RUNNING)


def test_raw_pymodbus_register_writes_drive_the_module():
    with serving() as (m, port):
        c = ModbusTcpClient("127.0.0.1", port=port, timeout=3)
        assert c.connect()
        try:
            def cycle(image: OutputImage) -> InputImage:
                assert not c.write_registers(0, pack(image.to_bytes())).isError()  # FC16
                fc4 = c.read_input_registers(0, count=6)
                assert not fc4.isError()
                return InputImage.from_bytes(unpack(fc4.registers))

            def poll(image: OutputImage, predicate, timeout: float = 5.0) -> InputImage:
                t0 = time.monotonic()
                while True:
                    st = cycle(image)
                    if predicate(st):
                        return st
                    assert time.monotonic() - t0 < timeout, st
                    time.sleep(0.005)

            poll(OutputImage(c1=ON), lambda s: s.s1 & S1.Ready and s.s1 & S1.Stop_N_ACK)
            # FC6 on register 5 (C2 low byte, C1 high byte) selects single positioning
            assert not c.write_register(5, (ON | C1.M_Positioning) << 8).isError()
            image = OutputImage(c1=ON | C1.M_Positioning, data=PositioningSetpoints(25000, 4000, 12800).encode())
            poll(image, lambda s: s.s1 & S1.M_Positioning_ACK)
            start = OutputImage(c1=ON | C1.M_Positioning | C1.Start, data=image.data)
            poll(start, lambda s: s.s1 & S1.Start_ACK)
            st = poll(image, lambda s: s.s2 & S2.On_Target and not s.s2 & S2.Busy)
            assert st.positioning().position == 12800
            regs = c.read_input_registers(0, count=6).registers
            assert regs[3] == 12800 & 0xFFFF and regs[4] & 0xFF == 12800 >> 16  # position bytes on the wire
            assert regs == c.read_holding_registers(0, count=6).registers  # FC3 reads the same image at rest
            assert c.read_holding_registers(0x0200, count=6).registers == pack(image.to_bytes())
            bad = c.read_holding_registers(6, count=1)
            assert bad.isError() and bad.exception_code == 2
            bad = c.write_registers(0x0200, [0])
            assert bad.isError() and bad.exception_code == 2
        finally:
            c.close()
        assert m.units["x"].drive.position == pytest.approx(5.0)


def test_a_client_that_disconnects_mid_move_leaves_the_motor_stopped():
    with serving() as (m, port):
        plc = Wago672Client("127.0.0.1", port)
        plc.enable()
        plc.move_to(512000, velocity=25000, acceleration=4000, wait=False)  # 200 mm: far away
        drive = m.units["x"].drive
        until(lambda: drive.velocity > 15.0, 3.0, "moving")
        plc.close()  # the PLC goes away: no more writes
        t = until(lambda: drive.velocity == 0.0, 2.0, "stopped after the watchdog time")
        assert 0.08 < t < 1.0  # watchdog 100 ms, then the STOP ramp (about 70 ms)
        p = drive.position
        time.sleep(0.3)
        assert drive.position == p < 100.0 and drive.velocity == 0.0  # stays stopped
        with Wago672Client("127.0.0.1", port, cycle=None, connect=False).connect(take_over=False) as other:
            assert other.read_watchdog() == (100, WD_EXPIRED)
            st = InputImage.from_bytes(other.read_inputs())
            assert st.s1 == 0 and st.s2 & S2.StandStill  # not Ready: the coupler cleared Enable
            assert other.read_outputs() == bytes(12)
        assert m.device.coupler.expiries == 1


def test_raw_client_that_drops_the_connection_mid_move():
    with serving() as (m, port):
        c = ModbusTcpClient("127.0.0.1", port=port, timeout=3)
        assert c.connect()
        c.write_registers(0, pack(OutputImage(c1=ON).to_bytes()))
        time.sleep(0.02)
        c.write_registers(0, pack(OutputImage(c1=ON | C1.M_Positioning).to_bytes()))
        time.sleep(0.02)
        c.write_registers(0, pack(OutputImage(c1=ON | C1.M_Positioning | C1.Start, data=PositioningSetpoints(25000, 4000, 512000).encode()).to_bytes()))
        drive = m.units["x"].drive
        try:
            until(lambda: drive.velocity > 0.0, 2.0, "moving")
        finally:
            c.close()
        until(lambda: drive.velocity == 0.0, 2.0, "stopped")
        assert drive.position < 50.0 and m.device.coupler.watchdog_expired


def test_writes_are_refused_without_the_operators_enable():
    with serving(writes=False) as (m, port):
        with pytest.raises(Wago672ClientError, match="exception 1"):
            Wago672Client("127.0.0.1", port)
        c = ModbusTcpClient("127.0.0.1", port=port, timeout=3)
        assert c.connect()
        try:
            w = c.write_registers(0, [0, 0, 0, 0, 0, ON << 8])
            assert w.isError() and w.exception_code == 1
            assert not c.read_input_registers(0, count=6).isError()  # reads still work
        finally:
            c.close()
        assert m.device.coupler.writes == 0


def test_reference_jog_speed_and_stop():
    with serving(example(position_microsteps=int(-14 * K))) as (m, port), Wago672Client("127.0.0.1", port) as plc:
        plc.enable()
        st = plc.reference(-1, timeout=10.0)  # reference cam at -20 .. -15 mm
        assert st.reference_ok and not st.busy and st.mode == MODES["reference"]
        assert abs(st.position) < 2560  # Reference_Offset 0 at the cam's edge, plus the braking distance
        st = plc.jog(+1)
        assert st.mode == MODES["jog"]
        st = plc.wait(lambda s: s.on_speed, 3.0, "jog at SetupSpeed")
        assert st.velocity == 20000 and st.busy
        plc.jog(0)
        st = plc.wait(lambda s: s.standstill, 3.0, "jog released")
        assert st.velocity == 0
        st = plc.speed(-5000, 4000)
        assert st.velocity == -5000 and st.mode == MODES["speed"]
        st = plc.stop()
        assert st.standstill and st.stop_n_ack and st.mode == 0
        assert m.units["x"].drive.velocity == 0.0


def test_a_module_error_is_reported_and_acknowledged():
    with serving() as (m, port), Wago672Client("127.0.0.1", port) as plc:
        plc.enable()
        with pytest.raises(Wago672DeviceError) as e:
            plc.move_to(1000, velocity=0)  # 1117: velocity outside 1 .. 25000
        assert e.value.status.error and not e.value.status.ready
        assert m.device.device(0).errors.error == 1117
        st = plc.quit_error()
        assert not st.error
        plc.enable()
        assert plc.move_to(1000, velocity=10000, acceleration=4000).position == 1000


def test_mailbox_toggle_handshake():
    with serving() as (m, port), Wago672Client("127.0.0.1", port) as plc:
        plc.enable()
        replies = [plc.mailbox(Mbx.IDLE) for _ in range(3)]
        assert all(r.opcode == Mbx.IDLE and r.ok for r in replies)
        r = plc.mailbox(Mbx.DIAG_RD_ERROR)
        assert r.opcode == Mbx.DIAG_RD_ERROR  # answered (return code: the module's)
        assert plc.status().mailbox and plc.status().position is None
        st = plc.mailbox_off()
        assert not st.mailbox and st.position == 0
        assert plc.move_to(2560, velocity=25000, acceleration=4000).position == 2560  # cyclic image again


def test_mailbox_diagnostics_and_configuration():
    with serving() as (m, port), Wago672Client("127.0.0.1", port) as plc:
        plc.enable()
        assert plc.read_variable(9) == 8  # hardware version: 8 = 750-672
        assert plc.read_error() == (0, 0)
        plc.config_write("SetupSpeed", 12345)
        assert plc.config_read("SetupSpeed") == 12345
        assert m.device.device(0).config["SetupSpeed"] == 12345


def test_mailbox_move_command():
    with serving() as (m, port), Wago672Client("127.0.0.1", port) as plc:
        plc.enable()
        plc.select_mode("mailbox")
        assert plc.drive_command(0x25, 25000).ok  # SET_VELOCITY
        r = plc.drive_command(0x02, 5120)  # MOVE 5120
        assert r.ok
        plc.wait(lambda s: s.on_target and not s.busy, 5.0, "mailbox MOVE")
        assert m.units["x"].drive.position == pytest.approx(2.0)


def test_table_download_of_the_manuals_run_program():
    lines = [(0x25, 20000), (0x22, 3000), (0x71, 0x0130), (0x02, 0x00FE20), (0x71, 0x0030), (0x02, 0), (0xF5, 2), (0x70, 2000)]
    rows = program_rows(lines)
    assert rows[3] == bytes([0x02, 0x20, 0xFE, 0x00]) and checksum(rows) == 0x61B  # wago.md §9.10
    with serving() as (m, port), Wago672Client("127.0.0.1", port) as plc:
        plc.enable()
        assert plc.download_table(1, 1, rows, activate=True) == 0x61B
        assert plc.mailbox(Mbx.TABLE_GET_ACTIVE, bytes([1]), check=True).data[0] == 1  # RAM1 active
        st = plc.run_program(0)
        assert st.mode == MODES["program"]
        # line 2 waits for Input1 = 1 (wired high), line 3 moves to 65056
        st = plc.wait(lambda s: s.velocity > 0, 3.0, "the program moves")
        assert st.busy


def test_configuration_saved_in_the_eeprom_survives_a_restart(tmp_path):
    data = example()
    data["device"]["modules"][0]["eeprom"] = str(tmp_path / "x.eeprom.json")
    with serving(data) as (m, port), Wago672Client("127.0.0.1", port) as plc:
        plc.config_write("SetupSpeed", 12000)
        plc.mailbox(Mbx.CONFIG_SAVE, (1).to_bytes(4, "little"), check=True)  # user data set
        plc.wait(lambda s: plc.mailbox(Mbx.DIAG_QUERY_STORAGE, check=True).data[0] == 0, 3.0, "EEPROM stored")
        assert m.persist() == [tmp_path / "x.eeprom.json"]
    again = Machine(parse_machine(data, "t.toml"), source="t.toml")
    assert again.device.device(0).config["SetupSpeed"] == 12000  # the saved user data set wins
    assert Machine(parse_machine(example(), "t.toml")).device.device(0).config["SetupSpeed"] == 20000


def test_several_modules_each_with_its_client():
    data = example()
    y = dict(data["axis"][0], name="y", switches=[])
    data["axis"].append(y)
    data["device"]["modules"].append({"axis": "y", "inputs": {"Input1": True}})
    with serving(data) as (m, port), Wago672Client("127.0.0.1", port, module=0) as px, Wago672Client("127.0.0.1", port, module=1) as py:
        px.enable()
        py.enable()
        py.move_to(-5120, velocity=25000, acceleration=4000, wait=False)
        px.move_to(7680, velocity=25000, acceleration=4000)
        assert py.wait_on_target(5.0).position == -5120
        assert m.units["x"].drive.position == pytest.approx(3.0) and m.units["y"].drive.position == pytest.approx(-2.0)
        assert px.base == 0 and py.base == 6
