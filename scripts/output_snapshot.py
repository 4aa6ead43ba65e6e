"""Snapshot every command's JSON output on the shipped specs, or compare two snapshots.

Used to show that a refactoring leaves behaviour unchanged: run it before and after, then
compare the two folders byte for byte.

    python scripts/output_snapshot.py write /tmp/before      # on the old commit
    python scripts/output_snapshot.py write /tmp/after       # on the new one
    python scripts/output_snapshot.py compare /tmp/before /tmp/after

Each file holds a command's stdout and, on the last line, its exit code.  Commands run through
the installed ``pumplink`` entry point of the interpreter running this script.
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


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
        if "grids" in rel.parts or path.name.endswith("-family.toml"):
            continue  # batch files: only batch reads them
        out[f"synth_{stem}"] = ["synth", str(rel), "--format", "json"]
        out[f"force_{stem}"] = ["force", str(rel), "--format", "json"]
        out[f"force_summary_{stem}"] = ["force", str(rel), "--summary", "--format", "json"]
        out[f"optimize_{stem}"] = ["optimize", str(rel), "--format", "json"]
    return out


def write(folder: Path) -> None:
    folder.mkdir(parents=True, exist_ok=True)
    exe = [sys.executable, "-m", "pumplink"]
    for name, args in commands().items():
        proc = subprocess.run(exe + args, cwd=ROOT, capture_output=True, text=True, check=False)
        (folder / f"{name}.txt").write_text(f"{proc.stdout}\nexit {proc.returncode}\n", encoding="utf-8")
        print(f"{name}: exit {proc.returncode}", file=sys.stderr)


def compare(a: Path, b: Path) -> int:
    names = sorted({p.name for p in a.glob("*.txt")} | {p.name for p in b.glob("*.txt")})
    bad = [
        n
        for n in names
        if not (a / n).exists() or not (b / n).exists() or (a / n).read_bytes() != (b / n).read_bytes()
    ]
    for n in bad:
        print(f"differs: {n}")
    print(f"{len(names) - len(bad)} of {len(names)} outputs byte-identical")
    return 1 if bad else 0


if __name__ == "__main__":
    if len(sys.argv) == 3 and sys.argv[1] == "write":
        write(Path(sys.argv[2]))
    elif len(sys.argv) == 4 and sys.argv[1] == "compare":
        sys.exit(compare(Path(sys.argv[2]), Path(sys.argv[3])))
    else:
        sys.exit(__doc__)
