"""Configuration table: addresses, defaults, ranges with the device's codes, byte access, save/load (manual §4.6, wago.md §4)."""

from __future__ import annotations

import pytest

from axisline.devices.wago672.config_table import (
    ENTRIES,
    TABLE_SIZE,
    ConfigTable,
    ConfigValueError,
    current_password,
)


def test_entries_tile_the_512_bytes_in_address_order():
    end = 0
    for e in ENTRIES:
        assert e.address == end, e.name
        end += e.size
    assert end == TABLE_SIZE == 512


def test_factory_defaults_of_section_4_6():
    t = ConfigTable()
    expected = {
        "ConfVersion": 4, "Application_Selector": 1, "Freq_Div": 40, "Acc_Fact": 1000, "Current": 50,
        "Current_Ratio_StandStill": 33, "Current_Ratio_RampUp": 100, "Current_Ratio_Drive": 50,
        "Current_Ratio_RampDown": 100, "Speed": 3000, "Speed_Limit": 25000, "SetupSpeed": 3000,
        "Acceleration_Stop_Fast": 30000, "Acceleration_RampUp": 1000, "Acceleration_RampUp_Param": 300,
        "Current_Ratio_Stop": 150, "SetupAcceleration": 1000, "Drive_Range_Neg": -8388607,
        "Drive_Range_Pos": 8388607, "Camshaft_Ch9_Period": 100, "ErrorNotificationMode": 0x06,
        "WarningNotificationMode": 0x18, "IdentNumber": 750672, "Current_Pass2": 0xC0F0,
        "Warn_Treshold_Temperature": 700, "Motor_Steps_per_Rev": 200, "TargetWindowSpeed": 2,
    }
    for name, value in expected.items():
        assert t[name] == value, name
    # default links (wago.md §9.9): Ptr_Stop1_N (194) = Input1 (0x30), Ptr_Stop2_N (177) = C1.1 (0x41)
    assert t.get(194) == 0x30 and t.get(177) == 0x41 and t.get(168) == 0x00 and t.get(187) == 0x53
    assert t.get("Break_Manual") == 0x02 and t.get("Ptr_OUT1") == 0x08 and t.get("Ptr_OUT2") == 0x0F
    # Drive_Range_Neg default 0x800001 as 24 bit (§3.11.3.2) in a little-endian INT32
    assert t.read_bytes(68, 4) == (-8388607).to_bytes(4, "little", signed=True)


@pytest.mark.parametrize(
    "name, value, code",
    [
        ("Current", 51, 1213),
        ("Current_Ratio_Drive", 151, 1217),
        ("Freq_Div", 3, 1216),
        ("Pos_Div", 0, 1517),
        ("Speed_Mult", 0, 1517),
        ("Application_Selector", 2, 1214),
        ("Motor_Steps_per_Rev", 202, 1819),
        ("Filter3_Function", 12, 1246),
        ("Camshaft_Ch9_Period", 0, 1331),
        ("Current_Ctrl_Type", 2, 1859),
        ("Speed_Limit", 25001, 1211),
        ("Acceleration_Modes", 0x03, 1557),
        ("Acceleration_Modes", 0xC0, 1557),
        ("User_Conf_Id", 50001, None),
    ],
)
def test_out_of_range_values_are_rejected_with_the_device_code(name, value, code):
    t = ConfigTable()
    before = t.to_bytes()
    with pytest.raises(ConfigValueError) as exc:
        t.set(name, value)
    assert exc.value.code == code
    assert exc.value.field == name and exc.value.value == value
    assert name in str(exc.value)
    assert t.to_bytes() == before


def test_special_values_allowed_besides_the_printed_ranges():
    t = ConfigTable()
    t.set("Freq_Div", 0)  # C2 '00' with Freq_Div 0 -> prescaler 200
    t.set("Acc_Fact", 0)  # -> Acc_Multiplier 8
    t.set("SetupSpeed", 0)  # "a 1 value is automatically accepted"
    t.set("Motor_Steps_per_Rev", 400)
    assert (t["Freq_Div"], t["Acc_Fact"], t["SetupSpeed"]) == (0, 0, 0)


def test_access_by_address_and_by_bytes():
    t = ConfigTable()
    t.set(4, 80)
    assert t["Freq_Div"] == 80 and t.read_bytes(4, 2) == bytes([0x50, 0x00])
    # wago.md §9.12: CONFIG_WR Freq_Div := 80 with two bytes at address 4
    t.write_bytes(4, bytes([0x28, 0x00]))
    assert t.get(4) == 40
    # a write covering part of an entry is checked with the entry's new value
    t.write_bytes(14, bytes([33]))
    assert t["Current"] == 33
    with pytest.raises(ConfigValueError) as exc:
        t.write_bytes(14, bytes([60, 10]))  # Current 60 invalid, Current_Ratio_StandStill 10 fine
    assert exc.value.code == 1213
    assert t["Current"] == 33 and t["Current_Ratio_StandStill"] == 33  # nothing half-written
    with pytest.raises(ConfigValueError) as exc:
        t.read_bytes(4, 5)
    assert exc.value.code == 1161
    with pytest.raises(KeyError, match="inside Freq_Div"):
        t.get(5)


def test_undocumented_addresses_8_to_13_read_zero_and_drop_writes():
    t = ConfigTable()
    t.write_bytes(8, bytes([1, 2, 3, 4]))
    assert t.read_bytes(8, 4) == bytes(4) and t.get(10) == 0


def test_update_checks_all_values_before_storing_any():
    t = ConfigTable()
    with pytest.raises(ConfigValueError, match="Current_Ratio_Stop"):
        t.update({"Speed": 5000, "Current_Ratio_Stop": 200})
    assert t["Speed"] == 3000


def test_current_controller_password_worked_example():
    # wago.md §9.8: 50 XOR 2 XOR 30 XOR 0 XOR 0xC0DE = 0xC0F0, the documented default
    assert current_password(50, 2, 30, 0) == 0xC0F0
    t = ConfigTable()
    t.validate()
    t.set("Current_Ctrl_Hysteresis", 100)
    with pytest.raises(ConfigValueError) as exc:
        t.validate()
    assert exc.value.code == 1162
    t.set("Current_Pass2", current_password(100, 2, 30, 0))
    t.validate()


def test_save_load_round_trip_and_defaults_restore(tmp_path):
    t = ConfigTable()
    t.update({"Freq_Div": 80, "Reference_Offset": -1234, "Drive_Range_Pos": 50000, "Acceleration_Modes": 0x21})
    path = tmp_path / "wago672.cfg"
    t.save(path)
    assert path.stat().st_size == 512
    u = ConfigTable()
    u.load(path)
    assert u.to_bytes() == t.to_bytes()
    assert u["Reference_Offset"] == -1234 and u["Acceleration_Modes"] == 0x21
    u.restore_defaults()
    assert u.to_bytes() == ConfigTable().to_bytes()


def test_load_rejects_a_broken_data_set_and_keeps_the_table(tmp_path):
    t = ConfigTable()
    t.set("Speed", 1234)
    raw = bytearray(t.to_bytes())
    raw[14] = 99  # Current 9.9 A
    path = tmp_path / "bad.cfg"
    path.write_bytes(bytes(raw))
    with pytest.raises(ConfigValueError) as exc:
        t.load(path)
    assert exc.value.code == 1213 and t["Speed"] == 1234 and t["Current"] == 50
    raw = bytearray(t.to_bytes())
    raw[2] = 5  # unknown ConfVersion
    with pytest.raises(ConfigValueError, match="ConfVersion"):
        t.load_bytes(bytes(raw))
    raw = bytearray(t.to_bytes())
    raw[384] = 99  # hysteresis changed without the password
    with pytest.raises(ConfigValueError) as exc:
        t.load_bytes(bytes(raw))
    assert exc.value.code == 1162
    with pytest.raises(ConfigValueError, match="512 bytes"):
        t.load_bytes(bytes(100))


def test_alternative_factory_defaults():
    # wago.md §4.2 [CONFLICT]: other sources give Freq_Div 200 and Acc_Fact 8
    t = ConfigTable(defaults={"Freq_Div": 200, "Acc_Fact": 8})
    t.set("Freq_Div", 40)
    t.restore_defaults()
    assert t["Freq_Div"] == 200 and t["Acc_Fact"] == 8
