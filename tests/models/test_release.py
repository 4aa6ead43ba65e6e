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

from pumplink.constants import GRAVITY
from pumplink.inputs.pump import load_spec
from pumplink.mechanisms.fourbar import synthesize
from pumplink.models import Masses
from pumplink.models import dynamics as dy
from pumplink.models import dynamics_terms as dt
from pumplink.models import release as RL
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


#: configs/village-10m.toml's inputs, restated: head 10 m, a 23 mm main, force efficiency 0.75, a
#: 0.25 m wheel with 10 kg at the rim, a 0.899 m handle, 1" tube at 2.407 kg/m.
HEAD, PIPE, EFFICIENCY, RIM, WHEEL_MASS, HANDLE, TUBE = 10.0, 0.023, 0.75, 0.25, 10.0, 0.899, 2.407
#: The water column, by hand (docs/physics.md §5, docs/models.md §2, docs/workshop.md §3): its mass
#: rho H (pi d^2/4) = 4.15476 kg moves with the rim; its weight on the rope times rw is the
#: column's torque M_col = 9.81 x 4.15476 x 0.25 = 10.18954 N m; its inertia J_c = 4.15476 x 0.25^2
#: = 0.259673 kg m^2; J = 10 x 0.25^2 + J_c = 0.884673 kg m^2 (rim and water); the wheel torque
#: M_col / 0.75, so the losses' torque, all of the inefficiency as friction, M_col (1/0.75 - 1).
WATER = 1000.0 * HEAD * math.pi * PIPE**2 / 4
COLUMN_TORQUE = 9.81 * WATER * RIM
COLUMN_INERTIA = WATER * RIM**2
INERTIA = WHEEL_MASS * RIM**2 + COLUMN_INERTIA
LOSS_TORQUE = COLUMN_TORQUE * (1 / EFFICIENCY - 1)


def test_the_hand_column_is_the_village_spec_s():
    """The numbers above, checked: 4.15476 kg of water, 10.18954 N m, 0.884673 kg m^2."""
    assert (WATER, COLUMN_TORQUE, INERTIA) == pytest.approx((4.15476, 10.18954, 0.884673), abs=5e-6)
    spec = load_spec(VILLAGE)
    assert (spec.load.head, spec.load.pipe_diameter) == (HEAD, PIPE)
    # the spec gives no efficiency: at its 1.38 m/s rope the constants decide (docs/water.md §2a)
    from pumplink.evaluate import pump_designs
    from pumplink.inputs.pump import spec_values

    designs = pump_designs(spec_values(spec))
    assert spec.load.efficiency is None
    assert (int(designs.losses), float(designs.force_efficiency)) == (0, EFFICIENCY)
    assert (spec.wheel.radius, spec.wheel.mass) == (RIM, WHEEL_MASS)
    assert (spec.linkage.handle, spec.linkage.mass_per_length) == (HANDLE, TUBE)


@pytest.fixture(scope="module")
def village():
    """The village well's force result, the links' masses by hand (the tube's mass per metre times
    the coupler's length and the handle's, docs/models.md §3a), its reference linkage and tables."""
    spec = load_spec(VILLAGE)
    r = force_analysis(spec, keep_samples=False)
    syn = r.design.synthesis
    masses = Masses(TUBE * float(syn.coupler_length), TUBE * max(HANDLE, float(syn.rocker_length)), 0.0)
    ref = R.from_synthesis(syn)
    return spec, r, syn, masses, ref, _scene_tables(ref, masses)


def _agrees(got, ref, tables, t0, w0, mloss):
    """``got`` (a :class:`pumplink.models.release.Release` from t0, w0) against the independent
    integration with the hand column, inertia and ``mloss``."""
    t_stop, t_end, reason, pieces = _independent_release(
        ref, tables, t0, w0, COLUMN_TORQUE, mloss, INERTIA, HEAD, RIM, COLUMN_INERTIA
    )
    assert got.reverses and reason == got.end_reason == "column empty"
    assert got.stop_time == pytest.approx(t_stop, rel=1e-7)
    assert got.reverse_time == pytest.approx(t_stop, rel=1e-7)
    assert got.end_time == pytest.approx(t_end, rel=1e-7)
    assert got.end_rope_travel == pytest.approx(HEAD, rel=1e-12)
    ts, vs = _grip(ref, tables, pieces)
    j = int(np.argmax(vs))
    assert got.peak_grip_speed == pytest.approx(vs[j], rel=1e-6)  # a sweep step of ~1e-5 s: 1e-7 of it
    assert got.peak_time == pytest.approx(ts[j], abs=2e-4)
    fn = next(f for f, a, b in pieces if a <= 1.0 <= b)
    th1, w1 = fn(1.0)
    one = float(ref.handle) * abs(tables[3](np.mod(th1, 2 * math.pi)) * w1)
    assert got.grip_speed_1s == pytest.approx(one, rel=1e-6)
    assert got.peak_grip_speed > 5.0  # the village well's column does throw the handle


@pytest.mark.parametrize("friction", [True, False], ids=["with friction", "free"])
def test_the_reported_release_agrees_with_an_independent_integration(village, friction):
    """What ``force --explain`` reports (studies.workshop.release: let go at the grip's fastest
    point, with the pump's losses as friction and with none) is the independent integration's
    motion from the same state with the column's torque, its inertia, J and the losses computed by
    hand from the spec: the product's own column torque, column inertia and J are what is checked."""
    from pumplink.studies import workshop

    _spec, r, _syn, _masses, ref, tables = village
    with_friction, free = workshop.release(r)
    got = with_friction if friction else free
    assert got.start_angle == with_friction.start_angle == free.start_angle
    _agrees(got, ref, tables, got.start_angle, got.start_speed, LOSS_TORQUE if friction else 0.0)


@pytest.mark.parametrize(("start_deg", "loss_share"), [(30.0, 1.0), (247.0, 0.0)])
def test_village_release_agrees_with_an_independent_integration(village, start_deg, loss_share):
    """The release model itself from two other moments of the turn, the hand column and J given."""
    _spec, r, syn, masses, ref, tables = village
    t0 = math.radians(start_deg)
    w0 = float(dy.wheel_speed(r.scene, t0))
    mloss = loss_share * LOSS_TORQUE
    got = RL.release(syn.linkage, t0, w0, COLUMN_TORQUE, mloss, INERTIA, HEAD, RIM, masses, COLUMN_INERTIA)
    _agrees(got, ref, tables, t0, w0, mloss)


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


# ----------------------------------------------------------------------------- bounded
#: The spec of an adversarial run that took 37 s and 561 MB: the prototype on a 1 mm wheel under
#: 168 m of 1 mm pipe, with a wheel mass so that the released handle is simulated.  Its column
#: (1.3e-3 N m) and losses barely brake the links, so the wheel coasts forward for more than the
#: 60 s horizon, and the column would need 168,000 rad of crank to empty: unbounded, it took 26,957
#: solver steps (both simulations).
TINY_WHEEL = {
    "name": "tiny wheel",
    "wheel": {"radius": 0.001, "mass": 10.0},
    "linkage": {"L1": 0.40, "D1": 0.20, "b": 0.10, "rocker": 0.20, "handle": 1.00, "swing": 60.0},
    "load": {"head": 168.0, "pipe_diameter": 0.001},
    "operator": {"force_limit": 100.0, "speed": 360.0, "dead_band": 20.0},
}


def test_a_tiny_wheel_under_a_tall_column_stops_early_within_the_step_limit(monkeypatch):
    """Counted here, at scipy's ``solve_ivp`` (independent of the product's own count): both
    simulations together take at most 2 x MAX_STEPS steps, and each reports that it stopped early,
    at the step limit, in its result, its JSON row and its line."""
    import scipy.integrate

    from pumplink.inputs.pump import parse_spec
    from pumplink.output.workshop import release_line, release_row
    from pumplink.studies.workshop import release

    counted = {"steps": 0, "evaluations": 0}
    solve = scipy.integrate.solve_ivp

    def counting(*args, **kw):
        sol = solve(*args, **kw)
        counted["steps"] += sol.t.size - 1
        counted["evaluations"] += sol.nfev
        return sol

    monkeypatch.setattr(scipy.integrate, "solve_ivp", counting)
    both = release(force_analysis(parse_spec(TINY_WHEEL), keep_samples=False))
    assert 0 < counted["steps"] <= 2 * RL.MAX_STEPS
    assert counted["evaluations"] <= 2 * RL.MAX_STEPS * 30  # DOP853: 12 a step, and retried steps
    for got in both:
        assert got.stopped_early and got.end_reason == "step limit" and not got.reverses
        assert math.isnan(got.stop_time) and 0 < got.end_time < RL.HORIZON
    row = release_row(both)
    assert (row["stopped_early"], row["end"], row["needs_ratchet_or_brake"]) == (True, "step limit", None)
    assert "STOPPED EARLY" in release_line(both) and f"{RL.MAX_STEPS:,} solver steps" in release_line(both)


def test_the_turn_limit_stops_a_long_run_back():
    """Without link masses the motion is smooth and the steps long; the run back to an empty
    column would take head / rw = 3000 rad.  With a turn limit of 100 rad the simulation stops
    once the crank has turned 100 rad in all (the coast, J w0^2 / 2 / (Mc + Ml) rad by the closed
    form of test_closed_form_without_link_masses, then the run back), at the limit exactly."""
    syn = synthesize(0.4, 0.2, 0.1, 0.2, math.radians(70.0), 1.2)
    mc_, ml, j, head, rw, w0 = 10.0, 2.0, 0.9, 3.0, 0.001, 5.0
    got = RL.release(syn.linkage, 1.0, w0, mc_, ml, j, head, rw, max_turned=100.0)
    coast = 0.5 * j * w0**2 / (mc_ + ml)
    assert got.reverses and got.stopped_early and got.end_reason == "turn limit"
    assert got.stop_angle - 1.0 == pytest.approx(coast, rel=1e-9)
    assert got.end_rope_travel == pytest.approx(rw * (100.0 - coast), rel=1e-9)
