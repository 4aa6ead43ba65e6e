"""Rows and tables of the textbook-mechanism commands (``slider``, ``slotted``, ``rocker``,
``structure``).  Renderers only: every number comes from :mod:`pumplink.synthesis` or
:mod:`pumplink.structure_spec`.  Degrees appear here only.  Tables fit 80 columns.
"""

from __future__ import annotations

import math
import sys
import textwrap
from typing import Any

from pumplink.output.formats import console, num, write_csv, write_json

_RESULT_TEXT = {"pass": "pass", "marginal": "marginal", "exceeds": "EXCEEDS"}


def _value(kind: str, x):
    if x is None:
        return None
    return num(math.degrees(x)) if kind == "angle" else num(x)


def _unit(kind: str) -> str:
    return {"angle": "deg", "ratio": "-", "length": "length"}[kind]


def synthesis_row(rep) -> dict[str, Any]:
    """JSON contract of the synthesis commands (angles in degrees, lengths in the input's unit)."""
    p = rep.pressure
    return {
        "mechanism": rep.mechanism,
        "task": rep.task,
        "given": {k: _value(kind, v) for k, _, kind, v in rep.given},
        "lengths": {k: num(v) for k, _, v in rep.lengths},
        "indicators": {
            i.key: {
                "unit": _unit(i.kind),
                "asked": _value(i.kind, i.asked),
                "closed_form": _value(i.kind, i.closed_form),
                "simulated": _value(i.kind, i.simulated),
                "agrees": i.agrees,
            }
            for i in rep.indicators
        },
        "pressure_angle": {
            "largest_deg": num(math.degrees(p.value)),
            "permissible_deg": list(p.permissible_deg),
            "driven_link": p.driven,
            "result": p.result,
        },
        "simulation_agrees": rep.agrees,
        "notes": list(rep.notes),
    }


def _g(x, kind="length") -> str:
    if x is None:
        return "—"
    if not math.isfinite(x):
        return "—"
    if kind == "angle":
        return f"{x:.6f}°"
    return f"{x:.9g}" if kind == "ratio" else f"{x:.6g}"


def synthesis_labels(rep) -> dict[str, str]:
    """The words of the report's keys for the table: {"given": .., "lengths": .., "indicators": ..}."""
    return {
        "given": {k: label + (" [deg]" if kind == "angle" else "") for k, label, kind, _ in rep.given},
        "lengths": {k: label for k, label, _ in rep.lengths},
        "indicators": {i.key: i.label for i in rep.indicators},
    }


def render_synthesis(row: dict[str, Any], labels: dict[str, str], fmt: str, out=None) -> None:
    """One synthesis report as a table, JSON or one CSV row.

    ``labels`` maps the row's keys to their words (:func:`synthesis_labels`).
    """
    out = out or sys.stdout
    if fmt == "json":
        return write_json(row, out)
    if fmt == "csv":
        flat = {k: v for k, v in row.items() if k != "notes"}
        return write_csv([flat], out)
    from rich.markup import escape
    from rich.table import Table

    c = console(out)
    c.print(f"[bold]{escape(row['mechanism'].capitalize())}[/], {escape(row['task'])}")
    given = ", ".join(f"{labels['given'].get(k, k)} = {_g(v, 'ratio')}" for k, v in row["given"].items())
    c.print("\n".join(textwrap.wrap(f"given: {given}", 78, subsequent_indent="  ")), markup=False)
    t = Table(title="Lengths", title_justify="left")
    t.add_column("link")
    t.add_column("length [input unit]", justify="right")
    for k, v in row["lengths"].items():
        t.add_row(escape(labels["lengths"].get(k, k)), _g(v, "ratio"))
    c.print(t)
    t = Table(title="Indicators: asked, closed form, measured by simulation", title_justify="left")
    for h in ("quantity", "asked", "closed form", "simulated", "check"):
        t.add_column(h, justify="left" if h == "quantity" else "right")
    for k, i in row["indicators"].items():
        kind = "angle" if i["unit"] == "deg" else "ratio"
        t.add_row(
            escape(labels["indicators"].get(k, k)),
            _g(i["asked"], kind),
            _g(i["closed_form"], kind),
            _g(i["simulated"], kind),
            "ok" if i["agrees"] else "[bold]DIFFERS[/]",
        )
    c.print(t)
    p = row["pressure_angle"]
    lo, hi = p["permissible_deg"]
    c.print(
        f"largest pressure angle {p['largest_deg']:.2f}°: {_RESULT_TEXT[p['result']]}\n"
        f"  (permissible for a {p['driven_link']} driven link: ≤ {lo:g}°, up to {hi:g}° in\n"
        "  preliminary design; the lever-mechanism textbook, §2.4)",
        markup=False,
    )
    for note in row["notes"]:
        c.print("\n".join(textwrap.wrap(f"note: {note}", 78, subsequent_indent="  ")), markup=False)
    c.print(
        "SIMULATION: the mechanism does what was asked"
        if row["simulation_agrees"]
        else "SIMULATION: the mechanism does NOT do what was asked (see DIFFERS)",
        markup=False,
    )
