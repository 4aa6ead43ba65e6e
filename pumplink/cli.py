"""Command-line interface: load spec -> call the library -> hand rows to ``pumplink.report``.

Exit codes: 0 every design passes (or is feasible, for ``synth``); 1 a design fails a check or
is infeasible; 2 the input cannot be used (one line on stderr, no traceback; ``--debug`` shows it).
Heavy imports (numpy, pydantic, scipy) happen inside the commands so ``--help`` starts fast.
"""

from __future__ import annotations

import sys
from enum import Enum
from pathlib import Path
from typing import Annotated, Optional

import typer

from pumplink.errors import PumplinkError, SpecError

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

_state = {"debug": False}


class Format(str, Enum):
    table = "table"
    json = "json"
    csv = "csv"


FormatOpt = Annotated[Format, typer.Option("--format", "-f", help="Output: table (Rich), json or csv.")]
SAMPLE_LIMIT_KEPT = 1_000_000


def _version(value: bool) -> None:
    if value:
        from importlib.metadata import version

        typer.echo(f"pumplink {version('pumplink')}")
        raise typer.Exit()


@app.callback()
def _main(
    debug: Annotated[bool, typer.Option("--debug", help="Show the full traceback on errors.")] = False,
    version: Annotated[Optional[bool], typer.Option("--version", callback=_version, is_eager=True,
                                                    help="Print the version and exit.")] = None,
) -> None:
    _state["debug"] = debug


def _load(paths: list[Path]):
    from pumplink.spec import load_spec

    return [load_spec(p) for p in paths]


@app.command()
def synth(
    specs: Annotated[list[Path], typer.Argument(help="One or more TOML pump specs.", show_default=False)],
    fmt: FormatOpt = Format.table,
) -> None:
    """Dead-centre synthesis: link lengths, dead centres, time ratio, transmission range.

    One row per spec (Table 1 of the pump paper).  Exit 1 if any design is infeasible.

    Example: [bold]pumplink synth configs/prototype.toml configs/*.toml --format json[/]
    """
    from pumplink.analysis import design
    from pumplink.report import render_designs

    designs = [design(s) for s in _load(specs)]
    render_designs(designs, fmt.value)
    raise typer.Exit(0 if all(d.feasible for d in designs) else 1)


@app.command()
def force(
    spec: Annotated[Optional[Path], typer.Argument(help="TOML pump spec; omit for the built-in default design.",
                                                   show_default=False)] = None,
    speed: Annotated[Optional[float], typer.Option(help="Wheel speed \\[deg/s] (default: the spec's operator.speed).",
                                                   min=1e-9, max=7200)] = None,
    samples: Annotated[int, typer.Option(help="Uniform crank samples over one revolution.", min=1, max=1_000_000_000)] = 360,
    at: Annotated[Optional[list[float]], typer.Option("--at", help="Evaluate exactly this crank angle \\[deg] (repeatable).",
                                                      show_default=False)] = None,
    summary: Annotated[bool, typer.Option("--summary", help="Only the checks and verdict (no per-sample rows).")] = False,
    plot: Annotated[Optional[Path], typer.Option(help="Also write the force curve to this .png/.svg/.pdf "
                                                      "(needs the plot extra: pip install 'pumplink[plot]').",
                                                 show_default=False)] = None,
    fmt: FormatOpt = Format.table,
) -> None:
    """Operator force over the crank cycle, the checks and the 100 N verdict.

    The force is quasi-static (Eq. 3 of the pump paper by virtual work): infinite at the two dead
    centres, so the peak is taken outside ±operator.dead_band of them, exactly, whatever
    --samples.  Exit 0 if the design passes, 1 if it fails or is infeasible.

    Example: [bold]pumplink force pump.toml --speed 360 --at 90 --at 270 --format json[/]

    Example: [bold]pumplink force pump.toml --summary --plot force.png[/]
    """
    import math

    from pumplink.analysis import force_analysis
    from pumplink.report import render_force
    from pumplink.spec import default_spec, load_spec

    if at and any(not math.isfinite(a) for a in at):
        raise SpecError(f"--at {next(a for a in at if not math.isfinite(a))!r} is not a finite angle; give degrees such as --at 90")
    if not summary and not at and samples > SAMPLE_LIMIT_KEPT:
        raise SpecError(f"--samples {samples} keeps too many rows (at most {SAMPLE_LIMIT_KEPT:,}); add --summary to stream them")
    if plot is not None:
        from pumplink.plots import check_path, pyplot

        check_path(plot)
        pyplot()  # fail early (exit 2) when matplotlib is missing
    s = load_spec(spec) if spec is not None else default_spec()
    result = force_analysis(s, speed, samples, at_deg=at or None, keep_samples=not summary)
    render_force(result, fmt.value, summary=summary)
    if plot is not None and result.design.feasible:
        from pumplink.plots import force_curve

        force_curve(result, plot)
        sys.stderr.write(f"wrote {plot}\n")
    raise typer.Exit(0 if result.passed else 1)


@app.command()
def init(
    path: Annotated[Path, typer.Argument(help="Where to write the spec ('-' for stdout).")] = Path("pump.toml"),
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


def main() -> None:
    """Console-script entry point: PumplinkError -> one line on stderr and its exit code."""
    for stream in (sys.stdout, sys.stderr):  # a non-UTF-8 terminal or pipe gets '?' for θ, ±, ∞, not a crash
        if hasattr(stream, "reconfigure"):
            stream.reconfigure(errors="replace")
    try:
        app()
    except PumplinkError as exc:
        if _state["debug"]:
            raise
        sys.stderr.write(f"error: {exc}\n")
        sys.exit(exc.exit_code)
    except KeyboardInterrupt:
        sys.stderr.write("interrupted\n")
        sys.exit(130)
    except BrokenPipeError:
        sys.exit(0)
