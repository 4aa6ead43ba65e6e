"""The one family of exceptions pumplink raises.

Every message states the offending value, the limit it broke and a fix, in one sentence, so the
CLI can print it as a single line on stderr.  Exit codes (see ``pumplink.cli``):

* :class:`SpecError` - the input cannot be used (exit 2).
* :class:`InfeasibleDesign` - the input is valid but describes no pump linkage (exit 1).
"""

from __future__ import annotations

import re


class PumplinkError(Exception):
    """Base class of every error pumplink raises on purpose."""

    exit_code = 2


class SpecError(PumplinkError, ValueError):
    """A spec or command-line value that cannot be used (bad file, bad key, bad value)."""

    exit_code = 2


class InfeasibleDesign(PumplinkError):
    """A valid spec for which the dead-centre synthesis gives no crank-rocker."""

    exit_code = 1


#: Longest piece of user text (a name, a key, a value) echoed in one message [characters].
SHOWN_CHARS = 80

#: Longest error line the CLI prints [characters]; the rest is cut with a note of how much.
LINE_CHARS = 1000

# C0 and C1 control characters and DEL: never echoed raw (a newline splits the one-line error,
# an escape sequence recolours or clears the terminal).
_CONTROL = re.compile(r"[\x00-\x1f\x7f-\x9f]")


def has_control(text: str) -> bool:
    """True when ``text`` contains a control character (newline, tab, escape, ...)."""
    return _CONTROL.search(text) is not None


def escape_control(text: str) -> str:
    """``text`` with every control character written as a Python escape (``\\n``, ``\\x1b``)."""
    return _CONTROL.sub(lambda m: repr(m.group())[1:-1], text)


def shown(value, limit: int = SHOWN_CHARS) -> str:
    """``repr(value)`` for a message: control characters escaped, cut to ``limit`` characters."""
    text = escape_control(repr(value))
    if len(text) > limit:
        text = f"{text[: limit - 1]}… ({len(text):,} characters)"
    return text


def one_line(message: str, limit: int = LINE_CHARS) -> str:
    """A message as one printable line: control characters escaped, cut to ``limit`` characters."""
    text = escape_control(message)
    if len(text) > limit:
        text = f"{text[: limit - 1]}… ({len(text) - limit + 1:,} more characters)"
    return text
