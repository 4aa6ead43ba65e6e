"""Unit tests of the output layer: JSON-safe numbers, CSV flattening, strict JSON (NaN -> null) and
the number formatting of the Rich tables (rendered into a string, as when piped).

The formatter is checked against the values of the result it was given (rounding, placeholders for
missing values); the physics of those values is checked elsewhere (test_cli.py, test_force.py).
"""

from __future__ import annotations

import csv
import io
import json
import math
import re

import numpy as np
import pytest

from pumplink.inputs.pump import parse_spec
from pumplink.output.force import force_summary, render_force, sample_rows
from pumplink.output.formats import console, deg, num, write_csv
from pumplink.output.synth import design_row, render_designs
from pumplink.studies.force import design, force_analysis

BASE = {
    "name": "Report test",
    "wheel": {"radius": 0.25},
    "linkage": {"L1": 0.40, "D1": 0.20, "b": 0.10, "rocker": 0.20, "handle": 1.00, "swing": 60.0},
    "load": {"rope_force": 45.0},
}
# D1 = 3 m: psi2 < 0, no crank-rocker (docs/physics.md) -> NaN lengths inside
INFEASIBLE = {**BASE, "name": "Deep", "linkage": {**BASE["linkage"], "D1": 3.0}}


def _no_nan(tok):
    raise AssertionError(f"non-standard JSON token {tok!r}")


def strict_json(text: str):
    assert not re.search(r"\b(NaN|Infinity)\b", text), text[:200]
    return json.loads(text, parse_constant=_no_nan)


# ----------------------------------------------------------------------------- num / deg
@pytest.mark.parametrize(
    "x,want",
    [
        (1.5, 1.5),
        (np.float64(2.25), 2.25),
        (np.int64(3), 3.0),
        (0, 0.0),
        (math.nan, None),
        (np.nan, None),
        (math.inf, None),
        (-math.inf, None),
    ],
)
def test_num(x, want):
    got = num(x)
    assert got == want and (got is None or type(got) is float)


def test_deg():
    assert deg(math.pi) == pytest.approx(180.0, rel=1e-15)
    assert deg(-math.pi / 2) == pytest.approx(-90.0, rel=1e-15)
    assert deg(math.nan) is None and deg(np.inf) is None


# ----------------------------------------------------------------------------- CSV
def read_csv(text: str) -> list[dict]:
    return list(csv.DictReader(io.StringIO(text)))


def test_write_csv_flattens_nested_keys():
    rows = [
        {
            "name": "a",
            "x": 1.5,
            "rocker_pivot": [-0.45, -0.2],
            "dead_centres_deg": {"extended": 182.5, "folded": None},
            "outer": {"inner": {"deep": 7}},
            "checks": [{"name": "c", "pass": True}],
            "flag": True,
            "err": None,
        },
        {
            "name": "b, with comma",
            "x": 2.0,
            "rocker_pivot": [0.1, 0.2],
            "dead_centres_deg": {"extended": 1.0, "folded": 2.0},
            "outer": {"inner": {"deep": 8}},
            "checks": [],
            "flag": False,
            "err": 'why "quoted"',
        },
    ]
    out = io.StringIO()
    write_csv(rows, out)
    text = out.getvalue()
    header = text.splitlines()[0].split(",")
    assert header == [
        "name",
        "x",
        "rocker_pivot_x",
        "rocker_pivot_y",
        "dead_centres_deg_extended",
        "dead_centres_deg_folded",
        "outer_inner_deep",
        "flag",
        "err",
    ]
    got = read_csv(text)
    assert len(got) == 2
    assert got[0]["rocker_pivot_x"] == "-0.45" and got[0]["rocker_pivot_y"] == "-0.2"
    assert got[0]["dead_centres_deg_folded"] == "" and got[0]["err"] == ""  # None -> empty cell
    assert got[1]["name"] == "b, with comma" and got[1]["err"] == 'why "quoted"'
    assert got[1]["outer_inner_deep"] == "8"
    assert "checks" not in got[0]


def test_write_csv_of_nothing_writes_nothing():
    out = io.StringIO()
    write_csv([], out)
    assert out.getvalue() == ""


def test_csv_of_real_designs_keeps_float_precision():
    rows = [design_row(design(parse_spec(BASE))), design_row(design(parse_spec(INFEASIBLE)))]
    out = io.StringIO()
    write_csv(rows, out)
    got = read_csv(out.getvalue())
    assert len(got) == 2
    assert float(got[0]["frame_length"]) == rows[0]["frame_length"]  # repr round trip, no rounding
    assert got[1]["crank_length"] == "" and got[1]["feasible"] == "False"
    assert "nan" not in out.getvalue().lower()


# ----------------------------------------------------------------------------- JSON
def test_infeasible_design_json_has_nulls_not_nan():
    r = force_analysis(parse_spec(INFEASIBLE))
    assert math.isnan(r.design.synthesis.crank_length)  # the NaN really is there inside
    out = io.StringIO()
    render_force(r, "json", out=out)
    obj = strict_json(out.getvalue())
    assert obj["feasible"] is False and obj["pass"] is False
    assert obj["crank_length"] is None and obj["mean_force_N"] is None and obj["peak_force_N"] is None
    assert obj["dead_centres_deg"] == {"extended": None, "folded": None}
    out = io.StringIO()
    render_designs([r.design], "json", out=out)
    assert strict_json(out.getvalue())["designs"][0]["time_ratio"] is None


def test_dead_centre_sample_is_null_in_json_and_csv():
    spec = parse_spec(BASE)
    syn = design(spec).synthesis
    dc = [float(np.degrees(syn.dead_centre_extended)), float(np.degrees(syn.dead_centre_folded))]
    r = force_analysis(spec, at_deg=[dc[0], 90.0, dc[1]])
    assert math.isnan(r.samples.force[0]) and math.isnan(r.samples.force[2])
    out = io.StringIO()
    render_force(r, "json", out=out)
    s = strict_json(out.getvalue())["samples"]
    assert [x["force_N"] is None for x in s] == [True, False, True]
    assert [x["singular"] for x in s] == [True, False, True]
    assert s[1]["force_N"] == pytest.approx(float(r.samples.force[1]), rel=1e-15)
    out = io.StringIO()
    render_force(r, "csv", out=out)
    rows = read_csv(out.getvalue())
    assert [row["force_N"] == "" for row in rows] == [True, False, True]


def test_zero_dead_band_gives_strict_json():
    """dead_band = 0: the peak window reaches a dead centre, the peak is infinite -> null, and FAIL."""
    r = force_analysis(parse_spec({**BASE, "operator": {"dead_band": 0.0}}), samples=12)
    out = io.StringIO()
    render_force(r, "json", summary=True, out=out)
    obj = strict_json(out.getvalue())
    assert obj["peak_force_N"] is None and obj["pass"] is False
    assert all(c["value"] is None or math.isfinite(c["value"]) for c in obj["checks"])


def test_sample_rows_match_summary_and_count():
    r = force_analysis(parse_spec(BASE), samples=10)
    rows = sample_rows(r)
    assert len(rows) == 10
    assert [row["crank_deg"] for row in rows] == pytest.approx([36.0 * i for i in range(10)], abs=1e-12)
    summ = force_summary(r)
    assert "samples" not in summ and summ["samples_n"] == 10
    json.dumps(summ, allow_nan=False)
    json.dumps(rows, allow_nan=False)


# ----------------------------------------------------------------------------- tables
def render(fn, *args, **kw) -> str:
    out = io.StringIO()
    fn(*args, out=out, **kw)
    return out.getvalue()


def test_console_to_a_string_has_no_escape_codes():
    out = io.StringIO()
    console(out).print("[bold red]x[/] [green]y[/]")
    assert "\x1b" not in out.getvalue() and "x y" in out.getvalue()


def test_synth_table_number_formatting():
    good, bad = design(parse_spec(BASE)), design(parse_spec(INFEASIBLE))
    text = render(render_designs, [good, bad], "table")
    assert "\x1b" not in text
    row = design_row(good)
    # rounded, not raw floats: lengths to 4 decimals, K to 4, dead centres to 2
    for v, nd in (
        (row["frame_length"], 4),
        (row["crank_length"], 4),
        (row["coupler_length"], 4),
        (row["time_ratio"], 4),
        (row["dead_centres_deg"]["extended"], 2),
        (row["dead_centres_deg"]["folded"], 2),
    ):
        assert f"{v:.{nd}f}" in text, (v, nd)
        assert repr(v) not in text
    # the infeasible row: placeholders, never "nan"; its reason is printed (whitespace-normalised)
    assert not re.search(r"\bnan\b", text, re.I)
    assert "—" in text
    assert design_row(bad)["error"][:50] in " ".join(text.split())


def test_force_table_number_formatting():
    r = force_analysis(parse_spec(BASE), samples=8)  # 8 samples: every row shown, none on a dead centre
    text = render(render_force, r, "table")
    assert "\x1b" not in text and not re.search(r"\bnan\b", text, re.I)
    for f in r.samples.force:
        assert f"{abs(float(f)):.1f}" in text
    assert f"{r.mean_force:.1f}" in text and f"{r.dead_band_peak_force:.1f}" in text
    for unit in ("[N]", "[°]", "[m/s]"):
        assert unit in text
    assert "PASS" in text


def test_force_table_marks_dead_centres_in_a_long_sweep():
    r = force_analysis(parse_spec(BASE), samples=360)
    text = render(render_force, r, "table")
    assert text.count("DC extended") == 1 and text.count("DC folded") == 1
    syn = r.design.synthesis
    for dc in (syn.dead_centre_extended, syn.dead_centre_folded):
        assert f"{math.degrees(dc):.2f}" in text


def test_force_table_of_a_failing_and_an_infeasible_design():
    heavy = force_analysis(parse_spec({**BASE, "load": {"rope_force": 400.0}}), samples=8)
    assert "FAIL" in render(render_force, heavy, "table")
    text = render(render_force, force_analysis(parse_spec(INFEASIBLE)), "table")
    assert "FAIL" in text and not re.search(r"\bnan\b", text, re.I)
