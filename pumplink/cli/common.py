"""The Typer app, the options every command shares, and spec loading for the commands."""

from __future__ import annotations

import copy
import inspect
import math
import re
from collections.abc import MutableMapping
from enum import Enum
from pathlib import Path
from typing import Annotated, Optional

import typer


def terminal_paragraphs(doc: str) -> str:
    """A docstring as help text for the terminal to wrap: each paragraph (blank-line separated) on
    one line.  Typer's rich mode keeps a docstring's line breaks after the first paragraph, so a
    text wrapped at the source's width would come out ragged in an 80-column terminal."""
    return "\n\n".join(" ".join(p.split()) for p in inspect.cleandoc(doc).split("\n\n"))


class _App(typer.Typer):
    """The Typer app, whose commands' help is their docstring as :func:`terminal_paragraphs`."""

    def command(self, *args, **kwargs):
        register = super().command(*args, **kwargs)

        def decorator(f):
            register(f)
            info = self.registered_commands[-1]
            if info.help is None and f.__doc__:
                info.help = terminal_paragraphs(f.__doc__)
            return f

        return decorator


app = _App(
    name="pumplink",
    help="Design the four-bar linkage that lets a standing operator drive a rope pump by hand.\n\n"
    "Example: [bold]pumplink init pump.toml && pumplink force pump.toml --speed 360[/]",
    no_args_is_help=True,
    rich_markup_mode="rich",
    pretty_exceptions_enable=False,
    context_settings={"help_option_names": ["-h", "--help"]},
    add_completion=True,
)


class _LazyCommands(MutableMapping):
    """The group's commands by name, in registration order, each built on first look-up.

    Typer builds a command from its function's signature (evaluating every annotation and
    option), about a millisecond a command; a run needs only its own command, ``--help`` and
    shell completion go through all of them in order."""

    def __init__(self, typer_app: typer.Typer):
        from typer.main import get_command_name

        self._app = typer_app
        commands = typer_app.registered_commands
        self._infos = {c.name or get_command_name(c.callback.__name__): c for c in commands}
        self._built: dict = {}

    def __getitem__(self, name: str):
        if name not in self._built:
            from typer.main import get_command_from_info

            self._built[name] = get_command_from_info(
                self._infos[name],  # KeyError for an unknown command, as in a dict
                pretty_exceptions_short=self._app.pretty_exceptions_short,
                rich_markup_mode=self._app.rich_markup_mode,
            )
        return self._built[name]

    def __setitem__(self, name: str, command) -> None:
        self._infos.setdefault(name, None)
        self._built[name] = command

    def __delitem__(self, name: str) -> None:
        del self._infos[name]
        self._built.pop(name, None)

    def __iter__(self):
        return iter(self._infos)

    def __len__(self) -> int:
        return len(self._infos)


def command_group(typer_app: typer.Typer):
    """The click group that ``typer_app(...)`` would run, with each command built only when it is
    looked up (:class:`_LazyCommands`): ``pumplink force`` builds ``force`` alone."""
    from typer.main import get_command

    shell = copy.copy(typer_app)  # the callback and the top-level options, no commands yet
    shell.registered_commands = []
    group = get_command(shell)
    group.commands = _LazyCommands(typer_app)
    return group


#: Options of the top-level callback that the entry point needs (``--debug``).
settings = {"debug": False}


def choices(name: str, *values: str) -> type[Enum]:
    """The words an option takes, as the str Enum typer lists as its choices (member names = the
    words; typer needs the str mixin, not a StrEnum)."""
    return Enum(name, [(v, v) for v in values], type=str)


Format = choices("Format", "table", "json", "csv")


FormatOpt = Annotated[Format, typer.Option("--format", "-f", help="Output: table (Rich), json or csv.")]


def optional(kind, help: str, *names: str, argument: bool = False, **settings):
    """The type of an option (``argument``: a positional argument) that may be left out: None when
    it is, and no default in ``--help`` (its help says what leaving it out means).

    ``names``: its flags (none: from the parameter's name); ``settings``: typer's other settings
    (``metavar``, ``min``, ...).  ``x: optional(float, "...") = None`` stands for
    ``x: Annotated[Optional[float], typer.Option(help="...", show_default=False)] = None``.
    """
    make = typer.Argument if argument else typer.Option
    return Annotated[Optional[kind], make(*names, help=help, show_default=False, **settings)]


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
        metavar="MODEL",
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


#: Units a wheel speed may be given in on the command line, to deg/s.
SPEED_UNITS = {"deg/s": 1.0, "rpm": 6.0, "rad/s": 180.0 / math.pi}

#: Largest wheel speed [deg/s] (the spec's operator.speed limit: 20 rev/s).
SPEED_MAX = 7200.0


def parse_speed(text: str | float) -> float:
    """A wheel speed with an optional unit -> deg/s: ``360``, ``360deg/s``, ``60rpm``, ``6.28rad/s``.

    Raises ``typer.BadParameter`` (one line, exit 2) for an unknown unit, a value that is not a
    finite number, or one outside 0 < speed <= 7200 deg/s.
    """
    if isinstance(text, (int, float)):
        value, unit = float(text), "deg/s"
    else:
        m = re.fullmatch(r"\s*([^a-zA-Z/\s]*(?:inf|nan|infinity)?)\s*([a-zA-Z/]*)\s*", text, re.I)
        number, unit = (m.group(1), m.group(2).lower()) if m else (text, "")
        unit = unit or "deg/s"
        if not number.strip():
            raise typer.BadParameter("is not a number; give e.g. 360, 360deg/s, 60rpm or 6.28rad/s")
        if unit not in SPEED_UNITS:
            raise typer.BadParameter(f"unknown unit '{unit}'; give deg/s (the default), rpm or rad/s")
        try:
            value = float(number)
        except ValueError:
            raise typer.BadParameter("is not a number; give e.g. 360, 360deg/s, 60rpm or 6.28rad/s") from None
    if not math.isfinite(value):
        raise typer.BadParameter("is not a finite number")
    deg_s = value * SPEED_UNITS[unit]
    if not 0 < deg_s <= SPEED_MAX:
        raise typer.BadParameter(
            f"is out of range; allowed: 0 < speed <= {SPEED_MAX:g} deg/s ({SPEED_MAX / 6:g} rpm)"
        )
    return deg_s


def speed_option(*names: str, help: str):
    """A wheel-speed option that takes units (:func:`parse_speed`)."""
    return typer.Option(
        *names,
        parser=parse_speed,
        metavar="SPEED",
        help=f"{help} In \\[deg/s], or with a unit: 60rpm, 6.28rad/s.",
    )


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
    from pumplink.inputs.pump import load_spec

    return [load_spec(p) for p in paths]


def spec_or_default(path: Path | None):
    """The spec at ``path``, read once (a rope pump's or a piston pump's,
    :func:`pumplink.inputs.load`); without one, ``./pump.toml`` if it exists (saying so on
    stderr), else the built-in design."""
    from pumplink.inputs import load
    from pumplink.inputs.pump import default_spec

    if path is not None:
        return load(path)
    if LOCAL_SPEC.is_file():
        typer.echo(f"using ./{LOCAL_SPEC} (give a spec file to use another)", err=True)
        return load(LOCAL_SPEC)
    return default_spec()


#: Units a length may be given in on the command line (tolerances), to metres.
LENGTH_UNITS = {"mm": 1e-3, "cm": 1e-2, "m": 1.0}


def parse_length(text: str, option: str) -> float:
    """A length with its unit -> metres: ``1mm``, ``0.5 mm``, ``0.1cm``, ``0.001m``.

    The unit is required (a bare ``1`` could be a metre or a millimetre).  Raises
    :class:`~pumplink.errors.SpecError` (one line, exit 2) naming the option.
    """
    from pumplink.errors import SpecError, shown

    m = re.fullmatch(r"\s*([0-9.eE+-]+)\s*([a-z]*)\s*", str(text))
    unit = m.group(2) if m else ""
    if not m or unit not in LENGTH_UNITS:
        raise SpecError(
            f"{option} {shown(str(text))} is not a length with a unit; give e.g. {option} 1mm "
            "(units: mm, cm, m)"
        )
    try:
        value = float(m.group(1)) * LENGTH_UNITS[unit]
    except ValueError:
        raise SpecError(f"{option} {shown(str(text))} is not a number; give e.g. {option} 1mm") from None
    if not math.isfinite(value) or value < 0:
        raise SpecError(f"{option} {shown(str(text))} must be a length of 0 or more, e.g. {option} 1mm")
    return value


def need_extra(module: str, option: str, extra: str, what: str) -> None:
    """One line saying how to install an optional extra when ``module`` cannot be imported (exit 2)."""
    import importlib

    from pumplink.errors import SpecError

    try:
        importlib.import_module(module)
    except ImportError:
        raise SpecError(
            f"{option} needs {what}, which is not installed; install it with pip install 'pumplink[{extra}]'"
        ) from None


def dask_cluster():
    """:mod:`pumplink.batch.cluster` for ``--scheduler``, or one line saying how to install Dask
    (exit 2)."""
    need_extra("distributed", "--scheduler", "dask", "Dask")
    from pumplink.batch import cluster

    return cluster


#: ``--tolerance`` and ``--yield`` of the searches (size, optimize): a robust design.
ToleranceOpt = optional(
    str,
    "Ask for a robust design: every hole and pivot built within ±LENGTH (e.g. 1mm) and at least "
    "--yield of such builds passing, to first order in the search and checked on the answer by a "
    "Monte Carlo of 2,000 builds (docs/tolerance.md).",
    "--tolerance",
    metavar="LENGTH",
)
YieldOpt = optional(
    float,
    "With --tolerance: the share of builds that must pass (default 0.95).",
    "--yield",
    min=0.5,
    max=0.9999,
)


def robust_ask(tolerance: str | None, target: float | None, strict: bool = False):
    """The search's :class:`pumplink.studies.tolerance_study.Robust` for ``--tolerance``/``--yield`` (None
    without --tolerance); --yield alone is a SpecError."""
    from pumplink.errors import SpecError

    if tolerance is None:
        if target is not None:
            raise SpecError("--yield is the share of builds at --tolerance that pass: give --tolerance too")
        return None
    from pumplink.studies.tolerance import tolerances
    from pumplink.studies.tolerance_study import Robust

    return Robust(
        tolerances(parse_length(tolerance, "--tolerance")), 0.95 if target is None else target, strict
    )
