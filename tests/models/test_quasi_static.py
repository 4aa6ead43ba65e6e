"""Operator-force quantities (docs/physics.md): mean force, exact windowed peak, the verdict.

Expected values come from hand formulas, the 50-digit reference (``tests/reference.py``) and
brute-force dense evaluation; never from the function under test.
"""

import math

import mpmath
import numpy as np
import pytest
import reference as R
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from mpmath import mp, mpf

from pumplink.inputs.pump import DEFAULT_SPEC, parse_spec
from pumplink.mechanisms.fourbar import FourBar, grip_stroke, kinematic_state, synthesize
from pumplink.models.quasi_static import dead_band_peak_force, mean_force, wheel_torque
from pumplink.studies.force import force_analysis

DEG = math.pi / 180
MIN_CRANK = R.MIN_CRANK


_gap, designs, _setup = R.angle_gap, R.force_designs, R.setup_design


# ---------------------------------------------------------------------------------------------
# Mean force


def test_mean_force_hand_values():
    # Mw = 45 N * 0.25 m = 11.25 N m, H = 1 m, swing 60 deg: stroke S = 2 * 1 * sin 30 = 1 m,
    # F = 2 pi Mw / (2 S) = 11.25 pi N.
    assert wheel_torque(45.0, 0.25) == pytest.approx(11.25, rel=1e-15)
    assert mean_force(11.25, grip_stroke(1.0, math.radians(60.0))) == pytest.approx(
        11.25 * math.pi, rel=1e-15
    )
    # H = 1.2 m, swing 90 deg: S = 2.4 sin 45 = 1.2 sqrt(2) m; F = pi Mw / (1.2 sqrt 2).
    assert mean_force(10.0, grip_stroke(1.2, math.radians(90.0))) == pytest.approx(
        10.0 * math.pi / (1.2 * math.sqrt(2.0)), rel=1e-15
    )
    # broadcasts over designs
    np.testing.assert_allclose(
        mean_force(np.array([11.25, 10.0]), grip_stroke(np.array([1.0, 1.2]), np.radians([60.0, 90.0]))),
        [11.25 * math.pi, 10.0 * math.pi / (1.2 * math.sqrt(2.0))],
        rtol=1e-15,
    )


# ~0.25 s each (two 30-digit quadratures of the grip speed); 10 designs
@settings(max_examples=10)
@given(designs())
def test_mean_force_does_the_cycle_work(design):
    """Work per crank turn 2 pi Mw = mean_force * (total grip travel), with the travel the
    integral of |dPx/dt2| over a turn of the simulated linkage (50-digit quadrature split at the
    reference dead centres, where |dPx/dt2| has its kinks).  Equivalently the integral of
    |F| dPx over a cycle is 2 pi Mw."""
    syn, lk, mw = _setup(design)
    ext, fold = R.dead_centres(lk)
    with mp.workdps(30):
        plus = mpmath.fmod(fold - ext + 4 * mp.pi, 2 * mp.pi)

        def speed(t):
            return abs(R.state(lk, t)["grip_rate"])

        travel = mpmath.quad(speed, [ext, ext + plus]) + mpmath.quad(speed, [ext + plus, ext + 2 * mp.pi])
        stroke = 2 * mpf(float(syn.handle_length)) * mpmath.sin(mpf(float(syn.swing)) / 2)
        assert abs(travel / (2 * stroke) - 1) <= 1e-12  # the grip goes the stroke S twice
        work = mean_force(mw, grip_stroke(syn.handle_length, syn.swing)) * travel
        assert abs(work / (2 * mp.pi * mw) - 1) <= 1e-12


# ---------------------------------------------------------------------------------------------
# Exact windowed peak


def _brute_peak(syn, lk, band, mw, per_window=200_000):
    """Largest |F| from evaluate on per_window points of each window (ends included), with the
    windows placed from the reference dead centres."""
    ext, fold = (float(x) for x in R.dead_centres(lk))
    plus = (fold - ext) % (2 * math.pi)
    best, where = -np.inf, None
    for start, length in ((ext + band, plus - 2 * band), (fold + band, 2 * math.pi - plus - 2 * band)):
        if length < 0:
            continue
        th = start + length * np.linspace(0.0, 1.0, per_window)
        f = np.abs(kinematic_state(syn.linkage, th, mw).force)
        j = int(np.argmax(f))
        if f[j] > best:
            best, where = float(f[j]), float(th[j])
    return best, where, ext, fold


# ~0.1 s each (a 200 000-point sweep and 50-digit dead centres); 25 designs and bands
@settings(max_examples=25)
@given(designs(), st.floats(0.5, 40.0))
def test_peak_force_against_brute_force_and_reference(design, band_deg):
    syn, lk, mw = _setup(design)
    band = math.radians(band_deg)
    peak, angle = dead_band_peak_force(
        syn.linkage, syn.dead_centre_extended, syn.dead_centre_folded, band, mw
    )
    brute, _, ext, fold = _brute_peak(syn, lk, band, mw)
    assert np.isfinite(peak) and 0 <= angle < 2 * math.pi
    # The reported angle is allowed (outside both dead bands) ...
    assert min(_gap(angle, ext), _gap(angle, fold)) >= band - 1e-12
    # ... the reported force is the true force there (50 digits) ...
    assert abs(peak / abs(R.force(lk, angle, mw)) - 1) <= 1e-10
    # ... and no dense sample beats it, nor falls short of it by more than a sweep can: each
    # window's ends are samples, so a peak at a band edge (all 100 designs of a trial) is matched
    # up to the dead centres' agreement (1e-12 rad) times |F'/F| ~ 1/band, and a smooth interior
    # maximum up to |F''/F| (step/2)^2 / 2 with step <= 2 pi / 200 000: 1.2e-10 |F''/F|.  Measured
    # 1.4e-13; the target was 0.1 %.
    assert brute <= peak * (1 + 1e-12)
    assert (peak - brute) / peak <= 1e-9


def test_peak_at_the_window_end_is_the_force_exactly_dead_band_from_the_dead_centre():
    """Prototype design: |F| rises toward both dead centres, so the peak sits at a window end;
    it must equal the 50-digit force exactly ``band`` from a dead centre."""
    syn = synthesize(0.40, 0.20, 0.10, 0.20, math.radians(60.0), 1.0)
    lk = R.from_synthesis(syn)
    mw = 11.25
    ext, fold = R.dead_centres(lk)
    for band_deg in (20.0, 10.0, 5.0, 1.0):
        band = math.radians(band_deg)
        peak, angle = dead_band_peak_force(
            syn.linkage, syn.dead_centre_extended, syn.dead_centre_folded, band, mw
        )
        with mp.workdps(R.DPS):
            ends = [dc + s * mpf(band) for dc in (ext, fold) for s in (-1, 1)]
            forces = [abs(R.force(lk, e, mw)) for e in ends]
            k = max(range(4), key=lambda i: forces[i])
        assert abs(peak / forces[k] - 1) <= 1e-10
        assert _gap(angle, ends[k]) <= 1e-12
        # and it really is the peak: a dense sweep of the windows finds nothing larger
        brute, where, _, _ = _brute_peak(syn, lk, band, mw, per_window=20_000)
        assert brute <= peak * (1 + 1e-12) and _gap(where, ends[k]) <= 1e-12


def test_peak_near_dead_centre_is_missed_by_sampling_but_decides_the_verdict():
    """With a 1 deg dead band the force spike next to a dead centre falls between the 1 deg
    samples of a 360-point sweep: the sampled maximum is lower than the exact peak.  A force
    limit between the two must fail (the verdict uses the exact peak)."""
    spec_d = {**DEFAULT_SPEC, "operator": {**DEFAULT_SPEC["operator"], "dead_band": 1.0}}
    spec = parse_spec(spec_d)
    syn = synthesize(0.40, 0.20, 0.10, 0.20, math.radians(60.0), 1.0)
    lk = R.from_synthesis(syn)
    mw = spec.wheel_torque
    ext, fold = R.dead_centres(lk)
    with mp.workdps(R.DPS):
        exact = max(abs(R.force(lk, dc + s * mp.pi / 180, mw)) for dc in (ext, fold) for s in (-1, 1))
    grid = np.arange(360) * DEG
    outside = (_gap(grid, ext) > DEG) & (_gap(grid, fold) > DEG)
    sampled = float(np.max([abs(R.force(lk, t, mw)) for t in grid[outside]]))
    assert sampled < 0.95 * float(exact)  # the sweep misses the spike by > 5 %

    res = force_analysis(spec, samples=360)
    assert abs(res.dead_band_peak_force / exact - 1) <= 1e-10
    assert abs(res.sampled_peak / sampled - 1) <= 1e-10
    limit = 0.5 * (sampled + float(exact))
    below = parse_spec({**spec_d, "operator": {**spec_d["operator"], "force_limit": limit}})
    res = force_analysis(below, samples=360)
    assert res.mean_force < limit and res.sampled_peak < limit < res.dead_band_peak_force
    assert res.passed is False
    above = parse_spec({**spec_d, "operator": {**spec_d["operator"], "force_limit": 1.01 * float(exact)}})
    assert force_analysis(above, samples=360).passed is True


# ~7 ms each; 40 lists of 2-6 designs and bands
@settings(max_examples=40)
@given(st.lists(st.tuples(designs(), st.floats(0.5, 40.0)), min_size=2, max_size=6))
def test_vectorised_peak_force_equals_per_design_calls(items):
    rows = []
    for (inputs, handle, mw), band_deg in items:
        L1, D1, b, rocker, swing_deg = inputs
        syn = synthesize(L1, D1, b, rocker, math.radians(swing_deg), handle)
        if syn.feasible and syn.crank_length >= MIN_CRANK:
            rows.append((syn, mw, math.radians(band_deg)))
    assume(len(rows) >= 2)
    fields = (
        "pivot_x",
        "pivot_y",
        "crank_length",
        "coupler_length",
        "rocker_length",
        "handle_length",
        "branch",
    )
    lk = FourBar(*[np.array([float(getattr(s, f)) for s, _, _ in rows]) for f in fields])
    dce = np.array([s.dead_centre_extended for s, _, _ in rows])
    dcf = np.array([s.dead_centre_folded for s, _, _ in rows])
    band = np.array([r[2] for r in rows])
    mw = np.array([r[1] for r in rows])
    peaks, angles = dead_band_peak_force(lk, dce, dcf, band, mw)
    assert peaks.shape == angles.shape == (len(rows),)
    for i, (syn, m, bd) in enumerate(rows):
        p1, a1 = dead_band_peak_force(syn.linkage, syn.dead_centre_extended, syn.dead_centre_folded, bd, m)
        assert peaks[i] == pytest.approx(p1, rel=1e-12)
        assert _gap(angles[i], a1) <= 1e-9


def test_sampled_peak_does_not_depend_on_keeping_the_samples():
    """`force` and `force --summary` report the same sampled peak (one route for uniform sweeps)."""
    from pumplink.studies.force import force_analysis

    spec = parse_spec(DEFAULT_SPEC)
    for n in (12, 360, 3600, 100001):
        kept = force_analysis(spec, samples=n, keep_samples=True)
        streamed = force_analysis(spec, samples=n, keep_samples=False)
        assert kept.sampled_peak == streamed.sampled_peak
        assert kept.samples.crank_angle.size == n and streamed.samples is None


def test_designs_alike_share_the_geometry_of_the_force_to_the_same_bits(monkeypatch):
    """The dead-band peak and the sampled peak compute the part of the force the wheel torque does
    not enter once for designs alike in linkage, dead centres and band (a grid's variants that
    differ in the load); each peak and its angle must be the one computed design by design: 10
    linkages (5 and the same with a swing 1e-5 deg larger) under 6 torques each and two bands
    (one 0: windows that reach the dead centres), shuffled, against the calls without the sharing."""
    import pumplink.models.quasi_static as qs

    rng = np.random.default_rng(6)
    m = 5
    frame = [np.tile(rng.uniform(a, b, m), 2) for a, b in ((0.3, 0.6), (0.0, 0.3), (0.0, 0.15), (0.12, 0.25))]
    swing = np.radians(np.tile(rng.uniform(40, 70, m), 2) + np.repeat([0.0, 1e-5], m))
    syn = synthesize(*frame, swing, 0.9)
    which = rng.permutation(np.repeat(np.arange(2 * m), 6))
    lk = syn.linkage.take(which)
    dce, dcf = syn.dead_centre_extended[which], syn.dead_centre_folded[which]
    mw = rng.uniform(5.0, 15.0, which.size)
    band = np.where(rng.uniform(size=which.size) < 0.5, math.radians(15.0), 0.0)
    first, _ = qs.alike_designs(*lk.parameters, dce, dcf, band)
    assert first is not None and first.size < 0.75 * which.size
    shared = (*qs.dead_band_peak_force(lk, dce, dcf, band, mw), qs.sampled_peak(lk, 360, mw, dce, dcf, band))
    monkeypatch.setattr(qs, "alike_designs", lambda *columns: (None, None))
    alone = (*qs.dead_band_peak_force(lk, dce, dcf, band, mw), qs.sampled_peak(lk, 360, mw, dce, dcf, band))
    for a, b in zip(shared, alone):
        assert a.tobytes() == b.tobytes()
    assert np.isfinite(shared[0]).sum() > 20 and np.isinf(shared[0]).sum() > 0  # both kinds of band
