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
