"""Cut envelope (manual §10): envelope.py against the cut cycle of cutter.py."""

from __future__ import annotations

import math

import pytest

from axisline.devices.fs701.cutter import FS701Error
from axisline.devices.fs701.envelope import (
    cycle_budget,
    envelope,
    envelope_command,
    feasible,
    plot_envelope,
)

from .test_cutter import mm_settings, running_rig
from .test_cutter_rig import Tool

# The manual's §10 example gives no ramp numbers. Used here (LU = 1 mm): Acceleration 1 =
# Deceleration 1 = 5000 mm/s^2 (the §4.3.1 example), Acceleration 2 = Deceleration 2 = 8000,
# Rel. Return Speed 3.00, S-ramps, Synchron Time 1 ms (mm_settings of test_cutter.py).
V60 = 60000.0  # 60 m/min in LU/min


def test_manual_section_10_one_metre_at_60_m_min_with_a_1_s_cut_is_not_feasible():
    """§10: 1 m at 60 m/min is one cut per second; a blade needing 1 s cannot work."""
    s = mm_settings()
    ok, reason = feasible(s, 1000, V60, cut_time=1.0)
    assert not ok and "not feasible" in reason
    b = cycle_budget(s, V60, cut_time=1.0)
    assert b.t_sync == pytest.approx(1.001)
    assert b.t_acc == pytest.approx(0.2) and b.t_dec == pytest.approx(0.2)  # 1 m/s at 5 m/s^2
    assert b.t_cycle > 1.0  # "no time left to accelerate, decelerate and return to home"
    # even an infinitely fast carriage cannot: the cut alone takes the whole second
    fast = mm_settings(acceleration_1=99999, acceleration_2=99999, deceleration_1=99999, deceleration_2=99999,
                       abs_return_speed=9999999)
    assert not feasible(fast, 1000, V60, cut_time=1.0)[0]


def test_feasible_example_one_metre_at_60_m_min_with_a_0_1_s_cut():
    s = mm_settings()
    ok, reason = feasible(s, 1000, V60, cut_time=0.1)
    assert ok, reason
    b = cycle_budget(s, V60, cut_time=0.1)
    # travel: ramp 100 + sync 1000 x 0.101 + brake 100 mm
    assert b.travel == pytest.approx(100 + 101 + 100)
    (pt,) = envelope(s, [V60], cut_time=0.1)
    assert pt.min_length == pytest.approx(1000.0 * b.t_cycle)
    assert pt.travel == pytest.approx(b.travel)


def test_envelope_grows_with_speed_and_cut_time_and_names_a_factor():
    s = mm_settings()
    pts = envelope(s, [10000, 30000, 60000, 100000], cut_time=0.1)
    mins = [p.min_length for p in pts]
    assert mins == sorted(mins) and all(p.limiting_factor for p in pts)
    slow = envelope(s, [V60], cut_time=1.0)[0]
    assert slow.min_length > pts[2].min_length and slow.limiting_factor.startswith("synchronous")
    assert envelope(s, [0.0])[0].min_length == 0.0


def test_linear_and_s_ramps_have_the_same_forward_ramp_time():
    lin = cycle_budget(mm_settings(ramp_form=1), V60, 0.1)
    s_r = cycle_budget(mm_settings(ramp_form=0), V60, 0.1)
    assert lin.t_acc == pytest.approx(s_r.t_acc) and lin.travel == pytest.approx(s_r.travel)


def test_return_speed_limits_the_envelope():
    # linear ramps: with S-ramps the cutter derives the return jerk from the return speed, so a
    # short return at a higher speed limit can take longer (the envelope follows the cutter)
    fast = envelope(mm_settings(ramp_form=1, return_speed=3.0), [V60], 0.1)[0]
    slow = envelope(mm_settings(ramp_form=1, return_speed=1.0), [V60], 0.1)[0]
    absolute = envelope(mm_settings(ramp_form=1, return_speed=1.0, abs_return_speed=180000), [V60], 0.1)[0]
    assert slow.min_length > fast.min_length
    assert absolute.min_length == pytest.approx(fast.min_length)  # 180 m/min = 3 x 60 m/min


def test_sync_rate_speeds_up_the_carriage_and_lengthens_the_travel():
    base = cycle_budget(mm_settings(), V60, 0.1)
    plus = cycle_budget(mm_settings(sync_rate=5.0), V60, 0.1)
    assert plus.travel > base.travel


def test_travel_beyond_maximum_position_is_not_feasible():
    s = mm_settings(maximum_position=250)
    ok, reason = feasible(s, 5000, V60, cut_time=0.1)  # travel 301 mm > 250
    assert not ok and "Maximum Position" in reason
    pt = envelope(s, [V60], 0.1)[0]
    assert math.isinf(pt.min_length) and pt.limiting_factor.startswith("travel")
    assert feasible(mm_settings(maximum_position=400), 5000, V60, 0.1)[0]


def test_tool_width_counts_to_the_cycle():
    a = envelope(mm_settings(), [V60], 0.1)[0]
    b = envelope(mm_settings(tool_width=50), [V60], 0.1)[0]
    assert b.min_length == pytest.approx(a.min_length - 50)


# ---------------------------------------------------------------- consistency with the Cutter


def _run(length: float, cut_time: float, seconds: float = 6.0):
    s = mm_settings(cutting_length=int(round(length)))
    rig = running_rig(s, 1000.0, tool=Tool(blade_delay=0.02, cut_time=cut_time))
    rig.run(seconds)
    return rig


@pytest.mark.parametrize("cut_time", [0.1, 0.3])
def test_envelope_agrees_with_the_cutter_simulation(cut_time):
    """A length 5 % above the envelope's minimum cuts without Error 02, 5 % below gets it."""
    s = mm_settings()
    lmin = envelope(s, [V60], cut_time)[0].min_length
    ok_len, bad_len = lmin * 1.05, lmin * 0.95
    assert feasible(s, ok_len, V60, cut_time)[0] and not feasible(s, bad_len, V60, cut_time)[0]
    good = _run(ok_len, cut_time)
    assert good.cutter.errors == 0 and len(good.cutter.cut_log) >= 4
    bad = _run(bad_len, cut_time)
    assert bad.cutter.error_active(FS701Error.CUT_NOT_POSSIBLE)


def test_plot_envelope_writes_a_png(tmp_path):
    p = plot_envelope(mm_settings(), tmp_path / "env.png", lengths=[(V60, 1000.0), (V60, 500.0)], cut_time=0.1)
    assert p.exists() and p.stat().st_size > 1000


def test_envelope_command_prints_the_table(tmp_path, capsys):
    from axisline.devices.fs701.paramfile import save_parameters
    from axisline.devices.fs701.parameters import ParameterSet

    params = ParameterSet()
    f = tmp_path / "p.toml"
    save_parameters(f, params)
    png = tmp_path / "env.png"
    rc = envelope_command(f, png, 0.1, "10000,50000")
    out = capsys.readouterr().out
    assert rc == 0 and "limiting factor" in out and "50000" in out and png.exists()
    assert envelope_command(tmp_path / "missing.toml", None, None, None) != 0
    assert envelope_command(f, None, None, "a,b") == 2
