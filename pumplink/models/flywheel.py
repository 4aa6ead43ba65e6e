"""The flywheel scene: the wheel's inertia carries the linkage through the dead centres.

The quasi-static force (``pumplink.mechanisms.fourbar``) is infinite at both dead centres, and speed
cancels out of it.  In the pump the upper wheel and the moving rope and water are a flywheel.
This module answers the question the quasi-static model cannot: *what is the least peak
force an operator needs to keep the wheel turning at a mean speed with a bounded speed
fluctuation?*  (docs/physics.md and docs/models.md §2).

The scene
---------
Crank angle t (the wheel's angle), kinetic energy E = J w^2 / 2 of the wheel plus the rope and
water that move with its rim; link inertias are neglected (their size is estimated by
:func:`link_energy`).  The load is a constant torque Mw; the operator applies a horizontal
force F at the grip with |F| <= Fp.  Per crank radian the energy balance is

    dE/dt = F g(t) - Mw,    g = dPx/dt  (grip travel per crank radian)          (1)

which does not contain w: in the crank angle the scene is the same at every speed.

Speed fluctuation
-----------------
The coefficient of speed fluctuation is delta = (w_max - w_min) / w_bar with the mean speed
w_bar = (w_max + w_min) / 2 (the machine-design definition).  Then exactly

    E_max - E_min = J (w_max^2 - w_min^2) / 2 = J w_bar^2 delta                  (2)

so a periodic motion with mean speed w_bar and delta <= delta_allow is a periodic E(t) whose
range is at most the *energy band* W = J w_bar^2 delta_allow.  J, w_bar and delta_allow enter
the answer only through W (the scaling law, tested).

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

Numerics: U on a grid (uniform, plus nodes clustered geometrically at both dead centres, so the
deficit arc around a dead centre is seen however short it is), every local extremum refined with
scipy's bracketing minimiser, then the drawdown of Eq. (3) over the refined extrema.  Wiggles of
|F_qs| narrower than one grid cell (2 pi / ``GRID``) are merged; their height is second order in
the cell size.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from pumplink.constants import DEFAULT_SPEED_FLUCTUATION, LINK_ENERGY_LIMIT, LINK_MASS_PER_METRE  # noqa: F401  (re-exported)
from pumplink.mechanisms.angles import TWO_PI
from pumplink.mechanisms.fourbar import FourBar, kinematic_state, loop_closure, per_design
from pumplink.models import quasi_static as _qs

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
#: rounding of U (~eps Fp S) grows past ~1e-6 of the band (tests/test_flywheel.py).
FORCE_CAP_RATIO = 1e4


def energy_band(inertia, mean_speed, speed_fluctuation):
    """Kinetic-energy band of a cycle, W = J w_bar^2 delta [J] (Eq. (2) of this module).

    Parameters
    ----------
    inertia : J about the axle [kg m^2];  mean_speed : w_bar = (w_max + w_min)/2 [rad/s];
    speed_fluctuation : delta = (w_max - w_min)/w_bar [-].
    """
    return np.asarray(inertia, float) * np.asarray(mean_speed, float) ** 2 * speed_fluctuation  # Eq. (2)


# ----------------------------------------------------------------------------- grip travel G
def _grip_x(theta, px, py, crank, coupler, rocker, handle, branch):
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
_GL_X, _GL_W = np.polynomial.legendre.leggauss(12)


def _grip_rate(theta, px, py, crank, coupler, rocker, handle, branch):
    """dPx/dt2 [m/rad] (the kinematics of ``pumplink.mechanisms.fourbar``, no cancellation at a
    dead centre)."""
    cs, sn = np.cos(theta), np.sin(theta)
    p1, p2, e2, t, q = loop_closure(FourBar(px, py, crank, coupler, rocker, handle, branch), cs, sn)
    dx, dy = px - crank * cs, py - crank * sn
    ry = crank * sn + t * dy + q * dx - py
    w = t * p2 + q * (p1 - crank)
    # -(H/rocker) Ry omega4/omega2, with omega4/omega2 = -crank w / (q e^2)
    return (handle / rocker) * ry * crank * w / (q * e2)


def _travel_parts(phi, px, py, crank, coupler, rocker, handle, branch, dce, plus, xe, xf, stroke):
    """Grip travel G = base + local [m] from the extended dead centre to crank angle dce + phi.

    ``base`` is G at the nearest dead centre (0, S or 2S, plus 2S per full turn of the unrolled
    phi); ``local`` the signed travel from it.  Px is monotone between the dead centres, so away
    from them local comes from positions; within TRAVEL_INTEGRATION_ARC it is integrated from the rate.
    Differences of G near one dead centre are then (local - local): no cancellation.
    """
    turns = np.floor(phi / TWO_PI)
    p = phi - turns * TWO_PI
    # nearest dead centre: 0 (extended), plus (folded) or 2 pi (extended, next turn)
    to_fold = p - plus
    at_fold = np.abs(to_fold) <= np.minimum(p, TWO_PI - p)
    s = np.where(at_fold, to_fold, np.where(p <= TWO_PI - p, p, p - TWO_PI))  # signed offset from it
    base = np.where(at_fold, stroke, np.where(s >= 0, 0.0, 2.0 * stroke)) + 2.0 * stroke * turns
    x = _grip_x(dce + p, px, py, crank, coupler, rocker, handle, branch)
    ref = np.where(at_fold, xf, xe)
    local = np.sign(s) * np.abs(x - ref)
    near = np.abs(s) < TRAVEL_INTEGRATION_ARC
    if np.any(near):
        geom = [np.broadcast_to(v, s.shape)[near] for v in (px, py, crank, coupler, rocker, handle, branch)]
        dc = np.broadcast_to(np.where(at_fold, dce + plus, dce), s.shape)[near]
        sn = s[near]
        t = 0.5 * sn[..., None] * (1.0 + _GL_X)  # nodes on (0, s)
        g = _grip_rate(dc[..., None] + t, *(v[..., None] for v in geom))
        local[near] = 0.5 * sn * (np.abs(g) * _GL_W).sum(axis=-1)  # not @: no BLAS threads
    return base, local


def _travel(phi, *args):
    """Grip travel G [m] from the extended dead centre to crank angle dce + phi (phi unrolled)."""
    base, local = _travel_parts(phi, *args)
    return base + local


def _nodes(dce, dcf, grid=GRID, cluster=CLUSTER):
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
class _Prepared:
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


def _prepare(lk: FourBar, dce, dcf, wheel_torque, grid=GRID, cluster=CLUSTER):
    scalar, (*geom, dce, dcf, mw) = per_design(lk, dce, dcf, wheel_torque)
    with np.errstate(all="ignore"):
        xe = _grip_x(dce, *geom)
        xf = _grip_x(dcf, *geom)
        stroke = np.abs(xf - xe)
        nodes, plus = _nodes(dce, dcf, grid, cluster)
        g2 = [p[:, None] for p in geom]
        base, local = _travel_parts(
            nodes, *g2, dce[:, None], plus[:, None], xe[:, None], xf[:, None], stroke[:, None]
        )
    return _Prepared(tuple(geom), dce, plus, xe, xf, stroke, mw, nodes, base, local), scalar


def _u_integral(phi, force, px, py, crank, coupler, rocker, handle, branch, dce, plus, xe, xf, stroke, mw):
    """U(phi) = Fp G(phi) - Mw phi [J]: the largest energy the operator can have added [Eq. (3)]."""
    return (
        force * _travel(phi, px, py, crank, coupler, rocker, handle, branch, dce, plus, xe, xf, stroke)
        - mw * phi
    )


def _u_relative(
    phi, force, ref_base, ref_x, px, py, crank, coupler, rocker, handle, branch, dce, plus, xe, xf, stroke, mw
):
    """U(phi) - (Fp ref_base - Mw ref_x) [J], computed without the large constant (for the refinement)."""
    base, local = _travel_parts(
        phi, px, py, crank, coupler, rocker, handle, branch, dce, plus, xe, xf, stroke
    )
    return force * ((base - ref_base) + local) - mw * (phi - ref_x)


def _refined_extrema(prep: _Prepared, force, rows=None, refine: bool = True):
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
        b_new, l_new = _travel_parts(xi, *args)
        x[d_idx, n_idx] = xi
        base[d_idx, n_idx] = b_new
        local[d_idx, n_idx] = l_new
        u[d_idx, n_idx] = f_el * (b_new + l_new) - mw_el * xi
    return x, u, base, local, a


def _drawdown(x, u, base, local, a, stroke):
    """Largest drop of U over an arc shorter than a revolution [Eq. (3)], and that arc.

    Returns (drop [J], arc length [rad], travel over the arc [m]) per design; the travel is
    (base difference) + (local difference), exact when both ends lie near one dead centre.
    """
    x2 = np.concatenate([x, x + TWO_PI], axis=1)
    u2 = np.concatenate([u, u + a[:, None]], axis=1)
    b2 = np.concatenate([base, base + 2.0 * stroke[:, None]], axis=1)
    l2 = np.concatenate([local, local], axis=1)
    top = np.maximum.accumulate(u2, axis=1)
    j = np.argmax(top - u2, axis=1)
    idx = np.arange(x.shape[0])
    drop = top[idx, j] - u2[idx, j]
    # the arc starts at the last node before j where U reached that running maximum
    cols = np.arange(u2.shape[1])
    i = np.argmax((u2 == top[idx, j][:, None]) & (cols[None, :] <= j[:, None]), axis=1)
    travel = (b2[idx, j] - b2[idx, i]) + (l2[idx, j] - l2[idx, i])
    return drop, x2[idx, j] - x2[idx, i], travel


def energy_deficit(lk: FourBar, dead_centre_extended, dead_centre_folded, wheel_torque, peak_force):
    """Least energy band W [J] an operator limited to ``peak_force`` needs: D(Fp) of Eq. (3).

    The flywheel must be able to give up this much kinetic energy on the arcs where the
    quasi-static force exceeds ``peak_force``; infinite when the peak is below F_mean (the
    operator cannot do a cycle's work).  Broadcasts over designs.

    Parameters
    ----------
    lk : linkage (scalars or 1-D arrays over designs).
    dead_centre_extended, dead_centre_folded : dead-centre crank angles [rad].
    wheel_torque : Mw [N m];  peak_force : the operator's largest |F| [N].
    """
    prep, scalar = _prepare(lk, dead_centre_extended, dead_centre_folded, wheel_torque)
    fp = np.broadcast_to(np.asarray(peak_force, float), prep.dce.shape).astype(float)
    out = np.full(prep.dce.shape, np.nan)
    with np.errstate(all="ignore"):
        ok = np.isfinite(prep.stroke) & np.isfinite(fp)
        low = ok & (fp < _qs.mean_force(prep.mw, prep.stroke) * (1 - 1e-15))
        out[low] = np.inf
        rows = np.nonzero(ok & ~low)[0]
        if rows.size:
            x, u, b, loc, a = _refined_extrema(prep, fp[rows], rows)
            out[rows] = _drawdown(x, u, b, loc, np.maximum(a, 0.0), prep.stroke[rows])[0]
    return float(out[0]) if scalar else out


def least_peak_force(lk: FourBar, dead_centre_extended, dead_centre_folded, wheel_torque, energy_band):
    """Least peak operator force [N] for a periodic motion inside the energy band, Eq. (4).

    Exact to solver tolerance (Dinkelbach's iteration on Eq. (3), every extremum refined).
    Between F_mean (W -> inf: an infinite flywheel) and the quasi-static maximum (W -> 0: no
    flywheel, infinite at the dead centres).

    Parameters
    ----------
    lk : linkage (scalars or 1-D arrays over designs).
    dead_centre_extended, dead_centre_folded : dead-centre crank angles [rad].
    wheel_torque : Mw [N m].
    energy_band : W = J w_bar^2 delta [J] (:func:`energy_band`).

    Returns
    -------
    Fp* [N]: inf where the band is zero or Fp* exceeds FORCE_CAP_RATIO * F_mean, NaN for an
    infeasible design.
    """
    prep, scalar = _prepare(lk, dead_centre_extended, dead_centre_folded, wheel_torque)
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


def _dinkelbach(prep: _Prepared, lam, band, active, refine: bool, cap):
    """Dinkelbach's iteration for Eq. (4) from ``lam`` (a lower bound) on the designs ``active``."""
    lam = lam.copy()
    for _ in range(100):
        if active.size == 0:
            break
        x, u, b, loc, a = _refined_extrema(prep, lam[active], active, refine)
        drop, length, travel = _drawdown(x, u, b, loc, np.maximum(a, 0.0), prep.stroke[active])
        new = (prep.mw[active] * length - band[active]) / travel  # Eq. (4): the arc's ratio
        grow = (drop > band[active]) & (new > lam[active])
        done = ~grow | (new - lam[active] <= RTOL * new)
        lam[active] = np.where(grow, new, lam[active])
        capped = lam[active] > cap[active]
        lam[active[capped]] = np.inf
        active = active[~(done | capped)]
    return lam


def min_passing_speed(
    lk: FourBar,
    dead_centre_extended,
    dead_centre_folded,
    wheel_torque,
    force_limit,
    inertia,
    speed_fluctuation,
):
    """Least mean wheel speed [rad/s] at which ``force_limit`` suffices: w = sqrt(D(F_limit) / (J delta)).

    From Eq. (2)-(3): the design passes iff D(F_limit) <= J w_bar^2 delta.  Infinite when the
    limit is below F_mean (no speed helps), NaN for an infeasible design.
    """
    need = energy_deficit(lk, dead_centre_extended, dead_centre_folded, wheel_torque, force_limit)
    with np.errstate(all="ignore"):
        return np.sqrt(need / (np.asarray(inertia, float) * speed_fluctuation))


# ----------------------------------------------------------------------------- one design in detail
@dataclass(frozen=True)
class Scene:
    """The flywheel scene of one design at one speed (SI units, radians).

    Attributes
    ----------
    inertia : J [kg m^2];  mean_speed : w_bar [rad/s];  speed_fluctuation : delta_allow [-].
    energy_band : W = J w_bar^2 delta_allow [J].
    least_peak_force : Fp*, least peak operator force [N].
    mean_force : F_mean [N].
    fluctuation : delta of the reported motion [-] (= delta_allow unless Fp* = F_mean).
    max_speed, min_speed : w_max, w_min of the reported motion [rad/s].
    ceiling : (k, 2) crank angles [rad] of the arcs on which the wheel is at w_max and the
        operator pushes only the quasi-static force; elsewhere |F| = Fp*.
    top_angle : crank angle [rad] where the motion is at w_max (start of the verification).
    peaks_phi, peaks_u : the refined local maxima of U [rad from the extended dead centre, J] and
        drift : U(phi + 2 pi) - U(phi) [J], from which :func:`wheel_speed` follows.
    """

    inertia: float
    mean_speed: float
    speed_fluctuation: float
    energy_band: float
    least_peak_force: float
    mean_force: float
    fluctuation: float
    max_speed: float
    min_speed: float
    ceiling: np.ndarray
    top_angle: float
    linkage: FourBar
    wheel_torque: float
    dead_centre_extended: float
    dead_centre_folded: float
    peaks_phi: np.ndarray
    peaks_u: np.ndarray
    drift: float


def _local_maxima(x, u, a0):
    """Indices of the local maxima of U over one period (neighbours wrap with the drift a0)."""
    u_prev = np.concatenate([[u[-1] - a0], u[:-1]])
    u_next = np.concatenate([u[1:], [u[0] + a0]])
    return np.nonzero((u >= u_prev) & (u > u_next))[0]


def scene(
    lk: FourBar,
    dead_centre_extended: float,
    dead_centre_folded: float,
    wheel_torque: float,
    inertia: float,
    mean_speed: float,
    speed_fluctuation: float,
    solved: float | None = None,
) -> Scene:
    """Solve the flywheel scene of one design: Fp*, the operator's force profile and w(t).

    The reported motion is the "as full as possible" one of the module docstring at Fp*: the
    operator pushes Fp* in the grip's direction of motion, except on the ``ceiling`` arcs where
    the wheel is at its top speed and the push is the quasi-static force.
    """
    from scipy.optimize.elementwise import find_root

    band = float(energy_band(inertia, mean_speed, speed_fluctuation))
    if solved is None:  # Fp* of this scene, unless the caller has it already
        solved = least_peak_force(lk, dead_centre_extended, dead_centre_folded, wheel_torque, band)
    fp = solved
    prep, _ = _prepare(lk, dead_centre_extended, dead_centre_folded, wheel_torque)
    f_mean = float(_qs.mean_force(wheel_torque, prep.stroke[0]))
    nan = float("nan")
    if not np.isfinite(fp):
        return Scene(
            inertia,
            mean_speed,
            speed_fluctuation,
            band,
            fp,
            f_mean,
            nan,
            nan,
            nan,
            np.empty((0, 2)),
            nan,
            lk,
            wheel_torque,
            dead_centre_extended,
            dead_centre_folded,
            np.empty(0),
            np.empty(0),
            nan,
        )
    x, u, b, loc, a = _refined_extrema(prep, np.array([fp]))
    a0 = max(float(a[0]), 0.0)
    drop = float(_drawdown(x, u, b, loc, np.array([a0]), prep.stroke)[0][0])
    x, u = x[0], u[0]
    # local maxima of U (refined) and their running maximum over the previous revolution
    peaks = _local_maxima(x, u, a0)
    xm, um = x[peaks], u[peaks]
    ceil = []
    args = prep.args(slice(0, 1))
    for m in range(peaks.size):
        # maxima in (xm - 2 pi, xm): the earlier ones this revolution and the later ones shifted back
        before = np.concatenate([um[:m], um[m + 1 :] - a0, [um[m] - a0]])
        level = before.max()
        if um[m] <= level:
            continue  # below an earlier top: the wheel is not full here
        # the ceiling arc starts where U climbs back to `level`, after the previous local minimum
        k = peaks[m]
        lo_idx = k - 1
        while True:  # walk back to the preceding node below `level` (wrapping, at most one revolution)
            xl = x[lo_idx % x.size] - (TWO_PI if lo_idx < 0 else 0.0)
            ul = u[lo_idx % x.size] - (a0 if lo_idx < 0 else 0.0)
            if ul <= level or lo_idx < k - x.size:
                break
            lo_idx -= 1
        res = find_root(
            lambda t, *p, level=level: _u_integral(t, fp, *p, prep.mw[:1]) - level,
            (xl, xm[m]),
            args=args,
            tolerances=dict(xatol=0.0, xrtol=1e-15),
        )
        ceil.append((float(res.x[0]), float(xm[m])))
    ceiling = np.mod(np.array(ceil).reshape(-1, 2) + dead_centre_extended, TWO_PI)
    top = float(np.mod(xm[np.argmax(um)] + dead_centre_extended, TWO_PI))
    fluct = drop / (inertia * mean_speed**2)  # Eq. (2): the range of E is the drawdown
    return Scene(
        inertia,
        mean_speed,
        speed_fluctuation,
        band,
        float(fp),
        f_mean,
        fluct,
        mean_speed * (1 + fluct / 2),
        mean_speed * (1 - fluct / 2),
        ceiling,
        top,
        lk,
        float(wheel_torque),
        float(dead_centre_extended),
        float(dead_centre_folded),
        xm,
        um,
        a0,
    )


def on_ceiling(sc: Scene, crank_angle):
    """True where a crank angle lies on one of the scene's ceiling arcs."""
    th = np.asarray(crank_angle, float)
    out = np.zeros(th.shape, bool)
    for s, e in sc.ceiling:
        out |= np.mod(th - s, TWO_PI) <= np.mod(e - s, TWO_PI)
    return out


def operator_force(sc: Scene, crank_angle):
    """The reported operator force profile F(t) [N], +x positive.

    Fp* in the grip's direction of motion, the quasi-static force on the ceiling arcs; at a
    dead centre (grip at rest) the push reverses and the force is reported as 0.
    """
    th = np.asarray(crank_angle, float)
    st = kinematic_state(sc.linkage, th, sc.wheel_torque)
    push = sc.least_peak_force * np.sign(st.handle_rate)
    return np.where(on_ceiling(sc, th) & ~st.singular, st.force, push)


def wheel_speed(sc: Scene, crank_angle):
    """Wheel speed w(t) [rad/s] of the reported motion (energy balance Eq. (1) from the top)."""
    th = np.asarray(crank_angle, float)
    prep, _ = _prepare(sc.linkage, sc.dead_centre_extended, sc.dead_centre_folded, sc.wheel_torque)
    xm, um, a0 = sc.peaks_phi, sc.peaks_u, sc.drift
    phi = np.mod(th - sc.dead_centre_extended, TWO_PI)
    uphi = _u_integral(phi, sc.least_peak_force, *prep.args(slice(0, 1)), prep.mw[:1])
    # running maximum of U over (phi - 2 pi, phi]: U(phi) itself or a local maximum in the window
    cand_x = np.concatenate([xm, xm - TWO_PI])
    cand_u = np.concatenate([um, um - a0])
    col = phi.reshape(-1, 1)
    inside = (cand_x <= col) & (cand_x > col - TWO_PI)
    top = np.maximum(uphi.reshape(-1), np.where(inside, cand_u, -np.inf).max(axis=1)).reshape(phi.shape)
    energy = 0.5 * sc.inertia * sc.max_speed**2 - (top - uphi)  # Eq. (1) from the top of the band
    return np.sqrt(2.0 * energy / sc.inertia)


# ----------------------------------------------------------------------------- cross-check
@dataclass(frozen=True)
class TimeIntegration:
    """Equation of motion integrated in time under the scene's force profile (scipy ``solve_ivp``).

    Attributes
    ----------
    cycles : revolutions integrated.
    speeds_at_start : w [rad/s] each time the crank passes the start angle again (periodic: all
        equal to the first).
    periodicity : max |w_k - w_0| / w_0 over those passes [-].
    max_speed, min_speed : over the last revolution [rad/s].
    mean_speed : (w_max + w_min) / 2 over the last revolution [rad/s].
    time_mean_speed : 2 pi / (duration of the last revolution) [rad/s].
    fluctuation : (w_max - w_min) / mean_speed [-].
    """

    cycles: int
    speeds_at_start: np.ndarray
    periodicity: float
    max_speed: float
    min_speed: float
    mean_speed: float
    time_mean_speed: float
    fluctuation: float


def integrate_motion(sc: Scene, cycles: int = 4, rtol: float = 1e-11) -> TimeIntegration:
    """Integrate J dw/dt = (F(t) g(t) - Mw) (Eq. (1) in time) from the reported top speed.

    The force is the reported profile F(t) as a function of the crank angle alone (open loop):
    an error in the profile shows as a drift from one revolution to the next.
    """
    from scipy.integrate import solve_ivp

    j, mw, t0 = sc.inertia, sc.wheel_torque, sc.top_angle

    def rhs(_t, y):
        th = y[0]
        g = kinematic_state(sc.linkage, th, 1.0).handle_rate
        return [
            y[1],
            (float(operator_force(sc, th)) * float(g) - mw) / j,
        ]  # Eq. (1): J w dw/dt = (F g - Mw) w

    def turn(_t, y):
        return np.sin(0.5 * (y[0] - t0))  # zero each time the crank is back at the start angle

    turn.terminal = cycles + 1  # the start itself may count as a crossing
    turn.direction = 0.0
    horizon = 4.0 * cycles * TWO_PI / sc.min_speed
    # On the top-speed arcs dw/dt is exactly 0, so the error estimate vanishes and, unbounded, one
    # step could jump over whole revolutions: at most 1/64 revolution per step.
    sol = solve_ivp(
        rhs,
        (0.0, horizon),
        [t0, sc.max_speed],
        method="DOP853",
        rtol=rtol,
        atol=1e-12 * sc.max_speed,
        events=turn,
        dense_output=True,
        max_step=TWO_PI / 64 / sc.max_speed,
    )
    times = sol.t_events[0]
    times = times[times > 1e-9 * horizon][:cycles]
    speeds = np.array([sc.max_speed] + [float(sol.sol(t)[1]) for t in times])
    last0, last1 = (times[-2] if times.size > 1 else 0.0), times[-1]
    w = sol.sol(np.linspace(last0, last1, 40001))[1]
    wmax, wmin = float(w.max()), float(w.min())
    mean = 0.5 * (wmax + wmin)
    return TimeIntegration(
        int(times.size),
        speeds,
        float(np.max(np.abs(speeds - speeds[0])) / speeds[0]),
        wmax,
        wmin,
        mean,
        TWO_PI / (last1 - last0),
        (wmax - wmin) / mean,
    )


# ----------------------------------------------------------------------------- neglected effects
def link_energy(lk: FourBar, crank_angle, mean_speed, mass_per_length=LINK_MASS_PER_METRE):
    """Kinetic energy [J] of the coupler and the handle at crank angles, turning at ``mean_speed``.

    Both are taken as uniform bars of ``mass_per_length`` [kg/m] (the handle from the rocker pivot
    to the grip, length max(H, rocker)); a uniform bar whose ends move at vA, vB has
    T = m (vA^2 + vA.vB + vB^2) / 6.  The crank is part of the wheel.
    """
    th = np.asarray(crank_angle, float)
    st = kinematic_state(lk, th, 1.0)
    w = mean_speed
    c = lk.crank
    vax, vay = -w * c * np.sin(th), w * c * np.cos(th)
    w4 = st.rocker_rate * w
    rx, ry = st.coupler_x - lk.pivot_x, st.coupler_y - lk.pivot_y
    vbx, vby = -w4 * ry, w4 * rx
    coupler = (
        mass_per_length
        * lk.coupler
        / 6.0
        * (vax * vax + vay * vay + vax * vbx + vay * vby + vbx * vbx + vby * vby)
    )
    arm = np.maximum(lk.handle, lk.rocker)
    handle = mass_per_length * arm / 6.0 * (w4 * arm) ** 2
    return coupler + handle
