"""docs/machine-file.md is the schema rendered: it must not drift from the code."""

from pathlib import Path

from axisline.schema_doc import render

DOC = Path(__file__).resolve().parent.parent / "docs" / "machine-file.md"


def test_machine_file_reference_matches_the_schema():
    assert DOC.read_text() == render(), "run: axisline schema --out docs/machine-file.md"


def test_reference_lists_ranges_and_choices():
    text = render()
    assert "| `cycle_us` | int | 1000 | >= 250 and <= 10000 |" in text
    assert "one of 'trapezoid', 'jerk', 'sin2'" in text
    assert "## [[axis.switches]]" in text and "## [[job.steps]]" in text
