"""The grip's travel G along the crank angle: the horizontal distance the grip covers.

Px (the grip's horizontal position) is monotone between the dead centres, so the travel G(s, t)
over an arc (its total variation, |dPx| summed) comes from positions, except within
TRAVEL_INTEGRATION_ARC of a dead centre, where positions cancel and it is integrated from the
rate dPx/dt2 (Gauss-Legendre).  Shared by the flywheel's (:mod:`pumplink.models.flywheel_solver`)
and full dynamics' (:mod:`pumplink.models.dynamics_solver`) solvers (docs/models.md §2, §3a).

Pure functions on floats / arrays over designs; SI units, radians.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from pumplink.mechanisms.angles import TWO_PI
from pumplink.mechanisms.fourbar import FourBar
from pumplink.mechanisms.fourbar_kernel import loop_closure


# ----------------------------------------------------------------------------- grip travel G
def grip_position(theta, px, py, crank, coupler, rocker, handle, branch):
    """Horizontal grip position Px [m] at crank angles theta (vector loop closure)."""
    cs, sn = np.cos(theta), np.sin(theta)
    lk = FourBar(px, py, crank, coupler, rocker, handle, branch)
    _p1, _p2, _e2, t, q = loop_closure(lk, cs, sn)
    dx, dy = px - crank * cs, py - crank * sn
    bx = crank * cs + t * dx - q * dy  # Eq. (6) as a vector (pumplink.mechanisms.fourbar)
    return px + (handle / rocker) * (bx - px)


#: Within this crank angle [rad] of a dead centre the grip travel is integrated (Gauss-Legendre on
#: |dPx/dt2|) instead of taken from position differences, which cancel there: the deficit arc
#: around a dead centre has travel ~ kappa a^2 / 2, far below the rounding of positions for small bands.
TRAVEL_INTEGRATION_ARC = 0.02
#: Gauss-Legendre nodes on [-1, 1] and their weights (12 points) of the travel integration.
GAUSS_LEGENDRE_NODES, GAUSS_LEGENDRE_WEIGHTS = np.polynomial.legendre.leggauss(12)


def grip_rate(theta, px, py, crank, coupler, rocker, handle, branch):
    """dPx/dt2 [m/rad] (the kinematics of ``pumplink.mechanisms.fourbar``, no cancellation at a
    dead centre)."""
    cs, sn = np.cos(theta), np.sin(theta)
    p1, p2, e2, t, q = loop_closure(FourBar(px, py, crank, coupler, rocker, handle, branch), cs, sn)
    dx, dy = px - crank * cs, py - crank * sn
    ry = crank * sn + t * dy + q * dx - py
    w = t * p2 + q * (p1 - crank)
    # -(H/rocker) Ry omega4/omega2, with omega4/omega2 = -crank w / (q e^2)
    return (handle / rocker) * ry * crank * w / (q * e2)


def travel_parts(
    phi,
    px,
    py,
    crank,
    coupler,
    rocker,
    handle,
    branch,
    dce,
    plus,
    xe,
    xf,
    stroke,
    integrate=True,
    grip_x=None,
):
    """Grip travel G = base + local [m] from the extended dead centre to crank angle dce + phi.

    ``base`` is G at the nearest dead centre (0, S or 2S, plus 2S per full turn of the unrolled
    phi); ``local`` the signed travel from it.  Px is monotone between the dead centres, so away
    from them local comes from positions; within TRAVEL_INTEGRATION_ARC it is integrated from the rate.
    Differences of G near one dead centre are then (local - local): no cancellation.
    ``integrate=False``: from positions everywhere (absolute error ~1e-16 m; enough to rank arcs).
    ``grip_x``: Px at crank angles dce + phi as :func:`grip_position` gives it (from a caller that has the
    loop closure there already), used where phi lies in the first turn [0, 2 pi).
    """
    turns = np.floor(phi / TWO_PI)
    first = not turns.any()  # phi in its first turn (the usual case): p is phi, no turn's travel
    p = phi if first else phi - turns * TWO_PI
    # nearest dead centre: 0 (extended), plus (folded) or 2 pi (extended, next turn)
    to_fold = p - plus
    back = TWO_PI - p
    at_fold = np.abs(to_fold) <= np.minimum(p, back)
    s = np.where(at_fold, to_fold, np.where(p <= back, p, p - TWO_PI))  # signed offset from it
    base = np.where(at_fold, stroke, np.where(s >= 0, 0.0, 2.0 * stroke))
    if not first or not np.isfinite(stroke).all():  # else 2 S turns is 0 and adds nothing
        base = base + 2.0 * stroke * turns
    if grip_x is not None and first:  # p is phi: Px at dce + phi is given
        x = grip_x
    else:
        x = grip_position(dce + p, px, py, crank, coupler, rocker, handle, branch)
    ref = np.where(at_fold, xf, xe)
    local = np.sign(s) * np.abs(x - ref)
    near = np.abs(s) < TRAVEL_INTEGRATION_ARC
    if integrate and np.any(near):
        at = np.nonzero(near) if near.ndim else near  # the few angles near a dead centre, found once

        def pick(v):
            return np.broadcast_to(v, s.shape)[at]

        geom = [pick(v) for v in (px, py, crank, coupler, rocker, handle, branch)]
        dc = np.where(pick(at_fold), pick(dce) + pick(plus), pick(dce))
        sn = s[at]
        t = 0.5 * sn[..., None] * (1.0 + GAUSS_LEGENDRE_NODES)  # nodes on (0, s)
        g = grip_rate(dc[..., None] + t, *(v[..., None] for v in geom))
        local[at] = 0.5 * sn * (np.abs(g) * GAUSS_LEGENDRE_WEIGHTS).sum(axis=-1)  # not @: no BLAS threads
    return base, local


def travel(phi, *args):
    """Grip travel G [m] from the extended dead centre to crank angle dce + phi (phi unrolled)."""
    base, local = travel_parts(phi, *args)
    return base + local


def crank_nodes(dce, dcf, grid, cluster):
    """Grid nodes phi in [0, 2 pi) per design, sorted, shape (D, M): uniform (half-cell offset)
    plus geometric clusters at both dead centres (phi = 0 and phi = plus)."""
    h = TWO_PI / grid
    plus = np.mod(dcf - dce, TWO_PI)
    uni = (np.arange(grid) + 0.5) * h
    off = h * 4.0 ** -np.arange(1, cluster + 1)  # h/4 ... : inside the first half cell
    near0 = np.concatenate([off, TWO_PI - off, [0.0]])
    nearp = np.concatenate([-off, off, [0.0]])
    x = np.concatenate(
        [
            np.broadcast_to(uni, plus.shape + uni.shape),
            np.broadcast_to(near0, plus.shape + near0.shape),
            np.mod(plus[:, None] + nearp, TWO_PI),
        ],
        axis=1,
    )
    return np.sort(x, axis=1), plus


@dataclass(frozen=True)
class Prepared:
    """One problem's geometry at the grid nodes, shared by the flywheel's and full dynamics'
    solvers: the four-bar, the dead centres and the crank travel between them, the grip's Px at
    both, the stroke, Mw, and the grip travel (base + local) at each node."""

    geom: tuple  # px, py, crank, coupler, rocker, handle, branch as (D,) arrays
    dce: np.ndarray
    plus: np.ndarray
    xe: np.ndarray
    xf: np.ndarray
    stroke: np.ndarray
    mw: np.ndarray
    nodes: np.ndarray  # (D, M)
    base: np.ndarray  # (D, M) grip travel at the nearest dead centre [m]
    local: np.ndarray  # (D, M) signed travel from it [m]

    def args(self, idx=slice(None)):
        g = tuple(p[idx] for p in self.geom)
        return g + (self.dce[idx], self.plus[idx], self.xe[idx], self.xf[idx], self.stroke[idx])


def node_travel(nodes, plus, grip_x, xe, xf, stroke):
    """Grip travel G = base + local [m] at the grid nodes from their positions: the split at the
    nearest dead centre of :func:`travel_parts`, without its integration
    next to a dead centre.  The grid only brackets the extrema and starts the iteration (every
    reported force comes from refined points, whose travel is integrated there), so position
    differences, exact to ~1e-16 m, are enough."""
    to_fold = nodes - plus
    at_fold = np.abs(to_fold) <= np.minimum(nodes, TWO_PI - nodes)
    s = np.where(at_fold, to_fold, np.where(nodes <= TWO_PI - nodes, nodes, nodes - TWO_PI))
    base = np.where(at_fold, stroke, np.where(s >= 0, 0.0, 2.0 * stroke))
    return base, np.sign(s) * np.abs(grip_x - np.where(at_fold, xf, xe))
