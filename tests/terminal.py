"""Run a command with stderr on a pseudo-terminal (test support): what a user at a terminal sees."""

from __future__ import annotations

import os
import pty
import subprocess


def run_on_terminal(args, timeout: float = 300, **popen):
    """Run ``args`` with stderr on a new pseudo-terminal.

    Returns
    -------
    returncode, terminal text (stderr as drawn), stdout bytes (captured when ``stdout`` is not
    given in ``popen``).
    """
    popen.setdefault("stdout", subprocess.PIPE)
    popen.setdefault("env", {**os.environ, "COLUMNS": "100", "TERM": "xterm"})
    master, slave = pty.openpty()
    p = subprocess.Popen(args, stderr=slave, **popen)
    os.close(slave)
    chunks = []
    while True:
        try:
            data = os.read(master, 65536)
        except OSError:  # the child closed the terminal
            break
        if not data:
            break
        chunks.append(data)
    out = p.communicate(timeout=timeout)[0]
    os.close(master)
    return p.returncode, b"".join(chunks).decode("utf-8", "replace"), out
