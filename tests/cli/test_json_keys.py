"""The README's "JSON keys other tools can rely on" against the JSON the commands emit.

The list once named keys that no longer existed (``peak_crank_deg``, check fields ``severity``,
``limit``, ``pass``; ``required_peak_force_N`` for optimize) and left out most of those that did.
Here the list is read back from the README (each command's bullet: a backticked key, followed
by ``{...}`` for the keys it holds) and compared, path by path and both ways, with the union of
the keys emitted by real runs that between them reach every optional part: ``--explain``,
``--verify`` for each model, the samples, a FAIL with advice, an inertia spec.
"""

from __future__ import annotations

import contextlib
import csv
import io
import json
import re
import signal
import tomllib
from pathlib import Path

import pytest
import tomli_w

import pumplink.cli as cli

ROOT = Path(__file__).resolve().parents[2]
MARKER = "JSON keys other tools can rely on"


@pytest.fixture(autouse=True)
def _keep_process_state(monkeypatch):
    """main() installs signal handlers and may point fd 1 at /dev/null: keep both from pytest."""
    saved = {s: signal.getsignal(s) for s in (signal.SIGINT, signal.SIGTERM)}
    monkeypatch.setattr(cli, "_quiet_stdout", lambda: None)
    yield
    for s, h in saved.items():
        signal.signal(s, h)


def run(*args) -> str:
    """stdout of ``pumplink ARGS`` through the real entry point (exit 0 or 1)."""
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        try:
            cli.main([str(a) for a in args])
        except SystemExit as exc:
            assert exc.code in (0, 1), err.getvalue()
    return out.getvalue()


def emitted(*args) -> dict:
    """``pumplink ARGS --format json``, parsed."""
    return json.loads(run(*args, "--format", "json"))


def paths(node, prefix: str = "", skip: tuple[str, ...] = ()) -> set[str]:
    """Every key path of a JSON document (``a.b``; a list's objects add their keys to the list's
    path); below the paths in ``skip`` nothing is collected."""
    out: set[str] = set()
    if isinstance(node, dict):
        for k, v in node.items():
            p = f"{prefix}.{k}" if prefix else k
            out.add(p)
            if p not in skip:
                out |= paths(v, p, skip)
    elif isinstance(node, list):
        for item in node:
            out |= paths(item, prefix, skip)
    return out


def bullets() -> dict[str, str]:
    """The text of each command's bullet after the marker line (in README.md, or in the docs/
    page the list moves to), by command."""
    for page in [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]:
        text = page.read_text(encoding="utf-8")
        if MARKER in text:
            break
    else:
        raise AssertionError(f"no page has {MARKER!r}")
    section = text.split(MARKER, 1)[1]
    section = section[section.index("\n- **") :]
    section = section[: re.search(r"\n(?!\s|- )", section[1:]).start() + 1]  # the list ends
    out = {}
    for bullet in re.split(r"\n- \*\*", section)[1:]:
        command, body = bullet.split("**", 1)
        out[command] = body
    return out


def documented() -> dict[str, set[str]]:
    """The README's key paths per command: ``{"force": {"checks", "checks.key", ...}, ...}``.

    A backticked identifier is a key; ``{`` opens the keys of the last key, ``}`` closes them.
    Other backticked text (options, values, JSON samples) is skipped."""
    out: dict[str, set[str]] = {}
    for command, body in bullets().items():
        keys: set[str] = set()
        stack: list[str] = []
        last = None
        for token in re.finditer(r"`([^`]*)`|[{}]", body):
            if token.group(1) is not None:
                if re.fullmatch(r"[A-Za-z_][A-Za-z0-9_]*", token.group(1)):
                    last = ".".join([*stack, token.group(1)])
                    keys.add(last)
            elif token.group() == "{":
                assert last is not None, body
                stack = last.split(".")
            else:
                stack = stack[:-1]
                last = ".".join(stack) or None
        assert not stack, f"unbalanced braces in the {command} bullet"
        out[command.split()[0]] = keys
    return out


DOC = documented()


def assert_same(command: str, documented_keys: set[str], emitted_keys: set[str]) -> None:
    missing = sorted(emitted_keys - documented_keys)
    stale = sorted(documented_keys - emitted_keys)
    assert not missing and not stale, (
        f"{command}: emitted but not in the README: {missing}; in the README but not emitted: {stale}"
    )


def test_the_list_covers_the_commands():
    assert set(DOC) == {"synth", "force", "optimize", "batch", "bom"}


def design_keys() -> set[str]:
    return {p.removeprefix("designs.") for p in DOC["synth"] if p.startswith("designs.")}


def test_synth_keys():
    doc = emitted("synth", "configs/prototype.toml", "configs/village-10m.toml")
    assert_same("synth", DOC["synth"], paths(doc))


#: Runs of ``pumplink force`` that between them reach every optional part of its JSON.
FORCE_RUNS = [
    # quasi-static: the samples, --explain, the quasi-static --verify
    ("force", "configs/prototype.toml", "--explain", "--verify"),
    # full dynamics decides: the best cadence and the speeds that pass
    ("force", "configs/village-10m.toml", "--explain", "--summary"),
    # the flywheel, a FAIL: advice, the energy models' --verify
    ("force", "examples/well-12m-flywheel.toml", "--model", "flywheel", "--verify", "--summary"),
]


@pytest.fixture(scope="module")
def force_docs() -> list[dict]:
    return [emitted(*r) for r in FORCE_RUNS]


def test_force_keys(force_docs):
    docs = force_docs
    assert any(d["advice"] for d in docs) and any(d["samples"] for d in docs if "samples" in d)
    assert len({d["verify"]["method"] for d in docs if "verify" in d}) == 2
    assert len({d["model"] for d in docs}) == 3
    keys = set().union(*(paths(d) for d in docs))
    assert_same("force", design_keys() | DOC["force"], keys)


def optional_keys(command: str) -> dict[str, tuple[str, str]]:
    """The top-level keys the list gives only with or without an option, read from its
    sub-bullets ("with `--explain`: `explain` ..."): key -> ("with" or "without", option)."""
    found = re.findall(r"\n\s+- (with|without) `(--[a-z-]+)`: `([A-Za-z_]+)`", bullets()[command])
    return {key: (word, option) for word, option, key in found}


def absent(doc: dict, documented_keys: set[str], args: tuple, optional: dict) -> list[str]:
    """The documented key paths a result leaves out.  A key must be in every object that holds
    its parent (each object of a list; nothing below a null); a top-level key the list gives
    only with (without) an option, only when the run has (has not) it."""
    out = []
    for path in sorted(documented_keys):
        *parents, leaf = path.split(".")
        if not parents and leaf in optional:
            word, option = optional[leaf]
            if (option in args) != (word == "with"):
                continue
        nodes = [doc]
        for k in parents:
            values = [n.get(k) for n in nodes]
            nodes = [v for v in values if isinstance(v, dict)]
            nodes += [x for v in values if isinstance(v, list) for x in v if isinstance(x, dict)]
        if any(leaf not in n for n in nodes):
            out.append(path)
    return out


#: A spec that gives a head and a pipe (the released handle has a water column), and ones with no
#: linkage (L1 = 0: the frame line rises above the handle's forward extreme, test_batch.SMALL),
#: or with no finite force that keeps the wheel turning (J = 0 by the flywheel: nothing to
#: integrate, no workshop view).
PROTOTYPE = tomllib.loads((ROOT / "configs" / "prototype.toml").read_text(encoding="utf-8"))
WITH_HEAD = {**PROTOTYPE, "load": {"head": 8.0, "pipe_diameter": 0.023}}
NO_LINKAGE = {**WITH_HEAD, "linkage": {**PROTOTYPE["linkage"], "L1": 0.0}}
NO_LINKAGE_FLYWHEEL = {**NO_LINKAGE, "wheel": {"radius": 0.25, "mass": 4.0}}
NO_MOTION = {**PROTOTYPE, "load": {"rope_force": 45.0, "moving_mass": 0.0}}
OPTIONS = [(), ("--explain",), ("--verify",), ("--explain", "--verify")]
SPECS = {"with-head": WITH_HEAD, "no-linkage": NO_LINKAGE, "no-linkage-flywheel": NO_LINKAGE_FLYWHEEL}
CASES = [(name, options) for name in SPECS for options in OPTIONS]
# (no finite force: ~1 s a run, for the advice's search; one run has both options)
CASES.append(("no-motion", ("--model", "flywheel", "--explain", "--verify")))


@pytest.mark.parametrize(("name", "options"), CASES, ids=[f"{n} {' '.join(o)}".strip() for n, o in CASES])
def test_every_documented_force_key_is_in_every_result(tmp_path, name, options):
    spec = {**SPECS, "no-motion": NO_MOTION}[name]
    path = tmp_path / "spec.toml"
    path.write_text(tomli_w.dumps(spec), encoding="utf-8")
    args = ("force", path, "--summary", *options)
    doc = emitted(*args)
    keys = design_keys() | DOC["force"]
    assert absent(doc, keys, args, optional_keys("force")) == []
    if spec is not WITH_HEAD:  # nothing to release or verify: null, not left out
        assert doc["release"] is None and doc.get("verify", None) is None
    if spec in (NO_LINKAGE, NO_LINKAGE_FLYWHEEL) and "--explain" in options:  # nor to explain
        assert doc["explain"] is None
    if spec is NO_MOTION and "--explain" in options:  # the model's choice, but no workshop view
        assert doc["explain"]["model"] == "flywheel" and doc["explain"]["workshop"] is None


def test_the_shared_force_runs_hold_every_documented_key(force_docs):
    optional = optional_keys("force")
    assert optional == {
        "explain": ("with", "--explain"),
        "verify": ("with", "--verify"),
        "samples": ("without", "--summary"),
    }
    for args, doc in zip(FORCE_RUNS, force_docs):
        assert absent(doc, design_keys() | DOC["force"], args, optional) == [], args


def test_a_released_handle_that_stops_early_says_so(tmp_path):
    """A 1 mm wheel under 168 m of 1 mm pipe: its column empties only after 168,000 rad of crank
    run back, past the simulation's turn limit (10,000 rad; with massless links the steps are
    long, so the turns, not the steps, run out).  The JSON and the line say it stopped early."""
    spec = {
        **PROTOTYPE,
        "wheel": {"radius": 0.001, "mass": 10.0},
        "linkage": {**PROTOTYPE["linkage"], "coupler_mass": 0.0, "handle_mass": 0.0},
        "load": {"head": 168.0, "pipe_diameter": 0.001},
    }
    path = tmp_path / "spec.toml"
    path.write_text(tomli_w.dumps(spec), encoding="utf-8")
    release = emitted("force", path, "--summary")["release"]
    assert (release["stopped_early"], release["end"]) == (True, "turn limit")
    text = run("force", path, "--summary")
    line = " ".join(text[text.index("released handle:") :].split())  # the wrapped lines joined
    assert "STOPPED EARLY" in line and "10,000 rad of crank" in line


def test_the_old_wrong_keys_are_gone_from_the_readme():
    """The keys the README once promised: none is emitted, none is listed."""
    everything = set().union(*DOC.values())
    leaves = {p.rsplit(".", 1)[-1] for p in everything}
    assert "peak_crank_deg" not in leaves and "required_peak_force_N" not in leaves
    checks = {p.removeprefix("checks.") for p in DOC["force"] if p.startswith("checks.")}
    assert checks == {"key", "name", "value", "unit", "relation", "warn_limit", "fail_limit", "result"}


def test_bom_keys():
    doc = emitted("bom", "configs/village-10m.toml")
    assert_same("bom", DOC["bom"], paths(doc))


def test_optimize_keys():
    doc = emitted("optimize", "configs/prototype.toml")
    assert_same("optimize", DOC["optimize"], paths(doc))


def test_batch_keys(tmp_path):
    grid = tmp_path / "grid.toml"
    grid.write_text(
        f'base = "{ROOT / "examples" / "well-12m-flywheel.toml"}"\n[vary]\n"linkage.swing" = [50, 60]\n'
    )
    docs = [emitted("batch", grid, "--fail-on", "none"), emitted("batch", "configs/", "--fail-on", "none")]
    keys = set().union(*(paths(d, skip=("variants.vary",)) for d in docs))
    assert_same("batch", DOC["batch"], keys)


def test_batch_csv_columns_are_the_json_keys(tmp_path):
    """The README: the CSV has the JSON's columns, one per varied key in place of vary."""
    grid = tmp_path / "grid.toml"
    grid.write_text(f'base = "{ROOT / "configs" / "prototype.toml"}"\n[vary]\n"linkage.swing" = [50, 60]\n')
    text = run("batch", grid, "--fail-on", "none", "--format", "csv")
    row_keys = [p.split(".")[1] for p in DOC["batch"] if p.startswith("variants.") and p.count(".") == 1]
    header = next(csv.reader(io.StringIO(text)))
    assert set(header) == (set(row_keys) - {"vary"}) | {"linkage.swing"}


def test_the_parser_reads_nesting():
    """The README reader itself, on a made-up bullet: braces nest, other backticks are skipped."""
    assert {p for p in DOC["force"] if p.startswith("explain.best_cadence.force_passes")} == {
        "explain.best_cadence.force_passes_deg_s",
        "explain.best_cadence.force_passes_deg_s.min",
        "explain.best_cadence.force_passes_deg_s.max",
    }
    assert "strict" in DOC["force"] and "--strict" not in DOC["force"]
