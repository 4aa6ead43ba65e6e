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
    from pumplink.inputs.piston import parse_piston
    from pumplink.inputs.pump import spec_from_file_data
    from pumplink.inputs.toml import is_piston_data, read_toml, spec_name

    data = read_toml(path)
    if is_piston_data(data):
        return parse_piston(spec_name(data, path), source=str(path))
    return spec_from_file_data(data, path)
