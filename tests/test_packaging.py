"""The source distribution stands on its own: it carries every file of the repository that the
tests, examples and docs need, its test suite collects from the unpacked archive, and a slice of
it runs there."""

from __future__ import annotations

import os
import re
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


#: A handful of the suite, run from the unpacked sdist: the golden tables through the CLI (the
#: configs, the golden files and the entry point), the JSON Schemas against the docs, and a
#: 50-digit reference check (the crank-rocker's).
SDIST_SLICE = (
    "tests/test_golden.py::test_rendered_table_matches_golden",
    "tests/test_schema.py",
    "tests/mechanisms/test_crank_rocker.py::test_seed_example_matches_high_precision_reference",
)


def _pytest_in(tree: Path, *args: str) -> subprocess.CompletedProcess:
    env = {**os.environ, "PYTHONPATH": str(tree)}
    return subprocess.run(
        [sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", "-p", "no:xdist", *args],
        cwd=tree,
        env=env,
        capture_output=True,
        text=True,
        timeout=900,
    )


def test_sdist_test_suite_slice_runs(sdist):
    """From the unpacked sdist, importing pumplink from the sdist itself, :data:`SDIST_SLICE`
    passes.  That the sdist holds every file the whole suite needs is
    test_sdist_carries_every_file_the_suite_needs; the whole suite is `make test`'s job in the
    repository (rerunning it from the sdist took a tenth of the suite's time, collecting it alone
    11 s)."""
    p = _pytest_in(sdist, *SDIST_SLICE)
    assert p.returncode == 0, p.stdout[-3000:]
    assert re.search(r"\b(\d+) passed\b", p.stdout) and "failed" not in p.stdout and "error" not in p.stdout


def test_the_all_extra_pulls_every_optional_feature():
    """`pip install 'pumplink[all]'` (the README's Quick start) installs every optional feature:
    each requirement of every other extra except ``test`` (the suite's tools) and ``bench``
    (pylinkage and numba, only for the benchmarks' comparison) is in ``all``, and ``all`` holds
    nothing else."""
    import tomllib

    extras = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["project"][
        "optional-dependencies"
    ]
    features = {name: set(reqs) for name, reqs in extras.items() if name not in ("all", "test", "bench")}
    assert {"plot", "dxf", "dask", "parquet"} <= set(features)
    assert set(extras["all"]) == set().union(*features.values())
