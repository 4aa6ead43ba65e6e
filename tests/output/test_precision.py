"""The rounding rules of pumplink/output/precision.py on hand-worked cases, and the optimum's sentence.

The expected values are worked by hand from the rules as docs/json.md ("Digits") states them; the
figures are the ones docs/optimize.md's example printed on three processors before the rules
(the binding slacks 4.223e-11, 7.961e-11, 7.853e-10, 5.294e-13 m, all one constraint that binds).
"""

from __future__ import annotations

import math

import pytest

from pumplink.output import precision as p
from pumplink.output.optimize import improvement_line


def test_a_binding_slack_is_zero_whatever_noise_the_solver_left():
    for noise in (4.223e-11, 7.961e-11, 7.853e-10, 5.294e-13, 0.0):
        assert p.slack(noise, True, 1e-8, 1.33 - noise) == 0.0


def test_a_slack_keeps_the_last_decimal_of_the_figure_it_bounds():
    # the lowest grip height 1.196 m (4 significant digits at tol 1e-8) above 0.9 m: 0.296 m
    assert p.slack(0.2960254037294491, False, 1e-8, 1.196025403729449) == 0.296
    # a slack that is its own figure (the crank-rocker's margin [deg]): 4 significant digits
    assert p.slack(48.166240100932306, False, 1e-8, 48.166240100932306) == 48.17
    # the village well's highest grip height, 1.33 m less 1.3239585 m here, 1.3239659 m with
    # OPENBLAS_CORETYPE=Haswell (0.006041 and 0.006034 m at 4 significant digits): the grip height
    # is known to 1.324 m, so the slack to the millimetre
    for grip in (1.3239585437748773, 1.3239659):
        assert p.slack(1.33 - grip, False, 1e-8, grip) == 0.006


def test_an_optimum_keeps_the_digits_the_square_root_of_its_tolerance_leaves():
    assert p.optimum_digits(1e-8) == 4  # sqrt = 1e-4
    assert p.optimum_digits(1e-6) == 3
    # the optimum's coordinates on three processors (docs/optimize.md's example): one answer
    for rocker in (0.12193481273322301, 0.12193481266870358, 0.12193481272492035):
        assert p.at_optimum(rocker, 1e-8) == 0.1219
    for l1 in (0.9999999999992973, 0.9999999778701483, 0.9999999999998536):
        assert p.at_optimum(l1, 1e-8) == 1.0
    assert p.optimum_text(1.0, 1e-8) == "1.000" and p.optimum_text(60.0, 1e-8) == "60.00"
    assert p.optimum_text(0.12193481, 1e-8) == "0.1219" and p.optimum_text(math.inf, 1e-8, "∞") == "∞"


def test_a_difference_below_the_optimums_last_digit_is_zero():
    # 66.64 N carries 2 decimals: a gain of 1.1e-10 N is none, 19.190125 N is 19.19 N
    assert p.difference(-1.1439027503001853e-10, 35.342917, 1e-8) == 0.0
    assert p.difference(19.190125489890974, 66.640259, 1e-8) == 19.19
    assert p.difference(0.004, 123.4567, 1e-8) == 0.0  # 123.5 N: one decimal


def test_a_figure_known_to_rtol_keeps_one_digit_back():
    assert p.digits(1e-7) == 6 and p.digits(1e-6) == 5 and p.digits(1e-10 * 100) == 7
    # the best cadence, found to 1e-7, here and with its search's tolerance loosened ten times
    assert p.known_to(409.7646442994298, 1e-7) == p.known_to(409.76468345024193, 1e-7) == 409.765
    assert p.known_text(316.0000, 1e-6) == "316.00" and p.known_text(0.19999999830082774, 1e-6) == "0.20000"


def test_a_root_keeps_no_digit_below_ten_times_its_bracket():
    # brentq to 1e-9 of a best speed of 409.76 deg/s: bracket 4.1e-7, so 5 decimals
    assert p.to_bracket(300.90121601458327, 4.1e-7) == p.to_bracket(300.90121627474394, 4.1e-7) == 300.90122
    assert p.to_bracket(None, 1e-7) is None


def test_a_residual_within_its_tolerance_is_zero():
    assert p.residual(2.618791670840044e-09, 1e-6) == 0.0
    assert p.residual(1e-6, 1e-6) == 0.0
    assert p.residual(3.2e-5, 1e-6) == 3.2e-5  # a check that fails keeps its residual
    assert p.residual(float("nan"), 1e-6) is None


def _row(objective: str, spec: float, optimum: float, gain: float, pct: float, violated=()) -> dict:
    key = "peak_force_N" if objective == "peak" else "mean_force_N"
    return {
        "objective": objective,
        "tolerance": 1e-8,
        "spec_design": {key: spec, "violated": list(violated)},
        "optimum": {key: optimum},
        "improvement_N": gain,
        "improvement_pct": pct,
    }


@pytest.mark.parametrize(
    "row,line",
    [
        (
            _row("peak", 85.83, 66.64, 19.19, 22.36),
            "peak force 85.83 N → 66.64 N (22.4 % lower than the spec's own design)",
        ),
        (
            _row("mean", 35.342917, 35.34, 0.0, 0.0),
            "mean force 35.34 N → 35.34 N (the spec's own design needs the same)",
        ),
        (
            _row("peak", 60.0, 61.25, -1.25, -2.083, ["grip stroke <= 1 m"]),
            "the optimum needs 1.250 N more than the spec's own design, which breaks: grip stroke <= 1 m",
        ),
    ],
)
def test_the_optimums_gain_in_words_has_no_sign_against_its_words(row, line):
    """'+22.4 % lower' said the same thing twice with a sign that read as 'higher'."""
    assert improvement_line(row) == line
