"""Kinematics and quasi-static force (docs/physics.md, Eq. 3-6 by virtual work) against the
independent 50-digit reference in ``tests/reference.py``."""

import math

import mpmath
import numpy as np
import reference as R
from hypothesis import assume, example, given, settings
from hypothesis import strategies as st
from mpmath import mpf

from pumplink.mechanisms.angles import crank_grid, grid_directions
from pumplink.mechanisms.fourbar import FourBar, kinematic_state, synthesize
from pumplink.mechanisms.fourbar_kernel import force_kernel

DEG = math.pi / 180
MIN_CRANK = R.MIN_CRANK


_gap, designs, _setup = R.angle_gap, R.force_designs, R.setup_design


# ~60 ms each (50-digit states at up to 8 angles); 40 designs
@settings(max_examples=40)
@given(designs(), st.lists(st.floats(0.0, 2 * math.pi, exclude_max=True), min_size=1, max_size=8))
def test_evaluate_matches_50_digit_reference(design, angles):
    syn, lk, mw = _setup(design)
    ext, fold = R.dead_centres(lk)
    th = np.array(angles)
    th = th[(_gap(th, ext) >= 1 * DEG) & (_gap(th, fold) >= 1 * DEG)]
    assume(th.size > 0)
    s = kinematic_state(syn.linkage, th, mw)
    assert s.force.shape == th.shape
    assert not s.singular.any()
    for i, t in enumerate(th):
        ref = R.state(lk, t, mw)
        assert abs(s.force[i] / ref["force"] - 1) <= 1e-10  # the accuracy target
        assert abs(s.handle_rate[i] / ref["grip_rate"] - 1) <= 1e-10
        assert abs(s.rocker_rate[i] / ref["rate"] - 1) <= 1e-10
        assert abs(s.coupler_x[i] - ref["bx"]) <= 1e-13 and abs(s.coupler_y[i] - ref["by"]) <= 1e-13
        assert abs(s.rocker_angle[i] - ref["rocker_angle"]) <= 1e-12
        assert abs(s.transmission_angle[i] - ref["transmission"]) <= 1e-10
        assert s.crank_angle[i] == t


def test_reference_rate_is_the_derivative_of_its_positions():
    """Self-check of the reference: the implicit-differentiation rate equals mpmath.diff of the
    rocker angle and of the grip position (central difference, h = 1e-15, error ~h^2)."""
    syn = synthesize(0.40, 0.20, 0.10, 0.20, math.radians(60.0), 1.0)
    lk = R.from_synthesis(syn)
    h = mpf("1e-15")
    for t in (0.3, 1.0, 2.0, 4.0, 5.5):
        ref = R.state(lk, t)
        d4 = mpmath.diff(lambda x: R.rocker_angle(lk, x), mpf(t), h=h)
        dp = mpmath.diff(lambda x: R.state(lk, x)["grip_x"], mpf(t), h=h)
        assert abs(d4 - ref["rate"]) <= 1e-25 and abs(dp - ref["grip_rate"]) <= 1e-25


# ~100 ms each (50-digit dead centres); 30 designs and the explicit near-change-point one
@settings(max_examples=30)
@given(designs())
@example(
    (
        (0.1236847703099308, -0.27499521107208724, 0.1236847703099308, 0.4718296892014639, 67.9510910401817),
        1.250985189963684,
        34.683698871265584,
    )
)
def test_singular_exactly_at_dead_centres(design):
    syn, lk, mw = _setup(design)
    for dc in R.dead_centres(lk):
        at = kinematic_state(syn.linkage, float(dc), mw)
        assert bool(at.singular) and np.isnan(at.force)  # NaN, never a huge finite number
        # 1e-6 deg away: regular, finite, and right to 1e-6 (rounding grows like eps / angle),
        # within the accuracy fourbar_kernel.SINGULAR_SIN documents: transmission angles of a few degrees
        # and more.  A near-change-point linkage (the @example: gamma_min = 0.012 deg) is
        # ill-conditioned there (1.8e-5, measured against the reference); it keeps the checks below.
        off = float(dc) + np.array([-1e-6, 1e-6]) * DEG
        s = kinematic_state(syn.linkage, off, mw)
        assert not s.singular.any() and np.isfinite(s.force).all()
        conditioned = min(syn.transmission_min, math.pi - syn.transmission_max) >= 2 * DEG
        for i, t in enumerate(off):
            if conditioned:
                assert abs(s.force[i] / R.force(lk, t, mw) - 1) <= 1e-6
        # Anywhere closer or farther: either flagged singular (NaN) or a finite force that is
        # the true force (within 1 %), so no spurious huge number slips through.  (How accurate
        # it is right next to the threshold: test_force_accuracy_just_outside_singular_threshold.)
        delta = np.concatenate([-np.logspace(-14, -2, 25), np.logspace(-14, -2, 25)])
        near = float(dc) + delta
        s = kinematic_state(syn.linkage, near, mw)
        np.testing.assert_array_equal(np.isnan(s.force), s.singular)
        for i in np.flatnonzero(~s.singular):
            assert abs(s.force[i] / R.force(lk, near[i], mw) - 1) <= 1e-2


def test_force_accuracy_just_outside_singular_threshold():
    """fourbar_kernel.SINGULAR_SIN's comment: beyond the threshold the force's relative rounding
    error is below ~1e-6.  Checked (with a 10x allowance, 1e-5) at 1e-9 rad from both dead
    centres of a design with a 40 mm crank, a 1.18 m coupler and a 50 mm rocker (a design found
    by hypothesis; measured 2.4e-5 and 3.1e-5 at the extended dead centre)."""
    syn = synthesize(
        0.99999, -0.4582216611135291, 0.15326738912249308, 0.05, math.radians(122.96307608597965), 1.1
    )
    lk = R.from_synthesis(syn)
    for dc in R.dead_centres(lk):
        for d in (-1e-9, 1e-9):
            t = float(dc) + d
            s = kinematic_state(syn.linkage, t, 1.0)
            assert not s.singular
            assert abs(s.force / R.force(lk, t, 1.0) - 1) <= 1e-5


# ~70 ms each (50-digit dead centres); 30 designs and angles
@settings(max_examples=30)
@given(designs(), st.floats(0.0, 2 * math.pi, exclude_max=True))
def test_power_balance_against_finite_difference_of_grip(design, t):
    """Fh * dPx/dt2 = Mw, with dPx/dt2 from a 5-point central difference (h = 1e-3 rad) of the
    grip position P = O4 + (H / rocker)(B - O4) built from evaluate's own coupler point B.
    Truncation ~h^4 and rounding ~eps/h keep the relative error far below 1e-8 at >= 1 deg
    from a dead centre (where |dPx/dt2| is at least ~1e-2 of its scale)."""
    syn, lk, mw = _setup(design)
    ext, fold = R.dead_centres(lk)
    assume(min(_gap(t, ext), _gap(t, fold)) >= 1 * DEG)
    h = 1e-3
    grid = t + h * np.array([-2, -1, 1, 2])
    s = kinematic_state(syn.linkage, grid, mw)
    px = syn.pivot_x + (syn.handle_length / syn.rocker_length) * (s.coupler_x - syn.pivot_x)
    dpx = (px[0] - 8 * px[1] + 8 * px[2] - px[3]) / (12 * h)
    f = kinematic_state(syn.linkage, t, mw).force
    assert abs(f * dpx / mw - 1) <= 1e-8


# ~10 ms each; 20 lists of 2-5 designs
@settings(max_examples=20)
@given(st.lists(designs(), min_size=2, max_size=5))
def test_kernel_and_broadcasting_match_per_design_evaluate(design_list):
    syns = []
    for inputs, handle, _mw in design_list:
        L1, D1, b, rocker, swing_deg = inputs
        syn = synthesize(L1, D1, b, rocker, math.radians(swing_deg), handle)
        if syn.feasible and syn.crank_length >= MIN_CRANK:
            syns.append(syn)
    assume(len(syns) >= 2)
    mw = np.array([d[2] for d in design_list[: len(syns)]])
    fields = (
        "pivot_x",
        "pivot_y",
        "crank_length",
        "coupler_length",
        "rocker_length",
        "handle_length",
        "branch",
    )
    cols = [np.array([float(getattr(s, f)) for s in syns])[:, None] for f in fields]
    lk = FourBar(*cols)
    th = crank_grid(97, 0.01)
    # include the exact dead centres so the NaN handling is compared too
    th = np.concatenate([th, [syns[0].dead_centre_extended, syns[0].dead_centre_folded]])
    many = kinematic_state(lk, th, mw[:, None])
    bx, by, fk = force_kernel(lk, np.cos(th), np.sin(th), mw[:, None])
    assert many.force.shape == (len(syns), th.size) == fk.shape
    for i, syn in enumerate(syns):
        one = kinematic_state(syn.linkage, th, mw[i])
        for name in (
            "coupler_x",
            "coupler_y",
            "rocker_angle",
            "rocker_rate",
            "handle_rate",
            "transmission_angle",
            "force",
        ):
            np.testing.assert_allclose(getattr(many, name)[i], getattr(one, name), rtol=1e-14, atol=0)
        np.testing.assert_array_equal(many.singular[i], one.singular)
        np.testing.assert_allclose(bx[i], one.coupler_x, rtol=1e-13, atol=1e-15)
        np.testing.assert_allclose(by[i], one.coupler_y, rtol=1e-13, atol=1e-15)
        np.testing.assert_array_equal(np.isnan(fk[i]), one.singular)
        np.testing.assert_allclose(fk[i], one.force, rtol=1e-12)


# ~2 ms each; 40 grid sizes and start indices
@settings(max_examples=40)
@given(st.integers(1, 100_000), st.data())
def test_grid_directions_match_numpy_to_a_few_ulp(n, data):
    i0 = data.draw(st.integers(0, n - 1))
    i1 = data.draw(st.integers(i0 + 1, min(n, i0 + 5000)))
    start = data.draw(st.sampled_from([0.0, 0.5, -1.25]))
    c, s = grid_directions(n, i0, i1, start)
    th = crank_grid(n, start)[i0:i1]
    # Angle addition re-rounds the angle: |error| <= a few ulp of the angle plus of the result.
    tol = 4 * np.spacing(np.abs(th) + 2 * math.pi) + 4 * np.spacing(1.0)
    assert c.shape == s.shape == th.shape
    assert np.all(np.abs(c - np.cos(th)) <= tol)
    assert np.all(np.abs(s - np.sin(th)) <= tol)


def test_alike_designs_are_alike_bit_for_bit(monkeypatch):
    """fourbar_kernel.alike_designs groups designs whose values have the same bits, as a dict of
    the values' bit patterns groups them: +0.0 and -0.0 apart, NaN with NaN of the same bits; a
    hash collision (every key made equal) is caught by the row check and shares nothing; with more
    than three quarters of the designs of kinds of their own nothing is shared."""
    from pumplink.mechanisms import fourbar_kernel as fk

    rng = np.random.default_rng(2)
    kinds = np.array(
        [[0.3, 0.1, 0.05], [0.3, 0.1, -0.0], [0.3, 0.1, 0.0], [np.nan, 0.2, 0.1], [0.3, 0.1, 0.05 + 1e-17]]
    )
    rows = kinds[rng.integers(0, kinds.shape[0], 40)]
    first, kind = fk.alike_designs(*rows.T)
    groups: dict = {}
    want = np.array([groups.setdefault(r.tobytes(), len(groups)) for r in rows])
    assert first.size == len(groups) and np.array_equal(
        rows[first][kind].view(np.uint64), rows.view(np.uint64)
    )
    assert all(len({want[i] for i in np.nonzero(kind == k)[0]}) == 1 for k in range(first.size))
    assert fk.alike_designs(*rng.uniform(size=(3, 40))) == (None, None)  # all distinct
    monkeypatch.setattr(fk, "_HASH", np.zeros(32, np.uint64))  # every key the same
    assert fk.alike_designs(*rows.T) == (None, None)
