"""Run pumplink with every iterative solver perturbed (tests/test_solver_perturbation.py).

    python tests/perturb.py force configs/prototype.toml      # as `pumplink force ...`

:func:`install` replaces the iterative solvers pumplink calls with wrappers that change what a
solver's answer may legitimately depend on and nothing else: its tolerances (loosened ten times,
or tightened ten times with ``PUMPLINK_PERTURB=tighten``, never below what the arithmetic can meet)
and where it starts, moved by :data:`SHIFT` (1e-9) of its size.  An output digit that changes
under this is one the method does not determine: another processor's rounding (another BLAS code
path, another libm) moves a solver's path the same way.

* ``scipy.optimize.minimize``: ``tol``, SLSQP's ``ftol``; ``x0``, toward the middle of the bounds;
* ``scipy.optimize.differential_evolution``: ``tol``, ``atol``; its first population (the bounds
  narrowed by SHIFT of their width);
* ``scipy.optimize.brentq``: ``xtol``, ``rtol``; the bracket, slid by SHIFT of its width where it
  still brackets the root;
* ``scipy.optimize.fsolve``: ``xtol``; ``x0``;
* ``scipy.optimize.minimize_scalar``: ``tol`` or the bounded method's ``xatol``; the bounds
  (narrowed) or the bracket;
* ``scipy.optimize.elementwise.find_root``: its tolerances; the bracket, slid where it still
  brackets the root;
* ``scipy.optimize.elementwise.find_minimum`` and ``pumplink.mechanisms.bracket.find_minimum``:
  their tolerances; the bracket's middle point, where it stays below the ends;
* ``scipy.integrate.solve_ivp``: ``rtol``, ``atol`` (its start is the state it integrates from, a
  result of the model, not a guess);
* ``pumplink.models.losses.duty_rope_speed`` (fixed-point steps, each shrinking the error at least
  fivefold): two steps fewer (loosened, 25 times the error) or more; its start moved by SHIFT.

pumplink imports scipy's solvers inside the functions that use them
(``from scipy.optimize import brentq``), so replacing the module attributes reaches every call;
pumplink's own minimiser is replaced in its module and in every pumplink module that has imported
it by name already.  The command line itself (:func:`pumplink.cli.main`) is unchanged.

Each wrapper counts its calls; with ``PUMPLINK_PERTURB_COUNTS=FILE`` the counts are appended to
FILE as one JSON line per process when it exits, so a test can check that the perturbation was
live (a solver that was never called perturbed nothing).
"""

from __future__ import annotations

import atexit
import functools
import importlib.abc
import importlib.util
import json
import os
import sys
from collections import Counter
from pathlib import Path

import numpy as np

#: How far a start moves, relative to its size (a bracket's width, a point's magnitude).
SHIFT = float(os.environ.get("PUMPLINK_PERTURB_SHIFT", "1e-9"))
#: ``loosen`` (tolerances x 10, the default) or ``tighten`` (tolerances / 10).
MODE = os.environ.get("PUMPLINK_PERTURB", "loosen")
FACTOR = {"loosen": 10.0, "tighten": 0.1}[MODE]
EPS = np.finfo(float).eps

#: Calls of each wrapped solver in this process.
CALLS: Counter[str] = Counter()


def _tol(value, floor: float = 0.0):
    """A tolerance scaled by :data:`FACTOR`; tightened, never below ``floor`` (the least the
    arithmetic can meet: a tighter one makes the solver give up, not answer better), unless the
    caller already asked for less."""
    value = float(value)
    return max(value * FACTOR, min(value, floor))


def _moved(x):
    """``x`` moved by :data:`SHIFT` of its magnitude (by SHIFT where it is 0)."""
    x = np.asarray(x, float)
    return x + SHIFT * np.where(x != 0, np.abs(x), 1.0)


def _counted(name: str):
    def wrap(fn):
        @functools.wraps(fn)
        def counted(*args, **kwargs):
            CALLS[name] += 1
            return fn(*args, **kwargs)

        return counted

    return wrap


def _minimize(original):
    @_counted("minimize")
    def minimize(fun, x0, *args, method=None, bounds=None, tol=None, options=None, **kwargs):
        x0 = np.asarray(x0, float)
        step = SHIFT * np.where(x0 != 0, np.abs(x0), 1.0)
        if bounds is not None:  # move toward the middle of the bounds, so the start stays inside
            lo = np.array([-np.inf if b[0] is None else b[0] for b in bounds], float)
            hi = np.array([np.inf if b[1] is None else b[1] for b in bounds], float)
            width = np.where(np.isfinite(hi - lo), hi - lo, 1.0)
            step = SHIFT * width * np.where(x0 - lo > hi - x0, -1.0, 1.0)
        options = dict(options or {})
        if str(method).upper() == "SLSQP":
            options["ftol"] = _tol(options.get("ftol", 1e-6))
        tol = None if tol is None else _tol(tol)
        return original(
            fun, x0 + step, *args, method=method, bounds=bounds, tol=tol, options=options, **kwargs
        )

    return minimize


def _differential_evolution(original):
    @_counted("differential_evolution")
    def differential_evolution(func, bounds, *args, tol=0.01, atol=0, **kwargs):
        # the start is the initial population drawn inside the bounds: narrowing them by SHIFT of
        # their width moves every member of it
        bounds = [(lo + SHIFT * (hi - lo), hi - SHIFT * (hi - lo)) for lo, hi in bounds]
        return original(func, bounds, *args, tol=_tol(tol), atol=_tol(atol), **kwargs)

    return differential_evolution


def _brentq(original):
    @_counted("brentq")
    def brentq(f, a, b, args=(), xtol=2e-12, rtol=4 * EPS, **kwargs):
        a, b = float(a), float(b)
        step = SHIFT * abs(b - a)
        for d in (step, -step, 0.0):  # moved one way or the other, as long as it still brackets
            if d == 0.0 or np.sign(f(a + d, *args)) * np.sign(f(b + d, *args)) < 0:
                break
        return original(f, a + d, b + d, args=args, xtol=_tol(xtol), rtol=_tol(rtol, 4 * EPS), **kwargs)

    return brentq


def _fsolve(original):
    @_counted("fsolve")
    def fsolve(func, x0, *args, xtol=1.49012e-08, **kwargs):
        return original(func, _moved(x0), *args, xtol=_tol(xtol), **kwargs)

    return fsolve


def _minimize_scalar(original):
    @_counted("minimize_scalar")
    def minimize_scalar(fun, bracket=None, bounds=None, *args, tol=None, options=None, **kwargs):
        options = dict(options or {})
        if bounds is not None:
            lo, hi = bounds
            d = SHIFT * (hi - lo)
            bounds = (lo + d, hi - d)
            options["xatol"] = _tol(options.get("xatol", 1e-5))
        if bracket is not None:
            bracket = tuple(_moved(bracket))
        tol = None if tol is None else _tol(tol)
        return original(fun, bracket, bounds, *args, tol=tol, options=options, **kwargs)

    return minimize_scalar


def _tolerances(tolerances, defaults):
    """Chandrupatla's tolerances scaled (scipy's defaults where none is given); a relative one
    tightened no further than 4 eps."""
    given = {**defaults, **{k: v for k, v in (tolerances or {}).items() if v is not None}}
    return {k: _tol(v, 4 * EPS if k == "xrtol" else 0.0) for k, v in given.items()}


_MINIMUM_DEFAULTS = {"xrtol": np.sqrt(EPS)}
_ROOT_DEFAULTS = {"xrtol": 4 * EPS}


def _find_minimum(original, name):
    @_counted(name)
    def find_minimum(f, init, /, *, args=(), tolerances=None, **kwargs):
        x1, x2, x3 = (np.asarray(v, float) for v in init)
        # the middle point moves (the first parabola, hence the path, changes; the bracket stays one
        # wherever f(x2) stays below its ends)
        moved = x2 + SHIFT * (x3 - x1)
        f1, f2, f3 = (np.asarray(f(x, *args), float) for x in np.broadcast_arrays(x1, moved, x3))
        keep = (f2 < f1) & (f2 <= f3)
        x2 = np.where(keep, moved, x2)
        return original(
            f, (x1, x2, x3), args=args, tolerances=_tolerances(tolerances, _MINIMUM_DEFAULTS), **kwargs
        )

    return find_minimum


def _find_root(original):
    @_counted("find_root")
    def find_root(f, init, /, *, args=(), tolerances=None, **kwargs):
        lo, hi = (np.asarray(v, float) for v in init)
        d = SHIFT * (hi - lo)
        lo2, hi2 = lo + d, hi + d
        fl, fh = (np.asarray(f(x, *args), float) for x in np.broadcast_arrays(lo2, hi2))
        keep = np.sign(fl) * np.sign(fh) < 0  # still a bracket
        lo, hi = np.where(keep, lo2, lo), np.where(keep, hi2, hi)
        return original(f, (lo, hi), args=args, tolerances=_tolerances(tolerances, _ROOT_DEFAULTS), **kwargs)

    return find_root


def _solve_ivp(original):
    # Its start is the state it integrates from, a result of the model rather than a guess: only its
    # tolerances change (and with them every step it takes).
    @_counted("solve_ivp")
    def solve_ivp(fun, t_span, y0, *args, rtol=1e-3, atol=1e-6, **kwargs):
        return original(fun, t_span, y0, *args, rtol=_tol(rtol, 100 * EPS), atol=_tol(atol), **kwargs)

    return solve_ivp


def _duty_rope_speed(original):
    @_counted("duty_rope_speed")
    def duty_rope_speed(power, head, pipe_diameter, efficiency, steps=60, start=1.0):
        steps = steps - 2 if MODE == "loosen" else steps + 2
        return original(power, head, pipe_diameter, efficiency, steps=steps, start=start * (1.0 + SHIFT))

    return duty_rope_speed


#: What to replace in each module, by the module's name: (attribute, wrapper maker, counted as).
PATCHES = {
    "scipy.optimize": [
        ("minimize", _minimize),
        ("differential_evolution", _differential_evolution),
        ("brentq", _brentq),
        ("fsolve", _fsolve),
        ("minimize_scalar", _minimize_scalar),
    ],
    "scipy.optimize.elementwise": [
        ("find_root", _find_root),
        ("find_minimum", lambda f: _find_minimum(f, "find_minimum")),
    ],
    "scipy.integrate": [("solve_ivp", _solve_ivp)],
    "pumplink.mechanisms.bracket": [("find_minimum", lambda f: _find_minimum(f, "bracket.find_minimum"))],
    "pumplink.models.losses": [("duty_rope_speed", _duty_rope_speed)],
}


def _patch(module) -> None:
    for name, make in PATCHES[module.__name__]:
        original = getattr(module, name)
        ours = make(original)
        setattr(module, name, ours)
        for other in list(sys.modules.values()):  # pumplink modules that imported it by name already
            if (
                getattr(other, "__name__", "").startswith("pumplink.")
                and getattr(other, name, None) is original
            ):
                setattr(other, name, ours)


class _Patcher(importlib.abc.MetaPathFinder):
    """Patches each module of :data:`PATCHES` as it is imported: nothing is imported early (scipy's
    optimisers cost a third of a second to import, and most commands never load them)."""

    def find_spec(self, fullname, path, target=None):
        if fullname not in PATCHES:
            return None
        sys.meta_path.remove(self)
        try:
            spec = importlib.util.find_spec(fullname)
        finally:
            sys.meta_path.insert(0, self)
        run = spec.loader.exec_module

        def exec_module(module):
            run(module)
            _patch(module)

        spec.loader.exec_module = exec_module
        return spec


def install() -> None:
    """Replace the solvers: those already imported now, the others as they are imported."""
    for name in PATCHES:
        if name in sys.modules:
            _patch(sys.modules[name])
    sys.meta_path.insert(0, _Patcher())
    path = os.environ.get("PUMPLINK_PERTURB_COUNTS")
    if path:
        atexit.register(_write_counts, Path(path))


def _write_counts(path: Path) -> None:
    with path.open("a", encoding="utf-8") as f:
        f.write(json.dumps({"argv": sys.argv[1:], "mode": MODE, "calls": dict(CALLS)}) + "\n")


if __name__ == "__main__":
    install()
    from pumplink.cli import main

    main()
