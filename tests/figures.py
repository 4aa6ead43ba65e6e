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


def run(*args, cwd=None, env=None, pre: str = "", log=None) -> subprocess.CompletedProcess:
    """``pumplink ARGS`` through its entry point (``pumplink.cli.main``) with the capture on (with
    ``log``, every figure saved by any route is described there too: :func:`capture`)."""
    code = (
        (PRE if log is None else PRE.replace("capture()", f"capture(log={str(log)!r})"))
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


def capture(log: str | None = None) -> None:
    """Describe every figure pumplink saves in ``<path>.json`` before saving it; with ``log``, also
    every figure any route saves (a template page, an animation frame), one JSON line each."""
    from pumplink.output import charts

    original = charts.save

    def save(fig, path, **kwargs):
        Path(f"{path}.json").write_text(json.dumps(describe(fig)), encoding="utf-8")
        return original(fig, path, **kwargs)

    charts.save = save
    if log is not None:
        from matplotlib.figure import Figure

        savefig = Figure.savefig

        def logged(fig, *args, **kwargs):
            with open(log, "a", encoding="utf-8") as f:
                f.write(json.dumps(describe(fig)) + "\n")
            return savefig(fig, *args, **kwargs)

        Figure.savefig = logged


def logged(log) -> list[dict]:
    """The descriptions :func:`capture` wrote to ``log``, in the order the figures were saved."""
    return [json.loads(line) for line in Path(log).read_text(encoding="utf-8").splitlines()]


def _floats(values) -> list:
    return [None if v != v else float(v) for v in (float(x) for x in values)]


def box(artist, fig, renderer) -> list[float]:
    """An artist's extent as drawn, (x0, y0, x1, y1) in fractions of the figure."""
    b = artist.get_window_extent(renderer)
    return [b.x0 / fig.bbox.width, b.y0 / fig.bbox.height, b.x1 / fig.bbox.width, b.y1 / fig.bbox.height]


def describe(fig) -> dict:
    """Titles, labels, legend entries, lines (label, marker, x, y), scatter offsets and texts, and
    where the title, the texts and the lines are drawn (renderer extents, after the layout)."""
    fig.canvas.draw()  # the layout as saved: extents are those of the file
    renderer = fig.canvas.get_renderer()
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
                "title_box": box(ax.title, fig, renderer),
                "text_boxes": [box(t, fig, renderer) for t in ax.texts],
                "box": box(ax, fig, renderer),
                "xlim": _floats(ax.get_xlim()),
                "ylim": _floats(ax.get_ylim()),
                "gids": {
                    ln.get_gid(): {
                        "x": _floats(ln.get_xdata()),
                        "y": _floats(ln.get_ydata()),
                        "box": box(ln, fig, renderer),
                    }
                    for ln in ax.get_lines()
                    if ln.get_gid() and len(ln.get_xdata())
                },
            }
        )
    suptitle = fig._suptitle.get_text() if getattr(fig, "_suptitle", None) is not None else ""
    legends = [t.get_text() for lg in fig.legends for t in lg.get_texts()]
    return {
        "axes": axes,
        "suptitle": suptitle,
        "figure_legend": legends,
        "figure_texts": [t.get_text() for t in fig.texts],
    }


def read(path) -> dict:
    """The description :func:`capture` wrote for the chart ``path``."""
    return json.loads(Path(f"{path}.json").read_text(encoding="utf-8"))


def marked(ax: dict, marker: str) -> list[tuple[float, float]]:
    """The single points drawn with ``marker`` on an axes description."""
    return [(ln["x"][0], ln["y"][0]) for ln in ax["lines"] if ln["marker"] == marker and len(ln["x"]) == 1]
