"""Force models of a single-acting piston pump driven through a crank-slider by a hand crank.

The scene (docs/piston-pump.md): the operator turns a handle crank of radius R fixed to the
crank-slider's crank (r, rod l, offset e; conventions of docs/mechanisms.md §1).  The piston
lifts the water column on its working stroke, against the load force

    F_load = rho g head (pi bore^2 / 4) / efficiency                                   (P.1)

and returns unloaded (single-acting).  The working stroke is the slow one: with the crank turning
counter-clockwise, towards the crank pivot for e >= 0 (ds/dt < 0), away from it for e < 0.  By
virtual work the crank torque and the operator's tangential force at the handle are

    T(t) = F_load max(0, sigma ds/dt),   F(t) = T(t) / R,   sigma = -1 (e >= 0) or +1   (P.2)

The operator drives the crank, so there is no dead centre for the operator: F is finite
everywhere and zero on the return stroke.  One revolution does the work F_load H (H the
stroke), so the mean tangential force is

    F_mean = F_load H / (2 pi R)                                                       (P.3)

Quasi-static model: the peak is F_load max(sigma ds/dt) / R, the maximum of (P.2) over the turn,
located on a scan and refined by a bracketing minimiser.

Flywheel model (the same reasoning as ``pumplink.models.flywheel``, docs/models.md §2, with the
roles of load and operator exchanged: here the load torque varies and the operator's lever arm
R is constant).  With |F| <= Fp the energy of the crank shaft (inertia J) changes as
dE/dt = F R - T(t); the path "as full as possible" pushes Fp R whenever the shaft is below the
top of the band W = J w^2 delta.  A periodic motion inside the band exists iff Fp >= F_mean and

    D(Fp) = max over arcs [a, b] of  integral_a^b (T - Fp R) dt  <=  W                    (P.4)

The integral of T over an arc of the working stroke is F_load times the slider's travel, exact
from positions; the worst arc ends where T = Fp R.  D decreases in Fp, so the least peak force
Fp* is the root of D(Fp) = W in [F_mean, quasi-static peak] (brentq), or F_mean when
D(F_mean) <= W.

Pure numpy/scipy on scalars (one design at a time); SI units, angles in radians.
"""

from __future__ import annotations

import math

import numpy as np

from pumplink.mechanisms import crank_slider as cs

#: Crank angles per revolution on which the arcs of (P.4) are scanned before refinement.
SCAN = 8192


def working_sign(offset) -> float:
    """sigma of (P.2): -1 (working stroke towards the crank pivot) for e >= 0, +1 for e < 0."""
    return -1.0 if float(offset) >= 0.0 else 1.0


def crank_torque(crank_length, rod_length, offset, load, crank_angle):
    """Load torque on the crank T(t) [N m] (Eq. P.2): load * max(0, sigma ds/dt)."""
    rate = np.asarray(cs.velocity_ratio(crank_length, rod_length, offset, crank_angle), float)
    lift = working_sign(offset) * rate
    return load * np.where(lift > 0.0, lift, 0.0)  # Eq. (P.2)


def operator_force(crank_length, rod_length, offset, load, handle, crank_angle):
    """Tangential force at the handle crank F(t) = T(t)/R [N] (Eq. P.2)."""
    return crank_torque(crank_length, rod_length, offset, load, crank_angle) / handle  # Eq. (P.2)


def mean_force(crank_length, rod_length, offset, load, handle):
    """Mean tangential force F_mean = load * H / (2 pi R) [N] (Eq. P.3)."""
    return load * float(cs.stroke(crank_length, rod_length, offset)) / (2.0 * math.pi * handle)  # Eq. (P.3)


def _grid(n=SCAN):
    return np.arange(n) * (2.0 * math.pi / n)


def quasi_static_peak(crank_length, rod_length, offset, load, handle):
    """Largest operator force over the turn [N] and its crank angle [rad] (quasi-static model)."""
    from scipy.optimize.elementwise import find_minimum

    r, rod, e = float(crank_length), float(rod_length), float(offset)
    t = _grid()
    f = operator_force(r, rod, e, load, handle, t)
    j = int(np.argmax(f))
    h = t[1] - t[0]
    res = find_minimum(
        lambda x: -operator_force(r, rod, e, load, handle, x),
        (t[j] - h, t[j], t[j] + h),
        tolerances=dict(xatol=1e-14, xrtol=1e-15),
    )
    if bool(res.success) and -float(res.f_x) >= f[j]:
        return -float(res.f_x), float(np.mod(res.x, 2.0 * math.pi))
    return float(f[j]), float(t[j])


def _load_work(r, rod, e, load, t):
    """Work done on the load from crank angle 0 to t (t in [0, 4 pi)) [J]: load times the slider's
    travel in the working direction, exact from positions (no quadrature)."""
    sigma = working_sign(e)
    ext, fold = (float(x) for x in cs.dead_centres(r, rod, e))
    # the working stroke runs between the dead centres: from ext to fold (sigma = -1, s falls)
    # or from fold to ext + 2 pi (sigma = +1, s rises), crank turning counter-clockwise
    start, end = (ext, fold) if sigma < 0 else (fold, ext + 2.0 * math.pi)
    s_start = float(cs.slider_position(r, rod, e, start))
    stroke = float(cs.stroke(r, rod, e))
    t = np.asarray(t, float)
    rev, phase = np.divmod(t - start, 2.0 * math.pi)  # phase in [0, 2 pi) after the stroke's start
    span = end - start
    inside = phase <= span
    s = np.asarray(cs.slider_position(r, rod, e, start + np.minimum(phase, span)), float)
    travel = np.where(inside, sigma * (s - s_start), stroke)
    return load * (rev * stroke + travel)


def energy_deficit(crank_length, rod_length, offset, load, handle, peak_force):
    """D(Fp) of (P.4): the largest energy the crank shaft loses over any arc with the operator
    pushing ``peak_force`` [J] (0 if it never loses)."""
    from scipy.optimize import brentq

    r, rod, e = float(crank_length), float(rod_length), float(offset)
    fr = peak_force * handle
    t = np.concatenate([_grid(), 2.0 * math.pi + _grid()])
    c = _load_work(r, rod, e, load, t) - fr * t  # integral of (T - Fp R) from 0 (P.4)
    low = np.minimum.accumulate(c)
    j = int(np.argmax(c - low))
    if c[j] - low[j] <= 0.0:
        return 0.0
    i = int(np.argmin(c[: j + 1]))
    h = t[1] - t[0]

    def slope(x):
        return float(crank_torque(r, rod, e, load, x)) - fr

    def end(k, rising):
        # the worst arc starts where T rises through Fp R and ends where it falls through it
        for lo, hi in ((t[k] - h, t[k] + h), (t[k] - 2 * h, t[k] + 2 * h)):
            a, b = slope(lo), slope(hi)
            if (a < 0 <= b) if rising else (a > 0 >= b):
                return brentq(slope, lo, hi, xtol=1e-15, rtol=1e-15)
        return float(t[k])

    a, b = end(i, True), end(j, False)
    exact = float(_load_work(r, rod, e, load, b) - _load_work(r, rod, e, load, a)) - fr * (b - a)
    return max(exact, float(c[j] - low[j]))


def least_peak_force(crank_length, rod_length, offset, load, handle, energy_band):
    """Least peak operator force Fp* for a periodic motion inside the energy band [N] (P.4).

    Parameters
    ----------
    crank_length, rod_length, offset : the crank-slider [m];  load : F_load [N];
    handle : radius R of the handle crank [m];  energy_band : W = J w^2 delta [J].
    """
    from scipy.optimize import brentq

    f_mean = mean_force(crank_length, rod_length, offset, load, handle)
    peak, _ = quasi_static_peak(crank_length, rod_length, offset, load, handle)

    def gap(fp):
        return energy_deficit(crank_length, rod_length, offset, load, handle, fp) - energy_band

    if gap(f_mean) <= 0.0:
        return f_mean
    if not energy_band > 0.0:
        return peak
    return brentq(gap, f_mean, peak, xtol=1e-12 * peak, rtol=1e-14)
