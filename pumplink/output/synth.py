"""`pumplink synth`: the Table-1-style dead-centre synthesis, as a table, JSON or CSV.

Renderers only render: every number comes from the library's results.
"""

from __future__ import annotations

import sys
from typing import TYPE_CHECKING, Any

from pumplink.output.formats import console, deg, num, render
from pumplink.output.formats import fmt as _f

if TYPE_CHECKING:
    from pumplink.studies.force import Design


def design_row(d: Design) -> dict[str, Any]:
    """The JSON contract of one synthesised design."""
    s, lk = d.synthesis, d.spec.linkage
    return {
        "name": d.spec.name,
        "feasible": d.feasible,
        "error": d.error,
        "L1": lk.L1,
        "D1": lk.D1,
        "b": lk.b,
        "swing_deg": lk.swing,
        "frame_length": num(s.frame_length),
        "beta_deg": deg(s.beta),
        "psi1_deg": deg(s.psi1),
        "psi2_deg": deg(s.psi2),
        "crank_length": num(s.crank_length),
        "coupler_length": num(s.coupler_length),
        "rocker_length": num(s.rocker_length),
        "handle_length": num(s.handle_length),
        "handle_stroke": num(d.handle_stroke),
        "rocker_pivot": [num(s.pivot_x), num(s.pivot_y)],
        "dead_centres_deg": {"extended": deg(s.dead_centre_extended), "folded": deg(s.dead_centre_folded)},
        "time_ratio": num(s.time_ratio),
        "stroke_plus_x_crank_deg": deg(s.stroke_plus_x),
        "transmission_angle_deg": {"min": deg(s.transmission_min), "max": deg(s.transmission_max)},
    }


#: ``pumplink synth`` shows designs side by side (one column each) up to this many; more
#: designs get one row each.
TRANSPOSED_DESIGNS = 4


def render_designs(designs: list[Design], fmt: str, out=None) -> None:
    """`pumplink synth`: the Table-1-style synthesis, laid out for an 80-column terminal.

    Up to :data:`TRANSPOSED_DESIGNS` designs: one column per design, one row per quantity (with
    its unit).  More: one numbered row per design with the essential columns, the names below.
    """
    out = out or sys.stdout
    rows = [design_row(d) for d in designs]

    def as_json():
        return {"designs": rows}

    def as_csv():
        return rows

    def table() -> None:
        from rich import box
        from rich.markup import escape
        from rich.table import Table

        c = console(out)
        notes = []
        for n, r in enumerate(rows, 1):
            if not r["feasible"]:
                notes.append(f"({n}) {r['name']}: infeasible: {r['error']}.")
        title = "Dead-centre synthesis, Eq. (1)–(2) of the pump paper"
        if len(designs) <= TRANSPOSED_DESIGNS:
            t = Table(
                title=title,
                title_justify="left",
                box=box.SIMPLE_HEAD,
                pad_edge=False,
                caption="DC: dead centre, the crank angle where crank and coupler line up",
                caption_justify="left",
            )
            t.add_column("quantity", no_wrap=True)
            for n, r in enumerate(rows, 1):
                t.add_column(
                    escape(r["name"]) if len(designs) == 1 else f"({n})", justify="right", overflow="fold"
                )
            lines = [
                ("L1, stand to pivot [m]", lambda d, r: _f(d.spec.linkage.L1)),
                ("D1, pivot below axle [m]", lambda d, r: _f(d.spec.linkage.D1)),
                ("b, stand width [m]", lambda d, r: _f(d.spec.linkage.b)),
                ("handle H [m]", lambda d, r: _f(d.spec.linkage.handle)),
                ("swing Δθ [°]", lambda d, r: _f(d.spec.linkage.swing, "{:.1f}")),
                ("frame l1 [m]", lambda d, r: _f(r["frame_length"], "{:.4f}")),
                ("crank l2 [m]", lambda d, r: _f(r["crank_length"], "{:.4f}")),
                ("coupler l3 [m]", lambda d, r: _f(r["coupler_length"], "{:.4f}")),
                ("rocker l4 [m]", lambda d, r: _f(d.spec.linkage.rocker, "{:.4f}")),
                ("β [°]", lambda d, r: _f(r["beta_deg"], "{:.2f}")),
                ("ψ1 [°]", lambda d, r: _f(r["psi1_deg"], "{:.2f}")),
                ("ψ2 [°]", lambda d, r: _f(r["psi2_deg"], "{:.2f}")),
                ("time ratio K", lambda d, r: _f(r["time_ratio"], "{:.4f}")),
                (
                    "transmission γ [°]",
                    lambda d, r: (
                        f"{_f(r['transmission_angle_deg']['min'], '{:.1f}')}–"
                        f"{_f(r['transmission_angle_deg']['max'], '{:.1f}')}"
                    ),
                ),
                ("DC extended, crank [°]", lambda d, r: _f(r["dead_centres_deg"]["extended"], "{:.2f}")),
                ("DC folded, crank [°]", lambda d, r: _f(r["dead_centres_deg"]["folded"], "{:.2f}")),
                ("grip stroke [m]", lambda d, r: _f(r["handle_stroke"], "{:.3f}")),
                (
                    "feasible",
                    lambda d, r: "[green]yes[/]" if r["feasible"] else "[red]no[/]",
                ),
            ]
            for label, get in lines:
                t.add_row(escape(label), *(get(d, r) for d, r in zip(designs, rows)))
            c.print(t)
            if len(designs) > 1:
                for n, r in enumerate(rows, 1):
                    c.print(f"({n}) {r['name']}", markup=False)
        else:
            t = Table(
                title=title,
                title_justify="left",
                box=box.SIMPLE_HEAD,
                pad_edge=False,
                caption="lengths [m], angles [°]; l2 crank, l3 coupler, H handle, Δθ swing, K time ratio, "
                "γ smallest transmission angle min(γmin, 180° − γmax); names below",
                caption_justify="left",
            )
            for h in ("#", "L1", "D1", "b", "l4", "H", "Δθ", "l2", "l3", "K", "γ", "ok"):
                t.add_column(h, justify="left" if h == "ok" else "right")
            for n, (d, r) in enumerate(zip(designs, rows), 1):
                lk = d.spec.linkage
                tr = r["transmission_angle_deg"]
                gamma = None if tr["min"] is None else min(tr["min"], 180.0 - tr["max"])
                t.add_row(
                    str(n),
                    _f(lk.L1, "{:g}"),
                    _f(lk.D1, "{:g}"),
                    _f(lk.b, "{:g}"),
                    _f(lk.rocker, "{:g}"),
                    _f(lk.handle, "{:g}"),
                    _f(lk.swing, "{:g}"),
                    _f(r["crank_length"], "{:.4f}"),
                    _f(r["coupler_length"], "{:.4f}"),
                    _f(r["time_ratio"], "{:.4f}"),
                    _f(gamma, "{:.1f}"),
                    "[green]yes[/]" if r["feasible"] else f"[red]no ({n})[/]",
                )
            c.print(t)
            for n, r in enumerate(rows, 1):
                c.print(f"{n}: {r['name']}", markup=False)
        for line in notes:
            c.print(line, markup=False)

    render(fmt, out, as_json=as_json, as_csv=as_csv, table=table)
