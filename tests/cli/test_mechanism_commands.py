"""The textbook-mechanism commands and the piston-pump spec through the real entry point.

Exit codes (0 / 1 infeasible or FAIL / 2 bad input), one-line errors, 80-column tables, the
--help examples (run in a temporary copy of configs/ and examples/), the structure configs.
"""

import json
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
CMD = [sys.executable, "-m", "pumplink"]


def run(*args, cwd=ROOT):
    env = {k: v for k, v in os.environ.items() if k not in ("FORCE_COLOR", "COLUMNS")}
    env.update(NO_COLOR="1", PYTHONIOENCODING="utf-8", PYTHONPATH=str(ROOT))
    return subprocess.run(
        [*CMD, *map(str, args)], capture_output=True, text=True, env=env, cwd=cwd, timeout=300
    )


def one_line_error(p, code):
    assert p.returncode == code, (p.returncode, p.stdout, p.stderr)
    assert "Traceback" not in p.stderr
    lines = p.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: "), p.stderr
    return lines[0]


def fits_80(text):
    long = [line for line in text.splitlines() if len(line.rstrip()) > 80]
    assert not long, long


NEW = ["slider", "slotted", "rocker", "structure"]


def examples(command):
    """The examples of a command's --help, from its docstring (the rendered help wraps lines)."""
    from pumplink.cli import app

    cb = next(c.callback for c in app.registered_commands if (c.name or c.callback.__name__) == command)
    return [e.split() for e in re.findall(r"Example: \[bold\](pumplink .+?)\[/\]", cb.__doc__)]


@pytest.mark.parametrize("command", [*NEW, "force", "batch"])
def test_help_examples_run(command, tmp_path):
    shutil.copytree(ROOT / "configs", tmp_path / "configs")
    shutil.copytree(ROOT / "examples", tmp_path / "examples")
    found = examples(command)
    assert found, command
    for ex in found:
        if ex[1] != command or "pump.toml" in ex:  # force's first example needs `pumplink init`
            continue
        p = run(*ex[1:], cwd=tmp_path)
        assert "Traceback" not in p.stderr, p.stderr
        allowed = (0,) if command in NEW else (0, 1)
        assert p.returncode in allowed, (ex, p.stderr)


@pytest.mark.parametrize(
    "args",
    [
        ["slider", "--stroke", "0.1", "--rod-ratio", "4", "--time-ratio", "1.2"],
        ["slider", "--stroke", "0.1", "--rod-ratio", "4"],
        ["slotted", "--time-ratio", "1.5", "--stroke", "0.3"],
        ["rocker", "--time-ratio", "1.25", "--swing", "50", "--rocker", "0.3", "--frame", "0.4"],
        ["structure", "configs/mechanisms/six-link.toml"],
        ["force", "examples/piston-pump.toml"],
        ["batch", "configs/grids/piston-bore.toml"],
    ],
)
def test_tables_fit_80_columns(args):
    p = run(*args)
    assert p.returncode in (0, 1), p.stderr
    fits_80(p.stdout)
    assert "\x1b" not in p.stdout


def test_slider_json_matches_the_request():
    p = run("slider", "--stroke", "0.1", "--rod-ratio", "4", "--time-ratio", "1.2", "--format", "json")
    out = json.loads(p.stdout)
    assert p.returncode == 0 and out["simulation_agrees"]
    assert out["indicators"]["time_ratio"]["simulated"] == pytest.approx(1.2, rel=1e-12)
    assert out["indicators"]["stroke"]["simulated"] == pytest.approx(0.1, rel=1e-12)


@pytest.mark.parametrize(
    "args, words",
    [
        (["slider", "--stroke", "1", "--rod-ratio", "3", "--time-ratio", "2"], "below 2"),
        (["slider", "--stroke", "1", "--rod-ratio", "1.5", "--offset-ratio", "0.5"], "longer than crank"),
        (["slotted", "--time-ratio", "1", "--stroke", "0.3"], "K = 1"),
        (["slotted", "--time-ratio", "1.5", "--stroke", "0.3", "--frame", "1"], "cannot hold"),
        (
            ["rocker", "--time-ratio", "1.25", "--swing", "50", "--rocker", "0.3", "--frame", "3"],
            "frame lengths",
        ),
        (["rocker", "--swing", "50", "--rocker", "0.3", "--pivot=0,0.1"], "one side"),
    ],
)
def test_outside_realisability_one_sentence_exit_1(args, words):
    line = one_line_error(run(*args), 1)
    assert words in line
    assert run(*args).stdout == ""  # never a mechanism that cannot turn


@pytest.mark.parametrize(
    "args, words",
    [
        (["slider", "--stroke", "-1", "--rod-ratio", "3"], "--stroke"),
        (["slider", "--stroke", "1", "--rod-ratio", "3", "--time-ratio", "0.5"], "--time-ratio"),
        (["rocker", "--swing", "50", "--rocker", "0.3", "--pivot", "x"], "--pivot"),
        (["rocker", "--swing", "200", "--rocker", "0.3", "-k", "1.2"], "--swing"),
        (["structure", "configs/prototype.toml"], "not a mechanism file"),
        (["synth", "examples/piston-pump.toml"], "piston-pump spec"),
        (["force", "examples/piston-pump.toml", "--plot", "p.png"], "--plot"),
    ],
)
def test_bad_input_one_line_exit_2(args, words):
    assert words in one_line_error(run(*args), 2)


def test_structure_shipped_configs():
    six = json.loads(run("structure", "configs/mechanisms/six-link.toml", "-f", "json").stdout)
    assert (six["moving_links"], six["lower_pairs"], six["higher_pairs"], six["mobility"]) == (5, 7, 0, 1)
    assert [g["links"] for g in six["groups"]] == [["2", "3"], ["4", "5"]]
    assert [g["dyad_type"] for g in six["groups"]] == ["RRR", "RRP"]
    dp = json.loads(run("structure", "configs/mechanisms/double-parallelogram.toml", "-f", "json").stdout)
    assert (dp["formula_mobility"], dp["redundant_constraints"], dp["mobility"]) == (0, 1, 1)


def test_structure_errors_name_the_key(tmp_path):
    f = tmp_path / "m.toml"
    f.write_text('frame = "0"\nlinks = ["0", "1"]\n[joints]\nA = { kind = "hinge", links = ["0", "1"] }\n')
    assert "joints.A.kind" in one_line_error(run("structure", f), 2)
    f.write_text(
        'frame = "0"\nlinks = ["0", "1", "2"]\n[joints]\nA = { kind = "revolute", links = ["0", "1"] }\n'
        'B = { kind = "revolute", links = ["1", "2"] }\nC = { kind = "revolute", links = ["2", "0"] }\n'
    )
    p = run("structure", f)  # a triangle: W = 0, a structure
    assert p.returncode == 1 and "NOT DECOMPOSED" in p.stdout


def test_piston_force_and_batch():
    out = json.loads(run("force", "examples/piston-pump.toml", "--summary", "-f", "json").stdout)
    assert out["pass"] and out["verdict"] == "PASS" and out["mechanism"] == "crank-slider"
    p = run("batch", "configs/grids/piston-bore.toml", "-f", "json")
    rows = json.loads(p.stdout)
    assert p.returncode == 1 and rows["total"] == 8 and rows["failed"] == 3
    assert run("batch", "configs/grids/piston-bore.toml", "--fail-on", "none").returncode == 0
    line = one_line_error(run("batch", "configs/grids/piston-bore.toml", "configs/prototype.toml"), 2)
    assert "separate runs" in line
