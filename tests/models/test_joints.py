"""Joint forces (``pumplink.models.joints``): Newton-Euler balances, virtual work, a hand case, peaks.

Expected values never come from the code under test:

* the balances of each link are written here again, with the links' accelerations from central
  differences of positions in mpmath (50 digits; positions by the Freudenstein route of
  ``tests/reference.py``, not the vector loop closure of the product) and the handle's moment
  taken as the rate of angular momentum of its parts (bar about its centre, point mass), not
  through I_O4 = m L^2 / 3;
* virtual work: the crank pin's torque on the wheel must be what the model's equation of motion
  leaves for it (F g - Mw = I a + I' w^2 / 2 + V' with I, V of full dynamics; F g - Mw = J a for
  the flywheel; F g = Mw quasi-statically);
* a position solved by hand (coupler horizontal, rocker vertical);
* a dense sweep for the peaks.
"""

import math
import pathlib
import types

import mpmath
import numpy as np
import pytest
import reference as R
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from pumplink.constants import GRAVITY
from pumplink.inputs.pump import load_spec
from pumplink.mechanisms.fourbar import FourBar, kinematic_state, synthesize
from pumplink.models import Masses
from pumplink.models import dynamics as dy
from pumplink.models import dynamics_terms as dt
from pumplink.models import joints as J
from pumplink.studies.force import force_analysis

ROOT = pathlib.Path(__file__).resolve().parents[2]
VILLAGE = ROOT / "configs/village-10m.toml"


# ----------------------------------------------------------------------------- the independent balance
def _positions(ref, t):
    """A, B, coupler centre, handle-bar centre, grip and the coupler's and handle's angles (mpmath)."""
    t4 = R.rocker_angle(ref, t)
    ax, ay = ref.crank * mpmath.cos(t), ref.crank * mpmath.sin(t)
    ex, ey = mpmath.cos(t4), mpmath.sin(t4)
    bx, by = ref.ox + ref.rocker * ex, ref.oy + ref.rocker * ey
    arm = max(ref.handle, ref.rocker)
    return dict(
        a=(ax, ay),
        b=(bx, by),
        gc=((ax + bx) / 2, (ay + by) / 2),
        gh=(ref.ox + arm / 2 * ex, ref.oy + arm / 2 * ey),
        g2=(ref.ox + (ref.rocker + arm) / 2 * ex, ref.oy + (ref.rocker + arm) / 2 * ey),
        p=(ref.ox + ref.handle * ex, ref.oy + ref.handle * ey),
        t3=mpmath.atan2(by - ay, bx - ax),
        t4=t4,
    )


def _accelerations(ref, t, w, a):
    """Positions at the instant and second time derivatives along t(tau) = t + w tau + a tau^2 / 2."""
    h = mpmath.mpf("1e-15")
    p0 = _positions(ref, t)
    pp = _positions(ref, t + w * h + a * h * h / 2)
    pm = _positions(ref, t - w * h + a * h * h / 2)

    def dd(key):
        if isinstance(p0[key], tuple):
            return tuple((pp[key][i] - 2 * p0[key][i] + pm[key][i]) / (h * h) for i in range(2))
        return (pp[key] - 2 * p0[key] + pm[key]) / (h * h)

    return p0, {k: dd(k) for k in p0}


def _cross(u, v):
    return u[0] * v[1] - u[1] * v[0]


def _sub(u, v):
    return (u[0] - v[0], u[1] - v[1])


def _residuals(ref, t, w, a, force, masses, out: J.JointForces, i=()):
    """Force and moment residuals of the coupler, the handle and the handle's outer part [N, N m]."""
    mc, mh, mp = (mpmath.mpf(float(v)) for v in (masses.coupler, masses.handle, masses.grip))
    g = mpmath.mpf(GRAVITY)
    arm = max(ref.handle, ref.rocker)
    p, acc = _accelerations(ref, mpmath.mpf(float(t)), mpmath.mpf(float(w)), mpmath.mpf(float(a)))
    f = mpmath.mpf(float(force))

    def vec(name):
        v = getattr(out, name)
        return (mpmath.mpf(float(v[(0, *i)])), mpmath.mpf(float(v[(1, *i)])))

    ra, rb, ro = vec("crank_pin"), vec("coupler_pin"), vec("rocker_pivot")
    o4 = (ref.ox, ref.oy)
    res = []
    # coupler: R_A + R_B + m_c g = m_c a_Gc;  about its centre: (A - G) x R_A + (B - G) x R_B = I_c a3
    res += [ra[0] + rb[0] - mc * acc["gc"][0], ra[1] + rb[1] - mc * g - mc * acc["gc"][1]]
    res.append(
        _cross(_sub(p["a"], p["gc"]), ra)
        + _cross(_sub(p["b"], p["gc"]), rb)
        - mc * ref.coupler**2 / 12 * acc["t3"]
    )
    # handle: R_O4 - R_B + F ex + (m_h + m_p) g = m_h a_Gh + m_p a_P
    res.append(ro[0] - rb[0] + f - mh * acc["gh"][0] - mp * acc["p"][0])
    res.append(ro[1] - rb[1] - (mh + mp) * g - mh * acc["gh"][1] - mp * acc["p"][1])
    # about the fixed O4: moments = rate of angular momentum of the bar (about its centre) and the point mass
    moments = (
        _cross(_sub(p["b"], o4), (-rb[0], -rb[1]))
        + _cross(_sub(p["p"], o4), (f, 0))
        + _cross(_sub(p["gh"], o4), (0, -mh * g))
        + _cross(_sub(p["p"], o4), (0, -mp * g))
    )
    rate = (
        _cross(_sub(p["gh"], o4), (mh * acc["gh"][0], mh * acc["gh"][1]))
        + mh * arm**2 / 12 * acc["t4"]
        + _cross(_sub(p["p"], o4), (mp * acc["p"][0], mp * acc["p"][1]))
    )
    res.append(moments - rate)
    # the handle's outer part beyond the section at B (bar [rocker, arm] and the grip): about B,
    # M_outer + (P - B) x F ex + weights = rate of its angular momentum, and M_outer = -handle_moment
    m2 = mh * (arm - ref.rocker) / arm
    i2 = m2 * (arm - ref.rocker) ** 2 / 12
    outer_moment = -mpmath.mpf(float(out.handle_moment[i]))
    lhs = (
        outer_moment
        + _cross(_sub(p["p"], p["b"]), (f, 0))
        + _cross(_sub(p["g2"], p["b"]), (0, -m2 * g))
        + _cross(_sub(p["p"], p["b"]), (0, -mp * g))
    )
    rhs = (
        _cross(_sub(p["g2"], p["b"]), (m2 * acc["g2"][0], m2 * acc["g2"][1]))
        + i2 * acc["t4"]
        + _cross(_sub(p["p"], p["b"]), (mp * acc["p"][0], mp * acc["p"][1]))
    )
    res.append(lhs - rhs)
    # its force balance along the handle: outer part gets -F_in from the inner part
    e = (mpmath.cos(p["t4"]), mpmath.sin(p["t4"]))
    f_out = (
        m2 * acc["g2"][0] + mp * acc["p"][0] + rb[0] - f,
        m2 * acc["g2"][1] + mp * acc["p"][1] + rb[1] + (m2 + mp) * g,
    )  # the inner part's force on the outer part
    res.append(-(f_out[0] * e[0] + f_out[1] * e[1]) - mpmath.mpf(float(out.handle_axial[i])))
    # the crank: torque on the wheel A x (-R_A)
    res.append(_cross(p["a"], (-ra[0], -ra[1])) - mpmath.mpf(float(out.crank_torque[i])))
    return [float(v) for v in res]


def _check_balance(ref, lk, t, w, a, force, masses):
    out = J.joint_forces(lk, np.array([t]), w, a, force, masses)
    with mpmath.workdps(50):
        res = _residuals(ref, t, w, a, force, masses, out, (0,))
    scale = max(float(np.abs(out.magnitudes).max()), abs(force), 1.0)
    length = max(float(ref.handle), float(ref.coupler), float(ref.rocker))
    forces = [res[i] for i in (0, 1, 3, 4, 7)]
    moments = [res[i] for i in (2, 5, 6, 8)]
    assert max(abs(v) for v in forces) <= 1e-9 * scale, res
    assert max(abs(v) for v in moments) <= 1e-9 * scale * length, res


def _village():
    spec = load_spec(VILLAGE)
    return spec, force_analysis(spec, keep_samples=False)


@pytest.fixture(scope="module")
def village():
    return _village()


@pytest.mark.parametrize(
    "t_deg,w,a,force",
    [(3.0, 4.7, -3.0, 80.0), (100.0, 5.5, 12.0, -95.0), (250.0, 0.0, 0.0, 40.0), (333.0, 9.0, -40.0, 0.0)],
)
def test_newton_euler_balances_of_every_link_to_1e9(village, t_deg, w, a, force):
    spec, r = village
    syn = r.design.synthesis
    ref = R.from_synthesis(syn)
    masses = Masses(0.7, 1.87, 4.32)
    _check_balance(ref, syn.linkage, math.radians(t_deg), w, a, force, masses)


@settings(
    max_examples=40,  # each example is one 50-digit balance (~0.1 s); 40 random designs, angles and motions
    deadline=None,
    suppress_health_check=[HealthCheck.filter_too_much],
)
@given(
    design=st.tuples(
        st.floats(0.1, 0.8),
        st.floats(-0.3, 0.5),
        st.floats(0.05, 0.4),
        st.floats(40.0, 100.0),
        st.floats(0.6, 1.6),
    ),
    t=st.floats(0.0, 2 * math.pi),
    w=st.floats(0.0, 12.0),
    a=st.floats(-50.0, 50.0),
    force=st.floats(-150.0, 150.0),
    masses=st.tuples(st.floats(0.0, 3.0), st.floats(0.0, 5.0), st.floats(0.0, 6.0)),
)
def test_newton_euler_balances_hold_on_random_feasible_designs(design, t, w, a, force, masses):
    reach, depth, rocker, swing, handle = design
    syn = synthesize(reach, depth, 0.0, rocker, math.radians(swing), handle)
    # buildable crank-rockers only
    assume(syn.feasible and syn.crank_length >= 1e-3 and syn.transmission_min >= math.radians(5))
    _check_balance(R.from_synthesis(syn), syn.linkage, t, w, a, force, Masses(*masses))


# ----------------------------------------------------------------------------- a hand case
def test_hand_derived_static_position():
    """Coupler horizontal, rocker vertical (crank at 90 deg): the coupler and rocker are both
    perpendicular to the crank, so the coupler translates and B moves like A.  By hand: the handle's
    moment about O4 gives the coupler force X = H F / r; the coupler carries half its weight at each
    pin; O4 takes X - F sideways and the handle's and half the coupler's weight; the axle the crank
    pin's force, the rope's pull and the wheel's weight; the crank pin's
    torque on the wheel is -c X, so F = -Mw r / (c H) balances the wheel."""
    c, k, r, h = 0.1, 0.45, 0.2, 1.2
    lk = FourBar(-k, c - r, c, k, r, h, -1.0)  # O4 straight below B = (-k, c); branch: B left of A
    mw, mc, mh, mp = 10.0, 0.7, 1.9, 4.3
    f = -mw * r / (c * h)
    assert float(kinematic_state(lk, math.pi / 2, mw).force) == pytest.approx(f, rel=1e-14)
    out = J.joint_forces(lk, math.pi / 2, 0.0, 0.0, f, Masses(mc, mh, mp))
    x = h * f / r
    g = GRAVITY
    np.testing.assert_allclose(out.coupler_pin, [x, mc * g / 2], rtol=1e-13, atol=1e-12)
    np.testing.assert_allclose(out.crank_pin, [-x, mc * g / 2], rtol=1e-13, atol=1e-12)
    np.testing.assert_allclose(out.rocker_pivot, [x - f, mc * g / 2 + (mh + mp) * g], rtol=1e-13, atol=1e-12)
    wheel = J.joint_forces(
        lk, math.pi / 2, 0.0, 0.0, f, Masses(mc, mh, mp), rope_pull=50.0, wheel_weight=30.0
    )
    np.testing.assert_allclose(wheel.axle, [-x, mc * g / 2 + 80.0], rtol=1e-13, atol=1e-12)
    assert float(out.crank_torque) == pytest.approx(mw, rel=1e-13)  # -c X = Mw
    # the handle just below B: the grip force's moment (H - r) F; compressed by the weight above the
    # section: the bar beyond B, the grip's mass and the half of the coupler's weight that B carries
    assert abs(float(out.handle_moment)) == pytest.approx((h - r) * abs(f), rel=1e-13)
    assert float(out.handle_axial) == pytest.approx(-(mh * (h - r) / h + mp + mc / 2) * g, rel=1e-13)
    assert abs(float(out.crank_moment)) == pytest.approx(mw, rel=1e-13)


# ----------------------------------------------------------------------------- virtual work
@settings(max_examples=60, deadline=None)  # float-only checks, ~5 ms each: 60 designs x 64 angles
@given(
    design=st.tuples(st.floats(0.1, 0.8), st.floats(-0.3, 0.5), st.floats(0.05, 0.4), st.floats(40.0, 100.0)),
    mw=st.floats(1.0, 40.0),
)
def test_quasi_static_crank_torque_is_the_wheel_torque(design, mw):
    """Virtual work: with F = Mw / g and massless links the crank pin turns the wheel with Mw."""
    reach, depth, rocker, swing = design
    syn = synthesize(reach, depth, 0.0, rocker, math.radians(swing), 1.2)
    # buildable crank-rockers only
    assume(syn.feasible and syn.crank_length >= 1e-3 and syn.transmission_min >= math.radians(5))
    th = np.linspace(0.0, 2 * math.pi, 64, endpoint=False)
    motion = J.quasi_static_motion(syn.linkage, th, mw)
    out = J.motion_forces(syn.linkage, motion)
    ok = np.isfinite(motion.operator_force) & (np.abs(motion.operator_force) < 1e4 * mw)
    np.testing.assert_allclose(out.crank_torque[ok], mw, rtol=1e-9)


@settings(max_examples=60, deadline=None)  # float-only, ~5 ms each
@given(
    design=st.tuples(st.floats(0.1, 0.8), st.floats(-0.3, 0.5), st.floats(0.05, 0.4), st.floats(40.0, 100.0)),
    w=st.floats(0.0, 12.0),
    a=st.floats(-50.0, 50.0),
    masses=st.tuples(st.floats(0.0, 3.0), st.floats(0.0, 5.0), st.floats(0.0, 6.0)),
)
def test_operator_force_by_virtual_work_matches_newton_euler(design, w, a, masses):
    """The operator force that closes the wheel's moment balance J a = T(F) - Mw from the reactions
    (T is affine in F) equals the one full dynamics' energy route gives, F g = Mw + I a + I' w^2/2 + V'
    (virtual work: the energy route is the links' Lagrange equation, the reactions Newton-Euler)."""
    reach, depth, rocker, swing = design
    syn = synthesize(reach, depth, 0.0, rocker, math.radians(swing), 1.2)
    # buildable crank-rockers only
    assume(syn.feasible and syn.crank_length >= 1e-3 and syn.transmission_min >= math.radians(5))
    lk, ms, jw, mw = syn.linkage, Masses(*masses), 0.9, 13.6
    th = np.linspace(0.0, 2 * math.pi, 64, endpoint=False)
    tm = dt.terms(lk, th, ms)
    g = tm.grip_rate
    keep = np.abs(g) > 1e-3 * float(np.abs(g).max())  # away from the dead centres, where F = inf
    th, g = th[keep], g[keep]
    tm = dt.terms(lk, th, ms)
    energy = (mw + (jw + tm.inertia) * a + 0.5 * tm.inertia_rate * w * w + tm.potential_rate) / g
    # T is affine in F: the force that closes the balance, by the reactions at F = 0 and F = 1
    t0 = J.joint_forces(lk, th, w, a, 0.0, ms).crank_torque
    t1 = J.joint_forces(lk, th, w, a, 1.0, ms).crank_torque
    by_reactions = (mw + jw * a - t0) / (t1 - t0)
    # compared in torque, on the scale of the terms of the balance: near a dead centre F = (...)/g
    # amplifies any rounding by 1/g in both routes alike
    scale = mw + abs(jw * a) + np.abs(t0) + np.abs(energy * g) + np.abs(tm.inertia_rate) * w * w
    np.testing.assert_array_less(np.abs((by_reactions - energy) * g), 1e-9 * scale)
    out = J.joint_forces(lk, th, w, a, energy, ms)  # and the balance itself at the energy route's F
    np.testing.assert_array_less(np.abs(out.crank_torque - mw - jw * a), 1e-9 * scale)


def test_dynamics_motion_is_the_scene_s_motion(village):
    """The village design's full-dynamics scene: the crank torque closes J a = T - Mw with the model's
    own force profile, and the acceleration is the slope of the scene's w^2/2 along the crank angle."""
    spec, r = village
    sc = r.scene
    assert r.dynamics
    th = np.linspace(0.0, 2 * math.pi, 400, endpoint=False) + 0.003
    m = J.dynamics_motion(sc, th)
    out = J.motion_forces(sc.linkage, m)
    np.testing.assert_allclose(
        out.crank_torque - sc.wheel_torque, sc.inertia * m.crank_acceleration, atol=1e-9 * 700
    )
    h = 1e-6
    slope = (dy.wheel_speed(sc, th + h) ** 2 - dy.wheel_speed(sc, th - h) ** 2) / (4 * h)
    regime = dy.regime(sc, th)
    same = (dy.regime(sc, th + 2 * h) == regime) & (dy.regime(sc, th - 2 * h) == regime)
    np.testing.assert_allclose(m.crank_acceleration[same], slope[same], rtol=1e-5, atol=1e-6)


def test_flywheel_motion_crank_torque_is_f_times_g(village):
    spec, _ = village
    r = force_analysis(spec, keep_samples=False, model="flywheel")
    sc = r.scene
    th = np.linspace(0.0, 2 * math.pi, 300, endpoint=False) + 0.002
    m = J.flywheel_motion(sc, th)
    out = J.motion_forces(sc.linkage, m)
    g = kinematic_state(sc.linkage, th, 1.0).handle_rate
    np.testing.assert_allclose(out.crank_torque, m.operator_force * g, atol=1e-12 * 700)


# ----------------------------------------------------------------------------- peaks
def test_scene_peaks_bound_a_dense_sweep(village):
    """No load on 200,000 crank angles exceeds the reported peak (to 1e-9); the sweep comes within
    1e-4 of it (one step of 3e-5 rad times the largest slope next to a dead centre)."""
    spec, r = village
    sc = r.scene
    pk = J.scene_peaks(sc, J.dynamics_motion)
    th = np.linspace(0.0, 2 * math.pi, 200_000, endpoint=False)
    out = J.motion_forces(sc.linkage, J.dynamics_motion(sc, th))
    mags = out.magnitudes
    for i in range(4):
        assert mags[i].max() <= pk.force[i] * (1 + 1e-9)
        assert mags[i].max() >= pk.force[i] * (1 - 1e-4)
        # the reported angle is where it happens (the peak may sit at a jump: either side of it)
        near = pk.angle[i] + np.array([-2e-9, 0.0, 2e-9])
        at = J.motion_forces(sc.linkage, J.dynamics_motion(sc, near)).magnitudes[i]
        assert at.max() == pytest.approx(pk.force[i], rel=1e-6)
    for got, sweep in ((pk.crank_moment[0], out.crank_moment), (pk.handle_moment[0], out.handle_moment)):
        assert np.abs(sweep).max() <= got * (1 + 1e-9)
        assert np.abs(sweep).max() >= got * (1 - 1e-4)


def test_quasi_static_peaks_outside_the_dead_band(village):
    spec, r = village
    syn = r.design.synthesis
    band = math.radians(spec.operator.dead_band)
    dce, dcf = syn.dead_centre_extended, syn.dead_centre_folded
    pk = J.quasi_static_peaks(syn.linkage, dce, dcf, band, spec.wheel_torque)
    th = np.linspace(0.0, 2 * math.pi, 200_000, endpoint=False)
    gap = np.minimum(R.angle_gap(th, dce), R.angle_gap(th, dcf))
    th = th[gap > band]
    mags = J.motion_forces(syn.linkage, J.quasi_static_motion(syn.linkage, th, spec.wheel_torque)).magnitudes
    for i in range(4):
        assert mags[i].max() <= pk.force[i] * (1 + 1e-9)
        assert mags[i].max() >= pk.force[i] * (1 - 1e-4)
    # the coupler is a two-force member without masses: the same force at A and B
    assert pk.force[1] == pytest.approx(pk.force[2], rel=1e-12)


# A bracket [LOW, HIGH] whose last zoom point LOW + (HIGH - LOW) * 1.0 does not round to HIGH (found
# by a search over random pairs; asserted below): the zoom computes that point anew.
LOW, HIGH = 0.0015813037591417738, 0.010117432431816264
#: That point: the first load has a spike there (only a zoom that computes it sees it).
SPIKE = LOW + (HIGH - LOW) * 1.0


def _bumps(centres, widths, heights, step):
    """Six loads of crank angles: Gaussian bumps (a load with NaN beyond 5 rad, where it is not
    defined; the first load with a spike at :data:`SPIKE`), one row of parameters per design, and
    for the last design a fourth load that only a search which reads its brackets' upper ends
    finds: spikes on the grid nodes ``step`` (3) and the next (2.5), and between the first zoom's
    last two points of the bracket around them a bump of 4 on a point of the next zoom, far
    narrower than the zoom's spacing."""
    a, j, b = step
    steps = np.linspace(0.0, 1.0, J.ZOOM_POINTS)
    x = a + (b - a) * steps  # the first zoom's points; the bump on the middle one of the next
    hidden = (x[-2] + (x[-1] - x[-2]) * steps)[J.ZOOM_POINTS // 2]

    def six(rows, th, read=None):
        """The loads at ``th``; with ``read`` (6, R), NaN where a row's load is not read (a search
        that reads one it did not ask for then finds another peak)."""
        th = np.asarray(th, float)
        c, w, h = (np.asarray(v, float)[rows][:, :, None] for v in (centres, widths, heights))
        out = h * np.exp(-(((th[:, None, :] - c) / w) ** 2))  # (R, 6, K)
        out[:, 5] = np.where(th > 5.0, np.nan, out[:, 5])
        out[:, 0] += np.where(th == SPIKE, 100.0, 0.0)
        last = np.asarray(rows) == len(centres) - 1
        steps = np.where(th == j, 3.0, np.where(th == b, 2.5, 4.0 * np.exp(-(((th - hidden) / 1e-9) ** 2))))
        out[last, 3] = steps[last]
        if read is not None:
            out[~read.T] = np.nan
        return out.transpose(1, 0, 2)

    return six


def test_cycle_peaks_are_each_designs_own_search():
    """:func:`pumplink.models.joints.cycle_peak_loads` (many designs; the zooms' end points taken
    from the points met before) gives :func:`~pumplink.models.joints.peak_joint_forces` of each
    design on its own (every zoom point computed), bit for bit: on loads with peaks inside a cell,
    two loads sharing a bracket, a load undefined on part of the turn, and a bracket whose last zoom
    point does not round to its upper end."""
    assert SPIKE != HIGH  # the case this test is for
    turn = np.arange(1440) * (2 * np.pi / 1440)
    trap = np.sort(np.concatenate([turn[(turn < LOW) | (turn > HIGH)], [LOW, 0.5 * (LOW + HIGH), HIGH]]))
    assert trap.size == turn.size + 1
    grid = np.stack([trap, np.sort(np.append(turn + 1e-4, 1.0)), np.sort(np.append(turn, 4.00005))])
    centres = np.array([
        [0.5 * (LOW + HIGH) + 1e-4, 0.5 * (LOW + HIGH) + 1e-4, 2.0, 3.1, 4.4, 1.0],
        [1.234567, 1.234567, 6.2, 0.3, 2.5, 5.5],
        [3.3, 0.01, 4.0, 4.0001, 6.27, 4.9],
    ])  # fmt: skip
    widths = np.full((3, 6), 0.05)
    heights = np.array(
        [[10.0, 5.0, 3.0, 2.0, 1.0, 4.0], [7.0, 3.0, 2.0, 1.0, 9.0, 6.0], [1.0, 2.0, 3.0, 4.0, 5.0, 6.0]]
    )
    six = _bumps(centres, widths, heights, grid[2, 916:919])  # the node 4.00005 off the middle
    value, angle = J.cycle_peak_loads(six, grid, six(np.arange(3), grid))

    for d in range(3):

        def forces(th, d=d):
            v = six(np.array([d]), np.asarray(th, float)[None, :])[:, 0]
            zero = np.zeros_like(v[0])
            return types.SimpleNamespace(
                **{name: (v[i], zero) for i, name in enumerate(J.JOINTS)},
                crank_moment=v[4],
                handle_moment=v[5],
            )

        want = J.peak_joint_forces(forces, nodes=(grid[d], forces(grid[d])))
        np.testing.assert_array_equal(value[:4, d], want.force)
        np.testing.assert_array_equal(angle[:4, d], want.angle)
        np.testing.assert_array_equal(value[4:, d], [want.crank_moment[0], want.handle_moment[0]])
        np.testing.assert_array_equal(angle[4:, d], [want.crank_moment[1], want.handle_moment[1]])
