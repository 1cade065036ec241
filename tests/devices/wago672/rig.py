"""A PLC and a simple stepper plant around one Wago672, driven cycle by cycle.

Each cycle: the PLC writes its 12 output bytes, the module ticks (before the axis), the axis
samples its set point, the stepper follows the commanded microsteps exactly (an open-loop
stepper without step losses: actual = command), and the PLC reads the 12 input bytes.
Switches are functions of the plant position `x` [microsteps, plant frame], so a reference
run that moves the logical zero does not move the switches.
"""

from __future__ import annotations

from collections.abc import Callable

from axisline.devices.wago672.config_table import ConfigTable
from axisline.devices.wago672.device import Wago672
from axisline.devices.wago672.image import (
    C1,
    InputImage,
    OutputImage,
    PositioningSetpoints,
    S1,
    S2,
    SpeedSetpoints,
)
from axisline.motion.axis import Axis, AxisConfig

ON = C1.Enable | C1.Stop2_N


class Rig:
    def __init__(self, config: ConfigTable | None = None, counts_per_unit: float = 1.0, **values: int) -> None:
        if values:
            config = config or ConfigTable()
            config.update(values)
        self.axis = Axis(
            AxisConfig(
                name="x", unit="step", counts_per_unit=counts_per_unit, v_max=1e7, a_max=1e10,
                following_error_limit=1e6,
            ),
            0.001,
        )
        self.inputs: dict[str, object] = {"Input1": True}
        self.dev = Wago672(self.axis, self.inputs, config)
        self.c0 = self.c1 = self.c2 = self.c3 = 0
        self.data = bytes(7)
        self.cycle = 0
        self.x = 0.0  # plant position [axis units, plant frame]
        self.inp = InputImage()
        self.trace: list[tuple[int, float, float]] = []  # (cycle, module set point, velocity) [microsteps]
        self.record = False

    # ---- the cycle
    def out(self) -> OutputImage:
        return OutputImage(self.c0, self.c1, self.c2, self.c3, self.data)

    def step(self, n: int = 1) -> InputImage:
        ax, dev = self.axis, self.dev
        for _ in range(n):
            self.cycle += 1
            dev.write_outputs(self.out().to_bytes())
            dev.tick(self.cycle)
            ax.update_setpoint(self.cycle)
            self.x = ax.command_position - ax.position_offset
            ax.position_loop(self.x)
            self.inp = InputImage.from_bytes(dev.read_inputs())
            if self.record:
                self.trace.append((self.cycle, dev.position_steps, dev.velocity_steps))
        return self.inp

    def until(self, predicate: Callable[[], bool], limit: int = 20000) -> int:
        """Step until predicate() holds; returns the number of cycles (fails the test at `limit`)."""
        for n in range(1, limit + 1):
            self.step()
            if predicate():
                return n
        raise AssertionError(f"condition not reached within {limit} cycles: S1={self.s1:#04x} S2={self.s2:#04x} error={self.dev.errors.error}")

    # ---- wiring
    def switch(self, name: str, when: Callable[[float], bool]) -> None:
        """Wire input `name` ("Input2", ...) as a function of the plant position."""
        self.inputs[name] = lambda: when(self.x)

    # ---- status read-outs
    @property
    def s0(self) -> int:
        return self.inp.s0

    @property
    def s1(self) -> int:
        return self.inp.s1

    @property
    def s2(self) -> int:
        return self.inp.s2

    @property
    def s3(self) -> int:
        return self.inp.s3

    def has(self, flag) -> bool:
        """Is a status flag (S1.x / S2.x / S3.x / S0.x) set in the last input image?"""
        from axisline.devices.wago672.image import S0, S3

        byte = {S0: self.s0, S1: self.s1, S2: self.s2, S3: self.s3}[type(flag)]
        return bool(byte & flag)

    @property
    def position(self) -> int:
        return self.inp.positioning().position

    @property
    def velocity(self) -> int:
        return self.inp.positioning().velocity

    @property
    def error(self) -> int:
        return self.dev.errors.error

    # ---- PLC sequences
    def enable(self) -> None:
        self.c1 |= ON
        self.until(lambda: self.has(S1.Ready) and self.has(S1.Stop_N_ACK), 5)

    def select(self, mode_bits: int, ack: int | None = None) -> None:
        """Set the mode bits and wait for their Command_ACK."""
        self.c1 = (self.c1 & 0x07) | mode_bits
        want = mode_bits if ack is None else ack
        self.until(lambda: (self.s1 & 0xF8) == want, 5)

    def positioning(self, velocity: int, acceleration: int, target: int) -> None:
        self.data = PositioningSetpoints(velocity, acceleration, target).encode()

    def speed(self, velocity: int, acceleration: int) -> None:
        self.data = SpeedSetpoints(velocity, acceleration).encode()

    def start(self) -> None:
        """Start 0 -> 1, wait for Start_ACK, Start -> 0 (sequence diagram steps 5, 6)."""
        self.c1 |= C1.Start
        self.until(lambda: self.has(S1.Start_ACK), 3)
        self.c1 &= ~C1.Start
        self.step()
        assert not self.has(S1.Start_ACK), "Start_ACK follows Start back to 0"

    def move(self, velocity: int, acceleration: int, target: int, limit: int = 20000) -> int:
        """A complete single positioning; returns the cycles until On_Target."""
        self.positioning(velocity, acceleration, target)
        self.start()
        return self.until(lambda: self.has(S2.On_Target), limit)
