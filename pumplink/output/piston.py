"""Rows and tables of the piston-pump spec under ``pumplink force`` and ``pumplink batch``.

Renderers only: every number comes from :func:`pumplink.studies.piston.force_analysis`.  Degrees here
only; tables fit 80 columns.
"""

from __future__ import annotations

import json
import math
import sys
from typing import Any

import numpy as np

from pumplink.constants import EXTREMUM_ARGUMENT
from pumplink.output.formats import console, deg, num, render
from pumplink.output.formats import fmt as _f
from pumplink.output.precision import known_to
from pumplink.output.words import WATER_KEYS, water_lines, water_row
from pumplink.output.words import check_row as verdict_check_row

#: Rows of the condensed sweep in the table (every k-th sample).
TABLE_ROWS = 24

_CHECK_LABELS = {
    "mean_force": "mean force at the handle",
    "peak_force": "peak force at the handle",
    "power": "operator power (sustained)",
}


def _checks(r) -> list[dict[str, Any]]:
    """The verdict's checks in the rope pump's JSON shape (``pumplink.output.words.check_row``)."""
    checks = r.verdict.checks if r.verdict is not None else ()
    return [verdict_check_row(c, name=_CHECK_LABELS.get(c.key, c.key)) for c in checks]


def summary_row(r) -> dict[str, Any]:
    """JSON contract of the piston-pump summary (``force --summary``, a batch row)."""
    s = r.spec
    cr = s.crank_slider
    lo, hi = r.pressure_permissible_deg
    return {
        "name": s.name,
        "mechanism": s.mechanism,
        "feasible": r.feasible,
        "error": r.error,
        "crank_m": cr.crank,
        "rod_m": cr.rod,
        "offset_m": cr.offset,
        "handle_m": s.operator.handle,
        "bore_m": s.piston.bore,
        "head_m": s.piston.head,
        "load_force_N": num(r.load_force),
        "stroke_m": num(r.stroke),
        "time_ratio": num(r.time_ratio),
        "largest_pressure_angle_deg": deg(r.largest_pressure_angle),
        "permissible_pressure_angle_deg": [lo, hi],
        "speed_deg_s": r.speed_deg_s,
        "power_W": num(r.power),
        **water_row(r.water),
        "mean_force_N": num(r.mean_force),
        "quasi_static_peak_N": num(r.quasi_static_peak),
        "quasi_static_peak_angle_deg": known_to(deg(r.quasi_static_peak_angle), EXTREMUM_ARGUMENT),
        "model": r.model,
        "inertia_kg_m2": None if r.inertia is None else num(r.inertia),
        "energy_band_J": None if r.energy_band is None else num(r.energy_band),
        "least_peak_force_N": None if r.least_peak_force is None else num(r.least_peak_force),
        "force_limit_N": r.force_limit,
        "verdict": r.verdict.outcome if r.verdict is not None else "FAIL",
        "pass": r.passed,
        "checks": _checks(r),
    }


def sample_rows(r) -> list[dict[str, Any]]:
    """One row per swept crank angle."""
    return [
        {
            "crank_angle_deg": deg(t),
            "slider_position_m": num(s),
            "velocity_ratio_m_per_rad": num(v),
            "crank_torque_Nm": num(q),
            "operator_force_N": num(f),
            "pressure_angle_deg": deg(p),
        }
        for t, s, v, q, f, p in zip(
            r.samples,
            r.slider_position,
            r.velocity_ratio,
            r.crank_torque,
            r.operator_force,
            r.pressure_angle,
            strict=True,
        )
    ]


def _verdict_line(row) -> str:
    if not row["feasible"]:
        return f"VERDICT: FAIL — infeasible: {row['error']}"
    peak = row["least_peak_force_N"] if row["least_peak_force_N"] is not None else row["quasi_static_peak_N"]
    limit = row["force_limit_N"]
    if row["pass"]:
        mean = row["mean_force_N"]
        return f"VERDICT: PASS — mean {mean:.1f} N and peak {peak:.1f} N are within the {limit:g} N limit"
    over = [f"{w} {v:.1f} N" for w, v in (("mean", row["mean_force_N"]), ("peak", peak)) if v > limit]
    return f"VERDICT: FAIL — {' and '.join(over)} above the {limit:g} N limit"


def check_row(check) -> dict[str, Any]:
    """The dense-sweep check of a piston pump (:class:`pumplink.studies.piston.PistonCheck`) as JSON."""
    return {
        "method": "trapezoid rule and a dense sweep",
        "samples": check.samples,
        "work": num(check.work),
        "sweep_peak_force_N": num(check.sweep_peak),
        "peak_force_N": num(check.peak),
        "deficit_over_band": None if check.deficit is None else num(check.deficit),
        "tolerance": check.tolerance,
        "agrees": check.agrees,
    }


def render_checks(r, why: str | None, check, out=None) -> None:
    """``--explain`` and ``--verify`` of a piston pump in words (after the table; stderr with CSV)."""
    if why is None and check is None:
        return
    c = console(out or sys.stdout)
    if why is not None:
        c.print(why, markup=False)
    if check is not None:
        fly = (
            f"; the largest energy lost over an arc at Fp* is {check.deficit:.6f} of the band W"
            if check.deficit is not None
            else ""
        )
        c.print(
            f"verify ({check.samples:,} crank angles): {'agrees' if check.agrees else 'DISAGREES'} — "
            f"the work of a turn by the trapezoid rule is F_load·H to {check.work:.1e}; the sweep "
            f"peaks at {check.sweep_peak:.3f} N, the exact peak {check.peak:.3f} N{fly}",
            markup=False,
        )


def render_force(r, fmt: str, summary: bool = False, out=None, why=None, check=None) -> None:
    """``pumplink force`` on a piston-pump spec: summary, the condensed sweep, the checks, the verdict
    (with JSON, ``explain`` and ``verify`` when given)."""
    out = out or sys.stdout
    row = summary_row(r)
    samples = [] if summary else sample_rows(r)

    def as_json():
        extra = {}
        if why is not None:
            extra["explain"] = {"model": row.get("model"), "why": why}
        if check is not None:
            extra["verify"] = check_row(check)
        return {**row, **extra, **({} if summary else {"samples": samples})}

    def as_csv():
        return samples if samples else [row]

    def table() -> None:
        from rich.markup import escape
        from rich.table import Table

        c = console(out)
        c.print(
            f"[bold]{escape(row['name'])}[/]\nsingle-acting piston pump, crank-slider turned by a hand crank"
        )
        if not row["feasible"]:
            c.print(_verdict_line(row), markup=False)
            return
        c.print(
            f"crank r = {row['crank_m']:.4g} m, rod l = {row['rod_m']:.4g} m, "
            f"offset e = {row['offset_m']:.4g} m, "
            f"handle R = {row['handle_m']:.4g} m\n"
            f"bore {row['bore_m'] * 1000:.4g} mm, head {row['head_m']:.4g} m: piston force "
            f"{row['load_force_N']:.1f} N on the working stroke\n"
            f"stroke H = {row['stroke_m']:.4g} m, time ratio K = {row['time_ratio']:.4f}, crank speed "
            f"{row['speed_deg_s']:g} deg/s ({row['power_W']:.1f} W)",
            markup=False,
        )
        if samples:
            step = max(1, math.ceil(len(samples) / TABLE_ROWS))
            t = Table(
                title=f"Sweep (every {step} of {len(samples)} samples; --format csv for all)"
                if step > 1
                else "Sweep",
                title_justify="left",
            )
            for h in ("crank [deg]", "slider [m]", "ds/dθ [m]", "torque [N·m]", "force [N]", "λ [deg]"):
                t.add_column(escape(h), justify="right")
            for s in samples[::step]:
                t.add_row(
                    _f(s["crank_angle_deg"], "{:.2f}"),
                    _f(s["slider_position_m"], "{:.4f}"),
                    _f(s["velocity_ratio_m_per_rad"], "{:+.4f}"),
                    _f(s["crank_torque_Nm"], "{:.2f}"),
                    _f(s["operator_force_N"], "{:.2f}"),
                    _f(s["pressure_angle_deg"], "{:.2f}"),
                )
            c.print(t)
        t = Table(title="Checks", title_justify="left")
        for h in ("check", "value", "limit", "result"):
            t.add_column(h, justify="left" if h == "check" else "right")
        for ch in row["checks"]:
            label = ch["name"]
            if ch["key"] == "peak_force":
                label += " (flywheel)" if row["least_peak_force_N"] is not None else " (quasi-st.)"
            t.add_row(
                label,
                f"{_f(ch['value'], '{:.2f}')} {ch['unit']}",
                f"{ch['relation']} {ch['fail_limit']:g} {ch['unit']}",
                {"pass": "pass", "warn": "warning", "fail": "FAIL"}[ch["result"]],
            )
        lo, hi = row["permissible_pressure_angle_deg"]
        lam = row["largest_pressure_angle_deg"]
        t.add_row(
            "largest pressure angle (rod/piston)",
            f"{lam:.2f} deg",
            f"<= {lo:g} ({hi:g}) deg",
            "ok" if lam <= lo else ("marginal" if lam <= hi else "warn"),
        )
        c.print(t)
        if row["least_peak_force_N"] is not None:
            c.print(
                f"model: flywheel (J = {row['inertia_kg_m2']:.4g} kg·m², energy band "
                f"{row['energy_band_J']:.4g} J; quasi-static peak {row['quasi_static_peak_N']:.1f} N)",
                markup=False,
            )
        else:
            c.print(
                f"model: quasi-static (peak at crank {row['quasi_static_peak_angle_deg']:.1f}°;\n"
                "  the operator turns the crank, so there is no dead centre)",
                markup=False,
            )
        use = r.spec.use
        for line in water_lines(
            r.water, r.power, r.spec.operator.profile or "men", use.hours_per_day, use.litres_per_person_day
        ):
            c.print(line, markup=False)
        c.print(_verdict_line(row), markup=False)

    render(fmt, out, as_json=as_json, as_csv=as_csv, table=table)


#: Columns of a piston-pump batch row in CSV and Parquet, in order (the JSON rows add
#: ``permissible_pressure_angle_deg`` and the checks).
BATCH_COLUMNS = (
    "variant",
    "mechanism",
    "feasible",
    "error",
    "crank_m",
    "rod_m",
    "offset_m",
    "handle_m",
    "bore_m",
    "head_m",
    "load_force_N",
    "stroke_m",
    "time_ratio",
    "largest_pressure_angle_deg",
    "speed_deg_s",
    "power_W",
    *WATER_KEYS,
    "mean_force_N",
    "quasi_static_peak_N",
    "quasi_static_peak_angle_deg",
    "model",
    "inertia_kg_m2",
    "energy_band_J",
    "least_peak_force_N",
    "force_limit_N",
    "verdict",
    "pass",
)
#: The permissible pressure angle of a sliding driven link [deg] (docs/mechanisms.md §4).
_PERMISSIBLE = [30.0, 45.0]


def batch_rows(names: list[str], c) -> list[dict[str, Any]]:
    """The JSON rows of a piston-pump batch chunk (``pumplink.batch.runner.PistonChunk``): the
    contract of :func:`summary_row`, named by variant."""
    ev, sp = c.evaluation, c.spec
    n = len(names)
    load = np.broadcast_to(np.asarray(ev.designs.load_force, float), (n,))
    inertia = np.broadcast_to(np.asarray(ev.designs.inertia, float), (n,))
    rows = []
    for i, name in enumerate(names):
        ok, fly = bool(ev.feasible[i]), bool(ev.model_index[i] > 0)
        verdict = ev.verdict.design(i) if ok else None
        checks = (
            []
            if verdict is None
            else [verdict_check_row(ch, name=_CHECK_LABELS.get(ch.key, ch.key)) for ch in verdict.checks]
        )
        rows.append(
            {
                "variant": name,
                "mechanism": "crank-slider",
                "feasible": ok,
                "error": c.reason[i],
                "crank_m": float(sp["crank_slider.crank"][i]),
                "rod_m": float(sp["crank_slider.rod"][i]),
                "offset_m": float(sp["crank_slider.offset"][i]),
                "handle_m": float(sp["operator.handle"][i]),
                "bore_m": float(sp["piston.bore"][i]),
                "head_m": float(sp["piston.head"][i]),
                "load_force_N": num(load[i]),
                "stroke_m": num(ev.stroke[i]),
                "time_ratio": num(ev.time_ratio[i]),
                "largest_pressure_angle_deg": deg(ev.largest_pressure_angle[i]),
                "permissible_pressure_angle_deg": list(_PERMISSIBLE),
                "speed_deg_s": float(sp["operator.speed"][i]),
                "power_W": num(ev.power[i]),
                **water_row(ev.water.design(i)),
                "mean_force_N": num(ev.mean_force[i]),
                "quasi_static_peak_N": num(ev.quasi_static_peak[i]),
                "quasi_static_peak_angle_deg": known_to(
                    deg(ev.quasi_static_peak_angle[i]), EXTREMUM_ARGUMENT
                ),
                "model": str(ev.model[i]),
                "inertia_kg_m2": num(inertia[i]) if fly else None,
                "energy_band_J": num(ev.energy_band[i]) if fly and ok else None,
                "least_peak_force_N": num(ev.least_peak_force[i]) if fly and ok else None,
                "force_limit_N": float(sp["operator.force_limit"][i]),
                "verdict": "FAIL" if verdict is None else verdict.outcome,
                "pass": bool(ok and verdict.passed),
                "checks": checks,
            }
        )
    return rows


def batch_csv(rows: list[dict[str, Any]]) -> str:
    """CSV lines of piston-pump batch rows (columns :data:`BATCH_COLUMNS`, empty for None)."""
    import csv
    import io

    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    for r in rows:
        w.writerow(["" if r[k] is None else r[k] for k in BATCH_COLUMNS])
    return buf.getvalue()


def batch_json(rows: list[dict[str, Any]]) -> str:
    """JSON of piston-pump batch rows as items of the ``variants`` list (indented as
    :func:`pumplink.output.formats.write_json` would), each followed by ',\n    '."""
    return "".join(json.dumps(r, indent=2, allow_nan=False).replace("\n", "\n    ") + ",\n    " for r in rows)
