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


def _check(s, xatol, xrtol, fatol, frtol):
    """Stop flags, status codes and x tolerances of the brackets ``s`` (:func:`find_minimum`'s
    array), whose ends are swapped in place so that (x2, x3) is the larger interval; as scipy's
    ``check_termination``: an invalid bracket, a non-finite value, converged (Eqs. (8)-(11))."""
    (x1, x2, x3), (f1, f2, f3) = s
    invalid = (f2 > f1) | (f2 > f3)  # no minimiser returned
    finite = np.isfinite(x1 + x2 + x3 + f1 + f2 + f3)
    code = np.where(invalid, INVALID_BRACKET, np.where(finite, CONVERGED, NONFINITE)).astype(np.int32)
    failed = code != CONVERGED
    if failed.any():  # no minimiser: x2 and f2 NaN, as scipy's (the steps below see them so)
        s[:, 1] = np.where(failed, np.nan, s[:, 1])
    swap = np.abs(x3 - x2) < np.abs(x2 - x1)  # (x2, x3) is the larger interval
    if swap.any():
        s[:, ::2] = np.where(swap, s[:, ::-2], s[:, ::2])  # x1 <-> x3 and f1 <-> f3
        (x1, x2, x3), (f1, f2, f3) = s
    xtol = np.abs(x2) * xrtol + xatol  # Eq. (8)
    done = np.abs(x3 - x2) <= 2 * xtol  # Eq. (9)
    ftol = np.abs(f2) * frtol + fatol  # Eq. (10)
    done |= (f1 - 2 * f2 + f3) <= 2 * ftol  # Eq. (11)
    return done | failed, code, xtol


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
    # the bracket as one array: s[0] the points x1 < x2 < x3, s[1] their values, s[:, i] point i
    order = np.argsort(np.stack(xs), axis=0)
    s = np.stack([np.take_along_axis(np.stack(v), order, axis=0) for v in (xs, fs)])
    q0 = s[0, 2].copy()  # "At the start, q0 is set at x3" (after Eq. (7))
    # arguments of one type ride in one array: one gather drops the finished problems' rows
    together = len(args) > 1 and len({a.dtype for a in args}) == 1
    held = np.stack(args) if together else args

    n = s.shape[2]
    out_x, out_f = np.zeros(n), np.zeros(n)
    out_status = np.full(n, 1, dtype=np.int32)
    out_nit, out_nfev = np.zeros(n, dtype=np.int32), np.zeros(n, dtype=np.int32)
    active = np.arange(n)
    nit, nfev = 0, 3
    stop, code, xtol = _check(s, xatol, xrtol, fatol, frtol)
    while True:
        if stop.any():  # record the finished problems, keep iterating the others
            idx = active[stop]
            out_x[idx], out_f[idx] = s[0, 1, stop], s[1, 1, stop]  # NaN where it failed
            out_status[idx] = code[stop]
            out_nit[idx], out_nfev[idx] = nit, nfev
            keep = np.nonzero(~stop)[0]
            active, s, xtol, q0 = active[keep], s.take(keep, axis=2), xtol[keep], q0[keep]
            held = held.take(keep, axis=1) if together else [a[keep] for a in held]
        if not active.size or nit >= maxiter:
            break
        (x1, x2, x3), (f1, f2, f3) = s
        x21, x32 = x2 - x1, x3 - x2
        with np.errstate(divide="ignore", invalid="ignore"):
            a, b = x21 * (f3 - f2), x32 * (f1 - f2)
            c = a / (a + b)
            q1 = 0.5 * (c * (x1 - x3) + x2 + x3)  # minimum of the parabola, Eqs. (5)-(6)
        accept = np.abs(q1 - q0) < 0.5 * np.abs(x21)  # Eq. (7)
        near = np.abs(q1 - x2) <= xtol  # too close to x2: step xtol into the larger interval
        x = np.where(accept, np.where(near, x2 + np.sign(x32) * xtol, q1), x2 + (2 - _PHI) * x32)
        q0 = q1
        fx = np.asarray(f(x, *held), float).reshape(-1)
        nfev += 1
        right = np.sign(x - x2) == np.sign(x3 - x2)  # the new point is on x3's side of x2
        higher = fx > f2
        new = np.empty((2, x.size))  # (x, f(x))
        new[0], new[1] = x, fx
        p1, p2, p3 = s[:, 0], s[:, 1], s[:, 2]
        nxt = np.empty_like(s)
        nxt[:, 0] = np.where(right & ~higher, p2, np.where(~right & higher, new, p1))
        nxt[:, 1] = np.where(higher, p2, new)
        nxt[:, 2] = np.where(right & higher, new, np.where(~right & ~higher, p2, p3))
        s = nxt
        nit += 1
        stop, code, xtol = _check(s, xatol, xrtol, fatol, frtol)
    if active.size:  # the iteration limit
        out_x[active], out_f[active], out_status[active] = s[0, 1], s[1, 1], MAXITER
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
