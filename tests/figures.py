"""What a chart shows, read from the matplotlib figure a pumplink command saves (test support).

A chart's bytes say little (a PNG of the wrong curve is still a PNG), so the chart tests run the
real command in a subprocess with :data:`PRE` run first: it wraps
``pumplink.output.charts.save`` so that every figure saved is also described, as plain data, in
``<chart file>.json`` (:func:`describe`: titles, axis labels, legend entries, the drawn lines and
markers with their data, the texts and annotations), then saved as usual.
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

TESTS = Path(__file__).resolve().parent

#: Python run before the CLI in the subprocess (see the module docstring).
PRE = f"import sys; sys.path.insert(0, {str(TESTS)!r}); import figures; figures.capture(); "


def run(*args, cwd=None, env=None, pre: str = "") -> subprocess.CompletedProcess:
    """``pumplink ARGS`` through its entry point (``pumplink.cli.main``) with the capture on."""
    code = (
        PRE
        + pre
        + f"sys.argv = ['pumplink', *{[str(a) for a in args]!r}]; from pumplink.cli import main; main()"
    )
    return subprocess.run(
        [sys.executable, "-c", code],
        cwd=cwd,
        env=env,
        capture_output=True,
        text=True,
        check=False,
        timeout=300,
    )


def capture() -> None:
    """Describe every figure pumplink saves in ``<path>.json`` before saving it."""
    from pumplink.output import charts

    original = charts.save

    def save(fig, path, **kwargs):
        Path(f"{path}.json").write_text(json.dumps(describe(fig)), encoding="utf-8")
        return original(fig, path, **kwargs)

    charts.save = save


def _floats(values) -> list:
    return [None if v != v else float(v) for v in (float(x) for x in values)]


def describe(fig) -> dict:
    """Titles, labels, legend entries, lines (label, marker, x, y), scatter offsets and texts."""
    axes = []
    for ax in fig.axes:
        legend = ax.get_legend()
        axes.append(
            {
                "title": ax.get_title(),
                "xlabel": ax.get_xlabel(),
                "ylabel": ax.get_ylabel(),
                "xscale": ax.get_xscale(),
                "yscale": ax.get_yscale(),
                "legend": [t.get_text() for t in legend.get_texts()] if legend else [],
                "lines": [
                    {
                        "label": line.get_label(),
                        "marker": str(line.get_marker()),
                        "x": _floats(line.get_xdata()),
                        "y": _floats(line.get_ydata()),
                    }
                    for line in ax.get_lines()
                ],
                "scatter": [
                    _floats(p) for c in ax.collections if hasattr(c, "get_offsets") for p in c.get_offsets()
                ],
                "contour_levels": [
                    _floats(c.levels) for c in ax.collections if hasattr(c, "levels") and c.levels is not None
                ],
                "texts": [t.get_text() for t in ax.texts],
            }
        )
    suptitle = fig._suptitle.get_text() if getattr(fig, "_suptitle", None) is not None else ""
    legends = [t.get_text() for lg in fig.legends for t in lg.get_texts()]
    return {"axes": axes, "suptitle": suptitle, "figure_legend": legends}


def read(path) -> dict:
    """The description :func:`capture` wrote for the chart ``path``."""
    return json.loads(Path(f"{path}.json").read_text(encoding="utf-8"))


def marked(ax: dict, marker: str) -> list[tuple[float, float]]:
    """The single points drawn with ``marker`` on an axes description."""
    return [(ln["x"][0], ln["y"][0]) for ln in ax["lines"] if ln["marker"] == marker and len(ln["x"]) == 1]
