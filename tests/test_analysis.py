"""pumplink.studies.force: the best cadence and the speeds that pass, and the quasi-static --verify.

References: the verdict of force_analysis itself at speeds just inside and just outside the
reported range (the range must be where that verdict changes), and for --verify negative controls
(a peak that is not the exact one must be caught).
"""

import dataclasses
import math
from pathlib import Path

import numpy as np
import pytest

from pumplink.constants import GRIP_SPEED_FAIL_M_S, HOUR_POWER_W
from pumplink.inputs.pump import load_spec, parse_spec, spec_to_dict
from pumplink.studies.force import force_analysis
from pumplink.studies.speed import cadence
from pumplink.studies.verify import verify_quasi_static

ROOT = Path(__file__).resolve().parents[1]
VILLAGE = ROOT / "configs" / "village-10m.toml"


@pytest.fixture(scope="module")
def village():
    spec = load_spec(VILLAGE)
    return spec, force_analysis(spec, keep_samples=False)


def _at(spec, speed_rad_s):  # (the best cadence is a float speed)
    return force_analysis(spec, math.degrees(speed_rad_s), keep_samples=False)


def test_the_passing_speeds_are_where_the_verdict_changes(village):
    """The village well: full dynamics decides; the passing speeds' ends are whole deg/s at which
    force_analysis passes, and one deg/s beyond each it fails: below by the hand force, above by
    the grip speed or the power, which there meets its fail limit."""
    spec, r = village
    c = cadence(r)
    assert c.model == "dynamics" and r.dynamics
    lo, hi = (round(math.degrees(x)) for x in c.passing)
    assert c.passing == (math.radians(lo), math.radians(hi)) and c.bands == (c.passing,)
    assert lo < spec.operator.speed < hi
    assert c.force_range[0] == c.passing[0]  # the force sets the lower end
    for inside in (lo, 0.5 * (lo + hi), hi):
        assert force_analysis(spec, inside, keep_samples=False).passed
    below, above = (force_analysis(spec, v, keep_samples=False) for v in (lo - 1, hi + 1))
    assert [c.key for c in below.verdict.failures] == ["peak_force"]
    assert {c.key for c in above.verdict.failures} <= {"grip_speed", "power"} and not above.passed
    edge = force_analysis(spec, hi, keep_samples=False)  # a speed-dependent check near its fail limit
    share = max(
        edge.verdict["grip_speed"].value / GRIP_SPEED_FAIL_M_S, edge.verdict["power"].value / HOUR_POWER_W
    )
    assert 1 - 1 / hi < share <= 1.0  # within the next deg/s of the limit


def test_the_passing_speeds_take_three_evaluations(village, monkeypatch):
    """The grid, then two steps narrowing every change at once (20 deg/s to 4, then to 1); the
    whole speeds at the ends found were evaluated on the way, so the second search evaluates
    nothing.  (The ends found are checked against force_analysis by the test above.)"""
    from pumplink.studies import speed

    spec, _ = village
    calls = []
    real = speed._at_speeds
    monkeypatch.setattr(speed, "_at_speeds", lambda *a: calls.append(len(a[1])) or real(*a))
    passing, clean, force = speed.passing_speeds(spec)
    assert len(calls) == 3, calls
    assert len(passing) == len(clean) == len(force) == 1  # one change at each end of each


def test_the_best_cadence_needs_the_least_effort(village):
    """The best cadence is the speed of least effort among those that pass without a warning: the
    village well's effort still falls above its top (316 deg/s, where the power reaches the 75 W
    a man sustains, a warning), so the best cadence is that top, and any slower speed costs more."""
    spec, r = village
    c = cadence(r)
    assert not c.at_edge and c.searched[0] < c.speed < c.searched[1]
    assert c.power == pytest.approx(spec.wheel_torque * c.speed, rel=1e-15)
    assert c.hand_force < c.effort  # the arms cost effort
    ((lo, hi),) = c.clean_bands
    assert lo <= c.speed <= hi
    assert (
        _at(spec, c.speed).verdict.passed_strict()
        and not _at(spec, hi + math.radians(1)).verdict.passed_strict()
    )
    for step in (0.97, 0.9):  # a slower cadence needs more effort
        assert _at(spec, c.speed * step).effort_peak_force > c.effort
    assert _at(spec, c.speed * 1.03).effort_peak_force < c.effort  # faster is easier, but warns
    assert _at(spec, c.speed).effort_peak_force == pytest.approx(c.effort, rel=1e-9)


def test_no_speed_passes_the_12m_example_and_the_cadence_says_so():
    """At 4 m/s the grip is too fast before the hand force comes within 100 N."""
    r = force_analysis(load_spec(ROOT / "examples" / "well-12m-flywheel.toml"), keep_samples=False)
    c = cadence(r)
    assert all(math.isnan(x) for x in c.passing) and math.isfinite(c.force_range[0])


def test_quasi_static_verify_agrees_and_catches_a_wrong_peak():
    r = force_analysis(load_spec(ROOT / "configs" / "prototype.toml"), keep_samples=False)
    ok = verify_quasi_static(r)
    assert ok.agrees and ok.virtual_work < 1e-8 and ok.sweep_peak <= ok.peak * (1 + 1e-9)
    for wrong in (r.dead_band_peak_force * (1 - 1e-4), r.dead_band_peak_force * (1 + 2e-3)):
        assert not verify_quasi_static(_with_peak(r, wrong)).agrees
    # a peak found for another load: twice the torque, the sweep goes far above it
    designs = dataclasses.replace(r.evaluation.designs, wheel_torque=2 * r.wheel_torque)
    assert not verify_quasi_static(_with(r, designs=designs)).agrees


def _with(r, **fields):
    """The force result ``r`` with its evaluation's ``fields`` replaced (a planted error)."""
    return dataclasses.replace(r, evaluation=dataclasses.replace(r.evaluation, **fields))


def _with_peak(r, peak):
    return _with(r, dead_band_peak_force=np.array([peak]))


@pytest.mark.parametrize("band_deg", [1.0, 0.5])
def test_quasi_static_verify_agrees_at_a_narrow_dead_band(band_deg):
    """Next to a dead centre F ~ 1/(theta - theta_dc), so a sweep of step h = 2 pi / 200,000 stays
    up to h / band below a peak at a band edge (1.6e-3 at 1 deg): the check allows 2 h / band
    there and still refuses a peak set 3 h / band too high."""
    data = spec_to_dict(load_spec(ROOT / "configs" / "prototype.toml"))
    data["operator"]["dead_band"] = band_deg
    r = force_analysis(parse_spec(data), keep_samples=False)
    ok = verify_quasi_static(r)
    h = 2 * math.pi / 200_000
    miss = 1 - ok.sweep_peak / ok.peak
    assert ok.agrees and 0 <= miss <= 2 * h / math.radians(band_deg)
    wrong = r.dead_band_peak_force * (1 + 3 * h / math.radians(band_deg))
    assert not verify_quasi_static(_with_peak(r, wrong)).agrees
