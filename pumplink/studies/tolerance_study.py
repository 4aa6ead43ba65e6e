"""The tolerance study of one design (``pumplink tolerance``) and the robust search's check.

* **Monte Carlo** (:func:`run_chunk`, :func:`summarize`): the builds of a
  :class:`pumplink.studies.tolerance.Problem`, drawn per fixed chunk of
  :data:`pumplink.studies.tolerance.CHUNK_SAMPLES` (:func:`pumplink.studies.tolerance.offsets`),
  through the one evaluation: the spread (median, 5th and 95th percentile) of each quantity and
  the share of builds that pass with its Wilson score 95 % interval;
* with the first order and the allocation of :mod:`pumplink.studies.tolerance`, one
  :class:`Result` (docs/tolerance.md);
* what a robust search asks and how its answer is checked (:class:`Robust`, :func:`robust_check`).

Pure functions on floats and arrays (SI units, radians).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Iterator
from dataclasses import dataclass, field

import numpy as np

from pumplink.evaluate import FAIL, MODEL_LABELS, PASS, WARN, Evaluation, PumpDesigns
from pumplink.inputs.pump import PumpSpec
from pumplink.malloc import tune_malloc
from pumplink.studies.builds import DIMENSIONS, HOLES, broadcast_column
from pumplink.studies.tolerance import (
    GROUPS,
    LADDER,
    WORKSHOP_TOLERANCE,
    Allocation,
    FirstOrder,
    Problem,
    Tolerances,
    allocate,
    evaluate_builds,
    first_order_shares,
    offsets,
    problem,
    sensitivities,
)

#: Coverage of the share's confidence interval (Wilson score interval).
CONFIDENCE = 0.95
#: The quantities whose spread is reported, with their SI unit.
QUANTITIES = (
    ("swing", "rad"),
    ("stroke", "m"),
    ("grip_low", "m"),
    ("grip_high", "m"),
    ("dead_centre_extended", "rad"),
    ("dead_centre_folded", "rad"),
    ("transmission_angle", "rad"),
    ("grip_speed", "m/s"),
    ("peak_force", "N"),
    ("mean_force", "N"),
    ("flow", "m3/s"),
)


def quantities(ev: Evaluation) -> dict[str, np.ndarray]:
    """The reported quantities of :data:`QUANTITIES` per design (NaN where not defined)."""
    syn, n = ev.synthesis, len(ev)
    nan = np.full(n, np.nan)
    low, high = ev.grip_height if ev.grip_height is not None else (nan, nan)
    return {
        "swing": broadcast_column(syn.swing, n),
        "stroke": broadcast_column(ev.stroke, n),
        "grip_low": broadcast_column(low, n),
        "grip_high": broadcast_column(high, n),
        "dead_centre_extended": broadcast_column(syn.dead_centre_extended, n),
        "dead_centre_folded": broadcast_column(syn.dead_centre_folded, n),
        "transmission_angle": broadcast_column(ev.transmission_angle, n),
        "grip_speed": broadcast_column(ev.grip_speed, n),
        "peak_force": broadcast_column(ev.peak_force, n),
        "mean_force": broadcast_column(ev.mean_force, n),
        "flow": broadcast_column(ev.water.flow, n),
    }


@dataclass(frozen=True)
class BuildChunk:
    """The builds ``start..stop-1`` (chunk ``index``): each quantity per build, the verdict's
    level, the deciding model, and how many builds fail and warn on each check."""

    index: int
    start: int
    stop: int
    values: dict[str, np.ndarray]
    level: np.ndarray
    model_index: np.ndarray
    fails: dict[str, int]
    warns: dict[str, int]

    def __len__(self) -> int:
        return self.stop - self.start


def run_chunk(prob: Problem, task: tuple[int, int, int]) -> BuildChunk:
    """One chunk of builds through the one evaluation (a task of the batch engine)."""
    index, start, stop = task
    ev = evaluate_builds(prob, offsets(prob, index, start, stop))
    fails, warns = {}, {}
    for c in ev.verdict.checks:
        lv = broadcast_column(c.level, len(ev))
        fails[c.key] = int(np.count_nonzero(lv == FAIL))
        warns[c.key] = int(np.count_nonzero(lv == WARN))
    return BuildChunk(
        index,
        start,
        stop,
        quantities(ev),
        broadcast_column(ev.verdict.level, len(ev)).astype(np.int8),
        np.asarray(ev.model_index, np.int8),
        fails,
        warns,
    )


def run_chunks(prob: Problem, mapper: Callable | None = None) -> Iterator[BuildChunk]:
    """Every chunk of builds, in order: ``mapper(run_chunk, [(prob, task), ...])`` (the batch
    engine's, on a pool or a cluster), else one after the other in this process."""
    items = [(prob, t) for t in prob.chunks]
    if mapper is None:
        return (run_chunk(p, t) for p, t in items)
    return mapper(run_chunk, items)


# ----------------------------------------------------------------------------- the result
@dataclass(frozen=True)
class Spread:
    """A quantity over the builds: the design's value, and the median, 5th and 95th percentile
    over the builds that are crank-rockers, the sample standard deviation [SI unit]."""

    nominal: float
    median: float
    p5: float
    p95: float
    std: float


@dataclass(frozen=True)
class Share:
    """How many builds of ``n`` do something, and the Wilson score interval of the share."""

    count: int
    n: int
    low: float
    high: float

    @property
    def value(self) -> float:
        return self.count / self.n if self.n else math.nan


def share(count: int, n: int, confidence: float = CONFIDENCE) -> Share:
    """``count`` of ``n`` with its Wilson score interval (Newcombe 1998, method 3), as
    ``scipy.stats.binomtest(count, n).proportion_ci(confidence, method="wilson")`` computes it:
    the same operations in the same order, without importing scipy.stats (about 0.5 s of a
    command's start-up; tests/test_tolerance.py holds the two together)."""
    from scipy.special import ndtri

    k, n = int(count), int(n)
    if n < 1:
        raise ValueError("n must be an integer not less than 1")
    p = k / n
    z = ndtri(0.5 + 0.5 * confidence)
    denom = 2 * (n + z**2)
    center = (2 * n * p + z**2) / denom
    delta = z / denom * math.sqrt(4 * n * p * (1 - p) + z**2)
    low = 0.0 if k == 0 else center - delta
    high = 1.0 if k == n else center + delta
    return Share(k, n, float(low), float(high))


@dataclass(frozen=True)
class Result:
    """What ``pumplink tolerance`` reports (SI units, radians).

    spread : per quantity of :data:`QUANTITIES`;  passed, clean : builds that pass, and that pass
    without warnings;  fails, warns : per check, the share of builds it fails or warns;
    infeasible : builds that are no crank-rocker;  models : builds decided by each model (by
    index into pumplink.models.ORDER);  first_order : the design's sensitivities;
    allocation : the tolerances per hole for the target share.
    """

    problem: Problem
    spread: dict[str, Spread]
    passed: Share
    clean: Share
    fails: dict[str, float]
    warns: dict[str, float]
    infeasible: int
    models: tuple[int, ...]
    first_order: FirstOrder
    allocation: Allocation
    target: float
    nominal_level: int
    values: dict[str, np.ndarray] = field(default_factory=dict, repr=False)
    offsets: np.ndarray | None = field(default=None, repr=False)

    # what a renderer needs to name things, without importing this module
    holes = HOLES
    dimensions = DIMENSIONS
    groups = GROUPS
    quantities = QUANTITIES
    model_labels = MODEL_LABELS
    ladder = LADDER
    workshop_tolerance = WORKSHOP_TOLERANCE

    @property
    def first_order_share(self) -> float:
        """The first-order share of builds that pass (fail limits, or warn limits with strict)."""
        return self.first_order.share(self.problem.tolerances)

    @property
    def meets_target(self) -> bool:
        """The Monte Carlo share (clean, with strict) is at least the target."""
        s = self.clean if self.problem.strict else self.passed
        return s.value >= self.target


def summarize(
    prob: Problem,
    chunks: Iterable[BuildChunk],
    target: float = 0.95,
    progress: Callable[[int], None] | None = None,
    keep: bool = False,
) -> Result:
    """The spread, the shares and the first order of a design's builds, from its chunks (in order).

    ``progress(n)`` after each chunk of n builds; ``keep``: every build's values, verdict level
    (``values["level"]``) and offsets (the (builds, 18) array, drawn again) in the result.  The
    chunks run here are evaluated with malloc tuned for long runs (:func:`pumplink.malloc.tune_malloc`).
    """
    tune_malloc()
    parts: dict[str, list[np.ndarray]] = {k: [] for k, _ in QUANTITIES}
    levels, models = [], []
    fails: dict[str, int] = {}
    warns: dict[str, int] = {}
    for c in chunks:
        for k in parts:
            parts[k].append(c.values[k])
        levels.append(c.level)
        models.append(c.model_index)
        for k, v in c.fails.items():
            fails[k] = fails.get(k, 0) + v
        for k, v in c.warns.items():
            warns[k] = warns.get(k, 0) + v
        if progress is not None:
            progress(len(c))
    values = {k: np.concatenate(v) for k, v in parts.items()}
    level = np.concatenate(levels)
    n = level.size
    nominal_ev = evaluate_builds(prob, np.zeros((1, len(DIMENSIONS))))
    nominal = {k: float(v[0]) for k, v in quantities(nominal_ev).items()}
    spread = {}
    for k, v in values.items():
        ok = ~np.isnan(v)
        if ok.any():
            p5, med, p95 = np.percentile(v[ok], [5.0, 50.0, 95.0])
            std = float(np.std(v[ok], ddof=1)) if np.count_nonzero(ok) > 1 else math.nan
        else:
            p5 = med = p95 = std = math.nan
        spread[k] = Spread(nominal[k], float(med), float(p5), float(p95), std)
    fo = sensitivities(prob)
    return Result(
        prob,
        spread,
        share(int(np.count_nonzero(level < FAIL)), n),
        share(int(np.count_nonzero(level == PASS)), n),
        {k: v / n for k, v in fails.items()},
        {k: v / n for k, v in warns.items()},
        int(np.count_nonzero(np.isnan(values["swing"]))),
        tuple(int(x) for x in np.bincount(np.concatenate(models), minlength=3)),
        fo,
        allocate(fo, target, prob.tolerances.distribution),
        target,
        int(np.ravel(nominal_ev.verdict.level)[0]),
        {**values, "level": level} if keep else {},
        np.concatenate([offsets(prob, *t) for t in prob.chunks]) if keep else None,
    )


def study(prob: Problem, target: float = 0.95, mapper: Callable | None = None,
          progress: Callable[[int], None] | None = None, keep: bool = False) -> Result:  # fmt: skip
    """A design's builds at these tolerances (``prob``, :func:`pumplink.studies.tolerance.problem`):
    the Monte Carlo (on ``mapper``, the batch engine's, or in this process), the first order and
    the allocation."""
    return summarize(prob, run_chunks(prob, mapper), target, progress, keep)


# ----------------------------------------------------------------------------- robust designs
#: Builds of the Monte Carlo check of a search's answer (the share to about ±1 % at 95 %).
CHECK_BUILDS = 2000


@dataclass(frozen=True)
class Robust:
    """What a robust search asks (``--tolerance 1mm --yield 0.95``): at least ``target`` of the
    builds at ``tolerances`` pass (``strict``: pass without warnings), to first order in the search
    (:func:`first_order_shares`) and checked on the answer by a Monte Carlo of ``builds`` builds."""

    tolerances: Tolerances
    target: float = 0.95
    strict: bool = False
    builds: int = CHECK_BUILDS
    seed: int = 0

    @property
    def tolerance(self) -> float:
        """The largest tolerance asked for [m] (a search's ``--tolerance``: every hole the same)."""
        return max(self.tolerances.holes)


@dataclass(frozen=True)
class RobustCheck:
    """A search's answer at its tolerances: the first-order share of builds that pass (the
    search's own estimate) and the Monte Carlo's share with its Wilson interval."""

    robust: Robust
    first_order: float
    monte_carlo: Share

    @property
    def meets(self) -> bool:
        """The Monte Carlo share reaches the target."""
        return self.monte_carlo.value >= self.robust.target


def shortfall(designs: PumpDesigns, ev: Evaluation, robust: Robust, model=None) -> np.ndarray:
    """How far the first-order share of builds that pass falls short of the target, per design
    (0: it reaches it; the target where the design itself does not pass) [-]."""
    shares = first_order_shares(designs, ev, robust.tolerances, robust.strict, model)
    return np.maximum(robust.target - shares, 0.0)


def robust_check(spec: PumpSpec, robust: Robust, model: str | None = None) -> RobustCheck:
    """The first-order share and the Monte Carlo check of a search's answer (in this process)."""
    res = study(
        problem(spec, robust.tolerances, robust.builds, robust.seed, model, robust.strict), robust.target
    )
    return RobustCheck(robust, res.first_order_share, res.clean if robust.strict else res.passed)
