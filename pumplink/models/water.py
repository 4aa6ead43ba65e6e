"""Water delivered by a design: flow, water power, efficiency, the power-limited flow Q* and the
people a pump serves (docs/water.md).

The physics (docs/water.md §1-§5):

    Q_rope   = eta_v (pi d^2 / 4) w r_w                                          (W.1)
    Q_piston = eta_v (pi bore^2 / 4) stroke w / (2 pi)   (single-acting)          (W.2)
    P_water  = rho g H Q                                                          (W.3)
    eta      = P_water / P_operator                                               (W.4)
    Q*       = eta_force eta_v P_sustained / (rho g H)                            (W.5)
    people   = Q t_day / (litres per person per day)                              (W.6)
    t_fill   = V / Q,  turns = t_fill w / (2 pi)   (a container of V)             (W.7)

w is the mean wheel (crank) speed [rad/s]; the rope moves with the wheel rim, so the rope speed
is w r_w.  eta_v is the volumetric efficiency (leakage past the pistons), eta_force the force
efficiency that sets the rope force rho g H (pi d^2/4) / eta_force (docs/physics.md §5).  With
both, a design's operator power is rho g H Q / (eta_force eta_v), so Q / Q* is exactly the
operator's mean power over the sustained power (docs/water.md §4).

Pure numpy on floats and arrays (broadcasting over designs), SI units throughout: flows in m^3/s,
powers in W, heads in m, speeds in rad/s.  Litres per minute and m^3/h are the output layer's
(x 60 000 and x 3 600).  Invalid inputs give NaN, never a made-up value.
"""

from __future__ import annotations

import math

import numpy as np

from pumplink.constants import (
    DEFAULT_DAILY_PUMPING_HOURS,
    DEFAULT_EFFICIENCY,
    DEFAULT_LITRES_PER_PERSON_DAY,
    DEFAULT_VOLUMETRIC_EFFICIENCY,
    GRAVITY,
    WATER_DENSITY,
)

_RHO_G = WATER_DENSITY * GRAVITY
#: The field's container: a 20-litre jerrycan, what a bucket test at a pump fills [m^3]
#: (docs/water.md §5).
CONTAINER_VOLUME = 0.020


def _nonnegative(x):
    """x as a float array, NaN where it is negative or not a number."""
    x = np.asarray(x, dtype=float)
    return np.where(x >= 0.0, x, np.nan)


def pipe_area(diameter):
    """Bore area pi d^2 / 4 [m^2] of a pipe or cylinder of diameter ``diameter`` [m] (NaN if < 0)."""
    d = _nonnegative(diameter)
    return math.pi * d * d / 4.0


def rope_pump_flow(pipe_diameter, wheel_speed, wheel_radius, volumetric_efficiency=None):
    """Flow delivered by a rope pump Q [m^3/s] (Eq. W.1, docs/water.md §1).

    Q = eta_v (pi d^2/4) w r_w: the pistons sweep the rising main at the rope speed, which is the
    wheel's rim speed w r_w (no slip on the wheel).

    Parameters
    ----------
    pipe_diameter : rising-main bore d [m];  wheel_speed : mean wheel speed w [rad/s];
    wheel_radius : r_w [m];  volumetric_efficiency : eta_v [-], default
    :data:`~pumplink.constants.DEFAULT_VOLUMETRIC_EFFICIENCY`.
    """
    eta_v = DEFAULT_VOLUMETRIC_EFFICIENCY if volumetric_efficiency is None else volumetric_efficiency
    rim_speed = _nonnegative(wheel_speed) * _nonnegative(wheel_radius)
    return _nonnegative(eta_v) * pipe_area(pipe_diameter) * rim_speed  # Eq. (W.1)


def piston_pump_flow(bore, stroke, crank_speed, volumetric_efficiency=None):
    """Flow delivered by a single-acting piston pump Q [m^3/s] (Eq. W.2, docs/water.md §1).

    Q = eta_v (pi bore^2/4) stroke f, f = w / (2 pi): one working stroke per crank turn.

    Parameters
    ----------
    bore : cylinder bore [m];  stroke : piston stroke [m];  crank_speed : mean crank speed w [rad/s];
    volumetric_efficiency : eta_v [-], default :data:`~pumplink.constants.DEFAULT_VOLUMETRIC_EFFICIENCY`.
    """
    eta_v = DEFAULT_VOLUMETRIC_EFFICIENCY if volumetric_efficiency is None else volumetric_efficiency
    frequency = _nonnegative(crank_speed) / (2.0 * math.pi)
    return _nonnegative(eta_v) * pipe_area(bore) * _nonnegative(stroke) * frequency  # Eq. (W.2)


def water_power(flow, head):
    """Hydraulic power rho g H Q [W] of the flow ``flow`` [m^3/s] lifted through ``head`` [m] (Eq. W.3)."""
    return _RHO_G * _nonnegative(head) * _nonnegative(flow)  # Eq. (W.3)


def overall_efficiency(water_power, operator_power):
    """Overall efficiency P_water / P_operator [-] (Eq. W.4); NaN where the operator's power is not
    positive (no efficiency without work)."""
    p_op = np.asarray(operator_power, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):
        eta = _nonnegative(water_power) / p_op  # Eq. (W.4)
    return np.where(p_op > 0.0, eta, np.nan)


def power_limited_flow(sustained_power, head, force_efficiency=None, volumetric_efficiency=None):
    """Q* [m^3/s]: the flow the operator's sustained power can lift through the pump (Eq. W.5).

    Q* = eta_force eta_v P_sustained / (rho g H), the pump's own overall efficiency (force x
    volumetric, docs/water.md §4) applied to the operator's sustained power.  With the same
    efficiencies as the design, Q / Q* is the design's mean operator power over P_sustained.
    Pass force_efficiency = volumetric_efficiency = 1 for the lossless bound.  Infinite at zero
    head (lifting costs nothing), NaN for a negative head.

    Parameters
    ----------
    sustained_power : the operator's sustained power [W];  head : pumping head [m];
    force_efficiency, volumetric_efficiency : [-], defaults
    :data:`~pumplink.constants.DEFAULT_EFFICIENCY` and
    :data:`~pumplink.constants.DEFAULT_VOLUMETRIC_EFFICIENCY`.
    """
    eta_f = DEFAULT_EFFICIENCY if force_efficiency is None else force_efficiency
    eta_v = DEFAULT_VOLUMETRIC_EFFICIENCY if volumetric_efficiency is None else volumetric_efficiency
    lift = _RHO_G * _nonnegative(head)
    useful = _nonnegative(eta_f) * _nonnegative(eta_v) * _nonnegative(sustained_power)
    with np.errstate(divide="ignore", invalid="ignore"):
        flow = useful / lift  # Eq. (W.5)
    return np.where(lift == 0.0, np.where(useful > 0.0, np.inf, np.nan), flow)


def flow_share(flow, limit):
    """A design's share of the power-limited flow, Q / Q* [-] (docs/water.md §4); 0 where Q* is
    infinite, NaN where Q* is not positive."""
    q_star = np.asarray(limit, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):
        share = _nonnegative(flow) / q_star
    return np.where(q_star > 0.0, share, np.nan)


def people_served(flow, daily_hours=None, litres_per_person_day=None):
    """People whose daily water the flow ``flow`` [m^3/s] supplies (Eq. W.6, docs/water.md §5).

    people = Q t_day / (litres per person per day), t_day the hours a day the pump is in use
    (default :data:`~pumplink.constants.DEFAULT_DAILY_PUMPING_HOURS`, Sphere) and the daily water
    per person default :data:`~pumplink.constants.DEFAULT_LITRES_PER_PERSON_DAY` (WHO basic
    access).  A capacity at the design flow, not a count of users.  NaN where the litres per person
    are not positive.
    """
    hours = DEFAULT_DAILY_PUMPING_HOURS if daily_hours is None else daily_hours
    litres = DEFAULT_LITRES_PER_PERSON_DAY if litres_per_person_day is None else litres_per_person_day
    per_person = np.asarray(litres, dtype=float) / 1000.0  # [m^3]
    daily_volume = _nonnegative(flow) * _nonnegative(hours) * 3600.0  # [m^3]
    with np.errstate(divide="ignore", invalid="ignore"):
        people = daily_volume / per_person  # Eq. (W.6)
    return np.where(per_person > 0.0, people, np.nan)


def fill(volume, flow, wheel_speed):
    """The time [s] and the wheel (crank) turns [-] to fill ``volume`` [m^3] at the flow ``flow``
    [m^3/s] and the mean speed ``wheel_speed`` [rad/s] (Eq. W.7, docs/water.md §5):
    t = V / Q and turns = t w / (2 pi).  Infinite where no water flows, NaN where the flow is not
    known."""
    q = _nonnegative(flow)
    with np.errstate(divide="ignore", invalid="ignore"):
        time = _nonnegative(volume) / q  # Eq. (W.7)
    time = np.where(q > 0.0, time, np.where(q == 0.0, np.inf, np.nan))
    return time, time * _nonnegative(wheel_speed) / (2.0 * math.pi)  # Eq. (W.7)
