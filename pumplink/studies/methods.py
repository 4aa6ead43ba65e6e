"""Interchangeable methods for the same job: positions, handle velocity ratio and force.

Every method has ONE signature, ``method(linkage, crank_angle, wheel_torque) -> MethodResult``,
and a registry entry (:data:`METHODS`) that says what it can and cannot handle, in the manner of
poliastro's propagators.  The point kinds a method may fail at are the constants ``UNIFORM``,
``NEAR_DEAD_CENTRE``, ``DEAD_CENTRE``, ``CRANK_PERPENDICULAR``, ``ROCKER_PERPENDICULAR``,
``CRANK_PARALLEL_ROCKER`` and ``CRANK_ALONG_FRAME``; :func:`danger_points` locates them.

* ``vector`` - the production kernel :func:`pumplink.mechanisms.fourbar.kinematic_state` (closed-form loop
  closure, analytic velocity ratio).  The default.
* ``paper`` - the pump paper's instant-centre route, Eq. (4)-(6), literally: slopes tA, tB,
  the quadratic for B, distances IA, IB; in the paper's frame-aligned coordinates (x along the
  frame line O2->O4), transformed to ours (docs/physics.md).
* ``numeric`` - what a user would write without this tool: ``scipy.optimize.fsolve`` on the
  loop closure at every crank angle, and a central difference of the grip position.
* ``reference`` - the textbook route (rocker angle from the loop closure, velocity ratio
  l2 sin(t3 - t2) / (l4 sin(t3 - t4))) in mpmath at 50 significant digits: ground truth only.

All functions are pure (no I/O, no timing); a method that cannot give a value at a point returns
NaN there with ``failed`` set, and NaN with ``singular`` set at a dead centre.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from pumplink.constants import (
    CRANK_ALONG_FRAME,
    CRANK_PARALLEL_ROCKER,
    CRANK_PERPENDICULAR,
    DEAD_CENTRE,
    NEAR_DEAD_CENTRE,
    ROCKER_PERPENDICULAR,
    UNIFORM,
)
from pumplink.mechanisms.fourbar import FourBar, kinematic_state
from pumplink.mechanisms.fourbar_kernel import SINGULAR_SIN

#: The kinds of position where a textbook formula breaks down (identifiers in
#: :mod:`pumplink.constants`; their words are the output layer's).
POINT_KINDS = (
    UNIFORM,
    NEAR_DEAD_CENTRE,
    DEAD_CENTRE,
    CRANK_PERPENDICULAR,
    ROCKER_PERPENDICULAR,
    CRANK_PARALLEL_ROCKER,
    CRANK_ALONG_FRAME,
)
DANGER_KINDS = (CRANK_PERPENDICULAR, ROCKER_PERPENDICULAR, CRANK_PARALLEL_ROCKER, CRANK_ALONG_FRAME)

#: Digits the ``reference`` method carries.
REFERENCE_DIGITS = 50


@dataclass(frozen=True)
class MethodResult:
    """What every method returns (SI units, radians; arrays shaped like ``crank_angle``).

    Attributes
    ----------
    crank_angle : crank angle t2 [rad].
    coupler_x, coupler_y : coupler-rocker joint B [m].
    grip_x, grip_y : hand grip P = O4 + (H / rocker) (B - O4) [m].
    handle_rate : dPx/dt2, horizontal grip travel per crank radian [m/rad].
    force : horizontal operator force Mw / (dPx/dt2) [N] (docs/physics.md); NaN where flagged.
    singular : the method found a dead centre here (force infinite).
    failed : the method could not produce a value here (its own breakdown, not the linkage's).
    """

    crank_angle: np.ndarray
    coupler_x: np.ndarray
    coupler_y: np.ndarray
    grip_x: np.ndarray
    grip_y: np.ndarray
    handle_rate: np.ndarray
    force: np.ndarray
    singular: np.ndarray
    failed: np.ndarray


def _result(lk: FourBar, th, bx, by, rate, wheel_torque, singular, failed) -> MethodResult:
    """Grip, handle rate and force from B and omega4/omega2; NaN wherever flagged."""
    scale = lk.handle / lk.rocker
    gx = lk.pivot_x + scale * (bx - lk.pivot_x)
    gy = lk.pivot_y + scale * (by - lk.pivot_y)
    handle_rate = -scale * (by - lk.pivot_y) * rate  # d/dt2 of O4x + H cos t4
    bad = singular | failed
    with np.errstate(divide="ignore", invalid="ignore"):
        force = np.where(bad, np.nan, wheel_torque / np.where(bad, 1.0, handle_rate))  # Eq. (3), virtual work
    nanf = np.where(failed, np.nan, 1.0)
    return MethodResult(
        th,
        bx * nanf,
        by * nanf,
        gx * nanf,
        gy * nanf,
        np.where(bad, np.nan, handle_rate),
        force,
        singular & ~failed,
        failed,
    )


# ----------------------------------------------------------------------------- vector
def vector(lk: FourBar, crank_angle, wheel_torque=1.0) -> MethodResult:
    """The production route, :func:`pumplink.mechanisms.fourbar.kinematic_state` (closed-form loop closure).

    Parameters
    ----------
    lk : linkage (scalars, or arrays broadcastable with ``crank_angle``).
    crank_angle : crank angles t2 [rad].
    wheel_torque : Mw [N m].
    """
    st = kinematic_state(lk, crank_angle, wheel_torque)
    failed = np.zeros(np.shape(st.force), bool)
    return _result(
        lk,
        st.crank_angle,
        st.coupler_x,
        st.coupler_y,
        st.rocker_rate,
        wheel_torque,
        st.singular,
        failed | np.isnan(st.coupler_x),
    )


# ----------------------------------------------------------------------------- paper
def seed_frame(lk: FourBar):
    """The seed's frame-aligned axes in our coordinates: (l1, e_x, e_y).

    e_x points along the frame line from O2 to O4 (the seed puts O4 at (l1, 0)); e_y is the
    normal on the side where the rocker swings, so yB > 0 over the whole cycle of a feasible
    crank-rocker (its rocker never crosses the frame line, ``pumplink.mechanisms.fourbar``) and the
    seed's positive square root for yB (Eq. 6) is the right one.
    """
    l1 = np.hypot(lk.pivot_x, lk.pivot_y)
    ex = (lk.pivot_x / l1, lk.pivot_y / l1)
    # n = (-ex_y, ex_x) has y-component ex_x; the rocker at mid swing points up (+y) from O4.
    side = np.where(ex[0] > 0, 1.0, -1.0)
    ey = (-ex[1] * side, ex[0] * side)
    return l1, ex, ey


def paper_seed_coordinates(l1, crank, coupler, rocker, seed_angle, root_sign):
    """Eq. (4)-(6) of the pump paper in the paper's own frame, as printed.

    Parameters
    ----------
    l1, crank, coupler, rocker : link lengths l1..l4 [m].
    seed_angle : the paper's crank angle [rad]: xA = l2 sin(t2), yA = l2 cos(t2).
    root_sign : +1 or -1, which root of the quadratic for xB (the paper prints +).

    Returns
    -------
    xA, yA, xB, yB, xI, yI : joints and instant centre in seed coordinates [m].
    ratio : |omega4 / omega2| = l2 IB / (IA l4) [-], Eq. (4).
    disc : discriminant of the quadratic for xB [m^4 scale] (< 0: cannot be assembled).
    tA, tB : slopes of the lines IA and IB [-], Eq. (5).
    """
    l2, l3, l4 = crank, coupler, rocker
    xa = l2 * np.sin(seed_angle)  # Eq. (5) text: xA = l2 sin t2
    ya = l2 * np.cos(seed_angle)  # yA = l2 cos t2
    m = xa**2 + ya**2 + l4**2 - l1**2 - l3**2
    a = 4.0 * (l1 - xa) ** 2 + 4.0 * ya**2  # Eq. (6)
    b = 4.0 * (l1 - xa) * m - 8.0 * l1 * ya**2  # Eq. (6)
    c = m**2 - 4.0 * ya**2 * (l4**2 - l1**2)  # Eq. (6)
    disc = b * b - 4.0 * a * c
    xb = (-b + root_sign * np.sqrt(disc)) / (2.0 * a)  # Eq. (6)
    yb = np.sqrt(l4**2 - l1**2 - xb**2 + 2.0 * xb * l1)  # Eq. (6), positive root
    ta = ya / xa  # Eq. (5)
    tb = yb / (xb - l1)  # Eq. (5)
    xi = l1 * tb / (tb - ta)  # Eq. (5)
    yi = ta * xi  # Eq. (5)
    ia = np.hypot(xi - xa, yi - ya)
    ib = np.hypot(xi - xb, yi - yb)
    ratio = l2 * ib / (ia * l4)  # Eq. (4): Vh / (omega2 H)
    return xa, ya, xb, yb, xi, yi, ratio, disc, ta, tb


def paper(lk: FourBar, crank_angle, wheel_torque=1.0) -> MethodResult:
    """The pump paper's instant-centre route, Eq. (4)-(6), transformed to product coordinates.

    Steps: our crank angle -> the paper's (measured from the normal to the frame line, so
    xA = l2 sin t2, yA = l2 cos t2); B from the quadratic of Eq. (6) and yB from the rocker
    circle; the instant centre I from the slopes tA = yA/xA and tB = yB/(xB - l1) (Eq. 5);
    |omega4/omega2| = l2 IB / (IA l4) (Eq. 4); B back to our axes, where the operator's force is
    horizontal, and F = Mw / (dPx/dt2) (Eq. 3; the paper's cos(phi) with our horizontal).

    Two things the seed leaves implicit are supplied: the root of the quadratic belonging to the
    linkage's assembly branch (the printed "+" root is that branch only while yA has one sign,
    i.e. for half the crank cycle: the two intersection points are mirror images across the line
    A-O4, whose x-order flips with the sign of yA), and the sign of omega4/omega2 (from the signed
    ratios (A . (A - I)) / IA^2 and ((B - I) . (B - O4)) / l4^2).

    Cannot handle, flagged (NaN + ``failed``): xA = 0 (crank perpendicular to the frame line,
    tA infinite), xB = l1 (rocker perpendicular, tB infinite), tA = tB (crank parallel to rocker,
    I at infinity), a negative discriminant.  At yA = 0 (crank along the frame line) the two
    roots of Eq. (6) merge: the discriminant is a difference of nearly equal O(l^8) terms, often
    rounds below zero (flagged, although the linkage assembles fine) and next to it B keeps only
    about half its digits.
    """
    th = np.asarray(crank_angle, float)
    l1, ex, ey = seed_frame(lk)
    handed = ex[0] * ey[1] - ex[1] * ey[0]  # +1 rotation, -1 reflection
    cs, sn = np.cos(th), np.sin(th)
    seed_angle = np.arctan2(cs * ex[0] + sn * ex[1], cs * ey[0] + sn * ey[1])  # t2 from the frame-line normal
    ya0 = lk.crank * np.cos(seed_angle)
    root_sign = np.where(handed * lk.branch * ya0 >= 0, 1.0, -1.0)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        xa, ya, xb, yb, xi, yi, ratio, disc, ta, tb = paper_seed_coordinates(
            l1, lk.crank, lk.coupler, lk.rocker, seed_angle, root_sign
        )
        # sign of omega4/omega2: omega3 (A - I) = omega2 A and omega4 (B - O4) = omega3 (B - I)
        s3 = np.sign(xa * (xa - xi) + ya * (ya - yi))
        s4 = np.sign((xb - xi) * (xb - l1) + (yb - yi) * yb)
        rate = s3 * s4 * ratio
    failed = (xa == 0) | (xb == l1) | (ta == tb) | ~(disc >= 0) | ~np.isfinite(rate)
    singular = (ratio * lk.rocker / lk.crank <= SINGULAR_SIN) & ~failed  # I = B: crank and coupler collinear
    bx = xb * ex[0] + yb * ey[0]
    by = xb * ex[1] + yb * ey[1]
    rate = np.where(failed, np.nan, rate)
    return _result(lk, th, bx, by, rate, wheel_torque, singular, failed)


# ----------------------------------------------------------------------------- numeric
#: Central-difference step of the ``numeric`` method [rad] (about cbrt(machine eps)).
NUMERIC_STEP = 1e-5
#: The forward and backward differences must agree to this relative tolerance.
NUMERIC_AGREE = 1e-3


def _solve_loop(lk: FourBar, theta: float, guess):
    """fsolve on the loop closure A + l3 u3 - O4 - l4 u4 = 0 for (t3, t4); None if it fails."""
    from scipy.optimize import fsolve

    ax, ay = lk.crank * np.cos(theta), lk.crank * np.sin(theta)

    def loop(x):
        t3, t4 = x
        return [
            ax + lk.coupler * np.cos(t3) - lk.pivot_x - lk.rocker * np.cos(t4),
            ay + lk.coupler * np.sin(t3) - lk.pivot_y - lk.rocker * np.sin(t4),
        ]

    sol, info, ier, _ = fsolve(loop, guess, full_output=True, xtol=1e-13)
    # judged by the residual: from an already converged guess fsolve can report "not making good
    # progress" (ier 5) although it sits on the root
    if not np.max(np.abs(info["fvec"])) <= 1e-12 * lk.coupler:
        return None
    return sol


def numeric(lk: FourBar, crank_angle, wheel_torque=1.0) -> MethodResult:
    """Root-finding plus numerical differentiation: a general route without this tool.

    At each crank angle (single design), ``scipy.optimize.fsolve`` solves the loop closure for
    the coupler and rocker angles from the mid-swing guess (rocker vertical); the grip's
    horizontal position is then differentiated by a central difference with step
    :data:`NUMERIC_STEP`, the neighbours solved from the centre solution.

    Self-checks (flagged ``failed``): the solver did not converge, it converged to the other
    assembly branch, or the forward and backward differences disagree by more than
    :data:`NUMERIC_AGREE` (the step straddles a dead centre or the solution jumped).  It cannot
    tell a dead centre from a failure, so it never sets ``singular``.
    """
    th = np.atleast_1d(np.asarray(crank_angle, float))
    px, py, c, k, r, h = (
        float(v) for v in (lk.pivot_x, lk.pivot_y, lk.crank, lk.coupler, lk.rocker, lk.handle)
    )
    n = th.size
    bx, by, rate = np.full(n, np.nan), np.full(n, np.nan), np.full(n, np.nan)
    failed = np.zeros(n, bool)
    for i, t in enumerate(th.ravel()):
        b0 = (px, py + r)  # rocker vertical, mid swing
        ax, ay = c * np.cos(t), c * np.sin(t)
        guess = [np.arctan2(b0[1] - ay, b0[0] - ax), 0.5 * np.pi]
        sol = _solve_loop(lk, t, guess)
        if sol is None:
            failed[i] = True
            continue
        t3, t4 = sol
        bxi, byi = px + r * np.cos(t4), py + r * np.sin(t4)
        cross = (bxi - ax) * (py - ay) - (byi - ay) * (px - ax)
        if np.sign(cross) != -np.sign(lk.branch):  # branch = -sign((B - A) x (O4 - A)), kinematics.py
            failed[i] = True  # converged to the other assembly branch
            continue
        plus, minus = _solve_loop(lk, t + NUMERIC_STEP, sol), _solve_loop(lk, t - NUMERIC_STEP, sol)
        if plus is None or minus is None:
            failed[i] = True
            continue
        gx0, gxp, gxm = (h * np.cos(v) for v in (t4, plus[1], minus[1]))  # grip x minus O4x
        fwd, bwd = (gxp - gx0) / NUMERIC_STEP, (gx0 - gxm) / NUMERIC_STEP
        if not abs(fwd - bwd) <= NUMERIC_AGREE * max(abs(fwd), abs(bwd)):
            failed[i] = True
            continue
        bx[i], by[i] = bxi, byi
        rate[i] = -(gxp - gxm) / (2.0 * NUMERIC_STEP) / (h * np.sin(t4))  # back to omega4/omega2
    shape = np.shape(crank_angle)
    res = _result(lk, th, bx, by, rate, wheel_torque, np.zeros(n, bool), failed)
    return MethodResult(
        *(
            np.reshape(v, shape)
            for v in (
                res.crank_angle,
                res.coupler_x,
                res.coupler_y,
                res.grip_x,
                res.grip_y,
                res.handle_rate,
                res.force,
                res.singular,
                res.failed,
            )
        )
    )


# ----------------------------------------------------------------------------- reference
def reference(lk: FourBar, crank_angle, wheel_torque=1.0, digits: int = REFERENCE_DIGITS) -> MethodResult:
    """Ground truth in mpmath at ``digits`` significant digits (single design, slow).

    An independent route: with d = A - O4, the rocker angle solves
    d . u4 = (l4^2 + |d|^2 - l3^2) / (2 l4), t4 = atan2(dy, dx) +- acos(...), the sign chosen
    by the assembly branch; omega4/omega2 = l2 sin(t3 - t2) / (l4 sin(t3 - t4)) (velocity loop
    dotted with the coupler direction).  The input angles are the given doubles, exactly.
    ``singular`` where |sin(t3 - t2)| <= SINGULAR_SIN (never for a double input in practice).
    """
    import mpmath as mp

    th = np.asarray(crank_angle, float)
    flat = th.ravel()
    out = np.empty((3, flat.size))
    sing = np.zeros(flat.size, bool)
    with mp.workdps(digits):
        px, py, c, k, r = (
            mp.mpf(float(v)) for v in (lk.pivot_x, lk.pivot_y, lk.crank, lk.coupler, lk.rocker)
        )
        br = float(lk.branch)
        for i, t in enumerate(flat):
            t = mp.mpf(float(t))
            ax, ay = c * mp.cos(t), c * mp.sin(t)
            dx, dy = ax - px, ay - py
            dd = mp.sqrt(dx * dx + dy * dy)
            cosv = (r * r + dd * dd - k * k) / (2 * r * dd)
            base, off = mp.atan2(dy, dx), mp.acos(max(min(cosv, mp.mpf(1)), mp.mpf(-1)))
            best = None
            for t4 in (base + off, base - off):
                bx, by = px + r * mp.cos(t4), py + r * mp.sin(t4)
                cross = (bx - ax) * (py - ay) - (by - ay) * (px - ax)
                if best is None or cross * br < 0:  # branch = -sign((B - A) x (O4 - A)), kinematics.py
                    best = (t4, bx, by)
                    if cross * br < 0:
                        break
            t4, bx, by = best
            t3 = mp.atan2(by - ay, bx - ax)
            s32 = mp.sin(t3 - t)
            sing[i] = abs(s32) <= SINGULAR_SIN
            rate = c * s32 / (r * mp.sin(t3 - t4))  # omega4 / omega2
            out[:, i] = float(bx), float(by), float(rate)
    shp = th.shape
    bx, by, rate = (v.reshape(shp) for v in out)
    return _result(lk, th, bx, by, rate, wheel_torque, sing.reshape(shp), np.zeros(shp, bool))


# ----------------------------------------------------------------------------- registry
@dataclass(frozen=True)
class Method:
    """A registry entry: the function and what it can and cannot handle.

    ``handles`` maps every point kind in :data:`POINT_KINDS` to one of ``"exact"`` (full
    double accuracy), ``"accurate"`` (relative error bounded by ``tolerance[kind]``), or
    ``"flags"`` (it must flag the point - NaN with ``failed`` or ``singular`` - or, where it does
    return a value, that value must still meet ``tolerance[kind]``).
    """

    name: str
    function: Callable[..., MethodResult]
    summary: str
    vectorised: bool
    handles: dict
    tolerance: dict
    cannot: str


#: The tolerance the paper's method and the numeric one promise: 1e-6 of the force away from the
#: dead centres, 1e-2 at and next to them.
_APPROXIMATE = {
    UNIFORM: 1e-6,
    NEAR_DEAD_CENTRE: 1e-2,
    DEAD_CENTRE: 1e-2,
    CRANK_PERPENDICULAR: 1e-6,
    ROCKER_PERPENDICULAR: 1e-6,
    CRANK_PARALLEL_ROCKER: 1e-6,
    CRANK_ALONG_FRAME: 1e-6,
}

#: Relative force error a method promises where it returns an unflagged value, by point kind.
#: vector: 1e-12 at >= 1 deg from a dead centre, 1e-6 at 1e-6 deg.
METHODS: dict[str, Method] = {
    "vector": Method(
        "vector",
        vector,
        "closed-form loop closure + analytic velocity ratio (production kernel)",
        True,
        {
            UNIFORM: "exact",
            NEAR_DEAD_CENTRE: "accurate",
            DEAD_CENTRE: "flags",
            CRANK_PERPENDICULAR: "exact",
            ROCKER_PERPENDICULAR: "exact",
            CRANK_PARALLEL_ROCKER: "exact",
            CRANK_ALONG_FRAME: "exact",
        },
        {
            UNIFORM: 1e-12,
            NEAR_DEAD_CENTRE: 1e-6,
            DEAD_CENTRE: 1e-6,
            CRANK_PERPENDICULAR: 1e-12,
            ROCKER_PERPENDICULAR: 1e-12,
            CRANK_PARALLEL_ROCKER: 1e-12,
            CRANK_ALONG_FRAME: 1e-12,
        },
        "only the dead centres themselves (flagged singular)",
    ),
    "paper": Method(
        "paper",
        paper,
        "the paper's instant centre, slopes tA, tB and quadratic for B (Eq. 4-6)",
        True,
        {
            UNIFORM: "accurate",
            NEAR_DEAD_CENTRE: "accurate",
            DEAD_CENTRE: "flags",
            CRANK_PERPENDICULAR: "flags",
            ROCKER_PERPENDICULAR: "flags",
            CRANK_PARALLEL_ROCKER: "flags",
            CRANK_ALONG_FRAME: "flags",
        },
        _APPROXIMATE,
        "xA = 0, xB = l1, tA = tB (division by zero) and yA ~ 0 (the quadratic's discriminant rounds "
        "below zero: flagged though the linkage assembles; half the digits lost nearby)",
    ),
    "numeric": Method(
        "numeric",
        numeric,
        "scipy fsolve on the loop closure + central difference of the grip position",
        False,
        {
            UNIFORM: "accurate",
            NEAR_DEAD_CENTRE: "flags",
            DEAD_CENTRE: "flags",
            CRANK_PERPENDICULAR: "accurate",
            ROCKER_PERPENDICULAR: "accurate",
            CRANK_PARALLEL_ROCKER: "accurate",
            CRANK_ALONG_FRAME: "accurate",
        },
        _APPROXIMATE,
        "within a few difference steps of a dead centre (flagged); cannot say 'dead centre'",
    ),
    "reference": Method(
        "reference",
        reference,
        f"textbook loop closure in mpmath, {REFERENCE_DIGITS} digits (ground truth)",
        False,
        {kind: "exact" for kind in POINT_KINDS},
        {kind: 1e-15 for kind in POINT_KINDS},
        "nothing in range; several hundred times slower than vector",
    ),
}


# ----------------------------------------------------------------------------- danger points
def danger_points(lk: FourBar) -> dict[str, np.ndarray]:
    """Crank angles [rad, in [0, 2 pi)] where some method's formulas break (single design).

    CRANK_PERPENDICULAR and CRANK_ALONG_FRAME in closed form from the frame direction;
    ROCKER_PERPENDICULAR from the circle intersection that puts B where the rocker is normal to
    the frame line (empty if the rocker never gets there); CRANK_PARALLEL_ROCKER as roots of
    sin(t4 - t2) located on a grid and polished with ``scipy.optimize.brentq``.
    """
    from scipy.optimize import brentq

    two_pi = 2.0 * np.pi
    px, py, c, k, r = (float(v) for v in (lk.pivot_x, lk.pivot_y, lk.crank, lk.coupler, lk.rocker))
    fdir = np.arctan2(py, px)  # O2 -> O4
    out = {
        CRANK_PERPENDICULAR: np.mod(fdir + np.array([0.5, -0.5]) * np.pi, two_pi),
        CRANK_ALONG_FRAME: np.mod(fdir + np.array([0.0, np.pi]), two_pi),
    }

    def rocker_angle(t):
        st = kinematic_state(lk, t)
        return st.rocker_angle

    rocker_pts = []
    for t4 in (fdir + np.pi + 0.5 * np.pi, fdir + np.pi - 0.5 * np.pi):  # normal to O4 -> O2
        bx, by = px + r * np.cos(t4), py + r * np.sin(t4)
        d = np.hypot(bx, by)
        cosv = (c * c + d * d - k * k) / (2 * c * d)  # A on the crank circle, |A - B| = coupler
        if abs(cosv) <= 1:
            for s in (1, -1):
                t = np.arctan2(by, bx) + s * np.arccos(cosv)
                st = kinematic_state(lk, t)
                if np.hypot(st.coupler_x - bx, st.coupler_y - by) < 1e-9 * r:  # on our assembly branch
                    rocker_pts.append(np.mod(t, two_pi))
    out[ROCKER_PERPENDICULAR] = np.array(sorted(rocker_pts))

    grid = np.linspace(0.0, two_pi, 3601)
    g = np.sin(rocker_angle(grid) - grid)
    roots = []
    for i in np.nonzero(np.sign(g[:-1]) * np.sign(g[1:]) < 0)[0]:
        roots.append(
            brentq(lambda t: np.sin(rocker_angle(t) - t), grid[i], grid[i + 1], xtol=1e-15, rtol=1e-15)
        )
    out[CRANK_PARALLEL_ROCKER] = np.mod(np.array(roots), two_pi)
    return out
