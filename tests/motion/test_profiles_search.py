"""The UDDU search (motion.uddu): the scans it skips hold no root (Decisions 1 there)."""

import random

import pytest

from axisline.motion.uddu import BASE, Ramp, solve_up


def _requests(seed: int, n: int, base: str):
    """Up-frame requests inside the limits (as plan() hands them to solve_up after braking):
    moving starts, target velocities of both signs, a != d in a third of them."""
    rnd = random.Random(seed)
    out = []
    while len(out) < n:
        vmax, amax, j = rnd.uniform(0.1, 5.0), rnd.uniform(0.1, 10.0), rnd.uniform(0.5, 100.0)
        dmax = amax if rnd.random() < 0.66 else rnd.uniform(0.1, 10.0)
        v0 = rnd.uniform(-vmax, vmax)
        # plan() brakes |a| into both limits first, and a sin² plan ramps it to 0 first
        alim = min(amax, dmax) if base == "jerk" else 0.0
        a0 = rnd.uniform(-alim, alim) * rnd.choice([0.0, 1.0])
        if abs(v0 + a0 * abs(a0) / (2 * j)) > vmax:
            continue
        vf = rnd.choice([0.0, rnd.uniform(-vmax, vmax)])
        dist = rnd.choice([rnd.uniform(-5.0, 5.0), rnd.uniform(-0.01, 0.01)])
        out.append((Ramp(base, j), v0, a0, dist, vf, vmax, amax, dmax))
    return out


def _fields(cands):
    return [(c.a1, c.t2, c.t4, c.a2, c.t6, c.duration) for c in cands]


@pytest.mark.parametrize("base", list(BASE))
def test_pruned_scans_find_exactly_the_candidates_of_the_full_grid(base):
    """Skipping grid intervals changes no candidate: same roots, same brackets, same bits."""
    with_roots = {"vf >= 0": 0, "vf < 0": 0}
    for req in _requests(18, 600, base):
        pruned, full = solve_up(*req), solve_up(*req, prune=False)
        assert _fields(pruned) == _fields(full), req
        if any(c.t4 == 0.0 for c in full):  # a root of the scans (not the cruise)
            with_roots["vf >= 0" if req[4] >= 0.0 else "vf < 0"] += 1
    # both kinds of scan had roots to find (the comparison is not about empty scans only)
    assert with_roots["vf >= 0"] > 20 and with_roots["vf < 0"] > 20, with_roots


@pytest.mark.parametrize("base", list(BASE))
def test_end_position_and_duration_rise_along_every_scan(base):
    """The premise of the pruning: along a scan, the duration T and the end position carried
    on at vf to a common time, M = error - vf * T, never fall (so the error rises where
    vf >= 0, and lies between M_lo + vf T_hi and M_hi + vf T_lo where vf < 0)."""
    from axisline.motion.uddu import UpSolver

    checked = 0
    for r, v0, a0, dist, vf, vmax, amax, dmax in _requests(19, 150, base):
        sol = UpSolver(r, v0, a0, dist, vf, vmax, amax, dmax)
        tol = 1e-9 * max(1.0, abs(dist), abs(v0), abs(vf), vmax)
        for vary_t2 in (False, True):
            exists, lo, hi, edge = sol.bounds(vary_t2)
            if not (exists and hi > lo):
                continue
            sol.vary_t2 = vary_t2
            points = [sol.end(lo + (hi - lo) * i / 40, edge and i == 0) for i in range(41)]
            feasible = [(f - vf * t, t) for f, t in points if f == f]
            for (m0, t0), (m1, t1) in zip(feasible, feasible[1:]):
                assert m1 >= m0 - tol and t1 >= t0 - tol * 1e-3, (base, vary_t2, v0, a0, dist, vf)
            checked += len(feasible) > 1
    assert checked > 100


@pytest.mark.parametrize("base", list(BASE))
def test_the_search_walk_reaches_the_state_the_written_segments_reach(base):
    """walk_end (the search's inner loop) and integrate (which writes the winner's segments)
    give the same end state and duration, bit for bit: a root found by the search is the
    profile that is written."""
    from axisline.motion.uddu import integrate, walk_end

    rnd = random.Random(20)
    for _ in range(2000):
        r = Ramp(base, rnd.uniform(0.5, 100.0))
        a1 = rnd.uniform(-5.0, 5.0)
        a2 = rnd.choice([rnd.uniform(-5.0, 0.0), a1 - rnd.uniform(0.0, 3.0)])
        t2, t6 = rnd.choice([0.0, rnd.uniform(0.0, 2.0)]), rnd.choice([0.0, rnd.uniform(0.0, 2.0)])
        args = (rnd.uniform(-3.0, 3.0), rnd.uniform(-5.0, 5.0), a1, t2)
        assert walk_end(r, *args, a2, t6) == integrate(r, *args, 0.0, a2, t6)
