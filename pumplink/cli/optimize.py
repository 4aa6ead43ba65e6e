"""`pumplink optimize`: search the frame placement, rocker and swing for the least force."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from pumplink.cli.common import (
    Format,
    FormatOpt,
    ModelOpt,
    StrictOpt,
    ToleranceOpt,
    YieldOpt,
    app,
    choices,
    load_specs,
    model_key,
    optional,
    robust_ask,
)
from pumplink.errors import SpecError

# ----------------------------------------------------------------------------- design search
Objective = choices("Objective", "peak", "mean", "flow")


def res_passes(result, strict: bool) -> bool:
    """The optimum's verdict decides the exit code (with --strict, warnings fail too)."""
    return result.best_result.passed_strict(strict)


@app.command()
def optimize(
    spec: Annotated[
        Path, typer.Argument(help="TOML pump spec: fixed values and the starting design.", show_default=False)
    ],
    vary: optional(
        list[str],
        (
            "KEY=LO:HI in spec units (repeatable); keys: L1, D1, "
            "b, rocker, handle \\[m], swing \\[deg], and what a builder chooses: wheel.radius, "
            "wheel.axle_height, load.pipe_diameter \\[m], wheel.mass \\[kg], operator.speed \\[deg/s]. "
            "Default: rocker=0.1:0.4 L1=0:1 D1=-0.3:1.2 swing=30:100."
        ),
        "--vary",
    ) = None,
    objective: Annotated[
        Objective,
        typer.Option(
            help="Minimise the peak force of the verdict (the least peak "
            "force of the flywheel or full dynamics when the spec gives "
            "inertia, else the exact peak outside the dead bands) or the mean force, or "
            "maximise the flow with no check failing (flow; vary the cadence, wheel or pipe too: "
            "the cadence and rope speed are then held in range)."
        ),
    ] = Objective.peak,
    seed: Annotated[
        int,
        typer.Option(
            help="Random seed of the differential evolution (same seed, same answer).", min=0, max=2**32 - 1
        ),
    ] = 0,
    axle_height: optional(
        float, "Wheel-axle height \\[m] (default: the spec's wheel.axle_height, else 0.55)."
    ) = None,
    grip_height: optional(
        str,
        (
            "Allowed grip height above ground over the swing, LO:HI \\[m] (default: the operator "
            "profile's, 0.9:1.33 for men)."
        ),
    ) = None,
    stroke: Annotated[str, typer.Option(help="Allowed horizontal grip stroke, LO:HI \\[m].")] = "0:1.0",
    write: optional(Path, "Write the optimum as a new spec (TOML).") = None,
    overwrite: Annotated[
        bool, typer.Option("--force", help="Overwrite the --write file if it exists.")
    ] = False,
    strict: StrictOpt = False,
    model: ModelOpt = None,
    tolerance: ToleranceOpt = None,
    target: YieldOpt = None,
    fmt: FormatOpt = Format.table,
) -> None:
    """Search frame placement, rocker and swing for the least operator force.

    Differential evolution over the vectorised force kernel, then a local polish, subject to: a
    crank-rocker exists, transmission angle >= 45°, grip height and stroke in the ergonomic
    ranges.  The spec's own design and the optimum are then judged exactly as pumplink force
    judges them: PASS, PASS with warnings or FAIL.  With --tolerance, at least --yield
    of the pumps built within it pass too (docs/tolerance.md).  Exit 0 if the optimum
    passes (1 with --strict if it warns), 1 if it fails or nothing is feasible.

    Example: [bold]pumplink optimize configs/prototype.toml --write best.toml[/]
    """  # noqa: E501 -- typer prints this docstring as the --help text, keeping its line breaks
    from pumplink.output.optimize import optimize_row, render_optimize
    from pumplink.search.optimize import optimize as run
    from pumplink.search.problem import STROKE_M, make_problem, parse_bounds, parse_range

    bounds = parse_bounds(vary)
    gh = None if grip_height is None else parse_range("grip-height", grip_height, (0.9, 1.33))
    st = parse_range("stroke", stroke, STROKE_M)
    if write is not None and write.exists() and not overwrite:
        raise SpecError(f"{write} exists; choose another path or add --force to overwrite it")
    if write is not None:
        from pumplink.output.formats import check_output

        check_output(write, "--write")
    problem = make_problem(
        load_specs([spec])[0],
        bounds,
        objective.value,
        axle_height,
        gh,
        st,
        model_key(model),
        robust_ask(tolerance, target, strict),
    )
    from pumplink.output.formats import progress

    with progress(300, "optimize (generations)") as advance:
        result = run(problem, seed=seed, progress=advance)
    row = optimize_row(result)
    render_optimize(row, fmt.value, strict=strict)
    if write is not None:
        import tomli_w

        from pumplink.output.formats import atomic_write
        from pumplink.search.optimize import best_spec_dict

        with atomic_write(write) as f:
            f.write(tomli_w.dumps(best_spec_dict(result)))
        typer.echo(f"wrote {write}; check it with: pumplink force {write}", err=True)
    raise typer.Exit(0 if res_passes(result, strict) else 1)
