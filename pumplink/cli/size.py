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
    keep: optional(
        str,
        "Hold what you have at the base spec's value: wheel (radius and mass), pipe (its "
        "rising main) and/or handle, e.g. --keep wheel,pipe.",
    ) = None,
    allow_pit: Annotated[
        bool,
        typer.Option("--allow-pit", help="Let the rocker pivot sit below the ground (in a pit)."),
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

    Searches the pipe bore (from a list: by default ½", ¾", 1", 1¼", 1½"; none
    below ½", 12.7 mm, the smallest a rope piston is made for), the cadence (10-90
    turns a minute), the wheel's radius (0.15-0.35 m) and mass at its rim (1-15 kg),
    the handle (0.5-1.6 m), rocker (0.10-0.40 m), swing (30-100 deg), the rocker
    pivot's place (L1 0-1 m beyond the stand, D1 0.6 m above to 0.6 m below the
    axle, never below the ground unless --allow-pit) and the axle height
    (0.40-0.70 m), for the most flow with no check failing and, unless
    --allow-warnings, none warning (so the cadence stays within the profile's 30-60
    turns a minute and the rope within 0.6-1.8 m/s); every candidate is judged as
    pumplink force judges it.  --keep holds the base spec's wheel, pipe or handle.
    Prints the pump, its flow all day and filling containers, its share of what
    the operator's sustained power could lift (Q*), what binds, what the base spec
    holds that the built-in design does not, and the flow at other heads.  With
    --tolerance, at least --yield of the pumps built within it pass too
    (docs/tolerance.md).  Exit 0 when a design is found, 1 when none meets the
    limits (the output says what holds it back).  Bounds and sources:
    docs/optimize.md, "Sizing the whole pump".

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
    kept = () if keep is None else tuple(k.strip() for k in keep.split(",") if k.strip())
    problem = sizing.problem_for(
        spec_or_default(spec), head, profile, _bores(pipes), allow_warnings, robust, kept, allow_pit
    )
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
