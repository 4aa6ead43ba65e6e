"""Every ``benchmarks/bench_*.py`` runs to its end in smoke mode (``--smoke``: the smallest size,
one repeat, no target judged; benchmarks/_record.py), and `make bench`'s summary table renders what
they recorded: an API the benchmarks use cannot move without ``make test`` noticing.

Each script runs as ``make bench`` runs it, ``python benchmarks/bench_X.py`` in a subprocess (the
scripts change directory, patch scipy and start pumplink commands of their own), once per script
for the whole module (``-k bench_X`` runs that one alone).  The scripts are found by the same glob
as the Makefile's, so a new one is covered without a change here.  The test extras have no
pylinkage (the bench extra): the two scripts that compare against it say so and skip its side;
bench_grid_baseline.py runs this checkout's side only and says so (the pinned old install is built
by ``make bench`` alone).
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
BENCH = ROOT / "benchmarks"
SCRIPTS = sorted(BENCH.glob("bench_*.py"))
#: Seconds one smoke run may take before it counts as hung (they take 1-20 s on this machine).
TIMEOUT = 300


@pytest.fixture(scope="module")
def smoke_run(tmp_path_factory):
    """``smoke_run(name)``: script ``name`` run with ``--smoke`` (once for the module, on first
    use): its process and the figures it recorded."""
    folder = tmp_path_factory.mktemp("bench")
    env = {k: v for k, v in os.environ.items() if k not in ("PUMPLINK_BENCH_OUT", "PUMPLINK_BENCH_SMOKE")}
    runs: dict[str, tuple[subprocess.CompletedProcess, list[dict]]] = {}

    def run(name: str) -> tuple[subprocess.CompletedProcess, list[dict]]:
        if name not in runs:
            out = folder / f"{name}.jsonl"
            p = subprocess.run(
                [sys.executable, str(BENCH / name), "--smoke"],
                cwd=ROOT,
                env={**env, "PUMPLINK_BENCH_OUT": str(out)},
                capture_output=True,
                text=True,
                timeout=TIMEOUT,
            )
            rows = [json.loads(line) for line in out.read_text().splitlines()] if out.exists() else []
            runs[name] = (p, rows)
        return runs[name]

    return run


def test_the_glob_finds_every_script():
    assert len(SCRIPTS) >= 10 and all(s.name.startswith("bench_") for s in SCRIPTS)


@pytest.mark.parametrize("name", [s.name for s in SCRIPTS])
def test_each_script_runs_to_its_end_and_judges_nothing(smoke_run, name):
    p, rows = smoke_run(name)
    assert p.returncode == 0, f"{name} --smoke exited {p.returncode}:\n{p.stderr[-3000:]}"
    assert "Traceback" not in p.stderr, p.stderr[-3000:]
    assert p.stdout.strip(), f"{name} printed nothing"
    # no target judged: nothing says met yes or NO, and every recorded figure has met null
    assert "met: yes" not in p.stdout and "met: NO" not in p.stdout, p.stdout
    assert all(r["met"] is None for r in rows), [r for r in rows if r["met"] is not None]
    assert all(r["script"] == name for r in rows)


def test_the_baseline_comparison_runs_this_checkout_and_says_it_skips_the_old_install(smoke_run):
    p, _ = smoke_run("bench_grid_baseline.py")
    assert "smoke run: the pinned install of 2cf593a is not run" in p.stdout
    assert "this checkout: median wall" in p.stdout  # this checkout's batch did run (its CSV counted)


def test_the_summary_table_renders_every_recorded_figure(smoke_run, tmp_path):
    rows = [r for s in SCRIPTS for r in smoke_run(s.name)[1]]
    assert len({r["script"] for r in rows}) >= 8  # the scripts that record figures did
    path = tmp_path / "bench.jsonl"
    path.write_text("".join(json.dumps(r) + "\n" for r in rows))
    p = subprocess.run(
        [sys.executable, str(BENCH / "summary.py"), str(path)],
        env={**os.environ, "COLUMNS": "200", "NO_COLOR": "1"},
        capture_output=True,
        text=True,
        check=True,
    )
    assert "0 of 0 targets met." in p.stdout  # a smoke run judges nothing
    for r in rows:
        assert r["name"][:40] in p.stdout, r["name"]
