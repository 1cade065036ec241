"""Drive Enable, Brake and the monitoring of one CLM axis, once per NC cycle (a part of `axis.ClmAxis`).

    err = clm.tick("automatic", enable_input=True, estop_ok=True)   # once per NC cycle
    clm.fault_stop(); clm.clear_fault(); clm.interface_enable(False)

The mixin holds what the axis does every cycle whatever it was commanded: the Drive Enable and
Brake outputs (spec §6.3), the kernel axis' power, the Ax14 lag / runaway monitoring, the travel
limits in Automatic, and the outputs Ax14 / Ax27 / Ax28. Its decisions are numbered with the
axis' (axis.py decisions 4, 5, 13-15). The axis' other per-cycle parts follow from here, only
when the axis has them: the open feed roll (Ax30 programmed, feedroll.py) and the measuring
wheel (Ax00 mode 3 / 4, measuring_wheel.py) - one call per cycle, not a chain of overrides.
The output bits it writes every cycle are located once (per configuration), not per write.
"""

from __future__ import annotations

from fractions import Fraction
from typing import Any

from axisline.motion.axis import AxisState

from .clmloop import LAG, NONE, RUNAWAY
from .errors import ClmError, axis_fault
from .operands import Operand

__all__ = ["BRAKE_DELAY_S", "DRIVE_OUTPUTS", "DriveMonitoring"]

#: Drive Enable and Brake outputs per axis (spec §6.3, L6010-6052).
DRIVE_OUTPUTS = {
    1: (Operand("Q", 0, 0, 3), Operand("Q", 0, 0, 4)),
    2: (Operand("Q", 0, 0, 6), Operand("Q", 0, 0, 7)),
    3: (Operand("Q", 0, 1, 6), Operand("Q", 0, 2, 0)),
    4: (Operand("Q", 0, 1, 7), Operand("Q", 0, 2, 1)),
}
BRAKE_DELAY_S = 0.2  # L6058


class DriveMonitoring:
    """Per-cycle drive enable, brake, monitoring and outputs of `ClmAxis` (state kept there)."""

    axis: Any
    loop: Any
    image: Any
    follower: Any
    number: int
    feed_signals: Any
    override: Any
    _con: float | None
    _speed: float
    _enable_bit: tuple[int, int]
    _brake_bit: tuple[int, int]
    _homing_proc: Any
    _ax30_in: Any  # feedroll.OpenFeedRoll: Ax30's input, None when not programmed
    wheel: Any  # measuring_wheel.WheelAxis: the WheelMode of an Ax00 mode 3 / 4 axis, else None
    _homing_inputs: bool
    _ax14_place: tuple[int, int, int] | None  # (byte, shift, mask) of a programmed output
    _ax27_place: tuple[int, int, int] | None
    _ax28_place: tuple[int, int, int] | None

    # ------------------------------------------------------------------ per NC cycle

    def tick(self, mode: str, enable_input: bool, estop_ok: bool) -> ClmError | None:
        """Drive Enable / Brake, the kernel axis' power, monitoring and outputs (decisions 4, 13-15)."""
        ax = self.axis
        self._ran = True
        run = mode in ("manual", "automatic") and estop_ok and enable_input and self._enabled and self._switched_on and not self._fault
        if run and not self._drive_on:
            self._drive_on = True
            self._on_cycles = 0
            ax.power(True)
            self.loop.resync()
            if self.follower is not None:  # slave: couple to the master (slave.py)
                self.follower.attach()
            if self._blocked:
                self._start()
        elif not run and self._drive_on:
            self._drive_off()
        elif run:
            self._on_cycles += 1
            if self.follower is not None:  # slave: coupled again after CPL / homing
                self.follower.keep()
        if self._braking and self._following:  # slave: the own part's stop
            self._braking = not self.follower.own_done  # type: ignore[union-attr]
        elif self._braking and ax.motion_ended and ax.command_velocity == 0.0:
            self._braking = False
            ax.halt()  # the kernel's state: STANDSTILL
        # (axisref: nothing to do without a homing running or a homing input to watch)
        fault = self._homing_tick(mode) if self._homing_proc is not None or self._homing_inputs else None
        if fault is None and not self._fault:
            fault = self._find_fault(mode, enable_input)
        if fault is not None:
            self.fault_stop()
        self._outputs()
        # then Ax30 (feedroll.py) and the measuring wheel (measuring_wheel.py), when the axis has them
        if self._ax30_in is not None:
            self._feed_roll_tick()
        if self.wheel is not None:
            fault = self._wheel_tick(mode, fault)
        return fault

    def _find_fault(self, mode: str, enable_input: bool) -> ClmError | None:
        n = self.number
        if not self._switched_on:  # !MxOFF: "axis-specific faults disabled" (spec §8.6)
            return None
        if mode == "automatic" and self._enabled and not enable_input:
            return ClmError(axis_fault(0x00, n), f"Enable Axis {n} missing in Automatic (L6039)")
        if not self._drive_on:
            return None
        ax = self.axis
        kind = self.loop.excess
        if ax.state is AxisState.ERROR_STOP:  # the machine file's following_error_limit: a safety net
            kind = LAG
        mode14 = self._monitor_mode
        if (kind == LAG and mode14 in (0, 3)) or (kind == RUNAWAY and mode14 in (0, 2)):
            self._homed = False  # errata §3.8
            self._homed_output(0)  # L3715-3717
            what = "Excess Pos Lag" if kind == LAG else "Drive Runaway"
            return ClmError(axis_fault(0x03 if kind == LAG else 0x02, n),
                            f"{what}: deviation {self.loop.deviation:.3f} beyond the Ax14 window {self.window:.3f} (L4518-4532)")
        if mode == "automatic" and self._limits_apply():
            actual = ax.actual_position - float(self._sac_shift)
            if actual < self._min_f:
                return ClmError(axis_fault(0x06, n), f"actual {actual:.3f} below Ax03 = {self._min_f:.3f} (L4294)")
            if actual > self._max_f:
                return ClmError(axis_fault(0x07, n), f"actual {actual:.3f} above Ax04 = {self._max_f:.3f} (L4332)")
        return None

    def _drive_off(self) -> None:
        """Drive Enable off at once: the amplifier is disabled, the motion is dropped."""
        self._drive_on = False
        self._on_cycles = 0
        self._con = None
        self._jog = 0
        self._kept = self._blocked = self._braking = False
        self._target = None
        if self.follower is not None:  # slave: the kernel drops the sync
            self.follower.detach()
        self.axis.power(False)

    def fault_stop(self) -> None:
        """After any CLM error: Drive Enable and Brake off at once (spec §7.1), until `clear_fault`."""
        self._fault = True
        if self._drive_on:
            self._drive_off()
        self._outputs()

    def interface_enable(self, on: bool) -> None:
        """``!MxON`` / ``!MxOFF`` (spec §8.6): off, the drive enable and brake outputs drop and the
        axis' own faults are not raised; on (also after power-on and an E-Stop) it runs again."""
        self._switched_on = on

    def clear_fault(self) -> None:
        """External Clear / CL / !sCLEAR: the drive may be enabled again at the next tick."""
        self._fault = False
        if self.axis.state is AxisState.ERROR_STOP:
            self.axis.reset()
        self._shortest = self._ax05_shortest  # RTM: Ax05 again after an error acknowledge (L2484)
        if self._sac_shift:  # SAC: the initial coordinate system again (L2510)
            self._shift(-self._sac_shift)
            self._sac_shift = Fraction(0)
        if self.follower is not None:  # FOL: mode 1, factor 1 after an error acknowledge (L1967)
            self.follower.defaults()

    @property
    def commanded_speed(self) -> float:
        """IU/s the axis' own motion is commanded at: |CON| or the positioning's speed after the
        override (Ax32's "Target Velocity Reached")."""
        con = self._con
        if con is not None:
            return abs(con)
        return self._speed if self.override is None else self.override(self._speed)

    def _outputs(self) -> None:
        signals = self.feed_signals
        if signals.active:  # Ax29 / Ax32 (feed_signals.py)
            signals.tick(self)
        img = self.image
        data = img.data
        on = self._drive_on
        at, bit = self._enable_bit
        data[at] = data[at] | bit if on else data[at] & ~bit
        at, bit = self._brake_bit
        data[at] = data[at] | bit if on and self._on_cycles >= self._brake_cycles else data[at] & ~bit
        place = self._ax27_place
        if place is not None:  # (an output not programmed, 00.00.0, costs nothing)
            at, shift, _ = place
            data[at] = data[at] | 1 << shift if self.in_position else data[at] & ~(1 << shift)
        place = self._ax28_place
        if place is not None:
            at, shift, _ = place
            data[at] = data[at] | 1 << shift if self._at_target(self._ax28) else data[at] & ~(1 << shift)
        place = self._ax14_place
        if place is not None:
            kind = self.loop.excess if on else NONE
            mode14 = self._monitor_mode
            silent = (kind == LAG and mode14 in (1, 2)) or (kind == RUNAWAY and mode14 in (1, 3))
            at, shift, _ = place
            data[at] = data[at] | 1 << shift if silent else data[at] & ~(1 << shift)
        if self.follower is not None:  # M1.x0.0 "Axis x synchronous" (spec §4.6)
            img.set(Operand("M", 1, self.number * 10, 0), int(self.follower.synchronous))

    @property
    def drive_enabled(self) -> bool:
        return self._drive_on

    @property
    def faulted(self) -> bool:
        return self._fault

