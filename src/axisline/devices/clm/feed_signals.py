"""The feed signals of a CLM axis: Ax29 presignaling and Ax32 "Target Velocity Reached" /
"Deceleration Active" (manual L4788-4808, L4833-4840; spec §5.2).

    signals = FeedSignals(params, number=1, image=image, nc_cycle_s=0.002)
    signals.new_feed()                   # POI / PSI / POA / PSA of this axis was received
    signals.tick(clm_axis)               # once per NC cycle, after the axis' monitoring

Nothing is done per cycle when none of the three outputs is programmed (00.00.0).

Decisions (spec line -> choice, why)
------------------------------------
1. Ax29 distance (L4792-4794, printed ``1234`` without a decimal point; spec [AMBIGUOUS]) ->
   whole IU as printed (0000-9999 IU). Test:
   tests/devices/clm/test_feed_signals.py::test_presignal_at_the_distance_before_the_target.
2. "The distance still to be traversed" (L4804) -> of the set point: |target - set point|
   <= distance switches the output on. The CLM's interpolator knows the rest of its path; the
   actual position would delay the signal by the lag (3 mm at 30 m/min with Kv 10), which
   the press that waits for it does not expect. With distance 0 the output comes when the set
   point reaches the target. Test: test_presignal_at_the_distance_before_the_target.
3. Pulse time (L4796-4798, 0.1 s steps, 0.0 = constant) -> on for ceil(t / NC cycle) cycles,
   then off until the next feed; constant: on until the next feed instruction ("disabled each
   time a new feed instruction is received", L4806). Only POI, PSI, POA and PSA arm it
   (L4802: "every positioning command"); CON, jog, homing and registration moves do not.
   Test: test_presignal_pulse_and_reset_by_the_next_feed.
4. Ax32 (L4833-4840; labels listed right to left, spec §0)
   -> (the left field is "Target Velocity Reached", the right "Deceleration Active")
   Target Velocity Reached: the axis' own motion (a positioning or CON) has a set point at its
   commanded velocity (after the override) within 0.1 % and no acceleration; Deceleration
   Active: the set point's speed is falling (velocity and acceleration of opposite signs).
   Both are 0 at rest. Test: test_ax32_velocity_reached_and_deceleration.
"""

from __future__ import annotations

import math
from typing import Any

from .image import ProcessImage
from .operands import Operand
from .parameters import ParameterSet

__all__ = ["FeedSignals"]


class FeedSignals:
    """Ax29 / Ax32 outputs of CLM axis `number` (see the module docstring)."""

    def __init__(self, params: ParameterSet, number: int, image: ProcessImage, nc_cycle_s: float) -> None:
        a = f"A{number}"
        p29, p32 = params.get(a + "29"), params.get(a + "32")
        self.image = image
        self._presignal: Operand = p29["presignal_output"]
        self._distance = float(p29.number("distance"))
        pulse = float(p29.number("pulse_time"))
        self._pulse_cycles = math.ceil(pulse / nc_cycle_s - 1e-9) if pulse > 0.0 else None
        self._reached: Operand = p32["velocity_reached_output"]
        self._decelerating: Operand = p32["deceleration_active_output"]
        self.active = not (self._presignal.unset and self._reached.unset and self._decelerating.unset)
        self._armed = False  # a positioning command runs towards its target, no signal yet
        self._left = -1  # cycles the pulse stays on (-1: constant while on)
        self._on = False

    def new_feed(self) -> None:
        """A POI / PSI / POA / PSA of this axis: the output drops, the next signal is armed."""
        self._armed = True
        self._on = False

    def tick(self, clm: Any) -> None:
        if not self.active:
            return
        img = self.image
        ax = clm.axis
        if not self._presignal.unset:
            self._presignal_tick(clm, ax)
            img.set(self._presignal, int(self._on))
        if self._reached.unset and self._decelerating.unset:
            return
        v, a = ax.command_velocity, ax.command_acceleration
        own = clm.drive_enabled and not clm.motion_done
        if not self._reached.unset:
            wanted = clm.commanded_speed if own else 0.0
            img.set(self._reached, int(own and wanted > 0.0 and abs(abs(v) - wanted) <= 1e-3 * wanted and abs(a) < 1e-9))
        if not self._decelerating.unset:
            img.set(self._decelerating, int(v * a < 0.0))

    def _presignal_tick(self, clm: Any, ax: Any) -> None:
        if self._on and self._left > 0:
            self._left -= 1
            if self._left == 0:
                self._on = False
            return
        target = clm.target
        if not self._armed or target is None or not clm.drive_enabled:
            return
        if abs(target - ax.command_position) <= self._distance:
            self._armed = False
            self._on = True
            self._left = self._pulse_cycles if self._pulse_cycles is not None else -1
