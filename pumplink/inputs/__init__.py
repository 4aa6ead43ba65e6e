"""Every file pumplink reads, and nothing else: pump specs (:mod:`~pumplink.inputs.pump`), piston
specs (:mod:`~pumplink.inputs.piston`), batch files for both (:mod:`~pumplink.inputs.batch`),
mechanism files (:mod:`~pumplink.inputs.structure`), their JSON Schemas
(:mod:`~pumplink.inputs.schema`), all read and validated the same way
(:mod:`~pumplink.inputs.toml`)."""

from __future__ import annotations

from pathlib import Path


def load(path: str | Path):
    """Read a spec file once and validate it as the pump it describes: a piston pump
    (:class:`~pumplink.inputs.piston.PistonSpec`) where it says ``mechanism = "crank-slider"``
    (docs/piston-pump.md), else a rope pump (:class:`~pumplink.inputs.pump.PumpSpec`); ``-`` is
    standard input.

    Raises
    ------
    SpecError : an unreadable file, invalid TOML, a batch file, or an invalid spec.
    """
    from pumplink.inputs.piston import PistonSpec
    from pumplink.inputs.pump import PumpSpec
    from pumplink.inputs.toml import read_spec

    return read_spec(path, PumpSpec, PistonSpec)
