"""Independent checks of one design's answer (``pumplink force --verify``): the energy models'
motion integrated in time, and the quasi-static force and its exact peak by routes that share
none of their formulas (docs/models.md §1-3)."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from pumplink.errors import SpecError
from pumplink.evaluate import motion
from pumplink.mechanisms.fourbar import kinematic_state
from pumplink.studies.force import ForceResult

#: Relative agreement the time-domain check demands (periodicity, mean speed, fluctuation).
VERIFY_RTOL = 1e-6


@dataclass(frozen=True)
class Verification:
    """The flywheel answer checked by integrating the equation of motion in time."""

    integration: Any  # pumplink.models.flywheel.TimeIntegration
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
    sim = motion.integrate(r.scene)
    return Verification(sim, rtol, motion.agrees(r.scene, sim, rtol))


# ----------------------------------------------------------------------------- quasi-static check
#: Crank angles of the virtual-work check and of the dense sweep of :func:`verify_quasi_static`.
STATIC_CHECK_ANGLES = 3600
STATIC_SWEEP = 200_000
#: Central-difference step [rad] of the virtual-work check (truncation ~h^2, rounding ~1e-16/h).
STATIC_STEP = 1e-5
#: How far below the exact peak the dense sweep may stay at a smooth maximum, relative: with the
#: sweep's step h = 2 pi / STATIC_SWEEP = 3.1e-5 rad it misses it by |F''/F| h^2 / 8, ~1e-10.
#: At a band edge it misses it by up to h |F'/F|, and next to a dead centre F ~ 1/(theta -
#: theta_dc), so |F'/F| ~ 1/band: :func:`sweep_miss` adds 2 h / band (9e-5 at the default 20 deg
#: band, 1e-3 at 1.8 deg; a constant 1e-3 failed right peaks at a 1 deg band).
STATIC_SWEEP_RTOL = 1e-9


def sweep_miss(dead_band: float) -> float:
    """How far below the exact peak a sweep of :data:`STATIC_SWEEP` angles may stay [-] with a
    dead band of ``dead_band`` [rad] either side of each dead centre."""
    h = 2 * np.pi / STATIC_SWEEP
    return STATIC_SWEEP_RTOL + (2 * h / dead_band if dead_band > 0 else 0.0)


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
      :func:`sweep_miss` of it (a sample step times the force's slope there).
    """
    syn = r.design.synthesis
    lk, mw, band = syn.linkage, r.wheel_torque, r.dead_band
    dce, dcf = syn.dead_centre_extended, syn.dead_centre_folded
    h = STATIC_STEP

    def grip_position(theta):
        return lk.pivot_x + lk.handle * np.cos(kinematic_state(lk, theta, mw).rocker_angle)

    theta = np.arange(STATIC_CHECK_ANGLES) * (2 * np.pi / STATIC_CHECK_ANGLES)
    theta = theta[~motion.in_dead_band(theta, dce, dcf, band)]
    rate = (grip_position(theta + h) - grip_position(theta - h)) / (2 * h)
    force = kinematic_state(lk, theta, mw).force
    vw = float(np.max(np.abs(force * rate / mw - 1.0))) if theta.size else 0.0
    sweep = np.arange(STATIC_SWEEP) * (2 * np.pi / STATIC_SWEEP)
    sweep = sweep[~motion.in_dead_band(sweep, dce, dcf, band)]
    f = np.abs(kinematic_state(lk, sweep, mw).force)
    top = float(np.nanmax(f)) if sweep.size else float("nan")
    peak = r.dead_band_peak_force
    ok = vw <= rtol and top <= peak * (1 + 1e-9) and top >= peak * (1 - sweep_miss(band))
    return StaticCheck(int(theta.size), vw, int(sweep.size), top, peak, rtol, bool(ok))
