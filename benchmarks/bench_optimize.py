"""Wall time of the design searches: `optimize` on every configs/*.toml spec and the
exact optimal-transmission crank-rocker.  Medians of repeated runs (the machine is shared, so
absolute seconds are noisy; compare side by side: the flywheel search next to the quasi-static
one, and next to the same search on the reference route of the flywheel model).

Target: `pumplink optimize configs/village-10m.toml` <= 3 s wall end to end, with the optimum of
the same search without its shortcuts (the polish's gradient one point at a time, the arms'
energy computed) to 1e-6.  Each target gives one line starting with ``RESULT``:
figure, target, met yes/no.

Run: .venv/bin/python benchmarks/bench_optimize.py   (or `make bench`; ``--smoke``: every search
on every spec for 3 generations, the end-to-end run and the search without its shortcuts on
configs/prototype.toml, the grid check on 2 points an axis, no target judged:
benchmarks/_record.py)
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
from _record import repeats, result, smoke

from pumplink.inputs.pump import load_spec
from pumplink.mechanisms.crank_rocker import optimal_crank_rocker
from pumplink.search.optimize import optimize
from pumplink.search.problem import make_problem

REPEATS = 3
ROOT = Path(__file__).resolve().parent.parent
VILLAGE = ROOT / "configs" / "village-10m.toml"
#: The in-process searches' size: the product's defaults, or a few generations in a smoke run.
SEARCH = {"maxiter": 3} if smoke() else {}


def median_time(fn, repeat=REPEATS):
    times, out = [], None
    for _ in range(repeats(repeat)):
        t = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t)
    return statistics.median(times), out


def main(village=VILLAGE):
    """Every search timed; ``village`` is the spec of the end-to-end target and of the check
    against the search without its shortcuts."""
    load = os.getloadavg()[0] if hasattr(os, "getloadavg") else float("nan")
    print(f"2-core shared machine, load average {load:.2f}; medians of {repeats(REPEATS)} runs, seed 0")
    optimal_crank_rocker(1.1818, math.radians(40), 50.0)  # warm-up: scipy import
    t, _ = median_time(lambda: optimal_crank_rocker(1.1818, math.radians(40), 50.0), 5)
    print(f"transmission optimum (the optimal-transmission paper example): median {t * 1e3:.1f} ms")
    times = {}
    for path in sorted((ROOT / "configs").glob("*.toml")):
        if "vary" in tomllib.loads(path.read_text(encoding="utf-8")):
            continue  # a batch file of variants, not a single spec
        spec = load_spec(path)
        problem = make_problem(spec)
        t, res = median_time(lambda problem=problem: optimize(problem, seed=0, **SEARCH))
        times[path.name] = (t, problem.model)
        # the flywheel's least peak when the spec gives inertia
        peak = float(res.at_best.verdict_peak_force[0])
        print(
            f"optimize {path.name} ({problem.model}): median {t:.2f} s in process; {res.evaluations} designs "
            f"({res.force_evaluations} forces); peak {peak:.2f} N (spec's own "
            f"{float(res.at_spec.verdict_peak_force[0]):.2f} N); "
            f"{'passes' if peak <= problem.force_limit else 'fails'} {problem.force_limit:g} N"
        )

    cmd = [sys.executable, "-m", "pumplink", "optimize", str(village)]
    wall, p = median_time(
        lambda: subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    )
    if p.returncode not in (0, 1):  # 1: the optimum fails the force limit (a verdict, not an error)
        raise SystemExit(f"{' '.join(cmd)} failed ({p.returncode}):\n{p.stderr}")
    ref_t, _ = times.get("prototype.toml", (float("nan"), ""))
    fly_t, _ = times[village.name]
    # the village well is decided by full dynamics (the smoke run's prototype by the quasi-static model)
    which = "full dynamics" if village == VILLAGE else village.stem
    result(
        f"pumplink optimize configs/{village.name} ({which}), end to end",
        f"{wall:.2f} s wall (median of {repeats(REPEATS)})",
        "<= 3 s",
        wall <= 3.0,
        f"search in process {fly_t:.2f} s; the quasi-static prototype.toml search {ref_t:.2f} s: "
        f"{which} / quasi-static {fly_t / ref_t:.1f}x",
        value=wall,
        unit="s",
    )

    # the same search without its shortcut, once: the polish's finite differences one point at a
    # time (scipy's own)
    import scipy.optimize

    problem = make_problem(load_spec(village))
    fast = optimize(problem, seed=0, **SEARCH)
    minimize = scipy.optimize.minimize

    def one_at_a_time(*args, options=None, **kwargs):
        return minimize(*args, options={k: v for k, v in (options or {}).items() if k != "workers"}, **kwargs)

    scipy.optimize.minimize = one_at_a_time
    try:
        t0 = time.perf_counter()
        slow = optimize(problem, seed=0, **SEARCH)
        slow_t = time.perf_counter() - t0
    finally:
        scipy.optimize.minimize = minimize
    dpeak = abs(fast.at_best.verdict_peak_force[0] / slow.at_best.verdict_peak_force[0] - 1.0)
    dx = float(np.max(np.abs(fast.x - slow.x) / (problem.upper - problem.lower)))
    result(
        f"optimize {village.stem}, optimum vs the search without its shortcuts",
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
    if smoke():  # the quasi-static prototype: the cheapest search there is
        main(ROOT / "configs" / "prototype.toml")
        grid_check(ROOT / "configs" / "prototype.toml", 2)
    else:
        main()
        for m in (21, 31):
            grid_check(VILLAGE, m)
