# The two commands a fresh machine needs: `make demo` and `make test`.
# Both create .venv if it is missing and install axisline with its pinned dependencies.
# The modules listed in compiled_modules.txt are compiled with mypyc on install (see
# "Compiled hot path" in README.md); `make test-pure` runs the suite on plain Python.
PY ?= python3
VENV := .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.installed

PURE_VENV := .venv-pure
PURE_BIN := $(PURE_VENV)/bin
PURE_STAMP := $(PURE_VENV)/.installed

# Runtime and build dependencies (mypy, setuptools in pip's isolated build environment) pinned.
PIP_INSTALL = -m pip install --quiet -c constraints.txt --build-constraint constraints.txt

# The sources of the compiled modules: an edit re-installs, i.e. recompiles, so that
# `make test` never runs a binary older than its .py. (Same parsing as setup.py: one path
# a line, comments and blank lines skipped.)
COMPILED_SOURCES := $(shell grep -oE '^[[:space:]]*[[:alnum:]_./-]+\.py' compiled_modules.txt)
BUILD_INPUTS := pyproject.toml constraints.txt setup.py compiled_modules.txt $(COMPILED_SOURCES)

# .venv is compiled unless AXISLINE_COMPILE=0; the stamp records which, and a switch re-installs.
BUILD_MODE := compile=$(if $(filter 0,$(strip $(AXISLINE_COMPILE))),0,1)

.PHONY: demo test test-pure bench setup setup-pure clean dist
ifneq ($(BUILD_MODE),$(shell cat $(STAMP) 2>/dev/null))
.PHONY: $(STAMP)
endif

$(BIN)/python:
	$(PY) -m venv $(VENV)

$(STAMP): $(BIN)/python $(BUILD_INPUTS)
	@echo "axisline: installing the pinned dependencies and axisline into $(VENV)$(if $(filter compile=1,$(BUILD_MODE)), (compiling $(words $(COMPILED_SOURCES)) modules with mypyc: about 1.5 minutes on two cores the first time),) ..."
	@start=$$(date +%s); \
	$(BIN)/python -m pip install --quiet --upgrade pip && \
	$(BIN)/python $(PIP_INSTALL) -e '.[test]' && \
	echo "axisline: installed in $$(( $$(date +%s) - start )) s"
	@echo $(BUILD_MODE) > $(STAMP)

setup: $(STAMP)

demo: $(STAMP)
	$(BIN)/axisline run examples/flying_shear.toml --report out/demo

# Debian's Chromium for the web HMI's browser tests (tests/hmi, driven by Playwright with this
# executable; Playwright's own browser download needs the internet). Installed once when missing;
# where it cannot be installed (not root, no sudo) those tests are skipped with that reason.
BROWSER := /usr/bin/chromium
APT_CHROMIUM = DEBIAN_FRONTEND=noninteractive apt-get install -y -q chromium >/dev/null 2>&1 || \
	{ apt-get update -q >/dev/null 2>&1 && DEBIAN_FRONTEND=noninteractive apt-get install -y -q chromium >/dev/null 2>&1; }
$(BROWSER):
	@echo "axisline: installing Debian's chromium for the HMI browser tests (about 20 s) ..."
	@if [ "$$(id -u)" = 0 ]; then ( $(APT_CHROMIUM) ) || echo "axisline: chromium could not be installed: the browser tests will be skipped"; \
	elif command -v sudo >/dev/null 2>&1 && sudo -n true 2>/dev/null; then sudo sh -c '$(APT_CHROMIUM)' || echo "axisline: chromium could not be installed: the browser tests will be skipped"; \
	else echo "axisline: not root and no sudo: chromium not installed, the browser tests will be skipped"; fi

test: $(STAMP) $(BROWSER)
	$(BIN)/python -m pytest

bench: $(STAMP)
	$(BIN)/python bench/run.py

# Plain Python, the same sources: a second venv with a regular (not editable) install built
# with AXISLINE_COMPILE=0, so it never sees the compiled modules that the editable install
# puts next to the sources in src/. Re-installed when any source changes.
$(PURE_BIN)/python:
	$(PY) -m venv $(PURE_VENV)

$(PURE_STAMP): $(PURE_BIN)/python $(BUILD_INPUTS) $(shell find src -name '*.py')
	$(PURE_BIN)/python -m pip install --quiet --upgrade pip
	rm -rf build/lib build/bdist.*  # setuptools' staging dir: no module deleted from src/ may linger
	AXISLINE_COMPILE=0 $(PURE_BIN)/python $(PIP_INSTALL) '.[test]'
	touch $(PURE_STAMP)

setup-pure: $(PURE_STAMP)

test-pure: $(PURE_STAMP)
	AXISLINE_COMPILE=0 $(PURE_BIN)/python -m pytest

# a wheel (compiled) and an sdist in dist/, built by PyPA's build in an isolated environment
dist: $(STAMP)
	$(BIN)/python -m pip install --quiet build
	$(BIN)/python -m build --outdir dist

clean:
	rm -rf $(VENV) $(PURE_VENV) out .pytest_cache build/mypyc dist
	find src -name '*.so' -delete
