"""`pumplink sheet`: the field sheet, one A4 page a mechanic takes to the well."""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Annotated, Optional

import typer

from pumplink.cli.common import app, load_specs, parse_length


@app.command()
def sheet(
    spec: Annotated[Path, typer.Argument(help="TOML pump spec.", show_default=False)],
    out: Annotated[Path, typer.Option("--out", "-o", help="Field sheet (.pdf).")] = Path("sheet.pdf"),
    hole: Annotated[
        Optional[str],
        typer.Option(
            "--hole",
            metavar="LENGTH",
            help="Give the builds' 5-95 % band: every hole within this tolerance, e.g. 1mm (a tolerance "
            "study of --samples builds, pumplink tolerance).",
            show_default=False,
        ),
    ] = None,
    samples: Annotated[
        int, typer.Option(help="Builds of the tolerance study (with --hole).", min=100)
    ] = 2000,
) -> None:
    """The field sheet: one A4 page (PDF) a mechanic takes to the well.

    The crank turns and the time to fill a 20-litre container at the design
    cadence, the turns before water reaches the spout, the hand force to
    expect, what to look at when they are off (leaking pistons, misdrilled
    holes), the ratchet's catch when the handle is let go, and an endurance
    test for a prototype (docs/water.md §5).  With --hole, the 5-95 % band
    of a tolerance study of the builds.  Needs pumplink\\[plot].

    Example: [bold]pumplink sheet configs/village-10m.toml --out sheet.pdf[/]
    """
    from pumplink.output.charts import pyplot
    from pumplink.output.sheet import check_sheet_path

    check_sheet_path(out)
    pyplot()
    from pumplink import __version__
    from pumplink.output.sheet import write_sheet_pdf
    from pumplink.studies.force import force_analysis
    from pumplink.studies.sheet import field_sheet

    s = load_specs([spec])[0]
    r = force_analysis(s, keep_samples=False)
    builds = None
    if hole is not None:
        from pumplink.studies.tolerance import problem, tolerances
        from pumplink.studies.tolerance_study import study

        builds = study(problem(s, tolerances(parse_length(hole, "--hole")), samples))
    write_sheet_pdf(field_sheet(r, builds), out, __version__)
    sys.stderr.write(f"wrote {out} (one A4 page; {r.outcome})\n")
