"""`pumplink optimize`: the design search's result, its constraints and the verdicts.

Renderers only render: every number comes from the library's results.
"""

from __future__ import annotations

import sys
from typing import TYPE_CHECKING, Any

from pumplink.output.formats import console, num, render, report_table
from pumplink.output.formats import fmt as _f
from pumplink.output.precision import at_optimum, difference, optimum_text, slack
from pumplink.output.tolerance import robust_line, robust_row
from pumplink.output.words import OUTCOME_MARKUP, check_row, water_row

if TYPE_CHECKING:
    from pumplink.search.optimize import OptimizationResult


def optimize_row(res: OptimizationResult) -> dict[str, Any]:
    """JSON contract of ``pumplink optimize`` (spec units: m, deg, N).

    ``optimum`` and ``spec_design`` each carry the verdict of ``pumplink force`` on that design
    (``verdict``, ``pass``, ``checks``), ``peak_force_N`` the verdict's peak (the flywheel's least
    peak force when the spec gives inertia) and ``dead_band_peak_force_N`` the quasi-static peak
    outside the dead bands.  ``meets_constraints`` is about the search's own constraints
    (--grip-height, --stroke, transmission angle), which the optimum always meets.

    Every figure of the optimum (its coordinates, what is read there, the constraints' slack and
    the improvement) carries the digits the search determines (:mod:`pumplink.output.precision`):
    ``tolerance`` is the search's relative tolerance, and a binding constraint's slack is 0.  The
    spec's own design is not searched: its figures are given in full.  ``evaluations``,
    ``generations`` and ``polished`` say how this run went; they follow the search's path, which
    the processor's rounding moves.
    """
    p = res.problem
    b, s = res.at_best, res.at_spec
    names = p.constraint_names()
    op = p.spec.operator
    tol = res.tolerance
    # the spec's objective less the optimum's, to the last decimal the optimum's objective carries
    gain = None if res.improvement is None else difference(res.improvement, b.objective[0], tol)

    def searched(x):
        return at_optimum(x, tol)

    def judged(r, at=num) -> dict[str, Any]:
        checks = [check_row(c, r) for c in r.checks]
        return {
            "model": r.model,
            "peak_force_N": at(r.verdict_peak_force),
            "dead_band_peak_force_N": at(r.dead_band_peak_force),
            "mean_force_N": at(r.mean_force),
            "flow_l_min": at(water_row(r.water)["flow_l_min"]),
            "verdict": r.outcome,
            "pass": r.passed,
            "checks": [{**c, "value": at(c["value"])} for c in checks],
        }

    return {
        "name": p.spec.name,
        "objective": p.objective,
        "model": p.model,
        "inertia_kg_m2": None if p.inertia is None else num(p.inertia),
        "speed_fluctuation": op.speed_fluctuation if p.flywheel else None,
        "speed_deg_s": op.speed,
        "seed": res.seed,
        "axle_height_m": p.axle_height,
        "grip_height_range_m": list(p.grip_height),
        "stroke_range_m": list(p.stroke),
        "force_limit_N": p.force_limit,
        "variables": [
            {
                "key": k,
                "unit": u,
                "lower": float(lo),
                "upper": float(hi),
                "spec": num(p.spec_value(k)),
                "optimum": searched(v),
            }
            for k, u, lo, hi, v in zip(p.names, res.variable_units, p.lower, p.upper, res.x)
        ],
        "optimum": {
            **judged(res.best_result, searched),
            "transmission_deg": searched(b.transmission[0]),
            "grip_height_m": [searched(b.grip_low[0]), searched(b.grip_high[0])],
            "stroke_m": searched(b.stroke[0]),
            "rocker_pivot_height_m": searched(p.axle_height - res.best.linkage.D1),
            "meets_constraints": True,
        },
        "spec_design": {
            **judged(res.spec_result),
            "transmission_deg": num(s.transmission[0]),
            "meets_constraints": not res.spec_violates,
            "violated": list(res.spec_violates),
        },
        "improvement_N": gain,
        "improvement_pct": None if gain is None else searched(100 * gain / float(s.objective[0])),
        "tolerance": tol,
        "constraints": [
            {"name": n, "unit": u, "slack": slack(g, n in res.binding, tol, f), "binding": n in res.binding}
            for n, u, g, f in zip(names, res.constraint_units, b.slack[:, 0], res.constrained)
        ],
        "binding": list(res.binding) + list(res.at_bounds),
        "evaluations": res.evaluations,
        "generations": res.iterations,
        "polished": res.polished,
        "robust": robust_row(p.robust, res.robust),
    }


def render_optimize(row: dict[str, Any], fmt: str, out=None, strict: bool = False) -> None:
    """`pumplink optimize`: variables, forces and verdicts, constraints and what binds."""
    out = out or sys.stdout

    def as_json():
        return row

    def as_csv():
        flat = {
            k: v
            for k, v in row.items()
            if k
            not in (
                "variables",
                "constraints",
                "binding",
                "spec_design",
                "grip_height_range_m",
                "stroke_range_m",
            )
        }
        flat["optimum"] = {k: v for k, v in row["optimum"].items() if k != "checks"}
        for v in row["variables"]:
            flat[f"{v['key']}_optimum"] = v["optimum"]
        flat["binding"] = "; ".join(row["binding"])
        return [flat]

    def table() -> None:
        from rich.markup import escape

        c = console(out)
        fly = row["speed_fluctuation"] is not None  # an energy model decides (flywheel or full dynamics)
        model = (
            f"{row['model']}, J = {row['inertia_kg_m2']:.4g} kg·m², δ ≤ {row['speed_fluctuation']:g}, at "
            f"{row['speed_deg_s']:g} deg/s"
            if fly
            else row["model"]
        )
        c.print(
            f"[bold]{escape(row['name'])}[/]: "
            + (
                "maximise the flow with no check failing "
                if row["objective"] == "flow"
                else f"minimise the {row['objective']} operator force "
            )
            + f"(model: {model}; seed {row['seed']}); axle height "
            f"{row['axle_height_m']:g} m, grip height "
            f"{row['grip_height_range_m'][0]:g}–{row['grip_height_range_m'][1]:g} m, "
            f"stroke {row['stroke_range_m'][0]:g}–{row['stroke_range_m'][1]:g} m"
        )
        t = report_table("Variables")
        for h in ("key", "bounds", "spec", "optimum"):
            t.add_column(h, justify="left" if h == "key" else "right")
        tol = row["tolerance"]
        for v in row["variables"]:
            t.add_row(
                f"{v['key']} \\[{v['unit']}]",
                f"{v['lower']:g} … {v['upper']:g}",
                f"{v['spec']:.4f}",
                optimum_text(v["optimum"], tol),
            )
        c.print(t)
        o, s = row["optimum"], row["spec_design"]
        t = report_table(
            "Forces and verdicts (as pumplink force)",
            "peak: the verdict's peak"
            + (f" ({s['model']} / {o['model']})" if fly else " outside the dead bands"),
        )
        for h in ("design", "peak [N]", "mean [N]", "γ [°]", "verdict"):
            t.add_column(escape(h), justify="left" if h in ("design", "verdict") else "right")
        t.add_row(
            "spec's own design",
            _f(s["peak_force_N"], "{:.2f}", none="∞"),
            _f(s["mean_force_N"], "{:.2f}"),
            _f(s["transmission_deg"], "{:.2f}"),
            OUTCOME_MARKUP[s["verdict"]],
        )
        t.add_row(
            "[bold]optimum[/]",
            optimum_text(o["peak_force_N"], tol, none="∞"),
            optimum_text(o["mean_force_N"], tol),
            optimum_text(o["transmission_deg"], tol),
            OUTCOME_MARKUP[o["verdict"]],
        )
        c.print(t)
        for label, d in (("spec's own design", s), ("optimum", o)):
            bad = [ch for ch in d["checks"] if ch["result"] != "pass"]
            if bad:
                c.print(
                    f"{label}: "
                    + "; ".join(
                        f"{ch['result']}s on {ch['name']} {_f(ch['value'], '{:.3g}', none='∞')} {ch['unit']}"
                        for ch in bad
                    ),
                    markup=False,
                )
        if not s["meets_constraints"]:
            c.print(
                f"the spec's own design is outside the search's limits: {'; '.join(s['violated'])}",
                markup=False,
            )
        t = report_table("Constraints at the optimum (slack >= 0 is met)")
        for h in ("constraint", "slack", "binding"):
            t.add_column(h, justify="right" if h == "slack" else "left")
        for k in row["constraints"]:
            value = _f(k["slack"], "{:g}")  # rounded in the row: to the figure's last decimal, 0 if it binds
            t.add_row(k["name"], f"{value} {k['unit']}", "[bold]binds[/]" if k["binding"] else "")
        c.print(t)
        if row["objective"] == "flow":
            c.print(
                f"flow {_f(s['flow_l_min'], '{:.1f}')} l/min → {_f(o['flow_l_min'], '{:.1f}')} l/min "
                "(the spec's own design → the optimum)",
                markup=False,
            )
        elif row["improvement_N"] is not None:
            c.print(improvement_line(row), markup=False)
        c.print(f"binding: {', '.join(row['binding']) or 'none (interior optimum)'}", markup=False)
        c.print(
            f"grip {o['grip_height_m'][0]:.3f}–{o['grip_height_m'][1]:.3f} m, stroke {o['stroke_m']:.3f} m, "
            f"rocker pivot {pivot_height(o['rocker_pivot_height_m'])}",
            markup=False,
        )
        if not o["pass"]:
            c.print(
                "no design inside these bounds and limits passes: the best one found still fails "
                f"({', '.join(ch['name'] for ch in o['checks'] if ch['result'] == 'fail')}); "
                f"it is held back by: {', '.join(row['binding']) or 'nothing at a bound'}. "
                "Widen the bounds that bind (--vary), or relax --grip-height / --stroke.",
                markup=False,
            )
        if row["robust"] is not None:
            c.print(robust_line(row["robust"]), markup=False)
        tail = " — fails under --strict" if strict and o["verdict"] == "PASS with warnings" else ""
        how = f" ({o['model']})" if fly else ""
        c.print(
            f"VERDICT: {OUTCOME_MARKUP[o['verdict']]} for the optimum: peak{how} "
            f"{optimum_text(o['peak_force_N'], tol, none='∞')} N vs limit {row['force_limit_N']:g} N{tail}"
        )

    render(fmt, out, as_json=as_json, as_csv=as_csv, table=table)


def improvement_line(row: dict[str, Any]) -> str:
    """The objective force of the spec's own design against the optimum's, in words: how much
    lower, the same (to the digits the search determines), or how much more it needs and which
    of the search's limits the spec's design breaks to do better."""
    key = "peak_force_N" if row["objective"] == "peak" else "mean_force_N"
    s, o, tol = row["spec_design"], row["optimum"], row["tolerance"]
    gain, pct = row["improvement_N"], row["improvement_pct"]
    forces = f"{row['objective']} force {_f(s[key], '{:.2f}')} N → {optimum_text(o[key], tol)} N"
    if gain > 0:
        return f"{forces} ({pct:.1f} % lower than the spec's own design)"
    if gain == 0:
        return f"{forces} (the spec's own design needs the same)"
    return (
        f"the optimum needs {optimum_text(-gain, tol)} N more than the spec's own design, which breaks: "
        f"{'; '.join(s['violated'])}"
    )


def pivot_height(height: float) -> str:
    """The rocker pivot's height [m] in words: '0.150 m above the ground', or '0.300 m below the
    ground (needs a pit)' for a negative height (never 'above' with a minus sign)."""
    if height < 0:
        return f"{-height:.3f} m below the ground (needs a pit)"
    return f"{height:.3f} m above the ground"
