"""Dead-centre synthesis of the pump linkage (Eq. 1-2 of the pump paper, NOTES.md §1).

Coordinates (product convention, NOTES.md §1): origin at the wheel axle O2, x horizontal, y up,
angles counter-clockwise from +x.  The rocker pivot is O4 = (-(L1 + b/2), -D1); the handle (the
rocker extended to length H) swings symmetrically about the vertical through
90 deg +- swing/2.

Every function is a pure numpy function of floats or arrays and broadcasts over designs.

Feasibility, derived here and proved by simulation in ``tests/test_synthesis.py``: with
psi1, psi2 the angles at O4 between the frame line O4->O2 and the rocker at its two extremes,
the closed form gives a crank-rocker whose rocker swings exactly through 90 +- swing/2 **iff**
0 < psi2 < psi1 < 180 deg.  Then the triangles O2-O4-B1 and O2-O4-B2 are proper, and their
triangle inequalities are exactly the conditions for the crank to turn fully
(frame + crank <= coupler + rocker and frame - crank >= |coupler - rocker|) while the
coupler point B never reaches the frame line (so the rocker cannot turn fully).  When
psi2 <= 0 or psi1 >= 180 deg the closed form still returns lengths (cos is even), but
the linkage they make swings through a different, unsymmetric arc; at psi = 0 or 180 deg
it is a change-point linkage that can flip assembly branch.  Those designs are rejected
with a reason.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

#: Reason codes for infeasible designs (0 = feasible).
FEASIBLE = 0
PIVOT_ON_AXLE = 1
SWING_CROSSES_FRAME_LINE = 2
SWING_CROSSES_FRAME_EXTENSION = 3

#: Margin [rad] kept from the change-point positions psi = 0 and psi = pi: closer than this the
#: linkage is numerically a change-point linkage (its transmission angle would drop below
#: ~1e-4 deg) and its assembly branch is not well defined.
CHANGE_POINT_MARGIN = 1e-6


@dataclass(frozen=True)
class Linkage:
    """A pump four-bar in product coordinates (floats or broadcastable arrays).

    Attributes
    ----------
    pivot_x, pivot_y : rocker pivot O4 [m] (the crank pivot O2 is the origin).
    crank, coupler, rocker : link lengths [m].
    handle : distance from O4 to the hand grip along the rocker [m].
    branch : +1 or -1, the assembly branch; the coupler point is
        B = A + t (O4 - A) + branch * |h/e| * perp(O4 - A) (see ``pumplink.kinematics``).
    """

    pivot_x: np.ndarray | float
    pivot_y: np.ndarray | float
    crank: np.ndarray | float
    coupler: np.ndarray | float
    rocker: np.ndarray | float
    handle: np.ndarray | float
    branch: np.ndarray | float


@dataclass(frozen=True)
class Synthesis:
    """Result of :func:`synthesize` (angles in radians, lengths in metres).

    ``reason`` is 0 for a feasible design, else one of the reason codes; for infeasible designs
    every quantity that depends on the crank and coupler is NaN.
    """

    frame_length: np.ndarray | float
    beta: np.ndarray | float
    psi1: np.ndarray | float
    psi2: np.ndarray | float
    crank_length: np.ndarray | float
    coupler_length: np.ndarray | float
    rocker_length: np.ndarray | float
    handle_length: np.ndarray | float
    swing: np.ndarray | float
    pivot_x: np.ndarray | float
    pivot_y: np.ndarray | float
    dead_centre_extended: np.ndarray | float
    dead_centre_folded: np.ndarray | float
    time_ratio: np.ndarray | float
    stroke_plus_x: np.ndarray | float
    transmission_min: np.ndarray | float
    transmission_max: np.ndarray | float
    branch: np.ndarray | float
    reason: np.ndarray | int

    @property
    def feasible(self) -> np.ndarray | bool:
        """True where the design is a crank-rocker with the requested swing."""
        return self.reason == FEASIBLE

    @property
    def linkage(self) -> Linkage:
        """The synthesised four-bar, for the kinematics and force functions."""
        return Linkage(self.pivot_x, self.pivot_y, self.crank_length, self.coupler_length,
                       self.rocker_length, self.handle_length, self.branch)


def rocker_pivot(L1, D1, b):
    """Rocker pivot O4 relative to the wheel axle [m] (NOTES.md §1).

    Returns
    -------
    x, y : O4 = (-(L1 + b/2), -D1)
    """
    return -(np.asarray(L1, float) + 0.5 * np.asarray(b, float)), -np.asarray(D1, float)


def frame_length(L1, D1, b):
    """Frame length O2-O4 [m], Eq. (1) of the pump paper as read in NOTES.md §1."""
    return np.hypot(np.asarray(L1, float) + 0.5 * np.asarray(b, float), D1)  # Eq. (1)


def extreme_angles(L1, D1, b, swing):
    """beta and the dead-centre angles psi1 > psi2 at O4 [rad], Eq. (2) of the pump paper.

    psi is measured at O4 from the frame line O4->O2 to the rocker; psi1 belongs to the rocker
    at 90 deg + swing/2 (the extended dead centre), psi2 to 90 deg - swing/2 (folded).

    Parameters
    ----------
    L1, D1, b : frame placement [m].
    swing : total handle swing [rad].
    """
    beta = 0.5 * np.pi + np.arctan2(D1, np.asarray(L1, float) + 0.5 * np.asarray(b, float))  # Eq. (2)
    half = 0.5 * np.asarray(swing, float)
    return beta, np.pi - beta + half, np.pi - beta - half  # Eq. (2): psi1, psi2


def _side(frame, rocker, psi):
    # |O2 B| from the law of cosines in the cancellation-free form
    # f^2 + r^2 - 2 f r cos psi = (f - r)^2 + 4 f r sin^2(psi/2).
    # Squares as products, never ``** 2``: on numpy scalars ``** 2`` calls libm pow(), which is
    # not always correctly rounded, while arrays use an exact square; with products the scalar
    # path (``pumplink force``) gives bit for bit the numbers of the array path (``pumplink batch``).
    fr = frame - rocker
    half = np.sin(0.5 * psi)
    return np.sqrt(fr * fr + 4.0 * frame * rocker * (half * half))


def transmission_range(frame, crank, coupler, rocker):
    """Extreme transmission angles of a crank-rocker [rad] (NOTES.md §2, seed 001 Eq. 4-5).

    The coupler-rocker angle is extreme when crank and frame are collinear:
    cos gamma = (coupler^2 + rocker^2 - (frame -+ crank)^2) / (2 coupler rocker).
    """
    den = 2.0 * coupler * rocker
    # Products, not ``** 2``, so scalars and arrays round identically (see ``_side``).
    near, far = frame - crank, frame + crank
    cmin = (coupler * coupler + rocker * rocker - near * near) / den  # seed 001 Eq. (4)
    cmax = (coupler * coupler + rocker * rocker - far * far) / den  # seed 001 Eq. (5)
    return np.arccos(np.clip(cmin, -1.0, 1.0)), np.arccos(np.clip(cmax, -1.0, 1.0))


def synthesize(L1, D1, b, rocker, swing, handle=1.0) -> Synthesis:
    """Dead-centre synthesis: crank and coupler lengths from the frame and the handle swing.

    At the rocker's extremes crank and coupler are collinear, so |O2 B| = crank + coupler
    (extended, psi1) or coupler - crank (folded, psi2); Eq. (2) of the pump paper:
    coupler = (d1 + d2)/2, crank = (d1 - d2)/2.

    Parameters
    ----------
    L1, D1, b : frame placement [m] (NOTES.md §1).
    rocker : rocker length l4 [m].
    swing : total handle swing [rad], 0 < swing < pi.
    handle : handle length H [m] (carried along for the force analysis).

    Returns
    -------
    Synthesis
        Broadcast over all inputs; infeasible designs carry a reason code and NaN lengths.
    """
    L1, D1, b, rocker, swing, handle = np.broadcast_arrays(*(np.asarray(v, float) for v in (L1, D1, b, rocker, swing, handle)))
    px, py = rocker_pivot(L1, D1, b)
    frame = frame_length(L1, D1, b)
    beta, psi1, psi2 = extreme_angles(L1, D1, b, swing)

    reason = np.full(frame.shape, FEASIBLE, dtype=np.int8)
    reason[psi1 >= np.pi - CHANGE_POINT_MARGIN] = SWING_CROSSES_FRAME_EXTENSION
    reason[psi2 <= CHANGE_POINT_MARGIN] = SWING_CROSSES_FRAME_LINE
    reason[frame <= 1e-9 * np.maximum(rocker, 1.0)] = PIVOT_ON_AXLE
    ok = reason == FEASIBLE
    nan = np.where(ok, 1.0, np.nan)

    d1 = _side(frame, rocker, psi1)  # Eq. (2): crank + coupler
    d2 = _side(frame, rocker, psi2)  # Eq. (2): coupler - crank
    # crank = (d1 - d2)/2 without cancellation for small cranks: d1^2 - d2^2 = 2 f r (cos psi2 - cos psi1)
    # = 4 f r sin((psi1 + psi2)/2) sin(swing/2), and (psi1 + psi2)/2 = pi - beta.
    crank = 2.0 * frame * rocker * np.sin(beta) * np.sin(0.5 * swing) / (d1 + d2) * nan  # Eq. (2)
    coupler = 0.5 * (d1 + d2) * nan

    # Rocker tips at the two extremes, and the crank angles that put A on the line O2-B.
    th_ext = 0.5 * np.pi + 0.5 * swing
    th_fold = 0.5 * np.pi - 0.5 * swing
    b1x, b1y = px + rocker * np.cos(th_ext), py + rocker * np.sin(th_ext)
    b2x, b2y = px + rocker * np.cos(th_fold), py + rocker * np.sin(th_fold)
    two_pi = 2.0 * np.pi
    dc_ext = np.mod(np.arctan2(b1y, b1x), two_pi) * nan  # crank along O2->B1
    dc_fold = np.mod(np.arctan2(b2y, b2x) + np.pi, two_pi) * nan  # crank opposite O2->B2
    # Crank travel (CCW) from the extended to the folded dead centre: the grip moves +x.
    plus = np.mod(dc_fold - dc_ext, two_pi)
    ratio = np.maximum(plus, two_pi - plus) / np.minimum(plus, two_pi - plus)

    # Assembly branch (the sign of q in pumplink.kinematics): q e^2 = -(B - A) x (O4 - A), whose sign
    # is constant over the cycle of a crank-rocker; at the extended dead centre it is
    # -sign(B1 x O4) = -sign(e1 x O4), with e1 the rocker direction there.
    cross = np.cos(th_ext) * py - np.sin(th_ext) * px
    branch = np.where(cross > 0, -1.0, 1.0) * nan

    gmin, gmax = transmission_range(frame, crank, coupler, rocker)
    gmin, gmax = gmin * nan, gmax * nan

    def out(a):
        return a[()] if a.ndim == 0 else a

    return Synthesis(
        frame_length=out(frame), beta=out(beta), psi1=out(psi1), psi2=out(psi2),
        crank_length=out(crank), coupler_length=out(coupler), rocker_length=out(rocker + 0.0),
        handle_length=out(handle + 0.0), swing=out(swing + 0.0), pivot_x=out(px), pivot_y=out(py),
        dead_centre_extended=out(dc_ext), dead_centre_folded=out(dc_fold), time_ratio=out(ratio),
        stroke_plus_x=out(plus), transmission_min=out(gmin), transmission_max=out(gmax),
        branch=out(branch), reason=out(reason),
    )


def infeasibility_reason(code, L1, D1, b, swing) -> str | None:
    """One sentence on why a design is infeasible and what to change (None when feasible).

    Parameters
    ----------
    code : reason code from :func:`synthesize` (scalar).
    L1, D1, b : frame placement [m];  swing : total handle swing [rad].
    """
    code = int(code)
    if code == FEASIBLE:
        return None
    reach = L1 + 0.5 * b
    half = 0.5 * np.degrees(swing)
    alpha = np.degrees(np.arctan2(D1, reach))
    if code == PIVOT_ON_AXLE:
        return "the rocker pivot is at the wheel axle (L1 + b/2 = 0 and D1 = 0); move it away from the axle"
    vertical = reach <= 0.0  # pivot straight below/above the axle: no D1 or swing helps
    if code == SWING_CROSSES_FRAME_LINE:
        limit_d1 = reach * np.tan(np.radians(90.0 - half))
        fix = ("place the pivot to the side of the axle (L1 + b/2 > 0)" if vertical else
               f"make D1 < {limit_d1:.4f} m, L1 larger, or the swing < {2 * (90 - alpha):.2f} deg")
        return (f"the frame line from the rocker pivot to the axle rises at {alpha:.2f} deg, so the handle's "
                f"forward extreme (rocker at {90 - half:.2f} deg) is not above it (psi2 = {90 - half - alpha:.2f} deg, "
                f"must be > 0) and no crank-rocker gives this swing; {fix}")
    if code == SWING_CROSSES_FRAME_EXTENSION:
        limit_d1 = -reach * np.tan(np.radians(90.0 - half))
        fix = ("place the pivot to the side of the axle (L1 + b/2 > 0)" if vertical else
               f"make D1 > {limit_d1:.4f} m (pivot less high), L1 larger, or the swing < {2 * (90 + alpha):.2f} deg")
        return (f"the frame line from the rocker pivot to the axle falls at {-alpha:.2f} deg, so the handle's "
                f"backward extreme (rocker at {90 + half:.2f} deg) passes the line's extension "
                f"(psi1 = {90 + half - alpha:.2f} deg, must be < 180) and no crank-rocker gives this swing; {fix}")
    raise ValueError(f"unknown reason code {code}")
