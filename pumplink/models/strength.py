"""Will the parts last? Pin bearing pressure and the fatigue of the crank and the handle
(docs/workshop.md §2).

The loads come from :mod:`pumplink.models.joints`; here they meet the parts a workshop builds:

* a **pin** of diameter d bearing on a wall or bushing of width w: the mean (projected) bearing
  pressure p = F / (d w), against the allowable pressure of a moving steel joint under alternating
  load;
* a **round tube** (outer diameter D, wall s; a solid bar is s = D/2) in bending and tension: the
  stress on its two extreme fibres sigma = N / A +- M / Z over the cycle, their amplitude and mean,
  and the fatigue safety factor of the modified Goodman line 1/n = sigma_a / S_e + sigma_m / S_ut,
  with the endurance limit S_e of Marin's equation (Shigley, "Mechanical Engineering Design",
  §6-7 and §6-9; the Goodman line §6-12).

Constants carry their source on the line above them.  Pure functions on floats / numpy arrays;
SI units (Pa, m, N, N m).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

# ----------------------------------------------------------------------------- pins
#: Allowable bearing pressure [Pa] of a pin in a **movable** joint of steel grade 37/42 (S235/S275)
#: under **alternating** load, 12 MPa (repeated 24 MPa, static 30 MPa): Autodesk Inventor Engineer's
#: Handbook, "Calculating Allowable Stresses for Clevis Pin Joints" (metric table; 1 700 / 3 400 /
#: 4 260 psi in the English one).  The pump's joints turn under a force that reverses every stroke.
PIN_PRESSURE_ALTERNATING = 12e6
#: The same table's movable joint under repeated (pulsating, one-sided) load [Pa].
PIN_PRESSURE_REPEATED = 24e6
#: The same table's movable joint under static load [Pa]: beyond it even a slowly turning joint
#: galls; the verdict's proposed fail level (docs/workshop.md §2).
PIN_PRESSURE_STATIC = 30e6


def bearing_pressure(force, pin_diameter, width):
    """Mean bearing pressure p = F / (d w) [Pa] of a pin on its bore (projected area d w).

    Parameters
    ----------
    force : joint force [N] (its magnitude is used);  pin_diameter : d [m];
    width : w, the length of bore the pin bears on [m] (a bushing's length, or the sum of the two
        walls of a tube the pin passes through).
    """
    return np.abs(np.asarray(force, float)) / (np.asarray(pin_diameter, float) * width)


# ----------------------------------------------------------------------------- tubes
#: Least tensile strength [Pa] of S235 (EN 10025-2 Table 7 and EN 10219-1 for S235JRH hollow
#: sections: Rm 360-510 MPa below 3 mm and up to 100 mm).
ULTIMATE_S235 = 360e6
#: Marin's surface factor k_a = a S_ut^b for a hot-rolled surface, S_ut in MPa: a = 57.7,
#: b = -0.718 (Shigley, Table 6-2).  As-rolled or welded tube is not machined.
SURFACE_HOT_ROLLED = (57.7, -0.718)
#: Marin's reliability factor k_e at 99 % (Shigley §6-9, reliability-factor table): 0.814.
RELIABILITY_99 = 0.814
#: Equivalent diameter of a round section in non-rotating bending, d_e = 0.370 D (Shigley §6-9, size factor);
#: for a tube whose wall is thicker than 0.05 D/2 the 95 %-stressed area is the solid bar's.
NON_ROTATING_DIAMETER = 0.370


@dataclass(frozen=True)
class Section:
    """Area [m^2] and elastic section modulus Z = I / (D/2) [m^3] of a round tube."""

    area: np.ndarray | float
    modulus: np.ndarray | float


def tube_section(outer_diameter, wall) -> Section:
    """A round tube of outer diameter D and wall s [m] (s = D/2: a solid bar).

    A = pi (D^2 - d^2) / 4,  Z = pi (D^4 - d^4) / (32 D),  d = D - 2 s.
    """
    big = np.asarray(outer_diameter, float)
    small = big - 2.0 * np.asarray(wall, float)
    return Section(np.pi / 4.0 * (big * big - small * small), np.pi * (big**4 - small**4) / (32.0 * big))


def fibre_stresses(moment, axial, section: Section):
    """Normal stress on the two extreme fibres [Pa], shape (2, ...): N / A + M / Z and N / A - M / Z.

    Parameters
    ----------
    moment : bending moment M [N m];  axial : axial force N [N], tension positive.
    """
    m = np.asarray(moment, float) / section.modulus
    n = np.asarray(axial, float) / section.area
    return np.stack([n + m, n - m])


def endurance_limit(
    ultimate,
    outer_diameter,
    notch_factor=1.0,
    surface=SURFACE_HOT_ROLLED,
    reliability=RELIABILITY_99,
):
    """Endurance limit of the part in fully reversed bending [Pa] (Marin's equation, Shigley §6-9).

        S_e' = 0.5 S_ut                        (Shigley §6-7, S_ut <= 1400 MPa)
        k_a = a S_ut^b                         (S_ut in MPa; hot-rolled a = 57.7, b = -0.718: Table 6-2)
        k_b = 1.24 d_e^-0.107, d_e = 0.370 D    (d_e in mm, 2.79-51 mm; 1.51 d_e^-0.157 above)
        k_c = 1 (bending),  k_d = 1 (room temperature),  k_e = 0.814 (99 % reliability)
        S_e = k_a k_b k_c k_d k_e S_e' / K_f

    The fatigue notch factor K_f (a hole or a weld toe at the section) divides the limit instead of
    multiplying the stress, which is the same for the safety factor.

    Parameters
    ----------
    ultimate : S_ut [Pa];  outer_diameter : D [m];  notch_factor : K_f [-] (1: a plain tube).
    surface : (a, b) of k_a;  reliability : k_e.
    """
    sut = np.asarray(ultimate, float) / 1e6  # MPa, as Marin's fits are written
    ka = surface[0] * sut ** surface[1]  # surface factor k_a
    de = NON_ROTATING_DIAMETER * np.asarray(outer_diameter, float) * 1e3  # mm
    kb = np.where(de <= 51.0, 1.24 * de**-0.107, 1.51 * de**-0.157)  # size factor k_b
    kb = np.minimum(kb, 1.0)
    return np.minimum(ka, 1.0) * kb * reliability * 0.5 * sut * 1e6 / notch_factor  # Marin's equation


@dataclass(frozen=True)
class Fatigue:
    """Fatigue of one section over the cycle (the worse of its two extreme fibres).

    Attributes
    ----------
    amplitude : sigma_a = (max - min) / 2 [Pa];  mean : sigma_m = (max + min) / 2 [Pa];
    largest : the largest |stress| [Pa];  safety : n of the modified Goodman line [-].
    """

    amplitude: np.ndarray | float
    mean: np.ndarray | float
    largest: np.ndarray | float
    safety: np.ndarray | float


def fatigue(moment, axial, section: Section, endurance, ultimate, axis=-1) -> Fatigue:
    """Fatigue safety factor of a section loaded by M(t), N(t) over one cycle (sampled along ``axis``).

    On each extreme fibre sigma(t) = N/A +- M/Z; its amplitude and mean over the cycle enter the
    modified Goodman line (Shigley §6-12): n = 1 / (sigma_a / S_e + sigma_m / S_ut) for a
    tensile mean; for a compressive mean the amplitude alone, n = S_e / sigma_a (Shigley §6-12: a
    compressive mean does not lower the fatigue strength).  The worse fibre decides.

    Parameters
    ----------
    moment, axial : M [N m] and N [N] over the cycle;  section : :func:`tube_section`;
    endurance : S_e [Pa] (:func:`endurance_limit`);  ultimate : S_ut [Pa];
    axis : the axis of the cycle in ``moment`` and ``axial``.
    """
    sig = fibre_stresses(moment, axial, section)  # (2, ...)
    ax = axis if axis < 0 else axis + 1
    hi, lo = sig.max(axis=ax), sig.min(axis=ax)
    amp, mean = 0.5 * (hi - lo), 0.5 * (hi + lo)
    with np.errstate(divide="ignore"):
        load = amp / endurance + np.maximum(mean, 0.0) / ultimate
        n = 1.0 / load
    k = np.argmin(n, axis=0)  # the worse fibre
    pick = np.take_along_axis
    out = [pick(v, np.expand_dims(k, 0), 0)[0] for v in (amp, mean, n)]
    largest = np.abs(sig).max(axis=(0, ax))

    def scalar(v):
        return v.item() if np.ndim(v) == 0 else v

    return Fatigue(scalar(out[0]), scalar(out[1]), scalar(largest), scalar(out[2]))
