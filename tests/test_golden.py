"""Golden files for the rendered tables (what a designer reads), through the real entry point.

The numbers inside are checked independently elsewhere (tests/models/test_quasi_static.py,
tests/mechanisms/test_fourbar_synthesis.py and tests/mechanisms/test_crank_rocker.py against
mpmath references); these files guard the layout: units in headers, dead centres marked, the
verdict in words without colour.  They compare text exactly, so every number in them must be
known to the digits printed on any processor: closed forms, roots of smooth equations and the
values (not the arguments) of stationary extrema are; the argument of a flat optimum and what
is read there are not (docs/crank-rocker.md §5).  After a deliberate layout change, regenerate
with `PUMPLINK_REGEN_GOLDEN=1 pytest tests/test_golden.py` and review the diff.
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
GOLDEN = Path(__file__).with_name("golden")

CASES = {
    "force_prototype_summary.txt": ["force", "configs/prototype.toml", "--summary"],
    "force_prototype_sweep.txt": ["force", "configs/prototype.toml"],
    "synth_configs.txt": [
        "synth",
        "configs/prototype.toml",
        "configs/village-10m.toml",
        "configs/women-operators-6m.toml",
    ],
    "force_village_summary.txt": ["force", "configs/village-10m.toml", "--summary"],
    "batch_configs.txt": ["batch", "configs/"],
    "transmission_default.txt": ["transmission"],
}


def _run(args, columns: int):
    env = {**os.environ, "NO_COLOR": "1", "COLUMNS": str(columns)}
    return subprocess.run(
        [sys.executable, "-m", "pumplink", *args],
        cwd=ROOT,
        env=env,
        capture_output=True,
        text=True,
        check=False,
    )


@pytest.mark.parametrize("name", sorted(CASES))
def test_rendered_table_matches_golden(name):
    out = _run(CASES[name], 80)
    assert out.returncode == 0, out.stderr
    assert "\x1b[" not in out.stdout  # no ANSI escapes when piped / NO_COLOR
    path = GOLDEN / name
    if os.environ.get("PUMPLINK_REGEN_GOLDEN"):
        path.write_text(out.stdout, encoding="utf-8")
    assert out.stdout == path.read_text(encoding="utf-8")


def _fits(text: str, columns: int) -> None:
    lines = text.splitlines()
    assert max(len(line) for line in lines) <= columns
    assert "…" not in text.replace("0.1 … 0.4", "")


@pytest.mark.parametrize("name", sorted(CASES))
def test_tables_fit_the_terminal_without_truncation(name):
    """A designer's terminal: every line fits, and no value is cut to '…' (Rich's truncation).
    At 80 columns that is the golden file itself (the output equals it, the test above); at 120
    columns the command is run again."""
    _fits((GOLDEN / name).read_text(encoding="utf-8"), 80)
    out = _run(CASES[name], 120)
    assert out.returncode == 0, out.stderr
    _fits(out.stdout, 120)
