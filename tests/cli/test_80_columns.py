"""A newcomer's terminal: every shipped example's output, piped at 80 columns, has no line wider
than 80 cells and no value cut short by Rich ('…' glued to text; 'a … b' is a range)."""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

import pytest
from rich.cells import cell_len

ROOT = Path(__file__).resolve().parents[2]
EXE = Path(sys.executable).parent / "pumplink"

SPECS = ["configs/prototype.toml", "configs/village-10m.toml", "configs/women-operators-6m.toml"]
EXAMPLES = ["examples/well-12m-flywheel.toml", "examples/piston-pump.toml"]

#: Commands whose output at 80 columns is a golden file (tests/test_golden.py checks the output
#: equals it and that the file fits): not run again here.
GOLDEN = (
    ["synth", *SPECS],
    ["force", "configs/prototype.toml"],
    ["force", "configs/prototype.toml", "--summary"],
    ["force", "configs/village-10m.toml", "--summary"],
    ["batch", "configs/"],
    ["transmission"],
)

ALL = (
    [["synth", *SPECS]]
    + [["force", f] for f in SPECS + EXAMPLES]
    + [["force", f, "--summary"] for f in SPECS + EXAMPLES]
    + [["force", f, "--explain"] for f in SPECS + EXAMPLES]
    + [["force", "configs/prototype.toml", "--at", "90", "--at", "270"]]
    + [["speed", f] for f in ("configs/village-10m.toml", "examples/well-12m-flywheel.toml")]
    + [
        ["batch", "configs/prototype-family.toml"],
        ["batch", "configs/grids/piston-bore.toml"],
        ["batch", "configs/"],
        ["methods", "--samples", "90", "--repeats", "1"],
        ["transmission"],
        ["slider", "--stroke", "0.1", "--rod-ratio", "4", "--time-ratio", "1.2"],
        ["slotted", "--time-ratio", "1.5", "--stroke", "0.3"],
        ["rocker", "--time-ratio", "1.25", "--swing", "50", "--rocker", "0.3", "--frame", "0.4"],
        ["structure", "configs/mechanisms/six-link.toml"],
        ["structure", "configs/mechanisms/double-parallelogram.toml"],
        ["init", "--example", "list"],
    ]
)
#: Commands that are also a help or README example: tests/cli/test_help_examples.py runs them at
#: 80 columns and checks the same.
EXAMPLES_RUN = (
    ["force", "examples/piston-pump.toml", "--summary"],
    ["force", "examples/well-12m-flywheel.toml", "--summary"],
    ["speed", "examples/well-12m-flywheel.toml"],
    ["batch", "configs/grids/piston-bore.toml"],
    ["slider", "--stroke", "0.1", "--rod-ratio", "4", "--time-ratio", "1.2"],
    ["slotted", "--time-ratio", "1.5", "--stroke", "0.3"],
    ["rocker", "--time-ratio", "1.25", "--swing", "50", "--rocker", "0.3", "--frame", "0.4"],
    ["structure", "configs/mechanisms/six-link.toml"],
)
COMMANDS = [c for c in ALL if c not in [list(g) for g in GOLDEN + EXAMPLES_RUN]]

TRUNCATED = re.compile(r"\S…")


@pytest.mark.parametrize("args", COMMANDS, ids=" ".join)
def test_fits_80_columns(args):
    env = {**os.environ, "COLUMNS": "80", "NO_COLOR": "1"}
    p = subprocess.run([EXE, *args], cwd=ROOT, env=env, capture_output=True, text=True, timeout=300)
    assert p.returncode in (0, 1), p.stderr
    assert "Traceback" not in p.stderr
    for line in (p.stdout + p.stderr).splitlines():
        assert cell_len(line) <= 80, line
        assert not TRUNCATED.search(line), line
