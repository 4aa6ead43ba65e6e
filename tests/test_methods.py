"""Stability and accuracy of the force methods (methods comparison), and the `methods` command.

Ground truth is the independent 50-digit reference of ``tests/reference.py`` (Freudenstein form
of the loop closure, rate by implicit differentiation, derived from docs/physics.md only) at the
same double crank angles, and its 50-digit dead centres.  The product's own ``reference`` method
is one of the methods under test here.

The allowed errors are written below (:func:`allowed`) from how each method computes the force,
as a function of the distance delta to the nearest dead centre (where the force's denominator,
the grip's rate, vanishes like delta); they are not read from the product's registry, whose
promises (``Method.tolerance``) are checked against them separately.
"""

from __future__ import annotations

import json
import math
import subprocess
import sys
import warnings

import numpy as np
import pytest
import reference as R
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from pumplink.evaluate import pump_designs
from pumplink.inputs.pump import default_spec, spec_values
from pumplink.mechanisms.angles import angular_distance
from pumplink.mechanisms.fourbar import synthesize
from pumplink.studies import accuracy
from pumplink.studies.force import design
from pumplink.studies.methods import (
    CRANK_ALONG_FRAME,
    CRANK_PARALLEL_ROCKER,
    CRANK_PERPENDICULAR,
    DANGER_KINDS,
    DEAD_CENTRE,
    METHODS,
    NEAR_DEAD_CENTRE,
    ROCKER_PERPENDICULAR,
    UNIFORM,
    danger_points,
    paper,
    paper_seed_coordinates,
    reference,
    seed_frame,
    vector,
)

EPS = np.finfo(float).eps


def allowed(name: str, kind: str, delta):
    """Relative force error ``name`` is known to achieve at ``delta`` [rad] from the nearest dead
    centre, near a point of ``kind``.  Each term is a rounding or step error of the method over
    the rate, which vanishes like delta; measured worst cases (200 random designs of
    :func:`designs`, all kinds, against ``tests/reference.py``) in brackets.

    * vector: closed-form positions and the analytic velocity ratio carry a few eps of the link
      angles, relative to a rate ~ delta: 64 eps (1 + 1/delta) [17 eps/delta].
    * paper: Eq. (6)'s quadratic has coefficients of order l^8 whose differences lose about five
      digits: 1e6 eps (1 + 1/delta) [1.1e5 eps/delta].  Next to the crank along the frame line
      its two roots merge and B keeps half the digits: 8 sqrt(eps) (1 + 1/delta) [1.3 sqrt(eps)/delta].
    * numeric: fsolve's grip positions (converged to ~1e-14 m) differenced over 2 h = 2e-5 rad
      (h = pumplink.studies.methods.NUMERIC_STEP), plus the h^2 ~ 1e-10 truncation: 4e-9 (1 + 1/delta)
      [1e-9/delta].
    * reference (the product's 50-digit route): its doubles are rounded once, then the grip rate and
      the force take a few roundings of their own: 8 eps.
    """
    delta = np.asarray(delta, float)
    if name == "vector":
        return 64 * EPS * (1 + 1 / delta)
    if name == "paper":
        return (8 * math.sqrt(EPS) if kind == CRANK_ALONG_FRAME else 1e6 * EPS) * (1 + 1 / delta)
    if name == "numeric":
        return 4e-9 * (1 + 1 / delta)
    if name == "reference":
        return np.full(delta.shape, 8 * EPS)
    raise KeyError(name)


@st.composite
def designs(draw, rocker_perpendicular=False):
    """Feasible pump designs with a crank-rocker of transmission angle >= 5 deg from a change point.

    Drawn feasible directly: with reach = L1 + b/2, the swing stays clear of the frame line and
    its extension iff |D1| < reach cot(swing/2) (Eq. 2, docs/physics.md), so D1 is drawn in that
    part of its range.  ``rocker_perpendicular``: also |D1| < reach tan(swing/2), where the rocker
    passes through the normal to the frame line (one of :data:`DANGER_KINDS`)."""
    L1 = draw(st.floats(0.05, 1.0))
    b = draw(st.floats(0.0, 0.3))
    rocker = draw(st.floats(0.08, 0.6))
    swing = np.radians(draw(st.floats(15.0, 110.0)))
    handle = draw(st.floats(0.4, 1.5))
    reach = L1 + b / 2
    limit = reach * math.tan(0.5 * math.pi - 0.5 * swing - 1e-5)  # 1e-5 rad inside (change-point margin)
    if rocker_perpendicular:
        limit = min(limit, reach * math.tan(0.5 * swing - 1e-5))
    D1 = draw(st.floats(max(-0.4, -limit), min(0.6, limit)))
    syn = synthesize(L1, D1, b, rocker, swing, handle)
    assert syn.feasible
    assume(min(syn.transmission_min, np.pi - syn.transmission_max) > np.radians(5.0))  # 7 % of draws
    return syn


def _truth(syn, angles, wheel_torque):
    """50-digit force of ``tests/reference.py`` at the given double angles, and each angle's
    distance to the nearest 50-digit dead centre [rad] (the reference's rate numerator polished
    to a root from each of pumplink's dead centres: faster than the reference's own scan)."""
    import mpmath

    lk = R.from_synthesis(syn)
    force = np.array([float(R.force(lk, float(t), wheel_torque)) for t in np.ravel(angles)])
    dcs = []
    with mpmath.workdps(R.DPS):
        for guess in (syn.dead_centre_extended, syn.dead_centre_folded):
            root = mpmath.findroot(lambda t: R.state(lk, t)["rate_numerator"], mpmath.mpf(float(guess)))
            assert abs(root - float(guess)) < 1e-9  # the same dead centre
            dcs.append(root)
        delta = np.min(
            [[float(abs(R._wrap(mpmath.mpf(float(t)) - d))) for t in np.ravel(angles)] for d in dcs], 0
        )
    return force.reshape(np.shape(angles)), delta.reshape(np.shape(angles))


def _rel(a, b):
    return np.abs(np.asarray(a) - b) / np.abs(b)


def test_reference_matches_hand_derivation_at_a_dead_centre_neighbour():

    # Independent check of the reference: at crank angle t the rocker tip B satisfies both circle
    # equations (|B - A| = l3, |B - O4| = l4) to 40 digits, and omega4/omega2 equals a central
    # difference of its rocker angle taken at 50 digits (step 1e-20).
    import mpmath as mp

    syn = design(default_spec()).synthesis
    lk = syn.linkage
    t = 1.234
    r0 = reference(lk, np.array([t]), 1.0)
    ax, ay = lk.crank * np.cos(t), lk.crank * np.sin(t)
    assert abs(np.hypot(r0.coupler_x[0] - ax, r0.coupler_y[0] - ay) - lk.coupler) < 1e-15
    assert abs(np.hypot(r0.coupler_x[0] - lk.pivot_x, r0.coupler_y[0] - lk.pivot_y) - lk.rocker) < 1e-15
    with mp.workdps(50):

        def rocker(th):
            px, py, c, k, r = (
                mp.mpf(float(v)) for v in (lk.pivot_x, lk.pivot_y, lk.crank, lk.coupler, lk.rocker)
            )
            dx, dy = c * mp.cos(th) - px, c * mp.sin(th) - py
            d = mp.sqrt(dx * dx + dy * dy)
            base, off = mp.atan2(dy, dx), mp.acos((r * r + d * d - k * k) / (2 * r * d))
            cands = [base + off, base - off]
            tip = mp.atan2(mp.mpf(r0.coupler_y[0]) - py, mp.mpf(r0.coupler_x[0]) - px)
            return min(cands, key=lambda a: abs(mp.sin((a - tip) / 2)))

        h = mp.mpf("1e-20")
        rate = (rocker(mp.mpf(t) + h) - rocker(mp.mpf(t) - h)) / (2 * h)
        grip_rate = -float(mp.mpf(lk.handle) * mp.sin(rocker(mp.mpf(t))) * rate)
    assert abs(r0.handle_rate[0] / grip_rate - 1) < 1e-14


# ~0.2 s each (50-digit truth at up to 10 angles); 25 designs over the 6-parameter box, with
# the 24 x 10 of the danger-point test below
@settings(max_examples=25, deadline=None)
@given(designs(), st.floats(1.0, 179.0), st.sampled_from([-1.0, 1.0]))
def test_vector_meets_item4_targets(syn, away_deg, side):
    """Production path: within :func:`allowed` (below the targets: 1e-12 at >= 1 deg from both
    dead centres, 1e-6 at 1e-6 deg), NaN + singular exactly at the dead centres, finite and exact
    at the paper's danger points, and no warnings."""
    lk = syn.linkage
    dc = np.array([syn.dead_centre_extended, syn.dead_centre_folded])
    far = dc + side * np.radians(away_deg)
    far = far[(angular_distance(far[:, None], dc[None, :]) >= np.radians(1.0)).all(axis=1)]
    near = np.concatenate([dc + np.radians(1e-6), dc - np.radians(1e-6)])
    pts = danger_points(lk)
    danger = np.concatenate([pts[k] for k in DANGER_KINDS])
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        for angles, target in ((far, 1e-12), (near, 1e-6), (danger, 1e-12)):
            if angles.size == 0:
                continue
            got = vector(lk, angles, 7.0)
            truth, delta = _truth(syn, angles, 7.0)
            assert np.all(np.isfinite(got.force)) and not got.singular.any()
            err = _rel(got.force, truth)
            assert np.all(err <= np.minimum(allowed("vector", UNIFORM, delta), target)), (angles, err)
            assert np.all(np.sign(got.force) == np.sign(truth))
        at = vector(lk, dc, 7.0)
        assert at.singular.all() and np.isnan(at.force).all() and np.isfinite(at.grip_x).all()


def _danger_angles(draw, syn, kind):
    lk = syn.linkage
    if kind == NEAR_DEAD_CENTRE or kind == DEAD_CENTRE:
        base = np.array([syn.dead_centre_extended, syn.dead_centre_folded])
    else:
        base = danger_points(lk)[kind]
    assert base.size > 0, kind  # designs() draws the rocker-perpendicular ones where it gets there
    if kind == DEAD_CENTRE:
        return base
    if kind == NEAR_DEAD_CENTRE:
        exps = draw(st.lists(st.floats(-6.0, 0.0), min_size=1, max_size=3))
        offs = np.radians(10.0 ** np.array(exps))
    else:
        exps = draw(st.lists(st.floats(-15.0, -3.0), min_size=1, max_size=3))
        offs = np.concatenate([[0.0], 10.0 ** np.array(exps)])
    return (base[:, None] + np.concatenate([offs, -offs])[None, :]).ravel()


@pytest.mark.parametrize("name", ["vector", "paper", "numeric", "reference"])
@pytest.mark.parametrize(
    "kind",
    [
        NEAR_DEAD_CENTRE,
        DEAD_CENTRE,
        CRANK_PERPENDICULAR,
        ROCKER_PERPENDICULAR,
        CRANK_PARALLEL_ROCKER,
        CRANK_ALONG_FRAME,
    ],
)
# ~60 ms each (up to 16 angles at 50 digits); 10 designs per method and kind, 240 in all
@settings(max_examples=10, deadline=None)
@given(data=st.data())
def test_registered_capabilities_hold_at_danger_points(name, kind, data):
    """Each method does what its registry entry says at its danger points: where it declares
    'flags' it either flags (NaN + failed/singular) or returns a value within :func:`allowed`;
    where it declares 'exact'/'accurate' it returns a value within :func:`allowed`.  Never
    garbage, never a warning.  And every tolerance the registry promises is met."""
    syn = data.draw(designs(rocker_perpendicular=kind == ROCKER_PERPENDICULAR))
    m = METHODS[name]
    angles = _danger_angles(data.draw, syn, kind)
    if name in ("numeric", "reference"):
        angles = angles[:4]  # a few points: these routes cost ~0.4 ms each
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        got = m.function(syn.linkage, angles, 3.0)
    truth, delta = _truth(syn, angles, 3.0)
    flagged = got.failed | got.singular
    assert np.all(np.isnan(got.force[flagged]))
    ok = ~flagged
    assert np.all(np.isfinite(got.force[ok]))
    err = _rel(got.force[ok], truth[ok])
    assert np.all(err <= allowed(name, kind, delta[ok])), (name, kind, angles[ok], err, delta[ok])
    # a danger point within 1 deg of a dead centre (the range of the near-dead-centre points drawn
    # by _danger_angles) is also a near-dead-centre point: the weaker of the two promises governs
    # there (a rocker perpendicular at 1e-5 rad of its swing's end sits 0.4 deg from a dead centre)
    dead = np.array([syn.dead_centre_extended, syn.dead_centre_folded])
    gap = np.abs(np.mod(np.asarray(angles)[:, None] - dead[None, :] + np.pi, 2 * np.pi) - np.pi).min(axis=1)
    near = (gap <= np.radians(1.0)) & (kind not in (NEAR_DEAD_CENTRE, DEAD_CENTRE))
    tolerance = np.where(near, max(m.tolerance[kind], m.tolerance[NEAR_DEAD_CENTRE]), m.tolerance[kind])
    assert np.all(err <= tolerance[ok]), (name, kind, angles[ok], err)  # the registry's promise
    promised = {"exact", "accurate"}
    must = np.where(near, m.handles[NEAR_DEAD_CENTRE] in promised, m.handles[kind] in promised)
    assert not got.failed[must].any(), (name, kind, angles[got.failed & must])
    if kind == DEAD_CENTRE and name != "reference":  # a finite force there would be made up
        assert flagged.all()


def test_paper_route_divides_by_zero_exactly_where_registered():
    # xA = 0 (seed angle 0: crank normal to the frame line) makes tA infinite; the route returns
    # a non-finite ratio there, and `paper` flags the equivalent product angle.
    syn = design(default_spec()).synthesis
    lk = syn.linkage
    l1 = float(np.hypot(lk.pivot_x, lk.pivot_y))
    with np.errstate(all="ignore"):
        out = paper_seed_coordinates(l1, lk.crank, lk.coupler, lk.rocker, np.array([0.0, -0.0]), 1.0)
    assert not np.isfinite(out[6]).any()
    _, ex, ey = seed_frame(lk)
    theta = np.arctan2(ey[1], ey[0])  # crank along e_y: seed angle 0
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        got = paper(lk, np.array([theta]), 1.0)
    truth, delta = _truth(syn, np.array([theta]), 1.0)
    assert got.failed[0] or _rel(got.force[0], truth[0]) <= allowed("paper", CRANK_PERPENDICULAR, delta[0])


def test_seed_plus_root_is_the_assembly_branch_for_half_the_cycle_only():
    # The seed prints xB = (-b + sqrt(b^2 - 4ac)) / 2a.  Against the reference's B, that root is
    # right only where the assembly branch and the sign of yA agree (pumplink.studies.methods.paper).
    syn = design(default_spec()).synthesis
    lk = syn.linkage
    th = np.linspace(0.0, 2 * np.pi, 73)[:-1] + 0.01
    l1, ex, ey = seed_frame(lk)
    cs, sn = np.cos(th), np.sin(th)
    seed_angle = np.arctan2(cs * ex[0] + sn * ex[1], cs * ey[0] + sn * ey[1])
    xa, ya, xb, yb, *_ = paper_seed_coordinates(l1, lk.crank, lk.coupler, lk.rocker, seed_angle, 1.0)
    ref_lk = R.from_synthesis(syn)
    bx, by = np.array([[float(R.state(ref_lk, float(t))[k]) for k in ("bx", "by")] for t in th]).T
    rx = bx * ex[0] + by * ex[1]
    right = np.abs(xb - rx) < 1e-9
    assert 0.3 < right.mean() < 0.7
    handed = ex[0] * ey[1] - ex[1] * ey[0]
    assert np.all(right == (handed * lk.branch * ya > 0))


def test_sampling_study_converges_and_never_overshoots():
    rows = accuracy.sampling_study(pump_designs(spec_values(default_spec())))
    for r in rows:
        assert r["sampled_peak"] <= r["exact_peak"] * (1 + 1e-12)  # samples are points of the window
        assert r["sampled_max"] >= r["sampled_peak"]
    # grip travel converges like the square of the step: 10x the samples, >= 50x smaller error
    assert rows[-1]["mean_error"] < rows[-2]["mean_error"] / 50
    assert rows[-1]["mean_error"] < 1e-6


def _run(*args, pre=""):
    code = pre + "import sys; from pumplink.cli import main; sys.argv = ['pumplink', *sys.argv[1:]]; main()"
    return subprocess.run([sys.executable, "-c", code, *args], capture_output=True, text=True, timeout=120)


def test_methods_command_json_and_charts(tmp_path):
    import figures

    png, svg = tmp_path / "m.png", tmp_path / "s.svg"
    r = _run(
        "methods",
        "--format",
        "json",
        "--repeats",
        "1",
        "--samples",
        "72",
        "--plot",
        str(png),
        "--samples-plot",
        str(svg),
        pre=figures.PRE,
    )
    assert r.returncode == 0, r.stderr
    obj = json.loads(r.stdout)
    names = [m["name"] for m in obj["methods"]]
    assert names == ["vector", "paper", "numeric", "reference"]
    for m in obj["methods"]:
        assert {
            "name",
            "seconds_per_position",
            "max_rel_error_uniform",
            "max_rel_error_near_dead_centre",
            "failures",
        } <= set(m)
        assert m["seconds_per_position"] > 0
    vec = obj["methods"][0]
    assert vec["max_rel_error_near_dead_centre"] <= 1e-6 and vec["failures"] == []
    assert [row["n"] for row in obj["sampling"]] == [12, 36, 72, 360, 3600]
    assert png.read_bytes()[:4] == b"\x89PNG"
    assert b"<svg" in svg.read_bytes()[:2000]
    # what the charts show: one marker per method and sampling at (time, error) of the JSON ...
    (ax,) = figures.read(png)["axes"]
    assert ax["xscale"] == ax["yscale"] == "log" and ax["texts"] == names
    assert ax["legend"] == ["uniform sweep", "near a dead centre (down to 1e-6 deg)", "danger points"]
    want = sorted(
        (s["seconds_per_position"], max(s["max_rel_error"], 1e-17))
        for m in obj["methods"]
        for s in m["samplings"].values()
        if s["max_rel_error"] is not None
    )
    got = sorted(map(tuple, ax["scatter"]))
    assert len(got) == len(want) and np.allclose(got, want, rtol=1e-12, atol=0)
    # ... and the sampling study's sampled peaks against N, below the exact peak line
    study = figures.read(svg)
    peak, errors = study["axes"]
    sampled = next(ln for ln in peak["lines"] if ln["label"].startswith("sampled peak outside"))
    assert sampled["x"] == [12.0, 36.0, 72.0, 360.0, 3600.0]
    assert sampled["y"] == pytest.approx([row["sampled_peak"] for row in obj["sampling"]], rel=1e-12)
    exact = next(ln for ln in peak["lines"] if ln["label"] == "exact peak outside band")["y"][0]
    assert exact == pytest.approx(obj["sampling"][0]["exact_peak"], rel=1e-12) and max(sampled["y"]) <= exact
    assert errors["title"] == "error of sampled values" and study["suptitle"] == "Prototype"


def test_methods_command_with_named_methods_compares_only_those():
    r = _run(
        "methods",
        "--method",
        "paper",
        "-m",
        "vector",
        "--format",
        "json",
        "--repeats",
        "1",
        "--samples",
        "36",
    )
    assert r.returncode == 0, r.stderr
    obj = json.loads(r.stdout)
    assert [m["name"] for m in obj["methods"]] == ["paper", "vector"]  # in the order asked
    pap, vec = obj["methods"]
    assert vec["failures"] == [] and vec["max_rel_error_uniform"] <= 1e-12
    # the paper's route flags points at its danger points (xA = 0, xB = l1, ...): reported as such
    assert any("flagged" in f for f in pap["failures"])


def test_methods_command_errors(tmp_path):
    r = _run("methods", "--plot", str(tmp_path / "x.jpg"))  # one suffix rule for every chart
    assert r.returncode == 2 and r.stderr.startswith("error: ") and ".png, .svg or .pdf" in r.stderr
    r = _run("methods", "--method", "magic")
    assert r.returncode == 2 and "magic" in r.stderr
    r = _run(
        "methods", "--plot", str(tmp_path / "x.png"), pre="import sys; sys.modules['matplotlib'] = None; "
    )
    assert r.returncode == 2 and "pip install 'pumplink[plot]'" in r.stderr
    assert not (tmp_path / "x.png").exists()


def test_compare_methods_reports_each_step_for_the_progress_bar():
    """``pumplink methods`` shows a progress bar: one step per (reference + method) and sample set,
    ending exactly at the total it announced."""
    d = design(default_spec())
    syn = d.synthesis
    steps = []
    names = ["vector", "paper"]
    rows = accuracy.compare_methods(
        syn.linkage, syn.dead_centre_extended, syn.dead_centre_folded, 1.0, names, 36, 1, steps.append
    )
    n_sets = len(accuracy.sample_sets(syn.linkage, syn.dead_centre_extended, syn.dead_centre_folded, 36))
    assert [r["name"] for r in rows] == names
    assert steps == [1] * ((len(names) + 1) * n_sets)
