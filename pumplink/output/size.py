"""`pumplink size`: the sized pump, its water against what its operator could lift, what binds,
and the flow at other heads.

Renderers only render: every number comes from :func:`pumplink.search.size.size`.
"""

from __future__ import annotations

import sys
from typing import TYPE_CHECKING, Any

from pumplink.output.formats import console, num, render
from pumplink.output.tolerance import robust_line, robust_row
from pumplink.output.words import (
    CHECK_ADVICE,
    CHECK_LABELS,
    L_PER_MIN,
    OPERATOR_NOUNS,
    check_advice,
    check_row,
    duty_words,
    losses_word,
    losses_words,
    pit_words,
)
from pumplink.quantities import headline_items
from pumplink.quantities import lines as quantity_lines

if TYPE_CHECKING:
    from pumplink.search.size import SizeResult

#: The sized quantities: spec key, JSON key, words, unit as printed, factor from spec units.
DESIGN = (
    ("load.pipe_diameter", "pipe_diameter_mm", "pipe bore", "mm", 1000.0),
    ("operator.speed", "speed_deg_s", "wheel speed", "deg/s", 1.0),
    ("wheel.radius", "wheel_radius_m", "wheel radius", "m", 1.0),
    ("wheel.mass", "wheel_mass_kg", "wheel mass (at the rim)", "kg", 1.0),
    ("wheel.axle_height", "axle_height_m", "axle height", "m", 1.0),
    ("linkage.handle", "handle_m", "handle H", "m", 1.0),
    ("linkage.rocker", "rocker_m", "rocker", "m", 1.0),
    ("linkage.swing", "swing_deg", "swing", "deg", 1.0),
    ("linkage.L1", "L1_m", "rocker pivot beyond the stand L1", "m", 1.0),
    ("linkage.D1", "D1_m", "rocker pivot below the axle D1", "m", 1.0),
)


def _value(spec, key: str) -> float:
    section, name = key.split(".")
    return float(getattr(getattr(spec, section), name))


def size_row(res: SizeResult) -> dict[str, Any]:
    """The JSON contract of ``pumplink size``."""
    b = res.best
    spec, ev = b.spec, b.evaluation
    verdict = ev.verdict.design(0)
    return {
        "name": res.problem.spec.name,
        "head_m": res.problem.spec.load.head,
        "profile": spec.operator.limits.name,
        "allow_warnings": res.problem.allow_warnings,
        "found": res.found,
        "reason": None if res.found else _holding_back(res),
        "design": {k: num(_value(spec, key) * f) for key, k, _, _, f in DESIGN},
        "cycles_per_min": num(_value(spec, "operator.speed") / 6.0),
        "kept": list(res.problem.kept),
        "allow_pit": res.problem.allow_pit,
        "pit_depth_m": num(max(spec.linkage.D1 - spec.wheel.axle_height, 0.0)),
        "held": [{"key": k, "value": v, "built_in": b} for k, v, b in res.problem.held],
        "losses": losses_word(ev.water.design(0)),
        **{k: num(v) for k, v in headline_items(ev).items()},  # the catalogue's headline figures
        "verdict": verdict.outcome,
        "checks": [check_row(c) for c in verdict.checks],
        "binding": list(res.binding),
        "pipes": [
            {
                "pipe_diameter_mm": num(s.pipe * 1000),
                "found": s.found,
                "flow_l_min": num(s.flow * L_PER_MIN) if s.found else None,
                "excess": num(s.excess),
            }
            for s in res.tried
        ],
        "discharge": [
            {"head_m": h, "speed_deg_s": num(v), "flow_l_min": num(q * L_PER_MIN)}
            for h, v, q in res.discharge
        ],
        "evaluations": res.evaluations,
        "robust": robust_row(res.problem.robust, res.robust),
    }


def held_words(problem) -> str:
    """What the base spec holds that the built-in design (the route without a spec) does not: why
    the same well can get two pumps from two routes."""
    items = [f"{k} {_shown(v)} (built-in: {_shown(b)})" for k, v, b in problem.held]
    return (
        f"from the base spec {problem.spec.name!r}, not the built-in design: {'; '.join(items)} "
        "(size without a spec starts from the built-in design, so the same well can get another pump)"
    )


def _shown(v) -> str:
    return "none" if v is None else (f"{v:g}" if isinstance(v, float) else str(v))


def beyond_limit(value: float, limit: float, unit: str, side: str) -> str:
    """The words "value unit > limit unit": the value to three significant digits, or as many more
    (up to six) as it takes to tell it from the limit (a stroke of 1.0028 m is not "1 m > 1 m")."""
    shown = f"{limit:g}"
    for digits in range(3, 7):
        text = f"{value:.{digits}g}"
        if text != shown:
            break
    return f"{text} {unit} {side} {shown} {unit}"


def _holding_back(res: SizeResult) -> str:
    """Why no design met the limits, in one sentence: the closest design's checks beyond them."""
    b = res.best
    verdict = b.evaluation.verdict.design(0)
    level = 2 if res.problem.allow_warnings else 1
    bad = [c for c in verdict.checks if c.level >= level]
    parts = []
    for c in bad:
        lim = c.fail_limit if (c.level == 2 or c.warn_limit is None) else c.warn_limit
        side = ">" if c.relation == "<=" else "<"
        beyond = beyond_limit(float(c.value), float(lim), c.unit, side)
        parts.append(f"{CHECK_LABELS.get(c.key, c.key)} {beyond}")
    advice = "; ".join(
        dict.fromkeys(check_advice(c.key, parts=b.spec.parts) for c in bad if c.key in CHECK_ADVICE)
    )
    bores = ", ".join(f"{s.pipe * 1000:g}" for s in res.tried)
    if not bad and b.shortfall > 0:
        r = res.problem.robust
        return (
            f"no design with a {bores} mm pipe meets the limits with {r.target:.0%} of its builds within "
            f"±{r.tolerance * 1000:g} mm passing: the closest ({b.pipe * 1000:g} mm) has "
            f"{r.target - b.shortfall:.1%} to first order; allow a larger --tolerance or a lower --yield"
        )
    return (
        f"no design with a {bores} mm pipe meets the limits: the closest ({b.pipe * 1000:g} mm) still has "
        f"{'; '.join(parts) or 'a check beyond its limit'}"
        + (f" ({advice})" if advice else "")
        + ("" if res.problem.allow_warnings else "; --allow-warnings accepts warnings")
    )


def render_size(res: SizeResult, fmt: str, out=None) -> None:
    """`pumplink size`: the table, JSON or one CSV row."""
    out = out or sys.stdout
    row = size_row(res)

    def as_csv():
        flat = {
            k: v for k, v in row.items() if k not in ("design", "checks", "pipes", "discharge", "binding")
        }
        flat.update(row["design"])
        flat["binding"] = "; ".join(row["binding"])
        return [flat]

    def table() -> None:
        from rich.markup import escape
        from rich.table import Table

        c = console(out)
        who = OPERATOR_NOUNS.get(row["profile"], "the operator")
        c.print(f"[bold]Sizing {escape(row['name'])}[/] for {row['head_m']:g} m of head, pumped by {who}")
        if not res.found:
            c.print(f"[red]no design found[/]: {escape(_holding_back(res))}")
            return
        t = Table(title="The sized pump", title_justify="left")
        t.add_column("quantity")
        t.add_column("value", justify="right")
        for _, k, words, unit, _f in DESIGN:
            t.add_row(words, f"{row['design'][k]:.4g} {unit}")
        t.add_row("cadence", f"{row['cycles_per_min']:.1f} push-pull cycles/min")
        t.add_row("rope speed", f"{row['rope_speed_m_s']:.2f} m/s")
        c.print(t)
        if res.problem.kept:
            c.print(f"kept from the base spec: {', '.join(res.problem.kept)}", markup=False)
        pit = pit_words(res.best.spec)
        if pit:
            c.print(pit, markup=False)
        c.print(
            f"water: {row['flow_l_min']:.1f} l/min ({row['flow_m3_h']:.2f} m³/h) "
            f"for {row['power_W']:.1f} W at the handle; {row['flow_share']:.0%} of the "
            f"{row['power_limited_flow_l_min']:.1f} l/min {who}'s "
            f"sustained power could lift here; serves about {row['people_served']:,.0f} people",
            markup=False,
        )
        water = res.best.evaluation.water.design(0)
        c.print(losses_words(water), markup=False)
        c.print(duty_words(water), markup=False)
        for line in quantity_lines(res.best.evaluation):  # the catalogue's quantities with a line
            c.print(line, markup=False)
        c.print(f"verdict: {row['verdict']} (pumplink force on the written spec says the same)", markup=False)
        if row["robust"] is not None:
            c.print(robust_line(row["robust"]), markup=False)
        if row["binding"]:
            words = [CHECK_LABELS.get(b, b) for b in row["binding"]]
            c.print(f"what binds: {'; '.join(words)}", markup=False)
        d = Table(title="The same pump at other heads (fastest cadence that passes)", title_justify="left")
        for h in ("head [m]", "wheel speed [deg/s]", "cycles/min", "flow [l/min]"):
            d.add_column(h.replace("[", "\\["), justify="right")
        for r in row["discharge"]:
            none = r["speed_deg_s"] is None
            d.add_row(
                f"{r['head_m']:g}",
                "—" if none else f"{r['speed_deg_s']:g}",
                "—" if none else f"{r['speed_deg_s'] / 6:.1f}",
                "none passes" if none else f"{r['flow_l_min']:.1f}",
            )
        c.print(d)
        if res.problem.held:
            c.print(held_words(res.problem), markup=False)
        tried = ", ".join(
            f"{p['pipe_diameter_mm']:g} mm: "
            + (f"{p['flow_l_min']:.1f} l/min" if p["found"] else "none meets the limits")
            for p in row["pipes"]
        )
        c.print(f"pipes tried: {tried} ({row['evaluations']:,} designs evaluated)", markup=False)

    render(fmt, out, as_json=lambda: row, as_csv=as_csv, table=table)


__all__ = ["render_size", "size_row"]
