"""Independent high-precision reference for the pump linkage (test support, not product code).

Derived from docs/physics.md only, on purpose by a different route from ``pumplink.mechanisms.fourbar``
(which intersects two circles as a vector construction and differentiates by the rigid
coupler): here the rocker angle theta4 is solved from the loop closure in Freudenstein form
and its rate by implicit differentiation of that closure, all in mpmath with 50 digits.

Coordinates (docs/physics.md): origin at the wheel axle O2, x horizontal, y up, angles CCW from +x;
rocker pivot O4 = (-(L1 + b/2), -D1); crank end A = crank (cos t2, sin t2);
coupler-rocker joint B = O4 + rocker (cos t4, sin t4); grip P = O4 + handle (cos t4, sin t4).

Loop closure.  With d = O4 - A, |B - A| = coupler reads |d + rocker u|^2 = coupler^2, u the rocker
direction, i.e.

    d . u = (coupler^2 - rocker^2 - |d|^2) / (2 rocker) =: C
    t4 = atan2(d_y, d_x) + sigma * acos(C / |d|),        sigma = +-1 (assembly branch).

sigma is constant along a branch as long as the coupler and rocker never become collinear
(acos argument never +-1), which holds for a crank-rocker that is not a change-point linkage.
The pump's branch is the one whose rocker lies on the counter-clockwise side of the frame line
O4->O2, i.e. psi = t4 - atan2(D1, L1 + b/2) in (0, pi) (the other branch is its mirror image
in the frame line, with psi in (-pi, 0)).

Rate: g(t2, t4) = |B(t4) - A(t2)|^2 - coupler^2 = 0 gives
dt4/dt2 = ((B - A) . A') / ((B - A) . B'),  A' = crank (-sin t2, cos t2),
B' = rocker (-sin t4, cos t4).  It vanishes exactly where B - A is parallel to the crank: the
dead centres.  Grip: Px = O4x + handle cos t4, dPx/dt2 = -handle sin t4 dt4/dt2.

Force by virtual work (docs/physics.md): Fh = Mw / (dPx/dt2).

Synthesis (Eq. 2 of the pump paper as restated in docs/physics.md): alpha = atan2(D1, L1 + b/2) is
the direction of the frame line O4->O2, psi1 = 90 deg + swing/2 - alpha (rocker at
90 + swing/2), psi2 = 90 deg - swing/2 - alpha; d_i^2 = frame^2 + rocker^2 -
2 frame rocker cos psi_i (computed directly: at 50 digits the cancellation is harmless);
crank = (d1 - d2)/2, coupler = (d1 + d2)/2.

Dead centres: roots of dt4/dt2 = 0 (the numerator (B - A) . A'), bracketed by a sign-change scan
and polished with ``mpmath.findroot``.

A float64 numpy twin of the same formulas (``sweep_*``) is provided for dense sweeps where 50
digits would be too slow; it is still independent of pumplink's code.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import mpmath
import numpy as np
from hypothesis import strategies as st
from mpmath import mp, mpf

DPS = 50
#: Every reference function runs at DPS digits (decorator); the test process also works at DPS
#: by default so that arithmetic on returned mpf values in the tests keeps the precision.
workdps = mp.workdps(DPS)
mp.dps = DPS


def _mpf(x):
    """mpf of a float taken exactly (no decimal rounding), or an mpf/int passed through."""
    return mpf(float(x)) if isinstance(x, (float, np.floating)) else mpf(x)


@dataclass(frozen=True)
class RefLinkage:
    """A pump four-bar at 50 digits (all fields mpf) plus its assembly branch sigma."""

    ox: mpf
    oy: mpf
    crank: mpf
    coupler: mpf
    rocker: mpf
    handle: mpf
    alpha: mpf  # direction of the frame line O4 -> O2 [rad]
    sigma: int  # +1 / -1, see module docstring

    def floats(self) -> dict:
        return {k: float(getattr(self, k)) for k in ("ox", "oy", "crank", "coupler", "rocker", "handle")}


@workdps
def make_linkage(L1, D1, b, rocker, handle, crank, coupler, sigma=None) -> RefLinkage:
    """Build a reference linkage from spec-level parameters (floats are taken exactly).

    ``sigma=None`` picks the pump's assembly branch (rocker CCW of the frame line O4->O2);
    raises ValueError if no single branch qualifies (not a crank-rocker on that side).
    """
    L1, D1, b, rocker, handle, crank, coupler = map(_mpf, (L1, D1, b, rocker, handle, crank, coupler))
    reach = L1 + b / 2
    alpha = mpmath.atan2(D1, reach)
    if sigma is not None:
        return RefLinkage(-reach, -D1, crank, coupler, rocker, handle, alpha, sigma)
    good = []
    for s in (1, -1):
        cand = RefLinkage(-reach, -D1, crank, coupler, rocker, handle, alpha, s)
        psi = _wrap(rocker_angle(cand, mpf(0)) - alpha)
        if 0 < psi < mp.pi:
            good.append(cand)
    if len(good) != 1:
        raise ValueError(
            f"no unique assembly branch with the rocker CCW of the frame line ({len(good)} found)"
        )
    return good[0]


def _wrap(a):
    """Angle wrapped to (-pi, pi]."""
    a = mpmath.fmod(a, 2 * mp.pi)
    if a > mp.pi:
        a -= 2 * mp.pi
    elif a <= -mp.pi:
        a += 2 * mp.pi
    return a


@workdps
def synthesis(L1, D1, b, rocker, swing):
    """Eq. (2) at 50 digits: dict of frame, alpha, psi1, psi2, d1, d2, crank, coupler (mpf).

    Returned for any input (the closed form does not care whether the result is a pump linkage).
    """
    L1, D1, b, rocker, swing = map(_mpf, (L1, D1, b, rocker, swing))
    reach = L1 + b / 2
    frame = mpmath.sqrt(reach**2 + D1**2)  # Eq. (1) as read in docs/physics.md
    alpha = mpmath.atan2(D1, reach)
    psi1 = mp.pi / 2 + swing / 2 - alpha
    psi2 = mp.pi / 2 - swing / 2 - alpha
    d1 = mpmath.sqrt(frame**2 + rocker**2 - 2 * frame * rocker * mpmath.cos(psi1))
    d2 = mpmath.sqrt(frame**2 + rocker**2 - 2 * frame * rocker * mpmath.cos(psi2))
    return dict(
        frame=frame,
        alpha=alpha,
        psi1=psi1,
        psi2=psi2,
        d1=d1,
        d2=d2,
        crank=(d1 - d2) / 2,
        coupler=(d1 + d2) / 2,
    )


def _crank_point(lk, t2):
    return lk.crank * mpmath.cos(t2), lk.crank * mpmath.sin(t2)


@workdps
def rocker_angle(lk: RefLinkage, t2):
    """Rocker angle t4 [rad] in (-pi, pi] at crank angle t2 (Freudenstein form of the closure)."""
    t2 = _mpf(t2)
    ax, ay = _crank_point(lk, t2)
    dx, dy = lk.ox - ax, lk.oy - ay
    dn = mpmath.sqrt(dx * dx + dy * dy)
    c = (lk.coupler**2 - lk.rocker**2 - dn * dn) / (2 * lk.rocker)
    arg = c / dn
    if abs(arg) > 1:
        raise ValueError("linkage cannot be assembled at this crank angle")
    return _wrap(mpmath.atan2(dy, dx) + lk.sigma * mpmath.acos(arg))


@workdps
def state(lk: RefLinkage, t2, wheel_torque=1):
    """Everything at one crank angle, as a dict of mpf (see the module docstring)."""
    t2 = _mpf(t2)
    t4 = rocker_angle(lk, t2)
    ax, ay = _crank_point(lk, t2)
    bx, by = lk.ox + lk.rocker * mpmath.cos(t4), lk.oy + lk.rocker * mpmath.sin(t4)
    ux, uy = bx - ax, by - ay  # B - A
    dax, day = -lk.crank * mpmath.sin(t2), lk.crank * mpmath.cos(t2)  # A'
    dbx, dby = -lk.rocker * mpmath.sin(t4), lk.rocker * mpmath.cos(t4)  # B'
    num = ux * dax + uy * day
    rate = num / (ux * dbx + uy * dby)  # implicit differentiation of the closure
    grip_rate = -lk.handle * mpmath.sin(t4) * rate
    # Transmission angle: the angle at B between B->A and B->O4.
    cosg = ((ax - bx) * (lk.ox - bx) + (ay - by) * (lk.oy - by)) / (lk.coupler * lk.rocker)
    return dict(
        rocker_angle=t4,
        bx=bx,
        by=by,
        rate=rate,
        rate_numerator=num,
        grip_x=lk.ox + lk.handle * mpmath.cos(t4),
        grip_rate=grip_rate,
        force=_mpf(wheel_torque) / grip_rate if grip_rate != 0 else mp.nan,  # NaN exactly at a dead centre
        transmission=mpmath.acos(max(-1, min(1, cosg))),
    )


def force(lk, t2, wheel_torque=1):
    return state(lk, t2, wheel_torque)["force"]


@workdps
def dead_centres(lk: RefLinkage, scan: int = 96):
    """Crank angles where dt4/dt2 = 0, as (extended, folded) in [0, 2 pi), mpf.

    Sign-change scan of the rate numerator on ``scan`` points, each bracket polished with
    ``mpmath.findroot`` (Anderson's bracketing solver).  The extended dead centre is the root
    with the larger rocker angle.  Raises if the scan does not find exactly two roots.
    """

    def num(t):
        return state(lk, t)["rate_numerator"]

    grid = [2 * mp.pi * j / scan for j in range(scan + 1)]
    vals = [num(t) for t in grid]
    roots = []
    for j in range(scan):
        if vals[j] == 0:
            roots.append(grid[j])
        elif vals[j] * vals[j + 1] < 0:
            roots.append(mpmath.findroot(num, (grid[j], grid[j + 1]), solver="anderson"))
    if len(roots) != 2:
        raise ValueError(f"expected two dead centres, found {len(roots)}")
    roots.sort(key=lambda t: rocker_angle(lk, t))
    fold, ext = roots
    return mpmath.fmod(ext, 2 * mp.pi), mpmath.fmod(fold, 2 * mp.pi)


def from_synthesis(syn, i=None, sigma=None) -> RefLinkage:
    """Reference linkage from pumplink's synthesised float lengths (design i of an array)."""

    def g(name):
        v = getattr(syn, name)
        return float(v if i is None else np.asarray(v)[i])

    L1, D1 = -g("pivot_x"), -g("pivot_y")  # b folded into L1: only L1 + b/2 matters
    return make_linkage(
        L1, D1, 0.0, g("rocker_length"), g("handle_length"), g("crank_length"), g("coupler_length"), sigma
    )


# ---------------------------------------------------------------------------------------------
# float64 twin for dense sweeps (same formulas, numpy; still independent of pumplink)


def sweep_rocker(lk: RefLinkage, t2, sigma=None):
    """Rocker angle t4, rate dt4/dt2 and transmission angle on float crank angles t2.

    Returns NaN where the linkage cannot be assembled.
    """
    f = lk.floats()
    s = lk.sigma if sigma is None else sigma
    t2 = np.asarray(t2, float)
    ax, ay = f["crank"] * np.cos(t2), f["crank"] * np.sin(t2)
    dx, dy = f["ox"] - ax, f["oy"] - ay
    dn = np.hypot(dx, dy)
    arg = (f["coupler"] ** 2 - f["rocker"] ** 2 - dn * dn) / (2 * f["rocker"] * dn)
    with np.errstate(invalid="ignore"):
        t4 = np.arctan2(dy, dx) + s * np.arccos(arg)
    t4 = np.where(np.abs(arg) <= 1, np.mod(t4 + np.pi, 2 * np.pi) - np.pi, np.nan)  # (-pi, pi]
    bx, by = f["ox"] + f["rocker"] * np.cos(t4), f["oy"] + f["rocker"] * np.sin(t4)
    ux, uy = bx - ax, by - ay
    with np.errstate(invalid="ignore", divide="ignore"):
        rate = (ux * -ay + uy * ax) / (ux * -f["rocker"] * np.sin(t4) + uy * f["rocker"] * np.cos(t4))
    # Transmission angle from atan2(|cross|, dot) of B->A and B->O4 (no acos).
    vx, vy = f["ox"] - bx, f["oy"] - by
    gamma = np.arctan2(np.abs(-ux * vy + uy * vx), -ux * vx - uy * vy)
    return t4, rate, gamma


# ---------------------------------------------------------------------------------------------
# Random inputs in the realistic ranges of the product's test plan


def linkage_inputs():
    """Spec-level linkage inputs: L1, D1, b, rocker [m], swing [deg]."""
    return st.tuples(
        st.floats(0.0, 1.0),
        st.floats(-0.5, 0.8),
        st.floats(0.0, 0.3),
        st.floats(0.05, 0.6),
        st.floats(10.0, 150.0),
    )


# ---------------------------------------------------------------------------------------------
# Shared by tests/mechanisms/test_fourbar_kinematics.py, tests/models/test_quasi_static.py and
# tests/models/test_flywheel.py

#: Shortest crank [m] for which force and kinematics accuracy is asserted.  The dead-centre
#: crank angles are conditioned like eps * rocker / crank: for a micrometre crank they move by
#: ~1e-12 rad under input rounding, which the 1e-12 rad checks at the dead-band edges would see.
#: A 0.1 mm crank is still far below anything buildable.
MIN_CRANK = 1e-4


def angle_gap(a, b):
    """|a - b| modulo 2 pi, in [0, pi] (numpy, elementwise)."""
    d = np.mod(np.asarray(a, float) - float(b), 2 * math.pi)
    return np.minimum(d, 2 * math.pi - d)


def force_designs():
    """Feasible designs in the issue's realistic ranges, with a handle [m] and a wheel torque [N m]."""
    return st.tuples(linkage_inputs(), st.floats(0.3, 1.5), st.floats(1.0, 50.0))


def setup_design(inputs):
    """(pumplink synthesis, reference linkage, wheel torque); rejects infeasible or sub-micron cranks."""
    from hypothesis import assume

    from pumplink.mechanisms.fourbar import synthesize

    (L1, D1, b, rocker, swing_deg), handle, mw = inputs
    syn = synthesize(L1, D1, b, rocker, math.radians(swing_deg), handle)
    assume(bool(syn.feasible) and syn.crank_length >= MIN_CRANK)
    return syn, from_synthesis(syn), mw
