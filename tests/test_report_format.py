"""Numbers in run reports are rounded to what they mean (issue 16): positions to the axis'
resolution, no rounding noise like 2.72848e-12 deg."""

from __future__ import annotations

from pathlib import Path

from axisline.machine import Machine
from axisline.report.markdown import _fmt, decimals, write_report

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


def test_decimals_show_a_tenth_of_a_count():
    assert decimals(1 / 2000) == 5  # 0.0005 mm per count -> 0.00050
    assert decimals(1 / 1000) == 4
    assert decimals(0.01) == 3
    assert decimals(None) == 6


def test_rounding_noise_reads_zero_and_no_negative_zero():
    assert _fmt(-5.45697e-12, "deg", 1 / 1000) == "0 deg"
    assert _fmt(2.72848e-12, "deg", 1 / 1000) == "0 deg"
    assert _fmt(30.00093, "deg", 1 / 1000) == "30.0009 deg"
    assert _fmt(1.5, "mm") == "1.5 mm"  # resolution unknown: 6 significant digits


def test_report_of_the_cam_packaging_example_has_no_exponent(tmp_path):
    m = Machine.from_file(EXAMPLES / "cam_packaging.toml", seed=None)
    result = m.run()
    summary = m.summary(result)
    path = write_report(summary, tmp_path, [])
    text = path.read_text()
    axes = text[text.index("## Axes"):text.index("## Faults")]
    assert "e-" not in axes and "e+" not in axes
    assert all("resolution" in a for a in summary["axes"].values())


def test_a_device_driven_run_has_no_empty_job_line(tmp_path):
    """Issue 16: the WAGO example is driven by its scripted PLC, not the machine file's job:
    the report says so instead of "finished, 0 round(s)"."""
    m = Machine.from_file(EXAMPLES / "wago_stepper.toml")
    summary = m.summary(m.run())
    text = write_report(summary, tmp_path, []).read_text()
    assert "0 round(s)" not in text and "the device drove the machine" in text
    m = Machine.from_file(EXAMPLES / "positioning.toml")  # a job of its own: its line stays
    text = write_report(m.summary(m.run()), tmp_path, []).read_text()
    assert "round(s)" in text


def test_warnings_name_a_saturated_drive_and_an_unlimited_stroke(tmp_path):
    """Issue 16: the print-mark example's return stroke holds the FS701's command at the +-10 V
    limit (19 mm following error): a warning of the run summary and the report; a carriage with
    no stroke limit (cam_sync's) is one too; the positioning example (software limits, no
    saturation) has none."""
    m = Machine.from_file(EXAMPLES / "flying_shear_printmark.toml")
    summary = m.summary(m.run())
    warnings = summary["warnings"]
    saturated = [w for w in warnings if "saturated" in w]
    assert len(saturated) == 1 and "axis 'carriage'" in saturated[0] and "+-10 V" in saturated[0]
    assert not any("no stroke limit" in w for w in warnings)  # its carriage has software limits
    text = write_report(summary, tmp_path, []).read_text()
    assert "## Warnings" in text and "saturated" in text
    m = Machine.from_file(EXAMPLES / "cam_sync.toml")  # a carriage with no limit anywhere
    warnings = m.summary(m.run())["warnings"]
    assert any("no stroke limit" in w and "axis 'carriage'" in w for w in warnings)
    m = Machine.from_file(EXAMPLES / "positioning.toml")
    assert m.summary(m.run())["warnings"] == []


def test_a_device_that_limits_its_axes_gets_no_stroke_warning():
    """The CLM monitors Ax03/Ax04 (or knows a feed roll endless): its carriage and feed roll get
    no "no stroke limit" warning, while cam_sync's carriage (no limit anywhere) does."""
    m = Machine.from_file(EXAMPLES / "roll_feed_clm.toml", )
    assert not any("no stroke limit" in w for w in m.summary(m.run())["warnings"])
    m = Machine.from_file(EXAMPLES / "cam_sync.toml")
    assert any("no stroke limit" in w for w in m.summary(m.run())["warnings"])
