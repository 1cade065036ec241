"""The compiled hot path (compiled_modules.txt, README "Compiled hot path").

- The install compiles what the list names (unless AXISLINE_COMPILE=0): a silent fallback to
  Python would make `make bench` measure something else than it says.
- Compiled and plain Python compute the same, bit for bit: the flying shear line is run twice
  in subprocesses, once as installed and once with every listed module imported from its .py
  source, and the traces are compared byte for byte.
"""

from __future__ import annotations

import importlib
import os
import subprocess
import sys
from importlib.machinery import EXTENSION_SUFFIXES
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parent.parent
LISTED = [
    line.split("#", 1)[0].strip()
    for line in (ROOT / "compiled_modules.txt").read_text(encoding="utf-8").splitlines()
    if line.split("#", 1)[0].strip()
]
MODULES = [p.removeprefix("src/").removesuffix(".py").replace("/", ".") for p in LISTED]
COMPILED = os.environ.get("AXISLINE_COMPILE", "1").strip() != "0"


def test_the_list_names_existing_modules() -> None:
    assert MODULES, "compiled_modules.txt names no module"
    for path in LISTED:
        assert (ROOT / path).is_file(), path


@pytest.mark.parametrize("name", MODULES)
def test_listed_modules_are_compiled_unless_switched_off(name: str) -> None:
    module = importlib.import_module(name)
    is_binary = str(module.__file__).endswith(tuple(EXTENSION_SUFFIXES))
    assert is_binary == COMPILED, f"{name} loaded from {module.__file__} (AXISLINE_COMPILE={'1' if COMPILED else '0'})"


# In the child: with FORCE_SOURCE set, the listed modules load from their .py files (a finder
# ahead of the normal ones), everything else as installed; then the line runs and its trace
# goes to the file given.
_CHILD = r"""
import importlib.machinery, importlib.util, os, sys
from pathlib import Path

names = set(sys.argv[3].split(","))
if sys.argv[2] == "source":
    class SourceFirst:
        @staticmethod
        def find_spec(name, path=None, target=None):
            if name not in names:
                return None
            spec = importlib.machinery.PathFinder.find_spec(name, path)
            source = Path(spec.origin).with_name(name.rsplit(".", 1)[-1] + ".py")
            return importlib.util.spec_from_file_location(name, source)
    sys.meta_path.insert(0, SourceFirst)

from axisline.machine import Machine
import axisline.machine as m
assert m.__file__.endswith(".py") == (sys.argv[2] == "source"), m.__file__
machine = Machine.from_file(sys.argv[4], duration=float(sys.argv[5]))
machine.run(float(sys.argv[5]))
machine.trace.save_npz(sys.argv[1])
"""


def _run_line(tmp_path: Path, how: str) -> dict[str, np.ndarray]:
    out = tmp_path / f"{how}.npz"
    subprocess.run(
        [sys.executable, "-c", _CHILD, str(out), how, ",".join(MODULES),
         str(ROOT / "examples" / "flying_shear.toml"), "3.0"],
        check=True, cwd=ROOT,
    )
    with np.load(out) as data:
        return {k: data[k] for k in data.files}


@pytest.mark.skipif(not COMPILED, reason="plain Python install: nothing compiled to compare")
def test_compiled_and_python_give_the_same_trace_bit_for_bit(tmp_path: Path) -> None:
    compiled = _run_line(tmp_path, "installed")
    source = _run_line(tmp_path, "source")
    assert compiled.keys() == source.keys()
    moving = compiled["carriage.actual_position"]
    assert np.ptp(moving) > 1.0  # the carriage cut pieces within the 3 s: a trace worth comparing
    for name in compiled:
        assert compiled[name].tobytes() == source[name].tobytes(), name
