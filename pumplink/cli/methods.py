"""`pumplink methods`: speed against accuracy of the force methods."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from pumplink.cli.common import Format, FormatOpt, app, optional
from pumplink.errors import SpecError


@app.command()
def methods(
    spec: optional(Path, "TOML pump spec; omit for the built-in default design.", argument=True) = None,
    samples: Annotated[
        int, typer.Option(help="Uniform crank samples of the accuracy sweep.", min=4, max=100_000)
    ] = 360,
    method: optional(
        list[str], "Only this method (repeatable): vector, paper, numeric, reference.", "--method", "-m"
    ) = None,
    repeats: Annotated[
        int, typer.Option(help="Timing repeats per method and sampling (median).", min=1, max=1000)
    ] = 7,
    plot: optional(Path, "Write log error vs log time per position (.png, .svg or .pdf).", "--plot") = None,
    samples_plot: optional(
        Path,
        "Write sampled vs exact peak and mean force for N = 12..3600 (.png, .svg or .pdf).",
        "--samples-plot",
    ) = None,
    fmt: FormatOpt = Format.table,
) -> None:
    """Speed against accuracy of the force methods, where each one fails, and how many samples a sweep needs.

    Every method (vector: production; paper: the paper's instant centre, Eq. 4-6; numeric: scipy
    root finding + finite difference; reference: mpmath, 50 digits) is timed (median of
    --repeats) and compared with the reference on a uniform sweep, next to the dead centres
    (1 to 1e-6 deg) and at the danger points (crank or rocker perpendicular to the frame line,
    crank parallel to the rocker, crank along the frame line).  Exit 0 if no method returns a
    silently wrong value, 1 otherwise.

    Example: [bold]pumplink methods --plot methods.png --samples-plot sampling.svg --format json[/]
    """
    from pumplink.inputs.pump import default_spec, load_spec
    from pumplink.output.charts import check_path, plot_methods, plot_sampling, pyplot
    from pumplink.output.methods import render_methods
    from pumplink.studies import accuracy
    from pumplink.studies.methods import METHODS

    names = method or list(METHODS)
    unknown = [m for m in names if m not in METHODS]
    if unknown:
        raise SpecError(f"--method {unknown[0]!r} is not a method; choose from {', '.join(METHODS)}")
    for option, path in (("--plot", plot), ("--samples-plot", samples_plot)):
        if path is not None:
            check_path(path, option)
    if plot is not None or samples_plot is not None:
        pyplot()  # fail early (exit 2) when matplotlib is missing
    try:
        import mpmath  # noqa: F401
    except ImportError:
        raise SpecError("the 50-digit reference needs mpmath; install it with: pip install mpmath") from None

    s = load_spec(spec) if spec is not None else default_spec()
    from pumplink.output.formats import progress

    with progress(accuracy.method_steps(names), "methods") as advance:
        found = accuracy.method_study(s, names, samples, repeats, advance)
    rows, study = found.methods, found.sampling
    render_methods(s.name, rows, study, fmt.value, dead_band_deg=s.operator.dead_band)
    if plot is not None:
        plot_methods(rows, plot, title=s.name)
        typer.echo(f"wrote {plot}", err=True)
    if samples_plot is not None:
        plot_sampling(study, samples_plot, title=s.name, dead_band_deg=s.operator.dead_band)
        typer.echo(f"wrote {samples_plot}", err=True)
    raise typer.Exit(1 if accuracy.silently_wrong(rows) else 0)
