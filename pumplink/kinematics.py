"""Position, velocity and quasi-static force of the pump four-bar (the ``vector`` method).

Closed-form loop closure in product coordinates (NOTES.md §1).  With the crank direction
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

The handle grip is P = O4 + (H/rocker) R.  Virtual work (NOTES.md §1) gives the horizontal
operator force that balances the wheel torque Mw:

    F = Mw / (dPx/dt2),  dPx/dt2 = (H/rocker) * Ry * crank * (t P2 + q (P1 - crank)) / (q e^2)

which is Eq. (3)-(5) of the pump paper (Fh = Mw w2 / (Vh cos phi)) without the instant centre.
At a dead centre dPx/dt2 = 0: the force is reported as NaN with ``singular`` set.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from pumplink.synthesis import Linkage

#: A crank angle counts as exactly at a dead centre when sin(crank, coupler) <= this.  The
#: force's relative rounding error grows like eps / sin(crank, coupler), amplified when the
#: transmission angle is small (a near-change-point linkage is ill-conditioned): just beyond the
#: threshold it is ~1e-6 for transmission angles of a few degrees and more (tests/test_kinematics.py),
#: and ~1e-8 at 1e-6 deg from a dead centre of a well-conditioned design.
SINGULAR_SIN = 1e-10


def crank_grid(n: int, start: float = 0.0) -> np.ndarray:
    """Uniform crank angles start + 2 pi j / n, j = 0..n-1 [rad]."""
    return start + np.arange(n) * (2.0 * np.pi / n)


def grid_directions(n: int, i0: int = 0, i1: int | None = None, start: float = 0.0):
    """cos and sin of the uniform crank angles ``crank_grid(n, start)[i0:i1]``.

    Uses the angle-addition formula (:func:`shifted_directions`: one sin/cos pair per block of
    1024 plus one table), several times cheaper than ``np.cos``/``np.sin`` per angle and within
    a few ulp of them.
    """
    i1 = n if i1 is None else i1
    step = 2.0 * np.pi / n
    block = 1024
    j0 = i0 - i0 % block
    nblocks = -(-(i1 - j0) // block)
    base = start + (j0 + np.arange(nblocks) * block) * step
    c, s = shifted_directions(base, offset_table(step, block), 0, block)
    return c.ravel()[i0 - j0:i1 - j0], s.ravel()[i0 - j0:i1 - j0]


def offset_table(step: float, size: int):
    """cos and sin of ``j * step`` for j < size (the table of :func:`shifted_directions`)."""
    off = np.arange(size) * step
    return np.cos(off), np.sin(off)


def shifted_directions(base, table, first: int, size: int):
    """cos/sin of ``base + (first + j) * step`` for j < size, from ``offset_table(step, ...)``.

    Angle addition, cos(a + b) = cos a cos b - sin a sin b; ``base`` may be an array of any
    shape, the result has shape ``base.shape + (size,)``.
    """
    co, so = table[0][first:first + size], table[1][first:first + size]
    cb, sb = np.cos(base)[..., None], np.sin(base)[..., None]
    c = co * cb
    c -= so * sb
    s = co * sb
    s += so * cb
    return c, s


def _loop(lk: Linkage, cs, sn):
    """Loop-closure scalars (P1, P2, e^2, t, q) for crank directions (cs, sn)."""
    px, py, c = lk.pivot_x, lk.pivot_y, lk.crank
    k, r = lk.coupler, lk.rocker
    p1 = cs * px + sn * py
    p2 = cs * py - sn * px
    e2 = (px * px + py * py + c * c) - 2.0 * c * p1
    t = 0.5 + 0.5 * (k * k - r * r) / e2
    q = lk.branch * _height(e2, k, r)  # NaN where not assemblable
    return p1, p2, e2, t, q


def _height(e2, k, r):
    """|h| / e, the height of B off the line A-O4 over e = |O4 - A| (Heron's formula).

    (h/e)^2 = (r^2 - (e - k)^2) ((e + k)^2 - r^2) / (4 e^4), with e - k = (e^2 - k^2)/(e + k):
    free of the cancellation in coupler^2/e^2 - t^2 when the rocker is much shorter than the
    coupler (10-30x smaller rounding next to a dead centre, measured against the mpmath reference).
    """
    e = np.sqrt(e2)
    e_k = (e2 - k * k) / (e + k)
    return np.sqrt((r * r - e_k * e_k) * ((e + k) ** 2 - r * r)) / (2.0 * e2)


def kernel_work(shape) -> np.ndarray:
    """Scratch memory for :func:`force_kernel` at a result shape (reuse it across chunks)."""
    return np.empty((9,) + tuple(shape))


def force_kernel(lk: Linkage, cs, sn, wheel_torque, work: np.ndarray | None = None):
    """Hot path: coupler point B and operator force for crank directions (cs, sn).

    The same formulas as :func:`evaluate`, written in place to keep the arrays in cache.
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
    px, py, c, k, r = lk.pivot_x, lk.pivot_y, lk.crank, lk.coupler, lk.rocker
    shape = np.broadcast_shapes(np.shape(cs), np.shape(px), np.shape(c), np.shape(k), np.shape(r),
                                np.shape(lk.branch), np.shape(lk.handle), np.shape(wheel_torque))
    if work is None or work.shape[1:] != shape:
        work = kernel_work(shape)
    with np.errstate(all="ignore"):  # dead centres and non-assemblable inputs give NaN/inf, by design
        return _force_into(lk, cs, sn, wheel_torque, work, shape)


def _force_into(lk: Linkage, cs, sn, wheel_torque, work, shape):
    # Every step writes into the scratch rows (f doubles as a temporary until the end), so no
    # array is allocated except the returned force.
    px, py, c, k, r = lk.pivot_x, lk.pivot_y, lk.crank, lk.coupler, lk.rocker
    p1, p2, e2, t, q, dx, dy, bx, by = work
    f = np.empty(shape)
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
    # q = branch * |h|/e by Heron's formula (see _height), using bx, dx, dy as scratch
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
    f *= wheel_torque * r / (lk.handle * c)
    f /= by
    f /= p2  # Eq. (3) by virtual work: F = Mw / (dPx/dt2)
    by += py
    np.abs(p2, out=p2)
    np.copyto(f, np.nan, where=p2 <= SINGULAR_SIN * k)  # exactly at a dead centre
    return bx, by, f


@dataclass(frozen=True)
class State:
    """Kinematic state and quasi-static force at given crank angles (SI units, radians).

    Attributes
    ----------
    crank_angle : crank angle t2 [rad].
    coupler_x, coupler_y : coupler-rocker joint B [m].
    rocker_angle : rocker (and handle) angle t4, CCW from +x [rad].
    rocker_rate : d t4 / d t2 [-] (omega4 / omega2).
    handle_rate : dPx / d t2, horizontal grip travel per crank radian [m/rad].
    transmission_angle : angle between coupler and rocker at B [rad].
    force : horizontal operator force at the grip [N], +x positive, NaN where ``singular``.
    singular : True at a dead centre (crank and coupler collinear).
    """

    crank_angle: np.ndarray
    coupler_x: np.ndarray
    coupler_y: np.ndarray
    rocker_angle: np.ndarray
    rocker_rate: np.ndarray
    handle_rate: np.ndarray
    transmission_angle: np.ndarray
    force: np.ndarray
    singular: np.ndarray


def evaluate(lk: Linkage, crank_angle, wheel_torque=1.0) -> State:
    """Full kinematic state and handle force at crank angles [rad] (the ``vector`` method).

    Parameters
    ----------
    lk : the linkage (from :attr:`pumplink.synthesis.Synthesis.linkage`).
    crank_angle : crank angles t2 [rad], any shape broadcastable with the linkage.
    wheel_torque : load torque Mw = Fw rw [N m] (Eq. 3 of the pump paper).
    """
    with np.errstate(all="ignore"):  # dead centres and non-assemblable inputs give NaN/inf, by design
        return _evaluate(lk, np.asarray(crank_angle, float), wheel_torque)


def _evaluate(lk: Linkage, th, wheel_torque) -> State:
    cs, sn = np.cos(th), np.sin(th)
    px, py, c, k, r = lk.pivot_x, lk.pivot_y, lk.crank, lk.coupler, lk.rocker
    p1, p2, e2, t, q = _loop(lk, cs, sn)
    dx, dy = px - c * cs, py - c * sn
    bx = c * cs + t * dx - q * dy
    by = c * sn + t * dy + q * dx
    rx, ry = bx - px, by - py
    w = t * p2 + q * (p1 - c)
    singular = np.abs(w) <= SINGULAR_SIN * k
    rate = -c * w / (q * e2)  # omega4/omega2 = (A x u)/(R x u)
    handle_rate = -(lk.handle / r) * ry * rate
    force = np.where(singular, np.nan, wheel_torque / handle_rate)  # Eq. (3), virtual work
    cos_g = (k * k + r * r - e2) / (2.0 * k * r)  # law of cosines in A-B-O4
    return State(th, bx, by, np.arctan2(ry, rx), rate, handle_rate,
                 np.arccos(np.clip(cos_g, -1.0, 1.0)), force, singular)
