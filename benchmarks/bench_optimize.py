"""Wall time of the design searches: `optimize` on every configs/*.toml spec and the
exact optimal-transmission crank-rocker.  Medians of repeated runs in this one process (the machine
is shared, so absolute seconds are noisy; compare side by side).

Run: .venv/bin/python benchmarks/bench_optimize.py   (or `make bench`)
"""

import math
import statistics
import time
import tomllib
from pathlib import Path

from _record import record

from pumplink.mechanisms.crank_rocker import optimal_crank_rocker
from pumplink.optimize import make_problem, optimize
from pumplink.spec import load_spec

REPEATS = 3
ROOT = Path(__file__).resolve().parent.parent


def median_time(fn, repeats=REPEATS):
    times, out = [], None
    for _ in range(repeats):
        t = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t)
    return statistics.median(times), out


def main():
    optimal_crank_rocker(1.1818, math.radians(40), 50.0)  # warm-up: scipy import
    t, _ = median_time(lambda: optimal_crank_rocker(1.1818, math.radians(40), 50.0), 5)
    print(f"transmission optimum (the optimal-transmission paper example): median {t * 1e3:.1f} ms")
    for path in sorted((ROOT / "configs").glob("*.toml")):
        if "vary" in tomllib.loads(path.read_text(encoding="utf-8")):
            continue  # a batch file of variants, not a single spec
        spec = load_spec(path)
        problem = make_problem(spec)
        t, res = median_time(lambda problem=problem: optimize(problem, seed=0))
        # the flywheel's least peak when the spec gives inertia
        peak = float(res.at_best.verdict_peak_force[0])
        print(
            f"optimize {path.name} ({problem.model}): median {t:.2f} s over {REPEATS} runs; "
            f"{res.evaluations} "
            f"designs; peak {peak:.2f} N (spec's own {float(res.at_spec.verdict_peak_force[0]):.2f} N); "
            f"{'passes' if peak <= spec.operator.force_limit else 'fails'} {spec.operator.force_limit:g} N"
        )
        goal = "<= 3 s" if path.name == "village-10m.toml" else None
        record(
            f"optimize {path.name} ({problem.model})",
            t,
            "s",
            goal,
            goal and t <= 3,
            f"best peak {peak:.2f} N",
        )


def grid_check(path: Path, m: int) -> None:
    """Brute force over the default bounds: is the optimiser's answer really the best there is?"""
    import numpy as np

    from pumplink.optimize import evaluate_designs

    problem = make_problem(load_spec(path))
    axes = [np.linspace(lo, hi, m) for lo, hi in zip(problem.lower, problem.upper)]
    x = np.array(np.meshgrid(*axes, indexing="ij")).reshape(len(axes), -1)
    best, feasible = np.inf, 0
    for i in range(0, x.shape[1], 50_000):
        ev = evaluate_designs(problem, x[:, i : i + 50_000])
        ok = np.all(ev.slack >= 0, axis=0) & np.isfinite(ev.verdict_peak_force)
        feasible += int(ok.sum())
        if ok.any():
            best = min(best, float(ev.verdict_peak_force[ok].min()))
    print(
        f"grid check {path.name} ({problem.model}): {m}^{len(axes)} = {x.shape[1]} designs over the default "
        f"bounds, {feasible} meet every constraint, lowest peak {best:.2f} N"
    )


if __name__ == "__main__":
    main()
    for m in (21, 31):
        grid_check(ROOT / "configs" / "village-10m.toml", m)
