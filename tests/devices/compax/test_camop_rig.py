"""Test rig for the COMPAX cam operation (no tests here): stand-ins for the parameter object and
the cam memory's curve records (the real ones live in devices/compax/{parameters,curves}.py),
a master encoder, and a slave axis on a perfect plant, driven cycle by cycle."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from axisline.devices.compax.camop import CamOperation
from axisline.devices.compax.masterchain import MasterChain
from axisline.motion.axis import Axis, AxisConfig

T = 0.001
FULL = 0.9999999  # the largest 24-bit fraction as the manual writes it: the full slave cycle


@dataclass
class Curve:
    """Stand-in for devices/compax/curves.CurveRecord (the field names of the brief)."""

    number: int = 1
    master_cycle: float = 360.0
    slave_cycle: float = 360.0
    set_points: list[float] = field(default_factory=lambda: [0.0, FULL])
    aux_digital: list[int] | None = None
    coupling: float = 0.0
    synchronous: float = 0.0
    decoupling: float = 0.0
    braking: float = 0.0
    standstill: float = 0.0
    label_set_point: float = 0.0
    label_window: float = 0.0
    correction_enable: float = 0.0
    correction_disable: float = 0.0
    aux_analog: list[tuple[int, int]] | None = None
    first_point: int = 1
    last_point: int = 0

    def __post_init__(self) -> None:
        if not self.last_point:
            self.last_point = self.first_point + len(self.set_points) - 1

    @property
    def open(self) -> bool:
        return self.set_points[0] != self.set_points[-1]


def line(n: int = 11, **kw: Any) -> Curve:
    """The manual's example curve (§25): n set points 0, .1, ..., .9999999, a straight line."""
    pts = [k / (n - 1) for k in range(n - 1)] + [FULL]
    return Curve(set_points=pts, **kw)


class Params(dict):
    """Stand-in for the parameter object: params[n] -> valid value."""


class Encoder:
    def __init__(self) -> None:
        self.counts = 0


# P143 = 90 lines, 4x: 360 increments per encoder revolution; P98 = 360: 1 increment = 1 master unit
BASE_PARAMS = {98: 360.0, 143: 90, 93: 1}


class Rig:
    def __init__(self, curves: Any = None, *, label: Any = None, plant_lag: bool = False,
                 fe_limit: float = 1e6, **params: Any) -> None:
        self.params = Params(BASE_PARAMS)
        self.params.update({int(k[1:]): v for k, v in params.items()})
        self.axis = Axis(
            AxisConfig(name="slave", unit="deg", counts_per_unit=1000.0, v_max=1e7, a_max=1e9,
                       following_error_limit=fe_limit),
            T,
        )
        self.axis.power(True)
        self.enc = Encoder()
        self.inputs: dict[str, Any] = {"I13": False, "I15": False, "I16": False}
        self.curves = curves if curves is not None else {1: line()}
        self.op = CamOperation(self.axis, self.params, self.curves, encoder=self.enc, inputs=self.inputs, label=label)
        self.cycle = 0
        self.speed = 0  # master increments per cycle
        self.trace: list[tuple[float, float, float, float]] = []  # (U, p, v, a)
        self.record = False
        self.lag = plant_lag
        self.x = 0.0
        self._v_cmd = 0.0

    @property
    def chain(self) -> MasterChain:
        return self.op.chain

    def step(self, n: int = 1, **tick: Any) -> None:
        ax, op = self.axis, self.op
        for _ in range(n):
            self.cycle += 1
            self.enc.counts += self.speed
            op.tick(self.cycle, **tick)
            tick = {}
            ax.update_setpoint(self.cycle)
            if self.lag:
                # a drive that only reaches half the commanded speed: a following error builds up
                self.x += 0.5 * self._v_cmd * T
                self._v_cmd = ax.position_loop(self.x)
            else:
                self.x = ax.command_position - ax.position_offset
                ax.position_loop(self.x)
            if self.record:
                self.trace.append((op._U, ax.command_position, ax.command_velocity, ax.command_acceleration))

    def until(self, predicate: Any, limit: int = 100000) -> int:
        for n in range(1, limit + 1):
            self.step()
            if predicate():
                return n
        raise AssertionError(f"condition not reached within {limit} cycles")

    def start_master(self, speed: int = 0) -> None:
        """SETC done: enable master counting (P31 = 0: an I16 edge)."""
        self.inputs["I16"] = False
        self.step()
        self.inputs["I16"] = True
        self.speed = speed
        self.step()

    @property
    def p(self) -> float:
        return self.axis.command_position
