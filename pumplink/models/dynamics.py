"""Full one-degree-of-freedom dynamics: link masses, their weight and the operator's arms.

The flywheel scene (:mod:`pumplink.models.flywheel`) carries only the wheel's inertia J.  Here the
coupler and the handle move with their masses, the handle's weight rises and falls, and an
optional point mass at the grip stands for the operator's hands and forearms (docs/models.md §3).
The scene's terms I(t), V(t) and the energy band, Eq. (5)-(8), are
:mod:`pumplink.models.dynamics_terms`; the least peak force in it, exactly,
:mod:`pumplink.models.dynamics_solver`.  Here: the sizes that decide the model choice, the
cadence (the best mean speed and the passing range), and one design in detail (the reported
motion, its force and speed profiles, and their check by time integration).

Pure functions on floats / arrays over designs; SI units, radians.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from pumplink.constants import CADENCE_RTOL, GRAVITY, PASSING_SPEED_RTOL
from pumplink.mechanisms.angles import TWO_PI
from pumplink.mechanisms.fourbar import FourBar, per_design
from pumplink.mechanisms.fourbar_kernel import alike_designs
from pumplink.models import flywheel as _fw
from pumplink.models import quasi_static as _qs
from pumplink.models.conditions import Masses
from pumplink.models.dynamics_solver import least_peak_force, problem, refined_points, solve
from pumplink.models.dynamics_terms import Terms, coefficients, point_terms, terms_from
from pumplink.models.grip_travel import (
    GAUSS_LEGENDRE_NODES,
    GAUSS_LEGENDRE_WEIGHTS,
    TRAVEL_INTEGRATION_ARC,
    grip_position,
    grip_rate,
    travel_parts,
)

# ----------------------------------------------------------------------------- model choice, cadence
#: Crank angles per revolution on which the links' largest kinetic energy and the range of their
#: potential energy are taken for the model choice (1 deg steps).
EFFECT_GRID = 360
#: Designs (of distinct kinds) whose sizes are found together: their (designs, EFFECT_GRID) arrays
#: stay in the cache (a batch's chunk at once held ~100 MB of temporaries, faulted in each chunk).
EFFECT_BLOCK = 128


def effect_sizes(lk: FourBar, masses: Masses, mean_speed, gravity=GRAVITY, rocker_rate=None):
    """The sizes the model choice compares with the flywheel's energy band (docs/models.md §3).

    Parameters
    ----------
    lk : linkage (scalars or 1-D arrays over designs).
    masses : coupler and handle masses [kg]; ``grip`` is the operator's arms [kg].
    mean_speed : w_bar [rad/s].
    rocker_rate : max|dt4/dt2| of each design when known [-] (None: found here).

    Returns
    -------
    (link_energy, link_weight, arm_energy) [J]: the coupler's and handle's largest kinetic energy
    at w_bar and the range of their potential energy over a revolution (both on
    :data:`EFFECT_GRID` crank angles), and the largest kinetic energy of the arms at the grip,
    m (H max|dt4/dt| w_bar)^2 / 2 (exact: :func:`pumplink.mechanisms.fourbar.peak_rocker_rate`;
    0 where the arm mass is 0).
    """
    from pumplink.mechanisms.fourbar import peak_rocker_rate

    known = rocker_rate is not None
    scalar, arrays = per_design(lk, masses.coupler, masses.handle, masses.grip, mean_speed,
                                rocker_rate if known else np.nan)  # fmt: skip
    geom, (mc, mh, ma, w, rate) = arrays[:7], arrays[7:]
    th = np.arange(EFFECT_GRID) * (TWO_PI / EFFECT_GRID)
    # designs alike in linkage and link masses (a grid's variants in load or speed): once per kind
    first, kind = alike_designs(*geom, mc, mh)
    own = [v if first is None else v[first] for v in (*geom, mc, mh)]
    top, weight = np.empty(own[0].shape), np.empty(own[0].shape)
    with np.errstate(all="ignore"):
        for s in range(0, top.size, EFFECT_BLOCK):  # blocks whose (designs, angles) arrays stay in the cache
            b = slice(s, s + EFFECT_BLOCK)
            col = FourBar(*(v[b, None] for v in own[:7]))
            co = coefficients(col, Masses(own[7][b, None], own[8][b, None], 0.0))
            tm = terms_from(co, th, gravity, rates=False, grip=False)
            top[b] = tm[0].max(axis=1)
            weight[b] = np.ptp(tm[2], axis=1)
        if first is not None:
            top, weight = top[kind], weight[kind]
        link = 0.5 * top * w * w
        # the peak rate only where arms are carried: a search that leaves them out of the verdict
        # passes no arm mass and skips the refinement (about half its cost per small batch)
        arm = np.zeros(np.shape(ma))
        r = np.nonzero(ma != 0.0)[0]
        if r.size:
            at = rate[r] if known else peak_rocker_rate(FourBar(*(v[r] for v in geom)))
            arm[r] = 0.5 * ma[r] * (geom[5][r] * at * w[r]) ** 2
    out = (link, weight, arm)
    return tuple(float(v[0]) for v in out) if scalar else out


def _at_speed(lk, dead_centre_extended, dead_centre_folded, wheel_torque, inertia, masses, fluctuation, g):
    """Fp*(mean speed) of one design, the other arguments fixed (:func:`least_peak_force`)."""

    def fp(w):
        return least_peak_force(
            lk, dead_centre_extended, dead_centre_folded, wheel_torque, inertia, masses, w, fluctuation, g
        )

    return fp


def best_speed(
    lk: FourBar,
    dead_centre_extended: float,
    dead_centre_folded: float,
    wheel_torque: float,
    inertia: float,
    masses: Masses,
    speed_fluctuation: float,
    lowest: float,
    highest: float,
    gravity: float = GRAVITY,
    points: int = 25,
):
    """The mean speed in [lowest, highest] [rad/s] with the least Fp*, and that Fp* [N] (one design).

    Every pair's N of (C1)-(C2) is affine in w_bar^2 (the band's edges are V + I w^2 / 2) and its K
    does not depend on w_bar, so Fp* = max(F_mean, max over pairs of N/K) is convex in w_bar^2
    (docs/models.md §3a): the least value on ``points`` speeds brackets the minimum, which scipy's
    bounded scalar minimiser then locates (to ``CADENCE_RTOL``, 1e-7, of the speed).
    """
    from scipy.optimize import minimize_scalar

    design = (lk, dead_centre_extended, dead_centre_folded, wheel_torque, inertia, masses)
    fp = _at_speed(*design, speed_fluctuation, gravity)

    w = np.linspace(lowest, highest, points)
    f = fp(w)
    if not np.isfinite(f).any():
        return float("nan"), float("inf")
    k = int(np.nanargmin(np.where(np.isfinite(f), f, np.inf)))
    a, b = w[max(k - 1, 0)], w[min(k + 1, points - 1)]
    res = minimize_scalar(
        lambda x: fp(x), bounds=(a, b), method="bounded", options=dict(xatol=CADENCE_RTOL * w[k])
    )
    if np.isfinite(res.fun) and res.fun <= f[k]:
        return float(res.x), float(res.fun)
    return float(w[k]), float(f[k])


def speed_range(
    lk: FourBar,
    dead_centre_extended: float,
    dead_centre_folded: float,
    wheel_torque: float,
    inertia: float,
    masses: Masses,
    speed_fluctuation: float,
    limit: float,
    lowest: float,
    highest: float,
    best: float,
    gravity: float = GRAVITY,
):
    """The mean speeds in [lowest, highest] with Fp* <= ``limit`` [rad/s]: (low, high), an interval
    because Fp* is convex in w_bar^2 (:func:`best_speed`); ``best`` is its minimiser.  NaN, NaN when
    none; an end of the interval at ``lowest`` or ``highest`` may continue beyond it."""
    from scipy.optimize import brentq

    design = (lk, dead_centre_extended, dead_centre_folded, wheel_torque, inertia, masses)
    fp = _at_speed(*design, speed_fluctuation, gravity)

    def excess(w):
        f = fp(w)
        return min(f, 1e6 * limit) - limit  # the cap's inf as a large finite value

    nan = float("nan")
    if not np.isfinite(best) or excess(best) > 0:
        return nan, nan
    ends = []
    for edge in (lowest, highest):
        if excess(edge) <= 0:
            ends.append(float(edge))
        else:
            root = brentq(excess, *sorted((edge, best)), xtol=PASSING_SPEED_RTOL * best, rtol=1e-12)
            ends.append(float(root))
    return ends[0], ends[1]


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
    travel: tuple  # the grip-travel arguments of pumplink.models.grip_travel for this design


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
    pb, _ = problem(*args, speed_fluctuation, gravity)
    fp = float(solve(pb)[0]) if force is None else float(force)
    pts = ()
    if np.isfinite(fp):
        pts = tuple(v[0] for v in refined_points(pb, np.array([fp]), np.array([0]))[0])
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


def _point_margins(sc: Scene):
    """The scene's refined points x [rad] and, at them, upper - Q (``al``) and upper - P (``de``)
    [J], with the shifts a and b [J] of Q and P over a revolution: what :func:`_profile` takes
    the past and future minima of."""
    fp, mw, s = sc.least_peak_force, sc.wheel_torque, sc.stroke
    x, kb, kl, kup, _klo = sc.points
    gk = kb + kl
    a = 2.0 * fp * s - TWO_PI * mw
    b = -2.0 * fp * s - TWO_PI * mw
    al = kup - (fp * gk - mw * x)  # upper - Q at the points
    de = kup - (-fp * gk - mw * x)  # upper - P
    return x, a, b, al, de


def _profile(sc: Scene, crank_angle):
    """Energy e, regime (-1 brake, 0 ride, +1 push), upper's rate, V, I, g and the links' terms at
    crank angles (1-D): :func:`_profiles` of the scene as a batch of one (the same values)."""
    th = np.atleast_1d(np.asarray(crank_angle, float))
    *values, tm = _profiles(_batch_of_one(sc), th[None, :])
    first = Terms(
        *(None if v is None else v[0] for v in (tm.inertia, tm.inertia_rate, tm.potential, tm.potential_rate,
                                                tm.grip_rate, tm.grip_x)),
        tuple(v[0] for v in tm.closure),
    )  # fmt: skip
    return (*(v[0] for v in values), first)


def _batch_of_one(sc: Scene) -> Scenes:
    """The scene as :class:`Scenes` of one design (its values as (1, 1) columns, its points as a
    row)."""

    def col(v):
        return np.reshape(np.asarray(v, float), (1, 1))

    return Scenes(
        FourBar(*(col(v) for v in sc.linkage.parameters)),
        col(sc.dead_centre_extended),
        col(sc.wheel_torque),
        col(sc.inertia),
        Masses(col(sc.masses.coupler), col(sc.masses.handle), col(sc.masses.grip)),
        sc.gravity,
        col(sc.least_peak_force),
        col(sc.max_speed**2),
        col(sc.stroke),
        tuple(np.reshape(np.asarray(v, float), (1, -1)) for v in sc.points),
        [col(v) for v in sc.travel],
    )


def _profile_at(sc: Scene):
    """:func:`_profile` at one crank angle at a time, for the right-hand side of
    :func:`integrate_motion`: returns ``at(crank_angle)`` giving (e, regime, dup, V, I, g, terms) of
    one crank angle as floats (``terms``: I - J, I', V, V', ... of :func:`point_terms`), the same
    operations in the same order as :func:`_profile`, so the same rounding
    (tests/models/test_scalar_paths.py holds the two together).

    The per-scene parts are computed once: the points' upper - Q and upper - P (and their shifts by
    a revolution) sorted by angle with their running minima from both ends, so the past and future
    minima are two look-ups (:func:`bisect.bisect_left`) instead of a pass over the points.  The
    links' terms and the grip position (Px at dce + phi, :func:`pumplink.models.grip_travel.grip_position`)
    come from :func:`point_terms`, the grip travel near a dead centre from the same Gauss-Legendre
    sum as :func:`pumplink.models.grip_travel.travel_parts`.  Beyond the first turn (phi rounded up
    to 2 pi) or where a value is not finite, the call takes :func:`_profile` itself.
    """
    import bisect
    import math

    fp, mw = sc.least_peak_force, sc.wheel_torque
    dce = sc.dead_centre_extended
    x, a, b, al, de = _point_margins(sc)
    order = np.argsort(x, kind="stable")
    xs = [float(v) for v in x[order]]
    inf = np.array([np.inf])

    def running(v, reverse=False):  # running minimum with inf at the empty end, as floats
        if reverse:
            return [float(u) for u in np.minimum.accumulate(np.concatenate([v[order], inf])[::-1])[::-1]]
        return [float(u) for u in np.minimum.accumulate(np.concatenate([inf, v[order]]))]

    # past: min over x < phi of al and over x >= phi of al + a; future: min over x > phi of de and
    # over x <= phi of de - b (the vector route's np.where(...).min())
    before_al, after_ala = running(al), running(al + a, reverse=True)
    before_deb, after_de = running(de - b), running(de, reverse=True)
    fast = x.size > 0 and bool(np.isfinite(al).all() and np.isfinite(de).all())
    tr = sc.travel
    geom_dce, plus, xe, xf, stroke = (float(v) for v in tr[7:])
    terms_at = point_terms(sc.linkage, sc.masses, sc.gravity)
    geom = tuple(float(v) for v in tr[:7])
    grip_at = point_terms(FourBar(*geom), Masses(), 0.0)
    j0, w2 = sc.inertia, sc.max_speed**2
    arc = TRAVEL_INTEGRATION_ARC

    def vector(th):
        e, reg, dup, v, i, g, tm = _profile(sc, th)
        tm = tuple(float(u[0]) for u in (tm.inertia, tm.inertia_rate, tm.potential, tm.potential_rate))
        return float(e[0]), int(reg[0]), float(dup[0]), float(v[0]), float(i[0]), float(g[0]), tm

    def at(crank_angle):
        th = float(crank_angle)
        if not fast:
            return vector(th)
        phi = (th - dce) % TWO_PI  # np.mod's floor remainder
        if math.floor(phi / TWO_PI) != 0:  # rounded up to a full turn: travel_parts counts a turn
            return vector(th)
        # grip_travel.travel_parts at one angle in its first turn (p = phi), away from the dead centres
        to_fold = phi - plus
        at_fold = abs(to_fold) <= min(phi, TWO_PI - phi)
        sd = to_fold if at_fold else (phi if phi <= TWO_PI - phi else phi - TWO_PI)
        base = (stroke if at_fold else (0.0 if sd >= 0 else 2.0 * stroke)) + 0.0
        tm = terms_at(th, fly_x=True)
        if abs(sd) < arc:  # integrated from the rate on the 12 Gauss-Legendre nodes, as there
            nodes = 0.5 * sd * (1.0 + GAUSS_LEGENDRE_NODES)
            rate = grip_rate((geom_dce + plus if at_fold else geom_dce) + nodes, *geom)
            local = float(0.5 * sd * (np.abs(rate) * GAUSS_LEGENDRE_WEIGHTS).sum(axis=-1))
        else:
            at_grip = geom_dce + phi  # where it rounds to th, the terms' loop closure gave Px (_grip_x)
            px_grip = tm[6] if at_grip == th else grip_at(at_grip, rates=False, values=False, fly_x=True)[6]
            local = (1.0 if sd > 0 else -1.0) * abs(px_grip - (xf if at_fold else xe))
        g_phi = base + local
        i = j0 + tm[0]
        up = tm[2] + 0.5 * i * w2
        dup = tm[3] + 0.5 * tm[1] * w2
        k = bisect.bisect_left(xs, phi)  # points with x < phi
        past = min(before_al[k], after_ala[k])
        k = bisect.bisect_right(xs, phi)  # points with x <= phi
        future = min(before_deb[k], after_de[k])
        cand = (fp * g_phi - mw * phi + past, up, -fp * g_phi - mw * phi + future)
        if not all(map(math.isfinite, cand)):
            return vector(th)
        e = min(cand)
        return e, 1 - cand.index(e), dup, tm[2], i, tm[4], tm

    return at


# ----------------------------------------------------------------------------- many designs at once
@dataclass(frozen=True)
class Scenes:
    """The reported motions of many designs at once, for the part checks of a batch: the data of
    :class:`Scene` that the motion on the cycle needs, per-design values as columns (D, 1), the
    refined points (x, base, local, up, lo) as rows (D, P) (sorted; a short row repeats its last
    point, which changes no minimum).  :func:`motion_state` of it is that of each design's
    :class:`Scene` (the same operations on the same values; tests/models/test_part_routes.py)."""

    linkage: FourBar
    dead_centre_extended: np.ndarray
    wheel_torque: np.ndarray
    inertia: np.ndarray
    masses: Masses
    gravity: float
    least_peak_force: np.ndarray
    max_speed_squared: np.ndarray  # w_hi^2 as Scene.max_speed**2 (Python's pow) rounds it
    stroke: np.ndarray
    points: tuple
    travel: list

    def take(self, rows) -> Scenes:
        """The scenes of designs ``rows`` (indices, repeats allowed)."""
        n = self.least_peak_force.shape[0]
        if rows.size == n and np.array_equal(rows, np.arange(n)):
            return self

        def pick(v):
            return v[rows]

        return Scenes(
            FourBar(*(pick(v) for v in self.linkage.parameters)),
            pick(self.dead_centre_extended),
            pick(self.wheel_torque),
            pick(self.inertia),
            Masses(*(pick(v) for v in vars(self.masses).values())),
            self.gravity,
            pick(self.least_peak_force),
            pick(self.max_speed_squared),
            pick(self.stroke),
            tuple(pick(v) for v in self.points),
            [pick(v) for v in self.travel],
        )


def scenes(lk: FourBar, dead_centre_extended, dead_centre_folded, wheel_torque, inertia, masses: Masses,
           mean_speed, speed_fluctuation, force, gravity: float = GRAVITY) -> Scenes:  # fmt: skip
    """:func:`scene` of many designs (1-D arrays over designs) solved at ``force`` [N] (finite:
    each design's least peak force), as :class:`Scenes`: one problem and one refinement of the
    points for all of them."""
    args = (lk, dead_centre_extended, dead_centre_folded, wheel_torque, inertia, masses, mean_speed)
    pb, _ = problem(*args, speed_fluctuation, gravity)
    n = pb.mw.size
    fp = np.array(np.broadcast_to(np.asarray(force, float), (n,)))
    pts, _ = refined_points(pb, fp, np.arange(n))

    def col(v):
        return np.reshape(v, (n, 1))

    w2 = np.array([float(w) ** 2 for w in pb.w_hi])  # Scene.max_speed**2: a Python float's pow
    return Scenes(
        FourBar(*(col(v) for v in pb.lk.parameters)),
        col(pb.prep.dce),
        col(pb.mw),
        col(pb.inertia),
        Masses(col(pb.masses.coupler), col(pb.masses.handle), col(pb.masses.grip)),
        gravity,
        col(fp),
        col(w2),
        col(pb.stroke),
        pts,
        pb.travel,
    )


#: Points a design up to which :func:`_profiles` counts the points before each angle column by
#: column (two comparisons a point, counted in bytes), beyond which all at once (a (D, K, points)
#: comparison).
_COUNT_BY_COLUMN = 12


def _profiles(scs: Scenes, crank_angle, trig=None):
    """:func:`_profile` of many designs: crank angles (D, K), the same operations on the same
    values per design.  The past and future minima over the points come from running minima
    along the sorted points and the count of points before each angle (a minimum is exact in
    any order; NaN sorts last, as a comparison leaves it out).  ``trig``: as :func:`motion_state`."""
    th = np.asarray(crank_angle, float)
    fp, mw = scs.least_peak_force, scs.wheel_torque
    phi = _past_extended(th, scs.dead_centre_extended)
    with np.errstate(all="ignore"):  # as terms(closure=True), and the grip's Px at the same angles
        co = coefficients(scs.linkage, scs.masses)
        out = terms_from(co, th, scs.gravity, grip=False, fly_x=True, closure=True, trig=trig)
    tm = Terms(*out[:6], out[7])
    base, local = travel_parts(phi, *scs.travel, grip_x=_grip_x(scs, th, phi, out[6]))
    g_phi = base + local
    i = scs.inertia + tm.inertia
    up = tm.potential + 0.5 * i * scs.max_speed_squared
    dup = tm.potential_rate + 0.5 * tm.inertia_rate * scs.max_speed_squared
    past, future = _minima(scs, phi)
    # fp g - Mw phi + past and -fp g - Mw phi + future: (-fp) g - Mw phi is -(fp g + Mw phi), bit
    # for bit (rounding is symmetric)
    fp_g, mw_phi = fp * g_phi, mw * phi
    push, brake = fp_g - mw_phi + past, future - (fp_g + mw_phi)
    # the three candidates' minimum and the first that takes it (NaN: the first NaN), as
    # np.min and np.argmin over them stacked give them
    e = np.minimum(np.minimum(push, up), brake)
    regime = np.where(np.isnan(push) | (push == e), _PUSH, np.where(np.isnan(up) | (up == e), _RIDE, _BRAKE))
    return e, regime, dup, tm.potential, i, tm.grip_rate, tm


#: The regimes as bytes (an array of them is an eighth of one of int64).
_PUSH, _RIDE, _BRAKE = np.int8(1), np.int8(0), np.int8(-1)


def _past_extended(th, dead_centre_extended):
    """np.mod(th - dce, 2 pi) [rad]: where every difference is within a turn, its remainder is the
    difference itself, plus 2 pi where negative (np.mod's exact fmod and its one sign correction,
    +0 for a zero), without the general remainder's cost."""
    r = th - dead_centre_extended
    if not (r.min(initial=0.0) > -TWO_PI and r.max(initial=0.0) < TWO_PI):  # NaN fails too
        return np.mod(r, TWO_PI)
    np.add(r, TWO_PI, out=r, where=r < 0)
    r += 0.0  # -0 as +0
    return r


def _grip_x(scs: Scenes, th, phi, grip_x):
    """The grip's Px [m] at crank angles dce + phi (D, K), as
    :func:`pumplink.models.grip_travel.grip_position` gives it there, from ``grip_x``, Px at
    ``th`` from the terms' loop closure (the same operations): where dce + phi rounds to th itself
    (phi = th - dce exactly: th at or past dce, within twice it) that is the value; elsewhere
    (dce + phi is th + 2 pi, rounded) the position is found anew, on the rows and the span of
    columns that hold such angles.  ``grip_x`` is overwritten."""
    at = scs.dead_centre_extended + phi
    same = at == th
    rows = np.nonzero(~same.all(axis=1))[0]
    if rows.size == 0:
        return grip_x
    cols = np.nonzero(~same[rows].all(axis=0))[0]
    span = slice(cols[0], cols[-1] + 1)
    found = grip_position(at[rows, span], *(v[rows] for v in scs.travel[:7]))
    grip_x[rows, span] = np.where(same[rows, span], grip_x[rows, span], found)
    return grip_x


def _minima(scs: Scenes, phi):
    """The past and future minima of :func:`_profile` at phi (D, K) [rad]: the least upper - Q
    over t in (phi - 2 pi, phi) and upper - P over (phi, phi + 2 pi) [J], from the running minima
    of both sides of the sorted points taken at the count of points before phi."""
    x, a, b, al, de = _point_margins(scs)
    inf = np.full((x.shape[0], 1), np.inf)

    def before(v):  # [k]: the minimum of v over the first k points
        return np.minimum.accumulate(np.concatenate([inf, v], axis=1), axis=1)

    def after(v):  # [k]: the minimum of v over the points from the k-th on
        return np.minimum.accumulate(np.concatenate([v, inf], axis=1)[:, ::-1], axis=1)[:, ::-1]

    if x.shape[1] <= _COUNT_BY_COLUMN:  # a few points a design: counted column by column, in bytes
        below = np.zeros(phi.shape, np.int8)  # points with x < phi
        upto = np.zeros(phi.shape, np.int8)  # points with x <= phi
        for j in range(x.shape[1]):
            below += x[:, j : j + 1] < phi
            upto += x[:, j : j + 1] <= phi
    else:  # many: all at once
        below = np.count_nonzero(x[:, None, :] < phi[..., None], axis=-1)
        upto = np.count_nonzero(x[:, None, :] <= phi[..., None], axis=-1)
    # the minimum of the two sides' minima at a count is the minimum at the count of the two
    # sides' minima (one look-up each)
    past = np.take_along_axis(np.minimum(before(al), after(al + a)), below, axis=1)  # t in (phi - 2 pi, phi)
    future = np.take_along_axis(np.minimum(before(de - b), after(de)), upto, axis=1)  # t in (phi, phi + 2 pi)
    return past, future


def regime(sc: Scene, crank_angle):
    """-1 where the operator brakes with Fp, 0 where the motion rides the top of the band, +1 where
    the operator pushes Fp with the grip."""
    return _profile(sc, crank_angle)[1]


def operator_force(sc: Scene, crank_angle):
    """The reported operator force F(t) [N], +x positive (0 at a dead centre, where g = 0)."""
    out = _force(sc, *_profile(sc, crank_angle)[1:])
    return out if np.ndim(crank_angle) else float(out[0])


def _force(sc: Scene, regime, dup, _v, _i, g, _tm):
    with np.errstate(all="ignore"):
        ride = (dup + sc.wheel_torque) / g  # Eq. (7) along the top of the band
        f = np.where(regime == 0, ride, regime * sc.least_peak_force * np.sign(g))
    return np.where(g == 0, 0.0, f)


def _force_at(sc: Scene, regime, dup, _v, _i, g, _tm):
    """:func:`_force` on the floats of :func:`_profile_at` (one crank angle)."""
    if g == 0:
        return 0.0  # a dead centre
    if regime == 0:
        return (dup + sc.wheel_torque) / g  # Eq. (7) along the top of the band
    return regime * sc.least_peak_force * (1.0 if g > 0 else -1.0 if g < 0 else g)  # np.sign: NaN for NaN


def wheel_speed(sc: Scene, crank_angle):
    """Wheel speed w(t) [rad/s] of the reported motion: sqrt(2 (e - V) / I)."""
    e, _r, _d, v, i, _g, _tm = _profile(sc, crank_angle)
    with np.errstate(invalid="ignore"):
        out = np.sqrt(2.0 * (e - v) / i)
    return out if np.ndim(crank_angle) else float(out[0])


def motion_state(sc: Scene | Scenes, crank_angle, trig=None):
    """:func:`operator_force`, :func:`wheel_speed` and the links' :func:`terms` at crank angles
    (1-D; of :class:`Scenes`, (D, K): K angles per design), from one evaluation of the profile:
    (force [N], speed [rad/s], terms).  ``trig``: (cos, sin) of the crank angles of
    :class:`Scenes` where known already (the cycle's: the same angles for every design)."""
    prof = _profiles(sc, crank_angle, trig) if isinstance(sc, Scenes) else _profile(sc, crank_angle)
    e, v, i, tm = prof[0], prof[3], prof[4], prof[6]
    with np.errstate(invalid="ignore"):
        speed = np.sqrt(2.0 * (e - v) / i)
    return _force(sc, *prof[1:]), speed, tm


def integrate_motion(
    sc: Scene, cycles: int = 4, rtol: float = 1e-11, by_pieces: bool = True
) -> _fw.TimeIntegration:
    """Integrate I t'' + I'/2 t'^2 + V' = F g - Mw (Eq. (7) in time, scipy ``solve_ivp``) under the
    reported force profile F(t) (open loop), from the reported speed at the extended dead centre.
    ``by_pieces``: piece by piece of the profile (:func:`profile_pieces`; the same motion in under a
    third of the right-hand side's evaluations), else the whole profile at each step."""
    t0 = sc.dead_centre_extended
    mw = sc.wheel_torque

    profile_at = _profile_at(sc)

    def rhs(_t, y):
        # one evaluation of the profile per call gives F and the links' terms, on floats
        _e, reg, dup, _v, i, g, tm = prof = profile_at(y[0])
        f = _force_at(sc, *prof[1:])
        return [y[1], (f * g - mw - tm[3] - 0.5 * tm[1] * y[1] ** 2) / i]

    pieces = profile_pieces(sc, profile_at) if by_pieces else None
    return _fw.revolutions(rhs, t0, wheel_speed(sc, t0), sc.min_speed, sc.max_speed, cycles, rtol, pieces)


#: Crank angles a turn on which :func:`profile_pieces` looks for the ends of the pieces.
PIECE_GRID = 8192
#: Shortest piece kept [rad]: a shorter one joins its neighbour (a piece must be crossed by a step).
PIECE_MIN = 1e-9


def profile_pieces(sc: Scene, profile_at=None):
    """The reported force profile in pieces over the turn from the extended dead centre, for
    :func:`pumplink.models.flywheel.revolutions`: (ends, right-hand sides).  A piece ends where the
    regime or the sign of g changes: F g jumps there (between +-Fp |g| and the ride's dV/dt + Mw) or
    has a kink (|g| at a dead centre).  The changes are looked for on :data:`PIECE_GRID` angles and
    each end bisected to adjacent floats on the profile itself (a piece shorter than a grid cell
    can only lie between two crossings of nearly touching candidates, where the two regimes' forces
    nearly agree).  A piece's right-hand side is Eq. (7) with the regime of its middle: I a =
    F g - Mw - V' - I' w^2 / 2, F g = +-Fp |g| pushing or braking and dV/dt + I' w_hi^2 / 2 + Mw
    riding the band's top, smooth past its ends."""
    at = _profile_at(sc) if profile_at is None else profile_at
    dce, fp, mw = sc.dead_centre_extended, sc.least_peak_force, sc.wheel_torque
    j0, w2 = sc.inertia, sc.max_speed**2
    th = dce + np.arange(PIECE_GRID) * (TWO_PI / PIECE_GRID)
    _e, reg, _d, _v, _i, g, _tm = _profile(sc, th)
    key = 2 * reg.astype(int) + (g > 0)

    def key_at(t):
        p = at(t)
        return 2 * int(p[1]) + (p[5] > 0)

    ends: list[float] = []
    for k in np.nonzero(key != np.roll(key, -1))[0].tolist():
        a, b = float(th[k]), (float(th[k + 1]) if k + 1 < PIECE_GRID else dce + TWO_PI)
        ka, m = key_at(a), 0.5 * (a + b)
        while a < m < b:  # bisection to adjacent floats
            a, b = (m, b) if key_at(m) == ka else (a, m)
            m = 0.5 * (a + b)
        if b - (ends[-1] if ends else dce) > PIECE_MIN and dce + TWO_PI - b > PIECE_MIN:
            ends.append(b)
    ends.append(dce + TWO_PI)
    terms_at = point_terms(sc.linkage, sc.masses, sc.gravity)

    def piece(start, end):
        p = at(0.5 * (start + end))
        push = p[1] * fp * (1.0 if p[5] > 0 else -1.0)  # F g = +-Fp |g|: pushing or braking

        def rhs(_t, y):
            i_j, rate, _v, v_rate, g = terms_at(y[0])[:5]
            if p[1] == 0:  # riding the band's top: F g - Mw = V' + I' w_hi^2 / 2
                return [y[1], 0.5 * rate * (w2 - y[1] * y[1]) / (j0 + i_j)]
            return [y[1], (push * g - mw - v_rate - 0.5 * rate * y[1] ** 2) / (j0 + i_j)]

        return rhs

    return ends, [piece(a, b) for a, b in zip([dce, *ends[:-1]], ends, strict=True)]


def agrees(sc: Scene, sim: _fw.TimeIntegration, rtol: float = 1e-6) -> bool:
    """The time integration is periodic, inside the band and at the mean speed, to ``rtol``."""
    return bool(
        sim.cycles > 0
        and sim.periodicity <= rtol
        and abs(sim.mean_speed - sc.mean_speed) <= rtol * sc.mean_speed
        and sim.min_speed >= sc.min_speed * (1 - rtol)
        and sim.max_speed <= sc.max_speed * (1 + rtol)
    )
