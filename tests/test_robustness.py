"""No input can make pumplink crash: fuzzed files and the full range of valid specs.

The bar: "no input file can make it print a traceback".  Three properties:
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
import os
from pathlib import Path

import pytest
import tomli_w
from budget import examples
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from pumplink.batch import load_batch
from pumplink.errors import SpecError
from pumplink.inputs.pump import PumpSpec, load_spec, parse_spec
from pumplink.inputs.toml import MAX_INPUT_BYTES, MAX_NESTING
from pumplink.output.force import render_force
from pumplink.output.synth import render_designs
from pumplink.studies.force import design, force_analysis

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


# ~1 ms each (a parse); bytes rarely get past TOML, so the budget is for the parser's error paths
@settings(max_examples=examples(60, 150), deadline=None)
@given(st.binary(max_size=300))
def test_arbitrary_bytes_give_a_spec_or_a_spec_error(tmp_path_factory, data):
    path = tmp_path_factory.mktemp("fuzz") / "spec.toml"
    path.write_bytes(data)
    try:
        assert isinstance(load_spec(path), PumpSpec)
    except SpecError as exc:
        assert "\n" not in str(exc) and str(path) in str(exc)


# ~8 ms each; 100 structures over the spec's keys give each key several wrong values (tests/budget.py)
@settings(max_examples=examples(100, 300), deadline=None)
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
        "name": st.text(st.characters(blacklist_categories=("Cc",)), min_size=1, max_size=20),
        "wheel": st.fixed_dictionaries({"radius": _in(0.001, 5)}, optional={"axle_height": _in(1e-9, 5)}),
        "linkage": st.fixed_dictionaries(
            {
                "L1": _in(0, 10),
                "D1": _in(-10, 10),
                "b": _in(0, 10),
                "rocker": _in(0.001, 10),
                "handle": _in(0.001, 20),
                "swing": _in(2 * math.pi, 180, exclude_max=True),
            }
        ),
        "load": st.one_of(
            st.fixed_dictionaries({"rope_force": _in(0.001, 10_000)}),
            st.fixed_dictionaries(
                {"head": _in(0.001, 200), "pipe_diameter": _in(0.001, 0.5)},
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


# ~30 ms each (a full analysis); 60 valid specs, each at one of 3 sample counts (tests/budget.py)
@settings(max_examples=examples(60, 150), deadline=None, suppress_health_check=[HealthCheck.too_slow])
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


# ~12 ms each; 100 batch structures over the batch keys in the default run (tests/budget.py)
@settings(max_examples=examples(100, 300), deadline=None)
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
    from pumplink.inputs.pump import DEFAULT_SPEC

    data = {**top, "base": DEFAULT_SPEC, "vary": vary} if "vary" in top else top
    try:
        parse_batch(data, "fuzz.toml")
    except SpecError as exc:
        assert "\n" not in str(exc)


# ----------------------------------------------------------------------------- adversarial files
# Each class once gave a traceback, a wrong exit code, gigabytes of memory or an echoed escape
# sequence.  The expected messages are the contract (README "Contract"): one line naming the file.
PROTOTYPE = (Path(__file__).parents[1] / "configs" / "prototype.toml").read_text(encoding="utf-8")


def _error(path) -> str:
    with pytest.raises(SpecError) as exc:
        load_spec(path)
    msg = str(exc.value)
    assert "\n" not in msg and "\x1b" not in msg, msg
    return msg


def test_a_byte_order_mark_is_accepted(tmp_path):
    p = tmp_path / "bom.toml"
    p.write_bytes(b"\xef\xbb\xbf" + PROTOTYPE.encode())
    assert load_spec(p).linkage.swing == 60.0


def test_a_cp1252_file_says_how_to_resave_it(tmp_path):
    p = tmp_path / "cp.toml"
    p.write_bytes(PROTOTYPE.replace("Prototype", "Pump für Dörfer").encode("cp1252"))
    msg = _error(p)
    assert "not UTF-8" in msg and "re-save it as UTF-8" in msg and "byte 0x" in msg, msg


@pytest.mark.parametrize("device", ["/dev/zero", "/dev/urandom", "fifo"])
def test_devices_and_pipes_are_refused_unread(tmp_path, device):
    if device == "fifo":  # opening a FIFO with no writer must not block
        device = tmp_path / "fifo"
        os.mkfifo(device)
    assert "not a regular file" in _error(device)


def test_a_batch_base_pointing_at_a_device_is_refused(tmp_path):
    p = tmp_path / "b.toml"
    p.write_text('base = "/dev/zero"\n[vary]\n"linkage.rocker" = [0.2]\n')
    with pytest.raises(SpecError, match="not a regular file"):
        load_batch(p)


def test_a_file_over_the_size_limit_is_refused_unread(tmp_path):
    p = tmp_path / "big.toml"
    with open(p, "wb") as f:  # sparse: no disk used
        f.truncate(MAX_INPUT_BYTES + 1)
    assert f"{MAX_INPUT_BYTES:,}" in _error(p)


DEEP = {
    "arrays": lambda n: "a = " + "[" * n + "]" * n,
    "inline tables": lambda n: "a = " + "{b = " * n + "1" + "}" * n,
    "array of tables": lambda n: "a = [" + "{b = [" * n + "]}" * n + "]",
    "dotted key": lambda n: ".".join(["a"] * n) + " = 1",
    "digit dotted key": lambda n: ".".join(["1"] * n) + " = 1",
    "quoted dotted key": lambda n: ".".join(['"a"'] * n) + " = 1",
    "header": lambda n: "[" + ".".join(["a"] * n) + "]",
    "array-of-tables header": lambda n: "[[" + " . ".join(["a"] * n) + "]]",
}


@pytest.mark.parametrize("kind", list(DEEP))
@pytest.mark.parametrize("depth", [MAX_NESTING + 1, 5_000, 20_000])
def test_deep_nesting_is_refused_before_parsing(tmp_path, kind, depth):
    # 20,000 parts of one dotted key once took 2.3 GB in the TOML parser; 5,000 brackets
    # overflowed its recursion.  Refused by the scan in a few milliseconds.
    p = tmp_path / "deep.toml"
    p.write_text(DEEP[kind](depth))
    assert str(MAX_NESTING) in _error(p)


@pytest.mark.parametrize("kind", ["arrays", "inline tables", "dotted key", "header"])
def test_nesting_up_to_the_limit_is_parsed(tmp_path, kind):
    p = tmp_path / "ok.toml"
    p.write_text(DEEP[kind](MAX_NESTING))
    assert "unknown key" in _error(p)  # parsed, then refused by the spec's keys


def test_brackets_and_dots_in_strings_and_comments_are_text(tmp_path):
    p = tmp_path / "s.toml"
    text = "[" * 100 + "." * 100
    p.write_text(
        f'name = "{text}"\n# {text}\n'
        + PROTOTYPE.replace('name = "Prototype"', "").replace("[load]", f"[load] # {text}")
        + f'"{text}" = 1\n'
    )
    msg = _error(p)  # parsed (not refused as deep): the quoted key is unknown
    assert "unknown key" in msg and "nested" not in msg and "parts" not in msg, msg


def test_a_long_float_array_is_not_a_deep_key(tmp_path):
    p = tmp_path / "floats.toml"
    p.write_text("x = [" + ", ".join(["0.1"] * 10_000) + "]\n" + PROTOTYPE)
    msg = _error(p)
    assert "unknown key 'x'" in msg and len(msg) < 600, msg


def test_names_with_control_characters_are_refused_and_escaped(tmp_path):
    p = tmp_path / "ctl.toml"
    p.write_text(PROTOTYPE.replace('"Prototype"', '"a\\u001b[31mred\\nx"'))
    msg = _error(p)
    assert "control character" in msg and "\\x1b[31m" in msg


def test_unknown_keys_with_escape_sequences_are_escaped(tmp_path):
    p = tmp_path / "esc.toml"
    p.write_text(PROTOTYPE + '\n"esc\\u001b[2J" = 1\n')
    assert "esc\\x1b[2J" in _error(p)


def test_twenty_thousand_unknown_keys_and_a_megabyte_name_give_a_short_line(tmp_path):
    p = tmp_path / "many.toml"
    p.write_text(PROTOTYPE + "\n" + "\n".join(f"k{i} = 1" for i in range(20_000)))
    msg = _error(p)
    assert "19999 more" in msg and len(msg) < 600, msg
    p.write_text(PROTOTYPE.replace('"Prototype"', '"' + "x" * 1_000_000 + '"'))
    msg = _error(p)
    assert "1,000,000 characters" in msg and len(msg) < 600, msg


@pytest.mark.parametrize("swing,deg", [(1.047, "60"), (0.5236, "30"), (3.0, "171.9"), (0.11, "6.3")])
def test_a_swing_in_radians_is_caught_with_the_fix(tmp_path, swing, deg):
    p = tmp_path / "rad.toml"
    p.write_text(PROTOTYPE.replace("swing = 60.0", f"swing = {swing}"))
    msg = _error(p)
    assert "looks like radians" in msg and f"did you mean {deg}°" in msg, msg


@pytest.mark.parametrize("swing", [6.143, 6.2, 3.1416, 3.2, 0.1])
def test_a_swing_whose_degrees_are_no_valid_swing_gets_the_range_not_a_fix(tmp_path, swing):
    """6.143 rad is 352°, 3.1416 rad 180.0°, 0.1 rad 5.7°: out of 2π <= swing < 180 as well, so
    "did you mean 352°?" would send the user to another error; the range is said instead."""
    p = tmp_path / "rad.toml"
    p.write_text(PROTOTYPE.replace("swing = 60.0", f"swing = {swing}"))
    msg = _error(p)
    assert "did you mean" not in msg and "6.28319 <= value < 180" in msg, msg


def test_a_400_digit_integer_is_one_line(tmp_path):
    p = tmp_path / "int.toml"
    p.write_text(PROTOTYPE.replace("radius = 0.25", "radius = " + "1" * 400))
    assert "400 characters" in _error(p)
    b = tmp_path / "b.toml"
    (tmp_path / "proto.toml").write_text(PROTOTYPE)
    for axis in ("[" + "1" * 400 + "]", "{ start = 0.2, stop = 0.3, num = " + "1" * 400 + " }"):
        b.write_text(f'base = "proto.toml"\n[vary]\n"linkage.rocker" = {axis}\n')
        with pytest.raises(SpecError, match="400 characters"):
            load_batch(b)


def test_a_linspace_end_one_ulp_below_a_limit_is_kept(tmp_path):
    (tmp_path / "proto.toml").write_text(PROTOTYPE)
    below = math.nextafter(180.0, 0.0)
    b = tmp_path / "b.toml"
    b.write_text(
        f'base = "proto.toml"\n[vary]\n"linkage.swing" = {{ start = 170, stop = {below!r}, num = 3 }}\n'
    )
    assert load_batch(b).axes[0].values.tolist() == [170.0, 175.0, below]


def test_a_tiny_load_is_refused_not_a_crash(tmp_path):
    # a denormal rope force once crashed the flywheel scene ("argmax of an empty sequence")
    p = tmp_path / "tiny.toml"
    p.write_text(
        PROTOTYPE.replace("rope_force = 45.0", "rope_force = 5e-324").replace(
            "radius = 0.25", "radius = 0.25\nmass = 4.0"
        )
    )
    assert "load.rope_force" in _error(p)
