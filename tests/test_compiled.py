"""The compiled hot path (compiled_modules.txt, README "Compiled hot path").

- The install compiles what the list names (unless AXISLINE_COMPILE=0): a silent fallback to
  Python would make `make bench` measure something else than it says.
- Compiled and plain Python compute the same, bit for bit: the flying shear line is run twice
  in subprocesses, once as installed and once with every listed module imported from its .py
  source, and the traces are compared byte for byte.
- Compiled, the public API is documented as in plain Python (issue 16): help() and
  inspect.signature show the source's docstrings and annotations (axisline/_docs.py), and
  the wrappers that carry them are never on the per-cycle path; py.typed ships.
"""

from __future__ import annotations

import importlib
import importlib.util
import inspect
import os
import pydoc
import subprocess
import sys
import tomllib
from importlib.resources import files
from importlib.machinery import EXTENSION_SUFFIXES
from pathlib import Path
from types import ModuleType

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


# --- documentation of the compiled modules (issue 16, "Packaging") ---------------------------

DOCUMENTED = ["axisline.motion.profiles", "axisline.machine", "axisline.motion.axis", "axisline.kernel.trace"]
# called every cycle from interpreted code: compiled-only, no documenting wrapper (the names
# given to document() at the end of each module)
HOT = {"Profile.sample", "Axis.update_setpoint", "Axis.position_loop", "Trace.record",
       "AxisUnit.sample", "AxisUnit.loop"}
# what issue 16 names, at least
REQUIRED = {
    "axisline.motion.profiles": ["plan", "plan_velocity", "State", "Limits", "Profile"],
    "axisline.machine": ["Machine", "Machine.run", "Machine.from_file", "Machine.axis",
                         "Machine.set_directions", "Machine.drive_by", "Machine.summary"],
    "axisline.motion.axis": ["Axis", "Axis.move_absolute", "Axis.halt", "Axis.power", "Axis.home"],
    "axisline.kernel.trace": ["Trace", "Trace.add_channel", "Trace.data", "Trace.load_npz"],
}


def _from_source(name: str) -> ModuleType:
    """The module `name` executed from its .py, next to the installed one (same package)."""
    installed = importlib.import_module(name)
    package, leaf = name.rsplit(".", 1)
    source = Path(str(installed.__file__)).with_name(leaf + ".py")
    spec = importlib.util.spec_from_file_location(f"{package}._plain_{leaf}", source)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module  # dataclasses look their module up while the class is made
    try:
        spec.loader.exec_module(module)
    finally:
        del sys.modules[spec.name]
    return module


def _public(module: ModuleType) -> list[str]:
    """Public functions, classes and their public methods (Class.method) that the module defines."""
    names = getattr(module, "__all__", None) or [
        n for n, v in vars(module).items()
        if not n.startswith("_") and getattr(v, "__module__", None) == module.__name__]
    out = []
    for n in names:
        obj = getattr(module, n)
        if inspect.isfunction(obj):
            out.append(n)
        elif isinstance(obj, type):
            out.append(n)
            out += [f"{n}.{k}" for k, v in vars(obj).items()
                    if not k.startswith("_") and (inspect.isfunction(v) or isinstance(v, (classmethod, staticmethod)))]
    return out


def _get(module: ModuleType, dotted: str) -> object:
    obj: object = module
    for part in dotted.split("."):
        obj = getattr(obj, part)
    return obj


def _rendered(obj: object) -> tuple[str, str | None, str]:
    try:
        signature = str(inspect.signature(obj))  # type: ignore[arg-type]
    except (TypeError, ValueError) as exc:
        signature = f"no signature: {exc}"
    return signature, obj.__doc__, pydoc.render_doc(obj, renderer=pydoc.plaintext)


@pytest.mark.skipif(not COMPILED, reason="plain Python install: the objects are the source's own")
@pytest.mark.parametrize("name", DOCUMENTED)
def test_compiled_public_api_shows_the_sources_docstrings_and_annotations(name: str) -> None:
    installed, plain = importlib.import_module(name), _from_source(name)
    assert str(installed.__file__).endswith(tuple(EXTENSION_SUFFIXES))
    public = _public(plain)
    assert set(REQUIRED[name]) <= set(public), set(REQUIRED[name]) - set(public)
    checked = 0
    for dotted in public:
        if dotted in HOT:
            continue  # compiled-only: help() shows its name and parameters, not its docstring
        signature, doc, text = _rendered(_get(installed, dotted))
        want_signature, want_doc, _ = _rendered(_get(plain, dotted))
        assert (signature, doc) == (want_signature, want_doc), dotted
        if want_doc:  # help() shows the docstring's first line and the annotated signature
            assert want_doc.strip().splitlines()[0] in text, dotted
        if ": '" in want_signature:
            assert want_signature.replace(" -> None", "")[:40] in text.replace(" -> None", ""), dotted
        checked += 1
    assert checked >= len(REQUIRED[name])


@pytest.mark.skipif(not COMPILED, reason="plain Python install: nothing is wrapped")
def test_hot_methods_stay_compiled_and_documented_calls_reach_the_compiled_code() -> None:
    from axisline.kernel.trace import Trace
    from axisline.machine import AxisUnit, Machine
    from axisline.motion.axis import Axis
    from axisline.motion.profiles import Limits, Profile, State, plan

    classes = {"Profile": Profile, "Axis": Axis, "Trace": Trace, "AxisUnit": AxisUnit}
    for dotted in HOT:
        cls, method = dotted.split(".")
        # found along the class' MRO (Axis' cycle methods are defined in its layer AxisCycle)
        assert inspect.ismethoddescriptor(inspect.getattr_static(classes[cls], method)), dotted  # no Python frame per cycle
    assert inspect.isfunction(plan) and inspect.isfunction(Machine.run)  # the documented wrappers
    compiled = [c.cell_contents for c in plan.__closure__ or () if inspect.isbuiltin(c.cell_contents)]
    assert len(compiled) == 1 and compiled[0].__name__ == "plan"
    # a call through the wrapper gives what the compiled function gives
    args = ("jerk", State(0.0, 0.5, 0.0), State(2.0, 0.0), Limits(1.0, 2.0, 2.0, 10.0))
    assert plan(*args).duration == compiled[0](*args).duration


@pytest.mark.parametrize("example", ["flying_shear.toml", "roll_feed_clm.toml"])
def test_no_documenting_wrapper_runs_every_cycle(example: str) -> None:
    """The wrappers cost one Python call; the per-cycle path must never pass through one."""
    from axisline.machine import Machine

    machine = Machine.from_file(str(ROOT / "examples" / example), duration=0.5)
    calls = 0

    def count(frame, event, arg):  # noqa: ANN001 - sys.setprofile signature
        nonlocal calls
        if event == "call" and frame.f_code.co_filename.startswith("<axisline._docs wrapper"):
            calls += 1

    sys.setprofile(count)
    try:
        machine.run(0.5)
    finally:
        sys.setprofile(None)
    cycles = round(0.5 / machine.period)
    assert cycles >= 250
    assert calls < cycles / 10, f"{calls} wrapper calls in {cycles} cycles"


def test_py_typed_ships() -> None:
    pyproject = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))
    assert "py.typed" in pyproject["tool"]["setuptools"]["package-data"]["axisline"]
    assert files("axisline").joinpath("py.typed").is_file()
