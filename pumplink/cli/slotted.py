"""`pumplink slotted`: crank and slotted lever (quick return), synthesis from K or analysis."""

from __future__ import annotations

from typing import Annotated, Optional

import typer

from pumplink.cli.common import Format, FormatOpt, app, optional


def _length(*names: str, text: str):
    return Annotated[Optional[float], typer.Option(*names, help=text, show_default=False)]


@app.command()
def slotted(
    time_ratio: optional(
        float, "Time ratio K > 1 (slow/fast stroke); leave out to analyse.", "--time-ratio", "-k"
    ) = None,
    stroke: _length(
        "--stroke", "-H", text="Chord between the lever tip's extremes (any length unit)."
    ) = None,
    frame: _length("--frame", text="Distance d of the crank pivot from the lever pivot.") = None,
    crank: _length("--crank", text="Crank length r.") = None,
    lever: _length("--lever", text="Lever length l (lever pivot to tip).") = None,
    fmt: FormatOpt = Format.table,
) -> None:
    """Crank and slotted lever (oscillating-lever quick return): synthesis from K, or analysis.

    With --time-ratio K the lever swings through ψ = 180°(K − 1)/(K + 1) and crank/frame =
    sin(ψ/2) (docs/mechanisms.md §2): give --crank or --frame for the size (neither: from the
    stroke), and --stroke or --lever for the lever (neither: the shortest lever that holds the
    block, l = frame + crank).  Without K, --crank and --frame describe a given slotted lever
    (with --lever, or --stroke to find the lever): its K, swing, stroke and dead centres.  Every
    value is also measured by running the mechanism through a full crank turn.  Verdict: the
    largest pressure angle (0° for the block on the lever) and the simulation, which must
    reproduce every value.  Exit 0 on PASS or PASS with warnings, 1 on FAIL or if no slotted lever
    meets the task (K = 1, a slot that cannot hold the block, crank not shorter than the frame),
    2 for bad input.

    Example: [bold]pumplink slotted --time-ratio 1.5 --stroke 0.3[/]

    Example: [bold]pumplink slotted --time-ratio 1.7 --crank 30 --stroke 120[/]

    Example: [bold]pumplink slotted --crank 120 --frame 240 --lever 450[/]
    """
    from pumplink.output.mechanisms import render_synthesis, synthesis_labels, synthesis_row
    from pumplink.studies.textbook import slotted as solve

    rep = solve(time_ratio, stroke, frame, crank=crank, lever=lever)
    render_synthesis(synthesis_row(rep), synthesis_labels(rep), fmt.value)
    raise typer.Exit(0 if rep.passed else 1)
