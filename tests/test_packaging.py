"""The source distribution stands on its own: it carries every file of the repository that the
tests, examples and docs need, and its test suite runs from the unpacked archive."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import tarfile
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]

#: Folders whose every file the sdist must carry (the suite reads them).
NEEDED = ("tests", "configs", "examples", "docs", "pumplink")


def _repository_files() -> set[str]:
    """Tracked files (git), or every file of the needed folders when run from an sdist."""
    if (ROOT / ".git").exists() and shutil.which("git"):
        out = subprocess.run(["git", "ls-files"], cwd=ROOT, capture_output=True, text=True, check=True)
        files = set(out.stdout.split())
    else:
        files = {str(p.relative_to(ROOT)) for d in NEEDED for p in (ROOT / d).rglob("*") if p.is_file()}
    return {
        f for f in files if f.split("/")[0] in NEEDED and "__pycache__" not in f and not f.endswith(".pyc")
    } | {"README.md", "pyproject.toml", "Makefile", "LICENSE"}


@pytest.fixture(scope="module")
def sdist(tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp("sdist")
    p = subprocess.run(
        [sys.executable, "-m", "build", "--sdist", "--outdir", str(out), str(ROOT)],
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert p.returncode == 0, p.stderr[-2000:]
    (archive,) = out.glob("pumplink-*.tar.gz")
    with tarfile.open(archive) as tar:
        tar.extractall(out, filter="data")
    (tree,) = (d for d in out.iterdir() if d.is_dir())
    return tree


def test_sdist_carries_every_file_the_suite_needs(sdist):
    have = {str(p.relative_to(sdist)) for p in sdist.rglob("*") if p.is_file() or p.is_symlink()}
    missing = sorted(_repository_files() - have)
    assert missing == [], missing[:20]


def test_sdist_test_suite_runs(sdist):
    """A slice of the suite (specs, schemas, golden tables, the reference) from the unpacked sdist,
    importing pumplink from the sdist itself."""
    env = {**os.environ, "PYTHONPATH": str(sdist)}
    p = subprocess.run(
        [
            sys.executable,
            "-m",
            "pytest",
            "-q",
            "-p",
            "no:cacheprovider",
            "tests/test_spec.py",
            "tests/test_schema.py",
            "tests/test_golden.py",
            "tests/mechanisms",
        ],
        cwd=sdist,
        env=env,
        capture_output=True,
        text=True,
        timeout=900,
    )
    assert p.returncode == 0, p.stdout[-3000:]
    assert " passed" in p.stdout and "failed" not in p.stdout
