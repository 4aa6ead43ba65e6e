"""A piston-pump grid is a batch like a rope pump's: the same runner, the same options.

`pumplink batch` on a crank-slider grid with `--scheduler local:2`, `--format parquet`, `--junit`
and `--chunk K/N` gives what one process gives (`--workers 1`), byte for byte; its rows are those
of `pumplink force` on each variant, and the one `--fail-on` rule decides the exit code.
"""

from __future__ import annotations

import csv
import io
import json
import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
CMD = [sys.executable, "-m", "pumplink"]
EXAMPLE = (ROOT / "examples" / "piston-pump.toml").as_posix()

# 4 x 3 x 2 = 24 variants: bores that pass and fail 100 N, a rod too short for the crank
# (infeasible), and a flywheel on half of them (the flywheel model decides those)
GRID = f"""\
name = "piston-grid"
base = "{EXAMPLE}"
[vary]
"piston.bore" = [0.04, 0.05, 0.063, 0.075]
"crank_slider.rod" = [0.05, 0.25, 0.4]
"operator.speed" = [180, 300]
"""
FLYWHEEL = GRID.replace('"operator.speed"', '"wheel.inertia" = [0.02, 0.2]\n"operator.speed"')


def pumplink(*args, cwd=ROOT) -> subprocess.CompletedProcess:
    return subprocess.run([*CMD, *map(str, args)], cwd=cwd, capture_output=True, text=True, timeout=300)


@pytest.fixture(scope="module")
def grids(tmp_path_factory) -> dict[str, Path]:
    folder = tmp_path_factory.mktemp("piston")
    out = {}
    for name, text in (("plain", GRID), ("flywheel", FLYWHEEL)):
        out[name] = folder / f"{name}.toml"
        out[name].write_text(text)
    return out


def _run(tmp_path: Path, grid, tag: str, *opts) -> dict[str, bytes]:
    """CSV, JSON, Parquet and JUnit of one run of ``grid`` (a path or a tuple of paths, one run)
    with the given options; their bytes by format."""
    grid = grid if isinstance(grid, tuple) else (grid,)
    files = {}
    for fmt in ("csv", "json", "parquet"):
        out = tmp_path / f"{tag}.{fmt}"
        junit = tmp_path / f"{tag}-{fmt}.xml"
        r = pumplink("batch", *grid, "--format", fmt, "--out", out, "--junit", junit, *opts)
        assert r.returncode in (0, 1), r.stderr
        files[fmt] = out.read_bytes()
        files[f"junit-{fmt}"] = junit.read_bytes()
    return files


def test_a_piston_grid_on_dask_gives_the_one_process_output_byte_for_byte(grids, tmp_path):
    """Both grids in one run: the plain grid (quasi-static) and the flywheel grid (the flywheel
    model decides).  On a local cluster as on one process: the CSV (every row at full precision)
    and its JUnit report the same bytes, and with ``--chunk 1/2`` the Parquet file the same table
    (its metadata names the writer) and its JUnit report the same bytes.  JSON renders the same
    rows (tests/batch/test_batch.py)."""
    import pyarrow.parquet as pq

    both = [grids["plain"], grids["flywheel"]]
    files = {}
    for tag, opts in (("one", ["--workers", "1"]), ("dask", ["--scheduler", "local:2"])):
        for fmt, extra in (("csv", []), ("parquet", ["--chunk", "1/2"])):
            out, junit = tmp_path / f"{tag}.{fmt}", tmp_path / f"{tag}-{fmt}.xml"
            r = pumplink("batch", *both, "--format", fmt, "--out", out, "--junit", junit, *extra, *opts)
            assert r.returncode in (0, 1), r.stderr
            files[tag, fmt] = out.read_bytes(), junit.read_bytes()
    assert files["one", "csv"] == files["dask", "csv"]
    assert files["one", "parquet"][1] == files["dask", "parquet"][1]  # the JUnit reports
    a, b = (pq.read_table(io.BytesIO(files[tag, "parquet"][0])) for tag in ("one", "dask"))
    assert a.equals(b) and a.num_rows == (24 + 48) // 2
    rows = list(csv.DictReader(io.StringIO(files["one", "csv"][0].decode())))
    assert len(rows) == 24 + 48 and {r["mechanism"] for r in rows} == {"crank-slider"}
    assert a.column("variant").to_pylist() == [r["variant"] for r in rows[:36]]  # the first half
    for kind, part in (("plain", rows[:24]), ("flywheel", rows[24:])):  # in the order given
        assert sum(r["feasible"] == "False" for r in part) == len(part) // 3  # rod 0.05 m < the crank
        if kind == "flywheel":
            assert {r["model"] for r in part if r["feasible"] == "True"} == {"flywheel"}


def test_the_parquet_rows_are_the_csv_rows(grids, tmp_path):
    import pyarrow.parquet as pq

    files = _run(tmp_path, grids["flywheel"], "x", "--workers", "1")
    table = pq.read_table(io.BytesIO(files["parquet"])).to_pylist()
    text = list(csv.DictReader(io.StringIO(files["csv"].decode())))
    assert len(table) == len(text) == 48
    for p, c in zip(table, text):
        for k, v in c.items():
            if v == "":
                assert p[k] is None, k
            elif isinstance(p[k], bool):
                assert str(p[k]) == v, k
            elif isinstance(p[k], float):
                assert p[k] == float(v), k
            else:
                assert p[k] == v, k


def test_chunks_of_a_piston_grid_partition_it(grids, tmp_path):
    whole = pumplink("batch", grids["plain"], "--format", "csv")
    parts = [pumplink("batch", grids["plain"], "--format", "csv", "--chunk", f"{k}/2") for k in (1, 2)]
    head, *rows = whole.stdout.splitlines()
    got = []
    for p in parts:
        h, *r = p.stdout.splitlines()
        assert h == head
        got += r
    assert got == rows and len(rows) == 24


def test_the_junit_file_names_each_variant_and_its_failure(grids, tmp_path):
    junit = tmp_path / "piston.xml"
    r = pumplink("batch", grids["plain"], "--junit", junit)
    assert r.returncode == 1  # some bores fail 100 N, some variants are infeasible
    cases = ET.parse(junit).getroot().iter("testcase")
    by_name = {c.get("name"): c for c in cases}
    assert len(by_name) == 24
    failed = {n for n, c in by_name.items() if c.find("failure") is not None}
    assert "piston-grid#00[bore=0.04 rod=0.05 speed=180]" in failed  # infeasible
    msg = by_name["piston-grid#00[bore=0.04 rod=0.05 speed=180]"].find("failure").get("message")
    assert msg.startswith("infeasible: rod 0.05 m is not longer than crank 0.05 m")
    table = pumplink("batch", grids["plain"])
    assert "Piston-pump variants" in table.stdout and table.returncode == 1


def test_each_row_is_pumplink_force_on_that_variant(grids, tmp_path):
    """The batch rows are the force JSON of each variant written out (the one evaluation)."""
    import tomli_w

    from pumplink.inputs.batch import load_batch, variant_spec

    rows = json.loads(pumplink("batch", grids["flywheel"], "--format", "json").stdout)["variants"]
    b = load_batch(grids["flywheel"])
    for i in (1, 9, 22):
        spec = tmp_path / f"v{i}.toml"
        spec.write_text(tomli_w.dumps(variant_spec(b, i)))
        one = json.loads(pumplink("force", spec, "--summary", "--format", "json").stdout)
        row = dict(rows[i])
        assert row.pop("variant") == one.pop("name")
        for k in ("explain", "verify", "strict"):
            one.pop(k, None)
        assert row == one
