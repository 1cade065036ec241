"""The coupler's register map and watchdog, as a PLC programmer relies on them (docs/wago672-modbus.md).

No network here: the registers are read and written as the Modbus server does it (between
cycles), the K-bus cycle is `Coupler.tick`, the axes follow the modules' set points.
"""

from __future__ import annotations

import pytest

from axisline.devices.wago672.coupler import (
    OUTPUT_READBACK,
    WATCHDOG_STATUS,
    WATCHDOG_TIME,
    WD_EXPIRED,
    WD_NOT_STARTED,
    WD_RUNNING,
    Coupler,
    pack,
    unpack,
)
from axisline.devices.wago672.device import Wago672
from axisline.devices.wago672.image import C1, S1, S2, InputImage, OutputImage, PositioningSetpoints
from axisline.fieldbus.modbus import RegisterRefused
from axisline.motion.axis import Axis, AxisConfig, AxisState

ON = C1.Enable | C1.Stop2_N
STOP_FAST = 30000 * 1000 / 40  # Acceleration_Stop_Fast at the default factors [microsteps/s^2]


class Bus:
    """A coupler with `n` modules, each on its own axis (microsteps), ticked cycle by cycle."""

    def __init__(self, n: int = 1, watchdog_ms: int = 50) -> None:
        self.axes = [
            Axis(AxisConfig(name=f"a{i}", unit="step", counts_per_unit=1.0, v_max=1e7, a_max=1e10, following_error_limit=1e6), 0.001)
            for i in range(n)
        ]
        self.devs = [Wago672(ax, {"Input1": True}) for ax in self.axes]
        self.coupler = Coupler(self.devs, watchdog_ms)
        self.cycle = 0
        self.velocities: list[list[float]] = [[] for _ in range(n)]

    def step(self, k: int = 1) -> None:
        for _ in range(k):
            self.cycle += 1
            self.coupler.tick(self.cycle)
            for i, ax in enumerate(self.axes):
                ax.update_setpoint(self.cycle)
                ax.position_loop(ax.command_position - ax.position_offset)
                self.velocities[i].append(ax.command_velocity)

    def write(self, module: int, image: OutputImage) -> None:
        self.coupler.write_registers(6 * module, pack(image.to_bytes()))

    def inputs(self, module: int = 0) -> InputImage:
        return InputImage.from_bytes(unpack(self.coupler.read_registers("input", 6 * module, 6)))

    def until(self, predicate, limit: int = 5000, feed: tuple[int, OutputImage] | None = None) -> int:
        """Tick until predicate(); `feed` re-writes a module's image each cycle (a PLC's cycle)."""
        for n in range(1, limit + 1):
            if feed is not None:
                self.write(*feed)
            self.step()
            if predicate():
                return n
        raise AssertionError(f"not reached within {limit} cycles: {self.inputs()}")

    def enable_and_start(self, module: int, target: int, velocity: int = 20000, acceleration: int = 2000) -> OutputImage:
        self.write(module, OutputImage(c1=ON))
        self.step(2)
        self.write(module, OutputImage(c1=ON | C1.M_Positioning))
        self.step(2)
        image = OutputImage(c1=ON | C1.M_Positioning | C1.Start, data=PositioningSetpoints(velocity, acceleration, target).encode())
        self.write(module, image)
        self.step()
        assert self.inputs(module).s1 & S1.Start_ACK
        return image


# ---------------------------------------------------------------- byte packing


def test_register_k_holds_byte_2k_low_and_byte_2k_plus_1_high():
    image = bytes(range(0x10, 0x1C))
    assert pack(image) == [0x1110, 0x1312, 0x1514, 0x1716, 0x1918, 0x1B1A]
    assert unpack(pack(image)) == image
    with pytest.raises(ValueError):
        pack(bytes(3))
    with pytest.raises(ValueError):
        unpack([0x10000])


def test_written_registers_reach_the_module_byte_for_byte():
    bus = Bus()
    regs = [0x0020, 0x4E20, 0x0BB8, 0xFE29, 0x0000, 0x0B00]  # C0 = 0x20, res, D0..D6, C3, C2, C1 = 0x0B
    bus.coupler.write_registers(0, regs)
    bus.step()
    seen = bus.coupler.module_outputs(0)
    assert seen == bytes([0x20, 0x00, 0x20, 0x4E, 0xB8, 0x0B, 0x29, 0xFE, 0x00, 0x00, 0x00, 0x0B])
    out = OutputImage.from_bytes(seen)
    assert out.c1 == 0x0B and out.c0 == 0x20
    # read back at 0x0200, with FC3 and FC4 alike
    assert bus.coupler.read_registers("holding", OUTPUT_READBACK, 6) == regs
    assert bus.coupler.read_registers("input", OUTPUT_READBACK + 3, 2) == regs[3:5]


def test_input_registers_carry_the_module_image_with_fc3_and_fc4():
    bus = Bus()
    bus.write(0, OutputImage(c1=ON))
    bus.step(3)
    raw = bus.devs[0].read_inputs()
    assert bus.coupler.read_registers("input", 0, 6) == pack(raw)
    assert bus.coupler.read_registers("holding", 0, 6) == pack(raw)
    reg5 = bus.coupler.read_registers("input", 5, 1)[0]
    assert reg5 & 0xFF == raw[10] and reg5 >> 8 == raw[11]  # S2 low, S1 high
    assert reg5 >> 8 == S1.Ready | S1.Stop_N_ACK


def test_position_on_the_wire_after_a_move():
    bus = Bus()
    image = bus.enable_and_start(0, -1000)
    bus.until(lambda: bus.inputs().s2 & S2.On_Target, feed=(0, image))
    regs = bus.coupler.read_registers("input", 0, 6)
    # D4..D6 = image bytes 6..8: register 3 (bytes 6, 7) and the low byte of register 4 (byte 8)
    position = int.from_bytes(bytes([regs[3] & 0xFF, regs[3] >> 8, regs[4] & 0xFF]), "little", signed=True)
    assert position == -1000 and bus.axes[0].command_position == -1000


def test_a_single_register_write_changes_two_bytes_only():
    bus = Bus()
    bus.coupler.write_registers(0, pack(bytes(range(1, 13))))
    bus.coupler.write_registers(2, [0xBEEF])  # FC6
    assert bus.coupler.outputs(0) == bytes([1, 2, 3, 4, 0xEF, 0xBE, 7, 8, 9, 10, 11, 12])


def test_several_modules_follow_each_other():
    bus = Bus(3)
    assert bus.coupler.size == 18
    bus.coupler.write_registers(6, pack(bytes([0xA0] * 12)))  # module 1 only
    bus.coupler.write_registers(17, [0x0301])  # last register of module 2: C2 = 0x01, C1 = 0x03
    bus.step()
    assert bus.coupler.module_outputs(0) == bytes(12)
    assert bus.coupler.module_outputs(1) == bytes([0xA0] * 12)
    assert bus.coupler.module_outputs(2)[10:] == bytes([0x01, 0x03])
    assert bus.coupler.read_registers("holding", OUTPUT_READBACK + 6, 6) == [0xA0A0] * 6
    # one read over all input images; module 2 is enabled, the others are not
    regs = bus.coupler.read_registers("input", 0, 18)
    assert [r >> 8 & S1.Ready for r in (regs[5], regs[11], regs[17])] == [0, 0, S1.Ready]
    # and they move independently
    bus2 = Bus(2)
    image = bus2.enable_and_start(1, 5000)
    bus2.until(lambda: bus2.inputs(1).s2 & S2.On_Target, feed=(1, image))
    assert bus2.axes[1].command_position == 5000 and bus2.axes[0].command_position == 0
    assert bus2.inputs(0).s1 == 0


@pytest.mark.parametrize(
    ("kind", "address", "count"),
    [("input", 6, 1), ("input", 4, 3), ("holding", OUTPUT_READBACK + 6, 1), ("holding", 0x0100, 1), ("input", 0, 0),
     ("holding", WATCHDOG_TIME, 7), ("coils", 0, 1)],
)
def test_reads_outside_the_map_are_refused(kind, address, count):
    with pytest.raises(RegisterRefused):
        Bus().coupler.read_registers(kind, address, count)


@pytest.mark.parametrize(("address", "values"), [(6, [0]), (5, [0, 0]), (OUTPUT_READBACK, [0]), (WATCHDOG_TIME, [10]), (0, []), (0, [0x10000])])
def test_writes_outside_the_output_image_are_refused_and_change_nothing(address, values):
    bus = Bus()
    bus.coupler.write_registers(0, [1, 2, 3, 4, 5, 6])
    with pytest.raises(RegisterRefused):
        bus.coupler.write_registers(address, values)
    assert bus.coupler.read_registers("holding", OUTPUT_READBACK, 6) == [1, 2, 3, 4, 5, 6]
    assert bus.coupler.writes == 1


# ---------------------------------------------------------------- watchdog


def test_watchdog_starts_with_the_first_write_and_reads_do_not_feed_it():
    bus = Bus(watchdog_ms=20)
    assert bus.coupler.read_registers("holding", WATCHDOG_TIME, 1) == [20]
    for _ in range(50):
        bus.coupler.read_registers("input", 0, 6)
        bus.step()
    assert bus.coupler.read_registers("holding", WATCHDOG_STATUS, 1) == [WD_NOT_STARTED]
    bus.write(0, OutputImage(c1=ON))
    assert bus.coupler.watchdog_status == WD_RUNNING
    for _ in range(20):
        bus.coupler.read_registers("input", 0, 6)
        bus.step()
    assert bus.coupler.watchdog_status == WD_RUNNING  # 20 ms: not yet longer than the watchdog time
    bus.step()
    assert bus.coupler.read_registers("input", WATCHDOG_STATUS, 1) == [WD_EXPIRED]
    assert bus.coupler.expiries == 1


def test_watchdog_stops_the_motor_with_the_stop_ramp_then_clears_the_outputs():
    bus = Bus(watchdog_ms=50)
    image = bus.enable_and_start(0, 8_000_000, velocity=20000)
    bus.until(lambda: bus.inputs().s2 & S2.On_Speed, feed=(0, image))
    v0 = bus.axes[0].command_velocity
    assert v0 == pytest.approx(40000.0)
    bus.until(lambda: bus.coupler.watchdog_expired, limit=100)
    assert bus.coupler.since_write == 51  # expired at the first tick more than 50 ms after the last write
    assert bus.coupler.outputs(0) == bytes(12)  # the coupler's outputs are 0 (read back shows it)
    assert bus.coupler.module_outputs(0)[11] == C1.Enable  # the module keeps Enable for its STOP ramp
    p0 = bus.axes[0].command_position
    k = len(bus.velocities[0])
    bus.until(lambda: bus.axes[0].command_velocity == 0.0, limit=1000)
    bus.step(3)
    v = bus.velocities[0][k - 1 :]
    decel = [(a - b) / 0.001 for a, b in zip(v, v[1:]) if a > 0.0]
    assert max(decel) == pytest.approx(STOP_FAST, rel=0.02)  # Acceleration_Stop_Fast, not a coast
    assert bus.axes[0].command_position - p0 == pytest.approx(v0 * v0 / (2 * STOP_FAST), rel=0.05, abs=60)
    # at standstill the coupler clears the image: Enable 0, the output stage is off, no mode
    assert bus.coupler.module_outputs(0) == bytes(12)
    st = bus.inputs()
    assert st.s1 == 0 and st.s2 & S2.StandStill
    assert bus.axes[0].state is AxisState.DISABLED
    assert bus.coupler.summary()["watchdog_status"] == "expired"


def test_the_next_write_rearms_the_watchdog():
    bus = Bus(watchdog_ms=10)
    bus.write(0, OutputImage(c1=ON))
    bus.step(30)
    assert bus.coupler.watchdog_expired and bus.inputs().s1 == 0
    bus.write(0, OutputImage(c1=ON))
    bus.step()
    assert bus.coupler.watchdog_status == WD_RUNNING
    assert bus.coupler.module_outputs(0)[11] == ON
    assert bus.inputs().s1 == S1.Ready | S1.Stop_N_ACK
    bus.step(20)
    assert bus.coupler.expiries == 2


def test_watchdog_of_a_module_that_was_never_enabled_clears_at_once():
    bus = Bus(2, watchdog_ms=10)
    bus.write(1, OutputImage(c1=ON))
    bus.step(12)
    assert bus.coupler.watchdog_expired
    bus.step()
    assert bus.coupler.module_outputs(0) == bytes(12) and bus.coupler.module_outputs(1) == bytes(12)
    assert bus.inputs(1).s1 == 0


def test_network_writes_follow_the_operators_enable():
    enabled = [False]
    c = Coupler(Bus().devs, writes_allowed=lambda: enabled[0])
    assert c.network_writes is False
    enabled[0] = True
    assert c.network_writes is True
    bare = Bus().coupler
    assert bare.network_writes is False
    bare.network_writes = True
    assert bare.network_writes is True


def test_shutdown_stop_brakes_moving_modules_with_their_stop_ramp():
    # serve stopped (Ctrl-C, SIGTERM): the personality's stop() brakes each module as a
    # watchdog expiry does, so the module's own set point stays the axis' set point
    bus = Bus(watchdog_ms=10_000)
    image = bus.enable_and_start(0, 8_000_000, velocity=20000)
    bus.until(lambda: bus.inputs().s2 & S2.On_Speed, feed=(0, image))
    k = len(bus.velocities[0])
    bus.coupler.stop_modules()
    bus.until(lambda: bus.axes[0].command_velocity == 0.0, limit=1000)
    v = bus.velocities[0][k - 1 :]
    decel = [(a - b) / 0.001 for a, b in zip(v, v[1:]) if a > 0.0]
    assert max(decel) == pytest.approx(STOP_FAST, rel=0.02)  # its stop ramp, not a coast
    assert bus.coupler.summary()["watchdog_expiries"] == 0  # a shutdown, not a watchdog event
