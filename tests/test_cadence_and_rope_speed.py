"""The verdict's cadence and rope-speed checks (docs/models.md §4, docs/operators.md §6,
docs/water.md §2a), judged by ``pumplink.analyse`` as every command judges.

Expected values by hand: the cadence is the wheel speed in deg/s over 6 (360 deg a turn, 60 s a
minute), the rope speed the wheel speed in rad/s times the wheel radius; the limits are the
published ones (the Harare trial's 30 turns a minute, the AIT tests' 60; the rope-speed range
0.6-1.8 m/s around Akvopedia's best 1.2 m/s).
"""

import math

import pytest

import pumplink
from pumplink.errors import SpecError

HARARE_SLOWEST, AIT_FASTEST = 30.0, 60.0  # turns a minute (docs/operators.md §6)
ROPE_SLOWEST, ROPE_FASTEST = 0.6, 1.8  # m/s (docs/water.md §2a)


def _checks(speed_deg_s: float, radius: float, **operator) -> dict:
    spec = {
        "name": "cadence check",
        "wheel": {"radius": radius},
        "linkage": {"L1": 0.40, "D1": 0.20, "b": 0.10, "rocker": 0.20, "handle": 1.00, "swing": 60.0},
        "load": {"rope_force": 20.0},
        "operator": {"speed": speed_deg_s, **operator},
    }
    row = pumplink.to_dict(pumplink.analyse(pumplink.load(spec)))
    return {c["key"]: c for c in row["checks"]}


@pytest.mark.parametrize(
    ("turns", "result"),
    [(29.0, "warn"), (30.0, "pass"), (45.0, "pass"), (60.0, "pass"), (61.0, "warn")],
)
def test_the_cadence_warns_outside_30_to_60_turns_a_minute(turns, result):
    """A 0.2 m wheel keeps the rope inside its range from 29 to 61 turns a minute (0.61-1.28 m/s):
    only the cadence check speaks."""
    checks = _checks(turns * 6.0, 0.2)
    c = checks["cadence"]
    assert c["value"] == pytest.approx(turns, rel=1e-12) and c["unit"] == "/min"
    assert c["result"] == result and c["fail_limit"] is None
    assert c["warn_limit"] == (HARARE_SLOWEST if turns < HARARE_SLOWEST else AIT_FASTEST)  # the side it is on
    assert checks["rope_speed"]["result"] == "pass"


@pytest.mark.parametrize(("rope", "result"), [(0.59, "warn"), (0.61, "pass"), (1.79, "pass"), (1.81, "warn")])
def test_the_rope_speed_warns_outside_0_6_to_1_8_m_s(rope, result):
    """At 45 turns a minute (inside the cadence range) the wheel radius sets the rope speed."""
    radius = rope / (2 * math.pi * 45.0 / 60.0)
    checks = _checks(270.0, radius)
    r = checks["rope_speed"]
    assert r["value"] == pytest.approx(rope, rel=1e-12) and r["unit"] == "m/s"
    assert r["result"] == result and r["fail_limit"] is None
    assert r["warn_limit"] == (ROPE_SLOWEST if rope < ROPE_SLOWEST else ROPE_FASTEST)
    assert checks["cadence"]["result"] == "pass"


def test_the_spec_can_narrow_the_cadence_range_to_the_harare_preference():
    """operator.cadence_max = 50 (the Harare trial's preferred upper end) warns at 55 turns."""
    assert _checks(330.0, 0.2)["cadence"]["result"] == "pass"
    narrowed = _checks(330.0, 0.2, cadence_max=50.0)["cadence"]
    assert narrowed["result"] == "warn" and narrowed["warn_limit"] == 50.0
    with pytest.raises(SpecError, match="cadence_min must be below operator.cadence_max"):
        _checks(330.0, 0.2, cadence_min=70.0)


def test_a_batch_has_a_column_for_each_new_check():
    from pumplink.output.batchfiles import CHECK_COLUMNS

    assert {"check_cadence", "check_rope_speed"} <= set(CHECK_COLUMNS)


def test_a_flow_search_that_varies_the_speed_keeps_the_cadence_and_rope_in_range():
    """optimize --objective flow: the verdict's constraint also holds the cadence and the rope speed
    in their ranges where the search varies the speed (they only warn). The village pump at
    480 deg/s, 80 turns a minute and 2.094 m/s of rope, breaks it by (80 − 60)/60 + (2.0944 −
    1.8)/1.8 = 0.4969 (no check fails there); at its own 316 deg/s nothing; varying the linkage
    alone leaves the constraint as it was."""
    import numpy as np

    from pumplink.inputs.pump import load_spec
    from pumplink.search import problem as P

    spec = load_spec("configs/village-10m.toml")
    varied = P.make_problem(spec, {"operator.speed": (60.0, 540.0)}, objective="flow")
    assert varied.constraint_names()[-1].endswith("the cadence and the rope speed in range")
    slack = P.evaluate_designs(varied, np.array([[480.0, 316.0]])).slack[-1]
    hand = (80 - 60) / 60 + (math.radians(480.0) * 0.25 - 1.8) / 1.8
    assert slack[0] == pytest.approx(-hand, rel=1e-9) and slack[1] == 0.0
    linkage = P.make_problem(spec, {"swing": (30.0, 100.0)}, objective="flow")
    assert linkage.constraint_names()[-1] == "no check of the verdict fails"


def test_speeds_where_the_cadence_warns_are_not_said_to_pass_every_check(monkeypatch):
    """configs/women-operators-6m.toml at 300 deg/s fails its peak force; the verdict line names
    the faster speeds where no check fails.  Above 60 turns a minute (360 deg/s, by hand: 60 x 6)
    the cadence warns there, so the words are "no check fails" with the clean band ending at
    360 deg/s, never "every check passes"."""
    from pathlib import Path

    from in_process import keep_process_state, run_main

    spec = Path(__file__).resolve().parents[1] / "configs" / "women-operators-6m.toml"
    state = keep_process_state(monkeypatch)
    next(state)
    code, out, _ = run_main("force", spec, "--speed", "300", "--summary")
    next(state, None)
    line = " ".join(out.split())
    assert code == 1 and "VERDICT: FAIL" in line and "every check passes" not in line
    assert f"none warns from 358 to {AIT_FASTEST * 6:.0f} deg/s" in line
    assert "; no check fails at a mean from 358 to " in line
