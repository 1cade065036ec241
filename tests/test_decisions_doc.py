"""docs/decisions.md carries every device module's Decisions list, current with the code."""

from pathlib import Path

from axisline.devices.decisions_doc import MARKER, render

DOC = Path(__file__).resolve().parent.parent / "docs" / "decisions.md"


def test_device_decisions_in_the_document_match_the_modules():
    text = DOC.read_text(encoding="utf-8")
    assert text[text.index(MARKER):] == render(), "run: python -m axisline.devices.decisions_doc docs/decisions.md"


def test_every_device_has_decisions_with_spec_references():
    text = render()
    for device in ("fs701", "compax", "wago672"):
        assert f"axisline/devices/{device}/" in text
    assert text.count("§") > 100  # entries cite the spec/manual sections they resolve
