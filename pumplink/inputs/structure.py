"""The structure-analysis input: a mechanism written by hand in TOML, validated by pydantic.

Schema (docs/mechanisms.md §3; examples in configs/mechanisms/)::

    name = "Six-link mechanism"        # optional; default: the file stem
    frame = "0"                        # the fixed link
    links = ["0", "1", "2", "3", "4", "5"]
    drivers = ["1"]                    # optional: the driving link(s); default: found
    passive_links = []                 # optional: links whose constraints are redundant
    local_mobilities = 0               # optional: local freedoms (a roller's spin)

    [joints]                           # one entry per joint: its pair class and its links
    A = { kind = "revolute", links = ["0", "1"] }
    C = { kind = "revolute", links = ["2", "3", "4"] }   # a multiple hinge: 3 links = 2 pairs
    F = { kind = "prismatic", links = ["5", "0"] }
    # kind: revolute or prismatic (lower pair, class V, 1 freedom) or higher (class IV, 2 freedoms)

Every problem is one sentence naming the key (:class:`~pumplink.errors.SpecError`, exit 2).
"""

from __future__ import annotations

from pathlib import Path
from typing import Literal

from pydantic import Field

from pumplink.errors import SpecError
from pumplink.inputs.toml import Section, optional, read_toml, spec_name, validate
from pumplink.mechanisms import structure as _structure

Name = str


class JointSpec(Section):
    kind: Literal["revolute", "prismatic", "higher"] = Field(
        description="pair class: revolute or prismatic (lower, 1 freedom) or higher (2 freedoms)"
    )
    links: list[Name] = Field(min_length=2, description="names of the links the joint connects")


class StructureSpec(Section):
    name: str = Field(default="mechanism", min_length=1, max_length=200, description="name")
    frame: Name = Field(description="name of the fixed link")
    links: list[Name] = Field(min_length=2, description="names of all links, the frame included")
    joints: dict[Name, JointSpec] = Field(
        min_length=1, description="table of joints: name = { kind = ..., links = [...] }"
    )
    drivers: list[Name] | None = optional("driving link(s) (default: found)")
    passive_links: list[Name] = Field(default=[], description="links whose constraints are redundant")
    local_mobilities: int = Field(default=0, ge=0, le=100, description="number of local freedoms")

    def joint_tuples(self) -> list[tuple[str, str, tuple[str, ...]]]:
        return [(name, j.kind, tuple(j.links)) for name, j in self.joints.items()]


def parse_structure(data, source: str = "mechanism") -> StructureSpec:
    """Validate a mapping read from TOML.

    Raises
    ------
    SpecError
        One sentence: the first problem, naming its key, and the count of the others.
    """
    if not isinstance(data, dict) or not data:
        raise SpecError(f"{source}: empty mechanism; expected frame, links and a [joints] table")
    if not {"frame", "links", "joints"} & set(data):
        raise SpecError(
            f"{source}: not a mechanism file: expected frame, links and a [joints] table "
            "(see configs/mechanisms/six-link.toml)"
        )
    return validate(StructureSpec, data, source)


def load_structure(path: str | Path) -> StructureSpec:
    """Read and validate a mechanism TOML file; the name defaults to the file stem."""
    return parse_structure(spec_name(read_toml(path, expected="a mechanism TOML"), path), source=str(path))


def analyse(spec: StructureSpec, source: str = "mechanism") -> _structure.StructureAnalysis:
    """:func:`pumplink.mechanisms.structure.analyse_structure` on a validated spec.

    Raises
    ------
    SpecError
        The kernel's one-sentence reason (unknown link, joint naming a link twice, ...).
    """
    try:
        return _structure.analyse_structure(
            spec.links,
            spec.frame,
            spec.joint_tuples(),
            spec.drivers,
            tuple(spec.passive_links),
            spec.local_mobilities,
        )
    except ValueError as exc:
        raise SpecError(f"{source}: {str(exc).rstrip('.')}.") from None
