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


def _p99(xs: list) -> float:
    return sorted(xs)[min(len(xs) - 1, int(0.99 * len(xs)))]


def bench_profiles(n: int = 2000, rounds: int = 3) -> None:
    """Each request planned by both, interleaved, `rounds` times: the median and p99 are over
    every single timing (as before); the per-request ratio takes each side's fastest of the
    rounds (a single timing of a 0.3 us Ruckig call is mostly timer and cache noise)."""
    import ruckig

    reqs = _requests(n)
    otg, traj, inp = ruckig.Ruckig(1), ruckig.Trajectory(1), ruckig.InputParameter(1)
    ours, theirs, ratios = [], [], []
    best_ours, best_theirs = [float("inf")] * n, [float("inf")] * n
    for round_ in range(rounds):
        for i, (start, target, lim) in enumerate(reqs):
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
            best_ours[i], best_theirs[i] = min(best_ours[i], t1 - t0), min(best_theirs[i], t3 - t2)
            if round_ == 0 and traj.duration > 1e-6:
                ratios.append(prof.duration / traj.duration)
    mo, mt = statistics.median(ours) / 1e3, statistics.median(theirs) / 1e3
    po, pt = _p99(ours) / 1e3, _p99(theirs) / 1e3
    per_request = [a / b for a, b in zip(best_ours, best_theirs)]
    print(f"profiles: {n} random jerk-limited requests (moving starts, target velocities), {rounds} rounds")
    print(f"  planning time, median   axisline {mo:9.2f} us   ruckig {mt:7.2f} us   ratio {mo / mt:8.1f}x   (bar 5x)")
    print(f"  planning time, p99      axisline {po:9.2f} us   ruckig {pt:7.2f} us   ratio {po / pt:8.1f}x   (bar 10x)")
    print(f"  per-request ratio (fastest of the rounds)   median {statistics.median(per_request):6.1f}x   "
          f"p99 {_p99(per_request):6.1f}x")
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


if __name__ == "__main__":
    random.seed(7)  # the requests `make bench` draws (bench/run.py seeds the same)
    bench_profiles()
