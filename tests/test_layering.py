"""The package's structure: no import cycle, and no private name used outside its module.

The layers themselves (cli > output > search > batch | studies > inputs > evaluate > verdict |
models > mechanisms, only the evaluation runs a force model, the output layer reaches no model)
are import-linter contracts in pyproject.toml, checked by ``lint-imports`` in ``make test``.
"""

from __future__ import annotations

import ast
import importlib.util
from pathlib import Path

import grimp

PACKAGE = Path(__file__).resolve().parents[1] / "pumplink"


def _cycles(graph) -> list[list[str]]:
    """The strongly connected components of more than one module (Tarjan's algorithm)."""
    adjacency = {m: sorted(graph.find_modules_directly_imported_by(m)) for m in sorted(graph.modules)}
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    found: list[list[str]] = []

    def visit(v: str) -> None:
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in adjacency[v]:
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                component.append(w)
                if w == v:
                    break
            if len(component) > 1:
                found.append(sorted(component))

    for m in adjacency:
        if m not in index:
            visit(m)
    return found


def test_no_import_cycle():
    graph = grimp.build_graph("pumplink", exclude_type_checking_imports=True)
    assert _cycles(graph) == []


def test_the_cycle_finder_finds_a_planted_cycle():
    """Negative control: a graph with a -> b -> c -> a has one cycle of three modules."""
    graph = grimp.ImportGraph()
    for m in ("p", "p.a", "p.b", "p.c", "p.d"):
        graph.add_module(m)
    for a, b in (("p.a", "p.b"), ("p.b", "p.c"), ("p.c", "p.a"), ("p.c", "p.d")):
        graph.add_import(importer=a, imported=b)
    assert _cycles(graph) == [["p.a", "p.b", "p.c"]]


def _module_name(path: Path) -> str:
    parts = path.relative_to(PACKAGE.parent).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _is_module(name: str) -> bool:
    try:
        return importlib.util.find_spec(name) is not None
    except (ImportError, ValueError):
        return False


def private_uses(source: str, module: str) -> list[str]:
    """Private names (``_x``, not dunders) of other pumplink modules that ``source`` uses: imported
    by name (``from pumplink.m import _x``) or reached through a module alias (``m._x``)."""
    tree = ast.parse(source)
    aliases: dict[str, str] = {}
    found = []
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom) and (node.module or "").startswith("pumplink"):
            for a in node.names:
                full = f"{node.module}.{a.name}"
                if _is_module(full):
                    aliases[a.asname or a.name] = full
                elif a.name.startswith("_") and not a.name.startswith("__") and node.module != module:
                    found.append(f"from {node.module} import {a.name}")
        elif isinstance(node, ast.Import):
            for a in node.names:
                if a.name.startswith("pumplink") and a.asname:
                    aliases[a.asname] = a.name
    for node in ast.walk(tree):
        if (
            isinstance(node, ast.Attribute)
            and isinstance(node.value, ast.Name)
            and node.value.id in aliases
            and aliases[node.value.id] != module
            and node.attr.startswith("_")
            and not node.attr.startswith("__")
        ):
            found.append(f"{aliases[node.value.id]}.{node.attr}")
    return found


def test_no_private_name_is_used_outside_its_module():
    bad = {}
    for path in sorted(PACKAGE.rglob("*.py")):
        module = _module_name(path)
        uses = private_uses(path.read_text(encoding="utf-8"), module)
        if uses:
            bad[module] = uses
    assert bad == {}


def test_the_private_name_check_catches_both_forms():
    """Negative control: an alias reaching a private helper, and a private name imported."""
    source = (
        "from pumplink.models import flywheel as fw\n"
        "from pumplink.mechanisms.fourbar import _height\n"
        "x = fw._prepare(1)\n"
        "y = fw.energy_band\n"
    )
    assert private_uses(source, "pumplink.somewhere") == [
        "from pumplink.mechanisms.fourbar import _height",
        "pumplink.models.flywheel._prepare",
    ]
