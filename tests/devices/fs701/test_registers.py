"""FS701 register map: codes, formatting, write rules, EEPROM store, Modbus map (manual §11, spec fs701.md §3.13, §2.20)."""

from __future__ import annotations

import pytest
from hypothesis import given
from hypothesis import strategies as st

from axisline.devices.fs701.io_assign import IOAssignment
from axisline.devices.fs701.parameters import BLOCKS, PARAMETERS, ParameterSet
from axisline.devices.fs701.modbus_map import (
    MODBUS_MAP,
    MODBUS_WIDE_BASE,
    ModbusError,
    ModbusImage,
    decode_words,
    encode_words,
    modbus_entry,
    modbus_read,
    modbus_table_markdown,
    modbus_write,
)
from axisline.devices.fs701.registers import (
    REGISTERS,
    REGISTERS_BY_CODE,
    CommandRefusedError,
    ReadOnlyRegisterError,
    RegisterFormatError,
    RegisterKind,
    RegisterMap,
    RegisterRangeError,
    UnknownRegisterError,
    format_display,
    parse_display,
    parse_wire,
    register,
    register_table_markdown,
)
from axisline.devices.fs701.status import StatusImage


def everything(m: RegisterMap) -> dict[int, int]:
    return {r.code: m.read(r.code) for r in REGISTERS} | {"eeprom": m.store_count}  # type: ignore[dict-item]


# ---- the map --------------------------------------------------------------------------------


def test_address_map_of_fs701_md_3_13():
    codes = set(REGISTERS_BY_CODE)
    for block in BLOCKS.values():  # every parameter block: 32 codes
        assert set(block.codes) <= codes
    assert set(range(0x0800, 0x0820)) <= codes  # process data
    assert set(range(0x0900, 0x0920)) - codes == {0x090E}  # single commands; 14 = Print Mark has none
    assert set(range(0x0A00, 0x0A20)) <= codes  # single outputs
    assert set(range(0x0B00, 0x0B06)) <= codes and 0x0B06 not in codes
    assert not codes & set(range(0x01A0, 0x02C0))  # not described
    assert len(REGISTERS) == 8 * 32 + 32 + 31 + 32 + 6
    assert [r.code for r in REGISTERS] == sorted(codes)
    kinds = {r.kind for r in REGISTERS}
    assert kinds == {RegisterKind.PARAMETER, RegisterKind.RESERVED, RegisterKind.PROCESS, RegisterKind.COMMAND,
                     RegisterKind.OUTPUT, RegisterKind.STATUS}  # fmt: skip
    assert [r.code for r in REGISTERS if r.writable and r.kind == RegisterKind.STATUS] == [0x0B01]
    assert register(0x02C8).name == "(Block 15 8)" and register(0x0003).name == "(Parameter 03)"
    assert "| 0x0105 | +/- Sync Rate | parameter | RW |" in register_table_markdown()


def test_read_and_write_by_code():
    m = RegisterMap()
    m.write(0x0000, 2500)
    assert m.params.cutting_length == 2500 and m.read(0x0000) == 2500
    m.write_value(0x0105, -1.25)
    assert m.read(0x0105) == -125 and m.read_value(0x0105) == -1.25
    m.write_text(0x0106, "2.50")
    assert m.params.return_speed == 2.5
    m.write_text(0x0106, "+075")
    assert m.read_text(0x0106) == "75"
    m.status.set_process_value("position_error", -17)
    assert m.read(0x0803) == -17 and m.read_text(0x0803) == "-17"
    m.params.batch_counter = 9_999_999_999
    assert m.read(0x080E) == 9_999_999_999  # "Read Batch Count" is the counter
    m.status.set_output("home", True)
    assert m.read(0x0A02) == 1 and m.read(0x0B04) == 0b100


def test_wire_text_as_the_unit_sends_it():
    m = RegisterMap()
    m.params.sync_rate = -1.25
    m.params.minimum_position = -100
    assert m.read_text(0x0105) == "-125"  # implied decimals, "-", no "+"
    assert m.read_text(0x0000) == "1000"  # no leading zeros
    assert m.read_text(0x0121) == "0"
    assert m.read_text(0x0141) == "-100"
    assert parse_wire(0x0105, "-1.25") == parse_wire(0x0105, "-125") == parse_wire(0x0105, "-0125") == -125
    with pytest.raises(RegisterFormatError, match="the register has 2"):
        parse_wire(0x0105, "1.5")  # ambiguous: refused
    with pytest.raises(RegisterFormatError, match="the register has 0"):
        parse_wire(0x0000, "10.0")
    for bad in ("", " 1", "1 ", "1e3", "0x10", "--1", "+", "1.", "12345678901234567"):
        with pytest.raises(RegisterFormatError):
            parse_wire(0x0000, bad)


def test_display_form_of_the_register_cards():
    """Screenshots of §4.2..§4.4 (values as shown by OS5.1)."""
    s = ParameterSet({"cutting_length": 10_000, "minimum_position": -100, "maximum_position": 10_000,
                      "alarm_position": 9000, "home_window": 3, "ana_out_gain_2": 10.17})  # fmt: skip
    m = RegisterMap(s)
    shown = {code: m.display_text(code) for code in (0x0000, 0x0002, 0x0100, 0x0102, 0x0104, 0x0105, 0x0106, 0x0108,
                                                     0x0109, 0x010B, 0x010F, 0x0110, 0x0117, 0x0119, 0x011C,
                                                     0x0121, 0x0140, 0x0141, 0x0142, 0x0143, 0x02E8, 0x02EB,
                                                     0x02F8, 0x02F9, 0x0800)}  # fmt: skip
    assert shown == {
        0x0000: "010000", 0x0002: "0010000", 0x0100: "001000", 0x0102: "01000", 0x0104: "00", 0x0105: "+0.00",
        0x0106: "1.00", 0x0108: "0001", 0x0109: "50", 0x010B: "000", 0x010F: "0010", 0x0110: "001",
        0x0117: "+00000", 0x0119: "01", 0x011C: "0000000", 0x0121: "0.000", 0x0140: "003", 0x0141: "-000100",
        0x0142: "+010000", 0x0143: "+009000", 0x02E8: "+0000", 0x02EB: "010.17", 0x02F8: "02000",
        0x02F9: "+050000", 0x0800: "+0000000",
    }  # fmt: skip
    # §4.3.4 screenshot counters (fs701.md §7 E25): the padded form parses back
    assert parse_display(0x0170, "000000243") == 243 and parse_display(0x0171, "00000009") == 9
    assert format_display(0x0170, 243) == "0000000243"


def test_refused_writes_change_nothing():
    m = RegisterMap()
    before = everything(m)
    cases = [
        (0x0800, 5, ReadOnlyRegisterError),  # process value
        (0x080E, 5, ReadOnlyRegisterError),  # read-only copy of the batch counter
        (0x0A00, 1, ReadOnlyRegisterError),  # single output
        (0x0B00, 1, ReadOnlyRegisterError),
        (0x0B02, 1, ReadOnlyRegisterError),
        (0x0B03, 1, ReadOnlyRegisterError),
        (0x0B04, 1, ReadOnlyRegisterError),
        (0x0B05, 1, ReadOnlyRegisterError),
        (0x01A0, 0, UnknownRegisterError),
        (0x090E, 1, UnknownRegisterError),
        (0x0B06, 0, UnknownRegisterError),
        (0x0000, 0, RegisterRangeError),
        (0x0000, 1_000_000, RegisterRangeError),
        (0x0105, 1000, RegisterRangeError),
        (0x02C5, 20, RegisterRangeError),  # fs701.md §7 E13
        (0x0003, 1, RegisterRangeError),  # reserved: 0..0
        (0x0900, 2, RegisterRangeError),
        (0x0B01, 1 << 14, RegisterRangeError),  # Print Mark has no serial bit
        (0x0B01, 1 << 32, RegisterRangeError),
        (0x0000, "5", RegisterFormatError),
    ]
    for code, raw, err in cases:
        with pytest.raises(err):
            m.write(code, raw)
        assert everything(m) == before, hex(code)
    with pytest.raises(RegisterRangeError, match="Cutting Length.*0x0000.*1..999999"):
        m.write_value(0x0000, 0)
    with pytest.raises(ReadOnlyRegisterError):
        m.write_text(0x0800, "1")
    with pytest.raises(RegisterFormatError):
        m.write_text(0x0000, "abc")
    assert everything(m) == before


@given(st.sampled_from([r for r in REGISTERS if r.kind == RegisterKind.PARAMETER]),
       st.integers(min_value=-(10**11), max_value=10**11))  # fmt: skip
def test_any_parameter_write_is_checked(reg, raw):
    m = RegisterMap()
    p = reg.parameter
    ok = p.minimum <= raw <= p.maximum and not (p.forbid_zero_digit and "0" in str(raw))
    before = m.read(reg.code)
    if ok:
        m.write_text(reg.code, str(raw))
        assert m.read(reg.code) == raw and m.read_text(reg.code) == str(raw)
    else:
        with pytest.raises(RegisterRangeError):
            m.write(reg.code, raw)
        assert m.read(reg.code) == before


def test_reserved_registers_read_zero_and_accept_only_zero():
    m = RegisterMap()
    for code in (0x0003, 0x001F, 0x011E, 0x0125, 0x014A, 0x0165, 0x0172, 0x0184, 0x02C8, 0x080B, 0x0819, 0x0A1F):
        assert m.read(code) == 0
    m.write(0x0003, 0)
    assert m.read(0x0003) == 0


def test_single_commands_and_serial_command_word():
    m = RegisterMap()
    m.write(0x0901, 1)  # Start / Stop
    m.write(0x0912, 1)  # Sync Mode Enable
    assert m.read(0x0B01) == (1 << 1) | (1 << 18) and m.read(0x0901) == 1
    m.status.hardware_commands = 1  # Control Enable from In1
    assert m.read(0x0B03) == 1 | (1 << 1) | (1 << 18)
    assert m.read(0x0900) == 0  # the single command shows the serial bit only
    m.write(0x0B01, 0)
    assert m.read(0x0B01) == 0
    m.write(0x091C, 1)  # (Command 28): stored, no effect
    assert m.read(0x091C) == 1


def test_adjust_and_test_program_need_control_enable_off():
    m = RegisterMap()
    m.write(0x0900, 1)  # Control Enable ON by serial
    with pytest.raises(CommandRefusedError, match="Control Enable OFF"):
        m.write(0x091E, 1)
    m.write(0x0900, 0)
    m.set_hardware_commands(1)  # ... or from a hardware input
    with pytest.raises(CommandRefusedError):
        m.write(0x0B01, 1 << 31)
    m.set_hardware_commands(0)
    m.write(0x091E, 1)  # Adjust
    assert m.read(0x0B03) == 1 << 30
    with pytest.raises(CommandRefusedError, match="together"):
        m.write(0x091F, 1)
    m.write(0x091E, 0)
    m.write(0x091F, 1)
    assert m.read(0x091F) == 1


def test_store_to_eeprom_on_the_rising_edge_fs701_md_2_20():
    m = RegisterMap()
    stored = []
    m.on_store.append(stored.append)
    m.params.cutting_length = 4000
    m.params.batch_counter = 243
    m.write(0x091D, 1)  # rising edge: store
    assert m.store_count == 1 and m.eeprom.params.cutting_length == 4000 and stored == [m.eeprom]
    m.write(0x091D, 1)  # still HIGH: no edge
    m.set_hardware_commands(1 << 29)  # HIGH from hardware too: OR unchanged
    assert m.store_count == 1
    m.write(0x091D, 0)
    m.set_hardware_commands(0)
    m.set_hardware_commands(1 << 29)  # a hardware edge stores as well
    assert m.store_count == 2
    # counters are not saved at power-down (§4.3.4): what was counted after the store is lost
    m.params.batch_counter = 250
    m.params.cutting_length = 100
    m.io.assign_input("start_gap", 16)
    m.power_cycle()
    assert (m.params.batch_counter, m.params.cutting_length) == (243, 4000)
    assert m.io == IOAssignment.default()
    assert m.read(0x0B01) == 0


def test_io_assignment_is_stored_when_set():
    m = RegisterMap()
    io = IOAssignment.default()
    io.assign_input("reset_batch_cou", 16)
    m.params.cutting_length = 3000
    m.set_io_assignment(io)
    assert m.io == io and m.store_count == 0
    m.power_cycle()
    assert m.io == io and m.params.cutting_length == 1000  # the card stores itself, not the parameters


def test_i_time_30_of_section_7_5_is_0_030_s():
    m = RegisterMap()
    m.write_text(0x0121, "30")  # "change I-Time to e.g. 30"
    assert m.params.i_time == 0.03 and m.display_text(0x0121) == "0.030"


def test_clear_error_and_control_enable_clear_errors():
    m = RegisterMap()
    m.status.raise_error(2)
    m.write(0x0907, 1)  # Clear Error, rising edge
    assert m.read(0x0B05) == 0
    m.status.raise_error(3)
    m.write(0x0907, 0)
    m.set_hardware_commands(1)  # Control Enable ON
    assert m.read(0x0B05) == 1 << 3
    m.set_hardware_commands(0)  # ... and OFF: clears
    assert m.read(0x0B05) == 0
    m.status.set_error_cause(5, True)  # ratio: comes back at once
    m.write(0x0907, 1)
    assert m.read(0x0B05) == 1 << 5
    assert m.errors_text() == ["Error 05: Val. Range exceed"]


def test_write_many_is_all_or_nothing():
    m = RegisterMap()
    with pytest.raises(RegisterRangeError):
        m.write_many([(0x0000, 2000), (0x0105, 5000)])
    assert m.read(0x0000) == 1000
    m.write_many([(0x0000, 2000), (0x0105, 500)])
    assert (m.read(0x0000), m.read(0x0105)) == (2000, 500)


def test_shared_objects():
    p, s, io = ParameterSet(), StatusImage(), IOAssignment.default()
    m = RegisterMap(p, s, io)
    m.write(0x0000, 1234)
    assert p.cutting_length == 1234 and m.status is s and m.io is io
    assert m.dump()[0x0000] == 1234 and 0x0105 in m and 0x090E not in m


# ---- Modbus ---------------------------------------------------------------------------------


def test_modbus_map_has_no_overlaps_and_covers_every_register():
    entries = sorted(MODBUS_MAP, key=lambda e: e.address)
    for a, b in zip(entries, entries[1:]):
        assert a.end <= b.address, (a, b)
    assert {e.code for e in MODBUS_MAP} == set(REGISTERS_BY_CODE)
    assert len({e.code for e in MODBUS_MAP}) == len(MODBUS_MAP)
    for p in PARAMETERS:  # every (writable) parameter is mapped and writable
        e = next(e for e in MODBUS_MAP if e.code == p.code)
        assert e.writable and e.decimals == p.decimals
        # the value range fits the width
        assert p.maximum < 1 << (16 * e.words - 1) and p.minimum >= -(1 << (16 * e.words - 1))
    for e in MODBUS_MAP:
        if e.code in (0x0170, 0x0171, 0x080E, 0x080F):
            assert e.words == 4 and e.address >= MODBUS_WIDE_BASE
        else:
            assert (e.address, e.words) == (2 * e.code, 2)
    assert max(e.end for e in MODBUS_MAP) <= 0x10000
    assert "| 522 (0x020A) | 2 | int32, high word first | 0x0105 | +/- Sync Rate | 2 | RW |" in modbus_table_markdown()


def test_words_encoding():
    assert encode_words(-125, 2) == [0xFFFF, 0xFF83] and decode_words([0xFFFF, 0xFF83]) == -125
    assert encode_words(100_000, 2) == [0x0001, 0x86A0]
    assert encode_words(9_999_999_999, 4) == [0x0000, 0x0002, 0x540B, 0xE3FF]
    assert decode_words([0x8000, 0x0000], signed=False) == 1 << 31
    with pytest.raises(ValueError):
        encode_words(1 << 31, 2)


def test_modbus_read_and_write():
    m = RegisterMap()
    m.params.sync_rate = -1.25
    assert modbus_read(m, 2 * 0x0105, 2) == [0xFFFF, 0xFF83]
    assert modbus_read(m, 2 * 0x0105 + 1, 1) == [0xFF83]  # reads may cut an entry
    assert modbus_read(m, 0, 6) == [0, 1000, 0, 1000, 0, 10_000]
    modbus_write(m, 2 * 0x0000, [0, 2500, 0, 3000])  # two entries in one write
    assert (m.params.cutting_length, m.params.test_cut_length) == (2500, 3000)
    modbus_write(m, MODBUS_WIDE_BASE, encode_words(9_999_999_999, 4))
    assert m.params.batch_counter == 9_999_999_999
    assert modbus_read(m, MODBUS_WIDE_BASE + 8, 4) == encode_words(9_999_999_999, 4)  # Read Batch Count
    modbus_write(m, 2 * 0x0B01, encode_words(1 << 31, 2, signed=False))  # Test Program, bit 31
    assert m.read(0x0B01) == 1 << 31
    assert modbus_read(m, 2 * 0x0B01, 2) == [0x8000, 0]


def test_modbus_refusals_change_nothing():
    m = RegisterMap()
    before = everything(m)
    cases = [
        (2 * 0x0000 + 1, [0], 3),  # half an entry
        (2 * 0x0000, [0], 3),  # too short
        (2 * 0x0020, [0, 0], 2),  # unmapped gap
        (2 * 0x0170, [0, 1], 2),  # counters live in the wide area
        (2 * 0x0800, [0, 1], 2),  # read only
        (2 * 0x0105, [0, 1000], 3),  # out of range
        (2 * 0x0000, [0, 2000, 0, 0], 3),  # second entry out of range: the first is not written either
        (2 * 0x0000, [70_000, 0], 3),
    ]
    for address, values, exc in cases:
        with pytest.raises(ModbusError) as info:
            modbus_write(m, address, values)
        assert info.value.exception_code == exc, (hex(address), values)
        assert everything(m) == before
    with pytest.raises(ModbusError) as info:
        modbus_read(m, 2 * 0x0020, 1)
    assert info.value.exception_code == 2
    with pytest.raises(ModbusError):
        modbus_read(m, 2 * 0x001F, 3)  # runs into the gap after the general block
    assert modbus_entry(2 * 0x0105 + 1).code == 0x0105


def test_modbus_image_endpoint():
    m = RegisterMap()
    img = ModbusImage(m, writes_allowed=False)
    assert img.read_registers("holding", 0, 2) == [0, 1000]
    assert img.read_registers("input", 0, 2) == [0, 1000]
    with pytest.raises(ModbusError) as info:
        img.write_registers(0, [0, 2000])
    assert info.value.exception_code == 4 and m.params.cutting_length == 1000
    img.writes_allowed = lambda: True
    img.write_registers(0, [0, 2000])
    assert m.params.cutting_length == 2000
    with pytest.raises(ModbusError):
        img.read_registers("coils", 0, 1)
    m.write(0x0900, 1)
    with pytest.raises(ModbusError) as info:
        img.write_registers(2 * 0x091E, [0, 1])  # Adjust with Control Enable ON
    assert info.value.exception_code == 4
