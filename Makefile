# Quick start:  make run   (creates .venv, installs, runs the default design)
#               make test  (creates .venv with the test extras, runs the suite)
PYTHON ?= python3
VENV   ?= .venv
BIN    := $(VENV)/bin

.PHONY: run test bench clean

$(BIN)/python:
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip

# One stamp per set of extras; reinstalls when pyproject.toml changes.  pip compiles the installed
# packages' bytecode one file after another (most of the install's time); it is compiled here on
# every core instead (a file that does not compile is skipped, as pip skips it).  The editable
# install puts this folder on sys.path (setuptools' compat mode) rather than an import hook that
# every Python start in the venv loads (15 ms instead of 50 ms a start here; most CLI tests
# start pumplink in a subprocess).
INSTALL = $(BIN)/python -m pip install --quiet --no-compile --config-settings editable_mode=compat
COMPILE = $(BIN)/python -m compileall -q -j 0 "$$($(BIN)/python -c 'import sysconfig; print(sysconfig.get_paths()["purelib"])')" >/dev/null || true

$(VENV)/.stamp-base: pyproject.toml | $(BIN)/python
	$(INSTALL) -e .
	$(COMPILE)
	touch $@

$(VENV)/.stamp-test: pyproject.toml | $(BIN)/python
	$(INSTALL) -e ".[test,plot]"
	$(COMPILE)
	touch $@

$(VENV)/.stamp-bench: pyproject.toml | $(BIN)/python
	$(INSTALL) -e ".[test,bench,plot]"
	$(COMPILE)
	touch $@

run: $(VENV)/.stamp-base
	$(BIN)/pumplink force --speed 360

# Lint, format check and the layering contract first (seconds), then the suite on two processes,
# a test file to a process (its module fixtures built once); PYTEST_ARGS= runs it in one.
PYTEST_ARGS ?= -n 2 --dist loadfile
# The package's bytecode is compiled once first: the CLI tests start pumplink in subprocesses,
# and where PYTHONDONTWRITEBYTECODE is set (as on this machine) each would compile it again.
test: $(VENV)/.stamp-test
	$(BIN)/python -m compileall -q pumplink
	$(BIN)/ruff check .
	$(BIN)/ruff format --check .
	$(BIN)/lint-imports --no-cache
	$(BIN)/python -m pytest -q $(PYTEST_ARGS)

# Every benchmarks/bench_*.py, one after the other in this process's venv (medians of repeats),
# with pumplink's bytecode compiled first as for the tests (the pinned baseline is a regular
# install, compiled by pip: a command's start-up is then compared like for like);
# each also appends its figures to $(BENCH_OUT) (benchmarks/_record.py), and the last step prints
# them all in one table with their targets (benchmarks/summary.py).
BENCH_OUT := $(CURDIR)/build/bench.jsonl
# Earlier code of this repository, installed beside this one for the side-by-side benchmarks, each
# a detached worktree of its commit with its own venv (built from this repository's own history):
# 2cf593a, before the one-evaluation restructure (the grid, benchmarks/bench_grid_baseline.py);
# 94c2ab6, before full dynamics and the part checks were computed for many designs at once (the
# part-check, tolerance and sizing commands, benchmarks/bench_parts.py).
BASE_COMMITS := 2cf593a 94c2ab6
build/base-%/.venv/.stamp:
	rm -rf build/base-$* && mkdir -p build
	git worktree prune
	git worktree add --detach build/base-$* $*
	$(PYTHON) -m venv build/base-$*/.venv
	build/base-$*/.venv/bin/python -m pip install --quiet build/base-$*
	touch $@

bench: $(VENV)/.stamp-bench $(foreach c,$(BASE_COMMITS),build/base-$(c)/.venv/.stamp)
	$(BIN)/python -m compileall -q pumplink
	@mkdir -p $(dir $(BENCH_OUT)) && rm -f $(BENCH_OUT)
	@for b in benchmarks/bench_*.py; do echo "== $$b"; \
		PUMPLINK_BENCH_OUT=$(BENCH_OUT) $(BIN)/python $$b || exit 1; done
	@$(BIN)/python benchmarks/summary.py $(BENCH_OUT)

clean:
	rm -rf $(VENV) build *.egg-info .pytest_cache .hypothesis .ruff_cache .import_linter_cache
