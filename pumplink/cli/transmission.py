"""`pumplink transmission`: the optimal-transmission crank-rocker for K and the swing."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from pumplink.cli.common import Format, FormatOpt, app, optional
from pumplink.errors import SpecError

#: Rocker lengths the command accepts (any unit): beyond them the lengths' squares overflow.
ROCKER_RANGE = (1e-6, 1e6)

#: Smallest swing [deg] the command accepts: below, the design circle's arc is lost to rounding.
SWING_MIN_DEG = 0.001


@app.command()
def transmission(
    time_ratio: Annotated[
        float, typer.Option("--time-ratio", "-k", help="Time ratio K > 1 (slow/fast stroke).")
    ] = 1.1818,
    swing: Annotated[float, typer.Option(help="Rocker swing φ \\[deg].")] = 40.0,
    rocker: Annotated[
        float, typer.Option(help="Rocker length (any unit; the other lengths come out in it).")
    ] = 50.0,
    compare: Annotated[
        bool,
        typer.Option(
            "--compare/--no-compare", help="Compare with the paper's published designs (its example only)."
        ),
    ] = True,
    chart: optional(
        Path,
        (
            "Write the paper's design diagram (contours over θ and φ) "
            "to this image file instead (needs pumplink\\[plot])."
        ),
    ) = None,
    fmt: FormatOpt = Format.table,
) -> None:
    """Crank-rocker with the best minimum transmission angle for K and φ (exact).

    Solves the problem of the optimal-transmission paper to solver tolerance on the one-branch
    arc of the design circle and verifies the result by simulating the linkage (the swing and K
    it really produces), and says whether the simulation agrees.  With the defaults it is the
    paper's worked example (K = 1.1818, φ = 40°, rocker 50 mm) compared with the paper's
    published designs.  Verdict: the optimum's smallest transmission angle warns below 45° and
    fails below 30° (the linkage would jam); the simulation must reproduce the asked swing and K
    and the optimum's transmission angle.  Exit 0 on PASS or PASS with warnings, 1 on FAIL or if
    no crank-rocker exists, 2 for bad input.

    Example: [bold]pumplink transmission --time-ratio 1.25 --swing 50 --rocker 0.3[/]
    """
    import math

    from pumplink.studies import textbook_rocker as study

    if chart is not None:
        from pumplink.output.charts import check_path, pyplot, transmission_chart

        check_path(chart, "--chart")
        pyplot()  # fail early (exit 2) when matplotlib is missing
        transmission_chart(study.design_chart(), chart)
        typer.echo(f"wrote {chart}", err=True)
        return

    from pumplink.output.transmission import render_transmission, transmission_rows

    for name, v in (("--time-ratio", time_ratio), ("--swing", swing), ("--rocker", rocker)):
        if not math.isfinite(v):
            raise SpecError(f"{name} {v!r} is not a finite number")
    if not SWING_MIN_DEG <= swing < 180:
        raise SpecError(
            f"--swing {swing:g}: the rocker swing is out of range; allowed: "
            f"{SWING_MIN_DEG:g} <= value < 180 [deg]; give e.g. 40"
        )
    if not ROCKER_RANGE[0] <= rocker <= ROCKER_RANGE[1]:
        raise SpecError(
            f"--rocker {rocker:g}: the rocker length is out of range; allowed: "
            f"{ROCKER_RANGE[0]:g} <= value <= {ROCKER_RANGE[1]:g} (any unit: give e.g. 50 for millimetres)"
        )
    t = study.transmission(time_ratio, math.radians(swing), rocker, compare)
    rows = transmission_rows(t.optimum, t.motion, t.comparisons, t.published_gamma_min_deg, t.check)
    render_transmission(rows, fmt.value)
    raise typer.Exit(0 if t.check.verdict.passed else 1)
