"""Build tolerances: how the pumps a workshop builds from a design differ from it, which holes
matter, and how exactly each must be drilled (docs/tolerance.md).

Every hole and pivot of a build (:data:`pumplink.studies.builds.HOLES`) is off by a little in
each of its two coordinates (:data:`pumplink.studies.builds.DIMENSIONS`); a build is analysed as
the linkage it *is* (:func:`pumplink.studies.builds.build`) by the one evaluation.

Three results:

* **Monte Carlo** (:mod:`pumplink.studies.tolerance_study`): builds drawn with every coordinate
  independently off by a uniform ±t or a normal with 3σ = t; the spread (median, 5th and 95th
  percentile) of each quantity and the share of builds that pass with its Wilson score 95 %
  interval.  The samples are drawn per fixed chunk of :data:`CHUNK_SAMPLES` from
  ``numpy.random.default_rng([seed, chunk])``, so a build's dimensions depend on the seed and its
  number only: one process, a pool or a Dask cluster give the same numbers.
* **First order** (:func:`sensitivities`): the derivative of every check's margin (and of the
  peak and mean force) with respect to each of the 18 coordinates, by central differences through
  the evaluation; the first-order spread σ = sqrt(Σ (∂/∂x_j σ_j)²) and a first-order share of
  builds that pass, Π Φ(margin / σ) over the checks.
* **Allocation** (:func:`allocate`): per hole, the loosest tolerance from a workshop ladder
  (:data:`LADDER`) that keeps the first-order share at the target, by the equal-effect rule with
  caps (docs/tolerance.md §4).

Here: the tolerances, the margins of the checks, the problem, the first order and the allocation;
the Monte Carlo, the result and the robust search's check are :mod:`pumplink.studies.tolerance_study`.
Pure functions on floats and arrays (SI units, radians); the CLI runs the chunks on the batch
engine and :mod:`pumplink.output.tolerance` renders the result.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from pumplink.constants import AXLE_HEIGHT_RANGE_M
from pumplink.errors import InfeasibleDesign, SpecError
from pumplink.evaluate import JUDGED, PASS, WARN, Evaluation, PumpDesigns, evaluate, pump_designs
from pumplink.inputs.pump import PumpSpec
from pumplink.mechanisms.fourbar import FourBar
from pumplink.studies.builds import (
    DIMENSIONS,
    HOLE_KEYS,
    HOLES,
    PARAMETERS,
    PARTS,
    as_built,
    broadcast_column,
    build,
    first_order_map,
    take,
)

#: Central-difference step of the sensitivities [m]: the peak force's relative rounding (~1e-12)
#: over it is ~1e-7 of the derivative, its curvature (~1e4 N/m² on the shipped designs) times it
#: ~1e-4 N/m, both far below the ~1e3 N/m that matter.
STEP = 1e-5
#: Builds per chunk: fixed, so that the builds (and their numbers) do not depend on the workers.
CHUNK_SAMPLES = 1000
#: Tolerances a workshop works to [m]: the allocation's ladder (docs/tolerance.md §4).  ±5 mm is
#: "by eye"; below ±0.1 mm a hand-drilled hole cannot be held.
LADDER = (0.0001, 0.0002, 0.0005, 0.001, 0.002, 0.005)
#: What a hand-marked, hand-drilled hole holds without special care [m] (the issue's "1-2 mm"):
#: a hole whose allocated tolerance is tighter is *critical* and marked on the template.
WORKSHOP_TOLERANCE = 0.001
DISTRIBUTIONS = ("uniform", "normal")


# ----------------------------------------------------------------------------- the tolerances
@dataclass(frozen=True)
class Tolerances:
    """How far each hole may be off: ``holes[i]`` [m] for :data:`HOLES` ``[i]``, on each of its
    two coordinates; ``distribution`` "uniform" (anywhere within ±t) or "normal" (t = 3σ)."""

    holes: tuple[float, ...]
    distribution: str = "uniform"

    def __post_init__(self):
        if self.distribution not in DISTRIBUTIONS:
            raise SpecError(
                f"distribution {self.distribution!r} is unknown; choose {' or '.join(DISTRIBUTIONS)}"
            )
        if len(self.holes) != len(HOLES):
            raise ValueError(f"{len(self.holes)} tolerances for {len(HOLES)} holes")

    @property
    def per_dimension(self) -> np.ndarray:
        """t for each of :data:`DIMENSIONS` [m]."""
        return np.repeat(np.asarray(self.holes, float), 2)

    @property
    def sigma(self) -> np.ndarray:
        """The standard deviation of each of :data:`DIMENSIONS` [m]: t/√3 (uniform), t/3 (normal)."""
        return self.per_dimension * spread_factor(self.distribution)

    def tolerance(self, key: str) -> float:
        return self.holes[HOLE_KEYS.index(key)]


def spread_factor(distribution: str) -> float:
    """σ / t: 1/√3 for a uniform ±t, 1/3 for a normal with 3σ = t."""
    return 1.0 / math.sqrt(3.0) if distribution == "uniform" else 1.0 / 3.0


def tolerances(
    hole: float = WORKSHOP_TOLERANCE,
    pivot: float | None = None,
    parts: dict[str, float] | None = None,
    holes: dict[str, float] | None = None,
    distribution: str = "uniform",
) -> Tolerances:
    """Tolerances from a global one and overrides [m]: ``hole`` for every hole, ``pivot`` for the
    stand's two pivots (default ``hole``), ``parts`` per part (crank, coupler, rocker, stand),
    ``holes`` per hole key (:data:`HOLE_KEYS`); the most specific wins.

    Raises
    ------
    SpecError : an unknown part or hole, or a tolerance that is negative, not finite or over 50 mm.
    """
    parts, holes = dict(parts or {}), dict(holes or {})
    for name in parts:
        if name not in PARTS:
            raise SpecError(f"part '{name}' is unknown; the parts are {', '.join(PARTS)}")
    for name in holes:
        if name not in HOLE_KEYS:
            raise SpecError(f"hole '{name}' is unknown; the holes are {', '.join(HOLE_KEYS)}")
    out = []
    for key, part, _ in HOLES:
        t = hole if part != "stand" or pivot is None else pivot
        t = parts.get(part, t)
        t = holes.get(key, t)
        if not (math.isfinite(t) and 0.0 <= t <= 0.05):
            raise SpecError(f"the tolerance of {key} is {t * 1000:g} mm; give 0-50 mm, e.g. 1mm")
        out.append(float(t))
    return Tolerances(tuple(out), distribution)


# ----------------------------------------------------------------------------- margins
#: The margins a check gives (key, the check of the verdict, which limit, the side): one per
#: limit; a height range gives one margin per end.
def margins(ev: Evaluation, strict: bool = False) -> dict[str, np.ndarray]:
    """The distance of each check's value inside its limit [the check's unit], per design:
    positive inside, negative beyond, -inf for a design that is not a crank-rocker (or a value
    that is not a number).  ``strict``: the warn limits too (a clean PASS), else the fail limits.

    Keys: a check's key (``peak_force``, ``transmission_angle``, ...) for its fail limit, with
    ``:warn`` for its warn limit; the grip height and the axle height give one margin per end of
    their range (``grip_height_low:warn``, ``grip_height_high:warn``, ``axle_height_low:warn``...).
    """
    out: dict[str, np.ndarray] = {}
    feasible = np.asarray(ev.feasible, bool)
    n = len(ev)

    def put(key, value, limit, relation):
        v = broadcast_column(value, n)
        lim = broadcast_column(limit, n)
        with np.errstate(invalid="ignore"):  # a range check (cadence, rope speed): per design's side
            m = np.where(np.broadcast_to(np.asarray(relation) == "<=", (n,)), lim - v, v - lim)
        out[key] = np.where(feasible & ~np.isnan(m), m, -np.inf)

    d = ev.designs
    for c in ev.verdict.checks:
        if c.key == "grip_height":
            if strict:
                low, high = ev.grip_height
                put("grip_height_low:warn", low, d.grip_height_min, ">=")
                put("grip_height_high:warn", high, d.grip_height_max, "<=")
            continue
        if c.key == "axle_height":
            if strict:
                put("axle_height_low:warn", d.axle_height, AXLE_HEIGHT_RANGE_M[0], ">=")
                put("axle_height_high:warn", d.axle_height, AXLE_HEIGHT_RANGE_M[1], "<=")
            continue
        if c.fail_limit is not None:
            put(c.key, c.value, c.fail_limit, c.relation)
        if strict and c.warn_limit is not None:
            put(f"{c.key}:warn", c.value, c.warn_limit, c.relation)
    return out


def limits(ev: Evaluation, strict: bool = False) -> dict[str, float]:
    """The limit of each margin of :func:`margins`, for design 0 (to make a margin relative)."""
    v = ev.verdict.design(0)
    d = ev.designs
    out = {}
    for c in v.checks:
        if c.key == "grip_height":
            if strict:
                out["grip_height_low:warn"] = float(np.ravel(d.grip_height_min)[0])
                out["grip_height_high:warn"] = float(np.ravel(d.grip_height_max)[0])
            continue
        if c.key == "axle_height":
            if strict:
                out["axle_height_low:warn"], out["axle_height_high:warn"] = AXLE_HEIGHT_RANGE_M
            continue
        if c.fail_limit is not None:
            out[c.key] = float(c.fail_limit)
        if strict and c.warn_limit is not None:
            out[f"{c.key}:warn"] = float(c.warn_limit)
    return out


def pass_margin(m: dict[str, np.ndarray], lim: dict[str, float]) -> np.ndarray:
    """The smallest relative margin over the checks [-]: ≥ 0 exactly where every check is within
    its limit (the build passes), its value how far the nearest check is from failing."""
    return np.min(np.stack([m[k] / abs(lim[k]) for k in m]), axis=0)


# ----------------------------------------------------------------------------- the problem
@dataclass(frozen=True)
class Problem:
    """One design and its tolerances: what every chunk of builds needs (picklable, small).

    designs : the design's evaluation columns (one design);  nominal : its four-bar as designed;
    axle_height : [m] (NaN: not given);  model : a model key (``--model``) or None;
    samples, seed : the Monte Carlo's size and seed;  strict : a clean PASS counts, not PASS with
    warnings.
    """

    name: str
    designs: PumpDesigns
    nominal: FourBar
    axle_height: float
    tolerances: Tolerances
    samples: int = 10_000
    seed: int = 0
    model: str | None = None
    strict: bool = False

    @property
    def chunks(self) -> list[tuple[int, int, int]]:
        """The chunks ``(index, start, stop)`` of builds: :data:`CHUNK_SAMPLES` each, the last one
        shorter."""
        return [
            (i, s, min(self.samples, s + CHUNK_SAMPLES))
            for i, s in enumerate(range(0, self.samples, CHUNK_SAMPLES))
        ]


def problem(
    spec: PumpSpec,
    tol: Tolerances,
    samples: int = 10_000,
    seed: int = 0,
    model: str | None = None,
    strict: bool = False,
) -> Problem:
    """The tolerance problem of a rope-pump spec.

    Raises
    ------
    InfeasibleDesign : the spec gives no crank-rocker (there is nothing to build).
    """
    designs = pump_designs(spec.values)
    ev = evaluate(designs, JUDGED, model=model, fitted=True)
    if not bool(ev.feasible[0]):
        raise InfeasibleDesign(f"{spec.name}: nothing to build, the spec gives no crank-rocker")
    nominal = FourBar(*(float(np.ravel(p)[0]) for p in ev.synthesis.linkage.parameters))
    axle = math.nan if spec.wheel.axle_height is None else float(spec.wheel.axle_height)
    return Problem(spec.name, designs, nominal, axle, tol, samples, seed, model, strict)


def offsets(prob: Problem, index: int, start: int, stop: int) -> np.ndarray:
    """The (builds, 18) offsets [m] of builds ``start..stop-1``, chunk ``index``: from
    ``default_rng([seed, index])``, uniform on ±t or normal with σ = t/3 for each dimension."""
    rng = np.random.default_rng([prob.seed, index])
    m = stop - start
    t = prob.tolerances.per_dimension
    if prob.tolerances.distribution == "uniform":
        return rng.uniform(-1.0, 1.0, (m, len(DIMENSIONS))) * t
    return rng.standard_normal((m, len(DIMENSIONS))) * (t / 3.0)


def evaluate_builds(prob: Problem, offs: np.ndarray) -> Evaluation:
    """The one evaluation of builds with these offsets (:func:`build`)."""
    lk, axle = build(prob.nominal, prob.axle_height, offs)
    return evaluate(as_built(prob.designs, lk, axle), JUDGED, model=prob.model, fitted=True)


# ----------------------------------------------------------------------------- first order
@dataclass(frozen=True)
class FirstOrder:
    """The design's first-order sensitivities (central differences through the evaluation).

    margin : each margin of :func:`margins` at the design [its check's unit];  limit : its limit.
    jacobian : ∂margin/∂dimension [unit/m], (18,) per margin, over :data:`DIMENSIONS`.
    peak_force, mean_force : ∂/∂dimension [N/m], (18,).
    pass_margin : ∂(the smallest relative margin)/∂dimension [1/m], (18,): the binding check's.
    binding : the margin nearest its limit (relative).
    """

    margin: dict[str, float]
    limit: dict[str, float]
    jacobian: dict[str, np.ndarray]
    peak_force: np.ndarray
    mean_force: np.ndarray
    pass_margin: np.ndarray
    binding: str
    nominal_pass_margin: float

    def sigma(self, tol: Tolerances) -> dict[str, float]:
        """The first-order standard deviation of each margin at these tolerances [unit]."""
        s = tol.sigma
        return {k: float(np.sqrt(np.sum((j * s) ** 2))) for k, j in self.jacobian.items()}

    def share(self, tol: Tolerances) -> float:
        """The first-order share of builds that pass: Π Φ(margin / σ) over the margins (the checks
        taken as independent; docs/tolerance.md §3)."""
        return float(share_of(self.margin, self.sigma(tol)))

    def spread(self, gradient: np.ndarray, tol: Tolerances) -> float:
        """The first-order standard deviation of a quantity with this gradient [its unit]."""
        return float(np.sqrt(np.sum((gradient * tol.sigma) ** 2)))

    def contributions(self, gradient: np.ndarray, tol: Tolerances) -> np.ndarray:
        """Each hole's share of a quantity's first-order variance at these tolerances, (9,)."""
        v = ((gradient * tol.sigma) ** 2).reshape(len(HOLES), 2).sum(axis=1)
        total = v.sum()
        return v / total if total > 0 else np.zeros(len(HOLES))


def share_of(margin: dict, sigma: dict):
    """Π Φ(margin / σ) over the margins (a margin with σ = 0 counts 1 inside its limit, else 0);
    floats or arrays over designs."""
    from scipy.special import ndtr

    total = 1.0
    for k, m in margin.items():
        m, s = np.asarray(m, float), np.asarray(sigma[k], float)
        with np.errstate(divide="ignore", invalid="ignore"):
            p = np.where(s > 0, ndtr(m / np.where(s > 0, s, 1.0)), (m >= 0).astype(float))
        total = total * p
    return total


def sensitivities(prob: Problem, step: float = STEP) -> FirstOrder:
    """Central differences of every margin, the peak and the mean force with respect to each of
    the 18 dimensions, through one evaluation of the design and its 36 perturbed builds."""
    k = len(DIMENSIONS)
    offs = np.zeros((1 + 2 * k, k))
    for j in range(k):
        offs[1 + 2 * j, j] = step
        offs[2 + 2 * j, j] = -step
    ev = evaluate_builds(prob, offs)
    m = margins(ev, prob.strict)
    lim = limits(ev, prob.strict)

    def grad(x):
        x = np.asarray(x, float)
        return (x[1::2] - x[2::2]) / (2.0 * step)

    jac = {key: grad(v) for key, v in m.items()}
    ratio = {key: m[key][0] / abs(lim[key]) for key in m}
    binding = min(ratio, key=ratio.get)
    return FirstOrder(
        {key: float(v[0]) for key, v in m.items()},
        lim,
        jac,
        grad(ev.peak_force),
        grad(ev.mean_force),
        jac[binding] / abs(lim[binding]),
        binding,
        float(ratio[binding]),
    )


def first_order_shares(
    designs: PumpDesigns,
    ev: Evaluation,
    tol: Tolerances,
    strict: bool,
    model=None,
    step: float = STEP,
    only: np.ndarray | None = None,
) -> np.ndarray:
    """The first-order share of builds that pass, per design of a search's population: 0 where the
    design itself does not pass (and where ``only``, a mask over the designs, is False).  Forward
    differences in the six linkage parameters (and the axle height, exactly), mapped onto the holes
    by :func:`first_order_map`: 6 evaluations a design beside its own (docs/tolerance.md §5)."""
    n = len(ev)
    level = np.asarray(broadcast_column(ev.verdict.level, n))
    ok = np.asarray(ev.feasible, bool) & (level <= (PASS if strict else WARN))
    if only is not None:
        ok &= np.asarray(only, bool)
    out = np.zeros(n)
    rows = np.nonzero(ok)[0]
    if rows.size == 0:
        return out
    base = take(designs, rows)
    lk = ev.synthesis.linkage
    nominal = [broadcast_column(p, n)[rows] for p in lk.parameters]
    axle = (
        broadcast_column(designs.axle_height, n)[rows]
        if designs.axle_height is not None
        else np.full(rows.size, np.nan)
    )
    m0 = {key: v[rows] for key, v in margins(ev, strict).items()}
    p = len(PARAMETERS) - 1  # the axle height is exact: it moves the heights one for one
    params = [np.tile(v, p) for v in nominal]
    for i in range(p):
        params[i][i * rows.size : (i + 1) * rows.size] += step
    tiled = take(base, np.tile(np.arange(rows.size), p))
    e = evaluate(as_built(tiled, FourBar(*params), np.tile(axle, p)), JUDGED, model=model, fitted=True)
    m1 = margins(e, strict)
    mp = first_order_map()
    sigma = tol.sigma
    sig = {}
    for key in m0:
        if key not in m1:
            continue
        d = (m1[key].reshape(p, rows.size) - m0[key][None, :]) / step  # (parameters, designs)
        axle_row = {"grip_height_low:warn": 1.0, "grip_height_high:warn": -1.0}.get(key, 0.0)
        axle_row = {"axle_height_low:warn": 1.0, "axle_height_high:warn": -1.0}.get(key, axle_row)
        d = np.vstack([d, np.full((1, rows.size), axle_row)])
        holes = mp.T @ d  # (18, designs)
        sig[key] = np.sqrt(np.sum((holes * sigma[:, None]) ** 2, axis=0))
    out[rows] = share_of({k: m0[k] for k in sig}, sig)
    return out


# ----------------------------------------------------------------------------- allocation
#: The groups of holes a fitter drills alike, and the allocation gives one tolerance: the two
#: holes of each link, the grip on its own (its dimension acts through the handle alone), the
#: stand's two pivots.
GROUPS = (
    ("crank", ("crank.O2", "crank.A")),
    ("coupler", ("coupler.A", "coupler.B")),
    ("rocker", ("rocker.O4", "rocker.B")),
    ("grip", ("rocker.grip",)),
    ("stand", ("stand.O2", "stand.O4")),
)


@dataclass(frozen=True)
class Allocation:
    """The loosest workshop tolerance per group of holes that keeps the first-order share of builds
    that pass at ``target`` (docs/tolerance.md §4).

    groups : per group of :data:`GROUPS` [m], a value of :data:`LADDER` (NaN where even its
        smallest step is not enough);  share : the first-order share at these tolerances;
    reason : why there is no allocation (the design itself does not pass), else None.
    """

    target: float
    distribution: str
    groups: tuple[float, ...]
    share: float
    reason: str | None = None

    @property
    def found(self) -> bool:
        return self.reason is None and all(math.isfinite(t) for t in self.groups)

    @property
    def holes(self) -> tuple[float, ...]:
        """The tolerance of each hole of :data:`HOLES` [m] (its group's)."""
        of = {h: t for (_, hs), t in zip(GROUPS, self.groups) for h in hs}
        return tuple(of[k] for k in HOLE_KEYS)

    @property
    def critical(self) -> tuple[bool, ...]:
        """Per group: it needs more care than a hand-drilled hole gets (:data:`WORKSHOP_TOLERANCE`)."""
        return tuple(not (t >= WORKSHOP_TOLERANCE) for t in self.groups)

    @property
    def tolerances(self) -> Tolerances:
        """The allocation as tolerances (a group below the ladder at its first step)."""
        return Tolerances(tuple(np.nan_to_num(self.holes, nan=LADDER[0])), self.distribution)


def _equal_effect(s2: np.ndarray, budget: float, cap: float) -> np.ndarray:
    """σ per group with Σ s2 σ² = budget² by equal shares of the variance, a group that would
    exceed ``cap`` held at it and its share given to the others (water-filling)."""
    sig = np.full(s2.shape, cap)
    free = s2 > 0
    while free.any():
        rest = budget**2 - np.sum(s2[~free] * sig[~free] ** 2)
        if rest <= 0:
            sig[free] = 0.0
            break
        trial = np.sqrt(rest / np.count_nonzero(free) / s2[free])
        over = trial > cap
        if not over.any():
            sig[free] = trial
            break
        idx = np.nonzero(free)[0][over]
        free[idx] = False
        sig[idx] = cap
    return sig


def _ladder_floor(x: float) -> float:
    """The largest step of :data:`LADDER` not above ``x`` (NaN below the first)."""
    return max((step for step in LADDER if step <= x * (1 + 1e-12)), default=math.nan)


def allocate(fo: FirstOrder, target: float = 0.95, distribution: str = "uniform") -> Allocation:
    """Tolerances per group of holes for ``target`` of builds passing, to first order.

    The rule (docs/tolerance.md §4): each margin m_c gets a budget σ_c ≤ m_c / z with
    z = Φ⁻¹(target); within it every group gets an equal share of the variance (the equal-effect
    rule), a group that could take more than the ladder's top step is held there and its share goes
    to the others; each group keeps the tightest of its margins' tolerances, rounded down to the
    ladder.  If the checks together then fall short of the target (Π Φ(m_c/σ_c) < target), z is
    raised until they do not.  Last, rounding down leaves room: the tightest group (of a tie, the
    least sensitive) is loosened a step of the ladder while the first-order share stays at the
    target, and again, until no group can be.
    """
    from statistics import NormalDist

    nan = tuple(math.nan for _ in GROUPS)
    if fo.nominal_pass_margin < 0 or not math.isfinite(fo.nominal_pass_margin):
        return Allocation(target, distribution, nan, 0.0, f"the design itself fails ({fo.binding})")
    k = spread_factor(distribution)
    cap = LADDER[-1]
    members = [[HOLE_KEYS.index(h) for h in hs] for _, hs in GROUPS]

    def group_s2(j):
        per_hole = (j.reshape(len(HOLES), 2) ** 2).sum(axis=1)
        return np.array([per_hole[m].sum() for m in members])

    s2 = {key: group_s2(j) for key, j in fo.jacobian.items()}

    def share(t):  # a group that needs less than the ladder's first step counted at that step
        tol = np.nan_to_num(np.asarray(t, float), nan=LADDER[0])
        holes = np.zeros(len(HOLES))
        for m, x in zip(members, tol):
            holes[m] = x
        return fo.share(Tolerances(tuple(holes), distribution))

    def groups_for(z):
        t = np.full(len(GROUPS), cap)
        for key, v in s2.items():
            budget = fo.margin[key] / z if z > 0 else math.inf  # a target of 50 % or less: any spread
            t = np.minimum(t, _equal_effect(v, budget, cap * k) / k)
        return np.array([_ladder_floor(x) for x in t])

    z = NormalDist().inv_cdf(target)
    t = groups_for(z)
    for _ in range(60):  # raise z until all the checks together reach the target
        if share(t) >= target or np.isnan(t).any():
            break
        z *= 1.05
        t = groups_for(z)
    weight = sum(s2.values())
    while True:  # loosen a step at a time, the tightest group first (the least sensitive of a tie)
        order = sorted(
            (g for g in range(len(GROUPS)) if math.isfinite(t[g]) and t[g] < cap),
            key=lambda g: (t[g], weight[g]),
        )
        for g in order:
            trial = t.copy()
            trial[g] = LADDER[LADDER.index(t[g]) + 1]
            if share(trial) >= target:
                t = trial
                break
        else:
            break
    return Allocation(target, distribution, tuple(float(x) for x in t), share(t))
