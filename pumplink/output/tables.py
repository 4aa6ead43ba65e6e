"""What each command shows: the rows (JSON/CSV contracts) and the Rich tables.

Renderers only render: every number comes from the library's results.  One dispatch for
table / JSON / CSV (:mod:`pumplink.output.formats`).
"""

from __future__ import annotations

import math
import sys
from typing import TYPE_CHECKING, Any

import numpy as np

if TYPE_CHECKING:
    from pumplink.analysis import Design, ForceResult, SpeedSweep
from pumplink.methods import POINT_LABELS
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
            "required_peak_force_N": None if r.least_peak_force is None else num(r.least_peak_force),
            "min_passing_speed_deg_s": None if r.min_passing_speed is None else deg(r.min_passing_speed),
            "wheel_speed_range_deg_s": _speed_range(r),
            "link_kinetic_energy_J": num(r.link_energy),
            "mean_force_N": num(r.mean_force),
            "peak_force_N": num(r.dead_band_peak_force),
            "peak_force_infinite": bool(
                r.dead_band_peak_force == math.inf
            ),  # dead_band = 0: the window reaches a dead centre
            "peak_crank_deg": deg(r.dead_band_peak_angle),
            "sampled_peak_force_N": num(r.sampled_peak),
            "samples_n": r.samples_n,
            "pass": r.passed,
            "checks": [
                {
                    "name": check_label(c, r),
                    "value": num(c.value),
                    "limit": c.limit,
                    "relation": c.relation,
                    "unit": c.unit,
                    "severity": c.severity,
                    "pass": c.passed,
                }
                for c in r.checks
            ],
        }
    )
    return out


def check_label(c, r: ForceResult) -> str:
    """The words for a verdict check (``pumplink.verdict.Check.key``) in this result's context."""
    op = r.design.spec.operator
    if c.key == "peak_force":
        if r.flywheel:
            return f"peak force with the flywheel (δ ≤ {op.speed_fluctuation:g})"
        return f"peak force outside ±{op.dead_band:g}° of the dead centres"
    return CHECK_LABELS[c.key]


#: Words for the checks whose label does not depend on the result.
CHECK_LABELS = {
    "mean_force": "mean force",
    "link_energy_share": "links' kinetic energy (neglected), share of the energy band",
    "transmission_angle": "transmission angle, min(γmin, 180° − γmax)",
    "power": "operator power (sustained)",
    "axle_height": "axle height (paper: 0.40-0.70 m)",
}


def _speed_range(r: ForceResult):
    sc = r.scene
    if sc is None or not math.isfinite(sc.least_peak_force):
        return None
    return {"min": deg(sc.min_speed), "max": deg(sc.max_speed)}


def sample_rows(r: ForceResult) -> list[dict[str, Any]]:
    """One dict per sampled crank angle (JSON/CSV)."""
    if r.samples is None:
        return []
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
    lists = {k: v.tolist() for k, v in cols.items()}
    sing, band = s.singular.tolist(), r.in_dead_band.tolist()
    rows = []
    for i in range(len(sing)):
        row = {k: (v[i] if math.isfinite(v[i]) else None) for k, v in lists.items()}
        row["singular"] = sing[i]
        row["in_dead_band"] = band[i]
        rows.append(row)
    return rows


def render_designs(designs: list[Design], fmt: str, out=None) -> None:
    """`pumplink synth`: one row per design (Table-1 style)."""
    out = out or sys.stdout
    rows = [design_row(d) for d in designs]
    if fmt == "json":
        return _json({"designs": rows}, out)
    if fmt == "csv":
        return write_csv(rows, out)
    from rich.markup import escape
    from rich.table import Table

    t = Table(
        title="Dead-centre synthesis, Eq. (1)–(2) of the pump paper",
        title_justify="left",
        caption="lengths \\[m], angles \\[deg]; l1 frame, l2 crank, l3 coupler, l4 rocker, H handle, "
        "Δθ swing, K time ratio, γ transmission angle, DC crank angle of the extended / folded "
        "dead centre",
        caption_justify="left",
    )
    for h in (
        "design",
        "L1",
        "D1",
        "b",
        "l4",
        "H",
        "Δθ",
        "l1",
        "β",
        "l2",
        "l3",
        "K",
        "γ min",
        "γ max",
        "DC ext",
        "DC fold",
        "feasible",
    ):
        t.add_column(h, justify="left" if h in ("design", "feasible") else "right", no_wrap=h == "design")
    notes = []
    for d, r in zip(designs, rows):
        ok = "[green]yes[/]" if r["feasible"] else f"[red]no ({len(notes) + 1})[/]"
        if not r["feasible"]:
            notes.append(f"({len(notes) + 1}) {r['name']}: {r['error']}.")  # printed with markup=False
        lk = d.spec.linkage
        tr, dc = r["transmission_angle_deg"], r["dead_centres_deg"]
        t.add_row(
            escape(r["name"]),
            _f(lk.L1),
            _f(lk.D1),
            _f(lk.b),
            _f(lk.rocker),
            _f(lk.handle),
            _f(lk.swing, "{:.1f}"),
            _f(r["frame_length"], "{:.4f}"),
            _f(r["beta_deg"], "{:.2f}"),
            _f(r["crank_length"], "{:.4f}"),
            _f(r["coupler_length"], "{:.4f}"),
            _f(r["time_ratio"], "{:.4f}"),
            _f(tr["min"], "{:.1f}"),
            _f(tr["max"], "{:.1f}"),
            _f(dc["extended"], "{:.2f}"),
            _f(dc["folded"], "{:.2f}"),
            ok,
        )
    c = console(out)
    c.print(t)
    for n in notes:
        c.print(n, markup=False)


def _bar(value, limit, width=20) -> str:
    if value is None or not math.isfinite(value):
        return "[red]" + "▶" * width + "[/]"
    n = int(round(min(float(width), abs(value) / limit * width / 1.5)))  # full bar at 1.5x the limit
    mark = "█" * n
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
            f"arms {op.arm_mass_kg:g} kg at the grip"
            if op.arms_in_verdict
            else "hand force (arms not included)"
        )
        return (
            f"model: full dynamics, J = {r.inertia:.3f} kg·m² plus the coupler and handle masses and "
            f"their weight, δ ≤ {r.speed_fluctuation:g} at a mean {r.speed_deg_s:g} deg/s; {arms}"
            + (f"; muscular effort with the arms {r.effort_peak_force:.1f} N" if r.effort_peak_force else "")
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
    r: ForceResult, fmt: str, summary: bool = False, out=None, extra: dict | None = None
) -> None:
    """`pumplink force`: sweep table (condensed), checks and the verdict.

    ``extra`` (JSON only): more top-level keys, e.g. ``explain`` and ``verify``.
    """
    out = out or sys.stdout
    if fmt == "json":
        obj = force_summary(r)
        obj.update(extra or {})
        if not summary:
            obj["samples"] = sample_rows(r)
        return _json(obj, out)
    if fmt == "csv":
        return write_csv([force_summary(r)] if summary or r.samples is None else sample_rows(r), out)

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
        f"[bold]{name}[/]  crank l2 = {d['crank_length']:.4f} m, coupler l3 = {d['coupler_length']:.4f} m, "
        f"rocker l4 = {d['rocker_length']:.4f} m, frame l1 = {d['frame_length']:.4f} m, "
        f"handle H = {d['handle_length']:.3f} m"
    )
    c.print(
        f"dead centres at crank {dc['extended']:.2f}° (extended) and {dc['folded']:.2f}° (folded); "
        f"time ratio K = {d['time_ratio']:.4f}; wheel torque Mw = {r.wheel_torque:.3f} N·m at "
        f"{r.speed_deg_s:g} deg/s ({r.power:.1f} W)"
    )
    fly = r.flywheel and r.operator_force is not None

    if not summary and r.samples is not None and r.samples.crank_angle.size:
        s = r.samples
        kind = "flywheel scene: the operator's force and the wheel speed" if fly else "quasi-static"
        t = Table(
            title=f"Operator force over the crank cycle ({kind}, {r.samples_n} samples"
            f"{', condensed' if s.crank_angle.size > 28 else ''})",
            title_justify="left",
        )
        heads = ["crank θ2 [deg]", "quasi-static Fh [N]"]
        heads += (
            ["operator F [N]", f"|F| vs {r.force_limit:g} N", "wheel ω [deg/s]"]
            if fly
            else [f"|Fh| vs {r.force_limit:g} N"]
        )
        heads += ["grip speed [m/s]", "φ [deg]", "rocker θ4 [deg]", "γ [deg]", "note"]
        for h in heads:
            t.add_column(escape(h), justify="left" if h.startswith(("|", "note")) else "right")
        rows = []
        hs = r.handle_speed

        def add(st, i, speed, note, op=None, w=None):
            f = st.force[i]
            qs = "∞ (dead centre)" if st.singular[i] else _f(f, "{:+.1f}")
            if fly:
                mid = [_f(op, "{:+.1f}"), _bar(op, r.force_limit), _f(np.degrees(w), "{:.1f}")]
            else:
                mid = [_bar(None if st.singular[i] else float(f), r.force_limit)]
            rows.append(
                (
                    float(st.crank_angle[i]) % (2 * math.pi),
                    _f(np.degrees(st.crank_angle[i]) % 360, "{:.2f}"),
                    qs,
                    *mid,
                    _f(speed, "{:.3f}"),
                    _f(np.degrees(st.rocker_angle[i]) - 90, "{:+.1f}"),
                    _f(np.degrees(st.rocker_angle[i]), "{:.1f}"),
                    _f(np.degrees(st.transmission_angle[i]), "{:.1f}"),
                    note,
                )
            )

        for i in _condensed_indices(r):
            if s.singular[i]:
                note = "[bold]dead centre[/]"
            elif fly:
                note = "[dim]wheel at top speed[/]" if r.on_ceiling[i] else ""
            else:
                note = "[dim]in dead band[/]" if r.in_dead_band[i] else ""
            add(s, i, hs[i], note, *((r.operator_force[i], r.wheel_speed[i]) if fly else ()))
        if s.crank_angle.size > 28 and r.marks is not None:  # mark the dead centres and the exact peak
            m = r.marks
            speeds = r.mark_grip_speed
            if fly:
                ws, ops = r.mark_wheel_speed, r.mark_operator_force
                for i, label in enumerate(("dead centre (extended)", "dead centre (folded)")):
                    add(m, i, speeds[i], f"[bold]{label}[/]", ops[i], ws[i])
            else:
                for i, label in enumerate(
                    ("dead centre (extended)", "dead centre (folded)", "exact peak outside dead band")
                ):
                    add(m, i, speeds[i], f"[bold]{label}[/]")
        for row in sorted(rows, key=lambda x: x[0] % (2 * math.pi)):
            t.add_row(*row[1:])
        c.print(t)

    ct = Table(title="Checks", title_justify="left")
    for h in ("check", "value", "limit", "result"):
        ct.add_column(h, justify="right" if h in ("value", "limit") else "left")
    if r.flywheel:
        ct.add_row(
            f"quasi-static peak outside ±{r.design.spec.operator.dead_band:g}° "
            "(dead-band model, for comparison)",
            f"{_f(r.dead_band_peak_force, '{:.2f}', '∞')} N",
            "",
            "[dim]info[/]",
        )
        mps = r.min_passing_speed
        ct.add_row(
            "least mean wheel speed that passes the limit",
            "never" if mps == math.inf else f"{_f(np.degrees(mps), '{:.1f}')} deg/s",
            f"at {r.force_limit:g} N",
            "[dim]info[/]",
        )
    else:
        ct.add_row(
            "sampled peak outside dead band (for comparison)",
            f"{_f(r.sampled_peak, '{:.2f}')} N",
            f"{r.samples_n} samples",
            "[dim]info[/]",
        )
    for ch in r.checks:
        res = (
            "[green]pass[/]"
            if ch.passed
            else ("[red]FAIL[/]" if ch.severity == "fail" else "[yellow]warning[/]")
        )
        unit = f" {ch.unit}" if ch.unit else ""
        ct.add_row(
            escape(check_label(ch, r)),
            f"{_f(ch.value, '{:.2f}', '∞') if ch.value != np.inf else '∞'}{unit}",
            f"{ch.relation} {ch.limit:g}{unit}",
            res,
        )
    c.print(ct)
    c.print(model_line(r))
    warned = [ch for ch in r.checks if ch.severity == "warn" and not ch.passed]
    peak = r.verdict_peak_force
    how = " with the flywheel" if r.flywheel else ""
    if r.passed:
        note = f" ({len(warned)} warning{'s' if len(warned) > 1 else ''} below)" if warned else ""
        c.print(
            f"[bold green]VERDICT: PASS[/] — mean {r.mean_force:.1f} N and peak {peak:.1f} N{how} are within "
            f"the {r.force_limit:g} N limit{note}"
        )
    else:
        bad = [check_label(ch, r) for ch in r.checks if ch.severity == "fail" and not ch.passed]
        hint = ""
        if r.flywheel and r.min_passing_speed is not None and math.isfinite(r.min_passing_speed):
            hint = (
                f"; it passes from a mean {np.degrees(r.min_passing_speed):.0f} deg/s (see: pumplink speed)"
            )
        c.print(
            f"[bold red]VERDICT: FAIL[/] — {', '.join(bad)} above the {r.force_limit:g} N limit "
            f"(mean {r.mean_force:.1f} N, peak {_f(peak, '{:.1f}', '∞')} N{how}){hint}"
        )
    for ch in warned:
        if ch.key == "link_energy_share":
            c.print(
                f"[yellow]warning:[/] the links' kinetic energy is {ch.value:.0f} % of the energy band (> "
                f"{ch.limit:g} %): the flywheel model neglects it, so treat the verdict as an estimate "
                "(a lighter handle or a heavier wheel; see --explain)"
            )
            continue
        c.print(
            f"[yellow]warning:[/] {escape(check_label(ch, r))} is {ch.value:.2f} {ch.unit}, "
            f"outside {ch.relation} {ch.limit:g} {ch.unit}"
            + (
                " (a person sustains ~75 W for hours; slow the wheel or lower the load)"
                if ch.key == "power"
                else ""
            )
            + (
                " (pressure angle above 45°: the coupler pushes the crank at a poor angle "
                "and the joints wear)"
                if ch.key == "transmission_angle"
                else ""
            )
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


def render_explain(effects, why: str, out=None) -> None:
    """`pumplink force --explain` (table output): the effects table and the reason."""
    from rich.markup import escape
    from rich.table import Table

    c = console(out or sys.stdout)
    t = Table(
        title="Model choice: what is in the model, and how big it is at this speed", title_justify="left"
    )
    for h in ("effect", "in model", "size", "compared with", "ratio", "note"):
        t.add_column(h, justify="right" if h in ("size", "ratio") else "left")
    for e in effects:
        inc = "[green]yes[/]" if e.included else "[dim]neglected[/]"
        ratio = (
            "" if not math.isfinite(e.ratio) else (f"{e.ratio:.0%}" if e.ratio < 10 else f"{e.ratio:.1f}×")
        )
        t.add_row(
            escape(e.name),
            inc,
            f"{_f(e.value, '{:.3g}', '∞')} {e.unit}",
            escape(e.compared_with),
            ratio,
            escape(e.note),
        )
    c.print(t)
    c.print(why, markup=False)


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


def render_verify(row: dict[str, Any], out=None) -> None:
    c = console(out or sys.stdout)
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
    return [
        {
            "speed_deg_s": float(w),
            "energy_band_J": num(b),
            "required_peak_force_N": num(f),
            "power_W": num(p),
            "pass": bool(ok),
        }
        for w, b, f, p, ok in zip(sw.speed_deg_s, sw.energy_band, sw.least_peak_force, sw.power, sw.passed)
    ]


def speed_summary(sw: SpeedSweep) -> dict[str, Any]:
    out = design_row(sw.design)
    out.update(
        {
            "model": "flywheel",
            "inertia_kg_m2": num(sw.inertia),
            "speed_fluctuation": sw.speed_fluctuation,
            "force_limit_N": num(sw.force_limit),
            "mean_force_N": num(sw.mean_force),
            "quasi_static_peak_force_N": num(sw.dead_band_peak_force),
            "min_passing_speed_deg_s": deg(sw.min_passing_speed),
        }
    )
    return out


def render_speed(sw: SpeedSweep, fmt: str, out=None) -> None:
    """`pumplink speed`: required peak force against wheel speed, and the least passing speed."""
    out = out or sys.stdout
    rows = speed_rows(sw)
    if fmt == "json":
        return _json({**speed_summary(sw), "speeds": rows}, out)
    if fmt == "csv":
        return write_csv(rows, out)
    from rich.markup import escape
    from rich.table import Table

    c = console(out)
    t = Table(
        title=f"{escape(sw.design.spec.name)}: least peak operator force against mean wheel speed (flywheel, "
        f"J = {sw.inertia:.3f} kg·m², δ ≤ {sw.speed_fluctuation:g})",
        title_justify="left",
    )
    for h in (
        "speed [deg/s]",
        "rpm",
        "band W [J]",
        "peak force [N]",
        f"vs {sw.force_limit:g} N",
        "power [W]",
        "result",
    ):
        t.add_column(escape(h), justify="left" if h.startswith(("vs", "result")) else "right")
    for r in rows:
        f = r["required_peak_force_N"]
        t.add_row(
            f"{r['speed_deg_s']:g}",
            f"{r['speed_deg_s'] / 6:.0f}",
            _f(r["energy_band_J"], "{:.2f}"),
            _f(f, "{:.1f}", "∞"),
            _bar(f, sw.force_limit),
            _f(r["power_W"], "{:.0f}"),
            "[green]pass[/]" if r["pass"] else "[red]FAIL[/]",
        )
    c.print(t)
    mps = sw.min_passing_speed
    c.print(
        f"mean force {sw.mean_force:.1f} N (the floor: an infinite flywheel); quasi-static peak "
        f"outside the dead band {sw.dead_band_peak_force:.1f} N (the dead-band model, blind to speed)"
    )
    if math.isfinite(mps):
        c.print(
            f"[bold]passes the {sw.force_limit:g} N limit from a mean {np.degrees(mps):.1f} deg/s "
            f"({np.degrees(mps) / 6:.0f} rpm)[/]"
        )
    else:
        c.print(
            f"[bold red]no speed passes[/]: the mean force {sw.mean_force:.1f} N is above the "
            f"{sw.force_limit:g} N limit"
        )


# ----------------------------------------------------------------------------- transmission

BINDING_TEXT = {
    0: "both extremes (gamma_min = 180 - gamma_max)",
    1: "gamma_min (stationary on the arc)",
    2: "180 - gamma_max (stationary on the arc)",
}


# ----------------------------------------------------------------------------- transmission
def transmission_rows(opt, sim, comparisons=(), printed_gamma_min=None) -> dict[str, Any]:
    """JSON contract of ``pumplink transmission``.

    Parameters
    ----------
    opt : :class:`pumplink.mechanisms.crank_rocker.OptimalCrankRocker` (scalar).
    sim : :class:`pumplink.mechanisms.crank_rocker.MeasuredMotion` of the optimum.
    comparisons : :class:`pumplink.mechanisms.crank_rocker.Comparison` of published designs.
    printed_gamma_min : the transmission angle the paper prints for its diagram design [deg].
    """
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
    return out


def render_transmission(row: dict[str, Any], fmt: str, out=None) -> None:
    """`pumplink transmission`: the optimum, its simulation and the comparison rows."""
    out = out or sys.stdout
    if fmt == "json":
        return _json(row, out)
    if fmt == "csv":
        flat = {k: v for k, v in row.items() if k != "compare"}
        return write_csv([flat], out)
    from rich.markup import escape
    from rich.table import Table

    c = console(out)
    c.print(
        f"[bold]Optimal-transmission crank-rocker[/] for K = {row['time_ratio']:g} "
        f"(θ = {row['theta_deg']:.6f}°), swing φ = {row['swing_deg']:g}°, rocker = {row['rocker']:g}"
    )
    t = Table(title="Link lengths (rocker's unit) and transmission angle", title_justify="left")
    for h in (
        "design",
        "crank",
        "coupler",
        "rocker",
        "frame",
        "rocker/frame",
        "min transmission [deg]",
        "simulated swing [deg]",
        "simulated K",
    ):
        t.add_column(escape(h), justify="left" if h == "design" else "right")
    sim = row["simulated"]
    t.add_row(
        "[bold]optimum (this tool)[/]",
        _f(row["crank"], "{:.6f}"),
        _f(row["coupler"], "{:.6f}"),
        _f(row["rocker"], "{:.6f}"),
        _f(row["frame"], "{:.6f}"),
        _f(row["rocker_to_frame"], "{:.6f}"),
        _f(row["min_transmission_deg"], "{:.9f}"),
        _f(sim["swing_deg"], "{:.9f}"),
        _f(sim["time_ratio"], "{:.9f}"),
    )
    for cmp in row["compare"]:
        t.add_row(
            cmp["design"],
            _f(cmp["crank"], "{:.4f}"),
            _f(cmp["coupler"], "{:.4f}"),
            _f(cmp["rocker"], "{:.4f}"),
            _f(cmp["frame"], "{:.4f}"),
            _f(cmp["rocker"] / cmp["frame"], "{:.6f}"),
            _f(cmp["min_transmission_deg"], "{:.9f}"),
            _f(cmp["simulated_swing_deg"], "{:.6f}"),
            _f(cmp["simulated_time_ratio"], "{:.6f}"),
        )
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


# ----------------------------------------------------------------------------- optimize
def optimize_row(res) -> dict[str, Any]:
    """JSON contract of ``pumplink optimize`` (spec units: m, deg, N).

    ``model`` says which model's peak force was the objective and decides ``passes_force_limit``
    (as ``pumplink force``): "flywheel" when the spec gives inertia, its least peak force then in
    ``required_peak_force_N`` (null for the quasi-static model); ``peak_force_N`` is always the
    windowed peak outside the dead bands.
    """
    from pumplink.optimize import CONSTRAINTS, VARIABLE_UNITS

    p = res.problem
    b, s = res.at_best, res.at_spec
    names = p.constraint_names()
    spec_lk = p.spec.linkage
    op = p.spec.operator
    peak_b, peak_s = float(b.dead_band_peak_force[0]), float(s.dead_band_peak_force[0])
    obj_b, obj_s = float(b.objective[0]), float(s.objective[0])
    spec_ok = bool(np.all(s.slack[:, 0] >= 0))
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
            "peak_force_N": num(peak_b),
            "required_peak_force_N": num(b.least_peak_force[0]),
            "mean_force_N": num(b.mean[0]),
            "transmission_deg": num(b.transmission[0]),
            "grip_height_m": [num(b.grip_low[0]), num(b.grip_high[0])],
            "stroke_m": num(b.stroke[0]),
            "rocker_pivot_height_m": num(p.axle_height - res.best.linkage.D1),
            "passes_force_limit": bool(b.passed[0]),
        },
        "spec_design": {
            "peak_force_N": num(peak_s),
            "required_peak_force_N": num(s.least_peak_force[0]),
            "mean_force_N": num(s.mean[0]),
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


def render_optimize(row: dict[str, Any], fmt: str, out=None) -> None:
    """`pumplink optimize`: variables, forces, constraints and what binds."""
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
        for v in row["variables"]:
            flat[f"{v['key']}_optimum"] = v["optimum"]
        flat["binding"] = "; ".join(row["binding"])
        return write_csv([flat], out)
    from rich.markup import escape
    from rich.table import Table

    c = console(out)
    fly = row["model"] == "flywheel"
    model = (
        f"model: flywheel, J = {row['inertia_kg_m2']:.4g} kg·m², δ ≤ {row['speed_fluctuation']:g}, at "
        f"{row['speed_deg_s']:g} deg/s"
        if fly
        else "model: quasi-static + dead band"
    )
    c.print(
        f"[bold]{row['name']}[/]: minimise the {row['objective']} operator force "
        f"({model}; seed {row['seed']}); axle height "
        f"{row['axle_height_m']:g} m, grip height "
        f"{row['grip_height_range_m'][0]:g}–{row['grip_height_range_m'][1]:g} m, "
        f"stroke {row['stroke_range_m'][0]:g}–{row['stroke_range_m'][1]:g} m"
    )
    t = Table(title="Variables", title_justify="left")
    for h in ("key", "bounds", "spec", "optimum"):
        t.add_column(h, justify="left" if h == "key" else "right")
    for v in row["variables"]:
        t.add_row(
            f"{v['key']} [{v['unit']}]",
            f"{v['lower']:g} … {v['upper']:g}",
            f"{v['spec']:.4f}",
            f"{v['optimum']:.6f}",
        )
    c.print(t)
    o, s = row["optimum"], row["spec_design"]
    peak_key = "required_peak_force_N" if fly else "peak_force_N"  # the peak of the verdict
    t = Table(title="Forces", title_justify="left")
    heads = (
        "design",
        *(("peak with the flywheel [N]", "peak outside the dead bands [N]") if fly else ("peak [N]",)),
        "mean [N]",
        "transmission [deg]",
        "meets constraints",
    )
    for h in heads:
        t.add_column(escape(h), justify="left" if h in ("design",) else "right")
    for label, d, meets in (
        (
            "spec's own design",
            s,
            "yes" if s["meets_constraints"] else "[red]no[/]: " + "; ".join(s["violated"]),
        ),
        ("[bold]optimum[/]", o, "yes"),
    ):
        peaks = (
            (_f(d["required_peak_force_N"], "{:.3f}", none="∞"), _f(d["peak_force_N"], "{:.3f}"))
            if fly
            else (_f(d["peak_force_N"], "{:.3f}"),)
        )
        t.add_row(label, *peaks, _f(d["mean_force_N"], "{:.3f}"), _f(d["transmission_deg"], "{:.2f}"), meets)
    c.print(t)
    t = Table(title="Constraints at the optimum (slack >= 0 is satisfied)", title_justify="left")
    for h in ("constraint", "slack", "binding"):
        t.add_column(h, justify="right" if h == "slack" else "left")
    for k in row["constraints"]:
        t.add_row(k["name"], f"{k['slack']:.6g} {k['unit']}", "[bold]binds[/]" if k["binding"] else "")
    c.print(t)
    if row["improvement_N"] is not None:
        c.print(
            f"{row['objective']} force "
            f"{_f(s[peak_key] if row['objective'] == 'peak' else s['mean_force_N'], '{:.2f}')} N → "
            f"{_f(o[peak_key] if row['objective'] == 'peak' else o['mean_force_N'], '{:.2f}')} N "
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
    if not o["passes_force_limit"]:
        c.print(
            "no design inside these bounds and ergonomic limits keeps the force within "
            f"{row['force_limit_N']:g} N: "
            f"the best needs {_f(o[peak_key], '{:.2f}', none='∞')} N peak; it is held back by: "
            f"{', '.join(row['binding'])}. "
            "Widen the bounds that bind (--vary), or relax --grip-height / --stroke.",
            markup=False,
        )
    verdict = "[bold green]PASS[/]" if o["passes_force_limit"] else "[bold red]FAIL[/]"
    c.print(
        f"{verdict}: optimum peak{' with the flywheel' if fly else ''} "
        f"{_f(o[peak_key], '{:.2f}', none='∞')} N "
        f"vs limit {row['force_limit_N']:g} N "
        f"({row['evaluations']} designs evaluated, {row['generations']} generations"
        f"{', polished' if row['polished'] else ''})"
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
    return [FAILURE_TEXT[f["what"]].format(label=POINT_LABELS[f["kind"]], **f) for f in records]


def json_rows(rows: list[dict]) -> list[dict]:
    """The JSON contract: name, seconds_per_position, max_rel_error_uniform,
    max_rel_error_near_dead_centre, failures (plus summary, cannot_handle and per-sampling detail,
    keyed by the words of each sampling)."""
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
    from rich.table import Table

    c = console(out)
    t = Table(
        title=f"{name}: force methods against the 50-digit reference (relative error of Fh)",
        title_justify="left",
    )
    kinds = list(rows[0]["samplings"]) if rows else []
    for h in (
        ["method", "time / position"] + [f"max err: {POINT_LABELS[k]}" for k in kinds] + ["failures / flags"]
    ):
        t.add_column(h, justify="left" if h in ("method", "failures / flags") else "right")
    for r in rows:
        cells = [r["name"], f"{r['seconds_per_position'] * 1e9:,.1f} ns"]
        for k in kinds:
            st = r["samplings"][k]
            cell = _e(st["max_rel_error"])
            if st["flagged"]:
                cell += f" ({st['flagged']}/{st['n']} flagged)"
            cells.append(cell)
        cells.append("\n".join(failure_sentences(r["failures"])) or "none")
        t.add_row(*cells)
    c.print(t)
    c.print(
        'flagged = NaN with a flag (dead centre: "∞ (dead centre)"), never a made-up number; '
        "'silently wrong' = an unflagged value off by more than the method's registered tolerance.",
        markup=False,
    )
    for r in rows:
        c.print(f"  {r['name']}: {r['summary']}; cannot handle: {r['cannot_handle']}", markup=False)

    st = Table(
        title="How many samples? Uniform sweep from crank 0° vs exact values "
        f"(dead band ±{dead_band_deg:g}°)",
        title_justify="left",
    )
    for h in (
        "N",
        "sweep max |Fh| (no band)",
        "sampled peak outside band",
        "exact peak",
        "peak error",
        "sampled mean",
        "exact mean",
        "mean error",
    ):
        st.add_column(h, justify="right")
    for s in study:
        st.add_row(
            str(s["n"]),
            f"{s['sampled_max']:.1f} N" if s["sampled_max"] is not None else "—",
            f"{s['sampled_peak']:.2f} N" if s["sampled_peak"] is not None else "—",
            f"{s['exact_peak']:.2f} N",
            _e(s["peak_error"]),
            f"{s['sampled_mean']:.4f} N",
            f"{s['exact_mean']:.4f} N",
            _e(s["mean_error"]),
        )
    c.print(st)
    c.print(
        "A sweep without a dead band reports whatever spike it lands next to (the true force is infinite at "
        "the dead centres); with the band, the exact peak is found by root-bracketing, whatever N.",
        markup=False,
    )
