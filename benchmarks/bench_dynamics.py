"""Full-dynamics benchmarks: the least peak force with link masses (pumplink.models.dynamics).

Medians over repeated runs in one process.  Targets: one design's Fp* in <= 5 ms; 10,000 designs
in one call at >= 10,000 designs/s per core as this process's malloc stands, and at >= 20,000/s
with malloc tuned as a batch run tunes it (:func:`pumplink.malloc.tune_malloc`: the batch engine,
its workers and a tolerance study keep the kernels' temporaries on the heap; measured after the
untuned figure, since the tuning cannot be undone in a process); and the rate through the real
command at >= 20,000 variants/s per core: `pumplink batch` on 10,000 variants of the village well
without its ``[parts]`` (full dynamics decides each), one process, every stage, CSV written, its
CPU time less that of the same command on one variant (the start-up), medians of 5 runs of each,
taking turns (on this shared 2-core machine the figure moves by a fifth from hour to hour: the
load average is printed beside it).  The figure judged is the
CPU time of this (single-threaded) process, i.e. per core: on a shared machine the wall clock,
printed beside it, also counts the time other processes hold the core (on an idle machine the two
agree).  Each line says the figure, the target and whether it is met.  Run with `make bench`;
``--smoke``: 20 designs and 8 batch variants, one run each, no target judged
(benchmarks/_record.py).
"""

from __future__ import annotations

import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
import tomllib
from pathlib import Path

import numpy as np
import tomli_w

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _record import judged, machine, record, repeats, smoke  # noqa: E402
from bench_batch import WRAPPER  # noqa: E402  (one measuring wrapper: wall, CPU)
from bench_core import ROOT  # noqa: E402

from pumplink.evaluate import motion  # noqa: E402
from pumplink.inputs.pump import load_spec  # noqa: E402
from pumplink.mechanisms.fourbar import synthesize  # noqa: E402
from pumplink.models import dynamics_solver as ds  # noqa: E402
from pumplink.models import dynamics_terms as dt  # noqa: E402
from pumplink.studies.force import force_analysis  # noqa: E402
from pumplink.studies.speed import cadence  # noqa: E402

EXAMPLE = ROOT / "examples" / "well-12m-flywheel.toml"
BATCH = 10_000
#: The batch command's variants of the village well: swing x rocker x head (10,000; 8 in a smoke run).
VILLAGE_GRID = """\
base = "village-10m.toml"
[vary]
"linkage.swing" = {{ start = 44, stop = 56, num = {swings} }}
"linkage.rocker" = {{ start = 0.12, stop = 0.15, num = {rockers} }}
"load.head" = {{ start = 6, stop = 14, num = {heads} }}
"""


def timed(fn, repeat):
    """Median wall and CPU time [s] of ``repeat`` calls (after one warm-up call; a smoke run: one
    call)."""
    if smoke():
        repeat = 1
    else:
        fn()
    wall, cpu = [], []
    for _ in range(repeat):
        t0, c0 = time.perf_counter(), time.process_time()
        fn()
        wall.append(time.perf_counter() - t0)
        cpu.append(time.process_time() - c0)
    return statistics.median(wall), statistics.median(cpu)


def line(label, figure, target, met, value=float("nan"), unit=""):
    """One line per target, and its figure for `make bench`'s summary table (benchmarks/_record.py)."""
    print(f"{label}: {figure}; target {target}; met: {judged(met)}")
    record(label, value, unit, target, met, figure)


def batch_designs(spec, n, seed=12):
    """``n`` distinct feasible designs around the spec: handle, swing, rocker, frame placement,
    link mass, arm mass, speed and speed fluctuation all varied."""
    rng = np.random.default_rng(seed)
    lk = spec.linkage
    m = 2 * n
    syn = synthesize(
        lk.L1 + rng.uniform(-0.05, 0.05, m),
        lk.D1 + rng.uniform(-0.05, 0.05, m),
        lk.b,
        lk.rocker * rng.uniform(0.85, 1.15, m),
        np.radians(lk.swing * rng.uniform(0.85, 1.15, m)),
        lk.handle * rng.uniform(0.8, 1.2, m),
    )
    ok = np.nonzero(syn.reason == 0)[0][:n]
    four = syn.linkage.take(ok)
    masses = dt.bar_masses(four, rng.uniform(0.5, 3.0, ok.size), rng.uniform(0.0, 6.0, ok.size))
    return (
        four,
        syn.dead_centre_extended[ok],
        syn.dead_centre_folded[ok],
        spec.wheel_torque,
        spec.inertia,
        masses,
        np.radians(rng.uniform(180.0, 720.0, ok.size)),
        rng.uniform(0.1, 0.4, ok.size),
    )


def main() -> None:
    print(f"machine: {machine()}")
    spec = load_spec(EXAMPLE)
    r = force_analysis(spec, keep_samples=False)
    syn, lk = motion.at_design(r.evaluation)
    mw, j = spec.wheel_torque, spec.inertia
    dce, dcf = syn.dead_centre_extended, syn.dead_centre_folded
    ms = motion.link_masses_of(r.evaluation, arms=False)  # the hand force: no arms at the grip
    w = np.radians(spec.operator.speed)
    wall, cpu = timed(lambda: ds.least_peak_force(lk, dce, dcf, mw, j, ms, w, 0.2), 51)
    line(
        "Fp*, one design (12 m example)",
        f"cpu {cpu * 1e3:.2f} ms (wall {wall * 1e3:.2f})",
        "<= 5 ms",
        cpu <= 5e-3,
        cpu * 1e3,
        "ms CPU",
    )
    args = batch_designs(spec, 20 if smoke() else BATCH)
    n = args[0].crank.size
    wall, cpu = timed(lambda: ds.least_peak_force(*args), 5)
    line(
        f"Fp*, {n:,} designs in one call",
        f"cpu {n / cpu:,.0f}/s (wall {n / wall:,.0f}/s)",
        ">= 10,000/s",
        n / cpu >= 10_000,
        n / cpu,
        "designs/s per core",
    )
    from pumplink.malloc import tune_malloc

    tuned = tune_malloc()
    wall, cpu = timed(lambda: ds.least_peak_force(*args), 5)
    line(
        f"Fp*, {n:,} designs in one call, malloc tuned as in a batch run",
        f"cpu {n / cpu:,.0f}/s (wall {n / wall:,.0f}/s){'' if tuned else ' (not glibc: not tuned)'}",
        ">= 20,000/s",
        n / cpu >= 20_000,
        n / cpu,
        "designs/s per core",
    )
    wall, cpu = timed(lambda: cadence(r), 5)
    print(
        f"best cadence and passing speeds (12 m example): cpu {cpu * 1e3:.0f} ms (wall {wall * 1e3:.0f} ms)"
    )
    batch_rate()


def batch_rate() -> None:
    """`pumplink batch` on variants of the village well without ``[parts]``, one process: the
    variants per second of CPU beyond the start-up (the same command on one variant)."""
    village = tomllib.loads((ROOT / "configs" / "village-10m.toml").read_text())
    del village["parts"]
    sizes = {"swings": 2, "rockers": 2, "heads": 2} if smoke() else {"swings": 25, "rockers": 20, "heads": 20}
    n = sizes["swings"] * sizes["rockers"] * sizes["heads"]
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        (folder / "village-10m.toml").write_text(tomli_w.dumps(village))
        runs = {}
        for name, size in (("one", {"swings": 1, "rockers": 1, "heads": 1}), ("all", sizes)):
            grid = folder / f"{name}.toml"
            grid.write_text(VILLAGE_GRID.format(**size))
            runs[name] = [
                sys.executable,
                "-m",
                "pumplink",
                "batch",
                str(grid),
                "--workers",
                "1",
                "--format",
                "csv",
            ]
            runs[name] += ["--out", str(folder / f"{name}.csv"), "--fail-on", "none"]
        cpu = {name: [] for name in runs}
        for _ in range(repeats(5)):  # interleaved: load falls on both alike
            for name, cmd in runs.items():
                out = subprocess.run(
                    [sys.executable, "-c", WRAPPER, *cmd], capture_output=True, text=True, check=True
                )
                res = json.loads(out.stdout)
                assert res["rc"] == 0, res
                cpu[name].append(res["cpu"])
        lines = (folder / "all.csv").read_text().splitlines()
    assert len(lines) == n + 1 and sum(",full dynamics," in ln for ln in lines[1:]) == n, lines[:2]
    start, whole = statistics.median(cpu["one"]), statistics.median(cpu["all"])
    rate = n / (whole - start) if whole > start else float("nan")  # a smoke run's 8 cost nothing
    load = os.getloadavg()[0]
    print(
        f"pumplink batch, {n:,} variants of the village well without [parts] (full dynamics), one "
        f"process: cpu {whole:.2f} s, start-up {start:.2f} s: {rate:,.0f} variants/s per core beyond it "
        f"(load average {load:.2f}); target >= 20,000/s; met: {judged(rate >= 20_000)}"
    )
    record(
        f"pumplink batch, {n:,} village variants (full dynamics), one process, beyond start-up",
        rate,
        "variants/s per core",
        ">= 20,000/s",
        rate >= 20_000,
        note=f"CPU {whole:.2f} s less {start:.2f} s of start-up (one variant), load average {load:.2f}; "
        "every stage, CSV written",
    )


if __name__ == "__main__":
    main()
