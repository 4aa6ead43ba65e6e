"""`pumplink speed`: the least peak force against the mean wheel speed."""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Annotated

import typer

from pumplink.cli.common import (
    Format,
    FormatOpt,
    ModelOpt,
    StrictOpt,
    app,
    load_specs,
    model_key,
    optional,
    speed_option,
)
from pumplink.errors import SpecError


@app.command()
def speed(
    spec: Annotated[
        Path,
        typer.Argument(
            help="TOML pump spec with the wheel's inertia (wheel.mass or wheel.inertia).", show_default=False
        ),
    ],
    lo: Annotated[float, speed_option("--from", help="Lowest mean wheel speed.")] = 120.0,
    hi: Annotated[float, speed_option("--to", help="Highest mean wheel speed.")] = 720.0,
    step: Annotated[float, speed_option("--step", help="Speed step.")] = 30.0,
    plot: optional(
        Path,
        (
            "Write the chart (peak force against speed by model, the "
            "best cadence, 75 W) to this .png/.svg/.pdf (needs pumplink\\[plot])."
        ),
    ) = None,
    strict: StrictOpt = False,
    model: ModelOpt = None,
    fmt: FormatOpt = Format.table,
) -> None:
    """Least peak operator force against mean wheel speed, the verdict at each speed and the
    best cadence.

    The flywheel model (see [bold]pumplink force --help[/]): a faster wheel
    stores more energy (J·ω̄²·δ) to carry the linkage through the dead
    centres, so the force falls toward the mean force.  Full dynamics adds
    the links' inertia and weight, and the operator's effort adds their own
    arms: their kinetic energy grows with speed too, so past the best
    cadence faster costs more effort, not less.  Each speed gets the
    verdict of pumplink force (PASS, PASS with warnings, FAIL) by the model
    that decides there.  Exit 0 if the spec's own speed passes (1 with
    --strict if it warns), 1 if not, 2 if the spec gives no inertia.

    Example: [bold]pumplink speed examples/well-12m-flywheel.toml --plot speed.png[/]
    """
    import numpy as np

    from pumplink.output.speed import render_speed
    from pumplink.studies.speed import speed_sweep

    if hi < lo:
        raise SpecError(f"--to {hi:g} is below --from {lo:g}; give --from LOW --to HIGH in deg/s")
    n = int(np.floor((hi - lo) / step + 1e-9)) + 1
    if n > 10_000:
        raise SpecError(
            f"--from {lo:g} --to {hi:g} --step {step:g} gives {n} speeds; at most 10,000 (raise --step)"
        )
    if plot is not None:
        from pumplink.output.charts import check_path, pyplot

        check_path(plot)
        pyplot()
    s = load_specs([spec])[0]
    speeds = [float(f"{v:.12g}") for v in lo + step * np.arange(n)]  # 420, not 420.00000000000006
    from pumplink.output.formats import progress

    with progress(1, "speed sweep", delay=0.0 if n > 200 else 1.0) as advance:
        sw = speed_sweep(s, speeds, model_key(model))
        advance(1)
    render_speed(sw, fmt.value)
    if plot is not None:
        import dataclasses

        from pumplink.output.charts import speed_chart

        # the chart's curves on a step four times finer than the table's (the same cadence)
        fine = np.linspace(speeds[0], speeds[-1], 4 * (n - 1) + 1) if n > 1 else np.array(speeds)
        curve = speed_sweep(s, fine, model_key(model), with_cadence=False)
        speed_chart(dataclasses.replace(curve, cadence=sw.cadence), plot)
        sys.stderr.write(f"wrote {plot}\n")
    raise typer.Exit(0 if sw.spec_speed_passes(strict) else 1)
