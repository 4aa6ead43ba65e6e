"""The synthesis commands' library (pumplink.synthesis): every result re-simulated, the
realisability boundaries from both sides, the K = 1 cases and the published example.

Independent routes: a dense brute-force sweep written here (no refinement, no kernel synthesis
formulas) for the crank-slider and slotted lever, hand derivations (K = 1 gives h = 2 and
nu = 0; L = 3, K = 2 lies on the boundary cos 60 deg = (L - 1)/(L + 1)), and the
optimal-transmission paper's worked example (K = 1.1818, swing 40 deg, rocker 50: its printed
designs have minimum transmission angles below the optimum).
"""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from pumplink import synthesis as S
from pumplink.errors import InfeasibleDesign, SpecError
from pumplink.mechanisms import crank_rocker as cr


def brute_slider(r, rod, e, n=2_000_001):
    """Stroke and K of a crank-slider from a dense sweep of its position (circle meets line)."""
    t = np.linspace(0.0, 2 * math.pi, n, endpoint=False)
    s = r * np.cos(t) + np.sqrt(rod * rod - (e - r * np.sin(t)) ** 2)
    arc = (t[np.argmin(s)] - t[np.argmax(s)]) % (2 * math.pi)
    return s.max() - s.min(), max(arc, 2 * math.pi - arc) / min(arc, 2 * math.pi - arc)


def brute_lever(r, d, lever, n=2_000_001):
    """Swing, K and tip chord of a slotted lever from a dense sweep (lever through the crank pin)."""
    t = np.linspace(0.0, 2 * math.pi, n, endpoint=False)
    phi = np.arctan2(d + r * np.sin(t), r * np.cos(t))
    arc = (t[np.argmin(phi)] - t[np.argmax(phi)]) % (2 * math.pi)
    swing = phi.max() - phi.min()
    return swing, max(arc, 2 * math.pi - arc) / min(arc, 2 * math.pi - arc), 2 * lever * math.sin(swing / 2)


def _ind(rep, key):
    return next(i for i in rep.indicators if i.key == key)


def _len(rep, key):
    return next(v for k, _, v in rep.lengths if k == key)


@pytest.mark.parametrize("K", [1.0, 1.15, 1.4, 1.7])
def test_slider_task2_resimulated(K):
    rep = S.slider(0.2, 4.0, K)
    assert rep.agrees
    stroke, k = brute_slider(_len(rep, "crank"), _len(rep, "rod"), _len(rep, "offset"))
    assert stroke == pytest.approx(0.2, rel=1e-9)
    assert k == pytest.approx(K, abs=1e-5)  # grid step 3e-6 rad
    assert _ind(rep, "time_ratio").simulated == pytest.approx(K, rel=1e-12)


def test_slider_k1_task2_is_task1():
    """K = 1: theta = 0, h = sqrt(2 * 2) = 2 and nu = 0: the central crank-slider of Task 1."""
    a, b = S.slider(0.1, 3.5, 1.0), S.slider(0.1, 3.5)
    for key in ("crank", "rod", "offset"):
        assert _len(a, key) == pytest.approx(_len(b, key), abs=1e-15)
    assert _len(b, "crank") == pytest.approx(0.05, rel=1e-15)  # r = H / 2
    assert _ind(b, "largest_pressure_angle").simulated == pytest.approx(math.asin(1 / 3.5), rel=1e-12)


def test_slider_task2_boundary_from_both_sides():
    """L = 3: K_max = 2 exactly (cos 60 deg = 2/4); below it a mechanism, at and above it none."""
    assert S.slider(1.0, 3.0, 2.0 - 1e-6).agrees
    for k in (2.0, 2.0 + 1e-6, 3.0):
        with pytest.raises(InfeasibleDesign, match="below 2"):
            S.slider(1.0, 3.0, k)


def test_slider_task1_boundary_from_both_sides():
    """Task 1 needs L > 1 + |e/r|: the rod longer than crank + offset."""
    assert S.slider(1.0, 1.5 + 1e-9, None, 0.5).agrees
    for L in (1.5, 1.2):
        with pytest.raises(InfeasibleDesign, match="longer than crank"):
            S.slider(1.0, L, None, 0.5)
    with pytest.raises(InfeasibleDesign):
        S.slider(1.0, 1.0)


@pytest.mark.parametrize(
    "kwargs",
    [
        dict(stroke=-1, rod_ratio=3),
        dict(stroke=math.nan, rod_ratio=3),
        dict(stroke=1, rod_ratio=3, time_ratio=0.9),
    ],
)
def test_slider_bad_input_is_a_spec_error(kwargs):
    with pytest.raises(SpecError):
        S.slider(**kwargs)


# ~10 ms each (a re-simulated crank-slider); 40 draws over the 2-parameter valid range
@settings(max_examples=40, deadline=None)
@given(
    L=st.floats(1.05, 12.0),
    frac=st.floats(0.0, 0.98),
    H=st.floats(1e-3, 10.0),
)
def test_slider_task2_property_over_the_valid_range(L, frac, H):
    kmax = (math.pi + 2 * math.atan(1 / math.sqrt(L))) / (math.pi - 2 * math.atan(1 / math.sqrt(L)))
    K = 1.0 + frac * (kmax - 1.0)
    rep = S.slider(H, L, K)
    assert rep.agrees
    r, rod, e = _len(rep, "crank"), _len(rep, "rod"), _len(rep, "offset")
    assert rod > r + abs(e)  # a crank that turns
    assert _ind(rep, "stroke").simulated == pytest.approx(H, rel=1e-9)


@pytest.mark.parametrize("K", [1.05, 1.5, 2.5])
def test_slotted_resimulated(K):
    rep = S.slotted(K, 0.3)
    swing, k, chord = brute_lever(_len(rep, "crank"), _len(rep, "frame"), _len(rep, "lever"))
    assert rep.agrees
    assert swing == pytest.approx(math.pi * (K - 1) / (K + 1), abs=1e-9)
    assert k == pytest.approx(K, abs=1e-5)
    assert chord == pytest.approx(0.3, rel=1e-9)
    assert _len(rep, "lever") == pytest.approx(_len(rep, "frame") + _len(rep, "crank"), rel=1e-12)


def test_slotted_boundaries_from_both_sides():
    psi = math.pi * 0.5 / 2.5
    lever = 0.3 / (2 * math.sin(psi / 2))
    dmax = lever / (1 + math.sin(psi / 2))  # l = d + r, by hand
    assert S.slotted(1.5, 0.3, dmax * (1 - 1e-9)).agrees
    with pytest.raises(InfeasibleDesign, match="cannot hold"):
        S.slotted(1.5, 0.3, dmax * (1 + 1e-6))
    with pytest.raises(InfeasibleDesign, match="K = 1"):
        S.slotted(1.0, 0.3)
    assert S.slotted(1.0 + 1e-6, 0.3).agrees


# ~8 ms each (a re-simulated slotted lever); 30 draws over K, H and the frame fraction
@settings(max_examples=30, deadline=None)
@given(K=st.floats(1.01, 5.0), H=st.floats(1e-3, 5.0), frac=st.floats(0.05, 1.0))
def test_slotted_property(K, H, frac):
    psi = math.pi * (K - 1) / (K + 1)
    dmax = H / (2 * math.sin(psi / 2)) / (1 + math.sin(psi / 2))
    rep = S.slotted(K, H, frac * dmax)
    assert rep.agrees


def test_rocker_optimum_reproduces_the_published_example():
    """The optimal-transmission paper's example: our optimum beats both printed designs
    (their minimum transmission angles by the paper's own Eq. (4), computed in the module's
    published comparisons) and runs exactly with K = 1.1818 and a 40 deg swing."""
    rep = S.rocker(math.radians(40), 50.0, 1.1818)
    assert rep.agrees
    mu = _ind(rep, "min_transmission").simulated
    for cmp in cr.published_comparisons():
        assert mu > cmp.transmission
    assert math.degrees(mu) == pytest.approx(46.950726188, abs=1e-8)


@pytest.mark.parametrize("K", [1.0, 1.25, 1.6])
def test_rocker_at_frame_resimulated(K):
    swing = math.radians(50)
    lo, hi = cr.frame_range(K, swing, 0.3)
    frame = 0.5 * (lo + hi)
    rep = S.rocker(swing, 0.3, K, frame=frame)
    assert rep.agrees
    assert _len(rep, "frame") == pytest.approx(frame, rel=1e-12)
    assert math.hypot(_len(rep, "pivot_x"), _len(rep, "pivot_y")) == pytest.approx(frame, rel=1e-12)


def test_rocker_k1_dead_centres_half_a_turn_apart():
    """K = 1: the crank pivot on the chord line; the rocker's extremes come 180 deg apart."""
    rep = S.rocker(math.radians(40), 1.0, 1.0, frame=1.6)
    assert _ind(rep, "time_ratio").simulated == pytest.approx(1.0, abs=1e-12)
    with pytest.raises(InfeasibleDesign, match="no optimum"):
        S.rocker(math.radians(40), 1.0, 1.0)


def test_rocker_frame_outside_range_is_infeasible():
    swing = math.radians(50)
    lo, hi = cr.frame_range(1.25, swing, 0.3)
    assert S.rocker(swing, 0.3, 1.25, frame=hi * 0.999).agrees
    with pytest.raises(InfeasibleDesign, match="frame lengths from"):
        S.rocker(swing, 0.3, 1.25, frame=hi * 1.01)


def test_rocker_pivot_point_fixes_k_and_is_checked():
    swing = math.radians(50)
    rep = S.rocker(swing, 0.3, pivot=(-0.26, 0.19))
    assert rep.agrees
    # by hand: theta = angle C1 A C2 from the coordinates
    w, y = 0.3 * math.sin(swing / 2), 0.3 * math.cos(swing / 2)
    a = np.array([-0.26, 0.19])
    u, v = np.array([-w, y]) - a, np.array([w, y]) - a
    theta = math.acos(u @ v / (np.linalg.norm(u) * np.linalg.norm(v)))
    assert _ind(rep, "time_ratio").simulated == pytest.approx(
        (math.pi + theta) / (math.pi - theta), rel=1e-10
    )
    # on the swing bisector, between D and the chord: C1 and C2 on opposite sides of the frame line
    with pytest.raises(InfeasibleDesign, match="one side"):
        S.rocker(swing, 0.3, pivot=(0.0, 0.1))
    with pytest.raises(SpecError):
        S.rocker(swing, 0.3, 1.2, pivot=(0.0, 0.1))


# ~15 ms each (a scan of both design arcs, a root per crossing, a simulation); 15 draws
@settings(max_examples=15, deadline=None)
@given(K=st.floats(1.0, 2.5), swing_deg=st.floats(10.0, 140.0), frac=st.floats(0.02, 0.98))
def test_rocker_at_frame_property(K, swing_deg, frac):
    """Any frame length inside the admissible range gives a crank-rocker that really swings
    through the asked swing with the asked K (checked by measure_motion)."""
    swing = math.radians(swing_deg)
    lo, hi = cr.frame_range(K, swing, 1.0)
    rep = S.rocker(swing, 1.0, K, frame=lo + frac * (hi - lo))
    assert rep.agrees
