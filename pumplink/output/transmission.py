"""`pumplink transmission`: the optimal-transmission crank-rocker and its simulation.

Renderers only render: every number comes from the library's results.
"""

from __future__ import annotations

import sys
from typing import TYPE_CHECKING, Any

import numpy as np

from pumplink.output.formats import console, deg, num, render, report_table
from pumplink.output.formats import fmt as _f

if TYPE_CHECKING:
    pass


BINDING_TEXT = {
    0: "both extremes (gamma_min = 180 - gamma_max)",
    1: "gamma_min (stationary on the arc)",
    2: "180 - gamma_max (stationary on the arc)",
}


def transmission_rows(opt, sim, comparisons=(), printed_gamma_min=None, check=None) -> dict[str, Any]:
    """JSON contract of ``pumplink transmission``.

    Parameters
    ----------
    opt : :class:`pumplink.mechanisms.crank_rocker.OptimalCrankRocker` (scalar).
    sim : :class:`pumplink.mechanisms.crank_rocker.MeasuredMotion` of the optimum.
    comparisons : :class:`pumplink.mechanisms.crank_rocker.Comparison` of published designs.
    printed_gamma_min : the transmission angle the paper prints for its diagram design [deg].
    check : :class:`pumplink.studies.textbook_rocker.OptimumCheck` (simulation agreement and
        verdict), or None.
    """
    from pumplink.output.mechanisms import verdict_fields

    out = {
        "time_ratio": num(opt.time_ratio),
        "theta_deg": deg(opt.theta),
        "swing_deg": deg(opt.swing),
        "crank": num(opt.crank),
        "coupler": num(opt.coupler),
        "rocker": num(opt.rocker),
        "frame": num(opt.frame),
        "rocker_to_frame": num(opt.rocker_to_frame),
        "min_transmission_deg": deg(opt.transmission),
        "gamma_min_deg": deg(opt.gamma_min),
        "gamma_max_deg": deg(opt.gamma_max),
        "binding": BINDING_TEXT[int(opt.binding)],
        "crank_pivot_side": "rocker-pivot side of the chord C1C2"
        if opt.side < 0
        else "far side of the chord C1C2",
        "simulated": {
            "swing_deg": deg(sim.swing),
            "time_ratio": num(sim.time_ratio),
            "min_transmission_deg": deg(sim.transmission),
            "assembles": sim.assembles,
        },
        "compare": [],
    }
    for cmp in comparisons:
        c, k, r, f = cmp.lengths
        out["compare"].append(
            {
                "design": cmp.label,
                "crank": c,
                "coupler": k,
                "rocker": r,
                "frame": f,
                "min_transmission_deg": deg(cmp.transmission),
                "ours_better_by_deg": num(np.degrees(opt.transmission - cmp.transmission)),
                "simulated_swing_deg": deg(cmp.motion.swing),
                "simulated_time_ratio": num(cmp.motion.time_ratio),
            }
        )
    if comparisons:
        out["printed_gamma_min_deg"] = printed_gamma_min
    if check is not None:
        out.update(verdict_fields(check.verdict, check.agrees))
    return out


def render_transmission(row: dict[str, Any], fmt: str, out=None) -> None:
    """`pumplink transmission`: the optimum, its simulation and the comparison rows."""
    out = out or sys.stdout

    def as_json():
        return row

    def as_csv():
        flat = {k: v for k, v in row.items() if k not in ("compare", "checks")}
        flat.update({f"check_{ch['key']}": ch["result"] for ch in row.get("checks", ())})
        return [flat]

    def table() -> None:
        from rich.markup import escape

        from pumplink.output.mechanisms import print_wrapped, render_verdict

        c = console(out)
        c.print(
            f"[bold]Optimal-transmission crank-rocker[/] for K = {row['time_ratio']:g} "
            f"(θ = {row['theta_deg']:.6f}°), swing φ = {row['swing_deg']:g}°, rocker = {row['rocker']:g}"
        )
        t = report_table(
            "Link lengths (in the rocker's unit) and transmission angle",
            "(1) optimum (this tool)"
            + "".join(f"; ({n}) {escape(cmp['design'])}" for n, cmp in enumerate(row["compare"], 2)),
        )
        sim = row["simulated"]
        cols = [
            {
                "crank": row["crank"],
                "coupler": row["coupler"],
                "rocker": row["rocker"],
                "frame": row["frame"],
                "ratio": row["rocker_to_frame"],
                "gamma": row["min_transmission_deg"],
                "swing": sim["swing_deg"],
                "k": sim["time_ratio"],
            }
        ] + [
            {
                "crank": cmp["crank"],
                "coupler": cmp["coupler"],
                "rocker": cmp["rocker"],
                "frame": cmp["frame"],
                "ratio": cmp["rocker"] / cmp["frame"],
                "gamma": cmp["min_transmission_deg"],
                "swing": cmp["simulated_swing_deg"],
                "k": cmp["simulated_time_ratio"],
            }
            for cmp in row["compare"]
        ]
        t.add_column("quantity", no_wrap=True)
        for n in range(1, len(cols) + 1):
            t.add_column(f"({n})", justify="right")
        for label, key, f in (
            ("crank", "crank", "{:.6f}"),
            ("coupler", "coupler", "{:.6f}"),
            ("rocker", "rocker", "{:.6f}"),
            ("frame", "frame", "{:.6f}"),
            ("rocker / frame", "ratio", "{:.6f}"),
            ("min transmission [°]", "gamma", "{:.9f}"),
            ("simulated swing [°]", "swing", "{:.9f}"),
            ("simulated K", "k", "{:.9f}"),
        ):
            t.add_row(escape(label), *(_f(col[key], f) for col in cols))
        c.print(t)
        c.print(
            f"γmin = {row['gamma_min_deg']:.9f}°, γmax = {row['gamma_max_deg']:.9f}°; "
            f"binding: {row['binding']}; "
            f"crank pivot on the {row['crank_pivot_side']}"
        )
        for cmp in row["compare"]:
            c.print(
                f"optimum is better than the {cmp['design']} by {cmp['ours_better_by_deg']:.9f}°",
                markup=False,
            )
        if row["compare"]:
            c.print(
                f"(the paper prints γmin = {row['printed_gamma_min_deg']}° for its diagram design; "
                "its own Eq. (4) gives the value above)",
                markup=False,
            )
        if "verdict" in row:
            print_wrapped(
                c,
                "SIMULATION: agrees — the linkage swings through the asked swing with the asked K and "
                "the optimum's transmission angle"
                if row["simulation_agrees"]
                else "SIMULATION: disagrees — the simulated linkage does NOT do what was asked (its "
                "swing, K or transmission angle differ, or it does not run)",
            )
            render_verdict(c, row)

    render(fmt, out, as_json=as_json, as_csv=as_csv, table=table)
