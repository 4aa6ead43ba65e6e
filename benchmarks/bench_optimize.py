"""Wall time of the design searches: `optimize` on every configs/*.toml spec and the
exact optimal-transmission crank-rocker.  Medians of repeated runs (the machine is shared, so
absolute seconds are noisy; compare side by side: the flywheel search next to the quasi-static
one, and next to the same search on the reference route of the flywheel model).

Target: `pumplink optimize configs/village-10m.toml` <= 3 s wall end to end, with the optimum of
the same search without its shortcuts (the polish's gradient one point at a time, the arms'
energy computed) to 1e-6.  Each target gives one line starting with ``RESULT``:
figure, target, met yes/no.

Run: .venv/bin/python benchmarks/bench_optimize.py   (or `make bench`)
"""

import math
import os
import statistics
import subprocess
import sys
import time
import tomllib
from pathlib import Path

import numpy as np
from _record import result

from pumplink.inputs.pump import load_spec
from pumplink.mechanisms.crank_rocker import optimal_crank_rocker
from pumplink.search.optimize import optimize
from pumplink.search.problem import make_problem

REPEATS = 3
ROOT = Path(__file__).resolve().parent.parent
VILLAGE = ROOT / "configs" / "village-10m.toml"


def median_time(fn, repeats=REPEATS):
    times, out = [], None
    for _ in range(repeats):
        t = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t)
    return statistics.median(times), out


def main():
    load = os.getloadavg()[0] if hasattr(os, "getloadavg") else float("nan")
    print(f"2-core shared machine, load average {load:.2f}; medians of {REPEATS} runs, seed 0")
    optimal_crank_rocker(1.1818, math.radians(40), 50.0)  # warm-up: scipy import
    t, _ = median_time(lambda: optimal_crank_rocker(1.1818, math.radians(40), 50.0), 5)
    print(f"transmission optimum (the optimal-transmission paper example): median {t * 1e3:.1f} ms")
    times = {}
    for path in sorted((ROOT / "configs").glob("*.toml")):
        if "vary" in tomllib.loads(path.read_text(encoding="utf-8")):
            continue  # a batch file of variants, not a single spec
        spec = load_spec(path)
        problem = make_problem(spec)
        t, res = median_time(lambda problem=problem: optimize(problem, seed=0))
        times[path.name] = (t, problem.model)
        # the flywheel's least peak when the spec gives inertia
        peak = float(res.at_best.verdict_peak_force[0])
        print(
            f"optimize {path.name} ({problem.model}): median {t:.2f} s in process; {res.evaluations} designs "
            f"({res.force_evaluations} forces); peak {peak:.2f} N (spec's own "
            f"{float(res.at_spec.verdict_peak_force[0]):.2f} N); "
            f"{'passes' if peak <= spec.operator.force_limit else 'fails'} {spec.operator.force_limit:g} N"
        )

    cmd = [sys.executable, "-m", "pumplink", "optimize", str(VILLAGE)]
    wall, _ = median_time(lambda: subprocess.run(cmd, stdout=subprocess.DEVNULL, check=False))
    ref_t, _ = times.get("prototype.toml", (float("nan"), ""))
    fly_t, _ = times[VILLAGE.name]
    result(
        "pumplink optimize configs/village-10m.toml (full dynamics), end to end",
        f"{wall:.2f} s wall (median of {REPEATS})",
        "<= 3 s",
        wall <= 3.0,
        f"search in process {fly_t:.2f} s; the quasi-static prototype.toml search {ref_t:.2f} s: "
        f"full dynamics / quasi-static {fly_t / ref_t:.1f}x",
        value=wall,
        unit="s",
    )

    # the same search without its shortcut, once: the polish's finite differences one point at a
    # time (scipy's own)
    import scipy.optimize

    problem = make_problem(load_spec(VILLAGE))
    fast = optimize(problem, seed=0)
    minimize = scipy.optimize.minimize

    def one_at_a_time(*args, options=None, **kwargs):
        return minimize(*args, options={k: v for k, v in (options or {}).items() if k != "workers"}, **kwargs)

    scipy.optimize.minimize = one_at_a_time
    try:
        t0 = time.perf_counter()
        slow = optimize(problem, seed=0)
        slow_t = time.perf_counter() - t0
    finally:
        scipy.optimize.minimize = minimize
    dpeak = abs(fast.at_best.verdict_peak_force[0] / slow.at_best.verdict_peak_force[0] - 1.0)
    dx = float(np.max(np.abs(fast.x - slow.x) / (problem.upper - problem.lower)))
    result(
        "optimize village-10m, optimum vs the search without its shortcuts",
        f"peak force {dpeak:.1e} relative, design {dx:.1e} of the bounds",
        "<= 1e-6",
        dpeak <= 1e-6 and dx <= 1e-6,
        f"the search without them {slow_t:.1f} s in process ({fast.best_result.model})",
        value=max(dpeak, dx),
        unit="relative",
    )


def grid_check(path: Path, m: int) -> None:
    """Brute force over the default bounds: is the optimiser's answer really the best there is?"""
    from pumplink.search.problem import evaluate_designs

    problem = make_problem(load_spec(path))
    axes = [np.linspace(lo, hi, m) for lo, hi in zip(problem.lower, problem.upper)]
    x = np.array(np.meshgrid(*axes, indexing="ij")).reshape(len(axes), -1)
    best, feasible = np.inf, 0
    t0 = time.perf_counter()
    for i in range(0, x.shape[1], 50_000):
        ev = evaluate_designs(problem, x[:, i : i + 50_000])
        ok = np.all(ev.slack >= 0, axis=0) & np.isfinite(ev.verdict_peak_force)
        feasible += int(ok.sum())
        if ok.any():
            best = min(best, float(ev.verdict_peak_force[ok].min()))
    took = time.perf_counter() - t0
    print(
        f"grid check {path.name} ({problem.model}): {m}^{len(axes)} = {x.shape[1]} designs over the default "
        f"bounds, {feasible} meet every constraint, lowest peak {best:.2f} N ({took:.1f} s)"
    )


if __name__ == "__main__":
    main()
    for m in (21, 31):
        grid_check(VILLAGE, m)
