"""Batch runs: batch files, the vectorised evaluation, `pumplink batch` end to end.

The numbers of a batch are checked against `pumplink force --summary --format json` (and
``force_analysis`` in-process) on the same variant, exactly: the per-design route is the
independent reference.  CLI tests go through the real entry point (``python -m pumplink``).
"""

from __future__ import annotations

import contextlib
import csv
import io
import json
import math
import os
import random
import signal
import subprocess
import sys
import time
import tomllib
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest
import tomli_w

from pumplink import batch as B
from pumplink.errors import SpecError
from pumplink.inputs.pump import parse_spec
from pumplink.mechanisms.fourbar import FourBar, synthesize
from pumplink.models import quasi_static as F
from pumplink.studies.force import force_analysis

ROOT = Path(__file__).resolve().parents[2]
CONFIGS = ROOT / "configs"
GRID = CONFIGS / "grids" / "design-space.toml"
PROTOTYPE = (CONFIGS / "prototype.toml").as_posix()
VILLAGE = (CONFIGS / "village-10m.toml").as_posix()


def pumplink(*args, cwd=ROOT, **kw) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-m", "pumplink", *map(str, args)],
        cwd=cwd,
        capture_output=True,
        text=True,
        timeout=120,
        **kw,
    )


def read_csv(text: str) -> list[dict[str, str]]:
    return list(csv.DictReader(io.StringIO(text)))


# A small batch whose outcome follows from a hand derivation: the prototype (L1 = 0.4) passes
# with peak 85.8 N at 45 N rope force; the force is linear in the wheel torque (F = Mw / (dPx/dθ2),
# docs/physics.md), so at 80 N the peak is 85.8 * 80/45 = 152 N > 100 N while the mean
# (35.3 N * 80/45 = 62.8 N) stays below; with L1 = 0 the frame line rises at
# atan(0.2/0.05) = 76° > 90° - 30°, so psi2 < 0: no crank-rocker (docs/physics.md).
SMALL = f"""\
name = "small"
base = "{PROTOTYPE}"
[vary]
"linkage.L1" = [0.4, 0.0]
"load.rope_force" = [45, 80]
"""


# Batches that give inertia: the least energy model that is enough decides their verdict, per
# variant (the flywheel, or full dynamics where the links' energy or weight is not small).  They
# cover every route to J of PumpSpec.inertia: wheel.mass plus the water column from head and
# pipe_diameter (the village base, also with head and bore on axes), wheel.inertia plus an explicit
# load.moving_mass on a rope-force base, and a moving mass alone; speed, speed fluctuation and force
# limit on axes; light links; and infeasible variants (L1 = 0, see SMALL).
PROTO_INLINE = """\
[base.wheel]
radius = 0.25
[base.linkage]
L1 = 0.40
D1 = 0.20
b = 0.10
rocker = 0.20
handle = 1.00
swing = 60.0
[base.load]
rope_force = 45.0
"""
FLYWHEEL_BATCHES = {
    "fly-mass": f"""\
base = "{VILLAGE}"
[vary]
"wheel.mass" = [0.5, 4.0, 20.0]
"operator.speed" = [180, 360, 540]
"linkage.rocker" = {{ start = 0.15, stop = 0.3, num = 4 }}
"linkage.L1" = [0.4, 0.0]
"operator.speed_fluctuation" = [0.1, 0.2]
""",
    "fly-water": f"""\
base = "{VILLAGE}"
[vary]
"load.head" = [6.0, 10.0, 14.0]
"load.pipe_diameter" = [0.02, 0.023]
"operator.speed" = [300, 420]
""",
    "fly-inertia": 'name = "fly-inertia"\n'
    + PROTO_INLINE
    + """\
[vary]
"wheel.inertia" = [0.05, 0.5]
"load.moving_mass" = [0.0, 10.0]
"operator.force_limit" = [60, 100]
"linkage.swing" = [60, 70]
""",
    "fly-moving": PROTO_INLINE
    + """\
[vary]
"load.moving_mass" = [5.0, 40.0]
"operator.speed" = [360, 720]
""",
    # light links (0.1 kg/m): the flywheel is enough, and a small wheel fails it on the peak
    "fly-light": PROTO_INLINE.replace("swing = 60.0", "swing = 60.0\nmass_per_length = 0.1")
    + """\
[vary]
"wheel.inertia" = [0.05, 0.5]
"load.rope_force" = [45.0, 90.0]
""",
}


@pytest.fixture(scope="module")
def fly_files(tmp_path_factory) -> list[Path]:
    folder = tmp_path_factory.mktemp("fly")
    out = []
    for name, text in FLYWHEEL_BATCHES.items():
        p = folder / f"{name}.toml"
        p.write_text(text)
        out.append(p)
    return out


@pytest.fixture()
def small(tmp_path) -> Path:
    p = tmp_path / "small.toml"
    p.write_text(SMALL)
    return p


@pytest.fixture(scope="module")
def qs_grid(tmp_path_factory) -> Path:
    """The design-space grid on a quasi-static base: the village well without its wheel mass and
    its [parts].

    configs/grids/design-space.toml builds on configs/village-10m.toml, whose wheel.mass turns on
    the flywheel model for all 27,216 variants (~10 s a run).  The streaming, chunking and worker
    tests below are about the plumbing, not the model, and run this copy (~1 s); the flywheel
    path has its own tests, and a slice of the real grid is checked against force_analysis.
    """
    folder = tmp_path_factory.mktemp("qs")
    village = tomllib.loads(Path(VILLAGE).read_text())
    del village["wheel"]["mass"], village["parts"]  # quasi-static, and no part checks (~2.5 ms a design)
    (folder / "village-10m.toml").write_text(tomli_w.dumps(village))
    text = GRID.read_text()
    assert text.count('base = "../village-10m.toml"') == 1
    path = folder / "design-space.toml"  # the same text (axis order and names), the other base
    path.write_text(text.replace('base = "../village-10m.toml"', 'base = "village-10m.toml"'))
    assert not B.load_batch(path).flywheel and B.load_batch(GRID).flywheel
    assert B.variant_names(B.load_batch(path), 0, 50) == B.variant_names(B.load_batch(GRID), 0, 50)
    return path


@pytest.fixture(scope="module")
def grid_csv(qs_grid) -> list[dict[str, str]]:
    r = pumplink("batch", qs_grid, "--fail-on", "none", "--format", "csv")
    assert r.returncode == 0, r.stderr
    return read_csv(r.stdout)


# ----------------------------------------------------------------------------- batch files
def test_linspace_values_and_variant_names(tmp_path):
    p = tmp_path / "t.toml"
    p.write_text(
        f'base = "{PROTOTYPE}"\n[vary]\n"linkage.rocker" = {{ start = 0.2, stop = 0.3, num = 3 }}\n'
        f'"linkage.swing" = [40, 50]\n'
    )
    b = B.load_batch(p)
    assert b.axes[0].values.tolist() == [0.2, 0.25, 0.3]  # what a user types, not 0.25000000000000006
    assert b.size == 6
    # itertools.product order, last axis fastest; names as documented in pumplink/batch.py
    assert B.variant_names(b, 0, 6) == [
        "t#0[rocker=0.2 swing=40]",
        "t#1[rocker=0.2 swing=50]",
        "t#2[rocker=0.25 swing=40]",
        "t#3[rocker=0.25 swing=50]",
        "t#4[rocker=0.3 swing=40]",
        "t#5[rocker=0.3 swing=50]",
    ]
    assert [B.variant_name(b, i) for i in range(6)] == B.variant_names(b, 0, 6)
    spec = B.variant_spec(b, 3)
    assert spec["linkage"]["rocker"] == 0.25 and spec["linkage"]["swing"] == 50.0
    assert spec["name"] == "t#3[rocker=0.25 swing=50]"


def test_inline_base_and_ambiguous_short_keys(tmp_path):
    p = tmp_path / "inline.toml"
    base = tomllib.loads(Path(PROTOTYPE).read_text())
    p.write_text(
        tomli_w.dumps(
            {"name": "inl", "base": base, "vary": {"wheel.radius": [0.2, 0.25], "linkage.handle": [1.0]}}
        )
    )
    b = B.load_batch(p)
    assert B.variant_names(b, 0, 2) == ["inl#0[radius=0.2 handle=1]", "inl#1[radius=0.25 handle=1]"]


BAD_FILES = [
    # (file text after the base line, what the one-line message must name)
    ('[vary]\n"linkage.rockr" = [0.2]\n', "linkage.rockr"),
    ('[vary]\n"pump.rocker" = [0.2]\n', "pump.rocker"),
    ('[vary]\n"name" = [1.0]\n', "'name'"),
    ('[vary]\n"linkage.rocker" = []\n', "linkage.rocker"),
    ('[vary]\n"linkage.swing" = { start = 40, stop = 70, num = 0 }\n', "linkage.swing"),
    ('[vary]\n"linkage.swing" = { start = 40, num = 7 }\n', "linkage.swing"),
    ('[vary]\n"linkage.swing" = { start = 40, stop = 70, num = 2.5 }\n', "linkage.swing"),
    ('[vary]\n"linkage.swing" = { start = "a", stop = 70, num = 3 }\n', "linkage.swing"),
    ('[vary]\n"linkage.swing" = { start = 40, stop = 40, num = 3 }\n', "linkage.swing"),
    ('[vary]\n"linkage.swing" = { start = 40, stop = 70, step = 5 }\n', "linkage.swing"),
    ('[vary]\n"linkage.swing" = { start = 40, stop = 190, num = 4 }\n', "linkage.swing"),
    ('[vary]\n"linkage.rocker" = ["0.2"]\n', "linkage.rocker"),
    ('[vary]\n"linkage.rocker" = [true]\n', "linkage.rocker"),
    ('[vary]\n"linkage.rocker" = 0.2\n', "linkage.rocker"),
    ('[vary]\n"linkage.rocker" = [0.2, nan]\n', "linkage.rocker"),
    ('[vary]\n"linkage.rocker" = [-0.1, 0.2]\n', "linkage.rocker"),
    ('[vary]\n"load.head" = [10.0]\n', "load"),  # base has rope_force: both given
    ("[vary]\n", "[vary]"),
    ('varry = 1\n[vary]\n"linkage.rocker" = [0.2]\n', "varry"),
    ('[vary\n"linkage.rocker" = [0.2]\n', "not valid TOML"),
]


@pytest.mark.parametrize("body,key", BAD_FILES)
def test_bad_batch_files_name_the_key_in_one_line(tmp_path, body, key):
    p = tmp_path / "bad.toml"
    p.write_text(f'base = "{PROTOTYPE}"\n' + body)
    with pytest.raises(SpecError) as exc:
        B.load_batch(p)
    msg = str(exc.value)
    assert "\n" not in msg and key in msg and str(p) in msg


@pytest.mark.parametrize(
    "text,key",
    [
        ('base = "nope.toml"\n[vary]\n"linkage.rocker" = [0.2]\n', "nope.toml"),
        ('[vary]\n"linkage.rocker" = [0.2]\n', "'base'"),
        ('base = 3\n[vary]\n"linkage.rocker" = [0.2]\n', "'base'"),
        (f'base = "{PROTOTYPE}"\n', "[vary]"),
        ('[base]\nname = "x"\n[vary]\n"linkage.rocker" = [0.2]\n', "wheel"),
    ],
)
def test_bad_base_names_the_key(tmp_path, text, key):
    p = tmp_path / "bad.toml"
    p.write_text(text)
    with pytest.raises(SpecError, match=None) as exc:
        B.load_batch(p)
    assert key in str(exc.value) and "\n" not in str(exc.value)


@pytest.mark.parametrize(
    "args,key",
    [
        (["BAD"], "linkage.rockr"),  # unknown spec path, through the real entry point
        (["MISSING"], "nope.toml"),  # missing base file
        (["EMPTYAXIS"], "linkage.rocker"),
        (["SMALL", "--chunk", "0/3"], "--chunk"),
        (["SMALL", "--chunk", "two/3"], "--chunk"),
        (["SMALL", "--fail-on", "peak,bogus"], "bogus"),
        (["SMALL", "--out", "x.csv"], "--out"),  # table output is not written to files
        (["EMPTYDIR"], "no .toml"),
        (["SMALL", "--format", "csv", "--out", "no-such-folder/x.csv"], "no-such-folder"),
        (["SMALL", "--junit", "EMPTYDIR"], "is a folder"),
    ],
)
def test_cli_bad_input_exits_2_with_one_line(tmp_path, small, args, key):
    (tmp_path / "bad.toml").write_text(f'base = "{PROTOTYPE}"\n[vary]\n"linkage.rockr" = [0.2]\n')
    (tmp_path / "missing.toml").write_text('base = "nope.toml"\n[vary]\n"linkage.rocker" = [0.2]\n')
    (tmp_path / "empty.toml").write_text(f'base = "{PROTOTYPE}"\n[vary]\n"linkage.rocker" = []\n')
    (tmp_path / "emptydir").mkdir()
    subst = {
        "BAD": tmp_path / "bad.toml",
        "MISSING": tmp_path / "missing.toml",
        "EMPTYAXIS": tmp_path / "empty.toml",
        "SMALL": small,
        "EMPTYDIR": tmp_path / "emptydir",
    }
    r = pumplink("batch", *[subst.get(a, a) for a in args], cwd=tmp_path)
    assert r.returncode == 2, r.stderr
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error:") and key in lines[0], r.stderr
    assert r.stdout == "" and not (tmp_path / "x.csv").exists()


# ----------------------------------------------------------------------------- numbers
def _sampled_reference(lk, samples, mw, dce, dcf, band):
    """Independent route: every sample angle through ``evaluate`` (np.cos/np.sin, not the angle
    addition), masked with ``in_dead_band``, one design at a time."""
    from pumplink.mechanisms.fourbar import kinematic_state

    th = np.arange(samples) * (2 * np.pi / samples)
    out = []
    for i in range(len(mw)):
        one = FourBar(
            *(
                np.float64(np.asarray(getattr(lk, f))[i])
                for f in ("pivot_x", "pivot_y", "crank", "coupler", "rocker", "handle", "branch")
            )
        )
        st = kinematic_state(one, th, float(mw[i]))
        keep = ~F.in_dead_band(th, dce[i], dcf[i], band[i]) & ~st.singular
        if not keep.any():
            out.append((np.nan, np.inf))
            continue
        j = np.flatnonzero(keep)[np.argmax(np.abs(st.force[keep]))]
        gap = min(F.angular_distance(th[j], dce[i]), F.angular_distance(th[j], dcf[i]))
        out.append((abs(st.force[j]), gap))
    return np.array(out).T  # peaks, distance of each peak's sample from the nearer dead centre


def _feasible_designs(n, seed):
    rng = np.random.default_rng(seed)
    syn = synthesize(
        rng.uniform(0, 0.6, n),
        rng.uniform(-0.3, 0.4, n),
        np.full(n, 0.1),
        rng.uniform(0.1, 0.4, n),
        np.radians(rng.uniform(10, 120, n)),
        np.full(n, 1.0),
    )
    ok = np.asarray(syn.feasible)
    lk = FourBar(
        *(
            np.asarray(getattr(syn.linkage, f))[ok]
            for f in ("pivot_x", "pivot_y", "crank", "coupler", "rocker", "handle", "branch")
        )
    )
    return lk, syn.dead_centre_extended[ok], syn.dead_centre_folded[ok], int(ok.sum())


@pytest.mark.parametrize("samples", [1, 7, 64, 97, 360, 1001, 20000])
@pytest.mark.parametrize("band_deg", [0.0, 1.0, 20.0, 89.0])
def test_sampled_peak_equals_a_brute_force_sweep(samples, band_deg):
    lk, dce, dcf, m = _feasible_designs(120, samples)
    mw = np.full(m, 12.0)
    band = np.full(m, np.radians(band_deg))
    got = F.sampled_peak(lk, samples, mw, dce, dcf, band)
    ref, gap = _sampled_reference(lk, samples, mw, dce, dcf, band)
    assert np.array_equal(np.isnan(got), np.isnan(ref))
    # The same samples: the directions (angle addition vs np.cos/np.sin) differ by a few ulp of
    # the angle, and the force's relative sensitivity to the angle is ~1/gap next to a dead
    # centre (dead_band 0); a different sample would be off by far more than this bound.
    ok = ~np.isnan(ref)
    bound = 1e-13 + 32 * np.finfo(float).eps / gap[ok]
    assert (np.abs(got[ok] / ref[ok] - 1) <= bound).all()


def _same(x, y) -> bool:
    return x == y or (math.isnan(x) and math.isnan(y))


def _assert_equals_force_analysis(b: B.Batch, c: B.Chunk, picks) -> None:
    """Row i of the chunk (variant c.start + i) equals force_analysis of its spec, exactly."""
    from pumplink.batch import QUASI_STATIC_LABEL as QUASI_STATIC

    nan = float("nan")
    for i in picks:
        r = force_analysis(parse_spec(B.variant_spec(b, c.start + i)), samples=360, keep_samples=False)
        s, e = r.design.synthesis, c.evaluation
        cs = e.synthesis
        pairs = {
            "frame": (s.frame_length, cs.frame_length[i]),
            "crank": (s.crank_length, cs.crank_length[i]),
            "coupler": (s.coupler_length, cs.coupler_length[i]),
            "K": (s.time_ratio, cs.time_ratio[i]),
            "gmin": (s.transmission_min, cs.transmission_min[i]),
            "gmax": (s.transmission_max, cs.transmission_max[i]),
            "mean": (r.mean_force, c.mean_force[i]),
            "peak": (r.dead_band_peak_force, e.dead_band_peak_force[i]),
            "sampled": (r.sampled_peak, e.sampled_peak[i]),
            "power": (r.power, e.power[i]),
            # the flywheel scene (None in force_analysis: quasi-static, or not computed)
            "inertia": (nan if r.inertia is None else r.inertia, c.inertia[i]),
            "delta": (nan if r.speed_fluctuation is None else r.speed_fluctuation, c.speed_fluctuation[i]),
            "required": (nan if r.least_peak_force is None else r.least_peak_force, c.least_peak_force[i]),
            "min speed": (
                nan if r.min_passing_speed is None else r.min_passing_speed,
                e.min_passing_speed[i],
            ),
        }
        for what, (x, y) in pairs.items():
            assert _same(x, y), (i, what, x, y)
        assert r.model == c.model[i] and (r.model != QUASI_STATIC) == c.flywheel[i]
        assert (
            r.passed == c.passed[i] and r.design.error == c.reason[i] and r.design.feasible == c.feasible[i]
        )


def test_random_variants_equal_force_analysis_exactly(qs_grid):
    b = B.load_batch(qs_grid)
    c = B.evaluate_chunk(b, 0, b.size, 360)
    assert not c.flywheel.any() and np.isnan(c.least_peak_force).all()  # this grid gives no inertia
    rng = random.Random(4)
    picks = rng.sample(range(b.size), 250)
    picks += [int(np.nonzero(~c.feasible)[0][0]), int(np.nonzero(c.feasible & ~c.passed)[0][0])]
    _assert_equals_force_analysis(b, c, picks)


def test_flywheel_variants_equal_force_analysis_exactly(fly_files):
    """Every variant of the batches that give inertia: J, the model chosen (the least that is
    enough: the flywheel or full dynamics, per variant), its least peak force, the minimum passing
    speed and the verdict equal force_analysis (the per-design scene) exactly."""
    outcomes, models = set(), set()
    for f in fly_files:
        b = B.load_batch(f)
        assert b.flywheel
        c = B.evaluate_chunk(b, 0, b.size, 360)
        assert c.flywheel.all()
        models |= set(c.model)
        _assert_equals_force_analysis(b, c, range(b.size))
        # the verdict's peak is the flywheel one: dead-band peak and verdict disagree somewhere
        ok = c.feasible
        outcomes |= {
            (bool(p), bool(q))
            for p, q in zip(c.evaluation.dead_band_peak_force[ok] <= c.force_limit[ok], c.peak_ok[ok])
        }
    assert outcomes == {(True, True), (True, False), (False, True), (False, False)}
    assert models == {B.FLYWHEEL_LABEL, B.DYNAMICS_LABEL}  # both decide somewhere in these grids


def test_design_space_grid_slice_equals_force_analysis_exactly():
    """The real exploration grid (flywheel: its village base gives wheel.mass): a slice, from a
    start that is no chunk boundary, against force_analysis."""
    b = B.load_batch(GRID)
    # 8 m of head on the 0.8 m handle: the village's 24-tooth ratchet holds the kick-back within
    # 0.15 m for some (on the 1.2 m handle it lets every one run back further: no pass to compare)
    start, stop = 3000, 3250
    c = B.evaluate_chunk(b, start, stop, 360)
    assert c.flywheel.all() and (~c.feasible).any() and (c.feasible & ~c.passed).any() and c.passed.any()
    rng = random.Random(5)
    picks = rng.sample(range(stop - start), 40)
    _assert_equals_force_analysis(b, c, picks)


def _val(text):
    return None if text == "" else float(text)


def _assert_rows_equal_force_json(tmp_path, b: B.Batch, rows: dict, picks) -> None:
    """Rows of `pumplink batch --format csv` equal `pumplink force --summary --format json`."""
    for i in picks:
        spec = B.variant_spec(b, i)
        row = rows[spec["name"]]
        path = tmp_path / f"v{i}.toml"
        path.write_text(tomli_w.dumps(spec))
        r = pumplink("force", path, "--summary", "--format", "json", "--samples", 360)
        assert r.returncode == (0 if row["pass"] == "True" else 1), r.stderr
        got = json.loads(r.stdout)
        assert got["name"] == row["name"]
        assert str(got["feasible"]) == row["feasible"] and (got["error"] or "") == row["reason"]
        for key in (
            "frame_length",
            "crank_length",
            "coupler_length",
            "time_ratio",
            "mean_force_N",
            "peak_force_N",
            "dead_band_peak_force_N",
            "sampled_peak_force_N",
            "power_W",
            "force_limit_N",
            "inertia_kg_m2",
            "speed_fluctuation",
            "least_peak_force_N",
            "min_passing_speed_deg_s",
            # the water: the same numbers in every format as in force's JSON
            "flow_l_min",
            "flow_share",
            "water_power_W",
            "pump_efficiency",
            "people_served",
        ):
            assert got[key] == _val(row[key]), (i, key)
        assert got["model"] == row["model"]
        tr = got["transmission_angle_deg"]
        assert (tr["min"], tr["max"]) == (
            _val(row["transmission_min_deg"]),
            _val(row["transmission_max_deg"]),
        )
        assert str(got["pass"]) == row["pass"]


def test_random_variants_equal_pumplink_force_json(tmp_path, qs_grid, grid_csv):
    b = B.load_batch(qs_grid)
    rows = {r["name"]: r for r in grid_csv}
    assert len(rows) == b.size == 27216
    rng = random.Random(11)
    picks = rng.sample(range(b.size), 3)
    picks.append(next(i for i, r in enumerate(grid_csv) if r["feasible"] == "False"))
    picks.append(next(i for i, r in enumerate(grid_csv) if r["feasible"] == "True" and r["pass"] == "False"))
    _assert_rows_equal_force_json(tmp_path, b, rows, picks)


def test_flywheel_rows_equal_pumplink_force_json(tmp_path, fly_files):
    """The scene columns of batch rows (CSV) equal `pumplink force --summary --format json`: a
    passing, a peak-failing (by each energy model) and an infeasible variant, and a moving mass
    alone."""
    junit = tmp_path / "r.xml"
    r = pumplink("batch", *fly_files, "--format", "csv", "--fail-on", "peak", "--junit", junit)
    assert r.returncode == 1, r.stderr
    all_rows = read_csv(r.stdout)
    b = B.load_batch(fly_files[0])
    rows = [x for x in all_rows if x["source"] == str(fly_files[0])]
    assert len(rows) == b.size and {x["model"] for x in all_rows} == {"flywheel", "full dynamics"}
    picks = [
        next(i for i, x in enumerate(rows) if x["pass"] == "True"),
        next(i for i, x in enumerate(rows) if x["failed"] == "peak" and x["model"] == "full dynamics"),
        next(i for i, x in enumerate(rows) if x["feasible"] == "False"),
    ]
    _assert_rows_equal_force_json(tmp_path, b, {x["name"]: x for x in rows}, picks)
    # a flywheel variant that fails on its peak, in whichever batch has one
    for f in fly_files:
        fb, frows = B.load_batch(f), [x for x in all_rows if x["source"] == str(f)]
        k = next(
            (i for i, x in enumerate(frows) if "peak" in x["failed"].split(";") and x["model"] == "flywheel"),
            None,
        )
        if k is not None:
            _assert_rows_equal_force_json(tmp_path, fb, {x["name"]: x for x in frows}, [k])
            break
    assert k is not None
    # the JUnit failure names the deciding model's peak, as the row has it
    for fail in (rows[picks[1]], frows[k]):
        (case,) = [t for t in ET.parse(junit).getroot().iter("testcase") if t.get("name") == fail["name"]]
        how = "the flywheel" if fail["model"] == "flywheel" else fail["model"]
        assert case.find("failure").get("message") == (
            f"peak force with {how} (δ ≤ {float(fail['speed_fluctuation']):g}) "
            f"{float(fail['least_peak_force_N']):.2f} N > limit {float(fail['force_limit_N']):g} N"
        )
    moving = B.load_batch(fly_files[3])
    _assert_rows_equal_force_json(
        tmp_path, moving, {x["name"]: x for x in all_rows if x["source"] == str(fly_files[3])}, [1]
    )


# ----------------------------------------------------------------------------- CLI
def test_configs_folder_passes_as_in_ci(tmp_path):
    """The CI recipe: `pumplink batch configs/ --junit report.xml` exits 0 with every design."""
    junit = tmp_path / "report.xml"
    r = pumplink("batch", "configs/", "--junit", junit)
    assert r.returncode == 0, r.stdout + r.stderr
    # expected test count, counted here from the files themselves
    expected = 0
    for f in sorted(CONFIGS.glob("*.toml")):
        data = tomllib.loads(f.read_text())
        expected += (
            math.prod(len(v) if isinstance(v, list) else v["num"] for v in data["vary"].values())
            if "vary" in data
            else 1
        )
    root = ET.parse(junit).getroot()
    cases = root.findall(".//testcase")
    assert len(cases) == expected >= 4
    assert sum(int(s.get("tests")) for s in root) == expected
    assert not root.findall(".//failure") and all(s.get("failures") == "0" for s in root)
    assert not any("grids" in s.get("name") for s in root)  # the exploration grid is not a CI gate
    assert f"{expected} variants: " in r.stdout and ", 0 fail, 0 infeasible" in r.stdout


@pytest.mark.parametrize(
    "fail_on,code,failures,skipped",
    [
        ("mean,peak,infeasible", 1, 3, 0),
        ("none", 0, 0, 2),
        ("mean", 0, 0, 2),
        ("peak", 1, 1, 2),
        ("infeasible", 1, 2, 0),
    ],
)
def test_fail_on_selects_exit_code_and_junit(tmp_path, small, fail_on, code, failures, skipped):
    junit = tmp_path / "r.xml"
    r = pumplink("batch", small, "--fail-on", fail_on, "--format", "csv", "--junit", junit)
    assert r.returncode == code, r.stderr
    rows = read_csv(r.stdout)
    assert [x["name"] for x in rows] == [
        "small#0[L1=0.4 rope_force=45]",
        "small#1[L1=0.4 rope_force=80]",
        "small#2[L1=0 rope_force=45]",
        "small#3[L1=0 rope_force=80]",
    ]
    assert [x["pass"] for x in rows] == ["True", "False", "False", "False"]
    assert [x["failed"] for x in rows] == ["", "peak", "infeasible", "infeasible"]
    assert [x["feasible"] for x in rows] == ["True", "True", "False", "False"]
    assert "psi2" in rows[2]["reason"]
    assert float(rows[1]["peak_force_N"]) == pytest.approx(
        float(rows[0]["peak_force_N"]) * 80 / 45, rel=1e-12
    )
    root = ET.parse(junit).getroot()
    assert len(root.findall(".//failure")) == failures and len(root.findall(".//skipped")) == skipped
    assert "1 pass, 1 fail, 2 infeasible" in r.stderr


# The prototype at three wheel speeds: quasi-static, so mean and peak force do not depend on the
# speed, while the grip speed (omega H |d theta4/d theta2|) and the power (Mw omega, Mw = 45 N x
# 0.25 m) grow with it.  docs/models.md §4: the grip speed warns above 2.5 m/s and fails above
# 4 m/s, the power warns above 75 W and fails above 150 W.
SPEEDS = f"""\
name = "speeds"
base = "{PROTOTYPE}"
[vary]
"operator.speed" = [240, 360, 480]
"""


@pytest.fixture(scope="module")
def speeds_run(tmp_path_factory):
    """The SPEEDS batch with --fail-on none: its rows, and each variant's failing and warning
    checks as the documented thresholds give them from the row's grip speed and power."""
    p = tmp_path_factory.mktemp("speeds") / "speeds.toml"
    p.write_text(SPEEDS)
    r = pumplink("batch", p, "--fail-on", "none", "--format", "json")
    assert r.returncode == 0, r.stderr
    rows = json.loads(r.stdout)["variants"]
    grip = [x["grip_speed_m_s"] for x in rows]
    assert grip[1] == pytest.approx(1.5 * grip[0], rel=1e-12) and grip[2] == pytest.approx(
        2 * grip[0], rel=1e-12
    )
    for x, w in zip(rows, (240, 360, 480)):
        assert x["power_W"] == pytest.approx(45 * 0.25 * math.radians(w), rel=1e-12)
        assert x["check_mean_force"] == x["check_peak_force"] == "pass"
    expected = []
    for x, w in zip(rows, (240, 360, 480)):
        fails = {"grip_speed"} if x["grip_speed_m_s"] > 4 else set()
        warns = {"grip_speed"} if 2.5 < x["grip_speed_m_s"] <= 4 else set()
        fails |= {"power"} if x["power_W"] > 150 else set()
        warns |= {"power"} if 75 < x["power_W"] <= 150 else set()
        # the cadence (w / 6 turns a minute) warns outside 30-60, the rope (w in rad/s x 0.25 m)
        # outside 0.6-1.8 m/s (docs/models.md §4)
        warns |= {"cadence"} if not 30 <= w / 6 <= 60 else set()
        warns |= {"rope_speed"} if not 0.6 <= math.radians(w) * 0.25 <= 1.8 else set()
        expected.append((fails, warns))
    # hand: 2.19, 3.28, 4.38 m/s and 47, 71, 94 W, 40, 60, 80 turns a minute and a rope at 1.05,
    # 1.57, 2.09 m/s: a clean pass, a grip-speed warning, and a failing grip speed with a power, a
    # cadence and a rope-speed warning
    assert expected == [
        (set(), set()),
        (set(), {"grip_speed"}),
        ({"grip_speed"}, {"power", "cadence", "rope_speed"}),
    ]
    assert [set(filter(None, x["failed"].split(";"))) for x in rows] == [e[0] for e in expected]
    assert [set(filter(None, x["warnings"].split(";"))) for x in rows] == [e[1] for e in expected]
    return p, rows


@pytest.mark.parametrize(
    "args,variants,code",
    [
        # the verdict (default): only a FAIL counts
        ([], 3, 1),
        (["--fail-on", "all"], 2, 0),
        # checks: any check other than mean and peak force that fails (the 480 deg/s grip speed)
        (["--fail-on", "checks"], 3, 1),
        (["--fail-on", "checks"], 2, 0),
        (["--fail-on", "mean,peak"], 3, 0),
        # warnings, and --strict (the verdict plus warnings): the 360 deg/s grip speed warns
        (["--fail-on", "warnings"], 2, 1),
        (["--strict"], 2, 1),
        (["--strict"], 1, 0),
        (["--strict", "--fail-on", "none"], 2, 1),
    ],
)
def test_fail_on_checks_warnings_all_and_strict(tmp_path, speeds_run, args, variants, code):
    """Exit code of each --fail-on selection and of --strict on the first ``variants`` speeds of
    SPEEDS, whose checks :func:`speeds_run` derives from the documented thresholds; the rows do not
    depend on the selection."""
    _, rows = speeds_run
    p = tmp_path / "speeds.toml"
    p.write_text(SPEEDS.replace("[240, 360, 480]", str([240, 360, 480][:variants])))
    r = pumplink("batch", p, *args, "--format", "json")
    assert r.returncode == code, (args, r.stderr)
    got = json.loads(r.stdout)["variants"]
    assert [(x["verdict"], x["failed"], x["warnings"]) for x in got] == [
        (x["verdict"], x["failed"], x["warnings"]) for x in rows[:variants]
    ]


# The flywheel decides the peak check, with outcomes that follow from the limits of the
# scene (pumplink/flywheel.py): the energy band W = J w^2 delta is 7.9e3 J for J = 1000 kg m^2 at
# 360 deg/s and delta = 0.2, far above the few joules the load can draw down near a dead centre
# (Mw * arc ~ 11 N m * 0.5 rad), so the least peak force is the mean force (W -> inf); for
# J = 1e-6 kg m^2, W = 7.9e-6 J and the least peak force tends to the quasi-static maximum,
# infinite at the dead centres (W -> 0): it is ~1e3 N already at J = 0.03 kg m^2 and grows like
# 1/W, past the 1e4 x F_mean above which pumplink.models.flywheel reports it as infinite (null in JSON,
# as `pumplink force` does).  The dead-band peaks are those of SMALL: 85.8 N at 45 N, 152 N at
# 80 N.  So the verdict is the opposite of the dead band's for two variants.
FLY_SMALL = (
    'name = "flysmall"\n'
    + PROTO_INLINE
    + """\
[vary]
"wheel.inertia" = [1e-6, 1000.0]
"load.rope_force" = [45, 80]
"""
)


@pytest.mark.parametrize(
    "fail_on,code,failures", [("mean,peak,infeasible", 1, 2), ("peak", 1, 2), ("mean", 0, 0)]
)
def test_fail_on_peak_is_the_flywheel_peak(tmp_path, fail_on, code, failures):
    p = tmp_path / "flysmall.toml"
    p.write_text(FLY_SMALL)
    junit = tmp_path / "r.xml"
    r = pumplink(
        "batch", p, "--fail-on", fail_on, "--format", "json", "--junit", junit, "--model", "flywheel"
    )
    assert r.returncode == code, r.stderr
    d = json.loads(r.stdout)
    v = d["variants"]
    assert [x["name"] for x in v] == [
        "flysmall#0[inertia=1e-06 rope_force=45]",
        "flysmall#1[inertia=1e-06 rope_force=80]",
        "flysmall#2[inertia=1000 rope_force=45]",
        "flysmall#3[inertia=1000 rope_force=80]",
    ]
    assert [x["model"] for x in v] == ["flywheel"] * 4 and [x["inertia_kg_m2"] for x in v] == [
        1e-6,
        1e-6,
        1000.0,
        1000.0,
    ]
    assert [x["dead_band_peak_force_N"] <= 100 for x in v] == [True, False, True, False]  # the dead band's
    assert [x["peak_force_N"] for x in v] == [
        None,
        None,
        v[2]["least_peak_force_N"],
        v[3]["least_peak_force_N"],
    ]
    assert [x["pass"] for x in v] == [False, False, True, True]  # the flywheel's
    assert [x["failed"] for x in v] == ["peak", "peak", "", ""]
    assert [x["least_peak_force_N"] for x in v[:2]] == [None, None]  # infinite
    for x in v[
        2:
    ]:  # W -> inf: the mean force (docs/physics.md, a different formula: pi Mw / (2 H sin(swing/2)))
        assert x["least_peak_force_N"] == pytest.approx(x["mean_force_N"], rel=1e-12)
        assert x["min_passing_speed_deg_s"] < 360
    s = d["summary"]
    assert (s["pass"], s["fail"], s["failed_selected"]) == (2, 2, 2 if "peak" in fail_on else 0)
    assert s["best"]["name"] == v[2]["name"] and s["best"]["model"] == "flywheel"
    assert s["best"]["peak_force_N"] == v[2]["least_peak_force_N"]
    msgs = [f.get("message") for f in ET.parse(junit).getroot().iter("failure")]
    assert len(msgs) == failures and all(
        "peak force with the flywheel (δ ≤ 0.2) infinite" in m and "J = 1e-06" in m for m in msgs
    )
    assert "lowest passing peak (flywheel) 35.3 N: flysmall#2" in r.stderr


def test_the_links_carry_the_dead_centres_when_the_wheel_cannot(tmp_path):
    """The same grid by the least model that is enough: with J = 1e-6 kg m^2 the links' kinetic
    energy dwarfs the flywheel's band, so full dynamics decides, and the coupler and handle (1 m
    of 1.56 kg/m tube) are themselves a flywheel: a finite least peak force, above the heavy
    wheel's; with J = 1000 kg m^2 the flywheel is enough and gives the mean force (W -> inf)."""
    p = tmp_path / "flysmall.toml"
    p.write_text(FLY_SMALL)
    r = pumplink("batch", p, "--fail-on", "none", "--format", "json")
    assert r.returncode == 0, r.stderr
    v = json.loads(r.stdout)["variants"]
    assert [x["model"] for x in v] == ["full dynamics"] * 2 + ["flywheel"] * 2
    for light, heavy in ((v[0], v[2]), (v[1], v[3])):
        assert math.isfinite(light["peak_force_N"]) and light["peak_force_N"] > heavy["peak_force_N"]
        assert heavy["peak_force_N"] == pytest.approx(heavy["mean_force_N"], rel=1e-12)


def test_flywheel_table_shows_the_verdict_peak_and_the_model(tmp_path):
    p = tmp_path / "flysmall.toml"
    p.write_text(FLY_SMALL)
    r = pumplink("batch", p, PROTOTYPE, "--fail-on", "none", "--model", "flywheel")
    assert r.returncode == 0, r.stderr
    rows = {
        ln.split()[0]: ln.split() for ln in r.stdout.splitlines() if ln.startswith(("flysmall#", "Proto"))
    }
    # the variant, the two varied values, then peak [N]: the flywheel's least peak (the mean, 62.8 N
    # at 80 N rope force) where inertia is given; the dead-band peak of the quasi-static prototype
    assert rows["flysmall#3"][1:4] == ["1000", "80", "62.8"]
    assert rows["Prototype"][1] == "85.8"
    assert "best: flysmall#2[inertia=1000 rope_force=45] — lowest peak force (flywheel) of 3" in r.stdout
    assert max(len(ln) for ln in r.stdout.splitlines()) <= 80


def test_zero_inertia_fails_with_an_infinite_peak(tmp_path):
    """A moving mass of 0 kg and no wheel mass, by the flywheel (--model): J = 0, no energy band
    (W = 0), so the least peak force is the quasi-static maximum, infinite
    (flywheel_solver.least_peak_force: inf for band 0)."""
    p = tmp_path / "j0.toml"
    p.write_text(PROTO_INLINE + '[vary]\n"load.moving_mass" = [0.0, 40.0]\n')
    junit = tmp_path / "r.xml"
    r = pumplink("batch", p, "--format", "csv", "--junit", junit, "--model", "flywheel")
    assert r.returncode == 1, r.stderr
    rows = read_csv(r.stdout)
    assert [x["inertia_kg_m2"] for x in rows] == ["0.0", "2.5"]  # 40 kg * 0.25^2 m^2
    assert (rows[0]["least_peak_force_N"], rows[0]["min_passing_speed_deg_s"], rows[0]["pass"]) == (
        "",
        "",
        "False",
    )
    assert rows[1]["pass"] == "True" and float(rows[1]["least_peak_force_N"]) <= 100
    (msg,) = [f.get("message") for f in ET.parse(junit).getroot().iter("failure")]
    assert "infinite" in msg and "J = 0" in msg


def test_json_rows_and_summary(small):
    r = pumplink("batch", small, "--format", "json", "--fail-on", "none")
    assert r.returncode == 0
    d = json.loads(r.stdout)
    v = d["variants"]
    assert len(v) == 4 and v[0]["vary"] == {"linkage.L1": 0.4, "load.rope_force": 45.0}
    assert v[2]["peak_force_N"] is None and v[2]["feasible"] is False
    s = d["summary"]
    assert (s["variants"], s["pass"], s["fail"], s["infeasible"]) == (4, 1, 1, 2)
    best = min((x for x in v if x["peak_force_N"] is not None), key=lambda x: x["peak_force_N"])
    assert s["best"]["name"] == best["name"] == "small#0[L1=0.4 rope_force=45]"


def test_chunks_partition_the_run(qs_grid):
    batches = B.load_inputs([CONFIGS, qs_grid, GRID])
    total = sum(b.size for b in batches)
    for n in (1, 2, 3, 7, 40):
        got = [(i, s, e) for k in range(1, n + 1) for (i, s, e) in B.plan(batches, (k, n), designs=5000)]
        seen = [(i, j) for i, s, e in got for j in range(s, e)]
        assert seen == [(i, j) for i, b in enumerate(batches) for j in range(b.size)] and len(seen) == total
        if n > 3:  # slices smaller than a task of the inertia batch: nothing to compare
            continue
        # tasks of a batch that gives inertia (the real grid) are cut smaller: the flywheel costs more
        size = {
            b.flywheel: max(e - s for i, s, e in got if batches[i].flywheel == b.flywheel)
            for b in batches[-2:]
        }
        assert size[True] <= B.FLYWHEEL_DESIGNS < size[False] <= 5000


def test_chunk_union_equals_full_run(tmp_path, qs_grid, fly_files):
    full = pumplink(
        "batch", "configs/", qs_grid, *fly_files, "--fail-on", "none", "--format", "csv", "--samples", 90
    )
    assert full.returncode == 0, full.stderr
    parts = []
    for k in (1, 2, 3):
        out = tmp_path / f"part{k}.csv"
        r = pumplink(
            "batch",
            "configs/",
            qs_grid,
            *fly_files,
            "--fail-on",
            "none",
            "--format",
            "csv",
            "--samples",
            90,
            "--chunk",
            f"{k}/3",
            "--out",
            out,
        )
        assert r.returncode == 0, r.stderr
        assert f"(slice {k}/3)" in r.stderr
        parts.append(out.read_text().splitlines())
    header = full.stdout.splitlines()[0]
    assert all(p[0] == header for p in parts)
    assert sum((p[1:] for p in parts), []) == full.stdout.splitlines()[1:]
    assert all(len(p) > 1 for p in parts)


def test_workers_give_the_same_rows(tmp_path, qs_grid, fly_files):
    outs = []
    n_fly = sum(B.load_batch(f).size for f in fly_files)
    for w in (1, 2):
        out = tmp_path / f"w{w}.csv"
        r = pumplink(
            "batch",
            qs_grid,
            *fly_files,
            "--fail-on",
            "none",
            "--format",
            "csv",
            "--out",
            out,
            "--workers",
            w,
            "--samples",
            60,
        )
        assert r.returncode == 0, r.stderr
        outs.append(out.read_bytes())
    assert outs[0] == outs[1] and outs[0].count(b"\n") == 27216 + n_fly + 1
    assert outs[0].count(b",flywheel,") + outs[0].count(b",full dynamics,") == n_fly


def test_no_progress_bar_or_colour_when_stderr_is_not_a_terminal(small):
    r = pumplink("batch", small, "--format", "csv", "--fail-on", "none")
    assert r.stderr.count("\n") == 1 and r.stderr.startswith("batch: 4 variants") and "\x1b" not in r.stderr


# ----------------------------------------------------------------------------- atomic outputs
def _leftovers(folder: Path) -> list[str]:
    return sorted(p.name for p in folder.iterdir() if p.name.endswith(".tmp"))


def _writing(pid: int, folder: Path, size: int = 20_000) -> bool:
    """True when process ``pid`` holds a file open in ``folder`` with more than ``size`` bytes:
    the output being written (unnamed, O_TMPFILE, or a hidden temp file)."""
    fds = Path(f"/proc/{pid}/fd")
    try:
        for fd in fds.iterdir():
            with contextlib.suppress(OSError):
                if os.readlink(fd).startswith(str(folder)) and os.stat(fd).st_size > size:
                    return True
    except OSError:
        return False
    return False


@pytest.mark.parametrize("exc", [KeyboardInterrupt, RuntimeError])
def test_interrupted_stream_leaves_no_partial_file(tmp_path, monkeypatch, exc, qs_grid):
    from pumplink.output import batchfiles as rb

    batches = B.load_inputs([qs_grid])  # the plumbing, not the model: the quasi-static copy
    out, junit = tmp_path / "rows.csv", tmp_path / "r.xml"
    junit.write_text("previous complete report\n")
    real = B.run_module.evaluate_chunk
    calls = []

    def flaky(*a, **k):
        calls.append(1)
        if len(calls) == 3:  # two chunks already written to the temp files
            raise exc("injected mid-stream")
        return real(*a, **k)

    monkeypatch.setattr(B.run_module, "evaluate_chunk", flaky)
    post = lambda b, c: rb.render_chunk(b, c, "csv", rb.varied_keys(batches), B.FAIL_CHECKS, True)  # noqa: E731
    with pytest.raises(exc):
        rb.write_stream(batches, B.run(batches, 30, post=post), 27216, "csv", out, junit, B.FAIL_CHECKS, 30)
    assert len(calls) == 3
    assert not out.exists()
    assert junit.read_text() == "previous complete report\n"  # the old file is untouched
    assert _leftovers(tmp_path) == []


@pytest.mark.parametrize(
    "sig,workers,group",
    [
        (signal.SIGINT, 1, False),
        (signal.SIGTERM, 2, False),
        (signal.SIGINT, 2, True),
        (signal.SIGTERM, 2, True),
    ],
)
def test_killed_run_leaves_no_partial_file(tmp_path, sig, workers, group):
    """Ctrl-C (SIGINT to the process group) or a CI runner's SIGTERM (to the process, or the
    group with the workers) mid-stream: exit 130, no output file and no temp file."""
    grid = tmp_path / "big.toml"
    grid.write_text(
        f'base = "{PROTOTYPE}"\n[vary]\n"linkage.rocker" = {{ start = 0.15, stop = 0.3, num = 100 }}\n'
        f'"linkage.swing" = {{ start = 40, stop = 80, num = 100 }}\n'
        '"load.rope_force" = [30, 40, 50, 60, 70, 80]\n'
    )
    out = tmp_path / "rows.csv"
    p = subprocess.Popen(
        [
            sys.executable,
            "-m",
            "pumplink",
            "batch",
            grid,
            "--format",
            "csv",
            "--out",
            out,
            "--junit",
            tmp_path / "r.xml",
            "--samples",
            "4000",
            "--workers",
            str(workers),
        ],
        cwd=ROOT,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        start_new_session=group,
    )
    deadline = time.monotonic() + 60
    while time.monotonic() < deadline:  # wait until rows are being written to the temp file
        if _writing(p.pid, tmp_path) or p.poll() is not None:
            break
        time.sleep(0.05)
    assert p.poll() is None, "the run finished before it could be interrupted"
    if group:
        os.killpg(p.pid, sig)
    else:
        p.send_signal(sig)
    _, err = p.communicate(timeout=60)
    assert p.returncode == 130, err
    assert "interrupted" in err and "Traceback" not in err
    assert not out.exists() and not (tmp_path / "r.xml").exists()
    assert _leftovers(tmp_path) == []


def test_csv_and_json_carry_the_same_rows(qs_grid, fly_files):
    """Standard designs (two models), the quasi-static grid and the flywheel batches in one run."""
    rc = pumplink(
        "batch", "configs/", qs_grid, *fly_files, "--format", "csv", "--fail-on", "none", "--samples", 30
    )
    rj = pumplink(
        "batch", "configs/", qs_grid, *fly_files, "--format", "json", "--fail-on", "none", "--samples", 30
    )
    assert rc.returncode == rj.returncode == 0
    rows, variants = read_csv(rc.stdout), json.loads(rj.stdout)["variants"]
    n_fly = sum(B.load_batch(f).size for f in fly_files)
    assert len(rows) == len(variants) == 27216 + 11 + n_fly
    assert {r["model"] for r in rows[:11]} == {
        "full dynamics",
        "quasi-static + dead band",
    }  # configs/ mixes the models
    spread = (
        list(range(12))
        + list(range(12, len(rows) - n_fly, 997))
        + list(range(len(rows) - n_fly, len(rows), 7))
    )
    for i in spread:  # every standard design, a spread of the grid and of the flywheel batches
        r, v = rows[i], variants[i]
        assert (r["name"], r["source"]) == (v["name"], v["source"])  # names with commas are quoted
        assert {k: float(x) for k, x in r.items() if "." in k and x} == v["vary"]
        for k in (
            "frame_length",
            "crank_length",
            "mean_force_N",
            "peak_force_N",
            "sampled_peak_force_N",
            "power_W",
            "transmission_min_deg",
            "time_ratio",
            "force_limit_N",
            "inertia_kg_m2",
            "speed_fluctuation",
            "least_peak_force_N",
            "min_passing_speed_deg_s",
        ):
            assert (None if r[k] == "" else float(r[k])) == v[k], (i, k)
        assert (r["feasible"], r["pass"], r["reason"], r["failed"], r["model"]) == (
            str(v["feasible"]),
            str(v["pass"]),
            v["reason"] or "",
            v["failed"],
            v["model"],
        )
        fly = r["model"] in ("flywheel", "full dynamics")  # an energy model: the wheel's inertia given
        assert (r["inertia_kg_m2"] != "") == fly and (r["speed_fluctuation"] != "") == fly


def test_progress_bar_on_a_terminal_for_long_runs(tmp_path, qs_grid):
    """stderr on a pseudo-terminal: a run longer than a second draws the Rich progress bar."""
    from terminal import run_on_terminal

    code, text, _ = run_on_terminal(
        [
            sys.executable,
            "-m",
            "pumplink",
            "batch",
            qs_grid,
            "--fail-on",
            "none",
            "--samples",
            "1500",
            "--format",
            "csv",
            "--out",
            tmp_path / "g.csv",
        ],
        timeout=120,
        cwd=ROOT,
        stdout=subprocess.DEVNULL,
    )
    assert code == 0
    assert "━" in text and "/27216" in text  # the bar and its count
    assert "batch: 27216 variants" in text  # then the summary line
