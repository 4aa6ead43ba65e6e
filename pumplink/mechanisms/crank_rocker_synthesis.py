"""General crank-rocker synthesis: the textbook's construction (docs/crank-rocker.md §7).

Given K and the rocker's two extreme positions, every crank pivot on the design circle gives a
crank-rocker; the designer picks the point.  Three ways to pick it: a given pivot point, a given
frame length, or the optimum of :func:`pumplink.mechanisms.crank_rocker.optimal_crank_rocker`.
The geometry (the design circle, its two arcs, the assembly branch) and the coordinates (rocker
pivot D at the origin, swing bisector +y) are those of :mod:`pumplink.mechanisms.crank_rocker`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from pumplink.mechanisms.crank_rocker import (
    SCAN_START,
    OptimalCrankRocker,
    arc_limit,
    crank_rocker_on_circle,
    effective_transmission,
    extreme_included_angle,
    time_ratio_from_angle,
)
from pumplink.mechanisms.fourbar import FourBar

#: Scan points per design-circle arc when solving for a given frame length.
FRAME_SCAN_POINTS = 4097
#: Largest a1 / (2 w) scanned when the arc is unbounded (K = 1: the design circle is the chord line).
SCAN_STOP = 1e7


@dataclass(frozen=True)
class CrankRocker:
    """One crank-rocker that swings the rocker between C1 and C2 (module coordinates: rocker
    pivot D at the origin, swing bisector +y, C1 on the -x side), lengths in the rocker's unit,
    angles in radians.  Scalars.

    Attributes
    ----------
    time_ratio : K the crank pivot gives (Eq. 7 of the optimal-transmission paper inverted) [-].
    theta : angle C1 A C2 [rad].
    swing, rocker : the rocker's swing phi [rad] and length.
    crank, coupler, frame : (|A C2| - |A C1|)/2 in absolute value, (|A C1| + |A C2|)/2, |A D|.
    transmission, gamma_min, gamma_max : effective minimum transmission angle and its extremes [rad].
    crank_pivot_x, crank_pivot_y : A.
    admissible : True where C1 and C2 lie strictly on one side of the line A-D and A is off the
        chord's ends (one assembly branch: the mechanism really swings between C1 and C2).
    """

    time_ratio: float
    theta: float
    swing: float
    rocker: float
    crank: float
    coupler: float
    frame: float
    transmission: float
    gamma_min: float
    gamma_max: float
    crank_pivot_x: float
    crank_pivot_y: float
    admissible: bool


def extreme_positions(swing, rocker):
    """The rocker tip's extreme positions C1 = rocker (-sin(phi/2), cos(phi/2)) and C2 (mirror)."""
    w, yc = rocker * np.sin(0.5 * swing), rocker * np.cos(0.5 * swing)
    return (-w, yc), (w, yc)


def crank_rocker_at_pivot(pivot_x, pivot_y, swing, rocker) -> CrankRocker:
    """The crank-rocker with its crank pivot at A = (pivot_x, pivot_y) (docs/crank-rocker.md §7).

    At the dead centres crank and coupler are collinear, so |A C_folded| = coupler - crank and
    |A C_extended| = coupler + crank: crank = | |A C2| - |A C1| | / 2, coupler = (|A C1| + |A C2|)/2
    (Eq. 8-9 of the optimal-transmission paper); the crank turns pi + theta on one stroke and
    pi - theta on the other, theta = angle C1 A C2, so K = (pi + theta)/(pi - theta).

    Parameters
    ----------
    pivot_x, pivot_y : crank pivot A (rocker pivot at the origin, swing bisector +y).
    swing : rocker swing phi [rad], 0 < phi < pi;  rocker : rocker length > 0.
    """
    (x1, y1), (x2, y2) = extreme_positions(swing, rocker)
    ax, ay = float(pivot_x), float(pivot_y)
    a1, a2 = float(np.hypot(x1 - ax, y1 - ay)), float(np.hypot(x2 - ax, y2 - ay))
    crank, coupler, frame = 0.5 * abs(a2 - a1), 0.5 * (a1 + a2), float(np.hypot(ax, ay))
    with np.errstate(invalid="ignore", divide="ignore"):
        cos_t = ((x1 - ax) * (x2 - ax) + (y1 - ay) * (y2 - ay)) / (a1 * a2)
        theta = float(np.arccos(np.clip(cos_t, -1.0, 1.0)))
    s1 = (x1 - ax) * (-ay) - (y1 - ay) * (-ax)  # cross(C1 - A, D - A)
    s2 = (x2 - ax) * (-ay) - (y2 - ay) * (-ax)
    admissible = bool(s1 * s2 > 0 and crank > 0 and frame > 0 and np.isfinite(theta))
    mu, gmin, gmax = (float(x) for x in effective_transmission(crank, coupler, rocker, frame))
    return CrankRocker(
        time_ratio=float(time_ratio_from_angle(theta)),
        theta=theta,
        swing=float(swing),
        rocker=float(rocker),
        crank=crank,
        coupler=coupler,
        frame=frame,
        transmission=mu,
        gamma_min=gmin,
        gamma_max=gmax,
        crank_pivot_x=ax,
        crank_pivot_y=ay,
        admissible=admissible,
    )


def from_optimum(opt: OptimalCrankRocker) -> CrankRocker:
    """The (scalar) optimum of :func:`optimal_crank_rocker` as a :class:`CrankRocker`."""
    return crank_rocker_at_pivot(
        float(opt.crank_pivot_x), float(opt.crank_pivot_y), float(opt.swing), float(opt.rocker)
    )


def _sides(theta):
    """Both design circles, or the one chord line when theta = 0 (K = 1)."""
    return (-1.0, 1.0) if theta > 0 else (1.0,)


def _arc_scan(theta, swing, rocker, side, n):
    top = min(float(arc_limit(theta)), SCAN_STOP)
    s = np.geomspace(SCAN_START, top, n)[:-1]
    c, k, f, _, _, ok = crank_rocker_on_circle(s, theta, swing, rocker, side)
    return s, f, ok


def frame_range(time_ratio, swing, rocker, samples: int = FRAME_SCAN_POINTS):
    """(smallest, largest) frame length of the admissible crank-rockers for K, phi, rocker.

    Read off a scan of both design-circle arcs (``samples`` points each), so accurate to the
    scan: for the error message of :func:`crank_rockers_at_frame`, not for design.
    """
    theta = float(extreme_included_angle(time_ratio))
    frames = []
    for side in _sides(theta):
        _, f, ok = _arc_scan(theta, swing, rocker, side, samples)
        frames.append(f[ok])
    f = np.concatenate(frames)
    return (float(f.min()), float(f.max())) if f.size else (float("nan"), float("nan"))


def crank_rockers_at_frame(
    time_ratio, swing, rocker, frame, samples: int = FRAME_SCAN_POINTS
) -> list[CrankRocker]:
    """Every admissible crank-rocker for K and phi whose crank pivot is ``frame`` from the rocker
    pivot (docs/crank-rocker.md §7): the design circle meets the circle of radius ``frame`` about
    D in up to two points per arc.  Best effective minimum transmission angle first; empty if
    no admissible point has this frame length.

    Each intersection is bracketed on a scan of the arc and located by a bracketing root finder
    (scipy's ``find_root``) to ~1e-15 in ln |A C1|.

    Parameters
    ----------
    time_ratio : K >= 1;  swing : phi [rad];  rocker, frame : lengths > 0.
    """
    from scipy.optimize.elementwise import find_root

    theta = float(extreme_included_angle(time_ratio))
    found = []
    for side in _sides(theta):
        s, f, ok = _arc_scan(theta, swing, rocker, side, samples)
        g = f - frame
        idx = np.nonzero(ok[:-1] & ok[1:] & (np.sign(g[:-1]) != np.sign(g[1:])))[0]
        for i in idx:

            def resid(x, side=side):
                return crank_rocker_on_circle(np.exp(x), theta, swing, rocker, side)[2] - frame

            x = float(
                find_root(
                    resid, (np.log(s[i]), np.log(s[i + 1])), tolerances=dict(xatol=1e-15, xrtol=1e-16)
                ).x
            )
            _, _, _, ax, ay, good = crank_rocker_on_circle(np.exp(x), theta, swing, rocker, side)
            if good:
                found.append(crank_rocker_at_pivot(float(ax), float(ay), swing, rocker))
    return sorted(found, key=lambda c: -c.transmission)


def linkage(cr: CrankRocker) -> FourBar:
    """A :class:`CrankRocker` as a :class:`~pumplink.mechanisms.fourbar.FourBar` (crank pivot at the
    origin), for :func:`measure_motion`.  The branch is the side of the line A-D on which the
    extended extreme (the farther of C1, C2 from A) lies (module docstring)."""
    ax, ay = cr.crank_pivot_x, cr.crank_pivot_y
    c1, c2 = extreme_positions(cr.swing, cr.rocker)
    ex, ey = c2 if np.hypot(c2[0] - ax, c2[1] - ay) >= np.hypot(c1[0] - ax, c1[1] - ay) else c1
    cross = (-ax) * (ey - ay) - (-ay) * (ex - ax)
    return FourBar(
        pivot_x=-ax,
        pivot_y=-ay,
        crank=cr.crank,
        coupler=cr.coupler,
        rocker=cr.rocker,
        handle=cr.rocker,
        branch=1.0 if cross > 0 else -1.0,
    )
