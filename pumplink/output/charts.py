"""Charts (optional extra ``pumplink[plot]``: matplotlib, imported lazily).

Each function writes one file (PNG, SVG or PDF by extension) and returns its path.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from pumplink.errors import SpecError
from pumplink.methods import DANGER, DEAD_CENTRE, NEAR_DEAD_CENTRE, POINT_LABELS, UNIFORM

PLOT_HINT = "install it with: pip install 'pumplink[plot]'"
SUFFIXES = (".png", ".svg", ".pdf")


def pyplot():
    """matplotlib.pyplot with a file-only backend, or SpecError saying how to install it."""
    try:
        import matplotlib
    except ImportError:
        raise SpecError(f"plotting needs matplotlib, which is not installed; {PLOT_HINT}") from None
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def save(fig, path, **kwargs) -> None:
    """``fig.savefig(path)``, atomically (:func:`~pumplink.output.formats.atomic_write`: complete
    or not at all, a device written in place); a path that cannot be written is a SpecError
    (one line, exit 2)."""
    from pumplink.output.formats import atomic_write

    try:
        with atomic_write(path, binary=True) as f:
            fig.savefig(f, format=Path(path).suffix.lower().lstrip("."), **kwargs)
    except OSError as exc:
        raise SpecError(f"{path}: cannot be written ({exc.strerror or exc})") from None
    finally:
        import matplotlib.pyplot as plt

        plt.close(fig)


def check_path(path, option: str = "--plot") -> Path:
    """Validate a chart path (its extension, and that it can be written) before any work is done."""
    from pumplink.output.formats import check_output

    path = Path(path)
    if path.suffix.lower() not in SUFFIXES:
        raise SpecError(
            f"{option} {path}: unknown chart type '{path.suffix}'; use a file ending in .png, .svg or .pdf"
        )
    return check_output(path, option)


def force_curve(result, curve, path) -> Path:
    """Operator force against crank angle: spikes at the dead centres, bands shaded, limit lines.

    Parameters
    ----------
    result : :class:`pumplink.analysis.ForceResult`.
    curve : :class:`pumplink.analysis.ForceCurve` of that result (the curves to draw).
    path : output file (.png, .svg, .pdf).
    """
    path = check_path(path)
    plt = pyplot()
    syn = result.design.synthesis
    lim = result.force_limit
    theta = curve.crank_angle
    f = curve.force.copy()
    f[np.abs(f) > 10 * lim] = np.nan  # off the chart: break the line instead of joining -inf to +inf
    fig, ax = plt.subplots(figsize=(9, 4.8), layout="constrained")
    ax.plot(np.degrees(theta), f, color="C0", lw=1.5, label="quasi-static operator force Fh")
    band = np.degrees(result.dead_band)
    for dc, label in ((syn.dead_centre_extended, "extended"), (syn.dead_centre_folded, "folded")):
        x = np.degrees(dc)
        ax.axvline(x, color="k", lw=0.8, ls=":")
        ax.text(x, 2.6 * lim, f" dead centre\n ({label})", fontsize=8, va="top")
        for lo, hi in (
            (x - band, x + band),
            (x - band + 360, x + band + 360),
            (x - band - 360, x + band - 360),
        ):
            ax.axvspan(lo, hi, color="0.85", lw=0)
    ax.axhline(lim, color="C3", lw=1, ls="--", label=f"limit ±{lim:g} N")
    ax.axhline(-lim, color="C3", lw=1, ls="--")
    for sgn in (1, -1):
        ax.axhline(
            sgn * result.mean_force,
            color="C2",
            lw=1,
            ls="-.",
            label=f"mean force ±{result.mean_force:.1f} N" if sgn > 0 else None,
        )
    if curve.operator_force is not None:
        ax.plot(
            np.degrees(theta),
            curve.operator_force,
            color="C1",
            lw=1.8,
            label=f"operator force with the flywheel (peak {result.least_peak_force:.1f} N)",
        )
        ax2 = ax.twinx()
        ax2.plot(np.degrees(theta), np.degrees(curve.wheel_speed), color="C4", lw=1, ls="--")
        ax2.set_ylabel("wheel speed [deg/s] (dashed)", color="C4")
        ax2.set_ylim(0, 1.3 * np.degrees(result.scene.max_speed))
    pk = np.degrees(result.dead_band_peak_angle)
    ax.plot(
        [pk],
        [curve.peak_sign * result.dead_band_peak_force],
        "o",
        color="C3",
        label=f"peak outside dead bands {result.dead_band_peak_force:.1f} N",
    )
    ax.set(
        xlim=(0, 360),
        ylim=(-3 * lim, 3 * lim),
        xlabel="crank angle θ2 [deg]",
        ylabel="horizontal force at the grip [N]",
        title=f"{result.design.spec.name}: operator force "
        f"(grey: ±{band:g}° dead bands left to the wheel's inertia)",
    )
    ax.set_xticks(range(0, 361, 45))
    ax.grid(alpha=0.3)
    ax.legend(loc="lower right", fontsize=8)
    save(fig, path)
    plt.close(fig)
    return path


def speed_chart(sweep, path) -> Path:
    """Required peak operator force against mean wheel speed (flywheel model), limit and minimum speed.

    Parameters
    ----------
    sweep : :class:`pumplink.analysis.SpeedSweep`.
    path : output file (.png, .svg, .pdf).
    """
    path = check_path(path)
    plt = pyplot()
    v = sweep.speed_deg_s
    fig, ax = plt.subplots(figsize=(8, 4.8), layout="constrained")
    ax.plot(
        v,
        sweep.least_peak_force,
        color="C1",
        lw=2,
        marker="o",
        ms=3,
        label=f"least peak force, flywheel (J = {sweep.inertia:.3f} kg·m², δ ≤ {sweep.speed_fluctuation:g})",
    )
    ax.axhline(sweep.force_limit, color="C3", ls="--", lw=1, label=f"limit {sweep.force_limit:g} N")
    ax.axhline(
        sweep.mean_force,
        color="C2",
        ls="-.",
        lw=1,
        label=f"mean force {sweep.mean_force:.1f} N (infinite flywheel)",
    )
    ax.axhline(
        sweep.dead_band_peak_force,
        color="C0",
        ls=":",
        lw=1,
        label=f"quasi-static peak outside the dead band {sweep.dead_band_peak_force:.1f} N (speed-blind)",
    )
    if np.isfinite(sweep.min_passing_speed):
        x = np.degrees(sweep.min_passing_speed)
        ax.axvline(x, color="k", lw=0.8, ls=":")
        ax.annotate(
            f"passes from {x:.0f} deg/s",
            (x, sweep.force_limit),
            xytext=(8, 30),
            textcoords="offset points",
            arrowprops=dict(arrowstyle="->", lw=0.8),
            fontsize=9,
        )
    top = np.nanmax(np.where(np.isfinite(sweep.least_peak_force), sweep.least_peak_force, np.nan))
    ax.set(
        xlabel="mean wheel speed ω̄ [deg/s]",
        ylabel="peak horizontal force at the grip [N]",
        ylim=(0, min(max(top, sweep.force_limit) * 1.1, 4 * sweep.force_limit)),
        title=f"{sweep.design.spec.name}: the wheel's inertia carries the dead centres; "
        "faster needs less force",
    )
    ax2 = ax.twinx()
    ax2.plot(v, sweep.power, color="0.5", lw=1, ls="--")
    ax2.axhline(75, color="0.5", lw=0.6, ls=":")
    ax2.set_ylabel("operator power Mw ω̄ [W] (grey; dotted: 75 W sustained)", color="0.4")
    ax.grid(alpha=0.3)
    ax.legend(loc="upper right", fontsize=8)
    save(fig, path)
    plt.close(fig)
    return path


#: Errors below this are drawn at this floor on the log axis (0 cannot be drawn).
ERROR_FLOOR = 1e-17


MARKERS = {UNIFORM: "o", NEAR_DEAD_CENTRE: "s", DEAD_CENTRE: "x", DANGER: "^"}


COLOURS = {"vector": "tab:blue", "paper": "tab:orange", "numeric": "tab:green", "reference": "tab:gray"}


def plot_methods(rows: list[dict], path: Path, title: str = "") -> None:
    """Log max relative error vs log time per position; one marker per method and sampling."""
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(7.5, 4.8))
    for r in rows:
        for kind, st in r["samplings"].items():
            if st["max_rel_error"] is None:
                continue  # every point flagged (e.g. exact dead centres): nothing to plot
            err = max(st["max_rel_error"], ERROR_FLOOR)
            ax.scatter(
                st["seconds_per_position"],
                err,
                marker=MARKERS.get(kind, "o"),
                color=COLOURS.get(r["name"], "k"),
                s=55,
                zorder=3,
            )
        ax.annotate(
            r["name"],
            (
                r["samplings"][UNIFORM]["seconds_per_position"],
                max(r["samplings"][UNIFORM]["max_rel_error"] or ERROR_FLOOR, ERROR_FLOOR),
            ),
            textcoords="offset points",
            xytext=(6, 6),
            color=COLOURS.get(r["name"], "k"),
        )
    for kind, mk in MARKERS.items():
        if kind != DEAD_CENTRE:
            ax.scatter([], [], marker=mk, color="k", label=POINT_LABELS[kind])
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("time per crank position [s] (median)")
    ax.set_ylabel("max relative error of Fh vs 50-digit reference")
    ax.axhline(ERROR_FLOOR, color="0.8", lw=0.8)
    ax.set_title(f"Speed vs accuracy of the force methods{': ' + title if title else ''}", fontsize=10)
    ax.legend(fontsize=8, loc="best")
    ax.grid(True, which="major", alpha=0.3)
    save(fig, path, dpi=120, bbox_inches="tight")
    plt.close(fig)


def plot_sampling(study: list[dict], path: Path, title: str = "", dead_band_deg: float = 20.0) -> None:
    """Sampled vs exact peak force and sampled-mean error against N (log N)."""
    plt = pyplot()
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(10, 4.2))
    n = [s["n"] for s in study]
    a1.plot(n, [s["sampled_max"] for s in study], "o-", color="tab:red", label="sweep max |Fh|, no dead band")
    a1.plot(
        n,
        [s["sampled_peak"] for s in study],
        "s-",
        color="tab:blue",
        label=f"sampled peak outside ±{dead_band_deg:g}°",
    )
    a1.axhline(study[0]["exact_peak"], color="tab:blue", ls="--", label="exact peak outside band")
    a1.axhline(study[0]["exact_mean"], color="tab:green", ls=":", label="mean force (lower bound)")
    a1.set_xscale("log")
    a1.set_yscale("log")
    a1.set_xlabel("samples per revolution N")
    a1.set_ylabel("force [N]")
    a1.legend(fontsize=8)
    a1.set_title("peak force a sweep reports", fontsize=10)
    a2.plot(n, [s["peak_error"] for s in study], "s-", color="tab:blue", label="sampled peak (outside band)")
    a2.plot(
        n,
        [max(s["mean_error"], ERROR_FLOOR) for s in study],
        "o-",
        color="tab:green",
        label="sampled mean force",
    )
    a2.set_xscale("log")
    a2.set_yscale("log")
    a2.set_xlabel("samples per revolution N")
    a2.set_ylabel("relative error vs exact")
    a2.legend(fontsize=8)
    a2.set_title("error of sampled values", fontsize=10)
    for a in (a1, a2):
        a.grid(True, which="major", alpha=0.3)
    if title:
        fig.suptitle(title, fontsize=10)
    save(fig, path, dpi=120, bbox_inches="tight")
    plt.close(fig)


def transmission_chart(chart, path) -> None:
    """The optimal-transmission paper's design diagram (its Fig. 3), regenerated exactly: contours
    of the optimal rocker/frame ratio and of the best minimum transmission angle over (phi, theta).

    Parameters
    ----------
    chart : :class:`pumplink.mechanisms.crank_rocker.DesignChart`.
    path : output file (.png, .svg, .pdf).
    """
    path = check_path(path)
    plt = pyplot()
    phi, th = np.meshgrid(chart.swing_deg, chart.theta_deg)
    mu = np.degrees(chart.optimum.transmission)
    ratio = chart.optimum.rocker_to_frame
    fig, ax = plt.subplots(figsize=(8.5, 6.5), dpi=120)
    cs1 = ax.contour(phi, th, mu, levels=np.arange(10, 90, 5), colors="tab:blue", linewidths=1.0)
    ax.clabel(cs1, fmt="%g°", fontsize=8)
    cs2 = ax.contour(
        phi,
        th,
        ratio,
        levels=np.round(np.arange(0.1, 2.01, 0.1), 2),
        colors="tab:red",
        linewidths=0.9,
        linestyles="--",
    )
    ax.clabel(cs2, fmt="%.1f", fontsize=8)
    ax.plot([chart.example_swing_deg], [chart.example_theta_deg], "ko", ms=4)
    ax.annotate(
        "the paper's example",
        (chart.example_swing_deg, chart.example_theta_deg),
        xytext=(6, 6),
        textcoords="offset points",
        fontsize=8,
    )
    ax.set_xlabel("rocker swing φ [deg]")
    ax.set_ylabel("extreme included angle θ = 180°(K−1)/(K+1) [deg]")
    sec = ax.secondary_yaxis(
        "right", functions=(lambda t: (180 + t) / (180 - t), lambda k: 180 * (k - 1) / (k + 1))
    )
    sec.set_ylabel("time ratio K")
    ax.set_title(
        "Optimal transmission of the crank-rocker (the paper's Fig. 3, exact)\n"
        "blue: best minimum transmission angle [deg]; red dashed: rocker/frame at the optimum",
        fontsize=9,
    )
    ax.grid(alpha=0.3)
    fig.tight_layout()
    save(fig, path)
    plt.close(fig)
