"""The one verdict (pumplink.verdict.assess): hand-checkable cases, arrays against scalars, and
every command's verdict coming from it.

Expected outcomes follow from the definitions in docs/models.md §4 (a check passes iff the
design is feasible and value <= limit, or >= for the transmission angle), worked by hand.
"""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from pumplink.verdict import assess


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
    v = assess(
        True,
        50.0,
        80.0,
        100.0,
        transmission_angle=12.0,
        power=154.0,
        axle_height=0.9,
        link_energy_share=230.0,
    )
    assert v.passed is True
    assert [c.key for c in v.warnings] == ["link_energy_share", "transmission_angle", "power", "axle_height"]
    assert v["transmission_angle"].relation == ">=" and v["transmission_angle"].limit == 45.0
    assert v["power"].limit == 75.0 and v["link_energy_share"].limit == 10.0


@pytest.mark.parametrize(
    ("height", "limit", "relation", "ok"),
    [
        (0.30, 0.40, ">=", False),
        (0.40, 0.70, "<=", True),
        (0.55, 0.70, "<=", True),
        (0.70, 0.70, "<=", True),
        (0.71, 0.70, "<=", False),
    ],
)
def test_axle_height_names_the_limit_it_breaks(height, limit, relation, ok):
    c = assess(True, 1.0, 1.0, 100.0, axle_height=height)["axle_height"]
    assert (c.limit, c.relation, c.passed) == (limit, relation, ok)


def test_optional_checks_are_left_out():
    v = assess(True, 1.0, 2.0, 100.0)
    assert [c.key for c in v.checks] == ["mean_force", "peak_force"]


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


def test_every_command_decides_through_assess(monkeypatch, tmp_path):
    """force, speed, batch and optimize all call pumplink.verdict.assess: replace it with one that
    fails every design and each of them reports FAIL."""
    import pumplink.analysis
    import pumplink.batch.runner
    import pumplink.optimize
    import pumplink.verdict as verdict
    from pumplink.spec import default_spec

    real = verdict.assess

    def never(feasible, *a, **k):
        v = real(feasible, *a, **k)
        return verdict.Verdict(v.checks, np.zeros_like(np.asarray(v.passed)) if np.ndim(v.passed) else False)

    for module in (pumplink.analysis, pumplink.batch.runner, pumplink.optimize):
        monkeypatch.setattr(module, "assess", never)
    spec = default_spec()
    assert real(True, 1.0, 1.0, 100.0).passed  # the real one passes such a design
    assert not pumplink.analysis.force_analysis(spec, keep_samples=False).passed
    from pumplink import batch

    chunk = batch.evaluate_chunk(batch.spec_batch(spec, "default"), 0, 1, 0)
    assert not chunk.passed.any()
    problem = pumplink.optimize.make_problem(spec)
    e = pumplink.optimize.evaluate_designs(problem, np.array([[0.2], [0.4], [0.2], [60.0]]))
    assert not e.passed.any()
    fly = spec.model_copy(update={"wheel": spec.wheel.model_copy(update={"mass": 4.0})})
    assert not pumplink.analysis.speed_sweep(fly, [360.0]).passed.any()
