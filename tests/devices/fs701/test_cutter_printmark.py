"""FS701 print mark operation: Cutting Mode 2 and 3 (printmark.py, decisions P1..P10; spec §2.9..§2.12,
E10, E11).

Geometry of the rig: the carriage home (the tool) is the origin of the line; the print mark
sensor sits Photocell -> Cut upstream of it (sensor_position = -P2C); a mark at material
coordinate m passes the tool when the material position is m, so a cut to it has
`material_point` m (CutRecord), and pieces are the differences.
"""

from __future__ import annotations

import math

import pytest

from axisline.devices.fs701.cutter import CutKind, CutState, CutterSettings, FS701Error
from axisline.devices.fs701.printmark import OFFSET_SIGN, PrintMarkControl
from axisline.plant import PrintMarks

from .test_cutter_rig import CutterRig, Tool


def pm_settings(**kw) -> CutterSettings:
    base = dict(
        cutting_mode=2,
        cutting_length=1500,  # the sheet (one mark per sheet)
        photocell_cut=3000,
        pulses_line_1000=4000,
        pulses_cut_1000=4000,
        acceleration_1=20000,
        deceleration_1=20000,
        acceleration_2=20000,
        deceleration_2=20000,
        max_line_speed=100000,
        p_gain=3000,
        cut_window=8,
        home_window=5,
        return_speed=3.0,
    )
    base.update(kw)
    return CutterSettings(**base)


def pm_rig(s: CutterSettings, marks: PrintMarks, speed: float = 1000.0, **kw) -> CutterRig:
    rig = CutterRig(s, line_speed=speed, marks=marks, sensor_position=-float(s.photocell_cut), **kw)
    rig.enable()
    rig.start()
    return rig


def cut_points(rig: CutterRig) -> list[float]:
    """Material point each cut was scheduled for: the point cut, less the carriage's position
    error at the cut (that is bounded by the Cut Window and checked below)."""
    kc = rig.s.cut_counts_per_lu
    for r in rig.recorder.records:
        assert abs(r.following_error) <= rig.s.cut_window + 1
    return [r.material_point - r.following_error / kc for r in rig.recorder.records]


def nearest_offsets(points: list[float], marks: list[float]) -> list[float]:
    return [min((p - m for m in marks), key=abs) for p in points]


def test_cuts_land_on_the_print_marks():
    s = pm_settings()
    marks = PrintMarks(width=10.0, pitch=1500.0, first=500.0, count=20)
    rig = pm_rig(s, marks)
    rig.run(9.0)
    pts = cut_points(rig)
    assert len(pts) >= 3 and rig.cutter.errors == 0
    offs = nearest_offsets(pts, [500.0 + 1500.0 * k for k in range(20)])
    assert all(abs(o) <= 0.5 for o in offs), offs
    assert all(r.kind == "PRINTMARK" for r in rig.recorder.records)
    pieces = [r for r in rig.recorder.records if not math.isnan(r.actual_length)]
    assert all(abs(p.actual_length - 1500.0) <= 0.5 for p in pieces)
    assert all(p.target_length == pytest.approx(1500.0, abs=0.3) for p in pieces)


def test_marks_with_varying_pitch_are_followed_exactly():
    s = pm_settings(cutting_length=1500)
    positions = [400.0, 1850.0, 3420.0, 4900.0, 6460.0, 7900.0]
    rig = pm_rig(s, PrintMarks(width=10.0, positions=positions))
    rig.run(9.0)
    pts = cut_points(rig)
    assert len(pts) >= 4
    assert all(abs(o) <= 0.5 for o in nearest_offsets(pts, positions))


@pytest.mark.parametrize("sign", [1, -1])
def test_printmark_offset_moves_the_cut_forward_p1(sign):
    """P1: a positive offset moves the cut forward (downstream: smaller material coordinate)."""
    s = pm_settings(printmark_offset=40)
    marks = PrintMarks(width=10.0, pitch=1500.0, first=500.0, count=20)
    rig = CutterRig(s, line_speed=1000.0, marks=marks, sensor_position=-3000.0)
    rig.cutter.printmarks.offset_sign = sign
    rig.enable()
    rig.start()
    rig.run(7.0)
    offs = nearest_offsets(cut_points(rig), [500.0 + 1500.0 * k for k in range(20)])
    assert len(offs) >= 3 and all(o == pytest.approx(-40.0 * sign, abs=0.5) for o in offs)
    assert OFFSET_SIGN == 1 and PrintMarkControl(rig.cutter).offset_sign == 1  # the default reading


def test_printmark_edge_selects_the_falling_edge():
    s = pm_settings(printmark_edge=1)
    marks = PrintMarks(width=10.0, pitch=1500.0, first=500.0, count=20)
    rig = pm_rig(s, marks)
    rig.run(7.0)
    offs = nearest_offsets(cut_points(rig), [510.0 + 1500.0 * k for k in range(20)])
    assert len(offs) >= 3 and all(abs(o) <= 0.5 for o in offs)  # the trailing edge, 10 LU later


def test_photocell_delay_is_compensated():
    marks = PrintMarks(width=10.0, pitch=1500.0, first=500.0, count=20)
    late = pm_rig(pm_settings(), marks, sensor_delay=0.005)
    late.run(7.0)
    offs = nearest_offsets(cut_points(late), [500.0 + 1500.0 * k for k in range(20)])
    assert all(o == pytest.approx(5.0, abs=0.5) for o in offs)  # 5 ms at 1000 LU/s, uncompensated
    marks = PrintMarks(width=10.0, pitch=1500.0, first=500.0, count=20)
    comp = pm_rig(pm_settings(photocell_delay=5.0), marks, sensor_delay=0.005)
    comp.run(7.0)
    offs = nearest_offsets(cut_points(comp), [500.0 + 1500.0 * k for k in range(20)])
    assert len(offs) >= 3 and all(abs(o) <= 0.5 for o in offs)
    assert comp.cutter.process_values()[17] == pytest.approx(5.0 * 4, abs=0.5)  # #17 in increments


def test_printmarks_per_length_cuts_every_nth_mark_p4():
    s = pm_settings(cutting_length=1500, printm_per_length=3)
    marks = PrintMarks(width=10.0, pitch=500.0, first=300.0, count=60)
    rig = pm_rig(s, marks)
    rig.run(9.0)
    pts = cut_points(rig)
    assert len(pts) >= 3
    assert all(abs(o) <= 0.5 for o in nearest_offsets(pts, [300.0 + 500.0 * k for k in range(60)]))
    diffs = [b - a for a, b in zip(pts, pts[1:])]
    assert all(d == pytest.approx(1500.0, abs=0.5) for d in diffs)


def test_window_with_teach_ignores_the_other_marks_p2():
    """Valid marks every 1500, a decorative mark 700 after each: teach picks the valid one."""
    valid = [1000.0 + 1500.0 * k for k in range(12)]
    decor = [v + 700.0 for v in valid]
    marks = PrintMarks(width=10.0, positions=sorted(valid + decor))
    s = pm_settings(printmark_window=200)
    rig = CutterRig(s, line_speed=1000.0, marks=marks, sensor_position=-3000.0)
    rig.enable()
    c = rig.cutter
    # Teach HIGH shortly before the valid mark at 1000 reaches the sensor (material 1000 - 3000 + ...)
    rig.run(3.95)  # material 3950: valid mark 1000 at the sensor at 4000 (sensor at -3000)
    c.inputs.teach_printmark = True
    rig.run(0.1)
    c.inputs.teach_printmark = False
    assert c.outputs.printm_teached
    rig.start()
    rig.run(9.0)
    pts = cut_points(rig)
    assert len(pts) >= 4 and c.errors == 0
    assert all(abs(o) <= 0.5 for o in nearest_offsets(pts, valid))
    assert c.printmarks.marks_ignored >= 4


def test_teach_at_standstill_takes_the_position_at_the_falling_edge_p2():
    s = pm_settings(printmark_window=100)
    marks = PrintMarks(width=10.0, pitch=1500.0, first=500.0, count=20)
    rig = CutterRig(s, line_speed=0.0, marks=marks, sensor_position=-3000.0)
    rig.enable()
    c = rig.cutter
    c.inputs.teach_printmark = True
    rig.run(0.05)
    c.inputs.teach_printmark = False
    rig.run(0.01)
    assert c.outputs.printm_teached
    w = c.printmarks.window
    assert w is not None and w.expected == pytest.approx(c.master.position)
    assert c.outputs.printmark_window  # the line stands in the middle of the taught window


def test_missing_mark_gives_a_substitute_cut_and_the_alarm_p3():
    positions = [500.0 + 1500.0 * k for k in range(12)]
    del positions[4]  # mark 6500 is missing
    marks = PrintMarks(width=10.0, positions=positions)
    s = pm_settings(printmark_window=200, missing_printmarks=1)
    rig = pm_rig(s, marks)
    c = rig.cutter
    seen_no_mark = seen_virtual = False
    for _ in range(14000):
        rig.step()
        seen_no_mark |= c.outputs.no_printmark
        seen_virtual |= c.outputs.virt_printmark
    pts = cut_points(rig)
    expected = [500.0 + 1500.0 * k for k in range(12)]
    assert all(abs(o) <= 0.5 for o in nearest_offsets(pts, expected))
    assert any(abs(p - 6500.0) <= 0.5 for p in pts)  # the substitute: one pitch after 5000
    kinds = [r.kind for r in rig.recorder.records]
    assert "VIRTUAL" in kinds and seen_no_mark and seen_virtual
    assert not c.outputs.no_printmark  # cleared by the next good mark
    assert c.errors == 0


def test_missing_mark_monitoring_is_off_without_a_window():
    positions = [500.0 + 1500.0 * k for k in range(8)]
    del positions[3]
    rig = pm_rig(pm_settings(missing_printmarks=1), PrintMarks(width=10.0, positions=positions))
    rig.run(10.0)
    pts = cut_points(rig)
    assert not any(abs(p - 5000.0) <= 1.0 for p in pts) and not rig.cutter.outputs.no_printmark
    assert rig.cutter.outputs.printmark_window  # always HIGH with the window off


def test_virtual_printmarks_at_start_p6():
    """P6: with Virt. Printmarks = 1 the stretch between sensor and tool is cut at once."""
    marks = PrintMarks(width=10.0, pitch=1000.0, first=4200.0, count=20)  # first real mark far away
    s = pm_settings(cutting_length=1000, photocell_cut=3000, virt_printmarks=1)
    rig = pm_rig(s, marks)
    c = rig.cutter
    rig.run(0.001)  # the Start edge: 3 virtual marks, the first already at the tool (dropped)
    assert len(c.printmarks.queue) == 2 and c.process_values()[21] == 2
    rig.run(6.0)
    kinds = [r.kind for r in rig.recorder.records]
    assert kinds[:2] == ["VIRTUAL", "VIRTUAL"] and "PRINTMARK" in kinds  # the first one was too close
    assert c.errors == 0
    no_virtual = pm_rig(pm_settings(cutting_length=1000), PrintMarks(width=10.0, pitch=1000.0, first=4200.0, count=20))
    no_virtual.run(0.001)
    assert len(no_virtual.cutter.printmarks.queue) == 0


def test_e10_fifo_capacity_64_32_21_16():
    """E10 (§4.3.5): the 65th / 33rd / 22nd / 17th mark between sensor and carriage is Error 04."""
    for n_add, capacity in ((0, 64), (1, 32), (2, 21), (3, 16)):
        s = pm_settings(
            cutting_mode=3 if n_add else 2,
            additional_cuts=n_add,
            add_cut_1_length=10,
            add_cut_2_length=10,
            add_cut_3_length=10,
            cutting_length=100,
            photocell_cut=900000,
        )
        marks = PrintMarks(width=5.0, pitch=100.0, first=900010.0, count=80)
        rig = CutterRig(s, line_speed=10000.0, marks=marks, sensor_position=-900000.0)
        rig.enable()
        rig.start()
        c = rig.cutter
        ok = rig.run_until(lambda r: r.cutter.errors != 0, 1.0)
        assert ok and c.error_active(FS701Error.PRINTMARK_BUFFER)
        assert c.printmarks.marks_counted == capacity + 1
        assert len(c.printmarks.queue) == capacity * (n_add + 1)


@pytest.mark.parametrize(
    "n_add, lengths, width, expect",
    [
        (1, (1000, 2000, 3000), 0, [4000.0, 1000.0]),  # E11 screenshot settings
        (1, (1000, 2000, 3000), 10, [3980.0, 1000.0]),  # E11 with Tool Width 10
        (3, (1000, 500, 300), 0, [3200.0, 300.0, 500.0, 1000.0]),  # tail, L3, L2, L1 (P7)
    ],
)
def test_e11_additional_cut_geometry_p7(n_add, lengths, width, expect):
    s = pm_settings(
        cutting_mode=3,
        additional_cuts=n_add,
        add_cut_1_length=lengths[0],
        add_cut_2_length=lengths[1],
        add_cut_3_length=lengths[2],
        tool_width=width,
        cutting_length=5000,
        photocell_cut=2000,
        acceleration_1=50000,
        deceleration_1=50000,
        acceleration_2=50000,
        deceleration_2=50000,
    )
    marks = PrintMarks(width=10.0, pitch=5000.0, first=2500.0, count=10)
    rig = pm_rig(s, marks, tool=Tool(blade_delay=0.01, cut_time=0.03, pulse=0.01))
    rig.run(13.0)
    c = rig.cutter
    assert c.errors == 0
    pieces = [r for r in rig.recorder.records if not math.isnan(r.actual_length)]
    got = [round(p.actual_length) for p in pieces]
    period = len(expect)
    assert len(got) >= period + 1
    # from the first full period on, the pieces repeat: tail, ..., L1 ending at the mark
    start = next(i for i, r in enumerate(rig.recorder.records) if abs(r.material_point - 7500.0) < 3.0)
    seq = [round(r.actual_length) for r in rig.recorder.records[start + 1 : start + 1 + period]]
    assert seq == [round(e) for e in expect]
    assert all(abs(p.error_lu) <= 0.5 for p in pieces)
    kinds = [r.kind for r in rig.recorder.records[start + 1 : start + 1 + period]]
    assert kinds == ["ADDITIONAL"] * n_add + ["PRINTMARK"]


def test_mark_too_close_to_the_tool_is_error_02_p9():
    """Photocell -> Cut shorter than the anticipation: the cut cannot be made (Error 02)."""
    s = pm_settings(photocell_cut=20, acceleration_1=5000)  # anticipation at 1000 LU/s: 100
    marks = PrintMarks(width=10.0, pitch=1500.0, first=500.0, count=10)
    rig = pm_rig(s, marks)
    rig.run(3.0)
    assert rig.cutter.error_active(FS701Error.CUT_NOT_POSSIBLE) and rig.cutter.cut_log == []


def test_marks_are_registered_only_in_automatic_p5():
    s = pm_settings()
    marks = PrintMarks(width=10.0, pitch=1500.0, first=500.0, count=20)
    rig = CutterRig(s, line_speed=1000.0, marks=marks, sensor_position=-3000.0)
    rig.enable()
    rig.run(5.0)
    c = rig.cutter
    assert c.printmarks.marks_seen >= 2 and len(c.printmarks.queue) == 0 and c.cut_log == []
    assert c.cut_state is CutState.HOME
    rig.start()
    rig.run(5.0)
    assert c.cut_log and all(x.kind is CutKind.PRINTMARK for x in c.cut_log)


def test_printmark_status_and_process_values_p10():
    s = pm_settings(printmark_window=200)
    marks = PrintMarks(width=10.0, pitch=1500.0, first=500.0, count=20)
    rig = pm_rig(s, marks)
    rig.run(4.2)  # mark m is at the sensor at material m - 3000: the last one, 6500, at 3500
    pv = rig.cutter.process_values()
    assert pv[20] & 1  # window on
    assert pv[24] == len(rig.cutter.printmarks.queue) and pv[22] == (pv[23] + pv[24]) % 64
    assert pv[18] == pytest.approx((6500.0 - 3000.0) * 4, abs=2)  # master at the last mark, increments
    assert pv[16] == pytest.approx((rig.cutter.master.position - rig.cutter.printmarks.last_mark) * 4)
    assert pv[19] == 0 and pv[21] == 0
