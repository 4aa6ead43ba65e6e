"""Check a synthesised mechanism by running it: measured stroke, time ratio, swing, pressure angle.

Independent of the synthesis formulas: only the position functions of the kernels are used
(``crank_slider.slider_position``, ``slotted_lever.lever_angle``) and their derivatives
(``velocity_ratio``, ``lever_rate``), on a fine crank sweep; each extreme the sweep finds is
located by a bracketing root finder on the derivative (scipy's ``find_root``) to ~1e-15 rad,
and the largest pressure angle by a bracketing minimiser.  The
crank-rocker has its own check, :func:`pumplink.mechanisms.crank_rocker.measure_motion`.
The measured values are what the ``slider``, ``slotted`` and ``rocker`` commands print beside the
requested ones (docs/mechanisms.md §4).

Scalar designs only (one mechanism at a time); angles in radians, lengths in the caller's unit.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from pumplink.mechanisms import crank_slider as cs
from pumplink.mechanisms import slotted_lever as sl

#: Crank angles in the sweep before refinement.
SAMPLES = 4096
_TOL = dict(xatol=1e-14, xrtol=1e-15)


@dataclass(frozen=True)
class Measured:
    """What a mechanism does over one crank turn, measured on its positions.

    Attributes
    ----------
    turns : True if the mechanism assembles at every swept crank angle (the crank turns fully).
    stroke : distance between the output's two extreme positions [length] (chord for a lever tip).
    time_ratio : longer crank arc between the extremes over the shorter one [-].
    swing : angle between the output's extreme positions [rad] (NaN for a slider).
    largest_pressure_angle : largest pressure angle over the turn [rad] (NaN where not measured).
    extremes : crank angles of the two extremes [rad], (maximum, minimum) of the output coordinate.
    """

    turns: bool
    stroke: float
    time_ratio: float
    swing: float
    largest_pressure_angle: float
    extremes: tuple[float, float]


def _refine(f, grid, values, j):
    """Minimum of ``f`` near grid index ``j`` (bracketed by its neighbours), as (x, f(x))."""
    from scipy.optimize.elementwise import find_minimum  # lazy: keeps start-up fast

    n = grid.size
    x0, x1, x2 = grid[j] - (grid[1] - grid[0]), grid[j], grid[j] + (grid[1] - grid[0])
    res = find_minimum(f, (x0, x1, x2), tolerances=_TOL)
    if bool(res.success) and float(res.f_x) <= values[j % n]:
        return float(res.x), float(res.f_x)
    return float(grid[j]), float(values[j % n])


def _stationary(rate, grid, j):
    """Root of ``rate`` (the output's derivative) next to the sampled extremum ``j``, located by a
    bracketing root finder (scipy's ``find_root``) to ~1e-15 rad: the argument of a flat extremum
    is only ~1e-8 accurate from a minimiser, the root of the derivative is exact."""
    from scipy.optimize.elementwise import find_root  # lazy: keeps start-up fast

    step = grid[1] - grid[0]
    for lo, hi in ((grid[j] - step, grid[j]), (grid[j], grid[j] + step), (grid[j] - step, grid[j] + step)):
        if float(rate(lo)) * float(rate(hi)) <= 0.0:
            return float(find_root(rate, (lo, hi), tolerances=dict(xatol=1e-15, xrtol=1e-16)).x)
    return float(grid[j])


def _arcs(t_max, t_min):
    arc = float(np.mod(t_min - t_max, 2.0 * np.pi))
    return max(arc, 2.0 * np.pi - arc) / min(arc, 2.0 * np.pi - arc)


def _failed() -> Measured:
    nan = float("nan")
    return Measured(False, nan, nan, nan, nan, (nan, nan))


def crank_slider(crank_length, rod_length, offset, samples: int = SAMPLES) -> Measured:
    """Run a crank-slider through one crank turn (docs/mechanisms.md §1 conventions).

    The stroke is s_max - s_min of the slider position, the time ratio the ratio of the crank
    arcs between the two extremes, the largest pressure angle the refined maximum of
    ``crank_slider.pressure_angle`` over the turn.
    """
    r, rod, e = float(crank_length), float(rod_length), float(offset)
    grid = np.arange(samples) * (2.0 * np.pi / samples)
    s = np.asarray(cs.slider_position(r, rod, e, grid))
    lam = np.asarray(cs.pressure_angle(r, rod, e, grid))
    # a crank that turns must assemble everywhere and never put the rod across the guide
    if not (np.all(np.isfinite(s)) and np.all(lam < 0.5 * np.pi)):
        return _failed()

    def rate(t):
        return np.asarray(cs.velocity_ratio(r, rod, e, t))

    t_max = _stationary(rate, grid, int(np.argmax(s)))
    t_min = _stationary(rate, grid, int(np.argmin(s)))
    s_max, s_min = (float(cs.slider_position(r, rod, e, t)) for t in (t_max, t_min))
    _, lam_max = _refine(
        lambda t: -np.asarray(cs.pressure_angle(r, rod, e, t)), grid, -lam, int(np.argmax(lam))
    )
    return Measured(True, s_max - s_min, _arcs(t_max, t_min), float("nan"), -lam_max, (t_max, t_min))


def slotted_lever(crank_length, frame_length, lever_length, samples: int = SAMPLES) -> Measured:
    """Run a crank and slotted lever through one crank turn (docs/mechanisms.md §2 conventions).

    The swing is the difference of the extremes of ``slotted_lever.lever_angle``, the
    stroke the chord between the lever tip's extreme positions (from ``tip_position``), the time
    ratio the ratio of the crank arcs between the extremes.  The pressure angle between block and
    slot is zero throughout (docs/mechanisms.md §2), so it is not measured.
    """
    r, d, lever = float(crank_length), float(frame_length), float(lever_length)
    grid = np.arange(samples) * (2.0 * np.pi / samples)
    phi = np.asarray(sl.lever_angle(r, d, grid))
    if not np.all(np.isfinite(phi)):
        return _failed()

    def rate(t):
        return np.asarray(sl.lever_rate(r, d, t))

    t_max = _stationary(rate, grid, int(np.argmax(phi)))
    t_min = _stationary(rate, grid, int(np.argmin(phi)))
    p_max, p_min = (float(sl.lever_angle(r, d, t)) for t in (t_max, t_min))
    xa, ya = sl.tip_position(r, d, lever, t_max)
    xb, yb = sl.tip_position(r, d, lever, t_min)
    chord = float(np.hypot(xa - xb, ya - yb))
    return Measured(True, chord, _arcs(t_max, t_min), p_max - p_min, 0.0, (t_max, t_min))
