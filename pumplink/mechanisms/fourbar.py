"""The pump four-bar: dead-centre synthesis, positions, velocity ratio and quasi-static force.

Part 1, synthesis -- Dead-centre synthesis of the pump linkage (Eq. 1-2 of the pump paper, docs/physics.md).

Coordinates (product convention, docs/physics.md): origin at the wheel axle O2, x horizontal, y up,
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

Part 2, kinematics and force -- the full kinematic state and quasi-static force at crank angles
(:func:`kinematic_state`), from the closed-form loop closure of
:mod:`pumplink.mechanisms.fourbar_kernel` (whose docstring derives it, with the in-place force
kernel of the hot path).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from pumplink.mechanisms.angles import TWO_PI
from pumplink.mechanisms.bracket import find_minimum
from pumplink.mechanisms.fourbar_kernel import SINGULAR_SIN, alike_designs, coupler_height, loop_closure

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
class FourBar:
    """A pump four-bar in product coordinates (floats or broadcastable arrays).

    Attributes
    ----------
    pivot_x, pivot_y : rocker pivot O4 [m] (the crank pivot O2 is the origin).
    crank, coupler, rocker : link lengths [m].
    handle : distance from O4 to the hand grip along the rocker [m].
    branch : +1 or -1, the assembly branch; the coupler point is
        B = A + t (O4 - A) + branch * |h/e| * perp(O4 - A) (see ``pumplink.mechanisms.fourbar``).
    """

    pivot_x: np.ndarray | float
    pivot_y: np.ndarray | float
    crank: np.ndarray | float
    coupler: np.ndarray | float
    rocker: np.ndarray | float
    handle: np.ndarray | float
    branch: np.ndarray | float

    @property
    def parameters(self) -> tuple:
        """The seven parameters in field order (pivot_x, pivot_y, crank, coupler, rocker, handle, branch)."""
        return (self.pivot_x, self.pivot_y, self.crank, self.coupler, self.rocker, self.handle, self.branch)

    def __getitem__(self, idx) -> FourBar:
        """The designs ``idx`` of a four-bar held as arrays over designs (``lk[i]``, indexed as
        numpy indexes each parameter)."""
        return FourBar(*(np.asarray(v)[idx] for v in self.parameters))

    take = __getitem__


def per_design(lk: FourBar, *extra):
    """The four-bar's parameters and ``extra`` per-design values, broadcast together.

    Returns ``(scalar, arrays)``: True when every input was a scalar, and the 7 + len(extra)
    values as 1-D float arrays over designs (four-bar parameters first).
    """
    params = np.broadcast_arrays(*(np.asarray(v, float) for v in (*lk.parameters, *extra)))
    return params[0].ndim == 0, [np.atleast_1d(p).ravel() for p in params]


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
    rocker_angle_extended: np.ndarray | float | None = None  # built linkages (analyse) only [rad]
    rocker_angle_folded: np.ndarray | float | None = None

    @property
    def feasible(self) -> np.ndarray | bool:
        """True where the design is a crank-rocker with the requested swing."""
        return self.reason == FEASIBLE

    @property
    def linkage(self) -> FourBar:
        """The synthesised four-bar, for the kinematics and force functions."""
        return FourBar(
            self.pivot_x,
            self.pivot_y,
            self.crank_length,
            self.coupler_length,
            self.rocker_length,
            self.handle_length,
            self.branch,
        )


def rocker_pivot(L1, D1, b):
    """Rocker pivot O4 relative to the wheel axle [m] (docs/physics.md).

    Returns
    -------
    x, y : O4 = (-(L1 + b/2), -D1)
    """
    return -(np.asarray(L1, float) + 0.5 * np.asarray(b, float)), -np.asarray(D1, float)


def frame_length(L1, D1, b):
    """Frame length O2-O4 [m], Eq. (1) of the pump paper as read in docs/physics.md."""
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


def grip_stroke(handle, swing):
    """Horizontal stroke of the grip, S = 2 H sin(swing/2) [m] (docs/physics.md §4).

    Parameters
    ----------
    handle : H [m];  swing : total handle swing [rad].
    """
    return 2.0 * handle * np.sin(0.5 * swing)


def grip_heights(axle_height, D1, handle, swing):
    """Lowest and highest grip height above the ground over the swing [m] (docs/physics.md §1).

    The rocker pivot is D1 below the axle and the handle swings symmetrically about the
    vertical, so the grip is lowest at the ends of the swing, H cos(swing/2) above the pivot,
    and highest, H above it, when the handle is upright.

    Parameters
    ----------
    axle_height : wheel-axle height above the ground [m];  D1 : pivot depth below the axle [m];
    handle : H [m];  swing : total handle swing [rad].
    """
    pivot = np.asarray(axle_height, float) - D1
    return pivot + handle * np.cos(0.5 * np.asarray(swing, float)), pivot + handle


#: Crank angles per revolution on which :func:`peak_rocker_rate` starts its search.
RATE_GRID = 180


#: Designs whose grid of rocker rates is evaluated at once in :func:`peak_rocker_rate`: their
#: (designs x RATE_GRID) temporaries stay in the processor's cache.
RATE_DESIGNS = 128


def _abs_rate(theta, px, py, c, k, r, h, br):
    """|dθ4/dθ2| at crank angles: the rocker rate of :func:`kinematic_state` (the same operations,
    so the same bits), computing nothing else."""
    cs, sn = np.cos(theta), np.sin(theta)
    p1 = cs * px + sn * py
    p2 = cs * py - sn * px
    e2 = (px * px + py * py + c * c) - 2.0 * c * p1
    t = 0.5 + 0.5 * (k * k - r * r) / e2
    q = br * coupler_height(e2, k, r)
    w = t * p2 + q * (p1 - c)
    return np.abs(-c * w / (q * e2))  # omega4/omega2 = (A x u)/(R x u)


def peak_rocker_rate(lk: FourBar):
    """Largest |d theta4 / d theta2| over a revolution [-]: the grip's peak speed is this times
    the wheel speed times H (docs/physics.md §4).

    A crank-rocker's rocker rate is smooth and finite over the whole revolution (it is zero at
    the dead centres), so the maximum is interior: found on a grid of :data:`RATE_GRID` points
    and refined with a bracketing minimiser (:func:`pumplink.mechanisms.bracket.find_minimum`)
    to solver tolerance.  NaN for an infeasible
    design.
    """
    scalar, geom = per_design(lk)
    step = 2.0 * np.pi / RATE_GRID
    theta = np.arange(RATE_GRID) * step
    g2 = [p[:, None] for p in geom]
    with np.errstate(all="ignore"):
        val = np.empty((geom[0].size, RATE_GRID))
        for d0 in range(0, geom[0].size, RATE_DESIGNS):  # cache-sized blocks: the same values
            d = slice(d0, d0 + RATE_DESIGNS)
            val[d] = _abs_rate(theta[None, :], *(p[d] for p in g2))
        val = np.where(np.isnan(val), -np.inf, val)
        j = np.argmax(val, axis=1)
        mid = theta[j]
        res = find_minimum(
            lambda x, *a: -_abs_rate(x, *a),
            (mid - step, mid, mid + step),
            args=tuple(geom),
            tolerances=dict(xatol=1e-13, xrtol=1e-15),
        )
    best = np.take_along_axis(val, j[:, None], 1)[:, 0]
    peak = np.where(res.success, np.maximum(-res.f_x, best), best)
    peak = np.where(np.isfinite(geom[2]) & np.isfinite(peak), peak, np.nan)
    return float(peak[0]) if scalar else peak


def transmission_range(frame, crank, coupler, rocker):
    """Extreme transmission angles of a crank-rocker [rad] (docs/crank-rocker.md, Eq. 4-5) of the
    optimal-transmission paper.

    The coupler-rocker angle is extreme when crank and frame are collinear:
    cos gamma = (coupler^2 + rocker^2 - (frame -+ crank)^2) / (2 coupler rocker).
    """
    den = 2.0 * coupler * rocker
    # Products, not ``** 2``, so scalars and arrays round identically (see ``_side``).
    near, far = frame - crank, frame + crank
    cmin = (
        coupler * coupler + rocker * rocker - near * near
    ) / den  # Eq. (4) of the optimal-transmission paper
    cmax = (
        coupler * coupler + rocker * rocker - far * far
    ) / den  # Eq. (5) of the optimal-transmission paper
    return np.arccos(np.clip(cmin, -1.0, 1.0)), np.arccos(np.clip(cmax, -1.0, 1.0))


def synthesize(L1, D1, b, rocker, swing, handle=1.0) -> Synthesis:
    """Dead-centre synthesis: crank and coupler lengths from the frame and the handle swing.

    At the rocker's extremes crank and coupler are collinear, so |O2 B| = crank + coupler
    (extended, psi1) or coupler - crank (folded, psi2); Eq. (2) of the pump paper:
    coupler = (d1 + d2)/2, crank = (d1 - d2)/2.

    Parameters
    ----------
    L1, D1, b : frame placement [m] (docs/physics.md).
    rocker : rocker length l4 [m].
    swing : total handle swing [rad], 0 < swing < pi.
    handle : handle length H [m] (carried along for the force analysis).

    Returns
    -------
    Synthesis
        Broadcast over all inputs; infeasible designs carry a reason code and NaN lengths.
    """
    L1, D1, b, rocker, swing, handle = np.broadcast_arrays(
        *(np.asarray(v, float) for v in (L1, D1, b, rocker, swing, handle))
    )
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

    # Assembly branch (the sign of q in pumplink.mechanisms.fourbar): q e^2 = -(B - A) x (O4 - A), whose sign
    # is constant over the cycle of a crank-rocker; at the extended dead centre it is
    # -sign(B1 x O4) = -sign(e1 x O4), with e1 the rocker direction there.
    cross = np.cos(th_ext) * py - np.sin(th_ext) * px
    branch = np.where(cross > 0, -1.0, 1.0) * nan

    gmin, gmax = transmission_range(frame, crank, coupler, rocker)
    gmin, gmax = gmin * nan, gmax * nan

    def out(a):
        return a[()] if a.ndim == 0 else a

    return Synthesis(
        frame_length=out(frame),
        beta=out(beta),
        psi1=out(psi1),
        psi2=out(psi2),
        crank_length=out(crank),
        coupler_length=out(coupler),
        rocker_length=out(rocker + 0.0),
        handle_length=out(handle + 0.0),
        swing=out(swing + 0.0),
        pivot_x=out(px),
        pivot_y=out(py),
        dead_centre_extended=out(dc_ext),
        dead_centre_folded=out(dc_fold),
        time_ratio=out(ratio),
        stroke_plus_x=out(plus),
        transmission_min=out(gmin),
        transmission_max=out(gmax),
        branch=out(branch),
        reason=out(reason),
    )


#: Reason code of a built linkage whose crank cannot turn fully (not a Grashof crank-rocker with
#: the crank the shortest link).
NOT_A_CRANK_ROCKER = 4


def analyse(lk: FourBar) -> Synthesis:
    """A built four-bar as it is: its dead centres, actual swing, time ratio and transmission
    angles from the link lengths and the pivot, with nothing re-synthesised (a workshop's linkage,
    whose holes are where they were drilled).

    The dead centres are where crank and coupler line up (|O2 B| = crank + coupler, extended, or
    coupler - crank, folded), B on the rocker's circle on the linkage's assembly branch; the
    rocker's extreme angles follow, and the swing is their difference (not symmetric about the
    vertical in general).  ``reason`` is 0 for a crank-rocker whose crank turns fully (Grashof,
    crank the shortest link), :data:`NOT_A_CRANK_ROCKER` otherwise (lengths NaN then).

    Returns
    -------
    Synthesis
        Over the designs of ``lk`` (1-D arrays or floats); ``swing`` the actual swing,
        ``rocker_angle_extended``/``rocker_angle_folded`` the rocker's angle at each dead centre.
    """
    scalar, geom = per_design(lk)
    px, py, c, k, r, h, br = geom
    frame = np.hypot(px, py)
    links = np.stack([frame, c, k, r])
    shortest, longest = links.min(axis=0), links.max(axis=0)
    ok = (c <= shortest) & (shortest + longest < links.sum(axis=0) - shortest - longest)
    nan = np.where(ok, 1.0, np.nan)
    angles, rockers = [], []
    with np.errstate(all="ignore"):
        for dist, flip in ((c + k, 0.0), (k - c, np.pi)):
            # B on circle(O2, dist) and circle(O4, r): the two points, the branch's one kept
            a = (dist * dist - r * r + frame * frame) / (2.0 * frame)
            hh = np.sqrt(np.maximum(dist * dist - a * a, 0.0))
            ux, uy = px / frame, py / frame
            cands = []
            for sgn in (1.0, -1.0):
                bx = a * ux - sgn * hh * uy
                by = a * uy + sgn * hh * ux
                crank = np.mod(np.arctan2(by, bx) + flip, TWO_PI)
                st = _kinematic_state(FourBar(px, py, c, k, r, h, br), crank, 1.0)
                cands.append(
                    (crank, np.hypot(st.coupler_x - bx, st.coupler_y - by), np.arctan2(by - py, bx - px))
                )
            pick = cands[0][1] <= cands[1][1]
            angles.append(np.where(pick, cands[0][0], cands[1][0]) * nan)
            rockers.append(np.where(pick, cands[0][2], cands[1][2]) * nan)
    dce, dcf = angles
    t4e, t4f = rockers
    plus = np.mod(dcf - dce, TWO_PI)
    ratio = np.maximum(plus, TWO_PI - plus) / np.minimum(plus, TWO_PI - plus)
    gmin, gmax = transmission_range(frame, c, k, r)
    to_o2 = np.arctan2(-py, -px)  # the frame line O4 -> O2
    psi = [np.abs(np.mod(t - to_o2 + np.pi, TWO_PI) - np.pi) for t in (t4e, t4f)]
    reason = np.where(ok, FEASIBLE, NOT_A_CRANK_ROCKER).astype(np.int8)

    def out(x):
        x = np.asarray(x, float)
        return float(x[0]) if scalar else x

    return Synthesis(
        frame_length=out(frame),
        beta=out(np.nan * frame),
        psi1=out(psi[0]),
        psi2=out(psi[1]),
        crank_length=out(c * nan),
        coupler_length=out(k * nan),
        rocker_length=out(r + 0.0),
        handle_length=out(h + 0.0),
        swing=out(np.abs(np.mod(t4e - t4f + np.pi, TWO_PI) - np.pi)),
        pivot_x=out(px),
        pivot_y=out(py),
        dead_centre_extended=out(dce),
        dead_centre_folded=out(dcf),
        time_ratio=out(ratio),
        stroke_plus_x=out(plus),
        transmission_min=out(gmin * nan),
        transmission_max=out(gmax * nan),
        branch=out(br * nan),
        reason=reason[0] if scalar else reason,
        rocker_angle_extended=out(t4e),
        rocker_angle_folded=out(t4f),
    )


def built_grip(axle_height, pivot_y, handle, rocker_angle_extended, rocker_angle_folded):
    """The grip's horizontal stroke and its lowest and highest height above the ground over the
    swing of a built linkage [m] (the rocker swings between its two extreme angles, not
    necessarily symmetric about the vertical; y up from the axle, the ground ``axle_height``
    below it)."""
    a, b = (
        np.minimum(rocker_angle_extended, rocker_angle_folded),
        np.maximum(rocker_angle_extended, rocker_angle_folded),
    )
    stroke = handle * np.abs(np.cos(a) - np.cos(b))
    ends = np.minimum(np.sin(a), np.sin(b))
    top = np.where((a <= 0.5 * np.pi) & (b >= 0.5 * np.pi), 1.0, np.maximum(np.sin(a), np.sin(b)))
    pivot = np.asarray(axle_height, float) + pivot_y
    return stroke, pivot + handle * ends, pivot + handle * top


def distinct_peak_rocker_rate(lk: FourBar) -> np.ndarray:
    """:func:`peak_rocker_rate` of designs (1-D arrays), solved once per kind of linkage alike bit
    for bit (:func:`pumplink.mechanisms.fourbar_kernel.alike_designs`): it depends on the geometry
    alone, and a grid that varies the load or the speed repeats each geometry many times (the same
    values, computed once)."""
    first, kind = alike_designs(*lk.parameters)
    if first is None:  # one design, mostly distinct ones, or a hash collision: each on its own
        return np.atleast_1d(peak_rocker_rate(lk))
    return peak_rocker_rate(lk[first])[kind]


class Geometry(NamedTuple):
    """What the geometry of pump designs gives (:func:`pump_geometry`): the synthesis (or the
    analysis of a built linkage), the handle H and rocker lengths [m], the grip's horizontal
    stroke [m] and its lowest and highest heights above the ground (None without an axle
    height) [m], and the rocker's largest rate max|dθ4/dθ2| of each feasible design [-] (NaN
    elsewhere; docs/models.md §4)."""

    synthesis: Synthesis
    handle: np.ndarray | float
    rocker: np.ndarray | float
    stroke: np.ndarray | float
    grip_height: tuple | None
    rocker_rate: np.ndarray


def pump_geometry(L1, D1, b, rocker, swing, handle, axle_height=None, built: FourBar | None = None,
                  designs: int | None = None) -> Geometry:  # fmt: skip
    """The geometry of pump designs: the dead-centre synthesis of the spec's L1, D1, b, rocker,
    swing and handle (Eq. 1-2 of the pump paper, :func:`synthesize`) with the grip's stroke
    S = 2 H sin(swing/2) and heights (docs/physics.md §1, §4); or, for a ``built`` linkage (a
    workshop's holes), its analysis (:func:`analyse`: not re-synthesised), over ``designs``
    designs, with the grip's stroke and heights between the rocker's extreme angles
    (:func:`built_grip`); and the rocker's largest rate of each feasible design
    (:func:`distinct_peak_rocker_rate`).  Arrays broadcast over designs; ``axle_height`` None: no
    heights."""
    if built is None:
        syn = synthesize(L1, D1, b, rocker, swing, handle)
        stroke = grip_stroke(handle, swing)
        heights = None if axle_height is None else grip_heights(axle_height, D1, handle, swing)
        return Geometry(syn, handle, rocker, stroke, heights, _rates(syn))
    _, params = per_design(built, np.zeros(designs or 1))
    built = FourBar(*params[:7])
    syn = analyse(built)
    ends = (syn.rocker_angle_extended, syn.rocker_angle_folded)
    stroke = built_grip(0.0, built.pivot_y, built.handle, *ends)[0]
    heights = None if axle_height is None else built_grip(axle_height, built.pivot_y, built.handle, *ends)[1:]
    return Geometry(syn, built.handle, built.rocker, stroke, heights, _rates(syn))


def _rates(syn: Synthesis) -> np.ndarray:
    """:func:`distinct_peak_rocker_rate` of the feasible designs (NaN elsewhere), as 1-D arrays."""
    feasible = np.atleast_1d(np.asarray(syn.feasible, bool))
    out = np.full(feasible.shape, np.nan)
    ok = np.nonzero(feasible)[0]
    if ok.size:
        out[ok] = distinct_peak_rocker_rate(FourBar(*(np.atleast_1d(v) for v in syn.linkage.parameters))[ok])
    return out


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
        fix = (
            "place the pivot to the side of the axle (L1 + b/2 > 0)"
            if vertical
            else f"make D1 < {limit_d1:.4f} m, L1 larger, or the swing < {2 * (90 - alpha):.2f} deg"
        )
        return (
            f"the frame line from the rocker pivot to the axle rises at {alpha:.2f} deg, so the handle's "
            f"forward extreme (rocker at {90 - half:.2f} deg) is not above it "
            f"(psi2 = {90 - half - alpha:.2f} deg, "
            f"must be > 0) and no crank-rocker gives this swing; {fix}"
        )
    if code == SWING_CROSSES_FRAME_EXTENSION:
        limit_d1 = -reach * np.tan(np.radians(90.0 - half))
        fix = (
            "place the pivot to the side of the axle (L1 + b/2 > 0)"
            if vertical
            else f"make D1 > {limit_d1:.4f} m (pivot less high), L1 larger, "
            f"or the swing < {2 * (90 + alpha):.2f} deg"
        )
        return (
            f"the frame line from the rocker pivot to the axle falls at {-alpha:.2f} deg, so the handle's "
            f"backward extreme (rocker at {90 + half:.2f} deg) passes the line's extension "
            f"(psi1 = {90 + half - alpha:.2f} deg, must be < 180) and no crank-rocker gives this swing; {fix}"
        )
    raise ValueError(f"unknown reason code {code}")


# ----------------------------------------------------------------------------- kinematics and force
@dataclass(frozen=True)
class State:
    """Kinematic state and quasi-static force at given crank angles (SI units, radians).

    Attributes
    ----------
    crank_angle : crank angle t2 [rad].
    coupler_x, coupler_y : coupler-rocker joint B [m].
    rocker_angle : rocker (and handle) angle t4, CCW from +x [rad].
    rocker_rate : d t4 / d t2 [-] (omega4 / omega2).
    handle_rate : dPx / d t2, horizontal grip travel per crank radian [m/rad].
    transmission_angle : angle between coupler and rocker at B [rad].
    force : horizontal operator force at the grip [N], +x positive, NaN where ``singular``.
    singular : True at a dead centre (crank and coupler collinear).
    """

    crank_angle: np.ndarray
    coupler_x: np.ndarray
    coupler_y: np.ndarray
    rocker_angle: np.ndarray
    rocker_rate: np.ndarray
    handle_rate: np.ndarray
    transmission_angle: np.ndarray
    force: np.ndarray
    singular: np.ndarray


def kinematic_state(lk: FourBar, crank_angle, wheel_torque=1.0) -> State:
    """Full kinematic state and handle force at crank angles [rad] (the ``vector`` method).

    Parameters
    ----------
    lk : the linkage (from :attr:`pumplink.mechanisms.fourbar.Synthesis.linkage`).
    crank_angle : crank angles t2 [rad], any shape broadcastable with the linkage.
    wheel_torque : load torque Mw = Fw rw [N m] (Eq. 3 of the pump paper).
    """
    with np.errstate(all="ignore"):  # dead centres and non-assemblable inputs give NaN/inf, by design
        return _kinematic_state(lk, np.asarray(crank_angle, float), wheel_torque)


def _kinematic_state(lk: FourBar, th, wheel_torque) -> State:
    cs, sn = np.cos(th), np.sin(th)
    px, py, c, k, r = lk.pivot_x, lk.pivot_y, lk.crank, lk.coupler, lk.rocker
    p1, p2, e2, t, q = loop_closure(lk, cs, sn)
    dx, dy = px - c * cs, py - c * sn
    bx = c * cs + t * dx - q * dy
    by = c * sn + t * dy + q * dx
    rx, ry = bx - px, by - py
    w = t * p2 + q * (p1 - c)
    singular = np.abs(w) <= SINGULAR_SIN * k
    rate = -c * w / (q * e2)  # omega4/omega2 = (A x u)/(R x u)
    handle_rate = -(lk.handle / r) * ry * rate
    force = np.where(singular, np.nan, wheel_torque / handle_rate)  # Eq. (3), virtual work
    cos_g = (k * k + r * r - e2) / (2.0 * k * r)  # law of cosines in A-B-O4
    return State(
        th,
        bx,
        by,
        np.arctan2(ry, rx),
        rate,
        handle_rate,
        np.arccos(np.clip(cos_g, -1.0, 1.0)),
        force,
        singular,
    )
