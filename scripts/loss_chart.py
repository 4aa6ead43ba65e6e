"""The loss model of docs/water.md §2a: its efficiency against rope speed and head (a chart), and
which efficiency decides where (a table), both from pumplink.models.losses and the rule of
pumplink.evaluate.designs.

    .venv/bin/python scripts/loss_chart.py                  # write docs/losses.png, print the table
    .venv/bin/python scripts/loss_chart.py --check          # exit 1 if docs/water.md's table differs

The table sits in docs/water.md between the lines ``<!-- losses table -->`` and
``<!-- end losses table -->``; tests/test_losses_docs.py holds it to this script.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

from pumplink.constants import (
    DEFAULT_EFFICIENCY,
    DEFAULT_VOLUMETRIC_EFFICIENCY,
    LOSS_SHARE,
    ROPE_SPEED_RANGE_M_S,
)
from pumplink.models import losses as L

ROOT = Path(__file__).resolve().parents[1]
CHART = ROOT / "docs" / "losses.png"
PAGE = ROOT / "docs" / "water.md"
START, END = "<!-- losses table -->\n", "<!-- end losses table -->\n"
#: The bores of the table and the chart [m]: the standard nominal sizes and the village design's 23 mm.
BORES = (0.0127, 0.01905, 0.023, 0.0254, 0.03175, 0.0381)
SPEEDS = (0.4, 0.6, 0.9, 1.2, 1.5, 1.8, 2.4)  # rope speeds of the table [m/s]
CONSTANT = DEFAULT_EFFICIENCY * DEFAULT_VOLUMETRIC_EFFICIENCY


def _decides(eta):
    return ~(L.off_by(CONSTANT, eta) <= LOSS_SHARE)


def constant_intervals(d: float, head: float = 10.0) -> list[tuple[float, float]]:
    """The rope speeds [m/s] between 0.1 and 3 m/s at which the constants decide for bore ``d`` (the
    loss model within the share of them), on a 1 mm/s grid: the runs (lowest, highest)."""
    v = np.arange(0.100, 3.0005, 0.001)
    ok = ~_decides(L.overall_efficiency(d, v, head))
    edges = np.flatnonzero(np.diff(np.r_[0, ok.astype(int), 0]))
    return [(float(v[a]), float(v[b - 1])) for a, b in zip(edges[::2], edges[1::2])]


def table(head: float = 10.0) -> str:
    """Markdown: the loss model's overall efficiency by bore and rope speed at ``head``, in bold where
    it decides (more than the share off the constants' product), and where the constants decide."""
    lines = [
        "| bore | " + " | ".join(f"{v:g} m/s" for v in SPEEDS) + " | the constants decide |",
        "|---|" + "---:|" * len(SPEEDS) + "---|",
    ]
    for d in BORES:
        cells = []
        for v in SPEEDS:
            eta = float(L.overall_efficiency(d, v, head))
            cells.append(f"**{eta:.3f}**" if _decides(eta) else f"{eta:.3f}")
        runs = constant_intervals(d, head)
        where = " and ".join(f"{a:.2f}-{b:.2f} m/s" for a, b in runs) or "nowhere"
        lines.append(f"| {d * 1000:g} mm | " + " | ".join(cells) + f" | {where} |")
    return "\n".join(lines) + "\n"


def chart(path: Path = CHART) -> None:
    """Overall efficiency against rope speed (each bore, 10 m) and against head (1.2 m/s)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (a, b) = plt.subplots(1, 2, figsize=(10, 4.4))
    fig.subplots_adjust(left=0.07, right=0.98, bottom=0.17, top=0.86, wspace=0.15)
    v = np.linspace(0.2, 2.6, 400)
    h = np.linspace(0.2, 40.0, 400)
    for ax in (a, b):
        ax.axhspan(CONSTANT / (1 + LOSS_SHARE), CONSTANT / (1 - LOSS_SHARE), color="0.9", zorder=0)
        ax.axhline(CONSTANT, color="0.4", lw=1, ls="--")
    for d in BORES:
        a.plot(v, L.overall_efficiency(d, v, 10.0), label=f"{d * 1000:g} mm")
        b.plot(h, L.overall_efficiency(d, 1.2, h), label=f"{d * 1000:g} mm")
    for x in ROPE_SPEED_RANGE_M_S:
        a.axvline(x, color="0.3", lw=0.8, ls=":")
    a.set(
        xlabel="rope speed [m/s]",
        ylabel="overall efficiency η_f η_v [-]",
        ylim=(0.3, 0.8),
        title="against rope speed, 10 m head",
    )
    b.set(xlabel="head [m]", ylim=(0.3, 0.8), title="against head, rope at 1.2 m/s")
    a.legend(title="rising-main bore", fontsize=8, loc="lower center")
    fig.text(
        0.5, 0.005, "grey band: within 5 % of the constants' 0.6525, which then decide; dotted: the "
        "rope-speed range 0.6-1.8 m/s; the head enters only below one piston spacing (1 m)",
        ha="center", fontsize=8,
    )  # fmt: skip
    fig.suptitle("The rope pump's losses by design (docs/water.md §2a)")
    fig.savefig(path, dpi=110)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--check", action="store_true", help="compare docs/water.md's table, write nothing")
    args = ap.parse_args()
    text = table()
    page = PAGE.read_text(encoding="utf-8")
    i, j = page.index(START) + len(START), page.index(END)
    if args.check:
        if page[i:j] != text:
            sys.stdout.write("docs/water.md's losses table differs from scripts/loss_chart.py:\n" + text)
            return 1
        return 0
    PAGE.write_text(page[:i] + text + page[j:], encoding="utf-8")
    chart()
    sys.stdout.write(text)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
