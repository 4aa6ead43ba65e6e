"""Force models that can decide the verdict: one signature, one registry.

A model answers one question for arrays of designs: *what peak operator force does this design
need?*  Every model has the signature ``peak_force(fourbar, dead_centre_extended,
dead_centre_folded, wheel_torque, conditions) -> [N]`` and says which operating conditions it
reads (``needs``).  :func:`model_index` picks the least model that is enough (docs/models.md
§3): without the wheel's inertia the quasi-static model with a dead band; with it the flywheel
model, unless the links' kinetic energy or weight (or the arms', when they are in the verdict) is
more than 10 % of its energy band, and then full dynamics.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from pumplink.constants import MODEL_WORDS
from pumplink.models import quasi_static
from pumplink.models.conditions import Conditions, Masses  # noqa: F401 (with the registry: what a model is given)

#: Registry keys (the ``model`` of reports is :attr:`Model.label`).
QUASI_STATIC = "quasi-static"
FLYWHEEL = "flywheel"
DYNAMICS = "dynamics"


@dataclass(frozen=True)
class Model:
    """One force model: its name in reports, its peak force and what it reads."""

    key: str
    label: str
    peak_force: Callable
    needs: tuple[str, ...]
    summary: str


def _quasi_static_peak(
    fourbar, dead_centre_extended, dead_centre_folded, wheel_torque, conditions: Conditions
):
    """Exact peak of the quasi-static force outside the dead bands [N] (docs/models.md §1)."""
    return quasi_static.dead_band_peak_force(
        fourbar, dead_centre_extended, dead_centre_folded, conditions.dead_band, wheel_torque
    )[0]


def _flywheel_peak(fourbar, dead_centre_extended, dead_centre_folded, wheel_torque, conditions: Conditions):
    """Least peak force for a periodic motion inside the energy band [N] (docs/models.md §2, Eq. (4))."""
    # loaded when first needed: a start-up cost otherwise
    from pumplink.models import flywheel, flywheel_solver

    band = flywheel.energy_band(conditions.inertia, conditions.speed, conditions.speed_fluctuation)
    return flywheel_solver.least_peak_force(
        fourbar, dead_centre_extended, dead_centre_folded, wheel_torque, band
    )


def _dynamics_peak(fourbar, dead_centre_extended, dead_centre_folded, wheel_torque, conditions: Conditions):
    """Least peak force with link masses, weight and arms [N] (docs/models.md §3, (C1)-(C2))."""
    from pumplink.models import dynamics_solver  # loaded when first needed: a start-up cost otherwise

    return dynamics_solver.least_peak_force(
        fourbar,
        dead_centre_extended,
        dead_centre_folded,
        wheel_torque,
        conditions.inertia,
        conditions.masses,
        conditions.speed,
        conditions.speed_fluctuation,
    )


MODELS: dict[str, Model] = {
    QUASI_STATIC: Model(
        QUASI_STATIC,
        MODEL_WORDS[QUASI_STATIC],
        _quasi_static_peak,
        ("dead_band",),
        "Eq. (3) of the pump paper; infinite at the dead centres, so the peak is taken outside "
        "±dead_band of them; blind to speed",
    ),
    FLYWHEEL: Model(
        FLYWHEEL,
        MODEL_WORDS[FLYWHEEL],
        _flywheel_peak,
        ("inertia", "speed", "speed_fluctuation"),
        "the wheel's inertia carries the dead centres: least peak force for a periodic motion with "
        "speed fluctuation within δ at the mean speed; link inertia neglected",
    ),
    DYNAMICS: Model(
        DYNAMICS,
        MODEL_WORDS[DYNAMICS],
        _dynamics_peak,
        ("inertia", "speed", "speed_fluctuation", "masses"),
        "the wheel, the coupler and the handle as masses, their weight and (for the effort) the "
        "operator's arms: least peak force for a periodic motion with speed fluctuation within δ; "
        "joint friction and posture left out",
    ),
}


#: The models in the order of :func:`model_index` (the least first).
ORDER = (QUASI_STATIC, FLYWHEEL, DYNAMICS)


def model_index(inertia, band, link_energy, link_weight, arm_energy, arms_in_verdict=False, forced=None):
    """The least model that is enough, per design (docs/models.md §3): 0 quasi-static, 1 flywheel,
    2 full dynamics (an index into :data:`ORDER`).

    Without the wheel's inertia (NaN) only the quasi-static model with a dead band can answer.
    With it the flywheel is enough when every effect it leaves out is at most
    ``LINK_ENERGY_LIMIT`` (10 %) of its energy band W = J w^2 delta: the links' largest kinetic
    energy, the range of their potential energy, and (when the arms are in the verdict) the arms'
    largest kinetic energy; else full dynamics, which includes them all.  ``forced``, a key of
    :data:`MODELS`, overrides the choice where the inertia is given (the quasi-static model
    everywhere).  Floats or arrays over designs [J].
    """
    from pumplink.constants import LINK_ENERGY_LIMIT

    given = ~np.isnan(np.asarray(inertia, float))
    with np.errstate(invalid="ignore"):
        cap = LINK_ENERGY_LIMIT * np.asarray(band, float)
        # an effect not known (NaN, an infeasible design) does not call for more model
        big = (link_energy > cap) | (link_weight > cap) | (np.asarray(arms_in_verdict) & (arm_energy > cap))
    small = ~big
    index = np.where(small, 1, 2) if forced is None else np.full(np.shape(small), ORDER.index(forced))
    out = np.where(given, index, 0) if forced != QUASI_STATIC else np.zeros(np.shape(small), int)
    return out.item() if np.ndim(out) == 0 else out


def choose_model(inertia_given: bool, links_negligible: bool = True) -> Model:
    """The least model that is enough for one design: quasi-static without inertia; with it the
    flywheel when the links' (and, in the verdict, the arms') energy is negligible, else full
    dynamics (:func:`model_index`, docs/models.md §3)."""
    if not inertia_given:
        return MODELS[QUASI_STATIC]
    return MODELS[FLYWHEEL if links_negligible else DYNAMICS]
