"""`pumplink tolerance`: the spread of a design's builds, the share that pass, the holes that matter
and how exactly to drill them (docs/tolerance.md).

Renderers only render: every number comes from :func:`pumplink.studies.tolerance_study.study`.
"""

from __future__ import annotations

import math
import sys
from typing import TYPE_CHECKING, Any

from pumplink.output.formats import console, num, render
from pumplink.output.words import CHECK_LABELS, L_PER_MIN

if TYPE_CHECKING:
    from pumplink.studies.tolerance import Allocation
    from pumplink.studies.tolerance_study import Result, Robust, RobustCheck

#: The reported quantities: key, JSON key, words, unit as printed, factor from SI, digits.
QUANTITY_VIEW = (
    ("swing", "swing_deg", "handle swing", "deg", 180.0 / math.pi, 2),
    ("stroke", "stroke_m", "grip stroke", "m", 1.0, 3),
    ("grip_low", "grip_low_m", "lowest grip height", "m", 1.0, 3),
    ("grip_high", "grip_high_m", "highest grip height", "m", 1.0, 3),
    ("dead_centre_extended", "dead_centre_extended_deg", "extended dead centre", "deg", 180.0 / math.pi, 2),
    ("dead_centre_folded", "dead_centre_folded_deg", "folded dead centre", "deg", 180.0 / math.pi, 2),
    ("transmission_angle", "transmission_angle_deg", "transmission angle", "deg", 180.0 / math.pi, 2),
    ("grip_speed", "grip_speed_m_s", "peak grip speed", "m/s", 1.0, 3),
    ("peak_force", "peak_force_N", "peak force", "N", 1.0, 2),
    ("mean_force", "mean_force_N", "mean force", "N", 1.0, 2),
    ("flow", "flow_l_min", "flow", "l/min", L_PER_MIN, 2),
)
#: Words for the groups of holes the allocation gives one tolerance (pumplink.studies.tolerance.GROUPS).
GROUP_WORDS = {
    "crank": "the crank holes (O2, A)",
    "coupler": "the coupler holes (A, B)",
    "rocker": "the rocker holes (O4, B)",
    "grip": "the grip on the handle",
    "stand": "the axle and rocker pivot on the stand",
}
SHARE_RULE = "Wilson score interval, 95 %"


def mm(x: float) -> str:
    """A tolerance in mm for people: ±0.5 mm, ±2 mm."""
    return f"±{x * 1000:g} mm"


def _margin_label(key: str) -> str:
    base, _, warn = key.partition(":")
    for end in ("_low", "_high"):
        if base.endswith(end) and base[: -len(end)] in CHECK_LABELS:
            base = f"{CHECK_LABELS[base[: -len(end)]]} ({end[1:]} end)"
            break
    else:
        base = CHECK_LABELS.get(base, base)
    return base + (" (warning limit)" if warn else "")


def allocation_words(a: Allocation, groups) -> str:
    """The allocation as a sentence a fitter acts on: the tighter groups first, then what the
    others can take."""
    if a.reason is not None:
        return f"no tolerance keeps the builds passing: {a.reason}"
    names = [g for g, _ in groups]
    below = [GROUP_WORDS[g] for g, t in zip(names, a.groups) if not math.isfinite(t)]
    if below:
        return (
            f"{' and '.join(below)} would need better than ±0.1 mm, which no hand-built pump holds: "
            "give the design more margin (pumplink optimize or size with --tolerance)"
        )
    values = sorted(set(a.groups))
    if len(values) == 1:
        return f"every hole and pivot can take {mm(values[0])}"
    parts = []
    for v in values[:-1]:
        who = [GROUP_WORDS[g] for g, t in zip(names, a.groups) if t == v]
        parts.append(f"{' and '.join(who)} to {mm(v)}")
    rest = [GROUP_WORDS[g] for g, t in zip(names, a.groups) if t == values[-1]]
    text = "hold " + "; ".join(parts)
    return f"{text}; the others ({', '.join(rest)}) can take {mm(values[-1])}"


def _share_row(s) -> dict[str, Any]:
    return {"share": num(s.value), "count": s.count, "builds": s.n, "low": num(s.low), "high": num(s.high)}


def tolerance_row(res: Result) -> dict[str, Any]:
    """The JSON contract of ``pumplink tolerance`` (tolerances and lengths in mm, forces in N)."""
    prob, fo = res.problem, res.first_order
    tol = prob.tolerances
    a = res.allocation
    per_mm = 1e-3  # a gradient per metre -> per millimetre
    contrib = fo.contributions(fo.pass_margin, tol)
    sigma = fo.sigma(tol)
    return {
        "name": prob.name,
        "builds": prob.samples,
        "seed": prob.seed,
        "distribution": tol.distribution,
        "sigma_rule": "uniform: ±t, σ = t/√3" if tol.distribution == "uniform" else "normal: t = 3σ",
        "strict": prob.strict,
        "tolerances_mm": {k: t * 1000 for (k, _, _), t in zip(res.holes, tol.holes)},
        "nominal_verdict": ("PASS", "PASS with warnings", "FAIL")[res.nominal_level],
        "models": {
            label: count / prob.samples for label, count in zip(res.model_labels, res.models) if count
        },
        "spread": {
            jk: {
                "nominal": num(res.spread[k].nominal * f),
                "median": num(res.spread[k].median * f),
                "p5": num(res.spread[k].p5 * f),
                "p95": num(res.spread[k].p95 * f),
                "std": num(res.spread[k].std * f),
            }
            for k, jk, _, _, f, _ in QUANTITY_VIEW
        },
        "builds_pass": _share_row(res.passed),
        "builds_pass_without_warnings": _share_row(res.clean),
        "share_interval": SHARE_RULE,
        "first_order_pass_share": num(res.first_order_share),
        "target": res.target,
        "meets_target": res.meets_target,
        "fail_share": {k: v for k, v in res.fails.items() if v},
        "warn_share": {k: v for k, v in res.warns.items() if v},
        "not_crank_rockers": res.infeasible,
        "pass_margin": {
            "binding": fo.binding,
            "relative": num(fo.nominal_pass_margin),
            "value": num(fo.margin[fo.binding]),
            "limit": num(fo.limit[fo.binding]),
        },
        "first_order_std": {
            "peak_force_N": num(fo.spread(fo.peak_force, tol)),
            "mean_force_N": num(fo.spread(fo.mean_force, tol)),
            **{f"margin_{k}": num(v) for k, v in sigma.items()},
        },
        "sensitivities": [
            {
                "hole": key,
                "axis": axis,
                "peak_force_N_per_mm": num(fo.peak_force[j] * per_mm),
                "mean_force_N_per_mm": num(fo.mean_force[j] * per_mm),
                "pass_margin_per_mm": num(fo.pass_margin[j] * per_mm),
            }
            for j, (key, axis) in enumerate(res.dimensions)
        ],
        "matters_most": [
            {"hole": res.holes[i][0], "share_of_spread": num(contrib[i])}
            for i in sorted(range(len(res.holes)), key=lambda i: -contrib[i])
        ],
        "allocation": {
            "target": a.target,
            "tolerances_mm": {g: num(t * 1000) for (g, _), t in zip(res.groups, a.groups)},
            "critical": [g for (g, _), c in zip(res.groups, a.critical) if c and a.reason is None],
            "first_order_pass_share": num(a.share),
            "words": allocation_words(a, res.groups),
        },
    }


def build_rows(res: Result):
    """One CSV row per build: its number, its offsets [mm], its quantities and its verdict."""
    v = res.values
    outcomes = ("PASS", "PASS with warnings", "FAIL")
    dims = [f"{k}_{axis}_mm" for k, axis in res.dimensions]
    for i in range(res.problem.samples):
        row: dict[str, Any] = {"build": i}
        row.update(zip(dims, (float(x) * 1000 for x in res.offsets[i])))
        for k, jk, _, _, f, _ in QUANTITY_VIEW:
            row[jk] = num(v[k][i] * f)
        row["verdict"] = outcomes[int(v["level"][i])]
        yield row


def summary_lines(res: Result) -> list[str]:
    """The shares in words (the table's last lines; on stderr beside CSV)."""
    prob = res.problem
    p, c = res.passed, res.clean
    lines = [
        f"builds that pass: {p.value:.1%} of {p.n:,} ({p.low:.1%}-{p.high:.1%}, {SHARE_RULE})",
        f"  without warnings: {c.value:.1%} ({c.low:.1%}-{c.high:.1%})",
        f"  first-order estimate: {res.first_order_share:.1%}" + (" without warnings" if prob.strict else ""),
    ]
    failing = sorted(((v, k) for k, v in res.fails.items() if v), reverse=True)
    if failing:
        lines.append(
            "failing: " + "; ".join(f"{CHECK_LABELS.get(k, k)} in {v:.1%} of builds" for v, k in failing)
        )
    if res.infeasible:
        lines.append(f"{res.infeasible:,} builds are not crank-rockers (the crank cannot turn)")
    return lines


def render_tolerance(res: Result, fmt: str, out=None) -> None:
    """`pumplink tolerance`: the table, JSON, or one CSV row per build (the shares on stderr)."""
    out = out or sys.stdout
    row = tolerance_row(res)

    def as_csv():
        for line in summary_lines(res):
            sys.stderr.write(line + "\n")
        return build_rows(res)

    def table() -> None:
        from rich.markup import escape
        from rich.table import Table

        prob, fo = res.problem, res.first_order
        tol = prob.tolerances
        c = console(out)
        given = sorted(set(tol.holes))
        what = (
            f"every hole and pivot {mm(given[0])}"
            if len(given) == 1
            else ", ".join(f"{k} {mm(t)}" for (k, _, _), t in zip(res.holes, tol.holes))
        )
        c.print(f"[bold]{escape(prob.name)}[/]: {prob.samples:,} builds, {escape(what)}")
        models = ", ".join(f"{k} {v:.0%}" for k, v in row["models"].items())
        c.print(f"{row['sigma_rule']} on each coordinate; seed {prob.seed}", markup=False)
        c.print(f"the design: {row['nominal_verdict']}; the builds decided by {models}", markup=False)
        t = Table(title="The builds (5 % and 95 %: percentiles)", title_justify="left")
        for h, j in (("quantity", "left"), ("design", "right"), ("median", "right"), ("5 %", "right"),
                     ("95 %", "right")):  # fmt: skip
            t.add_column(h, justify=j)
        for k, _jk, words, unit, f, d in QUANTITY_VIEW:
            s = res.spread[k]
            if not math.isfinite(s.nominal):
                continue
            cells = [
                f"{x * f:.{d}f}" if math.isfinite(x) else "—" for x in (s.nominal, s.median, s.p5, s.p95)
            ]
            t.add_row(f"{words} \\[{unit}]", *cells)
        c.print(t)
        for line in summary_lines(res):
            c.print(line, markup=False)
        contrib = fo.contributions(fo.pass_margin, tol)
        order = sorted(range(len(res.holes)), key=lambda i: -contrib[i])
        m = Table(
            title=f"What matters (first order; margin: {_margin_label(fo.binding)}, "
            f"{fo.nominal_pass_margin:.1%} to its limit)",
            title_justify="left",
        )
        m.add_column("hole")
        m.add_column("peak force \\[N/mm]\nalong/x, across/y", justify="right")
        m.add_column("share of\nthe spread", justify="right")
        for i in order:
            key, _, words = res.holes[i]
            g = fo.peak_force[2 * i : 2 * i + 2] * 1e-3
            m.add_row(words, f"{g[0]:+.2f}, {g[1]:+.2f}", f"{contrib[i]:.0%}")
        c.print(m)
        c.print(
            f"first-order spread of the peak force: σ = {fo.spread(fo.peak_force, tol):.2f} N "
            f"(the builds': {res.spread['peak_force'].std:.2f} N)",
            markup=False,
        )
        a = res.allocation
        share = f"; first order: {a.share:.1%} pass" if a.reason is None else ""
        c.print(
            f"[bold]For {a.target:.0%} of builds to pass[/] ({a.distribution}{share}): "
            f"{escape(allocation_words(a, res.groups))}"
        )

    render(fmt, out, as_json=lambda: row, as_csv=as_csv, table=table)


# ----------------------------------------------------------------------------- robust searches
def robust_row(robust: Robust | None, check: RobustCheck | None) -> dict[str, Any] | None:
    """The JSON of a robust search (``size``/``optimize --tolerance``): what was asked, the
    answer's first-order share of builds that pass and the Monte Carlo check (None: none asked;
    the shares None where no design was found)."""
    if robust is None:
        return None
    mc = None if check is None else check.monte_carlo
    return {
        "tolerance_mm": robust.tolerance * 1000,
        "distribution": robust.tolerances.distribution,
        "target": robust.target,
        "without_warnings": robust.strict,
        "first_order_share": None if check is None else num(check.first_order),
        "monte_carlo": None if mc is None else {**_share_row(mc), "interval": SHARE_RULE},
        "meets_target": None if check is None else check.meets,
    }


def robust_line(row: dict[str, Any]) -> str:
    """A robust search's answer in one sentence (``row`` from :func:`robust_row`)."""
    ask = (
        f"builds within ±{row['tolerance_mm']:g} mm that pass"
        f"{' without warnings' if row['without_warnings'] else ''}"
    )
    if row["monte_carlo"] is None:
        return f"{ask}: at least {row['target']:.0%} asked; no design found"
    mc = row["monte_carlo"]
    if row["meets_target"]:
        verdict = "meets"
    elif mc["high"] >= row["target"]:
        verdict = "is, within its interval, at"
    else:
        verdict = "falls short of"
    return (
        f"{ask}: {row['first_order_share']:.1%} to first order (the search's estimate); "
        f"{mc['share']:.1%} of {mc['builds']:,} built at random ({mc['low']:.1%}-{mc['high']:.1%}), "
        f"which {verdict} the {row['target']:.0%} asked"
    )


__all__ = [
    "allocation_words",
    "build_rows",
    "render_tolerance",
    "robust_line",
    "robust_row",
    "tolerance_row",
]
