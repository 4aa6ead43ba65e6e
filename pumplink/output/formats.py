"""The one output dispatch: number formatting, JSON and CSV writers, the console, progress.

Degrees appear in the output layer only; the library works in radians.  NaN becomes ``null``
in JSON, an empty cell in CSV and "—" (or "∞") in tables.
"""

from __future__ import annotations

import contextlib
import csv
import json
import math
import os
import sys
import time
from collections.abc import Callable, Iterable, Iterator
from typing import Any

import numpy as np

FORMATS = ("table", "json", "csv")


def num(x) -> float | None:
    """A JSON-safe float: None for None, NaN and inf."""
    if x is None:
        return None
    x = float(x)
    return x if math.isfinite(x) else None


def deg(x) -> float | None:
    return num(np.degrees(x))


# ----------------------------------------------------------------------------- progress
@contextlib.contextmanager
def progress(
    total: int, label: str = "batch", enabled: bool | None = None, delay: float = 1.0
) -> Iterator[Callable[[int], None]]:
    """``advance(n)`` for a Rich progress bar on stderr, shown only on a terminal and only once
    the run has taken longer than ``delay`` seconds."""
    if enabled is None:
        enabled = sys.stderr.isatty()
    state: dict[str, Any] = {"done": 0, "bar": None, "t0": time.monotonic()}

    def advance(n: int) -> None:
        state["done"] += n
        if not enabled:
            return
        if state["bar"] is None and time.monotonic() - state["t0"] > delay:
            from rich.console import Console
            from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeRemainingColumn

            bar = Progress(
                TextColumn(label),
                BarColumn(),
                MofNCompleteColumn(),
                TimeRemainingColumn(),
                console=Console(stderr=True),
                transient=True,
            )
            bar.start()
            state["bar"], state["task"] = bar, bar.add_task(label, total=total)
        if state["bar"] is not None:
            state["bar"].update(state["task"], completed=state["done"])

    try:
        yield advance
    finally:
        if state["bar"] is not None:
            state["bar"].stop()


# ----------------------------------------------------------------------------- text output
def write_json(obj, out) -> None:
    # ASCII JSON (\u escapes): valid whatever the terminal's or pipe's encoding.
    out.write(json.dumps(obj, indent=2, allow_nan=False) + "\n")


def _flatten(row: dict[str, Any], prefix: str = "") -> dict[str, Any]:
    flat: dict[str, Any] = {}
    for k, v in row.items():
        if isinstance(v, dict):
            flat.update(_flatten(v, f"{prefix}{k}_"))
        elif isinstance(v, list) and k == "rocker_pivot":
            flat[f"{prefix}rocker_pivot_x"], flat[f"{prefix}rocker_pivot_y"] = v
        elif isinstance(v, list):
            continue  # checks: in JSON and the table only
        else:
            flat[prefix + k] = "" if v is None else v
    return flat


def write_csv(rows: Iterable[dict[str, Any]], out) -> None:
    """CSV with a header from the first row; nested keys flattened with '_'."""
    rows = [_flatten(r) for r in rows]
    if not rows:
        return
    w = csv.DictWriter(out, fieldnames=list(rows[0]), lineterminator="\n")
    w.writeheader()
    w.writerows(rows)


#: Width of tables and text when the output is not a terminal and ``COLUMNS`` is not set.
DEFAULT_WIDTH = 80


def width() -> int | None:
    """``COLUMNS`` when set to a sane width (20-1000), else None."""
    try:
        w = int(os.environ.get("COLUMNS", ""))
    except ValueError:
        return None
    return w if 20 <= w <= 1000 else None


def console(file=None):
    """A Rich console: colour only on a terminal (and never with NO_COLOR); the terminal's width,
    else ``COLUMNS``, else 80 columns when piped."""
    from rich.console import Console

    file = file or sys.stdout
    tty = hasattr(file, "isatty") and file.isatty()
    w = width()
    if w is None and not tty:
        w = DEFAULT_WIDTH
    return Console(file=file, highlight=False, width=w, soft_wrap=False)


def fmt(x, fmt="{:.3f}", none="—") -> str:
    """``x`` formatted, or ``none`` for None, NaN and inf."""
    return none if x is None or not math.isfinite(float(x)) else fmt.format(float(x))
