"""``pumplink batch --format table`` and the run's summary in words (the table's last line and
the line on stderr).

The rows come from :func:`pumplink.output.batchfiles.write_stream`, which keeps those to show
(:data:`TABLE_ROWS`) and their identity (:func:`row_identity`) as the run streams.
"""

from __future__ import annotations

import re
import sys
import typing
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

from pumplink.constants import MODEL_WORDS
from pumplink.output.words import CHECK_LABELS

if TYPE_CHECKING:
    from pumplink.batch.runner import Chunk
    from pumplink.inputs.batch import Batch

#: The words of the energy models, which decide where a variant gives inertia.
ENERGY_WORDS = (MODEL_WORDS["flywheel"], MODEL_WORDS["dynamics"])
#: Rows shown by ``--format table``: all if the run has at most this many, else the failures.
TABLE_ROWS = 100


def _passing_words(s: dict[str, Any]) -> tuple[str, str, str]:
    """(model note, peak, mean) of the summary's ``best`` as text."""
    from pumplink.output.formats import fmt as _f

    best = s["best"]
    fly = f" ({best['model']})" if best["model"] in ENERGY_WORDS else ""
    return fly, _f(best["peak_force_N"], "{:.1f} N", none="∞"), _f(best["mean_force_N"], "{:.1f} N")


def _failed_words(keys: str) -> str:
    """The ``failed`` column's keys (``mean;peak;grip_speed``) in words."""
    long = {"mean": "mean_force", "peak": "peak_force"}
    return ", ".join(CHECK_LABELS.get(long.get(k, k), k) for k in keys.split(";") if k)


def best_line(s: dict[str, Any]) -> str:
    """The summary's best variant in words: the lowest peak force among those that pass, or, when
    none passes, that none does and which is closest (:func:`_update_summary`)."""
    best = s["best"]
    if best is None:
        return "no variant passes: none is feasible"
    fly, peak, mean = _passing_words(s)
    if best["pass"]:
        among = (
            "the only passing variant" if s["pass"] == 1 else f"lowest peak force{fly} of {s['pass']} passing"
        )
        return f"best: {best['name']} — {among}: peak {peak}, mean {mean} ({best['verdict']})"
    return (
        f"no variant passes; closest (fewest failing checks, then lowest peak): {best['name']} — "
        f"fails {_failed_words(s['_best_failed'])}; peak{fly} {peak}, mean {mean}"
    )


def summary_line(s: dict[str, Any], elapsed: float | None = None, wrote: Sequence[Path] = ()) -> str:
    """One line for stderr: counts, best variant, what failed, what was written."""
    best = s["best"]
    if best is None:
        best_txt = "; no variant passes: none is feasible"
    elif best["pass"]:
        fly, peak, _ = _passing_words(s)
        best_txt = f"; lowest passing peak{fly} {peak}: {best['name']}"
    else:
        best_txt = f"; no variant passes (closest: {best['name']}, fails {_failed_words(s['_best_failed'])})"
    sel = ",".join(s["fail_on"]) or "none"
    t = f" in {elapsed:.2f} s" if elapsed is not None else ""
    w = f"; wrote {', '.join(map(str, wrote))}" if wrote else ""
    chunk = f" (slice {s['chunk']})" if s["chunk"] != "1/1" else ""
    return (
        f"batch: {s['variants']} variants{chunk}{t}: {s['pass']} pass, {s['fail']} fail, "
        f"{s['infeasible']} infeasible; {s['failed_selected']} failing --fail-on {sel}{best_txt}{w}"
    )


#: A spec key's unit, read from the description of its field ("upper wheel radius rw [m]").
_UNIT = re.compile(r"\[([^\]]*)\]")


def key_unit(spec, key: str) -> str:
    """The unit of the dotted spec ``key`` as the table prints it ('m', '°', '' if none), from the
    field description of the spec's model (``spec`` is a PumpSpec or a PistonSpec instance)."""
    section, _, leaf = key.partition(".")
    field = type(spec).model_fields.get(section)
    if field is None:
        return ""
    kinds = [
        a for a in (typing.get_args(field.annotation) or (field.annotation,)) if hasattr(a, "model_fields")
    ]
    sub = kinds[0].model_fields.get(leaf) if kinds else None
    found = _UNIT.search((sub.description or "") if sub is not None else "")
    return "" if found is None else {"deg": "°"}.get(found.group(1), found.group(1))


def row_identity(batch: Batch, c: Chunk, pick: Sequence[int]) -> list[dict[str, Any]]:
    """What the table shows of each picked variant besides its results: ``id``, the variant's
    name up to its varied values (``<label>#<index>``, zero-padded as in the name, or the spec's
    name for a plain spec; every name starts with it, :func:`pumplink.inputs.batch.variant_names`),
    ``index`` (``#<index>``, None for a plain spec), ``number`` (the index as an int), ``label``,
    ``source``, ``vary`` (key -> value) and ``units`` (key -> unit)."""
    width = len(str(batch.size - 1))
    units = {k: key_unit(batch.spec, k) for k in batch.keys}
    vals = c.values.tolist()
    out = []
    for i in pick:
        number = c.start + i
        index = f"#{number:0{width}d}" if batch.axes else None
        out.append(
            {
                "id": batch.label + index if index else batch.label,
                "index": index,
                "number": number,
                "label": batch.label,
                "source": batch.source,
                "vary": dict(zip(batch.keys, vals[i])),
                "units": units,
            }
        )
    return out


def _header(name: str, unit: str) -> str:
    """A column header: the name, and the unit on a line of its own."""
    return f"{name}\n[{unit}]" if unit else name


def _widths(heads: list[tuple[str, str]], cells: list[list]) -> list[int]:
    """Each column's natural width: its widest header line or cell [characters]."""
    from rich.cells import cell_len

    def width(x) -> int:
        return max(cell_len(line) for line in str(x).split("\n"))

    return [max([width(h), *(width(row[j]) for row in cells)]) for j, (h, _) in enumerate(heads)]


def _gap(c, heads: list[tuple[str, str]], cells: list[list]) -> int | None:
    """Spaces between columns for the table to fit the console: 2, else 1, else None."""
    total = sum(_widths(heads, cells))
    return next((g for g in (2, 1) if total + g * (len(heads) - 1) <= c.width), None)


def _layout(c, heads: list[tuple[str, str]], cells: list[list]):
    """A Rich table of ``heads`` (header, justify) and rows of ``cells`` that fits the console
    without cutting a value: two spaces between columns, one when two do not fit.  If even that
    is too wide, only the first column (the variant) wraps, at spaces where it has them; the
    other columns keep their natural width; nothing is cut to an ellipsis."""
    from rich import box
    from rich.table import Table
    from rich.text import Text

    gap = _gap(c, heads, cells) or 1
    t = Table(
        box=box.SIMPLE_HEAD,
        show_edge=False,
        pad_edge=False,
        padding=(0, 1, 0, 0) if gap == 2 else 0,  # and the box puts one space between columns
    )
    for j, ((head, justify), width) in enumerate(zip(heads, _widths(heads, cells), strict=True)):
        fixed = {} if j == 0 else {"min_width": width, "no_wrap": True}
        t.add_column(Text(head), justify=justify, overflow="fold", **fixed)
    for row in cells:
        t.add_row(*(Text(x) if isinstance(x, str) else x for x in row))  # text, never markup
    return t


def _verdict_cell(r: dict[str, Any]):
    from rich.text import Text

    if not r["feasible"] or r["verdict"] == "FAIL":
        return Text("FAIL", style="red")
    return Text("PASS", style="green") if r["verdict"] == "PASS" else Text("warn", style="yellow")


def _notes(r: dict[str, Any]) -> str:
    """What an infeasible, failing or warning row fails or warns, in words ('' for none)."""
    if not r["feasible"]:
        return f"infeasible: {r.get('reason') or r.get('error')}"
    if "checks" in r:  # a piston pump's row: its checks
        failed = [ch["name"] for ch in r["checks"] if ch["result"] == "fail"]
        warned = [ch["name"] for ch in r["checks"] if ch["result"] == "warn"]
    else:
        failed = [_failed_words(r["failed"])] if r["failed"] else []
        warned = [_failed_words(r["warnings"])] if r["warnings"] else []
    parts = (["fails: " + ", ".join(failed)] if failed else []) + (
        ["warns: " + ", ".join(warned)] if warned else []
    )
    return "; ".join(parts)


def render_table(s: dict[str, Any], rows: list[dict], out=None) -> None:
    """``--format table`` for both pumps: the rows (or the failures of a large run) and the summary.

    Each row is named by its variant's identifier, the one the summary, the JSON, the CSV and the
    JUnit name it by (its name up to the varied values): ``#<index>`` when every row comes from
    one batch file (named in the title), else ``<label>#<index>`` or the spec's name.  Then one
    column per varied key (unit below the key), the forces, for rope pumps the smallest
    transmission angle and the peak grip speed, and the verdict (PASS, warn: PASS with warnings,
    FAIL); what fails or warns is listed below the table by identifier.  The last line names the
    best variant among those that pass (:func:`best_line`).  Laid out for an 80-column terminal.
    """
    from pumplink.output.formats import console
    from pumplink.output.formats import fmt as _f

    c = console(out or sys.stdout)
    if rows:
        piston = "checks" in rows[0]
        one = len({(r["label"], r["source"]) for r in rows}) == 1 and rows[0]["index"] is not None
        keys: list[str] = []
        units: dict[str, str] = {}
        for r in rows:
            keys.extend(k for k in r["vary"] if k not in keys)
            units.update(r["units"])
        of = f" of {rows[0]['label']}" if one else ""
        what = "Piston-pump variants" if piston else "Variants"
        title = (
            f"{what}{of}"
            if s["variants"] <= TABLE_ROWS
            else f"Failing variants{of} (first {len(rows)} of {s['failed_selected']}; all rows with "
            "--format csv --out FILE)"
        )
        fly = any(r["model"] in ENERGY_WORDS for r in rows)
        caption = "peak: the verdict's peak force" + (
            " (of the model that decided: flywheel or full dynamics where the spec gives inertia)"
            if fly
            else (" (quasi-static)" if piston else " outside the dead bands")
        )
        caption += ("" if piston else "; γ smallest transmission angle; v peak grip speed") + (
            "; warn: PASS with warnings"
        )

        def table(keys: list[str], named: bool):
            """Headers and cells: one column per varied key, or (``named``) the variant's whole
            name in the first column, which gives the varied values as key=value."""
            first = "variant (varied values in spec units)" if named else "#" if one else "variant"
            heads = [(first, "right" if one and not named else "left")]
            heads += [(_header(k.split(".")[-1], units.get(k, "")), "right") for k in keys]
            heads += [(_header("peak", "N"), "right"), (_header("mean", "N"), "right")]
            if not piston:
                heads += [(_header("γ", "°"), "right"), (_header("v", "m/s"), "right")]
            heads.append(("verdict", "left"))
            cells = []
            for r in rows:
                peak_value = r["peak_force_N"]
                row = [r.get("variant", r.get("name")) if named else r["index"] if one else r["id"]]
                row += [_f(r["vary"].get(k), "{:g}", none="") for k in keys]
                row += [
                    _f(peak_value, "{:.1f}", none="∞" if r["feasible"] else "—"),
                    _f(r["mean_force_N"], "{:.1f}"),
                ]
                if not piston:
                    tmin, tmax = r["transmission_min_deg"], r["transmission_max_deg"]
                    gamma = None if tmin is None or tmax is None else min(tmin, 180.0 - tmax)
                    row += [_f(gamma, "{:.1f}"), _f(r["grip_speed_m_s"], "{:.2f}")]
                row.append(_verdict_cell(r))
                cells.append(row)
            return heads, cells

        heads, cells = table(keys, named=False)
        if keys and _gap(c, heads, cells) is None:  # too many keys for a column each
            heads, cells = table([], named=True)
        c.print(title, markup=False)
        c.print(_layout(c, heads, cells))
        c.print(caption, markup=False)
        for ids, text in _ranges(rows, one):
            c.print(f"{ids}: {text}", markup=False)
    plural = "" if s["variants"] == 1 else "s"
    c.print(
        f"{s['variants']} variant{plural}: [green]{s['pass'] - s['pass_with_warnings']} pass[/], "
        f"[yellow]{s['pass_with_warnings']} pass with warnings[/], [red]{s['fail']} fail[/], "
        f"{s['infeasible']} infeasible; {s['failed_selected']} failing "
        f"--fail-on {','.join(s['fail_on']) or 'none'}"
    )
    c.print(best_line(s), markup=False)


def _ranges(rows: list[dict], one: bool) -> list[tuple[str, str]]:
    """The rows' notes (:func:`_notes`) by identifier: consecutive variants of one batch file with
    the same note joined (``#03-#05``, ``label#03-#05``), and the runs of rows in a row with the
    same note listed together: [('prototype-family#0-#7, Prototype', 'warns: peak grip speed')]."""
    groups: list[tuple[str, list[list[dict]]]] = []  # (note, runs [first row, last row])
    for r in rows:
        note = _notes(r)
        if not note:
            continue
        if not groups or groups[-1][0] != note:
            groups.append((note, []))
        runs = groups[-1][1]
        last = runs[-1][1] if runs else None
        if (
            last is not None
            and r["index"] is not None
            and (last["label"], last["source"], last["number"] + 1) == (r["label"], r["source"], r["number"])
        ):
            runs[-1][1] = r
        else:
            runs.append([r, r])
    out = []
    for note, runs in groups:
        names = [
            (first["index"] if one else first["id"]) + ("" if first is last else f"-{last['index']}")
            for first, last in runs
        ]
        out.append((", ".join(names), note))
    return out
