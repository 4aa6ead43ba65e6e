"""Rendering of batch runs (``pumplink batch``): rows, summary, CSV/JSON/Parquet, JUnit XML (the
table: :mod:`pumplink.output.batchtable`).

Rows are streamed chunk by chunk, so memory stays bounded whatever the grid size.  Files named
with ``--out``/``--junit`` are written atomically: to a temporary file in the same folder, moved
over the target (``os.replace``) only when the run completed; an interrupted or failed run
leaves the target as it was (absent, or the previous complete file).
"""

from __future__ import annotations

import contextlib
import json
import math
import shutil
import sys
import tempfile
from collections.abc import Callable, Iterable, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any
from xml.sax.saxutils import escape, quoteattr

import numpy as np
import orjson

from pumplink.constants import MODEL_WORDS
from pumplink.errors import escape_control
from pumplink.output.batchtable import TABLE_ROWS, row_identity
from pumplink.output.formats import atomic_write
from pumplink.output.piston import BATCH_COLUMNS, batch_csv, batch_json, batch_rows
from pumplink.quantities import CATALOGUE
from pumplink.quantities import columns as quantity_columns

if TYPE_CHECKING:
    from pumplink.batch.runner import Chunk
    from pumplink.inputs.batch import Batch

#: The words of the flywheel and of the quasi-static model (the ``model`` column).
FLYWHEEL, QUASI_STATIC = MODEL_WORDS["flywheel"], MODEL_WORDS["quasi-static"]

#: The verdict's checks (``pumplink.verdict``), one column each: pass, warn, fail, or empty where
#: the check does not apply to the variant (``check_<key>``).
CHECK_KEYS = (
    "mean_force",
    "peak_force",
    "link_energy_share",
    "transmission_angle",
    "power",
    "cadence",
    "rope_speed",
    "grip_speed",
    "stroke",
    "grip_height",
    "axle_height",
    "pin_pressure",
    "handle_fatigue",
    "crank_fatigue",
    "kick_back",
    "holding_torque",
    "pin_wear",
)
CHECK_COLUMNS = tuple(f"check_{k}" for k in CHECK_KEYS)
#: The numeric columns: the catalogue's batch columns (:data:`pumplink.quantities.CATALOGUE`), named
#: as in ``pumplink force --format json`` where both hold a quantity.
NUMBER_COLUMNS = tuple(q.column for q in CATALOGUE if q.column is not None)
#: The text and boolean columns that follow a numeric one in the CSV (the rest come last).
_TEXT_AFTER = {"coupler_length": ("feasible", "reason"), "force_limit_N": ("model",)}
#: Per-variant columns after the name, the source and the varied keys (CSV order).
FIXED_COLUMNS = (
    *(c for col in NUMBER_COLUMNS for c in (col, *_TEXT_AFTER.get(col, ()))),
    "verdict",
    "pass",
    "failed",
    "warnings",
    *CHECK_COLUMNS,
)
#: ``--format parquet``: the columns of :data:`FIXED_COLUMNS` that are numbers (float64) and
#: booleans; the others are text.
PARQUET_BOOLS = ("feasible", "pass")
PARQUET_TEXT = ("reason", "model", "verdict", "failed", "warnings", *CHECK_COLUMNS)
#: Rows per Parquet row group (chunks are gathered up to this many before they are written).
PARQUET_ROWS = 65_536


def varied_keys(batches: Sequence[Batch]) -> list[str]:
    """Union of the varied spec keys, in first-seen order (one CSV column each)."""
    keys: list[str] = []
    for b in batches:
        keys.extend(k for k in b.keys if k not in keys)
    return keys


def columns(batches: Sequence[Batch]) -> list[str]:
    """CSV header: name, source, each varied key, then :data:`FIXED_COLUMNS`."""
    return ["name", "source", *varied_keys(batches), *FIXED_COLUMNS]


def _floats(a) -> list:
    return [v if math.isfinite(v) else None for v in np.asarray(a, float).tolist()]


#: Words of a check's level in the ``check_<key>`` columns.
_RESULTS = np.array(["pass", "warn", "fail"], dtype=object)
#: Words of the verdict's level.
_OUTCOMES = np.array(["PASS", "PASS with warnings", "FAIL"], dtype=object)


def _check_results(c: Chunk) -> dict[str, list[str]]:
    """``check_<key>`` columns: pass / warn / fail, '' where the check does not apply (an
    infeasible variant; the neglected link energy where the flywheel did not decide)."""
    n = len(c)
    out = {col: [""] * n for col in CHECK_COLUMNS}
    models = np.asarray(c.model, dtype=object)
    for ch in c.verdict.checks:
        words = _RESULTS[np.broadcast_to(np.asarray(ch.level), (n,))]
        applies = c.feasible & ((models == FLYWHEEL) if ch.key == "link_energy_share" else True)
        out[f"check_{ch.key}"] = np.where(applies, words, "").tolist()
    return out


def _listed(c: Chunk, level: int) -> list[str]:
    """Per variant, the keys of the checks at ``level`` joined by ';' ('infeasible' for failures
    of an infeasible design).  Built from one bit per check: a grid repeats few combinations, so
    each distinct one is joined once."""
    n = len(c)
    checks = c.verdict.checks
    code = np.zeros(n, np.int64)
    for j, ch in enumerate(checks):
        hit = np.broadcast_to(np.asarray(ch.level) == level, (n,)) & c.feasible
        code |= hit.astype(np.int64) << j
    # the force checks by their --fail-on names, as before the other checks existed
    short = {"mean_force": "mean", "peak_force": "peak"} if level == 2 else {}
    names = [short.get(ch.key, ch.key) for ch in checks]
    unique, inverse = np.unique(code, return_inverse=True)
    words = np.array(
        [";".join(nm for j, nm in enumerate(names) if (int(u) >> j) & 1) for u in unique.tolist()],
        dtype=object,
    )
    text = words[inverse.ravel()]
    if level == 2:
        text = np.where(c.feasible, text, "infeasible")
    return text.tolist()


def _failed_text(c: Chunk) -> list[str]:
    return _listed(c, 2)


def _outcomes(c: Chunk) -> list[str]:
    return _OUTCOMES[np.broadcast_to(c.level, (len(c),))].tolist()


def _models(c: Chunk) -> list[str]:
    return c.model


def _number_columns(c: Chunk) -> dict[str, np.ndarray]:
    """The chunk's numeric columns by name (:data:`NUMBER_COLUMNS`), in the units shown: the one
    table the JSON, CSV and Parquet writers convert."""
    return quantity_columns(c.evaluation)


def _text_columns(c: Chunk) -> dict[str, list]:
    """The chunk's text and boolean columns by name (those of :data:`FIXED_COLUMNS` not numeric)."""
    return {
        "feasible": c.feasible.tolist(),
        "reason": c.reason,
        "model": _models(c),
        "verdict": _outcomes(c),
        "pass": c.passed.tolist(),
        "failed": _failed_text(c),
        "warnings": _listed(c, 1),
        **_check_results(c),
    }


def chunk_columns(batch: Batch, c: Chunk) -> dict[str, list]:
    """The chunk's rows as columns of JSON-safe values (NaN -> None; angles in degrees)."""
    return {
        "name": batch.names(c.start, c.stop),
        **{k: _floats(v) for k, v in _number_columns(c).items()},
        **_text_columns(c),
    }


def chunk_rows(batch: Batch, c: Chunk, cols: dict[str, list] | None = None) -> list[dict[str, Any]]:
    """One JSON row per variant (the varied values under ``vary``)."""
    cols = cols or chunk_columns(batch, c)
    vals = c.values.tolist()
    rows = []
    for i in range(len(c)):
        row = {
            "name": cols["name"][i],
            "source": batch.source,
            "vary": {k: v for k, v in zip(batch.keys, vals[i])},
        }
        row.update({k: cols[k][i] for k in FIXED_COLUMNS})
        rows.append(row)
    return rows


def _csv_cell(text: str) -> str:
    if any(ch in text for ch in ',"\n\r'):
        return '"' + text.replace('"', '""') + '"'
    return text


#: Magnitudes below which orjson's text of a float is not repr's (see :func:`float_texts`).
SMALL_TEXT = 1e-4


def float_texts(values: list[float]) -> list[str]:
    """repr of each float (shortest round-trip text, as the csv module writes), '' for NaN/inf.

    orjson writes the shortest round-trip digits of a float about seven times faster than repr
    (0.55 ms against 4.2 ms for 10,000); its text is repr's except below 1e-4 in magnitude, where
    repr writes an exponent of two digits (1e-05, 1.5e-07) and orjson 0.00001 or 1.5e-7.  Those,
    and the non-finite values (orjson: null), are written by repr here, so the text is repr's for
    every float (``tests/output/test_batchfiles.py`` compares the two on random bit patterns).
    """
    if not values:
        return []
    out = orjson.dumps(values)[1:-1].decode().split(",")
    a = np.asarray(values, float)
    with np.errstate(invalid="ignore"):
        odd = np.nonzero(~((np.abs(a) >= SMALL_TEXT) & np.isfinite(a)) & (a != 0.0))[0]  # NaN, inf too
    for i in odd.tolist():
        v = values[i]
        out[i] = repr(v) if math.isfinite(v) else ""
    return out


def _csv_floats(a) -> list[str]:
    """:func:`float_texts` of an array's values.

    Grid columns repeat values (lengths depend on the geometry axes only), so each distinct
    value is formatted once (a column whose first 64 values are mostly distinct is formatted
    value by value, unsorted: the same text).
    """
    a = np.asarray(a, float)
    if np.unique(a[:64]).size * 4 <= 3 * min(a.size, 64):  # repeats among the first 64: sort them all
        uniq, inverse = np.unique(a, return_inverse=True)
        if uniq.size * 2 <= a.size:
            text = np.array(float_texts(uniq.tolist()), dtype=object)
            return text[inverse.ravel()].tolist()
    return float_texts(a.tolist())


def csv_text(batch: Batch, c: Chunk, vkeys: Sequence[str]) -> str:
    """The chunk's CSV lines (columns as :func:`columns`), built column-wise for speed."""
    n = len(c)
    names = batch.names(c.start, c.stop)
    if any(_csv_cell(x) != x for x in (batch.label,)):
        names = [_csv_cell(x) for x in names]
    cols: list[list[str]] = [names, [_csv_cell(batch.source)] * n]
    for k in vkeys:
        cols.append(_csv_floats(c.values[:, batch.keys.index(k)]) if k in batch.keys else [""] * n)
    bools = {True: "True", False: "False"}
    cache: dict = {None: ""}
    numbers, text = _number_columns(c), _text_columns(c)
    text["reason"] = [cache[r] if r in cache else cache.setdefault(r, _csv_cell(r)) for r in c.reason]
    for col in ("feasible", "pass"):
        text[col] = [bools[x] for x in text[col]]
    for col in ("model", "verdict"):  # a few words, each quoted once
        cells = {x: _csv_cell(x) for x in set(text[col])}
        text[col] = [cells[x] for x in text[col]]
    cols += [_csv_floats(numbers[k]) if k in numbers else text[k] for k in FIXED_COLUMNS]
    return "\n".join(map(",".join, zip(*cols))) + "\n" if n else ""


def json_text(batch: Batch, c: Chunk) -> str:
    """The chunk's JSON rows, one per line, each followed by ',\n'."""
    return "".join(json.dumps(r, allow_nan=False, ensure_ascii=False) + ",\n" for r in chunk_rows(batch, c))


def junit_text(batch: Batch, c: Chunk, fail_on: Sequence[str]) -> tuple[str, int, int]:
    """The chunk's JUnit testcases, with the number of failures and skipped."""
    cols = {
        "mean_force_N": _floats(c.mean_force),
        "peak_force_N": _floats(c.verdict_peak_force),
        "force_limit_N": _floats(c.force_limit),
    }
    cls = f"pumplink.batch.{Path(batch.source).stem}"
    parts, failures, skipped = [], 0, 0
    names = batch.names(c.start, c.stop)
    for name, (fail, skip) in zip(names, _junit_messages(batch, c, cols, fail_on)):
        parts.append(junit_case(name, cls, fail, skip))
        failures += fail is not None
        skipped += skip is not None
    return "".join(parts), failures, skipped


#: The text and boolean columns of a piston-pump batch's Parquet file (the rest are float64).
PISTON_TEXT = ("variant", "mechanism", "error", "model", "verdict")
PISTON_BOOLS = ("feasible", "pass")


def piston_parquet_schema():
    """The Parquet columns of a piston-pump batch, named and ordered as its CSV's."""
    import pyarrow as pa

    def kind(col: str):
        if col in PISTON_TEXT:
            return pa.string()
        return pa.bool_() if col in PISTON_BOOLS else pa.float64()

    return pa.schema([(col, kind(col)) for col in BATCH_COLUMNS])


def piston_parquet_table(rows: list[dict]):
    """Piston-pump batch rows as an Arrow table of :func:`piston_parquet_schema` (None: null)."""
    import pyarrow as pa

    schema = piston_parquet_schema()
    return pa.Table.from_pylist([{k: r[k] for k in BATCH_COLUMNS} for r in rows], schema=schema)


def parquet_schema(vkeys: Sequence[str]):
    """The Parquet columns, named and ordered as the CSV's (:func:`columns`): text for the name,
    the source and :data:`PARQUET_TEXT`, booleans for :data:`PARQUET_BOOLS`, float64 for the
    rest.  A cell that is empty in the CSV is null, except the lists ``failed`` and ``warnings``,
    which are empty text where nothing failed or warned."""
    import pyarrow as pa

    def kind(col: str):
        if col in ("name", "source", *PARQUET_TEXT):
            return pa.string()
        return pa.bool_() if col in PARQUET_BOOLS else pa.float64()

    return pa.schema([(col, kind(col)) for col in ["name", "source", *vkeys, *FIXED_COLUMNS]])


def parquet_table(batch: Batch, c: Chunk, vkeys: Sequence[str]):
    """The chunk's rows as an Arrow table of :func:`parquet_schema`, column by column from the
    chunk's arrays: the values of :func:`csv_text`, numbers as float64 (NaN and inf: null)."""
    import pyarrow as pa

    n = len(c)

    def num(a):
        a = np.asarray(a, float)
        return pa.array(a, pa.float64(), mask=~np.isfinite(a))

    def text(values, empty_is_null: bool = True):
        return pa.array([None if empty_is_null and v in ("", None) else v for v in values], pa.string())

    cols: dict[str, Any] = {
        "name": pa.array(batch.names(c.start, c.stop), pa.string()),
        "source": pa.array([batch.source] * n, pa.string()),
    }
    for k in vkeys:
        cols[k] = num(c.values[:, batch.keys.index(k)]) if k in batch.keys else pa.nulls(n, pa.float64())
    cols.update({k: num(v) for k, v in _number_columns(c).items()})
    for k, v in _text_columns(c).items():
        bools, listed = k in PARQUET_BOOLS, k in ("failed", "warnings")
        cols[k] = pa.array(v, pa.bool_()) if bools else text(v, empty_is_null=not listed)
    schema = parquet_schema(vkeys)
    return pa.Table.from_arrays([cols[f.name] for f in schema], schema=schema)


def render_chunk(
    batch: Batch, c: Chunk, fmt: str, vkeys: Sequence[str], fail_on: Sequence[str], junit: bool
) -> dict[str, Any]:
    """Text for one chunk (an Arrow table for parquet), built where the chunk was evaluated (a
    worker of the local pool) or by the driver (Dask)."""
    out: dict[str, Any] = {"data": None, "junit": None}
    if c.mechanism == "crank-slider":  # a piston pump's rows (docs/piston-pump.md)
        rows = batch_rows(batch.names(c.start, c.stop), c) if fmt != "table" else []
        if fmt == "csv":
            out["data"] = batch_csv(rows)
        elif fmt == "json":
            out["data"] = batch_json(rows)
        elif fmt == "parquet":
            out["data"] = piston_parquet_table(rows)
    elif fmt == "csv":
        out["data"] = csv_text(batch, c, vkeys)
    elif fmt == "json":
        out["data"] = json_text(batch, c)
    elif fmt == "parquet":
        out["data"] = parquet_table(batch, c, vkeys)
    if junit:
        out["junit"] = junit_text(batch, c, fail_on)
    return out


# ----------------------------------------------------------------------------- files
def _attr(text: str) -> str:
    """An XML attribute value (quoted) that is well-formed whatever ``text`` holds: a file path
    may hold characters XML 1.0 cannot carry even as references, which are written as escapes
    (:func:`~pumplink.errors.escape_control`); the names pumplink accepts pass unchanged."""
    return quoteattr(escape_control(text))


def junit_case(name: str, classname: str, failure: str | None, skipped: str | None) -> str:
    """One JUnit testcase: passed, or with a ``failure`` or ``skipped`` message."""
    head = f'    <testcase classname={_attr(classname)} name={_attr(name)} time="0"'
    if failure is not None:
        return (
            f'{head}>\n      <failure message={_attr(failure)} type="pumplink">'
            f"{escape(escape_control(failure))}</failure>\n    </testcase>\n"
        )
    if skipped is not None:
        return f"{head}>\n      <skipped message={_attr(skipped)}/>\n    </testcase>\n"
    return f"{head}/>\n"


def _junit_messages(batch: Batch, c: Chunk, cols: dict[str, list], fail_on: Sequence[str]):
    """(failure, skipped) message per variant: failures selected by --fail-on; infeasible
    variants not selected are reported as skipped, other unselected failures pass."""
    n = len(c)
    out = []
    lim = cols["force_limit_N"]
    feasible, mean_ok, peak_ok = (
        np.broadcast_to(np.asarray(a), (n,)).tolist() for a in (c.feasible, c.mean_ok, c.peak_ok)
    )

    models = c.model  # a list built on each access: once per chunk

    def per_variant(a):
        return None if a is None else np.broadcast_to(np.asarray(a), (n,))

    # the other checks' levels, values and limits per variant, once per chunk (when --fail-on
    # selects them)
    others = [
        (
            ch,
            per_variant(ch.level).tolist(),
            *map(per_variant, (ch.value, ch.warn_limit, ch.fail_limit, ch.relation)),
        )
        for ch in c.verdict.checks
        if ch.key not in ("mean_force", "peak_force") and ("checks" in fail_on or "warnings" in fail_on)
    ]
    for i in range(n):
        if not feasible[i]:
            msg = f"infeasible: {c.reason[i]}"
            out.append((msg, None) if "infeasible" in fail_on else (None, msg))
            continue
        bad = []
        if "mean" in fail_on and not mean_ok[i]:
            bad.append(f"mean force {cols['mean_force_N'][i]:.2f} N > limit {lim[i]:g} N")
        if "peak" in fail_on and not peak_ok[i]:
            if c.flywheel[i]:
                pk = float(c.least_peak_force[i])
                how = "the flywheel" if models[i] == FLYWHEEL else models[i]
                what = f"peak force with {how} (δ ≤ {float(c.speed_fluctuation[i]):g})"
                if pk == math.inf:
                    bad.append(
                        f"{what} infinite (the energy band J ω² δ is too small to carry the linkage through "
                        f"the dead centres: J = {float(c.inertia[i]):g} kg m^2)"
                    )
                else:
                    bad.append(
                        f"{what} undefined" if math.isnan(pk) else f"{what} {pk:.2f} N > limit {lim[i]:g} N"
                    )
            else:
                pk = cols["peak_force_N"][i]
                bad.append(
                    "peak force undefined (no crank angle outside the dead bands)"
                    if pk is None
                    else f"peak force {pk:.2f} N > limit {lim[i]:g} N"
                )
        for ch, levels, values, warn_limits, fail_limits, relations in others:
            level = levels[i]
            if (level == 2 and "checks" in fail_on) or (level == 1 and "warnings" in fail_on):
                value = float(values[i])
                limit = float((fail_limits if level == 2 else warn_limits)[i])
                side = ">" if relations[i] == "<=" else "<"
                word = "fails" if level == 2 else "warns"
                bad.append(f"{ch.key} {value:.4g} {ch.unit} {side} {limit:g} {ch.unit} ({word})")
        out.append(("; ".join(bad) if bad else None, None))
    return out


# ----------------------------------------------------------------------------- the stream
def _new_summary(total: int, fail_on, samples, chunk) -> dict[str, Any]:
    return {
        "variants": total,
        "pass": 0,
        "pass_with_warnings": 0,
        "fail": 0,
        "infeasible": 0,
        "failed_selected": 0,
        "fail_on": list(fail_on),
        "samples": samples,
        "chunk": f"{chunk[0]}/{chunk[1]}",
        "best": None,
    }


def _failing_checks(c: Chunk) -> np.ndarray:
    """How many of the verdict's checks each variant fails (0 for an infeasible one)."""
    n = len(c)
    count = np.zeros(n, np.int64)
    for ch in c.verdict.checks:
        count += np.broadcast_to(np.asarray(ch.level) == 2, (n,))
    return np.where(c.feasible, count, 0)


def _update_summary(s: dict, batch: Batch, c: Chunk, fail_on) -> None:
    """Add a chunk to the counts and to ``best``.

    ``best`` is the variant with the lowest verdict peak among those whose verdict passes (PASS
    or PASS with warnings; ``peak_force_N`` is the peak that decided: the flywheel's where
    ``model`` is flywheel).  While no variant passes it is the closest feasible one, with
    ``pass`` false: the fewest failing checks, then the lowest verdict peak.  Ties go to the
    first variant of the run.  ``_best_rank`` and ``_best_failed`` (the keys of the checks it
    fails) are for the renderers; the JSON leaves them out (:func:`public_summary`).
    """
    n = len(c)
    passed = np.broadcast_to(np.asarray(c.passed), (n,))
    feasible = np.broadcast_to(np.asarray(c.feasible), (n,))
    s["pass"] += int(passed.sum())
    s["pass_with_warnings"] += int((np.broadcast_to(c.level, (n,)) == 1).sum())
    s["infeasible"] += int((~feasible).sum())
    s["fail"] += int((feasible & ~passed).sum())
    s["failed_selected"] += int(c.failed(fail_on).sum())
    if not feasible.any():
        return
    verdict = np.asarray(c.verdict_peak_force, float)
    peak = np.where(np.isfinite(verdict), verdict, np.inf)
    failing = _failing_checks(c)
    group = np.where(passed, 0, 1)
    order = np.lexsort((peak, failing, group))  # stable: the first of equal ranks wins
    i = int(order[feasible[order]][0])
    rank = (int(group[i]), int(failing[i]), float(peak[i]))
    if s["best"] is None or rank < s["_best_rank"]:
        level = int(np.broadcast_to(c.level, (n,))[i])
        s["_best_rank"] = rank
        s["_best_failed"] = _listed(c, 2)[i] if not passed[i] else ""
        s["best"] = {
            "name": batch.name(c.start + i),
            "model": c.model[i],
            "peak_force_N": float(peak[i]) if math.isfinite(peak[i]) else None,
            "mean_force_N": float(c.mean_force[i]) if math.isfinite(c.mean_force[i]) else None,
            "verdict": str(_OUTCOMES[level]),
            "pass": bool(passed[i]),
        }


def public_summary(s: dict[str, Any]) -> dict[str, Any]:
    """The summary as the JSON gives it (without the renderers' private ``_`` keys)."""
    return {k: v for k, v in s.items() if not k.startswith("_")}


def write_stream(
    batches: Sequence[Batch],
    results: Iterable[tuple[Chunk, dict]],
    total: int,
    fmt: str,
    out: Path | None,
    junit: Path | None,
    fail_on: Sequence[str],
    samples: int,
    chunk: tuple[int, int] = (1, 1),
    advance: Callable[[int], None] | None = None,
):
    """Write the rendered chunks (from ``batch.run(..., post=render_chunk)``) as they come.

    csv/json rows go to ``out`` (atomically) or stdout, parquet rows to ``out`` (row groups of
    :data:`PARQUET_ROWS`); JUnit to ``junit`` (atomically).
    Returns (summary, table rows): with ``table`` the rows to show (all when ``total`` <=
    :data:`TABLE_ROWS`, else up to that many failures).
    """
    summary = _new_summary(total, fail_on, samples, chunk)
    table_rows: list[dict] = []
    with contextlib.ExitStack() as stack:
        data = parquet = None
        if fmt in ("csv", "json"):
            data = stack.enter_context(atomic_write(out)) if out is not None else sys.stdout
        elif fmt == "parquet":
            import pyarrow as pa
            import pyarrow.parquet as pq

            target = stack.enter_context(atomic_write(out, binary=True))
            schema = (
                piston_parquet_schema()
                if batches and batches[0].mechanism == "crank-slider"
                else parquet_schema(varied_keys(batches))
            )
            parquet = stack.enter_context(pq.ParquetWriter(target, schema, compression="zstd"))
            gathered: list = []

            def flush_rows(final: bool = False) -> None:
                if gathered and (final or sum(t.num_rows for t in gathered) >= PARQUET_ROWS):
                    parquet.write_table(pa.concat_tables(gathered), row_group_size=PARQUET_ROWS * 2)
                    gathered.clear()

        jfile = stack.enter_context(atomic_write(junit)) if junit is not None else None
        suite = (
            stack.enter_context(tempfile.TemporaryFile("w+", encoding="utf-8")) if junit is not None else None
        )
        counts = {"tests": 0, "failures": 0, "skipped": 0}
        current = -1

        def flush_suite():
            if current < 0:
                return
            jfile.write(
                f'  <testsuite name={_attr(batches[current].source)} tests="{counts["tests"]}" '
                f'failures="{counts["failures"]}" errors="0" skipped="{counts["skipped"]}">\n'
            )
            suite.seek(0)
            shutil.copyfileobj(suite, jfile)  # a finished suite's testcases, streamed from disk
            jfile.write("  </testsuite>\n")
            suite.seek(0)
            suite.truncate()

        if jfile is not None:
            jfile.write('<?xml version="1.0" encoding="UTF-8"?>\n<testsuites name="pumplink batch">\n')
        piston = bool(batches) and batches[0].mechanism == "crank-slider"
        if fmt == "csv":
            head = BATCH_COLUMNS if piston else columns(batches)
            data.write(",".join(_csv_cell(x) for x in head) + "\n")
        pending = ""  # json: the previous row's trailing separator is dropped before "]"
        if fmt == "json":
            data.write('{\n  "variants": [' if piston else '{"variants": [\n')
        for c, text in results:
            b = batches[c.batch]
            _update_summary(summary, b, c, fail_on)
            if fmt == "csv":
                data.write(text["data"])
            elif fmt == "json" and len(c):
                data.write(("\n    " if piston and not pending else "") + pending)
                pending = text["data"]
            elif fmt == "parquet":
                gathered.append(text["data"])
                flush_rows()
            elif fmt == "table" and len(table_rows) < TABLE_ROWS:
                show = np.ones(len(c), bool) if total <= TABLE_ROWS else c.failed(fail_on)
                pick = np.nonzero(show)[0][: TABLE_ROWS - len(table_rows)].tolist()
                if pick:
                    where = row_identity(b, c, pick)
                if pick and piston:
                    rows = batch_rows(b.names(c.start, c.stop), c)
                    failed = c.failed(fail_on)
                    peaks = _floats(c.verdict_peak_force)  # the peak that decided, as the summary's
                    table_rows.extend(
                        {**rows[i], **w, "failed": bool(failed[i]), "peak_force_N": peaks[i]}
                        for i, w in zip(pick, where)
                    )
                elif pick:
                    cc = chunk_columns(b, c)
                    table_rows.extend(
                        {"name": cc["name"][i], **w, **{k: cc[k][i] for k in FIXED_COLUMNS}}
                        for i, w in zip(pick, where)
                    )
            if jfile is not None:
                if c.batch != current:
                    flush_suite()
                    current = c.batch
                    counts = {"tests": 0, "failures": 0, "skipped": 0}
                cases, failures, skipped = text["junit"]
                suite.write(cases)
                counts["tests"] += len(c)
                counts["failures"] += failures
                counts["skipped"] += skipped
            if advance is not None:
                advance(len(c))
        if fmt == "json" and piston:  # indented, as the piston pump's force JSON
            data.write(
                (pending.removesuffix(",\n    ") + "\n  ]" if pending else "]")
                + f',\n  "failed": {summary["failed_selected"]},\n  "total": {summary["variants"]}\n}}\n'
            )
        elif fmt == "json":
            data.write(
                pending.removesuffix(",\n")
                + ("\n" if pending else "")
                + '],\n"summary": '
                + json.dumps(public_summary(summary), allow_nan=False, ensure_ascii=False)
                + "}\n"
            )
        if parquet is not None:
            flush_rows(final=True)
        if jfile is not None:
            flush_suite()
            jfile.write("</testsuites>\n")
        if data is sys.stdout:
            data.flush()
    return summary, table_rows
