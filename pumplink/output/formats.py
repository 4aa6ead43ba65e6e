"""The one output dispatch: number formatting, JSON and CSV writers, the console, progress.

Degrees appear in the output layer only; the library works in radians.  NaN becomes ``null``
in JSON, an empty cell in CSV and "—" (or "∞") in tables.
"""

from __future__ import annotations

import contextlib
import csv
import errno
import json
import math
import os
import signal
import stat
import sys
import tempfile
import time
from collections.abc import Callable, Iterable, Iterator
from pathlib import Path
from typing import Any

import numpy as np

from pumplink.errors import SpecError

FORMATS = ("table", "json", "csv")


def num(x) -> float | None:
    """A JSON-safe float: None for None, NaN and inf."""
    if x is None:
        return None
    x = float(x)
    return x if math.isfinite(x) else None


def deg(x) -> float | None:
    return num(np.degrees(x))


# ----------------------------------------------------------------------------- progress
@contextlib.contextmanager
def progress(
    total: int, label: str = "batch", enabled: bool | None = None, delay: float = 1.0
) -> Iterator[Callable[[int], None]]:
    """``advance(n)`` for a Rich progress bar on stderr, shown only on a terminal and only once
    the run has taken longer than ``delay`` seconds."""
    if enabled is None:
        enabled = sys.stderr.isatty()
    state: dict[str, Any] = {"done": 0, "bar": None, "t0": time.monotonic()}

    def advance(n: int) -> None:
        state["done"] += n
        if not enabled:
            return
        if state["bar"] is None and time.monotonic() - state["t0"] > delay:
            from rich.console import Console
            from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeRemainingColumn

            bar = Progress(
                TextColumn(label),
                BarColumn(),
                MofNCompleteColumn(),
                TimeRemainingColumn(),
                console=Console(stderr=True),
                transient=True,
            )
            bar.start()
            state["bar"], state["task"] = bar, bar.add_task(label, total=total)
        if state["bar"] is not None:
            state["bar"].update(state["task"], completed=state["done"])

    try:
        yield advance
    finally:
        if state["bar"] is not None:
            state["bar"].stop()


# ----------------------------------------------------------------------------- output files
def check_output(path, option: str = "--out") -> Path:
    """Fail fast (exit 2, one line) when ``path`` cannot be an output file: a folder, or a
    folder that does not exist or cannot be written.  Checked before any work is done."""
    path = Path(path)
    target = Path(os.path.realpath(path))
    if target.is_dir():
        raise SpecError(f"{option} {path}: is a folder; give a file name")
    if not target.parent.is_dir():
        raise SpecError(f"{option} {path}: folder {target.parent} does not exist")
    special = target.exists() and not stat.S_ISREG(target.stat().st_mode)
    if not os.access(target if special else target.parent, os.W_OK):
        what = target if special else f"folder {target.parent}"
        raise SpecError(f"{option} {path}: {what} is not writable")
    return path


def _open_unnamed(folder: Path) -> int | None:
    """A file in ``folder`` with no name (Linux O_TMPFILE): nothing is left behind if the
    process is killed before it is linked.  None where the system or file system lacks it."""
    flag = getattr(os, "O_TMPFILE", 0)
    if not flag or not Path("/proc/self/fd").is_dir():
        return None
    try:
        return os.open(folder, flag | os.O_WRONLY, 0o666)  # the umask applies, as for any new file
    except OSError:
        return None


_WRITE_ERRORS = (errno.ENOSPC, errno.EDQUOT, errno.EFBIG, errno.EIO, errno.EROFS, errno.EACCES, errno.EPERM)


@contextlib.contextmanager
def atomic_write(path, binary: bool = False) -> Iterator[Any]:
    """A file that appears at ``path`` complete or not at all.

    The data go to a temporary file in the target's folder - unnamed where the system allows
    (Linux O_TMPFILE), so that even a SIGKILL leaves nothing - then replace the target in one
    ``os.replace``.  A symbolic link is followed (the link stays, its target is replaced).  A
    target that is not a regular file (``/dev/null``, a FIFO, a terminal) is written in place:
    a device is never renamed over.  A full disk or a read-only folder is a
    :class:`~pumplink.errors.SpecError` naming the path (one line, exit 2), and the temporary file
    is removed.
    """
    path = Path(path)
    target = Path(os.path.realpath(path))
    if target.is_dir():
        raise SpecError(f"{path}: is a folder; give a file name to write")
    mode, kw = ("wb", {}) if binary else ("w", {"encoding": "utf-8", "newline": ""})
    if target.exists() and not stat.S_ISREG(target.stat().st_mode):  # a device or a pipe
        with _write_errors(path), open(target, mode, **kw) as f:
            yield f
        return
    tmp = None
    try:
        try:
            fd = _open_unnamed(target.parent)
            if fd is None:
                fd, tmp = tempfile.mkstemp(prefix=f".{target.name}.", suffix=".tmp", dir=target.parent)
                umask = os.umask(0)
                os.umask(umask)
                os.chmod(tmp, 0o666 & ~umask)  # mkstemp makes 0600; give the file a normal file's mode
        except OSError as exc:
            raise SpecError(
                f"{path}: cannot be written ({exc.strerror}); check that the folder "
                f"{target.parent} exists and is writable"
            ) from None
        with _write_errors(path), os.fdopen(fd, mode, **kw) as f:
            yield f
            f.flush()
            os.fsync(f.fileno())
            _hold_interrupts()  # the file is complete: from here the run completes
            if tmp is None:  # give the unnamed file a name next to the target, then move it
                tmp = tempfile.mktemp(prefix=f".{target.name}.", suffix=".tmp", dir=target.parent)
                root = os.open("/", os.O_RDONLY)
                try:  # a dir_fd makes CPython call linkat(AT_SYMLINK_FOLLOW), which /proc needs
                    os.link(f"/proc/self/fd/{f.fileno()}", tmp, src_dir_fd=root, follow_symlinks=True)
                finally:
                    os.close(root)
            with _write_errors(path):
                os.replace(tmp, target)
    except BaseException:
        if tmp is not None:
            with contextlib.suppress(OSError):
                os.unlink(tmp)
        raise


def _hold_interrupts() -> None:
    """Tell the program's interrupt handler, if it has one, that a finished file is about to
    replace its target: the run then completes, and an interrupt never leaves some of a run's
    files written while it reports none (exit 130 means no output file was written).  The
    handler is the command line's (:class:`pumplink.cli.Interrupt`, which has ``hold``); it is
    found through the signal module, as this layer does not import the command line.  Elsewhere
    (a notebook, a test) there is no such handler and nothing changes."""
    hold = getattr(signal.getsignal(signal.SIGTERM), "hold", None)
    if callable(hold):
        hold()


@contextlib.contextmanager
def _write_errors(path) -> Iterator[None]:
    """A full disk, a quota, a file-size limit, a read-only or failing device: SpecError."""
    try:
        yield
    except OSError as exc:
        if exc.errno not in _WRITE_ERRORS:
            raise
        raise SpecError(f"{path}: cannot be written ({exc.strerror}); nothing was written") from None


# ----------------------------------------------------------------------------- text output
def write_json(obj, out, stream: tuple[str, Iterable[Any]] | None = None) -> None:
    """``obj`` as indented JSON; ``stream=(key, items)`` appends ``key`` as a list written one
    item at a time (memory: one item), byte for byte what ``json.dumps`` would write."""
    # ASCII JSON (\u escapes): valid whatever the terminal's or pipe's encoding.
    if stream is None:
        out.write(json.dumps(obj, indent=2, allow_nan=False) + "\n")
        return
    key, items = stream
    head = json.dumps({**obj, key: []}, indent=2, allow_nan=False)
    assert head.endswith(": []\n}")
    out.write(head[: -len("]\n}")])
    first = True
    for item in items:
        text = json.dumps(item, indent=2, allow_nan=False).replace("\n", "\n    ")
        out.write(("\n    " if first else ",\n    ") + text)
        first = False
    out.write("]\n}\n" if first else "\n  ]\n}\n")


def render(
    fmt: str,
    out,
    *,
    as_json: Callable[[], Any],
    as_csv: Callable[[], Iterable[dict[str, Any]]],
    table: Callable[[], None],
    stream: Callable[[], tuple[str, Iterable[Any]] | None] = lambda: None,
) -> None:
    """The one dispatch of every command's view: ``--format json`` writes ``as_json()`` (with the
    list ``stream()`` gives streamed after it, when any), ``csv`` the rows ``as_csv()`` gives, and
    ``table`` draws ``table()``.  Views hand in what each format shows; they choose nothing."""
    if fmt == "json":
        return write_json(as_json(), out, stream=stream())
    if fmt == "csv":
        return write_csv(as_csv(), out)
    if fmt != "table":
        raise ValueError(f"unknown format {fmt!r}; one of {', '.join(FORMATS)}")
    return table()


def _flatten(row: dict[str, Any], prefix: str = "") -> dict[str, Any]:
    flat: dict[str, Any] = {}
    for k, v in row.items():
        if isinstance(v, dict):
            flat.update(_flatten(v, f"{prefix}{k}_"))
        elif isinstance(v, list) and k == "rocker_pivot":
            flat[f"{prefix}rocker_pivot_x"], flat[f"{prefix}rocker_pivot_y"] = v
        elif isinstance(v, list):
            continue  # checks: in JSON and the table only
        else:
            flat[prefix + k] = "" if v is None else v
    return flat


def write_csv(rows: Iterable[dict[str, Any]], out) -> None:
    """CSV with a header from the first row; nested keys flattened with '_' (streamed: one row at
    a time in memory)."""
    it = iter(rows)
    first = next(it, None)
    if first is None:
        return
    first = _flatten(first)
    w = csv.DictWriter(out, fieldnames=list(first), lineterminator="\n")
    w.writeheader()
    w.writerow(first)
    for r in it:
        w.writerow(_flatten(r))


#: Width of tables and text when the output is not a terminal and ``COLUMNS`` is not set.
DEFAULT_WIDTH = 80


def width() -> int | None:
    """``COLUMNS`` when set to a sane width (20-1000), else None."""
    try:
        w = int(os.environ.get("COLUMNS", ""))
    except ValueError:
        return None
    return w if 20 <= w <= 1000 else None


def console(file=None):
    """A Rich console: colour only on a terminal (and never with NO_COLOR); the terminal's width,
    else ``COLUMNS``, else 80 columns when piped."""
    from rich.console import Console

    file = file or sys.stdout
    tty = hasattr(file, "isatty") and file.isatty()
    w = width()
    if w is None and not tty:
        w = DEFAULT_WIDTH
    return Console(file=file, highlight=False, width=w, soft_wrap=False)


def report_table(title: str, caption: str | None = None):
    """A Rich table in the reports' style: the title (and the caption) on the left, a rule under
    the header, no padding at the edges."""
    from rich import box
    from rich.table import Table

    return Table(
        title=title,
        title_justify="left",
        caption=caption,
        caption_justify="left",
        box=box.SIMPLE_HEAD,
        pad_edge=False,
    )


def duration(seconds: float) -> str:
    """A time for people: '40 s', '12 min', '3 h 20 min', '5.2 days'."""
    if seconds < 60:
        return f"{seconds:.0f} s"
    if seconds < 3600:
        return f"{seconds / 60:.0f} min"
    if seconds < 86400 * 2:
        return f"{seconds // 3600:.0f} h {seconds % 3600 / 60:.0f} min"
    return f"{seconds / 86400:.1f} days"


def fmt(x, fmt="{:.3f}", none="—") -> str:
    """``x`` formatted, or ``none`` for None, NaN and inf."""
    return none if x is None or not math.isfinite(float(x)) else fmt.format(float(x))
