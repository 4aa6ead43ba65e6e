"""`pumplink schema`: the JSON Schema of a spec or batch file, for editors that validate TOML."""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Annotated, Optional

import typer

from pumplink.cli.common import app, choices

Kind = choices("Kind", "spec", "piston", "batch")


@app.command()
def schema(
    kind: Annotated[
        Kind, typer.Argument(help="Which file: spec (rope pump), piston (piston pump) or batch.")
    ] = Kind.spec,
    out: Annotated[
        Optional[Path], typer.Option("--out", "-o", help="Write the schema to this .json file.")
    ] = None,
) -> None:
    """JSON Schema of a spec or batch file, so an editor checks keys and ranges as you type.

    Generated from the same models pumplink validates with.  With Taplo ("Even Better TOML" in
    VS Code), put [bold]#:schema pump.schema.json[/] on the first line of a spec.

    Example: [bold]pumplink schema spec --out pump.schema.json[/]
    """
    import json

    from pumplink.inputs.schema import schema as build

    text = json.dumps(build(kind.value), indent=2, ensure_ascii=False) + "\n"
    if out is None:
        sys.stdout.write(text)
        return
    from pumplink.output.formats import atomic_write, check_output

    check_output(out, "--out")
    with atomic_write(out) as f:
        f.write(text)
    sys.stderr.write(f"wrote {out}; first line of a spec: #:schema {out.name}\n")
