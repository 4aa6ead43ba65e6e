"""The kick-back and the ratchet's torque (``pumplink.models.kickback``, the service stage).

Expected values never come from the code under test:

* the column's torque rho g H (pi d^2/4) r_w by hand;
* an independent integration of the released handle with no losses: the links' I and V from
  positions in mpmath, splined (the scene of ``tests/models/test_release.py``), Lagrange's
  equation integrated by scipy's LSODA, the grip's path the integral of H |dt4/dt| along the run
  (a dense trapezoid on the spline), the release angle whose coast ends at the reported stop angle
  found by brentq on that integration;
* the march (where the bound cannot tell) against the same integration's stop.
"""

import math
import pathlib

import numpy as np
import pytest
import reference as R
from models.test_release import _scene_tables
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from pumplink.evaluate import evaluate, pump_designs
from pumplink.inputs.pump import load_spec, spec_values
from pumplink.mechanisms.fourbar import synthesize
from pumplink.models import Masses
from pumplink.models import dynamics as dy
from pumplink.models import kickback as kb
from pumplink.studies.force import force_analysis

ROOT = pathlib.Path(__file__).resolve().parents[2]
VILLAGE = ROOT / "configs/village-10m.toml"
WELL = ROOT / "examples/well-12m-flywheel.toml"
#: The village well by hand (as tests/models/test_release.py): 10 m of water in a 23 mm main on a
#: 0.25 m wheel of 10 kg at the rim, 1" tube at 2.407 kg/m.
HEAD, PIPE, RIM, WHEEL_MASS, HANDLE, TUBE = 10.0, 0.023, 0.25, 10.0, 0.899, 2.407
WATER = 1000.0 * HEAD * math.pi * PIPE**2 / 4
COLUMN_TORQUE = 9.81 * WATER * RIM
COLUMN_INERTIA = WATER * RIM**2
INERTIA = WHEEL_MASS * RIM**2 + COLUMN_INERTIA


def test_the_holding_torque_is_the_columns_by_hand():
    """rho g H (pi d^2/4) r_w: 10.18954 N m on the village well, 12.22745 N m on the 12 m example
    (12 m, 23 mm, 0.25 m), and for a grid of heads, pipes and wheels."""
    for path, want in ((VILLAGE, 10.18954), (WELL, 12.22745)):
        sv = evaluate(pump_designs(spec_values(load_spec(path))), ("service",)).service
        assert float(sv.holding_torque_required[0]) == pytest.approx(want, abs=5e-6)
    spec = load_spec(VILLAGE)
    heads, pipes, rims = (a.ravel() for a in np.meshgrid([3.0, 15.0], [0.012, 0.04], [0.2, 0.3]))
    values = {**spec_values(spec), "load.head": heads, "load.pipe_diameter": pipes, "wheel.radius": rims}
    sv = evaluate(pump_designs(values), ("service",)).service
    hand = [1000.0 * 9.81 * h * math.pi * d * d / 4.0 * r for h, d, r in zip(heads, pipes, rims)]
    np.testing.assert_allclose(sv.holding_torque_required, hand, rtol=1e-13)


@pytest.fixture(scope="module")
def village():
    """The village linkage without its ratchet, its links' masses by hand, the reference tables."""
    spec = load_spec(VILLAGE)
    r = force_analysis(spec, keep_samples=False)
    syn = r.design.synthesis
    masses = Masses(TUBE * float(syn.coupler_length), TUBE * max(HANDLE, float(syn.rocker_length)), 0.0)
    ref = R.from_synthesis(syn)
    return r, syn, masses, ref, _scene_tables(ref, masses)


def _run_back(tables, top, window):
    """From rest at crank angle ``top``, the water column drives the wheel back (no losses):
    (the crank angle where the run ends, how: "empty", "window" or "stopped")."""
    ii, di, dv, _rate = tables
    lc = HEAD / RIM

    def rhs(_t, y):
        th, w = y
        p = np.mod(th, 2 * math.pi)
        left = 1.0 - min(max((top - th) / lc, 0.0), 1.0)
        q = -COLUMN_TORQUE * left - dv(p) - 0.5 * di(p) * w * w
        return [w, q / (INERTIA - COLUMN_INERTIA * (1 - left) + ii(p))]

    end = lambda _t, y: (top - y[0]) - min(window, lc)  # noqa: E731
    end.terminal, end.direction = True, 1
    again = lambda t, y: y[1] if t > 1e-9 else -1.0  # noqa: E731
    again.terminal, again.direction = True, 1
    sol = solve_ivp(rhs, (0, 60), [top, 0.0], method="LSODA", rtol=1e-12, atol=1e-12, events=[end, again])
    how = "stopped" if sol.t_events[1].size else ("empty" if window >= lc else "window")
    return float(sol.y[0, -1]), how


def _path(tables, lo, hi, n=200_001):
    """The grip's path H int |dt4/dt| dt over crank angles [lo, hi] (trapezoid on the spline)."""
    th = np.linspace(lo, hi, n)
    return HANDLE * np.trapezoid(np.abs(tables[3](np.mod(th, 2 * math.pi))), th)


def _coast_end(tables, t0, w0):
    """Where the wheel released at (t0, w0) stops coasting forward (no losses)."""
    ii, di, dv, _rate = tables

    def rhs(_t, y):
        p = np.mod(y[0], 2 * math.pi)
        return [y[1], (-COLUMN_TORQUE - dv(p) - 0.5 * di(p) * y[1] ** 2) / (INERTIA + ii(p))]

    stop = lambda _t, y: y[1]  # noqa: E731
    stop.terminal, stop.direction = True, -1
    sol = solve_ivp(rhs, (0, 60), [t0, w0], method="LSODA", rtol=1e-12, atol=1e-12, events=stop)
    return float(sol.y[0, -1])


@pytest.mark.parametrize("teeth", [None, 12, 24], ids=["no ratchet", "12 teeth", "24 teeth"])
def test_the_kick_back_is_a_release_at_the_design_speed_by_an_independent_integration(village, teeth):
    """The reported kick-back is what the independent integration gives for a release at the
    design speed: the release angle whose forward coast stops at the reported stop angle (found by
    brentq on the integration), then the run back to the column's end or the pawl, the grip's path
    over it; no release among 12 over the turn kicks back further.  The evaluation of the village
    spec (its 24-tooth [ratchet]) reports that travel, and without the ratchet the column's."""
    r, syn, masses, _ref, tables = village
    window = math.inf if teeth is None else 2 * math.pi / teeth
    got = kb.kick_back(
        syn.linkage, syn.dead_centre_extended, syn.dead_centre_folded, masses, COLUMN_TORQUE, HEAD, RIM,
        INERTIA, COLUMN_INERTIA, None if teeth is None else window,
    )  # fmt: skip
    travel, ts = float(got.travel[0]), float(got.stop_angle[0])
    # a release at the design speed whose coast ends at ts: scan the release angles, then brentq
    speed = lambda t0: float(dy.wheel_speed(r.scene, np.mod(t0, 2 * math.pi)))  # noqa: E731
    starts = np.linspace(ts - 2 * math.pi, ts, 13)
    ends = np.array([_coast_end(tables, t0, speed(t0)) for t0 in starts[:-1]])
    k = int(np.nonzero((ends[:-1] - ts) * (ends[1:] - ts) <= 0)[0][0])
    t0 = brentq(lambda t: _coast_end(tables, t, speed(t)) - ts, starts[k], starts[k + 1], xtol=1e-13)
    top = _coast_end(tables, t0, speed(t0))
    end, how = _run_back(tables, top, window)
    assert how == ("empty" if teeth is None else "window")
    assert travel == pytest.approx(_path(tables, end, top), rel=1e-7)
    # the other releases of the scan kick back no further
    for e in ends:
        stop, _ = _run_back(tables, e, window)
        assert _path(tables, stop, e) <= travel * (1 + 1e-7)
    if teeth is None:
        assert got.end[0] == kb.ENDS.index("column empty") and travel > 9.0  # metres, not centimetres
    else:
        assert got.end[0] == kb.ENDS.index("pawl")
    # what `pumplink force` reports for the village (its [ratchet] of 24 teeth): the same release
    sv = r.evaluation.service
    if teeth == 24:
        assert float(sv.kick_back[0]) == pytest.approx(_path(tables, end, top), rel=1e-7)
    if teeth is None:  # without it
        assert float(sv.kick_back_free[0]) == pytest.approx(_path(tables, end, top), rel=1e-7)


def test_the_march_stops_where_the_integration_does(village):
    """A light column on heavy links (1 m of water, a 6 kg handle): the bound cannot tell, the march
    of (K.1) decides where the run back stops again, against the integration's stop."""
    _r, syn, _masses, ref, _tables = village
    heavy = Masses(3.0, 6.0, 0.0)
    tables = _scene_tables(ref, heavy, nodes=512)
    head, jc = 1.0, 1000.0 * 1.0 * math.pi * PIPE**2 / 4 * RIM**2
    mcol = 9.81 * 1000.0 * 1.0 * math.pi * PIPE**2 / 4 * RIM
    lk, dce, dcf = syn.linkage, syn.dead_centre_extended, syn.dead_centre_folded
    rate = float(np.max(np.abs(tables[3](np.linspace(0, 2 * math.pi, 20001)))))
    vm = kb.weight_torque_bound(lk, dce, dcf, heavy, rate)
    assert not kb.reaches_end(mcol, head / RIM, head / RIM, INERTIA, jc, vm)
    ii, di, dv, _ = tables
    lc = head / RIM
    for ts in np.linspace(0.3, 6.0, 7):
        if mcol + float(dv(ts)) <= 0:  # the links' weight holds it forward: not a stop
            continue
        run, how = kb.march(lk, heavy, [[ts]], [[lc]], mcol, lc, INERTIA, jc)

        def rhs(_t, y, ts=ts):
            p = np.mod(y[0], 2 * math.pi)
            left = 1.0 - min(max((ts - y[0]) / lc, 0.0), 1.0)
            q = -mcol * left - dv(p) - 0.5 * di(p) * y[1] ** 2
            return [y[1], q / (INERTIA - jc * (1 - left) + ii(p))]

        again = lambda t, y: y[1] if t > 1e-9 else -1.0  # noqa: E731
        again.terminal, again.direction = True, 1
        empty = lambda _t, y, ts=ts: (ts - y[0]) - lc  # noqa: E731
        empty.terminal, empty.direction = True, 1
        sol = solve_ivp(
            rhs, (0, 60), [ts, 0.0], method="LSODA", rtol=1e-12, atol=1e-12, events=[empty, again]
        )
        want = ts - float(sol.y[0, -1])
        assert (how[0, 0] == kb.ENDS.index("stops")) == bool(sol.t_events[1].size)
        assert float(run[0, 0]) == pytest.approx(want, rel=1e-4)


def test_without_a_column_there_is_no_kick_back_check():
    """A spec with a rope force (no head, no pipe) has no column to drive the wheel back: no
    kick-back check, no holding torque."""
    ev = evaluate(pump_designs(spec_values(load_spec(ROOT / "configs/prototype.toml"))))
    keys = {c.key for c in ev.verdict.checks}
    assert not keys & {"kick_back", "holding_torque"}
    assert np.isnan(ev.service.holding_torque_required).all()


def _circle_rocker(lk, th):
    """The rocker angle t4 at crank angles ``th`` by a route of its own: B where the coupler's circle
    about the crank pin A meets the rocker's about O4 (the chord's foot a = (e^2 + coupler^2 -
    rocker^2) / 2e along A->O4, the half-chord h = sqrt(coupler^2 - a^2)), on the side of the branch."""
    ax, ay = lk.crank * np.cos(th), lk.crank * np.sin(th)
    dx, dy = lk.pivot_x - ax, lk.pivot_y - ay
    e = np.hypot(dx, dy)
    a = (e * e + lk.coupler**2 - lk.rocker**2) / (2 * e)
    h = np.sign(lk.branch) * np.sqrt(lk.coupler**2 - a * a)
    bx, by = ax + (a * dx - h * dy) / e, ay + (a * dy + h * dx) / e
    return np.arctan2(by - lk.pivot_y, bx - lk.pivot_x)


def _dense_path(lk, dce, dcf, nodes=20_000):
    """The grip's path H |dt4| summed from crank angle 0, as a function of the crank angle: the
    rocker's angle on ``nodes`` crank angles a turn plus both dead centres (t4 is monotone between
    them, so the sum is the path to rounding), and path(x) = C(node below x) + H |t4(x) - t4(node)|."""
    th = np.unique(np.concatenate([np.linspace(0, 2 * math.pi, nodes + 1), np.mod([dce, dcf], 2 * math.pi)]))
    t4 = _circle_rocker(lk, th)
    cum = np.concatenate([[0.0], np.cumsum(np.abs(np.diff(t4)))]) * lk.handle
    turn = cum[-1]

    def path_to(x):
        turns, rest = np.divmod(x, 2 * math.pi)
        i = np.clip(np.searchsorted(th, rest, side="right") - 1, 0, th.size - 2)
        return turns * turn + cum[i] + lk.handle * np.abs(_circle_rocker(lk, rest) - t4[i])

    return path_to


#: Pump four-bars (L1, D1, b, rocker [m], swing [deg], handle [m]) and ratchets' teeth whose rocker
#: rate has two humps so near in height that the grid of stop angles ranks them the wrong way round
#: (refined, the lower one on the grid holds 2e-5 to 8e-5 more path): found among 200,000 random ones.
TWO_HUMPS = [
    (0.6634, 0.2428, 0.1367, 0.2118, 60.7665, 1.0915, 34),
    (0.6466, 0.197, 0.172, 0.1905, 30.7935, 0.6427, 13),
    (0.6859, 0.2562, 0.0795, 0.2394, 42.934, 0.7681, 23),
]


def test_the_widest_window_holds_the_most_path_of_a_dense_search():
    """widest_window on 30 random pump four-bars, each with a window of a ratchet's tooth (10-30 deg)
    or a column of one to six turns, and on the three of :data:`TWO_HUMPS`: against the grip's path
    by a route of its own (:func:`_dense_path`, t4 from the circles' intersection), the path it
    reports is the path over the window ending at its stop angle (to 1e-9), and no stop angle of
    7,200 a turn holds more than it (to 1e-9): the search refines the widest window's hump, not a
    lesser one."""
    rng = np.random.default_rng(20)
    m = 120
    given = np.array(TWO_HUMPS).T
    drawn = (rng.uniform(0.2, 0.8, m), rng.uniform(-0.1, 0.4, m), rng.uniform(0.0, 0.2, m),
             rng.uniform(0.1, 0.4, m), rng.uniform(30, 80, m), rng.uniform(0.6, 1.2, m))  # fmt: skip
    L1, D1, b, rocker, swing, handle = (np.concatenate([given[i], v]) for i, v in enumerate(drawn))
    syn = synthesize(L1, D1, b, rocker, np.radians(swing), handle)
    ok = np.nonzero(syn.reason == 0)[0][:33]
    assert ok.size == 33 and list(ok[:3]) == [0, 1, 2]
    lk = syn.linkage.take(ok)
    dce, dcf = syn.dead_centre_extended[ok], syn.dead_centre_folded[ok]
    tooth = 2 * math.pi / np.concatenate([given[6], rng.integers(12, 37, ok.size - 3)])
    column = rng.uniform(2 * math.pi, 12 * math.pi, ok.size)
    window = np.where((np.arange(ok.size) % 2 == 0) | (np.arange(ok.size) < 3), tooth, column)
    path, ts = kb.widest_window(lk, dce, dcf, window)
    stops = np.linspace(0, 2 * math.pi, 7200, endpoint=False)
    for i in range(ok.size):
        one = lk.take(i)
        path_to = _dense_path(one, dce[i], dcf[i])
        at = lambda s: path_to(s) - path_to(s - window[i])  # noqa: E731, B023
        assert path[i] == pytest.approx(float(at(ts[i])), rel=1e-9, abs=0)
        assert float(np.max(at(stops))) <= path[i] * (1 + 1e-9)


def test_the_wrap_is_numpys_remainder_bit_for_bit():
    """The kick-back's angle wrap skips fmod where it can; it must give np.mod(x + pi, 2 pi) - pi to
    the bit (the kick-back's digits are printed in full): on differences of angles and the edges of
    its shortcuts (x + pi at 0, 2 pi, 4 pi, -2 pi and floats either side), alone (the shortcuts:
    all in [0, 2 pi), all in [-2 pi, 4 pi)) and with far angles, NaN and inf beside them (numpy's
    remainder), and one at a time."""
    rng = np.random.default_rng(3)
    two_pi = 2 * math.pi
    edges = np.array([0.0, two_pi, 2 * two_pi, -two_pi]) - math.pi
    close = [edges]
    for way in (np.inf, -np.inf):  # the floats next to each edge, four either side
        v = edges
        for _ in range(4):
            v = np.nextafter(v, way)
            close.append(v)
    close = np.concatenate(close)
    x = np.concatenate([rng.uniform(-two_pi, two_pi, 100_000), close, -math.pi - np.array([1e-17, 5e-324])])
    a = x + math.pi
    near = x[(a >= -two_pi) & (a < 2 * two_pi)]  # the shortcut's range, and its edges in it
    assert {0.0, two_pi, -two_pi} <= set((near + math.pi).tolist())
    assert near.size > 100_020 and 2 * two_pi - 1e-14 < np.max(near + math.pi) < 2 * two_pi
    far = np.array(
        [edges[2], np.nextafter(-3 * math.pi, -np.inf), np.nan, np.inf, -np.inf, 1e300, -1e300, 40.0, -40.0]
    )
    inner = near[(near + math.pi >= 0.0) & (near + math.pi < two_pi)]  # x + pi itself
    assert 0.0 in (inner + math.pi).tolist() and np.max(inner + math.pi) > two_pi - 1e-14
    # each float next to an edge beside angles well inside: which shortcut holds is decided at the edge
    beside = [np.append(inner[:1000], v) for v in np.concatenate([close, far])]
    for x in (inner, near, np.concatenate([near, far]), *beside):
        with np.errstate(invalid="ignore"):
            want = np.mod(x + math.pi, two_pi) - math.pi
            assert kb._wrap(x).tobytes() == want.tobytes()
            for v, w in zip(x[-30:], want[-30:]):
                assert np.float64(kb._wrap(v)).tobytes() == np.float64(w).tobytes()


def test_designs_alike_are_searched_once_to_the_same_bits():
    """widest_window searches designs that pose the same search once (a grid's variants that differ
    only in the head share it); each design must still get the bits it gets searched alone: 12
    random linkages and the same with a swing 1e-5 deg larger (not alike: a few um apart), each 1-5
    times over, with a tooth's window and a column's, shuffled."""
    rng = np.random.default_rng(8)
    m = 30
    drawn = (rng.uniform(0.2, 0.8, m), rng.uniform(-0.1, 0.4, m), rng.uniform(0.0, 0.2, m),
             rng.uniform(0.1, 0.4, m), rng.uniform(0.6, 1.2, m))  # fmt: skip
    frame = [np.tile(v, 2) for v in drawn]
    swing = np.radians(np.tile(rng.uniform(30, 80, m), 2) + np.repeat([0.0, 1e-5], m))
    syn = synthesize(*frame[:4], swing, frame[4])
    ok = np.nonzero(syn.reason[:m] == 0)[0][:12]
    ok = np.concatenate([ok, ok + m])
    which = rng.permutation(np.concatenate([np.repeat(ok, rng.integers(1, 6, ok.size))] * 2))
    window = np.where(np.arange(which.size) < which.size // 2, 2 * math.pi / 24, 40.0)[
        rng.permutation(which.size)
    ]
    lk, dce, dcf = syn.linkage.take(which), syn.dead_centre_extended[which], syn.dead_centre_folded[which]
    path, ts = kb.widest_window(lk, dce, dcf, window)
    kinds = len({(int(i), float(v)) for i, v in zip(which, window)})
    assert kb.alike_designs(*lk.parameters, dce, dcf, window)[0].size == kinds < 0.75 * which.size  # shared
    for i in range(which.size):
        alone = kb.widest_window(lk.take([i]), dce[[i]], dcf[[i]], window[[i]])
        assert (path[i], ts[i]) == (alone[0][0], alone[1][0])
