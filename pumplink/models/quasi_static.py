"""Operator-force quantities over the crank cycle (docs/physics.md, Eq. 3 of the pump paper).

All functions are pure and broadcast over designs (1-D arrays of per-design parameters).
"""

from __future__ import annotations

import functools

import numpy as np

from pumplink.mechanisms.angles import TWO_PI, angular_distance, offset_table, shifted_directions
from pumplink.mechanisms.bracket import find_minimum
from pumplink.mechanisms.fourbar import FourBar, per_design
from pumplink.mechanisms.fourbar_kernel import (
    alike_designs,
    force_kernel,
    force_of_parts,
    force_parts,
    kernel_work,
)

#: Points per dead-band window on which the exact peak search starts (independent of the
#: user's --samples); the best interior point is then refined by a bracketing minimiser.
PEAK_GRID = 97
#: Designs whose peak-search grids are evaluated together (keeps the kernel's scratch in cache
#: when many designs are searched at once, as ``pumplink batch`` does).
GRID_DESIGNS = 128


def wheel_torque(rope_force, wheel_radius):
    """Load torque on the wheel axle, Mw = Fw rw [N m] (Eq. 3 of the pump paper)."""
    return np.asarray(rope_force, float) * wheel_radius


def mean_force(wheel_torque, stroke):
    """Constant push/pull magnitude that does one cycle's work [N] (docs/physics.md §4).

    The grip travels its horizontal stroke S twice per revolution, so F_mean = 2 pi Mw / (2 S)
    = pi Mw / S: a lower bound on any operator's peak force.  For the symmetric swing
    S = 2 H sin(swing/2) (:func:`pumplink.mechanisms.fourbar.grip_stroke`).

    Parameters
    ----------
    wheel_torque : Mw [N m];  stroke : S [m].
    """
    return np.pi * np.asarray(wheel_torque, float) / stroke  # docs/physics.md §4


def in_dead_band(crank_angle, dead_centre_extended, dead_centre_folded, dead_band):
    """True where a crank angle lies within ``dead_band`` [rad] of either dead centre."""
    return (angular_distance(crank_angle, dead_centre_extended) <= dead_band) | (
        angular_distance(crank_angle, dead_centre_folded) <= dead_band
    )


def _windows(dc_ext, dc_fold, band):
    """Starts and lengths [rad] of the two crank arcs outside the dead bands, shape (..., 2)."""
    plus = np.mod(dc_fold - dc_ext, TWO_PI)
    start = np.stack([dc_ext + band, dc_fold + band], axis=-1)
    length = np.stack([plus - 2 * band, TWO_PI - plus - 2 * band], axis=-1)
    return start, length


def _abs_force(theta, px, py, c, k, r, h, br, mw):
    lk = FourBar(px, py, c, k, r, h, br)
    return np.abs(force_kernel(lk, np.cos(theta), np.sin(theta), mw)[2])


def dead_band_peak_force(lk: FourBar, dead_centre_extended, dead_centre_folded, dead_band, wheel_torque):
    """Largest |operator force| at crank angles farther than ``dead_band`` from both dead centres.

    Exact to solver tolerance whatever the sweep sampling: each of the two windows is scanned on
    a fixed grid (including its ends, where the force usually peaks because it rises toward the
    dead centres), and an interior maximum is refined with a bracketing minimiser
    (:func:`pumplink.mechanisms.bracket.find_minimum`, Chandrupatla's method, as scipy's).

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
    scalar, params = per_design(lk, wheel_torque, dead_centre_extended, dead_centre_folded, dead_band)
    *geom, dce, dcf, band = params  # geom: the four-bar's seven parameters, then Mw
    start, length = _windows(dce, dcf, band)  # (D, 2)
    s = np.linspace(0.0, 1.0, PEAK_GRID)
    theta = start[..., None] + np.maximum(length, 0.0)[..., None] * s  # (D, 2, M)
    g3 = [p[:, None, None] for p in geom]
    val = np.empty_like(theta)
    # designs alike in linkage, dead centres and band (a grid's variants that differ in the load)
    # share the parts of the force the wheel torque does not enter, computed once per kind
    first, kind = alike_designs(*geom[:7], dce, dcf, band)
    if first is not None:
        parts = np.empty((3,) + (first.size,) + theta.shape[1:])
        for u0 in range(0, first.size, GRID_DESIGNS):  # cache-sized blocks: same values, faster
            u = first[u0 : u0 + GRID_DESIGNS]
            th = theta[u]
            parts[:, u0 : u0 + GRID_DESIGNS] = force_parts(
                FourBar(*(p[u] for p in g3[:7])), np.cos(th), np.sin(th)
            )
    for d0 in range(0, theta.shape[0], GRID_DESIGNS):  # cache-sized blocks: same values, faster
        d = slice(d0, d0 + GRID_DESIGNS)
        if first is None:
            val[d] = _abs_force(theta[d], *(p[d] for p in g3))
        else:
            own = parts.take(kind[d], axis=1)
            val[d] = np.abs(force_of_parts(FourBar(*(p[d] for p in g3[:7])), own, g3[7][d]))
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
        res = find_minimum(
            lambda x, *a: -_abs_force(x, *a), bracket, args=args, tolerances=dict(xatol=1e-13, xrtol=1e-15)
        )
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


#: Samples per angle-addition block of :func:`sampled_peak`: the directions of samples
#: j0 + m * SWEEP_BLOCK + i come from one table entry i and the block's base angle.
SWEEP_BLOCK = 8192
#: Crank samples evaluated at once (designs x angles) in :func:`sampled_peak`; bounds the
#: kernel's scratch (about 10 arrays of this many float64 values, ~20 MB) whatever ``n`` is.
SAMPLE_BLOCK = 262_144


@functools.lru_cache(maxsize=8)
def _offset_table(n: int):
    """``offset_table(2 pi / n, SWEEP_BLOCK)``, computed once per sample count."""
    return offset_table(TWO_PI / n, SWEEP_BLOCK)


def sampled_peak(
    lk: FourBar, n: int, wheel_torque, dead_centre_extended, dead_centre_folded, dead_band, progress=None
):
    """Largest |force| over a uniform sweep of ``n`` crank angles strictly outside the dead bands.

    This is what a sampled sweep reports (it can step over the rise toward a dead centre);
    the verdict uses :func:`peak_force` instead.  Only the samples inside the two windows
    between the dead bands are evaluated, a few hundred thousand at a time, so memory stays
    bounded for any ``n``; directions by angle addition (:func:`pumplink.mechanisms.fourbar.offset_table`).

    Parameters
    ----------
    lk : linkage (scalars, or 1-D arrays over designs).
    n : samples per revolution (crank angles 2 pi j / n).
    wheel_torque : Mw [N m];  dead_centre_extended, dead_centre_folded : [rad];  dead_band : [rad].
    progress : optional callable, called with the fraction of the sweep done (0..1) after each pass.

    Returns
    -------
    peak : largest sampled |force| [N] per design (NaN where no sample lies outside the bands).
    """
    scalar, params = per_design(lk, wheel_torque, dead_centre_extended, dead_centre_folded, dead_band)
    *geom, dce, dcf, band = params
    n_designs = dce.size
    out = np.full(n_designs, np.nan)
    if n <= 0 or n_designs == 0:
        return float(out[0]) if scalar and n_designs else out
    step = TWO_PI / n
    start, length = _windows(dce, dcf, band)  # (D, 2)
    j0 = np.floor(start / step).astype(np.int64) + 1  # first sample strictly inside each window
    j1 = np.ceil((start + length) / step).astype(np.int64) - 1  # last one
    count = np.where(length > 0, np.maximum(j1 - j0 + 1, 0), 0)  # (D, 2)
    table = _offset_table(n)
    g3 = [p[:, None, None] for p in geom]
    best = np.full(n_designs, -np.inf)
    work = None
    # designs alike in linkage, dead centres and band (a grid's variants that differ in the load)
    # share the parts of the force the wheel torque does not enter, computed once per kind
    first, kind = alike_designs(*geom[:7], dce, dcf, band)
    shared = None if first is None else FourBar(*(p[first] for p in g3[:7]))
    width = int(count.max())
    span = SWEEP_BLOCK  # samples per window per pass: a power of two, so a pass stays in one block
    while span > 1 and span * 2 * n_designs > SAMPLE_BLOCK:
        span //= 2
    for m0 in range(0, width, span):
        # offsets m0..m0+size-1 into each window, all in block m0 // SWEEP_BLOCK
        size = min(span, width - m0)
        off = m0 + np.arange(size)
        e0 = m0 % SWEEP_BLOCK
        if shared is None:
            cs, sn = shifted_directions((j0 + (m0 - e0)) * step, table, e0, size)  # (D, 2, size)
            if work is None or work.shape[1:] != cs.shape:
                work = kernel_work(cs.shape)  # scratch reused across passes
            f = np.abs(force_kernel(FourBar(*g3[:7]), cs, sn, g3[7], work)[2])
        else:
            cs, sn = shifted_directions((j0[first] + (m0 - e0)) * step, table, e0, size)  # (kinds, 2, size)
            parts = np.stack(force_parts(shared, cs, sn)).take(kind, axis=1)
            f = np.abs(force_of_parts(FourBar(*g3[:7]), parts, g3[7]))
        f[(off >= count[..., None]) | np.isnan(f)] = -np.inf  # beyond the window; a dead centre
        np.maximum(best, f.max(axis=(1, 2)), out=best)
        if progress is not None:
            progress((m0 + size) / width)
    found = best > -np.inf
    out[found] = best[found]
    return float(out[0]) if scalar else out
