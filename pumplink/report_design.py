"""Rows and rendering for the design commands (``transmission``, ``optimize``) and the chart.

Degrees appear here, at the edge; the library works in radians.  Same conventions as
``pumplink.report`` (JSON: NaN -> null; CSV: one flat row; table: Rich).
"""

from __future__ import annotations

import math
import sys
from typing import Any

import numpy as np

from pumplink.report import _f, _json, console, deg, num, write_csv

#: Seed 001's worked example (K = 1.1818, phi = 40 deg, rocker 50 mm): its diagram read-off and
#: its "computer" result, as printed in the seed (crank, coupler, rocker, frame in mm).
SEED_001_EXAMPLE = {"time_ratio": 1.1818, "swing_deg": 40.0, "rocker": 50.0}
SEED_001_DESIGNS = {
    "seed 001 diagram read-off": (16.0, 46.0, 50.0, 53.76),
    "seed 001 computer result": (16.2227, 44.5093, 50.0, 53.8986),
}
#: The minimum transmission angle the seed prints for its diagram design [deg].
SEED_001_PRINTED_GAMMA_MIN = 46.3698

BINDING_TEXT = {0: "both extremes (gamma_min = 180 - gamma_max)", 1: "gamma_min (stationary on the arc)",
                2: "180 - gamma_max (stationary on the arc)"}


# ----------------------------------------------------------------------------- transmission
def transmission_rows(opt, sim, comparisons: list[tuple[str, tuple, Any]] | None = None) -> dict[str, Any]:
    """JSON contract of ``pumplink transmission``.

    Parameters
    ----------
    opt : :class:`pumplink.transmission.OptimalCrankRocker` (scalar).
    sim : :class:`pumplink.transmission.Simulation` of the optimum.
    comparisons : (label, (crank, coupler, rocker, frame), Simulation) of other designs.
    """
    out = {
        "time_ratio": num(opt.time_ratio),
        "theta_deg": deg(opt.theta),
        "swing_deg": deg(opt.swing),
        "crank": num(opt.crank), "coupler": num(opt.coupler), "rocker": num(opt.rocker), "frame": num(opt.frame),
        "rocker_to_frame": num(opt.rocker_to_frame),
        "min_transmission_deg": deg(opt.transmission),
        "gamma_min_deg": deg(opt.gamma_min), "gamma_max_deg": deg(opt.gamma_max),
        "binding": BINDING_TEXT[int(opt.binding)],
        "crank_pivot_side": "rocker-pivot side of the chord C1C2" if opt.side < 0 else "far side of the chord C1C2",
        "simulated": {"swing_deg": deg(sim.swing), "time_ratio": num(sim.time_ratio),
                      "min_transmission_deg": deg(sim.transmission), "assembles": sim.assembles},
        "compare": [],
    }
    for label, (c, k, r, f), s in comparisons or []:
        from pumplink.transmission import effective_transmission

        mu = float(effective_transmission(c, k, r, f)[0])
        out["compare"].append({
            "design": label, "crank": c, "coupler": k, "rocker": r, "frame": f,
            "min_transmission_deg": deg(mu),
            "ours_better_by_deg": num(np.degrees(opt.transmission - mu)),
            "simulated_swing_deg": deg(s.swing), "simulated_time_ratio": num(s.time_ratio),
        })
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
    c.print(f"[bold]Optimal-transmission crank-rocker[/] for K = {row['time_ratio']:g} "
            f"(θ = {row['theta_deg']:.6f}°), swing φ = {row['swing_deg']:g}°, rocker = {row['rocker']:g}")
    t = Table(title="Link lengths (rocker's unit) and transmission angle", title_justify="left")
    for h in ("design", "crank", "coupler", "rocker", "frame", "rocker/frame", "min transmission [deg]",
              "simulated swing [deg]", "simulated K"):
        t.add_column(escape(h), justify="left" if h == "design" else "right")
    sim = row["simulated"]
    t.add_row("[bold]optimum (this tool)[/]", _f(row["crank"], "{:.6f}"), _f(row["coupler"], "{:.6f}"),
              _f(row["rocker"], "{:.6f}"), _f(row["frame"], "{:.6f}"), _f(row["rocker_to_frame"], "{:.6f}"),
              _f(row["min_transmission_deg"], "{:.9f}"), _f(sim["swing_deg"], "{:.9f}"),
              _f(sim["time_ratio"], "{:.9f}"))
    for cmp in row["compare"]:
        t.add_row(cmp["design"], _f(cmp["crank"], "{:.4f}"), _f(cmp["coupler"], "{:.4f}"), _f(cmp["rocker"], "{:.4f}"),
                  _f(cmp["frame"], "{:.4f}"), _f(cmp["rocker"] / cmp["frame"], "{:.6f}"),
                  _f(cmp["min_transmission_deg"], "{:.9f}"), _f(cmp["simulated_swing_deg"], "{:.6f}"),
                  _f(cmp["simulated_time_ratio"], "{:.6f}"))
    c.print(t)
    c.print(f"γmin = {row['gamma_min_deg']:.9f}°, γmax = {row['gamma_max_deg']:.9f}°; binding: {row['binding']}; "
            f"crank pivot on the {row['crank_pivot_side']}")
    for cmp in row["compare"]:
        c.print(f"optimum is better than the {cmp['design']} by {cmp['ours_better_by_deg']:.9f}°", markup=False)
    if row["compare"]:
        c.print(f"(the seed prints γmin = {SEED_001_PRINTED_GAMMA_MIN}° for its diagram design; its own Eq. (4) "
                f"gives the value above)", markup=False)


def transmission_chart(path, theta_deg: np.ndarray, swing_deg: np.ndarray, opt) -> None:
    """Seed 001 Fig. 3 regenerated: contours of the optimal rocker/frame ratio and of the optimal
    minimum transmission angle over a (phi, theta) grid; writes ``path`` (format from suffix)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    phi, th = np.meshgrid(swing_deg, theta_deg)
    mu = np.degrees(opt.transmission)
    ratio = opt.rocker_to_frame
    fig, ax = plt.subplots(figsize=(8.5, 6.5), dpi=120)
    cs1 = ax.contour(phi, th, mu, levels=np.arange(10, 90, 5), colors="tab:blue", linewidths=1.0)
    ax.clabel(cs1, fmt="%g°", fontsize=8)
    cs2 = ax.contour(phi, th, ratio, levels=np.round(np.arange(0.1, 2.01, 0.1), 2), colors="tab:red",
                     linewidths=0.9, linestyles="--")
    ax.clabel(cs2, fmt="%.1f", fontsize=8)
    ex = SEED_001_EXAMPLE
    from pumplink.transmission import extreme_included_angle

    ax.plot([ex["swing_deg"]], [math.degrees(float(extreme_included_angle(ex["time_ratio"])))], "ko", ms=4)
    ax.annotate("seed 001 example", (ex["swing_deg"], math.degrees(float(extreme_included_angle(ex["time_ratio"])))),
                xytext=(6, 6), textcoords="offset points", fontsize=8)
    ax.set_xlabel("rocker swing φ [deg]")
    ax.set_ylabel("extreme included angle θ = 180°(K−1)/(K+1) [deg]")
    sec = ax.secondary_yaxis("right", functions=(lambda t: (180 + t) / (180 - t), lambda k: 180 * (k - 1) / (k + 1)))
    sec.set_ylabel("time ratio K")
    ax.set_title("Optimal transmission of the crank-rocker (seed 001 Fig. 3, exact)\n"
                 "blue: best minimum transmission angle [deg]; red dashed: rocker/frame (l3/l4) at the optimum",
                 fontsize=9)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)


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
    peak_b, peak_s = float(b.peak[0]), float(s.peak[0])
    verdict_b = float(b.verdict_peak[0])
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
        "variables": [{"key": k, "unit": VARIABLE_UNITS[k], "lower": float(lo), "upper": float(hi),
                       "spec": float(getattr(spec_lk, k)), "optimum": float(v)}
                      for k, lo, hi, v in zip(p.names, p.lower, p.upper, res.x)],
        "optimum": {"peak_force_N": num(peak_b), "required_peak_force_N": num(b.required[0]),
                    "mean_force_N": num(b.mean[0]),
                    "transmission_deg": num(b.transmission[0]), "grip_height_m": [num(b.grip_low[0]), num(b.grip_high[0])],
                    "stroke_m": num(b.stroke[0]), "rocker_pivot_height_m": num(p.axle_height - res.best.linkage.D1),
                    "passes_force_limit": bool(max(verdict_b, float(b.mean[0])) <= op.force_limit)},
        "spec_design": {"peak_force_N": num(peak_s), "required_peak_force_N": num(s.required[0]),
                        "mean_force_N": num(s.mean[0]),
                        "transmission_deg": num(s.transmission[0]), "meets_constraints": spec_ok,
                        "violated": [n for n, g in zip(names, s.slack[:, 0]) if g < 0]},
        "improvement_N": num(obj_s - obj_b) if obj_s < 1e5 else None,
        "improvement_pct": num(100 * (obj_s - obj_b) / obj_s) if obj_s < 1e5 else None,
        "constraints": [{"name": n, "unit": u, "slack": num(g), "binding": n in res.binding}
                        for n, (_, u), g in zip(names, CONSTRAINTS, b.slack[:, 0])],
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
        flat = {k: v for k, v in row.items() if k not in ("variables", "constraints", "binding", "spec_design",
                                                          "grip_height_range_m", "stroke_range_m")}
        for v in row["variables"]:
            flat[f"{v['key']}_optimum"] = v["optimum"]
        flat["binding"] = "; ".join(row["binding"])
        return write_csv([flat], out)
    from rich.markup import escape
    from rich.table import Table

    c = console(out)
    fly = row["model"] == "flywheel"
    model = (f"model: flywheel, J = {row['inertia_kg_m2']:.4g} kg·m², δ ≤ {row['speed_fluctuation']:g}, at "
             f"{row['speed_deg_s']:g} deg/s" if fly else "model: quasi-static + dead band")
    c.print(f"[bold]{row['name']}[/]: minimise the {row['objective']} operator force ({model}; seed {row['seed']}); axle height "
            f"{row['axle_height_m']:g} m, grip height {row['grip_height_range_m'][0]:g}–{row['grip_height_range_m'][1]:g} m, "
            f"stroke {row['stroke_range_m'][0]:g}–{row['stroke_range_m'][1]:g} m")
    t = Table(title="Variables", title_justify="left")
    for h in ("key", "bounds", "spec", "optimum"):
        t.add_column(h, justify="left" if h == "key" else "right")
    for v in row["variables"]:
        t.add_row(f"{v['key']} [{v['unit']}]", f"{v['lower']:g} … {v['upper']:g}", f"{v['spec']:.4f}", f"{v['optimum']:.6f}")
    c.print(t)
    o, s = row["optimum"], row["spec_design"]
    peak_key = "required_peak_force_N" if fly else "peak_force_N"  # the peak of the verdict
    t = Table(title="Forces", title_justify="left")
    heads = ("design", *(("peak with the flywheel [N]", "peak outside the dead bands [N]") if fly else ("peak [N]",)),
             "mean [N]", "transmission [deg]", "meets constraints")
    for h in heads:
        t.add_column(escape(h), justify="left" if h in ("design",) else "right")
    for label, d, meets in (("spec's own design", s, "yes" if s["meets_constraints"] else "[red]no[/]: " + "; ".join(s["violated"])),
                            ("[bold]optimum[/]", o, "yes")):
        peaks = (_f(d["required_peak_force_N"], "{:.3f}", none="∞"), _f(d["peak_force_N"], "{:.3f}")) if fly else \
            (_f(d["peak_force_N"], "{:.3f}"),)
        t.add_row(label, *peaks, _f(d["mean_force_N"], "{:.3f}"), _f(d["transmission_deg"], "{:.2f}"), meets)
    c.print(t)
    t = Table(title="Constraints at the optimum (slack >= 0 is satisfied)", title_justify="left")
    for h in ("constraint", "slack", "binding"):
        t.add_column(h, justify="right" if h == "slack" else "left")
    for k in row["constraints"]:
        t.add_row(k["name"], f"{k['slack']:.6g} {k['unit']}", "[bold]binds[/]" if k["binding"] else "")
    c.print(t)
    if row["improvement_N"] is not None:
        c.print(f"{row['objective']} force {_f(s[peak_key] if row['objective'] == 'peak' else s['mean_force_N'], '{:.2f}')} N → "
                f"{_f(o[peak_key] if row['objective'] == 'peak' else o['mean_force_N'], '{:.2f}')} N "
                f"({row['improvement_pct']:+.1f} % lower than the spec's own design)" if row["improvement_pct"] >= 0 else
                f"the optimum needs {-row['improvement_N']:.2f} N more than the spec's own design, which breaks: "
                f"{'; '.join(s['violated'])}", markup=False)
    c.print(f"binding: {', '.join(row['binding']) or 'none (interior optimum)'}", markup=False)
    c.print(f"grip {o['grip_height_m'][0]:.3f}–{o['grip_height_m'][1]:.3f} m, stroke {o['stroke_m']:.3f} m, rocker pivot "
            f"{o['rocker_pivot_height_m']:+.3f} m above the ground{' (below ground: needs a pit)' if o['rocker_pivot_height_m'] < 0 else ''}",
            markup=False)
    if not o["passes_force_limit"]:
        c.print(f"no design inside these bounds and ergonomic limits keeps the force within {row['force_limit_N']:g} N: "
                f"the best needs {_f(o[peak_key], '{:.2f}', none='∞')} N peak; it is held back by: "
                f"{', '.join(row['binding'])}. "
                "Widen the bounds that bind (--vary), or relax --grip-height / --stroke.", markup=False)
    verdict = "[bold green]PASS[/]" if o["passes_force_limit"] else "[bold red]FAIL[/]"
    c.print(f"{verdict}: optimum peak{' with the flywheel' if fly else ''} {_f(o[peak_key], '{:.2f}', none='∞')} N "
            f"vs limit {row['force_limit_N']:g} N "
            f"({row['evaluations']} designs evaluated, {row['generations']} generations"
            f"{', polished' if row['polished'] else ''})")
