"""The JSON Schemas (``pumplink schema``) against the validators they are generated from.

A schema an editor uses must never refuse a file that pumplink reads, and must refuse the files
pumplink refuses for a key or a range.  The checks go through ``jsonschema`` (an independent
validator) on every shipped file and on specs drawn by hypothesis around each key's limits.
"""

from __future__ import annotations

import math
import tomllib
from pathlib import Path

import jsonschema
import pytest
from hypothesis import given
from hypothesis import strategies as st

from pumplink.errors import SpecError
from pumplink.inputs import schema as sch
from pumplink.inputs.pump import DEFAULT_SPEC, parse_spec

ROOT = Path(__file__).resolve().parents[1]


def validator(kind: str) -> jsonschema.Draft202012Validator:
    doc = sch.schema(kind)
    jsonschema.Draft202012Validator.check_schema(doc)  # the document is itself a valid schema
    return jsonschema.Draft202012Validator(doc)


SPEC, PISTON, BATCH = (validator(k) for k in sch.KINDS)


def _toml(path: Path) -> dict:
    return tomllib.loads(path.read_text(encoding="utf-8"))


def shipped() -> list[tuple[str, Path]]:
    """(kind, file) for every shipped spec and batch file."""
    out = []
    for p in sorted(
        [*ROOT.glob("configs/*.toml"), *ROOT.glob("configs/grids/*.toml"), *ROOT.glob("examples/*.toml")]
    ):
        data = _toml(p)
        kind = "batch" if "vary" in data or "base" in data else "piston" if "mechanism" in data else "spec"
        out.append((kind, p))
    return out


@pytest.mark.parametrize(("kind", "path"), shipped(), ids=lambda x: getattr(x, "name", x))
def test_every_shipped_file_is_valid(kind, path):
    errors = list({"spec": SPEC, "piston": PISTON, "batch": BATCH}[kind].iter_errors(_toml(path)))
    assert errors == [], (path, [e.message for e in errors])


def test_shipped_files_cover_each_kind():
    assert {k for k, _ in shipped()} == set(sch.KINDS)


def test_unknown_key_and_wrong_type_are_refused():
    bad_key = {**DEFAULT_SPEC, "linkage": {**DEFAULT_SPEC["linkage"], "swnig": 60.0}}
    assert not SPEC.is_valid(bad_key)
    wrong_type = {**DEFAULT_SPEC, "load": {"rope_force": "45"}}
    assert not SPEC.is_valid(wrong_type)
    missing = {k: v for k, v in DEFAULT_SPEC.items() if k != "wheel"}
    assert not SPEC.is_valid(missing)
    assert SPEC.is_valid(DEFAULT_SPEC)


#: (section, key, smallest allowed, largest allowed, exclusive low, exclusive high): the README's
#: spec table, written out by hand (not read from the models).
RANGES = [
    ("wheel", "radius", 0.001, 5, False, False),
    ("linkage", "L1", 0, 10, False, False),
    ("linkage", "D1", -10, 10, False, False),
    ("linkage", "b", 0, 10, False, False),
    ("linkage", "rocker", 0.001, 10, False, False),
    ("linkage", "handle", 0.001, 20, False, False),
    ("linkage", "swing", 2 * math.pi, 180, False, True),
    ("load", "rope_force", 0.001, 10_000, False, False),
    ("operator", "force_limit", 1, 10_000, False, False),
    ("operator", "speed", 0, 7200, True, False),
]


def _with(section: str, key: str, value) -> dict:
    return {**DEFAULT_SPEC, section: {**DEFAULT_SPEC.get(section, {}), key: value}}


def _pumplink_reads(data: dict) -> bool:
    try:
        parse_spec(data)
    except SpecError:
        return False
    return True


@pytest.mark.parametrize(("section", "key", "lo", "hi", "open_lo", "open_hi"), RANGES)
def test_limits_agree_with_the_readme(section, key, lo, hi, open_lo, open_hi):
    below = math.nextafter(lo, -math.inf)
    above = math.nextafter(hi, math.inf)
    for value, ok in (
        (below, False),
        (lo, not open_lo),
        (hi, not open_hi),
        (above, False),
    ):
        data = _with(section, key, value)
        assert SPEC.is_valid(data) is ok, (section, key, value)
        if not (key == "swing" and value < 2 * math.pi):  # pumplink says "looks like radians" instead
            assert _pumplink_reads(data) is ok, (section, key, value)


NUMBERS = st.one_of(
    st.floats(allow_nan=False, allow_infinity=False, min_value=-20_000, max_value=20_000),
    st.integers(min_value=-20_000, max_value=20_000),
    st.sampled_from([0.0, 1e-9, 6.2, 6.3, 179.999, 180.0, 7200.0, 10_000.0]),
)
KEYS = [(s, k) for s, k, *_ in RANGES] + [
    ("wheel", "mass"),
    ("wheel", "inertia"),
    ("wheel", "axle_height"),
    ("operator", "dead_band"),
    ("operator", "speed_fluctuation"),
    ("linkage", "mass_per_length"),
    ("linkage", "hole_diameter"),
]


@given(st.sampled_from(KEYS), NUMBERS)
def test_the_schema_never_refuses_what_pumplink_reads(where, value):
    """pumplink reads the file => the editor's schema accepts it; and for one edited key the two
    agree both ways (the checks a schema cannot state involve two keys, or the radians hint)."""
    section, key = where
    data = _with(section, key, value)
    if _pumplink_reads(data):
        assert SPEC.is_valid(data), data
    else:
        radians = key == "swing" and 0 < value < 2 * math.pi
        assert not SPEC.is_valid(data) or radians, data


def test_batch_schema():
    grid = {
        "base": "prototype.toml",
        "vary": {"linkage.handle": [0.8, 1.0], "wheel.radius": {"start": 0.2, "stop": 0.3, "num": 3}},
    }
    assert BATCH.is_valid(grid)
    assert BATCH.is_valid({"base": DEFAULT_SPEC, "vary": {"operator.speed": [300, 360]}})
    assert not BATCH.is_valid({"base": "p.toml", "vary": {"linkage.handel": [1.0]}})  # misspelt key
    assert not BATCH.is_valid({"base": "p.toml", "vary": {}})
    assert not BATCH.is_valid({"base": "p.toml"})
    assert not BATCH.is_valid({"base": "p.toml", "vary": {"linkage.handle": []}})
    assert not BATCH.is_valid({"base": "p.toml", "vary": {"linkage.handle": {"start": 0.8, "stop": 1.0}}})
    assert not BATCH.is_valid({"base": "p.toml", "vary": {"linkage.handle": [1.0]}, "extra": 1})


def test_unknown_kind_is_a_spec_error():
    with pytest.raises(SpecError, match="allowed: spec, piston, batch"):
        sch.schema("grid")


#: The name limit as the README's spec table states it ("1–200 printable characters").
README_NAME_LIMIT = 200


@pytest.mark.parametrize("kind", sch.KINDS)
def test_the_name_limit_is_in_every_schema(kind):
    """A spec's, a piston-pump spec's and a batch's name: at most 200 characters, no control
    character, no noncharacter; the schema refuses what pumplink refuses and accepts the rest."""
    doc = sch.schema(kind)
    rule = doc["properties"]["name"]
    assert rule["maxLength"] == README_NAME_LIMIT and rule["minLength"] == 1
    check = {"spec": SPEC, "piston": PISTON, "batch": BATCH}[kind]
    if kind == "batch":
        base = {"base": "prototype.toml", "vary": {"linkage.handle": [1.0]}}
    elif kind == "piston":
        base = _toml(ROOT / "examples" / "piston-pump.toml")
    else:
        base = dict(DEFAULT_SPEC)
    for name, ok in [
        ("x" * 200, True),
        ("Dorf-Pumpe, Brunnen № 3 — 12 m 😀", True),
        ("x" * 201, False),
        ("a\ufffeb", False),
        ("a\uffffb", False),
        ("a\ufdd0b", False),
        ("a\x1b[31m", False),
        ("a\nb", False),
        ("a\x85b", False),
    ]:
        assert check.is_valid({**base, "name": name}) is ok, (kind, name)


def test_the_readme_states_the_name_limit():
    """The spec table (docs/guide.md) and the batch file's example (docs/batch.md) state the limit."""
    pages = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]
    text = "\n".join(p.read_text(encoding="utf-8") for p in pages)
    row = next(line for line in text.splitlines() if line.startswith("| `name` |"))
    assert f"1–{README_NAME_LIMIT} printable characters" in row, row
    batch_name = next(line for line in text.splitlines() if line.startswith('name = "rocker-study"'))
    nxt = text.splitlines()[text.splitlines().index(batch_name) + 1]
    assert f"1–{README_NAME_LIMIT} printable characters" in batch_name + nxt
