"""The verdict's part checks (a spec's ``[parts]``; docs/workshop.md §2): the pins' bearing
pressure against a hand derivation of the joint forces, the levels at the documented limits, and
the searches' shortcut (``parts_of_failing=False``) giving the same verdicts.

The hand derivation (quasi-static, massless links; docs/workshop.md §1): the coupler is a
two-force member, so the force on it at A is t u (u the unit vector A -> B) and on the handle at
B it is t u too.  The handle's moments about the rocker pivot O4 with the grip force F ex,
F = Mw / (dPx/dtheta) (Eq. (3) of the pump paper), give t = F H sin(theta4) / ((B - O4) x u); the
pivot carries R_O4 = -(t u + F ex), and the axle R_O2 = t u + Fw ey (the wheel's balance: the
crank pin's -t u, the rope's pull Fw downward and the bearing's R_O2 sum to zero).  Positions
from the 50-digit reference of ``tests/reference.py`` (not the product's kinematics), peaks on a
grid refined by golden sections in mpmath.
"""

from __future__ import annotations

import math
from pathlib import Path

import mpmath
import numpy as np
import pytest
import reference as R

from pumplink.evaluate import evaluate, pump_designs
from pumplink.inputs.pump import load_spec, parse_spec, spec_to_dict, spec_values
from pumplink.studies.force import force_analysis
from pumplink.verdict import FAIL, PASS, WARN

ROOT = Path(__file__).resolve().parents[1]
PIN = 0.012  # pin diameter [m]


def _spec(parts: dict | None, **operator):
    data = spec_to_dict(load_spec(ROOT / "configs" / "prototype.toml"))
    if parts is not None:
        data["parts"] = parts
    data["operator"].update(operator)
    return parse_spec(data)


def _joint_magnitudes(lk, t2, mw, rope):
    """|R_A| (= |R_B|), |R_O4| and |R_O2| at crank angle t2, by hand."""
    st = R.state(lk, t2, mw)
    ax, ay = lk.crank * mpmath.cos(t2), lk.crank * mpmath.sin(t2)
    ux, uy = st["bx"] - ax, st["by"] - ay
    n = mpmath.sqrt(ux * ux + uy * uy)
    ux, uy = ux / n, uy / n
    rx, ry = st["bx"] - lk.ox, st["by"] - lk.oy
    f = st["force"]
    t = f * lk.handle * mpmath.sin(st["rocker_angle"]) / (rx * uy - ry * ux)
    pin = abs(t)
    pivot = mpmath.sqrt((t * ux + f) ** 2 + (t * uy) ** 2)
    axle = mpmath.sqrt((t * ux) ** 2 + (t * uy + rope) ** 2)
    return pin, pivot, axle


@pytest.fixture(scope="module")
def hand_peak():
    """The largest joint force of the prototype outside its ±20° dead bands [N], by hand."""
    spec = _spec(None)
    lin, load = spec.linkage, spec.load
    syn = R.synthesis(lin.L1, lin.D1, lin.b, lin.rocker, math.radians(lin.swing))
    lk = R.make_linkage(lin.L1, lin.D1, lin.b, lin.rocker, lin.handle, syn["crank"], syn["coupler"])
    dce, dcf = (float(x) for x in R.dead_centres(lk))
    band = math.radians(spec.operator.dead_band)
    mw = load.rope_force * spec.wheel.radius
    th = np.linspace(0.0, 2 * math.pi, 721)[:-1]
    gap = np.minimum(R.angle_gap(th, dce), R.angle_gap(th, dcf))
    th = np.concatenate([th[gap > band + 1e-9], [dce + band, dce - band, dcf + band, dcf - band]])
    peaks = []
    for k in range(3):
        vals = [float(_joint_magnitudes(lk, t, mw, load.rope_force)[k]) for t in th]
        j = int(np.argmax(vals))
        best = vals[j]
        lo, hi = th[j] - 2 * math.pi / 720, th[j] + 2 * math.pi / 720
        for edge in (dce + band, dce - band, dcf + band, dcf - band):  # stay outside the bands
            if lo < edge < hi:
                if abs(th[j] - edge) < 1e-12:
                    lo = hi = edge
                elif th[j] > edge:
                    lo = edge
                else:
                    hi = edge
        g = (math.sqrt(5) - 1) / 2
        a, b = mpmath.mpf(lo), mpmath.mpf(hi)
        for _ in range(60 if hi > lo else 0):  # golden sections in mpmath
            c, d = b - g * (b - a), a + g * (b - a)
            fc = _joint_magnitudes(lk, c, mw, load.rope_force)[k]
            fd = _joint_magnitudes(lk, d, mw, load.rope_force)[k]
            a, b = (a, d) if fc > fd else (c, b)
        best = max(best, float(_joint_magnitudes(lk, (a + b) / 2, mw, load.rope_force)[k]))
        peaks.append(best)
    return max(peaks)


def test_pin_pressure_is_the_largest_joint_force_over_the_pin_s_bearing_area(hand_peak):
    """p = F / (d w) with F the largest joint force outside the dead bands (docs/workshop.md §2)."""
    width = 0.0052
    r = force_analysis(_spec({"pin_diameter": PIN, "pin_width": width}), keep_samples=False)
    got = r.verdict["pin_pressure"].value
    assert got == pytest.approx(hand_peak / (PIN * width) / 1e6, rel=1e-6)
    assert r.verdict["pin_pressure"].unit == "MPa"


@pytest.mark.parametrize(("pressure", "level"), [(11.0, PASS), (13.0, WARN), (29.0, WARN), (31.0, FAIL)])
def test_pin_pressure_levels_at_the_documented_limits(hand_peak, pressure, level):
    """Warn above 12 MPa (an alternating moving joint), fail above 30 MPa (the static allowable):
    the bore is set so that the hand-derived pressure is ``pressure``."""
    width = hand_peak / (PIN * pressure * 1e6)
    r = force_analysis(_spec({"pin_diameter": PIN, "pin_width": width}), keep_samples=False)
    assert r.verdict["pin_pressure"].level == level
    if level == FAIL:
        assert not r.verdict.passed


def test_fatigue_levels_follow_their_values():
    """A notched, thin handle tube and a thin crank bar: each fatigue check warns below 1.5 and
    fails below 1, its level agreeing with its value; a larger section is safer."""
    seen = set()
    for notch in (1.0, 1.5, 2.0, 3.0, 4.0, 5.0):
        parts = {"handle_diameter": 0.0213, "handle_wall": 0.002, "handle_notch": notch,
                 "crank_diameter": 0.010, "crank_notch": notch}  # fmt: skip
        v = force_analysis(_spec(parts), keep_samples=False).verdict
        for key in ("handle_fatigue", "crank_fatigue"):
            n = v[key].value
            want = FAIL if n < 1.0 else WARN if n < 1.5 else PASS
            assert v[key].level == want, (key, notch, n)
            seen.add(want)
    assert seen == {PASS, WARN, FAIL}  # the sizes above reach all three levels
    small = force_analysis(_spec({"crank_diameter": 0.010}), keep_samples=False).verdict
    large = force_analysis(_spec({"crank_diameter": 0.020}), keep_samples=False).verdict
    assert large["crank_fatigue"].value > small["crank_fatigue"].value


def test_no_parts_table_no_part_checks():
    v = force_analysis(_spec(None), keep_samples=False).verdict
    keys = {c.key for c in v.checks}
    assert not keys & {"pin_pressure", "handle_fatigue", "crank_fatigue"}


def test_the_searches_shortcut_gives_the_same_verdicts():
    """``parts_of_failing=False`` (the part checks only where no other check fails) changes no
    design's outcome, and where it judges the parts their values are the full route's."""
    spec = _spec({"pin_diameter": PIN, "pin_width": 0.0052, "crank_diameter": 0.0127})
    base = spec_values(spec)
    speeds = np.linspace(60.0, 900.0, 12)  # [deg/s], as in a spec
    forces = np.linspace(20.0, 120.0, 5)
    sp, fw = (a.ravel() for a in np.meshgrid(speeds, forces))

    def value(key):
        if key == "operator.speed":
            return sp
        if key == "load.rope_force":
            return fw
        return base(key)

    full = evaluate(pump_designs(value))
    quick = evaluate(pump_designs(value), screen_parts=True)
    assert np.array_equal(np.asarray(full.verdict.level), np.asarray(quick.verdict.level))
    levels = np.asarray(full.verdict.level)
    assert {PASS, WARN, FAIL} <= set(levels.tolist()) or {PASS, FAIL} <= set(levels.tolist())
    judged = ~np.isnan(np.asarray(quick.verdict["pin_pressure"].value))
    assert judged.any() and not judged.all()
    for key in ("pin_pressure", "handle_fatigue", "crank_fatigue"):
        a = np.asarray(full.verdict[key].value)[judged]
        b = np.asarray(quick.verdict[key].value)[judged]
        np.testing.assert_array_equal(a, b)
