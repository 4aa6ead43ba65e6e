"""The rope pump's losses by design: leakage past the pistons, friction in the rising main and the
rest, and the rope speed at which a duty's power drives the pump (docs/water.md §2a).

The physics (docs/water.md §2a, symbols of §1: d the bore, v = w r_w the rope speed, H the head):

    Re   = rho v d / mu,   f = 0.3164 Re^-1/4 (Blasius, smooth pipe), 64 / Re below Re 2300 (L.1)
    k_f  = f v^2 / (2 g d)           friction in the rising main over the lift, rho g H A v   (L.2)
    dp   = rho g (1 + k_f) min(H, s)  the pressure one piston holds (n = H / s of them)       (L.3)
    Q_l  = C a_gap sqrt(2 dp / rho)   leakage past each piston, a short annular orifice        (L.4)
    eta_v = 1 - Q_l / (A v)           volumetric efficiency                                    (L.5)
    eta_f = 1 / (1 + k_f + k_o)       force efficiency; k_o: the guide, bearings and pistons   (L.6)

a_gap = pi/4 (d^2 - (d - c)^2) is the annulus between a piston of diametral clearance c and the
bore, A = pi d^2 / 4, s the piston spacing.  Every piston holds the same pressure and leaks the
same flow (continuity), so the head enters only through the pressure each piston holds: min(H, s)
above; a deeper well has more pistons, not a larger leak.

Parameters and where they come from (docs/water.md §2a has the fit and its check):

* c = 0.35 mm: the middle of the 0.2-0.5 mm a rope-pump piston fits its pipe with (University of
  Twente WOT, *Rope pump construction manual*, introduction);
* s = 1 m: the piston spacing the mawama model equations confirm (Akvopedia, "Rope pump");
* mu = 1.0e-3 Pa s: water at 20 °C;
* C and k_o: fitted so that the reference pump (23 mm bore, c and s as above) has its best overall
  efficiency at 1.2 m/s and that efficiency is 65 % (Akvopedia, "Rope pump": the mawama model's
  best rope speed "around 1.2 m/s", efficiencies "typically" 65 %).  Two values from two
  conditions: the residuals are zero by construction; the out-of-sample check is ``pumplink
  validate`` against the published discharges.  C = 0.822 is the discharge coefficient of a
  short tube in the textbooks (about 0.82), which the fit was not told.

Pure numpy on floats and arrays (broadcasting over designs), SI units.  Invalid inputs give NaN.
"""

from __future__ import annotations

import math

import numpy as np

from pumplink.constants import GRAVITY, WATER_DENSITY

#: Diametral clearance of a piston in its bore [m]: the middle of the University of Twente WOT
#: construction manual's 0.2-0.5 mm (docs/water.md §2a).
PISTON_CLEARANCE = 0.35e-3
#: Piston spacing on the rope [m]: the mawama model's 1 m, as Akvopedia quotes it (docs/water.md §2a).
PISTON_SPACING = 1.0
#: Dynamic viscosity of water at 20 °C [Pa s].
WATER_VISCOSITY = 1.0e-3
#: Discharge coefficient of the gap past a piston [-]: fitted (module docstring; docs/water.md §2a).
LEAK_COEFFICIENT = 0.822
#: The other losses (rope guide, bearings, pistons rubbing) as a share of the lifting power [-]:
#: fitted with :data:`LEAK_COEFFICIENT` (docs/water.md §2a).
OTHER_LOSS_SHARE = 0.3137
#: The reference pump of the fit: bore [m], best rope speed [m/s], its overall efficiency [-], head [m].
REFERENCE = (0.023, 1.2, 0.65, 10.0)
#: Reynolds number below which the flow in the rising main is laminar.
LAMINAR_REYNOLDS = 2300.0

_RHO_G = WATER_DENSITY * GRAVITY


def _positive(x):
    x = np.asarray(x, dtype=float)
    return np.where(x > 0.0, x, np.nan)


def friction_factor(reynolds):
    """Darcy friction factor of a smooth pipe [-] (Eq. L.1): 64/Re below Re 2300, Blasius's
    0.3164 Re^-1/4 above (valid to about Re 1e5, beyond any hand pump)."""
    re = _positive(reynolds)
    return np.where(re < LAMINAR_REYNOLDS, 64.0 / re, 0.3164 * re**-0.25)  # Eq. (L.1)


def pipe_friction_share(pipe_diameter, rope_speed):
    """Friction in the rising main over the lifting work, k_f = f v² / (2 g d) [-] (Eq. L.2): the
    water column moves at the rope speed through a pipe as long as the head, so the share does not
    depend on the head."""
    d, v = _positive(pipe_diameter), _positive(rope_speed)
    f = friction_factor(WATER_DENSITY * v * d / WATER_VISCOSITY)
    return f * v * v / (2.0 * GRAVITY * d)  # Eq. (L.2)


def gap_area(pipe_diameter, clearance=PISTON_CLEARANCE):
    """The annulus between a piston of diametral clearance ``clearance`` and the bore [m²]."""
    d, c = _positive(pipe_diameter), np.asarray(clearance, float)
    return math.pi / 4.0 * (d * d - (d - c) ** 2)


def volumetric_efficiency(
    pipe_diameter,
    rope_speed,
    head,
    clearance=PISTON_CLEARANCE,
    spacing=PISTON_SPACING,
    coefficient=LEAK_COEFFICIENT,
):
    """Delivered over swept flow, η_v = 1 − Q_l / (A v) [-] (Eq. L.3-L.5), 0 where the leak
    exceeds the sweep.

    Parameters
    ----------
    pipe_diameter : d [m];  rope_speed : v [m/s];  head : H [m];  clearance : diametral clearance
    c [m];  spacing : piston spacing s [m];  coefficient : the gap's discharge coefficient C [-].
    """
    d, v = _positive(pipe_diameter), _positive(rope_speed)
    held = np.minimum(np.asarray(head, float), np.asarray(spacing, float))
    dp = _RHO_G * (1.0 + pipe_friction_share(d, v)) * held  # Eq. (L.3)
    leak = coefficient * gap_area(d, clearance) * np.sqrt(2.0 * dp / WATER_DENSITY)  # Eq. (L.4)
    swept = math.pi * d * d / 4.0 * v
    return np.maximum(1.0 - leak / swept, 0.0)  # Eq. (L.5)


def force_efficiency(pipe_diameter, rope_speed, other=OTHER_LOSS_SHARE):
    """The lifting power over the power at the rope, η_f = 1 / (1 + k_f + k_o) [-] (Eq. L.6)."""
    return 1.0 / (1.0 + pipe_friction_share(pipe_diameter, rope_speed) + other)  # Eq. (L.6)


def overall_efficiency(pipe_diameter, rope_speed, head, **losses):
    """η_v η_f [-] (Eq. L.5 × L.6); ``losses``: clearance, spacing, coefficient, other."""
    other = losses.pop("other", OTHER_LOSS_SHARE)
    return volumetric_efficiency(pipe_diameter, rope_speed, head, **losses) * force_efficiency(
        pipe_diameter, rope_speed, other
    )


def off_by(constant, model):
    """How far a constant efficiency is from the loss model's, |constant / model − 1| [-]: the
    share by which the constant changes the flow (η_v) or the force (η_f)."""
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.abs(np.asarray(constant, float) / np.asarray(model, float) - 1.0)


#: Fixed-point steps of :func:`duty_rope_speed` (each shrinks the error by |v dη_f/dv / η_f| < 0.2
#: in the pump's range: 60 steps settle it to rounding).
DUTY_STEPS = 60


def duty_rope_speed(power, head, pipe_diameter, efficiency, steps=DUTY_STEPS, start=1.0):
    """The rope speed [m/s] at which the pump asks the operator for ``power`` [W]:
    P = ρ g H A v / η_f(v), solved by ``steps`` fixed-point steps v ← P η_f(v) / (ρ g H A) from
    ``start`` times P / (ρ g H A) (the lossless speed).

    ``efficiency(v)`` gives η_f at rope speed v (arrays over designs, each design's from its own
    speed); a constant η_f solves in one step.  The steps stop once the speeds repeat to the bit
    (every two steps at most: a speed may settle between two adjacent floats), with the speeds the
    last step would give.  NaN where the head or the bore is not positive."""
    lift = _RHO_G * _positive(head) * math.pi * _positive(pipe_diameter) ** 2 / 4.0  # [N]
    p = np.asarray(power, float)
    v, before = start * p / lift, None
    for i in range(steps):
        new = p * efficiency(v) / lift  # the speeds after step i + 1
        if before is not None and np.array_equal(new, before, equal_nan=True):
            # from step i - 1 on they repeat every two steps (or stay): the last step's are these
            # or the ones before, by its parity; the same bits as stepping on
            return new if (steps - i - 1) % 2 == 0 else v
        before, v = v, new
    return v


__all__ = [
    "DUTY_STEPS",
    "LEAK_COEFFICIENT",
    "OTHER_LOSS_SHARE",
    "PISTON_CLEARANCE",
    "PISTON_SPACING",
    "REFERENCE",
    "duty_rope_speed",
    "force_efficiency",
    "friction_factor",
    "gap_area",
    "off_by",
    "overall_efficiency",
    "pipe_friction_share",
    "volumetric_efficiency",
]
