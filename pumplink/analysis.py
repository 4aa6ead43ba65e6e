"""From a validated spec to results: synthesis, force sweep, checks and the verdict.

Pure functions (no I/O); the results are frozen dataclasses in SI units (radians inside),
converted to degrees and rows only by ``pumplink.report``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from pumplink import force as _force
from pumplink.kinematics import State, evaluate
from pumplink.spec import PumpSpec
from pumplink.synthesis import Synthesis, infeasibility_reason, synthesize

#: Warning limits (NOTES.md §3-4).  Transmission: the crank is the rotating driven link, so the
#: pressure angle should stay below 45 deg (transmission angle within 45..135 deg).
MIN_TRANSMISSION_DEG = 45.0
#: Sustained human power for hours [W] (NOTES.md §4).
SUSTAINED_POWER_W = 75.0
#: Wheel-axle height range used in the pump paper [m].
AXLE_HEIGHT_RANGE_M = (0.40, 0.70)


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

    @property
    def handle_speed(self) -> np.ndarray:
        """Grip speed [m/s] at the sampled crank angles: |omega4| H."""
        return np.abs(self.samples.rocker_rate) * self.speed * self.design.spec.linkage.handle


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
    if not d.feasible:
        return ForceResult(d, speed_deg, float(speed), mw, mw * float(speed), op.force_limit, float(band), nan, nan,
                           nan, nan, 0, (), False, None, None)
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
    checks = [
        _check("mean force", mean, op.force_limit, "<=", "N", "fail"),
        _check(f"peak force outside ±{op.dead_band:g}° of the dead centres", peak, op.force_limit, "<=", "N", "fail"),
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
                       evaluate(lk, np.array([dce, dcf, peak_angle]), mw))
