"""How a benchmark script hands its figures to the summary table of `make bench`.

Every ``benchmarks/bench_*.py`` prints its own report and also calls :func:`record` once per
figure; with ``PUMPLINK_BENCH_OUT`` set (``make bench`` sets it) each call appends one JSON line
to that file, and ``benchmarks/summary.py`` renders all of them as one table at the end.
Without the variable :func:`record` does nothing, so a script run by hand behaves as before.

Every script also has a smoke mode (``--smoke`` on its command line, or ``PUMPLINK_BENCH_SMOKE=1``
in the environment): the smallest size, one repeat, each measurement of the full run taken once
(every spec, command and backend it runs; only the pinned old install of bench_grid_baseline.py is
left out, and pylinkage where it is not installed) and no target judged (its figures are recorded
with ``met`` null).  ``make test`` runs each script so
(tests/test_benchmarks_smoke.py), so a moved API cannot silently break ``make bench``.

A line: ``{"script", "name", "value", "unit", "target", "met", "note", "load"}``; ``target``
is the goal in words ("<= 0.25 s") or null, ``met`` true/false or null without a target,
``load`` the 1-minute load average when the figure was taken (the machine is shared).
"""

from __future__ import annotations

import json
import math
import os
import platform
import sys
from pathlib import Path

#: The environment variable naming the JSON-lines file the figures are appended to.
ENV = "PUMPLINK_BENCH_OUT"
#: The environment variable that puts every script in smoke mode (as ``--smoke`` does).
SMOKE_ENV = "PUMPLINK_BENCH_SMOKE"
#: The help of each script's ``--smoke`` option.
SMOKE_HELP = "smoke run: the smallest size, one repeat, no target judged (make test runs it)"


def smoke() -> bool:
    """Whether this run is a smoke run: ``--smoke`` on the command line or ``PUMPLINK_BENCH_SMOKE``
    set to anything but empty or 0.  The figures of a smoke run measure nothing worth reading."""
    return "--smoke" in sys.argv[1:] or os.environ.get(SMOKE_ENV, "") not in ("", "0")


def repeats(n: int) -> int:
    """How many times to repeat a measurement: ``n``, or once in a smoke run."""
    return 1 if smoke() else n


def judged(met: bool) -> str:
    """How a line says whether a target is met: yes, NO, or, in a smoke run, that it is not judged."""
    if smoke():
        return "not judged (smoke run)"
    return "yes" if met else "NO"


def record(
    name: str, value: float, unit: str, target: str | None = None, met: bool | None = None, note: str = ""
):
    """Append one figure to ``$PUMPLINK_BENCH_OUT`` (nothing when it is unset).

    Parameters
    ----------
    name : what was measured, as a reader would say it ("pumplink synth SPEC, start-up").
    value : the figure.
    unit : its unit ("s", "ms", "designs/s", "x" for a ratio).
    target : the goal with its comparison ("<= 0.25 s", ">= 5x"), or None when there is none.
    met : whether the figure meets ``target``; None without a target, and in a smoke run.
    note : a few words of context (a reference figure beside it, how it was measured).
    """
    if smoke():
        met = None
    path = os.environ.get(ENV)
    if not path:
        return
    row = {
        "script": Path(sys.argv[0]).name,
        "name": name,
        "value": float(value),
        "unit": unit,
        "target": target,
        "met": None if met is None else bool(met),
        "note": note,
        "load": os.getloadavg()[0],
    }
    with open(path, "a", encoding="utf-8") as f:
        f.write(json.dumps(row) + "\n")


def machine() -> str:
    """CPU model, cores, Python and numpy versions of this machine (numpy's without importing it)."""
    model = "unknown CPU"
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                model = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    try:
        from importlib.metadata import version

        np_version = f", numpy {version('numpy')}"
    except Exception:  # noqa: BLE001 -- the header only
        np_version = ""
    return f"{model}, {os.cpu_count()} cores, Python {platform.python_version()}{np_version}"


def result(
    what: str, figure: str, target: str, met: bool, beside: str = "", value: float = math.nan, unit: str = ""
) -> None:
    """One ``RESULT`` line per target (the figure, the target, whether it is met and what is
    beside it), and the figure for the summary table (:func:`record`)."""
    extra = f"  [{beside}]" if beside else ""
    print(f"RESULT {what}: {figure} (target {target}) met: {judged(met)}{extra}")
    record(what, value, unit, target, met, beside)
