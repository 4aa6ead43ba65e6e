"""Snapshot every command's JSON output on the shipped specs, or compare two snapshots.

Used to show that a refactoring leaves behaviour unchanged: run it before and after, then
compare the two folders byte for byte.

    python scripts/output_snapshot.py write /tmp/before      # on the old commit
    python scripts/output_snapshot.py write /tmp/after       # on the new one
    python scripts/output_snapshot.py compare /tmp/before /tmp/after
    python scripts/output_snapshot.py compare /tmp/before /tmp/after --stdout   # stdout only
    python scripts/output_snapshot.py write /tmp/after force_   # only the names with force_

Each file holds a command's stdout, its stderr after a ``--- stderr`` line, and, on the last
line, its exit code.  Commands run through the installed ``pumplink`` entry point of the
interpreter running this script, at ``COLUMNS=80`` with ``NO_COLOR`` (the tables too).
"""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
#: A run's duration in its summary line ("in 0.04 s"), masked in the snapshots.
TIMING = re.compile(r"in \d+(?:\.\d+)? ?(?:ms|s|min|h)\b")


def specs() -> list[Path]:
    """Every spec and batch file shipped in configs/ and examples/ (sorted); not the mechanism
    files of configs/mechanisms/ (input of `pumplink structure`, not pump specs)."""
    found = sorted(ROOT.glob("configs/**/*.toml")) + sorted(ROOT.glob("examples/*.toml"))
    return [p for p in found if "mechanisms" not in p.relative_to(ROOT).parts]


def commands() -> dict[str, list[str]]:
    """Snapshot name -> pumplink arguments."""
    out: dict[str, list[str]] = {}
    for path in specs():
        rel = path.relative_to(ROOT)
        stem = str(rel).replace("/", "_").removesuffix(".toml")
        out[f"batch_{stem}"] = ["batch", str(rel), "--format", "json"]
        out[f"batch_csv_{stem}"] = ["batch", str(rel), "--format", "csv"]
        out[f"batch_table_{stem}"] = ["batch", str(rel)]
        if "grids" in rel.parts or path.name.endswith("-family.toml"):
            continue  # batch files: only batch reads them
        out[f"synth_{stem}"] = ["synth", str(rel), "--format", "json"]
        out[f"force_{stem}"] = ["force", str(rel), "--format", "json"]
        out[f"force_summary_{stem}"] = ["force", str(rel), "--summary", "--format", "json"]
        out[f"force_table_{stem}"] = ["force", str(rel)]
        explain = ["--summary", "--explain", "--verify"]
        out[f"force_explain_{stem}"] = ["force", str(rel), *explain, "--format", "json"]
        out[f"force_explain_table_{stem}"] = ["force", str(rel), *explain]
        out[f"speed_{stem}"] = ["speed", str(rel), "--format", "json"]
        out[f"speed_table_{stem}"] = ["speed", str(rel)]
        out[f"optimize_{stem}"] = ["optimize", str(rel), "--format", "json"]
    return out


def write(folder: Path, only: str = "") -> None:
    """Run every command (those whose snapshot name contains ``only``) into ``folder``."""
    folder.mkdir(parents=True, exist_ok=True)
    exe = [sys.executable, "-m", "pumplink"]
    env = {**os.environ, "COLUMNS": "80", "NO_COLOR": "1"}
    for name, args in commands().items():
        if only not in name:
            continue
        proc = subprocess.run(exe + args, cwd=ROOT, capture_output=True, text=True, check=False, env=env)
        stderr = TIMING.sub("in <time>", proc.stderr)  # the run's own duration is not its output
        text = f"{proc.stdout}\n--- stderr\n{stderr}\nexit {proc.returncode}\n"
        (folder / f"{name}.txt").write_text(text, encoding="utf-8")
        print(f"{name}: exit {proc.returncode}", file=sys.stderr)


def _part(path: Path, stdout_only: bool) -> bytes | None:
    if not path.exists():
        return None
    data = path.read_bytes()
    return data.split(b"\n--- stderr\n")[0] if stdout_only else data


def compare(a: Path, b: Path, stdout_only: bool = False) -> int:
    """Byte-compare the snapshots of ``b`` with those of the same name in ``a`` (their stdout
    alone with ``stdout_only``: the JSON, CSV and tables, not the messages beside them)."""
    names = sorted(p.name for p in b.glob("*.txt"))
    bad = [
        n
        for n in names
        if _part(a / n, stdout_only) is None or _part(a / n, stdout_only) != _part(b / n, stdout_only)
    ]
    for n in bad:
        print(f"differs: {n}")
    print(f"{len(names) - len(bad)} of {len(names)} outputs byte-identical")
    return 1 if bad else 0


if __name__ == "__main__":
    if len(sys.argv) in (3, 4) and sys.argv[1] == "write":
        write(Path(sys.argv[2]), *sys.argv[3:])
    elif len(sys.argv) in (4, 5) and sys.argv[1] == "compare":
        sys.exit(compare(Path(sys.argv[2]), Path(sys.argv[3]), "--stdout" in sys.argv[4:]))
    else:
        sys.exit(__doc__)
