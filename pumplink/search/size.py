"""Size the whole rope pump: the pipe, the wheel, the cadence, the handle and the linkage that give
the most water one operator can pump, with no check failing and, by default, none warning.

The question a pump designer brings: "which pipe, wheel, handle and pace give this village the
most water one of its people can pump for an hour?".  The water is the rope pump's flow
Q = η_v (π d²/4) ω̄ r_w (docs/water.md §1); every candidate is judged by the one evaluation
(:func:`pumplink.evaluate.evaluate`), so the answer is what ``pumplink force`` says of it.

The search.  The pipe bore is a discrete choice (standard sizes, or the user's list); for each
bore the continuous variables (cadence, wheel radius and mass, handle, rocker, swing, the rocker
pivot's place L1 and D1, the axle height) are searched by scipy's differential evolution,
vectorised over the population: the objective is the flow (a formula, no model), the constraint
the verdict's excess over its limits (the sum of each check's relative distance beyond its warn
limit and beyond its fail limit, or beyond its fail limit alone when warnings are accepted;
:func:`pumplink.evaluate.excess`), which is 0 exactly when no check warns (fails).  The best bore
wins; a final polish is not needed for a flow that the limits bound, but the optimum rounded to
workshop figures is moved back inside the limits it touches (:data:`ROUNDING`).

Why the answer approaches Q*: the operator's power is Mw ω̄ = ρ g H Q / (η_f η_v), so the
no-warning limit on power is exactly Q ≤ Q* = η_f η_v P_sustained / (ρ g H); what else binds (the
force, the grip's speed, stroke or height) is reported, and :func:`relax` shows that easing it
raises the share.

Pure functions; the CLI renders the result.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np

from pumplink.errors import SpecError
from pumplink.evaluate import (
    JUDGED,
    SCREENED_CHECKS,
    WARN,
    Evaluation,
    evaluate,
    excess,
    pump_designs,
    rope_pump_flow,
)
from pumplink.inputs.pump import PumpSpec, parse_spec, spec_to_dict
from pumplink.studies.tolerance_study import Robust, RobustCheck, robust_check, shortfall
from pumplink.studies.workshop import ratchet_needed

#: Nominal pipe bores searched by default [m]: ½", ¾", 1", 1¼" and 1½" (12.7-38.1 mm), the sizes
#: rope-pump rising mains are made of.  They are the nominal inch sizes, not measured bores: give
#: your pipe's real bore with ``--pipes``.
STANDARD_PIPES = (0.0127, 0.01905, 0.0254, 0.03175, 0.0381)
#: The smallest rising main a rope piston is made for [m]: ½", the smallest nominal size of
#: :data:`STANDARD_PIPES`.  A piston is a washer knotted on a 6 mm (1/4") rope (ropepump.com,
#: "Operation, Maintenance and Repair"); in a ½" bore it leaves a 3.35 mm ring around the rope,
#: in an 8 mm bore 1 mm.  The rope-pump manuals' tables of tube size by depth (University of Twente
#: WOT manual, Tables 1-2; Arrakis P-model manual §1.8) could not be read here (docs/optimize.md).
MIN_PIPE = 0.0127
#: What the search varies, with its bounds (spec units: m, kg, deg, deg/s; docs/optimize.md, "Sizing
#: the whole pump"):
#: the cadence 10 to 90 turns a minute (the verdict holds it in the profile's range unless
#: warnings are allowed); the wheel a tyre rim of 12" to 28" (radius 0.15-0.35 m) with up to
#: 15 kg at its rim: the village wheel's 10 kg of two 20" bead rims and a rebar ring (ropepump.com,
#: "Manual of experiences and tolerances", C.e; configs/village-10m.toml) and half as much ring
#: again, what a workshop welds into a rim; the axle height the pump paper's 0.40-0.70 m (outside
#: it the verdict warns); the handle 0.5-1.6 m, the rocker 0.10-0.40 m and the swing 30-100 deg
#: (docs/optimize.md); the rocker pivot 0-1 m beyond the stand and 0.6 m above to 0.6 m below
#: the axle, no deeper than the ground unless a pit is allowed (``allow_pit``).
BOUNDS = {
    "operator.speed": (60.0, 540.0),
    "wheel.radius": (0.15, 0.35),
    "wheel.mass": (1.0, 15.0),
    "wheel.axle_height": (0.40, 0.70),
    "linkage.handle": (0.5, 1.6),
    "linkage.rocker": (0.10, 0.40),
    "linkage.swing": (30.0, 100.0),
    "linkage.L1": (0.0, 1.0),
    "linkage.D1": (-0.6, 0.6),
}
#: What ``--keep`` can hold at the base spec's value, and the varied keys each holds.
KEEP = {
    "wheel": ("wheel.radius", "wheel.mass"),
    "pipe": (),
    "handle": ("linkage.handle",),
}
#: What a kilogram of wheel costs in the objective [l/min]: where the operator's power caps the
#: flow (Q*), many designs give the same water, and this picks the one with the lightest wheel
#: (30 kg cost 0.15 l/min, half a per cent of a typical answer).
WHEEL_MASS_COST = 0.005
#: The decimals a workshop measures each varied key to (spec units: 1 deg/s, 0.1 kg, 0.1 deg;
#: every other key 1 mm).
ROUNDING = {"operator.speed": 0, "wheel.mass": 1, "linkage.swing": 1}
#: The largest miss of the search's best design, as found (its constraint: the excess of
#: :func:`pumplink.evaluate.excess`, and a robust search's shortfall), that the repair of the
#: rounded design (``_workshop``) tries to close.  A workshop unit moves a value by 0.1-1 %
#: (1 deg/s of 300 deg/s, 1 mm of a 0.1-0.35 m length, 0.1 kg of 10 kg), so its 30 steps close a
#: few per cent at most; the misses it closed at 15 m for women with a ¾" pipe (seeds 0-5) were
#: 0.006-0.022, while a bore that cannot meet the limits misses by 0.17 or more (35 m, women).
REPAIR_REACH = 0.05
#: The constraint value of a design with no crank-rocker (differential evolution ranks them by it).
INFEASIBLE = 1e3
#: A check counts as binding when its value is within this share of its limit.
BINDING_SHARE = 0.01


@dataclass(frozen=True)
class SizeProblem:
    """What to size: the base spec (its head, operator and everything not varied), the pipe bores
    to choose from, the varied keys and their bounds, and whether warnings are allowed."""

    spec: PumpSpec
    pipes: tuple[float, ...]
    bounds: dict[str, tuple[float, float]] = field(default_factory=lambda: dict(BOUNDS))
    allow_warnings: bool = False
    robust: Robust | None = None  # at least this share of builds at these tolerances pass
    allow_pit: bool = False  # the rocker pivot may sit below the ground (in a pit)
    kept: tuple[str, ...] = ()  # what --keep holds at the base spec's value (KEEP's names)
    held: tuple = ()  # (key, the base's value, the built-in design's) where the base differs

    @property
    def names(self) -> tuple[str, ...]:
        return tuple(self.bounds)


@dataclass(frozen=True)
class Sized:
    """One pipe bore's best design: its spec, evaluation and flow [m³/s].  Where no design of
    this bore meets the limits (``found`` False) they are the closest one's, and ``excess`` says by
    how much it misses (:func:`excess`); ``shortfall`` how far the first-order share of builds that
    pass falls short of a robust search's target (0 without one)."""

    pipe: float
    spec: PumpSpec
    evaluation: Evaluation
    flow: float
    excess: float
    shortfall: float = 0.0

    @property
    def found(self) -> bool:
        return self.excess == 0.0 and self.shortfall == 0.0


@dataclass(frozen=True)
class SizeResult:
    """The sized pump (the best bore's design), every bore tried, and what binds it."""

    problem: SizeProblem
    best: Sized
    tried: tuple[Sized, ...]
    binding: tuple[str, ...]  # the checks at their limit, and variables at a bound
    evaluations: int
    discharge: tuple = ()  # (head [m], fastest passing cadence [deg/s], flow [m³/s]) at other heads
    robust: RobustCheck | None = None  # a robust search's answer at its tolerances (found only)

    @property
    def found(self) -> bool:
        return self.best.found


def _values(problem: SizeProblem, pipe: float, x: np.ndarray) -> dict:
    """The spec values :func:`pumplink.evaluate.pump_designs` reads: x (variables, designs) on the
    varied keys, this pipe, the base spec elsewhere."""
    # the wheel's mass is varied instead of its inertia (unless the wheel is kept as it is)
    inertia = {} if "wheel" in problem.kept else {"wheel.inertia": None}
    return {**problem.spec.values, "load.pipe_diameter": pipe, **inertia,
            **dict(zip(problem.names, x))}  # fmt: skip


def pit_depth(problem: SizeProblem, x: np.ndarray) -> np.ndarray:
    """How far below the ground the rocker pivot of designs x sits [m] (D1 − axle height; ≤ 0: at
    or above the ground), with the base spec's value of a key that is not varied."""
    values = _values(problem, problem.pipes[0], x)
    d1, axle = values.get("linkage.D1"), values.get("wheel.axle_height")
    if d1 is None or axle is None:
        return np.zeros(np.shape(x)[1:])
    return np.asarray(d1, float) - np.asarray(axle, float)


def _flow(problem: SizeProblem, pipe: float, x: np.ndarray) -> np.ndarray:
    """The flow of designs x [m³/s] (a formula: no model) through :func:`evaluate`'s columns."""
    d = pump_designs(_values(problem, pipe, x))
    return np.asarray(rope_pump_flow(pipe, d.speed, d.wheel_radius, d.volumetric_efficiency), float)


def size_pipe(problem: SizeProblem, pipe: float, seed: int = 0, maxiter: int = 30, popsize: int = 8):
    """The best design for one pipe bore: (Sized, evaluations)."""
    from scipy.optimize import NonlinearConstraint, differential_evolution

    names = problem.names
    lower = np.array([problem.bounds[k][0] for k in names])
    upper = np.array([problem.bounds[k][1] for k in names])
    count = [0]
    cache: dict[bytes, np.ndarray] = {}

    def violation(x):
        x = np.asarray(x, float).reshape(len(names), -1)
        key = x.tobytes()
        if key not in cache:
            if len(cache) > 8:
                cache.clear()
            d = pump_designs(_values(problem, pipe, x))
            ev = evaluate(d, JUDGED, screen_parts=True, fitted=True)
            over = excess(ev.verdict, problem.allow_warnings, INFEASIBLE, screened=SCREENED_CHECKS)
            v = np.where(ev.feasible, over, INFEASIBLE)
            if not problem.allow_pit:  # the pivot no deeper than the ground: D1 <= axle height
                v = v + np.maximum(pit_depth(problem, x), 0.0)
            if problem.robust is not None:  # the builds too: the first-order share's shortfall
                v = v + shortfall(d, ev, problem.robust)
            cache[key] = v
            count[0] += x.shape[1]
        return cache[key]

    def objective(x):
        x = np.asarray(x, float).reshape(len(names), -1)
        mass = x[names.index("wheel.mass")] if "wheel.mass" in names else 0.0
        return -_flow(problem, pipe, x) * 6e4 + WHEEL_MASS_COST * mass  # l/min, negated: DE minimises

    res = differential_evolution(
        objective,
        list(zip(lower, upper)),
        constraints=NonlinearConstraint(lambda x: violation(x)[None, :], -np.inf, 0.0),
        vectorized=True,
        updating="deferred",
        rng=seed,
        popsize=popsize,
        maxiter=maxiter,
        tol=1e-6,
        polish=False,
        init="sobol",
    )
    x = np.asarray(res.x, float)

    def misses(spec, ev) -> tuple[float, float]:
        over = float(excess(ev.verdict, problem.allow_warnings, INFEASIBLE)[0])
        if problem.robust is None:
            return over, 0.0
        return over, float(shortfall(pump_designs(spec.values), ev, problem.robust)[0])

    if float(violation(x[:, None])[0]) <= REPAIR_REACH:  # rounding or a hair from the limits
        x = _workshop(problem, x, violation, objective)
    spec = spec_of(problem, pipe, x)
    ev = evaluate(pump_designs(spec.values), fitted=True)
    return Sized(pipe, spec, ev, float(ev.water.flow[0]), *misses(spec, ev)), count[0]


def _workshop(problem: SizeProblem, x: np.ndarray, violation, objective, steps: int = 30) -> np.ndarray:
    """The search's design x rounded to workshop figures (:data:`ROUNDING`) and moved, a workshop
    unit at a time, until it meets the limits.

    The optimum touches its limits: rounding can step over one, and the search's best design can
    miss one by a hair.  Which way back depends on the limit (a slower wheel lowers the power and
    the grip's speed but raises a flywheel's peak force; the grip's height moves with the axle, the
    handle and the pivot), and where two limits bind it takes two keys at once (a slower and
    heavier wheel).  So each step tries every key one unit up and down, then, if none of those
    comes closer, every pair of keys: it takes a neighbour that meets the limits with the most
    water, else the one closest to meeting them (:func:`excess`), until one meets them or none
    comes closer (the closest design is then returned as it is).  The caller repairs only a design
    that misses by at most :data:`REPAIR_REACH`: the steps cannot close more."""
    names = problem.names
    unit = np.array([10.0 ** -ROUNDING.get(k, 3) for k in names])
    lower = np.array([problem.bounds[k][0] for k in names])
    upper = np.array([problem.bounds[k][1] for k in names])
    single = np.vstack([np.diag(unit), -np.diag(unit)])
    n = len(names)
    pairs = np.array([a + b for i, a in enumerate(single) for j, b in enumerate(single) if i % n < j % n])

    def lattice(y):
        return np.array([round(float(v), ROUNDING.get(k, 3)) for k, v in zip(names, y)])

    here = lattice(x)
    miss = float(violation(here[:, None])[0])
    for _ in range(steps):
        if miss == 0.0:
            break
        for moves in (single, pairs):
            near = np.array([lattice(np.clip(here + d, lower, upper)) for d in moves]).T
            v = violation(near)
            if np.any(v == 0.0):
                ok = np.nonzero(v == 0.0)[0]
                return near[:, ok[np.argmin(objective(near[:, ok]))]]
            if float(v.min()) < miss:
                here, miss = near[:, int(np.argmin(v))], float(v.min())
                break
        else:
            break
    return here


def spec_of(problem: SizeProblem, pipe: float, x) -> PumpSpec:
    """The spec of a sized design (values rounded to what a workshop measures: 1 mm, 0.1 kg,
    0.1 deg, 1 deg/s), named after the base."""
    data = spec_to_dict(problem.spec)
    for k, v in zip(problem.names, np.ravel(x)):
        section, name = k.split(".")
        data.setdefault(section, {})[name] = round(float(v), ROUNDING.get(k, 3))
    data["load"] = {k: v for k, v in data["load"].items() if k != "rope_force"}
    data["load"]["pipe_diameter"] = pipe
    if "wheel" not in problem.kept:
        data["wheel"].pop("inertia", None)
    data["name"] = f"{problem.spec.name} (sized)"
    spec = parse_spec(data, source="the sized design")
    ratchet = ratchet_needed(spec)  # the back-stop its water column needs (docs/workshop.md §3)
    return spec if ratchet is None else parse_spec({**data, "ratchet": ratchet}, source="the sized design")


def size(problem: SizeProblem, seed: int = 0, progress=None, maxiter: int = 30) -> SizeResult:
    """Size the pump: the best design for each pipe bore, and the bore with the most water.

    Bores are tried from the smallest; once one meets the limits, the first larger one that does
    not ends the search (a larger bore needs more force for the same flow, so the bores that can
    meet the limits form one run).  ``progress(1)`` is called after each bore.

    Raises
    ------
    SpecError : the base spec gives no head (there is no water to size for).
    """
    if problem.spec.load.head is None:
        raise SpecError(
            f"{problem.spec.name}: sizing needs the pumping head; give load.head [m] (or --head), not "
            "load.rope_force"
        )
    tried, evaluations = [], 0
    for pipe in sorted(problem.pipes):
        s, n = size_pipe(problem, pipe, seed, maxiter)
        tried.append(s)
        evaluations += n
        if progress is not None:
            progress(1)
        if not s.found and any(t.found for t in tried):
            break
    found = [s for s in tried if s.found]
    best = max(found, key=lambda s: s.flow) if found else min(tried, key=lambda s: (s.excess, s.shortfall))
    table = ()
    check = None
    if best.found:
        table = tuple(discharge(best.spec, discharge_heads(best.spec.load.head), problem.allow_warnings))
        if problem.robust is not None:  # the Monte Carlo check of the first-order answer
            check = robust_check(best.spec, problem.robust)
    return SizeResult(problem, best, tuple(tried), _binding(problem, best), evaluations, table, check)


def discharge_heads(head: float) -> list[float]:
    """The heads of the discharge table [m]: the design head and 0.5, 0.75, 1.25 and 1.5 times it
    (to 0.1 m)."""
    return sorted({round(head * k, 1) for k in (0.5, 0.75, 1.0, 1.25, 1.5)})


def _binding(problem: SizeProblem, best: Sized) -> tuple[str, ...]:
    """The checks within :data:`BINDING_SHARE` of their limit, and the varied keys at a bound.
    Where nothing is that close yet the flow is short of Q*, the check nearest its limit (the least
    relative slack) is named: it is what holds the flow back."""
    out, slack = [], {}
    v = best.evaluation.verdict.design(0)
    for c in v.checks:
        lim = c.warn_limit if (c.warn_limit is not None and not problem.allow_warnings) else c.fail_limit
        if lim is None or not math.isfinite(float(c.value)) or c.key == "axle_height":
            continue
        gap = (float(lim) - float(c.value)) if c.relation == "<=" else (float(c.value) - float(lim))
        slack[c.key] = gap / abs(float(lim))
        if abs(gap) <= BINDING_SHARE * abs(float(lim)):
            out.append(c.key)
    values = best.spec.values
    for k, (lo, hi) in problem.bounds.items():
        x = values.get(k)
        if x is not None and min(abs(x - lo), abs(hi - x)) <= 1e-3 * (hi - lo):
            out.append(f"{k} at its {'lower' if abs(x - lo) <= abs(hi - x) else 'upper'} bound")
    short = float(best.evaluation.water.share[0]) < 0.95
    if short and not any(k in slack for k in out) and slack:
        out.insert(0, min(slack, key=slack.get))
    return tuple(out)


def discharge(spec: PumpSpec, heads, allow_warnings: bool = False, speeds=None):
    """The sized pump at other heads: for each head [m], the fastest cadence [deg/s] at which it
    still passes without warnings (or failures, with ``allow_warnings``), on a grid of cadences,
    and the flow there [m³/s] (NaN, NaN where no cadence passes)."""
    speeds = np.arange(30.0, 721.0, 5.0) if speeds is None else np.asarray(speeds, float)
    base = spec.values
    out = []
    for h in heads:
        values = {**base, "load.head": float(h), "operator.speed": speeds}
        ev = evaluate(pump_designs(values), JUDGED, screen_parts=True, fitted=True)
        ok = np.asarray(ev.verdict.level) <= (WARN if allow_warnings else 0)
        ok = np.broadcast_to(ok, speeds.shape)
        if ok.any():
            i = int(np.nonzero(ok)[0].max())
            out.append((float(h), float(speeds[i]), float(ev.water.flow[i])))
        else:
            out.append((float(h), math.nan, math.nan))
    return out


def problem_for(
    spec: PumpSpec,
    head: float | None = None,
    profile: str | None = None,
    pipes=None,
    allow_warnings: bool = False,
    robust: Robust | None = None,
    keep=(),
    allow_pit: bool = False,
) -> SizeProblem:
    """A sizing problem from a base spec: ``head`` [m] and ``profile`` replace the spec's;
    ``robust``: at least its share of builds at its tolerances must pass (docs/tolerance.md §5);
    ``keep``: names of :data:`KEEP` held at the base spec's values (its wheel, its rising main, its
    handle); ``allow_pit``: the rocker pivot may sit below the ground.

    Raises
    ------
    SpecError : no head; a bore below :data:`MIN_PIPE`; something to keep the base does not give.
    """
    data = spec_to_dict(spec)
    load = {k: v for k, v in data["load"].items() if k != "rope_force"}
    if head is not None:
        load["head"] = float(head)
    keep = tuple(dict.fromkeys(keep))
    unknown = [k for k in keep if k not in KEEP]
    if unknown:
        raise SpecError(f"--keep {','.join(unknown)}: choose from {', '.join(KEEP)} (e.g. --keep wheel,pipe)")
    if "pipe" in keep:
        if pipes is not None:
            raise SpecError(
                "--keep pipe holds the base spec's rising main; give --pipes or --keep pipe, not both"
            )
        if spec.load.pipe_diameter is None:
            raise SpecError(
                f"--keep pipe: {spec.name} gives no load.pipe_diameter to keep; give the spec of the "
                "pump you have, or the bore with --pipes"
            )
        pipes = (spec.load.pipe_diameter,)
    if "wheel" in keep and spec.wheel.mass is None and spec.wheel.inertia is None:
        raise SpecError(
            f"--keep wheel: {spec.name} gives neither wheel.mass nor wheel.inertia to keep; give the "
            "spec of the pump you have (e.g. pumplink size configs/village-10m.toml --keep wheel)"
        )
    load.setdefault("pipe_diameter", STANDARD_PIPES[0])
    data["load"] = load
    if profile is not None:
        data.setdefault("operator", {})["profile"] = profile
        data["operator"].pop("force_limit", None)  # the profile's, unless the user overrides it
    if "wheel" not in keep:
        data.setdefault("wheel", {}).setdefault("mass", 10.0)
        data["wheel"].pop("inertia", None)
    base = parse_spec(data, source="the sizing base")
    if base.load.head is None:
        raise SpecError("sizing needs the pumping head: give --head [m] or load.head in the spec")
    chosen = tuple(STANDARD_PIPES if pipes is None else pipes)
    if not chosen or any(not (MIN_PIPE <= p <= 0.5) for p in chosen):
        given = ", ".join(f"{p * 1000:g}" for p in chosen)
        small = ", ".join(f"{p * 1000:g}" for p in chosen if p < MIN_PIPE)
        why = f'; {small} mm is smaller than the ½" (12.7 mm) rope pistons are made for' if small else ""
        raise SpecError(
            f"--pipes {given} mm: each bore must be {MIN_PIPE * 1000:g}-500 mm{why} (e.g. --pipes "
            "16,20,25mm; docs/optimize.md, Sizing the whole pump)"
        )
    if robust is not None:  # the builds are judged as the design is: warnings fail unless allowed
        robust = replace(robust, strict=not allow_warnings)
    held_keys = {k for name in keep for k in KEEP[name]}
    bounds = {k: v for k, v in BOUNDS.items() if k not in held_keys}
    return SizeProblem(
        base, chosen, bounds, allow_warnings, robust, allow_pit, keep, _differences(base, bounds)
    )


#: Spec keys :func:`_differences` leaves out: the well and the operator are the question, not the
#: base; the wheel's mass, the load's pipe are varied or kept, and the name is a name.
_NOT_HELD = (
    "name",
    "load.head",
    "load.pipe_diameter",
    "load.rope_force",
    "operator.profile",
    "operator.force_limit",
)


def _differences(base: PumpSpec, bounds) -> tuple:
    """The base spec's values the search does not vary and that differ from the built-in design's
    (the design ``pumplink size`` starts from without a spec): (key, base value, built-in value or
    None), so that the output can say why two routes to the same well give two pumps."""
    from pumplink.inputs.pump import default_spec

    mine, builtin = base.values, default_spec().values
    out = []
    for key in sorted(set(mine) | set(builtin)):
        if key in bounds or key in _NOT_HELD or key == "wheel.inertia":
            continue
        a, b = mine.get(key), builtin.get(key)
        if a != b and not (key == "wheel.mass" and "wheel.mass" in bounds):
            out.append((key, a, b))
    return tuple(out)


__all__ = [
    "BOUNDS",
    "KEEP",
    "MIN_PIPE",
    "STANDARD_PIPES",
    "SizeProblem",
    "SizeResult",
    "Sized",
    "discharge",
    "problem_for",
    "size",
    "spec_of",
]
