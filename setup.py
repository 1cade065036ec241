"""Build hook: compiles the hot-path modules listed in compiled_modules.txt with mypyc.

All project metadata lives in pyproject.toml; this file only adds the extension modules.

- AXISLINE_COMPILE=0: no compilation, axisline is plain Python (the same sources).
- otherwise (default): every module in compiled_modules.txt is compiled; if mypyc or
  the C compiler fails, the build fails. There is no silent fallback to Python.

Floating point must stay bit-identical to CPython (the same machine file and seed give a
bit-identical trace, compiled or not): the C code is built with -ffp-contract=off (no fused
multiply-add) and without -ffast-math (-fno-fast-math, and fast-math flags in CFLAGS are
refused).

Editable installs (`pip install -e .`, what the Makefile does): setuptools builds the
extensions and copies them next to their sources (src/axisline/.../material.cpython-311-...so,
plus mypyc's shared runtime src/<hash>__mypyc.cpython-311-...so when there are several
modules), where the import system prefers them over the .py. Before each editable build
every extension module under src/ is removed, so a module taken off the list, or an
AXISLINE_COMPILE=0 install, never keeps running an old binary.
"""

from __future__ import annotations

import os
import sys
from concurrent.futures import ThreadPoolExecutor
from importlib.machinery import EXTENSION_SUFFIXES
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext
from setuptools.command.build_py import build_py

ROOT = Path(__file__).resolve().parent
SRC = ROOT / "src"
MODULE_LIST = ROOT / "compiled_modules.txt"
BUILD_DIR = "build/mypyc"  # generated C and mypy's cache (relative: pip builds in ROOT)

# Flags appended after Python's own CFLAGS and mypyc's (-O3 -g1 -Werror ...): the last
# -f option wins, so these hold whatever came before.
FP_CFLAGS = ["-ffp-contract=off", "-fno-fast-math"]
FAST_MATH_FLAGS = ("-ffast-math", "-Ofast", "-funsafe-math-optimizations", "-ffp-contract=fast")


def compile_enabled() -> bool:
    value = os.environ.get("AXISLINE_COMPILE", "1").strip()
    return value != "0"


def read_module_list() -> list[str]:
    """Paths from compiled_modules.txt (relative to the repository root), checked."""
    paths: list[str] = []
    for number, raw in enumerate(MODULE_LIST.read_text(encoding="utf-8").splitlines(), 1):
        line = raw.split("#", 1)[0].strip()
        if not line:
            continue
        path = ROOT / line
        if not line.endswith(".py") or not line.startswith("src/axisline/") or not path.is_file():
            sys.exit(f"compiled_modules.txt:{number}: {line!r} is not a .py file under src/axisline/")
        paths.append(line)
    if not paths:
        sys.exit("compiled_modules.txt lists no module (set AXISLINE_COMPILE=0 to build without mypyc)")
    return paths


def check_cflags() -> None:
    import sysconfig

    sources = {
        "CFLAGS (environment)": os.environ.get("CFLAGS", ""),
        "CPPFLAGS (environment)": os.environ.get("CPPFLAGS", ""),
        "Python's CFLAGS (sysconfig)": sysconfig.get_config_var("CFLAGS") or "",
    }
    for where, flags in sources.items():
        bad = [flag for flag in flags.split() if flag in FAST_MATH_FLAGS]
        if bad:
            sys.exit(f"{where} contains {' '.join(bad)}: the compiled modules would not compute "
                     "like CPython. Remove it, or build with AXISLINE_COMPILE=0.")


def extensions() -> list:
    paths = read_module_list()
    check_cflags()
    # Imported here, not at the top: an AXISLINE_COMPILE=0 build must not need mypy.
    from mypyc.build import mypycify

    # mypy options. Third-party packages (numpy, pydantic, ...) are typed as Any: mypy would
    # otherwise look them up in the target environment (pip's isolated build environment
    # runs the target's python), where they are missing on a first install and present on
    # a re-install, and the compiled code would depend on that. Errors in modules that are
    # only imported (not compiled) do not stop the build; the compiled ones must type-check.
    # Any mypy or mypyc error exits here with a non-zero status: the build fails.
    exts = mypycify(
        [
            "--no-site-packages",
            "--ignore-missing-imports",
            "--follow-imports=silent",
            f"--cache-dir={BUILD_DIR}/mypy_cache",
            *paths,
        ],
        opt_level="3",
        target_dir=BUILD_DIR,
        # one C file per module (not one file for all): the C compiler runs on them in parallel
        # (BuildExt.build_extension); one file of 50 MB took 8 minutes on one core
        multi_file=True,
    )
    for ext in exts:
        ext.extra_compile_args = [*ext.extra_compile_args, *FP_CFLAGS]
    return exts


# pip runs setup.py three times per install (build requirements, metadata, build), and the
# first two also set up build_ext (to list sources for the manifest); mypyc is a full mypy
# run (~10 s in a fresh build environment) and is only needed to build. So setup() gets a
# placeholder, which marks the distribution as having extension modules (platform wheel,
# build_ext runs), and BuildExt.run swaps in mypyc's extensions just before building.
PLACEHOLDER = Extension("axisline._mypyc_placeholder", sources=[])


class BuildExt(build_ext):
    def run(self) -> None:
        modules = self.distribution.ext_modules
        if modules and modules[0] is PLACEHOLDER:
            modules[:] = extensions()
            self._adopt(modules)
        super().run()

    def build_extension(self, ext: Extension) -> None:
        """Compile an extension's C files in parallel, one compiler process per CPU (mypyc's
        shared library has one file per compiled module); then link as setuptools does."""
        jobs = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else (os.cpu_count() or 1)
        if len(ext.sources) < 2 or jobs < 2:
            super().build_extension(ext)
            return
        compile_files = self.compiler.compile

        def compile_parallel(sources: list[str], *args: object, **kwargs: object) -> list[str]:
            # largest first: the pool stays busy to the end
            order = sorted(sources, key=lambda f: -os.path.getsize(f) if os.path.exists(f) else 0)
            with ThreadPoolExecutor(jobs) as pool:
                done = dict(zip(order, pool.map(lambda f: compile_files([f], *args, **kwargs), order)))
            return [obj for f in sources for obj in done[f]]  # objects in the sources' order

        self.compiler.compile = compile_parallel  # type: ignore[method-assign]
        try:
            super().build_extension(ext)
        finally:
            self.compiler.compile = compile_files  # type: ignore[method-assign]

    def _adopt(self, modules: list) -> None:
        """What setuptools' build_ext.finalize_options does for each extension."""
        self.extensions = modules
        self.check_extensions_list(self.extensions)
        self.ext_map = {}
        for ext in self.extensions:
            ext._full_name = fullname = self.get_ext_fullname(ext.name)
            self.ext_map[fullname] = self.ext_map[fullname.split(".")[-1]] = ext
            ext._links_to_dynamic = ext._needs_stub = False
            ext._file_name = self.get_ext_filename(fullname)


class BuildPy(build_py):
    """In an editable build, first remove the extension modules a previous build left in src/."""

    def run(self) -> None:
        if getattr(self, "editable_mode", False):
            for path in sorted(SRC.rglob("*")):
                if path.is_file() and path.name.endswith(tuple(EXTENSION_SUFFIXES)):
                    print(f"removing old binary {path.relative_to(ROOT)}")
                    path.unlink()
        super().run()


setup(
    ext_modules=[PLACEHOLDER] if compile_enabled() else [],
    cmdclass={"build_py": BuildPy, "build_ext": BuildExt},
)
