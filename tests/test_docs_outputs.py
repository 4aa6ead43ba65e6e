"""Every command output quoted in README.md and docs/*.md is what the tool prints today.

Each marked block (``<!-- output: pumplink ... -->`` before a fenced block; scripts/docs_outputs.py)
is run again through the installed console script at COLUMNS=80 with NO_COLOR, in a copy of
configs/ and examples/, and compared with the committed text.  The only thing masked is what
varies from one run to the next of the same command on the same files: the elapsed time in batch's
summary line ("batch: 2 variants in 0.13 s"); times that are results ("the wheel stops in 0.46 s")
are compared.  A difference fails with the diff; `python scripts/docs_outputs.py
--write` regenerates every block.
"""

from __future__ import annotations

import importlib.util
import re
import sys
from pathlib import Path

import pytest
from rich.cells import cell_len

ROOT = Path(__file__).resolve().parents[1]
_spec = importlib.util.spec_from_file_location("docs_outputs", ROOT / "scripts" / "docs_outputs.py")
docs_outputs = importlib.util.module_from_spec(_spec)
sys.modules["docs_outputs"] = docs_outputs  # its dataclass looks its module up there
_spec.loader.exec_module(docs_outputs)

BLOCKS = docs_outputs.all_blocks()


def test_the_pages_have_blocks():
    """The README quotes the first design session and the docs quote theirs (a marker that the
    pattern stopped matching would otherwise pass silently)."""
    readme = [b for b in BLOCKS if b.page.name == "README.md"]
    assert len(readme) >= 2  # the first design session and the sizing example
    commands = " ".join(b.command for b in BLOCKS)
    for needed in ("pumplink force configs/village-10m.toml", "pumplink size", "pumplink tolerance"):
        assert needed in commands, needed
    # every fenced block right after an output marker was recognised as one
    for page in docs_outputs.pages():
        text = page.read_text(encoding="utf-8")
        assert text.count("<!-- output") == len(docs_outputs.blocks(page)), page


def test_elapsed_times_are_the_only_thing_masked():
    assert (
        docs_outputs.masked("batch: 2 variants in 0.13 s: 2 pass") == "batch: 2 variants in <elapsed>: 2 pass"
    )
    assert (
        docs_outputs.masked("1,000 variants (slice 1/4) in 12.5 s")
        == "1,000 variants (slice 1/4) in <elapsed>"
    )
    stop = "the wheel stops in 0.46 s and the grip reaches 5.3 m/s after 3.5 s"
    assert docs_outputs.masked(stop) == stop  # a result, not the run's duration


@pytest.mark.parametrize("block", BLOCKS, ids=lambda b: re.sub(r"\s+", "_", b.name)[:90])
def test_block_is_what_the_tool_prints(block):
    """The committed block is the tool's output, and that output fits the reader's 80-column
    terminal with no value cut (``x…``), as tests/cli/test_80_columns.py asks of every command
    (it leaves the documented examples to this test and the examples' test)."""
    fresh = docs_outputs.run(block.command, block.exit_code)
    diff = docs_outputs.difference(block, fresh)
    assert diff == "", f"{block.name} differs from the tool (python scripts/docs_outputs.py --write):\n{diff}"
    for line in fresh.splitlines()[1:]:  # after the `$ command` line
        assert cell_len(line) <= 80 and not re.search(r"\S…", line), (block.name, line)
