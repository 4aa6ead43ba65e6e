"""Full dynamics' scene: the links' reduced inertia and potential, their rates, and the energy band.

The flywheel scene (:mod:`pumplink.models.flywheel`) carries only the wheel's inertia J.  Here the
coupler and the handle move with their masses, the handle's weight rises and falls, and an
optional point mass at the grip stands for the operator's hands and forearms (docs/models.md §3).
The least peak force in this scene is :mod:`pumplink.models.dynamics_solver`; one design in detail
and the cadence are :mod:`pumplink.models.dynamics`.

The scene
---------
Generalised coordinate: the crank angle t (= the wheel's angle).  Kinetic and potential energy

    T = I(t) w^2 / 2,   I(t) = J + sum over moving links (m |v_G|^2 + I_G w_link^2) / w^2    (5)
    V(t) = g_n (sum of m y_G)                                                              (6)

with the coupler and the handle (the rocker extended from O4 to the grip, length max(H, rocker))
as uniform bars, the point mass at the grip, and g_n the standard gravity.  The energy balance per
crank radian (the power balance F vx - Mw w = d(T + V)/dt divided by w) still contains no w:

    dE/dt = F g(t) - Mw,   E = T + V,   g = dPx/dt                                    (7)

The speed band w in [w_bar (1 - delta/2), w_bar (1 + delta/2)] is the t-dependent band on E

    lower(t) = V + I w_lo^2 / 2  <=  E  <=  upper(t) = V + I w_hi^2 / 2                  (8)

The flywheel scene is the special case I = J, V = 0 (a constant band of width J w_bar^2 delta).

Pure functions on floats / arrays over designs; SI units, radians.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from pumplink.constants import GRAVITY
from pumplink.mechanisms.fourbar import FourBar
from pumplink.mechanisms.fourbar_kernel import alike_designs
from pumplink.models.conditions import Masses


# ----------------------------------------------------------------------------- masses
def bar_masses(lk: FourBar, mass_per_length, grip=0.0) -> Masses:
    """Coupler and handle as uniform bars of ``mass_per_length`` [kg/m]; ``grip`` [kg] at the grip."""
    return Masses(
        mass_per_length * np.asarray(lk.coupler, float),
        mass_per_length * np.maximum(lk.handle, lk.rocker),
        grip,
    )


# ----------------------------------------------------------------------------- I, I', V, V'
@dataclass(frozen=True)
class Terms:
    """Reduced inertia and potential of the links at crank angles (wheel inertia J not included).

    inertia : I - J [kg m^2];  inertia_rate : dI/dt [kg m^2/rad];  potential : V [J];
    potential_rate : dV/dt [J/rad];  grip_rate : g = dPx/dt [m/rad];  grip_x : Px [m].
    closure : the loop closure at the crank angles, for the joint forces along the same motion
        (:func:`pumplink.models.joints.joint_forces`; None unless asked for): cos t, sin t, the crank
        pin A, O4 - A, u = B - A, w = B - O4 and u x w, each (x, y) as two arrays (the values the
        joint forces compute from :func:`pumplink.mechanisms.fourbar_kernel.loop_closure`: the same
        operations).
    """

    inertia: np.ndarray
    inertia_rate: np.ndarray
    potential: np.ndarray
    potential_rate: np.ndarray
    grip_rate: np.ndarray
    grip_x: np.ndarray
    closure: tuple | None = None


def coefficients(lk: FourBar, masses: Masses) -> tuple:
    """The per-design constants of :func:`terms` (scalars, arrays over designs or their columns).

    Computed once per design and gathered with the designs (the solver evaluates the terms many
    times on a few points each): the same expressions as written out in :func:`terms`, so the same
    rounding.  Order: px, py, crank, |O4|^2 + crank^2, 2 crank, (coupler^2 - rocker^2) / 2,
    coupler^2, coupler, rocker^2, branch (the loop closure of
    :func:`pumplink.mechanisms.fourbar_kernel.loop_closure`); the coupler's mass, its moment of inertia
    about its centre, the handle's and the arms' about O4, their first moment about O4 per metre
    of the rocker, (mh + ma) py (their weight's term at the pivot's height), H / rocker and its
    negative.
    """
    px, py, c, k, r, hh = lk.pivot_x, lk.pivot_y, lk.crank, lk.coupler, lk.rocker, lk.handle
    mc, mh, ma = masses.coupler, masses.handle, masses.grip
    arm = np.maximum(hh, r)  # the handle as a bar from O4, at least the rocker's length
    hr = hh / r
    return (
        px,
        py,
        c,
        px * px + py * py + c * c,
        2.0 * c,
        0.5 * (k * k - r * r),
        k * k,
        k,
        r * r,
        lk.branch,
        mc,
        mc * k * k / 12.0,  # coupler about its centre
        mh * arm * arm / 3.0 + ma * hh * hh,  # handle and arms about O4
        (0.5 * mh * arm + ma * hh) / r,  # first moment about O4 along the rocker, per metre of w
        (mh + ma) * py,
        hr,
        -hr,
    )


#: Number of constants :func:`coefficients` returns.
COEFFICIENT_COUNT = 17


def terms_from(
    co: tuple,
    th,
    gravity,
    rates: bool = True,
    values: bool = True,
    fly_x: bool = False,
    grip: bool = True,
    lib=np,
    closure: bool = False,
    trig=None,
):
    """:func:`terms` on the constants ``co`` of :func:`coefficients` (no floating-point context).

    Returns (inertia, inertia_rate, potential, potential_rate, grip_rate, grip_x, crank_x): the
    first six as :class:`Terms` (the rates None unless ``rates``, I, V and Px None unless
    ``values``: the band's edges need no second derivatives; Px None unless ``grip`` too);
    ``crank_x`` (``fly_x``, else None) the grip's Px as :func:`pumplink.models.grip_travel.grip_position`
    computes it (its rounding), from the same loop closure.  ``lib``: the module whose cos, sin and
    sqrt are used; ``math`` on floats (``co`` and ``th`` floats) is the one-point route of
    :func:`point_terms`, the same operations in the same order, without numpy's per-call cost.
    ``closure``: an eighth value, the loop closure (:attr:`Terms.closure`);  ``trig``: (cos th,
    sin th) where known already (the same values: a cycle's angles are every design's).
    """
    plain = lib is np and not closure and trig is None
    if plain and np.ndim(th) == 1 and all(np.ndim(v) in (0, 2) for v in co):
        # designs (rows of column constants) at the same angles: those alike bit for bit (a grid's
        # variants that differ in the load or the speed) are computed once, the same values
        columns = [v[:, 0] for v in co if np.ndim(v) == 2 and np.shape(v)[1] == 1]
        first, kind = alike_designs(*columns) if columns else (None, None)
        if first is not None:
            out = _terms_from(
                [v[first] if np.ndim(v) else v for v in co], th, gravity, rates, values, fly_x, grip
            )
            return tuple(None if v is None else v.take(kind, axis=0) for v in out)
    return _terms_from(co, th, gravity, rates, values, fly_x, grip, lib, closure, trig)


def _terms_from(co, th, gravity, rates=True, values=True, fly_x=False, grip=True, lib=np, closure=False,
                trig=None):  # fmt: skip
    """The body of :func:`terms_from` (its arguments as there)."""
    px, py, c, o2, c2, hkr, kk, k, rr, branch, mc, ic, i4, lever, mpy, hr, nhr = co
    cs, sn = (lib.cos(th), lib.sin(th)) if trig is None else trig
    # the loop closure of pumplink.mechanisms.fourbar_kernel.loop_closure (t, q), written out
    p1 = cs * px + sn * py
    e2 = o2 - c2 * p1
    t = 0.5 + hkr / e2
    e = lib.sqrt(e2)
    ek = e + k
    e_k = (e2 - kk) / ek
    # ek * ek, not ek**2: on arrays numpy squares (correctly rounded), on floats and numpy scalars
    # ** calls the C library's pow, 1 ulp off now and then; the one-point route must match the arrays
    q = branch * (lib.sqrt((rr - e_k * e_k) * (ek * ek - rr)) / (2.0 * e2))
    ccs, csn = c * cs, c * sn  # the crank pin A
    dx, dy = px - ccs, py - csn  # O4 - A
    tdx, qdy = t * dx, q * dy
    ux, uy = tdx - qdy, t * dy + q * dx  # B - A (Eq. (6) of pumplink.mechanisms.fourbar)
    wx, wy = ux - dx, uy - dy  # B - O4
    den = ux * wy - uy * wx  # u x w
    inv = 1.0 / den
    h3 = (csn * wx - ccs * wy) * inv  # first derivative of the loop closure
    h4 = (csn * ux - ccs * uy) * inv
    h33, h44 = h3 * h3, h4 * h4
    # coupler centre A + u/2: velocity coefficients
    half3 = 0.5 * h3
    ncsn = -csn
    vx = ncsn - half3 * uy
    vy = ccs + half3 * ux
    inertia = rate = potential = potential_rate = grip_rate = grip_x = crank_x = None
    if rates:
        h33ux, h33uy = h33 * ux, h33 * uy
        rx = ccs + h33ux - h44 * wx
        ry = csn + h33uy - h44 * wy
        d3 = (rx * wx + ry * wy) * inv  # second derivative
        d4 = (rx * ux + ry * uy) * inv
        ax = -ccs - 0.5 * (d3 * uy + h33ux)  # the coupler centre's acceleration coefficients
        ay = ncsn + 0.5 * (d3 * ux - h33uy)
        rate = 2.0 * (mc * (vx * ax + vy * ay) + ic * h3 * d3 + i4 * h4 * d4)
        potential_rate = gravity * (mc * vy + lever * h4 * wx)
        grip_rate = nhr * h4 * wy
    if values:
        inertia = mc * (vx * vx + vy * vy) + ic * h33 + i4 * h44  # Eq. (5)
        potential = gravity * (mc * (csn + 0.5 * uy) + mpy + lever * wy)  # Eq. (6)
        if grip:
            grip_x = px + hr * wx
    if fly_x:
        crank_x = px + hr * ((ccs + tdx) - qdy - px)
    if closure:
        loop = (cs, sn, ccs, csn, dx, dy, ux, uy, wx, wy, den)
        return inertia, rate, potential, potential_rate, grip_rate, grip_x, crank_x, loop
    return inertia, rate, potential, potential_rate, grip_rate, grip_x, crank_x


def terms(
    lk: FourBar, crank_angle, masses: Masses, gravity=GRAVITY, rates_only: bool = False, closure: bool = False
) -> Terms:
    """I(t) - J, I'(t), V(t), V'(t) and g(t) of Eq. (5)-(7) (docs/models.md §3a).

    With u = B - A (the coupler) and w = B - O4 (the rocker), the loop closure A + u = O4 + w
    differentiated once and twice (unit crank speed, no crank acceleration) gives the velocity
    coefficients h3 = dt3/dt, h4 = dt4/dt and their derivatives d3, d4 from one 2 x 2 system each:

        h3 = (V . w) / S,  h4 = (V . u) / S,   V = -dA/dt,           S = u x w
        d3 = (R . w) / S,  d4 = (R . u) / S,   R = -d2A/dt2 + h3^2 u - h4^2 w

    (S = coupler * rocker * sin of the transmission angle: never zero for a crank-rocker; no instant
    centres).  ``rates_only``: I - J, V and Px are left None (the extremum refinement needs only I',
    V' and g);  ``closure``: the loop closure too (:attr:`Terms.closure`).
    """
    th = np.asarray(crank_angle, float)
    with np.errstate(all="ignore"):
        out = terms_from(coefficients(lk, masses), th, gravity, values=not rates_only, closure=closure)
    return Terms(*out[:6], out[7] if closure else None)


def point_terms(lk: FourBar, masses: Masses, gravity=GRAVITY):
    """:func:`terms` of one design at one crank angle at a time, for an ODE's right-hand side.

    Returns ``at(crank_angle, rates=True, values=True, fly_x=False)`` giving the floats (I - J, I',
    V, V', g, Px, crank_x) of :func:`terms_from` with those flags (None where they leave a value out).
    The per-design constants are computed once; each call runs :func:`terms_from` on floats with
    ``math`` (the same operations in the same order as on arrays: ~4 us a call instead of ~30 us
    for :func:`terms` on one angle).
    Where a float operation would raise (a square root of a negative number, a division by zero:
    a state the linkage cannot take) the call falls back to the numpy route, NaN/inf as there.
    """
    import math

    co = tuple(float(v) for v in coefficients(lk, masses))
    gravity = float(gravity)

    def at(crank_angle, rates: bool = True, values: bool = True, fly_x: bool = False):
        th = float(crank_angle)
        try:
            return terms_from(co, th, gravity, rates, values, fly_x, lib=math)
        except (ValueError, ZeroDivisionError, OverflowError):
            with np.errstate(all="ignore"):
                out = terms_from(co, np.float64(th), gravity, rates, values, fly_x)
            return tuple(None if v is None else float(v) for v in out)

    return at


def reduced_inertia(lk: FourBar, crank_angle, inertia, masses: Masses):
    """I(t) and dI/dt [kg m^2, kg m^2/rad] of Eq. (5): the wheel's J plus the links'."""
    tm = terms(lk, crank_angle, masses)
    return inertia + tm.inertia, tm.inertia_rate


def potential(lk: FourBar, crank_angle, masses: Masses, gravity=GRAVITY):
    """V(t) and dV/dt [J, J/rad] of Eq. (6), zero at the wheel axle's height."""
    tm = terms(lk, crank_angle, masses, gravity)
    return tm.potential, tm.potential_rate


def speed_limits(mean_speed, speed_fluctuation):
    """w_lo = w_bar (1 - delta/2), w_hi = w_bar (1 + delta/2) [rad/s]."""
    w = np.asarray(mean_speed, float)
    return w * (1.0 - 0.5 * speed_fluctuation), w * (1.0 + 0.5 * speed_fluctuation)


def energy_band(
    lk: FourBar, crank_angle, inertia, masses: Masses, mean_speed, speed_fluctuation, gravity=GRAVITY
):
    """The t-dependent band on E = T + V, Eq. (8): (lower, upper) [J]."""
    tm = terms(lk, crank_angle, masses, gravity)
    lo, hi = speed_limits(mean_speed, speed_fluctuation)
    i = inertia + tm.inertia
    return tm.potential + 0.5 * i * lo * lo, tm.potential + 0.5 * i * hi * hi
