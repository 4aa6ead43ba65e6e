"""The flywheel scene's least peak force and energy deficit, Eq. (3)-(4), by two routes.

The scene, its energy balance Eq. (1) and the energy band W of Eq. (2) are those of
:mod:`pumplink.models.flywheel` (docs/physics.md and docs/models.md §2).

The least peak force, exactly
-----------------------------
With |F| <= Fp the fastest possible gain is u(t) = Fp |g(t)| - Mw, and any slope between
-Fp |g| - Mw < 0 and u is possible.  Keeping the flywheel "as full as possible" (push with Fp
in the direction the grip moves; once the wheel is at the top of the band, push just the
quasi-static force, which is <= Fp there because u >= 0) is a reflected path at the top of
the band: with U(t) the integral of u, started at the top W at t0,

    E(t) = min(W + U(t) - U(t0), min over t0 <= s <= t of W + U(t) - U(s)).

Over one revolution this maps a start x to min(x + A, C), A = U(t + 2 pi) - U(t) = 2 Fp S -
2 pi Mw (S: grip stroke), C a constant.  A periodic path needs A >= 0, i.e. Fp >= F_mean
(docs/physics.md), and then the fixed point is reached after one revolution; the path from the
top dominates every other feasible path, so a periodic motion inside the band exists **iff**
A >= 0 and it never drops more than W below the top:

    D(Fp) = max over arcs s < t < s + 2 pi of U(s) - U(t)  <=  W.                  (3)

U(s) - U(t) = Mw (t - s) - Fp G(s, t) is linear in Fp, with G the grip's horizontal travel over
the arc (its total variation: |dPx| summed; Px is monotone between the dead centres, so G comes
from positions, no quadrature).  Hence the least peak force is the fractional programme

    Fp* = max(F_mean, max over arcs of (Mw (t - s) - W) / G(s, t)),                (4)

solved here by Dinkelbach's iteration on Eq. (3).  At the optimum the arc ends where the
quasi-static force equals Fp* (the operator's limit meets the load): the wheel decelerates
exactly on the arcs around the dead centres where |F_qs| > Fp*.  Limits: W -> inf gives F_mean;
W -> 0 gives the quasi-static maximum, infinite.

Numerics (the fast route, :func:`least_peak_force` and :func:`energy_deficit`): the extrema of U
are where |g| crosses the level Mw / Fp (U' = Fp |g| - Mw).  |g| is tabulated per design at
``GRID`` uniform nodes plus both dead centres (g = 0 there, so a deficit arc around a dead centre
is bracketed however short it is); each crossing is located in the table and refined by a secant
iteration on |g|, and the drawdown of Eq. (3) is taken over the crossings.  Within
TRAVEL_INTEGRATION_ARC of a dead centre the grip travel is integrated (Gauss-Legendre on |g|),
elsewhere it comes from positions.  Wiggles of |F_qs| narrower than one grid cell (2 pi / ``GRID``)
are merged; their height is second order in the cell size.  The reference route
(:func:`_reference_least_peak_force`) evaluates U on the grid plus nodes clustered geometrically
at both dead centres and refines every local extremum of U with scipy's bracketing minimiser; the
two agree to ~1e-10 (tests/models/test_flywheel_fast.py), and the fast route hands a design it
cannot resolve to the reference route.

Pure functions on floats / arrays over designs; SI units, radians.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from pumplink.mechanisms.angles import TWO_PI
from pumplink.mechanisms.fourbar import FourBar, per_design
from pumplink.models import quasi_static as _qs
from pumplink.models.grip_travel import Prepared, crank_nodes, grip_position, grip_rate, travel, travel_parts

#: Uniform grid points per revolution on which the extrema of U are located before refinement.
GRID = 256
#: Geometric nodes each side of a dead centre, at GRID cell / 4**k for k = 1..CLUSTER (down to
#: ~1e-13 rad: a deficit arc around a dead centre is seen up to forces of FORCE_CAP_RATIO * F_mean).
CLUSTER = 20
#: Tolerances of the extremum refinement [rad]: U is flat at an extremum, so 1e-9 rad puts U within
#: ~1e-16 of its extreme value relative to the energy band for practical designs.
REFINE_TOL = dict(xatol=1e-9, xrtol=1e-12, fatol=0.0, frtol=0.0)
#: Relative convergence of Dinkelbach's iteration on the peak force.
RTOL = 1e-13
#: Peak forces above this multiple of F_mean are reported as infinite: the energy band is then, for
#: every practical purpose, zero (no operator pushes 10,000 times the mean force), and beyond it the
#: rounding of U (~eps Fp S) grows past ~1e-6 of the band (tests/models/test_flywheel.py).
FORCE_CAP_RATIO = 1e4


def prepare(lk: FourBar, dce, dcf, wheel_torque, grid=GRID, cluster=CLUSTER):
    """The designs' :class:`~pumplink.models.grip_travel.Prepared` problem on ``grid`` uniform
    nodes plus ``cluster`` at each dead centre, and whether the input was one design."""
    scalar, (*geom, dce, dcf, mw) = per_design(lk, dce, dcf, wheel_torque)
    with np.errstate(all="ignore"):
        xe = grip_position(dce, *geom)
        xf = grip_position(dcf, *geom)
        stroke = np.abs(xf - xe)
        nodes, plus = crank_nodes(dce, dcf, grid, cluster)
        g2 = [p[:, None] for p in geom]
        base, local = travel_parts(
            nodes, *g2, dce[:, None], plus[:, None], xe[:, None], xf[:, None], stroke[:, None]
        )
    return Prepared(tuple(geom), dce, plus, xe, xf, stroke, mw, nodes, base, local), scalar


def u_integral(phi, force, px, py, crank, coupler, rocker, handle, branch, dce, plus, xe, xf, stroke, mw):
    """U(phi) = Fp G(phi) - Mw phi [J]: the largest energy the operator can have added [Eq. (3)]."""
    return (
        force * travel(phi, px, py, crank, coupler, rocker, handle, branch, dce, plus, xe, xf, stroke)
        - mw * phi
    )


def _u_relative(
    phi, force, ref_base, ref_x, px, py, crank, coupler, rocker, handle, branch, dce, plus, xe, xf, stroke, mw
):
    """U(phi) - (Fp ref_base - Mw ref_x) [J], computed without the large constant (for the refinement)."""
    base, local = travel_parts(phi, px, py, crank, coupler, rocker, handle, branch, dce, plus, xe, xf, stroke)
    return force * ((base - ref_base) + local) - mw * (phi - ref_x)


def refined_extrema(prep: Prepared, force, rows=None, refine: bool = True):
    """Nodes, U and the grip travel (base, local) with every local extremum of U refined.

    Returns (x, u, base, local, a) with shape (D, M) (rows: the designs to do) and the drift
    a = U(phi + 2 pi) - U(phi) = 2 Fp S - 2 pi Mw.
    """
    from scipy.optimize.elementwise import find_minimum  # lazy: keeps start-up fast

    rows = np.arange(prep.dce.size) if rows is None else rows
    x = prep.nodes[rows].copy()
    base = prep.base[rows].copy()
    local = prep.local[rows].copy()
    fp = force[:, None]
    mw = prep.mw[rows][:, None]
    u = fp * (base + local) - mw * x
    a = 2.0 * force * prep.stroke[rows] - TWO_PI * prep.mw[rows]
    if not refine:
        return x, u, base, local, a
    # neighbours with the period wrap: U(phi - 2 pi) = U(phi) - a
    u_prev = np.concatenate([u[:, -1:] - a[:, None], u[:, :-1]], axis=1)
    u_next = np.concatenate([u[:, 1:], u[:, :1] + a[:, None]], axis=1)
    x_prev = np.concatenate([x[:, -1:] - TWO_PI, x[:, :-1]], axis=1)
    x_next = np.concatenate([x[:, 1:], x[:, :1] + TWO_PI], axis=1)
    with np.errstate(invalid="ignore"):
        is_max = (u >= u_prev) & (u > u_next)
        is_min = (u <= u_prev) & (u < u_next)
    for mask, sign in ((is_max, -1.0), (is_min, 1.0)):
        d_idx, n_idx = np.nonzero(mask)
        if d_idx.size == 0:
            continue
        args = prep.args(rows[d_idx])
        f_el = force[d_idx]
        mw_el = prep.mw[rows[d_idx]]
        rb, rx = base[d_idx, n_idx], x[d_idx, n_idx]  # U relative to the node's dead centre: no cancellation
        res = find_minimum(
            lambda t, f, b0, x0, *p, sign=sign: sign * _u_relative(t, f, b0, x0, *p),
            (x_prev[d_idx, n_idx], rx, x_next[d_idx, n_idx]),
            args=(f_el, rb, rx) + args + (mw_el,),
            tolerances=REFINE_TOL,
        )
        at_node = f_el * local[d_idx, n_idx]  # the node's own relative U
        better = np.isfinite(res.f_x) & ((-res.f_x >= at_node) if sign < 0 else (res.f_x <= at_node))
        xi = np.where(better, res.x, rx)
        b_new, l_new = travel_parts(xi, *args)
        x[d_idx, n_idx] = xi
        base[d_idx, n_idx] = b_new
        local[d_idx, n_idx] = l_new
        u[d_idx, n_idx] = f_el * (b_new + l_new) - mw_el * xi
    return x, u, base, local, a


def _worst_arc(u, a):
    """Columns (i, j) of the largest drop of U in the sequence u over two periods, [u, u + a]."""
    u2 = np.concatenate([u, u + a[:, None]], axis=1)
    top = np.maximum.accumulate(u2, axis=1)
    j = np.argmax(top - u2, axis=1)
    idx = np.arange(u.shape[0])
    # the arc starts at the first node before j where U reached that running maximum
    cols = np.arange(u2.shape[1])
    i = np.argmax((u2 == top[idx, j][:, None]) & (cols[None, :] <= j[:, None]), axis=1)
    return i, j


def drawdown(x, u, base, local, a, stroke, force, mw):
    """Largest drop of U over an arc shorter than a revolution [Eq. (3)], and that arc.

    Returns (drop [J], arc length [rad], travel over the arc [m]) per design; the travel is
    (base difference) + (local difference), exact when both ends lie near one dead centre.
    The arc is the one where U drops most; its drop is then Mw (t - s) - Fp G(s, t) from the
    arc's length and travel, not the difference of the two values of U: those are ~Fp S, up to
    ~1e7 times the drop near the force cap, and their rounding (~1e-10 of the drop there) decided
    whether Dinkelbach's iteration took its last step.
    """
    x2 = np.concatenate([x, x + TWO_PI], axis=1)
    b2 = np.concatenate([base, base + 2.0 * stroke[:, None]], axis=1)
    l2 = np.concatenate([local, local], axis=1)
    i, j = _worst_arc(u, a)
    idx = np.arange(x.shape[0])
    travel = (b2[idx, j] - b2[idx, i]) + (l2[idx, j] - l2[idx, i])
    length = x2[idx, j] - x2[idx, i]
    return mw * length - force * travel, length, travel  # Eq. (3): U(s) - U(t)


def _reference_energy_deficit(
    lk: FourBar, dead_centre_extended, dead_centre_folded, wheel_torque, peak_force
):
    """:func:`energy_deficit` by the reference route: U on the nodes of :func:`prepare`, every local
    extremum refined by scipy's bracketing minimiser (kept to check the fast route against)."""
    prep, scalar = prepare(lk, dead_centre_extended, dead_centre_folded, wheel_torque)
    fp = np.broadcast_to(np.asarray(peak_force, float), prep.dce.shape).astype(float)
    out = np.full(prep.dce.shape, np.nan)
    with np.errstate(all="ignore"):
        ok = np.isfinite(prep.stroke) & np.isfinite(fp)
        low = ok & (fp < _qs.mean_force(prep.mw, prep.stroke) * (1 - 1e-15))
        out[low] = np.inf
        rows = np.nonzero(ok & ~low)[0]
        if rows.size:
            x, u, b, loc, a = refined_extrema(prep, fp[rows], rows)
            a = np.maximum(a, 0.0)
            out[rows] = drawdown(x, u, b, loc, a, prep.stroke[rows], fp[rows], prep.mw[rows])[0]
    return float(out[0]) if scalar else out


def _reference_least_peak_force(
    lk: FourBar, dead_centre_extended, dead_centre_folded, wheel_torque, energy_band
):
    """:func:`least_peak_force` by the reference route: Dinkelbach's iteration on U at the nodes of
    :func:`prepare`, then with every local extremum refined by scipy's bracketing minimiser (kept to
    check the fast route against)."""
    prep, scalar = prepare(lk, dead_centre_extended, dead_centre_folded, wheel_torque)
    band = np.broadcast_to(np.asarray(energy_band, float), prep.dce.shape).astype(float)
    n = prep.dce.size
    out = np.full(n, np.nan)
    with np.errstate(all="ignore"):
        ok = np.isfinite(prep.stroke) & (prep.stroke > 0) & ~np.isnan(band)
        f_mean = _qs.mean_force(prep.mw, prep.stroke)
        out[ok & (band <= 0)] = np.inf
        out[ok & (band == np.inf)] = f_mean[ok & (band == np.inf)]
        finite = ok & (band > 0) & np.isfinite(band)
        todo = np.nonzero(finite)[0]
        lam = f_mean.copy()
        for refine in (False, True):
            # Dinkelbach on the grid nodes first (cheap; the grid's arcs are a subset of all arcs, so its
            # answer is a lower bound to start from), then with every extremum refined
            lam = _dinkelbach(prep, lam, band, todo[np.isfinite(lam[todo])], refine, FORCE_CAP_RATIO * f_mean)
        out[finite] = lam[finite]
    return float(out[0]) if scalar else out


def _dinkelbach(prep: Prepared, lam, band, active, refine: bool, cap):
    """Dinkelbach's iteration for Eq. (4) from ``lam`` (a lower bound) on the designs ``active``."""
    lam = lam.copy()
    for _ in range(100):
        if active.size == 0:
            break
        x, u, b, loc, a = refined_extrema(prep, lam[active], active, refine)
        drop, length, travel = drawdown(
            x, u, b, loc, np.maximum(a, 0.0), prep.stroke[active], lam[active], prep.mw[active]
        )
        new = (prep.mw[active] * length - band[active]) / travel  # Eq. (4): the arc's ratio
        grow = (drop > band[active]) & (new > lam[active])
        done = ~grow | (new - lam[active] <= RTOL * new)
        lam[active] = np.where(grow, new, lam[active])
        capped = lam[active] > cap[active]
        lam[active[capped]] = np.inf
        active = active[~(done | capped)]
    return lam


# ----------------------------------------------------------------------------- the fast route
# The same Eq. (3)-(4), from the local extrema of U alone.  U' = u = Fp |g| - Mw, so U has its
# local maxima where |g| falls through the level Mw / Fp and its minima where |g| rises through
# it.  |g| is tabulated once per design on the uniform nodes of the grid plus the two dead centres
# (where g = 0: every deficit arc around a dead centre is bracketed however short it is); for each
# force the crossings of the level are located in that table and refined by a safeguarded secant
# iteration on |g| itself, and the drawdown of Eq. (3) is taken over them, with the grip travel of
# :func:`travel_parts` as in the reference route.  Dinkelbach's iteration starts at the dead-centre
# asymptote and runs first on crossings interpolated linearly in the table, then on refined ones;
# every arc's ratio in Eq. (4) is a lower bound of Fp*, so the starting value and the interpolated
# arcs cost no exactness, only steps.  Far below the answer, where D(Fp) ~ 1/Fp (the dead-centre
# asymptote), a hyperbolic step replaces Dinkelbach's (Newton's) step.

#: Designs per block of the fast route: bounded (block x GRID) tables (~4 MB), few Python-level
#: passes per design; the scratch of the table's kernel is allocated once per call.
BLOCK = 2048
#: Designs per call of the table's kernel (its nine (rows x GRID) scratch arrays ~1.2 MB).
KERNEL_ROWS = 64
#: Dinkelbach's iteration moves from interpolated to refined crossings at this relative step.
COARSE_RTOL = 1e-3
#: ... and stops at this relative step on refined crossings.  The grip travel from positions just
#: outside TRAVEL_INTEGRATION_ARC is rounded to ~1e-13 of itself, so the arc's ratio is too: at RTOL
#: the rounding decided when to stop (two extra passes for some designs).  Near the answer the
#: error of a Dinkelbach step is the square of the step, so 1e-12 costs no accuracy.
FINE_RTOL = 1e-12
#: A refined crossing is accepted when the secant step is below this fraction of its distance
#: from the nearest dead centre (the arc's ratio is stationary in its ends, so its error is the
#: square of this, relative).
CROSSING_RTOL = 1e-10
#: Most passes and secant steps; a design that needs more goes to the reference route.
MAX_PASSES = 80
MAX_SECANT = 50

_H = TWO_PI / GRID
_UNIFORM = (np.arange(GRID) + 0.5) * _H  # the uniform nodes of _nodes
_COS_U, _SIN_U = np.cos(_UNIFORM), np.sin(_UNIFORM)
_EPS = np.finfo(float).eps


def _rate_table_into(geom, dce, out, work):
    """|g| = |dPx/dt2| [m/rad] at the uniform nodes (rows, GRID) into ``out``: the formulas of
    :func:`pumplink.models.grip_travel.grip_rate`, in place in ``work`` (9, rows, GRID), the crank
    direction by angle addition."""
    px, py, c, k, r, hd, br = (v[:, None] for v in geom)
    cd, sd = np.cos(dce)[:, None], np.sin(dce)[:, None]
    cs, sn, p1, p2, e2, t, q, a, b = work
    np.multiply(cd, _COS_U, out=cs)
    np.multiply(sd, _SIN_U, out=a)
    cs -= a  # cos(dce + phi)
    np.multiply(sd, _COS_U, out=sn)
    np.multiply(cd, _SIN_U, out=a)
    sn += a  # sin(dce + phi)
    np.multiply(cs, px, out=p1)
    np.multiply(sn, py, out=a)
    p1 += a  # P1
    np.multiply(cs, py, out=p2)
    np.multiply(sn, px, out=a)
    p2 -= a  # P2
    np.multiply(p1, -2.0 * c, out=e2)
    e2 += px * px + py * py + c * c  # e^2
    np.divide(0.5 * (k * k - r * r), e2, out=t)
    t += 0.5
    np.sqrt(e2, out=a)  # e; q by Heron's formula as fourbar_kernel.coupler_height
    np.add(a, k, out=b)  # e + k
    np.subtract(e2, k * k, out=q)
    q /= b  # e - k
    np.multiply(q, q, out=q)
    np.subtract(r * r, q, out=q)
    np.multiply(b, b, out=b)
    b -= r * r
    q *= b
    np.sqrt(q, out=q)
    q /= e2
    q *= 0.5 * br
    np.multiply(cs, -c, out=a)
    a += px  # dx
    np.multiply(sn, -c, out=b)
    b += py  # dy
    b *= t
    a *= q
    np.multiply(sn, c, out=cs)
    cs += b
    cs += a
    cs -= py  # Ry = crank sn + t dy + q dx - py
    p1 -= c
    p1 *= q
    p2 *= t
    p2 += p1  # t P2 + q (P1 - crank)
    cs *= p2
    cs *= (hd / r) * c
    q *= e2
    cs /= q
    np.abs(cs, out=out)


#: Rows of the parameter matrix of a table: the four-bar's seven parameters (FourBar order), then
_DCE, _PLUS, _XE, _XF, _STROKE, _MW = 7, 8, 9, 10, 11, 12


@dataclass(frozen=True)
class _Table:
    """One block of designs for the fast route: per-design values and |g| at the nodes."""

    params: np.ndarray  # (13, n): px, py, crank, coupler, rocker, handle, branch, dce, plus, xe, xf, S, Mw
    kp: np.ndarray  # uniform nodes below the folded dead centre
    rate: np.ndarray  # (n, GRID + 3): |g| at 0, the uniform nodes with plus among them, 2 pi


def _table(geom, dce, dcf, mw, xe, xf, work) -> _Table:
    """The table of a block of designs (arrays (n,); xe, xf: the grip's Px at the dead centres)."""
    n = dce.size
    plus = np.mod(dcf - dce, TWO_PI)
    # the folded dead centre among the uniform nodes: kp of them lie below it, at columns 1..kp;
    # it is column kp + 1 and the others follow; the extended one is column 0 and GRID + 2
    kp = np.clip(np.ceil(plus / _H - 0.5), 0, GRID).astype(np.intp)
    rate = np.empty((n, GRID + 3))
    for s0 in range(0, n, KERNEL_ROWS):
        s = slice(s0, s0 + KERNEL_ROWS)
        rows = min(n, s0 + KERNEL_ROWS) - s0
        _rate_table_into(tuple(v[s] for v in geom), dce[s], rate[s, 2 : GRID + 2], work[:, :rows])
    np.copyto(rate[:, 1 : GRID + 1], rate[:, 2 : GRID + 2], where=np.arange(GRID) < kp[:, None])
    rate[:, 0] = rate[:, -1] = 0.0
    rate[np.arange(n), kp + 1] = 0.0
    params = np.stack([*geom, dce, plus, xe, xf, np.abs(xf - xe), mw])
    return _Table(params, kp, rate)


def _node_phi(kp, plus, c):
    """Crank angle phi [rad] of column c of a table (kp, plus: of each column's design)."""
    u = _UNIFORM[np.clip(np.where(c <= kp, c - 1, c - 2), 0, GRID - 1)]
    return np.where(c == 0, 0.0, np.where(c == kp + 1, plus, np.where(c == GRID + 2, TWO_PI, u)))


def _crossings(tab: _Table, rows, level, refine):
    """The crossings of |g| through ``level`` (per row) in crank angle phi from the extended dead
    centre, sorted per design: (design index into rows, phi, converged flag, the crossings'
    parameter columns)."""
    rate = tab.rate if rows.size == tab.rate.shape[0] else tab.rate[rows]  # rows: all, or a subset
    above = rate > level[:, None]
    d, c = np.nonzero(above[:, 1:] != above[:, :-1])
    r = rows[d]
    par = tab.params[:, r]
    kp, plus = tab.kp[r], par[_PLUS]
    lo, hi = _node_phi(kp, plus, c), _node_phi(kp, plus, c + 1)
    lv = level[d]
    flo, fhi = tab.rate[r, c] - lv, tab.rate[r, c + 1] - lv
    x = lo + (hi - lo) * (flo / (flo - fhi))  # linear interpolation in the table
    ok = np.ones(d.size, bool)
    if refine.any():
        sel = np.nonzero(refine[d])[0]
        x[sel], ok[sel] = _secant(par[:, sel], lv[sel], lo[sel], hi[sel], flo[sel], fhi[sel], x[sel])
    return d, x, ok, par


def _secant(par, level, lo, hi, flo, fhi, x):
    """Refine the crossings |g(phi)| = level in [lo, hi] from x (``par``: their parameter columns):
    secant steps kept inside the bracket (else the Illinois false position), until a step is below
    CROSSING_RTOL of the distance from the nearest dead centre.  Returns (phi, converged)."""
    out = x.copy()
    ok = np.zeros(x.size, bool)
    act = np.arange(x.size)
    near = np.minimum(np.minimum(x, TWO_PI - x), np.abs(x - par[_PLUS]))
    tol = CROSSING_RTOL * near + 4.0 * _EPS * x
    xp = fp = None
    slope = (fhi - flo) / (hi - lo)  # first step: Newton with the table's slope
    side = np.zeros(x.size, np.int8)  # the bracket's end moved last: 1 lo, -1 hi
    for _ in range(MAX_SECANT):
        f = np.abs(grip_rate(par[_DCE] + x, *par[:7])) - level
        on_lo = (f > 0.0) == (flo > 0.0)
        # Illinois: an end kept twice in a row has its value halved (false position then converges)
        fhi = np.where(on_lo & (side == 1), 0.5 * fhi, fhi)
        flo = np.where(~on_lo & (side == -1), 0.5 * flo, flo)
        side = np.where(on_lo, 1, -1).astype(np.int8)
        lo = np.where(on_lo, x, lo)
        flo = np.where(on_lo, f, flo)
        hi = np.where(on_lo, hi, x)
        fhi = np.where(on_lo, fhi, f)
        if xp is not None:
            slope = (f - fp) / (x - xp)
        step = f / slope
        # converged on the secant step itself: a point on the root may lie on the bracket's end
        conv = ((np.abs(step) <= tol) | (f == 0.0) | (hi - lo <= tol)) & np.isfinite(f)
        nxt = x - step
        out[act[conv]] = np.clip(np.where(f == 0.0, x, nxt), lo, hi)[conv]
        inside = (nxt > lo) & (nxt < hi)  # False for NaN
        nxt = np.where(inside, nxt, lo - flo * (hi - lo) / (fhi - flo))
        done = conv | ~np.isfinite(f)
        ok[act[conv]] = True
        if done.all():
            break
        keep = ~done
        act = act[keep]
        xp, fp = x[keep], f[keep]
        x, lo, hi, flo, fhi, level, side, tol = (v[keep] for v in (nxt, lo, hi, flo, fhi, level, side, tol))
        par = par[:, keep]
    return out, ok


def _fast_drawdown(tab: _Table, rows, force, refine):
    """Eq. (3) at ``force`` (per row) over the extrema of U: (drop [J], arc length [rad], travel
    [m], ok) per row; ok is False where the table shows no crossing or a refinement failed."""
    mw = tab.params[_MW, rows]
    d, x, conv, par = _crossings(tab, rows, mw / force, refine)
    n = rows.size
    count = np.bincount(d, minlength=n)
    ok = (count > 0) & (np.bincount(d, weights=~conv * 1.0, minlength=n) == 0)
    if d.size == 0:
        nan = np.full(n, np.nan)
        return nan, nan, nan, ok
    base, local = travel_parts(x, *par[:12], integrate=False)  # enough to rank the arcs
    u = force[d] * (base + local) - par[_MW] * x
    # per design in rows of width max(count), the last extremum repeated (no new drop, same maximum)
    width = max(int(count.max()), 1)
    start = np.cumsum(count) - count
    col = np.minimum(np.arange(width)[None, :], np.maximum(count - 1, 0)[:, None])
    g = np.minimum(start[:, None] + col, d.size - 1)
    stroke = tab.params[_STROKE, rows]
    a = np.maximum(2.0 * force * stroke - TWO_PI * mw, 0.0)  # drift U(phi + 2 pi) - U(phi)
    i, j = _worst_arc(u[g], a)
    # the worst arc's ends, unrolled (the second period is one turn on), their travel exactly
    at = np.arange(n)
    ends = np.concatenate([g[at, i % width], g[at, j % width]])
    phi = x[ends] + TWO_PI * np.concatenate([i // width, j // width])
    eb, el = travel_parts(phi, *par[:12, ends])
    length = phi[n:] - phi[:n]
    travel = (eb[n:] - eb[:n]) + (el[n:] - el[:n])
    return mw * length - force * travel, length, travel, ok  # Eq. (3): U(s) - U(t)


def _asymptote(tab: _Table, band):
    """The dead-centre asymptote Fp ~ Mw^2 / (kappa W) [N] of each design (docs/models.md §2), kappa
    = |g| / distance at the table's nodes beside each dead centre, the smaller of the two: the first
    trial of Dinkelbach's iteration (within 2 % of Fp* for 90 % of random designs; any trial will
    do, the arcs' ratios are the lower bounds)."""
    n = band.size
    at = np.arange(n)
    kp, rate, plus = tab.kp, tab.rate, tab.params[_PLUS]
    below = _UNIFORM[np.maximum(kp - 1, 0)]
    above = _UNIFORM[np.minimum(kp, GRID - 1)]
    extended = 0.5 * (rate[:, 1] / _UNIFORM[0] + rate[:, GRID + 1] / (TWO_PI - _UNIFORM[-1]))
    folded = 0.5 * (rate[at, kp] / (plus - below) + rate[at, kp + 2] / (above - plus))
    mw = tab.params[_MW]
    return mw * mw / (np.minimum(extended, folded) * band)


def _fast_least_peak_force(tab: _Table, band, f_mean):
    """Fp* per design of a table with finite positive bands; NaN where the reference route must
    answer (no crossing in the table, a refinement or the iteration did not converge)."""
    n = band.size
    cap = FORCE_CAP_RATIO * f_mean
    lam = f_mean.copy()  # a lower bound of Fp*
    trial = np.maximum(f_mean, _asymptote(tab, band))  # where the next pass evaluates Eq. (3)
    fine = np.zeros(n, bool)
    out = np.full(n, np.nan)
    active = np.arange(n)
    for _ in range(MAX_PASSES):
        if active.size == 0:
            break
        t = trial[active]
        w = band[active]
        mw = tab.params[_MW, active]
        drop, length, travel, ok = _fast_drawdown(tab, active, t, fine[active])
        ratio = (mw * length - w) / travel  # Eq. (4) on the worst arc at t: a lower bound of Fp*
        ok &= np.isfinite(ratio) & (travel > 0)
        below = drop > w  # D(t) > W: t < Fp*, a lower bound too (and ratio > t)
        low = lam[active]
        best = np.maximum(low, ratio)
        # settled: a step below the tolerance, or no deficit at a lower bound (t is Fp*)
        settled = (np.abs(ratio - t) <= np.where(fine[active], FINE_RTOL, COARSE_RTOL) * ratio) | (
            ~below & (t <= low)
        )
        # hyperbolic step: D = alpha / Fp + beta through D(t) and D'(t) = -G; Newton's would be
        # t (1 + x), this is t / (1 - x), exact where D ~ 1/Fp
        x = (drop - w) / (travel * t)
        hyper = np.where(x < 0.9, t / (1.0 - x), 10.0 * t)
        trial[active] = np.where(below & ~(settled & fine[active]), np.maximum(hyper, best), best)
        lam[active] = np.where(ok, best, low)
        done = settled & fine[active] & ok
        out[active[done]] = best[done]
        capped = ok & (best > cap[active])
        out[active[capped]] = np.inf
        fine[active[settled]] = True
        active = active[ok & ~done & ~capped]
    return out


def _fast_route(lk: FourBar, dead_centre_extended, dead_centre_folded, wheel_torque, value):
    """Per-design arrays for the fast route and a generator of its tables over blocks of ``rows``."""
    scalar, (*geom, dce, dcf, mw, value) = per_design(
        lk, dead_centre_extended, dead_centre_folded, wheel_torque, value
    )
    with np.errstate(all="ignore"):  # NaN for an infeasible design
        xe = grip_position(dce, *geom)
        xf = grip_position(dcf, *geom)
    stroke = np.abs(xf - xe)

    def tables(rows):
        work = np.empty((9, min(max(rows.size, 1), KERNEL_ROWS), GRID))
        for b0 in range(0, rows.size, BLOCK):
            i = rows[b0 : b0 + BLOCK]
            yield i, _table(tuple(v[i] for v in geom), dce[i], dcf[i], mw[i], xe[i], xf[i], work)

    return scalar, geom, dce, dcf, mw, value, stroke, tables


def energy_deficit(lk: FourBar, dead_centre_extended, dead_centre_folded, wheel_torque, peak_force):
    """Least energy band W [J] an operator limited to ``peak_force`` needs: D(Fp) of Eq. (3).

    The flywheel must be able to give up this much kinetic energy on the arcs where the
    quasi-static force exceeds ``peak_force``; infinite when the peak is below F_mean (the
    operator cannot do a cycle's work).  Broadcasts over designs.  The fast route (the extrema of U
    from the table of |g|); the reference route answers for a design the table cannot resolve.

    Parameters
    ----------
    lk : linkage (scalars or 1-D arrays over designs).
    dead_centre_extended, dead_centre_folded : dead-centre crank angles [rad].
    wheel_torque : Mw [N m];  peak_force : the operator's largest |F| [N].
    """
    scalar, geom, dce, dcf, mw, fp, stroke, tables = _fast_route(
        lk, dead_centre_extended, dead_centre_folded, wheel_torque, peak_force
    )
    out = np.full(dce.shape, np.nan)
    with np.errstate(all="ignore"):
        ok = np.isfinite(stroke) & np.isfinite(fp)
        low = ok & (fp < _qs.mean_force(mw, stroke) * (1 - 1e-15))
        out[low] = np.inf
        redo = []
        for idx, tab in tables(np.nonzero(ok & ~low)[0]):
            rows = np.arange(idx.size)
            drop, _, _, good = _fast_drawdown(tab, rows, fp[idx], np.ones(idx.size, bool))
            out[idx] = drop
            redo.append(idx[~good])
        redo = np.concatenate(redo) if redo else np.empty(0, np.intp)
        if redo.size:
            out[redo] = _reference_energy_deficit(
                FourBar(*(v[redo] for v in geom)), dce[redo], dcf[redo], mw[redo], fp[redo]
            )
    return float(out[0]) if scalar else out


def least_peak_force(lk: FourBar, dead_centre_extended, dead_centre_folded, wheel_torque, energy_band):
    """Least peak operator force [N] for a periodic motion inside the energy band, Eq. (4).

    Exact to solver tolerance (Dinkelbach's iteration on Eq. (3) over the extrema of U, each
    refined).  Between F_mean (W -> inf: an infinite flywheel) and the quasi-static maximum
    (W -> 0: no flywheel, infinite at the dead centres).  The fast route (the extrema of U from the
    table of |g|); the reference route answers for a design the table cannot resolve.

    Parameters
    ----------
    lk : linkage (scalars or 1-D arrays over designs).
    dead_centre_extended, dead_centre_folded : dead-centre crank angles [rad].
    wheel_torque : Mw [N m].
    energy_band : W = J w_bar^2 delta [J] (:func:`pumplink.models.flywheel.energy_band`).

    Returns
    -------
    Fp* [N]: inf where the band is zero or Fp* exceeds FORCE_CAP_RATIO * F_mean, NaN for an
    infeasible design.
    """
    scalar, geom, dce, dcf, mw, band, stroke, tables = _fast_route(
        lk, dead_centre_extended, dead_centre_folded, wheel_torque, energy_band
    )
    out = np.full(dce.shape, np.nan)
    with np.errstate(all="ignore"):
        ok = np.isfinite(stroke) & (stroke > 0) & ~np.isnan(band)
        f_mean = _qs.mean_force(mw, stroke)
        out[ok & (band <= 0)] = np.inf
        out[ok & (band == np.inf)] = f_mean[ok & (band == np.inf)]
        redo = []
        for idx, tab in tables(np.nonzero(ok & (band > 0) & np.isfinite(band))[0]):
            out[idx] = _fast_least_peak_force(tab, band[idx], f_mean[idx])
            redo.append(idx[np.isnan(out[idx])])
        redo = np.concatenate(redo) if redo else np.empty(0, np.intp)
        if redo.size:
            out[redo] = _reference_least_peak_force(
                FourBar(*(v[redo] for v in geom)), dce[redo], dcf[redo], mw[redo], band[redo]
            )
    return float(out[0]) if scalar else out
