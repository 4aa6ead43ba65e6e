"""The documents read once through: no section of README.md or docs/ appears twice.

docs/performance.md once carried a second, older copy of its last five sections, pasted in beside
an updated paragraph; a reader met two tables of the same benchmark with different figures.
"""

from __future__ import annotations

from collections import Counter
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
DOCUMENTS = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]


@pytest.mark.parametrize("path", DOCUMENTS, ids=lambda p: p.name)
def test_no_section_heading_is_repeated(path):
    """A top-level section (``#`` or ``##``, outside code blocks) is named once per document."""
    headings, fenced = [], False
    for line in path.read_text(encoding="utf-8").splitlines():
        if line.startswith("```"):
            fenced = not fenced
        elif not fenced and line.startswith(("# ", "## ")):
            headings.append(line.strip())
    repeated = [h for h, n in Counter(headings).items() if n > 1]
    assert not repeated, f"{path.name}: {repeated}"
