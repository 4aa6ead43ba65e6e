"""Build tolerances (pumplink.studies.builds, tolerance and tolerance_study): the linkage a build
is, the builds' independence of the chunking, the Monte Carlo spread against the first-order
prediction, the Wilson interval and the tolerance allocation.

References: the build's geometry is rebuilt here from hole positions with plain 2-D vectors (the
definition in docs/tolerance.md §1, not the module's formulas); the Wilson score interval from its
closed form (Wilson 1927, Eq. as in Brown, Cai & DasGupta 2001, Eq. 4); the first-order spread is
compared with the Monte Carlo's own sample standard deviation.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from pumplink.inputs.pump import load_spec
from pumplink.mechanisms.fourbar import FourBar
from pumplink.studies import builds as bd
from pumplink.studies import tolerance as tl
from pumplink.studies import tolerance_study as ts

VILLAGE = "tests/data/village-first-sized.toml"  # a fixed design: see its header


@pytest.fixture(scope="module")
def village():
    return load_spec(VILLAGE)


@pytest.fixture(scope="module")
def village_problem(village):
    return tl.problem(village, tl.tolerances(0.001), samples=2000)


@pytest.fixture(scope="module")
def village_first_order(village_problem):
    return tl.sensitivities(village_problem)


# ----------------------------------------------------------------------------- the linkage a build is
def _by_hand(nominal, axle, offs: dict) -> dict:
    """Hole positions as 2-D points in each bar's own frame (first hole at the origin, the bar
    along +x), offset by (along, across); the stand's pivots in product coordinates."""

    def point(base, key):
        return np.array([base + offs[key, "along"], offs[key, "across"]])

    crank = np.linalg.norm(point(nominal.crank, "crank.A") - point(0.0, "crank.O2"))
    coupler = np.linalg.norm(point(nominal.coupler, "coupler.B") - point(0.0, "coupler.A"))
    o4, b, grip = (
        point(0.0, "rocker.O4"),
        point(nominal.rocker, "rocker.B"),
        point(nominal.handle, "rocker.grip"),
    )
    rocker = np.linalg.norm(b - o4)
    handle = np.dot(grip - o4, (b - o4) / rocker)  # the grip measured along the rocker O4 -> B
    o2_stand = np.array([offs["stand.O2", "x"], offs["stand.O2", "y"]])
    o4_stand = np.array([nominal.pivot_x + offs["stand.O4", "x"], nominal.pivot_y + offs["stand.O4", "y"]])
    pivot = o4_stand - o2_stand
    return dict(
        crank=crank, coupler=coupler, rocker=rocker, handle=handle, pivot_x=pivot[0], pivot_y=pivot[1],
        axle=axle + offs["stand.O2", "y"],
    )  # fmt: skip


@settings(max_examples=30)  # 30 random builds: each checks all seven parameters; cheap
@given(st.lists(st.floats(-0.005, 0.005), min_size=18, max_size=18))
def test_a_build_is_the_linkage_between_its_holes(values):
    nominal = FourBar(-1.048, -0.307, 0.0484, 1.0659, 0.123, 0.897, -1.0)
    offs = dict(zip(bd.DIMENSIONS, values))
    lk, axle = bd.build(nominal, 0.574, np.array([values]))
    want = _by_hand(nominal, 0.574, offs)
    got = dict(
        crank=lk.crank[0], coupler=lk.coupler[0], rocker=lk.rocker[0], handle=lk.handle[0],
        pivot_x=lk.pivot_x[0], pivot_y=lk.pivot_y[0], axle=axle[0],
    )  # fmt: skip
    for k in want:
        assert got[k] == pytest.approx(want[k], abs=1e-15), k
    assert lk.branch[0] == -1.0


def test_the_first_order_map_is_the_derivative_of_the_build():
    nominal = FourBar(-1.048, -0.307, 0.0484, 1.0659, 0.123, 0.897, -1.0)
    h = 1e-7
    eye = np.eye(18) * h
    up, axle_up = bd.build(nominal, 0.574, eye)
    down, axle_down = bd.build(nominal, 0.574, -eye)
    fd = np.array(
        [(getattr(up, p) - getattr(down, p)) / (2 * h) for p in bd.PARAMETERS[:-1]]
        + [(axle_up - axle_down) / (2 * h)]
    )
    assert np.allclose(fd, bd.first_order_map(), atol=1e-7)


# ----------------------------------------------------------------------------- the builds
def test_a_builds_dimensions_do_not_depend_on_how_many_are_drawn(village):
    """Builds are drawn per fixed chunk from the seed and the chunk's number: the first 1,500 of
    2,500 builds are the 1,500 builds of a run of 1,500."""
    small = tl.problem(village, tl.tolerances(0.001), samples=1500, seed=3)
    large = tl.problem(village, tl.tolerances(0.001), samples=2500, seed=3)
    a = np.concatenate([tl.offsets(small, *t) for t in small.chunks])
    b = np.concatenate([tl.offsets(large, *t) for t in large.chunks])
    assert [t[1:] for t in large.chunks] == [(0, 1000), (1000, 2000), (2000, 2500)]
    assert np.array_equal(a, b[:1500])
    ra = ts.summarize(small, ts.run_chunks(small), keep=True)
    rb = ts.summarize(large, ts.run_chunks(large), keep=True)
    assert np.array_equal(ra.values["peak_force"], rb.values["peak_force"][:1500])


#: Standard errors allowed between a statistic of the draws and its exact value: a two-sided
#: normal tail of 4 standard errors has probability 6.3e-5, so a correct sampler fails a check one
#: seed in about 16,000 (the seed is fixed: the draws, and so the outcome, never change).
SE = 4.0


@pytest.mark.parametrize("distribution", ["uniform", "normal"])
def test_offsets_follow_the_distribution(village, distribution):
    """Uniform: within ±t, σ = t/√3; normal: σ = t/3 (t = 3σ), not cut off at t.

    360,000 draws (20,000 builds x 18 dimensions, seed 0).  The sample σ's standard error is
    σ sqrt((κ - 1) / 4n) with κ the kurtosis (normal 3: 0.118 % of σ; uniform 1.8: 0.075 %); the
    share of normal draws beyond t = 3σ is 2 Φ(-3) = 0.2700 % with the binomial standard error
    sqrt(p (1 - p) / n) = 0.0087 %; each is held to :data:`SE` standard errors.  The largest normal
    draw: P(max |x| > 6.5σ) = 1 - (1 - 2 Φ(-6.5))^n = 2.9e-5 and P(max |x| < 4σ) = (1 - 2 Φ(-4))^n
    = 1e-10 (a sampler cut at ±t = 3σ fails it)."""
    prob = tl.problem(village, tl.tolerances(0.002, distribution=distribution), samples=20_000, seed=0)
    assert np.all(prob.tolerances.per_dimension == 0.002)
    offs = np.concatenate([tl.offsets(prob, *t) for t in prob.chunks]).ravel()
    n = offs.size
    assert n == 360_000
    if distribution == "uniform":
        sigma, kurtosis = 0.002 / math.sqrt(3), 1.8
        assert np.abs(offs).max() <= 0.002
    else:
        sigma, kurtosis = 0.002 / 3, 3.0
        beyond = 2 * 0.5 * math.erfc(3 / math.sqrt(2))  # 2 Φ(-3)
        share = float(np.mean(np.abs(offs) > 0.002))
        assert abs(share - beyond) <= SE * math.sqrt(beyond * (1 - beyond) / n), share
        assert 4.0 * sigma <= np.abs(offs).max() <= 6.5 * sigma
    assert abs(np.std(offs) / sigma - 1) <= SE * math.sqrt((kurtosis - 1) / (4 * n))


@pytest.mark.parametrize("distribution", ["uniform", "normal"])
def test_the_monte_carlo_spread_at_a_small_tolerance_is_the_first_order_spread(village, distribution):
    """±0.1 mm on every hole and pivot: the builds' standard deviation of the peak and the mean
    force is the first-order σ = sqrt(Σ (∂F/∂x_j σ_j)²) within 3 % (8,000 builds: the sample
    σ's own standard error is ~1/sqrt(2n) = 0.8 %, the curvature over 0.1 mm far less)."""
    tol = tl.tolerances(0.0001, distribution=distribution)
    prob = tl.problem(village, tol, samples=8000)
    res = ts.summarize(prob, ts.run_chunks(prob))
    fo = res.first_order
    for key, gradient in (("peak_force", fo.peak_force), ("mean_force", fo.mean_force)):
        predicted = fo.spread(gradient, tol)
        assert res.spread[key].std == pytest.approx(predicted, rel=0.03), key
        assert predicted > 0.05  # not a vacuous comparison of two zeros
    assert res.passed.value == 1.0  # 2.4 N of margin, σ ≈ 0.19 N


def test_holes_across_a_bar_do_nothing_to_first_order(village_first_order):
    fo = village_first_order
    for j, (key, axis) in enumerate(bd.DIMENSIONS):
        if axis == "across":
            assert abs(fo.peak_force[j]) < 1e-6, key
        else:
            assert abs(fo.peak_force[j]) > 1.0, key  # every other dimension moves the peak force


def test_the_search_route_of_the_first_order_share_is_the_reports(village, village_first_order):
    """The searches' first-order share (forward differences in the six linkage parameters, mapped
    onto the holes) equals the report's (central differences in the 18 dimensions)."""
    from pumplink.evaluate import evaluate

    tol = tl.tolerances(0.001)
    prob = tl.problem(village, tol)
    ev = evaluate(prob.designs, ("verdict", "water"), fitted=True)  # as the searches judge it
    fast = tl.first_order_shares(prob.designs, ev, tol, strict=False)
    assert fast[0] == pytest.approx(village_first_order.share(tol), abs=2e-4)


# ----------------------------------------------------------------------------- the share
@pytest.mark.parametrize("count, n", [(8, 10), (0, 50), (950, 1000), (100_000, 100_000)])
def test_the_share_interval_is_wilsons(count, n):
    z = 1.959963984540054  # Φ⁻¹(0.975)
    p = count / n
    centre = (p + z * z / (2 * n)) / (1 + z * z / n)
    half = z / (1 + z * z / n) * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n))
    s = ts.share(count, n)
    assert s.value == p
    assert s.low == pytest.approx(max(0.0, centre - half), abs=1e-12)
    assert s.high == pytest.approx(min(1.0, centre + half), abs=1e-12)


@settings(max_examples=200, deadline=None)
@given(n=st.integers(1, 200_000), at=st.floats(0.0, 1.0), confidence=st.sampled_from([0.9, 0.95, 0.99]))
def test_the_share_interval_is_scipys_to_the_bit(n, at, confidence):
    """The interval is computed as scipy.stats.binomtest's Wilson interval (not imported by the
    command: its start-up), with the same operations: the JSON prints every bit of it."""
    from scipy.stats import binomtest

    count = round(at * n)
    ci = binomtest(count, n).proportion_ci(confidence, method="wilson")
    s = ts.share(count, n, confidence)
    assert (s.low, s.high) == (float(ci.low), float(ci.high))


# ----------------------------------------------------------------------------- the allocation
def test_the_allocation_is_the_loosest_ladder_that_keeps_the_target(village_first_order):
    fo = village_first_order
    a = tl.allocate(fo, 0.95)
    assert a.found and a.share >= 0.95
    assert all(t in tl.LADDER for t in a.groups)
    for g, t in enumerate(a.groups):  # one step looser on any group drops below the target
        if t == tl.LADDER[-1]:
            continue
        looser = list(a.holes)
        for k, (key, _, _) in enumerate(bd.HOLES):
            if key in tl.GROUPS[g][1]:
                looser[k] = tl.LADDER[tl.LADDER.index(t) + 1]
        assert fo.share(tl.Tolerances(tuple(looser))) < 0.95, tl.GROUPS[g][0]
    # the crank, whose holes carry 80 % of the spread, is the tightest group
    assert a.groups[0] == min(a.groups) and a.critical[0]


def test_the_allocation_holds_in_the_monte_carlo(village, village_first_order):
    """At the allocated tolerances 95 % of 4,000 builds pass, within the Wilson interval."""
    a = tl.allocate(village_first_order, 0.95)
    prob = tl.problem(village, a.tolerances, samples=4000)
    res = ts.summarize(prob, ts.run_chunks(prob))
    assert res.passed.high >= 0.95


def test_a_design_that_fails_gets_no_allocation(village):
    from pumplink.inputs.pump import parse_spec, spec_to_dict

    data = spec_to_dict(village)
    data["operator"]["force_limit"] = 90.0  # below the design's 97.6 N peak
    fo = tl.sensitivities(tl.problem(parse_spec(data), tl.tolerances(0.001)))
    a = tl.allocate(fo)
    assert not a.found and "fails" in a.reason and fo.binding == "peak_force"


@pytest.mark.parametrize(
    "s2, budget, cap",
    [([4.0, 1.0, 0.25], 1.0, 10.0), ([4.0, 1.0, 1e-6], 1.0, 0.5), ([1.0, 0.0, 1.0], 2.0, 0.1)],
)
def test_equal_effect_shares_the_variance_equally_below_the_cap(s2, budget, cap):
    s2 = np.array(s2)
    sig = tl._equal_effect(s2, budget, cap)
    assert np.all(sig <= cap + 1e-15)
    var = s2 * sig**2
    free = (s2 > 0) & (sig < cap)
    if free.any():
        assert np.sum(var) == pytest.approx(budget**2)
        assert np.allclose(var[free], var[free][0])
    assert np.all(sig[s2 == 0] == cap)  # a hole that moves nothing takes the top of the ladder
