"""The one-point float routes of the ODE right-hand sides against the array routes they mirror.

``dynamics_terms.point_terms`` (the links' I, I', V, V', g and Px at one crank angle, on floats with
``math``) runs the same :func:`pumplink.models.dynamics_terms.terms_from` as ``dynamics_terms.terms`` does on
arrays; ``dynamics._profile_at`` (the reported motion's energy, regime and force at one angle, the
right-hand side of ``integrate_motion``) is a float twin of ``dynamics._profile``.  The expected
values here are the array routes' (numpy on many angles at once), so the twins cannot drift apart:
agreement is asked to 1e-13 of each quantity's range over a turn (they agree bit for bit on this
machine; the margin is for a platform whose numpy and C library round sin, cos or pow apart).
"""

import math
import pathlib

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from pumplink.inputs.pump import load_spec
from pumplink.mechanisms.fourbar import FourBar, synthesize
from pumplink.models import dynamics as dy
from pumplink.models import dynamics_terms as dt
from pumplink.studies.force import design

ROOT = pathlib.Path(__file__).resolve().parents[2]
SPECS = ["examples/well-12m-flywheel.toml", "configs/women-operators-6m.toml", "configs/village-10m.toml"]
RTOL = 1e-13


def _close(got, want, scale):
    """|got - want| <= RTOL * scale elementwise, NaN where the other is NaN."""
    got, want = np.asarray(got, float), np.asarray(want, float)
    assert np.array_equal(np.isnan(got), np.isnan(want))
    ok = ~np.isnan(want)
    assert np.all(np.abs(got[ok] - want[ok]) <= RTOL * scale)


@settings(max_examples=60, deadline=None)  # 60 designs x 200 angles: each design ~0.01 s
@given(
    geometry=st.tuples(st.floats(0.2, 0.6), st.floats(0.0, 0.4), st.floats(0.12, 0.3), st.floats(50.0, 80.0)),
    mass_per_length=st.floats(0.0, 3.0),
    arms=st.floats(0.0, 6.0),
    seed=st.integers(0, 2**32 - 1),
)
def test_point_terms_equal_the_array_terms(geometry, mass_per_length, arms, seed):
    """All seven outputs of the float route at 200 random angles (several turns either way) equal
    the array route's on the same angles at once."""
    reach, depth, rocker, swing = geometry
    syn = synthesize(reach, depth, 0.0, rocker, math.radians(swing), 1.1)
    assume(syn.feasible)
    lk = syn.linkage
    masses = dt.bar_masses(lk, mass_per_length, arms)
    th = np.random.default_rng(seed).uniform(-20.0, 40.0, 200)
    with np.errstate(all="ignore"):
        want = dt.terms_from(dt.coefficients(lk, masses), th, 9.80665, fly_x=True)
    at = dt.point_terms(lk, masses, 9.80665)
    got = np.array([at(t, fly_x=True) for t in th]).T
    for g, w in zip(got, want, strict=True):
        _close(g, w, max(np.nanmax(np.abs(w)), 1e-300))


def test_point_terms_give_nan_where_the_linkage_does_not_assemble():
    """A coupler too short to close the loop at some angles: the float route's square root of a
    negative number falls back to numpy, NaN where the array route gives NaN (and equal elsewhere)."""
    lk = FourBar(0.5, 0.3, 0.2, 0.3, 0.25, 0.9, 1.0)
    masses = dt.bar_masses(lk, 1.56, 2.0)
    th = np.linspace(0.0, 2 * np.pi, 73)
    want = dt.terms(lk, th, masses)
    assert np.isnan(want.inertia).any() and not np.isnan(want.inertia).all()  # the case is a mixed one
    at = dt.point_terms(lk, masses)
    got = np.array([at(t)[:6] for t in th]).T
    for g, w in zip(
        got, (want.inertia, want.inertia_rate, want.potential, want.potential_rate), strict=False
    ):
        _close(g, w, np.nanmax(np.abs(w)))


@pytest.fixture(scope="module", params=SPECS)
def scene(request):
    spec = load_spec(ROOT / request.param)
    syn = design(spec).synthesis
    lk = syn.linkage
    masses = dt.bar_masses(lk, 1.56, 4.0)
    args = (lk, syn.dead_centre_extended, syn.dead_centre_folded, spec.wheel_torque, spec.inertia, masses)
    return dy.scene(*args, 2 * np.pi, 0.2)


def test_profile_at_one_angle_equals_the_array_profile(scene):
    """Energy, regime, upper rate, V, I, g, I' and V' of the float route against ``_profile`` on
    random angles over several turns, angles within the travel-integration arc of both dead
    centres, and the refined points themselves (where the past/future minima switch sides)."""
    sc = scene
    rng = np.random.default_rng(7)
    dce, dcf = sc.dead_centre_extended, sc.dead_centre_folded
    x = sc.points[0] + dce
    th = np.concatenate(
        [
            rng.uniform(-15.0, 40.0, 1500),
            dce + rng.uniform(-0.03, 0.03, 300),
            dcf + rng.uniform(-0.03, 0.03, 300),
            [dce, dcf, dce + 2 * np.pi],
            x,
            np.nextafter(x, np.inf),
            np.nextafter(x, -np.inf),
        ]
    )
    e, reg, dup, v, i, g, tm = dy._profile(sc, th)
    at = dy._profile_at(sc)
    got = [at(t) for t in th]
    assert [r for _e, r, *_ in got] == list(reg)
    for k, want in ((0, e), (2, dup), (3, v), (4, i), (5, g)):
        _close([row[k] for row in got], want, np.nanmax(np.abs(want)))
    for k, want in ((1, tm.inertia_rate), (3, tm.potential_rate)):
        _close([row[6][k] for row in got], want, np.nanmax(np.abs(want)))


def test_integration_right_hand_side_uses_the_reported_force(scene):
    """The force the time integration applies (``_force_at`` on the float profile) is
    ``operator_force`` on arrays, pushing and riding the top of the band, and at both dead centres
    (F = 0 where g = 0)."""
    sc = scene
    th = np.concatenate(
        [
            np.random.default_rng(3).uniform(0.0, 4 * np.pi, 600),
            [sc.dead_centre_extended, sc.dead_centre_folded],
        ]
    )
    at = dy._profile_at(sc)
    got = [dy._force_at(sc, *at(t)[1:]) for t in th]
    want = dy.operator_force(sc, th)
    assert {0, 1} <= set(dy.regime(sc, th).tolist())  # pushes and rides seen
    _close(got, want, sc.least_peak_force)
