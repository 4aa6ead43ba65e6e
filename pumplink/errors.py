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


# Characters no name may hold: the controls above, the surrogates (a lone one has no UTF-8
# encoding) and the 66 Unicode noncharacters (U+FDD0-U+FDEF and the last two code points of each
# plane): XML 1.0 cannot carry the C0 controls, the surrogates, U+FFFE and U+FFFF at all, even as
# character references, and a name is written into JUnit XML, CSV, JSON and file names.
_NOT_TEXT = re.compile(
    "[\x00-\x1f\x7f-\x9f\ud800-\udfff\ufdd0-\ufdef"
    + "".join(chr(plane << 16 | 0xFFFE) + chr(plane << 16 | 0xFFFF) for plane in range(17))
    + "]"
)


def bad_character(text: str) -> str | None:
    """What makes ``text`` unfit for a name (the first such character, in words), or None.

    Refused: control characters (C0, DEL, C1), surrogates and the Unicode noncharacters."""
    m = _NOT_TEXT.search(text)
    if m is None:
        return None
    c = m.group()
    if _CONTROL.fullmatch(c):
        return f"a control character ({repr(c)[1:-1]})"
    kind = "a lone surrogate" if 0xD800 <= ord(c) <= 0xDFFF else "a Unicode noncharacter"
    return f"U+{ord(c):04X}, {kind}"


def escape_control(text: str) -> str:
    """``text`` with every control character, surrogate and noncharacter (what no name may hold,
    :func:`bad_character`) written as a Python escape (``\\n``, ``\\x1b``, ``\\ufffe``): one printable
    line, which XML 1.0 can carry too (a file path can hold anything)."""
    return _NOT_TEXT.sub(lambda m: repr(m.group())[1:-1], text)


def shown(value, limit: int = SHOWN_CHARS) -> str:
    """``repr(value)`` for a message: control characters escaped, cut to ``limit`` characters."""
    text = escape_control(repr(value))
    if len(text) > limit:  # a text's own length, else the length of what it is shown as
        text = f"{text[: limit - 1]}… ({len(value) if isinstance(value, str) else len(text):,} characters)"
    return text


def one_line(message: str, limit: int = LINE_CHARS) -> str:
    """A message as one printable line: control characters escaped, cut to ``limit`` characters."""
    text = escape_control(message)
    if len(text) > limit:
        text = f"{text[: limit - 1]}… ({len(text) - limit + 1:,} more characters)"
    return text
