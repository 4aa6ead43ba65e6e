"""Optimal-transmission crank-rocker (the optimal-transmission paper): exactness, one-branch arc,
kinematic verification.

Reference values come from independent routes: a 40-digit mpmath golden-section search on the
design circle in the classic centre/angle parametrisation (not the law-of-sines form of
pumplink.mechanisms.crank_rocker), and mpmath evaluations of Eq. (4)-(6) of the optimal-transmission
paper for the paper's designs.
"""

import json
import math
import os
import subprocess
import sys

import mpmath as mp
import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st

from pumplink.errors import SpecError
from pumplink.mechanisms import crank_rocker as cr
from pumplink.mechanisms.crank_rocker import (
    crank_rocker_on_circle,
    extreme_included_angle,
    measure_motion,
    optimal_crank_rocker,
    optimum_linkage,
)
from pumplink.mechanisms.fourbar import FourBar

SEED_K, SEED_PHI, SEED_ROCKER = 1.1818, 40.0, 50.0
# The optimal-transmission paper §3 (crank, coupler, rocker, frame) [mm].
SEED_DIAGRAM = (16.0, 46.0, 50.0, 53.76)
SEED_COMPUTER = (16.2227, 44.5093, 50.0, 53.8986)


def mp_mu(c, k, r, f):
    """min(gamma_min, 180 - gamma_max) [deg] in mpmath, Eq. (4)-(6) of the optimal-transmission paper."""
    c, k, r, f = (mp.mpf(v) for v in (c, k, r, f))
    gmin = mp.acos((k * k + r * r - (f - c) ** 2) / (2 * k * r))
    gmax = mp.acos((k * k + r * r - (f + c) ** 2) / (2 * k * r))
    return mp.degrees(min(gmin, mp.pi - gmax))


def mp_reference(K, phi_deg, r, scan=4000):
    """Best mu over both design circles, parametrised by the angle tau about the circle centre."""
    mp.mp.dps = 40
    K, r = mp.mpf(K), mp.mpf(r)
    th = mp.pi * (K - 1) / (K + 1)
    phi = mp.radians(mp.mpf(phi_deg))
    w, yc = r * mp.sin(phi / 2), r * mp.cos(phi / 2)
    R = w / mp.sin(th)
    best = None
    for sgn in (-1, 1):
        oy = yc + sgn * R * mp.cos(th)

        def design(tau, oy=oy):
            ax, ay = R * mp.cos(tau), oy + R * mp.sin(tau)
            a1 = mp.hypot(ax + w, ay - yc)
            a2 = mp.hypot(ax - w, ay - yc)
            ang = mp.acos(((-w - ax) * (w - ax) + (yc - ay) ** 2) / (a1 * a2))
            s1 = (-w - ax) * (-ay) - (yc - ay) * (-ax)
            s2 = (w - ax) * (-ay) - (yc - ay) * (-ax)
            ok = a2 > a1 and s1 * s2 > 0 and abs(ang - th) < mp.mpf(10) ** -20
            c, k, f = (a2 - a1) / 2, (a2 + a1) / 2, mp.hypot(ax, ay)
            return ok, c, k, f

        def mu(tau):
            ok, c, k, f = design(tau)
            return mp_mu(c, k, r, f) if ok else mp.mpf(-1)

        # half a step off the round angles, where the circle can pass exactly through C1 or C2
        taus = [2 * mp.pi * (i + mp.mpf(0.5)) / scan for i in range(scan)]
        vals = [mu(t) for t in taus]
        j = max(range(scan), key=lambda i: vals[i])
        if vals[j] < 0:
            continue
        a, b = taus[j] - 2 * mp.pi / scan, taus[j] + 2 * mp.pi / scan
        g = (mp.sqrt(5) - 1) / 2
        x1, x2 = b - g * (b - a), a + g * (b - a)
        f1, f2 = mu(x1), mu(x2)
        for _ in range(110):  # golden section: bracket shrinks to ~1e-26 rad
            if f1 > f2:
                b, x2, f2 = x2, x1, f1
                x1 = b - g * (b - a)
                f1 = mu(x1)
            else:
                a, x1, f1 = x1, x2, f2
                x2 = a + g * (b - a)
                f2 = mu(x2)
        tau = (a + b) / 2
        val = mu(tau)
        if best is None or val > best[0]:
            _, c, k, f = design(tau)
            best = (val, c, k, f)
    return best


@pytest.fixture(scope="module")
def seed_opt():
    return optimal_crank_rocker(SEED_K, math.radians(SEED_PHI), SEED_ROCKER)


@pytest.fixture(scope="module")
def seed_ref():
    return mp_reference(SEED_K, SEED_PHI, SEED_ROCKER, scan=1500)


def test_seed_example_matches_high_precision_reference(seed_opt, seed_ref):
    """The optimum is a root of a smooth condition (gamma_min stationary on the arc), not the
    argmax of a flat function: the lengths and gamma_max, read off the optimum, are exact to
    rounding like mu itself (measured: 5e-17 relative; gamma_max 96.8301631305650 deg)."""
    mu_ref, c, k, f = seed_ref
    gmax_ref = mp.degrees(mp.acos((k * k + SEED_ROCKER**2 - (f + c) ** 2) / (2 * k * SEED_ROCKER)))
    assert abs(math.degrees(seed_opt.transmission) - float(mu_ref)) < 1e-12
    assert abs(math.degrees(seed_opt.gamma_min) - float(mu_ref)) < 1e-12
    assert abs(math.degrees(seed_opt.gamma_max) - float(gmax_ref)) < 1e-12
    assert seed_opt.binding == 1  # gamma_min binds, as the paper's example says
    for ours, ref in ((seed_opt.crank, c), (seed_opt.coupler, k), (seed_opt.frame, f)):
        assert abs(ours - float(ref)) < 1e-14 * float(ref)


@pytest.mark.parametrize(("K", "phi"), [(1.03, 15.0), (1.5, 100.0), (2.9, 2.0)])
def test_optimum_lengths_and_gamma_max_are_exact_elsewhere(K, phi):
    """Away from the paper's example too, including a degenerate corner (2 deg swing, K = 2.9,
    mu = 0.07 deg, where the cosines of Eq. 4-5 lose digits to cancellation)."""
    opt = optimal_crank_rocker(K, math.radians(phi), 1.0)
    mu_ref, c, k, f = mp_reference(K, phi, 1.0, scan=1500)
    gmax_ref = mp.degrees(mp.acos((k * k + 1 - (f + c) ** 2) / (2 * k)))
    # measured: 1e-16 relative, 2.5e-14 on the crank at (2.9, 2 deg)
    rel = 1e-14 if phi > 10 else 1e-12
    for ours, ref in ((opt.crank, c), (opt.coupler, k), (opt.frame, f)):
        assert abs(ours - float(ref)) < rel * float(ref)
    assert abs(math.degrees(opt.transmission) - float(mu_ref)) < 1e-10
    assert abs(math.degrees(opt.gamma_max) - float(gmax_ref)) < 1e-10


def test_optimum_does_not_depend_on_the_scan_that_brackets_it():
    """Perturbing the solver's start (the scan that brackets the root: 999 to 4097 points) moves
    the optimum by a few units in the last place, nowhere near the digits printed."""
    k = np.array([1.02, 1.1818, 1.4, 2.0])[:, None]
    phi = np.radians([10.0, 40.0, 90.0, 150.0])[None, :]
    base = optimal_crank_rocker(k, phi, 1.0)
    for n in (999, 1537, 4097):
        other = optimal_crank_rocker(k, phi, 1.0, samples=n)
        for name in ("crank", "coupler", "frame", "gamma_min", "gamma_max", "transmission"):
            a, b = getattr(base, name), getattr(other, name)
            assert np.all(np.abs(a - b) <= 1e-13 * np.abs(a)), (name, n, np.max(np.abs(a - b) / a))


@settings(max_examples=60, deadline=None)  # ~3 ms each: many designs for a claim about all of them
@given(
    K=st.floats(1.001, 30.0),
    phi=st.floats(0.5, 179.5),
    tau=st.lists(st.floats(0.0, 2 * math.pi), min_size=50, max_size=50),
)
@example(K=3.0, phi=0.95, tau=[0.0] * 50)  # every point on a chord's end
def test_which_extreme_binds_is_fixed_on_each_arc(K, phi, tau):
    """The claim the product's root finder rests on (``pumplink.mechanisms.crank_rocker``
    docstring): at every admissible point of the design circle, gamma_min < 180 deg - gamma_max
    on the rocker-pivot side of the chord and gamma_min > 180 deg - gamma_max beyond it, where
    admissible points exist only for theta + phi < 180 deg.  Checked on points of both circles
    in the centre/angle parametrisation of ``mp_reference`` with Eq. (4)-(5) in plain floats
    (not the product's formulas)."""
    th, ph = float(extreme_included_angle(K)), math.radians(phi)
    w, yc = math.sin(ph / 2), math.cos(ph / 2)
    R = w / math.sin(th)
    t = np.asarray(tau)
    for sgn in (-1, 1):
        ax, ay = R * np.cos(t), yc + sgn * R * math.cos(th) + R * np.sin(t)
        a1, a2 = np.hypot(ax + w, ay - yc), np.hypot(ax - w, ay - yc)
        # tau = 0 or pi puts the point on a chord's end (a1 or a2 = 0: 0/0): not an admissible point,
        # and the NaN it gives fails every comparison of ``ok`` below
        with np.errstate(invalid="ignore", divide="ignore"):
            cosang = ((-w - ax) * (w - ax) + (yc - ay) ** 2) / (a1 * a2)
        s1 = (-w - ax) * (-ay) - (yc - ay) * (-ax)
        s2 = (w - ax) * (-ay) - (yc - ay) * (-ax)
        ok = (s1 * s2 > 0) & (np.abs(cosang - math.cos(th)) < 1e-9) & (np.abs(a2 - a1) > 1e-9)
        c, k, f = np.abs(a2 - a1) / 2, (a2 + a1) / 2, np.hypot(ax, ay)
        both = (k * k + 1 - (f - c) ** 2) / (2 * k) + (k * k + 1 - (f + c) ** 2) / (2 * k)  # cos + cos
        near = ay < yc  # the crank pivot on the rocker pivot's side of the chord
        decided = ok & (np.abs(both) > 1e-9)  # it vanishes only at the arc's ends
        assert np.all(both[decided & near] > 0) and np.all(both[decided & ~near] < 0), (K, phi)
        assert not np.any(ok & ~near) or th + ph < math.pi


def test_the_stationarity_root_is_where_that_extreme_is_stationary():
    """``stationarity`` for gamma_min and for gamma_max: at each of its roots on the admissible
    arcs the slope of that extreme along the design circle, an mpmath central difference of Eq. (4)
    / (5) in the centre/angle parametrisation of ``mp_reference`` (not the product's delta), is 0."""
    from scipy.optimize import brentq

    K, phi = 1.4, math.radians(60.0)
    th = float(extreme_included_angle(K))
    grid = np.linspace(1e-6, 0.5 * math.pi - 0.5 * th - 1e-6, 4001)
    for extreme in (cr.GAMMA_MIN, cr.GAMMA_MAX):
        found = 0
        for side in (-1.0, 1.0):
            g = cr.stationarity(grid, th, phi, 1.0, side, extreme)
            ok = cr.crank_rocker_at_delta(grid, th, phi, 1.0, side)[5]
            for i in np.nonzero(ok[:-1] & ok[1:] & (np.sign(g[:-1]) != np.sign(g[1:])))[0]:
                d = brentq(cr.stationarity, grid[i], grid[i + 1], args=(th, phi, 1.0, side, extreme))
                _, _, _, ax, ay, _ = cr.crank_rocker_at_delta(d, th, phi, 1.0, side)
                assert abs(_mp_slope(K, phi, ax, ay, extreme)) < 1e-10
                found += 1
        assert found, extreme


def _mp_slope(K, phi, ax, ay, binding):
    """d gamma / d tau at the crank pivot (ax, ay), tau the angle about the design circle's centre
    (as in ``mp_reference``), by a 40-digit central difference; [rad/rad]."""
    mp.mp.dps = 40
    th = mp.pi * (mp.mpf(K) - 1) / (mp.mpf(K) + 1)
    w, yc = mp.sin(mp.mpf(phi) / 2), mp.cos(mp.mpf(phi) / 2)
    R = w / mp.sin(th)
    oy = min((yc + s * R * mp.cos(th) for s in (-1, 1)), key=lambda o: abs(mp.hypot(ax, ay - o) - R))
    tau0 = mp.atan2(mp.mpf(float(ay)) - oy, mp.mpf(float(ax)))

    def gamma(tau):
        px, py = R * mp.cos(tau), oy + R * mp.sin(tau)
        a1, a2 = mp.hypot(px + w, py - yc), mp.hypot(px - w, py - yc)
        c, k, f = (a2 - a1) / 2, (a2 + a1) / 2, mp.hypot(px, py)
        e = f - c if binding == cr.GAMMA_MIN else f + c
        return mp.acos((k * k + 1 - e * e) / (2 * k))

    h = mp.mpf(10) ** -15
    return (gamma(tau0 + h) - gamma(tau0 - h)) / (2 * h)


def test_seed_example_beats_the_seeds_published_designs(seed_opt, seed_ref):
    ours = math.degrees(seed_opt.transmission)
    for design in (SEED_DIAGRAM, SEED_COMPUTER):
        theirs = float(mp_mu(*design))
        margin = ours - theirs
        assert margin > 0
        # The margin to 1e-6 deg: ours against the mpmath optimum minus the mpmath seed value.
        assert abs(margin - float(seed_ref[0] - mp_mu(*design))) < 1e-9
    # The optimal-transmission paper reads l3/l4 = 0.93 off its diagram; the exact optimum rounds to 0.92.
    assert 0.92 < seed_opt.rocker_to_frame < 0.93


def test_optimum_simulates_to_the_requested_swing_and_time_ratio(seed_opt):
    sim = measure_motion(optimum_linkage(seed_opt))
    assert sim.assembles
    assert abs(math.degrees(sim.swing) - SEED_PHI) < 1e-9
    assert abs(sim.time_ratio - SEED_K) < 1e-9
    assert abs(sim.transmission - seed_opt.transmission) < 1e-10


def test_seed_computer_design_does_not_meet_its_own_k_and_swing():
    # Independent fact reported in the output: simulated with the crank pivot at the origin.
    c, k, r, f = SEED_COMPUTER
    sim = measure_motion(FourBar(f, 0.0, c, k, r, r, 1.0))
    assert abs(math.degrees(sim.swing) - 40.0) > 0.05
    assert abs(sim.time_ratio - SEED_K) > 1e-3


def test_inadmissible_arc_gives_a_different_linkage():
    # A design-circle point where C1 and C2 lie on opposite sides of the line A-D: the linkage
    # built from its lengths does not swing through phi (the other assembly branch is reached).
    th, phi, r = float(extreme_included_angle(SEED_K)), math.radians(SEED_PHI), 1.0
    s = np.geomspace(1e-3, 0.5 / math.sin(th / 2) * 0.999, 4000)
    c, k, f, ax, ay, ok = crank_rocker_on_circle(s, th, phi, r, -1.0)
    i = int(np.nonzero(~ok)[0][len(np.nonzero(~ok)[0]) // 2])
    cross = (-ax[i]) * (r * math.cos(phi / 2) - ay[i]) - (-ay[i]) * (r * math.sin(phi / 2) - ax[i])
    sim = measure_motion(FourBar(-ax[i], -ay[i], c[i], k[i], r, r, 1.0 if cross > 0 else -1.0))
    assert abs(sim.swing - phi) > 1e-3


# ~60 ms each (a 400 000-point brute force and a simulation); 12 draws of K and the swing
@settings(max_examples=12, deadline=None)
@given(K=st.floats(1.03, 1.6), phi=st.floats(15.0, 120.0))
def test_optimum_beats_dense_brute_force_and_simulates_exactly(K, phi):
    opt = optimal_crank_rocker(K, math.radians(phi), 1.0)
    # Brute force in the centre/angle parametrisation (independent of the scan in the module).
    th, ph = float(extreme_included_angle(K)), math.radians(phi)
    w, yc = math.sin(ph / 2), math.cos(ph / 2)
    R = w / math.sin(th)
    best = -1.0
    tau = np.linspace(0, 2 * np.pi, 200_001)
    for sgn in (-1, 1):
        ax, ay = R * np.cos(tau), yc + sgn * R * math.cos(th) + R * np.sin(tau)
        a1, a2 = np.hypot(ax + w, ay - yc), np.hypot(ax - w, ay - yc)
        # tau = 0 or pi puts the point on a chord's end (a1 or a2 = 0: 0/0): not an admissible point,
        # and the NaN it gives fails every comparison of ``ok`` below
        with np.errstate(invalid="ignore", divide="ignore"):
            cosang = ((-w - ax) * (w - ax) + (yc - ay) ** 2) / (a1 * a2)
        s1 = (-w - ax) * (-ay) - (yc - ay) * (-ax)
        s2 = (w - ax) * (-ay) - (yc - ay) * (-ax)
        ok = (a2 > a1) & (s1 * s2 > 0) & (np.abs(cosang - math.cos(th)) < 1e-9)
        c, k, f = (a2 - a1) / 2, (a2 + a1) / 2, np.hypot(ax, ay)
        gmin = np.arccos(np.clip((k * k + 1 - (f - c) ** 2) / (2 * k), -1, 1))
        gmax = np.arccos(np.clip((k * k + 1 - (f + c) ** 2) / (2 * k), -1, 1))
        mu = np.where(ok, np.minimum(gmin, np.pi - gmax), -1.0)
        best = max(best, float(mu.max()))
    assert opt.transmission >= best - 1e-12
    assert opt.transmission - best < 1e-5  # the brute force is within its grid step of the optimum
    sim = measure_motion(optimum_linkage(opt))
    assert abs(sim.swing - math.radians(phi)) < 1e-8
    assert abs(sim.time_ratio - K) < 1e-8 * K
    assert abs(sim.transmission - opt.transmission) < 1e-9


def test_k_equal_one_has_no_optimum_and_the_limit_is_90_minus_half_swing():
    with pytest.raises(SpecError, match="K = 1"):
        optimal_crank_rocker(1.0, math.radians(40), 1.0)
    a = math.degrees(optimal_crank_rocker(1.001, math.radians(40), 1.0).transmission)
    b = math.degrees(optimal_crank_rocker(1.00001, math.radians(40), 1.0).transmission)
    assert a < b < 70.0 and 70.0 - b < 0.5


def test_broadcasts_over_grids():
    k = np.array([1.1, 1.2, 1.3])[:, None]
    phi = np.radians([30.0, 60.0])[None, :]
    grid = optimal_crank_rocker(k, phi, 1.0)
    assert grid.transmission.shape == (3, 2)
    one = optimal_crank_rocker(1.2, math.radians(60), 1.0)
    assert abs(grid.transmission[1, 1] - one.transmission) < 1e-13


def run(*args, env=None):
    return subprocess.run([sys.executable, "-m", "pumplink", *args], capture_output=True, text=True, env=env)


def test_cli_seed_example_json():
    p = run("transmission", "--format", "json")
    assert p.returncode == 0, p.stderr
    d = json.loads(p.stdout)
    assert abs(d["simulated"]["swing_deg"] - 40) < 1e-9 and abs(d["simulated"]["time_ratio"] - 1.1818) < 1e-9
    assert [c["design"] for c in d["compare"]] == ["paper's diagram read-off", "paper's computer result"]
    assert all(c["ours_better_by_deg"] > 0.4 for c in d["compare"])


def test_cli_no_compare_leaves_out_the_papers_designs_only():
    """--no-compare: the same optimum, without the paper's designs (JSON and table)."""
    with_, without = (
        run("transmission", "--format", "json"),
        run("transmission", "--no-compare", "--format", "json"),
    )
    assert with_.returncode == without.returncode == 0, without.stderr
    a, b = json.loads(with_.stdout), json.loads(without.stdout)
    assert b["compare"] == [] and "printed_gamma_min_deg" not in b
    assert {k: v for k, v in a.items() if k != "printed_gamma_min_deg"} == {**b, "compare": a["compare"]}
    t = run("transmission", "--no-compare", env={**os.environ, "NO_COLOR": "1", "COLUMNS": "80"})
    assert t.returncode == 0 and "(1) optimum (this tool)" in t.stdout
    assert "(2)" not in t.stdout and "better than" not in t.stdout and "46.3698" not in t.stdout
    assert "γmax = 96.830163131°" in t.stdout  # exact to the digits shown (docs/crank-rocker.md §5)


@pytest.mark.parametrize(
    "args,key",
    [
        (["--time-ratio", "1"], "K = 1"),
        (["--swing", "190"], "swing"),
        (["--rocker", "-2"], "rocker length"),
        (["--time-ratio", "nan"], "time-ratio"),
    ],
)
def test_cli_bad_input_exits_2(args, key):
    p = run("transmission", *args)
    assert p.returncode == 2 and key in p.stderr and "Traceback" not in p.stderr


def test_cli_chart_without_matplotlib_exits_2(tmp_path):
    fake = tmp_path / "fake"
    (fake / "matplotlib").mkdir(parents=True)
    (fake / "matplotlib" / "__init__.py").write_text("raise ImportError('no matplotlib here')\n")
    env = dict(os.environ, PYTHONPATH=str(fake))
    p = run("transmission", "--chart", str(tmp_path / "c.png"), env=env)
    assert p.returncode == 2 and "pip install 'pumplink[plot]'" in p.stderr
    assert not (tmp_path / "c.png").exists()


def test_cli_chart_is_the_papers_design_diagram(tmp_path):
    """--chart draws the paper's Fig. 3 (needs the [plot] extra: `make test` installs .[test,plot]):
    contours of the best transmission angle (10..85 deg) and of rocker/frame (0.1..2.0) over
    (phi, theta), with the paper's example marked at phi = 40 deg, theta = 180 (K - 1)/(K + 1) deg
    for K = 1.1818 (read from the figure, tests/figures.py)."""
    import figures

    out = tmp_path / "diagram.png"
    p = figures.run("transmission", "--chart", out)
    assert p.returncode == 0, p.stderr
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    (ax, *_) = figures.read(out)["axes"]
    assert ax["title"].startswith("Optimal transmission of the crank-rocker (the paper's Fig. 3, exact)")
    assert ax["xlabel"] == "rocker swing φ [deg]" and ax["ylabel"].startswith("extreme included angle θ")
    assert figures.marked(ax, "o") == [pytest.approx((40.0, 180 * 0.1818 / 2.1818), rel=1e-12)]
    assert "the paper's example" in ax["texts"]
    mu_levels, ratio_levels = ax["contour_levels"]
    assert mu_levels == list(range(10, 90, 5)) and ratio_levels == pytest.approx(np.arange(1, 21) / 10)
    assert "45°" in ax["texts"] and "0.9" in ax["texts"]  # labelled contours near the example
