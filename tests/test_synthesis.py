"""The synthesis commands' library (pumplink.studies.textbook): every result re-simulated, the
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

from pumplink.errors import InfeasibleDesign, SpecError
from pumplink.mechanisms import crank_rocker as cr
from pumplink.mechanisms import crank_rocker_synthesis as crs
from pumplink.studies import textbook as S
from pumplink.studies import textbook_rocker as SR


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
    rep = SR.rocker(math.radians(40), 50.0, 1.1818)
    assert rep.agrees
    mu = _ind(rep, "min_transmission").simulated
    for cmp in cr.published_comparisons():
        assert mu > cmp.transmission
    assert math.degrees(mu) == pytest.approx(46.950726188, abs=1e-8)


@pytest.mark.parametrize("K", [1.0, 1.25, 1.6])
def test_rocker_at_frame_resimulated(K):
    swing = math.radians(50)
    lo, hi = crs.frame_range(K, swing, 0.3)
    frame = 0.5 * (lo + hi)
    rep = SR.rocker(swing, 0.3, K, frame=frame)
    assert rep.agrees
    assert _len(rep, "frame") == pytest.approx(frame, rel=1e-12)
    assert math.hypot(_len(rep, "pivot_x"), _len(rep, "pivot_y")) == pytest.approx(frame, rel=1e-12)


def test_rocker_k1_dead_centres_half_a_turn_apart():
    """K = 1: the crank pivot on the chord line; the rocker's extremes come 180 deg apart."""
    rep = SR.rocker(math.radians(40), 1.0, 1.0, frame=1.6)
    assert _ind(rep, "time_ratio").simulated == pytest.approx(1.0, abs=1e-12)
    with pytest.raises(InfeasibleDesign, match="no optimum"):
        SR.rocker(math.radians(40), 1.0, 1.0)


def test_rocker_frame_outside_range_is_infeasible():
    swing = math.radians(50)
    lo, hi = crs.frame_range(1.25, swing, 0.3)
    assert SR.rocker(swing, 0.3, 1.25, frame=hi * 0.999).agrees
    with pytest.raises(InfeasibleDesign, match="frame lengths from"):
        SR.rocker(swing, 0.3, 1.25, frame=hi * 1.01)


def test_rocker_pivot_point_fixes_k_and_is_checked():
    swing = math.radians(50)
    rep = SR.rocker(swing, 0.3, pivot=(-0.26, 0.19))
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
        SR.rocker(swing, 0.3, pivot=(0.0, 0.1))
    with pytest.raises(SpecError):
        SR.rocker(swing, 0.3, 1.2, pivot=(0.0, 0.1))


# ~15 ms each (a scan of both design arcs, a root per crossing, a simulation); 15 draws
@settings(max_examples=15, deadline=None)
@given(K=st.floats(1.0, 2.5), swing_deg=st.floats(10.0, 140.0), frac=st.floats(0.02, 0.98))
def test_rocker_at_frame_property(K, swing_deg, frac):
    """Any frame length inside the admissible range gives a crank-rocker that really swings
    through the asked swing with the asked K (checked by measure_motion).  Near K = 1 the range
    runs to frames millions of times the rocker (9.5e6 at K = 1, 57°), where a float's rounding of
    the positions alone is 1e-9 of the swing, the agreement asked: the frame is drawn up to 100
    rockers, far beyond a lever mechanism anyone builds."""
    swing = math.radians(swing_deg)
    lo, hi = crs.frame_range(K, swing, 1.0)
    rep = SR.rocker(swing, 1.0, K, frame=lo + frac * (min(hi, 100.0) - lo))
    assert rep.agrees


# ----------------------------------------------------------------------------- analysis forms
def brute_slider_full(r, rod, e, n=2_000_001):
    """Stroke, K, far/near dead-centre crank angles and largest pressure angle of a crank-slider
    from a dense sweep of its position (circle about the crank pin meets the guide y = e)."""
    t = np.linspace(0.0, 2 * math.pi, n, endpoint=False)
    rise = e - r * np.sin(t)
    s = r * np.cos(t) + np.sqrt(rod * rod - rise * rise)
    far, near = t[np.argmax(s)], t[np.argmin(s)]
    arc = (near - far) % (2 * math.pi)
    k = max(arc, 2 * math.pi - arc) / min(arc, 2 * math.pi - arc)
    lam = np.arcsin(np.abs(rise) / rod).max()  # the rod's angle to the guide
    return s.max() - s.min(), k, far, near, float(lam)


def _turn_gap(a, b):
    """Distance of two crank angles on the circle [rad]."""
    return abs(math.remainder(a - b, 2 * math.pi))


@pytest.mark.parametrize(
    "r, rod, e",
    [(0.1, 0.4, 0.02), (0.1, 0.4, -0.05), (1.0, 2.5, 1.2), (0.3, 5.0, 0.0), (2.0, 3.0, -0.9)],
)
def test_slider_analysis_matches_a_brute_force_sweep(r, rod, e):
    rep = S.slider_analysis(r, rod, e)
    stroke, k, far, near, lam = brute_slider_full(r, rod, e)
    assert rep.agrees and rep.verdict.passed == (math.degrees(lam) <= 60)
    assert _ind(rep, "stroke").simulated == pytest.approx(stroke, rel=1e-9)
    assert _ind(rep, "stroke").closed_form == pytest.approx(stroke, rel=1e-9)
    assert _ind(rep, "relative_stroke").closed_form == pytest.approx(stroke / r, rel=1e-9)
    assert _ind(rep, "time_ratio").closed_form == pytest.approx(k, abs=1e-5)  # grid step 3e-6 rad
    assert _ind(rep, "largest_pressure_angle").closed_form == pytest.approx(lam, abs=1e-9)
    # dead centres: the sweep's argmax / argmin of the slider position, to a few grid steps
    assert _turn_gap(_ind(rep, "dead_centre_extended").closed_form, far) < 1e-5
    assert _turn_gap(_ind(rep, "dead_centre_folded").closed_form, near) < 1e-5
    theta = (math.pi * (k - 1) / (k + 1)) if k > 1 else 0.0
    assert _ind(rep, "extreme_rod_angle").closed_form == pytest.approx(theta, abs=1e-5)
    ratios = dict((key, v) for key, _, v in rep.ratios)
    assert ratios == {"rod_ratio": rod / r, "offset_ratio": e / r}


def test_slider_analysis_central_by_hand():
    """e = 0 by hand: H = 2r, K = 1, theta = 0, lambda_max = asin(r/l) (crank square to the
    guide), dead centres at 0 and 180 deg."""
    rep = S.slider_analysis(0.1, 0.4)
    assert _ind(rep, "stroke").simulated == pytest.approx(0.2, rel=1e-12)
    assert _ind(rep, "relative_stroke").simulated == pytest.approx(2.0, rel=1e-12)
    assert _ind(rep, "time_ratio").simulated == pytest.approx(1.0, abs=1e-12)
    assert _ind(rep, "largest_pressure_angle").simulated == pytest.approx(math.asin(0.25), abs=1e-12)
    assert _turn_gap(_ind(rep, "dead_centre_extended").simulated, 0.0) < 1e-9
    assert _turn_gap(_ind(rep, "dead_centre_folded").simulated, math.pi) < 1e-9
    assert "both strokes take 180° of crank" in rep.notes


def test_slider_analysis_published_gate_2025():
    """GATE 2025 Mechanical Engineering paper, question 60: an offset slider-crank with crank
    30 mm, rod 50 mm and offset 10 mm; the stroke, rounded to the nearest mm, is 62 mm.  By hand
    (Eq. 1.5 with the dead centres' right triangles): sqrt(80^2 - 10^2) - sqrt(20^2 - 10^2)
    = 79.3725 - 17.3205 = 62.0520 mm."""
    rep = S.slider_analysis(30.0, 50.0, 10.0)
    hand = math.sqrt(6300.0) - math.sqrt(300.0)
    assert _ind(rep, "stroke").simulated == pytest.approx(hand, rel=1e-12)
    assert round(_ind(rep, "stroke").simulated) == 62


def test_slider_analysis_realisability_from_both_sides():
    """The crank turns fully iff l > r + |e| (Eq. 1.7)."""
    assert S.slider_analysis(1.0, 1.5 + 1e-9, -0.5).agrees
    for rod in (1.5, 1.4):
        with pytest.raises(InfeasibleDesign, match="cannot turn fully"):
            S.slider_analysis(1.0, rod, -0.5)
    for kwargs in (
        dict(crank=0.0, rod=1.0),
        dict(crank=1.0, rod=-3.0),
        dict(crank=1.0, rod=3.0, offset=math.inf),
    ):
        with pytest.raises(SpecError):
            S.slider_analysis(**kwargs)


# Khurmi & Gupta, "Theory of Machines", ch. 5 (Simple Mechanisms), the crank and slotted lever
# quick return motion mechanism.  Their symbols: AC = distance between the fixed centres (our
# frame d), CB = driving crank (our r), AP = slotted lever (our l), R1R2 = stroke (the chord).
def test_slotted_khurmi_example_5_1_crank_and_centre_distance():
    """Example 5.1: AC = 300 mm, CB = 120 mm; the printed ratio of the cutting to the return
    time is 1.7.  By hand: sin(angle CAB1) = 120/300, the return crank angle is
    alpha = 2 (90 deg - asin 0.4) and K = (360 deg - alpha)/alpha."""
    rep = S.slotted(crank=120.0, frame_length=300.0)
    alpha = 2 * (math.pi / 2 - math.asin(0.4))
    hand = (2 * math.pi - alpha) / alpha
    k = _ind(rep, "time_ratio").simulated
    assert k == pytest.approx(hand, rel=1e-12) and round(k, 1) == 1.7
    assert _ind(rep, "fast_arc").simulated == pytest.approx(alpha, abs=1e-12)
    assert all(key != "stroke" for key in (i.key for i in rep.indicators))  # no lever, no stroke
    _, kb, _ = brute_lever(120.0, 300.0, 450.0)
    assert kb == pytest.approx(hand, abs=1e-5)


def test_slotted_khurmi_example_5_2_with_the_lever():
    """Example 5.2: AC = 240 mm, CB = 120 mm, AP = 450 mm; printed: the slotted bar is inclined
    30 deg to the vertical at its extremes, the time ratio is 2 and the stroke 450 mm
    (sin 30 deg = 120/240, alpha = 120 deg, K = 240/120, stroke = 2 * 450 * sin 30 deg)."""
    rep = S.slotted(crank=120.0, frame_length=240.0, lever=450.0)
    assert _ind(rep, "lever_inclination").simulated == pytest.approx(math.radians(30), abs=1e-12)
    assert _ind(rep, "time_ratio").simulated == pytest.approx(2.0, rel=1e-12)
    assert _ind(rep, "stroke").simulated == pytest.approx(450.0, rel=1e-12)
    swing, k, chord = brute_lever(120.0, 240.0, 450.0)
    assert chord == pytest.approx(450.0, rel=1e-9) and k == pytest.approx(2.0, abs=1e-5)
    assert rep.passed


def test_slotted_khurmi_example_5_3_from_the_crank():
    """Example 5.3: driving crank BC = 30 mm, time ratio 1.7, working stroke 120 mm; find AC
    and AP.  By hand: half the swing is 90 deg (K - 1)/(K + 1) = 23.333 deg, so
    AC = 30 / sin(23.333 deg) = 75.742 mm and AP = 120 / (2 sin(23.333 deg)) = 151.485 mm."""
    rep = S.slotted(1.7, 120.0, crank=30.0)
    half = math.radians(90 * 0.7 / 2.7)
    assert _len(rep, "crank") == 30.0
    assert _len(rep, "frame") == pytest.approx(30 / math.sin(half), rel=1e-14)
    assert _len(rep, "lever") == pytest.approx(120 / (2 * math.sin(half)), rel=1e-14)
    assert round(_len(rep, "frame"), 1) == 75.7 and round(_len(rep, "lever"), 1) == 151.5
    swing, k, chord = brute_lever(_len(rep, "crank"), _len(rep, "frame"), _len(rep, "lever"))
    assert chord == pytest.approx(120.0, rel=1e-9) and k == pytest.approx(1.7, abs=1e-5)
    assert rep.agrees and rep.passed


def test_slotted_crank_and_time_ratio_alone():
    """'Crank 300 mm, time ratio 2': sin(psi/2) = 1/2 by hand, so d = 600, and without a
    stroke or lever the shortest lever that holds the block, l = d + r = 900, strokes
    2 * 900 * 1/2 = 900."""
    rep = S.slotted(2.0, crank=300.0)
    assert (_len(rep, "frame"), _len(rep, "lever")) == (pytest.approx(600.0), pytest.approx(900.0))
    assert _ind(rep, "stroke").simulated == pytest.approx(900.0, rel=1e-12)
    assert any("l = d + r = 900" in n for n in rep.notes)


@settings(max_examples=15, deadline=None)  # each example sweeps 200 001 crank angles twice
@given(
    K=st.floats(1.05, 4.0),
    crank=st.floats(1e-3, 10.0),
    lever_factor=st.one_of(st.none(), st.floats(1.0, 3.0)),
    by_stroke=st.booleans(),
)
def test_slotted_from_the_crank_property(K, crank, lever_factor, by_stroke):
    """Any K and crank, with a lever (or its stroke) at least d + r long, or none: the
    mechanism brute-force swept here swings with K and, where asked, strokes as asked."""
    half = math.sin(math.pi * (K - 1) / (K + 1) / 2)
    d = crank / half
    lever = None if lever_factor is None else lever_factor * (d + crank) * (1 + 1e-12)
    stroke = None if lever is None else 2 * lever * half
    rep = S.slotted(K, stroke if by_stroke else None, crank=crank, lever=None if by_stroke else lever)
    assert rep.agrees and rep.passed
    swing, k, chord = brute_lever(_len(rep, "crank"), _len(rep, "frame"), _len(rep, "lever"), n=200_001)
    assert k == pytest.approx(K, abs=1e-4)
    if lever is not None:
        assert chord == pytest.approx(stroke, rel=1e-9)


def test_slotted_analysis_realisability_and_bad_sets():
    with pytest.raises(InfeasibleDesign, match="Whitworth"):
        S.slotted(crank=2.0, frame_length=2.0)
    assert S.slotted(crank=1.99, frame_length=2.0).agrees  # swings 168.5 deg, K = 30.4
    with pytest.raises(InfeasibleDesign, match="cannot hold"):
        S.slotted(crank=1.0, frame_length=2.0, lever=3.0 * (1 - 1e-9))
    assert S.slotted(crank=1.0, frame_length=2.0, lever=3.0).agrees
    with pytest.raises(InfeasibleDesign, match="take r <="):
        S.slotted(1.5, crank=1.0, lever=1.0)
    for kwargs in (
        dict(time_ratio=2.0, crank=1.0, frame_length=2.0),  # over-determined
        dict(time_ratio=2.0),  # no length
        dict(crank=1.0),  # analysis without the frame
        dict(time_ratio=2.0, stroke=1.0, lever=2.0),
        dict(crank=-1.0, frame_length=2.0),
    ):
        with pytest.raises(SpecError):
            S.slotted(**kwargs)


# ----------------------------------------------------------------------------- crank-rocker extremes
def brute_rocker(rep, n=2_000_001):
    """gamma_min, gamma_max and the dead-centre crank angles of a reported crank-rocker from a
    dense sweep written here: the coupler point is the intersection of the circle about the
    crank pin (coupler) with the circle about the rocker pivot D = 0 (rocker), on the branch
    whose rocker stays inside the swing (90 deg +- swing/2, the bisector on +y); the
    transmission angle is the angle at B between B->A and B->D from the positions."""
    ax, ay = _len(rep, "pivot_x"), _len(rep, "pivot_y")
    c, k, r = _len(rep, "crank"), _len(rep, "coupler"), _len(rep, "rocker")
    swing = next(v for key, _, _, v in rep.given if key == "swing")
    t = np.linspace(0.0, 2 * math.pi, n, endpoint=False)
    px, py = ax + c * np.cos(t), ay + c * np.sin(t)  # crank pin
    dist = np.hypot(px, py)
    # circle-circle: foot along D->pin at distance (r^2 - k^2 + dist^2)/(2 dist), height h
    a = (r * r - k * k + dist * dist) / (2 * dist)
    h = np.sqrt(r * r - a * a)
    ux, uy = px / dist, py / dist
    for sign in (1.0, -1.0):
        bx, by = a * ux - sign * h * uy, a * uy + sign * h * ux
        ang = np.arctan2(by, bx)
        if np.all(np.abs(ang - math.pi / 2) <= swing / 2 + 1e-6):
            break
    else:
        raise AssertionError("no branch keeps the rocker inside its swing")
    v1x, v1y, v2x, v2y = px - bx, py - by, -bx, -by
    gamma = np.arctan2(np.abs(v1x * v2y - v1y * v2x), v1x * v2x + v1y * v2y)
    far = np.hypot(bx - ax, by - ay)  # crank pivot to B: coupler + crank when stretched out
    extended = t[np.argmax(far)]
    folded = t[np.argmin(far)]
    return float(gamma.min()), float(gamma.max()), float(extended), float(folded)


@pytest.mark.parametrize(
    "args, kwargs",
    [
        ((math.radians(40), 50.0, 1.1818), {}),  # the optimal-transmission paper's example
        ((math.radians(40), 0.3, 1.1), dict(frame=0.4)),
        ((math.radians(50), 0.3), dict(pivot=(-0.26, 0.19))),
        ((math.radians(170), 1.0, 3.0), {}),  # jams: gamma_min 0.76 deg
        ((math.radians(40), 1.0, 1.0), dict(frame=1.6)),
    ],
)
def test_rocker_gamma_extremes_and_dead_centres_by_brute_force(args, kwargs):
    rep = SR.rocker(*args, **kwargs)
    gmin, gmax, extended, folded = brute_rocker(rep)
    assert _ind(rep, "gamma_min").closed_form == pytest.approx(gmin, abs=1e-9)
    assert _ind(rep, "gamma_max").closed_form == pytest.approx(gmax, abs=1e-9)
    assert _ind(rep, "gamma_min").simulated == pytest.approx(gmin, abs=1e-9)
    assert _ind(rep, "gamma_max").simulated == pytest.approx(gmax, abs=1e-9)
    # the farthest and nearest coupler point: crank and coupler stretched out / folded
    assert _turn_gap(_ind(rep, "dead_centre_extended").closed_form, extended) < 1e-5
    assert _turn_gap(_ind(rep, "dead_centre_folded").closed_form, folded) < 1e-5
    assert rep.agrees
    effective = min(gmin, math.pi - gmax)
    assert rep.passed == (math.degrees(effective) >= 30)


def test_rocker_k1_dead_centres_are_half_a_turn_apart_by_hand():
    """K = 1: the crank turns 180 deg from one dead centre to the other (theta = 0)."""
    rep = SR.rocker(math.radians(40), 1.0, 1.0, frame=1.6)
    gap = _ind(rep, "dead_centre_folded").simulated - _ind(rep, "dead_centre_extended").simulated
    assert _turn_gap(gap, math.pi) < 1e-9


def test_rocker_k1_without_frame_states_the_limit_as_a_number():
    """The bound 90 deg - swing/2 at a 40 deg swing is 70 deg (by hand), printed as a number."""
    with pytest.raises(InfeasibleDesign) as err:
        SR.rocker(math.radians(40), 1.0, 1.0)
    assert "approaches 70°" in str(err.value) and "swing/2" not in str(err.value)


# ----------------------------------------------------------------------------- the verdict
def _indicator(deviation=0.0):
    return S.Indicator("x", "x", S.RATIO, 1.0, 1.0, 1.0 + deviation)


@pytest.mark.parametrize(
    "pressure_deg, pairs, outcome",
    [
        (29.9, "sliding", "PASS"),
        (30.1, "sliding", "PASS with warnings"),  # the textbook's permissible 30 deg (sliding pair)
        (59.9, "sliding", "PASS with warnings"),
        (60.1, "sliding", "FAIL"),  # transmission angle below 30 deg
        (44.9, "revolute", "PASS"),
        (45.1, "revolute", "PASS with warnings"),  # permissible 45 deg (revolute pairs only)
        (89.8, "sliding", "FAIL"),
    ],
)
def test_pressure_angle_verdict_levels(pressure_deg, pairs, outcome):
    v = S.judge([_indicator()], pressure=math.radians(pressure_deg), pairs=pairs)
    assert v.outcome == outcome and v["pressure_angle"].fail_limit == 60.0


@pytest.mark.parametrize("gamma_deg, outcome", [(45.1, "PASS"), (44.9, "PASS with warnings"), (29.9, "FAIL")])
def test_transmission_angle_verdict_levels(gamma_deg, outcome):
    assert S.judge([_indicator()], transmission=math.radians(gamma_deg)).outcome == outcome


@pytest.mark.parametrize(
    "deviation, outcome", [(0.0, "PASS"), (5e-10, "PASS"), (2e-9, "FAIL"), (math.nan, "FAIL")]
)
def test_a_simulation_that_disagrees_fails(deviation, outcome):
    assert S.judge([_indicator(deviation)], transmission=math.radians(50)).outcome == outcome


def test_optimum_check_catches_a_simulation_that_disagrees():
    """The published example agrees; the same optimum against a simulation whose swing is off by
    1e-6 rad (what an optimum off the design circle would give) disagrees and fails."""
    import dataclasses

    swing = math.radians(40)
    opt = cr.optimal_crank_rocker(1.1818, swing, 50.0)
    sim = cr.measure_motion(cr.optimum_linkage(opt))
    good = SR.optimum_check(opt, sim, 1.1818, swing)
    assert good.agrees and good.verdict.outcome == "PASS"
    bad = SR.optimum_check(opt, dataclasses.replace(sim, swing=sim.swing + 1e-6), 1.1818, swing)
    assert not bad.agrees and bad.verdict.outcome == "FAIL"
    assert bad.verdict["simulation"].result == "fail"
