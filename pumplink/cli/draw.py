"""`pumplink draw`: the linkage to scale at its dead centres, dimensioned; or its animation."""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Annotated

import typer

from pumplink.cli.common import app, load_specs, optional
from pumplink.errors import SpecError


@app.command()
def draw(
    spec: Annotated[Path, typer.Argument(help="TOML pump spec.", show_default=False)],
    out: optional(
        Path, "Drawing file, .png/.svg/.pdf (default: SPEC's name with .png, in this folder).", "--out", "-o"
    ) = None,
    peak: Annotated[
        bool, typer.Option("--peak", help="Also draw the linkage where the quasi-static peak force is.")
    ] = False,
    animate: optional(
        Path, "Write an animation of one revolution to this .gif instead (with --out: as well).", "--animate"
    ) = None,
    steps: Annotated[
        int, typer.Option(help="Frames of the animation: crank steps per revolution.", min=4, max=720)
    ] = 72,
) -> None:
    """Draw the linkage to scale at both dead centres, dimensioned in mm.

    With the grip path, the swing, the frame placement L1, D1, b and every
    link length.

    The sheet is A4 landscape at the largest standard scale that fits
    (stated on the sheet).  --animate draws one revolution in --steps frames,
    with the operator's force as an arrow at the grip (needs pumplink\\[plot]).
    Exit 1 if the spec gives no crank-rocker.

    Example: [bold]pumplink draw configs/prototype.toml --out linkage.svg --peak[/]
    """
    from pumplink.output.charts import check_path, pyplot
    from pumplink.output.drawings import check_animation_path

    if animate is not None:
        check_animation_path(animate)
    if out is None and animate is None:
        if str(spec) == "-":
            raise SpecError(
                "draw -: give --out FILE (.png, .svg or .pdf); a spec read from standard input names no file"
            )
        out = Path(spec.stem + ".png")
    if out is not None:
        check_path(out, "--out")
    pyplot()
    from pumplink.output.drawings import animation, linkage_drawing
    from pumplink.studies.drawing import drawing, motion

    s = load_specs([spec])[0]
    dr = drawing(s, peak=peak)
    # the animation (seconds of work) first: once a run's first file is in place an interrupt no
    # longer stops it (pumplink.cli.Interrupt), and the drawing after it is quick
    if animate is not None:
        animation(dr, motion(s, steps), animate)
        sys.stderr.write(f"wrote {animate} ({steps} frames, one revolution)\n")
    if out is not None:
        _, scale = linkage_drawing(dr, out)
        sys.stderr.write(f"wrote {out} (scale 1:{scale:g} on A4)\n")
