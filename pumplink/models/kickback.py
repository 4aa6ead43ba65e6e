"""The kick-back: how far the grip runs back when the operator lets go with water in the rising
main, let go at the worst moment (docs/workshop.md §3), for many designs at once.

The scene is the released handle's (:mod:`pumplink.models.release`) with **no losses counted**:
the pump's friction is not relied on to hold the wheel (a safety check credits no friction, as the
ratchet's required torque, the column's whole M_col = rho g head A rw, credits none).

Where the wheel stops
    From a release at any crank angle at the design speed the wheel coasts forward against the
    column and the links' weight until it stops at a crank angle ts; the coast's end is a continuous
    function of the release angle that gains 2 pi a turn, so it takes **every** crank angle where
    the wheel can come to rest (where the column plus the links' weight decelerates it,
    M_col + V'(ts) >= 0, V the links' potential).  The worst release is the one that stops the
    wheel at the worst ts, whatever the speed.

The run back
    From rest at ts the column drives the wheel back (M_col + V'(ts) >= 0, no friction holds it).
    With phi = ts - t the crank angle run back, s = rw phi the rope run back (the column's top
    falls by s), K the kinetic energy, the equation of motion of :mod:`pumplink.models.release`
    (the water leaving the pipe's foot takes its own kinetic energy) is linear in K along phi:

        dK/dphi = M_col (1 - phi/Lc) + V'(ts - phi) - a(phi) K,                         (K.1)
        a(phi) = Jc / (Lc (J - Jc phi/Lc + I(ts - phi))),   Lc = head / rw,

    J the wheel's inertia with the water (Jc of it), I(t) the links' reduced inertia.  The run
    ends where K first returns to 0, where the column is empty (phi = Lc), or, with a ratchet that
    holds the column, where its pawl catches: within one tooth, phi = 2 pi / teeth.

The travel
    The grip moves on a circle of radius H about O4; between the dead centres the rocker angle t4
    is monotone, so the grip's path over a crank interval is H times the sum of |delta t4| over its
    pieces between the dead centres (2 H swing a whole turn): a closed form (:func:`grip_path`).
    The kick-back is the largest path over the run back, over every stop angle ts.  Where the run
    reaches its end (the column empty, the pawl) from the stop angle whose window holds the most
    path, that path is the largest over every ts (no run is longer than its window): found on a
    grid of stop angles and refined by Chandrupatla's bracket; (K.1) is marched (RK4 on a periodic
    table of the links' terms) from that one ts to confirm that K stays positive.  Where it does
    not (heavy links on a light column), every stop angle of the grid is marched and the largest
    path taken.

Vectorised over designs (the grid of stop angles in blocks of designs that stay in the cache); SI
units, radians.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from pumplink.constants import GRAVITY, KICK_BACK_ENDS
from pumplink.mechanisms.angles import TWO_PI
from pumplink.mechanisms.bracket import find_minimum
from pumplink.mechanisms.fourbar import FourBar, peak_rocker_rate
from pumplink.mechanisms.fourbar_kernel import alike_designs, loop_closure
from pumplink.models.conditions import Masses

#: Stop angles per turn on which the window holding the most path is searched before it is refined
#: (2°: the path over a window has a few extrema a turn, the rocker rate's two humps at each end).
STOP_SAMPLES = 180
#: Steps per crank turn of the march of (K.1) (RK4 on 4° steps; the links' terms tabulated at twice
#: as many angles, the steps' ends and middles).  It runs only where the bound of
#: :func:`reaches_end` cannot tell (heavy links on a light column, a wheel of no given mass).
MARCH_STEPS = 90
#: Most crank angle one march runs back [rad]: past it the run is cut there (a deep well on a tiny
#: wheel: 200 m on 2 cm is 10,000 rad), its travel the path so far (a lower bound), ``end`` "limit".
MARCH_LIMIT = 10_000.0
#: Local maxima of the stop-angle grid refined (the largest is kept).
PEAKS = 3
#: How a run back ends (:data:`pumplink.constants.KICK_BACK_ENDS`): the column is empty, the
#: ratchet's pawl catches (within a tooth), the wheel stops again (the links' weight against the
#: column), or the march's limit; "held" where a ratchet with no play holds the column at once.
ENDS = KICK_BACK_ENDS


@dataclass(frozen=True)
class KickBack:
    """The kick-back of designs (arrays over designs; SI units, radians).

    travel : the grip's path over the run back [m], let go at the worst moment.
    stop_angle : the crank angle where the worst run back starts, in [0, 2 pi) [rad].
    run : the crank angle it runs back [rad];  end : its index in :data:`ENDS`.
    marched_all : True where every stop angle of the grid was marched (the run from the widest
        window ended early): the travel is then the largest on that grid.
    """

    travel: np.ndarray
    stop_angle: np.ndarray
    run: np.ndarray
    end: np.ndarray
    marched_all: np.ndarray


def _wrap(x):
    """An angle difference in [-pi, pi): ``np.mod(x + pi, 2 pi) - pi`` bit for bit.

    Where a = x + pi lies in [-2 pi, 4 pi) (every difference of two angles in [-pi, pi], the
    rocker's) the remainder is a, a + 2 pi or a - 2 pi, each as numpy's remainder gives it (its
    fmod is exact, and so is a - 2 pi there, by Sterbenz's lemma) without fmod's cost (a third of
    the kick-back's); numpy's remainder elsewhere (NaN, inf, far angles).
    """
    a = x + np.pi
    if np.ndim(a) and a.size:
        low, high = a.min(), a.max()  # NaN if any is
        if 0.0 <= low and high < TWO_PI:  # the rocker's angle differences, as a rule: a itself
            return a - np.pi
        if -TWO_PI <= low and high < 2.0 * TWO_PI:
            return ((a - TWO_PI * (a >= TWO_PI)) + TWO_PI * (a < 0.0)) - np.pi
    far = ~((a >= -TWO_PI) & (a < 2.0 * TWO_PI))
    return np.where(far, np.mod(a, TWO_PI), (a - TWO_PI * (a >= TWO_PI)) + TWO_PI * (a < 0.0)) - np.pi


def _rocker(lk: FourBar, th):
    """The rocker angle t4 at crank angles ``th`` [rad]: that of
    :func:`pumplink.mechanisms.fourbar.kinematic_state` (the same operations), nothing else."""
    with np.errstate(all="ignore"):
        cs, sn = np.cos(th), np.sin(th)
        _p1, _p2, _e2, t, q = loop_closure(lk, cs, sn)
        c = lk.crank
        dx, dy = lk.pivot_x - c * cs, lk.pivot_y - c * sn
        bx = c * cs + t * dx - q * dy
        by = c * sn + t * dy + q * dx
        return np.arctan2(by - lk.pivot_y, bx - lk.pivot_x)


def grip_path(lk: FourBar, dead_centre_extended, dead_centre_folded, start, stop, at_dc=None):
    """The grip's path length [m] while the crank turns from ``start`` to ``stop`` >= start [rad]:
    H times the total variation of the rocker angle, a closed form between the dead centres where
    the rocker reverses (broadcasts over designs and intervals).  ``at_dc``: the rocker's angles at
    the two dead centres where already known [rad]."""
    start, stop = np.broadcast_arrays(np.asarray(start, float), np.asarray(stop, float))
    dce, dcf = (np.asarray(v, float) for v in (dead_centre_extended, dead_centre_folded))
    if at_dc is None:
        at_dc = (_rocker(lk, dce), _rocker(lk, dcf))
    swing = np.abs(_wrap(at_dc[0] - at_dc[1]))
    length = stop - start
    turns = np.floor(length / TWO_PI)
    a = stop - (length - turns * TWO_PI)  # the partial turn [a, stop], shorter than 2 pi
    t_a, t_b = _rocker(lk, a), _rocker(lk, stop)
    # the dead centres inside (a, stop): the rocker reverses there
    inner, values = [], []
    for dc, t_dc in zip((dce, dcf), at_dc):
        k = np.ceil((a - dc) / TWO_PI)
        x = dc + TWO_PI * k
        inside = x < stop
        inner.append(np.where(inside, x, stop))
        values.append(np.where(inside, t_dc, t_b))
    first = inner[0] <= inner[1]
    v1 = np.where(first, values[0], values[1])
    v2 = np.where(first, values[1], values[0])
    partial = np.abs(_wrap(v1 - t_a)) + np.abs(_wrap(v2 - v1)) + np.abs(_wrap(t_b - v2))
    return lk.handle * (2.0 * swing * turns + partial)


def _closure(lk: FourBar) -> tuple:
    """The per-design constants of :func:`_rocker`'s loop closure, computed once (the same
    expressions as :func:`pumplink.mechanisms.fourbar_kernel.loop_closure`, so the same rounding):
    px, py, crank, |O4|^2 + crank^2, 2 crank, (coupler^2 - rocker^2) / 2, coupler^2, coupler,
    rocker^2, branch."""
    px, py, c, k, r = lk.pivot_x, lk.pivot_y, lk.crank, lk.coupler, lk.rocker
    return px, py, c, px * px + py * py + c * c, 2.0 * c, 0.5 * (k * k - r * r), k * k, k, r * r, lk.branch


def _rocker_from(co, cs, sn):
    """:func:`_rocker` from the constants of :func:`_closure` and the crank directions (cs, sn)
    (arrays): the same operations in the same order, so the same bits."""
    px, py, c, o2, c2, hkr, kk, k, rr, branch = co
    p1 = cs * px + sn * py
    e2 = o2 - c2 * p1
    t = 0.5 + hkr / e2
    ek = np.sqrt(e2) + k
    e_k = (e2 - kk) / ek
    # (e + k)**2 of coupler_height: numpy squares arrays (ek * ek, correctly rounded)
    q = branch * (np.sqrt((rr - e_k * e_k) * (ek * ek - rr)) / (2.0 * e2))
    ccs, csn = c * cs, c * sn
    dx, dy = px - ccs, py - csn
    bx = ccs + t * dx - q * dy
    by = csn + t * dy + q * dx
    return np.arctan2(by - py, bx - px)


def _window_path(co, handle, two_swing, dc, at_dc, start, stop, t_b=None):
    """:func:`grip_path` from ``start`` to ``stop`` (arrays) of designs given by the constants of
    :func:`_closure`, H, 2 swing, their dead centres (extended, folded) stacked and the rocker's
    angles there, with the rocker's angle at ``stop`` where known (``t_b``; else found beside the
    one at the partial turn's start, in one call): the same operations, so the same bits."""
    length = stop - start
    turns = np.floor(length / TWO_PI)
    a = stop - (length - turns * TWO_PI)  # the partial turn [a, stop], shorter than 2 pi
    if t_b is None:
        ends = np.empty((2,) + np.broadcast_shapes(np.shape(a), np.shape(stop)))
        ends[0], ends[1] = a, stop
        t_a, t_b = _rocker_from(co, np.cos(ends), np.sin(ends))
    else:
        t_a = _rocker_from(co, np.cos(a), np.sin(a))
    # the dead centres inside (a, stop): the rocker reverses there
    x = dc + TWO_PI * np.ceil((a - dc) / TWO_PI)
    inside = x < stop
    first = np.where(inside[0], x[0], stop) <= np.where(inside[1], x[1], stop)
    value = np.where(inside, at_dc, t_b)
    v1 = np.where(first, value[0], value[1])
    v2 = np.where(first, value[1], value[0])
    turn = np.empty((3,) + v1.shape)
    np.subtract(v1, t_a, out=turn[0])
    np.subtract(v2, v1, out=turn[1])
    np.subtract(t_b, v2, out=turn[2])
    turn = np.abs(_wrap(turn))
    return handle * (two_swing * turns + (turn[0] + turn[1] + turn[2]))


#: Designs whose grid of stop angles :func:`widest_window` evaluates at once (designs x
#: STOP_SAMPLES arrays of ~90 kB: they stay in the processor's cache).
GRID_DESIGNS = 64


def widest_window(lk: FourBar, dead_centre_extended, dead_centre_folded, window, samples=STOP_SAMPLES):
    """The stop angle ts whose window [ts - window, ts] holds the most grip path, and that path:
    (path [m], ts [rad]) over designs (1-D arrays), on ``samples`` stop angles a turn refined by
    Chandrupatla's bracket (the path is smooth in ts: its derivative H (|t4'(ts)| - |t4'(ts -
    window)|) is continuous, t4' vanishing at the dead centres).

    The path at a stop angle is :func:`grip_path`'s, computed by the same operations from the
    per-design constants of the loop closure (:func:`_closure`), the rocker's angles at the grid's
    stop angles from one cos and sin of the grid.  Designs that pose the same search (the same
    linkage, dead centres and window, bit for bit: a grid's variants that differ in the head, the
    pipe or the wheel only) are searched once."""
    dce, dcf, w = (np.asarray(v, float) for v in (dead_centre_extended, dead_centre_folded, window))
    first, kind = alike_designs(*lk.parameters, dce, dcf, w) if np.ndim(w) == 1 else (None, None)
    if first is not None:
        sub = FourBar(*(np.broadcast_to(np.asarray(v, float), w.shape)[first] for v in lk.parameters))
        wide = (np.broadcast_to(v, w.shape)[first] for v in (dce, dcf, w))
        path, angle = _widest_window(sub, *wide, samples)
        return path[kind], angle[kind]
    return _widest_window(lk, dce, dcf, w, samples)


def _widest_window(lk: FourBar, dead_centre_extended, dead_centre_folded, window, samples):
    """:func:`widest_window` of every design given (no two alike as a rule)."""
    n = np.size(window)
    out_path, out_angle = np.empty(n), np.empty(n)
    if n == 0:
        return out_path, out_angle
    grid = np.arange(samples) * (TWO_PI / samples)
    cos_grid, sin_grid = np.cos(grid), np.sin(grid)
    step = TWO_PI / samples
    dce, dcf = (np.asarray(v, float) for v in (dead_centre_extended, dead_centre_folded))
    w = np.asarray(window, float)
    with np.errstate(all="ignore"):
        co = _closure(lk)
        at_dce, at_dcf = _rocker(lk, dce), _rocker(lk, dcf)
        # per design: the closure's constants, H, 2 swing (grip_path's), the dead centres, the
        # rocker there and the window, one row each
        table = np.stack(np.broadcast_arrays(*co, lk.handle, 2.0 * np.abs(_wrap(at_dce - at_dcf)), dce, dcf,
                                             at_dce, at_dcf, w))  # fmt: skip
        path = np.empty((n, samples))
        for s0 in range(0, n, GRID_DESIGNS):
            rows = table[:, s0 : s0 + GRID_DESIGNS, None]
            t_b = _rocker_from(rows[:10], cos_grid, sin_grid)
            path[s0 : s0 + GRID_DESIGNS] = _window_path(
                rows[:10], rows[10], rows[11], rows[12:14], rows[14:16], grid - rows[16], grid, t_b
            )
    # the grid's PEAKS largest local maxima (the path may have two near-equal humps), each refined
    bump = (path >= np.roll(path, 1, axis=1)) & (path >= np.roll(path, -1, axis=1))
    j = np.argsort(np.where(bump, path, -np.inf), axis=1)[:, -PEAKS:]  # (n, PEAKS)
    best = np.take_along_axis(path, j, 1)
    x2 = grid[j]
    res = find_minimum(
        lambda x, design: _minus_path(x, design, table),
        (x2 - step, x2, x2 + step),
        args=(np.broadcast_to(np.arange(n)[:, None], j.shape),),
        tolerances=dict(xatol=1e-12, xrtol=0.0),
    )
    fx, rx = res.f_x.reshape(best.shape), res.x.reshape(best.shape)
    ok = res.success.reshape(best.shape) & (-fx >= best)
    value, where = np.where(ok, -fx, best), np.where(ok, rx, x2)
    k = np.argmax(value, axis=1)[:, None]
    out_path[:] = np.take_along_axis(value, k, 1)[:, 0]
    out_angle[:] = np.mod(np.take_along_axis(where, k, 1)[:, 0], TWO_PI)
    return out_path, out_angle


def _minus_path(x, design, table):
    """Minus the path over the window ending at stop angles ``x`` of designs ``design`` (indices
    into the columns of ``table``, :func:`widest_window`'s), for the bracket's minimisation."""
    rows = table.take(design.astype(np.intp), axis=1)
    with np.errstate(all="ignore"):
        return -_window_path(rows[:10], rows[10], rows[11], rows[12:14], rows[14:16], x - rows[16], x)


def _masses(masses: Masses) -> tuple:
    return masses.coupler, masses.handle, masses.grip


def _column(masses: Masses) -> Masses:
    """The masses as columns (designs x 1)."""
    return Masses(*(np.atleast_1d(np.asarray(m, float))[:, None] for m in _masses(masses)))


def _table(lk: FourBar, masses: Masses, angles, gravity):
    """The links' reduced inertia I - J and dV/dt at ``angles`` (designs x k) [kg m^2, J/rad]."""
    from pumplink.models import dynamics_terms as _dt  # only for the march: not loaded at startup

    co = _dt.coefficients(FourBar(*(np.atleast_1d(np.asarray(v, float))[:, None] for v in lk.parameters)),
                          _column(masses))  # fmt: skip
    with np.errstate(all="ignore"):
        out = _dt.terms_from(co, angles, gravity, grip=False)
    return out[0], out[3]


def march(lk: FourBar, masses: Masses, stop_angle, window, column_torque, column_window, inertia,
          column_inertia, gravity=GRAVITY, steps=MARCH_STEPS, limit=MARCH_LIMIT):  # fmt: skip
    """March (K.1) from rest at ``stop_angle`` over ``window`` [rad] of run back, designs x runs.

    Every argument broadcasts to (designs, runs) except ``lk`` and ``masses`` (per design, 1-D);
    ``column_window`` Lc = head / rw [rad], ``inertia`` J with the water [kg m^2], ``column_inertia``
    Jc the water's [kg m^2].  Returns (run [rad], end index into :data:`ENDS`): the crank angle run
    back where K first returns to 0 (located by the cubic through the step's ends and slopes),
    else the window (ends 0 column empty, 1 pawl: the window shorter than Lc) or ``limit`` (3).
    """
    ts, w, mcol, lc, jj, jc = np.broadcast_arrays(*(np.asarray(v, float) for v in (
        stop_angle, window, column_torque, column_window, inertia, column_inertia)))  # fmt: skip
    n, runs = ts.shape
    half = TWO_PI / (2 * steps)  # the table's spacing: the steps' ends and middles
    k_table = 2 * steps
    # the links' terms on each run's own periodic grid ts - m half, m = 0 .. 2 steps - 1
    offsets = np.arange(k_table) * half
    inert = np.empty((n, runs, k_table))
    slope = np.empty((n, runs, k_table))
    for r in range(runs):
        inert[:, r], slope[:, r] = _table(lk, masses, ts[:, r, None] - offsets[None, :], gravity)
    reach = np.minimum(w, limit)
    h = 2 * half

    def rate(m, phi, k):
        i_l, v_r = inert[..., m % k_table], slope[..., m % k_table]
        share = np.minimum(phi / lc, 1.0)
        a = jc / (lc * (jj - jc * share + i_l))
        return mcol * (1.0 - share) + v_r - a * k

    k = np.zeros((n, runs))
    f = rate(0, 0.0, k)
    end_run = np.full((n, runs), np.nan)
    going = np.ones((n, runs), bool)
    total = int(np.ceil(np.max(reach) / h)) if reach.size else 0
    for step in range(total):
        phi = step * h
        m = 2 * step
        k1 = f
        k2 = rate(m + 1, phi + half, k + half * k1)
        k3 = rate(m + 1, phi + half, k + half * k2)
        k_new = k + h * k3
        k4 = rate(m + 2, phi + h, k_new)
        k_new = k + h / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4)
        f_new = rate(m + 2, phi + h, k_new)
        # where K returns to 0 within this step (after the start): the cubic through the ends
        down = going & (k_new <= 0.0)
        if down.any():
            root = _hermite_root(k[down], f[down], k_new[down], f_new[down], h)
            end_run[down] = phi + root
        going &= ~down
        past = going & (phi + h >= reach)
        end_run[past] = reach[past]
        going &= ~past
        if not going.any():
            break
        k, f = np.where(going, k_new, k), np.where(going, f_new, f)
    end = np.where(end_run < reach, 2, np.where(w < lc, 1, 0))
    end = np.where((end != 2) & (w > limit), 3, end)
    return end_run, end


def _hermite_root(k0, f0, k1, f1, h):
    """The first zero in (0, h] of the cubic through (0, k0, slope f0) and (h, k1, slope f1), with
    k0 >= 0 >= k1: bisection on the cubic (60 halvings of the step)."""
    lo, hi = np.zeros_like(k0), np.full_like(k0, h)

    def cubic(x):
        t = x / h
        return ((2 * t**3 - 3 * t**2 + 1) * k0 + (t**3 - 2 * t**2 + t) * h * f0
                + (-2 * t**3 + 3 * t**2) * k1 + (t**3 - t**2) * h * f1)  # fmt: skip

    for _ in range(60):
        mid = 0.5 * (lo + hi)
        pos = cubic(mid) > 0.0
        lo, hi = np.where(pos, mid, lo), np.where(pos, hi, mid)
    return hi


def weight_torque_bound(lk: FourBar, dead_centre_extended, dead_centre_folded, masses: Masses, rocker_rate,
                        gravity=GRAVITY):  # fmt: skip
    """An upper bound of the links' weight torque |dV/dt| over a turn [N m]: with the coupler's
    centre at height (y_A + y_B)/2 and the handle's (a bar of length max(H, rocker) from O4) at
    O4 + (arm/2) sin t4, |dV/dt| <= g (m_c (c + r C R) / 2 + (m_h arm / 2 + m_grip H) C R), R the
    rocker's largest rate max|dt4/dt| and C the largest |cos t4| over the rocker's swing (1 where
    the swing holds a horizontal rocker)."""
    lo, hi = (_rocker(lk, np.asarray(x, float)) for x in (dead_centre_extended, dead_centre_folded))
    a, b = np.minimum(lo, hi), np.maximum(lo, hi)
    level = np.floor(b / np.pi) * np.pi >= a  # a multiple of pi (t4 = 0 or pi) inside the swing
    cos = np.where(level, 1.0, np.maximum(np.abs(np.cos(a)), np.abs(np.cos(b))))
    rate = np.asarray(rocker_rate, float) * 1.001  # the refined maximum, with room for its tolerance
    arm = np.maximum(lk.handle, lk.rocker)
    coupler = masses.coupler * (lk.crank + lk.rocker * cos * rate) / 2.0
    handle = (masses.handle * arm / 2.0 + masses.grip * lk.handle) * cos * rate
    return gravity * (coupler + handle)


def reaches_end(column_torque, column_window, window, inertia, column_inertia, weight_bound):
    """True where the run back surely reaches its window's end: K stays positive, by a bound.

    With |V'| <= Vm the drive of (K.1) is at least g(phi) = M_col (1 - phi/Lc) - Vm, and the factor
    exp(-int a) that discounts it is at least exp(-A), A = ln(J / (J - Jc L/Lc)) (I >= 0).  Where
    g >= 0 over the window K > 0 throughout; else, with phi0 where g = 0, K(phi) >= exp(-A) P -
    N(phi), P = (M_col - Vm) phi0 / 2 the gain before phi0 and N <= (M_col/Lc)(L - phi0)^2 / 2 the
    loss after it: positive where exp(-A) P > N(L)."""
    mcol, lc, w, jj, jc, vm = (np.asarray(v, float) for v in (column_torque, column_window, window, inertia,
                                                              column_inertia, weight_bound))  # fmt: skip
    with np.errstate(divide="ignore", invalid="ignore"):
        phi0 = lc * (1.0 - vm / mcol)
        rest = jj - jc * np.minimum(w / lc, 1.0)
        discount = np.where(rest > 0.0, rest / jj, 0.0)  # exp(-A)
        gain = 0.5 * (mcol - vm) * phi0
        loss = 0.5 * mcol / lc * np.maximum(w - phi0, 0.0) ** 2
        return (vm < mcol) & ((w <= phi0) | (discount * gain > loss))


def kick_back(lk: FourBar, dead_centre_extended, dead_centre_folded, masses: Masses, column_torque,
              head, wheel_radius, inertia, column_inertia, pawl_window=None, gravity=GRAVITY,
              samples=STOP_SAMPLES, rocker_rate=None) -> KickBack:  # fmt: skip
    """The kick-back of designs (1-D arrays over designs; the module docstring's method).

    Parameters
    ----------
    lk, dead_centre_extended, dead_centre_folded : the linkages and their dead centres [rad].
    masses : the links' masses [kg] (the hand is gone: no grip mass).
    column_torque : M_col = rho g head A rw [N m];  head, wheel_radius : [m].
    inertia : J of the wheel with the water [kg m^2] (NaN: not given; the wheel is then counted
        massless, the water alone);  column_inertia : Jc = rho head A rw^2 [kg m^2].
    pawl_window : 2 pi / teeth of a ratchet that holds the column [rad]: the run ends there;
        0 where one holds it with no play; NaN or None: no ratchet holds it.
    rocker_rate : max|dt4/dt| [-] (:func:`pumplink.mechanisms.fourbar.peak_rocker_rate`; None:
        computed): the bound of the links' weight torque that spares the march.
    """
    n = np.size(head)

    def col(v):
        return np.broadcast_to(np.asarray(v, float), (n,)).copy()

    lk = FourBar(*(col(v) for v in lk.parameters))
    dce, dcf = col(dead_centre_extended), col(dead_centre_folded)
    masses = Masses(*(col(m) for m in _masses(masses)))
    mcol, jc = col(column_torque), col(column_inertia)
    lc = col(head) / col(wheel_radius)
    jj = col(inertia)
    jj = np.where(np.isnan(jj), jc, jj)
    pawl = np.full(n, np.nan) if pawl_window is None else col(pawl_window)
    window = np.where(np.isnan(pawl), lc, np.minimum(pawl, lc))
    held = pawl == 0.0
    travel, angle = np.zeros(n), np.zeros(n)
    run, end = np.zeros(n), np.full(n, ENDS.index("held"))
    everywhere = np.zeros(n, bool)
    go = np.nonzero(~held & np.isfinite(window))[0]
    if go.size:
        sub = lk.take(go)
        path, ts = widest_window(sub, dce[go], dcf[go], window[go], samples)
        masses_go = Masses(*(m[go] for m in _masses(masses)))
        rate = peak_rocker_rate(sub) if rocker_rate is None else col(rocker_rate)[go]
        vm = weight_torque_bound(sub, dce[go], dcf[go], masses_go, rate, gravity)
        sure = reaches_end(mcol[go], lc[go], window[go], jj[go], jc[go], vm)
        end_run, how = window[go].copy(), np.where(window[go] < lc[go], 1, 0)
        m = np.nonzero(~sure)[0]
        if m.size:  # the bound cannot tell: march from the stop angle of the widest window
            args = (mcol[go][m, None], lc[go][m, None], jj[go][m, None], jc[go][m, None])
            sub_m = Masses(*(x[m] for x in _masses(masses_go)))
            e, h = march(sub.take(m), sub_m, ts[m, None], window[go][m, None], *args, gravity=gravity)
            end_run[m], how[m] = e[:, 0], h[:, 0]
        short = how == 2
        travel[go], angle[go], run[go], end[go] = path, ts, window[go], how
        cut = how == 3
        if cut.any():  # the march's limit: the path so far
            g = go[cut]
            travel[g] = grip_path(lk.take(g), dce[g], dcf[g], ts[cut] - end_run[cut], ts[cut])
            run[g] = end_run[cut]
        if short.any():  # the widest window's run stops early: every stop angle of the grid
            g = go[short]
            everywhere[g] = True
            sub_masses = Masses(*(m[g] for m in _masses(masses)))
            travel[g], angle[g], run[g], end[g] = _every_stop(
                lk.take(g),
                dce[g],
                dcf[g],
                sub_masses,
                mcol[g],
                lc[g],
                jj[g],
                jc[g],
                window[g],
                gravity,
                samples,
            )
    bad = ~np.isfinite(window)
    travel[bad] = angle[bad] = run[bad] = np.nan
    return KickBack(travel, angle, run, end, everywhere)


def _every_stop(lk, dce, dcf, masses, mcol, lc, jj, jc, window, gravity, samples):
    """The largest travel over a grid of ``samples`` stop angles, each run marched (where the
    column and the links' weight can stop the wheel: M_col + V'(ts) >= 0)."""
    n = dce.size
    grid = np.arange(samples) * (TWO_PI / samples)
    ts = np.broadcast_to(grid, (n, samples))
    col = [v[:, None] for v in (mcol, lc, jj, jc)]
    end_run, how = march(lk, masses, ts, window[:, None], *col, gravity=gravity)
    slope = _table(lk, masses, ts, gravity)[1]
    can_stop = mcol[:, None] + slope >= 0.0
    lk2 = FourBar(*(v[:, None] for v in lk.parameters))
    path = grip_path(lk2, dce[:, None], dcf[:, None], ts - end_run, ts)
    path = np.where(can_stop, path, -np.inf)
    j = np.argmax(path, axis=1)
    r = np.arange(n)
    return path[r, j], grid[j], end_run[r, j], how[r, j]


__all__ = [
    "ENDS",
    "KickBack",
    "grip_path",
    "kick_back",
    "march",
    "reaches_end",
    "weight_torque_bound",
    "widest_window",
]
