"""The HTML design report (``pumplink report``) quotes the operator profile's own limits and the
water the design delivers, for every shipped spec and every operator profile.

The limits expected are the profiles' data (pumplink.profiles, docs/operators.md), the water
figures the formulas of docs/water.md written out here: the rope moves with the rim, so
Q = eta_v (pi d^2 / 4) omega r_w (W.1); the operator's sustained power lifts
Q* = eta_f eta_v P_sustained / (rho g H) (W.5), rho = 1000 kg/m^3, g = 9.81 m/s^2 (docs/physics.md
§5); the people served Q x hours a day / litres a person a day (W.6).  The report's text sections
are read in-process (its images are the charts' and the drawing's, tested with them).
"""

from __future__ import annotations

import html
import math
import re
import tomllib

import pytest
from shipped import PROFILE_NAMES, ROOT, ROPE_PUMP_SPECS, spec_id

from pumplink.inputs.pump import parse_spec
from pumplink.inputs.toml import spec_name
from pumplink.output.report import report_html, verdict_html, water_html
from pumplink.profiles import PROFILES
from pumplink.studies.force import force_analysis

#: The operator keys that override a profile's limits: left out of the copies, so that the
#: profile sets every limit.
OVERRIDES = ("force_limit", "sustained_power", "hour_power", "grip_height_min", "grip_height_max",
             "grip_speed_warn", "grip_speed_fail")  # fmt: skip


def _with_profile(path, profile):
    data = tomllib.loads(path.read_text(encoding="utf-8"))
    op = {k: v for k, v in data.get("operator", {}).items() if k not in OVERRIDES}
    data["operator"] = {**op, "profile": profile}
    return data, parse_spec(spec_name(data, path))


def _rows(page: str) -> list[list[str]]:
    """The checks table's rows (check, value, warn if, fail if, result), as text."""
    table = page[page.index("<table>") : page.index("</table>")]
    rows = re.findall(r"<tr>(.*?)</tr>", table, re.S)[1:]
    return [[html.unescape(c) for c in re.findall(r"<td[^>]*>(.*?)</td>", row, re.S)] for row in rows]


def _limit(cell: str) -> tuple[float, str] | None:
    m = re.fullmatch(r"[<>] (\S+) ?(.*)", cell)
    return None if m is None else (float(m.group(1)), m.group(2))


def _number(text: str, pattern: str) -> float:
    return float(re.search(pattern, text).group(1).replace(",", ""))


@pytest.mark.parametrize("profile", PROFILE_NAMES)
@pytest.mark.parametrize("path", ROPE_PUMP_SPECS, ids=spec_id)
def test_the_report_quotes_the_profile_s_limits_and_the_water(path, profile):
    data, spec = _with_profile(path, profile)
    p = PROFILES[profile]
    r = force_analysis(spec, keep_samples=False)
    page = verdict_html(r) + water_html(r)
    text = html.unescape(re.sub(r"<[^>]+>", "", page))
    assert f"against the {p.force_limit:g} N limit (operator profile: {profile})" in text
    # every limit of the checks table is its check's, and the operator's are the profile's
    by_key = {c.key: c for c in r.checks}
    profile_limits = {
        "mean_force": (None, p.force_limit),
        "peak_force": (None, p.force_limit),
        "power": (p.sustained_power, p.hour_power),
        "grip_speed": (p.grip_speed_warn, p.grip_speed_fail),
    }
    rows = _rows(page)
    assert len(rows) == len(r.checks)
    for (label, _value, warn, fail, _result), check in zip(rows, r.checks):
        got = tuple(None if _limit(c) is None else _limit(c)[0] for c in (warn, fail))
        assert got == (check.warn_limit, check.fail_limit), label
        if check.key in profile_limits:
            assert got == profile_limits[check.key], (label, got)
        if check.key == "grip_height":
            assert got[0] in p.grip_height_range, (label, got)
    assert {"mean_force", "peak_force", "power", "grip_speed"} <= by_key.keys()
    # the water: the flow, the share of what the profile's sustained power lifts, the people
    load, use = data["load"], data.get("use", {})
    if "head" not in load:
        assert "no flow figure" in text
        return
    eta_v, eta_f = load.get("volumetric_efficiency", 0.87), load.get("efficiency", 0.75)
    omega = math.radians(data["operator"].get("speed", 360.0))
    flow = eta_v * math.pi * load["pipe_diameter"] ** 2 / 4 * omega * data["wheel"]["radius"]  # (W.1)
    lifted = eta_f * eta_v * p.sustained_power / (1000.0 * 9.81 * load["head"])  # (W.5)
    people = flow * use.get("hours_per_day", 8.0) * 3600 * 1000 / use.get("litres_per_person_day", 20.0)
    assert _number(text, r"water: ([\d.]+) l/min") == pytest.approx(flow * 60_000, abs=0.05 + 1e-9)
    assert _number(text, r"of the ([\d.]+) l/min") == pytest.approx(lifted * 60_000, abs=0.05 + 1e-9)
    assert f"sustaining {p.sustained_power:g} W could lift" in text
    assert _number(text, r"that is (\d+)%") == pytest.approx(100 * flow / lifted, abs=0.5 + 1e-9)
    assert _number(text, r"serves about ([\d,]+) people") == pytest.approx(people, abs=0.5 + 1e-9)


def test_the_report_file_has_the_water_section(tmp_path):
    """The whole report, images and all, on the women's well: the water section, the bill of
    materials and the field sheet are in it."""
    from pumplink.inputs.pump import load_spec
    from pumplink.output.charts import pyplot
    from pumplink.output.report import bom_html
    from pumplink.output.sheet import sheet_html
    from pumplink.studies.bom import bom
    from pumplink.studies.drawing import drawing
    from pumplink.studies.force import force_curve
    from pumplink.studies.sheet import field_sheet
    from pumplink.studies.workshop import workshop

    pyplot()
    spec = load_spec(ROOT / "configs" / "women-operators-6m.toml")
    r = force_analysis(spec, keep_samples=False)
    b, fs = bom(spec), field_sheet(r)
    out = report_html(
        r, force_curve(r), drawing(spec), "", tmp_path / "r.html", shop=workshop(r), bom=b, sheet=fs
    )
    page = out.read_text(encoding="utf-8")
    assert "<h2>Water</h2>" in page and water_html(r) in page and verdict_html(r) in page
    assert "(operator profile: women)" in page and "a woman sustaining 60 W" in page
    # the bill of materials and the field sheet, as their own renderers give them
    assert "<h2>Bill of materials</h2>" in page and bom_html(b) in page
    assert '<h2 id="field-sheet">Field sheet</h2>' in page and sheet_html(fs) in page
    assert "the ratchet (24 teeth, 20 N·m) goes on the wheel&#x27;s axle O2" in page
