"""One design: from a validated spec to the synthesis, the force analysis, the speed study, the
model-choice report, the time-domain check and the curves a chart shows.

Pure functions (no I/O); the results are frozen dataclasses in SI units (radians inside),
converted to degrees and rows only by :mod:`pumplink.output`.  The verdict comes from
:func:`pumplink.verdict.assess`, the peak force from the least model that is enough
(:func:`energy_model`, :func:`pumplink.models.model_index`) or the one asked for.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from pumplink.constants import (
    GRIP_SPEED_FAIL_M_S,
    HOUR_POWER_W,
    LINK_ENERGY_LIMIT,
    LINK_MASS_PER_METRE,
    SUSTAINED_POWER_W,
)
from pumplink.errors import InfeasibleDesign, SpecError
from pumplink.mechanisms.fourbar import (
    FourBar,
    State,
    Synthesis,
    grip_heights,
    grip_stroke,
    infeasibility_reason,
    kinematic_state,
    peak_rocker_rate,
    per_design,
    synthesize,
)
from pumplink.models import DYNAMICS, FLYWHEEL, MODELS, ORDER, QUASI_STATIC, Conditions, Masses, model_index
from pumplink.models import quasi_static as _qs
from pumplink.spec import PumpSpec
from pumplink.verdict import Check, Verdict, assess

if TYPE_CHECKING:  # the flywheel and dynamics modules load when a command first needs them
    from pumplink.models import flywheel as _fw

#: Crank angles of the curve a force chart draws (0.05 deg steps, both ends).
CURVE_POINTS = 7201
#: Relative agreement the time-domain check demands (periodicity, mean speed, fluctuation).
VERIFY_RTOL = 1e-6


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

    def to_dict(self) -> dict:
        """The JSON contract of ``pumplink synth --format json`` for this design."""
        from pumplink.output.tables import design_row

        return design_row(self)

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
    scene: _fw.Scene | None = None
    operator_force: np.ndarray | None = None  # at the samples [N]
    wheel_speed: np.ndarray | None = None  # at the samples [rad/s]
    on_ceiling: np.ndarray | None = None  # at the samples: the wheel at its top speed
    mark_operator_force: np.ndarray | None = None  # at the marks [N] (flywheel)
    mark_wheel_speed: np.ndarray | None = None  # at the marks [rad/s]
    link_energy: float = float("nan")  # largest kinetic energy of coupler + handle at this speed [J]
    effort_peak_force: float | None = None  # least peak effort: hand force + the arms (full dynamics) [N]
    effects: EnergyModel | None = None  # the model choice with the wheel's inertia (None without)

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

    def to_dict(self, samples: bool = False) -> dict:
        """The JSON contract of ``pumplink force --format json`` (``--summary`` unless ``samples``)."""
        from pumplink.output.tables import force_summary, sample_rows

        out = force_summary(self)
        if samples:
            out["samples"] = sample_rows(self)
        return out

    def _repr_html_(self) -> str:
        from pumplink.output.tables import force_html

        return force_html(self)

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
    syn = synthesize(lk.L1, lk.D1, lk.b, lk.rocker, swing, lk.handle)
    return Design(spec, syn, infeasibility_reason(syn.reason, lk.L1, lk.D1, lk.b, swing))


def link_masses(spec: PumpSpec, coupler_length, arms: bool) -> Masses:
    """Coupler, handle and grip masses [kg] from the spec (docs/models.md §3a): linkage.coupler_mass
    and linkage.handle_mass, else linkage.mass_per_length times the coupler's length and the
    handle's max(H, rocker); the grip carries operator.arm_mass when ``arms``, else nothing."""
    lk = spec.linkage
    mpl = lk.mass_per_length or LINK_MASS_PER_METRE
    return Masses(
        lk.coupler_mass if lk.coupler_mass is not None else mpl * np.asarray(coupler_length, float),
        lk.handle_mass if lk.handle_mass is not None else mpl * max(lk.handle, lk.rocker),
        spec.operator.arm_mass_kg if arms else 0.0,
    )


@dataclass(frozen=True)
class EnergyModel:
    """The model that decides with the wheel's inertia, what decided it, and its peak force.

    Floats for one design, arrays over designs otherwise.  ``index`` 1 flywheel, 2 full dynamics
    (:data:`pumplink.models.ORDER`); ``band`` W = J w^2 delta, ``link_energy`` the coupler's and
    handle's largest kinetic energy, ``link_weight`` the range of their potential energy,
    ``arm_energy`` the arms' largest kinetic energy [J] (:func:`pumplink.models.dynamics.effect_sizes`);
    ``peak_force`` the deciding model's least peak force [N] (NaN where not solved).
    """

    index: np.ndarray | int
    band: np.ndarray | float
    link_energy: np.ndarray | float
    link_weight: np.ndarray | float
    arm_energy: np.ndarray | float
    arms_in_verdict: np.ndarray | bool
    peak_force: np.ndarray | float
    forced: bool = False  # the model was asked for (--model), not chosen

    @property
    def model(self):
        """The deciding model's key per design."""
        return np.asarray(ORDER, dtype=object)[np.asarray(self.index)]


def energy_model(
    lk,
    dead_centre_extended,
    dead_centre_folded,
    wheel_torque,
    inertia,
    speed,
    speed_fluctuation,
    masses: Masses,
    arms_in_verdict,
    forced: str | None = None,
    solve=True,
) -> EnergyModel:
    """Choose between the flywheel and full dynamics and solve the chosen one's least peak force.

    The one route for ``force``, ``speed``, ``batch`` and ``optimize`` (floats or arrays over designs,
    broadcast together), so they decide alike.  ``masses``: coupler and handle [kg] and the arms at
    the grip (operator.arm_mass); the arms enter the solved force only where ``arms_in_verdict``.
    ``forced``: a model key that overrides the choice.  ``solve``: False (or False per design) to
    leave the force unsolved (NaN), e.g. for an infeasible design.
    """
    from pumplink.models import dynamics as _dy  # loaded when first needed (start-up)
    from pumplink.models import flywheel as _fw  # loaded when first needed (start-up)

    scalar, arrays = per_design(
        lk,
        dead_centre_extended,
        dead_centre_folded,
        wheel_torque,
        inertia,
        speed,
        speed_fluctuation,
        masses.coupler,
        masses.handle,
        masses.grip,
        arms_in_verdict,
        solve,
    )
    geom, (dce, dcf, mw, j, w, delta, mc, mh, ma, arms, todo) = arrays[:7], arrays[7:]
    four = FourBar(*geom)
    arms, todo = arms.astype(bool), todo.astype(bool)
    band = _fw.energy_band(j, w, delta)
    link, weight, arm = _dy.effect_sizes(four, _dy.Masses(mc, mh, ma), w)
    index = np.asarray(model_index(j, band, link, weight, arm, arms, forced))
    peak = np.full(j.shape, np.nan)
    for key in (FLYWHEEL, DYNAMICS):
        r = np.nonzero((index == ORDER.index(key)) & todo)[0]
        if r.size:
            ms = _dy.Masses(mc[r], mh[r], np.where(arms[r], ma[r], 0.0))
            cond = Conditions(w[r], 0.0, j[r], delta[r], ms)
            peak[r] = MODELS[key].peak_force(four.take(r), dce[r], dcf[r], mw[r], cond)
    out = (index, band, link, weight, arm, arms, peak)
    if scalar:
        out = (int(index[0]), *(float(v[0]) for v in out[1:5]), bool(arms[0]), float(peak[0]))
    return EnergyModel(*out, forced=forced is not None)


def conditions(spec: PumpSpec, speed: float | None = None) -> Conditions:
    """The spec's operating conditions at wheel speed ``speed`` [rad/s] (default: the spec's)."""
    op = spec.operator
    w = np.radians(op.speed) if speed is None else speed
    j = np.nan if spec.inertia is None else spec.inertia
    return Conditions(w, np.radians(op.dead_band), j, op.speed_fluctuation)


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
    d = design(spec)
    op = spec.operator
    speed_deg = float(op.speed if speed_deg_s is None else speed_deg_s)
    speed = np.radians(speed_deg)
    mw = spec.wheel_torque
    band = np.radians(op.dead_band)
    syn = d.synthesis
    nan = float("nan")
    inertia = spec.inertia
    if model is not None and model != QUASI_STATIC and inertia is None:
        raise SpecError(
            f"--model {model} needs the wheel's inertia, but {spec.name} gives none; add wheel.mass [kg] "
            "or wheel.inertia [kg m^2] to the spec"
        )
    # the least model that is enough (docs/models.md §3), or the one asked for
    em = None
    if inertia is not None:
        # the inertia models load here, not at start-up (a spec without inertia never needs them)
        from pumplink.models import dynamics as _dy
        from pumplink.models import flywheel as _fw

        em = energy_model(
            syn.linkage,
            syn.dead_centre_extended,
            syn.dead_centre_folded,
            mw,
            inertia,
            speed,
            op.speed_fluctuation,
            link_masses(spec, syn.coupler_length, arms=True),
            bool(op.arms_in_verdict),
            forced=model,
            solve=d.feasible,
        )
    model = MODELS[model] if model == QUASI_STATIC else MODELS[ORDER[0 if em is None else em.index]]
    fly = (
        {}
        if inertia is None
        else dict(
            inertia=inertia,
            speed_fluctuation=op.speed_fluctuation,
            energy_band=float(_fw.energy_band(inertia, speed, op.speed_fluctuation)),
            effects=em,
        )
    )
    if not d.feasible:
        return ForceResult(
            d,
            speed_deg,
            float(speed),
            mw,
            mw * float(speed),
            op.force_limit,
            float(band),
            nan,
            nan,
            nan,
            nan,
            0,
            None,
            None,
            None,
            model=model.label,
            **fly,
        )
    lk = syn.linkage
    dce, dcf = syn.dead_centre_extended, syn.dead_centre_folded
    mean = float(_qs.mean_force(mw, grip_stroke(spec.linkage.handle, syn.swing)))
    peak, peak_angle = _qs.dead_band_peak_force(lk, dce, dcf, band, mw)

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
        band_mask = _qs.in_dead_band(theta, dce, dcf, band)
    if at_deg is not None:
        f = np.where(band_mask | state.singular, -np.inf, np.abs(state.force))
        sampled = float(f.max()) if f.size and np.isfinite(f.max()) else nan
        n = int(theta.size)
    else:
        sampled = _qs.sampled_peak(lk, samples, mw, dce, dcf, band, progress=progress)
        n = samples

    marks = kinematic_state(lk, np.array([dce, dcf, peak_angle]), mw)
    link = nan if em is None else em.link_energy
    share = None
    verdict_peak = peak
    if model.key in (FLYWHEEL, DYNAMICS):
        delta = op.speed_fluctuation
        if model.key == DYNAMICS:
            ms = link_masses(spec, syn.coupler_length, bool(op.arms_in_verdict))
            sc = _dy.scene(lk, dce, dcf, mw, inertia, ms, float(speed), delta, force=em.peak_force)
            m, lowest = _dy, nan  # faster is not always easier: pumplink speed gives the range
        else:
            sc = _fw.scene(lk, dce, dcf, mw, inertia, float(speed), delta, solved=em.peak_force)
            m, lowest = _fw, float(_fw.min_passing_speed(lk, dce, dcf, mw, op.force_limit, inertia, delta))
            share = 100.0 * link / fly["energy_band"] if fly["energy_band"] > 0 else np.inf  # J = 0: no band
        # the operator's effort: the hand force plus accelerating and lifting their own arms
        effort = float(
            MODELS[DYNAMICS].peak_force(
                lk,
                dce,
                dcf,
                mw,
                Conditions(speed, band, inertia, delta, link_masses(spec, syn.coupler_length, arms=True)),
            )
        )
        fly.update(least_peak_force=sc.least_peak_force, scene=sc, min_passing_speed=lowest)
        fly.update(effort_peak_force=effort)
        if np.isfinite(sc.least_peak_force):
            fly.update(
                mark_operator_force=m.operator_force(sc, marks.crank_angle),
                mark_wheel_speed=m.wheel_speed(sc, marks.crank_angle),
            )
            if theta is not None:
                fly.update(
                    operator_force=m.operator_force(sc, theta),
                    wheel_speed=m.wheel_speed(sc, theta),
                    on_ceiling=(_dy.regime(sc, theta) == 0) if m is _dy else _fw.on_ceiling(sc, theta),
                )
        verdict_peak = sc.least_peak_force
    verdict = judge(
        True,
        mean,
        verdict_peak,
        op.force_limit,
        share,
        d.transmission_angle,
        mw * speed,
        peak_rocker_rate(lk)
        * top_speed(speed, op.speed_fluctuation if model.key in (FLYWHEEL, DYNAMICS) else None)
        * spec.linkage.handle,
        spec.linkage.handle,
        syn.swing,
        spec.linkage.D1,
        spec.wheel.axle_height,
    )
    return ForceResult(
        d,
        speed_deg,
        float(speed),
        mw,
        mw * float(speed),
        op.force_limit,
        float(band),
        mean,
        peak,
        peak_angle,
        sampled,
        n,
        verdict,
        state if keep_samples or at_deg is not None else None,
        band_mask,
        marks,
        model=model.label,
        link_energy=link,
        **fly,
    )


def top_speed(mean_speed, speed_fluctuation=None):
    """The wheel's highest speed [rad/s]: the mean for the quasi-static model, ω̄(1 + δ/2) with the
    flywheel (docs/models.md §2); the peak grip speed is judged at it (docs/models.md §4)."""
    if speed_fluctuation is None:
        return mean_speed
    return mean_speed * (1.0 + 0.5 * np.asarray(speed_fluctuation, float))


def judge(
    feasible,
    mean,
    peak,
    force_limit,
    link_energy_share,
    transmission_angle,
    power,
    grip_speed,
    handle,
    swing,
    D1,
    axle_height,
) -> Verdict:
    """The verdict of :func:`pumplink.verdict.assess` from a design's quantities, the same for
    ``force``, ``speed``, ``batch`` and ``optimize`` (scalars or arrays over designs).

    Parameters
    ----------
    transmission_angle : min(γmin, π − γmax) [rad];  power : Mw ω̄ [W];
    grip_speed : peak grip speed at the mean wheel speed [m/s];  handle : H [m];
    swing : [rad];  D1 : [m];  axle_height : [m] or None (no height checks);
    link_energy_share : [%] or None (quasi-static model).
    """
    heights = None if axle_height is None else grip_heights(axle_height, D1, handle, swing)
    return assess(
        feasible,
        mean,
        peak,
        force_limit,
        link_energy_share=link_energy_share,
        transmission_angle=np.degrees(transmission_angle),
        power=power,
        grip_speed=grip_speed,
        stroke=grip_stroke(handle, swing),
        grip_height=heights,
        axle_height=axle_height,
    )


def _link_grid() -> np.ndarray:
    """Crank angles [rad] on which the link kinetic energy is maximised (0.5 deg steps)."""
    return np.arange(720) * (np.pi / 360)


# ----------------------------------------------------------------------------- curves for charts
@dataclass(frozen=True)
class ForceCurve:
    """The force over one revolution on a fine grid, for a chart (SI units, radians).

    ``force`` is the quasi-static force (NaN at a dead centre); ``operator_force`` and
    ``wheel_speed`` the flywheel model's profile (None for the quasi-static model).
    """

    crank_angle: np.ndarray
    force: np.ndarray
    operator_force: np.ndarray | None
    wheel_speed: np.ndarray | None
    peak_sign: float  # sign of the quasi-static force at the dead-band peak


def force_curve(r: ForceResult, points: int = CURVE_POINTS) -> ForceCurve:
    """The curves ``pumplink force --plot`` draws, computed here so the chart only draws."""
    syn = r.design.synthesis
    theta = np.linspace(0.0, 2 * np.pi, points)
    f = kinematic_state(syn.linkage, theta, r.wheel_torque).force
    op = ws = None
    if r.flywheel and r.scene is not None and np.isfinite(r.scene.least_peak_force):
        from pumplink.models import dynamics as _dy
        from pumplink.models import flywheel as _fw

        m = _dy if r.dynamics else _fw
        op, ws = m.operator_force(r.scene, theta), m.wheel_speed(r.scene, theta)
    return ForceCurve(theta, f, op, ws, float(np.sign(np.interp(r.dead_band_peak_angle, theta, f))))


# ----------------------------------------------------------------------------- time-domain check
@dataclass(frozen=True)
class Verification:
    """The flywheel answer checked by integrating the equation of motion in time."""

    integration: _fw.TimeIntegration
    tolerance: float
    agrees: bool


def verify(r: ForceResult, rtol: float = VERIFY_RTOL) -> Verification:
    """Integrate the equation of motion under the reported force profile (scipy ``solve_ivp``) and
    check the motion is periodic with the mean speed and fluctuation asked for, to ``rtol``.

    Raises
    ------
    SpecError : the result has no flywheel scene with a finite peak force.
    """
    from pumplink.models import dynamics as _dy  # loaded when first needed (start-up)
    from pumplink.models import flywheel as _fw  # loaded when first needed (start-up)

    if r.scene is None or not math.isfinite(r.scene.least_peak_force):
        raise SpecError("nothing to integrate: no finite peak force keeps the wheel turning")
    if r.dynamics:
        sim = _dy.integrate_motion(r.scene)
        return Verification(sim, rtol, _dy.agrees(r.scene, sim, rtol))
    sim = _fw.integrate_motion(r.scene)
    agree = (
        sim.periodicity <= rtol
        and abs(sim.mean_speed - r.speed) <= rtol * r.speed
        and sim.fluctuation <= r.speed_fluctuation * (1 + rtol)
    )
    return Verification(sim, rtol, bool(agree))


# ----------------------------------------------------------------------------- best cadence
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
    from pumplink.models import dynamics as _dy  # loaded when first needed (start-up)
    from pumplink.models import flywheel as _fw  # loaded when first needed (start-up)

    spec = r.design.spec
    if spec.inertia is None:
        raise SpecError(
            f"{spec.name}: the best cadence needs the wheel's inertia (the quasi-static force does not "
            "depend on speed); add wheel.mass [kg] or wheel.inertia [kg m^2] to the spec"
        )
    syn, op, mw, j = r.design.synthesis, spec.operator, spec.wheel_torque, spec.inertia
    lk, dce, dcf, delta = syn.linkage, syn.dead_centre_extended, syn.dead_centre_folded, op.speed_fluctuation
    lo, hi = (math.radians(v) for v in searched_deg_s)
    nan = float("nan")
    with_arms = link_masses(spec, syn.coupler_length, arms=True)
    best, effort = _dy.best_speed(lk, dce, dcf, mw, j, with_arms, delta, lo, hi)
    no_arms = link_masses(spec, syn.coupler_length, arms=False)
    hand = _dy.least_peak_force(lk, dce, dcf, mw, j, no_arms, best, delta)
    edge = bool(np.isfinite(best) and min(best - lo, hi - best) <= 1e-6 * hi)
    model = r.model_key
    if model == DYNAMICS:
        arms_in = bool(op.arms_in_verdict)
        judged = link_masses(spec, syn.coupler_length, arms_in)
        # the verdict's force is least at the best cadence (arms in the verdict) or at its own minimiser
        at = best if arms_in else _dy.best_speed(lk, dce, dcf, mw, j, judged, delta, lo, hi)[0]
        force = _dy.speed_range(lk, dce, dcf, mw, j, judged, delta, op.force_limit, lo, hi, at)
    elif model == FLYWHEEL:
        slowest = float(_fw.min_passing_speed(lk, dce, dcf, mw, op.force_limit, j, delta))
        force = (slowest, math.inf) if math.isfinite(slowest) else (nan, nan)
    else:
        force = (0.0, math.inf) if r.passed else (nan, nan)
    # the checks that depend on speed fail above a speed: the power and the peak grip speed
    top = top_speed(1.0, delta if model in (FLYWHEEL, DYNAMICS) else None)
    fastest = min(HOUR_POWER_W / mw, GRIP_SPEED_FAIL_M_S / (peak_rocker_rate(lk) * top * spec.linkage.handle))
    fixed = [c.key for c in r.verdict.failures if c.key not in ("peak_force", "power", "grip_speed")]
    low, high = force[0], min(force[1], fastest)
    passing = (float(low), float(high)) if not fixed and low <= high else (nan, nan)
    return Cadence(best, effort, hand, mw * best, edge, (lo, hi), model, force, passing)


# ----------------------------------------------------------------------------- quasi-static check
#: Crank angles of the virtual-work check and of the dense sweep of :func:`verify_quasi_static`.
STATIC_CHECK_ANGLES = 3600
STATIC_SWEEP = 200_000
#: Central-difference step [rad] of the virtual-work check (truncation ~h^2, rounding ~1e-16/h).
STATIC_STEP = 1e-5
#: How far below the exact peak the dense sweep may stay, relative.  With the sweep's step
#: h = 2 pi / STATIC_SWEEP = 3.1e-5 rad, a peak at a smooth maximum is missed by at most
#: |F''/F| h^2 / 8 (~1e-10), a peak at a band edge by h |F'/F| there; next to a dead centre
#: F ~ 1 / (theta - theta_dc), so |F'/F| ~ 1 / band and the miss is up to h / band: 9e-5 for the
#: default 20 deg band, 1e-3 at 1.8 deg.  So this bound holds for bands of 1.8 deg and more; below
#: that a right peak can fail the check (measured: the prototype at a 1 deg band, 1.04e-3).
STATIC_SWEEP_RTOL = 1e-3


@dataclass(frozen=True)
class StaticCheck:
    """The quasi-static answer checked by two routes that share none of its formulas: virtual work
    from positions alone, and a dense sweep of the force against the exact peak."""

    angles: int  # crank angles outside the dead bands in the virtual-work check
    virtual_work: float  # largest |F (dPx/dt2 by central differences of positions) / Mw - 1|
    samples: int  # crank angles of the dense sweep outside the dead bands
    sweep_peak: float  # largest |F| on the sweep [N]
    peak: float  # the exact peak outside the dead bands (the verdict's) [N]
    tolerance: float  # of the virtual-work check
    agrees: bool


def verify_quasi_static(r: ForceResult, rtol: float = VERIFY_RTOL) -> StaticCheck:
    """Check the quasi-static force and its exact peak (docs/physics.md §3-4, docs/models.md §1).

    * Virtual work: at :data:`STATIC_CHECK_ANGLES` crank angles outside the dead bands, F times
      the grip's horizontal travel per crank radian, taken by central differences of the grip's
      position (Px = x_O4 + H cos t4), must be Mw to ``rtol``.
    * The peak: on a sweep of :data:`STATIC_SWEEP` crank angles outside the dead bands no |F| may
      exceed the exact peak (to 1e-9), and the largest must come within
      :data:`STATIC_SWEEP_RTOL` of it (a sample step).
    """
    syn = r.design.synthesis
    lk, mw, band = syn.linkage, r.wheel_torque, r.dead_band
    dce, dcf = syn.dead_centre_extended, syn.dead_centre_folded
    h = STATIC_STEP

    def grip_x(theta):
        return lk.pivot_x + lk.handle * np.cos(kinematic_state(lk, theta, mw).rocker_angle)

    theta = np.arange(STATIC_CHECK_ANGLES) * (2 * np.pi / STATIC_CHECK_ANGLES)
    theta = theta[~_qs.in_dead_band(theta, dce, dcf, band)]
    rate = (grip_x(theta + h) - grip_x(theta - h)) / (2 * h)
    force = kinematic_state(lk, theta, mw).force
    vw = float(np.max(np.abs(force * rate / mw - 1.0))) if theta.size else 0.0
    sweep = np.arange(STATIC_SWEEP) * (2 * np.pi / STATIC_SWEEP)
    sweep = sweep[~_qs.in_dead_band(sweep, dce, dcf, band)]
    f = np.abs(kinematic_state(lk, sweep, mw).force)
    top = float(np.nanmax(f)) if sweep.size else float("nan")
    peak = r.dead_band_peak_force
    ok = vw <= rtol and top <= peak * (1 + 1e-9) and top >= peak * (1 - STATIC_SWEEP_RTOL)
    return StaticCheck(int(theta.size), vw, int(sweep.size), top, peak, rtol, bool(ok))


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
        return SUSTAINED_POWER_W / self.design.spec.wheel_torque


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
    from pumplink.models import dynamics as _dy  # loaded when first needed (start-up)
    from pumplink.models import flywheel as _fw  # loaded when first needed (start-up)

    if spec.inertia is None:
        raise SpecError(
            f"{spec.name}: the speed study needs the wheel's inertia (the quasi-static force does not "
            "depend on speed); add wheel.mass [kg] or wheel.inertia [kg m^2] to the spec"
        )
    d = design(spec)
    if not d.feasible:
        raise InfeasibleDesign(f"{spec.name}: {d.error}")
    syn, op, mw, j = d.synthesis, spec.operator, spec.wheel_torque, spec.inertia
    given = np.asarray(speeds_deg_s, float)
    w = np.radians(np.append(given, op.speed))  # the spec's own speed last
    lk = syn.linkage
    rep = type(lk)(*(np.full(w.size, float(v)) for v in lk.parameters))  # one design per speed
    dce, dcf, delta = syn.dead_centre_extended, syn.dead_centre_folded, op.speed_fluctuation
    arms_in = bool(op.arms_in_verdict)
    with_arms = link_masses(spec, syn.coupler_length, arms=True)
    em = energy_model(rep, dce, dcf, mw, j, w, delta, with_arms, arms_in, forced=model)
    cond = Conditions(w, np.radians(op.dead_band), j, delta)
    fly = MODELS[FLYWHEEL].peak_force(rep, dce, dcf, mw, cond)
    judged = link_masses(spec, syn.coupler_length, arms_in)
    hand = _dy.least_peak_force(rep, dce, dcf, mw, j, judged, w, delta)
    effort = _dy.least_peak_force(rep, dce, dcf, mw, j, with_arms, w, delta)
    index = np.asarray(em.index)
    energy = index > 0
    req = np.where(energy, em.peak_force, np.nan)
    mean = float(_qs.mean_force(mw, grip_stroke(spec.linkage.handle, syn.swing)))
    qs = _qs.dead_band_peak_force(lk, dce, dcf, np.radians(op.dead_band), mw)[0]
    if not energy.all():  # --model quasi-static: the dead-band peak decides at every speed
        req = np.where(energy, req, qs)
    mps = float(_fw.min_passing_speed(lk, dce, dcf, mw, op.force_limit, j, delta))
    with np.errstate(divide="ignore", invalid="ignore"):
        share = np.where(em.band > 0, 100.0 * em.link_energy / em.band, np.inf)
    share = np.where(index == ORDER.index(FLYWHEEL), share, 0.0)  # a check of the flywheel only
    grip = peak_rocker_rate(lk) * np.where(energy, top_speed(w, delta), w) * spec.linkage.handle
    verdict = judge(
        True,
        mean,
        req,
        op.force_limit,
        share,
        d.transmission_angle,
        mw * w,
        grip,
        spec.linkage.handle,
        syn.swing,
        spec.linkage.D1,
        spec.wheel.axle_height,
    )
    result = force_analysis(spec, keep_samples=False, samples=0, model=model)
    passed = np.asarray(verdict.passed)
    keys = np.asarray(ORDER, dtype=object)[index]
    return SpeedSweep(
        d,
        j,
        delta,
        op.force_limit,
        mean,
        float(qs),
        mps,
        given,
        w[:-1],
        em.band[:-1],
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
    )


# ----------------------------------------------------------------------------- model choice
@dataclass(frozen=True)
class Effect:
    """One physical effect in the model-choice report: included or not, and its size."""

    name: str
    included: bool
    value: float
    unit: str
    compared_with: str  # what the ratio measures the value against, in words ('of the force limit')
    ratio: float  # value / that reference [-] (NaN when there is none)
    note: str


def _ratio(a: float, b: float) -> float:
    """a / b, with inf (a > 0) or NaN (a = 0) for b = 0 (a flywheel of zero inertia has no band)."""
    return float(a) / float(b) if b else (float("inf") if a else float("nan"))


def explain(r: ForceResult) -> tuple[tuple[Effect, ...], str]:
    """Which effects the verdict's model includes, their size at this speed, and why it is enough.

    The "least model that is enough" rule made visible (docs/models.md §3): each effect the
    flywheel leaves out (the links' kinetic energy and weight, the operator's arms) against its
    energy band, and a sentence naming the model that decided and why it is enough.
    """
    from pumplink.models import dynamics as _dy  # loaded when first needed (start-up)

    spec = r.design.spec
    op = spec.operator
    nan = float("nan")
    syn = r.design.synthesis
    work = 2 * np.pi * r.wheel_torque  # load work per revolution [J]
    masses = link_masses(spec, syn.coupler_length, arms=True)
    em = r.effects
    if em is None:  # no inertia: the sizes for information, against the work per revolution
        sizes = _dy.effect_sizes(syn.linkage, masses, r.speed)
    else:
        sizes = (em.link_energy, em.link_weight, em.arm_energy)
    link, weight, arm = sizes
    effects = [
        Effect(
            "load torque Mw = Fw rw (pump efficiency in Fw)",
            True,
            r.wheel_torque,
            "N·m",
            "",
            nan,
            f"work per revolution 2π Mw = {work:.1f} J: what the operator supplies on average",
        )
    ]
    qs = r.dead_band_peak_force
    effects.append(
        Effect(
            f"quasi-static force, peak outside ±{op.dead_band:g}° of the dead centres",
            True,
            qs,
            "N",
            "of the force limit",
            qs / r.force_limit,
            "infinite at the dead centres themselves: something must carry the linkage through",
        )
    )
    if r.flywheel:
        moving = spec.load.moving_mass_kg * spec.wheel.radius**2
        effects.append(
            Effect(
                "inertia of wheel + rope and water, J",
                True,
                r.inertia,
                "kg·m²",
                "rope and water",
                _ratio(moving, r.inertia),
                f"kinetic energy {0.5 * r.inertia * r.speed**2:.2f} J at {r.speed_deg_s:g} deg/s; band "
                f"W = J ω̄² δ = {r.energy_band:.2f} J",
            )
        )
        ref, ref_name = r.energy_band, "of the energy band W"
    else:
        ref, ref_name = work, "of the work per revolution"
    dyn, arms_in = r.dynamics, bool(op.arms_in_verdict)
    effects += [
        Effect(
            "kinetic energy of coupler + handle (largest)",
            dyn,
            link,
            "J",
            ref_name,
            _ratio(link, ref),
            f"coupler {float(masses.coupler):.2f} kg, handle {float(masses.handle):.2f} kg; grows as speed²",
        ),
        Effect(
            "weight of coupler + handle (range of potential energy)",
            dyn,
            weight,
            "J",
            ref_name,
            _ratio(weight, ref),
            "lifted and given back each revolution",
        ),
        Effect(
            "operator's arms at the grip (kinetic energy, largest)",
            dyn and arms_in,
            arm,
            "J",
            ref_name,
            _ratio(arm, ref),
            f"{op.arm_mass_kg:.2f} kg (hands, forearms, half the upper arms): in the effort"
            + (
                f" {r.effort_peak_force:.1f} N"
                if r.effort_peak_force is not None and math.isfinite(r.effort_peak_force)
                else ""
            )
            + ("" if arms_in else ", not in the hand force the verdict judges"),
        ),
        Effect(
            "operator power Mw ω̄",
            True,
            r.power,
            "W",
            "of 75 W sustained for hours",
            r.power / SUSTAINED_POWER_W,
            "a person gives 50-150 W for an hour (docs/physics.md §5)",
        ),
    ]
    return tuple(effects), _why(r, link, weight, arm, ref)


def _share(a: float, b: float) -> str:
    """a / b in words: '57%' below ten times, else '10.4×'."""
    x = _ratio(a, b)
    return f"{x:.0%}" if x < 10 else f"{x:.1f}×"


def _why(r: ForceResult, link: float, weight: float, arm: float, band: float) -> str:
    """The sentence of :func:`explain`: which model decided and why it is enough."""
    op = r.design.spec.operator
    limit = LINK_ENERGY_LIMIT
    if not r.flywheel:
        return (
            "Quasi-static + dead band decided: the spec gives no inertia, so no model with speed in it can "
            "answer. The force at each crank angle is exact by virtual work (the speed cancels out of "
            f"it) and its peak outside ±{op.dead_band:g}° of the dead centres is exact; the dead band "
            "stands in for the wheel's inertia at the dead centres, where the force is infinite. That is "
            "enough for the geometry (synthesis, transmission, where the force rises); whether a person "
            "carries the linkage through the dead centres needs the wheel: give wheel.mass or "
            "wheel.inertia and the flywheel or full dynamics decides."
        )
    sizes = (
        f"the links' kinetic energy is {_share(link, band)} of the flywheel's energy band W = "
        f"{band:.3g} J and their weight {_share(weight, band)}"
        + (f", the arms (in the verdict) {_share(arm, band)}" if op.arms_in_verdict else "")
    )
    small = model_index(r.inertia, band, link, weight, arm, bool(op.arms_in_verdict)) == ORDER.index(FLYWHEEL)
    left_out = "Still left out: joint friction and the operator's posture."
    if r.dynamics:
        effort = (
            f" The arms ({op.arm_mass_kg:g} kg at the grip, {_share(arm, band)} of W) are in the "
            f"effort figure {r.effort_peak_force:.1f} N, not in the hand force that guidance such as the "
            f"{r.force_limit:g} N limit refers to."
            if not op.arms_in_verdict and r.effort_peak_force is not None
            else ""
        )
        if r.effects.forced and small:
            return (
                f"Full dynamics decided because --model dynamics asked for it; {sizes} (at most "
                f"{limit:.0%}), so the flywheel would have been enough.{effort} {left_out}"
            )
        return (
            f"Full dynamics decided: {sizes}, more than {limit:.0%}, so the flywheel alone is not enough. "
            "It is enough here: it keeps the wheel's, the coupler's and the handle's inertia and the "
            "links' weight exactly, with the same exact least-peak-force test as the flywheel "
            f"(docs/models.md §3a).{effort} {left_out}"
        )
    if r.effects.forced and not small:
        return (
            f"Flywheel decided because --model flywheel asked for it, but {sizes}: more than "
            f"{limit:.0%}, so treat the verdict as an estimate; the least model that is enough is full "
            "dynamics (leave out --model)."
        )
    return (
        "Flywheel decided: the quasi-static force is infinite at the dead centres, so the wheel's "
        f"energy must enter; {sizes}, at most {limit:.0%} each: the links' inertia and weight, which "
        "full dynamics adds, move the band's edges by about that share of its width at most, so the "
        f"flywheel is enough. {left_out}"
    )


# ----------------------------------------------------------------------------- advice after a FAIL
@dataclass(frozen=True)
class Suggestion:
    """One change to one spec key and what it does to the verdict (:func:`suggest`)."""

    key: str  # dotted spec key, e.g. "linkage.handle"
    old: float
    new: float
    unit: str
    peak_force: float  # the verdict's peak force after the change [N]
    outcome: str  # PASS / PASS with warnings / FAIL after the change
    level: int
    excess: float  # how far the failing checks still are beyond their limits (0: none fail)
    failing: tuple[str, ...] = ()  # keys of the checks that still fail


#: The knobs :func:`suggest` turns: dotted key, unit, and the candidate changes, each a factor
#: (relative) or, for the frame placement, a step [m].
KNOBS = (
    ("linkage.handle", "m", ("x", 0.85, 1.15)),
    ("linkage.swing", "deg", ("x", 0.85, 1.15)),
    ("linkage.rocker", "m", ("x", 0.85, 1.15)),
    ("linkage.L1", "m", ("+", -0.05, 0.05)),
    ("linkage.D1", "m", ("+", -0.05, 0.05)),
    ("operator.speed", "deg/s", ("x", 0.75, 0.85, 1.15)),
    ("wheel.mass", "kg", ("x", 1.5, 2.0)),
    ("wheel.inertia", "kg m^2", ("x", 1.5, 2.0)),
)


def _excess(verdict: Verdict) -> float:
    """Sum over failing checks of the relative distance beyond the fail limit (inf: unbounded)."""
    total = 0.0
    for c in verdict.failures:
        v, lim = float(c.value), float(c.fail_limit)
        if not math.isfinite(v):
            return math.inf
        total += (v - lim) / abs(lim) if c.relation == "<=" else (lim - v) / abs(lim)
    return total


def suggest(spec: PumpSpec, result: ForceResult, count: int = 2) -> list[Suggestion]:
    """The ``count`` single changes to the spec that help a failing design most.

    Each knob of :data:`KNOBS` that the spec has is changed alone, the design is analysed again
    (the same model and checks as ``pumplink force``), and the changes are ranked by the
    verdict they give, then by how far the failing checks remain beyond their limits (the sum of
    relative excesses).  Only changes that improve on the spec are returned, at most one per key.
    Empty for a design that does not fail.
    """
    from pumplink.spec import parse_spec, spec_to_dict

    if result.verdict is None or result.passed:
        return []
    base = (int(result.verdict.level), _excess(result.verdict))
    found: dict[str, Suggestion] = {}
    for key, unit, (kind, *steps) in KNOBS:
        table, field = key.split(".")
        data = spec_to_dict(spec)
        old = data.get(table, {}).get(field)
        if old is None:
            continue
        for step in steps:
            new = old * step if kind == "x" else old + step
            new = float(f"{new:.4g}")
            data[table][field] = new
            try:
                r = force_analysis(parse_spec(data), keep_samples=False, samples=0)
            except (SpecError, InfeasibleDesign):
                continue
            if r.verdict is None:
                continue
            s = Suggestion(
                key,
                float(old),
                new,
                unit,
                r.verdict_peak_force,
                r.outcome,
                int(r.verdict.level),
                _excess(r.verdict),
                tuple(c.key for c in r.verdict.failures),
            )
            if (s.level, s.excess) < base and (
                key not in found or (s.level, s.excess) < (found[key].level, found[key].excess)
            ):
                found[key] = s
    return sorted(found.values(), key=lambda s: (s.level, s.excess))[:count]
