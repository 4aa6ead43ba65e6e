"""Crank-slider kernels (docs/mechanisms.md §1) checked against simulation.

Independent routes used here, none of which calls the code under test:

* constraint residuals: the slider point the code returns must lie on the guide and at rod
  length from the crank pin;
* a 30-digit mpmath simulation written in this file: the slider position from the circle-line
  intersection, a dense sweep of the crank, and the extremes (dead centres, largest pressure
  angle) located exactly by bracketed root finding on the derivative;
* hand derivations (K = 1 gives the central crank-slider with h = 2; cos theta* = (L-1)/(L+1)
  at the largest time ratio, solved here with acos instead of the module's atan form).

The textbook has no numerical worked example for Tasks 1 and 2, so none is reproduced; the
stroke of a given offset crank-slider is checked against a published examination problem
(GATE 2025, Mechanical Engineering, question 60).
"""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from mpmath import mp, mpf

from pumplink.mechanisms import crank_slider as cs

mp.dps = 30
TAU = 2 * math.pi


# --------------------------------------------------------------------------- reference simulation
def _position(r, rod, e, t):
    """Slider x from the circle (centre A, radius l) meeting the line y = e, +x branch (mpmath)."""
    ax, ay = r * mp.cos(t), r * mp.sin(t)
    return ax + mp.sqrt(rod * rod - (e - ay) ** 2)


def _slope(r, rod, e, t):
    """ds/dt of _position by the chain rule (mpmath)."""
    rise = e - r * mp.sin(t)
    return -r * mp.sin(t) + r * mp.cos(t) * rise / mp.sqrt(rod * rod - rise * rise)


def _refine(f, grid, i):
    """Root of f bracketed by the grid neighbours of the sampled extremum i (mpmath bisection)."""
    step = mpf(TAU) / len(grid)
    a, b = mpf(grid[i]) - step, mpf(grid[i]) + step
    fa = f(a)
    assert fa * f(b) <= 0, "the sampled extremum does not bracket a root of the derivative"
    for _ in range(110):
        m = (a + b) / 2
        fm = f(m)
        if fm * fa > 0:
            a, fa = m, fm
        else:
            b = m
    return (a + b) / 2


def simulate(r, rod, e, samples=4001):
    """Sweep the crank, locate the extremes exactly and measure the quality indicators.

    Returns a dict with the exact and the swept stroke, the time ratio, the crank angles of the
    slider extremes and the largest pressure angle.
    """
    r, rod, e = mpf(r), mpf(rod), mpf(e)
    grid = np.linspace(0.0, TAU, samples, endpoint=False)
    fr, fl, fe = float(r), float(rod), float(e)
    s = fr * np.cos(grid) + np.sqrt(fl * fl - (fe - fr * np.sin(grid)) ** 2)
    t_far = _refine(lambda t: _slope(r, rod, e, t), grid, int(np.argmax(s)))
    t_near = _refine(lambda t: _slope(r, rod, e, t), grid, int(np.argmin(s)))
    stroke = _position(r, rod, e, t_far) - _position(r, rod, e, t_near)
    arc = (t_near - t_far) % (2 * mp.pi)  # crank turn from the far to the near extreme
    ratio = max(arc, 2 * mp.pi - arc) / min(arc, 2 * mp.pi - arc)
    # pressure angle: maximise (e - r sin t)^2, d/dt = -2 (e - r sin t) r cos t
    rise = np.abs(fe - fr * np.sin(grid))
    t_lam = _refine(lambda t: (e - r * mp.sin(t)) * mp.cos(t), grid, int(np.argmax(rise)))
    lam = mp.asin(abs(e - r * mp.sin(t_lam)) / rod)
    return {
        "stroke": stroke,
        "swept_stroke": s.max() - s.min(),
        "time_ratio": ratio,
        "far": t_far % (2 * mp.pi),
        "near": t_near % (2 * mp.pi),
        "lam": lam,
    }


def _close(a, b, rel=1e-9):
    return abs(float(a) - float(b)) <= rel * max(1.0, abs(float(b)))


def _kmax(L):
    """Largest time ratio by hand: cos theta* = (L - 1)/(L + 1)."""
    theta = mp.acos((mpf(L) - 1) / (mpf(L) + 1))
    return (mp.pi + theta) / (mp.pi - theta)


designs = st.tuples(st.floats(0.01, 10.0), st.floats(1.02, 15.0), st.floats(-0.98, 0.98))


def _rle(d):
    r, L, f = d
    rod = L * r
    return r, rod, f * (rod - r)  # |e| < l - r: the crank turns fully


# --------------------------------------------------------------------------- analysis
# ~2 ms each: 60 designs and crank angles
@settings(max_examples=60)
@given(designs, st.floats(-10.0, 10.0))
def test_slider_position_satisfies_the_constraints(d, t):
    r, rod, e = _rle(d)
    s = cs.slider_position(r, rod, e, t)
    # B = (s, e) is on the guide by construction; it must be at rod length from A, on the +x side
    ax, ay = r * math.cos(t), r * math.sin(t)
    assert math.hypot(s - ax, e - ay) == pytest.approx(rod, rel=1e-12, abs=1e-12 * rod)
    assert s - ax > 0
    assert _close(s, _position(mpf(r), mpf(rod), mpf(e), mpf(t)), 1e-12)


# ~1 ms each: 40 designs and crank angles
@settings(max_examples=40)
@given(designs, st.floats(-10.0, 10.0))
def test_velocity_ratio_is_the_numerical_derivative(d, t):
    r, rod, e = _rle(d)
    ref = mp.diff(lambda x: _position(mpf(r), mpf(rod), mpf(e), x), mpf(t))
    scale = max(r, 1.0) * max(1.0, rod / (rod - r - abs(e)))
    assert abs(cs.velocity_ratio(r, rod, e, t) - float(ref)) <= 1e-9 * scale


# ~1 ms each: 40 designs and crank angles
@settings(max_examples=40)
@given(designs, st.floats(-10.0, 10.0))
def test_pressure_angle_is_the_angle_between_rod_and_guide(d, t):
    r, rod, e = _rle(d)
    s = float(_position(mpf(r), mpf(rod), mpf(e), mpf(t)))
    vec = np.array([s - r * math.cos(t), e - r * math.sin(t)])  # A -> B
    lam = math.acos(abs(vec @ np.array([1.0, 0.0])) / np.linalg.norm(vec))
    assert cs.pressure_angle(r, rod, e, t) == pytest.approx(lam, abs=1e-7)
    assert cs.transmission_angle(r, rod, e, t) == pytest.approx(math.pi / 2 - lam, abs=1e-7)


# ~35 ms each (a simulated revolution); 40 designs
@settings(max_examples=40)
@given(designs)
def test_cycle_quantities_match_the_simulated_crank_slider(d):
    r, rod, e = _rle(d)
    sim = simulate(r, rod, e)
    ext, fold = cs.dead_centres(r, rod, e)
    assert _angle_close(ext, sim["far"]) and _angle_close(fold, sim["near"])
    # crank and rod collinear there: extended (pointing the same way) and folded (opposite)
    for t, sign in ((ext, 1), (fold, -1)):
        a = np.array([math.cos(t), math.sin(t)])
        vec = np.array([cs.slider_position(r, rod, e, t), e]) - r * a  # A -> B
        assert abs(a[0] * vec[1] - a[1] * vec[0]) <= 1e-9 * rod
        assert np.sign(a @ vec) == sign
    assert _close(cs.stroke(r, rod, e), sim["stroke"])
    assert cs.stroke(r, rod, e) >= sim["swept_stroke"] - 1e-12 * rod  # a sweep never overshoots
    assert _close(cs.time_ratio(r, rod, e), sim["time_ratio"])
    assert _close(cs.largest_pressure_angle(r, rod, e), sim["lam"])
    # Eq. (1.9) by hand
    assert _close(cs.largest_pressure_angle(r, rod, e), mp.asin((mpf(r) + abs(mpf(e))) / mpf(rod)))


def _angle_close(a, b, tol=1e-9):
    gap = abs(float(a) - float(b)) % TAU
    return min(gap, TAU - gap) <= tol


def test_time_ratio_direction_for_positive_offset():
    """Counter-clockwise crank, e > 0: the slow stroke runs from the far to the near extreme."""
    r, rod, e = 1.0, 4.0, 1.5
    ext, fold = cs.dead_centres(r, rod, e)
    slow = (fold - ext) % TAU
    assert slow > math.pi
    assert cs.time_ratio(r, rod, e) == pytest.approx(slow / (TAU - slow), rel=1e-12)


def test_cycle_quantities_are_nan_where_the_crank_cannot_turn():
    r, rod = 1.0, 3.0
    for e in (2.0, 2.5, -2.0):  # l <= r + |e|
        assert np.isnan(cs.stroke(r, rod, e))
        assert np.isnan(cs.time_ratio(r, rod, e))
        assert np.isnan(cs.largest_pressure_angle(r, rod, e))
        assert all(np.isnan(cs.dead_centres(r, rod, e)))
        assert not cs.turns_fully(r, rod, e)
    assert cs.turns_fully(r, rod, 2.0 - 1e-9)
    # a single crank angle where the rod cannot reach the guide
    assert np.isnan(cs.slider_position(1.0, 2.0, 2.5, -math.pi / 2))
    assert np.isfinite(cs.slider_position(1.0, 2.0, 2.5, math.pi / 2))


def test_broadcasting_over_designs_and_angles():
    r = np.array([1.0, 2.0, 0.5])[:, None]
    t = np.linspace(0, TAU, 7)[None, :]
    s = cs.slider_position(r, 5.0, 0.3, t)
    assert s.shape == (3, 7)
    for i in range(3):
        for j in range(7):
            assert s[i, j] == cs.slider_position(float(r[i, 0]), 5.0, 0.3, float(t[0, j]))
    assert cs.stroke(r[:, 0], 5.0, 0.3).shape == (3,)
    assert isinstance(cs.stroke(1.0, 5.0, 0.3), float)


# --------------------------------------------------------------------------- Task 1
# ~30 ms each (a simulated revolution); 40 draws over H and L
@settings(max_examples=40)
@given(st.floats(1e-3, 10.0), st.floats(1.02, 20.0))
def test_task1_simulated(H, L):
    d = cs.synthesize_from_stroke(H, L)
    assert d.reason == cs.OK
    assert d.crank_length == pytest.approx(H / 2, rel=1e-15) and d.offset == 0.0
    sim = simulate(d.crank_length, d.rod_length, d.offset)
    assert _close(sim["stroke"], H) and _close(sim["time_ratio"], 1.0)
    assert _close(sim["lam"], math.asin(1 / L))
    assert _close(d.stroke, H) and _close(d.largest_pressure_angle, sim["lam"])


# ~20 ms each (a simulated revolution); 30 draws over H, L and the offset
@settings(max_examples=30)
@given(st.floats(1e-3, 10.0), st.floats(1.05, 20.0), st.floats(-0.95, 0.95))
def test_task1_with_offset_simulated(H, L, f):
    nu = f * (L - 1)
    d = cs.synthesize_from_stroke(H, L, nu)
    assert d.reason == cs.OK
    sim = simulate(d.crank_length, d.rod_length, d.offset)
    assert _close(sim["stroke"], H)
    assert _close(d.rod_length / d.crank_length, L, 1e-12)
    assert _close(d.offset / d.crank_length, nu, 1e-12)
    assert _close(sim["lam"], mp.asin((1 + abs(mpf(nu))) / mpf(L)))


def test_task1_realisability_boundary_both_sides():
    assert cs.synthesize_from_stroke(1.0, 3.0, 2.0 - 1e-9).reason == cs.OK
    bad = cs.synthesize_from_stroke(1.0, 3.0, [2.0, -2.0, 2.0 + 1e-9])
    assert np.all(bad.reason == cs.OFFSET_TOO_LARGE) and np.all(np.isnan(bad.crank_length))
    assert cs.synthesize_from_stroke(1.0, 1.0 + 1e-9).reason == cs.OK
    for L in (1.0, 0.5, -2.0):
        d = cs.synthesize_from_stroke(1.0, L)
        assert d.reason == cs.ROD_RATIO_NOT_ABOVE_ONE and np.isnan(d.rod_length)
    for H in (0.0, -1.0):
        assert cs.synthesize_from_stroke(H, 4.0).reason == cs.STROKE_NOT_POSITIVE
    assert cs.synthesize_from_stroke(math.inf, 4.0).reason == cs.INPUT_NOT_FINITE


# --------------------------------------------------------------------------- Task 2
# ~25 ms each (a simulated revolution); 60 draws over H, L and K up to its limit
@settings(max_examples=60)
@given(st.floats(1e-3, 10.0), st.floats(1.05, 20.0), st.floats(0.0, 0.99))
def test_task2_simulated(H, L, u):
    K = 1 + u * (float(_kmax(L)) - 1)
    d = cs.synthesize_from_time_ratio(H, K, L)
    assert d.reason == cs.OK
    sim = simulate(d.crank_length, d.rod_length, d.offset)
    assert _close(sim["stroke"], H)
    assert _close(sim["time_ratio"], K)
    assert _close(d.rod_length / d.crank_length, L, 1e-12)
    assert _close(sim["lam"], d.largest_pressure_angle)
    assert d.offset >= 0.0
    # lambda_max by hand from the requested values: asin((1 + nu)/L), nu from the triangle
    theta = mp.pi * (mpf(K) - 1) / (mpf(K) + 1)
    h = mp.sqrt(2 * ((mpf(L) ** 2 + 1) - (mpf(L) ** 2 - 1) * mp.cos(theta)))
    nu = (mpf(L) ** 2 - 1) * mp.sin(theta) / h
    assert _close(sim["lam"], mp.asin((1 + nu) / L))


def test_task2_with_time_ratio_one_is_task1():
    """K = 1: theta = 0, h = sqrt(2 (L^2 + 1 - L^2 + 1)) = 2, nu = 0 (hand check)."""
    for L in (1.5, 4.0, 10.0):
        d2 = cs.synthesize_from_time_ratio(0.3, 1.0, L)
        assert d2.offset == 0.0
        assert d2.crank_length == pytest.approx(0.15, rel=1e-15)
        assert d2.rod_length == pytest.approx(0.15 * L, rel=1e-15)
        assert d2.largest_pressure_angle == pytest.approx(math.asin(1 / L), rel=1e-14)


def test_task2_hand_case():
    """L = 2, K = 2 (theta = 60 deg), by hand: h^2 = 2 (5 - 3/2) = 7, nu = 3 (sqrt 3 / 2) / sqrt 7."""
    d = cs.synthesize_from_time_ratio(math.sqrt(7.0), 2.0, 2.0)
    assert d.reason == cs.OK
    assert d.crank_length == pytest.approx(1.0, rel=1e-14)
    assert d.rod_length == pytest.approx(2.0, rel=1e-14)
    assert d.offset == pytest.approx(3 * math.sqrt(3) / (2 * math.sqrt(7)), rel=1e-14)
    # L = 3, K = 2 sits on the boundary (cos 60 deg = 1/2 = (3 - 1)/(3 + 1)), nu = L - 1 exactly:
    # rejected just above it, and on it (rounding decides) never returned with NaN indicators;
    # L = 5, K = 2 lies beyond it although its nu = 6 sqrt 3 / sqrt 7 = 3.93 < L - 1 = 4
    assert cs.synthesize_from_time_ratio(1.0, 2.0 * (1 + 1e-12), 3.0).reason == cs.TIME_RATIO_TOO_LARGE
    edge = cs.synthesize_from_time_ratio(1.0, 2.0, 3.0)
    assert edge.reason == cs.TIME_RATIO_TOO_LARGE or np.isfinite(edge.time_ratio)
    assert cs.synthesize_from_time_ratio(1.0, 2.0, 5.0).reason == cs.TIME_RATIO_TOO_LARGE


@pytest.mark.parametrize("L", [1.1, 2.0, 4.0, 12.0])
def test_largest_time_ratio(L):
    kmax = _kmax(L)
    assert _close(cs.largest_time_ratio(L), kmax, 1e-14)
    # brute force: theta of crank-sliders with ratio L grows with the offset towards theta*
    f = np.linspace(0.0, 1.0 - 1e-9, 200)
    ks = [float(simulate(1.0, L, x * (L - 1))["time_ratio"]) for x in f[[0, 50, 100, 150, 199]]]
    assert all(a < b for a, b in zip(ks, ks[1:], strict=False))
    assert ks[-1] < float(kmax) and float(kmax) - ks[-1] < 1e-3


@pytest.mark.parametrize("L", [1.1, 2.0, 4.0, 12.0])
def test_task2_realisability_boundary_both_sides(L):
    kmax = float(_kmax(L))
    # nu approaches L - 1 quadratically in K_max - K, so 1e-5 below K_max already leaves
    # l - r - e at ~1e-10 of l: the mechanism is on the edge of turning fully
    inside = cs.synthesize_from_time_ratio(1.0, kmax * (1 - 1e-5), L)
    assert inside.reason == cs.OK
    sim = simulate(inside.crank_length, inside.rod_length, inside.offset, samples=40001)
    assert _close(sim["stroke"], 1.0) and _close(sim["time_ratio"], kmax * (1 - 1e-5))
    outside = cs.synthesize_from_time_ratio(1.0, [kmax * (1 + 1e-9), kmax * 1.2, 50.0], L)
    assert np.all(outside.reason == cs.TIME_RATIO_TOO_LARGE)
    assert np.all(np.isnan(outside.crank_length)) and np.all(np.isnan(outside.time_ratio))


def test_beyond_the_largest_time_ratio_the_formulas_make_a_different_mechanism():
    """Why K >= K_max must be refused: the closed form still gives lengths that even pass the
    'rod longer than crank + offset' check, but the mechanism they make has another K."""
    H, K, L = 1.0, 2.5, 4.0  # K_max(4) = 1.8376
    theta = math.pi * (K - 1) / (K + 1)
    h = math.sqrt(2 * ((L * L + 1) - (L * L - 1) * math.cos(theta)))
    nu = (L * L - 1) * math.sin(theta) / h
    assert 1 + nu < L  # the naive check passes
    r = H / h
    sim = simulate(r, L * r, nu * r)
    assert abs(float(sim["time_ratio"]) - K) > 0.1
    assert cs.synthesize_from_time_ratio(H, K, L).reason == cs.TIME_RATIO_TOO_LARGE


def test_printed_offset_formula_is_only_first_order():
    """The printed nu = sqrt((h - 2)(L^2 - 1)) gives a mechanism with the wrong K, or none."""
    H, L = 1.0, 4.0

    def printed_and_exact(K):
        theta = math.pi * (K - 1) / (K + 1)
        h = math.sqrt(2 * ((L * L + 1) - (L * L - 1) * math.cos(theta)))
        return h, math.sqrt((h - 2) * (L * L - 1)), (L * L - 1) * math.sin(theta) / h

    h, printed, exact = printed_and_exact(1.15)
    d = cs.synthesize_from_time_ratio(H, 1.15, L)
    assert d.offset / d.crank_length == pytest.approx(exact, rel=1e-12)
    assert abs(printed - exact) > 5e-2
    r = H / h
    sim = simulate(r, L * r, printed * r)
    assert abs(float(sim["time_ratio"]) - 1.15) > 5e-3
    # at K = 1.4 the printed offset exceeds l - r: that crank cannot even turn fully
    h, printed, exact = printed_and_exact(1.4)
    assert 1 + printed > L > 1 + exact
    # ... while both agree to first order in theta: their ratio tends to 1
    h, printed, exact = printed_and_exact(1 + 1e-5)
    assert printed / exact == pytest.approx(1, abs=1e-4)


def test_task2_reason_codes():
    d = cs.synthesize_from_time_ratio(
        [math.nan, -1.0, 1.0, 1.0, 1.0], [1.2, 1.2, 0.9, 1.2, 1.2], [3.0, 3.0, 3.0, 1.0, 3.0]
    )
    assert list(d.reason) == [
        cs.INPUT_NOT_FINITE,
        cs.STROKE_NOT_POSITIVE,
        cs.TIME_RATIO_BELOW_ONE,
        cs.ROD_RATIO_NOT_ABOVE_ONE,
        cs.OK,
    ]
    assert list(d.ok) == [False, False, False, False, True]
    assert np.isnan(d.stroke[:4]).all() and np.isfinite(d.stroke[4])
    assert set(cs.REASONS) == {
        cs.OK,
        cs.INPUT_NOT_FINITE,
        cs.STROKE_NOT_POSITIVE,
        cs.ROD_RATIO_NOT_ABOVE_ONE,
        cs.OFFSET_TOO_LARGE,
        cs.TIME_RATIO_BELOW_ONE,
        cs.TIME_RATIO_TOO_LARGE,
    }


def test_stroke_of_the_published_gate_2025_problem():
    """GATE 2025 Mechanical Engineering paper, question 60: crank 30 mm, rod 50 mm, offset
    10 mm; the answer is the stroke rounded to the nearest mm, 62 mm.  By hand from the dead
    centres' right triangles: sqrt(80^2 - 10^2) - sqrt(20^2 - 10^2) = 62.052 mm."""
    H = cs.stroke(30.0, 50.0, 10.0)
    assert round(H) == 62
    assert _close(H, math.sqrt(6300.0) - math.sqrt(300.0), rel=1e-14)
    assert _close(H, simulate(30.0, 50.0, 10.0)["stroke"])
