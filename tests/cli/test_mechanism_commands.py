"""The textbook-mechanism commands and the piston-pump spec through the real entry point.

Exit codes (0 / 1 infeasible or FAIL / 2 bad input), one-line errors, 80-column tables, the
--help examples (run in a temporary copy of configs/ and examples/), the structure configs.
"""

import json
import math
import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
CMD = [sys.executable, "-m", "pumplink"]


def run(*args, cwd=ROOT):
    env = {k: v for k, v in os.environ.items() if k not in ("FORCE_COLOR", "COLUMNS")}
    env.update(NO_COLOR="1", PYTHONIOENCODING="utf-8", PYTHONPATH=str(ROOT))
    return subprocess.run(
        [*CMD, *map(str, args)], capture_output=True, text=True, env=env, cwd=cwd, timeout=300
    )


def one_line_error(p, code):
    assert p.returncode == code, (p.returncode, p.stdout, p.stderr)
    assert "Traceback" not in p.stderr
    lines = p.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: "), p.stderr
    return lines[0]


def fits_80(text):
    long = [line for line in text.splitlines() if len(line.rstrip()) > 80]
    assert not long, long


# The commands' --help examples run, with their output checked, in tests/cli/test_help_examples.py.


def docs_examples():
    """The indented `pumplink ...` example lines of docs/mechanisms.md (comments stripped)."""
    text = (ROOT / "docs" / "mechanisms.md").read_text(encoding="utf-8")
    return [m.split("#")[0].split() for m in re.findall(r"^    (pumplink .+)$", text, re.M)]


def test_docs_examples_run():
    found = docs_examples()
    assert {e[1] for e in found} >= {"slider", "slotted"}
    for ex in found:
        p = run(*ex[1:])
        assert p.returncode == 0 and "Traceback" not in p.stderr, (ex, p.stderr)


#: The cases tests/cli/test_80_columns.py does not run (it runs every shipped spec and the
#: commands' other table views).
@pytest.mark.parametrize(
    "args",
    [
        ["slider", "--stroke", "0.1", "--rod-ratio", "4"],
        ["rocker", "--time-ratio", "3", "--swing", "170", "--rocker", "1"],
        ["slotted", "--time-ratio", "1.7", "--crank", "30", "--stroke", "120"],
        ["slotted", "--crank", "120", "--frame", "300"],
        ["transmission", "--swing", "179.9999"],
        ["force", "examples/piston-pump.toml"],
    ],
)
def test_tables_fit_80_columns(args):
    p = run(*args)
    assert p.returncode in (0, 1), p.stderr
    fits_80(p.stdout)
    assert "\x1b" not in p.stdout


def test_slider_json_matches_the_request():
    p = run("slider", "--stroke", "0.1", "--rod-ratio", "4", "--time-ratio", "1.2", "--format", "json")
    out = json.loads(p.stdout)
    assert p.returncode == 0 and out["simulation_agrees"] and out["simulation"] == "agrees"
    assert out["indicators"]["time_ratio"]["simulated"] == pytest.approx(1.2, rel=1e-12)
    assert out["indicators"]["stroke"]["simulated"] == pytest.approx(0.1, rel=1e-12)


@pytest.mark.parametrize(
    "args, words",
    [
        (["slider", "--stroke", "1", "--rod-ratio", "3", "--time-ratio", "2"], "below 2"),
        (["slider", "--stroke", "1", "--rod-ratio", "1.5", "--offset-ratio", "0.5"], "longer than crank"),
        (["slotted", "--time-ratio", "1", "--stroke", "0.3"], "K = 1"),
        (["slotted", "--time-ratio", "1.5", "--stroke", "0.3", "--frame", "1"], "cannot hold"),
        (
            ["rocker", "--time-ratio", "1.25", "--swing", "50", "--rocker", "0.3", "--frame", "3"],
            "frame lengths",
        ),
        (["rocker", "--swing", "50", "--rocker", "0.3", "--pivot=0,0.1"], "one side"),
    ],
)
def test_outside_realisability_one_sentence_exit_1(args, words):
    line = one_line_error(run(*args), 1)
    assert words in line
    assert run(*args).stdout == ""  # never a mechanism that cannot turn


@pytest.mark.parametrize(
    "args, words",
    [
        (["slider", "--stroke", "-1", "--rod-ratio", "3"], "--stroke"),
        (["slider", "--stroke", "1", "--rod-ratio", "3", "--time-ratio", "0.5"], "--time-ratio"),
        (["rocker", "--swing", "50", "--rocker", "0.3", "--pivot", "x"], "--pivot"),
        (["rocker", "--swing", "200", "--rocker", "0.3", "-k", "1.2"], "--swing"),
        (["structure", "configs/prototype.toml"], "not a mechanism file"),
        (["synth", "examples/piston-pump.toml"], "piston-pump spec"),
        (["force", "examples/piston-pump.toml", "--plot", "p.png"], "--plot"),
    ],
)
def test_bad_input_one_line_exit_2(args, words):
    assert words in one_line_error(run(*args), 2)


def test_structure_shipped_configs():
    six = json.loads(run("structure", "configs/mechanisms/six-link.toml", "-f", "json").stdout)
    assert (six["moving_links"], six["lower_pairs"], six["higher_pairs"], six["mobility"]) == (5, 7, 0, 1)
    assert [g["links"] for g in six["groups"]] == [["2", "3"], ["4", "5"]]
    assert [g["dyad_type"] for g in six["groups"]] == ["RRR", "RRP"]
    dp = json.loads(run("structure", "configs/mechanisms/double-parallelogram.toml", "-f", "json").stdout)
    assert (dp["formula_mobility"], dp["redundant_constraints"], dp["mobility"]) == (0, 1, 1)


def test_structure_errors_name_the_key(tmp_path):
    f = tmp_path / "m.toml"
    f.write_text('frame = "0"\nlinks = ["0", "1"]\n[joints]\nA = { kind = "hinge", links = ["0", "1"] }\n')
    assert "joints.A.kind" in one_line_error(run("structure", f), 2)
    f.write_text(
        'frame = "0"\nlinks = ["0", "1", "2"]\n[joints]\nA = { kind = "revolute", links = ["0", "1"] }\n'
        'B = { kind = "revolute", links = ["1", "2"] }\nC = { kind = "revolute", links = ["2", "0"] }\n'
    )
    p = run("structure", f)  # a triangle: W = 0, a structure
    assert p.returncode == 1 and "NOT DECOMPOSED" in p.stdout


def test_piston_force_and_batch():
    out = json.loads(run("force", "examples/piston-pump.toml", "--summary", "-f", "json").stdout)
    assert out["pass"] and out["verdict"] == "PASS" and out["mechanism"] == "crank-slider"
    p = run("batch", "configs/grids/piston-bore.toml", "-f", "json")
    rows = json.loads(p.stdout)
    assert p.returncode == 1 and rows["total"] == 8 and rows["failed"] == 3
    assert run("batch", "configs/grids/piston-bore.toml", "--fail-on", "none").returncode == 0
    line = one_line_error(run("batch", "configs/grids/piston-bore.toml", "configs/prototype.toml"), 2)
    assert "separate runs" in line


# ----------------------------------------------------------------------------- the textbook's forms
def _json(*args, code=0):
    p = run(*args, "--format", "json")
    assert p.returncode == code, (p.returncode, p.stderr)
    return json.loads(p.stdout)


def test_slotted_from_the_crank_as_khurmi_states_it():
    """Khurmi & Gupta, Theory of Machines, Example 5.3: driving crank 30 mm, time ratio 1.7,
    working stroke 120 mm; find the centre distance AC and the slotted lever AP.  By hand:
    half the swing is 90 deg * 0.7/2.7, AC = 30/sin(23.333 deg) = 75.742 mm,
    AP = 120/(2 sin(23.333 deg)) = 151.485 mm."""
    out = _json("slotted", "--time-ratio", "1.7", "--crank", "30", "--stroke", "120")
    half = math.radians(90 * 0.7 / 2.7)
    assert out["lengths"]["frame"] == pytest.approx(30 / math.sin(half), rel=1e-12)
    assert out["lengths"]["lever"] == pytest.approx(60 / math.sin(half), rel=1e-12)
    assert out["verdict"] == "PASS" and out["simulation"] == "agrees"


def test_slotted_analysis_as_khurmi_states_it():
    """Khurmi & Gupta, Example 5.2: centre distance 240 mm, crank 120 mm, slotted lever 450 mm;
    printed answers: inclination of the slotted bar to the vertical 30 deg, time ratio 2,
    stroke 450 mm.  Example 5.1: 300 mm and 120 mm, printed ratio 1.7 (1.714 by hand:
    alpha = 2 acos(0.4), K = (360 deg - alpha)/alpha)."""
    out = _json("slotted", "--crank", "120", "--frame", "240", "--lever", "450")
    ind = out["indicators"]
    assert ind["lever_inclination"]["simulated"] == pytest.approx(30.0, abs=1e-9)
    assert ind["time_ratio"]["simulated"] == pytest.approx(2.0, rel=1e-12)
    assert ind["stroke"]["simulated"] == pytest.approx(450.0, rel=1e-12)
    k = _json("slotted", "--crank", "120", "--frame", "300")["indicators"]["time_ratio"]["simulated"]
    alpha = 2 * math.acos(0.4)
    assert k == pytest.approx((2 * math.pi - alpha) / alpha, rel=1e-12) and round(k, 1) == 1.7


def test_slotted_crank_and_time_ratio_alone():
    """'Crank 300 mm, time ratio 2': sin(psi/2) = 1/2 by hand, frame 600, the shortest lever
    900 (= frame + crank), stroke 2 * 900 * 1/2 = 900."""
    out = _json("slotted", "--crank", "300", "--time-ratio", "2")
    assert out["lengths"] == pytest.approx({"crank": 300.0, "frame": 600.0, "lever": 900.0}, rel=1e-14)
    assert out["indicators"]["stroke"]["simulated"] == pytest.approx(900.0, rel=1e-12)


def test_slider_analysis_of_given_lengths():
    """GATE 2025, Mechanical Engineering, question 60: crank 30 mm, rod 50 mm, offset 10 mm,
    stroke 62 mm to the nearest mm (sqrt(6300) - sqrt(300) = 62.052 by hand); h = H/r and the
    ratios L = 5/3, nu = 1/3; lambda_max = asin((30 + 10)/50) (crank square to the guide,
    away from it) = 53.13 deg: above the permissible 30 deg, below 60 deg: PASS with warnings."""
    out = _json("slider", "--crank", "30", "--rod", "50", "--offset", "10")
    hand = math.sqrt(6300) - math.sqrt(300)
    ind = out["indicators"]
    assert ind["stroke"]["simulated"] == pytest.approx(hand, rel=1e-12) and round(hand) == 62
    assert ind["relative_stroke"]["simulated"] == pytest.approx(hand / 30, rel=1e-12)
    assert out["ratios"] == pytest.approx({"rod_ratio": 5 / 3, "offset_ratio": 1 / 3}, rel=1e-15)
    lam = ind["largest_pressure_angle"]["simulated"]
    assert lam == pytest.approx(math.degrees(math.asin(0.8)), abs=1e-9)
    assert out["verdict"] == "PASS with warnings"
    assert {"dead_centre_extended", "dead_centre_folded", "time_ratio", "extreme_rod_angle"} <= set(ind)


@pytest.mark.parametrize(
    "args, words",
    [
        (["slider", "--crank", "1", "--rod", "3", "--stroke", "2"], "cannot be mixed"),
        (["slider", "--crank", "1"], "--rod"),
        (["slider"], "--stroke and --rod-ratio"),
        (["slotted", "--time-ratio", "2", "--crank", "1", "--frame", "2"], "over-determine"),
        (["slotted", "--crank", "1"], "--frame"),
        (["slotted", "--time-ratio", "2"], "give a length"),
    ],
)
def test_problem_form_misuse_one_line_exit_2(args, words):
    assert words in one_line_error(run(*args), 2)


@pytest.mark.parametrize(
    "args, words",
    [
        (["slider", "--crank", "1", "--rod", "1.5", "--offset", "-0.5"], "cannot turn fully"),
        (["slotted", "--crank", "2", "--frame", "2"], "Whitworth"),
        (["slotted", "--crank", "1", "--frame", "2", "--lever", "2.9"], "cannot hold"),
    ],
)
def test_analysis_outside_realisability_exit_1(args, words):
    assert words in one_line_error(run(*args), 1)


# ----------------------------------------------------------------------------- crank-rocker output
def test_rocker_prints_both_transmission_extremes_and_the_dead_centres():
    """gamma_min, gamma_max and the two dead-centre crank angles, in the table and in JSON; the
    crank turns 180 deg + theta between the dead centres, theta = 180 deg (K - 1)/(K + 1)
    (K = 1.1: 8.571 deg by hand)."""
    args = ["rocker", "--time-ratio", "1.1", "--swing", "40", "--rocker", "0.3", "--frame", "0.4"]
    p = run(*args)
    assert p.returncode == 0, p.stderr
    for words in ("transmission γmin", "transmission γmax", "dead centre, extended", "dead centre, folded"):
        assert words in p.stdout
    ind = _json(*args)["indicators"]
    assert ind["gamma_min"]["simulated"] < ind["gamma_max"]["simulated"]
    gap = (ind["dead_centre_folded"]["simulated"] - ind["dead_centre_extended"]["simulated"]) % 360
    assert min(gap, 360 - gap) == pytest.approx(180 - 180 * 0.1 / 2.1, abs=1e-9)


def test_rocker_k1_limit_is_a_number():
    """At K = 1 and a 40 deg swing the transmission angle tends to 90 - 40/2 = 70 deg (by hand)."""
    line = one_line_error(run("rocker", "--time-ratio", "1", "--swing", "40", "--rocker", "1"), 1)
    assert "70°" in line and "swing/2" not in line


# ----------------------------------------------------------------------------- the verdict
def test_a_crank_rocker_that_would_jam_fails():
    """K = 3, swing 170 deg: the best crank-rocker's transmission angle is 0.76 deg (checked
    against a brute-force sweep in tests/test_synthesis.py): FAIL, exit 1, with the mechanism."""
    p = run("rocker", "--time-ratio", "3", "--swing", "170", "--rocker", "1")
    assert p.returncode == 1 and "VERDICT: FAIL" in p.stdout and "Lengths" in p.stdout
    out = _json("rocker", "--time-ratio", "3", "--swing", "170", "--rocker", "1", code=1)
    check = next(c for c in out["checks"] if c["key"] == "transmission_angle")
    assert check["value"] < 1.0 and check["fail_limit"] == 30.0 and check["result"] == "fail"


def test_a_crank_slider_near_its_largest_time_ratio_fails():
    """L = 4, K = 1.833 (K_max(4) = 1.8376): the largest pressure angle asin((r + e)/l) is 89.8 deg,
    above 60 deg: FAIL, exit 1."""
    out = _json("slider", "--stroke", "0.1", "--rod-ratio", "4", "--time-ratio", "1.833", code=1)
    lengths = out["lengths"]
    hand = math.degrees(math.asin((lengths["crank"] + lengths["offset"]) / lengths["rod"]))
    check = next(c for c in out["checks"] if c["key"] == "pressure_angle")
    assert check["value"] == pytest.approx(hand, abs=1e-9) and hand > 89.8
    assert out["verdict"] == "FAIL" and not out["pass"]


def test_three_levels_and_the_pump_verdicts_check_shape():
    """PASS (lambda_max 17.5 deg), PASS with warnings (45.4 deg, above the permissible 30 deg)
    and FAIL exit 0, 0 and 1; a check row has the keys of the pump verdict's check rows."""
    ok = _json("slider", "--crank", "0.1", "--rod", "0.4", "--offset", "0.02")
    warn = _json("slider", "--stroke", "0.1", "--rod-ratio", "4", "--time-ratio", "1.2")
    assert (ok["verdict"], warn["verdict"]) == ("PASS", "PASS with warnings")
    pump = json.loads(run("force", "configs/prototype.toml", "--summary", "-f", "json").stdout)
    assert {frozenset(c) for c in ok["checks"]} == {frozenset(pump["checks"][0])}
    p = run("slider", "--stroke", "0.1", "--rod-ratio", "4", "--time-ratio", "1.2")
    assert "VERDICT: PASS with warnings — largest pressure angle 45.45° above 30°" in p.stdout


def test_transmission_says_whether_the_simulation_agrees():
    out = _json("transmission")
    assert out["simulation"] == "agrees" and out["simulation_agrees"] and out["verdict"] == "PASS"
    p = run("transmission")
    assert "SIMULATION: agrees" in p.stdout and "VERDICT: PASS" in p.stdout
    # a 179.9999 deg swing: the linkage that the optimum gives cannot be run (its rocker has no
    # two clean extremes) and its transmission angle is 0: disagrees, FAIL, exit 1
    out = _json("transmission", "--swing", "179.9999", code=1)
    assert out["simulation"] == "disagrees" and out["verdict"] == "FAIL"
    assert "SIMULATION: disagrees" in run("transmission", "--swing", "179.9999").stdout
    # the transmission angle alone fails: 0.76 deg at K = 3 and a 170 deg swing
    out = _json("transmission", "--time-ratio", "3", "--swing", "170", "--rocker", "1", code=1)
    assert out["simulation"] == "agrees" and out["verdict"] == "FAIL"


# ----------------------------------------------------------------------------- structure words
CAM = """name = "cam and flat follower"
frame = "0"
links = ["0", "cam", "follower"]
[joints]
O = { kind = "revolute", links = ["0", "cam"] }
F = { kind = "prismatic", links = ["follower", "0"] }
K = { kind = "higher", links = ["cam", "follower"] }
"""


def test_structure_counts_agree_in_number(tmp_path):
    """One higher pair is 'p2 = 1 higher pair', not 'pairs'; one driver, one passive link."""
    f = tmp_path / "cam.toml"
    f.write_text(CAM)
    p = run("structure", f)
    assert "n = 2 moving links, p1 = 2 lower pairs (class V), p2 = 1 higher pair (class IV)" in p.stdout
    dp = run("structure", "configs/mechanisms/double-parallelogram.toml").stdout
    assert "passive link, left out" in dp and "driving link: 1 (a primary mechanism" in dp
    assert "link(s)" not in dp
