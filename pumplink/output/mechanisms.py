"""Rows and tables of the textbook-mechanism commands (``slider``, ``slotted``, ``rocker``,
``structure``).  Renderers only: every number comes from :mod:`pumplink.studies.textbook` or
:mod:`pumplink.inputs.structure`.  Degrees appear here only.  Tables fit 80 columns.
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
    title = textwrap.wrap(f"{row['mechanism'].capitalize()}, {row['task']}", 78, subsequent_indent="  ")
    c.print("[bold]" + escape(title[0]) + "[/]" + "".join("\n" + escape(x) for x in title[1:]))
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


# ----------------------------------------------------------------------------- structure
_ROMAN = {1: "I", 2: "II", 3: "III", 4: "IV", 5: "V", 6: "VI", 7: "VII", 8: "VIII"}


def _roman(n: int) -> str:
    return _ROMAN.get(n, str(n))


def structure_row(name: str, a, passive_links=()) -> dict[str, Any]:
    """JSON contract of ``pumplink structure``.

    Parameters
    ----------
    name : the mechanism's name;  a : :class:`~pumplink.mechanisms.structure.StructureAnalysis`;
    passive_links : the links the input marked passive.
    """
    return {
        "name": name,
        "passive_links": list(passive_links),
        "moving_links": a.moving_links,
        "lower_pairs": a.lower_pairs,
        "higher_pairs": a.higher_pairs,
        "formula_mobility": a.formula_mobility,
        "redundant_constraints": a.redundant_constraints,
        "local_mobilities": a.local_mobilities,
        "mobility": a.mobility,
        "drivers": list(a.drivers),
        "groups": [
            {
                "links": list(g.links),
                "internal_joints": list(g.internal_joints),
                "lead_joints": list(g.lead_joints),
                "class": g.group_class,
                "order": g.order,
                "dyad_type": g.dyad_type,
            }
            for g in a.groups
        ],
        "mechanism_class": a.mechanism_class,
        "decomposed": a.decomposed,
        "reason": a.reason,
    }


def render_structure(row: dict[str, Any], fmt: str, out=None) -> None:
    """`pumplink structure`: the counts, the drivers and the Assur groups in attachment order."""
    out = out or sys.stdout
    if fmt == "json":
        return write_json(row, out)
    counts = {k: row[k] for k in row if k not in ("groups", "drivers", "reason", "passive_links")}
    counts["drivers"] = " ".join(row["drivers"])
    counts["passive_links"] = " ".join(row["passive_links"])
    if fmt == "csv":
        rows = [
            {
                **counts,
                "group": i,
                "group_links": " ".join(g["links"]),
                "group_internal_joints": " ".join(g["internal_joints"]),
                "group_lead_joints": " ".join(g["lead_joints"]),
                "group_class": g["class"],
                "group_order": g["order"],
                "group_dyad_type": g["dyad_type"] or "",
            }
            for i, g in enumerate(row["groups"], 1)
        ] or [counts]
        return write_csv(rows, out)
    from rich.markup import escape
    from rich.table import Table

    c = console(out)
    n, p1, p2 = row["moving_links"], row["lower_pairs"], row["higher_pairs"]
    c.print(f"[bold]{escape(row['name'])}[/]: structure analysis")
    c.print(f"n = {n} moving links, p1 = {p1} lower pairs (class V), p2 = {p2} higher pairs (class IV)")
    c.print(f"W = 3n − 2p1 − p2 = 3·{n} − 2·{p1} − {p2} = {row['formula_mobility']} (Chebyshev)")
    if row["passive_links"]:
        c.print(f"passive link(s), left out of the decomposition: {escape(', '.join(row['passive_links']))}")
    c.print(
        f"redundant constraints q = {row['redundant_constraints']}, local mobilities = "
        f"{row['local_mobilities']}: working mobility W0 = {row['mobility']}"
    )
    if row["drivers"]:
        c.print(f"driving link(s): {escape(', '.join(row['drivers']))} (primary mechanisms, class I)")
    if row["groups"]:
        t = Table(title="Assur groups in the order they are attached", title_justify="left")
        for h in ("#", "links", "internal pairs", "leads", "class", "order", "type"):
            t.add_column(h, justify="right" if h in ("#", "class", "order") else "left")
        for i, g in enumerate(row["groups"], 1):
            t.add_row(
                str(i),
                escape(", ".join(g["links"])),
                escape(", ".join(g["internal_joints"]) or "—"),
                escape(", ".join(g["lead_joints"])),
                _roman(g["class"]),
                str(g["order"]),
                g["dyad_type"] or "—",
            )
        c.print(t)
    if row["decomposed"]:
        c.print(f"mechanism class: {_roman(row['mechanism_class'])} (its highest group class)")
    else:
        c.print(
            "\n".join(textwrap.wrap(f"NOT DECOMPOSED: {row['reason']}", 78, subsequent_indent="  ")),
            markup=False,
        )
