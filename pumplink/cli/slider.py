"""`pumplink slider`: crank-slider synthesis (the textbook's Tasks 1 and 2), checked by simulation."""

from __future__ import annotations

from typing import Annotated, Optional

import typer

from pumplink.cli.common import Format, FormatOpt, app


@app.command()
def slider(
    stroke: Annotated[float, typer.Option("--stroke", "-H", help="Slider stroke H (any length unit).")],
    rod_ratio: Annotated[float, typer.Option("--rod-ratio", "-L", help="Rod ratio L = rod/crank > 1.")],
    time_ratio: Annotated[
        Optional[float],
        typer.Option(
            "--time-ratio", "-k", help="Time ratio K >= 1 (Task 2: the offset follows).", show_default=False
        ),
    ] = None,
    offset_ratio: Annotated[
        float,
        typer.Option("--offset-ratio", help="Offset ratio e/r (Task 1 only; 0: a central crank-slider)."),
    ] = 0.0,
    fmt: FormatOpt = Format.table,
) -> None:
    """Crank-slider (piston drive) from its stroke and rod ratio, and the time ratio if given.

    Task 1 (no --time-ratio): crank r = H/h with h = 2 for a central crank-slider.  Task 2: the
    offset crank-slider with time ratio K (docs/mechanisms.md §1).  Prints the lengths, the
    stroke, K and the largest pressure angle (closed form and measured by running the mechanism
    through a full crank turn) against the textbook's permissible 30-45° for a sliding driven
    link.  Exit 0 if the mechanism exists and the simulation agrees, 1 if no crank-slider meets
    the task (K too large for L, rod not longer than crank + offset), 2 for bad input.

    Example: [bold]pumplink slider --stroke 0.1 --rod-ratio 4 --time-ratio 1.2[/]
    """
    from pumplink.output.mechanisms import render_synthesis, synthesis_labels, synthesis_row
    from pumplink.studies.textbook import slider as synthesise

    rep = synthesise(stroke, rod_ratio, time_ratio, offset_ratio)
    render_synthesis(synthesis_row(rep), synthesis_labels(rep), fmt.value)
    raise typer.Exit(0 if rep.agrees else 1)
