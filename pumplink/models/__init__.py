"""Force models that can decide the verdict: one signature, one registry.

A model answers one question for arrays of designs: *what peak operator force does this design
need?*  Every model has the signature ``peak_force(fourbar, dead_centre_extended,
dead_centre_folded, wheel_torque, conditions) -> [N]`` and says which operating conditions it
reads (``needs``).  :func:`choose_model` picks the least model the spec supports (docs/models.md
§3): the flywheel model when the spec gives the wheel's inertia, else the quasi-static model with
a dead band.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from pumplink.models import flywheel, quasi_static

#: Registry keys (the ``model`` of reports is :attr:`Model.label`).
QUASI_STATIC = "quasi-static"
FLYWHEEL = "flywheel"


@dataclass(frozen=True)
class Conditions:
    """Operating conditions of designs (floats or arrays over designs, SI units).

    Attributes
    ----------
    speed : mean wheel speed ω̄ [rad/s].
    dead_band : crank angle each side of a dead centre left to the wheel's inertia [rad].
    inertia : J about the wheel axle [kg m^2]; NaN where not given.
    speed_fluctuation : δ = (ωmax − ωmin)/ω̄ allowed [-].
    """

    speed: np.ndarray | float
    dead_band: np.ndarray | float
    inertia: np.ndarray | float = np.nan
    speed_fluctuation: np.ndarray | float = np.nan


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
    band = flywheel.energy_band(conditions.inertia, conditions.speed, conditions.speed_fluctuation)
    return flywheel.least_peak_force(fourbar, dead_centre_extended, dead_centre_folded, wheel_torque, band)


MODELS: dict[str, Model] = {
    QUASI_STATIC: Model(
        QUASI_STATIC,
        "quasi-static + dead band",
        _quasi_static_peak,
        ("dead_band",),
        "Eq. (3) of the pump paper; infinite at the dead centres, so the peak is taken outside "
        "±dead_band of them; blind to speed",
    ),
    FLYWHEEL: Model(
        FLYWHEEL,
        "flywheel",
        _flywheel_peak,
        ("inertia", "speed", "speed_fluctuation"),
        "the wheel's inertia carries the dead centres: least peak force for a periodic motion with "
        "speed fluctuation within δ at the mean speed; link inertia neglected",
    ),
}


def choose_model(inertia_given: bool) -> Model:
    """The least model the spec supports: flywheel when it gives inertia, else quasi-static."""
    return MODELS[FLYWHEEL if inertia_given else QUASI_STATIC]
