"""JSON Schemas of the input files, generated from the pydantic models that validate them.

Editors that validate TOML against a JSON Schema (Taplo / "Even Better TOML", for one) read a
``#:schema pump.schema.json`` line at the top of a spec and underline a misspelt key or an
out-of-range value as it is typed.  The schemas are built from the same models and limits that
``pumplink`` applies when it reads a file, so an editor and the tool agree; what a schema cannot
say (a swing below 2π "looks like radians", give the inertia or the mass but not both) is still
said by pumplink when the file is read.

Three kinds of file: ``spec`` (a rope-pump spec, :class:`pumplink.inputs.pump.PumpSpec`), ``piston`` (a
piston-pump spec, :class:`pumplink.studies.piston.PistonSpec`) and ``batch`` (a base spec and the keys to
vary, docs/batch.md: "Batch files").
"""

from __future__ import annotations

from typing import Any

#: The JSON Schema dialect of the generated documents.
DIALECT = "https://json-schema.org/draft/2020-12/schema"

#: Names of the schemas, in the order ``pumplink schema --help`` lists them.
KINDS = ("spec", "piston", "batch")


def _toml_only(node: Any) -> Any:
    """TOML has no null: an optional key is simply left out.  Drop the ``null`` branch pydantic
    writes for ``float | None`` fields and their ``default: null``."""
    if isinstance(node, list):
        return [_toml_only(n) for n in node]
    if not isinstance(node, dict):
        return node
    out = {k: _toml_only(v) for k, v in node.items()}
    branches = out.get("anyOf")
    if isinstance(branches, list):
        kept = [b for b in branches if b != {"type": "null"}]
        if len(kept) < len(branches):
            del out["anyOf"]
            if len(kept) == 1:
                out.update(kept[0])
            else:
                out["anyOf"] = kept
    if out.get("default", 0) is None:
        del out["default"]
    return out


#: What a name may hold, as a JSON Schema (ECMA-262) pattern: no control character (C0, DEL, C1)
#: and no noncharacter of the Basic Multilingual Plane (U+FDD0-U+FDEF, U+FFFE, U+FFFF).  The
#: surrogates and the other planes' noncharacters, which a pattern cannot state the same way in
#: every regex dialect, are refused by pumplink when it reads the file (pumplink.errors.bad_character).
NAME_PATTERN = r"^[^\u0000-\u001f\u007f-\u009f\ufdd0-\ufdef\ufffe\uffff]*$"


def name_schema(what: str) -> dict[str, Any]:
    """The ``name`` key of every input file: 1 to MAX_NAME_CHARS printable characters."""
    from pumplink.inputs.toml import MAX_NAME_CHARS

    return {
        "type": "string",
        "minLength": 1,
        "maxLength": MAX_NAME_CHARS,
        "pattern": NAME_PATTERN,
        "description": f"{what}: 1 to {MAX_NAME_CHARS} printable characters (no newline, tab, escape or "
        "other control character, no Unicode noncharacter)",
    }


def _document(model, title: str, description: str) -> dict[str, Any]:
    schema = _toml_only(model.model_json_schema())
    name = schema["properties"]["name"]
    name.update({k: v for k, v in name_schema(name.get("description", "name")).items() if k != "type"})
    return {"$schema": DIALECT, **schema, "title": title, "description": description}


def spec_schema() -> dict[str, Any]:
    """JSON Schema of a rope-pump spec (``[wheel]``, ``[linkage]``, ``[load]``, ``[operator]``)."""
    from pumplink.inputs.pump import PumpSpec

    return _document(
        PumpSpec,
        "pumplink rope-pump spec",
        "A rope pump driven through a four-bar linkage by a standing operator (docs/guide.md: the spec).",
    )


def piston_schema() -> dict[str, Any]:
    """JSON Schema of a piston-pump spec (``mechanism = "crank-slider"``, docs/piston-pump.md)."""
    from pumplink.inputs.piston import PistonSpec

    return _document(
        PistonSpec,
        "pumplink piston-pump spec",
        "A single-acting piston pump driven by a crank-slider (docs/piston-pump.md).",
    )


def _piston_keys() -> tuple[str, ...]:
    """Dotted keys of a piston-pump spec's numbers (what a piston batch file may vary)."""
    from pumplink.inputs.piston import PistonSpec

    props = piston_schema()
    defs = props.get("$defs", {})
    keys = []
    for section, node in props["properties"].items():
        ref = node.get("$ref") or next((b["$ref"] for b in node.get("anyOf", []) if "$ref" in b), None)
        if ref is None or section not in PistonSpec.model_fields:
            continue
        for leaf, sub in defs[ref.rsplit("/", 1)[1]]["properties"].items():
            if sub.get("type") in ("number", "integer"):
                keys.append(f"{section}.{leaf}")
    return tuple(keys)


def batch_schema() -> dict[str, Any]:
    """JSON Schema of a batch file: ``base`` (a spec's path, or the spec inline, rope or piston
    pump) and ``[vary]`` (dotted spec keys, each a list of numbers or a ``{start, stop, num}``
    range)."""
    from pumplink.inputs.batch import MAX_AXIS_VALUES, VARIABLE_KEYS

    inline, defs = [], {}
    for doc in (spec_schema(), piston_schema()):
        for name, node in doc.pop("$defs", {}).items():
            if defs.setdefault(name, node) != node:  # pragma: no cover - a renamed model would clash
                raise ValueError(f"two different schema definitions named {name}")
        for key in ("$schema", "title", "description"):
            doc.pop(key, None)
        inline.append(doc)
    axis = {
        "oneOf": [
            {"type": "array", "items": {"type": "number"}, "minItems": 1, "maxItems": MAX_AXIS_VALUES},
            {
                "type": "object",
                "properties": {
                    "start": {"type": "number"},
                    "stop": {"type": "number"},
                    "num": {"type": "integer", "minimum": 1, "maximum": MAX_AXIS_VALUES},
                },
                "required": ["start", "stop", "num"],
                "additionalProperties": False,
                "description": "num values evenly spaced from start to stop (both included)",
            },
        ]
    }
    return {
        "$schema": DIALECT,
        "title": "pumplink batch file",
        "description": "A base spec and the spec keys to vary; every combination is one variant "
        '(docs/batch.md: "Batch files").',
        "type": "object",
        "properties": {
            "name": name_schema("name of the batch, the prefix of every variant name"),
            "base": {
                "description": "the base spec: a file path (relative to this file) or the spec inline",
                "oneOf": [{"type": "string", "minLength": 1}, *inline],
            },
            "vary": {
                "type": "object",
                "description": "spec keys to vary, as section.key (e.g. linkage.handle)",
                "propertyNames": {"enum": list(dict.fromkeys((*VARIABLE_KEYS, *_piston_keys())))},
                "minProperties": 1,
                "additionalProperties": axis,
            },
        },
        "required": ["base", "vary"],
        "additionalProperties": False,
        "$defs": defs,
    }


def schema(kind: str = "spec") -> dict[str, Any]:
    """The JSON Schema of one kind of input file (``spec``, ``piston`` or ``batch``)."""
    from pumplink.errors import SpecError

    builders = {"spec": spec_schema, "piston": piston_schema, "batch": batch_schema}
    if kind not in builders:
        raise SpecError(f"schema '{kind}' is unknown; allowed: {', '.join(KINDS)}")
    return builders[kind]()
