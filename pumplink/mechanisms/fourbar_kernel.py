"""The pump four-bar's closed-form loop closure and its in-place force kernel (the hot path).

Position, velocity and quasi-static force of the pump four-bar (the ``vector`` method; the full
state at crank angles is :func:`pumplink.mechanisms.fourbar.kinematic_state`, the same formulas).

Closed-form loop closure in product coordinates (docs/physics.md).  With the crank direction
(cos t2, sin t2), A = crank * (cos t2, sin t2) and d = O4 - A, e^2 = |d|^2:

    P1 = cos t2 * O4x + sin t2 * O4y          (O4 . crank direction)
    P2 = cos t2 * O4y - sin t2 * O4x          (crank direction x O4)
    e^2 = |O4|^2 + crank^2 - 2 crank P1
    t = 1/2 + (coupler^2 - rocker^2) / (2 e^2) (foot of B on A-O4, as a fraction of e)
    q = branch * sqrt(coupler^2 / e^2 - t^2)  (height of B off A-O4, as a fraction of e)
    B = A + t d + q perp(d),   perp(x, y) = (-y, x)                      (Eq. 6, as a vector)

Velocities from the rigid coupler, (vB - vA) . (B - A) = 0, give
omega4/omega2 = (A x u)/(R x u) with u = B - A, R = B - O4; here R x u = -q e^2 and
A x u = crank * (t P2 + q (P1 - crank)), so no slope or instant centre appears and
nothing divides by zero except at the dead centres (A x u = 0) themselves.

The handle grip is P = O4 + (H/rocker) R.  Virtual work (docs/physics.md) gives the horizontal
operator force that balances the wheel torque Mw:

    F = Mw / (dPx/dt2),  dPx/dt2 = (H/rocker) * Ry * crank * (t P2 + q (P1 - crank)) / (q e^2)

which is Eq. (3)-(5) of the pump paper (Fh = Mw w2 / (Vh cos phi)) without the instant centre.
At a dead centre dPx/dt2 = 0: the force is reported as NaN with ``singular`` set.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from pumplink.mechanisms.fourbar import FourBar

#: A crank angle counts as exactly at a dead centre when sin(crank, coupler) <= this.  The
#: force's relative rounding error grows like eps / sin(crank, coupler), amplified when the
#: transmission angle is small (a near-change-point linkage is ill-conditioned): just beyond the
#: threshold it is ~1e-6 for transmission angles of a few degrees and more
#: (tests/mechanisms/test_fourbar_kinematics.py), and ~1e-8 at 1e-6 deg from a dead centre of a
#: well-conditioned design.
SINGULAR_SIN = 1e-10


def loop_closure(lk: FourBar, cs, sn):
    """Loop-closure scalars (P1, P2, e^2, t, q) for crank directions (cs, sn)."""
    px, py, c = lk.pivot_x, lk.pivot_y, lk.crank
    k, r = lk.coupler, lk.rocker
    p1 = cs * px + sn * py
    p2 = cs * py - sn * px
    e2 = (px * px + py * py + c * c) - 2.0 * c * p1
    t = 0.5 + 0.5 * (k * k - r * r) / e2
    q = lk.branch * coupler_height(e2, k, r)  # NaN where not assemblable
    return p1, p2, e2, t, q


def coupler_height(e2, k, r):
    """|h| / e, the height of B off the line A-O4 over e = |O4 - A| (Heron's formula).

    (h/e)^2 = (r^2 - (e - k)^2) ((e + k)^2 - r^2) / (4 e^4), with e - k = (e^2 - k^2)/(e + k):
    free of the cancellation in coupler^2/e^2 - t^2 when the rocker is much shorter than the
    coupler (10-30x smaller rounding next to a dead centre, measured against the mpmath reference).
    """
    e = np.sqrt(e2)
    e_k = (e2 - k * k) / (e + k)
    return np.sqrt((r * r - e_k * e_k) * ((e + k) ** 2 - r * r)) / (2.0 * e2)


def _multipliers(n: int) -> np.ndarray:
    """``n`` odd 64-bit words from splitmix64's sequence (seed 0), to hash a design's values."""
    mask, x, out = (1 << 64) - 1, 0, []
    for _ in range(n):
        x = (x + 0x9E3779B97F4A7C15) & mask
        z = ((x ^ (x >> 30)) * 0xBF58476D1CE4E5B9) & mask
        z = ((z ^ (z >> 27)) * 0x94D049BB133111EB) & mask
        out.append((z ^ (z >> 31)) | 1)
    return np.array(out, dtype=np.uint64)


#: Multipliers that hash a design's values (their bits) to one word: at most 32 values a design.
_HASH = _multipliers(32)


def alike_designs(*columns):
    """(first, kind) of designs alike bit for bit in ``columns`` (1-D arrays over designs, or
    scalars; at most 32): ``first`` the index of one design of each kind, ``kind`` each design's
    index into ``first``; (None, None) where more than three quarters of the designs are of kinds
    of their own (computing per kind would not pay).  A grid's variants that differ only in the
    load or the wheel are alike in their linkage: a kernel of the linkage alone runs once per kind
    (the same operations per design, so the same values).  Kinds are found by a hash of the values'
    bits and checked design by design (a collision: (None, None))."""
    # one row per column (designs along the rows: the hash and the check run along them)
    rows = np.stack(np.broadcast_arrays(*(np.asarray(v, float) for v in columns)))
    if rows.ndim != 2 or rows.shape[1] < 2:
        return None, None
    bits = rows.view(np.uint64)
    with np.errstate(over="ignore"):
        key = (bits * _HASH[: bits.shape[0], None]).sum(axis=0, dtype=np.uint64)
    _, first, kind = np.unique(key, return_index=True, return_inverse=True)
    kind = kind.ravel()
    if first.size > 0.75 * bits.shape[1] or not np.array_equal(bits.take(first, 1).take(kind, 1), bits):
        return None, None
    return first, kind


def kernel_work(shape) -> np.ndarray:
    """Scratch memory for :func:`force_kernel` at a result shape (reuse it across chunks)."""
    return np.empty((9,) + tuple(shape))


def force_kernel(lk: FourBar, cs, sn, wheel_torque, work: np.ndarray | None = None):
    """Hot path: coupler point B and operator force for crank directions (cs, sn).

    The same formulas as :func:`kinematic_state`, written in place to keep the arrays in cache.
    Broadcasts linkage parameters (e.g. shape (designs, 1)) against directions (angles,).

    Parameters
    ----------
    lk : linkage (floats or arrays).
    cs, sn : cos and sin of the crank angles.
    wheel_torque : Mw [N m] (float or array broadcastable with the result).
    work : optional scratch from :func:`kernel_work` of the result shape; the returned arrays
        are views into it, valid until the next call that reuses it.

    Returns
    -------
    bx, by : coupler point B [m].
    force : horizontal operator force at the grip [N], +x positive; NaN at a dead centre.
    """
    px, c, k, r = lk.pivot_x, lk.crank, lk.coupler, lk.rocker
    shape = np.broadcast_shapes(
        np.shape(cs),
        np.shape(px),
        np.shape(c),
        np.shape(k),
        np.shape(r),
        np.shape(lk.branch),
        np.shape(lk.handle),
        np.shape(wheel_torque),
    )
    if work is None or work.shape[1:] != shape:
        work = kernel_work(shape)
    with np.errstate(all="ignore"):  # dead centres and non-assemblable inputs give NaN/inf, by design
        return _force_into(lk, cs, sn, wheel_torque, work, shape)


def _force_into(lk: FourBar, cs, sn, wheel_torque, work, shape):
    f = np.empty(shape)
    bx, by, p2 = _geometry_into(lk, cs, sn, work, f)
    f *= wheel_torque * lk.rocker / (lk.handle * lk.crank)
    f /= by
    f /= p2  # Eq. (3) by virtual work: F = Mw / (dPx/dt2)
    by += lk.pivot_y
    np.abs(p2, out=p2)
    np.copyto(f, np.nan, where=p2 <= SINGULAR_SIN * lk.coupler)  # exactly at a dead centre
    return bx, by, f


def _geometry_into(lk: FourBar, cs, sn, work, f):
    """Everything of :func:`force_kernel` that the wheel torque does not enter: B's x, Ry = By -
    O4y and w = (A x u) / crank in the scratch rows (returned), q e^2 in ``f``."""
    # Every step writes into the scratch rows (f doubles as a temporary until the end), so no
    # array is allocated.
    px, py, c, k, r = lk.pivot_x, lk.pivot_y, lk.crank, lk.coupler, lk.rocker
    p1, p2, e2, t, q, dx, dy, bx, by = work
    np.multiply(cs, px, out=p1)
    np.multiply(sn, py, out=f)
    p1 += f  # P1 = dir . O4
    np.multiply(cs, py, out=p2)
    np.multiply(sn, px, out=f)
    p2 -= f  # P2 = dir x O4
    np.multiply(p1, -2.0 * c, out=e2)
    e2 += px * px + py * py + c * c  # e^2 = |O4 - A|^2
    np.divide(0.5 * (k * k - r * r), e2, out=t)
    t += 0.5
    # q = branch * |h|/e by Heron's formula (see coupler_height), using bx, dx, dy as scratch
    np.sqrt(e2, out=bx)  # e
    np.add(bx, k, out=dx)  # e + k
    np.subtract(e2, k * k, out=dy)
    dy /= dx  # e - k
    np.multiply(dy, dy, out=q)
    np.subtract(r * r, q, out=q)  # r^2 - (e - k)^2
    np.multiply(dx, dx, out=dx)
    dx -= r * r  # (e + k)^2 - r^2
    q *= dx
    np.sqrt(q, out=q)
    q /= e2
    q *= 0.5 * lk.branch
    np.multiply(cs, -c, out=dx)
    dx += px  # d = O4 - A
    np.multiply(sn, -c, out=dy)
    dy += py
    np.multiply(t, dx, out=bx)  # Eq. (6) as B = A + t d + q perp(d), with A = O4 - d
    np.multiply(q, dy, out=f)
    bx -= f
    bx -= dx
    bx += px
    np.multiply(t, dy, out=by)
    np.multiply(q, dx, out=f)
    by += f
    by -= dy  # by is now Ry = By - O4y
    p1 -= c
    p1 *= q
    np.multiply(t, p2, out=p2)
    p2 += p1  # w = (A x u) / crank
    np.multiply(q, e2, out=f)
    return bx, by, p2


def force_parts(lk: FourBar, cs, sn):
    """The parts of :func:`force_kernel`'s force that the wheel torque does not enter, at crank
    directions (cs, sn): (q e^2, Ry, w), new arrays; :func:`force_of_parts` gives the force of a
    wheel torque from them with the same operations, so the same bits (designs alike in their
    geometry share the parts whatever their loads)."""
    shape = np.broadcast_shapes(np.shape(cs), *(np.shape(v) for v in lk.parameters))
    work = kernel_work(shape)
    qe2 = np.empty(shape)
    with np.errstate(all="ignore"):
        _bx, ry, w = _geometry_into(lk, cs, sn, work, qe2)
    return qe2, ry.copy(), w.copy()


def force_of_parts(lk: FourBar, parts, wheel_torque):
    """The force of :func:`force_kernel` [N] from :func:`force_parts`' parts (each broadcast with
    ``lk`` and ``wheel_torque``): the same operations in the same order."""
    qe2, ry, w = parts
    with np.errstate(all="ignore"):
        f = qe2 * (wheel_torque * lk.rocker / (lk.handle * lk.crank))
        f /= ry
        f /= w
        np.copyto(f, np.nan, where=np.abs(w) <= SINGULAR_SIN * lk.coupler)
    return f
