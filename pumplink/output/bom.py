"""`pumplink bom`: the bill of materials as a table, CSV or JSON (docs/workshop.md §4).

Renderers only render: every number comes from :func:`pumplink.studies.bom.bom`.
"""

from __future__ import annotations

import math
import sys
from typing import Any

from pumplink.output.formats import console, num, render, report_table


def bom_rows(b) -> list[dict[str, Any]]:
    """One row per item (CSV and JSON): part, stock, count, length [mm], mass each and in all [kg]."""
    return [
        {
            "part": i.part,
            "stock": i.stock,
            "count": i.count,
            "length_mm": None if not math.isfinite(i.length) else round(i.length * 1000.0, 1),
            "mass_each_kg": None if not math.isfinite(i.mass) else round(i.mass, 3),
            "mass_kg": None if not math.isfinite(i.mass) else round(i.total_mass, 3),
            "note": i.note,
        }
        for i in b.items
    ]


def bom_json(b) -> dict[str, Any]:
    """The bill of materials as JSON: the items, their mass, the links against the dynamics."""
    return {
        "name": b.name,
        "items": bom_rows(b),
        "mass_kg": num(round(b.mass, 3)),
        "links": {
            "coupler_kg": num(b.coupler_mass),
            "handle_kg": num(b.handle_mass),
            "dynamics_coupler_kg": num(b.dynamics_coupler_mass),
            "dynamics_handle_kg": num(b.dynamics_handle_mass),
        },
        "tube_note": b.tube_note,
    }


def links_sentence(b) -> str:
    """The moving links' tube between their joints against what the dynamics counts, in words."""
    return (
        f"between their joints the coupler's tube weighs {b.coupler_mass:.3f} kg and the handle's "
        f"{b.handle_mass:.3f} kg; the dynamics counts {b.dynamics_coupler_mass:.3f} and "
        f"{b.dynamics_handle_mass:.3f} kg (the pieces cut are longer by the edges beyond the outer holes)"
    )


def render_bom(b, fmt: str, out=None) -> None:
    """The bill of materials (:class:`pumplink.studies.bom.Bom`) in ``fmt``."""
    out = out or sys.stdout

    def table() -> None:
        c = console(out)
        t = report_table(f"Bill of materials: {b.name}")
        for h in ("part", "stock", "count", "cut", "mass"):
            t.add_column(h, justify="right" if h in ("count", "cut", "mass") else "left")
        for i in b.items:
            cut = f"{i.length * 1000:.0f} mm" if math.isfinite(i.length) else ""
            mass = f"{i.total_mass:.2f} kg" if math.isfinite(i.mass) else ""
            t.add_row(i.part, i.stock, str(i.count), cut, mass)
        c.print(t)
        for i in b.items:
            if i.note:
                c.print(f"{i.part}: {i.note}", markup=False)
        c.print(f"total {b.mass:.1f} kg of the parts with a mass; {links_sentence(b)}", markup=False)
        if b.tube_note is not None:
            c.print(f"note: {b.tube_note}", markup=False)

    render(fmt, out, as_json=lambda: bom_json(b), as_csv=lambda: bom_rows(b), table=table)
