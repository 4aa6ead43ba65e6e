"""`pumplink report`: one self-contained HTML design report."""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Annotated

import typer

from pumplink.cli.common import app, load_specs


@app.command()
def report(
    spec: Annotated[Path, typer.Argument(help="TOML pump spec.", show_default=False)],
    out: Annotated[Path, typer.Option("--out", "-o", help="Report file (.html).")] = Path("report.html"),
) -> None:
    """One self-contained HTML design report to send to a client.

    The spec, the synthesis table, the verdict with its model and checks
    against the operator profile's limits, the water it delivers and the people
    it serves, the force chart, the drawing, the loads on the parts with the
    pins' life and the released handle, the cut list, the bill of materials
    and the field sheet (images embedded; needs pumplink\\[plot]).

    Exit 0 if the design passes, 1 if it fails (the report is written
    either way) or no crank-rocker exists, 2 for bad input.

    Example: [bold]pumplink report configs/prototype.toml --out report.html[/]
    """
    from pumplink.output.charts import pyplot
    from pumplink.output.report import check_report_path

    check_report_path(out)
    pyplot()
    import tomli_w

    from pumplink.inputs.pump import spec_to_dict
    from pumplink.output.report import report_html
    from pumplink.studies.bom import bom
    from pumplink.studies.drawing import drawing
    from pumplink.studies.force import force_analysis, force_curve
    from pumplink.studies.sheet import field_sheet
    from pumplink.studies.workshop import workshop

    s = load_specs([spec])[0]
    dr = drawing(s)
    r = force_analysis(s, keep_samples=False)
    report_html(r, force_curve(r), dr, tomli_w.dumps(spec_to_dict(s)), out, shop=workshop(r), bom=bom(s),
                sheet=field_sheet(r))  # fmt: skip
    sys.stderr.write(f"wrote {out} ({r.outcome})\n")
    raise typer.Exit(0 if r.passed else 1)
