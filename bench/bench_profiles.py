"""Jerk-limited planning: axisline next to Ruckig on the same requests."""

from __future__ import annotations

import random
import statistics
import time

from axisline.motion.profiles import Limits, State, plan


def _requests(n: int):
    out = []
    while len(out) < n:
        vmax, amax, jmax = random.uniform(0.1, 5), random.uniform(0.1, 10), random.uniform(0.5, 100)
        v0, a0 = random.uniform(-vmax, vmax), random.uniform(-amax, amax)
        if abs(v0 + a0 * abs(a0) / (2 * jmax)) > vmax:
            continue  # start states outside the limits are braked differently (see profiles.py)
        vf = random.choice([0.0, random.uniform(-vmax, vmax)])
        out.append((State(random.uniform(-5, 5), v0, a0), State(random.uniform(-5, 5), vf), Limits(vmax, amax, amax, jmax)))
    return out


def bench_profiles(n: int = 2000) -> None:
    import ruckig

    reqs = _requests(n)
    otg, traj, inp = ruckig.Ruckig(1), ruckig.Trajectory(1), ruckig.InputParameter(1)
    ours, theirs, ratios = [], [], []
    for start, target, lim in reqs:
        t0 = time.perf_counter_ns()
        prof = plan("jerk", start, target, lim)
        t1 = time.perf_counter_ns()
        inp.current_position, inp.current_velocity, inp.current_acceleration = [start.p], [start.v], [start.a]
        inp.target_position, inp.target_velocity, inp.target_acceleration = [target.p], [target.v], [0.0]
        inp.max_velocity, inp.max_acceleration, inp.max_jerk = [lim.v], [lim.a], [lim.j]
        t2 = time.perf_counter_ns()
        otg.calculate(inp, traj)
        t3 = time.perf_counter_ns()
        ours.append(t1 - t0)
        theirs.append(t3 - t2)
        if traj.duration > 1e-6:
            ratios.append(prof.duration / traj.duration)
    mo, mt = statistics.median(ours) / 1e3, statistics.median(theirs) / 1e3
    print(f"profiles: {n} random jerk-limited requests (moving starts, target velocities)")
    print(f"  planning time, median   axisline {mo:9.1f} us   ruckig {mt:7.2f} us   ratio {mo / mt:8.1f}x")
    print(f"  duration ratio axisline/ruckig   median {statistics.median(ratios):.6f}   "
          f"min {min(ratios):.6f}   max {max(ratios):.6f}")
    t0 = time.perf_counter_ns()
    prof = plan("jerk", State(0, 0, 0), State(10, 0), Limits(1, 2, 2, 10))
    k = 20000
    t0 = time.perf_counter_ns()
    for i in range(k):
        prof.sample(i * 0.0005)
    t1 = time.perf_counter_ns()
    print(f"  sampling one profile point            {(t1 - t0) / k / 1e3:9.2f} us")
