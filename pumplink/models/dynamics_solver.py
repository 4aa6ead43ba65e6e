"""Full dynamics: the least peak operator force, exactly (docs/models.md §3, the proof; §3a).

In the scene of :mod:`pumplink.models.dynamics_terms` (E = T + V inside the band of its Eq. (8)):
with |F| <= Fp the slope of E lies in [-Fp |g| - Mw, Fp |g| - Mw]; with G the grip's horizontal
travel (|dPx| summed), Q = Fp G - Mw t and P = -Fp G - Mw t are the fastest gain and the fastest
loss.  A periodic motion inside the band exists **iff** Fp >= F_mean and, over every arc shorter
than a revolution,

    (C1) t <= s:  lower(s) - upper(t) <= Q(s) - Q(t)   (from the top at t, full push reaches s)
    (C2) s <= t:  upper(t) - lower(s) >= P(t) - P(s)   (from the bottom at s, full braking stays
                                                          below the top at t)

and then the largest motion, e = min(Q + running min of (upper - Q) over the past revolution,
P + running min of (upper - P) over the next one), is one.  Both are linear in Fp, so the least
peak force is a fractional programme over pairs of crank angles, solved by Dinkelbach's iteration
on grid nodes (plus nodes clustered at the dead centres), then with every local extremum of the
four functions upper - Q, lower - Q, lower - P, upper - P refined by a bracketing root search on
their derivatives (analytic: I', V' from the acceleration analysis).  Pure functions on floats /
arrays over designs; SI units, radians.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from pumplink.constants import GRAVITY
from pumplink.mechanisms.angles import TWO_PI
from pumplink.mechanisms.fourbar import FourBar, per_design
from pumplink.mechanisms.fourbar_kernel import alike_designs
from pumplink.models import flywheel_solver as _fs
from pumplink.models import quasi_static as _qs
from pumplink.models.conditions import Masses
from pumplink.models.dynamics_terms import COEFFICIENT_COUNT, coefficients, speed_limits, terms_from
from pumplink.models.grip_travel import Prepared, crank_nodes, grip_position, node_travel, travel_parts

#: Uniform grid nodes per revolution that bracket the extrema before refinement (the refinement
#: makes the answer exact; features of the four functions narrower than a cell, 3.75 deg, are merged).
GRID = 96
#: Geometric nodes each side of a dead centre, at cell / 4**k for k = 1..CLUSTER (down to ~1e-5 rad).
CLUSTER = 6
#: Designs solved together: their (designs, nodes) arrays stay in the processor's cache (a third
#: faster than one pass over 5,000 designs, benchmarks/bench_dynamics.py).
CHUNK = 1024
#: Relative convergence of Dinkelbach's iteration on the peak force.
RTOL = 1e-13
#: Relative convergence of the iteration over the grid nodes (it only says where to refine).
GRID_RTOL = 1e-3
#: Designs from which the iteration over the grid nodes first runs on a quarter of them (fewer
#: passes over the whole grid; on fewer designs the cost is per call, not per node, and the quarter
#: does not pay: it ends on the same force, the same pair's ratio, on every design tried).
QUARTER_FROM = 48
#: Largest relative step of the force after which the next pass only follows the extrema already
#: found (the passes converge quadratically; the last pass always looks at the whole grid).
TRACK_RTOL = 1e-9
#: Peak forces above this multiple of F_mean are reported as infinite (as in the flywheel scene).
FORCE_CAP_RATIO = _fs.FORCE_CAP_RATIO
#: A Newton step [rad] below which the extremum refinement stops (its error is then of second
#: order, below 1e-14 rad; the value of the function, flat at an extremum, is exact to rounding).
REFINE_XTOL = 1e-8
#: Most iterations of the bracketed refinement (safeguarded Newton: 3-5 in practice).
REFINE_ITER = 60
#: Most Newton steps of a warm start from the previous pass's root before the bracketed search.
WARM_ITER = 3
#: Finite-difference step of the refinement's Newton iteration, as a fraction of the bracket.
REFINE_STEP = 1e-6


#: Designs from which a running minimum loops over the columns (:func:`_running_min`).
RUN_DESIGNS = 256
#: Evaluations of the terms on at most this many points take per-point copies of the per-design
#: constants: a ufunc that broadcasts costs twice or three times one on equal shapes when the
#: arrays are small (optimize's batches of 1-25 designs); larger ones broadcast (less memory).
_SMALL = 4096


# ----------------------------------------------------------------------------- the solver
@dataclass(frozen=True)
class DynamicsProblem:
    """Per-design data (1-D arrays over D designs) and the band's edges at the grid nodes (D, M)."""

    prep: object  # grip_travel.Prepared: geometry, dead centres, stroke, grip travel at the nodes
    lk: FourBar  # (D,) arrays
    inertia: np.ndarray
    masses: Masses  # (D,) arrays
    w_lo: np.ndarray
    w_hi: np.ndarray
    gravity: float
    mw: np.ndarray
    stroke: np.ndarray
    up: np.ndarray | None  # upper edge of the band at the nodes (D, M) [J]
    lo: np.ndarray | None  # lower edge [J]
    design: np.ndarray  # per design (columns): the constants of coefficients, then Mw, dce,
    # w_hi^2 / 2, w_lo^2 / 2 and J (rows COEFFICIENT_COUNT ... COEFFICIENT_COUNT + 4)
    travel: list  # the grip-travel arguments of pumplink.models.grip_travel as columns (D, 1)

    def points(self, rows=None):
        """The grid nodes of designs ``rows`` (all: None) as points (x, base, local, up, lo)."""
        p = self.prep
        if rows is None:
            return p.nodes, p.base, p.local, self.up, self.lo
        return p.nodes[rows], p.base[rows], p.local[rows], self.up[rows], self.lo[rows]

    def edges(self, phi, rows=None, fly_x: bool = False):
        """upper and lower edge of the band [J] at points phi [rad from the extended dead centre],
        shape (R, K), of the designs ``rows`` (R,) (all: None).  ``fly_x``: also the grip's Px [m]
        as :func:`pumplink.models.grip_travel.grip_position` computes it."""
        every = rows is None or rows.size == self.mw.size  # rows are sorted and distinct: all
        dm = self.design if every else self.design.take(rows, axis=1)
        if phi.size <= _SMALL:
            dm = np.repeat(dm[:, :, None], phi.shape[1], axis=2)
        else:
            dm = dm[:, :, None]
        co, (_mw, dce, hi, lo, j) = dm[:COEFFICIENT_COUNT], dm[COEFFICIENT_COUNT:]
        with np.errstate(all="ignore"):
            tm = terms_from(co, dce + phi, self.gravity, rates=False, fly_x=fly_x, grip=False)
            i = j + tm[0]
            out = tm[2] + i * hi, tm[2] + i * lo  # Eq. (8) of pumplink.models.dynamics_terms
        return (*out, tm[6]) if fly_x else out


def problem(lk, dce, dcf, wheel_torque, inertia, masses, mean_speed, speed_fluctuation, gravity):
    scalar, arrays = per_design(
        lk,
        dce,
        dcf,
        wheel_torque,
        inertia,
        masses.coupler,
        masses.handle,
        masses.grip,
        mean_speed,
        speed_fluctuation,
    )
    return _problem_of(arrays, gravity), scalar


def _problem_of(arrays, gravity) -> DynamicsProblem:
    """:func:`problem` of the 1-D arrays of :func:`pumplink.mechanisms.fourbar.per_design`."""
    geom, (dce, dcf, mw, j, mc, mh, ma, w, delta) = arrays[:7], arrays[7:]
    lk1 = FourBar(*geom)
    ms = Masses(mc, mh, ma)
    w_lo, w_hi = speed_limits(w, delta)
    with np.errstate(all="ignore"):
        co = coefficients(lk1, ms)
        kin = (0.5 * w_hi**2, 0.5 * w_lo**2)
        xe, xf = grip_position(np.stack([dce, dcf]), *geom)  # both dead centres in one call
        stroke = np.abs(xf - xe)
        # the links' terms and the grip's travel at the nodes depend on the linkage and the masses
        # only: designs alike in those (a grid's variants that differ in the load or the wheel) share
        # them, computed once (the same operations per design, so the same values)
        first, inverse = alike_designs(*geom, dce, dcf, mc, mh, ma)
        u = slice(None) if first is None else first
        nodes, plus = crank_nodes(dce[u], dcf[u], GRID, CLUSTER)
        tm = terms_from([v[u, None] for v in co], dce[u, None] + nodes, gravity, rates=False)
        base, local = node_travel(nodes, plus[:, None], tm[5], xe[u, None], xf[u, None], stroke[u, None])
        inertia, potential = tm[0], tm[2]
        if first is not None:
            per_kind = (nodes, plus, inertia, potential, base, local)
            nodes, plus, inertia, potential, base, local = (v.take(inverse, axis=0) for v in per_kind)
        i = j[:, None] + inertia
        up = potential + i * kin[0][:, None]  # Eq. (8) of pumplink.models.dynamics_terms
        lo = potential + i * kin[1][:, None]
        dm = np.stack(np.broadcast_arrays(*co, mw, dce, *kin, j))
    prep = Prepared(tuple(geom), dce, plus, xe, xf, stroke, mw, nodes, base, local)
    travel = [v[:, None] for v in prep.args()]
    return DynamicsProblem(prep, lk1, j, ms, w_lo, w_hi, gravity, mw, stroke, up, lo, dm, travel)


# The pairs of (C1)-(C2) in the form the sweeps use (docs/models.md §3a).  At the points x of a row
# (sorted, one revolution) with G = base + local and the lam-free parts au = upper + Mw x,
# al = lower + Mw x:  upper - Q = au - lam G,  lower - Q = al - lam G,  lower - P = al + lam G,
# upper - P = au + lam G; one revolution later Q has grown by a = 2 lam S - 2 pi Mw and P by
# b = -2 lam S - 2 pi Mw.  N and K of a pair (earlier point i, later point j, "wrap" when i lies
# one revolution back):  (C1) N = al_j - au_i (+ 2 pi Mw),  (C2) N = al_i - au_j (- 2 pi Mw),
# K = G_j - G_i (+ 2 S) for both.
def _pairs(g, au, al, base, local, mw, stroke, lam):
    """The worst pair of (C1) and of (C2) at Fp = lam over the points of each row.

    Returns (h, ratio), each (D, 2) for the two families: h = max over pairs of N - lam K [J]
    (feasible iff h <= 0 in both), ratio = N / K of the maximising pair [N] (Dinkelbach's next
    iterate).  Pairs whose earlier point lies up to a revolution back are included without
    doubling the arrays: a running extremum one revolution back is the row's extremum shifted by
    the drift (a or b), so the later copy of a point always dominates its first copy.
    """
    h, r = _pairs_held(_held(g, au, al, base, local, mw, stroke), lam)
    return h.T, r.T


def _held(g, au, al, base, local, mw, stroke) -> list:
    """The arrays :func:`_pairs_held` reads: G, (au, -al), (al, au), base, local, (-2 pi Mw,
    2 pi Mw), 2 pi Mw and 2 S; rows over designs (axis 1 of the stacked ones).

    (C2) is swept negated beside (C1): its running maximum of lower - P is minus the running
    minimum of -(lower - P), so both families take one pass of each operation.  Negation is exact,
    so every value is the one the two families give apart.
    """
    al_au = np.empty((2,) + g.shape)
    al_au[0], al_au[1] = al, au
    return _held_of(g, al_au, base, local, mw, stroke)


def _held_of(g, al_au, base, local, mw, stroke) -> list:
    """:func:`_held` from G and (al, au) stacked."""
    au_nal = np.empty_like(al_au)
    au_nal[0] = al_au[1]
    np.negative(al_au[0], out=au_nal[1])
    turns = np.empty((2,) + mw.shape)
    np.multiply(TWO_PI, mw, out=turns[1])
    np.negative(turns[1], out=turns[0])
    base, local = np.ascontiguousarray(base), np.ascontiguousarray(local)
    return [g, au_nal, al_au, base, local, turns, turns[1], 2.0 * stroke]


#: Axis over the designs of each array of :func:`_held` (the stacked ones carry the family first).
_HELD_AXIS = (0, 1, 1, 0, 0, 1, 0, 0)


def _pairs_held(held, lam):
    """:func:`_pairs` on the arrays of :func:`_held`: (h, ratio), each (2, D) (no floating-point
    context)."""
    g, au_nal, al_au, base, local, turns, turn, two_s = held
    d, k = g.shape
    lg = lam[:, None] * g
    # (C1): lower(s) - Q(s) - min over t <= s of (upper(t) - Q(t)) <= 0;
    # (C2): max over s <= t of (lower(s) - P(s)) - (upper(t) - P(t)) <= 0, swept negated
    f = au_nal - lg  # upper - Q, -(lower - P)
    run = _running_min(f)
    back = (run[:, :, -1] + lam * two_s) + turns  # the minimum one revolution back (2 lam S: exact)
    best = np.minimum(run, back[:, :, None])
    v = np.empty_like(f)
    np.subtract(al_au[0], lg, out=v[0])
    v[0] -= best[0]
    np.negative(best[1], out=v[1])
    v[1] -= al_au[1]
    v[1] -= lg
    j = v.argmax(axis=2)
    off = np.arange(0, 2 * d * k, k).reshape(2, d)  # (family, row) in the flattened (2, D, K)
    fj = off + j
    h = v.take(fj)
    run_j = run.take(fj)
    wrap = best.take(fj) < run_j
    # i: the first point where f meets the minimum the pair takes (a row's own where it wraps: its
    # argmin, every value finite on a row still iterating)
    i = (f == np.where(wrap, run[:, :, -1], run_j)[:, :, None]).argmax(axis=2)
    # N: (C1) al_j - au_i (+ 2 pi Mw), (C2) minus (au_j - al_i (+ 2 pi Mw))
    num = (al_au.take(fj) - al_au.take(off[::-1] + i)) + np.where(wrap, turn, 0.0)
    rj, ri = off[0] + j, off[0] + i
    kk = (base.take(rj) - base.take(ri)) + (local.take(rj) - local.take(ri))  # no cancellation at a DC
    r = num / (kk + np.where(wrap, two_s, 0.0))
    np.negative(r[1], out=r[1])
    return h, r


def _running_min(f):
    """``np.minimum.accumulate(f, axis=2)`` of a (2, D, K) array: over many designs a loop over the K
    columns, a vector minimum over the designs each (numpy's accumulate runs row by row: about twice
    as slow on a chunk), the same values."""
    if f.shape[1] < RUN_DESIGNS or f.shape[2] == 0:
        return np.minimum.accumulate(f, axis=2)
    run = np.empty_like(f)
    run[:, :, 0] = f[:, :, 0]
    for j in range(1, f.shape[2]):
        np.minimum(run[:, :, j - 1], f[:, :, j], out=run[:, :, j])
    return run


def _dinkelbach(pts, mw, stroke, lam, cap, rtol=RTOL):
    """Dinkelbach's iteration over the pairs of the points ``pts`` = (x, base, local, up, lo), each
    (D, K), from the lower bound ``lam``.

    Every iterate is the ratio of a pair, so a lower bound of Fp*; a row stops when no pair of its
    points is violated (or the iterate moves by less than RTOL).  The rows still iterating are
    gathered into smaller arrays only when they are fewer than half of those held.
    """
    x, base, local, up, lo = pts
    m = mw[:, None] * x
    al_au = np.empty((2,) + x.shape)
    np.add(lo, m, out=al_au[0])
    np.add(up, m, out=al_au[1])
    held = _held_of(base + local, al_au, base, local, mw, stroke)
    lam = np.array(lam, float)
    if lam.size == 0:
        return lam
    cur = lam  # the iterate of each held row (a row's stays put once it stops)
    where = None  # row of lam for each held row, once gathered
    live = np.ones(lam.size, bool)
    with np.errstate(all="ignore"):
        for _ in range(200):
            h, r = _pairs_held(held, cur)
            r = np.where(h > 0, np.where(np.isnan(r), np.inf, r), -np.inf)
            new = r.max(axis=0)
            grow = live & (new > cur)
            done = ~grow | (new - cur <= rtol * np.abs(new))
            cur = np.where(grow, new, cur)
            capped = ~(cur <= cap)
            cur[capped] = np.inf
            live &= ~(done | capped)
            n_live = np.count_nonzero(live)
            if n_live == 0:
                break
            if n_live < 0.5 * live.size:
                keep = np.nonzero(live)[0]
                if where is None:
                    lam, where = cur, keep
                else:
                    lam[where] = cur
                    where = where[keep]
                held = [v.take(keep, axis=ax) for v, ax in zip(held, _HELD_AXIS, strict=True)]
                cur, live, cap = cur[keep], live[keep], cap[keep]
    if where is None:
        return cur
    lam[where] = cur
    return lam


#: The four functions whose local extrema hold the worst pairs: (edge, sign of lam G, kind) with
#: edge 0 upper / 1 lower, sign -1 for "minus Q" / +1 for "minus P", kind -1 minima / +1 maxima.
#: (C1) pairs a local minimum of upper - Q with a later local maximum of lower - Q, (C2) a local
#: maximum of lower - P with a later local minimum of upper - P.
_FAMILIES = ((0, -1.0, -1), (1, -1.0, 1), (1, 1.0, 1), (0, 1.0, -1))


_EDGE = np.array([f[0] for f in _FAMILIES])
_SIGN = np.array([f[1] for f in _FAMILIES])


def _extrema(pb: DynamicsProblem, lam, rows):
    """The local extrema of :data:`_FAMILIES` on the grid nodes of designs ``rows`` at Fp = lam (per
    row): (design, node, lo, hi, family) with the neighbouring nodes (lo, hi) as the bracket."""
    every = rows.size == pb.mw.size  # rows are sorted and distinct: all designs
    x, base, local, up, low = pb.points(None if every else rows)
    mw, stroke = (pb.mw, pb.stroke) if every else (pb.mw[rows], pb.stroke[rows])
    lg = lam[:, None] * (base + local)
    m = mw[:, None] * x
    ls2, turn = 2.0 * lam * stroke, TWO_PI * mw
    a = ls2 - turn  # the drifts of Q and P over a revolution
    b = -ls2 - turn
    last = x.shape[1] - 1
    # the four functions, maxima turned into minima (times -kind): upper - Q, -(lower - Q),
    # -(lower - P), upper - P; and -kind times their drift (a for Q, b for P)
    au, al = up + m, low + m
    f = np.empty((4,) + x.shape)  # written in place: no stacked copy
    np.subtract(au, lg, out=f[0])
    np.subtract(al, lg, out=f[1])
    np.add(al, lg, out=f[2])
    np.add(au, lg, out=f[3])
    np.negative(f[1:3], out=f[1:3])
    kd = np.stack([-a, a, b, -b])
    ext = np.empty(f.shape, bool)
    np.less(f[:, :, 1:-1], f[:, :, 2:], out=ext[:, :, 1:-1])
    ext[:, :, 1:-1] &= f[:, :, 1:-1] <= f[:, :, :-2]
    # the neighbours across the period: f(x - 2 pi) = f(x) + drift (times -kind)
    ext[:, :, 0] = (f[:, :, 0] <= f[:, :, -1] - kd) & (f[:, :, 0] < f[:, :, 1])
    ext[:, :, -1] = (f[:, :, -1] <= f[:, :, -2]) & (f[:, :, -1] < f[:, :, 0] + kd)
    at = np.flatnonzero(ext)  # as np.nonzero(ext), in its order: (family, row, node) of each
    fam, at = np.divmod(at, x.size)  # flat index into (R, M)
    d, k = np.divmod(at, x.shape[1])
    node = x.take(at)
    lo = np.where(k > 0, x.take(at - 1), x.take(at - k + last) - TWO_PI)
    hi = np.where(k < last, x.take(np.minimum(at + 1, x.size - 1)), x.take(at - k) + TWO_PI)
    return d, node, lo, hi, fam


class _Slope:
    """The derivative of one family's function at the extrema being refined (1-D arrays, one per
    extremum): f' = V' + I' w^2/2 + sign lam |g| + Mw, with w the band's top or bottom speed."""

    def __init__(self, pb: DynamicsProblem, dd, fam, lam_e):
        e = dd.size
        n = COEFFICIENT_COUNT
        m = np.empty((n + 4, e))  # the constants of the terms, Mw, dce, w^2 / 2, sign lam
        m[: n + 2] = pb.design[: n + 2].take(dd, axis=1)
        m[n + 2] = pb.design[n + 2 + _EDGE[fam], dd]  # the top (upper edge) or bottom speed
        np.multiply(_SIGN[fam], lam_e, out=m[n + 3])
        # the Newton steps evaluate f' at two stacked points per extremum
        self.m = np.repeat(m[:, None, :], 2, axis=1) if e <= _SMALL else m
        self.size, self.gravity = e, pb.gravity

    def __call__(self, phi, idx=None):
        """f' at phi (2, E) or (2, len(idx)) [rad from the extended dead centre].

        A few extrema of many are gathered first; otherwise f' is evaluated at all of them (the
        others at phi = 0) and the wanted ones picked: fewer operations on small arrays, the same
        values."""
        pick, m = None, self.m
        if idx is not None and idx.size < self.size:
            if 2 * idx.size < self.size:
                m = m.take(idx, axis=m.ndim - 1)
            else:
                pick, phi0 = idx, phi
                phi = np.zeros((2, self.size))
                phi[:, idx] = phi0
        co, (mw, dce, w2, slam) = m[:COEFFICIENT_COUNT], m[COEFFICIENT_COUNT:]
        tm = terms_from(co, dce + phi, self.gravity, values=False)
        out = tm[3] + tm[1] * w2 + slam * np.abs(tm[4]) + mw
        return out if pick is None else out[:, pick]


def _two(c, step):
    """The points c and c + step stacked, (2, n)."""
    out = np.empty((2, c.size))
    out[0] = c
    np.add(c, step, out=out[1])
    return out


def _newton(slope: _Slope, start, lo, hi, width):
    """Newton's method on f' (finite-difference second derivative, step REFINE_STEP * width) from
    ``start`` without a bracket: the root where a step below REFINE_XTOL lands inside (lo, hi),
    NaN where it leaves the bracket or has not converged after WARM_ITER steps."""
    out = np.full(start.size, np.nan)
    live = np.nonzero(np.isfinite(start))[0]
    if live.size == start.size:
        cc, lo_l, hi_l, step = start, lo, hi, REFINE_STEP * width
    else:
        cc, lo_l, hi_l, step = start[live], lo[live], hi[live], REFINE_STEP * width[live]
    for _ in range(WARM_ITER):
        if live.size == 0:
            break
        fc, fh = slope(_two(cc, step), live)
        new = np.where(fc == 0, cc, cc - fc * step / (fh - fc))
        inside = (new > lo_l) & (new < hi_l)
        conv = inside & (np.abs(new - cc) <= REFINE_XTOL)
        out[live[conv]] = new[conv]
        keep = inside & ~conv
        if not keep.all():
            live, new, lo_l, hi_l, step = live[keep], new[keep], lo_l[keep], hi_l[keep], step[keep]
        cc = new
    return out


def _bracketed(slope: _Slope, lo, hi, node, idx):
    """Roots of f' in the brackets (lo, hi) of the extrema ``idx``: a secant start, then Newton
    safeguarded by the bracket, until a step is below REFINE_XTOL (the extremum's value is then
    exact to rounding: the function is flat there).  Where f' does not change sign over the
    bracket (an extremum at a node, e.g. a dead centre) the node itself."""
    a, b = lo[idx], hi[idx]
    root = node[idx].copy()
    with np.errstate(all="ignore"):
        ab = np.empty((2, idx.size))
        ab[0], ab[1] = a, b
        fa, fb = slope(ab, idx)
        live = np.nonzero(np.isfinite(fa) & np.isfinite(fb) & (np.sign(fa) * np.sign(fb) < 0))[0]
        c = (a * fb - b * fa) / (fb - fa)  # a secant step to start
        al, bl, fal, cc, il = a[live], b[live], fa[live], c[live], idx[live]
        for _ in range(REFINE_ITER):
            if live.size == 0:
                break
            cc = np.where((cc > al) & (cc < bl), cc, 0.5 * (al + bl))
            step = REFINE_STEP * np.maximum(bl - al, REFINE_XTOL)
            fc, fh = slope(_two(cc, step), il)
            left = np.sign(fc) == np.sign(fal)  # keep the root bracketed
            al, bl, fal = np.where(left, cc, al), np.where(left, bl, cc), np.where(left, fc, fal)
            new = np.where(fc == 0, cc, cc - fc * step / (fh - fc))
            conv = (np.abs(new - cc) <= REFINE_XTOL) | (bl - al <= REFINE_XTOL)
            root[live[conv]] = np.clip(new[conv], al[conv], bl[conv])
            keep = ~conv
            live, al, bl, fal, cc, il = live[keep], al[keep], bl[keep], fal[keep], new[keep], il[keep]
        root[live] = 0.5 * (al + bl)
    return root


@dataclass(frozen=True)
class _Track:
    """Refined extrema, one entry each: design (absolute index), family, bracket, grid node, root."""

    design: np.ndarray
    family: np.ndarray
    lo: np.ndarray
    hi: np.ndarray
    node: np.ndarray
    root: np.ndarray

    def _fields(self):
        return (self.design, self.family, self.lo, self.hi, self.node, self.root)

    def _among(self, rows):
        """True for the entries of the designs ``rows``."""
        if self.design.size == 0:
            return np.zeros(0, bool)
        mark = np.zeros(max(int(self.design.max()), int(rows.max(initial=0))) + 1, bool)
        mark[rows] = True
        return mark[self.design]

    def of(self, rows):
        """The entries of the designs ``rows``, in their order."""
        keep = self._among(rows)
        if keep.all():
            return self
        return _Track(*(v[keep] for v in self._fields()))

    def updated(self, other: _Track, rows):
        """These entries with those of the designs ``rows`` replaced by ``other``'s."""
        keep = ~self._among(rows)
        return _Track(*(np.concatenate([a[keep], b]) for a, b in zip(self._fields(), other._fields())))


def _warm_start(track: _Track | None, dd, fam, node, lo, hi):
    """The previous root of the same family and design nearest to each grid node, where it lies in
    the node's bracket (lo, hi); NaN elsewhere."""
    start = np.full(dd.size, np.nan)
    if track is None or track.root.size == 0 or dd.size == 0:
        return start
    span = int(max(dd.max(), track.design.max())) + 1
    key = fam * span + dd
    wkey = track.family * span + track.design
    order = np.lexsort((track.root, wkey))
    wkey, wroot = wkey[order], track.root[order]
    pos = np.searchsorted(wkey * 8.0 + wroot, key * 8.0 + np.mod(node, TWO_PI))  # roots lie in [0, 2 pi)
    for p in (pos - 1, pos):
        p = np.clip(p, 0, wkey.size - 1)
        off = np.mod(wroot[p] - node + np.pi, TWO_PI) - np.pi
        near = (wkey[p] == key) & (node + off > lo) & (node + off < hi)
        better = near & ~(np.abs(off) >= np.abs(start - node))
        start = np.where(better, node + off, start)
    return start


def refined_points(pb: DynamicsProblem, lam, rows, track: _Track | None = None, detect: bool = True):
    """Every local extremum of :data:`_FAMILIES` at Fp = lam, located by a root search on its
    analytic derivative (bracketed by the neighbouring grid nodes), as the points
    (x, base, local, up, lo), each (len(rows), K) sorted per row, and the extrema as a
    :class:`_Track` for the next call.

    The pairs of (C1)-(C2) are extreme at such points (a running minimum is attained at a local
    minimum, the largest excess after it at a local maximum), so the points hold the worst pair
    at this lam exactly; at another force they still give lower bounds.  ``track`` (the extrema of
    the previous call, at a nearby force) starts Newton at the same family's root in the same
    bracket; where that fails the bracketed search runs.  ``detect=False`` follows the extrema of
    ``track`` to this lam without looking for new ones on the grid (cheap; the points are then
    only lower bounds, for the passes before the last).
    """
    with np.errstate(all="ignore"):
        if detect:
            d, node, lo, hi, fam = _extrema(pb, lam, rows)
            dd = rows[d]
        else:
            track = track.of(rows)
            dd, fam, lo, hi, node = track.design, track.family, track.lo, track.hi, track.node
            d = np.searchsorted(rows, dd)
        slope = _Slope(pb, dd, fam, lam[d])
        width = hi - lo
        start = _warm_start(track, dd, fam, node, lo, hi) if detect else track.root
        root = _newton(slope, start, lo, hi, width)
        if detect:
            cold = np.nonzero(~np.isfinite(root))[0]
            if cold.size:
                root[cold] = _bracketed(slope, lo, hi, node, cold)
        else:  # a root that could not be followed stays where it was (still a point of the curve)
            root = np.where(np.isfinite(root), root, start)
        root = np.mod(root, TWO_PI)
        # one sorted row of points per design; short rows repeat their last point (a repeated point
        # adds no pair and keeps the row sorted), a design without extrema gets its extended dead
        # centre
        if rows.size == 1:  # one design: its roots sorted
            x = np.sort(root, kind="stable")[None, :] if root.size else np.zeros((1, 1))
        else:
            count = np.bincount(d, minlength=rows.size)
            width_k = max(int(count.max()) if count.size else 1, 1)
            order = np.lexsort((root, d))
            ds, rs = d[order], root[order]
            slot = np.arange(ds.size) - (np.cumsum(count) - count)[ds]
            x = np.full((rows.size, width_k), np.nan)
            x[ds, slot] = rs
            last = np.where(count > 0, x[np.arange(rows.size), np.maximum(count - 1, 0)], 0.0)
            x = np.where(np.isnan(x), last[:, None], x)
        every = rows.size == pb.mw.size  # rows are sorted and distinct: all designs
        args = pb.travel if every else [v[rows][:, None] for v in pb.prep.args()]
        up, low, grip_x = pb.edges(x, None if every else rows, fly_x=True)
        base, local = travel_parts(x, *args, grip_x=grip_x)
    return (x, base, local, up, low), _Track(dd, fam, lo, hi, node, root)


def solve(pb: DynamicsProblem, max_passes: int = 24):
    n = pb.mw.size
    out = np.full(n, np.nan)
    with np.errstate(all="ignore"):
        ok = (
            np.isfinite(pb.stroke)
            & (pb.stroke > 0)
            & np.isfinite(pb.up).all(axis=1)
            & np.isfinite(pb.lo).all(axis=1)
        )
        f_mean = _qs.mean_force(pb.mw, pb.stroke)
        cap = FORCE_CAP_RATIO * f_mean
        zero = ok & (pb.w_hi <= pb.w_lo)
        out[zero] = np.inf
        todo = np.nonzero(ok & ~zero)[0]
    if todo.size == 0:
        return out
    # Dinkelbach over the pairs of grid nodes, only to find where to refine (the grid's travel
    # next to a dead centre is not integrated, so this force is not trusted as a bound); then
    # passes over the extrema refined at the current force: Dinkelbach over their pairs (from
    # F_mean in the first pass, from the last, exact, lower bound after).  Between full passes
    # (extrema looked for on the whole grid) the extrema found are only followed to the new force,
    # while it still moves by more than TRACK_RTOL.  A design is done when a full pass leaves its
    # force where it was: it then is the ratio of a pair (a lower bound of Fp*) at which no pair is
    # violated (an upper bound), Fp* up to the refinement tolerance.
    grid = pb.points(None if todo.size == n else todo)
    mw, stroke = pb.mw[todo], pb.stroke[todo]
    lam = f_mean[todo]
    if todo.size >= QUARTER_FROM:  # a quarter of the nodes first
        lam = _dinkelbach(tuple(v[:, ::4] for v in grid), mw, stroke, lam, cap[todo], GRID_RTOL)
    lam = _dinkelbach(grid, mw, stroke, lam, cap[todo], GRID_RTOL)
    live = np.nonzero(np.isfinite(lam))[0]
    follow = np.zeros(todo.size, bool)  # designs whose next pass only follows their extrema
    start = f_mean[todo]
    track = None
    for _ in range(max_passes):
        if live.size == 0:
            break
        detect = not follow[live].any()
        sel = live if detect else live[follow[live]]
        rows = todo[sel]
        pts, found = refined_points(pb, lam[sel], rows, track, detect)
        track = found if detect or track is None else track.updated(found, rows)
        new = _dinkelbach(pts, pb.mw[rows], pb.stroke[rows], start[sel], cap[rows])
        step = np.abs(new - lam[sel])
        lam[sel] = start[sel] = new
        follow[sel] = step > TRACK_RTOL * np.abs(new)
        done = ~np.isfinite(new)
        if detect:  # certified where the full pass left the force where it was
            done |= step <= 4 * RTOL * np.abs(new)
        if done.any():
            gone = np.zeros(todo.size, bool)
            gone[sel[done]] = True
            live = live[~gone[live]]
    out[todo] = lam
    return out


def least_peak_force(
    lk: FourBar,
    dead_centre_extended,
    dead_centre_folded,
    wheel_torque,
    inertia,
    masses: Masses,
    mean_speed,
    speed_fluctuation,
    gravity=GRAVITY,
):
    """Least peak operator force [N] for a periodic motion inside the band of Eq. (8)
    (:mod:`pumplink.models.dynamics_terms`).

    Exact up to the refinement tolerance ((C1)-(C2) of the module docstring, docs/models.md §3a).
    With no link masses (I = J, V = 0) it is the flywheel scene's Eq. (4).

    Parameters
    ----------
    lk : linkage (scalars or 1-D arrays over designs).
    dead_centre_extended, dead_centre_folded : dead-centre crank angles [rad].
    wheel_torque : Mw [N m];  inertia : J of the wheel, rope and water [kg m^2].
    masses : :class:`Masses` [kg];  mean_speed : w_bar [rad/s];  speed_fluctuation : delta [-].
    gravity : [m/s^2].

    Returns
    -------
    Fp* [N]: inf where no force up to FORCE_CAP_RATIO * F_mean keeps the motion in the band,
    NaN for an infeasible design.
    """
    scalar, arrays = per_design(
        lk,
        dead_centre_extended,
        dead_centre_folded,
        wheel_torque,
        inertia,
        masses.coupler,
        masses.handle,
        masses.grip,
        mean_speed,
        speed_fluctuation,
    )
    n = arrays[0].size
    out = np.empty(n)
    for start in range(0, n, CHUNK):  # chunks whose (designs, nodes) arrays stay in the cache
        part = arrays if n <= CHUNK else [v[start : start + CHUNK] for v in arrays]
        pb = _problem_of(part, gravity)  # held until the next chunk's is made: freeing it first
        out[start : start + CHUNK] = solve(pb)  # costs ~10 % on 10,000 designs (the allocator)
    return float(out[0]) if scalar else out


def band_margin(lk: FourBar, dead_centre_extended, dead_centre_folded, wheel_torque, inertia, masses: Masses,
                mean_speed, speed_fluctuation, force, gravity=GRAVITY):  # fmt: skip
    """max over the pairs of (C1)-(C2) of N - Fp K at Fp = ``force`` [J]: for Fp >= F_mean a periodic
    motion inside the band exists iff this is <= 0 (docs/models.md §3a)."""
    pb, scalar = problem(lk, dead_centre_extended, dead_centre_folded, wheel_torque, inertia, masses,
                         mean_speed, speed_fluctuation, gravity)  # fmt: skip
    lam = np.broadcast_to(np.asarray(force, float), pb.mw.shape).astype(float)
    rows = np.arange(lam.size)
    (x, base, local, up, lo), _ = refined_points(pb, lam, rows)
    m = pb.mw[:, None] * x
    with np.errstate(all="ignore"):
        h, _ = _pairs(base + local, up + m, lo + m, base, local, pb.mw, pb.stroke, lam)
    out = h.max(axis=1)
    return float(out[0]) if scalar else out
