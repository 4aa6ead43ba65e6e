"""`pumplink synth`: the dead-centre synthesis table of one or more specs."""

from __future__ import annotations

from pathlib import Path

import typer

from pumplink.cli.common import Format, FormatOpt, app, load_specs, optional, spec_or_default


@app.command()
def synth(
    specs: optional(
        list[Path],
        (
            "TOML pump specs ('-' reads one from stdin); none: ./pump.toml if present, else the "
            "built-in design."
        ),
        argument=True,
    ) = None,
    fmt: FormatOpt = Format.table,
) -> None:
    """Dead-centre synthesis: link lengths, dead centres, time ratio, transmission range.

    One row per spec (Table 1 of the pump paper).  Exit 1 if any design is infeasible.

    Example: [bold]pumplink synth configs/prototype.toml configs/village-10m.toml --format json[/]
    """
    from pumplink.output.synth import render_designs
    from pumplink.studies.force import design

    designs = [design(s) for s in (load_specs(specs) if specs else [spec_or_default(None)])]
    render_designs(designs, fmt.value)
    raise typer.Exit(0 if all(d.feasible for d in designs) else 1)
