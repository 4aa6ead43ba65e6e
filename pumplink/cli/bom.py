"""`pumplink bom`: the bill of materials of a design, with sizes a workshop can buy."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from pumplink.cli.common import Format, FormatOpt, app, load_specs


@app.command()
def bom(
    spec: Annotated[Path, typer.Argument(help="TOML pump spec.", show_default=False)],
    fmt: FormatOpt = Format.table,
) -> None:
    """The bill of materials: every part with a size to buy, its cut length and mass.

    The coupler and the handle from the handle's tube, the crank from its
    round bar, the pins, the bushes they turn in, the lug, the wheel and the
    ratchet: sizes from the spec's \\[parts] and \\[ratchet], else pumplink's
    defaults; lengths from the drilling template (docs/workshop.md §4).
    CSV for a spreadsheet, JSON for other tools.

    Example: [bold]pumplink bom configs/village-10m.toml --format csv[/]
    """
    from pumplink.output.bom import render_bom
    from pumplink.studies.bom import bom as _bom

    render_bom(_bom(load_specs([spec])[0]), fmt.value)
