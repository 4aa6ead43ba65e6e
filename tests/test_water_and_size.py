"""Water beside the force, and `pumplink size` (docs/water.md, docs/operators.md).

The flow is checked against the hand formula written out here with numbers, through the real
command; sizing is checked by what `pumplink force` says of the written spec, and by the physics
that bounds it: the operator's power caps the flow at Q*, so where power binds the share is 1,
and where another limit binds, relaxing that limit raises the share.
"""

from __future__ import annotations

import json
import math
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
CMD = [sys.executable, "-m", "pumplink"]


def pumplink(*args, cwd=ROOT):
    return subprocess.run([*CMD, *map(str, args)], capture_output=True, text=True, cwd=cwd, timeout=600)


ROPE = """\
name = "hand check"
[wheel]
radius = 0.25
mass = 10.0
axle_height = 0.55
[linkage]
L1 = 0.40
D1 = 0.20
b = 0.10
rocker = 0.20
handle = 1.00
swing = 60.0
[load]
head = 10.0
pipe_diameter = 0.023
[operator]
speed = 270.0
"""


def test_the_rope_pumps_flow_is_the_hand_formula(tmp_path):
    """Q = eta_v (pi d^2/4) w r_w with eta_v = 0.87 (docs/water.md §2): 23 mm pipe, 270 deg/s =
    4.712389 rad/s, r_w = 0.25 m; by hand: area 4.15476e-4 m^2, rim speed 1.178097 m/s,
    Q = 0.87 x 4.15476e-4 x 1.178097 = 4.25840e-4 m^3/s = 25.5504 l/min."""
    spec = tmp_path / "rope.toml"
    spec.write_text(ROPE)
    row = json.loads(pumplink("force", spec, "--summary", "--format", "json").stdout)
    area = math.pi * 0.023**2 / 4
    q = 0.87 * area * math.radians(270.0) * 0.25
    assert row["flow_l_min"] == pytest.approx(25.5504, abs=5e-4)
    assert row["flow_l_min"] == pytest.approx(q * 60_000, rel=1e-12)
    assert row["flow_m3_h"] == pytest.approx(q * 3600, rel=1e-12)
    assert row["water_power_W"] == pytest.approx(1000 * 9.81 * 10.0 * q, rel=1e-12)  # rho g H Q
    # the pump's efficiency is water power over the operator's power Mw w: 0.75 x 0.87 = 0.6525
    assert row["pump_efficiency"] == pytest.approx(0.75 * 0.87, rel=1e-12)
    # Q* = eta_f eta_v 75 W / (rho g H), the men's sustained power (the default profile)
    q_star = 0.75 * 0.87 * 75.0 / (1000 * 9.81 * 10.0)
    assert row["power_limited_flow_l_min"] == pytest.approx(q_star * 60_000, rel=1e-12)
    assert row["flow_share"] == pytest.approx(q / q_star, rel=1e-12)
    assert row["people_served"] == pytest.approx(q * 1000 * 8 * 3600 / 20, rel=1e-12)  # 20 l, 8 h a day
    table = pumplink("force", spec, "--summary").stdout
    assert "25.6 l/min (1.53 m³/h) from 10 m" in table


def test_a_spec_with_a_rope_force_says_it_has_no_flow():
    row = json.loads(pumplink("force", "configs/prototype.toml", "--summary", "--format", "json").stdout)
    assert row["flow_l_min"] is None and row["flow_share"] is None
    assert "no flow figure" in pumplink("force", "configs/prototype.toml", "--summary").stdout


def test_the_piston_pumps_flow_is_the_hand_formula():
    """Q = eta_v (pi bore^2/4) H f, single-acting: examples/piston-pump.toml has a 50 mm bore, a
    0.05 m crank with no offset (stroke 0.1 m) at 240 deg/s (f = 2/3 turn a second);
    0.87 x 1.963495e-3 x 0.1 x 0.666667 = 1.138827e-4 m^3/s = 6.83296 l/min."""
    row = json.loads(pumplink("force", "examples/piston-pump.toml", "--summary", "--format", "json").stdout)
    q = 0.87 * math.pi * 0.05**2 / 4 * 0.1 * (240.0 / 360.0)
    assert row["flow_l_min"] == pytest.approx(6.83296, abs=5e-5)
    assert row["flow_l_min"] == pytest.approx(q * 60_000, rel=1e-9)
    assert row["water_power_W"] == pytest.approx(1000 * 9.81 * 10.0 * q, rel=1e-9)


def test_a_profile_changes_the_limits_the_verdict_judges(tmp_path):
    spec = tmp_path / "women.toml"
    spec.write_text(ROPE.replace("speed = 270.0", 'speed = 270.0\nprofile = "women"'))
    row = json.loads(pumplink("force", spec, "--summary", "--format", "json").stdout)
    checks = {c["key"]: c for c in row["checks"]}
    assert row["operator_profile"] == "women" and row["force_limit_N"] == 70.0
    assert checks["power"]["warn_limit"] == 60.0 and checks["grip_speed"]["warn_limit"] == 2.1
    assert checks["grip_height"]["warn_limit"] in (0.83, 1.23)


def test_size_finds_a_pump_that_force_passes_with_the_same_water(tmp_path):
    out = tmp_path / "sized.toml"
    r = pumplink("size", "--head", "8", "--pipes", "25.4mm", "--format", "json", "--write", out)
    assert r.returncode == 0, r.stderr
    row = json.loads(r.stdout)
    assert row["found"] and row["verdict"] == "PASS"
    force = pumplink("force", out, "--summary", "--format", "json")
    assert force.returncode == 0
    checked = json.loads(force.stdout)
    assert checked["verdict"] == "PASS"
    assert checked["flow_l_min"] == pytest.approx(row["flow_l_min"], rel=1e-12)
    # the time and the turns to fill a 20-litre container (Eq. W.7, by hand from the written spec)
    t = 20.0 / checked["flow_l_min"] * 60.0
    assert row["fill_time_20l_s"] == pytest.approx(t, rel=1e-12)
    assert row["fill_turns_20l"] == pytest.approx(t * checked["speed_deg_s"] / 360.0, rel=1e-12)
    assert (
        f"time to fill a 20-litre container: {t:.0f} s"
        in pumplink("size", "--head", "8", "--pipes", "25.4mm").stdout
    )
    # the cadence and the rope speed it recommends are inside the field's ranges (30-60 turns a
    # minute, 0.6-1.8 m/s), by hand from the written spec: deg/s over 6, rad/s times the radius
    turns = checked["speed_deg_s"] / 6.0
    rope = math.radians(checked["speed_deg_s"]) * row["design"]["wheel_radius_m"]
    assert row["cadence_per_min"] == pytest.approx(turns, rel=1e-12) and 30.0 <= turns <= 60.0
    assert row["rope_speed_m_s"] == pytest.approx(rope, rel=1e-12) and 0.6 <= rope <= 1.8
    # the operator's power is the limit that binds: the flow is Q*, to the cadence's 1 deg/s rounding
    assert "power" in row["binding"]
    assert 0.99 <= row["flow_share"] <= 1.0
    # the duties (docs/water.md §6) with the constants deciding: Q = 0.75 x 0.87 x P / (rho g H)
    assert row["losses"] == "constant"
    for key, power in (("all_day_flow_l_min", 75.0), ("filling_flow_l_min", 81.0)):
        assert row[key] == pytest.approx(0.75 * 0.87 * power / (9810.0 * 8.0) * 60_000, rel=1e-12)


@pytest.mark.parametrize("seed, limit", [(10, "peak_force"), (11, "grip_height")])
def test_the_rounded_design_meets_a_limit_a_slower_wheel_does_not_help(seed, limit):
    """The search's optimum touches its limits, and rounding it to workshop figures can step over
    one.  For these two starts (8 m, 1" pipe, men) the limit stepped over is the flywheel's peak
    force (a slower wheel stores less energy: the peak rises) and the grip's height (the cadence
    does not move it), so slowing the cadence, the old repair, gave up 30 deg/s later with no
    design; stepping each workshop figure back finds one with the optimum's water (share >= 0.99
    of Q*, the cadence's 1 deg/s rounding).  ~1.2 s each."""
    from pumplink.inputs.pump import default_spec
    from pumplink.search import size as S

    result = S.size(S.problem_for(default_spec(), head=8.0, pipes=[0.0254]), seed=seed)
    assert result.found and int(result.best.evaluation.verdict.level[0]) == 0
    assert limit in result.binding and "power" in result.binding
    assert float(result.best.evaluation.water.share[0]) >= 0.99


def test_a_three_quarter_inch_pipe_beats_the_half_inch_rope_speed_cap_at_15_m_for_women():
    """At 15 m for a woman the ½" pipe is held by the rope's 1.8 m/s (docs/water.md §2a): even with
    no leakage (eta_v = 1) its flow cannot pass (pi/4) 0.0127² m² x 1.8 m/s = 13.68 l/min (by
    hand).  A ¾" pipe meets the limits with more water; the search's best design misses them by a
    hair (cadence, grip speed and peak force all bind) and the workshop steps close the miss.
    ~2 s."""
    from pumplink.inputs.pump import default_spec
    from pumplink.search import size as S

    cap = math.pi / 4 * 0.0127**2 * 1.8 * 60_000
    assert cap == pytest.approx(13.68, abs=0.005)
    result = S.size(S.problem_for(default_spec(), head=15.0, profile="women", pipes=[0.01905]))
    assert result.found and int(result.best.evaluation.verdict.level[0]) == 0
    assert result.best.flow * 60_000 > cap


def test_a_base_spec_with_parts_searches_the_same_bores():
    """configs/village-10m.toml gives [parts], whose checks a search judges only where nothing else
    fails (NaN elsewhere).  Counting that NaN as unbounded ranked every design that failed anything
    below one with no crank-rocker, and the ¾" search ended on one; now the base-spec route finds
    the ¾" pump the built-in route does (above).  ~4 s."""
    from pumplink.inputs.pump import load_spec
    from pumplink.search import size as S

    village = load_spec(ROOT / "configs" / "village-10m.toml")
    result = S.size(S.problem_for(village, head=15.0, profile="women", pipes=[0.01905]))
    assert result.found and int(result.best.evaluation.verdict.level[0]) == 0
    assert result.best.flow * 60_000 > math.pi / 4 * 0.0127**2 * 1.8 * 60_000  # 13.68 l/min, above


#: The spec keys that set each check's limits (the operator profile's, overridden).
RELAX = {
    "mean_force": {"force_limit": 1.5},
    "peak_force": {"force_limit": 1.5},
    "grip_speed": {"grip_speed_warn": 1.5, "grip_speed_fail": 1.5},
}


def test_relaxing_the_limit_that_binds_raises_the_share():
    """An operator of limited strength (the accessible profile) at 5 m through a 12.7 mm pipe:
    something other than the power holds the flow below Q*, and the output names it; the same
    search with that limit 1.5 times as loose gives a larger share of the same Q*."""
    from pumplink.inputs.pump import default_spec, parse_spec, spec_to_dict
    from pumplink.search import size as S

    problem = S.problem_for(default_spec(), head=5.0, profile="accessible", pipes=[0.0127])
    base = S.size(problem, maxiter=20)
    low = float(base.best.evaluation.water.share[0])
    assert base.found and low < 0.9 and "power" not in base.binding
    check = next(b for b in base.binding if b in RELAX)
    limits = base.best.spec.operator.limits
    data = spec_to_dict(problem.spec)
    for key, factor in RELAX[check].items():
        data["operator"][key] = getattr(limits, key) * factor
    relaxed = S.size(S.SizeProblem(parse_spec(data), problem.pipes, problem.bounds), maxiter=20)
    high = float(relaxed.best.evaluation.water.share[0])
    assert relaxed.found and high > low + 0.05, (check, low, high)


def test_size_says_in_one_sentence_what_holds_every_design_back():
    r = pumplink("size", "--head", "60", "--profile", "children", "--pipes", "25mm", "--format", "json")
    assert r.returncode == 1
    row = json.loads(r.stdout)
    assert not row["found"] and row["reason"].startswith("no design with a 25 mm pipe meets the limits")
    assert "\n" not in row["reason"]


def test_size_needs_a_head():
    r = pumplink("size", "configs/prototype.toml")
    assert r.returncode == 2 and "head" in r.stderr and r.stderr.count("\n") == 1


#: The operators' sustained power [W], docs/operators.md §1 (Q* is the flow it lifts, docs/water.md §4).
SUSTAINED_W = {"men": 75.0, "women": 60.0, "children": 33.0, "accessible": 25.0}


def _water(spec_text: str, **tables) -> dict:
    """``force --summary --format json``'s row of a spec, in process (the entry point is tested
    above): ``tables`` add or replace keys of the spec's tables."""
    import tomllib

    import pumplink

    spec = tomllib.loads(spec_text)
    for table, keys in tables.items():
        spec.setdefault(table, {}).update(keys)
    return pumplink.to_dict(pumplink.analyse(pumplink.load(spec)))


@pytest.mark.parametrize("profile", list(SUSTAINED_W))
def test_q_star_is_each_profiles_own_sustained_power_over_the_lift(profile):
    """Q* = eta_f eta_v P_sustained / (rho g H) with the profile's own sustained power (Eq. W.5):
    the hand check's 10 m through the default efficiencies 0.75 and 0.87, so Q* = 0.6525 P / 98,100
    m^3/s (men 29.93 l/min, women 23.94, children 13.17, accessible 9.98), and the share Q / Q*."""
    row = _water(ROPE, operator={"profile": profile})
    q = 0.87 * math.pi * 0.023**2 / 4 * math.radians(270.0) * 0.25
    q_star = 0.75 * 0.87 * SUSTAINED_W[profile] / (1000 * 9.81 * 10.0)
    assert row["operator_profile"] == profile
    assert row["power_limited_flow_l_min"] == pytest.approx(q_star * 60_000, rel=1e-12)
    assert row["flow_share"] == pytest.approx(q / q_star, rel=1e-12)


def test_the_specs_volumetric_efficiency_sets_the_flow_and_q_star():
    """load.volumetric_efficiency = 0.6 instead of the default 0.87: Q = 0.6 (pi d^2/4) w r_w =
    0.6 x 4.15476e-4 x 1.178097 = 2.93683e-4 m^3/s = 17.621 l/min, the pump's efficiency 0.75 x 0.6,
    Q* = 0.75 x 0.6 x 75 W / (rho g H) = 20.642 l/min, the water power rho g H Q; the rope force, so
    the operator's power, does not change (64.02 W: eta_v is leakage, not friction)."""
    row = _water(ROPE, load={"volumetric_efficiency": 0.6})
    q = 0.6 * math.pi * 0.023**2 / 4 * math.radians(270.0) * 0.25
    assert row["flow_l_min"] == pytest.approx(17.621, abs=5e-4)
    assert row["flow_l_min"] == pytest.approx(q * 60_000, rel=1e-12)
    assert row["water_power_W"] == pytest.approx(1000 * 9.81 * 10.0 * q, rel=1e-12)
    assert row["pump_efficiency"] == pytest.approx(0.75 * 0.6, rel=1e-12)
    assert row["power_limited_flow_l_min"] == pytest.approx(0.75 * 0.6 * 75.0 / 98_100 * 60_000, rel=1e-12)
    assert row["power_W"] == pytest.approx(13.586053 * math.radians(270.0), rel=1e-7)


def test_the_specs_use_table_sets_the_people_served():
    """use.hours_per_day = 5 and use.litres_per_person_day = 15 (defaults 8 and 20): people = Q x
    5 h x 3600 s / 0.015 m^3 with the hand check's Q = 4.25840e-4 m^3/s, 511.0 people (613.2 with
    the defaults)."""
    q = 0.87 * math.pi * 0.023**2 / 4 * math.radians(270.0) * 0.25
    row = _water(ROPE, use={"hours_per_day": 5.0, "litres_per_person_day": 15.0})
    assert row["people_served"] == pytest.approx(q * 5 * 3600 / 0.015, rel=1e-12)
    assert row["people_served"] == pytest.approx(511.0, abs=0.05)
    hours_only = _water(ROPE, use={"hours_per_day": 5.0})
    assert hours_only["people_served"] == pytest.approx(q * 5 * 3600 / 0.020, rel=1e-12)
