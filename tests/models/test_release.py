"""The released handle (``pumplink.models.release``).

Expected values never come from the code under test:

* an independent integration of the same physics written here: Lagrange's equation in the crank
  angle with the links' I and V computed from positions in mpmath (Freudenstein route of
  ``tests/reference.py``; the bar about its centre, not about O4), tabulated and splined, its own
  phase logic, integrated by scipy's ``solve_ivp`` (LSODA, not the product's DOP853) and its peak
  taken from a dense sweep of the solution;
* closed forms without link masses: the coast is a constant deceleration, the run back a harmonic
  oscillation about the point where the column's torque equals the losses;
* the energy balance of a whole release on random feasible designs.
"""

import math
import pathlib

import mpmath
import numpy as np
import pytest
import reference as R
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from scipy.integrate import solve_ivp
from scipy.interpolate import CubicSpline

from pumplink.constants import GRAVITY, LINK_MASS_PER_METRE
from pumplink.inputs.pump import load_spec
from pumplink.mechanisms.fourbar import synthesize
from pumplink.models import Masses
from pumplink.models import dynamics as dy
from pumplink.models import dynamics_terms as dt
from pumplink.models import release as RL
from pumplink.models.load import link_masses
from pumplink.studies.force import force_analysis

ROOT = pathlib.Path(__file__).resolve().parents[2]
VILLAGE = ROOT / "configs/village-10m.toml"


# ----------------------------------------------------------------------------- independent scene
def _pos(ref, t, arm):
    t4 = R.rocker_angle(ref, t)
    ax, ay = ref.crank * mpmath.cos(t), ref.crank * mpmath.sin(t)
    ex, ey = mpmath.cos(t4), mpmath.sin(t4)
    bx, by = ref.ox + ref.rocker * ex, ref.oy + ref.rocker * ey
    return (
        (ax + bx) / 2,
        (ay + by) / 2,
        ref.ox + arm / 2 * ex,
        ref.oy + arm / 2 * ey,
        mpmath.atan2(by - ay, bx - ax),
        t4,
    )


def _inertia(ref, t, mc, mh, arm):
    """The links' reduced inertia at t from central differences of positions (kinetic energy / w^2 * 2)."""
    h = mpmath.mpf("1e-12")
    p, m = _pos(ref, t + h, arm), _pos(ref, t - h, arm)
    d = [(a - b) / (2 * h) for a, b in zip(p, m, strict=True)]
    return (
        mc * (d[0] ** 2 + d[1] ** 2) + mc * ref.coupler**2 / 12 * d[4] ** 2 + mh * (d[2] ** 2 + d[3] ** 2)
    ) + mh * arm**2 / 12 * d[5] ** 2


def _scene_tables(ref, masses: Masses, nodes=1024):
    """Periodic splines of I_l, I_l', V_l' and dt4/dt over a turn, from mpmath at 30 digits."""
    mc, mh = mpmath.mpf(float(masses.coupler)), mpmath.mpf(float(masses.handle))
    arm = max(ref.handle, ref.rocker)
    g = mpmath.mpf(GRAVITY)
    th = np.linspace(0.0, 2 * math.pi, nodes + 1)
    tab = np.empty((4, nodes + 1))
    e = mpmath.mpf("1e-9")
    with mpmath.workdps(30):
        for j, t in enumerate(th[:-1]):
            t = mpmath.mpf(t)

            def pot(tt):
                p = _pos(ref, tt, arm)
                return g * (mc * p[1] + mh * p[3])

            tab[0, j] = float(_inertia(ref, t, mc, mh, arm))
            tab[1, j] = float(
                (_inertia(ref, t + e, mc, mh, arm) - _inertia(ref, t - e, mc, mh, arm)) / (2 * e)
            )
            tab[2, j] = float((pot(t + e) - pot(t - e)) / (2 * e))
            tab[3, j] = float(R.state(ref, t)["rate"])
    tab[:, -1] = tab[:, 0]
    return [CubicSpline(th, row, bc_type="periodic") for row in tab]


def _independent_release(ref, tables, t0, w0, mcol, mloss, inertia, head, rw, jc):
    """The released motion by a route of its own: (stop time, end time, reason, t, theta, w dense)."""
    ii, di, dv, rate = tables
    empty = head / rw

    def left(th, top):
        return 1.0 - min(max((top - th) / empty, 0.0), 1.0)

    def rhs(sign, top):
        def f(_t, y):
            th, w = y
            p = np.mod(th, 2 * math.pi)
            lam = left(th, top)
            q = -mcol * lam - sign * mloss - dv(p) - 0.5 * di(p) * w * w
            return [w, q / (inertia - jc * (1 - lam) + ii(p))]

        return f

    ts = []
    # forward coast
    stop = lambda _t, y: y[1]  # noqa: E731
    stop.terminal, stop.direction = True, -1
    sol = solve_ivp(
        rhs(1.0, t0),
        (0, 60),
        [t0, w0],
        method="LSODA",
        rtol=1e-12,
        atol=1e-12,
        events=stop,
        dense_output=True,
    )
    t_stop, top = float(sol.t[-1]), float(sol.y[0, -1])
    ts.append((sol.sol, 0.0, t_stop))
    drive = -mcol - float(dv(np.mod(top, 2 * math.pi)))
    if abs(drive) <= mloss or drive > 0:
        return t_stop, t_stop, "held", ts
    back = lambda _t, y: (top - y[0]) - empty  # noqa: E731
    back.terminal, back.direction = True, 1
    again = lambda _t, y: y[1]  # noqa: E731
    again.terminal, again.direction = True, 1
    sol = solve_ivp(
        rhs(-1.0, top),
        (t_stop, 60),
        [top, 0.0],
        method="LSODA",
        rtol=1e-12,
        atol=1e-12,
        events=[back, again],
        dense_output=True,
    )
    ts.append((sol.sol, t_stop, float(sol.t[-1])))
    reason = "column empty" if sol.t_events[0].size else ("held" if sol.t_events[1].size else "horizon")
    return t_stop, float(sol.t[-1]), reason, ts


def _grip(ref, tables, pieces, n=400_000):
    """Grip speed H |dt4/dt| |w| on a dense time grid over the pieces: (t, speed)."""
    rate = tables[3]
    t_all, v_all = [], []
    for fn, a, b in pieces:
        t = np.linspace(a, b, max(int(n * (b - a) / pieces[-1][2]), 10))
        th, w = fn(t)
        t_all.append(t)
        v_all.append(float(ref.handle) * np.abs(rate(np.mod(th, 2 * math.pi)) * w))
    return np.concatenate(t_all), np.concatenate(v_all)


@pytest.fixture(scope="module")
def village():
    spec = load_spec(VILLAGE)
    r = force_analysis(spec, keep_samples=False)
    syn = r.design.synthesis
    lk = spec.linkage
    masses = link_masses(
        syn.coupler_length,
        lk.handle,
        lk.rocker,
        lk.mass_per_length or LINK_MASS_PER_METRE,
        lk.coupler_mass,
        lk.handle_mass,
    )
    ref = R.from_synthesis(syn)
    return spec, r, syn, masses, ref, _scene_tables(ref, masses)


@pytest.mark.parametrize("loss_share", [1.0, 0.0])
@pytest.mark.parametrize("start_deg", [247.0, 30.0])
def test_village_release_agrees_with_an_independent_integration(village, loss_share, start_deg):
    spec, r, syn, masses, ref, tables = village
    head, d, rw = spec.load.head, spec.load.pipe_diameter, spec.wheel.radius
    mcol = float(RL.column_torque(head, d, rw))
    jc = float(RL.column_inertia(head, d, rw))
    mloss = loss_share * (spec.wheel_torque - mcol)
    t0 = math.radians(start_deg)
    w0 = float(dy.wheel_speed(r.scene, t0))
    got = RL.release(syn.linkage, t0, w0, mcol, mloss, spec.inertia, head, rw, masses, jc)
    t_stop, t_end, reason, pieces = _independent_release(
        ref, tables, t0, w0, mcol, mloss, spec.inertia, head, rw, jc
    )
    assert got.reverses and reason == got.end_reason == "column empty"
    assert got.stop_time == pytest.approx(t_stop, rel=1e-7)
    assert got.reverse_time == pytest.approx(t_stop, rel=1e-7)
    assert got.end_time == pytest.approx(t_end, rel=1e-7)
    assert got.end_rope_travel == pytest.approx(head, rel=1e-12)
    ts, vs = _grip(ref, tables, pieces)
    j = int(np.argmax(vs))
    assert got.peak_grip_speed == pytest.approx(vs[j], rel=1e-6)  # a sweep step of ~1e-5 s: 1e-7 of it
    assert got.peak_time == pytest.approx(ts[j], abs=2e-4)
    fn = next(f for f, a, b in pieces if a <= 1.0 <= b)
    th1, w1 = fn(1.0)
    one = float(ref.handle) * abs(tables[3](np.mod(th1, 2 * math.pi)) * w1)
    assert got.grip_speed_1s == pytest.approx(one, rel=1e-6)
    assert got.peak_grip_speed > 5.0  # the village well's column does throw the handle


def test_closed_form_without_link_masses():
    """No link masses, a constant inertia: the coast decelerates at (Mc + Ml)/J, so it stops after
    J w0 / (Mc + Ml) s and (J w0^2 / 2) / (Mc + Ml) rad; the run back phi(t) obeys
    J phi'' = Mc (1 - phi/phi_e) - Ml, phi(t) = A (1 - cos(W t)), A = (Mc - Ml) phi_e / Mc,
    W^2 = Mc / (J phi_e): the wheel is fastest, A W, at phi = A, and the column is empty where
    phi = phi_e (if 2 A > phi_e)."""
    syn = synthesize(0.4, 0.2, 0.1, 0.2, math.radians(70.0), 1.2)
    mc_, ml, j, head, rw, w0 = 10.0, 2.0, 0.9, 3.0, 0.25, 5.0
    got = RL.release(syn.linkage, 1.0, w0, mc_, ml, j, head, rw)
    assert got.stop_time == pytest.approx(j * w0 / (mc_ + ml), rel=1e-9)
    assert got.stop_angle == pytest.approx(1.0 + 0.5 * j * w0**2 / (mc_ + ml), rel=1e-9)
    phi_e = head / rw
    amp = (mc_ - ml) * phi_e / mc_
    om = math.sqrt(mc_ / (j * phi_e))
    assert got.peak_wheel_speed[0] == pytest.approx(amp * om, rel=1e-8)
    assert got.peak_wheel_speed[1] - got.stop_time == pytest.approx(math.pi / 2 / om, rel=1e-6)
    t_empty = math.acos(1.0 - phi_e / amp) / om
    assert got.end_time - got.stop_time == pytest.approx(t_empty, rel=1e-8)
    assert got.end_reason == "column empty"


def test_losses_that_beat_the_column_hold_the_wheel():
    syn = synthesize(0.4, 0.2, 0.1, 0.2, math.radians(70.0), 1.2)
    got = RL.release(syn.linkage, 1.0, 5.0, 4.0, 6.0, 0.9, 3.0, 0.25)
    assert not got.reverses and got.end_reason == "held"
    assert math.isnan(got.reverse_time)
    assert got.end_time == pytest.approx(got.stop_time)


@settings(max_examples=15, deadline=None)  # each example integrates ~10 s of motion (~0.5 s)
@given(
    design=st.tuples(st.floats(0.2, 0.6), st.floats(0.0, 0.4), st.floats(0.12, 0.3), st.floats(50.0, 80.0)),
    start=st.floats(0.0, 2 * math.pi),
    speed=st.floats(1.0, 8.0),
    loss=st.floats(0.0, 0.45),
)
def test_energy_balance_of_a_whole_release(design, start, speed, loss):
    """Kinetic plus potential energy at the end = at the release minus the column's work on the
    coast, plus its work on the run back (the column shrinks linearly: Mc (phi_e - phi_e/2)), minus
    the losses over the whole path (J constant here, so energy is conserved otherwise)."""
    reach, depth, rocker, swing = design
    syn = synthesize(reach, depth, 0.0, rocker, math.radians(swing), 1.1)
    assume(syn.feasible and syn.transmission_min >= math.radians(15))  # buildable crank-rockers only
    lk = syn.linkage
    masses = dt.bar_masses(lk, 1.56)
    mc_, j, head, rw = 10.0, 0.9, 4.0, 0.25
    got = RL.release(lk, start, speed, mc_, loss * mc_, j, head, rw, masses)
    assert got.end_reason == "column empty"
    phi_e = head / rw
    coast = got.stop_angle - start
    tm0 = dt.terms(lk, start, masses)
    end_angle = got.stop_angle - phi_e
    tm1 = dt.terms(lk, end_angle, masses)
    e0 = 0.5 * (j + float(tm0.inertia)) * speed**2 + float(tm0.potential)
    work = -mc_ * coast + mc_ * phi_e / 2 - loss * mc_ * (coast + phi_e)
    kinetic = e0 + work - float(tm1.potential)
    w_end = -math.sqrt(2 * kinetic / (j + float(tm1.inertia)))
    assert got.end_speed == pytest.approx(w_end, rel=1e-7)
    assert got.end_rope_travel == pytest.approx(head, rel=1e-12)
