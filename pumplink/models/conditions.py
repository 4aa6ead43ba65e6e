"""What a force model is given besides the linkage: the moving masses and the operating
conditions (floats or arrays over designs, SI units)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class Masses:
    """Moving masses of the linkage (floats or arrays over designs) [kg].

    Attributes
    ----------
    coupler : mass of the coupler, a uniform bar from the crank pin A to the joint B.
    handle : mass of the handle, a uniform bar from the rocker pivot O4 along the rocker, of
        length max(H, rocker).
    grip : point mass at the grip (the operator's hands and forearms), 0 for the hand force.
    """

    coupler: np.ndarray | float = 0.0
    handle: np.ndarray | float = 0.0
    grip: np.ndarray | float = 0.0


@dataclass(frozen=True)
class Conditions:
    """Operating conditions of designs (floats or arrays over designs, SI units).

    Attributes
    ----------
    speed : mean wheel speed ω̄ [rad/s].
    masses : moving link masses and the point mass at the grip [kg] (full dynamics only).
    dead_band : crank angle each side of a dead centre left to the wheel's inertia [rad].
    inertia : J about the wheel axle [kg m^2]; NaN where not given.
    speed_fluctuation : δ = (ωmax − ωmin)/ω̄ allowed [-].
    """

    speed: np.ndarray | float
    dead_band: np.ndarray | float
    inertia: np.ndarray | float = np.nan
    speed_fluctuation: np.ndarray | float = np.nan
    masses: Masses = Masses()  # coupler, handle, grip [kg] (full dynamics)
