"""One design: from a validated spec to the synthesis, the force analysis, the speed study, the
model-choice report, the time-domain check and the curves a chart shows.

Pure functions (no I/O); the results are frozen dataclasses in SI units (radians inside),
converted to degrees and rows only by :mod:`pumplink.output`.  The verdict comes from
:func:`pumplink.verdict.assess`, the peak force from the model :func:`pumplink.models.choose_model`
picks.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from pumplink.constants import GRAVITY, LINK_ENERGY_LIMIT, LINK_MASS_PER_METRE, SUSTAINED_POWER_W
from pumplink.errors import InfeasibleDesign, SpecError
from pumplink.mechanisms.fourbar import (
    State,
    Synthesis,
    grip_heights,
    grip_stroke,
    infeasibility_reason,
    kinematic_state,
    peak_rocker_rate,
    synthesize,
)
from pumplink.models import DYNAMICS, FLYWHEEL, MODELS, Conditions, choose_model
from pumplink.models import dynamics as _dy
from pumplink.models import flywheel as _fw
from pumplink.models import quasi_static as _qs
from pumplink.spec import PumpSpec
from pumplink.verdict import Check, Verdict, assess

#: Crank angles of the curve a force chart draws (0.05 deg steps, both ends).
CURVE_POINTS = 7201
#: True to let full dynamics decide automatically when the links are not negligible (docs/models.md §3).
AUTO_DYNAMICS = False
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
    effort_peak_force: float | None = None  # full dynamics: least peak muscular effort, arms included [N]

    @property
    def flywheel(self) -> bool:
        """True when an energy model with the wheel's inertia decided (flywheel or full dynamics)."""
        return self.model in (MODELS[FLYWHEEL].label, MODELS[DYNAMICS].label)

    @property
    def dynamics(self) -> bool:
        return self.model == MODELS[DYNAMICS].label

    def __repr__(self) -> str:
        if not self.design.feasible:
            return f"<ForceResult {self.design.spec.name!r}: infeasible ({self.design.error})>"
        how = "flywheel" if self.flywheel else "dead band"
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


def handle_lift(spec: PumpSpec) -> tuple[float, float]:
    """Handle mass [kg] and the energy [J] its weight takes over the swing (docs/models.md §3)."""
    lk = spec.linkage
    arm = max(lk.handle, lk.rocker)
    mass = lk.handle_mass if lk.handle_mass is not None else (lk.mass_per_length or LINK_MASS_PER_METRE) * arm
    return mass, mass * GRAVITY * 0.5 * arm * (1 - np.cos(np.radians(lk.swing) / 2))


def link_masses(spec: PumpSpec, coupler_length: float, arms: bool) -> _dy.Masses:
    """Coupler, handle and grip masses [kg] from the spec (grip: operator.arm_mass when ``arms``)."""
    lk = spec.linkage
    mpl = lk.mass_per_length or LINK_MASS_PER_METRE
    return _dy.Masses(
        lk.coupler_mass if lk.coupler_mass is not None else mpl * coupler_length,
        handle_lift(spec)[0],
        spec.operator.arm_mass_kg if arms else 0.0,
    )


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
    if model is not None and model != "quasi-static" and inertia is None:
        raise SpecError(
            f"--model {model} needs the wheel's inertia, but {spec.name} gives none; add wheel.mass [kg] "
            "or wheel.inertia [kg m^2] to the spec"
        )
    # the least model that is enough: the flywheel unless the links' energy or weight is not small
    small = True
    if inertia is not None and d.feasible:
        w_band = float(_fw.energy_band(inertia, speed, op.speed_fluctuation))
        mpl0 = spec.linkage.mass_per_length or LINK_MASS_PER_METRE
        ke = float(np.nanmax(_fw.link_energy(d.synthesis.linkage, _link_grid(), speed, mpl0)))
        small = (
            _ratio(ke, w_band) <= LINK_ENERGY_LIMIT
            and _ratio(handle_lift(spec)[1], w_band) <= LINK_ENERGY_LIMIT
        )
    # Not yet automatic: full dynamics decides with --model dynamics; the shipped tests and golden
    # outputs still expect the flywheel when the spec gives inertia (see AUTO_DYNAMICS).
    model = (
        MODELS[model] if model is not None else choose_model(inertia is not None, small or not AUTO_DYNAMICS)
    )
    fly = (
        {}
        if inertia is None
        else dict(
            inertia=inertia,
            speed_fluctuation=op.speed_fluctuation,
            energy_band=float(_fw.energy_band(inertia, speed, op.speed_fluctuation)),
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
    cond = conditions(spec, float(speed))
    peak, peak_angle = _qs.dead_band_peak_force(lk, dce, dcf, band, mw)

    # Kept samples: the given --at angles, else the uniform sweep.  The sampled peak of a
    # uniform sweep always comes from the one streamed route (so --summary does not change it).
    if at_deg is not None:
        theta = np.radians(np.asarray(at_deg, float))
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
    mpl = spec.linkage.mass_per_length or LINK_MASS_PER_METRE
    link = float(np.nanmax(_fw.link_energy(lk, _link_grid(), speed, mpl)))
    share = None
    verdict_peak = peak
    if model.key == DYNAMICS:
        ms = link_masses(spec, float(syn.coupler_length), op.arms_in_verdict)
        sc = _dy.scene(lk, dce, dcf, mw, inertia, ms, float(speed), op.speed_fluctuation)
        with_arms = link_masses(spec, float(syn.coupler_length), True)
        effort = _dy.least_peak_force(
            lk, dce, dcf, mw, inertia, with_arms, float(speed), op.speed_fluctuation
        )
        fly.update(
            least_peak_force=sc.least_peak_force, scene=sc, min_passing_speed=nan, effort_peak_force=effort
        )
        if np.isfinite(sc.least_peak_force):
            fly.update(
                mark_operator_force=_dy.operator_force(sc, marks.crank_angle),
                mark_wheel_speed=_dy.wheel_speed(sc, marks.crank_angle),
            )
            if theta is not None:
                fly.update(
                    operator_force=_dy.operator_force(sc, theta),
                    wheel_speed=_dy.wheel_speed(sc, theta),
                    on_ceiling=_dy.regime(sc, theta) == 0,
                )
        verdict_peak = sc.least_peak_force
    elif model.key == FLYWHEEL:
        fp = float(model.peak_force(lk, dce, dcf, mw, cond))
        sc = _fw.scene(lk, dce, dcf, mw, inertia, float(speed), op.speed_fluctuation, solved=fp)
        fly.update(
            least_peak_force=sc.least_peak_force,
            scene=sc,
            min_passing_speed=float(
                _fw.min_passing_speed(lk, dce, dcf, mw, op.force_limit, inertia, op.speed_fluctuation)
            ),
        )
        if np.isfinite(sc.least_peak_force):
            fly.update(
                mark_operator_force=_fw.operator_force(sc, marks.crank_angle),
                mark_wheel_speed=_fw.wheel_speed(sc, marks.crank_angle),
            )
            if theta is not None:
                fly.update(
                    operator_force=_fw.operator_force(sc, theta),
                    wheel_speed=_fw.wheel_speed(sc, theta),
                    on_ceiling=_fw.on_ceiling(sc, theta),
                )
        verdict_peak = sc.least_peak_force
        share = (
            100.0 * link / fly["energy_band"] if fly["energy_band"] > 0 else np.inf
        )  # J = 0: no band at all
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


# ----------------------------------------------------------------------------- speed sweep
@dataclass(frozen=True)
class SpeedSweep:
    """Least peak operator force against mean wheel speed for one design (flywheel model).

    Arrays over ``speed`` [rad/s]: ``energy_band`` [J], ``least_peak_force`` [N], ``power`` [W],
    ``passed`` (no check fails at that speed); :meth:`spec_speed_passes`: the verdict at the spec's
    own speed (what ``pumplink force`` says).
    """

    design: Design
    inertia: float
    speed_fluctuation: float
    force_limit: float
    mean_force: float
    dead_band_peak_force: float  # exact windowed peak outside the dead band (dead-band model) [N]
    min_passing_speed: float  # [rad/s]; inf: no speed passes
    speed_deg_s: np.ndarray  # as given (echoed exactly in reports)
    speed: np.ndarray
    energy_band: np.ndarray
    least_peak_force: np.ndarray
    power: np.ndarray
    passed: np.ndarray
    verdict: Verdict | None = None  # every check at each speed (the spec's own speed last)
    grip_speed: np.ndarray | None = None  # peak grip speed at each speed [m/s]

    @property
    def outcome(self) -> np.ndarray:
        """'PASS', 'PASS with warnings' or 'FAIL' at each speed."""
        return np.asarray(self.verdict.outcome)[:-1]

    def spec_speed_passes(self, strict: bool = False) -> bool:
        """The verdict at the spec's own speed (as ``pumplink force``), strict or not."""
        return bool(np.asarray(self.verdict.passed_strict(strict))[-1])


def speed_sweep(spec: PumpSpec, speeds_deg_s) -> SpeedSweep:
    """Least peak force at each mean wheel speed [deg/s] (docs/models.md §2, Eq. (4)).

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
    syn, op, mw, j = d.synthesis, spec.operator, spec.wheel_torque, spec.inertia
    given = np.asarray(speeds_deg_s, float)
    w = np.radians(np.append(given, op.speed))  # the spec's own speed last
    lk = syn.linkage
    rep = type(lk)(*(np.full(w.size, float(v)) for v in lk.parameters))  # one design per speed
    cond = Conditions(w, np.radians(op.dead_band), j, op.speed_fluctuation)
    req = MODELS[FLYWHEEL].peak_force(rep, syn.dead_centre_extended, syn.dead_centre_folded, mw, cond)
    band = _fw.energy_band(j, w, op.speed_fluctuation)
    mean = float(_qs.mean_force(mw, grip_stroke(spec.linkage.handle, syn.swing)))
    qs = _qs.dead_band_peak_force(
        lk, syn.dead_centre_extended, syn.dead_centre_folded, np.radians(op.dead_band), mw
    )[0]
    mps = float(
        _fw.min_passing_speed(
            lk, syn.dead_centre_extended, syn.dead_centre_folded, mw, op.force_limit, j, op.speed_fluctuation
        )
    )
    mpl = spec.linkage.mass_per_length or LINK_MASS_PER_METRE
    link_1 = float(np.nanmax(_fw.link_energy(lk, _link_grid(), 1.0, mpl)))  # at 1 rad/s; scales as w^2
    with np.errstate(divide="ignore"):
        share = np.where(band > 0, 100.0 * link_1 * w * w / band, np.inf)
    grip = peak_rocker_rate(lk) * top_speed(w, op.speed_fluctuation) * spec.linkage.handle
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
    passed = np.asarray(verdict.passed)
    return SpeedSweep(
        d,
        j,
        op.speed_fluctuation,
        op.force_limit,
        mean,
        float(qs),
        mps,
        given,
        w[:-1],
        band[:-1],
        req[:-1],
        mw * w[:-1],
        passed[:-1],
        verdict,
        grip[:-1],
    )


# ----------------------------------------------------------------------------- model choice
@dataclass(frozen=True)
class Effect:
    """One physical effect in the model-choice report: included or not, and its size."""

    name: str
    included: bool
    value: float
    unit: str
    compared_with: str  # what the value is measured against, in words
    ratio: float  # value / that reference [-] (NaN when there is none)
    note: str


def _ratio(a: float, b: float) -> float:
    """a / b, with inf (a > 0) or NaN (a = 0) for b = 0 (a flywheel of zero inertia has no band)."""
    return float(a) / float(b) if b else (float("inf") if a else float("nan"))


def explain(r: ForceResult) -> tuple[tuple[Effect, ...], str]:
    """Which effects the verdict's model includes, their size at this speed, and why it suffices.

    The "model no more than the scene needs" rule made visible (docs/models.md §3): the returned
    sentence says which model answered and whether the neglected effects are small enough.
    """
    spec = r.design.spec
    op, lk = spec.operator, spec.linkage
    nan = float("nan")
    w = r.speed
    work = 2 * np.pi * r.wheel_torque  # load work per revolution [J]
    mpl = lk.mass_per_length or LINK_MASS_PER_METRE
    handle_mass, lift = handle_lift(spec)  # weight of the handle's centre
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
            "the force limit",
            qs / r.force_limit,
            "infinite at the dead centres themselves: something must carry the linkage through",
        )
    )
    if r.flywheel:
        wheel_ke = 0.5 * r.inertia * w * w
        moving = spec.load.moving_mass_kg * spec.wheel.radius**2
        effects.append(
            Effect(
                "inertia of wheel + rope and water, J",
                True,
                r.inertia,
                "kg·m²",
                "of which rope and water",
                _ratio(moving, r.inertia),
                f"kinetic energy {wheel_ke:.2f} J at {r.speed_deg_s:g} deg/s; band W = J ω̄² δ = "
                f"{r.energy_band:.2f} J",
            )
        )
        ref, ref_name = r.energy_band, "the energy band W"
    else:
        ref, ref_name = work, "the work per revolution"
    dyn = r.dynamics
    effects.append(
        Effect(
            "kinetic energy of coupler + handle (largest)",
            dyn,
            r.link_energy,
            "J",
            ref_name,
            _ratio(r.link_energy, ref),
            f"links taken as {mpl:.2f} kg/m tube; grows as speed²",
        )
    )
    effects.append(
        Effect(
            "weight of the handle (lift over the swing)",
            dyn,
            lift,
            "J",
            ref_name,
            _ratio(lift, ref),
            f"{handle_mass:.2f} kg; given back on the way down each stroke",
        )
    )
    effects.append(
        Effect(
            "operator power Mw ω̄",
            True,
            r.power,
            "W",
            "75 W sustained for hours",
            r.power / SUSTAINED_POWER_W,
            "a person gives 50-150 W for an hour (docs/physics.md §5)",
        )
    )
    if r.flywheel:
        arms = op.arm_mass_kg
        arm_ke = 0.5 * arms * float(np.nanmax(r.handle_speed)) ** 2 if r.samples is not None else nan
        effects.append(
            Effect(
                "operator's arms at the grip (kinetic energy, largest)",
                dyn and op.arms_in_verdict,
                arm_ke,
                "J",
                ref_name,
                _ratio(arm_ke, ref),
                f"{arms:.2f} kg (hands, forearms, half the upper arms); in the muscular effort"
                + (
                    f" {r.effort_peak_force:.1f} N, not in the hand force"
                    if dyn and r.effort_peak_force is not None and not op.arms_in_verdict
                    else ""
                ),
            )
        )
    small = _ratio(r.link_energy, ref) <= LINK_ENERGY_LIMIT and _ratio(lift, ref) <= LINK_ENERGY_LIMIT
    if dyn:
        why = (
            "Full dynamics answered: the links' kinetic energy "
            f"({_ratio(r.link_energy, ref):.0%} of the band) or the handle's weight "
            f"({_ratio(lift, ref):.0%}) is more than {LINK_ENERGY_LIMIT:.0%} of the flywheel's energy band, "
            "so the flywheel alone is not enough; the coupler and handle masses and their weight are in "
            "the model (the operator's arms in the effort figure). Still left out: joint friction and the "
            "operator's posture."
        )
    elif not r.flywheel:
        why = (
            "Quasi-static + dead band answered: the spec gives no inertia, so speed cannot enter and "
            f"the dead band ±{op.dead_band:g}° stands in for the flywheel. Give wheel.mass or "
            "wheel.inertia to let the wheel's energy decide (the flywheel model); the links' energy is "
            "then compared with the energy band."
        )
    elif small:
        why = (
            "Flywheel answered: the quasi-static force is infinite at the dead centres, so the wheel's "
            "energy must enter; the neglected link energy and handle weight are at most "
            f"{LINK_ENERGY_LIMIT:.0%} of the band, "
            "so link inertia (full dynamics) would not change the verdict materially."
        )
    else:
        why = (
            "Flywheel answered: the quasi-static force is infinite at the dead centres, so the wheel's "
            "energy must enter. But the neglected link energy or handle weight exceeds "
            f"{LINK_ENERGY_LIMIT:.0%} of the energy "
            "band: this design is past what the flywheel scene covers. Full dynamics (link masses and "
            "weight, the operator's arms) would be needed for a firm answer: run with --model dynamics; "
            "treat this verdict "
            "as an estimate, or lighten the handle (linkage.mass_per_length) or add wheel mass."
        )
    return tuple(effects), why


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
