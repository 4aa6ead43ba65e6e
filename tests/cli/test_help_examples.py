"""Every example in every --help text and in the README's shell blocks runs, in a temporary copy
of the repository's configs and examples (never over a tracked file), with the exit code its
text implies and an output that answers it (:func:`check_output`: the files it names are
written, JSON parses, the spec's name, the values given and the verdict's word are printed).

A command whose output the README or a docs/ page quotes in a marked output block is run, and
its whole output compared, by tests/test_docs_outputs.py; it is not run a second time here (the
slow ones, ``size`` and ``tolerance``, take tens of seconds)."""

from __future__ import annotations

import json
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
from rich.cells import cell_len

from examples import QUOTED, help_examples, readme_examples

ROOT = Path(__file__).resolve().parents[2]
BIN = Path(sys.executable).parent


#: The exit code each example's text implies (0 PASS or written; 1 FAIL), by its first words.
EXPECTED_FAIL = (
    "pumplink force examples/well-12m-flywheel.toml",  # the 12 m well fails at any speed (its comments)
    "pumplink speed examples/well-12m-flywheel.toml",
    "pumplink batch configs/grids/piston-bore.toml",  # 3 of 8 bores fail
)


def _workdir(d: Path) -> Path:
    for name in ("configs", "examples"):
        shutil.copytree(ROOT / name, d / name, symlinks=False)
    return d


@pytest.fixture(scope="module")
def initial_spec(tmp_path_factory) -> Path:
    """The ./pump.toml the force examples edit, as `pumplink init pump.toml` writes it (once)."""
    d = tmp_path_factory.mktemp("init")
    subprocess.run([BIN / "pumplink", "init", "pump.toml"], cwd=d, check=True, capture_output=True)
    return d / "pump.toml"


@pytest.fixture
def workdir(tmp_path, initial_spec) -> Path:
    """A fresh copy of configs/ and examples/, with the ./pump.toml the force example edits."""
    d = _workdir(tmp_path)
    shutil.copyfile(initial_spec, d / "pump.toml")
    return d


def _run(line: str, cwd: Path) -> subprocess.CompletedProcess:
    env = {
        **os.environ,
        "PATH": f"{BIN}{os.pathsep}{os.environ.get('PATH', '')}",
        "COLUMNS": "80",
        "NO_COLOR": "1",
    }
    return subprocess.run(line, shell=True, cwd=cwd, env=env, capture_output=True, text=True, timeout=600)


#: Options and arguments that name a file the example writes.
WRITES = re.compile(r"(?:--out|--plot|--samples-plot|--junit|--write|>)\s+(\S+)")
#: The first line of each spec file the examples use: its name, printed by the commands.
NAMES = {
    "configs/prototype.toml": "Prototype",
    "configs/village-10m.toml": "Village well, 10 m head",
    "examples/well-12m-flywheel.toml": "Well, 12 m head",
    "examples/piston-pump.toml": "Piston hand pump, 10 m well",
}
#: Mechanism commands echo the values they were given ("given: ... K = 1.25").
ECHOES = ("slider", "slotted", "rocker", "transmission")


def check_output(line: str, p: subprocess.CompletedProcess, cwd: Path, expected: int) -> None:
    """What a reader of the example expects to see, checked cheaply from the command line itself.

    Each file the line writes exists and is not empty; JSON output parses; a command run on a
    shipped spec names it (table output); a mechanism command echoes every number it was given;
    a force, optimize or batch table says PASS or FAIL as the exit code implies; a failing
    mechanism command says why in one line.
    """
    words = line.split()
    cmd = words[1] if len(words) > 1 else ""
    for target in WRITES.findall(line):
        f = cwd / target
        assert f.is_file() and f.stat().st_size > 0, (line, target)
    if cmd == "init" and len(words) > 2 and words[2].endswith(".toml"):
        assert (cwd / words[2]).stat().st_size > 0, line
    json_out = "--format json" in line or "-f json" in line
    if ">" in line:  # the output went to that file
        if json_out:
            json.loads((cwd / WRITES.findall(line)[-1]).read_text(encoding="utf-8"))
        return
    if json_out:
        json.loads(p.stdout)
    if expected == 1 and cmd in ECHOES:
        if p.stdout == "":  # no such mechanism: one line on stderr
            assert p.stderr.startswith("error: ") and p.stderr.count("\n") == 1, line
            return
        assert "VERDICT: FAIL" in p.stdout, line  # a mechanism that would jam: judged, exit 1
    table = re.search(r"(?:--format|-f) (?:json|csv|parquet)", line) is None
    if not table or cmd in ("schema", "init", "draw", "template", "report", "sheet") or cmd.startswith("-"):
        return
    # a newcomer's 80-column terminal (as tests/cli/test_80_columns.py, which leaves these out)
    for text in (p.stdout + p.stderr).splitlines():
        assert cell_len(text) <= 80 and not re.search(r"\S…", text), (line, text)
    for path, name in NAMES.items():
        if path in words and cmd != "batch":
            assert name in " ".join(p.stdout.split()), (line, name)
    if cmd in ECHOES:
        for value in re.findall(r"--[a-z-]+[ =](-?[0-9.]+)(?:\s|$)", line):
            assert re.search(rf"(?<![0-9.]){re.escape(value)}(?![0-9])", p.stdout), (line, value)
    if cmd in ("force", "optimize", "batch") and "piston" not in line:
        assert ("FAIL" if expected else "PASS") in p.stdout, (line, p.stdout[-300:])


def test_quoted_commands_are_found():
    """The marked blocks are read (else the help and README examples they cover would go unrun)."""
    assert "pumplink size --head 12 --profile women --write well.toml" in QUOTED
    assert any(c.startswith("pumplink tolerance configs/village-10m.toml") for c in QUOTED)


@pytest.mark.parametrize(
    ("command", "example"),
    [(c, e) for c, e in help_examples() if e not in QUOTED],
    ids=lambda x: x if " " not in x else None,
)
def test_every_help_example_runs(command, example, workdir):
    before = {p: p.stat().st_mtime_ns for p in (ROOT / "docs").glob("*")}
    p = _run(
        example.replace(
            "pump.toml && pumplink force pump.toml", "pump.toml --force && pumplink force pump.toml"
        ),
        workdir,
    )
    expected = 1 if example.startswith(EXPECTED_FAIL) else 0
    assert p.returncode == expected, (example, p.stderr[-500:])
    assert "Traceback" not in p.stderr
    assert {p: p.stat().st_mtime_ns for p in (ROOT / "docs").glob("*")} == before  # no tracked file touched
    check_output(example.split(" && ")[-1], p, workdir, expected)


def test_every_readme_command_runs_in_order(tmp_path):
    """The README's shell lines, in order in one folder (the quick start writes my-pump.toml first);
    those whose output a marked block quotes are checked there."""
    d = _workdir(tmp_path)
    lines = readme_examples()
    assert len(lines) >= 6
    for line in (line for line in lines if line not in QUOTED):
        p = _run(line, d)
        expected = 1 if line.startswith(EXPECTED_FAIL) else 0
        assert p.returncode == expected, (line, p.stderr[-500:])
        assert "Traceback" not in p.stderr
        check_output(line, p, d, expected)


def readme_inline_examples() -> list[str]:
    """The concrete `pumplink ...` commands quoted inline in the README's prose: every one with an
    argument or option, except those with placeholders (SPEC, FILE, N, [...], ...) or shell
    templating, which are syntax summaries rather than commands, and those a marked output block
    quotes (tests/test_docs_outputs.py runs them)."""
    text = (ROOT / "README.md").read_text(encoding="utf-8")
    out = []
    for span in dict.fromkeys(" ".join(m.split()) for m in re.findall(r"`(pumplink\s[^`]*)`", text)):
        words = span.split()
        if len(words) < 2 or len(words) == 2 and not words[1].startswith("-"):
            continue  # a command's name (`pumplink batch`), not an example
        if re.search(r"\.\.\.|\[|\$\{|\b[A-Z][A-Z_]+\b|\|", span) or span in QUOTED:
            continue
        out.append(span)
    return out


#: Inline README commands that a FAIL (exit 1) is what the text says.
INLINE_FAIL = (
    *EXPECTED_FAIL,
    "pumplink slider --stroke 1 --rod-ratio 3 --time-ratio 2",  # outside the realisability condition
    "pumplink rocker --time-ratio 1.25 --swing 50 --rocker 0.3 --frame 0.4",  # 28.5°: it would jam
)


def test_readme_inline_examples_are_found():
    found = readme_inline_examples()
    assert "pumplink init village.toml --example village-10m" in found
    assert "pumplink rocker --time-ratio 1.25 --swing 50 --rocker 0.3 --frame 0.4" in found
    assert not any("SPEC" in s for s in found)
    assert len(inline_only()) < len(found)  # some are help examples too, run once


def inline_only() -> list[str]:
    """The inline examples that are not also a help example (those run, with the same exit code
    and checks, in :func:`test_every_help_example_runs`)."""
    helps = {example for _, example in help_examples()}
    return [line for line in readme_inline_examples() if line not in helps]


@pytest.mark.parametrize("line", inline_only())
def test_every_readme_inline_example_runs(line, workdir):
    """Each inline example, alone in a fresh copy (with a docs/ folder for the ones that write
    the README's pictures), gives the exit code its text implies, no traceback and the output
    :func:`check_output` expects."""
    (workdir / "docs").mkdir(exist_ok=True)
    # in bash with HOME in the copy: `pumplink --install-completion` edits that HOME's .bashrc.
    # Typer finds the shell by walking up the process tree, so bash must stay the command's parent:
    # `bash -c CMD` would exec a lone command in its own place, and the shell found would be the
    # one that started pytest (`sh -c` under make: "Shell sh not supported"); `; exit $?` keeps it.
    env = {
        **os.environ,
        "PATH": f"{BIN}{os.pathsep}{os.environ.get('PATH', '')}",
        "COLUMNS": "80",
        "NO_COLOR": "1",
        "HOME": str(workdir),
    }
    p = subprocess.run(
        ["bash", "-c", f"{line}; exit $?"], cwd=workdir, env=env, capture_output=True, text=True, timeout=600
    )
    expected = 1 if line.startswith(INLINE_FAIL) else 0
    assert p.returncode == expected, (line, p.stderr[-500:])
    assert "Traceback" not in p.stderr
    check_output(line, p, workdir, expected)
    if "--install-completion" in line:
        assert "bash completion installed" in p.stdout
        assert "_PUMPLINK_COMPLETE" in (workdir / ".bash_completions" / "pumplink.sh").read_text(
            encoding="utf-8"
        )
        assert "pumplink.sh" in (workdir / ".bashrc").read_text(encoding="utf-8")
    if "--show-completion" in line:
        assert "_PUMPLINK_COMPLETE=complete_bash" in p.stdout  # the script for bash, the shell it runs in
    if line == "pumplink --help":
        assert all(c in p.stdout for c in ("force", "batch", "transmission", "Usage"))
