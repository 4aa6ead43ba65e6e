"""`pumplink size`: the pipe, wheel, cadence, handle and linkage that give the most water."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from pumplink.cli.common import (
    Format,
    FormatOpt,
    ToleranceOpt,
    YieldOpt,
    app,
    optional,
    robust_ask,
    spec_or_default,
)
from pumplink.errors import SpecError


def _bores(text: str | None) -> tuple[float, ...] | None:
    """``--pipes 16,20,25mm`` (or metres: 0.016,0.02) -> bores [m]."""
    if text is None:
        return None
    raw = text.strip().lower()
    scale = 1e-3 if raw.endswith("mm") else 1.0
    raw = raw.removesuffix("mm").removesuffix("m")
    try:
        values = tuple(float(v) * scale for v in raw.split(",") if v.strip())
    except ValueError:
        raise SpecError(f"--pipes {text!r} is not a list of bores; give e.g. --pipes 16,20,25mm") from None
    if not values:
        raise SpecError(f"--pipes {text!r} names no bore; give e.g. --pipes 16,20,25mm")
    return values


@app.command()
def size(
    spec: optional(
        Path,
        "Base spec (its frame width, dead band, masses...); omit it for the built-in design.",
        argument=True,
    ) = None,
    head: optional(float, "Pumping head [m] (default: the spec's load.head).", min=0.001, max=200) = None,
    profile: optional(
        str, "Who pumps: men, women, children or accessible (default: the spec's, else men)."
    ) = None,
    pipes: optional(
        str, 'Pipe bores to choose from, e.g. 16,20,25mm (default: the nominal ½" to 1½").'
    ) = None,
    allow_warnings: Annotated[
        bool, typer.Option("--allow-warnings", help="Accept warnings; only failing checks are excluded.")
    ] = False,
    seed: Annotated[
        int, typer.Option(help="Seed of the search (the same seed, the same answer).", min=0)
    ] = 0,
    tolerance: ToleranceOpt = None,
    target: YieldOpt = None,
    write: optional(Path, "Write the sized pump as a spec (TOML).") = None,
    overwrite: Annotated[
        bool, typer.Option("--force", help="Overwrite the --write file if it exists.")
    ] = False,
    fmt: FormatOpt = Format.table,
) -> None:
    """Size the whole rope pump for the most water one operator can pump for hours.

    Searches the pipe bore (from a list), the cadence, the wheel's radius and mass,
    the handle, rocker, swing, the rocker pivot's place and the axle height, for
    the most flow with no check failing and, unless --allow-warnings, none
    warning; every candidate is judged as pumplink force judges it.  Prints the
    pump, its flow, its share of what the operator's sustained power could lift
    (Q*), what binds, and the flow at other heads.  With --tolerance, at least
    --yield of the pumps built within it pass too (docs/tolerance.md).  Exit 0
    when a design is found, 1 when none meets the limits (the output says what
    holds it back).

    Example: [bold]pumplink size --head 12 --profile women --write well.toml[/]
    """
    from pumplink.output.formats import check_output, progress
    from pumplink.output.size import render_size
    from pumplink.search import size as sizing

    if profile is not None and profile not in ("men", "women", "children", "accessible"):
        raise SpecError(f"--profile {profile!r} is not a profile; choose men, women, children or accessible")
    if write is not None and write.exists() and not overwrite:
        raise SpecError(f"{write} exists; choose another path or add --force to overwrite it")
    if write is not None:
        check_output(write, "--write")
    robust = robust_ask(tolerance, target)
    problem = sizing.problem_for(spec_or_default(spec), head, profile, _bores(pipes), allow_warnings, robust)
    with progress(len(problem.pipes), "size (pipe bores)") as advance:
        result = sizing.size(problem, seed=seed, progress=advance)
    render_size(result, fmt.value)
    if write is not None and result.found:
        import tomli_w

        from pumplink.inputs.pump import spec_to_dict
        from pumplink.output.formats import atomic_write

        with atomic_write(write) as f:
            f.write(tomli_w.dumps(spec_to_dict(result.best.spec)))
        typer.echo(f"wrote {write}; check it with: pumplink force {write}", err=True)
    raise typer.Exit(0 if result.found else 1)
