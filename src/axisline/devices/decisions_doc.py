"""The device part of docs/decisions.md, collected from the device modules.

Each device module keeps its decisions ("Decisions" list in its module docstring: the spec
line, the choice, why, the test) next to the code they govern. This renders them into the
"## Device personalities" section of docs/decisions.md, so the document cannot drift from
the code: `python -m axisline.devices.decisions_doc docs/decisions.md` rewrites the section,
and tests/test_decisions_doc.py fails when it is stale.
"""

from __future__ import annotations

import ast
import re
import sys
from pathlib import Path

MARKER = "## Device personalities"

_DEVICES = (
    ("FS701 flying shear / saw (issue 4)", "devices/fs701"),
    ("COMPAX cam controller (issue 5)", "devices/compax"),
    ("WAGO 750-672 stepper module (issue 6)", "devices/wago672"),
    ("Rexroth CLM1.4 (issue 11)", "devices/clm"),
    # read as files, never imported: the layers above the devices keep their decisions here too
    ("Motion kernel and scope (issue 18)", "motion"),
    ("Kernel (issue 18)", "kernel"),
    ("Plant (issue 18)", "plant"),
    ("Scope channels (issue 18)", "scope_channels.py"),
    ("Serving a machine and the web HMI (issue 17)", "serve"),
    ("Web HMI pages (issue 17)", "hmi"),
    ("Web HMI device views (issue 17)", "hmi/devices"),
    ("CiA 402 drives over CANopen (issue 20)", "drives"),
    ("Sweeps on Dask (issue 21)", "sweep"),
)


def _decisions(path: Path) -> str | None:
    doc = ast.get_docstring(ast.parse(path.read_text(encoding="utf-8"))) or ""
    # the section starts a line ("Decisions (...):"); a mention inside a sentence is not it
    found = re.search(r"(?m)^Decision", doc)
    at = found.start() if found else doc.find("Decision")
    return doc[at:].strip() if at >= 0 else None


def render(package: Path | None = None) -> str:
    root = package or Path(__file__).resolve().parent.parent  # the axisline package
    out = [
        MARKER,
        "",
        "Each device module keeps its decisions in a \"Decisions\" list in its module docstring, next to the",
        "code they govern; this section is generated from them (`python -m axisline.devices.decisions_doc",
        "docs/decisions.md`). Every entry names the spec line it resolves and the test that holds it (test",
        "names are in the entries or in the test files of the same module).",
        "",
    ]
    for title, name in _DEVICES:
        blocks = []
        for path in [root / name] if name.endswith(".py") else sorted((root / name).glob("*.py")):
            text = _decisions(path)
            if text:
                shown = name if name.endswith(".py") else f"{name}/{path.name}"
                blocks += [f"#### `axisline/{shown}`", "", text, ""]
        if blocks:
            out += [f"### {title}", ""] + blocks
    return "\n".join(out).rstrip() + "\n"


def update(doc: Path) -> bool:
    """Rewrite the device section of `doc`; True if it changed."""
    text = doc.read_text(encoding="utf-8")
    at = text.find(MARKER)
    head = text if at < 0 else text[:at]
    new = head.rstrip() + "\n\n" + render()
    if new == text:
        return False
    from ..kernel import atomic_write_text

    atomic_write_text(doc, new)
    return True


if __name__ == "__main__":  # pragma: no cover
    print("updated" if update(Path(sys.argv[1])) else "unchanged")
