"""What the 1 ms tick takes from tables it does not re-read each time (bits.py, config_table.py,
device.py): the bit links follow every change of the configuration at once, the plain values of
the configuration follow every write, the input image decodes to the actual values, the inputs
follow their wiring (manual §3.10.4, §4.6, §3.7.3; wago.md §5)."""

from __future__ import annotations

import random

import pytest

from axisline.devices.wago672.bits import MAX_NESTING, Bit, BitTable
from axisline.devices.wago672.config_table import ConfigTable
from axisline.devices.wago672.coupler import Coupler, pack
from axisline.devices.wago672.device import Wago672
from axisline.devices.wago672.errors import WagoError
from axisline.devices.wago672.image import C0, C1, S0, S1, InputImage, OutputImage, PositioningSetpoints
from axisline.motion.axis import Axis, AxisConfig

from .rig import ON, Rig

FILT = range(Bit.FILT1, Bit.FILT1 + 8)


def _reference(cfg: ConfigTable, field: bytes, n: int, depth: int = 0) -> int | None:
    """Bit n by the manual's rule (§3.10.4): a target reads the bit its pointer names, a marker
    (MZERO/MONE) its own written value, at most four levels; None: too deep."""
    if n < 128:
        return field[n]
    if n >= 224:
        return 0
    ptr = cfg.get(n)
    if ptr in (Bit.MZERO, Bit.MONE):
        return field[n]
    if ptr >= 128:
        if depth + 1 >= MAX_NESTING or ptr == n:
            return None
        return _reference(cfg, field, ptr, depth + 1)
    return field[ptr]


def test_random_linkings_read_as_the_manual_rule_after_every_change():
    rng = random.Random(672)
    cfg = ConfigTable()
    table = BitTable(cfg)  # one table through all changes: its links must follow each of them
    group = table.group(tuple(range(128, 224)))
    targets = [t for t in range(128, 224) if t not in FILT]
    for _ in range(150):
        relink = {t: rng.choice([p for p in range(256) if p not in FILT]) for t in rng.sample(targets, 12)}
        if rng.random() < 0.5:
            cfg.update(relink)
        else:
            for t, p in relink.items():
                cfg.write_bytes(t, bytes([p]))
        for n in range(4, 128):
            table.put(n, rng.random() < 0.5)
        for t in targets:
            if table.writable(t):
                table.write(t, rng.random() < 0.5)
        field = bytes(table.field)
        expected = {n: _reference(cfg, field, n) for n in range(256) if n not in FILT}
        for n, want in expected.items():
            if want is None:
                with pytest.raises(WagoError) as exc:
                    table.read(n)
                assert exc.value.code == 1245
            else:
                assert table.read(n) == bool(want), f"bit {n:#04x}"
        if None not in expected.values():
            values = table.values(group)
            assert [values[n - 128] for n in range(128, 224) if n not in FILT] == [bool(expected[n]) for n in targets]
        for first in (Bit.KBUS_ST1_0, Bit.KBUS_ST2_0, Bit.KBUS_ST3_0):
            if all(expected[first + i] is not None for i in range(8)):
                assert table.byte(first) == sum(expected[first + i] << i for i in range(8))


@pytest.mark.parametrize("how", ["set", "update", "write_bytes", "load_bytes", "restore_defaults"])
def test_every_kind_of_configuration_write_moves_a_link_at_once(how):
    # Ptr_Stop1_N (194): Input1 by default; ONE frees the stop circuit (wago.md §9.9)
    r = Rig()
    r.inputs["Input1"] = False
    r.c1 = ON
    r.step()
    assert not r.has(S1.Stop_N_ACK) and not r.dev.bits.read(Bit.Stop1_N)
    cfg = r.dev.config
    if how == "set":
        cfg.set("Ptr_Stop1_N", Bit.ONE)
    elif how == "update":
        cfg.update({"Ptr_Stop1_N": Bit.ONE})
    elif how == "write_bytes":
        cfg.write_bytes(194, bytes([Bit.ONE]))
    elif how == "load_bytes":
        data = bytearray(cfg.to_bytes())
        data[194] = Bit.ONE
        cfg.load_bytes(bytes(data))
    else:
        cfg.set("Ptr_Stop1_N", Bit.ZERO)
        r.inputs["Input1"] = True
        r.step()
        assert not r.dev.bits.read(Bit.Stop1_N) and not r.has(S1.Stop_N_ACK)
        cfg.restore_defaults()  # the factory link again: Input1, which is 1 now
    assert r.dev.bits.read(Bit.Stop1_N), "a read between ticks sees the new link"
    r.step()
    assert r.has(S1.Stop_N_ACK), "the tick sees the new link"


def test_a_link_changed_by_config_wr_in_the_mailbox_moves_the_status_bit_in_the_same_tick():
    from axisline.devices.wago672.mailbox import attach

    r = Rig()
    attach(r.dev)
    r.c3 = 0x80  # Reset_Quit
    r.enable()
    assert r.has(S1.Ready)
    # CONFIG_SET_PTR 128 (Ptr_KBUS_ST1_0), 1 byte; CONFIG_WR Input3 (0x32): S1.0 shows DI3 from now on
    r.c0 = C0.MBX
    r.data = bytes([0x50, 0x80, 128, 0, 1, 0, 0])
    r.step()
    r.data = bytes([0x51, 0x00, Bit.Input3, 0, 0, 0, 0])
    r.step()
    assert r.dev.config["Ptr_KBUS_ST1_0"] == Bit.Input3
    assert r.has(S0.MBX) and not r.has(S1.Ready), "S1.0 reads DI3 (0) in the tick that wrote the link"
    r.inputs["Input3"] = True
    r.step()
    assert r.has(S1.Ready)


def test_configuration_values_follow_every_write_and_name_unknown_keys():
    cfg = ConfigTable()
    values = cfg.values
    assert values["SetupSpeed"] == 3000 and values[44] == 3000  # by name and by address
    cfg.set("SetupSpeed", 5000)
    assert values["SetupSpeed"] == 5000 and values[44] == 5000
    cfg.write_bytes(44, (7000).to_bytes(2, "little"))
    assert cfg.values["SetupSpeed"] == 7000 and cfg["SetupSpeed"] == 7000
    cfg.restore_defaults()
    assert values["SetupSpeed"] == 3000
    with pytest.raises(KeyError, match="no configuration variable named 'SetupSpeeed'"):
        values["SetupSpeeed"]
    other = cfg.copy()
    assert other.values["SetupSpeed"] == 3000
    other.set("SetupSpeed", 100)
    assert cfg.values["SetupSpeed"] == 3000, "a copy has its own values"
    assert len({cfg.generation, other.generation, ConfigTable().generation}) == 3, (
        "no two tables share a generation: a cache keyed on it cannot mix them up"
    )


def test_the_input_image_decodes_to_the_actual_values_on_both_sides_of_zero():
    # D4..D6 position (24 bit two's complement), D0..D1 velocity (16 bit signed) as the PLC decodes them
    r = Rig()
    r.enable()
    r.select(C1.M_Positioning)
    r.positioning(20000, 32767, -3000)
    r.start()
    seen = set()
    for _ in range(400):
        r.step()
        image = InputImage.from_bytes(r.dev.read_inputs())
        assert image == r.dev.input_image()
        assert image.positioning().position == r.dev.actual_position
        assert image.positioning().velocity == r.dev.actual_velocity
        seen.add((image.positioning().position < 0, image.positioning().velocity < 0))
    assert (True, True) in seen and r.dev.actual_position == -3000


def test_inputs_follow_their_wiring_between_ticks():
    class Level:  # an object whose truth changes (not a function)
        on = False

        def __bool__(self) -> bool:
            return self.on

    level = Level()
    r = Rig()
    r.inputs.clear()
    r.inputs[1] = True  # by number
    r.c1 = ON
    r.step()
    assert r.has(S1.Stop_N_ACK)
    r.inputs["Input1"] = level  # the name wins over the number
    r.step()
    assert not r.has(S1.Stop_N_ACK)
    level.on = True
    r.step()
    assert r.has(S1.Stop_N_ACK)
    del r.inputs["Input1"]
    r.inputs[1] = False
    r.step()
    assert not r.has(S1.Stop_N_ACK)


def test_an_fc16_write_across_two_modules_lands_in_both_images():
    config = {"unit": "step", "counts_per_unit": 1.0, "v_max": 1e7, "a_max": 1e10, "following_error_limit": 1e6}
    axes = [Axis(AxisConfig(name=f"a{i}", **config), 0.001) for i in range(2)]
    coupler = Coupler([Wago672(ax, {"Input1": True}) for ax in axes], 0)
    a = OutputImage(c1=ON, data=PositioningSetpoints(100, 200, 300).encode()).to_bytes()
    b = OutputImage(c1=ON | C1.M_Positioning, c2=1, c3=0x80).to_bytes()
    coupler.write_registers(0, pack(a[:6] + bytes(6)))
    coupler.write_registers(3, pack(a[6:] + b[:12]))  # registers 3 .. 11: module 0's last three, module 1's six
    assert coupler.outputs(0) == a and coupler.outputs(1) == b


def test_the_scripted_plcs_write_of_the_whole_area_is_an_fc16_from_register_0():
    config = {"unit": "step", "counts_per_unit": 1.0, "v_max": 1e7, "a_max": 1e10, "following_error_limit": 1e6}
    couplers = [Coupler([Wago672(Axis(AxisConfig(name=f"a{i}", **config), 0.001)) for i in range(2)], 100) for _ in range(2)]
    area = bytes(range(1, 25))
    couplers[0].write_registers(0, pack(area))
    couplers[1].write_images(area)
    for c in couplers:
        c.tick(1)
    a, b = couplers
    assert (a.outputs(0), a.outputs(1), a.watchdog_status, a.since_write, a.writes) == (
        b.outputs(0), b.outputs(1), b.watchdog_status, b.since_write, b.writes)
    assert b.outputs(1) == area[12:]
    with pytest.raises(ValueError, match="the output area of 2 modules is 24 bytes, got 12"):
        b.write_images(area[:12])
