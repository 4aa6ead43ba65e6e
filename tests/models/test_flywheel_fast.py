"""The fast route of the flywheel model against its reference route.

``pumplink.models.flywheel_solver.least_peak_force`` and ``energy_deficit`` take the extrema of U from a
table of |g| at the grid's uniform nodes and the dead centres, refined by a secant iteration on
|g| (the fast route).  The reference route (``_reference_least_peak_force``,
``_reference_energy_deficit``) evaluates U at 338 nodes per design, with 12-point Gauss-Legendre
travel at the nodes near the dead centres, and refines every local extremum of U by minimising U
itself with scipy's bracketing minimiser; it is the route the brute-force and asymptote tests of
tests/models/test_flywheel.py were written against.  Here both routes answer the same random
designs (the spec's ranges, forces from F_mean to the cap) and must agree to 1e-9 relative;
measured: 2.5e-11 (force) and 9.5e-11 (deficit) at most, the size of the reference's own
refinement tolerance (1e-9 rad on the extrema).
"""

import numpy as np
import pytest

from pumplink.mechanisms.fourbar import synthesize
from pumplink.models import flywheel_solver as fs
from pumplink.models.quasi_static import mean_force

REL = 1e-9


def _random_designs(seed, n):
    """Feasible crank-rockers drawn in the spec's ranges, each with a wheel torque [N m]."""
    rng = np.random.default_rng(seed)
    syn = synthesize(
        rng.uniform(0.0, 1.0, n),  # L1 [m]
        rng.uniform(-0.5, 0.8, n),  # D1 [m]
        rng.uniform(0.0, 0.3, n),  # b [m]
        rng.uniform(0.05, 0.6, n),  # rocker [m]
        np.radians(rng.uniform(10.0, 150.0, n)),  # swing
        rng.uniform(0.3, 1.5, n),  # handle [m]
    )
    ok = syn.feasible
    mw = 0.25 * rng.uniform(5.0, 200.0, n)[ok]  # rope force 5-200 N on a 0.25 m wheel
    f_mean = mean_force(mw, 2.0 * syn.handle_length[ok] * np.sin(0.5 * syn.swing[ok]))
    return (syn.linkage.take(ok), syn.dead_centre_extended[ok], syn.dead_centre_folded[ok], mw), f_mean, rng


def _assert_same(fast, ref):
    assert np.array_equal(np.isnan(fast), np.isnan(ref))
    assert np.array_equal(np.isinf(fast), np.isinf(ref))
    finite = np.isfinite(ref)
    rel = np.abs(fast[finite] - ref[finite]) / ref[finite]
    assert rel.max() <= REL, (rel.max(), np.flatnonzero(finite)[np.argmax(rel)])


@pytest.fixture
def reference_calls(monkeypatch):
    """Designs handed to the reference route by the fast one (it falls back where its table cannot
    resolve a design)."""
    calls = []
    for name in ("_reference_least_peak_force", "_reference_energy_deficit"):
        original = getattr(fs, name)

        def spy(*args, original=original):
            calls.append(np.size(args[1]))
            return original(*args)

        monkeypatch.setattr(fs, name, spy)
    return calls


@pytest.mark.parametrize("seed", [1, 2])
def test_least_peak_force_equals_the_reference_route(seed, reference_calls):
    designs, f_mean, rng = _random_designs(seed, 500)
    m = f_mean.size
    band = 10.0 ** rng.uniform(-3.0, 2.5, m)  # 1 mJ to 300 J
    fast = fs.least_peak_force(*designs, band)
    assert reference_calls == []  # the fast route resolved every design itself
    reference = fs._reference_least_peak_force(*designs, band)
    _assert_same(fast, reference)
    # the designs cover every regime: F_mean itself, above it, near the cap, beyond it (inf)
    ratio = reference / f_mean
    assert np.sum(np.abs(ratio - 1.0) <= 1e-12) >= 20
    assert np.sum((ratio > 1.0) & (ratio < 10.0)) >= 50
    assert np.sum((ratio > 1000.0) & np.isfinite(ratio)) >= 10
    assert np.sum(np.isinf(ratio)) >= 5


def test_energy_deficit_equals_the_reference_route(reference_calls):
    designs, f_mean, rng = _random_designs(3, 400)
    force = f_mean * 10.0 ** rng.uniform(0.0, 3.5, f_mean.size)
    force[:20] = f_mean[:20] * (1 + 1e-12)  # at F_mean: the deficit the largest
    force[20:30] = f_mean[20:30] * 0.99  # below it: inf
    fast = fs.energy_deficit(*designs, force)
    assert reference_calls == []
    _assert_same(fast, fs._reference_energy_deficit(*designs, force))
    assert np.all(np.isinf(fast[20:30])) and np.all(np.isfinite(fast[30:]))


def test_designs_the_table_cannot_resolve_go_to_the_reference_route(monkeypatch, reference_calls):
    """With no pass allowed, every design falls back: the answer is the reference's, bit for bit,
    and the fallback sees exactly the designs with a finite positive band."""
    designs, f_mean, rng = _random_designs(4, 60)
    band = 10.0 ** rng.uniform(-2.0, 2.0, f_mean.size)
    band[:3] = (0.0, np.inf, np.nan)  # answered without the iteration: inf, F_mean, NaN
    monkeypatch.setattr(fs, "MAX_PASSES", 0)
    fast = fs.least_peak_force(*designs, band)
    assert reference_calls == [f_mean.size - 3]
    reference = fs._reference_least_peak_force(*designs, band)
    assert np.array_equal(fast, reference, equal_nan=True)
    assert fast[0] == np.inf and fast[1] == pytest.approx(f_mean[1], rel=1e-12) and np.isnan(fast[2])
