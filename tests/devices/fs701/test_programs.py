"""Process values #11, #25..#28, #31 and the serial Adjust / Test Program command bits.

Spec §3.11 / §8 item 10 (decisions in status.py), §3.1 bits 30/31 "Ser./Bus ... Control Enable
must be OFF" (decision D4 in personality.py). Driven through the personality's endpoints on the
example machine file, as a PLC or the PC operator software would.
"""

from __future__ import annotations

import copy

import pytest

from axisline.devices.fs701.cutter import ControlState
from axisline.devices.fs701.drivecom import DrivecomClient
from axisline.devices.fs701.modbus_map import encode_words
from axisline.devices.fs701.registers import ReadOnlyRegisterError
from axisline.devices.fs701.status import StatusError
from axisline.fieldbus.modbus import RegisterRefused

from .test_personality import build, example_data, quick, run_s

ADJUST, TEST = 0x091E, 0x091F
TEST_COUNTER = 0x081F
UNNAMED = (0x080B, 0x0819, 0x081A, 0x081B, 0x081C)  # #11, #25..#28


def serial_machine(drive_errors: bool = False):
    """No hardware Control Enable / Start: the serial link switches them (Control Enable OFF)."""
    d = quick(example_data())
    if drive_errors:  # keep the example's analogue input errors, for the Adjust program to find
        d["axis"][0]["drive"].update(copy.deepcopy(example_data()["axis"][0]["drive"]))
    d["device"]["batch"] = 0
    d["device"]["inputs"] = {"cut_completed": "shear"}
    m = build(d)
    m.device.network_writes = True
    return m


def modbus_bit(ep, code: int, on: int) -> None:
    ep.write_registers(2 * code, encode_words(on, 2))


def modbus_read(ep, code: int) -> int:
    hi, lo = ep.read_registers("holding", 2 * code, 2)
    v = hi << 16 | lo
    return v - (1 << 32) if v >= 1 << 31 else v


# ---------------------------------------------------------------------------------- item 1


def test_unnamed_process_values_read_zero_and_are_read_only():
    m = build(quick(example_data()))
    dev = m.device
    run_s(m, 4.0)  # automatic cutting: every named value is busy
    assert len(dev.cuts) >= 1
    client = DrivecomClient(dev.byte_endpoint().feed)
    ep = dev.register_endpoint()
    assert client.read(0x0802) != 0  # (a live value, for contrast)
    for code in UNNAMED:
        assert client.read(code) == 0, hex(code)
        assert modbus_read(ep, code) == 0, hex(code)
        with pytest.raises(ReadOnlyRegisterError):
            dev.registers.write(code, 1)
        with pytest.raises(StatusError):  # the device cannot give them a value either
            dev.registers.status.set_process_value(code, 1)
    dev.network_writes = True
    with pytest.raises(RegisterRefused):
        modbus_bit(ep, 0x080B, 5)
    # #31 Test Counter is 0 until the Test program has run
    assert client.read(TEST_COUNTER) == 0


def test_test_counter_counts_the_test_program_cycles():
    m = serial_machine()
    dev = m.device
    ep = dev.register_endpoint()
    run_s(m, 0.02)
    modbus_bit(ep, TEST, 1)
    m.scheduler.run_cycle()
    assert dev.programs[-1]["program"] == "test" and dev.programs[-1]["ok"], dev.programs
    assert modbus_read(ep, TEST_COUNTER) == 2  # TEST_PROGRAM_CYCLES up/down ramps
    # holding the bit does not repeat the program; the count stays after leaving it
    run_s(m, 0.05)
    assert len(dev.programs) == 1
    modbus_bit(ep, TEST, 0)
    run_s(m, 0.01)
    assert modbus_read(ep, TEST_COUNTER) == 2
    # entering again resets and counts again
    modbus_bit(ep, TEST, 1)
    m.scheduler.run_cycle()
    assert len(dev.programs) == 2 and modbus_read(ep, TEST_COUNTER) == 2


# ---------------------------------------------------------------------------------- item 3


def test_serial_test_program_runs_the_cycle_test():
    m = serial_machine()
    dev = m.device
    client = DrivecomClient(dev.byte_endpoint().feed)
    run_s(m, 0.02)
    x0 = m.units["carriage"].drive.position
    client.write(TEST, 1)  # the Drivecom single command 0x091F
    m.scheduler.run_cycle()
    prog = dev.programs[-1]
    assert prog["program"] == "test" and prog["ok"] and prog["steps"][0]["step"] == "cycle"
    assert "differential counter" in prog["steps"][0]["message"]
    assert m.units["carriage"].drive.position == pytest.approx(x0, abs=1e-9)  # back where it stood
    assert client.read(TEST_COUNTER) == 2


def test_serial_adjust_program_tunes_offset_and_gain_at_runtime():
    m = serial_machine(drive_errors=True)
    dev = m.device
    ep = dev.register_endpoint()
    run_s(m, 0.02)
    assert dev.params.ana_out_gain_2 == pytest.approx(10.0) and dev.params.ana_out_offset_2 == 0
    modbus_bit(ep, ADJUST, 1)
    m.scheduler.run_cycle()
    prog = dev.programs[-1]
    assert prog["program"] == "adjust" and prog["ok"], prog
    assert [s["step"] for s in prog["steps"]] == ["direction", "offset", "gain"]
    # the example drive: +21 mV offset, gain x1.046 -> Offset 2 negative, Gain 2 below 10 V
    assert dev.params.ana_out_offset_2 < 0 and dev.params.ana_out_gain_2 < 10.0
    assert dev.settings.ana_out_gain_2 == pytest.approx(dev.params.ana_out_gain_2)
    modbus_bit(ep, ADJUST, 0)
    # then the machine cuts with the tuned values (Control Enable and Start over the bus)
    modbus_bit(ep, 0x0900, 1)
    modbus_bit(ep, 0x0901, 1)
    run_s(m, 4.0)
    assert dev.cutter.control_state is ControlState.AUTOMATIC and len(dev.cuts) >= 1
    assert all(c.in_tolerance is not False for c in dev.cuts)


def test_adjust_and_test_are_refused_while_control_enable_is_on():
    m = serial_machine()
    dev = m.device
    ep = dev.register_endpoint()
    modbus_bit(ep, 0x0900, 1)  # Control Enable ON (serial)
    run_s(m, 0.02)
    for code in (ADJUST, TEST):
        with pytest.raises(RegisterRefused):
            modbus_bit(ep, code, 1)
    run_s(m, 0.02)
    assert dev.programs == [] and dev.registers.status.serial_commands == 0b1
    # a CAN word cannot be refused by the registers: the device logs the refusal
    dev.registers.set_can_commands(1 << 31)
    m.scheduler.run_cycle()
    assert dev.programs[-1]["program"] == "refused" and modbus_read(ep, TEST_COUNTER) == 0
    # Adjust and Test together: the second is refused
    dev.registers.set_can_commands(0)
    modbus_bit(ep, 0x0900, 0)
    run_s(m, 0.01)
    modbus_bit(ep, ADJUST, 1)
    with pytest.raises(RegisterRefused):
        modbus_bit(ep, TEST, 1)


# ---------------------------------------------------------------------------------- item 2


SET_LENGTH_PS, SET_LENGTH_LU = 0x0111, 0x0112


@pytest.mark.parametrize(
    "ps, lu, expected_incr",
    [
        (8000, 300, 8000),  # both set: Ps wins (cutter.py C10, spec §2.14 / §8 item 13)
        (0, 300, None),  # LU only: 300 LU x line increments per LU
        (8000, 0, 8000),  # Ps only
    ],
)
def test_set_length_counter_ps_wins_over_lu_through_the_registers(ps, lu, expected_incr):
    m = serial_machine()
    dev = m.device
    client = DrivecomClient(dev.byte_endpoint().feed)
    client.write(0x0900, 1)  # Control Enable, Stop
    run_s(m, 0.02)
    client.write(SET_LENGTH_PS, ps)
    client.write(SET_LENGTH_LU, lu)
    m.scheduler.run_cycle()
    c = dev.cutter
    kl = dev.settings.line_counts_per_lu
    if expected_incr is None:
        expected_incr = lu * kl
    line_step = 1000.0 / 60.0 * kl * m.period  # increments per cycle at 60 m/min (1 m/s)
    client.write(0x0901, 1)  # Start: the counter is set to the preset
    m.scheduler.run_cycle()
    assert c.length_counter == pytest.approx(expected_incr, abs=2 * line_step + 2)
    assert client.read(0x0800) == pytest.approx(expected_incr, abs=3 * line_step + 2)  # #0 Length Counter
    # used once: both registers read 0 afterwards, a second Start keeps the counted length
    assert client.read(SET_LENGTH_PS) == 0 and client.read(SET_LENGTH_LU) == 0
    assert dev.settings.set_length_cou_ps == 0 and dev.settings.set_length_cou_lu == 0
