"""Charts (optional extra ``pumplink[plot]``: matplotlib, imported lazily).

Each function writes one file (PNG, SVG or PDF by extension) and returns its path.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from pumplink.constants import DANGER, DEAD_CENTRE, MODEL_WORDS, NEAR_DEAD_CENTRE, UNIFORM
from pumplink.errors import SpecError
from pumplink.output.methods import POINT_LABELS

PLOT_HINT = "install it with: pip install 'pumplink[plot]'"
SUFFIXES = (".png", ".svg", ".pdf")
#: The widest a chart's title may be [fraction of the figure's width]: centred over the axes,
#: which constrained layout shifts a little off the figure's centre.
TITLE_WIDTH = 0.86


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


#: The most lines a title may take; a longer name loses its middle to an ellipsis.
TITLE_LINES = 3


def shorten_middle(text: str, keep: int) -> str:
    """``text`` cut to ``keep`` characters by an ellipsis in its middle (both ends stay)."""
    if len(text) <= keep:
        return text
    head = keep // 2
    return text[:head] + "…" + text[len(text) - (keep - 1 - head) :]


def width_of(artist) -> float:
    """The width of a text artist as drawn [fraction of its figure's width] (renderer extents)."""
    fig = artist.figure
    box = artist.get_window_extent(fig.canvas.get_renderer())
    return box.width / fig.bbox.width


def fit_text(artist, name: str, compose, width: float, lines: int = TITLE_LINES) -> str:
    """Set ``artist``'s text to ``compose(name)``, wrapped at spaces (a word longer than a line is
    broken) so that no line is wider than ``width`` [fraction of the figure's width]; where that
    takes more than ``lines`` lines the name loses characters from its middle (an ellipsis, so
    that both ends stay) until it does.  Returns the text set."""
    import textwrap

    artist.set_parse_math(False)  # a name is text: a '$' in it is a dollar sign

    def wrapped(text: str) -> str:
        artist.set_text(text)
        full = width_of(artist)
        if full <= width:
            return text
        n = max(1, int(len(text) * width / full))
        while True:
            out = "\n".join(textwrap.wrap(text, n, break_on_hyphens=False))
            artist.set_text(out)
            if n == 1 or width_of(artist) <= width:
                return out
            n -= 1

    text = wrapped(compose(name))
    if text.count("\n") < lines:
        return text
    lo, hi = 3, len(name)  # the most characters of the name that fit in the lines (bisection)
    while hi - lo > 1:
        mid = (lo + hi) // 2
        fits = wrapped(compose(shorten_middle(name, mid))).count("\n") < lines
        lo, hi = (mid, hi) if fits else (lo, mid)
    return wrapped(compose(shorten_middle(name, lo)))


def force_curve(result, curve, path) -> Path:
    """Operator force against crank angle by the model that decided, its peak marked.

    The quasi-static force (spikes at the dead centres) is always drawn; where it decided, its
    dead bands are shaded and its peak outside them is marked; where an energy model decided
    (the flywheel or full dynamics), its operator force and wheel speed are drawn and its peak
    is marked where the wheel is slowest (:class:`pumplink.studies.force.ForceCurve`).

    Parameters
    ----------
    result : :class:`pumplink.studies.force.ForceResult`.
    curve : :class:`pumplink.studies.force.ForceCurve` of that result (the curves to draw).
    path : output file (.png, .svg, .pdf).
    """
    path = check_path(path)
    plt = pyplot()
    syn = result.design.synthesis
    lim = result.force_limit
    words = MODEL_WORDS[result.model_key]
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
        if result.flywheel:
            continue  # the dead bands decide nothing: not shaded
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
            label=f"operator force, {words} (peak {result.verdict_peak_force:.1f} N)",
        )
        ax2 = ax.twinx()
        ax2.plot(np.degrees(theta), np.degrees(curve.wheel_speed), color="C4", lw=1, ls="--")
        ax2.set_ylabel("wheel speed [deg/s] (dashed)", color="C4")
        ax2.set_ylim(0, 1.3 * np.degrees(result.scene.max_speed))
    top = 3 * lim
    if np.isfinite(curve.peak_force):
        ax.plot(
            [np.degrees(curve.peak_angle)],
            [curve.peak_force],
            "o",
            color="C3",
            zorder=5,
            label=f"verdict's peak {abs(curve.peak_force):.1f} N ({words})",
        )
        top = max(top, 1.1 * abs(curve.peak_force))
    if result.flywheel:
        # no-break spaces keep a number with its unit when the title is wrapped
        j, delta = f"{result.inertia:.3f}", f"{result.speed_fluctuation:g}"
        what = f"{words} decides (J\u00a0=\u00a0{j}\u00a0kg·m², δ\u00a0≤\u00a0{delta})"
        if not np.isfinite(result.verdict_peak_force):
            what += ": no finite peak force keeps the wheel turning"
    else:
        what = f"{words} decides (grey: ±{band:g}° dead bands left to the wheel's inertia)"
    ax.set(
        xlim=(0, 360),
        ylim=(-top, top),
        xlabel="crank angle θ2 [deg]",
        ylabel="horizontal force at the grip [N]",
    )
    title = ax.set_title("x")
    fit_text(title, result.design.spec.name, lambda n: f"{n}: operator force, {what}", TITLE_WIDTH)
    ax.set_xticks(range(0, 361, 45))
    ax.grid(alpha=0.3)
    ax.legend(loc="lower right", fontsize=8)
    save(fig, path)
    plt.close(fig)
    return path


def speed_chart(sweep, path) -> Path:
    """Least peak force against mean wheel speed by the flywheel and full dynamics, the operator's
    effort with their arms, the best cadence, the speeds that pass and the 75 W line.

    Parameters
    ----------
    sweep : :class:`pumplink.studies.speed.SpeedSweep` (with its cadence).
    path : output file (.png, .svg, .pdf).
    """
    path = check_path(path)
    plt = pyplot()
    v = np.asarray(sweep.speed_deg_s, float)
    spec = sweep.design.spec
    fig, ax = plt.subplots(figsize=(9, 6.2), layout="constrained")
    limit = sweep.force_limit
    cad = sweep.cadence
    for band in () if cad is None else cad.bands:
        lo, hi = max(np.degrees(band[0]), v.min()), min(np.degrees(band[1]), v.max())
        if lo >= hi:
            continue
        ax.axvspan(lo, hi, color="tab:green", alpha=0.13, lw=0)
        ax.text(
            0.5 * (lo + hi), 0.02, "passes\nevery check", transform=ax.get_xaxis_transform(),
            ha="center", va="bottom", fontsize=9, color="darkgreen",
        )  # fmt: skip
    w75, p75 = np.degrees(sweep.sustained_speed), sweep.sustained_power
    if v.min() < w75 < v.max():
        ax.axvspan(w75, v.max(), color="0.5", alpha=0.10, lw=0)
        ax.axvline(w75, color="0.35", lw=1.4, ls="--")
        ax.text(
            w75, 0.14, f" {p75:g} W sustained ({w75:.0f} deg/s)\n more power →", rotation=0,
            transform=ax.get_xaxis_transform(), ha="left", va="center", fontsize=9.5, color="0.2",
            bbox=dict(boxstyle="round,pad=0.3", fc="white", ec="0.35"),
        )  # fmt: skip
    ax.plot(v, sweep.flywheel_force, color="tab:blue", lw=2, label="flywheel (links' inertia neglected)")
    ax.plot(v, sweep.dynamics_force, color="tab:orange", lw=2.6, label="full dynamics: hand force")
    arm = spec.operator.arm_mass_kg
    ax.plot(
        v, sweep.effort_force, color="tab:red", lw=2, ls="-.",
        label=f"full dynamics: effort (hand force + {arm:.2f} kg of arms)",
    )  # fmt: skip
    ax.axhline(limit, color="k", ls=":", lw=1.2, label=f"force limit {limit:g} N")
    ax.axhline(
        sweep.mean_force, color="0.5", ls=(0, (1, 3)), lw=1, label=f"mean force {sweep.mean_force:.1f} N"
    )
    if cad is not None and np.isfinite(cad.speed):
        x, y = np.degrees(cad.speed), cad.effort
        ax.plot([x], [y], marker="*", ms=16, color="tab:red", mec="k", zorder=5)
        ax.annotate(
            f"best cadence {x:.0f} deg/s ({x / 6:.0f} rpm)\neffort {y:.0f} N, hand {cad.hand_force:.0f} N, "
            f"{cad.power:.0f} W",
            (x, y), xytext=(0.74, 0.6), textcoords="axes fraction", ha="center", fontsize=9.5,
            arrowprops=dict(arrowstyle="->", lw=0.9),
            bbox=dict(boxstyle="round,pad=0.3", fc="white", ec="0.6"),
        )  # fmt: skip
    r = sweep.result  # pumplink force at the spec's own speed: the model that decides there, its peak
    if r is not None and np.isfinite(r.verdict_peak_force):
        ax.plot(
            [r.speed_deg_s], [r.verdict_peak_force], "D", ms=8, color="k", mfc="yellow", zorder=6,
            label=f"the verdict at the spec's {r.speed_deg_s:g} deg/s: {MODEL_WORDS[r.model_key]}, "
            f"peak {r.verdict_peak_force:.1f} N",
        )  # fmt: skip
    finite = [np.asarray(a, float) for a in (sweep.flywheel_force, sweep.dynamics_force, sweep.effort_force)]
    top = max(np.nanmax(np.where(np.isfinite(a), a, np.nan)) for a in finite)
    ax.set(
        xlabel="mean wheel speed ω̄ [deg/s]",
        ylabel="least peak horizontal force at the grip [N]",
        xlim=(v.min(), v.max()),
        ylim=(0, min(max(top * 1.12, limit * 1.25), 4 * limit)),
    )
    how = f"(J = {sweep.inertia:.3f} kg·m², δ ≤ {sweep.speed_fluctuation:g})"
    title = ax.set_title("x", fontsize=11)
    fit_text(title, spec.name, lambda n: f"{n}: the force a person needs against cadence {how}", TITLE_WIDTH)
    rpm = ax.secondary_xaxis("top", functions=(lambda d: d / 6.0, lambda r: r * 6.0))
    rpm.set_xlabel("wheel speed [rpm]")
    ax.grid(alpha=0.3)
    fig.legend(loc="outside lower center", ncols=2, fontsize=9, frameon=False)
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
    a2.plot(n, [s["peak_error"] for s in study], "s-", color="tab:blue", label="sampled peak (outside band)")
    a2.plot(
        n,
        [max(s["mean_error"], ERROR_FLOOR) for s in study],
        "o-",
        color="tab:green",
        label="sampled mean force",
    )
    for a, quantity, what in (
        (a1, "force [N]", "peak force a sweep reports"),
        (a2, "relative error vs exact", "error of sampled values"),
    ):
        a.set_xscale("log")
        a.set_yscale("log")
        a.set_xlabel("samples per revolution N")
        a.set_ylabel(quantity)
        a.legend(fontsize=8)
        a.set_title(what, fontsize=10)
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
