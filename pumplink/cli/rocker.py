"""`pumplink rocker`: crank-rocker from K and the rocker's two extreme positions."""

from __future__ import annotations

from typing import Annotated

import typer

from pumplink.cli.common import Format, FormatOpt, app, optional
from pumplink.errors import SpecError


def _pivot(text: str | None):
    if text is None:
        return None
    parts = text.split(",")
    try:
        if len(parts) != 2:
            raise ValueError
        return float(parts[0]), float(parts[1])
    except ValueError:
        raise SpecError(f"--pivot {text!r} must be two numbers X,Y such as --pivot=-0.26,0.19") from None


@app.command()
def rocker(
    swing: Annotated[float, typer.Option(help="Rocker swing between its extreme positions \\[deg].")],
    rocker_length: Annotated[float, typer.Option("--rocker", help="Rocker length (any length unit).")],
    time_ratio: optional(float, "Time ratio K >= 1 (not with --pivot).", "--time-ratio", "-k") = None,
    frame: optional(float, "Put the crank pivot at this distance from the rocker pivot.") = None,
    pivot: optional(
        str, "Put the crank pivot at X,Y (rocker pivot at 0,0, swing bisector along +y); fixes K."
    ) = None,
    fmt: FormatOpt = Format.table,
) -> None:
    """Crank-rocker that swings the rocker between two extreme positions with time ratio K.

    The crank pivot lies on the design circle through the extreme positions C1, C2 (the angle
    C1-A-C2 is 180°(K − 1)/(K + 1)); each point is another mechanism (docs/crank-rocker.md §7).
    Choose it with --frame (distance from the rocker pivot), --pivot X,Y (the point itself; K then
    follows from it), or neither: the best minimum transmission angle (the optimal-transmission
    paper, as `pumplink transmission`).  The result is run through a full crank turn and its
    measured swing, K, transmission angles γmin and γmax and dead-centre crank angles are printed.
    Verdict: the smallest transmission angle min(γmin, 180° − γmax) warns below 45° and fails
    below 30° (the linkage would jam); the simulation must reproduce every value.  Exit 0 on PASS
    or PASS with warnings, 1 on FAIL or if no crank-rocker meets the choice, 2 for bad input.

    Example: [bold]pumplink rocker --time-ratio 1.1 --swing 40 --rocker 0.3 --frame 0.4[/]

    Example: [bold]pumplink rocker --swing 50 --rocker 0.3 --pivot=-0.26,0.19 -f json[/]
    """
    import math

    from pumplink.output.mechanisms import render_synthesis, synthesis_labels, synthesis_row
    from pumplink.studies.textbook_rocker import rocker as synthesise

    if not math.isfinite(swing):
        raise SpecError(f"--swing {swing!r} is not a finite number")
    rep = synthesise(math.radians(swing), rocker_length, time_ratio, frame, _pivot(pivot))
    render_synthesis(synthesis_row(rep), synthesis_labels(rep), fmt.value)
    raise typer.Exit(0 if rep.passed else 1)
