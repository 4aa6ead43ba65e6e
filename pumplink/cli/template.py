"""`pumplink template`: the 1:1 drilling template of every link (PDF pages, SVG or DXF)."""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Annotated

import typer

from pumplink.cli.common import app, choices, load_specs

Paper = choices("Paper", "A4", "A3", "letter")


@app.command()
def template(
    spec: Annotated[Path, typer.Argument(help="TOML pump spec.", show_default=False)],
    out: Annotated[
        Path, typer.Option("--out", "-o", help="Template file: .pdf (printable pages), .svg or .dxf.")
    ] = Path("template.pdf"),
    paper: Annotated[Paper, typer.Option(help="Paper of the PDF pages (landscape).")] = Paper.A4,
    target: Annotated[
        float,
        typer.Option(
            "--yield",
            help="The share of builds that must pass: each hole's tolerance is allocated for it "
            "(pumplink tolerance, docs/tolerance.md).",
            min=0.5,
            max=0.9999,
        ),
    ] = 0.95,
) -> None:
    """A 1:1 drilling template of each link (PDF, SVG or DXF).

    Hole centres, the distance between them in mm, hole diameter (the pins'
    of \\[parts], default 12 mm; a cross and no hole where \\[parts] welds the
    joint: the crank to the axle, a lug to the handle), link name, and each
    hole's tolerance for --yield of the builds to pass (the critical holes,
    which need more care than a hand-drilled hole gets, ringed in red;
    docs/tolerance.md).

    PDF: links longer than the paper are tiled over several pages with
    numbered alignment marks; every page has a 100 mm scale bar to check the
    printer did not scale it; page 1 has the cut list with the sizes to buy,
    the pins, bushes and lug, and where the ratchet goes (pumplink bom).  SVG:
    one 1:1 canvas.
    DXF (needs pumplink\\[dxf]): millimetres, one layer per link, for laser or
    CNC.  Exit 1 if the spec gives no crank-rocker.

    Example: [bold]pumplink template configs/prototype.toml --out template.pdf --paper A4[/]
    """
    from pumplink.output.template import check_template_path

    check_template_path(out)
    from pumplink.output.charts import pyplot

    if out.suffix.lower() != ".dxf":
        pyplot()
    from pumplink.output.template import write_template
    from pumplink.studies.bom import bom
    from pumplink.studies.drawing import drawing, tolerance_marks

    s = load_specs([spec])[0]
    dr = drawing(s)
    parts, marks = tolerance_marks(s, dr.parts, target)
    pages = write_template(parts, out, paper.value, s.name, dr.tube_given, marks, bom(s))
    sys.stderr.write(
        f"wrote {out}" + (f" ({pages} pages, {paper.value})" if out.suffix.lower() == ".pdf" else "") + "\n"
    )
    if marks.reason is not None:
        sys.stderr.write(f"no tolerances on the template: {marks.reason}\n")
