"""What each command shows: the rows (JSON/CSV contracts) and the Rich tables.

Renderers only render: every number comes from the library's results.  One dispatch for
table / JSON / CSV (:mod:`pumplink.output.formats`).
"""

from __future__ import annotations

import math
import sys
from collections.abc import Iterator
from typing import TYPE_CHECKING, Any

import numpy as np

if TYPE_CHECKING:
    from pumplink.analysis import Design, ForceResult, SpeedSweep
from pumplink.output.formats import console, deg, num, write_csv
from pumplink.output.formats import fmt as _f
from pumplink.output.formats import write_json as _json


# ----------------------------------------------------------------------------- rows
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


def force_summary(r: ForceResult) -> dict[str, Any]:
    """The JSON contract of a force analysis without samples."""
    out = design_row(r.design)
    out.update(
        {
            "speed_deg_s": r.speed_deg_s,
            "wheel_torque_Nm": num(r.wheel_torque),
            "power_W": num(r.power),
            "force_limit_N": num(r.force_limit),
            "dead_band_deg": r.design.spec.operator.dead_band,
            "model": r.model,
            "inertia_kg_m2": None if r.inertia is None else num(r.inertia),
            "speed_fluctuation": r.speed_fluctuation,
            "energy_band_J": None if r.energy_band is None else num(r.energy_band),
            "least_peak_force_N": None if r.least_peak_force is None else num(r.least_peak_force),
            "min_passing_speed_deg_s": None if r.min_passing_speed is None else deg(r.min_passing_speed),
            "wheel_speed_range_deg_s": _speed_range(r),
            "link_kinetic_energy_J": num(r.link_energy),
            "link_weight_J": None if r.effects is None else num(r.effects.link_weight),
            "arm_kinetic_energy_J": None if r.effects is None else num(r.effects.arm_energy),
            "effort_peak_force_N": None if r.effort_peak_force is None else num(r.effort_peak_force),
            "mean_force_N": num(r.mean_force),
            # the verdict's peak (of the model that decided), and the dead-band model's under its own name
            "peak_force_N": num(r.verdict_peak_force),
            "peak_force_infinite": bool(r.verdict_peak_force == math.inf),
            "dead_band_peak_force_N": num(r.dead_band_peak_force),
            "dead_band_peak_crank_deg": deg(r.dead_band_peak_angle),
            "sampled_peak_force_N": num(r.sampled_peak),
            "samples_n": r.samples_n,
            "verdict": r.outcome,
            "pass": r.passed,
            "checks": [check_row(c, r) for c in r.checks],
        }
    )
    return out


def check_row(c, r: ForceResult | None = None) -> dict[str, Any]:
    """One verdict check as a JSON row (``result``: pass, warn or fail)."""
    return {
        "key": c.key,
        "name": check_label(c, r),
        "value": num(c.value),
        "unit": c.unit,
        "relation": c.relation,
        "warn_limit": None if c.warn_limit is None else num(c.warn_limit),
        "fail_limit": None if c.fail_limit is None else num(c.fail_limit),
        "result": c.result,
    }


def force_html(r: ForceResult) -> str:
    """A force result as an HTML table for notebooks (``ForceResult._repr_html_``)."""
    import html

    h = html.escape
    head = f"<b>{h(r.design.spec.name)}</b>: {h(r.outcome)} at {r.speed_deg_s:g} deg/s ({h(r.model)})"
    if not r.design.feasible:
        return f"<p>{head}: infeasible, {h(str(r.design.error))}</p>"
    rows = "".join(
        f"<tr><td>{h(check_label(c, r))}</td><td>{h(check_value(c))}</td><td>{h(c.result)}</td></tr>"
        for c in r.checks
    )
    return (
        f"<p>{head}</p><table><thead><tr><th>check</th><th>value</th><th>result</th></tr></thead>"
        f"<tbody>{rows}</tbody></table>"
    )


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
    "grip_speed": "peak grip speed",
    "stroke": "grip stroke",
    "grip_height": "grip height over the swing",
    "axle_height": "axle height",
}


def _speed_range(r: ForceResult):
    sc = r.scene
    if sc is None or not math.isfinite(sc.least_peak_force):
        return None
    return {"min": deg(sc.min_speed), "max": deg(sc.max_speed)}


def sample_rows(r: ForceResult) -> list[dict[str, Any]]:
    """One dict per sampled crank angle (JSON/CSV)."""
    return list(iter_sample_rows(r))


#: Samples converted to rows at a time by :func:`iter_sample_rows` (memory: one block).
ROW_BLOCK = 4096


def iter_sample_rows(r: ForceResult) -> Iterator[dict[str, Any]]:
    """:func:`sample_rows` one row at a time, converted in blocks, so that a million samples
    stream to JSON or CSV without a million dicts in memory."""
    if r.samples is None:
        return
    s = r.samples
    cols = {
        "crank_deg": np.degrees(s.crank_angle),
        "force_N": s.force,
        "handle_speed_m_s": r.handle_speed,
        "phi_deg": np.degrees(s.rocker_angle) - 90.0,
        "rocker_deg": np.degrees(s.rocker_angle),
        "transmission_deg": np.degrees(s.transmission_angle),
        # the operator's force and the wheel speed: the flywheel scene's profile, or (quasi-static)
        # the quasi-static force at a constant speed
        "operator_force_N": s.force if r.operator_force is None else r.operator_force,
        "wheel_speed_deg_s": np.degrees(
            np.broadcast_to(r.speed if r.wheel_speed is None else r.wheel_speed, s.force.shape)
        ),
    }
    n = len(s.singular)
    for b0 in range(0, n, ROW_BLOCK):
        b = slice(b0, b0 + ROW_BLOCK)
        lists = {k: np.asarray(v)[b].tolist() for k, v in cols.items()}
        sing, band = s.singular[b].tolist(), r.in_dead_band[b].tolist()
        for i in range(len(sing)):
            row = {k: (v[i] if math.isfinite(v[i]) else None) for k, v in lists.items()}
            row["singular"] = sing[i]
            row["in_dead_band"] = band[i]
            yield row


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
    if fmt == "json":
        return _json({"designs": rows}, out)
    if fmt == "csv":
        return write_csv(rows, out)
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


def _bar(value, limit, width=12) -> str:
    if value is None or not math.isfinite(value):
        return "[red]" + "▶" * width + "[/]"
    full = abs(value) / limit * width / 1.5 >= width  # full bar at 1.5x the limit, then an arrow
    mark = "█" * (width - 1) + "▶" if full else "█" * int(round(abs(value) / limit * width / 1.5))
    return f"[red]{mark}[/]" if abs(value) > limit else f"[green]{mark}[/]"


def _condensed_indices(r: ForceResult, max_rows: int = 24) -> list[int]:
    n = r.samples.crank_angle.size
    if n <= max_rows + 4:
        return list(range(n))
    return sorted(set(np.linspace(0, n - 1, max_rows).round().astype(int).tolist()))


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


def render_force(
    r: ForceResult,
    fmt: str,
    summary: bool = False,
    out=None,
    extra: dict | None = None,
    strict: bool = False,
    advice=(),
) -> None:
    """`pumplink force`: sweep table (condensed), checks and the verdict.

    ``extra`` (JSON only): more top-level keys, e.g. ``explain`` and ``verify``.  ``strict``:
    warnings fail (``--strict``).  ``advice``: :class:`pumplink.analysis.Suggestion` records,
    printed after a FAIL (and in JSON as ``advice``).
    """
    out = out or sys.stdout
    if fmt == "json":
        obj = force_summary(r)
        obj["strict"] = strict
        obj["advice"] = [advice_row(a) for a in advice]
        obj.update(extra or {})
        if not summary:  # streamed: a million samples must not be a million dicts at once
            return _json(obj, out, stream=("samples", iter_sample_rows(r)))
        return _json(obj, out)
    if fmt == "csv":
        return write_csv([force_summary(r)] if summary or r.samples is None else iter_sample_rows(r), out)

    from rich import box
    from rich.markup import escape
    from rich.table import Table

    c = console(out)
    d = design_row(r.design)
    name = escape(d["name"])
    if not r.design.feasible:
        c.print(f"[bold]{name}[/]: [red]infeasible[/] — {escape(r.design.error)}.")
        c.print("[bold red]VERDICT: FAIL[/] (no linkage to drive)")
        return
    dc = d["dead_centres_deg"]
    c.print(
        f"[bold]{name}[/]: crank {d['crank_length']:.4f} m, coupler {d['coupler_length']:.4f} m, "
        f"rocker {d['rocker_length']:.4f} m, frame {d['frame_length']:.4f} m, "
        f"handle {d['handle_length']:.3f} m"
    )
    c.print(
        f"dead centres (DC) at crank {dc['extended']:.2f}° (extended) and {dc['folded']:.2f}° (folded); "
        f"time ratio K = {d['time_ratio']:.4f}; wheel torque {r.wheel_torque:.3f} N·m at "
        f"{r.speed_deg_s:g} deg/s ({r.power:.1f} W)"
    )
    fly = r.flywheel and r.operator_force is not None

    if not summary and r.samples is not None and r.samples.crank_angle.size:
        s = r.samples
        kind = "flywheel scene" if fly else "quasi-static"
        t = Table(
            title=f"Operator force over the crank cycle ({kind}, {r.samples_n} samples"
            f"{', condensed' if s.crank_angle.size > 28 else ''})",
            title_justify="left",
            min_width=min(c.width, 78),  # the title on one line
            caption="θ2 crank angle; Fh quasi-static force"
            + (
                "; F the operator's force, ω the wheel speed (ω max: at its top speed); DC ext/fold: "
                "the extended/folded dead centre"
                if fly
                else ""
            )
            + "; bar full at 1.5× the limit; v grip speed; φ handle from vertical; "
            "γ transmission angle",
            caption_justify="left",
            box=box.SIMPLE_HEAD,
            pad_edge=False,
        )
        heads = ["θ2 [°]", "Fh [N]"]
        heads += (
            ["F [N]", f"|F| vs {r.force_limit:g} N", "ω [°/s]"] if fly else [f"|Fh| vs {r.force_limit:g} N"]
        )
        heads += ["v [m/s]", "φ [°]", "γ [°]", "note"]
        for h in heads:
            t.add_column(
                escape(h), justify="left" if h.startswith(("|", "note")) else "right", no_wrap=h == "note"
            )
        rows = []
        hs = r.handle_speed

        def add(st, i, speed, note, op=None, w=None):
            f = st.force[i]
            qs = "∞" if st.singular[i] else _f(f, "{:+.1f}")
            if fly:
                mid = [_f(op, "{:+.1f}"), _bar(op, r.force_limit, 8), _f(np.degrees(w), "{:.1f}")]
            else:
                mid = [_bar(None if st.singular[i] else float(f), r.force_limit, 12)]
            rows.append(
                (
                    float(st.crank_angle[i]) % (2 * math.pi),
                    _f(np.degrees(st.crank_angle[i]) % 360, "{:.2f}"),
                    qs,
                    *mid,
                    _f(speed, "{:.2f}"),
                    _f(np.degrees(st.rocker_angle[i]) - 90, "{:+.1f}"),
                    _f(np.degrees(st.transmission_angle[i]), "{:.1f}"),
                    note,
                )
            )

        for i in _condensed_indices(r):
            if s.singular[i]:
                note = "[bold]DC[/]"
            elif fly:
                note = "[dim]ω max[/]" if r.on_ceiling[i] else ""
            else:
                note = "[dim]dead band[/]" if r.in_dead_band[i] else ""
            add(s, i, hs[i], note, *((r.operator_force[i], r.wheel_speed[i]) if fly else ()))
        if s.crank_angle.size > 28 and r.marks is not None:  # mark the dead centres and the exact peak
            m = r.marks
            speeds = r.mark_grip_speed
            if fly:
                ws, ops = r.mark_wheel_speed, r.mark_operator_force
                for i, label in enumerate(("DC ext", "DC fold")):
                    add(m, i, speeds[i], f"[bold]{label}[/]", ops[i], ws[i])
            else:
                for i, label in enumerate(("DC extended", "DC folded", "peak (exact)")):
                    add(m, i, speeds[i], f"[bold]{label}[/]")
        for row in sorted(rows, key=lambda x: x[0] % (2 * math.pi)):
            t.add_row(*row[1:])
        c.print(t)

    ct = Table(
        title="Checks",
        title_justify="left",
        box=box.SIMPLE_HEAD,
        pad_edge=False,
        caption="DC: dead centre; a warning is reported, a failure fails the design (docs/models.md §4)",
        caption_justify="left",
    )
    for h in ("check", "value", "warn if", "fail if", "result"):
        ct.add_column(h, justify="right" if h in ("value", "warn if", "fail if") else "left")
    if r.flywheel:
        ct.add_row(
            f"dead-band peak (±{r.design.spec.operator.dead_band:g}° of DCs)",
            f"{_f(r.dead_band_peak_force, '{:.2f}', '∞')} N",
            "",
            "",
            "[dim]info[/]",
        )
        if r.dynamics:  # faster is not always easier: the speeds that pass come from pumplink speed
            if not r.design.spec.operator.arms_in_verdict:
                ct.add_row(
                    f"effort: + {r.design.spec.operator.arm_mass_kg:g} kg of arms",
                    f"{_f(r.effort_peak_force, '{:.1f}', '∞')} N",
                    "",
                    "",
                    "[dim]info[/]",
                )
        else:
            mps = r.min_passing_speed
            ct.add_row(
                "slowest passing mean speed",
                "never" if mps == math.inf else f"{_f(np.degrees(mps), '{:.1f}')} °/s",
                "",
                "",
                "[dim]info[/]",
            )
    else:
        ct.add_row(
            f"sampled peak ({r.samples_n} samples)",
            f"{_f(r.sampled_peak, '{:.2f}')} N",
            "",
            "",
            "[dim]info[/]",
        )
    for ch in r.checks:
        ct.add_row(
            escape(check_label(ch, r)),
            check_value(ch),
            _limit_text(ch, ch.warn_limit),
            _limit_text(ch, ch.fail_limit),
            RESULT_MARKUP[ch.result],
        )
    c.print(ct)
    c.print(model_line(r))
    c.print(verdict_line(r, strict))
    for ch in r.checks:
        if ch.result == "warn":
            c.print(f"[yellow]warning:[/] {escape(check_sentence(ch, r))}")
        elif ch.result == "fail" and ch.key in CHECK_ADVICE:
            c.print(f"[red]fails:[/] {escape(check_sentence(ch, r))}")
    if advice:
        c.print("[bold]what would help most[/] (one change at a time, everything else as in the spec):")
        for a in advice:
            c.print(f"  {escape(advice_sentence(a))}")


#: Rich markup of a check's result.
RESULT_MARKUP = {"pass": "[green]pass[/]", "warn": "[yellow]warning[/]", "fail": "[red]FAIL[/]"}

#: Format of each check's value (and its limits) in tables and sentences.
_CHECK_FORMAT = {"mean_force": "{:.1f}", "peak_force": "{:.1f}", "link_energy_share": "{:.0f}"}


def check_value(ch) -> str:
    """A check's value with its unit, e.g. '85.8 N', '∞ N'."""
    f = _CHECK_FORMAT.get(ch.key, "{:.2f}")
    return f"{_f(ch.value, f, '∞') if ch.value != -math.inf else '−∞'} {ch.unit}"


def _limit_text(ch, limit) -> str:
    """'> 75 W' style: the side of ``limit`` on which the check warns or fails ('' for none)."""
    if limit is None:
        return ""
    bad = ">" if ch.relation == "<=" else "<"
    return f"{bad} {limit:g} {ch.unit}"


#: What to change when a check warns or fails (the check's own advice).
CHECK_ADVICE = {
    "link_energy_share": "the flywheel model neglects it, so treat the verdict as an estimate "
    "(a lighter handle or a heavier wheel; see --explain)",
    "transmission_angle": "the coupler meets the rocker at a poor angle: large joint forces, "
    "wear, and with friction a jam (move the rocker pivot or lengthen the rocker)",
    "power": "a person sustains ~75 W for hours and at most ~150 W for an hour; "
    "slow the wheel or lower the load",
    "grip_speed": "faster than a rower's handle: the operator tires soon; slow the wheel or "
    "shorten the swing",
    "grip_speed fail": "the operator cannot follow the handle; slow the wheel or shorten the swing",
    "transmission_angle fail": "the coupler meets the rocker so obliquely that joint friction can jam "
    "the linkage (move the rocker pivot or lengthen the rocker)",
    "power fail": "more than a person gives even for an hour (~150 W); slow the wheel or lower the load",
    "stroke": "a standing operator must step or lean; shorten the handle or the swing",
    "grip_height": "the efficient push height is 0.5-0.9 m; change D1, the handle or the axle height",
    "axle_height": "outside the pump paper's 0.40-0.70 m",
}


def check_sentence(ch, r: ForceResult | None = None) -> str:
    """One sentence for a check that warns or fails: value, limit, and what to do."""
    lim = ch.fail_limit if ch.result == "fail" else ch.limit
    if lim is None:
        lim = ch.limit
    side = ">" if ch.relation == "<=" else "<"
    val = check_value(ch)
    advice = CHECK_ADVICE.get(f"{ch.key} {ch.result}", CHECK_ADVICE.get(ch.key, ""))
    return f"{check_label(ch, r)} is {val} ({side} {lim:g} {ch.unit}): {advice}".rstrip(": ")


def verdict_line(r: ForceResult, strict: bool = False) -> str:
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
        f"{check_label(ch, r)} {check_value(ch)} {_limit_text(ch, ch.fail_limit)}" for ch in v.failures
    )
    hint = ""
    force_failed = any(ch.key in ("mean_force", "peak_force") for ch in v.failures)
    if force_failed and r.flywheel and r.min_passing_speed is not None and math.isfinite(r.min_passing_speed):
        hint = f"; the force passes from a mean {np.degrees(r.min_passing_speed):.0f} deg/s (pumplink speed)"
    elif force_failed and r.dynamics:
        hint = "; pumplink speed gives the speeds at which it passes"
    return f"[bold red]VERDICT: FAIL[/] — {bad}{hint}"


def advice_row(a) -> dict[str, Any]:
    """One suggested change (:class:`pumplink.analysis.Suggestion`) as a JSON row."""
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


# -------------------------------------------------------------------------- model choice, verification, speed
def explain_rows(effects) -> list[dict[str, Any]]:
    """The model-choice report as rows (JSON/CSV)."""
    return [
        {
            "effect": e.name,
            "included": e.included,
            "value": num(e.value),
            "unit": e.unit,
            "compared_with": e.compared_with,
            "ratio": num(e.ratio),
            "note": e.note,
        }
        for e in effects
    ]


def render_explain(effects, why: str, out=None, cadence=None, force_limit: float = 0.0) -> None:
    """`pumplink force --explain` (table output): the effects table, the reason, and the best
    cadence (:class:`pumplink.analysis.Cadence`, when the spec gives inertia)."""
    from rich import box
    from rich.markup import escape
    from rich.table import Table

    c = console(out or sys.stdout)
    t = Table(
        title="Model choice: what is in the model, and how big it is at this speed",
        title_justify="left",
        box=box.SIMPLE_HEAD,
        pad_edge=False,
    )
    for h in ("effect", "in model", "size", "compared with"):
        t.add_column(h, justify="right" if h == "size" else "left")
    notes = []
    for i, e in enumerate(effects, 1):
        inc = "[green]yes[/]" if e.included else "[dim]neglected[/]"
        ratio = (
            "" if not math.isfinite(e.ratio) else (f"{e.ratio:.0%}" if e.ratio < 10 else f"{e.ratio:.1f}×")
        )
        t.add_row(
            f"{i}. {escape(e.name)}",
            inc,
            f"{_f(e.value, '{:.3g}', '∞')} {e.unit}",
            escape(f"{ratio} {e.compared_with}" if ratio else ""),
        )
        notes.append(f"{i}. {e.note}")
    c.print(t)
    for n in notes:
        c.print(n, markup=False)
    c.print(why, markup=False)
    if cadence is not None:
        for line in cadence_lines(cadence, force_limit):
            c.print(line, markup=False)


def verify_row(v) -> dict[str, Any]:
    """The solve_ivp cross-check (:class:`pumplink.analysis.Verification`) as a row."""
    sim = v.integration
    return {
        "method": "scipy solve_ivp (DOP853, rtol 1e-11), open-loop force profile F(θ2)",
        "cycles": sim.cycles,
        "periodicity": num(sim.periodicity),
        "mean_speed_deg_s": deg(sim.mean_speed),
        "time_mean_speed_deg_s": deg(sim.time_mean_speed),
        "speed_range_deg_s": {"min": deg(sim.min_speed), "max": deg(sim.max_speed)},
        "fluctuation": num(sim.fluctuation),
        "tolerance": v.tolerance,
        "agrees": v.agrees,
    }


def static_verify_row(v) -> dict[str, Any]:
    """The quasi-static cross-check (:class:`pumplink.analysis.StaticCheck`) as a row."""
    return {
        "method": "virtual work from positions (central differences) and a dense sweep",
        "angles": v.angles,
        "virtual_work": num(v.virtual_work),
        "samples": v.samples,
        "sweep_peak_force_N": num(v.sweep_peak),
        "peak_force_N": num(v.peak),
        "tolerance": v.tolerance,
        "agrees": v.agrees,
    }


def render_verify(row: dict[str, Any], out=None) -> None:
    c = console(out or sys.stdout)
    if "virtual_work" in row:  # the quasi-static model
        ok = "[bold green]agrees[/]" if row["agrees"] else "[bold red]DISAGREES[/]"
        c.print(
            f"verify (quasi-static: {row['method']}): {ok} — F·dPx/dθ2 = Mw to {row['virtual_work']:.1e} "
            f"at {row['angles']} crank angles; {row['samples']:,} samples outside the dead bands peak at "
            f"{row['sweep_peak_force_N']:.3f} N, the exact peak {row['peak_force_N']:.3f} N"
        )
        return
    ok = "[bold green]agrees[/]" if row["agrees"] else "[bold red]DISAGREES[/]"
    c.print(
        f"verify ({row['method']}, {row['cycles']} revolutions): {ok} — "
        f"periodic to {row['periodicity']:.1e}, "
        f"mean speed (max+min)/2 = {row['mean_speed_deg_s']:.4f} deg/s, "
        f"fluctuation δ = {row['fluctuation']:.6f}, "
        f"wheel {row['speed_range_deg_s']['min']:.1f}–{row['speed_range_deg_s']['max']:.1f} deg/s "
        f"(time-averaged {row['time_mean_speed_deg_s']:.1f} deg/s)"
    )


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
            "grip_speed_m_s": num(g),
            "verdict": o,
            "pass": bool(ok),
        }
        for w, b, f, fw, dy, ef, m, p, g, o, ok in zip(*cols)
    ]


#: The words of a model key in reports (``pumplink.models.MODELS[key].label``).
MODEL_WORDS = {
    "quasi-static": "quasi-static + dead band",
    "flywheel": "flywheel",
    "dynamics": "full dynamics",
}


def cadence_row(c) -> dict[str, Any]:
    """The best cadence and the passing speeds (:class:`pumplink.analysis.Cadence`) as JSON."""

    def rng(pair):
        lo, hi = pair
        if not math.isfinite(lo):
            return None
        return {"min": deg(lo), "max": deg(hi) if math.isfinite(hi) else None}

    return {
        "speed_deg_s": deg(c.speed),
        "rpm": num(math.degrees(c.speed) / 6.0),
        "effort_peak_force_N": num(c.effort),
        "hand_peak_force_N": num(c.hand_force),
        "power_W": num(c.power),
        "at_edge_of_search": c.at_edge,
        "searched_deg_s": {"min": deg(c.searched[0]), "max": deg(c.searched[1])},
        "model": MODEL_WORDS[c.model],
        "force_passes_deg_s": rng(c.force_range),
        "verdict_passes_deg_s": rng(c.passing),
    }


def cadence_lines(c, force_limit: float) -> list[str]:
    """The best cadence and the passing speeds in words (plain text, each under 80 columns)."""
    rpm = math.degrees(c.speed) / 6.0
    edge = " (the edge of the speeds searched)" if c.at_edge else ""
    lines = [
        f"best cadence: {math.degrees(c.speed):.0f} deg/s ({rpm:.0f} rpm){edge}, where the peak effort",
        f"  (hand force + the operator's arms) is least, {c.effort:.1f} N (hand force {c.hand_force:.1f} N),",
        f"  at {c.power:.0f} W",
    ]

    def span(pair):
        lo, hi = (math.degrees(v) for v in pair)
        top = "up" if not math.isfinite(hi) or hi >= math.degrees(c.searched[1]) * (1 - 1e-9) else f"{hi:.0f}"
        return f"from {lo:.0f} deg/s" + (" up" if top == "up" else f" to {top} deg/s")

    what = MODEL_WORDS[c.model]
    if math.isfinite(c.force_range[0]):
        lines.append(f"peak force ({what}) within {force_limit:g} N: {span(c.force_range)}")
    else:
        lines.append(f"peak force ({what}) above {force_limit:g} N at every speed")
    if math.isfinite(c.passing[0]):
        lines.append(f"no check fails (force, power, grip speed): {span(c.passing)}")
    else:
        lines.append("no speed passes every check (see the checks that fail)")
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
    if fmt == "json":
        return _json({**speed_summary(sw), "speeds": rows}, out)
    if fmt == "csv":
        return write_csv(rows, out)
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


# ----------------------------------------------------------------------------- transmission

BINDING_TEXT = {
    0: "both extremes (gamma_min = 180 - gamma_max)",
    1: "gamma_min (stationary on the arc)",
    2: "180 - gamma_max (stationary on the arc)",
}


# ----------------------------------------------------------------------------- transmission
def transmission_rows(opt, sim, comparisons=(), printed_gamma_min=None, check=None) -> dict[str, Any]:
    """JSON contract of ``pumplink transmission``.

    Parameters
    ----------
    opt : :class:`pumplink.mechanisms.crank_rocker.OptimalCrankRocker` (scalar).
    sim : :class:`pumplink.mechanisms.crank_rocker.MeasuredMotion` of the optimum.
    comparisons : :class:`pumplink.mechanisms.crank_rocker.Comparison` of published designs.
    printed_gamma_min : the transmission angle the paper prints for its diagram design [deg].
    check : :class:`pumplink.synthesis.OptimumCheck` (simulation agreement and verdict), or None.
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
    if fmt == "json":
        return _json(row, out)
    if fmt == "csv":
        flat = {k: v for k, v in row.items() if k not in ("compare", "checks")}
        flat.update({f"check_{ch['key']}": ch["result"] for ch in row.get("checks", ())})
        return write_csv([flat], out)
    from rich.markup import escape
    from rich.table import Table

    from pumplink.output.mechanisms import print_wrapped, render_verdict

    c = console(out)
    c.print(
        f"[bold]Optimal-transmission crank-rocker[/] for K = {row['time_ratio']:g} "
        f"(θ = {row['theta_deg']:.6f}°), swing φ = {row['swing_deg']:g}°, rocker = {row['rocker']:g}"
    )
    from rich import box

    t = Table(
        title="Link lengths (in the rocker's unit) and transmission angle",
        title_justify="left",
        box=box.SIMPLE_HEAD,
        pad_edge=False,
        caption="(1) optimum (this tool)"
        + "".join(f"; ({n}) {escape(cmp['design'])}" for n, cmp in enumerate(row["compare"], 2)),
        caption_justify="left",
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
        f"γmin = {row['gamma_min_deg']:.9f}°, γmax = {row['gamma_max_deg']:.9f}°; binding: {row['binding']}; "
        f"crank pivot on the {row['crank_pivot_side']}"
    )
    for cmp in row["compare"]:
        c.print(
            f"optimum is better than the {cmp['design']} by {cmp['ours_better_by_deg']:.9f}°", markup=False
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


# ----------------------------------------------------------------------------- optimize
def optimize_row(res) -> dict[str, Any]:
    """JSON contract of ``pumplink optimize`` (spec units: m, deg, N).

    ``optimum`` and ``spec_design`` each carry the verdict of ``pumplink force`` on that design
    (``verdict``, ``pass``, ``checks``), ``peak_force_N`` the verdict's peak (the flywheel's least
    peak force when the spec gives inertia) and ``dead_band_peak_force_N`` the quasi-static peak
    outside the dead bands.  ``meets_constraints`` is about the search's own constraints
    (--grip-height, --stroke, transmission angle), which the optimum always meets.
    """
    from pumplink.optimize import CONSTRAINTS, VARIABLE_UNITS

    p = res.problem
    b, s = res.at_best, res.at_spec
    names = p.constraint_names()
    spec_lk = p.spec.linkage
    op = p.spec.operator
    obj_b, obj_s = float(b.objective[0]), float(s.objective[0])
    spec_ok = bool(np.all(s.slack[:, 0] >= 0))

    def judged(r) -> dict[str, Any]:
        return {
            "model": r.model,
            "peak_force_N": num(r.verdict_peak_force),
            "dead_band_peak_force_N": num(r.dead_band_peak_force),
            "mean_force_N": num(r.mean_force),
            "verdict": r.outcome,
            "pass": r.passed,
            "checks": [check_row(c, r) for c in r.checks],
        }

    return {
        "name": p.spec.name,
        "objective": p.objective,
        "model": p.model,
        "inertia_kg_m2": None if p.spec.inertia is None else num(p.spec.inertia),
        "speed_fluctuation": op.speed_fluctuation if p.flywheel else None,
        "speed_deg_s": op.speed,
        "seed": res.seed,
        "axle_height_m": p.axle_height,
        "grip_height_range_m": list(p.grip_height),
        "stroke_range_m": list(p.stroke),
        "force_limit_N": p.spec.operator.force_limit,
        "variables": [
            {
                "key": k,
                "unit": VARIABLE_UNITS[k],
                "lower": float(lo),
                "upper": float(hi),
                "spec": float(getattr(spec_lk, k)),
                "optimum": float(v),
            }
            for k, lo, hi, v in zip(p.names, p.lower, p.upper, res.x)
        ],
        "optimum": {
            **judged(res.best_result),
            "transmission_deg": num(b.transmission[0]),
            "grip_height_m": [num(b.grip_low[0]), num(b.grip_high[0])],
            "stroke_m": num(b.stroke[0]),
            "rocker_pivot_height_m": num(p.axle_height - res.best.linkage.D1),
            "meets_constraints": True,
        },
        "spec_design": {
            **judged(res.spec_result),
            "transmission_deg": num(s.transmission[0]),
            "meets_constraints": spec_ok,
            "violated": [n for n, g in zip(names, s.slack[:, 0]) if g < 0],
        },
        "improvement_N": num(obj_s - obj_b) if obj_s < 1e5 else None,
        "improvement_pct": num(100 * (obj_s - obj_b) / obj_s) if obj_s < 1e5 else None,
        "constraints": [
            {"name": n, "unit": u, "slack": num(g), "binding": n in res.binding}
            for n, (_, u), g in zip(names, CONSTRAINTS, b.slack[:, 0])
        ],
        "binding": list(res.binding) + list(res.at_bounds),
        "evaluations": res.evaluations,
        "generations": res.iterations,
        "polished": res.polished,
    }


#: The verdict's words with Rich markup.
OUTCOME_MARKUP = {
    "PASS": "[bold green]PASS[/]",
    "PASS with warnings": "[bold yellow]PASS with warnings[/]",
    "FAIL": "[bold red]FAIL[/]",
}


def render_optimize(row: dict[str, Any], fmt: str, out=None, strict: bool = False) -> None:
    """`pumplink optimize`: variables, forces and verdicts, constraints and what binds."""
    out = out or sys.stdout
    if fmt == "json":
        return _json(row, out)
    if fmt == "csv":
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
        return write_csv([flat], out)
    from rich import box
    from rich.markup import escape
    from rich.table import Table

    c = console(out)
    fly = row["speed_fluctuation"] is not None  # an energy model decides (flywheel or full dynamics)
    model = (
        f"{row['model']}, J = {row['inertia_kg_m2']:.4g} kg·m², δ ≤ {row['speed_fluctuation']:g}, at "
        f"{row['speed_deg_s']:g} deg/s"
        if fly
        else row["model"]
    )
    c.print(
        f"[bold]{escape(row['name'])}[/]: minimise the {row['objective']} operator force "
        f"(model: {model}; seed {row['seed']}); axle height "
        f"{row['axle_height_m']:g} m, grip height "
        f"{row['grip_height_range_m'][0]:g}–{row['grip_height_range_m'][1]:g} m, "
        f"stroke {row['stroke_range_m'][0]:g}–{row['stroke_range_m'][1]:g} m"
    )
    t = Table(title="Variables", title_justify="left", box=box.SIMPLE_HEAD, pad_edge=False)
    for h in ("key", "bounds", "spec", "optimum"):
        t.add_column(h, justify="left" if h == "key" else "right")
    for v in row["variables"]:
        t.add_row(
            f"{v['key']} \\[{v['unit']}]",
            f"{v['lower']:g} … {v['upper']:g}",
            f"{v['spec']:.4f}",
            f"{v['optimum']:.6f}",
        )
    c.print(t)
    o, s = row["optimum"], row["spec_design"]
    t = Table(
        title="Forces and verdicts (as pumplink force)",
        title_justify="left",
        box=box.SIMPLE_HEAD,
        pad_edge=False,
        caption="peak: the verdict's peak"
        + (f" ({s['model']} / {o['model']})" if fly else " outside the dead bands"),
        caption_justify="left",
    )
    for h in ("design", "peak [N]", "mean [N]", "γ [°]", "verdict"):
        t.add_column(escape(h), justify="left" if h in ("design", "verdict") else "right")
    for label, d in (("spec's own design", s), ("[bold]optimum[/]", o)):
        t.add_row(
            label,
            _f(d["peak_force_N"], "{:.2f}", none="∞"),
            _f(d["mean_force_N"], "{:.2f}"),
            _f(d["transmission_deg"], "{:.2f}"),
            OUTCOME_MARKUP[d["verdict"]],
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
            f"the spec's own design is outside the search's limits: {'; '.join(s['violated'])}", markup=False
        )
    t = Table(
        title="Constraints at the optimum (slack >= 0 is met)",
        title_justify="left",
        box=box.SIMPLE_HEAD,
        pad_edge=False,
    )
    for h in ("constraint", "slack", "binding"):
        t.add_column(h, justify="right" if h == "slack" else "left")
    for k in row["constraints"]:
        t.add_row(k["name"], f"{k['slack']:.4g} {k['unit']}", "[bold]binds[/]" if k["binding"] else "")
    c.print(t)
    key = "peak_force_N" if row["objective"] == "peak" else "mean_force_N"
    if row["improvement_N"] is not None:
        c.print(
            f"{row['objective']} force {_f(s[key], '{:.2f}')} N → {_f(o[key], '{:.2f}')} N "
            f"({row['improvement_pct']:+.1f} % lower than the spec's own design)"
            if row["improvement_pct"] >= 0
            else f"the optimum needs {-row['improvement_N']:.2f} N more than the spec's own design, "
            f"which breaks: {'; '.join(s['violated'])}",
            markup=False,
        )
    c.print(f"binding: {', '.join(row['binding']) or 'none (interior optimum)'}", markup=False)
    c.print(
        f"grip {o['grip_height_m'][0]:.3f}–{o['grip_height_m'][1]:.3f} m, stroke {o['stroke_m']:.3f} m, "
        f"rocker pivot {o['rocker_pivot_height_m']:+.3f} m above the ground"
        f"{' (below ground: needs a pit)' if o['rocker_pivot_height_m'] < 0 else ''}",
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
    tail = " — fails under --strict" if strict and o["verdict"] == "PASS with warnings" else ""
    how = f" ({o['model']})" if fly else ""
    c.print(
        f"VERDICT: {OUTCOME_MARKUP[o['verdict']]} for the optimum: peak{how} "
        f"{_f(o['peak_force_N'], '{:.2f}', none='∞')} N vs limit {row['force_limit_N']:g} N "
        f"({row['evaluations']} designs evaluated, {row['generations']} generations"
        f"{', polished' if row['polished'] else ''}){tail}"
    )


# ----------------------------------------------------------------------------- methods
def _e(x) -> str:
    return "—" if x is None else ("0" if x == 0 else f"{x:.1e}")


#: How each finding of the method comparison reads (``pumplink.accuracy.failures``).
FAILURE_TEXT = {
    "wrong": "{label}: {count} of {n} values silently wrong",
    "missed_singular": "{label}: {count} dead centres returned as finite forces",
    "flagged": "{label}: {count} of {n} points flagged (no value)",
}


def failure_sentences(records: list[dict]) -> list[str]:
    """The method comparison's findings in words."""
    from pumplink.methods import POINT_LABELS  # here: `force` and `synth` need no method study

    return [FAILURE_TEXT[f["what"]].format(label=POINT_LABELS[f["kind"]], **f) for f in records]


def json_rows(rows: list[dict]) -> list[dict]:
    """The JSON contract: name, seconds_per_position, max_rel_error_uniform,
    max_rel_error_near_dead_centre, failures (plus summary, cannot_handle and per-sampling detail,
    keyed by the words of each sampling)."""
    from pumplink.methods import POINT_LABELS

    return [
        {
            "name": r["name"],
            "summary": r["summary"],
            "cannot_handle": r["cannot_handle"],
            "seconds_per_position": r["seconds_per_position"],
            "max_rel_error_uniform": r["max_rel_error_uniform"],
            "max_rel_error_near_dead_centre": r["max_rel_error_near_dead_centre"],
            "failures": failure_sentences(r["failures"]),
            "samplings": {POINT_LABELS[k]: v for k, v in r["samplings"].items()},
        }
        for r in rows
    ]


def render_methods(
    name: str, rows: list[dict], study: list[dict], fmt: str, dead_band_deg: float, out=None
) -> None:
    """`pumplink methods`: one row per method and the sampling study."""
    out = out or sys.stdout
    if fmt == "json":
        return _json({"design": name, "methods": json_rows(rows), "sampling": study}, out)
    if fmt == "csv":
        return write_csv(
            [
                {k: v for k, v in r.items() if k not in ("samplings", "failures")}
                | {"failures": "; ".join(failure_sentences(r["failures"]))}
                for r in rows
            ],
            out,
        )
    from rich import box
    from rich.markup import escape
    from rich.table import Table

    c = console(out)
    kinds = list(rows[0]["samplings"]) if rows else []
    short = {
        "uniform": "uniform",
        "near_dead_centre": "near DC",
        "dead_centre": "at DC",
        "danger_points": "danger",
    }
    t = Table(
        title=f"{name}: force methods vs the 50-digit reference",
        title_justify="left",
        caption="largest relative error of Fh on each sample set: uniform sweep; near DC (1° down to "
        "1e-6° from a dead centre); at DC; danger points; — = every point flagged",
        caption_justify="left",
        box=box.SIMPLE_HEAD,
        pad_edge=False,
    )
    for h in ["method", "time/pos. [ns]"] + [short.get(k, k) for k in kinds] + ["verdict"]:
        t.add_column(escape(h), justify="left" if h in ("method", "verdict") else "right")
    notes = []
    for r in rows:
        cells = [r["name"], f"{r['seconds_per_position'] * 1e9:,.0f}"]
        for k in kinds:
            st = r["samplings"][k]
            cells.append(_e(st["max_rel_error"]) + ("*" if st["flagged"] else ""))
        sentences = failure_sentences(r["failures"])
        wrong = any(st["wrong"] or st["missed_singular"] for st in r["samplings"].values())
        cells.append("[red]WRONG[/]" if wrong else "flags" if sentences else "[green]ok[/]")
        t.add_row(*cells)
        notes += [f"  {r['name']}: {x}" for x in sentences]
    c.print(t)
    c.print(
        '* some points flagged: NaN with a flag (dead centre: "∞ (dead centre)"), never a made-up '
        "number. WRONG = an unflagged value off by more than the method's registered tolerance.",
        markup=False,
    )
    for line in notes:
        c.print(line, markup=False)
    for r in rows:
        c.print(f"  {r['name']}: {r['summary']}; cannot handle: {r['cannot_handle']}", markup=False)

    st = Table(
        title=f"How many samples? A uniform sweep from crank 0° vs exact (dead band ±{dead_band_deg:g}°)",
        title_justify="left",
        caption="max |Fh|: the sweep's largest force with no band; peak: outside the band; "
        "err: relative error of the sampled value",
        caption_justify="left",
        box=box.SIMPLE_HEAD,
        pad_edge=False,
    )
    for h in (
        "N",
        "max |Fh| [N]",
        "peak [N]",
        "exact [N]",
        "err",
        "mean [N]",
        "exact [N]",
        "err",
    ):
        st.add_column(escape(h), justify="right")
    for s in study:
        st.add_row(
            str(s["n"]),
            f"{s['sampled_max']:.1f}" if s["sampled_max"] is not None else "—",
            f"{s['sampled_peak']:.2f}" if s["sampled_peak"] is not None else "—",
            f"{s['exact_peak']:.2f}",
            _e(s["peak_error"]),
            f"{s['sampled_mean']:.4f}",
            f"{s['exact_mean']:.4f}",
            _e(s["mean_error"]),
        )
    c.print(st)
    c.print(
        "A sweep without a dead band reports whatever spike it lands next to (the true force is infinite at "
        "the dead centres); with the band, the exact peak is found by root-bracketing, whatever N.",
        markup=False,
    )
