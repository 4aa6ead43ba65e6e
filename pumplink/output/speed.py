"""`pumplink speed`: the least peak force against wheel speed, the verdict at each speed and the
best cadence.

Renderers only render: every number comes from the library's results.
"""

from __future__ import annotations

import math
import sys
import textwrap
from typing import TYPE_CHECKING, Any

from pumplink.output.formats import console, deg, num, render
from pumplink.output.formats import fmt as _f
from pumplink.output.precision import known_to

if TYPE_CHECKING:
    from pumplink.studies.speed import SpeedSweep
from pumplink.constants import CADENCE_RTOL, MODEL_WORDS
from pumplink.output.synth import design_row
from pumplink.output.words import L_PER_MIN, passing_words


def speed_rows(sw: SpeedSweep) -> list[dict[str, Any]]:
    """One row per speed; ``peak_force_N`` is the verdict's peak (of the model in ``model``)."""
    outcome = sw.outcome.tolist()
    cols = (
        sw.speed_deg_s,
        sw.energy_band,
        sw.least_peak_force,
        sw.flywheel_force,
        sw.dynamics_force,
        sw.effort_force,
        sw.model,
        sw.power,
        sw.grip_speed,
        outcome,
        sw.passed,
        [math.nan] * len(outcome) if sw.flow is None else sw.flow,
    )
    return [
        {
            "speed_deg_s": float(w),
            "energy_band_J": num(b),
            "model": MODEL_WORDS[m],
            "peak_force_N": num(f),
            "flywheel_peak_force_N": num(fw),
            "dynamics_peak_force_N": num(dy),
            "effort_peak_force_N": num(ef),
            "power_W": num(p),
            "flow_l_min": num(q * L_PER_MIN),
            "grip_speed_m_s": num(g),
            "verdict": o,
            "pass": bool(ok),
        }
        for w, b, f, fw, dy, ef, m, p, g, o, ok, q in zip(*cols)
    ]


def cadence_row(c) -> dict[str, Any]:
    """The best cadence and the passing speeds (:class:`pumplink.studies.speed.Cadence`) as JSON."""

    # the best speed and what is read there to its search's tolerance (pumplink.output.precision);
    # the ends of the passing speeds are whole deg/s (pumplink.studies.speed.passing_speeds)

    def rng(pair):
        lo, hi = pair
        if not math.isfinite(lo):
            return None
        return {"min": float(round(math.degrees(lo))), "max": float(round(math.degrees(hi)))}

    def known(x):
        return known_to(x, CADENCE_RTOL)

    return {
        "speed_deg_s": known(deg(c.speed)),
        "rpm": known(math.degrees(c.speed) / 6.0),
        "passing_bands_deg_s": [rng(b) for b in c.bands],
        "passing_without_warnings_deg_s": [rng(b) for b in c.clean_bands],
        "effort_peak_force_N": known(c.effort),
        "hand_peak_force_N": known(c.hand_force),
        "power_W": known(c.power),
        "at_edge_of_search": c.at_edge,
        "searched_deg_s": {"min": deg(c.searched[0]), "max": deg(c.searched[1])},
        "model": MODEL_WORDS[c.model],
        "force_passes_deg_s": rng(c.force_range),
        "verdict_passes_deg_s": rng(c.passing),
    }


def cadence_lines(c, force_limit: float) -> list[str]:
    """The best cadence and the passing speeds in words (plain text, each under 80 columns)."""
    lines = []
    if math.isfinite(c.speed):
        rpm = math.degrees(c.speed) / 6.0
        edge = " (the edge of the speeds searched)" if c.at_edge else ""
        how = "pass without a warning" if c.clean_bands else "pass"
        text = (
            f"best cadence: {math.degrees(c.speed):.0f} deg/s ({rpm:.0f} rpm){edge} at {c.power:.0f} W: of "
            f"the speeds that {how}, the one with the least peak effort (hand force + the operator's "
            f"arms), {c.effort:.1f} N (hand force {c.hand_force:.1f} N)"
        )
        lines += textwrap.wrap(text, 79, subsequent_indent="  ", break_on_hyphens=False)
    what = MODEL_WORDS[c.model]
    if math.isfinite(c.force_range[0]):
        lines.append(
            f"peak force ({what}) within {force_limit:g} N: {passing_words([c.force_range], c.searched)}"
        )
    else:
        lines.append(f"peak force ({what}) above {force_limit:g} N at every speed searched")
    if c.bands and c.clean_bands == c.bands:
        lines.append(f"every check passes: {passing_words(c.bands, c.searched)}")
    elif c.bands:  # a check warns at some of the speeds where none fails
        lines.append(f"no check fails: {passing_words(c.bands, c.searched)}")
        clean = passing_words(c.clean_bands, c.searched) if c.clean_bands else "at no speed"
        lines.append(f"  without a warning: {clean}")
    else:
        lines.append("some check fails at every speed (see the checks that fail)")
    return lines


def speed_summary(sw: SpeedSweep) -> dict[str, Any]:
    out = design_row(sw.design)
    out.update(
        {
            "model": sw.result.model,
            "inertia_kg_m2": num(sw.inertia),
            "speed_fluctuation": sw.speed_fluctuation,
            "force_limit_N": num(sw.force_limit),
            "mean_force_N": num(sw.mean_force),
            "quasi_static_peak_force_N": num(sw.dead_band_peak_force),
            "min_passing_speed_deg_s": deg(sw.min_passing_speed),
            "best_cadence": None if sw.cadence is None else cadence_row(sw.cadence),
        }
    )
    return out


def render_speed(sw: SpeedSweep, fmt: str, out=None) -> None:
    """`pumplink speed`: the least peak force of the flywheel and of full dynamics against wheel
    speed, the verdict at each speed, the best cadence and the passing speeds."""
    out = out or sys.stdout
    rows = speed_rows(sw)

    def as_json():
        return {**speed_summary(sw), "speeds": rows}

    def as_csv():
        return rows

    def table() -> None:
        from rich import box
        from rich.markup import escape
        from rich.table import Table

        c = console(out)
        t = Table(
            title=f"{escape(sw.design.spec.name)}: least peak operator force against mean wheel speed "
            f"(J = {sw.inertia:.3f} kg·m², δ ≤ {sw.speed_fluctuation:g})",
            title_justify="left",
            box=box.SIMPLE_HEAD,
            pad_edge=False,
            caption="flywheel: links neglected; dynamics: links' inertia and weight (the hand force); "
            "effort: + the operator's arms; bold: the model that decides (least that is enough); "
            "v: peak grip speed; warn: PASS with warnings (docs/models.md §3-4)",
            caption_justify="left",
        )
        for h in (
            "speed [°/s]",
            "rpm",
            "flywheel [N]",
            "dynamics [N]",
            "effort [N]",
            "power [W]",
            "v [m/s]",
            "verdict",
        ):
            t.add_column(escape(h), justify="left" if h == "verdict" else "right")
        for r in rows:
            fly, dyn = (
                _f(r["flywheel_peak_force_N"], "{:.1f}", "∞"),
                _f(r["dynamics_peak_force_N"], "{:.1f}", "∞"),
            )
            if r["model"] == "flywheel":
                fly = f"[bold]{fly}[/]"
            elif r["model"] == "full dynamics":
                dyn = f"[bold]{dyn}[/]"
            t.add_row(
                f"{r['speed_deg_s']:g}",
                f"{r['speed_deg_s'] / 6:.0f}",
                fly,
                dyn,
                _f(r["effort_peak_force_N"], "{:.1f}", "∞"),
                _f(r["power_W"], "{:.0f}"),
                _f(r["grip_speed_m_s"], "{:.2f}"),
                {"PASS": "[green]PASS[/]", "FAIL": "[red]FAIL[/]"}.get(r["verdict"], "[yellow]warn[/]"),
            )
        c.print(t)
        c.print(
            f"mean force {sw.mean_force:.1f} N (the floor: an infinite flywheel); quasi-static peak "
            f"outside the dead band {sw.dead_band_peak_force:.1f} N (the dead-band model, blind to speed)",
            markup=False,
        )
        if sw.cadence is not None:
            for line in cadence_lines(sw.cadence, sw.force_limit):
                c.print(line, markup=False)

    render(fmt, out, as_json=as_json, as_csv=as_csv, table=table)
