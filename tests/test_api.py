"""The Python API (pumplink.load/analyse/synthesize) and the docs' examples of it, the commented
init template, and one verdict across force, batch and optimize on every shipped config."""

from __future__ import annotations

import json
import re
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest

import pumplink
from pumplink.inputs.pump import DEFAULT_SPEC, parse_spec, spec_template

ROOT = Path(__file__).resolve().parents[1]
#: Every shipped rope-pump spec (batch files and other mechanisms' specs are checked elsewhere).
SHIPPED = sorted(
    (
        p
        for p in [*ROOT.glob("configs/*.toml"), *ROOT.glob("examples/*.toml")]
        if not {"vary", "base", "mechanism"} & tomllib.loads(p.read_text(encoding="utf-8")).keys()
    ),
    key=lambda p: p.name,
)


def _python_blocks(path: Path) -> list[str]:
    return re.findall(r"^```python\n(.*?)^```", path.read_text(encoding="utf-8"), re.S | re.M)


@pytest.mark.parametrize("doc", ["docs/api.md", "README.md"])
def test_python_examples_in_the_docs_run(doc, monkeypatch):
    monkeypatch.chdir(ROOT)
    blocks = _python_blocks(ROOT / doc)
    assert blocks
    for code in blocks:
        exec(compile(code, doc, "exec"), {})


def test_help_shows_the_api():
    out = subprocess.run(
        [sys.executable, "-c", "import pumplink; help(pumplink)"],
        capture_output=True,
        text=True,
        check=True,
        env={"PAGER": "cat", "TERM": "dumb", "PATH": ""},
    ).stdout
    for name in ("load(", "analyse(", "synthesize(", "default(", "to_dict(", "to_html(", "examples("):
        assert name in out, name


def test_results_have_a_short_repr_a_dict_and_html():
    r = pumplink.analyse(pumplink.default())
    text = repr(r)
    assert len(text) < 300 and "Prototype" in text and r.outcome in text
    d = pumplink.to_dict(r)
    json.dumps(d, allow_nan=False)  # JSON-safe
    assert d["verdict"] == r.outcome and d["peak_force_N"] == pytest.approx(r.verdict_peak_force)
    assert not hasattr(r, "to_dict") and not hasattr(r, "_repr_html_")  # results do not render themselves
    html = pumplink.to_html(r)
    assert html.count("<tr>") == len(r.checks) + 1 and "grip speed" in html
    assert len(repr(pumplink.synthesize(pumplink.default()))) < 200
    assert set(pumplink.examples()) >= {"prototype", "village-10m", "women-operators-6m", "well-12m-flywheel"}
    assert pumplink.examples() == pumplink.examples()  # a second call too (the data folder is no module)


def test_the_init_template_is_the_default_design_with_the_file_name():
    data = tomllib.loads(spec_template("my-pump"))
    assert data == {**DEFAULT_SPEC, "name": "my-pump"}
    # every optional key commented out in the template is a valid key with a valid example value
    text = spec_template('a "quoted" name')
    assert tomllib.loads(text)["name"] == 'a "quoted" name'
    uncommented = re.sub(r"^# (\w+ = |\[)", r"\1", text, flags=re.M)  # keys, [parts] and [use]
    uncommented = uncommented.replace("rope_force = 45.0", "")  # head/pipe instead of rope_force
    uncommented = uncommented.replace("inertia = 0.25", "")  # mass instead of inertia
    spec = parse_spec(tomllib.loads(uncommented))
    assert spec.wheel.mass == 4.0 and spec.load.head == 10.0 and spec.inertia is not None


def _cli(*args, cwd=ROOT):
    return subprocess.run(
        [sys.executable, "-m", "pumplink", *map(str, args)],
        cwd=cwd,
        capture_output=True,
        text=True,
        check=False,
    )


@pytest.mark.parametrize("path", SHIPPED, ids=lambda p: p.name)
def test_force_batch_and_optimize_agree_on_every_shipped_config(path):
    assert len(SHIPPED) >= 4
    f = _cli("force", path, "--summary", "--format", "json")
    force = json.loads(f.stdout)
    b = _cli("batch", path, "--format", "json")
    (row,) = json.loads(b.stdout)["variants"]
    assert row["verdict"] == force["verdict"] and row["pass"] == force["pass"]
    assert row["peak_force_N"] == force["peak_force_N"]
    results = {c["key"]: c["result"] for c in force["checks"]}
    assert {k.removeprefix("check_"): v for k, v in row.items() if k.startswith("check_") and v} == results
    from pumplink.search.optimize import optimize
    from pumplink.search.problem import make_problem

    problem = make_problem(pumplink.load(path), grip_height=(0.0, 5.0), stroke=(0.0, 5.0))
    res = optimize(problem, maxiter=3, polish=False)
    assert res.spec_result.outcome == force["verdict"]
    assert f.returncode == b.returncode == (0 if force["pass"] else 1)
