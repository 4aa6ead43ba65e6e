"""`pumplink force`: the sweep, the checks and the verdict; the model-choice report (``--explain``)
and the independent check (``--verify``); the JSON contract of a force result.

Renderers only render: every number comes from the library's results.
"""

from __future__ import annotations

import math
import sys
from collections.abc import Iterator
from typing import TYPE_CHECKING, Any

import numpy as np

from pumplink.output.formats import console, deg, num, render
from pumplink.output.formats import fmt as _f
from pumplink.output.precision import known_text, known_to, residual, shown

if TYPE_CHECKING:
    from pumplink.studies.force import ForceResult
from pumplink.output.speed import cadence_lines
from pumplink.output.synth import design_row
from pumplink.output.words import (
    CHECK_ADVICE,
    RESULT_MARKUP,
    advice_row,
    advice_sentence,
    check_label,
    check_row,
    check_sentence,
    check_value,
    limit_text,
    losses_word,
    model_line,
    pit_words,
    verdict_line,
    water_lines,
)
from pumplink.quantities import json_items
from pumplink.quantities import lines as quantity_lines


def force_summary(r: ForceResult) -> dict[str, Any]:
    """The JSON contract of a force analysis without samples: the design, then every quantity of
    the catalogue (:data:`pumplink.quantities.CATALOGUE`) that force's JSON holds, then the
    verdict and its checks."""
    out = design_row(r.design)
    out.update(
        {
            "speed_deg_s": r.speed_deg_s,
            "operator_profile": r.profile,
            "dead_band_deg": r.design.spec.operator.dead_band,
            "model": r.model,
            "losses": losses_word(r.water),
            **{k: shown(q, v) for k, (q, v) in json_items(r.evaluation).items()},
            # the sampled peak of the angles this study kept (--at), else the evaluation's sweep
            "sampled_peak_force_N": num(r.sampled_peak),
            "samples_n": r.samples_n,
            "wheel_speed_range_deg_s": _speed_range(r),
            "peak_force_infinite": bool(r.verdict_peak_force == math.inf),
            "verdict": r.outcome,
            "pass": r.passed,
            "checks": [check_row(c, r) for c in r.checks],
        }
    )
    return out


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


#: Eighths of a cell, for a bar's last partial cell.
_EIGHTHS = ("", "▏", "▎", "▍", "▌", "▋", "▊", "▉")


def _bar(value, limit, width=12) -> str:
    """A force as a bar of ``width`` cells that is full at 1.5x ``limit``: solid up to the limit in
    eighths of a cell, then a lighter block for each cell past it (at least one, so that a force
    over the limit reads as such without colour), an arrow at the end when full; arrows
    throughout for an infinite force.  ``width`` is a multiple of 3, so the limit falls on a cell
    boundary."""
    if value is None or not math.isfinite(value):
        return "[red]" + "▶" * width + "[/]"
    at_limit = width * 2 // 3  # cells up to the limit
    v = abs(value)
    if v <= limit:
        eighths = round(v / (1.5 * limit) * width * 8)
        mark = "█" * (eighths // 8) + _EIGHTHS[eighths % 8]
        return f"[green]{mark}[/]"
    past = round((v - limit) / (1.5 * limit) * width)
    if v >= 1.5 * limit or at_limit + past >= width:
        mark = "█" * at_limit + "▒" * (width - at_limit - 1) + "▶"
    else:
        mark = "█" * at_limit + "▒" * max(1, past)
    return f"[red]{mark}[/]"


def _condensed_indices(r: ForceResult, max_rows: int = 24) -> list[int]:
    n = r.samples.crank_angle.size
    if n <= max_rows + 4:
        return list(range(n))
    return sorted(set(np.linspace(0, n - 1, max_rows).round().astype(int).tolist()))


def render_force(
    r: ForceResult,
    fmt: str,
    summary: bool = False,
    out=None,
    extra: dict | None = None,
    strict: bool = False,
    advice=(),
    cadence=None,
) -> None:
    """`pumplink force`: sweep table (condensed), checks and the verdict.

    ``extra`` (JSON only): more top-level keys, e.g. ``explain`` and ``verify``.  ``strict``:
    warnings fail (``--strict``).  ``advice``: :class:`pumplink.studies.advice.Suggestion` records,
    printed after a FAIL (and in JSON as ``advice``).
    """
    out = out or sys.stdout

    def as_json():
        obj = force_summary(r)
        obj["strict"] = strict
        obj["advice"] = [advice_row(a) for a in advice]
        obj.update(extra or {})
        return obj

    def as_csv():
        return [force_summary(r)] if summary or r.samples is None else iter_sample_rows(r)

    def stream():  # the samples streamed: a million must not be a million dicts at once
        return None if summary else ("samples", iter_sample_rows(r))

    def table() -> None:
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
            kind = "full dynamics" if r.dynamics else "flywheel" if fly else "quasi-static"
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
                + "; bar: █ up to the limit, ▒ past it, full at 1.5× it; v grip speed; "
                "φ handle from vertical; γ transmission angle",
                caption_justify="left",
                box=box.SIMPLE_HEAD,
                pad_edge=False,
            )
            heads = ["θ2 [°]", "Fh [N]"]
            heads += (
                ["F [N]", f"|F| vs {r.force_limit:g} N", "ω [°/s]"]
                if fly
                else [f"|Fh| vs {r.force_limit:g} N"]
            )
            heads += ["v [m/s]", "φ [°]", "γ [°]", "note"]
            bar = 6 if fly else 12  # cells (a multiple of 3: the limit on a cell boundary)
            for h in heads:
                is_bar = h.startswith("|")
                t.add_column(
                    escape(h),
                    justify="left" if is_bar or h == "note" else "right",
                    no_wrap=h == "note",
                    min_width=bar if is_bar else None,  # a bar is never folded or cropped
                )
            rows = []
            hs = r.handle_speed

            def add(st, i, speed, note, op=None, w=None):
                f = st.force[i]
                qs = "∞" if st.singular[i] else _f(f, "{:+.1f}")
                if fly:
                    mid = [_f(op, "{:+.1f}"), _bar(op, r.force_limit, bar), _f(np.degrees(w), "{:.1f}")]
                else:
                    mid = [_bar(None if st.singular[i] else float(f), r.force_limit, bar)]
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
                limit_text(ch, ch.warn_limit),
                limit_text(ch, ch.fail_limit),
                RESULT_MARKUP[ch.result],
            )
        c.print(ct)
        c.print(model_line(r))
        use = r.design.spec.use
        for line in water_lines(r.water, r.power, r.profile, use.hours_per_day, use.litres_per_person_day):
            c.print(line, markup=False)
        for line in quantity_lines(r.evaluation):  # the catalogue's quantities with a line of their own
            c.print(line, markup=False)
        if pit_words(r.design.spec):
            c.print(pit_words(r.design.spec), markup=False)
        c.print(verdict_line(r, strict, cadence))
        for ch in r.checks:
            if ch.result == "warn":
                c.print(f"[yellow]warning:[/] {escape(check_sentence(ch, r))}")
            elif ch.result == "fail" and ch.key in CHECK_ADVICE:
                c.print(f"[red]fails:[/] {escape(check_sentence(ch, r))}")
        if advice:
            c.print("[bold]what would help most[/] (one change at a time, everything else as in the spec):")
            for a in advice:
                c.print(f"  {escape(advice_sentence(a))}")

    render(fmt, out, as_json=as_json, as_csv=as_csv, table=table, stream=stream)


def render_study(st, fmt: str, summary: bool = False, strict: bool = False, out=None) -> None:
    """`pumplink force`: a :class:`pumplink.studies.design.DesignStudy` rendered: the force result
    (:func:`render_force`), then, in a table, the model-choice report, the workshop's view, the
    independent check and the released handle (on standard error beside CSV; in JSON as keys)."""
    from pumplink.output.speed import cadence_row
    from pumplink.output.workshop import release_line, release_row, render_workshop, workshop_row

    r = st.result
    # every key docs/json.md lists is in the JSON: null where it has no value (an infeasible design
    # has nothing to explain, verify or release)
    extra = {**({"explain": None} if st.explained else {}), **({"verify": None} if st.verified else {})}
    if st.why is not None:
        extra["explain"] = {
            "model": r.model,
            "effects": explain_rows(st.effects),
            "why": st.why,
            "best_cadence": None if st.cadence is None else cadence_row(st.cadence),
            "workshop": workshop_row(st.workshop),
        }
    if st.check is not None:
        extra["verify"] = (verify_row if hasattr(st.check, "integration") else static_verify_row)(st.check)
    if st.nothing_to_verify:
        sys.stderr.write(
            f"verify: nothing to integrate; no finite peak force keeps the wheel turning "
            f"(energy band J·ω̄²·δ = {r.energy_band:.3g} J)\n"
        )
    extra["release"] = release_row(st.release)
    render_force(r, fmt, summary=summary, extra=extra, strict=strict, advice=st.advice,
                 cadence=st.cadence, out=out)  # fmt: skip
    if fmt == "json":
        return
    side = out or (sys.stdout if fmt == "table" else sys.stderr)  # beside CSV: on standard error
    if st.why is not None:
        render_explain(st.effects, st.why, out=side, cadence=st.cadence, force_limit=r.force_limit)
        render_workshop(st.workshop, out=side, service=_service(r))
    if extra.get("verify") is not None:
        render_verify(extra["verify"], out=side)
    if st.release is not None and st.why is None:  # (else in the workshop's report)
        console(side).print(release_line(st.release, _service(r)), markup=False)


def _service(r: ForceResult):
    """The design's :class:`pumplink.evaluate.service.Service` (None where it was not evaluated)."""
    sv = None if r.evaluation is None else r.evaluation.service
    return None if sv is None else sv.design(0)


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


def _effect_head(name: str) -> str:
    """The words of an effect's name before its first qualifier (' (...)' or ', ...'): what the
    model-choice table shows; the whole name is in the numbered line under it."""
    cut = min((i for i in (name.find(" ("), name.find(", ")) if i > 0), default=len(name))
    return name[:cut]


def render_explain(effects, why: str, out=None, cadence=None, force_limit: float = 0.0) -> None:
    """`pumplink force --explain` (table output): the effects table, the reason, and the best
    cadence (:class:`pumplink.studies.speed.Cadence`, when the spec gives inertia).

    The table (one line an effect, to fit 80 columns) gives each effect's short name, whether
    the model includes it, its size and its share of what it is compared with; the numbered
    lines under it give the whole name, what the share is of, and the note."""
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
    for h in ("effect", "in model", "size", "share"):
        t.add_column(h, justify="right" if h in ("size", "share") else "left", no_wrap=True)
    notes = []
    for i, e in enumerate(effects, 1):
        inc = "[green]yes[/]" if e.included else "[dim]neglected[/]"
        ratio = (
            "" if not math.isfinite(e.ratio) else (f"{e.ratio:.0%}" if e.ratio < 10 else f"{e.ratio:.1f}×")
        )
        size = f"{_f(e.value, '{:.3g}', '∞')} {e.unit}"
        t.add_row(f"{i}. {escape(_effect_head(e.name))}", inc, size, ratio)
        share = f"{ratio} {e.compared_with}; " if ratio else ""
        notes.append(f"{i}. {e.name}: {share}{e.note}")
    c.print(t)
    for n in notes:
        c.print(n, markup=False)
    c.print(why, markup=False)
    if cadence is not None:
        for line in cadence_lines(cadence, force_limit):
            c.print(line, markup=False)


#: The keys only one model's cross-check fills: null in the other's row (docs/json.md: every key
#: in every result).
_MOTION_KEYS = (
    "cycles",
    "periodicity",
    "mean_speed_deg_s",
    "time_mean_speed_deg_s",
    "speed_range_deg_s",
    "fluctuation",
)
_STATIC_KEYS = ("angles", "virtual_work", "samples", "sweep_peak_force_N", "peak_force_N")


def verify_row(v) -> dict[str, Any]:
    """The solve_ivp cross-check (:class:`pumplink.studies.verify.Verification`) as a row."""
    sim, tol = v.integration, v.tolerance

    def known(x):  # an integration in time from the reported motion: settled to the check's tolerance
        return known_to(x, tol)

    return {
        "method": "scipy solve_ivp (DOP853, rtol 1e-11), open-loop force profile F(θ2)",
        "cycles": sim.cycles,
        "periodicity": residual(sim.periodicity, tol),
        "mean_speed_deg_s": known(deg(sim.mean_speed)),
        "time_mean_speed_deg_s": known(deg(sim.time_mean_speed)),
        "speed_range_deg_s": {"min": known(deg(sim.min_speed)), "max": known(deg(sim.max_speed))},
        "fluctuation": known(sim.fluctuation),
        **dict.fromkeys(_STATIC_KEYS),
        "tolerance": tol,
        "agrees": v.agrees,
    }


def static_verify_row(v) -> dict[str, Any]:
    """The quasi-static cross-check (:class:`pumplink.studies.verify.StaticCheck`) as a row."""
    return {
        "method": "virtual work from positions (central differences) and a dense sweep",
        "angles": v.angles,
        "virtual_work": residual(v.virtual_work, v.tolerance),
        "samples": v.samples,
        "sweep_peak_force_N": num(v.sweep_peak),
        "peak_force_N": num(v.peak),
        **dict.fromkeys(_MOTION_KEYS),
        "tolerance": v.tolerance,
        "agrees": v.agrees,
    }


def render_verify(row: dict[str, Any], out=None) -> None:
    c = console(out or sys.stdout)
    if row["cycles"] is None:  # the quasi-static model
        ok = "[bold green]agrees[/]" if row["agrees"] else "[bold red]DISAGREES[/]"
        c.print(
            f"verify (quasi-static: {row['method']}): {ok} — F·dPx/dθ2 = Mw "
            f"{_within(row['virtual_work'], row['tolerance'])} "
            f"at {row['angles']} crank angles; {row['samples']:,} samples outside the dead bands peak at "
            f"{row['sweep_peak_force_N']:.3f} N, the exact peak {row['peak_force_N']:.3f} N"
        )
        return
    ok = "[bold green]agrees[/]" if row["agrees"] else "[bold red]DISAGREES[/]"
    c.print(
        f"verify ({row['method']}, {row['cycles']} revolutions): {ok} — "
        f"periodic {_within(row['periodicity'], row['tolerance'])}, "
        f"mean speed (max+min)/2 = {known_text(row['mean_speed_deg_s'], row['tolerance'])} deg/s, "
        f"fluctuation δ = {known_text(row['fluctuation'], row['tolerance'])}, "
        f"wheel {row['speed_range_deg_s']['min']:.1f}–{row['speed_range_deg_s']['max']:.1f} deg/s "
        f"(time-averaged {row['time_mean_speed_deg_s']:.1f} deg/s)"
    )


def _within(value: float, tolerance: float) -> str:
    """A checked residual in words: 'to within 1e-06' where it is 0 (at or below the tolerance,
    :func:`pumplink.output.precision.residual`), else 'to 3.2e-05'."""
    return f"to within {tolerance:g}" if value == 0 else f"to {value:.1e}"
