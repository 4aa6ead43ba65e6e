"""The least model that is enough, chosen and solved for designs with the wheel's inertia.

:func:`energy_model` decides between the flywheel and full dynamics per design
(:func:`pumplink.models.model_index`, docs/models.md §3) and solves the chosen one's least peak
force.  Floats for one design, arrays over designs otherwise.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from pumplink.mechanisms.fourbar import FourBar, per_design
from pumplink.models import DYNAMICS, FLYWHEEL, MODELS, ORDER, Conditions, Masses, model_index


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
    least: np.ndarray | int | None = None  # the least model that is enough (``index`` when not forced)

    def design(self, i: int) -> EnergyModel:
        """The choice for design ``i`` alone (floats), from a choice over designs."""
        index, band, link, weight, arm, arms, peak, least = (
            np.asarray(getattr(self, k))[i]
            for k in (
                "index",
                "band",
                "link_energy",
                "link_weight",
                "arm_energy",
                "arms_in_verdict",
                "peak_force",
                "least",
            )
        )
        return EnergyModel(
            int(index),
            float(band),
            float(link),
            float(weight),
            float(arm),
            bool(arms),
            float(peak),
            self.forced,
            int(least),
        )

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
    rocker_rate=None,
) -> EnergyModel:
    """Choose between the flywheel and full dynamics and solve the chosen one's least peak force.

    ``masses``: coupler and handle [kg] and the arms at the grip (operator.arm_mass); the arms
    enter the solved force only where ``arms_in_verdict``.  ``forced``: a model key that overrides
    the choice.  ``solve``: False (or False per design) to leave the force unsolved (NaN), e.g. for
    an infeasible design.  ``rocker_rate``: max|dθ4/dθ2| of each design where known (the arms'
    energy), else found here.
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
    link, weight, arm = _dy.effect_sizes(four, _dy.Masses(mc, mh, ma), w, rocker_rate=rocker_rate)
    least = np.asarray(model_index(j, band, link, weight, arm, arms))
    index = least if forced is None else np.asarray(model_index(j, band, link, weight, arm, arms, forced))
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
        least = int(least[0])
    return EnergyModel(*out, forced=forced is not None, least=least)
