"""`pumplink validate`: the published one-person discharges, predicted through the evaluation."""

from __future__ import annotations

from pathlib import Path

import typer

from pumplink.cli.common import Format, FormatOpt, app, optional


@app.command()
def validate(
    junit: optional(Path, "Also write JUnit XML, one testcase per discharge (atomically).", "--junit") = None,
    fmt: FormatOpt = Format.table,
) -> None:
    """Reproduce every published one-person discharge the docs cite.

    Each figure (Akvopedia, the University of Twente, Arrakis: head, who
    pumped, the duty they were measured at) is run through the same
    evaluation as pumplink force, on the village pump of
    configs/village-10m.toml at the published head: the flow at the
    duty's power (filling containers), with the efficiencies the loss
    model chooses there.  Prints prediction against publication, and the
    figures left out with the reason (docs/water.md §6).  Exit 0 if every
    prediction is within 15 % of its figure, 1 if any is not.

    Example: [bold]pumplink validate --junit validate.xml[/]
    """
    from pumplink.output.formats import atomic_write, check_output
    from pumplink.output.validate import junit_xml, render_validation
    from pumplink.studies.validate import validate as run

    if junit is not None:
        check_output(junit, "--junit")
    result = run()
    render_validation(result, fmt.value)
    if junit is not None:
        with atomic_write(junit) as f:
            f.write(junit_xml(result))
    raise typer.Exit(0 if result.passed else 1)
