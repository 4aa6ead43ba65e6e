"""`pumplink structure`: mobility, redundant constraints and Assur groups of a mechanism (TOML)."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from pumplink.cli.common import Format, FormatOpt, app


@app.command()
def structure(
    mechanism: Annotated[
        Path, typer.Argument(help="TOML mechanism: frame, links, \\[joints] (see configs/mechanisms/).")
    ],
    fmt: FormatOpt = Format.table,
) -> None:
    """Structure analysis: n, p1, p2, Chebyshev's W, redundant constraints, Assur groups.

    The file lists the links, the frame and each joint with its pair class (revolute,
    prismatic or higher) and the links it connects; optional drivers, passive_links (redundant
    constraints) and local_mobilities.  The Assur groups are removed farthest from the drivers
    first and printed in the order they are attached, with class and order (docs/mechanisms.md
    §3).  Exit 0 if the mechanism decomposes into drivers and Assur groups, 1 if it does not
    (e.g. W0 <= 0: a structure), 2 for bad input.

    Example: [bold]pumplink structure configs/mechanisms/six-link.toml[/]

    Example: [bold]pumplink structure configs/mechanisms/double-parallelogram.toml --format json[/]
    """
    from pumplink.inputs.structure import analyse, load_structure
    from pumplink.output.mechanisms import render_structure, structure_row

    spec = load_structure(mechanism)
    a = analyse(spec, str(mechanism))
    render_structure(structure_row(spec.name, a, spec.passive_links), fmt.value)
    raise typer.Exit(0 if a.decomposed else 1)
