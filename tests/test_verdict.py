"""The one verdict (pumplink.verdict.assess): hand-checkable cases, arrays against scalars, and
every command's verdict coming from it.

Expected outcomes follow from the definitions in docs/models.md §4 (a check fails where the
design is infeasible or the value is beyond its fail limit, warns beyond its warn limit; the
verdict is the worst), worked by hand.
"""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from pumplink.verdict import PART_CHECKS, assess, excess


def test_pass_needs_feasible_and_every_fail_check():
    # limit 100 N: (feasible, mean, peak) -> verdict, by hand
    cases = [
        (True, 60.0, 90.0, True),
        (True, 60.0, 100.0, True),  # at the limit: <= passes
        (True, 60.0, 100.000001, False),
        (True, 101.0, 90.0, False),
        (False, 60.0, 90.0, False),  # infeasible never passes
        (True, 60.0, math.inf, False),  # no finite force suffices
        (True, 60.0, math.nan, False),  # NaN is not a pass
    ]
    for feasible, mean, peak, expected in cases:
        v = assess(feasible, mean, peak, 100.0)
        assert v.passed is expected, (feasible, mean, peak)
        assert isinstance(v.passed, bool)


def test_warnings_never_fail_a_design():
    # every value beyond its warn limit but inside its fail limit (docs/models.md §4)
    v = assess(
        True,
        50.0,
        80.0,
        100.0,
        transmission_angle=40.0,  # warn below 45, fail below 30
        power=120.0,  # warn above 75, fail above 150
        grip_speed=3.0,  # warn above 2.5, fail above 4
        stroke=1.2,  # warn above 1.0
        grip_height=(1.0, 1.4),  # warn above 1.33 (the men's profile, the default)
        axle_height=0.9,  # warn above 0.7
        link_energy_share=230.0,  # warn above 10 %
    )
    assert v.passed is True and v.level == 1 and v.outcome == "PASS with warnings"
    assert v.passed_strict() is False and v.passed_strict(False) is True
    assert [c.key for c in v.warnings] == [
        "link_energy_share",
        "transmission_angle",
        "power",
        "grip_speed",
        "stroke",
        "grip_height",
        "axle_height",
    ]
    assert v["transmission_angle"].relation == ">=" and v["transmission_angle"].limit == 45.0
    assert v["power"].limit == 75.0 and v["link_energy_share"].limit == 10.0
    assert v["grip_height"].value == 1.4 and v["grip_height"].limit == 1.33


@pytest.mark.parametrize(
    ("key", "value", "fail_limit"),
    [
        ("transmission_angle", 12.0, 30.0),  # the 11.65 deg case: a jam risk, fails
        ("power", 154.0, 150.0),  # more than a person gives for an hour
        ("grip_speed", 7.6, 4.0),  # nobody follows a handle at 7.6 m/s
    ],
)
def test_checks_with_a_fail_limit_fail_the_design(key, value, fail_limit):
    v = assess(True, 50.0, 80.0, 100.0, **{key: value})
    assert v.passed is False and v.outcome == "FAIL"
    c = v[key]
    assert c.result == "fail" and c.limit == fail_limit and [f.key for f in v.failures] == [key]


def test_a_clean_design_is_a_plain_pass():
    v = assess(True, 35.0, 86.0, 100.0, transmission_angle=53.4, power=70.7, grip_speed=2.0, stroke=1.0)
    assert v.level == 0 and v.outcome == "PASS" and v.passed_strict() is True and v.warnings == ()


@pytest.mark.parametrize(
    ("height", "limit", "relation", "result"),
    [
        (0.30, 0.40, ">=", "warn"),
        (0.40, 0.70, "<=", "pass"),
        (0.55, 0.70, "<=", "pass"),
        (0.70, 0.70, "<=", "pass"),
        (0.71, 0.70, "<=", "warn"),
    ],
)
def test_axle_height_names_the_limit_it_breaks(height, limit, relation, result):
    c = assess(True, 1.0, 1.0, 100.0, axle_height=height)["axle_height"]
    assert (c.limit, c.relation, c.result) == (limit, relation, result)
    assert c.passed  # a warning never fails the design


def test_optional_checks_are_left_out():
    v = assess(True, 1.0, 2.0, 100.0)
    assert [c.key for c in v.checks] == ["mean_force", "peak_force"]


# ~4 ms each; 60 lists of designs over the checks' warn and fail levels
@settings(max_examples=60)
@given(
    st.lists(
        st.tuples(
            st.booleans(),
            st.floats(0, 300),
            st.one_of(st.floats(0, 300), st.just(math.inf)),
            st.floats(1, 200),
            st.floats(0, 90),
        ),
        min_size=1,
        max_size=20,
    )
)
def test_arrays_decide_as_each_design_alone(rows):
    feasible, mean, peak, limit, gamma = (np.array(c) for c in zip(*rows))
    many = assess(feasible, mean, peak, limit, transmission_angle=gamma)
    for i, row in enumerate(rows):
        one = assess(*row[:4], transmission_angle=row[4])
        assert bool(many.passed[i]) is one.passed
        for cm, c1 in zip(many.checks, one.checks):
            assert bool(cm.passed[i]) is c1.passed


def _grip(speed, **kw):
    """The verdict of one design whose only check beyond a limit can be the grip's speed (warn
    2.1 m/s, fail 3.3 m/s: the women's profile)."""
    return assess(True, 10.0, 10.0, 100.0, grip_speed=speed, grip_speed_limits=(2.1, 3.3), **kw)


def test_a_failing_value_ranks_worse_than_a_warning_one():
    """The searches rank designs by excess: a grip speed just past its fail limit must count more
    than one just under it.  By hand (docs of pumplink.verdict.excess): where warnings count,
    (v - 2.1)/2.1 + max(v - 3.3, 0)/3.3; where they do not, max(v - 3.3, 0)/3.3."""
    warning, failing = _grip(3.29), _grip(3.31)
    assert warning["grip_speed"].result == "warn" and failing["grip_speed"].result == "fail"
    assert excess(warning, False) == pytest.approx(1.19 / 2.1, rel=1e-12)
    assert excess(failing, False) == pytest.approx(1.21 / 2.1 + 0.01 / 3.3, rel=1e-12)
    assert excess(failing, False) > excess(warning, False)
    # a key in ``warned`` counts its warnings even where warnings are accepted
    assert excess(failing, True, warned=("grip_speed",)) > excess(warning, True, warned=("grip_speed",))
    assert excess(warning, True, warned=("grip_speed",)) == pytest.approx(1.19 / 2.1, rel=1e-12)
    # where only failures count, a warning is 0 and a failure its distance beyond the fail limit
    assert excess(warning, True) == 0.0
    assert excess(failing, True) == pytest.approx(0.01 / 3.3, rel=1e-12)
    # a check with only a fail limit (the peak force, 100 N), and one with only a warn limit
    # (the stroke, 1 m): the distance beyond the one limit
    assert excess(assess(True, 10.0, 103.0, 100.0), False) == pytest.approx(0.03, rel=1e-12)
    stroke = assess(True, 10.0, 10.0, 100.0, stroke=1.05)
    assert excess(stroke, False) == pytest.approx(0.05, rel=1e-12) and excess(stroke, True) == 0.0


def test_parts_not_judged_where_another_check_fails_count_nothing():
    """A search judges the part checks only where no other check fails (NaN elsewhere): there
    they count nothing in ``screened`` mode, and the failing check (peak force 103 N against
    100 N: 0.03 by hand) is the excess; where nothing else fails, a NaN part value is a real
    failure and counts ``unbounded``."""
    nan = math.nan
    parts = dict(pin_pressure=nan, handle_fatigue=nan, crank_fatigue=nan)
    failing = assess(True, 10.0, 103.0, 100.0, **parts)
    assert excess(failing, True, 1e3) == pytest.approx(3e3 + 0.03, rel=1e-12)
    assert excess(failing, True, 1e3, screened=PART_CHECKS) == pytest.approx(0.03, rel=1e-12)
    clean = assess(True, 10.0, 90.0, 100.0, **parts)
    assert excess(clean, True, 1e3, screened=PART_CHECKS) == 3e3


# ~2 ms each
@settings(max_examples=100)
@given(st.floats(0.0, 6.0), st.floats(0.0, 6.0), st.booleans())
def test_excess_never_drops_as_a_value_moves_beyond_its_limits(a, b, accept_warnings):
    low, high = sorted((a, b))
    assert excess(_grip(low), accept_warnings) <= excess(_grip(high), accept_warnings)
    # the transmission angle ('>=': warn below 45 deg, fail below 30 deg): the lower, the worse
    angles = (15.0 * low, 15.0 * high)
    lo, hi = (excess(assess(True, 10.0, 10.0, 100.0, transmission_angle=g), accept_warnings) for g in angles)
    assert hi <= lo


def test_every_command_decides_through_assess(monkeypatch, tmp_path):
    """force, speed, batch, optimize and piston pumps all decide through pumplink.verdict.assess,
    called by the one evaluation (its verdict stage, and the piston pumps' evaluation): replace it
    there with one that fails every design and each of them reports FAIL."""
    import pumplink.evaluate.piston
    import pumplink.evaluate.stages
    import pumplink.search.optimize
    import pumplink.search.problem
    import pumplink.studies.force
    import pumplink.studies.speed
    import pumplink.verdict as verdict
    from pumplink.inputs.pump import default_spec

    real = verdict.assess

    def never(feasible, *a, **k):
        v = real(feasible, *a, **k)
        return verdict.Verdict(v.checks, np.full(np.shape(v.level), verdict.FAIL) if np.ndim(v.level) else 2)

    monkeypatch.setattr(pumplink.evaluate.stages, "assess", never)
    monkeypatch.setattr(pumplink.evaluate.piston, "assess", never)
    spec = default_spec()
    assert real(True, 1.0, 1.0, 100.0).passed  # the real one passes such a design
    assert not pumplink.studies.force.force_analysis(spec, keep_samples=False).passed
    from pumplink import batch

    chunk = batch.evaluate_chunk(batch.spec_batch(spec, "default"), 0, 1, 0)
    assert not chunk.passed.any()
    problem = pumplink.search.problem.make_problem(spec)
    result = pumplink.search.optimize.optimize(problem, maxiter=30, polish=False)
    assert not result.best_result.passed and not result.spec_result.passed
    fly = spec.model_copy(update={"wheel": spec.wheel.model_copy(update={"mass": 4.0})})
    assert not pumplink.studies.speed.speed_sweep(fly, [360.0]).passed.any()
    from pumplink.inputs.piston import parse_piston
    from pumplink.studies.piston import force_analysis

    piston = {
        "mechanism": "crank-slider",
        "piston": {"bore": 0.05, "head": 5.0, "efficiency": 0.8},
        "crank_slider": {"crank": 0.05, "rod": 0.3},
        "operator": {"handle": 0.3},
    }
    assert real(True, 1.0, 1.0, 100.0).passed and not force_analysis(parse_piston(piston)).passed
