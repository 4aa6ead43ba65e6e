"""Start-up guard: the commands a person waits for import only what they use.

Importing ``scipy.optimize`` alone costs about 0.3 s; matplotlib, mpmath, loky, the optional
extras (dask, pyarrow, numba) and pumplink's design search, batch, method study and piston pump
are for other commands.  Each case runs the real entry point in a fresh interpreter, checks the
command did its work, and lists the modules of that list it loaded.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]

#: Never loaded by synth or force on a rope-pump spec without inertia (the quasi-static model).
HEAVY = [
    "scipy.optimize",
    "scipy.integrate",
    "matplotlib",
    "mpmath",
    "loky",
    "dask",
    "distributed",
    "pyarrow",
    "numba",
    # pumplink's own modules for other commands and mechanisms
    "pumplink.search.optimize",
    "pumplink.search.problem",
    "pumplink.batch",
    "pumplink.studies.methods",
    "pumplink.studies.accuracy",
    "pumplink.studies.piston",
    "pumplink.models.flywheel",  # the inertia models: a spec without inertia never needs them
    "pumplink.models.dynamics",
    "pumplink.models.dynamics_solver",
    "pumplink.models.dynamics_terms",
    "pumplink.models.flywheel_solver",
    "pumplink.models.grip_travel",
]

PROBE = """
import contextlib, io, json, sys
from pumplink.cli import main
out = io.StringIO()
code = None
with contextlib.redirect_stdout(out):
    try:
        main(sys.argv[1:])
    except SystemExit as exc:
        code = exc.code
loaded = [h for h in HEAVY if h in sys.modules]
print(json.dumps({"code": code, "out": out.getvalue(), "loaded": loaded, "modules": sorted(sys.modules)}))
"""


def _probe(*args: str) -> dict:
    env = {**os.environ, "NO_COLOR": "1", "COLUMNS": "80"}
    p = subprocess.run(
        [sys.executable, "-c", f"HEAVY = {HEAVY!r}\n{PROBE}", *args],
        cwd=ROOT,
        env=env,
        capture_output=True,
        text=True,
        check=True,
    )
    return json.loads(p.stdout)


@pytest.mark.parametrize(
    "args, expect",
    [
        (["synth", "configs/prototype.toml"], "0.0998"),  # the crank length [m], Table 1 style
        (["force", "configs/prototype.toml", "--summary"], "VERDICT: PASS"),
        (["force", "configs/prototype.toml"], "DC extended"),  # the 360-sample sweep's rows
    ],
)
def test_single_spec_commands_load_nothing_heavy(args, expect):
    res = _probe(*args)
    assert res["code"] == 0 and expect in res["out"], res["out"]  # the command really ran
    assert res["loaded"] == [], f"{' '.join(args)} imported {res['loaded']}"


def test_a_spec_with_inertia_loads_the_inertia_models():
    """The guard above is not vacuous: where the wheel's inertia decides, the force command loads
    the flywheel and full-dynamics modules, and, the spec giving a head, the released handle's
    integration (scipy.integrate's solve_ivp, scipy.optimize's bounded search: the line printed
    under the verdict); still none of the other heavy ones."""
    res = _probe("force", "examples/well-12m-flywheel.toml", "--summary")
    assert "VERDICT" in res["out"] and "released handle" in res["out"], res["out"]
    assert sorted(res["loaded"]) == [
        "pumplink.models.dynamics",
        "pumplink.models.dynamics_solver",
        "pumplink.models.dynamics_terms",
        "pumplink.models.flywheel",
        "pumplink.models.flywheel_solver",
        "pumplink.models.grip_travel",
        "scipy.integrate",
        "scipy.optimize",
    ], res["loaded"]


def test_importing_the_cli_loads_no_library():
    """``import pumplink.cli`` (and so ``pumplink --help``) leaves numpy, pydantic and scipy to
    the commands that need them."""
    res = _probe("--help")
    assert res["code"] == 0 and "force" in res["out"] and "synth" in res["out"]
    top = {m.split(".")[0] for m in res["modules"]}
    assert not top & {"numpy", "scipy", "pydantic", "matplotlib", "mpmath"}, sorted(
        top & {"numpy", "scipy", "pydantic", "matplotlib", "mpmath"}
    )


AT_EXIT = (
    "import atexit, os, sys\n"
    "atexit.register(lambda: sys.stderr.write(f\"at exit: {os.environ.get('OPENBLAS_NUM_THREADS')}\\n\"))\n"
    "sys.argv = ['pumplink', 'synth', 'configs/prototype.toml']\n"
    "from pumplink.cli import main\n"
    "main()\n"
)


@pytest.mark.parametrize("given, expected", [(None, "1"), ("3", "3")])
def test_run_as_the_program_asks_openblas_for_one_thread(given, expected):
    """Run as the program, pumplink asks numpy's OpenBLAS for one thread unless the user chose a
    number; exit handlers still run (after the garbage collector's freeze) and the exit code is
    the command's."""
    env = {k: v for k, v in os.environ.items() if k != "OPENBLAS_NUM_THREADS"}
    if given is not None:
        env["OPENBLAS_NUM_THREADS"] = given
    p = subprocess.run([sys.executable, "-c", AT_EXIT], cwd=ROOT, env=env, capture_output=True, text=True)
    assert p.returncode == 0 and "0.0998" in p.stdout, p.stderr
    assert p.stderr.splitlines()[-1] == f"at exit: {expected}"
