"""`pumplink batch --format parquet`: the same rows as the CSV, typed, in a tenth of the space.

The CSV is the reference (its float cells are the shortest round-trip text of each value), so a
Parquet cell is right when printing it the CSV's way gives the CSV's cell: float64 values by
``repr``, booleans as True/False, null as the empty cell.
"""

from __future__ import annotations

import csv
import subprocess
import sys
import textwrap
from pathlib import Path

import pyarrow as pa
import pyarrow.parquet as pq
import pytest

from pumplink import batch as B
from pumplink.output import batchfiles as rb

ROOT = Path(__file__).resolve().parents[2]
PROTOTYPE = (ROOT / "configs" / "prototype.toml").as_posix()
VILLAGE = (ROOT / "configs" / "village-10m.toml").as_posix()

# Two files with different axes (each leaves the other's columns empty), every model, infeasible
# variants (L1 = 0) whose reasons hold commas, and a name that needs CSV quoting.
QS = f"""\
name = "qs, quoted"
base = "{PROTOTYPE}"
[vary]
"linkage.L1" = [0.0, 0.4]
"linkage.rocker" = {{ start = 0.15, stop = 0.3, num = 7 }}
"load.rope_force" = [30, 60, 90]
"""
FLY = f"""\
base = "{VILLAGE}"
[vary]
"wheel.mass" = [0.5, 4.0, 20.0]
"operator.speed" = [180, 540]
"linkage.L1" = [0.4, 0.0]
"""


def pumplink(*args) -> subprocess.CompletedProcess:
    cmd = [sys.executable, "-m", "pumplink", *map(str, args)]
    return subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True, timeout=120)


@pytest.fixture(scope="module")
def grids(tmp_path_factory) -> list[Path]:
    folder = tmp_path_factory.mktemp("grids")
    (folder / "qs.toml").write_text(QS)
    (folder / "fly.toml").write_text(FLY)
    return [folder / "qs.toml", folder / "fly.toml"]


def _cell(value) -> str:
    """A Parquet value as the CSV writes it."""
    if value is None:
        return ""
    if isinstance(value, bool):
        return str(value)
    return repr(value) if isinstance(value, float) else value


def _same_as_csv(table: pa.Table, csv_text: str) -> None:
    rows = list(csv.DictReader(csv_text.splitlines()))
    assert table.schema.names == list(rows[0])
    cols = table.to_pydict()
    assert table.num_rows == len(rows)
    bad = [(i, k, cols[k][i], r[k]) for i, r in enumerate(rows) for k in r if _cell(cols[k][i]) != r[k]]
    assert bad == []


def test_parquet_round_trips_to_the_csv_values(tmp_path, grids):
    """The real entry point, both formats of the same run: every cell equal."""
    args = ("batch", *grids, "--fail-on", "none", "--samples", 90)
    rc = pumplink(*args, "--format", "csv")
    rp = pumplink(*args, "--format", "parquet", "--out", tmp_path / "rows.parquet")
    assert rc.returncode == rp.returncode == 0, rp.stderr
    assert rp.stderr.count("\n") == 1 and rp.stderr.endswith(f"wrote {tmp_path / 'rows.parquet'}\n")
    table = pq.read_table(tmp_path / "rows.parquet")
    _same_as_csv(table, rc.stdout)
    types = dict(zip(table.schema.names, table.schema.types))
    assert types["mean_force_N"] == types["linkage.rocker"] == types["wheel.mass"] == pa.float64()
    assert types["feasible"] == types["pass"] == pa.bool_()
    assert types["name"] == types["reason"] == types["check_power"] == pa.string()
    col = table.to_pydict()
    n_qs = 2 * 7 * 3
    assert col["wheel.mass"][:n_qs] == [None] * n_qs and col["linkage.rocker"][n_qs:] == [None] * 12
    qs = B.QUASI_STATIC_LABEL
    assert col["model"][:n_qs] == [qs] * n_qs and qs not in col["model"][n_qs:]
    assert col["name"][0].startswith("qs, quoted#")
    assert None in col["reason"] and any("," in r for r in col["reason"] if r)
    assert "" in col["failed"] and None not in col["failed"]  # an empty list, not a missing value


def test_row_groups_gather_chunks(tmp_path, grids, monkeypatch):
    """Chunks are gathered into row groups of PARQUET_ROWS (here 20) and still give every row once."""
    monkeypatch.setattr(rb, "PARQUET_ROWS", 20)
    batches = B.load_inputs(grids)
    vkeys = rb.varied_keys(batches)
    post = lambda b, c: rb.render_chunk(b, c, "parquet", vkeys, B.FAIL_CHECKS, False)  # noqa: E731
    out = tmp_path / "rows.parquet"
    rb.write_stream(batches, B.run(batches, 60, designs=8, post=post), 54, "parquet", out, None, (), 60)
    post_csv = lambda b, c: rb.render_chunk(b, c, "csv", vkeys, B.FAIL_CHECKS, False)  # noqa: E731
    rows_csv = tmp_path / "rows.csv"
    rb.write_stream(batches, B.run(batches, 60, post=post_csv), 54, "csv", rows_csv, None, (), 60)
    meta = pq.ParquetFile(out).metadata
    # tasks of 8 variants: 42 = 5 x 8 + 2, then 12 = 8 + 4; row groups of 24, 26 and 4
    assert meta.num_rows == 54 and meta.num_row_groups == 3
    _same_as_csv(pq.read_table(out), rows_csv.read_text())


@pytest.mark.parametrize(
    "args,words",
    [
        ([PROTOTYPE, "--format", "parquet"], "--format parquet writes a binary file: give --out"),
        (["configs/grids/piston-bore.toml", "--format", "parquet"], "--format parquet writes a binary file"),
    ],
)
def test_parquet_needs_an_output_file(args, words):
    r = pumplink("batch", *args)
    assert r.returncode == 2 and r.stdout == "" and r.stderr.count("\n") == 1 and words in r.stderr, r.stderr


def test_without_pyarrow_parquet_says_how_to_install_it(tmp_path):
    code = textwrap.dedent(
        f"""
        import sys
        sys.modules["pyarrow"] = None
        from pumplink.cli import main
        main(["batch", {PROTOTYPE!r}, "--format", "parquet", "--out", {str(tmp_path / "x.parquet")!r}])
        """
    )
    r = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, timeout=60)
    assert r.returncode == 2 and r.stdout == "" and not (tmp_path / "x.parquet").exists()
    assert r.stderr == (
        "error: --format parquet needs pyarrow, which is not installed; "
        "install it with pip install 'pumplink[parquet]'\n"
    )
