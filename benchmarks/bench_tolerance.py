"""`pumplink tolerance` on 100,000 builds of configs/village-10m.toml at ±1 mm: the share that pass,
its time on one process and on a local Dask cluster of two (`--scheduler local:2`), and whether
both give the same numbers (they must: the builds are drawn per fixed chunk from the seed).

Each run is the real command in a subprocess (start-up included), once: the builds are seeded,
so the numbers do not change between runs; the time is one run's wall time.

    .venv/bin/python benchmarks/bench_tolerance.py [--samples 100000] [--hole 1mm] [--smoke]

``--smoke``: the least the command takes, 100 builds, of configs/prototype.toml (no ``[parts]``: the
cheapest builds), Dask with one worker (``local:1``), no target judged (benchmarks/_record.py).

Targets: local:2 faster than one process, and both outputs identical byte for byte.  The one
process's time is recorded without a target here: the village well carries ``[parts]``, so every
build also gets its pin and fatigue checks under full dynamics (blocks of builds at once); the
10,000-build run's target, against the code before, is benchmarks/bench_parts.py's.
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import time
from pathlib import Path

from _record import SMOKE_HELP, machine, record, result, smoke

ROOT = Path(__file__).resolve().parents[1]
PUMPLINK = [sys.executable, "-m", "pumplink"]
SPEC = "configs/village-10m.toml"


def run(*args: str) -> tuple[float, subprocess.CompletedProcess]:
    t0 = time.perf_counter()
    p = subprocess.run([*PUMPLINK, *args], capture_output=True, text=True, cwd=ROOT)
    wall = time.perf_counter() - t0
    if p.returncode not in (0, 1):
        raise SystemExit(f"pumplink {' '.join(args)} failed:\n{p.stderr}")
    return wall, p


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--samples", type=int, default=100_000)
    ap.add_argument("--hole", default="1mm")
    ap.add_argument("--smoke", action="store_true", help=SMOKE_HELP)
    args = ap.parse_args()
    spec = "configs/prototype.toml" if smoke() else SPEC
    dask = "local:1" if smoke() else "local:2"
    if smoke():
        args.samples = 100
    cmd = ["tolerance", spec, "--hole", args.hole, "--samples", str(args.samples), "--format", "json"]
    print(f"pumplink {' '.join(cmd)} ({machine()})")
    one_s, one = run(*cmd)
    two_s, two = run(*cmd, "--scheduler", dask)
    row = json.loads(one.stdout)
    share = row["builds_pass"]
    clean = row["builds_pass_without_warnings"]
    print(
        f"  builds that pass: {share['share']:.2%} ({share['low']:.2%}-{share['high']:.2%}, "
        f"{row['share_interval']}) of {share['builds']:,}; without warnings {clean['share']:.2%}"
    )
    print(f"  first-order estimate: {row['first_order_pass_share']:.2%}")
    peak = row["spread"]["peak_force_N"]
    print(
        f"  peak force: design {peak['nominal']:.2f} N, median {peak['median']:.2f} N, "
        f"5-95 % {peak['p5']:.2f}-{peak['p95']:.2f} N"
    )
    print(f"  allocation for {row['allocation']['target']:.0%}: {row['allocation']['words']}")
    same = one.stdout == two.stdout
    print(f"  one process {one_s:.1f} s; --scheduler {dask} {two_s:.1f} s; identical output: {same}")
    record(
        f"tolerance {spec} ±{args.hole}, {args.samples:,} builds: share that pass",
        share["share"],
        "",
        None,
        None,
        f"Wilson 95 % {share['low']:.4f}-{share['high']:.4f}; "
        f"first order {row['first_order_pass_share']:.4f}",
    )
    record(
        f"tolerance, {args.samples:,} builds, one process",
        one_s,
        "s",
        note=f"{one_s / args.samples * 1e3:.1f} ms a build, start-up included",
    )
    result(
        f"tolerance, {args.samples:,} builds, --scheduler {dask}",
        f"{two_s:.1f} s",
        "< one process",
        two_s < one_s,
        f"{one_s / two_s:.2f}x the one process",
        two_s,
        "s",
    )
    result(
        f"tolerance, {dask} output identical to one process",
        "yes" if same else "no",
        "identical",
        same,
        value=float(same),
        unit="",
    )


if __name__ == "__main__":
    main()
