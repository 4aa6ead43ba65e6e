"""One design against its wheel speed (``pumplink speed``): the least peak force of each model
at each mean speed, the verdict at each speed, the speeds at which it passes and the best cadence
(docs/models.md §2-3a).

The speeds that pass are where the verdict of the one evaluation changes over a grid of mean
speeds, its edges located to the whole degree per second (the printed edge passes, the next whole
speed beyond it fails); the best cadence is the passing speed with the least peak effort.  No
limit is judged here: every check is the evaluation's, with the operator profile's limits.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from pumplink.errors import InfeasibleDesign, SpecError
from pumplink.evaluate import DYNAMICS, FLYWHEEL, JUDGED, Evaluation, Verdict, evaluate, motion, pump_designs
from pumplink.inputs.pump import PumpSpec
from pumplink.studies.force import Design, ForceResult, design, force_analysis

#: Mean speeds [deg/s] searched for the best cadence and the passing speeds (10 to 240 rpm), and
#: the step of the grid on which the verdict's changes are found (each then located to 1 deg/s).
CADENCE_RANGE_DEG_S = (60.0, 1440.0)
CADENCE_STEP_DEG_S = 20.0


@dataclass(frozen=True)
class Cadence:
    """The speeds at which one design passes and its best cadence (SI units, radians).

    ``passing`` are the mean speeds where no check of the verdict fails, ``force_range`` those
    where its peak-force check passes (each (low, high), (NaN, NaN) when there are none; an end at
    the edge of ``searched`` may go on beyond it; ``bands``: every passing interval, lowest first;
    ``clean_bands``: those where it passes without a warning).  Their ends are whole degrees per
    second at which the verdict passes, the next whole speed outside failing.  ``speed`` is the
    mean speed with the least peak *effort* (hand force plus accelerating and lifting the
    operator's own arms, full dynamics, docs/models.md §3a) among those that pass without a
    warning, else among those that pass (NaN where none passes or the spec gives no inertia),
    ``effort`` that least peak effort,
    ``hand_force`` the hand force there and ``power`` Mw ω̄ there.  ``model`` decided at the
    spec's own speed.
    """

    speed: float
    effort: float
    hand_force: float
    power: float
    at_edge: bool
    searched: tuple[float, float]
    model: str
    force_range: tuple[float, float]
    passing: tuple[float, float]
    bands: tuple[tuple[float, float], ...] = ()
    clean_bands: tuple[tuple[float, float], ...] = ()


def _at_speeds(spec: PumpSpec, speeds_deg, model: str | None):
    return evaluate(pump_designs(spec.values, np.asarray(speeds_deg, float)), JUDGED, model=model,
                    screen_parts=True, fitted=True)  # fmt: skip


def _tests(ev) -> np.ndarray:
    """(3, n): where the verdict passes, where it passes without a warning, and where its
    peak-force check passes."""
    v = ev.verdict
    return np.array([np.asarray(v.passed, bool), np.asarray(v.passed_strict(), bool),
                     np.asarray(v["peak_force"].passed, bool)])  # fmt: skip


def _results(spec: PumpSpec, model, speeds: list, known: dict) -> np.ndarray:
    """:func:`_tests` at the whole ``speeds`` [deg/s], (3, len(speeds)): those not in ``known``
    (speed -> column) evaluated together, in one evaluation, and added to it."""
    new = sorted(set(speeds) - known.keys())
    if new:
        known.update(zip(new, _tests(_at_speeds(spec, new, model)).T, strict=True))
    return np.array([known[v] for v in speeds]).T


#: Whole speeds looked at inside each bracket per step of :func:`_edges`: a bracket of the grid's
#: 20 deg/s is narrowed to 4, then to 1, in two evaluations (bisection took five, and a sixth for
#: the whole speeds of its last bracket).
SPLIT = 4


def _edges(spec: PumpSpec, model, grid: np.ndarray, ok: np.ndarray, known: dict) -> list[list[int]]:
    """For each test (a row of ``ok`` on ``grid``), the whole speeds [deg/s] where its result
    changes: the first whole speed with the new result.  Each bracket between grid points is cut
    at up to :data:`SPLIT` whole speeds inside it a step, every test and edge in one evaluation,
    until its ends are neighbouring whole speeds.  ``known``: the tests' results at whole speeds
    already evaluated (speed [deg/s] -> column of :func:`_tests`), added to here."""
    which, at = np.nonzero(ok[:, :-1] != ok[:, 1:])
    before = ok[which, at]
    # the whole speeds around each change: at the lower end the old result, at the upper the new
    lo, hi = np.floor(grid[at]).astype(int), np.ceil(grid[at + 1]).astype(int)
    while np.any(wide := hi - lo > 1):
        cuts = {j: np.unique(np.linspace(lo[j], hi[j], SPLIT + 2)[1:-1].round().clip(lo[j] + 1, hi[j] - 1)
                             .astype(int)) for j in np.nonzero(wide)[0].tolist()}  # fmt: skip
        _results(spec, model, np.concatenate(list(cuts.values())).tolist(), known)
        for j, c in cuts.items():
            changed = [known[v][which[j]] != before[j] for v in c.tolist()]
            k = changed.index(True) if True in changed else c.size
            lo[j] = c[k - 1] if k > 0 else lo[j]
            hi[j] = c[k] if k < c.size else hi[j]
    out: list[list[int]] = [[] for _ in ok]
    for t, e in zip(which.tolist(), hi.tolist(), strict=True):
        out[t].append(int(e))
    return out


def _bands(grid: np.ndarray, ok: np.ndarray, edges: list[int]) -> tuple[tuple[float, float], ...]:
    """The passing intervals [deg/s] of one test from its result on the grid and its edges."""
    bands, start = [], grid[0] if ok[0] else None
    for e in edges:
        if start is None:
            start = e
        else:
            bands.append((float(start), float(e - 1)))
            start = None
    if start is not None:
        bands.append((float(start), float(grid[-1])))
    return tuple(bands)


def passing_speeds(spec: PumpSpec, model: str | None = None, searched_deg_s=CADENCE_RANGE_DEG_S):
    """The mean speeds [deg/s] at which the one evaluation's verdict passes, those at which it
    passes without a warning, and those at which its peak-force check passes: three tuples of
    (low, high) intervals, each end a whole speed that passes (the next whole speed outside fails,
    but at the ends of ``searched_deg_s``)."""
    lo, hi = searched_deg_s
    grid = np.arange(lo, hi, CADENCE_STEP_DEG_S)
    grid = np.unique(np.concatenate([grid, [hi], np.clip([spec.operator.speed], lo, hi)]))
    ok = _tests(_at_speeds(spec, grid, model))
    known = {int(v): column for v, column in zip(grid.tolist(), ok.T, strict=True) if v == int(v)}
    edges = _edges(spec, model, grid, ok, known)
    # a band narrower than the grid's step is found where another test changes or at the spec's
    # speed: the whole speeds at every edge found join the grid, and the edges are found again
    extra = np.setdiff1d(np.clip([e + d for es in edges for e in es for d in (-1, 0)], lo, hi), grid)
    if extra.size:
        grid, order = np.unique(np.concatenate([grid, extra]), return_index=True)
        ok = np.concatenate([ok, _results(spec, model, extra.tolist(), known)], axis=1)[:, order]
        edges = _edges(spec, model, grid, ok, known)
    return tuple(_bands(grid, ok[t], edges[t]) for t in range(len(ok)))


def _widest(bands) -> tuple[float, float]:
    nan = float("nan")
    return max(bands, key=lambda b: b[1] - b[0]) if bands else (nan, nan)


def cadence(r: ForceResult, searched_deg_s=CADENCE_RANGE_DEG_S) -> Cadence:
    """The speeds at which the design of ``r`` passes and its best cadence (``r``: a force
    analysis at the spec's speed, with the model asked for, if any)."""
    spec, ev = r.design.spec, r.evaluation
    forced = None if r.effects is None or not r.effects.forced else r.model_key
    passing, clean, force = passing_speeds(spec, forced, searched_deg_s)
    nan = float("nan")
    best = effort = hand = nan
    if spec.gives_inertia and passing:  # the least peak effort where it passes (without a warning if it can)
        syn, lk = motion.at_design(ev)
        design = (lk, syn.dead_centre_extended, syn.dead_centre_folded, r.wheel_torque, r.inertia)
        with_arms, no_arms = motion.link_masses_of(ev, arms=True), motion.link_masses_of(ev, arms=False)
        found = [motion.best_speed(*design, with_arms, r.speed_fluctuation, *np.radians(b))
                 for b in clean or passing]  # fmt: skip
        best, effort = min(found, key=lambda f: f[1])
        hand = motion.dynamics_peak_force(*design, no_arms, best, r.speed_fluctuation)
    lo, hi = (math.radians(v) for v in searched_deg_s)
    edge = bool(np.isfinite(best) and min(best - lo, hi - best) <= 1e-6 * hi)

    def rad(b):
        return tuple(math.radians(x) for x in b)

    return Cadence(best, effort, hand, r.wheel_torque * best, edge, (lo, hi), r.model_key,
                   rad(_widest(force)), rad(_widest(passing)), tuple(rad(b) for b in passing),
                   tuple(rad(b) for b in clean))  # fmt: skip


# ----------------------------------------------------------------------------- speed sweep
@dataclass(frozen=True, kw_only=True)
class SpeedSweep:
    """The least peak operator force against mean wheel speed for one design, by model: a view of
    the one evaluation over the given speeds (``evaluation``, arrays over ``speed``) with the
    chart's curves of each energy model, the force result at the spec's own speed and the cadence.

    ``flywheel_force`` (links neglected) and ``dynamics_force`` (full dynamics, the hand force; the
    arms only where the spec puts them in the verdict) [N] at every speed; the evaluation's
    ``effort_peak_force`` (full dynamics with the arms), ``model_index`` (the model that decides
    at each speed: the least that is enough, or the one asked for), ``peak_force`` (its force, the
    verdict's peak), ``power``, ``grip_speed`` and ``verdict`` at each speed.
    """

    result: ForceResult  # pumplink force at the spec's own speed
    evaluation: Evaluation  # over the given speeds
    speed_deg_s: np.ndarray  # as given (echoed exactly in reports)
    flywheel_force: np.ndarray
    dynamics_force: np.ndarray
    min_passing_speed: float  # the flywheel's slowest passing speed [rad/s]; inf: no speed passes
    cadence: Cadence | None = None

    @property
    def design(self) -> Design:
        return self.result.design

    @property
    def wheel_torque(self) -> float:
        return self.result.wheel_torque

    @property
    def inertia(self) -> float:
        return self.result.inertia

    @property
    def speed_fluctuation(self) -> float:
        return self.result.speed_fluctuation

    @property
    def force_limit(self) -> float:
        return self.result.force_limit

    @property
    def mean_force(self) -> float:
        return self.result.mean_force

    @property
    def dead_band_peak_force(self) -> float:
        return self.result.dead_band_peak_force

    @property
    def speed(self) -> np.ndarray:
        return np.broadcast_to(np.asarray(self.evaluation.designs.speed, float), self.speed_deg_s.shape)

    @property
    def energy_band(self) -> np.ndarray:
        return self.evaluation.energy_band

    @property
    def least_peak_force(self) -> np.ndarray:
        """The verdict's peak force at each speed [N]."""
        return self.evaluation.peak_force

    @property
    def effort_force(self) -> np.ndarray:
        return self.evaluation.effort_peak_force

    @property
    def power(self) -> np.ndarray:
        return self.evaluation.power

    @property
    def grip_speed(self) -> np.ndarray:
        return self.evaluation.grip_speed

    @property
    def flow(self) -> np.ndarray:
        """The water delivered at each speed [m³/s] (NaN without a head)."""
        return self.evaluation.water.flow

    @property
    def verdict(self) -> Verdict:
        return self.evaluation.verdict

    @property
    def passed(self) -> np.ndarray:
        return np.asarray(self.verdict.passed)

    @property
    def model(self) -> np.ndarray:
        """The model key at each speed."""
        return self.evaluation.model

    @property
    def outcome(self) -> np.ndarray:
        """'PASS', 'PASS with warnings' or 'FAIL' at each speed."""
        return np.asarray(self.verdict.outcome)

    def spec_speed_passes(self, strict: bool = False) -> bool:
        """The verdict at the spec's own speed (as ``pumplink force``), strict or not."""
        return self.result.passed_strict(strict)

    @property
    def sustained_power(self) -> float:
        """The power the operator profile sustains for hours [W]."""
        return float(np.asarray(self.evaluation.designs.sustained_power, float).ravel()[0])

    @property
    def sustained_speed(self) -> float:
        """The mean speed at which the power Mw ω̄ reaches the operator's sustained power [rad/s]."""
        return self.sustained_power / self.wheel_torque


def speed_sweep(
    spec: PumpSpec, speeds_deg_s, model: str | None = None, with_cadence: bool = True
) -> SpeedSweep:
    """Least peak force at each mean wheel speed [deg/s] by the flywheel (docs/models.md §2) and
    full dynamics (§3a), and the verdict of the model that decides at each speed (``model``: the
    one asked for, else the least that is enough), with the speeds that pass and the best cadence
    (``with_cadence``).

    Raises
    ------
    SpecError : the spec gives no inertia (the quasi-static force does not depend on speed).
    InfeasibleDesign : no crank-rocker for this spec.
    """
    if spec.inertia is None:
        raise SpecError(
            f"{spec.name}: the speed study needs the wheel's inertia (the quasi-static force does not "
            "depend on speed); add wheel.mass [kg] or wheel.inertia [kg m^2] to the spec"
        )
    d = design(spec)
    if not d.feasible:
        raise InfeasibleDesign(f"{spec.name}: {d.error}")
    given = np.asarray(speeds_deg_s, float)
    designs = pump_designs(spec.values, given)
    ev = evaluate(designs, (*JUDGED, "effort"), model=model)
    # the least peak force of each energy model at every speed (the chart's curves)
    fly, hand = (evaluate(designs, ("model",), model=key).least_peak_force for key in (FLYWHEEL, DYNAMICS))
    result = force_analysis(spec, keep_samples=False, samples=0, model=model)
    syn = d.synthesis
    mps = float(
        motion.min_passing_speed(syn.linkage, syn.dead_centre_extended, syn.dead_centre_folded,
                                 result.wheel_torque, result.force_limit, result.inertia,
                                 result.speed_fluctuation)
    )  # fmt: skip
    return SpeedSweep(
        result=result,
        evaluation=ev,
        speed_deg_s=given,
        flywheel_force=fly,
        dynamics_force=hand,
        min_passing_speed=mps,
        cadence=cadence(result) if with_cadence else None,
    )
