"""One design's force analysis: the dead-centre synthesis, the force over the crank cycle, the
checks and the verdict (``pumplink force``), and the curves a force chart draws.

The verdict and every number it judges come from the one evaluation
(:func:`pumplink.evaluate.evaluate`, n = 1); this module adds what a study of one design shows:
the force at sampled crank angles, the dead centres and the peak marked, and the deciding energy
model's motion (:mod:`pumplink.evaluate.motion`).  Results are frozen dataclasses in SI units
(radians inside), rendered only by :mod:`pumplink.output`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from pumplink.errors import SpecError
from pumplink.evaluate import (
    DYNAMICS,
    FLYWHEEL,
    MODEL_LABELS,
    MODELS,
    ORDER,
    QUASI_STATIC,
    REPORTED,
    Check,
    EnergyModel,
    Evaluation,
    Verdict,
    Water,
    evaluate,
    motion,
    pump_designs,
)
from pumplink.inputs.pump import PumpSpec
from pumplink.mechanisms.fourbar import State, Synthesis, infeasibility_reason, kinematic_state, synthesize

#: Crank angles of the curve a force chart draws (0.05 deg steps, both ends).
CURVE_POINTS = 7201


@dataclass(frozen=True, repr=False)
class Design:
    """A spec and its dead-centre synthesis (scalars)."""

    spec: PumpSpec
    synthesis: Synthesis
    error: str | None

    @property
    def feasible(self) -> bool:
        return self.error is None

    def __repr__(self) -> str:
        s = self.synthesis
        if not self.feasible:
            return f"<Design {self.spec.name!r}: infeasible ({self.error})>"
        return (
            f"<Design {self.spec.name!r}: crank {float(s.crank_length):.4f} m, coupler "
            f"{float(s.coupler_length):.4f} m, K = {float(s.time_ratio):.4f}>"
        )

    @property
    def handle_stroke(self) -> float:
        """Horizontal grip stroke 2 H sin(swing/2) [m] (docs/physics.md §4)."""
        lk = self.spec.linkage
        return 2 * lk.handle * math.sin(math.radians(lk.swing) / 2)

    @property
    def transmission_angle(self) -> float:
        """Effective smallest transmission angle min(γmin, 180° − γmax) [rad]."""
        syn = self.synthesis
        return min(syn.transmission_min, np.pi - syn.transmission_max)


@dataclass(frozen=True, repr=False, kw_only=True)
class ForceResult:
    """Force analysis of one design at one wheel speed (SI units, radians): a view of the one
    evaluation (``evaluation``, n = 1) with what a study of one design adds: the force at sampled
    crank angles, the dead centres and the peak marked, and the deciding energy model's motion.

    Three peak forces, named apart: ``dead_band_peak_force`` (the quasi-static model's exact peak
    outside the dead bands), ``least_peak_force`` (the energy model's, None without inertia) and
    :attr:`verdict_peak_force` (the one of the model that decided).
    """

    design: Design
    evaluation: Evaluation  # the one evaluation this result shows (one design)
    speed_deg_s: float  # wheel speed as given [deg/s] (echoed exactly in reports)
    sampled_peak: float = float("nan")  # peak over the requested samples outside the dead bands [N]
    samples_n: int = 0
    samples: State | None = None  # None with --summary
    in_dead_band: np.ndarray | None = None
    marks: State | None = None  # state at (extended dead centre, folded dead centre, dead-band peak)
    scene: Any = None  # the deciding energy model's motion (pumplink.evaluate.motion.scene)
    operator_force: np.ndarray | None = None  # at the samples [N]
    wheel_speed: np.ndarray | None = None  # at the samples [rad/s]
    on_ceiling: np.ndarray | None = None  # at the samples: the wheel at its top speed
    mark_operator_force: np.ndarray | None = None  # at the marks [N] (flywheel)
    mark_wheel_speed: np.ndarray | None = None  # at the marks [rad/s]

    def _at(self, x) -> float:
        return float(np.asarray(x, float).ravel()[0])

    @property
    def speed(self) -> float:
        """Mean wheel speed [rad/s]."""
        return self._at(self.evaluation.designs.speed)

    @property
    def wheel_torque(self) -> float:
        """Mw = Fw rw [N m]."""
        return self._at(self.evaluation.designs.wheel_torque)

    @property
    def power(self) -> float:
        """Mw ω̄ [W]."""
        return self._at(self.evaluation.power)

    @property
    def force_limit(self) -> float:
        """The operator profile's force limit [N]."""
        return self._at(self.evaluation.designs.force_limit)

    @property
    def dead_band(self) -> float:
        """[rad]"""
        return self._at(self.evaluation.designs.dead_band)

    @property
    def mean_force(self) -> float:
        """F_mean [N] (NaN: infeasible)."""
        return self._at(self.evaluation.mean_force)

    @property
    def dead_band_peak_force(self) -> float:
        """The quasi-static model's exact peak outside the dead bands [N]."""
        return self._at(self.evaluation.dead_band_peak_force)

    @property
    def dead_band_peak_angle(self) -> float:
        """Where it is [rad]."""
        return self._at(self.evaluation.dead_band_peak_angle)

    @property
    def verdict(self) -> Verdict | None:
        """Every check and the verdict (None for an infeasible design)."""
        return self.evaluation.verdict.design(0) if self.design.feasible else None

    @property
    def model(self) -> str:
        """The words of the model that decided."""
        return MODEL_LABELS[int(self.evaluation.model_index[0])]

    @property
    def effects(self) -> EnergyModel | None:
        """The model choice with the wheel's inertia (None without)."""
        em = self.evaluation.energy
        return None if em is None or not self.design.spec.gives_inertia else em.design(0)

    def _with_inertia(self, x) -> float | None:
        return None if self.effects is None else self._at(x)

    @property
    def inertia(self) -> float | None:
        """J [kg m^2] (None without)."""
        return self._with_inertia(self.evaluation.designs.inertia)

    @property
    def speed_fluctuation(self) -> float | None:
        """δ allowed [-] (None without inertia)."""
        return self._with_inertia(self.evaluation.designs.speed_fluctuation)

    @property
    def energy_band(self) -> float | None:
        """W = J ω̄² δ [J] (None without inertia)."""
        return self._with_inertia(self.evaluation.energy_band)

    @property
    def link_energy(self) -> float:
        """The coupler's and handle's largest kinetic energy at this speed [J] (NaN without inertia)."""
        return float("nan") if self.effects is None else self.effects.link_energy

    def _with_scene(self, x) -> float | None:
        return None if self.scene is None else self._at(x)

    @property
    def least_peak_force(self) -> float | None:
        """Fp* [N] of the energy model that decided (None where none did)."""
        return None if self.scene is None else self.scene.least_peak_force

    @property
    def min_passing_speed(self) -> float | None:
        """The flywheel's slowest passing speed [rad/s] (inf: none passes; NaN: full dynamics)."""
        return self._with_scene(self.evaluation.min_passing_speed)

    @property
    def effort_peak_force(self) -> float | None:
        """Least peak effort: the hand force plus the arms (full dynamics) [N]."""
        return self._with_scene(self.evaluation.effort_peak_force)

    @property
    def water(self) -> Water:
        """The water it delivers and the most its operator could lift."""
        return self.evaluation.water.design(0)

    @property
    def profile(self) -> str:
        """The operator profile whose limits judged it (pumplink.profiles)."""
        return self.design.spec.operator.limits.name

    @property
    def flywheel(self) -> bool:
        """True when an energy model with the wheel's inertia decided (flywheel or full dynamics)."""
        return self.model in (MODELS[FLYWHEEL].label, MODELS[DYNAMICS].label)

    @property
    def dynamics(self) -> bool:
        """True when full dynamics decided."""
        return self.model == MODELS[DYNAMICS].label

    @property
    def model_key(self) -> str:
        """The registry key of the model that decided (``pumplink.models.ORDER``)."""
        return next(k for k in ORDER if MODELS[k].label == self.model)

    def __repr__(self) -> str:
        if not self.design.feasible:
            return f"<ForceResult {self.design.spec.name!r}: infeasible ({self.design.error})>"
        how = self.model if self.flywheel else "dead band"
        fails = ", ".join(c.key for c in self.verdict.failures)
        return (
            f"<ForceResult {self.design.spec.name!r}: {self.outcome}{f' ({fails})' if fails else ''}, "
            f"peak {self.verdict_peak_force:.1f} N ({how}), mean {self.mean_force:.1f} N, "
            f"limit {self.force_limit:g} N at {self.speed_deg_s:g} deg/s>"
        )

    @property
    def passed(self) -> bool:
        """True when no check fails (PASS or PASS with warnings); False for an infeasible design."""
        return bool(self.verdict is not None and self.verdict.passed)

    @property
    def outcome(self) -> str:
        """'PASS', 'PASS with warnings' or 'FAIL' (docs/models.md §4)."""
        return "FAIL" if self.verdict is None else str(self.verdict.outcome)

    def passed_strict(self, strict: bool) -> bool:
        """:attr:`passed`, or with ``strict`` (``--strict``) True only without warnings."""
        return bool(self.verdict is not None and self.verdict.passed_strict(strict))

    @property
    def checks(self) -> tuple[Check, ...]:
        return () if self.verdict is None else self.verdict.checks

    @property
    def verdict_peak_force(self) -> float:
        """The peak force that decided the verdict [N]."""
        return self.least_peak_force if self.flywheel else self.dead_band_peak_force

    @property
    def handle_speed(self) -> np.ndarray:
        """Grip speed [m/s] at the sampled crank angles: |omega4| H (at the scene's wheel speed)."""
        w = self.speed if self.wheel_speed is None else self.wheel_speed
        return np.abs(self.samples.rocker_rate) * w * self.design.spec.linkage.handle

    @property
    def mark_grip_speed(self) -> np.ndarray:
        """Grip speed [m/s] at the marks (0 at a dead centre)."""
        w = self.speed if self.mark_wheel_speed is None else self.mark_wheel_speed
        m = self.marks
        speed = np.abs(m.rocker_rate) * w * self.design.spec.linkage.handle
        return np.where(m.singular, 0.0, speed)


def design(spec: PumpSpec) -> Design:
    """Run the dead-centre synthesis (Eq. 1-2 of the pump paper) for one spec."""
    lk = spec.linkage
    swing = np.radians(lk.swing)
    return _design(spec, synthesize(lk.L1, lk.D1, lk.b, lk.rocker, swing, lk.handle))


def _first(x):
    """The first design's value of a column (None stays None)."""
    return None if x is None else np.asarray(x)[0][()]


def _design(spec: PumpSpec, syn: Synthesis) -> Design:
    """The :class:`Design` of one spec from its synthesis (scalars, or the first of arrays)."""
    from dataclasses import fields

    if np.ndim(syn.reason):
        syn = Synthesis(**{f.name: _first(getattr(syn, f.name)) for f in fields(syn)})
    lk = spec.linkage
    return Design(spec, syn, infeasibility_reason(syn.reason, lk.L1, lk.D1, lk.b, np.radians(lk.swing)))


def force_analysis(
    spec: PumpSpec,
    speed_deg_s: float | None = None,
    samples: int = 360,
    at_deg=None,
    keep_samples: bool = True,
    progress=None,
    model: str | None = None,
) -> ForceResult:
    """Force sweep, checks and verdict for one spec.

    Parameters
    ----------
    spec : validated pump spec.
    speed_deg_s : wheel speed [deg/s]; default ``spec.operator.speed``.
    samples : number of uniform crank samples (ignored when ``at_deg`` is given).
    at_deg : explicit crank angles [deg] to evaluate instead of the uniform sweep.
    keep_samples : False to stream the sweep without keeping it (``--summary``).
    progress : optional callable given the fraction of a streamed sweep done (for a progress bar).
    model : "quasi-static", "flywheel" or "dynamics" to override the choice of the least model that
        is enough (the energy models need the wheel's inertia).
    """
    speed_deg = float(spec.operator.speed if speed_deg_s is None else speed_deg_s)
    if model is not None and model != QUASI_STATIC and not spec.gives_inertia:
        raise SpecError(
            f"--model {model} needs the wheel's inertia, but {spec.name} gives none; add wheel.mass [kg] "
            "or wheel.inertia [kg m^2] to the spec"
        )
    ev = evaluate(
        pump_designs(spec.values, speed_deg),
        (*REPORTED, "effort", "sampled_peak"),
        model=model,
        samples=samples if at_deg is None else 0,
        progress=progress,
    )
    d = _design(spec, ev.synthesis)
    if not d.feasible:
        return ForceResult(design=d, evaluation=ev, speed_deg_s=speed_deg)
    syn = d.synthesis
    lk, mw = syn.linkage, float(ev.designs.wheel_torque)
    dce, dcf, band = syn.dead_centre_extended, syn.dead_centre_folded, float(ev.designs.dead_band)
    # Kept samples: the given --at angles, else the uniform sweep.  The sampled peak of a
    # uniform sweep always comes from the one streamed route (so --summary does not change it).
    if at_deg is not None:
        # reduced in degrees first, exactly (fmod is exact): 1e50 deg is 320 deg, while radians(1e50)
        # has lost every digit of the angle within a turn
        theta = np.radians(np.fmod(np.asarray(at_deg, float), 360.0))
    elif keep_samples:
        theta = np.arange(samples) * (2 * np.pi / samples)
    else:
        theta = None
    view = {}
    if theta is not None:
        state = kinematic_state(lk, theta, mw)
        view.update(samples=state, in_dead_band=motion.in_dead_band(theta, dce, dcf, band))
    if at_deg is not None:
        f = np.where(view["in_dead_band"] | state.singular, -np.inf, np.abs(state.force))
        sampled = float(f.max()) if f.size and np.isfinite(f.max()) else float("nan")
        view.update(sampled_peak=sampled, samples_n=int(theta.size))
    else:
        view.update(sampled_peak=float(ev.sampled_peak[0]), samples_n=samples)
    marks = kinematic_state(lk, np.array([dce, dcf, float(ev.dead_band_peak_angle[0])]), mw)
    sc = motion.scene(ev)
    if sc is not None and np.isfinite(sc.least_peak_force):
        view.update(
            mark_operator_force=motion.operator_force(sc, marks.crank_angle),
            mark_wheel_speed=motion.wheel_speed(sc, marks.crank_angle),
        )
        if theta is not None:
            view.update(
                operator_force=motion.operator_force(sc, theta),
                wheel_speed=motion.wheel_speed(sc, theta),
                on_ceiling=motion.on_ceiling(sc, theta),
            )
    return ForceResult(design=d, evaluation=ev, speed_deg_s=speed_deg, marks=marks, scene=sc, **view)


# ----------------------------------------------------------------------------- curves for charts
@dataclass(frozen=True)
class ForceCurve:
    """The force over one revolution on a fine grid, for a chart (SI units, radians).

    ``force`` is the quasi-static force (NaN at a dead centre); ``operator_force`` and
    ``wheel_speed`` the deciding energy model's profile (None for the quasi-static model).
    ``peak_angle`` and ``peak_force`` are the verdict's peak as a chart marks it: the crank angle
    [rad] and the signed force [N] (+x positive) whose size is :attr:`ForceResult.verdict_peak_force`.
    The quasi-static model's is its exact peak outside the dead bands; an energy model's operator
    pushes with the peak force over whole arcs, and the one marked is where the wheel is slowest
    (the operator at the peak force there, which is the least that keeps the wheel in its speed
    band).  NaN when the peak is infinite or the design infeasible.
    """

    crank_angle: np.ndarray
    force: np.ndarray
    operator_force: np.ndarray | None
    wheel_speed: np.ndarray | None
    peak_sign: float  # sign of the quasi-static force at the dead-band peak
    peak_angle: float = float("nan")  # the verdict's peak: crank angle [rad]
    peak_force: float = float("nan")  # the verdict's peak: signed force [N]


def force_curve(r: ForceResult, points: int = CURVE_POINTS) -> ForceCurve:
    """The curves ``pumplink force --plot`` draws, computed here so the chart only draws."""
    syn = r.design.synthesis
    theta = np.linspace(0.0, 2 * np.pi, points)
    f = kinematic_state(syn.linkage, theta, r.wheel_torque).force
    op = ws = None
    if r.flywheel and r.scene is not None and np.isfinite(r.scene.least_peak_force):
        op, ws = motion.operator_force(r.scene, theta), motion.wheel_speed(r.scene, theta)
    sign = float(np.sign(np.interp(r.dead_band_peak_angle, theta, f)))
    angle, peak = r.dead_band_peak_angle, sign * r.dead_band_peak_force
    if r.flywheel:
        angle = peak = float("nan")
        if op is not None:
            k = int(np.nanargmin(ws))  # the slowest wheel: the operator at the peak force
            angle, peak = float(theta[k]), float(op[k])
    return ForceCurve(theta, f, op, ws, sign, angle, peak)
