"""The benchmarks' figures reach `make bench`'s one summary table (benchmarks/_record.py and
benchmarks/summary.py): every recorded figure appears once with its target and verdict, in an
80-column terminal, and a script run by hand (no PUMPLINK_BENCH_OUT) writes nothing."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
BENCH = ROOT / "benchmarks"

RECORDS = """
import sys
sys.path.insert(0, {bench!r})
from _record import record
record("pumplink force SPEC --summary, start-up", 0.213, "s", "<= 0.25 s", True, "1.9x `import numpy`")
record("flywheel least peak force, vectorised", 12345.6, "designs/s", ">= 20,000/s", False)
record("pylinkage / pumplink, 5 M positions", 4.26, "x")
"""


def _record_three(env: dict, cwd: Path = ROOT) -> None:
    code = RECORDS.format(bench=str(BENCH))
    subprocess.run([sys.executable, "-c", code], env=env, check=True, cwd=cwd)


def test_every_figure_in_one_table(tmp_path):
    out = tmp_path / "bench.jsonl"
    env = {**os.environ, "PUMPLINK_BENCH_OUT": str(out), "COLUMNS": "80", "NO_COLOR": "1"}
    _record_three(env)
    rows = [json.loads(line) for line in out.read_text().splitlines()]
    assert [r["name"] for r in rows] == [
        "pumplink force SPEC --summary, start-up",
        "flywheel least peak force, vectorised",
        "pylinkage / pumplink, 5 M positions",
    ]
    assert [r["met"] for r in rows] == [True, False, None] and rows[0]["value"] == 0.213
    p = subprocess.run(
        [sys.executable, str(BENCH / "summary.py"), str(out)],
        env=env,
        capture_output=True,
        text=True,
        check=True,
    )
    text = p.stdout
    assert max(len(line) for line in text.splitlines()) <= 80
    flat = " ".join(text.split())
    for expected in (
        "0.213 s",
        "<= 0.25 s",
        "12,346 designs/s",
        ">= 20,000/s",
        "4.3x",
        "1.9x `import numpy`",
    ):
        assert expected in flat, expected
    assert "1 of 2 targets met:" in flat
    assert "not met: flywheel least peak force, vectorised" in flat
    assert flat.count("yes") == 1 and flat.count("NO") == 1


def test_nothing_written_without_the_variable(tmp_path):
    env = {k: v for k, v in os.environ.items() if k != "PUMPLINK_BENCH_OUT"}
    _record_three({**env, "HOME": str(tmp_path)}, cwd=tmp_path)  # a stray file would land here
    assert list(tmp_path.iterdir()) == []
    p = subprocess.run([sys.executable, str(BENCH / "summary.py")], env=env, capture_output=True, text=True)
    assert p.returncode == 2 and "PUMPLINK_BENCH_OUT" in p.stderr
