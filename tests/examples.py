"""The commands the docs quote and the examples the help texts and the README give (test support):
tests/cli/test_help_examples.py runs the examples, tests/test_docs_outputs.py the quoted commands,
and tests/cli/test_80_columns.py leaves both out (they are checked at 80 columns there)."""

from __future__ import annotations

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def quoted_commands() -> set[str]:
    """The commands of the marked output blocks of README.md and docs/*.md (scripts/docs_outputs.py)."""
    pattern = re.compile(r"^<!-- output(?: exit=\d+)?: (.+?) -->$", re.M)
    pages = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]
    return {m for page in pages for m in pattern.findall(page.read_text(encoding="utf-8"))}


QUOTED = quoted_commands()


def help_examples() -> list[tuple[str, str]]:
    """(command, example) for every 'Example: [bold]...[/]' in the commands' help texts."""
    from pumplink.cli import app

    out = [
        ("pumplink", " ".join(m.split())) for m in re.findall(r"Example: \[bold\](.*?)\[/\]", app.info.help)
    ]
    for c in app.registered_commands:
        for m in re.findall(r"Example: \[bold\](.*?)\[/\]", c.callback.__doc__ or "", re.S):
            out.append((c.callback.__name__, " ".join(m.split())))
    return out


def readme_examples() -> list[str]:
    """The `pumplink ...` lines of the README's sh blocks (comments stripped)."""
    text = (ROOT / "README.md").read_text(encoding="utf-8")
    lines = []
    for block in re.findall(r"^```sh\n(.*?)^```", text, re.S | re.M):
        for line in block.splitlines():
            line = line.split("  #")[0].strip()
            if line.startswith("pumplink "):
                lines.append(line)
    return lines
