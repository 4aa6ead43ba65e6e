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
