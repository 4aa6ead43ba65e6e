"""How long the pins and bushes last, and how much a pump turns (docs/workshop.md §5).

Archard's law in its depth form: a surface sliding a distance s under a mean pressure p wears to
a depth

    h = k p s,   k = K / H                                                          (L.1)

with K the dimensionless wear coefficient of the material pair and H the hardness of the surface
worn [Pa] (J. F. Archard, W. Hirst, "The wear of metals under unlubricated conditions", Proc. R.
Soc. Lond. A 236 (1956) 397-410; their pin-on-ring values as tabulated by Hutchings and Shipway,
*Tribology*, 2nd ed., 2017, Table 5.2: :data:`PAIRS`).

Per crank turn the crank pin A turns a whole turn in the coupler's bush, so it slides pi d (d the
pin's diameter); B and O4 swing through less (the handle's and the coupler's swings), so pi d is
the largest sliding of the joints.  Taken at the largest bearing pressure of the joints
(the verdict's pin check, the peak over the turn), the wear per turn

    h_turn = n k p_max pi d                                                          (L.2)

is an upper bound for every pin (n: the surfaces that wear, 2 for steel on steel, 1 for a
polyethylene bush on a steel pin).  The play a joint may open, the wear allowance, is worn after
``allowance / h_turn`` turns.

The use: a pump serving P people of V litres each a day turns P V / v_turn times a day (v_turn
the water a crank turn delivers), but no more than its hours a day at the design cadence allow
(W.6 read backwards, docs/water.md §5); without P it turns for its hours a day.

USAID's laboratory tests of 15 hand pumps (B. S. Dixit, P. W. Potts, *Laboratory testing of
hand-operated water pumps*, USAID, 1984) ran them for 6 million cycles: a pump whose pins outlast
6 million turns (:data:`ENDURANCE_TURNS`) has the life their hardened pins showed.

Pure functions on floats / arrays over designs; SI units.
"""

from __future__ import annotations

import math

import numpy as np

#: The material pairs a pin may turn in (``[parts] bush``): the dimensionless wear coefficient K,
#: the worn surface's hardness H [Pa] (Vickers, kgf/mm^2 x 9.807 MPa) and the surfaces that wear.
#: Archard and Hirst (1956), dry pin-on-ring, as tabulated by Hutchings and Shipway (2017), Table 5.2:
#: mild steel on mild steel K = 7e-3, 186 HV; polyethylene on tool steel K = 1.3e-7, 17 HV.
PAIRS = {
    "steel": (7e-3, 186 * 9.807e6, 2),
    "polyethylene": (1.3e-7, 17 * 9.807e6, 1),
}
#: The cycles of USAID's endurance tests of hand pumps (Dixit and Potts, 1984): hardened pins and
#: bushings showed negligible wear after 6 million cycles without lubrication.
ENDURANCE_TURNS = 6.0e6
#: Days in a year, for turns a year.
DAYS_PER_YEAR = 365.0


def wear_rate(bush: str) -> tuple[float, int]:
    """(k = K / H [m^2/N], surfaces that wear) of a ``[parts] bush`` material pair (:data:`PAIRS`)."""
    k, hardness, surfaces = PAIRS[bush]
    return k / hardness, surfaces


def wear_per_turn(pressure, pin_diameter, rate, surfaces):
    """The play a joint opens per crank turn [m], Eq. (L.2): ``surfaces`` x ``rate`` [m^2/N] x the
    bearing pressure [Pa] x the crank pin's sliding pi d [m]."""
    return surfaces * rate * pressure * math.pi * np.asarray(pin_diameter, float)


def turns_per_day(speed, hours_per_day, people=np.nan, litres_per_person_day=np.nan, water_per_turn=np.nan):
    """Crank turns a day: ``people`` x ``litres_per_person_day`` [l] over the water a turn delivers
    [m^3], at most (and without people) ``hours_per_day`` [h] at ``speed`` [rad/s] (NaN people:
    the hours alone)."""
    most = np.asarray(hours_per_day, float) * 3600.0 * np.asarray(speed, float) / (2.0 * math.pi)
    with np.errstate(invalid="ignore", divide="ignore"):
        needed = np.asarray(people, float) * np.asarray(litres_per_person_day, float) * 1e-3 / water_per_turn
    return np.where(np.isnan(needed), most, np.minimum(needed, most))


def column_fill_turns(head, wheel_radius, volumetric_efficiency):
    """Crank turns before water reaches the spout from an empty rising main [-] (docs/water.md §5):
    the column rises by eta_v 2 pi rw a turn (the swept volume less the leakage), so head / (2 pi
    rw eta_v) turns fill it."""
    return np.asarray(head, float) / (2.0 * math.pi * np.asarray(wheel_radius, float) * volumetric_efficiency)


__all__ = [
    "DAYS_PER_YEAR",
    "ENDURANCE_TURNS",
    "PAIRS",
    "column_fill_turns",
    "turns_per_day",
    "wear_per_turn",
    "wear_rate",
]
