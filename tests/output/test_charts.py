"""Charts through the real entry point: written when matplotlib is there, exit 2 when not."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def run(*args, pre=""):
    code = f"{pre}import sys; sys.argv = ['pumplink', *{list(args)!r}]; from pumplink.cli import main; main()"
    return subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, check=False)


def test_force_plot_png_and_svg(tmp_path):
    for name in ("f.png", "f.svg"):
        out = run("force", "configs/prototype.toml", "--summary", "--plot", str(tmp_path / name))
        assert out.returncode == 0, out.stderr
        data = (tmp_path / name).read_bytes()
        assert data.startswith(b"\x89PNG") if name.endswith(".png") else b"<svg" in data[:2000]


def test_plot_without_matplotlib_says_how_to_install_and_exits_2(tmp_path):
    out = run(
        "force", "--plot", str(tmp_path / "f.png"), pre="import sys; sys.modules['matplotlib'] = None; "
    )
    assert out.returncode == 2
    assert "pip install 'pumplink[plot]'" in out.stderr
    assert "Traceback" not in out.stderr and out.stdout == ""
    assert not (tmp_path / "f.png").exists()


def test_plot_unknown_extension_exits_2(tmp_path):
    out = run("force", "--plot", str(tmp_path / "f.txt"))
    assert out.returncode == 2 and "--plot" in out.stderr and ".png" in out.stderr
    assert len(out.stderr.strip().splitlines()) == 1
