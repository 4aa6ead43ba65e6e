"""Rendering for ``pumplink methods``: table / JSON / CSV and the two charts (issue #3).

Only formatting lives here; the numbers come from ``pumplink.accuracy`` and the timing from the
command.  matplotlib is imported lazily (optional extra ``pumplink[plot]``).
"""

from __future__ import annotations

import sys
from pathlib import Path

from pumplink.errors import SpecError
from pumplink.report import _json, console, write_csv

#: Errors below this are drawn at this floor on the log axis (0 cannot be drawn).
ERROR_FLOOR = 1e-17


def _e(x) -> str:
    return "—" if x is None else ("0" if x == 0 else f"{x:.1e}")


def json_rows(rows: list[dict]) -> list[dict]:
    """The JSON contract: name, seconds_per_position, max_rel_error_uniform,
    max_rel_error_near_dead_centre, failures (plus summary, cannot_handle and per-sampling detail)."""
    return [{k: r[k] for k in ("name", "summary", "cannot_handle", "seconds_per_position", "max_rel_error_uniform",
                               "max_rel_error_near_dead_centre", "failures", "samplings")} for r in rows]


def render_methods(name: str, rows: list[dict], study: list[dict], fmt: str, dead_band_deg: float, out=None) -> None:
    """`pumplink methods`: one row per method and the sampling study."""
    out = out or sys.stdout
    if fmt == "json":
        return _json({"design": name, "methods": json_rows(rows), "sampling": study}, out)
    if fmt == "csv":
        return write_csv([{k: v for k, v in r.items() if k not in ("samplings", "failures")}
                          | {"failures": "; ".join(r["failures"])} for r in rows], out)
    from rich.table import Table

    c = console(out)
    t = Table(title=f"{name}: force methods against the 50-digit reference (relative error of Fh)",
              title_justify="left")
    kinds = list(rows[0]["samplings"]) if rows else []
    for h in ["method", "time / position"] + [f"max err: {k}" for k in kinds] + ["failures / flags"]:
        t.add_column(h, justify="left" if h in ("method", "failures / flags") else "right")
    for r in rows:
        cells = [r["name"], f"{r['seconds_per_position'] * 1e9:,.1f} ns"]
        for k in kinds:
            st = r["samplings"][k]
            cell = _e(st["max_rel_error"])
            if st["flagged"]:
                cell += f" ({st['flagged']}/{st['n']} flagged)"
            cells.append(cell)
        cells.append("\n".join(r["failures"]) or "none")
        t.add_row(*cells)
    c.print(t)
    c.print("flagged = NaN with a flag (dead centre: \"∞ (dead centre)\"), never a made-up number; "
            "'silently wrong' = an unflagged value off by more than the method's registered tolerance.",
            markup=False)
    for r in rows:
        c.print(f"  {r['name']}: {r['summary']}; cannot handle: {r['cannot_handle']}", markup=False)

    st = Table(title=f"How many samples? Uniform sweep from crank 0° vs exact values (dead band ±{dead_band_deg:g}°)",
               title_justify="left")
    for h in ("N", "sweep max |Fh| (no band)", "sampled peak outside band", "exact peak", "peak error",
              "sampled mean", "exact mean", "mean error"):
        st.add_column(h, justify="right")
    for s in study:
        st.add_row(str(s["n"]), f"{s['sampled_max']:.1f} N" if s["sampled_max"] is not None else "—",
                   f"{s['sampled_peak']:.2f} N" if s["sampled_peak"] is not None else "—",
                   f"{s['exact_peak']:.2f} N", _e(s["peak_error"]), f"{s['sampled_mean']:.4f} N",
                   f"{s['exact_mean']:.4f} N", _e(s["mean_error"]))
    c.print(st)
    c.print("A sweep without a dead band reports whatever spike it lands next to (the true force is infinite at "
            "the dead centres); with the band, the exact peak is found by root-bracketing, whatever N.", markup=False)


def _pyplot():
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        raise SpecError("writing a chart needs matplotlib; install it with: pip install 'pumplink[plot]'") from None
    return plt


def _save(fig, path: Path) -> None:
    try:
        fig.savefig(path, dpi=120, bbox_inches="tight")
    except OSError as exc:
        raise SpecError(f"{path}: cannot be written ({exc.strerror})") from None


MARKERS = {"uniform sweep": "o", "near a dead centre (down to 1e-6 deg)": "s", "exactly at a dead centre": "x",
           "danger points": "^"}
COLOURS = {"vector": "tab:blue", "paper": "tab:orange", "numeric": "tab:green", "reference": "tab:gray"}


def plot_methods(rows: list[dict], path: Path, title: str = "") -> None:
    """Log max relative error vs log time per position; one marker per method and sampling."""
    plt = _pyplot()
    fig, ax = plt.subplots(figsize=(7.5, 4.8))
    for r in rows:
        for kind, st in r["samplings"].items():
            if st["max_rel_error"] is None:
                continue  # every point flagged (e.g. exact dead centres): nothing to plot
            err = max(st["max_rel_error"], ERROR_FLOOR)
            ax.scatter(st["seconds_per_position"], err, marker=MARKERS.get(kind, "o"),
                       color=COLOURS.get(r["name"], "k"), s=55, zorder=3)
        ax.annotate(r["name"], (r["samplings"]["uniform sweep"]["seconds_per_position"],
                                max(r["samplings"]["uniform sweep"]["max_rel_error"] or ERROR_FLOOR, ERROR_FLOOR)),
                    textcoords="offset points", xytext=(6, 6), color=COLOURS.get(r["name"], "k"))
    for kind, mk in MARKERS.items():
        if kind != "exactly at a dead centre":
            ax.scatter([], [], marker=mk, color="k", label=kind)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("time per crank position [s] (median)")
    ax.set_ylabel("max relative error of Fh vs 50-digit reference")
    ax.axhline(ERROR_FLOOR, color="0.8", lw=0.8)
    ax.set_title(f"Speed vs accuracy of the force methods{': ' + title if title else ''}", fontsize=10)
    ax.legend(fontsize=8, loc="best")
    ax.grid(True, which="major", alpha=0.3)
    _save(fig, path)
    plt.close(fig)


def plot_sampling(study: list[dict], path: Path, title: str = "", dead_band_deg: float = 20.0) -> None:
    """Sampled vs exact peak force and sampled-mean error against N (log N)."""
    plt = _pyplot()
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(10, 4.2))
    n = [s["n"] for s in study]
    a1.plot(n, [s["sampled_max"] for s in study], "o-", color="tab:red", label="sweep max |Fh|, no dead band")
    a1.plot(n, [s["sampled_peak"] for s in study], "s-", color="tab:blue",
            label=f"sampled peak outside ±{dead_band_deg:g}°")
    a1.axhline(study[0]["exact_peak"], color="tab:blue", ls="--", label="exact peak outside band")
    a1.axhline(study[0]["exact_mean"], color="tab:green", ls=":", label="mean force (lower bound)")
    a1.set_xscale("log")
    a1.set_yscale("log")
    a1.set_xlabel("samples per revolution N")
    a1.set_ylabel("force [N]")
    a1.legend(fontsize=8)
    a1.set_title("peak force a sweep reports", fontsize=10)
    a2.plot(n, [s["peak_error"] for s in study], "s-", color="tab:blue", label="sampled peak (outside band)")
    a2.plot(n, [max(s["mean_error"], ERROR_FLOOR) for s in study], "o-", color="tab:green", label="sampled mean force")
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
    _save(fig, path)
    plt.close(fig)
