"""Cam switches: position windows, the WAGO camshaft (CAM1..CAM9), COMPAX aux functions.

Sources: wago.md §2.10 and §9.11 (camshaft table and its worked example, manual
§3.11.1.9), wago.md error table (1331 TBL_CAM9PARMS); compax.md §2.12 (auxiliary
functions, P37/P38/I15) and §7 X20 (cam memory example with aux bytes).
"""

from __future__ import annotations

import pytest

from axisline.motion.cam import PointTable, encode_fraction
from axisline.motion.camswitch import (
    AuxTrack,
    Cam9ParameterError,
    CamSwitchTrack,
    CamTable,
    CamWindow,
    PeriodicCam,
)

# ---------------------------------------------------------------------------------------
# windows


def test_window_is_on_from_the_on_position_up_to_but_not_including_the_off_position() -> None:
    track = CamSwitchTrack([CamWindow(100.0, 200.0)], period=360.0)
    assert [track.is_on(p) for p in (99.999, 100.0, 150.0, 199.999, 200.0)] == [False, True, True, True, False]
    # the next master cycles see the same window, forwards and backwards
    assert track.is_on(360.0 + 150.0) and track.is_on(-360.0 + 150.0)
    assert not track.is_on(360.0 + 250.0)


def test_window_wraps_across_the_end_of_the_modulo_period() -> None:
    # on 300, off 60: on from 300 to the period end and from 0 to 60
    track = CamSwitchTrack([(300.0, 60.0)], period=360.0)
    on = [p for p in range(-360, 720, 30) if track.is_on(float(p))]
    assert on == [-360, -330, -60, -30, 0, 30, 300, 330, 360, 390, 660, 690]
    assert track.is_on(359.999) and track.is_on(0.0) and not track.is_on(60.0)


def test_several_windows_on_one_track_switch_one_output() -> None:
    track = CamSwitchTrack([(10.0, 20.0), (50.0, 70.0)], period=100.0)
    assert [track.update(p) for p in (5.0, 15.0, 30.0, 60.0, 115.0)] == [False, True, False, True, True]
    assert track.output is True


def test_linear_track_without_period() -> None:
    track = CamSwitchTrack([(-5.0, 5.0)])
    assert track.is_on(-5.0) and track.is_on(4.9) and not track.is_on(5.0) and not track.is_on(365.0)
    with pytest.raises(ValueError, match="only a modulo track"):
        CamSwitchTrack([(300.0, 60.0)])  # a wrapping window needs a period


def test_window_for_one_direction_of_motion_only() -> None:
    # a glue gun that may only fire while the line runs forward
    track = CamSwitchTrack([CamWindow(100.0, 200.0, direction=+1)], period=360.0)
    assert track.is_on(150.0, velocity=10.0)
    assert not track.is_on(150.0, velocity=-10.0)
    assert not track.is_on(150.0, velocity=0.0)  # standing still: off
    back = CamSwitchTrack([CamWindow(100.0, 200.0, direction=-1)], period=360.0)
    assert back.is_on(150.0, velocity=-1.0) and not back.is_on(150.0, velocity=1.0)


def test_lead_time_switches_earlier_by_speed_times_dead_time() -> None:
    # 4 ms dead time at 1000 units/s: 4 units early, on both edges
    track = CamSwitchTrack([(100.0, 200.0)], period=360.0, lead_time=0.004)
    assert not track.is_on(95.9, 1000.0) and track.is_on(96.0, 1000.0)
    assert track.is_on(195.9, 1000.0) and not track.is_on(196.0, 1000.0)
    # moving backwards the window is entered at its off edge: again 4 units early
    assert not track.is_on(204.1, -1000.0) and track.is_on(203.9, -1000.0)
    assert track.is_on(104.1, -1000.0) and not track.is_on(103.9, -1000.0)


def test_separate_off_lead_time() -> None:
    # valve opens in 10 ms, closes in 2 ms
    track = CamSwitchTrack([(100.0, 200.0)], period=360.0, lead_time=0.010, off_lead_time=0.002)
    assert not track.is_on(89.9, 1000.0) and track.is_on(90.1, 1000.0)
    assert track.is_on(197.9, 1000.0) and not track.is_on(198.1, 1000.0)
    assert not track.is_on(210.1, -1000.0) and track.is_on(209.9, -1000.0)
    assert track.is_on(102.1, -1000.0) and not track.is_on(101.9, -1000.0)


def test_lead_time_across_the_period_end() -> None:
    # window 350 -> 20 wraps; 10 units of lead make it switch at 340 and 10
    track = CamSwitchTrack([(350.0, 20.0)], period=360.0, lead_time=0.01)
    v = 1000.0
    on = [p for p in range(300, 400, 5) if track.is_on(float(p), v)]
    assert on == [340, 345, 350, 355, 360, 365]
    assert [p for p in range(-50, 50, 5) if track.is_on(float(p), v)] == [-20, -15, -10, -5, 0, 5]


def test_actuator_with_dead_time_acts_exactly_over_the_window() -> None:
    # Simulate 1 ms cycles: the track's output reaches the valve dead_time later. With lead
    # compensation the valve is open exactly while the material is inside the window.
    dead_cycles, cycle = 7, 0.001
    v = 250.0  # units/s, 0.25 units per cycle
    track = CamSwitchTrack([(10.0, 30.0), (80.0, 5.0)], period=100.0, lead_time=dead_cycles * cycle)
    window = CamSwitchTrack([(10.0, 30.0), (80.0, 5.0)], period=100.0)
    commands: list[bool] = []
    for n in range(2000):
        position = 0.1 + v * cycle * n  # offset so no sample lands on an edge
        commands.append(track.update(position, v))
        if n >= dead_cycles:
            valve = commands[n - dead_cycles]
            assert valve == window.is_on(position)


@pytest.mark.parametrize(
    ("windows", "kwargs", "expected"),
    [
        ([(10.0, 10.0)], {"period": 360.0}, "ambiguous"),
        ([(400.0, 10.0)], {"period": 360.0}, "on_position"),
        ([(10.0, 20.0, 2)], {"period": 360.0}, "direction"),
        ([(10.0, 20.0)], {"period": 0.0}, "period"),
        ([(10.0, 20.0)], {"lead_time": float("nan")}, "lead_time"),
    ],
)
def test_bad_windows_are_rejected(windows, kwargs, expected: str) -> None:
    with pytest.raises(ValueError, match=expected):
        CamSwitchTrack(windows, **kwargs)


def test_whole_cycle_window() -> None:
    track = CamSwitchTrack([(0.0, 360.0)], period=360.0)
    assert all(track.is_on(float(p), v) for p in range(-720, 720, 45) for v in (-5.0, 0.0, 5.0))


# ---------------------------------------------------------------------------------------
# WAGO camshaft CAM1..CAM8: the worked example of wago.md §9.11 (manual §3.11.1.9)

# (MB5, MB4, MB3, MB2) = position bytes MSB..LSB and the bit sample, exactly as in the table
WAGO_EXAMPLE_ROWS = [
    (0x00, 0x2E, 0xE0, 0x84),
    (0x00, 0x5D, 0xC0, 0x44),
    (0x00, 0xBB, 0x80, 0x22),
    (0x01, 0x77, 0x00, 0x12),
    (0x01, 0xD4, 0xC0, 0x08),
    (0x02, 0x90, 0x40, 0x44),
    (0x07, 0xB0, 0xC0, 0x42),
    (0x07, 0xDF, 0xA0, 0x41),
]


def _wago_example_table() -> CamTable:
    entries = [((b4 << 16) | (b3 << 8) | b2, sample) for b4, b3, b2, sample in WAGO_EXAMPLE_ROWS]
    return CamTable(entries)


def test_wago_worked_example_positions_and_samples() -> None:
    table = _wago_example_table()
    assert table.positions == (12000, 24000, 48000, 96000, 120000, 168000, 504000, 516000)
    # wago.md §9.11 "Resulting CAM outputs": each sample holds up to the next entry
    expected = [
        (0, 0x84),  # below the first entry: the first entry's pattern
        (11999, 0x84),
        (12000, 0x84),
        (24000, 0x44),
        (47999, 0x44),
        (48000, 0x22),
        (95999, 0x22),
        (96000, 0x12),
        (119999, 0x12),
        (120000, 0x08),
        (168000, 0x44),
        (503999, 0x44),
        (504000, 0x42),
        (515999, 0x42),
        (516000, 0x41),
        (10_000_000, 0x41),
        (-5000, 0x84),
    ]
    assert [(p, table.sample_at(p)) for p, _ in expected] == expected


def test_wago_worked_example_position_100000_sets_cam5_and_cam2() -> None:
    # wago.md §9.11: "pos 100000 -> CAM5 = 1, CAM2 = 1, others 0"
    table = _wago_example_table()
    assert [n for n in range(1, 9) if table.cam(n, 100000)] == [2, 5]
    assert table.update(100000) == 0x12 and table.sample == 0x12


def test_camshaft_table_rules() -> None:
    # entries must ascend (the module rejects the download otherwise), at most 50
    with pytest.raises(ValueError, match=r"entry 2: position 100 .*strictly ascending"):
        CamTable([(200, 1), (100, 2)])
    with pytest.raises(ValueError, match="at most 50 entries"):
        CamTable([(k, 1) for k in range(51)])
    assert len(CamTable([(k, 1) for k in range(50)])) == 50
    with pytest.raises(ValueError, match="bit sample 256"):
        CamTable([(0, 256)])
    # unused entries of a downloaded table carry the invalid position 0x80000000
    table = CamTable.from_device([(10, 0x01), (20, 0x02), (0x80000000, 0), (-0x80000000, 0)])
    assert table.positions == (10, 20)
    assert CamTable([]).sample_at(5) == 0


# ---------------------------------------------------------------------------------------
# WAGO CAM9


def test_cam9_with_the_default_parameters() -> None:
    # defaults Start 0, Period 100, Pulsewidth 50 (wago.md register table 88/92/96)
    cam9 = PeriodicCam()
    assert [cam9.is_on(p) for p in (0, 49, 50, 99, 100, 149, 150)] == [True, True, False, False, True, True, False]


def test_cam9_continues_below_the_start_and_at_negative_positions() -> None:
    cam9 = PeriodicCam(start=25, period=100, pulse_width=30)
    assert cam9.is_on(25) and cam9.is_on(54) and not cam9.is_on(55) and not cam9.is_on(24)
    # floored modulo: -75 is one period below 25 -> on; -46 -> offset 29 -> on; -45 -> off
    assert cam9.is_on(-75) and cam9.is_on(-46) and not cam9.is_on(-45) and not cam9.is_on(-76)
    assert cam9.update(-75) is True and cam9.output is True


def test_cam9_period_zero_is_wago_error_1331() -> None:
    with pytest.raises(ValueError, match="1331 TBL_CAM9PARMS") as excinfo:
        PeriodicCam(start=0, period=0, pulse_width=10)
    assert isinstance(excinfo.value, Cam9ParameterError) and excinfo.value.code == 1331


# ---------------------------------------------------------------------------------------
# COMPAX digital auxiliary functions (compax.md §2.12, §7 X20)

X20_SET_POINTS = (0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 0.9999999)
X20_AUX_DIGITAL = (1, 3, 7, 15, 31, 63, 127, 255, 254, 252, 248)  # B0007 ... B0027, first byte


def _x20_curve() -> PointTable:
    return PointTable.from_fractions([encode_fraction(v) for v in X20_SET_POINTS], 360.0, 360.0)


def test_aux_bits_of_the_last_set_point_passed() -> None:
    curve = _x20_curve()
    aux = AuxTrack.from_compax(X20_AUX_DIGITAL, p37=0, p38=16320)  # P38 = 16320: O7..O14 enabled
    # X20: "at m = 180 slave = 180, O-byte 63 (O7…O12 = 1) ⇒ with P38=16320, I15=1:
    # O7–O12 on, O13/O14 off"
    assert aux.outputs_at(curve, 180.0, previous=0, enabled=True) == 0b0011_1111
    assert aux.outputs_at(curve, 179.9, previous=0) == 31  # still set point 4
    assert aux.outputs_at(curve, 0.0, previous=0) == 1
    assert aux.outputs_at(curve, 360.0, previous=0) == 248  # the last set point at the cycle end


def test_aux_mask_keeps_other_outputs_and_i15_low_gives_the_reset_value() -> None:
    # P38 = O7 + O8 (64 + 128): only those two follow the curve; the rest keep what OUTPUT set
    aux = AuxTrack.from_compax(X20_AUX_DIGITAL, p37=128, p38=64 + 128)
    previous = 0b1010_0000
    assert aux.outputs(point=7, previous=previous, enabled=True) == 0b1010_0011  # 255 -> O7, O8 on
    assert aux.outputs(point=8, previous=previous, enabled=True) == 0b1010_0010  # 254 -> O7 off
    # I15 = 0: the masked outputs take the P37 reset value (O8 = 128 -> bit 1)
    assert aux.outputs(point=7, previous=previous, enabled=False) == 0b1010_0010


def test_aux_track_checks_its_inputs() -> None:
    with pytest.raises(ValueError, match="P38 1"):
        AuxTrack.from_compax(X20_AUX_DIGITAL, p37=0, p38=1)  # 2^0 is not an aux output valence
    with pytest.raises(ValueError, match="one aux byte per set point"):
        AuxTrack([1, 2, 3]).outputs_at(_x20_curve(), 10.0, previous=0)
