"""The example specs shipped with pumplink (``pumplink init --example NAME``).

They are the repository's ``configs/`` and ``examples/`` files, installed as package data in
pumplink/examples/ so the README's commands have their files after a plain ``pip install``.  That
folder is data, not a module: were it imported as ``pumplink.examples`` it would take the place
of :func:`pumplink.examples` on the package.
"""

from __future__ import annotations

import tomllib
from importlib import resources

from pumplink.errors import SpecError


def _root():
    return resources.files("pumplink").joinpath("examples")


def _files() -> dict[str, str]:
    root = _root()
    return {p.name.removesuffix(".toml"): p.name for p in root.iterdir() if p.name.endswith(".toml")}


def example_names() -> dict[str, str]:
    """Shipped example names and each one's design name, sorted."""
    out = {}
    for name, file in sorted(_files().items()):
        data = tomllib.loads(_root().joinpath(file).read_text(encoding="utf-8"))
        out[name] = str(data.get("name", name))
    return out


def example_text(name: str) -> str:
    """The text of the shipped example ``name`` (comments included)."""
    files = _files()
    if name not in files:
        raise SpecError(
            f"--example {name!r} is not a shipped example; choose one of {', '.join(sorted(files))} "
            "(or --example list)"
        )
    return _root().joinpath(files[name]).read_text(encoding="utf-8")
