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
from typing import TYPE_CHECKING, Any

import numpy as np

from pumplink.errors import SpecError
from pumplink.evaluate import REPORTED, Evaluation, Water, evaluate, motion, pump_designs
from pumplink.inputs.pump import PumpSpec, spec_values
from pumplink.mechanisms.fourbar import State, Synthesis, infeasibility_reason, kinematic_state, synthesize
from pumplink.models import DYNAMICS, FLYWHEEL, MODELS, ORDER, QUASI_STATIC
from pumplink.verdict import Check, Verdict

if TYPE_CHECKING:
    from pumplink.models.choice import EnergyModel

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


@dataclass(frozen=True, repr=False)
class ForceResult:
    """Force analysis of one design at one wheel speed (SI units, radians).

    Three peak forces, named apart: ``dead_band_peak_force`` (the quasi-static model's exact peak
    outside the dead bands), ``least_peak_force`` (the flywheel model's, None without inertia) and
    :attr:`verdict_peak_force` (the one of the model that decided).
    """

    design: Design
    speed_deg_s: float  # wheel speed as given [deg/s] (echoed exactly in reports)
    speed: float  # wheel speed [rad/s]
    wheel_torque: float  # Mw [N m]
    power: float  # Mw * omega [W]
    force_limit: float  # [N]
    dead_band: float  # [rad]
    mean_force: float  # [N]
    dead_band_peak_force: float  # exact windowed peak [N]
    dead_band_peak_angle: float  # [rad]
    sampled_peak: float  # peak over the requested samples outside the dead bands [N]
    samples_n: int
    verdict: Verdict | None  # None for an infeasible design
    samples: State | None  # None with --summary
    in_dead_band: np.ndarray | None
    marks: State | None = None  # state at (extended dead centre, folded dead centre, dead-band peak)
    # The flywheel model; model == the quasi-static label leaves the rest None.
    model: str = MODELS["quasi-static"].label
    inertia: float | None = None  # J [kg m^2]
    speed_fluctuation: float | None = None  # delta_allow [-]
    energy_band: float | None = None  # W = J w^2 delta [J]
    least_peak_force: float | None = None  # Fp* [N]
    min_passing_speed: float | None = None  # [rad/s]; inf: no speed passes
    scene: Any = None  # the deciding energy model's motion (pumplink.evaluate.motion.scene)
    operator_force: np.ndarray | None = None  # at the samples [N]
    wheel_speed: np.ndarray | None = None  # at the samples [rad/s]
    on_ceiling: np.ndarray | None = None  # at the samples: the wheel at its top speed
    mark_operator_force: np.ndarray | None = None  # at the marks [N] (flywheel)
    mark_wheel_speed: np.ndarray | None = None  # at the marks [rad/s]
    link_energy: float = float("nan")  # largest kinetic energy of coupler + handle at this speed [J]
    effort_peak_force: float | None = None  # least peak effort: hand force + the arms (full dynamics) [N]
    effects: EnergyModel | None = None  # the model choice with the wheel's inertia (None without)
    evaluation: Evaluation | None = None  # the one evaluation this result shows (one design)
    water: Water | None = None  # the water it delivers and the most its operator could lift
    profile: str = "men"  # the operator profile whose limits judged it (pumplink.profiles)

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
    op = spec.operator
    speed_deg = float(op.speed if speed_deg_s is None else speed_deg_s)
    if model is not None and model != QUASI_STATIC and not spec.gives_inertia:
        raise SpecError(
            f"--model {model} needs the wheel's inertia, but {spec.name} gives none; add wheel.mass [kg] "
            "or wheel.inertia [kg m^2] to the spec"
        )
    ev = evaluate(
        pump_designs(spec_values(spec), speed_deg),
        (*REPORTED, "effort", "sampled_peak"),
        model=model,
        samples=samples if at_deg is None else 0,
        progress=progress,
    )
    d = _design(spec, ev.synthesis)
    syn = d.synthesis
    profile = spec.operator.limits.name
    mw, speed, band = float(ev.designs.wheel_torque), float(ev.designs.speed), float(ev.designs.dead_band)
    inertia = float(ev.designs.inertia) if spec.gives_inertia else None
    nan = float("nan")
    em = None if ev.energy is None else ev.energy.design(0)
    model = MODELS[model] if model == QUASI_STATIC else MODELS[ORDER[int(ev.model_index[0])]]
    fly = (
        {}
        if inertia is None
        else dict(inertia=inertia, speed_fluctuation=op.speed_fluctuation, energy_band=em.band, effects=em)
    )
    if not d.feasible:
        return ForceResult(
            d,
            speed_deg,
            speed,
            mw,
            mw * speed,
            float(ev.designs.force_limit),
            band,
            nan,
            nan,
            nan,
            nan,
            0,
            None,
            None,
            None,
            model=model.label,
            evaluation=ev,
            water=ev.water.design(0),
            profile=profile,
            **fly,
        )
    lk = syn.linkage
    dce, dcf = syn.dead_centre_extended, syn.dead_centre_folded
    mean = float(ev.mean_force[0])
    peak, peak_angle = float(ev.dead_band_peak_force[0]), float(ev.dead_band_peak_angle[0])

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
    state = band_mask = None
    if theta is not None:
        state = kinematic_state(lk, theta, mw)
        band_mask = motion.in_dead_band(theta, dce, dcf, band)
    if at_deg is not None:
        f = np.where(band_mask | state.singular, -np.inf, np.abs(state.force))
        sampled = float(f.max()) if f.size and np.isfinite(f.max()) else nan
        n = int(theta.size)
    else:
        sampled = float(ev.sampled_peak[0])
        n = samples

    marks = kinematic_state(lk, np.array([dce, dcf, peak_angle]), mw)
    link = nan if em is None else em.link_energy
    sc = motion.scene(ev)
    if sc is not None:
        fly.update(
            least_peak_force=sc.least_peak_force, scene=sc, min_passing_speed=float(ev.min_passing_speed[0])
        )
        # the operator's effort: the hand force plus accelerating and lifting their own arms
        fly.update(effort_peak_force=float(ev.effort_peak_force[0]))
        if np.isfinite(sc.least_peak_force):
            fly.update(
                mark_operator_force=motion.operator_force(sc, marks.crank_angle),
                mark_wheel_speed=motion.wheel_speed(sc, marks.crank_angle),
            )
            if theta is not None:
                fly.update(
                    operator_force=motion.operator_force(sc, theta),
                    wheel_speed=motion.wheel_speed(sc, theta),
                    on_ceiling=motion.on_ceiling(sc, theta),
                )
    return ForceResult(
        d,
        speed_deg,
        speed,
        mw,
        mw * speed,
        float(ev.designs.force_limit),
        band,
        mean,
        peak,
        peak_angle,
        sampled,
        n,
        ev.verdict.design(0),
        state if keep_samples or at_deg is not None else None,
        band_mask,
        marks,
        model=model.label,
        link_energy=link,
        evaluation=ev,
        water=ev.water.design(0),
        profile=profile,
        **fly,
    )


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
