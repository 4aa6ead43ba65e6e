"""Small things that each cost a user a minute, through the console script as a user runs it.

``pumplink init - | pumplink force -``; ``synth`` without a spec; the option named in an error;
the "more problems" suffix; a mechanism file given to a pump command; the init template's swing
range; the radians hint only when its fix is valid; ``batch --help`` showing the extras; the
``--fail-on`` default stated one way in the README, ``--help`` and the run's summary.
"""

from __future__ import annotations

import json
import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
PROTOTYPE = ROOT / "configs" / "prototype.toml"
FLYWHEEL = ROOT / "examples" / "well-12m-flywheel.toml"
MECHANISM = ROOT / "configs" / "mechanisms" / "six-link.toml"

_SCRIPT = Path(sys.executable).with_name("pumplink")
CMD = [str(_SCRIPT)] if _SCRIPT.is_file() else [sys.executable, "-m", "pumplink"]


def run(*args, stdin: str | None = None, cwd: Path = ROOT, columns: int | None = None):
    env = {k: v for k, v in os.environ.items() if k not in ("FORCE_COLOR", "NO_COLOR", "COLUMNS")}
    env["PYTHONIOENCODING"] = "utf-8"
    if columns is not None:
        env["COLUMNS"] = str(columns)
    return subprocess.run(
        [*CMD, *map(str, args)],
        input=stdin if stdin is not None else "",
        capture_output=True,
        text=True,
        encoding="utf-8",
        env=env,
        cwd=cwd,
        timeout=120,
    )


def one_error(p, code: int = 2) -> str:
    assert p.returncode == code, (p.returncode, p.stdout, p.stderr)
    lines = p.stderr.strip("\n").split("\n")
    assert len(lines) == 1 and lines[0].startswith("error: "), p.stderr
    return lines[0]


# ----------------------------------------------------------------------------- stdin
def test_init_piped_into_force():
    template = run("init", "-")
    assert template.returncode == 0 and 'name = "pump"' in template.stdout
    p = run("force", "-", "--summary", stdin=template.stdout)
    assert p.returncode == 0, p.stderr
    assert "VERDICT: PASS" in p.stdout


#: Every command that takes a spec (or a mechanism file), with the options it needs to run.
SPEC_COMMANDS = [
    ("synth", "-"),
    ("force", "-", "--summary"),
    ("speed", "-"),
    ("draw", "-", "--out", "{tmp}/d.svg"),
    ("optimize", "-"),
    ("report", "-", "--out", "{tmp}/r.html"),
    ("template", "-", "--out", "{tmp}/t.svg"),
    ("methods", "-"),
    ("batch", "-"),
    ("structure", "-"),
]


@pytest.mark.parametrize("args", SPEC_COMMANDS, ids=lambda a: a[0])
def test_every_spec_argument_reads_standard_input(tmp_path, args):
    """What is piped in is what is read: a broken spec on stdin is reported as standard input's."""
    args = [a.format(tmp=tmp_path) for a in args]
    line = one_error(run(*args, stdin="x = \n"))
    assert line.startswith("error: standard input: not valid TOML"), line


@pytest.mark.parametrize(
    "args, stdin, words",
    [
        (("synth", "-", "-"), PROTOTYPE, "Prototype"),  # read once, used twice
        (("batch", "-", "--format", "csv"), PROTOTYPE, "Prototype"),
        (("force", "-", "--summary"), ROOT / "examples" / "piston-pump.toml", "VERDICT"),  # a piston pump
        (("speed", "-"), FLYWHEEL, "speed"),
        (("structure", "-"), MECHANISM, "mechanism class"),
    ],
    ids=["synth", "batch", "piston", "speed", "structure"],
)
def test_a_spec_on_standard_input_runs(args, stdin, words):
    p = run(*args, stdin=stdin.read_text(encoding="utf-8"))
    assert p.returncode in (0, 1), p.stderr
    assert words in p.stdout, p.stdout


def test_a_spec_without_a_name_on_standard_input_is_named_stdin():
    text = "\n".join(line for line in PROTOTYPE.read_text().splitlines() if not line.startswith("name"))
    p = run("synth", "-", "--format", "json", stdin=text)
    assert p.returncode == 0 and '"name": "stdin"' in p.stdout, p.stderr


def test_draw_from_standard_input_asks_for_out():
    line = one_error(run("draw", "-", stdin=PROTOTYPE.read_text()))
    assert "give --out FILE" in line


# ----------------------------------------------------------------------------- synth's default
def test_synth_without_a_spec_uses_the_built_in_design(tmp_path):
    p = run("synth", "--format", "json", cwd=tmp_path)
    assert p.returncode == 0, p.stderr
    assert '"name": "Prototype"' in p.stdout and "0.0998" in p.stdout  # the crank length [m]
    assert p.stderr == ""


def test_synth_without_a_spec_uses_pump_toml_here(tmp_path):
    text = PROTOTYPE.read_text(encoding="utf-8").replace('"Prototype"', '"Here"')
    (tmp_path / "pump.toml").write_text(text, encoding="utf-8")
    p = run("synth", "--format", "json", cwd=tmp_path)
    assert p.returncode == 0 and '"name": "Here"' in p.stdout, p.stderr
    assert "using ./pump.toml" in p.stderr


# ----------------------------------------------------------------------------- the option named
@pytest.mark.parametrize(
    "args, option",
    [
        (("draw", PROTOTYPE, "--out", "x.bmp"), "--out"),
        (("transmission", "--chart", "x.bmp"), "--chart"),
        (("methods", "--samples-plot", "x.bmp"), "--samples-plot"),
        (("methods", "--plot", "x.bmp"), "--plot"),
        (("force", PROTOTYPE, "--plot", "x.bmp"), "--plot"),
    ],
    ids=["draw", "transmission", "methods-samples", "methods", "force"],
)
def test_a_bad_chart_file_names_its_own_option(tmp_path, args, option):
    line = one_error(run(*args, cwd=tmp_path))
    assert line.startswith(f"error: {option} x.bmp: unknown chart type '.bmp'"), line


# ----------------------------------------------------------------------------- messages
def test_the_other_problems_are_places_not_allowed_keys(tmp_path):
    spec = tmp_path / "two.toml"
    text = PROTOTYPE.read_text(encoding="utf-8")
    spec.write_text(text.replace("swing = 60.0", "swnig = 60.0").replace("rocker = 0.2", "rocker = -1.0"))
    line = one_error(run("force", spec))
    # the first problem with what is allowed there, then where the others are
    assert re.search(r"allowed keys in \[linkage\]: L1, .*hole_diameter; 2 more problems, at ", line), line
    assert line.endswith("; 2 more problems, at linkage.rocker and linkage.swing."), line
    spec.write_text(text.replace("rocker = 0.2", "rocker = -1.0").replace("swing = 60.0", "swing = 500.0"))
    line = one_error(run("force", spec))
    assert line.endswith("0.001 <= value <= 10; 1 more problem, at linkage.swing."), line


def test_a_mechanism_file_given_to_force_points_to_structure():
    line = one_error(run("force", MECHANISM))
    assert "is a mechanism file (frame, links, [joints]), not a pump spec" in line
    assert f"`pumplink structure {MECHANISM}`" in line


def test_the_init_template_states_the_swing_rule():
    """The rule is 2π <= swing < 180 (the README's spec table); the template once said 1-179."""
    text = run("init", "-").stdout
    comment = next(line for line in text.splitlines() if line.startswith("swing ="))
    assert "2π-180" in comment and "180 excluded" in comment and "1-179" not in comment, comment


@pytest.mark.parametrize("swing, hint", [(6.143, None), (3.1416, None), (1.047, "60"), (3.0, "171.9")])
def test_the_radians_hint_only_suggests_a_valid_swing(tmp_path, swing, hint):
    """6.143 rad is 352° (3.1416 rad is 180.0°), itself out of range: no "did you mean"."""
    spec = tmp_path / "s.toml"
    spec.write_text(PROTOTYPE.read_text(encoding="utf-8").replace("swing = 60.0", f"swing = {swing}"))
    line = one_error(run("synth", spec))
    if hint is None:
        assert "did you mean" not in line and "6.28319 <= value < 180" in line, line
    else:
        assert f"did you mean {hint}°?" in line, line


# ----------------------------------------------------------------------------- batch
def _flat(text: str) -> str:
    """Help text without Rich's box and line breaks."""
    return " ".join(re.sub(r"[│╭╮╰╯─]", " ", text).split())


def test_batch_help_shows_the_extras_literally():
    """Rich read '[parquet]' and '[dask]' as markup and printed pip install 'pumplink'."""
    text = _flat(run("batch", "--help", columns=200).stdout)
    assert "pip install 'pumplink[parquet]'" in text and "pip install 'pumplink[dask]'" in text
    assert "'pumplink'" not in text


def test_the_fail_on_default_is_said_one_way(tmp_path):
    """README, --help and the run's summary state the same default: all, that is these checks."""
    p = run("batch", PROTOTYPE, "--format", "csv", "--out", tmp_path / "rows.csv")
    summary = re.search(r"failing --fail-on (\S+?);", p.stderr).group(1)
    assert summary == "mean,peak,infeasible,checks"
    help_text = _flat(run("batch", "--help", columns=200).stdout)
    assert f"all (the default: {summary}," in help_text and "[default: all]" in help_text
    pages = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]  # batch's options: docs/batch.md
    readme = "\n".join(p.read_text(encoding="utf-8") for p in pages)
    assert f"(default `all`: `{summary}`," in " ".join(readme.split())
    assert "--fail-on mean,peak,infeasible]" not in readme  # the old usage line
    for m in re.finditer(r"default[^.;]{0,20}--fail-on ([a-z,]+)", readme):
        assert m.group(1) in ("all", summary), m.group(0)


# ----------------------------------------------------------------------------- words in tables
def test_a_pivot_under_ground_is_below_it_not_minus_above():
    """optimize printed "rocker pivot -0.300 m above the ground"."""
    from pumplink.output.optimize import pivot_height

    assert pivot_height(-0.3) == "0.300 m below the ground (needs a pit)"
    assert pivot_height(0.15) == "0.150 m above the ground"


def test_the_axle_height_row_shows_both_sides_of_its_range():
    """The check warns below 0.40 m as well as above 0.70 m (the pump paper's range); the row
    once showed only '> 0.7 m'."""
    p = run("force", ROOT / "configs" / "village-10m.toml", "--summary", columns=80)
    row = next(line for line in p.stdout.splitlines() if line.strip().startswith("axle height"))
    assert "<0.4, >0.7 m" in row, row
    text = (ROOT / "configs" / "village-10m.toml").read_text(encoding="utf-8")
    assert "axle_height = 0.645" in text
    low = run("force", "-", "--summary", "--format", "json", stdin=text.replace("0.645", "0.3"))
    axle = next(c for c in json.loads(low.stdout)["checks"] if c["key"] == "axle_height")
    assert axle["value"] == 0.3 and axle["result"] == "warn", axle
