"""From a validated spec to results: synthesis, force sweep, checks and the verdict.

Pure functions (no I/O); the results are frozen dataclasses in SI units (radians inside),
converted to degrees and rows only by ``pumplink.report``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from pumplink import flywheel as _fw
from pumplink import force as _force
from pumplink.kinematics import State, evaluate
from pumplink.spec import PumpSpec
from pumplink.synthesis import Linkage, Synthesis, infeasibility_reason, synthesize

#: Warning limits (NOTES.md §3-4).  Transmission: the crank is the rotating driven link, so the
#: pressure angle should stay below 45 deg (transmission angle within 45..135 deg).
MIN_TRANSMISSION_DEG = 45.0
#: Sustained human power for hours [W] (NOTES.md §4).
SUSTAINED_POWER_W = 75.0
#: Wheel-axle height range used in the pump paper [m].
AXLE_HEIGHT_RANGE_M = (0.40, 0.70)

#: The two models that can decide the verdict (issue #6).
QUASI_STATIC = "quasi-static + dead band"
FLYWHEEL = "flywheel"


@dataclass(frozen=True)
class Design:
    """A spec and its dead-centre synthesis (scalars)."""

    spec: PumpSpec
    synthesis: Synthesis
    error: str | None

    @property
    def feasible(self) -> bool:
        return self.error is None


@dataclass(frozen=True)
class Check:
    """One verdict line: ``value`` compared with ``limit`` by ``relation`` ('<=' or '>=')."""

    name: str
    value: float
    limit: float
    relation: str
    unit: str
    severity: str  # "fail": decides the verdict; "warn": reported only
    passed: bool


@dataclass(frozen=True)
class ForceResult:
    """Force analysis of one design at one wheel speed (SI units, radians)."""

    design: Design
    speed_deg_s: float  # wheel speed as given [deg/s] (echoed exactly in reports)
    speed: float  # wheel speed [rad/s]
    wheel_torque: float  # Mw [N m]
    power: float  # Mw * omega [W]
    force_limit: float  # [N]
    dead_band: float  # [rad]
    mean_force: float  # [N]
    peak_force: float  # exact windowed peak [N]
    peak_angle: float  # [rad]
    sampled_peak: float  # peak over the requested samples outside the dead bands [N]
    samples_n: int
    checks: tuple[Check, ...]
    passed: bool
    samples: State | None  # None with --summary
    in_dead_band: np.ndarray | None
    marks: State | None = None  # state at (extended dead centre, folded dead centre, peak)
    # The flywheel scene (issue #6); model == QUASI_STATIC leaves the rest None.
    model: str = "quasi-static + dead band"
    inertia: float | None = None  # J [kg m^2]
    speed_fluctuation: float | None = None  # delta_allow [-]
    energy_band: float | None = None  # W = J w^2 delta [J]
    required_peak_force: float | None = None  # Fp* [N]
    min_passing_speed: float | None = None  # [rad/s]; inf: no speed passes
    scene: _fw.Scene | None = None
    operator_force: np.ndarray | None = None  # at the samples [N]
    wheel_speed: np.ndarray | None = None  # at the samples [rad/s]
    link_energy: float = float("nan")  # largest kinetic energy of coupler + handle at this speed [J]

    @property
    def flywheel(self) -> bool:
        return self.model == FLYWHEEL

    @property
    def handle_speed(self) -> np.ndarray:
        """Grip speed [m/s] at the sampled crank angles: |omega4| H (at the scene's wheel speed)."""
        w = self.speed if self.wheel_speed is None else self.wheel_speed
        return np.abs(self.samples.rocker_rate) * w * self.design.spec.linkage.handle


def design(spec: PumpSpec) -> Design:
    """Run the dead-centre synthesis (Eq. 1-2) for one spec."""
    lk = spec.linkage
    swing = np.radians(lk.swing)
    syn = synthesize(lk.L1, lk.D1, lk.b, lk.rocker, swing, lk.handle)
    return Design(spec, syn, infeasibility_reason(syn.reason, lk.L1, lk.D1, lk.b, swing))


def _check(name, value, limit, relation, unit, severity) -> Check:
    ok = bool(value <= limit) if relation == "<=" else bool(value >= limit)
    return Check(name, float(value), float(limit), relation, unit, severity, ok)


def force_analysis(spec: PumpSpec, speed_deg_s: float | None = None, samples: int = 360,
                   at_deg=None, keep_samples: bool = True, progress=None) -> ForceResult:
    """Quasi-static force sweep, checks and verdict for one spec.

    Parameters
    ----------
    spec : validated pump spec.
    speed_deg_s : wheel speed [deg/s]; default ``spec.operator.speed``.
    samples : number of uniform crank samples (ignored when ``at_deg`` is given).
    at_deg : explicit crank angles [deg] to evaluate instead of the uniform sweep.
    keep_samples : False to stream the sweep without keeping it (``--summary``).
    progress : optional callable given the fraction of a streamed sweep done (for a progress bar).
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
    model = QUASI_STATIC if inertia is None else FLYWHEEL
    fly = {} if inertia is None else dict(inertia=inertia, speed_fluctuation=op.speed_fluctuation,
                                          energy_band=float(_fw.energy_band(inertia, speed, op.speed_fluctuation)))
    if not d.feasible:
        return ForceResult(d, speed_deg, float(speed), mw, mw * float(speed), op.force_limit, float(band), nan, nan,
                           nan, nan, 0, (), False, None, None, model=model, **fly)
    lk = syn.linkage
    dce, dcf = syn.dead_centre_extended, syn.dead_centre_folded
    mean = float(_force.mean_force(mw, spec.linkage.handle, syn.swing))
    peak, peak_angle = _force.peak_force(lk, dce, dcf, band, mw)

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
        state = evaluate(lk, theta, mw)
        band_mask = _force.in_dead_band(theta, dce, dcf, band)
    if at_deg is not None:
        f = np.where(band_mask | state.singular, -np.inf, np.abs(state.force))
        sampled = float(f.max()) if f.size and np.isfinite(f.max()) else nan
        n = int(theta.size)
    else:
        sampled = _force.sampled_peak(lk, samples, mw, dce, dcf, band, progress=progress)
        n = samples

    gamma = np.degrees(min(syn.transmission_min, np.pi - syn.transmission_max))
    mpl = spec.linkage.mass_per_length or _fw.LINK_MASS_PER_METRE
    link = float(np.nanmax(_fw.link_energy(lk, _link_grid(), speed, mpl)))
    checks = [_check("mean force", mean, op.force_limit, "<=", "N", "fail")]
    if inertia is None:
        checks.append(_check(f"peak force outside ±{op.dead_band:g}° of the dead centres", peak, op.force_limit, "<=",
                             "N", "fail"))
    else:
        sc = _fw.scene(lk, dce, dcf, mw, inertia, float(speed), op.speed_fluctuation)
        fly.update(required_peak_force=sc.peak_force, scene=sc, min_passing_speed=float(_fw.min_passing_speed(
            lk, dce, dcf, mw, op.force_limit, inertia, op.speed_fluctuation)))
        if theta is not None:
            fly.update(operator_force=_fw.operator_force(sc, theta) if np.isfinite(sc.peak_force) else None,
                       wheel_speed=_fw.wheel_speed(sc, theta) if np.isfinite(sc.peak_force) else None)
        checks.append(_check(f"peak force with the flywheel (δ ≤ {op.speed_fluctuation:g})", sc.peak_force,
                             op.force_limit, "<=", "N", "fail"))
        share = 100.0 * link / fly["energy_band"] if fly["energy_band"] > 0 else np.inf  # J = 0: no band at all
        checks.append(_check("links' kinetic energy (neglected), share of the energy band", share,
                             100.0 * _fw.LINK_ENERGY_LIMIT, "<=", "%", "warn"))
    checks += [
        _check("transmission angle, min(γmin, 180° − γmax)", gamma, MIN_TRANSMISSION_DEG, ">=", "deg", "warn"),
        _check("operator power (sustained)", mw * speed, SUSTAINED_POWER_W, "<=", "W", "warn"),
    ]
    if spec.wheel.axle_height is not None:
        lo, hi = AXLE_HEIGHT_RANGE_M
        h = spec.wheel.axle_height
        checks.append(_check("axle height (paper: 0.40-0.70 m)", h, lo if h < lo else hi, ">=" if h < lo else "<=", "m", "warn"))
    passed = all(c.passed for c in checks if c.severity == "fail")
    return ForceResult(d, speed_deg, float(speed), mw, mw * float(speed), op.force_limit, float(band), mean, peak,
                       peak_angle, sampled, n, tuple(checks), passed,
                       state if keep_samples or at_deg is not None else None, band_mask,
                       evaluate(lk, np.array([dce, dcf, peak_angle]), mw), model=model, link_energy=link, **fly)


def _link_grid() -> np.ndarray:
    """Crank angles [rad] on which the link kinetic energy is maximised (0.5 deg steps)."""
    return np.arange(720) * (np.pi / 360)


# ----------------------------------------------------------------------------- speed sweep (issue #6)
@dataclass(frozen=True)
class SpeedSweep:
    """Least peak operator force against mean wheel speed for one design (flywheel model).

    Arrays over ``speed`` [rad/s]: ``energy_band`` [J], ``required_peak_force`` [N], ``power`` [W],
    ``passed`` (mean and required peak within the limit).
    """

    design: Design
    inertia: float
    speed_fluctuation: float
    force_limit: float
    mean_force: float
    quasi_static_peak: float  # exact windowed peak outside the dead band (dead-band model) [N]
    min_passing_speed: float  # [rad/s]; inf: no speed passes
    speed_deg_s: np.ndarray  # as given (echoed exactly in reports)
    speed: np.ndarray
    energy_band: np.ndarray
    required_peak_force: np.ndarray
    power: np.ndarray
    passed: np.ndarray


def speed_sweep(spec: PumpSpec, speeds_deg_s) -> SpeedSweep:
    """Required peak force at each mean wheel speed [deg/s] (Eq. (4) of ``pumplink.flywheel``).

    Raises
    ------
    SpecError : the spec gives no inertia (the quasi-static force does not depend on speed).
    InfeasibleDesign : no crank-rocker for this spec.
    """
    from pumplink.errors import InfeasibleDesign, SpecError

    if spec.inertia is None:
        raise SpecError(f"{spec.name}: the speed study needs the wheel's inertia (the quasi-static force does not "
                        "depend on speed); add wheel.mass [kg] or wheel.inertia [kg m^2] to the spec")
    d = design(spec)
    if not d.feasible:
        raise InfeasibleDesign(f"{spec.name}: {d.error}")
    syn, op, mw, j = d.synthesis, spec.operator, spec.wheel_torque, spec.inertia
    w = np.radians(np.asarray(speeds_deg_s, float))
    lk = syn.linkage
    rep = Linkage(*(np.full(w.size, float(v)) for v in (lk.pivot_x, lk.pivot_y, lk.crank, lk.coupler, lk.rocker,
                                                            lk.handle, lk.branch)))
    band = _fw.energy_band(j, w, op.speed_fluctuation)
    req = _fw.required_peak_force(rep, syn.dead_centre_extended, syn.dead_centre_folded, mw, band)
    mean = float(_force.mean_force(mw, spec.linkage.handle, syn.swing))
    qs = _force.peak_force(lk, syn.dead_centre_extended, syn.dead_centre_folded, np.radians(op.dead_band), mw)[0]
    mps = float(_fw.min_passing_speed(lk, syn.dead_centre_extended, syn.dead_centre_folded, mw, op.force_limit, j,
                                      op.speed_fluctuation))
    passed = (req <= op.force_limit) & (mean <= op.force_limit)
    return SpeedSweep(d, j, op.speed_fluctuation, op.force_limit, mean, float(qs), mps,
                      np.asarray(speeds_deg_s, float), w, band, req, mw * w, passed)


# ----------------------------------------------------------------------------- model choice (issue #6)
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

    The "model no more than the scene needs" rule made visible (issue #6): the returned sentence
    says which model answered and whether the neglected effects are small enough.
    """
    from pumplink import flywheel as fw

    spec = r.design.spec
    op, lk = spec.operator, spec.linkage
    nan = float("nan")
    w = r.speed
    work = 2 * np.pi * r.wheel_torque  # load work per revolution [J]
    arm = max(lk.handle, lk.rocker)
    mpl = lk.mass_per_length or fw.LINK_MASS_PER_METRE
    handle_mass = mpl * arm
    lift = handle_mass * 9.81 * 0.5 * arm * (1 - np.cos(np.radians(lk.swing) / 2))  # weight of the handle's centre
    effects = [Effect("load torque Mw = Fw rw (pump efficiency in Fw)", True, r.wheel_torque, "N·m", "", nan,
                      f"work per revolution 2π Mw = {work:.1f} J: what the operator supplies on average")]
    qs = r.peak_force
    effects.append(Effect(f"quasi-static force, peak outside ±{op.dead_band:g}° of the dead centres", True, qs, "N",
                          "the force limit", qs / r.force_limit,
                          "infinite at the dead centres themselves: something must carry the linkage through"))
    if r.flywheel:
        wheel_ke = 0.5 * r.inertia * w * w
        moving = spec.load.moving_mass_kg * spec.wheel.radius ** 2
        effects.append(Effect("inertia of wheel + rope and water, J", True, r.inertia, "kg·m²",
                              "of which rope and water", _ratio(moving, r.inertia),
                              f"kinetic energy {wheel_ke:.2f} J at {r.speed_deg_s:g} deg/s; band W = J ω̄² δ = "
                              f"{r.energy_band:.2f} J"))
        ref, ref_name = r.energy_band, "the energy band W"
    else:
        ref, ref_name = work, "the work per revolution"
    effects.append(Effect("kinetic energy of coupler + handle (largest)", False, r.link_energy, "J", ref_name,
                          _ratio(r.link_energy, ref), f"links taken as {mpl:.2f} kg/m tube; grows as speed²"))
    effects.append(Effect("weight of the handle (lift over the swing)", False, lift, "J", ref_name, _ratio(lift, ref),
                          f"{handle_mass:.2f} kg; given back on the way down each stroke"))
    effects.append(Effect("operator power Mw ω̄", True, r.power, "W", "75 W sustained for hours", r.power / SUSTAINED_POWER_W,
                          "a person gives 50-150 W for an hour (NOTES.md §4)"))
    small = _ratio(r.link_energy, ref) <= fw.LINK_ENERGY_LIMIT and _ratio(lift, ref) <= fw.LINK_ENERGY_LIMIT
    if not r.flywheel:
        why = ("Quasi-static + dead band answered: the spec gives no inertia, so speed cannot enter and the dead band "
               f"±{op.dead_band:g}° stands in for the flywheel. Give wheel.mass or wheel.inertia to let the wheel's "
               "energy decide (the flywheel model); the links' energy is then compared with the energy band.")
    elif small:
        why = ("Flywheel answered: the quasi-static force is infinite at the dead centres, so the wheel's energy must "
               f"enter; the neglected link energy and handle weight are at most {fw.LINK_ENERGY_LIMIT:.0%} of the band, "
               "so link inertia (full dynamics) would not change the verdict materially.")
    else:
        why = ("Flywheel answered: the quasi-static force is infinite at the dead centres, so the wheel's energy must "
               f"enter. But the neglected link energy or handle weight exceeds {fw.LINK_ENERGY_LIMIT:.0%} of the energy "
               "band: this design is past what the flywheel scene covers. Full dynamics (link masses and weight, the "
               "operator's arms) would be needed for a firm answer, which pumplink does not model; treat the verdict "
               "as an estimate, or lighten the handle (linkage.mass_per_length) or add wheel mass.")
    return tuple(effects), why
