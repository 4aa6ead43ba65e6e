"""The 100,000-variant quasi-static grid against the code before the one-evaluation restructure.

The grid varies rocker x swing x rope force (50 x 40 x 50) on the prototype at 360 crank samples,
CSV written, one process.  The same command runs on this checkout and on a pinned install of
commit 2cf593a (main before the restructure that made batch slower; ``make bench`` builds it in
build/base-2cf593a from this repository's own history), interleaved, so load from other
processes hits both alike; medians of ``--repeat`` runs of wall time, CPU time and peak memory.

    .venv/bin/python benchmarks/bench_grid_baseline.py [--repeat 5] [--base build/base-2cf593a]

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

from _record import machine, record

ROOT = Path(__file__).resolve().parents[1]
BASE_COMMIT = "2cf593a"

GRID = """\
base = "{base}"
[vary]
"linkage.rocker" = {{ start = 0.15, stop = 0.30, num = 50 }}
"linkage.swing" = {{ start = 40, stop = 80, num = 40 }}
"load.rope_force" = {{ start = 20, stop = 65, num = 50 }}
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
    args = ap.parse_args()
    base_python = args.base / ".venv" / "bin" / "python"
    if not base_python.exists():
        raise SystemExit(
            f"no pinned install at {args.base}: run `make bench` (it builds one from {BASE_COMMIT})"
        )
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        grid = tmp / "grid.toml"
        grid.write_text(GRID.format(base=(ROOT / "configs" / "prototype.toml").as_posix()))
        runs: dict[str, list[dict]] = {"this checkout": [], BASE_COMMIT: []}
        for _ in range(args.repeat):
            for name, python in (("this checkout", sys.executable), (BASE_COMMIT, str(base_python))):
                out = tmp / f"{name.replace(' ', '-')}.csv"
                cmd = [python, "-m", "pumplink", "batch", str(grid), "--samples", "360", "--fail-on", "none"]
                r = measure([*cmd, "--format", "csv", "--out", str(out), "--workers", "1"])
                assert r["rc"] == 0, (name, r)
                assert sum(1 for _ in out.open()) == 100_001
                runs[name].append(r)
    print(f"100,000-variant grid (rocker x swing x rope force), 360 samples, one process; {machine()}")
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
    ratio = med["this checkout"]["wall"] / med[BASE_COMMIT]["wall"]
    print(
        f"  ratio, this checkout / {BASE_COMMIT}: {ratio:.2f}x wall, "
        f"{med['this checkout']['rss'] / med[BASE_COMMIT]['rss']:.2f}x memory"
    )
    record(
        f"100,000-variant grid, wall time against {BASE_COMMIT} (same run, interleaved)",
        ratio,
        "x",
        "<= 1.0x",
        ratio <= 1.0,
        f"{med['this checkout']['wall']:.2f} s vs {med[BASE_COMMIT]['wall']:.2f} s; "
        f"{med['this checkout']['rss']:.0f} vs {med[BASE_COMMIT]['rss']:.0f} MiB",
    )


if __name__ == "__main__":
    main()
