"""The project's own fuzz campaign, through the real entry point (``pumplink.cli.main``).

Inputs: specs and batch files drawn over the spec's own schema (every key, values inside,
at and beyond its limits, of wrong types, with control characters, huge integers, denormals),
mutated copies of the shipped configs and examples (bytes inserted, deleted, flipped; lines
duplicated; deep nesting and long keys spliced in), and option values typed wrong.  Each run
goes through ``main()`` in this process (fast, so hundreds of examples fit the suite's time
budget), and a few through the console command in a subprocess.

The property is the contract in README.md: exit 0 or 1 with well-formed output (strict JSON,
the exit code agreeing with the verdict), or exit 2 with exactly one printable line on stderr
and nothing on stdout.  Never a traceback, never another exit code.
"""

from __future__ import annotations

import json
import math
import random
import subprocess
import sys
import typing
from pathlib import Path

import pytest
import tomli_w
from budget import examples
from hypothesis import given, settings
from hypothesis import strategies as st
from in_process import keep_process_state, run_main

from pumplink.batch import VARIABLE_KEYS
from pumplink.inputs.pump import PumpSpec

ROOT = Path(__file__).parents[1]
SHIPPED = sorted([*ROOT.glob("configs/*.toml"), *ROOT.glob("examples/*.toml")])


# ----------------------------------------------------------------------------- running
@pytest.fixture(autouse=True)
def _keep_process_state(monkeypatch):
    yield from keep_process_state(monkeypatch)


def check_contract(args, code, out: str, err: str) -> None:
    """The README's contract for one run."""
    assert code in (0, 1, 2), (args, code, err)
    assert "Traceback" not in err, (args, err)
    if code == 2:
        assert out == "", (args, out)
        assert err.endswith("\n") and err.count("\n") == 1 and err.startswith("error: "), (args, err)
        assert not any(ord(c) < 32 or 127 <= ord(c) < 160 for c in err[:-1]), (args, repr(err))
        assert len(err) < 1100, (args, len(err))
        return
    if "json" in args and out:
        doc = json.loads(out, parse_constant=lambda c: pytest.fail(f"{c} in JSON: {args}"))
        if args[0] == "force":
            assert doc["pass"] is (code == 0) or not doc["feasible"], (args, code, doc["pass"])


def run_and_check(args: list[str]) -> int:
    code, out, err = run_main(*args)
    check_contract(args, code, out, err)
    return code


# ----------------------------------------------------------------------------- schema strategy
def _bounds(info) -> tuple[float, float]:
    lo, hi = -1e3, 1e3
    for m in info.metadata:
        for attr in ("gt", "ge"):
            if getattr(m, attr, None) is not None:
                lo = float(getattr(m, attr))
        for attr in ("lt", "le"):
            if getattr(m, attr, None) is not None:
                hi = float(getattr(m, attr))
    return lo, hi


NASTY_TEXT = st.sampled_from(["", " ", "\x1b[2J", "a\nb", "\t", "x" * 300, "é", "\u202e", "[bold]x[/]"])
NASTY = st.one_of(
    st.sampled_from([math.nan, math.inf, -math.inf, 5e-324, -0.0, 1e308, 10**400, -(10**30), True]),
    NASTY_TEXT,
    st.lists(st.floats(allow_nan=False), max_size=2),
    st.dictionaries(st.sampled_from(["x", "radius"]), st.integers(), max_size=2),
)


def field_value(info):
    """Values for one numeric field: inside its range, at its ends and one ulp beyond, or nasty."""
    lo, hi = _bounds(info)
    edges = [lo, hi, math.nextafter(lo, -math.inf), math.nextafter(hi, math.inf), (lo + hi) / 2]
    return st.one_of(
        st.floats(lo, hi, allow_nan=False, allow_infinity=False),
        st.floats(lo, hi, allow_nan=False, allow_infinity=False),  # weight: mostly valid
        st.sampled_from(edges),
        st.integers(int(max(lo, -1e6)), int(min(hi, 1e6))) if hi - lo >= 1 else st.just(lo),
        NASTY,
    )


def section(model):
    fields = {k: field_value(v) for k, v in model.model_fields.items()}
    required = {k: v for k, v in fields.items() if model.model_fields[k].is_required()}
    optional = {k: v for k, v in fields.items() if not model.model_fields[k].is_required()}
    return st.fixed_dictionaries(required, optional=optional)


def _table(annotation):
    """The section model of a field: ``Parts | None`` (an optional table) is the table too."""
    for a in (annotation, *typing.get_args(annotation)):
        if hasattr(a, "model_fields"):
            return a
    return None


SECTIONS = {k: _table(v.annotation) for k, v in PumpSpec.model_fields.items() if _table(v.annotation)}


@st.composite
def specs(draw) -> dict:
    d: dict = {}
    if draw(st.booleans()):
        d["name"] = draw(st.one_of(st.text(max_size=30), NASTY_TEXT))
    for name, model in SECTIONS.items():
        if name == "operator" and draw(st.booleans()):
            continue
        if draw(st.integers(0, 20)) == 0:
            d[name] = draw(NASTY)  # a section that is not a table
            continue
        sec = dict(draw(section(model)))
        if name == "load":  # the two ways to give the load, mostly one of them
            way = draw(st.sampled_from(["rope", "head", "both"]))
            if way == "rope":
                for k in ("head", "pipe_diameter", "efficiency"):
                    sec.pop(k, None)
            elif way == "head":
                sec.pop("rope_force", None)
                sec.setdefault("head", 10.0)
                sec.setdefault("pipe_diameter", 0.023)
        if name == "wheel" and "inertia" in sec and "mass" in sec and draw(st.booleans()):
            del sec["mass"]
        if draw(st.integers(0, 10)) == 0:
            sec[draw(st.sampled_from(["rockr", "Swing", "extra", "esc\x1b[2J", "a\nb"]))] = 1
        d[name] = sec
    return d


def toml_text(data: dict) -> str:
    try:
        return tomli_w.dumps(data)
    except (TypeError, ValueError, OverflowError):  # tomli-w cannot write this value: any text will do
        return repr(data)


FORCE_ARGS = st.sampled_from(
    [
        ["force", "{p}", "--summary", "--format", "json"],
        ["force", "{p}", "--samples", "24", "--format", "json"],
        ["force", "{p}", "--summary"],
        ["synth", "{p}", "--format", "json"],
        ["synth", "{p}"],
    ]
)


# ~30 ms each through main(); 150 specs, each through one of 5 commands, in the default run (tests/budget.py)
@settings(max_examples=examples(150, 500), deadline=None)
@given(specs(), FORCE_ARGS)
def test_schema_specs_keep_the_contract(tmp_path_factory, data, args):
    p = tmp_path_factory.mktemp("fuzz") / "spec.toml"
    p.write_text(toml_text(data), encoding="utf-8")
    run_and_check([a.format(p=p) for a in args])


@st.composite
def batch_files(draw) -> dict:
    base = draw(specs())
    keys = draw(st.lists(st.sampled_from(VARIABLE_KEYS), min_size=1, max_size=3, unique=True))
    vary = {}
    for k in keys:
        section_, name = k.split(".")
        info = SECTIONS[section_].model_fields[name]
        vary[k] = draw(
            st.one_of(
                st.lists(field_value(info), min_size=1, max_size=3),
                st.fixed_dictionaries(
                    {"start": field_value(info), "stop": field_value(info), "num": st.integers(-1, 4)}
                ),
                st.sampled_from([[], {"start": 1}, [10**400], {"start": 0, "stop": 1, "num": 10**400}]),
            )
        )
    doc = {"base": base, "vary": vary}
    if draw(st.booleans()):
        doc["name"] = draw(st.one_of(st.text(max_size=20), NASTY_TEXT))
    return doc


# ~30 ms each; 60 batch files in the default run (tests/budget.py)
@settings(max_examples=examples(60, 150), deadline=None)
@given(batch_files())
def test_schema_batch_files_keep_the_contract(tmp_path_factory, data):
    p = tmp_path_factory.mktemp("fuzz") / "batch.toml"
    p.write_text(toml_text(data), encoding="utf-8")
    run_and_check(["batch", p, "--format", "json", "--samples", "12"])


# ----------------------------------------------------------------------------- mutated files
SPLICES = [
    b"\xef\xbb\xbf",
    b"\xe9",
    b"\x00",
    b"\n[linkage]\n",
    b"\nx = " + b"[" * 5000 + b"]" * 5000 + b"\n",
    b"\n" + b".".join([b"a"] * 5000) + b" = 1\n",
    b'\n"\x1b[2J" = 1\n',
    b"\nname = 'a\\u001b'\n",
    b"1" * 400,
    b"e-320",
    b"\n[[vary]]\n",
    b'"',
    b"{",
]


@st.composite
def mutated(draw) -> bytes:
    data = bytearray(draw(st.sampled_from(SHIPPED)).read_bytes())
    for _ in range(draw(st.integers(1, 4))):
        op = draw(st.sampled_from(["flip", "delete", "insert", "splice", "duplicate"]))
        i = draw(st.integers(0, len(data)))
        if op == "flip" and data:
            data[min(i, len(data) - 1)] = draw(st.integers(0, 255))
        elif op == "delete":
            del data[i : i + draw(st.integers(1, 40))]
        elif op == "insert":
            data[i:i] = draw(st.binary(min_size=1, max_size=8))
        elif op == "splice":
            data[i:i] = draw(st.sampled_from(SPLICES))
        else:
            lines = bytes(data).split(b"\n")
            j = draw(st.integers(0, len(lines) - 1))
            lines.insert(j, lines[j])
            data = bytearray(b"\n".join(lines))
    return bytes(data)


# ~15 ms each; 150 mutations of the 7 shipped files, each through one of 3 commands (tests/budget.py)
@settings(max_examples=examples(150, 450), deadline=None)
@given(mutated(), st.sampled_from(["force", "synth", "batch"]))
def test_mutated_shipped_files_keep_the_contract(tmp_path_factory, data, command):
    p = tmp_path_factory.mktemp("fuzz") / "mutated.toml"
    p.write_bytes(data)
    extra = {"force": ["--summary", "--format", "json"], "synth": [], "batch": ["--samples", "12"]}
    run_and_check([command, p, *extra[command]])


# ----------------------------------------------------------------------------- options
OPTION_VALUES = st.one_of(
    st.sampled_from(["nan", "inf", "-1", "0", "1e400", "60rpm", "1e50", "0x10", "", "\x1b[2J", "9" * 400]),
    st.text(max_size=8),
    st.floats().map(repr),
)


# ~12 ms each; 100 values over the 4 options in the default run (tests/budget.py)
@settings(max_examples=examples(100, 250), deadline=None)
@given(st.sampled_from(["--speed", "--samples", "--at", "--format"]), OPTION_VALUES)
def test_option_values_keep_the_contract(option, value):
    args = ["force", "--summary", option, value]
    if option == "--samples" or option == "--speed":
        args += ["--format", "json"]
    run_and_check(args)


# ----------------------------------------------------------------------------- as processes
def test_a_few_mutated_files_through_the_console_command(tmp_path):
    rng = random.Random(20240517)
    cmd = [sys.executable, "-m", "pumplink"]
    for k in range(6):
        data = bytearray(rng.choice(SHIPPED).read_bytes())
        at = rng.randrange(len(data))
        data[at:at] = rng.choice(SPLICES)
        p = tmp_path / f"m{k}.toml"
        p.write_bytes(bytes(data))
        args = ["force", str(p), "--summary", "--format", "json"]
        r = subprocess.run(
            [*cmd, *args], capture_output=True, text=True, errors="replace", cwd=ROOT, timeout=120
        )
        check_contract(args, r.returncode, r.stdout, r.stderr)
