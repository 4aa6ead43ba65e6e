"""Every documented output and every golden file is what the tool prints with its iterative solvers
perturbed: no printed digit is one the solvers' tolerances leave open.

Such a digit changes with the processor (another linear-algebra code path, another maths library
moves a solver's path): docs/optimize.md once quoted an optimum's binding slack as ``4.223e-11 m``,
which another machine printed as ``7.961e-11 m``.  Here each command of a README/docs output block
(scripts/docs_outputs.py) and of a golden file (tests/test_golden.py) runs once more, through
tests/perturb.py: every iterative solver's tolerances loosened ten times and its start (a starting
point, a bracket, differential evolution's first population) moved by 1e-9 of its size.  The text
must be the committed one, character for character (a batch's elapsed time masked, as
tests/test_docs_outputs.py masks it); the rules that make it so are pumplink/output/precision.py.

The perturbation must be live: each perturbed process counts its solvers' calls, and the solvers
each command uses (:data:`SOLVERS`) must have been called.  One perturbed run per output, all
solvers at once, loosened (``PUMPLINK_PERTURB=tighten pytest tests/test_solver_perturbation.py``
tightens them instead, by hand: the outputs were the same both ways when the test was written).
"""

from __future__ import annotations

import importlib.util
import json
import os
import re
import shlex
import subprocess
import sys
from collections import Counter
from pathlib import Path

import pytest
from test_golden import CASES, GOLDEN

ROOT = Path(__file__).resolve().parents[1]
PERTURB = Path(__file__).with_name("perturb.py")
if "docs_outputs" not in sys.modules:  # tests/test_docs_outputs.py may have loaded it
    _spec = importlib.util.spec_from_file_location("docs_outputs", ROOT / "scripts" / "docs_outputs.py")
    _module = importlib.util.module_from_spec(_spec)
    sys.modules["docs_outputs"] = _module  # its dataclass looks its module up there
    _spec.loader.exec_module(_module)
docs_outputs = sys.modules["docs_outputs"]

#: The solvers each command calls, by the words after ``pumplink``: each must be called (so
#: perturbed) in its run.  A command left out of this table calls none (structure analysis and
#: dead-centre synthesis are closed forms).
SOLVERS = {
    "force configs/village-10m.toml": {"bracket.find_minimum", "minimize_scalar", "brentq", "solve_ivp"},
    "force configs/prototype.toml": {"bracket.find_minimum"},
    # the kick-back's worst stop angle (bracket), the release at full speed (the village's too)
    "force examples/well-12m-flywheel.toml": {
        "bracket.find_minimum",
        "minimize_scalar",
        "brentq",
        "solve_ivp",
    },
    "force examples/piston-pump.toml": {"find_minimum"},
    "size": {"differential_evolution", "bracket.find_minimum"},
    # the passing speeds' ends are whole deg/s, settled by the verdict there (no solver of their
    # own); the best cadence's bounded search runs only where a speed passes, not on the 12 m well
    "speed": {"bracket.find_minimum"},
    "slider": {"find_root", "find_minimum"},
    "transmission": {"find_root", "find_minimum"},
    "optimize": {"differential_evolution", "minimize", "bracket.find_minimum"},
    "tolerance": {"bracket.find_minimum"},
    "batch": {"bracket.find_minimum"},
    # the water alone: the loss model's duty where it decides (the 20 m wells' all-day duty)
    "validate": {"duty_rope_speed"},
}
#: Commands with no iterative solver (closed forms): nothing to perturb, nothing may be called.
CLOSED_FORMS = ("structure", "synth", "bom")


def expected(args: list[str]) -> set[str]:
    """The solvers ``pumplink ARGS`` must call (:data:`SOLVERS`, the longest key that starts it)."""
    words = " ".join(args)
    keys = [k for k in SOLVERS if words == k or words.startswith(k + " ")]
    if not keys:
        assert args[0] in CLOSED_FORMS, f"say in SOLVERS which solvers `pumplink {words}` calls"
        return set()
    return SOLVERS[max(keys, key=len)]


def calls(path: Path) -> Counter:
    """The solvers' calls the perturbed processes counted (tests/perturb.py), summed."""
    total: Counter = Counter()
    for line in path.read_text(encoding="utf-8").splitlines():
        total.update(json.loads(line)["calls"])
    return total


def check_live(args: list[str], counted: Counter) -> None:
    need = expected(args)
    missing = sorted(s for s in need if counted[s] == 0)
    assert not missing, (
        f"pumplink {' '.join(args)}: never called {missing}, so never perturbed ({dict(counted)})"
    )
    if not need:
        assert not counted, f"pumplink {' '.join(args)} calls {dict(counted)}: add it to SOLVERS"


@pytest.fixture
def perturbed(tmp_path, monkeypatch):
    """A ``pumplink`` on PATH that runs tests/perturb.py (loosened tolerances, moved starts), and
    the file its processes count their solvers' calls in."""
    bin_dir = tmp_path / "bin"
    bin_dir.mkdir()
    shim = bin_dir / "pumplink"
    shim.write_text(f'#!/bin/sh\nexec "{sys.executable}" "{PERTURB}" "$@"\n', encoding="utf-8")
    shim.chmod(0o755)
    counts = tmp_path / "calls.jsonl"
    counts.touch()
    monkeypatch.setattr(docs_outputs, "BIN", bin_dir)  # docs_outputs.run puts BIN first on PATH
    monkeypatch.setenv("PUMPLINK_PERTURB", os.environ.get("PUMPLINK_PERTURB", "loosen"))
    monkeypatch.setenv("PUMPLINK_PERTURB_COUNTS", str(counts))
    return counts


@pytest.mark.parametrize("block", docs_outputs.all_blocks(), ids=lambda b: re.sub(r"\s+", "_", b.name)[:90])
def test_documented_output_is_the_same_with_solvers_perturbed(block, perturbed):
    fresh = docs_outputs.run(block.command, block.exit_code)
    diff = docs_outputs.difference(block, fresh)
    assert diff == "", f"{block.name}: a digit the solvers' tolerances leave open is printed:\n{diff}"
    args = shlex.split(block.command.split("|")[0])[1:]  # the words after `pumplink`
    check_live(args, calls(perturbed))


@pytest.mark.parametrize("name", sorted(CASES))
def test_golden_file_is_the_same_with_solvers_perturbed(name, perturbed):
    env = {**os.environ, "NO_COLOR": "1", "COLUMNS": "80"}
    out = subprocess.run(
        [sys.executable, str(PERTURB), *CASES[name]],
        cwd=ROOT,
        env=env,
        capture_output=True,
        text=True,
        check=False,
    )
    assert out.returncode == 0, out.stderr
    assert out.stdout == (GOLDEN / name).read_text(encoding="utf-8"), (
        f"{name}: a digit the solvers' tolerances leave open is printed"
    )
    check_live(CASES[name], calls(perturbed))
