"""`pumplink batch`: the table, the summary, the JSON and the JUnit name a variant the same way,
the summary's best variant passes, and the table fits 80 columns without cutting a header.

Everything runs through the real entry point (``python -m pumplink``) piped, at COLUMNS=80 and
NO_COLOR=1, as a user's terminal or a CI log shows it.  The table is read back as text; the JUnit
XML and the JSON are parsed.  That the best variant passes is checked by an independent route:
the variant's spec is rebuilt here from the base spec file and the JSON row's varied values, and
``pumplink force`` judges it on its own.
"""

from __future__ import annotations

import json
import os
import re
import subprocess
import sys
import tomllib
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest
import tomli_w

ROOT = Path(__file__).resolve().parents[2]
VILLAGE = ROOT / "configs" / "village-10m.toml"
PISTON = ROOT / "examples" / "piston-pump.toml"

#: A grid on the village well whose lowest peak force belongs to a variant that FAILs (its
#: smallest transmission angle: #6, radius 0.225 m and a 75° swing, 10.4 N against the passing
#: #2's 11.2 N), with infeasible variants (the pivot 0.05 m beyond the stand and 0.3 m deep);
#: seven varied keys, the widest table a design-space grid gives.
GRID = """name = "{name}"
base = "{base}"
[vary]
"wheel.radius" = [0.2, 0.225]
"load.head" = [{head}]
"linkage.handle" = [0.8]
"linkage.swing" = [45, 75]
"linkage.rocker" = [0.15]
"linkage.L1" = [0.05, 0.4]
"linkage.D1" = [0.3]
"""
#: The table's word for each verdict of the JSON (an infeasible variant's verdict is FAIL).
WORDS = {"PASS": "PASS", "PASS with warnings": "warn", "FAIL": "FAIL"}


def pumplink(*args, cwd=ROOT) -> subprocess.CompletedProcess:
    env = {**os.environ, "COLUMNS": "80", "NO_COLOR": "1"}
    return subprocess.run(
        [sys.executable, "-m", "pumplink", *map(str, args)],
        cwd=cwd,
        env=env,
        capture_output=True,
        text=True,
        check=False,
    )


@pytest.fixture(scope="module")
def grids(tmp_path_factory) -> dict[str, Path]:
    d = tmp_path_factory.mktemp("grids")
    out = {}
    for name, head in (("mixed", 2), ("deep", 40)):
        out[name] = d / f"{name}.toml"
        out[name].write_text(GRID.format(name=name, base=VILLAGE.as_posix(), head=head))
    out["piston"] = d / "piston.toml"
    out["piston"].write_text(
        f'name = "piston"\nbase = "{PISTON.as_posix()}"\n[vary]\n'
        '"piston.bore" = [0.040, 0.063, 0.075]\n"operator.handle" = [0.20, 0.30]\n'
    )
    return out


def run_all(tmp_path, *inputs, fail_on="all"):
    """The table (with --junit) and the JSON of one run: (table result, JUnit cases by name,
    JSON document)."""
    junit = tmp_path / "r.xml"
    table = pumplink("batch", *inputs, "--fail-on", fail_on, "--junit", junit)
    assert table.returncode in (0, 1), table.stderr
    cases = {c.get("name"): c for c in ET.parse(junit).getroot().iter("testcase")}
    doc = json.loads(pumplink("batch", *inputs, "--fail-on", fail_on, "--format", "json").stdout)
    return table, cases, doc


def body(text: str) -> list[str]:
    """The table's rows: the lines between the rule under the headers and the caption."""
    lines = text.splitlines()
    start = next(i for i, ln in enumerate(lines) if ln.startswith("─"))
    end = next(i for i, ln in enumerate(lines) if ln.startswith("peak: "))
    return lines[start + 1 : end]


def headers(text: str) -> list[str]:
    lines = text.splitlines()
    rule = next(i for i, ln in enumerate(lines) if ln.startswith("─"))
    title = next(i for i, ln in enumerate(lines) if "variants" in ln.lower())
    return lines[title + 1 : rule]


def identifier(name: str) -> str:
    """A variant's identifier as the README defines names, ``<label>#<index>[<key>=<value> ...]``:
    the name up to its varied values (a plain spec's name is its own)."""
    return name.split("[", 1)[0]


def piston_name(row: dict) -> str:
    return row.get("variant", row.get("name"))


def table_rows(lines: list[str]) -> list[tuple[str, list[str]]]:
    """The table's rows as (first line, words of all its lines): a row starts on a line that
    ends with a verdict; a name too long for its column goes on below, at a space."""
    out: list[tuple[str, list[str]]] = []
    for line in lines:
        if line.split()[-1] in WORDS.values():
            out.append((line, line.split()))
        else:
            out[-1][1].extend(line.split())
    return out


def check_rows_against_json_and_junit(lines, rows, cases, shown, one_line=True) -> None:
    """Each table row names one variant (``shown`` maps a JSON row to the text its table row
    starts with), and shows that variant's peak force and verdict; its JUnit testcase has that
    name and fails exactly where the verdict is FAIL (--fail-on all)."""
    parsed = table_rows(lines)
    assert len(parsed) == len(rows)
    if one_line:
        assert len(lines) == len(rows)  # nothing wrapped onto a second line
    for (line, words), row in zip(parsed, rows, strict=True):
        name = piston_name(row)
        start = shown(row)
        assert line.startswith(start) and line[len(start)] in " [", (line, start)  # the whole id
        assert name in cases, name
        assert words[-1] == WORDS[row["verdict"]] if one_line else WORDS[row["verdict"]] in words
        assert line.split()[-1] == WORDS[row["verdict"]], (line, row["verdict"])
        assert (cases[name].find("failure") is not None) == (row["verdict"] == "FAIL"), name
        peak = row.get("peak_force_N")
        if "variant" in row:  # a piston pump's row
            lpf = row["least_peak_force_N"]
            peak = lpf if lpf is not None else row["quasi_static_peak_N"]
        assert (f"{peak:.1f}" if peak is not None else "—") in line.split()[1:], (line, peak)


def rebuilt_spec(tmp_path, base: Path, row: dict) -> Path:
    """The variant's spec, rebuilt from the base spec file and the JSON row's varied values."""
    data = tomllib.loads(base.read_text(encoding="utf-8"))
    for key, value in row["vary"].items():
        section, leaf = key.split(".")
        data.setdefault(section, {})[leaf] = value
    data["name"] = "rebuilt"
    path = tmp_path / "rebuilt.toml"
    path.write_text(tomli_w.dumps(data), encoding="utf-8")
    return path


def force_verdict(spec: Path) -> dict:
    r = pumplink("force", spec, "--summary", "--format", "json")
    assert r.returncode in (0, 1), r.stderr
    return json.loads(r.stdout)


def flat(text: str) -> str:
    """The text with its line breaks (where the terminal wrapped a line) as single spaces."""
    return " ".join(text.split())


def fits(text: str, words) -> None:
    """Every line fits 80 columns, nothing is cut to '…', and each header word is whole."""
    assert max(len(ln) for ln in text.splitlines()) <= 80
    assert "…" not in text
    head = " ".join(headers(text)).split()
    for w in words:
        assert w in head, (w, head)


def test_one_grid_ids_junit_and_a_best_that_passes(tmp_path, grids):
    """A grid alone: '#<index>' rows (zero-padded as in the names) under a title naming the grid;
    the lowest peak overall FAILs, so the best is the passing variant with the lowest peak, and
    `pumplink force` on its rebuilt spec passes too."""
    table, cases, doc = run_all(tmp_path, grids["mixed"])
    rows, summary = doc["variants"], doc["summary"]
    assert table.stdout.startswith("Variants of mixed\n")
    check_rows_against_json_and_junit(
        body(table.stdout), rows, cases, lambda r: "#" + identifier(r["name"]).split("#")[1]
    )
    assert [identifier(r["name"]) for r in rows] == [f"mixed#{i}" for i in range(8)]
    fits(
        table.stdout,
        ["#", "radius", "head", "handle", "swing", "rocker", "L1", "D1", "peak", "mean", "γ", "v", "verdict"],
    )
    # the trap the old summary fell into: the lowest peak of all fails
    feasible = [r for r in rows if r["peak_force_N"] is not None]
    lowest = min(feasible, key=lambda r: r["peak_force_N"])
    assert lowest["verdict"] == "FAIL"
    passing = [r for r in rows if r["pass"]]
    best = summary["best"]
    assert best["pass"] and best["name"] == min(passing, key=lambda r: r["peak_force_N"])["name"]
    assert best["name"] != lowest["name"]
    # named the same in the table's summary line and the JUnit, where it does not fail
    assert f"best: {best['name']} — lowest peak force (full dynamics) of {len(passing)} passing" in flat(
        table.stdout
    )
    assert cases[best["name"]].find("failure") is None
    # independent route: the variant's spec rebuilt by hand and judged by `pumplink force`
    one = force_verdict(rebuilt_spec(tmp_path, VILLAGE, next(r for r in rows if r["name"] == best["name"])))
    assert one["pass"] is True and one["verdict"] == best["verdict"]
    assert one["peak_force_N"] == pytest.approx(best["peak_force_N"], rel=1e-9)
    # and the failing lowest one fails there as well
    assert force_verdict(rebuilt_spec(tmp_path, VILLAGE, lowest))["pass"] is False


def test_several_files_name_rows_by_label_and_index(tmp_path, grids):
    """configs/ (a batch file and three specs) with the grid: every row is named by its
    identifier, '<label>#<index>' or the spec's name, as in the JSON and the JUnit; the notes
    below the table use the same identifiers."""
    table, cases, doc = run_all(tmp_path, ROOT / "configs", grids["mixed"])
    rows = doc["variants"]
    assert set(cases) == {r["name"] for r in rows} and len(rows) == 19
    # nine varied keys do not fit a column each: the name gives them (key=value), wrapped at spaces
    check_rows_against_json_and_junit(
        body(table.stdout), rows, cases, lambda r: identifier(r["name"]), one_line=False
    )
    for (_, words), row in zip(table_rows(body(table.stdout)), rows, strict=True):
        assert set(row["name"].split()) <= set(words), (row["name"], words)
    fits(table.stdout, ["variant", "peak", "mean", "γ", "v", "verdict"])
    notes = [ln for ln in table.stdout.splitlines() if re.match(r"^[^ ].*: (fails|warns|infeasible)", ln)]
    assert notes and notes[0].startswith("prototype-family#0-#7, Prototype: warns: peak grip speed")
    shown = {identifier(r["name"]) for r in rows}
    for ln in notes:
        for part in ln.split(": ", 1)[0].split(", "):
            first = part.split("-#")[0]
            assert first in shown, part
    best = doc["summary"]["best"]
    assert best["pass"] and best["name"] in cases and cases[best["name"]].find("failure") is None


def test_no_variant_passes_says_so(tmp_path, grids):
    """40 m head: every variant fails. The summary says no variant passes and names the closest
    (fewest failing checks, then lowest peak) as such; the JSON's best carries pass: false."""
    table, cases, doc = run_all(tmp_path, grids["deep"])
    rows, best = doc["variants"], doc["summary"]["best"]
    assert table.returncode == 1 and not any(r["pass"] for r in rows)
    text = flat(table.stdout)
    assert "no variant passes; closest (fewest failing checks, then lowest peak): " + best["name"] in text
    assert "best:" not in text and best["pass"] is False and best["verdict"] == "FAIL"
    feasible = [r for r in rows if r["feasible"]]
    fewest = min(len(r["failed"].split(";")) for r in feasible)
    closest = min(
        (r for r in feasible if len(r["failed"].split(";")) == fewest),
        key=lambda r: r["peak_force_N"] or float("inf"),
    )
    assert best["name"] == closest["name"]
    assert force_verdict(rebuilt_spec(tmp_path, VILLAGE, closest))["pass"] is False
    err = pumplink("batch", grids["deep"], "--format", "csv").stderr
    assert f"no variant passes (closest: {best['name']}, fails " in err


def test_piston_grid_ids_and_best(tmp_path, grids):
    """A piston-pump grid through the same table: '#<index>' rows, the JUnit names, and the best
    variant (lowest peak force among those that pass) passes `pumplink force` on its rebuilt spec."""
    table, cases, doc = run_all(tmp_path, grids["piston"])
    rows = doc["variants"]
    assert table.stdout.startswith("Piston-pump variants of piston\n")
    check_rows_against_json_and_junit(
        body(table.stdout), rows, cases, lambda r: "#" + identifier(r["variant"]).split("#")[1]
    )
    fits(table.stdout, ["#", "bore", "handle", "peak", "mean", "verdict"])
    passing = [r for r in rows if r["pass"]]
    assert 0 < len(passing) < len(rows)

    def peak(r):
        return r["least_peak_force_N"] if r["least_peak_force_N"] is not None else r["quasi_static_peak_N"]

    best = min(passing, key=peak)
    assert f"best: {best['variant']} — lowest peak force of {len(passing)} passing" in flat(table.stdout)
    one = force_verdict(
        rebuilt_spec(
            tmp_path, PISTON, {"vary": {"piston.bore": best["bore_m"], "operator.handle": best["handle_m"]}}
        )
    )
    assert one["pass"] is True and one["quasi_static_peak_N"] == pytest.approx(peak(best), rel=1e-9)
