"""`pumplink methods`: the force methods against the 50-digit reference, and the sampling study.

Renderers only render: every number comes from the library's results.
"""

from __future__ import annotations

import sys
from typing import TYPE_CHECKING

from pumplink.constants import (
    CRANK_ALONG_FRAME,
    CRANK_PARALLEL_ROCKER,
    CRANK_PERPENDICULAR,
    DANGER,
    DEAD_CENTRE,
    NEAR_DEAD_CENTRE,
    ROCKER_PERPENDICULAR,
    UNIFORM,
)
from pumplink.output.formats import console, render, report_table

if TYPE_CHECKING:
    pass

#: What reports call each kind of position (and the keys of ``pumplink methods --format json``).
POINT_LABELS = {
    UNIFORM: "uniform sweep",
    NEAR_DEAD_CENTRE: "near a dead centre (down to 1e-6 deg)",
    DEAD_CENTRE: "exactly at a dead centre",
    CRANK_PERPENDICULAR: "crank perpendicular to the frame line",
    ROCKER_PERPENDICULAR: "rocker perpendicular to the frame line",
    CRANK_PARALLEL_ROCKER: "crank parallel to the rocker",
    CRANK_ALONG_FRAME: "crank along the frame line",
    DANGER: "danger points",
}


def _e(x) -> str:
    return "—" if x is None else ("0" if x == 0 else f"{x:.1e}")


#: How each finding of the method comparison reads (``pumplink.studies.accuracy.failures``).
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

    def as_json():
        return {"design": name, "methods": json_rows(rows), "sampling": study}

    def as_csv():
        return [
            {k: v for k, v in r.items() if k not in ("samplings", "failures")}
            | {"failures": "; ".join(failure_sentences(r["failures"]))}
            for r in rows
        ]

    def table() -> None:
        from rich.markup import escape

        c = console(out)
        kinds = list(rows[0]["samplings"]) if rows else []
        short = {
            "uniform": "uniform",
            "near_dead_centre": "near DC",
            "dead_centre": "at DC",
            "danger_points": "danger",
        }
        t = report_table(
            f"{name}: force methods vs the 50-digit reference",
            "largest relative error of Fh on each sample set: uniform sweep; near DC (1° down to "
            "1e-6° from a dead centre); at DC; danger points; — = every point flagged",
        )
        for h in ["method", "time/pos. [ns]"] + [short.get(k, k) for k in kinds] + ["verdict"]:
            t.add_column(escape(h), justify="left" if h in ("method", "verdict") else "right")
        notes = []
        for r in rows:
            cells = [r["name"], f"{r['seconds_per_position'] * 1e9:,.0f}"]
            for k in kinds:
                st = r["samplings"][k]
                cells.append(_e(st["max_rel_error"]) + ("*" if st["flagged"] else ""))
            sentences = failure_sentences(r["failures"])
            wrong = any(st["wrong"] or st["missed_singular"] for st in r["samplings"].values())
            cells.append("[red]WRONG[/]" if wrong else "flags" if sentences else "[green]ok[/]")
            t.add_row(*cells)
            notes += [f"  {r['name']}: {x}" for x in sentences]
        c.print(t)
        c.print(
            '* some points flagged: NaN with a flag (dead centre: "∞ (dead centre)"), never a made-up '
            "number. WRONG = an unflagged value off by more than the method's registered tolerance.",
            markup=False,
        )
        for line in notes:
            c.print(line, markup=False)
        for r in rows:
            c.print(f"  {r['name']}: {r['summary']}; cannot handle: {r['cannot_handle']}", markup=False)

        st = report_table(
            f"How many samples? A uniform sweep from crank 0° vs exact (dead band ±{dead_band_deg:g}°)",
            "max |Fh|: the sweep's largest force with no band; peak: outside the band; "
            "err: relative error of the sampled value",
        )
        for h in (
            "N",
            "max |Fh| [N]",
            "peak [N]",
            "exact [N]",
            "err",
            "mean [N]",
            "exact [N]",
            "err",
        ):
            st.add_column(escape(h), justify="right")
        for s in study:
            st.add_row(
                str(s["n"]),
                f"{s['sampled_max']:.1f}" if s["sampled_max"] is not None else "—",
                f"{s['sampled_peak']:.2f}" if s["sampled_peak"] is not None else "—",
                f"{s['exact_peak']:.2f}",
                _e(s["peak_error"]),
                f"{s['sampled_mean']:.4f}",
                f"{s['exact_mean']:.4f}",
                _e(s["mean_error"]),
            )
        c.print(st)
        c.print(
            "A sweep without a dead band reports whatever spike it lands next to (the true force is "
            "infinite at "
            "the dead centres); with the band, the exact peak is found by root-bracketing, whatever N.",
            markup=False,
        )

    render(fmt, out, as_json=as_json, as_csv=as_csv, table=table)
