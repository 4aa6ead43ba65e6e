"""Rows and tables of the textbook-mechanism commands (``slider``, ``slotted``, ``rocker``,
``structure``) and the verdict lines ``transmission`` shares with them.  Renderers only: every
number comes from :mod:`pumplink.studies.textbook` or
:mod:`pumplink.inputs.structure`.  Degrees appear
here only.  Tables fit 80 columns.
"""

from __future__ import annotations

import math
import sys
import textwrap
from typing import Any

from pumplink.output.formats import console, num, render
from pumplink.output.words import check_row as verdict_check_row

#: Words for the mechanism verdict's checks (``pumplink.studies.textbook.judge``).
CHECK_NAMES = {
    "pressure_angle": "largest pressure angle",
    "transmission_angle": "min transmission angle",
    "simulation": "simulation deviation",
}


def _value(kind: str, x):
    if x is None:
        return None
    return num(math.degrees(x)) if kind == "angle" else num(x)


def _unit(kind: str) -> str:
    return {"angle": "deg", "ratio": "-", "length": "length"}[kind]


def check_row(c) -> dict[str, Any]:
    """One check of a mechanism verdict (:class:`pumplink.verdict.Check`) in the pump verdict's
    JSON shape ({key, name, value, unit, relation, warn_limit, fail_limit, result})."""
    return verdict_check_row(c, name=CHECK_NAMES[c.key])


def verdict_fields(verdict, agrees: bool) -> dict[str, Any]:
    """The verdict's JSON fields, shared by the mechanism commands and ``transmission``."""
    return {
        "simulation": "agrees" if agrees else "disagrees",
        "simulation_agrees": bool(agrees),
        "verdict": str(verdict.outcome),
        "pass": bool(verdict.passed),
        "checks": [check_row(c) for c in verdict.checks],
    }


def synthesis_row(rep) -> dict[str, Any]:
    """JSON contract of the mechanism commands (angles in degrees, lengths in the input's unit)."""
    return {
        "mechanism": rep.mechanism,
        "task": rep.task,
        "given": {k: _value(kind, v) for k, _, kind, v in rep.given},
        "lengths": {k: num(v) for k, _, v in rep.lengths},
        "ratios": {k: num(v) for k, _, v in rep.ratios},
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
        **verdict_fields(rep.verdict, rep.agrees),
        "pairs": rep.pairs,
        "permissible_pressure_angle_deg": list(rep.permissible_pressure_deg),
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


def synthesis_labels(rep) -> dict[str, dict[str, str]]:
    """The words of the report's keys for the table: {"given": .., "lengths": .., "ratios": ..,
    "indicators": ..}."""
    return {
        "given": {k: label + (" [deg]" if kind == "angle" else "") for k, label, kind, _ in rep.given},
        "lengths": {k: label for k, label, _ in rep.lengths},
        "ratios": {k: label for k, label, _ in rep.ratios},
        "indicators": {i.key: i.label for i in rep.indicators},
    }


#: Deviations below this are rounding (a few eps of the lengths) and print as "< 1e-12".
ROUNDING_LEVEL = 1e-12


def print_wrapped(c, text: str) -> None:
    """``text`` on console ``c``, wrapped at 78 columns with a two-space hanging indent."""
    c.print("\n".join(textwrap.wrap(text, 78, subsequent_indent="  ")), markup=False)


def _limit_text(c, limit) -> str:
    if limit is None:
        return "—"
    return f"{limit:g}°" if c["unit"] == "deg" else f"{limit:.0e}"


def _limit(c, limit) -> str:
    if limit is None:
        return "—"
    return f"{'>' if c['relation'] == '<=' else '<'} {_limit_text(c, limit)}"


def _check_value(c, x) -> str:
    if x is None:
        return "—"
    if c["unit"] == "deg":
        return f"{x:.2f}°"
    # a deviation at rounding level is shown as such: its digits are the machine's, not the design's
    return f"{x:.1e}" if x >= ROUNDING_LEVEL else f"< {ROUNDING_LEVEL:.0e}"


def _reason(c) -> str:
    if c["value"] is None:
        return f"{c['name']}: no finite value (the simulation failed)"
    limit = c["fail_limit"] if c["result"] == "fail" else c["warn_limit"]
    side = "above" if c["relation"] == "<=" else "below"
    return f"{c['name']} {_check_value(c, c['value'])} {side} {_limit_text(c, limit)}"


def render_verdict(c, row: dict[str, Any]) -> None:
    """The checks table, the verdict line and where the limits come from (``c``: a console).

    ``row`` holds :func:`verdict_fields`, and for a pressure-angle check ``pairs`` and
    ``permissible_pressure_angle_deg`` (:func:`synthesis_row`).
    """
    from rich.table import Table

    t = Table(title="Verdict checks", title_justify="left")
    for h in ("check", "value", "warns if", "fails if", "result"):
        t.add_column(h, justify="left" if h == "check" else "right")
    for ch in row["checks"]:
        t.add_row(
            ch["name"],
            _check_value(ch, ch["value"]),
            _limit(ch, ch["warn_limit"]),
            _limit(ch, ch["fail_limit"]),
            ch["result"] if ch["result"] == "pass" else ch["result"].upper(),
        )
    c.print(t)
    bad = [ch for ch in row["checks"] if ch["result"] == "fail"] or [
        ch for ch in row["checks"] if ch["result"] == "warn"
    ]
    why = f" — {'; '.join(_reason(ch) for ch in bad)}" if bad else ""
    print_wrapped(c, f"VERDICT: {row['verdict']}{why}")
    for ch in row["checks"]:
        warn, fail = _limit_text(ch, ch["warn_limit"]), _limit_text(ch, ch["fail_limit"])
        if ch["key"] == "pressure_angle":
            lo, hi = row["permissible_pressure_angle_deg"]
            pair = "with a sliding pair" if row["pairs"] == "sliding" else "with revolute pairs only"
            print_wrapped(
                c,
                f"limits: the textbook's permissible largest pressure angle for a mechanism {pair} is "
                f"{lo:g}° ({hi:g}° in preliminary design): above {warn} warns, above {fail} (a transmission "
                "angle of 30°) fails; the lever-mechanism textbook, §2.4 (docs/mechanisms.md §4)",
            )
        elif ch["key"] == "transmission_angle":
            print_wrapped(
                c,
                f"limits: a transmission angle below {warn} (a pressure angle above the textbook's "
                f"permissible 45° for revolute pairs) warns, below {fail} fails: joint friction can "
                "jam the linkage; the lever-mechanism textbook, §2.4 (docs/mechanisms.md §4)",
            )


def render_synthesis(row: dict[str, Any], labels: dict[str, dict[str, str]], fmt: str, out=None) -> None:
    """One mechanism report as a table, JSON or one CSV row.

    ``labels`` maps the row's keys to their words (:func:`synthesis_labels`).
    """
    out = out or sys.stdout

    def as_json():
        return row

    def as_csv():
        flat = {k: v for k, v in row.items() if k not in ("notes", "checks")}
        flat.update({f"check_{ch['key']}": ch["result"] for ch in row["checks"]})
        return [flat]

    def table() -> None:
        from rich.markup import escape
        from rich.table import Table

        c = console(out)
        title = textwrap.wrap(f"{row['mechanism'].capitalize()}, {row['task']}", 78, subsequent_indent="  ")
        c.print("[bold]" + escape(title[0]) + "[/]" + "".join("\n" + escape(x) for x in title[1:]))
        given = ", ".join(f"{labels['given'].get(k, k)} = {_g(v, 'ratio')}" for k, v in row["given"].items())
        print_wrapped(c, f"given: {given}")
        if row["ratios"]:
            ratios = ", ".join(
                f"{labels['ratios'].get(k, k)} = {_g(v, 'ratio')}" for k, v in row["ratios"].items()
            )
            print_wrapped(c, f"ratios: {ratios}")
        t = Table(title="Lengths", title_justify="left")
        t.add_column("link")
        t.add_column("length [input unit]", justify="right")
        for k, v in row["lengths"].items():
            t.add_row(escape(labels["lengths"].get(k, k)), _g(v, "ratio"))
        c.print(t)
        asked = any(i["asked"] is not None for i in row["indicators"].values())
        heads = (
            ("quantity", "asked", "closed form", "simulated", "check")
            if asked
            else (
                "quantity",
                "closed form",
                "simulated",
                "check",
            )
        )
        what = (
            "asked, closed form, measured by simulation" if asked else "closed form, measured by simulation"
        )
        t = Table(title=f"Indicators: {what}", title_justify="left")
        for h in heads:
            t.add_column(h, justify="left" if h == "quantity" else "right")
        for k, i in row["indicators"].items():
            kind = "angle" if i["unit"] == "deg" else "ratio"
            cells = [escape(labels["indicators"].get(k, k))]
            if asked:
                cells.append(_g(i["asked"], kind))
            cells += [
                _g(i["closed_form"], kind),
                _g(i["simulated"], kind),
                "ok" if i["agrees"] else "[bold]DIFFERS[/]",
            ]
            t.add_row(*cells)
        c.print(t)
        for note in row["notes"]:
            print_wrapped(c, f"note: {note}")
        print_wrapped(
            c,
            "SIMULATION: agrees — the mechanism does what was asked"
            if row["simulation_agrees"]
            else "SIMULATION: disagrees — the mechanism does NOT do what was asked (see DIFFERS)",
        )
        render_verdict(c, row)

    # ----------------------------------------------------------------------------- structure

    render(fmt, out, as_json=as_json, as_csv=as_csv, table=table)


_ROMAN = {1: "I", 2: "II", 3: "III", 4: "IV", 5: "V", 6: "VI", 7: "VII", 8: "VIII"}


def _plural(n: int, word: str) -> str:
    """``word`` in the number that agrees with ``n`` (1 link, 2 links, 0 links)."""
    return word if n == 1 else word + "s"


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

    def as_csv():
        counts = {k: row[k] for k in row if k not in ("groups", "drivers", "reason", "passive_links")}
        counts["drivers"] = " ".join(row["drivers"])
        counts["passive_links"] = " ".join(row["passive_links"])
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
        return rows

    def table() -> None:
        from rich.markup import escape
        from rich.table import Table

        c = console(out)
        n, p1, p2 = row["moving_links"], row["lower_pairs"], row["higher_pairs"]
        c.print(f"[bold]{escape(row['name'])}[/]: structure analysis")
        c.print(
            f"n = {n} moving {_plural(n, 'link')}, p1 = {p1} lower {_plural(p1, 'pair')} (class V), "
            f"p2 = {p2} higher {_plural(p2, 'pair')} (class IV)"
        )
        c.print(f"W = 3n − 2p1 − p2 = 3·{n} − 2·{p1} − {p2} = {row['formula_mobility']} (Chebyshev)")
        if row["passive_links"]:
            passive = row["passive_links"]
            words = f"passive {_plural(len(passive), 'link')}, left out of the decomposition"
            c.print(f"{words}: {escape(', '.join(passive))}")
        c.print(
            f"redundant constraints q = {row['redundant_constraints']}, local mobilities = "
            f"{row['local_mobilities']}: working mobility W0 = {row['mobility']}"
        )
        if row["drivers"]:
            drivers = row["drivers"]
            kind = "primary mechanisms" if len(drivers) > 1 else "a primary mechanism"
            c.print(
                f"driving {_plural(len(drivers), 'link')}: {escape(', '.join(drivers))} ({kind}, class I)"
            )
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

    render(fmt, out, as_json=lambda: row, as_csv=as_csv, table=table)
