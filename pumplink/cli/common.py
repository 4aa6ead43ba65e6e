"""The Typer app, the options every command shares, and spec loading for the commands."""

from __future__ import annotations

from enum import Enum
from pathlib import Path
from typing import Annotated, Optional

import typer

app = typer.Typer(
    name="pumplink",
    help="Design the four-bar linkage that lets a standing operator drive a rope pump by hand.\n\n"
    "Example: [bold]pumplink init pump.toml && pumplink force pump.toml --speed 360[/]",
    no_args_is_help=True,
    rich_markup_mode="rich",
    pretty_exceptions_enable=False,
    context_settings={"help_option_names": ["-h", "--help"]},
    add_completion=False,
)


#: Options of the top-level callback that the entry point needs (``--debug``).
settings = {"debug": False}


class Format(str, Enum):  # noqa: UP042 -- typer needs the str mixin semantics unchanged
    table = "table"
    json = "json"
    csv = "csv"


FormatOpt = Annotated[Format, typer.Option("--format", "-f", help="Output: table (Rich), json or csv.")]


SAMPLE_LIMIT_KEPT = 1_000_000


class Model(str, Enum):  # noqa: UP042 -- typer needs the str mixin semantics unchanged
    quasi_static = "quasi-static"
    flywheel = "flywheel"
    dynamics = "dynamics"


#: ``--model`` of force, speed, batch and optimize (the same option and words everywhere).
ModelOpt = Annotated[
    Optional[Model],
    typer.Option(
        "--model",
        help="Decide with this model: quasi-static, flywheel or dynamics (default: the least model "
        "that is enough, see force --explain; the last two need the wheel's inertia).",
        show_default=False,
    ),
]


def model_key(model: Model | None) -> str | None:
    """The registry key of ``--model`` (None: the automatic choice)."""
    return None if model is None else model.value


StrictOpt = Annotated[
    bool,
    typer.Option(
        "--strict", help="Warnings fail too: exit 1 unless the verdict is a clean PASS (for CI gates)."
    ),
]

#: The spec a command uses when none is given and it exists in the working directory.
LOCAL_SPEC = Path("pump.toml")


def _version(value: bool) -> None:
    if value:
        from importlib.metadata import version

        typer.echo(f"pumplink {version('pumplink')}")
        raise typer.Exit()


@app.callback()
def _main(
    debug: Annotated[bool, typer.Option("--debug", help="Show the full traceback on errors.")] = False,
    version: Annotated[
        Optional[bool],
        typer.Option("--version", callback=_version, is_eager=True, help="Print the version and exit."),
    ] = None,
) -> None:
    settings["debug"] = debug


def load_specs(paths: list[Path]):
    from pumplink.spec import load_spec

    return [load_spec(p) for p in paths]


def spec_or_default(path: Path | None):
    """The spec at ``path``; without one, ``./pump.toml`` if it exists (saying so on stderr), else
    the built-in design."""
    from pumplink.spec import default_spec, load_spec

    if path is not None:
        return load_spec(path)
    if LOCAL_SPEC.is_file():
        typer.echo(f"using ./{LOCAL_SPEC} (give a spec file to use another)", err=True)
        return load_spec(LOCAL_SPEC)
    return default_spec()
