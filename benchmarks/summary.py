"""The one table at the end of `make bench`: every figure the bench scripts recorded, its target
beside it and whether it is met.

Reads the JSON lines that ``benchmarks/_record.py`` appended (the file named on the command line,
else ``$PUMPLINK_BENCH_OUT``), in the order they were taken, one section per script.

    .venv/bin/python benchmarks/summary.py build/bench.jsonl
"""

from __future__ import annotations

import json
import os
import sys
from pathlib import Path

from _record import ENV, machine
from rich import box
from rich.console import Console
from rich.markup import escape
from rich.table import Table


def figure(value: float, unit: str) -> str:
    """A figure with three significant digits (thousands separated) and its unit."""
    if unit == "x":
        return f"{value:.1f}x" if value < 100 else f"{value:,.0f}x"
    if abs(value) >= 1000:
        text = f"{value:,.0f}"
    elif abs(value) >= 100:
        text = f"{value:.0f}"
    else:
        text = f"{value:.3g}"
    return f"{text} {unit}"


def load_rows(path: Path) -> list[dict]:
    return [json.loads(line) for line in path.read_text(encoding="utf-8").splitlines() if line.strip()]


def render(rows: list[dict], console: Console) -> None:
    loads = [r["load"] for r in rows if r.get("load") is not None]
    console.print(f"machine: {escape(machine())}")
    if loads:
        console.print(
            f"load average (1 min) while measuring: {min(loads):.1f} to {max(loads):.1f} on "
            f"{os.cpu_count()} cores (above 0 means other jobs shared the machine)"
        )
    table = Table(title="make bench: every figure and its target", title_justify="left", box=box.SIMPLE_HEAD)
    table.add_column("figure", ratio=1, overflow="fold")
    table.add_column("measured", justify="right", no_wrap=True)
    table.add_column("target", justify="right", no_wrap=True)
    table.add_column("met", no_wrap=True)
    script = None
    for r in rows:
        if r["script"] != script:
            script = r["script"]
            table.add_row(f"[bold]{escape(script)}[/]", "", "", "", end_section=False)
        name = escape(r["name"]) + (f"\n[dim]{escape(r['note'])}[/]" if r.get("note") else "")
        met = {True: "yes", False: "[bold]NO[/]", None: "–"}[r.get("met")]
        table.add_row(name, figure(r["value"], r["unit"]), escape(r.get("target") or "–"), met)
    console.print(table)
    judged = [r for r in rows if r.get("met") is not None]
    missed = [r["name"] for r in judged if not r["met"]]
    console.print(f"{len(judged) - len(missed)} of {len(judged)} targets met" + (":" if missed else "."))
    for name in missed:
        console.print(f"  not met: {escape(name)}")


def main() -> int:
    source = sys.argv[1] if len(sys.argv) > 1 else os.environ.get(ENV)
    if not source or not Path(source).is_file():
        sys.stderr.write(f"no figures to summarise: give the file the bench scripts wrote (or set {ENV})\n")
        return 2
    render(load_rows(Path(source)), Console())
    return 0


if __name__ == "__main__":
    sys.exit(main())
