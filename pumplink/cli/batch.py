"""`pumplink batch`: many variants at once, for CI and design-space runs."""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Annotated

import typer

from pumplink.cli.common import (
    ModelOpt,
    StrictOpt,
    app,
    choices,
    dask_cluster,
    model_key,
    need_extra,
    optional,
)
from pumplink.errors import SpecError

BatchFormat = choices("BatchFormat", "table", "json", "csv", "parquet")


#: Runs of at least this many variants print their size and estimated time before they start.
LARGE_BATCH = 100_000


@app.command()
def batch(
    inputs: Annotated[
        list[Path],
        typer.Argument(help="Batch files, spec files or folders of them (*.toml).", show_default=False),
    ],
    samples: Annotated[
        int,
        typer.Option(
            metavar="N",
            help="Uniform crank samples per variant for the sampled-peak column "
            "(0: skip it); peak_force_N is exact whatever this is.",
            min=0,
            max=1_000_000,
        ),
    ] = 360,
    fmt: Annotated[
        BatchFormat,
        typer.Option(
            "--format",
            "-f",
            metavar="FORMAT",
            help="table, csv, json or parquet.  Rows as csv or json, or parquet (with --out; needs "
            "pip install 'pumplink\\[parquet]'); table: the summary (and the rows, or the failures "
            "of a large run).",
        ),
    ] = BatchFormat.table,
    out: optional(Path, "Write the rows to this file (atomically) instead of stdout.", "--out", "-o") = None,
    junit: optional(Path, "Also write JUnit XML, one testcase per variant (atomically).", "--junit") = None,
    workers: Annotated[
        int,
        typer.Option(
            metavar="N", help="Worker processes (0: one per CPU; never more than the tasks).", min=0, max=256
        ),
    ] = 1,
    fail_on: Annotated[
        str,
        typer.Option(
            "--fail-on",
            help="What makes the run fail (exit 1): any of mean, peak, infeasible, checks (any "
            "other check that fails: transmission angle, power, grip speed), warnings; all (the "
            "default: mean,peak,infeasible,checks, a variant whose verdict is FAIL) or none. peak is "
            "the verdict's peak: the least peak force "
            "of the flywheel or full dynamics where the variant gives inertia, else the peak outside "
            "the dead bands.",
        ),
    ] = "all",
    strict: StrictOpt = False,
    model: ModelOpt = None,
    chunk: optional(
        str,
        "Evaluate only slice K of N (1-based) of all variants, e.g. 3/8; names stay those of the full run.",
        "--chunk",
    ) = None,
    scheduler: optional(
        str,
        (
            "Run on Dask instead of the local pool: local:N (a local cluster of N worker "
            "processes) or the address of a running scheduler, tcp://host:8786 (needs pip "
            "install 'pumplink\\[dask]'). Same rows, same order."
        ),
        "--scheduler",
    ) = None,
) -> None:
    """Evaluate many variants at once: a base spec plus axes to vary (Cartesian product).

    A batch file is TOML: base = "pump.toml" (or the spec inline as \\[base]) and a \\[vary] table of
    "section.key" = \\[values] or { start, stop, num }.  Plain spec files count as one variant;
    a folder means its *.toml files (not sub-folders).

    One row per variant (lengths, feasibility, forces, verdict) and a summary (counts, the
    passing variant with the lowest peak force, or the closest if none passes).  The verdict is
    that of pumplink force: where the variant gives inertia the least model that is enough
    (flywheel or full dynamics, or --model), else quasi-static with the dead band (the model
    column says which): PASS, PASS with warnings or FAIL, with each check's result in its own
    column.  Exit 0 if no variant
    fails a --fail-on check (default all: no variant FAILs; --strict: none warns either), 1 if one
    does, 2 for bad input.

    Example: [bold]pumplink batch configs/ --junit report.xml[/]

    Piston-pump specs and batch files (mechanism = "crank-slider") run the same way, with every
    option; a run holds one kind of pump.

    Example: [bold]pumplink batch configs/grids/piston-bore.toml --junit piston.xml[/]

    Grids too large for one machine run on Dask (docs/batch.md, "Grids too large for one machine").
    """
    import contextlib
    import functools
    import os
    import time
    from concurrent.futures.process import BrokenProcessPool

    from pumplink import batch as _batch
    from pumplink.output import batchfiles as rb
    from pumplink.output import batchtable
    from pumplink.output.formats import check_output, duration, progress

    t0 = time.perf_counter()
    sel = _batch.parse_fail_on(fail_on + (",warnings" if strict else ""))
    k_n = _batch.parse_chunk(chunk)
    if fmt.value == "table" and out is not None:
        raise SpecError("--out writes rows: give --format csv, json or parquet with it")
    if fmt.value == "parquet":
        if out is None:
            raise SpecError("--format parquet writes a binary file: give --out FILE.parquet with it")
        need_extra("pyarrow", "--format parquet", "parquet", "pyarrow")
    for opt, path in (("--out", out), ("--junit", junit)):  # before any work: fail fast, exit 2
        if path is not None:
            check_output(path, opt)
    cluster = dask_cluster() if scheduler is not None else None  # not installed: one line, exit 2
    where = cluster.parse_scheduler(scheduler) if cluster is not None else None
    if where is not None and workers != 1:
        raise SpecError(
            f"--workers {workers} is for the local pool; with --scheduler the cluster's workers run the "
            "tasks (local:N sets how many)"
        )
    batches = _batch.load_inputs(inputs)
    kinds = {b.mechanism for b in batches}
    if len(kinds) > 1:
        raise SpecError(
            "give piston-pump files (mechanism = 'crank-slider') and rope-pump files in separate runs "
            "(their rows have different columns)"
        )
    if model is not None and kinds == {"crank-slider"}:
        raise SpecError(
            "--model is for rope pumps; a piston pump's model follows its spec (a flywheel or none)"
        )
    key = model_key(model)  # the flywheel and full dynamics decide where the variants give inertia
    tasks = _batch.plan(batches, k_n, _batch.run_module.task_designs(samples))
    total = sum(e - s for _, s, e in tasks)

    with cluster.connect(where) if where is not None else contextlib.nullcontext() as client:
        if client is not None:
            n_workers = min(cluster.threads(client), len(tasks))
        else:
            n_workers = max(1, min(workers or os.cpu_count() or 1, len(tasks)))  # no idle processes
        if total >= LARGE_BATCH:  # say what is coming before a long run starts
            secs = _batch.run_module.estimate_seconds(batches, tasks, samples, n_workers)
            on = f" (Dask, {where})" if where is not None else ""
            sys.stderr.write(
                f"batch: {total:,} variants in {len(tasks):,} tasks on {n_workers} worker"
                f"{'s' if n_workers > 1 else ''}{on}; estimated {duration(secs)} "
                "(Ctrl-C stops it, writing nothing)\n"
            )
        try:
            with progress(total, "batch") as advance:
                post = functools.partial(
                    rb.render_chunk,
                    fmt=fmt.value,
                    vkeys=rb.varied_keys(batches),
                    fail_on=sel,
                    junit=junit is not None,
                )  # runs in the local pool's workers; with Dask in this process, on the arrays sent back
                if client is not None:
                    results = cluster.run(batches, client, samples, k_n, post=post, model=key)
                else:
                    results = _batch.run(batches, samples, k_n, n_workers, post=post, model=key)
                summary, rows = rb.write_stream(
                    batches, results, total, fmt.value, out, junit, sel, samples, k_n, advance
                )
        except BrokenProcessPool as exc:  # a worker was killed (SIGKILL, out of memory), a cluster lost
            what = str(exc) if client is not None else "a worker process was killed (out of memory?)"
            sys.stderr.write(f"interrupted: {what}; no output file written\n")
            raise typer.Exit(130) from None
    if fmt.value == "table":
        batchtable.render_table(summary, rows)
    else:
        wrote = [p for p in (out, junit) if p is not None]
        sys.stderr.write(batchtable.summary_line(summary, time.perf_counter() - t0, wrote) + "\n")
    raise typer.Exit(1 if summary["failed_selected"] else 0)
