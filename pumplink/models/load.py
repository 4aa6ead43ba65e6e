"""The load a pump puts on the operator's side, and the masses that move: pure functions of spec
values, on floats or numpy arrays alike (one design passes floats, a batch one array per key), so
one formula serves both and gives the same bits.

Sources: docs/physics.md §5 (rope force, water column), docs/models.md §2-§3a (inertia, link
masses, the wheel's top speed).
"""

from __future__ import annotations

import math

import numpy as np

from pumplink.constants import DEFAULT_EFFICIENCY, GRAVITY, WATER_DENSITY
from pumplink.models import Masses


def rope_force(rope_force=None, head=None, pipe_diameter=None, efficiency=None):
    """Rope force at the wheel rim Fw [N] (docs/physics.md §5).

    ``rope_force`` when given, else the water column's weight over the pump's efficiency,
    rho g head (pi d^2 / 4) / efficiency, with :data:`~pumplink.constants.DEFAULT_EFFICIENCY`
    when ``efficiency`` is None.

    Parameters
    ----------
    rope_force : Fw [N] or None;  head : pumping head [m];  pipe_diameter : rising-main bore [m];
    efficiency : [-] or None.
    """
    if rope_force is not None:
        return rope_force
    eff = DEFAULT_EFFICIENCY if efficiency is None else efficiency
    return WATER_DENSITY * GRAVITY * head * math.pi * (pipe_diameter * pipe_diameter) / 4.0 / eff


def piston_load_force(bore, head, efficiency):
    """A single-acting piston pump's force on its working stroke [N] (Eq. P.1 of
    docs/piston-pump.md): rho g head (pi bore^2 / 4) / efficiency."""
    return (
        WATER_DENSITY
        * GRAVITY
        * np.asarray(head, float)
        * math.pi
        * np.asarray(bore, float) ** 2
        / 4.0
        / efficiency
    )


def moving_mass(moving_mass=None, head=None, pipe_diameter=None):
    """Mass moving at rim speed [kg]: ``moving_mass``, else the water column in the rising main
    rho head pi d^2 / 4 when ``head`` is given, else 0 (docs/models.md §2)."""
    if moving_mass is not None:
        return moving_mass
    if head is not None:
        return WATER_DENSITY * head * math.pi * (pipe_diameter * pipe_diameter) / 4.0
    return 0.0


def inertia(radius, wheel_inertia=None, wheel_mass=None, moving_mass_kg=0.0):
    """Moment of inertia about the wheel axle J [kg m^2] (docs/models.md §2).

    ``wheel_inertia``, or ``wheel_mass`` * radius^2 (a rim), or 0, plus the moving mass * radius^2.

    Parameters
    ----------
    radius : wheel radius rw [m];  wheel_inertia : [kg m^2] or None;  wheel_mass : [kg] or None;
    moving_mass_kg : rope and water moving with the rim [kg] (:func:`moving_mass`).
    """
    if wheel_inertia is not None:
        wheel = wheel_inertia
    elif wheel_mass is not None:
        wheel = wheel_mass * radius * radius
    else:
        wheel = 0.0 * radius * radius
    return wheel + moving_mass_kg * radius * radius


def rim_inertia(inertia=None, mass=None, radius=None):
    """A flywheel's inertia [kg m^2]: ``inertia``, else ``mass`` as a rim of ``radius``,
    J = mass radius^2 (docs/piston-pump.md: the flywheel on a piston pump's crank shaft)."""
    if inertia is not None:
        return inertia
    return mass * radius**2


def link_masses(
    coupler_length, handle, rocker, mass_per_length, coupler_mass=None, handle_mass=None, grip=0.0
):
    """Coupler, handle and grip masses [kg] (docs/models.md §3a).

    ``coupler_mass`` and ``handle_mass`` where given (NaN, or None: not given), else uniform bars
    of ``mass_per_length`` [kg/m]: the coupler's length and the handle's max(H, rocker); ``grip``
    the point mass at the grip (the operator's arms, or 0 for the hand force).
    """
    coupler = mass_per_length * np.asarray(coupler_length, float)
    if coupler_mass is not None:
        coupler = np.where(np.isnan(coupler_mass), coupler, coupler_mass)
    bar = mass_per_length * np.maximum(handle, rocker)
    if handle_mass is not None:
        bar = np.where(np.isnan(handle_mass), bar, handle_mass)
    return Masses(coupler, bar, grip)


def top_speed(mean_speed, speed_fluctuation=None):
    """The wheel's highest speed [rad/s]: the mean for the quasi-static model, ω̄(1 + δ/2) with the
    flywheel (docs/models.md §2); the peak grip speed is judged at it (docs/models.md §4)."""
    if speed_fluctuation is None:
        return mean_speed
    return mean_speed * (1.0 + 0.5 * np.asarray(speed_fluctuation, float))


def grip_speed(rocker_rate, mean_speed, handle, speed_fluctuation=None):
    """The grip's peak speed [m/s]: the rocker's largest rate max|dθ4/dθ2|
    (:func:`pumplink.mechanisms.fourbar.peak_rocker_rate`) times the wheel's top speed
    (:func:`top_speed`) times H (docs/models.md §4)."""
    return rocker_rate * top_speed(mean_speed, speed_fluctuation) * handle
