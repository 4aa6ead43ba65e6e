"""Run the real entry point (``pumplink.cli.main``) in this process (test support): cheaper than a
subprocess where the entry point itself, not the program's start-up, is what a test checks."""

from __future__ import annotations

import contextlib
import io
import signal

from pumplink import cli


def run_main(*args) -> tuple[int, str, str]:
    """``pumplink ARGS`` through ``pumplink.cli.main``: exit code, stdout, stderr."""
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        try:
            cli.main([str(a) for a in args])
        except SystemExit as exc:
            code = exc.code
        else:
            code = 0
    return code, out.getvalue(), err.getvalue()


def keep_process_state(monkeypatch):
    """A fixture's body: main() installs signal handlers and may point fd 1 at /dev/null; keep
    both from pytest (``yield from keep_process_state(monkeypatch)``)."""
    saved = {s: signal.getsignal(s) for s in (signal.SIGINT, signal.SIGTERM)}
    monkeypatch.setattr(cli, "_quiet_stdout", lambda: None)
    yield
    for s, h in saved.items():
        signal.signal(s, h)
