"""The 100,000-variant quasi-static grid against the code before the one-evaluation restructure.

The grid varies rocker x swing x rope force (50 x 40 x 50) on the prototype at 360 crank samples,
CSV written, one process.  The same command runs on this checkout and on a pinned install of
commit 2cf593a (main before the restructure that made batch slower; ``make bench`` builds it in
build/base-2cf593a from this repository's own history), interleaved, so load from other
processes hits both alike; medians of ``--repeat`` runs of wall time, CPU time and peak memory.

    .venv/bin/python benchmarks/bench_grid_baseline.py [--repeat 5] [--base build/base-2cf593a] [--smoke]

``--smoke``: one run of this checkout on a 2 x 2 x 2 grid, the pinned install's side skipped (it
need not exist), no target judged (benchmarks/_record.py).

Target: this checkout's median wall time at most the baseline's (ratio <= 1.0).  The baseline's
CSV has fewer columns (it predates the verdict's checks); the figure compared is the whole run.
"""

from __future__ import annotations

import argparse
import json
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

from _record import SMOKE_HELP, machine, record, repeats, smoke

ROOT = Path(__file__).resolve().parents[1]
BASE_COMMIT = "2cf593a"

GRID = """\
base = "{base}"
[vary]
"linkage.rocker" = {{ start = 0.15, stop = 0.30, num = {rockers} }}
"linkage.swing" = {{ start = 40, stop = 80, num = {swings} }}
"load.rope_force" = {{ start = 20, stop = 65, num = {forces} }}
"""

WRAPPER = r"""
import json, resource, subprocess, sys, time
t = time.perf_counter()
r = subprocess.run(sys.argv[1:], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
wall = time.perf_counter() - t
u = resource.getrusage(resource.RUSAGE_CHILDREN)
print(json.dumps({"wall": wall, "cpu": u.ru_utime + u.ru_stime, "sys": u.ru_stime,
                  "maxrss_kb": u.ru_maxrss, "rc": r.returncode}))
"""


def measure(cmd: list[str]) -> dict:
    out = subprocess.run([sys.executable, "-c", WRAPPER, *cmd], capture_output=True, text=True, check=True)
    return json.loads(out.stdout)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--base", type=Path, default=ROOT / "build" / f"base-{BASE_COMMIT}")
    ap.add_argument("--smoke", action="store_true", help=SMOKE_HELP)
    args = ap.parse_args()
    base_python = args.base / ".venv" / "bin" / "python"
    pythons = {"this checkout": sys.executable}
    if smoke():
        print(
            f"smoke run: the pinned install of {BASE_COMMIT} is not run (its side of the comparison is "
            "skipped)"
        )
    elif not base_python.exists():
        raise SystemExit(
            f"no pinned install at {args.base}: run `make bench` (it builds one from {BASE_COMMIT})"
        )
    else:
        pythons[BASE_COMMIT] = str(base_python)
    sizes = (
        {"rockers": 2, "swings": 2, "forces": 2} if smoke() else {"rockers": 50, "swings": 40, "forces": 50}
    )
    n = sizes["rockers"] * sizes["swings"] * sizes["forces"]
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        grid = tmp / "grid.toml"
        grid.write_text(GRID.format(base=(ROOT / "configs" / "prototype.toml").as_posix(), **sizes))
        runs: dict[str, list[dict]] = {name: [] for name in pythons}
        for _ in range(repeats(args.repeat)):
            for name, python in pythons.items():
                out = tmp / f"{name.replace(' ', '-')}.csv"
                # -P: not this folder first on sys.path, where `-m pumplink` would import this
                # checkout's source whichever interpreter runs it (the pinned install's too)
                cmd = [python, "-P", "-m", "pumplink", "batch", str(grid), "--samples", "360"]
                cmd += ["--fail-on", "none"]
                r = measure([*cmd, "--format", "csv", "--out", str(out), "--workers", "1"])
                assert r["rc"] == 0, (name, r)
                assert sum(1 for _ in out.open()) == n + 1
                runs[name].append(r)
    print(f"{n:,}-variant grid (rocker x swing x rope force), 360 samples, one process; {machine()}")
    med = {}
    for name, rs in runs.items():
        med[name] = {k: statistics.median(r[k] for r in rs) for k in ("wall", "cpu", "sys")}
        med[name]["rss"] = max(r["maxrss_kb"] for r in rs) / 1024
        walls = ", ".join(f"{r['wall']:.2f}" for r in rs)
        m = med[name]
        print(
            f"  {name:>13}: median wall {m['wall']:.2f} s, CPU {m['cpu']:.2f} s (system {m['sys']:.2f} s), "
            f"peak RSS {m['rss']:.0f} MiB   [walls: {walls}]"
        )
    if BASE_COMMIT not in med:
        return
    ratio = med["this checkout"]["wall"] / med[BASE_COMMIT]["wall"]
    print(
        f"  ratio, this checkout / {BASE_COMMIT}: {ratio:.2f}x wall, "
        f"{med['this checkout']['rss'] / med[BASE_COMMIT]['rss']:.2f}x memory"
    )
    record(
        f"{n:,}-variant grid, wall time against {BASE_COMMIT} (same run, interleaved)",
        ratio,
        "x",
        "<= 1.0x",
        ratio <= 1.0,
        f"{med['this checkout']['wall']:.2f} s vs {med[BASE_COMMIT]['wall']:.2f} s; "
        f"{med['this checkout']['rss']:.0f} vs {med[BASE_COMMIT]['rss']:.0f} MiB",
    )


if __name__ == "__main__":
    main()
