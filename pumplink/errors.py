"""The one family of exceptions pumplink raises.

Every message states the offending value, the limit it broke and a fix, in one sentence, so the
CLI can print it as a single line on stderr.  Exit codes (see ``pumplink.cli``):

* :class:`SpecError` - the input cannot be used (exit 2).
* :class:`InfeasibleDesign` - the input is valid but describes no pump linkage (exit 1).
"""

from __future__ import annotations


class PumplinkError(Exception):
    """Base class of every error pumplink raises on purpose."""

    exit_code = 2


class SpecError(PumplinkError, ValueError):
    """A spec or command-line value that cannot be used (bad file, bad key, bad value)."""

    exit_code = 2


class InfeasibleDesign(PumplinkError):
    """A valid spec for which the dead-centre synthesis gives no crank-rocker."""

    exit_code = 1
