"""The words of the verdict: check labels, values against their limits, the verdict line, the
advice after a FAIL and the line naming the model that decided.  Shared by every view.

Renderers only render: every number comes from the library's results.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

from pumplink.constants import (
    AXLE_HEIGHT_RANGE_M,
    DEFAULT_EFFICIENCY,
    DEFAULT_VOLUMETRIC_EFFICIENCY,
    LOSS_SHARE,
)
from pumplink.output.formats import fmt as _f
from pumplink.output.formats import num

if TYPE_CHECKING:
    from pumplink.studies.force import ForceResult


def check_row(c, r: ForceResult | None = None, name: str | None = None) -> dict[str, Any]:
    """One verdict check as a JSON row (``result``: pass, warn or fail); ``name``: its words
    (default :func:`check_label`'s, in ``r``'s context)."""
    return {
        "key": c.key,
        "name": check_label(c, r) if name is None else name,
        "value": num(c.value),
        "unit": c.unit,
        "relation": c.relation,
        "warn_limit": None if c.warn_limit is None else num(c.warn_limit),
        "fail_limit": None if c.fail_limit is None else num(c.fail_limit),
        "result": c.result,
    }


def check_label(c, r: ForceResult | None = None) -> str:
    """The words for a verdict check (``pumplink.verdict.Check.key``), in this result's context."""
    if c.key == "peak_force" and r is not None:
        op = r.design.spec.operator
        if r.dynamics:
            return f"peak force, dynamics (δ ≤ {op.speed_fluctuation:g})"
        if r.flywheel:
            return f"peak force, flywheel (δ ≤ {op.speed_fluctuation:g})"
        return f"peak force outside ±{op.dead_band:g}° of DCs"
    return CHECK_LABELS[c.key]


#: Words for the checks (short enough for an 80-column table).
CHECK_LABELS = {
    "mean_force": "mean force",
    "peak_force": "peak force",
    "link_energy_share": "link kinetic energy / band",
    "transmission_angle": "transmission angle (smallest)",
    "power": "operator power",
    "cadence": "cadence, turns a minute",
    "rope_speed": "rope speed",
    "grip_speed": "peak grip speed",
    "stroke": "grip stroke",
    "grip_height": "grip height over the swing",
    "axle_height": "axle height",
    "pin_pressure": "pin bearing pressure",
    "handle_fatigue": "handle fatigue safety",
    "crank_fatigue": "crank fatigue safety",
    "kick_back": "kick-back when let go",
    "holding_torque": "ratchet's torque / column's",
    "pin_wear": "pin wear, 6 million turns",
}


def model_line(r: ForceResult) -> str:
    """Which model decided the verdict, in words."""
    if r.dynamics:
        op = r.design.spec.operator
        arms = (
            f"the effort: the hand force + {op.arm_mass_kg:g} kg of arms at the grip"
            if op.arms_in_verdict
            else "the hand force (the operator's arms not in it)"
        )
        return (
            f"model: full dynamics, J = {r.inertia:.3f} kg·m² plus the coupler's and handle's inertia and "
            f"weight, δ ≤ {r.speed_fluctuation:g} at a mean {r.speed_deg_s:g} deg/s; {arms}"
        )
    if r.flywheel:
        return (
            f"model: flywheel, J = {r.inertia:.3f} kg·m², δ ≤ {r.speed_fluctuation:g} at a mean "
            f"{r.speed_deg_s:g} deg/s (energy band W = J·ω̄²·δ = {r.energy_band:.2f} J); "
            "links' inertia neglected"
        )
    return (
        "model: quasi-static + dead band (the wheel's inertia is assumed to carry the linkage "
        f"through ±{r.design.spec.operator.dead_band:g}° of each dead centre; give wheel.mass or "
        "wheel.inertia to let the speed decide)"
    )


#: Rich markup of a check's result.
RESULT_MARKUP = {"pass": "[green]pass[/]", "warn": "[yellow]warning[/]", "fail": "[red]FAIL[/]"}

#: Format of each check's value (and its limits) in tables and sentences.
_CHECK_FORMAT = {
    "mean_force": "{:.1f}",
    "peak_force": "{:.1f}",
    "link_energy_share": "{:.0f}",
    "pin_pressure": "{:.1f}",
    "handle_fatigue": "{:.2f}",
    "crank_fatigue": "{:.2f}",
    "holding_torque": "{:.2f}",
    "pin_wear": "{:.3g}",
}


def check_value(ch) -> str:
    """A check's value with its unit, e.g. '85.8 N', '∞ N'."""
    f = _CHECK_FORMAT.get(ch.key, "{:.2f}")
    return f"{_f(ch.value, f, '∞') if ch.value != -math.inf else '−∞'} {ch.unit}".rstrip()


def limit_text(ch, limit) -> str:
    """'> 75 W' style: the side of ``limit`` on which the check warns or fails ('' for none)."""
    if limit is None:
        return ""
    if ch.key == "axle_height":  # a range: it warns on either side (pumplink.verdict)
        lo, hi = AXLE_HEIGHT_RANGE_M
        return f"<{lo:g}, >{hi:g} {ch.unit}"
    bad = ">" if ch.relation == "<=" else "<"
    return f"{bad} {limit:g} {ch.unit}".rstrip()


#: What to change when a check warns or fails (the check's own advice).
CHECK_ADVICE = {
    "link_energy_share": "the flywheel model neglects it, so treat the verdict as an estimate "
    "(a lighter handle or a heavier wheel; see --explain)",
    "transmission_angle": "the coupler meets the rocker at a poor angle: large joint forces, "
    "wear, and with friction a jam (move the rocker pivot or lengthen the rocker)",
    "power": "more than the operator sustains for hours (the profile's sustained power); "
    "slow the wheel or lower the load",
    "grip_speed": "faster than a rower's handle: the operator tires soon; slow the wheel or "
    "shorten the swing",
    "grip_speed fail": "the operator cannot follow the handle; slow the wheel or shorten the swing",
    "transmission_angle fail": "the coupler meets the rocker so obliquely that joint friction can jam "
    "the linkage (move the rocker pivot or lengthen the rocker)",
    "power fail": "more than the operator gives even for an hour; slow the wheel or lower the load",
    "cadence": "outside the 30-60 turns a minute people keep up at a crank or handle (the profile's "
    "range, docs/operators.md §6); change the wheel speed",
    "rope_speed": "outside 0.6-1.8 m/s, where leakage (slow) or friction in the rising main (fast) "
    "costs more than twice what it does at the best 1.2 m/s (docs/water.md §2a); change the wheel "
    "speed or radius",
    "stroke": "a standing operator must step or lean; shorten the handle or the swing",
    "grip_height": "push and pull with the hands between knuckle and shoulder height (the operator "
    "profile's range); change D1, the handle or the axle height",
    "axle_height": "outside the pump paper's 0.40-0.70 m",
    "pin_pressure": "the pin wears its bore out: a thicker pin, a longer bushing, or hardened pins and "
    "bushings",
    "handle_fatigue": "the handle may crack at the coupler's pin B after years of strokes: a thicker tube "
    "or a reinforcing sleeve there",
    "crank_fatigue": "the crank may crack at the axle: a thicker bar (rope-pump manuals report "
    '1/2" cranks failing after several years)',
    "kick_back": "let go, the water column drives the wheel and the handle back: fit a ratchet on the "
    "wheel's axle that holds the column (a [ratchet] table: its torque and teeth; docs/workshop.md §3)",
    "holding_torque": "the ratchet cannot hold the water column: a stronger pawl and teeth, or a "
    "freewheel rated for the column's torque",
    "pin_wear": "the pins and bushes wear their play open before 6 million turns: grease them, fit "
    'polyethylene bushes (parts.bush = "polyethylene"), a thicker pin or a longer bush',
}
#: The kick-back's advice where the spec has a ratchet (it holds, but catches too late, or it does
#: not hold: the holding-torque check says which).
RATCHET_ADVICE = (
    "the ratchet lets the handle run back too far before it holds: more teeth or pawls (each tooth lets "
    "the grip run back its share of a turn), a freewheel with no play (teeth = 0), or one that holds the "
    "column's torque"
)
#: The advice of the fatigue checks for how ``[parts]`` says the handle is joined at B
#: (``handle_joint``) and the crank at the axle (``crank_joint``): docs/workshop.md §2.
JOINT_ADVICE = {
    ("handle_fatigue", "hole"): "the handle may crack at its pin hole at B after years of strokes: weld a "
    'lug on for the pin instead of drilling the tube (parts.handle_joint = "lug"), or a thicker tube',
    ("handle_fatigue", "lug"): "the handle may crack at the weld toe of its lug at B after years of "
    "strokes: a thicker tube or a reinforcing sleeve there",
    ("crank_fatigue", "welded"): "the crank may crack where it is welded on: a thicker bar (rope-pump "
    'manuals report 1/2" cranks failing after several years)',
    ("crank_fatigue", "hole"): "the crank may crack at its hole for the axle: a thicker bar, or weld it "
    'to the axle (parts.crank_joint = "welded")',
}


def check_advice(key: str, result: str = "warn", parts=None) -> str:
    """What to do about a check that warns or fails ("" where there is no advice); for the fatigue
    checks, by how ``parts`` (the spec's ``[parts]``) joins the handle and the crank."""
    joint = {"handle_fatigue": "handle_joint", "crank_fatigue": "crank_joint"}.get(key)
    if joint is not None and parts is not None:
        return JOINT_ADVICE[(key, getattr(parts, joint))]
    return CHECK_ADVICE.get(f"{key} {result}", CHECK_ADVICE.get(key, ""))


def check_sentence(ch, r: ForceResult | None = None) -> str:
    """One sentence for a check that warns or fails: value, limit, and what to do."""
    lim = ch.fail_limit if ch.result == "fail" else ch.limit
    if lim is None:
        lim = ch.limit
    side = ">" if ch.relation == "<=" else "<"
    val = check_value(ch)
    advice = check_advice(ch.key, ch.result, r.design.spec.parts if r is not None else None)
    if ch.key == "kick_back" and r is not None and r.design.spec.ratchet is not None:
        advice = RATCHET_ADVICE
    limit = f"{side} {lim:g} {ch.unit}".rstrip()
    return f"{check_label(ch, r)} is {val} ({limit}): {advice}".rstrip(": ")


def passing_words(bands, searched) -> str:
    """Intervals of mean speed [rad/s] in words ('from 498 to 856 deg/s'), saying where one runs
    on to the edge of the speeds ``searched``."""
    lo_s, hi_s = (math.degrees(v) for v in searched)

    def span(pair):
        lo, hi = (math.degrees(v) for v in pair)
        low, high = lo <= lo_s * (1 + 1e-9), hi >= hi_s * (1 - 1e-9)
        if low and high:
            return f"every speed searched ({lo:.0f} to {hi:.0f} deg/s)"
        if low:
            return f"up to {hi:.0f} deg/s (searched from {lo:.0f})"
        if high:
            return f"from {lo:.0f} deg/s up (searched to {hi:.0f})"
        return f"from {lo:.0f} to {hi:.0f} deg/s"

    return " and ".join(span(b) for b in bands)


def verdict_line(r: ForceResult, strict: bool = False, cadence=None) -> str:
    """The verdict in words, with Rich markup: PASS, PASS with warnings or FAIL."""
    peak = r.verdict_peak_force
    how = " with full dynamics" if r.dynamics else " with the flywheel" if r.flywheel else ""
    forces = f"mean {r.mean_force:.1f} N, peak {_f(peak, '{:.1f}', '∞')} N{how}"
    v = r.verdict
    if r.outcome == "PASS":
        return f"[bold green]VERDICT: PASS[/] — {forces}, within the {r.force_limit:g} N limit; no warnings"
    if r.outcome == "PASS with warnings":
        n = len(v.warnings)
        tail = " — fails under --strict" if strict else ""
        return (
            f"[bold yellow]VERDICT: PASS with warnings[/] — {forces}, within the {r.force_limit:g} N limit; "
            f"{n} warning{'s' if n > 1 else ''} below{tail}"
        )
    bad = "; ".join(
        f"{check_label(ch, r)} {check_value(ch)} {limit_text(ch, ch.fail_limit)}" for ch in v.failures
    )
    hint = ""
    fitting = any(ch.key in ("kick_back", "holding_torque") for ch in v.failures)
    # the speeds are judged with the linkage fitted with its ratchet: a fitting check is left out
    every = "every check but the ratchet's" if fitting else "every check"
    no_check = "no check but the ratchet's" if fitting else "no check"
    some_check = "some check besides the ratchet's" if fitting else "some check"
    if cadence is not None and cadence.bands:  # (:class:`pumplink.studies.speed.Cadence`)
        speeds = passing_words(cadence.bands, cadence.searched)
        if cadence.clean_bands == cadence.bands:
            hint = f"; {every} passes at a mean {speeds} (pumplink speed)"
        else:  # a check warns at some of these speeds: they pass the verdict, not every check
            clean = passing_words(cadence.clean_bands, cadence.searched) if cadence.clean_bands else ""
            clean = f", none warns {clean}" if clean else ", though a check warns at each"
            hint = f"; {no_check} fails at a mean {speeds}{clean} (pumplink speed)"
    elif cadence is not None:
        lo, hi = (math.degrees(v) for v in cadence.searched)
        hint = f"; {some_check} fails at every mean speed from {lo:.0f} to {hi:.0f} deg/s"
    return f"[bold red]VERDICT: FAIL[/] — {bad}{hint}"


def advice_row(a) -> dict[str, Any]:
    """One suggested change (:class:`pumplink.studies.advice.Suggestion`) as a JSON row."""
    return {
        "key": a.key,
        "from": a.old,
        "to": a.new,
        "unit": a.unit,
        "peak_force_N": num(a.peak_force),
        "verdict": a.outcome,
        "still_failing": list(a.failing),
    }


def advice_sentence(a) -> str:
    """'linkage.handle 1.2 → 1.32 m: peak 97.2 N, PASS with warnings'."""
    still = f" (still fails: {', '.join(CHECK_LABELS[k] for k in a.failing)})" if a.failing else ""
    return (
        f"{a.key} {a.old:g} → {a.new:g} {a.unit}: peak {_f(a.peak_force, '{:.1f}', '∞')} N, "
        f"{a.outcome}{still}"
    )


#: The verdict's words with Rich markup.
OUTCOME_MARKUP = {
    "PASS": "[bold green]PASS[/]",
    "PASS with warnings": "[bold yellow]PASS with warnings[/]",
    "FAIL": "[bold red]FAIL[/]",
}


#: m³/s in litres per minute and in cubic metres per hour (the units a pump's users read).
L_PER_MIN, M3_PER_H = 60_000.0, 3_600.0


#: The keys of the water a design delivers, in its JSON (:func:`water_row`) and a batch's rows.
WATER_KEYS = (
    "flow_l_min",
    "flow_m3_h",
    "water_power_W",
    "pump_efficiency",
    "power_limited_flow_l_min",
    "flow_share",
    "people_served",
)


def water_row(w) -> dict[str, Any]:
    """The JSON of the water a design delivers (:class:`pumplink.evaluate.Water`, one design):
    ``null`` throughout where the spec gives a rope force instead of a head and a pipe."""
    given = w is not None and math.isfinite(w.flow)
    if not given:
        return dict.fromkeys(WATER_KEYS)
    return {
        "flow_l_min": num(w.flow * L_PER_MIN),
        "flow_m3_h": num(w.flow * M3_PER_H),
        "water_power_W": num(w.water_power),
        "pump_efficiency": num(w.efficiency),
        "power_limited_flow_l_min": num(w.limit * L_PER_MIN),
        "flow_share": num(w.share),
        "people_served": num(w.people),
    }


#: Who works the pump under each operator profile, in a sentence (pumplink.profiles).
OPERATOR_NOUNS = {
    "men": "a man",
    "women": "a woman",
    "children": "a child",
    "accessible": "an operator of limited strength",
}


def water_lines(w, power: float, profile: str, hours: float, litres: float) -> list[str]:
    """The water in words: the flow, its power against the operator's, the share of what the
    operator's sustained power could lift at this head, and the people it serves."""
    if w is None or not math.isfinite(w.flow):
        return [
            "water: no flow figure (the spec gives load.rope_force; give load.head and "
            "load.pipe_diameter for litres per minute)"
        ]
    who = OPERATOR_NOUNS.get(profile, "the operator")
    out = [
        f"water: {w.flow * L_PER_MIN:.1f} l/min ({w.flow * M3_PER_H:.2f} m³/h) from {w.head:g} m; "
        f"{w.water_power:.1f} W of water for {power:.1f} W at the handle ({w.efficiency:.0%})",
    ]
    if math.isfinite(w.losses):
        out.append(losses_words(w))
    out.append(
        f"that is {w.share:.0%} of the {w.limit * L_PER_MIN:.1f} l/min {who} sustaining "
        f"{w.sustained_power:g} W could lift here with this pump"
    )
    if math.isfinite(w.filling_flow):
        out.append(duty_words(w))
    out.append(f"serves about {w.people:,.0f} people ({litres:g} l each a day, {hours:g} h of pumping a day)")
    return out


#: The words of :data:`pumplink.evaluate.designs.LOSSES`, by index, in the JSON's ``losses``.
LOSSES_WORDS = ("constant", "loss model", "spec")


def losses_word(w) -> str | None:
    """The JSON's ``losses``: which efficiencies decided (:data:`LOSSES_WORDS`), None without a
    head and a pipe."""
    if w is None or not math.isfinite(w.losses) or not math.isfinite(w.flow):
        return None
    return LOSSES_WORDS[int(w.losses)]


def losses_words(w) -> str:
    """Which efficiencies decided the water and the force, in a sentence (docs/water.md §2a)."""
    model = w.model_force_efficiency * w.model_volumetric_efficiency
    used = f"{w.force_efficiency:.3g} × {w.volumetric_efficiency:.3g}"
    if w.losses == 2:
        return f"efficiency: the spec's {used} (a measurement: the loss model is not consulted)"
    if w.losses == 0:
        off = abs(w.force_efficiency * w.volumetric_efficiency / model - 1.0)
        return (
            f"efficiency: the constants {used}; the loss model's {model:.3f} is {off:.1%} from "
            f"their product, within {LOSS_SHARE:.0%} (docs/water.md §2a)"
        )
    constants = DEFAULT_EFFICIENCY * DEFAULT_VOLUMETRIC_EFFICIENCY
    if not model > 0.0:
        return (
            f"efficiency: the loss model's {used}: at this rope speed the leak past the pistons is as "
            "much as the pistons sweep, and no water comes up (docs/water.md §2a)"
        )
    return (
        f"efficiency: the loss model's {used} = {model:.3f} (leakage and friction at this rope speed "
        f"and bore); the constants' {constants:.4g} would be {abs(constants / model - 1.0):.1%} off "
        "(docs/water.md §2a)"
    )


def pit_words(spec) -> str:
    """The pit a design needs where its rocker pivot sits below the ground (D1 deeper than the axle
    height), in a sentence; "" where it needs none or the axle height is not given."""
    axle = spec.wheel.axle_height
    if axle is None or spec.linkage.D1 <= axle:
        return ""
    return (
        f"pit: the rocker pivot sits {spec.linkage.D1 - axle:.3f} m below the ground (D1 "
        f"{spec.linkage.D1:g} m under an axle {axle:g} m high): dig a pit for it, lined and drained"
    )


def duty_words(w) -> str:
    """The flow at the two duties (docs/water.md §6): all day, at the sustained power, and while
    filling containers, at the power the field's discharges imply."""
    return (
        f"duties: all day ({w.sustained_power:g} W) {w.all_day_flow * L_PER_MIN:.1f} l/min at "
        f"{w.all_day_cadence:.1f} turns a minute; filling containers ({w.filling_power:g} W) "
        f"{w.filling_flow * L_PER_MIN:.1f} l/min at {w.filling_cadence:.1f} turns a minute"
    )
