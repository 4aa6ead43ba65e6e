"""The part checks under full dynamics for many designs at once: the commands that waited on them,
side by side with the code before (a pinned install of commit 94c2ab6, where they ran one design
at a time; ``make bench`` builds it in build/base-94c2ab6 from this repository's own history).

Each command is the real one in a subprocess, start-up included, run through a wrapper that reads
its wall time and its CPU time (user + system, of it and every process it starts); this
checkout's runs and 94c2ab6's are interleaved, so load from other processes falls on both alike.
Both sides run their own installed entry point (``.venv/bin/pumplink``), each from its own
checkout's folder on that checkout's copy of the specs (94c2ab6 reads no ``handle_joint`` or
``crank_joint`` in ``[parts]``, words added since; the village well is the same design).
Medians of ``--repeat`` runs; the old install's design-space grid takes minutes a run, so it
runs ``--repeat-slow`` times (once by default).

    .venv/bin/python benchmarks/bench_parts.py [--repeat 3] [--repeat-slow 1] [--base DIR] [--smoke]

(``--base``: the pinned install's folder, build/base-94c2ab6 by default.)

Targets (the figures judged are CPU times where the command runs in one process, i.e. per core:
on a shared machine the wall clock also counts the time other processes hold the core; wall
times where it runs on two workers):

* ``tolerance configs/village-10m.toml --samples 10000`` (one process): <= 10 s and >= 5x
  faster than 94c2ab6;
* ``batch configs/grids/design-space.toml --workers 2`` (27,216 variants of the village well with
  its ``[parts]``, CSV written): <= 30 s wall and >= 5x faster;
* ``force configs/village-10m.toml --explain --verify`` (one design in depth, the workshop view's
  one-design route): no slower than 94c2ab6 (ratio <= 1.05, the spread of repeated runs here);
* ``size --tolerance 1mm --yield 0.95 --head 10 --profile women`` (a robust search, the answer
  checked on 2,000 builds): <= 30 s wall (94c2ab6's beside it).

``--smoke``: this checkout only (the pinned install is not run), each command once and small:
tolerance on 100 builds, a thousandth of the grid (``--chunk 1/1000``, 27 variants) on one
worker, the force explanation, and a robust size of one pipe bore at 5 m for men; no target
judged (benchmarks/_record.py).
"""

from __future__ import annotations

import argparse
import json
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _record import SMOKE_HELP, judged, machine, record, repeats, smoke  # noqa: E402
from bench_batch import WRAPPER  # noqa: E402  (one measuring wrapper: wall, CPU)

ROOT = Path(__file__).resolve().parents[1]
BASE_COMMIT = "94c2ab6"
THIS = "this checkout"
VILLAGE = "configs/village-10m.toml"
GRID = "configs/grids/design-space.toml"
#: "No slower": the spread of repeated runs of one command on this machine (a few per cent).
SPREAD = 1.05


def measure(exe: tuple[str, Path], args: list[str]) -> dict:
    """Wall and CPU time [s] of ``exe args`` (``exe``: the entry point and the folder it runs
    from); its exit code must be 0 or 1 (a verdict), else the benchmark stops."""
    out = subprocess.run(
        [sys.executable, "-c", WRAPPER, exe[0], *args], capture_output=True, text=True, check=True, cwd=exe[1]
    )
    res = json.loads(out.stdout)
    if res["rc"] not in (0, 1):
        raise SystemExit(f"{exe[0]} {' '.join(args)} failed ({res['rc']}):\n{res['stderr']}")
    return res


def side_by_side(exes: dict[str, tuple], args: list[str], runs: int, base_runs: int) -> dict[str, dict]:
    """Median wall and CPU time of ``args`` on each install, interleaved round by round."""
    got: dict[str, list[dict]] = {name: [] for name in exes}
    for k in range(max(runs, base_runs)):
        for name, exe in exes.items():
            if k < (runs if name == THIS else base_runs):
                got[name].append(measure(exe, args))
    return {
        name: {key: statistics.median(r[key] for r in rs) for key in ("wall", "cpu")} | {"runs": len(rs)}
        for name, rs in got.items()
    }


def report(label: str, med: dict[str, dict]) -> None:
    for name, m in med.items():
        print(f"  {label}, {name}: median wall {m['wall']:.2f} s, CPU {m['cpu']:.2f} s ({m['runs']} runs)")


def beside(med: dict[str, dict], key: str, digits: int = 1) -> str:
    """The two installs' medians of ``key`` ("wall" or "cpu") in words."""
    return f"{key} {med[THIS][key]:.{digits}f} s here, {med[BASE_COMMIT][key]:.{digits}f} s on {BASE_COMMIT}"


def target(label, value, unit, goal, met, note="") -> None:
    """One judged line and its figure for the summary table."""
    print(f"  {label}: {value:.2f}{unit}; target {goal}; met: {judged(met)}" + (f" [{note}]" if note else ""))
    record(label, value, unit.strip() or "x", goal, met, note)


def in_time_and_faster(med, key, label, limit, ratio_label, other) -> None:
    """The two judged lines of a command run side by side: its ``key`` time ("cpu" or "wall") at
    most ``limit`` seconds, and at least 5x faster than the pinned install (``other``: the other
    time, given beside it)."""
    value, ratio = med[THIS][key], med[BASE_COMMIT][key] / med[THIS][key]
    target(label, value, " s", f"<= {limit:g} s", value <= limit, f"{beside(med, key)}; {beside(med, other)}")
    target(f"{ratio_label}: {BASE_COMMIT}'s {key.upper() if key == 'cpu' else key} / this checkout's", ratio,
           "x", ">= 5x", ratio >= 5.0)  # fmt: skip


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--repeat-slow", type=int, default=1, help="runs of the old install's design-space grid")
    ap.add_argument("--base", type=Path, default=ROOT / "build" / f"base-{BASE_COMMIT}")
    ap.add_argument("--smoke", action="store_true", help=SMOKE_HELP)
    args = ap.parse_args()
    exes = {THIS: (str(Path(sys.executable).parent / "pumplink"), ROOT)}
    base_exe = args.base / ".venv" / "bin" / "pumplink"
    if smoke():
        print(
            f"smoke run: the pinned install of {BASE_COMMIT} is not run (its side of each comparison "
            "is skipped)"
        )
    elif not base_exe.exists():
        raise SystemExit(
            f"no pinned install at {args.base}: run `make bench` (it builds one from {BASE_COMMIT})"
        )
    else:
        exes[BASE_COMMIT] = (str(base_exe), args.base)
    n, slow = repeats(args.repeat), repeats(args.repeat_slow)
    print(f"the part checks under full dynamics, this checkout against {BASE_COMMIT}; {machine()}")
    with tempfile.TemporaryDirectory() as tmp:
        samples = "100" if smoke() else "10000"
        tol = ["tolerance", VILLAGE, "--samples", samples, "--format", "json"]
        print(f"pumplink {' '.join(tol)}")
        med = side_by_side(exes, tol, n, n)
        report("tolerance", med)
        if BASE_COMMIT in med:
            in_time_and_faster(med, "cpu", f"tolerance {VILLAGE}, {samples} builds, one process: CPU", 10.0,
                               f"tolerance, {samples} builds", "wall")  # fmt: skip
        else:
            record(f"tolerance {VILLAGE}, {samples} builds, one process: CPU", med[THIS]["cpu"], "s")

        out = str(Path(tmp) / "grid.csv")
        grid = ["batch", GRID, "--format", "csv", "--out", out, "--fail-on", "none"]
        grid += ["--chunk", "1/1000", "--workers", "1"] if smoke() else ["--workers", "2"]
        print(f"pumplink {' '.join(grid)}")
        med = side_by_side(exes, grid, n, slow)
        report("grid", med)
        if BASE_COMMIT in med:
            in_time_and_faster(med, "wall", "design-space grid with [parts], --workers 2: wall", 30.0,
                               "design-space grid with [parts]", "cpu")  # fmt: skip
        else:
            record(
                "design-space grid with [parts] (smoke: 27 variants, one worker): wall",
                med[THIS]["wall"],
                "s",
            )

        force = ["force", VILLAGE, "--explain", "--verify", "--format", "json"]
        print(f"pumplink {' '.join(force)}")
        med = side_by_side(exes, force, repeats(3 * args.repeat), repeats(3 * args.repeat))
        report("force --explain --verify", med)
        if BASE_COMMIT in med:
            ratio = med[THIS]["cpu"] / med[BASE_COMMIT]["cpu"]
            note = beside(med, "cpu", 3)
            target(
                f"force {VILLAGE} --explain --verify: CPU against {BASE_COMMIT}",
                ratio,
                "x",
                f"<= {SPREAD}x",
                ratio <= SPREAD,
                note,
            )
        else:
            record(f"force {VILLAGE} --explain --verify: CPU", med[THIS]["cpu"], "s")

        size = ["size", "--tolerance", "1mm", "--yield", "0.95", "--format", "json"]
        size += (
            ["--head", "5", "--profile", "men", "--pipes", "20mm"]
            if smoke()
            else ["--head", "10", "--profile", "women"]
        )
        print(f"pumplink {' '.join(size)}")
        med = side_by_side(exes, size, 1, 1)
        report("size", med)
        if BASE_COMMIT in med:
            wall = med[THIS]["wall"]
            note = f"{beside(med, 'wall')}; {beside(med, 'cpu')}"
            target(
                "size --tolerance 1mm --yield 0.95 --head 10 --profile women: wall",
                wall,
                " s",
                "<= 30 s",
                wall <= 30.0,
                note,
            )
        else:
            record("size --tolerance 1mm (smoke: 5 m, men, one bore): wall", med[THIS]["wall"], "s")


if __name__ == "__main__":
    main()
