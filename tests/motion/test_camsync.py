"""Cam coupling on the fly (compax.md §2.11): continuity, synchronism, standstill positions."""

import math

import numpy as np
import pytest

from axisline.motion.axis import Axis, AxisConfig, AxisState
from axisline.motion.camsync import CamFollower, CamState, smooth_step
from axisline.motion.curve import CamCurve

T = 0.001


class SineCam(CamCurve):
    """s = feed * x / P + amp * sin(2 pi x / P): closed for feed = 0, open otherwise."""

    def __init__(self, period=360.0, amp=20.0, feed=0.0):
        self.master_period, self.amp, self.feed = period, amp, feed

    def eval(self, x):
        w = 2 * math.pi / self.master_period
        return (
            self.feed * x / self.master_period + self.amp * math.sin(w * x),
            self.feed / self.master_period + self.amp * w * math.cos(w * x),
            -self.amp * w * w * math.sin(w * x),
            -self.amp * w**3 * math.cos(w * x),
        )


class Master:
    """A master moving with a given speed profile v(t) (exact integration per cycle)."""

    def __init__(self, v0=360.0, accel=0.0, x0=0.0):
        self.position, self.velocity, self.acceleration = x0, v0, accel

    def step(self):
        self.position += self.velocity * T + 0.5 * self.acceleration * T * T
        self.velocity += self.acceleration * T


def run(follower, master, cycles):
    out = []
    for c in range(cycles):
        master.step()
        out.append((master.position, *follower.sample(c), follower.state))
    return out


def assert_continuous(trace, v_bound, a_bound):
    """No step in position or velocity: every cycle's change is what its velocity and
    acceleration explain (trapezoid rule), and the speeds stay bounded."""
    p = np.array([r[1] for r in trace])
    v = np.array([r[2] for r in trace])
    a = np.array([r[3] for r in trace])
    assert np.max(np.abs(v)) <= v_bound and np.max(np.abs(a)) <= a_bound
    dp = np.diff(p) - (v[1:] + v[:-1]) / 2 * T
    dv = np.diff(v) - (a[1:] + a[:-1]) / 2 * T
    assert np.max(np.abs(dp)) <= 1e-3 * v_bound * T, np.argmax(np.abs(dp))
    assert np.max(np.abs(dv)) <= 1e-2 * a_bound * T, np.argmax(np.abs(dv))


def test_smooth_step_boundary_conditions():
    assert smooth_step(0.0) == (0.0, 0.0, 0.0) and smooth_step(1.0) == (1.0, 0.0, 0.0)
    h, dh, ddh = smooth_step(0.5)
    assert (h, dh) == pytest.approx((0.5, 1.875))
    eps = 1e-6
    for u in (0.1, 0.37, 0.8):
        assert smooth_step(u)[1] == pytest.approx((smooth_step(u + eps)[0] - smooth_step(u - eps)[0]) / (2 * eps), rel=1e-6)


def test_synchronous_follower_is_the_curve_in_time():
    cam, m = SineCam(), Master(v0=720.0, accel=100.0)
    f = CamFollower(m, cam)
    m.step()
    p, v, a = f.sample(0)
    s, ds, dds, _ = cam.eval(m.position)
    assert (p, v, a) == pytest.approx((s, ds * m.velocity, dds * m.velocity**2 + ds * m.acceleration))


def test_coupling_waits_for_me_and_is_on_the_curve_at_ms():
    cam, m = SineCam(), Master(v0=360.0, x0=10.0)
    f = CamFollower(m, cam)
    f.couple(slave_position=-5.0, coupling=90.0, synchronous=180.0)
    trace = run(f, m, 700)
    before = [r for r in trace if r[0] < 90.0]
    assert all(r[1] == -5.0 and r[2] == 0.0 for r in before)  # at rest until M_E
    after = [r for r in trace if r[0] >= 180.0]
    assert all(r[4] is CamState.SYNCHRONOUS for r in after)
    for x, p, v, a, _ in after:
        s, ds, _, _ = cam.eval(x % 360.0)
        assert p == pytest.approx(s, abs=1e-9) and v == pytest.approx(ds * 360.0, abs=1e-9)
    assert_continuous(trace, v_bound=200.0, a_bound=3000.0)


def test_coupling_with_ms_in_the_next_cycle_and_a_slowing_master():
    cam, m = SineCam(feed=100.0), Master(v0=400.0, accel=-150.0, x0=300.0)
    f = CamFollower(m, cam)
    f.couple(slave_position=0.0, coupling=350.0, synchronous=40.0)  # 50 master units across the wrap
    trace = run(f, m, 900)
    sync = [r for r in trace if r[4] is CamState.SYNCHRONOUS]
    assert sync and sync[0][0] >= 400.0 - 1.0  # synchronous from 360 + 40
    assert_continuous(trace, v_bound=2500.0, a_bound=200000.0)


def test_adjusting_the_curve_to_a_standing_slave_does_not_move_it():
    cam, m = SineCam(), Master(v0=0.0, x0=45.0)
    f = CamFollower(m, cam)
    f.couple(slave_position=3.0)
    assert f.sample(0)[0] == pytest.approx(3.0) and f.synchronous


def test_decoupling_stops_at_s0_at_mb_without_steps():
    cam, m = SineCam(feed=100.0), Master(v0=360.0)
    f = CamFollower(m, cam)
    trace = run(f, m, 200)
    f.decouple(decoupling=270.0, braking=330.0, standstill=50.0)
    trace += run(f, m, 1000)
    assert f.state is CamState.DECOUPLED
    stop = [r for r in trace if r[4] is CamState.DECOUPLED]
    assert stop[0][0] >= 330.0 and all(r[1] == pytest.approx(50.0) and r[2] == 0.0 for r in stop)
    assert_continuous(trace, v_bound=400.0, a_bound=6000.0)


def test_open_curve_stops_at_s0_of_the_cycle_it_stops_in():
    cam, m = SineCam(feed=100.0), Master(v0=360.0, x0=400.0)  # second master cycle
    f = CamFollower(m, cam)
    f.decouple(decoupling=90.0, braking=180.0, standstill=10.0)
    run(f, m, 1000)
    assert f.p == pytest.approx(110.0)  # 10 + one cycle's feed


def test_bad_positions_are_named():
    f = CamFollower(Master(), SineCam())
    with pytest.raises(ValueError, match="coupling position"):
        f.couple(0.0, coupling=400.0, synchronous=10.0)
    with pytest.raises(ValueError, match="both"):
        f.couple(0.0, coupling=10.0)
    with pytest.raises(ValueError, match="differ"):
        f.decouple(10.0, 10.0, 0.0)


def test_an_axis_follows_the_cam_through_coupling():
    cfg = AxisConfig(name="s", unit="mm", counts_per_unit=1000.0, v_max=500.0, a_max=50000.0, following_error_limit=1.0)
    ax = Axis(cfg, T)
    ax.power(True)
    ax.update_setpoint(0)
    ax.position_loop(0.0)
    cam, m = SineCam(), Master(v0=360.0)
    f = CamFollower(m, cam)
    f.couple(slave_position=0.0, coupling=30.0, synchronous=120.0)
    cmd = ax.start_sync(f)
    ps = []
    for c in range(1, 800):
        m.step()
        ax.update_setpoint(c)
        ax.position_loop(ax.command_position)
        ps.append(ax.command_position)
    assert ax.state is AxisState.SYNCHRONIZED_MOTION and not cmd.error
    assert ps[-1] == pytest.approx(cam.eval(m.position % 360.0)[0], abs=1e-9)
    assert np.max(np.abs(np.diff(ps))) <= 250.0 * T  # no jump: bounded by a speed


def test_rotary_knife_decouples_forward_to_the_nearest_standstill_position():
    # open curve: one turn (360) per master cycle; stopping "at 0" means the next multiple of 360
    cam, m = SineCam(amp=0.0, feed=360.0), Master(v0=360.0, x0=1000.0)
    f = CamFollower(m, cam)
    f.decouple(decoupling=250.0, braking=340.0, standstill=0.0)
    trace = run(f, m, 1500)
    # master at 1000 is past M_A = 250 of its cycle: decoupling starts at 1330, ends at 1420,
    # where the curve stands at 1420: the nearest standstill 0 (mod 360) is 1440, not 1080
    assert f.state is CamState.DECOUPLED and f.p == pytest.approx(1440.0)
    assert min(r[2] for r in trace) >= -1e-9  # never backwards
