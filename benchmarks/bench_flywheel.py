"""Benchmarks of the flywheel scene: the least peak force (Eq. (4) of pumplink.models.flywheel).

Medians over repeated runs in one process, one thread (end-to-end commands in subprocesses).
The machine is shared, so each figure is printed beside the same run's reference route (the
previous kernel, kept in pumplink.models.flywheel) and the quasi-static windowed peak, as ratios.
Targets: one design <= 2 ms (wall); >= 20,000 designs/s per core vectorised (designs per second of
this process's CPU time, so that other jobs on the machine do not count; the wall figure is
printed beside it); the answers of the reference route to 1e-9 relative.  Each target gives one
line starting with ``RESULT``: figure, target, met yes/no.  Run with `make bench`; ``--smoke``:
a few dozen designs, one run each, one revolution integrated, every command once, no target judged
(benchmarks/_record.py).
"""

from __future__ import annotations

import os
import statistics
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _record import machine, repeats, result, smoke  # noqa: E402
from bench_core import EXE, ROOT, median_time  # noqa: E402

from pumplink.inputs.pump import load_spec  # noqa: E402
from pumplink.mechanisms.fourbar import FourBar, synthesize  # noqa: E402
from pumplink.models import flywheel as fw  # noqa: E402
from pumplink.models import flywheel_solver as fs  # noqa: E402
from pumplink.models import grip_travel as gt  # noqa: E402
from pumplink.models.quasi_static import dead_band_peak_force, mean_force  # noqa: E402
from pumplink.studies.force import design  # noqa: E402

EXAMPLE = ROOT / "examples" / "well-12m-flywheel.toml"
DEAD_BAND = np.radians(20)


def wall_and_cpu(fn, repeat):
    """Medians of the wall time and of this process's CPU time over ``repeat`` runs [s]."""
    wall, cpu = [], []
    for _ in range(repeats(repeat)):
        w0, c0 = time.perf_counter(), time.process_time()
        fn()
        wall.append(time.perf_counter() - w0)
        cpu.append(time.process_time() - c0)
    return statistics.median(wall), statistics.median(cpu)


def run_command(args: list[str]) -> None:
    """One run of a pumplink command, its output discarded; exit 0 or 1 (the verdict), anything
    else (bad input: a command line out of date) stops the benchmark."""
    p = subprocess.run(args, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True, check=False)
    if p.returncode not in (0, 1):
        raise SystemExit(f"{' '.join(args)} failed ({p.returncode}):\n{p.stderr}")


def random_designs(n: int, seed: int = 0):
    """Feasible crank-rockers in the spec's ranges with a wheel torque [N m] and a band [J]."""
    rng = np.random.default_rng(seed)
    syn = synthesize(
        rng.uniform(0.0, 1.0, n),
        rng.uniform(-0.5, 0.8, n),
        rng.uniform(0.0, 0.3, n),
        rng.uniform(0.05, 0.6, n),
        np.radians(rng.uniform(10.0, 150.0, n)),
        rng.uniform(0.3, 1.5, n),
    )
    ok = syn.feasible
    m = int(ok.sum())
    args = (syn.linkage.take(ok), syn.dead_centre_extended[ok], syn.dead_centre_folded[ok])
    return args, 0.25 * rng.uniform(5.0, 200.0, m), 10.0 ** rng.uniform(-2.0, 2.0, m)


def main() -> None:
    load = os.getloadavg()[0] if hasattr(os, "getloadavg") else float("nan")
    print(f"machine: {machine()}; load average {load:.2f} (shared: compare the ratios)")
    spec = load_spec(EXAMPLE)
    syn = design(spec).synthesis
    lk, mw, j = syn.linkage, spec.wheel_torque, spec.inertia
    dce, dcf = syn.dead_centre_extended, syn.dead_centre_folded
    band = float(fw.energy_band(j, 2 * np.pi, 0.2))

    # one design (the example at 360 deg/s)
    t1, c1 = wall_and_cpu(lambda: fs.least_peak_force(lk, dce, dcf, mw, band), 41)
    r1 = median_time(lambda: fs._reference_least_peak_force(lk, dce, dcf, mw, band), 7)
    tq = median_time(lambda: dead_band_peak_force(lk, dce, dcf, DEAD_BAND, mw), 41)
    result(
        "flywheel least peak force, one design",
        f"{t1 * 1e3:.2f} ms wall (CPU {c1 * 1e3:.2f} ms; medians of {repeats(41)})",
        "<= 2 ms",
        t1 <= 2e-3,
        f"reference route {r1 * 1e3:.1f} ms: {r1 / t1:.0f}x faster; quasi-static peak {tq * 1e3:.2f} ms: "
        f"flywheel / quasi-static {t1 / tq:.1f}x",
        value=t1 * 1e3,
        unit="ms",
    )

    # 10,000 designs in one vectorised call: the example over 10,000 bands, and 10,000 random designs
    n = 40 if smoke() else 10_000
    rep = FourBar(*(np.full(n, float(v)) for v in lk.parameters))
    bands = np.linspace(0.5, 15.0, n)
    wn, tn = wall_and_cpu(lambda: fs.least_peak_force(rep, dce, dcf, mw, bands), 5)
    _, tqn = wall_and_cpu(lambda: dead_band_peak_force(rep, dce, dcf, DEAD_BAND, mw), 5)
    k = n // 5  # the reference route on a fifth of them (its rate)
    part = rep.take(slice(0, k))
    _, rn = wall_and_cpu(lambda: fs._reference_least_peak_force(part, dce, dcf, mw, bands[:k]), 1)
    result(
        f"flywheel least peak force, {n:,} bands of the example vectorised",
        f"{n / tn:,.0f} designs/s per core (CPU; wall {n / wn:,.0f}/s; medians of {repeats(5)})",
        ">= 20,000/s",
        n / tn >= 20_000,
        f"reference route {k / rn:,.0f}/s: {(n / tn) / (k / rn):.0f}x faster; "
        f"quasi-static peak {n / tqn:,.0f}/s: flywheel / quasi-static {tn / tqn:.1f}x",
        value=n / tn,
        unit="designs/s",
    )
    (rlk, rdce, rdcf), rmw, rband = random_designs(56 if smoke() else 14_000)
    m = rdce.size
    wr, tr = wall_and_cpu(lambda: fs.least_peak_force(rlk, rdce, rdcf, rmw, rband), 5)
    _, trq = wall_and_cpu(lambda: dead_band_peak_force(rlk, rdce, rdcf, DEAD_BAND, rmw), 5)
    result(
        f"flywheel least peak force, {m:,} random designs vectorised",
        f"{m / tr:,.0f} designs/s per core (CPU; wall {m / wr:,.0f}/s; medians of {repeats(5)})",
        ">= 20,000/s",
        m / tr >= 20_000,
        f"quasi-static peak {m / trq:,.0f}/s: flywheel / quasi-static {tr / trq:.1f}x",
        value=m / tr,
        unit="designs/s",
    )
    fast = fs.least_peak_force(rlk, rdce, rdcf, rmw, rband)
    ref = fs._reference_least_peak_force(rlk, rdce, rdcf, rmw, rband)
    fin = np.isfinite(ref)
    same = np.array_equal(np.isfinite(fast), fin) and np.array_equal(np.isnan(fast), np.isnan(ref))
    rel = float(np.max(np.abs(fast[fin] / ref[fin] - 1.0)))
    result(
        f"flywheel least peak force, fast vs reference route on those {m:,} designs",
        f"largest relative difference {rel:.1e}",
        "<= 1e-9",
        same and rel <= 1e-9,
        f"{int(np.sum(np.isinf(ref)))} beyond the cap (inf) in both" if same else "inf/NaN pattern differs",
        value=rel,
        unit="relative",
    )
    stroke = np.abs(gt.grip_position(rdcf, *rlk.parameters) - gt.grip_position(rdce, *rlk.parameters))
    limit = mean_force(rmw, stroke) * 10.0 ** np.random.default_rng(1).uniform(0.0, 2.0, m)  # to 100 F_mean
    _, te = wall_and_cpu(lambda: fw.min_passing_speed(rlk, rdce, rdcf, rmw, limit, 1.0, 0.2), 5)
    print(f"slowest passing speed (energy deficit), {m:,} random designs: {m / te:,.0f} designs/s per core")

    cycles = 1 if smoke() else 4
    ts = median_time(lambda: fw.integrate_motion(fw.scene(lk, dce, dcf, mw, j, 2 * np.pi, 0.2), cycles), 3)
    print(f"scene + solve_ivp cross-check ({cycles} revolution{'s' * (cycles > 1)}): {ts:.3f} s")
    for label, args in (
        ("pumplink force EXAMPLE --summary", [EXE, "force", str(EXAMPLE), "--summary"]),
        ("pumplink force EXAMPLE --summary --verify", [EXE, "force", str(EXAMPLE), "--summary", "--verify"]),
        ("pumplink speed EXAMPLE (21 speeds)", [EXE, "speed", str(EXAMPLE)]),
    ):
        t = median_time(lambda args=args: run_command(args), 5)
        print(f"{label:<44} {t:6.3f} s wall (median of {repeats(5)})")


if __name__ == "__main__":
    main()
