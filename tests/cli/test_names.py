"""Every name pumplink accepts is written everywhere as given, and JUnit XML stays well-formed.

A name (a spec's, a batch's) goes into tables, CSV, JSON, file names and ``batch --junit``.  XML
1.0 cannot carry the C0 controls, the surrogates, U+FFFE or U+FFFF even as character references,
so such a name once produced a JUnit file no CI system could read.  The rule tested here: a name
holding a control character (C0, DEL, C1), a surrogate or a Unicode noncharacter is refused when
the file is read (exit 2, one line naming the character); every other name of 1 to 200
characters is accepted and comes back unchanged from the JUnit XML, parsed by xml.etree.

The two alphabets are written out here from the Unicode definitions (general categories Cc and
Cs; the 66 noncharacters U+FDD0..U+FDEF and U+xxFFFE, U+xxFFFF), not taken from pumplink.
"""

from __future__ import annotations

import tomllib
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest
import tomli_w
from hypothesis import given, settings
from hypothesis import strategies as st
from in_process import keep_process_state, run_main

ROOT = Path(__file__).resolve().parents[2]
PROTOTYPE = ROOT / "configs" / "prototype.toml"


def noncharacter(c: str) -> bool:
    """The Unicode Standard's 66 noncharacters (chapter 23.7)."""
    cp = ord(c)
    return 0xFDD0 <= cp <= 0xFDEF or cp & 0xFFFE == 0xFFFE


#: Characters a name may hold: anything but the controls (Cc: C0, DEL, C1) and surrogates (Cs),
#: and but the noncharacters.
ACCEPTED = st.characters(exclude_categories=("Cc", "Cs")).filter(lambda c: not noncharacter(c))
#: Characters no name may hold.
REFUSED = st.one_of(
    st.characters(categories=("Cc",)),
    st.characters(categories=("Cs",)),
    st.sampled_from(["\ufdd0", "\ufdef", "\ufffe", "\uffff", "\U0001fffe", "\U0010ffff"]),
)


@pytest.fixture(autouse=True)
def _keep_process_state(monkeypatch):
    yield from keep_process_state(monkeypatch)


def write_input(folder: Path, name: str, kind: str) -> Path:
    """A batch file named ``name`` (two variants), or a spec named ``name``, written by tomli_w."""
    if kind == "batch":
        data = {"name": name, "base": str(PROTOTYPE), "vary": {"linkage.swing": [50.0, 60.0]}}
    else:
        data = {**tomllib.loads(PROTOTYPE.read_text(encoding="utf-8")), "name": name}
    path = folder / f"{kind}.toml"
    path.write_text(tomli_w.dumps(data), encoding="utf-8")
    return path


def junit_names(path: Path) -> list[str]:
    return [case.get("name") for case in ET.parse(path).getroot().iter("testcase")]


@settings(max_examples=60)  # each example is one in-process batch run (~50 ms); 60 cover the planes
@given(
    name=st.text(ACCEPTED, min_size=1, max_size=200).filter(str.strip),
    kind=st.sampled_from(["batch", "spec"]),
)
def test_every_accepted_name_comes_back_from_well_formed_junit(tmp_path_factory, name, kind):
    folder = tmp_path_factory.mktemp("names")
    path = write_input(folder, name, kind)
    report = folder / "report.xml"
    code, _, err = run_main("batch", path, "--junit", report, "--format", "csv", "--fail-on", "none")
    assert code == 0, err
    names = junit_names(report)  # raises ParseError if the XML is not well-formed
    if kind == "batch":
        assert len(names) == 2 and all(n.startswith(name + "#") for n in names), (name, names)
    else:
        assert names == [name]


@settings(max_examples=40)  # each example is refused while reading the file (~5 ms)
@given(
    before=st.text(ACCEPTED, max_size=20),
    bad=REFUSED,
    after=st.text(ACCEPTED, max_size=20),
    kind=st.sampled_from(["batch", "spec"]),
)
def test_a_name_no_xml_can_carry_is_refused_in_one_line(tmp_path_factory, before, bad, after, kind):
    folder = tmp_path_factory.mktemp("names")
    name = before + bad + after
    if kind == "batch":
        path = folder / "batch.toml"  # tomli_w refuses surrogates: write the escape by hand
        path.write_text(
            f'name = "{_toml_escape(name)}"\nbase = "{PROTOTYPE}"\n[vary]\n"linkage.swing" = [50.0]\n',
            encoding="utf-8",
        )
    else:
        text = PROTOTYPE.read_text(encoding="utf-8").replace('"Prototype"', f'"{_toml_escape(name)}"')
        path = folder / "spec.toml"
        path.write_text(text, encoding="utf-8")
    report = folder / "report.xml"
    code, out, err = run_main("batch", path, "--junit", report)
    if 0xD800 <= ord(bad) <= 0xDFFF:  # TOML itself has no escape for a surrogate: the parser refuses
        assert code == 2 and err.count("\n") == 1 and err.startswith("error: "), err
    else:
        assert code == 2 and out == "" and err.count("\n") == 1, err
        word = "a control character" if ord(bad) < 0xA0 else f"U+{ord(bad):04X}, a Unicode noncharacter"
        assert word in err, err
    assert not report.exists()


def _toml_escape(text: str) -> str:
    """``text`` as the inside of a TOML basic string, every non-ASCII character as \\u or \\U."""
    out = []
    for c in text:
        if c in '"\\':
            out.append("\\" + c)
        elif 32 <= ord(c) < 127:
            out.append(c)
        else:
            out.append(f"\\u{ord(c):04x}" if ord(c) < 0x10000 else f"\\U{ord(c):08x}")
    return "".join(out)


def test_a_name_with_ufffe_is_refused_naming_the_character(tmp_path):
    """The case that once wrote unreadable JUnit: ``name = "a\\ufffeb"``."""
    path = tmp_path / "spec.toml"
    path.write_text(PROTOTYPE.read_text(encoding="utf-8").replace('"Prototype"', '"a\\ufffeb"'))
    code, out, err = run_main("force", path)
    assert code == 2 and out == ""
    assert err == (
        f"error: {path}: name = 'a\\ufffeb' contains U+FFFE, a Unicode noncharacter; "
        "give a name of printable characters.\n"
    )


def test_a_file_name_no_name_may_hold_is_escaped_in_junit(tmp_path):
    """File paths hold anything (here U+FFFE and a byte that is not UTF-8): a spec that names
    itself runs, and the path is written into the XML as escapes."""
    folder = tmp_path / "in"
    folder.mkdir()
    raw = bytes(folder) + b"/p\xef\xbf\xbex\xff.toml"  # U+FFFE in UTF-8, then a lone 0xFF
    Path(raw.decode("utf-8", "surrogateescape")).write_bytes(PROTOTYPE.read_bytes())
    report = tmp_path / "r.xml"
    code, _, err = run_main("batch", folder, "--junit", report)
    assert code == 0, err
    suite = ET.parse(report).getroot().find("testsuite")
    assert suite.get("name") == f"{folder}/p\\ufffex\\udcff.toml"
    assert [c.get("name") for c in suite.iter("testcase")] == ["Prototype"]


def test_a_file_name_that_cannot_be_the_default_name_says_so(tmp_path):
    path = Path(str(tmp_path / "p\ufffeq.toml"))
    text = PROTOTYPE.read_text(encoding="utf-8")
    path.write_text("\n".join(line for line in text.splitlines() if not line.startswith("name")))
    code, _, err = run_main("force", path)
    assert code == 2 and err.count("\n") == 1, err
    assert "the name defaults to the file's name 'p\\ufffeq', which holds U+FFFE" in err
    assert 'add name = "..." to the file, or rename it' in err


@pytest.mark.parametrize("kind", ["batch", "spec"])
def test_a_300_character_name_is_one_line_naming_the_limit(tmp_path, kind):
    path = write_input(tmp_path, "x" * 300, kind)
    code, out, err = run_main("batch", path)
    assert code == 2 and out == "" and err.count("\n") == 1 and err.startswith("error: "), err
    assert "200" in err and "300 characters" in err, err


@pytest.mark.parametrize("kind", ["spec", "piston", "batch"])
def test_pumplink_schema_states_the_name_limit(kind):
    import json

    code, out, err = run_main("schema", kind)
    assert code == 0, err
    name = json.loads(out)["properties"]["name"]
    assert name["maxLength"] == 200 and "1 to 200 printable characters" in name["description"]
