"""The numpy bracketing minimiser against scipy's (``scipy.optimize.elementwise.find_minimum``).

pumplink's start-up path refines the peak force and the peak rocker rate with
``pumplink.mechanisms.bracket.find_minimum`` instead of importing ``scipy.optimize``; it must
give scipy's answers, to 1e-12 relative, on the very problems the peak searches pose and on
textbook functions whose minimiser is known by hand.
"""

import math

import numpy as np
import pytest
from scipy.optimize import elementwise

from pumplink.mechanisms.bracket import CONVERGED, INVALID_BRACKET, MAXITER, NONFINITE, find_minimum
from pumplink.mechanisms.fourbar import FourBar, kinematic_state, synthesize
from pumplink.mechanisms.fourbar_kernel import force_kernel

TIGHT = dict(xatol=1e-13, xrtol=1e-15)  # the peak searches' tolerances


def _designs(n, seed):
    """``n`` feasible pump four-bars from random frames and swings: the seven parameters and the
    two dead-centre angles [rad], each a 1-D array over the designs."""
    rng = np.random.default_rng(seed)
    m = 4 * n
    syn = synthesize(
        rng.uniform(0.2, 0.8, m),
        rng.uniform(-0.1, 0.4, m),
        rng.uniform(0.0, 0.2, m),
        rng.uniform(0.15, 0.4, m),
        np.radians(rng.uniform(30, 80, m)),
        rng.uniform(0.6, 1.2, m),
    )
    ok = np.nonzero(syn.feasible)[0][:n]
    assert ok.size == n
    geom = tuple(
        np.asarray(v)[ok]
        for v in (
            syn.pivot_x,
            syn.pivot_y,
            syn.crank_length,
            syn.coupler_length,
            syn.rocker_length,
            syn.handle_length,
            syn.branch,
        )
    )
    return geom, np.asarray(syn.dead_centre_extended)[ok], np.asarray(syn.dead_centre_folded)[ok]


def _abs_force(theta, px, py, c, k, r, h, br):
    lk = FourBar(px, py, c, k, r, h, br)
    return np.abs(force_kernel(lk, np.cos(theta), np.sin(theta), 11.25)[2])


def _neg_abs_rate(theta, px, py, c, k, r, h, br):
    return -np.abs(kinematic_state(FourBar(px, py, c, k, r, h, br), theta, 1.0).rocker_rate)


def _same(ours, theirs):
    assert np.array_equal(ours.status, theirs.status)
    assert np.array_equal(ours.success, theirs.success)
    for a, b in ((ours.x, theirs.x), (ours.f_x, theirs.f_x)):
        a, b = np.asarray(a), np.asarray(b)
        assert np.array_equal(np.isnan(a), np.isnan(b))
        ok = ~np.isnan(a)
        np.testing.assert_allclose(a[ok], b[ok], rtol=1e-12, atol=0)


@pytest.mark.parametrize("seed", [1, 2])
def test_peak_rocker_rate_problems_match_scipy(seed):
    """The problem ``fourbar.peak_rocker_rate`` poses (the grip's peak speed): -|d theta4/d theta2|
    on the three-point bracket around the largest of 180 crank angles, for 400 random designs."""
    geom, _, _ = _designs(400, seed)
    step = 2 * np.pi / 180
    theta = np.arange(180) * step
    val = _neg_abs_rate(theta[None, :], *(p[:, None] for p in geom))
    mid = theta[np.argmin(val, axis=1)]
    init = (mid - step, mid, mid + step)
    ours = find_minimum(_neg_abs_rate, init, args=geom, tolerances=TIGHT)
    _same(ours, elementwise.find_minimum(_neg_abs_rate, init, args=geom, tolerances=TIGHT))
    assert np.all(ours.success)
    for d in (-1e-6, 1e-6):  # a local maximum of the rate: no point 1e-6 rad either side is higher
        assert np.all(_neg_abs_rate(ours.x + d, *geom) >= ours.f_x)


@pytest.mark.parametrize("seed", [3, 4])
def test_force_kernel_problems_match_scipy(seed):
    """The force kernel as the objective: the least |F| between the two dead centres (an
    interior minimum on each stroke), bracketed on a 97-point grid over each arc, 400 designs.
    (The windowed peak search poses the same function with the sign flipped; its largest point
    is usually at an end of the window, where no refinement is needed.)"""
    geom, dce, dcf = _designs(400, seed)
    plus = np.mod(dcf - dce, 2 * np.pi)
    starts = np.concatenate([dce, dcf])
    lengths = np.concatenate([plus, 2 * np.pi - plus])
    geom = tuple(np.concatenate([p, p]) for p in geom)
    theta = starts[:, None] + lengths[:, None] * np.linspace(0.0, 1.0, 97)[1:-1]
    val = _abs_force(theta, *(p[:, None] for p in geom))
    j = np.argmin(val, axis=1)
    assert np.all((j > 0) & (j < 94))
    k = np.arange(j.size)
    init = (theta[k, j - 1], theta[k, j], theta[k, j + 1])
    ours = find_minimum(_abs_force, init, args=geom, tolerances=TIGHT)
    _same(ours, elementwise.find_minimum(_abs_force, init, args=geom, tolerances=TIGHT))
    assert np.all(ours.success)
    for d in (-1e-6, 1e-6):
        assert np.all(_abs_force(ours.x + d, *geom) >= ours.f_x)


def test_known_minimisers_and_default_tolerances():
    """(x - c)^2 + 2 has its minimum 2 at x = c (by hand); with scipy's default tolerances
    (xrtol = sqrt(eps)) both land within 1e-7 of c and agree with each other."""
    c = np.linspace(-3.0, 3.0, 41)
    f = lambda x, c: (x - c) ** 2 + 2.0
    init = (c - 1.3, c + 0.1, c + 2.0)
    ours = find_minimum(f, init, args=(c,))
    _same(ours, elementwise.find_minimum(f, init, args=(c,)))
    assert np.all(ours.success)
    np.testing.assert_allclose(ours.x, c, atol=1e-7)
    np.testing.assert_allclose(ours.f_x, 2.0, rtol=1e-14)
    # a smooth non-quadratic one: cosh(x - c) + 0.3 sin(5 x) (x - c)^2, tight tolerances
    g = lambda x, c: np.cosh(x - c) + 0.3 * np.sin(5 * x) * (x - c) ** 2
    init = (c - 0.4, c + 0.01, c + 0.5)
    _same(
        find_minimum(g, init, args=(c,), tolerances=TIGHT),
        elementwise.find_minimum(g, init, args=(c,), tolerances=TIGHT),
    )


def test_failures_are_flagged_as_scipy_flags_them():
    f = lambda x: (x - 1.0) ** 2
    # invalid bracket (middle point not lowest): status -1, NaN minimiser
    bad = find_minimum(f, (np.array([2.0, -1.0]), np.array([3.0, 1.1]), np.array([4.0, 3.0])))
    assert bad.status.tolist() == [INVALID_BRACKET, CONVERGED]
    assert math.isnan(bad.x[0]) and not bad.success[0]
    # a non-finite value in the bracket: status -3
    inf = find_minimum(lambda x: np.where(x > 2.5, np.inf, f(x)), (0.0, 1.1, 3.0))
    assert inf.status == NONFINITE and math.isnan(inf.x)
    # the iteration limit: status -2, the best point so far
    few = find_minimum(f, (-5.0, 0.3, 7.0), maxiter=2, tolerances=TIGHT)
    assert few.status == MAXITER and not few.success and few.nit == 2
    for ours, theirs in (
        (
            bad,
            elementwise.find_minimum(f, (np.array([2.0, -1.0]), np.array([3.0, 1.1]), np.array([4.0, 3.0]))),
        ),
        (few, elementwise.find_minimum(f, (-5.0, 0.3, 7.0), maxiter=2, tolerances=TIGHT)),
    ):
        _same(ours, theirs)
        assert np.array_equal(ours.nit, theirs.nit) and np.array_equal(ours.nfev, theirs.nfev)


def test_shapes_follow_the_broadcast():
    f = lambda x, c: (x - c) ** 2
    one = find_minimum(f, (0.0, 0.4, 1.0), args=(0.5,))
    assert np.ndim(one.x) == 0 and abs(float(one.x) - 0.5) < 1e-7
    grid = find_minimum(f, (0.0, 0.4, 1.0), args=(np.full((2, 3), 0.5),))
    assert grid.x.shape == (2, 3) and grid.success.shape == (2, 3)


@pytest.mark.parametrize("seed", [5, 6])
def test_the_iterates_are_scipys_bit_for_bit(seed):
    """Not only the answers: every problem takes scipy's steps, so the minimiser, its value and the
    iteration and evaluation counts are scipy's to the bit (the peak-rate and force problems above,
    400 designs each, and a bumpy function with random tolerances) - the numbers pumplink prints in
    full are refined here."""
    geom, dce, dcf = _designs(400, seed)
    step = 2 * np.pi / 180
    theta = np.arange(180) * step
    mid = theta[np.argmin(_neg_abs_rate(theta[None, :], *(p[:, None] for p in geom)), axis=1)]
    # the least |F| on each stroke, as test_force_kernel_problems_match_scipy poses it
    plus = np.mod(dcf - dce, 2 * np.pi)
    both = tuple(np.concatenate([g, g]) for g in geom)
    arc = (
        np.concatenate([dce, dcf])[:, None]
        + np.concatenate([plus, 2 * np.pi - plus])[:, None] * np.linspace(0.0, 1.0, 97)[1:-1]
    )
    j, k = np.argmin(_abs_force(arc, *(g[:, None] for g in both)), axis=1), np.arange(arc.shape[0])
    rng = np.random.default_rng(seed)
    c, p = rng.uniform(-1, 1, 300), rng.uniform(1.1, 4.0, 300)
    bumpy = lambda x, c, p: np.abs(x - c) ** p + 0.1 * np.sin(7 * x)  # noqa: E731
    problems = [
        (_neg_abs_rate, (mid - step, mid, mid + step), geom, TIGHT),
        (_abs_force, (arc[k, j - 1], arc[k, j], arc[k, j + 1]), both, TIGHT),
        (bumpy, (np.full(300, -1.5), rng.uniform(-0.5, 0.5, 300), np.full(300, 1.7)), (c, p),
         dict(xatol=10 ** rng.uniform(-14, -3), xrtol=0.0)),
    ]  # fmt: skip
    for f, init, args, tol in problems:
        ours = find_minimum(f, init, args=args, tolerances=tol)
        theirs = elementwise.find_minimum(f, init, args=args, tolerances=tol)
        for name in ("x", "f_x", "status", "nit", "nfev"):
            a, b = np.asarray(getattr(ours, name)), np.asarray(getattr(theirs, name))
            assert a.astype(float).tobytes() == b.astype(float).tobytes(), name
        assert np.count_nonzero(ours.success) >= 200  # the bumpy one: some brackets are invalid
