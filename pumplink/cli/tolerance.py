"""`pumplink tolerance`: the pumps a workshop builds from a design, with their holes off by a little."""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Annotated, Optional

import typer

from pumplink.cli.common import (
    Format,
    FormatOpt,
    ModelOpt,
    StrictOpt,
    app,
    choices,
    dask_cluster,
    model_key,
    optional,
    parse_length,
    spec_or_default,
)
from pumplink.errors import SpecError

Distribution = choices("Distribution", "uniform", "normal")


def _below_2_63(value: int) -> int:
    """--seed: numpy's generators take a seed below 2**63 here (the range is stated in the help
    rather than as Typer's range, whose 19 digits would not fit an 80-column help)."""
    if value >= 2**63:
        raise typer.BadParameter(f"must be < 2**63 ({2**63 - 1} at most)")
    return value


def _length(option: str):
    return typer.Option(
        option,
        metavar="LENGTH",
        help={
            "--hole": "Every hole on the links (and the pivots, unless --pivot), e.g. 1mm.",
            "--pivot": "The wheel axle O2 and the rocker pivot O4 on the stand.",
            "--crank-hole": "The crank's two holes (O2, A).",
            "--coupler-hole": "The coupler's two holes (A, B).",
            "--rocker-hole": "The rocker's holes (O4, B) and the grip, unless --grip.",
            "--grip": "The grip on the handle (P).",
        }[option],
        show_default=False,
    )


@app.command()
def tolerance(
    spec: optional(
        Path,
        "TOML rope-pump spec; omit it to use ./pump.toml if present, else the built-in design.",
        argument=True,
    ) = None,
    hole: Annotated[str, _length("--hole")] = "1mm",
    pivot: Annotated[Optional[str], _length("--pivot")] = None,
    crank_hole: Annotated[Optional[str], _length("--crank-hole")] = None,
    coupler_hole: Annotated[Optional[str], _length("--coupler-hole")] = None,
    rocker_hole: Annotated[Optional[str], _length("--rocker-hole")] = None,
    grip: Annotated[Optional[str], _length("--grip")] = None,
    tol: optional(
        list[str],
        (
            "One hole's tolerance (repeatable): crank.O2, crank.A, coupler.A, coupler.B, rocker.O4, "
            "rocker.B, rocker.grip, stand.O2, stand.O4; e.g. --tol crank.A=0.5mm."
        ),
        "--tol",
        metavar="HOLE=LENGTH",
    ) = None,
    distribution: Annotated[
        Distribution,
        typer.Option(
            help="How a coordinate is off: uniform, anywhere within ±t; normal, with t = 3σ.",
        ),
    ] = Distribution.uniform,
    samples: Annotated[int, typer.Option(help="Builds drawn.", min=100, max=10_000_000)] = 10_000,
    seed: Annotated[
        int,
        typer.Option(
            help="Seed of the builds (the same seed, the same builds), below 2**63.",
            min=0,
            callback=_below_2_63,
        ),
    ] = 0,
    target: Annotated[
        float,
        typer.Option(
            "--yield",
            help="The share of builds that must pass: exit 1 below it; also the target of the "
            "tolerances the output suggests per hole.",
            min=0.5,
            max=0.9999,
        ),
    ] = 0.95,
    strict: StrictOpt = False,
    model: ModelOpt = None,
    workers: Annotated[
        int,
        typer.Option(help="Worker processes (0: one per CPU; never more than the chunks).", min=0, max=256),
    ] = 1,
    scheduler: optional(
        str,
        (
            "Run on Dask instead of the local pool: local:N or tcp://host:8786 (needs pip install "
            "'pumplink\\[dask]'). The same numbers as one process."
        ),
        "--scheduler",
    ) = None,
    fmt: FormatOpt = Format.table,
) -> None:
    """The pumps a workshop builds from a design: every hole off by a little.

    Monte Carlo over the built dimensions: each hole on each link off along
    and across its bar, the wheel axle and the rocker pivot off on the stand,
    by a uniform ±t (or a normal with t = 3σ).  Each build is judged as the
    linkage it is, as pumplink force judges a design: the spread of its swing,
    grip heights and stroke, dead centres, transmission angle, forces and
    flow (median, 5th and 95th percentile), the share of builds that pass
    with its 95 % interval, the holes that matter (first-order sensitivities)
    and the tolerance each group of holes can take for --yield of the builds
    to pass (docs/tolerance.md).  CSV: one row per build, the shares on
    stderr.  Exit 0 when at least --yield of the builds pass (with --strict:
    without warnings), 1 when fewer do, 2 for bad input.

    Example: [bold]pumplink tolerance configs/village-10m.toml --hole 0.5mm --samples 500[/]
    """
    import contextlib
    import functools
    import os
    from concurrent.futures.process import BrokenProcessPool

    from pumplink.inputs.piston import PistonSpec

    s = spec_or_default(spec)  # read once
    if isinstance(s, PistonSpec):
        raise SpecError(f"{spec} is a piston pump (mechanism = 'crank-slider'); tolerance is for rope pumps")
    cluster = dask_cluster() if scheduler is not None else None
    where = cluster.parse_scheduler(scheduler) if cluster is not None else None
    if where is not None and workers != 1:
        raise SpecError(
            f"--workers {workers} is for the local pool; with --scheduler the cluster's workers run the "
            "chunks (local:N sets how many)"
        )
    parts = {
        part: parse_length(text, option)
        for part, text, option in (
            ("crank", crank_hole, "--crank-hole"),
            ("coupler", coupler_hole, "--coupler-hole"),
            ("rocker", rocker_hole, "--rocker-hole"),
        )
        if text is not None
    }
    holes = {} if grip is None else {"rocker.grip": parse_length(grip, "--grip")}
    for item in tol or []:
        key, sep, value = item.partition("=")
        if not sep:
            raise SpecError(f"--tol {item!r} is not HOLE=LENGTH; write e.g. --tol crank.A=0.5mm")
        holes[key.strip()] = parse_length(value, f"--tol {key.strip()}")
    from pumplink.batch import run_module
    from pumplink.output.formats import progress
    from pumplink.output.tolerance import render_tolerance
    from pumplink.studies import tolerance as tl
    from pumplink.studies import tolerance_study as ts

    tols = tl.tolerances(
        parse_length(hole, "--hole"),
        None if pivot is None else parse_length(pivot, "--pivot"),
        parts,
        holes,
        distribution.value,
    )
    prob = tl.problem(s, tols, samples, seed, model_key(model), strict)
    with cluster.connect(where) if where is not None else contextlib.nullcontext() as client:
        if client is not None:
            mapper = functools.partial(cluster.map_ordered, client=client)
        else:
            n = workers or os.cpu_count() or 1
            mapper = functools.partial(run_module.map_ordered, workers=n)
        try:
            with progress(samples, "tolerance (builds)") as advance:
                result = ts.summarize(prob, ts.run_chunks(prob, mapper), target, advance, fmt.value == "csv")
        except BrokenProcessPool as exc:
            what = str(exc) if client is not None else "a worker process was killed (out of memory?)"
            sys.stderr.write(f"interrupted: {what}\n")
            raise typer.Exit(130) from None
    render_tolerance(result, fmt.value)
    raise typer.Exit(0 if result.meets_target else 1)
