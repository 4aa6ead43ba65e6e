"""Crank and slotted lever kernels (docs/mechanisms.md §2) checked against simulation.

Independent routes, none of which calls the code under test: constraint residuals (the block
on the crank pin lies on the lever line), a 30-digit mpmath simulation written here (the lever
angle from the crank pin, a dense sweep, the extremes located by bisection on a numerical
derivative, the tip's extreme positions and the crank arcs between them), and hand values.
"""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from mpmath import mp, mpf

from pumplink.mechanisms import slotted_lever as sl

mp.dps = 30
TAU = 2 * math.pi


def _phi(r, d, t):
    """Lever angle: direction of the crank pin A = (r cos t, d + r sin t) seen from C (mpmath)."""
    return mp.atan2(d + r * mp.sin(t), r * mp.cos(t))


def _bisect(f, a, b):
    fa = f(a)
    assert fa * f(b) <= 0
    for _ in range(110):
        m = (a + b) / 2
        fm = f(m)
        if fm * fa > 0:
            a, fa = m, fm
        else:
            b = m
    return (a + b) / 2


def simulate(r, d, lever, samples=4001):
    """Sweep the crank, locate the lever's extremes exactly and measure swing, stroke and K."""
    r, d, lever = mpf(r), mpf(d), mpf(lever)
    grid = np.linspace(0.0, TAU, samples, endpoint=False)
    phi = np.arctan2(float(d) + float(r) * np.sin(grid), float(r) * np.cos(grid))
    rate = lambda t: mp.diff(lambda x: _phi(r, d, x), t)  # noqa: E731
    step = mpf(TAU) / samples
    ends = []
    for i in (int(np.argmin(phi)), int(np.argmax(phi))):
        ends.append(_bisect(rate, mpf(grid[i]) - step, mpf(grid[i]) + step))
    t_lo, t_hi = ends
    p_lo, p_hi = _phi(r, d, t_lo), _phi(r, d, t_hi)
    chord = mp.hypot(lever * (mp.cos(p_hi) - mp.cos(p_lo)), lever * (mp.sin(p_hi) - mp.sin(p_lo)))
    arc = (t_hi - t_lo) % (2 * mp.pi)
    ratio = max(arc, 2 * mp.pi - arc) / min(arc, 2 * mp.pi - arc)
    reach = max(np.sqrt(float(r) ** 2 + float(d) ** 2 + 2 * float(r) * float(d) * np.sin(grid)))
    return {
        "swing": p_hi - p_lo,
        "stroke": chord,
        "time_ratio": ratio,
        "t_lo": t_lo % (2 * mp.pi),
        "t_hi": t_hi % (2 * mp.pi),
        "slow_arc": arc,
        "reach": reach,
    }


def _close(a, b, rel=1e-9):
    return abs(float(a) - float(b)) <= rel * max(1.0, abs(float(b)))


def _angle_close(a, b, tol=1e-9):
    gap = abs(float(a) - float(b)) % TAU
    return min(gap, TAU - gap) <= tol


designs = st.tuples(st.floats(0.01, 10.0), st.floats(0.01, 0.99))  # d, r/d


# ~2 ms each: 50 designs and crank angles
@settings(max_examples=50)
@given(designs, st.floats(-10.0, 10.0))
def test_lever_passes_through_the_block(dd, t):
    d, f = dd
    r = f * d
    phi = sl.lever_angle(r, d, t)
    a = np.array([r * math.cos(t), d + r * math.sin(t)])
    u = np.array([math.cos(phi), math.sin(phi)])
    assert abs(u[0] * a[1] - u[1] * a[0]) <= 1e-12 * d and u @ a > 0
    assert 0 < phi < math.pi
    assert sl.block_distance(r, d, t) == pytest.approx(np.linalg.norm(a), rel=1e-12)
    ref = mp.diff(lambda x: _phi(mpf(r), mpf(d), x), mpf(t))
    assert sl.lever_rate(r, d, t) == pytest.approx(float(ref), rel=1e-9, abs=1e-12)
    x, y = sl.tip_position(r, d, 2.5 * d, t)
    assert math.hypot(x, y) == pytest.approx(2.5 * d, rel=1e-14)


# ~50 ms each (a simulated revolution); 40 designs
@settings(max_examples=40)
@given(designs)
def test_extremes_swing_and_time_ratio_match_simulation(dd):
    d, f = dd
    r = f * d
    sim = simulate(r, d, 3.0 * d)
    right, left = sl.extremes(r, d)
    assert _angle_close(right, sim["t_lo"]) and _angle_close(left, sim["t_hi"])
    # at the extremes the crank is perpendicular to the lever
    for t in (right, left):
        crank = np.array([math.cos(t), math.sin(t)])
        phi = sl.lever_angle(r, d, t)
        assert abs(crank @ np.array([math.cos(phi), math.sin(phi)])) <= 1e-9
        assert abs(sl.lever_rate(r, d, t)) <= 1e-9
    assert _close(sl.swing_angle(r, d), sim["swing"])
    assert _close(sl.time_ratio(r, d), sim["time_ratio"])
    assert _close(sl.stroke(r, d, 3.0 * d), sim["stroke"])
    # counter-clockwise crank: from the right extreme to the left one is the slow stroke
    assert float(sim["slow_arc"]) > math.pi


# ~50 ms each (a simulated revolution); 60 draws over K, H and the frame fraction
@settings(max_examples=60)
@given(st.floats(1.001, 20.0), st.floats(1e-3, 10.0), st.floats(0.02, 1.0))
def test_synthesis_simulated(K, H, frac):
    psi = math.pi * (K - 1) / (K + 1)  # hand: K = (pi + psi)/(pi - psi)
    lever = H / (2 * math.sin(psi / 2))
    d = frac * lever / (1 + math.sin(psi / 2))  # any d up to the slot limit
    design = sl.synthesize_from_time_ratio(K, H, d)
    assert design.reason == sl.OK
    sim = simulate(design.crank_length, design.frame_length, design.lever_length)
    assert _close(sim["stroke"], H)
    assert _close(sim["time_ratio"], K)
    assert _close(sim["swing"], psi)
    assert sim["reach"] <= design.lever_length * (1 + 1e-12)  # the slot holds the block
    assert _close(design.stroke, H) and _close(design.time_ratio, K)


# ~60 ms each (a simulated revolution); 30 draws over K and H
@settings(max_examples=30)
@given(st.floats(1.001, 20.0), st.floats(1e-3, 10.0))
def test_synthesis_without_frame_uses_the_whole_lever_as_slot(K, H):
    design = sl.synthesize_from_time_ratio(K, H)
    assert design.reason == sl.OK
    sim = simulate(design.crank_length, design.frame_length, design.lever_length)
    assert _close(sim["stroke"], H) and _close(sim["time_ratio"], K)
    assert design.frame_length + design.crank_length == pytest.approx(design.lever_length, rel=1e-12)


def test_hand_case():
    """K = 2: psi = 60 deg, sin(psi/2) = 1/2: r = d/2, l = H."""
    design = sl.synthesize_from_time_ratio(2.0, 0.4, 0.2)
    assert design.crank_length == pytest.approx(0.1, rel=1e-14)
    assert design.lever_length == pytest.approx(0.4, rel=1e-14)
    assert design.swing_angle == pytest.approx(math.pi / 3, rel=1e-14)
    assert sl.lever_rate(1.0, 2.0, math.pi / 2) == pytest.approx(1 / 3, rel=1e-15)  # r/(d + r)
    assert sl.lever_rate(1.0, 2.0, -math.pi / 2) == pytest.approx(-1.0, rel=1e-15)  # -r/(d - r)


def test_realisability_boundaries_both_sides():
    # time ratio: K = 1 refused, just above accepted
    assert sl.synthesize_from_time_ratio(1.0, 0.3, 0.2).reason == sl.TIME_RATIO_NOT_ABOVE_ONE
    assert sl.synthesize_from_time_ratio(0.8, 0.3, 0.2).reason == sl.TIME_RATIO_NOT_ABOVE_ONE
    assert sl.synthesize_from_time_ratio(1.0 + 1e-9, 1e-9).reason == sl.OK  # l = 0.64, d = l/(1 + 8e-10)
    # slot: d up to l / (1 + sin(psi/2))
    K, H = 2.0, 0.4  # l = 0.4, sin(psi/2) = 1/2, d_max = 0.4 / 1.5
    d_max = 0.4 / 1.5
    assert sl.synthesize_from_time_ratio(K, H, d_max * (1 - 1e-9)).reason == sl.OK
    bad = sl.synthesize_from_time_ratio(K, H, d_max * (1 + 1e-9))
    assert bad.reason == sl.SLOT_TOO_SHORT and np.isnan(bad.crank_length) and np.isnan(bad.stroke)
    # analysis: r < d oscillates, r >= d does not
    assert sl.oscillates(1.0, 1.0 + 1e-12) and not sl.oscillates(1.0, 1.0) and not sl.oscillates(0.0, 1.0)
    assert np.isnan(sl.time_ratio(1.0, 1.0)) and np.isnan(sl.lever_angle(2.0, 1.0, 0.3))
    assert all(np.isnan(sl.extremes(1.5, 1.0)))
    codes = sl.synthesize_from_time_ratio([math.nan, 1.5, 1.5], [0.3, -0.3, 0.3], [0.2, 0.2, 0.0]).reason
    assert list(codes) == [sl.INPUT_NOT_FINITE, sl.STROKE_NOT_POSITIVE, sl.FRAME_NOT_POSITIVE]


def test_textbook_arc_stroke_is_not_the_chord():
    """The textbook's H = psi l is the tip's arc length; the distance between the extreme
    positions (the textbook's own definition of the stroke) is the chord 2 l sin(psi/2)."""
    r, d, lever = 0.5, 1.0, 2.0  # psi = 60 deg
    sim = simulate(r, d, lever)
    assert _close(sl.stroke(r, d, lever), sim["stroke"])
    assert abs(float(sim["stroke"]) - float(sim["swing"]) * lever) > 0.09


def test_broadcasting():
    t = np.linspace(0, TAU, 5)[None, :]
    d = np.array([1.0, 2.0])[:, None]
    assert sl.lever_angle(0.5, d, t).shape == (2, 5)
    assert sl.synthesize_from_time_ratio(np.array([1.2, 1.5, 3.0]), 0.3).crank_length.shape == (3,)
    assert isinstance(sl.time_ratio(0.5, 1.0), float)


# --------------------------------------------------------------------------- the crank as the scale
@settings(max_examples=40)
@given(st.floats(1.001, 20.0), st.floats(1e-3, 10.0), st.floats(1.0, 4.0))
def test_synthesis_from_the_crank_simulated(K, r, f):
    """K and the crank r (Khurmi's problem form) with a lever f (d + r) long: d = r / sin(psi/2)
    by hand, and the mpmath simulation swings with K and strokes 2 l sin(psi/2)."""
    half = math.sin(math.pi * (K - 1) / (K + 1) / 2)
    d = r / half
    lever = f * (d + r) * (1 + 1e-12)
    design = sl.synthesize_from_time_ratio(K, crank_length=r, lever_length=lever)
    assert design.reason == sl.OK and design.crank_length == r
    assert _close(design.frame_length, d) and design.lever_length == lever
    sim = simulate(design.crank_length, design.frame_length, design.lever_length)
    assert _close(sim["time_ratio"], K) and _close(sim["stroke"], 2 * lever * half)
    assert sim["reach"] <= lever * (1 + 1e-12)


def test_the_pair_not_given_makes_the_slot_just_hold_the_block():
    """K = 2 (sin(psi/2) = 1/2 by hand): crank 300 alone gives d = 600 and l = d + r = 900;
    stroke 0.4 alone gives l = 0.4, d = l / 1.5; the lever 0.9 alone the same as stroke 0.9."""
    a = sl.synthesize_from_time_ratio(2.0, crank_length=300.0)
    assert (a.frame_length, a.lever_length) == (
        pytest.approx(600.0, rel=1e-15),
        pytest.approx(900.0, rel=1e-15),
    )
    assert a.stroke == pytest.approx(900.0, rel=1e-14)
    b = sl.synthesize_from_time_ratio(2.0, 0.4)
    assert b.frame_length == pytest.approx(0.4 / 1.5, rel=1e-15)
    c, e = sl.synthesize_from_time_ratio(2.0, lever_length=0.9), sl.synthesize_from_time_ratio(2.0, 0.9)
    assert c.frame_length == pytest.approx(e.frame_length, rel=1e-15) and c.stroke == pytest.approx(0.9)


def test_the_crank_form_reasons_and_misuse():
    K, r = 2.0, 1.0  # d = 2, the block reaches d + r = 3
    assert sl.synthesize_from_time_ratio(K, crank_length=r, lever_length=3.0).reason == sl.OK
    short = sl.synthesize_from_time_ratio(K, crank_length=r, lever_length=3.0 * (1 - 1e-9))
    assert short.reason == sl.SLOT_TOO_SHORT and np.isnan(short.frame_length)
    codes = sl.synthesize_from_time_ratio(
        [1.5, 1.5, 1.0, 1.5], crank_length=[0.0, 1.0, 1.0, math.inf], lever_length=[5.0, -1.0, 5.0, 5.0]
    ).reason
    assert list(codes) == [
        sl.CRANK_NOT_POSITIVE,
        sl.LEVER_NOT_POSITIVE,
        sl.TIME_RATIO_NOT_ABOVE_ONE,
        sl.INPUT_NOT_FINITE,
    ]
    for kwargs in (
        dict(frame_length=1.0, crank_length=0.5),
        dict(stroke=1.0, lever_length=2.0),
        dict(),
    ):
        with pytest.raises(ValueError):
            sl.synthesize_from_time_ratio(1.5, **kwargs)


def test_lever_rate_stays_finite_next_to_a_turning_lever():
    """r/d = 1 - 1e-9: rho^2 = (d - r)^2 = 1e-18 at t = -90 deg, where r^2 + d^2 - 2 d r would
    round to 0; by hand the rate there is r (r - d)/(d - r)^2 = -r/(d - r)."""
    r, d = 1.0 - 1e-9, 1.0
    assert sl.lever_rate(r, d, -math.pi / 2) == pytest.approx(-r / (d - r), rel=1e-6)
    assert sl.block_distance(r, d, -math.pi / 2) == pytest.approx(1e-9, rel=1e-6)
