"""The CLM1.4 position loop of one axis: Kv, feed-forward, Ax12 scaling -> +-10 V; the Ax14 model.

    loop = ClmLoop(kernel_axis, period)
    loop.configure(kv=1.0, feedforward=0, full_speed=500.0, full_volts=10.0, window=3.0)
    machine.drive_by("feed", loop, volts=True)       # POSITION_LOOP calls loop(actual, drive_v)
    loop.volts, loop.lag, loop.deviation, loop.excess  # after each cycle

The control law (manual L4437-4486; errata §1.1 / §3.1 for the unit of Kv):

    e      = set point - actual position                     IU   (the position lag)
    v_cmd  = FF + Kv * (1000/60) * e                         IU/s (Kv = 1: 1 mm lag at 1 m/min, L4461)
    FF     = set-point velocity (Ax11 feedforward 1), averaged over 2^(n-1) cycles for n >= 2
             (L4443-4453), 0 when off
    volts  = v_cmd / (Ax12 RPM / 60 x feed constant) x Ax12 volts, clipped to +-10 V (L4473-4482)

Ax14 (L4518-4532): "The CLM uses a mathematical model of the system to calculate the expected
position". The model here is the ideal closed loop itself: a motor that follows the command
velocity at once, m += T (FF + Kv (1000/60) (set point - m)). Its lag is exactly the expected
lag (v / (Kv 1000/60) at constant speed, less while accelerating); ``deviation = m - actual``
is what the drive does differently from that ideal (its own lag, offset, a stall, a wrong
direction). Beyond the window (Ax14 % of the maximum deviation Ax12 RPM x Ax01 / (1000 Kv),
L4532) it is "Drive Runaway" when the actual position, as the encoder sees it, moves away
from the model position (positive feedback, "moving without command", a faster drive:
L4520), else "Position Lag" (a drive that is slower, stalled or not enabled: L4522).
`ClmAxis.tick` turns ``excess`` into the fault per the Ax14 mode (decisions there).

``feedback`` (measuring wheel mode, measuring_wheel.py): when set, ``feedback.actual(motor)``
turns the motor encoder's position into the loop's actual position each cycle (Version 1: the
motor plus what the wheel measured differently), before anything else sees it. ``open`` (Ax30,
feedroll.py): the loop commands 0 V and the Ax14 model waits, as without power.
"""

from __future__ import annotations

from typing import Any

__all__ = ["ClmLoop", "KV_UNIT", "NONE", "LAG", "RUNAWAY"]

KV_UNIT = 1000.0 / 60.0  # Kv = 1 -> loop gain 16.67 1/s (errata §1.1)
VOLTS_LIMIT = 10.0
NONE, LAG, RUNAWAY = 0, 1, 2


class ClmLoop:
    """Called by the machine in POSITION_LOOP with (actual position, drive velocity); returns volts."""

    def __init__(self, axis: Any, period: float) -> None:
        self.axis = axis
        self.period = float(period)
        self.gain = KV_UNIT  # 1/s
        self.volts_per_velocity = 0.0
        self.window = float("inf")
        self._ff_on = False
        self._ff_buffer = [0.0]
        self._ff_at = 0
        self._ff_sum = 0.0
        self.volts = 0.0
        self.lag = 0.0  # set point - actual, IU
        self.deviation = 0.0  # model - actual, IU
        self.excess = NONE
        self._model = 0.0
        self._previous = 0.0
        self._sync = True  # take the model from the actual position at the next cycle
        self.feedback: Any = None  # measuring_wheel.WheelMode of a mode 3/4 axis
        self.open = False  # Ax30 open feed roll (feedroll.py): 0 V, no Ax14 model

    def configure(self, *, kv: float, feedforward: int, full_speed: float, full_volts: float, window: float) -> None:
        """kv: Ax11 factor; feedforward: Ax11 digit; full_speed: IU/s at full_volts (Ax12); window: IU."""
        self.gain = kv * KV_UNIT
        self.volts_per_velocity = full_volts / full_speed if full_speed > 0.0 else 0.0
        self.window = window
        self._ff_on = feedforward > 0
        self._ff_buffer = [0.0] * (2 ** (feedforward - 1) if feedforward >= 2 else 1)
        self.resync()

    def resync(self) -> None:
        """Model and feed-forward restart from the axis as it is (power on, CPL, a new reference)."""
        self._sync = True
        for i in range(len(self._ff_buffer)):
            self._ff_buffer[i] = 0.0
        self._ff_at = 0
        self._ff_sum = 0.0
        self.excess = NONE

    def __call__(self, actual_position: float, drive_velocity: float) -> float:
        ax = self.axis
        if self.feedback is not None:  # measuring wheel: the actual position the loop closes on
            actual_position = self.feedback.actual(actual_position)
        ax.position_loop(actual_position, drive_velocity)  # the kernel's bookkeeping (actual, lag)
        actual = ax.actual_position
        if not ax.powered or self.open:  # (open feed roll: 0 V, the roll may drift)
            self._sync = True
            self._previous = actual
            self.lag = self.deviation = self.volts = 0.0
            self.excess = NONE
            return 0.0
        if self._sync:
            self._sync = False
            self._model = actual
            self._previous = actual
        p = ax.command_position
        ff = 0.0
        if self._ff_on:
            buf = self._ff_buffer
            v = ax.command_velocity
            self._ff_sum += v - buf[self._ff_at]
            buf[self._ff_at] = v
            self._ff_at = (self._ff_at + 1) % len(buf)
            ff = self._ff_sum / len(buf)
        e = p - actual
        self.lag = e
        # Ax14: the ideal loop's position now against the encoder's
        m = self._model
        dev = m - actual
        self.deviation = dev
        moved = actual - self._previous
        self._previous = actual
        if dev > self.window or -dev > self.window:
            self.excess = RUNAWAY if dev * moved < 0.0 else LAG
        else:
            self.excess = NONE
        self._model = m + self.period * (ff + self.gain * (p - m))
        u = (ff + self.gain * e) * self.volts_per_velocity
        if u > VOLTS_LIMIT:
            u = VOLTS_LIMIT
        elif u < -VOLTS_LIMIT:
            u = -VOLTS_LIMIT
        self.volts = u
        return u
