"""Charts (optional extra ``pumplink[plot]``: matplotlib, imported lazily).

Each function writes one file (PNG, SVG or PDF by extension) and returns its path.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from pumplink.errors import SpecError

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


def check_path(path) -> Path:
    """Validate a chart path's extension before any work is done."""
    path = Path(path)
    if path.suffix.lower() not in SUFFIXES:
        raise SpecError(f"--plot {path}: unknown chart type '{path.suffix}'; use a file ending in .png, .svg or .pdf")
    return path


def force_curve(result, path) -> Path:
    """Operator force against crank angle: spikes at the dead centres, bands shaded, limit lines.

    Parameters
    ----------
    result : :class:`pumplink.analysis.ForceResult` with samples.
    path : output file (.png, .svg, .pdf).
    """
    from pumplink.kinematics import evaluate

    path = check_path(path)
    plt = pyplot()
    syn = result.design.synthesis
    lim = result.force_limit
    theta = np.linspace(0.0, 2 * np.pi, 7201)
    f = evaluate(syn.linkage, theta, result.wheel_torque).force
    f[np.abs(f) > 10 * lim] = np.nan  # off the chart: break the line instead of joining -inf to +inf
    fig, ax = plt.subplots(figsize=(9, 4.8), layout="constrained")
    ax.plot(np.degrees(theta), f, color="C0", lw=1.5, label="quasi-static operator force Fh")
    band = np.degrees(result.dead_band)
    for dc, label in ((syn.dead_centre_extended, "extended"), (syn.dead_centre_folded, "folded")):
        x = np.degrees(dc)
        ax.axvline(x, color="k", lw=0.8, ls=":")
        ax.text(x, 2.6 * lim, f" dead centre\n ({label})", fontsize=8, va="top")
        for lo, hi in ((x - band, x + band), (x - band + 360, x + band + 360), (x - band - 360, x + band - 360)):
            ax.axvspan(lo, hi, color="0.85", lw=0)
    ax.axhline(lim, color="C3", lw=1, ls="--", label=f"limit ±{lim:g} N")
    ax.axhline(-lim, color="C3", lw=1, ls="--")
    for sgn in (1, -1):
        ax.axhline(sgn * result.mean_force, color="C2", lw=1, ls="-.",
                   label=f"mean force ±{result.mean_force:.1f} N" if sgn > 0 else None)
    if result.flywheel and result.scene is not None and np.isfinite(result.scene.peak_force):
        from pumplink import flywheel as fw

        sc = result.scene
        ax.plot(np.degrees(theta), fw.operator_force(sc, theta), color="C1", lw=1.8,
                label=f"operator force with the flywheel (peak {sc.peak_force:.1f} N)")
        ax2 = ax.twinx()
        ax2.plot(np.degrees(theta), np.degrees(fw.wheel_speed(sc, theta)), color="C4", lw=1, ls="--")
        ax2.set_ylabel("wheel speed [deg/s] (dashed)", color="C4")
        ax2.set_ylim(0, 1.3 * np.degrees(sc.max_speed))
    pk = np.degrees(result.peak_angle)
    ax.plot([pk], [np.sign(np.interp(result.peak_angle, theta, f)) * result.peak_force], "o", color="C3",
            label=f"peak outside dead bands {result.peak_force:.1f} N")
    ax.set(xlim=(0, 360), ylim=(-3 * lim, 3 * lim), xlabel="crank angle θ2 [deg]", ylabel="horizontal force at the grip [N]",
           title=f"{result.design.spec.name}: operator force (grey: ±{band:g}° dead bands left to the wheel's inertia)")
    ax.set_xticks(range(0, 361, 45))
    ax.grid(alpha=0.3)
    ax.legend(loc="lower right", fontsize=8)
    fig.savefig(path)
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
    ax.plot(v, sweep.required_peak_force, color="C1", lw=2, marker="o", ms=3,
            label=f"least peak force, flywheel (J = {sweep.inertia:.3f} kg·m², δ ≤ {sweep.speed_fluctuation:g})")
    ax.axhline(sweep.force_limit, color="C3", ls="--", lw=1, label=f"limit {sweep.force_limit:g} N")
    ax.axhline(sweep.mean_force, color="C2", ls="-.", lw=1, label=f"mean force {sweep.mean_force:.1f} N (infinite flywheel)")
    ax.axhline(sweep.quasi_static_peak, color="C0", ls=":", lw=1,
               label=f"quasi-static peak outside the dead band {sweep.quasi_static_peak:.1f} N (speed-blind)")
    if np.isfinite(sweep.min_passing_speed):
        x = np.degrees(sweep.min_passing_speed)
        ax.axvline(x, color="k", lw=0.8, ls=":")
        ax.annotate(f"passes from {x:.0f} deg/s", (x, sweep.force_limit), xytext=(8, 30), textcoords="offset points",
                    arrowprops=dict(arrowstyle="->", lw=0.8), fontsize=9)
    top = np.nanmax(np.where(np.isfinite(sweep.required_peak_force), sweep.required_peak_force, np.nan))
    ax.set(xlabel="mean wheel speed ω̄ [deg/s]", ylabel="peak horizontal force at the grip [N]",
           ylim=(0, min(max(top, sweep.force_limit) * 1.1, 4 * sweep.force_limit)),
           title=f"{sweep.design.spec.name}: the wheel's inertia carries the dead centres; faster needs less force")
    ax2 = ax.twinx()
    ax2.plot(v, sweep.power, color="0.5", lw=1, ls="--")
    ax2.axhline(75, color="0.5", lw=0.6, ls=":")
    ax2.set_ylabel("operator power Mw ω̄ [W] (grey; dotted: 75 W sustained)", color="0.4")
    ax.grid(alpha=0.3)
    ax.legend(loc="upper right", fontsize=8)
    fig.savefig(path)
    plt.close(fig)
    return path
