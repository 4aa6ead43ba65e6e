"""The CLI's contract under abuse: one line on stderr, the right exit code, no traceback.

Every case here is a class of input that once produced a traceback, a multi-line usage panel, a
wrong exit code or a clobbered file.  The expected behaviour is the contract in README.md
(exit codes 0/1/2/130, one-line errors, atomic and device-safe outputs, bounded inputs).
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).parents[2]
CMD = [sys.executable, "-m", "pumplink"]


def env() -> dict:
    e = {k: v for k, v in os.environ.items() if k not in ("FORCE_COLOR", "NO_COLOR", "COLUMNS")}
    e["PYTHONIOENCODING"] = "utf-8"
    return e


def run(*args, cwd=ROOT, stdout=subprocess.PIPE, timeout=120) -> subprocess.CompletedProcess:
    return subprocess.run(
        [*CMD, *map(str, args)],
        stdout=stdout,
        stderr=subprocess.PIPE,
        env=env(),
        cwd=cwd,
        timeout=timeout,
        encoding="utf-8",
        errors="replace",
    )


def one_error_line(p: subprocess.CompletedProcess, code: int = 2) -> str:
    """Exit ``code``, nothing on stdout, exactly one printable line on stderr; return it."""
    assert p.returncode == code, (p.returncode, p.stdout, p.stderr)
    assert not p.stdout, p.stdout
    assert "Traceback" not in p.stderr, p.stderr
    lines = p.stderr.strip("\n").split("\n")
    assert len(lines) == 1 and lines[0].startswith("error: "), p.stderr
    assert "\x1b" not in lines[0] and "\r" not in lines[0], repr(lines[0])
    return lines[0]


# ----------------------------------------------------------------------------- option errors
@pytest.mark.parametrize(
    "args,words",
    [
        (["force", "--samples", "0"], ["--samples 0", ">= 1", "pumplink force --help"]),
        (["force", "--speed", "nan"], ["--speed nan", "not a finite number"]),
        (["force", "--speed", "inf"], ["--speed inf", "not a finite number"]),
        (["force", "--format", "xml"], ["--format xml", "'table', 'json', 'csv'"]),
        (["force", "--bogus"], ["No such option: --bogus", "pumplink force --help"]),
        (["force", "--samples=abc"], ["--samples abc", "not a valid integer"]),
        (["batch", "--workers", "1000", "configs"], ["--workers 1000", "<= 256"]),
        (["synth"], ["Missing argument", "pumplink synth --help"]),
        (["nonsense"], ["No such command", "nonsense"]),
    ],
)
def test_option_errors_are_one_line_like_spec_errors(args, words):
    line = one_error_line(run(*args))
    for w in words:
        assert w in line, line
    # `--speed nan` once said "less than or equal to 7200": NaN fails every comparison
    assert "7200" not in line or "nan" not in line


def test_an_option_value_with_control_characters_is_escaped():
    line = one_error_line(run("force", "--samples", "1\x1b[2J\n2"))
    assert "\\x1b[2J\\n2" in line


def test_pumplink_alone_prints_the_help_and_exits_2():
    p = run()
    assert p.returncode == 2 and "Usage" in p.stdout and "Traceback" not in p.stderr


# ----------------------------------------------------------------------------- full disk
@pytest.mark.parametrize("fmt", ["table", "json", "csv"])
def test_a_full_disk_on_stdout_is_one_line_exit_2(fmt):
    with open("/dev/full", "w") as full:
        p = run("force", "--summary", "--format", fmt, stdout=full)
    assert p.returncode == 2, p.stderr
    assert p.stderr.count("\n") == 1 and "No space left on device" in p.stderr, p.stderr
