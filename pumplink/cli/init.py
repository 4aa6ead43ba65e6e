"""`pumplink init`: write a spec to edit."""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Annotated

import typer

from pumplink.cli.common import app
from pumplink.errors import SpecError


@app.command()
def init(
    path: Annotated[Path, typer.Argument(help="Where to write the spec ('-' for stdout).")] = Path(
        "pump.toml"
    ),
    overwrite: Annotated[bool, typer.Option("--force", help="Overwrite an existing file.")] = False,
) -> None:
    """Write the built-in default spec (a realistic prototype) as TOML to edit.

    Example: [bold]pumplink init my-pump.toml[/] then edit it and run [bold]pumplink force my-pump.toml[/]
    """
    import tomli_w

    from pumplink.spec import DEFAULT_SPEC

    text = tomli_w.dumps(DEFAULT_SPEC)
    if str(path) == "-":
        sys.stdout.write(text)
        return
    if path.exists() and not overwrite:
        raise SpecError(f"{path} exists; choose another path or add --force to overwrite it")
    try:
        path.write_text(text, encoding="utf-8")
    except OSError as exc:
        raise SpecError(f"{path}: cannot be written ({exc.strerror})") from None
    typer.echo(f"wrote {path}; edit it, then run: pumplink force {path}", err=True)
