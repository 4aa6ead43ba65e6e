"""Rows and rendering: results -> table (Rich) / JSON / CSV.  The only module that formats.

Degrees appear here, at the edge; the library works in radians.  NaN becomes ``null`` in JSON,
an empty cell in CSV and "∞ (dead centre)" or "—" in tables.
"""

from __future__ import annotations

import contextlib
import csv
import io
import json
import math
import sys
import time
from typing import Any, Callable, Iterable, Iterator

import numpy as np

from pumplink.analysis import Design, ForceResult, SpeedSweep

FORMATS = ("table", "json", "csv")


def num(x) -> float | None:
    """A JSON-safe float: None for NaN/inf."""
    x = float(x)
    return x if math.isfinite(x) else None


def deg(x) -> float | None:
    return num(np.degrees(x))


# ----------------------------------------------------------------------------- rows
def design_row(d: Design) -> dict[str, Any]:
    """The JSON contract of one synthesised design (issue #2)."""
    s, lk = d.synthesis, d.spec.linkage
    return {
        "name": d.spec.name,
        "feasible": d.feasible,
        "error": d.error,
        "L1": lk.L1, "D1": lk.D1, "b": lk.b, "swing_deg": lk.swing,
        "frame_length": num(s.frame_length),
        "beta_deg": deg(s.beta),
        "psi1_deg": deg(s.psi1),
        "psi2_deg": deg(s.psi2),
        "crank_length": num(s.crank_length),
        "coupler_length": num(s.coupler_length),
        "rocker_length": num(s.rocker_length),
        "handle_length": num(s.handle_length),
        "handle_stroke": num(2 * lk.handle * math.sin(math.radians(lk.swing) / 2)),
        "rocker_pivot": [num(s.pivot_x), num(s.pivot_y)],
        "dead_centres_deg": {"extended": deg(s.dead_centre_extended), "folded": deg(s.dead_centre_folded)},
        "time_ratio": num(s.time_ratio),
        "stroke_plus_x_crank_deg": deg(s.stroke_plus_x),
        "transmission_angle_deg": {"min": deg(s.transmission_min), "max": deg(s.transmission_max)},
    }


def force_summary(r: ForceResult) -> dict[str, Any]:
    """The JSON contract of a force analysis without samples (issue #2)."""
    out = design_row(r.design)
    out.update({
        "speed_deg_s": r.speed_deg_s,
        "wheel_torque_Nm": num(r.wheel_torque),
        "power_W": num(r.power),
        "force_limit_N": num(r.force_limit),
        "dead_band_deg": r.design.spec.operator.dead_band,
        "model": r.model,
        "inertia_kg_m2": None if r.inertia is None else num(r.inertia),
        "speed_fluctuation": r.speed_fluctuation,
        "energy_band_J": None if r.energy_band is None else num(r.energy_band),
        "required_peak_force_N": None if r.required_peak_force is None else num(r.required_peak_force),
        "min_passing_speed_deg_s": None if r.min_passing_speed is None else deg(r.min_passing_speed),
        "wheel_speed_range_deg_s": _speed_range(r),
        "link_kinetic_energy_J": num(r.link_energy),
        "mean_force_N": num(r.mean_force),
        "peak_force_N": num(r.peak_force),
        "peak_force_infinite": bool(r.peak_force == math.inf),  # dead_band = 0: the window reaches a dead centre
        "peak_crank_deg": deg(r.peak_angle),
        "sampled_peak_force_N": num(r.sampled_peak),
        "samples_n": r.samples_n,
        "pass": r.passed,
        "checks": [{"name": c.name, "value": num(c.value), "limit": c.limit, "relation": c.relation,
                    "unit": c.unit, "severity": c.severity, "pass": c.passed} for c in r.checks],
    })
    return out


def _speed_range(r: ForceResult):
    sc = r.scene
    if sc is None or not math.isfinite(sc.peak_force):
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
        "wheel_speed_deg_s": np.degrees(np.broadcast_to(r.speed if r.wheel_speed is None else r.wheel_speed,
                                                        s.force.shape)),
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


# ----------------------------------------------------------------------------- progress
@contextlib.contextmanager
def progress(total: int, label: str = "batch", enabled: bool | None = None,
             delay: float = 1.0) -> Iterator[Callable[[int], None]]:
    """``advance(n)`` for a Rich progress bar on stderr, shown only on a terminal and only once
    the run has taken longer than ``delay`` seconds."""
    if enabled is None:
        enabled = sys.stderr.isatty()
    state: dict[str, Any] = {"done": 0, "bar": None, "t0": time.monotonic()}

    def advance(n: int) -> None:
        state["done"] += n
        if not enabled:
            return
        if state["bar"] is None and time.monotonic() - state["t0"] > delay:
            from rich.console import Console
            from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeRemainingColumn

            bar = Progress(TextColumn(label), BarColumn(), MofNCompleteColumn(), TimeRemainingColumn(),
                           console=Console(stderr=True), transient=True)
            bar.start()
            state["bar"], state["task"] = bar, bar.add_task(label, total=total)
        if state["bar"] is not None:
            state["bar"].update(state["task"], completed=state["done"])

    try:
        yield advance
    finally:
        if state["bar"] is not None:
            state["bar"].stop()


# ----------------------------------------------------------------------------- text output
def _json(obj, out) -> None:
    # ASCII JSON (\u escapes): valid whatever the terminal's or pipe's encoding.
    out.write(json.dumps(obj, indent=2, allow_nan=False) + "\n")


def _flatten(row: dict[str, Any], prefix: str = "") -> dict[str, Any]:
    flat: dict[str, Any] = {}
    for k, v in row.items():
        if isinstance(v, dict):
            flat.update(_flatten(v, f"{prefix}{k}_"))
        elif isinstance(v, list) and k == "rocker_pivot":
            flat[f"{prefix}rocker_pivot_x"], flat[f"{prefix}rocker_pivot_y"] = v
        elif isinstance(v, list):
            continue  # checks: in JSON and the table only
        else:
            flat[prefix + k] = "" if v is None else v
    return flat


def write_csv(rows: Iterable[dict[str, Any]], out) -> None:
    """CSV with a header from the first row; nested keys flattened with '_'."""
    rows = [_flatten(r) for r in rows]
    if not rows:
        return
    w = csv.DictWriter(out, fieldnames=list(rows[0]), lineterminator="\n")
    w.writeheader()
    w.writerows(rows)


def console(file=None):
    """A Rich console: colour only on a terminal (and never with NO_COLOR), wide when piped."""
    from rich.console import Console

    file = file or sys.stdout
    tty = hasattr(file, "isatty") and file.isatty()
    return Console(file=file, highlight=False, width=None if tty else 200, soft_wrap=False)


def _f(x, fmt="{:.3f}", none="—") -> str:
    return none if x is None or not math.isfinite(float(x)) else fmt.format(float(x))


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

    t = Table(title="Dead-centre synthesis, Eq. (1)–(2) of the pump paper", title_justify="left",
              caption="lengths \\[m], angles \\[deg]; l1 frame, l2 crank, l3 coupler, l4 rocker, H handle, Δθ swing, "
                      "K time ratio, γ transmission angle, DC crank angle of the extended / folded dead centre",
              caption_justify="left")
    for h in ("design", "L1", "D1", "b", "l4", "H", "Δθ", "l1", "β", "l2", "l3", "K", "γ min", "γ max",
              "DC ext", "DC fold", "feasible"):
        t.add_column(h, justify="left" if h in ("design", "feasible") else "right", no_wrap=h == "design")
    notes = []
    for d, r in zip(designs, rows):
        ok = "[green]yes[/]" if r["feasible"] else f"[red]no ({len(notes) + 1})[/]"
        if not r["feasible"]:
            notes.append(f"({len(notes) + 1}) {r['name']}: {r['error']}.")  # printed with markup=False
        lk = d.spec.linkage
        tr, dc = r["transmission_angle_deg"], r["dead_centres_deg"]
        t.add_row(escape(r["name"]), _f(lk.L1), _f(lk.D1), _f(lk.b), _f(lk.rocker), _f(lk.handle), _f(lk.swing, "{:.1f}"),
                  _f(r["frame_length"], "{:.4f}"), _f(r["beta_deg"], "{:.2f}"),
                  _f(r["crank_length"], "{:.4f}"), _f(r["coupler_length"], "{:.4f}"), _f(r["time_ratio"], "{:.4f}"),
                  _f(tr["min"], "{:.1f}"), _f(tr["max"], "{:.1f}"), _f(dc["extended"], "{:.2f}"),
                  _f(dc["folded"], "{:.2f}"), ok)
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
    """Which model decided the verdict, in words (issue #6)."""
    if r.flywheel:
        return (f"model: flywheel, J = {r.inertia:.3f} kg·m², δ ≤ {r.speed_fluctuation:g} at a mean "
                f"{r.speed_deg_s:g} deg/s (energy band W = J·ω̄²·δ = {r.energy_band:.2f} J); links' inertia neglected")
    return ("model: quasi-static + dead band (the wheel's inertia is assumed to carry the linkage "
            f"through ±{r.design.spec.operator.dead_band:g}° of each dead centre; give wheel.mass or "
            "wheel.inertia to let the speed decide)")


def render_force(r: ForceResult, fmt: str, summary: bool = False, out=None, extra: dict | None = None) -> None:
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
    c.print(f"[bold]{name}[/]  crank l2 = {d['crank_length']:.4f} m, coupler l3 = {d['coupler_length']:.4f} m, "
            f"rocker l4 = {d['rocker_length']:.4f} m, frame l1 = {d['frame_length']:.4f} m, handle H = {d['handle_length']:.3f} m")
    c.print(f"dead centres at crank {dc['extended']:.2f}° (extended) and {dc['folded']:.2f}° (folded); "
            f"time ratio K = {d['time_ratio']:.4f}; wheel torque Mw = {r.wheel_torque:.3f} N·m at "
            f"{r.speed_deg_s:g} deg/s ({r.power:.1f} W)")
    fly = r.flywheel and r.operator_force is not None

    if not summary and r.samples is not None and r.samples.crank_angle.size:
        s = r.samples
        kind = "flywheel scene: the operator's force and the wheel speed" if fly else "quasi-static"
        t = Table(title=f"Operator force over the crank cycle ({kind}, {r.samples_n} samples"
                        f"{', condensed' if s.crank_angle.size > 28 else ''})", title_justify="left")
        heads = ["crank θ2 [deg]", "quasi-static Fh [N]"]
        heads += ["operator F [N]", f"|F| vs {r.force_limit:g} N", "wheel ω [deg/s]"] if fly else [f"|Fh| vs {r.force_limit:g} N"]
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
            rows.append((float(st.crank_angle[i]) % (2 * math.pi), _f(np.degrees(st.crank_angle[i]) % 360, "{:.2f}"),
                         qs, *mid, _f(speed, "{:.3f}"),
                         _f(np.degrees(st.rocker_angle[i]) - 90, "{:+.1f}"), _f(np.degrees(st.rocker_angle[i]), "{:.1f}"),
                         _f(np.degrees(st.transmission_angle[i]), "{:.1f}"), note))

        for i in _condensed_indices(r):
            if s.singular[i]:
                note = "[bold]dead centre[/]"
            elif fly:
                note = "[dim]wheel at top speed[/]" if _on_ceiling(r, s.crank_angle[i]) else ""
            else:
                note = "[dim]in dead band[/]" if r.in_dead_band[i] else ""
            add(s, i, hs[i], note, *((r.operator_force[i], r.wheel_speed[i]) if fly else ()))
        if s.crank_angle.size > 28 and r.marks is not None:  # mark the dead centres and the exact peak
            m = r.marks
            if fly:
                from pumplink import flywheel as _fw

                ws = _fw.wheel_speed(r.scene, m.crank_angle)
                ops = _fw.operator_force(r.scene, m.crank_angle)
                labels = ("dead centre (extended)", "dead centre (folded)")
                speeds = np.abs(m.rocker_rate) * ws * r.design.spec.linkage.handle
                for i, label in enumerate(labels):
                    add(m, i, 0.0 if m.singular[i] else speeds[i], f"[bold]{label}[/]", ops[i], ws[i])
            else:
                speeds = np.abs(m.rocker_rate) * r.speed * r.design.spec.linkage.handle
                for i, label in enumerate(("dead centre (extended)", "dead centre (folded)", "exact peak outside dead band")):
                    add(m, i, 0.0 if m.singular[i] else speeds[i], f"[bold]{label}[/]")
        for row in sorted(rows, key=lambda x: x[0] % (2 * math.pi)):
            t.add_row(*row[1:])
        c.print(t)

    ct = Table(title="Checks", title_justify="left")
    for h in ("check", "value", "limit", "result"):
        ct.add_column(h, justify="right" if h in ("value", "limit") else "left")
    if r.flywheel:
        ct.add_row(f"quasi-static peak outside ±{r.design.spec.operator.dead_band:g}° (dead-band model, for comparison)",
                   f"{_f(r.peak_force, '{:.2f}', '∞')} N", "", "[dim]info[/]")
        mps = r.min_passing_speed
        ct.add_row("least mean wheel speed that passes the limit", "never" if mps == math.inf else
                   f"{_f(np.degrees(mps), '{:.1f}')} deg/s", f"at {r.force_limit:g} N", "[dim]info[/]")
    else:
        ct.add_row("sampled peak outside dead band (for comparison)", f"{_f(r.sampled_peak, '{:.2f}')} N",
                   f"{r.samples_n} samples", "[dim]info[/]")
    for ch in r.checks:
        res = "[green]pass[/]" if ch.passed else ("[red]FAIL[/]" if ch.severity == "fail" else "[yellow]warning[/]")
        unit = f" {ch.unit}" if ch.unit else ""
        ct.add_row(escape(ch.name), f"{_f(ch.value, '{:.2f}', '∞') if ch.value != np.inf else '∞'}{unit}",
                   f"{ch.relation} {ch.limit:g}{unit}", res)
    c.print(ct)
    c.print(model_line(r))
    warned = [ch for ch in r.checks if ch.severity == "warn" and not ch.passed]
    peak = r.required_peak_force if r.flywheel else r.peak_force
    how = " with the flywheel" if r.flywheel else ""
    if r.passed:
        note = f" ({len(warned)} warning{'s' if len(warned) > 1 else ''} below)" if warned else ""
        c.print(f"[bold green]VERDICT: PASS[/] — mean {r.mean_force:.1f} N and peak {peak:.1f} N{how} are within "
                f"the {r.force_limit:g} N limit{note}")
    else:
        bad = [ch.name for ch in r.checks if ch.severity == "fail" and not ch.passed]
        hint = ""
        if r.flywheel and r.min_passing_speed is not None and math.isfinite(r.min_passing_speed):
            hint = f"; it passes from a mean {np.degrees(r.min_passing_speed):.0f} deg/s (see: pumplink speed)"
        c.print(f"[bold red]VERDICT: FAIL[/] — {', '.join(bad)} above the {r.force_limit:g} N limit "
                f"(mean {r.mean_force:.1f} N, peak {_f(peak, '{:.1f}', '∞')} N{how}){hint}")
    for ch in warned:
        if ch.unit == "%":
            c.print(f"[yellow]warning:[/] the links' kinetic energy is {ch.value:.0f} % of the energy band (> "
                    f"{ch.limit:g} %): the flywheel model neglects it, so treat the verdict as an estimate "
                    "(a lighter handle or a heavier wheel; see --explain)")
            continue
        c.print(f"[yellow]warning:[/] {escape(ch.name)} is {ch.value:.2f} {ch.unit}, outside {ch.relation} {ch.limit:g} {ch.unit}"
                + (" (a person sustains ~75 W for hours; slow the wheel or lower the load)" if ch.unit == "W" else "")
                + (" (pressure angle above 45°: the coupler pushes the crank at a poor angle and the joints wear)" if ch.unit == "deg" else ""))


def _on_ceiling(r: ForceResult, angle) -> bool:
    from pumplink import flywheel as _fw

    return bool(_fw.on_ceiling(r.scene, angle))


# ----------------------------------------------------------------------------- model choice, verification, speed
def explain_rows(effects) -> list[dict[str, Any]]:
    """The model-choice report as rows (JSON/CSV)."""
    return [{"effect": e.name, "included": e.included, "value": num(e.value), "unit": e.unit,
             "compared_with": e.compared_with, "ratio": num(e.ratio), "note": e.note} for e in effects]


def render_explain(effects, why: str, out=None) -> None:
    """`pumplink force --explain` (table output): the effects table and the reason."""
    from rich.markup import escape
    from rich.table import Table

    c = console(out or sys.stdout)
    t = Table(title="Model choice: what is in the model, and how big it is at this speed", title_justify="left")
    for h in ("effect", "in model", "size", "compared with", "ratio", "note"):
        t.add_column(h, justify="right" if h in ("size", "ratio") else "left")
    for e in effects:
        inc = "[green]yes[/]" if e.included else "[dim]neglected[/]"
        ratio = "" if not math.isfinite(e.ratio) else (f"{e.ratio:.0%}" if e.ratio < 10 else f"{e.ratio:.1f}×")
        t.add_row(escape(e.name), inc, f"{_f(e.value, '{:.3g}', '∞')} {e.unit}", escape(e.compared_with), ratio,
                  escape(e.note))
    c.print(t)
    c.print(why, markup=False)


def verify_row(sim, r: ForceResult) -> dict[str, Any]:
    """The solve_ivp cross-check as a row: what it measured and whether it agrees."""
    tol = VERIFY_RTOL
    agree = (sim.periodicity <= tol and abs(sim.mean_speed - r.speed) <= tol * r.speed
             and sim.fluctuation <= r.speed_fluctuation * (1 + tol))
    return {"method": "scipy solve_ivp (DOP853, rtol 1e-11), open-loop force profile F(θ2)",
            "cycles": sim.cycles, "periodicity": num(sim.periodicity),
            "mean_speed_deg_s": deg(sim.mean_speed), "time_mean_speed_deg_s": deg(sim.time_mean_speed),
            "speed_range_deg_s": {"min": deg(sim.min_speed), "max": deg(sim.max_speed)},
            "fluctuation": num(sim.fluctuation), "tolerance": tol, "agrees": bool(agree)}


#: Relative agreement the --verify cross-check demands (periodicity, mean speed, fluctuation).
VERIFY_RTOL = 1e-6


def render_verify(row: dict[str, Any], out=None) -> None:
    c = console(out or sys.stdout)
    ok = "[bold green]agrees[/]" if row["agrees"] else "[bold red]DISAGREES[/]"
    c.print(f"verify ({row['method']}, {row['cycles']} revolutions): {ok} — periodic to {row['periodicity']:.1e}, "
            f"mean speed (max+min)/2 = {row['mean_speed_deg_s']:.4f} deg/s, fluctuation δ = {row['fluctuation']:.6f}, "
            f"wheel {row['speed_range_deg_s']['min']:.1f}–{row['speed_range_deg_s']['max']:.1f} deg/s "
            f"(time-averaged {row['time_mean_speed_deg_s']:.1f} deg/s)")


def speed_rows(sw: SpeedSweep) -> list[dict[str, Any]]:
    return [{"speed_deg_s": float(w), "energy_band_J": num(b), "required_peak_force_N": num(f),
             "power_W": num(p), "pass": bool(ok)}
            for w, b, f, p, ok in zip(sw.speed_deg_s, sw.energy_band, sw.required_peak_force, sw.power, sw.passed)]


def speed_summary(sw: SpeedSweep) -> dict[str, Any]:
    out = design_row(sw.design)
    out.update({"model": "flywheel", "inertia_kg_m2": num(sw.inertia), "speed_fluctuation": sw.speed_fluctuation,
                "force_limit_N": num(sw.force_limit), "mean_force_N": num(sw.mean_force),
                "quasi_static_peak_force_N": num(sw.quasi_static_peak),
                "min_passing_speed_deg_s": deg(sw.min_passing_speed)})
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
    t = Table(title=f"{escape(sw.design.spec.name)}: least peak operator force against mean wheel speed (flywheel, "
                    f"J = {sw.inertia:.3f} kg·m², δ ≤ {sw.speed_fluctuation:g})", title_justify="left")
    for h in ("speed [deg/s]", "rpm", "band W [J]", "peak force [N]", f"vs {sw.force_limit:g} N", "power [W]", "result"):
        t.add_column(escape(h), justify="left" if h.startswith(("vs", "result")) else "right")
    for r in rows:
        f = r["required_peak_force_N"]
        t.add_row(f"{r['speed_deg_s']:g}", f"{r['speed_deg_s'] / 6:.0f}", _f(r["energy_band_J"], "{:.2f}"),
                  _f(f, "{:.1f}", "∞"), _bar(f, sw.force_limit), _f(r["power_W"], "{:.0f}"),
                  "[green]pass[/]" if r["pass"] else "[red]FAIL[/]")
    c.print(t)
    mps = sw.min_passing_speed
    c.print(f"mean force {sw.mean_force:.1f} N (the floor: an infinite flywheel); quasi-static peak outside the dead "
            f"band {sw.quasi_static_peak:.1f} N (the dead-band model, blind to speed)")
    if math.isfinite(mps):
        c.print(f"[bold]passes the {sw.force_limit:g} N limit from a mean {np.degrees(mps):.1f} deg/s "
                f"({np.degrees(mps) / 6:.0f} rpm)[/]")
    else:
        c.print(f"[bold red]no speed passes[/]: the mean force {sw.mean_force:.1f} N is above the {sw.force_limit:g} N limit")
