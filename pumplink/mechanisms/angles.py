"""Crank-angle grids and exact angle arithmetic shared by every mechanism kernel.

Pure numpy; angles in radians.
"""

from __future__ import annotations

import numpy as np

TWO_PI = 2.0 * np.pi


def angular_distance(a, b):
    """Smallest absolute difference of two angles [rad], in [0, pi]."""
    d = np.mod(np.asarray(a) - b, TWO_PI)
    return np.minimum(d, TWO_PI - d)


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
    return c.ravel()[i0 - j0 : i1 - j0], s.ravel()[i0 - j0 : i1 - j0]


def offset_table(step: float, size: int):
    """cos and sin of ``j * step`` for j < size (the table of :func:`shifted_directions`)."""
    off = np.arange(size) * step
    return np.cos(off), np.sin(off)


def shifted_directions(base, table, first: int, size: int):
    """cos/sin of ``base + (first + j) * step`` for j < size, from ``offset_table(step, ...)``.

    Angle addition, cos(a + b) = cos a cos b - sin a sin b; ``base`` may be an array of any
    shape, the result has shape ``base.shape + (size,)``.
    """
    co, so = table[0][first : first + size], table[1][first : first + size]
    cb, sb = np.cos(base)[..., None], np.sin(base)[..., None]
    c = co * cb
    c -= so * sb
    s = co * sb
    s += so * cb
    return c, s
