"""Chandrupatla's bracketing minimiser, vectorised over independent problems, in numpy alone.

The same algorithm, steps and stopping rules as ``scipy.optimize.elementwise.find_minimum``
(scipy >= 1.15), which the peak-force and rocker-rate refinements used before.  Importing
``scipy.optimize`` costs about 0.3 s (it loads scipy.linalg, the sparse and linear-programming
machinery); the commands a person waits for (``pumplink synth``, ``pumplink force``) need only
this 100-line loop, so it lives here and answers like scipy's to 1e-12 relative
(``tests/mechanisms/test_bracket.py`` runs both on the same problems).

Reference: T. R. Chandrupatla, "An efficient quadratic fit-sectioning algorithm for
minimization without derivatives", Computer Methods in Applied Mechanics and Engineering 152
(1998) 211-217: a three-point bracket shrunk by the minimum of the parabola through the three
points when it is near the previous one (Eq. (7)), else by golden sectioning of the larger
interval; stops when the bracket is narrower than the tolerance (Eqs. (8)-(9)) or the
parabola's curvature is below the function tolerance (Eqs. (10)-(11)).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

#: Status codes, as scipy's: converged, invalid bracket, iteration limit, non-finite value.
CONVERGED, INVALID_BRACKET, MAXITER, NONFINITE = 0, -1, -2, -3
_PHI = 0.5 + 0.5 * 5**0.5  # golden ratio


@dataclass(frozen=True)
class Minimum:
    """The result of :func:`find_minimum`, one element per problem (the broadcast shape).

    Attributes
    ----------
    x : the minimiser (NaN unless ``success``).
    f_x : ``f(x)``.
    success : converged to the tolerances (``status == 0``).
    status : 0 converged, -1 invalid bracket, -2 iteration limit, -3 non-finite value.
    nit, nfev : iterations and function evaluations per problem.
    """

    x: np.ndarray
    f_x: np.ndarray
    success: np.ndarray
    status: np.ndarray
    nit: np.ndarray
    nfev: np.ndarray


def find_minimum(f, init, /, *, args=(), tolerances=None, maxiter=100) -> Minimum:
    """Minimise the elementwise function ``f`` on each bracket ``init = (x1, x2, x3)``.

    A call-compatible subset of ``scipy.optimize.elementwise.find_minimum``.

    Parameters
    ----------
    f : callable ``f(x, *args) -> array``, elementwise (``f(x)[i]`` depends on ``x[i]`` only).
    init : three broadcastable arrays with ``f(x1) > f(x2) <= f(x3)`` (any order of x).
    args : arrays broadcastable with ``init``, passed to ``f``.
    tolerances : dict of ``xatol``, ``xrtol``, ``fatol``, ``frtol`` (scipy's defaults: the
        smallest normal float, and sqrt(eps) for ``xrtol``).  Converged when the bracket is
        narrower than ``2 (|x2| xrtol + xatol)`` or ``f1 - 2 f2 + f3 <= 2 (|f2| frtol + fatol)``.
    maxiter : iteration limit.
    """
    tol = {"xatol": None, "xrtol": None, "fatol": None, "frtol": None, **(tolerances or {})}
    tiny = np.finfo(float).smallest_normal
    xatol = tiny if tol["xatol"] is None else tol["xatol"]
    xrtol = np.sqrt(np.finfo(float).eps) if tol["xrtol"] is None else tol["xrtol"]
    fatol = tiny if tol["fatol"] is None else tol["fatol"]
    frtol = tiny if tol["frtol"] is None else tol["frtol"]

    both = np.broadcast_arrays(*(np.asarray(v, float) for v in init), *args)
    xs, args = both[:3], both[3:]
    shape = xs[0].shape
    fs = [np.asarray(f(x, *args), float).reshape(-1) for x in xs]
    xs = [x.reshape(-1) for x in xs]
    args = [np.array(a).reshape(-1) for a in args]
    order = np.argsort(np.stack(xs), axis=0)  # x1 < x2 < x3
    x1, x2, x3 = np.take_along_axis(np.stack(xs), order, axis=0)
    f1, f2, f3 = np.take_along_axis(np.stack(fs), order, axis=0)
    q0 = x3.copy()  # "At the start, q0 is set at x3" (after Eq. (7))

    n = x1.size
    out_x, out_f = np.zeros(n), np.zeros(n)
    out_status = np.full(n, 1, dtype=np.int32)
    out_nit, out_nfev = np.zeros(n, dtype=np.int32), np.zeros(n, dtype=np.int32)
    active = np.arange(n)
    status = np.full(n, 1, dtype=np.int32)
    nit, nfev = 0, 3

    def check(x1, x2, x3, f1, f2, f3, status):
        """Stop flags and the (possibly swapped) bracket; as scipy's ``check_termination``."""
        stop = np.zeros(x1.shape, dtype=bool)
        bad = (f2 > f1) | (f2 > f3)  # invalid bracket: no minimiser returned
        x2, f2 = np.where(bad, np.nan, x2), np.where(bad, np.nan, f2)
        stop |= bad
        status = np.where(bad, INVALID_BRACKET, status)
        bad = ~(np.isfinite(x1 + x2 + x3 + f1 + f2 + f3) | stop)
        x2, f2 = np.where(bad, np.nan, x2), np.where(bad, np.nan, f2)
        stop |= bad
        status = np.where(bad, NONFINITE, status)
        swap = np.abs(x3 - x2) < np.abs(x2 - x1)  # (x2, x3) is the larger interval
        x1, x3 = np.where(swap, x3, x1), np.where(swap, x1, x3)
        f1, f3 = np.where(swap, f3, f1), np.where(swap, f1, f3)
        xtol = np.abs(x2) * xrtol + xatol  # Eq. (8)
        done = np.abs(x3 - x2) <= 2 * xtol  # Eq. (9)
        ftol = np.abs(f2) * frtol + fatol  # Eq. (10)
        done |= (f1 - 2 * f2 + f3) <= 2 * ftol  # Eq. (11)
        done &= ~stop
        status = np.where(done, CONVERGED, status)
        return stop | done, (x1, x2, x3, f1, f2, f3, status, xtol)

    stop, (x1, x2, x3, f1, f2, f3, status, xtol) = check(x1, x2, x3, f1, f2, f3, status)
    while True:
        if stop.any():  # record the finished problems, keep iterating the others
            idx = active[stop]
            out_x[idx], out_f[idx], out_status[idx] = x2[stop], f2[stop], status[stop]
            out_nit[idx], out_nfev[idx] = nit, nfev
            keep = ~stop
            active = active[keep]
            x1, x2, x3, f1, f2, f3, status, xtol, q0 = (
                v[keep] for v in (x1, x2, x3, f1, f2, f3, status, xtol, q0)
            )
            args = [a[keep] for a in args]
        if not active.size or nit >= maxiter:
            break
        x21, x32 = x2 - x1, x3 - x2
        with np.errstate(divide="ignore", invalid="ignore"):
            a, b = x21 * (f3 - f2), x32 * (f1 - f2)
            c = a / (a + b)
            q1 = 0.5 * (c * (x1 - x3) + x2 + x3)  # minimum of the parabola, Eqs. (5)-(6)
        accept = np.abs(q1 - q0) < 0.5 * np.abs(x21)  # Eq. (7)
        near = np.abs(q1 - x2) <= xtol  # too close to x2: step xtol into the larger interval
        x = np.where(accept, np.where(near, x2 + np.sign(x32) * xtol, q1), x2 + (2 - _PHI) * x32)
        q0 = q1
        fx = np.asarray(f(x, *args), float).reshape(-1)
        nfev += 1
        right = np.sign(x - x2) == np.sign(x3 - x2)  # the new point is on x3's side of x2
        higher = fx > f2
        x1, f1, x2, f2, x3, f3 = (
            np.where(right & ~higher, x2, np.where(~right & higher, x, x1)),
            np.where(right & ~higher, f2, np.where(~right & higher, fx, f1)),
            np.where(higher, x2, x),
            np.where(higher, f2, fx),
            np.where(right & higher, x, np.where(~right & ~higher, x2, x3)),
            np.where(right & higher, fx, np.where(~right & ~higher, f2, f3)),
        )
        nit += 1
        stop, (x1, x2, x3, f1, f2, f3, status, xtol) = check(x1, x2, x3, f1, f2, f3, status)
    if active.size:  # the iteration limit
        out_x[active], out_f[active], out_status[active] = x2, f2, MAXITER
        out_nit[active], out_nfev[active] = nit, nfev

    def shaped(v):
        v = v.reshape(shape)
        return v[()] if v.ndim == 0 else v

    return Minimum(
        x=shaped(out_x),
        f_x=shaped(out_f),
        success=shaped(out_status == CONVERGED),
        status=shaped(out_status),
        nit=shaped(out_nit),
        nfev=shaped(out_nfev),
    )
