# `make demo` and `make test` work on a fresh machine: they create .venv here and install
# everything they need (the test target adds the test tools, Dask and headless Chromium).
# pyproject.toml states compatible ranges; constraints.txt pins the exact versions installed.
PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
OUT    ?= out

.PHONY: demo test lint docs bench bench-all clean chromium

$(BIN)/python:
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install -q --upgrade pip

# Numba's OpenMP threads spin while they wait by default; on a shared 2-core machine that made the
# kernels about 3x slower. The library leaves the environment alone; make's commands set it.
export OMP_WAIT_POLICY ?= PASSIVE

CONSTRAINTS := constraints.txt
PIP := $(BIN)/python -m pip install -q -c $(CONSTRAINTS)

# The demo needs no Dask: studies run on local processes unless a scheduler is named.
# An editable install leaves the sources uncompiled: each command would compile every module
# again where bytecode is not written (PYTHONDONTWRITEBYTECODE), about 1,200 compilations.
$(VENV)/.installed: pyproject.toml $(CONSTRAINTS) | $(BIN)/python
	$(PIP) -e .
	$(BIN)/python -m compileall -q src/funcnet
	touch $@

$(VENV)/.installed-test: pyproject.toml $(CONSTRAINTS) $(VENV)/.installed
	$(PIP) -e ".[test,dask,docs]"
	touch $@

demo: $(VENV)/.installed
	$(BIN)/funcnet demo --out $(OUT)

# The user guide and the API reference from the docstrings; a warning fails the build.
docs: $(VENV)/.installed-test
	$(BIN)/sphinx-build -W --keep-going -q -b html docs docs/_build/html

# The report test drives Debian's Chromium; install it when it is absent (CI runs as root).
chromium:
	@command -v chromium >/dev/null 2>&1 || { \
	  (apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq chromium >/dev/null) \
	  || echo "warning: could not install chromium"; }

test: $(VENV)/.installed-test chromium
	$(BIN)/ruff check src tests benchmarks
	$(BIN)/mypy
	$(MAKE) docs
	$(BIN)/python -m pytest -n 2 -q

lint: $(VENV)/.installed-test
	$(BIN)/ruff check src tests benchmarks
	$(BIN)/mypy

# `make bench`: the quick set (a few minutes); `make bench BENCH="bench_long bench_windows"`: the
# named ones; `make bench-all`: every benchmarks/bench_*.py (an hour or more). Figures and the
# command behind each: benchmarks/RESULTS.md.
BENCH_QUICK := bench_core bench_reader bench_simulate bench_short_pair
BENCH_ALL   := $(sort $(basename $(notdir $(wildcard benchmarks/bench_*.py))))
BENCH       ?= $(BENCH_QUICK)

bench: $(VENV)/.installed-test
	@set -e; for name in $(BENCH); do \
	  echo "== benchmarks.$$name"; $(BIN)/python -m benchmarks.$$name; done

bench-all: $(VENV)/.installed-test
	@$(MAKE) --no-print-directory bench BENCH="$(BENCH_ALL)"

clean:
	rm -rf $(VENV) out .pytest_cache docs/_build
