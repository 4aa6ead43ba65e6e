"""Full dynamics (``pumplink.models.dynamics``): I(t), V(t), the least peak force, its limits and
scalings, and the time-domain cross-check.

Expected values never come from the code under test.  They come from

* the flywheel scene (``pumplink.models.flywheel``), itself tested against a brute-force
  reservoir sweep: with no link masses the dynamics must give its least peak force;
* closed forms: F_mean = pi Mw / S (docs/physics.md §4) for an infinite wheel, and the point
  mass at the grip, whose I = J + m |dP/dt|^2 and V = m g Py are written down from the grip's
  position;
* the 50-digit reference linkage of ``tests/reference.py`` (positions by a different route):
  kinetic energy from central differences of positions, I' and V' from central differences of
  I and V, all in mpmath;
* a brute-force lower bound: the pairs of (C1)-(C2) on 200,000 uniform crank angles.
"""

import math

import mpmath
import numpy as np
import pytest
import reference as R

from pumplink.constants import GRAVITY
from pumplink.inputs.pump import load_spec, parse_spec
from pumplink.models import dynamics as dy
from pumplink.models import dynamics_solver as ds
from pumplink.models import dynamics_terms as dt
from pumplink.models import flywheel as fw
from pumplink.models import flywheel_solver as fs
from pumplink.models import grip_travel as gt
from pumplink.models.quasi_static import mean_force
from pumplink.studies.force import design, force_analysis

EXAMPLE = "examples/well-12m-flywheel.toml"
ROOT = __import__("pathlib").Path(__file__).resolve().parents[2]


def _case(path=EXAMPLE, **linkage):
    spec = load_spec(path)
    if linkage:
        data = spec.model_dump(exclude_none=True)
        data["linkage"].update(linkage)
        spec = parse_spec(data)
    syn = design(spec).synthesis
    return spec, syn, syn.linkage, syn.dead_centre_extended, syn.dead_centre_folded


@pytest.fixture(scope="module", params=[EXAMPLE, "configs/women-operators-6m.toml"])
def case(request):
    import pathlib

    root = pathlib.Path(__file__).resolve().parents[2]
    return _case(root / request.param)


@pytest.mark.parametrize("speed_deg", [90.0, 180.0, 360.0, 540.0, 1080.0])
def test_flywheel_is_the_special_case_without_link_masses(case, speed_deg):
    spec, syn, lk, dce, dcf = case
    w = math.radians(speed_deg)
    ref = fs.least_peak_force(lk, dce, dcf, spec.wheel_torque, fw.energy_band(spec.inertia, w, 0.2))
    got = ds.least_peak_force(lk, dce, dcf, spec.wheel_torque, spec.inertia, dy.Masses(), w, 0.2)
    assert got == pytest.approx(ref, rel=1e-11)


def test_zero_masses_give_the_flywheel_band_and_terms(case):
    spec, syn, lk, dce, dcf = case
    th = np.linspace(0, 2 * np.pi, 37)
    lo, hi = dt.energy_band(lk, th, 0.5, dy.Masses(), 3.0, 0.2)
    assert np.all(np.ptp(lo) == 0) and np.all(np.ptp(hi) == 0)  # no V, no link inertia: flat
    assert lo[0] == pytest.approx(0.5 * 0.5 * 2.7**2, rel=1e-15)
    assert hi[0] == pytest.approx(0.5 * 0.5 * 3.3**2, rel=1e-15)
    assert hi[0] - lo[0] == pytest.approx(float(fw.energy_band(0.5, 3.0, 0.2)), rel=1e-14)


def test_infinite_wheel_needs_only_the_mean_force(case):
    spec, syn, lk, dce, dcf = case
    ms = dt.bar_masses(lk, 1.56, 4.0)
    got = ds.least_peak_force(lk, dce, dcf, spec.wheel_torque, 1e9, ms, 2 * np.pi, 0.2)
    stroke = 2 * spec.linkage.handle * math.sin(math.radians(spec.linkage.swing) / 2)
    assert got == pytest.approx(float(mean_force(spec.wheel_torque, stroke)), rel=1e-9)


def test_scaling_all_masses_and_the_load_scales_the_force(case):
    spec, syn, lk, dce, dcf = case
    ms = dt.bar_masses(lk, 1.56, 2.0)
    base = ds.least_peak_force(lk, dce, dcf, spec.wheel_torque, spec.inertia, ms, 2 * np.pi, 0.2)
    k = 3.0
    ms3 = dy.Masses(k * ms.coupler, k * ms.handle, k * ms.grip)
    got = ds.least_peak_force(lk, dce, dcf, k * spec.wheel_torque, k * spec.inertia, ms3, 2 * np.pi, 0.2)
    assert got == pytest.approx(k * base, rel=1e-10)


def test_time_scaling_speed_gravity_and_load_together(case):
    """w -> s w, g -> s^2 g, Mw -> s^2 Mw: every energy scales by s^2, so Fp* does too."""
    spec, syn, lk, dce, dcf = case
    ms = dt.bar_masses(lk, 1.56, 3.0)
    base = ds.least_peak_force(lk, dce, dcf, spec.wheel_torque, spec.inertia, ms, 2 * np.pi, 0.2)
    s = 1.5
    got = ds.least_peak_force(
        lk, dce, dcf, s * s * spec.wheel_torque, spec.inertia, ms, s * 2 * np.pi, 0.2, gravity=s * s * GRAVITY
    )
    assert got == pytest.approx(s * s * base, rel=1e-10)


# ----------------------------------------------------------------------------- I and V, independently
def _ref_positions(ref, t2, arm):
    """Coupler centre, handle-bar centre and grip at crank angle t2 (mpmath, 50 digits)."""
    t4 = R.rocker_angle(ref, t2)
    ax, ay = ref.crank * mpmath.cos(t2), ref.crank * mpmath.sin(t2)
    bx, by = ref.ox + ref.rocker * mpmath.cos(t4), ref.oy + ref.rocker * mpmath.sin(t4)
    u = mpmath.cos(t4), mpmath.sin(t4)
    return dict(
        a=(ax, ay),
        b=(bx, by),
        gc=((ax + bx) / 2, (ay + by) / 2),
        gh=(ref.ox + arm / 2 * u[0], ref.oy + arm / 2 * u[1]),
        p=(ref.ox + ref.handle * u[0], ref.oy + ref.handle * u[1]),
        t3=mpmath.atan2(by - ay, bx - ax),
        t4=t4,
    )


def _ref_energy(ref, t2, mc, mh, ma, arm):
    """(I - J, V) at t2 by central differences of positions (step 1e-20 at 50 digits)."""
    h = mpmath.mpf("1e-20")
    p, m = _ref_positions(ref, t2 + h, arm), _ref_positions(ref, t2 - h, arm)
    c = _ref_positions(ref, t2, arm)

    def v2(key):
        return ((p[key][0] - m[key][0]) / (2 * h)) ** 2 + ((p[key][1] - m[key][1]) / (2 * h)) ** 2

    w3 = (p["t3"] - m["t3"]) / (2 * h)
    w4 = (p["t4"] - m["t4"]) / (2 * h)
    k = ref.coupler
    inertia = (
        mc * v2("gc") + mc * k * k / 12 * w3**2 + mh * v2("gh") + mh * arm * arm / 12 * w4**2 + ma * v2("p")
    )
    pot = GRAVITY * (mc * c["gc"][1] + mh * c["gh"][1] + ma * c["p"][1])
    return inertia, pot


@pytest.mark.parametrize("t2_deg", [3.0, 47.0, 130.0, 181.0, 250.0, 333.0])
def test_inertia_and_potential_against_positions_in_mpmath(t2_deg):
    spec, syn, lk, dce, dcf = _case()
    ref = R.from_synthesis(syn)
    mc, mh, ma = 1.1, 1.9, 3.7
    arm = max(float(lk.handle), float(lk.rocker))
    ms = dy.Masses(mc, mh, ma)
    with mpmath.workdps(50):
        t2 = mpmath.mpf(math.radians(t2_deg))
        i0, v0 = _ref_energy(ref, t2, mc, mh, ma, arm)
        e = mpmath.mpf("1e-12")
        ip, vp = _ref_energy(ref, t2 + e, mc, mh, ma, arm)
        im, vm = _ref_energy(ref, t2 - e, mc, mh, ma, arm)
        di, dv = (ip - im) / (2 * e), (vp - vm) / (2 * e)
    tm = dt.terms(lk, math.radians(t2_deg), ms)
    scale_i = float(i0) + 1.0
    assert float(tm.inertia) == pytest.approx(float(i0), abs=1e-12 * scale_i)
    assert float(tm.inertia_rate) == pytest.approx(float(di), abs=1e-11 * scale_i)
    assert float(tm.potential) == pytest.approx(float(v0), abs=1e-12 * 100)
    assert float(tm.potential_rate) == pytest.approx(float(dv), abs=1e-11 * 100)


def test_point_mass_at_the_grip_by_hand():
    """Massless links, m at the grip: I = J + m |dP/dt|^2 = J + m H^2 (dt4/dt)^2, V = m g Py."""
    spec, syn, lk, dce, dcf = _case()
    ref = R.from_synthesis(syn)
    m, j = 4.0, 0.5
    for t2 in np.radians([10.0, 95.0, 200.0, 300.0]):
        st = R.state(ref, t2)
        i, _ = dt.reduced_inertia(lk, t2, j, dy.Masses(0.0, 0.0, m))
        v, _ = dt.potential(lk, t2, dy.Masses(0.0, 0.0, m))
        hand_i = j + m * float(ref.handle) ** 2 * float(st["rate"]) ** 2
        hand_v = m * GRAVITY * float(ref.oy + ref.handle * mpmath.sin(st["rocker_angle"]))
        assert float(i) == pytest.approx(hand_i, rel=1e-12)
        assert float(v) == pytest.approx(hand_v, rel=1e-12)


# ----------------------------------------------------------------------------- exactness
def _brute_lower_bound(lk, dce, dcf, mw, j, ms, w, delta, n=200_000):
    """Dinkelbach over the pairs of n uniform angles plus the grid nodes: a lower bound of Fp*."""
    pb, _ = ds.problem(lk, dce, dcf, mw, j, ms, w, delta, GRAVITY)
    x = np.sort(np.concatenate([np.linspace(0, 2 * np.pi, n, endpoint=False), pb.prep.nodes[0]]))[None, :]
    base, local = gt.travel_parts(x, *(v[:, None] for v in pb.prep.args()))
    up, lo = pb.edges(x)
    cap = np.array([np.inf])
    f_mean = mean_force(pb.mw, pb.stroke)
    return float(ds._dinkelbach((x, base, local, up, lo), pb.mw, pb.stroke, f_mean, cap)[0])


@pytest.mark.parametrize("speed_deg,arms", [(180.0, 0.0), (360.0, 0.0), (360.0, 4.0), (540.0, 4.0)])
def test_least_force_is_exact_brute_force_and_margin(speed_deg, arms):
    spec, syn, lk, dce, dcf = _case()
    ms = dt.bar_masses(lk, 1.56, arms)
    w, mw, j = math.radians(speed_deg), spec.wheel_torque, spec.inertia
    got = ds.least_peak_force(lk, dce, dcf, mw, j, ms, w, 0.2)
    low = _brute_lower_bound(lk, dce, dcf, mw, j, ms, w, 0.2)
    # a lower bound from a 200,000-point grid: below, by at most its sampling error (~1e-6)
    assert low <= got * (1 + 1e-12)
    assert low >= got * (1 - 1e-6)
    # the exact test of docs/models.md §3 holds at Fp* and fails just below it
    assert ds.band_margin(lk, dce, dcf, mw, j, ms, w, 0.2, got) <= 1e-9
    assert ds.band_margin(lk, dce, dcf, mw, j, ms, w, 0.2, got * (1 - 1e-3)) > 0


def test_vectorised_equals_one_at_a_time():
    spec, syn, lk, dce, dcf = _case()
    speeds = np.radians([200.0, 300.0, 450.0, 700.0])
    arms = np.array([0.0, 4.0, 2.0, 6.0])
    n = speeds.size
    rep = type(lk)(*(np.full(n, float(v)) for v in lk.parameters))
    ms = dt.bar_masses(rep, 1.56, arms)
    many = ds.least_peak_force(rep, dce, dcf, spec.wheel_torque, spec.inertia, ms, speeds, 0.2)
    for i in range(n):
        one = ds.least_peak_force(
            lk, dce, dcf, spec.wheel_torque, spec.inertia, dt.bar_masses(lk, 1.56, arms[i]), speeds[i], 0.2
        )
        assert many[i] == pytest.approx(one, rel=1e-12)


def test_designs_alike_share_their_terms_to_the_same_bits(monkeypatch):
    """The least peak force computes the links' terms and the grip's travel at the grid nodes once
    for designs alike in linkage and masses (a grid's variants that differ in the load or the
    wheel); every force must be the one computed design by design: 60 designs, 15 linkages (8 and
    the same with a swing 1e-5 deg larger, feasible ones) of two tubes' masses under 4 loads,
    wheels and speeds each, shuffled, against the same call with the sharing turned off."""
    from pumplink.mechanisms.fourbar import synthesize

    rng = np.random.default_rng(4)
    m = 8
    frame = [np.tile(rng.uniform(a, b, m), 2) for a, b in ((0.3, 0.6), (0.0, 0.3), (0.0, 0.15), (0.12, 0.25))]
    swing = np.radians(np.tile(rng.uniform(40, 70, m), 2) + np.repeat([0.0, 1e-5], m))
    syn = synthesize(*frame, swing, 0.9)
    ok = np.nonzero(syn.reason == 0)[0][:15]
    assert ok.size == 15
    which = rng.permutation(np.repeat(ok, 4))
    n = which.size
    lk = syn.linkage.take(which)
    dce, dcf = syn.dead_centre_extended[which], syn.dead_centre_folded[which]
    heavy = np.arange(n) % 2 == 0  # two tubes: each linkage with two masses
    ms = dt.bar_masses(lk, np.where(heavy, 2.0, 1.56), 0.0)
    load = (rng.uniform(8.0, 14.0, n), rng.uniform(0.5, 1.5, n), np.radians(rng.uniform(200, 500, n)), 0.2)
    shared = ds.least_peak_force(lk, dce, dcf, *load[:2], ms, *load[2:])
    kinds = len(set(zip(which.tolist(), heavy.tolist())))
    first, _ = ds.alike_designs(*lk.parameters, dce, dcf, ms.coupler, ms.handle, ms.grip)
    assert kinds < 0.75 * n and first.size == kinds
    monkeypatch.setattr(ds, "alike_designs", lambda *columns: (None, None))
    alone = ds.least_peak_force(lk, dce, dcf, *load[:2], ms, *load[2:])
    assert np.isfinite(shared).all() and shared.tobytes() == alone.tobytes()


def test_terms_of_designs_alike_at_shared_angles_are_the_same_bits(monkeypatch):
    """terms_from on designs as columns at shared crank angles (the model choice's sizes) computes
    designs alike bit for bit once; every term must be the one computed design by design: 6
    linkages (3 and the same with a swing 1e-5 deg larger) of two tubes' masses, 8 rows each,
    shuffled, 360 angles, against the call without the sharing."""
    from pumplink.mechanisms.fourbar import FourBar, synthesize

    rng = np.random.default_rng(9)
    frame = [np.tile(rng.uniform(a, b, 3), 2) for a, b in ((0.3, 0.6), (0.0, 0.3), (0.0, 0.15), (0.12, 0.25))]
    syn = synthesize(*frame, np.radians(np.tile(rng.uniform(40, 70, 3), 2) + np.repeat([0.0, 1e-5], 3)), 0.9)
    which = rng.permutation(np.repeat(np.arange(6), 8))
    lk = syn.linkage.take(which)
    col = FourBar(*(np.asarray(v, float)[:, None] for v in lk.parameters))
    heavy = (np.arange(which.size) % 2 == 0)[:, None]
    co = dt.coefficients(col, dt.bar_masses(col, np.where(heavy, 2.0, 1.56), np.where(heavy, 3.0, 0.0)))
    th = np.arange(360) * (2 * math.pi / 360)
    first, _ = dt.alike_designs(*(v[:, 0] for v in co if np.ndim(v) == 2))
    assert first is not None and first.size == 12
    shared = dt.terms_from(co, th, GRAVITY, fly_x=True)
    monkeypatch.setattr(dt, "alike_designs", lambda *columns: (None, None))
    alone = dt.terms_from(co, th, GRAVITY, fly_x=True)
    assert all(a.tobytes() == b.tobytes() and a.shape == (which.size, 360) for a, b in zip(shared, alone))


def _pairs_by_enumeration(g, au, al, mw, stroke, lam):
    """(h, ratio, wrapped) of each row and family of (C1)-(C2), every pair listed (docs/models.md §3a):
    (C1) N = al_j - au_i (+ 2 pi Mw), (C2) N = al_i - au_j (- 2 pi Mw), K = G_j - G_i (+ 2 S), for
    i <= j and (in brackets) for every i one revolution back; h = max N - lam K, ratio its N / K."""
    d, k = g.shape
    h, r, wrapped = np.full((d, 2), -np.inf), np.full((d, 2), np.nan), np.zeros((d, 2), bool)
    for j in range(k):
        for i in range(k):
            for wrap in (False, True):
                if i > j and not wrap:
                    continue
                kk = g[:, j] - g[:, i] + (2.0 * stroke if wrap else 0.0)
                turn = 2.0 * math.pi * mw if wrap else 0.0
                for fam, n in ((0, al[:, j] - au[:, i] + turn), (1, al[:, i] - au[:, j] - turn)):
                    val = n - lam * kk
                    better = val > h[:, fam]
                    h[better, fam] = val[better]
                    with np.errstate(all="ignore"):
                        r[better, fam] = (n / kk)[better]
                    wrapped[better, fam] = wrap
    return h, r, wrapped


@pytest.mark.parametrize("designs", [3, 300])  # numpy's running minimum, and the loop over columns
def test_the_pair_sweep_finds_the_worst_pair_of_every_row(designs):
    """The sweep of (C1)-(C2) over the points of each row (running minima, the revolution before
    folded in as a drift) against every pair listed: the largest excess h and the ratio N / K of the
    pair that gives it, on random rows (8 points) where the worst pair lies within the revolution
    on some rows and one revolution back on others."""
    rng = np.random.default_rng(17)
    k = 8
    stroke = rng.uniform(0.3, 0.6, designs)
    g = np.sort(rng.uniform(0.0, 2.0, (designs, k)), axis=1) * stroke[:, None]
    au = rng.uniform(-5.0, 5.0, (designs, k))
    al = au - rng.uniform(0.0, 4.0, (designs, k))
    mw = rng.uniform(0.5, 3.0, designs)
    lam = rng.uniform(0.0, 20.0, designs)
    with np.errstate(all="ignore"):  # as the solver calls it: a row whose worst pair has K = 0
        h, r = ds._pairs(g, au, al, g, np.zeros_like(g), mw, stroke, lam)
    ref_h, ref_r, wrapped = _pairs_by_enumeration(g, au, al, mw, stroke, lam)
    np.testing.assert_allclose(h, ref_h, rtol=0, atol=1e-12)
    live = ref_h > 0  # the pairs Dinkelbach's iteration takes its next force from
    np.testing.assert_allclose(r[live], ref_r[live], rtol=1e-12)
    assert (live & wrapped).any() and (live & ~wrapped).any()


def test_the_running_minimum_is_numpys_to_the_bit():
    """The sweep's running minimum along the points (a loop over the columns on many designs) is
    numpy's minimum.accumulate bit for bit, NaN and infinities included, on both routes."""
    rng = np.random.default_rng(23)
    for designs in (5, ds.RUN_DESIGNS, 2 * ds.RUN_DESIGNS + 3):
        f = rng.normal(size=(2, designs, 37))
        f[rng.random(f.shape) < 0.01] = np.nan
        f[rng.random(f.shape) < 0.01] = np.inf
        f[rng.random(f.shape) < 0.01] = -np.inf
        assert ds._running_min(f).tobytes() == np.minimum.accumulate(f, axis=2).tobytes()
    for shape in ((2, ds.RUN_DESIGNS, 1), (2, ds.RUN_DESIGNS, 0)):  # one point a row, and none
        f = rng.normal(size=shape)
        assert ds._running_min(f).tobytes() == f.tobytes()


def test_effect_sizes_of_designs_alike_are_the_same_bits(monkeypatch):
    """The model choice's sizes are found once for designs alike in linkage and link masses (a
    grid's variants that differ in the load or the speed); every size must be the one computed
    design by design: 4 linkages (2 and the same with a swing 1e-5 deg larger) of two tubes' masses,
    10 rows each at their own speeds and arm masses, shuffled, against the call without sharing."""
    from pumplink.mechanisms.fourbar import synthesize

    rng = np.random.default_rng(29)
    frame = [np.tile(rng.uniform(a, b, 2), 2) for a, b in ((0.3, 0.6), (0.0, 0.3), (0.0, 0.15), (0.12, 0.25))]
    syn = synthesize(*frame, np.radians(np.tile(rng.uniform(40, 70, 2), 2) + np.repeat([0.0, 1e-5], 2)), 0.9)
    which = rng.permutation(np.repeat(np.arange(4), 10))
    lk = syn.linkage.take(which)
    heavy = np.arange(which.size) % 2 == 0
    ms = dt.bar_masses(lk, np.where(heavy, 2.0, 1.56), rng.uniform(0.0, 5.0, which.size))
    speed = np.radians(rng.uniform(200.0, 500.0, which.size))
    first, _ = dy.alike_designs(*lk.parameters, ms.coupler, ms.handle)
    assert first is not None and first.size == 8
    shared = dy.effect_sizes(lk, ms, speed)
    monkeypatch.setattr(dy, "alike_designs", lambda *columns: (None, None))
    alone = dy.effect_sizes(lk, ms, speed)
    assert all(a.tobytes() == b.tobytes() and np.isfinite(a).all() for a, b in zip(shared, alone))
    assert len(set(shared[0].tolist())) == which.size  # each its own speed: no size copied across


# ----------------------------------------------------------------------------- time domain
def test_solve_ivp_confirms_the_profile_and_rejects_a_weaker_operator():
    """At Fp* the reported profile, integrated open loop, is periodic inside the band at the mean
    speed (to 1e-6); at Fp* (1 - 1e-3) the best motion leaves the band (negative control)."""
    spec, syn, lk, dce, dcf = _case()
    ms = dt.bar_masses(lk, 1.56, 4.0)
    args = (lk, dce, dcf, spec.wheel_torque, spec.inertia, ms, 2 * np.pi, 0.2)
    sc = dy.scene(*args)
    th = np.linspace(0, 2 * np.pi, 721)
    assert np.nanmax(np.abs(dy.operator_force(sc, th))) <= sc.least_peak_force * (1 + 1e-12)
    sim = dy.integrate_motion(sc, cycles=3)
    assert dy.agrees(sc, sim)
    assert sim.mean_speed == pytest.approx(2 * np.pi, rel=1e-6)
    weak = dy.scene(*args, force=sc.least_peak_force * (1 - 1e-3))
    sim = dy.integrate_motion(weak, cycles=3)
    assert not dy.agrees(weak, sim)
    assert sim.min_speed < weak.min_speed * (1 - 1e-5)


def _scenes_to_integrate():
    """The 12 m example at 2 pi rad/s and a heavy-handled women's design at pi rad/s, each at Fp*
    (the reported motion is periodic), at Fp* (1 - 1e-3) and at 0.6 Fp* (it leaves the band)."""
    out = []
    for path, speed in ((EXAMPLE, 2 * np.pi), ("configs/women-operators-6m.toml", np.pi)):
        spec, syn, lk, dce, dcf = _case(ROOT / path)
        args = (lk, dce, dcf, spec.wheel_torque, spec.inertia, dt.bar_masses(lk, 1.56, 4.0), speed, 0.2)
        sc = dy.scene(*args)
        out += [sc, dy.scene(*args, force=sc.least_peak_force * (1 - 1e-3))]
        out.append(dy.scene(*args, force=sc.least_peak_force * 0.6))
    return out


def test_integration_by_pieces_follows_the_profile_in_fewer_steps(monkeypatch):
    """The reported profile integrated piece by piece (each regime's right-hand side between the
    ends where the regime or the sign of g changes) against the whole profile at every step: the
    same motion to 1e-7 (the whole route's own error: a step across a jump of F g is rejected down
    to a tiny one, and its drift over a turn reaches 2e-8 here), in under half the right-hand side's
    evaluations; at Fp* the motion is the reported one, its fastest and slowest speed within 1e-8
    of the profile's on 400,001 angles, and periodic to 1e-9."""
    import scipy.integrate

    solve_ivp, counted = scipy.integrate.solve_ivp, []

    def counting(*args, **kwargs):
        sol = solve_ivp(*args, **kwargs)
        counted.append(sol.nfev)
        return sol

    monkeypatch.setattr(scipy.integrate, "solve_ivp", counting)
    for n, sc in enumerate(_scenes_to_integrate()):
        counted.clear()
        whole = dy.integrate_motion(sc, cycles=3, by_pieces=False)
        n_whole = sum(counted)
        counted.clear()
        pieces = dy.integrate_motion(sc, cycles=3)
        assert pieces.cycles == whole.cycles == 3 and sum(counted) < 0.5 * n_whole
        for got, want in ((pieces.max_speed, whole.max_speed), (pieces.min_speed, whole.min_speed),
                          (pieces.time_mean_speed, whole.time_mean_speed)):  # fmt: skip
            assert got == pytest.approx(want, rel=1e-7)
        np.testing.assert_allclose(pieces.speeds_at_start, whole.speeds_at_start, rtol=1e-7)
        assert pieces.periodicity <= 1e-9
        if n % 3 == 0:  # at Fp*
            speed = dy.wheel_speed(sc, sc.dead_centre_extended + np.linspace(0.0, 2 * np.pi, 400001))
            assert pieces.max_speed == pytest.approx(speed.max(), rel=1e-8)
            assert pieces.min_speed == pytest.approx(speed.min(), rel=1e-8)
            assert dy.agrees(sc, pieces) and dy.agrees(sc, whole)


def test_a_wheel_only_the_links_turn_comes_back_periodic():
    """The prototype with no wheel (J = 1e-9 kg m^2, the links the only flywheel, Fp* ~ 18 kN):
    its profile rides the band's top next to the dead centres with forces of kilonewtons.  The
    whole profile integrated at every step drifted 5 % a turn there (its mean speed 10 % high);
    piece by piece the motion is the reported one: periodic and at the mean speed to 1e-9, its
    slowest speed (a blink at each dead centre, between the 40,001 samples of the last turn) the
    band's bottom to 1e-9, so ``--verify`` agrees."""
    spec = load_spec(ROOT / "configs" / "prototype.toml")
    data = spec.model_dump(exclude_none=True)
    data["wheel"]["inertia"] = 1e-9
    sc = force_analysis(parse_spec(data), model="dynamics").scene
    assert isinstance(sc, dy.Scene) and 1.7e4 < sc.least_peak_force < 1.9e4
    sim = dy.integrate_motion(sc)
    assert sim.cycles == 4 and sim.periodicity <= 1e-9
    assert sim.mean_speed == pytest.approx(sc.mean_speed, rel=1e-9)
    assert sim.min_speed == pytest.approx(sc.min_speed, rel=1e-9)
    assert sim.max_speed == pytest.approx(sc.max_speed, rel=1e-9)
    assert dy.agrees(sc, sim)


def test_each_piece_holds_one_regime_of_the_profile():
    """Between consecutive ends of :func:`profile_pieces` the profile's regime and the sign of g
    are those of the piece's middle, on 20,000 random angles; at an end the next piece's begin
    (the regime changes between the end and the float below it)."""
    for sc in _scenes_to_integrate()[::3]:
        ends, _rhs = dy.profile_pieces(sc)
        at = dy._profile_at(sc)
        starts = [sc.dead_centre_extended, *ends[:-1]]
        assert len(ends) >= 3 and all(b > a for a, b in zip(starts, ends))

        def key(t, at=at):
            p = at(t)
            return int(p[1]), p[5] > 0

        mids = [key(0.5 * (a + b)) for a, b in zip(starts, ends)]
        th = np.random.default_rng(5).uniform(starts[0], ends[-1], 20000)
        k = np.searchsorted(ends, th, side="right")
        assert all(key(t) == mids[i] for t, i in zip(th.tolist(), k.tolist()))
        for i, e in enumerate(ends[:-1]):
            assert key(np.nextafter(e, -np.inf)) == mids[i] and key(e) == mids[i + 1]


# ----------------------------------------------------------------------------- model choice sizes
def test_effect_sizes_against_independent_routes():
    """The sizes the model choice compares with the band, each by another route: the links' kinetic
    energy by the uniform-bar formula m (vA^2 + vA.vB + vB^2)/6 of the flywheel module's estimate;
    their weight from the float twin of the reference linkage's positions; the arms' kinetic energy
    from a 200,000-point sweep of the reference rocker rate."""
    spec, syn, lk, dce, dcf = _case()
    ref = R.from_synthesis(syn)
    mpl, arms, w = 1.56, 4.32, math.radians(300.0)
    ms = dt.bar_masses(lk, mpl, arms)
    link, weight, arm = dy.effect_sizes(lk, ms, w)
    th = np.arange(dy.EFFECT_GRID) * (2 * np.pi / dy.EFFECT_GRID)
    assert link == pytest.approx(float(np.max(fw.link_energy(lk, th, w, mpl))), rel=1e-12)
    t4, _rate, _g = R.sweep_rocker(ref, th)
    f = ref.floats()
    long = max(f["handle"], f["rocker"])
    y_coupler = 0.5 * (f["crank"] * np.sin(th) + f["oy"] + f["rocker"] * np.sin(t4))
    y_handle = f["oy"] + 0.5 * long * np.sin(t4)
    v = GRAVITY * (mpl * f["coupler"] * y_coupler + mpl * long * y_handle)
    assert weight == pytest.approx(float(np.ptp(v)), rel=1e-11)
    dense = np.linspace(0.0, 2 * np.pi, 200_001)
    _t4, rate, _g = R.sweep_rocker(ref, dense)
    top = 0.5 * arms * (f["handle"] * w * float(np.nanmax(np.abs(rate)))) ** 2
    assert top <= arm * (1 + 1e-12) and arm == pytest.approx(top, rel=1e-8)


def test_model_index_by_hand():
    """The least model that is enough: 0 without inertia, 1 while every neglected effect is at most
    10 % of the band, 2 beyond; the arms count only in the verdict; --model overrides."""
    from pumplink.models import model_index

    nan = float("nan")
    assert model_index(nan, 1.0, 5.0, 5.0, 5.0) == 0  # no inertia: quasi-static, whatever the sizes
    assert model_index(0.5, 1.0, 0.1, 0.1, 9.0) == 1  # at the limit; the arms not in the verdict
    assert model_index(0.5, 1.0, 0.1 + 1e-12, 0.0, 0.0) == 2
    assert model_index(0.5, 1.0, 0.0, 0.1 + 1e-12, 0.0) == 2
    assert model_index(0.5, 1.0, 0.0, 0.0, 0.2, arms_in_verdict=True) == 2
    assert model_index(0.5, 0.0, 0.0, 0.0, 0.0) == 1  # nothing left out of a zero band
    assert model_index(0.5, 1.0, nan, nan, nan) == 1  # not known (infeasible): no call for more
    assert model_index(0.5, 1.0, 5.0, 5.0, 5.0, forced="flywheel") == 1
    assert model_index(0.5, 1.0, 0.0, 0.0, 0.0, forced="dynamics") == 2
    assert model_index(0.5, 1.0, 5.0, 5.0, 5.0, forced="quasi-static") == 0
    got = model_index(np.array([nan, 0.5, 0.5]), np.ones(3), np.array([0.0, 0.0, 0.2]), 0.0, 0.0)
    assert got.tolist() == [0, 1, 2]


# ----------------------------------------------------------------------------- best cadence
def test_least_peak_force_is_convex_in_the_mean_speed_squared():
    """Every pair's N is affine in w^2 and K does not depend on it (docs/models.md §3a), so Fp* is
    the maximum of affine functions of w^2: convex.  Second differences on a uniform grid in w^2."""
    spec, syn, lk, dce, dcf = _case()
    ms = dt.bar_masses(lk, 1.56, 4.32)
    u = np.linspace(math.radians(200.0) ** 2, math.radians(900.0) ** 2, 41)
    rep = type(lk)(*(np.full(u.size, float(v)) for v in lk.parameters))
    f = ds.least_peak_force(rep, dce, dcf, spec.wheel_torque, spec.inertia, ms, np.sqrt(u), 0.2)
    second = f[:-2] - 2 * f[1:-1] + f[2:]
    assert np.all(second >= -1e-9 * f[1:-1])
    assert np.any(second > 1e-3)  # and not affine: the effort has a minimum inside


def test_best_speed_is_the_minimum_of_a_dense_scan():
    """The best cadence against 600 speeds scanned in one call: no scanned speed needs less effort,
    and the nearest ones differ by no more than the scan's step allows."""
    spec, syn, lk, dce, dcf = _case()
    ms = dt.bar_masses(lk, 1.56, 4.32)
    lo, hi = math.radians(60.0), math.radians(1440.0)
    best, effort = dy.best_speed(lk, dce, dcf, spec.wheel_torque, spec.inertia, ms, 0.2, lo, hi)
    w = np.linspace(lo, hi, 600)
    rep = type(lk)(*(np.full(w.size, float(v)) for v in lk.parameters))
    f = ds.least_peak_force(rep, dce, dcf, spec.wheel_torque, spec.inertia, ms, w, 0.2)
    assert effort <= np.nanmin(f) * (1 + 1e-12)
    k = int(np.nanargmin(f))
    assert w[k - 1] <= best <= w[k + 1]
    assert effort == pytest.approx(
        ds.least_peak_force(lk, dce, dcf, spec.wheel_torque, spec.inertia, ms, best, 0.2), rel=1e-12
    )
    # without links or arms this is the flywheel: faster is never harder, and from some speed on the
    # force is the mean force (an infinite flywheel's, the floor), where the search stops
    none = dy.Masses()
    at, floor = dy.best_speed(lk, dce, dcf, spec.wheel_torque, spec.inertia, none, 0.2, lo, hi)
    stroke = 2 * spec.linkage.handle * math.sin(math.radians(spec.linkage.swing) / 2)
    assert floor == pytest.approx(float(mean_force(spec.wheel_torque, stroke)), rel=1e-9)
    faster = ds.least_peak_force(lk, dce, dcf, spec.wheel_torque, spec.inertia, none, hi, 0.2)
    assert faster == pytest.approx(floor, rel=1e-9) and at < hi


def test_speed_range_ends_where_the_force_meets_the_limit():
    spec, syn, lk, dce, dcf = _case()
    ms = dt.bar_masses(lk, 1.56, 4.32)
    args = (lk, dce, dcf, spec.wheel_torque, spec.inertia, ms, 0.2)
    lo, hi = math.radians(60.0), math.radians(1440.0)
    best, effort = dy.best_speed(*args, lo, hi)
    limit = 1.5 * effort  # an interval around the best cadence
    a, b = dy.speed_range(*args, limit, lo, hi, best)
    assert lo < a < best < b < hi
    for end in (a, b):
        assert ds.least_peak_force(*args[:6], end, 0.2) == pytest.approx(limit, rel=1e-7)
    inside = ds.least_peak_force(*args[:6], np.array([a * (1 + 1e-4), b * (1 - 1e-4)]), 0.2)
    outside = ds.least_peak_force(*args[:6], np.array([a * (1 - 1e-4), b * (1 + 1e-4)]), 0.2)
    assert np.all(inside <= limit) and np.all(outside > limit)
    assert all(math.isnan(x) for x in dy.speed_range(*args, 0.9 * effort, lo, hi, best))  # none passes


def _profile_by_definition(sc, th):
    """The reported motion's energy and regime written as docs/models.md §3 defines them, the
    minima over the refined points taken point by point: e = min(Fp G - Mw phi + past minimum of
    (upper - Q), upper, -Fp G - Mw phi + future minimum of (upper - P)), with the grip travel G from
    :func:`pumplink.models.grip_travel.travel_parts` (its own Px at dce + phi), the links' terms
    from :func:`pumplink.models.dynamics_terms.terms` and phi from np.mod."""
    fp, mw = sc.least_peak_force, sc.wheel_torque
    phi = np.mod(th - sc.dead_centre_extended, 2 * np.pi)
    base, local = gt.travel_parts(phi, *sc.travel)
    g_phi = base + local
    tm = dt.terms(sc.linkage, th, sc.masses, sc.gravity)
    i = sc.inertia + tm.inertia
    up = tm.potential + 0.5 * i * sc.max_speed**2
    x, kb, kl, kup, _ = sc.points
    a, b = 2.0 * fp * sc.stroke - 2 * np.pi * mw, -2.0 * fp * sc.stroke - 2 * np.pi * mw
    al, de = kup - (fp * (kb + kl) - mw * x), kup - (-fp * (kb + kl) - mw * x)
    col = phi[:, None]
    past = np.where(x[None, :] < col, al, al + a).min(axis=1)
    future = np.where(x[None, :] > col, de, de - b).min(axis=1)
    cand = np.stack([fp * g_phi - mw * phi + past, up, -fp * g_phi - mw * phi + future])
    return cand.min(axis=0), 1 - np.argmin(cand, axis=0), i, tm


@pytest.mark.parametrize("spec", ["examples/well-12m-flywheel.toml", "configs/village-10m.toml"])
def test_the_profile_is_its_definition_bit_for_bit(spec):
    """The reported motion's profile (the vector route of many designs, run for one: the grip's Px
    taken from the terms' loop closure where the angles agree, the points counted, np.mod's
    remainder formed directly) equals its definition written out, bit for bit, on angles over
    several turns, next to both dead centres (the travel integrated there) and on the refined
    points, for scenes with and without the operator's arms."""
    spec, _syn, lk, dce, dcf = _case(spec)
    rng = np.random.default_rng(11)
    for arms in (0.0, 4.0):
        masses = dt.bar_masses(lk, 1.56, arms)
        sc = dy.scene(lk, dce, dcf, spec.wheel_torque, spec.inertia, masses, 2 * np.pi, 0.2)
        dce, dcf = sc.dead_centre_extended, sc.dead_centre_folded
        th = np.concatenate([
            rng.uniform(-15.0, 40.0, 800), np.linspace(0.0, 2 * np.pi, 1441),
            dce + rng.uniform(-0.03, 0.03, 200), dcf + rng.uniform(-0.03, 0.03, 200), sc.points[0] + dce,
        ])  # fmt: skip
        e, regime, _dup, _v, i, _g, tm = dy._profile(sc, th)
        want_e, want_regime, want_i, want_tm = _profile_by_definition(sc, th)
        np.testing.assert_array_equal(e, want_e)
        np.testing.assert_array_equal(regime, want_regime)
        np.testing.assert_array_equal(i, want_i)
        for k in ("inertia_rate", "potential", "potential_rate", "grip_rate"):
            np.testing.assert_array_equal(getattr(tm, k), getattr(want_tm, k))
