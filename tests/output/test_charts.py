"""Charts through the real entry point: written when matplotlib is there, exit 2 when not; what
they show is read from the figure objects (``tests/figures.py``), not from the file's bytes."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import figures
import pytest

ROOT = Path(__file__).resolve().parents[2]


def run(*args, pre=""):
    code = f"{pre}import sys; sys.argv = ['pumplink', *{list(args)!r}]; from pumplink.cli import main; main()"
    return subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, check=False)


def test_force_plot_shows_the_curve_limits_dead_centres_and_the_peak(tmp_path):
    """The force chart of the prototype: its title, the legend, the limit and mean-force lines, a
    dotted line at each dead centre and the peak marked where the JSON puts it, in PNG and SVG."""
    for name in ("f.png", "f.svg"):
        out = figures.run(
            "force",
            "configs/prototype.toml",
            "--summary",
            "--format",
            "json",
            "--plot",
            tmp_path / name,
            cwd=ROOT,
        )
        assert out.returncode == 0, out.stderr
        j = json.loads(out.stdout)
        data = (tmp_path / name).read_bytes()
        assert data.startswith(b"\x89PNG") if name.endswith(".png") else b"<svg" in data[:2000]
        (ax,) = figures.read(tmp_path / name)["axes"]
        band, limit, mean = 20, j["force_limit_N"], j["mean_force_N"]
        assert (
            ax["title"]
            == f"Prototype: operator force (grey: ±{band}° dead bands left to the wheel's inertia)"
        )
        assert ax["legend"] == [
            "quasi-static operator force Fh",
            f"limit ±{limit:g} N",
            f"mean force ±{mean:.1f} N",
            f"peak outside dead bands {j['peak_force_N']:.1f} N",
        ]
        flat = {(ln["y"][0], ln["y"][1]) for ln in ax["lines"] if ln["x"] == [0.0, 1.0]}  # horizontal lines
        assert {(limit, limit), (-limit, -limit), (mean, mean), (-mean, -mean)} <= flat
        vertical = sorted(ln["x"][0] for ln in ax["lines"] if ln["y"] == [0.0, 1.0])
        assert vertical == pytest.approx(sorted(j["dead_centres_deg"].values()), abs=1e-12)
        ((x, y),) = figures.marked(ax, "o")
        assert x == pytest.approx(j["dead_band_peak_crank_deg"], abs=1e-12)
        assert abs(y) == pytest.approx(j["peak_force_N"], rel=1e-12)
        (curve,) = [ln for ln in ax["lines"] if ln["label"] == "quasi-static operator force Fh"]
        assert curve["x"][0] == 0.0 and curve["x"][-1] == 360.0 and len(curve["x"]) > 1000


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
