"""Throughput of the force kernel vs pylinkage's step_fast and the `numeric` route.

All in one process, side by side, medians of repeated runs (the machine is shared and noisy).
A "position" is one (design, crank angle) pair: for pumplink, coupler point B plus the operator
force; for pylinkage's numba `step_fast`, the joint positions only (it computes no force).

Run: .venv/bin/python benchmarks/bench_methods.py [--smoke]   (or `make bench`; ``--smoke``: 16
designs, one run each, no target judged, pylinkage's side only where it is installed:
benchmarks/_record.py)
"""

from __future__ import annotations

import statistics
import time

import numpy as np
from _record import judged, record, repeats, smoke

from pumplink.inputs.pump import default_spec
from pumplink.mechanisms.angles import grid_directions
from pumplink.mechanisms.fourbar import FourBar, synthesize
from pumplink.mechanisms.fourbar_kernel import force_kernel, kernel_work
from pumplink.studies.force import design
from pumplink.studies.methods import numeric, vector

REPEATS = 7


def median_time(fn, repeat=REPEATS):
    fn()  # warm-up (numba compilation, caches)
    times = []
    for _ in range(repeats(repeat)):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


def feasible_designs(n, seed=1):
    rng = np.random.default_rng(seed)
    m = 4 * n
    syn = synthesize(
        rng.uniform(0.2, 0.8, m),
        rng.uniform(-0.1, 0.4, m),
        rng.uniform(0.0, 0.2, m),
        rng.uniform(0.15, 0.4, m),
        np.radians(rng.uniform(30, 80, m)),
        rng.uniform(0.6, 1.2, m),
    )
    ok = np.nonzero(syn.feasible)[0][:n]
    assert ok.size == n
    return FourBar(
        *(
            np.asarray(v)[ok][:, None]
            for v in (
                syn.pivot_x,
                syn.pivot_y,
                syn.crank_length,
                syn.coupler_length,
                syn.rocker_length,
                syn.handle_length,
                syn.branch,
            )
        )
    )


def batched(lk: FourBar, cs, sn, block=8):
    """Designs x angles through force_kernel, `block` designs at a time with one reused scratch
    buffer (keeps arrays in cache); cos/sin of the angles computed once for all designs."""
    d = lk.crank.shape[0]
    work = kernel_work((block, cs.size))
    for i in range(0, d, block):
        sub = FourBar(
            *(
                v[i : i + block]
                for v in (lk.pivot_x, lk.pivot_y, lk.crank, lk.coupler, lk.rocker, lk.handle, lk.branch)
            )
        )
        force_kernel(sub, cs, sn, 13.5, work if sub.crank.shape[0] == block else None)


def pylinkage_fourbar(lk: FourBar, n):
    """The same four-bar in pylinkage 1.3.0 (crank at the wheel axle, RRR dyad to the rocker pivot)."""
    from pylinkage.actuators import Crank
    from pylinkage.components import Ground
    from pylinkage.dyads import RRRDyad
    from pylinkage.simulation import Linkage as PlLinkage

    o2 = Ground(0.0, 0.0, name="O2")
    o4 = Ground(float(lk.pivot_x), float(lk.pivot_y), name="O4")
    crank = Crank(anchor=o2, radius=float(lk.crank), angular_velocity=2 * np.pi / n)
    rocker = RRRDyad(crank.output, o4, distance1=float(lk.coupler), distance2=float(lk.rocker))
    pl = PlLinkage([o2, o4, crank, rocker], name="pump four-bar")
    pl.compile()
    return pl, rocker


def main():
    try:
        import pylinkage
    except ImportError:
        if not smoke():
            raise SystemExit("pylinkage is not installed: pip install '.[bench]' (make bench does)") from None
        pylinkage = None
        print("smoke run: pylinkage is not installed (the bench extra), its side is skipped")

    spec = default_spec()
    syn = design(spec).synthesis
    lk = syn.linkage
    n_angles = 3600
    cs, sn = grid_directions(n_angles)

    # 1. pumplink batched: designs x angles, kinematics (B) + force
    n_designs = 16 if smoke() else 2000
    many = feasible_designs(n_designs)
    results = {}
    for block in (1, 4, 16, 64):
        t = median_time(lambda block=block: batched(many, cs, sn, block))
        results[f"pumplink force_kernel, {n_designs} designs x {n_angles} angles, {block} designs/block"] = (
            n_designs * n_angles / t
        )
    # single design, same sweep
    t = median_time(lambda: force_kernel(lk, cs, sn, 13.5))
    results[f"pumplink force_kernel, 1 design x {n_angles} angles"] = n_angles / t
    t = median_time(lambda: vector(lk, np.arange(n_angles) * (2 * np.pi / n_angles), 13.5))
    results[f"pumplink vector method (evaluate, full state), 1 design x {n_angles}"] = n_angles / t

    # 2. pylinkage step_fast on the same four-bar: positions only
    if pylinkage is not None:
        pl, rocker = pylinkage_fourbar(lk, n_angles)
        traj = pl.step_fast(iterations=n_angles)
        t = median_time(lambda: pl.step_fast(iterations=n_angles))
        name = f"pylinkage {pylinkage.__version__} step_fast (numba), 1 design x {n_angles}, positions only"
        results[name] = n_angles / t
        # sanity: pylinkage's rocker joint traces the same rocker circle as ours
        bxy = traj[:, -1, :]
        radius = np.hypot(bxy[:, 0] - lk.pivot_x, bxy[:, 1] - lk.pivot_y)
        assert np.nanmax(np.abs(radius - lk.rocker)) < 1e-9, "pylinkage four-bar does not match"

    # 3. numeric: scipy fsolve + central difference (slow: fewer angles)
    n_few = 8 if smoke() else 72
    few = np.arange(n_few) * (2 * np.pi / n_few) + 0.01
    t = median_time(lambda: numeric(lk, few, 13.5), repeat=3)
    numeric_name = f"numeric (fsolve + central difference), 1 design x {n_few}"
    results[numeric_name] = few.size / t

    width = max(len(k) for k in results)
    best_pumplink = max(
        v for k, v in results.items() if k.startswith("pumplink force_") and " designs x " in k
    )
    pyl = next((v for k, v in results.items() if k.startswith("pylinkage")), None)
    num = results[numeric_name]
    print(f"positions per second (median of {repeats(REPEATS)}; one core; {time.strftime('%Y-%m-%d %H:%M')})")
    for k, v in results.items():
        print(f"  {k:<{width}}  {v / 1e6:10.3f} M/s")
    single = results[f"pumplink force_kernel, 1 design x {n_angles} angles"]
    if pyl is not None:
        print(
            "ratio best batched pumplink (B + force) / pylinkage step_fast (positions): "
            f"{best_pumplink / pyl:8.1f}x"
        )
        print(
            f"ratio single-design pumplink force_kernel / pylinkage step_fast:           {single / pyl:8.1f}x"
        )
    print(
        "ratio best batched pumplink / numeric:                                     "
        f"{best_pumplink / num:8.0f}x"
    )
    rate = best_pumplink / 1e6
    print(f"target >= 50 M positions/s (batched): {rate:.1f} M/s, met: {judged(rate >= 50)}")
    record("force kernel, batched designs x 3600 angles", rate, "M/s", ">= 50 M/s", rate >= 50)
    if pyl is not None:
        print(f"target >= 5x pylinkage: {best_pumplink / pyl:.1f}x, met: {judged(best_pumplink >= 5 * pyl)}")
        record(
            "force kernel batched / pylinkage step_fast (kernels alone)",
            best_pumplink / pyl,
            "x",
            ">= 5x",
            best_pumplink >= 5 * pyl,
            note=f"one design: {single / pyl:.1f}x; pylinkage computes positions only",
        )


if __name__ == "__main__":
    import os

    os.environ.setdefault("OMP_NUM_THREADS", "1")
    main()
