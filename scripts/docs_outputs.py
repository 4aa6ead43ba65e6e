"""Regenerate or check the command outputs quoted in README.md and docs/*.md.

An output block is a fenced block right after a marker line naming the command:

    <!-- output: pumplink force configs/village-10m.toml -->
    ```
    $ pumplink force configs/village-10m.toml
    ...what the command printed...
    ```

A marker may state the exit code the command must end with, ``<!-- output exit=1: ... -->``
(default 0).  Each command runs through the installed ``pumplink`` console script of the
interpreter running this script, with ``COLUMNS=80`` and ``NO_COLOR=1``, in a temporary folder
holding a copy of the repository's configs/ and examples/ (so a command that writes a file never
touches the repository); stdout and stderr are quoted together, as a terminal shows them, after a
``$ command`` line.  Trailing spaces (Rich pads its table titles) are dropped.

    python scripts/docs_outputs.py --write            # rewrite every block from the tool
    python scripts/docs_outputs.py --check            # exit 1 and show a diff where a block differs
    python scripts/docs_outputs.py --check README.md  # only these pages

``--check`` masks only what varies from run to run: the elapsed time of a batch run ("batch: 2
variants in 0.13 s").
"""

from __future__ import annotations

import argparse
import difflib
import os
import re
import shutil
import subprocess
import sys
import tempfile
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
BIN = Path(sys.executable).parent
#: A marker line and the fenced block after it (the block's body is group "body").
BLOCK = re.compile(
    r"^<!-- output(?: exit=(?P<exit>\d+))?: (?P<command>.+?) -->\n"
    r"(?P<fence>```[a-z]*\n)(?P<body>.*?)^```$",
    re.M | re.S,
)
#: A run's elapsed time, the one thing that varies between two runs of the same command on the same
#: files: batch's summary line ("batch: 2 variants in 0.13 s: ...").  Physical times ("the wheel
#: stops in 0.46 s") are results and stay compared.
ELAPSED = re.compile(r"(\bvariants(?: \(slice \d+/\d+\))?) in \d+(?:\.\d+)? s\b")


@dataclass(frozen=True)
class Block:
    """One marked output block of a page."""

    page: Path
    command: str
    exit_code: int
    body: str  # the block's text as committed (without the fences)
    start: int  # offsets of the body in the page
    end: int

    @property
    def name(self) -> str:
        return f"{self.page.relative_to(ROOT)}: {self.command}"


def pages() -> list[Path]:
    """README.md and every docs/*.md."""
    return [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]


def blocks(page: Path) -> list[Block]:
    """The marked output blocks of one page, in order."""
    text = page.read_text(encoding="utf-8")
    return [
        Block(page, m["command"], int(m["exit"] or 0), m["body"], m.start("body"), m.end("body"))
        for m in BLOCK.finditer(text)
    ]


def all_blocks(selected: list[Path] | None = None) -> list[Block]:
    return [b for p in (selected or pages()) for b in blocks(p)]


def run(command: str, exit_code: int = 0) -> str:
    """The block's text for ``command``: ``$ command``, then what it printed (stdout and stderr
    merged), trailing spaces dropped, ending with a newline.  Raises if it exits otherwise than
    ``exit_code`` or prints a traceback."""
    env = {
        **os.environ,
        "PATH": f"{BIN}{os.pathsep}{os.environ.get('PATH', '')}",
        "COLUMNS": "80",
        "NO_COLOR": "1",
    }
    env.pop("FORCE_COLOR", None)
    with tempfile.TemporaryDirectory(prefix="docs-outputs-") as tmp:
        for name in ("configs", "examples"):
            shutil.copytree(ROOT / name, Path(tmp) / name)
        p = subprocess.run(
            ["bash", "-c", command],
            cwd=tmp,
            env=env,
            stdout=subprocess.PIPE,
            stderr=subprocess.STDOUT,
            text=True,
            timeout=600,
        )
    out = p.stdout
    if p.returncode != exit_code or "Traceback" in out:
        raise RuntimeError(f"{command!r} exited {p.returncode} (expected {exit_code}):\n{out[-2000:]}")
    lines = [f"$ {command}", *(line.rstrip() for line in out.rstrip("\n").splitlines())]
    return "\n".join(lines) + "\n"


def masked(text: str) -> str:
    """``text`` with the elapsed times masked (the only run-to-run difference)."""
    return ELAPSED.sub(r"\1 in <elapsed>", text)


def difference(block: Block, fresh: str | None = None) -> str:
    """A unified diff of the committed block against a fresh run (``fresh``, else run now; '' when
    they agree)."""
    fresh = run(block.command, block.exit_code) if fresh is None else fresh
    if masked(fresh) == masked(block.body):
        return ""
    return "".join(
        difflib.unified_diff(
            block.body.splitlines(keepends=True),
            fresh.splitlines(keepends=True),
            f"{block.name} (committed)",
            f"{block.name} (the tool now)",
        )
    )


def write(page: Path) -> int:
    """Rewrite every marked block of ``page`` from a fresh run; the number of blocks changed."""
    text = page.read_text(encoding="utf-8")
    changed = 0
    for block in reversed(blocks(page)):  # from the end, so the earlier offsets stay valid
        fresh = run(block.command, block.exit_code)
        if fresh != block.body:
            text = text[: block.start] + fresh + text[block.end :]
            changed += 1
    page.write_text(text, encoding="utf-8")
    return changed


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    mode = parser.add_mutually_exclusive_group(required=True)
    mode.add_argument("--write", action="store_true", help="rewrite the blocks from the tool")
    mode.add_argument("--check", action="store_true", help="report the blocks that differ (exit 1)")
    parser.add_argument("pages", nargs="*", type=Path, help="pages (default: README.md and docs/*.md)")
    args = parser.parse_args(argv)
    selected = [p.resolve() for p in args.pages] or pages()
    if args.write:
        for page in selected:
            n = write(page)
            print(f"{page.relative_to(ROOT)}: {len(blocks(page))} blocks, {n} rewritten")
        return 0
    bad = 0
    for block in all_blocks(selected):
        diff = difference(block)
        if diff:
            bad += 1
            sys.stdout.write(diff)
    print(f"{bad} of {len(all_blocks(selected))} blocks differ from the tool")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
