"""`pumplink tolerance` through the real entry point: its first-order sensitivities against finite
differences of two `pumplink force` runs on hand-edited specs, the same numbers on one process,
a local pool and a Dask cluster, and its exit codes.

The spec states a linkage by its synthesis inputs (L1, D1, b, rocker, handle, swing), so a spec
edit moves the holes the synthesis puts elsewhere too; the expected derivative is then the chain
rule over the reported sensitivities, with the synthesis' own derivatives taken from the 50-digit
reference of tests/reference.py (an independent route to Eq. (2) of the pump paper):

* the grip along the rocker is the spec's ``handle`` alone (the synthesis does not use it), so
  d(peak)/d(handle) is the reported sensitivity of the grip hole, directly;
* ``L1`` moves the rocker pivot O4 in x by -dL1 and changes the crank and coupler lengths:
  d(peak)/dL1 = -S(O4 x on the stand) + S(crank A) dcrank/dL1 + S(coupler B) dcoupler/dL1;
* ``D1`` likewise, O4 in y by -dD1; ``swing`` changes the crank and the coupler only.
"""

from __future__ import annotations

import json
import math
import os
import subprocess
import sys
import tomllib
from pathlib import Path

import mpmath
import pytest
import reference as ref
import tomli_w

from pumplink.studies import tolerance as tl

ROOT = Path(__file__).resolve().parents[2]
EXE = Path(sys.executable).parent / "pumplink"
SHIPPED = ROOT / "configs" / "village-10m.toml"
# The machinery (sensitivities, workers, seeds, exit codes) runs on a fixed design written for these
# tests (its header says why); the shipped spec, [parts] and all, runs in the 80-column test and in
# test_the_parts_are_judged_on_every_build.
VILLAGE = ROOT / "tests" / "data" / "village-first-sized.toml"


def run(*args, cwd=ROOT) -> subprocess.CompletedProcess:
    env = {**os.environ, "COLUMNS": "80", "NO_COLOR": "1"}
    return subprocess.run(
        [EXE, *map(str, args)], cwd=cwd, env=env, capture_output=True, text=True, timeout=600
    )


def force_peak(spec: Path) -> float:
    p = run("force", spec, "--summary", "--format", "json")
    assert p.returncode in (0, 1), p.stderr
    return json.loads(p.stdout)["peak_force_N"]


@pytest.fixture(scope="module")
def village_tolerance() -> dict:
    p = run("tolerance", VILLAGE, "--samples", "100", "--format", "json")
    assert p.returncode in (0, 1), p.stderr
    return json.loads(p.stdout)


def sensitivity(row: dict, hole: str, axis: str) -> float:
    """The reported d(peak force)/d(offset) [N/m]."""
    s = next(s for s in row["sensitivities"] if s["hole"] == hole and s["axis"] == axis)
    return s["peak_force_N_per_mm"] * 1000.0


def edited(tmp_path: Path, key: str, value: float) -> Path:
    """The test's village design with linkage.<key> = value (written as TOML, as by hand)."""
    data = tomllib.loads(VILLAGE.read_text())
    data["linkage"][key] = value
    path = tmp_path / f"village-{key}-{value!r}.toml"
    path.write_text(tomli_w.dumps(data))
    return path


def central(tmp_path: Path, key: str, h: float) -> float:
    """(peak(key + h) - peak(key - h)) / 2h from two `pumplink force` runs [N per spec unit]."""
    base = tomllib.loads(VILLAGE.read_text())["linkage"][key]
    up, down = (force_peak(edited(tmp_path, key, round(base + s * h, 10))) for s in (1, -1))
    return (up - down) / (2 * h)


def synthesis_rate(name: str, key: str) -> float:
    """d(crank or coupler)/d(L1, D1 [m] or swing [deg]) from the 50-digit synthesis."""
    lk = tomllib.loads(VILLAGE.read_text())["linkage"]
    x0 = {"L1": lk["L1"], "D1": lk["D1"], "swing": math.radians(lk["swing"])}

    def length(x):
        args = {**x0, key: x}
        return ref.synthesis(args["L1"], args["D1"], lk["b"], lk["rocker"], args["swing"])[name]

    # a central difference at 50 digits: its truncation (h = 1e-20) and rounding (1e-50 / h) are
    # far below float precision (mpmath.diff would step below the reference's fixed 50 digits)
    x, h = mpmath.mpf(x0[key]), mpmath.mpf("1e-20")
    rate = float((length(x + h) - length(x - h)) / (2 * h))
    return rate * (math.pi / 180.0 if key == "swing" else 1.0)


# The two finite differences differ only by their truncation, (h²/6) F''' ~ (h/L)² F ~ 1e-8 N/mm at
# h = 0.1 mm, and the rounding of the peak force (~1e-12 of 100 N over h): 1e-6 relative leaves
# a wide margin while a wrong hole, sign or factor (errors of order 1) cannot pass.
AGREE = 1e-6


def test_grip_sensitivity_is_two_force_runs_on_the_handle(village_tolerance, tmp_path):
    fd = central(tmp_path, "handle", 1e-4)
    assert sensitivity(village_tolerance, "rocker.grip", "along") == pytest.approx(fd, rel=AGREE)
    # the grip off across the rocker changes nothing to first order (the handle is measured along it)
    assert abs(sensitivity(village_tolerance, "rocker.grip", "across")) < 1e-6 * abs(fd)


@pytest.mark.parametrize(
    "key, pivot, h",
    [("L1", ("stand.O4", "x"), 1e-4), ("D1", ("stand.O4", "y"), 1e-4), ("swing", None, 0.01)],
)
def test_pivot_and_link_sensitivities_are_two_force_runs_by_the_chain_rule(
    village_tolerance, tmp_path, key, pivot, h
):
    fd = central(tmp_path, key, h)
    expected = (
        sensitivity(village_tolerance, "crank.A", "along") * synthesis_rate("crank", key)
        + sensitivity(village_tolerance, "coupler.B", "along") * synthesis_rate("coupler", key)
        # L1 and D1 put O4 at (-(L1 + b/2), -D1): the pivot moves by minus the edit
        - (sensitivity(village_tolerance, *pivot) if pivot else 0.0)
    )
    assert expected == pytest.approx(fd, rel=AGREE)


def test_the_holes_of_one_bar_act_through_its_length_alone(village_tolerance):
    """The two holes of the crank pull its length apart: equal and opposite sensitivities; the
    stand's two pivots act through O4 - O2: equal and opposite too."""
    for first, second, axes in (
        ("crank.O2", "crank.A", ("along",)),
        ("coupler.A", "coupler.B", ("along",)),
        ("stand.O2", "stand.O4", ("x", "y")),
    ):
        for axis in axes:
            a, b = sensitivity(village_tolerance, first, axis), sensitivity(village_tolerance, second, axis)
            assert a == pytest.approx(-b, rel=1e-6) and abs(a) > 1.0


# ----------------------------------------------------------------------------- the same numbers anywhere
def test_a_pool_and_a_dask_cluster_give_the_numbers_of_one_process():
    """1,500 builds in two chunks of unequal size (1,000 and 500): on one process, two loky workers
    and a local Dask cluster of two, the output is byte for byte the same.  CSV: every build's
    dimensions and results at full precision on stdout, the summary (shares, interval, first-order
    estimate) on stderr; the JSON is computed from the same builds by the same driver."""
    pytest.importorskip("distributed")
    assert tl.CHUNK_SAMPLES == 1000
    args = ("tolerance", VILLAGE, "--samples", "1500", "--seed", "7", "--format", "csv")
    one, pool, dask = run(*args), run(*args, "--workers", "2"), run(*args, "--scheduler", "local:2")
    for p in (one, pool, dask):
        assert p.returncode in (0, 1) and "Traceback" not in p.stderr, p.stderr
    assert one.stdout and pool.stdout == one.stdout and dask.stdout == one.stdout
    assert one.stdout.count("\n") == 1501 and pool.stderr == one.stderr == dask.stderr


def test_another_seed_gives_other_builds_and_the_same_seed_the_same():
    a = json.loads(run("tolerance", VILLAGE, "--samples", "100", "--format", "json").stdout)
    b = json.loads(run("tolerance", VILLAGE, "--samples", "100", "--seed", "1", "--format", "json").stdout)
    c = json.loads(run("tolerance", VILLAGE, "--samples", "100", "--format", "json").stdout)
    assert a == c and a["spread"]["peak_force_N"]["median"] != b["spread"]["peak_force_N"]["median"]


# ----------------------------------------------------------------------------- exit codes, words
def test_exit_0_when_enough_builds_pass_and_1_when_too_few():
    """The village design is 2.4 N under its 100 N limit: at ±0.2 mm every build passes, at ±2 mm
    far fewer than 95 % do."""
    tight = run("tolerance", VILLAGE, "--hole", "0.2mm", "--samples", "500", "--format", "json")
    loose = run("tolerance", VILLAGE, "--hole", "2mm", "--samples", "500", "--format", "json")
    assert tight.returncode == 0 and json.loads(tight.stdout)["builds_pass"]["share"] == 1.0
    assert loose.returncode == 1 and json.loads(loose.stdout)["builds_pass"]["share"] < 0.95


@pytest.mark.parametrize(
    "args, words",
    [
        (("--hole", "1"), "--hole '1' is not a length with a unit"),
        (("--hole", "-1mm"), "must be a length of 0 or more"),
        (("--tol", "crank.X=1mm"), "hole 'crank.X' is unknown"),
        (("--tol", "crank.A"), "is not HOLE=LENGTH"),
        (("--hole", "60mm"), "give 0-50 mm"),
        (("--yield", "0.3"), "--yield"),
    ],
)
def test_bad_input_is_one_line_and_exit_2(args, words):
    p = run("tolerance", VILLAGE, *args)
    assert p.returncode == 2 and words in p.stderr and len(p.stderr.strip().splitlines()) == 1, p.stderr


def test_a_piston_pump_is_refused():
    p = run("tolerance", ROOT / "examples" / "piston-pump.toml")
    assert p.returncode == 2 and "rope pumps" in p.stderr


def test_the_table_fits_80_columns_and_says_what_to_drill():
    p = run("tolerance", SHIPPED, "--samples", "300")
    assert p.returncode in (0, 1), p.stderr
    assert max(len(line) for line in p.stdout.splitlines()) <= 80
    text = " ".join(p.stdout.split())
    assert "builds that pass:" in text and "hold the crank holes (O2, A) to ±" in text


def test_per_part_and_per_hole_tolerances_reach_the_builds(tmp_path):
    """--crank-hole 0 and --tol crank.A=... : the most specific wins; a hole held at 0 never moves."""
    p = run(
        "tolerance", VILLAGE, "--samples", "100", "--crank-hole", "0mm", "--tol", "crank.A=0.3mm",
        "--pivot", "2mm", "--format", "csv",
    )  # fmt: skip
    assert p.returncode in (0, 1), p.stderr
    rows = list(__import__("csv").DictReader(p.stdout.splitlines()))
    assert len(rows) == 100
    o2 = [abs(float(r["crank.O2_along_mm"])) for r in rows]
    a = [abs(float(r["crank.A_along_mm"])) for r in rows]
    stand = [abs(float(r["stand.O4_x_mm"])) for r in rows]
    coupler = [abs(float(r["coupler.A_along_mm"])) for r in rows]
    assert max(o2) == 0.0 and 0.2 < max(a) <= 0.3 and 1.0 < max(stand) <= 2.0 and 0.5 < max(coupler) <= 1.0


def test_the_parts_are_judged_on_every_build(tmp_path):
    """A spec's [parts] reach every build: with the village's pins on a tenth of their bore length
    each build bears ten times the pressure (19 MPa: above the 12 MPa of a moving joint), so every
    build passes with a warning on the pins; with its own parts none warns on them."""
    data = tomllib.loads(SHIPPED.read_text())
    data["parts"]["pin_width"] = data["parts"]["pin_width"] / 10
    thin = tmp_path / "thin-pins.toml"
    thin.write_text(tomli_w.dumps(data))
    rows = {}
    for name, spec in (("thin", thin), ("shipped", SHIPPED)):
        p = run("tolerance", spec, "--samples", "100", "--format", "json")
        assert p.returncode in (0, 1), p.stderr
        rows[name] = json.loads(p.stdout)
    assert rows["thin"]["warn_share"].get("pin_pressure") == 1.0, rows["thin"]["warn_share"]
    assert "pin_pressure" not in rows["shipped"]["warn_share"], rows["shipped"]["warn_share"]
