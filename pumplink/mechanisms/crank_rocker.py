"""Optimal-transmission crank-rocker for a given time ratio and rocker swing (the
optimal-transmission paper, docs/crank-rocker.md).

Problem (§1 of the optimal-transmission paper): given the time ratio K, the rocker swing phi and
the rocker length, find the crank-rocker (crank, coupler, rocker, frame) whose effective minimum
transmission angle min(gamma_min, 180 deg - gamma_max) is largest.  The optimal-transmission
paper steps the crank pivot along the design circle and reads a diagram; here the optimum is
solved to solver tolerance.

Geometry (derived here; coordinates of this module only).  The rocker pivot D is the origin and
the bisector of the rocker swing is +y.  The rocker's extreme positions are

    C1 = rocker (-sin(phi/2), cos(phi/2))   (folded dead centre: |A C1| = coupler - crank)
    C2 = rocker ( sin(phi/2), cos(phi/2))   (extended dead centre: |A C2| = coupler + crank)

At the dead centres crank and coupler are collinear, so the crank directions there are A->C2 and
C1->A: they differ by 180 deg + angle(C1 A C2).  The time ratio K therefore fixes the angle
C1 A C2 = theta = 180 deg (K - 1)/(K + 1) (Eq. 7 of the optimal-transmission paper), and the
crank pivot A lies on one of the two circles through C1 and C2 on which the chord C1C2 subtends
theta (the "design circle" of Fig. 1 of the optimal-transmission paper, and its mirror image in
the chord).  We place A with the law of sines in the triangle C1 A C2:  with a1 = |A C1| and
w = rocker sin(phi/2) (half the chord),

    sin v = a1 sin(theta) / (2 w),   u = pi - theta - v          (v, u: angles at C2, C1)
    A = C1 + a1 (cos u, side * sin u)                           (side = -1 toward D, +1 away)
    a2 = |A C2| = sqrt(a1^2 + 4 w^2 - 4 w a1 cos u)             (law of cosines at C1)
    crank = (a2 - a1)/2,  coupler = (a2 + a1)/2,  frame = |A|   (Eq. 8-9 of the optimal-transmission paper)

for 0 < a1 < w / sin(theta/2) (beyond it a1 > a2: the mirror-image design with C1 and C2
swapped, which has the same transmission angles).  This form stays finite as theta -> 0.

Assembly branch.  A four-bar whose crank turns fully keeps one assembly branch: the sign of the
triangle (crank tip, coupler point, rocker pivot).  At the dead centres that sign is the side of
the line A-D on which C1 resp. C2 lies, so the linkage really swings between C1 and C2 **iff
C1 and C2 lie strictly on the same side of the line A-D**; otherwise its folded extreme is the
mirror image of C1 in A-D, and the swing and K it produces differ from the ones asked for.  On
the boundary (A, D and C1 or C2 collinear) a transmission angle is 0 or 180 deg.  With the
triangle inequalities of A-D-C1 and A-D-C2 (frame + crank <= coupler + rocker,
frame - crank >= |coupler - rocker|) every admissible point gives a crank-rocker.
:func:`measure_motion` checks all of this by running the linkage through ``pumplink.mechanisms.fourbar``.

Transmission angle (docs/crank-rocker.md, Eq. 4-6) of the optimal-transmission paper: its
extremes occur with crank and frame collinear,
cos gamma = (coupler^2 + rocker^2 - (frame -+ crank)^2)/(2 coupler rocker); the effective
minimum is min(gamma_min, pi - gamma_max).

The optimum exactly (docs/crank-rocker.md §5).  On the design circle write the angles at C1 and
C2 as u, v = (pi - theta)/2 +- delta; the law of sines and the sum-to-product formulas give

    crank = w sin(delta) / cos(theta/2),   coupler = w cos(delta) / sin(theta/2),
    coupler - crank = a1 = 2 w cos(delta + theta/2) / sin(theta)

and A = C1 + a1 (cos u, side sin u), all smooth in 0 < delta < pi/2 - theta/2.  Which extreme
binds is fixed on each arc: with f^2 = rocker^2 + a1^2 - 2 a1 (w cos u - side yc sin u) (law of
cosines in A-C1-D, yc = rocker cos(phi/2)) and coupler^2 - crank^2 = a1 (a1 + 2 crank),

    (cos gamma_min + cos gamma_max) coupler rocker = coupler^2 + rocker^2 - frame^2 - crank^2
        = 2 a1 cos(delta - theta/2) (w tan(theta/2) - side yc),

whose sign does not change along the arc: gamma_min < 180 deg - gamma_max everywhere on the
rocker-pivot side (side -1), and gamma_min > 180 deg - gamma_max on the far side wherever it is
admissible, which needs theta + phi < 180 deg (there line A-D meets the chord's line outside
C1C2, say beyond C2, so C2 lies inside the triangle A C1 D and angle A C2 D = theta + phi +
angle A C1 D < 180 deg).  So on each arc the effective minimum is one smooth function of delta,
gamma_min resp. 180 deg - gamma_max, and its largest value is where that extreme is stationary:
d/d delta of (coupler^2 + rocker^2 - (frame -+ crank)^2) / coupler = 0 (Eq. 4 resp. 5 of the
optimal-transmission paper).  That is a smooth equation with a
simple root, solved by a bracketing root finder to the last bits of delta: the lengths,
gamma_min and gamma_max of the optimum are exact to rounding, not only the stationary value mu
(which a maximiser of mu fixes only to ~sqrt(eps) in delta).

K = 1 (theta = 0) has no optimum: the design circle becomes the chord line, and the effective
minimum rises toward 90 deg - phi/2 as the frame grows without bound (checked numerically in
``tests/mechanisms/test_crank_rocker.py``), so :func:`optimal_crank_rocker` needs K > 1.

The textbook's general synthesis on the same design circle (any pivot point, a given frame
length) is :mod:`pumplink.mechanisms.crank_rocker_synthesis`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from pumplink.errors import SpecError
from pumplink.mechanisms.fourbar import FourBar, transmission_range

#: Scan points per design-circle arc before the bracketing refinement.
SCAN_POINTS = 2049
#: Smallest a1 / (2 w) scanned (the arc starts at C1 where the linkage degenerates).
SCAN_START = 1e-7
#: Designs per chunk in the vectorised scan (bounds memory for chart grids).
CHUNK = 256
#: |gamma_min - (pi - gamma_max)| below this [rad] counts as "both extremes bind".
BALANCE_TOL = 1e-9


@dataclass(frozen=True)
class OptimalCrankRocker:
    """Optimal-transmission crank-rocker (lengths in the rocker's unit, angles in radians).

    Attributes
    ----------
    time_ratio : K [-];  theta : extreme included angle [rad] (Eq. 7 of the optimal-transmission paper).
    swing : rocker swing phi [rad].
    crank, coupler, rocker, frame : link lengths.
    transmission : effective minimum transmission angle min(gamma_min, pi - gamma_max) [rad].
    gamma_min, gamma_max : transmission-angle extremes [rad] (Eq. 4-5 of the optimal-transmission paper).
    rocker_to_frame : rocker / frame (the optimal-transmission paper's l3/l4).
    crank_pivot_x, crank_pivot_y : crank pivot A, rocker pivot at the origin, swing bisector +y.
    side : -1 if A is on the rocker pivot's side of the chord C1C2, +1 if beyond it.
    binding : 0 both extremes equal (gamma_min = pi - gamma_max), 1 gamma_min alone, 2 gamma_max alone.
    """

    time_ratio: np.ndarray | float
    theta: np.ndarray | float
    swing: np.ndarray | float
    crank: np.ndarray | float
    coupler: np.ndarray | float
    rocker: np.ndarray | float
    frame: np.ndarray | float
    transmission: np.ndarray | float
    gamma_min: np.ndarray | float
    gamma_max: np.ndarray | float
    rocker_to_frame: np.ndarray | float
    crank_pivot_x: np.ndarray | float
    crank_pivot_y: np.ndarray | float
    side: np.ndarray | float
    binding: np.ndarray | int


@dataclass(frozen=True)
class MeasuredMotion:
    """What a crank-rocker really does, from the kinematics (angles in radians).

    Attributes
    ----------
    swing : rocker swing between its two extremes [rad].
    time_ratio : slow/fast ratio of the crank arcs between the rocker extremes [-].
    transmission : smallest min(gamma, pi - gamma) over the cycle [rad].
    assembles : False if the coupler cannot close the loop at some crank angle.
    """

    swing: float
    time_ratio: float
    transmission: float
    assembles: bool


def extreme_included_angle(time_ratio):
    """Extreme included angle theta = pi (K - 1)/(K + 1) [rad] (Eq. 7 of the optimal-transmission
    paper, docs/crank-rocker.md)."""
    k = np.asarray(time_ratio, float)
    return np.pi * (k - 1.0) / (k + 1.0)  # Eq. (7) of the optimal-transmission paper


def time_ratio_from_angle(theta):
    """K = (pi + theta)/(pi - theta), the inverse of :func:`extreme_included_angle`."""
    theta = np.asarray(theta, float)
    return (np.pi + theta) / (np.pi - theta)


def effective_transmission(crank, coupler, rocker, frame):
    """min(gamma_min, pi - gamma_max) of a crank-rocker [rad] (Eq. 4-6 of the optimal-transmission
    paper, docs/crank-rocker.md).

    Returns
    -------
    mu, gamma_min, gamma_max : [rad].
    """
    gmin, gmax = transmission_range(
        frame, crank, coupler, rocker
    )  # Eq. (4)-(5) of the optimal-transmission paper
    return np.minimum(gmin, np.pi - gmax), gmin, gmax  # Eq. (6) of the optimal-transmission paper


def arc_limit(theta):
    """Upper end of the folded distance a1 / (2 w) on the design arc: 1 / (2 sin(theta/2))."""
    with np.errstate(divide="ignore"):
        return 0.5 / np.sin(0.5 * np.asarray(theta, float))


def crank_rocker_on_circle(s, theta, swing, rocker, side):
    """The crank-rocker whose crank pivot is the design-circle point with |A C1| = 2 w s.

    Parameters
    ----------
    s : folded distance a1 as a fraction of the chord 2 w = 2 rocker sin(phi/2), 0 < s < :func:`arc_limit`.
    theta : extreme included angle [rad];  swing : rocker swing phi [rad];  rocker : rocker length.
    side : -1 (crank pivot on the rocker pivot's side of the chord) or +1.

    Returns
    -------
    crank, coupler, frame, pivot_x, pivot_y, admissible
        Lengths, the crank pivot A (module coordinates) and True where C1 and C2 lie strictly on
        one side of the line A-D (one assembly branch; see the module docstring).
    """
    w = rocker * np.sin(0.5 * swing)
    yc = rocker * np.cos(0.5 * swing)
    a1 = 2.0 * w * s
    v = np.arcsin(np.clip(s * np.sin(theta), -1.0, 1.0))  # law of sines in C1 A C2
    u = np.pi - theta - v
    ax = -w + a1 * np.cos(u)
    ay = yc + side * a1 * np.sin(u)
    a2 = np.sqrt(a1 * a1 + 4.0 * w * w - 4.0 * w * a1 * np.cos(u))  # law of cosines at C1
    crank = 0.5 * (a2 - a1)  # Eq. (8) of the optimal-transmission paper
    coupler = 0.5 * (a2 + a1)  # Eq. (9) of the optimal-transmission paper
    frame = np.hypot(ax, ay)
    # cross(C - A, D - A) for C = C1, C2 (D = origin): same sign <=> same side of line A-D.
    s1 = (-w - ax) * (-ay) - (yc - ay) * (-ax)
    s2 = (w - ax) * (-ay) - (yc - ay) * (-ax)
    admissible = (s1 * s2 > 0) & (a2 > a1)
    return crank, coupler, frame, ax, ay, admissible


def crank_rocker_at_delta(delta, theta, swing, rocker, side):
    """The crank-rocker at the design-circle point with angles (pi - theta)/2 +- delta at C1, C2.

    Parameters
    ----------
    delta : half the difference of the angles at C1 and C2 of the triangle C1 A C2 [rad],
        0 < delta < pi/2 - theta/2 (delta -> 0: crank -> 0; the other end: A -> C1).
    theta, swing, rocker, side : as :func:`crank_rocker_on_circle`.

    Returns
    -------
    crank, coupler, frame, pivot_x, pivot_y, admissible
        As :func:`crank_rocker_on_circle` (module docstring for the formulas).
    """
    half = 0.5 * theta
    w = rocker * np.sin(0.5 * swing)
    yc = rocker * np.cos(0.5 * swing)
    crank = w * np.sin(delta) / np.cos(half)  # Eq. (8) of the optimal-transmission paper, law of sines
    coupler = w * np.cos(delta) / np.sin(half)  # Eq. (9) of the optimal-transmission paper, law of sines
    a1 = 2.0 * w * np.cos(delta + half) / np.sin(theta)  # coupler - crank without cancellation
    u = 0.5 * (np.pi - theta) + delta
    ax = -w + a1 * np.cos(u)
    ay = yc + side * a1 * np.sin(u)
    frame = np.hypot(ax, ay)
    s1 = (-w - ax) * (-ay) - (yc - ay) * (-ax)  # cross(C1 - A, D - A)
    s2 = (w - ax) * (-ay) - (yc - ay) * (-ax)  # cross(C2 - A, D - A)
    admissible = (s1 * s2 > 0) & (crank > 0) & (a1 > 0)
    return crank, coupler, frame, ax, ay, admissible


#: Which extreme binds (:attr:`OptimalCrankRocker.binding`): both, gamma_min alone, gamma_max alone.
BOTH, GAMMA_MIN, GAMMA_MAX = 0, 1, 2


def binding_extreme(side):
    """The extreme that binds everywhere on the admissible arc ``side`` (module docstring):
    ``GAMMA_MIN`` on the rocker-pivot side (-1), ``GAMMA_MAX`` on the far side (+1)."""
    return np.where(np.asarray(side) < 0, GAMMA_MIN, GAMMA_MAX)


def stationarity(delta, theta, swing, rocker, side, extreme):
    """The numerator of d/d delta (n / coupler), n = coupler^2 + rocker^2 - (frame -+ crank)^2
    (2 rocker cos gamma_min resp. gamma_max times the coupler, Eq. 4 resp. 5 of the
    optimal-transmission paper), over rocker^3: zero where ``extreme`` (``GAMMA_MIN`` or
    ``GAMMA_MAX``) is stationary along the design circle (module docstring).  Dimensionless."""
    half = 0.5 * theta
    w = rocker * np.sin(0.5 * swing)
    crank, coupler, frame, ax, ay, _ = crank_rocker_at_delta(delta, theta, swing, rocker, side)
    d_crank = w * np.cos(delta) / np.cos(half)
    d_coupler = -w * np.sin(delta) / np.sin(half)
    a1 = 2.0 * w * np.cos(delta + half) / np.sin(theta)
    d_a1 = -2.0 * w * np.sin(delta + half) / np.sin(theta)
    u = 0.5 * (np.pi - theta) + delta
    d_ax = d_a1 * np.cos(u) - a1 * np.sin(u)
    d_ay = side * (d_a1 * np.sin(u) + a1 * np.cos(u))
    d_frame = (ax * d_ax + ay * d_ay) / frame
    sign = np.where(extreme == GAMMA_MAX, 1.0, -1.0)  # frame + crank for gamma_max, - for gamma_min
    e, d_e = frame + sign * crank, d_frame + sign * d_crank
    n = coupler * coupler + rocker * rocker - e * e  # Eq. (4) / (5) times 2 coupler rocker
    d_n = 2.0 * coupler * d_coupler - 2.0 * e * d_e
    return (d_n * coupler - n * d_coupler) / rocker**3


def _delta_of(log_s, theta):
    """delta of the design-circle point with |A C1| = 2 w exp(log_s) (sin v = s sin theta)."""
    return 0.5 * np.pi - 0.5 * theta - np.arcsin(np.clip(np.exp(log_s) * np.sin(theta), -1.0, 1.0))


def _optimum_chunk(theta, swing, rocker, n):
    """Best (mu, delta, side, binding) over both design circles for 1-D arrays of designs."""
    from scipy.optimize.elementwise import find_root  # lazy: keeps start-up fast

    d = theta.size
    best_mu = np.full(d, -np.inf)
    best_delta = np.full(d, np.nan)
    best_side = np.zeros(d)
    best_binding = np.full(d, -1)
    top = np.log(arc_limit(theta))  # (D,)
    frac = np.linspace(0.0, 1.0, n)
    lo = np.log(SCAN_START)
    rows = np.arange(d)
    for side in (-1.0, 1.0):
        ls = lo + (top[:, None] - lo) * frac[None, 1:-1]  # open interval (SCAN_START, arc limit)
        th, ph, rk = theta[:, None], swing[:, None], rocker[:, None]
        c, k, f, _, _, ok = crank_rocker_on_circle(np.exp(ls), th, ph, rk, side)
        mu = np.where(ok, effective_transmission(c, k, rk, f)[0], -np.inf)
        j = np.argmax(mu, axis=1)
        m = ls.shape[1]
        jc = np.clip(j, 1, m - 2)
        has = np.isfinite(mu[rows, j])
        # the stationary point of the binding extreme within a scan step of the best point
        # (larger s is smaller delta); the scan point itself if there is no root in the bracket
        extreme = binding_extreme(side)
        res = find_root(
            lambda x, t, p, r, side=side: stationarity(x, t, p, r, side, binding_extreme(side)),
            (_delta_of(ls[rows, jc + 1], theta), _delta_of(ls[rows, jc - 1], theta)),
            args=(theta, swing, rocker),
        )
        scan_delta = _delta_of(ls[rows, j], theta)
        x = np.where(res.success, res.x, scan_delta)
        cc, kk, ff, _, _, okc = crank_rocker_at_delta(x, theta, swing, rocker, side)
        with np.errstate(invalid="ignore"):
            root_mu = np.where(okc, effective_transmission(cc, kk, rocker, ff)[0], -np.inf)
        # the root is the arc's maximum: it may round below a scan point next to it (the two are
        # computed by different formulas), never by more than a few eps
        solved = res.success & (root_mu >= mu[rows, j] - 1e-12)
        cand_delta = np.where(solved, x, scan_delta)
        cand_mu = np.where(solved, root_mu, mu[rows, j])
        cand_binding = np.where(solved, extreme, -1)
        better = has & (cand_mu > best_mu)
        best_mu = np.where(better, cand_mu, best_mu)
        best_delta = np.where(better, cand_delta, best_delta)
        best_side = np.where(better, side, best_side)
        best_binding = np.where(better, cand_binding, best_binding)
    return best_mu, best_delta, best_side, best_binding


def optimal_crank_rocker(time_ratio, swing, rocker=1.0, samples: int = SCAN_POINTS) -> OptimalCrankRocker:
    """Crank-rocker with the largest effective minimum transmission angle (the
    optimal-transmission paper, exact).

    Both design circles are scanned on ``samples`` points (geometric in |A C1|) restricted to
    the one-branch arc; within a scan step of the best point, the condition of the module
    docstring (the binding extreme stationary on the arc) is solved by scipy's bracketing root
    finder (``scipy.optimize.elementwise.find_root``, Chandrupatla) to
    its default tolerance, a few units in the last place of delta; the better arc's root is the
    optimum.  So the lengths, gamma_min and gamma_max are exact to rounding (measured: 1e-15
    relative against a 40-digit search), and do not depend on ``samples`` beyond that.
    Broadcasts over ``time_ratio``, ``swing`` and ``rocker``.

    Parameters
    ----------
    time_ratio : K > 1 [-].
    swing : rocker swing phi [rad], 0 < phi < pi.
    rocker : rocker length (any unit; the other lengths come out in it).

    Raises
    ------
    SpecError
        K <= 1 (no optimum exists, see the module docstring), phi outside (0, pi), rocker <= 0.
    """
    k, phi, r = np.broadcast_arrays(*(np.asarray(v, float) for v in (time_ratio, swing, rocker)))
    if not np.all(np.isfinite(k) & (k > 1.0)):
        bad = k[~(np.isfinite(k) & (k > 1.0))].flat[0]
        raise SpecError(
            f"time ratio K = {bad:g} must be > 1: at K = 1 the minimum transmission angle only "
            "approaches 90 deg - swing/2 as the frame grows without bound; give e.g. K = 1.05"
        )
    if not np.all(np.isfinite(phi) & (phi > 0) & (phi < np.pi)):
        bad = phi[~(np.isfinite(phi) & (phi > 0) & (phi < np.pi))].flat[0]
        raise SpecError(f"rocker swing {np.degrees(bad):g} deg must be between 0 and 180 deg; give e.g. 40")
    if not np.all(np.isfinite(r) & (r > 0)):
        raise SpecError(f"rocker length {r[~(np.isfinite(r) & (r > 0))].flat[0]:g} must be a positive number")
    theta = extreme_included_angle(k)  # Eq. (7) of the optimal-transmission paper
    shape = k.shape
    th, ph, rr = theta.ravel(), phi.ravel(), r.ravel()
    out_mu, out_delta, out_side, out_binding = (np.empty(th.size) for _ in range(4))
    for i0 in range(0, th.size, CHUNK):
        sl = slice(i0, i0 + CHUNK)
        out_mu[sl], out_delta[sl], out_side[sl], out_binding[sl] = _optimum_chunk(
            th[sl], ph[sl], rr[sl], samples
        )
    c, kk, f, ax, ay, _ = crank_rocker_at_delta(out_delta, th, ph, rr, out_side)
    mu, gmin, gmax = effective_transmission(c, kk, rr, f)
    # a scan point that no root beat (none in the designs tested): classify by value
    by_value = np.where(
        np.abs(gmin - (np.pi - gmax)) <= BALANCE_TOL,
        BOTH,
        np.where(gmin < np.pi - gmax, GAMMA_MIN, GAMMA_MAX),
    )
    binding = np.where(out_binding >= 0, out_binding, by_value)

    def out(a):
        a = np.asarray(a).reshape(shape)
        return a[()] if a.ndim == 0 else a

    return OptimalCrankRocker(
        time_ratio=out(k),
        theta=out(theta),
        swing=out(phi),
        crank=out(c),
        coupler=out(kk),
        rocker=out(rr),
        frame=out(f),
        transmission=out(mu),
        gamma_min=out(gmin),
        gamma_max=out(gmax),
        rocker_to_frame=out(rr / f),
        crank_pivot_x=out(ax),
        crank_pivot_y=out(ay),
        side=out(out_side),
        binding=out(binding.astype(np.int8)),
    )


def optimum_linkage(opt: OptimalCrankRocker) -> FourBar:
    """The optimum as a :class:`~pumplink.mechanisms.fourbar.FourBar` (crank pivot at the origin).

    Rocker pivot D - A = -A; branch = sign of cross(D - A, C2 - A), the side of the line A-D
    on which the extended extreme C2 lies (module docstring), for the kinematics' convention
    B = T + t d + q perp(d) with q proportional to the branch.
    """
    ax, ay = float(opt.crank_pivot_x), float(opt.crank_pivot_y)
    r, phi = float(opt.rocker), float(opt.swing)
    c2x, c2y = r * np.sin(0.5 * phi), r * np.cos(0.5 * phi)
    cross = (-ax) * (c2y - ay) - (-ay) * (c2x - ax)
    return FourBar(
        pivot_x=-ax,
        pivot_y=-ay,
        crank=float(opt.crank),
        coupler=float(opt.coupler),
        rocker=r,
        handle=r,
        branch=1.0 if cross > 0 else -1.0,
    )


def rocker_stops(lk: FourBar, grid, rate):
    """The crank angles [rad] where the rocker stops (its dead centres): each sign change of the
    rocker rate d(theta4)/d(theta2), ``rate`` on the crank angles ``grid``, located by a bracketing
    root finder (~1e-15 rad) on :func:`pumplink.mechanisms.fourbar.kinematic_state`'s rate; None
    unless the rate changes sign exactly twice."""
    from scipy.optimize.elementwise import find_root

    from pumplink.mechanisms.fourbar import kinematic_state

    flips = np.nonzero(np.sign(rate[:-1]) != np.sign(rate[1:]))[0]
    if flips.size != 2:
        return None
    return find_root(
        lambda x: kinematic_state(lk, x).rocker_rate,
        (grid[flips], grid[flips + 1]),
        tolerances=dict(xatol=1e-15, xrtol=1e-16),
    ).x


def measure_motion(lk: FourBar, samples: int = 4096) -> MeasuredMotion:
    """Run a crank-rocker through a full crank turn and measure its swing, K and transmission.

    Independent of the design formulas: positions and the rocker rate d(theta4)/d(theta2) come
    from ``pumplink.mechanisms.fourbar.kinematic_state``.  The rocker extremes are the two sign changes of the
    rocker rate on ``samples`` crank angles, located exactly with a bracketing root finder; the
    smallest transmission deviation min(gamma, pi - gamma) is refined with a bracketing minimiser.

    Parameters
    ----------
    lk : scalar linkage (crank pivot at the origin).
    samples : crank angles in the initial scan.
    """
    from scipy.optimize.elementwise import find_minimum

    from pumplink.mechanisms.fourbar import kinematic_state

    two_pi = 2.0 * np.pi
    # half a step off the round angles, where a symmetric design (K = 1, frame along the chord)
    # puts its dead centres exactly: a rate that is zero to rounding on a sample gives no bracket
    th = (np.arange(samples + 1) + 0.5) * (two_pi / samples)
    st = kinematic_state(lk, th)
    assembles = bool(np.all(np.isfinite(st.coupler_x)))
    roots = rocker_stops(lk, th, st.rocker_rate) if assembles else None
    nan = float("nan")
    if roots is None:
        return MeasuredMotion(nan, nan, nan, assembles)
    ends = kinematic_state(lk, roots)
    ang = np.arctan2(ends.coupler_y - lk.pivot_y, ends.coupler_x - lk.pivot_x)
    swing = abs(float(np.angle(np.exp(1j * (ang[1] - ang[0])))))
    arc = float(np.mod(roots[1] - roots[0], two_pi))
    ratio = max(arc, two_pi - arc) / min(arc, two_pi - arc)

    def dev(x):
        g = kinematic_state(lk, x).transmission_angle
        return np.minimum(g, np.pi - g)

    dv = dev(th)
    j = int(np.clip(np.argmin(dv), 1, samples - 1))
    res = find_minimum(dev, (th[j - 1], th[j], th[j + 1]), tolerances=dict(xatol=1e-14, xrtol=1e-15))
    # the refinement where it converged (a flat minimum next to a symmetric design's sample may
    # give none: then the sample's value, not NaN)
    refined = float(res.f_x) if bool(res.success) and np.isfinite(res.f_x) else math.inf
    tmin = min(refined, float(dv[j]))
    return MeasuredMotion(swing=swing, time_ratio=ratio, transmission=tmin, assembles=assembles)


# ----------------------------------------------------------------------------- the paper's example
#: The optimal-transmission paper's worked example (K = 1.1818, phi = 40 deg, rocker 50 mm).
PUBLISHED_EXAMPLE = {"time_ratio": 1.1818, "swing_deg": 40.0, "rocker": 50.0}
#: Its designs as printed: the diagram read-off and the "computer" result (crank, coupler, rocker,
#: frame in mm; docs/crank-rocker.md).
PUBLISHED_DESIGNS = {
    "paper's diagram read-off": (16.0, 46.0, 50.0, 53.76),
    "paper's computer result": (16.2227, 44.5093, 50.0, 53.8986),
}
#: The minimum transmission angle the paper prints for its diagram design [deg].
PUBLISHED_GAMMA_MIN_DEG = 46.3698


@dataclass(frozen=True)
class Comparison:
    """A published design measured as pumplink measures its own optimum."""

    label: str
    lengths: tuple[float, float, float, float]  # crank, coupler, rocker, frame
    transmission: float  # effective minimum transmission angle [rad] (Eq. 4-6)
    motion: MeasuredMotion


def is_published_example(time_ratio: float, swing_deg: float, rocker: float) -> bool:
    """True when the inputs are exactly the paper's worked example."""
    ex = PUBLISHED_EXAMPLE
    return (time_ratio, swing_deg, rocker) == (ex["time_ratio"], ex["swing_deg"], ex["rocker"])


def published_comparisons() -> list[Comparison]:
    """The paper's designs, each placed with the crank pivot at the origin and the frame along +x,
    with its transmission angle and its simulated swing and time ratio."""
    out = []
    for label, (c, k, r, f) in PUBLISHED_DESIGNS.items():
        mu = float(effective_transmission(c, k, r, f)[0])
        out.append(Comparison(label, (c, k, r, f), mu, measure_motion(FourBar(f, 0.0, c, k, r, r, 1.0))))
    return out


@dataclass(frozen=True)
class DesignChart:
    """The paper's design diagram, solved exactly on a grid (degrees for the axes)."""

    theta_deg: np.ndarray  # extreme included angle, rows
    swing_deg: np.ndarray  # rocker swing, columns
    optimum: OptimalCrankRocker  # over the (theta, swing) grid
    example_swing_deg: float
    example_theta_deg: float


def design_chart() -> DesignChart:
    """Optimal crank-rockers over theta = 1..40 deg (1 deg steps) and phi = 10..120 deg (2 deg)."""
    th = np.linspace(1.0, 40.0, 40)
    ph = np.linspace(10.0, 120.0, 56)
    opt = optimal_crank_rocker(time_ratio_from_angle(np.radians(th))[:, None], np.radians(ph)[None, :])
    ex = PUBLISHED_EXAMPLE
    return DesignChart(
        th, ph, opt, ex["swing_deg"], float(np.degrees(extreme_included_angle(ex["time_ratio"])))
    )
