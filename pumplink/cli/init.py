"""`pumplink init`: write a spec to edit."""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Annotated, Optional

import typer

from pumplink.cli.common import app
from pumplink.errors import SpecError


@app.command()
def init(
    path: Annotated[Path, typer.Argument(help="Where to write the spec ('-' for stdout).")] = Path(
        "pump.toml"
    ),
    example: Annotated[
        Optional[str],
        typer.Option(
            "--example",
            help="Write one of the shipped examples instead (e.g. village-10m); --example list names them.",
            show_default=False,
        ),
    ] = None,
    overwrite: Annotated[bool, typer.Option("--force", help="Overwrite an existing file.")] = False,
) -> None:
    """Write a commented spec to edit (or a shipped example).

    The built-in prototype design, every key commented with its unit and allowed range, the
    operator profile (men; the limits each profile sets listed beside it), and the optional
    keys (axle height, wheel mass for the flywheel model, load from head and pipe, the
    profile's limits, the \\[parts] and \\[use] tables with their defaults) commented out.  The
    design's name is the file's name.

    Example: [bold]pumplink init my-pump.toml[/] then edit it and run [bold]pumplink force my-pump.toml[/]

    Example: [bold]pumplink init village.toml --example village-10m[/]
    """
    from pumplink.inputs.examples import example_names, example_text
    from pumplink.inputs.pump import spec_template

    if example == "list":
        for name, title in example_names().items():
            typer.echo(f"{name:24} {title}")
        return
    if example is not None:
        text = example_text(example)
    else:
        text = spec_template("pump" if str(path) == "-" else path.stem, str(path))
    if str(path) == "-":
        sys.stdout.write(text)
        return
    if path.exists() and not overwrite:
        raise SpecError(f"{path} exists; choose another path or add --force to overwrite it")
    from pumplink.output.formats import atomic_write, check_output

    check_output(path, "init")
    with atomic_write(path) as f:
        f.write(text)
    typer.echo(f"wrote {path}; edit it, then run: pumplink force {path}", err=True)
