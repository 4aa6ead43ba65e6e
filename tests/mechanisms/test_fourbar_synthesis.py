"""Dead-centre synthesis (Eq. 1-2 of the pump paper, docs/physics.md) checked by simulating the linkage.

Every expected number here comes from ``tests/reference.py``: a 50-digit mpmath loop-closure
solution and synthesis written independently of ``pumplink`` (see its docstring), or from a
dense float sweep of that reference refined by a bounded optimiser.
"""

import math
import re

import mpmath
import numpy as np
import pytest
import reference as R
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from mpmath import mp, mpf
from scipy.optimize import minimize_scalar

from pumplink.mechanisms.fourbar import (
    CHANGE_POINT_MARGIN,
    FEASIBLE,
    PIVOT_ON_AXLE,
    SWING_CROSSES_FRAME_EXTENSION,
    SWING_CROSSES_FRAME_LINE,
    infeasibility_reason,
    synthesize,
)

DEG = math.pi / 180


def _angle_gap(a, b):
    """|a - b| modulo 2 pi, in [0, pi]."""
    d = math.fmod(abs(float(a) - float(b)), 2 * math.pi)
    return min(d, 2 * math.pi - d)


def _expected_code(L1, D1, b, rocker, swing_rad):
    """Reason code from the 50-digit psi angles (pumplink's documented thresholds)."""
    ref = R.synthesis(L1, D1, b, rocker, swing_rad)
    if ref["frame"] <= mpf("1e-9"):
        return PIVOT_ON_AXLE, ref
    if ref["psi2"] <= CHANGE_POINT_MARGIN:
        return SWING_CROSSES_FRAME_LINE, ref
    if ref["psi1"] >= mp.pi - CHANGE_POINT_MARGIN:
        return SWING_CROSSES_FRAME_EXTENSION, ref
    return FEASIBLE, ref


def _near_threshold(ref):
    """True within 1e-12 rad of a reason threshold (float and mpf may round either way there)."""
    return (
        abs(ref["psi2"] - CHANGE_POINT_MARGIN) < 1e-12
        or abs(ref["psi1"] - (mp.pi - CHANGE_POINT_MARGIN)) < 1e-12
        or abs(ref["frame"] - mpf("1e-9")) < 1e-15
    )


#: Shortest crank [m] for which the exact-swing claims are asserted to 1e-9 deg.  Eq. (2) is
#: evaluated without cancellation (crank = 2 f r sin(beta) sin(swing/2) / (d1 + d2)), so the
#: bound is set by conditioning, not by the formula: a design whose crank is below a micrometre
#: (e.g. a rocker pivot 0.1 um from the axle) is not a linkage, and its rocker extremes move by
#: ~1e-9 deg under float64 rounding of the inputs.  See test_tiny_crank_is_still_accurate.
MIN_CRANK = 1e-6


# ---------------------------------------------------------------------------------------------
# Feasible designs: the synthesised linkage really swings 90 deg +- swing/2


# ~60 ms each (50-digit dead centres); 60 draws, 7 in 10 feasible (the rest are assume()d away)
@settings(max_examples=60)
@given(R.linkage_inputs())
def test_feasible_design_swings_exactly_and_dead_centres_are_where_reported(inputs):
    L1, D1, b, rocker, swing_deg = inputs
    syn = synthesize(L1, D1, b, rocker, math.radians(swing_deg), 1.0)
    assume(bool(syn.feasible) and syn.crank_length >= MIN_CRANK)

    # The simulated linkage uses pumplink's float lengths exactly; the branch is the one with
    # the rocker CCW of the frame line (make_linkage raises if that is not unique).
    lk = R.from_synthesis(syn)
    ext, fold = R.dead_centres(lk)  # the only two stationary points of t4(t2): global extremes
    with mp.workdps(R.DPS):
        half = mpf(float(syn.swing)) / 2
        top, bottom = mp.pi / 2 + half, mp.pi / 2 - half
        # Rocker extremes exactly 90 +- swing/2 (1e-9 deg), at the reference dead centres ...
        assert abs(mpmath.degrees(R.rocker_angle(lk, ext) - top)) <= 1e-9
        assert abs(mpmath.degrees(R.rocker_angle(lk, fold) - bottom)) <= 1e-9
        # ... and at pumplink's reported dead-centre crank angles.
        assert abs(mpmath.degrees(R.rocker_angle(lk, syn.dead_centre_extended) - top)) <= 1e-9
        assert abs(mpmath.degrees(R.rocker_angle(lk, syn.dead_centre_folded) - bottom)) <= 1e-9
    assert _angle_gap(ext, syn.dead_centre_extended) <= 1e-10
    assert _angle_gap(fold, syn.dead_centre_folded) <= 1e-10
    assert 0 <= syn.dead_centre_extended < 2 * math.pi and 0 <= syn.dead_centre_folded < 2 * math.pi

    # Between the extremes a dense sweep never leaves [bottom, top] (no third extremum missed).
    t4, _, _ = R.sweep_rocker(lk, np.linspace(0, 2 * math.pi, 4001))
    assert np.all(np.isfinite(t4))
    assert t4.max() <= float(top) + 1e-12 and t4.min() >= float(bottom) - 1e-12

    # A Grashof crank-rocker with the crank the shortest link (s + l <= p + q).
    links = sorted([syn.frame_length, syn.crank_length, syn.coupler_length, syn.rocker_length])
    assert links[0] == syn.crank_length > 0
    assert links[0] + links[3] <= (links[1] + links[2]) * (1 + 1e-14)

    # Lengths agree with the independent 50-digit closed form (Eq. 2).
    ref = R.synthesis(L1, D1, b, rocker, math.radians(swing_deg))
    assert abs(syn.crank_length / ref["crank"] - 1) <= 1e-12
    assert abs(syn.coupler_length / ref["coupler"] - 1) <= 1e-12
    assert abs(syn.frame_length / ref["frame"] - 1) <= 1e-14
    assert abs(syn.psi1 - ref["psi1"]) <= 1e-14 and abs(syn.psi2 - ref["psi2"]) <= 1e-14

    # Time ratio from the reference dead-centre spacing; the CCW crank travel from the extended
    # to the folded dead centre is the +x stroke (rocker angle falls, so cos t4 rises).
    with mp.workdps(R.DPS):
        plus = mpmath.fmod(fold - ext + 4 * mp.pi, 2 * mp.pi)
        ratio = max(plus, 2 * mp.pi - plus) / min(plus, 2 * mp.pi - plus)
        assert abs(syn.stroke_plus_x - plus) <= 1e-10
        assert abs(syn.time_ratio / ratio - 1) <= 1e-9
        assert R.state(lk, ext + plus / 2)["grip_rate"] > 0
        assert R.state(lk, fold + (2 * mp.pi - plus) / 2)["grip_rate"] < 0


# ~10 ms each (a 20 000-point sweep); 40 designs
@settings(max_examples=40)
@given(R.linkage_inputs())
def test_transmission_range_matches_a_dense_sweep(inputs):
    L1, D1, b, rocker, swing_deg = inputs
    syn = synthesize(L1, D1, b, rocker, math.radians(swing_deg), 1.0)
    assume(bool(syn.feasible))
    lk = R.from_synthesis(syn)
    n = 20000
    grid = np.linspace(0, 2 * math.pi, n, endpoint=False)
    _, _, gamma = R.sweep_rocker(lk, grid)

    def extreme(sign):
        """sign = +1: the minimum, -1: the maximum (grid point, then a bounded refinement)."""
        j = int(np.argmin(sign * gamma))
        res = minimize_scalar(
            lambda t: sign * R.sweep_rocker(lk, t)[2],
            method="bounded",
            bounds=(grid[j] - 2 * math.pi / n, grid[j] + 2 * math.pi / n),
            options=dict(xatol=1e-12),
        )
        return sign * min(sign * gamma[j], res.fun)

    assert abs(extreme(1.0) - syn.transmission_min) <= 1e-9
    assert abs(extreme(-1.0) - syn.transmission_max) <= 1e-9


def test_tiny_crank_is_still_accurate():
    """A 1 um frame with a 0.5 m rocker (a degenerate but accepted design: crank 87 nm).

    The 50-digit closed form is well conditioned here (crank = (d1^2 - d2^2)/(2 (d1 + d2)) =
    2 frame rocker (cos psi2 - cos psi1)/(d1 + d2) has no cancellation), so a float64
    implementation can give the crank to a few ulp; the subtraction d1 - d2 loses
    log10(coupler/crank) ~ 7 digits.
    """
    swing = math.radians(10.0)
    syn = synthesize(1e-6, 0.0, 0.0, 0.5, swing, 1.0)
    ref = R.synthesis(1e-6, 0.0, 0.0, 0.5, swing)
    assert syn.feasible
    assert abs(syn.crank_length / ref["crank"] - 1) <= 1e-12


def test_published_prototype_numbers():
    """The issue's example layout, against the 50-digit route (not against pumplink)."""
    syn = synthesize(0.40, 0.20, 0.10, 0.20, math.radians(60.0), 1.0)
    ref = R.synthesis(0.40, 0.20, 0.10, 0.20, math.radians(60.0))
    assert syn.feasible
    assert syn.frame_length == pytest.approx(math.hypot(0.45, 0.20), rel=1e-15)  # Eq. (1) by hand
    assert syn.beta == pytest.approx(math.pi / 2 + math.atan2(0.20, 0.45), rel=1e-15)
    assert syn.crank_length == pytest.approx(float(ref["crank"]), rel=1e-13)
    assert syn.coupler_length == pytest.approx(float(ref["coupler"]), rel=1e-13)


# ---------------------------------------------------------------------------------------------
# Feasibility: exactly the inputs with 0 < psi2 < psi1 < 180 deg (up to the documented
# CHANGE_POINT_MARGIN) are feasible, the others carry the right reason and a useful sentence.


# ~2 ms each; 300 draws put about 60 on each infeasibility code
@settings(max_examples=300)
@given(R.linkage_inputs())
def test_reason_code_is_exactly_the_psi_condition(inputs):
    L1, D1, b, rocker, swing_deg = inputs
    swing = math.radians(swing_deg)
    code, ref = _expected_code(L1, D1, b, rocker, swing)
    assume(not _near_threshold(ref))
    syn = synthesize(L1, D1, b, rocker, swing, 1.0)
    assert int(syn.reason) == code
    assert bool(syn.feasible) == (code == FEASIBLE)
    if code == FEASIBLE:
        assert infeasibility_reason(syn.reason, L1, D1, b, swing) is None
        assert np.isfinite(
            [
                syn.crank_length,
                syn.coupler_length,
                syn.dead_centre_extended,
                syn.dead_centre_folded,
                syn.time_ratio,
            ]
        ).all()
        return
    # Infeasible: NaN lengths (never a made-up value) and one sentence naming the value.
    assert np.isnan(
        [
            syn.crank_length,
            syn.coupler_length,
            syn.dead_centre_extended,
            syn.dead_centre_folded,
            syn.time_ratio,
            syn.transmission_min,
        ]
    ).all()
    text = infeasibility_reason(syn.reason, L1, D1, b, swing)
    assert isinstance(text, str) and text and "\n" not in text
    if code == PIVOT_ON_AXLE:
        assert "axle" in text
        return
    name, psi, limit = (
        ("psi2", ref["psi2"], "> 0") if code == SWING_CROSSES_FRAME_LINE else ("psi1", ref["psi1"], "< 180")
    )
    m = re.search(re.escape(name) + r" = (-?\d+\.\d+) deg", text)
    assert m, text
    assert abs(float(m.group(1)) - float(mpmath.degrees(psi))) <= 0.006  # printed with 2 decimals
    assert limit in text


@st.composite
def crossing_inputs(draw, beyond_deg=0.0):
    """Inputs in the ranges of ``R.linkage_inputs`` whose swing crosses the frame line or its
    extension, drawn directly (four in five draws of the whole box are feasible).  With
    reach = L1 + b/2 and alpha = atan2(D1, reach), Eq. (2) gives psi2 = 90 deg - alpha - swing/2
    and psi1 = 90 deg - alpha + swing/2, so psi2 <= 0 iff D1 >= reach cot(swing/2) and
    psi1 >= 180 deg iff D1 <= -reach cot(swing/2); ``beyond_deg`` puts alpha at least that much
    past the limit.  The swing is drawn from the range where such a D1 exists within the box.
    The pivot is kept 1 cm off the axle (straight under it: see the explicit test), so that the
    feasible window of D1, 2 reach cot(swing/2) >= 5 mm wide, holds the 1 mm probes of the fixes."""
    L1, b, rocker = draw(st.floats(0.01, 1.0)), draw(st.floats(0.0, 0.3)), draw(st.floats(0.05, 0.6))
    reach = L1 + b / 2
    code = draw(st.sampled_from([SWING_CROSSES_FRAME_LINE, SWING_CROSSES_FRAME_EXTENSION]))
    d_max = 0.8 if code == SWING_CROSSES_FRAME_LINE else 0.5  # the box: -0.5 <= D1 <= 0.8
    lowest = 2 * (math.degrees(math.atan2(reach, d_max)) + beyond_deg) + 1e-6
    swing_deg = draw(st.floats(max(10.0, lowest), 150.0))
    limit = reach * math.tan(math.radians(90.0 - swing_deg / 2 + beyond_deg))
    size = draw(st.floats(min(limit, d_max), d_max))
    return L1, size if code == SWING_CROSSES_FRAME_LINE else -size, b, rocker, swing_deg


# ~5 ms each (six synthesis calls); 80 draws over both codes and the whole crossing region
@settings(max_examples=80)
@given(crossing_inputs())
def test_suggested_fixes_are_right(inputs):
    """'make D1 < X' / 'swing < Y' in the sentence: just past X (Y) the design becomes feasible,
    just short of it it stays infeasible (the limit is tight, not merely safe)."""
    L1, D1, b, rocker, swing_deg = inputs
    swing = math.radians(swing_deg)
    code = int(synthesize(L1, D1, b, rocker, swing).reason)
    assert code in (SWING_CROSSES_FRAME_LINE, SWING_CROSSES_FRAME_EXTENSION)
    text = infeasibility_reason(code, L1, D1, b, swing)
    rel = "<" if code == SWING_CROSSES_FRAME_LINE else ">"
    d1_limit = float(re.search(rf"make D1 {rel} (-?\d+\.\d+) m", text).group(1))
    sw_limit = float(re.search(r"swing < (-?\d+\.\d+) deg", text).group(1))
    sgn = -1 if rel == "<" else 1
    assert synthesize(L1, d1_limit + sgn * 1e-3, b, rocker, swing).feasible
    assert int(synthesize(L1, d1_limit - sgn * 1e-3, b, rocker, swing).reason) == code
    if sw_limit > 0.1:
        assert synthesize(L1, D1, b, rocker, math.radians(sw_limit - 0.05)).feasible
        assert not synthesize(L1, D1, b, rocker, math.radians(sw_limit + 0.05)).feasible


# ~0.1 s each (50-digit dead centres on both branches); 25 draws over both codes
@settings(max_examples=25)
@given(crossing_inputs(beyond_deg=0.1 + 1e-6))
def test_rejected_closed_form_really_swings_differently(inputs):
    """For rejected inputs, the Eq. (2) lengths (computed anyway, at 50 digits) do not make a
    rocker swinging 90 +- swing/2: cos is even, so they are the lengths of the design with psi
    reflected into (0, 180 deg), a crank-rocker swinging 180 deg - 2|alpha| instead
    (alpha = atan2(D1, L1 + b/2), the frame line's slope).  Both assembly branches are simulated."""
    L1, D1, b, rocker, swing_deg = inputs
    swing = math.radians(swing_deg)
    code, ref = _expected_code(L1, D1, b, rocker, swing)
    assert code in (SWING_CROSSES_FRAME_LINE, SWING_CROSSES_FRAME_EXTENSION)
    # 0.1 deg away from the change-point linkage psi = 0 / 180 deg (it can flip branch).
    excess = -ref["psi2"] if code == SWING_CROSSES_FRAME_LINE else ref["psi1"] - mp.pi
    assert excess > 0.1 * DEG
    with mp.workdps(R.DPS):
        expected = mp.pi - 2 * abs(ref["alpha"])
        for sigma in (1, -1):
            lk = R.make_linkage(L1, D1, b, rocker, 1.0, ref["crank"], ref["coupler"], sigma=sigma)
            t_a, t_b = R.dead_centres(lk)  # raises if the crank cannot turn fully
            real = abs(R._wrap(R.rocker_angle(lk, t_a) - R.rocker_angle(lk, t_b)))
            assert abs(real - expected) <= 1e-20
            assert abs(real - mpf(swing)) >= 2 * excess - 1e-20
            assert abs(mpmath.degrees(real - mpf(swing))) > 0.1


def test_pivot_straight_under_the_axle_gives_a_zero_crank():
    """L1 = b = 0, D1 > 0: the frame line is vertical, psi2 = -swing/2 and the closed form's
    d1 = d2, i.e. a crank of length 0 that cannot move the rocker at all: rejected (code 2)."""
    swing = math.radians(60.0)
    ref = R.synthesis(0.0, 0.3, 0.0, 0.2, swing)
    assert abs(ref["crank"]) <= 1e-45  # zero to the 50-digit working precision
    syn = synthesize(0.0, 0.3, 0.0, 0.2, swing)
    assert int(syn.reason) == SWING_CROSSES_FRAME_LINE
    text = infeasibility_reason(syn.reason, 0.0, 0.3, 0.0, swing)
    assert "psi2 = -30.00 deg" in text


def test_pivot_on_axle_is_rejected():
    syn = synthesize(0.0, 0.0, 0.0, 0.2, math.radians(60.0))
    assert int(syn.reason) == PIVOT_ON_AXLE and not syn.feasible
    assert "axle" in infeasibility_reason(syn.reason, 0.0, 0.0, 0.0, math.radians(60.0))


def test_synthesis_broadcasts_over_designs():
    L1 = np.array([0.4, 0.1, 0.6, 0.0])
    D1 = np.array([0.2, 0.7, -0.3, 0.0])
    syn = synthesize(L1, D1, 0.1, 0.2, math.radians(60.0), 1.0)
    for i in range(L1.size):
        one = synthesize(L1[i], D1[i], 0.1, 0.2, math.radians(60.0), 1.0)
        for field in (
            "crank_length",
            "coupler_length",
            "dead_centre_extended",
            "dead_centre_folded",
            "time_ratio",
            "transmission_min",
            "reason",
        ):
            np.testing.assert_array_equal(np.asarray(getattr(syn, field))[i], getattr(one, field))
