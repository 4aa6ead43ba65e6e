"""Command-line interface: parse, call the library, hand the results to ``pumplink.output``.

One module per command (Typer's "one file per command" layout); :mod:`pumplink.cli.common`
holds the app and the shared options.  Exit codes: 0 every design passes (or is feasible, for
``synth``); 1 a design fails a check or is infeasible; 2 the input cannot be used (one line on
stderr, no traceback; ``--debug`` shows it); 130 interrupted.  Heavy imports (numpy, pydantic,
scipy) happen inside the commands so ``--help`` starts fast.
"""

from __future__ import annotations

import signal
import sys

# Importing a command module registers it; this order is the order of `pumplink --help`.
from pumplink.cli import (  # noqa: F401, I001 -- in the order of `pumplink --help`
    synth,
    force,
    speed,
    init,
    batch,
    optimize,
    draw,
    template,
    report,
    methods,
    transmission,
    slider,
    slotted,
    rocker,
    structure,
)
from pumplink.cli.common import app, settings
from pumplink.errors import PumplinkError

__all__ = ["app", "main"]


def main() -> None:
    """Console-script entry point: PumplinkError -> one line on stderr and its exit code."""
    if hasattr(signal, "SIGPIPE"):  # `pumplink ... | head` ends quietly, like any Unix filter (not exit 1)
        signal.signal(signal.SIGPIPE, signal.SIG_DFL)
    for stream in (sys.stdout, sys.stderr):  # a non-UTF-8 terminal or pipe gets '?' for θ, ±, ∞, not a crash
        if hasattr(stream, "reconfigure"):
            stream.reconfigure(errors="replace")
    try:
        app()
    except PumplinkError as exc:
        if settings["debug"]:
            raise
        sys.stderr.write(f"error: {exc}\n")
        sys.exit(exc.exit_code)
    except KeyboardInterrupt:
        sys.stderr.write("interrupted\n")
        sys.exit(130)
    except BrokenPipeError:
        sys.exit(0)
