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

test: $(STAMP)
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
