"""Command-line interface: parse, call the library, hand the results to ``pumplink.output``.

One module per command (Typer's "one file per command" layout); :mod:`pumplink.cli.common`
holds the app and the shared options.  Exit codes: 0 every design passes (or is feasible, for
``synth``); 1 a design fails a check or is infeasible; 2 the input cannot be used (one line on
stderr, no traceback; ``--debug`` shows it); 130 interrupted, no output file written.  Heavy
imports (numpy, pydantic, scipy) happen inside the commands so ``--help`` starts fast.

Run as the program, the interrupt handler is installed before anything else of pumplink is
imported (:class:`Interrupt`), so that Ctrl-C or SIGTERM ends every run with 130 from its first
line on; only the interpreter's own start-up, before any of pumplink's code runs, is left to
the signal's default action.
"""

from __future__ import annotations

import contextlib
import os
import signal
import sys


class Interrupt:
    """The handler of SIGINT and SIGTERM for one run of the program.

    * While the command modules are imported (before :func:`main`): exit 130 at once; nothing
      has been opened.
    * While a command runs: raise :class:`KeyboardInterrupt`, so that ``finally`` blocks remove
      temporary files and stop worker pools on the way out; :func:`main` then exits 130.
    * Once the run has begun to move a finished file into place (``hold``, called by
      :func:`pumplink.output.formats.atomic_write` just before it replaces the target), or the
      command has returned: nothing.  The run completes and exits with its own code, so that
      130 always means that no output file was written and 0/1 that every file is complete.

    A second signal while the first unwinds is ignored (it would interrupt the clean-up).
    """

    def __init__(self) -> None:
        self.running = False  # main() is running the command
        self.held = False  # the run is past its point of no return
        self.interrupted = False

    def start(self) -> None:
        """A command starts (main): a signal from now on unwinds it."""
        self.running, self.held, self.interrupted = True, False, False

    def __call__(self, signum, frame) -> None:
        if self.held or self.interrupted:
            return
        self.interrupted = True
        if not self.running:
            _interrupted()
        raise KeyboardInterrupt

    def hold(self) -> None:
        """From now on the run completes: a signal no longer interrupts it."""
        self.held = True

    def install(self) -> None:
        signal.signal(signal.SIGINT, self)
        signal.signal(signal.SIGTERM, self)


def _quiet_stdout() -> None:
    """Point fd 1 at /dev/null so the interpreter's final flush cannot fail a second time."""
    with contextlib.suppress(OSError, ValueError):
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())


def _interrupted(say: bool = True) -> None:
    """Exit 130 now.  ``os._exit``: CPython marks a KeyboardInterrupt raised inside ``eval`` (as
    typer evaluates annotations) as unhandled even when it is caught, and would then end the
    process by SIGINT instead of the exit code.  Clean-up (temp files, worker pools) has run in
    the ``finally`` blocks on the way here; stdout is discarded, as the run is incomplete."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, signal.SIG_IGN)
    _quiet_stdout()
    with contextlib.suppress(OSError, ValueError, RuntimeError):  # RuntimeError: a reentrant write
        if say:
            sys.stderr.write("interrupted; no output file written\n")
        sys.stderr.flush()
    os._exit(130)


def _started_as_program() -> bool:
    """True when this import is the start of the program: the ``pumplink`` console script or
    ``python -m pumplink`` (not a test or a notebook importing the module)."""
    main_module = sys.modules.get("__main__")
    spec = getattr(main_module, "__spec__", None)
    if spec is not None:
        return spec.name == "pumplink.__main__"
    script = os.path.basename(getattr(main_module, "__file__", None) or "")
    return script.removesuffix(".exe").removesuffix("-script.py") == "pumplink"


def _unraisable(hook):
    """``sys.unraisablehook`` for the program: a KeyboardInterrupt the handler raised while Python
    ran a callback whose exceptions it cannot propagate (a weak reference's, as the import system's
    module locks use) is not printed as "Exception ignored ... Traceback" and lost: the signal is
    delivered again once this hook has returned, to be raised in the command's own code
    (:class:`Interrupt`).  Not from inside the hook: ``signal.raise_signal`` runs the handler at
    once, and its KeyboardInterrupt, raised in the hook, was printed and lost in turn."""

    def unraisable(args) -> None:
        if issubclass(args.exc_type, KeyboardInterrupt) and INTERRUPT.running and not INTERRUPT.held:
            INTERRUPT.interrupted = False
            _deliver_after_return().set()  # the last statement: the hook returns before it lands
            return
        hook(args)

    return unraisable


def _deliver_after_return():
    """An event that, once set, has a helper thread raise SIGINT: Python's C-level handler marks it
    for the main thread, which runs the handler at its next check, after the caller has returned
    (the helper needs the interpreter lock, which the main thread hands over only after its switch
    interval, 5 ms; from the main thread itself ``signal.raise_signal`` runs the handler at once)."""
    import threading

    ready = threading.Event()

    def deliver() -> None:
        ready.wait()
        signal.raise_signal(signal.SIGINT)

    threading.Thread(target=deliver, name="pumplink-interrupt", daemon=True).start()
    return ready


#: The run's interrupt handler (one per process).
INTERRUPT = Interrupt()
if _started_as_program():
    INTERRUPT.install()
    sys.unraisablehook = _unraisable(sys.unraisablehook)

import gc  # noqa: E402 -- after the handler: an interrupt from here on exits 130
import math  # noqa: E402
import re  # noqa: E402

# Importing a command module registers it; this order is the order of `pumplink --help`.
from pumplink.cli import (  # noqa: E402, F401, I001 -- in the order of `pumplink --help`
    synth,
    force,
    speed,
    init,
    batch,
    optimize,
    size,
    validate,
    tolerance,
    draw,
    template,
    bom,
    sheet,
    report,
    methods,
    transmission,
    slider,
    slotted,
    rocker,
    structure,
    schema,
)
from pumplink.cli.common import app, command_group, settings  # noqa: E402
from pumplink.errors import SHOWN_CHARS, PumplinkError, one_line  # noqa: E402

__all__ = ["app", "main"]


def _option_error(exc, args: list[str]) -> str:
    """A usage error (bad option value, unknown option, missing argument) as one line in the
    style of the spec errors: the option, the value given, what is allowed, where to look."""
    from typer._click import exceptions as ce  # noqa: PLC2701 (typer's bundled click has no public path)

    ctx = getattr(exc, "ctx", None)
    where = f" (see `{ctx.command_path} --help`)" if ctx is not None else ""
    param = getattr(exc, "param", None)
    opts = [o for o in getattr(param, "opts", []) if o.startswith("-")]
    if not isinstance(exc, ce.BadParameter) or isinstance(exc, ce.MissingParameter) or not opts:
        return f"{exc.format_message().rstrip('.')}{where}"
    name = max(opts, key=len)
    raw = _raw_value(opts, args)
    reason = re.sub(r"^Value error, ", "", exc.message).rstrip(".")
    for words, sym in (
        ("greater than or equal to", ">="),
        ("greater than", ">"),
        ("less than or equal to", "<="),
        ("less than", "<"),
    ):
        reason = re.sub(rf"^Input should be {words} (\S+)$", rf"must be {sym} \1", reason)
    reason = re.sub(r"^Input should be a valid (\w+).*", r"is not a valid \1", reason)
    try:
        if raw is not None and not math.isfinite(float(raw)):
            reason = "is not a finite number"
    except ValueError:
        pass
    given = f" {one_line(raw, SHOWN_CHARS)}" if raw is not None else ""
    return f"{name}{given}: {reason}{where}"


def _raw_value(opts: list[str], args: list[str]) -> str | None:
    """The text the user gave for the option ``opts`` (the last occurrence), or None."""
    value = None
    for i, a in enumerate(args):
        for o in opts:
            if a == o and i + 1 < len(args):
                value = args[i + 1]
            elif a.startswith(o + "="):
                value = a[len(o) + 1 :]
    return value


def main(argv: list[str] | None = None) -> None:
    """Console-script entry point: every failure is one line on stderr and an exit code.

    0 pass, 1 fail or infeasible, 2 unusable input or an output that cannot be written (usage
    errors included), 130 interrupted (Ctrl-C or SIGTERM) before any output file was written
    (:class:`Interrupt`: a signal that arrives once the run is writing its files, or has
    finished, lets it complete with its own code).

    Run as the program (``argv`` None), two things keep a short command short.  OpenBLAS, which
    numpy loads, starts one thread per core at import, about 60 ms of CPU on a 2-core machine;
    pumplink's numerics are elementwise and use no multi-threaded linear algebra, so one thread
    is asked for (``OPENBLAS_NUM_THREADS=1``, unless the variable is set; batch workers inherit
    it).  And the garbage collector is told to leave the objects alive at the end alone
    (``gc.freeze``): the process ends next, and the collections the interpreter runs while
    tearing down every module numpy, pydantic, typer and rich loaded cost about a fifth of a
    short command's time.  Exit handlers, ``finally`` blocks and stream flushes run as usual;
    SIGINT and SIGTERM are ignored from here on (the interpreter's tear-down would otherwise
    restore their default action and die of a late signal).  Called with ``argv`` (in a test),
    the previous handlers are restored instead.
    """
    if argv is None:
        os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
    previous = [signal.getsignal(s) for s in (signal.SIGINT, signal.SIGTERM)]
    INTERRUPT.start()
    try:
        try:
            INTERRUPT.install()
            code = _run(sys.argv[1:] if argv is None else list(argv))
        finally:
            INTERRUPT.hold()  # the command has returned or is unwinding: nothing left to interrupt
    except KeyboardInterrupt:
        code = 130
    except Exception as exc:
        if not (INTERRUPT.interrupted and _wraps_an_interrupt(exc)):
            raise
        code = 130  # the interrupt, re-raised by Python as another exception
    if code == 130:  # said here, unless the command said why itself (a killed batch worker)
        _interrupted(say=INTERRUPT.interrupted)
    if argv is None:
        signal.signal(signal.SIGINT, signal.SIG_IGN)
        signal.signal(signal.SIGTERM, signal.SIG_IGN)
        gc.freeze()
    else:
        for sig, handler in zip((signal.SIGINT, signal.SIGTERM), previous):
            if handler is not None:
                signal.signal(sig, handler)
    sys.exit(code)


def _wraps_an_interrupt(exc: BaseException) -> bool:
    """True when a KeyboardInterrupt is the cause or context of ``exc`` (at any depth): Python
    re-raises an exception of some callbacks as another one, e.g. as ``RuntimeError: Error
    calling __set_name__`` while a class is created (3.11), so the handler's interrupt can reach
    :func:`main` in disguise."""
    seen = set()
    while exc is not None and id(exc) not in seen:
        if isinstance(exc, KeyboardInterrupt):
            return True
        seen.add(id(exc))
        exc = exc.__cause__ or exc.__context__
    return False


def _run(args: list[str]) -> int:
    from typer._click import exceptions as ce  # noqa: PLC2701 (typer's bundled click has no public path)
    from typer.exceptions import Abort

    if hasattr(signal, "SIGPIPE"):  # `pumplink ... | head` ends quietly, like any Unix filter (not exit 1)
        signal.signal(signal.SIGPIPE, signal.SIG_DFL)
    for stream in (sys.stdout, sys.stderr):  # a non-UTF-8 terminal or pipe gets '?' for θ, ±, ∞, not a crash
        if hasattr(stream, "reconfigure"):
            stream.reconfigure(errors="replace")
    settings["debug"] = "--debug" in args[:1]
    try:
        code = command_group(app)(args=args, prog_name="pumplink", standalone_mode=False)
        sys.stdout.flush()  # a full disk or a closed pipe is reported here, not at exit
    except PumplinkError as exc:
        if settings["debug"]:
            raise
        return _fail(str(exc), exc.exit_code)
    except ce.NoArgsIsHelpError as exc:  # `pumplink` alone: the help (typer has printed it), exit 2
        if exc.format_message().strip():
            sys.stderr.write(exc.format_message() + "\n")
        return 2
    except ce.UsageError as exc:
        if settings["debug"]:
            raise
        return _fail(_option_error(exc, args), 2)
    except Abort:  # typer's word for a KeyboardInterrupt it caught
        INTERRUPT.interrupted = True
        return 130
    except BrokenPipeError:
        _quiet_stdout()
        return 0
    except OSError as exc:  # writing the output: a full disk (ENOSPC), a read-only or lost device
        if settings["debug"]:
            raise
        _quiet_stdout()
        where = f"{exc.filename}: " if exc.filename else "standard output: "
        return _fail(f"{where}cannot be written ({exc.strerror or exc})", 2)
    return code if isinstance(code, int) else 0


def _fail(message: str, code: int) -> int:
    sys.stderr.write(f"error: {one_line(message)}\n")
    return code
