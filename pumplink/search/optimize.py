"""Pump design search: the feasible linkage that needs the least operator force.

The variables, the objective and the constraints, and the candidates' evaluation, are
:mod:`pumplink.search.problem` (its module docstring gives them with their sources).

Search: ``scipy.optimize.differential_evolution`` (vectorised over the population, the
constraints by Lampinen's rule), then a local SLSQP polish; a polished point is kept only if it
is strictly feasible and better (else the feasible point on the segment toward it that is).
Deterministic for a given ``seed``.  Pure functions; the CLI renders the result.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from pumplink.errors import InfeasibleDesign
from pumplink.inputs.pump import PumpSpec, parse_spec, spec_to_dict
from pumplink.search.problem import (
    BINDING_TOL,
    INFEASIBLE_OBJECTIVE,
    SEARCH_TOL,
    VARIABLE_UNITS,
    Candidates,
    Problem,
    constraint_slack,
    evaluate_designs,
)
from pumplink.studies.tolerance_study import RobustCheck, robust_check


@dataclass(frozen=True)
class OptimizationResult:
    """Outcome of :func:`optimize` (spec units: m, deg, N)."""

    problem: Problem
    x: np.ndarray
    best: PumpSpec
    at_best: Candidates
    at_spec: Candidates
    binding: tuple[str, ...]
    at_bounds: tuple[str, ...]
    evaluations: int
    iterations: int
    polished: bool
    seed: int | None
    message: str = field(default="")
    spec_result: Any = None  # pumplink force's analysis of the spec's own design (ForceResult)
    best_result: Any = None  # ... and of the optimum (its verdict decides the exit code)
    force_evaluations: int = 0  # designs whose force was computed: those meeting every constraint
    robust: RobustCheck | None = None  # a robust search's optimum at its tolerances
    tolerance: float = SEARCH_TOL  # the relative tolerance the search stopped at (its objective's)

    @property
    def variable_units(self) -> tuple[str, ...]:
        """The unit of each varied key, in :attr:`Problem.names` order."""
        return tuple(VARIABLE_UNITS[k] for k in self.problem.names)

    @property
    def constraint_units(self) -> tuple[str, ...]:
        """The unit of each constraint's slack, in :meth:`Problem.constraint_names` order."""
        return tuple(self.problem.constraint_units())

    @property
    def constrained(self) -> tuple[float, ...]:
        """The figure each constraint bounds at the optimum, in :meth:`Problem.constraint_names`
        order: the transmission angle [deg], the grip heights and the stroke [m], the builds' share
        passing; the slack itself where the slack is the figure (the crank-rocker's margin, the
        dead-band window [deg], the verdict's relative excess).  Its size sets the decimal to which
        the search determines the slack (pumplink.output.precision)."""
        b = self.at_best
        figures = [float(g) for g in b.slack[:, 0]]
        figures[1:6] = [b.transmission[0], b.grip_low[0], b.grip_high[0], b.stroke[0], b.stroke[0]]
        if self.problem.robust is not None:
            figures[-1] += self.problem.robust.target
        return tuple(float(f) for f in figures)

    @property
    def spec_violates(self) -> tuple[str, ...]:
        """The constraints the spec's own design misses (empty: it meets them all)."""
        names = self.problem.constraint_names()
        return tuple(n for n, g in zip(names, self.at_spec.slack[:, 0]) if g < 0)

    @property
    def improvement(self) -> float | None:
        """How much lower the optimum's objective is than the spec's [N] (None when the spec's
        design has no finite objective)."""
        spec, best = float(self.at_spec.objective[0]), float(self.at_best.objective[0])
        return spec - best if spec < INFEASIBLE_OBJECTIVE / 10 else None


def _spec_with(problem: Problem, x) -> PumpSpec:
    data = spec_to_dict(problem.spec)
    data["wheel"]["axle_height"] = problem.axle_height
    for k, v in zip(problem.names, np.asarray(x, float).ravel()):
        section, _, name = k.rpartition(".")
        data.setdefault(section or "linkage", {})[name] = float(v)
    if "wheel.mass" in problem.names:
        data["wheel"].pop("inertia", None)
    data["name"] = f"{problem.spec.name} (optimised)"
    return parse_spec(data, source="optimum")


def _feasible(ev: Candidates, i: int = 0) -> bool:
    return bool(np.all(ev.slack[:, i] >= 0) and ev.objective[i] < INFEASIBLE_OBJECTIVE)


def optimize(
    problem: Problem,
    seed: int | None = 0,
    popsize: int = 20,
    maxiter: int = 300,
    tol: float = SEARCH_TOL,
    polish: bool = True,
    progress=None,
) -> OptimizationResult:
    """Global search (differential evolution, vectorised) then a local SLSQP polish.

    ``progress``: optional callable given the number of generations done after each one (for a
    progress bar; at most ``maxiter``).

    Raises
    ------
    InfeasibleDesign
        No design inside the bounds satisfies every constraint; the message names the
        constraint violated at the least-violating design found and by how much.
    """
    from scipy.optimize import NonlinearConstraint, differential_evolution, minimize

    count = [0, 0]  # designs looked at (their constraints), and those whose force was computed
    if problem.robust is not None:
        # The optimum without the builds' constraint, first: where its builds pass too, it is the
        # optimum with the constraint (a constraint the unconstrained optimum meets changes
        # nothing), found at a seventh of the cost (docs/tolerance.md §5).
        plain = optimize(replace(problem, robust=None), seed, popsize, maxiter, tol, polish, progress)
        e = evaluate_designs(problem, plain.x[:, None])
        if _feasible(e):
            return _result(
                problem, plain.x, e, plain.evaluations, plain.iterations, plain.polished, seed,
                plain.message, plain.force_evaluations, tol,
            )  # fmt: skip
        count = [plain.evaluations, plain.force_evaluations]  # the search goes on: both count

    cache: dict[bytes, Candidates] = {}
    n = len(problem.names)

    def ev(x, looked_at=True):
        x2 = np.asarray(x, float).reshape(n, -1)
        key = x2.tobytes()
        if key not in cache:
            if len(cache) > 4:
                cache.clear()
            cache[key] = evaluate_designs(problem, x2, search=True)
            count[0] += x2.shape[1] if looked_at else 0
            count[1] += x2.shape[1]
        return cache[key]

    def slack(x):
        # DE asks for the constraints of every trial design first, then for the objective of only
        # those that meet them all: the constraints need the geometry, no force model
        x2 = np.asarray(x, float).reshape(n, -1)
        count[0] += x2.shape[1]
        return constraint_slack(problem, x2)

    con = NonlinearConstraint(slack, 0.0, np.inf)
    res = differential_evolution(
        lambda x: ev(x, looked_at=False).objective,
        list(zip(problem.lower, problem.upper)),
        constraints=con,
        vectorized=True,
        updating="deferred",
        rng=seed,
        popsize=popsize,
        maxiter=maxiter,
        tol=tol,
        polish=False,
        init="sobol",
        callback=None if progress is None else (lambda intermediate_result: progress(1)),
    )
    x = np.asarray(res.x, float)
    e = evaluate_designs(problem, x[:, None])
    if not _feasible(e):
        names = problem.constraint_names()
        if np.all(e.slack[:, 0] >= 0):  # constraints met, but the objective is not finite
            fix = (
                "give the wheel more inertia (wheel.mass) or allow more speed fluctuation"
                if problem.flywheel
                else "give operator.dead_band > 0"
            )
            raise InfeasibleDesign(
                f"no design inside the bounds needs a finite {problem.objective} force "
                f"({problem.model} model): the "
                f"best one found ({_fmt_x(problem, x)}) meets every constraint but needs more than "
                f"{INFEASIBLE_OBJECTIVE:g} N; {fix}"
            )
        j = int(np.argmin(e.slack[:, 0]))
        unit = problem.constraint_units()[j]
        raise InfeasibleDesign(
            f"no design inside the bounds meets every constraint: the closest one found "
            f"({_fmt_x(problem, x)}) misses '{names[j]}' by {-e.slack[j, 0]:.4g} {unit}; "
            f"widen the --vary bounds or relax --grip-height / --stroke / --axle-height"
        )
    polished = False
    if polish:
        scale = problem.upper - problem.lower
        gradient_points: dict[bytes, float] = {}

        def f(z):
            key = np.asarray(z, float).tobytes()
            if key in gradient_points:
                return gradient_points.pop(key)
            return float(ev(problem.lower + z * scale).objective[0])

        def g(z):
            # the constraints need the geometry only, no force model
            x2 = (problem.lower + np.asarray(z, float) * scale)[:, None]
            return constraint_slack(problem, x2)[:, 0]

        def gradient_map(fun, points):
            # SLSQP's finite-difference gradient asks for n + 1 objective values at once: one
            # vectorised evaluation of them all, then each handed back through ``fun``
            zs = [np.asarray(z, float) for z in points]
            objective = ev(problem.lower[:, None] + np.stack(zs, axis=1) * scale[:, None]).objective
            gradient_points.update((z.tobytes(), float(v)) for z, v in zip(zs, objective))
            return [fun(z) for z in zs]

        z0 = (x - problem.lower) / scale
        loc = minimize(
            f,
            z0,
            method="SLSQP",
            bounds=[(0.0, 1.0)] * n,
            constraints=[{"type": "ineq", "fun": g}],
            options=dict(maxiter=200, ftol=1e-12, workers=gradient_map),
        )
        # lower + 1.0 * (upper - lower) can round one ulp past the upper bound: clip in x too
        xp = np.clip(problem.lower + np.clip(loc.x, 0.0, 1.0) * scale, problem.lower, problem.upper)
        cand = _pull_back(problem, x, xp)
        if cand is not None:
            cand = np.clip(cand, problem.lower, problem.upper)
            ec = evaluate_designs(problem, cand[:, None])
            if _feasible(ec) and ec.objective[0] < e.objective[0]:
                x, e, polished = cand, ec, True
    return _result(problem, x, e, count[0], int(res.nit), polished, seed, str(res.message), count[1], tol)


def _result(
    problem: Problem, x, e: Candidates, looked_at, nit, polished, seed, message, forced, tol
) -> OptimizationResult:
    """The result at the optimum ``x`` (its evaluation ``e``): the spec's own design beside it,
    what binds, both verdicts as pumplink force gives them and a robust search's check."""
    spec_x = np.array([problem.spec_value(k) for k in problem.names])
    at_spec = evaluate_designs(problem, spec_x[:, None])
    names = problem.constraint_names()
    binding = tuple(nm for nm, s in zip(names, e.slack[:, 0]) if s <= BINDING_TOL)
    span = problem.upper - problem.lower
    at_bounds = tuple(
        f"{k} at {'lower' if abs(v - lo) <= 1e-6 * s else 'upper'} bound"
        for k, v, lo, hi, s in zip(problem.names, x, problem.lower, problem.upper, span)
        if min(abs(v - lo), abs(hi - v)) <= 1e-6 * s
    )
    from pumplink.studies.force import force_analysis

    best = _spec_with(problem, x)
    check = None if problem.robust is None else robust_check(best, problem.robust, problem.forced)
    return OptimizationResult(
        problem,
        x,
        best,
        e,
        at_spec,
        binding,
        at_bounds,
        looked_at,
        nit,
        polished,
        seed,
        message,
        # the verdicts, exactly as pumplink force gives them on each spec (one verdict)
        force_analysis(problem.spec, keep_samples=False, samples=0, model=problem.forced),
        force_analysis(best, keep_samples=False, samples=0, model=problem.forced),
        forced,
        check,
        tol,
    )


def _pull_back(problem: Problem, good: np.ndarray, cand: np.ndarray, steps: int = 40):
    """``cand`` if feasible, else the feasible point nearest to it on the segment from ``good``."""
    t = np.linspace(1.0, 0.0, steps + 1)
    pts = good[:, None] + (cand - good)[:, None] * t[None, :]
    e = evaluate_designs(problem, pts)
    ok = np.all(e.slack >= 0, axis=0) & (e.objective < INFEASIBLE_OBJECTIVE)
    if ok[0]:
        return cand
    idx = np.nonzero(ok)[0]
    if idx.size == 0 or idx[0] == steps:
        return None
    # Bisect between the last infeasible and the first feasible sample.  The steps look at the
    # constraints only (the geometry, no force model); the point they end at is checked in full,
    # and only if its force is not finite is the bisection repeated with the force (the same
    # point wherever the force is finite along the segment, at a fiftieth of the cost).
    lo_t, hi_t = t[idx[0]], t[idx[0] - 1]
    for full in (False, True):
        lo, hi = lo_t, hi_t
        for _ in range(50):
            mid = 0.5 * (lo + hi)
            x2 = (good + (cand - good) * mid)[:, None]
            ok = (
                _feasible(evaluate_designs(problem, x2))
                if full
                else np.all(constraint_slack(problem, x2) >= 0)
            )
            if ok:
                lo = mid
            else:
                hi = mid
        if _feasible(evaluate_designs(problem, (good + (cand - good) * lo)[:, None])):
            break
    return good + (cand - good) * lo


def _fmt_x(problem: Problem, x) -> str:
    return ", ".join(f"{k} = {v:.4g} {VARIABLE_UNITS[k]}" for k, v in zip(problem.names, np.ravel(x)))


def best_spec_dict(result: OptimizationResult) -> dict:
    """The optimum as a spec mapping for tomli-w (``--write``)."""
    return spec_to_dict(result.best)
