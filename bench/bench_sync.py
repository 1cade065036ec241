"""Cost of one cycle of a coupled slave: gear, cam of 2500 points, cam of motion laws."""

from __future__ import annotations

import math
import statistics
import time

from axisline.motion.axis import Axis, AxisConfig
from axisline.motion.cam import PointTable
from axisline.motion.camsync import CamFollower
from axisline.motion.gear import Gear
from axisline.motion.master import VirtualMaster
from axisline.motion.segments import Segment, SegmentCam

T = 0.001


def _slave() -> Axis:
    cfg = AxisConfig(name="slave", unit="mm", counts_per_unit=1000.0, v_max=5000.0, a_max=1e6, j_max=1e8,
                     following_error_limit=10.0)
    ax = Axis(cfg, T)
    ax.power(True)
    ax.update_setpoint(0)
    ax.position_loop(0.0)
    return ax


def _cycle_cost(make_source, n: int = 5000) -> float:
    ax = _slave()
    master = VirtualMaster(T, 360.0, acceleration=1e4, counts_per_unit=1000.0)
    source = make_source(master, ax)
    if isinstance(source, Gear):
        source.gear_in()
    else:
        ax.start_sync(source)
    costs = []
    for c in range(1, n):
        t0 = time.perf_counter_ns()
        ax.update_setpoint(c)  # samples the source, which updates its master
        ax.position_loop(ax.command_position)
        costs.append(time.perf_counter_ns() - t0)
    return statistics.median(costs) / 1e3


def bench_sync() -> None:
    table = PointTable.equidistant([20.0 * math.sin(2 * math.pi * i / 2500) for i in range(2501)], 360.0)
    laws = SegmentCam([Segment(90.0, 0.0, "dwell"), Segment(180.0, 50.0, "cycloidal"),
                       Segment(270.0, 50.0, "dwell"), Segment(360.0, 0.0, "modified_sine")])
    print("sync: one cycle of a coupled slave axis (master update + set point + position loop), median")
    idle = _cycle_cost(lambda m, ax: _Still())
    for name, make in (
        ("gear 16523/11872", lambda m, ax: Gear(m, ax, 16523, 11872)),
        ("cam, 2500-point table", lambda m, ax: CamFollower(m, table)),
        ("cam of motion laws", lambda m, ax: CamFollower(m, laws)),
    ):
        cost = _cycle_cost(make)
        print(f"  {name:24s} {cost:7.2f} us   ({cost / idle:4.1f}x a slave holding still)")


class _Still:
    """Reference: a sync source that holds the slave still."""

    def sample(self, cycle: int):
        return 0.0, 0.0, 0.0
