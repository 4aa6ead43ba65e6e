"""One design against its wheel speed (``pumplink speed``): the least peak force of each model
at each mean speed, the verdict at each speed, the best cadence and the speeds that pass
(docs/models.md §2-3a)."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from pumplink.constants import GRIP_SPEED_FAIL_M_S, HOUR_POWER_W, SUSTAINED_POWER_W
from pumplink.errors import InfeasibleDesign, SpecError
from pumplink.evaluate import evaluate, motion, pump_designs
from pumplink.inputs.pump import PumpSpec, spec_values
from pumplink.models import DYNAMICS, FLYWHEEL, ORDER
from pumplink.models.load import grip_speed
from pumplink.studies.force import Design, ForceResult, design, force_analysis
from pumplink.verdict import Verdict

#: Mean speeds [deg/s] searched for the best cadence and the passing range (10 to 240 rpm).
CADENCE_RANGE_DEG_S = (60.0, 1440.0)


@dataclass(frozen=True)
class Cadence:
    """The best cadence of one design and the mean speeds that pass (SI units, radians).

    ``speed`` is the mean speed with the least peak *effort* (hand force plus accelerating and
    lifting the operator's own arms, full dynamics, docs/models.md §3a), ``effort`` that least
    peak effort, ``hand_force`` the hand force there (full dynamics, arms left out) and ``power``
    Mw w there.  ``force_range`` are the mean speeds where the verdict's peak force (of ``model``,
    the model that decided at the spec's speed) is within the force limit, ``passing`` those where
    no check fails (that force, the power, the peak grip speed, and every check that does not
    depend on speed); (NaN, NaN) when there are none, and an end at the edge of ``searched`` may go on
    beyond it.
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


def cadence(r: ForceResult, searched_deg_s=CADENCE_RANGE_DEG_S) -> Cadence:
    """The best cadence and the passing mean speeds of the design of ``r`` (a force analysis at the
    spec's speed, which says which model decides and which checks fail at any speed).

    Raises
    ------
    SpecError : the spec gives no inertia (then the force does not depend on speed).
    """
    spec = r.design.spec
    if not spec.gives_inertia:
        raise SpecError(
            f"{spec.name}: the best cadence needs the wheel's inertia (the quasi-static force does not "
            "depend on speed); add wheel.mass [kg] or wheel.inertia [kg m^2] to the spec"
        )
    syn, op, mw, j = r.design.synthesis, spec.operator, r.wheel_torque, r.inertia
    lk, dce, dcf, delta = syn.linkage, syn.dead_centre_extended, syn.dead_centre_folded, op.speed_fluctuation
    lo, hi = (math.radians(v) for v in searched_deg_s)
    nan = float("nan")
    ev = r.evaluation
    with_arms = motion.link_masses_of(ev, arms=True)
    best, effort = motion.best_speed(lk, dce, dcf, mw, j, with_arms, delta, lo, hi)
    no_arms = motion.link_masses_of(ev, arms=False)
    hand = motion.dynamics_peak_force(lk, dce, dcf, mw, j, no_arms, best, delta)
    edge = bool(np.isfinite(best) and min(best - lo, hi - best) <= 1e-6 * hi)
    model = r.model_key
    if model == DYNAMICS:
        arms_in = bool(op.arms_in_verdict)
        judged = motion.link_masses_of(ev)
        # the verdict's force is least at the best cadence (arms in the verdict) or at its own minimiser
        at = best if arms_in else motion.best_speed(lk, dce, dcf, mw, j, judged, delta, lo, hi)[0]
        force = motion.speed_range(lk, dce, dcf, mw, j, judged, delta, r.force_limit, lo, hi, at)
    elif model == FLYWHEEL:
        slowest = float(motion.min_passing_speed(lk, dce, dcf, mw, r.force_limit, j, delta))
        force = (slowest, math.inf) if math.isfinite(slowest) else (nan, nan)
    else:
        force = (0.0, math.inf) if r.passed else (nan, nan)
    # the checks that depend on speed fail above a speed: the power and the peak grip speed

    # the grip speed at a mean speed of 1 rad/s (it grows in proportion)
    per_speed = grip_speed(
        float(ev.rocker_rate[0]), 1.0, spec.linkage.handle, delta if model in (FLYWHEEL, DYNAMICS) else None
    )
    fastest = min(HOUR_POWER_W / mw, GRIP_SPEED_FAIL_M_S / per_speed)
    fixed = [c.key for c in r.verdict.failures if c.key not in ("peak_force", "power", "grip_speed")]
    low, high = force[0], min(force[1], fastest)
    passing = (float(low), float(high)) if not fixed and low <= high else (nan, nan)
    return Cadence(best, effort, hand, mw * best, edge, (lo, hi), model, force, passing)


# ----------------------------------------------------------------------------- speed sweep
@dataclass(frozen=True)
class SpeedSweep:
    """The least peak operator force against mean wheel speed for one design, by model.

    Arrays over ``speed`` [rad/s]: ``energy_band`` [J]; ``flywheel_force`` (links neglected),
    ``dynamics_force`` (full dynamics, the hand force; the arms only where the spec puts them in the
    verdict) and ``effort_force`` (full dynamics with the arms) [N]; ``model`` the model that decides
    at each speed (the least that is enough, or the one asked for) and ``least_peak_force`` its
    force, the verdict's peak [N]; ``power`` [W]; ``passed`` (no check fails at that speed).
    :meth:`spec_speed_passes`: the verdict at the spec's own speed (what ``pumplink force`` says);
    ``cadence``: the best cadence and the passing speeds (:func:`cadence`).
    """

    design: Design
    wheel_torque: float  # Mw [N m]
    inertia: float
    speed_fluctuation: float
    force_limit: float
    mean_force: float
    dead_band_peak_force: float  # exact windowed peak outside the dead band (dead-band model) [N]
    min_passing_speed: float  # the flywheel's slowest passing speed [rad/s]; inf: no speed passes
    speed_deg_s: np.ndarray  # as given (echoed exactly in reports)
    speed: np.ndarray
    energy_band: np.ndarray
    least_peak_force: np.ndarray
    power: np.ndarray
    passed: np.ndarray
    verdict: Verdict | None = None  # every check at each speed (the spec's own speed last)
    grip_speed: np.ndarray | None = None  # peak grip speed at each speed [m/s]
    flywheel_force: np.ndarray | None = None
    dynamics_force: np.ndarray | None = None
    effort_force: np.ndarray | None = None
    model: np.ndarray | None = None  # model key at each speed
    cadence: Cadence | None = None
    result: ForceResult | None = None  # pumplink force at the spec's own speed
    flow: np.ndarray | None = None  # the water delivered at each speed [m³/s] (NaN without a head)

    @property
    def outcome(self) -> np.ndarray:
        """'PASS', 'PASS with warnings' or 'FAIL' at each speed."""
        return np.asarray(self.verdict.outcome)[:-1]

    def spec_speed_passes(self, strict: bool = False) -> bool:
        """The verdict at the spec's own speed (as ``pumplink force``), strict or not."""
        return bool(np.asarray(self.verdict.passed_strict(strict))[-1])

    @property
    def sustained_speed(self) -> float:
        """The mean speed at which the power Mw w reaches the 75 W a person sustains [rad/s]."""
        return SUSTAINED_POWER_W / self.wheel_torque


def speed_sweep(
    spec: PumpSpec, speeds_deg_s, model: str | None = None, with_cadence: bool = True
) -> SpeedSweep:
    """Least peak force at each mean wheel speed [deg/s] by the flywheel (docs/models.md §2) and
    full dynamics (§3a), and the verdict of the model that decides at each speed (``model``: the
    one asked for, else the least that is enough), with the best cadence (``with_cadence``).

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
    syn, op = d.synthesis, spec.operator
    given = np.asarray(speeds_deg_s, float)
    designs = pump_designs(spec_values(spec), np.append(given, op.speed))  # the spec's own speed last
    w, mw, j = np.asarray(designs.speed), float(designs.wheel_torque), float(designs.inertia)
    ev = evaluate(designs, ("verdict", "water", "effort", "dead_band_peak"), model=model)
    # the least peak force of each energy model at every speed (the chart's curves)
    fly, hand = (evaluate(designs, ("model",), model=key).least_peak_force for key in (FLYWHEEL, DYNAMICS))
    effort = ev.effort_peak_force
    lk, dce, dcf, delta = syn.linkage, syn.dead_centre_extended, syn.dead_centre_folded, op.speed_fluctuation
    index = ev.model_index
    req = ev.peak_force
    mean, qs = float(ev.mean_force[0]), float(ev.dead_band_peak_force[0])
    limit = float(ev.designs.force_limit)
    mps = float(motion.min_passing_speed(lk, dce, dcf, mw, limit, j, delta))
    grip = ev.grip_speed
    verdict = ev.verdict
    result = force_analysis(spec, keep_samples=False, samples=0, model=model)
    passed = np.asarray(verdict.passed)
    keys = np.asarray(ORDER, dtype=object)[index]
    return SpeedSweep(
        d,
        mw,
        j,
        delta,
        limit,
        mean,
        float(qs),
        mps,
        given,
        w[:-1],
        ev.energy_band[:-1],
        req[:-1],
        mw * w[:-1],
        passed[:-1],
        verdict,
        grip[:-1],
        fly[:-1],
        hand[:-1],
        effort[:-1],
        keys[:-1],
        cadence(result) if with_cadence else None,
        result,
        flow=ev.water.flow[:-1],
    )
