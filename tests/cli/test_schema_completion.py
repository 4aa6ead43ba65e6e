"""`pumplink schema` and shell completion, through the installed console script."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import tomllib
from pathlib import Path

import jsonschema

ROOT = Path(__file__).resolve().parents[2]
EXE = shutil.which("pumplink", path=str(Path(sys.executable).parent))


def run(*args, env=None, cwd=None) -> subprocess.CompletedProcess:
    return subprocess.run(
        [EXE, *map(str, args)],
        capture_output=True,
        text=True,
        timeout=120,
        env={**os.environ, **(env or {})},
        cwd=cwd,
    )


def test_schema_to_stdout_validates_the_prototype():
    p = run("schema")
    assert p.returncode == 0, p.stderr
    doc = json.loads(p.stdout)
    spec = tomllib.loads((ROOT / "configs/prototype.toml").read_text(encoding="utf-8"))
    jsonschema.validate(spec, doc)
    spec["linkage"]["swing"] = 200.0
    assert not jsonschema.Draft202012Validator(doc).is_valid(spec)


def test_schema_out_file(tmp_path):
    out = tmp_path / "batch.schema.json"
    p = run("schema", "batch", "--out", out)
    assert p.returncode == 0, p.stderr
    assert p.stdout == "" and "#:schema batch.schema.json" in p.stderr
    grid = tomllib.loads((ROOT / "configs/grids/design-space.toml").read_text(encoding="utf-8"))
    jsonschema.validate(grid, json.loads(out.read_text(encoding="utf-8")))


def test_schema_bad_kind_and_bad_path_are_one_line(tmp_path):
    for args in (("schema", "grid"), ("schema", "--out", tmp_path / "no" / "x.json")):
        p = run(*args)
        assert p.returncode == 2 and p.stdout == ""
        assert p.stderr.count("\n") == 1 and p.stderr.startswith("error: "), p.stderr


def test_bash_completion_of_commands_and_options():
    env = {"_PUMPLINK_COMPLETE": "complete_bash", "COMP_WORDS": "pumplink fo", "COMP_CWORD": "1"}
    p = run(env=env)
    assert p.returncode == 0 and p.stdout.split() == ["force"], (p.stdout, p.stderr)
    env.update(COMP_WORDS="pumplink force --spe", COMP_CWORD="2")
    assert run(env=env).stdout.split() == ["--speed"]


def test_completion_script_is_offered():
    """`--show-completion` prints the script for the shell it runs in, which Typer finds by walking
    up the process tree: run it from bash (as its parent, `; exit $?` keeps bash from exec'ing
    it away), so that the shell that started pytest (sh under make) does not decide."""
    p = subprocess.run(
        ["bash", "-c", f"{EXE} --show-completion; exit $?"], capture_output=True, text=True, timeout=120
    )
    assert p.returncode == 0 and "_PUMPLINK_COMPLETE=complete_bash" in p.stdout, p.stderr
