"""Full one-degree-of-freedom dynamics: link masses, their weight and the operator's arms.

The flywheel scene (:mod:`pumplink.models.flywheel`) carries only the wheel's inertia J.  Here the
coupler and the handle move with their masses, the handle's weight rises and falls, and an
optional point mass at the grip stands for the operator's hands and forearms (docs/models.md §3).

The scene
---------
Generalised coordinate: the crank angle t (= the wheel's angle).  Kinetic and potential energy

    T = I(t) w^2 / 2,   I(t) = J + sum over moving links (m |v_G|^2 + I_G w_link^2) / w^2    (5)
    V(t) = g_n (sum of m y_G)                                                              (6)

with the coupler and the handle (the rocker extended from O4 to the grip, length max(H, rocker))
as uniform bars, the point mass at the grip, and g_n the standard gravity.  The energy balance per
crank radian (the power balance F vx - Mw w = d(T + V)/dt divided by w) still contains no w:

    dE/dt = F g(t) - Mw,   E = T + V,   g = dPx/dt                                    (7)

The speed band w in [w_bar (1 - delta/2), w_bar (1 + delta/2)] is the t-dependent band on E

    lower(t) = V + I w_lo^2 / 2  <=  E  <=  upper(t) = V + I w_hi^2 / 2                  (8)

The flywheel scene is the special case I = J, V = 0 (a constant band of width J w_bar^2 delta).

The least peak force, exactly (docs/models.md §3, the proof)
-----------------------------------------------------------
With |F| <= Fp the slope of E lies in [-Fp |g| - Mw, Fp |g| - Mw]; with G the grip's horizontal
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
their derivatives (analytic: I', V' from the acceleration analysis).

Pure functions on floats / arrays over designs; SI units, radians.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from pumplink.constants import GRAVITY
from pumplink.mechanisms.angles import TWO_PI
from pumplink.mechanisms.fourbar import FourBar, loop_closure, per_design
from pumplink.models import flywheel as _fw
from pumplink.models import quasi_static as _qs

#: Uniform grid nodes per revolution that bracket the extrema before refinement (the refinement
#: makes the answer exact; features of the four functions narrower than a cell, 3.75 deg, are merged).
GRID = 96
#: Geometric nodes each side of a dead centre, at cell / 4**k for k = 1..CLUSTER (down to ~1e-5 rad).
CLUSTER = 6
#: Relative convergence of Dinkelbach's iteration on the peak force.
RTOL = 1e-13
#: Peak forces above this multiple of F_mean are reported as infinite (as in the flywheel scene).
FORCE_CAP_RATIO = _fw.FORCE_CAP_RATIO
#: Bracket width [rad] at which the extremum refinement stops.
REFINE_XTOL = 1e-12
#: Most iterations of the refinement (safeguarded Newton: 3-5 in practice).
REFINE_ITER = 60
#: Finite-difference step of the refinement's Newton iteration, as a fraction of the bracket.
REFINE_STEP = 1e-6


# ----------------------------------------------------------------------------- masses
@dataclass(frozen=True)
class Masses:
    """Moving masses of the linkage (floats or arrays over designs) [kg].

    Attributes
    ----------
    coupler : mass of the coupler, a uniform bar from the crank pin A to the joint B.
    handle : mass of the handle, a uniform bar from the rocker pivot O4 along the rocker, of
        length max(H, rocker).
    grip : point mass at the grip (the operator's hands and forearms), 0 for the hand force.
    """

    coupler: np.ndarray | float = 0.0
    handle: np.ndarray | float = 0.0
    grip: np.ndarray | float = 0.0


def bar_masses(lk: FourBar, mass_per_length, grip=0.0) -> Masses:
    """Coupler and handle as uniform bars of ``mass_per_length`` [kg/m]; ``grip`` [kg] at the grip."""
    return Masses(
        mass_per_length * np.asarray(lk.coupler, float),
        mass_per_length * np.maximum(lk.handle, lk.rocker),
        grip,
    )


# ----------------------------------------------------------------------------- I, I', V, V'
@dataclass(frozen=True)
class Terms:
    """Reduced inertia and potential of the links at crank angles (wheel inertia J not included).

    inertia : I - J [kg m^2];  inertia_rate : dI/dt [kg m^2/rad];  potential : V [J];
    potential_rate : dV/dt [J/rad];  grip_rate : g = dPx/dt [m/rad].
    """

    inertia: np.ndarray
    inertia_rate: np.ndarray
    potential: np.ndarray
    potential_rate: np.ndarray
    grip_rate: np.ndarray


def terms(lk: FourBar, crank_angle, masses: Masses, gravity=GRAVITY) -> Terms:
    """I(t) - J, I'(t), V(t), V'(t) and g(t) of Eq. (5)-(7) (docs/models.md §3).

    Velocity coefficients h3 = dt3/dt, h4 = dt4/dt and their derivatives from the loop closure
    A + coupler e3 = O4 + rocker e4 differentiated once and twice (unit crank speed, no crank
    acceleration); no instant centres, nothing divides by zero for a crank-rocker (sin(t3 - t4)
    is the sine of the transmission angle).
    """
    th = np.asarray(crank_angle, float)
    cs, sn = np.cos(th), np.sin(th)
    px, py, c, k, r, hh = lk.pivot_x, lk.pivot_y, lk.crank, lk.coupler, lk.rocker, lk.handle
    with np.errstate(all="ignore"):
        _p1, _p2, _e2, t, q = loop_closure(lk, cs, sn)
        dx, dy = px - c * cs, py - c * sn
        ux, uy = t * dx - q * dy, t * dy + q * dx  # B - A (Eq. (6) of pumplink.mechanisms.fourbar)
        e3x, e3y = ux / k, uy / k
        e4x, e4y = (c * cs + ux - px) / r, (c * sn + uy - py) / r
        s34 = e3y * e4x - e3x * e4y  # sin(t3 - t4)
        c34 = e3x * e4x + e3y * e4y
        s24 = sn * e4x - cs * e4y  # sin(t2 - t4)
        c24 = cs * e4x + sn * e4y
        s23 = sn * e3x - cs * e3y  # sin(t2 - t3)
        c23 = cs * e3x + sn * e3y
        h3 = -c * s24 / (k * s34)  # first derivative of the loop closure
        h4 = -c * s23 / (r * s34)
        d3 = (-c * c24 - k * h3 * h3 * c34 + r * h4 * h4) / (k * s34)  # second derivative
        d4 = (-c * c23 - k * h3 * h3 + r * h4 * h4 * c34) / (r * s34)
        # coupler centre: velocity and acceleration coefficients
        vx = -c * sn - 0.5 * k * h3 * e3y
        vy = c * cs + 0.5 * k * h3 * e3x
        ax = -c * cs - 0.5 * k * (d3 * e3y + h3 * h3 * e3x)
        ay = -c * sn + 0.5 * k * (d3 * e3x - h3 * h3 * e3y)
        arm = np.maximum(hh, r)
        mc, mh, ma = masses.coupler, masses.handle, masses.grip
        ic = mc * k * k / 12.0
        i4 = mh * arm * arm / 3.0 + ma * hh * hh  # about O4
        inertia = mc * (vx * vx + vy * vy) + ic * h3 * h3 + i4 * h4 * h4  # Eq. (5)
        rate = 2.0 * (mc * (vx * ax + vy * ay) + ic * h3 * d3 + i4 * h4 * d4)
        lever = 0.5 * mh * arm + ma * hh  # first moment about O4 along the rocker
        potential = gravity * (mc * (c * sn + 0.5 * k * e3y) + (mh + ma) * py + lever * e4y)  # Eq. (6)
        potential_rate = gravity * (mc * vy + lever * h4 * e4x)
        grip_rate = -hh * h4 * e4y
    return Terms(inertia, rate, potential, potential_rate, grip_rate)


def reduced_inertia(lk: FourBar, crank_angle, inertia, masses: Masses):
    """I(t) and dI/dt [kg m^2, kg m^2/rad] of Eq. (5): the wheel's J plus the links'."""
    tm = terms(lk, crank_angle, masses)
    return inertia + tm.inertia, tm.inertia_rate


def potential(lk: FourBar, crank_angle, masses: Masses, gravity=GRAVITY):
    """V(t) and dV/dt [J, J/rad] of Eq. (6), zero at the wheel axle's height."""
    tm = terms(lk, crank_angle, masses, gravity)
    return tm.potential, tm.potential_rate


def speed_limits(mean_speed, speed_fluctuation):
    """w_lo = w_bar (1 - delta/2), w_hi = w_bar (1 + delta/2) [rad/s]."""
    w = np.asarray(mean_speed, float)
    return w * (1.0 - 0.5 * speed_fluctuation), w * (1.0 + 0.5 * speed_fluctuation)


def energy_band(
    lk: FourBar, crank_angle, inertia, masses: Masses, mean_speed, speed_fluctuation, gravity=GRAVITY
):
    """The t-dependent band on E = T + V, Eq. (8): (lower, upper) [J]."""
    tm = terms(lk, crank_angle, masses, gravity)
    lo, hi = speed_limits(mean_speed, speed_fluctuation)
    i = inertia + tm.inertia
    return tm.potential + 0.5 * i * lo * lo, tm.potential + 0.5 * i * hi * hi


# ----------------------------------------------------------------------------- the solver
@dataclass(frozen=True)
class _Problem:
    """Per-design data (1-D arrays over D designs) and the grid nodes (D, M) of the flywheel scene."""

    prep: object  # flywheel._Prepared: geometry, dead centres, stroke, grip travel at the nodes
    lk: FourBar  # (D,) arrays
    inertia: np.ndarray
    masses: Masses  # (D,) arrays
    w_lo: np.ndarray
    w_hi: np.ndarray
    gravity: float
    mw: np.ndarray
    stroke: np.ndarray
    up: np.ndarray  # upper edge of the band at the nodes (D, M) [J]
    lo: np.ndarray  # lower edge [J]

    def points(self, idx):
        """The grid nodes of designs idx: (x, base, local, up, lo), each (len(idx), M)."""
        p = self.prep
        return p.nodes[idx], p.base[idx], p.local[idx], self.up[idx], self.lo[idx]

    def edges(self, phi, idx):
        """upper, lower, their rates and g at points phi [rad from the extended dead centre] of the
        designs idx (same shapes)."""
        lk = FourBar(*(v[idx] for v in self.lk.parameters))
        ms = Masses(self.masses.coupler[idx], self.masses.handle[idx], self.masses.grip[idx])
        tm = terms(lk, self.prep.dce[idx] + phi, ms, self.gravity)
        i = self.inertia[idx] + tm.inertia
        hi2, lo2 = 0.5 * self.w_hi[idx] ** 2, 0.5 * self.w_lo[idx] ** 2
        return (
            tm.potential + i * hi2,  # Eq. (8)
            tm.potential + i * lo2,
            tm.potential_rate + tm.inertia_rate * hi2,
            tm.potential_rate + tm.inertia_rate * lo2,
            tm.grip_rate,
        )


def _problem(lk, dce, dcf, wheel_torque, inertia, masses, mean_speed, speed_fluctuation, gravity):
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
    geom, (dce, dcf, mw, j, mc, mh, ma, w, delta) = arrays[:7], arrays[7:]
    lk1 = FourBar(*geom)
    prep, _ = _fw._prepare(lk1, dce, dcf, mw, GRID, CLUSTER)
    w_lo, w_hi = speed_limits(w, delta)
    ms = Masses(mc, mh, ma)
    d = np.broadcast_to(np.arange(dce.size)[:, None], prep.nodes.shape)
    half = _Problem(prep, lk1, j, ms, w_lo, w_hi, gravity, mw, prep.stroke, None, None)
    with np.errstate(all="ignore"):
        up, lo, *_ = half.edges(prep.nodes, d)
    return _Problem(prep, lk1, j, ms, w_lo, w_hi, gravity, mw, prep.stroke, up, lo), scalar


def _doubled(a, drift):
    return np.concatenate([a, a - drift[:, None]], axis=1)


def _pairs(x, base, local, up, lo, mw, stroke, lam):
    """The worst pair of (C1) and of (C2) at Fp = lam over the points x (sorted per row).

    Returns (h, ratio), each (D, 2) for the two families: h = max over pairs of N - lam K [J]
    (feasible iff h <= 0 in both), ratio = N / K of the maximising pair [N] (Dinkelbach's next
    iterate).  N and K of a pair: (C1) t <= s: N = lower(s) - upper(t) + Mw (s - t), K = G(s) - G(t);
    (C2) s <= t: N = lower(s) - upper(t) - Mw (t - s), K = G(t) - G(s).
    """
    n = x.shape[1]
    g = base + local
    m, la = mw[:, None], lam[:, None]
    a = 2.0 * lam * stroke - TWO_PI * mw  # Q(x + 2 pi) - Q(x)
    b = -2.0 * lam * stroke - TWO_PI * mw  # P(x + 2 pi) - P(x)
    q = la * g - m * x
    p = -la * g - m * x
    rows = np.arange(x.shape[0])
    cols = np.arange(2 * n)[None, :]
    out_h = np.empty((x.shape[0], 2))
    out_r = np.empty((x.shape[0], 2))

    def ratio(i, j, sign):  # N/K of the pair (earlier i, later j) on the doubled points
        xi, xj = x[rows, i % n] + TWO_PI * (i >= n), x[rows, j % n] + TWO_PI * (j >= n)
        gi = base[rows, i % n] + 2.0 * stroke * (i >= n)
        gj = base[rows, j % n] + 2.0 * stroke * (j >= n)
        k = (gj - gi) + (local[rows, j % n] - local[rows, i % n])  # no cancellation near a dead centre
        if sign > 0:  # (C1): t = i, s = j
            num = lo[rows, j % n] - up[rows, i % n] + mw * (xj - xi)
        else:  # (C2): s = i, t = j
            num = lo[rows, i % n] - up[rows, j % n] - mw * (xj - xi)
        return num / k

    # (C1): lower(s) - Q(s) - min over t <= s of (upper(t) - Q(t)) <= 0
    al = _doubled(up - q, a)
    run = np.minimum.accumulate(al, axis=1)
    v = _doubled(lo - q, a) - run
    j = np.argmax(v, axis=1)
    out_h[:, 0] = v[rows, j]
    i = np.argmax((al == run[rows, j][:, None]) & (cols <= j[:, None]), axis=1)
    out_r[:, 0] = ratio(i, j, 1)
    # (C2): max over s <= t of (lower(s) - P(s)) - (upper(t) - P(t)) <= 0
    ga = _doubled(lo - p, b)
    run = np.maximum.accumulate(ga, axis=1)
    v = run - _doubled(up - p, b)
    j = np.argmax(v, axis=1)
    out_h[:, 1] = v[rows, j]
    i = np.argmax((ga == run[rows, j][:, None]) & (cols <= j[:, None]), axis=1)
    out_r[:, 1] = ratio(i, j, -1)
    return out_h, out_r


def _dinkelbach(pts, mw, stroke, lam, cap):
    """Dinkelbach's iteration over the pairs of the points ``pts`` from the lower bound ``lam``.

    Every iterate is the ratio of a pair, so a lower bound of Fp*; it stops when no pair of the
    points is violated (or the iterate moves by less than RTOL).  Arrays over the rows of pts.
    """
    lam = lam.copy()
    active = np.arange(lam.size)
    for _ in range(200):
        if active.size == 0:
            break
        with np.errstate(all="ignore"):
            h, r = _pairs(*(v[active] for v in pts), mw[active], stroke[active], lam[active])
            r = np.where(h > 0, np.where(np.isnan(r), np.inf, r), -np.inf)
            new = r.max(axis=1)
        grow = new > lam[active]
        done = ~grow | (new - lam[active] <= RTOL * np.abs(new))
        lam[active] = np.where(grow, new, lam[active])
        capped = ~(lam[active] <= cap[active])
        lam[active[capped]] = np.inf
        active = active[~(done | capped)]
    return lam


def _extrema(pb: _Problem, lam, rows):
    """Local extrema of the four functions upper - Q, lower - Q, lower - P, upper - P on the grid
    nodes of designs ``rows`` at Fp = lam (per row): (design, node, lo, hi, edge, sign), with the
    neighbouring nodes (lo, hi) as the bracket."""
    x, base, local, up, low = pb.points(rows)
    g = base + local
    la, m = lam[:, None], pb.mw[rows][:, None]
    a = 2.0 * lam * pb.stroke[rows] - TWO_PI * pb.mw[rows]
    b = -2.0 * lam * pb.stroke[rows] - TWO_PI * pb.mw[rows]
    xp = np.concatenate([x[:, -1:] - TWO_PI, x[:, :-1]], axis=1)
    xn = np.concatenate([x[:, 1:], x[:, :1] + TWO_PI], axis=1)
    out = []
    for edge, sign, drift in ((0, -1.0, a), (1, -1.0, a), (1, 1.0, b), (0, 1.0, b)):
        f = (up if edge == 0 else low) + sign * la * g + m * x  # upper/lower minus Q (sign -1) or P (+1)
        fp = np.concatenate([f[:, -1:] + drift[:, None], f[:, :-1]], axis=1)
        fn = np.concatenate([f[:, 1:], f[:, :1] - drift[:, None]], axis=1)
        with np.errstate(invalid="ignore"):
            ext = ((f <= fp) & (f < fn)) | ((f >= fp) & (f > fn))
        d, k = np.nonzero(ext)
        out.append((d, x[d, k], xp[d, k], xn[d, k], np.full(d.size, edge), np.full(d.size, sign)))
    return [np.concatenate(v) for v in zip(*out, strict=True)]


def _refined_points(pb: _Problem, lam, rows):
    """Every local extremum of the four functions at Fp = lam, located to REFINE_XTOL by a root
    search on the analytic derivative (Newton, safeguarded by bisection, bracketed by the neighbouring grid
    nodes), as the points (x, base, local, up, lo), each (len(rows), K) sorted per row.

    The pairs of (C1)-(C2) are extreme at such points (a running minimum is attained at a local
    minimum, the largest excess after it at a local maximum), so the points hold the worst pair
    at this lam exactly; at another force they still give lower bounds.
    """
    d, node, lo, hi, edge, sign = _extrema(pb, lam, rows)
    dd = rows[d]
    lam_e, mw_e = lam[d], pb.mw[dd]

    def deriv(phi, reps=1):
        rep = (lambda v: np.tile(v, reps)) if reps > 1 else (lambda v: v)  # noqa: E731
        _u, _l, du, dl, g = pb.edges(phi, rep(dd))
        return np.where(rep(edge) == 0, du, dl) + rep(sign * lam_e) * np.abs(g) + rep(mw_e)

    with np.errstate(all="ignore"):
        a, b = lo.copy(), hi.copy()
        fa, fb = deriv(a), deriv(b)
        ok = np.isfinite(fa) & np.isfinite(fb) & (np.sign(fa) * np.sign(fb) < 0)
        c = (a * fb - b * fa) / (fb - fa)  # a secant step to start
        live = ok.copy()
        for _ in range(REFINE_ITER):  # Newton on the derivative, safeguarded by the bracket
            c = np.where((c > a) & (c < b), c, 0.5 * (a + b))
            step = REFINE_STEP * np.maximum(b - a, REFINE_XTOL)
            both = deriv(np.concatenate([c, c + step]), 2)
            fc, fh = both[: c.size], both[c.size :]
            left = np.sign(fc) == np.sign(fa)  # keep the root bracketed
            a = np.where(live & left, c, a)
            b = np.where(live & ~left, c, b)
            fa = np.where(live & left, fc, fa)
            newton = c - fc * step / (fh - fc)
            done = (np.abs(newton - c) <= REFINE_XTOL) | (fc == 0) | (b - a <= REFINE_XTOL)
            a = np.where(live & done, newton, a)
            b = np.where(live & done, newton, b)
            live &= ~done
            if not live.any():
                break
            c = np.where(live, newton, c)
    # no sign change of the derivative (an extremum at a node, e.g. a dead centre): the node itself
    root = np.mod(np.where(ok, 0.5 * (a + b), node), TWO_PI)
    count = np.bincount(d, minlength=rows.size)
    width = max(int(count.max()), 1)
    order = np.argsort(d, kind="stable")
    d, root = d[order], root[order]
    slot = np.arange(d.size) - (np.cumsum(count) - count)[d]
    first = np.repeat(np.where(count > 0, 0, np.nan), 1)  # rows without extrema: NaN (never)
    x = np.empty((rows.size, width))
    x[:] = root[(np.cumsum(count) - count).clip(max=max(d.size - 1, 0))][:, None] if d.size else 0.0
    x += first[:, None] * 0.0
    x[d, slot] = root
    x = np.sort(x, axis=1)
    args = [v[rows][:, None] for v in pb.prep.args()]
    with np.errstate(all="ignore"):
        base, local = _fw._travel_parts(x, *args)
        up, low, *_ = pb.edges(x, np.broadcast_to(rows[:, None], x.shape))
    return x, base, local, up, low


def _solve(pb: _Problem, max_passes: int = 12):
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
    # Dinkelbach over the pairs of grid nodes (a subset of all pairs: a lower bound), then passes
    # over the extrema refined at the current iterate until it no longer moves
    lam = _dinkelbach(pb.points(todo), pb.mw[todo], pb.stroke[todo], f_mean[todo], cap[todo])
    live = np.nonzero(np.isfinite(lam))[0]
    for _ in range(max_passes):
        if live.size == 0:
            break
        rows = todo[live]
        pts = _refined_points(pb, lam[live], rows)
        new = _dinkelbach(pts, pb.mw[rows], pb.stroke[rows], lam[live], cap[rows])
        moved = ~(new - lam[live] <= 4 * RTOL * np.abs(new))
        lam[live] = new
        live = live[moved & np.isfinite(new)]
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
    """Least peak operator force [N] for a periodic motion inside the band of Eq. (8).

    Exact up to the refinement tolerance ((C1)-(C2) of the module docstring, docs/models.md §3).
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
    pb, scalar = _problem(
        lk,
        dead_centre_extended,
        dead_centre_folded,
        wheel_torque,
        inertia,
        masses,
        mean_speed,
        speed_fluctuation,
        gravity,
    )
    out = _solve(pb)
    return float(out[0]) if scalar else out


def band_margin(
    lk: FourBar,
    dead_centre_extended,
    dead_centre_folded,
    wheel_torque,
    inertia,
    masses: Masses,
    mean_speed,
    speed_fluctuation,
    force,
    gravity=GRAVITY,
):
    """max over the pairs of (C1)-(C2) of N - Fp K at Fp = ``force`` [J]: for Fp >= F_mean a periodic
    motion inside the band exists iff this is <= 0 (docs/models.md §3)."""
    pb, scalar = _problem(
        lk,
        dead_centre_extended,
        dead_centre_folded,
        wheel_torque,
        inertia,
        masses,
        mean_speed,
        speed_fluctuation,
        gravity,
    )
    lam = np.broadcast_to(np.asarray(force, float), pb.mw.shape).astype(float)
    rows = np.arange(lam.size)
    pts = _refined_points(pb, lam, rows)
    with np.errstate(all="ignore"):
        h, _ = _pairs(*pts, pb.mw, pb.stroke, lam)
    out = h.max(axis=1)
    return float(out[0]) if scalar else out


# ----------------------------------------------------------------------------- one design in detail
@dataclass(frozen=True)
class Scene:
    """The dynamics of one design at one mean speed (SI units, radians).

    Attributes
    ----------
    least_peak_force : the peak force Fp of the reported motion [N] (Fp* unless given).
    mean_force : F_mean [N];  mean_speed, min_speed, max_speed : w_bar, w_lo, w_hi [rad/s].
    The reported motion is the largest one of docs/models.md §3, e = min(upper, Q + past minimum
    of (upper - Q), P + future minimum of (upper - P)): the operator pushes Fp with the grip,
    rides the top of the band, or brakes with Fp against the grip's motion.
    """

    linkage: FourBar
    dead_centre_extended: float
    dead_centre_folded: float
    wheel_torque: float
    inertia: float
    masses: Masses
    gravity: float
    mean_speed: float
    speed_fluctuation: float
    least_peak_force: float
    mean_force: float
    min_speed: float
    max_speed: float
    points: tuple  # refined extrema (x, base, local, up, lo) of the four functions at Fp, each (K,)
    stroke: float  # grip stroke S [m]
    travel: tuple  # the grip-travel arguments of pumplink.models.flywheel for this design


def scene(
    lk: FourBar,
    dead_centre_extended: float,
    dead_centre_folded: float,
    wheel_torque: float,
    inertia: float,
    masses: Masses,
    mean_speed: float,
    speed_fluctuation: float,
    gravity: float = GRAVITY,
    force: float | None = None,
) -> Scene:
    """Solve one design: Fp* (or take ``force``), and the data of the reported motion."""
    args = (lk, dead_centre_extended, dead_centre_folded, wheel_torque, inertia, masses, mean_speed)
    pb, _ = _problem(*args, speed_fluctuation, gravity)
    fp = float(_solve(pb)[0]) if force is None else float(force)
    pts = ()
    if np.isfinite(fp):
        pts = tuple(v[0] for v in _refined_points(pb, np.array([fp]), np.array([0])))
    return Scene(
        lk,
        float(dead_centre_extended),
        float(dead_centre_folded),
        float(wheel_torque),
        float(inertia),
        masses,
        gravity,
        float(mean_speed),
        float(speed_fluctuation),
        fp,
        float(_qs.mean_force(wheel_torque, pb.stroke[0])),
        float(pb.w_lo[0]),
        float(pb.w_hi[0]),
        pts,
        float(pb.stroke[0]),
        tuple(v[0] for v in pb.prep.args()),
    )


def _profile(sc: Scene, crank_angle):
    """Energy e, regime (-1 brake, 0 ride, +1 push), upper, its rate, V, I and g at crank angles."""
    th = np.atleast_1d(np.asarray(crank_angle, float))
    fp, mw, s = sc.least_peak_force, sc.wheel_torque, sc.stroke
    phi = np.mod(th - sc.dead_centre_extended, TWO_PI)
    base, local = _fw._travel_parts(phi, *sc.travel)
    g_phi = base + local
    tm = terms(sc.linkage, th, sc.masses, sc.gravity)
    i = sc.inertia + tm.inertia
    up = tm.potential + 0.5 * i * sc.max_speed**2
    dup = tm.potential_rate + 0.5 * tm.inertia_rate * sc.max_speed**2
    x, kb, kl, kup, _klo = sc.points
    gk = kb + kl
    a = 2.0 * fp * s - TWO_PI * mw
    b = -2.0 * fp * s - TWO_PI * mw
    al = kup - (fp * gk - mw * x)  # upper - Q at the points
    de = kup - (-fp * gk - mw * x)  # upper - P
    col = phi[:, None]
    past = np.where(x[None, :] < col, al, al + a).min(axis=1)  # t in (phi - 2 pi, phi)
    future = np.where(x[None, :] > col, de, de - b).min(axis=1)  # t in (phi, phi + 2 pi)
    cand = np.stack([fp * g_phi - mw * phi + past, up, -fp * g_phi - mw * phi + future])
    regime = 1 - np.argmin(cand, axis=0)
    return cand.min(axis=0), regime, dup, tm.potential, i, tm.grip_rate


def regime(sc: Scene, crank_angle):
    """-1 where the operator brakes with Fp, 0 where the motion rides the top of the band, +1 where
    the operator pushes Fp with the grip."""
    return _profile(sc, crank_angle)[1]


def operator_force(sc: Scene, crank_angle):
    """The reported operator force F(t) [N], +x positive (0 at a dead centre, where g = 0)."""
    _e, regime, dup, _v, _i, g = _profile(sc, crank_angle)
    with np.errstate(all="ignore"):
        ride = (dup + sc.wheel_torque) / g  # Eq. (7) along the top of the band
        f = np.where(regime == 0, ride, regime * sc.least_peak_force * np.sign(g))
    out = np.where(g == 0, 0.0, f)
    return out if np.ndim(crank_angle) else float(out[0])


def wheel_speed(sc: Scene, crank_angle):
    """Wheel speed w(t) [rad/s] of the reported motion: sqrt(2 (e - V) / I)."""
    e, _r, _d, v, i, _g = _profile(sc, crank_angle)
    with np.errstate(invalid="ignore"):
        out = np.sqrt(2.0 * (e - v) / i)
    return out if np.ndim(crank_angle) else float(out[0])


def integrate_motion(sc: Scene, cycles: int = 4, rtol: float = 1e-11) -> _fw.TimeIntegration:
    """Integrate I t'' + I'/2 t'^2 + V' = F g - Mw (Eq. (7) in time, scipy ``solve_ivp``) under the
    reported force profile F(t) (open loop), from the reported speed at the extended dead centre."""
    from scipy.integrate import solve_ivp

    t0 = sc.dead_centre_extended
    w0 = wheel_speed(sc, t0)
    mw = sc.wheel_torque

    def rhs(_t, y):
        tm = terms(sc.linkage, y[0], sc.masses, sc.gravity)
        f = operator_force(sc, y[0])
        i = sc.inertia + tm.inertia
        return [y[1], (f * tm.grip_rate - mw - tm.potential_rate - 0.5 * tm.inertia_rate * y[1] ** 2) / i]

    def turn(_t, y):
        return np.sin(0.5 * (y[0] - t0))

    turn.terminal = cycles + 1
    horizon = 4.0 * cycles * TWO_PI / sc.min_speed
    sol = solve_ivp(
        rhs,
        (0.0, horizon),
        [t0, w0],
        method="DOP853",
        rtol=rtol,
        atol=1e-12 * sc.max_speed,
        events=turn,
        dense_output=True,
        max_step=TWO_PI / 64 / sc.max_speed,
    )
    times = sol.t_events[0]
    times = times[times > 1e-9 * horizon][:cycles]
    if times.size == 0:  # the wheel stopped or turned back: no revolution completed
        nan = float("nan")
        return _fw.TimeIntegration(0, np.array([w0]), np.inf, nan, nan, nan, nan, np.inf)
    speeds = np.array([w0] + [float(sol.sol(t)[1]) for t in times])
    last0, last1 = (times[-2] if times.size > 1 else 0.0), times[-1]
    w = sol.sol(np.linspace(last0, last1, 40001))[1]
    wmax, wmin = float(w.max()), float(w.min())
    mean = 0.5 * (wmax + wmin)
    return _fw.TimeIntegration(
        int(times.size),
        speeds,
        float(np.max(np.abs(speeds - speeds[0])) / speeds[0]),
        wmax,
        wmin,
        mean,
        TWO_PI / (last1 - last0),
        (wmax - wmin) / mean,
    )


def agrees(sc: Scene, sim: _fw.TimeIntegration, rtol: float = 1e-6) -> bool:
    """The time integration is periodic, inside the band and at the mean speed, to ``rtol``."""
    return bool(
        sim.cycles > 0
        and sim.periodicity <= rtol
        and abs(sim.mean_speed - sc.mean_speed) <= rtol * sc.mean_speed
        and sim.min_speed >= sc.min_speed * (1 - rtol)
        and sim.max_speed <= sc.max_speed * (1 + rtol)
    )
