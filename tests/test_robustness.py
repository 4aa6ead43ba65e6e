"""No input can make pumplink crash: fuzzed files and the full range of valid specs.

Issue #2's bar: "no input file can make it print a traceback".  Three properties:
* arbitrary bytes as a spec file: either a valid spec or SpecError (exit 2), nothing else;
* arbitrary TOML structures over the real key names (and typos, wrong types, nesting): ditto;
* every valid spec, drawn over the whole allowed range of every key: synthesis, force analysis
  and the JSON rendering complete without an exception or a RuntimeWarning (pytest turns those
  into errors, pyproject.toml), and the JSON is strict (no NaN/Infinity tokens).
"""

from __future__ import annotations

import io
import json
import math

import tomli_w
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from pumplink.analysis import design, force_analysis
from pumplink.errors import SpecError
from pumplink.output.tables import render_designs, render_force
from pumplink.spec import PumpSpec, load_spec, parse_spec

KEYS = [
    "name",
    "wheel",
    "linkage",
    "load",
    "operator",
    "radius",
    "axle_height",
    "L1",
    "D1",
    "b",
    "rocker",
    "handle",
    "swing",
    "rope_force",
    "head",
    "pipe_diameter",
    "efficiency",
    "force_limit",
    "speed",
    "dead_band",
    "rockr",
    "Swing",
    "extra",
]
SCALARS = st.one_of(
    st.floats(allow_nan=True, allow_infinity=True),
    st.integers(-(10**6), 10**6),
    st.booleans(),
    st.text(max_size=8),
    st.none(),
)


def toml_values():
    return st.recursive(
        SCALARS.filter(lambda v: v is not None),
        lambda inner: st.one_of(
            st.lists(inner, max_size=3), st.dictionaries(st.sampled_from(KEYS), inner, max_size=6)
        ),
        max_leaves=12,
    )


@settings(max_examples=150, deadline=None)
@given(st.binary(max_size=300))
def test_arbitrary_bytes_give_a_spec_or_a_spec_error(tmp_path_factory, data):
    path = tmp_path_factory.mktemp("fuzz") / "spec.toml"
    path.write_bytes(data)
    try:
        assert isinstance(load_spec(path), PumpSpec)
    except SpecError as exc:
        assert "\n" not in str(exc) and str(path) in str(exc)


@settings(max_examples=300, deadline=None)
@given(st.dictionaries(st.sampled_from(KEYS), toml_values(), max_size=6))
def test_arbitrary_toml_structures_give_a_spec_or_a_spec_error(data):
    try:
        assert isinstance(parse_spec(data, "fuzz"), PumpSpec)
    except SpecError as exc:
        assert "\n" not in str(exc) and str(exc).startswith("fuzz: ")


def _in(lo, hi, **kw):
    return st.floats(lo, hi, allow_nan=False, allow_infinity=False, **kw)


valid_specs = st.fixed_dictionaries(
    {
        "name": st.text(min_size=1, max_size=20),
        "wheel": st.fixed_dictionaries({"radius": _in(0.001, 5)}, optional={"axle_height": _in(1e-9, 5)}),
        "linkage": st.fixed_dictionaries(
            {
                "L1": _in(0, 10),
                "D1": _in(-10, 10),
                "b": _in(0, 10),
                "rocker": _in(0.001, 10),
                "handle": _in(0.001, 20),
                "swing": _in(1, 180, exclude_max=True),
            }
        ),
        "load": st.one_of(
            st.fixed_dictionaries({"rope_force": _in(0, 10_000, exclude_min=True)}),
            st.fixed_dictionaries(
                {"head": _in(0, 200, exclude_min=True), "pipe_diameter": _in(0.001, 0.5)},
                optional={"efficiency": _in(0.05, 1)},
            ),
        ),
        "operator": st.fixed_dictionaries(
            {},
            optional={
                "force_limit": _in(1, 10_000),
                "speed": _in(0, 7200, exclude_min=True),
                "dead_band": _in(0, 90, exclude_max=True),
            },
        ),
    }
)


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(valid_specs, st.sampled_from([1, 7, 64]))
def test_every_valid_spec_is_analysed_without_crash_or_warning(data, samples):
    spec = parse_spec(data, "valid")  # the strategy stays inside the documented ranges
    d = design(spec)
    assert d.feasible == (d.error is None)
    result = force_analysis(spec, samples=samples)
    for fmt in ("json", "csv", "table"):
        out = io.StringIO()
        render_force(result, fmt, out=out)
        if fmt == "json":
            obj = json.loads(out.getvalue(), parse_constant=lambda c: (_ for _ in ()).throw(ValueError(c)))
            assert obj["pass"] in (True, False)
            if obj["feasible"]:
                assert obj["mean_force_N"] is None or math.isfinite(obj["mean_force_N"])
        render_designs([d], fmt, out=io.StringIO())
    # The spec written as TOML reads back to the same spec (what `init` and `optimize --write` rely on).
    import tomllib

    assert parse_spec(tomllib.loads(tomli_w.dumps(spec.model_dump(exclude_none=True))), "again") == spec


BATCH_KEYS = [
    "base",
    "vary",
    "name",
    "start",
    "stop",
    "num",
    "linkage.swing",
    "linkage.rocker",
    "load.rope_force",
    "wheel.radius",
    "operator.dead_band",
    "linkage",
    "nope.key",
    "linkage.rockr",
    "load.head",
]


@settings(max_examples=300, deadline=None)
@given(
    st.dictionaries(st.sampled_from(BATCH_KEYS), toml_values(), max_size=4),
    st.dictionaries(
        st.sampled_from(BATCH_KEYS),
        st.one_of(
            st.lists(SCALARS.filter(lambda v: v is not None), max_size=4),
            st.dictionaries(
                st.sampled_from(["start", "stop", "num", "step"]),
                SCALARS.filter(lambda v: v is not None),
                max_size=4,
            ),
            SCALARS.filter(lambda v: v is not None),
        ),
        max_size=3,
    ),
)
def test_arbitrary_batch_files_give_a_batch_or_a_spec_error(top, vary):
    from pumplink.batch import parse_batch
    from pumplink.spec import DEFAULT_SPEC

    data = {**top, "base": DEFAULT_SPEC, "vary": vary} if "vary" in top else top
    try:
        parse_batch(data, "fuzz.toml")
    except SpecError as exc:
        assert "\n" not in str(exc)
