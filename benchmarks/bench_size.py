"""`pumplink size` for heads 5, 10, 20 and 35 m and every operator profile: the time of each answer,
the cadence (wheel turns a minute) and rope speed it recommends, and the share of Q* it reaches (the
flow the operator's sustained power lifts at that head).

Each answer runs the real command in a subprocess (start-up included), once: the search is
seeded, so its answer does not change between runs; the time is one run's wall time.  Where a
design is found, `pumplink force` on the written spec must pass (exit 0) and give the same flow.

    .venv/bin/python benchmarks/bench_size.py [--heads 5,10,20,35] [--profiles men,women,...] [--smoke]

``--smoke``: head 5 m, the men's profile, one pipe bore (``--pipes 20mm``), no target judged
(benchmarks/_record.py).

Target: each answer in <= 30 s on this 2-core machine, with a cadence in the field's 30-60 turns a
minute and a rope speed in 0.6-1.8 m/s (docs/operators.md §6, docs/water.md §2a); aim for >= 80 %
of Q*, and where an answer falls below, its output names the limit that holds it back.
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from _record import SMOKE_HELP, machine, record, smoke

ROOT = Path(__file__).resolve().parents[1]
PUMPLINK = [sys.executable, "-m", "pumplink"]
PROFILES = ("men", "women", "children", "accessible")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--heads", default="5,10,20,35")
    ap.add_argument("--profiles", default=",".join(PROFILES))
    ap.add_argument("--smoke", action="store_true", help=SMOKE_HELP)
    args = ap.parse_args()
    heads = [5.0] if smoke() else [float(h) for h in args.heads.split(",")]
    profiles = ["men"] if smoke() else args.profiles.split(",")
    pipes = ["--pipes", "20mm"] if smoke() else []  # the smallest search: one bore
    print(f"pumplink size --head H --profile P ({machine()})")
    head = f"  {'head':>5} {'profile':<11} {'time':>7} {'cadence':>8} {'rope':>8}"
    head += f" {'flow':>12} {'share of Q*':>12}"
    print(head + "  what binds / holds it back")
    slowest = 0.0
    with tempfile.TemporaryDirectory() as tmp:
        for h in heads:
            for p in profiles:
                out = Path(tmp) / f"size-{h:g}-{p}.toml"
                cmd = [
                    *PUMPLINK,
                    "size",
                    "--head",
                    f"{h:g}",
                    "--profile",
                    p,
                    "--format",
                    "json",
                    "--write",
                    str(out),
                    *pipes,
                ]
                t0 = time.perf_counter()
                r = subprocess.run(cmd, capture_output=True, text=True, cwd=ROOT)
                wall = time.perf_counter() - t0
                slowest = max(slowest, wall)
                row = json.loads(r.stdout)
                if row["found"]:
                    force = subprocess.run(
                        [*PUMPLINK, "force", str(out), "--summary", "--format", "json"],
                        capture_output=True,
                        text=True,
                        cwd=ROOT,
                    )
                    checked = json.loads(force.stdout)
                    assert force.returncode == 0, (h, p, force.stderr)
                    assert abs(checked["flow_l_min"] - row["flow_l_min"]) <= 1e-9 * row["flow_l_min"]
                    what = ", ".join(row["binding"]) or "-"
                    share = row["flow_share"]
                    flow = row["flow_l_min"]
                    turns, rope = row["cadence_per_min"], row["rope_speed_m_s"]
                    print(
                        f"  {h:>5g} {p:<11} {wall:>6.1f}s {turns:>5.1f}/min {rope:>4.2f} m/s "
                        f"{flow:>7.1f} l/min {share:>11.0%}  {what}"
                    )
                    what_holds = f"binds: {what}"
                    record(
                        f"size --head {h:g} --profile {p}, cadence",
                        turns,
                        "/min",
                        "30-60 /min",
                        30.0 <= turns <= 60.0,
                        what_holds,
                    )
                    record(
                        f"size --head {h:g} --profile {p}, rope speed",
                        rope,
                        "m/s",
                        "0.6-1.8 m/s",
                        0.6 <= rope <= 1.8,
                        what_holds,
                    )
                    name = f"size --head {h:g} --profile {p}, share of Q*"
                    note = f"{wall:.1f} s, {flow:.1f} l/min; binds: {what}"
                    record(name, share, "", ">= 0.80", share >= 0.80, note)
                else:
                    print(
                        f"  {h:>5g} {p:<11} {wall:>6.1f}s {'-':>8} {'-':>8} {'none':>12} {'-':>12}  "
                        f"{row['reason']}"
                    )
                    record(
                        f"size --head {h:g} --profile {p}, share of Q*",
                        0.0,
                        "",
                        ">= 0.80",
                        False,  # no design: the aim is missed, whatever the note says holds it back
                        f"{wall:.1f} s, none: {row['reason']}",
                    )
    record("size, slowest answer", slowest, "s", "<= 30 s", slowest <= 30.0)


if __name__ == "__main__":
    main()
