"""Actuators driven by a digital output: a cylinder (a press ram, a clamp, a knife) with end switches.

    ram = Cylinder(extend_time=0.12, retract_time=0.18)
    ram.step(dt, valve_on)      # once per cycle, after the controller wrote its outputs
    ram.retracted, ram.extended # the end switches

The ram moves at a constant speed, from one end to the other in `extend_time` while the valve
is on and back in `retract_time` while it is off (a pneumatic or hydraulic cylinder with flow
control, a press with its stroke). Each end switch is closed while the ram is at its end. A
controller waiting on the switches sees the travel times; nothing else of the mechanics matters
to it.
"""

from __future__ import annotations

__all__ = ["Cylinder"]


class Cylinder:
    def __init__(self, extend_time: float, retract_time: float, *, extended: bool = False) -> None:
        if not (extend_time > 0.0 and retract_time > 0.0):
            raise ValueError(f"extend_time = {extend_time}, retract_time = {retract_time}: both must be > 0 s")
        self.extend_time, self.retract_time = extend_time, retract_time
        self.stroke = 1.0 if extended else 0.0  # 0 retracted .. 1 extended

    def step(self, dt: float, valve_on: bool) -> None:
        if valve_on:
            self.stroke = min(1.0, self.stroke + dt / self.extend_time)
        else:
            self.stroke = max(0.0, self.stroke - dt / self.retract_time)

    @property
    def retracted(self) -> bool:
        return self.stroke <= 0.0

    @property
    def extended(self) -> bool:
        return self.stroke >= 1.0
