"""`pumplink force`: the operator force over the crank cycle, the checks and the verdict."""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Annotated, Optional

import typer

from pumplink.cli.common import (
    SAMPLE_LIMIT_KEPT,
    Format,
    FormatOpt,
    ModelOpt,
    StrictOpt,
    app,
    model_key,
    optional,
    spec_or_default,
    speed_option,
)
from pumplink.errors import SpecError


@app.command()
def force(
    spec: optional(
        Path,
        "TOML pump spec; omit it to use ./pump.toml if present, else the built-in design.",
        argument=True,
    ) = None,
    speed: Annotated[
        Optional[float], speed_option(help="Wheel speed (default: the spec's operator.speed).")
    ] = None,
    samples: Annotated[
        int, typer.Option(help="Uniform crank samples over one revolution.", min=1, max=1_000_000_000)
    ] = 360,
    at: optional(list[float], "Evaluate exactly this crank angle \\[deg] (repeatable).", "--at") = None,
    summary: Annotated[
        bool, typer.Option("--summary", help="Only the checks and verdict (no per-sample rows).")
    ] = False,
    plot: optional(
        Path,
        (
            "Also write the force curve to this .png/.svg/.pdf "
            "(needs the plot extra: pip install 'pumplink\\[plot]')."
        ),
    ) = None,
    explain: Annotated[
        bool,
        typer.Option(
            "--explain",
            help="Also report which effects the model includes, their "
            "size at this speed, and why the model is enough.",
        ),
    ] = False,
    verify: Annotated[
        bool,
        typer.Option(
            "--verify",
            help="Check the answer by an independent route: the flywheel and full "
            "dynamics integrate the equation of motion (scipy solve_ivp) under "
            "the reported force profile (periodic, mean speed, δ); the "
            "quasi-static model checks virtual work from positions and its "
            "exact peak against a dense sweep.",
        ),
    ] = False,
    model: ModelOpt = None,
    strict: StrictOpt = False,
    fmt: FormatOpt = Format.table,
) -> None:
    """Operator force over the crank cycle, the checks and the 100 N verdict.

    Three models; the least one that is enough decides the verdict (docs/models.md §3; --model
    picks one, --explain says why).  Without the wheel's inertia in the spec the force is
    [bold]quasi-static[/] (Eq. 3 of the pump paper), infinite at the two dead centres, so the
    peak is taken outside ±operator.dead_band of them, exactly, whatever --samples.  With it
    (wheel.mass or wheel.inertia; the rope and water are added) the [bold]flywheel[/] model
    finds the least peak force that keeps the wheel at the mean --speed with a speed
    fluctuation within operator.speed_fluctuation: the speed changes the answer.  Where the
    coupler's and handle's inertia and weight are too large to neglect, [bold]full dynamics[/]
    keeps them in the same least-peak-force test (docs/models.md §3a).  The verdict is PASS,
    PASS with warnings or FAIL (docs/models.md §4); after a FAIL the one or two single changes
    that help most are printed.  Exit 0 on PASS and PASS with warnings (1 with --strict), 1 on
    FAIL, an infeasible design or a --verify disagreement.

    Example: [bold]pumplink force pump.toml --speed 360 --at 90 --at 270 --format json[/]

    Example: [bold]pumplink force examples/well-12m-flywheel.toml --speed 540 --explain --verify[/]

    A spec with mechanism = "crank-slider" is a piston pump turned by a hand crank
    (docs/piston-pump.md): the same verdict on the handle force.

    Example: [bold]pumplink force examples/piston-pump.toml --summary[/]
    """
    import math

    from pumplink.output.force import render_study
    from pumplink.studies.design import study
    from pumplink.studies.force import force_analysis

    if at and any(not math.isfinite(a) for a in at):
        raise SpecError(
            f"--at {next(a for a in at if not math.isfinite(a))!r} is not a finite angle; "
            "give degrees such as --at 90"
        )
    if not summary and not at and samples > SAMPLE_LIMIT_KEPT:
        raise SpecError(
            f"--samples {samples} keeps too many rows (at most {SAMPLE_LIMIT_KEPT:,}); "
            "add --summary to stream them"
        )
    from pumplink.inputs.piston import PistonSpec

    s = spec_or_default(spec)  # read once: a rope pump's spec, or a piston pump's
    if isinstance(s, PistonSpec):  # mechanism = "crank-slider": docs/piston-pump.md
        _piston(s, spec, speed, samples, at, summary, plot, explain, verify, fmt.value)
    if plot is not None:
        from pumplink.output.charts import check_path, pyplot

        check_path(plot)
        pyplot()  # fail early (exit 2) when matplotlib is missing
    from pumplink.output.formats import progress

    with progress(1000, "force sweep") as advance:  # drawn on a terminal for sweeps over a second
        done = [0]

        def tick(fraction: float) -> None:
            k = int(fraction * 1000)
            advance(k - done[0])
            done[0] = k

        r = force_analysis(s, speed, samples, at_deg=at or None, keep_samples=not summary, progress=tick,
                           model=model_key(model))  # fmt: skip
    st = study(r, explain=explain, verify=verify)  # what --explain and --verify add, after the sweep
    render_study(st, fmt.value, summary=summary, strict=strict)
    result = st.result
    if plot is not None and result.design.feasible:
        from pumplink.output.charts import force_curve
        from pumplink.studies.force import force_curve as curve

        force_curve(result, curve(result), plot)
        sys.stderr.write(f"wrote {plot}\n")
    raise typer.Exit(0 if result.passed_strict(strict) and st.agrees else 1)


def _piston(
    s, spec: Path, speed, samples: int, at, summary: bool, plot, explain: bool, verify: bool, fmt: str
):
    """``pumplink force SPEC`` for a piston-pump spec (``s``, read from ``spec``); exits 0 (PASS)
    or 1 (FAIL, infeasible, a --verify disagreement)."""
    if plot is not None:
        raise SpecError(
            f"--plot is for rope-pump specs; {spec} is a piston pump (mechanism = 'crank-slider')"
        )
    from pumplink.output.piston import render_checks, render_force
    from pumplink.studies import piston

    result = piston.force_analysis(s, speed, samples, at_deg=at or None, keep_samples=not summary)
    why = piston.explain(result) if explain and result.feasible else None
    check = piston.verify(result) if verify and result.feasible else None
    render_force(result, fmt, summary=summary, why=why, check=check)
    if fmt != "json":
        render_checks(result, why, check)
    raise typer.Exit(0 if result.passed and (check is None or check.agrees) else 1)
