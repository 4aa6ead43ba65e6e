"""`pumplink slotted`: crank and slotted lever (quick return) from K and the stroke."""

from __future__ import annotations

from typing import Annotated, Optional

import typer

from pumplink.cli.common import Format, FormatOpt, app


@app.command()
def slotted(
    time_ratio: Annotated[
        float, typer.Option("--time-ratio", "-k", help="Time ratio K > 1 (slow/fast stroke).")
    ],
    stroke: Annotated[
        float,
        typer.Option("--stroke", "-H", help="Chord between the lever tip's extremes (any length unit)."),
    ],
    frame: Annotated[
        Optional[float],
        typer.Option(
            help="Distance d of the crank pivot from the lever pivot (default: the largest whose slot "
            "holds the block).",
            show_default=False,
        ),
    ] = None,
    fmt: FormatOpt = Format.table,
) -> None:
    """Crank and slotted lever (oscillating-lever quick return) from K and the tip's stroke.

    The lever swings through ψ = 180°(K − 1)/(K + 1); the lever is H / (2 sin(ψ/2)) long and the
    crank d·sin(ψ/2) (docs/mechanisms.md §2).  The mechanism is run through a full crank turn and
    the measured swing, K and stroke are printed beside the asked ones.  Exit 0 if it exists and
    the simulation agrees, 1 if no slotted lever meets the task (K = 1, or a frame so long that
    the slot cannot hold the block), 2 for bad input.

    Example: [bold]pumplink slotted --time-ratio 1.5 --stroke 0.3[/]
    """
    from pumplink.output.mechanisms import render_synthesis, synthesis_labels, synthesis_row
    from pumplink.studies.textbook import slotted as synthesise

    rep = synthesise(time_ratio, stroke, frame)
    render_synthesis(synthesis_row(rep), synthesis_labels(rep), fmt.value)
    raise typer.Exit(0 if rep.agrees else 1)
