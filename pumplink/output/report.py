"""The design report: one self-contained HTML file (images embedded as base64 PNG).

Spec, synthesis table, verdict with its model and checks, the water it delivers and the people it
serves, the force chart, the linkage drawing, the loads on the parts with the pins' life and the
released handle, the cut list, the bill of materials and the field sheet.  Renderers only: every number
comes from the library's results (:class:`pumplink.studies.force.ForceResult`,
:class:`pumplink.studies.drawing.Drawing`, :class:`pumplink.studies.workshop.Workshop`).
"""

from __future__ import annotations

import base64
import html
import math
import tempfile
from pathlib import Path

import numpy as np

from pumplink.errors import SpecError
from pumplink.output.bom import links_sentence
from pumplink.output.charts import force_curve
from pumplink.output.drawings import linkage_drawing
from pumplink.output.formats import atomic_write, check_output, fmt
from pumplink.output.sheet import sheet_html
from pumplink.output.template import cut_list_rows
from pumplink.output.words import check_label, model_line, water_lines
from pumplink.output.workshop import (
    load_rows,
    loads_title,
    parts_sentence,
    pin_life_sentence,
    workshop_release_line,
)
from pumplink.quantities import lines as quantity_lines

REPORT_SUFFIXES = (".html", ".htm")

CSS = """
body { font-family: system-ui, sans-serif; max-width: 60rem; margin: 2rem auto; color: #222; }
table { border-collapse: collapse; margin: 0.5rem 0 1.2rem; }
th, td { border: 1px solid #ccc; padding: 0.2rem 0.6rem; text-align: left; }
td.num { text-align: right; font-variant-numeric: tabular-nums; }
.pass { color: #176f2c; font-weight: bold; } .fail { color: #b00020; font-weight: bold; }
.warn { color: #8a6100; } pre { background: #f5f5f5; padding: 0.6rem; }
img { max-width: 100%; border: 1px solid #ddd; }
"""


def check_report_path(path) -> Path:
    """Validate the report path's extension before any work is done."""
    path = Path(path)
    if path.suffix.lower() not in REPORT_SUFFIXES:
        raise SpecError(f"--out {path}: unknown report type '{path.suffix}'; use a file ending in .html")
    return check_output(path, "--out")


def _png(draw, *args) -> str:
    """Base64 of the PNG that ``draw(*args, path)`` writes."""
    with tempfile.TemporaryDirectory() as tmp:
        p = Path(tmp) / "figure.png"
        draw(*args, p)
        return base64.b64encode(p.read_bytes()).decode("ascii")


def _table(rows, header=True, numeric=()) -> str:
    out = ["<table>"]
    for i, row in enumerate(rows):
        tag = "th" if header and i == 0 else "td"
        cells = []
        for j, cell in enumerate(row):
            cls = ' class="num"' if tag == "td" and j in numeric else ""
            cells.append(f"<{tag}{cls}>{html.escape(str(cell))}</{tag}>")
        out.append("<tr>" + "".join(cells) + "</tr>")
    out.append("</table>")
    return "\n".join(out)


def _deg(x) -> str:
    return fmt(np.degrees(x), "{:.2f}") + "°"


def _mm(x) -> str:
    return fmt(x * 1000, "{:.1f}") + " mm"


def synthesis_rows(r) -> list[tuple[str, str]]:
    """The dead-centre synthesis as (quantity, value) rows."""
    d = r.design
    s = d.synthesis
    return [
        ("quantity", "value"),
        ("frame l1 (O2-O4)", _mm(s.frame_length)),
        ("crank l2", _mm(s.crank_length)),
        ("coupler l3", _mm(s.coupler_length)),
        ("rocker l4", _mm(s.rocker_length)),
        ("handle H", _mm(s.handle_length)),
        ("grip stroke 2H·sin(Δθ/2)", _mm(d.handle_stroke)),
        ("rocker pivot O4", f"({_mm(s.pivot_x)}, {_mm(s.pivot_y)})"),
        ("extended dead centre, crank at", _deg(s.dead_centre_extended)),
        ("folded dead centre, crank at", _deg(s.dead_centre_folded)),
        ("time ratio K", fmt(s.time_ratio, "{:.4f}")),
        ("transmission angle range", f"{_deg(s.transmission_min)} to {_deg(s.transmission_max)}"),
        ("wheel torque Mw", f"{r.wheel_torque:.3f} N·m"),
        ("power at the spec's speed", f"{r.power:.1f} W at {r.speed_deg_s:g} deg/s"),
    ]


def verdict_html(r) -> str:
    """The verdict line, the model line and the checks table."""
    peak = r.verdict_peak_force
    css = {"PASS": "pass", "PASS with warnings": "warn", "FAIL": "fail"}[r.outcome]
    failing = ", ".join(check_label(c, r) for c in r.verdict.failures) if r.verdict is not None else ""
    head = (
        f'<p><span class="{css}">{html.escape(r.outcome)}</span>: mean {r.mean_force:.1f} N, peak '
        f"{fmt(peak, '{:.1f}', '∞')} N against the {r.force_limit:g} N limit (operator profile: "
        f"{html.escape(r.profile)})" + (f"; fails on {html.escape(failing)}" if failing else "") + ".</p>"
    )
    rows = [("check", "value", "warn if", "fail if", "result")]
    for c in r.checks:
        value = fmt(c.value, "{:.2f}", "∞" if c.value == math.inf else "—")
        bad = ">" if c.relation == "<=" else "<"
        warn = "" if c.warn_limit is None else f"{bad} {c.warn_limit:g} {c.unit}"
        fail = "" if c.fail_limit is None else f"{bad} {c.fail_limit:g} {c.unit}"
        result = {"pass": "pass", "warn": "warning", "fail": "FAIL"}[c.result]
        rows.append((check_label(c, r), f"{value} {c.unit}", warn, fail, result))
    return head + f"<p>{html.escape(model_line(r))}</p>" + _table(rows, numeric=(1, 2, 3))


def water_html(r) -> str:
    """The water it delivers (l/min), its share of what the operator profile's sustained power
    could lift at this head, and the people it serves: the evaluation's water figures, in the
    words ``pumplink force`` prints them."""
    use = r.design.spec.use
    lines = water_lines(r.water, r.power, r.profile, use.hours_per_day, use.litres_per_person_day)
    lines += quantity_lines(r.evaluation)  # the catalogue's quantities with a line of their own
    return "".join(f'<p class="water">{html.escape(line)}</p>' for line in lines)


def _service(r):
    sv = None if r.evaluation is None else r.evaluation.service
    return None if sv is None else sv.design(0)


def bom_html(b) -> str:
    """The bill of materials (:func:`pumplink.studies.bom.bom`) as a table, with its notes."""
    rows = [("part", "stock", "count", "cut", "mass", "note")]
    for i in b.items:
        cut = f"{i.length * 1000:.0f} mm" if math.isfinite(i.length) else ""
        mass = f"{i.total_mass:.2f} kg" if math.isfinite(i.mass) else ""
        rows.append((i.part, i.stock, i.count, cut, mass, i.note))
    notes = [links_sentence(b), *(n for n in (b.tube_note, b.ratchet_note) if n is not None)]
    return _table(rows, numeric=(2, 3, 4)) + "".join(f"<p>{html.escape(n)}.</p>" for n in notes)


def workshop_html(w, service=None) -> str:
    """The workshop's view (:func:`pumplink.studies.workshop.workshop`): the peak loads on the
    pins, the crank and the handle, what they mean for the parts, the pins' life and the released
    handle (``service``: the design's kick-back and ratchet)."""
    if w is None:
        return "<p>No crank-rocker: no loads to report.</p>"
    rows = [("where", "peak", "at crank"), *load_rows(w)]
    lines = [parts_sentence(w), pin_life_sentence(w), workshop_release_line(w, service)]
    return (
        f"<p>{html.escape(loads_title(w))}</p>"
        + _table(rows, numeric=(1, 2))
        + "".join(f"<p>{html.escape(line)}</p>" for line in lines if line is not None)
    )


def report_html(r, curve, dr, spec_toml: str, path, shop=None, bom=None, sheet=None) -> Path:
    """Write the report for one design (``r``: ForceResult, ``curve``: its ForceCurve, ``dr``:
    its Drawing, ``spec_toml``: the spec as TOML text, ``shop``: its workshop view, ``bom``: its
    bill of materials, ``sheet``: its field sheet) to ``path`` atomically."""
    path = check_report_path(path)
    name = html.escape(r.design.spec.name)
    force_png = _png(force_curve, r, curve)
    drawing_png = _png(lambda d, p: linkage_drawing(d, p), dr)
    cut = cut_list_rows(dr.parts, dr.tube_given, bom)
    parts = [
        "<!DOCTYPE html>",
        '<html lang="en"><head><meta charset="utf-8">',
        f"<title>{name}: pumplink design report</title><style>{CSS}</style></head><body>",
        f"<h1>{name}</h1>",
        "<p>Four-bar linkage for a hand-driven rope pump, designed with pumplink: dead-centre "
        "synthesis, operator force over the crank cycle, verdict, drawing and cut list.</p>",
        "<h2>Verdict</h2>",
        verdict_html(r),
        "<h2>Water</h2>",
        water_html(r),
        "<h2>Spec</h2>",
        f"<pre>{html.escape(spec_toml)}</pre>",
        "<h2>Synthesis</h2>",
        _table(synthesis_rows(r), numeric=(1,)),
        "<h2>Operator force</h2>",
        f'<img alt="operator force over one crank revolution" src="data:image/png;base64,{force_png}">',
        "<h2>Drawing</h2>",
        f'<img alt="the linkage at its dead centres, dimensioned" src="data:image/png;base64,{drawing_png}">',
        "<h2>Loads on the parts</h2>",
        workshop_html(shop, _service(r)),
        "<h2>Cut list</h2>",
        _table(cut, numeric=(2, 3, 5)),
        "<p>Hole centres and the 1:1 drilling template: <code>pumplink template SPEC</code>.</p>",
    ]
    if bom is not None:
        parts += [
            "<h2>Bill of materials</h2>",
            bom_html(bom),
            "<p>As CSV: <code>pumplink bom SPEC -f csv</code>.</p>",
        ]
    if sheet is not None:
        parts += [
            '<h2 id="field-sheet">Field sheet</h2>',
            sheet_html(sheet),
            "<p>On one A4 page: <code>pumplink sheet SPEC --out sheet.pdf</code>.</p>",
        ]
    parts.append("</body></html>")
    with atomic_write(path) as f:
        f.write("\n".join(parts) + "\n")
    return path
