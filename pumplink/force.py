"""Operator-force quantities over the crank cycle (NOTES.md §1, Eq. 3 of the pump paper).

All functions are pure and broadcast over designs (1-D arrays of per-design parameters).
"""

from __future__ import annotations

import numpy as np

from pumplink.kinematics import force_kernel, kernel_work, offset_table, shifted_directions
from pumplink.synthesis import Linkage

TWO_PI = 2.0 * np.pi

#: Points per dead-band window on which the exact peak search starts (independent of the
#: user's --samples); the best interior point is then refined by a bracketing minimiser.
PEAK_GRID = 97
#: Designs whose peak-search grids are evaluated together (keeps the kernel's scratch in cache
#: when many designs are searched at once, as ``pumplink batch`` does).
GRID_DESIGNS = 128


def wheel_torque(rope_force, wheel_radius):
    """Load torque on the wheel axle, Mw = Fw rw [N m] (Eq. 3 of the pump paper)."""
    return np.asarray(rope_force, float) * wheel_radius


def mean_force(wheel_torque, handle, swing):
    """Constant push/pull magnitude that does one cycle's work [N] (NOTES.md §1).

    The grip's horizontal stroke is S = 2 H sin(swing/2), travelled twice per revolution, so
    F_mean = 2 pi Mw / (2 S) = pi Mw / (2 H sin(swing/2)): a lower bound on any operator's
    peak force.

    Parameters
    ----------
    wheel_torque : Mw [N m];  handle : H [m];  swing : total handle swing [rad].
    """
    return np.pi * wheel_torque / (2.0 * handle * np.sin(0.5 * swing))  # NOTES.md §1


def angular_distance(a, b):
    """Smallest absolute difference of two angles [rad], in [0, pi]."""
    d = np.mod(np.asarray(a) - b, TWO_PI)
    return np.minimum(d, TWO_PI - d)


def in_dead_band(crank_angle, dead_centre_extended, dead_centre_folded, dead_band):
    """True where a crank angle lies within ``dead_band`` [rad] of either dead centre."""
    return (angular_distance(crank_angle, dead_centre_extended) <= dead_band) | (
        angular_distance(crank_angle, dead_centre_folded) <= dead_band)


def _windows(dc_ext, dc_fold, band):
    """Starts and lengths [rad] of the two crank arcs outside the dead bands, shape (..., 2)."""
    plus = np.mod(dc_fold - dc_ext, TWO_PI)
    start = np.stack([dc_ext + band, dc_fold + band], axis=-1)
    length = np.stack([plus - 2 * band, TWO_PI - plus - 2 * band], axis=-1)
    return start, length


def _abs_force(theta, px, py, c, k, r, h, br, mw):
    lk = Linkage(px, py, c, k, r, h, br)
    return np.abs(force_kernel(lk, np.cos(theta), np.sin(theta), mw)[2])


def peak_force(lk: Linkage, dead_centre_extended, dead_centre_folded, dead_band, wheel_torque):
    """Largest |operator force| at crank angles farther than ``dead_band`` from both dead centres.

    Exact to solver tolerance whatever the sweep sampling: each of the two windows is scanned on
    a fixed grid (including its ends, where the force usually peaks because it rises toward the
    dead centres), and an interior maximum is refined with scipy's bracketing minimiser
    (``scipy.optimize.elementwise.find_minimum``, Chandrupatla's method).

    Parameters
    ----------
    lk : linkage (scalars or 1-D arrays over designs).
    dead_centre_extended, dead_centre_folded : dead-centre crank angles [rad].
    dead_band : crank angle left to the wheel's inertia each side of a dead centre [rad].
    wheel_torque : Mw [N m].

    Returns
    -------
    peak : largest |force| [N] (NaN for an infeasible design).
    angle : crank angle where it occurs [rad], in [0, 2 pi).
    """
    from scipy.optimize.elementwise import find_minimum  # lazy: keeps start-up fast

    params = np.broadcast_arrays(*(np.asarray(v, float) for v in (
        lk.pivot_x, lk.pivot_y, lk.crank, lk.coupler, lk.rocker, lk.handle, lk.branch,
        wheel_torque, dead_centre_extended, dead_centre_folded, dead_band)))
    scalar = params[0].ndim == 0
    params = [np.atleast_1d(p).ravel() for p in params]
    *geom, dce, dcf, band = params  # geom: px, py, c, k, r, h, br, mw
    start, length = _windows(dce, dcf, band)  # (D, 2)
    s = np.linspace(0.0, 1.0, PEAK_GRID)
    theta = start[..., None] + np.maximum(length, 0.0)[..., None] * s  # (D, 2, M)
    g3 = [p[:, None, None] for p in geom]
    val = np.empty_like(theta)
    for d0 in range(0, theta.shape[0], GRID_DESIGNS):  # cache-sized blocks: same values, faster
        d = slice(d0, d0 + GRID_DESIGNS)
        val[d] = _abs_force(theta[d], *(p[d] for p in g3))
    val = np.where(np.isnan(val), np.inf, val)  # a window reaching a dead centre (dead_band = 0): infinite
    val = np.where(length[..., None] >= 0, val, -np.inf)  # an empty window contributes nothing
    j = np.argmax(val, axis=-1)  # (D, 2)
    best = np.take_along_axis(val, j[..., None], -1)[..., 0]
    best_th = np.take_along_axis(theta, j[..., None], -1)[..., 0]

    inner = (j > 0) & (j < PEAK_GRID - 1) & np.isfinite(best)
    feasible = np.isfinite(geom[2])  # NaN crank length: infeasible design
    if inner.any():
        d_idx, a_idx = np.nonzero(inner)
        jj = j[inner]
        th = theta[d_idx, a_idx]
        bracket = (th[np.arange(jj.size), jj - 1], th[np.arange(jj.size), jj], th[np.arange(jj.size), jj + 1])
        args = tuple(p[d_idx] for p in geom)
        res = find_minimum(lambda x, *a: -_abs_force(x, *a), bracket, args=args,
                           tolerances=dict(xatol=1e-13, xrtol=1e-15))
        better = res.success & (-res.f_x > best[inner])
        best[inner] = np.where(better, -res.f_x, best[inner])
        best_th[inner] = np.where(better, res.x, best_th[inner])

    arc = np.argmax(best, axis=-1)
    peak = np.take_along_axis(best, arc[:, None], -1)[:, 0]
    angle = np.mod(np.take_along_axis(best_th, arc[:, None], -1)[:, 0], TWO_PI)
    peak = np.where(feasible, peak, np.nan)
    if scalar:
        return float(peak[0]), float(angle[0])
    return peak, angle


def sampled_peak(lk: Linkage, n: int, wheel_torque, dead_centre_extended, dead_centre_folded,
                 dead_band, chunk: int = 8192):
    """Largest |force| over a uniform sweep of ``n`` crank angles outside the dead bands.

    This is what a sampled sweep reports (it can step over the rise toward a dead centre).
    Only the samples inside the two windows are evaluated, streamed in cache-sized chunks, so
    memory stays bounded for any ``n``.  Single design (scalar linkage).

    Returns
    -------
    peak : largest sampled |force| [N] strictly outside the dead bands (NaN if no sample is).
    angle : its crank angle [rad].
    """
    step = TWO_PI / n
    start, length = _windows(float(dead_centre_extended), float(dead_centre_folded), float(dead_band))
    table = offset_table(step, chunk)
    dirs = np.empty((2, chunk))
    work = kernel_work((chunk,))
    best, best_j = -np.inf, -1
    for s0, ln in zip(start, length):
        if ln <= 0:
            continue
        j0 = int(np.floor(s0 / step)) + 1  # first sample strictly inside the window
        j1 = int(np.ceil((s0 + ln) / step)) - 1  # last one
        for a in range(j0, j1 + 1, chunk):
            size = min(chunk, j1 + 1 - a)
            cs, sn = shifted_directions(a * step, table, size, dirs)
            w = work[:, :size]
            f = np.abs(force_kernel(lk, cs, sn, wheel_torque, w)[2])
            i = int(np.argmax(f))
            if np.isnan(f[i]):
                i = int(np.nanargmax(f)) if not np.isnan(f).all() else i
            if f[i] > best:
                best, best_j = float(f[i]), a + i
    if best_j < 0:
        return float("nan"), float("nan")
    return best, float((best_j % n) * step)
