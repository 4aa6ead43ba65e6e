"""Unit tests of pumplink.inputs.pump: validation messages, the head-based rope force, defaults and the
TOML round trip (spec_to_dict -> tomli_w -> load_spec).

The allowed ranges are read from the model's declared constraints (the contract the messages must
state); expected physical values come from the formula of docs/physics.md §5 written out here.
"""

from __future__ import annotations

import copy
import math
import re
import tomllib
import types
import typing
from pathlib import Path
from typing import Any

import pytest
import tomli_w
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from shipped import PROFILE_NAMES

from pumplink.errors import PumplinkError, SpecError
from pumplink.inputs.piston import PistonSpec, parse_piston
from pumplink.inputs.pump import PumpSpec, default_spec, load_spec, parse_spec, spec_to_dict

ROPE = {
    "name": "t",
    "wheel": {"radius": 0.25},
    "linkage": {"L1": 0.40, "D1": 0.20, "b": 0.10, "rocker": 0.20, "handle": 1.00, "swing": 60.0},
    "load": {"rope_force": 45.0},
}
HEAD = {
    **ROPE,
    "wheel": {"radius": 0.25, "axle_height": 0.55},
    "load": {"head": 10.0, "pipe_diameter": 0.023, "efficiency": 0.75},
    "operator": {"force_limit": 100.0, "speed": 360.0, "dead_band": 20.0},
}

# every numeric key of the contract, with a base spec in which it is present
NUMERIC_KEYS = (
    [(ROPE, "wheel", "radius"), (HEAD, "wheel", "axle_height")]
    + [(ROPE, "linkage", k) for k in ("L1", "D1", "b", "rocker", "handle", "swing")]
    + [(ROPE, "load", "rope_force")]
    + [(HEAD, "load", k) for k in ("head", "pipe_diameter", "efficiency")]
    + [(HEAD, "operator", k) for k in ("force_limit", "speed", "dead_band")]
)


def constraints(section: str, key: str) -> dict[str, float]:
    info = PumpSpec.model_fields[section].annotation.model_fields[key]
    out = {}
    for m in info.metadata:
        for attr in ("gt", "ge", "lt", "le"):
            if getattr(m, attr, None) is not None:
                out[attr] = float(getattr(m, attr))
    return out


def with_value(base: dict, section: str, key: str, value) -> dict:
    d = copy.deepcopy(base)
    d[section][key] = value
    return d


def names_key(msg: str, section: str, key: str) -> bool:
    return f"{section}.{key}" in msg or (
        f"[{section}]" in msg and re.search(rf"\b{re.escape(key)}\b", msg) is not None
    )


def test_every_numeric_key_has_a_finite_range():
    for _, section, key in NUMERIC_KEYS:
        c = constraints(section, key)
        assert ({"gt", "ge"} & c.keys()) and ({"lt", "le"} & c.keys()), (section, key, c)


def test_base_specs_are_valid():
    assert parse_spec(copy.deepcopy(ROPE)).load.rope_force == 45.0
    assert parse_spec(copy.deepcopy(HEAD)).wheel.axle_height == 0.55


@st.composite
def out_of_range(draw):
    base, section, key = draw(st.sampled_from(NUMERIC_KEYS))
    c = constraints(section, key)
    options = [st.sampled_from([math.nan, math.inf, -math.inf])]
    if "gt" in c:
        options.append(st.floats(max_value=c["gt"], allow_nan=False, allow_infinity=False))
    if "ge" in c:  # below the closed bound, drawn directly (no filter)
        options.append(st.floats(max_value=c["ge"], exclude_max=True, allow_nan=False, allow_infinity=False))
    if "lt" in c:
        options.append(st.floats(min_value=c["lt"], allow_nan=False, allow_infinity=False))
    if "le" in c:
        options.append(st.floats(min_value=c["le"], exclude_min=True, allow_nan=False, allow_infinity=False))
    value = draw(st.one_of(options))
    return base, section, key, value, c


# ~1 ms each; 200 draws give every numeric key (about 30) several out-of-range kinds of value
@settings(max_examples=200, deadline=None)
@given(out_of_range())
def test_any_out_of_range_value_names_its_key_value_and_range(case):
    base, section, key, value, c = case
    with pytest.raises(SpecError) as exc:
        parse_spec(with_value(base, section, key, value), source="x.toml")
    msg = str(exc.value)
    assert "\n" not in msg
    assert msg.startswith("x.toml")
    assert names_key(msg, section, key), msg
    if math.isnan(value):
        assert "nan" in msg.lower(), msg
    elif math.isinf(value):
        assert "inf" in msg.lower(), msg
    else:
        assert repr(value) in msg or f"{value:g}" in msg, msg
    for bound in c.values():
        assert f"{bound:g}" in msg, (bound, msg)


# ~2 ms each; 60 draws of 30 keys x 5 wrong types
@settings(max_examples=60, deadline=None)
@given(st.sampled_from(NUMERIC_KEYS), st.sampled_from(["0.2", True, False, [1.0], {"x": 1.0}]))
def test_wrong_type_names_the_key(entry, value):
    base, section, key = entry
    with pytest.raises(SpecError) as exc:
        parse_spec(with_value(base, section, key, value))
    assert names_key(str(exc.value), section, key), str(exc.value)


def test_integers_are_accepted_as_numbers():
    s = parse_spec(with_value(ROPE, "linkage", "swing", 60))
    assert s.linkage.swing == 60.0


def test_unknown_key_is_an_error_and_suggests_the_right_one():
    d = copy.deepcopy(ROPE)
    d["linkage"]["rockr"] = d["linkage"].pop("rocker")
    with pytest.raises(SpecError) as exc:
        parse_spec(d)
    msg = str(exc.value)
    assert "rockr" in msg and "rocker" in msg
    # first thing said is the typo, not the missing key it causes
    assert msg.index("rockr") < msg.index("rocker")


def test_unknown_top_level_key_and_section():
    for extra in ({"colour": "red"}, {"operater": {"speed": 300.0}}):
        with pytest.raises(SpecError) as exc:
            parse_spec({**copy.deepcopy(ROPE), **extra})
        assert next(iter(extra)) in str(exc.value)


def test_missing_key_and_section_messages():
    d = copy.deepcopy(ROPE)
    del d["linkage"]["handle"]
    with pytest.raises(SpecError, match=r"linkage\.handle"):
        parse_spec(d)
    d = copy.deepcopy(ROPE)
    del d["load"]
    with pytest.raises(SpecError) as exc:
        parse_spec(d)
    assert "load" in str(exc.value)
    assert "None" not in str(exc.value), str(exc.value)  # no Python internals in a user message


def test_section_that_is_not_a_table():
    d = {**copy.deepcopy(ROPE), "linkage": 5}
    with pytest.raises(SpecError, match="linkage"):
        parse_spec(d)


def test_name_must_be_text_and_the_message_says_so():
    with pytest.raises(SpecError) as exc:
        parse_spec({**copy.deepcopy(ROPE), "name": 3})
    msg = str(exc.value)
    assert "name" in msg and "3" in msg
    assert "number" not in msg, msg  # the name is text; it must not be described as "a number"
    with pytest.raises(SpecError, match="name"):
        parse_spec({**copy.deepcopy(ROPE), "name": ""})


def test_load_alternatives():
    both = with_value(ROPE, "load", "head", 10.0)
    both["load"]["pipe_diameter"] = 0.023
    with pytest.raises(SpecError) as exc:
        parse_spec(both)
    assert "rope_force" in str(exc.value) and "head" in str(exc.value)
    with pytest.raises(SpecError, match="pipe_diameter"):
        parse_spec({**copy.deepcopy(ROPE), "load": {"head": 10.0}})
    with pytest.raises(SpecError, match="efficiency"):
        parse_spec(with_value(ROPE, "load", "efficiency", 0.7))
    with pytest.raises(SpecError, match="rope_force"):
        parse_spec({**copy.deepcopy(ROPE), "load": {}})


@pytest.mark.parametrize("data", [{}, [], "x", None, 3])
def test_empty_or_non_mapping_spec(data):
    with pytest.raises(SpecError) as exc:
        parse_spec(data, source="s.toml")
    assert str(exc.value).startswith("s.toml")


def test_spec_error_maps_to_exit_2():
    assert issubclass(SpecError, PumplinkError) and SpecError.exit_code == 2


# ----------------------------------------------------------------------------- load physics
@pytest.mark.parametrize(
    "head,d,eff", [(10.0, 0.023, 0.75), (10.0, 0.023, None), (6.0, 0.019, 0.6), (35.0, 0.012, 1.0)]
)
def test_head_based_rope_force(head, d, eff):
    """Fw = rho g head (pi d^2 / 4) / efficiency, rho = 1000 kg/m^3, g = 9.81 m/s^2, efficiency 0.75
    by default (docs/physics.md §5: 10 m, 23 mm, 0.75 -> about 54 N)."""
    load = {"head": head, "pipe_diameter": d} | ({} if eff is None else {"efficiency": eff})
    s = parse_spec({**copy.deepcopy(ROPE), "load": load})
    want = 1000.0 * 9.81 * head * math.pi * d**2 / 4.0 / (0.75 if eff is None else eff)
    assert s.load.rope_force_N == pytest.approx(want, rel=1e-14)
    assert s.wheel_torque == pytest.approx(want * 0.25, rel=1e-14)


def test_notes_example_is_about_54_newtons():
    s = parse_spec({**copy.deepcopy(ROPE), "load": {"head": 10.0, "pipe_diameter": 0.023}})
    assert 53.5 < s.load.rope_force_N < 55.0
    assert s.wheel_torque == pytest.approx(13.6, abs=0.05)  # docs/physics.md §5: Mw ~ 13.6 N m at rw = 0.25 m


def test_wheel_torque_from_rope_force():
    s = parse_spec(with_value(ROPE, "wheel", "radius", 0.3))
    assert s.wheel_torque == pytest.approx(45.0 * 0.3, rel=1e-15)


# ----------------------------------------------------------------------------- defaults
def test_operator_defaults_when_section_is_omitted():
    s = parse_spec(copy.deepcopy(ROPE))
    assert (s.operator.limits.force_limit, s.operator.speed, s.operator.dead_band) == (100.0, 360.0, 20.0)
    assert s.operator.force_limit is None and s.operator.limits.name == "men"  # the default profile's
    assert s.wheel.axle_height is None


def test_partial_operator_section_keeps_other_defaults():
    s = parse_spec({**copy.deepcopy(ROPE), "operator": {"speed": 200.0}})
    assert (s.operator.limits.force_limit, s.operator.speed, s.operator.dead_band) == (100.0, 200.0, 20.0)


def test_a_profile_sets_the_limits_and_each_key_given_overrides_it():
    women = parse_spec({**copy.deepcopy(ROPE), "operator": {"profile": "women"}}).operator.limits
    assert (women.force_limit, women.sustained_power, women.grip_height_range) == (70.0, 60.0, (0.83, 1.23))
    mixed = {"profile": "women", "force_limit": 80.0, "grip_height_max": 1.3}
    lim = parse_spec({**copy.deepcopy(ROPE), "operator": mixed}).operator.limits
    assert (lim.force_limit, lim.sustained_power, lim.grip_height_range) == (80.0, 60.0, (0.83, 1.3))
    with pytest.raises(SpecError, match="grip_speed_warn must be below operator.grip_speed_fail"):
        parse_spec({**copy.deepcopy(ROPE), "operator": {"grip_speed_warn": 5.0}})
    with pytest.raises(SpecError, match="operator.profile"):
        parse_spec({**copy.deepcopy(ROPE), "operator": {"profile": "athletes"}})


def _spec_keys(model) -> set[str]:
    """Every dotted key ``section.leaf`` of a spec model (read from its pydantic fields)."""
    out = set()
    for section, field in model.model_fields.items():
        for a in (field.annotation, *typing.get_args(field.annotation)):
            out |= {f"{section}.{leaf}" for leaf in getattr(a, "model_fields", {})}
    return out


PISTON = {
    "mechanism": "crank-slider",
    "piston": {"bore": 0.05, "head": 10.0, "efficiency": 0.6},
    "crank_slider": {"crank": 0.05, "rod": 0.25},
    "operator": {"handle": 0.3},
}


@pytest.mark.parametrize(
    ("base", "low", "high", "value_low", "value_high"),
    [
        (ROPE, "grip_height_min", "grip_height_max", 1.2, 1.0),
        (ROPE, "grip_speed_warn", "grip_speed_fail", 4.0, 3.0),
        (ROPE, "sustained_power", "hour_power", 200.0, 100.0),
        (PISTON, "sustained_power", "hour_power", 200.0, 100.0),
    ],
)
def test_a_pair_in_the_wrong_order_is_named_by_its_real_keys(base, low, high, value_low, value_high):
    d = copy.deepcopy(base)
    d.setdefault("operator", {}).update({low: value_low, high: value_high})
    piston = "mechanism" in d
    with pytest.raises(SpecError) as err:
        (parse_piston if piston else parse_spec)(d, source="spec")
    message = str(err.value).removeprefix("spec: ")
    named = re.findall(r"[a-z_]+(?:\.[a-z_]+)+", message)
    assert named == [f"operator.{low}", f"operator.{high}"], message
    assert set(named) <= _spec_keys(PistonSpec if piston else PumpSpec)
    assert f"{value_low:g} and {value_high:g}" in message


# ----------------------------------------------------------------------------- the guide's tables
GUIDE = Path(__file__).resolve().parents[1] / "docs" / "guide.md"
#: A bound as the guide writes it: "0.001 ≤ r ≤ 5", "0 < h ≤ 24", "2π ≤ Δθ < 180", "1 ≤ F ≤ 10 000".
_NUMBER = r"[−-]?\d+(?: \d{3})*(?:\.\d+)?π?"
_BOUND = re.compile(rf"({_NUMBER}) (≤|<) \S+ (≤|<) ({_NUMBER})")


def _number(text: str) -> float:
    text = text.replace(" ", "").replace("−", "-")
    return float(text[:-1]) * math.pi if text.endswith("π") else float(text)


def guide_tables() -> list[dict[str, str]]:
    """The guide's spec tables (``| key | meaning | allowed |``), in order: the rope pump's, then
    the piston pump's; each maps a dotted key (``wheel.radius``; ``name``) to its allowed cell,
    one entry per key a row names (``[load] head``, ``pipe_diameter``: ``load.head`` and
    ``load.pipe_diameter``)."""
    tables: list[dict[str, str]] = []
    rows = None
    for line in GUIDE.read_text(encoding="utf-8").splitlines():
        if line.startswith("| key | meaning | allowed |"):
            rows = {}
            tables.append(rows)
        elif rows is not None and line.startswith("| `"):
            cell, _, allowed = (c.strip() for c in line.strip("|").split(" | "))
            section = re.match(r"`\[([a-z_]+)\] ", cell)
            names = re.findall(r"`(?:\[[a-z_]+\] )?([A-Za-z_0-9]+)`", cell)
            for name in names:
                rows[f"{section.group(1)}.{name}" if section else name] = allowed
        elif not line.startswith("|"):
            rows = None
    return tables


def model_bounds(info) -> tuple[float | None, bool, float | None, bool]:
    """(lower, lower included, upper, upper included) of a pydantic field."""
    lo = hi = None
    lo_in = hi_in = True
    for m in info.metadata:
        for attr, inclusive in (("ge", True), ("gt", False)):
            if getattr(m, attr, None) is not None:
                lo, lo_in = float(getattr(m, attr)), inclusive
        for attr, inclusive in (("le", True), ("lt", False)):
            if getattr(m, attr, None) is not None:
                hi, hi_in = float(getattr(m, attr)), inclusive
    return lo, lo_in, hi, hi_in


def spec_fields(model) -> dict[str, Any]:
    """Every key of a spec model with its pydantic field: ``name``, ``mechanism``, ``wheel.radius``..."""
    out = {}
    for section, field in model.model_fields.items():
        kinds = (field.annotation, *typing.get_args(field.annotation))
        tables = [a for a in kinds if hasattr(a, "model_fields")]
        if not tables:
            out[section] = field
        for t in tables:
            out |= {f"{section}.{leaf}": info for leaf, info in t.model_fields.items()}
    return out


def _kind(annotation):
    """The type of a field, without the None of an optional one (``float | None``: float)."""
    if isinstance(annotation, types.UnionType) or typing.get_origin(annotation) is typing.Union:
        (annotation,) = (a for a in typing.get_args(annotation) if a is not type(None))
    return annotation


@pytest.mark.parametrize("model", [PumpSpec, PistonSpec], ids=["rope", "piston"])
def test_the_guide_states_every_bound_of_the_spec(model):
    table = guide_tables()[0 if model is PumpSpec else 1]
    fields = spec_fields(model)
    assert set(table) == set(fields)  # every key, and no key the spec does not have
    cells: dict[str, list[str]] = {}
    for key, allowed in table.items():
        cells.setdefault(allowed, []).append(key)
    for allowed, keys in cells.items():
        bounds = _BOUND.findall(allowed)
        for i, key in enumerate(keys):
            info = fields[key]
            kind = _kind(info.annotation)
            if typing.get_origin(kind) is typing.Literal:  # a word from a list
                assert allowed == ", ".join(typing.get_args(kind)), key
            elif kind is bool:
                assert allowed == "true, false", key
            elif kind is str:  # a name: its length
                lengths = f"{info.metadata[0].min_length}–{info.metadata[1].max_length} "
                assert allowed.startswith(lengths), key
            else:  # one bound per key, or one for all the keys of the row
                assert len(bounds) in (1, len(keys)), (key, allowed)
                lo, op_lo, op_hi, hi = bounds[i if len(bounds) > 1 else 0]
                stated = (_number(lo), op_lo == "≤", _number(hi), op_hi == "≤")
                assert stated == model_bounds(info), (key, allowed)


def test_the_init_template_states_every_bound_it_gives():
    """The commented spec of ``pumplink init``: each key whose comment gives a range ("0.001-5",
    "-10..10", "2π-180", with "X excluded" for an open end) states the model's bounds."""
    from pumplink.inputs.pump import SPEC_TEMPLATE

    fields = spec_fields(PumpSpec)
    section, checked = None, []
    for line in SPEC_TEMPLATE.splitlines():
        header = re.fullmatch(r"(?:# )?\[([a-z_]+)\]", line)  # a table, or one commented out
        if header:
            section = header.group(1)
            continue
        m = re.match(r"#? ?([a-z_A-Z0-9]+) += [^#]*#(.*)", line)
        found = m and re.search(r", (-?\d+(?:\.\d+)?π?)(?:-|\.\.)(\d+(?:\.\d+)?)\b", m.group(2))
        if not found:
            continue
        key = f"{section}.{m.group(1)}"
        lo, hi = _number(found.group(1)), _number(found.group(2))
        excluded = {_number(x) for x in re.findall(r"(\d+(?:\.\d+)?) excluded", m.group(2))}
        assert (lo, lo not in excluded, hi, hi not in excluded) == model_bounds(fields[key]), line
        checked.append(key)
    assert len(checked) >= 15, checked  # every range the template gives was read


def test_load_spec_name_defaults_to_file_stem(tmp_path):
    d = copy.deepcopy(ROPE)
    del d["name"]
    p = tmp_path / "my-well.toml"
    p.write_text(tomli_w.dumps(d), encoding="utf-8")
    assert load_spec(p).name == "my-well"


def test_default_spec_is_valid_and_has_all_sections():
    s = default_spec()
    assert isinstance(s, PumpSpec) and s.wheel_torque > 0
    assert parse_spec(spec_to_dict(s)) == s


# ----------------------------------------------------------------------------- load_spec errors
def test_load_spec_file_errors(tmp_path):
    cases = {
        "missing.toml": None,
        "folder.toml": "dir",
        "binary.toml": b'name = "\xff"\n',
        "syntax.toml": b"[wheel\nradius = 1\n",
        "empty.toml": b"",
    }
    for name, content in cases.items():
        p = tmp_path / name
        if content == "dir":
            p.mkdir()
        elif content is not None:
            p.write_bytes(content)
        with pytest.raises(SpecError) as exc:
            load_spec(p)
        msg = str(exc.value)
        assert name in msg and "\n" not in msg, msg


# ----------------------------------------------------------------------------- round trip
finite = dict(allow_nan=False, allow_infinity=False)


@st.composite
def valid_specs(draw):
    d = {
        "name": draw(st.text(st.characters(blacklist_categories=("Cc",)), min_size=1, max_size=40)),
        "wheel": {"radius": draw(st.floats(0.001, 5, **finite))},
        "linkage": {
            "L1": draw(st.floats(0, 10, **finite)),
            "D1": draw(st.floats(-10, 10, **finite)),
            "b": draw(st.floats(0, 10, **finite)),
            "rocker": draw(st.floats(0.001, 10, **finite)),
            "handle": draw(st.floats(0.001, 20, **finite)),
            "swing": draw(st.floats(2 * math.pi, 180, exclude_max=True, **finite)),
        },
    }
    if draw(st.booleans()):
        d["wheel"]["axle_height"] = draw(st.floats(0.01, 5, **finite))
    if draw(st.booleans()):
        d["load"] = {"rope_force": draw(st.floats(0.01, 10_000, **finite))}
    else:
        d["load"] = {
            "head": draw(st.floats(0.01, 200, **finite)),
            "pipe_diameter": draw(st.floats(0.001, 0.5, **finite)),
        }
        if draw(st.booleans()):
            d["load"]["efficiency"] = draw(st.floats(0.05, 1, **finite))
    op = {}
    if draw(st.booleans()):
        op["force_limit"] = draw(st.floats(1, 10_000, **finite))
    if draw(st.booleans()):
        op["speed"] = draw(st.floats(0.01, 7200, **finite))
    if draw(st.booleans()):
        op["dead_band"] = draw(st.floats(0, 90, exclude_max=True, **finite))
    if op or draw(st.booleans()):
        d["operator"] = op
    return d


# ~4 ms each; 100 specs with each optional section present or not (tmp_path is only overwritten)
@settings(max_examples=100, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(valid_specs())
def test_spec_to_dict_round_trips_through_toml(tmp_path, data):
    spec = parse_spec(copy.deepcopy(data))
    d = spec_to_dict(spec)
    assert "axle_height" in d["wheel"] or spec.wheel.axle_height is None
    assert all(v is not None for sec in d.values() if isinstance(sec, dict) for v in sec.values())
    p = tmp_path / "rt.toml"
    p.write_text(tomli_w.dumps(d), encoding="utf-8")
    again = load_spec(p)
    assert again == spec
    assert again.load.rope_force_N == spec.load.rope_force_N


def test_example_configs_round_trip(tmp_path):
    configs = sorted((Path(__file__).parents[1] / "configs").glob("*.toml"))
    # batch files (a top-level base/vary) live there too; tests/test_batch.py covers them
    configs = [c for c in configs if not {"base", "vary"} & set(tomllib.loads(c.read_text(encoding="utf-8")))]
    assert configs
    for c in configs:
        spec = load_spec(c)
        p = tmp_path / c.name
        p.write_text(tomli_w.dumps(spec_to_dict(spec)), encoding="utf-8")
        assert load_spec(p) == spec


# ----------------------------------------------------------------------------- flywheel keys
def _fly(**wheel):
    d = copy.deepcopy(default_spec().model_dump(exclude_none=True))
    d["wheel"].update(wheel)
    return d


def test_inertia_is_none_without_inertia_keys():
    """No wheel.inertia / wheel.mass / load.moving_mass: the quasi-static model (the default)."""
    assert default_spec().inertia is None
    d = _fly()
    d["load"] = {"head": 10.0, "pipe_diameter": 0.023}  # a water column alone does not switch the model
    assert parse_spec(d).inertia is None


def test_inertia_from_mass_and_water_column():
    """Hand derivation: J = m rw^2 + rho head (pi d^2/4) rw^2 (a rim plus the water moving with it)."""
    d = _fly(mass=4.0)
    d["load"] = {"head": 10.0, "pipe_diameter": 0.023}
    water = 1000.0 * 10.0 * math.pi * 0.023**2 / 4  # 4.1548 kg
    assert parse_spec(d).inertia == pytest.approx(4.0 * 0.25**2 + water * 0.25**2, rel=1e-14)
    d["load"]["moving_mass"] = 1.5  # an explicit moving mass replaces the water-column estimate
    assert parse_spec(d).inertia == pytest.approx((4.0 + 1.5) * 0.0625, rel=1e-14)
    assert parse_spec(_fly(inertia=0.3)).inertia == 0.3
    d = _fly()
    d["load"]["moving_mass"] = 2.0  # moving mass alone is inertia too
    assert parse_spec(d).inertia == pytest.approx(2.0 * 0.0625)


def test_mass_and_inertia_together_is_one_sentence():
    with pytest.raises(SpecError) as e:
        parse_spec(_fly(mass=4.0, inertia=0.3), "p.toml")
    msg = str(e.value)
    assert "wheel.inertia" in msg and "wheel.mass" in msg and "not both" in msg and "\n" not in msg


@pytest.mark.parametrize("key,value", [("speed_fluctuation", 0.0), ("speed_fluctuation", 1.5)])
def test_speed_fluctuation_range(key, value):
    d = _fly()
    d["operator"][key] = value
    with pytest.raises(SpecError) as e:
        parse_spec(d)
    assert f"operator.{key}" in str(e.value) and "allowed" in str(e.value)


# ----------------------------------------------------------------------------- how the parts are joined
@pytest.mark.parametrize(
    ("joints", "notches"),
    [
        ({}, (3.0, 2.0)),  # the defaults: the handle drilled at B, the crank welded to the axle
        ({"handle_joint": "lug"}, (2.0, 2.0)),
        ({"crank_joint": "hole"}, (3.0, 3.0)),
        ({"handle_joint": "lug", "handle_notch": 1.2, "crank_notch": 4.0}, (1.2, 4.0)),  # given: kept
    ],
)
def test_a_notch_factor_not_given_follows_from_the_joint(joints, notches):
    """docs/workshop.md §2: about 3 at a drilled hole (Peterson's transverse hole), about 2 at a
    weld toe; a notch factor the spec gives is its own."""
    spec = parse_spec({**ROPE, "parts": joints})
    assert (spec.parts.handle_notch, spec.parts.crank_notch) == notches
    assert spec.parts.handle_joint == joints.get("handle_joint", "hole")
    assert spec.parts.crank_joint == joints.get("crank_joint", "welded")


def test_a_joint_is_one_of_its_words():
    with pytest.raises(SpecError, match=r"'parts.handle_joint' = 'weld' must be hole or lug"):
        parse_spec({**ROPE, "parts": {"handle_joint": "weld"}})


def test_the_pins_diameter_is_given_once():
    """linkage.hole_diameter is the older name of parts.pin_diameter: alone it is the default parts'
    pin (and the template's holes); beside a [parts] that says otherwise it is one sentence."""
    old = {**ROPE, "linkage": {**ROPE["linkage"], "hole_diameter": 0.0125}}
    assert parse_spec(old).parts is None and parse_spec(old).parts_or_defaults.pin_diameter == 0.0125
    assert parse_spec({**old, "parts": {"pin_diameter": 0.0125}}).parts.pin_diameter == 0.0125
    with pytest.raises(SpecError) as e:
        parse_spec({**old, "parts": {"pin_width": 0.04}})  # and the default 12 mm pin
    msg = str(e.value)
    assert "linkage.hole_diameter = 0.0125" in msg and "parts.pin_diameter = 0.012" in msg
    assert "parts.pin_diameter = 0.0125" in msg.split("give it once")[1]
    assert parse_spec(ROPE).parts_or_defaults.pin_diameter == 0.012


# ----------------------------------------------------------------------------- the spec init writes
@pytest.mark.parametrize("profile", PROFILE_NAMES)
def test_the_init_spec_names_its_profile_and_lists_what_each_sets(profile):
    """``pumplink init`` writes ``profile = "men"`` and no limit of its own, so changing the word
    changes every limit (a force_limit alone would leave the men's power and grip limits: the
    reason the profile is named); the line listing each profile states its limits, read here from
    pumplink.profiles' data."""
    from pumplink.inputs.pump import spec_template
    from pumplink.profiles import PROFILES

    text = spec_template("p")
    assert re.search(r'^profile = "men" ', text, re.M)
    spec = parse_spec(tomllib.loads(text.replace('profile = "men"', f'profile = "{profile}"', 1)))
    assert spec.operator.profile == profile and spec.operator.limits == PROFILES[profile]
    p = PROFILES[profile]
    line = next(ln for ln in text.splitlines() if re.match(rf"\s+#\s+{profile}\s", ln))
    lo, hi = p.grip_height_range
    numbers = [float(x) for x in re.findall(r"\d+(?:\.\d+)?", line)]
    assert numbers == [p.force_limit, p.sustained_power, p.hour_power, lo, hi, p.grip_speed_warn,
                       p.grip_speed_fail], line  # fmt: skip


def test_the_init_spec_shows_parts_and_use_with_their_defaults():
    """Uncommented, the [parts] and [use] tables and the profile's limits of the init spec are the
    defaults each stands for: the men's limits, Parts() and Use() as the models declare them."""
    from pumplink.inputs.pump import Parts, Use, spec_template
    from pumplink.profiles import PROFILES

    text = spec_template("p")
    assert "\n# [parts]\n" in text and "\n# [use]\n" in text
    uncommented = re.sub(r"^# (\w+ = |\[)", r"\1", text, flags=re.M)
    uncommented = uncommented.replace("rope_force = 45.0", "").replace("inertia = 0.25", "")
    spec = parse_spec(tomllib.loads(uncommented))
    assert spec.parts == Parts() and spec.use == Use() and spec.operator.limits == PROFILES["men"]
    assert (spec.parts.handle_joint, spec.parts.crank_joint) == ("hole", "welded")
