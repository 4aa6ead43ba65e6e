"""The shipped specs and the operator profiles, for tests parametrised over them (test support).

Shipped: configs/*.toml, examples/*.toml and the package's pumplink/examples/*.toml (links to the
first two, listed once each by the file they resolve to).  Rope-pump specs only: a batch file
(``vary``/``base``) and a piston-pump spec (``mechanism``) are not drawn, templated or reported
(the loader refuses them with one line: tests/cli/test_mechanism_commands.py).
"""

from __future__ import annotations

import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def rope_pump_specs() -> list[Path]:
    """Every shipped rope-pump spec, once (by the file it resolves to)."""
    found: dict[Path, Path] = {}
    for folder in ("configs", "examples", "pumplink/examples"):
        for path in sorted((ROOT / folder).glob("*.toml")):
            data = tomllib.loads(path.read_text(encoding="utf-8"))
            if not ({"vary", "base", "mechanism"} & data.keys()):
                found.setdefault(path.resolve(), path)
    return list(found.values())


ROPE_PUMP_SPECS = rope_pump_specs()
#: The operator profiles (pumplink.profiles.PROFILES), written out so that a new one is noticed.
PROFILE_NAMES = ("men", "women", "children", "accessible")


def spec_id(path: Path) -> str:
    return str(path.relative_to(ROOT))
